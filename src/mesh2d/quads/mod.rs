//! All-quadrilateral meshes: triangles paired into quadrilaterals by a maximum-weight
//! matching (the lecture's pairing test: only pairs that make a strictly convex quad of
//! fair shape are candidates), then one split to all quads (each quad into 4, each
//! leftover triangle into 3), then smoothing.
//!
//! Stages, one file each (the input is first flipped to its constrained Delaunay
//! triangulation, boundary kept: `mesh2d::flips`):
//! 1. `source`: [`mesh`] only: triangles of the domain at twice the size, its boundary
//!    points kept (the quadtree's interior lattice as seeds, spade's CDT with the segments as
//!    constraints, refined to 25° without splitting them);
//! 2. `matching`: the candidate pairs (adjacent triangles whose quad is strictly convex,
//!    exactly, with a scaled Jacobian of at least [`Options::min_pair_quality`]) and a
//!    maximum-weight matching: greedy on sorted weights, then augmenting and
//!    weight-improving alternating paths from every unpaired triangle;
//! 3. `split`: every edge halved at its midpoint, each quad into 4 (corner, midpoints,
//!    centre), each leftover triangle into 3 (corner, midpoints, centroid): all quads at half
//!    the size, the boundary edges' midpoints listed;
//! 4. `smooth`: interior points moved by Laplacian smoothing, then by a pattern search that
//!    raises the worst scaled Jacobian around the point; a move is kept only if every quad
//!    around the point stays strictly convex (exact `orient2d` at every corner) and the worst
//!    scaled Jacobian around it does not decrease.
//!
//! # Guarantees
//! - The output has quads only, strictly convex (`PlanarMesh::validate`), covering exactly
//!   the input's area; input vertex `i` is output vertex `i` (interior ones may move,
//!   boundary ones never do); every boundary edge of the input is split at its midpoint once
//!   (listed in [`Output::midpoints`]), nothing else is added on the boundary.
//! - Deterministic: sorted candidates, index-ordered searches and passes, no hashing order.

mod matching;
mod smooth;
mod source;
mod split;

#[cfg(test)]
mod tests;

use crate::core::RegionId;
use crate::mesh::PlanarMesh;
use crate::mesh2d::domain::{Domain, DomainError};
use crate::mesh2d::flips::lawson_flips;
use crate::mesh2d::measure::min_corner_jacobian;
use rustc_hash::FxHashSet;
use glam::DVec2;

/// Options of [`mesh`] and [`from_triangles`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// Smallest scaled Jacobian of a pair's quad for the pair to be a candidate (the pairing
    /// test; strict convexity is required in any case).
    pub min_pair_quality: f64,
    /// Weight of a pair in the matching: this bonus plus its quad's scaled Jacobian (a
    /// bonus of 1 makes nearly every augmenting path worth taking: few leftovers).
    pub pair_bonus: f64,
    /// Longest alternating path searched from an unpaired triangle, in edges.
    pub augment_depth: usize,
    /// Rounds of augmenting searches over all unpaired triangles.
    pub augment_rounds: usize,
    /// Smoothing passes over the interior points (each a Laplacian pass then a
    /// scaled-Jacobian pass); 0 leaves the split mesh as it is.
    pub smooth_passes: usize,
    /// The region tag of every quad.
    pub region: RegionId,
}

impl Default for Options {
    fn default() -> Options {
        Options { min_pair_quality: 0.3, pair_bonus: 1.0, augment_depth: 12, augment_rounds: 4, smooth_passes: 6, region: RegionId(1) }
    }
}

/// What the method did and the quality it reached.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Stats {
    /// Triangles of the input (or of the source triangulation).
    pub triangles: usize,
    /// Candidate pairs (adjacent triangles passing the pairing test).
    pub candidates: usize,
    /// Pairs matched (each became 4 quads).
    pub pairs: usize,
    /// Triangles left unpaired (each became 3 quads).
    pub leftover_triangles: usize,
    /// Edges of the input flipped to make it constrained Delaunay (boundary kept).
    pub flips: usize,
    /// Pairs the greedy start gave, before the augmenting searches.
    pub greedy_pairs: usize,
    /// Accepted alternating paths (augmenting or weight-improving).
    pub augmentations: usize,
    /// Accepted smoothing moves.
    pub smoothing_moves: usize,
    /// Smallest and median scaled Jacobian of the quads after the split, before smoothing.
    pub scaled_jacobian_before: [f64; 2],
    /// Smallest and median scaled Jacobian of the final quads.
    pub scaled_jacobian_after: [f64; 2],
}

/// The all-quad mesh.
#[derive(Clone, Debug)]
pub struct Output {
    /// Quads only (no triangles), each tagged `options.region`.
    pub mesh: PlanarMesh,
    /// Every boundary edge of the triangles halved: `(new vertex, [the edge's two input
    /// vertices])`, sorted by new vertex (for [`mesh`]: the domain segments' midpoints).
    pub midpoints: Vec<(u32, [u32; 2])>,
    /// Counts and quality.
    pub stats: Stats,
}

