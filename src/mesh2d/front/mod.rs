//! Geometry decomposition by iterative removal of a boundary layer: the advancing-front
//! triangle mesher (Lo; Löhner and Parikh), section 23.2.3 of the lecture.
//!
//! Stages, one file each:
//! 1. the input: a valid [`Domain`] whose points are final (the caller divides its segments
//!    by the size first, [`split_boundary`](crate::mesh2d::boundary::split_boundary); a CAD
//!    face keeps its tessellation's points so that neighbouring faces conform);
//! 2. `grid` and `queue`: the front, the domain's segments at first, directed with the
//!    unmeshed region on their left, in a queue by length (shortest first) and in a uniform
//!    grid;
//! 3. `step`: the shortest front edge gets a triangle on its left, to a front vertex near
//!    the ideal point or to a new point (exact fit tests, a Delaunay check, fallbacks and a
//!    step bound), until the front is empty;
//! 4. `improve`: Lawson flips (domain segments kept) and smoothing of the new points, each
//!    move kept only where no angle around the point gets worse;
//! 5. `check`: [`check_coverage`]: valid, conforming, the boundary kept, the area exact.
//!
//! # What is guaranteed
//! Every mesh returned passes [`check_coverage`]; the domain's points are the first mesh
//! vertices, in order, and no point is added on a segment. The same input gives the same
//! mesh. Angles are not guaranteed but measured ([`FrontStats`], [`ImproveStats`]).

mod check;
mod grid;
mod improve;
mod queue;
mod step;

#[cfg(test)]
mod tests;

pub use check::check_coverage;
pub use step::FrontStats;

use crate::core::RegionId;
use crate::mesh::PlanarMesh;
use crate::mesh2d::boundary::SizeError;
use crate::mesh2d::{Domain, DomainError};
use glam::DVec2;

/// Why a domain could not be meshed.
#[derive(Clone, Debug, PartialEq, thiserror::Error, serde::Serialize)]
#[non_exhaustive]
pub enum Error {
    /// The input is not a valid domain.
    #[error("invalid domain: {0}")]
    Domain(#[from] DomainError),
    /// The size field gave a size that is not positive and finite.
    #[error(transparent)]
    Size(#[from] SizeError),
    /// A domain point on no segment: the front cannot reach it.
    #[error("domain point {point} ({x}, {y}) is on no segment: the advancing front meshes from the boundary only (remove the point or join it to the boundary)")]
    IsolatedPoint {
        /// The point.
        point: u32,
        /// Where.
        x: f64,
        /// Where.
        y: f64,
    },
    /// No triangle could be placed on a front edge, even after the others advanced.
    #[error("the front stalled at edge {from} -> {to} (({x0}, {y0}) -> ({x1}, {y1})): no valid triangle fits on it (a boundary much finer than the size nearby, or a gap narrower than the boundary's pieces; divide the boundary by the size first)")]
    Stalled {
        /// The edge's start (a mesh vertex; the domain's points come first).
        from: u32,
        /// Its end.
        to: u32,
        /// Start.
        x0: f64,
        /// Start.
        y0: f64,
        /// End.
        x1: f64,
        /// End.
        y1: f64,
    },
    /// The front took more steps than the expected element count allows.
    #[error("the front took more than {steps} steps ({triangles} triangles made): the size is far below the size the boundary was divided by")]
    StepLimit {
        /// The bound.
        steps: usize,
        /// Triangles made when it stopped.
        triangles: usize,
    },
    /// An internal check failed (a bug, reported rather than returned as a bad mesh).
    #[error("internal check failed: {0}")]
    Internal(String),
}

/// Options of [`mesh`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct Options {
    /// Smoothing sweeps after the front (each followed by flips); 0 keeps the points where
    /// the front put them.
    pub smooth_passes: usize,
    /// Lawson flips after the front (domain segments never flipped).
    pub flips: bool,
    /// The Delaunay check of each new triangle (no front vertex in its circumcircle).
    pub delaunay_check: bool,
    /// The region tag of every element.
    pub region: RegionId,
}

impl Default for Options {
    fn default() -> Options {
        Options { smooth_passes: 4, flips: true, delaunay_check: true, region: RegionId(1) }
    }
}

impl Options {
    /// With `passes` smoothing sweeps.
    pub fn with_smooth_passes(mut self, passes: usize) -> Options {
        self.smooth_passes = passes;
        self
    }

    /// With or without flips.
    pub fn with_flips(mut self, flips: bool) -> Options {
        self.flips = flips;
        self
    }

    /// With or without the Delaunay check.
    pub fn with_delaunay_check(mut self, check: bool) -> Options {
        self.delaunay_check = check;
        self
    }

