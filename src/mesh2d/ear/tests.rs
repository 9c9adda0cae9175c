//! Unit tests of ear cutting: every test region covered, sizes near the field, gross
//! elements, bridges, islands, errors, determinism.

use super::testkit::{check_cover, prepared, regions, two_holes};
use super::*;
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
        eprintln!("ear {:10} tris {:5} angles {:5.1}..{:5.1} size ratio {:.2}/{:.2}/{:.2} under 30: {} {:?}", r.name, q.triangles, q.angle_range[0], q.angle_range[1], q.size_ratio[0], q.size_ratio[1], q.size_ratio[2], q.triangles_under[1], out.stats);
        assert!(q.size_ratio[1] > 0.8 && q.size_ratio[1] < 1.2, "{}: median size ratio {:?}", r.name, q.size_ratio);
        assert!(out.stats.ears_cut >= dom.points.len() - 2);
    }
}

#[test]
fn gross_elements_use_only_the_boundary_points() {
    let dom = two_holes();
    let out = mesh(&dom, &|_| 1.0, &Options::default().with_refine(false)).unwrap();
    check_cover(&dom, &out.mesh, RegionId(1));
    assert_eq!(out.mesh.vertices.len(), dom.points.len());
    // n points and two holes: n + 2 triangles
    assert_eq!(out.mesh.triangles.len(), dom.points.len() + 2);
    assert_eq!(out.stats.bridges, 2);
    assert_eq!(out.stats.points_inserted, 0);
}

#[test]
fn an_island_in_a_hole_is_meshed_too() {
    let outer = vec![d(0.0, 0.0), d(3.0, 0.0), d(3.0, 3.0), d(0.0, 3.0)];
    let hole = vec![d(1.0, 1.0), d(2.0, 1.0), d(2.0, 2.0), d(1.0, 2.0)];
    let island = vec![d(1.3, 1.3), d(1.7, 1.3), d(1.7, 1.7), d(1.3, 1.7)];
    let dom = Domain::from_loops(&[outer, hole, island], None).unwrap();
    let size = |_: DVec2| 0.2;
    let dom = crate::mesh2d::boundary::split_boundary(&dom, &size).unwrap().domain;
    let out = mesh(&dom, &size, &Options::default()).unwrap();
    check_cover(&dom, &out.mesh, RegionId(1));
    assert_eq!(out.stats.bridges, 1);
}

#[test]
fn loops_touching_at_a_point_are_refused() {
    // two squares sharing the corner (1, 1)
    let pts = vec![d(0.0, 0.0), d(1.0, 0.0), d(1.0, 1.0), d(0.0, 1.0), d(2.0, 1.0), d(2.0, 2.0), d(1.0, 2.0)];
    let segs = vec![[0, 1], [1, 2], [2, 3], [3, 0], [2, 4], [4, 5], [5, 6], [6, 2]];
    let dom = Domain::new(pts, segs, vec![1; 8]).unwrap();
    let e = mesh(&dom, &|_| 0.5, &Options::default()).unwrap_err();
    assert_eq!(e, Error::Loops(LoopError::TouchingLoops(2)));
    assert!(e.to_string().contains("point 2"));
}

#[test]
fn bad_inputs_are_named() {
    let dom = two_holes();
    assert!(matches!(mesh(&dom, &|p| if p.x > 2.0 { 0.0 } else { 0.3 }, &Options::default()), Err(Error::Size(_))));
    let bad = Domain { points: vec![d(0.0, 0.0), d(1.0, 0.0)], segments: vec![[0, 1], [1, 0]], tags: vec![1, 1] };
    assert!(matches!(mesh(&bad, &|_| 1.0, &Options::default()), Err(Error::Domain(_))));
    let opts = Options { split_ratio: f64::NAN, ..Options::default() };
    assert!(matches!(mesh(&dom, &|_| 1.0, &opts), Err(Error::Option(_))));
}

#[test]
fn the_same_input_gives_the_same_mesh() {
    let r = &regions()[5];
    let dom = prepared(r);
    let a = mesh(&dom, &r.size, &Options::default()).unwrap();
    let b = mesh(&dom, &r.size, &Options::default()).unwrap();
    assert_eq!(a, b);
}

#[test]
fn collinear_points_and_a_comb() {
    // a comb with teeth, every side divided: many collinear boundary points and reflex corners
    let mut pts = vec![d(0.0, 0.0), d(5.0, 0.0), d(5.0, 2.0)];
    for k in (0..5).rev() {
        let x = k as f64;
        pts.extend([d(x + 0.8, 2.0), d(x + 0.8, 0.6), d(x + 0.2, 0.6), d(x + 0.2, 2.0)]);
    }
    pts.push(d(0.0, 2.0));
    let dom = Domain::from_loops(&[pts], None).unwrap();
    let size = |_: DVec2| 0.1;
    let dom = crate::mesh2d::boundary::split_boundary(&dom, &size).unwrap().domain;
    let out = mesh(&dom, &size, &Options::default()).unwrap();
    check_cover(&dom, &out.mesh, RegionId(1));
    let q = measure(&out.mesh, &size);
    assert!(q.size_ratio[1] > 0.8 && q.size_ratio[1] < 1.2, "{:?}", q.size_ratio);
}

#[test]
fn a_tiny_angle_and_a_hole_near_the_boundary() {
    let r = super::testkit::hard();
    let dom = prepared(&r);
    let out = mesh(&dom, &r.size, &Options::default()).unwrap();
    check_cover(&dom, &out.mesh, RegionId(1));
    let q = measure(&out.mesh, &r.size);
    eprintln!("ear hard tris {} angles {:.1}..{:.1} size ratio {:?} {:?}", q.triangles, q.angle_range[0], q.angle_range[1], q.size_ratio, out.stats);
    assert!(q.size_ratio[1] > 0.8 && q.size_ratio[1] < 1.2, "{:?}", q.size_ratio);
}
