//! Triangulation of the polygonal faces of OBJ and OFF files.
//!
//! - Triangles are kept as they are.
//! - Quads are split along their shorter diagonal, unless that diagonal lies outside the quad
//!   (a non-convex "dart"), in which case the other one is used.
//! - Larger polygons are triangulated by ear clipping in their best-fit plane: the plane of the
//!   Newell normal, into which the corners are projected by dropping the coordinate of the
//!   normal's largest component (no rounding, so the exact [`orient2d`] decides convexity and
//!   containment on the file's own coordinates).
//!
//! Triangles keep the polygon's winding. Corners that repeat the previous corner are merged
//! first; a polygon with fewer than three distinct corners yields nothing. A polygon that is
//! not simple in its plane (self-intersecting, folded, all corners collinear) still yields
//! `n - 2` triangles, cut where no proper ear exists, and is reported as
//! [`Outcome::Approximate`].

use crate::core::predicates::orient2d;
use crate::core::Sign;
use glam::{DVec2, DVec3};

/// How a polygon was triangulated.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// The triangles tile the polygon (every cut was a proper ear, or the polygon was a
    /// triangle or a quad split inside).
    Exact,
    /// The polygon is not simple in its best-fit plane; some triangles were cut without a
    /// proper ear, so they cover the polygon only approximately (and may overlap or be flat).
    Approximate,
    /// Fewer than three distinct corners, or a corner index out of range: nothing was emitted.
    Degenerate,
}

/// The Newell normal of a closed polygon: perpendicular to its best-fit plane, with length
/// twice the area of its projection onto that plane, oriented by the winding (right-hand
/// rule). Zero for fewer than three corners or collinear corners.
pub fn newell_normal(p: &[DVec3]) -> DVec3 {
    if p.len() < 3 {
        return DVec3::ZERO;
    }
    // centring reduces cancellation for polygons far from the origin
    let c = p.iter().copied().sum::<DVec3>() / p.len() as f64;
    let mut n = DVec3::ZERO;
    for (i, a) in p.iter().enumerate() {
        let b = p[(i + 1) % p.len()];
        n += (*a - c).cross(b - c);
    }
    n
}

/// Projects `p` onto the coordinate plane most nearly parallel to the plane with normal `n`,
/// by dropping a coordinate (exactly), with the two kept axes ordered so that a polygon
/// winding counter-clockwise about `n` winds counter-clockwise in 2D.
pub fn project(p: &[DVec3], n: DVec3) -> Vec<DVec2> {
    let a = n.abs();
    let (u, v) = if a.z >= a.x && a.z >= a.y {
        if n.z >= 0.0 { (0, 1) } else { (1, 0) }
    } else if a.x >= a.y {
        if n.x >= 0.0 { (1, 2) } else { (2, 1) }
    } else if n.y >= 0.0 {
        (2, 0)
    } else {
        (0, 2)
    };
    p.iter().map(|q| DVec2::new(q[u], q[v])).collect()
}

/// Triangulates the polygon whose corners are the vertex indices `corners` (positions in
/// `vertices`), appending triangles of vertex indices to `out` with the polygon's winding.
///
/// Returns [`Outcome::Degenerate`] (and appends nothing) when a corner index is out of range
/// or fewer than three distinct corners remain after merging repeated neighbours. Triangles
/// that would use one vertex twice (polygons that revisit a vertex) are not emitted; the
/// outcome is then [`Outcome::Approximate`].
pub fn triangulate(corners: &[u32], vertices: &[DVec3], out: &mut Vec<[u32; 3]>) -> Outcome {
    let mut c: Vec<u32> = Vec::with_capacity(corners.len());
    for &i in corners {
        if i as usize >= vertices.len() {
            return Outcome::Degenerate;
        }
        if c.last() != Some(&i) {
            c.push(i);
        }
    }
    while c.len() > 1 && c.first() == c.last() {
        c.pop();
    }
    match c.len() {
        0..=2 => Outcome::Degenerate,
        3 => {
            if c[0] == c[2] {
                return Outcome::Degenerate;
            }
            out.push([c[0], c[1], c[2]]);
            Outcome::Exact
        }
        _ => {
            let p: Vec<DVec3> = c.iter().map(|&i| vertices[i as usize]).collect();
            let q = project(&p, newell_normal(&p));
            let mut local = Vec::with_capacity(c.len() - 2);
            let mut outcome = if c.len() == 4 { split_quad(&p, &q, &mut local) } else { clip_ears(&q, &mut local) };
            for t in local {
                let tri = [c[t[0]], c[t[1]], c[t[2]]];
                if tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] {
                    outcome = Outcome::Approximate;
                } else {
                    out.push(tri);
                }
            }
            outcome
        }
    }
}

