//! The split to all quadrilaterals: every quad of a pair into 4, every leftover triangle
//! into 3, at half the size.
//!
//! - Stage: third, after the matching.
//! - Inputs: the triangle mesh and its [`Matching`].
//! - Output: [`Split`]: a mesh of quads only, the vertices that may not move, and the
//!   boundary edges' midpoints.
//! - Invariants: input vertex `i` is output vertex `i`; then the midpoints of the edges that
//!   survive (every triangle edge but the pairs' diagonals), in sorted edge order; then the
//!   centres of the pairs' quads and the centroids of the leftovers, in that order. A quad
//!   `a b c d` becomes `a m_ab o m_da`, ... around its vertex centroid `o` (the centre of
//!   its Varignon parallelogram, so the four are convex when the quad is); a triangle
//!   `a b c` becomes `a m_ab g m_ca`, ... around its centroid `g`. Neighbours share the
//!   midpoint of their common edge, so the quads conform.

use super::matching::Matching;
use crate::core::RegionId;
use crate::mesh::PlanarMesh;

/// The all-quad mesh before smoothing.
#[derive(Clone, Debug)]
pub struct Split {
    /// Quads only.
    pub mesh: PlanarMesh,
    /// Per vertex: on the boundary (input boundary vertices and boundary midpoints).
    pub fixed: Vec<bool>,
    /// Boundary midpoints `(vertex, [input edge ends])`, by vertex.
    pub midpoints: Vec<(u32, [u32; 2])>,
}

/// Splits the pairs and the leftovers of `tris` (see the module docs).
pub fn split(tris: &PlanarMesh, m: &Matching, region: RegionId) -> Split {
    let n = tris.vertices.len();
    let mut diagonals: Vec<[u32; 2]> = m.pairs.iter().map(|(_, q)| [q[0].min(q[2]), q[0].max(q[2])]).collect();
    diagonals.sort_unstable();
    // every edge with its number of triangles
    let mut all: Vec<[u32; 2]> = tris.triangles.iter().flat_map(|t| (0..3).map(move |k| [t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3])])).collect();
    all.sort_unstable();
    let mut edges: Vec<[u32; 2]> = Vec::with_capacity(all.len() / 2 + 1);
    let mut boundary: Vec<bool> = Vec::with_capacity(all.len() / 2 + 1);
    let mut i = 0;
    while i < all.len() {
        let single = i + 1 >= all.len() || all[i + 1] != all[i];
        if diagonals.binary_search(&all[i]).is_err() {
            edges.push(all[i]);
            boundary.push(single);
        }
        i += if single { 1 } else { 2 };
    }
    let mut vertices = tris.vertices.clone();
    let mut fixed = vec![false; n];
    let mut midpoints = Vec::new();
    for (k, e) in edges.iter().enumerate() {
        let id = vertices.len() as u32;
        vertices.push(0.5 * (tris.vertices[e[0] as usize] + tris.vertices[e[1] as usize]));
        fixed.push(boundary[k]);
        if boundary[k] {
            fixed[e[0] as usize] = true;
            fixed[e[1] as usize] = true;
            midpoints.push((id, *e));
        }
    }
    let mid = |a: u32, b: u32| -> u32 {
        let key = [a.min(b), a.max(b)];
        // every non-diagonal edge is listed
        (n + edges.binary_search(&key).unwrap_or(0)) as u32
    };
    let mut quads: Vec<[u32; 4]> = Vec::with_capacity(4 * m.pairs.len() + 3 * m.leftovers.len());
    for (_, q) in &m.pairs {
        let o = vertices.len() as u32;
        vertices.push(q.iter().map(|&v| tris.vertices[v as usize]).sum::<glam::DVec2>() * 0.25);
        fixed.push(false);
        for k in 0..4 {
            let (prev, cur, next) = (q[(k + 3) % 4], q[k], q[(k + 1) % 4]);
            quads.push([cur, mid(cur, next), o, mid(prev, cur)]);
        }
    }
    for &t in &m.leftovers {
        let tri = tris.triangles[t as usize];
        let g = vertices.len() as u32;
        vertices.push(tri.iter().map(|&v| tris.vertices[v as usize]).sum::<glam::DVec2>() / 3.0);
        fixed.push(false);
        for k in 0..3 {
            let (prev, cur, next) = (tri[(k + 2) % 3], tri[k], tri[(k + 1) % 3]);
            quads.push([cur, mid(cur, next), g, mid(prev, cur)]);
        }
    }
    let mesh = PlanarMesh { vertices, triangles: Vec::new(), triangle_tags: Vec::new(), quad_tags: vec![region; quads.len()], quads, region_names: Default::default() };
    Split { mesh, fixed, midpoints }
}
