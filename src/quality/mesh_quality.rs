//! Whole-mesh quality reports for [`TetMesh`], [`TriSurface`] and [`PlanarMesh`].
//!
//! Each report gathers the per-element measures of [`crate::quality::tetrahedron`],
//! [`crate::quality::triangle`] and [`crate::quality::quad`] into [`Stats`], threshold counts
//! and an angle [`Histogram`]. Elements are processed in parallel in fixed-size chunks merged
//! in order ([`chunked_reduce`]), so a report is identical for any thread count. Orientation
//! (inverted, degenerate, non-convex) is decided with the exact predicates.
//!
//! The headline fields of [`TetQualityReport`] are those of the reference judge
//! (`shared/tools/cgal_ref/tetquality`), computed with the same formulas, except that
//! `inverted` uses the exact `orient3d` rather than the sign of the rounded volume.

use crate::core::Sign;
use crate::core::predicates::{orient2d, orient3d};
use crate::mesh::{PlanarMesh, TetMesh, TriSurface};
use crate::quality::quad::{QuadMeasures, quad_angles, quad_measures};
use crate::quality::summary::{Histogram, KahanSum, Stats, StatsAccumulator, chunked_reduce};
use crate::quality::tetrahedron::{TetMeasures, dihedral_from_cosine, tet_measures_and_cosines};
use crate::quality::triangle::{TriMeasures, tri_angles, tri_measures, tri_measures_2d};
use glam::{DVec2, DVec3};
use serde::Serialize;
use std::fmt::Write as _;

/// Bin edges (degrees) of the dihedral-angle histogram: finer near the bad ends.
pub const DIHEDRAL_EDGES: [f64; 21] =
    [0.0, 5.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0, 90.0, 100.0, 110.0, 120.0, 130.0, 140.0, 150.0, 160.0, 170.0, 175.0, 180.0];

/// Radius-edge threshold for the "over √2" count, as TetGen's `-q1.414` and the reference
/// judge use it.
pub const RADIUS_EDGE_SQRT2: f64 = 1.414;

/// A tet is near-degenerate when its volume-length ratio `6√2 |V| / l_rms³` is below this:
/// its volume is under 0.1 % of a regular tet's with the same root-mean-square edge, flat to
/// the eye (a sliver of four nearly coplanar points has a smallest dihedral angle of about
/// 0.06°; the ratio is about 0.016 per degree for slivers and caps).
pub const NEAR_DEGENERATE_VOLUME_LENGTH: f64 = 1e-3;

/// Quality report of a tetrahedral mesh (see [`tet_mesh_quality`]).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TetQualityReport {
    /// Number of vertices.
    pub vertices: usize,
    /// Number of tetrahedra.
    pub tets: usize,
    /// Sum of the signed tet volumes (compensated summation).
    pub volume: f64,
    /// Tets whose orientation is not `Positive`, decided exactly.
    pub inverted: usize,
    /// Exactly degenerate tets (zero computed determinant, zero edge or zero face): they have
    /// no dihedral angles in the histogram and count with min 0° / max 180°. Flat slivers of
    /// nearly coplanar points are not counted here: see [`TetQualityReport::near_degenerate`].
    pub degenerate: usize,
    /// Near-degenerate tets: volume-length ratio below `NEAR_DEGENERATE_VOLUME_LENGTH`
    /// (the exactly degenerate ones included).
    pub near_degenerate: usize,
    /// Smallest dihedral angle of the mesh (degrees).
    pub min_dihedral_deg: f64,
    /// Largest dihedral angle of the mesh (degrees).
    pub max_dihedral_deg: f64,
    /// Largest circumradius-to-shortest-edge ratio.
    pub max_radius_edge: f64,
    /// Mean radius-edge ratio over all tets (`+∞` if any tet is degenerate).
    pub mean_radius_edge: f64,
    /// Smallest volume-length ratio.
    pub min_volume_length: f64,
    /// Tets with a dihedral angle below 1°.
    pub tets_min_dihedral_below_1: usize,
    /// Tets with a dihedral angle below 5°.
    pub tets_min_dihedral_below_5: usize,
    /// Tets with a dihedral angle below 10°.
    pub tets_min_dihedral_below_10: usize,
    /// Tets with a dihedral angle below 20°.
    pub tets_min_dihedral_below_20: usize,
    /// Tets with radius-edge ratio above `RADIUS_EDGE_SQRT2` (1.414).
    pub tets_radius_edge_over_sqrt2: usize,
    /// Tets with radius-edge ratio above 2.
    pub tets_radius_edge_over_2: usize,
    /// Per-tet smallest dihedral angle.
    pub min_dihedral: Stats,
    /// Per-tet largest dihedral angle.
    pub max_dihedral: Stats,
    /// Radius-edge ratio.
    pub radius_edge: Stats,
    /// Verdict radius ratio.
    pub radius_ratio: Stats,
    /// Verdict scaled Jacobian.
    pub scaled_jacobian: Stats,
    /// Volume-length ratio.
    pub volume_length: Stats,
    /// Verdict aspect ratio.
    pub aspect_ratio: Stats,
    /// Edge ratio.
    pub edge_ratio: Stats,
    /// Signed tet volume.
    pub tet_volume: Stats,
    /// All six dihedral angles of every non-degenerate tet, over `DIHEDRAL_EDGES`.
    pub dihedral_histogram: Histogram,
}

