//! Discretisation of B-rep edges: each edge once, shared by the faces that use it.

use crate::cad::brep::{Edge, Model};
use super::edge_strip::EdgeStrip;
use crate::core::SizeField;
use glam::DVec3;

/// The points of one edge, from its start vertex to its end vertex.
#[derive(Clone, Debug, Default)]
pub struct EdgePoints {
    /// Global vertex indices; the first and last are the edge's B-rep vertices (all equal for
    /// a degenerate edge).
    pub ids: Vec<u32>,
    /// Curve parameters of the points (the edge's range, in the direction start → end).
    pub params: Vec<f64>,
}

/// Points along `edge` with chord error at most `tol` and tangent turn at most `max_angle_deg`
/// per segment; new points are appended to `vertices`.
///
/// A straight edge is split into pieces no longer than `max_straight` (a straight edge on a
/// curved face, such as a cone's generator, would otherwise make long thin triangles there:
/// near an apex they fold over the small ones), and so is a curve that lies on
/// its chord (a line written as a B-spline).
///
/// With a size field, the points are then spaced by it (the integral of `1 / h` along the
/// edge; see [`super::tessellate_sized`]), never farther apart than the chord and angle
/// criteria allow. `strip` gives points near small corners of a face (see
/// [`super::corner_strips`]); the size spaces the rest.
#[allow(clippy::too_many_arguments)]
pub fn discretise(model: &Model, edge: &Edge, tol: f64, max_angle_deg: f64, max_straight: f64, size: Option<&dyn SizeField>, strip: Option<&EdgeStrip>, vertices: &mut Vec<DVec3>) -> EdgePoints {
    let (a, b) = (edge.range.min, edge.range.max);
    let Some(ci) = edge.curve.filter(|_| !edge.degenerate && a.is_finite() && b.is_finite()) else {
        // no curve or a point: the vertices only
        let params = vec![a, b];
        return EdgePoints { ids: vec![edge.start, edge.end], params };
    };
    let curve = model.curve(ci);
    let straight = matches!(curve, crate::cad::geom::Curve::Line(_));
    let mut ts = vec![a];
    if !straight {
        let cos_max = max_angle_deg.to_radians().cos();
        let n0 = if edge.closed { 8 } else { 4 };
        for k in 0..n0 {
            let (t0, t1) = (a + (b - a) * k as f64 / n0 as f64, a + (b - a) * (k + 1) as f64 / n0 as f64);
            refine(&|t| curve.point(t), &|t| curve.derivative(t), t0, t1, tol, cos_max, 0, &mut ts);
        }
        if size.is_some() && !edge.closed {
            // the first pieces are for the criteria's sake only: a short edge (a line written
            // as a B-spline, 0.2 mm long) must not keep four pieces of 0.05 beside a size of 2
            ts = coarsen(&|t| curve.point(t), &|t| curve.derivative(t), &ts, tol, cos_max);
        }
        let (p0, p1) = (curve.point(a), curve.point(b));
        let on_chord = |t: f64| (curve.point(t) - p0).reject_from(p1 - p0).length() <= tol;
        if max_straight > 0.0 && p0 != p1 && ts.iter().all(|&t| on_chord(t)) {
            // a curve that is a straight line (a B-spline written for one) gets the pieces
            // of a straight edge on a curved face
            ts = split_long(&|t| curve.point(t), &ts, max_straight);
        }
    } else {
        ts.push(b);
        if max_straight > 0.0 {
            ts = split_long(&|t| curve.point(t), &ts, max_straight);
        }
    }
    if let Some(size) = size {
        ts = match strip.filter(|s| !s.params.is_empty()) {
            Some(s) => {
                let cos_max = max_angle_deg.to_radians().cos();
                with_strips(&|t| curve.point(t), &|t| curve.derivative(t), &ts, s, size, tol, cos_max)
            }
            None => super::sizing::edge_params(&|t| curve.point(t), &ts, size),
        };
    }
    // in the direction start -> end
    if !edge.same_sense {
        ts.reverse();
    }
    let n = ts.len();
    let mut ids = Vec::with_capacity(n);
    for (k, &t) in ts.iter().enumerate() {
        if k == 0 {
            ids.push(edge.start);
        } else if k == n - 1 {
            ids.push(edge.end);
        } else {
            vertices.push(curve.point(t));
            ids.push(vertices.len() as u32 - 1);
        }
    }
    EdgePoints { ids, params: ts }
}

