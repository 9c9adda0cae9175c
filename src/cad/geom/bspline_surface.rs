//! B-spline surfaces, polynomial or rational (STEP `B_SPLINE_SURFACE_WITH_KNOTS`, and the
//! complex instance with `RATIONAL_B_SPLINE_SURFACE`), evaluated exactly by Cox–de Boor.

use super::basis::{MAX_DEGREE, basis_derivatives, check_knots, check_points_weights, find_span};
use super::spline_error::SplineError;
use super::derivs::SurfaceDerivs;
use super::domain::{Interval, SurfaceDomain};
use super::frame::Rigid;
use super::newton::{SurfaceSamples, refine_surface, span_samples};
use glam::{DVec2, DVec3};
use std::sync::OnceLock;

/// A tensor-product B-spline surface. Control point `(i, j)` (`i` along `u`, `j` along `v`) is
/// `control_points()[i * nv + j]`, as STEP lists them (a list of rows of constant `i`).
#[derive(Clone, Debug)]
pub struct BSplineSurface {
    degree: [usize; 2],
    knots_u: Vec<f64>,
    knots_v: Vec<f64>,
    nu: usize,
    nv: usize,
    points: Vec<DVec3>,
    weights: Option<Vec<f64>>,
    samples: OnceLock<SurfaceSamples>,
    dom: OnceLock<SurfaceDomain>,
}

impl BSplineSurface {
    /// A checked surface: `points` holds `nu × nv` control points row by row (`i` slow);
    /// `knots_u`/`knots_v` are full knot vectors; `weights`, if given, are positive, one per point.
    pub fn new(
        degree_u: usize,
        degree_v: usize,
        knots_u: Vec<f64>,
        knots_v: Vec<f64>,
        nu: usize,
        nv: usize,
        points: Vec<DVec3>,
        weights: Option<Vec<f64>>,
    ) -> Result<BSplineSurface, SplineError> {
        if nu.checked_mul(nv) != Some(points.len()) {
            return Err(SplineError::Grid { points: points.len(), nu, nv });
        }
        check_knots(degree_u, &knots_u, nu).map_err(|e| SplineError::Direction { direction: "u", error: Box::new(e) })?;
        check_knots(degree_v, &knots_v, nv).map_err(|e| SplineError::Direction { direction: "v", error: Box::new(e) })?;
        // all weights equal: polynomial
        let weights = check_points_weights(&points, weights)?;
        Ok(BSplineSurface { degree: [degree_u, degree_v], knots_u, knots_v, nu, nv, points, weights, samples: OnceLock::new(), dom: OnceLock::new() })
    }

    /// Degrees in `u` and `v`.
    pub fn degrees(&self) -> [usize; 2] {
        self.degree
    }

    /// Full knot vectors in `u` and `v`.
    pub fn knots(&self) -> [&[f64]; 2] {
        [&self.knots_u, &self.knots_v]
    }

    /// Number of control points in `u` and `v`.
    pub fn counts(&self) -> [usize; 2] {
        [self.nu, self.nv]
    }

    /// The control points, row by row (`i` along `u` slow).
    pub fn control_points(&self) -> &[DVec3] {
        &self.points
    }

    /// The weights, `None` for a polynomial surface.
    pub fn weights(&self) -> Option<&[f64]> {
        self.weights.as_deref()
    }

    /// Point and derivatives up to second order at `(u, v)`.
    pub fn derivs(&self, u: f64, v: f64) -> SurfaceDerivs {
        self.derivs_to(u, v, 2)
    }

    /// Point and derivatives up to order `nd` (0, 1 or 2) at `(u, v)`; the higher ones zero.
    /// The point alone costs about a third of all derivatives (the quadrature of the
    /// certificate and of the volume check evaluates millions of them).
    pub fn derivs_to(&self, u: f64, v: f64, nd: usize) -> SurfaceDerivs {
        let nd = nd.min(2);
        let [pu, pv] = self.degree;
        let su = find_span(&self.knots_u, pu, self.nu, u);
        let sv = find_span(&self.knots_v, pv, self.nv, v);
        let mut bu = [[0.0; MAX_DEGREE + 1]; 3];
        let mut bv = [[0.0; MAX_DEGREE + 1]; 3];
        basis_derivatives(&self.knots_u, pu, su, u, nd, &mut bu);
        basis_derivatives(&self.knots_v, pv, sv, v, nd, &mut bv);
        // homogeneous sums: a[k][l] = Σ N^(k) M^(l) w P, w[k][l] = Σ N^(k) M^(l) w
        let mut a = [[DVec3::ZERO; 3]; 3];
        let mut w = [[0.0f64; 3]; 3];
        for i in 0..=pu {
            let row = (su - pu + i) * self.nv + (sv - pv);
            // inner sums over j for each v-derivative order
            let mut ra = [DVec3::ZERO; 3];
            let mut rw = [0.0f64; 3];
            for j in 0..=pv {
                let idx = row + j;
                let (q, wt) = match &self.weights {
                    Some(ws) => (self.points[idx] * ws[idx], ws[idx]),
                    None => (self.points[idx], 1.0),
                };
                for l in 0..=nd {
                    ra[l] += bv[l][j] * q;
                    rw[l] += bv[l][j] * wt;
                }
            }
            for k in 0..=nd {
                for l in 0..=nd - k {
                    a[k][l] += bu[k][i] * ra[l];
                    w[k][l] += bu[k][i] * rw[l];
                }
            }
        }
        if self.weights.is_none() {
            return SurfaceDerivs { p: a[0][0], du: a[1][0], dv: a[0][1], duu: a[2][0], duv: a[1][1], dvv: a[0][2] };
        }
        // quotient rule for S = A / W
        let w0 = w[0][0];
        let s = a[0][0] / w0;
        let su_ = (a[1][0] - w[1][0] * s) / w0;
        let sv_ = (a[0][1] - w[0][1] * s) / w0;
        let suu = (a[2][0] - 2.0 * w[1][0] * su_ - w[2][0] * s) / w0;
        let svv = (a[0][2] - 2.0 * w[0][1] * sv_ - w[0][2] * s) / w0;
        let suv = (a[1][1] - w[1][0] * sv_ - w[0][1] * su_ - w[1][1] * s) / w0;
        SurfaceDerivs { p: s, du: su_, dv: sv_, duu: suu, duv: suv, dvv: svv }
    }

