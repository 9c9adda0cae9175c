//! Unit tests of element removal on the test regions of issue 66: convex, non-convex, two
//! holes, a thin strip, a graded size; every mesh checked by [`check_cover`], sizes and
//! angles measured, determinism, refusals.

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

/// Divides the boundary by the size, meshes, asserts the cover and the tags, measures.
fn accept(domain: &Domain, size: &dyn Fn(DVec2) -> f64, options: &Options) -> (Output, Quality2d) {
    let split = split_boundary(domain, size).unwrap();
    let out = mesh(&split.domain, size, options).unwrap();
    assert_eq!(check_cover(&out.mesh, &split.domain), Ok(()));
    assert!(out.mesh.triangle_tags.iter().all(|&t| t == options.region));
    let q = measure(&out.mesh, size);
    eprintln!("{} triangles, angles {:.1}..{:.1}, under 20/30: {:?}, size ratio {:?}, {:?}", q.triangles, q.angle_range[0], q.angle_range[1], q.triangles_under, q.size_ratio, out.stats);
    (out, q)
}

fn sized(q: &Quality2d) {
    assert!(q.size_ratio[1] > 0.8 && q.size_ratio[1] < 1.2, "median size ratio {:?}", q.size_ratio);
}

fn rectangle(w: f64, h: f64) -> Vec<DVec2> {
    vec![d(0.0, 0.0), d(w, 0.0), d(w, h), d(0.0, h)]
}

#[test]
fn a_twelve_gon() {
    let dom = Domain::from_loops(&[polygon(DVec2::ZERO, 1.0, 12, 0.0)], None).unwrap();
    let (out, q) = accept(&dom, &|_| 0.15, &Options::default());
    sized(&q);
    assert!(q.angle_range[0] > 20.0, "{q:?}");
    assert!(out.stats.ears > 0 && out.stats.pairs > 0);
}

#[test]
fn a_rectangle() {
    let dom = Domain::from_loops(&[rectangle(3.0, 2.0)], None).unwrap();
    let (_, q) = accept(&dom, &|_| 0.2, &Options::default());
    sized(&q);
    assert!(q.angle_range[0] > 20.0, "{q:?}");
}

#[test]
fn an_l_shape() {
    let l = vec![d(0.0, 0.0), d(2.0, 0.0), d(2.0, 1.0), d(1.0, 1.0), d(1.0, 2.0), d(0.0, 2.0)];
    let dom = Domain::from_loops(&[l], None).unwrap();
    let (_, q) = accept(&dom, &|_| 0.1, &Options::default());
    sized(&q);
    assert!(q.angle_range[0] > 20.0, "{q:?}");
}

#[test]
fn a_comb_and_a_star() {
    let mut comb = vec![d(0.0, 0.0), d(5.0, 0.0), d(5.0, 2.0)];
    for k in (0..5).rev() {
        let x = k as f64;
        comb.extend([d(x + 0.7, 2.0), d(x + 0.7, 0.6), d(x + 0.3, 0.6), d(x + 0.3, 2.0)]);
    }
    comb.push(d(0.0, 2.0));
    let dom = Domain::from_loops(&[comb], None).unwrap();
    let (_, q) = accept(&dom, &|_| 0.1, &Options::default());
    sized(&q);
    let star: Vec<DVec2> = (0..10).map(|k| DVec2::from_angle(TAU * k as f64 / 10.0) * if k % 2 == 0 { 1.0 } else { 0.4 }).collect();
    let dom = Domain::from_loops(&[star], None).unwrap();
    let (_, q) = accept(&dom, &|_| 0.08, &Options::default());
    sized(&q);
}

#[test]
fn two_holes() {
    let outer = rectangle(4.0, 2.0);
    let circle = polygon(d(1.0, 1.0), 0.5, 24, 0.0);
    let square = vec![d(2.6, 0.6), d(3.4, 0.6), d(3.4, 1.4), d(2.6, 1.4)];
    let dom = Domain::from_loops(&[outer, circle, square], None).unwrap();
    let (_, q) = accept(&dom, &|_| 0.12, &Options::default());
    sized(&q);
    assert!(q.angle_range[0] > 15.0, "{q:?}");
}

#[test]
fn a_thin_strip() {
    let dom = Domain::from_loops(&[rectangle(10.0, 0.3)], None).unwrap();
    let (_, q) = accept(&dom, &|_| 0.25, &Options::default());
    assert!(q.angle_range[0] > 15.0, "{q:?}");
    // thinner than the size: one layer of triangles
    let dom = Domain::from_loops(&[rectangle(10.0, 0.05)], None).unwrap();
    accept(&dom, &|_| 0.25, &Options::default());
}

