//! The initial constrained Delaunay triangulation of the domain's points and segments, and
//! the classification that keeps the domain.
//!
//! - Stage: first, after the domain is validated.
//! - Inputs: a valid [`Domain`].
//! - Output: a [`Tri`] whose triangles are exactly those left of the directed segments (flood
//!   fill from the segments' sides, never crossing a segment); the domain's points keep their
//!   indices; every segment is a constrained edge.
//! - How: spade's CDT (bulk loaded, order kept), converted into the triangle arrays; every
//!   triangle's orientation is checked again with fepre's exact predicate on the same
//!   coordinates (the domain's, with residue under the guard's flush made 0, as spade sees
//!   them; those are the output's points).

use super::tri::{next, prev, Tri, NONE};
use crate::core::cdt::{flush, point};
use glam::DVec2;
use crate::core::predicates::orient2d;
use crate::core::Sign;
use crate::mesh2d::Domain;
use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};

/// Triangulates `domain` and keeps its inside (see the module docs); the error says what
/// went wrong (an internal failure: the domain was validated).
pub(crate) fn build(domain: &Domain) -> Result<Tri, String> {
    let n = domain.points.len();
    // the points as spade sees them (residue under the guard's flush is 0), used throughout
    let pts: Vec<DVec2> = domain.points.iter().map(|p| DVec2::new(flush(p.x), flush(p.y))).collect();
    let mut guarded = Vec::with_capacity(n);
    for p in &pts {
        guarded.push(point(*p).ok_or_else(|| format!("point ({}, {}) is beyond the triangulation's range", p.x, p.y))?);
    }
    let edges: Vec<[usize; 2]> = domain.segments.iter().map(|s| [s[0] as usize, s[1] as usize]).collect();
    let mut conflict = None;
    let cdt: ConstrainedDelaunayTriangulation<Point2<f64>> =
        ConstrainedDelaunayTriangulation::try_bulk_load_cdt(guarded, edges, |e| conflict = conflict.or(Some(e))).map_err(|e| format!("spade: {e:?}"))?;
    if let Some(e) = conflict {
        return Err(format!("segments conflict at {e:?}"));
    }
    if cdt.num_vertices() != n {
        return Err("points merged by the triangulation".into());
    }
    // triangles, counter-clockwise, checked exactly on the domain's coordinates
    let mut tv: Vec<[u32; 3]> = Vec::with_capacity(cdt.num_inner_faces());
    for f in cdt.inner_faces() {
        let v = f.vertices().map(|h| h.fix().index() as u32);
        let p = v.map(|i| pts[i as usize]);
        if orient2d(p[0], p[1], p[2]) != Sign::Positive {
            return Err(format!("triangle {v:?} of the initial triangulation is not positive"));
        }
        tv.push(v);
    }
    // neighbours by sorted edges
    let mut edges: Vec<(u32, u32, u32, u8)> = Vec::with_capacity(3 * tv.len());
    for (t, v) in tv.iter().enumerate() {
        for i in 0..3 {
            let (a, b) = (v[next(i)], v[prev(i)]);
            edges.push((a.min(b), a.max(b), t as u32, i as u8));
        }
    }
    edges.sort_unstable();
    let mut tn = vec![[NONE; 3]; tv.len()];
    for w in edges.windows(2) {
        if w[0].0 == w[1].0 && w[0].1 == w[1].1 {
            tn[w[0].2 as usize][w[0].3 as usize] = w[1].2;
            tn[w[1].2 as usize][w[1].3 as usize] = w[0].2;
        }
    }
    // segment sides: a triangle having segment a -> b as its edge a -> b is inside
    let mut segs: Vec<(u32, u32)> = domain.segments.iter().map(|s| (s[0], s[1])).collect();
    segs.sort_unstable();
    let directed = |a: u32, b: u32| segs.binary_search(&(a, b)).is_ok();
    let mut cons = vec![0u8; tv.len()];
    let mut state = vec![0u8; tv.len()]; // 0 unknown, 1 inside, 2 outside seed
    let mut stack = Vec::new();
    for (t, v) in tv.iter().enumerate() {
        for i in 0..3 {
            let (a, b) = (v[next(i)], v[prev(i)]);
            if directed(a, b) {
                cons[t] |= 1 << i;
                if state[t] == 2 {
                    return Err(format!("triangle {v:?} lies on both sides of the boundary"));
                }
                if state[t] == 0 {
                    state[t] = 1;
                    stack.push(t as u32);
                }
            } else if directed(b, a) {
                cons[t] |= 1 << i;
                if state[t] == 1 {
                    return Err(format!("triangle {v:?} lies on both sides of the boundary"));
                }
                state[t] = 2;
            }
        }
    }
    while let Some(t) = stack.pop() {
        for i in 0..3 {
            let nb = tn[t as usize][i];
            if nb == NONE || cons[t as usize] & (1 << i) != 0 {
                continue;
            }
            match state[nb as usize] {
                0 => {
                    state[nb as usize] = 1;
                    stack.push(nb);
                }
                2 => return Err(format!("the inside reaches triangle {:?} outside", tv[nb as usize])),
                _ => {}
            }
        }
    }
    // keep the inside, renumbered
    let mut new_id = vec![NONE; tv.len()];
    let mut k = 0u32;
    for t in 0..tv.len() {
        if state[t] == 1 {
            new_id[t] = k;
            k += 1;
        }
    }
    let mut tri = Tri { pts, on_seg: vec![NONE; n], vtri: vec![NONE; n], inputs: n, ..Tri::default() };
    for t in 0..tv.len() {
        if state[t] != 1 {
            continue;
        }
        let nbs = tn[t].map(|nb| if nb == NONE { NONE } else { new_id[nb as usize] });
        for i in 0..3 {
            if nbs[i] == NONE && cons[t] & (1 << i) == 0 {
                return Err(format!("triangle {:?} has a boundary edge that is no segment", tv[t]));
            }
        }
        for &v in &tv[t] {
            tri.vtri[v as usize] = new_id[t];
        }
        tri.tv.push(tv[t]);
        tri.tn.push(nbs);
        tri.cons.push(cons[t]);
    }
    if let Some(v) = tri.vtri.iter().position(|&t| t == NONE) {
        return Err(format!("point {v} is in no triangle of the domain"));
    }
    Ok(tri)
}
