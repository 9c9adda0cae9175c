//! The refinement queue: bad tets, worst first, in buckets by priority.
//!
//! Refinement pops far more entries than it refines: on `part.step` at TetGen's tet count,
//! 173,328 of 196,888 popped entries were stale (a later insertion had taken the tet), with up
//! to 58,428 entries queued. One heap of them all spent eight levels of sifting on each pop,
//! over a megabyte of entries. Here the entries are kept in buckets by their priority's bits
//! (512 to an octave), each bucket a 4-ary heap, and a bitset of the non-empty buckets finds
//! the highest: a pop sifts a heap of a few hundred entries that stays in cache.
//!
//! The order is exactly one heap's: the bucket is a monotone function of the priority, so the
//! greatest entry lies in the highest non-empty bucket, and within it the heap orders entries
//! as one heap of all would (priorities outside the buckets' range share the end buckets,
//! which order them the same way).

use dary_heap::QuaternaryHeap;

/// Mantissa bits of the priority that pick a bucket: 512 buckets to an octave.
const MANTISSA_BITS: u32 = 9;

/// The least binary exponent with buckets of its own (priorities under `2^LOW_EXP` share the
/// first bucket).
const LOW_EXP: u64 = 1023 - 4;

/// Octaves with buckets of their own (priorities from `2^(LOW_EXP - 1023 + OCTAVES)` share the
/// last bucket).
const OCTAVES: u64 = 16;

/// Buckets in all.
const BUCKETS: usize = (OCTAVES as usize) << MANTISSA_BITS;

/// A priority queue of `(priority, slot, fingerprint)`, greatest first, ordered as the tuple
/// is: the priority is a non-negative `f64`'s bits (ordered as the numbers are).
pub(crate) struct BadQueue {
    buckets: Vec<QuaternaryHeap<u128>>,
    /// Bit `b` of word `b / 64`: bucket `b` holds entries.
    nonempty: Vec<u64>,
    /// No word of `nonempty` past this one is non-zero.
    top_word: usize,
}

impl Default for BadQueue {
    fn default() -> Self {
        BadQueue { buckets: (0..BUCKETS).map(|_| QuaternaryHeap::new()).collect(), nonempty: vec![0; BUCKETS / 64], top_word: 0 }
    }
}

/// The bucket of a priority: its exponent and top mantissa bits, clamped to the range.
fn bucket(priority: u64) -> usize {
    let key = priority.saturating_sub(LOW_EXP << 52) >> (52 - MANTISSA_BITS);
    key.min(BUCKETS as u64 - 1) as usize
}

impl BadQueue {
    /// Queues an entry.
    pub(crate) fn push(&mut self, priority: u64, slot: u32, fingerprint: u32) {
        let b = bucket(priority);
        self.buckets[b].push(u128::from(priority) << 64 | u128::from(slot) << 32 | u128::from(fingerprint));
        self.nonempty[b / 64] |= 1 << (b % 64);
        self.top_word = self.top_word.max(b / 64);
    }

    /// The greatest entry, taken off the queue.
    pub(crate) fn pop(&mut self) -> Option<(u64, u32, u32)> {
        loop {
            let word = self.nonempty[self.top_word];
            if word != 0 {
                let b = self.top_word * 64 + 63 - word.leading_zeros() as usize;
                let heap = &mut self.buckets[b];
                let e = heap.pop()?;
                if heap.is_empty() {
                    self.nonempty[self.top_word] &= !(1 << (b % 64));
                }
                return Some(((e >> 64) as u64, (e >> 32) as u32, e as u32));
            }
            if self.top_word == 0 {
                return None;
            }
            self.top_word -= 1;
        }
    }

    /// Entries queued.
    #[cfg(test)]
    fn len(&self) -> usize {
        self.buckets.iter().map(QuaternaryHeap::len).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::collections::BinaryHeap;

    #[test]
    fn buckets_are_monotone_and_clamped() {
        let xs = [0.0, 1e-300, 0.01, 0.0625, 0.07, 1.0, 1.5, 1.5000001, 2.0, 3.99, 4096.0, 1e9, f64::MAX];
        for w in xs.windows(2) {
            assert!(bucket(w[0].to_bits()) <= bucket(w[1].to_bits()), "{} {}", w[0], w[1]);
        }
        assert_eq!(bucket(0.0f64.to_bits()), 0);
        assert_eq!(bucket(0.0625f64.to_bits()), 0);
        assert!(bucket(0.0626f64.to_bits()) <= 1);
        assert_eq!(bucket(1e9f64.to_bits()), BUCKETS - 1);
        // an octave has 512 buckets of its own
        assert_eq!(bucket(2.0f64.to_bits()) - bucket(1.0f64.to_bits()), 512);
        assert!(bucket(1.5000001f64.to_bits()) == bucket(1.5f64.to_bits()));
    }

    /// Pops in the order of one heap of `(priority, slot, fingerprint)`.
    fn same_as_one_heap(ops: &[(bool, f64, u32, u32)]) {
        let mut q = BadQueue::default();
        let mut h = BinaryHeap::new();
        for &(push, x, s, f) in ops {
            if push {
                q.push(x.to_bits(), s, f);
                h.push((x.to_bits(), s, f));
            } else {
                assert_eq!(q.pop(), h.pop());
            }
            assert_eq!(q.len(), h.len());
        }
        while let Some(e) = h.pop() {
            assert_eq!(q.pop(), Some(e));
        }
        assert_eq!(q.pop(), None);
        assert_eq!(q.len(), 0);
    }

    #[test]
    fn ties_and_the_end_buckets_pop_as_one_heap() {
        same_as_one_heap(&[
            (true, 1.5, 3, 9),
            (true, 1.5, 3, 2),
            (true, 1.5, 7, 1),
            (true, 0.001, 1, 1),
            (true, 0.002, 1, 1),
            (true, 1e12, 1, 1),
            (true, 1e11, 2, 1),
            (false, 0.0, 0, 0),
            (true, 1.5000000001, 0, 0),
            (false, 0.0, 0, 0),
            (false, 0.0, 0, 0),
            (false, 0.0, 0, 0),
        ]);
    }

    proptest! {
        #[test]
        fn pops_as_one_heap(ops in prop::collection::vec((prop::bool::weighted(0.6), prop_oneof![0.0f64..1e-3, 0.5f64..8.0, 1.0f64..1.01, 1e3f64..1e6], 0u32..50, 0u32..4), 0..400)) {
            same_as_one_heap(&ops);
        }
    }
}
