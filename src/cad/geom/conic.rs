//! Parabolas and hyperbolas (STEP `PARABOLA`, `HYPERBOLA`): open conics, unbounded, trimmed by
//! their edges.

use super::derivs::CurveDerivs;
use super::domain::{CurveDomain, Interval};
use super::frame::{Frame, Rigid};
use super::newton::refine_curve;
use glam::DVec3;

/// The parabola `origin + f (t² x + 2 t y)`: vertex at the origin, axis along `x`, focus at
/// `origin + f x`; `t` dimensionless.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Parabola {
    /// Vertex and plane; `x` is the axis of symmetry.
    pub frame: Frame,
    /// The focal distance (STEP's `focal_dist`).
    pub focal: f64,
}

impl Parabola {
    /// Point at `t`.
    pub fn point(&self, t: f64) -> DVec3 {
        self.derivs(t).p
    }

    /// Point and derivatives at `t`.
    pub fn derivs(&self, t: f64) -> CurveDerivs {
        let (x, y, f) = (self.frame.x, self.frame.y, self.focal);
        CurveDerivs { p: self.frame.origin + f * (t * t * x + 2.0 * t * y), d1: f * (2.0 * t * x + 2.0 * y), d2: 2.0 * f * x }
    }

    /// All of `t`, open.
    pub fn domain(&self) -> CurveDomain {
        CurveDomain { range: Interval::ALL, period: None, closed: false }
    }

    /// The parameter of the closest point: from the point's height over the axis, refined by
    /// Newton (exact for points on the parabola).
    pub fn project(&self, p: DVec3) -> f64 {
        let l = self.frame.to_local(p);
        refine_curve(|t| self.derivs(t), &self.domain(), p, l.y / (2.0 * self.focal))
    }

    /// The parabola moved.
    pub fn transformed(&self, t: &Rigid) -> Parabola {
        Parabola { frame: self.frame.transformed(t), ..*self }
    }
}

/// The branch `origin + a cosh t · x + b sinh t · y` of a hyperbola; `t` dimensionless.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Hyperbola {
    /// Centre and plane; `x` points to the branch's vertex.
    pub frame: Frame,
    /// The real semi-axis (STEP's `semi_axis`).
    pub a: f64,
    /// The imaginary semi-axis (STEP's `semi_imag_axis`).
    pub b: f64,
}

impl Hyperbola {
    /// Point at `t`.
    pub fn point(&self, t: f64) -> DVec3 {
        self.derivs(t).p
    }

    /// Point and derivatives at `t`.
    pub fn derivs(&self, t: f64) -> CurveDerivs {
        let (x, y) = (self.frame.x, self.frame.y);
        let (c, s) = (t.cosh(), t.sinh());
        CurveDerivs { p: self.frame.origin + self.a * c * x + self.b * s * y, d1: self.a * s * x + self.b * c * y, d2: self.a * c * x + self.b * s * y }
    }

    /// All of `t`, open.
    pub fn domain(&self) -> CurveDomain {
        CurveDomain { range: Interval::ALL, period: None, closed: false }
    }

    /// The parameter of the closest point: from the point's height, refined by Newton (exact
    /// for points on the branch).
    pub fn project(&self, p: DVec3) -> f64 {
        let l = self.frame.to_local(p);
        refine_curve(|t| self.derivs(t), &self.domain(), p, (l.y / self.b).asinh())
    }

    /// The hyperbola moved.
    pub fn transformed(&self, t: &Rigid) -> Hyperbola {
        Hyperbola { frame: self.frame.transformed(t), ..*self }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_project_back_to_their_parameters() {
        let frame = Frame::WORLD;
        let p = Parabola { frame, focal: 2.5 };
        let h = Hyperbola { frame, a: 3.0, b: 2.0 };
        for t in [-2.0, -0.3, 0.0, 0.7, 1.9] {
            assert!((p.project(p.point(t)) - t).abs() < 1e-9, "parabola {t}");
            assert!((h.project(h.point(t)) - t).abs() < 1e-9, "hyperbola {t}");
            // the derivative agrees with a difference quotient
            let e = 1e-6;
            assert!(((p.point(t + e) - p.point(t - e)) / (2.0 * e) - p.derivs(t).d1).length() < 1e-6);
            assert!(((h.point(t + e) - h.point(t - e)) / (2.0 * e) - h.derivs(t).d1).length() < 1e-6);
        }
        // the focus property: distance to the focus equals distance to the directrix
        let q = p.point(1.3);
        assert!(((q - DVec3::new(2.5, 0.0, 0.0)).length() - (q.x + 2.5)).abs() < 1e-12);
    }
}
