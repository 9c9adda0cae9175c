//! The few measures a mesh summary reports, in one lean pass over the tets: the extreme
//! dihedral angles and radius-edge ratio with the tets that reach them, the tets under 1°, 5°
//! and 10° and under a given angle, above a given radius-edge ratio, and the near-degenerate
//! ones.
//!
//! Stage: layer 3 (quality). Input: a [`TetMesh`] whose indices are in range. Output:
//! [`TetExtremes`].
//!
//! Every figure is bitwise the full report's ([`tet_mesh_quality`]): the same measures
//! ([`tet_summary_measures`]), the same rule for ties (the lowest tet index), and the same
//! handling of degenerate tets (`0°`/`180°`, an infinite radius-edge ratio). The angles come
//! from the extreme cosines, with an arc cosine only where a tet could change an extreme or
//! its cosine lies within 1e-9 of a count's limit: the angle is non-decreasing in the cosine. The full report
//! also computes five more measures, their means and deviations, an exact orientation and a
//! histogram bin per tet, which a summary does not print: on plc's 72,627 octree tets its pass
//! took 14 ms of the summary's 24 ms.
//!
//! Chunks of tets are measured in parallel and merged in order ([`chunked_reduce`]), so the
//! result is the same for any thread count.
//!
//! [`tet_mesh_quality`]: crate::quality::tet_mesh_quality

use crate::mesh::TetMesh;
use crate::quality::mesh_quality::NEAR_DEGENERATE_VOLUME_LENGTH;
use crate::quality::summary::chunked_reduce;
use crate::quality::tetrahedron::{dihedral_from_cosine, tet_summary_measures};

/// What [`tet_mesh_extremes`] measures.
#[derive(Clone, Debug, PartialEq)]
pub struct TetExtremes {
    /// Tets measured.
    pub tets: usize,
    /// The smallest dihedral angle (degrees; 0 without tets) and the first tet that has it.
    pub min_dihedral: (f64, Option<usize>),
    /// The largest dihedral angle (degrees; 0 without tets) and the first tet that has it.
    pub max_dihedral: (f64, Option<usize>),
    /// The largest radius-edge ratio (infinite where a tet is degenerate; 0 without tets)
    /// and the first tet that has it.
    pub max_radius_edge: (f64, Option<usize>),
    /// Tets whose smallest dihedral angle is under 1°, 5° and 10°.
    pub under: [usize; 3],
    /// Tets whose smallest dihedral angle is under the angle given.
    pub under_dihedral: usize,
    /// Tets whose radius-edge ratio is not at most the ratio given (a degenerate tet's is
    /// infinite).
    pub above_radius_edge: usize,
    /// Tets whose volume-length ratio is under [`NEAR_DEGENERATE_VOLUME_LENGTH`].
    pub near_degenerate: usize,
    /// The tets whose smallest dihedral angle is under the angle given or under 10°, whichever
    /// is larger (ascending): those `explained_among`
    /// needs to look at.
    pub low: Vec<usize>,
}

/// A running extreme: the value and the lowest index that has it (`None` until one is given).
#[derive(Clone, Copy)]
struct Extreme {
    value: f64,
    at: Option<usize>,
}

impl Extreme {
    const NONE: Extreme = Extreme { value: 0.0, at: None };

    /// Takes `(v, i)` where `v` beats the value by `better` (the indices come in order, so a
    /// tie keeps the lower one). `NaN` is never taken.
    #[inline]
    fn offer(&mut self, v: f64, i: usize, better: impl Fn(f64, f64) -> bool) {
        if !v.is_nan() && (self.at.is_none() || better(v, self.value)) {
            *self = Extreme { value: v, at: Some(i) };
        }
    }

    fn pair(self) -> (f64, Option<usize>) {
        (self.value, self.at)
    }
}

/// A running extreme dihedral angle, fed cosines in tet order: the angle of a cosine is taken
/// only where it could beat the extreme. The angle is non-decreasing in the cosine, so a
/// cosine on the far side of `cosine` (the cosine of the extreme so far, or one with the same
/// angle) cannot beat it; `NaN` there (a degenerate tet holds the extreme) makes every cosine
/// be measured.
#[derive(Clone, Copy)]
struct AngleExtreme {
    best: Extreme,
    cosine: f64,
    /// Whether this is the largest angle (else the smallest).
    largest: bool,
}

