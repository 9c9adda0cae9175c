//! Keep-surface: the Steiner points that boundary recovery put on the surface are merged back
//! into their neighbours, so that the boundary is exactly the input triangles again.
//!
//! First the tets outside the material go (their faces on the boundary then face slot 0, the
//! scratch slot), so a boundary vertex's star is the material around it only. Then each
//! boundary Steiner point `v` is merged into a neighbour `w` along its segment or in its
//! facet (a half-edge collapse): tets holding both go, the others take `w` for `v`. A merge is
//! made only when
//! - every changed tet stays positively oriented (exact `orient3d`), which also keeps every
//!   boundary triangle non-degenerate, as each has a material tet on it;
//! - the link condition holds: the vertices and edges that the links of `v` and `w` share
//!   are exactly the link of the edge `vw` (so no tet, face or edge is doubled);
//! - `w` lies on `v`'s segment or facet, so the boundary keeps its shape.
//!
//! Among the neighbours allowed, the one whose new tets have the best worst shape is taken.
//! Passes repeat while they merge something; what is left is reported.

use crate::core::Sign;
use crate::core::ids::NONE;
use crate::mesh3d::delaunay::kernel::Kernel;
use crate::mesh3d::delaunay::store::{DEAD, GHOST};
use crate::mesh3d::mesher::carve::Labels;
use crate::mesh3d::mesher::surface_model::{Location, SurfaceModel};
use crate::mesh3d::mesher::tetra::Tetra;
use glam::DVec3;

/// Removes the tets outside the material (label 0) and the ghosts; faces that looked at them
/// look at slot 0 afterwards.
pub(crate) fn drop_exterior(tr: &mut Tetra, labels: &Labels) {
    let n = tr.tets.len();
    let gone = |tr: &Tetra, t: usize| -> bool {
        let v = tr.tets[t].v;
        v[0] == DEAD || v[3] == GHOST || labels.get(t as u32) == 0
    };
    let doomed: Vec<u32> = (1..n).filter(|&t| tr.tets[t].v[0] != DEAD && gone(tr, t)).map(|t| t as u32).collect();
    for t in 1..n {
        if gone(tr, t) {
            continue;
        }
        for f in 0..4 {
            let m = (tr.tets[t].n[f] >> 2) as usize;
            if gone(tr, m) {
                tr.tets[t].n[f] = 0;
            }
        }
    }
    for &t in &doomed {
        tr.free_slot(t);
    }
    // seen from outside, every face towards slot 0 is a wall (insertions read walls there)
    tr.walls[0] = 0b1111;
    for v in tr.vtet.iter_mut() {
        *v = NONE;
    }
    for t in 1..n {
        let w = tr.tets[t].v;
        if w[0] != DEAD {
            for x in w {
                tr.vtet[x as usize] = t as u32;
            }
        }
    }
}

/// Scale-free shape of a tet: its volume over the cube of its root-mean-square edge, 0 for
/// flat or inverted ones (the regular tet gives 1/(6√2)).
fn shape(p: [DVec3; 4]) -> f64 {
    let vol = (p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0])) / 6.0;
    let e2: f64 = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)].iter().map(|&(i, j)| p[i].distance_squared(p[j])).sum::<f64>() / 6.0;
    if vol <= 0.0 || e2 <= 0.0 { 0.0 } else { vol / (e2 * e2.sqrt()) }
}

/// The star of `v` in the material: tets holding it.
fn star(tr: &Tetra, v: u32, out: &mut Vec<u32>) {
    tr.star(v, out);
    out.retain(|&t| t != 0 && tr.tets[t as usize].v[0] != DEAD);
}

