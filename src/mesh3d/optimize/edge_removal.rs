//! Edge removal: the tets around an interior edge `(a, b)` are replaced by the best
//! triangulation of the ring of their other vertices, each ring triangle `(r_i, r_j, r_k)` giving
//! the two tets `(a, r_i, r_j, r_k)` and `(r_i, r_j, r_k, b)` (Shewchuk, "Two discrete
//! optimization algorithms for the topological improvement of tetrahedral meshes", 2002).
//!
//! With 3 tets around the edge this is the 3-2 flip, with 4 the 4-4 flip. The triangulation is
//! chosen by dynamic programming over the ring polygon, maximising the least score of the new
//! tets; a triangle whose tets are not both positively oriented (exact
//! [`orient3d`](crate::core::predicates::orient3d)) is not allowed. The edge is removed only if
//! the new tets' least score beats the old ones', no new tet exceeds the radius-edge bound
//! (unless an old one already did by more, or an old one is a sliver under
//! [`SLIVER_DEG`](crate::mesh3d::optimize::measure::SLIVER_DEG)), and [`Work::replace`]
//! confirms the new tets fill the same cavity.
//!
//! The ring is listed so that every `(a, b, r_i, r_{i+1})` is positively oriented, i.e. it turns
//! clockwise seen from `a`; then both tets of a ring triangle with `i < j < k` are positively
//! oriented when the triangle is a valid one.

use crate::core::ids::NONE;
use crate::mesh3d::optimize::work::{Work, even_perm, local};
use crate::mesh3d::optimize::measure::flip_radius_edge_bound;
use crate::quality::tetrahedron::tet_radius_edge;

/// The most tets around an edge that edge removal considers.
pub(crate) const MAX_RING: usize = 12;

/// Scratch space for edge removal, reused across calls.
pub(crate) struct EdgeRemoval {
    ring_tets: Vec<u32>,
    ring: Vec<u32>,
    new: Vec<[u32; 4]>,
    /// Best least score of the sub-polygon `i..=j`.
    best: [[f64; MAX_RING]; MAX_RING],
    /// The apex `k` of the triangle on chord `(i, j)` in the best triangulation.
    apex: [[u8; MAX_RING]; MAX_RING],
}

impl Default for EdgeRemoval {
    fn default() -> Self {
        EdgeRemoval {
            ring_tets: Vec::new(),
            ring: Vec::new(),
            new: Vec::new(),
            best: [[0.0; MAX_RING]; MAX_RING],
            apex: [[0; MAX_RING]; MAX_RING],
        }
    }
}

/// The two vertices of `tet` other than those at local positions `i` and `j`, ordered so that
/// `(tet[i], tet[j], c, d)` is an even permutation of `tet`.
#[inline]
pub(crate) fn others(tet: &[u32; 4], i: usize, j: usize) -> (u32, u32) {
    let mut rest = (0..4).filter(|&x| x != i && x != j);
    let (k, l) = (rest.next().unwrap_or(0), rest.next().unwrap_or(0));
    if even_perm([i, j, k, l]) { (tet[k], tet[l]) } else { (tet[l], tet[k]) }
}

impl EdgeRemoval {
    /// Walks around the edge `(a, b)` of live tet `t`, filling the ring; false if the edge is on
    /// a constrained face or has more than [`MAX_RING`] tets.
    fn walk(&mut self, w: &Work, t: u32, a: u32, b: u32) -> bool {
        self.ring_tets.clear();
        self.ring.clear();
        let tet = w.tets[t as usize];
        let (Some(i), Some(j)) = (local(&tet, a), local(&tet, b)) else {
            return false;
        };
        let (mut x, mut y) = others(&tet, i, j);
        let mut cur = t;
        loop {
            if self.ring_tets.len() == MAX_RING {
                return false;
            }
            self.ring_tets.push(cur);
            self.ring.push(x);
            let ct = &w.tets[cur as usize];
            let Some(k) = local(ct, x) else { return false };
            if w.constrained(cur, k) {
                return false;
            }
            let n = w.nbr[cur as usize][k];
            if n == NONE {
                return false;
            }
            cur = n >> 2;
            if cur == t {
                return self.ring_tets.len() >= 3;
            }
            let nt = &w.tets[cur as usize];
            let Some(z) = nt.iter().copied().find(|&v| v != a && v != b && v != y) else {
                return false;
            };
            x = y;
            y = z;
        }
    }