/// The parameters `ts` (increasing, the chord criteria's pieces) with the strips' points,
/// the chord's points in the strips' tips, and the size spacing the stretches the strips
/// do not cover; a chord point that falls a sliver away from a strip's point or end is left
/// out where the chord across it meets the criteria ([`drop_slivers`]).
fn with_strips(p: &dyn Fn(f64) -> DVec3, d: &dyn Fn(f64) -> DVec3, ts: &[f64], strip: &EdgeStrip, size: &dyn SizeField, tol: f64, cos_max: f64) -> Vec<f64> {
    let (lo, hi) = (ts[0], ts[ts.len() - 1]);
    let mut covered = strip.covered.clone();
    covered.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut out: Vec<f64> = vec![lo, hi];
    out.extend(strip.params.iter().copied().filter(|&t| t > lo && t < hi));
    // in a strip's tip, the chord's points only
    let in_tips: Vec<f64> = ts.iter().copied().filter(|&t| strip.tips.iter().any(|&(a, b)| t > a && t < b)).collect();
    out.extend(&in_tips);
    // the stretches no strip covers, spaced by the size
    let mut from = lo;
    for &(a, b) in covered.iter().chain([&(hi, hi)]) {
        if a > from {
            let mut piece = vec![from];
            piece.extend(ts.iter().copied().filter(|&t| t > from && t < a));
            piece.push(a);
            out.extend(super::sizing::edge_params(p, &piece, size));
        }
        from = from.max(b);
    }
    out.sort_by(f64::total_cmp);
    out.dedup();
    // the strips' points stay, and so do the chord's points in the tips
    let mut kept: Vec<f64> = strip.params.clone();
    kept.extend(in_tips);
    kept.sort_by(f64::total_cmp);
    drop_slivers(p, d, &mut out, &kept, tol, cos_max);
    out
}

/// A segment this many times shorter than the one beside it is a sliver.
const SLIVER_RATIO: f64 = 0.02;

/// Leaves out of `ts` (increasing) each inner point, but those in `kept` (sorted), whose
/// shorter segment is under [`SLIVER_RATIO`] of its longer one where the chord across it
/// meets the criteria of [`coarsen`]. The pieces that the strips and the size spacing make
/// meet: where a strip ends a hair before a chord point, the two made a segment a thousandth
/// of its neighbours' length, and triangles as thin on both faces of the edge.
fn drop_slivers(p: &dyn Fn(f64) -> DVec3, d: &dyn Fn(f64) -> DVec3, ts: &mut Vec<f64>, kept: &[f64], tol: f64, cos_max: f64) {
    let mut i = 1;
    while i + 1 < ts.len() {
        let (a, b) = (p(ts[i - 1]).distance(p(ts[i])), p(ts[i]).distance(p(ts[i + 1])));
        if a.min(b) < SLIVER_RATIO * a.max(b) && kept.binary_search_by(|x| x.total_cmp(&ts[i])).is_err() && chord_meets(p, d, &ts[i - 1..=i + 1], tol, cos_max) {
            ts.remove(i);
        } else {
            i += 1;
        }
    }
}