/// Checks merging `v` into `w`; returns the worst shape of the changed tets, or `None` when
/// the merge is not allowed.
fn check(tr: &Tetra, v: u32, w: u32, sv: &[u32], sw: &[u32]) -> Option<f64> {
    let mut worst = f64::INFINITY;
    let mut shared = false;
    let mut link_vw_vertices: Vec<u32> = Vec::new();
    let mut link_vw_edges: Vec<[u32; 2]> = Vec::new();
    for &t in sv {
        let q = tr.tets[t as usize].v;
        if q.contains(&w) {
            shared = true;
            let (iv, iw) = (q.iter().position(|&x| x == v)?, q.iter().position(|&x| x == w)?);
            if tr.tets[t as usize].n[iv] >> 2 == 0 && tr.tets[t as usize].n[iw] >> 2 == 0 {
                return None; // the material would pinch to nothing there
            }
            let o: Vec<u32> = q.iter().copied().filter(|&x| x != v && x != w).collect();
            for &x in &o {
                if !link_vw_vertices.contains(&x) {
                    link_vw_vertices.push(x);
                }
            }
            link_vw_edges.push([o[0].min(o[1]), o[0].max(o[1])]);
            continue;
        }
        let moved = q.map(|x| if x == v { w } else { x });
        if tr.k.orient(moved[0], moved[1], moved[2], moved[3]) != Sign::Positive {
            return None;
        }
        worst = worst.min(shape(moved.map(|x| tr.point(x))));
    }
    if !shared {
        return None; // vw is no edge
    }
    // vertex link condition
    let verts = |s: &[u32], c: u32| -> Vec<u32> {
        let mut o: Vec<u32> = s.iter().flat_map(|&t| tr.tets[t as usize].v).filter(|&x| x != c).collect();
        o.sort_unstable();
        o.dedup();
        o
    };
    let (nv, nw) = (verts(sv, v), verts(sw, w));
    let common = nv.iter().filter(|x| **x != w && nw.binary_search(x).is_ok()).count();
    if common != link_vw_vertices.len() {
        return None;
    }
    // edge link condition: edges of the faces opposite the centre
    let edges = |s: &[u32], c: u32| -> Vec<[u32; 2]> {
        let mut o = Vec::with_capacity(3 * s.len());
        for &t in s {
            let q = tr.tets[t as usize].v;
            let f: Vec<u32> = q.iter().copied().filter(|&x| x != c).collect();
            for (a, b) in [(f[0], f[1]), (f[1], f[2]), (f[0], f[2])] {
                o.push([a.min(b), a.max(b)]);
            }
        }
        o.sort_unstable();
        o.dedup();
        o
    };
    let (ev, ew) = (edges(sv, v), edges(sw, w));
    let common = ev.iter().filter(|e| !e.contains(&w) && ew.binary_search(e).is_ok()).count();
    link_vw_edges.sort_unstable();
    link_vw_edges.dedup();
    if common != link_vw_edges.len() {
        return None;
    }
    Some(worst)
}

/// Merges `v` into `w` in the tetrahedralization (checked by [`check`]).
fn apply(tr: &mut Tetra, v: u32, w: u32, sv: &[u32]) {
    // the tets holding both: glue their outer neighbours together
    for &t in sv {
        let q = tr.tets[t as usize].v;
        if !q.contains(&w) {
            continue;
        }
        let iv = q.iter().position(|&x| x == v).unwrap_or(0);
        let iw = q.iter().position(|&x| x == w).unwrap_or(0);
        let r1 = tr.tets[t as usize].n[iv]; // across the face without v
        let x1 = tr.tets[t as usize].n[iw]; // across the face without w: a tet that stays
        // the two faces become one, a wall if either was
        let wall = (tr.walls[t as usize] >> iv | tr.walls[t as usize] >> iw) & 1;
        for (a, b) in [(x1, r1), (r1, x1)] {
            let (at, af) = ((a >> 2) as usize, (a & 3) as usize);
            if at != 0 {
                tr.tets[at].n[af] = b;
                tr.walls[at] = (tr.walls[at] & !(1 << af)) | (wall << af);
            }
        }
    }
    for &t in sv {
        let q = tr.tets[t as usize].v;
        if q.contains(&w) {
            tr.free_slot(t);
        }
    }
    for &t in sv {
        let q = tr.tets[t as usize].v;
        if q[0] == DEAD {
            continue;
        }
        let moved = q.map(|x| if x == v { w } else { x });
        tr.tets[t as usize].v = moved;
        for x in moved {
            tr.vtet[x as usize] = t;
        }
    }
    tr.vtet[v as usize] = NONE;
}

/// Merges every boundary Steiner point it can; returns how many are left. With `no_worse`,
/// a point is merged only where its new tets are no worse shaped than its star was (when the
/// boundary may keep Steiner points, a merge is worth no bad tet).
pub(crate) fn keep_surface(tr: &mut Tetra, sm: &mut SurfaceModel, no_worse: bool) -> usize {
    let mut sv = Vec::new();
    let mut sw = Vec::new();
    loop {
        let mut merged = 0;
        let points: Vec<u32> =
            (0..sm.location.len() as u32).filter(|&v| matches!(sm.location[v as usize], Location::Segment(_) | Location::Facet(_))).collect();
        for v in points {
            star(tr, v, &mut sv);
            let floor = if no_worse { sv.iter().map(|&t| shape(tr.tets[t as usize].v.map(|x| tr.point(x)))).fold(f64::INFINITY, f64::min) } else { f64::NEG_INFINITY };
            let mut best: Option<(f64, u32)> = None;
            for w in sm.merge_targets(v) {
                star(tr, w, &mut sw);
                if let Some(q) = check(tr, v, w, &sv, &sw) {
                    if q >= floor && best.is_none_or(|b| q > b.0) {
                        best = Some((q, w));
                    }
                }
            }
            if let Some((_, w)) = best {
                apply(tr, v, w, &sv);
                sm.collapse(v, w);
                merged += 1;
            }
        }
        if merged == 0 {
            return sm.boundary_steiner_points();
        }
    }
}
