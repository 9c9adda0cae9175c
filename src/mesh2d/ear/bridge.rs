//! Loops of a domain, grouped into components (an outer loop and its holes), and holes
//! bridged into their outer loop: the first stage of ear cutting, shared with recursive
//! subdivision.
//!
//! - Inputs: a valid [`Domain`].
//! - Output: [`components`]: per outer loop (counter-clockwise; islands inside holes are
//!   outer loops of their own) its holes (clockwise), as cycles of point indices;
//!   [`bridge`]: one weakly simple cycle per component, each hole joined to the cycle by a
//!   bridge traversed both ways (its two end points appear twice).
//! - Invariants: a bridge joins two mutually visible points: it crosses and touches no
//!   boundary edge but at its ends, and leaves both ends into the domain (exact [`orient2d`]
//!   cone and crossing tests). Deterministic: holes in order of their rightmost point, the
//!   bridge to the nearest visible point of the cycle (ties by index).

use crate::core::predicates::orient2d;
use crate::core::Sign;
use crate::mesh2d::domain::{segments_intersect, Domain};
use glam::DVec2;

/// Why the loops could not be grouped or bridged.
#[derive(Clone, Debug, PartialEq, thiserror::Error, serde::Serialize)]
#[non_exhaustive]
pub enum LoopError {
    /// Two boundary loops share a point (loops must be disjoint).
    #[error("point {0} is on two boundary loops (or a loop passes it twice): separate the loops")]
    TouchingLoops(u32),
    /// A hole lies inside no outer loop.
    #[error("the hole through point {0} lies inside no outer loop")]
    HoleOutside(u32),
    /// No point of the outer loop is visible from the hole.
    #[error("no bridge from the hole through point {0} to its outer loop is free of the boundary")]
    NoBridge(u32),
}

/// An outer loop and the holes inside it, as cycles of point indices (domain on the left).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Component {
    /// Counter-clockwise.
    pub outer: Vec<u32>,
    /// Clockwise, each inside `outer` and inside no other outer loop inside `outer`.
    pub holes: Vec<Vec<u32>>,
}

fn signed_area(points: &[DVec2], cycle: &[u32]) -> f64 {
    let n = cycle.len();
    (0..n).map(|k| points[cycle[k] as usize].perp_dot(points[cycle[(k + 1) % n] as usize])).sum::<f64>() * 0.5
}

/// Whether `p` is inside the closed loop `cycle` (exact crossing parity).
pub(crate) fn inside_cycle(points: &[DVec2], cycle: &[u32], p: DVec2) -> bool {
    let n = cycle.len();
    let mut inside = false;
    for k in 0..n {
        let (a, b) = (points[cycle[k] as usize], points[cycle[(k + 1) % n] as usize]);
        if (a.y > p.y) != (b.y > p.y) {
            let o = if b.y > a.y { orient2d(a, b, p) } else { orient2d(b, a, p) };
            if o == Sign::Positive {
                inside = !inside;
            }
        }
    }
    inside
}

/// The domain's loops grouped into components (see the module docs).
///
/// # Errors
/// [`LoopError::TouchingLoops`] where a point starts two segments, [`LoopError::HoleOutside`]
/// for a clockwise loop inside no counter-clockwise one.
pub(crate) fn components(domain: &Domain) -> Result<Vec<Component>, LoopError> {
    let n = domain.points.len();
    let mut next = vec![u32::MAX; n];
    for &[a, b] in &domain.segments {
        if next[a as usize] != u32::MAX {
            return Err(LoopError::TouchingLoops(a));
        }
        next[a as usize] = b;
    }
    let mut seen = vec![false; n];
    let mut loops: Vec<(Vec<u32>, f64)> = Vec::new();
    for &[start, _] in &domain.segments {
        if seen[start as usize] {
            continue;
        }
        let mut cycle = Vec::new();
        let mut v = start;
        while !seen[v as usize] {
            seen[v as usize] = true;
            cycle.push(v);
            v = next[v as usize];
        }
        if v != start {
            return Err(LoopError::TouchingLoops(v));
        }
        let area = signed_area(&domain.points, &cycle);
        loops.push((cycle, area));
    }
    let mut out: Vec<Component> = Vec::new();
    let mut outer_of_loop = vec![usize::MAX; loops.len()];
    for (l, (cycle, area)) in loops.iter().enumerate() {
        if *area > 0.0 {
            outer_of_loop[l] = out.len();
            out.push(Component { outer: cycle.clone(), holes: Vec::new() });
        }
    }
    for (cycle, area) in &loops {
        if *area > 0.0 {
            continue;
        }
        let probe = domain.points[cycle[0] as usize];
        let host = loops.iter().enumerate().filter(|(_, (c, a))| *a > 0.0 && inside_cycle(&domain.points, c, probe)).min_by(|x, y| x.1 .1.total_cmp(&y.1 .1).then(x.0.cmp(&y.0)));
        match host {
            Some((l, _)) => out[outer_of_loop[l]].holes.push(cycle.clone()),
            None => return Err(LoopError::HoleOutside(cycle[0])),
        }
    }
    Ok(out)
}