/// Bins dihedral angles by their cosines, with no `acos`: `thresholds[i]` is the smallest
/// cosine whose [`dihedral_from_cosine`] reaches `edges[i]`, found by bisection over the
/// doubles (the angle is monotone in the cosine), so the bin is exactly the one
/// [`Histogram::add`] would pick for the angle itself.
#[derive(Clone, Debug)]
pub(crate) struct CosineBins {
    thresholds: Vec<f64>,
}

/// Doubles in `[-1, 1]` to order-preserving integers and back.
fn ordered(x: f64) -> i64 {
    let b = x.to_bits() as i64;
    if b < 0 { i64::MIN - b } else { b }
}

fn unordered(k: i64) -> f64 {
    f64::from_bits((if k < 0 { i64::MIN - k } else { k }) as u64)
}

impl CosineBins {
    pub(crate) fn new(edges: &[f64]) -> CosineBins {
        let thresholds = edges
            .iter()
            .map(|&e| {
                if dihedral_from_cosine(-1.0) >= e {
                    return -1.0;
                }
                if dihedral_from_cosine(1.0) < e {
                    return f64::INFINITY;
                }
                // invariant: angle(lo) < e <= angle(hi)
                let (mut lo, mut hi) = (ordered(-1.0), ordered(1.0));
                while hi - lo > 1 {
                    let mid = lo + (hi - lo) / 2;
                    if dihedral_from_cosine(unordered(mid)) >= e { hi = mid } else { lo = mid }
                }
                unordered(hi)
            })
            .collect();
        CosineBins { thresholds }
    }

    /// Counts the angle whose cosine is `c` into `h` (which must have the edges given to
    /// [`CosineBins::new`]).
    #[inline]
    pub(crate) fn add(&self, h: &mut Histogram, c: f64) {
        let t = &self.thresholds;
        let last = t.len() - 1;
        if c.is_nan() {
            h.nan += 1;
        } else if c < t[0] {
            h.below += 1;
        } else if c >= t[last] {
            // the angle is the last edge exactly (the last bin is closed) or above it
            if dihedral_from_cosine(c) == h.edges[last] { h.counts[last - 1] += 1 } else { h.above += 1 }
        } else {
            h.counts[t.partition_point(|&x| x <= c) - 1] += 1;
        }
    }
}

struct TetAcc {
    volume: KahanSum,
    radius_edge_sum: f64,
    inverted: usize,
    degenerate: usize,
    near_degenerate: usize,
    below: [usize; 4],
    over: [usize; 2],
    stats: [StatsAccumulator; 9],
    hist: Histogram,
}

