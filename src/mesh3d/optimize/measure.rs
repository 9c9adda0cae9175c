//! The quality score the optimiser maximises, and its gradient with respect to one vertex.
//!
//! A tet's *score* combines its smallest and largest dihedral angles, each normalised by its
//! target, and its radius-edge ratio `R / l_min` normalised by its bound `ρ`:
//! `min(θ_min / θ_target_min, (180° − θ_max) / (180° − θ_target_max), ρ l_min / R)`. A tet meets
//! all targets exactly when its score is at least 1; the score is 0 for a flat tet. The three
//! measures are computed bitwise as the judge (`shared/tools/cgal_ref/tet_quality.h`) computes
//! them, so the optimiser's idea of a bad tet is the judge's: the interior dihedral angle at an
//! edge is `180° − acos(n̂_k · n̂_l)` with `n_k`, `n_l` the outward normals of the two faces at
//! the edge. Smoothing follows the gradients of the angle terms (from normals computed here,
//! equal to the judge's up to rounding) and, where the radius-edge term is among the least,
//! its gradient by central differences: a tet bad only for a short edge at a free vertex is
//! mended by moving that vertex away.
//!
//! The score is only ever evaluated on tets already known to be positively oriented (decided
//! exactly with [`orient3d`](crate::core::predicates::orient3d) by the caller); it is a
//! floating-point heuristic that ranks candidates, never a decision on validity.
//!
//! Gradients (used by smoothing) are of one dihedral angle with respect to one vertex. For the
//! angle `θ` at edge `(p, q)` between the faces `F_r = (p, q, r)` and `F_s = (p, q, s)`, with
//! `N_r` the outward (unnormalised) normal of `F_r` and `e = q − p`:
//! - `∂θ/∂r = |e| N_r / |N_r|²` (moving `r` out of the tet opens the angle by the step over the
//!   height of `r` above the edge, `|N_r| / |e|`);
//! - `∂θ/∂q = −(t_r ∂θ/∂r + t_s ∂θ/∂s)` with `t_x = (x − p)·e / |e|²`, which follows from the
//!   invariance of `θ` under translations and rotations and from `∂θ/∂q ⊥ e`; `p` likewise with
//!   the roles of `p` and `q` exchanged.

use crate::core::array_map::{map4, map6};
use crate::mesh::tet_mesh::TET_FACES;
use crate::quality::tetrahedron::{TET_EDGES, dihedrals_of_extreme_cosines, tet_extreme_dihedral_cosines, tet_min_max_dihedral_radius_edge, tet_radius_edge};
use glam::DVec3;

/// The faces at each edge of [`TET_EDGES`]: the faces opposite the edge's two other vertices.
pub(crate) const EDGE_FACES: [[usize; 2]; 6] = [[2, 3], [1, 3], [1, 2], [0, 3], [0, 2], [0, 1]];

const DEG: f64 = 180.0 / std::f64::consts::PI;

/// A flip that replaces a tet with a dihedral angle under this many degrees (a sliver the
/// report warns about, or a flat tet) may make tets above the radius-edge bound: any positive
/// tet is better than it.
pub(crate) const SLIVER_DEG: f64 = 1.0;

/// The radius-edge ratio that new tets of a flip may reach, given the old tets' corners: the
/// bound or the old tets' largest ratio, and no limit where an old tet is under
/// [`SLIVER_DEG`].
pub(crate) fn flip_radius_edge_bound(old: impl IntoIterator<Item = [DVec3; 4]>, max_re: f64) -> f64 {
    let mut bound = max_re;
    for p in old {
        let (lo, _, re) = tet_min_max_dihedral_radius_edge(&p);
        if !(lo >= SLIVER_DEG) {
            return f64::INFINITY;
        }
        bound = bound.max(re);
    }
    bound
}

/// The two dihedral targets, as the reciprocals the score multiplies by, and the radius-edge
/// bound.
#[derive(Copy, Clone, Debug, PartialEq)]
pub(crate) struct Targets {
    /// `1 / θ_target_min` (degrees⁻¹).
    pub inv_min: f64,
    /// `1 / (180° − θ_target_max)` (degrees⁻¹).
    pub inv_max: f64,
    /// The radius-edge bound `ρ` (`+∞`: none); the score's third term is `ρ / (R / l_min)`.
    pub max_re: f64,
    /// `θ_target_min` (degrees).
    pub min_deg: f64,
    /// `180° − θ_target_max` (degrees).
    pub max_gap: f64,
    /// A largest angle above this (degrees) scores 0, so that no change makes one (180°: none).
    pub hi_cap: f64,
}

