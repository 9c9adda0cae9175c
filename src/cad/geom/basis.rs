//! B-spline basis functions (Cox–de Boor) and their derivatives, on expanded knot vectors.
//!
//! Written for fepre after the triangular-table scheme of Piegl & Tiller, *The NURBS Book*,
//! algorithms A2.1–A2.3: the non-zero basis functions of one span and their first two
//! derivatives are computed together in O(p²).

use super::spline_error::SplineError;

/// Largest degree accepted (OpenCASCADE's limit too).
pub const MAX_DEGREE: usize = 25;

const M: usize = MAX_DEGREE + 1;

/// Checks control points (finite) and their weights (as many, positive, finite); returns the
/// weights to keep: `None` when there are none or all are equal (the spline is polynomial).
pub fn check_points_weights(points: &[glam::DVec3], weights: Option<Vec<f64>>) -> Result<Option<Vec<f64>>, SplineError> {
    if let Some(w) = &weights {
        if w.len() != points.len() {
            return Err(SplineError::WeightCount { weights: w.len(), points: points.len() });
        }
        if let Some(index) = w.iter().position(|&x| !(x > 0.0 && x.is_finite())) {
            return Err(SplineError::Weight { index, weight: w[index] });
        }
    }
    if let Some(index) = points.iter().position(|p| !p.is_finite()) {
        return Err(SplineError::PointNotFinite { index });
    }
    Ok(weights.filter(|w| w.iter().any(|&x| x != w[0])))
}

/// Checks a knot vector (with repeated knots written out) for `n` control points of degree
/// `degree`: length `n + degree + 1`, finite, non-decreasing, no knot repeated more than
/// `degree + 1` times, and a non-empty domain `[knots[degree], knots[n]]`.
pub fn check_knots(degree: usize, knots: &[f64], n: usize) -> Result<(), SplineError> {
    if degree == 0 || degree > MAX_DEGREE {
        return Err(SplineError::Degree { degree, max: MAX_DEGREE });
    }
    if n < degree + 1 {
        return Err(SplineError::TooFewPoints { points: n, degree });
    }
    if knots.len() != n + degree + 1 {
        return Err(SplineError::KnotCount { knots: knots.len(), points: n, degree });
    }
    if let Some(index) = knots.iter().position(|k| !k.is_finite()) {
        return Err(SplineError::KnotNotFinite { index, knot: knots[index] });
    }
    let mut run = 1;
    for i in 1..knots.len() {
        if knots[i] < knots[i - 1] {
            return Err(SplineError::KnotsDecrease { index: i, knot: knots[i], previous: knots[i - 1] });
        }
        run = if knots[i] == knots[i - 1] { run + 1 } else { 1 };
        if run > degree + 1 {
            return Err(SplineError::KnotRepeated { index: i, knot: knots[i], degree });
        }
    }
    if !(knots[degree] < knots[n]) {
        return Err(SplineError::EmptyDomain);
    }
    Ok(())
}

/// Expands knot values and multiplicities (STEP's form) into the full knot vector.
pub fn expand_knots(values: &[f64], multiplicities: &[i64]) -> Result<Vec<f64>, SplineError> {
    if values.len() != multiplicities.len() {
        return Err(SplineError::MultiplicityCount { values: values.len(), multiplicities: multiplicities.len() });
    }
    let total: i64 = multiplicities.iter().map(|&m| m.max(0)).sum();
    if multiplicities.iter().any(|&m| m < 1) || total > 10_000_000 {
        return Err(SplineError::Multiplicities { index: multiplicities.iter().position(|&m| m < 1) });
    }
    let mut out = Vec::with_capacity(total as usize);
    for (&k, &m) in values.iter().zip(multiplicities) {
        for _ in 0..m {
            out.push(k);
        }
    }
    Ok(out)
}

