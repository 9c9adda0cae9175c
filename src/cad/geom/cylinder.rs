//! Circular cylinders (STEP `CYLINDRICAL_SURFACE`).

use super::derivs::SurfaceDerivs;
use super::domain::{Interval, SurfaceDomain, angle_0_2pi};
use super::frame::{Frame, Rigid};
use glam::{DVec2, DVec3};
use std::f64::consts::TAU;

/// The cylinder `origin + r (cos u · x + sin u · y) + v · z`: `u` the angle (period 2π), `v` the
/// height along the axis `z`. The parametric normal points away from the axis.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Cylinder {
    /// Axis frame.
    pub frame: Frame,
    /// Radius.
    pub radius: f64,
}

impl Cylinder {
    /// Point at `(u, v)`.
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        let (s, c) = u.sin_cos();
        self.frame.origin + self.radius * (c * self.frame.x + s * self.frame.y) + v * self.frame.z
    }

    /// Point and derivatives.
    pub fn derivs(&self, u: f64, v: f64) -> SurfaceDerivs {
        let (s, c) = u.sin_cos();
        let radial = c * self.frame.x + s * self.frame.y;
        let tangent = -s * self.frame.x + c * self.frame.y;
        SurfaceDerivs {
            p: self.frame.origin + self.radius * radial + v * self.frame.z,
            du: self.radius * tangent,
            dv: self.frame.z,
            duu: -self.radius * radial,
            duv: DVec3::ZERO,
            dvv: DVec3::ZERO,
        }
    }

    /// The outward unit normal at angle `u`.
    pub fn normal(&self, u: f64) -> DVec3 {
        let (s, c) = u.sin_cos();
        c * self.frame.x + s * self.frame.y
    }

    /// `u` in `[0, 2π]` periodic, `v` unbounded.
    pub fn domain(&self) -> SurfaceDomain {
        SurfaceDomain { u: Interval::TURN, v: Interval::ALL, u_period: Some(TAU), v_period: None, u_closed: true, v_closed: false }
    }

    /// Angle in `[0, 2π)` (0 on the axis) and height (closed form).
    pub fn project(&self, p: DVec3) -> DVec2 {
        let l = self.frame.to_local(p);
        let u = if l.x == 0.0 && l.y == 0.0 { 0.0 } else { angle_0_2pi(l.y.atan2(l.x)) };
        DVec2::new(u, l.z)
    }

    /// The cylinder moved.
    pub fn transformed(&self, t: &Rigid) -> Cylinder {
        Cylinder { frame: self.frame.transformed(t), radius: self.radius }
    }
}
