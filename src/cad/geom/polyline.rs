//! Polylines (STEP `POLYLINE`).

use super::derivs::CurveDerivs;
use super::domain::{CurveDomain, Interval};
use super::frame::Rigid;
use glam::DVec3;

/// A polyline through at least two points; `t` in `[0, n - 1]`, segment `i` for `t` in `[i, i+1]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Polyline {
    /// The points (at least two).
    pub points: Vec<DVec3>,
}

impl Polyline {
    fn segment(&self, t: f64) -> (usize, f64) {
        let last = self.points.len().saturating_sub(2);
        let i = (t.floor().max(0.0) as usize).min(last);
        (i, t - i as f64)
    }

    /// Point at `t`.
    pub fn point(&self, t: f64) -> DVec3 {
        self.derivs(t).p
    }

    /// Point and derivatives at `t` (the derivative of the segment holding `t`).
    pub fn derivs(&self, t: f64) -> CurveDerivs {
        let (i, f) = self.segment(t);
        match (self.points.get(i), self.points.get(i + 1)) {
            (Some(&a), Some(&b)) => CurveDerivs { p: a + f * (b - a), d1: b - a, d2: DVec3::ZERO },
            (Some(&a), None) => CurveDerivs { p: a, ..Default::default() },
            _ => CurveDerivs::default(),
        }
    }

    /// `[0, n - 1]`.
    pub fn domain(&self) -> CurveDomain {
        let n = self.points.len();
        let closed = n > 2 && self.points.first() == self.points.last();
        CurveDomain { range: Interval::new(0.0, n.saturating_sub(1) as f64), period: None, closed }
    }

    /// Parameter of the closest point (exact: closest point of each segment).
    pub fn project(&self, p: DVec3) -> f64 {
        let mut best = (f64::INFINITY, 0.0);
        for (i, w) in self.points.windows(2).enumerate() {
            let d = w[1] - w[0];
            let l2 = d.length_squared();
            let f = if l2 > 0.0 { ((p - w[0]).dot(d) / l2).clamp(0.0, 1.0) } else { 0.0 };
            let dist = (w[0] + f * d - p).length_squared();
            if dist < best.0 {
                best = (dist, i as f64 + f);
            }
        }
        best.1
    }

    /// The polyline moved.
    pub fn transformed(&self, t: &Rigid) -> Polyline {
        Polyline { points: self.points.iter().map(|&p| t.apply_point(p)).collect() }
    }
}