/// Splits the segments `ks` of an edge's points (segment `k` between points `k` and `k + 1`)
/// at their parameter midpoints, the new points appended to `vertices`. Both faces of the
/// edge take the new points, so the surface stays watertight. An edge without a curve (or a
/// degenerate one) is left as it is.
pub fn split_segments(model: &Model, edge: &Edge, ep: &mut EdgePoints, ks: &mut [usize], vertices: &mut Vec<DVec3>) {
    let Some(ci) = edge.curve.filter(|_| !edge.degenerate) else { return };
    let curve = model.curve(ci);
    ks.sort_unstable();
    let mut last = None;
    // from the end, so the indices before each split stay valid
    for &k in ks.iter().rev() {
        if last == Some(k) || k + 1 >= ep.ids.len() || ep.params.len() != ep.ids.len() {
            continue;
        }
        last = Some(k);
        let t = 0.5 * (ep.params[k] + ep.params[k + 1]);
        let p = curve.point(t);
        if !p.is_finite() {
            continue;
        }
        vertices.push(p);
        ep.ids.insert(k + 1, vertices.len() as u32 - 1);
        ep.params.insert(k + 1, t);
    }
}

/// Puts a point on each edge exactly where its curve passes, between its ends, through a pole
/// of a face it bounds: a sphere's pole, a cone's apex. A great circle through both poles of a
/// sphere (a hemisphere's rim on a flat face, the sphere's axis lying in that face) has no
/// B-rep vertex there; without a point at each pole the face's loop jumps half a turn in `u`
/// across it, and the face took the pole as a vertex of its own that its neighbour across the
/// edge does not have. The point is the pole itself where the curve passes within `1e-6` of
/// the model's size of it: a new point, or the edge's nearest point moved there when that one
/// lies within a tenth of its segment's length.
pub fn through_poles(model: &Model, edges: &mut [EdgePoints], vertices: &mut Vec<DVec3>) {
    let eps = 1e-6 * model.size();
    for face in &model.faces {
        let poles = surface_poles(model.surface(face.surface));
        if poles.is_empty() {
            continue;
        }
        for &l in &face.loops {
            for c in &model.loops[l as usize].coedges {
                let edge = &model.edges[c.edge as usize];
                for &pole in &poles {
                    add_pole(model, edge, &mut edges[c.edge as usize], pole, eps, vertices);
                }
            }
        }
    }
}

/// The points where a surface's parametrisation collapses: a sphere's two poles, a cone's apex.
fn surface_poles(surf: &crate::cad::geom::Surface) -> Vec<DVec3> {
    use crate::cad::geom::Surface;
    match surf {
        Surface::Sphere(s) => vec![s.point(0.0, -std::f64::consts::FRAC_PI_2), s.point(0.0, std::f64::consts::FRAC_PI_2)],
        Surface::Cone(c) => vec![c.point(0.0, c.apex_v())],
        _ => Vec::new(),
    }
}

fn add_pole(model: &Model, edge: &Edge, ep: &mut EdgePoints, pole: DVec3, eps: f64, vertices: &mut Vec<DVec3>) {
    let Some(ci) = edge.curve.filter(|_| !edge.degenerate) else { return };
    let n = ep.ids.len();
    if n < 2 || ep.params.len() != n || ep.ids.iter().any(|&id| vertices[id as usize].distance(pole) <= eps) {
        return;
    }
    let curve = model.curve(ci);
    let (lo, hi) = (ep.params[0].min(ep.params[n - 1]), ep.params[0].max(ep.params[n - 1]));
    let mut t = curve.project(pole);
    if let Some(per) = curve.domain().period {
        t = lo + (t - lo).rem_euclid(per);
    }
    if !(t > lo && t < hi) || curve.point(t).distance(pole) > eps {
        return;
    }
    let Some(k) = (0..n - 1).find(|&k| (ep.params[k] - t) * (ep.params[k + 1] - t) <= 0.0) else { return };
    let (a, b) = (vertices[ep.ids[k] as usize], vertices[ep.ids[k + 1] as usize]);
    let near = 0.1 * a.distance(b);
    if k > 0 && a.distance(pole) <= near {
        vertices[ep.ids[k] as usize] = pole;
        ep.params[k] = t;
    } else if k + 2 < n && b.distance(pole) <= near {
        vertices[ep.ids[k + 1] as usize] = pole;
        ep.params[k + 1] = t;
    } else {
        vertices.push(pole);
        ep.ids.insert(k + 1, vertices.len() as u32 - 1);
        ep.params.insert(k + 1, t);
    }
}