/// Both triangles of a split turn counter-clockwise in the projection.
fn split_ok(q: &[DVec2], split: &[[usize; 3]; 2]) -> bool {
    split.iter().all(|t| orient2d(q[t[0]], q[t[1]], q[t[2]]) == Sign::Positive)
}

/// Splits a quad along its shorter diagonal, or along the other if the shorter one lies
/// outside the quad.
fn split_quad(p: &[DVec3], q: &[DVec2], out: &mut Vec<[usize; 3]>) -> Outcome {
    let d02 = [[0, 1, 2], [0, 2, 3]];
    let d13 = [[0, 1, 3], [1, 2, 3]];
    let (first, second) = if p[0].distance_squared(p[2]) <= p[1].distance_squared(p[3]) { (d02, d13) } else { (d13, d02) };
    if split_ok(q, &first) {
        out.extend(first);
        Outcome::Exact
    } else if split_ok(q, &second) {
        out.extend(second);
        Outcome::Exact
    } else {
        out.extend(first);
        Outcome::Approximate
    }
}

/// True if `p` lies inside or on the boundary of the counter-clockwise triangle `a b c`.
fn in_triangle(a: DVec2, b: DVec2, c: DVec2, p: DVec2) -> bool {
    orient2d(a, b, p) != Sign::Negative && orient2d(b, c, p) != Sign::Negative && orient2d(c, a, p) != Sign::Negative
}