/// Why no all-quad mesh was made.
#[derive(Clone, Debug, PartialEq, thiserror::Error, serde::Serialize)]
#[non_exhaustive]
pub enum Error {
    /// The input is not a valid domain.
    #[error("invalid domain: {0}")]
    Domain(#[from] DomainError),
    /// The size function gave a size that is not positive and finite.
    #[error("the size at ({x}, {y}) is {size} (must be positive and finite)")]
    Size {
        /// Where.
        x: f64,
        /// Where.
        y: f64,
        /// What it gave.
        size: f64,
    },
    /// The triangle mesh given to [`from_triangles`] cannot be paired.
    #[error("the input triangle mesh is not usable: {0} (give a valid mesh of triangles only)")]
    Input(String),
    /// The source triangulation of the domain failed.
    #[error("the domain could not be triangulated: {0}")]
    Triangulation(String),
    /// An internal check failed (a bug, reported rather than returned as a bad mesh).
    #[error("internal check failed: {0}")]
    Internal(String),
}

/// Meshes `domain` with quadrilaterals of about `size` (see the module docs). The domain's
/// points are kept; each of its segments is halved at its midpoint (listed in
/// [`Output::midpoints`]), and nothing else is added on the boundary. The triangles are
/// made at twice the size by `source` (the switch for another triangle mesher).
///
/// # Errors
/// [`Error`]: an invalid domain, a bad size, a failed triangulation or internal check.
pub fn mesh(domain: &Domain, size: &dyn Fn(DVec2) -> f64, options: &Options) -> Result<Output, Error> {
    domain.validate()?;
    let tris = source::triangulate(domain, size)?;
    let out = from_triangles(&tris, options)?;
    // every domain segment halved once, and its midpoint listed
    let mut listed: Vec<[u32; 2]> = out.midpoints.iter().map(|(_, e)| [e[0].min(e[1]), e[0].max(e[1])]).collect();
    listed.sort_unstable();
    let mut segs: Vec<[u32; 2]> = domain.segments.iter().map(|e| [e[0].min(e[1]), e[0].max(e[1])]).collect();
    segs.sort_unstable();
    if listed != segs {
        return Err(Error::Internal(format!("{} boundary midpoints for {} domain segments", listed.len(), segs.len())));
    }
    Ok(out)
}

/// Turns a triangle mesh into an all-quad mesh at half its size (see the module docs).
///
/// # Errors
/// [`Error::Input`] if `tris` is not a valid mesh of triangles only; [`Error::Internal`]
/// if the result fails its checks.
pub fn from_triangles(tris: &PlanarMesh, options: &Options) -> Result<Output, Error> {
    if !tris.quads.is_empty() {
        return Err(Error::Input(format!("it has {} quads", tris.quads.len())));
    }
    if tris.triangles.is_empty() {
        return Err(Error::Input("it has no triangles".to_string()));
    }
    tris.validate().map_err(|e| Error::Input(e.to_string()))?;
    // the constrained Delaunay triangulation of the same points and boundary first: the
    // largest smallest angle, so no sliver whose split would be degenerate
    let mut flipped = tris.clone();
    let boundary = boundary_edges(&flipped.triangles);
    let flips = lawson_flips(&flipped.vertices, &mut flipped.triangles, &boundary);
    let tris = &flipped;
    let m = matching::match_triangles(tris, options);
    let mut stats = Stats {
        triangles: tris.triangles.len(),
        candidates: m.candidates,
        pairs: m.pairs.len(),
        leftover_triangles: m.leftovers.len(),
        greedy_pairs: m.greedy_pairs,
        augmentations: m.augmentations,
        flips,
        ..Stats::default()
    };
    let s = split::split(tris, &m, options.region);
    s.mesh.validate().map_err(|e| Error::Internal(format!("split: {e}")))?;
    stats.scaled_jacobian_before = min_median(&s.mesh);
    let mut mesh = s.mesh;
    stats.smoothing_moves = smooth::smooth(&mut mesh, &s.fixed, options.smooth_passes);
    mesh.validate().map_err(|e| Error::Internal(format!("smoothing: {e}")))?;
    stats.scaled_jacobian_after = min_median(&mesh);
    let rel = (mesh.area() - tris.area()).abs() / tris.area().abs().max(f64::MIN_POSITIVE);
    if rel > 1e-9 {
        return Err(Error::Internal(format!("area {} instead of {}", mesh.area(), tris.area())));
    }
    Ok(Output { mesh, midpoints: s.midpoints, stats })
}

/// The edges of one triangle only, as sorted pairs.
fn boundary_edges(triangles: &[[u32; 3]]) -> FxHashSet<[u32; 2]> {
    let mut all: Vec<[u32; 2]> = triangles.iter().flat_map(|t| (0..3).map(move |k| [t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3])])).collect();
    all.sort_unstable();
    let mut out = FxHashSet::default();
    let mut i = 0;
    while i < all.len() {
        let single = i + 1 >= all.len() || all[i + 1] != all[i];
        if single {
            out.insert(all[i]);
        }
        i += if single { 1 } else { 2 };
    }
    out
}

/// Smallest and median scaled Jacobian of the quads (the median as `measure` takes it).
fn min_median(mesh: &PlanarMesh) -> [f64; 2] {
    let mut v: Vec<f64> = mesh.quads.iter().map(|q| min_corner_jacobian(&q.map(|i| mesh.vertices[i as usize]))).collect();
    if v.is_empty() {
        return [f64::NAN, f64::NAN];
    }
    v.sort_by(f64::total_cmp);
    [v[0], v[((v.len() - 1) as f64 * 0.5).round() as usize]]
}
