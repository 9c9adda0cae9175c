//! The surface topology report: what a [`TriSurface`] is, topologically and geometrically.
//!
//! Input: a `TriSurface` (not necessarily valid) and [`ReportOptions`]. Output: a
//! [`SurfaceReport`] (serialisable) with counts, one [`ShellReport`] per edge-connected
//! component, and lists that name offending edges and triangles; plus the lists on their own
//! ([`open_edges_list`], [`nonmanifold_edges_list`], [`boundary_loops`],
//! [`intersecting_pairs`], [`triangle_shells`]) for error messages of later stages.
//!
//! # Definitions and invariants
//! - Triangles with an index out of range or a repeated index are *invalid*: counted in
//!   [`SurfaceReport::invalid_triangles`] (repeated ones also as degenerate) and left out of
//!   everything else. Every triangle index the report gives is an index into
//!   `s.triangles`.
//! - An edge is an unordered vertex pair used by a triangle. *Open*: one triangle; *non-manifold*:
//!   more than two. *Closed*: every edge has exactly two triangles (and there is one).
//! - Components (*shells*) join triangles across shared edges (non-manifold ones included);
//!   they are numbered in the order of their smallest triangle index.
//! - A vertex is *manifold* when its triangles form one fan (joined across its two-triangle
//!   edges); endpoints of non-manifold edges, bow-ties and shells touching at a vertex are not.
//! - *Oriented*: every edge's triangles traverse it as often in each direction (an
//!   interior edge once each way). *Orientable*: some choice of flips makes it so.
//! - Euler characteristic `V - E + F` counts only vertices used by a valid triangle. Genus
//!   `(2 - χ) / 2` is given for closed, manifold, orientable shells.
//! - Volume is the signed volume by the divergence theorem (positive for an outward closed
//!   surface); nesting of closed shells is decided with exact ray parity, and a shell inside
//!   an odd number of closed shells is a cavity, outward when its volume is negative.
//! - Degeneracy (zero area) and self-intersection are decided exactly
//!   (`crate::core::intersection`); degenerate triangles are not tested for intersection.
//! - Every result is deterministic: the same input gives the same report for any number of
//!   threads. Flat sorted arrays, no hash maps; about linear time plus the intersection pass.

mod boundary;
mod edges;
mod flat_pieces;
mod nesting;
mod self_intersection;
mod shells;
#[cfg(test)]
mod tests;

pub use boundary::boundary_loops;
pub use edges::{nonmanifold_edges_list, open_edges_list};
pub use flat_pieces::flat_pieces;
pub use self_intersection::intersecting_pairs;
pub use shells::triangle_shells;

use crate::core::ids::INDEX_MAX;
use crate::core::bvh::Bvh;
use crate::core::intersection::is_degenerate;
use crate::core::{Aabb, FaceId};
use crate::mesh::TriSurface;
use glam::DVec3;
use rayon::prelude::*;
use serde::Serialize;
use std::borrow::Cow;

/// What to compute and how much to list.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct ReportOptions {
    /// Run the exact self-intersection test (default `true`).
    pub self_intersections: bool,
    /// How many offending items (intersecting pairs, degenerate triangles) to list
    /// (default 10).
    pub max_listed: usize,
}

impl Default for ReportOptions {
    fn default() -> Self {
        ReportOptions { self_intersections: true, max_listed: 10 }
    }
}

impl ReportOptions {
    /// Sets [`ReportOptions::self_intersections`].
    pub fn with_self_intersections(mut self, on: bool) -> Self {
        self.self_intersections = on;
        self
    }

    /// Sets [`ReportOptions::max_listed`].
    pub fn with_max_listed(mut self, n: usize) -> Self {
        self.max_listed = n;
        self
    }
}

/// Two intersecting triangles and their face tags.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize)]
pub struct IntersectingPair {
    /// The first triangle (the smaller index).
    pub a: u32,
    /// The second triangle.
    pub b: u32,
    /// Tag of `a`.
    pub tag_a: FaceId,
    /// Tag of `b`.
    pub tag_b: FaceId,
}

