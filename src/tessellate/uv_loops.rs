//! A face's boundary in its parameter domain: the B-rep loops mapped to `(u, v)` (seam points
//! on their neighbours' side, poles opened, a loop across a closed B-spline's seam refused),
//! loops that go around a periodic surface joined by a cut between them (on a torus, the band
//! on the face's side of them: two circles bound two bands) or to a pole line,
//! and the domain rectangle of a face without edge loops. `face_mesh` triangulates what this
//! gives.

use super::edge_points::EdgePoints;
use super::face_error::FaceError;
use super::surface_scales::surface_scales;
use super::face_vertices::FaceVertices;
use super::seams::{is_pole, open_poles, seam_sides, unwrap_through_poles};
use crate::cad::brep::Model;
use crate::cad::geom::Surface;
use crate::core::{FaceId, SizeField};
use super::uv_polygon::{UvLoop, signed_area};
use glam::DVec2;

/// A loop in `(u, v)` and, when it goes once around a surface periodic in `u` (closed edges
/// without a seam), the `u` shift from its start to its end.
struct Mapped {
    pts: UvLoop,
    wrap: Option<f64>,
    /// True when the face lies to the left of the loop in `(u, v)`.
    face_left: bool,
}

/// The loops of face `fid` in `(u, v)`.
fn map_loops(model: &Model, fid: FaceId, edges: &[EdgePoints], vertices: &FaceVertices) -> Result<Vec<Mapped>, FaceError> {
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
            return Err(FaceError::LoopTooShort { edge_loop: lp.source });
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
                    return Err(FaceError::AcrossSeam { edge_loop: lp.source, direction: name });
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
        // a loop that goes up an edge to the pole and back down the same edge (a dome cut
        // open along a meridian: the edge is its seam) goes around too, and is unwrapped from
        // the pole the same way: down the edge on one side, around, and up it on the other
        let slit = |k: usize| pts[(k + n - 1) % n].1 == pts[(k + 1) % n].1;
        if let Some(k) = (0..n).find(|&k| analytic_pole && n >= 3 && (!goes_around || slit(k)) && through_pole(k)) {
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
                return Err(FaceError::AroundInV { edge_loop: lp.source });
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
/// `shift` moves its corner: its seam where no loop of the face crosses it (zero for a face
/// without loops).
fn domain_rectangle(model: &Model, fid: FaceId, tol: f64, shift: DVec2, vertices: &mut FaceVertices) -> Result<UvLoop, FaceError> {
    let surf = model.surface(model.face(fid).surface);
    let dom = surf.domain();
    if !(dom.u.is_bounded() && dom.v.is_bounded()) {
        return Err(FaceError::UnboundedWithoutLoops);
    }
    let (lo, hi) = (DVec2::new(dom.u.min, dom.v.min) + shift, DVec2::new(dom.u.max, dom.v.max) + shift);
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

/// The outer boundary of a face on a closed surface whose every loop has the face outside it
/// in `(u, v)`: a ball with a hole drilled across its axis, whose two openings are small
/// loops that do not go around the poles, or a torus with a window. No loop bounds such a
/// face from outside; the surface's domain rectangle does (its periodic sides sharing
/// vertices, its poles a single vertex), placed where no loop crosses its sides, and the loops
/// are moved by whole periods into it. `None` when a loop has the face inside it, the surface
/// is not closed, or a loop touches a pole.
///
/// # Errors
/// When the loops cover every `u` (or every `v` on a torus), so that no place for the seam
/// avoids them.
fn enclosing_rectangle(model: &Model, fid: FaceId, plain: &mut [Mapped], tol: f64, vertices: &mut FaceVertices) -> Result<Option<UvLoop>, FaceError> {
    let surf = model.surface(model.face(fid).surface);
    let dom = surf.domain();
    let Some(u_period) = dom.u_period else { return Ok(None) };
    let poles = || {
        let (a, b) = (surf.point(0.0, dom.v.min), surf.point(0.5 * u_period, dom.v.min));
        let (c, d) = (surf.point(0.0, dom.v.max), surf.point(0.5 * u_period, dom.v.max));
        let same = |p: glam::DVec3, q: glam::DVec3| (p - q).length() <= 1e-9 * (1.0 + p.length());
        same(a, b) && same(c, d)
    };
    let closed = dom.v_period.is_some() || (dom.v.is_bounded() && poles());
    let hole = |m: &Mapped| {
        let p: Vec<DVec2> = m.pts.iter().map(|(p, _)| *p).collect();
        (signed_area(&p) > 0.0) != m.face_left
    };
    if !closed || plain.is_empty() || !plain.iter().all(hole) || plain.iter().flat_map(|m| &m.pts).any(|(p, _)| is_pole(surf, *p)) {
        return Ok(None);
    }
    let span = |m: &Mapped, axis: usize| m.pts.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), (p, _)| (lo.min(p[axis]), hi.max(p[axis])));
    let mut start = DVec2::new(dom.u.min, dom.v.min);
    for (axis, period) in [(0, Some(u_period)), (1, dom.v_period)] {
        let Some(period) = period else { continue };
        let spans: Vec<(f64, f64)> = plain.iter().map(|m| span(m, axis)).collect();
        let Some(seam) = free_parameter(&spans, period) else {
            let name = if axis == 0 { "u" } else { "v" };
            return Err(FaceError::HolesCoverClosed { direction: name });
        };
        start[axis] = seam;
        for (m, &(lo, _)) in plain.iter_mut().zip(&spans) {
            let shift = -((lo - seam) / period).floor() * period;
            m.pts.iter_mut().for_each(|(p, _)| p[axis] += shift);
        }
    }
    let shift = start - DVec2::new(dom.u.min, dom.v.min);
    domain_rectangle(model, fid, tol, shift, vertices).map(Some)
}

/// A parameter, modulo `period`, that lies in none of the intervals `[lo, hi]` (each shorter
/// than the period): the middle of the widest gap between them. `None` when they cover the
/// whole period.
fn free_parameter(spans: &[(f64, f64)], period: f64) -> Option<f64> {
    let mut iv: Vec<(f64, f64)> = spans
        .iter()
        .map(|&(lo, hi)| {
            let l = lo.rem_euclid(period);
            (l, l + (hi - lo))
        })
        .collect();
    iv.sort_by(|a, b| a.0.total_cmp(&b.0));
    let first = iv.first()?.0;
    let mut end = iv[0].1;
    let mut best: Option<(f64, f64)> = None;
    let mut consider = |a: f64, b: f64| {
        if b - a > 1e-9 * period && best.is_none_or(|(x, y)| b - a > y - x) {
            best = Some((a, b));
        }
    };
    for &(l, h) in &iv[1..] {
        if l > end {
            consider(end, l);
        }
        end = end.max(h);
    }
    consider(end, first + period);
    best.map(|(a, b)| 0.5 * (a + b))
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


/// Closed polygons in `(u, v)` for the face: loops as they are, and loops that go around a
/// periodic surface joined into one polygon by a cut between them (two such loops: a band
/// such as a cylinder between two circles) or to a pole line (one such loop: a cone up to
/// its apex, a spherical cap). The cut runs between existing boundary vertices, so no vertex
/// is added on an edge and the surface stays watertight.
#[allow(clippy::too_many_arguments)]
pub(super) fn uv_loops(model: &Model, fid: FaceId, edges: &[EdgePoints], tol: f64, max_straight: f64, size: Option<&dyn SizeField>, vertices: &mut FaceVertices) -> Result<Vec<UvLoop>, FaceError> {
    let face = model.face(fid);
    let surf = model.surface(face.surface);
    let dom = surf.domain();
    let mapped = map_loops(model, fid, edges, vertices)?;
    if mapped.is_empty() {
        return domain_rectangle(model, fid, tol, DVec2::ZERO, vertices).map(|l| vec![l]);
    }
    let (wrapping, mut plain): (Vec<Mapped>, Vec<Mapped>) = mapped.into_iter().partition(|m| m.wrap.is_some());
    let mut loops: Vec<UvLoop> = Vec::new();
    let period = dom.u_period.unwrap_or(0.0);
    match wrapping.len() {
        0 => {
            if let Some(rect) = enclosing_rectangle(model, fid, &mut plain, tol, vertices)? {
                loops.push(rect);
            }
        }
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
            // b traversed so that its total change is -ga (it must run back by ga), moved by
            // `dv` in v
            let b_run = |dv: f64| -> UvLoop {
                let mut pb: UvLoop = Vec::with_capacity(b.pts.len() + 1);
                for k in 0..b.pts.len() {
                    let i = (jb + k) % b.pts.len();
                    let (p, id) = b.pts[i];
                    let shift = bj_shift + if i < jb { gb } else { 0.0 };
                    pb.push((p + DVec2::new(shift, dv), id));
                }
                if (gb + ga).abs() < 0.5 * period {
                    // natural order ends at b0 + gb = b0 - ga
                    let mut v = pb.clone();
                    v.push((pb[0].0 + DVec2::new(gb, 0.0), pb[0].1));
                    v
                } else {
                    let mut v = vec![pb[0]];
                    v.extend(pb[1..].iter().rev().copied());
                    v.push((pb[0].0 - DVec2::new(gb, 0.0), pb[0].1));
                    v
                }
            };
            // the band between the two loops, without the cut's inner points (it is straight
            // in (u, v)): on a surface periodic in v too (a torus) the loops bound two bands,
            // and the one on the face's side of `a` is taken, b moved by a period if need be
            let band = |b_seq: &UvLoop| -> Vec<DVec2> {
                let mut poly: Vec<DVec2> = pa.iter().map(|(p, _)| *p).collect();
                poly.push(a0.0 + DVec2::new(ga, 0.0));
                poly.extend(b_seq.iter().map(|(p, _)| *p + DVec2::new(ga, 0.0)));
                poly
            };
            let mut b_seq = b_run(0.0);
            if let Some(vp) = dom.v_period
                && (signed_area(&band(&b_seq)) > 0.0) != a.face_left
            {
                let dv = if b_seq[0].0.y > a0.0.y { -vp } else { vp };
                let other = b_run(dv);
                if (signed_area(&band(&other)) > 0.0) == a.face_left {
                    b_seq = other;
                }
            }
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
                poles.push(c.apex_v());
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
                return Err(FaceError::NoPoleOnSide);
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
        n => return Err(FaceError::ManyAround { loops: n }),
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
