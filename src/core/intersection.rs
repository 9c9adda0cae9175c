//! Exact intersection decisions between triangles and segments.
//!
//! Inputs: `f64` points; triangles are given by their three corners and, for
//! [`triangle_pair_intersects`], by their vertex indices. Outputs: booleans or a
//! [`SegmentCrossing`], decided only with the exact predicates of [`crate::core::predicates`]
//! (no epsilon, no constructed intersection point).
//!
//! # Semantics
//! Triangles and segments are closed sets: touching counts as meeting. Between two triangles
//! of one mesh, what they share by index is allowed:
//! - no shared vertex: any common point is an intersection;
//! - one shared vertex `v`: an intersection iff they have a common point other than `v`;
//! - a shared edge: an intersection iff they are coplanar and their opposite vertices lie on
//!   the same side of the edge (they overlap: a fold), else not (they meet only along the edge);
//! - all three vertices shared (a duplicate triangle): an intersection.
//!
//! Shared vertices are decided by index: two distinct indices at the same position are
//! distinct vertices, so triangles meeting there intersect.
//!
//! # Preconditions
//! Triangles must have non-zero area ([`is_degenerate`] false) and distinct indices. Callers
//! report degenerate triangles separately; on them the answers here are unspecified (but
//! never a panic).
//!
//! # Method
//! Non-coplanar triangles meet iff an edge of one meets the other (closed sets): the common
//! part lies on the line where their planes cross, and its end points lie on edges.
//! Coplanar configurations are decided in 2D on the projection that drops an axis along which
//! the triangle's projection keeps a non-zero `orient2d`; dropping a coordinate is exact and
//! maps the plane one-to-one, so 2D signs equal 3D in-plane signs up to one global flip.

use crate::core::predicates::{Sign, orient2d};
use glam::{DVec2, DVec3};