/// Whether the segment from the vertex `v` (with neighbours `prev`, `next` on its cycle,
/// the domain on the left) towards `p` starts into the domain (strictly inside its wedge).
pub(crate) fn in_cone(prev: DVec2, v: DVec2, next: DVec2, p: DVec2) -> bool {
    let left_in = orient2d(prev, v, p) == Sign::Positive;
    let left_out = orient2d(v, next, p) == Sign::Positive;
    if orient2d(prev, v, next) == Sign::Positive {
        left_in && left_out
    } else {
        left_in || left_out
    }
}

/// Whether the segment `a`–`b` (point indices) meets any edge of `cycle` other than at `a`
/// or `b` themselves (exact). Edges sharing one end with it block it only when they overlap.
pub(crate) fn blocked(points: &[DVec2], cycle: &[u32], a: u32, b: u32) -> bool {
    let (pa, pb) = (points[a as usize], points[b as usize]);
    let n = cycle.len();
    for k in 0..n {
        let (u, w) = (cycle[k], cycle[(k + 1) % n]);
        let shares = [u == a || u == b, w == a || w == b];
        let (pu, pw) = (points[u as usize], points[w as usize]);
        match shares {
            [true, true] => {}
            [true, false] | [false, true] => {
                let other = if shares[0] { pw } else { pu };
                let on = orient2d(pa, pb, other) == Sign::Zero && (other - pa).dot(other - pb) <= 0.0;
                if on {
                    return true;
                }
            }
            [false, false] => {
                if segments_intersect(pa, pb, pu, pw) {
                    return true;
                }
            }
        }
    }
    false
}

/// Joins the holes to the outer loop by bridges (see the module docs); returns the cycle and
/// the number of bridges.
///
/// # Errors
/// [`LoopError::NoBridge`] when no point of the cycle is visible from a hole's rightmost
/// point (not expected for a valid domain: reported, never meshed badly).
pub(crate) fn bridge(points: &[DVec2], component: &Component) -> Result<(Vec<u32>, usize), LoopError> {
    let p = |i: u32| points[i as usize];
    let rightmost = |h: &Vec<u32>| (0..h.len()).max_by(|&i, &j| p(h[i]).x.total_cmp(&p(h[j]).x).then(p(h[i]).y.total_cmp(&p(h[j]).y)).then(h[j].cmp(&h[i]))).unwrap_or(0);
    let mut order: Vec<usize> = (0..component.holes.len()).collect();
    let key = |h: usize| p(component.holes[h][rightmost(&component.holes[h])]);
    order.sort_by(|&i, &j| key(j).x.total_cmp(&key(i).x).then(key(j).y.total_cmp(&key(i).y)).then(i.cmp(&j)));
    let mut cycle = component.outer.clone();
    let mut bridges = 0;
    for (done, &h) in order.iter().enumerate() {
        let hole = &component.holes[h];
        let k = rightmost(hole);
        let m = hole[k];
        let (hp, hn) = (hole[(k + hole.len() - 1) % hole.len()], hole[(k + 1) % hole.len()]);
        let mut cands: Vec<usize> = (0..cycle.len()).collect();
        cands.sort_by(|&i, &j| p(cycle[i]).distance_squared(p(m)).total_cmp(&p(cycle[j]).distance_squared(p(m))).then(cycle[i].cmp(&cycle[j])).then(i.cmp(&j)));
        let n = cycle.len();
        let found = cands.into_iter().find(|&c| {
            let v = cycle[c];
            let (vp, vn) = (cycle[(c + n - 1) % n], cycle[(c + 1) % n]);
            in_cone(p(vp), p(v), p(vn), p(m))
                && in_cone(p(hp), p(m), p(hn), p(v))
                && !blocked(points, &cycle, v, m)
                && !order[done..].iter().any(|&o| blocked(points, &component.holes[o], v, m))
        });
        let Some(c) = found else {
            return Err(LoopError::NoBridge(m));
        };
        let mut merged = Vec::with_capacity(cycle.len() + hole.len() + 2);
        merged.extend_from_slice(&cycle[..=c]);
        for j in 0..=hole.len() {
            merged.push(hole[(k + j) % hole.len()]);
        }
        merged.push(cycle[c]);
        merged.extend_from_slice(&cycle[c + 1..]);
        cycle = merged;
        bridges += 1;
    }
    Ok((cycle, bridges))
}