    /// With the region tag `region`.
    pub fn with_region(mut self, region: RegionId) -> Options {
        self.region = region;
        self
    }
}

/// Counts and angles of the improvement stage.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct ImproveStats {
    /// Edges flipped.
    pub flips: usize,
    /// Points moved by smoothing (summed over the sweeps).
    pub smoothing_moves: usize,
    /// The smallest angle as the front left the mesh, degrees.
    pub worst_angle_before: f64,
    /// The smallest angle after the improvement, degrees.
    pub worst_angle_after: f64,
}

/// The mesh and how it was made.
#[derive(Clone, Debug, PartialEq)]
pub struct Output {
    /// The triangles, each tagged `options.region`; vertices: the domain's points first (same
    /// indices), then the new interior points.
    pub mesh: PlanarMesh,
    /// The front's counts.
    pub front: FrontStats,
    /// The improvement's counts and angles.
    pub improve: ImproveStats,
}

/// Meshes `domain` by an advancing front to the size `size` (see the module docs).
///
/// # Errors
/// [`Error`]: an invalid domain, an isolated point, a bad size, a stalled front, too many
/// steps, or a failed internal check.
pub fn mesh(domain: &Domain, size: &dyn Fn(DVec2) -> f64, options: &Options) -> Result<Output, Error> {
    domain.validate()?;
    let mut on_segment = vec![false; domain.points.len()];
    for s in &domain.segments {
        on_segment[s[0] as usize] = true;
        on_segment[s[1] as usize] = true;
    }
    if let Some(i) = on_segment.iter().position(|&x| !x) {
        let p = domain.points[i];
        return Err(Error::IsolatedPoint { point: i as u32, x: p.x, y: p.y });
    }
    let expected = expected_triangles(domain, size);
    let mut lengths: Vec<f64> = (0..domain.segments.len()).map(|s| {
        let (a, b) = domain.ends(s);
        a.distance(b)
    }).collect();
    lengths.sort_by(f64::total_cmp);
    let (lo, hi) = domain.bounds();
    let grid = grid::Grid::new(lo, hi, lengths[lengths.len() / 2], 2 * (expected + domain.segments.len()) + 64);
    let mut front = queue::Front::new(grid);
    for s in &domain.segments {
        front.add(s[0], s[1], &domain.points);
    }
    let max_steps = 20 * (expected + domain.segments.len()) + 1000;
    let mut adv = step::Advance::new(domain.points.clone(), front, size, options.delaunay_check);
    adv.run(max_steps)?;
    let front_stats = adv.stats;
    let (mut pts, mut tris) = (adv.pts, adv.tris);
    let mut stats = ImproveStats { worst_angle_before: improve::worst_angle(&pts, &tris), ..ImproveStats::default() };
    {
        let mut imp = improve::Improve::new(&mut pts, &mut tris, &domain.segments, domain.points.len());
        if options.flips {
            stats.flips += imp.flip_all();
        }
        for _ in 0..options.smooth_passes {
            let moved = imp.smooth();
            stats.smoothing_moves += moved;
            if options.flips {
                stats.flips += imp.flip_all();
            }
            if moved == 0 {
                break;
            }
        }
    }
    stats.worst_angle_after = improve::worst_angle(&pts, &tris);
    let mesh = PlanarMesh { vertices: pts, triangle_tags: vec![options.region; tris.len()], triangles: tris, quads: Vec::new(), quad_tags: Vec::new(), region_names: Default::default() };
    check_coverage(domain, &mesh).map_err(Error::Internal)?;
    Ok(Output { mesh, front: front_stats, improve: stats })
}

/// The expected triangle count: the integral of `1 / (√3/4 h²)` over the domain, sampled on
/// a 32 × 32 grid over its bounding box and scaled by the area's share of the box (sizes
/// that are not positive and finite, e.g. outside the domain, are skipped).
fn expected_triangles(domain: &Domain, size: &dyn Fn(DVec2) -> f64) -> usize {
    const N: usize = 32;
    let (lo, hi) = domain.bounds();
    let step = (hi - lo) / N as f64;
    let (mut sum, mut count) = (0.0, 0usize);
    for i in 0..N {
        for j in 0..N {
            let p = lo + step * DVec2::new(i as f64 + 0.5, j as f64 + 0.5);
            let h = size(p);
            if h.is_finite() && h > 0.0 {
                sum += 1.0 / (0.25 * 3f64.sqrt() * h * h);
                count += 1;
            }
        }
    }
    let per_area = if count > 0 { sum / count as f64 } else { 0.0 };
    let e = per_area * domain.area();
    if e.is_finite() { e.min(1e9) as usize } else { 1_000_000_000 }
}
