//! Geometry decomposition by recursive subdivision (the lecture's 23.2.3, Bykat): the
//! region is cut into convex pieces, each convex piece is cut near the middle of its
//! longest axis with nodes on the cut by the size field, recursively, until the pieces are
//! triangles.
//!
//! Stages, one file each:
//! 1. holes joined to their outer loop by cuts (the bridges of [`ear`](crate::mesh2d::ear),
//!    with nodes placed on them by the size), islands in holes meshed on their own;
//! 2. `choose`: which cut next: from the most reflex vertex while one is reflex (the
//!    non-convex region split into convex pieces), else across the middle of the longest
//!    axis, the candidate cuts scored by the angles they leave at their ends;
//! 3. `split`: nodes on the cut by the size field, the cut checked exactly (a diagonal: in
//!    the cone at both ends, no piece meeting the polygon's edges), the two polygons;
//!    pieces with no valid shortlisted cut try every pair of vertices, then ear cutting;
//! 4. smoothing of the nodes on cuts (the shared `ear::smooth`: moves that keep every
//!    triangle counter-clockwise, exact, and raise the smallest angle around the node).
//!
//! # The boundary
//! The domain's points are final: no point is added on a segment (divide the segments by
//! the size first, [`split_boundary`](crate::mesh2d::boundary::split_boundary)). The output's
//! first vertices are the domain's points, in order; every segment is a mesh edge.
//!
//! # Guarantees
//! A mesh that passes [`PlanarMesh::validate`] and covers the domain exactly, or an error
//! naming why (checked before returning). Deterministic: no hash order, no time budget.

mod choose;
mod split;

#[cfg(test)]
mod tests;

use crate::core::predicates::orient2d;
use crate::core::{RegionId, Sign};
use crate::mesh::PlanarMesh;
use crate::mesh2d::boundary::{check_size, SizeError};
use crate::mesh2d::domain::{Domain, DomainError};
use crate::mesh2d::ear::{bridge_holes, components, cut_ears, smooth::smooth, LoopError};
use glam::DVec2;
use std::collections::BTreeMap;

/// Options of [`mesh`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct Options {
    /// Passes of Laplacian smoothing of the nodes on cuts (each move only where it raises
    /// the smallest angle around the node).
    pub smoothing_passes: usize,
    /// The region tag of every element.
    pub region: RegionId,
}

impl Default for Options {
    fn default() -> Options {
        Options { smoothing_passes: 3, region: RegionId(1) }
    }
}

impl Options {
    /// With the region tag set.
    pub fn with_region(mut self, region: RegionId) -> Options {
        self.region = region;
        self
    }

    /// With the smoothing passes set.
    pub fn with_smoothing_passes(mut self, passes: usize) -> Options {
        self.smoothing_passes = passes;
        self
    }
}

/// Counts of a run of [`mesh`].
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Stats {
    /// Cuts made (bridges to holes, reflex cuts and axis cuts).
    pub cuts: usize,
    /// Of them, cuts from a reflex vertex (the convex decomposition) and bridges.
    pub reflex_cuts: usize,
    /// Deepest level of recursion (a component's cycle is level 0).
    pub depth: usize,
    /// Nodes placed on cuts.
    pub points_on_cuts: usize,
    /// Pieces no shortlisted cut could split, triangulated by trying every pair of vertices
    /// or by ear cutting.
    pub fallbacks: usize,
    /// Nodes moved by smoothing.
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
    /// More cuts than expected of the domain and size.
    #[error("subdivision stopped after {0} cuts (the size is far below the domain's features)")]
    TooManyCuts(usize),
    /// Our own check failed (a bug: reported rather than returned as a bad mesh).
    #[error("internal check failed: {0}")]
    Internal(String),
}

