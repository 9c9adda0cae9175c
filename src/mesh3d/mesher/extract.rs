//! The result as a [`TetMesh`]: the material tets with their region tags, the subfaces as
//! boundary triangles with the tags of the input triangles they lie in, oriented outward from
//! the material (interfaces between two regions keep the input's orientation). The input
//! vertices keep their indices; Steiner points follow.

use crate::core::ids::NONE;
use crate::mesh::TetMesh;
use crate::mesh::TriSurface;
use crate::mesh3d::mesher::MeshingError;
use crate::mesh3d::mesher::carve::Labels;
use crate::mesh3d::mesher::surface_model::SurfaceModel;
use crate::mesh3d::mesher::tetra::Tetra;
use crate::mesh3d::optimize::Adjacency;
use crate::mesh::tet_mesh::{TET_FACES, sorted3};
use rustc_hash::FxHashMap;

/// The output mesh and its adjacency, as the optimiser keeps it
/// ([`crate::mesh3d::optimize::Adjacency`]): read off the tetrahedralization's own links
/// instead of found again by sorting the faces.
pub(crate) struct Extracted {
    pub mesh: TetMesh,
    pub adjacency: Adjacency,
}

/// Builds the output mesh; with `check`, validated ([`TetMesh::validate`]). Without it the
/// caller checks it: the optimiser's working mesh is built with the same checks.
///
/// # Errors
/// [`MeshingError::Internal`] if a subface is missing or, with `check`, the result fails
/// [`TetMesh::validate`] (both would be bugs).
pub(crate) fn extract(tr: &Tetra, sm: &SurfaceModel, labels: &Labels, input: &TriSurface, check: bool) -> Result<Extracted, MeshingError> {
    let n_in = input.vertices.len();
    let mut index = vec![NONE; tr.num_points()];
    let mut vertices = input.vertices.clone();
    for (i, slot) in index.iter_mut().enumerate().take(n_in) {
        *slot = i as u32;
    }
    let mut tets = Vec::new();
    let mut region_tags = Vec::new();
    // per slot, the mesh's index of its tet (material tets only)
    let mut tet_index = vec![NONE; tr.tets.len()];
    let mut slots = Vec::new();
    for t in tr.live() {
        let l = labels.get(t);
        if l == 0 {
            continue;
        }
        tet_index[t as usize] = tets.len() as u32;
        slots.push(t);
        let v = tr.tets[t as usize].v.map(|p| {
            if index[p as usize] == NONE {
                index[p as usize] = vertices.len() as u32;
                vertices.push(tr.point(p));
            }
            index[p as usize]
        });
        tets.push(v);
        region_tags.push(labels.tags[(l - 1) as usize]);
    }
    let mut boundary = Vec::new();
    let mut face_tags = Vec::new();
    let mut buf = Vec::new();
    // the walled faces by their vertices, each from one of its sides: every subface is one
    // (carving walls them, refinement walls the pieces it makes), and any that were not would
    // be found by a walk; what follows does not depend on the side
    let mut walled: FxHashMap<[u32; 3], (u32, usize)> = FxHashMap::default();
    walled.reserve(sm.subfaces().count());
    for &t in &slots {
        let (w, v) = (tr.walls[t as usize], tr.tets[t as usize].v);
        for k in (0..4).filter(|&k| w >> k & 1 != 0) {
            walled.entry(sorted3(TET_FACES[k].map(|i| v[i])).0).or_insert((t, k));
        }
    }
    // the faces (slot, face) of the boundary triangles
    let mut listed = Vec::new();
    for (f, s) in sm.subfaces() {
        let (t, k) = match walled.get(&sorted3(s).0) {
            Some(&x) => x,
            None => tr.face_tet(s[0], s[1], s[2], &mut buf).ok_or_else(|| MeshingError::Internal(format!("subface {s:?} is missing at the end")))?,
        };
        let other = tr.tets[t as usize].n[k] >> 2;
        let (lt, lo) = (labels.get(t), labels.get(other));
        if lt == 0 && lo == 0 {
            continue; // between two voids: not a boundary of the mesh
        }
        listed.push((t, k));
        // orientation: outward from the material tet when only one side is material
        let mut tri = s;
        let inner = if lt != 0 && lo == 0 { Some(t) } else if lo != 0 && lt == 0 { Some(other) } else { None };
        if let Some(m) = inner {
            let w = tr.tets[m as usize].v;
            let apex = w.iter().copied().find(|x| !s.contains(x)).unwrap_or(w[0]);
            let [a, b, c, d] = [s[0], s[1], s[2], apex].map(|p| tr.point(p));
            // the apex must be on the negative side of an outward face
            if crate::core::predicates::orient3d(a, b, c, d) == crate::core::Sign::Positive {
                tri = [s[0], s[2], s[1]];
            }
        }
        let mapped = tri.map(|p| index[p as usize]);
        if mapped.contains(&NONE) {
            return Err(MeshingError::Internal(format!("subface {s:?} uses a vertex of no tet")));
        }
        boundary.push(mapped);
        face_tags.push(sm.facets[f as usize].tag);
    }
    // the neighbours across each face (the mesh's index and face) and the constrained faces:
    // on the boundary of the material, between two regions, or listed as a boundary triangle
    let index_of = |t: u32| tet_index.get(t as usize).copied().unwrap_or(NONE);
    let mut nbr = vec![[NONE; 4]; tets.len()];
    let mut cons = vec![0u8; tets.len()];
    for (i, &t) in slots.iter().enumerate() {
        for k in 0..4 {
            let n = tr.tets[t as usize].n[k];
            let j = index_of(n >> 2);
            if j == NONE {
                cons[i] |= 1 << k;
            } else {
                nbr[i][k] = j << 2 | (n & 3);
                if region_tags[i] != region_tags[j as usize] {
                    cons[i] |= 1 << k;
                }
            }
        }
    }
    for (t, k) in listed {
        let n = tr.tets[t as usize].n[k];
        for (s, f) in [(t, k), (n >> 2, (n & 3) as usize)] {
            let i = index_of(s);
            if i != NONE {
                cons[i as usize] |= 1 << f;
            }
        }
    }
    let mesh = TetMesh {
        vertices,
        tets,
        region_tags,
        boundary,
        face_tags,
        face_names: input.face_names.clone(),
        region_names: Default::default(),
    };
    if check {
        mesh.validate().map_err(|e| MeshingError::Internal(format!("the mesh does not validate: {e}")))?;
    }
    Ok(Extracted { mesh, adjacency: Adjacency { nbr, cons } })
}
