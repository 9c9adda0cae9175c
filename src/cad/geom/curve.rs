//! The curve kinds of a B-rep edge, behind one enum: evaluation, natural domain and the inverse
//! (closest point) of each.

use super::bspline_curve::BSplineCurve;
use super::circle::Circle;
use super::conic::{Hyperbola, Parabola};
use super::derivs::CurveDerivs;
use super::domain::{CurveDomain, Interval, unwrap_near, wrap_into};
use super::ellipse::Ellipse;
use super::frame::Rigid;
use super::line::Line;
use super::newton::{CurveSamples, even_samples, refine_curve, refine_curve_within, span_samples};
use super::polyline::Polyline;
use super::similarity::Similarity;
use glam::DVec3;
use std::fmt;

/// A 3D curve in millimetres (also used, with `z = 0`, for the 2D curves of pcurves).
#[derive(Clone, Debug)]
pub enum Curve {
    /// `LINE`.
    Line(Line),
    /// `CIRCLE`.
    Circle(Circle),
    /// `ELLIPSE`.
    Ellipse(Ellipse),
    /// `PARABOLA`.
    Parabola(Parabola),
    /// `HYPERBOLA`.
    Hyperbola(Hyperbola),
    /// `B_SPLINE_CURVE_WITH_KNOTS` (rational or not) and its special forms.
    BSpline(BSplineCurve),
    /// `POLYLINE`.
    Polyline(Polyline),
    /// `TRIMMED_CURVE`: a basis curve restricted to a parameter interval (the basis curve's
    /// parameters, increasing).
    Trimmed(Box<Curve>, Interval),
    /// `CURVE_REPLICA`: a parent curve under a similarity.
    Replica(CurveReplica),
    /// `OFFSET_CURVE_3D`.
    Offset(OffsetCurve),
}

/// The kind of a [`Curve`], for summaries.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum CurveKind {
    /// A line.
    Line,
    /// A circle.
    Circle,
    /// An ellipse.
    Ellipse,
    /// A parabola.
    Parabola,
    /// A hyperbola.
    Hyperbola,
    /// A B-spline.
    BSpline,
    /// A polyline.
    Polyline,
    /// A trimmed curve.
    Trimmed,
    /// A replica (a transformed parent curve).
    Replica,
    /// A 3D offset curve.
    Offset,
}

impl CurveKind {
    /// The name used in reports (`line`, `circle`, `ellipse`, `parabola`, `hyperbola`, `bspline`, `polyline`, `trimmed`,
    /// `replica`, `offset`).
    pub fn name(self) -> &'static str {
        match self {
            CurveKind::Line => "line",
            CurveKind::Circle => "circle",
            CurveKind::Ellipse => "ellipse",
            CurveKind::Parabola => "parabola",
            CurveKind::Hyperbola => "hyperbola",
            CurveKind::BSpline => "bspline",
            CurveKind::Polyline => "polyline",
            CurveKind::Trimmed => "trimmed",
            CurveKind::Replica => "replica",
            CurveKind::Offset => "offset",
        }
    }
}

impl fmt::Display for CurveKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl Curve {
    /// The kind.
    pub fn kind(&self) -> CurveKind {
        match self {
            Curve::Line(_) => CurveKind::Line,
            Curve::Circle(_) => CurveKind::Circle,
            Curve::Ellipse(_) => CurveKind::Ellipse,
            Curve::Parabola(_) => CurveKind::Parabola,
            Curve::Hyperbola(_) => CurveKind::Hyperbola,
            Curve::BSpline(_) => CurveKind::BSpline,
            Curve::Polyline(_) => CurveKind::Polyline,
            Curve::Trimmed(..) => CurveKind::Trimmed,
            Curve::Replica(_) => CurveKind::Replica,
            Curve::Offset(_) => CurveKind::Offset,
        }
    }

    /// Point and first two derivatives at `t`.
    pub fn derivs(&self, t: f64) -> CurveDerivs {
        match self {
            Curve::Line(c) => c.derivs(t),
            Curve::Circle(c) => c.derivs(t),
            Curve::Ellipse(c) => c.derivs(t),
            Curve::Parabola(c) => c.derivs(t),
            Curve::Hyperbola(c) => c.derivs(t),
            Curve::BSpline(c) => c.derivs(t),
            Curve::Polyline(c) => c.derivs(t),
            Curve::Trimmed(c, _) => c.derivs(t),
            Curve::Replica(c) => c.derivs(t),
            Curve::Offset(c) => c.derivs(t),
        }
    }

    /// Point at `t`.
    pub fn point(&self, t: f64) -> DVec3 {
        match self {
            Curve::Line(c) => c.point(t),
            Curve::Circle(c) => c.point(t),
            Curve::Ellipse(c) => c.point(t),
            Curve::Parabola(c) => c.point(t),
            Curve::Hyperbola(c) => c.point(t),
            Curve::BSpline(c) => c.point(t),
            Curve::Polyline(c) => c.point(t),
            Curve::Trimmed(c, _) => c.point(t),
            Curve::Replica(c) => c.point(t),
            Curve::Offset(c) => c.point(t),
        }
    }

    /// First derivative at `t`.
    pub fn derivative(&self, t: f64) -> DVec3 {
        self.derivs(t).d1
    }

    /// The natural parameter domain: lines unbounded, conics `[0, 2π]` periodic, B-splines
    /// their knot range, polylines `[0, n-1]`, trimmed curves their trimming interval.
    pub fn domain(&self) -> CurveDomain {
        match self {
            Curve::Line(c) => c.domain(),
            Curve::Circle(c) => c.domain(),
            Curve::Ellipse(c) => c.domain(),
            Curve::Parabola(c) => c.domain(),
            Curve::Hyperbola(c) => c.domain(),
            Curve::BSpline(c) => c.domain(),
            Curve::Polyline(c) => c.domain(),
            Curve::Replica(c) => c.domain(),
            Curve::Offset(c) => c.domain(),
            Curve::Trimmed(c, range) => {
                let base = c.domain();
                let closed = base.period.is_some_and(|p| (range.length() - p).abs() <= 1e-12 * p);
                CurveDomain { range: *range, period: None, closed }
            }
        }
    }

