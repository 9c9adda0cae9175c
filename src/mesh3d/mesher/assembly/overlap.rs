//! The one thing an assembly may not have: two solids whose interiors overlap.
//!
//! Touching is allowed, and a tessellation makes touching inexact: where two solids share a
//! curved face, each side's chords cut through the other's by up to the chord deviation `δ`
//! (every point of a certified tessellation lies within `δ` of the B-rep): a point of one
//! tessellated solid lies at most `2δ` inside the other. The caller's `gap` (3δ for a CAD
//! part) is the depth that is still contact. An overlap is a point that lies deeper than the
//! gap inside a solid and either on the other solid's surface or inside it too:
//!
//! - **surface points** of solid A strictly inside solid B and farther than the gap from B's
//!   surface. Candidates: the corners of A's triangles that meet a triangle of B, points
//!   along such a triangle from where they meet into B (the deepest point of a triangle that
//!   enters B at a small angle is inside the triangle), and A's vertices reached from those
//!   by walking over A's edges while they stay inside B (a surface that dives in slowly);
//! - **wedge points**: where a triangle of A meets a triangle of B and their normals are not
//!   nearly opposite (a crossing at an angle, or coincident faces with both solids on the same
//!   side), the point a little way along the bisector of the two inward normals, tested to be
//!   inside both solids and farther than the gap from both surfaces;
//! - **nesting**: a few vertices of A away from B's surface, tested to be inside B (a solid
//!   entirely inside another meets none of its triangles).
//!
//! "Inside" is exact ray parity ([`SolidSurface::inside`]), distances are floating point. A
//! single solid crossing itself is the input check's business, not this one's.

use super::solid::SolidSurface;
use super::{Pair, SolidFace, Solids};
use crate::core::intersection::triangles_meet;
use crate::mesh3d::mesher::MeshingError;
use glam::{DVec2, DVec3};
use rayon::prelude::*;

/// Below this `|na + nb|` two meeting triangles face each other: no wedge point (the wedge
/// between them is thinner than the gap near where they meet).
const WEDGE_MIN: f64 = 0.2;

/// Points tried along a triangle from where it meets the other solid.
const WALK_POINTS: usize = 4;

/// Vertices of each solid tested against every other solid whose box it reaches (nesting).
const NESTING_SAMPLES: usize = 8;

/// What was found: a point deeper than the gap inside both solids.
struct Finding {
    /// Solid (index), triangle (local) of the first side.
    a: (usize, u32),
    /// Solid, triangle of the second side.
    b: (usize, u32),
    point: DVec3,
    depth: f64,
}

/// Refuses the first overlap, in the order of the solid pairs (`pairs` sorted by solid pair).
///
/// # Errors
/// [`MeshingError::Overlap`] naming both solids, their faces, a point and the depth.
pub(crate) fn check(solids: &[SolidSurface], spec: &Solids, pairs: &[Pair], gap: f64) -> Result<(), MeshingError> {
    // the meeting pairs of each solid pair; every solid pair whose boxes are within the gap
    let mut groups: Vec<((usize, usize), &[Pair])> = Vec::new();
    let mut i = 0;
    while i < pairs.len() {
        let key = (pairs[i].a.0, pairs[i].b.0);
        let mut j = i;
        while j < pairs.len() && (pairs[j].a.0, pairs[j].b.0) == key {
            j += 1;
        }
        groups.push((key, &pairs[i..j]));
        i = j;
    }
    let mut boxes: Vec<(usize, usize)> = Vec::new();
    for a in 0..solids.len() {
        for b in a + 1..solids.len() {
            let (ba, bb) = (&solids[a].bbox, &solids[b].bbox);
            let grown = crate::core::Aabb { min: ba.min - DVec3::splat(gap), max: ba.max + DVec3::splat(gap) };
            if grown.overlaps(bb) {
                boxes.push((a, b));
            }
        }
    }
    let found: Vec<Option<Finding>> = boxes
        .par_iter()
        .map(|&(a, b)| {
            let meeting = groups.binary_search_by_key(&(a, b), |g| g.0).map_or(&[][..], |k| groups[k].1);
            pair_overlap(solids, a, b, meeting, gap)
        })
        .collect();
    match found.into_iter().flatten().next() {
        None => Ok(()),
        Some(f) => {
            let side = |(s, t): (usize, u32)| SolidFace {
                solid: spec.solids[s].tag,
                solid_name: spec.solids[s].name.clone(),
                face: solids[s].tag(t),
                face_name: solids[s].surface.face_names.get(solids[s].tag(t)).map(str::to_string),
            };
            Err(MeshingError::Overlap { a: side(f.a), b: side(f.b), point: f.point.to_array(), depth: f.depth, gap })
        }
    }
}

