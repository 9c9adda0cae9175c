//! The triangle-array structure the refinement works on: three vertices and three
//! neighbours per triangle, constrained-edge flags, one incident triangle per vertex.
//!
//! - Stage: shared by every stage after the initial triangulation.
//! - Layout: triangle `t` has vertices `tv[t]` counter-clockwise; its edge `i` goes from
//!   `tv[t][(i + 1) % 3]` to `tv[t][(i + 2) % 3]` (opposite vertex `i`); `tn[t][i]` is the
//!   triangle across edge `i` ([`NONE`] on the domain's boundary); bit `i` of `cons[t]` is set
//!   when edge `i` is a piece of a domain segment (a subsegment).
//! - Invariants: every triangle is positively oriented (exact); neighbours are mutual; every
//!   boundary edge (no neighbour) is constrained; `vtri[v]` is a triangle having `v`.
//! - Vertices: the domain's points first (same indices), then Steiner points; `on_seg[v]` is
//!   the domain segment a Steiner point lies on ([`NONE`] for the others).

use crate::core::predicates::orient2d;
use crate::core::Sign;
use glam::DVec2;

/// No triangle, no segment.
pub(crate) const NONE: u32 = u32::MAX;

/// Where a point lies, found by [`Tri::locate`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Located {
    /// Strictly inside triangle `t`, or on its non-constrained edge.
    Inside(u32),
    /// On a vertex (the point would be a duplicate).
    Vertex,
    /// The walk met constrained edge `i` of triangle `t` (the point is on it or beyond it).
    Blocked(u32, u8),
    /// The walk did not end (not expected on a constrained Delaunay triangulation).
    Lost,
}

/// The triangulation (see the module docs).
#[derive(Clone, Debug, Default)]
pub(crate) struct Tri {
    /// Vertex positions.
    pub pts: Vec<DVec2>,
    /// Per vertex: the domain segment a Steiner point lies on, [`NONE`] otherwise.
    pub on_seg: Vec<u32>,
    /// Per vertex: one triangle having it.
    pub vtri: Vec<u32>,
    /// Triangle vertices, counter-clockwise.
    pub tv: Vec<[u32; 3]>,
    /// Triangle neighbours across edges `0, 1, 2`.
    pub tn: Vec<[u32; 3]>,
    /// Constrained-edge bits.
    pub cons: Vec<u8>,
    /// How many of the first vertices are the domain's points.
    pub inputs: usize,
}

/// The next corner.
#[inline]
pub(crate) fn next(i: usize) -> usize {
    if i == 2 { 0 } else { i + 1 }
}

/// The previous corner.
#[inline]
pub(crate) fn prev(i: usize) -> usize {
    if i == 0 { 2 } else { i - 1 }
}

impl Tri {
    /// The positions of triangle `t`'s vertices.
    #[inline]
    pub fn corners(&self, t: u32) -> [DVec2; 3] {
        let v = self.tv[t as usize];
        [self.pts[v[0] as usize], self.pts[v[1] as usize], self.pts[v[2] as usize]]
    }

    /// The end points of edge `i` of `t`.
    #[inline]
    pub fn edge(&self, t: u32, i: usize) -> (u32, u32) {
        let v = self.tv[t as usize];
        (v[next(i)], v[prev(i)])
    }

    /// Whether edge `i` of `t` is constrained.
    #[inline]
    pub fn constrained(&self, t: u32, i: usize) -> bool {
        self.cons[t as usize] & (1 << i) != 0
    }

    /// The edge index of `t`'s neighbour `nb` that points back at `t`.
    #[inline]
    pub fn back(&self, nb: u32, t: u32) -> usize {
        let n = self.tn[nb as usize];
        if n[0] == t {
            0
        } else if n[1] == t {
            1
        } else {
            2
        }
    }

    /// Walks from `start` towards `p` (a visibility walk with exact orientations, preferring
    /// edges that are not constrained), never crossing a constrained edge.
    pub fn locate(&self, start: u32, p: DVec2) -> Located {
        let mut t = start;
        let limit = self.tv.len() + 16;
        for _ in 0..limit {
            let v = self.tv[t as usize];
            let q = [self.pts[v[0] as usize], self.pts[v[1] as usize], self.pts[v[2] as usize]];
            let mut blocked = None;
            let mut moved = false;
            let mut zeros = 0;
            let mut zero_edge = 0u8;
            for i in 0..3 {
                match orient2d(q[next(i)], q[prev(i)], p) {
                    Sign::Negative => {
                        let nb = self.tn[t as usize][i];
                        if nb == NONE || self.constrained(t, i) {
                            blocked = Some(i as u8);
                        } else {
                            t = nb;
                            moved = true;
                            break;
                        }
                    }
                    Sign::Zero => {
                        zeros += 1;
                        zero_edge = i as u8;
                    }
                    Sign::Positive => {}
                }
            }
            if moved {
                continue;
            }
            if let Some(i) = blocked {
                return Located::Blocked(t, i);
            }
            if zeros >= 2 {
                return Located::Vertex;
            }
            if zeros == 1 && self.constrained(t, zero_edge as usize) {
                return Located::Blocked(t, zero_edge);
            }
            return Located::Inside(t);
        }
        Located::Lost
    }

    /// The triangle and edge index of the edge from `a` to `b` (counter-clockwise in the
    /// triangle), by a turn around `a`; `None` if there is none.
    pub fn find_edge(&self, a: u32, b: u32) -> Option<(u32, usize)> {
        let start = self.vtri[a as usize];
        if start == NONE {
            return None;
        }
        // turn one way around `a`, then the other (a boundary vertex has a fan, not a wheel)
        for dir in 0..2 {
            let mut t = start;
            for _ in 0..self.tv.len() + 1 {
                let v = self.tv[t as usize];
                let k = v.iter().position(|&x| x == a)?;
                if v[next(k)] == b {
                    return Some((t, prev(k)));
                }
                // across the edge from a to v[next(k)] (edge prev(k)) or into a (edge next(k))
                let e = if dir == 0 { prev(k) } else { next(k) };
                let nb = self.tn[t as usize][e];
                if nb == NONE || nb == start {
                    break;
                }
                t = nb;
            }
        }
        None
    }
}