impl TetAcc {
    fn new() -> TetAcc {
        TetAcc {
            volume: KahanSum::default(),
            radius_edge_sum: 0.0,
            inverted: 0,
            degenerate: 0,
            near_degenerate: 0,
            below: [0; 4],
            over: [0; 2],
            stats: std::array::from_fn(|_| StatsAccumulator::new()),
            hist: Histogram::with_edges(DIHEDRAL_EDGES.to_vec()),
        }
    }

    fn push(&mut self, t: usize, p: &[DVec3; 4], bins: &CosineBins) {
        let (m, cosines): (TetMeasures, _) = tet_measures_and_cosines(p);
        if orient3d(p[0], p[1], p[2], p[3]) != Sign::Positive {
            self.inverted += 1;
        }
        match cosines {
            Some(c) => c.iter().for_each(|&x| bins.add(&mut self.hist, x)),
            None => self.degenerate += 1,
        }
        self.volume.add(m.volume);
        self.radius_edge_sum += m.radius_edge;
        for (k, lim) in [1.0, 5.0, 10.0, 20.0].into_iter().enumerate() {
            self.below[k] += usize::from(m.min_dihedral < lim);
        }
        self.near_degenerate += usize::from(!(m.volume_length >= NEAR_DEGENERATE_VOLUME_LENGTH));
        self.over[0] += usize::from(m.radius_edge > RADIUS_EDGE_SQRT2);
        self.over[1] += usize::from(m.radius_edge > 2.0);
        let v = [
            m.min_dihedral,
            m.max_dihedral,
            m.radius_edge,
            m.radius_ratio,
            m.scaled_jacobian,
            m.volume_length,
            m.aspect_ratio,
            m.edge_ratio,
            m.volume,
        ];
        for (s, x) in self.stats.iter_mut().zip(v) {
            s.push(t, x);
        }
    }

    fn merge(&mut self, o: TetAcc) {
        self.volume.merge(o.volume);
        self.radius_edge_sum += o.radius_edge_sum;
        self.inverted += o.inverted;
        self.degenerate += o.degenerate;
        self.near_degenerate += o.near_degenerate;
        for k in 0..4 {
            self.below[k] += o.below[k];
        }
        for k in 0..2 {
            self.over[k] += o.over[k];
        }
        for (a, b) in self.stats.iter_mut().zip(&o.stats) {
            a.merge(b);
        }
        self.hist.merge(&o.hist);
    }
}

/// The quality report of a tet mesh: measures of every tet, in parallel, deterministic.
///
/// Tets with out-of-range indices are outside the contract (they panic); call
/// [`TetMesh::validate`] first on untrusted input.
///
/// ```
/// use fepre::mesh::TetMesh;
/// use fepre::quality::tet_mesh_quality;
/// use glam::DVec3;
/// let m = TetMesh { vertices: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z], tets: vec![[0, 1, 2, 3]], ..Default::default() };
/// let r = tet_mesh_quality(&m);
/// assert_eq!((r.tets, r.inverted), (1, 0));
/// assert!((r.max_dihedral_deg - 90.0).abs() < 1e-12);
/// ```
/// A mesh summary that needs only the extremes and a few counts gets them in a leaner pass:
/// `crate::quality::extremes::tet_mesh_extremes`.
pub fn tet_mesh_quality(m: &TetMesh) -> TetQualityReport {
    let bins = CosineBins::new(&DIHEDRAL_EDGES);
    let acc = chunked_reduce(
        m.tets.len(),
        TetAcc::new(),
        |a, b| {
            let mut acc = TetAcc::new();
            for t in a..b {
                let p = m.tets[t].map(|i| m.vertices[i as usize]);
                acc.push(t, &p, &bins);
            }
            acc
        },
        |acc, part| acc.merge(part),
    );
    let s: Vec<Stats> = acc.stats.iter().map(|s| s.finish()).collect();
    let n = m.tets.len();
    let report = TetQualityReport {
        vertices: m.vertices.len(),
        tets: n,
        volume: acc.volume.value(),
        inverted: acc.inverted,
        degenerate: acc.degenerate,
        near_degenerate: acc.near_degenerate,
        min_dihedral_deg: s[0].min,
        max_dihedral_deg: s[1].max,
        max_radius_edge: s[2].max,
        mean_radius_edge: if n == 0 { 0.0 } else { acc.radius_edge_sum / n as f64 },
        min_volume_length: s[5].min,
        tets_min_dihedral_below_1: acc.below[0],
        tets_min_dihedral_below_5: acc.below[1],
        tets_min_dihedral_below_10: acc.below[2],
        tets_min_dihedral_below_20: acc.below[3],
        tets_radius_edge_over_sqrt2: acc.over[0],
        tets_radius_edge_over_2: acc.over[1],
        min_dihedral: s[0].clone(),
        max_dihedral: s[1].clone(),
        radius_edge: s[2].clone(),
        radius_ratio: s[3].clone(),
        scaled_jacobian: s[4].clone(),
        volume_length: s[5].clone(),
        aspect_ratio: s[6].clone(),
        edge_ratio: s[7].clone(),
        tet_volume: s[8].clone(),
        dihedral_histogram: acc.hist,
    };
    report
}