/// The first overlap of solids `a` and `b` (`a < b`), given their candidate triangle pairs.
fn pair_overlap(solids: &[SolidSurface], a: usize, b: usize, pairs: &[Pair], gap: f64) -> Option<Finding> {
    let (sa, sb) = (&solids[a], &solids[b]);
    let mut seeds_a: Vec<u32> = Vec::new(); // vertices of a to test against b
    let mut seeds_b: Vec<u32> = Vec::new();
    for p in pairs {
        let (ta, tb) = (p.a.1, p.b.1);
        let (ca, cb) = (sa.corners[ta as usize], sb.corners[tb as usize]);
        if !triangles_meet(ca, cb) {
            continue;
        }
        let (na, nb) = (sa.normals[ta as usize], sb.normals[tb as usize]);
        let m = common_point(ca, na, cb, nb);
        // wedge point
        let s = na + nb;
        if s.length() >= WEDGE_MIN {
            let q = m - s.normalize() * (3.0 * gap / s.length());
            if !sa.within(q, gap) && !sb.within(q, gap) && sa.inside(q) && sb.inside(q) {
                let depth = sa.nearest(q).0.min(sb.nearest(q).0);
                return Some(Finding { a: (a, ta), b: (b, tb), point: q, depth });
            }
        }
        // points along each triangle into the other solid
        for x in walk(ca, na, nb, m) {
            if let Some(f) = surface_point(x, (a, ta), sb, b, gap) {
                return Some(f);
            }
        }
        for x in walk(cb, nb, na, m) {
            if let Some(f) = surface_point(x, (b, tb), sa, a, gap).map(|f| Finding { a: f.b, b: f.a, ..f }) {
                return Some(f);
            }
        }
        seeds_a.extend(sa.surface.triangles[ta as usize]);
        seeds_b.extend(sb.surface.triangles[tb as usize]);
    }
    if let Some(f) = flood(sa, a, sb, b, seeds_a, gap) {
        return Some(f);
    }
    if let Some(f) = flood(sb, b, sa, a, seeds_b, gap).map(|f| Finding { a: f.b, b: f.a, ..f }) {
        return Some(f);
    }
    nested(sa, a, sb, b, gap).or_else(|| nested(sb, b, sa, a, gap).map(|f| Finding { a: f.b, b: f.a, ..f }))
}

/// A point `x` on triangle `on` of one solid, tested against solid `other` (index `o`).
fn surface_point(x: DVec3, on: (usize, u32), other: &SolidSurface, o: usize, gap: f64) -> Option<Finding> {
    if other.within(x, gap) || !other.inside(x) {
        return None;
    }
    let (depth, t) = other.nearest(x);
    Some(Finding { a: on, b: (o, t), point: x, depth })
}

/// Walks over the vertices of solid `s` (index `si`) from `seeds` while they stay strictly
/// inside solid `other`; the first vertex farther than the gap from `other`'s surface is an
/// overlap.
fn flood(s: &SolidSurface, si: usize, other: &SolidSurface, o: usize, mut seeds: Vec<u32>, gap: f64) -> Option<Finding> {
    if seeds.is_empty() {
        return None;
    }
    seeds.sort_unstable();
    seeds.dedup();
    let mut seen = vec![false; s.surface.vertices.len()];
    let mut queue: std::collections::VecDeque<u32> = std::collections::VecDeque::new();
    for v in seeds {
        seen[v as usize] = true;
        queue.push_back(v);
    }
    let mut neighbours: Option<Vec<Vec<u32>>> = None;
    while let Some(v) = queue.pop_front() {
        let x = s.surface.vertices[v as usize];
        if !other.inside(x) {
            continue;
        }
        if !other.within(x, gap) {
            let (depth, t) = other.nearest(x);
            let on = s.surface.triangles.iter().position(|tri| tri.contains(&v)).unwrap_or(0) as u32;
            return Some(Finding { a: (si, on), b: (o, t), point: x, depth });
        }
        let nb = neighbours.get_or_insert_with(|| s.neighbours());
        for &w in &nb[v as usize] {
            if !seen[w as usize] {
                seen[w as usize] = true;
                queue.push_back(w);
            }
        }
    }
    None
}

/// Solid `s` entirely inside solid `other`: a few of its vertices away from `other`'s surface
/// tested.
fn nested(s: &SolidSurface, si: usize, other: &SolidSurface, o: usize, gap: f64) -> Option<Finding> {
    let n = s.surface.vertices.len();
    let step = (n / NESTING_SAMPLES).max(1);
    for v in (0..n).step_by(step).take(NESTING_SAMPLES) {
        let x = s.surface.vertices[v];
        if !other.bbox.overlaps(&crate::core::Aabb { min: x, max: x }) || other.within(x, gap) || !other.inside(x) {
            continue;
        }
        let (depth, t) = other.nearest(x);
        let on = s.surface.triangles.iter().position(|tri| tri.contains(&(v as u32))).unwrap_or(0) as u32;
        return Some(Finding { a: (si, on), b: (o, t), point: x, depth });
    }
    None
}

