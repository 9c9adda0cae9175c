//! Surface replicas (STEP `SURFACE_REPLICA`): a parent surface under a [`Similarity`].

use super::derivs::SurfaceDerivs;
use super::domain::SurfaceDomain;
use super::frame::Rigid;
use super::similarity::Similarity;
use super::surface::Surface;
use glam::{DVec2, DVec3};

/// A surface under a similarity (same parameters as the parent; a reflection turns the
/// parametric normal `∂S/∂u × ∂S/∂v` round with it).
#[derive(Clone, Debug)]
pub struct SurfaceReplica {
    /// The parent surface.
    pub parent: Box<Surface>,
    /// The transformation.
    pub map: Similarity,
}

impl SurfaceReplica {
    /// Point and derivatives.
    pub fn derivs(&self, u: f64, v: f64) -> SurfaceDerivs {
        let d = self.parent.derivs(u, v);
        let m = |x: DVec3| self.map.apply_vector(x);
        SurfaceDerivs { p: self.map.apply_point(d.p), du: m(d.du), dv: m(d.dv), duu: m(d.duu), duv: m(d.duv), dvv: m(d.dvv) }
    }

    /// Point at `(u, v)`.
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        self.map.apply_point(self.parent.point(u, v))
    }

    /// The unit normal: the parent's, turned (and reversed by a reflection).
    pub fn normal(&self, u: f64, v: f64) -> Option<DVec3> {
        let n = self.map.axes * self.parent.normal(u, v)?;
        Some(if self.map.reflects() { -n } else { n })
    }

    /// The parent's domain.
    pub fn domain(&self) -> SurfaceDomain {
        self.parent.domain()
    }

    /// The parent's closest point to the point moved back.
    pub fn project(&self, p: DVec3) -> DVec2 {
        self.parent.project(self.map.invert_point(p))
    }

    /// Like [`SurfaceReplica::project`], near `near`.
    pub fn project_near(&self, p: DVec3, near: DVec2) -> DVec2 {
        self.parent.project_near(self.map.invert_point(p), near)
    }

    /// The replica moved.
    pub fn transformed(&self, t: &Rigid) -> SurfaceReplica {
        SurfaceReplica { parent: self.parent.clone(), map: self.map.then(t) }
    }
}
