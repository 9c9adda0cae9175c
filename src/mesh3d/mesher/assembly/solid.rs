//! One solid of an assembly on its own: its closed surface cut out of the part's surface
//! (vertices renumbered, tags and names kept), and the queries the overlap check asks of it:
//! is a point within a distance of the surface, how far is it, is it strictly inside.
//!
//! Distances are floating point (closest point on a triangle, Ericson's regions); "inside" is
//! decided exactly, by the parity of proper crossings of a segment from the point to beyond
//! the solid's box ([`segment_crosses_triangle`]), another direction of a fixed sequence
//! being tried whenever a segment meets an edge, a vertex or a triangle's plane. A point on
//! the surface is not strictly inside.

use crate::core::bvh::Bvh;
use crate::core::ids::NONE;
use crate::core::closest::point_triangle_distance;
use crate::core::intersection::{SegmentCrossing, point_on_triangle, segment_crosses_triangle};
use crate::core::{Aabb, FaceId};
use crate::mesh::TriSurface;
use glam::DVec3;

/// Directions tried by [`SolidSurface::inside`] before it gives up (and answers "not inside").
const MAX_DIRECTIONS: usize = 32;

/// A solid's closed surface with a BVH over its triangles.
pub(crate) struct SolidSurface {
    /// The surface, with its own vertex numbering.
    pub surface: TriSurface,
    /// The part surface's index of each triangle.
    pub triangle_of: Vec<u32>,
    /// The part surface's index of each vertex.
    pub vertex_of: Vec<u32>,
    /// Corners of each triangle.
    pub corners: Vec<[DVec3; 3]>,
    /// Outward unit normal of each triangle.
    pub normals: Vec<DVec3>,
    /// Box of the surface.
    pub bbox: Aabb,
    bvh: Bvh,
}

/// Cuts `surface` into one surface per solid: triangle `t` goes to solid `of_triangle[t]`
/// (`< count`); a vertex used by several solids is copied into each.
pub(crate) fn split(surface: &TriSurface, of_triangle: &[u32], count: usize) -> Vec<SolidSurface> {
    let mut out: Vec<SolidSurface> = (0..count)
        .map(|_| SolidSurface {
            surface: TriSurface { face_names: surface.face_names.clone(), ..TriSurface::default() },
            triangle_of: Vec::new(),
            vertex_of: Vec::new(),
            corners: Vec::new(),
            normals: Vec::new(),
            bbox: Aabb::EMPTY,
            bvh: Bvh::default(),
        })
        .collect();
    let mut by_solid: Vec<Vec<u32>> = vec![Vec::new(); count];
    for (t, &s) in of_triangle.iter().enumerate() {
        by_solid[s as usize].push(t as u32);
    }
    // local index of each part vertex in the solid being cut, valid where stamp == solid
    let mut local = vec![0u32; surface.vertices.len()];
    let mut stamp = vec![NONE; surface.vertices.len()];
    for (s, (part, tris)) in out.iter_mut().zip(&by_solid).enumerate() {
        for &t in tris {
            let mapped = surface.triangles[t as usize].map(|v| {
                let vi = v as usize;
                if stamp[vi] != s as u32 {
                    stamp[vi] = s as u32;
                    local[vi] = part.surface.vertices.len() as u32;
                    part.surface.vertices.push(surface.vertices[vi]);
                    part.vertex_of.push(v);
                }
                local[vi]
            });
            part.surface.triangles.push(mapped);
            part.surface.face_tags.push(surface.face_tags[t as usize]);
            part.triangle_of.push(t);
        }
    }
    out
}

impl SolidSurface {
    /// Computes corners, normals, box and BVH (the surface must be free of zero-area
    /// triangles).
    pub(crate) fn prepare(&mut self) {
        let s = &self.surface;
        self.corners = s.triangles.iter().map(|t| t.map(|v| s.vertices[v as usize])).collect();
        self.normals = self.corners.iter().map(|[a, b, c]| (*b - *a).cross(*c - *a).normalize_or_zero()).collect();
        self.bbox = Aabb::from_points(&s.vertices);
        self.bvh = Bvh::build(self.corners.iter().enumerate().map(|(i, c)| (i as u32, Aabb::from_points(c))));
    }

