//! Vertex smoothing by non-smooth optimisation: a free vertex moves to raise the least score of
//! the tets around it, after Freitag, Jones and Plassmann's method as Klingner and Shewchuk use
//! it ("Aggressive tetrahedral mesh improvement", 2007).
//!
//! The objective `f(x) = min` over the star's tets of their terms in
//! [`measure`](crate::mesh3d::optimize::measure) (two normalised angle terms per edge, and the
//! radius-edge term) is maximised from the current position:
//! 1. the *active* terms are those within a small margin of `f`; the search direction `d` is the
//!    point of least norm in the convex hull of their gradients (Gilbert's algorithm), the
//!    steepest ascent direction of their minimum;
//! 2. the first step goes where the linear model of an inactive term would meet that of the
//!    active ones, capped to a fraction of the star's size; it is halved until the least score
//!    rises and every tet of the star stays positively oriented, decided exactly with
//!    [`orient3d`](crate::core::predicates::orient3d) at the very position that is kept;
//! 3. this repeats while the score rises.
//!
//! Vertices on no constrained face move freely. A constrained face's vertices are fixed, but
//! for those that may slide ([`crate::mesh3d::optimize::slide`]): their gradients are projected
//! on their plane or line and every position tried is put back on it. So the boundary, the
//! region interfaces and the union of the star (hence the volume, up to rounding) stay as they
//! are.

use crate::core::Sign;
use crate::core::predicates::orient3d;
use crate::mesh3d::optimize::measure::{LeastScore, Term, terms_below};
use crate::mesh3d::optimize::slide::{self, Mover};
use crate::mesh3d::optimize::star::Star;
use crate::mesh3d::optimize::work::Work;
use crate::quality::tetrahedron::tet_radius_edge;
use glam::DVec3;

/// Terms within this much of the least are active.
const ACTIVE: f64 = 1e-3;
/// Terms within this much of the least are considered for the step prediction.
const WINDOW: f64 = 0.6;
/// Iterations of steepest ascent per call.
const ITERATIONS: usize = 12;
/// Halvings of the step in the line search.
const HALVINGS: usize = 10;
/// Least improvement of the score that counts.
pub(crate) const MIN_GAIN: f64 = 1e-6;

/// Scratch space for smoothing, reused across calls.
#[derive(Default)]
pub(crate) struct Smoother {
    star: Star,
    terms: Vec<Term>,
    grads: Vec<DVec3>,
    /// Per vertex, the [`Work::clock`] when smoothing it last failed (0: never).
    failed: Vec<u32>,
    /// The order [`Smoother::evaluate`] goes through the star in: the tet that failed the last
    /// position tried first (the next, half as far, usually fails on the same tet).
    order: Vec<usize>,
}

/// The point of least norm in the convex hull of `g` (Gilbert's algorithm, approximately).
fn min_norm(g: &[DVec3]) -> DVec3 {
    let Some(mut x) = g.iter().copied().min_by(|a, b| a.length_squared().total_cmp(&b.length_squared())) else {
        return DVec3::ZERO;
    };
    for _ in 0..64 {
        let xx = x.length_squared();
        if xx == 0.0 {
            break;
        }
        let (gi, gx) = g.iter().map(|&gi| (gi, gi.dot(x))).min_by(|a, b| a.1.total_cmp(&b.1)).unwrap_or((x, xx));
        if xx - gx <= 1e-10 * xx {
            break;
        }
        let diff = gi - x;
        let dd = diff.length_squared();
        if dd == 0.0 {
            break;
        }
        x += diff * ((xx - gx) / dd).clamp(0.0, 1.0);
    }
    x
}

