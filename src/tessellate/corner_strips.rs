//! Strips at small corners of a face: where two edges of one face leave a vertex at a small
//! angle (a fillet's arc running out tangent to a straight side, a wedge), both edges get
//! their points at the same distances from the vertex, each step about the strip's width
//! there, so that the triangles across the strip are well shaped.
//!
//! Without it, the first points on the two edges sit a chord apart along the strip but only
//! the strip's width across it: the triangles after the corner are needles (angles of 5° on
//! the horn of this module's tests), and the tets on them slivers that touch no small input
//! angle. `feature_size` leaves edges that share a vertex out of its widths (their distance
//! goes to zero there); this measures them, from the corner outward.
//!
//! The width at distance `d` from the corner is the distance between the two sides' points
//! at `d`; the steps are 1.5 times it. A straight wedge of angle `θ` gets steps growing by
//! `1.5 θ` of the distance; a tangent corner, whose strip widens as `d² / 2R` (`R` the
//! fillet's radius), a handful of points. A side follows its edges across vertices where it
//! runs on smoothly (an arc running on into a line). The strip ends where its steps are as
//! long as the size asks for or as the chords: the size and the chords space the rest. A
//! strip that never widens that much within its reach is made only if it opens there, its
//! steps growing at least fourfold (a wedge of a few degrees whose sides are short beside the
//! size): then it ends at its reach and the size spaces the rest. One that does not open (a
//! sliver face of the CAD model, its sides nearly parallel) is not made: its points would only
//! crowd it. The sizes of the points join the size field, so the faces beside grade down to
//! them.
//!
//! Where the faces across the sides are walls (they do not run on tangent from the strip's
//! face), the strip is a wedge of the solid too. `proximity` grades the walls of a wedge only
//! where it is wider than two chords, so the strip starts there as well; the tip before it
//! keeps its chord points and is left to the tets on the wedge's edge (measured on real
//! parts: points in the tip made more slivers there, not fewer).

use super::edge_points::EdgePoints;
use super::edge_strip::EdgeStrip;
use crate::cad::brep::{Coedge, Model};
use crate::core::SizeField;
use glam::DVec3;

/// Corners of a face under this angle (degrees, between the first chords of the two edges,
/// measured inside the face) get strips. Beside a wider corner the triangle after it has
/// about the corner's angle anyway.
const CORNER_DEG: f64 = 15.0;

/// A face across a strip's side runs on from the strip's face (it is not a wall) where
/// their normals at the corner are less than this apart (degrees).
const TANGENT_DEG: f64 = 30.0;

/// A strip follows its side across a vertex where the side turns by less than this
/// (degrees): a fillet's arc running on into a line, the strip still narrowing.
const SMOOTH_DEG: f64 = 20.0;

/// Edges one side of a strip follows at most.
const MAX_EDGES: usize = 8;

/// A step is this many times the strip's width (triangles across it of angles 34° and more).
const WIDTH_FACTOR: f64 = 1.5;

/// A step is never under this share of the size asked for (as `feature_size`'s floor).
const FLOOR: f64 = 1.0 / 256.0;

/// A strip ends where its step is this share of the size asked for: the size's spacing
/// beyond makes triangles across it of angles about 25° and more.
const ENOUGH: f64 = 0.75;

/// Points one strip puts on each of its sides at most.
const MAX_POINTS: usize = 2000;

/// A strip runs at most this share of its sides' length from its corner (the other end may
/// have one too).
const REACH: f64 = 0.45;

/// A strip that reaches [`REACH`] before its steps are long enough is made when its last step
/// is at least this many times its first: a wedge that opens, not a sliver face. Measured on
/// real parts: a Pawl's four 3.7° wedge corners (size 2.9, sides about 7 long) left a 9.6° tet
/// beside them without strips and none under 10° that the corners do not explain with them;
/// 2, 3, 4 and 8 gave the same meshes of the Pawl, t20_data and wing_fuselage, 16 left the
/// Pawl's corners out.
const OPENS: f64 = 4.0;

/// The strips of a model: per edge, what they ask of it, and the sizes at their points for
/// the size field.
#[derive(Default)]
pub(super) struct CornerStrips {
    /// Per edge (empty where no strip).
    pub edges: Vec<EdgeStrip>,
    /// `(point, step)` at every strip point.
    pub samples: Vec<(DVec3, f64)>,
}

