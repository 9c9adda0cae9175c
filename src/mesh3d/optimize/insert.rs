//! Vertex insertion, for bad tets that flips and smoothing cannot improve (typically slivers
//! whose four vertices are fixed).
//!
//! A new vertex `p` goes at the circumcentre of the bad tet (or, failing that, its centroid, or
//! above one of its constrained faces at the height of a well-shaped tet on it).
//! Its cavity starts from the tet containing `p`, found by a walk decided with exact
//! [`orient3d`](crate::core::predicates::orient3d), and from the bad tet itself (a flat tet on
//! a curved boundary, all four vertices on it, may hold neither `p` nor `p` in its
//! circumsphere, whose centre lies beyond the wall), and grows over unconstrained faces to the
//! tets whose circumsphere contains `p` (exact [`insphere`](crate::core::predicates::insphere));
//! then, while some cavity face does not see `p` strictly (exact), the tet beyond it joins the
//! cavity. Where that cavity fails (too large, or judged worse), `p` is tried once more with
//! the least cavity: the two seeds grown only until star-shaped. The cavity never crosses a
//! constrained face, so `p` is interior to one region. The cavity is replaced by the tets
//! joining its faces to `p`, `p` is smoothed in its new star, and the insertion is kept only if
//! the least score of the new tets beats that of the cavity and the radius-edge bound holds
//! (twice the bound where the cavity's worst tet is far under target);
//! otherwise the old tets are put back and `p` is dropped.

use crate::core::Sign;
use crate::core::ids::NONE;
use crate::core::predicates::{insphere, orient3d};
use crate::mesh::tet_mesh::TET_FACES;
use crate::mesh3d::optimize::{LAST_PASSES_BELOW, RESCUE_BELOW};
use crate::mesh3d::optimize::smooth::{MIN_GAIN, Smoother};
use crate::mesh3d::optimize::work::Work;
use crate::quality::tetrahedron::{tet_circumradius, tet_radius_edge};
use glam::DVec3;

/// The least score of a new star that may exceed the radius-edge bound a little when it
/// replaces a tet under [`LAST_PASSES_BELOW`].
const NEARLY_GOOD: f64 = 0.9;

/// The most tets a cavity may hold.
const MAX_CAVITY: usize = 48;
/// Heights above a tet's constrained face, in mean edges of the face, of the points tried
/// there (0.82 is a regular tet's height). The low ones are for thin walls: a flat tet on a
/// tube's wall thinner than its edges (`abc-0000`: 3.2 thick, edges 5 to 9) has no room for a
/// point at the height of a well-shaped tet.
const ABOVE_WALL: [f64; 4] = [0.8, 0.5, 0.3, 0.15];
/// The most steps of the point-location walk.
const MAX_WALK: usize = 64;

/// Scratch space for insertion, reused across calls.
#[derive(Default)]
pub(crate) struct Inserter {
    cavity: Vec<u32>,
    old: Vec<[u32; 4]>,
    new: Vec<[u32; 4]>,
    star: Vec<u32>,
}

/// Circumcentre of a tet (floating point; `None` if not finite).
fn circumcentre(p: &[DVec3; 4]) -> Option<DVec3> {
    let (a, b, c) = (p[1] - p[0], p[2] - p[0], p[3] - p[0]);
    let det = a.dot(b.cross(c));
    if det == 0.0 {
        return None;
    }
    let num = b.cross(c) * a.length_squared() + c.cross(a) * b.length_squared() + a.cross(b) * c.length_squared();
    let o = p[0] + num / (2.0 * det);
    o.is_finite().then_some(o)
}