/// The parameters `ts` with each piece longer than `max_len` (its chord) cut into equal
/// parameter steps no longer than that, at most 64.
fn split_long(p: &dyn Fn(f64) -> DVec3, ts: &[f64], max_len: f64) -> Vec<f64> {
    let mut out = vec![ts[0]];
    for w in ts.windows(2) {
        let n = ((p(w[1]).distance(p(w[0])) / max_len).ceil() as usize).clamp(1, 64);
        out.extend((1..=n).map(|k| if k == n { w[1] } else { w[0] + (w[1] - w[0]) * k as f64 / n as f64 }));
    }
    out
}

/// The parameters `ts` of an open curve with a point left out wherever the chord across it
/// still meets the criteria of [`refine`]: the curve within `tol` of the chord at the points
/// left out and at the quarters of every piece between, and its tangent turning by at most
/// the angle of `cos_max` from end to end.
fn coarsen(p: &dyn Fn(f64) -> DVec3, d: &dyn Fn(f64) -> DVec3, ts: &[f64], tol: f64, cos_max: f64) -> Vec<f64> {
    let Some(&first) = ts.first() else { return Vec::new() };
    let mut out = vec![first];
    let mut i = 0;
    while i + 1 < ts.len() {
        let mut j = i + 1;
        while j + 1 < ts.len() && chord_meets(p, d, &ts[i..=j + 1], tol, cos_max) {
            j += 1;
        }
        out.push(ts[j]);
        i = j;
    }
    out
}

/// True if the chord from the first to the last of `ts` meets the criteria of [`coarsen`].
fn chord_meets(p: &dyn Fn(f64) -> DVec3, d: &dyn Fn(f64) -> DVec3, ts: &[f64], tol: f64, cos_max: f64) -> bool {
    let (Some(&t0), Some(&t1)) = (ts.first(), ts.last()) else { return false };
    let (p0, p1) = (p(t0), p(t1));
    let chord = p1 - p0;
    if !(chord.length_squared() > 0.0) {
        return false;
    }
    turn_ok(d, t0, t1, cos_max)
        && ts.windows(2).all(|w| {
            [0.0, 0.25, 0.5, 0.75].iter().all(|&f| (p(w[0] + (w[1] - w[0]) * f) - p0).reject_from(chord).length() <= tol)
        })
}

/// True if the curve's tangent turns by at most the angle of `cos_max` from `t0` to `t1` (or
/// has no direction at either end).
fn turn_ok(d: &dyn Fn(f64) -> DVec3, t0: f64, t1: f64, cos_max: f64) -> bool {
    match (d(t0).try_normalize(), d(t1).try_normalize()) {
        (Some(u), Some(v)) => u.dot(v) >= cos_max,
        _ => true,
    }
}

