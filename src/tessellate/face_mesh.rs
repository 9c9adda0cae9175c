//! Meshing one face in its parameter domain with spade's constrained Delaunay triangulation.
//!
//! Parameters are scaled by the surface's mean speeds (`|∂S/∂u|`, `|∂S/∂v|`) so that the
//! triangulation sees roughly isometric coordinates (radians against millimetres otherwise).

use super::TessellateOptions;
use super::edge_points::EdgePoints;
use super::improve::Point;
use super::face_vertices::FaceVertices;
use super::seams::{is_pole, open_poles, seam_sides, unwrap_through_poles};
use crate::cad::brep::Model;
use crate::cad::geom::Surface;
use crate::core::cdt;
use crate::core::{FaceId, SizeField};
use glam::{DVec2, DVec3};
use spade::handles::FixedVertexHandle;
use spade::{ConstrainedDelaunayTriangulation, HasPosition, Point2, Triangulation};

/// A vertex of the parameter-domain triangulation.
#[derive(Clone, Copy, Debug)]
pub(super) struct V {
    /// Position in scaled `(u, v)`.
    pub(super) p: Point2<f64>,
    /// Global vertex index, or `None` for an interior point not yet lifted.
    pub(super) id: Option<u32>,
    /// Position in `(u, v)`.
    pub(super) uv: DVec2,
    /// The point in 3D.
    pub(super) p3: DVec3,
}

/// A point spade's refinement inserts: lifted by [`super::sizing::lift_new`] once refinement is done.
impl From<Point2<f64>> for V {
    fn from(p: Point2<f64>) -> V {
        V { p, id: None, uv: DVec2::NAN, p3: DVec3::NAN }
    }
}

impl HasPosition for V {
    type Scalar = f64;
    fn position(&self) -> Point2<f64> {
        self.p
    }
}

/// A loop in parameter space: `(u, v)` and global vertex index per point (not repeated at
/// the end).
pub(super) type UvLoop = Vec<(DVec2, u32)>;

/// A loop in `(u, v)` and, when it goes once around a surface periodic in `u` (closed edges
/// without a seam), the `u` shift from its start to its end.
struct Mapped {
    pts: UvLoop,
    wrap: Option<f64>,
    /// True when the face lies to the left of the loop in `(u, v)`.
    face_left: bool,
}

