//! 3D offset curves (STEP `OFFSET_CURVE_3D`).

use super::curve::Curve;
use super::derivs::CurveDerivs;
use super::domain::CurveDomain;
use super::frame::Rigid;
use super::newton::refine_curve;
use glam::DVec3;

/// `C(t) + d · (V × T) / |V × T|`: a basis curve moved by `distance` across its unit tangent
/// `T` and the fixed `direction` `V` (ISO 10303-42 `offset_curve_3d`; OpenCASCADE's
/// `Geom_OffsetCurve` with the distance negated is the same curve).
#[derive(Clone, Debug)]
pub struct OffsetCurve {
    /// The basis curve.
    pub basis: Box<Curve>,
    /// The offset distance in mm.
    pub distance: f64,
    /// The reference direction `V` (unit).
    pub direction: DVec3,
}

impl OffsetCurve {
    /// Point and first derivative (exact, from the basis' second derivative), and the second
    /// derivative by central differences of the first.
    pub fn derivs(&self, t: f64) -> CurveDerivs {
        let (p, d1) = self.first(t);
        let h = 1e-6 * (1.0 + t.abs());
        let (_, d1p) = self.first(t + h);
        let (_, d1m) = self.first(t - h);
        CurveDerivs { p, d1, d2: (d1p - d1m) / (2.0 * h) }
    }

    fn first(&self, t: f64) -> (DVec3, DVec3) {
        let b = self.basis.derivs(t);
        let w = self.direction.cross(b.d1);
        let len = w.length();
        if !len.is_normal() {
            // the tangent along the reference direction: no offset direction there
            return (b.p, b.d1);
        }
        let n = w / len;
        let dw = self.direction.cross(b.d2);
        let dn = (dw - n * n.dot(dw)) / len;
        (b.p + self.distance * n, b.d1 + self.distance * dn)
    }

    /// Point at `t`.
    pub fn point(&self, t: f64) -> DVec3 {
        self.first(t).0
    }

    /// The basis' domain.
    pub fn domain(&self) -> CurveDomain {
        self.basis.domain()
    }

    /// The basis' closest point (the same parameter for offsets smaller than the curvature
    /// radius), refined by Newton on the offset curve.
    pub fn project(&self, p: DVec3) -> f64 {
        let start = self.basis.project(p);
        refine_curve(|t| self.derivs(t), &self.domain(), p, start)
    }

    /// The curve moved.
    pub fn transformed(&self, t: &Rigid) -> OffsetCurve {
        OffsetCurve { basis: Box::new(self.basis.transformed(t)), distance: self.distance, direction: t.apply_vector(self.direction) }
    }
}
