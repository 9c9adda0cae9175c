//! One step of the advancing front: the shortest front edge gets a triangle on its left.
//!
//! - Stage: the front's main loop ([`Advance::run`]), after the front is built from the
//!   domain's segments and before `improve`.
//! - Inputs: the front, the points so far, the size `h(p)`.
//! - Output: triangles, counter-clockwise, and the new points (all strictly inside the
//!   domain); the front shrinks to nothing.
//! - The step (Lo, Löhner): for the front edge `AB` the ideal point `P` lies on its left at
//!   the height of an equilateral triangle of side `h` (clamped to `0.55..2 |AB|`). The
//!   candidates are the front vertices within `|AP|` of `P`, scored by the shape of the
//!   triangle they make with `AB`, and `P` itself, scored a little lower (closing the front
//!   is preferred) and only when no front vertex or edge comes within half its side. The
//!   first candidate `C` that fits wins: `ABC` positive, no front edge meeting the triangle
//!   other than along its own edges, no reversed triangle edge on the front, and (first pass)
//!   no front vertex on the left of `AB` strictly inside the circumcircle (Delaunay check).
//! - Fallbacks, in order, when nothing fits: candidates without the Delaunay check; `P`
//!   lowered; every front vertex within three sides; then the edge is deferred and retried
//!   after the others. A round of deferred edges that makes no triangle is a stall, and an
//!   error naming the edge.
//! - Invariants: every sign is exact (`orient2d`, `incircle`); the front always bounds the
//!   unmeshed region (so a triangle that meets no front edge lies inside it); candidates
//!   are ordered by score then index, so the result depends only on the input.

use super::queue::Front;
use super::Error;
use crate::core::predicates::{incircle, orient2d};
use crate::core::Sign;
use crate::mesh2d::boundary::check_size;
use crate::mesh2d::domain::{point_segment_distance, segments_intersect};
use glam::DVec2;

/// The candidate id of the new point.
const NEW: u32 = u32::MAX;
/// The new point's score is its triangle's shape times this (closing the front is preferred).
const NEW_POINT_WEIGHT: f64 = 0.85;
/// A new point keeps this fraction of its side away from front vertices and edges.
const SPACING: f64 = 0.5;
/// The height of the ideal point, in front edge lengths.
const HEIGHT: [f64; 2] = [0.55, 2.0];

/// Counts of the front's run.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct FrontStats {
    /// Edges taken from the queue (deferrals included).
    pub steps: usize,
    /// Points created inside the domain.
    pub points: usize,
    /// Triangles made by a fallback (no Delaunay check, a lowered point, a wider search).
    pub fallbacks: usize,
    /// Edges deferred because nothing fitted at the time.
    pub deferrals: usize,
}

/// What a step did.
enum Outcome {
    Made,
    Deferred,
}

/// The advancing front's state.
pub(crate) struct Advance<'a> {
    /// Points: the domain's first, then the new ones.
    pub(crate) pts: Vec<DVec2>,
    /// Triangles made so far.
    pub(crate) tris: Vec<[u32; 3]>,
    pub(crate) front: Front,
    size: &'a dyn Fn(DVec2) -> f64,
    delaunay: bool,
    pub(crate) stats: FrontStats,
    edges: Vec<u32>,
    verts: Vec<u32>,
}

/// The shape of a triangle: `4√3 area / Σ edge²`, 1 for the equilateral, negative when
/// clockwise.
pub(crate) fn shape(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    let area2 = (b - a).perp_dot(c - a);
    let sum = a.distance_squared(b) + b.distance_squared(c) + c.distance_squared(a);
    if sum > 0.0 { 2.0 * 3f64.sqrt() * area2 / sum } else { 0.0 }
}

/// Whether `p` lies in the closed triangle `abc` (counter-clockwise), exactly.
fn in_closed(a: DVec2, b: DVec2, c: DVec2, p: DVec2) -> bool {
    orient2d(a, b, p) != Sign::Negative && orient2d(b, c, p) != Sign::Negative && orient2d(c, a, p) != Sign::Negative
}

