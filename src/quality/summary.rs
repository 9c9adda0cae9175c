//! Summary statistics and histograms of per-element measures, with deterministic merging.
//!
//! [`StatsAccumulator`] and [`Histogram`] are built element by element and merged; the mesh
//! reports split the elements into chunks of a fixed size (independent of the thread count),
//! accumulate each chunk, and merge the chunks in order, so every result is bit-identical for
//! any number of threads ([`chunked_reduce`]).
//!
//! Conventions: `NaN` values are counted in `non_finite` and otherwise ignored; `±∞` take part
//! in the minimum and maximum but not in the mean and standard deviation (which are over the
//! finite values, population standard deviation). Ties for the extreme keep the lowest index.

use rayon::prelude::*;
use serde::Serialize;
use std::fmt::Write as _;

/// Statistics of one measure over a set of elements.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Stats {
    /// Number of values given (including non-finite ones).
    pub count: usize,
    /// Values that were `NaN` or infinite (excluded from `mean` and `std_dev`).
    pub non_finite: usize,
    /// Smallest value (`+∞` entries included); 0 when there is none.
    pub min: f64,
    /// Largest value (`+∞` entries included); 0 when there is none.
    pub max: f64,
    /// Mean of the finite values; 0 when there is none.
    pub mean: f64,
    /// Population standard deviation of the finite values; 0 when there is none.
    pub std_dev: f64,
    /// Element index of the minimum (lowest index on ties).
    pub argmin: Option<usize>,
    /// Element index of the maximum (lowest index on ties).
    pub argmax: Option<usize>,
}

impl Stats {
    /// Statistics of `values`, element `i` being `values[i]`.
    ///
    /// ```
    /// use fepre::quality::Stats;
    /// let s = Stats::of(&[3.0, 1.0, 2.0, f64::INFINITY]);
    /// assert_eq!((s.min, s.argmin, s.max, s.argmax), (1.0, Some(1), f64::INFINITY, Some(3)));
    /// assert_eq!((s.mean, s.non_finite), (2.0, 1));
    /// ```
    pub fn of(values: &[f64]) -> Stats {
        let mut acc = StatsAccumulator::new();
        for (i, &v) in values.iter().enumerate() {
            acc.push(i, v);
        }
        acc.finish()
    }

    /// One-line rendering: `min … (#i)  max … (#j)  mean …  sd …`.
    pub fn render(&self) -> String {
        let idx = |i: Option<usize>| i.map(|i| format!(" (#{i})")).unwrap_or_default();
        format!(
            "min {}{}  max {}{}  mean {}  sd {}",
            fmt_num(self.min),
            idx(self.argmin),
            fmt_num(self.max),
            idx(self.argmax),
            fmt_num(self.mean),
            fmt_num(self.std_dev)
        )
    }
}

/// Compact number formatting for renderings: 4 significant decimals, scientific when large or
/// tiny.
fn fmt_num(x: f64) -> String {
    if x == 0.0 || (x.is_finite() && (1e-3..1e6).contains(&x.abs())) {
        format!("{x:.4}")
    } else if x.is_finite() {
        format!("{x:.3e}")
    } else {
        format!("{x}")
    }
}

/// Running statistics; merge in a fixed order for reproducible results.
#[derive(Clone, Debug)]
pub struct StatsAccumulator {
    count: usize,
    non_finite: usize,
    min: (f64, usize),
    max: (f64, usize),
    finite: usize,
    mean: f64,
    m2: f64,
}

impl Default for StatsAccumulator {
    fn default() -> Self {
        Self::new()
    }
}

impl StatsAccumulator {
    /// An empty accumulator.
    pub fn new() -> Self {
        StatsAccumulator {
            count: 0,
            non_finite: 0,
            min: (f64::INFINITY, usize::MAX),
            max: (f64::NEG_INFINITY, usize::MAX),
            finite: 0,
            mean: 0.0,
            m2: 0.0,
        }
    }

    /// Adds the value `v` of element `index`. Push in increasing index order (or merge
    /// accumulators of increasing index ranges) for the lowest-index tie rule.
    #[inline]
    pub fn push(&mut self, index: usize, v: f64) {
        self.count += 1;
        if v.is_nan() {
            self.non_finite += 1;
            return;
        }
        if v < self.min.0 || self.min.1 == usize::MAX {
            self.min = (v, index);
        }
        if v > self.max.0 || self.max.1 == usize::MAX {
            self.max = (v, index);
        }
        if !v.is_finite() {
            self.non_finite += 1;
            return;
        }
        self.finite += 1;
        let d = v - self.mean;
        self.mean += d / self.finite as f64;
        self.m2 += d * (v - self.mean);
    }