/// [`crate::core::predicates::orient3d`] with an exact shortcut: four points sharing one
/// coordinate are coplanar. Axis-aligned flat faces, common in CAD models, are exactly where
/// the adaptive predicate is slowest (an exact zero needs its exact stage).
#[inline]
fn orient3d(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Sign {
    if (a.x == b.x && a.x == c.x && a.x == d.x)
        || (a.y == b.y && a.y == c.y && a.y == d.y)
        || (a.z == b.z && a.z == c.z && a.z == d.z)
    {
        return Sign::Zero;
    }
    crate::core::predicates::orient3d(a, b, c, d)
}

/// True if the triangle has zero area exactly: its corners are collinear or coincide
/// (all three coordinate projections have a zero `orient2d`).
pub fn is_degenerate(a: DVec3, b: DVec3, c: DVec3) -> bool {
    projection_axis(a, b, c).is_none()
}

/// An axis to drop such that the projection of the triangle onto the other two axes has a
/// non-zero `orient2d` (prefers `z`, then `x`, then `y`), or `None` for a degenerate triangle.
pub fn projection_axis(a: DVec3, b: DVec3, c: DVec3) -> Option<usize> {
    [2, 0, 1].into_iter().find(|&axis| !orient2d(project(a, axis), project(b, axis), project(c, axis)).is_zero())
}

/// `p` without coordinate `axis` (exact).
#[inline]
pub fn project(p: DVec3, axis: usize) -> DVec2 {
    match axis {
        0 => DVec2::new(p.y, p.z),
        1 => DVec2::new(p.z, p.x),
        _ => DVec2::new(p.x, p.y),
    }
}

/// True if the closed 2D segments `p`–`q` and `r`–`s` share a point. Segments may not be
/// reduced to points.
pub fn segments_meet_2d(p: DVec2, q: DVec2, r: DVec2, s: DVec2) -> bool {
    let o1 = orient2d(p, q, r);
    let o2 = orient2d(p, q, s);
    if o1 == o2 && !o1.is_zero() {
        return false;
    }
    let o3 = orient2d(r, s, p);
    let o4 = orient2d(r, s, q);
    if o3 == o4 && !o3.is_zero() {
        return false;
    }
    if o1.is_zero() && o2.is_zero() {
        // collinear: compare intervals along an axis on which the line is not constant
        let k = if p.x != q.x { 0 } else { 1 };
        let (a0, a1) = (p[k].min(q[k]), p[k].max(q[k]));
        let (b0, b1) = (r[k].min(s[k]), r[k].max(s[k]));
        return a0 <= b1 && b0 <= a1;
    }
    true
}

/// True if `p` lies in the closed 2D triangle `a, b, c` (of either orientation, non-zero area).
pub fn point_in_triangle_2d(p: DVec2, a: DVec2, b: DVec2, c: DVec2) -> bool {
    let o = orient2d(a, b, c);
    let ok = |s: Sign| s.times(o) != Sign::Negative;
    ok(orient2d(a, b, p)) && ok(orient2d(b, c, p)) && ok(orient2d(c, a, p))
}

/// True if every point of `pts` lies strictly on the other side of the line `a`–`b` than
/// `inner` (which is off the line).
fn strictly_beyond(a: DVec2, b: DVec2, inner: DVec2, pts: &[DVec2]) -> bool {
    let side = orient2d(a, b, inner);
    pts.iter().all(|&x| orient2d(a, b, x).times(side) == Sign::Negative)
}

/// True if the closed 2D segment `p`–`q` (not a point) meets the closed 2D triangle `t`
/// (non-degenerate).
///
/// Separating axes: disjoint convex polygons are strictly separated by a line parallel to
/// one of their edges (here the triangle's edges and the segment itself); touching sets
/// never are.
pub fn segment_meets_triangle_2d(p: DVec2, q: DVec2, t: [DVec2; 3]) -> bool {
    let o = [orient2d(p, q, t[0]), orient2d(p, q, t[1]), orient2d(p, q, t[2])];
    if o[0] == o[1] && o[1] == o[2] && !o[0].is_zero() {
        return false;
    }
    !(0..3).any(|i| strictly_beyond(t[i], t[(i + 1) % 3], t[(i + 2) % 3], &[p, q]))
}

/// True if two closed coplanar 2D triangles (non-degenerate) share a point; decided by
/// separating axes along the six edges, as for [`segment_meets_triangle_2d`].
pub fn triangles_meet_2d(a: [DVec2; 3], b: [DVec2; 3]) -> bool {
    !(0..3).any(|i| {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        strictly_beyond(a[i], a[j], a[k], &b) || strictly_beyond(b[i], b[j], b[k], &a)
    })
}

fn project3(t: [DVec3; 3], axis: usize) -> [DVec2; 3] {
    t.map(|p| project(p, axis))
}

/// True if `p` lies on the closed triangle `t` (non-degenerate).
pub fn point_on_triangle(p: DVec3, t: [DVec3; 3]) -> bool {
    if !orient3d(t[0], t[1], t[2], p).is_zero() {
        return false;
    }
    let Some(axis) = projection_axis(t[0], t[1], t[2]) else { return false };
    let [a, b, c] = project3(t, axis);
    point_in_triangle_2d(project(p, axis), a, b, c)
}

/// Closed segment against closed triangle, given the exact signs `sp`, `sq` of
/// `orient3d(t0, t1, t2, ·)` at the segment's end points.
fn segment_meets_triangle_signed(p: DVec3, q: DVec3, t: [DVec3; 3], sp: Sign, sq: Sign) -> bool {
    if sp == sq {
        if !sp.is_zero() {
            return false;
        }
        // the segment lies in the triangle's plane
        let Some(axis) = projection_axis(t[0], t[1], t[2]) else { return false };
        return segment_meets_triangle_2d(project(p, axis), project(q, axis), project3(t, axis));
    }
    if sp.times(sq) == Sign::Positive {
        return false;
    }
    // the segment reaches the plane at one point (an end point where a sign is zero); it lies
    // in the closed triangle iff the line p-q passes on no strict outer side of any edge
    let o = [orient3d(p, q, t[0], t[1]), orient3d(p, q, t[1], t[2]), orient3d(p, q, t[2], t[0])];
    !(o.contains(&Sign::Positive) && o.contains(&Sign::Negative))
}

/// True if the closed segment `p`–`q` (not a point) meets the closed triangle `t`
/// (non-degenerate).
pub fn segment_meets_triangle(p: DVec3, q: DVec3, t: [DVec3; 3]) -> bool {
    let sp = orient3d(t[0], t[1], t[2], p);
    let sq = orient3d(t[0], t[1], t[2], q);
    segment_meets_triangle_signed(p, q, t, sp, sq)
}

/// How a segment meets a triangle, for ray-parity counting.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum SegmentCrossing {
    /// No common point.
    Miss,
    /// The open segment crosses the open triangle at one point, transversally.
    Proper,
    /// Any other contact: through an edge or a vertex of the triangle, along its plane, or
    /// with an end point on the triangle. A parity count must choose another segment.
    Degenerate,
}

/// Classifies how the closed segment `p`–`q` meets the closed triangle `t` (non-degenerate).
pub fn segment_crosses_triangle(p: DVec3, q: DVec3, t: [DVec3; 3]) -> SegmentCrossing {
    let sp = orient3d(t[0], t[1], t[2], p);
    let sq = orient3d(t[0], t[1], t[2], q);
    if sp.is_zero() || sq.is_zero() {
        return if segment_meets_triangle_signed(p, q, t, sp, sq) { SegmentCrossing::Degenerate } else { SegmentCrossing::Miss };
    }
    if sp == sq {
        return SegmentCrossing::Miss;
    }
    let o = [orient3d(p, q, t[0], t[1]), orient3d(p, q, t[1], t[2]), orient3d(p, q, t[2], t[0])];
    if o.contains(&Sign::Positive) && o.contains(&Sign::Negative) {
        SegmentCrossing::Miss
    } else if o.contains(&Sign::Zero) {
        SegmentCrossing::Degenerate
    } else {
        SegmentCrossing::Proper
    }
}

