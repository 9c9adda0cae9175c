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
//! handling of degenerate tets (`0°`/`180°`, an infinite radius-edge ratio). The full report
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
use crate::quality::tetrahedron::tet_summary_measures;

/// What [`tet_mesh_extremes`] measures.
#[derive(Clone, Copy, Debug, PartialEq)]
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

fn less(a: f64, b: f64) -> bool {
    a < b
}

fn greater(a: f64, b: f64) -> bool {
    a > b
}

/// One chunk's figures; chunks are merged in index order.
struct Acc {
    min: Extreme,
    max: Extreme,
    re: Extreme,
    under: [usize; 3],
    under_dihedral: usize,
    above_radius_edge: usize,
    near_degenerate: usize,
}

impl Acc {
    fn new() -> Acc {
        Acc { min: Extreme::NONE, max: Extreme::NONE, re: Extreme::NONE, under: [0; 3], under_dihedral: 0, above_radius_edge: 0, near_degenerate: 0 }
    }

    /// Merges the chunk `o` that follows this one.
    fn merge(&mut self, o: Acc) {
        for (mine, theirs, better) in [(&mut self.min, o.min, less as fn(f64, f64) -> bool), (&mut self.max, o.max, greater), (&mut self.re, o.re, greater)] {
            if let Some(i) = theirs.at {
                mine.offer(theirs.value, i, better);
            }
        }
        for k in 0..3 {
            self.under[k] += o.under[k];
        }
        self.under_dihedral += o.under_dihedral;
        self.above_radius_edge += o.above_radius_edge;
        self.near_degenerate += o.near_degenerate;
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
/// use fepre::quality::extremes::tet_mesh_extremes;
/// use glam::DVec3;
/// let m = TetMesh { vertices: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z], tets: vec![[0, 1, 2, 3]], ..Default::default() };
/// let e = tet_mesh_extremes(&m, 60.0, 2.0);
/// assert_eq!((e.max_dihedral.0, e.max_dihedral.1), (90.0, Some(0)));
/// assert_eq!((e.under_dihedral, e.above_radius_edge), (1, 0));
/// ```
pub fn tet_mesh_extremes(m: &TetMesh, dihedral: f64, radius_edge: f64) -> TetExtremes {
    let acc = chunked_reduce(
        m.tets.len(),
        Acc::new(),
        |a, b| {
            let mut acc = Acc::new();
            for t in a..b {
                let p = m.tets[t].map(|i| m.vertices[i as usize]);
                let (lo, hi, re, volume_length) = tet_summary_measures(&p);
                acc.min.offer(lo, t, less);
                acc.max.offer(hi, t, greater);
                acc.re.offer(re, t, greater);
                for (k, limit) in [1.0, 5.0, 10.0].into_iter().enumerate() {
                    acc.under[k] += usize::from(lo < limit);
                }
                acc.under_dihedral += usize::from(lo < dihedral);
                acc.above_radius_edge += usize::from(!(re <= radius_edge));
                acc.near_degenerate += usize::from(!(volume_length >= NEAR_DEGENERATE_VOLUME_LENGTH));
            }
            acc
        },
        |acc, part| acc.merge(part),
    );
    TetExtremes {
        tets: m.tets.len(),
        min_dihedral: acc.min.pair(),
        max_dihedral: acc.max.pair(),
        max_radius_edge: acc.re.pair(),
        under: acc.under,
        under_dihedral: acc.under_dihedral,
        above_radius_edge: acc.above_radius_edge,
        near_degenerate: acc.near_degenerate,
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
            if n > 97 {
                // the soup's flat tets and repeated vertices
                assert!(e.near_degenerate > 0 && e.max_radius_edge.0 == f64::INFINITY && e.min_dihedral.0 == 0.0, "{n}: {e:?}");
            }
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
