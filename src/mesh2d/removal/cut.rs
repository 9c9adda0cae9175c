//! Stage 2 of element removal: the cuts (Sadek). The front node of smallest interior angle
//! is removed, again and again, until no loop is left.
//!
//! - Inputs: the [`Front`] of the domain, the size `h(p)`, the [`Options`].
//! - Output: the front's triangles (every loop consumed) and the [`Stats`] counts.
//! - The rule at a node `v` with neighbours `a`, `b` and angle `α`:
//!   1. `α < ear_angle` (90°), or `v` closes a loop of three: cut the ear `(a, v, b)`, unless
//!      `|ab|` exceeds `long_ear` times the size there (then as 2.);
//!   2. `α < 180°`: a new point `x` on the bisector at the size's distance (kept within
//!      0.6..1.6 times the mean length of `v`'s edges so the two triangles stay well shaped),
//!      and the two triangles `(a, v, x)`, `(v, b, x)`; where `x` falls near a front vertex
//!      `q` (or near a front edge ending at `q`), `q` is taken instead: the front splits in
//!      two, or two loops (a hole's and the outer one) merge;
//!   3. else (or where the cuts above are blocked): the diagonal from `v` to the nearest
//!      visible front vertex, splitting or merging loops.
//!   Every cut is checked exactly: its triangles positive, no front vertex in them, no
//!   front edge crossing their new edges, the diagonal inside both nodes' angles.
//! - Nodes at or above `pair_angle` wait behind the others; a node whose cuts are all
//!   blocked waits behind the nodes blocked fewer times. Ties go to the lower node id.
//! - Termination: a bound on steps proportional to the expected element count, and a
//!   bound on consecutive blocked nodes; either ends in [`Error::Stalled`] naming where.

use super::front::Front;
use super::{Error, Options, Stats};
use crate::core::predicates::orient2d;
use crate::core::Sign;
use crate::mesh2d::boundary::check_size;
use glam::DVec2;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// A heap entry: blocked count, deferred, angle bits, node.
type Key = Reverse<(u32, bool, u64, u32)>;

struct Cutter<'a> {
    front: Front,
    size: &'a dyn Fn(DVec2) -> f64,
    options: &'a Options,
    heap: BinaryHeap<Key>,
    /// Per node: its current key (an entry that differs is stale).
    key: Vec<(u32, bool, u64)>,
    stats: Stats,
    scratch: Vec<u32>,
}

/// Removes elements until the front is empty; `limit` bounds the steps.
pub(crate) fn remove(front: Front, size: &dyn Fn(DVec2) -> f64, options: &Options, limit: usize) -> Result<(Front, Stats), Error> {
    let mut c = Cutter { front, size, options, heap: BinaryHeap::new(), key: Vec::new(), stats: Stats::default(), scratch: Vec::new() };
    for k in 0..c.front.nodes.len() as u32 {
        c.push(k, 0);
    }
    let mut blocked_run = 0usize;
    while let Some(Reverse((fails, deferred, bits, k))) = c.heap.pop() {
        let node = c.front.nodes[k as usize];
        if !node.alive || c.key[k as usize] != (fails, deferred, bits) {
            continue;
        }
        c.stats.steps += 1;
        if c.stats.steps > limit {
            let p = c.front.pos(k);
            return Err(Error::Stalled { x: p.x, y: p.y, left: c.alive(), steps: c.stats.steps, why: "step limit".into() });
        }
        if c.step(k)? {
            blocked_run = 0;
        } else {
            blocked_run += 1;
            if blocked_run > 2 * c.alive() + 16 {
                let p = c.front.pos(k);
                return Err(Error::Stalled { x: p.x, y: p.y, left: c.alive(), steps: c.stats.steps, why: "every front vertex is blocked".into() });
            }
            c.push(k, fails + 1);
        }
    }
    Ok((c.front, c.stats))
}