    /// Merges `other`, whose elements all come after this one's.
    pub fn merge(&mut self, other: &StatsAccumulator) {
        self.count += other.count;
        self.non_finite += other.non_finite;
        if other.min.1 != usize::MAX && (self.min.1 == usize::MAX || other.min.0 < self.min.0) {
            self.min = other.min;
        }
        if other.max.1 != usize::MAX && (self.max.1 == usize::MAX || other.max.0 > self.max.0) {
            self.max = other.max;
        }
        if other.finite > 0 {
            let n = self.finite + other.finite;
            let d = other.mean - self.mean;
            let (na, nb) = (self.finite as f64, other.finite as f64);
            self.mean += d * nb / n as f64;
            self.m2 += other.m2 + d * d * na * nb / n as f64;
            self.finite = n;
        }
    }

    /// The statistics.
    pub fn finish(&self) -> Stats {
        let some = |(v, i): (f64, usize)| if i == usize::MAX { (0.0, None) } else { (v, Some(i)) };
        let (min, argmin) = some(self.min);
        let (max, argmax) = some(self.max);
        let (mean, std_dev) =
            if self.finite == 0 { (0.0, 0.0) } else { (self.mean, (self.m2.max(0.0) / self.finite as f64).sqrt()) };
        Stats { count: self.count, non_finite: self.non_finite, min, max, mean, std_dev, argmin, argmax }
    }
}

/// A histogram over caller-given bin edges: bin `i` is `[edges[i], edges[i+1])`, the last bin
/// also includes its right edge. Values outside go to `below` / `above`, `NaN` to `nan`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Histogram {
    /// Bin edges, strictly increasing (at least two).
    pub edges: Vec<f64>,
    /// One count per bin (`edges.len() - 1`).
    pub counts: Vec<u64>,
    /// Values below `edges[0]`.
    pub below: u64,
    /// Values above the last edge.
    pub above: u64,
    /// `NaN` values.
    pub nan: u64,
}

impl Histogram {
    /// A histogram over the given edges.
    ///
    /// # Panics
    /// If there are fewer than two edges or they are not finite and strictly increasing.
    pub fn with_edges(edges: Vec<f64>) -> Histogram {
        match Histogram::try_with_edges(edges) {
            Ok(h) => h,
            Err(edges) => panic!("histogram edges must be at least two, finite and strictly increasing: {edges:?}"),
        }
    }

    /// A histogram over the given edges, or the edges back if there are fewer than two or they
    /// are not finite and strictly increasing.
    ///
    /// # Errors
    /// The rejected edges.
    pub fn try_with_edges(edges: Vec<f64>) -> Result<Histogram, Vec<f64>> {
        if edges.len() < 2 || !edges.iter().all(|e| e.is_finite()) || !edges.windows(2).all(|w| w[0] < w[1]) {
            return Err(edges);
        }
        let n = edges.len() - 1;
        Ok(Histogram { edges, counts: vec![0; n], below: 0, above: 0, nan: 0 })
    }

    /// `bins` equal bins over `[lo, hi]`.
    ///
    /// # Panics
    /// If `bins == 0` or the range is empty or not finite.
    ///
    /// ```
    /// use fepre::quality::Histogram;
    /// let mut h = Histogram::uniform(0.0, 180.0, 18);
    /// for x in [0.0, 9.99, 10.0, 180.0, 181.0] { h.add(x); }
    /// assert_eq!((h.counts[0], h.counts[1], h.counts[17], h.above), (2, 1, 1, 1));
    /// ```
    pub fn uniform(lo: f64, hi: f64, bins: usize) -> Histogram {
        assert!(bins > 0 && lo.is_finite() && hi.is_finite() && lo < hi, "bad histogram range [{lo}, {hi}] / {bins}");
        let edges = (0..=bins).map(|i| if i == bins { hi } else { lo + (hi - lo) * i as f64 / bins as f64 }).collect();
        Histogram::with_edges(edges)
    }

    /// An empty histogram with the same edges.
    pub fn empty_like(&self) -> Histogram {
        Histogram { edges: self.edges.clone(), counts: vec![0; self.counts.len()], below: 0, above: 0, nan: 0 }
    }

