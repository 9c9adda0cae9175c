//! Offset surfaces (STEP `OFFSET_SURFACE`).

use super::derivs::SurfaceDerivs;
use super::domain::SurfaceDomain;
use super::frame::Rigid;
use super::newton::refine_surface;
use super::surface::Surface;
use glam::{DVec2, DVec3};

/// `S(u, v) + d · N(u, v)`: a basis surface moved by `distance` along its unit normal.
#[derive(Clone, Debug)]
pub struct Offset {
    /// The basis surface.
    pub basis: Box<Surface>,
    /// The offset distance in mm (signed, along the basis' parametric normal).
    pub distance: f64,
}

impl Offset {
    /// Point and first derivatives (exact, from the basis' second derivatives); the second
    /// derivatives by central differences of the first.
    pub fn derivs(&self, u: f64, v: f64) -> SurfaceDerivs {
        let (p, du, dv) = self.first(u, v);
        let h = 1e-6;
        let (_, du_p, dv_p) = self.first(u + h, v);
        let (_, du_m, dv_m) = self.first(u - h, v);
        let (_, _, dv_vp) = self.first(u, v + h);
        let (_, _, dv_vm) = self.first(u, v - h);
        SurfaceDerivs { p, du, dv, duu: (du_p - du_m) / (2.0 * h), duv: (dv_p - dv_m) / (2.0 * h), dvv: (dv_vp - dv_vm) / (2.0 * h) }
    }

    fn first(&self, u: f64, v: f64) -> (DVec3, DVec3, DVec3) {
        let b = self.basis.derivs(u, v);
        let n = b.du.cross(b.dv);
        let len = n.length();
        if !(len > 0.0) {
            let nn = self.basis.normal(u, v).unwrap_or(DVec3::ZERO);
            return (b.p + self.distance * nn, b.du, b.dv);
        }
        let unit = n / len;
        let nu = b.duu.cross(b.dv) + b.du.cross(b.duv);
        let nv = b.duv.cross(b.dv) + b.du.cross(b.dvv);
        let unit_u = (nu - unit * unit.dot(nu)) / len;
        let unit_v = (nv - unit * unit.dot(nv)) / len;
        (b.p + self.distance * unit, b.du + self.distance * unit_u, b.dv + self.distance * unit_v)
    }

    /// Point at `(u, v)`.
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        let n = self.basis.normal(u, v).unwrap_or(DVec3::ZERO);
        self.basis.point(u, v) + self.distance * n
    }

    /// The basis' domain.
    pub fn domain(&self) -> SurfaceDomain {
        self.basis.domain()
    }

    /// The basis' closest point (the same parameters for offsets smaller than the curvature
    /// radius), refined by Newton on the offset surface.
    pub fn project(&self, p: DVec3) -> DVec2 {
        let start = self.basis.project(p);
        refine_surface(|u, v| self.derivs(u, v), &self.domain(), p, start)
    }

    /// The surface moved.
    pub fn transformed(&self, t: &Rigid) -> Offset {
        Offset { basis: Box::new(self.basis.transformed(t)), distance: self.distance }
    }
}
