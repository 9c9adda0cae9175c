//! The mesher's input checks: a closed, edge-manifold surface without degenerate or crossing
//! triangles. Each failure names what to fix.

use crate::mesh::TriSurface;
use crate::mesh::topology::{intersecting_pairs, nonmanifold_edges_list, open_edges_list};
use crate::mesh3d::mesher::MeshingError;
use crate::core::intersection::is_degenerate;

/// Checks `s` for meshing.
///
/// # Errors
/// [`MeshingError::Open`] (listing boundary edges), [`MeshingError::NonManifold`] (naming an
/// edge), [`MeshingError::Degenerate`] (a zero-area triangle, invalid indices) or
/// [`MeshingError::SelfIntersecting`] (two crossing triangles and their tags).
pub(crate) fn check(s: &TriSurface) -> Result<(), MeshingError> {
    s.validate().map_err(|e| MeshingError::Degenerate(e.to_string()))?;
    if s.triangles.len() < 4 {
        return Err(MeshingError::Degenerate(format!("{} triangles cannot enclose a volume", s.triangles.len())));
    }
    let open = open_edges_list(s);
    if !open.is_empty() {
        let count = open.len();
        // the faces along the open edges: the tags of the triangles that hold them
        let lookup: std::collections::BTreeSet<[u32; 2]> = open.iter().copied().collect();
        let mut tags: std::collections::BTreeSet<crate::core::FaceId> = std::collections::BTreeSet::new();
        for (t, tri) in s.triangles.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                if lookup.contains(&[a.min(b), a.max(b)]) {
                    tags.insert(s.face_tags.get(t).copied().unwrap_or_default());
                }
            }
        }
        let faces = tags.into_iter().take(10).map(|f| (f, s.face_names.get(f).map(str::to_string))).collect();
        let edges: Vec<[u32; 2]> = open.into_iter().take(10).collect();
        let at = edges.iter().map(|e| e.map(|v| s.vertices[v as usize].to_array())).collect();
        return Err(MeshingError::Open { count, edges, at, faces });
    }
    let nm = nonmanifold_edges_list(s);
    if let Some(&edge) = nm.first() {
        let count = s.triangles.iter().filter(|t| t.contains(&edge[0]) && t.contains(&edge[1])).count();
        return Err(MeshingError::NonManifold { edge, count });
    }
    for (i, t) in s.triangles.iter().enumerate() {
        let [a, b, c] = t.map(|v| s.vertices[v as usize]);
        if is_degenerate(a, b, c) {
            return Err(MeshingError::Degenerate(format!("triangle {i} ({}) has zero area", s.face_tags[i])));
        }
    }
    let pairs = intersecting_pairs(s);
    if let Some(&[a, b]) = pairs.first() {
        return Err(MeshingError::SelfIntersecting {
            a,
            b,
            tag_a: s.face_tags[a as usize],
            tag_b: s.face_tags[b as usize],
            count: pairs.len(),
        });
    }
    Ok(())
}
