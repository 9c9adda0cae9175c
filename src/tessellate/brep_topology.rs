//! What the B-rep's own topology says the certificate ([`super::certificate`]) must find in
//! a tessellation: each face's Euler characteristic and number of boundary loops, the pieces
//! of each vertex's link per shell group (pinches), and pairs of edges that coincide (a solid
//! touching itself along a line).

use crate::cad::brep::Model;
use crate::core::union_find::UnionFind;
use rustc_hash::FxHashMap;

/// The number of boundary loops the patch of face `f` should have (module docs): the pieces
/// that its trim loops' coedges make, joined where they share a vertex, once seams (used twice
/// by the face) and degenerate edges are dropped: runs of a loop cut by a seam join where they
/// meet (a cylinder's two circles stay two loops), and a loop that passes through a vertex
/// twice (a hole touching the outer boundary there), or two loops that touch at one, make
/// one, as the triangles' open edges do (`certificate::patch_loops`).
pub(super) fn expected_patch_loops(model: &Model, f: usize) -> usize {
    let face = &model.faces[f];
    let mut uses: FxHashMap<u32, u32> = FxHashMap::default();
    for &l in &face.loops {
        for c in &model.loops[l as usize].coedges {
            *uses.entry(c.edge).or_insert(0) += 1;
        }
    }
    let mut uf = UnionFind::new(model.vertices.len());
    let mut touched: Vec<u32> = Vec::new();
    for &l in &face.loops {
        for c in &model.loops[l as usize].coedges {
            let e = &model.edges[c.edge as usize];
            if e.degenerate || uses[&c.edge] >= 2 || e.start as usize >= model.vertices.len() || e.end as usize >= model.vertices.len() {
                continue;
            }
            uf.union(e.start, e.end);
            touched.extend([e.start, e.end]);
        }
    }
    let mut roots: Vec<u32> = touched.into_iter().map(|v| uf.find(v)).collect();
    roots.sort_unstable();
    roots.dedup();
    roots.len()
}

/// Per shell group and B-rep vertex with more than one, the number of pieces of the vertex's
/// link in the group: the corners of the group's face loops at the vertex, two of them joined
/// when they share an edge there. A vertex of a 2-manifold has one piece; where two sheets
/// touch at a point (a pinch), two. `group` is the group of each face.
pub(super) fn vertex_umbrellas(model: &Model, group: &[u32]) -> FxHashMap<(u32, u32), usize> {
    // corners: (group, vertex, edge in, edge out) where a loop passes through the vertex
    let mut corners: Vec<(u32, u32, u32, u32)> = Vec::new();
    for lp in &model.loops {
        let Some(&g) = lp.face.index().and_then(|f| group.get(f)) else { continue };
        let n = lp.coedges.len();
        for k in 0..n {
            let (c, d) = (&lp.coedges[k], &lp.coedges[(k + 1) % n]);
            let e = &model.edges[c.edge as usize];
            let v = if c.forward { e.end } else { e.start };
            corners.push((g, v, c.edge, d.edge));
        }
    }
    corners.sort_unstable();
    let mut out = FxHashMap::default();
    let mut i = 0;
    while i < corners.len() {
        let (g, v) = (corners[i].0, corners[i].1);
        let j = i + corners[i..].iter().take_while(|c| (c.0, c.1) == (g, v)).count();
        let at = &corners[i..j];
        if at.len() > 1 {
            let mut uf = crate::core::union_find::UnionFind::new(at.len());
            // corners sharing an edge at the vertex are one piece
            let mut by_edge: Vec<(u32, usize)> = at.iter().enumerate().flat_map(|(k, c)| [(c.2, k), (c.3, k)]).collect();
            by_edge.sort_unstable();
            for w in by_edge.windows(2) {
                if w[0].0 == w[1].0 {
                    uf.union(w[0].1 as u32, w[1].1 as u32);
                }
            }
            let pieces = (0..at.len() as u32).filter(|&k| uf.is_root(k)).count();
            if pieces > 1 {
                out.insert((g, v), pieces);
            }
        }
        i = j;
    }
    out
}

/// Pairs of B-rep edges between the same two vertices whose curves coincide (their middles
/// within `1e-6` of the model's size): the solid touches itself along a line there. The B-rep
/// allows it (OpenCASCADE reads such parts as valid); a closed 2-manifold surface cannot be
/// made of it, and its mesh has four triangles on a segment or two triangles crossing.
pub(super) fn coincident_edges(model: &Model) -> Vec<(usize, usize)> {
    let mut by_ends: std::collections::BTreeMap<(u32, u32), Vec<usize>> = std::collections::BTreeMap::new();
    for (i, e) in model.edges.iter().enumerate() {
        if e.start != e.end && e.curve.is_some() && !e.degenerate {
            by_ends.entry((e.start.min(e.end), e.start.max(e.end))).or_default().push(i);
        }
    }
    let middle = |i: usize| {
        let e = &model.edges[i];
        e.curve.map(|c| model.curve(c).point(0.5 * (e.range.min + e.range.max)))
    };
    let eps = 1e-6 * model.size();
    let mut out = Vec::new();
    for group in by_ends.values().filter(|g| g.len() >= 2) {
        for (k, &x) in group.iter().enumerate() {
            for &y in &group[k + 1..] {
                if let (Some(p), Some(q)) = (middle(x), middle(y)) {
                    if p.distance(q) <= eps {
                        out.push((x, y));
                    }
                }
            }
        }
    }
    out
}

/// The B-rep's own `χ_f` of face `f` (the certificate's module docs): 2 − 2g − its loops, the
/// genus 1 for a torus face without edge loops.
pub(super) fn face_euler(model: &Model, f: usize) -> i64 {
    let face = &model.faces[f];
    let loops = face.loops.len() as i64;
    let edge_loops = face.loops.iter().filter(|&&l| !model.loops[l as usize].coedges.is_empty()).count();
    let dom = model.surface(face.surface).domain();
    let genus = i64::from(edge_loops == 0 && dom.u_period.is_some() && dom.v_period.is_some());
    2 - 2 * genus - loops
}
