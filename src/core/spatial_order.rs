//! Insertion orders for incremental algorithms: Hilbert-curve keys and BRIO (biased randomized
//! insertion order), as used by Delaunay insertion.
//!
//! A BRIO shuffles the points, splits them into rounds whose sizes grow geometrically (each
//! round 8× the one before, the last holding 7/8 of the points), and sorts each round along a
//! Hilbert curve: randomness between rounds keeps the expected work optimal, locality within a
//! round keeps point location short and memory access cache-friendly. Deterministic for a given
//! seed; independent of the number of threads.

use crate::core::Aabb;
use glam::DVec3;
use rayon::prelude::*;

/// Bits per axis of the Hilbert keys (3 × 21 = 63 bits).
pub const HILBERT_BITS: u32 = 21;

/// The Hilbert index of integer coordinates `x` (each below `2^bits`), `3 × bits` bits long.
///
/// Skilling's transpose form ("Programming the Hilbert curve", 2004): undo excess work, Gray
/// encode, then interleave the bits of the three axes, most significant first.
pub fn hilbert_index(mut x: [u32; 3], bits: u32) -> u64 {
    debug_assert!((1..=21).contains(&bits));
    let m = 1u32 << (bits - 1);
    let mut q = m;
    while q > 1 {
        let p = q - 1;
        for i in 0..3 {
            if x[i] & q != 0 {
                x[0] ^= p;
            } else {
                let t = (x[0] ^ x[i]) & p;
                x[0] ^= t;
                x[i] ^= t;
            }
        }
        q >>= 1;
    }
    for i in 1..3 {
        x[i] ^= x[i - 1];
    }
    let mut t = 0;
    q = m;
    while q > 1 {
        if x[2] & q != 0 {
            t ^= q - 1;
        }
        q >>= 1;
    }
    for v in &mut x {
        *v ^= t;
    }
    let mut key = 0u64;
    for j in (0..bits).rev() {
        for v in &x {
            key = (key << 1) | ((*v >> j) & 1) as u64;
        }
    }
    key
}

/// Bits per axis that resolve `n` points: about 16 grid cells per point along the curve,
/// between 6 and [`HILBERT_BITS`].
pub fn hilbert_bits_for(n: usize) -> u32 {
    let log2 = usize::BITS - n.max(1).leading_zeros();
    (log2.div_ceil(3) + 2).clamp(6, HILBERT_BITS)
}

/// Hilbert keys of `points` on a `2^bits` grid per axis over `bbox`, with
/// `bits = hilbert_bits_for(points.len())` (non-finite points get key 0).
pub fn hilbert_keys(points: &[DVec3], bbox: &Aabb) -> Vec<u64> {
    let bits = hilbert_bits_for(points.len());
    let ext = bbox.extent();
    let side = ext.max_element();
    let scale = if side > 0.0 { ((1u64 << bits) - 1) as f64 / side } else { 0.0 };
    let lo = bbox.min;
    points
        .par_iter()
        .with_min_len(4096)
        .map(|p| {
            if !p.is_finite() {
                return 0;
            }
            let q = (*p - lo) * scale;
            let c = |v: f64| (v.max(0.0) as u64).min((1u64 << bits) - 1) as u32;
            hilbert_index([c(q.x), c(q.y), c(q.z)], bits)
        })
        .collect()
}

/// A small deterministic generator (xorshift64*), enough for shuffling.
#[derive(Clone, Debug)]
pub struct XorShift(u64);

impl XorShift {
    /// A generator from `seed` (any value).
    pub fn new(seed: u64) -> Self {
        XorShift(seed ^ 0x9e37_79b9_7f4a_7c15 | 1)
    }

    /// The next 64 random bits.
    #[inline]
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    /// A uniform integer in `0..n` (`n > 0`).
    #[inline]
    pub fn below(&mut self, n: u64) -> u64 {
        ((self.next_u64() >> 32) * n) >> 32
    }
}

