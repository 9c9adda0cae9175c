//! One cut of recursive subdivision: nodes placed on it by the size field, its exact
//! validity check, and the two polygons it leaves.
//!
//! - Inputs: a polygon (a weakly simple cycle of point indices, counter-clockwise), two of
//!   its positions, the size.
//! - Output: [`Cut`]: the nodes added on the cut and the two polygons, or `None` when the
//!   cut is not a diagonal of the polygon.
//! - Invariants: a cut is taken only when it leaves both ends strictly into the polygon
//!   (exact cone tests) and none of its pieces (between consecutive nodes) meets an edge of
//!   the polygon except at the cut's own ends (exact crossing tests), so both parts are
//!   weakly simple, counter-clockwise, and tile the polygon.

use crate::mesh2d::boundary::{divide_sampled, SizeError};
use crate::mesh2d::ear::{blocked, in_cone};
use glam::DVec2;

/// Samples of `1/h` along a cut for its node count and placement.
const SAMPLES: usize = 16;

/// The interior nodes of a cut from `a` to `b`: the rounded integral of `1/h` along it gives
/// the pieces (at least one), the nodes where the integral reaches its equal parts.
pub(crate) fn cut_nodes(a: DVec2, b: DVec2, size: &dyn Fn(DVec2) -> f64) -> Result<Vec<DVec2>, SizeError> {
    Ok(divide_sampled(a, b, size, SAMPLES)?.into_iter().map(|t| a.lerp(b, t)).collect())
}

/// A cut made: the two polygons it leaves.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Cut {
    /// The polygon from the cut's first end along the boundary to its second, back by the cut.
    pub left: Vec<u32>,
    /// The rest.
    pub right: Vec<u32>,
    /// Nodes added on the cut.
    pub nodes: usize,
}

/// The smallest of the four angles a cut from position `x` to `y` makes with the polygon's
/// edges at its ends, degrees (by floating point: a criterion, not a check).
pub(crate) fn cut_angle(pts: &[DVec2], poly: &[u32], x: usize, y: usize) -> f64 {
    let n = poly.len();
    let p = |i: usize| pts[poly[i] as usize];
    let ang = |u: DVec2, v: DVec2| u.perp_dot(v).atan2(u.dot(v)).to_degrees().rem_euclid(360.0);
    let mut best = f64::INFINITY;
    for (s, t) in [(x, y), (y, x)] {
        let (v, prev, next) = (p(s), p((s + n - 1) % n), p((s + 1) % n));
        let to = p(t) - v;
        // the interior angle is counter-clockwise from next to prev; the cut splits it
        let a1 = ang(next - v, to);
        let a2 = ang(to, prev - v);
        best = best.min(a1).min(a2);
    }
    best
}

/// Tries the cut between positions `x` and `y` of `poly` (see the module docs); the nodes
/// are appended to `pts` only when it is taken.
///
/// # Errors
/// [`SizeError`] where the size along the cut is not positive and finite.
pub(crate) fn try_cut(pts: &mut Vec<DVec2>, poly: &[u32], x: usize, y: usize, size: &dyn Fn(DVec2) -> f64) -> Result<Option<Cut>, SizeError> {
    let n = poly.len();
    let (x, y) = (x.min(y), x.max(y));
    if y - x < 2 || (x == 0 && y == n - 1) || poly[x] == poly[y] {
        return Ok(None);
    }
    let (a, b) = (poly[x], poly[y]);
    let (pa, pb) = (pts[a as usize], pts[b as usize]);
    let nodes = cut_nodes(pa, pb, size)?;
    let first = nodes.first().copied().unwrap_or(pb);
    let last = nodes.last().copied().unwrap_or(pa);
    let p = |i: usize| pts[poly[i] as usize];
    if !in_cone(p((x + n - 1) % n), pa, p(x + 1), first) || !in_cone(p(y - 1), pb, p((y + 1) % n), last) {
        return Ok(None);
    }
    let base = pts.len() as u32;
    pts.extend_from_slice(&nodes);
    let chain: Vec<u32> = std::iter::once(a).chain(base..base + nodes.len() as u32).chain(std::iter::once(b)).collect();
    if chain.windows(2).any(|w| blocked(pts, poly, w[0], w[1])) {
        pts.truncate(base as usize);
        return Ok(None);
    }
    let inner = &chain[1..chain.len() - 1];
    let mut left: Vec<u32> = poly[x..=y].to_vec();
    left.extend(inner.iter().rev());
    let mut right: Vec<u32> = poly[y..].to_vec();
    right.extend_from_slice(&poly[..=x]);
    right.extend_from_slice(inner);
    Ok(Some(Cut { left, right, nodes: nodes.len() }))
}
