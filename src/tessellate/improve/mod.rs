//! Shape improvement of one face's sized triangulation, judged on the surface.
//!
//! The size refinement ([`super::sizing`]) makes triangles well shaped in the scaled `(u, v)`,
//! which is isometric only where the surface's speeds are near their means: about a sphere's
//! or a cone's pole a whole period of `u` shrinks to a point, and the rows of points the
//! domain refinement leaves there are fans of needles on the surface (a valence of 86 and
//! corners of 2° at occt-sphere's poles at the default size). A volume mesher cannot make
//! good tets on such a boundary. Here, round after round:
//! - an interior point with an edge shorter than [`SHORT`] times the local size merges into
//!   the point at its other end (Botsch and Kobbelt's isotropic remeshing, with edge-collapse
//!   checks as in Hoppe's), when the smallest 3D angle around it does not fall below
//!   [`GOOD_DEG`] or its old value and no edge grows past [`LONG`] times the size;
//! - interior edges flip when the smaller 3D angle of their two triangles grows;
//! - interior points move toward the centroid of their neighbours, projected onto the
//!   surface, when the smallest 3D angle around them grows.
//!
//! Every step keeps what the face shares and what it promises: boundary points and segments
//! do not change (the neighbouring faces hold them); every triangle stays counter-clockwise
//! in the scaled `(u, v)` by exact orientation (the domain stays a triangulation of the same
//! region, for the quadrature); no triangle goes farther than the face's chord from the
//! surface or turns past the angle criterion from its normal ([`super::refine::deviation`]);
//! triangles that collapse to a pole in 3D stay in the domain. Budgets are counts of rounds:
//! the result depends on the input alone.

use super::refine::deviation;
use crate::cad::geom::Surface;
use crate::core::SizeField;
use crate::core::cdt;
use crate::core::ids::NONE;
use crate::core::predicates::{Sign, orient2d};
use glam::{DVec2, DVec3};
use rustc_hash::FxHashSet;

mod insert;

/// A point of the face's domain triangulation.
#[derive(Clone, Copy, Debug)]
pub(super) struct Point {
    /// Position in scaled `(u, v)`, as spade saw it.
    pub(super) s: DVec2,
    /// Position in `(u, v)`.
    pub(super) uv: DVec2,
    /// The point on the surface.
    pub(super) p3: DVec3,
    /// Its global vertex index when it lies on the face's boundary (it is then fixed).
    pub(super) id: Option<u32>,
}

/// Rounds of collapses, flips and moves at most.
const ROUNDS: usize = 8;
/// Sweeps of flips per round at most.
const FLIP_SWEEPS: usize = 4;
/// An interior point merges along an edge shorter than this times the local size.
const SHORT: f64 = 0.6;
/// No merge makes an edge longer than this times the local size.
const LONG: f64 = 1.5;
/// A merge may lower the smallest angle around it down to this (degrees) or its old value.
const GOOD_DEG: f64 = 30.0;
/// A bad triangle's longest side is split when it is more than this times its shortest.
const SPLIT_RATIO: f64 = 2.0;
/// The least gain of a flip in the shape measure ([`shape`]: minus the largest corner cosine).
const FLIP_GAIN: f64 = 1e-9;
/// The least gain of a move in the shape measure: about 0.01° at 30° (smoothing creeps
/// otherwise).
const MOVE_GAIN: f64 = 1e-4;

/// What the caller gets back: which points are still used.
pub(super) struct Improved {
    /// Per point: true when a merge removed it.
    pub(super) removed: Vec<bool>,
}

