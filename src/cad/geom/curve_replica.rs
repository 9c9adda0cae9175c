//! Curve replicas (STEP `CURVE_REPLICA`): a parent curve under a [`Similarity`].

use super::curve::Curve;
use super::derivs::CurveDerivs;
use super::domain::CurveDomain;
use super::frame::Rigid;
use super::similarity::Similarity;
use glam::DVec3;

/// A curve under a similarity (same parameters as the parent).
#[derive(Clone, Debug)]
pub struct CurveReplica {
    /// The parent curve.
    pub parent: Box<Curve>,
    /// The transformation.
    pub map: Similarity,
}

impl CurveReplica {
    /// Point and derivatives.
    pub fn derivs(&self, t: f64) -> CurveDerivs {
        let d = self.parent.derivs(t);
        CurveDerivs { p: self.map.apply_point(d.p), d1: self.map.apply_vector(d.d1), d2: self.map.apply_vector(d.d2) }
    }

    /// Point at `t`.
    pub fn point(&self, t: f64) -> DVec3 {
        self.map.apply_point(self.parent.point(t))
    }

    /// The parent's domain.
    pub fn domain(&self) -> CurveDomain {
        self.parent.domain()
    }

    /// The parent's closest point to the point moved back (a similarity keeps the closest
    /// point).
    pub fn project(&self, p: DVec3) -> f64 {
        self.parent.project(self.map.invert_point(p))
    }

    /// The replica moved.
    pub fn transformed(&self, t: &Rigid) -> CurveReplica {
        CurveReplica { parent: self.parent.clone(), map: self.map.then(t) }
    }
}