impl TetQualityReport {
    /// Plain-text rendering for the CLI: `key value` lines in the reference judge's style,
    /// then one line of statistics per measure and the dihedral histogram.
    pub fn render(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "vertices {}", self.vertices);
        let _ = writeln!(s, "tets {}", self.tets);
        let _ = writeln!(s, "volume {:.9}", self.volume);
        let _ = writeln!(s, "inverted {}", self.inverted);
        let _ = writeln!(s, "degenerate_exact {}", self.degenerate);
        let _ = writeln!(s, "near_degenerate {} (volume-length under {NEAR_DEGENERATE_VOLUME_LENGTH})", self.near_degenerate);
        let _ = writeln!(s, "min_dihedral_deg {:.4}", self.min_dihedral_deg);
        let _ = writeln!(s, "max_dihedral_deg {:.4}", self.max_dihedral_deg);
        let _ = writeln!(s, "max_radius_edge_ratio {:.4}", self.max_radius_edge);
        let _ = writeln!(s, "mean_radius_edge_ratio {:.4}", self.mean_radius_edge);
        let _ = writeln!(s, "tets_radius_edge_over_1.414 {}", self.tets_radius_edge_over_sqrt2);
        let _ = writeln!(s, "tets_radius_edge_over_2 {}", self.tets_radius_edge_over_2);
        let _ = writeln!(s, "min_vol_length_quality {:.5}", self.min_volume_length);
        let _ = writeln!(s, "tets_min_dihedral_below_1 {}", self.tets_min_dihedral_below_1);
        let _ = writeln!(s, "tets_min_dihedral_below_5 {}", self.tets_min_dihedral_below_5);
        let _ = writeln!(s, "tets_min_dihedral_below_10 {}", self.tets_min_dihedral_below_10);
        let _ = writeln!(s, "tets_min_dihedral_below_20 {}", self.tets_min_dihedral_below_20);
        for (name, st) in [
            ("min dihedral", &self.min_dihedral),
            ("max dihedral", &self.max_dihedral),
            ("radius-edge", &self.radius_edge),
            ("radius ratio", &self.radius_ratio),
            ("scaled Jacobian", &self.scaled_jacobian),
            ("volume-length", &self.volume_length),
            ("aspect ratio", &self.aspect_ratio),
            ("edge ratio", &self.edge_ratio),
            ("tet volume", &self.tet_volume),
        ] {
            let _ = writeln!(s, "{name:>16}: {}", st.render());
        }
        let _ = writeln!(s, "dihedral angles (deg):");
        s.push_str(&self.dihedral_histogram.render(40));
        s
    }
}

