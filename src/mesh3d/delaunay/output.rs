//! The canonical form of a tetrahedralization: equal inputs give equal arrays, whatever the
//! insertion order or the number of threads.
//!
//! The form is taken in the internal numbering (the points' Hilbert ranks, a function of the
//! input alone), where it is cheap: every tet is rotated (by an even permutation, so it stays
//! positive) to start with its smallest rank, followed by the smallest of the other three;
//! tets are sorted by a counting sort on the first rank (spatially coherent, so the scatter
//! stays local) and a small sort within each bucket. Then ranks become input indices, and every
//! duplicate group is represented by its smallest index.

use crate::mesh3d::delaunay::kernel::Kernel;
use crate::mesh3d::delaunay::store::{AtomicTet, Tet, is_finite};
use rayon::prelude::*;

/// `t` rotated by an even permutation to start with its smallest vertex, then the smallest of
/// the remaining three.
#[inline]
pub(crate) fn canonical_rotation(mut t: [u32; 4]) -> [u32; 4] {
    let m = (0..4).min_by_key(|&i| t[i]).unwrap_or(0);
    if m != 0 {
        t.swap(0, m);
        // a second transposition away from position 0 keeps the parity even
        let (a, b) = match m {
            1 => (2, 3),
            2 => (1, 3),
            _ => (1, 2),
        };
        t.swap(a, b);
    }
    // rotate positions 1..4 (a 3-cycle, even) to put the smallest there first
    let r = (1..4).min_by_key(|&i| t[i]).unwrap_or(1);
    match r {
        2 => t = [t[0], t[2], t[3], t[1]],
        3 => t = [t[0], t[3], t[1], t[2]],
        _ => {}
    }
    t
}

/// Sorts `tets` (already canonically rotated, vertices below `n`) into canonical order.
#[cfg(test)]
pub(crate) fn sort_tets(tets: Vec<[u32; 4]>, n: usize) -> Vec<[u32; 4]> {
    let mut start = vec![0u32; n + 1];
    for t in &tets {
        start[t[0] as usize + 1] += 1;
    }
    for i in 0..n {
        start[i + 1] += start[i];
    }
    let mut out = vec![[0u32; 4]; tets.len()];
    let mut next = start.clone();
    for t in tets {
        let s = &mut next[t[0] as usize];
        out[*s as usize] = t;
        *s += 1;
    }
    sort_buckets(&mut out, &start);
    out
}

/// Rewrites `duplicates` (pairs `(left out, kept)` of input indices) so that the kept point of
/// every group is its smallest index, sorted; returns the map from every input index to the
/// kept index of its group, if there are duplicates.
pub(crate) fn canonical_duplicates(n: usize, duplicates: &mut [[u32; 2]]) -> Option<Vec<u32>> {
    if duplicates.is_empty() {
        return None;
    }
    let mut r: Vec<u32> = (0..n as u32).collect();
    for &[d, v] in duplicates.iter() {
        if d < r[v as usize] {
            r[v as usize] = d;
        }
    }
    for e in duplicates.iter_mut() {
        let v = e[1];
        let kept = r[v as usize];
        if e[0] == kept {
            e[0] = v;
        }
        e[1] = kept;
    }
    duplicates.sort_unstable();
    Some(r)
}

/// Sorts each bucket `out[start[i]..start[i + 1]]` (contiguous) in parallel.
fn sort_buckets(out: &mut [[u32; 4]], start: &[u32]) {
    let mut rest: &mut [[u32; 4]] = out;
    let mut buckets: Vec<&mut [[u32; 4]]> = Vec::new();
    for w in start.windows(2) {
        let len = (w[1] - w[0]) as usize;
        let (b, r) = rest.split_at_mut(len);
        if len > 1 {
            buckets.push(b);
        }
        rest = r;
    }
    buckets.par_iter_mut().with_min_len(1024).for_each(|b| b.sort_unstable());
}

/// Read access to the tet slots of a finished triangulation, plain or atomic.
pub(crate) trait Slots: Sync {
    /// Number of slots.
    fn count(&self) -> usize;
    /// The vertices of slot `t`.
    fn v(&self, t: usize) -> [u32; 4];
}

