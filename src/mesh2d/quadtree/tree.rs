//! The quadtree: quadrants, their refinement by size and by boundary features, neighbours.
//!
//! - Stage: first (build and refine), before balancing.
//! - Inputs: a checked [`Domain`], a size function `h(p)` in the plane and [`Params`].
//! - Output: a [`Quadtree`] whose leaves cover a square holding the domain with a margin.
//! - Invariants: quadrant `(level, x, y)` is the square `origin + side / 2^level · ([x, x+1] ×
//!   [y, y+1])`; corners are integer lattice points at [`MAX_LEVEL`] (exact, shared by every
//!   quadrant that has them); a node has no children or four (`children..children + 4`, in the
//!   order `(0,0) (1,0) (0,1) (1,1)`); each leaf lists the boundary segments within
//!   `clearance · size` of its square (`near`) and is [`Status::Interior`] (none near, inside),
//!   [`Status::Exterior`] (none near, outside) or [`Status::Boundary`] (some near).
//!
//! A leaf is split while it is larger than `h` at its centre (exterior leaves excepted), and,
//! for boundary leaves, while two boundary segments that share no point come within its
//! clearance (gaps, narrow parts and the sides of short edges are resolved) or its closed
//! square holds two boundary points (every polygon vertex gets a quadrant of its own):
//! Yerry and Shephard's modified-quadtree refinement, with the clearance band of the lecture.

use crate::mesh2d::domain::{Domain, segment_square_distance};
use super::QuadtreeError;
use crate::core::ids::NONE;
use glam::DVec2;

/// The deepest level (lattice coordinates are below `2^MAX_LEVEL`, quadrants at least
/// `2^-MAX_LEVEL` of the root, about 1e-9).
pub const MAX_LEVEL: u8 = 30;

/// What a leaf is with respect to the domain.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// Inside, no boundary segment within the clearance: meshed by templates.
    Interior,
    /// Outside, no boundary segment within the clearance: not meshed.
    Exterior,
    /// A boundary segment within the clearance: meshed with the boundary.
    Boundary,
}

/// One quadrant.
#[derive(Clone, Debug)]
pub struct Quadrant {
    /// Depth (the root is 0).
    pub level: u8,
    /// Column at its level.
    pub x: u32,
    /// Row at its level.
    pub y: u32,
    /// First of four children, or `NONE` for a leaf.
    pub children: u32,
    /// Boundary segments within the clearance (leaves only; emptied when split).
    pub near: Vec<u32>,
    /// Interior, exterior or boundary.
    pub status: Status,
}

impl Quadrant {
    /// Whether it has no children.
    #[inline]
    pub fn is_leaf(&self) -> bool {
        self.children == NONE
    }
}

/// Refinement parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Params {
    /// Width of the band around the boundary, in quadrant sizes: a leaf closer than
    /// `clearance · size` to a boundary segment is a boundary leaf.
    pub clearance: f64,
    /// Refuse to grow past this many quadrants.
    pub max_quadrants: usize,
}

impl Default for Params {
    fn default() -> Params {
        Params { clearance: 0.5, max_quadrants: 4_000_000 }
    }
}

/// The four directions: `-x`, `+x`, `-y`, `+y`.
pub const DIRECTIONS: [(i64, i64); 4] = [(-1, 0), (1, 0), (0, -1), (0, 1)];

/// A quadtree over a square.
#[derive(Clone, Debug)]
pub struct Quadtree {
    /// Lower-left corner of the root.
    pub origin: DVec2,
    /// Side of the root.
    pub side: f64,
    /// All quadrants; the root is 0.
    pub nodes: Vec<Quadrant>,
    /// The clearance the leaves were classified with.
    pub params: Params,
}

impl Quadtree {
    /// The root square around `domain`: centred on its box, side 1.25 times its larger
    /// extent.
    pub fn new(domain: &Domain, params: Params) -> Quadtree {
        let (lo, hi) = domain.bounds();
        let ext = (hi - lo).max_element().max(f64::MIN_POSITIVE);
        let side = 1.25 * ext;
        let origin = 0.5 * (lo + hi) - DVec2::splat(0.5 * side);
        let near: Vec<u32> = (0..domain.segments.len() as u32).collect();
        let root = Quadrant { level: 0, x: 0, y: 0, children: NONE, near, status: Status::Boundary };
        Quadtree { origin, side, nodes: vec![root], params }
    }

    /// Side of a quadrant at `level`.
    #[inline]
    pub fn size(&self, level: u8) -> f64 {
        self.side / (1u64 << level) as f64
    }

    /// Lower-left corner of quadrant `i`.
    #[inline]
    pub fn lo(&self, i: u32) -> DVec2 {
        let q = &self.nodes[i as usize];
        self.point(lattice(q.level, q.x, q.y))
    }

    /// Centre of quadrant `i`.
    #[inline]
    pub fn centre(&self, i: u32) -> DVec2 {
        let q = &self.nodes[i as usize];
        self.lo(i) + DVec2::splat(0.5 * self.size(q.level))
    }

    /// The position of a lattice point.
    #[inline]
    pub fn point(&self, (ix, iy): (u32, u32)) -> DVec2 {
        let unit = self.side / (1u64 << MAX_LEVEL) as f64;
        self.origin + DVec2::new(ix as f64 * unit, iy as f64 * unit)
    }