/// Quality report of a triangle mesh, in space ([`tri_surface_quality`]) or in the plane
/// (the triangles of [`planar_mesh_quality`]).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TriQualityReport {
    /// Number of triangles.
    pub triangles: usize,
    /// Sum of the triangle areas (signed in the plane).
    pub area: f64,
    /// Triangles whose corners are exactly collinear (or coincide).
    pub degenerate: usize,
    /// Plane only: clockwise triangles (exact); always 0 in space.
    pub inverted: usize,
    /// Smallest angle of the mesh (degrees).
    pub min_angle_deg: f64,
    /// Largest angle of the mesh (degrees).
    pub max_angle_deg: f64,
    /// Triangles with an angle below 10°.
    pub triangles_min_angle_below_10: usize,
    /// Triangles with an angle below 20°.
    pub triangles_min_angle_below_20: usize,
    /// Triangles with an angle below 30°.
    pub triangles_min_angle_below_30: usize,
    /// Per-triangle smallest angle.
    pub min_angle: Stats,
    /// Per-triangle largest angle.
    pub max_angle: Stats,
    /// Verdict aspect ratio.
    pub aspect_ratio: Stats,
    /// Verdict radius ratio.
    pub radius_ratio: Stats,
    /// Verdict scaled Jacobian.
    pub scaled_jacobian: Stats,
    /// Edge ratio.
    pub edge_ratio: Stats,
    /// Triangle area.
    pub triangle_area: Stats,
    /// All three angles of every non-degenerate triangle, 18 bins of 10° over `[0, 180]`.
    pub angle_histogram: Histogram,
}

struct TriAcc {
    area: KahanSum,
    degenerate: usize,
    inverted: usize,
    below: [usize; 3],
    stats: [StatsAccumulator; 7],
    hist: Histogram,
}

impl TriAcc {
    fn new() -> TriAcc {
        TriAcc {
            area: KahanSum::default(),
            degenerate: 0,
            inverted: 0,
            below: [0; 3],
            stats: std::array::from_fn(|_| StatsAccumulator::new()),
            hist: Histogram::uniform(0.0, 180.0, 18),
        }
    }

    fn push(&mut self, t: usize, m: &TriMeasures, angles: Option<[f64; 3]>, degenerate: bool, inverted: bool) {
        self.area.add(m.area);
        self.degenerate += usize::from(degenerate);
        self.inverted += usize::from(inverted);
        if let Some(a) = angles {
            a.iter().for_each(|&x| self.hist.add(x));
        }
        for (k, lim) in [10.0, 20.0, 30.0].into_iter().enumerate() {
            self.below[k] += usize::from(m.min_angle < lim);
        }
        let v = [m.min_angle, m.max_angle, m.aspect_ratio, m.radius_ratio, m.scaled_jacobian, m.edge_ratio, m.area];
        for (s, x) in self.stats.iter_mut().zip(v) {
            s.push(t, x);
        }
    }

    fn merge(&mut self, o: TriAcc) {
        self.area.merge(o.area);
        self.degenerate += o.degenerate;
        self.inverted += o.inverted;
        for k in 0..3 {
            self.below[k] += o.below[k];
        }
        for (a, b) in self.stats.iter_mut().zip(&o.stats) {
            a.merge(b);
        }
        self.hist.merge(&o.hist);
    }

    fn finish(self, n: usize) -> TriQualityReport {
        let s: Vec<Stats> = self.stats.iter().map(|s| s.finish()).collect();
        TriQualityReport {
            triangles: n,
            area: self.area.value(),
            degenerate: self.degenerate,
            inverted: self.inverted,
            min_angle_deg: s[0].min,
            max_angle_deg: s[1].max,
            triangles_min_angle_below_10: self.below[0],
            triangles_min_angle_below_20: self.below[1],
            triangles_min_angle_below_30: self.below[2],
            min_angle: s[0].clone(),
            max_angle: s[1].clone(),
            aspect_ratio: s[2].clone(),
            radius_ratio: s[3].clone(),
            scaled_jacobian: s[4].clone(),
            edge_ratio: s[5].clone(),
            triangle_area: s[6].clone(),
            angle_histogram: self.hist,
        }
    }
}

/// Whether three points in space are exactly collinear: all three coordinate projections are.
fn collinear3(p: &[DVec3; 3]) -> bool {
    let proj = |f: fn(DVec3) -> DVec2| orient2d(f(p[0]), f(p[1]), f(p[2])) == Sign::Zero;
    proj(|v| DVec2::new(v.x, v.y)) && proj(|v| DVec2::new(v.y, v.z)) && proj(|v| DVec2::new(v.z, v.x))
}