/// A point common to two meeting triangles, in floating point: the middle of the segment
/// where they cross, or of their overlap when coplanar (near enough: it only places probes).
fn common_point(a: [DVec3; 3], na: DVec3, b: [DVec3; 3], nb: DVec3) -> DVec3 {
    let da = a.map(|p| nb.dot(p - b[0]));
    let db = b.map(|p| na.dot(p - a[0]));
    let on_a = plane_points(a, da);
    let on_b = plane_points(b, db);
    let dir = na.cross(nb);
    if dir.length() > 1e-9 && !on_a.is_empty() && !on_b.is_empty() {
        let dir = dir.normalize();
        let span = |pts: &[DVec3]| {
            let (mut lo, mut hi) = ((f64::INFINITY, pts[0]), (f64::NEG_INFINITY, pts[0]));
            for &p in pts {
                let s = p.dot(dir);
                if s < lo.0 {
                    lo = (s, p);
                }
                if s > hi.0 {
                    hi = (s, p);
                }
            }
            (lo, hi)
        };
        let ((la, pla), (ha, pha)) = span(&on_a);
        let ((lb, plb), (hb, phb)) = span(&on_b);
        // the overlap of the two spans on the line where the planes cross (or, where the
        // spans only touch in floating point, the gap between them)
        let plo = if la > lb { pla } else { plb };
        let phi = if ha < hb { pha } else { phb };
        return (plo + phi) * 0.5;
    }
    // coplanar (or nearly): the centroid of the overlap in a's plane
    let u = na.any_orthonormal_vector();
    let v = na.cross(u);
    let flat = |p: DVec3| DVec2::new(p.dot(u), p.dot(v));
    let pa = a.map(flat);
    let pb = b.map(flat);
    let mut poly: Vec<DVec2> = if orient(pa) >= 0.0 { pa.to_vec() } else { vec![pa[0], pa[2], pa[1]] };
    let pb = if orient(pb) >= 0.0 { pb } else { [pb[0], pb[2], pb[1]] };
    for k in 0..3 {
        let (p, q) = (pb[k], pb[(k + 1) % 3]);
        poly = clip_left(&poly, p, q);
    }
    if poly.is_empty() {
        // touching at a point or along an edge: the nearest corners
        let mut best = (f64::INFINITY, a[0], b[0]);
        for &p in &a {
            for &q in &b {
                if p.distance_squared(q) < best.0 {
                    best = (p.distance_squared(q), p, q);
                }
            }
        }
        return (best.1 + best.2) * 0.5;
    }
    let c = poly.iter().copied().sum::<DVec2>() / poly.len() as f64;
    let h = na.dot(a[0]);
    u * c.x + v * c.y + na * h
}

fn orient(t: [DVec2; 3]) -> f64 {
    (t[1] - t[0]).perp_dot(t[2] - t[0])
}

fn clip_left(poly: &[DVec2], p: DVec2, q: DVec2) -> Vec<DVec2> {
    let f = |x: DVec2| (q - p).perp_dot(x - p);
    let mut out = Vec::with_capacity(poly.len() + 1);
    for k in 0..poly.len() {
        let (x, y) = (poly[k], poly[(k + 1) % poly.len()]);
        let (fx, fy) = (f(x), f(y));
        if fx >= 0.0 {
            out.push(x);
        }
        if (fx >= 0.0) != (fy >= 0.0) {
            out.push(x + (y - x) * (fx / (fx - fy)));
        }
    }
    out
}

/// The points of triangle `t` on a plane, given the signed distances `d` of its corners.
fn plane_points(t: [DVec3; 3], d: [f64; 3]) -> Vec<DVec3> {
    let mut out = Vec::with_capacity(3);
    for k in 0..3 {
        let (i, j) = (k, (k + 1) % 3);
        if d[i] == 0.0 {
            out.push(t[i]);
        } else if d[i] * d[j] < 0.0 {
            out.push(t[i] + (t[j] - t[i]) * (d[i] / (d[i] - d[j])));
        }
    }
    out
}

/// Points of triangle `t` (normal `n`) from `m` in the direction that enters the other solid
/// (normal `other_n` there: against it, within `t`'s plane), up to `t`'s boundary.
fn walk(t: [DVec3; 3], n: DVec3, other_n: DVec3, m: DVec3) -> Vec<DVec3> {
    let d = -(other_n - n * other_n.dot(n));
    if d.length() < 1e-3 {
        return Vec::new();
    }
    let d = d.normalize();
    // distance from m along d to the boundary of t (in t's plane)
    let u = d;
    let w = n.cross(u);
    let flat = |p: DVec3| DVec2::new((p - m).dot(u), (p - m).dot(w));
    let q = t.map(flat);
    let mut reach = f64::INFINITY;
    for k in 0..3 {
        let (p0, p1) = (q[k], q[(k + 1) % 3]);
        // the ray (s, 0), s > 0, meets the edge where its second coordinate is 0
        if (p0.y > 0.0) != (p1.y > 0.0) {
            let s = p0.x + (p1.x - p0.x) * (p0.y / (p0.y - p1.y));
            if s > 0.0 {
                reach = reach.min(s);
            }
        }
    }
    if !reach.is_finite() {
        return Vec::new();
    }
    (1..=WALK_POINTS).map(|k| m + d * (reach * k as f64 / WALK_POINTS as f64)).collect()
}
