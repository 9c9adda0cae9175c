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
//! otherwise the old tets are put back and `p` is dropped. Where a face of the cavity's
//! outline already rules that out (a tet's radius-edge ratio is at least its faces', and
//! smoothing `p` leaves the outline as it is), nothing is inserted: on `part.step` at TetGen's
//! tet count 351 of the 1,168 cavities tried were such, each an insertion, a smoothing and an
//! undo for nothing. In the focus phase's rounds the wedges of the outline rule out more
//! ([`Inserter::wedge_bound`]): half of those left there.

use crate::core::Sign;
use crate::core::ids::NONE;
use crate::core::predicates::{insphere, orient3d};
use crate::mesh::tet_mesh::TET_FACES;
use crate::mesh3d::optimize::{LAST_PASSES_BELOW, RESCUE_BELOW};
use crate::mesh3d::optimize::smooth::{MIN_GAIN, Smoother};
use crate::mesh3d::optimize::measure::{EDGE_FACES, angle, cosines, normals};
use crate::mesh3d::optimize::work::Work;
use crate::quality::tetrahedron::{TET_EDGES, tet_circumradius};
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
    /// The cavity's tets' edges (sorted vertices), their dihedral angles there and whether
    /// the edge lies on the cavity's outline ([`Inserter::wedge_bound`]).
    edges: Vec<([u32; 2], f64, bool)>,
    /// Whether an insertion that the cavity's wedges rule out ([`Inserter::wedge_bound`]) is
    /// left out: in the rounds of the focus phase (`focus.rs`), where, on `part.step` at
    /// TetGen's tet count, half the cavities tried were such. Not in the passes before it:
    /// there an attempt that is undone still leaves its cavity's tets in new slots and its
    /// vertices touched, so that later passes try them again, and without those retries
    /// `featuretype.STL` stopped at 14.28° with 7 tets under 18° (18.17° with them).
    pub(crate) wedges: bool,
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

    /// A score no position of the new vertex can beat, from the wedges of the cavity's
    /// outline: at an edge of the outline the cavity's tets fill a wedge (their dihedral
    /// angles there add up to it), and with the cavity replaced by the tets joining its outline
    /// to the new vertex, two new tets fill it, their faces through the edge and the vertex
    /// splitting it in two, so the smaller of their angles is at most half the wedge wherever
    /// the vertex goes (smoothing leaves the outline as it is). Half the smallest wedge, over
    /// the smallest-angle target, bounds the new star's least score. A bad tet alone at an
    /// outline edge where its smallest angle lies is halved there: no insertion in that cavity
    /// can help it. The cavity's tets are those of [`Inserter::cavity`], and the visit marks
    /// those of [`Inserter::insert_at`] (the cavity's tets). The half wedge is taken a little
    /// high (1e-3°, far above the rounding of the arc cosines), so that the bound never
    /// refuses what the judgement would keep; where the outline pinches at an edge (two
    /// wedges of the cavity there) the sum is over both and only larger.
    fn wedge_bound(&mut self, w: &Work) -> f64 {
        self.edges.clear();
        for &s in &self.cavity {
            let tet = w.tets[s as usize];
            let Some(c) = cosines(&normals(&w.corners(&tet))) else { continue };
            // whether face k of s lies on the outline
            let outside = |k: usize| {
                let n = w.nbr[s as usize][k];
                n == NONE || !w.visited(n >> 2)
            };
            for (e, [i, j]) in TET_EDGES.iter().enumerate() {
                let [k, l] = EDGE_FACES[e];
                let (a, b) = (tet[*i], tet[*j]);
                self.edges.push(([a.min(b), a.max(b)], angle(c[e]), outside(k) || outside(l)));
            }
        }
        self.edges.sort_unstable_by(|x, y| x.0.cmp(&y.0));
        let mut least = f64::INFINITY;
        for group in self.edges.chunk_by(|x, y| x.0 == y.0) {
            if group.iter().any(|x| x.2) {
                least = least.min(group.iter().map(|x| x.1).sum::<f64>());
            }
        }
        (least / 2.0 + 1e-3) / w.tg.min_deg
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
            old_re = old_re.max(w.judged[s as usize].re);
            self.old.push(tet);
        }
        // the index the new vertex gets once pushed
        let v = w.pts.len() as u32;
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
        if hopeless(w, &self.new, old_min, old_re, max_re) || (self.wedges && self.wedge_bound(w) <= old_min + MIN_GAIN) {
            return false;
        }
        let pushed = w.push_vertex(p);
        debug_assert_eq!(pushed, v);
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
            let bound = radius_edge_bound(old_min, new_min, old_re, max_re);
            new_min > old_min + MIN_GAIN && star.iter().all(|&s| w.judged[s as usize].re <= bound)
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

