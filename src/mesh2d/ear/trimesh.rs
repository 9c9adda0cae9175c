//! A triangle list with adjacency for the refinement after ear cutting: Lawson flips that
//! never cross a domain segment, point insertion inside a triangle or on an interior edge,
//! point location by a walk that stops at domain segments.
//!
//! - Inputs: points and counter-clockwise triangles that tile a domain conformingly, and
//!   which edges are domain segments (fixed).
//! - Output: the same tiling changed in place by flips and insertions.
//! - Invariants: every triangle stays strictly counter-clockwise (each flip and split is
//!   checked with exact [`orient2d`]); a fixed edge is never flipped nor split; an edge is
//!   flipped only when the opposite point is strictly inside the circumcircle (exact
//!   [`incircle`]), so Lawson's algorithm ends in the constrained Delaunay triangulation.
//!   Every triangle created or changed is listed in `touched`.

use crate::core::predicates::{incircle, orient2d};
use crate::core::Sign;
use glam::DVec2;

/// No neighbour (a domain segment on the boundary).
pub(crate) const NONE: u32 = u32::MAX;

/// The smallest corner angle of a triangle, degrees.
pub(crate) fn min_angle(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    let ang = |p: DVec2, q: DVec2, r: DVec2| {
        let (u, v) = (q - p, r - p);
        u.perp_dot(v).abs().atan2(u.dot(v)).to_degrees()
    };
    ang(a, b, c).min(ang(b, c, a)).min(ang(c, a, b))
}

/// Where a point lies in a [`TriMesh`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Location {
    /// Strictly inside the triangle.
    Inside(u32),
    /// On edge `k` (opposite corner `k`) of the triangle, not at its ends.
    OnEdge(u32, usize),
    /// Behind a fixed edge or the boundary, on a vertex, or the walk did not end.
    Blocked,
}

/// Triangles with adjacency (see the module docs).
#[derive(Clone, Debug)]
pub(crate) struct TriMesh {
    /// Points.
    pub pts: Vec<DVec2>,
    /// Counter-clockwise triangles.
    pub tris: Vec<[u32; 3]>,
    /// Per triangle, the neighbour across edge `k` (the edge opposite corner `k`), or [`NONE`].
    pub adj: Vec<[u32; 3]>,
    /// Per triangle, whether edge `k` is a domain segment.
    pub fixed: Vec<[bool; 3]>,
    /// Flips done so far.
    pub flips: usize,
    /// Triangles created or changed since the caller last drained this list.
    pub touched: Vec<u32>,
}

/// Triangle `t = (a, b, c)` (`a` its vertex `k`) and triangle `u` across its edge `b c`
/// (opposite `a`), whose vertex opposite that edge is `q`: the neighbours (`n`) and fixed
/// flags (`f`) across the four outer edges, `[c a, a b, b q, q c]`.
struct Diamond {
    u: u32,
    a: u32,
    b: u32,
    c: u32,
    q: u32,
    n: [u32; 4],
    f: [bool; 4],
}

