//! Tessellation to a size field: edge points spaced by the field (the integral of `1 / h`
//! along the edge, as Gmsh spaces its 1D meshes), and faces refined until their triangles are
//! of the local size and well shaped. What a volume mesher wants as its boundary.

use super::uv_cdt::{V, constraint_parity};
use crate::cad::geom::Surface;
use crate::core::SizeField;
use glam::{DVec2, DVec3};
use spade::handles::FixedVertexHandle;
use crate::core::cdt;
use spade::{ConstrainedDelaunayTriangulation, Triangulation};

/// The most points one edge gets from the size.
pub const MAX_EDGE_POINTS: usize = 100_000;
/// Points the size refinement adds to one face at most.
const MAX_FACE_POINTS: usize = 500_000;
/// Rounds of size refinement at most (each inserts the centroid of every triangle too big).
const SIZE_ROUNDS: usize = 40;
/// The largest area of a triangle of size `h`: this times `h²`, in spade's first pass (at the
/// face's largest size) and in the graded rounds (at the size at the triangle's centroid).
/// Calibrated on planar and cylindrical faces so that the median edge of a face meshed to a
/// uniform size is that size (1.00 measured on the bracket at size 2.25).
const AREA_FACTOR: f64 = 0.8;
/// A triangle is split in the graded rounds only if its longest edge is also more than this
/// many times the local size.
const SPLIT_RATIO: f64 = 1.6;

/// The parameters of the points along a curve: `ts` (increasing or decreasing, the pieces the
/// chord and angle criteria cut) re-spaced so that each segment is about the local size, and
/// never longer than the piece of `ts` it lies in (the chord bound is kept).
pub(super) fn edge_params(point: &dyn Fn(f64) -> DVec3, ts: &[f64], size: &dyn SizeField) -> Vec<f64> {
    // sample each piece finely, integrating 1 / min(h, piece length)
    let mut t_s = vec![ts[0]];
    let mut s_s = vec![0.0];
    let mut s = 0.0;
    for w in ts.windows(2) {
        let (t0, t1) = (w[0], w[1]);
        let piece = point(t0).distance(point(t1));
        let h_ends = size.size_at(point(t0)).min(size.size_at(point(t1))).min(size.size_at(point(0.5 * (t0 + t1))));
        let m = ((4.0 * piece / h_ends).ceil() as usize).clamp(4, 4096);
        let mut prev = point(t0);
        for k in 1..=m {
            let t = t0 + (t1 - t0) * k as f64 / m as f64;
            let p = point(t);
            // the size on the curve, halfway along the step
            let h = size.size_at(point(t - 0.5 * (t1 - t0) / m as f64)).min(piece);
            if h > 0.0 && h.is_finite() {
                s += prev.distance(p) / h;
            }
            prev = p;
            t_s.push(t);
            s_s.push(s);
        }
    }
    let n = (s.round() as usize).clamp(1, MAX_EDGE_POINTS).max((ts.len() - 1).min(1));
    let mut out = Vec::with_capacity(n + 1);
    out.push(ts[0]);
    let mut j = 1;
    for k in 1..n {
        let target = s * k as f64 / n as f64;
        while j < s_s.len() - 1 && s_s[j] < target {
            j += 1;
        }
        let (s0, s1) = (s_s[j - 1], s_s[j]);
        let f = if s1 > s0 { ((target - s0) / (s1 - s0)).clamp(0.0, 1.0) } else { 0.0 };
        out.push(t_s[j - 1] + f * (t_s[j] - t_s[j - 1]));
    }
    out.push(*ts.last().unwrap_or(&ts[0]));
    out
}

