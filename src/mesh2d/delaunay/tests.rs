//! Unit tests of the Delaunay refinement: the test regions of the issue, angles at 30° and
//! 33°, the boundary kept, area, small input angles, protected segments, the size field,
//! determinism, errors; and an ignored speed run beside Triangle.

use super::*;
use crate::mesh2d::measure::measure;
use glam::DVec2;
use std::f64::consts::TAU;

fn d(x: f64, y: f64) -> DVec2 {
    DVec2::new(x, y)
}

/// Asserts the contract: valid, the domain's area, domain points kept with their index,
/// every segment a union of edges (one edge when segments are protected), triangles inside,
/// tags; returns the output.
fn accept(domain: &Domain, size: &dyn Fn(DVec2) -> f64, options: &Options) -> Output {
    let out = mesh(domain, size, options).unwrap();
    let m = &out.mesh;
    assert_eq!(m.validate(), Ok(()));
    let rel = (m.area() - domain.area()).abs() / domain.area();
    assert!(rel < 1e-9, "area {} vs {} ({rel:e})", m.area(), domain.area());
    assert_eq!(&m.vertices[..domain.points.len()], &domain.points[..]);
    assert!(m.triangle_tags.iter().all(|&t| t == options.region));
    let mut edges: Vec<(u32, u32)> = m.triangles.iter().flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])]).collect();
    edges.sort_unstable();
    assert_eq!(out.boundary.len(), domain.segments.len());
    for (s, chain) in out.boundary.iter().enumerate() {
        let [a, b] = domain.segments[s];
        assert_eq!((chain[0], chain[chain.len() - 1]), (a, b));
        if !options.split_segments {
            assert_eq!(chain.len(), 2, "segment {s} split");
        }
        let (pa, pb) = domain.ends(s);
        for w in chain.windows(2) {
            assert!(edges.binary_search(&(w[0], w[1])).is_ok(), "segment {s}: {w:?} is no edge");
            let q = m.vertices[w[1] as usize];
            let off = (pb - pa).perp_dot(q - pa).abs() / (pb - pa).length();
            assert!(off <= 1e-12 * (pb - pa).length(), "segment {s}: vertex {} off the line by {off:e}", w[1]);
        }
    }
    for t in &m.triangles {
        let g = t.iter().map(|&i| m.vertices[i as usize]).sum::<DVec2>() / 3.0;
        assert!(domain.contains(g), "triangle {t:?} outside");
    }
    out
}

fn ngon(c: DVec2, r: f64, n: usize, phase: f64) -> Vec<DVec2> {
    (0..n).map(|k| c + r * DVec2::from_angle(phase + TAU * k as f64 / n as f64)).collect()
}

fn dodecagon() -> Domain {
    Domain::from_loops(&[ngon(d(0.0, 0.0), 1.0, 12, 0.1)], None).unwrap()
}

fn rectangle() -> Domain {
    Domain::from_loops(&[vec![d(0.0, 0.0), d(3.0, 0.0), d(3.0, 2.0), d(0.0, 2.0)]], None).unwrap()
}

fn l_shape() -> Domain {
    Domain::from_loops(&[vec![d(0.0, 0.0), d(2.0, 0.0), d(2.0, 1.0), d(1.0, 1.0), d(1.0, 2.0), d(0.0, 2.0)]], None).unwrap()
}

/// A comb: a spine with four teeth (every input angle 90° or 270°).
fn comb() -> Domain {
    let mut pts = vec![d(0.0, 0.0), d(4.4, 0.0), d(4.4, 0.6)];
    for k in (0..4).rev() {
        let x = 0.2 + 1.1 * k as f64;
        pts.extend([d(x + 0.8, 0.6), d(x + 0.8, 2.0), d(x, 2.0), d(x, 0.6)]);
    }
    pts.push(d(0.0, 0.6));
    Domain::from_loops(&[pts], None).unwrap()
}

