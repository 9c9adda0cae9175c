//! Planes (STEP `PLANE`).

use super::derivs::SurfaceDerivs;
use super::domain::{Interval, SurfaceDomain};
use super::frame::{Frame, Rigid};
use glam::{DVec2, DVec3};

/// The plane `origin + u · x + v · y` of a frame; its normal is the frame's `z`.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Plane {
    /// Position and orientation.
    pub frame: Frame,
}

impl Plane {
    /// Point at `(u, v)`.
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        self.frame.origin + u * self.frame.x + v * self.frame.y
    }

    /// Point and derivatives.
    pub fn derivs(&self, u: f64, v: f64) -> SurfaceDerivs {
        SurfaceDerivs { p: self.point(u, v), du: self.frame.x, dv: self.frame.y, ..Default::default() }
    }

    /// The unit normal (the frame's `z` everywhere).
    pub fn normal(&self) -> DVec3 {
        self.frame.z
    }

    /// Unbounded in `u` and `v`.
    pub fn domain(&self) -> SurfaceDomain {
        SurfaceDomain { u: Interval::ALL, v: Interval::ALL, u_period: None, v_period: None, u_closed: false, v_closed: false }
    }

    /// The coordinates of the foot of the perpendicular (closed form).
    pub fn project(&self, p: DVec3) -> DVec2 {
        let l = self.frame.to_local(p);
        DVec2::new(l.x, l.y)
    }

    /// The plane moved.
    pub fn transformed(&self, t: &Rigid) -> Plane {
        Plane { frame: self.frame.transformed(t) }
    }
}