impl Targets {
    /// Targets for a smallest angle `min_deg` and a largest angle `max_deg` (degrees), both
    /// clamped into `(0°, 180°)`.
    pub(crate) fn new(min_deg: f64, max_deg: f64) -> Targets {
        let lo = if min_deg.is_finite() { min_deg.clamp(1e-3, 179.0) } else { 15.0 };
        let hi = if max_deg.is_finite() { max_deg.clamp(1.0, 180.0 - 1e-3) } else { 160.0 };
        Targets { inv_min: 1.0 / lo, inv_max: 1.0 / (180.0 - hi), max_re: f64::INFINITY, min_deg: lo, max_gap: 180.0 - hi, hi_cap: 180.0 }
    }

    /// The same targets with largest angles above `deg` scoring 0.
    pub(crate) fn with_hi_cap(mut self, deg: f64) -> Targets {
        self.hi_cap = deg;
        self
    }

    /// The same targets with the radius-edge bound `ratio` (ignored unless positive).
    pub(crate) fn with_radius_edge(mut self, ratio: f64) -> Targets {
        if ratio > 0.0 {
            self.max_re = ratio;
        }
        self
    }
}

/// Outward normals (unnormalised) of a positively oriented tet: face `k` opposite vertex `k`.
#[inline]
pub(crate) fn normals(p: &[DVec3; 4]) -> [DVec3; 4] {
    map4(TET_FACES, |[a, b, c]| (p[b] - p[a]).cross(p[c] - p[a]))
}

/// The cosines `n̂_k · n̂_l` at the six edges ([`TET_EDGES`] order); the dihedral angle is
/// `180° − acos(c)`, so the smallest angle has the smallest cosine. `None` if a face is
/// degenerate in floating point.
#[inline]
pub(crate) fn cosines(n: &[DVec3; 4]) -> Option<[f64; 6]> {
    let l2 = map4(*n, |v| v.length_squared());
    if l2.iter().any(|&x| x.is_nan() || x <= 0.0 || !x.is_finite()) {
        return None;
    }
    let inv = map4(l2, |x| 1.0 / x.sqrt());
    Some(map6(EDGE_FACES, |[k, l]| (n[k].dot(n[l]) * inv[k] * inv[l]).clamp(-1.0, 1.0)))
}

/// The dihedral angle in degrees from the cosine of the outward normals.
#[inline]
pub(crate) fn angle(c: f64) -> f64 {
    180.0 - c.acos() * DEG
}

/// A tet's judged measures: smallest and largest dihedral angle (degrees) and radius-edge
/// ratio, bitwise the judge's ([`tet_min_max_dihedral_radius_edge`]).
#[derive(Copy, Clone, Debug, Default, PartialEq)]
pub(crate) struct Judged {
    /// Smallest dihedral angle.
    pub lo: f64,
    /// Largest dihedral angle.
    pub hi: f64,
    /// Radius-edge ratio.
    pub re: f64,
}

impl Judged {
    /// The measures of the tet `p`.
    #[inline]
    pub(crate) fn of(p: &[DVec3; 4]) -> Judged {
        let (lo, hi, re) = tet_min_max_dihedral_radius_edge(p);
        Judged { lo, hi, re }
    }

    /// The score (see the module documentation): at least 1 when all targets are met, 0 for a
    /// tet degenerate in floating point.
    #[inline]
    pub(crate) fn score(&self, tg: &Targets) -> f64 {
        if self.hi > tg.hi_cap {
            return 0.0;
        }
        // divisions, so that a measure meeting its target exactly scores at least 1
        let s = (self.lo / tg.min_deg).min((180.0 - self.hi) / tg.max_gap).max(0.0);
        if tg.max_re.is_finite() { s.min(tg.max_re / self.re) } else { s }
    }

    /// Componentwise extremes: least `lo`, largest `hi` and `re`.
    #[inline]
    pub(crate) fn worst(self, o: Judged) -> Judged {
        Judged { lo: self.lo.min(o.lo), hi: self.hi.max(o.hi), re: self.re.max(o.re) }
    }
}

/// The score of a positively oriented tet: [`Judged::score`] of its [`Judged`] measures.
#[cfg(test)]
#[inline]
pub(crate) fn score(p: &[DVec3; 4], tg: &Targets) -> f64 {
    Judged::of(p).score(tg)
}

/// A margin on cosines that covers the rounding of every angle computed from them (under
/// 1e-15 in the cosine), so that a test on a cosine against a threshold decides as the test on
/// the angle would, or abstains.
const COSINE_MARGIN: f64 = 1e-9;