impl Smoother {
    /// The least score of the star with the vertex at `x`, or `None` if a tet would not be
    /// positively oriented (exact). It may stop at a tet that surely scores at most `beat`
    /// and then gives a value at most `beat` (the caller only asks whether `beat` is beaten).
    /// The angle terms are folded by their cosines ([`LeastScore`]): two arc cosines per call,
    /// not two per tet, and the same bits.
    /// `fail` is [`Targets::failing_cosines`](crate::mesh3d::optimize::measure::Targets) of
    /// `beat`.
    ///
    /// The tets are taken in [`Smoother::order`], and the one that stops it goes to the front.
    /// The answer does not depend on the order: the least of the scores is the least in any
    /// order (the cosines and the radius-edge term are folded by `min` and `max`), and where
    /// one tet stops it, that tet stops it in every order, so `beat` is not beaten either way.
    fn evaluate(&mut self, w: &Work, x: DVec3, beat: f64, fail: (f64, f64)) -> Option<f64> {
        let (fail_lo, fail_hi) = fail;
        let mut least = LeastScore::new();
        for i in 0..self.order.len() {
            let s = self.order[i];
            let [a, b, c, d] = self.star.corners_at(w, s, x);
            if orient3d(a, b, c, d) != Sign::Positive {
                self.order[..=i].rotate_right(1);
                return None;
            }
            let sure_fail = match least.add(&[a, b, c, d], &w.tg) {
                None => true,
                Some((lo, hi)) => lo < fail_lo || hi > fail_hi || least.re_term() <= beat,
            };
            if sure_fail {
                self.order[..=i].rotate_right(1);
                return Some(least.value(&w.tg).min(beat));
            }
        }
        Some(least.value(&w.tg))
    }

    /// Forgets where smoothing failed (the targets changed: it may succeed there now).
    pub(crate) fn forget_failures(&mut self) {
        self.failed.clear();
    }

    /// Moves free vertex `v` to raise the least score of its star; true if it moved. New tets
    /// keep radius-edge ratios within `max(max_re, the star's worst before)`.
    pub(crate) fn try_smooth(&mut self, w: &mut Work, v: u32, max_re: f64) -> bool {
        let vi = v as usize;
        if !w.movable(v) || self.failed.get(vi).is_some_and(|&f| f != 0 && w.touched[vi] <= f) {
            // fixed, or failed before and no tet at it changed since: it would fail again
            return false;
        }
        let moved = self.smooth_free(w, v, max_re);
        if !moved {
            if self.failed.len() <= vi {
                self.failed.resize(vi + 1, 0);
            }
            self.failed[vi] = w.clock;
        }
        moved
    }

    fn smooth_free(&mut self, w: &mut Work, v: u32, max_re: f64) -> bool {
        if !self.star.load(w, v) {
            return false;
        }
        let x0 = w.pts[v as usize];
        let f0 = self.star.tets.iter().map(|&t| w.q[t as usize]).fold(f64::INFINITY, f64::min);
        slide::prepare(w, v);
        let Some((x, f)) = self.optimise(w, x0, f0, Mover::of(w, v, x0)) else {
            return false;
        };
        if f <= f0 + MIN_GAIN {
            return false;
        }
        let old_re = self.star.tets.iter().map(|&t| w.judged[t as usize].re).fold(0.0f64, f64::max);
        let bound = max_re.max(old_re);
        for s in 0..self.star.len() {
            if tet_radius_edge(&self.star.corners_at(w, s, x)) > bound {
                return false;
            }
        }
        w.move_vertex(v, x, &self.star.tets);
        true
    }