/// One stretch of a strip's side: an edge's chord points in the direction the side runs.
struct Stretch {
    edge: usize,
    pts: Vec<DVec3>,
    params: Vec<f64>,
}

/// One side of a strip: the edges from the corner on, while the side runs smoothly.
struct Arm<'a> {
    stretches: Vec<Stretch>,
    /// Every chord point from the corner on, with its stretch and index in it.
    pts: Vec<(DVec3, usize, usize)>,
    model: &'a Model,
    /// How far from the corner the distance keeps growing along the side, and at most
    /// [`REACH`] of its length.
    reach: f64,
}

/// The chord points of `edges[c.edge]` in the direction coedge `c` runs, or reversed.
fn stretch(model: &Model, edges: &[EdgePoints], vertices: &[DVec3], c: &Coedge, reversed: bool) -> Option<Stretch> {
    let e = &model.edges[c.edge as usize];
    let ep = &edges[c.edge as usize];
    if e.curve.is_none() || e.degenerate || e.closed || e.start == e.end || ep.ids.len() < 2 || ep.params.len() != ep.ids.len() {
        return None;
    }
    let mut pts: Vec<DVec3> = ep.ids.iter().map(|&i| vertices[i as usize]).collect();
    let mut params = ep.params.clone();
    if c.forward == reversed {
        pts.reverse();
        params.reverse();
    }
    Some(Stretch { edge: c.edge as usize, pts, params })
}

