//! The lecture's quadtree mesher for planar domains (Yerry and Shephard's modified
//! quadtree): quadrants sized by the density, neighbours at most one level apart, interior
//! quadrants split by templates, boundary quadrants cut and triangulated conformingly.
//!
//! Stages, one file each:
//! 1. the input, [`Domain`]: a polygon with holes whose segments carry
//!    tags, checked exactly;
//! 2. `tree`: the quadtree, refined until each quadrant is no larger than the size at its
//!    centre and around boundary features (two segments that share no point within a
//!    quadrant's clearance, two boundary points in one quadrant);
//! 3. `balance`: 2:1 balance across sides, and [`balance::check_balance`];
//! 4. `templates`: interior quadrants (inside, no segment within `clearance · size`) to
//!    triangles by the 2:1 templates (every angle 45° or 90°), or to squares where they have
//!    no hanging node and quadrilaterals are asked for;
//! 5. `band`: the rest of the domain (the boundary quadrants, cut by the boundary) by a
//!    constrained Delaunay triangulation of the segment pieces, the kept lattice points and
//!    the interface to the templates, refined by spade to 25° with constraints kept;
//! 6. `check`: conformity, the boundary kept, angles.
//!
//! # The size
//! A plain closure `h(p)` on the plane's coordinates (for a CAD face, the caller lifts `p`
//! onto the face's plane and asks its `SizeField`; see `mesh2d::face`). It is evaluated at
//! quadrant centres; it must be positive and finite there.
//!
//! # What is guaranteed
//! - Leaves sharing a side differ by at most one level.
//! - Inside (triangles of interior quadrants): every angle is 45° or 90°.
//! - The band: polygon vertices kept exactly, every input segment a union of mesh edges,
//!   conforming with the inside. Its angles are spade's: the refinement aims at 25° but
//!   does not split constraint edges, so a triangle against a short piece or at an input
//!   angle below 25° may stay under it; [`check::angles`] measures it (the corpus figures
//!   are in `docs/benchmarks.md`).
//! - Deterministic: the same input gives the same mesh (node order, fixed maps).

pub(crate) mod balance;
pub(crate) mod band;
pub(crate) mod check;
pub(crate) mod templates;
pub(crate) mod tree;
mod vertices;

#[cfg(test)]
mod tests;

pub use balance::{balance as balance_tree, check_balance, Unbalanced};
pub use check::{angles, check_conforming, Angles, CheckError};
pub use crate::mesh2d::domain::{Domain, DomainError};
pub use tree::{Params, Quadtree, Status};

use crate::core::ids::NONE;
use crate::core::RegionId;
use crate::mesh::PlanarMesh;
use glam::DVec2;

/// Why a domain could not be meshed.
#[derive(Clone, Debug, PartialEq, thiserror::Error, serde::Serialize)]
#[non_exhaustive]
pub enum QuadtreeError {
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
    /// The tree would grow past its limit (a size far below the domain's extent).
    #[error("the quadtree would exceed {0} quadrants (size too small for the domain)")]
    TooManyQuadrants(usize),
    /// The band could not be triangulated.
    #[error("the boundary band could not be triangulated: {0}")]
    Band(String),
    /// An internal check failed (a bug, reported rather than returned as a bad mesh).
    #[error("internal check failed: {0}")]
    Check(String),
}

/// Options of [`mesh`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QuadtreeOptions {
    /// Refinement parameters (the band's clearance, the quadrant limit).
    pub tree: Params,
    /// Band parameters (lattice points kept, refinement).
    pub band: band::BandParams,
    /// Interior quadrants without hanging nodes as squares instead of two triangles.
    pub quads: bool,
    /// The region tag of every element.
    pub region: RegionId,
}

impl Default for QuadtreeOptions {
    fn default() -> QuadtreeOptions {
        QuadtreeOptions { tree: Params::default(), band: band::BandParams::default(), quads: false, region: RegionId(1) }
    }
}

/// Counts of the tree.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct TreeStats {
    /// All quadrants (leaves and parents).
    pub quadrants: usize,
    /// Interior leaves (templates).
    pub interior: usize,
    /// Boundary leaves (band).
    pub boundary: usize,
    /// Exterior leaves (not meshed).
    pub exterior: usize,
    /// Shallowest and deepest level of the leaves that are not exterior.
    pub levels: [u8; 2],
    /// Leaves sharing a side differ by at most one level ([`check_balance`]).
    pub balanced: bool,
    /// Points spade's refinement added in the band.
    pub refinement_points: usize,
}

