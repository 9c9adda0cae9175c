//! The cap that closes any triangle surface into a cycle, so that the winding number of an
//! open, holed or inconsistently oriented surface can be counted along rows too.
//!
//! Stage: beside `rows.rs`, for the oracles of `winding_volume.rs` and the lattice. Input: a
//! [`TriSurface`]. Output: [`Capped`], the cap `C` and the union `S ∪ C`.
//!
//! # Invariants
//! - The boundary of `S` as a chain: each edge `a → b` with multiplicity (uses `a → b`) minus
//!   (uses `b → a`); a cycle (closed, consistently oriented) has none. The chain is itself a
//!   closed 1-cycle (every vertex has as much chain entering as leaving), and so is its part
//!   on each connected component of its edges.
//! - `C` is the cone over the reversed chain from one apex per component (the mean of the
//!   component's vertices): a chain edge `a → b` gives the triangle `(b, a, apex)`. Its
//!   spokes cancel (in- and out-degree agree at every vertex), so `∂C = -∂S` and `S ∪ C` is a
//!   cycle: its winding number is an integer off it, counted exactly along rows
//!   (`rows.rs`).
//! - Off both, `w_S(q) = w_{S∪C}(q) - w_C(q)` exactly (solid angles add), whatever `C`'s shape
//!   (it may cross `S` or itself); `C` has one triangle per boundary edge, so its solid angle
//!   is cheap where `S` has many triangles.
//! - Deterministic: edges sorted, components and apexes in that order.

use crate::core::ids::FaceId;
use crate::core::union_find::UnionFind;
use crate::mesh::TriSurface;
use glam::DVec3;

/// A surface's cap and the cycle it closes; see the module docs.
#[derive(Clone, Debug)]
pub struct Capped {
    /// `C`: one triangle per boundary edge (its multiplicity counted), tag 0.
    pub cap: TriSurface,
    /// `S ∪ C`: `S`'s vertices and triangles, then the apexes and the cap's triangles.
    pub union: TriSurface,
}

/// The boundary chain of `s`: `(a, b, m)` for the edge `a → b` with multiplicity `m > 0`,
/// sorted; empty for a cycle.
pub fn boundary_chain(s: &TriSurface) -> Vec<(u32, u32, u32)> {
    let mut edges: Vec<(u32, u32, i64)> = Vec::with_capacity(3 * s.triangles.len());
    for t in &s.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            if a != b {
                edges.push(if a < b { (a, b, 1) } else { (b, a, -1) });
            }
        }
    }
    edges.sort_unstable();
    let mut chain = Vec::new();
    let mut i = 0;
    while i < edges.len() {
        let (a, b) = (edges[i].0, edges[i].1);
        let mut net = 0;
        while i < edges.len() && (edges[i].0, edges[i].1) == (a, b) {
            net += edges[i].2;
            i += 1;
        }
        match net.cmp(&0) {
            std::cmp::Ordering::Greater => chain.push((a, b, net as u32)),
            std::cmp::Ordering::Less => chain.push((b, a, (-net) as u32)),
            std::cmp::Ordering::Equal => {}
        }
    }
    chain.sort_unstable();
    chain
}

/// The cap of `s` and the cycle `s ∪ cap`; `None` when `s` is a cycle already.
pub fn capped(s: &TriSurface) -> Option<Capped> {
    let chain = boundary_chain(s);
    if chain.is_empty() {
        return None;
    }
    // components of the chain's edges, by union-find over their vertices
    let mut verts: Vec<u32> = chain.iter().flat_map(|&(a, b, _)| [a, b]).collect();
    verts.sort_unstable();
    verts.dedup();
    let slot = |v: u32| verts.binary_search(&v).expect("a chain vertex");
    let mut uf = UnionFind::new(verts.len());
    for &(a, b, _) in &chain {
        uf.union(slot(a) as u32, slot(b) as u32);
    }
    // one apex per component, numbered in the order of their smallest vertex
    let mut apex_of = vec![usize::MAX; verts.len()];
    let mut sums: Vec<(DVec3, usize)> = Vec::new();
    for (i, &v) in verts.iter().enumerate() {
        let r = uf.find(i as u32) as usize;
        if apex_of[r] == usize::MAX {
            apex_of[r] = sums.len();
            sums.push((DVec3::ZERO, 0));
        }
        let k = apex_of[r];
        sums[k].0 += s.vertices[v as usize];
        sums[k].1 += 1;
    }
    let apexes: Vec<DVec3> = sums.iter().map(|&(p, n)| p / n as f64).collect();
    // the cap on its own: the chain's vertices then the apexes
    let n_chain = verts.len() as u32;
    let mut cap = TriSurface { vertices: verts.iter().map(|&v| s.vertices[v as usize]).collect(), ..Default::default() };
    cap.vertices.extend(&apexes);
    let mut union = s.clone();
    let n_s = s.vertices.len() as u32;
    union.vertices.extend(&apexes);
    for &(a, b, m) in &chain {
        let k = apex_of[uf.find(slot(a) as u32) as usize] as u32;
        for _ in 0..m {
            cap.triangles.push([slot(b) as u32, slot(a) as u32, n_chain + k]);
            union.triangles.push([b, a, n_s + k]);
        }
    }
    cap.face_tags = vec![FaceId(0); cap.triangles.len()];
    union.face_tags.extend(std::iter::repeat_n(FaceId(0), cap.triangles.len()));
    Some(Capped { cap, union })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh3d::octree::rows::is_cycle;
    use crate::mesh3d::octree::tests::cube_surface;
    use crate::mesh3d::octree::winding::Winding;

    /// A cube with two holes and one face flipped: its cap closes it into a cycle, and the
    /// winding numbers of the union less the cap's are the surface's own.
    #[test]
    fn the_cap_closes_any_surface_into_a_cycle() {
        let cube = cube_surface(4);
        assert!(capped(&cube).is_none());
        let mut s = cube.clone();
        s.triangles.remove(40);
        s.triangles.remove(7);
        s.triangles[20].swap(0, 1);
        s.face_tags.truncate(s.triangles.len());
        assert!(!is_cycle(&s));
        let c = capped(&s).unwrap();
        assert!(is_cycle(&c.union), "the union is a cycle");
        assert_eq!(c.cap.triangles.len(), boundary_chain(&s).iter().map(|e| e.2 as usize).sum::<usize>());
        let (ws, wu, wc) = (Winding::new(&s), Winding::new(&c.union), Winding::new(&c.cap));
        for q in [DVec3::splat(0.5), DVec3::new(0.2, 0.7, 0.4), DVec3::splat(2.0), DVec3::new(0.5, 0.5, 1.1)] {
            let (a, b) = (ws.at_with(q, f64::INFINITY), wu.at_with(q, f64::INFINITY) - wc.at_with(q, f64::INFINITY));
            assert!((a - b).abs() < 1e-9, "{q}: {a} {b}");
            assert!((wu.at_with(q, f64::INFINITY) - wu.at_with(q, f64::INFINITY).round()).abs() < 1e-9);
        }
    }
}