/// The quality report of a triangle surface (areas and scaled Jacobians non-negative).
pub fn tri_surface_quality(s: &TriSurface) -> TriQualityReport {
    let n = s.triangles.len();
    chunked_reduce(
        n,
        TriAcc::new(),
        |a, b| {
            let mut acc = TriAcc::new();
            for t in a..b {
                let p = s.corners(t);
                let m = tri_measures(&p);
                acc.push(t, &m, tri_angles(&p), collinear3(&p), false);
            }
            acc
        },
        |acc, part| acc.merge(part),
    )
    .finish(n)
}

/// Quality report of the quadrilaterals of a planar mesh.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct QuadQualityReport {
    /// Number of quadrilaterals.
    pub quads: usize,
    /// Sum of the signed quad areas.
    pub area: f64,
    /// Quads with a corner that is not strictly convex counter-clockwise (exact).
    pub non_convex: usize,
    /// Smallest corner angle of the mesh (degrees).
    pub min_angle_deg: f64,
    /// Largest corner angle of the mesh (degrees).
    pub max_angle_deg: f64,
    /// Per-quad smallest angle.
    pub min_angle: Stats,
    /// Per-quad largest angle.
    pub max_angle: Stats,
    /// Verdict aspect ratio.
    pub aspect_ratio: Stats,
    /// Verdict scaled Jacobian.
    pub scaled_jacobian: Stats,
    /// Edge ratio.
    pub edge_ratio: Stats,
    /// Quad area.
    pub quad_area: Stats,
    /// All four corner angles of every quad with non-zero edges, 18 bins of 10° over
    /// `[0, 180]` (reflex corners count as `above`).
    pub angle_histogram: Histogram,
}

/// Quality report of a planar mesh: its triangles and its quadrilaterals.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PlanarQualityReport {
    /// Total signed area.
    pub area: f64,
    /// The triangles (areas and scaled Jacobians signed).
    pub triangles: TriQualityReport,
    /// The quadrilaterals.
    pub quads: QuadQualityReport,
}

struct QuadAcc {
    area: KahanSum,
    non_convex: usize,
    stats: [StatsAccumulator; 6],
    hist: Histogram,
}

impl QuadAcc {
    fn new() -> QuadAcc {
        QuadAcc {
            area: KahanSum::default(),
            non_convex: 0,
            stats: std::array::from_fn(|_| StatsAccumulator::new()),
            hist: Histogram::uniform(0.0, 180.0, 18),
        }
    }

    fn push(&mut self, q: usize, p: &[DVec2; 4]) {
        let m: QuadMeasures = quad_measures(p);
        self.area.add(m.area);
        let convex = (0..4).all(|k| orient2d(p[(k + 3) % 4], p[k], p[(k + 1) % 4]) == Sign::Positive);
        self.non_convex += usize::from(!convex);
        if let Some(a) = quad_angles(p) {
            a.iter().for_each(|&x| self.hist.add(x));
        }
        let v = [m.min_angle, m.max_angle, m.aspect_ratio, m.scaled_jacobian, m.edge_ratio, m.area];
        for (s, x) in self.stats.iter_mut().zip(v) {
            s.push(q, x);
        }
    }

    fn merge(&mut self, o: QuadAcc) {
        self.area.merge(o.area);
        self.non_convex += o.non_convex;
        for (a, b) in self.stats.iter_mut().zip(&o.stats) {
            a.merge(b);
        }
        self.hist.merge(&o.hist);
    }
}