    /// Counts `x`.
    #[inline]
    pub fn add(&mut self, x: f64) {
        let last = self.edges.len() - 1;
        if x.is_nan() {
            self.nan += 1;
        } else if x < self.edges[0] {
            self.below += 1;
        } else if x > self.edges[last] {
            self.above += 1;
        } else if x == self.edges[last] {
            self.counts[last - 1] += 1;
        } else {
            let i = self.edges.partition_point(|&e| e <= x) - 1;
            self.counts[i] += 1;
        }
    }

    /// Adds the counts of `other`, which must have the same edges.
    ///
    /// # Panics
    /// If the edges differ.
    pub fn merge(&mut self, other: &Histogram) {
        assert_eq!(self.edges, other.edges, "merging histograms with different edges");
        for (a, b) in self.counts.iter_mut().zip(&other.counts) {
            *a += b;
        }
        self.below += other.below;
        self.above += other.above;
        self.nan += other.nan;
    }

    /// Total number of values counted, including those outside the range and `NaN`s.
    pub fn total(&self) -> u64 {
        self.counts.iter().sum::<u64>() + self.below + self.above + self.nan
    }

    /// A multi-line ASCII bar chart, one line per bin (`[lo, hi)  count  ####`), bars scaled
    /// to at most `width` characters; out-of-range and `NaN` counts follow where non-zero.
    pub fn render(&self, width: usize) -> String {
        let peak = self.counts.iter().copied().max().unwrap_or(0).max(1);
        let cw = self.counts.iter().map(|c| c.to_string().len()).max().unwrap_or(1);
        let mut s = String::new();
        let last = self.counts.len() - 1;
        for (i, &c) in self.counts.iter().enumerate() {
            let bar = ((c as f64 / peak as f64) * width as f64).ceil() as usize;
            let close = if i == last { ']' } else { ')' };
            let _ = writeln!(
                s,
                "[{:>8}, {:>8}{close} {c:>cw$} {}",
                fmt_edge(self.edges[i]),
                fmt_edge(self.edges[i + 1]),
                "#".repeat(bar)
            );
        }
        for (what, c) in [("below", self.below), ("above", self.above), ("nan", self.nan)] {
            if c > 0 {
                let _ = writeln!(s, "{what} {c}");
            }
        }
        s
    }

    /// A one-line ASCII sparkline, one character per bin from ` ` (empty) through `.:-=+*#%`
    /// to `@` (the fullest bin); any non-empty bin shows at least `.`.
    pub fn sparkline(&self) -> String {
        const RAMP: &[u8] = b" .:-=+*#%@";
        let peak = self.counts.iter().copied().max().unwrap_or(0);
        self.counts
            .iter()
            .map(|&c| {
                if c == 0 || peak == 0 {
                    ' '
                } else {
                    let k = ((c as f64 / peak as f64) * (RAMP.len() - 1) as f64).ceil() as usize;
                    RAMP[k.clamp(1, RAMP.len() - 1)] as char
                }
            })
            .collect()
    }
}

fn fmt_edge(x: f64) -> String {
    if x == x.round() && x.abs() < 1e9 { format!("{x:.0}") } else { fmt_num(x) }
}

/// Number of elements per chunk in [`chunked_reduce`]; fixed, so that results do not depend
/// on the thread count.
pub const CHUNK: usize = 8192;

/// Maps each chunk `[start, end)` of `0..n` (chunks of [`CHUNK`] elements) to an accumulator
/// in parallel, then merges the accumulators sequentially in chunk order, starting from
/// `init`: deterministic for any thread count.
pub fn chunked_reduce<A, F, M>(n: usize, init: A, map: F, mut merge: M) -> A
where
    A: Send,
    F: Fn(usize, usize) -> A + Sync + Send,
    M: FnMut(&mut A, A),
{
    let chunks = n.div_ceil(CHUNK);
    let parts: Vec<A> = (0..chunks).into_par_iter().map(|c| map(c * CHUNK, ((c + 1) * CHUNK).min(n))).collect();
    let mut acc = init;
    for p in parts {
        merge(&mut acc, p);
    }
    acc
}

/// Neumaier-compensated running sum, for volumes and areas.
#[derive(Copy, Clone, Debug, Default)]
pub(crate) struct KahanSum {
    sum: f64,
    comp: f64,
}

impl KahanSum {
    #[inline]
    pub(crate) fn add(&mut self, x: f64) {
        let t = self.sum + x;
        if self.sum.abs() >= x.abs() {
            self.comp += (self.sum - t) + x;
        } else {
            self.comp += (x - t) + self.sum;
        }
        self.sum = t;
    }

