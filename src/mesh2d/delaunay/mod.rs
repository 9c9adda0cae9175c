//! Constrained Delaunay triangulation and Ruppert/Chew refinement (the lecture's 23.1.5 and
//! 23.2.4), done as Shewchuk's Triangle does it (`-pq<θ>a<A>`).
//!
//! Stages, one file each:
//! 1. the input, a [`Domain`], validated exactly;
//! 2. `initial`: the constrained Delaunay triangulation of its points and segments (spade),
//!    converted to triangle arrays (`tri`), the outside and the holes removed by a flood fill
//!    from the segments' sides;
//! 3. `refine`: encroached subsegments split (concentric shells at small angles), bad
//!    triangles split at off-centers or circumcenters (`insert`: Bowyer-Watson cavities with
//!    exact predicates), shortest edge first;
//! 4. `report`: the small input angles, the triangles left under the bound and why.
//!
//! # Criteria
//! - Angle: a triangle is bad when its smallest angle is under [`Options::min_angle`].
//! - Size: with [`Options::use_size`], a triangle is too large when its circumradius exceeds
//!   [`SIZE_FACTOR`]` · h(centroid) / √3` (`h/√3` is the circumradius of the equilateral
//!   triangle of side `h`; the factor is tuned so that the median element size over `h`, as
//!   [`measure`](crate::mesh2d::measure::measure) computes it, is near 1).
//! - Area: with [`Options::max_area`], too large when its area exceeds it (Triangle's `-a`).
//!
//! # What holds
//! - Every output triangle is positive (exact), the mesh conforms, covers the domain, has
//!   every domain point as a vertex (same index) and every segment as a union of edges
//!   ([`Output::boundary`]); with `split_segments = false` as one edge.
//! - On domains without input angles under 60°, every angle is at least `min_angle` when
//!   segments may be split (tested at 30° and 33°; Ruppert's proof covers 20.7°, practice
//!   goes to about 34°, so larger bounds are refused: [`MAX_MIN_ANGLE`]).
//! - Near an input angle φ under 60° (the terminator: concentric shells and Miller, Pav and
//!   Walkington's rule), triangles at the small angle may keep an angle under the bound;
//!   they are counted in [`Stats::below`] and the angles named in
//!   [`Stats::small_input_angles`]; every other triangle meets the bound
//!   ([`Stats::smallest_angle_away`]).
//! - With `split_segments = false` (Triangle's `-Y`), no point is added on the boundary;
//!   triangles touching it whose split point lies beyond a segment stay as they are and are
//!   counted ([`Below::protected_boundary`]).
//! - Deterministic: the same input gives the same mesh.

mod initial;
mod insert;
mod refine;
mod report;
mod tri;

#[cfg(test)]
mod tests;

pub use report::{Below, SmallAngle};

use crate::core::RegionId;
use crate::mesh::PlanarMesh;
use crate::mesh2d::{Domain, DomainError};
use glam::DVec2;

/// The largest [`Options::min_angle`] accepted, degrees.
pub const MAX_MIN_ANGLE: f64 = 35.0;

/// A triangle is too large when its circumradius exceeds `SIZE_FACTOR · h / √3`.
pub const SIZE_FACTOR: f64 = 1.3;

/// Options of [`mesh`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// The smallest angle asked, degrees, in `[0, MAX_MIN_ANGLE]` (default 30).
    pub min_angle: f64,
    /// A global bound on triangle areas (Triangle's `-a`); `None`: none.
    pub max_area: Option<f64>,
    /// Whether the size `h` bounds triangles (see the module docs); false to refine by the
    /// angle and `max_area` only.
    pub use_size: bool,
    /// Whether encroached segments may be split at Steiner points on them (default true);
    /// false keeps every boundary point final (Triangle's `-Y`, for CAD faces).
    pub split_segments: bool,
    /// Refuse to go past this many vertices (a guard against sizes far below the domain).
    pub max_vertices: usize,
    /// The region tag of every triangle.
    pub region: RegionId,
}

impl Default for Options {
    fn default() -> Options {
        Options { min_angle: 30.0, max_area: None, use_size: true, split_segments: true, max_vertices: 20_000_000, region: RegionId(1) }
    }
}

