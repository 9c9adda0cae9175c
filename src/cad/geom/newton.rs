//! Closest-point refinement by Newton's method, shared by the curves and surfaces whose
//! inverse has no closed form (B-splines, swept and offset surfaces).

use super::derivs::{CurveDerivs, SurfaceDerivs};
use super::domain::{CurveDomain, SurfaceDomain, wrap_into};
use glam::{DVec2, DVec3};

const MAX_ITERATIONS: usize = 60;

/// Keeps a parameter inside a domain axis: periodic axes are left free (wrapped later),
/// bounded ones clamped.
fn keep_in(t: f64, min: f64, max: f64, periodic: bool) -> f64 {
    if periodic { t } else { t.max(min).min(max) }
}

/// The parameter of the point of a curve closest to `target`, by Newton's method on
/// `(C(t) - target) · C'(t) = 0` from `t0`. Periodic parameters come back in the domain's window.
pub fn refine_curve(eval: impl Fn(f64) -> CurveDerivs, domain: &CurveDomain, target: DVec3, t0: f64) -> f64 {
    refine_curve_within(eval, domain, target, t0, 0.0)
}

/// [`refine_curve`], stopping once a Newton step would move the point by `tol · (1 + |C(t)|)`
/// or less (`0`: only where rounding stops it, after its last step halvings fail).
pub fn refine_curve_within(eval: impl Fn(f64) -> CurveDerivs, domain: &CurveDomain, target: DVec3, t0: f64, tol: f64) -> f64 {
    let periodic = domain.period.is_some();
    let (lo, hi) = (domain.range.min, domain.range.max);
    let mut t = keep_in(t0, lo, hi, periodic);
    let mut c = eval(t);
    let mut dist = (c.p - target).length_squared();
    for _ in 0..MAX_ITERATIONS {
        let d = c.p - target;
        let g = d.dot(c.d1);
        let mut h = c.d1.length_squared() + d.dot(c.d2);
        if !(h > 0.0) {
            h = c.d1.length_squared();
        }
        if !(h > 0.0) || !g.is_finite() {
            break;
        }
        let mut step = -g / h;
        if tol > 0.0 && step.abs() * c.d1.length() <= tol * (1.0 + c.p.length()) {
            break;
        }
        let mut improved = false;
        for _ in 0..12 {
            let nt = keep_in(t + step, lo, hi, periodic);
            let nc = eval(nt);
            let nd = (nc.p - target).length_squared();
            // near the minimum the distance is flat to rounding: accept a smaller gradient too
            if nd < dist || (nd <= dist * (1.0 + 1e-9) && (nc.p - target).dot(nc.d1).abs() < g.abs()) {
                let moved = (nt - t).abs();
                t = nt;
                c = nc;
                dist = nd;
                improved = moved > 0.0;
                break;
            }
            step *= 0.5;
        }
        if !improved || (step.abs() * c.d1.length()) <= 1e-16 * (1.0 + c.p.length()) {
            break;
        }
    }
    match domain.period {
        Some(per) => wrap_into(t, lo, per),
        None => t,
    }
}

/// Newton ([`refine_surface`]) from the three starts nearest to `target` (`starts` holds
/// squared distance and `(u, v)`); the result closest to `target`, or `fallback` if there is
/// no start.
pub fn refine_from_best(eval: impl Fn(f64, f64) -> SurfaceDerivs, domain: &SurfaceDomain, target: DVec3, mut starts: Vec<(f64, DVec2)>, fallback: DVec2) -> DVec2 {
    starts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut out = (f64::INFINITY, fallback);
    for &(_, start) in starts.iter().take(3) {
        let r = refine_surface(&eval, domain, target, start);
        let d = (eval(r.x, r.y).p - target).length_squared();
        if d < out.0 {
            out = (d, r);
        }
    }
    out.1
}

/// The parameters of the point of a surface closest to `target`, by Newton's method on the
/// gradient of the squared distance from `start` (Gauss–Newton where the Hessian is not
/// positive definite), with step halving. Periodic parameters come back in the domain's window.
pub fn refine_surface(eval: impl Fn(f64, f64) -> SurfaceDerivs, domain: &SurfaceDomain, target: DVec3, start: DVec2) -> DVec2 {
    refine_surface_within(eval, domain, target, start, 0.0)
}

