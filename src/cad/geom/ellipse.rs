//! Ellipses (STEP `ELLIPSE`).

use super::derivs::CurveDerivs;
use super::domain::{CurveDomain, Interval, angle_0_2pi};
use super::frame::{Frame, Rigid};
use super::newton::refine_curve;
use glam::DVec3;
use std::f64::consts::TAU;

/// The ellipse `origin + a cos t · x + b sin t · y`; `t` in radians, period 2π.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Ellipse {
    /// Centre and plane; `x` is the direction of the first semi-axis.
    pub frame: Frame,
    /// Semi-axis along `x` (STEP's `semi_axis_1`).
    pub a: f64,
    /// Semi-axis along `y` (STEP's `semi_axis_2`).
    pub b: f64,
}

impl Ellipse {
    /// Point at `t`.
    pub fn point(&self, t: f64) -> DVec3 {
        let (s, c) = t.sin_cos();
        self.frame.origin + self.a * c * self.frame.x + self.b * s * self.frame.y
    }

    /// Point and derivatives at `t`.
    pub fn derivs(&self, t: f64) -> CurveDerivs {
        let (s, c) = t.sin_cos();
        let (x, y) = (self.frame.x, self.frame.y);
        CurveDerivs {
            p: self.frame.origin + self.a * c * x + self.b * s * y,
            d1: -self.a * s * x + self.b * c * y,
            d2: -self.a * c * x - self.b * s * y,
        }
    }

    /// `[0, 2π]`, periodic.
    pub fn domain(&self) -> CurveDomain {
        CurveDomain { range: Interval::TURN, period: Some(TAU), closed: true }
    }

    /// The parameter of the closest point: the eccentric angle of `p` as a start, refined by
    /// Newton (exact for points on the ellipse), in `[0, 2π)`.
    pub fn project(&self, p: DVec3) -> f64 {
        let l = self.frame.to_local(p);
        let t0 = if self.a > 0.0 && self.b > 0.0 { (l.y / self.b).atan2(l.x / self.a) } else { 0.0 };
        let t0 = angle_0_2pi(t0);
        refine_curve(|t| self.derivs(t), &self.domain(), p, t0)
    }

    /// The ellipse moved.
    pub fn transformed(&self, t: &Rigid) -> Ellipse {
        Ellipse { frame: self.frame.transformed(t), ..*self }
    }
}
