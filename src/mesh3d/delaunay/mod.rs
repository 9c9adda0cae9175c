//! 3D Delaunay tetrahedralization of point sets.
//!
//! Stage: layer 4 (mesh3d). Input: points (`f64`, finite). Output: [`Delaunay`], the finite
//! tets of the Delaunay tetrahedralization as indices into the input, positively oriented, in a
//! canonical order, plus the duplicate points that were left out.
//!
//! Method: incremental Bowyer–Watson insertion in a biased randomized insertion order sorted
//! along a Hilbert curve, point location by a visibility walk from the last created tet, a
//! ghost vertex closing the convex hull, compact flat arrays (4 vertex ids and 4 neighbour
//! references per tet, slots reused). Every orientation and in-sphere decision is exact, and
//! ties (cospherical and coplanar points) are broken by a lifting perturbation by vertex index,
//! so the result is the unique Delaunay tetrahedralization of the perturbed points: a valid
//! Delaunay tetrahedralization of the input, without flat tets, whatever the insertion order
//! or the number of threads. [`Delaunay::validate`] checks all of this independently.

pub(crate) mod cavity;
pub(crate) mod edge_table;
pub(crate) mod kernel;
mod output;
mod parallel;
pub(crate) mod store;
mod triangulation;
mod validate;

pub use validate::DelaunayViolation;

use crate::core::spatial_order::{brio_positions, hilbert_sort};
use crate::core::Sign;
use crate::mesh::TetMesh;
use crate::core::RegionId;
use glam::DVec3;
use kernel::{FloatKernel, IntKernel, Kernel, integer_points};
use triangulation::Triangulation;

/// Options of [`tetrahedralize`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct DelaunayOptions {
    /// Seed of the randomized insertion order (the result does not depend on it).
    pub seed: u64,
    /// Insert in parallel rounds on the current rayon pool when it has more than one thread
    /// (the result does not depend on it, nor on the number of threads).
    pub parallel: bool,
}

impl Default for DelaunayOptions {
    fn default() -> Self {
        DelaunayOptions { seed: 0x5eed, parallel: true }
    }
}

impl DelaunayOptions {
    /// Sets [`DelaunayOptions::parallel`].
    pub fn with_parallel(mut self, parallel: bool) -> Self {
        self.parallel = parallel;
        self
    }

    /// Sets [`DelaunayOptions::seed`].
    pub fn with_seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }
}

/// Which exact kernel decided the signs.
#[derive(Copy, Clone, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum KernelKind {
    /// Integer predicates on dyadic coordinates (grids, integer data).
    Integer,
    /// `robust`'s adaptive floating-point predicates.
    Float,
}

/// Where the time of a tetrahedralization went (wall seconds).
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct DelaunayTimings {
    /// Hilbert ordering, copying the points, choosing the kernel, the BRIO.
    pub order: f64,
    /// The serial insertion (all of it, or the start before the parallel passes).
    pub serial: f64,
    /// Preparing the shared arrays of the parallel insertion.
    pub parallel_setup: f64,
    /// The parallel passes in order.
    pub passes: Vec<PassTiming>,
    /// Counting the tets, or putting them in canonical form.
    pub output: f64,
}

/// One pass of the parallel insertion.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct PassTiming {
    /// How the work was split: "ranks", "x slabs", "y slabs" or "all".
    pub split: &'static str,
    /// Points offered.
    pub points: usize,
    /// Points postponed to the next pass.
    pub postponed: usize,
    /// Wall seconds.
    pub seconds: f64,
}

/// A Delaunay tetrahedralization.
#[derive(Clone, Debug)]
pub struct Delaunay {
    /// Finite tets: #T × 4 indices into the input points, positively oriented, in a canonical
    /// order and rotation that depend on the input alone (equal inputs give equal arrays, for
    /// any insertion order or number of threads): grouped by their vertex that comes first
    /// along a Hilbert curve through the points. Empty from [`count_tetrahedra`].
    pub tets: Vec<[u32; 4]>,
    /// Number of tets (equal to `tets.len()` unless only counted).
    pub count: usize,
    /// Points left out because they coincide with another: `(left out, kept)`, the kept one
    /// being the smallest index of its group; sorted.
    pub duplicates: Vec<[u32; 2]>,
    /// The kernel that decided the signs.
    pub kernel: KernelKind,
    /// Where the time went.
    pub timings: DelaunayTimings,
}