    /// The face tag of triangle `t`.
    pub(crate) fn tag(&self, t: u32) -> FaceId {
        self.surface.face_tags[t as usize]
    }

    /// True if some triangle is within `r` of `p`.
    pub(crate) fn within(&self, p: DVec3, r: f64) -> bool {
        let q = Aabb { min: p - DVec3::splat(r), max: p + DVec3::splat(r) };
        let mut found = false;
        self.bvh.for_each_overlapping(&q, |t| {
            if !found && point_triangle_distance(p, self.corners[t as usize]) <= r {
                found = true;
            }
        });
        found
    }

    /// The distance from `p` to the surface and the nearest triangle.
    pub(crate) fn nearest(&self, p: DVec3) -> (f64, u32) {
        let mut r = (self.bbox.diagonal() * 1e-3).max(f64::MIN_POSITIVE);
        loop {
            let q = Aabb { min: p - DVec3::splat(r), max: p + DVec3::splat(r) };
            let mut best = (f64::INFINITY, 0u32);
            self.bvh.for_each_overlapping(&q, |t| {
                let d = point_triangle_distance(p, self.corners[t as usize]);
                if d < best.0 {
                    best = (d, t);
                }
            });
            // every triangle within r of p has its box in the query box
            if best.0 <= r || !r.is_finite() || self.corners.is_empty() {
                return best;
            }
            r *= 4.0;
        }
    }

    /// True if `p` is strictly inside the solid (on the surface is not inside). Undecided
    /// after [`MAX_DIRECTIONS`] segments that all graze an edge or a plane: not inside.
    pub(crate) fn inside(&self, p: DVec3) -> bool {
        if !self.bbox.overlaps(&Aabb { min: p, max: p }) {
            return false;
        }
        let mut on = false;
        self.bvh.for_each_overlapping(&Aabb { min: p, max: p }, |t| {
            on = on || point_on_triangle(p, self.corners[t as usize]);
        });
        if on {
            return false;
        }
        let reach = 2.0 * (self.bbox.diagonal() + (p - self.bbox.center()).length()) + 1.0;
        'directions: for k in 0..MAX_DIRECTIONS {
            let q = p + direction(k) * reach;
            let mut odd = false;
            let mut clean = true;
            self.bvh.for_each_on_segment(p, q, |t| {
                if clean {
                    match segment_crosses_triangle(p, q, self.corners[t as usize]) {
                        SegmentCrossing::Miss => {}
                        SegmentCrossing::Proper => odd = !odd,
                        SegmentCrossing::Degenerate => clean = false,
                    }
                }
            });
            if !clean {
                continue 'directions;
            }
            return odd;
        }
        false
    }

    /// For each vertex, its neighbours along triangle edges (sorted, once each).
    pub(crate) fn neighbours(&self) -> Vec<Vec<u32>> {
        let mut n: Vec<Vec<u32>> = vec![Vec::new(); self.surface.vertices.len()];
        for t in &self.surface.triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                n[a as usize].push(b);
                n[b as usize].push(a);
            }
        }
        for l in &mut n {
            l.sort_unstable();
            l.dedup();
        }
        n
    }
}

/// The `k`-th direction of a fixed, well spread sequence of unit vectors (a spherical
/// Fibonacci spiral with irrational offsets, so that none is axis-aligned).
fn direction(k: usize) -> DVec3 {
    let n = (MAX_DIRECTIONS + 1) as f64;
    let z = 1.0 - 2.0 * ((k as f64 + 0.5 + 0.318_309_886) / n).fract();
    let phi = 2.399_963_229_728_653 * k as f64 + 0.693_147_18;
    let r = (1.0 - z * z).max(0.0).sqrt();
    DVec3::new(r * phi.cos(), r * phi.sin(), z)
}