/// Ear clipping of the polygon `q` (counter-clockwise for a simple polygon), appending
/// triangles of corner positions.
fn clip_ears(q: &[DVec2], out: &mut Vec<[usize; 3]>) -> Outcome {
    let n = q.len();
    let mut next: Vec<usize> = (0..n).map(|i| (i + 1) % n).collect();
    let mut prev: Vec<usize> = (0..n).map(|i| (i + n - 1) % n).collect();
    let mut remaining = n;
    let mut exact = true;
    let mut i = 0;
    let mut failures = 0;
    let is_ear = |prev: &[usize], next: &[usize], b: usize| -> bool {
        let (a, c) = (prev[b], next[b]);
        if orient2d(q[a], q[b], q[c]) != Sign::Positive {
            return false;
        }
        let mut v = next[c];
        while v != a {
            let pv = q[v];
            // a corner at the same place as a corner of the ear (a touching polygon) does not block it
            if pv != q[a] && pv != q[b] && pv != q[c] && in_triangle(q[a], q[b], q[c], pv) {
                return false;
            }
            v = next[v];
        }
        true
    };
    while remaining > 3 {
        let mut cut = None;
        if is_ear(&prev, &next, i) {
            cut = Some(i);
        } else {
            failures += 1;
            if failures >= remaining {
                // No proper ear: the polygon is not simple. Cut a convex corner if there is
                // one, else a flat one, else any.
                exact = false;
                let ring: Vec<usize> = std::iter::successors(Some(i), |&v| Some(next[v])).take(remaining).collect();
                let turn = |v: usize| orient2d(q[prev[v]], q[v], q[next[v]]);
                cut = ring
                    .iter()
                    .find(|&&v| turn(v) == Sign::Positive)
                    .or_else(|| ring.iter().find(|&&v| turn(v) == Sign::Zero))
                    .copied()
                    .or(Some(i));
            }
        }
        match cut {
            Some(b) => {
                let (a, c) = (prev[b], next[b]);
                out.push([a, b, c]);
                next[a] = c;
                prev[c] = a;
                remaining -= 1;
                failures = 0;
                i = c;
            }
            None => i = next[i],
        }
    }
    let (a, c) = (prev[i], next[i]);
    if orient2d(q[a], q[i], q[c]) != Sign::Positive {
        exact = false;
    }
    out.push([a, i, c]);
    if exact { Outcome::Exact } else { Outcome::Approximate }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(tris: &[[u32; 3]], v: &[DVec3]) -> DVec3 {
        tris.iter().map(|t| (v[t[1] as usize] - v[t[0] as usize]).cross(v[t[2] as usize] - v[t[0] as usize]) * 0.5).sum()
    }

    fn xy(pts: &[(f64, f64)]) -> Vec<DVec3> {
        pts.iter().map(|&(x, y)| DVec3::new(x, y, 0.0)).collect()
    }

    #[test]
    fn quad_uses_the_shorter_diagonal_unless_it_lies_outside() {
        // a long thin rhombus: diagonal 1-3 is the short one
        let v = xy(&[(0.0, 0.0), (2.0, -0.5), (4.0, 0.0), (2.0, 0.5)]);
        let mut out = Vec::new();
        assert_eq!(triangulate(&[0, 1, 2, 3], &v, &mut out), Outcome::Exact);
        assert_eq!(out, vec![[0, 1, 3], [1, 2, 3]]);
        // a dart: the short diagonal 1-3 runs outside; 0-2 (through the reflex corner 2) is used
        let v = xy(&[(0.0, 0.0), (3.0, -0.5), (2.0, 0.0), (3.0, 0.5)]);
        let mut out = Vec::new();
        assert_eq!(triangulate(&[0, 1, 2, 3], &v, &mut out), Outcome::Exact);
        assert_eq!(out, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(area(&out, &v).z, 1.0);
    }

    #[test]
    fn ear_clipping_tiles_concave_and_tilted_polygons() {
        // an L-shape with a collinear corner, tilted out of every coordinate plane, clockwise
        let l = [(0.0, 0.0), (1.0, 0.0), (2.0, 0.0), (2.0, 1.0), (1.0, 1.0), (1.0, 2.0), (0.0, 2.0)];
        let rot = glam::DQuat::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), 0.7);
        let mut v: Vec<DVec3> = l.iter().rev().map(|&(x, y)| rot * DVec3::new(x, y, 0.0) + DVec3::splat(100.0)).collect();
        v.push(DVec3::ZERO);
        let idx: Vec<u32> = (0..7).collect();
        let mut out = Vec::new();
        assert_eq!(triangulate(&idx, &v, &mut out), Outcome::Exact);
        assert_eq!(out.len(), 5);
        let n = newell_normal(&v[..7]);
        let a = area(&out, &v);
        // all triangles turn like the polygon and their areas add up to its area (3)
        assert!((a.length() - 3.0).abs() < 1e-9, "{a}");
        assert!(a.dot(n) > 0.0);
        for t in &out {
            let tn = (v[t[1] as usize] - v[t[0] as usize]).cross(v[t[2] as usize] - v[t[0] as usize]);
            assert!(tn.dot(n) > 0.0, "triangle {t:?} is flipped or flat");
        }
    }

    #[test]
    fn degenerate_and_self_intersecting_polygons() {
        let v = xy(&[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (2.0, 2.0)]);
        let mut out = Vec::new();
        assert_eq!(triangulate(&[0, 0, 1, 1], &v, &mut out), Outcome::Degenerate);
        assert_eq!(triangulate(&[0, 1, 0], &v, &mut out), Outcome::Degenerate);
        assert_eq!(triangulate(&[0, 1, 9], &v, &mut out), Outcome::Degenerate);
        assert!(out.is_empty());
        // repeated neighbours are merged: a quad with a doubled corner is a triangle
        assert_eq!(triangulate(&[0, 1, 1, 2, 0], &v, &mut out), Outcome::Exact);
        assert_eq!(out, vec![[0, 1, 2]]);
        // a bow-tie pentagon still gives three triangles with distinct corners
        out.clear();
        let bow = xy(&[(0.0, 0.0), (2.0, 2.0), (2.0, 0.0), (0.0, 2.0), (-1.0, 1.0)]);
        let o = triangulate(&[0, 1, 2, 3, 4], &bow, &mut out);
        assert_eq!(out.len(), 3);
        assert_eq!(o, Outcome::Approximate);
        // all corners collinear
        out.clear();
        let line = xy(&[(0.0, 0.0), (1.0, 0.0), (2.0, 0.0), (3.0, 0.0), (4.0, 0.0)]);
        assert_eq!(triangulate(&[0, 1, 2, 3, 4], &line, &mut out), Outcome::Approximate);
        assert_eq!(out.len(), 3);
    }
}