/// [`refine_surface`], stopping once a Newton step would move the point by
/// `tol · (1 + |S(u, v)|)` or less (`0`: only where rounding stops it, after its last step
/// halvings fail).
pub fn refine_surface_within(eval: impl Fn(f64, f64) -> SurfaceDerivs, domain: &SurfaceDomain, target: DVec3, start: DVec2, tol: f64) -> DVec2 {
    let (pu, pv) = (domain.u_period.is_some(), domain.v_period.is_some());
    let clamp = |q: DVec2| DVec2::new(keep_in(q.x, domain.u.min, domain.u.max, pu), keep_in(q.y, domain.v.min, domain.v.max, pv));
    let mut q = clamp(start);
    let mut s = eval(q.x, q.y);
    let mut dist = (s.p - target).length_squared();
    for _ in 0..MAX_ITERATIONS {
        let d = s.p - target;
        let g = DVec2::new(d.dot(s.du), d.dot(s.dv));
        let (a0, b0, c0) = (s.du.length_squared(), s.du.dot(s.dv), s.dv.length_squared());
        let (mut a, mut b, mut c) = (a0 + d.dot(s.duu), b0 + d.dot(s.duv), c0 + d.dot(s.dvv));
        if !(a > 0.0 && a * c - b * b > 0.0) {
            (a, b, c) = (a0, b0, c0);
        }
        let det = a * c - b * b;
        if !(det > 1e-300) || !g.is_finite() {
            break;
        }
        let mut step = DVec2::new(-(c * g.x - b * g.y) / det, -(a * g.y - b * g.x) / det);
        if tol > 0.0 && step.x.abs() * s.du.length() + step.y.abs() * s.dv.length() <= tol * (1.0 + s.p.length()) {
            break;
        }
        let mut improved = false;
        let gnorm = g.x.abs() / s.du.length().max(1e-300) + g.y.abs() / s.dv.length().max(1e-300);
        for _ in 0..12 {
            let nq = clamp(q + step);
            let ns = eval(nq.x, nq.y);
            let nd = (ns.p - target).length_squared();
            let e = ns.p - target;
            let ngnorm = e.dot(ns.du).abs() / ns.du.length().max(1e-300) + e.dot(ns.dv).abs() / ns.dv.length().max(1e-300);
            // near the minimum the distance is flat to rounding: accept a smaller gradient too
            if nd < dist || (nd <= dist * (1.0 + 1e-9) && ngnorm < gnorm) {
                improved = nq != q;
                q = nq;
                s = ns;
                dist = nd;
                break;
            }
            step *= 0.5;
        }
        let moved = step.x.abs() * s.du.length() + step.y.abs() * s.dv.length();
        if !improved || moved <= 1e-16 * (1.0 + s.p.length()) {
            break;
        }
    }
    if let Some(per) = domain.u_period {
        q.x = wrap_into(q.x, domain.u.min, per);
    }
    if let Some(per) = domain.v_period {
        q.y = wrap_into(q.y, domain.v.min, per);
    }
    q
}

/// A sampling of a curve for a global start: parameters and points.
#[derive(Clone, Debug, Default)]
pub struct CurveSamples {
    /// Parameters.
    pub t: Vec<f64>,
    /// Points at those parameters.
    pub p: Vec<DVec3>,
}

impl CurveSamples {
    /// The parameters of the `k` samples nearest to `target` (fewer if there are fewer).
    pub fn nearest(&self, target: DVec3, k: usize) -> Vec<f64> {
        let mut best: Vec<(f64, f64)> = Vec::with_capacity(k + 1);
        for (&t, &p) in self.t.iter().zip(&self.p) {
            push_best(&mut best, ((p - target).length_squared(), t), k);
        }
        best.into_iter().map(|(_, t)| t).collect()
    }
}