    pub(crate) fn merge(&mut self, o: KahanSum) {
        self.add(o.sum);
        self.comp += o.comp;
    }

    pub(crate) fn value(&self) -> f64 {
        self.sum + self.comp
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stats_basic_and_edge_cases() {
        let s = Stats::of(&[2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0]);
        assert_eq!((s.count, s.mean, s.std_dev), (8, 5.0, 2.0));
        assert_eq!((s.min, s.argmin, s.max, s.argmax), (2.0, Some(0), 9.0, Some(7)));
        let e = Stats::of(&[]);
        assert_eq!((e.count, e.min, e.max, e.mean, e.argmin), (0, 0.0, 0.0, 0.0, None));
        let n = Stats::of(&[f64::NAN, 1.0, f64::NAN, 1.0]);
        assert_eq!((n.count, n.non_finite, n.min, n.argmin, n.argmax, n.mean), (4, 2, 1.0, Some(1), Some(1), 1.0));
        let only_nan = Stats::of(&[f64::NAN]);
        assert_eq!((only_nan.min, only_nan.argmin, only_nan.mean), (0.0, None, 0.0));
        let inf = Stats::of(&[f64::INFINITY, f64::INFINITY]);
        assert_eq!((inf.min, inf.argmin, inf.mean, inf.non_finite), (f64::INFINITY, Some(0), 0.0, 2));
        assert!(s.render().contains("(#7)"));
    }

    #[test]
    fn merge_matches_sequential() {
        let v: Vec<f64> = (0..1000).map(|i| ((i * 7919) % 1013) as f64 * 0.37 - 50.0).collect();
        let whole = Stats::of(&v);
        let mut a = StatsAccumulator::new();
        for chunk in (0..v.len()).collect::<Vec<_>>().chunks(77) {
            let mut c = StatsAccumulator::new();
            for &i in chunk {
                c.push(i, v[i]);
            }
            a.merge(&c);
        }
        let m = a.finish();
        assert_eq!((m.count, m.min, m.max, m.argmin, m.argmax), (whole.count, whole.min, whole.max, whole.argmin, whole.argmax));
        assert!((m.mean - whole.mean).abs() < 1e-12 && (m.std_dev - whole.std_dev).abs() < 1e-12);
        let mut e = StatsAccumulator::new();
        e.merge(&StatsAccumulator::new());
        assert_eq!(e.finish().argmin, None);
    }

    #[test]
    fn histogram_bins_and_rendering() {
        let mut h = Histogram::with_edges(vec![0.0, 5.0, 10.0, 20.0]);
        for x in [-1.0, 0.0, 4.9, 5.0, 19.0, 20.0, 20.5, f64::NAN] {
            h.add(x);
        }
        assert_eq!(h.counts, vec![2, 1, 2]);
        assert_eq!((h.below, h.above, h.nan, h.total()), (1, 1, 1, 8));
        let mut g = h.empty_like();
        g.merge(&h);
        g.merge(&h);
        assert_eq!(g.counts, vec![4, 2, 4]);
        let r = h.render(10);
        assert_eq!(r.lines().count(), 6, "{r}");
        assert!(r.contains("##########") && r.contains("below 1"));
        assert_eq!(h.sparkline(), "@+@");
        assert!(Histogram::try_with_edges(vec![0.0]).is_err());
        assert!(Histogram::try_with_edges(vec![0.0, f64::NAN]).is_err());
        assert!(Histogram::try_with_edges(vec![0.0, 2.0, 1.0]).is_err());
        let u = Histogram::uniform(0.0, 1.0, 3);
        assert_eq!(u.edges.len(), 4);
        assert_eq!(u.edges[3], 1.0);
    }

    #[test]
    #[should_panic]
    fn histogram_rejects_bad_edges() {
        let _ = Histogram::with_edges(vec![1.0, 1.0]);
    }

    #[test]
    fn chunked_reduce_is_ordered() {
        let n = CHUNK * 3 + 17;
        let v = chunked_reduce(n, Vec::new(), |a, b| vec![(a, b)], |acc, p| acc.extend(p));
        assert_eq!(v.len(), 4);
        assert_eq!(v[0], (0, CHUNK));
        assert_eq!(v[3], (3 * CHUNK, n));
        let mut k = KahanSum::default();
        for _ in 0..10 {
            k.add(0.1);
        }
        assert_eq!(k.value(), 1.0);
    }
}