impl Slots for Vec<Tet> {
    fn count(&self) -> usize {
        self.len()
    }
    #[inline]
    fn v(&self, t: usize) -> [u32; 4] {
        self[t].v
    }
}

impl Slots for Vec<AtomicTet> {
    fn count(&self) -> usize {
        self.len()
    }
    #[inline]
    fn v(&self, t: usize) -> [u32; 4] {
        self[t].get().v
    }
}

/// Number of finite tets among the slots.
pub(crate) fn count_finite<S: Slots>(slots: &S) -> usize {
    (0..slots.count()).into_par_iter().with_min_len(4096).filter(|&t| is_finite(&slots.v(t))).count()
}

/// The finite tets of `slots` in canonical form, as input indices; consumes the slots so that
/// their memory is released before the bucket sorts. Rewrites `duplicates` (pairs
/// `(left out, kept)` of input indices) so that the kept point of every group is its smallest
/// index, sorted.
pub(crate) fn canonical_tets<S: Slots, K: Kernel>(slots: S, k: &K, duplicates: &mut [[u32; 2]]) -> Vec<[u32; 4]> {
    let n = k.len();
    let live = || (0..slots.count()).map(|t| slots.v(t)).filter(is_finite);
    // counting sort on the first rank, straight from the slots: one output buffer only
    let mut start = vec![0u32; n + 1];
    for v in live() {
        start[canonical_rotation(v)[0] as usize + 1] += 1;
    }
    for i in 0..n {
        start[i + 1] += start[i];
    }
    let total = start[n] as usize;
    let mut out = vec![[0u32; 4]; total];
    {
        let mut next = start.clone();
        for v in live() {
            let r = canonical_rotation(v);
            let s = &mut next[r[0] as usize];
            out[*s as usize] = r;
            *s += 1;
        }
    }
    drop(slots);
    sort_buckets(&mut out, &start);
    let rep = canonical_duplicates(n, duplicates);
    out.par_iter_mut().with_min_len(4096).for_each(|t| {
        *t = t.map(|v| {
            let o = k.original(v);
            rep.as_ref().map_or(o, |r| r[o as usize])
        })
    });
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parity(t: [u32; 4], of: [u32; 4]) -> bool {
        let pos: Vec<usize> = t.iter().map(|v| of.iter().position(|w| w == v).unwrap()).collect();
        let mut inv = 0;
        for i in 0..4 {
            for j in i + 1..4 {
                if pos[i] > pos[j] {
                    inv += 1;
                }
            }
        }
        inv % 2 == 0
    }

    #[test]
    fn rotation_is_even_and_canonical() {
        let base = [10u32, 20, 30, 40];
        // all 12 even permutations of base map to the same canonical tet
        let mut seen = std::collections::HashSet::new();
        for a in 0..4 {
            for b in 0..4 {
                for c in 0..4 {
                    for d in 0..4 {
                        let t = [base[a], base[b], base[c], base[d]];
                        let mut s = t;
                        s.sort();
                        if s != base || !parity(t, base) {
                            continue;
                        }
                        let r = canonical_rotation(t);
                        assert!(parity(r, t), "{t:?} -> {r:?} changed orientation");
                        seen.insert(r);
                    }
                }
            }
        }
        assert_eq!(seen.len(), 1);
        // the reversal of four is two transpositions: even
        assert_eq!(canonical_rotation([40, 30, 20, 10]), [10, 20, 30, 40]);
        assert_eq!(canonical_rotation([40, 30, 10, 20]), [10, 20, 40, 30]);
    }

    #[test]
    fn sorts_by_buckets() {
        let t = vec![[2, 3, 4, 5], [0, 9, 1, 2], [0, 1, 2, 3], [2, 3, 1, 0]];
        assert_eq!(sort_tets(t, 10), vec![[0, 1, 2, 3], [0, 9, 1, 2], [2, 3, 1, 0], [2, 3, 4, 5]]);
    }
}
