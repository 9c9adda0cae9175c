//! Tests of the surface report on small constructed surfaces.

use super::*;
use crate::core::Tolerance;
use std::f64::consts::TAU;

fn report(s: &TriSurface) -> SurfaceReport {
    let r = surface_report(s, &ReportOptions::default());
    // the JSON form must always be producible
    assert!(serde_json::to_string(&r).is_ok());
    r
}

/// The cube `[lo, lo + size]^3`, outward unless `reversed`, all triangles tagged `tag`.
fn cube(lo: DVec3, size: f64, reversed: bool, tag: u32) -> TriSurface {
    let v = (0..8).map(|i| lo + size * DVec3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64)).collect();
    #[rustfmt::skip]
    let mut t = vec![
        [0, 2, 3], [0, 3, 1], [4, 5, 7], [4, 7, 6], [0, 1, 5], [0, 5, 4],
        [2, 6, 7], [2, 7, 3], [0, 4, 6], [0, 6, 2], [1, 3, 7], [1, 7, 5],
    ];
    if reversed {
        for x in &mut t {
            x.swap(1, 2);
        }
    }
    TriSurface::with_single_tag(v, t, FaceId(tag))
}

fn join(parts: &[TriSurface]) -> TriSurface {
    let mut s = TriSurface::default();
    for p in parts {
        s.append(p);
    }
    s
}

/// A torus with radii `big`, `small`, `n × m` quads, outward.
fn torus(big: f64, small: f64, n: usize, m: usize) -> TriSurface {
    let mut v = Vec::new();
    for i in 0..n {
        for j in 0..m {
            let (u, w) = (TAU * i as f64 / n as f64, TAU * j as f64 / m as f64);
            v.push(DVec3::new((big + small * w.cos()) * u.cos(), (big + small * w.cos()) * u.sin(), small * w.sin()));
        }
    }
    let id = |i: usize, j: usize| ((i % n) * m + j % m) as u32;
    let mut t = Vec::new();
    for i in 0..n {
        for j in 0..m {
            t.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            t.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    TriSurface::with_single_tag(v, t, FaceId(1))
}

#[test]
fn unit_cube() {
    let r = report(&cube(DVec3::ZERO, 1.0, false, 1));
    assert_eq!((r.vertices, r.triangles, r.edges, r.components), (8, 12, 18, 1));
    assert!(r.closed && r.manifold && r.oriented && r.outward);
    assert_eq!((r.euler, r.genus, r.open_edges, r.nonmanifold_edges, r.nonmanifold_vertices), (2, Some(0), 0, 0, 0));
    assert!((r.volume - 1.0).abs() < 1e-14 && (r.area - 6.0).abs() < 1e-14);
    assert_eq!((r.self_intersections, r.degenerate_triangles, r.boundary_loops), (Some(0), 0, 0));
    let s = &r.shells[0];
    assert_eq!((s.euler, s.genus, s.depth, s.parent, s.outward), (2, Some(0), Some(0), None, Some(true)));
    assert_eq!(s.tags, vec![FaceId(1)]);
    assert_eq!(r.bbox, Some([[0.0; 3], [1.0; 3]]));
    // inside out: still closed and oriented, but not outward
    let r = report(&cube(DVec3::ZERO, 1.0, true, 1));
    assert!(r.closed && r.oriented && !r.outward);
    assert!((r.volume + 1.0).abs() < 1e-14);
    assert_eq!(r.shells[0].outward, Some(false));
}

#[test]
fn torus_has_genus_one() {
    let s = torus(3.0, 1.0, 24, 12);
    let r = report(&s);
    assert!(r.closed && r.manifold && r.oriented && r.outward);
    assert_eq!((r.euler, r.genus, r.self_intersections), (0, Some(1), Some(0)));
    let exact = TAU * std::f64::consts::PI * 3.0;
    assert!(r.volume > 0.9 * exact && r.volume < exact);
}

#[test]
fn two_disjoint_cubes() {
    let s = join(&[cube(DVec3::ZERO, 1.0, false, 1), cube(DVec3::splat(3.0), 1.0, false, 2)]);
    let r = report(&s);
    assert_eq!((r.components, r.euler, r.genus), (2, 4, Some(0)));
    assert!(r.closed && r.manifold && r.outward);
    assert_eq!(r.shells.iter().map(|x| x.first_triangle).collect::<Vec<_>>(), vec![0, 12]);
    assert_eq!(r.shells[1].tags, vec![FaceId(2)]);
    assert_eq!(r.shells.iter().map(|x| x.depth).collect::<Vec<_>>(), vec![Some(0), Some(0)]);
    assert!((r.volume - 2.0).abs() < 1e-14);
    assert_eq!(triangle_shells(&s)[13], Some(1));
}

#[test]
fn cube_with_cavity() {
    let outer = cube(DVec3::ZERO, 3.0, false, 1);
    let good = join(&[outer.clone(), cube(DVec3::ONE, 1.0, true, 2)]);
    let r = report(&good);
    assert_eq!(r.components, 2);
    assert!(r.closed && r.manifold && r.oriented && r.outward, "{r:?}");
    assert_eq!((r.shells[1].depth, r.shells[1].parent, r.shells[1].outward), (Some(1), Some(0), Some(true)));
    assert!((r.volume - 26.0).abs() < 1e-12);
    // the cavity not reversed is wrong
    let bad = join(&[outer.clone(), cube(DVec3::ONE, 1.0, false, 2)]);
    let r = report(&bad);
    assert!(r.closed && r.oriented && !r.outward);
    assert_eq!((r.shells[0].outward, r.shells[1].outward), (Some(true), Some(false)));
    // an island inside the cavity is outward again, its parent the cavity
    let big = cube(DVec3::ZERO, 5.0, false, 1);
    let three = join(&[cube(DVec3::splat(2.0), 1.0, false, 3), big, cube(DVec3::ONE, 3.0, true, 2)]);
    let r = report(&three);
    assert!(r.outward);
    let d: Vec<_> = r.shells.iter().map(|x| (x.depth, x.parent)).collect();
    assert_eq!(d, vec![(Some(2), Some(2)), (Some(0), None), (Some(1), Some(1))]);
    assert!(r.self_intersections == Some(0));
}

#[test]
fn open_box() {
    let mut s = cube(DVec3::ZERO, 1.0, false, 1);
    s.triangles.drain(2..4); // the top
    s.face_tags.drain(2..4);
    let r = report(&s);
    assert!(!r.closed && r.manifold && r.oriented && !r.outward);
    assert_eq!((r.open_edges, r.boundary_loops, r.boundary_loop_edges.clone(), r.boundary_chains), (4, 1, vec![4], 0));
    assert_eq!((r.euler, r.genus, r.shells[0].genus, r.shells[0].depth, r.shells[0].outward), (1, None, None, None, None));
    assert_eq!(open_edges_list(&s), vec![[4, 5], [4, 6], [5, 7], [6, 7]]);
    let loops = boundary_loops(&s);
    assert_eq!(loops.len(), 1);
    let mut l = loops[0].clone();
    l.sort_unstable();
    assert_eq!(l, vec![4, 5, 6, 7]);
}

#[test]
fn nonmanifold_edge() {
    let v = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z, DVec3::new(0.0, -1.0, -1.0)];
    let s = TriSurface::with_single_tag(v, vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]], FaceId(1));
    let r = report(&s);
    assert_eq!((r.nonmanifold_edges, r.open_edges, r.components, r.nonmanifold_vertices), (1, 6, 1, 2));
    assert!(!r.closed && !r.manifold && !r.edge_manifold && !r.oriented);
    assert_eq!(nonmanifold_edges_list(&s), vec![[0, 1]]);
    assert_eq!(r.self_intersections, Some(0));
    assert!(!r.shells[0].edge_manifold);
}

