//! The edge table: every edge of a triangle list with the triangles that use it.
//!
//! Input: triangles with distinct in-range indices. Output: [`EdgeTable`], the distinct
//! edges `(lo, hi)` (`lo < hi`) in increasing order, each with its *half-edges* (triangle and
//! local edge) in increasing triangle order, in flat arrays (CSR). Built by a counting sort on
//! the smaller vertex and a sort of each (small) bucket: linear time, no hash map.

use super::Prepared;
use crate::mesh::TriSurface;

/// One use of an edge by a triangle: the edge `tris[tri][k] -> tris[tri][(k + 1) % 3]`.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) struct Half {
    /// The larger vertex of the edge (sort key within a bucket).
    hi: u32,
    /// The triangle.
    pub tri: u32,
    /// The local edge, 0..3.
    pub k: u8,
}

/// Distinct edges and their half-edges; see the module docs.
pub(crate) struct EdgeTable {
    /// `(lo, hi)` per edge, increasing.
    pub edges: Vec<[u32; 2]>,
    /// Half-edges of edge `e` are `half[start[e]..start[e + 1]]`.
    start: Vec<usize>,
    half: Vec<Half>,
}

impl EdgeTable {
    /// Builds the table of `tris` over `nv` vertices (indices must be `< nv`).
    pub fn build(tris: &[[u32; 3]], nv: usize) -> EdgeTable {
        let mut off = vec![0usize; nv + 1];
        for t in tris {
            for k in 0..3 {
                off[t[k].min(t[(k + 1) % 3]) as usize + 1] += 1;
            }
        }
        for v in 0..nv {
            off[v + 1] += off[v];
        }
        let mut cursor = off.clone();
        let mut half = vec![Half::default(); 3 * tris.len()];
        for (ti, t) in tris.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                let slot = &mut cursor[a.min(b) as usize];
                half[*slot] = Half { hi: a.max(b), tri: ti as u32, k: k as u8 };
                *slot += 1;
            }
        }
        let mut edges = Vec::with_capacity(half.len() / 2 + 1);
        let mut start = Vec::with_capacity(half.len() / 2 + 2);
        for lo in 0..nv {
            let bucket = &mut half[off[lo]..off[lo + 1]];
            if bucket.len() > 1 {
                bucket.sort_unstable();
            }
            for (i, h) in bucket.iter().enumerate() {
                if i == 0 || bucket[i - 1].hi != h.hi {
                    edges.push([lo as u32, h.hi]);
                    start.push(off[lo] + i);
                }
            }
        }
        start.push(half.len());
        EdgeTable { edges, start, half }
    }

    /// Number of distinct edges.
    pub fn len(&self) -> usize {
        self.edges.len()
    }

    /// The half-edges of edge `e`.
    #[inline]
    pub fn halves(&self, e: usize) -> &[Half] {
        &self.half[self.start[e]..self.start[e + 1]]
    }

    /// Number of triangles on edge `e`.
    #[inline]
    pub fn valence(&self, e: usize) -> usize {
        self.start[e + 1] - self.start[e]
    }

    /// True if the edge's triangles traverse it as often in each direction (always true for
    /// an open edge).
    pub fn consistent(&self, tris: &[[u32; 3]], e: usize) -> bool {
        let h = self.halves(e);
        if h.len() == 1 {
            return true;
        }
        let forward = h.iter().filter(|x| forward(tris, x)).count();
        2 * forward == h.len()
    }
}

/// True if the half-edge runs from the smaller to the larger vertex.
#[inline]
pub(crate) fn forward(tris: &[[u32; 3]], h: &Half) -> bool {
    let t = tris[h.tri as usize];
    t[h.k as usize] < t[(h.k as usize + 1) % 3]
}

/// The ends of a half-edge in its triangle's direction.
#[inline]
pub(crate) fn ends(tris: &[[u32; 3]], h: &Half) -> (u32, u32) {
    let t = tris[h.tri as usize];
    (t[h.k as usize], t[(h.k as usize + 1) % 3])
}

fn edges_with(s: &TriSurface, keep: impl Fn(usize) -> bool) -> Vec<[u32; 2]> {
    let m = Prepared::new(s);
    let et = EdgeTable::build(&m.tris, m.verts.len());
    (0..et.len()).filter(|&e| keep(et.valence(e))).map(|e| et.edges[e]).collect()
}

/// The open edges (used by one triangle) as `[lo, hi]` vertex pairs, increasing. Invalid
/// triangles (index out of range or repeated) are ignored.
pub fn open_edges_list(s: &TriSurface) -> Vec<[u32; 2]> {
    edges_with(s, |n| n == 1)
}

/// The non-manifold edges (used by more than two triangles) as `[lo, hi]` vertex pairs,
/// increasing. Invalid triangles are ignored.
pub fn nonmanifold_edges_list(s: &TriSurface) -> Vec<[u32; 2]> {
    edges_with(s, |n| n > 2)
}