/// The cosine at which [`angle`] (and the judge's dihedral angle) equals `deg`, or `±∞` when
/// `deg` is outside `(0°, 180°)`: `-∞` at or below 0°, `+∞` at or above 180°.
fn cosine_of_angle(deg: f64) -> f64 {
    if !(deg > 0.0) {
        f64::NEG_INFINITY
    } else if !(deg < 180.0) {
        f64::INFINITY
    } else {
        (180.0 - deg).to_radians().cos()
    }
}

impl Targets {
    /// Cosines past which a tet surely scores at most `beat`: its least cosine under the first,
    /// or its largest over the second (margins included; `±∞` where no cosine decides).
    pub(crate) fn failing_cosines(&self, beat: f64) -> (f64, f64) {
        let lo = cosine_of_angle(beat * self.min_deg) - COSINE_MARGIN;
        let hi = cosine_of_angle(180.0 - beat * self.max_gap) + COSINE_MARGIN;
        (lo, hi)
    }

    /// Cosines between which neither angle term of an edge falls under `limit` (margins
    /// included): an edge whose cosine lies strictly between them has both terms at or above
    /// it. [`terms_below`] takes them.
    pub(crate) fn quiet_cosines(&self, limit: f64) -> (f64, f64) {
        let small = cosine_of_angle(limit * self.min_deg) + COSINE_MARGIN;
        let large = cosine_of_angle(180.0 - limit * self.max_gap) - COSINE_MARGIN;
        (small, large)
    }
}

/// The least [`score`] over a set of positively oriented tets, folded tet by tet with no arc
/// cosine per tet: the score is non-decreasing in each tet's least cosine and non-increasing
/// in its largest, so the least score is bitwise that of the least and the largest cosine over
/// the set, and of the least radius-edge term.
#[derive(Copy, Clone, Debug)]
pub(crate) struct LeastScore {
    lo_c: f64,
    hi_c: f64,
    re_term: f64,
    tets: usize,
    flat: bool,
}

impl LeastScore {
    pub(crate) fn new() -> LeastScore {
        LeastScore { lo_c: f64::INFINITY, hi_c: f64::NEG_INFINITY, re_term: f64::INFINITY, tets: 0, flat: false }
    }

    /// Adds the tet `p`; returns its extreme cosines (`None` if it is degenerate: score 0).
    #[inline]
    pub(crate) fn add(&mut self, p: &[DVec3; 4], tg: &Targets) -> Option<(f64, f64)> {
        self.tets += 1;
        let Some((lo, hi)) = tet_extreme_dihedral_cosines(p) else {
            self.flat = true;
            return None;
        };
        self.lo_c = self.lo_c.min(lo);
        self.hi_c = self.hi_c.max(hi);
        if tg.max_re.is_finite() {
            self.re_term = self.re_term.min(tg.max_re / tet_radius_edge(p));
        }
        Some((lo, hi))
    }

    /// The least radius-edge term so far (`+∞` without a radius-edge bound).
    pub(crate) fn re_term(&self) -> f64 {
        self.re_term
    }

    /// The least score of the tets added: bitwise the least [`score`] of them; `+∞` for none.
    pub(crate) fn value(&self, tg: &Targets) -> f64 {
        if self.tets == 0 {
            return f64::INFINITY;
        }
        if self.flat {
            return 0.0;
        }
        // as Judged::score, with the extremes over the set
        let (lo, hi) = dihedrals_of_extreme_cosines(self.lo_c, self.hi_c);
        if hi > tg.hi_cap {
            return 0.0;
        }
        let s = (lo / tg.min_deg).min((180.0 - hi) / tg.max_gap).max(0.0);
        if tg.max_re.is_finite() { s.min(self.re_term) } else { s }
    }
}

/// One term of a tet's score: the normalised small-angle or large-angle measure of one edge,
/// with its gradient with respect to the moving vertex.
#[derive(Copy, Clone, Debug)]
pub(crate) struct Term {
    /// The value (the tet's score is the least of its terms).
    pub value: f64,
    /// Its gradient with respect to the moving vertex (score units per length).
    pub grad: DVec3,
}