/// The quality report of a planar mesh (triangles and quadrilaterals separately).
pub fn planar_mesh_quality(m: &PlanarMesh) -> PlanarQualityReport {
    let v = |i: u32| m.vertices[i as usize];
    let nt = m.triangles.len();
    let tris = chunked_reduce(
        nt,
        TriAcc::new(),
        |a, b| {
            let mut acc = TriAcc::new();
            for t in a..b {
                let p = m.triangles[t].map(v);
                let tm = tri_measures_2d(&p);
                let o = orient2d(p[0], p[1], p[2]);
                let lifted = p.map(|q| DVec3::new(q.x, q.y, 0.0));
                acc.push(t, &tm, tri_angles(&lifted), o == Sign::Zero, o == Sign::Negative);
            }
            acc
        },
        |acc, part| acc.merge(part),
    )
    .finish(nt);
    let nq = m.quads.len();
    let qa = chunked_reduce(
        nq,
        QuadAcc::new(),
        |a, b| {
            let mut acc = QuadAcc::new();
            for q in a..b {
                acc.push(q, &m.quads[q].map(v));
            }
            acc
        },
        |acc, part| acc.merge(part),
    );
    let s: Vec<Stats> = qa.stats.iter().map(|s| s.finish()).collect();
    let quads = QuadQualityReport {
        quads: nq,
        area: qa.area.value(),
        non_convex: qa.non_convex,
        min_angle_deg: s[0].min,
        max_angle_deg: s[1].max,
        min_angle: s[0].clone(),
        max_angle: s[1].clone(),
        aspect_ratio: s[2].clone(),
        scaled_jacobian: s[3].clone(),
        edge_ratio: s[4].clone(),
        quad_area: s[5].clone(),
        angle_histogram: qa.hist,
    };
    PlanarQualityReport { area: tris.area + quads.area, triangles: tris, quads }
}

impl TriQualityReport {
    /// Plain-text rendering for the CLI: headline `key value` lines, statistics per measure,
    /// the angle histogram.
    pub fn render(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "triangles {}", self.triangles);
        let _ = writeln!(s, "area {:.9}", self.area);
        let _ = writeln!(s, "degenerate {}", self.degenerate);
        let _ = writeln!(s, "inverted {}", self.inverted);
        let _ = writeln!(s, "min_angle_deg {:.4}", self.min_angle_deg);
        let _ = writeln!(s, "max_angle_deg {:.4}", self.max_angle_deg);
        let _ = writeln!(s, "triangles_min_angle_below_10 {}", self.triangles_min_angle_below_10);
        let _ = writeln!(s, "triangles_min_angle_below_20 {}", self.triangles_min_angle_below_20);
        let _ = writeln!(s, "triangles_min_angle_below_30 {}", self.triangles_min_angle_below_30);
        for (name, st) in [
            ("min angle", &self.min_angle),
            ("max angle", &self.max_angle),
            ("aspect ratio", &self.aspect_ratio),
            ("radius ratio", &self.radius_ratio),
            ("scaled Jacobian", &self.scaled_jacobian),
            ("edge ratio", &self.edge_ratio),
            ("area", &self.triangle_area),
        ] {
            let _ = writeln!(s, "{name:>16}: {}", st.render());
        }
        let _ = writeln!(s, "angles (deg):");
        s.push_str(&self.angle_histogram.render(40));
        s
    }
}

impl PlanarQualityReport {
    /// Plain-text rendering for the CLI.
    pub fn render(&self) -> String {
        let mut s = format!("area {:.9}\n", self.area);
        if self.triangles.triangles > 0 {
            s.push_str(&self.triangles.render());
        }
        let q = &self.quads;
        if q.quads > 0 {
            let _ = writeln!(s, "quads {}", q.quads);
            let _ = writeln!(s, "quad_area {:.9}", q.area);
            let _ = writeln!(s, "non_convex {}", q.non_convex);
            let _ = writeln!(s, "quad_min_angle_deg {:.4}", q.min_angle_deg);
            let _ = writeln!(s, "quad_max_angle_deg {:.4}", q.max_angle_deg);
            for (name, st) in [
                ("min angle", &q.min_angle),
                ("max angle", &q.max_angle),
                ("aspect ratio", &q.aspect_ratio),
                ("scaled Jacobian", &q.scaled_jacobian),
                ("edge ratio", &q.edge_ratio),
                ("area", &q.quad_area),
            ] {
                let _ = writeln!(s, "{name:>16}: {}", st.render());
            }
            let _ = writeln!(s, "quad angles (deg):");
            s.push_str(&q.angle_histogram.render(40));
        }
        s
    }
}
