//! Circles (STEP `CIRCLE`).

use super::derivs::CurveDerivs;
use super::domain::{CurveDomain, Interval, angle_0_2pi};
use super::frame::{Frame, Rigid};
use glam::DVec3;
use std::f64::consts::TAU;

/// The circle `origin + r (cos t · x + sin t · y)` of a frame; `t` in radians, period 2π.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Circle {
    /// Centre and plane (the circle turns from `x` towards `y`, counter-clockwise about `z`).
    pub frame: Frame,
    /// Radius (zero only for a degenerate edge's curve).
    pub radius: f64,
}

impl Circle {
    /// Point at `t`.
    pub fn point(&self, t: f64) -> DVec3 {
        let (s, c) = t.sin_cos();
        self.frame.origin + self.radius * (c * self.frame.x + s * self.frame.y)
    }

    /// Point and derivatives at `t`.
    pub fn derivs(&self, t: f64) -> CurveDerivs {
        let (s, c) = t.sin_cos();
        let radial = c * self.frame.x + s * self.frame.y;
        let tangent = -s * self.frame.x + c * self.frame.y;
        CurveDerivs { p: self.frame.origin + self.radius * radial, d1: self.radius * tangent, d2: -self.radius * radial }
    }

    /// `[0, 2π]`, periodic.
    pub fn domain(&self) -> CurveDomain {
        CurveDomain { range: Interval::TURN, period: Some(TAU), closed: true }
    }

    /// The angle of `p` about the centre, in `[0, 2π)` (closed form; 0 on the axis).
    pub fn project(&self, p: DVec3) -> f64 {
        let l = self.frame.to_local(p);
        if l.x == 0.0 && l.y == 0.0 { 0.0 } else { angle_0_2pi(l.y.atan2(l.x)) }
    }

    /// The circle moved.
    pub fn transformed(&self, t: &Rigid) -> Circle {
        Circle { frame: self.frame.transformed(t), radius: self.radius }
    }
}