/// Improves the triangles `tris` (indices into `pts`, counter-clockwise in `s`) in place;
/// `boundary` lists the face's boundary segments (pairs of point indices, either order).
#[allow(clippy::too_many_arguments)]
pub(super) fn improve(pts: &mut Vec<Point>, tris: &mut Vec<[u32; 3]>, boundary: &[[u32; 2]], surf: &Surface, su: f64, sv: f64, size: &dyn SizeField, tol: f64, cos_max: f64) -> Improved {
    let mut w = Work::new(pts, tris, boundary, surf, su, sv, size, tol, cos_max);
    for _ in 0..ROUNDS {
        // only where something changed in the round before
        w.active = std::mem::replace(&mut w.dirty, vec![false; w.pts.len()]);
        let mut changed = w.collapse_pass();
        changed += w.split_pass();
        changed += w.insert_pass();
        for _ in 0..FLIP_SWEEPS {
            let f = w.flip_pass();
            changed += f;
            if f == 0 {
                break;
            }
        }
        changed += w.smooth_pass();
        if changed == 0 {
            break;
        }
    }
    let removed = w.removed;
    tris.retain(|t| *t != [NONE; 3]);
    Improved { removed }
}

struct Work<'a> {
    pts: &'a mut Vec<Point>,
    /// The triangles; a removed one is `[NONE; 3]`.
    tris: &'a mut Vec<[u32; 3]>,
    /// Per point, the live triangles that use it.
    star: Vec<Vec<u32>>,
    /// Boundary segments, smaller index first.
    boundary: FxHashSet<(u32, u32)>,
    /// Per point: the key of its 3D vertex (its global index, or its own for interior points).
    key: Vec<u64>,
    /// Per point: another point has the same key (a pole or a seam point).
    shared: Vec<bool>,
    removed: Vec<bool>,
    /// Per point: worth a look in this round (something near it changed in the last one).
    active: Vec<bool>,
    /// Per point: something near it changed in this round.
    dirty: Vec<bool>,
    /// Points that splits and insertions may still add.
    split_budget: usize,
    /// While an insertion is tried: the old contents of the triangles and stars it changed.
    undo: Option<Undo>,
    surf: &'a Surface,
    su: f64,
    sv: f64,
    size: &'a dyn SizeField,
    /// Sizes already asked for, by the point's bits: the passes ask again at the same edge
    /// midpoints round after round, and a feature-size query walks a tree of samples.
    sizes: std::cell::RefCell<rustc_hash::FxHashMap<[u64; 3], f64>>,
    tol: f64,
    cos_max: f64,
}

/// What an insertion changed, to put back when it does not pay.
#[derive(Default)]
struct Undo {
    tris: Vec<(u32, [u32; 3])>,
    stars: Vec<(u32, Vec<u32>)>,
}

/// The shape of a 3D triangle: minus the largest cosine of its corners, which grows with its
/// smallest angle (−1 when degenerate, −1/2 when equilateral).
fn shape(p: [DVec3; 3]) -> f64 {
    let mut m: f64 = -1.0;
    for i in 0..3 {
        let (a, b) = (p[(i + 1) % 3] - p[i], p[(i + 2) % 3] - p[i]);
        let (la, lb) = (a.length(), b.length());
        if !(la > 0.0 && lb > 0.0) {
            return -1.0;
        }
        m = m.max((a.dot(b) / (la * lb)).clamp(-1.0, 1.0));
    }
    -m
}