/// Appends the parameters after `t0` up to and including `t1`, splitting where the midpoint
/// is farther than `tol` from the chord or the tangent turns too much.
#[allow(clippy::too_many_arguments)]
fn refine(p: &dyn Fn(f64) -> DVec3, d: &dyn Fn(f64) -> DVec3, t0: f64, t1: f64, tol: f64, cos_max: f64, depth: u32, out: &mut Vec<f64>) {
    let tm = 0.5 * (t0 + t1);
    let (p0, p1, pm) = (p(t0), p(t1), p(tm));
    let chord = p1 - p0;
    let dev = if chord.length_squared() > 0.0 { (pm - p0).reject_from(chord).length() } else { (pm - p0).length() };
    if depth < 16 && (dev > tol || !turn_ok(d, t0, t1, cos_max)) {
        refine(p, d, t0, tm, tol, cos_max, depth + 1, out);
        refine(p, d, tm, t1, tol, cos_max, depth + 1, out);
    } else {
        out.push(t1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_strip_that_ends_a_hair_before_a_chord_point_leaves_no_sliver_segment() {
        // a quarter circle of radius 10, its chord points by the criteria; a strip graded from
        // the corner at t = 0 whose last point falls a thousandth of a segment before one of
        // them (the AutoMobRos_verschluss case: 0.0008 mm beside 0.47 and 0.68)
        let p = |t: f64| DVec3::new(10.0 * t.cos(), 10.0 * t.sin(), 0.0);
        let d = |t: f64| DVec3::new(-10.0 * t.sin(), 10.0 * t.cos(), 0.0);
        let (tol, cos_max) = (2e-3, 20f64.to_radians().cos());
        let mut ts = vec![0.0];
        for k in 0..4 {
            let (t0, t1) = (std::f64::consts::FRAC_PI_2 * k as f64 / 4.0, std::f64::consts::FRAC_PI_2 * (k + 1) as f64 / 4.0);
            refine(&p, &d, t0, t1, tol, cos_max, 0, &mut ts);
        }
        let end = ts[3] - 1e-4 * (ts[3] - ts[2]);
        let params: Vec<f64> = (1..=6).map(|k| end * 1.5f64.powi(k - 6)).collect();
        let strip = EdgeStrip { params: params.clone(), covered: vec![(0.0, end)], tips: vec![(0.0, params[0])] };
        let size = crate::core::size_field::UniformSize(0.5);
        let out = with_strips(&p, &d, &ts, &strip, &size, tol, cos_max);
        for t in &params {
            assert!(out.contains(t), "strip point {t} lost");
        }
        assert!(!out.contains(&ts[3]), "the chord point a hair past the strip's end is left out");
        for w in out.windows(3) {
            let (a, b) = (p(w[0]).distance(p(w[1])), p(w[1]).distance(p(w[2])));
            assert!(a.min(b) >= SLIVER_RATIO * a.max(b) || params.contains(&w[1]), "{w:?}: {a} beside {b}");
        }
        for w in out.windows(2) {
            assert!(chord_meets(&p, &d, w, tol, cos_max), "{w:?}");
        }
        // without the strip's grading the same chord point stays where the chord needs it
        let mut tight = vec![0.0, 0.5, 0.5001, 1.5];
        drop_slivers(&p, &d, &mut tight, &[], 1e-9, cos_max);
        assert_eq!(tight.len(), 4, "{tight:?}");
    }

    #[test]
    fn a_straight_curve_cut_for_the_criteria_is_one_piece_again() {
        // a 0.2 mm line written as a curve: refinement starts from four pieces
        let p = |t: f64| DVec3::new(t, 0.0, 0.0);
        let d = |_: f64| DVec3::X;
        let ts = [0.0, 0.05, 0.1, 0.15, 0.2];
        assert_eq!(coarsen(&p, &d, &ts, 1e-6, 0.9), vec![0.0, 0.2]);
    }

    #[test]
    fn a_curved_edge_keeps_the_points_its_chord_needs() {
        // a quarter circle of radius 1: every piece kept stays within the chord and the turn
        let p = |t: f64| DVec3::new(t.cos(), t.sin(), 0.0);
        let d = |t: f64| DVec3::new(-t.sin(), t.cos(), 0.0);
        let (tol, cos_max) = (1e-3, 10f64.to_radians().cos());
        let mut ts = vec![0.0];
        for k in 0..4 {
            let (t0, t1) = (std::f64::consts::FRAC_PI_2 * k as f64 / 4.0, std::f64::consts::FRAC_PI_2 * (k + 1) as f64 / 4.0);
            refine(&p, &d, t0, t1, tol, cos_max, 0, &mut ts);
        }
        let fewer = coarsen(&p, &d, &ts, tol, cos_max);
        assert!(fewer.len() <= ts.len() && fewer.len() > 2, "{} of {}", fewer.len(), ts.len());
        assert_eq!((fewer[0], fewer[fewer.len() - 1]), (ts[0], ts[ts.len() - 1]));
        for w in fewer.windows(2) {
            assert!(chord_meets(&p, &d, &[w[0], w[1]], tol, cos_max), "{w:?}");
            let mid = p(0.5 * (w[0] + w[1]));
            assert!((mid - p(w[0])).reject_from(p(w[1]) - p(w[0])).length() <= tol);
        }
    }
}