impl AngleExtreme {
    fn new(largest: bool) -> AngleExtreme {
        AngleExtreme { best: Extreme::NONE, cosine: f64::NAN, largest }
    }

    /// Whether `a` beats `b` for the largest angle (`largest`) or the smallest.
    fn better(largest: bool, a: f64, b: f64) -> bool {
        if largest { a > b } else { a < b }
    }

    /// Tet `i`, its extreme cosine `c` (`None`: degenerate, the angle `degenerate`).
    #[inline]
    fn offer(&mut self, c: Option<f64>, degenerate: f64, i: usize) {
        let Some(c) = c else {
            if self.best.at.is_none() || Self::better(self.largest, degenerate, self.best.value) {
                self.best = Extreme { value: degenerate, at: Some(i) };
                self.cosine = f64::NAN;
            }
            return;
        };
        let beyond = if self.largest { c <= self.cosine } else { c >= self.cosine };
        if self.best.at.is_some() && beyond {
            return;
        }
        let a = dihedral_from_cosine(c);
        if self.best.at.is_none() || Self::better(self.largest, a, self.best.value) {
            self.best = Extreme { value: a, at: Some(i) };
            self.cosine = c;
        } else if a == self.best.value {
            // the same angle: the lower tet keeps it, this cosine bounds the later ones
            self.cosine = c;
        }
    }

    /// Merges the extreme of the chunk that follows (a tie keeps this one's tet).
    fn merge(&mut self, o: AngleExtreme) {
        if let Some(i) = o.best.at {
            let largest = self.largest;
            self.best.offer(o.best.value, i, |a, b| Self::better(largest, a, b));
        }
    }
}

/// Decides `dihedral_from_cosine(c) < limit` mostly from the cosine: surely under below
/// `under`, surely not above `not_under`, measured between them (a margin of 1e-9 in the
/// cosine covers the rounding of the angle, under 1e-13 degrees, many times over).
#[derive(Clone, Copy)]
struct UnderLimit {
    limit: f64,
    under: f64,
    not_under: f64,
}

impl UnderLimit {
    fn new(limit: f64) -> UnderLimit {
        if limit > 0.0 && limit < 180.0 {
            let c = (180.0 - limit).to_radians().cos();
            UnderLimit { limit, under: c - 1e-9, not_under: c + 1e-9 }
        } else {
            // every cosine is measured
            UnderLimit { limit, under: f64::NEG_INFINITY, not_under: f64::INFINITY }
        }
    }

    /// Whether the smallest angle, of least cosine `c` (`None`: degenerate, 0°), is under
    /// the limit.
    #[inline]
    fn holds(&self, c: Option<f64>) -> bool {
        match c {
            None => 0.0 < self.limit,
            Some(c) if c < self.under => true,
            Some(c) if c > self.not_under => false,
            Some(c) => dihedral_from_cosine(c) < self.limit,
        }
    }
}

fn greater(a: f64, b: f64) -> bool {
    a > b
}

/// One chunk's figures; chunks are merged in index order.
struct Acc {
    min: AngleExtreme,
    max: AngleExtreme,
    re: Extreme,
    under: [usize; 3],
    under_dihedral: usize,
    above_radius_edge: usize,
    near_degenerate: usize,
    low: Vec<usize>,
}

impl Acc {
    fn new() -> Acc {
        Acc { min: AngleExtreme::new(false), max: AngleExtreme::new(true), re: Extreme::NONE, under: [0; 3], under_dihedral: 0, above_radius_edge: 0, near_degenerate: 0, low: Vec::new() }
    }