impl Inserter {
    /// The live tet containing `p` (strictly inside or on its boundary), walking from `t`
    /// without crossing constrained faces; `None` if the walk fails.
    fn locate(&self, w: &Work, mut t: u32, p: DVec3) -> Option<u32> {
        'walk: for _ in 0..MAX_WALK {
            let tet = w.tets[t as usize];
            let c = w.corners(&tet);
            for (k, f) in TET_FACES.iter().enumerate() {
                // p strictly beyond the outward face k
                if orient3d(c[f[0]], c[f[1]], c[f[2]], p) == Sign::Positive {
                    let n = w.nbr[t as usize][k];
                    if n == NONE || w.constrained(t, k) {
                        return None;
                    }
                    t = n >> 2;
                    continue 'walk;
                }
            }
            return Some(t);
        }
        None
    }

    /// Grows the cavity of `p` from `start` and the bad tet `bad` (which may not contain `p`
    /// nor have it in its circumsphere: a flat tet on the boundary, whose circumcentre lies
    /// beyond the wall, is taken out by a point below it only so); false if it gets too large
    /// or cannot be made star-shaped.
    fn grow(&mut self, w: &mut Work, start: u32, bad: u32, p: DVec3, delaunay: bool) -> bool {
        self.cavity.clear();
        w.new_visit();
        for t in [start, bad] {
            if !w.visited(t) {
                w.visit(t);
                self.cavity.push(t);
            }
        }
        let mut i = if delaunay { 0 } else { self.cavity.len() };
        while i < self.cavity.len() {
            let t = self.cavity[i];
            i += 1;
            for k in 0..4 {
                let n = w.nbr[t as usize][k];
                if n == NONE || w.constrained(t, k) || w.visited(n >> 2) {
                    continue;
                }
                let [a, b, c, d] = w.corners(&w.tets[(n >> 2) as usize]);
                if insphere(a, b, c, d, p) == Sign::Positive {
                    w.visit(n >> 2);
                    self.cavity.push(n >> 2);
                    if self.cavity.len() > MAX_CAVITY {
                        return false;
                    }
                }
            }
        }
        // star-shape: every outer face must see p strictly
        loop {
            let mut grew = false;
            let mut i = 0;
            while i < self.cavity.len() {
                let t = self.cavity[i];
                i += 1;
                let tet = w.tets[t as usize];
                let c = w.corners(&tet);
                for (k, f) in TET_FACES.iter().enumerate() {
                    let n = w.nbr[t as usize][k];
                    if n != NONE && w.visited(n >> 2) {
                        continue;
                    }
                    // outward face: p must be strictly inside, i.e. Negative
                    if orient3d(c[f[0]], c[f[1]], c[f[2]], p) == Sign::Negative {
                        continue;
                    }
                    if n == NONE || w.constrained(t, k) {
                        return false;
                    }
                    w.visit(n >> 2);
                    self.cavity.push(n >> 2);
                    grew = true;
                    if self.cavity.len() > MAX_CAVITY {
                        return false;
                    }
                }
            }
            if !grew {
                return true;
            }
        }
    }

    /// The live tet with the vertices of `tet` (in any order), from the star of its first
    /// vertex; `NONE` if there is none.
    fn find(&mut self, w: &mut Work, tet: &[u32; 4]) -> u32 {
        let mut star = std::mem::take(&mut self.star);
        let mut key = *tet;
        key.sort_unstable();
        let found = if w.star(tet[0], &mut star) {
            star.iter().copied().find(|&s| {
                let mut v = w.tets[s as usize];
                v.sort_unstable();
                v == key
            })
        } else {
            None
        };
        self.star = star;
        found.unwrap_or(NONE)
    }

    /// Tries to insert a vertex for the bad live tet `t`; true if one was inserted (and kept).
    pub(crate) fn try_insert(&mut self, w: &mut Work, sm: &mut Smoother, t: u32, max_re: f64) -> bool {
        let tet = w.tets[t as usize];
        let c = w.corners(&tet);
        let centroid = (c[0] + c[1] + c[2] + c[3]) * 0.25;
        let mut candidates = vec![circumcentre(&c), Some(centroid)];
        // above each constrained face, at the height of a well-shaped tet on it: a sliver on a
        // wall (its fourth vertex near the wall's plane, its centre far off or behind the wall)
        // gets a vertex of its own there
        for (k, f) in TET_FACES.iter().enumerate() {
            if !w.constrained(t, k) {
                continue;
            }
            let [a, b, d] = f.map(|i| c[i]);
            let n = (d - a).cross(b - a).normalize_or_zero(); // into the tet
            let edge = (a.distance(b) + b.distance(d) + d.distance(a)) / 3.0;
            let g = (a + b + d) / 3.0;
            for h in ABOVE_WALL {
                candidates.push(Some(g + n * (h * edge)));
            }
        }
        for p in candidates.into_iter().flatten() {
            // a circumcentre far away is of no use
            if p.distance(centroid) > 2.0 * tet_circumradius(&c) {
                continue;
            }
            // the Delaunay cavity of p, else the least one (the bad tet and the tet holding p,
            // grown only until it is star-shaped): a flat tet's neighbours whose spheres hold
            // p make large cavities, and in them a new tet that fails the judgement
            for delaunay in [true, false] {
                // an undone attempt puts the tets back in other slots: find the bad tet again
                let start = if w.alive(t) && w.tets[t as usize] == tet { t } else { self.find(w, &tet) };
                if start == NONE {
                    return false;
                }
                if self.insert_at(w, sm, start, p, max_re, delaunay) {
                    return true;
                }
            }
        }
        false
    }

    fn insert_at(&mut self, w: &mut Work, sm: &mut Smoother, bad: u32, p: DVec3, max_re: f64, delaunay: bool) -> bool {
        let Some(start) = self.locate(w, bad, p) else {
            return false;
        };
        if !self.grow(w, start, bad, p, delaunay) {
            return false;
        }
        let region = w.region[start as usize];
        if self.cavity.iter().any(|&s| w.region[s as usize] != region) {
            return false;
        }
        let old_min = self.cavity.iter().map(|&s| w.q[s as usize]).fold(f64::INFINITY, f64::min);
        let mut old_re = 0.0f64;
        self.old.clear();
        for &s in &self.cavity {
            let tet = w.tets[s as usize];
            old_re = old_re.max(tet_radius_edge(&w.corners(&tet)));
            self.old.push(tet);
        }
        let v = w.push_vertex(p);
        self.new.clear();
        w.new_visit();
        for &s in &self.cavity {
            w.visit(s);
        }
        for &s in &self.cavity {
            let tet = w.tets[s as usize];
            for (k, f) in TET_FACES.iter().enumerate() {
                let n = w.nbr[s as usize][k];
                if n != NONE && w.visited(n >> 2) {
                    continue;
                }
                // the outward face (f0, f1, f2) sees v on its inner side: (f1, f0, f2, v)
                self.new.push([tet[f[1]], tet[f[0]], tet[f[2]], v]);
            }
        }
        let cavity = std::mem::take(&mut self.cavity);
        let done = w.replace(&cavity, &self.new, region);
        self.cavity = cavity;
        if !done {
            w.pop_vertex(v);
            return false;
        }
        sm.smooth_new(w, v);
        // judge the new star
        let mut star = std::mem::take(&mut self.star);
        let ok = w.star(v, &mut star) && {
            let new_min = star.iter().map(|&s| w.q[s as usize]).fold(f64::INFINITY, f64::min);
            // far under target (a sliver of 1-9°), a new star a little over the radius-edge
            // bound is better than the sliver: allow twice the bound there
            // a tet that fails the usual acceptance figures (under LAST_PASSES_BELOW) may give
            // way to a star whose every tet is nearly good by the score, which has a
            // radius-edge term of its own (at least NEARLY_GOOD: radius-edge 2.22 for 2)
            let bound = if old_min < RESCUE_BELOW {
                (2.0 * max_re).max(old_re)
            } else if old_min < LAST_PASSES_BELOW && new_min >= NEARLY_GOOD {
                (max_re / NEARLY_GOOD).max(old_re)
            } else {
                max_re.max(old_re)
            };
            new_min > old_min + MIN_GAIN && star.iter().all(|&s| tet_radius_edge(&w.corners(&w.tets[s as usize])) <= bound)
        };
        if ok {
            self.star = star;
            return true;
        }
        // undo: the old tets fill the same cavity
        let undone = w.replace(&star, &self.old, region);
        self.star = star;
        if undone {
            w.v2t[v as usize] = NONE;
            w.pop_vertex(v);
        }
        // if the undo failed (it cannot: the old tets were a valid filling), the insertion stays
        !undone
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh3d::optimize::measure::Targets;

    #[test]
    fn circumcentre_is_equidistant() {
        let p = [DVec3::new(0.1, 0.0, 0.0), DVec3::new(1.0, 0.2, 0.0), DVec3::new(0.0, 1.0, 0.3), DVec3::new(0.2, 0.1, 1.0)];
        let o = circumcentre(&p).unwrap();
        let r = o.distance(p[0]);
        for q in &p[1..] {
            assert!((o.distance(*q) - r).abs() < 1e-12);
        }
        let _ = Targets::new(15.0, 160.0);
    }
}
