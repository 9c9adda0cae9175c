//! Point insertion by Bowyer and Watson's cavity, walled by the constrained edges.
//!
//! - Stage: every insertion of the refinement (a free point, or a point splitting a
//!   subsegment).
//! - Inputs: the [`Tri`], the point, a seed triangle holding it (for a split: the triangle
//!   on the subsegment's inside), and, for a free point, the diametral-lens parameter when
//!   encroachment must refuse it.
//! - Output: the new vertex and the fan of new triangles ([`Scratch::created`]); or the
//!   subsegments the point would encroach ([`Scratch::encroached`], nothing changed); or a
//!   refusal (nothing changed).
//! - Invariants kept: the cavity is the connected set of triangles whose circumcircle holds
//!   the point strictly (exact in-circle), never crossing a constrained edge; before anything
//!   changes, every new triangle is checked positive by the exact orientation (a cavity
//!   triangle whose edge the point does not see is left out, and the cavity found again) and
//!   the cavity is checked to be a disk with every vertex on its boundary.

use super::tri::{Tri, NONE};
use crate::core::predicates::{incircle, orient2d};
use crate::core::Sign;
use glam::DVec2;

/// One edge of the cavity's boundary, counter-clockwise around the cavity.
#[derive(Clone, Copy, Debug)]
struct Bedge {
    a: u32,
    b: u32,
    /// The triangle outside, [`NONE`] on the domain's boundary.
    nb: u32,
    /// Its edge index pointing back.
    back: u8,
    cons: bool,
    /// The cavity triangle it belongs to.
    owner: u32,
}

/// Buffers reused by every insertion.
#[derive(Clone, Debug, Default)]
pub(crate) struct Scratch {
    stamp: Vec<u32>,
    epoch: u32,
    cavity: Vec<u32>,
    boundary: Vec<Bedge>,
    banned: Vec<u32>,
    start_of: Vec<u32>,
    vstamp: Vec<u32>,
    /// The triangles the last successful insertion created.
    pub created: Vec<u32>,
    /// The subsegments `(a, b)` (as their inside triangle runs them) the last refused point
    /// encroaches.
    pub encroached: Vec<(u32, u32)>,
}

/// What to insert.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Kind {
    /// A point inside the domain; `Some(lens)`: refuse it if it encroaches a subsegment of
    /// its cavity's boundary (see [`encroaches`]).
    Free(Option<f64>),
    /// A point on the subsegment that is edge `i` of the seed triangle.
    Split(u8),
}

/// The result of [`insert`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Outcome {
    /// Inserted as this vertex.
    Inserted(u32),
    /// Not inserted: it encroaches the subsegments in [`Scratch::encroached`].
    Encroaches,
    /// Not inserted: a duplicate, or a cavity that could not be made valid.
    Refused,
}

/// Whether `p` encroaches the subsegment `a b`: the angle `a p b` is at least
/// `180° - 2θ` (Triangle's diametral lens; `lens = cos²(2θ)`, and `lens = 0` is the
/// diametral circle, an angle over 90°).
#[inline]
pub(crate) fn encroaches(a: DVec2, b: DVec2, p: DVec2, lens: f64) -> bool {
    let (u, v) = (a - p, b - p);
    let dot = u.dot(v);
    dot < 0.0 && dot * dot >= lens * u.length_squared() * v.length_squared()
}

/// Inserts `p` (see the module docs).
pub(crate) fn insert(tri: &mut Tri, sc: &mut Scratch, p: DVec2, seed: u32, kind: Kind) -> Outcome {
    sc.banned.clear();
    sc.encroached.clear();
    if sc.stamp.len() < tri.tv.len() {
        sc.stamp.resize(tri.tv.len().max(1024) * 2, 0);
    }
    if sc.vstamp.len() < tri.pts.len() + 1 {
        sc.vstamp.resize((tri.pts.len() + 1).max(1024) * 2, 0);
        sc.start_of.resize(sc.vstamp.len(), NONE);
    }
    let split = match kind {
        Kind::Split(i) => Some(i as usize),
        Kind::Free(_) => None,
    };
    let mut found = false;
    for _attempt in 0..32 {
        if find_cavity(tri, sc, p, seed, split) {
            found = true;
            break;
        }
        if sc.banned.last() == Some(&seed) {
            return Outcome::Refused;
        }
    }
    if !found {
        return Outcome::Refused;
    }
    if let Kind::Free(Some(lens)) = kind {
        for e in &sc.boundary {
            if e.cons && encroaches(tri.pts[e.a as usize], tri.pts[e.b as usize], p, lens) {
                sc.encroached.push((e.a, e.b));
            }
        }
        if !sc.encroached.is_empty() {
            return Outcome::Encroaches;
        }
    }
    commit(tri, sc, p, seed, split);
    Outcome::Inserted(tri.pts.len() as u32 - 1)
}

