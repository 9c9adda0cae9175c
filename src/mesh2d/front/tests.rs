//! Unit tests of the advancing front: the test regions of issue 66 (convex, non-convex, two
//! holes, a thin strip, a graded size), CAD-like boundaries, determinism, errors.

use super::*;
use crate::mesh2d::boundary::split_boundary;
use crate::mesh2d::measure::{measure, Quality2d};
use std::f64::consts::TAU;

fn d(x: f64, y: f64) -> DVec2 {
    DVec2::new(x, y)
}

fn polygon(c: DVec2, r: f64, n: usize, phase: f64) -> Vec<DVec2> {
    (0..n).map(|k| c + r * DVec2::from_angle(phase + TAU * k as f64 / n as f64)).collect()
}

/// Divides the boundary by the size, meshes, and checks the contract: valid, the domain's
/// points and segments kept, the area exact, every element tagged. Returns the quality.
fn accept(domain: &Domain, size: &dyn Fn(DVec2) -> f64, options: &Options, name: &str) -> (Output, Quality2d, Domain) {
    let split = split_boundary(domain, size).unwrap().domain;
    let out = mesh(&split, size, options).unwrap_or_else(|e| panic!("{name}: {e}"));
    check_coverage(&split, &out.mesh).unwrap();
    assert!(out.mesh.triangle_tags.iter().all(|&t| t == options.region));
    let q = measure(&out.mesh, size);
    eprintln!("{name}: {} triangles, angles {:.1}..{:.1} (front's worst {:.1}), size ratio {:.2?}, input angle {:.1}, {:?}", q.triangles, q.angle_range[0], q.angle_range[1], out.improve.worst_angle_before, q.size_ratio, split.smallest_angle_deg(), out.front);
    assert!((q.angle_range[0] - out.improve.worst_angle_after).abs() < 1e-9);
    let worst = out.mesh.triangles.iter().min_by(|s, t| {
        let a = |t: &[u32; 3]| improve::min_angle(out.mesh.vertices[t[0] as usize], out.mesh.vertices[t[1] as usize], out.mesh.vertices[t[2] as usize]);
        a(s).total_cmp(&a(t))
    });
    if let Some(t) = worst {
        let fixed = t.iter().filter(|&&i| (i as usize) < split.points.len()).count();
        eprintln!("{name}: the worst triangle has {fixed} boundary vertices");
    }
    (out, q, split)
}

/// The acceptance of issue 66 on a region without input angles under 50°.
fn assert_quality(q: &Quality2d, name: &str) {
    assert!(q.angle_range[0] >= 25.0, "{name}: smallest angle {:.2}", q.angle_range[0]);
    assert!(q.size_ratio[1] >= 0.8 && q.size_ratio[1] <= 1.2, "{name}: median size ratio {:.3}", q.size_ratio[1]);
}

fn dodecagon() -> Domain {
    Domain::from_loops(&[polygon(DVec2::ZERO, 1.0, 12, 0.0)], None).unwrap()
}

fn l_shape() -> Domain {
    Domain::from_loops(&[vec![d(0.0, 0.0), d(2.0, 0.0), d(2.0, 1.0), d(1.0, 1.0), d(1.0, 2.0), d(0.0, 2.0)]], None).unwrap()
}

fn comb() -> Domain {
    let mut pts = vec![d(0.0, 0.0), d(4.0, 0.0), d(4.0, 2.0)];
    for k in (0..4).rev() {
        let x = k as f64;
        pts.extend([d(x + 0.6, 2.0), d(x + 0.6, 0.8), d(x + 0.4, 0.8), d(x + 0.4, 2.0)]);
        if k == 0 {
            pts.push(d(0.0, 2.0));
        } else {
            pts.push(d(x, 2.0));
        }
    }
    pts.dedup();
    Domain::from_loops(&[pts], None).unwrap()
}

fn two_holes() -> Domain {
    let outer = vec![d(0.0, 0.0), d(4.0, 0.0), d(4.0, 3.0), d(0.0, 3.0)];
    let circle = polygon(d(1.2, 1.5), 0.6, 24, 0.1);
    let square = vec![d(2.6, 1.0), d(3.4, 1.0), d(3.4, 2.0), d(2.6, 2.0)];
    Domain::from_loops(&[outer, circle, square], None).unwrap()
}

fn strip() -> Domain {
    Domain::from_loops(&[vec![d(0.0, 0.0), d(5.0, 0.0), d(5.0, 0.25), d(0.0, 0.25)]], None).unwrap()
}

#[test]
fn convex_dodecagon() {
    let (_, q, _) = accept(&dodecagon(), &|_| 0.1, &Options::default(), "12-gon");
    assert!(q.triangles > 500);
    assert_quality(&q, "12-gon");
}

#[test]
fn convex_rectangle() {
    let r = Domain::from_loops(&[vec![d(0.0, 0.0), d(3.0, 0.0), d(3.0, 1.0), d(0.0, 1.0)]], None).unwrap();
    let (_, q, _) = accept(&r, &|_| 0.1, &Options::default(), "rectangle");
    assert_quality(&q, "rectangle");
}

#[test]
fn non_convex_l_and_comb() {
    let (_, q, _) = accept(&l_shape(), &|_| 0.1, &Options::default(), "L");
    assert_quality(&q, "L");
    let (_, q, _) = accept(&comb(), &|_| 0.1, &Options::default(), "comb");
    assert_quality(&q, "comb");
}

