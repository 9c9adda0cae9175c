//! Exact geometric predicates: the only place in fepre where a sign is decided.
//!
//! Stage: layer 0, used by every algorithm. Inputs are `f64` coordinates; outputs are [`Sign`]s
//! that are exact for the given floating-point inputs (Shewchuk's adaptive predicates through
//! the `robust` crate). Constructions elsewhere may round; decisions made here never do.
//!
//! # Conventions (pinned by the permutation tests below)
//! - [`orient2d`]`(a, b, c)` is `Positive` when `a, b, c` turn counter-clockwise.
//! - [`orient3d`]`(a, b, c, d)` is `Positive` when `det[b-a, c-a, d-a] > 0`, i.e. the tet
//!   `(a, b, c, d)` has positive volume: seen from `d`, `a, b, c` turn counter-clockwise.
//!   (This is the opposite sign of Shewchuk's `orient3d`.)
//! - [`incircle`]`(a, b, c, d)` is `Positive` when `d` lies strictly inside the circle through
//!   `a, b, c`, provided `orient2d(a, b, c)` is `Positive` (the sign flips with that orientation).
//! - [`insphere`]`(a, b, c, d, e)` is `Positive` when `e` lies strictly inside the sphere through
//!   `a, b, c, d`, provided `orient3d(a, b, c, d)` is `Positive` (it flips with that orientation).
//!
//! # Symbolic perturbation (simulation of simplicity)
//! The `_sos` variants take a vertex index per point and never return [`Sign::Zero`] for
//! points with distinct indices; where the exact sign is non-zero they return it unchanged.
//! - [`orient2d_sos`] and [`orient3d_sos`] perturb every coordinate: point `i`, coordinate `c`
//!   moves by `ε^(2^k)` with `k` growing with the rank of the point (larger vertex index first)
//!   and then with the axis, as in Edelsbrunner and Mücke's scheme. The sign is that of the
//!   first non-vanishing term of the expanded determinant, evaluated exactly.
//! - [`incircle_sos`] and [`insphere_sos`] perturb the lifting (`|p|² + ε^rank`), i.e. they
//!   decide as for a regular triangulation with infinitesimal weights, as CGAL's
//!   `side_of_oriented_sphere` does. The result is consistent over a whole point set, so a
//!   Delaunay triangulation of grid or cospherical points is unique and valid. Their
//!   precondition is that the first three (incircle) or four (insphere) points are not
//!   collinear (coplanar); otherwise they fall back to the coordinate perturbation of the
//!   lower-order minors, which is deterministic but not part of one global perturbation.

use glam::{DVec2, DVec3};
use robust::{Coord, Coord3D};

/// The sign of an exactly evaluated determinant.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Sign {
    /// Strictly negative.
    Negative = -1,
    /// Exactly zero: a degenerate configuration.
    Zero = 0,
    /// Strictly positive.
    Positive = 1,
}

impl Sign {
    /// The sign of `x` (`NaN` counts as zero).
    #[inline]
    pub fn of(x: f64) -> Sign {
        if x > 0.0 {
            Sign::Positive
        } else if x < 0.0 {
            Sign::Negative
        } else {
            Sign::Zero
        }
    }

    /// The opposite sign (`Zero` stays `Zero`).
    #[inline]
    pub fn reversed(self) -> Sign {
        match self {
            Sign::Negative => Sign::Positive,
            Sign::Zero => Sign::Zero,
            Sign::Positive => Sign::Negative,
        }
    }

    /// `-1`, `0` or `1`.
    #[inline]
    pub fn as_i32(self) -> i32 {
        self as i32
    }

    /// True for `Positive`.
    #[inline]
    pub fn is_positive(self) -> bool {
        self == Sign::Positive
    }

    /// True for `Negative`.
    #[inline]
    pub fn is_negative(self) -> bool {
        self == Sign::Negative
    }

    /// True for `Zero`.
    #[inline]
    pub fn is_zero(self) -> bool {
        self == Sign::Zero
    }

    /// The sign of the product of two signs.
    #[inline]
    pub fn times(self, other: Sign) -> Sign {
        match self.as_i32() * other.as_i32() {
            1 => Sign::Positive,
            -1 => Sign::Negative,
            _ => Sign::Zero,
        }
    }
}

#[inline]
fn c2(p: DVec2) -> Coord<f64> {
    Coord { x: p.x, y: p.y }
}

#[inline]
fn c3(p: DVec3) -> Coord3D<f64> {
    Coord3D { x: p.x, y: p.y, z: p.z }
}