/// A rectangle with a 24-gon hole and a square hole.
fn two_holes() -> Domain {
    let outer = vec![d(0.0, 0.0), d(4.0, 0.0), d(4.0, 2.0), d(0.0, 2.0)];
    let circle = ngon(d(1.0, 1.0), 0.5, 24, 0.0);
    let square = vec![d(2.6, 0.6), d(3.4, 0.6), d(3.4, 1.4), d(2.6, 1.4)];
    Domain::from_loops(&[outer, circle, square], None).unwrap()
}

fn strip() -> Domain {
    Domain::from_loops(&[vec![d(0.0, 0.0), d(5.0, 0.0), d(5.0, 0.1), d(0.0, 0.1)]], None).unwrap()
}

/// A triangle-like region with a 10° corner.
fn ten_degrees() -> Domain {
    let t = 10f64.to_radians();
    Domain::from_loops(&[vec![d(0.0, 0.0), d(3.0, 0.0), d(3.0, 3.0 * t.tan())]], None).unwrap()
}

fn regions() -> Vec<(&'static str, Domain, f64)> {
    vec![("12-gon", dodecagon(), 0.15), ("rectangle", rectangle(), 0.2), ("L", l_shape(), 0.15), ("comb", comb(), 0.15), ("two holes", two_holes(), 0.15), ("strip", strip(), 0.1)]
}

#[test]
fn every_angle_meets_30_and_33_degrees_on_the_test_regions() {
    for theta in [30.0, 33.0] {
        for (name, dom, h) in regions() {
            let o = Options { min_angle: theta, ..Options::default() };
            let out = accept(&dom, &|_| h, &o);
            let q = measure(&out.mesh, &|_| h);
            assert!(out.stats.small_input_angles.is_empty(), "{name}: {:?}", out.stats.small_input_angles);
            assert!(q.angle_range[0] >= theta - 1e-9, "{name} at {theta}: smallest angle {} ({:?})", q.angle_range[0], out.stats);
            assert_eq!(out.stats.below, Below::default(), "{name}");
            assert!((out.stats.smallest_angle - q.angle_range[0]).abs() < 1e-9);
            assert!(q.triangles > 50, "{name}: {} triangles", q.triangles);
        }
    }
}

#[test]
fn the_size_is_met_near_one() {
    for (name, dom, h) in regions() {
        let out = accept(&dom, &|_| h, &Options::default());
        let q = measure(&out.mesh, &|_| h);
        assert!((0.8..=1.2).contains(&q.size_ratio[1]), "{name}: size ratios {:?}", q.size_ratio);
    }
}

#[test]
fn a_graded_size_field_is_followed() {
    let dom = two_holes();
    let c = d(2.0, 1.0);
    let (h0, l) = (0.05, 4.0);
    let h = move |p: DVec2| h0 * (1.0 + 2.0 * (p - c).length() / l);
    let out = accept(&dom, &h, &Options::default());
    let q = measure(&out.mesh, &h);
    assert!((0.8..=1.2).contains(&q.size_ratio[1]), "size ratios {:?}", q.size_ratio);
    assert!(q.angle_range[0] >= 30.0 - 1e-9, "{:?}", q.angle_range);
}

#[test]
fn a_ten_degree_corner_terminates_and_is_named() {
    let dom = ten_degrees();
    for split in [true, false] {
        let o = Options { split_segments: split, ..Options::default() };
        let out = accept(&dom, &|_| 0.2, &o);
        let s = &out.stats;
        assert_eq!(s.small_input_angles.len(), 1, "{s:?}");
        assert_eq!(s.small_input_angles[0].vertex, 0);
        assert!((s.small_input_angles[0].degrees - 10.0).abs() < 1e-9);
        if split {
            assert!(s.smallest_angle_away >= 30.0 - 1e-9, "{s:?}");
            assert_eq!(s.below.other, 0, "{s:?}");
            assert_eq!(s.below.protected_boundary, 0, "{s:?}");
        }
    }
}