/// One edge-connected component of the surface.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ShellReport {
    /// Its smallest triangle index (shells are numbered in this order).
    pub first_triangle: u32,
    /// Triangles.
    pub triangles: usize,
    /// Vertices used.
    pub vertices: usize,
    /// Edges.
    pub edges: usize,
    /// Every edge has exactly two triangles.
    pub closed: bool,
    /// No edge has more than two triangles.
    pub edge_manifold: bool,
    /// Every vertex's triangles of this shell form one fan.
    pub vertex_manifold: bool,
    /// Consistently oriented (see the module docs).
    pub oriented: bool,
    /// Some choice of flips orients it consistently (false for a Möbius strip).
    pub orientable: bool,
    /// `V - E + F`.
    pub euler: i64,
    /// `(2 - euler) / 2`, only for closed, manifold, orientable shells.
    pub genus: Option<i64>,
    /// Signed volume (divergence theorem); meaningful only when closed and oriented.
    pub volume: f64,
    /// Area.
    pub area: f64,
    /// Number of other closed shells that contain it (closed shells only, when decided).
    pub depth: Option<usize>,
    /// The innermost closed shell containing it, by index into [`SurfaceReport::shells`].
    pub parent: Option<usize>,
    /// For a closed, oriented shell whose nesting was decided: whether its orientation is
    /// right (positive volume at even depth, negative inside an odd number of shells).
    pub outward: Option<bool>,
    /// The distinct face tags, increasing.
    pub tags: Vec<FaceId>,
    /// `[[xmin, ymin, zmin], [xmax, ymax, zmax]]`.
    pub bbox: Option<[[f64; 3]; 2]>,
}

/// The topology and geometry of a triangle surface; see the module docs for definitions.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SurfaceReport {
    /// Vertices in the surface.
    pub vertices: usize,
    /// Vertices used by a valid triangle.
    pub used_vertices: usize,
    /// Triangles in the surface.
    pub triangles: usize,
    /// Triangles with an out-of-range or repeated index, left out of the rest.
    pub invalid_triangles: usize,
    /// Triangles of zero area (exactly), including those with a repeated index.
    pub degenerate_triangles: usize,
    /// The first degenerate triangles (at most `max_listed`).
    pub first_degenerate: Vec<u32>,
    /// Distinct edges.
    pub edges: usize,
    /// Edge-connected components.
    pub components: usize,
    /// One report per component.
    pub shells: Vec<ShellReport>,
    /// Every edge has exactly two triangles.
    pub closed: bool,
    /// Edge-manifold and vertex-manifold.
    pub manifold: bool,
    /// No edge has more than two triangles.
    pub edge_manifold: bool,
    /// Every vertex's triangles form one fan.
    pub vertex_manifold: bool,
    /// Every edge is traversed as often in each direction.
    pub oriented: bool,
    /// Closed, and every shell is outward.
    pub outward: bool,
    /// Edges with one triangle.
    pub open_edges: usize,
    /// Edges with more than two triangles.
    pub nonmanifold_edges: usize,
    /// Vertices whose triangles form more than one fan.
    pub nonmanifold_vertices: usize,
    /// Edges whose triangles do not traverse it equally often in each direction.
    pub misoriented_edges: usize,
    /// `V - E + F` of the whole surface.
    pub euler: i64,
    /// Sum of the shells' genera, when closed, manifold and oriented.
    pub genus: Option<i64>,
    /// Sum of the shells' signed volumes.
    pub volume: f64,
    /// Total area.
    pub area: f64,
    /// Number of closed loops formed by open edges.
    pub boundary_loops: usize,
    /// Edge count of each boundary loop.
    pub boundary_loop_edges: Vec<usize>,
    /// Chains of open edges that do not close (only around non-manifold configurations).
    pub boundary_chains: usize,
    /// Number of intersecting triangle pairs (exact), `None` when not tested.
    pub self_intersections: Option<usize>,
    /// The first intersecting pairs in increasing order (at most `max_listed`).
    pub first_intersections: Vec<IntersectingPair>,
    /// `[[xmin, ymin, zmin], [xmax, ymax, zmax]]` of all vertices.
    pub bbox: Option<[[f64; 3]; 2]>,
}

