//! Tori (STEP `TOROIDAL_SURFACE`) and degenerate tori (`DEGENERATE_TOROIDAL_SURFACE`, minor
//! radius larger than the major one).

use super::derivs::SurfaceDerivs;
use super::domain::{Interval, SurfaceDomain, angle_0_2pi};
use super::frame::{Frame, Rigid};
use glam::{DVec2, DVec3};
use std::f64::consts::{PI, TAU};

/// Which part of a self-intersecting (degenerate) torus a surface is.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum TorusPart {
    /// The whole torus (an ordinary ring torus, minor < major).
    Full,
    /// The outer "apple" of a degenerate torus: points with `R + r cos v ≥ 0`
    /// (`select_outer = .T.`).
    Outer,
    /// The inner "lemon" of a degenerate torus: points with `R + r cos v ≤ 0`
    /// (`select_outer = .F.`).
    Inner,
}

/// The torus `origin + (R + r cos v)(cos u · x + sin u · y) + r sin v · z`: `u` the angle about
/// the axis, `v` the angle about the tube, both in radians. For a ring torus both are periodic;
/// for a degenerate torus (`r > R`) `v` is limited to the selected [`TorusPart`].
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Torus {
    /// Axis frame.
    pub frame: Frame,
    /// Major radius `R` (centre of the tube to the axis). Negative in STEP files that put
    /// the tube's centre across the axis (a spindle torus from SolidWorks): the formula holds.
    pub major: f64,
    /// Minor radius `r` (the tube).
    pub minor: f64,
    /// The part of a degenerate torus.
    pub part: TorusPart,
}

impl Torus {
    /// Point at `(u, v)`.
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        let (su, cu) = u.sin_cos();
        let (sv, cv) = v.sin_cos();
        let rho = self.major + self.minor * cv;
        self.frame.origin + rho * (cu * self.frame.x + su * self.frame.y) + self.minor * sv * self.frame.z
    }

    /// Point and derivatives.
    pub fn derivs(&self, u: f64, v: f64) -> SurfaceDerivs {
        let (su, cu) = u.sin_cos();
        let (sv, cv) = v.sin_cos();
        let (x, y, z) = (self.frame.x, self.frame.y, self.frame.z);
        let radial = cu * x + su * y;
        let tangent = -su * x + cu * y;
        let (big, r) = (self.major, self.minor);
        let rho = big + r * cv;
        SurfaceDerivs {
            p: self.frame.origin + rho * radial + r * sv * z,
            du: rho * tangent,
            dv: -r * sv * radial + r * cv * z,
            duu: -rho * radial,
            duv: -r * sv * tangent,
            dvv: -r * cv * radial - r * sv * z,
        }
    }

    /// The unit normal `du × dv / |du × dv|` (outward from the tube where `R + r cos v > 0`);
    /// `None` at the apexes of a degenerate torus.
    pub fn normal(&self, u: f64, v: f64) -> Option<DVec3> {
        let (su, cu) = u.sin_cos();
        let (sv, cv) = v.sin_cos();
        let rho = self.major + self.minor * cv;
        if rho.abs() <= 1e-12 * (self.major.abs() + self.minor.abs()) {
            return None;
        }
        let n = cv * (cu * self.frame.x + su * self.frame.y) + sv * self.frame.z;
        Some(if rho > 0.0 { n } else { -n })
    }

    /// The angle `v` where the tube meets the axis, `acos(-R/r)`, for a degenerate torus.
    fn apex_angle(&self) -> f64 {
        (-self.major / self.minor).clamp(-1.0, 1.0).acos()
    }

    /// `u` in `[0, 2π]` periodic; `v` in `[0, 2π]` periodic for a ring torus,
    /// `[-acos(-R/r), acos(-R/r)]` for the outer part of a degenerate one and
    /// `[acos(-R/r), 2π - acos(-R/r)]` for the inner part.
    pub fn domain(&self) -> SurfaceDomain {
        let (v, v_period) = match self.part {
            TorusPart::Full => (Interval::TURN, Some(TAU)),
            TorusPart::Outer => {
                let a = self.apex_angle();
                (Interval::new(-a, a), None)
            }
            TorusPart::Inner => {
                let a = self.apex_angle();
                (Interval::new(a, TAU - a), None)
            }
        };
        SurfaceDomain { u: Interval::TURN, v, u_period: Some(TAU), v_period, u_closed: true, v_closed: v_period.is_some() }
    }

    /// Closed form: `u` the angle of `p` about the axis (of the opposite half-plane for the
    /// inner part, and for points nearer the inner part of a self-intersecting full torus), `v` the angle about the tube's centre circle; both in the domain's window.
    pub fn project(&self, p: DVec3) -> DVec2 {
        let l = self.frame.to_local(p);
        let rho = l.x.hypot(l.y);
        let phi = if rho == 0.0 { 0.0 } else { l.y.atan2(l.x) };
        match self.part {
            TorusPart::Inner => {
                let u = angle_0_2pi(phi + PI);
                let v = angle_0_2pi(l.z.atan2(-rho - self.major));
                DVec2::new(u, v)
            }
            TorusPart::Outer => DVec2::new(angle_0_2pi(phi), l.z.atan2(rho - self.major)),
            TorusPart::Full => {
                let apple = DVec2::new(angle_0_2pi(phi), angle_0_2pi(l.z.atan2(rho - self.major)));
                if self.minor <= self.major {
                    return apple;
                }
                // a self-intersecting torus given as TOROIDAL_SURFACE: the point may lie on the
                // inner (lemon) part, reached from the opposite half-plane
                let lemon = DVec2::new(angle_0_2pi(phi + PI), angle_0_2pi(l.z.atan2(-rho - self.major)));
                let (da, dl) = ((self.point(apple.x, apple.y) - p).length(), (self.point(lemon.x, lemon.y) - p).length());
                if dl < da { lemon } else { apple }
            }
        }
    }

    /// The torus moved.
    pub fn transformed(&self, t: &Rigid) -> Torus {
        Torus { frame: self.frame.transformed(t), ..*self }
    }
}
