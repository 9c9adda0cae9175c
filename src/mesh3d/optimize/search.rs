//! The last resort for the tets left under the focus phase's bound: a search over the position
//! of each of their movable vertices by deterministic random samples, where smoothing's ascent
//! stops.
//!
//! Smoothing follows the steepest ascent of the star's least score from where the vertex is.
//! The least of many terms is far from concave: beside a thin boundary triangle the ascent
//! stalls, or climbs to a place whose radius-edge ratios it may not keep and is undone, while
//! samples around the vertex find a narrow ridge of better positions and walk up it in many
//! small steps (measured on real parts: a sliver of 7.63° left by the passes on
//! `BudimanZahri_Drawer` reaches 14.0°, and one of 8.10° on `aksprasan_top_cover` 10.4°).
//!
//! The merit of a tet is `min(θ_min, (180° − θ_max) · 2/3)` (degrees): a largest angle of
//! 165° counts as a smallest of 10°. A sample is taken when it raises the star's least merit
//! and keeps, over the star:
//! - every tet positively oriented (exact, at the very position kept);
//! - radius-edge ratios within the bound given or the star's worst before;
//! - largest angles within the star's worst before or 165° (the merit of the bound);
//! - no more tets under the bound than before: a least raised at the cost of others falling
//!   under it measured worse (on `jwchen119_fan_shroud` 1 tet under 10° that touches no small
//!   input angle became 4, on `efogtech_adapter-static` none became 5).
//!
//! Samples are drawn about normally (sums of uniforms: arithmetic alone, the same bits on
//! every machine) around the best position so far, with a spread from a tenth of the mean
//! distance to the star's other vertices, halving each round; the rounds start again while
//! they gain. A sliding boundary vertex's samples are put back on its plane or line. The
//! generator is seeded by the vertex, so the result depends on the mesh alone.

use crate::core::Sign;
use crate::core::predicates::orient3d;
use crate::mesh3d::optimize::measure::Judged;
use crate::mesh3d::optimize::slide::{self, Mover};
use crate::mesh3d::optimize::star::Star;
use crate::mesh3d::optimize::work::Work;
use glam::DVec3;

/// The weight of the largest angle's gap to 180° in the merit: 10° for a gap of 15°.
const HI_WEIGHT: f64 = 10.0 / 15.0;

/// Rounds of sampling, the spread halving after each.
const ROUNDS: usize = 10;

/// Samples per round.
const SAMPLES: usize = 200;

/// The first round's spread, as a share of the mean distance to the star's other vertices.
const START: f64 = 0.1;

/// The rounds start again from the best position while they gain this much (degrees), at
/// most [`REPEATS`] times in all: a narrow ridge takes many small steps.
const REPEAT_GAIN: f64 = 0.5;

/// The most times the rounds run for one vertex.
const REPEATS: usize = 4;

/// Least gain of the star's least merit that counts (degrees).
const MIN_GAIN: f64 = 1e-3;

/// The search's merit of a tet's measures (degrees).
#[inline]
pub(crate) fn merit(j: &Judged) -> f64 {
    j.lo.min((180.0 - j.hi) * HI_WEIGHT)
}

/// A small generator (SplitMix64): samples that depend on the seed alone.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[-1, 1)`.
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 * (2.0 / (1u64 << 53) as f64) - 1.0
    }

    /// About normal (the sum of four uniforms, scaled to unit variance): mostly small steps,
    /// now and then a long one, from arithmetic alone.
    fn normal(&mut self) -> f64 {
        (self.unit() + self.unit() + self.unit() + self.unit()) * 0.866_025_403_784_438_6
    }
}

/// Scratch space for the search, reused across calls.
#[derive(Default)]
pub(crate) struct Searcher {
    star: Star,
}

impl Searcher {
    /// The star's least merit with the vertex at `x`, `None` where a tet would not be
    /// positively oriented (exact), would pass `max_re`, or where more than `most_under` tets
    /// would have a merit under `below`. It may stop at a tet whose merit is at most `beat`
    /// and then gives a value at most `beat` (the caller only asks whether `beat` is beaten).
    #[allow(clippy::too_many_arguments)]
    fn evaluate(&self, w: &Work, x: DVec3, beat: f64, max_re: f64, max_hi: f64, below: f64, most_under: usize) -> Option<f64> {
        let mut least = f64::INFINITY;
        let mut under = 0;
        for s in 0..self.star.len() {
            let p = self.star.corners_at(w, s, x);
            if orient3d(p[0], p[1], p[2], p[3]) != Sign::Positive {
                return None;
            }
            let j = Judged::of(&p);
            if !(j.re <= max_re && j.hi <= max_hi) {
                return None;
            }
            let m = merit(&j);
            least = least.min(m);
            if least <= beat {
                return Some(least);
            }
            under += usize::from(m < below);
            if under > most_under {
                return None;
            }
        }
        Some(least)
    }