/// The loops of face `fid` in `(u, v)`.
fn map_loops(model: &Model, fid: FaceId, edges: &[EdgePoints], vertices: &FaceVertices) -> Result<Vec<Mapped>, String> {
    let face = model.face(fid);
    let surf = model.surface(face.surface);
    let dom = surf.domain();
    let mut loops: Vec<Mapped> = Vec::new();
    for &li in &face.loops {
        let lp = &model.loops[li as usize];
        if lp.coedges.is_empty() {
            continue; // a vertex loop: a pole or apex, nothing to bound
        }
        let mut pts: UvLoop = Vec::new();
        let mut prev: Option<DVec2> = None;
        let mut last_id = None;
        for c in &lp.coedges {
            let ep = &edges[c.edge as usize];
            let ids: Vec<u32> = if c.forward { ep.ids.clone() } else { ep.ids.iter().rev().copied().collect() };
            for (k, &id) in ids.iter().enumerate() {
                if k + 1 == ids.len() {
                    last_id = Some(id);
                    break;
                }
                let p = vertices[id as usize];
                let uv = match prev {
                    None => surf.project(p),
                    Some(q) => surf.project_near(p, q),
                };
                pts.push((uv, id));
                prev = Some(uv);
            }
        }
        if pts.len() < 2 {
            return Err(format!("loop {} has fewer than two points", lp.source));
        }
        // a surface closed but not periodic (a B-spline whose first and last rows of control
        // points coincide): seam points have two parameters, and inversion returns either
        if dom.u_closed && dom.u_period.is_none() {
            seam_sides(&mut pts, 0, dom.u.min, dom.u.max);
        }
        if dom.v_closed && dom.v_period.is_none() {
            seam_sides(&mut pts, 1, dom.v.min, dom.v.max);
        }
        // a loop that still steps across such a seam goes around the surface: its polygon in
        // (u, v) would cut straight across the domain (tens of thousands of triangles, or
        // crossing segments), so the face is refused, named, instead
        for (axis, closed, period, len) in [(0, dom.u_closed, dom.u_period, dom.u.length()), (1, dom.v_closed, dom.v_period, dom.v.length())] {
            if closed && period.is_none() && len.is_finite() {
                let n = pts.len();
                if (0..n).any(|i| (pts[(i + 1) % n].0[axis] - pts[i].0[axis]).abs() > 0.5 * len) {
                    let name = if axis == 0 { "u" } else { "v" };
                    return Err(format!("loop {} goes once around a closed B-spline surface in {name} (across its seam): not supported yet", lp.source));
                }
            }
        }
        // a loop through a pole (a cone's apex between two generators): u jumps there
        // arbitrarily, so the loop is rotated to end at the pole and unwrapped from its new
        // start; the pole then becomes a segment of the pole line (open_poles)
        let n = pts.len();
        let through_pole = |k: usize| is_pole(surf, pts[k].0) && pts[(k + n - 1) % n].1 != pts[k].1 && pts[(k + 1) % n].1 != pts[k].1;
        // the turn in u along the loop, leaving out the steps into and out of poles
        let turn: f64 = match dom.u_period {
            Some(per) => (0..n)
                .filter(|&i| !is_pole(surf, pts[i].0) && !is_pole(surf, pts[(i + 1) % n].0))
                .map(|i| {
                    let (a, b) = (pts[i].0.x, pts[(i + 1) % n].0.x);
                    crate::cad::geom::unwrap_near(b, a, per) - a
                })
                .sum(),
            None => 0.0,
        };
        let goes_around = dom.u_period.is_some_and(|per| turn.abs() > 0.75 * per);
        // (cones and spheres only: a loop of a swept B-spline face through its pole is left to
        // the general path, which meshes the corpus's wing_fuselage.step right; on a sphere the
        // general path took u across the pole by the nearest turn, a spherical triangle with a
        // corner at the pole then seemed to go once around and was cut to the pole again)
        let analytic_pole = matches!(surf, Surface::Cone(_) | Surface::Sphere(_));
        if let Some(k) = (0..n).find(|&k| analytic_pole && n >= 3 && !goes_around && through_pole(k)) {
            pts.rotate_left(k + 1);
            let face_left = face.same_sense == lp.orientation;
            if let Some(per) = dom.u_period {
                unwrap_through_poles(surf, &mut pts, per, face_left);
            }
            pts = open_poles(surf, pts);
            loops.push(Mapped { pts, wrap: None, face_left });
            continue;
        }
        // closure: the last point comes back to the first, or a period away
        let mut wrap = None;
        if let (Some(id), Some(q)) = (last_id, prev) {
            let end = surf.project_near(vertices[id as usize], q);
            let gap = end - pts[0].0;
            let wraps = |g: f64, per: Option<f64>| per.is_some_and(|p| (g.abs() - p).abs() < 0.25 * p);
            if wraps(gap.y, dom.v_period) {
                return Err(format!("loop {} goes once around the surface in v: not supported yet", lp.source));
            }
            if wraps(gap.x, dom.u_period) {
                wrap = Some(gap.x.signum() * dom.u_period.unwrap_or(0.0));
            }
        }
        loops.push(Mapped { pts, wrap, face_left: face.same_sense == lp.orientation });
    }
    Ok(loops)
}

/// The boundary of a face without edge loops (a whole sphere or torus): the rectangle of the
/// surface's bounded domain, its periodic sides sharing vertices and its collapsed sides
/// (poles) a single vertex, so the mesh closes on itself.
fn domain_rectangle(model: &Model, fid: FaceId, tol: f64, vertices: &mut FaceVertices) -> Result<UvLoop, String> {
    let surf = model.surface(model.face(fid).surface);
    let dom = surf.domain();
    if !(dom.u.is_bounded() && dom.v.is_bounded()) {
        return Err("a face without edge loops on an unbounded surface".into());
    }
    let (lo, hi) = (DVec2::new(dom.u.min, dom.v.min), DVec2::new(dom.u.max, dom.v.max));
    let (su, sv, k) = surface_scales(surf, lo, hi);
    let h = if k > 0.0 { (8.0 * tol / k).sqrt() } else { f64::INFINITY };
    let count = |len: f64| ((len / h).ceil() as usize).clamp(8, 200);
    let (nu, nv) = (count(su * dom.u.length()), count(sv * dom.v.length()));
    let uv = |i: usize, j: usize| DVec2::new(lo.x + dom.u.length() * i as f64 / nu as f64, lo.y + dom.v.length() * j as f64 / nv as f64);
    let collapsed = |j: usize| {
        let (a, b) = (surf.point(uv(0, j).x, uv(0, j).y), surf.point(uv(nu / 2, j).x, uv(nu / 2, j).y));
        (a - b).length() <= 1e-9 * (1.0 + a.length())
    };
    let (pole0, pole1) = (collapsed(0), collapsed(nv));
    let mut ids: std::collections::HashMap<(usize, usize), u32> = std::collections::HashMap::new();
    let mut id_of = |i: usize, j: usize, vertices: &mut FaceVertices| -> u32 {
        let mut key = (i, j);
        if dom.u_period.is_some() && key.0 == nu {
            key.0 = 0;
        }
        if dom.v_period.is_some() && key.1 == nv {
            key.1 = 0;
        }
        if (pole0 && key.1 == 0) || (pole1 && key.1 == nv) {
            key.0 = 0;
        }
        *ids.entry(key).or_insert_with(|| {
            let q = uv(key.0, key.1);
            let p = surf.point(q.x, q.y);
            match model.vertices.iter().position(|v| (v.point - p).length() <= 1e-9 * (1.0 + p.length())) {
                Some(k) => k as u32,
                None => {
                    vertices.push(p)
                }
            }
        })
    };
    let mut out: UvLoop = Vec::new();
    for i in 0..nu {
        out.push((uv(i, 0), id_of(i, 0, vertices)));
    }
    for j in 0..nv {
        out.push((uv(nu, j), id_of(nu, j, vertices)));
    }
    for i in (1..=nu).rev() {
        out.push((uv(i, nv), id_of(i, nv, vertices)));
    }
    for j in (1..=nv).rev() {
        out.push((uv(0, j), id_of(0, j, vertices)));
    }
    Ok(out)
}

