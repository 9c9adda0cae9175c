//! Ruppert's Delaunay refinement as Shewchuk's Triangle does it: encroached subsegments
//! split first, then bad triangles (smallest angle under the bound, or too large) split at
//! their off-center (Üngör) or circumcenter, shortest edge first.
//!
//! - Stage: after the initial triangulation ([`super::initial`]).
//! - Inputs: the [`Tri`] of the domain, the [`Criteria`].
//! - Output: the refined [`Tri`] and the counts of what was inserted or refused.
//! - Rules:
//!   - a subsegment is encroached when a vertex sees it under an angle of at least
//!     `180° - 2θ` (the diametral lens, Triangle's default); a free point that would encroach
//!     a subsegment is not inserted, the subsegment is split instead (when segments may be
//!     split), and the triangle tried again;
//!   - a subsegment whose inside triangle spans the whole angle between it and another
//!     segment is split on the concentric shells (distance a power of two from that end),
//!     any other in its middle (then moved onto the segment's line by one Newton step);
//!   - Miller, Pav and Walkington's rule (Triangle's form): a triangle bad by its angle only
//!     is not split when its shortest edge joins two Steiner points on two segments that
//!     share an end, at the same distance from it (they lie on one shell across a small
//!     input angle);
//!   - a point whose walk from the bad triangle meets a segment splits that subsegment (or,
//!     with segments protected, leaves the triangle as it is);
//!   - the queue: 4096 buckets by the squared shortest edge (half powers of two), shortest
//!     first, first in first out within a bucket; everything deterministic.

use super::insert::{encroaches, insert, Kind, Outcome, Scratch};
use super::tri::{next, prev, Located, Tri, NONE};
use glam::DVec2;
use rustc_hash::FxHashSet;
use std::collections::VecDeque;

/// What makes a triangle bad, and what may be split.
pub(crate) struct Criteria<'a> {
    /// `cos²` of the smallest angle allowed (1: no angle bound).
    pub cos2: f64,
    /// The diametral lens, `cos²(2θ)`.
    pub lens: f64,
    /// Üngör's off-center constant (0: circumcenters only).
    pub offconstant: f64,
    /// Largest area allowed (infinite: none).
    pub max_area: f64,
    /// The size field and the factor on it: too large when the circumradius exceeds
    /// `factor · h(centroid)`.
    pub size: Option<(&'a dyn Fn(DVec2) -> f64, f64)>,
    /// Whether subsegments may be split.
    pub split_segments: bool,
    /// Stop (with an error) past this many vertices.
    pub max_vertices: usize,
    /// The domain's segments (for the segment a Steiner point lies on).
    pub segments: &'a [[u32; 2]],
}

/// Why the refinement stopped early.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Stop {
    /// The size field gave a bad value at this point.
    Size(DVec2, f64),
    /// Too many vertices.
    TooMany(usize),
}

/// Counts of the refinement.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Counts {
    /// Steiner points inside.
    pub interior: usize,
    /// Steiner points on segments.
    pub on_segments: usize,
    /// Bad triangles left as they are (protected boundary, walk or cavity refused).
    pub refused: usize,
    /// Subsegment splits refused (cavity refused).
    pub refused_splits: usize,
}

/// 4096 first-in-first-out buckets by the squared shortest edge.
struct BadQueue {
    buckets: Vec<VecDeque<(u32, [u32; 3], f64)>>,
    lowest: usize,
    len: usize,
}

impl BadQueue {
    fn new() -> BadQueue {
        BadQueue { buckets: (0..4096).map(|_| VecDeque::new()).collect(), lowest: 4096, len: 0 }
    }

    fn bucket(key: f64) -> usize {
        let bits = key.to_bits();
        let exp = ((bits >> 52) & 0x7ff) as i64 - 1023;
        let mantissa = f64::from_bits((bits & ((1u64 << 52) - 1)) | (1023u64 << 52));
        let half = i64::from(mantissa > std::f64::consts::SQRT_2);
        (2 * exp + half + 2048).clamp(0, 4095) as usize
    }

    fn push(&mut self, t: u32, v: [u32; 3], key: f64) {
        let b = BadQueue::bucket(key);
        self.buckets[b].push_back((t, v, key));
        self.lowest = self.lowest.min(b);
        self.len += 1;
    }

