//! Which cut recursive subdivision makes next in a polygon: first from its most reflex
//! vertex (non-convex pieces are made convex first), then across the middle of its longest
//! axis (Bykat).
//!
//! - Inputs: the points and a polygon (weakly simple, counter-clockwise).
//! - Output: candidate cuts (pairs of positions), best first; `split::try_cut` takes the
//!   first valid one.
//! - Reflex phase: the vertex with the largest interior angle above 180° + [`REFLEX_SLACK`]
//!   (nodes on earlier cuts, at 180° up to rounding, do not count); candidates to every
//!   other vertex, scored by how far the cut strays from the angle's bisector (relative to
//!   the wedge in which both parts are convex at the vertex) and by length.
//! - Axis phase: the longest axis `AB` (the farthest point from vertex 0, then the farthest
//!   from that); the vertices nearest the line through its middle, perpendicular to it, on
//!   each side, and `A` and `B`; every pair of them scored by the smallest angle the cut
//!   makes at its ends (capped at 45°) less a penalty for the distance of its middle from
//!   the axis's middle. Deterministic: scores, then positions.

use glam::DVec2;
use std::f64::consts::PI;

/// Interior angles up to 180° plus this many degrees count as flat, not reflex.
pub(crate) const REFLEX_SLACK: f64 = 5.0;

/// Candidates nearest the middle line on each side of the axis.
const NEAR: usize = 4;

fn interior_angle(pts: &[DVec2], poly: &[u32], i: usize) -> f64 {
    let n = poly.len();
    let p = |i: usize| pts[poly[i] as usize];
    let (u, v) = (p((i + 1) % n) - p(i), p((i + n - 1) % n) - p(i));
    u.perp_dot(v).atan2(u.dot(v)).rem_euclid(2.0 * PI)
}

fn by_score(mut c: Vec<(f64, usize, usize)>) -> Vec<(usize, usize)> {
    c.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
    c.into_iter().map(|(_, x, y)| (x, y)).collect()
}

/// The reflex phase's candidates (see the module docs), empty when no vertex is reflex.
pub(crate) fn reflex_candidates(pts: &[DVec2], poly: &[u32]) -> Vec<(usize, usize)> {
    let n = poly.len();
    let slack = PI + REFLEX_SLACK.to_radians();
    let Some((r, theta)) = (0..n).map(|i| (i, interior_angle(pts, poly, i))).filter(|&(_, a)| a > slack).max_by(|a, b| a.1.total_cmp(&b.1).then(b.0.cmp(&a.0))) else {
        return Vec::new();
    };
    let p = |i: usize| pts[poly[i] as usize];
    let v = p(r);
    let e1 = (p((r + 1) % n) - v).normalize_or_zero();
    let bisector = DVec2::from_angle(theta / 2.0).rotate(e1);
    let wedge = (PI - theta / 2.0).max(1e-9);
    let (lo, hi) = pts_bounds(pts, poly);
    let diam = lo.distance(hi).max(f64::MIN_POSITIVE);
    let mut c = Vec::with_capacity(n);
    for j in 0..n {
        if j == r || j == (r + 1) % n || j == (r + n - 1) % n || poly[j] == poly[r] {
            continue;
        }
        let to = p(j) - v;
        let dev = bisector.perp_dot(to).atan2(bisector.dot(to)).abs();
        let mut score = dev / wedge + 0.5 * to.length() / diam;
        if dev >= wedge {
            score += 10.0; // leaves the vertex reflex on one side
        }
        c.push((score, r, j));
    }
    by_score(c)
}

fn pts_bounds(pts: &[DVec2], poly: &[u32]) -> (DVec2, DVec2) {
    let mut lo = DVec2::splat(f64::INFINITY);
    let mut hi = DVec2::splat(f64::NEG_INFINITY);
    for &v in poly {
        lo = lo.min(pts[v as usize]);
        hi = hi.max(pts[v as usize]);
    }
    (lo, hi)
}

/// The axis phase's candidates (see the module docs).
pub(crate) fn axis_candidates(pts: &[DVec2], poly: &[u32]) -> Vec<(usize, usize)> {
    let n = poly.len();
    let p = |i: usize| pts[poly[i] as usize];
    let far = |from: DVec2| (0..n).max_by(|&i, &j| from.distance_squared(p(i)).total_cmp(&from.distance_squared(p(j))).then(j.cmp(&i))).unwrap_or(0);
    let i0 = far(p(0));
    let i1 = far(p(i0));
    let (a, b) = (p(i0), p(i1));
    let len = a.distance(b).max(f64::MIN_POSITIVE);
    let u = (b - a) / len;
    let mid = (a + b) * 0.5;
    let s = |i: usize| (p(i) - mid).dot(u);
    let mut picks = vec![i0, i1];
    for chain in [(i0, i1), (i1, i0)] {
        let mut side: Vec<usize> = Vec::new();
        let mut j = (chain.0 + 1) % n;
        while j != chain.1 {
            side.push(j);
            j = (j + 1) % n;
        }
        side.sort_by(|&x, &y| s(x).abs().total_cmp(&s(y).abs()).then(x.cmp(&y)));
        picks.extend(side.into_iter().take(NEAR));
    }
    picks.sort_unstable();
    picks.dedup();
    let mut c = Vec::new();
    for (k, &x) in picks.iter().enumerate() {
        for &y in &picks[k + 1..] {
            if y - x < 2 || (x == 0 && y == n - 1) {
                continue;
            }
            let angle = super::split::cut_angle(pts, poly, x, y).min(45.0);
            let offset = ((p(x) + p(y)) * 0.5 - mid).dot(u).abs() / len;
            c.push((-(angle - 90.0 * offset), x, y));
        }
    }
    by_score(c)
}

/// Every pair of positions, by the smallest angle the cut makes (the last resort for small
/// polygons whose shortlisted cuts all failed).
pub(crate) fn all_candidates(pts: &[DVec2], poly: &[u32]) -> Vec<(usize, usize)> {
    let n = poly.len();
    let mut c = Vec::new();
    for x in 0..n {
        for y in x + 2..n {
            if x == 0 && y == n - 1 {
                continue;
            }
            c.push((-super::split::cut_angle(pts, poly, x, y), x, y));
        }
    }
    by_score(c)
}
