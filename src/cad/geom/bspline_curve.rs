//! B-spline curves, polynomial or rational (STEP `B_SPLINE_CURVE_WITH_KNOTS`, and the complex
//! instance with `RATIONAL_B_SPLINE_CURVE`), evaluated exactly by Cox–de Boor.

use super::basis::{MAX_DEGREE, basis_derivatives, check_knots, check_points_weights, find_span, span_count};
use super::spline_error::SplineError;
use super::derivs::CurveDerivs;
use super::domain::{CurveDomain, Interval};
use super::frame::Rigid;
use super::newton::{CurveSamples, refine_curve, span_samples};
use glam::DVec3;
use std::sync::OnceLock;

/// A B-spline curve: degree, full knot vector, control points and optional weights.
#[derive(Clone, Debug)]
pub struct BSplineCurve {
    degree: usize,
    knots: Vec<f64>,
    points: Vec<DVec3>,
    weights: Option<Vec<f64>>,
    samples: OnceLock<CurveSamples>,
}

impl BSplineCurve {
    /// A checked B-spline curve. `knots` is the full vector (multiplicities written out);
    /// `weights`, if given, must be positive and as many as the points.
    pub fn new(degree: usize, knots: Vec<f64>, points: Vec<DVec3>, weights: Option<Vec<f64>>) -> Result<BSplineCurve, SplineError> {
        check_knots(degree, &knots, points.len())?;
        // all weights equal: polynomial
        let weights = check_points_weights(&points, weights)?;
        Ok(BSplineCurve { degree, knots, points, weights, samples: OnceLock::new() })
    }

    /// The degree.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The full knot vector.
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// The control points.
    pub fn control_points(&self) -> &[DVec3] {
        &self.points
    }

    /// The weights, `None` for a polynomial curve (or all weights equal).
    pub fn weights(&self) -> Option<&[f64]> {
        self.weights.as_deref()
    }

    /// Point and first two derivatives at `t` (outside the domain the end polynomial is
    /// extrapolated).
    pub fn derivs(&self, t: f64) -> CurveDerivs {
        let (p, n) = (self.degree, self.points.len());
        let span = find_span(&self.knots, p, n, t);
        let mut b = [[0.0; MAX_DEGREE + 1]; 3];
        basis_derivatives(&self.knots, p, span, t, 2, &mut b);
        let first = span - p;
        match &self.weights {
            None => {
                let mut d = CurveDerivs::default();
                for j in 0..=p {
                    let q = self.points[first + j];
                    d.p += b[0][j] * q;
                    d.d1 += b[1][j] * q;
                    d.d2 += b[2][j] * q;
                }
                d
            }
            Some(w) => {
                let (mut a0, mut a1, mut a2) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
                let (mut w0, mut w1, mut w2) = (0.0, 0.0, 0.0);
                for j in 0..=p {
                    let (q, wj) = (self.points[first + j], w[first + j]);
                    a0 += b[0][j] * wj * q;
                    a1 += b[1][j] * wj * q;
                    a2 += b[2][j] * wj * q;
                    w0 += b[0][j] * wj;
                    w1 += b[1][j] * wj;
                    w2 += b[2][j] * wj;
                }
                let c = a0 / w0;
                let c1 = (a1 - w1 * c) / w0;
                let c2 = (a2 - 2.0 * w1 * c1 - w2 * c) / w0;
                CurveDerivs { p: c, d1: c1, d2: c2 }
            }
        }
    }

    /// Point at `t`.
    pub fn point(&self, t: f64) -> DVec3 {
        self.derivs(t).p
    }

    /// `[knots[p], knots[n]]`; closed when the first and last control points coincide.
    pub fn domain(&self) -> CurveDomain {
        let n = self.points.len();
        let (a, b) = (self.points[0], self.points[n - 1]);
        let size = self.points.iter().fold(0.0f64, |m, p| m.max(p.length()));
        let closed = (a - b).length() <= 1e-12 * size.max(1e-300);
        CurveDomain { range: Interval::new(self.knots[self.degree], self.knots[n]), period: None, closed }
    }

