//! Ear cutting (the lecture's topology decomposition, 23.2.2): triangles whose corners are
//! polygon vertices are cut off until three vertices remain.
//!
//! - Inputs: the points and a weakly simple cycle (counter-clockwise, domain on the left;
//!   bridge ends may appear twice, see `bridge`).
//! - Output: the triangles (counter-clockwise), `n - 2` for a cycle of `n` vertices.
//! - Invariants: an ear is cut only when its tip is strictly convex and no other vertex that
//!   is not strictly convex lies inside or on it (exact [`orient2d`]); copies of the ear's
//!   own corners (bridge ends) are not counted. The ear cut next is the one with the largest
//!   smallest angle, ties by the smaller cycle position: deterministic.

use crate::core::predicates::orient2d;
use crate::core::Sign;
use super::trimesh::min_angle;
use glam::DVec2;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// Cuts ears off `cycle`; `None` if at some point no ear exists (not expected of a valid
/// domain; the caller reports it).
pub(crate) fn cut_ears(points: &[DVec2], cycle: &[u32]) -> Option<Vec<[u32; 3]>> {
    let n = cycle.len();
    if n < 3 {
        return None;
    }
    let p = |pos: usize| points[cycle[pos] as usize];
    let mut prev: Vec<usize> = (0..n).map(|i| (i + n - 1) % n).collect();
    let mut next: Vec<usize> = (0..n).map(|i| (i + 1) % n).collect();
    let mut alive = vec![true; n];
    let mut stamp = vec![0u32; n];
    let convex = |prev: &[usize], next: &[usize], i: usize| orient2d(p(prev[i]), p(i), p(next[i])) == Sign::Positive;
    // vertices that are not strictly convex: the only possible blockers
    let mut blockers: Vec<usize> = (0..n).filter(|&i| !convex(&prev, &next, i)).collect();
    let mut heap: BinaryHeap<(u64, Reverse<usize>, u32)> = BinaryHeap::new();
    let quality = |a: DVec2, b: DVec2, c: DVec2| min_angle(a, b, c).max(0.0).to_bits();
    for i in 0..n {
        if convex(&prev, &next, i) {
            heap.push((quality(p(prev[i]), p(i), p(next[i])), Reverse(i), 0));
        }
    }
    let mut deferred: Vec<usize> = Vec::new();
    let mut remaining = n;
    let mut out = Vec::with_capacity(n - 2);
    let mut progress = true;
    while remaining > 3 {
        let Some((_, Reverse(i), s)) = heap.pop() else {
            if !progress || deferred.is_empty() {
                return None;
            }
            progress = false;
            for i in std::mem::take(&mut deferred) {
                if alive[i] && convex(&prev, &next, i) {
                    heap.push((quality(p(prev[i]), p(i), p(next[i])), Reverse(i), stamp[i]));
                }
            }
            continue;
        };
        if !alive[i] || s != stamp[i] {
            continue;
        }
        let (a, c) = (prev[i], next[i]);
        let (pa, pb, pc) = (p(a), p(i), p(c));
        let ids = [cycle[a], cycle[i], cycle[c]];
        let is_ear = blockers.iter().all(|&w| {
            if !alive[w] || ids.contains(&cycle[w]) {
                return true;
            }
            let q = p(w);
            !(orient2d(pa, pb, q) != Sign::Negative && orient2d(pb, pc, q) != Sign::Negative && orient2d(pc, pa, q) != Sign::Negative)
        });
        if !is_ear {
            deferred.push(i);
            continue;
        }
        out.push(ids);
        alive[i] = false;
        next[a] = c;
        prev[c] = a;
        remaining -= 1;
        progress = true;
        for j in [a, c] {
            stamp[j] += 1;
            if convex(&prev, &next, j) {
                heap.push((quality(p(prev[j]), p(j), p(next[j])), Reverse(j), stamp[j]));
            }
        }
        if blockers.len() > 64 && blockers.iter().filter(|&&w| !alive[w]).count() * 2 > blockers.len() {
            blockers.retain(|&w| alive[w]);
        }
    }
    let first = (0..n).find(|&i| alive[i])?;
    let tri = [cycle[prev[first]], cycle[first], cycle[next[first]]];
    if orient2d(points[tri[0] as usize], points[tri[1] as usize], points[tri[2] as usize]) != Sign::Positive {
        return None;
    }
    out.push(tri);
    Some(out)
}