/// Points strictly between `a` and `b` on the straight `(u, v)` segment of a cut, as an
/// edge gets them: the image on the surface within `tol` of the chords (midpoint test after
/// uniform subdivision, at most 256 pieces), no piece longer than `max_straight` (the rule
/// for a straight edge on a curved face), and with a size field spaced by it. Without the
/// last two a cut along a cylinder, whose image is a straight line, was one chord as long as
/// the cylinder beside sized points: a fan of needles that the volume mesh cannot repair.
fn iso_points(surf: &Surface, a: DVec2, b: DVec2, tol: f64, max_straight: f64, size: Option<&dyn SizeField>) -> Vec<DVec2> {
    let at = |t: f64| a + (b - a) * t;
    let point = |t: f64| {
        let uv = at(t);
        surf.point(uv.x, uv.y)
    };
    let mut n = 1usize;
    while n < 256 {
        let ok = (0..n).all(|k| {
            let (t0, t1) = (k as f64 / n as f64, (k + 1) as f64 / n as f64);
            (point(0.5 * (t0 + t1)) - 0.5 * (point(t0) + point(t1))).length() <= tol
        });
        if ok {
            break;
        }
        n *= 2;
    }
    if max_straight > 0.0 {
        let len: f64 = (0..n).map(|k| point(k as f64 / n as f64).distance(point((k + 1) as f64 / n as f64))).sum();
        n = n.max(((len / max_straight).ceil() as usize).min(256));
    }
    let mut ts: Vec<f64> = (0..=n).map(|k| k as f64 / n as f64).collect();
    if let Some(size) = size {
        ts = super::sizing::edge_params(&point, &ts, size);
    }
    ts[1..ts.len() - 1].iter().map(|&t| at(t)).collect()
}

/// Signed area of a polygon (positive counter-clockwise).
pub(super) fn signed_area(p: &[DVec2]) -> f64 {
    let n = p.len();
    (0..n).map(|i| p[i].perp_dot(p[(i + 1) % n])).sum::<f64>() / 2.0
}