    /// Indices of the leaves, in node order.
    pub fn leaves(&self) -> impl Iterator<Item = u32> + '_ {
        (0..self.nodes.len() as u32).filter(|&i| self.nodes[i as usize].is_leaf())
    }

    /// The deepest node at a level at most `level` containing cell `(level, x, y)`.
    pub fn locate(&self, level: u8, x: u32, y: u32) -> u32 {
        let mut i = 0u32;
        loop {
            let q = &self.nodes[i as usize];
            if q.level >= level || q.is_leaf() {
                return i;
            }
            let bit = level - q.level - 1;
            let (cx, cy) = ((x >> bit) & 1, (y >> bit) & 1);
            i = q.children + cx + 2 * cy;
        }
    }

    /// The node across side `dir` (see `DIRECTIONS`) of quadrant `i`: at its level (which
    /// may have children: finer neighbours) or a coarser leaf; `None` past the root.
    pub fn neighbour(&self, i: u32, dir: usize) -> Option<u32> {
        let q = &self.nodes[i as usize];
        let (dx, dy) = DIRECTIONS[dir];
        let (nx, ny) = (q.x as i64 + dx, q.y as i64 + dy);
        let n = 1i64 << q.level;
        if nx < 0 || ny < 0 || nx >= n || ny >= n {
            return None;
        }
        Some(self.locate(q.level, nx as u32, ny as u32))
    }

    /// The two children of node `n` along its side facing direction `dir` seen from the
    /// quadrant it neighbours (that is, `n`'s side `dir ^ 1`), in increasing coordinate.
    pub fn children_facing(&self, n: u32, dir: usize) -> [u32; 2] {
        let c = self.nodes[n as usize].children;
        match dir {
            0 => [c + 1, c + 3], // neighbour on -x: its +x children
            1 => [c, c + 2],
            2 => [c + 2, c + 3], // neighbour on -y: its +y children
            _ => [c, c + 1],
        }
    }

    /// Splits leaf `i` into four, giving each child its near segments and status.
    ///
    /// # Errors
    /// [`QuadtreeError::TooManyQuadrants`] past `params.max_quadrants`.
    pub fn split(&mut self, i: u32, domain: &Domain) -> Result<(), QuadtreeError> {
        if self.nodes.len() + 4 > self.params.max_quadrants {
            return Err(QuadtreeError::TooManyQuadrants(self.params.max_quadrants));
        }
        let near = std::mem::take(&mut self.nodes[i as usize].near);
        let (level, x, y, status) = {
            let q = &self.nodes[i as usize];
            (q.level + 1, 2 * q.x, 2 * q.y, q.status)
        };
        let first = self.nodes.len() as u32;
        let s = self.size(level);
        for k in 0..4u32 {
            let (cx, cy) = (x + (k & 1), y + (k >> 1));
            let lo = self.point(lattice(level, cx, cy));
            let child_near: Vec<u32> = if status == Status::Boundary {
                near.iter().copied().filter(|&seg| {
                    let (a, b) = domain.ends(seg as usize);
                    segment_square_distance(a, b, lo, s) <= self.params.clearance * s
                }).collect()
            } else {
                Vec::new()
            };
            let child_status = if !child_near.is_empty() {
                Status::Boundary
            } else if status != Status::Boundary {
                status
            } else if domain.contains(lo + DVec2::splat(0.5 * s)) {
                Status::Interior
            } else {
                Status::Exterior
            };
            self.nodes.push(Quadrant { level, x: cx, y: cy, children: NONE, near: child_near, status: child_status });
        }
        self.nodes[i as usize].children = first;
        Ok(())
    }

    /// Whether leaf `i` must be split: larger than the size at its centre (not exterior), or
    /// a boundary leaf near two segments that share no point, or holding two boundary points.
    fn wants_split(&self, i: u32, domain: &Domain, size: &dyn Fn(DVec2) -> f64) -> Result<bool, QuadtreeError> {
        let q = &self.nodes[i as usize];
        if q.level >= MAX_LEVEL {
            return Ok(false);
        }
        let s = self.size(q.level);
        if q.status != Status::Exterior {
            let c = self.centre(i);
            let h = size(c);
            if !(h.is_finite() && h > 0.0) {
                return Err(QuadtreeError::Size { x: c.x, y: c.y, size: h });
            }
            if s > h {
                return Ok(true);
            }
        }
        if q.status != Status::Boundary {
            return Ok(false);
        }
        for (k, &a) in q.near.iter().enumerate() {
            let [a0, a1] = domain.segments[a as usize];
            for &b in &q.near[k + 1..] {
                let [b0, b1] = domain.segments[b as usize];
                if a0 != b0 && a0 != b1 && a1 != b0 && a1 != b1 {
                    return Ok(true);
                }
            }
        }
        let lo = self.lo(i);
        let hi = lo + DVec2::splat(s);
        let mut held = Vec::new();
        for &seg in &q.near {
            for p in domain.segments[seg as usize] {
                let v = domain.points[p as usize];
                if v.x >= lo.x && v.x <= hi.x && v.y >= lo.y && v.y <= hi.y && !held.contains(&p) {
                    held.push(p);
                    if held.len() > 1 {
                        return Ok(true);
                    }
                }
            }
        }
        Ok(false)
    }

    /// Refines the leaves by the size and the boundary features (see the module docs), in
    /// node order (deterministic).
    ///
    /// # Errors
    /// A size that is not positive and finite, or too many quadrants.
    pub fn refine(&mut self, domain: &Domain, size: &dyn Fn(DVec2) -> f64) -> Result<(), QuadtreeError> {
        let mut i = 0u32;
        while (i as usize) < self.nodes.len() {
            if self.nodes[i as usize].is_leaf() && self.wants_split(i, domain, size)? {
                self.split(i, domain)?;
            }
            i += 1;
        }
        Ok(())
    }
}

/// The lattice coordinates (at [`MAX_LEVEL`]) of the lower-left corner of quadrant
/// `(level, x, y)`.
#[inline]
pub fn lattice(level: u8, x: u32, y: u32) -> (u32, u32) {
    let shift = MAX_LEVEL - level;
    (x << shift, y << shift)
}