    /// Merges the chunk `o` that follows this one.
    fn merge(&mut self, o: Acc) {
        self.min.merge(o.min);
        self.max.merge(o.max);
        if let Some(i) = o.re.at {
            self.re.offer(o.re.value, i, greater);
        }
        for k in 0..3 {
            self.under[k] += o.under[k];
        }
        self.under_dihedral += o.under_dihedral;
        self.above_radius_edge += o.above_radius_edge;
        self.near_degenerate += o.near_degenerate;
        self.low.extend(o.low);
    }
}

/// The extremes and counts of `m`'s tets (see [`TetExtremes`]), with the tets under
/// `dihedral` degrees and above radius-edge `radius_edge` (the bounds a mesher aimed at).
///
/// Tets with out-of-range indices are outside the contract (they panic); call
/// [`TetMesh::validate`] first on untrusted input.
///
/// ```
/// use fepre::mesh::TetMesh;
/// use fepre::quality::tet_mesh_extremes;
/// use glam::DVec3;
/// let m = TetMesh { vertices: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z], tets: vec![[0, 1, 2, 3]], ..Default::default() };
/// let e = tet_mesh_extremes(&m, 60.0, 2.0);
/// assert_eq!((e.max_dihedral.0, e.max_dihedral.1), (90.0, Some(0)));
/// assert_eq!((e.under_dihedral, e.above_radius_edge), (1, 0));
/// ```
pub fn tet_mesh_extremes(m: &TetMesh, dihedral: f64, radius_edge: f64) -> TetExtremes {
    let limits = [1.0, 5.0, 10.0, dihedral].map(UnderLimit::new);
    let low = UnderLimit::new(dihedral.max(10.0));
    let acc = chunked_reduce(
        m.tets.len(),
        Acc::new(),
        |a, b| {
            let mut acc = Acc::new();
            for t in a..b {
                let p = m.tets[t].map(|i| m.vertices[i as usize]);
                let (cosines, re, volume_length) = tet_summary_measures(&p);
                let (lo, hi) = (cosines.map(|c| c.0), cosines.map(|c| c.1));
                acc.min.offer(lo, 0.0, t);
                acc.max.offer(hi, 180.0, t);
                acc.re.offer(re, t, greater);
                for (n, limit) in acc.under.iter_mut().zip(&limits) {
                    *n += usize::from(limit.holds(lo));
                }
                acc.under_dihedral += usize::from(limits[3].holds(lo));
                acc.above_radius_edge += usize::from(!(re <= radius_edge));
                acc.near_degenerate += usize::from(!(volume_length >= NEAR_DEGENERATE_VOLUME_LENGTH));
                if low.holds(lo) {
                    acc.low.push(t);
                }
            }
            acc
        },
        |acc, part| acc.merge(part),
    );
    TetExtremes {
        tets: m.tets.len(),
        min_dihedral: acc.min.best.pair(),
        max_dihedral: acc.max.best.pair(),
        max_radius_edge: acc.re.pair(),
        under: acc.under,
        under_dihedral: acc.under_dihedral,
        above_radius_edge: acc.above_radius_edge,
        near_degenerate: acc.near_degenerate,
        low: acc.low,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::spatial_order::XorShift;
    use crate::quality::tet_mesh_quality;
    use crate::quality::tetrahedron::tet_measures;
    use glam::DVec3;

    /// Random tets (some flat, some repeated so that extremes tie, some with a repeated
    /// vertex), more than one chunk of them.
    fn soup(n: usize) -> TetMesh {
        let mut rng = XorShift::new(11);
        let mut r = || (rng.next_u64() % 1000) as f64 / 1000.0;
        let mut vertices = Vec::new();
        let mut tets = Vec::new();
        for t in 0..n {
            let base = vertices.len() as u32;
            match t % 97 {
                // flat: four points in a plane
                13 => vertices.extend([DVec3::new(r(), r(), 0.5), DVec3::new(r(), r(), 0.5), DVec3::new(r(), r(), 0.5), DVec3::new(r(), r(), 0.5)]),
                // a repeated vertex
                41 => {
                    let a = DVec3::new(r(), r(), r());
                    vertices.extend([a, a, DVec3::new(r(), r(), r()), DVec3::new(r(), r(), r())]);
                }
                _ => vertices.extend((0..4).map(|_| DVec3::new(r(), r(), r()))),
            }
            tets.push([base, base + 1, base + 2, base + 3]);
            if t % 211 == 5 {
                // the same tet again: ties at whatever it measures
                tets.push([base, base + 1, base + 2, base + 3]);
            }
        }
        let region_tags = vec![Default::default(); tets.len()];
        TetMesh { vertices, tets, region_tags, ..Default::default() }
    }

    #[test]
    fn the_extremes_are_the_full_reports() {
        for n in [0, 1, 500, 70_000] {
            let m = soup(n);
            let e = tet_mesh_extremes(&m, 18.0, 1.5);
            let q = tet_mesh_quality(&m);
            assert_eq!(e.tets, q.tets);
            assert_eq!(e.min_dihedral, (q.min_dihedral.min, q.min_dihedral.argmin), "{n}");
            assert_eq!(e.max_dihedral, (q.max_dihedral.max, q.max_dihedral.argmax), "{n}");
            assert_eq!(e.max_radius_edge, (q.max_radius_edge, q.radius_edge.argmax), "{n}");
            assert_eq!(e.max_radius_edge.0.to_bits(), q.radius_edge.max.to_bits());
            assert_eq!(e.under, [q.tets_min_dihedral_below_1, q.tets_min_dihedral_below_5, q.tets_min_dihedral_below_10], "{n}");
            assert_eq!(e.near_degenerate, q.near_degenerate, "{n}");
            // the counts against the bounds, tet by tet
            let measures: Vec<_> = m.tets.iter().map(|t| tet_measures(&t.map(|v| m.vertices[v as usize]))).collect();
            assert_eq!(e.under_dihedral, measures.iter().filter(|x| x.min_dihedral < 18.0).count());
            assert_eq!(e.above_radius_edge, measures.iter().filter(|x| !(x.radius_edge <= 1.5)).count());
            // the tets under the larger of the bound and 10°, ascending, for the explained counts
            let low: Vec<usize> = (0..m.tets.len()).filter(|&t| measures[t].min_dihedral < 18.0).collect();
            assert_eq!(e.low, low, "{n}");
            let e5 = tet_mesh_extremes(&m, 5.0, 1.5);
            assert_eq!(e5.low, (0..m.tets.len()).filter(|&t| measures[t].min_dihedral < 10.0).collect::<Vec<_>>(), "{n}");
            if n > 97 {
                // the soup's flat tets and repeated vertices
                assert!(e.near_degenerate > 0 && e.max_radius_edge.0 == f64::INFINITY && e.min_dihedral.0 == 0.0, "{n}: {e:?}");
            }
        }
    }

    #[test]
    fn the_cosine_tests_decide_as_the_angles() {
        let mut rng = XorShift::new(5);
        for limit in [1.0, 5.0, 10.0, 18.0, 0.0, -3.0, 180.0, 200.0] {
            let u = UnderLimit::new(limit);
            let at = (180.0f64 - limit).to_radians().cos();
            let near = (-4000..4000).map(|k| at + k as f64 * 1e-12);
            let spread = (0..4000).map(|_| (rng.next_u64() % 2_000_001) as f64 / 1e6 - 1.0);
            for c in near.chain(spread).chain([-1.0, 1.0]).filter(|c| (-1.0..=1.0).contains(c)) {
                assert_eq!(u.holds(Some(c)), dihedral_from_cosine(c) < limit, "{limit}° at {c}");
            }
            assert_eq!(u.holds(None), 0.0 < limit);
        }
    }

    #[test]
    fn ties_go_to_the_lowest_tet() {
        let v = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
        let m = TetMesh { vertices: v, tets: vec![[0, 1, 2, 3]; 3], region_tags: vec![Default::default(); 3], ..Default::default() };
        let e = tet_mesh_extremes(&m, 0.0, f64::INFINITY);
        assert_eq!((e.min_dihedral.1, e.max_dihedral.1, e.max_radius_edge.1), (Some(0), Some(0), Some(0)));
        assert_eq!((e.under_dihedral, e.above_radius_edge), (0, 0));
    }
}