/// Refines a face's domain triangulation (scaled parameters: `(u su, v sv)`) until every
/// inside triangle is about the size at its centroid and its angles are 25° or more away from
/// small input angles; the boundary segments are kept, as the faces around share their
/// points. New points get their `(u, v)` and 3D point.
pub(super) fn refine_face(cdt: &mut ConstrainedDelaunayTriangulation<V>, surf: &Surface, su: f64, sv: f64, size: &dyn SizeField) {
    let hmax = cdt.vertices().map(|v| size.size_at(v.data().p3)).filter(|h| h.is_finite()).fold(0.0, f64::max);
    if hmax.is_nan() || hmax <= 0.0 {
        return;
    }
    // the coarsest size of the face first: spade's area bound (lengths in the scaled
    // parameters are 3D lengths where the speeds are near their means)
    cdt.refine(cdt::quality_refinement((2.0 * AREA_FACTOR).sqrt() * hmax, MAX_FACE_POINTS));
    lift_new(cdt, surf, su, sv);
    // then the centroids of triangles bigger than the local size, round after round
    let mut added = 0;
    // the sizes at centroids already asked for: a triangle that a round leaves alone is asked
    // again in the next, and a feature-size query walks a tree of samples
    let mut sizes: rustc_hash::FxHashMap<[u64; 3], f64> = rustc_hash::FxHashMap::default();
    for _ in 0..SIZE_ROUNDS {
        let inside = constraint_parity(cdt);
        let mut new_points = Vec::new();
        for f in cdt.inner_faces() {
            if !inside[f.fix().index()] {
                continue;
            }
            let vs = f.vertices();
            let p3 = vs.map(|v| v.data().p3);
            let area = 0.5 * (p3[1] - p3[0]).cross(p3[2] - p3[0]).length();
            let longest = (0..3).map(|i| p3[i].distance(p3[(i + 1) % 3])).fold(0.0, f64::max);
            let centroid = (p3[0] + p3[1] + p3[2]) / 3.0;
            let h = *sizes.entry(centroid.to_array().map(f64::to_bits)).or_insert_with(|| size.size_at(centroid));
            // too big both by area (as the first pass) and by its longest edge: a thin
            // triangle at a small input angle has a small area and stays (splitting it would
            // only make thinner ones); a NaN splits nothing
            let big = area > AREA_FACTOR * h * h && longest > SPLIT_RATIO * h;
            if !big {
                continue;
            }
            let sp = vs.map(|v| v.data().p);
            let c = DVec2::new((sp[0].x + sp[1].x + sp[2].x) / 3.0, (sp[0].y + sp[1].y + sp[2].y) / 3.0);
            // a centroid inside the diametral circle of a boundary segment would crowd it
            let encroaches = f.adjacent_edges().iter().any(|e| {
                if !e.is_constraint_edge() {
                    return false;
                }
                let (a, b) = (e.from().data().p, e.to().data().p);
                let (a, b) = (DVec2::new(a.x, a.y), DVec2::new(b.x, b.y));
                (c - a).dot(c - b) < 0.0
            });
            if !encroaches {
                new_points.push(c);
            }
        }
        if new_points.is_empty() || added > MAX_FACE_POINTS {
            break;
        }
        added += new_points.len();
        for c in new_points {
            let uv = DVec2::new(c.x / su, c.y / sv);
            // a point spade cannot take (on top of another) is left out
            let _ = cdt::insert(cdt, c, |p| V { p, id: None, uv, p3: surf.point(uv.x, uv.y) });
        }
    }
    // and the shape again
    cdt.refine(cdt::quality_refinement(f64::INFINITY, MAX_FACE_POINTS));
    lift_new(cdt, surf, su, sv);
}

/// Gives the points spade's refinement inserted their `(u, v)` (the scaled position over the
/// speeds `su`, `sv`) and their 3D point on the surface.
pub(super) fn lift_new(cdt: &mut ConstrainedDelaunayTriangulation<V>, surf: &Surface, su: f64, sv: f64) {
    let new: Vec<FixedVertexHandle> = cdt.vertices().filter(|v| v.data().id.is_none() && v.data().uv.is_nan()).map(|v| v.fix()).collect();
    for h in new {
        let d = cdt.vertex_data_mut(h);
        let uv = DVec2::new(d.p.x / su, d.p.y / sv);
        d.uv = uv;
        d.p3 = surf.point(uv.x, uv.y);
    }
}