/// The valid triangles of a surface, numbered densely, with the way back.
pub(crate) struct Prepared<'a> {
    pub verts: &'a [DVec3],
    pub tris: Cow<'a, [[u32; 3]]>,
    /// Original index of every valid triangle; `None` when all are valid.
    orig: Option<Vec<u32>>,
    /// Original indices of the invalid triangles with a repeated index.
    pub repeated: Vec<u32>,
    pub invalid: usize,
}

impl<'a> Prepared<'a> {
    pub fn new(s: &'a TriSurface) -> Prepared<'a> {
        let nv = s.vertices.len();
        // indices are u32 throughout (corner ids 3t + k included)
        let limit = (INDEX_MAX / 3) as usize;
        let ok = |t: &[u32; 3]| t.iter().all(|&v| (v as usize) < nv) && t[0] != t[1] && t[1] != t[2] && t[0] != t[2];
        let all_ok = s.triangles.len() <= limit && s.triangles.iter().all(ok);
        if all_ok {
            return Prepared {
                verts: &s.vertices,
                tris: Cow::Borrowed(&s.triangles),
                orig: None,
                repeated: Vec::new(),
                invalid: 0,
            };
        }
        let mut tris = Vec::new();
        let mut orig = Vec::new();
        let mut repeated = Vec::new();
        for (i, t) in s.triangles.iter().enumerate().take(limit) {
            if ok(t) {
                tris.push(*t);
                orig.push(i as u32);
            } else if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
                repeated.push(i as u32);
            }
        }
        let invalid = s.triangles.len() - tris.len();
        Prepared { verts: &s.vertices, tris: Cow::Owned(tris), orig: Some(orig), repeated, invalid }
    }

    /// The original index of valid triangle `t`.
    #[inline]
    pub fn orig(&self, t: usize) -> u32 {
        self.orig.as_ref().map_or(t as u32, |o| o[t])
    }

    /// Corner positions of valid triangle `t`.
    #[inline]
    pub fn corners(&self, t: usize) -> [DVec3; 3] {
        self.tris[t].map(|v| self.verts[v as usize])
    }

    /// Exact zero-area flag per valid triangle.
    pub fn degenerate_flags(&self) -> Vec<bool> {
        self.tris
            .par_iter()
            .map(|t| {
                let [a, b, c] = t.map(|v| self.verts[v as usize]);
                is_degenerate(a, b, c)
            })
            .collect()
    }

    /// A BVH over the non-degenerate valid triangles (item = valid triangle index).
    pub fn bvh(&self, degenerate: &[bool]) -> Bvh {
        let boxes: Vec<(u32, Aabb)> = (0..self.tris.len())
            .into_par_iter()
            .filter(|&t| !degenerate[t])
            .map(|t| (t as u32, Aabb::from_points(&self.corners(t))))
            .collect();
        Bvh::build(boxes)
    }
}