/// True if two closed triangles (non-degenerate) share any point.
pub fn triangles_meet(a: [DVec3; 3], b: [DVec3; 3]) -> bool {
    let sb = b.map(|p| orient3d(a[0], a[1], a[2], p));
    if sb[0] == sb[1] && sb[1] == sb[2] {
        if !sb[0].is_zero() {
            return false;
        }
        let Some(axis) = projection_axis(a[0], a[1], a[2]) else { return false };
        return triangles_meet_2d(project3(a, axis), project3(b, axis));
    }
    let sa = a.map(|p| orient3d(b[0], b[1], b[2], p));
    if sa[0] == sa[1] && sa[1] == sa[2] && !sa[0].is_zero() {
        return false;
    }
    (0..3).any(|i| {
        let j = (i + 1) % 3;
        segment_meets_triangle_signed(b[i], b[j], a, sb[i], sb[j]) || segment_meets_triangle_signed(a[i], a[j], b, sa[i], sa[j])
    })
}

/// What two index triples share.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Shared {
    /// No index in common.
    Nothing,
    /// One index, at corner `a` of the first and corner `b` of the second triangle.
    Vertex {
        /// Corner of the first triangle.
        a: usize,
        /// Corner of the second triangle.
        b: usize,
    },
    /// Two indices: corner `a` of the first triangle and corner `b` of the second are the
    /// vertices *not* shared.
    Edge {
        /// The unshared corner of the first triangle.
        a: usize,
        /// The unshared corner of the second triangle.
        b: usize,
    },
    /// All three indices.
    All,
}

/// What the index triples `ia` and `ib` (each with distinct indices) share.
pub fn shared(ia: [u32; 3], ib: [u32; 3]) -> Shared {
    let mut count = 0;
    let (mut sa, mut sb) = ([false; 3], [false; 3]);
    let (mut va, mut vb) = (0, 0);
    for i in 0..3 {
        for j in 0..3 {
            if ia[i] == ib[j] && !sa[i] && !sb[j] {
                sa[i] = true;
                sb[j] = true;
                count += 1;
                (va, vb) = (i, j);
            }
        }
    }
    let unshared = |s: [bool; 3]| s.iter().position(|&x| !x).unwrap_or(0);
    match count {
        0 => Shared::Nothing,
        1 => Shared::Vertex { a: va, b: vb },
        2 => Shared::Edge { a: unshared(sa), b: unshared(sb) },
        _ => Shared::All,
    }
}

/// Decides whether two triangles of one mesh intersect, allowing what they share by index
/// (see the module docs). `ia`/`ib` are the vertex indices, `a`/`b` the corner positions.
///
/// ```
/// use fepre::core::triangle_pair_intersects;
/// use glam::DVec3;
/// let p = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
/// let a = [p(0., 0., 0.), p(1., 0., 0.), p(0., 1., 0.)];
/// // a fin on the shared edge 0-1: not an intersection
/// assert!(!triangle_pair_intersects([0, 1, 2], a, [1, 0, 3], [a[1], a[0], p(0., 0., 1.)]));
/// // folded onto the same side in the same plane: an intersection
/// assert!(triangle_pair_intersects([0, 1, 2], a, [1, 0, 3], [a[1], a[0], p(0.5, 0.5, 0.)]));
/// ```
pub fn triangle_pair_intersects(ia: [u32; 3], a: [DVec3; 3], ib: [u32; 3], b: [DVec3; 3]) -> bool {
    match shared(ia, ib) {
        Shared::Nothing => triangles_meet(a, b),
        Shared::Vertex { a: i, b: j } => {
            let v = a[i];
            let (a1, a2) = (a[(i + 1) % 3], a[(i + 2) % 3]);
            let (b1, b2) = (b[(j + 1) % 3], b[(j + 2) % 3]);
            meet_beyond_shared_vertex(v, a1, a2, b1, b2)
        }
        Shared::Edge { a: i, b: j } => {
            let (p, q, r) = (a[(i + 1) % 3], a[(i + 2) % 3], a[i]);
            let s = b[j];
            // a fold: coplanar, the third corners on one side of the shared edge. The side
            // first: two triangles of a flat face lie on both sides, and are decided without
            // the exact zero that their coplanarity costs (a collinear `p, q, r` has no axis,
            // and no fold)
            let Some(axis) = projection_axis(p, q, r) else { return false };
            let (p2, q2) = (project(p, axis), project(q, axis));
            orient2d(p2, q2, project(r, axis)).times(orient2d(p2, q2, project(s, axis))) == Sign::Positive && orient3d(p, q, r, s).is_zero()
        }
        Shared::All => true,
    }
}