impl<'a> Work<'a> {
    #[allow(clippy::too_many_arguments)]
    fn new(pts: &'a mut Vec<Point>, tris: &'a mut Vec<[u32; 3]>, boundary: &[[u32; 2]], surf: &'a Surface, su: f64, sv: f64, size: &'a dyn SizeField, tol: f64, cos_max: f64) -> Work<'a> {
        let n = pts.len();
        let mut star = vec![Vec::new(); n];
        for (k, t) in tris.iter().enumerate() {
            for &i in t {
                star[i as usize].push(k as u32);
            }
        }
        let key: Vec<u64> = pts.iter().enumerate().map(|(i, p)| p.id.map_or((1 << 32) + i as u64, u64::from)).collect();
        let mut sorted: Vec<u64> = key.clone();
        sorted.sort_unstable();
        let twice: FxHashSet<u64> = sorted.windows(2).filter(|w| w[0] == w[1]).map(|w| w[0]).collect();
        let shared = key.iter().map(|k| twice.contains(k)).collect();
        let boundary = boundary.iter().map(|&[a, b]| (a.min(b), a.max(b))).collect();
        Work { pts, tris, star, boundary, key, shared, removed: vec![false; n], active: vec![true; n], dirty: vec![true; n], split_budget: n, undo: None, surf, su, sv, size, sizes: Default::default(), tol, cos_max }
    }

    fn free(&self, i: u32) -> bool {
        self.pts[i as usize].id.is_none()
    }

    /// A triangle with three distinct 3D vertices (not collapsed to a pole).
    fn real(&self, t: [u32; 3]) -> bool {
        let k = t.map(|i| self.key[i as usize]);
        k[0] != k[1] && k[1] != k[2] && k[0] != k[2]
    }

    fn p3(&self, t: [u32; 3]) -> [DVec3; 3] {
        t.map(|i| self.pts[i as usize].p3)
    }

    /// The [`shape`] of `t`; infinite for a collapsed triangle (no shape to judge).
    fn angle(&self, t: [u32; 3]) -> f64 {
        if self.real(t) { shape(self.p3(t)) } else { f64::INFINITY }
    }

    fn size_at(&self, p: DVec3) -> f64 {
        *self.sizes.borrow_mut().entry(p.to_array().map(f64::to_bits)).or_insert_with(|| self.size.size_at(p))
    }

    /// `t` is counter-clockwise in the scaled domain and, when real, within the chord of the
    /// surface and turned from its normal less than the angle criterion.
    fn acceptable(&self, t: [u32; 3]) -> bool {
        let s = t.map(|i| self.pts[i as usize].s);
        if orient2d(s[0], s[1], s[2]) != Sign::Positive {
            return false;
        }
        if !self.real(t) {
            return true;
        }
        let free = [0, 1, 2].map(|i| {
            let (a, b) = (t[i], t[(i + 1) % 3]);
            !self.boundary.contains(&(a.min(b), a.max(b)))
        });
        let uv = t.map(|i| self.pts[i as usize].uv);
        deviation(self.surf, self.p3(t), uv, free, self.cos_max) <= self.tol
    }

    fn save_tri(&mut self, t: u32) {
        if let Some(u) = &mut self.undo {
            u.tris.push((t, self.tris[t as usize]));
        }
    }

    fn save_star(&mut self, v: u32) {
        if let Some(u) = &mut self.undo {
            u.stars.push((v, self.star[v as usize].clone()));
        }
    }

    /// Marks the points of triangles `ts` for the next round.
    fn touch(&mut self, ts: &[u32]) {
        for &t in ts {
            let tri = self.tris[t as usize];
            if tri != [NONE; 3] {
                for i in tri {
                    self.dirty[i as usize] = true;
                }
            }
        }
    }

    /// The distinct neighbours of point `a`, in index order.
    fn neighbours(&self, a: u32) -> Vec<u32> {
        let mut n: Vec<u32> = self.star[a as usize].iter().flat_map(|&t| self.tris[t as usize]).filter(|&i| i != a).collect();
        n.sort_unstable();
        n.dedup();
        n
    }

    /// The real triangle `(y, x, d)` across interior edge `x y` of triangle `t`: its slot,
    /// corners and `d`; `None` across a boundary segment or a collapsed triangle.
    fn across(&self, t: u32, x: u32, y: u32) -> Option<(u32, [u32; 3], u32)> {
        if self.boundary.contains(&(x.min(y), x.max(y))) {
            return None;
        }
        // the triangles on the edge: exactly two, `t` and the other
        let (mut count, mut other) = (0, None);
        for k in self.on_edge(x, y) {
            count += 1;
            if k != t && other.is_none() {
                other = Some(k);
            }
        }
        if count != 2 {
            return None;
        }
        let u = other?;
        let ut = self.tris[u as usize];
        if !self.real(ut) {
            return None;
        }
        let d = *ut.iter().find(|&&i| i != x && i != y)?;
        Some((u, ut, d))
    }

    /// The live triangles with both `a` and `b`.
    fn with_edge(&self, a: u32, b: u32) -> Vec<u32> {
        self.on_edge(a, b).collect()
    }

    /// The triangles of `a`'s star that hold `b` (those on edge `a b`), in star order.
    fn on_edge(&self, a: u32, b: u32) -> impl Iterator<Item = u32> + '_ {
        self.star[a as usize].iter().copied().filter(move |&t| self.tris[t as usize].contains(&b))
    }

    fn collapse_pass(&mut self) -> usize {
        let mut done = 0;
        for a in 0..self.pts.len() as u32 {
            if !self.free(a) || self.removed[a as usize] || !self.active[a as usize] || self.star[a as usize].is_empty() {
                continue;
            }
            let pa = self.pts[a as usize].p3;
            let mut short: Vec<(f64, u32)> = self
                .neighbours(a)
                .into_iter()
                .filter(|&b| !self.shared[b as usize])
                .filter_map(|b| {
                    let pb = self.pts[b as usize].p3;
                    let len = pa.distance(pb);
                    let h = self.size_at(0.5 * (pa + pb));
                    (h > 0.0 && h.is_finite() && len < SHORT * h).then_some((len / h, b))
                })
                .collect();
            short.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
            for (_, b) in short.into_iter().take(3) {
                if self.try_collapse(a, b) {
                    done += 1;
                    break;
                }
            }
        }
        done
    }

    /// Merges interior point `a` into its neighbour `b` if every check passes.
    fn try_collapse(&mut self, a: u32, b: u32) -> bool {
        let both = self.with_edge(a, b);
        if both.len() != 2 {
            return false;
        }
        // the link condition: a and b share exactly the two points opposite their edge
        let opposite: Vec<u32> = both.iter().flat_map(|&t| self.tris[t as usize]).filter(|&i| i != a && i != b).collect();
        let na = self.neighbours(a);
        let nb = self.neighbours(b);
        let common = na.iter().filter(|i| nb.binary_search(i).is_ok()).count();
        if common != 2 || opposite.len() != 2 || opposite[0] == opposite[1] {
            return false;
        }
        let pb = self.pts[b as usize].p3;
        let mut old_min = f64::INFINITY;
        let mut new_min = f64::INFINITY;
        let mut changed = Vec::new();
        for &t in &self.star[a as usize] {
            let tri = self.tris[t as usize];
            old_min = old_min.min(self.angle(tri));
            if both.contains(&t) {
                continue;
            }
            let nt = tri.map(|i| if i == a { b } else { i });
            if self.real(tri) != self.real(nt) {
                return false;
            }
            if self.real(nt) {
                for i in 0..3 {
                    let (x, y) = (self.pts[nt[i] as usize].p3, self.pts[nt[(i + 1) % 3] as usize].p3);
                    if x == pb || y == pb {
                        let h = self.size_at(0.5 * (x + y));
                        if x.distance(y) > LONG * h {
                            return false;
                        }
                    }
                }
                new_min = new_min.min(self.angle(nt));
            }
            changed.push((t, nt));
        }
        for &t in &both {
            old_min = old_min.min(self.angle(self.tris[t as usize]));
        }
        if new_min < old_min.min(-GOOD_DEG.to_radians().cos()) || !changed.iter().all(|&(_, nt)| self.acceptable(nt)) {
            return false;
        }
        for &t in &both {
            let tri = self.tris[t as usize];
            for i in tri {
                self.star[i as usize].retain(|&x| x != t);
            }
            self.tris[t as usize] = [NONE; 3];
        }
        for (t, nt) in changed {
            self.tris[t as usize] = nt;
            self.star[b as usize].push(t);
        }
        self.star[a as usize].clear();
        let around = self.star[b as usize].clone();
        self.touch(&around);
        self.removed[a as usize] = true;
        true
    }

    fn flip_pass(&mut self) -> usize {
        let mut done = 0;
        for t in 0..self.tris.len() as u32 {
            for i in 0..3 {
                let tri = self.tris[t as usize];
                if tri == [NONE; 3] || !self.real(tri) || !tri.iter().any(|&v| self.active[v as usize]) {
                    break;
                }
                if self.try_flip(t, tri[i], tri[(i + 1) % 3], tri[(i + 2) % 3]) {
                    done += 1;
                    break;
                }
            }
        }
        done
    }

    /// Flips edge `x y` of triangle `t = (x, y, c)` with the triangle across it, `(y, x, d)`,
    /// into `(x, d, c)` and `(d, y, c)` if every check passes and the smaller angle grows.
    fn try_flip(&mut self, t: u32, x: u32, y: u32, c: u32) -> bool {
        let Some((u, ut, d)) = self.across(t, x, y) else { return false };
        // no flip onto an edge that is there already
        if self.key[c as usize] == self.key[d as usize] || self.on_edge(c, d).next().is_some() {
            return false;
        }
        let (n1, n2) = ([x, d, c], [d, y, c]);
        if !self.real(n1) || !self.real(n2) {
            return false;
        }
        let old = self.angle(self.tris[t as usize]).min(self.angle(ut));
        let new = self.angle(n1).min(self.angle(n2));
        if new <= old + FLIP_GAIN || !self.acceptable(n1) || !self.acceptable(n2) {
            return false;
        }
        for v in [x, y, c, d] {
            self.save_star(v);
        }
        self.save_tri(t);
        self.save_tri(u);
        self.tris[t as usize] = n1;
        self.tris[u as usize] = n2;
        self.star[x as usize].retain(|&k| k != u);
        self.star[y as usize].retain(|&k| k != t);
        self.star[c as usize].push(u);
        self.star[d as usize].push(t);
        self.touch(&[t, u]);
        true
    }

    fn smooth_pass(&mut self) -> usize {
        let mut done = 0;
        for a in 0..self.pts.len() as u32 {
            if !self.free(a) || self.removed[a as usize] || !self.active[a as usize] || self.star[a as usize].is_empty() {
                continue;
            }
            let star = self.star[a as usize].clone();
            let old_min = star.iter().map(|&t| self.angle(self.tris[t as usize])).fold(f64::INFINITY, f64::min);
            // only where an angle is below the aim: elsewhere moves creep by hundredths of a
            // degree, round after round
            if old_min >= -GOOD_DEG.to_radians().cos() {
                continue;
            }
            // the centroid of the distinct 3D neighbours (a pole counts once)
            let mut keys: Vec<(u64, u32)> = self.neighbours(a).into_iter().map(|i| (self.key[i as usize], i)).collect();
            keys.sort_unstable();
            keys.dedup_by_key(|k| k.0);
            let c = keys.iter().map(|&(_, i)| self.pts[i as usize].p3).sum::<DVec3>() / keys.len() as f64;
            let old = self.pts[a as usize];
            // one Gauss-Newton step toward it on the surface (the move is checked anyway)
            let (_, du, dv) = self.surf.point_and_tangents(old.uv.x, old.uv.y);
            let r = c - old.p3;
            let (a11, a12, a22) = (du.dot(du), du.dot(dv), dv.dot(dv));
            let det = a11 * a22 - a12 * a12;
            if !(det > 1e-12 * a11 * a22) {
                continue;
            }
            let (b1, b2) = (du.dot(r), dv.dot(r));
            let target = old.uv + DVec2::new(a22 * b1 - a12 * b2, a11 * b2 - a12 * b1) / det;
            for uv in [target, 0.5 * (old.uv + target)] {
                let s = DVec2::new(cdt::flush(uv.x * self.su), cdt::flush(uv.y * self.sv));
                let p3 = self.surf.point(uv.x, uv.y);
                if !(s.is_finite() && p3.is_finite()) {
                    continue;
                }
                self.pts[a as usize] = Point { s, uv, p3, id: None };
                let new_min = star.iter().map(|&t| self.angle(self.tris[t as usize])).fold(f64::INFINITY, f64::min);
                if new_min > old_min + MOVE_GAIN && star.iter().all(|&t| self.acceptable(self.tris[t as usize])) {
                    self.touch(&star);
                    done += 1;
                    break;
                }
                self.pts[a as usize] = old;
            }
        }
        done
    }
}

#[cfg(test)]
mod tests;