/// Closed polygons in `(u, v)` for the face: loops as they are, and loops that go around a
/// periodic surface joined into one polygon by a cut between them (two such loops: a band
/// such as a cylinder between two circles) or to a pole line (one such loop: a cone up to
/// its apex, a spherical cap). The cut runs between existing boundary vertices, so no vertex
/// is added on an edge and the surface stays watertight.
#[allow(clippy::too_many_arguments)]
fn uv_loops(model: &Model, fid: FaceId, edges: &[EdgePoints], tol: f64, max_straight: f64, size: Option<&dyn SizeField>, vertices: &mut FaceVertices) -> Result<Vec<UvLoop>, String> {
    let face = model.face(fid);
    let surf = model.surface(face.surface);
    let dom = surf.domain();
    let mapped = map_loops(model, fid, edges, vertices)?;
    if mapped.is_empty() {
        return domain_rectangle(model, fid, tol, vertices).map(|l| vec![l]);
    }
    let (wrapping, plain): (Vec<Mapped>, Vec<Mapped>) = mapped.into_iter().partition(|m| m.wrap.is_some());
    let mut loops: Vec<UvLoop> = Vec::new();
    let period = dom.u_period.unwrap_or(0.0);
    match wrapping.len() {
        0 => {}
        2 => {
            let (a, b) = (&wrapping[0], &wrapping[1]);
            let ga = a.wrap.unwrap_or(0.0);
            let gb = b.wrap.unwrap_or(0.0);
            // the cut starts at a's point farthest (in u) from every hole
            let holes: Vec<(f64, f64)> = plain
                .iter()
                .map(|m| m.pts.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), (p, _)| (lo.min(p.x), hi.max(p.x))))
                .collect();
            let clearance = |u: f64| {
                holes
                    .iter()
                    .map(|&(lo, hi)| {
                        let mid = 0.5 * (lo + hi);
                        let d = crate::cad::geom::unwrap_near(u, mid, period) - mid;
                        d.abs() - 0.5 * (hi - lo)
                    })
                    .fold(f64::INFINITY, f64::min)
            };
            let ia = (0..a.pts.len()).max_by(|&i, &j| clearance(a.pts[i].0.x).total_cmp(&clearance(a.pts[j].0.x))).unwrap_or(0);
            // a unwrapped from ia
            let mut pa: UvLoop = Vec::with_capacity(a.pts.len() + 1);
            for k in 0..a.pts.len() {
                let i = (ia + k) % a.pts.len();
                let (p, id) = a.pts[i];
                let shift = if i < ia { ga } else { 0.0 };
                pa.push((p + DVec2::new(shift, 0.0), id));
            }
            let a0 = pa[0];
            // b's point nearest to a0 in u, b unwrapped near it
            let jb = (0..b.pts.len())
                .min_by(|&i, &j| {
                    let di = (crate::cad::geom::unwrap_near(b.pts[i].0.x, a0.0.x, period) - a0.0.x).abs();
                    let dj = (crate::cad::geom::unwrap_near(b.pts[j].0.x, a0.0.x, period) - a0.0.x).abs();
                    di.total_cmp(&dj)
                })
                .unwrap_or(0);
            let bj_shift = crate::cad::geom::unwrap_near(b.pts[jb].0.x, a0.0.x, period) - b.pts[jb].0.x;
            let mut pb: UvLoop = Vec::with_capacity(b.pts.len() + 1);
            for k in 0..b.pts.len() {
                let i = (jb + k) % b.pts.len();
                let (p, id) = b.pts[i];
                let shift = bj_shift + if i < jb { gb } else { 0.0 };
                pb.push((p + DVec2::new(shift, 0.0), id));
            }
            // b must run back by ga: traverse it so its total change is -ga
            let b_seq: UvLoop = if (gb + ga).abs() < 0.5 * period {
                // natural order ends at b0 + gb = b0 - ga
                let mut v = pb.clone();
                v.push((pb[0].0 + DVec2::new(gb, 0.0), pb[0].1));
                v
            } else {
                let mut v = vec![pb[0]];
                v.extend(pb[1..].iter().rev().copied());
                v.push((pb[0].0 - DVec2::new(gb, 0.0), pb[0].1));
                v
            };
            // b_seq runs from b0 to b0 - ga; shifted by +ga it runs from b0 + ga to b0
            // points along the cut from a0 to b0, shared by its two sides (u and u + ga)
            let b0 = b_seq[0].0;
            let cut: Vec<(DVec2, u32)> = iso_points(surf, a0.0, b0, tol, max_straight, size)
                .into_iter()
                .map(|uv| {
                    (uv, vertices.push(surf.point(uv.x, uv.y)))
                })
                .collect();
            let mut poly = pa.clone();
            poly.push((a0.0 + DVec2::new(ga, 0.0), a0.1));
            poly.extend(cut.iter().map(|&(p, id)| (p + DVec2::new(ga, 0.0), id)));
            poly.extend(b_seq.iter().map(|&(p, id)| (p + DVec2::new(ga, 0.0), id)));
            // the last point equals b0 (unshifted start of b_seq + ga - ga); back along the cut
            poly.extend(cut.iter().rev().copied());
            loops.push(poly);
        }
        1 => {
            let a = &wrapping[0];
            let ga = a.wrap.unwrap_or(0.0);
            // candidate pole lines: bounded ends of v, and a cone's apex
            let mut poles: Vec<f64> = Vec::new();
            if dom.v.min.is_finite() {
                poles.push(dom.v.min);
            }
            if dom.v.max.is_finite() {
                poles.push(dom.v.max);
            }
            if let crate::cad::geom::Surface::Cone(c) = surf {
                poles.push(-c.radius / c.semi_angle.tan());
            }
            let a0 = a.pts[0];
            let mut chosen = None;
            for vp in poles {
                // a pole: the surface collapses to a point along v = vp
                let (p0, p1) = (surf.point(a0.0.x, vp), surf.point(a0.0.x + 0.5 * period, vp));
                if (p0 - p1).length() > 1e-9 * (1.0 + p0.length()) {
                    continue;
                }
                let mut poly: Vec<DVec2> = a.pts.iter().map(|(p, _)| *p).collect();
                poly.push(a0.0 + DVec2::new(ga, 0.0));
                poly.push(DVec2::new(a0.0.x + ga, vp));
                poly.push(DVec2::new(a0.0.x, vp));
                if (signed_area(&poly) > 0.0) == a.face_left {
                    chosen = Some((vp, p0));
                    break;
                }
            }
            let Some((vp, pole)) = chosen else {
                return Err("a loop goes once around a periodic surface that has no pole on the face's side: not supported yet".into());
            };
            // the pole vertex: an existing vertex there, else a new one
            let pid = match model.vertices.iter().position(|v| (v.point - pole).length() <= 1e-9 * (1.0 + pole.length())) {
                Some(k) => k as u32,
                None => {
                    vertices.push(pole)
                }
            };
            // points along the cut from a0 to the pole, shared by its two sides
            let cut: Vec<(DVec2, u32)> = iso_points(surf, a0.0, DVec2::new(a0.0.x, vp), tol, max_straight, size)
                .into_iter()
                .map(|uv| {
                    (uv, vertices.push(surf.point(uv.x, uv.y)))
                })
                .collect();
            let mut poly = a.pts.clone();
            poly.push((a0.0 + DVec2::new(ga, 0.0), a0.1));
            poly.extend(cut.iter().map(|&(p, id)| (p + DVec2::new(ga, 0.0), id)));
            // points along the pole line (all the same 3D point) keep the triangles there thin
            let n = 16;
            for k in 0..=n {
                poly.push((DVec2::new(a0.0.x + ga * (1.0 - k as f64 / n as f64), vp), pid));
            }
            poly.extend(cut.iter().rev().copied());
            loops.push(poly);
        }
        n => return Err(format!("{n} loops go around a periodic surface: not supported yet")),
    }
    let outer_mean = loops.first().map(|l| l.iter().fold(DVec2::ZERO, |s, (p, _)| s + *p) / l.len() as f64);
    for m in plain {
        loops.push(m.pts);
    }
    // other loops into the first loop's period window
    let mean = |l: &UvLoop| l.iter().fold(DVec2::ZERO, |s, (p, _)| s + *p) / l.len() as f64;
    let m0 = outer_mean.unwrap_or_else(|| mean(&loops[0]));
    for l in loops.iter_mut().skip(1) {
        let m = mean(l);
        let shift = DVec2::new(
            dom.u_period.map_or(0.0, |p| ((m0.x - m.x) / p).round() * p),
            dom.v_period.map_or(0.0, |p| ((m0.y - m.y) / p).round() * p),
        );
        if shift != DVec2::ZERO {
            l.iter_mut().for_each(|(p, _)| *p += shift);
        }
    }
    Ok(loops)
}

