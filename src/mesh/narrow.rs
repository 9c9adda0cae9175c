//! Narrow strips: input triangles narrower than a tolerance, as a CAD model leaves where two
//! faces almost meet (a step of 0.0001 mm between two coaxial cylinders, a sliver face a
//! thousandth of a millimetre wide along an edge). A quality mesh cannot resolve them at any
//! sensible size: tets there must either be as small as the strip is wide, all along it, or
//! slivers. [`collapse_narrow`] closes them up, as Gmsh's small-face fixing and a CAD
//! mesher's defeaturing tolerance do: short edges collapse and caps (a vertex within the
//! tolerance of its triangle's opposite side) give their vertex to the neighbour across that
//! side. What is left is the same closed, manifold surface less the strip, within the
//! tolerance of the input everywhere.

use crate::core::FaceId;
use crate::mesh::TriSurface;
use glam::DVec3;
use rustc_hash::{FxHashMap, FxHashSet};
use std::collections::BTreeSet;

/// Rounds of needle collapses and cap splits (each round rebuilds the adjacency).
const ROUNDS: usize = 32;

/// The least cosine between the normals of two triangles around a vertex after a collapse:
/// −0.5 is 120° between them. A collapse that would bring two faces that face each other
/// together (the two sides of a thin sheet at its rim) is not made: such a strip is a wall,
/// not a sliver.
const FOLD_COS: f64 = -0.5;

/// What [`collapse_narrow`] did.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct NarrowReport {
    /// Edges shorter than the tolerance collapsed.
    pub collapses: usize,
    /// Caps whose vertex went onto the neighbour across their long side.
    pub caps: usize,
    /// Triangles removed by the collapses (a cap's triangle is reused by its neighbour).
    pub removed: usize,
    /// The faces that lost triangles (collapsed, or caps given away), with how many each lost.
    pub faces: Vec<(FaceId, usize)>,
    /// The tolerance used.
    pub tolerance: f64,
}

impl NarrowReport {
    /// Adds `other`'s counts and faces to these (the solids of an assembly, one tolerance).
    pub fn add(&mut self, other: &NarrowReport) {
        self.collapses += other.collapses;
        self.caps += other.caps;
        self.removed += other.removed;
        self.tolerance = self.tolerance.max(other.tolerance);
        for &(f, n) in &other.faces {
            match self.faces.binary_search_by_key(&f, |e| e.0) {
                Ok(i) => self.faces[i].1 += n,
                Err(i) => self.faces.insert(i, (f, n)),
            }
        }
    }
}

/// Collapses the strips of `s` narrower than `tol`: edges shorter than `tol` and caps whose
/// vertex lies within `tol` of their opposite side. Vertices of triangles tagged `frozen`
/// never move and their triangles are never split (an assembly's contact faces, whose nodes
/// another solid shares). A collapse is made only where it keeps the surface manifold (the
/// link condition), turns no triangle over and folds no two triangles onto each other
/// ([`FOLD_COS`]). Returns the new surface (vertices renumbered, unused ones dropped, tags
/// kept) and what was done, or `None` where nothing is narrower than `tol` (or `s` has
/// indices out of range or tags that do not match: its checks name those).
pub fn collapse_narrow(s: &TriSurface, tol: f64, frozen: &[FaceId]) -> Option<(TriSurface, NarrowReport)> {
    let n = s.vertices.len();
    if !(tol > 0.0) || s.face_tags.len() != s.triangles.len() || s.triangles.iter().flatten().any(|&v| v as usize >= n) || s.vertices.iter().any(|p| !p.is_finite()) {
        return None;
    }
    let frozen: FxHashSet<FaceId> = frozen.iter().copied().collect();
    let mut w = Work { p: s.vertices.clone(), t: s.triangles.clone(), tags: s.face_tags.clone(), dead: vec![false; s.triangles.len()], fixed: vec![false; n], frozen, lost: Default::default(), tol };
    for (t, tag) in s.triangles.iter().zip(&s.face_tags) {
        if w.frozen.contains(tag) {
            for &v in t {
                w.fixed[v as usize] = true;
            }
        }
    }
    let mut report = NarrowReport { tolerance: tol, ..Default::default() };
    for _ in 0..ROUNDS {
        let collapsed = w.needles();
        let capped = w.caps();
        report.collapses += collapsed;
        report.caps += capped;
        if collapsed + capped == 0 {
            break;
        }
    }
    if report.collapses + report.caps == 0 {
        return None;
    }
    report.removed = w.dead.iter().filter(|&&d| d).count();
    report.faces = w.lost.iter().map(|(&f, &n)| (f, n)).collect();
    report.faces.sort_unstable();
    // the vertices the live triangles use, in their order (the mesher's insertion order and
    // ties follow it: a surface with one cap flipped stays the same elsewhere)
    let live = |i: &usize| !w.dead[*i];
    let mut out = TriSurface {
        triangles: (0..w.t.len()).filter(live).map(|i| w.t[i]).collect(),
        face_tags: (0..w.t.len()).filter(live).map(|i| w.tags[i]).collect(),
        vertices: w.p,
        face_names: s.face_names.clone(),
    };
    out.remove_unused_vertices();
    Some((out, report))
}