impl<'a> Arm<'a> {
    /// The side that leaves the corner along `first` (the stretch of `coedges[0]`; reversed:
    /// against the loop's direction), following `coedges[1..]` across smooth vertices.
    fn new(model: &'a Model, edges: &[EdgePoints], vertices: &[DVec3], first: Stretch, coedges: &[&Coedge], reversed: bool) -> Option<Arm<'a>> {
        let mut stretches: Vec<Stretch> = vec![first];
        for c in &coedges[1..] {
            let Some(next) = stretch(model, edges, vertices, c, reversed) else { break };
            let last = stretches.last()?;
            let n = last.pts.len();
            let (u, w) = (last.pts[n - 1] - last.pts[n - 2], next.pts[1] - next.pts[0]);
            if last.pts[n - 1] != next.pts[0] || stretches.iter().any(|s| s.edge == next.edge) || !(u.angle_between(w).to_degrees() < SMOOTH_DEG) {
                break;
            }
            stretches.push(next);
        }
        let mut pts = Vec::new();
        for (s, st) in stretches.iter().enumerate() {
            for (k, &p) in st.pts.iter().enumerate() {
                if k > 0 || s == 0 {
                    pts.push((p, s, k));
                }
            }
        }
        let o = pts[0].0;
        let len: f64 = pts.windows(2).map(|w| w[0].0.distance(w[1].0)).sum();
        let mut reach = 0.0;
        for &(p, _, _) in &pts[1..] {
            let d = p.distance(o);
            if d <= reach {
                break;
            }
            reach = d;
        }
        let reach = reach.min(REACH * len);
        (reach > 0.0 && reach.is_finite()).then_some(Arm { stretches, pts, model, reach })
    }

    fn corner(&self) -> DVec3 {
        self.pts[0].0
    }

    /// The chord piece `[k, k + 1]` (of `pts`) that distance `d` from the corner falls in.
    fn piece(&self, d: f64) -> usize {
        let o = self.corner();
        (0..self.pts.len() - 1).find(|&k| self.pts[k + 1].0.distance(o) >= d).unwrap_or(self.pts.len() - 2)
    }

    /// The point of the side at distance `d` from the corner: its stretch, curve parameter
    /// and position (by bisection on the curve in the chord piece that holds it).
    fn at(&self, d: f64) -> (usize, f64, DVec3) {
        let o = self.corner();
        let k = self.piece(d);
        let s = self.pts[k + 1].1;
        let st = &self.stretches[s];
        let j = self.pts[k + 1].2;
        let curve = self.model.curve(self.model.edges[st.edge].curve.unwrap_or_default());
        let (mut lo, mut hi) = (st.params[j - 1], st.params[j]);
        for _ in 0..60 {
            let m = 0.5 * (lo + hi);
            if curve.point(m).distance(o) < d {
                lo = m;
            } else {
                hi = m;
            }
        }
        let t = 0.5 * (lo + hi);
        (s, t, curve.point(t))
    }

    /// The length of the chord piece that distance `d` falls in (no step may be longer: the
    /// chord bound).
    fn chord(&self, d: f64) -> f64 {
        let k = self.piece(d);
        self.pts[k].0.distance(self.pts[k + 1].0)
    }

    /// The side's points of `strip` (`side` 0 or 1: which of the two this is): per point its
    /// edge and parameter; the stretches they cover (whole edges up to the last point's,
    /// that one from where the side enters it to the point), as `(edge, from, to)` with
    /// `from <= to`; and of those the tip's, before the first point.
    #[allow(clippy::type_complexity)]
    fn points(&self, strip: &[StripPoint], side: usize) -> (Vec<(usize, f64)>, Vec<(usize, f64, f64)>, Vec<(usize, f64, f64)>) {
        let (Some(first), Some(last)) = (strip.first(), strip.last()) else { return Default::default() };
        let params: Vec<(usize, f64)> = strip.iter().map(|q| (self.stretches[q.on[side].0].edge, q.on[side].1)).collect();
        let span = |(s_end, t_end, _): (usize, f64, DVec3)| -> Vec<(usize, f64, f64)> {
            self.stretches[..=s_end]
                .iter()
                .enumerate()
                .map(|(s, st)| {
                    let t0 = st.params[0];
                    let t1 = if s == s_end { t_end } else { st.params[st.params.len() - 1] };
                    (st.edge, t0.min(t1), t0.max(t1))
                })
                .collect()
        };
        (params, span(last.on[side]), span(first.on[side]))
    }
}

/// One point of a strip on both its sides: the step there, and per side its stretch, curve
/// parameter and position.
struct StripPoint {
    step: f64,
    on: [(usize, f64, DVec3); 2],
}

/// The strips at every corner of a face of `model` under [`CORNER_DEG`], on the edges'
/// chord-only points `edges` (vertex indices into `vertices`), with steps up to the size
/// `size` asks for.
pub(super) fn corner_strips(model: &Model, edges: &[EdgePoints], vertices: &[DVec3], size: &dyn SizeField, chord: f64) -> CornerStrips {
    let mut out = CornerStrips { edges: vec![EdgeStrip::default(); model.edges.len()], samples: Vec::new() };
    // the corners, smallest first; an edge goes to the first strip that reaches it
    let mut corners: Vec<(f64, usize, usize, Arm, Arm, bool)> = Vec::new();
    let faces_of = model.edge_faces();
    // a face's outward normal at point p
    let outward = |f: usize, p: DVec3| -> Option<DVec3> {
        let face = &model.faces[f];
        let surf = model.surface(face.surface);
        let uv = surf.project(p);
        surf.normal(uv.x, uv.y).map(|n| if face.same_sense { n } else { -n })
    };
    for (fi, face) in model.faces.iter().enumerate() {
        let surf = model.surface(face.surface);
        for &li in &face.loops {
            let lp = &model.loops[li as usize];
            let n = lp.coedges.len();
            if n < 2 {
                continue;
            }
            let face_left = face.same_sense == lp.orientation;
            for k in 0..n {
                // the corner between coedge k (in) and k + 1 (out); the sides: forward from
                // k + 1 along the loop, backward from k against it
                let fwd: Vec<&Coedge> = (1..=n.min(MAX_EDGES)).map(|j| &lp.coedges[(k + j) % n]).collect();
                let back: Vec<&Coedge> = (0..n.min(MAX_EDGES)).map(|j| &lp.coedges[(k + n - j) % n]).collect();
                if fwd[0].edge == back[0].edge {
                    continue;
                }
                // the corner's angle from the first chord of each side
                let (Some(a0), Some(b0)) = (stretch(model, edges, vertices, back[0], true), stretch(model, edges, vertices, fwd[0], false)) else { continue };
                let v = a0.pts[0];
                if b0.pts[0] != v {
                    continue;
                }
                let uv = surf.project(v);
                let Some(normal) = surf.normal(uv.x, uv.y) else { continue };
                let normal = if face_left { normal } else { -normal };
                let (u1, u2) = ((a0.pts[1] - v).normalize_or_zero(), (b0.pts[1] - v).normalize_or_zero());
                // inside the face: from the outgoing side round to the incoming one, turning
                // about the normal
                let mut angle = normal.dot(u2.cross(u1)).atan2(u2.dot(u1)).to_degrees();
                if angle < 0.0 {
                    angle += 360.0;
                }
                if angle >= CORNER_DEG {
                    continue;
                }
                let Some(a) = Arm::new(model, edges, vertices, a0, &back, true) else { continue };
                let Some(b) = Arm::new(model, edges, vertices, b0, &fwd, false) else { continue };
                // walls: a face across a side does not run on tangent from this one at the
                // corner (a fillet running out into a plane does; the solid there is not
                // thin, only the face)
                let Some(nf) = outward(fi, v) else { continue };
                let smooth = |e: usize| faces_of[e].iter().map(|&g| g as usize).filter(|&g| g != fi).all(|g| outward(g, v).is_some_and(|ng| ng.angle_between(nf).to_degrees() < TANGENT_DEG));
                let walls = !(smooth(fwd[0].edge as usize) && smooth(back[0].edge as usize));
                corners.push((angle, li as usize, k, a, b, walls));
            }
        }
    }
    corners.sort_by(|x, y| x.0.total_cmp(&y.0).then((x.1, x.2).cmp(&(y.1, y.2))));
    let min_width = super::proximity::MIN_CHORDS * chord;
    for (_, _, _, a, b, walls) in &corners {
        // beside walls the strip is a wedge of the solid too: the faces beside grade towards
        // its edge only where it is wider than `proximity` measures (two chords), so the
        // strip starts there too, and the wedge's tip is left to tets on its edge
        let pts = strip(a, b, size, if *walls { min_width } else { 0.0 });
        if pts.is_empty() {
            continue;
        }
        let ((pa, ca, ta), (pb, cb, tb)) = (a.points(&pts, 0), b.points(&pts, 1));
        // a stretch another strip covers already: the first strip keeps it
        let overlaps = |e: usize, x: f64, y: f64| out.edges[e].covered.iter().any(|&(u, w)| x < w && u < y);
        if ca.iter().chain(&cb).any(|&(e, x, y)| overlaps(e, x, y)) {
            continue;
        }
        for (e, t) in pa.into_iter().chain(pb) {
            out.edges[e].params.push(t);
        }
        for (e, x, y) in ca.into_iter().chain(cb) {
            out.edges[e].covered.push((x, y));
        }
        for (e, x, y) in ta.into_iter().chain(tb) {
            out.edges[e].tips.push((x, y));
        }
        for q in &pts {
            out.samples.push((q.on[0].2, q.step));
            out.samples.push((q.on[1].2, q.step));
        }
    }
    out
}

/// The points of a strip, and the step at each: the first where
/// the nearer of the two sides' first chord points is (or the size at the corner), then
/// steps of [`WIDTH_FACTOR`] times the width, until they are as long as the size asks for
/// or as the sides' chords, or the strip reaches [`REACH`] of its sides having opened
/// [`OPENS`]-fold. Empty where it neither widens nor opens that much within its sides (a
/// sliver face of the CAD model, whose points would only crowd it) or is wide enough at the
/// first point.
fn strip(a: &Arm, b: &Arm, size: &dyn SizeField, min_width: f64) -> Vec<StripPoint> {
    let v = a.corner();
    let reach = a.reach.min(b.reach);
    let h0 = size.size_at(v);
    let mut d = a.pts[1].0.distance(v).min(b.pts[1].0.distance(v)).min(reach);
    if h0.is_finite() && h0 > 0.0 {
        d = d.min(h0);
    }
    if min_width > 0.0 {
        // the first distance where the strip is `min_width` wide (the sides keep only the
        // chord's points before it)
        let (mut lo, mut hi) = (d, reach);
        if a.at(hi).2.distance(b.at(hi).2) < min_width {
            return Vec::new();
        }
        if a.at(lo).2.distance(b.at(lo).2) < min_width {
            for _ in 0..50 {
                let m = 0.5 * (lo + hi);
                if a.at(m).2.distance(b.at(m).2) < min_width {
                    lo = m;
                } else {
                    hi = m;
                }
            }
            d = hi;
        }
    }
    let mut out = Vec::new();
    while out.len() < MAX_POINTS && d > 0.0 && d < reach {
        let on = [a.at(d), b.at(d)];
        let (p, q) = (on[0].2, on[1].2);
        let h = size.size_at(p).min(size.size_at(q));
        if !(h.is_finite() && h > 0.0) {
            break;
        }
        let step = (WIDTH_FACTOR * p.distance(q)).max(FLOOR * h);
        if step >= ENOUGH * h || step >= a.chord(d).min(b.chord(d)) {
            // about as wide as the size asks for (a width `feature_size` measures across
            // the face beyond, or the size itself), or as the chords are long: the size and
            // the chords space the rest
            return out;
        }
        out.push(StripPoint { step, on });
        d += step;
    }
    match (out.first(), out.last()) {
        (Some(first), Some(last)) if d >= reach && last.step >= OPENS * first.step => out,
        _ => Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::size_field::UniformSize;
    use truck_modeling::{Point3, Vector3, Wire, builder};

    /// A plate `thickness` thick whose outline runs along the x axis from the origin to
    /// `length + 2`, up, back to `x = length` on the circle of `radius` about `(0, radius)`,
    /// and along that circle back to the origin, where it meets the axis tangentially: a horn,
    /// its top and bottom faces with a tangent corner at the origin, between a flat wall and
    /// a cylindrical one.
    fn horn(radius: f64, length: f64, thickness: f64) -> Model {
        let y = |x: f64| radius - (radius * radius - x * x).sqrt();
        let corners = [Point3::new(0.0, 0.0, 0.0), Point3::new(length + 2.0, 0.0, 0.0), Point3::new(length + 2.0, y(length), 0.0), Point3::new(length, y(length), 0.0)];
        let v = corners.map(builder::vertex);
        let via = Point3::new(0.5 * length, y(0.5 * length), 0.0);
        let wire: Wire = vec![builder::line(&v[0], &v[1]), builder::line(&v[1], &v[2]), builder::line(&v[2], &v[3]), builder::circle_arc(&v[3], &v[0], via)].into();
        let face = builder::try_attach_plane(&[wire]).unwrap();
        let solid = builder::tsweep(&face, Vector3::new(0.0, 0.0, thickness));
        crate::cad::parts::solid_to_model(&solid, "horn").unwrap()
    }

    /// A triangular plate 1 thick whose outline has a corner of `angle_deg` at the origin
    /// between two sides `length` long: a wedge, its top and bottom faces between flat walls.
    fn wedge(angle_deg: f64, length: f64) -> Model {
        let a = angle_deg.to_radians();
        let corners = [Point3::new(0.0, 0.0, 0.0), Point3::new(length, 0.0, 0.0), Point3::new(length * a.cos(), length * a.sin(), 0.0)];
        let v = corners.map(builder::vertex);
        let wire: Wire = vec![builder::line(&v[0], &v[1]), builder::line(&v[1], &v[2]), builder::line(&v[2], &v[0])].into();
        let face = builder::try_attach_plane(&[wire]).unwrap();
        let solid = builder::tsweep(&face, Vector3::new(0.0, 0.0, 1.0));
        crate::cad::parts::solid_to_model(&solid, "wedge").unwrap()
    }

    /// The strips of `m` at size `h`, on its chord-only tessellation at the default options.
    fn strips_of(m: &Model, h: f64) -> CornerStrips {
        let opts = super::super::TessellateOptions::default();
        let t = super::super::tessellate(m, &opts);
        corner_strips(m, &t.edges, &t.surface.vertices, &UniformSize(h), opts.chord_relative * m.size())
    }

    /// The strips' samples on the x axis at the bottom of `m`, nearest the origin first.
    fn on_axis(s: &CornerStrips) -> Vec<(f64, f64)> {
        let mut out: Vec<(f64, f64)> = s.samples.iter().filter(|x| x.0.y.abs() < 1e-12 && x.0.z.abs() < 1e-12).map(|x| (x.0.x, x.1)).collect();
        out.sort_by(|a, b| a.0.total_cmp(&b.0));
        out
    }

    #[test]
    fn a_wedge_that_opens_gets_its_strip_to_its_reach_and_a_sliver_gets_none() {
        let opts = super::super::TessellateOptions::default();
        // a 4° wedge, sides 20 long, size 1.5: from the size's distance from the corner its
        // steps stay under 3/4 of the size up to its reach (9 from the corner, where it is 0.63
        // wide), and it opens sixfold on the way
        let (length, h) = (20.0, 1.5);
        let m = wedge(4.0, length);
        let axis = on_axis(&strips_of(&m, h));
        assert!(axis.len() >= 5, "{axis:?}");
        let (first, last) = (axis[0], axis[axis.len() - 1]);
        assert!((first.0 - h).abs() < 1e-9, "starts at {first:?}");
        assert!(last.0 <= REACH * length && last.0 + last.1 >= REACH * length, "ends at {last:?}");
        assert!(last.1 >= OPENS * first.1 && last.1 < ENOUGH * h, "{first:?} .. {last:?}");
        // the width between the sides' points at one distance, 2 d sin(2°)
        let width = |x: f64| 2.0 * x * 2f64.to_radians().sin();
        for w in axis.windows(2) {
            let step = w[1].0 - w[0].0;
            assert!((step - w[0].1).abs() < 1e-9 && (step / (1.5 * width(w[0].0)) - 1.0).abs() < 1e-6, "{w:?}");
        }
        // a horn of radius 2000 (a sliver between a line and an arc nearly along it) is two
        // chords wide only about 5.1 from its corner and opens about twofold (as d^2) up to its
        // reach, 0.45 of its sides (14 and 16 long): left to the size
        let m = horn(2000.0, 14.0, 1.0);
        let chord = opts.chord_relative * m.size();
        let d0 = (4.0 * 2000.0 * chord).sqrt();
        assert!(d0 < REACH * 14.0 && (REACH * 16.0 / d0).powi(2) < 0.6 * OPENS, "{d0}");
        let axis = on_axis(&strips_of(&m, 2.0));
        assert!(axis.is_empty(), "{axis:?}");
    }

    fn min_angle(p: [DVec3; 3]) -> f64 {
        (0..3).map(|k| (p[(k + 1) % 3] - p[k]).angle_between(p[(k + 2) % 3] - p[k]).to_degrees()).fold(180.0, f64::min)
    }

    #[test]
    fn the_sides_of_a_tangent_corner_get_points_facing_each_other_a_width_apart() {
        let m = horn(20.0, 14.0, 1.0);
        let h = 2.0;
        let s = strips_of(&m, h);
        // the top and the bottom face: one strip each, on the line and the arc
        let with = s.edges.iter().filter(|e| !e.params.is_empty()).count();
        assert_eq!(with, 4, "{:?}", s.edges);
        // the points come in pairs at one distance from a corner, on the axis and on the
        // circle, each step 1.5 times the width across, until the step is 3/4 of the size
        let xs: Vec<f64> = on_axis(&s).into_iter().map(|x| x.0).collect();
        assert!(xs.len() >= 5, "{xs:?}");
        for w in xs.windows(2) {
            let width = w[0] * w[0] / 40.0;
            let step = w[1] - w[0];
            assert!((step / (1.5 * width) - 1.0).abs() < 0.1, "step {step} at {}, width {width}", w[0]);
            assert!(step < 0.75 * h);
        }
        for &(p, step) in &s.samples {
            let partner = s.samples.iter().find(|q| q.0 != p && (q.0.length() - p.length()).abs() < 1e-9 && (q.0.z - p.z).abs() < 1e-12);
            assert!(partner.is_some_and(|q| q.1 == step), "{p} has no partner");
        }
        // from a width of 2 chords to one where the step is as long as the arc's chords
        let last = xs[xs.len() - 1];
        assert!(1.5 * last * last / 40.0 > 0.2, "ends at {last}");
    }

    #[test]
    fn a_sized_tessellation_of_a_horn_has_no_needle_past_its_tip() {
        let m = horn(20.0, 14.0, 1.0);
        let opts = super::super::TessellateOptions::default();
        let t = super::super::tessellate_sized(&m, &opts, &UniformSize(2.0));
        let s = &t.surface;
        // between walls, the tip narrower than two chords keeps the chord's points (a wedge
        // of the solid that thin is left to the tets on its edge): x^2 / 40 < 2 chords
        let tip = (80.0 * opts.chord_relative * m.size()).sqrt();
        let corner = |p: DVec3| p.x < tip && p.y < 0.5;
        let mut worst = 180.0f64;
        for tri in &s.triangles {
            let p = tri.map(|i| s.vertices[i as usize]);
            // the top and bottom faces, past the tip
            if p.iter().all(|q| q.z.abs() < 1e-9 || (q.z - 1.0).abs() < 1e-9) && !p.iter().any(|&q| corner(q)) {
                worst = worst.min(min_angle(p));
            }
        }
        // (without the strips: needles of 5.2° along the tip)
        assert!(worst > 20.0, "{worst}");
    }
}