/// Even-odd test of `p` against all loops.
fn inside(loops: &[Vec<DVec2>], p: DVec2) -> bool {
    let mut odd = false;
    for l in loops {
        let n = l.len();
        for i in 0..n {
            let (a, b) = (l[i], l[(i + 1) % n]);
            if (a.y > p.y) != (b.y > p.y) {
                let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
                if p.x < x {
                    odd = !odd;
                }
            }
        }
    }
    odd
}

/// Mean speeds `|∂S/∂u|`, `|∂S/∂v|` and the largest normal curvature-like term, over a
/// sample grid of the box `lo..hi`.
pub(super) fn surface_scales(surf: &Surface, lo: DVec2, hi: DVec2) -> (f64, f64, f64) {
    let (su, sv, [ku, kv]) = surface_bends(surf, lo, hi);
    (su, sv, ku.max(kv))
}

/// Mean speeds `|∂S/∂u|`, `|∂S/∂v|` and the largest normal curvature-like terms along each
/// scaled parameter, over a sample grid of the box `lo..hi`: `[max(k_uu, k_uv), max(k_vv,
/// k_uv)]` (a cylinder bends along `u` only: its `v` term is zero).
pub(super) fn surface_bends(surf: &Surface, lo: DVec2, hi: DVec2) -> (f64, f64, [f64; 2]) {
    let n = 6;
    let (mut su, mut sv, mut cnt) = (0.0, 0.0, 0.0);
    let mut samples = Vec::new();
    for i in 0..=n {
        for j in 0..=n {
            let u = lo.x + (hi.x - lo.x) * i as f64 / n as f64;
            let v = lo.y + (hi.y - lo.y) * j as f64 / n as f64;
            let d = surf.derivs(u, v);
            su += d.du.length();
            sv += d.dv.length();
            cnt += 1.0;
            samples.push(d);
        }
    }
    let (su, sv) = ((su / cnt).max(1e-300), (sv / cnt).max(1e-300));
    // second derivatives against the scaled parameters, normal part only (tangential parts
    // do not bend the surface)
    let (mut ku, mut kv): (f64, f64) = (0.0, 0.0);
    for d in &samples {
        let Some(nrm) = d.normal() else { continue };
        let kuu = d.duu.dot(nrm).abs() / (su * su);
        let kvv = d.dvv.dot(nrm).abs() / (sv * sv);
        let kuv = d.duv.dot(nrm).abs() / (su * sv);
        ku = ku.max(kuu).max(kuv);
        kv = kv.max(kvv).max(kuv);
    }
    (su, sv, [ku, kv])
}

/// One face's triangulation: 3D triangles and the same triangles in the face's parameter
/// domain, with the boundary segments, for quadrature over the exact surface
/// ([`super::quadrature`]).
#[derive(Clone, Debug, Default)]
pub struct FaceMesh {
    /// Triangles with global vertex indices, oriented outward by the face's sense.
    pub triangles: Vec<[u32; 3]>,
    /// The parameter-domain triangles, counter-clockwise in `(u, v)` (periodic parameters
    /// unwrapped consistently within a triangle): `uv[k]` is `triangles[k]` for
    /// `k < triangles.len()`; the rest are triangles of the domain that collapse to a line or
    /// point in 3D (along a pole), kept so that the domain is complete.
    pub uv: Vec<[DVec2; 3]>,
    /// Boundary segments of the parameter-domain triangulation: `(a, b)` global vertex
    /// indices and their `(u, v)`, directed with the face on the left in `(u, v)`.
    pub boundary: Vec<([u32; 2], [DVec2; 2])>,
}

