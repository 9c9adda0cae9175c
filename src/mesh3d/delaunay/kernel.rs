//! The two exact kernels the Delaunay insertion runs on, chosen once per input.
//!
//! - [`IntKernel`]: when every coordinate is an integer multiple of one power of two and the
//!   scaled coordinates, shifted to start at zero, fit [`INT_COORD_LIMIT`] (grids, integer and
//!   dyadic data), the points are stored as `i32` triples and decided by the integer
//!   predicates: exact in `i128` behind a float filter, fast even when nearly every test is a
//!   tie (a grid's cospherical cells).
//! - [`FloatKernel`]: otherwise, `robust`'s adaptive predicates on the `f64` coordinates.
//!
//! Scaling by a power of two and shifting by an integer are exact, so both kernels decide the
//! same signs on the same input; ties are broken by the same lifting perturbation by vertex
//! index.

use crate::core::predicates::{
    INT_COORD_LIMIT, insphere, insphere_filter, insphere_int, insphere_sos, insphere_sos_int, orient3d, orient3d_filter, orient3d_int,
};
use crate::core::Sign;
use crate::core::predicates::orient2d;
use glam::{DVec2, DVec3};

/// Exact orientation and in-sphere decisions on points addressed by their internal index (the
/// Hilbert rank, so that spatial neighbours are memory neighbours). Ties are broken by the
/// points' original indices, so the result does not depend on the internal numbering.
pub(crate) trait Kernel: Sync {
    /// [`orient3d`] of four points.
    fn orient(&self, a: u32, b: u32, c: u32, d: u32) -> Sign;
    /// The perturbed in-sphere test of `e` against the positively oriented tet `t`.
    fn insphere(&self, t: [u32; 4], e: u32) -> Sign;
    /// True if two points have equal coordinates.
    fn same(&self, a: u32, b: u32) -> bool;
    /// True if three points lie on one line (exactly).
    fn collinear(&self, a: u32, b: u32, c: u32) -> bool;
    /// The original index of internal point `i`.
    fn original(&self, i: u32) -> u32;
    /// Number of points.
    fn len(&self) -> usize;
    /// Coordinate `axis` of point `i` (in the kernel's own units: only its order matters).
    fn coord(&self, i: u32, axis: usize) -> f64;
}

/// `robust`'s adaptive predicates on `f64` points.
pub(crate) struct FloatKernel {
    /// Points by internal index.
    pub points: Vec<DVec3>,
    /// Original index of every internal index (the tie-break order).
    pub ids: Vec<u32>,
}

impl Kernel for FloatKernel {
    #[inline]
    fn orient(&self, a: u32, b: u32, c: u32, d: u32) -> Sign {
        let p = &self.points;
        let pd = p[d as usize];
        let diff = |i: u32| {
            let q = p[i as usize];
            [q.x - pd.x, q.y - pd.y, q.z - pd.z]
        };
        match orient3d_filter(diff(a), diff(b), diff(c)) {
            Some(s) => s,
            None => orient3d(p[a as usize], p[b as usize], p[c as usize], pd),
        }
    }

    #[inline]
    fn insphere(&self, t: [u32; 4], e: u32) -> Sign {
        let p = &self.points;
        let pe = p[e as usize];
        let diff = |i: u32| {
            let q = p[i as usize];
            [q.x - pe.x, q.y - pe.y, q.z - pe.z]
        };
        if let Some(s) = insphere_filter(diff(t[0]), diff(t[1]), diff(t[2]), diff(t[3])) {
            return s;
        }
        self.insphere_exact(t, e)
    }

    #[inline]
    fn same(&self, a: u32, b: u32) -> bool {
        self.points[a as usize] == self.points[b as usize]
    }

    fn collinear(&self, a: u32, b: u32, c: u32) -> bool {
        let p = |i: u32, x: usize, y: usize| DVec2::new(self.points[i as usize][x], self.points[i as usize][y]);
        [(0, 1), (1, 2), (2, 0)].iter().all(|&(x, y)| orient2d(p(a, x, y), p(b, x, y), p(c, x, y)).is_zero())
    }

    fn original(&self, i: u32) -> u32 {
        self.ids[i as usize]
    }

    fn len(&self) -> usize {
        self.points.len()
    }

    fn coord(&self, i: u32, axis: usize) -> f64 {
        self.points[i as usize][axis]
    }
}

impl FloatKernel {
    /// The adaptive evaluation and, on a tie, the perturbation (the filter's rare fallback).
    #[cold]
    fn insphere_exact(&self, t: [u32; 4], e: u32) -> Sign {
        let p = &self.points;
        let q = [p[t[0] as usize], p[t[1] as usize], p[t[2] as usize], p[t[3] as usize], p[e as usize]];
        let s = insphere(q[0], q[1], q[2], q[3], q[4]);
        if !s.is_zero() {
            return s;
        }
        let id = |i: u32| self.ids[i as usize];
        insphere_sos(q, [id(t[0]), id(t[1]), id(t[2]), id(t[3]), id(e)])
    }
}

/// Exact integer predicates on scaled, shifted integer points.
pub(crate) struct IntKernel {
    /// Points by internal index.
    pub points: Vec<[i32; 3]>,
    /// Original index of every internal index (the tie-break order).
    pub ids: Vec<u32>,
}

impl Kernel for IntKernel {
    #[inline]
    fn orient(&self, a: u32, b: u32, c: u32, d: u32) -> Sign {
        let p = &self.points;
        orient3d_int(p[a as usize], p[b as usize], p[c as usize], p[d as usize])
    }

