//! The mesher's input checks: a closed, edge-manifold surface without degenerate or crossing
//! triangles. Each failure names what to fix.

use crate::core::FaceId;
use crate::mesh::TriSurface;
use crate::mesh::narrow::{NarrowReport, collapse_narrow};
use crate::mesh3d::mesher::MeshOptions;
use crate::mesh::topology::{intersecting_pairs, nonmanifold_edges_list, open_edges_list};
use crate::mesh3d::mesher::MeshingError;
use crate::core::intersection::is_degenerate;

/// The surface the mesher takes: `surface` with its caps repaired and its narrow strips
/// closed up, where it had any (`surface: None` where it is taken as it is).
pub(crate) struct Prepared {
    pub surface: Option<TriSurface>,
    pub caps: usize,
    pub narrow: Option<NarrowReport>,
}

/// Prepares `surface` for meshing and checks it. Caps (flat triangles with a vertex on their
/// long side) would make input edges meet at an angle of zero: each takes its neighbour's
/// other half instead, before the checks (a cap may look like a crossing of its neighbours).
/// Then strips narrower than `options`' narrow tolerance are closed up, faces tagged `pinned`
/// left as they are; where the surface that leaves fails the checks that the input passes,
/// the input is meshed as it is.
///
/// # Errors
/// What [`check`] finds in the input.
pub(crate) fn prepare(surface: &TriSurface, options: &MeshOptions, pinned: &[FaceId]) -> Result<Prepared, MeshingError> {
    let repaired = crate::mesh::caps::repair_caps(surface);
    let caps = repaired.as_ref().map_or(0, |r| r.1);
    let base = repaired.as_ref().map_or(surface, |r| &r.0);
    check(base)?;
    let tol = options.narrow_length(surface);
    if let Some((closed, report)) = collapse_narrow(base, tol, pinned) {
        if check(&closed).is_ok() {
            return Ok(Prepared { surface: Some(closed), caps, narrow: Some(report) });
        }
    }
    Ok(Prepared { surface: repaired.map(|r| r.0), caps, narrow: None })
}

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
