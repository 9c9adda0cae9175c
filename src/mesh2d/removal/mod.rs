//! Geometry decomposition by iterative removal of elements (Sadek; lecture 23.2.3): cut the
//! front's vertex angles under 90° as single triangles, those between 90° and 180° as two
//! triangles with a new point, and repeat until the last three points form a triangle.
//!
//! Stages, one file each:
//! 1. `front`: the domain's loops (holes as loops of their own) as the front, with a
//!    uniform grid over its vertices and edges for the exact checks;
//! 2. `cut`: the removals, smallest angle first, with front splits and loop merges where
//!    a new point falls near another part of the front;
//! 3. `improve`: Lawson flips to the constrained Delaunay triangulation (domain segments
//!    never flipped) and guarded Laplacian smoothing of the added points;
//! 4. `check`: the output is verified (valid, the domain's area, every domain point a vertex
//!    and every domain segment a boundary edge) before it is returned.
//!
//! The domain's boundary points are final: no point is added on a segment (divide the
//! segments by the size first, [`boundary::split_boundary`](crate::mesh2d::boundary::split_boundary),
//! where the boundary must follow the size). The size is evaluated at front vertices and
//! at the middle of ears' new edges. Deterministic: counts only, ties by node id.

mod check;
mod cut;
mod front;
mod improve;

#[cfg(test)]
mod tests;

pub use check::{check_cover, CoverError};

use crate::core::RegionId;
use crate::mesh::PlanarMesh;
use crate::mesh2d::boundary::{check_size, SizeError};
use crate::mesh2d::domain::{Domain, DomainError};
use glam::DVec2;

/// Parameters of [`mesh`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct Options {
    /// Front angles under this (degrees) are cut as one triangle (the lecture: 90°).
    pub ear_angle: f64,
    /// Front angles at or above this (degrees) wait until every smaller one is cut (180°:
    /// only reflex vertices wait; smaller values let the front's flatter parts wait too).
    pub pair_angle: f64,
    /// An ear whose new edge is longer than this times the size there gets a new point
    /// instead (two triangles).
    pub long_ear: f64,
    /// Passes of Laplacian smoothing (each followed by flips).
    pub smooth_passes: usize,
    /// The region tag of every element.
    pub region: RegionId,
}

impl Default for Options {
    fn default() -> Options {
        Options { ear_angle: 90.0, pair_angle: 180.0, long_ear: 1.5, smooth_passes: 4, region: RegionId(1) }
    }
}

impl Options {
    /// With another smoothing pass count.
    pub fn with_smooth_passes(mut self, passes: usize) -> Options {
        self.smooth_passes = passes;
        self
    }

    /// With another region tag.
    pub fn with_region(mut self, region: RegionId) -> Options {
        self.region = region;
        self
    }

    /// With other angle thresholds (degrees).
    pub fn with_angles(mut self, ear_angle: f64, pair_angle: f64) -> Options {
        self.ear_angle = ear_angle;
        self.pair_angle = pair_angle;
        self
    }
}

/// What the removal did.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Stats {
    /// Cuts of one triangle (a front vertex's two neighbours joined).
    pub ears: usize,
    /// Cuts of two triangles with a new point.
    pub pairs: usize,
    /// Cuts of two triangles to an existing front vertex (a front split or merge).
    pub joins: usize,
    /// Points added.
    pub points: usize,
    /// Front splits and loop merges (the joins and the bare diagonals).
    pub splits: usize,
    /// Front vertices taken (including those whose cuts were blocked).
    pub steps: usize,
    /// Lawson flips in the improvement.
    pub flips: usize,
    /// Accepted smoothing moves.
    pub moves: usize,
}

/// The mesh and its counts.
pub type Output = crate::mesh2d::Counted<Stats>;