    #[inline]
    fn insphere(&self, t: [u32; 4], e: u32) -> Sign {
        let p = &self.points;
        let q = [p[t[0] as usize], p[t[1] as usize], p[t[2] as usize], p[t[3] as usize], p[e as usize]];
        let s = insphere_int(q[0], q[1], q[2], q[3], q[4]);
        if !s.is_zero() {
            return s;
        }
        let id = |i: u32| self.ids[i as usize];
        insphere_sos_int(q, [id(t[0]), id(t[1]), id(t[2]), id(t[3]), id(e)])
    }

    #[inline]
    fn same(&self, a: u32, b: u32) -> bool {
        self.points[a as usize] == self.points[b as usize]
    }

    fn collinear(&self, a: u32, b: u32, c: u32) -> bool {
        let (pa, pb, pc) = (self.points[a as usize], self.points[b as usize], self.points[c as usize]);
        let u = [0, 1, 2].map(|k| pb[k] as i64 - pa[k] as i64);
        let v = [0, 1, 2].map(|k| pc[k] as i64 - pa[k] as i64);
        // the cross product of differences below 2^24 is exact in i64
        u[1] * v[2] == u[2] * v[1] && u[2] * v[0] == u[0] * v[2] && u[0] * v[1] == u[1] * v[0]
    }

    fn original(&self, i: u32) -> u32 {
        self.ids[i as usize]
    }

    fn len(&self) -> usize {
        self.points.len()
    }

    fn coord(&self, i: u32, axis: usize) -> f64 {
        self.points[i as usize][axis] as f64
    }
}

/// The integer image of `points` if they are all integer multiples of one power of two whose
/// scaled range fits [`INT_COORD_LIMIT`] on every axis; `None` otherwise (or for non-finite
/// points).
pub(crate) fn integer_points(points: &[DVec3]) -> Option<Vec<[i32; 3]>> {
    if points.is_empty() || points.iter().any(|p| !p.is_finite()) {
        return None;
    }
    // the smallest binary exponent of a set bit over all coordinates: every coordinate is an
    // integer multiple of 2^emin
    let mut emin = i32::MAX;
    for p in points {
        for x in p.to_array() {
            if x != 0.0 {
                emin = emin.min(lowest_bit_exponent(x));
            }
        }
    }
    if emin == i32::MAX {
        emin = 0; // all zero
    }
    let scale = 2f64.powi(-emin);
    if !scale.is_finite() || scale == 0.0 {
        return None;
    }
    let lo = points.iter().fold(DVec3::splat(f64::INFINITY), |m, p| m.min(*p));
    let mut out = Vec::with_capacity(points.len());
    let limit = INT_COORD_LIMIT as f64;
    // shift by the integer nearest the centre so the range is symmetric about zero
    let hi = points.iter().fold(DVec3::splat(f64::NEG_INFINITY), |m, p| m.max(*p));
    let centre = ((lo * scale + hi * scale) * 0.5).floor();
    for p in points {
        let q = *p * scale - centre; // exact: integers below 2^53 after scaling
        if q.abs().max_element() > limit {
            return None;
        }
        out.push([q.x as i32, q.y as i32, q.z as i32]);
    }
    // the integer coordinates must be exactly the scaled ones (no rounding anywhere)
    let exact = points.iter().zip(&out).all(|(p, q)| {
        let back = (DVec3::new(q[0] as f64, q[1] as f64, q[2] as f64) + centre) / scale;
        back == *p
    });
    exact.then_some(out)
}

/// The exponent of the lowest set bit of a finite non-zero `x`: `x` is an odd integer times
/// `2^e`.
fn lowest_bit_exponent(x: f64) -> i32 {
    let bits = x.to_bits();
    let exp = ((bits >> 52) & 0x7ff) as i32;
    let mant = bits & ((1u64 << 52) - 1);
    let (m, e) = if exp == 0 { (mant, -1074) } else { (mant | (1u64 << 52), exp - 1075) };
    e + m.trailing_zeros() as i32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn detects_dyadic_grids_only() {
        let g: Vec<DVec3> = (0..27).map(|i| DVec3::new((i % 3) as f64, ((i / 3) % 3) as f64, (i / 9) as f64) * 0.25).collect();
        let ints = integer_points(&g).expect("a grid of spacing 1/4 is dyadic");
        assert_eq!(ints[26][0] - ints[0][0], 2);
        let ids: Vec<u32> = (0..27).collect();
        let k = IntKernel { points: ints, ids: ids.clone() };
        let f = FloatKernel { points: g.clone(), ids };
        for t in [[0u32, 1, 3, 9], [13, 14, 16, 22]] {
            for e in 0..27 {
                if !t.contains(&e) {
                    assert_eq!(k.insphere(t, e), f.insphere(t, e));
                }
            }
            assert_eq!(k.orient(t[0], t[1], t[2], t[3]), f.orient(t[0], t[1], t[2], t[3]));
        }
        // a single non-round point is still one integer times a power of two
        assert!(integer_points(&[DVec3::new(0.1, 0.0, 0.0)]).is_some());
    }

    #[test]
    fn rejects_wide_or_fine_ranges() {
        // 1e9 = 2^9 · 1953125 fits; an odd number above 2^23 does not
        assert!(integer_points(&[DVec3::ZERO, DVec3::new(1e9, 0.0, 0.0)]).is_some());
        assert!(integer_points(&[DVec3::ZERO, DVec3::new(1e9 + 1.0, 0.0, 0.0)]).is_none());
        assert!(integer_points(&[DVec3::new(0.1, 0.0, 0.0), DVec3::new(0.3, 0.0, 0.0)]).is_none());
        assert!(integer_points(&[DVec3::new(f64::NAN, 0.0, 0.0)]).is_none());
        assert_eq!(lowest_bit_exponent(1.0), 0);
        assert_eq!(lowest_bit_exponent(0.75), -2);
        assert_eq!(lowest_bit_exponent(96.0), 5);
    }
}