    /// Searches for a better position of vertex `v` (free, or sliding on its plane or line);
    /// true if it moved. New tets keep radius-edge ratios within `max(max_re, the star's worst
    /// before)`, and no more tets of the star than before have a merit under `below`.
    pub(crate) fn try_search(&mut self, w: &mut Work, v: u32, max_re: f64, below: f64) -> bool {
        if !self.star.load(w, v) {
            return false;
        }
        // the star's worst tets first, so that most samples are judged on a few tets
        self.star.order_by(|t| merit(&w.judged[t as usize]));
        let x0 = w.pts[v as usize];
        let f0 = self.star.tets.iter().map(|&t| merit(&w.judged[t as usize])).fold(f64::INFINITY, f64::min);
        let under0 = self.star.tets.iter().filter(|&&t| merit(&w.judged[t as usize]) < below).count();
        let re0 = self.star.tets.iter().map(|&t| w.judged[t as usize].re).fold(0.0, f64::max);
        let bound = max_re.max(re0);
        // no largest angle past the star's, or past the one a merit of `below` allows
        let hi0 = self.star.tets.iter().map(|&t| w.judged[t as usize].hi).fold(0.0, f64::max);
        let max_hi = hi0.max(180.0 - below / HI_WEIGHT);
        slide::prepare(w, v);
        let mover = Mover::of(w, v, x0);
        let scale = self.star.scale(w, x0);
        let mut rng = Rng(u64::from(v).wrapping_mul(0x2545_F491_4F6C_DD1D) ^ 0x5EED);
        let (mut x, mut f) = (x0, f0);
        for _ in 0..REPEATS {
            let start = f;
            let mut step = START * scale;
            for _ in 0..ROUNDS {
                for _ in 0..SAMPLES {
                    let d = DVec3::new(rng.normal(), rng.normal(), rng.normal()) * step;
                    let y = mover.place(w, x, x + d);
                    if let Some((y, fy)) = y.and_then(|y| Some((y, self.evaluate(w, y, f, bound, max_hi, below, under0)?))) {
                        if fy > f {
                            (x, f) = (y, fy);
                        }
                    }
                }
                step *= 0.5;
            }
            if f >= below || !(f - start > REPEAT_GAIN) {
                break;
            }
        }
        if !(f > f0 + MIN_GAIN) {
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

    /// A 2×2×2 Kuhn cube with its centre pushed near a face: the star's least merit, its
    /// count under `below`, and the work.
    fn pushed(to: DVec3) -> (crate::mesh::TetMesh, Work<'static>, u32) {
        let mut m = kuhn_cube(2, 0.0, 1);
        let centre = m.vertices.iter().position(|p| (*p - DVec3::splat(0.5)).length() < 1e-12).unwrap() as u32;
        m.vertices[centre as usize] = to;
        assert_eq!(m.validate(), Ok(()));
        let w = Work::build(&m, Targets::new(30.0, 158.0)).unwrap();
        (m, w, centre)
    }

    fn star_figures(w: &mut Work, v: u32, below: f64) -> (f64, usize, f64) {
        let mut star = Vec::new();
        assert!(w.star(v, &mut star));
        let m = star.iter().map(|&t| merit(&w.judged[t as usize])).fold(f64::INFINITY, f64::min);
        let n = star.iter().filter(|&&t| merit(&w.judged[t as usize]) < below).count();
        let re = star.iter().map(|&t| w.judged[t as usize].re).fold(0.0, f64::max);
        (m, n, re)
    }

    #[test]
    fn a_vertex_pushed_near_a_face_is_searched_back_and_the_same_way_each_time() {
        let (m, mut w, v) = pushed(DVec3::new(0.5, 0.52, 0.04));
        let (m0, n0, _) = star_figures(&mut w, v, 10.0);
        assert!(m0 < 5.0, "{m0}");
        let mut s = Searcher::default();
        assert!(s.try_search(&mut w, v, 2.0, 10.0));
        let (m1, n1, _) = star_figures(&mut w, v, 10.0);
        assert!(m1 > m0 + 5.0, "{m0} -> {m1}");
        assert!(n1 <= n0);
        let mut out = m.clone();
        let x = w.pts[v as usize];
        w.write_back(&mut out);
        assert_eq!(out.validate(), Ok(()));
        assert!((out.volume() - m.volume()).abs() < 1e-14);
        // the samples depend on the vertex alone
        let (_, mut w2, _) = pushed(DVec3::new(0.5, 0.52, 0.04));
        assert!(Searcher::default().try_search(&mut w2, v, 2.0, 10.0));
        assert_eq!(w2.pts[v as usize], x);
    }

    #[test]
    fn a_search_keeps_the_radius_edge_bound_and_the_count_under_the_bound() {
        // from the cube's centre all 24 tets of the star are Kuhn tets, under a bound of 60°:
        // a move must raise their least merit without passing their radius-edge ratio
        let (_, mut w, v) = pushed(DVec3::splat(0.5));
        let (m0, n0, re0) = star_figures(&mut w, v, 60.0);
        assert_eq!(n0, 24);
        let moved = Searcher::default().try_search(&mut w, v, 0.0, 60.0);
        let (m1, n1, re1) = star_figures(&mut w, v, 60.0);
        assert!(!moved || (m1 > m0 && n1 <= n0 && re1 <= re0), "{m0} {n0} {re0} -> {m1} {n1} {re1}");
        // pushed near a face with a tight radius-edge bound: whatever moves stays within it
        let (_, mut w, v) = pushed(DVec3::new(0.5, 0.52, 0.04));
        let (_, _, re0) = star_figures(&mut w, v, 10.0);
        let bound = 1.5;
        assert!(re0 > bound);
        let moved = Searcher::default().try_search(&mut w, v, bound, 10.0);
        let (_, _, re1) = star_figures(&mut w, v, 10.0);
        assert!(!moved || re1 <= re0.max(bound), "{re0} -> {re1}");
        // a fixed vertex (a cube corner) never moves
        let (_, mut w, _) = pushed(DVec3::splat(0.5));
        assert!(!Searcher::default().try_search(&mut w, 0, 2.0, 10.0));
    }
}