impl TriMesh {
    /// Builds the adjacency; `None` if an edge is in more than two triangles or twice in the
    /// same direction (not a conforming tiling).
    pub(crate) fn new(pts: Vec<DVec2>, tris: Vec<[u32; 3]>, is_fixed: &dyn Fn(u32, u32) -> bool) -> Option<TriMesh> {
        let mut edges: Vec<(u32, u32, u32, usize)> = Vec::with_capacity(tris.len() * 3);
        for (t, tri) in tris.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (tri[(k + 1) % 3], tri[(k + 2) % 3]);
                edges.push((a.min(b), a.max(b), t as u32, k));
            }
        }
        edges.sort_unstable();
        let mut adj = vec![[NONE; 3]; tris.len()];
        let mut fixed = vec![[false; 3]; tris.len()];
        let mut i = 0;
        while i < edges.len() {
            let (a, b, t, k) = edges[i];
            let f = is_fixed(a, b);
            if i + 1 < edges.len() && edges[i + 1].0 == a && edges[i + 1].1 == b {
                let (_, _, u, j) = edges[i + 1];
                if i + 2 < edges.len() && edges[i + 2].0 == a && edges[i + 2].1 == b {
                    return None;
                }
                if tris[t as usize][(k + 1) % 3] == tris[u as usize][(j + 1) % 3] {
                    return None;
                }
                adj[t as usize][k] = u;
                adj[u as usize][j] = t;
                fixed[t as usize][k] = f;
                fixed[u as usize][j] = f;
                i += 2;
            } else {
                fixed[t as usize][k] = true;
                i += 1;
            }
        }
        Some(TriMesh { pts, tris, adj, fixed, flips: 0, touched: Vec::new() })
    }

    fn p(&self, v: u32) -> DVec2 {
        self.pts[v as usize]
    }

    fn relink(&mut self, n: u32, old: u32, new: u32) {
        if n != NONE {
            if let Some(k) = self.adj[n as usize].iter().position(|&x| x == old) {
                self.adj[n as usize][k] = new;
            }
        }
    }

    /// Whether edge `k` of `t` is not locally Delaunay and may be flipped.
    fn illegal(&self, t: u32, k: usize) -> bool {
        let u = self.adj[t as usize][k];
        if u == NONE || self.fixed[t as usize][k] {
            return false;
        }
        let tri = self.tris[t as usize];
        let Some(j) = self.adj[u as usize].iter().position(|&x| x == t) else {
            return false;
        };
        let q = self.tris[u as usize][j];
        incircle(self.p(tri[0]), self.p(tri[1]), self.p(tri[2]), self.p(q)) == Sign::Positive
    }

    /// The two triangles across edge `k` of `t` (`None` when the edge is fixed or on the
    /// boundary).
    fn diamond(&self, t: u32, k: usize) -> Option<Diamond> {
        let u = self.adj[t as usize][k];
        if u == NONE || self.fixed[t as usize][k] {
            return None;
        }
        let j = self.adj[u as usize].iter().position(|&x| x == t)?;
        let tri = self.tris[t as usize];
        let (at, au) = (self.adj[t as usize], self.adj[u as usize]);
        let (ft, fu) = (self.fixed[t as usize], self.fixed[u as usize]);
        let (k1, k2, j1, j2) = ((k + 1) % 3, (k + 2) % 3, (j + 1) % 3, (j + 2) % 3);
        Some(Diamond { u, a: tri[k], b: tri[k1], c: tri[k2], q: self.tris[u as usize][j], n: [at[k1], at[k2], au[j1], au[j2]], f: [ft[k1], ft[k2], fu[j1], fu[j2]] })
    }

    /// Flips edge `k` of `t`; returns the two new triangles (both hold `t[k]`), or `None`
    /// when the edge is fixed, on the boundary, or its quadrilateral is not strictly convex.
    pub(crate) fn flip(&mut self, t: u32, k: usize) -> Option<[u32; 2]> {
        let Diamond { u, a, b, c, q, n: [n_ca, n_ab, n_bq, n_qc], f: [f_ca, f_ab, f_bq, f_qc] } = self.diamond(t, k)?;
        if orient2d(self.p(a), self.p(b), self.p(q)) != Sign::Positive || orient2d(self.p(a), self.p(q), self.p(c)) != Sign::Positive {
            return None;
        }
        self.tris[t as usize] = [a, b, q];
        self.adj[t as usize] = [n_bq, u, n_ab];
        self.fixed[t as usize] = [f_bq, false, f_ab];
        self.tris[u as usize] = [a, q, c];
        self.adj[u as usize] = [n_qc, n_ca, t];
        self.fixed[u as usize] = [f_qc, f_ca, false];
        self.relink(n_bq, u, t);
        self.relink(n_ca, t, u);
        self.flips += 1;
        self.touched.extend([t, u]);
        Some([t, u])
    }

    /// Lawson flips from the triangles on `stack`, each checked across its edge opposite
    /// vertex `v` (the point just inserted).
    fn legalize_around(&mut self, v: u32, mut stack: Vec<u32>) {
        while let Some(t) = stack.pop() {
            let Some(k) = self.tris[t as usize].iter().position(|&x| x == v) else {
                continue;
            };
            if self.illegal(t, k) {
                if let Some(pair) = self.flip(t, k) {
                    stack.extend(pair);
                }
            }
        }
    }

    /// Flips until every edge that is not fixed is locally Delaunay (Lawson); returns the
    /// flips done.
    pub(crate) fn make_delaunay(&mut self) -> usize {
        let before = self.flips;
        loop {
            let mut any = false;
            for t in 0..self.tris.len() as u32 {
                for k in 0..3 {
                    if self.illegal(t, k) && self.flip(t, k).is_some() {
                        any = true;
                    }
                }
            }
            if !any {
                return self.flips - before;
            }
        }
    }

    /// Walks from `start` towards `p`, stopping at fixed edges (see [`Location`]).
    pub(crate) fn locate(&self, start: u32, p: DVec2) -> Location {
        let mut t = start;
        for step in 0..self.tris.len() + 16 {
            let tri = self.tris[t as usize];
            let o: [Sign; 3] = std::array::from_fn(|k| orient2d(self.p(tri[(k + 1) % 3]), self.p(tri[(k + 2) % 3]), p));
            if let Some(k) = (0..3).map(|i| (i + step) % 3).find(|&k| o[k] == Sign::Negative) {
                let u = self.adj[t as usize][k];
                if u == NONE || self.fixed[t as usize][k] {
                    return Location::Blocked;
                }
                t = u;
                continue;
            }
            let zeros: Vec<usize> = (0..3).filter(|&k| o[k] == Sign::Zero).collect();
            return match zeros.len() {
                0 => Location::Inside(t),
                1 => Location::OnEdge(t, zeros[0]),
                _ => Location::Blocked,
            };
        }
        Location::Blocked
    }

    /// Inserts `p` where it was located and restores the Delaunay property around it;
    /// returns its index, or `None` for [`Location::Blocked`] or a fixed edge.
    pub(crate) fn insert(&mut self, p: DVec2, at: Location) -> Option<u32> {
        let v = self.pts.len() as u32;
        match at {
            Location::Blocked => None,
            Location::Inside(t) => {
                let [a, b, c] = self.tris[t as usize];
                let [n0, n1, n2] = self.adj[t as usize];
                let [f0, f1, f2] = self.fixed[t as usize];
                self.pts.push(p);
                let (t1, t2) = (self.tris.len() as u32, self.tris.len() as u32 + 1);
                self.tris[t as usize] = [v, b, c];
                self.adj[t as usize] = [n0, t1, t2];
                self.fixed[t as usize] = [f0, false, false];
                self.tris.extend([[v, c, a], [v, a, b]]);
                self.adj.extend([[n1, t2, t], [n2, t, t1]]);
                self.fixed.extend([[f1, false, false], [f2, false, false]]);
                self.relink(n1, t, t1);
                self.relink(n2, t, t2);
                self.touched.extend([t, t1, t2]);
                self.legalize_around(v, vec![t, t1, t2]);
                Some(v)
            }
            Location::OnEdge(t, k) => {
                let Diamond { u, a, b, c, q, n: [n_ca, n_ab, n_bq, n_qc], f: [f_ca, f_ab, f_bq, f_qc] } = self.diamond(t, k)?;
                self.pts.push(p);
                let (t2, u2) = (self.tris.len() as u32, self.tris.len() as u32 + 1);
                self.tris[t as usize] = [a, b, v];
                self.adj[t as usize] = [u2, t2, n_ab];
                self.fixed[t as usize] = [false, false, f_ab];
                self.tris[u as usize] = [q, c, v];
                self.adj[u as usize] = [t2, u2, n_qc];
                self.fixed[u as usize] = [false, false, f_qc];
                self.tris.extend([[a, v, c], [q, v, b]]);
                self.adj.extend([[u, n_ca, t], [t, n_bq, u]]);
                self.fixed.extend([[false, f_ca, false], [false, f_bq, false]]);
                self.relink(n_ca, t, t2);
                self.relink(n_bq, u, u2);
                self.touched.extend([t, u, t2, u2]);
                self.legalize_around(v, vec![t, u, t2, u2]);
                Some(v)
            }
        }
    }
}
