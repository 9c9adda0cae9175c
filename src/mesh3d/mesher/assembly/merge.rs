//! The meshes of an assembly's solids made one [`TetMesh`]: nodes renumbered (solid by solid,
//! in order), each solid's tets tagged with its region and named after it, boundary
//! triangles kept with their face tags. Where a boundary triangle of one solid and one of
//! another are the same three points with opposite orientations, the two solids' nodes there
//! are merged: the meshes share that face, a conforming interface, and both boundary
//! triangles stay (each oriented out of its own solid, with its own face's tag). Nothing
//! else is merged: solids that touch elsewhere keep their own nodes (the contact report says
//! where). Should the merged mesh fail [`TetMesh::validate`], the solids are left unmerged,
//! which is always valid.

use crate::core::ids::NONE;
use crate::core::union_find::UnionFind;
use crate::core::{FaceId, RegionId};
use crate::mesh::TetMesh;
use crate::mesh3d::mesher::MeshReport;
use crate::mesh3d::optimize::OptimizeReport;
use glam::DVec3;
use rustc_hash::FxHashMap;

/// A face shared by two solids after merging: (solid, face tag) of each side and the area.
pub(crate) type Shared = ((usize, FaceId), (usize, FaceId), f64);

/// Merges the solids' meshes (`meshes[s]` is solid `s`, tagged `tags[s]`, named `names[s]`).
pub(crate) fn merge(meshes: Vec<TetMesh>, tags: &[RegionId], names: &[Option<String>]) -> (TetMesh, Vec<Shared>) {
    let mut out = TetMesh::default();
    let mut solid_of_boundary: Vec<usize> = Vec::new();
    for (s, m) in meshes.into_iter().enumerate() {
        let off = out.vertices.len() as u32;
        out.vertices.extend(m.vertices);
        out.tets.extend(m.tets.iter().map(|t| t.map(|v| v + off)));
        out.region_tags.extend(std::iter::repeat_n(tags[s], m.tets.len()));
        out.boundary.extend(m.boundary.iter().map(|t| t.map(|v| v + off)));
        out.face_tags.extend(&m.face_tags);
        solid_of_boundary.extend(std::iter::repeat_n(s, m.boundary.len()));
        out.face_names.extend_missing(&m.face_names);
        if let Some(n) = &names[s] {
            out.region_names.insert(tags[s], n.clone());
        }
    }
    let pairs = coincident_pairs(&out, &solid_of_boundary);
    if pairs.is_empty() {
        return (out, Vec::new());
    }
    let mut uf = UnionFind::new(out.vertices.len());
    for &(i, j) in &pairs {
        let (ti, tj) = (out.boundary[i], out.boundary[j]);
        for vj in tj {
            if let Some(&vi) = ti.iter().find(|&&vi| out.vertices[vi as usize] == out.vertices[vj as usize]) {
                uf.union(vi, vj);
            }
        }
    }
    // the root of a set is its smallest index: the node of the first solid; the other nodes
    // go, the rest keep their order
    let mut index = vec![NONE; out.vertices.len()];
    let mut vertices: Vec<DVec3> = Vec::with_capacity(out.vertices.len());
    for v in 0..out.vertices.len() as u32 {
        let r = uf.find(v);
        if r == v {
            index[v as usize] = vertices.len() as u32;
            vertices.push(out.vertices[v as usize]);
        }
    }
    for v in 0..out.vertices.len() as u32 {
        let r = uf.find(v);
        index[v as usize] = index[r as usize];
    }
    let merged = TetMesh {
        vertices,
        tets: out.tets.iter().map(|t| t.map(|v| index[v as usize])).collect(),
        region_tags: out.region_tags.clone(),
        boundary: out.boundary.iter().map(|t| t.map(|v| index[v as usize])).collect(),
        face_tags: out.face_tags.clone(),
        face_names: out.face_names.clone(),
        region_names: out.region_names.clone(),
    };
    if merged.validate().is_err() {
        return (out, Vec::new());
    }
    let shared = pairs
        .iter()
        .map(|&(i, j)| {
            let [a, b, c] = out.boundary[i].map(|v| out.vertices[v as usize]);
            let area = 0.5 * (b - a).cross(c - a).length();
            ((solid_of_boundary[i], out.face_tags[i]), (solid_of_boundary[j], out.face_tags[j]), area)
        })
        .collect();
    (merged, shared)
}

