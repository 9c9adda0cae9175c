//! Test regions of issue 66 and the coverage check, shared by the tests of `ear` and
//! `recursive`.

use crate::core::RegionId;
use crate::mesh::PlanarMesh;
use crate::mesh2d::boundary::split_boundary;
use crate::mesh2d::domain::Domain;
use glam::DVec2;
use std::f64::consts::TAU;

fn d(x: f64, y: f64) -> DVec2 {
    DVec2::new(x, y)
}

fn ngon(c: DVec2, r: f64, n: usize, phase: f64) -> Vec<DVec2> {
    (0..n).map(|k| c + r * DVec2::from_angle(phase + TAU * k as f64 / n as f64)).collect()
}

/// A named test region with its size field.
pub(crate) struct Region {
    /// Name for reports.
    pub name: &'static str,
    /// The domain as given (segments not yet divided).
    pub domain: Domain,
    /// The size field.
    pub size: Box<dyn Fn(DVec2) -> f64>,
}

/// The regions of HELPERS66.md: convex, non-convex, two holes, thin strip, graded size.
pub(crate) fn regions() -> Vec<Region> {
    let twelve = Domain::from_loops(&[ngon(DVec2::ZERO, 1.0, 12, 0.0)], None).unwrap();
    let l = Domain::from_loops(&[vec![d(0.0, 0.0), d(2.0, 0.0), d(2.0, 1.0), d(1.0, 1.0), d(1.0, 2.0), d(0.0, 2.0)]], None).unwrap();
    let star: Vec<DVec2> = (0..16).map(|k| DVec2::from_angle(TAU * k as f64 / 16.0) * if k % 2 == 0 { 1.0 } else { 0.45 }).collect();
    let star = Domain::from_loops(&[star], None).unwrap();
    let holes = two_holes();
    let strip = Domain::from_loops(&[vec![d(0.0, 0.0), d(6.0, 0.0), d(6.0, 0.2), d(0.0, 0.2)]], None).unwrap();
    let graded = move |p: DVec2| 0.06 * (1.0 + 2.0 * (p - d(0.0, 0.0)).length() / 5.0);
    vec![
        Region { name: "12-gon", domain: twelve, size: Box::new(|_: DVec2| 0.1) },
        Region { name: "L", domain: l, size: Box::new(|_: DVec2| 0.1) },
        Region { name: "star", domain: star, size: Box::new(|_: DVec2| 0.08) },
        Region { name: "two holes", domain: holes.clone(), size: Box::new(|_: DVec2| 0.15) },
        Region { name: "thin strip", domain: strip, size: Box::new(|_: DVec2| 0.05) },
        Region { name: "graded", domain: holes, size: Box::new(graded) },
    ]
}

/// A 4 × 3 rectangle with a 24-gon hole and a square hole.
pub(crate) fn two_holes() -> Domain {
    let outer = vec![d(0.0, 0.0), d(4.0, 0.0), d(4.0, 3.0), d(0.0, 3.0)];
    let circle = ngon(d(1.2, 1.5), 0.7, 24, 0.1);
    let square = vec![d(2.6, 1.0), d(3.4, 1.0), d(3.4, 1.8), d(2.6, 1.8)];
    Domain::from_loops(&[outer, circle, square], None).unwrap()
}

/// The domain with its segments divided by the size (what the lead does before a method).
pub(crate) fn prepared(r: &Region) -> Domain {
    split_boundary(&r.domain, &r.size).unwrap().domain
}

/// Asserts the contract: a valid mesh, its area the domain's, the domain's points its first
/// vertices, its boundary edges exactly the domain's segments (same direction), every
/// element tagged `region`.
pub(crate) fn check_cover(domain: &Domain, mesh: &PlanarMesh, region: RegionId) {
    assert_eq!(mesh.validate(), Ok(()));
    let rel = (mesh.area() - domain.area()).abs() / domain.area();
    assert!(rel < 1e-9, "area {} vs {} ({rel:e})", mesh.area(), domain.area());
    assert!(mesh.vertices.len() >= domain.points.len());
    assert_eq!(&mesh.vertices[..domain.points.len()], &domain.points[..]);
    assert!(mesh.triangle_tags.iter().chain(&mesh.quad_tags).all(|&t| t == region));
    let mut edges: Vec<(u32, u32)> = Vec::new();
    for t in &mesh.triangles {
        for k in 0..3 {
            edges.push((t[k], t[(k + 1) % 3]));
        }
    }
    for q in &mesh.quads {
        for k in 0..4 {
            edges.push((q[k], q[(k + 1) % 4]));
        }
    }
    edges.sort_unstable();
    let mut boundary: Vec<(u32, u32)> = edges.iter().copied().filter(|&(a, b)| edges.binary_search(&(b, a)).is_err()).collect();
    boundary.sort_unstable();
    let mut segments: Vec<(u32, u32)> = domain.segments.iter().map(|&[a, b]| (a, b)).collect();
    segments.sort_unstable();
    assert_eq!(boundary, segments, "the mesh's boundary edges are not the domain's segments");
}

/// A CAD-like hard case: a 4.9° input angle, a reflex corner, and a square hole 0.03 to 0.07
/// from the outer loop (closer than the size), every segment divided by the size.
pub(crate) fn hard() -> Region {
    let outer = vec![d(0.0, 0.0), d(4.0, 0.0), d(4.2, 1.5), d(2.0, 1.5), d(3.5, 0.3)];
    let hole = vec![d(3.75, 0.6), d(4.05, 0.6), d(4.05, 0.9), d(3.75, 0.9)];
    Region { name: "hard", domain: Domain::from_loops(&[outer, hole], None).unwrap(), size: Box::new(|_: DVec2| 0.1) }
}
