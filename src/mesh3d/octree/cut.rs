//! Signs, cut points and warping of isosurface stuffing (Labelle and Shewchuk 2007, section
//! 3): where the surface crosses the lattice edges, and which lattice vertices move onto it.
//!
//! Stage: between the lattice and the stencils. Input: the [`Lattice`], the [`Winding`]
//! oracle, the winding number at every lattice vertex, `α_long` and `α_short`. Output:
//! [`Cuts`]: the sign of every lattice vertex after warping (`-1` inside, `0` on the surface,
//! `+1` outside), its position (moved for warped vertices), and the surviving cut points.
//!
//! # Invariants
//! - A vertex is inside when its winding number is above one half. An edge whose ends have
//!   different signs gets exactly one cut point. It is found on the input surface where the
//!   surface is clean along the edge: the triangles the edge crosses, decided by exact
//!   predicates, none through a triangle's edge or vertex, walked from the inside end while
//!   the winding number (the inside end's, changed by ±1 at each crossing) stays above one
//!   half; the first crossing that takes it to one half or below is the cut. Where that does
//!   not explain the sign change (a hole of an open surface, where the winding number passes
//!   one half between triangles; a crossing through an edge or vertex; inconsistent
//!   orientation), the cut is found by bisecting the winding number along the edge to
//!   2⁻³⁰ of its length ([`Cuts::bisected`] counts them).
//! - Warping: a cut point closer to an end than `α` times the edge's length (`α_long` on long
//!   edges, `α_short` on short ones) *violates* that end. Every violated vertex moves to its
//!   nearest violating cut point (ties to the lower cut index) and its sign becomes 0; then the
//!   cut points of every edge with a warped end are dropped. All decisions are made on the
//!   cut points found before warping, so the result does not depend on any order.
//! - Everything is computed per vertex or per edge in parallel and collected in index
//!   order: the same input gives the same cuts for any number of threads.

use super::lattice::Lattice;
use crate::core::ids::NONE;
use super::winding::{INSIDE, Winding};
use glam::DVec3;
use rayon::prelude::*;
use rustc_hash::FxHashMap;

/// Lattice signs and cut points after warping; see the module docs.
#[derive(Clone, Debug, Default)]
pub struct Cuts {
    /// Per lattice vertex: -1 inside, 0 on the surface (warped), +1 outside.
    pub sign: Vec<i8>,
    /// Positions of the warped vertices (the others are at their lattice positions).
    pub warped: FxHashMap<u32, DVec3>,
    /// Surviving cut points: the edge `(a, b)`, `a < b`, and the point.
    pub edges: Vec<([u32; 2], DVec3)>,
    /// Index into `edges` by edge.
    pub index: FxHashMap<[u32; 2], u32>,
    /// Sign-changing edges before warping.
    pub crossing_edges: usize,
    /// Cut points found by bisection of the winding number (the others on input triangles).
    pub bisected: usize,
    /// Lattice vertices warped onto the surface.
    pub num_warped: usize,
}

impl Cuts {
    /// The position of lattice vertex `v` (after warping).
    pub fn position(&self, lattice: &Lattice, v: u32) -> DVec3 {
        self.warped.get(&v).copied().unwrap_or_else(|| lattice.position(v))
    }

    /// The surviving cut point on edge `{a, b}`.
    pub fn cut(&self, a: u32, b: u32) -> Option<u32> {
        self.index.get(&[a.min(b), a.max(b)]).copied()
    }
}

/// Signs from winding numbers `w`, cut points, warping; see the module docs.
pub fn cut_and_warp(lattice: &Lattice, oracle: &Winding, w: &[f64], alpha_long: f64, alpha_short: f64) -> Cuts {
    let n = lattice.num_vertices();
    let inside: Vec<bool> = w.iter().map(|&x| x > INSIDE).collect();
    // sign-changing edges, from the inside end, in vertex order
    let edges: Vec<(u32, u32, bool)> = (0..n as u32)
        .into_par_iter()
        .filter(|&v| inside[v as usize])
        .flat_map_iter(|v| lattice.neighbours(v).filter(|&(u, _)| !inside[u as usize]).map(move |(u, long)| (v, u, long)))
        .collect();
    // the cut point of each, as a parameter from the inside end
    let found: Vec<(f64, bool)> = edges
        .par_iter()
        .map(|&(a, b, _)| {
            let (pa, pb) = (lattice.position(a), lattice.position(b));
            match exact_cut(oracle, pa, pb, w[a as usize]) {
                Some(t) => (t, false),
                None => (bisect(oracle, pa, pb), true),
            }
        })
        .collect();
    // warping: the nearest violating cut point per vertex
    let mut best: FxHashMap<u32, (f64, u32)> = FxHashMap::default();
    for (k, (&(a, b, long), &(t, _))) in edges.iter().zip(&found).enumerate() {
        let alpha = if long { alpha_long } else { alpha_short };
        for (v, d) in [(a, t), (b, 1.0 - t)] {
            if d < alpha {
                let e = best.entry(v).or_insert((f64::INFINITY, NONE));
                if d < e.0 || (d == e.0 && (k as u32) < e.1) {
                    *e = (d, k as u32);
                }
            }
        }
    }
    let mut sign: Vec<i8> = inside.iter().map(|&i| if i { -1 } else { 1 }).collect();
    let point = |k: usize| {
        let (a, b, _) = edges[k];
        let (pa, pb) = (lattice.position(a), lattice.position(b));
        pa + found[k].0 * (pb - pa)
    };
    let mut warped = FxHashMap::default();
    for (&v, &(_, k)) in &best {
        sign[v as usize] = 0;
        warped.insert(v, point(k as usize));
    }
    let mut out = Cuts { crossing_edges: edges.len(), num_warped: warped.len(), ..Cuts::default() };
    for k in 0..edges.len() {
        let (a, b, _) = edges[k];
        if sign[a as usize] == 0 || sign[b as usize] == 0 {
            continue;
        }
        if found[k].1 {
            out.bisected += 1;
        }
        let key = [a.min(b), a.max(b)];
        out.index.insert(key, out.edges.len() as u32);
        out.edges.push((key, point(k)));
    }
    out.sign = sign;
    out.warped = warped;
    out
}

/// The cut on the input surface (parameter from `a`, inside, towards `b`), if the crossings
/// explain the sign change; see the module docs.
fn exact_cut(oracle: &Winding, a: DVec3, b: DVec3, wa: f64) -> Option<f64> {
    let crossings = oracle.crossings(a, b);
    if crossings.is_empty() || crossings.iter().any(|c| c.degenerate) {
        return None;
    }
    let mut w = wa;
    for c in &crossings {
        let next = w + c.jump as f64;
        if w > INSIDE && next <= INSIDE {
            return Some(c.t);
        }
        w = next;
    }
    None
}

/// The cut by bisection of the winding number on `a` (inside) – `b` (outside).
fn bisect(oracle: &Winding, a: DVec3, b: DVec3) -> f64 {
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    for _ in 0..30 {
        let mid = 0.5 * (lo + hi);
        if oracle.inside(a + mid * (b - a)) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}