impl Cutter<'_> {
    fn alive(&self) -> usize {
        self.front.live
    }

    fn push(&mut self, k: u32, fails: u32) {
        if !self.front.nodes[k as usize].alive {
            return;
        }
        let a = self.front.angle(k);
        let key = (fails, a >= self.options.pair_angle, a.to_bits());
        if self.key.len() < self.front.nodes.len() {
            self.key.resize(self.front.nodes.len(), (0, false, 0));
        }
        self.key[k as usize] = key;
        self.heap.push(Reverse((key.0, key.1, key.2, k)));
    }

    fn size(&self, p: DVec2) -> Result<f64, Error> {
        Ok(check_size(p, (self.size)(p))?)
    }

    /// One step at node `k`: whether a cut was made.
    fn step(&mut self, k: u32) -> Result<bool, Error> {
        let (a, b) = self.front.around(k);
        let (pa, pv, pb) = (self.front.pos(a), self.front.pos(k), self.front.pos(b));
        let alpha = self.front.angle(k);
        let convex = orient2d(pa, pv, pb) == Sign::Positive;
        let triangle = self.front.on_triangle(k);
        let h = self.size(pv)?;
        let mut ear_tried = false;
        if convex && (triangle || alpha < self.options.ear_angle) {
            let hm = self.size(0.5 * (pa + pb))?;
            if triangle || pa.distance(pb) <= self.options.long_ear * hm {
                ear_tried = true;
                if self.try_ear(k) {
                    return Ok(true);
                }
            }
        }
        if triangle {
            return Ok(self.try_diagonal(k, pv.distance(pa).max(pv.distance(pb))));
        }
        // the new point on the bisector
        let mean = 0.5 * (pv.distance(pa) + pv.distance(pb));
        let d = h.clamp(0.6 * mean, 1.6 * mean);
        let dir = DVec2::from_angle(0.5 * alpha.to_radians()).rotate((pb - pv).normalize());
        let x = pv + d * dir;
        let skip = [self.front.vert(a), self.front.vert(k), self.front.vert(b)];
        let near = self.front.near(x, 1.2 * d, 0.5 * d, skip);
        let mut joins = 0;
        for &(dist, q) in &near {
            if dist >= 0.6 * d || joins == 4 {
                break;
            }
            joins += 1;
            if self.try_join(k, q) {
                return Ok(true);
            }
        }
        if convex && alpha < 180.0 && x.is_finite() && self.try_point(k, x) {
            return Ok(true);
        }
        if convex && !ear_tried && self.try_ear(k) {
            return Ok(true);
        }
        for &(_, q) in near.iter().skip(joins).take(8) {
            if self.try_join(k, q) {
                return Ok(true);
            }
        }
        Ok(self.try_diagonal(k, 1.5 * d.max(mean)))
    }

    /// Whether the triangle (three vertex ids) is positive and holds no other front vertex.
    fn clear(&mut self, t: [u32; 3]) -> bool {
        let p = t.map(|v| self.front.points[v as usize]);
        if orient2d(p[0], p[1], p[2]) != Sign::Positive {
            return false;
        }
        self.scratch.clear();
        let mut s = std::mem::take(&mut self.scratch);
        self.front.vertices_in(t, &mut s);
        let empty = s.is_empty();
        self.scratch = s;
        empty
    }

    fn try_ear(&mut self, k: u32) -> bool {
        let (a, b) = self.front.around(k);
        let (va, vk, vb) = (self.front.vert(a), self.front.vert(k), self.front.vert(b));
        if !self.clear([va, vk, vb]) || self.front.segment_blocked(va, vb) {
            return false;
        }
        let (p, n) = self.front.cut_ear(k);
        self.stats.ears += 1;
        self.push(p, 0);
        self.push(n, 0);
        true
    }

    fn try_point(&mut self, k: u32, x: DVec2) -> bool {
        let (a, b) = self.front.around(k);
        let (va, vk, vb) = (self.front.vert(a), self.front.vert(k), self.front.vert(b));
        let vx = self.front.add_point(x);
        let ok = self.clear([va, vk, vx]) && self.clear([vk, vb, vx]) && !self.front.segment_blocked(va, vx) && !self.front.segment_blocked(vb, vx) && !self.front.segment_blocked(vk, vx);
        if !ok {
            self.front.points.pop();
            return false;
        }
        let m = self.front.replace(k, vx);
        self.stats.pairs += 1;
        self.stats.points += 1;
        self.push(a, 0);
        self.push(m, 0);
        self.push(b, 0);
        true
    }

    /// Joins node `k` to the front node `q` with the two triangles `(a, k, q)`, `(k, b, q)`.
    fn try_join(&mut self, k: u32, q: u32) -> bool {
        let (a, b) = self.front.around(k);
        if q == a || q == b || !self.front.nodes[q as usize].alive {
            return false;
        }
        let (va, vk, vb, vq) = (self.front.vert(a), self.front.vert(k), self.front.vert(b), self.front.vert(q));
        if [va, vk, vb].contains(&vq) || !self.front.in_sector(q, self.front.pos(k)) {
            return false;
        }
        let ok = self.clear([va, vk, vq]) && self.clear([vk, vb, vq]) && !self.front.segment_blocked(va, vq) && !self.front.segment_blocked(vb, vq) && !self.front.segment_blocked(vk, vq);
        if !ok {
            return false;
        }
        let (k2, q2) = self.front.split(k, q);
        // k: a -> k -> q; k2: q2 -> k2 -> b
        let (p1, n1) = self.front.cut_ear(k);
        let (p2, n2) = self.front.cut_ear(k2);
        self.stats.joins += 1;
        self.stats.splits += 1;
        for n in [p1, n1, p2, n2, q, q2] {
            self.push(n, 0);
        }
        true
    }

    /// The diagonal from `k` to the nearest front vertex within `r` that both see inside
    /// their angles, the segment crossing no front edge.
    fn try_diagonal(&mut self, k: u32, r: f64) -> bool {
        let (a, b) = self.front.around(k);
        let pv = self.front.pos(k);
        let skip = [self.front.vert(a), self.front.vert(k), self.front.vert(b)];
        let near = self.front.near(pv, r, 0.0, skip);
        for &(_, q) in near.iter().take(16) {
            let (vk, vq) = (self.front.vert(k), self.front.vert(q));
            if !self.front.in_sector(k, self.front.pos(q)) || !self.front.in_sector(q, pv) || self.front.segment_blocked(vk, vq) {
                continue;
            }
            let (k2, q2) = self.front.split(k, q);
            self.stats.splits += 1;
            for n in [k, k2, q, q2] {
                self.push(n, 0);
            }
            return true;
        }
        false
    }
}
