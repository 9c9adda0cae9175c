//! Straight lines (STEP `LINE`).

use super::derivs::CurveDerivs;
use super::domain::{CurveDomain, Interval};
use super::frame::Rigid;
use glam::DVec3;

/// The line `origin + t · direction`. `direction` keeps the magnitude of STEP's `VECTOR`, so
/// the parameter is the same as in the file whatever the length unit.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Line {
    /// The point at `t = 0`.
    pub origin: DVec3,
    /// The derivative (non-zero).
    pub direction: DVec3,
}

impl Line {
    /// Point at `t`.
    pub fn point(&self, t: f64) -> DVec3 {
        self.origin + t * self.direction
    }

    /// Point and derivatives at `t`.
    pub fn derivs(&self, t: f64) -> CurveDerivs {
        CurveDerivs { p: self.point(t), d1: self.direction, d2: DVec3::ZERO }
    }

    /// The whole real line.
    pub fn domain(&self) -> CurveDomain {
        CurveDomain { range: Interval::ALL, period: None, closed: false }
    }

    /// Parameter of the foot of the perpendicular from `p` (closed form).
    pub fn project(&self, p: DVec3) -> f64 {
        let l2 = self.direction.length_squared();
        if l2 > 0.0 { (p - self.origin).dot(self.direction) / l2 } else { 0.0 }
    }

    /// The line moved.
    pub fn transformed(&self, t: &Rigid) -> Line {
        Line { origin: t.apply_point(self.origin), direction: t.apply_vector(self.direction) }
    }
}