/// Why a point set has no tetrahedralization.
#[derive(Clone, Debug, PartialEq, thiserror::Error, serde::Serialize)]
#[non_exhaustive]
pub enum DelaunayError {
    /// A coordinate is NaN or infinite.
    #[error("point {point} has a non-finite coordinate {coords:?}")]
    NonFinite {
        /// The point.
        point: usize,
        /// Its coordinates.
        coords: [f64; 3],
    },
    /// More points than `u32` indices can address (the ghost vertex takes one).
    #[error("{0} points: at most 4,294,967,293 are supported")]
    TooManyPoints(usize),
    /// All points lie in one plane (or on one line, or coincide): there is no tetrahedron.
    #[error("the {distinct} distinct points are {what}: no tetrahedron can be formed")]
    Degenerate {
        /// Distinct points.
        distinct: usize,
        /// "coplanar", "collinear", "coincident" or "fewer than four".
        what: &'static str,
    },
}

/// The Delaunay tetrahedralization of `points`.
///
/// # Errors
/// [`DelaunayError`] for non-finite points, more than `u32` can index, or points that span no
/// tetrahedron.
///
/// ```
/// use fepre::mesh3d::delaunay::{tetrahedralize, DelaunayOptions};
/// use glam::DVec3;
/// // the 8 corners of a cube are cospherical: any 5 tets or 6 would do, perturbation picks one
/// let p: Vec<DVec3> = (0..8).map(|i| DVec3::new((i & 1) as f64, ((i >> 1) & 1) as f64, (i >> 2) as f64)).collect();
/// let d = tetrahedralize(&p, &DelaunayOptions::default()).unwrap();
/// assert!(d.validate(&p).is_ok());
/// let volume: f64 = d.to_tet_mesh(&p).volume();
/// assert_eq!(volume, 1.0);
/// ```
pub fn tetrahedralize(points: &[DVec3], options: &DelaunayOptions) -> Result<Delaunay, DelaunayError> {
    build(points, options, Finish::Tets)
}

/// The same tetrahedralization as [`tetrahedralize`], but only counted: `tets` is left empty
/// (`count` says how many there are) and the cost of ordering the output canonically is saved.
/// For statistics, and for timing against tools that do not output their tets either.
///
/// # Errors
/// As [`tetrahedralize`].
pub fn count_tetrahedra(points: &[DVec3], options: &DelaunayOptions) -> Result<Delaunay, DelaunayError> {
    build(points, options, Finish::Count)
}

fn build(points: &[DVec3], options: &DelaunayOptions, finish: Finish) -> Result<Delaunay, DelaunayError> {
    if points.len() >= store::DEAD as usize {
        return Err(DelaunayError::TooManyPoints(points.len()));
    }
    if let Some(i) = points.iter().position(|p| !p.is_finite()) {
        return Err(DelaunayError::NonFinite { point: i, coords: points[i].to_array() });
    }
    // internal numbering: Hilbert rank, so that spatial neighbours are memory neighbours
    let started = std::time::Instant::now();
    let perm = hilbert_sort(points);
    let local: Vec<DVec3> = perm.iter().map(|&i| points[i as usize]).collect();
    let order = brio_positions(points.len(), options.seed);
    match integer_points(&local) {
        Some(ints) => run(&IntKernel { points: ints, ids: perm }, points, &order, options, KernelKind::Integer, finish, started),
        None => run(&FloatKernel { points: local, ids: perm }, points, &order, options, KernelKind::Float, finish, started),
    }
}

/// Finds four points spanning a positive tet, in insertion order, or says why there are none
/// ("fewer than four", "coincident", "collinear", "coplanar").
fn first_tet<K: Kernel>(k: &K, order: &[u32]) -> Result<[u32; 4], &'static str> {
    if k.len() < 4 {
        return Err("fewer than four");
    }
    let a = order[0];
    let b = *order.iter().find(|&&i| !k.same(i, a)).ok_or("coincident")?;
    let c = *order.iter().find(|&&i| !k.collinear(a, b, i)).ok_or("collinear")?;
    let d = *order.iter().find(|&&i| !k.orient(a, b, c, i).is_zero()).ok_or("coplanar")?;
    Ok(if k.orient(a, b, c, d) == Sign::Positive { [a, b, c, d] } else { [b, a, c, d] })
}

/// The number of distinct points (for error messages).
fn count_distinct(points: &[DVec3]) -> usize {
    let mut keys: Vec<[u64; 3]> = points.iter().map(|p| (*p + DVec3::ZERO).to_array().map(f64::to_bits)).collect();
    keys.sort_unstable();
    keys.dedup();
    keys.len()
}