    /// Tries to remove the edge `(a, b)` of live tet `t`; on success returns the number of tets
    /// that were around it.
    pub(crate) fn try_remove(&mut self, w: &mut Work, t: u32, a: u32, b: u32, max_re: f64) -> Option<usize> {
        if !self.walk(w, t, a, b) {
            return None;
        }
        let n = self.ring.len();
        let old_min = self.ring_tets.iter().map(|&s| w.q[s as usize]).fold(f64::INFINITY, f64::min);
        let r = &self.ring;
        // best[i][j] for j - i >= 1; chords of length 1 are polygon edges
        for i in 0..n - 1 {
            self.best[i][i + 1] = f64::INFINITY;
        }
        for len in 2..n {
            for i in 0..n - len {
                let j = i + len;
                let mut bq = f64::NEG_INFINITY;
                let mut bk = 0u8;
                for k in i + 1..j {
                    let sub = self.best[i][k].min(self.best[k][j]);
                    if sub <= bq.max(old_min) {
                        continue;
                    }
                    let top = [a, r[i], r[k], r[j]];
                    let bottom = [r[i], r[k], r[j], b];
                    if w.orient(&top) != crate::core::Sign::Positive || w.orient(&bottom) != crate::core::Sign::Positive {
                        continue;
                    }
                    let s = sub.min(w.score_of(&top));
                    if s <= bq.max(old_min) {
                        continue;
                    }
                    let s = s.min(w.score_of(&bottom));
                    if s > bq {
                        bq = s;
                        bk = k as u8;
                    }
                }
                self.best[i][j] = bq;
                self.apex[i][j] = bk;
            }
        }
        if self.best[0][n - 1] <= old_min {
            return None;
        }
        // the triangulation, chord by chord
        self.new.clear();
        let mut stack = w.take_stack();
        stack.push((n - 1) as u32);
        while let Some(code) = stack.pop() {
            let (i, j) = ((code >> 16) as usize, (code & 0xffff) as usize);
            if j < i + 2 {
                continue;
            }
            let k = self.apex[i][j] as usize;
            self.new.push([a, r[i], r[k], r[j]]);
            self.new.push([r[i], r[k], r[j], b]);
            stack.push((i as u32) << 16 | k as u32);
            stack.push((k as u32) << 16 | j as u32);
        }
        w.give_stack(stack);
        let bound = flip_radius_edge_bound(self.ring_tets.iter().map(|&s| w.corners(&w.tets[s as usize])), max_re);
        if self.new.iter().any(|t| tet_radius_edge(&w.corners(t)) > bound) {
            return None;
        }
        let region = w.region[t as usize];
        if w.replace(&self.ring_tets, &self.new, region) { Some(n) } else { None }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::RegionId;
    use crate::mesh::TetMesh;
    use crate::mesh3d::optimize::measure::Targets;
    use glam::DVec3;

    /// `n` tets around the edge from (0,0,-h) to (0,0,h), ring on the unit circle, closed by an
    /// outer layer so the ring faces are interior: returns the mesh (only the star of the edge).
    fn edge_star(n: usize, h: f64) -> TetMesh {
        let mut vertices = vec![DVec3::new(0.0, 0.0, h), DVec3::new(0.0, 0.0, -h)];
        for i in 0..n {
            // clockwise seen from a = (0, 0, h)
            let t = -std::f64::consts::TAU * i as f64 / n as f64;
            vertices.push(DVec3::new(t.cos(), t.sin(), 0.0));
        }
        let tets = (0..n).map(|i| [0, 1, 2 + i as u32, 2 + ((i + 1) % n) as u32]).collect::<Vec<_>>();
        let region_tags = vec![RegionId(1); n];
        TetMesh { vertices, tets, region_tags, ..Default::default() }
    }

    #[test]
    fn ring_orientation_and_removal() {
        for n in 3..=7 {
            let m = edge_star(n, 2.0);
            assert_eq!(m.validate(), Ok(()), "n = {n}");
            let v0 = m.volume();
            let mut w = Work::build(&m, Targets::new(15.0, 160.0)).unwrap();
            // the outer faces are hull faces, the edge's faces are interior
            let mut er = EdgeRemoval::default();
            assert!(er.walk(&w, 0, 0, 1));
            assert_eq!(er.ring.len(), n);
            // a long edge: the tets around it have a large dihedral angle at it when n is
            // small; removal replaces n tets by 2(n - 2)
            let before = w.live();
            let removed = er.try_remove(&mut w, 0, 0, 1, 2.0);
            if let Some(k) = removed {
                assert_eq!(k, n);
                assert_eq!(w.live(), before - n + 2 * (n - 2));
                let mut out = TetMesh { boundary: m.boundary.clone(), face_tags: m.face_tags.clone(), ..m.clone() };
                w.write_back(&mut out);
                assert_eq!(out.validate(), Ok(()));
                assert!((out.volume() - v0).abs() < 1e-12 * v0);
            }
            if n == 3 {
                assert_eq!(removed, Some(3), "a 3-2 flip of a flat ring improves");
            }
        }
    }
}