#[test]
fn a_graded_size() {
    let dom = Domain::from_loops(&[rectangle(4.0, 3.0)], None).unwrap();
    let c = d(0.0, 0.0);
    let h = |p: DVec2| 0.05 * (1.0 + 2.0 * (p - c).length() / 5.0);
    let (_, q) = accept(&dom, &h, &Options::default());
    sized(&q);
    assert!(q.angle_range[0] > 15.0, "{q:?}");
}

#[test]
fn boundary_points_kept_without_division() {
    // a CAD-like face: many short boundary pieces, a hole near the outer loop, a small angle
    let mut outer = vec![d(0.0, 0.0)];
    outer.extend((1..=40).map(|k| d(0.1 * k as f64, 0.0)));
    outer.extend([d(4.0, 1.0), d(0.0, 0.3)]);
    let hole = polygon(d(3.5, 0.35), 0.2, 16, 0.1);
    let dom = Domain::from_loops(&[outer, hole], None).unwrap();
    let out = mesh(&dom, &|_| 0.15, &Options::default()).unwrap();
    assert_eq!(check_cover(&out.mesh, &dom), Ok(()));
}

#[test]
fn deterministic() {
    let dom = Domain::from_loops(&[rectangle(4.0, 2.0), polygon(d(1.0, 1.0), 0.5, 24, 0.0)], None).unwrap();
    let h = |p: DVec2| 0.1 + 0.05 * p.x;
    let split = split_boundary(&dom, &h).unwrap();
    let a = mesh(&split.domain, &h, &Options::default()).unwrap();
    let b = mesh(&split.domain, &h, &Options::default()).unwrap();
    assert_eq!(a.mesh, b.mesh);
    assert_eq!(a.stats, b.stats);
}

#[test]
fn no_smoothing_is_valid_too() {
    let dom = Domain::from_loops(&[polygon(DVec2::ZERO, 1.0, 12, 0.0)], None).unwrap();
    let (out, _) = accept(&dom, &|_| 0.2, &Options::default().with_smooth_passes(0));
    assert_eq!(out.stats.moves, 0);
}

#[test]
fn refusals_are_named() {
    let dom = Domain::from_loops(&[rectangle(1.0, 1.0)], None).unwrap();
    assert!(matches!(mesh(&dom, &|_| -1.0, &Options::default()), Err(Error::Size(_))));
    assert!(matches!(mesh(&dom, &|_| 0.1, &Options::default().with_angles(0.0, 180.0)), Err(Error::Option { name: "ear_angle", .. })));
    let bad = Domain { points: vec![d(0.0, 0.0), d(1.0, 0.0)], segments: vec![[0, 1], [1, 0]], tags: vec![0, 0] };
    assert!(matches!(mesh(&bad, &|_| 0.1, &Options::default()), Err(Error::Domain(_))));
}

/// A small deterministic generator for the random regions.
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

#[test]
fn random_star_regions_with_holes() {
    let mut r = Lcg(7);
    let mut meshed = 0;
    for t in 0..24 {
        let n = 5 + (r.next() * 40.0) as usize;
        let outer: Vec<DVec2> = (0..n).map(|k| (0.5 + r.next()) * DVec2::from_angle(TAU * k as f64 / n as f64)).collect();
        let mut loops = vec![outer];
        if t % 2 == 0 {
            let m = 3 + (r.next() * 10.0) as usize;
            loops.push((0..m).map(|k| 0.2 * DVec2::from_angle(TAU * k as f64 / m as f64 + r.next())).collect());
        }
        let Ok(dom) = Domain::from_loops(&loops, None) else { continue };
        let h = 0.03 + 0.1 * r.next();
        // every third region keeps its coarse boundary (points final, not divided)
        let dom = if t % 3 == 0 { dom } else { split_boundary(&dom, &|_| h).unwrap().domain };
        let out = mesh(&dom, &|_| h, &Options::default()).unwrap();
        assert_eq!(check_cover(&out.mesh, &dom), Ok(()), "region {t}");
        meshed += 1;
    }
    assert!(meshed >= 20, "{meshed}");
}

#[test]
fn a_hole_near_the_outer_loop_and_a_pinch() {
    let hole = polygon(d(2.0, 0.52), 0.5, 20, 0.0);
    let dom = Domain::from_loops(&[rectangle(4.0, 3.0), hole], None).unwrap();
    let (_, q) = accept(&dom, &|_| 0.1, &Options::default());
    sized(&q);
    // a hole touching the outer loop at point 0 (two segments in and two out there)
    let pts = vec![d(0.0, 0.0), d(4.0, 0.0), d(4.0, 4.0), d(0.0, 4.0), d(2.0, 1.0), d(1.0, 2.0)];
    let segs = vec![[0, 1], [1, 2], [2, 3], [3, 0], [0, 5], [5, 4], [4, 0]];
    let pinch = Domain::new(pts, segs, vec![1; 7]).unwrap();
    let (_, q) = accept(&pinch, &|_| 0.2, &Options::default());
    sized(&q);
}