/// Index `i` of the knot span `[knots[i], knots[i+1])` holding `t`, for `n` control points;
/// always a non-empty span in `degree..n`. Parameters outside the domain get the first or last
/// span (evaluation then extrapolates the end polynomial).
pub fn find_span(knots: &[f64], degree: usize, n: usize, t: f64) -> usize {
    let (lo_k, hi_k) = (knots[degree], knots[n]);
    if !(t < hi_k) {
        let mut i = n - 1;
        while i > degree && knots[i] == knots[i + 1] {
            i -= 1;
        }
        return i;
    }
    if t <= lo_k {
        let mut i = degree;
        while i < n - 1 && knots[i] == knots[i + 1] {
            i += 1;
        }
        return i;
    }
    // knots[lo] <= t < knots[hi]
    let (mut lo, mut hi) = (degree, n);
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        if t < knots[mid] { hi = mid } else { lo = mid }
    }
    lo
}

/// The `degree + 1` non-zero basis functions at `t` in span `span`, and their derivatives up to
/// order `nd` (at most 2): `out[k][j]` is the k-th derivative of `N_{span-degree+j}`.
pub fn basis_derivatives(knots: &[f64], degree: usize, span: usize, t: f64, nd: usize, out: &mut [[f64; M]; 3]) {
    // the work tables sized for the degree: zeroing the largest (26 × 26) on every call took
    // a third of the time of tessellating B-spline parts
    if degree < 8 { basis_derivatives_in::<8>(knots, degree, span, t, nd, out) } else { basis_derivatives_in::<M>(knots, degree, span, t, nd, out) }
}