#[test]
fn cubes_sharing_a_vertex() {
    let mut s = join(&[cube(DVec3::ZERO, 1.0, false, 1), cube(DVec3::ONE, 1.0, false, 2)]);
    s.weld(Tolerance::WELD);
    assert_eq!(s.vertices.len(), 15);
    let r = report(&s);
    assert_eq!((r.components, r.nonmanifold_vertices, r.self_intersections), (2, 1, Some(0)));
    assert!(r.closed && r.edge_manifold && !r.vertex_manifold && !r.manifold);
    assert_eq!(r.genus, None);
    assert!(r.shells.iter().all(|x| x.vertex_manifold && x.genus == Some(0) && x.depth == Some(0)));
    assert_eq!(r.euler, 15 - 36 + 24);
}

#[test]
fn bow_tie_vertex_within_one_shell() {
    // two triangles touching only at a vertex are two shells; joined by a third they are one
    // shell with one non-manifold vertex
    let v = vec![DVec3::ZERO, DVec3::X, DVec3::Y, -DVec3::X, -DVec3::Y];
    let s = TriSurface::with_single_tag(v, vec![[0, 1, 2], [0, 3, 4]], FaceId(1));
    let r = report(&s);
    assert_eq!((r.components, r.nonmanifold_vertices, r.boundary_loops), (2, 1, 2));
    assert!(r.shells.iter().all(|x| x.vertex_manifold));
}

