//! Where the input surface is not the boundary of what stuffing meshes: sheets inside the
//! stuffed volume (a dowel's wall where it sits in a plate's hole, the walls where two
//! bodies overlap) or outside it (an inward shell inside nothing). The boundary of
//! `w > 1/2` lies on the input where the winding number is above one half on one side and
//! below it on the other; elsewhere the input is *buried*, and the mesh is rightly far from
//! it, so the deviation leaves it out.
//!
//! Stage: the octree mesher's report (`deviation.rs`). Input: the [`Winding`] of the input.
//! Output: [`Buried::piece`], asked only for the pieces whose distance would pass the cell.
//! Why the seal: `pins.glb`'s dowels sit in its plate's holes with gaps of about 0.002
//! between the two facetings; those walls, half the plate's thickness from the mesh's
//! boundary, were measured at 1.3 to 2.6 cells at every cell tried.
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
//! - *Sealed*: where shells cross each other (a dowel through a plate's hole, faceted
//!   differently), their walls run within a hair of each other, crossing and parting again;
//!   the slivers of void between them are faceting, not shape, and no cell resolves them. A
//!   piece not buried is sealed when a triangle of a shell that crosses its own lies within
//!   the seal of every point of it (its distance from the centroid plus the piece's reach),
//!   and the winding number a seal's length off each side of the centroid is inside; a
//!   piece near such a wall but too large for that is unsure (cut further). The octree
//!   mesher seals at a sixteenth of the cell; the report gives the seal and the area sealed.
//!   Walls of shells that do not cross are never sealed: a real slot stays the boundary.
//! - The pairwise test runs once per surface ([`Winding::meets`]), when first asked; nothing
//!   depends on threads.

use super::winding::Winding;
use crate::core::closest::point_triangle_distance;
use glam::DVec3;

/// The buried-sheet judge of one input surface; see the module docs.
pub struct Buried<'a> {
    w: &'a Winding<'a>,
    /// Gaps narrower than this between shells that cross are closed.
    seal: f64,
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
    /// Not buried, but within the seal of a wall of a shell that crosses its own, and inside
    /// a seal's length off both sides (a hairline gap or overlap between crossing shells):
    /// left out, with every piece of it.
    Sealed,
}

