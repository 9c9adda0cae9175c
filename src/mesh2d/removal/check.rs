//! Stage 4 of element removal: the output's cover of the domain, checked before it is
//! returned (and by every test).
//!
//! - Inputs: a planar mesh whose first vertices are the domain's points (same indices),
//!   the domain.
//! - Checks: `PlanarMesh::validate` (positive triangles, conforming edges), the area equal
//!   to the domain's within 1e-9 relative, every domain point a vertex at the same position
//!   and used by an element, every domain segment an edge of a triangle in its direction,
//!   and the mesh's boundary edges exactly the domain's segments.

use crate::mesh::PlanarMesh;
use crate::mesh2d::domain::Domain;
use rustc_hash::FxHashSet;

/// How a mesh fails to cover its domain.
#[derive(Clone, Debug, PartialEq, thiserror::Error, serde::Serialize)]
#[non_exhaustive]
pub enum CoverError {
    /// `PlanarMesh::validate` failed.
    #[error("invalid mesh: {0}")]
    Invalid(String),
    /// The areas differ.
    #[error("mesh area {mesh} differs from the domain's {domain}")]
    Area {
        /// The mesh's.
        mesh: f64,
        /// The domain's.
        domain: f64,
    },
    /// A domain point is not a vertex of an element.
    #[error("domain point {0} is not a mesh vertex")]
    Point(u32),
    /// A domain segment is not a boundary edge of the mesh.
    #[error("domain segment {0} is not a boundary edge of the mesh")]
    Segment(usize),
    /// The mesh has a boundary edge that is no domain segment.
    #[error("mesh boundary edge {0} -> {1} is no domain segment")]
    ExtraBoundary(u32, u32),
}

/// Checks that `mesh` covers `domain` exactly (see the module docs).
///
/// # Errors
/// The first failure found.
pub fn check_cover(mesh: &PlanarMesh, domain: &Domain) -> Result<(), CoverError> {
    mesh.validate().map_err(|e| CoverError::Invalid(e.to_string()))?;
    let (a, d) = (mesh.area(), domain.area());
    if !((a - d).abs() <= 1e-9 * d.abs()) {
        return Err(CoverError::Area { mesh: a, domain: d });
    }
    let mut used = vec![false; mesh.vertices.len()];
    let mut edges: FxHashSet<[u32; 2]> = FxHashSet::default();
    for t in &mesh.triangles {
        for e in 0..3 {
            used[t[e] as usize] = true;
            edges.insert([t[e], t[(e + 1) % 3]]);
        }
    }
    for (i, p) in domain.points.iter().enumerate() {
        if mesh.vertices.get(i) != Some(p) || !used[i] {
            return Err(CoverError::Point(i as u32));
        }
    }
    let segments: FxHashSet<[u32; 2]> = domain.segments.iter().copied().collect();
    for (s, &[a, b]) in domain.segments.iter().enumerate() {
        if !edges.contains(&[a, b]) || edges.contains(&[b, a]) {
            return Err(CoverError::Segment(s));
        }
    }
    let mut boundary: Vec<[u32; 2]> = edges.iter().copied().filter(|&[a, b]| !edges.contains(&[b, a]) && !segments.contains(&[a, b])).collect();
    boundary.sort_unstable();
    if let Some(&[a, b]) = boundary.first() {
        return Err(CoverError::ExtraBoundary(a, b));
    }
    Ok(())
}