/// Calls `f` with every term of the tet `p` below `limit` and its gradient with respect to
/// vertex `m`: each edge gives `θ / θ_target_min` and `(180° − θ) / (180° − θ_target_max)`;
/// the radius-edge term comes only below `re_limit` (its gradient costs six evaluations).
/// Nothing for a tet degenerate in floating point. `quiet` is [`Targets::quiet_cosines`] of
/// `limit`: the edges whose cosines lie between them are skipped without an arc cosine.
pub(crate) fn terms_below(p: &[DVec3; 4], m: usize, tg: &Targets, limit: f64, quiet: (f64, f64), re_limit: f64, mut f: impl FnMut(Term)) {
    let n = normals(p);
    let Some(c) = cosines(&n) else { return };
    // most edges are far from the targets: their cosines tell, without an arc cosine
    let (quiet_lo, quiet_hi) = quiet;
    for (e, &ce) in c.iter().enumerate() {
        if ce > quiet_lo && ce < quiet_hi {
            continue;
        }
        let th = angle(ce);
        let small = th * tg.inv_min;
        let large = (180.0 - th) * tg.inv_max;
        if small >= limit && large >= limit {
            continue;
        }
        let g = angle_gradient(p, &n, e, m) * DEG;
        if small < limit {
            f(Term { value: small, grad: g * tg.inv_min });
        }
        if large < limit {
            f(Term { value: large, grad: -g * tg.inv_max });
        }
    }
    if tg.max_re.is_finite() {
        let re = tet_radius_edge(p);
        let value = tg.max_re / re;
        if value < re_limit && re.is_finite() {
            f(Term { value, grad: radius_edge_term_gradient(p, m, tg.max_re) });
        }
    }
}

/// The gradient of the radius-edge term `ρ / (R / l_min)` with respect to vertex `m`, by
/// central differences (the term is only active on the few tets near the bound, and the
/// shortest edge switching makes it piecewise anyway).
fn radius_edge_term_gradient(p: &[DVec3; 4], m: usize, max_re: f64) -> DVec3 {
    let scale = TET_EDGES.iter().map(|&[i, j]| p[i].distance(p[j])).fold(0.0, f64::max);
    let h = 1e-7 * scale;
    if h <= 0.0 || !h.is_finite() {
        return DVec3::ZERO;
    }
    let mut g = DVec3::ZERO;
    for axis in 0..3 {
        let (mut a, mut b) = (*p, *p);
        a[m][axis] += h;
        b[m][axis] -= h;
        let (ra, rb) = (tet_radius_edge(&a), tet_radius_edge(&b));
        if !(ra.is_finite() && rb.is_finite()) {
            return DVec3::ZERO;
        }
        g[axis] = (max_re / ra - max_re / rb) / (2.0 * h);
    }
    g
}