/// A grid sampling of a surface for a global start.
#[derive(Clone, Debug, Default)]
pub struct SurfaceSamples {
    /// Parameters.
    pub uv: Vec<DVec2>,
    /// Points at those parameters.
    pub p: Vec<DVec3>,
    /// The diagonal of the points' bounding box (0 without points).
    pub size: f64,
}

impl SurfaceSamples {
    /// Samples `eval` on the grid `us × vs`.
    pub fn grid(us: &[f64], vs: &[f64], eval: impl Fn(f64, f64) -> DVec3) -> SurfaceSamples {
        let mut s = SurfaceSamples { uv: Vec::with_capacity(us.len() * vs.len()), p: Vec::with_capacity(us.len() * vs.len()), size: 0.0 };
        for &u in us {
            for &v in vs {
                s.uv.push(DVec2::new(u, v));
                s.p.push(eval(u, v));
            }
        }
        s.size = crate::core::aabb::Aabb::from_points(&s.p).diagonal();
        s
    }

    /// The parameters of the `k` samples nearest to `target`.
    pub fn nearest(&self, target: DVec3, k: usize) -> Vec<DVec2> {
        let mut best: Vec<(f64, DVec2)> = Vec::with_capacity(k + 1);
        for (&uv, &p) in self.uv.iter().zip(&self.p) {
            push_best(&mut best, ((p - target).length_squared(), uv), k);
        }
        best.into_iter().map(|(_, uv)| uv).collect()
    }
}

fn push_best<T: Copy>(best: &mut Vec<(f64, T)>, item: (f64, T), k: usize) {
    if best.len() == k && best.last().is_some_and(|l| l.0 <= item.0) {
        return;
    }
    let pos = best.partition_point(|b| b.0 <= item.0);
    best.insert(pos, item);
    best.truncate(k);
}

/// `n` parameters spread over each non-empty knot span (ends included once), capped at `max`
/// in all by thinning; for B-spline sampling.
pub fn span_samples(knots: &[f64], degree: usize, n_ctrl: usize, per_span: usize, max: usize) -> Vec<f64> {
    let mut out = Vec::new();
    for i in degree..n_ctrl {
        let (a, b) = (knots[i], knots[i + 1]);
        if a < b {
            for k in 0..per_span {
                out.push(a + (b - a) * k as f64 / per_span as f64);
            }
        }
    }
    out.push(knots[n_ctrl]);
    if out.len() > max && max >= 2 {
        let n = out.len();
        out = (0..max).map(|k| out[k * (n - 1) / (max - 1)]).collect();
    }
    out
}

/// `n + 1` evenly spaced parameters over `[a, b]`.
pub fn even_samples(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..=n).map(|k| a + (b - a) * k as f64 / n as f64).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cad::geom::domain::Interval;
    use std::cell::Cell;

    #[test]
    fn a_tolerance_stops_the_search_sooner_at_the_same_point() {
        // a helix, as a curve whose inverse has no closed form
        let evals = Cell::new(0usize);
        let eval = |t: f64| {
            evals.set(evals.get() + 1);
            CurveDerivs {
                p: DVec3::new(t.cos(), t.sin(), 0.3 * t),
                d1: DVec3::new(-t.sin(), t.cos(), 0.3),
                d2: DVec3::new(-t.cos(), -t.sin(), 0.0),
            }
        };
        let domain = CurveDomain { range: Interval { min: -10.0, max: 10.0 }, period: None, closed: false };
        let target = DVec3::new(2.0 * 1.0f64.cos(), 2.0 * 1.0f64.sin(), 0.35);
        let full = refine_curve(eval, &domain, target, 0.6);
        let n_full = evals.replace(0);
        let within = refine_curve_within(eval, &domain, target, 0.6, 1e-12);
        let n_within = evals.get();
        let (a, b) = (eval(full).p, eval(within).p);
        assert!(a.distance(b) <= 1e-10, "{a} {b}");
        assert!(n_within < n_full, "{n_within} evaluations against {n_full}");
        // tol 0 is the full search, bit for bit
        assert_eq!(refine_curve_within(eval, &domain, target, 0.6, 0.0), full);
    }
}
