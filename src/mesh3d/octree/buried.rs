//! Where the input surface is not the boundary of what stuffing meshes: sheets inside the
//! stuffed volume (a dowel's wall where it sits in a plate's hole, the walls where two
//! bodies overlap) or outside it (an inward shell inside nothing). The boundary of
//! `w > 1/2` lies on the input where the winding number is above one half on one side and
//! below it on the other; elsewhere the input is *buried*, and the mesh is rightly far from
//! it, so the deviation leaves it out.
//!
//! Stage: the octree mesher's report (`deviation.rs`). Input: the [`Winding`] of the input.
//! Output: [`Buried::piece`], asked only for the pieces whose distance would pass the cell.
//!
//! # Invariants
//! - Along a triangle the winding numbers on its two sides change only where another
//!   triangle meets it. A piece of triangle `t` is *clean* when every triangle that meets
//!   `t` (the exact pairwise test of `mesh::topology`, shared vertices and edges allowed) is
//!   farther from the piece's centroid than its corners are, or lies in `t`'s plane and
//!   covers the piece (a coincident wall, which the probe crosses with `t`). Only a clean
//!   piece is judged; any other is kept (the deviation stays an upper bound).
//! - A clean piece is judged by the winding number at its centroid a step off each side,
//!   the step a quarter of the distance to the nearest other triangle (not a coverer), at
//!   most the piece's size: the jump between the two must be a whole number (else the
//!   piece is kept), and the piece is buried when both sides are on one side of one half.
//! - The pairwise test runs once per surface ([`Winding::meets`]), when first asked; nothing
//!   depends on threads.

use super::winding::Winding;
use crate::core::closest::point_triangle_distance;
use glam::DVec3;

/// The buried-sheet judge of one input surface; see the module docs.
pub struct Buried<'a> {
    w: &'a Winding<'a>,
}

/// How a piece relates to the boundary of the stuffed volume.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Side {
    /// On the boundary: measured.
    Boundary,
    /// Inside or outside on both sides: left out, with every piece of it.
    Buried,
    /// Another triangle meets the piece, or the probe was not clear: measured, its smaller
    /// pieces asked again.
    Unsure,
}

impl<'a> Buried<'a> {
    /// The judge of `w`'s surface.
    pub fn new(w: &'a Winding<'a>) -> Buried<'a> {
        Buried { w }
    }

    /// Where piece `p` of input triangle `t` lies (its corners in `t`); see the module docs.
    pub fn piece(&self, t: usize, p: &[DVec3; 3]) -> Side {
        let s = self.w.surface();
        let tri = s.corners(t);
        let normal = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
        let area2 = normal.length();
        if !(area2 > 0.0) {
            return Side::Unsure;
        }
        let n = normal / area2;
        let c = (p[0] + p[1] + p[2]) / 3.0;
        let reach = p.iter().map(|q| q.distance(c)).fold(0.0, f64::max);
        if !(reach > 0.0) {
            return Side::Unsure;
        }
        let scale = tri.iter().map(|q| q.length()).fold(0.0, f64::max) + reach;
        let tol = 1e-9 * scale;
        // the triangles meeting `t` that cover the piece in its plane
        let mut covers: Vec<u32> = Vec::new();
        for &o in &self.w.meets()[t] {
            let q = s.corners(o as usize);
            if point_triangle_distance(c, q) > reach * (1.0 + 1e-9) + tol {
                continue;
            }
            let coplanar = q.iter().all(|x| (*x - tri[0]).dot(n).abs() <= tol);
            if coplanar && p.iter().all(|x| point_triangle_distance(*x, q) <= tol) {
                covers.push(o);
            } else {
                return Side::Unsure;
            }
        }
        // the probe's step: clear of every other triangle
        let near = self.w.bvh().nearest_from(c, None, |o| {
            if o as usize == t || covers.contains(&o) { f64::INFINITY } else { point_triangle_distance(c, s.corners(o as usize)) }
        });
        let step = near.map_or(reach, |(_, d)| (0.25 * d).min(reach));
        if !(step > tol) {
            return Side::Unsure;
        }
        let (front, back) = (self.w.at(c + n * step), self.w.at(c - n * step));
        let jump = back - front;
        if (jump - jump.round()).abs() > 0.1 {
            return Side::Unsure;
        }
        if (front > super::winding::INSIDE) == (back > super::winding::INSIDE) { Side::Buried } else { Side::Boundary }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh3d::octree::tests::{cube_at, together};

    /// A small cube wholly inside a big one: its faces are buried; the big cube's are the
    /// boundary; a piece of the big cube's face is the boundary too.
    #[test]
    fn a_cube_inside_a_cube_is_buried() {
        let s = together(&[cube_at(DVec3::ZERO, 4.0), cube_at(DVec3::splat(1.0), 1.0)]);
        let w = Winding::new(&s);
        let b = Buried::new(&w);
        for k in 0..24 {
            let want = if k < 12 { Side::Boundary } else { Side::Buried };
            assert_eq!(b.piece(k, &s.corners(k)), want, "triangle {k}");
        }
        let [a, bb, c] = s.corners(0);
        assert_eq!(b.piece(0, &[a, (a + bb) * 0.5, (a + c) * 0.5]), Side::Boundary);
    }

    /// Two cubes overlapping by half: the faces crossing the other cube are unsure as wholes;
    /// a piece of one wholly inside the other is buried, one wholly outside is the boundary.
    #[test]
    fn overlapping_cubes_are_unsure_where_they_cross() {
        let s = together(&[cube_at(DVec3::ZERO, 1.0), cube_at(DVec3::new(0.5, 0.0, 0.0), 1.0)]);
        let w = Winding::new(&s);
        let b = Buried::new(&w);
        // the first cube's triangle on x = 1, inside the second cube: buried, but the second
        // cube's faces y = 0 ... meet it along its edges
        let on = |t: usize, axis: usize, at: f64| s.corners(t).iter().all(|q| q[axis] == at);
        let x1 = (0..12).find(|&t| on(t, 0, 1.0)).unwrap();
        let p = s.corners(x1);
        let c = (p[0] + p[1] + p[2]) / 3.0;
        let small = p.map(|q| c + (q - c) * 0.2);
        assert_eq!(b.piece(x1, &small), Side::Buried);
        // the first cube's triangle on y = 0: half inside the second cube, unsure whole
        let y0 = (0..12).find(|&t| on(t, 1, 0.0)).unwrap();
        assert_eq!(b.piece(y0, &s.corners(y0)), Side::Unsure);
        // a piece of it at its corner on x = 0, outside the second cube: the boundary
        let p = s.corners(y0);
        let k = (0..3).find(|&k| p[k].x == 0.0).unwrap();
        let a = p[k];
        let near0 = [a, a + (p[(k + 1) % 3] - a) * 0.2, a + (p[(k + 2) % 3] - a) * 0.2];
        assert_eq!(b.piece(y0, &near0), Side::Boundary);
    }
}