/// Why a face could not be meshed.
#[derive(Clone, Debug, PartialEq)]
pub enum FaceError {
    /// Boundary segments cross or touch in parameter space: those segments, as the global
    /// vertex ids of their ends (the tessellator splits the edge segments among them and
    /// meshes again).
    Crossing(Vec<[u32; 2]>),
    /// Any other reason, in words.
    Other(String),
}

impl From<String> for FaceError {
    fn from(s: String) -> FaceError {
        FaceError::Other(s)
    }
}

impl From<&str> for FaceError {
    fn from(s: &str) -> FaceError {
        FaceError::Other(s.to_string())
    }
}

impl std::fmt::Display for FaceError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FaceError::Crossing(segs) => write!(f, "boundary segments cross in parameter space ({} segments)", segs.len()),
            FaceError::Other(s) => f.write_str(s),
        }
    }
}

/// The triangles of one face, with global vertex indices (new interior vertices appended to
/// `vertices`, the face's own), oriented outward by the face's sense.
///
/// # Errors
/// Why the face could not be meshed: crossing boundary segments, or a message.
#[allow(clippy::too_many_arguments)]
pub fn mesh_face(model: &Model, fid: FaceId, edges: &[EdgePoints], tol: f64, max_straight: f64, opts: &TessellateOptions, size: Option<&dyn SizeField>, vertices: &mut FaceVertices) -> Result<FaceMesh, FaceError> {
    let face = model.face(fid);
    let surf = model.surface(face.surface);
    let loops = uv_loops(model, fid, edges, tol, max_straight, size, vertices)?;
    let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    for (p, _) in loops.iter().flatten() {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    if !(lo.is_finite() && hi.is_finite()) {
        return Err("parameters of the boundary are not finite".into());
    }
    let (su, sv, [ku, kv]) = surface_bends(surf, lo, hi);
    // interior grid steps: from the largest bend, or on a cylinder without a size field along
    // each parameter from its own bend (its generators are straight: one step along them)
    let ruled = matches!(surf, Surface::Cylinder(_)) && size.is_none();
    let ext = (hi - lo) * DVec2::new(su, sv);
    let (ku, kv) = if ruled { (ku, kv) } else { (ku.max(kv), ku.max(kv)) };
    let step = |k: f64, len: f64| if k > 0.0 { (8.0 * tol / k).sqrt() } else { len };
    // (along the generators at most four pieces of a straight edge on a curved face: the
    // triangles stay shorter than the sides they lie along, a cylinder cut by its own seam
    // has rows along it)
    let along = if max_straight > 0.0 { 4.0 * max_straight } else { f64::INFINITY };
    let (hu, hv) = if ruled { (step(ku, ext.x).min(ext.x).min(along), step(kv, ext.y).min(ext.y).min(along)) } else { (step(ku, ext.x), step(kv, ext.y)) };
    let steps = |len: f64, h: f64| if h > 0.0 { ((len / h).ceil() as usize).clamp(1, opts.max_grid) } else { 1 };
    let (nu, nv) = (steps(ext.x, hu), steps(ext.y, hv));
    // without a size field, spade triangulates a cylinder in a metric where those steps are
    // equal: the triangles stretch along its straight generators (it becomes a strip between
    // its two circles, as long as it is) instead of filling them with points. Not with a
    // size field (it needs lengths near 3D lengths), nor on other surfaces (a cone's apex, an
    // extrusion's pole: the fans there fold; wing_fuselage.step)
    let (su, sv) = match size {
        None if ruled && hu > 0.0 && hv > 0.0 => {
            let h = hu.min(hv);
            (su * h / hu, sv * h / hv)
        }
        _ => (su, sv),
    };
    // flushed as spade will see them (`core::cdt`'s guard), for the inside tests too
    let scale = |p: DVec2| DVec2::new(cdt::flush(p.x * su), cdt::flush(p.y * sv));
    let scaled: Vec<Vec<DVec2>> = loops.iter().map(|l| l.iter().map(|(p, _)| scale(*p)).collect()).collect();

    let mut tri: ConstrainedDelaunayTriangulation<V> = ConstrainedDelaunayTriangulation::new();
    let mut handles: Vec<Vec<FixedVertexHandle>> = Vec::new();
    for (l, sl) in loops.iter().zip(&scaled) {
        let mut hs = Vec::with_capacity(l.len());
        for ((uv, id), s) in l.iter().zip(sl) {
            let h = cdt::insert(&mut tri, *s, |p| V { p, id: Some(*id), uv: *uv, p3: vertices[*id as usize] }).map_err(|e| format!("cannot insert a boundary point: {e}"))?;
            hs.push(h);
        }
        handles.push(hs);
    }
    for hs in &handles {
        let n = hs.len();
        for i in 0..n {
            let (a, b) = (hs[i], hs[(i + 1) % n]);
            if a == b {
                continue;
            }
            if tri.try_add_constraint(a, b).is_empty() && !tri.exists_constraint(a, b) {
                let ids: Vec<Vec<u32>> = loops.iter().map(|l| l.iter().map(|(_, id)| *id).collect()).collect();
                let mut segs = super::crossings::crossing_segments(&scaled, &ids);
                if segs.is_empty() {
                    // spade refused it for a reason the exact test does not see: this segment
                    let (ia, ib) = (tri.vertex(a).data().id, tri.vertex(b).data().id);
                    segs.extend(ia.zip(ib).map(|(x, y)| [x, y]));
                }
                return Err(FaceError::Crossing(segs));
            }
        }
    }
    // interior grid where the surface bends, spaced along each parameter by its own bend
    if ku.max(kv) > 0.0 {
        let (slo, shi) = (scale(lo), scale(hi));
        if nu >= 2 || nv >= 2 {
            let (nu, nv) = (nu.max(1), nv.max(1));
            let cell = DVec2::new((shi.x - slo.x) / nu as f64, (shi.y - slo.y) / nv as f64);
            let clear = Clearance::new(&scaled, slo, cell, nu, nv);
            for i in 0..nu {
                for j in 0..nv {
                    let s = DVec2::new(slo.x + (shi.x - slo.x) * (i as f64 + 0.5) / nu as f64, slo.y + (shi.y - slo.y) * (j as f64 + 0.5) / nv as f64);
                    // a grid point on or next to a boundary segment would split it (spade
                    // splits constraints through inserted points) or make slivers
                    if inside(&scaled, s) && clear.far(s, 0.3 * cell.min_element()) {
                        let uv = DVec2::new(s.x / su, s.y / sv);
                        cdt::insert(&mut tri, s, |p| V { p, id: None, uv, p3: surf.point(uv.x, uv.y) }).map_err(|e| format!("cannot insert an interior point: {e}"))?;
                    }
                }
            }
        }
    }
    super::refine::refine(&mut tri, surf, tol, opts)?;
    if let Some(size) = size {
        // well-shaped triangles of the local size, after the deviation's refinement, whose
        // centroids make thin triangles that this mends
        super::sizing::refine_face(&mut tri, surf, su, sv, size);
    }
    // the triangles inside the loops (an odd number of constraint edges crossed from the
    // outside: exact, unlike a point-in-polygon test on thin triangles along nearly straight
    // boundaries), their boundary segments, as points and indices
    let inside_faces = constraint_parity(&tri);
    let mut pts: Vec<Point> = tri.vertices().map(|v| {
        let d = v.data();
        Point { s: DVec2::new(d.p.x, d.p.y), uv: d.uv, p3: d.p3, id: d.id }
    }).collect();
    let mut tris: Vec<[u32; 3]> = Vec::new();
    let mut segments: Vec<[u32; 2]> = Vec::new();
    for f in tri.inner_faces() {
        if !inside_faces[f.fix().index()] {
            continue;
        }
        // boundary segments: constraint edges with the outside (or the outer face) beyond
        for e in f.adjacent_edges() {
            let beyond = e.rev().face().as_inner().is_none_or(|g| !inside_faces[g.fix().index()]);
            if e.is_constraint_edge() && beyond {
                segments.push([e.from().fix().index() as u32, e.to().fix().index() as u32]);
            }
        }
        tris.push(f.vertices().map(|v| v.fix().index() as u32));
    }
    let removed = match size {
        Some(size) => {
            let cos_max = (2.0 * opts.max_angle_deg).to_radians().cos();
            super::improve::improve(&mut pts, &mut tris, &segments, surf, su, sv, size, tol, cos_max).removed
        }
        None => vec![false; pts.len()],
    };
    // lift: boundary points have their global index, the others get one
    let ids: Vec<u32> = pts.iter().zip(&removed).map(|(p, &gone)| match p.id {
        Some(id) => id,
        None if gone => u32::MAX,
        None => vertices.push(p.p3),
    }).collect();
    let mut out = FaceMesh::default();
    for &[a, b] in &segments {
        out.boundary.push(([ids[a as usize], ids[b as usize]], [pts[a as usize].uv, pts[b as usize].uv]));
    }
    for t in &tris {
        let uv = t.map(|i| pts[i as usize].uv);
        let [a, b, cc] = t.map(|i| ids[i as usize]);
        if a == b || b == cc || a == cc {
            // a triangle collapsed in 3D (along a pole line): zero area, but part of the domain
            out.uv.push(uv);
            out.triangles.push([u32::MAX; 3]);
            continue;
        }
        out.uv.push(uv);
        out.triangles.push(if face.same_sense { [a, b, cc] } else { [a, cc, b] });
    }
    // collapsed triangles: kept in the domain for quadrature only
    let keep: Vec<bool> = out.triangles.iter().map(|t| t[0] != u32::MAX).collect();
    let domain_only: Vec<[DVec2; 3]> = out.uv.iter().zip(&keep).filter(|(_, k)| !**k).map(|(u, _)| *u).collect();
    let mut k = 0;
    out.triangles.retain(|t| t[0] != u32::MAX);
    out.uv.retain(|_| {
        k += 1;
        keep[k - 1]
    });
    out.uv.extend(domain_only);
    if out.triangles.is_empty() {
        return Err("no triangle inside the face's loops".into());
    }
    Ok(out)
}

/// Per face index (outer face included): true when an odd number of constraint edges
/// separates it from the outer face. A 0-1 breadth-first search over face adjacency.
pub(super) fn constraint_parity(cdt: &ConstrainedDelaunayTriangulation<V>) -> Vec<bool> {
    let n = cdt.num_all_faces();
    let mut depth = vec![usize::MAX; n];
    let mut queue = std::collections::VecDeque::new();
    let outer = cdt.outer_face().fix().index();
    depth[outer] = 0;
    // the outer face has no adjacent_edges list of three: seed from the convex hull
    for e in cdt.convex_hull() {
        for f in [e.face(), e.rev().face()] {
            if let Some(inner) = f.as_inner() {
                let d = usize::from(e.is_constraint_edge());
                let k = inner.fix().index();
                if d < depth[k] {
                    depth[k] = d;
                    if d == 0 { queue.push_front(k) } else { queue.push_back(k) }
                }
            }
        }
    }
    let faces: Vec<_> = cdt.inner_faces().collect();
    let mut by_index = vec![None; n];
    for (k, f) in faces.iter().enumerate() {
        by_index[f.fix().index()] = Some(k);
    }
    while let Some(k) = queue.pop_front() {
        let Some(fi) = by_index[k] else { continue };
        let f = faces[fi];
        for e in f.adjacent_edges() {
            let Some(nb) = e.rev().face().as_inner() else { continue };
            let j = nb.fix().index();
            let step = usize::from(e.is_constraint_edge());
            let d = depth[k] + step;
            if d < depth[j] {
                depth[j] = d;
                if step == 0 { queue.push_front(j) } else { queue.push_back(j) }
            }
        }
    }
    depth.into_iter().map(|d| d != usize::MAX && d % 2 == 1).collect()
}

/// Boundary segments bucketed on the interior grid's cells, for the distance test of grid
/// points.
struct Clearance<'a> {
    loops: &'a [Vec<DVec2>],
    lo: DVec2,
    cell: DVec2,
    nu: usize,
    nv: usize,
    /// Per cell: (loop, segment) pairs whose box, grown by one cell, covers it.
    buckets: Vec<Vec<(u32, u32)>>,
}

