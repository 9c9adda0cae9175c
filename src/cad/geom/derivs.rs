//! Points with derivatives, as curves and surfaces return them.

use glam::DVec3;

/// A curve point with its first and second derivatives in the curve parameter.
#[derive(Copy, Clone, Debug, Default, PartialEq)]
pub struct CurveDerivs {
    /// The point.
    pub p: DVec3,
    /// First derivative `dC/dt`.
    pub d1: DVec3,
    /// Second derivative `d²C/dt²`.
    pub d2: DVec3,
}

/// A surface point with its first and second partial derivatives.
#[derive(Copy, Clone, Debug, Default, PartialEq)]
pub struct SurfaceDerivs {
    /// The point.
    pub p: DVec3,
    /// `∂S/∂u`.
    pub du: DVec3,
    /// `∂S/∂v`.
    pub dv: DVec3,
    /// `∂²S/∂u²`.
    pub duu: DVec3,
    /// `∂²S/∂u∂v`.
    pub duv: DVec3,
    /// `∂²S/∂v²`.
    pub dvv: DVec3,
}

impl SurfaceDerivs {
    /// The unit normal `du × dv / |du × dv|`, or `None` where the parametrization is singular.
    pub fn normal(&self) -> Option<DVec3> {
        let n = self.du.cross(self.dv);
        let scale = self.du.length() * self.dv.length();
        if n.length() > 1e-14 * scale && scale > 0.0 { n.try_normalize() } else { None }
    }
}
