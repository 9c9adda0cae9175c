//! Spheres (STEP `SPHERICAL_SURFACE`).

use super::derivs::SurfaceDerivs;
use super::domain::{Interval, SurfaceDomain, angle_0_2pi};
use super::frame::{Frame, Rigid};
use glam::{DVec2, DVec3};
use std::f64::consts::{FRAC_PI_2, TAU};

/// The sphere `origin + r cos v (cos u · x + sin u · y) + r sin v · z`: `u` the longitude
/// (period 2π), `v` the latitude in `[-π/2, π/2]`; poles at `v = ±π/2`. The normal points out.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Sphere {
    /// Centre and axes.
    pub frame: Frame,
    /// Radius.
    pub radius: f64,
}

impl Sphere {
    /// Point at `(u, v)`.
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        self.frame.origin + self.radius * self.normal(u, v)
    }

    /// Point and derivatives.
    pub fn derivs(&self, u: f64, v: f64) -> SurfaceDerivs {
        let (su, cu) = u.sin_cos();
        let (sv, cv) = v.sin_cos();
        let (x, y, z) = (self.frame.x, self.frame.y, self.frame.z);
        let radial = cu * x + su * y;
        let tangent = -su * x + cu * y;
        let r = self.radius;
        SurfaceDerivs {
            p: self.frame.origin + r * (cv * radial + sv * z),
            du: r * cv * tangent,
            dv: r * (-sv * radial + cv * z),
            duu: -r * cv * radial,
            duv: -r * sv * tangent,
            dvv: -r * (cv * radial + sv * z),
        }
    }

    /// The outward unit normal (defined at the poles too).
    pub fn normal(&self, u: f64, v: f64) -> DVec3 {
        let (su, cu) = u.sin_cos();
        let (sv, cv) = v.sin_cos();
        cv * (cu * self.frame.x + su * self.frame.y) + sv * self.frame.z
    }

    /// `u` in `[0, 2π]` periodic, `v` in `[-π/2, π/2]`.
    pub fn domain(&self) -> SurfaceDomain {
        SurfaceDomain {
            u: Interval::TURN,
            v: Interval::new(-FRAC_PI_2, FRAC_PI_2),
            u_period: Some(TAU),
            v_period: None,
            u_closed: true,
            v_closed: false,
        }
    }

    /// Longitude in `[0, 2π)` (0 at the poles) and latitude (closed form).
    pub fn project(&self, p: DVec3) -> DVec2 {
        let l = self.frame.to_local(p);
        let rho = l.x.hypot(l.y);
        let u = if rho == 0.0 { 0.0 } else { angle_0_2pi(l.y.atan2(l.x)) };
        let v = if rho == 0.0 && l.z == 0.0 { 0.0 } else { l.z.atan2(rho) };
        DVec2::new(u, v)
    }

    /// The sphere moved.
    pub fn transformed(&self, t: &Rigid) -> Sphere {
        Sphere { frame: self.frame.transformed(t), radius: self.radius }
    }
}