#[test]
fn protected_segments_keep_every_boundary_point() {
    for (name, dom, h) in regions() {
        let o = Options { split_segments: false, ..Options::default() };
        // the boundary divided by the size first, as the lead does for CAD faces
        let dom = crate::mesh2d::boundary::split_boundary(&dom, &|_| h).unwrap().domain;
        let out = accept(&dom, &|_| h, &o);
        let s = &out.stats;
        assert_eq!(s.steiner_on_segments, 0, "{name}");
        assert_eq!(s.below.other, 0, "{name}: {s:?}");
        let q = measure(&out.mesh, &|_| h);
        let under = out.mesh.triangles.iter().filter(|t| report::smallest_angle(t.map(|i| out.mesh.vertices[i as usize])) < 30.0).count();
        assert_eq!(under, s.below.at_small_input_angle + s.below.protected_boundary, "{name}");
        assert!(q.angle_range[0] > 0.0);
    }
}

#[test]
fn max_area_alone_bounds_areas() {
    let dom = two_holes();
    let o = Options { max_area: Some(0.01), use_size: false, ..Options::default() };
    let out = accept(&dom, &|_| f64::NAN, &o);
    for t in &out.mesh.triangles {
        let p = t.map(|i| out.mesh.vertices[i as usize]);
        assert!(0.5 * (p[1] - p[0]).perp_dot(p[2] - p[0]) <= 0.01);
    }
    assert!(out.mesh.triangles.len() > 500);
}

#[test]
fn two_runs_are_equal() {
    let dom = two_holes();
    let h = |p: DVec2| 0.05 + 0.1 * p.x;
    let a = mesh(&dom, &h, &Options::default()).unwrap();
    let b = mesh(&dom, &h, &Options::default()).unwrap();
    assert_eq!(a, b);
}

#[test]
fn bad_options_and_sizes_are_refused() {
    let dom = rectangle();
    assert!(matches!(mesh(&dom, &|_| 0.1, &Options { min_angle: 36.0, ..Options::default() }), Err(Error::MinAngle(_))));
    assert!(matches!(mesh(&dom, &|_| 0.1, &Options { max_area: Some(0.0), ..Options::default() }), Err(Error::MaxArea(_))));
    assert!(matches!(mesh(&dom, &|_| -1.0, &Options::default()), Err(Error::Size { .. })));
    assert!(matches!(mesh(&dom, &|_| 1e-4, &Options { max_vertices: 1000, ..Options::default() }), Err(Error::TooManyVertices(1000))));
    let bad = Domain { points: vec![d(0.0, 0.0), d(1.0, 0.0)], segments: vec![[0, 1]], tags: vec![1] };
    assert!(matches!(mesh(&bad, &|_| 0.1, &Options::default()), Err(Error::Domain(_))));
}

/// The speed run beside Triangle (see `docs/benchmarks.md`): a 4 × 2 rectangle with the two
/// holes of [`two_holes`] at `max_area` giving about a million triangles, 33°.
/// `cargo test --release --lib mesh2d::delaunay::tests::million -- --ignored --nocapture`
#[test]
#[ignore]
fn million() {
    let dom = two_holes();
    let area = std::env::var("FEPRE_MAX_AREA").ok().and_then(|s| s.parse().ok()).unwrap_or(1.1e-5);
    let o = Options { min_angle: 33.0, max_area: Some(area), use_size: false, ..Options::default() };
    let start = std::time::Instant::now();
    let out = mesh(&dom, &|_| f64::NAN, &o).unwrap();
    let secs = start.elapsed().as_secs_f64();
    let q = measure(&out.mesh, &|_| 1.0);
    println!("fepre delaunay: {secs:.3} s, {} triangles, {} vertices, angles {:?}, stats {:?}", q.triangles, q.vertices, q.angle_range, out.stats.below);
    assert_eq!(out.mesh.validate(), Ok(()));
}