    /// Optimises the position of the star's vertex from `x0` (least score `f0`): the best
    /// position found and its least score, every star tet positive there.
    fn optimise(&mut self, w: &Work, x0: DVec3, f0: f64, mover: Mover) -> Option<(DVec3, f64)> {
        // a length scale: the mean distance to the star's other vertices
        let scale = self.star.scale(w, x0);
        self.order.clear();
        self.order.extend(0..self.star.len());
        let (mut x, mut f) = (x0, f0);
        for _ in 0..ITERATIONS {
            self.terms.clear();
            let quiet = w.tg.quiet_cosines(f + WINDOW);
            for s in 0..self.star.len() {
                let p = self.star.corners_at(w, s, x);
                let terms = &mut self.terms;
                terms_below(&p, self.star.at(s), &w.tg, f + WINDOW, quiet, f + ACTIVE, |t| terms.push(t));
            }
            self.grads.clear();
            for t in &self.terms {
                if t.value <= f + ACTIVE {
                    self.grads.push(mover.project(t.grad));
                }
            }
            let d = min_norm(&self.grads);
            let dd = d.length_squared();
            if dd.is_nan() || dd <= 0.0 || !dd.is_finite() {
                break;
            }
            let mut alpha = 0.2 * scale / dd.sqrt();
            for t in &self.terms {
                let gd = t.grad.dot(d);
                if t.value > f + ACTIVE && gd < dd {
                    alpha = alpha.min((t.value - f) / (dd - gd));
                }
            }
            let mut moved = false;
            let fail = w.tg.failing_cosines(f + MIN_GAIN);
            for _ in 0..HALVINGS {
                let y = mover.place(w, x, x + d * alpha);
                if let Some((y, fy)) = y.and_then(|y| Some((y, self.evaluate(w, y, f + MIN_GAIN, fail)?))) {
                    if fy > f + MIN_GAIN {
                        x = y;
                        f = fy;
                        moved = true;
                        break;
                    }
                }
                alpha *= 0.5;
            }
            if !moved {
                break;
            }
        }
        (f > f0).then_some((x, f))
    }

    /// Optimises the position of a vertex `v` just inserted (its star in place), as
    /// [`Smoother::try_smooth`] without the radius-edge comparison (the caller judges the
    /// result); true if it moved.
    pub(crate) fn smooth_new(&mut self, w: &mut Work, v: u32) -> bool {
        if !self.star.load(w, v) {
            return false;
        }
        let x0 = w.pts[v as usize];
        let f0 = self.star.tets.iter().map(|&t| w.q[t as usize]).fold(f64::INFINITY, f64::min);
        let Some((x, f)) = self.optimise(w, x0, f0, Mover::free()) else {
            return false;
        };
        if f <= f0 + MIN_GAIN {
            return false;
        }
        w.move_vertex(v, x, &self.star.tets);
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shapes::kuhn_cube;
    use crate::mesh3d::optimize::measure::Targets;

    #[test]
    fn min_norm_point() {
        let d = min_norm(&[DVec3::new(1.0, 1.0, 0.0), DVec3::new(1.0, -1.0, 0.0)]);
        assert!((d - DVec3::X).length() < 1e-9, "{d}");
        let d = min_norm(&[DVec3::X, -DVec3::X]);
        assert!(d.length() < 1e-9);
        assert_eq!(min_norm(&[]), DVec3::ZERO);
    }

    #[test]
    fn smoothing_a_displaced_vertex() {
        // the centre of a 2×2×2 Kuhn cube pushed towards a corner: smoothing pulls it back
        let mut m = kuhn_cube(2, 0.0, 1);
        let centre = m.vertices.iter().position(|p| (*p - DVec3::splat(0.5)).length() < 1e-12).unwrap() as u32;
        m.vertices[centre as usize] = DVec3::new(0.3, 0.32, 0.35);
        assert_eq!(m.validate(), Ok(()));
        let v0 = m.volume();
        let mut w = Work::build(&m, Targets::new(30.0, 130.0)).unwrap();
        let mut star = Vec::new();
        w.star(centre, &mut star);
        assert_eq!(star.len(), 24);
        let before = star.iter().map(|&t| w.q[t as usize]).fold(f64::INFINITY, f64::min);
        let mut sm = Smoother::default();
        assert!(sm.try_smooth(&mut w, centre, 2.0));
        let after = star.iter().map(|&t| w.q[t as usize]).fold(f64::INFINITY, f64::min);
        assert!(after > before + 0.1, "{before} -> {after}");
        let mut out = m.clone();
        w.write_back(&mut out);
        assert_eq!(out.validate(), Ok(()));
        assert!((out.volume() - v0).abs() < 1e-14);
        // corner vertices are fixed
        let mut w = Work::build(&m, Targets::new(30.0, 130.0)).unwrap();
        assert!(!sm.try_smooth(&mut w, 0, 2.0));
    }
}