/// Orientation of three points in the plane: `Positive` if counter-clockwise.
#[inline]
pub fn orient2d(a: DVec2, b: DVec2, c: DVec2) -> Sign {
    Sign::of(robust::orient2d(c2(a), c2(b), c2(c)))
}

/// Orientation of four points: `Positive` if the tet `(a, b, c, d)` has positive volume,
/// i.e. `det[b-a, c-a, d-a] > 0`.
#[inline]
pub fn orient3d(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Sign {
    Sign::of(robust::orient3d(c3(a), c3(b), c3(c), c3(d))).reversed()
}

/// In-circle test: `Positive` if `d` lies strictly inside the circle through `a, b, c` and
/// `a, b, c` are counter-clockwise (the sign flips for clockwise `a, b, c`).
#[inline]
pub fn incircle(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> Sign {
    Sign::of(robust::incircle(c2(a), c2(b), c2(c), c2(d)))
}

/// In-sphere test: `Positive` if `e` lies strictly inside the sphere through `a, b, c, d` and
/// [`orient3d`]`(a, b, c, d)` is `Positive` (the sign flips for a negative tet).
#[inline]
pub fn insphere(a: DVec3, b: DVec3, c: DVec3, d: DVec3, e: DVec3) -> Sign {
    Sign::of(robust::insphere(c3(a), c3(b), c3(c), c3(d), c3(e))).reversed()
}

/// Positions of `ids` sorted by decreasing vertex index: `order[0]` is the point whose
/// perturbation dominates.
#[inline]
fn rank_order<const N: usize>(ids: &[u32; N]) -> [usize; N] {
    let mut order: [usize; N] = std::array::from_fn(|i| i);
    // insertion sort: N <= 5
    for i in 1..N {
        let mut j = i;
        while j > 0 && ids[order[j - 1]] < ids[order[j]] {
            order.swap(j - 1, j);
            j -= 1;
        }
    }
    order
}

/// Parity (+1 / -1) of moving the listed rows (in the listed order) to the front, the other
/// rows keeping their relative order.
fn front_parity(rows: &[usize]) -> i32 {
    let mut moves = 0usize;
    for (j, &r) in rows.iter().enumerate() {
        let before = rows[..j].iter().filter(|&&q| q < r).count();
        moves += r - before;
    }
    if moves % 2 == 0 { 1 } else { -1 }
}

/// The sign of `det M(ε)` for the `(n+1) × (n+1)` matrix `M` whose row `i` is
/// `(p_i coordinates…, 1)` with every coordinate perturbed as described in the module
/// docs. `n` is 2 or 3; `minor` evaluates the exact sign of the minor that keeps the
/// given rows and coordinate axes (the column of ones is always kept).
fn coordinate_sos<const R: usize>(
    ids: &[u32; R],
    dims: usize,
    minor: &dyn Fn(&[usize], &[usize]) -> Sign,
) -> Sign {
    debug_assert_eq!(R, dims + 1);
    let order = rank_order(ids);
    // bit k <-> (row order[k / dims], axis k % dims); a smaller mask is a larger term.
    let bits = R * dims;
    let all_rows: Vec<usize> = (0..R).collect();
    let all_axes: Vec<usize> = (0..dims).collect();
    let s = minor(&all_rows, &all_axes);
    if !s.is_zero() {
        return s;
    }
    for mask in 1u32..(1u32 << bits) {
        let mut rows = [0usize; 4];
        let mut axes = [0usize; 4];
        let mut m = 0usize;
        let mut used_rows = 0u32;
        let mut used_axes = 0u32;
        let mut valid = true;
        for k in 0..bits {
            if mask & (1 << k) != 0 {
                let r = order[k / dims];
                let a = k % dims;
                if used_rows & (1 << r) != 0 || used_axes & (1 << a) != 0 {
                    valid = false;
                    break;
                }
                used_rows |= 1 << r;
                used_axes |= 1 << a;
                rows[m] = r;
                axes[m] = a;
                m += 1;
            }
        }
        if !valid || m > dims {
            continue;
        }
        // Replace column axes[j] by the unit vector e_{rows[j]}; bring those columns and rows
        // to the front (columns sorted by axis), leaving the complementary minor.
        let mut pairs: Vec<(usize, usize)> = (0..m).map(|j| (axes[j], rows[j])).collect();
        pairs.sort_unstable();
        let col_moves: usize = pairs.iter().enumerate().map(|(j, &(a, _))| a - j).sum();
        let row_list: Vec<usize> = pairs.iter().map(|&(_, r)| r).collect();
        let parity = front_parity(&row_list) * if col_moves % 2 == 0 { 1 } else { -1 };
        let keep_rows: Vec<usize> = (0..R).filter(|r| used_rows & (1 << r) == 0).collect();
        let keep_axes: Vec<usize> = (0..dims).filter(|a| used_axes & (1 << a) == 0).collect();
        let s = minor(&keep_rows, &keep_axes);
        if !s.is_zero() {
            return if parity > 0 { s } else { s.reversed() };
        }
    }
    Sign::Zero
}

/// Exact sign of the minor of `[coords | 1]` keeping `rows` (in order) and `axes`.
fn ones_minor<const R: usize>(coord: &dyn Fn(usize, usize) -> f64, rows: &[usize], axes: &[usize]) -> Sign {
    debug_assert_eq!(rows.len(), axes.len() + 1);
    let _ = R;
    match axes.len() {
        0 => Sign::Positive,
        1 => {
            let (u, v) = (coord(rows[0], axes[0]), coord(rows[1], axes[0]));
            // det [[u, 1], [v, 1]] = u - v, decided by comparison
            Sign::of(if u > v { 1.0 } else if u < v { -1.0 } else { 0.0 })
        }
        2 => {
            let p = |r: usize| Coord { x: coord(r, axes[0]), y: coord(r, axes[1]) };
            // det [[x_i, y_i, 1]] over three rows equals Shewchuk's orient2d
            Sign::of(robust::orient2d(p(rows[0]), p(rows[1]), p(rows[2])))
        }
        3 => {
            let p = |r: usize| Coord3D { x: coord(r, 0), y: coord(r, 1), z: coord(r, 2) };
            // det [[x, y, z, 1]] over four rows equals Shewchuk's orient3d
            Sign::of(robust::orient3d(p(rows[0]), p(rows[1]), p(rows[2]), p(rows[3])))
        }
        _ => unreachable!("at most three axes"),
    }
}

/// [`orient2d`] with symbolic perturbation: never `Zero` for distinct indices.
///
/// `p[k]` has vertex index `id[k]`. Where [`orient2d`] is non-zero the result equals it.
pub fn orient2d_sos(p: [DVec2; 3], id: [u32; 3]) -> Sign {
    let exact = orient2d(p[0], p[1], p[2]);
    if !exact.is_zero() {
        return exact;
    }
    let coord = |r: usize, a: usize| p[r][a];
    // det [[x, y, 1]] = orient2d, same sign convention
    coordinate_sos(&id, 2, &|rows, axes| ones_minor::<3>(&coord, rows, axes))
}

/// [`orient3d`] with symbolic perturbation: never `Zero` for distinct indices.
///
/// `p[k]` has vertex index `id[k]`. Where [`orient3d`] is non-zero the result equals it.
pub fn orient3d_sos(p: [DVec3; 4], id: [u32; 4]) -> Sign {
    let exact = orient3d(p[0], p[1], p[2], p[3]);
    if !exact.is_zero() {
        return exact;
    }
    let coord = |r: usize, a: usize| p[r][a];
    // det [[x, y, z, 1]] is Shewchuk's orient3d, the opposite of ours
    coordinate_sos(&id, 3, &|rows, axes| ones_minor::<4>(&coord, rows, axes)).reversed()
}

/// [`incircle`] with the lifting perturbed symbolically (a regular triangulation with
/// infinitesimal weights): never `Zero` when `a, b, c` are not collinear.
///
/// Where [`incircle`] is non-zero the result equals it.
pub fn incircle_sos(p: [DVec2; 4], id: [u32; 4]) -> Sign {
    let exact = incircle(p[0], p[1], p[2], p[3]);
    if !exact.is_zero() {
        return exact;
    }
    // det of rows (x, y, |p|² + ε_i, 1) equals Shewchuk's incircle (ours) at ε = 0; the
    // coefficient of ε_i is the cofactor (-1)^(i+3) · orient2d(other three, in order).
    let order = rank_order(&id);
    for pass in 0..2 {
        for &i in &order {
            let others: Vec<usize> = (0..4).filter(|&k| k != i).collect();
            let s = if pass == 0 {
                orient2d(p[others[0]], p[others[1]], p[others[2]])
            } else {
                orient2d_sos(
                    [p[others[0]], p[others[1]], p[others[2]]],
                    [id[others[0]], id[others[1]], id[others[2]]],
                )
            };
            if !s.is_zero() {
                // 0-based i: cofactor sign (-1)^(i+1+4-1) with 1-based row i+1, column 3
                return if (i + 3) % 2 == 0 { s.reversed() } else { s };
            }
        }
    }
    Sign::Zero
}

/// [`insphere`] with the lifting perturbed symbolically (a regular triangulation with
/// infinitesimal weights): never `Zero` when `a, b, c, d` are not coplanar.
///
/// Where [`insphere`] is non-zero the result equals it.
pub fn insphere_sos(p: [DVec3; 5], id: [u32; 5]) -> Sign {
    let exact = insphere(p[0], p[1], p[2], p[3], p[4]);
    if !exact.is_zero() {
        return exact;
    }
    // M5 rows (x, y, z, |p|² + ε_i, 1): det M5 is Shewchuk's insphere, the opposite of ours.
    // The coefficient of ε_i is (-1)^(i+4) (1-based i) times the 4×4 [x y z 1] minor of the
    // other rows, which is Shewchuk's orient3d = -(our orient3d).
    let order = rank_order(&id);
    for pass in 0..2 {
        for &i in &order {
            let o: Vec<usize> = (0..5).filter(|&k| k != i).collect();
            let ours = if pass == 0 {
                orient3d(p[o[0]], p[o[1]], p[o[2]], p[o[3]])
            } else {
                orient3d_sos([p[o[0]], p[o[1]], p[o[2]], p[o[3]]], [id[o[0]], id[o[1]], id[o[2]], id[o[3]]])
            };
            if !ours.is_zero() {
                // det M5 coefficient sign = (-1)^(i+1+4) · (-ours); our result = -det M5
                let cof_even = (i + 1 + 4) % 2 == 0;
                let det_sign = if cof_even { ours.reversed() } else { ours };
                return det_sign.reversed();
            }
        }
    }
    Sign::Zero
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v3(x: f64, y: f64, z: f64) -> DVec3 {
        DVec3::new(x, y, z)
    }

    #[test]
    fn conventions() {
        let o = v3(0.0, 0.0, 0.0);
        let x = v3(1.0, 0.0, 0.0);
        let y = v3(0.0, 1.0, 0.0);
        let z = v3(0.0, 0.0, 1.0);
        assert_eq!(orient3d(o, x, y, z), Sign::Positive);
        assert_eq!(orient3d(o, y, x, z), Sign::Negative);
        assert_eq!(orient3d(o, x, y, v3(3.0, 4.0, 0.0)), Sign::Zero);
        let (a, b, c) = (DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0), DVec2::new(0.0, 1.0));
        assert_eq!(orient2d(a, b, c), Sign::Positive);
        assert_eq!(incircle(a, b, c, DVec2::new(0.4, 0.4)), Sign::Positive);
        assert_eq!(incircle(a, b, c, DVec2::new(2.0, 2.0)), Sign::Negative);
        assert_eq!(incircle(a, b, c, DVec2::new(1.0, 1.0)), Sign::Zero);
        assert_eq!(incircle(a, c, b, DVec2::new(0.4, 0.4)), Sign::Negative);
        assert_eq!(insphere(o, x, y, z, v3(0.3, 0.3, 0.3)), Sign::Positive);
        assert_eq!(insphere(o, x, y, z, v3(2.0, 2.0, 2.0)), Sign::Negative);
        assert_eq!(insphere(o, x, y, z, v3(1.0, 1.0, 1.0)), Sign::Zero);
        assert_eq!(insphere(o, y, x, z, v3(0.3, 0.3, 0.3)), Sign::Negative);
    }

    #[test]
    fn sos_resolves_cospherical_and_coplanar() {
        // eight cube corners are cospherical; every pair of tets must get opposite answers
        let c: Vec<DVec3> = (0..8).map(|i| v3((i & 1) as f64, ((i >> 1) & 1) as f64, (i >> 2) as f64)).collect();
        let tet = [0usize, 1, 2, 4];
        assert_eq!(orient3d(c[0], c[1], c[2], c[4]), Sign::Positive);
        let s = insphere_sos([c[0], c[1], c[2], c[4], c[7]], [0, 1, 2, 4, 7]);
        assert_ne!(s, Sign::Zero);
        let _ = tet;
        // coplanar: four points of the bottom face
        let s = orient3d_sos([c[0], c[1], c[2], c[3]], [0, 1, 2, 3]);
        assert_ne!(s, Sign::Zero);
        let t = orient3d_sos([c[1], c[0], c[2], c[3]], [1, 0, 2, 3]);
        assert_eq!(t, s.reversed());
        // collinear in 2D
        let p = [DVec2::new(0.0, 0.0), DVec2::new(1.0, 1.0), DVec2::new(2.0, 2.0)];
        let s = orient2d_sos(p, [0, 1, 2]);
        assert_ne!(s, Sign::Zero);
        assert_eq!(orient2d_sos([p[1], p[0], p[2]], [1, 0, 2]), s.reversed());
    }
}
