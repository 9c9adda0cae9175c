//! Parameter domains of curves and surfaces, and helpers for periodic parameters.

use std::f64::consts::TAU;

/// A closed parameter interval `[min, max]`; either end may be infinite (lines, planes).
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Interval {
    /// Lower end.
    pub min: f64,
    /// Upper end.
    pub max: f64,
}

impl Interval {
    /// `[min, max]`.
    pub const fn new(min: f64, max: f64) -> Interval {
        Interval { min, max }
    }

    /// The whole real line.
    pub const ALL: Interval = Interval { min: f64::NEG_INFINITY, max: f64::INFINITY };

    /// One full turn, `[0, 2π]`.
    pub const TURN: Interval = Interval { min: 0.0, max: TAU };

    /// `max - min` (infinite for unbounded intervals).
    pub fn length(&self) -> f64 {
        self.max - self.min
    }

    /// True if both ends are finite.
    pub fn is_bounded(&self) -> bool {
        self.min.is_finite() && self.max.is_finite()
    }

    /// `t` clamped into the interval.
    pub fn clamp(&self, t: f64) -> f64 {
        t.max(self.min).min(self.max)
    }

    /// True if `t` lies in the interval, widened by `tol` on both sides.
    pub fn contains(&self, t: f64, tol: f64) -> bool {
        t >= self.min - tol && t <= self.max + tol
    }
}

/// The natural parameter domain of a curve.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct CurveDomain {
    /// The natural parameter range (for periodic curves one period, `[0, 2π]` for conics).
    pub range: Interval,
    /// `Some(period)` if `point(t + period) == point(t)` for every `t` (circles, ellipses,
    /// periodic B-splines).
    pub period: Option<f64>,
    /// True if the curve ends where it starts (periodic curves, closed B-splines).
    pub closed: bool,
}

/// The natural parameter domain of a surface.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct SurfaceDomain {
    /// Range of `u` (one period where `u` is periodic).
    pub u: Interval,
    /// Range of `v` (one period where `v` is periodic).
    pub v: Interval,
    /// `Some(period)` if the surface repeats in `u` (the angle of cylinders, cones, spheres,
    /// tori, surfaces of revolution).
    pub u_period: Option<f64>,
    /// `Some(period)` if the surface repeats in `v` (the tube angle of tori).
    pub v_period: Option<f64>,
    /// True if the `u = min` and `u = max` boundaries coincide (periodic, or a closed
    /// B-spline surface): an edge there is a seam.
    pub u_closed: bool,
    /// True if the `v = min` and `v = max` boundaries coincide.
    pub v_closed: bool,
}

/// `t` moved by whole periods into `[start, start + period)`.
pub fn wrap_into(t: f64, start: f64, period: f64) -> f64 {
    if !(period > 0.0) || !t.is_finite() {
        return t;
    }
    let mut w = t - ((t - start) / period).floor() * period;
    // rounding can land exactly on the upper end
    if w >= start + period {
        w -= period;
    }
    if w < start {
        w = start;
    }
    w
}

/// `t` moved by whole periods to lie as close as possible to `reference` (within half a period).
/// The tessellator uses this to keep parameters of consecutive points on one side of a seam.
pub fn unwrap_near(t: f64, reference: f64, period: f64) -> f64 {
    if !(period > 0.0) || !t.is_finite() || !reference.is_finite() {
        return t;
    }
    t - ((t - reference) / period).round() * period
}

/// An angle in `[0, 2π)`.
pub fn angle_0_2pi(a: f64) -> f64 {
    wrap_into(a, 0.0, TAU)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrapping() {
        assert_eq!(angle_0_2pi(-0.5), TAU - 0.5);
        assert_eq!(angle_0_2pi(TAU), 0.0);
        assert!((wrap_into(7.0, 1.0, 2.0) - 1.0).abs() < 1e-15);
        assert!((unwrap_near(0.1, TAU - 0.1, TAU) - (TAU + 0.1)).abs() < 1e-15);
        assert_eq!(unwrap_near(1.0, 1.2, TAU), 1.0);
        assert_eq!(wrap_into(3.0, 0.0, 0.0), 3.0);
        assert!(Interval::ALL.contains(1e300, 0.0) && !Interval::ALL.is_bounded());
        assert_eq!(Interval::new(0.0, 1.0).clamp(2.0), 1.0);
    }
}
