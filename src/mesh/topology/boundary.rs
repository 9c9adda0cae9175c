//! Boundary loops: the open edges (one triangle) chained into closed loops.
//!
//! Input: valid triangles and their edge table. Output: [`Walk`], the loops as vertex
//! sequences (a loop of `n` vertices has `n` edges) in the direction of their triangles where
//! that is consistent, and the number of chains that cannot close (open edges around
//! non-manifold configurations, where a vertex has an odd number of open edges).
//!
//! Each walk starts at the unused open edge with the smallest index (edges in `(lo, hi)`
//! order), continues at each vertex with an unused open edge leaving it in its triangle's
//! direction if there is one (else any unused one, smallest index first) and closes as soon as
//! it returns to its start vertex, so two holes touching at a vertex give two loops.

use super::Prepared;
use super::edges::{EdgeTable, ends};
use crate::mesh::TriSurface;

/// Loops and unclosed chains of open edges.
pub(crate) struct Walk {
    pub loops: Vec<Vec<u32>>,
    pub chains: usize,
}

/// Chains the open edges of `tris` into loops.
pub(crate) fn walk(tris: &[[u32; 3]], et: &EdgeTable) -> Walk {
    // open edges, directed as their triangle runs them
    let open: Vec<(u32, u32)> = (0..et.len()).filter(|&e| et.valence(e) == 1).map(|e| ends(tris, &et.halves(e)[0])).collect();
    if open.is_empty() {
        return Walk { loops: Vec::new(), chains: 0 };
    }
    // incidence of vertices (compacted) to open edges, CSR
    let mut verts: Vec<u32> = open.iter().flat_map(|&(a, b)| [a, b]).collect();
    verts.sort_unstable();
    verts.dedup();
    let local = |v: u32| verts.binary_search(&v).unwrap_or(0);
    let mut start = vec![0usize; verts.len() + 1];
    for &(a, b) in &open {
        start[local(a) + 1] += 1;
        start[local(b) + 1] += 1;
    }
    for i in 0..verts.len() {
        start[i + 1] += start[i];
    }
    let mut cursor = start.clone();
    let mut inc = vec![0u32; 2 * open.len()];
    for (e, &(a, b)) in open.iter().enumerate() {
        for v in [a, b] {
            inc[cursor[local(v)]] = e as u32;
            cursor[local(v)] += 1;
        }
    }
    let mut used = vec![false; open.len()];
    let mut loops = Vec::new();
    let mut chains = 0;
    for e0 in 0..open.len() {
        if used[e0] {
            continue;
        }
        used[e0] = true;
        let (first, mut cur) = open[e0];
        let mut path = vec![first];
        loop {
            if cur == first {
                loops.push(path);
                break;
            }
            path.push(cur);
            let l = local(cur);
            let candidates = &inc[start[l]..start[l + 1]];
            let next = candidates
                .iter()
                .copied()
                .find(|&e| !used[e as usize] && open[e as usize].0 == cur)
                .or_else(|| candidates.iter().copied().find(|&e| !used[e as usize]));
            let Some(e) = next else {
                chains += 1;
                break;
            };
            used[e as usize] = true;
            let (a, b) = open[e as usize];
            cur = if a == cur { b } else { a };
        }
    }
    Walk { loops, chains }
}

/// The boundary loops of `s` as vertex sequences (loop `i` has `loops[i].len()` edges),
/// directed as their triangles run them where that is consistent. Open edges that do not
/// close into loops (at non-manifold edges) are left out; invalid triangles are ignored.
pub fn boundary_loops(s: &TriSurface) -> Vec<Vec<u32>> {
    let m = Prepared::new(s);
    let et = EdgeTable::build(&m.tris, m.verts.len());
    walk(&m.tris, &et).loops
}