struct Work {
    p: Vec<DVec3>,
    t: Vec<[u32; 3]>,
    tags: Vec<FaceId>,
    dead: Vec<bool>,
    /// Vertices that may not move or go (on a frozen face).
    fixed: Vec<bool>,
    /// Faces whose triangles are never split.
    frozen: FxHashSet<FaceId>,
    /// Triangles each face lost (collapsed, or a cap given to its neighbour).
    lost: FxHashMap<FaceId, usize>,
    tol: f64,
}

fn normal(p: [DVec3; 3]) -> DVec3 {
    (p[1] - p[0]).cross(p[2] - p[0])
}

impl Work {
    fn corners(&self, t: [u32; 3]) -> [DVec3; 3] {
        t.map(|v| self.p[v as usize])
    }

    /// The live triangles around each vertex.
    fn stars(&self) -> Vec<Vec<u32>> {
        let mut star = vec![Vec::new(); self.p.len()];
        for (i, t) in self.t.iter().enumerate() {
            if !self.dead[i] {
                for &v in t {
                    star[v as usize].push(i as u32);
                }
            }
        }
        star
    }

    /// One pass of edge collapses: each edge shorter than the tolerance, shortest first, where
    /// neither end was touched yet in this pass.
    fn needles(&mut self) -> usize {
        let mut edges: Vec<(f64, u32, u32)> = Vec::new();
        for (i, t) in self.t.iter().enumerate() {
            if self.dead[i] {
                continue;
            }
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                let l = self.p[a as usize].distance(self.p[b as usize]);
                if a < b && l <= self.tol {
                    edges.push((l, a, b));
                }
            }
        }
        if edges.is_empty() {
            return 0;
        }
        edges.sort_by(|x, y| x.0.total_cmp(&y.0).then((x.1, x.2).cmp(&(y.1, y.2))));
        let star = self.stars();
        let mut touched = vec![false; self.p.len()];
        let mut done = 0;
        for (_, a, b) in edges {
            if touched[a as usize] || touched[b as usize] {
                continue;
            }
            // keep the end with more faces around it (a corner or an edge of the model)
            let faces = |v: u32| star[v as usize].iter().map(|&t| self.tags[t as usize]).collect::<BTreeSet<_>>().len();
            let (keep, go) = match (self.fixed[a as usize], self.fixed[b as usize]) {
                (true, true) => continue,
                (true, false) => (a, b),
                (false, true) => (b, a),
                _ if faces(b) > faces(a) => (b, a),
                _ => (a, b),
            };
            if self.collapse(&star, keep, go) {
                done += 1;
                for v in [keep, go] {
                    touched[v as usize] = true;
                    for &t in &star[v as usize] {
                        for &u in &self.t[t as usize] {
                            touched[u as usize] = true;
                        }
                    }
                }
            }
        }
        done
    }

    /// Moves `go` onto `keep` (at `keep`'s position), removing the two triangles of their
    /// edge, where the surface stays manifold, unfolded and unturned.
    fn collapse(&mut self, star: &[Vec<u32>], keep: u32, go: u32) -> bool {
        let shared: Vec<u32> = star[go as usize].iter().copied().filter(|&t| self.t[t as usize].contains(&keep)).collect();
        if shared.len() != 2 {
            return false;
        }
        // the link condition: the ends' common neighbours are the two triangles' third corners
        let ring = |v: u32| star[v as usize].iter().flat_map(|&t| self.t[t as usize]).filter(move |&u| u != v).collect::<BTreeSet<u32>>();
        let opposite: BTreeSet<u32> = shared.iter().flat_map(|&t| self.t[t as usize]).filter(|&u| u != keep && u != go).collect();
        if ring(keep).intersection(&ring(go)).copied().collect::<BTreeSet<u32>>() != opposite || opposite.len() != 2 {
            return false;
        }
        // the triangles that move: none may turn over or become flat
        let moved: Vec<(u32, [u32; 3])> = star[go as usize].iter().filter(|t| !shared.contains(t)).map(|&t| (t, self.t[t as usize].map(|v| if v == go { keep } else { v }))).collect();
        for &(t, nt) in &moved {
            let (old, new) = (normal(self.corners(self.t[t as usize])), normal(self.corners(nt)));
            // a triangle of the strip itself (no wider than the tolerance) has no direction
            // to keep
            let strip = self.height(self.t[t as usize]) <= self.tol;
            if !(strip || old.dot(new) > 0.0) || new.length() <= f64::EPSILON * self.p[keep as usize].length().max(1.0).powi(2) {
                return false;
            }
        }
        // no fold: no two triangles around `keep` afterwards may face each other (a thin
        // wall's two sides brought together at its rim); the strip's own triangles, no wider
        // than the tolerance, have no direction to judge by
        let after: Vec<DVec3> = star[keep as usize]
            .iter()
            .filter(|t| !shared.contains(t))
            .map(|&t| self.t[t as usize])
            .chain(moved.iter().map(|m| m.1))
            .filter(|&t| self.height(t) > self.tol)
            .map(|t| normal(self.corners(t)))
            .collect();
        for (i, x) in after.iter().enumerate() {
            if after[i + 1..].iter().any(|y| x.dot(*y) < FOLD_COS * x.length() * y.length()) {
                return false;
            }
        }
        for t in shared {
            self.dead[t as usize] = true;
            *self.lost.entry(self.tags[t as usize]).or_default() += 1;
        }
        for (t, nt) in moved {
            self.t[t as usize] = nt;
        }
        true
    }

    /// One pass of cap splits: a cap `(v, a, b)` ([`Work::cap`]) gives `v` to the neighbour
    /// `(b, a, w)`: the two become `(b, v, w)` and `(v, a, w)`, the neighbour's tag on both
    /// (the cap is gone, the neighbour split at `v`).
    fn caps(&mut self) -> usize {
        // the caps, found once: a triangle changed by a split below is touched and skipped,
        // and the others keep their corners through the pass
        let caps: Vec<(usize, (u32, u32, u32))> = (0..self.t.len()).filter(|&i| !self.dead[i]).filter_map(|i| self.cap(self.t[i]).map(|c| (i, c))).collect();
        // the adjacency only where there is a cap to split
        if caps.is_empty() {
            return 0;
        }
        let mut on_edge: FxHashMap<(u32, u32), u32> = Default::default();
        for (i, t) in self.t.iter().enumerate() {
            if !self.dead[i] {
                for k in 0..3 {
                    on_edge.insert((t[k], t[(k + 1) % 3]), i as u32);
                }
            }
        }
        let mut touched = vec![false; self.t.len()];
        let mut done = 0;
        for (i, (v, a, b)) in caps {
            if touched[i] {
                continue;
            }
            let Some(&j) = on_edge.get(&(b, a)) else { continue };
            let j = j as usize;
            if touched[j] || j == i || self.frozen.contains(&self.tags[j]) || self.frozen.contains(&self.tags[i]) {
                continue;
            }
            let tj = self.t[j];
            let Some(k) = (0..3).find(|&k| tj[k] == b && tj[(k + 1) % 3] == a) else { continue };
            let w = tj[(k + 2) % 3];
            if w == v || (self.fixed[a as usize] && self.fixed[b as usize] && self.fixed[w as usize]) {
                continue;
            }
            let (x, y) = ([b, v, w], [v, a, w]);
            // neither half may turn over against the neighbour, nor be as flat as the cap
            // (each split makes the flattest triangle there less flat: the splits end)
            let nj = normal(self.corners(tj));
            let flat = self.height(self.t[i]);
            if [x, y].iter().any(|&h| !(normal(self.corners(h)).dot(nj) > 0.0) || !(self.height(h) > flat)) {
                continue;
            }
            // an edge (v, w) that exists already would be doubled
            if on_edge.contains_key(&(v, w)) || on_edge.contains_key(&(w, v)) {
                continue;
            }
            *self.lost.entry(self.tags[i]).or_default() += 1;
            self.t[j] = x;
            self.t[i] = y;
            self.tags[i] = self.tags[j];
            touched[i] = true;
            touched[j] = true;
            done += 1;
        }
        done
    }

    /// The height of `t` over its longest side.
    fn height(&self, t: [u32; 3]) -> f64 {
        let [a, b, c] = self.corners(t);
        let longest = a.distance(b).max(b.distance(c)).max(c.distance(a));
        if longest > 0.0 { normal([a, b, c]).length() / longest } else { 0.0 }
    }

    /// The corner of `t` within the tolerance of its opposite side, the longest, with its
    /// foot strictly inside that side, as `(v, a, b)`; none where `t` has a side shorter than
    /// the tolerance (a needle: collapsed instead).
    fn cap(&self, t: [u32; 3]) -> Option<(u32, u32, u32)> {
        let c = self.corners(t);
        let side = [0, 1, 2].map(|k| c[(k + 1) % 3].distance(c[(k + 2) % 3]));
        if side.iter().any(|&l| !(l > self.tol)) {
            return None;
        }
        let k = (0..3).max_by(|&i, &j| side[i].total_cmp(&side[j]).then(j.cmp(&i)))?;
        let (v, a, b) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
        let (pa, pb, pv) = (c[(k + 1) % 3], c[(k + 2) % 3], c[k]);
        let e = pb - pa;
        let l = e.length();
        let u = (pv - pa).dot(e) / l;
        let h = e.cross(pv - pa).length() / l;
        (u > 0.0 && u < l && h <= self.tol).then_some((v, a, b))
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::mesh::topology::{nonmanifold_edges_list, open_edges_list};

    /// A surface from planar polygons (outward, counter-clockwise seen from outside), each
    /// fanned from its first vertex and tagged with its place in the list plus one.
    fn polygons(points: &[[f64; 3]], faces: &[&[u32]]) -> TriSurface {
        let mut s = TriSurface { vertices: points.iter().map(|&p| DVec3::from_array(p)).collect(), ..Default::default() };
        for (f, poly) in faces.iter().enumerate() {
            for k in 1..poly.len() - 1 {
                s.triangles.push([poly[0], poly[k], poly[k + 1]]);
                s.face_tags.push(FaceId(f as u32 + 1));
            }
        }
        s
    }

    /// A unit box whose top is two halves, the half x > 0.5 raised by `e`: the step between
    /// them is a face `e` high and 1 long (tag 4), as a CAD model leaves where two faces
    /// almost meet.
    pub(crate) fn stepped_box(e: f64) -> TriSurface {
        let h = 1.0 + e;
        let p = [
            [0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0], [0.5, 0.0, 1.0], [0.5, 1.0, 1.0], [0.0, 1.0, 1.0],
            [0.5, 0.0, h], [1.0, 0.0, h], [1.0, 1.0, h], [0.5, 1.0, h],
        ];
        let faces: [&[u32]; 8] = [&[0, 3, 2, 1], &[4, 5, 6, 7], &[8, 9, 10, 11], &[5, 8, 11, 6], &[5, 4, 0, 1, 9, 8], &[6, 11, 10, 2, 3, 7], &[0, 4, 7, 3], &[1, 2, 10, 9]];
        polygons(&p, &faces)
    }

    fn volume(s: &TriSurface) -> f64 {
        s.triangles.iter().map(|t| { let [a, b, c] = t.map(|v| s.vertices[v as usize]); a.dot(b.cross(c)) / 6.0 }).sum()
    }

    fn closed(s: &TriSurface) {
        assert!(open_edges_list(s).is_empty(), "open");
        assert!(nonmanifold_edges_list(s).is_empty(), "non-manifold");
        for t in &s.triangles {
            let [a, b, c] = t.map(|v| s.vertices[v as usize]);
            assert!((b - a).cross(c - a).length() > 1e-9, "a flat triangle {t:?}");
        }
    }

    #[test]
    fn a_step_narrower_than_the_tolerance_is_closed_up() {
        let s = stepped_box(1e-5);
        closed(&s);
        let (r, report) = collapse_narrow(&s, 1e-3, &[]).unwrap();
        closed(&r);
        // the step is gone, every other face is there
        let tags: BTreeSet<u32> = r.face_tags.iter().map(|f| f.0).collect();
        assert_eq!(tags, [1, 2, 3, 5, 6, 7, 8].into_iter().collect());
        assert!(report.faces.iter().any(|&(f, n)| f == FaceId(4) && n == 2), "{report:?}");
        assert!(report.collapses > 0 && report.removed > 0);
        // every vertex is one of the input's, the volume within the step's
        assert!(r.vertices.iter().all(|v| s.vertices.contains(v)));
        assert!((volume(&r) - volume(&s)).abs() <= 1e-5, "{} {}", volume(&r), volume(&s));
        // and nothing is left to close
        assert!(collapse_narrow(&r, 1e-3, &[]).is_none());
    }

    #[test]
    fn a_step_wider_than_the_tolerance_stays() {
        assert!(collapse_narrow(&stepped_box(1e-2), 1e-3, &[]).is_none());
        assert!(collapse_narrow(&stepped_box(1e-5), 0.0, &[]).is_none());
    }

    #[test]
    fn frozen_faces_keep_their_vertices_and_triangles() {
        let s = stepped_box(1e-5);
        // the step's own vertices may not go: nothing can close it
        assert!(collapse_narrow(&s, 1e-3, &[FaceId(4)]).is_none());
        // the raised top frozen: what closes the step keeps the top's vertices and triangles
        if let Some((r, _)) = collapse_narrow(&s, 1e-3, &[FaceId(3)]) {
            closed(&r);
            let top = |s: &TriSurface| s.triangles.iter().zip(&s.face_tags).filter(|(_, f)| f.0 == 3).map(|(t, _)| t.map(|v| s.vertices[v as usize].to_array())).collect::<Vec<_>>();
            assert_eq!(top(&r), top(&s));
        }
    }

    #[test]
    fn a_thin_wall_is_not_folded_flat() {
        // a slab 1e-5 thick: its four sides are strips narrower than the tolerance, but
        // closing them would bring the top down onto the bottom
        let e = 1e-5;
        let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, e], [1.0, 0.0, e], [1.0, 1.0, e], [0.0, 1.0, e]];
        let faces: [&[u32]; 6] = [&[0, 3, 2, 1], &[4, 5, 6, 7], &[0, 1, 5, 4], &[1, 2, 6, 5], &[2, 3, 7, 6], &[3, 0, 4, 7]];
        let s = polygons(&p, &faces);
        closed(&s);
        assert!((volume(&s) - e).abs() < 1e-12);
        if let Some((r, _)) = collapse_narrow(&s, 1e-3, &[]) {
            closed(&r);
            assert!((volume(&r) - e).abs() < 1e-9, "{}", volume(&r));
        }
    }
}
