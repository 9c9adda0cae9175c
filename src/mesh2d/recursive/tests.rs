//! Unit tests of recursive subdivision: every test region covered, sizes near the field,
//! cuts and nodes counted, errors, determinism.

use super::*;
use crate::mesh2d::ear::testkit::{check_cover, prepared, regions};
use crate::mesh2d::measure::measure;

fn d(x: f64, y: f64) -> DVec2 {
    DVec2::new(x, y)
}

#[test]
fn every_region_is_covered_at_the_size() {
    for r in regions() {
        let dom = prepared(&r);
        let out = mesh(&dom, &r.size, &Options::default()).unwrap_or_else(|e| panic!("{}: {e}", r.name));
        check_cover(&dom, &out.mesh, Options::default().region);
        let q = measure(&out.mesh, &r.size);
        eprintln!("recursive {:10} tris {:5} angles {:5.1}..{:5.1} size ratio {:.2}/{:.2}/{:.2} under 30: {} {:?}", r.name, q.triangles, q.angle_range[0], q.angle_range[1], q.size_ratio[0], q.size_ratio[1], q.size_ratio[2], q.triangles_under[1], out.stats);
        assert!(q.size_ratio[1] > 0.8 && q.size_ratio[1] < 1.2, "{}: median size ratio {:?}", r.name, q.size_ratio);
        assert!(out.stats.cuts > 0 && out.stats.points_on_cuts > 0, "{}: {:?}", r.name, out.stats);
    }
}

#[test]
fn a_convex_region_needs_no_reflex_cut_and_a_hole_one_bridge() {
    let r = &regions()[0];
    let out = mesh(&prepared(r), &r.size, &Options::default()).unwrap();
    assert_eq!(out.stats.reflex_cuts, 0);
    assert!(out.stats.depth >= 4, "{:?}", out.stats);
    let outer = vec![d(0.0, 0.0), d(2.0, 0.0), d(2.0, 2.0), d(0.0, 2.0)];
    let hole = vec![d(0.8, 0.8), d(1.2, 0.8), d(1.2, 1.2), d(0.8, 1.2)];
    let size = |_: DVec2| 0.2;
    let dom = crate::mesh2d::boundary::split_boundary(&Domain::from_loops(&[outer, hole], None).unwrap(), &size).unwrap().domain;
    let out = mesh(&dom, &size, &Options::default()).unwrap();
    check_cover(&dom, &out.mesh, RegionId(1));
    assert!(out.stats.reflex_cuts >= 1);
}

#[test]
fn a_quad_is_cut_by_its_better_diagonal() {
    let dom = Domain::from_loops(&[vec![d(0.0, 0.0), d(1.0, 0.0), d(1.1, 0.5), d(0.0, 0.6)]], None).unwrap();
    let out = mesh(&dom, &|_| 2.0, &Options::default()).unwrap();
    check_cover(&dom, &out.mesh, RegionId(1));
    assert_eq!(out.mesh.triangles.len(), 2);
    assert_eq!(out.stats.points_on_cuts, 0);
}

#[test]
fn bad_inputs_are_named() {
    let r = &regions()[3];
    let dom = prepared(r);
    assert!(matches!(mesh(&dom, &|p| if p.x > 2.0 { -1.0 } else { 0.3 }, &Options::default()), Err(Error::Size(_))));
    let pts = vec![d(0.0, 0.0), d(1.0, 0.0), d(1.0, 1.0), d(0.0, 1.0), d(2.0, 1.0), d(2.0, 2.0), d(1.0, 2.0)];
    let segs = vec![[0, 1], [1, 2], [2, 3], [3, 0], [2, 4], [4, 5], [5, 6], [6, 2]];
    let dom = Domain::new(pts, segs, vec![1; 8]).unwrap();
    assert_eq!(mesh(&dom, &|_| 0.5, &Options::default()).unwrap_err(), Error::Loops(LoopError::TouchingLoops(2)));
}

#[test]
fn the_same_input_gives_the_same_mesh() {
    let r = &regions()[5];
    let dom = prepared(r);
    assert_eq!(mesh(&dom, &r.size, &Options::default()).unwrap(), mesh(&dom, &r.size, &Options::default()).unwrap());
}

#[test]
fn a_tiny_angle_and_a_hole_near_the_boundary() {
    let r = crate::mesh2d::ear::testkit::hard();
    let dom = prepared(&r);
    let out = mesh(&dom, &r.size, &Options::default()).unwrap();
    check_cover(&dom, &out.mesh, RegionId(1));
    let q = measure(&out.mesh, &r.size);
    eprintln!("recursive hard tris {} angles {:.1}..{:.1} size ratio {:?} {:?}", q.triangles, q.angle_range[0], q.angle_range[1], q.size_ratio, out.stats);
    assert!(q.size_ratio[1] > 0.8 && q.size_ratio[1] < 1.2, "{:?}", q.size_ratio);
}