/// Finds the cavity and its boundary; false (with the culprit appended to `banned`) if a
/// boundary edge is not seen from `p` or the cavity is not a disk.
fn find_cavity(tri: &Tri, sc: &mut Scratch, p: DVec2, seed: u32, split: Option<usize>) -> bool {
    sc.epoch = sc.epoch.wrapping_add(1);
    if sc.epoch == 0 {
        sc.stamp.iter_mut().for_each(|s| *s = 0);
        sc.vstamp.iter_mut().for_each(|s| *s = 0);
        sc.epoch = 1;
    }
    let epoch = sc.epoch;
    sc.cavity.clear();
    sc.boundary.clear();
    sc.cavity.push(seed);
    sc.stamp[seed as usize] = epoch;
    let mut k = 0;
    while k < sc.cavity.len() {
        let t = sc.cavity[k];
        k += 1;
        for i in 0..3 {
            let nb = tri.tn[t as usize][i];
            if nb == NONE || tri.constrained(t, i) || sc.stamp[nb as usize] == epoch || sc.banned.contains(&nb) {
                continue;
            }
            let q = tri.corners(nb);
            if incircle(q[0], q[1], q[2], p) == Sign::Positive {
                sc.stamp[nb as usize] = epoch;
                sc.cavity.push(nb);
            }
        }
    }
    for &t in &sc.cavity {
        for i in 0..3 {
            if split == Some(i) && t == seed {
                continue;
            }
            let nb = tri.tn[t as usize][i];
            if nb != NONE && !tri.constrained(t, i) && sc.stamp[nb as usize] == epoch {
                continue;
            }
            let (a, b) = tri.edge(t, i);
            let back = if nb == NONE { 0 } else { tri.back(nb, t) as u8 };
            sc.boundary.push(Bedge { a, b, nb, back, cons: tri.constrained(t, i), owner: t });
        }
    }
    for e in &sc.boundary {
        if orient2d(tri.pts[e.a as usize], tri.pts[e.b as usize], p) != Sign::Positive {
            sc.banned.push(e.owner);
            return false;
        }
    }
    // a disk with every vertex on its boundary: k + 2 boundary edges (the split edge among
    // them), each vertex starting one
    let expected = sc.cavity.len() + 2 - usize::from(split.is_some());
    if sc.boundary.len() != expected {
        sc.banned.push(seed);
        return false;
    }
    for e in &sc.boundary {
        if sc.vstamp[e.a as usize] == epoch {
            sc.banned.push(seed);
            return false;
        }
        sc.vstamp[e.a as usize] = epoch;
    }
    true
}

/// Replaces the cavity by the fan around the new vertex `p`.
fn commit(tri: &mut Tri, sc: &mut Scratch, p: DVec2, seed: u32, split: Option<usize>) {
    let pv = tri.pts.len() as u32;
    tri.pts.push(p);
    tri.on_seg.push(NONE);
    tri.vtri.push(NONE);
    // the split edge's ends: the fan has no triangle starting at `sa`
    let (sa, sb) = match split {
        Some(i) => tri.edge(seed, i),
        None => (NONE, NONE),
    };
    sc.created.clear();
    for (j, e) in sc.boundary.iter().enumerate() {
        let s = if j < sc.cavity.len() {
            sc.cavity[j]
        } else {
            tri.tv.push([0; 3]);
            tri.tn.push([NONE; 3]);
            tri.cons.push(0);
            tri.tv.len() as u32 - 1
        };
        tri.tv[s as usize] = [e.a, e.b, pv];
        tri.tn[s as usize] = [NONE, NONE, e.nb];
        let mut c = if e.cons { 4 } else { 0 };
        if e.b == sa {
            c |= 1; // edge b -> p is the first half of the split subsegment
        }
        if e.a == sb {
            c |= 2; // edge p -> a is its second half
        }
        tri.cons[s as usize] = c;
        if e.nb != NONE {
            tri.tn[e.nb as usize][e.back as usize] = s;
        }
        sc.start_of[e.a as usize] = s;
        // both ends: a split subsegment's far end starts no fan edge, and its old triangle
        // may have been in the cavity
        tri.vtri[e.b as usize] = s;
        tri.vtri[e.a as usize] = s;
        sc.created.push(s);
    }
    for &s in &sc.created {
        let b = tri.tv[s as usize][1];
        if b == sa {
            continue;
        }
        let t2 = sc.start_of[b as usize];
        tri.tn[s as usize][0] = t2;
        tri.tn[t2 as usize][1] = s;
    }
    tri.vtri[pv as usize] = sc.created[0];
}