    fn pop(&mut self) -> Option<(u32, [u32; 3], f64)> {
        if self.len == 0 {
            return None;
        }
        while self.buckets[self.lowest].is_empty() {
            self.lowest += 1;
        }
        self.len -= 1;
        self.buckets[self.lowest].pop_front()
    }
}

/// The refinement's state.
pub(crate) struct Refiner<'a> {
    /// The triangulation.
    pub tri: Tri,
    crit: Criteria<'a>,
    sc: Scratch,
    bad: BadQueue,
    enc: VecDeque<(u32, u32)>,
    failed: FxHashSet<(u32, u32)>,
    /// What was done.
    pub counts: Counts,
    stop: Option<Stop>,
    /// The domain's segments `(from, to)` sorted, with their index.
    seg_lookup: Vec<((u32, u32), u32)>,
}

impl<'a> Refiner<'a> {
    /// A refiner of `tri` under `crit`.
    pub fn new(tri: Tri, crit: Criteria<'a>) -> Refiner<'a> {
        let mut seg_lookup: Vec<((u32, u32), u32)> = crit.segments.iter().enumerate().map(|(k, s)| ((s[0], s[1]), k as u32)).collect();
        seg_lookup.sort_unstable();
        Refiner { tri, crit, sc: Scratch::default(), bad: BadQueue::new(), enc: VecDeque::new(), failed: FxHashSet::default(), counts: Counts::default(), stop: None, seg_lookup }
    }

    /// Runs the refinement to the end (see the module docs).
    pub fn run(&mut self) -> Result<(), Stop> {
        for t in 0..self.tri.tv.len() as u32 {
            for i in 0..3 {
                if self.tri.constrained(t, i) {
                    let c = self.tri.pts[self.tri.tv[t as usize][i] as usize];
                    let (a, b) = self.tri.edge(t, i);
                    if encroaches(self.tri.pts[a as usize], self.tri.pts[b as usize], c, self.crit.lens) {
                        self.enc.push_back((a, b));
                    }
                }
            }
        }
        self.split_encroached();
        for t in 0..self.tri.tv.len() as u32 {
            self.test(t);
        }
        while let Some((t, v, key)) = self.bad.pop() {
            if let Some(s) = self.stop.take() {
                return Err(s);
            }
            if self.tri.tv[t as usize] != v {
                continue;
            }
            self.split_triangle(t);
            if !self.enc.is_empty() {
                // tried again only when splitting the subsegments inserted something
                let before = self.tri.pts.len();
                self.split_encroached();
                if self.tri.pts.len() > before {
                    self.bad.push(t, v, key);
                } else {
                    self.counts.refused += 1;
                }
            }
        }
        match self.stop.take() {
            Some(s) => Err(s),
            None => Ok(()),
        }
    }

    /// Tests triangle `t` and queues it when bad.
    fn test(&mut self, t: u32) {
        let v = self.tri.tv[t as usize];
        let [a, b, c] = self.tri.corners(t);
        // edge i is opposite corner i
        let l = [(b - c).length_squared(), (c - a).length_squared(), (a - b).length_squared()];
        let k = if l[0] < l[1] && l[0] < l[2] { 0 } else if l[1] < l[2] { 1 } else { 2 };
        let minedge = l[k];
        let twice_area = (b - a).perp_dot(c - a);
        let mut big = 0.5 * twice_area > self.crit.max_area;
        if !big {
            if let Some((h, factor)) = self.crit.size {
                let g = (a + b + c) / 3.0;
                let size = h(g);
                if !(size.is_finite() && size > 0.0) {
                    self.stop = Some(Stop::Size(g, size));
                    return;
                }
                let r2 = l[0] * l[1] * l[2] / (4.0 * twice_area * twice_area);
                big = r2 > factor * factor * size * size;
            }
        }
        if big {
            self.bad.push(t, v, minedge);
            return;
        }
        // the smallest angle is at corner k, between its two edges
        let q = self.tri.corners(t);
        let (u, w) = (q[next(k)] - q[k], q[prev(k)] - q[k]);
        let dot = u.dot(w);
        let cos2 = dot * dot / (l[next(k)] * l[prev(k)]);
        if dot > 0.0 && cos2 > self.crit.cos2 && !self.shell_pair(v[next(k)], v[prev(k)]) {
            self.bad.push(t, v, minedge);
        }
    }

    /// Miller, Pav and Walkington's exception (Triangle's form): `p` and `q` are Steiner
    /// points on two segments sharing an end, at the same distance from it.
    fn shell_pair(&self, p: u32, q: u32) -> bool {
        let (sp, sq) = (self.tri.on_seg[p as usize], self.tri.on_seg[q as usize]);
        if sp == NONE || sq == NONE || sp == sq {
            return false;
        }
        let (a, b) = (self.crit.segments[sp as usize], self.crit.segments[sq as usize]);
        let joint = if a[1] == b[0] || a[1] == b[1] {
            a[1]
        } else if a[0] == b[0] || a[0] == b[1] {
            a[0]
        } else {
            return false;
        };
        let j = self.tri.pts[joint as usize];
        let d1 = (self.tri.pts[p as usize] - j).length_squared();
        let d2 = (self.tri.pts[q as usize] - j).length_squared();
        d1 < 1.001 * d2 && d1 > 0.999 * d2
    }

    /// Tests the triangles the last insertion created; with `segments`, queues their
    /// encroached subsegments too.
    fn after_insertion(&mut self, segments: bool) {
        if self.tri.pts.len() > self.crit.max_vertices {
            self.stop = Some(Stop::TooMany(self.crit.max_vertices));
        }
        for k in 0..self.sc.created.len() {
            let t = self.sc.created[k];
            if segments {
                for i in 0..3 {
                    if self.tri.constrained(t, i) {
                        let c = self.tri.pts[self.tri.tv[t as usize][i] as usize];
                        let (a, b) = self.tri.edge(t, i);
                        if encroaches(self.tri.pts[a as usize], self.tri.pts[b as usize], c, self.crit.lens) {
                            self.enc.push_back((a, b));
                        }
                    }
                }
            }
            self.test(t);
        }
    }

    /// Tries to split bad triangle `t` (see the module docs).
    fn split_triangle(&mut self, t: u32) {
        let c = self.center(t);
        if !c.is_finite() {
            self.counts.refused += 1;
            return;
        }
        match self.tri.locate(t, c) {
            Located::Inside(s) => {
                let lens = if self.crit.split_segments { Some(self.crit.lens) } else { None };
                match insert(&mut self.tri, &mut self.sc, c, s, Kind::Free(lens)) {
                    Outcome::Inserted(_) => {
                        self.counts.interior += 1;
                        self.after_insertion(false);
                    }
                    Outcome::Encroaches => {
                        let before = self.enc.len();
                        for &e in &self.sc.encroached {
                            if !self.failed.contains(&e) {
                                self.enc.push_back(e);
                            }
                        }
                        if self.enc.len() == before {
                            self.counts.refused += 1;
                        }
                    }
                    Outcome::Refused => self.counts.refused += 1,
                }
            }
            Located::Blocked(s, i) => {
                let e = self.tri.edge(s, i as usize);
                if self.crit.split_segments && !self.failed.contains(&e) {
                    self.enc.push_back(e);
                } else {
                    self.counts.refused += 1;
                }
            }
            Located::Vertex | Located::Lost => self.counts.refused += 1,
        }
    }

    /// The point that splits `t`: Üngör's off-center where it is nearer than the
    /// circumcenter (Triangle's construction, relative to the shortest edge).
    fn center(&self, t: u32) -> DVec2 {
        let [o, d, a] = self.tri.corners(t);
        let (xdo, ydo) = (d.x - o.x, d.y - o.y);
        let (xao, yao) = (a.x - o.x, a.y - o.y);
        let dodist = xdo * xdo + ydo * ydo;
        let aodist = xao * xao + yao * yao;
        let dadist = (d - a).length_squared();
        let det = robust::orient2d(robust::Coord { x: d.x, y: d.y }, robust::Coord { x: a.x, y: a.y }, robust::Coord { x: o.x, y: o.y });
        let denominator = 0.5 / det;
        let mut dx = (yao * dodist - ydo * aodist) * denominator;
        let mut dy = (xdo * aodist - xao * dodist) * denominator;
        let off = self.crit.offconstant;
        if off > 0.0 {
            if dodist < aodist && dodist < dadist {
                let (ox, oy) = (0.5 * xdo - off * ydo, 0.5 * ydo + off * xdo);
                if ox * ox + oy * oy < dx * dx + dy * dy {
                    (dx, dy) = (ox, oy);
                }
            } else if aodist < dadist {
                let (ox, oy) = (0.5 * xao + off * yao, 0.5 * yao - off * xao);
                if ox * ox + oy * oy < dx * dx + dy * dy {
                    (dx, dy) = (ox, oy);
                }
            } else {
                let (ox, oy) = (0.5 * (a.x - d.x) - off * (a.y - d.y), 0.5 * (a.y - d.y) + off * (a.x - d.x));
                if ox * ox + oy * oy < (dx - xdo) * (dx - xdo) + (dy - ydo) * (dy - ydo) {
                    (dx, dy) = (xdo + ox, ydo + oy);
                }
            }
        }
        DVec2::new(o.x + dx, o.y + dy)
    }

    /// Splits the queued subsegments that still exist (see the module docs).
    fn split_encroached(&mut self) {
        while let Some((a, b)) = self.enc.pop_front() {
            if self.stop.is_some() {
                return;
            }
            let Some((t, i)) = self.tri.find_edge(a, b) else { continue };
            if !self.tri.constrained(t, i) || !self.crit.split_segments || self.failed.contains(&(a, b)) {
                continue;
            }
            let (pa, pb) = (self.tri.pts[a as usize], self.tri.pts[b as usize]);
            let acute_org = self.tri.constrained(t, prev(i));
            let acute_dest = self.tri.constrained(t, next(i));
            let split = if acute_org || acute_dest {
                let length = pa.distance(pb);
                let mut power = 1.0f64;
                while length > 3.0 * power {
                    power *= 2.0;
                }
                while length < 1.5 * power {
                    power *= 0.5;
                }
                let s = power / length;
                if acute_dest { 1.0 - s } else { s }
            } else {
                0.5
            };
            let mut p = pa + split * (pb - pa);
            // one Newton step onto the segment's line (Triangle's step, on the whole segment)
            let seg = self.segment_of(a, b);
            let (la, lb) = match self.crit.segments.get(seg as usize) {
                Some(&[u, v]) => (self.tri.pts[u as usize], self.tri.pts[v as usize]),
                None => (pa, pb),
            };
            let det = robust::orient2d(robust::Coord { x: la.x, y: la.y }, robust::Coord { x: lb.x, y: lb.y }, robust::Coord { x: p.x, y: p.y });
            let len2 = (lb - la).length_squared();
            if det != 0.0 && len2 > 0.0 {
                let m = det / len2;
                if m.is_finite() {
                    p += m * DVec2::new(lb.y - la.y, la.x - lb.x);
                }
            }
            // strictly between the ends (the cavity check decides the rest exactly)
            if (p - pa).dot(pb - pa) <= 0.0 || (p - pb).dot(pa - pb) <= 0.0 {
                self.failed.insert((a, b));
                self.counts.refused_splits += 1;
                continue;
            }
            match insert(&mut self.tri, &mut self.sc, p, t, Kind::Split(i as u8)) {
                Outcome::Inserted(v) => {
                    self.tri.on_seg[v as usize] = seg;
                    self.counts.on_segments += 1;
                    self.after_insertion(true);
                }
                Outcome::Encroaches | Outcome::Refused => {
                    self.failed.insert((a, b));
                    self.counts.refused_splits += 1;
                }
            }
        }
    }

    /// The domain segment the subsegment `a -> b` is part of.
    fn segment_of(&self, a: u32, b: u32) -> u32 {
        for v in [a, b] {
            if self.tri.on_seg[v as usize] != NONE {
                return self.tri.on_seg[v as usize];
            }
        }
        match self.seg_lookup.binary_search_by(|e| e.0.cmp(&(a, b))) {
            Ok(k) => self.seg_lookup[k].1,
            Err(_) => NONE,
        }
    }
}
