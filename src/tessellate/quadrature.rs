//! The B-rep's own area and enclosed volume, by quadrature over each face's parameter domain.
//!
//! Input: a face's parameter-domain triangulation ([`FaceDomain`], made by the tessellator)
//! and the points of the B-rep edges. Output: the face's area `∫∫ |S_u × S_v| du dv` and its
//! volume term `(1/3) ∫∫ (S − c)·(S_u × S_v) du dv` (negated when the face is reversed), so
//! that the volume terms of a closed shell add up to its enclosed volume (divergence theorem;
//! `c` is any fixed point, the model's centre keeps the terms small).
//!
//! Each `(u, v)` triangle is integrated with the 7-point degree-5 rule of Dunavant (1985):
//! the integrands are smooth, so the error falls like `h^6` in the triangle size, far below
//! the flat triangles' `O(δ)`. The triangulation's boundary is a polygon in `(u, v)` through
//! points of the edges; between two of them the true trimming curve bulges off the chord.
//! That sliver is added (or removed: signed areas) as a fan through [`SLIVER_POINTS`] points of
//! the edge curve projected onto the surface, so the domain follows the true boundary up to
//! a deviation about `(1 + SLIVER_POINTS)²` times smaller than the chord tolerance. Segments
//! that are not pieces of an edge (cuts between seam sides, pole lines) are straight in
//! `(u, v)` and need no correction.

use super::FaceDomain;
use super::edge_points::EdgePoints;
use crate::cad::brep::Model;
use crate::cad::geom::Surface;
use crate::core::FaceId;
use glam::{DVec2, DVec3};
use rustc_hash::FxHashMap;

/// Points of the edge curve sampled inside each boundary segment for the sliver correction.
pub const SLIVER_POINTS: usize = 4;

/// Dunavant's 7-point rule: barycentric coordinates and weights (summing to 1).
const RULE: [([f64; 3], f64); 7] = {
    const A1: f64 = 0.059_715_871_789_770;
    const B1: f64 = 0.470_142_064_105_115;
    const W1: f64 = 0.132_394_152_788_506;
    const A2: f64 = 0.797_426_985_353_087;
    const B2: f64 = 0.101_286_507_323_456;
    const W2: f64 = 0.125_939_180_544_827;
    const T: f64 = 1.0 / 3.0;
    [
        ([T, T, T], 0.225),
        ([A1, B1, B1], W1),
        ([B1, A1, B1], W1),
        ([B1, B1, A1], W1),
        ([A2, B2, B2], W2),
        ([B2, A2, B2], W2),
        ([B2, B2, A2], W2),
    ]
};

/// Area and volume term of a face (see the module docs).
#[derive(Copy, Clone, Debug, Default, PartialEq)]
pub struct FaceIntegrals {
    /// `∫ dA`, mm².
    pub area: f64,
    /// `(1/3) ∫ (S − c)·n dA` with the face's outward normal, mm³.
    pub volume: f64,
}

/// Where each edge segment is: `(lo, hi)` vertex ids → `(edge, k)` with the segment between
/// points `k` and `k + 1` of the edge.
pub struct SegmentIndex(FxHashMap<(u32, u32), (u32, u32)>);

impl SegmentIndex {
    /// Indexes the segments of all edges.
    pub fn new(edges: &[EdgePoints]) -> SegmentIndex {
        let mut map = FxHashMap::default();
        for (e, ep) in edges.iter().enumerate() {
            for k in 0..ep.ids.len().saturating_sub(1) {
                let (a, b) = (ep.ids[k], ep.ids[k + 1]);
                if a != b {
                    map.insert((a.min(b), a.max(b)), (e as u32, k as u32));
                }
            }
        }
        SegmentIndex(map)
    }

    /// The edge and the index of its segment between the points `a` and `b`, if any.
    pub fn segment(&self, a: u32, b: u32) -> Option<(u32, u32)> {
        self.0.get(&(a.min(b), a.max(b))).copied()
    }
}

/// Adds the integrals over the `(u, v)` triangle `t`, signed by its orientation (the domain's
/// triangles are counter-clockwise, so positive).
fn triangle(surf: &Surface, t: [DVec2; 3], c: DVec3, acc: &mut FaceIntegrals) {
    let det = (t[1] - t[0]).perp_dot(t[2] - t[0]) / 2.0;
    if det == 0.0 {
        return;
    }
    let (mut a, mut v) = (0.0, 0.0);
    for (b, w) in RULE {
        let q = t[0] * b[0] + t[1] * b[1] + t[2] * b[2];
        let (p, su, sv) = surf.point_and_tangents(q.x, q.y);
        let n = su.cross(sv);
        a += w * n.length();
        v += w * (p - c).dot(n);
    }
    acc.area += det * a;
    acc.volume += det * v / 3.0;
}

/// The area and volume term of face `fid` over its domain triangulation, the volume term
/// relative to the point `c`.
pub fn face_integrals(model: &Model, fid: FaceId, domain: &FaceDomain, edges: &[EdgePoints], index: &SegmentIndex, c: DVec3) -> FaceIntegrals {
    oriented(model, fid, surface_integrals(model, fid, domain, edges, index, c))
}

/// Integrals of [`surface_integrals`] with the face's sense: the volume term negated where
/// the face is reversed on its surface.
pub fn oriented(model: &Model, fid: FaceId, q: FaceIntegrals) -> FaceIntegrals {
    let sign = if model.face(fid).same_sense { 1.0 } else { -1.0 };
    FaceIntegrals { area: q.area, volume: sign * q.volume }
}

/// [`face_integrals`] with the surface's normal, whatever the face's sense (what the
/// tessellator keeps: turning a shell inside out changes the sense, not these).
pub fn surface_integrals(model: &Model, fid: FaceId, domain: &FaceDomain, edges: &[EdgePoints], index: &SegmentIndex, c: DVec3) -> FaceIntegrals {
    let face = model.face(fid);
    let surf = model.surface(face.surface);
    let mut acc = FaceIntegrals::default();
    for t in &domain.uv {
        triangle(surf, *t, c, &mut acc);
    }
    // slivers between the boundary chords and the true trimming curves: a fan from the
    // segment's start through points of the edge curve; bulging out of the face (to the right
    // of a segment that has the face on its left) it is counter-clockwise and adds
    for &([a, b], [ua, ub]) in &domain.boundary {
        let Some(&(e, k)) = index.0.get(&(a.min(b), a.max(b))) else { continue };
        let Some(ci) = model.edges[e as usize].curve else { continue };
        let curve = model.curve(ci);
        let ep = &edges[e as usize];
        let (k, k1) = (k as usize, k as usize + 1);
        let (ta, tb) = if ep.ids[k] == a { (ep.params[k], ep.params[k1]) } else { (ep.params[k1], ep.params[k]) };
        let n = SLIVER_POINTS + 1;
        let mut prev = ua;
        for j in 1..=n {
            let s = j as f64 / n as f64;
            let (pt, near) = (curve.point(ta + (tb - ta) * s), ua + (ub - ua) * s);
            // a B-spline's Newton from the chord's (u, v) alone: an edge point just off the
            // surface sent project_near to its global search (four starts) nearly every time
            let q = if j == n {
                ub
            } else if matches!(surf, Surface::BSpline(_)) {
                surf.refine(pt, near)
            } else {
                surf.project_near(pt, near)
            };
            if !q.is_finite() {
                break;
            }
            triangle(surf, [ua, prev, q], c, &mut acc);
            prev = q;
        }
    }
    acc
}
