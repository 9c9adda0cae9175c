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
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize)]
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

    /// The sign of an exact integer.
    #[inline]
    pub fn of_i128(x: i128) -> Sign {
        match x.cmp(&0) {
            std::cmp::Ordering::Greater => Sign::Positive,
            std::cmp::Ordering::Less => Sign::Negative,
            std::cmp::Ordering::Equal => Sign::Zero,
        }
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
///
/// [`orient3d_filter`] decides first; `robust`'s adaptive evaluation decides the rest.
#[inline]
pub fn orient3d(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Sign {
    let diff = |p: DVec3| [p.x - d.x, p.y - d.y, p.z - d.z];
    match orient3d_filter(diff(a), diff(b), diff(c)) {
        Some(s) => s,
        // four points with one coordinate equal lie in a plane of the axes: the determinant
        // has a zero column (most ties on CAD parts, which the adaptive stages would spend
        // their every stage on)
        None if (0..3).any(|k| a[k] == d[k] && b[k] == d[k] && c[k] == d[k]) => Sign::Zero,
        None => Sign::of(robust::orient3d(c3(a), c3(b), c3(c), c3(d))).reversed(),
    }
}

/// A semi-static filter for [`orient3d`], given the rounded differences `a - d`, `b - d`,
/// `c - d`: the sign when it is certain, `None` otherwise.
///
/// The determinant is evaluated as in Shewchuk's first stage; his error bound is
/// `(7 + 56ε)ε · permanent`, the permanent at most `6 m³ ≤ 6 L^1.5` with `L` the largest
/// `|x - d|²`. The sign is certain when `det² > (4.9e-15)² · L³` (`4.9e-15` covers
/// `6 · (7 + 56ε)ε = 4.663e-15` with margin for the rounding of the squares and powers).
#[inline(always)]
pub fn orient3d_filter(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> Option<Sign> {
    let det = a[0] * (b[1] * c[2] - b[2] * c[1]) + b[0] * (c[1] * a[2] - c[2] * a[1]) + c[0] * (a[1] * b[2] - a[2] * b[1]);
    let lift = |p: [f64; 3]| p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
    let (la, lb, lc) = (lift(a), lift(b), lift(c));
    let l1 = if la > lb { la } else { lb };
    let l = if l1 > lc { l1 } else { lc };
    if !(l > 1e-90 && l < 1e90) {
        return None;
    }
    if det * det > 2.4e-29 * (l * l * l) {
        // det[a-d, b-d, c-d] is Shewchuk's orient3d, the opposite of ours
        Some(if det > 0.0 { Sign::Negative } else { Sign::Positive })
    } else {
        None
    }
}

/// In-circle test: `Positive` if `d` lies strictly inside the circle through `a, b, c` and
/// `a, b, c` are counter-clockwise (the sign flips for clockwise `a, b, c`).
#[inline]
pub fn incircle(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> Sign {
    Sign::of(robust::incircle(c2(a), c2(b), c2(c), c2(d)))
}

/// In-sphere test: `Positive` if `e` lies strictly inside the sphere through `a, b, c, d` and
/// [`orient3d`]`(a, b, c, d)` is `Positive` (the sign flips for a negative tet).
///
/// [`insphere_filter`] decides first; `robust`'s adaptive evaluation decides the rest.
#[inline]
pub fn insphere(a: DVec3, b: DVec3, c: DVec3, d: DVec3, e: DVec3) -> Sign {
    let diff = |p: DVec3| [p.x - e.x, p.y - e.y, p.z - e.z];
    match insphere_filter(diff(a), diff(b), diff(c), diff(d)) {
        Some(s) => s,
        None => Sign::of(robust::insphere(c3(a), c3(b), c3(c), c3(d), c3(e))).reversed(),
    }
}

/// A semi-static filter for [`insphere`], given the rounded differences `a - e`, `b - e`,
/// `c - e`, `d - e`: the sign when it is certain, `None` otherwise.
///
/// The determinant is evaluated as in Shewchuk's first stage; his error bound is
/// `(16 + 224ε)ε · permanent`. With `L` the largest lift `|a - e|²` (so every difference is at
/// most `√L`), each 2×2 product sum is at most `2L`, each 3×3 at most `6L^1.5`, each lift at most
/// `L`... more tightly every coordinate is at most `m ≤ √L` and the permanent at most
/// `72 m⁵ ≤ 72 L^2.5`. The sign is certain when `det² > (1.3e-13)² · L⁵` (`1.3e-13` covers
/// `72 · (16 + 224ε)ε = 1.279e-13` with margin for the rounding of the squares and powers).
/// `None` also when `L` is so small or large that the powers could underflow or overflow.
#[inline(always)]
pub fn insphere_filter(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> Option<Sign> {
    let ab = a[0] * b[1] - b[0] * a[1];
    let bc = b[0] * c[1] - c[0] * b[1];
    let cd = c[0] * d[1] - d[0] * c[1];
    let da = d[0] * a[1] - a[0] * d[1];
    let ac = a[0] * c[1] - c[0] * a[1];
    let bd = b[0] * d[1] - d[0] * b[1];
    let abc = a[2] * bc - b[2] * ac + c[2] * ab;
    let bcd = b[2] * cd - c[2] * bd + d[2] * bc;
    let cda = c[2] * da + d[2] * ac + a[2] * cd;
    let dab = d[2] * ab + a[2] * bd + b[2] * da;
    let lift = |p: [f64; 3]| p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
    let (la, lb, lc, ld) = (lift(a), lift(b), lift(c), lift(d));
    let det = (ld * abc - lc * dab) + (lb * cda - la * bcd);
    // plain comparisons: the lifts are never NaN for finite input (NaN fails the range test)
    let l1 = if la > lb { la } else { lb };
    let l2 = if lc > ld { lc } else { ld };
    let l = if l1 > l2 { l1 } else { l2 };
    if !(l > 1e-55 && l < 1e55) {
        return None;
    }
    let l2 = l * l;
    let bound2 = 1.69e-26 * (l2 * l2 * l);
    if det * det > bound2 {
        // Shewchuk's sign is the opposite of ours
        Some(if det > 0.0 { Sign::Negative } else { Sign::Positive })
    } else {
        None
    }
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
    let s = lifted_sos(&id, |o| orient3d(p[o[0]], p[o[1]], p[o[2]], p[o[3]]));
    if !s.is_zero() {
        return s;
    }
    lifted_sos(&id, |o| orient3d_sos([p[o[0]], p[o[1]], p[o[2]], p[o[3]]], [id[o[0]], id[o[1]], id[o[2]], id[o[3]]]))
}

/// The sign of the perturbed in-sphere determinant when the exact one vanishes.
///
/// M5 has rows (x, y, z, |p|² + ε_i, 1); det M5 is Shewchuk's insphere, the opposite of ours.
/// The coefficient of ε_i is (-1)^(i+4) (1-based i) times the 4×4 [x y z 1] minor of the other
/// rows, which is Shewchuk's orient3d = -(our orient3d). The largest perturbation belongs to
/// the largest vertex index. `orient` gives our orient3d of the four points listed.
#[inline]
fn lifted_sos(id: &[u32; 5], mut orient: impl FnMut([usize; 4]) -> Sign) -> Sign {
    for i in rank_order(id) {
        let mut o = [0usize; 4];
        let mut k = 0;
        for j in 0..5 {
            if j != i {
                o[k] = j;
                k += 1;
            }
        }
        let ours = orient(o);
        if !ours.is_zero() {
            // det M5 coefficient sign = (-1)^(i+1+4) · (-ours); our result = -det M5
            let cof_even = (i + 1 + 4) % 2 == 0;
            let det_sign = if cof_even { ours.reversed() } else { ours };
            return det_sign.reversed();
        }
    }
    Sign::Zero
}

/// Largest magnitude of an integer coordinate accepted by the integer predicates: coordinate
/// differences then stay below 2^24 and every in-sphere term below 2^127.
pub const INT_COORD_LIMIT: i32 = (1 << 23) - 1;

#[inline]
fn diff_i(a: [i32; 3], b: [i32; 3]) -> [i64; 3] {
    [a[0] as i64 - b[0] as i64, a[1] as i64 - b[1] as i64, a[2] as i64 - b[2] as i64]
}

/// [`orient3d`] for integer coordinates of magnitude at most [`INT_COORD_LIMIT`], exact in
/// `i128` (same sign convention).
#[inline]
pub fn orient3d_int(a: [i32; 3], b: [i32; 3], c: [i32; 3], d: [i32; 3]) -> Sign {
    let (u, v, w) = (diff_i(b, a), diff_i(c, a), diff_i(d, a));
    // the products of two differences fit i64 (< 2^48); the triple products need i128
    let m0 = (v[1] * w[2] - v[2] * w[1]) as i128;
    let m1 = (v[0] * w[2] - v[2] * w[0]) as i128;
    let m2 = (v[0] * w[1] - v[1] * w[0]) as i128;
    let det = u[0] as i128 * m0 - u[1] as i128 * m1 + u[2] as i128 * m2;
    Sign::of_i128(det)
}

/// [`insphere`] for integer coordinates of magnitude at most [`INT_COORD_LIMIT`] (same sign
/// convention): a floating-point evaluation with a certified error bound decides when it can,
/// an exact `i128` evaluation otherwise.
#[inline]
pub fn insphere_int(a: [i32; 3], b: [i32; 3], c: [i32; 3], d: [i32; 3], e: [i32; 3]) -> Sign {
    let r = [diff_i(a, e), diff_i(b, e), diff_i(c, e), diff_i(d, e)];
    // |x|² < 3·2^48: exact in f64 and i64
    let w: [i64; 4] = r.map(|q| q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
    // 3×3 minors of the rows other than i, by 2×2 minors of rows pairs (exact in i64)
    let m2 = |i: usize, j: usize, x: usize, y: usize| r[i][x] * r[j][y] - r[i][y] * r[j][x];
    // float filter: differences and lifts are exact in f64; the evaluation below makes at
    // most ~10 roundings of relative size 2^-53 on terms bounded by the permanent
    let f = r.map(|q| q.map(|x| x as f64));
    let minor_f = |i: usize, j: usize, k: usize| -> (f64, f64) {
        let (p, q, s) = (f[i], f[j], f[k]);
        let v = p[0] * (q[1] * s[2] - q[2] * s[1]) - p[1] * (q[0] * s[2] - q[2] * s[0]) + p[2] * (q[0] * s[1] - q[1] * s[0]);
        let pa = |t: [f64; 3]| t.map(f64::abs);
        let (p, q, s) = (pa(p), pa(q), pa(s));
        let perm = p[0] * (q[1] * s[2] + q[2] * s[1]) + p[1] * (q[0] * s[2] + q[2] * s[0]) + p[2] * (q[0] * s[1] + q[1] * s[0]);
        (v, perm)
    };
    let wf = w.map(|x| x as f64);
    let (m0, p0) = minor_f(1, 2, 3);
    let (m1, p1) = minor_f(0, 2, 3);
    let (m2f, p2) = minor_f(0, 1, 3);
    let (m3, p3) = minor_f(0, 1, 2);
    // det of rows (x, y, z, w) expanded along w: -w0 M0 + w1 M1 - w2 M2 + w3 M3 (Shewchuk's sign)
    let det = -wf[0] * m0 + wf[1] * m1 - wf[2] * m2f + wf[3] * m3;
    let perm = wf[0] * p0 + wf[1] * p1 + wf[2] * p2 + wf[3] * p3;
    let bound = 1e-14 * perm;
    if det > bound {
        return Sign::Negative;
    }
    if det < -bound {
        return Sign::Positive;
    }
    let minor_i = |i: usize, j: usize, k: usize| -> i128 {
        r[i][0] as i128 * m2(j, k, 1, 2) as i128 - r[i][1] as i128 * m2(j, k, 0, 2) as i128
            + r[i][2] as i128 * m2(j, k, 0, 1) as i128
    };
    let det = -(w[0] as i128) * minor_i(1, 2, 3) + w[1] as i128 * minor_i(0, 2, 3) - w[2] as i128 * minor_i(0, 1, 3)
        + w[3] as i128 * minor_i(0, 1, 2);
    // det above is Shewchuk's insphere; ours is its opposite
    Sign::of_i128(det).reversed()
}

/// [`insphere_sos`] for integer coordinates of magnitude at most [`INT_COORD_LIMIT`]: the same
/// perturbation, so the same decisions as on the equal `f64` coordinates.
pub fn insphere_sos_int(p: [[i32; 3]; 5], id: [u32; 5]) -> Sign {
    let exact = insphere_int(p[0], p[1], p[2], p[3], p[4]);
    if !exact.is_zero() {
        return exact;
    }
    let s = lifted_sos(&id, |o| orient3d_int(p[o[0]], p[o[1]], p[o[2]], p[o[3]]));
    if !s.is_zero() {
        return s;
    }
    let f = p.map(|q| DVec3::new(q[0] as f64, q[1] as f64, q[2] as f64));
    lifted_sos(&id, |o| orient3d_sos([f[o[0]], f[o[1]], f[o[2]], f[o[3]]], [id[o[0]], id[o[1]], id[o[2]], id[o[3]]]))
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

    proptest::proptest! {
        /// Points in a plane of the axes are decided without the adaptive stages, as those
        /// decide.
        #[test]
        fn points_in_a_plane_of_the_axes_are_coplanar(k in 0usize..3, level in -100.0f64..100.0, c in proptest::array::uniform12(-100.0f64..100.0)) {
            let mut p = [0, 1, 2, 3].map(|i| v3(c[3 * i], c[3 * i + 1], c[3 * i + 2]));
            for q in &mut p {
                q[k] = level;
            }
            proptest::prop_assert_eq!(Sign::of(robust::orient3d(c3(p[0]), c3(p[1]), c3(p[2]), c3(p[3]))), Sign::Zero);
            proptest::prop_assert_eq!(orient3d(p[0], p[1], p[2], p[3]), Sign::Zero);
            // one point off the plane by the least amount: decided, and as Shewchuk's
            p[3][k] = level.next_up();
            let shewchuk = Sign::of(robust::orient3d(c3(p[0]), c3(p[1]), c3(p[2]), c3(p[3]))).reversed();
            proptest::prop_assert_eq!(orient3d(p[0], p[1], p[2], p[3]), shewchuk);
        }
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
