//! Nesting of closed shells, by exact ray parity.
//!
//! Input: the shells of a surface, a BVH over its non-degenerate triangles. Output: for every
//! closed shell, how many other closed shells contain it (`depth`) and the innermost one
//! (`parent`); `None` for open shells and where no decision was possible.
//!
//! For a closed shell `S`, a vertex `p` of `S` lying on no other closed shell is chosen
//! (decided exactly with [`point_on_triangle`]); a segment from `p` to a point beyond the
//! surface's box is cast and its crossings with each other closed shell are counted. A
//! closed shell (every edge with two triangles) bounds a region mod 2, so `p` is inside it iff
//! the count is odd. Every crossing is classified exactly ([`segment_crosses_triangle`]); if
//! any contact is not a transversal crossing of a triangle's interior (an edge, a vertex, a
//! segment in a triangle's plane), another direction from a fixed sequence is tried.
//! Degenerate (zero-area) triangles are skipped: a segment can only meet one where it also
//! meets an edge of a neighbour, which is detected. Shells that cross each other get
//! whatever answer the chosen point gives.

use super::Prepared;
use super::shells::Analysis;
use crate::core::Aabb;
use crate::core::bvh::Bvh;
use crate::core::intersection::{SegmentCrossing, point_on_triangle, segment_crosses_triangle};
use glam::DVec3;

/// Depth and innermost container of every shell.
pub(crate) struct Nesting {
    pub depth: Vec<Option<usize>>,
    pub parent: Vec<Option<usize>>,
}

/// Vertices of a shell tried as ray origins.
const MAX_ORIGINS: usize = 12;
/// Directions tried per origin.
const MAX_DIRECTIONS: usize = 32;

/// The `k`-th direction of a fixed, well spread sequence of unit vectors (a spherical
/// Fibonacci spiral with irrational offsets, so that no direction is axis-aligned).
fn direction(k: usize) -> DVec3 {
    let n = (MAX_DIRECTIONS + 1) as f64;
    let z = 1.0 - 2.0 * ((k as f64 + 0.5 + 0.1234567) / n).fract();
    let phi = 2.399_963_229_728_653 * k as f64 + 0.577_215_664_9;
    let r = (1.0 - z * z).max(0.0).sqrt();
    DVec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// Computes the nesting of the closed shells.
pub(crate) fn nest(m: &Prepared, sh: &Analysis, bvh: &Bvh, degenerate: &[bool]) -> Nesting {
    let ns = sh.shells.len();
    let closed: Vec<bool> = sh.shells.iter().map(|s| s.closed()).collect();
    let mut depth: Vec<Option<usize>> = closed.iter().map(|&c| c.then_some(0)).collect();
    let mut parent = vec![None; ns];
    if closed.iter().filter(|&&c| c).count() < 2 {
        return Nesting { depth, parent };
    }
    let bbox = bvh.bbox();
    let mut parity = vec![false; ns];
    let mut containers: Vec<Vec<usize>> = vec![Vec::new(); ns];
    for s in 0..ns {
        if !closed[s] {
            continue;
        }
        let found = contained_in(m, sh, bvh, degenerate, &closed, s, &bbox, &mut parity);
        match found {
            Some(list) => {
                depth[s] = Some(list.len());
                containers[s] = list;
            }
            None => depth[s] = None,
        }
    }
    for s in 0..ns {
        // the innermost container is the deepest one (smallest index among equals)
        parent[s] = containers[s].iter().copied().max_by_key(|&c| (depth[c].unwrap_or(0), std::cmp::Reverse(c)));
    }
    Nesting { depth, parent }
}

/// The closed shells (other than `s`) containing shell `s`, increasing; `None` if undecided.
#[allow(clippy::too_many_arguments)]
fn contained_in(
    m: &Prepared,
    sh: &Analysis,
    bvh: &Bvh,
    degenerate: &[bool],
    closed: &[bool],
    s: usize,
    bbox: &Aabb,
    parity: &mut [bool],
) -> Option<Vec<usize>> {
    let other = |t: u32| {
        let ts = sh.shell_of[t as usize] as usize;
        (ts != s && closed[ts] && !degenerate[t as usize]).then_some(ts)
    };
    let mut tried: Vec<u32> = Vec::new();
    for &t in sh.members(s) {
        for v in m.tris[t as usize] {
            if tried.len() >= MAX_ORIGINS {
                return None;
            }
            if tried.contains(&v) {
                continue;
            }
            tried.push(v);
            let p = m.verts[v as usize];
            let mut on_other = false;
            bvh.for_each_overlapping(&Aabb { min: p, max: p }, |t| {
                if !on_other && other(t).is_some() && point_on_triangle(p, m.corners(t as usize)) {
                    on_other = true;
                }
            });
            if on_other {
                continue;
            }
            let reach = 2.0 * (bbox.diagonal() + (p - bbox.center()).length()) + 1.0;
            for k in 0..MAX_DIRECTIONS {
                let q = p + direction(k) * reach;
                if bbox.overlaps(&Aabb { min: q, max: q }) {
                    continue;
                }
                let mut touched: Vec<usize> = Vec::new();
                let mut clean = true;
                bvh.for_each_on_segment(p, q, |t| {
                    if !clean {
                        return;
                    }
                    let Some(ts) = other(t) else { return };
                    match segment_crosses_triangle(p, q, m.corners(t as usize)) {
                        SegmentCrossing::Miss => {}
                        SegmentCrossing::Proper => {
                            parity[ts] = !parity[ts];
                            touched.push(ts);
                        }
                        SegmentCrossing::Degenerate => clean = false,
                    }
                });
                let mut inside: Vec<usize> = touched.iter().copied().filter(|&x| parity[x]).collect();
                for &x in &touched {
                    parity[x] = false;
                }
                if clean {
                    inside.sort_unstable();
                    inside.dedup();
                    return Some(inside);
                }
            }
        }
    }
    None
}