#[test]
fn intersecting_cubes() {
    let s = join(&[cube(DVec3::ZERO, 1.0, false, 1), cube(DVec3::splat(0.5), 1.0, false, 2)]);
    let r = report(&s);
    let n = r.self_intersections.unwrap_or(0);
    assert!(n > 0);
    assert_eq!(r.first_intersections.len(), 10.min(n));
    for p in &r.first_intersections {
        assert!(p.a < 12 && p.b >= 12 && p.tag_a == FaceId(1) && p.tag_b == FaceId(2));
    }
    let all = intersecting_pairs(&s);
    assert_eq!(all.len(), n);
    assert_eq!(all[..r.first_intersections.len()], r.first_intersections.iter().map(|p| [p.a, p.b]).collect::<Vec<_>>()[..]);
    let r2 = surface_report(&s, &ReportOptions::default().with_self_intersections(false).with_max_listed(3));
    assert_eq!((r2.self_intersections, r2.first_intersections.len()), (None, 0));
    let r3 = surface_report(&s, &ReportOptions::default().with_max_listed(3));
    assert_eq!(r3.first_intersections[..], r.first_intersections[..3]);
    // cubes touching along a face, with distinct vertices: touching counts
    let s = join(&[cube(DVec3::ZERO, 1.0, false, 1), cube(DVec3::X, 1.0, false, 2)]);
    let r = report(&s);
    assert!(r.self_intersections.unwrap_or(0) > 0);
    assert_eq!(r.shells.iter().map(|x| x.depth).collect::<Vec<_>>(), vec![Some(0), Some(0)]);
}

#[test]
fn folds_and_duplicates_intersect() {
    let mut s = cube(DVec3::ZERO, 1.0, false, 1);
    s.triangles.push([0, 2, 3]);
    s.face_tags.push(FaceId(9));
    let r = report(&s);
    assert_eq!(r.self_intersections, Some(1));
    assert_eq!(r.first_intersections[0].a, 0);
    assert_eq!(r.nonmanifold_edges, 3);
    // a flat fold: two triangles on the same side of their shared edge
    let v = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(0.5, 0.8, 0.0)];
    let s = TriSurface::with_single_tag(v, vec![[0, 1, 2], [1, 0, 3]], FaceId(1));
    assert_eq!(report(&s).self_intersections, Some(1));
}

#[test]
fn flipped_triangle() {
    let mut s = cube(DVec3::ZERO, 1.0, false, 1);
    s.triangles[5].swap(0, 1);
    let r = report(&s);
    assert!(r.closed && r.manifold && !r.oriented && !r.outward);
    assert_eq!((r.misoriented_edges, r.genus), (3, None));
    let sh = &r.shells[0];
    assert!(sh.orientable && !sh.oriented && sh.genus == Some(0) && sh.outward.is_none());
}

#[test]
fn mobius_strip_is_not_orientable() {
    let n = 12;
    let mut v = Vec::new();
    for i in 0..n {
        let u = TAU * i as f64 / n as f64;
        let c = DVec3::new(3.0 * u.cos(), 3.0 * u.sin(), 0.0);
        let w = DVec3::new(u.cos() * (u / 2.0).cos(), u.sin() * (u / 2.0).cos(), (u / 2.0).sin());
        v.extend([c - w, c + w]);
    }
    let id = |i: usize, j: usize| if i == n { (1 - j) as u32 } else { (2 * i + j) as u32 }; // half twist at the seam
    let mut t = Vec::new();
    for i in 0..n {
        t.push([id(i, 0), id(i + 1, 0), id(i + 1, 1)]);
        t.push([id(i, 0), id(i + 1, 1), id(i, 1)]);
    }
    let r = report(&TriSurface::with_single_tag(v, t, FaceId(1)));
    assert!(!r.shells[0].orientable && !r.oriented && r.manifold);
    assert_eq!((r.boundary_loops, r.boundary_loop_edges.clone(), r.euler), (1, vec![2 * n], 0));
}

#[test]
fn degenerate_and_invalid_triangles() {
    let mut s = cube(DVec3::ZERO, 1.0, false, 1);
    s.vertices.push(DVec3::new(0.5, 0.0, 0.0)); // 8: on the edge 0-1
    s.triangles.extend([[0, 1, 8], [0, 0, 1], [0, 1, 99]]);
    s.face_tags.extend([FaceId(1); 3]);
    let r = report(&s);
    assert_eq!((r.invalid_triangles, r.degenerate_triangles, r.first_degenerate.clone()), (2, 2, vec![12, 13]));
    assert_eq!((r.self_intersections, r.triangles), (Some(0), 15));
    assert_eq!(r.nonmanifold_edges, 1);
    assert_eq!(triangle_shells(&s)[13..], [None, None]);
    // missing tags and an empty surface do not panic
    let mut s = cube(DVec3::ZERO, 1.0, false, 1);
    s.face_tags.clear();
    assert!(report(&s).closed);
    let r = report(&TriSurface::default());
    assert!(!r.closed && r.components == 0 && r.bbox.is_none());
}

#[test]
fn same_report_for_any_thread_count() {
    let s = join(&[
        torus(3.0, 1.0, 40, 20),
        cube(DVec3::new(3.5, -0.5, -0.5), 1.0, false, 2),
        cube(DVec3::splat(-0.5), 1.0, true, 3),
    ]);
    let run = |threads| rayon::ThreadPoolBuilder::new().num_threads(threads).build().map(|p| p.install(|| report(&s))).ok();
    let one = run(1);
    assert!(one.as_ref().is_some_and(|r| r.self_intersections.unwrap_or(0) > 0));
    assert_eq!(one, run(2));
    assert_eq!(one, run(5));
}
