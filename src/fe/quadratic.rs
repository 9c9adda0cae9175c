//! Second order: a mid-edge node on every tet edge; on the boundary, on the CAD face the edge
//! lies on (or the CAD edge two faces share), inside at the chord's midpoint. Elements that
//! curving would invert or distort past [`MIN_JACOBIAN_RATIO`] get their mid nodes moved back
//! to the chords, and are counted.

use super::element::TET_EDGES;
use super::geometry::BoundaryGeometry;
use super::jacobian::min_jacobian_ratio;
use super::model::CurvingReport;
use crate::core::FaceId;
use crate::mesh::TetMesh;
use glam::DVec3;
use rayon::prelude::*;
use rustc_hash::FxHashMap;

/// The smallest ratio of an element's Jacobian determinant (at its check points) to the
/// straight element's that curving may leave; below it the element's mid nodes go back to
/// the chords.
pub const MIN_JACOBIAN_RATIO: f64 = 0.05;

/// A boundary mid node farther from the chord's midpoint than this fraction of the edge's
/// length stays on the chord (a projection that went to another sheet of the surface).
const MAX_OFFSET: f64 = 0.25;

/// Ten-node tets.
#[derive(Clone, Debug)]
pub struct Quadratic {
    /// The mesh's vertices, then one mid node per edge.
    pub nodes: Vec<DVec3>,
    /// Ten nodes per element, Abaqus C3D10 order.
    pub elements: Vec<u32>,
    /// What curving did.
    pub report: CurvingReport,
}

/// The ten-node version of `mesh`, its boundary mid nodes placed through `geometry` (at the
/// chords' midpoints without one). Deterministic: mid nodes are numbered in the order the
/// tets first reach their edges.
pub fn make_quadratic(mesh: &TetMesh, geometry: Option<&dyn BoundaryGeometry>) -> Quadratic {
    let nv = mesh.vertices.len() as u32;
    let mut edge_id: FxHashMap<(u32, u32), u32> = FxHashMap::default();
    let mut edges: Vec<(u32, u32)> = Vec::new();
    let mut elements = Vec::with_capacity(10 * mesh.tets.len());
    for t in &mesh.tets {
        elements.extend_from_slice(t);
        for &[a, b] in &TET_EDGES {
            let key = (t[a].min(t[b]), t[a].max(t[b]));
            let id = *edge_id.entry(key).or_insert_with(|| {
                edges.push(key);
                nv + edges.len() as u32 - 1
            });
            elements.push(id);
        }
    }
    // the distinct non-zero face tags of the boundary triangles at each edge
    let mut tags: FxHashMap<u32, Vec<FaceId>> = FxHashMap::default();
    for (tri, &tag) in mesh.boundary.iter().zip(&mesh.face_tags) {
        for i in 0..3 {
            let (a, b) = (tri[i], tri[(i + 1) % 3]);
            if let Some(&id) = edge_id.get(&(a.min(b), a.max(b))) {
                let v = tags.entry(id - nv).or_default();
                if tag != FaceId::UNTAGGED && !v.contains(&tag) {
                    v.push(tag);
                }
            }
        }
    }
    let p = &mesh.vertices;
    let chord: Vec<DVec3> = edges.iter().map(|&(a, b)| (p[a as usize] + p[b as usize]) * 0.5).collect();
    // (curved position, on a face or on an edge) of each boundary edge's mid node
    let placed: Vec<(u32, Option<(DVec3, bool)>)> = {
        let mut ids: Vec<u32> = tags.keys().copied().collect();
        ids.sort_unstable();
        ids.into_par_iter()
            .map(|e| {
                let (a, b) = (p[edges[e as usize].0 as usize], p[edges[e as usize].1 as usize]);
                let m = chord[e as usize];
                let on = match (geometry, tags[&e].as_slice()) {
                    (Some(g), [f]) => g.on_face(*f, a, b, m).map(|q| (q, true)),
                    (Some(g), [f, h]) => g.on_edge(*f, *h, a, b, m).map(|q| (q, false)),
                    _ => None,
                };
                (e, on.filter(|(q, _)| (*q - m).length() <= MAX_OFFSET * (b - a).length()))
            })
            .collect()
    };
    let mut nodes: Vec<DVec3> = p.clone();
    nodes.extend_from_slice(&chord);
    let mut report = CurvingReport::default();
    let mut curved = vec![false; edges.len()];
    for (e, on) in placed {
        match on {
            Some((q, face)) => {
                nodes[(nv + e) as usize] = q;
                curved[e as usize] = true;
                if face { report.on_faces += 1 } else { report.on_edges += 1 }
            }
            None => report.left_straight += 1,
        }
    }
    straighten(&mut nodes, &elements, &chord, &mut curved, nv, &mut report);
    Quadratic { nodes, elements, report }
}

/// Moves the curved mid nodes of every element whose Jacobian ratio falls below
/// [`MIN_JACOBIAN_RATIO`] back to their chords, then checks the elements that share those
/// edges again, until none is below (a straight element's ratio is 1).
fn straighten(nodes: &mut [DVec3], elements: &[u32], chord: &[DVec3], curved: &mut [bool], nv: u32, report: &mut CurvingReport) {
    let ratio = |nodes: &[DVec3], e: usize| -> f64 {
        let pts: Vec<DVec3> = elements[10 * e..10 * e + 10].iter().map(|&v| nodes[v as usize]).collect();
        min_jacobian_ratio(&pts)
    };
    let ne = elements.len() / 10;
    // elements of each mid node
    let mut of_edge: Vec<Vec<u32>> = vec![Vec::new(); chord.len()];
    for e in 0..ne {
        for &m in &elements[10 * e + 4..10 * e + 10] {
            of_edge[(m - nv) as usize].push(e as u32);
        }
    }
    let is_curved = |e: usize, curved: &[bool]| elements[10 * e + 4..10 * e + 10].iter().any(|&m| curved[(m - nv) as usize]);
    let mut check: Vec<usize> = (0..ne).filter(|&e| is_curved(e, curved)).collect();
    let mut fixed = vec![false; ne];
    while !check.is_empty() {
        let snapshot: &[DVec3] = nodes;
        let bad: Vec<usize> = check.par_iter().copied().filter(|&e| ratio(snapshot, e) < MIN_JACOBIAN_RATIO).collect();
        let mut next = Vec::new();
        for e in bad {
            if !fixed[e] {
                fixed[e] = true;
                report.straightened_elements += 1;
            }
            for &m in &elements[10 * e + 4..10 * e + 10] {
                let k = (m - nv) as usize;
                if curved[k] {
                    curved[k] = false;
                    nodes[m as usize] = chord[k];
                    report.straightened += 1;
                    next.extend(of_edge[k].iter().map(|&x| x as usize));
                }
            }
        }
        next.sort_unstable();
        next.dedup();
        next.retain(|&e| is_curved(e, curved));
        check = next;
    }
    report.min_jacobian_ratio = (0..ne).into_par_iter().map(|e| ratio(nodes, e)).reduce(|| f64::INFINITY, f64::min);
    if ne == 0 {
        report.min_jacobian_ratio = 0.0;
    }
}