/// Why a domain was not meshed.
#[derive(Clone, Debug, PartialEq, thiserror::Error, serde::Serialize)]
#[non_exhaustive]
pub enum Error {
    /// The input is not a valid domain.
    #[error("invalid domain: {0}")]
    Domain(#[from] DomainError),
    /// The size field gave a size that is not positive and finite.
    #[error(transparent)]
    Size(#[from] SizeError),
    /// An option is out of range.
    #[error("option {name} = {value} is out of range ({range})")]
    Option {
        /// The option.
        name: &'static str,
        /// Its value.
        value: f64,
        /// What is allowed.
        range: &'static str,
    },
    /// The boundary could not be traced into loops at a point (segments in and out do not
    /// alternate around it).
    #[error("the boundary cannot be traced into loops at point {0}")]
    Untraceable(u32),
    /// The front could not advance.
    #[error("the front stalled at ({x}, {y}) with {left} front vertices left after {steps} steps ({why}); a finer size or a boundary divided by the size may help")]
    Stalled {
        /// Where.
        x: f64,
        /// Where.
        y: f64,
        /// Front vertices left.
        left: usize,
        /// Steps taken.
        steps: usize,
        /// Why.
        why: String,
    },
    /// The output failed its check (a bug, reported rather than returned as a bad mesh).
    #[error("internal check failed: {0}")]
    Internal(String),
}

/// Meshes `domain` by iterative removal of elements (see the module docs).
///
/// # Errors
/// [`Error`]: an invalid domain or option, a bad size, a front that stalled, or a failed
/// final check.
pub fn mesh(domain: &Domain, size: &dyn Fn(DVec2) -> f64, options: &Options) -> Result<Output, Error> {
    domain.validate()?;
    let o = options;
    let bad = |name, value, range| Err(Error::Option { name, value, range });
    if !(o.ear_angle > 0.0 && o.ear_angle <= 180.0) {
        return bad("ear_angle", o.ear_angle, "(0, 180]");
    }
    if !(o.pair_angle >= o.ear_angle && o.pair_angle <= 360.0) {
        return bad("pair_angle", o.pair_angle, "[ear_angle, 360]");
    }
    if !(o.long_ear > 0.0 && o.long_ear.is_finite()) {
        return bad("long_ear", o.long_ear, "positive");
    }
    let mut lengths: Vec<f64> = domain.segments.iter().enumerate().map(|(s, _)| {
        let (a, b) = domain.ends(s);
        a.distance(b)
    }).collect();
    lengths.sort_by(f64::total_cmp);
    let cell = lengths[lengths.len() / 2];
    let limit = step_limit(domain, size)?;
    let front = front::Front::new(domain, cell).map_err(|e| Error::Untraceable(e.0))?;
    let (front, mut stats) = cut::remove(front, size, options, limit)?;
    let mut points = front.points;
    let mut triangles = front.triangles;
    let imp = improve::improve(&mut points, &mut triangles, domain.points.len(), &domain.segments, options.smooth_passes);
    stats.flips = imp.flips;
    stats.moves = imp.moves;
    let mesh = PlanarMesh { vertices: points, triangle_tags: vec![options.region; triangles.len()], triangles, quads: Vec::new(), quad_tags: Vec::new(), region_names: Default::default() };
    check_cover(&mesh, domain).map_err(|e| Error::Internal(e.to_string()))?;
    Ok(Output { mesh, stats })
}

/// The bound on steps: ten times the expected triangle count (the area over the smallest
/// size sampled at the boundary points and a 16 × 16 lattice inside) plus ten per boundary
/// point.
fn step_limit(domain: &Domain, size: &dyn Fn(DVec2) -> f64) -> Result<usize, Error> {
    let mut h_min = f64::INFINITY;
    for &p in &domain.points {
        h_min = h_min.min(check_size(p, size(p))?);
    }
    let (lo, hi) = domain.bounds();
    for i in 0..16 {
        for j in 0..16 {
            let p = lo + (hi - lo) * DVec2::new((i as f64 + 0.5) / 16.0, (j as f64 + 0.5) / 16.0);
            if domain.contains(p) {
                h_min = h_min.min(check_size(p, size(p))?);
            }
        }
    }
    let expected = domain.area() / (0.25 * 3f64.sqrt() * h_min * h_min);
    Ok((10.0 * expected).min(1e12) as usize + 10 * domain.points.len() + 1000)
}