#[test]
fn a_star_with_sharp_tips() {
    let pts: Vec<DVec2> = (0..16).map(|k| DVec2::from_angle(TAU * k as f64 / 16.0) * if k % 2 == 0 { 1.0 } else { 0.55 }).collect();
    let dom = Domain::from_loops(&[pts], None).unwrap();
    let (_, q, split) = accept(&dom, &|_| 0.08, &Options::default(), "star");
    let input = split.smallest_angle_deg();
    assert!(input > 50.0 || q.angle_range[0] >= (0.5 * input).min(25.0), "star: smallest {:.1} at input {input:.1}", q.angle_range[0]);
}

#[test]
fn two_holes_region() {
    let (_, q, _) = accept(&two_holes(), &|_| 0.12, &Options::default(), "two holes");
    assert_quality(&q, "two holes");
}

#[test]
fn thin_strip() {
    let (_, q, _) = accept(&strip(), &|_| 0.1, &Options::default(), "strip");
    assert_quality(&q, "strip");
}

#[test]
fn graded_size() {
    let c = d(0.0, 0.0);
    let h = move |p: DVec2| 0.03 * (1.0 + 2.0 * (p - c).length() / 2.0);
    let (_, q, _) = accept(&l_shape(), &h, &Options::default(), "graded L");
    assert_quality(&q, "graded L");
    let h = move |p: DVec2| 0.05 * (1.0 + 2.0 * (p - d(2.0, 1.5)).length() / 4.0);
    let (_, q, _) = accept(&two_holes(), &h, &Options::default(), "graded holes");
    assert_quality(&q, "graded holes");
}

#[test]
fn improvement_helps() {
    let raw = Options::default().with_smooth_passes(0).with_flips(false);
    let (a, qa, _) = accept(&two_holes(), &|_| 0.12, &raw, "two holes, raw front");
    assert_eq!((a.improve.flips, a.improve.smoothing_moves), (0, 0));
    let (b, qb, _) = accept(&two_holes(), &|_| 0.12, &Options::default(), "two holes");
    assert!(b.improve.flips + b.improve.smoothing_moves > 0);
    assert!(qb.angle_range[0] >= qa.angle_range[0], "{} < {}", qb.angle_range[0], qa.angle_range[0]);
}

/// CAD-like: boundary points not divided by the size (many short pieces beside long ones),
/// a 10° corner, a hole close to the outer loop.
#[test]
fn cad_like_boundaries() {
    // a fine arc of 80 pieces beside coarse straight sides, a hole close to the outer loop
    let mut outer = vec![d(0.0, 0.0), d(3.0, 0.0)];
    outer.extend((0..=80).map(|k| d(3.0, 1.0) + DVec2::from_angle(-0.5 * TAU / 2.0 + 0.5 * TAU * k as f64 / 80.0)));
    outer.push(d(0.0, 2.0));
    outer.dedup();
    let hole = vec![d(0.3, 0.05), d(0.3, 0.5), d(1.0, 0.5), d(1.0, 0.05)];
    let dom = Domain::from_loops(&[outer, hole], None).unwrap();
    let size = |_: DVec2| 0.15;
    let out = mesh(&dom, &size, &Options::default()).unwrap();
    check_coverage(&dom, &out.mesh).unwrap();
    let q = measure(&out.mesh, &size);
    eprintln!("cad-like: {} triangles, angles {:.1}..{:.1}, input {:.1}, {:?}", q.triangles, q.angle_range[0], q.angle_range[1], dom.smallest_angle_deg(), out.front);
    // a 10° corner, boundary divided
    let t = 10f64.to_radians();
    let wedge = Domain::from_loops(&[vec![d(0.0, 0.0), d(3.0, 0.0), d(3.0, 3.0 * t.tan())]], None).unwrap();
    let (_, q, _) = accept(&wedge, &|_| 0.1, &Options::default(), "10° wedge");
    assert!(q.angle_range[0] >= 5.0, "{}", q.angle_range[0]);
}

#[test]
fn deterministic() {
    let h = |p: DVec2| 0.05 + 0.05 * p.x;
    let split = split_boundary(&two_holes(), &h).unwrap().domain;
    let a = mesh(&split, &h, &Options::default()).unwrap();
    let b = mesh(&split, &h, &Options::default()).unwrap();
    assert_eq!(a, b);
}

#[test]
fn errors_name_the_cause() {
    let mut dom = dodecagon();
    dom.points.push(d(0.0, 0.0));
    assert!(matches!(mesh(&dom, &|_| 0.1, &Options::default()), Err(Error::IsolatedPoint { point: 12, .. })));
    assert!(matches!(mesh(&dodecagon(), &|_| -1.0, &Options::default()), Err(Error::Size(_))));
    let mut bad = dodecagon();
    bad.segments.swap(0, 1);
    bad.segments[0].reverse();
    assert!(matches!(mesh(&bad, &|_| 0.1, &Options::default()), Err(Error::Domain(_))));
}

/// About 100k triangles on the two-hole region; run with `--ignored --nocapture` to time it.
#[test]
#[ignore]
fn speed_100k() {
    let h = |_: DVec2| 0.0128;
    let split = split_boundary(&two_holes(), &h).unwrap().domain;
    let t = std::time::Instant::now();
    let out = mesh(&split, &h, &Options::default()).unwrap();
    let dt = t.elapsed();
    let q = measure(&out.mesh, &h);
    eprintln!("speed: {} triangles in {:.3} s, angles {:.1}..{:.1}, size ratio {:.2?}, {:?}, {:?}", q.triangles, dt.as_secs_f64(), q.angle_range[0], q.angle_range[1], q.size_ratio, out.front, out.improve);
    check_coverage(&split, &out.mesh).unwrap();
}