impl<'a> Clearance<'a> {
    fn new(loops: &'a [Vec<DVec2>], lo: DVec2, cell: DVec2, nu: usize, nv: usize) -> Clearance<'a> {
        let mut buckets = vec![Vec::new(); nu * nv];
        let idx = |p: f64, lo: f64, c: f64, n: usize| (((p - lo) / c).floor().max(0.0) as usize).min(n - 1);
        for (li, l) in loops.iter().enumerate() {
            let n = l.len();
            for si in 0..n {
                let (a, b) = (l[si], l[(si + 1) % n]);
                let (mn, mx) = (a.min(b) - cell, a.max(b) + cell);
                let (i0, i1) = (idx(mn.x, lo.x, cell.x, nu), idx(mx.x, lo.x, cell.x, nu));
                let (j0, j1) = (idx(mn.y, lo.y, cell.y, nv), idx(mx.y, lo.y, cell.y, nv));
                for i in i0..=i1 {
                    for j in j0..=j1 {
                        buckets[i * nv + j].push((li as u32, si as u32));
                    }
                }
            }
        }
        Clearance { loops, lo, cell, nu, nv, buckets }
    }

    /// True when `p` is farther than `d` from every boundary segment.
    fn far(&self, p: DVec2, d: f64) -> bool {
        let i = (((p.x - self.lo.x) / self.cell.x).floor().max(0.0) as usize).min(self.nu - 1);
        let j = (((p.y - self.lo.y) / self.cell.y).floor().max(0.0) as usize).min(self.nv - 1);
        self.buckets[i * self.nv + j].iter().all(|&(li, si)| {
            let l = &self.loops[li as usize];
            let (a, b) = (l[si as usize], l[(si as usize + 1) % l.len()]);
            let ab = b - a;
            let t = if ab.length_squared() > 0.0 { ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0) } else { 0.0 };
            (a + t * ab - p).length() > d
        })
    }
}