/// The largest radius-edge ratio a new star may have: the bound `max_re` or the cavity's
/// worst `old_re`, and where the cavity's least score `old_min` is far under target (a sliver
/// of 1-9°) twice the bound, a new star a little over the bound being better than the
/// sliver; where `old_min` fails the usual acceptance figures (under [`LAST_PASSES_BELOW`]),
/// a new star whose least score `new_min` is nearly good ([`NEARLY_GOOD`], a score with a
/// radius-edge term of its own: radius-edge 2.22 for 2) may reach the bound over that.
fn radius_edge_bound(old_min: f64, new_min: f64, old_re: f64, max_re: f64) -> f64 {
    if old_min < RESCUE_BELOW {
        (2.0 * max_re).max(old_re)
    } else if old_min < LAST_PASSES_BELOW && new_min >= NEARLY_GOOD {
        (max_re / NEARLY_GOOD).max(old_re)
    } else {
        max_re.max(old_re)
    }
}

/// Whether no position of the new vertex can make the star `new` (the cavity's outline
/// faces joined to it, the vertex last) pass the judgement of [`Inserter::insert_at`]: a
/// tet's radius-edge ratio is at least that of each of its faces (its circumsphere holds the
/// face's circumcircle, and its shortest edge is at most the face's), and smoothing the
/// vertex leaves the outline as it is. So where an outline face's ratio exceeds the largest
/// bound [`radius_edge_bound`] may give, or caps the score's radius-edge term at the cavity's
/// least score, the attempt would only be undone: it is not made. The face's ratio is taken a
/// little low (a relative 1e-9, far above the rounding of either side), so the test never
/// refuses what the judgement would keep.
fn hopeless(w: &Work, new: &[[u32; 4]], old_min: f64, old_re: f64, max_re: f64) -> bool {
    let worst = new.iter().map(|t| triangle_radius_edge([t[0], t[1], t[2]].map(|i| w.pts[i as usize]))).fold(0.0, f64::max) * (1.0 - 1e-9);
    let re_term = if w.tg.max_re.is_finite() { w.tg.max_re / worst } else { f64::INFINITY };
    re_term <= old_min + MIN_GAIN || worst > radius_edge_bound(old_min, f64::INFINITY, old_re, max_re)
}