    /// Point at `(u, v)`.
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        self.derivs_to(u, v, 0).p
    }

    fn rows_equal(&self, a: usize, b: usize, along_u: bool) -> bool {
        let size = self.points.iter().fold(0.0f64, |m, p| m.max(p.length())).max(1e-300);
        let n = if along_u { self.nv } else { self.nu };
        (0..n).all(|k| {
            let (pa, pb) = if along_u { (self.points[a * self.nv + k], self.points[b * self.nv + k]) } else { (self.points[k * self.nv + a], self.points[k * self.nv + b]) };
            (pa - pb).length() <= 1e-12 * size
        })
    }

    /// The knot ranges; `u_closed` / `v_closed` when the first and last rows of control points
    /// coincide. Never periodic (parameters are not wrapped).
    pub fn domain(&self) -> SurfaceDomain {
        // kept: every projection asks, and the closed test compares all control points
        *self.dom.get_or_init(|| self.domain_uncached())
    }

    fn domain_uncached(&self) -> SurfaceDomain {
        let [pu, pv] = self.degree;
        SurfaceDomain {
            u: Interval::new(self.knots_u[pu], self.knots_u[self.nu]),
            v: Interval::new(self.knots_v[pv], self.knots_v[self.nv]),
            u_period: None,
            v_period: None,
            u_closed: self.rows_equal(0, self.nu - 1, true),
            v_closed: self.rows_equal(0, self.nv - 1, false),
        }
    }

    fn samples(&self) -> &SurfaceSamples {
        self.samples.get_or_init(|| {
            let [pu, pv] = self.degree;
            let us = span_samples(&self.knots_u, pu, self.nu, (pu + 1).max(3), 48);
            let vs = span_samples(&self.knots_v, pv, self.nv, (pv + 1).max(3), 48);
            SurfaceSamples::grid(&us, &vs, |u, v| self.point(u, v))
        })
    }

    /// Parameters of the closest point: Newton from each of the four grid samples nearest to
    /// `p` (the grid has a few samples per knot span, at most 48 × 48), the best result kept.
    /// When that best is farther from `p` than 1e-5 of the grid's size, from the 32 nearest:
    /// on a surface that folds back near itself (a long skinned face) the nearest samples can
    /// all lie on the wrong sheet, and a point of its boundary went 0.6 mm off, its face's loop
    /// across itself.
    pub fn project(&self, p: DVec3) -> DVec2 {
        let dom = self.domain();
        let samples = self.samples();
        let mut best = (f64::INFINITY, DVec2::new(dom.u.min, dom.v.min));
        let from = |starts: Vec<DVec2>, best: &mut (f64, DVec2)| {
            for start in starts {
                let q = refine_surface(|u, v| self.derivs(u, v), &dom, p, start);
                let d = (self.point(q.x, q.y) - p).length_squared();
                if d < best.0 {
                    *best = (d, q);
                }
            }
        };
        from(samples.nearest(p, 4), &mut best);
        let far = 1e-5 * samples.size;
        if best.0 > far * far {
            from(samples.nearest(p, 32), &mut best);
        }
        best.1
    }

    /// Parameters of the closest point by Newton from `start` only (for marching; no global
    /// search).
    pub fn project_near(&self, p: DVec3, start: DVec2) -> DVec2 {
        refine_surface(|u, v| self.derivs(u, v), &self.domain(), p, start)
    }

    /// The surface moved.
    pub fn transformed(&self, t: &Rigid) -> BSplineSurface {
        BSplineSurface {
            points: self.points.iter().map(|&p| t.apply_point(p)).collect(),
            samples: OnceLock::new(),
            dom: OnceLock::new(),
            ..self.clone()
        }
    }
}