/// Pairs `(i, j)` of boundary triangles of different solids (`i` earlier) that are the same
/// three points with opposite orientations; each triangle in one pair at most.
fn coincident_pairs(m: &TetMesh, solid_of: &[usize]) -> Vec<(usize, usize)> {
    let key = |t: [u32; 3]| {
        let mut k = t.map(|v| m.vertices[v as usize].to_array().map(|x| (x + 0.0).to_bits()));
        k.sort_unstable();
        k
    };
    let mut earlier: FxHashMap<[[u64; 3]; 3], Vec<usize>> = FxHashMap::default();
    let mut taken = vec![false; m.boundary.len()];
    let mut pairs = Vec::new();
    for j in 0..m.boundary.len() {
        let k = key(m.boundary[j]);
        let list = earlier.entry(k).or_default();
        if let Some(&i) = list.iter().find(|&&i| !taken[i] && solid_of[i] != solid_of[j] && opposite(m, m.boundary[i], m.boundary[j])) {
            taken[i] = true;
            taken[j] = true;
            pairs.push((i, j));
        }
        list.push(j);
    }
    pairs
}

/// True if triangle `b` runs through the points of `a` the other way round.
fn opposite(m: &TetMesh, a: [u32; 3], b: [u32; 3]) -> bool {
    let p = |v: u32| m.vertices[v as usize];
    let (a, b) = (a.map(p), b.map(p));
    (0..3).any(|r| a[0] == b[r] && a[1] == b[(r + 2) % 3] && a[2] == b[(r + 1) % 3])
}

/// The solids' reports as one: counts added, stage seconds added per stage, the
/// optimisation's extremes over all solids; `nodes`, `tets`, `regions` and `seconds` are the
/// caller's.
pub(crate) fn merge_reports(reports: &[MeshReport]) -> MeshReport {
    let mut out = MeshReport::default();
    for r in reports {
        out.boundary_steiner_points += r.boundary_steiner_points;
        out.volume_steiner_points += r.volume_steiner_points;
        out.refinement_boundary_points += r.refinement_boundary_points;
        out.input_caps_repaired += r.input_caps_repaired;
        if let Some(n) = &r.narrow {
            out.narrow.get_or_insert_with(Default::default).add(n);
        }
        out.flattening_volume += r.flattening_volume;
        out.refinement_stopped |= r.refinement_stopped;
        out.refinement_stop = out.refinement_stop.take().or_else(|| r.refinement_stop.clone());
        for (stage, s) in &r.stage_seconds {
            match out.stage_seconds.iter_mut().find(|(n, _)| n == stage) {
                Some((_, t)) => *t += s,
                None => out.stage_seconds.push((stage.clone(), *s)),
            }
        }
        if let Some(o) = &r.optimize {
            out.optimize = Some(match out.optimize.take() {
                None => o.clone(),
                Some(m) => merge_optimize(&m, o),
            });
        }
    }
    out
}

fn merge_optimize(a: &OptimizeReport, b: &OptimizeReport) -> OptimizeReport {
    OptimizeReport {
        tets_before: a.tets_before + b.tets_before,
        tets_after: a.tets_after + b.tets_after,
        min_dihedral_before: a.min_dihedral_before.min(b.min_dihedral_before),
        max_dihedral_before: a.max_dihedral_before.max(b.max_dihedral_before),
        min_dihedral_after: a.min_dihedral_after.min(b.min_dihedral_after),
        max_dihedral_after: a.max_dihedral_after.max(b.max_dihedral_after),
        max_radius_edge_before: a.max_radius_edge_before.max(b.max_radius_edge_before),
        max_radius_edge_after: a.max_radius_edge_after.max(b.max_radius_edge_after),
        bad_before: a.bad_before + b.bad_before,
        bad_after: a.bad_after + b.bad_after,
        flips23: a.flips23 + b.flips23,
        flips32: a.flips32 + b.flips32,
        flips44: a.flips44 + b.flips44,
        edge_removals: a.edge_removals + b.edge_removals,
        smoothing_moves: a.smoothing_moves + b.smoothing_moves,
        boundary_moves: a.boundary_moves + b.boundary_moves,
        curved_boundary_moves: a.curved_boundary_moves + b.curved_boundary_moves,
        insertions: a.insertions + b.insertions,
        insertion_attempts: a.insertion_attempts + b.insertion_attempts,
        passes: a.passes.max(b.passes),
        attempts: a.attempts + b.attempts,
        polish_attempts: a.polish_attempts + b.polish_attempts,
        focus_attempts: a.focus_attempts + b.focus_attempts,
        focus_dihedral_attempts: a.focus_dihedral_attempts + b.focus_dihedral_attempts,
        focus_repeat_attempts: a.focus_repeat_attempts + b.focus_repeat_attempts,
        focus_rounds: a.focus_rounds + b.focus_rounds,
        searched_vertices: a.searched_vertices + b.searched_vertices,
        search_moves: a.search_moves + b.search_moves,
        out_of_attempts: a.out_of_attempts || b.out_of_attempts,
        seconds: a.seconds + b.seconds,
        setup_seconds: a.setup_seconds + b.setup_seconds,
    }
}