/// Rounds of a BRIO over `n` items: `(start, end)` ranges of the shuffled order, smallest
/// first, each 8× the previous, the first at most `first` long.
pub fn brio_rounds(n: usize, first: usize) -> Vec<(usize, usize)> {
    let mut ends = vec![n];
    let mut m = n;
    while m > first {
        m /= 8;
        ends.push(m);
    }
    ends.reverse();
    let mut rounds = Vec::with_capacity(ends.len());
    let mut start = 0;
    for e in ends {
        if e > start {
            rounds.push((start, e));
        }
        start = e;
    }
    rounds
}

/// The permutation that sorts `points` along a Hilbert curve over their bounding box (ties by
/// index): `perm[k]` is the point at rank `k`.
pub fn hilbert_sort(points: &[DVec3]) -> Vec<u32> {
    let bbox = Aabb::from_points(points.iter().filter(|p| p.is_finite()));
    let mut pairs: Vec<(u64, u32)> = hilbert_keys(points, &bbox).into_iter().zip(0..points.len() as u32).collect();
    pairs.par_sort_unstable();
    pairs.into_iter().map(|(_, i)| i).collect()
}

/// A biased randomized insertion order of `0..n` for items already sorted along a Hilbert
/// curve: a seeded shuffle cut into rounds by [`brio_rounds`] (first round at most 1024), each
/// round sorted ascending, i.e. along the curve.
pub fn brio_positions(n: usize, seed: u64) -> Vec<u32> {
    let mut order: Vec<u32> = (0..n as u32).collect();
    let mut rng = XorShift::new(seed);
    for i in (1..n).rev() {
        let j = rng.below(i as u64 + 1) as usize;
        order.swap(i, j);
    }
    for (s, e) in brio_rounds(n, 1024) {
        let round = &mut order[s..e];
        if round.len() > 1 << 15 {
            round.par_sort_unstable();
        } else {
            round.sort_unstable();
        }
    }
    order
}

/// A biased randomized insertion order of `points`: [`brio_positions`] over their
/// [`hilbert_sort`].
pub fn brio_order(points: &[DVec3], seed: u64) -> Vec<u32> {
    let perm = hilbert_sort(points);
    brio_positions(points.len(), seed).into_iter().map(|k| perm[k as usize]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hilbert_visits_every_cell_once_with_unit_steps() {
        // on a 4×4×4 grid the curve is a Hamiltonian path with unit steps
        let bits = 2;
        let mut cells = vec![[0u32; 3]; 64];
        let mut seen = [false; 64];
        for x in 0..4 {
            for y in 0..4 {
                for z in 0..4 {
                    let k = hilbert_index([x, y, z], bits) as usize;
                    assert!(!seen[k], "key {k} twice");
                    seen[k] = true;
                    cells[k] = [x, y, z];
                }
            }
        }
        for w in cells.windows(2) {
            let d: u32 = (0..3).map(|i| w[0][i].abs_diff(w[1][i])).sum();
            assert_eq!(d, 1, "{:?} -> {:?}", w[0], w[1]);
        }
    }

    #[test]
    fn brio_is_a_deterministic_permutation() {
        let pts: Vec<DVec3> = (0..5000).map(|i| DVec3::new((i % 17) as f64, (i % 13) as f64, (i / 221) as f64)).collect();
        let a = brio_order(&pts, 7);
        let mut s = a.clone();
        s.sort_unstable();
        assert_eq!(s, (0..5000).collect::<Vec<u32>>());
        assert_eq!(a, brio_order(&pts, 7));
        assert_ne!(a, brio_order(&pts, 8));
        assert_eq!(brio_rounds(5000, 1024), vec![(0, 625), (625, 5000)]);
        assert_eq!(brio_rounds(100_000, 1024), vec![(0, 195), (195, 1562), (1562, 12500), (12500, 100_000)]);
        assert_eq!(brio_rounds(3, 1024), vec![(0, 3)]);
        assert_eq!(hilbert_bits_for(1_000_000), 9);
        assert_eq!(hilbert_bits_for(10), 6);
    }
}