/// Meshes `domain` to the size `size` by recursive subdivision (see the module docs).
///
/// # Errors
/// See [`Error`]: an invalid domain or size, loops touching at a point, or a failed
/// internal check.
pub fn mesh(domain: &Domain, size: &dyn Fn(DVec2) -> f64, options: &Options) -> Result<Output, Error> {
    domain.validate()?;
    let mut stats = Stats::default();
    let mut pts = domain.points.clone();
    let mut segments: Vec<(u32, u32)> = domain.segments.iter().map(|&[a, b]| (a, b)).collect();
    segments.sort_unstable();
    let mut estimate = 0.0;
    for &[a, b] in &domain.segments {
        let p = domain.points[a as usize];
        let h = check_size(p, size(p))?;
        estimate += domain.points[b as usize].distance(p) / h;
    }
    let cap = (8.0 * estimate * estimate).min(1e9) as usize + 1000;
    let mut stack: Vec<(Vec<u32>, usize)> = Vec::new();
    for component in components(domain)? {
        let (cycle, _) = bridge_holes(&domain.points, &component)?;
        // the bridges become cuts with nodes, shared by their two sides
        let mut nodes: BTreeMap<(u32, u32), Vec<u32>> = BTreeMap::new();
        let mut poly = Vec::with_capacity(cycle.len());
        for k in 0..cycle.len() {
            let (a, b) = (cycle[k], cycle[(k + 1) % cycle.len()]);
            poly.push(a);
            if segments.binary_search(&(a, b)).is_ok() {
                continue;
            }
            let key = (a.min(b), a.max(b));
            if !nodes.contains_key(&key) {
                let (p, q) = (pts[key.0 as usize], pts[key.1 as usize]);
                let new = split::cut_nodes(p, q, size)?;
                let base = pts.len() as u32;
                pts.extend_from_slice(&new);
                nodes.insert(key, (base..base + new.len() as u32).collect());
                stats.cuts += 1;
                stats.reflex_cuts += 1;
                stats.points_on_cuts += new.len();
            }
            let chain = &nodes[&key];
            if a < b {
                poly.extend(chain.iter());
            } else {
                poly.extend(chain.iter().rev());
            }
        }
        stack.push((poly, 0));
    }
    let mut tris: Vec<[u32; 3]> = Vec::new();
    while let Some((poly, depth)) = stack.pop() {
        stats.depth = stats.depth.max(depth);
        if poly.len() == 3 {
            let t = [poly[0], poly[1], poly[2]];
            if orient2d(pts[t[0] as usize], pts[t[1] as usize], pts[t[2] as usize]) != Sign::Positive {
                return Err(Error::Internal(format!("piece {t:?} is not a counter-clockwise triangle")));
            }
            tris.push(t);
            continue;
        }
        if stats.cuts >= cap {
            return Err(Error::TooManyCuts(stats.cuts));
        }
        // reflex cuts first, then axis cuts, then (small pieces) every pair
        let reflex = choose::reflex_candidates(&pts, &poly);
        let reflex_count = reflex.len();
        let shortlist: Vec<(usize, usize)> = reflex.into_iter().chain(choose::axis_candidates(&pts, &poly)).collect();
        let mut cut = None;
        for (k, &(x, y)) in shortlist.iter().enumerate() {
            if let Some(c) = split::try_cut(&mut pts, &poly, x, y, size)? {
                stats.reflex_cuts += usize::from(k < reflex_count);
                cut = Some(c);
                break;
            }
        }
        if cut.is_none() && poly.len() <= 24 {
            for (x, y) in choose::all_candidates(&pts, &poly) {
                if let Some(c) = split::try_cut(&mut pts, &poly, x, y, size)? {
                    stats.fallbacks += 1;
                    cut = Some(c);
                    break;
                }
            }
        }
        match cut {
            Some(c) => {
                stats.cuts += 1;
                stats.points_on_cuts += c.nodes;
                stack.push((c.right, depth + 1));
                stack.push((c.left, depth + 1));
            }
            None => {
                stats.fallbacks += 1;
                let ears = cut_ears(&pts, &poly).ok_or_else(|| Error::Internal(format!("no cut and no ear in the piece through point {}", poly[0])))?;
                tris.extend(ears);
            }
        }
    }
    let boundary = domain.points.len() as u32;
    stats.smoothing_moves = smooth(&mut pts, &tris, &|v| v >= boundary, options.smoothing_passes);
    let n = tris.len();
    let mesh = PlanarMesh { vertices: pts, triangles: tris, triangle_tags: vec![options.region; n], ..PlanarMesh::default() };
    mesh.validate().map_err(|e| Error::Internal(e.to_string()))?;
    let rel = (mesh.area() - domain.area()).abs() / domain.area();
    if rel > 1e-9 {
        return Err(Error::Internal(format!("the mesh's area differs from the domain's by {rel:e} (relative)")));
    }
    Ok(Output { mesh, stats })
}