/// [`basis_derivatives`] with work tables of `N > degree` rows.
fn basis_derivatives_in<const N: usize>(knots: &[f64], degree: usize, span: usize, t: f64, nd: usize, out: &mut [[f64; M]; 3]) {
    let p = degree;
    let nd = nd.min(2);
    let mut ndu = [[0.0f64; N]; N];
    let mut left = [0.0f64; N];
    let mut right = [0.0f64; N];
    ndu[0][0] = 1.0;
    for j in 1..=p {
        left[j] = t - knots[span + 1 - j];
        right[j] = knots[span + j] - t;
        let mut saved = 0.0;
        for r in 0..j {
            // lower triangle: knot differences; upper triangle: basis functions
            ndu[j][r] = right[r + 1] + left[j - r];
            let temp = ndu[r][j - 1] / ndu[j][r];
            ndu[r][j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        ndu[j][j] = saved;
    }
    for row in out.iter_mut() {
        row[..=p].fill(0.0);
    }
    for j in 0..=p {
        out[0][j] = ndu[j][p];
    }
    if nd == 0 {
        return;
    }
    let mut a = [[0.0f64; N]; 2];
    for r in 0..=p {
        let (mut s1, mut s2) = (0usize, 1usize);
        a[0][0] = 1.0;
        for k in 1..=nd.min(p) {
            let mut d = 0.0;
            let rk = r as isize - k as isize;
            let pk = p - k;
            if r >= k {
                a[s2][0] = a[s1][0] / ndu[pk + 1][rk as usize];
                d = a[s2][0] * ndu[rk as usize][pk];
            }
            let j1 = if rk >= -1 { 1 } else { (-rk) as usize };
            let j2 = if r as isize - 1 <= pk as isize { k - 1 } else { p - r };
            for j in j1..=j2 {
                let c = (rk + j as isize) as usize;
                a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][c];
                d += a[s2][j] * ndu[c][pk];
            }
            if r <= pk {
                a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
                d += a[s2][k] * ndu[r][pk];
            }
            out[k][r] = d;
            std::mem::swap(&mut s1, &mut s2);
        }
    }
    let mut f = p as f64;
    for k in 1..=nd.min(p) {
        for v in out[k][..=p].iter_mut() {
            *v *= f;
        }
        f *= (p - k) as f64;
    }
}

/// Number of non-empty knot spans in the domain.
pub fn span_count(knots: &[f64], degree: usize, n: usize) -> usize {
    (degree..n).filter(|&i| knots[i] < knots[i + 1]).count()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The textbook recursive definition, for comparison only.
    fn naive(knots: &[f64], i: usize, p: usize, t: f64) -> f64 {
        if p == 0 {
            return if knots[i] <= t && t < knots[i + 1] { 1.0 } else { 0.0 };
        }
        let mut v = 0.0;
        let d1 = knots[i + p] - knots[i];
        if d1 > 0.0 {
            v += (t - knots[i]) / d1 * naive(knots, i, p - 1, t);
        }
        let d2 = knots[i + p + 1] - knots[i + 1];
        if d2 > 0.0 {
            v += (knots[i + p + 1] - t) / d2 * naive(knots, i + 1, p - 1, t);
        }
        v
    }

    #[test]
    fn hand_computed_cubic_at_interior_knot() {
        // clamped cubic, one interior knot at 1: at t = 1, N_1..N_3 are (1/4, 1/2, 1/4) and N_4 = 0
        let knots = [0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 2.0, 2.0];
        let span = find_span(&knots, 3, 5, 1.0);
        assert_eq!(span, 4);
        let mut out = [[0.0; M]; 3];
        basis_derivatives(&knots, 3, span, 1.0, 2, &mut out);
        assert_eq!(&out[0][..4], &[0.25, 0.5, 0.25, 0.0]);
    }

    #[test]
    fn matches_the_recursive_definition_and_differences() {
        let knots = [0.0, 0.0, 0.0, 0.3, 0.5, 0.5, 0.9, 1.0, 1.0, 1.0];
        let (p, n) = (2, 7);
        check_knots(p, &knots, n).unwrap();
        for k in 0..50 {
            let t = k as f64 / 50.0 + 0.0071;
            let span = find_span(&knots, p, n, t);
            let mut out = [[0.0; M]; 3];
            basis_derivatives(&knots, p, span, t, 2, &mut out);
            let h = 1e-6;
            let mut sum = 0.0;
            for j in 0..=p {
                let i = span - p + j;
                assert!((out[0][j] - naive(&knots, i, p, t)).abs() < 1e-14);
                let fd = (naive(&knots, i, p, t + h) - naive(&knots, i, p, t - h)) / (2.0 * h);
                // skip points where a derivative jumps (knots of multiplicity 2)
                if (t - 0.5).abs() > 2.0 * h && (t - 0.3).abs() > 2.0 * h && (t - 0.9).abs() > 2.0 * h {
                    assert!((out[1][j] - fd).abs() < 1e-6, "t {t} j {j}: {} vs {fd}", out[1][j]);
                }
                sum += out[0][j];
            }
            assert!((sum - 1.0).abs() < 1e-14);
        }
    }

    #[test]
    fn knot_checks() {
        assert!(check_knots(2, &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0], 3).is_ok());
        let decrease = check_knots(2, &[0.0, 0.0, 1.0, 0.5, 1.0, 1.0], 3).unwrap_err();
        assert_eq!(decrease, SplineError::KnotsDecrease { index: 3, knot: 0.5, previous: 1.0 });
        assert_eq!(decrease.to_string(), "knots decrease at index 3 (0.5 after 1)");
        let count = check_knots(2, &[0.0, 0.0, 0.0, 1.0, 1.0], 3).unwrap_err();
        assert_eq!(count, SplineError::KnotCount { knots: 5, points: 3, degree: 2 });
        assert!(count.to_string().contains("expected 6"));
        assert_eq!(check_knots(0, &[0.0, 1.0], 1), Err(SplineError::Degree { degree: 0, max: MAX_DEGREE }));
        assert_eq!(check_knots(0, &[0.0, 1.0], 1).unwrap_err().to_string(), "degree 0 is outside 1..=25");
        let repeated = check_knots(1, &[0.0, 0.0, 0.0, 0.0], 2).unwrap_err();
        assert!(matches!(repeated, SplineError::KnotRepeated { index: 2, degree: 1, .. }));
        assert!(repeated.to_string().contains("repeated"));
        assert_eq!(expand_knots(&[0.0, 1.0], &[2, 2]).unwrap(), vec![0.0, 0.0, 1.0, 1.0]);
        assert_eq!(expand_knots(&[0.0], &[0]), Err(SplineError::Multiplicities { index: Some(0) }));
        assert_eq!(span_count(&[0.0, 0.0, 0.5, 1.0, 1.0], 1, 3), 2);
    }
}