/// The mesh and what it was made of.
#[derive(Clone, Debug)]
pub struct QuadtreeMesh {
    /// The elements: the template triangles first (`..inside_triangles`), then the band's.
    pub mesh: PlanarMesh,
    /// How many of the first triangles come from the templates.
    pub inside_triangles: usize,
    /// Per input segment, its vertex ids from start to end (the boundary kept).
    pub boundary: Vec<Vec<u32>>,
    /// The tree's counts.
    pub stats: TreeStats,
}

/// Meshes `domain` to the size `size` (see the module docs).
///
/// # Errors
/// [`QuadtreeError`]: an invalid domain, a bad size, too many quadrants, a band that could
/// not be triangulated, or a failed internal check.
pub fn mesh(domain: &Domain, size: &dyn Fn(DVec2) -> f64, options: &QuadtreeOptions) -> Result<QuadtreeMesh, QuadtreeError> {
    domain.validate()?;
    let tree = build_tree(domain, size, options.tree)?;
    check_balance(&tree).map_err(|e| QuadtreeError::Check(e.to_string()))?;
    let mut vertices = vertices::Vertices::default();
    let t = templates::build(&tree, &mut vertices, options.quads);
    let b = band::build(&tree, domain, &mut vertices, &t.interface, options.band)?;
    let mut stats = TreeStats { quadrants: tree.nodes.len(), balanced: true, refinement_points: b.refinement_points, levels: [u8::MAX, 0], ..TreeStats::default() };
    for i in tree.leaves() {
        let q = &tree.nodes[i as usize];
        match q.status {
            Status::Interior => stats.interior += 1,
            Status::Boundary => stats.boundary += 1,
            Status::Exterior => stats.exterior += 1,
        }
        if q.status != Status::Exterior {
            stats.levels = [stats.levels[0].min(q.level), stats.levels[1].max(q.level)];
        }
    }
    // compact: only vertices some element or chain uses, in first-use order
    let inside_triangles = t.triangles.len();
    let mut triangles = t.triangles;
    triangles.extend(b.triangles);
    let mut remap = vec![NONE; vertices.positions.len()];
    let mut positions = Vec::new();
    let mut take = |i: u32, positions: &mut Vec<DVec2>| -> u32 {
        if remap[i as usize] == NONE {
            remap[i as usize] = positions.len() as u32;
            positions.push(vertices.positions[i as usize]);
        }
        remap[i as usize]
    };
    let boundary: Vec<Vec<u32>> = b.chains.iter().map(|c| c.iter().map(|&i| take(i, &mut positions)).collect()).collect();
    let triangles: Vec<[u32; 3]> = triangles.iter().map(|t| t.map(|i| take(i, &mut positions))).collect();
    let quads: Vec<[u32; 4]> = t.quads.iter().map(|q| q.map(|i| take(i, &mut positions))).collect();
    let mesh = PlanarMesh {
        vertices: positions,
        triangle_tags: vec![options.region; triangles.len()],
        triangles,
        quad_tags: vec![options.region; quads.len()],
        quads,
        region_names: Default::default(),
    };
    let out = QuadtreeMesh { mesh, inside_triangles, boundary, stats };
    check_conforming(&out, domain).map_err(|e| QuadtreeError::Check(e.to_string()))?;
    Ok(out)
}

/// The refined and balanced quadtree of `domain` (stages 2 and 3), the tree [`mesh`]
/// meshes; for checks and reports.
///
/// # Errors
/// A bad size or too many quadrants.
pub fn build_tree(domain: &Domain, size: &dyn Fn(DVec2) -> f64, params: Params) -> Result<Quadtree, QuadtreeError> {
    let mut tree = Quadtree::new(domain, params);
    tree.refine(domain, size)?;
    balance::balance(&mut tree, domain)?;
    Ok(tree)
}

/// [`mesh`] with the same size everywhere.
///
/// # Errors
/// As [`mesh`].
pub fn mesh_uniform(domain: &Domain, size: f64, options: &QuadtreeOptions) -> Result<QuadtreeMesh, QuadtreeError> {
    mesh(domain, &|_| size, options)
}