/// What the refinement did and left.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct Stats {
    /// Steiner points inserted inside the domain.
    pub steiner_interior: usize,
    /// Steiner points inserted on segments.
    pub steiner_on_segments: usize,
    /// The input angles under 60°, with their vertex.
    pub small_input_angles: Vec<SmallAngle>,
    /// Triangles whose smallest angle stayed under `min_angle`, by cause.
    pub below: Below,
    /// The smallest angle of any triangle, degrees.
    pub smallest_angle: f64,
    /// The smallest angle among triangles not at a small input angle, degrees.
    pub smallest_angle_away: f64,
    /// Bad triangles left because their split point could not be inserted (beyond a
    /// protected segment, or a cavity refused).
    pub refused: usize,
    /// Subsegment splits refused (the split point could not be placed).
    pub refused_splits: usize,
}

/// The mesh and its figures.
#[derive(Clone, Debug, PartialEq)]
pub struct Output {
    /// The triangles (every one tagged `options.region`); vertices `0..domain.points.len()`
    /// are the domain's points.
    pub mesh: PlanarMesh,
    /// Per domain segment, its vertices from start to end.
    pub boundary: Vec<Vec<u32>>,
    /// The figures.
    pub stats: Stats,
}

/// Why a domain was not meshed.
#[derive(Clone, Debug, PartialEq, thiserror::Error, serde::Serialize)]
#[non_exhaustive]
pub enum Error {
    /// The input is not a valid domain.
    #[error("invalid domain: {0}")]
    Domain(#[from] DomainError),
    /// The angle bound is out of range.
    #[error("min_angle {0}° is out of range (0 to {MAX_MIN_ANGLE}°; refinement above about 34° may not end)")]
    MinAngle(f64),
    /// The area bound is not positive and finite.
    #[error("max_area {0} must be positive and finite")]
    MaxArea(f64),
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
    /// The refinement went past `max_vertices`.
    #[error("more than {0} vertices (the size or area bound is too small for the domain; raise max_vertices)")]
    TooManyVertices(usize),
    /// An internal step failed (a bug, reported rather than returned as a bad mesh).
    #[error("internal failure: {0}")]
    Internal(String),
}

/// Meshes `domain` by Delaunay refinement to `options` and the size `size` (see the module
/// docs).
///
/// # Errors
/// [`Error`]: an invalid domain or option, a bad size, too many vertices, an internal failure.
pub fn mesh(domain: &Domain, size: &dyn Fn(DVec2) -> f64, options: &Options) -> Result<Output, Error> {
    domain.validate()?;
    let theta = options.min_angle;
    if !(0.0..=MAX_MIN_ANGLE).contains(&theta) {
        return Err(Error::MinAngle(theta));
    }
    if let Some(a) = options.max_area {
        if !(a.is_finite() && a > 0.0) {
            return Err(Error::MaxArea(a));
        }
    }
    let tri = initial::build(domain).map_err(Error::Internal)?;
    let cos = theta.to_radians().cos();
    let crit = refine::Criteria {
        cos2: cos * cos,
        lens: (2.0 * cos * cos - 1.0).powi(2),
        offconstant: if cos >= 1.0 { 0.0 } else { 0.475 * ((1.0 + cos) / (1.0 - cos)).sqrt() },
        max_area: options.max_area.unwrap_or(f64::INFINITY),
        size: if options.use_size { Some((size, SIZE_FACTOR / 3f64.sqrt())) } else { None },
        split_segments: options.split_segments,
        max_vertices: options.max_vertices,
        segments: &domain.segments,
    };
    let mut r = refine::Refiner::new(tri, crit);
    r.run().map_err(|s| match s {
        refine::Stop::Size(p, h) => Error::Size { x: p.x, y: p.y, size: h },
        refine::Stop::TooMany(n) => Error::TooManyVertices(n),
    })?;
    let counts = r.counts;
    let tri = r.tri;
    let small = report::small_input_angles(domain);
    let (below, all, away) = report::below(&tri, domain, &small, theta, options.split_segments);
    let boundary = report::chains(&tri, domain);
    let stats = Stats {
        steiner_interior: counts.interior,
        steiner_on_segments: counts.on_segments,
        small_input_angles: small,
        below,
        smallest_angle: all,
        smallest_angle_away: away,
        refused: counts.refused,
        refused_splits: counts.refused_splits,
    };
    // the domain's own points back (refinement saw them with sub-1e-30 residue made 0)
    let mut vertices = tri.pts;
    vertices[..domain.points.len()].copy_from_slice(&domain.points);
    let mesh = PlanarMesh {
        vertices,
        triangle_tags: vec![options.region; tri.tv.len()],
        triangles: tri.tv,
        quads: Vec::new(),
        quad_tags: Vec::new(),
        region_names: Default::default(),
    };
    Ok(Output { mesh, boundary, stats })
}