/// What to make of the finished triangulation.
#[derive(Copy, Clone, PartialEq, Eq)]
enum Finish {
    /// The canonical tets.
    Tets,
    /// Only their number.
    Count,
}

fn run<K: Kernel>(
    k: &K,
    points: &[DVec3],
    order: &[u32],
    options: &DelaunayOptions,
    kind: KernelKind,
    finish: Finish,
    started: std::time::Instant,
) -> Result<Delaunay, DelaunayError> {
    let mut timings = DelaunayTimings { order: started.elapsed().as_secs_f64(), ..Default::default() };
    let clock = std::time::Instant::now();
    let first = first_tet(k, order).map_err(|what| DelaunayError::Degenerate { distinct: count_distinct(points), what })?;
    // about 6.7 tets per point for random points, plus the ghosts
    let capacity = k.len() * 7 + 64;
    let mut tr = Triangulation::new(k, first, capacity, options.seed);
    let mut duplicates = Vec::new();
    let parallel = options.parallel && rayon::current_num_threads() > 1 && order.len() >= PARALLEL_MIN_POINTS;
    // the serial start: everything, or the first rounds up to a base for the parallel rounds
    let serial_end = if parallel { serial_prefix(order.len()) } else { order.len() };
    for &p in &order[..serial_end] {
        if first.contains(&p) {
            continue;
        }
        if let Some(v) = tr.insert(p) {
            duplicates.push([k.original(p), k.original(v)]);
        }
    }
    timings.serial = clock.elapsed().as_secs_f64();
    if !parallel {
        return Ok(finish_with(tr.tets, k, duplicates, kind, finish, timings));
    }
    let mut internal = Vec::new();
    let tets = parallel::insert_parallel(tr, order, serial_end, &first, options.seed, &mut internal, &mut timings);
    duplicates.extend(internal.iter().map(|&[p, v]| [k.original(p), k.original(v)]));
    Ok(finish_with(tets, k, duplicates, kind, finish, timings))
}

/// The result from the finished slots: counted, or in canonical form.
fn finish_with<S: output::Slots, K: Kernel>(
    slots: S,
    k: &K,
    mut duplicates: Vec<[u32; 2]>,
    kernel: KernelKind,
    finish: Finish,
    mut timings: DelaunayTimings,
) -> Delaunay {
    let clock = std::time::Instant::now();
    let (tets, count) = match finish {
        Finish::Count => {
            let count = output::count_finite(&slots);
            output::canonical_duplicates(k.len(), &mut duplicates);
            (Vec::new(), count)
        }
        Finish::Tets => {
            let tets = output::canonical_tets(slots, k, &mut duplicates);
            let count = tets.len();
            (tets, count)
        }
    };
    timings.output = clock.elapsed().as_secs_f64();
    Delaunay { tets, count, duplicates, kernel, timings }
}

/// Below this many points the parallel rounds do not pay.
const PARALLEL_MIN_POINTS: usize = 20_000;

/// How many points of the insertion order are inserted serially before the parallel rounds:
/// the BRIO rounds that end within the first 8,192 points.
fn serial_prefix(n: usize) -> usize {
    crate::core::spatial_order::brio_rounds(n, 1024).iter().map(|r| r.1).filter(|&e| e <= 8192).max().unwrap_or(0)
}

impl Delaunay {
    /// The tetrahedralization as a [`TetMesh`] over all input points (left-out duplicates stay
    /// as unused vertices), region 1, no boundary triangles.
    pub fn to_tet_mesh(&self, points: &[DVec3]) -> TetMesh {
        TetMesh {
            vertices: points.to_vec(),
            tets: self.tets.clone(),
            region_tags: vec![RegionId(1); self.tets.len()],
            ..Default::default()
        }
    }

    /// Checks, independently of how it was built (adjacency is rebuilt from the tets): every
    /// tet positively oriented, every face shared by at most two tets from opposite sides, the
    /// faces shared by one tet forming the convex hull (no point beyond any of them, hull edges
    /// convex), every interior face locally Delaunay (the opposite vertex is not inside the
    /// circumsphere, decided exactly, and not inside under the perturbation), and every
    /// non-duplicate point a vertex.
    ///
    /// # Errors
    /// The first violation found.
    pub fn validate(&self, points: &[DVec3]) -> Result<(), DelaunayViolation> {
        validate::validate(self, points)
    }
}

#[cfg(test)]
mod tests;
