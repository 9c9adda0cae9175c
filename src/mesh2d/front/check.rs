//! The output check: the mesh is valid and covers exactly the domain.
//!
//! - Stage: last, before [`mesh`](super::mesh) returns (a failure is an internal error, never
//!   a bad mesh); the tests call it on every mesh.
//! - Inputs: the domain and the mesh made of it.
//! - Checks: [`PlanarMesh::validate`] (exact orientation, conformity); every domain point is
//!   the mesh vertex of the same index at the same place; the mesh's boundary edges (used by
//!   one triangle) are exactly the domain's segments, each run with the domain on its left;
//!   the area equals the domain's within `1e-9` relative.

use crate::mesh::PlanarMesh;
use crate::mesh2d::Domain;
use std::collections::BTreeMap;

/// Checks that `mesh` is a valid mesh of exactly `domain` (see the module docs).
///
/// # Errors
/// The first violation, in words.
pub fn check_coverage(domain: &Domain, mesh: &PlanarMesh) -> Result<(), String> {
    mesh.validate().map_err(|e| format!("the mesh is invalid: {e}"))?;
    for (i, p) in domain.points.iter().enumerate() {
        if mesh.vertices.get(i) != Some(p) {
            return Err(format!("domain point {i} ({}, {}) is not mesh vertex {i}", p.x, p.y));
        }
    }
    // undirected edge -> (uses, direction of the last use)
    let mut uses: BTreeMap<(u32, u32), (usize, [u32; 2])> = BTreeMap::new();
    for t in &mesh.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let e = uses.entry((a.min(b), a.max(b))).or_insert((0, [a, b]));
            e.0 += 1;
            e.1 = [a, b];
        }
    }
    for q in &mesh.quads {
        for k in 0..4 {
            let (a, b) = (q[k], q[(k + 1) % 4]);
            let e = uses.entry((a.min(b), a.max(b))).or_insert((0, [a, b]));
            e.0 += 1;
            e.1 = [a, b];
        }
    }
    let mut boundary: Vec<[u32; 2]> = uses.values().filter(|u| u.0 == 1).map(|u| u.1).collect();
    let mut segments = domain.segments.clone();
    boundary.sort_unstable();
    segments.sort_unstable();
    if boundary != segments {
        let stray = boundary.iter().find(|e| segments.binary_search(e).is_err());
        let lost = segments.iter().find(|s| boundary.binary_search(s).is_err());
        return Err(format!("the mesh's boundary is not the domain's: mesh boundary edge {stray:?} is no segment, segment {lost:?} is no boundary edge"));
    }
    let (area, want) = (mesh.area(), domain.area());
    if !((area - want).abs() <= 1e-9 * want.abs()) {
        return Err(format!("the mesh's area {area} is not the domain's {want}"));
    }
    Ok(())
}
