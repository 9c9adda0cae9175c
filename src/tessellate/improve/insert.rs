//! The face's points grow where its triangles are bad: the longest side of a needle split,
//! circumcentres inserted with flips around them, each kept only when the smallest angle of
//! the triangles it changed grows.

use super::{FLIP_GAIN, FLIP_SWEEPS, GOOD_DEG, Point, SPLIT_RATIO, Undo, Work};
use crate::core::cdt;
use crate::core::ids::NONE;
use crate::core::predicates::{Sign, orient2d};
use glam::DVec2;

impl Work<'_> {
    /// Splits the longest side of each bad triangle (smallest angle under [`GOOD_DEG`]) at its
    /// `(u, v)` midpoint lifted onto the surface, when that side is interior, more than
    /// [`SPLIT_RATIO`] times the triangle's shortest and the smallest angle of the two
    /// triangles grows: a fan of needles from a short boundary segment to a far corner (a
    /// short CAD edge beside a wide face, which the domain refinement may not split) becomes
    /// graded toward the segment, as longest-edge bisection grades it; flips then mend.
    pub(super) fn split_pass(&mut self) -> usize {
        self.bad_triangle_pass(|w, t, tri| {
            let p = w.p3(tri);
            let len = [0, 1, 2].map(|i| p[i].distance(p[(i + 1) % 3]));
            let i = (0..3).fold(0, |b, k| if len[k] > len[b] { k } else { b });
            let shortest = len.iter().copied().fold(f64::INFINITY, f64::min);
            len[i] > SPLIT_RATIO * shortest && w.try_split(t, tri[i], tri[(i + 1) % 3], tri[(i + 2) % 3])
        })
    }

    /// Calls `add` on each live, real, active triangle under [`GOOD_DEG`] while the budget of
    /// added points lasts; `add` says whether it added one. Returns how many were added.
    fn bad_triangle_pass(&mut self, add: impl Fn(&mut Self, u32, [u32; 3]) -> bool) -> usize {
        let mut done = 0;
        let good = -GOOD_DEG.to_radians().cos();
        for t in 0..self.tris.len() as u32 {
            if self.split_budget == 0 {
                break;
            }
            let tri = self.tris[t as usize];
            if tri == [NONE; 3] || !self.real(tri) || !tri.iter().any(|&v| self.active[v as usize]) || self.angle(tri) >= good {
                continue;
            }
            if add(self, t, tri) {
                self.split_budget -= 1;
                done += 1;
            }
        }
        done
    }

    /// Splits edge `x y` of triangle `t = (x, y, c)` and of the triangle across it,
    /// `(y, x, d)`, at its `(u, v)` midpoint, if every check passes and the smaller angle of
    /// the two grows.
    fn try_split(&mut self, t: u32, x: u32, y: u32, c: u32) -> bool {
        let Some((u, ut, d)) = self.across(t, x, y) else { return false };
        let uv = 0.5 * (self.pts[x as usize].uv + self.pts[y as usize].uv);
        let s = DVec2::new(cdt::flush(uv.x * self.su), cdt::flush(uv.y * self.sv));
        let p3 = self.surf.point(uv.x, uv.y);
        if !(s.is_finite() && p3.is_finite()) {
            return false;
        }
        let m = self.pts.len() as u32;
        self.pts.push(Point { s, uv, p3, id: None });
        self.key.push((1 << 32) + u64::from(m));
        let new = [[x, m, c], [m, y, c], [y, m, d], [m, x, d]];
        let old = self.angle(self.tris[t as usize]).min(self.angle(ut));
        let worst = new.iter().map(|&n| self.angle(n)).fold(f64::INFINITY, f64::min);
        if worst <= old + FLIP_GAIN || !new.iter().all(|&n| self.acceptable(n)) {
            self.pts.pop();
            self.key.pop();
            return false;
        }
        self.shared.push(false);
        self.removed.push(false);
        self.active.push(true);
        self.dirty.push(true);
        let (n1, n2) = (self.tris.len() as u32, self.tris.len() as u32 + 1);
        self.tris[t as usize] = new[0];
        self.tris[u as usize] = new[2];
        self.tris.push(new[1]);
        self.tris.push(new[3]);
        self.star[x as usize].retain(|&k| k != u);
        self.star[x as usize].push(n2);
        self.star[y as usize].retain(|&k| k != t);
        self.star[y as usize].push(n1);
        self.star[c as usize].push(n1);
        self.star[d as usize].push(n2);
        self.star.push(vec![t, u, n1, n2]);
        self.touch(&[t, u, n1, n2]);
        true
    }

    /// Inserts the circumcentre of each bad triangle (moved inside it where it lies outside: a
    /// needle over a short boundary segment, its apex far from a short CAD edge, has it near
    /// the middle of its long sides), lifted onto the surface, then flips around the new point
    /// while the smallest angle grows (Ruppert's step, restricted to the triangle); kept only when the smallest angle of the
    /// triangles it changed grows, else undone. Each round halves such a needle.
    pub(super) fn insert_pass(&mut self) -> usize {
        self.bad_triangle_pass(|w, t, tri| w.try_insert(t, tri))
    }

    fn try_insert(&mut self, t: u32, tri: [u32; 3]) -> bool {
        let p = self.p3(tri);
        let (a, b) = (p[1] - p[0], p[2] - p[0]);
        let n = a.cross(b);
        let nn = n.length_squared();
        if !(nn > 0.0) {
            return false;
        }
        // the circumcentre in the triangle's plane, and its barycentric coordinates
        let cc = p[0] + (b.length_squared() * n.cross(a) + a.length_squared() * b.cross(n)) / (2.0 * nn);
        let w1 = (cc - p[0]).cross(b).dot(n) / nn;
        let w2 = a.cross(cc - p[0]).dot(n) / nn;
        // (a right or slightly obtuse needle has it just outside its long side: moved inside)
        let w = [1.0 - w1 - w2, w1, w2].map(|x| x.max(0.05));
        if !w.iter().all(|x| x.is_finite()) {
            return false;
        }
        let sum: f64 = w.iter().sum();
        let w = w.map(|x| x / sum);
        let uvs = tri.map(|i| self.pts[i as usize].uv);
        let uv = w[0] * uvs[0] + w[1] * uvs[1] + w[2] * uvs[2];
        let s = DVec2::new(cdt::flush(uv.x * self.su), cdt::flush(uv.y * self.sv));
        let p3 = self.surf.point(uv.x, uv.y);
        if !(s.is_finite() && p3.is_finite()) {
            return false;
        }
        let m = self.pts.len() as u32;
        let old_min = self.angle(tri);
        let parts = [[tri[0], tri[1], m], [tri[1], tri[2], m], [tri[2], tri[0], m]];
        self.pts.push(Point { s, uv, p3, id: None });
        self.key.push((1 << 32) + u64::from(m));
        // (a part may be thin before the flips, its normal meaningless: the checks that count
        // are on what the flips leave)
        if !parts.iter().all(|&q| {
            let s = q.map(|i| self.pts[i as usize].s);
            orient2d(s[0], s[1], s[2]) == Sign::Positive
        }) {
            self.pts.pop();
            self.key.pop();
            return false;
        }
        self.shared.push(false);
        self.removed.push(false);
        self.active.push(true);
        self.dirty.push(true);
        let first = self.tris.len() as u32;
        self.undo = Some(Undo::default());
        for v in tri {
            self.save_star(v);
        }
        self.save_tri(t);
        self.tris[t as usize] = parts[0];
        self.tris.push(parts[1]);
        self.tris.push(parts[2]);
        self.star[tri[0] as usize].push(first + 1);
        self.star[tri[1] as usize].push(first);
        self.star[tri[2] as usize].retain(|&k| k != t);
        self.star[tri[2] as usize].extend([first, first + 1]);
        self.star.push(vec![t, first, first + 1]);
        // flips of the edges opposite the new point, while they pay
        for _ in 0..4 * FLIP_SWEEPS {
            let mut flipped = false;
            for k in self.star[m as usize].clone() {
                let q = self.tris[k as usize];
                let Some(i) = q.iter().position(|&v| v == m) else { continue };
                if self.try_flip(k, q[(i + 1) % 3], q[(i + 2) % 3], m) {
                    flipped = true;
                }
            }
            if !flipped {
                break;
            }
        }
        let undo = self.undo.take().unwrap_or_default();
        let mut slots: Vec<u32> = undo.tris.iter().map(|&(k, _)| k).chain([first, first + 1]).collect();
        slots.sort_unstable();
        slots.dedup();
        // what the changed triangles were before this insertion: the first saved state of each
        // slot that existed (later saves hold states made within the insertion)
        let mut before = old_min;
        let mut seen: Vec<u32> = Vec::new();
        for &(k, old) in &undo.tris {
            if k < first && !seen.contains(&k) {
                seen.push(k);
                before = before.min(self.angle(old));
            }
        }
        let after = slots.iter().map(|&k| self.angle(self.tris[k as usize])).fold(f64::INFINITY, f64::min);
        if after > before + FLIP_GAIN && slots.iter().all(|&k| self.acceptable(self.tris[k as usize])) {
            self.touch(&slots);
            return true;
        }
        // undo, newest first
        for (k, old) in undo.tris.into_iter().rev() {
            self.tris[k as usize] = old;
        }
        for (v, old) in undo.stars.into_iter().rev() {
            self.star[v as usize] = old;
        }
        self.tris.truncate(first as usize);
        self.star.pop();
        self.pts.pop();
        self.key.pop();
        self.shared.pop();
        self.removed.pop();
        self.active.pop();
        self.dirty.pop();
        false
    }
}