/// Computes the [`SurfaceReport`] of `s`.
///
/// ```
/// use fepre::mesh::topology::{surface_report, ReportOptions};
/// use fepre::mesh::TriSurface;
/// use fepre::core::FaceId;
/// use glam::DVec3;
/// // a tetrahedron, outward
/// let v = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
/// let s = TriSurface::with_single_tag(v, vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]], FaceId(1));
/// let r = surface_report(&s, &ReportOptions::default());
/// assert!(r.closed && r.manifold && r.oriented && r.outward);
/// assert_eq!((r.euler, r.genus, r.self_intersections), (2, Some(0), Some(0)));
/// assert!((r.volume - 1.0 / 6.0).abs() < 1e-15);
/// ```
pub fn surface_report(s: &TriSurface, opts: &ReportOptions) -> SurfaceReport {
    let m = Prepared::new(s);
    let n = opts.max_listed;
    let degenerate = m.degenerate_flags();
    let mut first_degenerate: Vec<u32> =
        (0..m.tris.len()).filter(|&t| degenerate[t]).map(|t| m.orig(t)).chain(m.repeated.iter().copied()).collect();
    let degenerate_triangles = first_degenerate.len();
    first_degenerate.sort_unstable();
    first_degenerate.truncate(n);

    let et = edges::EdgeTable::build(&m.tris, m.verts.len());
    let sh = shells::analyse(&m, &et, &s.face_tags);
    let closed_shells = sh.shells.iter().filter(|x| x.closed()).count();
    let need_bvh = opts.self_intersections || closed_shells >= 2;
    let bvh = if need_bvh { m.bvh(&degenerate) } else { Bvh::default() };
    let nest = nesting::nest(&m, &sh, &bvh, &degenerate);
    let (self_intersections, first_intersections) = if opts.self_intersections {
        let (count, pairs) = self_intersection::find(&m, &bvh, n);
        let tag = |t: u32| s.face_tags.get(t as usize).copied().unwrap_or_default();
        let list = pairs.into_iter().map(|[a, b]| IntersectingPair { a, b, tag_a: tag(a), tag_b: tag(b) }).collect();
        (Some(count), list)
    } else {
        (None, Vec::new())
    };
    let walk = boundary::walk(&m.tris, &et);

    let mut shells_out = Vec::with_capacity(sh.shells.len());
    for (i, x) in sh.shells.iter().enumerate() {
        let euler = x.vertices as i64 - x.edges as i64 + x.triangles as i64;
        let closed = x.closed();
        let genus =
            (closed && x.vertex_manifold && x.orientable && (2 - euler) % 2 == 0 && euler <= 2).then_some((2 - euler) / 2);
        let oriented = x.misoriented == 0;
        let depth = nest.depth[i];
        let outward = match depth {
            Some(d) if closed && oriented => Some(if d % 2 == 0 { x.volume > 0.0 } else { x.volume < 0.0 }),
            _ => None,
        };
        shells_out.push(ShellReport {
            first_triangle: m.orig(x.first_triangle as usize),
            triangles: x.triangles,
            vertices: x.vertices,
            edges: x.edges,
            closed,
            edge_manifold: x.nonmanifold == 0,
            vertex_manifold: x.vertex_manifold,
            oriented,
            orientable: x.orientable,
            euler,
            genus,
            volume: x.volume,
            area: x.area,
            depth,
            parent: nest.parent[i],
            outward,
            tags: x.tags.clone(),
            bbox: x.bbox.to_array(),
        });
    }
    let open_edges = sh.shells.iter().map(|x| x.open).sum();
    let nonmanifold_edges = sh.shells.iter().map(|x| x.nonmanifold).sum();
    let misoriented_edges = sh.shells.iter().map(|x| x.misoriented).sum();
    let closed = open_edges == 0 && nonmanifold_edges == 0 && !m.tris.is_empty();
    let edge_manifold = nonmanifold_edges == 0;
    let vertex_manifold = sh.nonmanifold_vertices == 0;
    let manifold = edge_manifold && vertex_manifold;
    let oriented = misoriented_edges == 0;
    let genus = if closed && manifold && oriented && shells_out.iter().all(|x| x.genus.is_some()) {
        Some(shells_out.iter().filter_map(|x| x.genus).sum())
    } else {
        None
    };
    let outward = closed && shells_out.iter().all(|x| x.outward == Some(true));
    SurfaceReport {
        vertices: s.vertices.len(),
        used_vertices: sh.used_vertices,
        triangles: s.triangles.len(),
        invalid_triangles: m.invalid,
        degenerate_triangles,
        first_degenerate,
        edges: et.len(),
        components: shells_out.len(),
        closed,
        manifold,
        edge_manifold,
        vertex_manifold,
        oriented,
        outward,
        open_edges,
        nonmanifold_edges,
        nonmanifold_vertices: sh.nonmanifold_vertices,
        misoriented_edges,
        euler: sh.used_vertices as i64 - et.len() as i64 + m.tris.len() as i64,
        genus,
        volume: shells_out.iter().map(|x| x.volume).sum(),
        area: shells_out.iter().map(|x| x.area).sum(),
        boundary_loops: walk.loops.len(),
        boundary_loop_edges: walk.loops.iter().map(Vec::len).collect(),
        boundary_chains: walk.chains,
        self_intersections,
        first_intersections,
        bbox: s.bbox().to_array(),
        shells: shells_out,
    }
}