    /// Parameter of the point of the curve closest to `p`: closed form for lines and circles,
    /// Newton from the eccentric angle for ellipses, Newton from the nearest sample for
    /// B-splines. Periodic parameters come back in `[0, 2π)`; trimmed curves' in their
    /// interval.
    pub fn project(&self, p: DVec3) -> f64 {
        match self {
            Curve::Line(c) => c.project(p),
            Curve::Circle(c) => c.project(p),
            Curve::Ellipse(c) => c.project(p),
            Curve::Parabola(c) => c.project(p),
            Curve::Hyperbola(c) => c.project(p),
            Curve::BSpline(c) => c.project(p),
            Curve::Polyline(c) => c.project(p),
            Curve::Replica(c) => c.project(p),
            Curve::Offset(c) => c.project(p),
            Curve::Trimmed(c, range) => {
                let t = c.project(p);
                match c.domain().period {
                    Some(per) => {
                        let w = wrap_into(t, range.min, per);
                        // past the end of the trim: the nearer end
                        if w > range.max {
                            let (da, db) = ((c.point(range.min) - p).length(), (c.point(range.max) - p).length());
                            if da < db { range.min } else { range.max }
                        } else {
                            w
                        }
                    }
                    None => range.clamp(t),
                }
            }
        }
    }

    /// Like [`Curve::project`], but near `t0`: periodic parameters are unwrapped to within half
    /// a period of `t0`, and B-splines refine from `t0` (for marching along an edge).
    pub fn project_near(&self, p: DVec3, t0: f64) -> f64 {
        match self {
            Curve::BSpline(c) => {
                let t = refine_curve(|t| c.derivs(t), &c.domain(), p, t0);
                // a poor local minimum: fall back to the global answer
                let g = c.project(p);
                if (c.point(g) - p).length() < (c.point(t) - p).length() * (1.0 - 1e-12) { g } else { t }
            }
            _ => {
                let t = self.project(p);
                match self.domain().period {
                    Some(per) => unwrap_near(t, t0, per),
                    None => t,
                }
            }
        }
    }

    /// Refines `t0` by Newton towards the parameter of the point closest to `p`, without a
    /// global search, until a step would move the point by `tol` relative or less.
    pub fn refine_within(&self, p: DVec3, t0: f64, tol: f64) -> f64 {
        refine_curve_within(|t| self.derivs(t), &self.domain(), p, t0, tol)
    }

    /// The curve moved.
    pub fn transformed(&self, t: &Rigid) -> Curve {
        match self {
            Curve::Line(c) => Curve::Line(c.transformed(t)),
            Curve::Circle(c) => Curve::Circle(c.transformed(t)),
            Curve::Ellipse(c) => Curve::Ellipse(c.transformed(t)),
            Curve::Parabola(c) => Curve::Parabola(c.transformed(t)),
            Curve::Hyperbola(c) => Curve::Hyperbola(c.transformed(t)),
            Curve::BSpline(c) => Curve::BSpline(c.transformed(t)),
            Curve::Polyline(c) => Curve::Polyline(c.transformed(t)),
            Curve::Trimmed(c, r) => Curve::Trimmed(Box::new(c.transformed(t)), *r),
            Curve::Replica(c) => Curve::Replica(c.transformed(t)),
            Curve::Offset(c) => Curve::Offset(c.transformed(t)),
        }
    }

    /// Approximate length of the curve over `[a, b]` (a 64-segment chord sum; for telling
    /// degenerate edges).
    pub fn chord_length(&self, a: f64, b: f64) -> f64 {
        let n = 64;
        let mut len = 0.0;
        let mut prev = self.point(a);
        for k in 1..=n {
            let q = self.point(a + (b - a) * k as f64 / n as f64);
            len += (q - prev).length();
            prev = q;
        }
        len
    }
}

impl Curve {
    /// Samples for a global start of a projection onto a surface swept from this curve:
    /// every knot span of a B-spline, else evenly over its domain (an unbounded one limited
    /// to where the curve stays within 1e6 mm of its point at 0).
    pub fn sweep_samples(&self) -> CurveSamples {
        let r = self.domain().range;
        let t = match self {
            Curve::BSpline(b) => span_samples(b.knots(), b.degree(), b.control_points().len(), (b.degree() + 1).max(3), 512),
            _ if r.is_bounded() => even_samples(r.min, r.max, 64),
            _ => {
                // out to where the curve is 1e6 mm from its point at 0 (a hyperbola's cosh
                // overflows long before t = 1e6), or to t = ±1e6
                let p0 = self.point(r.clamp(0.0));
                let reach = |sign: f64| {
                    let mut t = 1.0;
                    while t < 1e6 {
                        let q = self.point(r.clamp(sign * 2.0 * t));
                        if !(q.is_finite() && (q - p0).length() < 1e6) {
                            break;
                        }
                        t *= 2.0;
                    }
                    r.clamp(sign * t)
                };
                even_samples(reach(-1.0), reach(1.0), 256)
            }
        };
        let p = t.iter().map(|&t| self.point(t)).collect();
        CurveSamples { t, p }
    }
}

// Curve replicas (STEP `CURVE_REPLICA`): a parent curve under a [`Similarity`].

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


// 3D offset curves (STEP `OFFSET_CURVE_3D`).

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