impl<'a> Buried<'a> {
    /// The judge of `w`'s surface, closing gaps narrower than `seal` between crossing
    /// shells (0: none).
    pub fn new(w: &'a Winding<'a>, seal: f64) -> Buried<'a> {
        Buried { w, seal }
    }

    /// Whether the piece of `t` about `c` (normal `n`, every point within `reach` of `c`)
    /// lies in a gap narrower than the seal between crossing shells: a wall of a shell that
    /// crosses `t`'s passes within the seal of every point of it, and the winding number a
    /// seal's length off each side is inside. `Some(Unsure)` where the piece is too large
    /// to tell; `None` where it is not sealed.
    fn sealed(&self, t: usize, c: DVec3, n: DVec3, reach: f64) -> Option<Side> {
        if !(self.seal > 0.0) || !self.w.crosses_any(t) {
            return None;
        }
        let s = self.w.surface();
        let wall = self.w.bvh().nearest_from(c, None, |o| {
            if o as usize == t || !self.w.shells_cross(t, o as usize) { f64::INFINITY } else { point_triangle_distance(c, s.corners(o as usize)) }
        });
        let (_, d) = wall.filter(|&(_, d)| d < self.seal)?;
        if d + reach > self.seal {
            return Some(Side::Unsure);
        }
        let inside = |q: DVec3| self.w.inside(q);
        (inside(c + n * self.seal) && inside(c - n * self.seal)).then_some(Side::Sealed)
    }

    /// Where piece `p` of input triangle `t` lies (its corners in `t`); see the module docs.
    pub fn piece(&self, t: usize, p: &[DVec3; 3]) -> Side {
        let tri = self.w.surface().corners(t);
        let normal = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
        let area2 = normal.length();
        if !(area2 > 0.0) {
            return Side::Unsure;
        }
        let n = normal / area2;
        let c = (p[0] + p[1] + p[2]) / 3.0;
        let reach = p.iter().map(|q| q.distance(c)).fold(0.0, f64::max);
        let side = self.judge(t, p, n, c, reach);
        if side == Side::Buried {
            return side;
        }
        self.sealed(t, c, n, reach).unwrap_or(side)
    }

    /// The width of the gaps closed.
    pub fn seal(&self) -> f64 {
        self.seal
    }

    /// [`Buried::piece`] without the seal: `n` the unit normal of `t`, `c` the piece's
    /// centroid, `reach` the farthest of its corners from `c`.
    fn judge(&self, t: usize, p: &[DVec3; 3], n: DVec3, c: DVec3, reach: f64) -> Side {
        let s = self.w.surface();
        let tri = s.corners(t);
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
        let (front, back) = (self.w.counted(c + n * step), self.w.counted(c - n * step));
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
    use crate::mesh::TriSurface;

    /// A small cube wholly inside a big one: its faces are buried; the big cube's are the
    /// boundary; a piece of the big cube's face is the boundary too.
    #[test]
    fn a_cube_inside_a_cube_is_buried() {
        let s = together(&[cube_at(DVec3::ZERO, 4.0), cube_at(DVec3::splat(1.0), 1.0)]);
        let w = Winding::new(&s);
        let b = Buried::new(&w, 0.0);
        for k in 0..24 {
            let want = if k < 12 { Side::Boundary } else { Side::Buried };
            assert_eq!(b.piece(k, &s.corners(k)), want, "triangle {k}");
        }
        let [a, bb, c] = s.corners(0);
        assert_eq!(b.piece(0, &[a, (a + bb) * 0.5, (a + c) * 0.5]), Side::Boundary);
    }

    /// A cube and a box beside it whose near wall is tilted through the cube's face at
    /// `x = 2` (crossing it along `y = 1`), and the same box moved off so the walls do not
    /// cross. Between crossing walls the gap (under 0.01 wide) is closed by a seal of 0.1
    /// and left as it is without one; between walls that do not cross it is the boundary.
    #[test]
    fn a_gap_between_crossing_shells_is_sealed() {
        let tilted = |shift: f64| {
            let mut b = cube_at(DVec3::new(2.0, 0.0, 0.0), 2.0);
            b.vertices.iter_mut().filter(|p| p.x == 2.0).for_each(|p| p.x = 2.0 + shift + 0.01 * (p.y - 1.0));
            b
        };
        let piece = |s: &TriSurface, y: f64| {
            let t = (0..12).find(|&t| s.corners(t).iter().all(|q| q.x == 2.0) && {
                let c = s.corners(t);
                crate::core::closest::point_triangle_distance(DVec3::new(2.0, y, 1.0), c) == 0.0
            });
            let t = t.unwrap();
            (t, [DVec3::new(2.0, y - 0.02, 0.98), DVec3::new(2.0, y + 0.02, 0.98), DVec3::new(2.0, y, 1.02)])
        };
        let s = together(&[cube_at(DVec3::ZERO, 2.0), tilted(0.0)]);
        let w = Winding::new(&s);
        let (sealed, plain) = (Buried::new(&w, 0.1), Buried::new(&w, 0.0));
        // in the gap (y > 1) and in the overlap (y < 1)
        for y in [1.6, 0.4] {
            let (t, p) = piece(&s, y);
            assert_eq!(plain.piece(t, &p), Side::Unsure, "y = {y}");
            assert_eq!(sealed.piece(t, &p), Side::Sealed, "y = {y}");
        }
        // a piece too large to be within the seal of the other wall everywhere: cut further
        let (t, _) = piece(&s, 1.6);
        assert_eq!(sealed.piece(t, &s.corners(t)), Side::Unsure);
        // the outer face is the boundary
        let x0 = (0..12).find(|&t| s.corners(t).iter().all(|q| q.x == 0.0)).unwrap();
        assert_eq!(sealed.piece(x0, &s.corners(x0)), Side::Boundary);
        // walls 0.002 to 0.022 apart that do not cross: a real slot, not sealed
        let s = together(&[cube_at(DVec3::ZERO, 2.0), tilted(0.012)]);
        let w = Winding::new(&s);
        let (t, p) = piece(&s, 1.6);
        assert_eq!(Buried::new(&w, 0.1).piece(t, &p), Side::Boundary);
    }

    /// Two cubes overlapping by half: the faces crossing the other cube are unsure as wholes;
    /// a piece of one wholly inside the other is buried, one wholly outside is the boundary.
    #[test]
    fn overlapping_cubes_are_unsure_where_they_cross() {
        let s = together(&[cube_at(DVec3::ZERO, 1.0), cube_at(DVec3::new(0.5, 0.0, 0.0), 1.0)]);
        let w = Winding::new(&s);
        let b = Buried::new(&w, 0.0);
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
