//! The pairing of triangles into quadrilaterals: candidates and a maximum-weight matching.
//!
//! - Stage: second, on a valid triangle mesh.
//! - Inputs: the triangles (counter-clockwise), [`Options`].
//! - Output: [`Matching`]: the matched pairs with the strictly convex quads they make, and
//!   the triangles left unpaired.
//! - Invariants: a candidate pair shares an edge and makes a quad that is strictly convex
//!   (exact `orient2d` at its four corners, the lecture's pairing test) with a scaled
//!   Jacobian of at least `min_pair_quality`; every triangle is in at most one pair.
//!
//! The weight of a pair is `pair_bonus` plus its quad's scaled Jacobian. The matching starts
//! greedy (candidates by decreasing weight, ties by triangle index), then, from every unpaired
//! triangle in index order, a depth-first search over alternating paths (at most
//! `augment_depth` edges, a triangle at most once) finds the path of largest gain: an
//! augmenting path (ending at another unpaired triangle: one more pair) or an even one (its
//! last triangle becomes unpaired: better pairs, as many). A path is applied when its gain is
//! positive; every application raises the total weight strictly, so the rounds end. This is
//! a local-search approximation of Edmonds' maximum-weight matching: the dual graph of a
//! triangle mesh has degree at most 3, so short alternating paths find nearly all of what
//! blossoms would.

use super::Options;
use crate::core::predicates::orient2d;
use crate::core::Sign;
use crate::mesh::PlanarMesh;
use crate::mesh2d::measure::min_corner_jacobian;
use glam::DVec2;

/// Gains at most this are not worth a change (against rounding in the sums).
const MIN_GAIN: f64 = 1e-9;

/// A candidate pair: two triangles sharing an edge and the quad they make.
#[derive(Clone, Copy, Debug)]
struct Candidate {
    tris: [u32; 2],
    quad: [u32; 4],
    weight: f64,
}

/// The matched pairs and the unpaired triangles.
#[derive(Clone, Debug, Default)]
pub struct Matching {
    /// Matched pairs: the two triangles and their quad (counter-clockwise, strictly convex),
    /// by the smaller triangle index.
    pub pairs: Vec<([u32; 2], [u32; 4])>,
    /// Unpaired triangles, in index order.
    pub leftovers: Vec<u32>,
    /// Candidate pairs.
    pub candidates: usize,
    /// Pairs after the greedy start.
    pub greedy_pairs: usize,
    /// Alternating paths applied.
    pub augmentations: usize,
}

/// The candidate pairs of `mesh` (every interior edge whose two triangles pass the pairing
/// test), by edge order.
fn candidates(mesh: &PlanarMesh, min_quality: f64) -> Vec<Candidate> {
    let p = |i: u32| mesh.vertices[i as usize];
    // directed edges (min, max, triangle, local edge) sorted: the two sides of an edge meet
    let mut edges: Vec<(u32, u32, u32, u8)> = Vec::with_capacity(3 * mesh.triangles.len());
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            edges.push((a.min(b), a.max(b), t as u32, k as u8));
        }
    }
    edges.sort_unstable();
    let mut out = Vec::new();
    for w in edges.windows(2) {
        if (w[0].0, w[0].1) != (w[1].0, w[1].1) {
            continue;
        }
        let (t1, k1) = (w[0].2, w[0].3 as usize);
        let (t2, k2) = (w[1].2, w[1].3 as usize);
        let (x, y) = (mesh.triangles[t1 as usize], mesh.triangles[t2 as usize]);
        // t1 = a b c with the shared edge a -> b; t2 = b a d
        let (a, b, c) = (x[k1], x[(k1 + 1) % 3], x[(k1 + 2) % 3]);
        let d = y[(k2 + 2) % 3];
        let quad = [a, d, b, c];
        let q = quad.map(p);
        if !strictly_convex(&q) {
            continue;
        }
        let sj = min_corner_jacobian(&q);
        if sj >= min_quality {
            out.push(Candidate { tris: [t1, t2], quad, weight: sj });
        }
    }
    out
}

/// Whether a counter-clockwise quad is strictly convex (exact).
pub(super) fn strictly_convex(q: &[DVec2; 4]) -> bool {
    (0..4).all(|k| orient2d(q[(k + 3) % 4], q[k], q[(k + 1) % 4]) == Sign::Positive)
}

/// The matching state: per triangle its candidate pairs and its current pair.
struct State {
    cands: Vec<Candidate>,
    /// Per triangle: (neighbour, candidate) pairs, by neighbour.
    adj: Vec<Vec<(u32, u32)>>,
    /// Per triangle: the candidate it is matched by.
    mate: Vec<Option<u32>>,
}

impl State {
    fn other(&self, c: u32, t: u32) -> u32 {
        let [x, y] = self.cands[c as usize].tris;
        if x == t { y } else { x }
    }

