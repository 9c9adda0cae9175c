//! Topology decomposition (the lecture's 23.2.2): ear cutting on a polygon with holes, then
//! refinement of the gross elements to the size field.
//!
//! Stages, one file each:
//! 1. `bridge`: the domain's loops grouped into an outer loop and its holes (islands inside
//!    holes are meshed as components of their own), each hole joined to the outer loop by a
//!    bridge to the nearest mutually visible point (checked exactly);
//! 2. `cut`: ears cut off the bridged cycle, the ear with the largest smallest angle first,
//!    each checked exactly (no vertex that is not strictly convex inside or on it), until
//!    three vertices remain;
//! 3. `trimesh`: Lawson flips to the constrained Delaunay triangulation (exact in-circle,
//!    domain segments never flipped);
//! 4. `refine`: points inserted at circumcenters (centroids where the circumcenter lies
//!    behind a segment or encroaches one) of triangles larger than the size, with point
//!    location and Lawson flips, until every triangle is within the size;
//! 5. `smooth`: a few passes of Laplacian smoothing of the inserted points that keep every
//!    triangle counter-clockwise (exact) and raise the smallest angle around the point,
//!    each followed by Lawson flips.
//!
//! # The boundary
//! The domain's points are final: no point is added on a segment (divide the segments by
//! the size first, [`split_boundary`](crate::mesh2d::boundary::split_boundary)). The output's
//! first vertices are the domain's points, in order; every segment is a mesh edge.
//!
//! # Guarantees
//! A mesh that passes [`PlanarMesh::validate`] and covers the domain exactly, or an error
//! naming why (checked before returning). Deterministic: no hash order, no time budget.

mod bridge;
mod cut;
mod refine;
pub(crate) mod smooth;
pub(crate) mod trimesh;

#[cfg(test)]
pub(crate) mod testkit;
#[cfg(test)]
mod tests;

pub use bridge::LoopError;
pub(crate) use bridge::{blocked, bridge as bridge_holes, components, in_cone};
pub(crate) use cut::cut_ears;

use crate::core::RegionId;
use crate::mesh::PlanarMesh;
use crate::mesh2d::boundary::{check_size, SizeError};
use crate::mesh2d::domain::{Domain, DomainError};
use glam::DVec2;
use trimesh::TriMesh;

/// Options of [`mesh`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct Options {
    /// Refine the gross elements to the size (false: the ear cutting's triangles only, made
    /// constrained Delaunay).
    pub refine: bool,
    /// A triangle is split while its mean edge exceeds this times the size at its centroid.
    pub split_ratio: f64,
    /// Passes of Laplacian smoothing after refinement.
    pub smoothing_passes: usize,
    /// The region tag of every element.
    pub region: RegionId,
}

impl Default for Options {
    fn default() -> Options {
        Options { refine: true, split_ratio: 1.3, smoothing_passes: 3, region: RegionId(1) }
    }
}

impl Options {
    /// With `refine` set.
    pub fn with_refine(mut self, refine: bool) -> Options {
        self.refine = refine;
        self
    }

    /// With the region tag set.
    pub fn with_region(mut self, region: RegionId) -> Options {
        self.region = region;
        self
    }
}

/// Counts of a run of [`mesh`].
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Stats {
    /// Ears cut (the ear cutting's triangles, the last one of each component included).
    pub ears_cut: usize,
    /// Bridges joining holes to outer loops.
    pub bridges: usize,
    /// Points inserted by the refinement.
    pub points_inserted: usize,
    /// Lawson flips (after ear cutting, during refinement and after smoothing).
    pub flips: usize,
    /// Points moved by smoothing.
    pub smoothing_moves: usize,
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
    /// The loops cannot be grouped or bridged.
    #[error("{0}")]
    Loops(#[from] LoopError),
    /// The size field is not positive and finite somewhere it was asked.
    #[error("{0}")]
    Size(#[from] SizeError),
    /// The options are out of range.
    #[error("bad option: {0}")]
    Option(String),
    /// Refinement needed more points than expected of the domain and size.
    #[error("refinement stopped after {0} points (the size is far below the domain's features)")]
    Refinement(usize),
    /// Our own check failed (a bug: reported rather than returned as a bad mesh).
    #[error("internal check failed: {0}")]
    Internal(String),
}

/// Meshes `domain` to the size `size` by ear cutting and refinement (see the module docs).
///
/// # Errors
/// See [`Error`]: an invalid domain or size, loops touching at a point, an option out of
/// range, or a failed internal check.
pub fn mesh(domain: &Domain, size: &dyn Fn(DVec2) -> f64, options: &Options) -> Result<Output, Error> {
    domain.validate()?;
    if !(options.split_ratio > 0.5 && options.split_ratio.is_finite()) {
        return Err(Error::Option(format!("split_ratio {} must be above 0.5", options.split_ratio)));
    }
    let mut stats = Stats::default();
    let mut tris = Vec::new();
    for component in components(domain)? {
        let (cycle, bridges) = bridge_holes(&domain.points, &component)?;
        stats.bridges += bridges;
        let ears = cut_ears(&domain.points, &cycle).ok_or_else(|| Error::Internal(format!("no ear left on the loop through point {}", cycle[0])))?;
        tris.extend(ears);
    }
    stats.ears_cut = tris.len();
    let mut segments: Vec<(u32, u32)> = domain.segments.iter().map(|&[a, b]| (a.min(b), a.max(b))).collect();
    segments.sort_unstable();
    let is_fixed = |a: u32, b: u32| segments.binary_search(&(a.min(b), a.max(b))).is_ok();
    let mut m = TriMesh::new(domain.points.clone(), tris, &is_fixed).ok_or_else(|| Error::Internal("the ears do not tile the domain conformingly".into()))?;
    m.make_delaunay();
    if options.refine {
        let mut estimate = 0.0;
        for t in &m.tris {
            let [a, b, c] = t.map(|v| m.pts[v as usize]);
            let g = (a + b + c) / 3.0;
            let h = check_size(g, size(g))?;
            estimate += 0.5 * (b - a).perp_dot(c - a) / (0.433 * h * h);
        }
        let cap = (20.0 * estimate).min(1e9) as usize + 10 * domain.points.len() + 1000;
        stats.points_inserted = refine::refine(&mut m, size, options.split_ratio, cap)?;
        let boundary = domain.points.len() as u32;
        for _ in 0..options.smoothing_passes {
            let moved = smooth::smooth(&mut m.pts, &m.tris, &|v| v >= boundary, 1);
            stats.smoothing_moves += moved;
            if moved == 0 {
                break;
            }
            m.make_delaunay();
        }
    }
    stats.flips = m.flips;
    let n = m.tris.len();
    let mesh = PlanarMesh { vertices: m.pts, triangles: m.tris, triangle_tags: vec![options.region; n], ..PlanarMesh::default() };
    mesh.validate().map_err(|e| Error::Internal(e.to_string()))?;
    let rel = (mesh.area() - domain.area()).abs() / domain.area();
    if rel > 1e-9 {
        return Err(Error::Internal(format!("the mesh's area differs from the domain's by {rel:e} (relative)")));
    }
    Ok(Output { mesh, stats })
}
