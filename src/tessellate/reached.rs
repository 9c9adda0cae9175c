//! The deviation a tessellation reached on each face, measured: what the certificate's
//! volume and area tolerances are made of (not the chord that was asked for).
//!
//! A face's deviation is the largest distance, over its triangles, between the surface and
//! the triangle's plane at seven points of the triangle's `(u, v)` image (its centroid, its
//! edge midpoints and the points `(2/3, 1/6, 1/6)`: where the gap of a triangle inscribed in
//! a smooth surface, a quadratic vanishing at the corners, peaks), and over its boundary
//! segments, between the edge curve and the segment's chord at its ends, a quarter, half and
//! three quarters of the segment's parameters (the slivers between the trimming curves and
//! the chords; at an edge's ends the chord runs to the B-rep vertex, which a file may place
//! off the curve within its tolerance), and between the surface's image of the segment's
//! `(u, v)` (the quadrature's boundary) and the chord at a quarter, half and three quarters.

use super::FaceDomain;
use super::edge_points::EdgePoints;
use super::quadrature::SegmentIndex;
use crate::cad::brep::Model;
use crate::cad::geom::Surface;
use crate::core::FaceId;
use glam::{DVec2, DVec3};

/// Barycentric sample points of a triangle (module docs).
const SAMPLES: [[f64; 3]; 7] = {
    const T: f64 = 1.0 / 3.0;
    const A: f64 = 2.0 / 3.0;
    const B: f64 = 1.0 / 6.0;
    [[T, T, T], [0.5, 0.5, 0.0], [0.0, 0.5, 0.5], [0.5, 0.0, 0.5], [A, B, B], [B, A, B], [B, B, A]]
};

/// The largest gap between the surface and the triangle `p` (its corners in 3D) whose
/// `(u, v)` image is `uv`: distances from its plane, or from its points where it has no
/// plane (collapsed).
fn triangle_gap(surf: &Surface, p: [DVec3; 3], uv: [DVec2; 3]) -> f64 {
    let n = (p[1] - p[0]).cross(p[2] - p[0]).try_normalize();
    let mut d: f64 = 0.0;
    for b in SAMPLES {
        let q = uv[0] * b[0] + uv[1] * b[1] + uv[2] * b[2];
        let s = surf.point(q.x, q.y);
        let gap = match n {
            Some(n) => (s - p[0]).dot(n).abs(),
            None => (s - (p[0] * b[0] + p[1] * b[1] + p[2] * b[2])).length(),
        };
        // NaN (a point off the surface's domain) counts as infinitely far
        d = if gap.is_nan() { f64::INFINITY } else { d.max(gap) };
    }
    d
}

/// The deviation reached on face `fid` (module docs), mm, from its triangles `tris` (corners
/// in 3D, in the order of `domain.uv`) and its boundary segments (their ends in `vertices`).
pub fn face_deviation(model: &Model, fid: FaceId, domain: &FaceDomain, tris: &[[DVec3; 3]], vertices: &[DVec3], edges: &[EdgePoints], index: &SegmentIndex) -> f64 {
    let surf = model.surface(model.face(fid).surface);
    let mut d: f64 = 0.0;
    for (p, uv) in tris.iter().zip(&domain.uv) {
        d = d.max(triangle_gap(surf, *p, *uv));
    }
    for &([a, b], [ua, ub]) in &domain.boundary {
        // the segment's image by the surface, the quadrature's boundary, against its chord:
        // straight in (u, v) is curved on a surface whose map is not affine (a planar
        // bilinear patch bulges in its plane, which no distance from a plane sees)
        if let (Some(&pa), Some(&pb)) = (vertices.get(a as usize), vertices.get(b as usize)) {
            for s in [0.25, 0.5, 0.75] {
                let q = surf.point(ua.x + (ub.x - ua.x) * s, ua.y + (ub.y - ua.y) * s);
                let gap = crate::core::closest::closest_point_on_segment(q, pa, pb).distance(q);
                d = if gap.is_nan() { f64::INFINITY } else { d.max(gap) };
            }
        }
        let Some((e, k)) = index.segment(a, b) else { continue };
        let Some(ci) = model.edges.get(e as usize).and_then(|e| e.curve) else { continue };
        let Some(ep) = edges.get(e as usize) else { continue };
        let (Some(&ta), Some(&tb)) = (ep.params.get(k as usize), ep.params.get(k as usize + 1)) else { continue };
        let curve = model.curve(ci);
        // the segment as the mesh has it: at an edge's end the B-rep vertex, which a file may
        // place off its curve within its tolerance (the sliver between them counts too)
        // (the samples are symmetric, so which end is a does not matter)
        let (Some(&pa), Some(&pb)) = (vertices.get(a as usize), vertices.get(b as usize)) else { continue };
        for s in [0.0, 0.25, 0.5, 0.75, 1.0] {
            let q = curve.point(ta + (tb - ta) * s);
            let gap = crate::core::closest::closest_point_on_segment(q, pa, pb).distance(q);
            d = if gap.is_nan() { f64::INFINITY } else { d.max(gap) };
        }
    }
    d
}