    fn set(&mut self, c: u32, on: bool) {
        for t in self.cands[c as usize].tris {
            self.mate[t as usize] = if on { Some(c) } else { None };
        }
    }
}

/// The best alternating path found so far: gain, candidates to add, candidates to remove.
struct Best {
    gain: f64,
    add: Vec<u32>,
    remove: Vec<u32>,
}

/// Pairs the triangles of `mesh` (see the module docs).
pub fn match_triangles(mesh: &PlanarMesh, options: &Options) -> Matching {
    let n = mesh.triangles.len();
    let mut cands = candidates(mesh, options.min_pair_quality);
    for c in &mut cands {
        c.weight += options.pair_bonus;
    }
    let mut adj: Vec<Vec<(u32, u32)>> = vec![Vec::new(); n];
    for (k, c) in cands.iter().enumerate() {
        adj[c.tris[0] as usize].push((c.tris[1], k as u32));
        adj[c.tris[1] as usize].push((c.tris[0], k as u32));
    }
    for a in &mut adj {
        a.sort_unstable();
    }
    let mut st = State { cands, adj, mate: vec![None; n] };
    // greedy start
    let mut order: Vec<u32> = (0..st.cands.len() as u32).collect();
    order.sort_by(|&i, &j| {
        let (a, b) = (&st.cands[i as usize], &st.cands[j as usize]);
        b.weight.total_cmp(&a.weight).then(a.tris.cmp(&b.tris))
    });
    for c in order {
        let [x, y] = st.cands[c as usize].tris;
        if st.mate[x as usize].is_none() && st.mate[y as usize].is_none() {
            st.set(c, true);
        }
    }
    let greedy_pairs = st.mate.iter().filter(|m| m.is_some()).count() / 2;
    // alternating paths from the unpaired triangles
    let mut augmentations = 0;
    let mut s = Search { in_path: vec![false; n], add: Vec::new(), remove: Vec::new(), best: Best { gain: 0.0, add: Vec::new(), remove: Vec::new() } };
    for _ in 0..options.augment_rounds {
        let mut changed = false;
        for u in 0..n as u32 {
            if st.mate[u as usize].is_some() || st.adj[u as usize].is_empty() {
                continue;
            }
            s.best = Best { gain: MIN_GAIN, add: Vec::new(), remove: Vec::new() };
            s.in_path[u as usize] = true;
            search(&st, u, options.augment_depth, 0.0, &mut s);
            s.in_path[u as usize] = false;
            let best = std::mem::replace(&mut s.best, Best { gain: 0.0, add: Vec::new(), remove: Vec::new() });
            if best.add.is_empty() {
                continue;
            }
            for &c in &best.remove {
                st.set(c, false);
            }
            for &c in &best.add {
                st.set(c, true);
            }
            augmentations += 1;
            changed = true;
        }
        if !changed {
            break;
        }
    }
    let mut out = Matching { candidates: st.cands.len(), greedy_pairs, augmentations, ..Matching::default() };
    for t in 0..n as u32 {
        match st.mate[t as usize] {
            None => out.leftovers.push(t),
            Some(c) => {
                let cand = &st.cands[c as usize];
                if cand.tris[0].min(cand.tris[1]) == t {
                    out.pairs.push((cand.tris, cand.quad));
                }
            }
        }
    }
    out
}

/// The path being searched: its triangles, the candidates it adds and removes, the best
/// path found.
struct Search {
    in_path: Vec<bool>,
    add: Vec<u32>,
    remove: Vec<u32>,
    best: Best,
}

/// Depth-first search of alternating paths from `x` (whose pair, if any, is already
/// removed on the path), at most `depth` more edges, the gain so far `acc`.
fn search(st: &State, x: u32, depth: usize, acc: f64, s: &mut Search) {
    if depth == 0 {
        return;
    }
    for &(v, c) in &st.adj[x as usize] {
        if s.in_path[v as usize] {
            continue;
        }
        let w = st.cands[c as usize].weight;
        let Some(mc) = st.mate[v as usize] else {
            // augmenting: v was unpaired
            if acc + w > s.best.gain {
                s.best = Best { gain: acc + w, add: s.add.iter().copied().chain([c]).collect(), remove: s.remove.clone() };
            }
            continue;
        };
        let v2 = st.other(mc, v);
        if s.in_path[v2 as usize] {
            continue;
        }
        let acc2 = acc + w - st.cands[mc as usize].weight;
        s.add.push(c);
        s.remove.push(mc);
        if acc2 > s.best.gain {
            // even: v2 becomes unpaired
            s.best = Best { gain: acc2, add: s.add.clone(), remove: s.remove.clone() };
        }
        if depth >= 3 {
            s.in_path[v as usize] = true;
            s.in_path[v2 as usize] = true;
            search(st, v2, depth - 2, acc2, s);
            s.in_path[v as usize] = false;
            s.in_path[v2 as usize] = false;
        }
        s.add.pop();
        s.remove.pop();
    }
}