impl<'a> Advance<'a> {
    /// A front over `pts` (already holding the domain's segments).
    pub(crate) fn new(pts: Vec<DVec2>, front: Front, size: &'a dyn Fn(DVec2) -> f64, delaunay: bool) -> Advance<'a> {
        Advance { pts, tris: Vec::new(), front, size, delaunay, stats: FrontStats::default(), edges: Vec::new(), verts: Vec::new() }
    }

    /// Advances until the front is empty.
    ///
    /// # Errors
    /// A bad size, more than `max_steps` steps, or a stall (a round of deferred edges that
    /// made no triangle).
    pub(crate) fn run(&mut self, max_steps: usize) -> Result<(), Error> {
        let mut deferred: Vec<u32> = Vec::new();
        let mut progress = false;
        while self.front.live > 0 {
            let Some(e) = self.front.pop() else {
                deferred.retain(|&d| self.front.alive[d as usize]);
                if !progress || deferred.is_empty() {
                    let d = deferred.first().copied().or_else(|| (0..self.front.edges.len() as u32).find(|&d| self.front.alive[d as usize]));
                    let [a, b] = d.map_or([0, 0], |d| self.front.edges[d as usize]);
                    let (p, q) = (self.pts[a as usize], self.pts[b as usize]);
                    return Err(Error::Stalled { from: a, to: b, x0: p.x, y0: p.y, x1: q.x, y1: q.y });
                }
                progress = false;
                for d in deferred.drain(..) {
                    self.front.requeue(d, &self.pts);
                }
                continue;
            };
            self.stats.steps += 1;
            if self.stats.steps > max_steps {
                return Err(Error::StepLimit { steps: max_steps, triangles: self.tris.len() });
            }
            match self.step(e)? {
                Outcome::Made => progress = true,
                Outcome::Deferred => {
                    self.stats.deferrals += 1;
                    deferred.push(e);
                }
            }
        }
        Ok(())
    }

    fn size_at(&self, p: DVec2) -> Result<f64, Error> {
        Ok(check_size(p, (self.size)(p))?)
    }

    /// One step on the front edge `e` (see the module docs).
    fn step(&mut self, e: u32) -> Result<Outcome, Error> {
        let [a, b] = self.front.edges[e as usize];
        let (pa, pb) = (self.pts[a as usize], self.pts[b as usize]);
        let l = pa.distance(pb);
        let mid = 0.5 * (pa + pb);
        let n = (pb - pa).perp() / l;
        let height = |h: f64| (0.5 * 3f64.sqrt() * h).clamp(HEIGHT[0] * l, HEIGHT[1] * l);
        let h0 = self.size_at(mid)?;
        // the size where the triangle will be (the size may be undefined outside the domain)
        let p0 = mid + n * height(h0);
        let h1 = (self.size)(p0);
        let h = if h1.is_finite() && h1 > 0.0 { 0.5 * (h0 + h1) } else { h0 };
        let ht = height(h);
        let p = mid + n * ht;
        let side = p.distance(pa);

        // candidates: front vertices near P on the left of AB, and P itself
        let mut cands: Vec<(f64, u32)> = Vec::new();
        let r = DVec2::splat(side);
        self.front.vertices_in(p - r, p + r, self.pts.len(), &mut self.verts);
        for &v in &self.verts {
            let pv = self.pts[v as usize];
            if v != a && v != b && pv.distance(p) <= side && orient2d(pa, pb, pv) == Sign::Positive {
                cands.push((shape(pa, pb, pv), v));
            }
        }
        if !self.too_close(p, SPACING * side, e, a, b) {
            cands.push((NEW_POINT_WEIGHT * shape(pa, pb, p), NEW));
        }
        cands.sort_by(|x, y| y.0.total_cmp(&x.0).then(x.1.cmp(&y.1)));
        let passes: &[bool] = if self.delaunay { &[true, false] } else { &[false] };
        for (k, &check) in passes.iter().enumerate() {
            for &(_, c) in &cands {
                let pc = if c == NEW { p } else { self.pts[c as usize] };
                if self.fits(e, a, b, c, pc) && (!check || self.delaunay_ok(a, b, c, pc, side.max(l))) {
                    if k > 0 {
                        self.stats.fallbacks += 1;
                    }
                    self.accept(e, a, b, c, pc);
                    return Ok(Outcome::Made);
                }
            }
        }
        // fallbacks: P lowered, then every front vertex within three sides
        for f in [0.6, 0.35, 0.2] {
            let q = mid + n * (ht * f);
            let s = q.distance(pa);
            if !self.too_close(q, SPACING * s, e, a, b) && self.fits(e, a, b, NEW, q) {
                self.stats.fallbacks += 1;
                self.accept(e, a, b, NEW, q);
                return Ok(Outcome::Made);
            }
        }
        let r = DVec2::splat(3.0 * side.max(l));
        self.front.vertices_in(mid - r, mid + r, self.pts.len(), &mut self.verts);
        let mut wide: Vec<(f64, u32)> = self.verts.iter().filter(|&&v| v != a && v != b).map(|&v| (shape(pa, pb, self.pts[v as usize]), v)).filter(|x| x.0 > 0.0).collect();
        wide.sort_by(|x, y| y.0.total_cmp(&x.0).then(x.1.cmp(&y.1)));
        for &(_, c) in &wide {
            let pc = self.pts[c as usize];
            if orient2d(pa, pb, pc) == Sign::Positive && self.fits(e, a, b, c, pc) {
                self.stats.fallbacks += 1;
                self.accept(e, a, b, c, pc);
                return Ok(Outcome::Made);
            }
        }
        Ok(Outcome::Deferred)
    }

    /// Whether a front vertex (other than `a`, `b`) or a front edge (other than `e`) comes
    /// within `d` of `p`.
    fn too_close(&mut self, p: DVec2, d: f64, e: u32, a: u32, b: u32) -> bool {
        let r = DVec2::splat(d);
        self.front.vertices_in(p - r, p + r, self.pts.len(), &mut self.verts);
        if self.verts.iter().any(|&v| v != a && v != b && self.pts[v as usize].distance(p) < d) {
            return true;
        }
        self.front.edges_in(p - r, p + r, self.pts.len(), &mut self.edges);
        self.edges.iter().any(|&f| {
            let [u, v] = self.front.edges[f as usize];
            f != e && point_segment_distance(p, self.pts[u as usize], self.pts[v as usize]) < d
        })
    }

    /// Whether the triangle `a b c` (`c` at `pc`, `NEW` for a new point) may be added on
    /// front edge `e`: positive, and no front edge meets it other than along its own edges
    /// (exact). Since the front bounds the unmeshed region, such a triangle lies inside it.
    fn fits(&mut self, e: u32, a: u32, b: u32, c: u32, pc: DVec2) -> bool {
        let (pa, pb) = (self.pts[a as usize], self.pts[b as usize]);
        if orient2d(pa, pb, pc) != Sign::Positive {
            return false;
        }
        if c != NEW && (self.front.find(a, c).is_some() || self.front.find(c, b).is_some()) {
            return false; // the meshed side of a front edge
        }
        let tri = [pa, pb, pc];
        let ids = [a, b, c];
        let (lo, hi) = (pa.min(pb).min(pc), pa.max(pb).max(pc));
        self.front.edges_in(lo, hi, self.pts.len(), &mut self.edges);
        for &f in &self.edges {
            if f == e {
                continue;
            }
            let [u, v] = self.front.edges[f as usize];
            let (pu, pv) = (self.pts[u as usize], self.pts[v as usize]);
            let at = |x: u32| ids.iter().position(|&i| i == x);
            match (at(u), at(v)) {
                (Some(_), Some(_)) => {}
                (None, None) => {
                    if in_closed(pa, pb, pc, pu) || (0..3).any(|k| segments_intersect(pu, pv, tri[k], tri[(k + 1) % 3])) {
                        return false;
                    }
                }
                (Some(k), None) | (None, Some(k)) => {
                    // shares the corner k: it meets the triangle elsewhere only through its
                    // other end or across the opposite edge
                    let o = if at(u).is_some() { pv } else { pu };
                    if in_closed(pa, pb, pc, o) || segments_intersect(pu, pv, tri[(k + 1) % 3], tri[(k + 2) % 3]) {
                        return false;
                    }
                }
            }
        }
        true
    }

    /// The Delaunay check: no front vertex on the left of `ab` strictly inside the
    /// circumcircle of `abc` (exact); a circle wider than `4 reach` fails it.
    fn delaunay_ok(&mut self, a: u32, b: u32, c: u32, pc: DVec2, reach: f64) -> bool {
        let (pa, pb) = (self.pts[a as usize], self.pts[b as usize]);
        let (u, v) = (pb - pa, pc - pa);
        let d = 2.0 * u.perp_dot(v);
        let centre = pa + DVec2::new(v.y * u.length_squared() - u.y * v.length_squared(), u.x * v.length_squared() - v.x * u.length_squared()) / d;
        let radius = centre.distance(pa);
        if !(radius <= 4.0 * reach) {
            return false;
        }
        let r = DVec2::splat(radius * 1.01);
        self.front.vertices_in(centre - r, centre + r, self.pts.len(), &mut self.verts);
        !self.verts.iter().any(|&w| {
            let pw = self.pts[w as usize];
            w != a && w != b && w != c && orient2d(pa, pb, pw) == Sign::Positive && incircle(pa, pb, pc, pw) == Sign::Positive
        })
    }

    /// Adds the triangle `a b c` on front edge `e` and updates the front: each of its other
    /// two edges closes a front edge running the same way, or opens the reversed one.
    fn accept(&mut self, e: u32, a: u32, b: u32, c: u32, pc: DVec2) {
        let c = if c == NEW {
            self.pts.push(pc);
            self.stats.points += 1;
            self.pts.len() as u32 - 1
        } else {
            c
        };
        self.tris.push([a, b, c]);
        self.front.remove(e);
        for (x, y) in [(b, c), (c, a)] {
            match self.front.find(x, y) {
                Some(f) => self.front.remove(f),
                None => {
                    self.front.add(y, x, &self.pts);
                }
            }
        }
    }
}
