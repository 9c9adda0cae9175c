//! Circular cones (STEP `CONICAL_SURFACE`).

use super::derivs::SurfaceDerivs;
use super::domain::{Interval, SurfaceDomain, angle_0_2pi};
use super::frame::{Frame, Rigid};
use glam::{DVec2, DVec3};
use std::f64::consts::TAU;

/// The cone `origin + (r + v tan α)(cos u · x + sin u · y) + v · z` (ISO 10303-42): `u` the
/// angle (period 2π), `v` the height along the axis, `r` the radius at `v = 0` and `α` the
/// semi-angle. The apex is at `v = -r / tan α`. OpenCASCADE's own cone measures `v` along the
/// generator instead; pcurves written by it on cones may use that form.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Cone {
    /// Axis frame.
    pub frame: Frame,
    /// Radius at `v = 0`.
    pub radius: f64,
    /// Semi-angle in radians, in `(0, π/2)`.
    pub semi_angle: f64,
}

impl Cone {
    fn tan(&self) -> f64 {
        self.semi_angle.tan()
    }

    /// The `v` of the apex, where the radius `r + v tan α` is zero.
    pub fn apex_v(&self) -> f64 {
        -self.radius / self.tan()
    }

    /// Point at `(u, v)`.
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        let (s, c) = u.sin_cos();
        let rho = self.radius + v * self.tan();
        self.frame.origin + rho * (c * self.frame.x + s * self.frame.y) + v * self.frame.z
    }

    /// Point and derivatives.
    pub fn derivs(&self, u: f64, v: f64) -> SurfaceDerivs {
        let (s, c) = u.sin_cos();
        let t = self.tan();
        let rho = self.radius + v * t;
        let radial = c * self.frame.x + s * self.frame.y;
        let tangent = -s * self.frame.x + c * self.frame.y;
        SurfaceDerivs {
            p: self.frame.origin + rho * radial + v * self.frame.z,
            du: rho * tangent,
            dv: t * radial + self.frame.z,
            duu: -rho * radial,
            duv: t * tangent,
            dvv: DVec3::ZERO,
        }
    }

    /// The unit normal `du × dv / |du × dv|` (away from the axis where `r + v tan α > 0`);
    /// `None` at the apex.
    pub fn normal(&self, u: f64, v: f64) -> Option<DVec3> {
        let (s, c) = u.sin_cos();
        let t = self.tan();
        let rho = self.radius + v * t;
        if rho.abs() <= 1e-12 * (self.radius.abs() + (v * t).abs()) {
            return None;
        }
        let n = (c * self.frame.x + s * self.frame.y - t * self.frame.z) / (1.0 + t * t).sqrt();
        Some(if rho > 0.0 { n } else { -n })
    }

    /// `u` in `[0, 2π]` periodic, `v` unbounded.
    pub fn domain(&self) -> SurfaceDomain {
        SurfaceDomain { u: Interval::TURN, v: Interval::ALL, u_period: Some(TAU), v_period: None, u_closed: true, v_closed: false }
    }

    /// Angle in `[0, 2π)` and height of the closest point (closed form). STEP cones are whole
    /// double cones: past the apex (`r + v tan α < 0`) the radius is negative and the point
    /// lies at the opposite angle, so both half-planes through the axis are tried.
    pub fn project(&self, p: DVec3) -> DVec2 {
        let l = self.frame.to_local(p);
        let phi = if l.x == 0.0 && l.y == 0.0 { 0.0 } else { l.y.atan2(l.x) };
        let rho = l.x.hypot(l.y);
        let t = self.tan();
        let best = |rho_s: f64| {
            let v = ((rho_s - self.radius) * t + l.z) / (1.0 + t * t);
            let d = (self.radius + v * t - rho_s).hypot(v - l.z);
            (v, d)
        };
        let (v1, d1) = best(rho);
        let (v2, d2) = best(-rho);
        if d2 < d1 { DVec2::new(angle_0_2pi(phi + std::f64::consts::PI), v2) } else { DVec2::new(angle_0_2pi(phi), v1) }
    }

    /// The cone moved.
    pub fn transformed(&self, t: &Rigid) -> Cone {
        Cone { frame: self.frame.transformed(t), ..*self }
    }
}