/// Triangles `(v, a1, a2)` and `(v, b1, b2)` sharing the vertex `v`: do they have a common
/// point other than `v`?
///
/// Their common part is convex and contains `v`, so it holds another point iff it holds a
/// short segment from `v`, i.e. iff the two corner cones at `v` share a ray.
/// - Not coplanar: the second triangle meets the first one's plane in the segment `v`–`w`
///   (`w` on `b1`–`b2`), and the answer is whether the direction `w - v` lies in the closed
///   cone of the first triangle at `v`. With `s_i = orient3d(v, a1, a2, b_i)` and
///   `d = sign(s2 - s1)`, `orient3d(v, a_k, b1, b2) · d` is the side of `w` of the line
///   `v`–`a_k` within the first plane (positive towards `a2` for `k = 1`), so no `w` needs
///   constructing.
/// - Coplanar: two closed convex cones (under 180°) share a ray iff a bounding ray of one lies
///   in the other; decided in 2D.
///
/// First, in the plane of an axis along which the first triangle projects without
/// degenerating: a common point `w` other than `v` projects to one other than `v`'s (`w - v`
/// lies in the first plane, which the projection maps one to one), so the projected cones share
/// a ray, and one's bounding ray lies in the other (a degenerate projected second cone counts
/// as sharing). Where they share none the answer is no, without the 3D orientations: two
/// triangles of a flat face around a vertex are coplanar, an exact zero each. Where they share
/// one and the triangles are coplanar, that is the answer. A first triangle with no such axis
/// is collinear: both orientations vanish, and it meets nothing.
fn meet_beyond_shared_vertex(v: DVec3, a1: DVec3, a2: DVec3, b1: DVec3, b2: DVec3) -> bool {
    let Some(axis) = projection_axis(v, a1, a2) else { return false };
    let [v2, a12, a22, b12, b22] = [v, a1, a2, b1, b2].map(|p| project(p, axis));
    if !(in_cone_2d(v2, a12, a22, b12) || in_cone_2d(v2, a12, a22, b22) || in_cone_2d(v2, b12, b22, a12) || in_cone_2d(v2, b12, b22, a22)) {
        return false;
    }
    let s1 = orient3d(v, a1, a2, b1);
    let s2 = orient3d(v, a1, a2, b2);
    if s1 == s2 {
        // only at v in the first plane, or coplanar with cones sharing a ray
        return s1.is_zero();
    }
    let d = if s1.is_zero() { s2 } else { s1.reversed() };
    orient3d(v, a1, b1, b2).times(d) != Sign::Negative && orient3d(v, a2, b1, b2).times(d) != Sign::Positive
}