    /// Parameter of the closest point: the nearest of a sampling of every knot span as a start,
    /// refined by Newton (the best of three starts).
    pub fn project(&self, p: DVec3) -> f64 {
        let samples = self.samples.get_or_init(|| {
            let n = self.points.len();
            let per = (self.degree + 1).max(3);
            let t = span_samples(&self.knots, self.degree, n, per, 4096);
            let p = t.iter().map(|&t| self.point(t)).collect();
            CurveSamples { t, p }
        });
        let dom = self.domain();
        let mut best = (f64::INFINITY, dom.range.min);
        for t0 in samples.nearest(p, 3) {
            let t = refine_curve(|t| self.derivs(t), &dom, p, t0);
            let d = (self.point(t) - p).length_squared();
            if d < best.0 {
                best = (d, t);
            }
        }
        best.1
    }

    /// Number of non-empty knot spans.
    pub fn spans(&self) -> usize {
        span_count(&self.knots, self.degree, self.points.len())
    }

    /// The curve moved (control points moved; weights unchanged).
    pub fn transformed(&self, t: &Rigid) -> BSplineCurve {
        BSplineCurve {
            degree: self.degree,
            knots: self.knots.clone(),
            points: self.points.iter().map(|&p| t.apply_point(p)).collect(),
            weights: self.weights.clone(),
            samples: OnceLock::new(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hand_computed_values() {
        // quadratic Bézier (0,0) (1,2) (2,0): C(1/2) = (1, 1), C'(1/2) = (2, 0), C'' = (0, -8)
        let c = BSplineCurve::new(
            2,
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            vec![DVec3::ZERO, DVec3::new(1.0, 2.0, 0.0), DVec3::new(2.0, 0.0, 0.0)],
            None,
        )
        .unwrap();
        let d = c.derivs(0.5);
        assert!((d.p - DVec3::new(1.0, 1.0, 0.0)).length() < 1e-15);
        assert!((d.d1 - DVec3::new(2.0, 0.0, 0.0)).length() < 1e-14);
        assert!((d.d2 - DVec3::new(0.0, -8.0, 0.0)).length() < 1e-13);
        // clamped cubic with an interior knot: at the knot the basis is (1/4, 1/2, 1/4)
        let pts = [(0.0, 0.0), (1.0, 1.0), (2.0, 3.0), (3.0, 1.0), (4.0, 0.0)].map(|(x, y)| DVec3::new(x, y, 0.0));
        let c = BSplineCurve::new(3, vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 2.0, 2.0], pts.to_vec(), None).unwrap();
        assert!((c.point(1.0) - DVec3::new(2.0, 2.0, 0.0)).length() < 1e-15);
        assert_eq!(c.point(0.0), pts[0]);
        assert_eq!(c.point(2.0), pts[4]);
        assert_eq!(c.spans(), 2);
    }

    #[test]
    fn rational_quarter_circle_is_exact() {
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let c = BSplineCurve::new(
            2,
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            vec![DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
            Some(vec![1.0, h, 1.0]),
        )
        .unwrap();
        assert!((c.point(0.5) - DVec3::new(h, h, 0.0)).length() < 1e-15);
        for k in 0..=20 {
            let t = k as f64 / 20.0;
            let d = c.derivs(t);
            assert!((d.p.length() - 1.0).abs() < 1e-15);
            assert!(d.p.dot(d.d1).abs() < 1e-14, "tangent is orthogonal to the radius");
            // second derivative by differences of the first
            let e = 1e-6;
            let fd = (c.derivs(t + e).d1 - c.derivs(t - e).d1) / (2.0 * e);
            if t > e && t < 1.0 - e {
                assert!((fd - d.d2).length() < 1e-6);
            }
            let q = c.project(d.p * 1.5);
            assert!((q - t).abs() < 1e-12, "t {t}: projection {q}");
        }
    }

    #[test]
    fn rejects_bad_data() {
        let p = vec![DVec3::ZERO, DVec3::X];
        assert!(BSplineCurve::new(1, vec![0.0, 0.0, 1.0, 1.0], p.clone(), Some(vec![1.0, 0.0])).unwrap_err().to_string().contains("not positive"));
        assert!(BSplineCurve::new(1, vec![0.0, 0.0, 1.0, 1.0], p.clone(), Some(vec![1.0])).is_err());
        assert!(BSplineCurve::new(1, vec![0.0, 1.0, 0.0, 1.0], p, None).is_err());
    }
}
