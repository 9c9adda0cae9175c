//! Exact self-intersection test of a triangle surface.
//!
//! Input: the valid, non-degenerate triangles and a BVH over their boxes. Output: the number
//! of intersecting pairs and the first ones in increasing `(a, b)` order, as original triangle
//! indices. Candidate pairs are the BVH's overlapping box pairs; each is decided by
//! [`triangle_pair_intersects`] (shared vertices and edges allowed, folds and duplicates not).
//! The candidate traversal runs in parallel over a fixed task list, so the count and the
//! list are the same for any number of threads.

use super::Prepared;
use crate::core::bvh::Bvh;
use crate::core::intersection::triangle_pair_intersects;
use crate::mesh::TriSurface;

/// Per-task accumulator: the count and the smallest pairs seen.
struct Acc {
    count: usize,
    smallest: Vec<[u32; 2]>,
}

/// Keeps the `n` smallest pairs of `v` (sorted).
fn keep_smallest(v: &mut Vec<[u32; 2]>, n: usize) {
    v.sort_unstable();
    v.dedup();
    v.truncate(n);
}

/// Tests the candidate pair of valid triangles `a`, `b`.
#[inline]
fn test(m: &Prepared, a: u32, b: u32) -> bool {
    let (a, b) = (a as usize, b as usize);
    triangle_pair_intersects(m.tris[a], m.corners(a), m.tris[b], m.corners(b))
}

/// The number of intersecting pairs among the triangles in `bvh`, and the first `max_listed`
/// of them (original indices, increasing).
pub(crate) fn find(m: &Prepared, bvh: &Bvh, max_listed: usize) -> (usize, Vec<[u32; 2]>) {
    let keep = max_listed.max(1);
    let parts = bvh.par_fold_overlapping_pairs(
        || Acc { count: 0, smallest: Vec::new() },
        |acc, a, b| {
            if test(m, a, b) {
                acc.count += 1;
                let (oa, ob) = (m.orig(a as usize), m.orig(b as usize));
                acc.smallest.push([oa.min(ob), oa.max(ob)]);
                if acc.smallest.len() >= 4 * keep + 64 {
                    keep_smallest(&mut acc.smallest, keep);
                }
            }
        },
    );
    let count = parts.iter().map(|p| p.count).sum();
    let mut all: Vec<[u32; 2]> = Vec::new();
    for mut p in parts {
        keep_smallest(&mut p.smallest, keep);
        all.extend(p.smallest);
    }
    keep_smallest(&mut all, max_listed);
    (count, all)
}

/// Every intersecting pair `[a, b]` (`a < b`, triangle indices of `s`), increasing.
/// Degenerate and invalid triangles are not tested (the report counts them separately).
pub fn intersecting_pairs(s: &TriSurface) -> Vec<[u32; 2]> {
    let m = Prepared::new(s);
    let degenerate = m.degenerate_flags();
    let bvh = m.bvh(&degenerate);
    let mut out = bvh.par_filter_map_overlapping_pairs(|a, b| {
        test(&m, a, b).then(|| {
            let (oa, ob) = (m.orig(a as usize), m.orig(b as usize));
            [oa.min(ob), oa.max(ob)]
        })
    });
    out.sort_unstable();
    out
}