/// True if `x` lies in the closed cone at `v` spanned by `a` and `b` (angle below 180°).
fn in_cone_2d(v: DVec2, a: DVec2, b: DVec2, x: DVec2) -> bool {
    let o = orient2d(v, a, b);
    orient2d(v, a, x).times(o) != Sign::Negative && orient2d(v, b, x).times(o) != Sign::Positive
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn p(x: f64, y: f64, z: f64) -> DVec3 {
        DVec3::new(x, y, z)
    }

    /// Both argument orders and all cyclic rotations must agree; returns the common answer.
    fn pair(ia: [u32; 3], a: [DVec3; 3], ib: [u32; 3], b: [DVec3; 3]) -> bool {
        let r = triangle_pair_intersects(ia, a, ib, b);
        for k in 0..3 {
            let rot = |t: [DVec3; 3]| [t[k], t[(k + 1) % 3], t[(k + 2) % 3]];
            let roti = |t: [u32; 3]| [t[k], t[(k + 1) % 3], t[(k + 2) % 3]];
            assert_eq!(triangle_pair_intersects(roti(ia), rot(a), ib, b), r);
            assert_eq!(triangle_pair_intersects(ib, b, roti(ia), rot(a)), r);
            let rev = |t: [DVec3; 3]| [t[0], t[2], t[1]];
            let revi = |t: [u32; 3]| [t[0], t[2], t[1]];
            assert_eq!(triangle_pair_intersects(ia, a, revi(roti(ib)), rev(rot(b))), r);
        }
        r
    }

    const A: [u32; 3] = [0, 1, 2];
    const B: [u32; 3] = [3, 4, 5];
    fn base() -> [DVec3; 3] {
        [p(0., 0., 0.), p(4., 0., 0.), p(0., 4., 0.)]
    }

    #[test]
    fn degenerate_triangles() {
        assert!(is_degenerate(p(0., 0., 0.), p(1., 1., 1.), p(2., 2., 2.)));
        assert!(is_degenerate(p(1., 2., 3.), p(1., 2., 3.), p(5., 0., 0.)));
        assert!(!is_degenerate(p(0., 0., 0.), p(1., 0., 0.), p(0.5, 1e-30, 0.)));
        assert!(!is_degenerate(p(0., 0., 0.), p(0., 1., 0.), p(0., 0., 1.)));
        assert_eq!(projection_axis(p(0., 0., 0.), p(0., 1., 0.), p(0., 0., 1.)), Some(0));
        assert_eq!(projection_axis(p(0., 0., 0.), p(1., 0., 0.), p(0., 0., 1.)), Some(1));
    }

    #[test]
    fn planar_primitives() {
        let q = |x: f64, y: f64| DVec2::new(x, y);
        assert!(segments_meet_2d(q(0., 0.), q(2., 2.), q(0., 2.), q(2., 0.)));
        assert!(segments_meet_2d(q(0., 0.), q(2., 0.), q(2., 0.), q(3., 0.))); // collinear, touching
        assert!(segments_meet_2d(q(0., 0.), q(0., 2.), q(0., 1.), q(0., 3.))); // vertical overlap
        assert!(!segments_meet_2d(q(0., 0.), q(0., 2.), q(0., 2.5), q(0., 3.)));
        assert!(!segments_meet_2d(q(0., 0.), q(2., 0.), q(2.5, 0.), q(3., 0.)));
        assert!(segments_meet_2d(q(0., 0.), q(2., 0.), q(1., 0.), q(1., 5.))); // T junction
        assert!(!segments_meet_2d(q(0., 0.), q(2., 0.), q(3., -1.), q(3., 5.)));
        let t = [q(0., 0.), q(2., 0.), q(0., 2.)];
        assert!(point_in_triangle_2d(q(1., 1.), t[0], t[1], t[2]));
        assert!(point_in_triangle_2d(q(1., 1.), t[0], t[2], t[1]));
        assert!(!point_in_triangle_2d(q(1.5, 1.), t[0], t[1], t[2]));
        assert!(segment_meets_triangle_2d(q(-1., 1.), q(3., 1.), t));
        assert!(!segment_meets_triangle_2d(q(-1., 3.), q(3., 3.), t));
        assert!(triangles_meet_2d(t, [q(1., 1.), q(3., 3.), q(1., 3.)]));
    }

    #[test]
    fn no_shared_vertex() {
        let a = base();
        // parallel planes
        assert!(!pair(A, a, B, a.map(|v| v + DVec3::Z)));
        // piercing through the interior
        assert!(pair(A, a, B, [p(1., 1., -1.), p(1., 1., 1.), p(5., 5., 1.)]));
        // a vertex touching the interior, an edge touching an edge, a vertex on an edge
        assert!(pair(A, a, B, [p(1., 1., 0.), p(1., 1., 2.), p(3., 1., 2.)]));
        assert!(pair(A, a, B, [p(2., -1., 0.), p(2., 1., 0.), p(2., 0., 3.)]));
        assert!(pair(A, a, B, [p(2., 0., 0.), p(2., -1., 3.), p(2., 1., 3.)]));
        // just missing the hypotenuse, above and across
        assert!(!pair(A, a, B, [p(2.5, 2.5, -1.), p(2.5, 2.5, 1.), p(9., 9., 0.)]));
        // crossing the plane outside the triangle
        assert!(!pair(A, a, B, [p(-1., -1., -1.), p(-1., -1., 1.), p(-3., 1., 0.)]));
        // an edge lying in the plane, crossing the triangle or not
        assert!(pair(A, a, B, [p(-1., 1., 0.), p(5., 1., 0.), p(2., 2., 3.)]));
        assert!(!pair(A, a, B, [p(-1., 5., 0.), p(5., 6., 0.), p(2., 2., 3.)]));
        // coincident positions under different indices touch
        assert!(pair(A, a, B, [a[1], p(5., 0., 1.), p(5., 1., -1.)]));
    }

    #[test]
    fn no_shared_vertex_coplanar() {
        let a = base();
        assert!(pair(A, a, B, [p(1., 1., 0.), p(5., 1., 0.), p(1., 5., 0.)])); // overlap
        assert!(pair(A, a, B, [p(1., 1., 0.), p(2., 1., 0.), p(1., 2., 0.)])); // contained
        assert!(pair(A, a, B, [p(-1., -1., 0.), p(9., -1., 0.), p(-1., 9., 0.)])); // contains
        assert!(!pair(A, a, B, [p(3., 3., 0.), p(5., 3., 0.), p(3., 5., 0.)])); // beside
        assert!(pair(A, a, B, [p(2., 2., 0.), p(5., 3., 0.), p(3., 5., 0.)])); // touches at a point
        assert!(pair(A, a, B, [p(1., 0., 0.), p(3., 0., 0.), p(2., -1., 0.)])); // shares part of an edge
        assert!(pair(A, a, B, [p(4., 0., 0.), p(6., 0., 0.), p(5., -1., 0.)])); // collinear edges touch at an end
        assert!(!pair(A, a, B, [p(5., 0., 0.), p(6., 0., 0.), p(5., -1., 0.)])); // collinear, apart
        // star of David: edges cross, no vertex inside the other
        let t1 = [p(0., 0., 0.), p(6., 0., 0.), p(3., 5., 0.)];
        let t2 = [p(0., 3., 0.), p(3., -2., 0.), p(6., 3., 0.)];
        assert!(pair(A, t1, B, t2));
    }

    #[test]
    fn one_shared_vertex() {
        let a = base();
        let ib = [0, 4, 5];
        // mesh neighbours in the plane: cones apart, or sharing only the apex (bow tie)
        assert!(!pair(A, a, ib, [a[0], p(0., -4., 0.), p(4., -4., 0.)]));
        assert!(!pair(A, a, ib, [a[0], p(-4., 0., 0.), p(0., -4., 0.)]));
        // coplanar cones overlapping, or sharing one bounding ray
        assert!(pair(A, a, ib, [a[0], p(1., 1., 0.), p(4., -4., 0.)]));
        assert!(pair(A, a, ib, [a[0], p(1., 0., 0.), p(1., -4., 0.)]));
        assert!(pair(A, a, ib, [a[0], p(9., 0., 0.), p(0., -9., 0.)]));
        // one cone inside the other
        assert!(pair(A, a, ib, [a[0], p(1., 2., 0.), p(2., 1., 0.)]));
        // out of plane: touches the plane only at v
        assert!(!pair(A, a, ib, [a[0], p(1., 1., 1.), p(-1., 2., 3.)]));
        // an edge lying in the plane, outside or inside the cone, or along its border
        assert!(!pair(A, a, ib, [a[0], p(-1., -1., 0.), p(1., 1., 3.)]));
        assert!(pair(A, a, ib, [a[0], p(1., 1., 0.), p(-1., -1., 3.)]));
        assert!(pair(A, a, ib, [a[0], p(0., 9., 0.), p(-1., -1., 3.)]));
        // opposite edge crossing the triangle
        assert!(pair(A, a, ib, [a[0], p(1., 1., 1.), p(1., 1., -1.)]));
        // opposite edge crossing the plane beyond the triangle but inside the cone
        assert!(pair(A, a, ib, [a[0], p(9., 9., 1.), p(9., 9., -1.)]));
        // opposite edge crossing the plane outside the cone
        assert!(!pair(A, a, ib, [a[0], p(-1., 1., 1.), p(-1., 2., -1.)]));
        assert!(!pair(A, a, ib, [a[0], p(1., -1., 1.), p(1., -2., -1.)]));
        // opposite edge crossing exactly on a bounding ray of the cone
        assert!(pair(A, a, ib, [a[0], p(2., 0., 1.), p(2., 0., -1.)]));
        // a fin standing on the edge 0-1 with only v in common
        assert!(pair(A, a, ib, [a[0], p(1., 0., 0.), p(1., 0., 2.)]));
        // another vertex sitting on the first triangle
        assert!(pair(A, a, ib, [a[0], p(1., 1., 0.), p(1., 1., 1.)]));
        // a second corner at the position of a corner of the first, under another index
        assert!(pair(A, a, ib, [a[0], a[1], p(1., -1., 1.)]));
        assert!(!pair(A, a, [0, 1, 5], [a[0], a[1], p(1., -1., 1.)]));
    }

    #[test]
    fn shared_edge() {
        let a = base();
        let ib = [1, 0, 5];
        assert!(!pair(A, a, ib, [a[1], a[0], p(1., -2., 3.)])); // dihedral fin
        assert!(!pair(A, a, ib, [a[1], a[0], p(1., 2., 3.)]));
        assert!(!pair(A, a, ib, [a[1], a[0], p(1., -2., 0.)])); // flat neighbours
        assert!(pair(A, a, ib, [a[1], a[0], p(1., 2., 0.)])); // fold onto the same side
        assert!(pair(A, a, ib, [a[1], a[0], p(9., 9., 0.)])); // fold, apex beyond
        assert!(pair(A, a, ib, [a[1], a[0], p(-9., 1., 0.)]));
    }

    #[test]
    fn duplicate_triangle() {
        let a = base();
        assert!(pair(A, a, A, a));
        assert!(pair(A, a, [2, 1, 0], [a[2], a[1], a[0]]));
        assert_eq!(shared(A, [2, 0, 1]), Shared::All);
        assert_eq!(shared(A, [7, 2, 1]), Shared::Edge { a: 0, b: 0 });
        assert_eq!(shared(A, [7, 8, 1]), Shared::Vertex { a: 1, b: 2 });
    }

    #[test]
    fn segment_crossings() {
        let t = base();
        use SegmentCrossing::*;
        assert_eq!(segment_crosses_triangle(p(1., 1., -1.), p(1., 1., 1.), t), Proper);
        assert_eq!(segment_crosses_triangle(p(5., 5., -1.), p(5., 5., 1.), t), Miss);
        assert_eq!(segment_crosses_triangle(p(1., 1., 1.), p(1., 1., 2.), t), Miss);
        assert_eq!(segment_crosses_triangle(p(2., 0., -1.), p(2., 0., 1.), t), Degenerate); // edge
        assert_eq!(segment_crosses_triangle(p(0., 0., -1.), p(0., 0., 1.), t), Degenerate); // vertex
        assert_eq!(segment_crosses_triangle(p(-1., 1., 0.), p(5., 1., 0.), t), Degenerate); // in plane
        assert_eq!(segment_crosses_triangle(p(-1., 9., 0.), p(9., 9., 0.), t), Miss); // in plane, apart
        assert_eq!(segment_crosses_triangle(p(1., 1., 0.), p(1., 1., 5.), t), Degenerate); // end point on it
        assert_eq!(segment_crosses_triangle(p(5., 5., 0.), p(1., 1., 5.), t), Miss); // end point in plane
        assert!(segment_meets_triangle(p(1., 1., 0.), p(1., 1., 5.), t));
        assert!(point_on_triangle(p(2., 2., 0.), t));
        assert!(!point_on_triangle(p(2.5, 2., 0.), t));
        assert!(!point_on_triangle(p(1., 1., 1e-300), t));
    }

    // ---- independent oracle: explicit rational candidate points in i128 ----

    type V = [i128; 3];
    fn sub(a: V, b: V) -> V {
        [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
    }
    fn dot(a: V, b: V) -> i128 {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }
    fn cross(a: V, b: V) -> V {
        [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
    }
    fn mul(a: V, k: i128) -> V {
        a.map(|x| x * k)
    }
    fn add(a: V, b: V) -> V {
        [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
    }

    /// Is the rational point `x / w` (w > 0) in the closed triangle `t`?
    fn in_tri(x: V, w: i128, t: &[V; 3]) -> bool {
        let n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
        dot(n, sub(x, mul(t[0], w))) == 0 && (0..3).all(|i| dot(cross(sub(t[(i + 1) % 3], t[i]), sub(x, mul(t[i], w))), n) >= 0)
    }

    /// Is `x / w` on the closed segment `p`–`q`?
    fn on_seg(x: V, w: i128, p: V, q: V) -> bool {
        let (e, r) = (sub(q, p), sub(x, mul(p, w)));
        cross(e, r) == [0; 3] && dot(r, e) >= 0 && dot(r, e) <= w * dot(e, e)
    }

    /// The common part of two convex polygons is a convex polytope whose vertices are vertices
    /// of either triangle, points where an edge crosses the other plane, or crossings of
    /// coplanar edges. The triangles meet outside what they share iff such a candidate lies
    /// in both and outside the shared vertex or edge.
    fn oracle(ia: [u32; 3], a: [V; 3], ib: [u32; 3], b: [V; 3]) -> bool {
        let sh: Vec<usize> = (0..3).filter(|&i| ib.contains(&ia[i])).collect();
        let outside_shared = |x: V, w: i128| match sh.len() {
            0 => true,
            1 => x != mul(a[sh[0]], w),
            2 => !on_seg(x, w, a[sh[0]], a[sh[1]]),
            _ => true,
        };
        let mut cand: Vec<(V, i128)> = a.iter().chain(b.iter()).map(|&v| (v, 1)).collect();
        for (s, t) in [(&a, &b), (&b, &a)] {
            let n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
            for i in 0..3 {
                let (p, q) = (s[i], s[(i + 1) % 3]);
                let (dp, dq) = (dot(n, sub(p, t[0])), dot(n, sub(q, t[0])));
                if (dp > 0 && dq < 0) || (dp < 0 && dq > 0) {
                    let (x, w) = (add(mul(p, -dq), mul(q, dp)), dp - dq);
                    cand.push(if w < 0 { (mul(x, -1), -w) } else { (x, w) });
                }
                for j in 0..3 {
                    let (r, u) = (t[j], t[(j + 1) % 3]);
                    let (e1, e2) = (sub(q, p), sub(u, r));
                    let c = cross(e1, e2);
                    let cc = dot(c, c);
                    if cc != 0 && dot(sub(r, p), c) == 0 {
                        let num = dot(cross(sub(r, p), e2), c);
                        cand.push((add(mul(p, cc), mul(e1, num)), cc));
                    }
                }
            }
        }
        cand.iter().any(|&(x, w)| in_tri(x, w, &a) && in_tri(x, w, &b) && outside_shared(x, w))
    }

    fn to_f(v: V) -> DVec3 {
        DVec3::new(v[0] as f64, v[1] as f64, v[2] as f64)
    }

    fn nondegenerate(t: &[V; 3]) -> bool {
        cross(sub(t[1], t[0]), sub(t[2], t[0])) != [0; 3]
    }

    /// A triangle pair: corners of `a`, and for `b` either a new point or (by index) a corner
    /// of `a`, giving every sharing pattern.
    fn arb_pair() -> impl Strategy<Value = ([u32; 3], [V; 3], [u32; 3], [V; 3])> {
        (1i128..=3)
            .prop_flat_map(|r| {
                let pt = prop::array::uniform3(-r..=r);
                let pick = prop_oneof![3 => Just(None), 1 => (0usize..3).prop_map(Some)];
                (prop::array::uniform3(pt.clone()), prop::array::uniform3((pt, pick)))
            })
            .prop_map(|(a, bs)| {
                let mut ib = [3, 4, 5];
                let mut b = [[0i128; 3]; 3];
                for (k, (q, pick)) in bs.into_iter().enumerate() {
                    match pick {
                        Some(i) => {
                            ib[k] = i as u32;
                            b[k] = a[i];
                        }
                        None => b[k] = q,
                    }
                }
                ([0, 1, 2], a, ib, b)
            })
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 20_000, max_global_rejects: 200_000, ..ProptestConfig::default() })]
        #[test]
        fn agrees_with_rational_oracle((ia, a, ib, b) in arb_pair()) {
            prop_assume!(ib[0] != ib[1] && ib[1] != ib[2] && ib[0] != ib[2]);
            prop_assume!(nondegenerate(&a) && nondegenerate(&b));
            let want = oracle(ia, a, ib, b);
            let got = triangle_pair_intersects(ia, a.map(to_f), ib, b.map(to_f));
            prop_assert_eq!(got, want, "a {:?} {:?} b {:?} {:?}", ia, a, ib, b);
            prop_assert_eq!(triangle_pair_intersects(ib, b.map(to_f), ia, a.map(to_f)), want);
        }

        #[test]
        fn coplanar_pairs_agree_with_oracle((ia, a, ib, b) in arb_pair(), tilted in any::<bool>()) {
            // flatten into z = 0 or the tilted plane z = x - 2y
            let flat = |v: V| [v[0], v[1], if tilted { v[0] - 2 * v[1] } else { 0 }];
            let (a, b) = (a.map(flat), b.map(flat));
            prop_assume!(ib[0] != ib[1] && ib[1] != ib[2] && ib[0] != ib[2]);
            prop_assume!(nondegenerate(&a) && nondegenerate(&b));
            let want = oracle(ia, a, ib, b);
            prop_assert_eq!(triangle_pair_intersects(ia, a.map(to_f), ib, b.map(to_f)), want);
            prop_assert_eq!(triangle_pair_intersects(ib, b.map(to_f), ia, a.map(to_f)), want);
        }

        #[test]
        fn segment_test_agrees_with_oracle(a in prop::array::uniform3(prop::array::uniform3(-2i128..=2)),
                                           s in prop::array::uniform2(prop::array::uniform3(-2i128..=2))) {
            prop_assume!(nondegenerate(&a) && s[0] != s[1]);
            // a segment is a triangle squeezed flat: test it as the candidates of the oracle do
            let n = cross(sub(a[1], a[0]), sub(a[2], a[0]));
            let (dp, dq) = (dot(n, sub(s[0], a[0])), dot(n, sub(s[1], a[0])));
            let mut cand: Vec<(V, i128)> = vec![(s[0], 1), (s[1], 1)];
            if (dp > 0 && dq < 0) || (dp < 0 && dq > 0) {
                let (x, w) = (add(mul(s[0], -dq), mul(s[1], dp)), dp - dq);
                cand.push(if w < 0 { (mul(x, -1), -w) } else { (x, w) });
            }
            for j in 0..3 {
                let (e1, e2) = (sub(s[1], s[0]), sub(a[(j + 1) % 3], a[j]));
                let c = cross(e1, e2);
                let cc = dot(c, c);
                if cc != 0 && dot(sub(a[j], s[0]), c) == 0 {
                    let num = dot(cross(sub(a[j], s[0]), e2), c);
                    cand.push((add(mul(s[0], cc), mul(e1, num)), cc));
                }
            }
            let want = cand.iter().any(|&(x, w)| in_tri(x, w, &a) && on_seg(x, w, s[0], s[1]));
            prop_assert_eq!(segment_meets_triangle(to_f(s[0]), to_f(s[1]), a.map(to_f)), want);
            let c = segment_crosses_triangle(to_f(s[0]), to_f(s[1]), a.map(to_f));
            prop_assert_eq!(c != SegmentCrossing::Miss, want);
        }
    }
}