/// The gradient (radians per length) of the dihedral angle at edge `e` ([`TET_EDGES`] order)
/// with respect to the position of vertex `m`, given the outward normals `n`.
pub(crate) fn angle_gradient(p: &[DVec3; 4], n: &[DVec3; 4], e: usize, m: usize) -> DVec3 {
    let [i, j] = TET_EDGES[e];
    let [fk, fl] = EDGE_FACES[e];
    // the face opposite vertex `fl` contains vertex `fk`, and vice versa
    let edge = p[j] - p[i];
    let len = edge.length();
    let g_of = |face: usize| {
        let nn = n[face].length_squared();
        if nn > 0.0 { n[face] * (len / nn) } else { DVec3::ZERO }
    };
    let gk = g_of(fl);
    let gl = g_of(fk);
    if m == fk {
        return gk;
    }
    if m == fl {
        return gl;
    }
    let l2 = edge.length_squared();
    if l2 == 0.0 {
        return DVec3::ZERO;
    }
    // m is an endpoint; w the other one
    let w = if m == i { j } else { i };
    let axis = p[m] - p[w];
    let tk = (p[fk] - p[w]).dot(axis) / l2;
    let tl = (p[fl] - p[w]).dot(axis) / l2;
    -(gk * tk + gl * tl)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::quality::tetrahedron::{tet_dihedral_angles, tet_min_max_dihedral, tet_radius_edge};

    fn tet() -> [DVec3; 4] {
        [DVec3::new(0.1, -0.2, 0.05), DVec3::new(1.2, 0.1, -0.1), DVec3::new(0.3, 0.9, 0.2), DVec3::new(0.4, 0.35, 1.1)]
    }

    #[test]
    fn angles_match_the_judge() {
        let p = tet();
        let c = cosines(&normals(&p)).unwrap();
        let a = tet_dihedral_angles(&p).unwrap();
        for e in 0..6 {
            assert!((angle(c[e]) - a[e]).abs() < 1e-12, "edge {e}: {} vs {}", angle(c[e]), a[e]);
        }
        let tg = Targets::new(15.0, 160.0);
        let (lo, hi) = tet_min_max_dihedral(&p);
        let s = score(&p, &tg);
        assert!((s - (lo / 15.0).min((180.0 - hi) / 20.0)).abs() < 1e-12);
        let tg = tg.with_radius_edge(0.5);
        assert_eq!(score(&p, &tg), 0.5 / tet_radius_edge(&p));
    }

    #[test]
    fn judged_measures_are_bitwise_the_judges() {
        let mut state = 12345u64;
        let mut rnd = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for i in 0..20000 {
            let mut p = [0; 4].map(|_| DVec3::new(rnd(), rnd(), rnd()));
            if i % 3 == 0 {
                // slivers and needles
                p[3] = (p[0] + p[1] + p[2]) / 3.0 + DVec3::new(rnd(), rnd(), rnd()) * 1e-6;
            }
            let j = Judged::of(&p);
            assert_eq!((j.lo, j.hi), tet_min_max_dihedral(&p), "{p:?}");
            assert_eq!(j.re.to_bits(), tet_radius_edge(&p).to_bits(), "{p:?}");
        }
    }

    #[test]
    fn gradients_match_finite_differences() {
        let p = tet();
        let n = normals(&p);
        for e in 0..6 {
            for m in 0..4 {
                let g = angle_gradient(&p, &n, e, m);
                for axis in 0..3 {
                    let h = 1e-6;
                    let mut a = p;
                    let mut b = p;
                    a[m][axis] += h;
                    b[m][axis] -= h;
                    let fa = tet_dihedral_angles(&a).unwrap()[e].to_radians();
                    let fb = tet_dihedral_angles(&b).unwrap()[e].to_radians();
                    let fd = (fa - fb) / (2.0 * h);
                    assert!(
                        (fd - g[axis]).abs() < 1e-5 * (1.0 + fd.abs()),
                        "edge {e} vertex {m} axis {axis}: {fd} vs {}",
                        g[axis]
                    );
                }
            }
        }
    }

    #[test]
    fn least_score_is_bitwise_the_least_of_the_scores() {
        let mut rng = crate::core::spatial_order::XorShift::new(7);
        let mut rnd = move || (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        for (k, tg) in [Targets::new(18.0, 158.0).with_radius_edge(2.0), Targets::new(15.0, 160.0)].into_iter().cycle().take(4000).enumerate() {
            let mut least = LeastScore::new();
            let mut plain = f64::INFINITY;
            for i in 0..(1 + k % 9) {
                let mut p = [0; 4].map(|_| DVec3::new(rnd(), rnd(), rnd()));
                if (i + k) % 4 == 0 {
                    // slivers, needles and flat tets
                    p[3] = (p[0] + p[1] + p[2]) / 3.0 + DVec3::new(rnd(), rnd(), rnd()) * if k % 8 == 0 { 0.0 } else { 1e-6 };
                }
                least.add(&p, &tg);
                plain = plain.min(score(&p, &tg));
            }
            assert_eq!(least.value(&tg).to_bits(), plain.to_bits(), "set {k}");
        }
        assert_eq!(LeastScore::new().value(&Targets::new(18.0, 158.0)), f64::INFINITY);
    }

    #[test]
    fn cosine_thresholds_never_decide_wrongly() {
        // a tet past the failing cosines scores at most `beat`; an edge between the quiet
        // cosines has both angle terms at or above `limit`
        let mut rng = crate::core::spatial_order::XorShift::new(11);
        let mut rnd = move || (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        let tg = Targets::new(18.0, 158.0);
        for k in 0..20000 {
            let mut p = [0; 4].map(|_| DVec3::new(rnd(), rnd(), rnd()));
            if k % 3 == 0 {
                p[3] = (p[0] + p[1] + p[2]) / 3.0 + DVec3::new(rnd(), rnd(), rnd()) * 1e-3;
            }
            let beat = 2.0 * rnd();
            let (fail_lo, fail_hi) = tg.failing_cosines(beat);
            if let Some((lo, hi)) = tet_extreme_dihedral_cosines(&p) {
                if lo < fail_lo || hi > fail_hi {
                    assert!(score(&p, &tg) <= beat, "{p:?} {beat}");
                }
            }
            let limit = 2.0 * rnd();
            let (q_lo, q_hi) = tg.quiet_cosines(limit);
            if let Some(c) = cosines(&normals(&p)) {
                for ce in c {
                    if ce > q_lo && ce < q_hi {
                        let th = angle(ce);
                        assert!(th * tg.inv_min >= limit && (180.0 - th) * tg.inv_max >= limit, "{ce} {limit}");
                    }
                }
            }
        }
    }

    #[test]
    fn flat_tets_score_zero() {
        let p = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 0.0)];
        assert_eq!(score(&p, &Targets::new(15.0, 160.0)), 0.0);
    }
}
