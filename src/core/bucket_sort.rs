//! Sorting records whose order starts with a small integer (a vertex index): a counting pass
//! on that integer, then each bucket sorted on its own, in parallel. Face records of a tet
//! mesh (sorted vertex triples) are the use: their first vertex has about twenty records, so
//! the buckets are tiny and the whole sort is linear in practice.
//!
//! # Invariants
//! - The result is the records sorted by `Ord`, the same as `sort_unstable` (equal records
//!   are indistinguishable), whatever the thread count, provided `lead(x)` is the first key
//!   of the order: `lead(x) < lead(y)` implies `x < y`.

use rayon::prelude::*;

/// The records that `records()` yields (it is called twice, and must yield the same records
/// both times), sorted by `Ord`, every `lead(x) < n` (the order's first key). The records are
/// placed straight into their buckets: no unsorted copy is ever held.
///
/// # Panics
/// When a lead is `n` or more, or the two passes differ (callers' bugs).
pub fn collect_sorted_by_lead<T: Ord + Copy + Send, I: Iterator<Item = T>>(n: usize, records: impl Fn() -> I, lead: impl Fn(&T) -> u32) -> Vec<T> {
    let mut start = vec![0usize; n + 1];
    let mut first = None;
    for x in records() {
        start[lead(&x) as usize + 1] += 1;
        first.get_or_insert(x);
    }
    let Some(first) = first else { return Vec::new() };
    for i in 0..n {
        start[i + 1] += start[i];
    }
    let mut at = start.clone();
    // every slot is written exactly once below; it starts as a copy of the first record
    let mut out: Vec<T> = vec![first; start[n]];
    for x in records() {
        let b = lead(&x) as usize;
        out[at[b]] = x;
        at[b] += 1;
    }
    sort_buckets_by(&mut out, &start, T::cmp);
    out
}

/// Sorts each bucket `out[start[b]..start[b + 1]]` on its own by `cmp`, the buckets in
/// parallel (`start` non-decreasing, its last entry `out.len()`). The result is the same for
/// any thread count where `cmp` is a total order on distinct records.
pub fn sort_buckets_by<T: Send>(out: &mut [T], start: &[usize], cmp: impl Fn(&T, &T) -> std::cmp::Ordering + Sync) {
    let mut buckets: Vec<&mut [T]> = Vec::with_capacity(start.len());
    let mut rest: &mut [T] = out;
    for w in start.windows(2) {
        let (head, tail) = rest.split_at_mut(w[1] - w[0]);
        if head.len() > 1 {
            buckets.push(head);
        }
        rest = tail;
    }
    buckets.par_iter_mut().with_min_len(256).for_each(|b| b.sort_unstable_by(&cmp));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equals_a_full_sort() {
        let mut rng = crate::core::spatial_order::XorShift::new(7);
        let mut rnd = || rng.next_u64();
        let recs: Vec<([u32; 3], u32)> = (0..5000)
            .map(|i| {
                let mut k = [(rnd() % 300) as u32, (rnd() % 300) as u32, (rnd() % 300) as u32];
                k.sort_unstable();
                (k, i % 7)
            })
            .collect();
        let mut want = recs.clone();
        want.sort_unstable();
        assert_eq!(collect_sorted_by_lead(300, || recs.iter().copied(), |r| r.0[0]), want);
    }

    #[test]
    fn empty_and_single() {
        let e: Vec<([u32; 3], u32)> = Vec::new();
        assert!(collect_sorted_by_lead(0, || e.iter().copied(), |r| r.0[0]).is_empty());
        let r = vec![([5, 6, 7], 1), ([1, 2, 3], 0), ([1, 2, 3], 0)];
        assert_eq!(collect_sorted_by_lead(8, || r.iter().copied(), |x| x.0[0]), vec![([1, 2, 3], 0), ([1, 2, 3], 0), ([5, 6, 7], 1)]);
    }
}
