//! Surfaces of linear extrusion (STEP `SURFACE_OF_LINEAR_EXTRUSION`).

use super::curve::Curve;
use super::derivs::SurfaceDerivs;
use super::domain::{Interval, SurfaceDomain};
use super::frame::Rigid;
use super::newton::{CurveSamples, refine_from_best};
use glam::{DVec2, DVec3};
use std::sync::OnceLock;

/// `C(u) + v · direction`: a curve swept along a vector (ISO 10303-42: `u` the curve's
/// parameter, `v` the multiple of the extrusion vector, whose magnitude is kept).
#[derive(Clone, Debug)]
pub struct Extrusion {
    /// The swept curve.
    pub curve: Curve,
    /// The extrusion vector (with its magnitude, in mm).
    pub direction: DVec3,
    samples: OnceLock<CurveSamples>,
}

impl Extrusion {
    /// `curve` swept along `direction` (`None` if the vector is zero).
    pub fn new(curve: Curve, direction: DVec3) -> Option<Extrusion> {
        if !(direction.length() > 0.0) {
            return None;
        }
        Some(Extrusion { curve, direction, samples: OnceLock::new() })
    }

    /// Point and derivatives.
    pub fn derivs(&self, u: f64, v: f64) -> SurfaceDerivs {
        let c = self.curve.derivs(u);
        SurfaceDerivs { p: c.p + v * self.direction, du: c.d1, dv: self.direction, duu: c.d2, duv: DVec3::ZERO, dvv: DVec3::ZERO }
    }

    /// Point at `(u, v)`.
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        self.curve.point(u) + v * self.direction
    }

    /// `u` the curve's domain, `v` unbounded.
    pub fn domain(&self) -> SurfaceDomain {
        let cd = self.curve.domain();
        SurfaceDomain { u: cd.range, v: Interval::ALL, u_period: cd.period, v_period: None, u_closed: cd.closed, v_closed: false }
    }

    fn curve_samples(&self) -> &CurveSamples {
        self.samples.get_or_init(|| self.curve.sweep_samples())
    }

    /// For each curve sample the best `v` in closed form, then Newton from the three best.
    pub fn project(&self, p: DVec3) -> DVec2 {
        let d2 = self.direction.length_squared();
        let samples = self.curve_samples();
        let best: Vec<(f64, DVec2)> = samples
            .t
            .iter()
            .zip(&samples.p)
            .map(|(&u, &c)| {
                let v = (p - c).dot(self.direction) / d2;
                ((c + v * self.direction - p).length_squared(), DVec2::new(u, v))
            })
            .collect();
        let dom = self.domain();
        refine_from_best(|u, v| self.derivs(u, v), &dom, p, best, DVec2::ZERO)
    }

    /// The surface moved.
    pub fn transformed(&self, t: &Rigid) -> Extrusion {
        Extrusion { curve: self.curve.transformed(t), direction: t.apply_vector(self.direction), samples: OnceLock::new() }
    }
}
