//! Surfaces of revolution (STEP `SURFACE_OF_REVOLUTION`).

use super::curve::Curve;
use super::derivs::SurfaceDerivs;
use super::domain::{Interval, SurfaceDomain, angle_0_2pi};
use super::frame::Rigid;
use super::newton::{CurveSamples, refine_from_best};
use glam::{DVec2, DVec3};
use std::f64::consts::TAU;
use std::sync::OnceLock;

/// The profile curve `C(v)` turned by the angle `u` (radians, period 2π) about an axis
/// through `origin` along the unit vector `axis` (ISO 10303-42: `u` the angle, `v` the
/// curve's parameter).
#[derive(Clone, Debug)]
pub struct Revolution {
    /// The profile (swept curve).
    pub curve: Curve,
    /// A point of the axis.
    pub origin: DVec3,
    /// Unit axis direction.
    pub axis: DVec3,
    samples: OnceLock<CurveSamples>,
}

impl Revolution {
    /// The surface of `curve` turned about the axis through `origin` along `axis` (normalised
    /// here; `None` if zero).
    pub fn new(curve: Curve, origin: DVec3, axis: DVec3) -> Option<Revolution> {
        Some(Revolution { curve, origin, axis: axis.try_normalize()?, samples: OnceLock::new() })
    }

    /// `w` turned by `u` about the axis, and the derivative of that in `u`.
    fn turn(&self, u: f64, w: DVec3) -> (DVec3, DVec3, DVec3) {
        let (s, c) = u.sin_cos();
        let par = w.dot(self.axis) * self.axis;
        let perp = w - par;
        let side = self.axis.cross(perp);
        (par + c * perp + s * side, -s * perp + c * side, -c * perp - s * side)
    }

    /// Point and derivatives.
    pub fn derivs(&self, u: f64, v: f64) -> SurfaceDerivs {
        let cd = self.curve.derivs(v);
        let (p, du, duu) = self.turn(u, cd.p - self.origin);
        let (dv, duv, _) = self.turn(u, cd.d1);
        let (dvv, _, _) = self.turn(u, cd.d2);
        SurfaceDerivs { p: self.origin + p, du, dv, duu, duv, dvv }
    }

    /// Point at `(u, v)`.
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        self.origin + self.turn(u, self.curve.point(v) - self.origin).0
    }

    /// `u` in `[0, 2π]` periodic; `v` the profile's domain (unbounded profiles are limited to
    /// `[-1e6, 1e6]` mm for sampling only).
    pub fn domain(&self) -> SurfaceDomain {
        let cd = self.curve.domain();
        SurfaceDomain { u: Interval::TURN, v: cd.range, u_period: Some(TAU), v_period: cd.period, u_closed: true, v_closed: cd.closed }
    }

    fn profile_samples(&self) -> &CurveSamples {
        self.samples.get_or_init(|| self.curve.sweep_samples())
    }

    /// For each profile sample the best angle in closed form, then Newton from the three best
    /// `(u, v)`; `u` in `[0, 2π)`.
    pub fn project(&self, p: DVec3) -> DVec2 {
        let q = p - self.origin;
        let qp = q - q.dot(self.axis) * self.axis;
        let samples = self.profile_samples();
        let mut best: Vec<(f64, DVec2)> = Vec::new();
        for (&t, &c) in samples.t.iter().zip(&samples.p) {
            let w = c - self.origin;
            let wp = w - w.dot(self.axis) * self.axis;
            let u = if wp.length_squared() > 0.0 && qp.length_squared() > 0.0 {
                angle_0_2pi(self.axis.dot(wp.cross(qp)).atan2(wp.dot(qp)))
            } else {
                0.0
            };
            let d = (self.origin + self.turn(u, w).0 - p).length_squared();
            best.push((d, DVec2::new(u, t)));
        }
        let dom = self.domain();
        refine_from_best(|u, v| self.derivs(u, v), &dom, p, best, DVec2::new(0.0, dom.v.min))
    }

    /// The surface moved.
    pub fn transformed(&self, t: &Rigid) -> Revolution {
        Revolution {
            curve: self.curve.transformed(t),
            origin: t.apply_point(self.origin),
            axis: t.apply_vector(self.axis),
            samples: OnceLock::new(),
        }
    }
}