/// A triangle's circumradius over its shortest edge; `+∞` for a flat triangle (every tet on
/// it is flat) or one with a repeated vertex.
fn triangle_radius_edge(t: [DVec3; 3]) -> f64 {
    let [a, b, c] = t;
    let (ab, bc, ca) = (a.distance(b), b.distance(c), c.distance(a));
    // circumradius abc / (4 area), the cross product's length being twice the area
    let twice_area = (b - a).cross(c - a).length();
    let ratio = ab * bc * ca / (2.0 * twice_area) / ab.min(bc).min(ca);
    if ratio.is_nan() { f64::INFINITY } else { ratio }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shapes::kuhn_cube;
    use crate::mesh3d::optimize::measure::Targets;
    use crate::quality::tetrahedron::tet_radius_edge;

    #[test]
    fn a_tet_has_at_least_the_radius_edge_ratio_of_each_face() {
        // the lemma `hopeless` rests on, with its margin, on random tets, slivers and needles
        let mut rng = crate::core::spatial_order::XorShift::new(5);
        let mut rnd = move || (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        for k in 0..20000 {
            let mut p = [0; 4].map(|_| DVec3::new(rnd(), rnd(), rnd()));
            match k % 3 {
                // a sliver: the fourth vertex near the plane of the others
                1 => p[3] = (p[0] + p[1] + p[2]) / 3.0 + DVec3::new(rnd(), rnd(), rnd()) * 1e-6,
                // a needle: the fourth vertex near the first
                2 => p[3] = p[0] + DVec3::new(rnd(), rnd(), rnd()) * 1e-4,
                _ => {}
            }
            let re = tet_radius_edge(&p);
            for f in TET_FACES {
                let face = triangle_radius_edge(f.map(|i| p[i]));
                assert!(re >= face * (1.0 - 1e-9), "tet {p:?}: {re} under its face's {face}");
            }
        }
        assert_eq!(triangle_radius_edge([DVec3::ZERO, DVec3::X, DVec3::X * 2.0]), f64::INFINITY);
        assert_eq!(triangle_radius_edge([DVec3::ZERO, DVec3::ZERO, DVec3::X]), f64::INFINITY);
        let equilateral = triangle_radius_edge([DVec3::ZERO, DVec3::X, DVec3::new(0.5, 0.75f64.sqrt(), 0.0)]);
        assert!((equilateral - 1.0 / 3f64.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn an_insertion_on_a_thin_outline_face_is_hopeless() {
        let m = kuhn_cube(2, 0.0, 1);
        let tg = Targets::new(18.0, 158.0).with_radius_edge(2.0);
        let mut w = Work::build(&m, tg).unwrap();
        let (pa, pb) = (DVec3::new(5.0, 0.0, 0.0), DVec3::new(6.0, 0.0, 0.0));
        let [a, b] = [pa, pb].map(|p| w.push_vertex(p));
        let v = w.push_vertex(DVec3::new(5.5, 0.3, 0.5));
        // an outline face of ratio 12.5 (sides 1, 0.5 and 0.5, height 0.02): over the bound
        // of 2, or twice it for a cavity far under target
        let thin = DVec3::new(5.5, 0.02, 0.0);
        assert!((triangle_radius_edge([pa, pb, thin]) - 12.5).abs() < 0.1);
        let c = w.push_vertex(thin);
        assert!(hopeless(&w, &[[a, b, c, v]], 0.1, 3.0, 2.0));
        // not where the cavity's own worst ratio is as high and its least score under the
        // star's cap (2 / 12.5)
        assert!(!hopeless(&w, &[[a, b, c, v]], 0.1, 30.0, 2.0));
        assert!(hopeless(&w, &[[a, b, c, v]], 0.2, 30.0, 2.0));
        // a well-shaped outline face leaves it to the judgement
        let d = w.push_vertex(DVec3::new(5.5, 0.8, 0.0));
        assert!(!hopeless(&w, &[[a, b, d, v]], 0.1, 3.0, 2.0));
        // the score's radius-edge term caps what the star can reach: a face of ratio 1.118
        // caps it at 2 / 1.118 = 1.79, under a cavity's least score of 1.95
        let low = DVec3::new(5.5, 0.25, 0.0);
        assert!((triangle_radius_edge([pa, pb, low]) - 1.118).abs() < 1e-3);
        let e = w.push_vertex(low);
        assert!(hopeless(&w, &[[a, b, e, v]], 1.95, 3.0, 2.0));
        assert!(!hopeless(&w, &[[a, b, e, v]], 0.5, 3.0, 2.0));
    }

    #[test]
    fn the_wedge_bound_is_half_the_least_wedge_of_the_outline() {
        let m = kuhn_cube(2, 0.0, 1);
        let tg = Targets::new(18.0, 158.0);
        let mut w = Work::build(&m, tg).unwrap();
        let mut ins = Inserter::default();
        let angles = |w: &Work, t: u32| cosines(&normals(&w.corners(&w.tets[t as usize]))).unwrap().map(angle);
        // a lone tet: every edge is on the outline, its wedge the tet's own angle there
        ins.cavity = vec![0];
        w.new_visit();
        w.visit(0);
        let least = angles(&w, 0).into_iter().fold(f64::INFINITY, f64::min);
        assert!((ins.wedge_bound(&w) - (least / 2.0 + 1e-3) / 18.0).abs() < 1e-12);
        // two tets across a face: at that face's edges the wedge is the sum of both angles
        let n = w.nbr[0].iter().copied().find(|&n| n != NONE).unwrap() >> 2;
        ins.cavity = vec![0, n];
        w.new_visit();
        w.visit(0);
        w.visit(n);
        let key = |t: u32, e: usize| {
            let [i, j] = TET_EDGES[e];
            let v = w.tets[t as usize];
            [v[i].min(v[j]), v[i].max(v[j])]
        };
        let mut wedges: Vec<([u32; 2], f64)> = Vec::new();
        for t in [0, n] {
            for (e, a) in angles(&w, t).into_iter().enumerate() {
                match wedges.iter_mut().find(|x| x.0 == key(t, e)) {
                    Some(x) => x.1 += a,
                    None => wedges.push((key(t, e), a)),
                }
            }
        }
        let least = wedges.iter().map(|x| x.1).fold(f64::INFINITY, f64::min);
        assert!((ins.wedge_bound(&w) - (least / 2.0 + 1e-3) / 18.0).abs() < 1e-12);
        // the Kuhn cube's tets have right and 45°, 60° angles: a lone tet's least wedge is 45°
        // or under, two of them fill at least 90° at their shared face's edges
        assert!(wedges.iter().filter(|x| [0, n].iter().all(|&t| (0..6).any(|e| key(t, e) == x.0))).all(|x| x.1 > 89.0));
    }

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
