//! Independent checks of a quadtree mesh: conformity, the boundary kept, angles.
//!
//! - Stage: after meshing (the mesher runs them before returning; tests and the CLI report
//!   them).
//! - Inputs: a [`QuadtreeMesh`] and the [`Domain`] it was made from.
//! - Output: `Ok` or the first violation; [`angles`] measures the smallest and largest
//!   angles of the template triangles (inside) and of the band.
//! - Invariants checked: [`PlanarMesh::validate`](crate::mesh::PlanarMesh::validate)
//!   (orientation exact, every edge in at most two elements, in opposite directions); the
//!   mesh's boundary edges are exactly the pieces of the input segments, each traversed with
//!   the domain on its left; each segment's pieces run from its start to its end, its
//!   interior points on the segment within `1e-12` of the domain's size.

use crate::mesh2d::domain::{point_segment_distance, Domain};
use super::QuadtreeMesh;
use crate::mesh::MeshError;
use glam::DVec2;
use std::collections::BTreeMap;

/// A violation found by [`check_conforming`].
#[derive(Clone, Debug, PartialEq, thiserror::Error, serde::Serialize)]
#[non_exhaustive]
pub enum CheckError {
    /// The container's own checks failed.
    #[error("the mesh is invalid: {0}")]
    Mesh(#[from] MeshError),
    /// A boundary edge of the mesh is no piece of an input segment.
    #[error("mesh edge {0} -> {1} is on the mesh's boundary but no piece of an input segment")]
    StrayBoundary(u32, u32),
    /// A piece of an input segment is not a boundary edge of the mesh (with the domain on
    /// its left).
    #[error("piece {1} -> {2} of input segment {0} is not a boundary edge of the mesh")]
    LostPiece(usize, u32, u32),
    /// A segment's chain does not start at its start, end at its end, or leaves the segment.
    #[error("input segment {0} is not kept: {1}")]
    Segment(usize, String),
}

/// Checks conformity and that the boundary is kept (see the module docs).
///
/// # Errors
/// The first violation found.
pub fn check_conforming(m: &QuadtreeMesh, domain: &Domain) -> Result<(), CheckError> {
    m.mesh.validate()?;
    let v = &m.mesh.vertices;
    // directed edges used once: the mesh's boundary
    let mut count: BTreeMap<(u32, u32), (usize, bool)> = BTreeMap::new();
    let mut add = |a: u32, b: u32| {
        let e = count.entry((a.min(b), a.max(b))).or_insert((0, a < b));
        e.0 += 1;
    };
    for t in &m.mesh.triangles {
        for k in 0..3 {
            add(t[k], t[(k + 1) % 3]);
        }
    }
    for q in &m.mesh.quads {
        for k in 0..4 {
            add(q[k], q[(k + 1) % 4]);
        }
    }
    let mut pieces: BTreeMap<(u32, u32), (usize, bool)> = BTreeMap::new();
    let tol = 1e-12 * (domain.bounds().1 - domain.bounds().0).length();
    for (s, chain) in m.boundary.iter().enumerate() {
        let (a, b) = domain.ends(s);
        if chain.len() < 2 || v[chain[0] as usize] != a || v[*chain.last().unwrap_or(&0) as usize] != b {
            return Err(CheckError::Segment(s, "its pieces do not run from its start to its end".to_string()));
        }
        for &p in &chain[1..chain.len() - 1] {
            let d = point_segment_distance(v[p as usize], a, b);
            if d > tol {
                return Err(CheckError::Segment(s, format!("vertex {p} is {d:e} off it")));
            }
        }
        for w in chain.windows(2) {
            pieces.insert((w[0].min(w[1]), w[0].max(w[1])), (s, w[0] < w[1]));
        }
    }
    for (&(a, b), &(n, forward)) in &count {
        if n == 1 {
            match pieces.get(&(a, b)) {
                Some(&(_, f)) if f == forward => {}
                _ => return Err(CheckError::StrayBoundary(if forward { a } else { b }, if forward { b } else { a })),
            }
        }
    }
    for (&(a, b), &(s, forward)) in &pieces {
        if count.get(&(a, b)).is_none_or(|&(n, f)| n != 1 || f != forward) {
            return Err(CheckError::LostPiece(s, if forward { a } else { b }, if forward { b } else { a }));
        }
    }
    Ok(())
}

/// Smallest and largest angles, in degrees.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Angles {
    /// Over the template triangles (interior quadrants): 45° and 90° by construction.
    pub inside: [f64; 2],
    /// Over the band's triangles.
    pub band: [f64; 2],
    /// Over the band's triangles with no vertex on the boundary.
    pub band_off_boundary: [f64; 2],
    /// Over the band's triangles with a vertex on the boundary.
    pub band_at_boundary: [f64; 2],
    /// The smallest angle of the input between two of its segments.
    pub input_smallest: f64,
}

/// The three angles of a triangle, degrees.
pub fn triangle_angles(p: [DVec2; 3]) -> [f64; 3] {
    let mut out = [0.0; 3];
    for k in 0..3 {
        let (a, b, c) = (p[k], p[(k + 1) % 3], p[(k + 2) % 3]);
        let (u, w) = (b - a, c - a);
        out[k] = u.perp_dot(w).abs().atan2(u.dot(w)).to_degrees();
    }
    out
}

/// The angles of the mesh (see [`Angles`]); quads are squares (90°) and not counted.
pub fn angles(m: &QuadtreeMesh, domain: &Domain) -> Angles {
    let mut on_boundary = vec![false; m.mesh.vertices.len()];
    for chain in &m.boundary {
        for &p in chain {
            on_boundary[p as usize] = true;
        }
    }
    let empty = [f64::INFINITY, f64::NEG_INFINITY];
    let mut r = Angles { inside: empty, band: empty, band_off_boundary: empty, band_at_boundary: empty, input_smallest: domain.smallest_angle_deg() };
    let widen = |x: &mut [f64; 2], a: [f64; 3]| {
        for v in a {
            x[0] = x[0].min(v);
            x[1] = x[1].max(v);
        }
    };
    for (t, tri) in m.mesh.triangles.iter().enumerate() {
        let a = triangle_angles(tri.map(|i| m.mesh.vertices[i as usize]));
        if t < m.inside_triangles {
            widen(&mut r.inside, a);
        } else {
            widen(&mut r.band, a);
            if tri.iter().any(|&i| on_boundary[i as usize]) {
                widen(&mut r.band_at_boundary, a);
            } else {
                widen(&mut r.band_off_boundary, a);
            }
        }
    }
    r
}
