//! The last phase of the optimiser, around the worst tets ([`Focus`]): its rounds, the search
//! by samples after them, and when a round is worth repeating ([`Under`]).

use super::Optimizer;
use crate::mesh3d::optimize::measure::Targets;
use crate::quality::worst_tet::touches_angle_below;

/// A last phase around the worst tets: where the passes leave tets under
/// [`Focus::below_deg`], the tets with a vertex within [`FOCUS_RINGS`] rings of them are worked
/// on toward a smallest angle of [`Focus::target_deg`], the largest-angle and radius-edge
/// targets as before. No largest angle may grow past the mesh's own (or past the target, where
/// the mesh is within it). Its attempts: [`FOCUS_TRIES`] per tet of the region under the
/// phase's target, and never more than [`FOCUS_SHARE`] of the attempts made before it.
///
/// At the usual target the passes stop improving a tet once it meets it, so the tets around a
/// bad one settle at the target and leave it no room; a higher target moves them further.
/// Only the region around the worst tets is worked on, so a mesh without tets under
/// `below_deg` is untouched and the cost stays with the few that have them. Like every change
/// here, it never lowers the least score of the tets it replaces (judged against the phase's
/// targets). A second round, with as many attempts again (counted in
/// [`OptimizeReport::focus_dihedral_attempts`]), works around the tets still under
/// `below_deg` against the dihedral targets alone, with changes allowed radius-edge ratios up
/// to [`FOCUS_RADIUS_EDGE`] times the bound (`Optimizer::focus`). Last, each movable vertex
/// of the tets still under `below_deg` is moved where samples around it find its star better
/// (`search.rs`, at most [`SEARCH_VERTICES`] vertices, each once a time; counted in
/// [`OptimizeReport::searched_vertices`] and [`OptimizeReport::search_moves`]); the second
/// round and the search run again, up to [`FOCUS_SEARCH_ROUNDS`] times in all, while tets under
/// `below_deg` are left and the last round and search made progress: fewer of them, or the
/// worst of them at least [`FOCUS_ROUND_GAIN_DEG`] better, or, of those the input does not
/// explain (that touch none of the input angles given to [`optimize_explained`]), fewer or
/// the worst better. A repeat costs as much as the round before it, and where nothing moved,
/// or only an explained tet at a small input angle crept up, another finds about what the
/// last did.
///
/// [`OptimizeReport::focus_dihedral_attempts`]: super::OptimizeReport::focus_dihedral_attempts
/// [`OptimizeReport::searched_vertices`]: super::OptimizeReport::searched_vertices
/// [`OptimizeReport::search_moves`]: super::OptimizeReport::search_moves
/// [`optimize_explained`]: super::optimize_explained
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Focus {
    /// Tets under this smallest dihedral angle (degrees) start the phase.
    pub below_deg: f64,
    /// The smallest-angle target of the phase (degrees).
    pub target_deg: f64,
}

/// How many times the second round of [`Focus`] and the search after it run at most while
/// they make progress. On the three batches of real parts in docs/benchmarks.md (parts whose
/// every tet under 10° touches an input angle as small): once 116 of 126, twice 118, three
/// times 119, four 119, six 120; no largest angle rose past 162.52° where it was under it.
/// On the later batches (94 parts): six 85, twelve 86, twenty 88, thirty-two 88 (a sliver
/// face's corner on `chrismorley498_Part2` took sixteen rounds to lift its last tet over 10°,
/// `T-Lind_Part1` eight); the rule stops most runs long before the cap, and at TetGen's tet
/// counts no corpus part reaches six.
pub const FOCUS_SEARCH_ROUNDS: usize = 32;

/// The least rise of the worst tet under [`Focus::below_deg`] (degrees) for which a round of
/// [`Focus`] and its search count as progress where they left as many tets under it and
/// those the input does not explain no better (see [`Focus`]). On `t20_data.step` at TetGen's
/// tet count the worst tet, an explained one at a 2.5° corner, rose by 0.006° a round while
/// each round cost a twentieth of the run.
pub const FOCUS_ROUND_GAIN_DEG: f64 = 0.1;

/// The most vertices the search after the focus phase's rounds works on (`search.rs`): a
/// budget that bounds its work on a part with thousands of tets under the bound near small
/// input angles (at most 8,000 samples a vertex).
pub const SEARCH_VERTICES: usize = 20_000;

/// The rings of tets (sharing a vertex) around the worst tets that [`Focus`] works on.
pub const FOCUS_RINGS: usize = 2;

/// Attempts [`Focus`] may spend, per tet of its region under the phase's target when it starts.
pub const FOCUS_TRIES: usize = 4;

/// The most attempts [`Focus`] may spend, as a share of those made before it.
pub const FOCUS_SHARE: f64 = 0.1;

/// In the second round of [`Focus`], changes may make radius-edge ratios up to this many
/// times [`OptimizeOptions::max_radius_edge`] (or the worst of the tets they replace): a tet
/// of good dihedral angles but a high ratio (a needle) is sound for a solver, a sliver is
/// not (no small dihedral angle, so no ill-conditioned stiffness, and no large one, so no
/// gradient error). On the three batches of real parts in docs/benchmarks.md, 3 took the parts
/// whose every tet under 10° touches an input angle as small from 109 to 115 of 126; 1 (the
/// usual rule) brought none of the eight failing parts it was tried on within that count. On
/// the later 94 parts, with the rounds up to [`FOCUS_SEARCH_ROUNDS`]: 3 and 4 gave 88, 6 gave
/// 90 and 8 gave 91 (the tips of 1.3–2.7° face corners on `alliums_base`,
/// `FormaRobotics_link1` and `dg-shadow_gimbal_test`, where every tet beside the thin
/// boundary triangles is a needle). On the 151 corpus and sweep files, 8 instead of 3
/// changes 4 meshes, each for the better: `part.step` at its default size 7.29° → 10.00° and
/// `t20_data` 4.98° → 10.19° (neither with a tet under 10° left), `nist_ftc_08` 0.33° → 0.60°
/// with 832 tets under 10° instead of 1,377, `bm2_ec_leverrod-A` 37 → 32 of them; the largest
/// radius-edge ratio rose from 12.5 to 28 on `part.step`, its largest dihedral angle from
/// 169.1° to 170.3°.
///
/// [`OptimizeOptions::max_radius_edge`]: super::OptimizeOptions::max_radius_edge
pub const FOCUS_RADIUS_EDGE: f64 = 8.0;

impl Optimizer<'_> {
    /// The phase of [`Focus`]: the region around the tets under `f.below_deg`, worked on
    /// toward `f.target_deg`, then the targets restored. Two rounds, each with its own
    /// attempts (see [`Focus`]), the second followed by the search and run again while tets
    /// under the bound are left, up to [`FOCUS_SEARCH_ROUNDS`] times:
    /// 1. against the phase's targets with the radius-edge term in the score;
    /// 2. around the tets still under `f.below_deg`, against the dihedral targets alone, each
    ///    change allowed radius-edge ratios up to [`FOCUS_RADIUS_EDGE`] times the bound (or
    ///    the worst it replaces). Next to a thin boundary triangle (a small corner of a CAD
    ///    face, a tangent fillet's edge) every tet has a radius-edge ratio above the bound, so
    ///    the first round's least score is that term and no move of the free vertex raises
    ///    it; the dihedral angles then stay where they are although moving it lifts them.
    pub(super) fn focus(&mut self, f: Focus) {
        if f.target_deg <= self.opts.min_dihedral_deg {
            return;
        }
        let Some(region) = self.focus_region(&self.tets_under(f.below_deg)) else {
            return;
        };
        // no largest angle may pass the mesh's, or the target where the mesh is within it
        let cap = self.w.worst().hi.max(self.opts.max_dihedral_deg);
        let tg = self.w.tg;
        let dihedral = Targets::new(f.target_deg, self.opts.max_dihedral_deg).with_hi_cap(cap);
        self.w.retarget(dihedral.with_radius_edge(self.opts.max_radius_edge));
        self.region = Some(region);
        self.ins.wedges = true;
        let share = (FOCUS_SHARE * self.report.attempts as f64) as usize;
        let out_of_attempts = self.report.out_of_attempts;
        self.report.focus_attempts = self.focus_round(share);
        // the second round and the search, again while tets under the bound are left (the
        // vertices the search moved open flips and moves that failed before), each round
        // within its own share
        self.w.retarget(dihedral);
        self.max_re = FOCUS_RADIUS_EDGE * self.opts.max_radius_edge;
        // the tets under the bound, found once a round for the progress rule and the region
        let mut seeds = self.tets_under(f.below_deg);
        let mut last = self.under(&seeds);
        for round in 0..FOCUS_SEARCH_ROUNDS {
            if round > 0 {
                seeds = self.tets_under(f.below_deg);
                let now = self.under(&seeds);
                if !now.progress_since(&last) {
                    break;
                }
                last = now;
            }
            self.region = self.focus_region(&seeds);
            if self.region.is_none() {
                break;
            }
            self.report.focus_rounds += 1;
            let made = self.focus_round(share);
            if round == 0 {
                self.report.focus_dihedral_attempts = made;
            } else {
                self.report.focus_repeat_attempts += made;
            }
            self.search_below(f.below_deg);
        }
        self.max_re = self.opts.max_radius_edge;
        self.report.out_of_attempts = out_of_attempts;
        self.region = None;
        self.ins.wedges = false;
        self.w.retarget(tg);
    }

    /// One round of [`Optimizer::focus`] on its region against the current targets, within
    /// [`FOCUS_TRIES`] attempts per tet under them and at most `share`; the attempts made.
    fn focus_round(&mut self, share: usize) -> usize {
        let start = self.report.attempts;
        let limit = start.saturating_add(FOCUS_TRIES.saturating_mul(self.bad_tets().len()).min(share));
        // insertion and smoothing failed on some tets against the old targets: they may
        // succeed now
        self.insert_failed.clear();
        self.sm.forget_failures();
        self.passes_below(1.0, limit);
        self.report.attempts - start
    }

    /// The search of `search.rs` on each movable vertex of the tets under `below` degrees,
    /// worst tet first, each vertex once, at most [`SEARCH_VERTICES`] vertices.
    fn search_below(&mut self, below: f64) {
        let mut bad: Vec<(f64, u32)> = self.tets_under(below).into_iter().map(|t| (self.w.judged[t as usize].lo, t)).collect();
        bad.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let mut tried = rustc_hash::FxHashSet::default();
        for (_, t) in bad {
            if !self.w.alive(t) || !(self.w.judged[t as usize].lo < below) {
                continue;
            }
            for v in self.w.tets[t as usize] {
                if tried.len() >= SEARCH_VERTICES || !self.w.movable(v) || !tried.insert(v) {
                    continue;
                }
                self.report.searched_vertices += 1;
                if self.search.try_search(&mut self.w, v, self.max_re, below) {
                    self.report.search_moves += 1;
                    self.report.smoothing_moves += 1;
                    self.report.boundary_moves += usize::from(self.w.fixed[v as usize]);
                    self.report.curved_boundary_moves += usize::from(self.w.slide[v as usize].is_some_and(|s| s.curved()));
                }
            }
        }
    }

    /// The live tets under `below` degrees, by slot.
    fn tets_under(&self, below: f64) -> Vec<u32> {
        self.w.live_slots().filter(|&t| self.w.judged[t as usize].lo < below).collect()
    }

    /// Of the tets `under` the bound ([`Optimizer::tets_under`]), all of them and those that
    /// touch none of the input's angles (asked for the first time there are some).
    fn under(&mut self, under: &[u32]) -> Under {
        let mut out = Under { all: (0, f64::INFINITY), unexplained: (0, f64::INFINITY) };
        if under.is_empty() {
            return out;
        }
        let angles = self.input_angles.get_or_insert_with(self.angles);
        for &t in under {
            let lo = self.w.judged[t as usize].lo;
            out.all = (out.all.0 + 1, out.all.1.min(lo));
            if !touches_angle_below(&self.w.tets[t as usize].map(|v| self.w.pts[v as usize]), angles, f64::INFINITY) {
                out.unexplained = (out.unexplained.0 + 1, out.unexplained.1.min(lo));
            }
        }
        out
    }

    /// The vertices within [`FOCUS_RINGS`] rings of the tets `seeds` (those under the bound),
    /// `None` where there are none.
    fn focus_region(&self, seeds: &[u32]) -> Option<Vec<bool>> {
        if seeds.is_empty() {
            return None;
        }
        let mut region = vec![false; self.w.pts.len()];
        for &t in seeds {
            for v in self.w.tets[t as usize] {
                region[v as usize] = true;
            }
        }
        // each ring: every vertex of a tet that has one in the region
        for _ in 0..FOCUS_RINGS {
            let before = region.clone();
            for t in self.w.live_slots() {
                let tet = self.w.tets[t as usize];
                if tet.iter().any(|&v| before[v as usize]) {
                    for v in tet {
                        region[v as usize] = true;
                    }
                }
            }
        }
        Some(region)
    }
}

/// The tets under [`Focus::below_deg`] between the rounds of [`Focus`]: how many, and the
/// smallest dihedral angle among them (infinite where there are none), of all and of those
/// the input does not explain.
#[derive(Copy, Clone, Debug)]
struct Under {
    all: (usize, f64),
    unexplained: (usize, f64),
}

impl Under {
    /// Whether another round is worth its cost after `last`: tets under the bound are left,
    /// and the last round and search made fewer of them or raised the worst by at least
    /// [`FOCUS_ROUND_GAIN_DEG`], or made fewer of those the input does not explain or raised
    /// the worst of them at all.
    fn progress_since(&self, last: &Under) -> bool {
        let (n, lo) = self.all;
        let (u, ulo) = self.unexplained;
        n > 0 && (n < last.all.0 || lo >= last.all.1 + FOCUS_ROUND_GAIN_DEG || (u > 0 && (u < last.unexplained.0 || ulo > last.unexplained.1)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_focus_round_counts_as_progress_by_the_tets_under_the_bound() {
        let at = |all: (usize, f64), unexplained: (usize, f64)| Under { all, unexplained };
        let last = at((5, 3.0), (2, 6.0));
        // none left: nothing to do
        assert!(!at((0, f64::INFINITY), (0, f64::INFINITY)).progress_since(&last));
        // fewer tets under the bound, or the worst raised by FOCUS_ROUND_GAIN_DEG
        assert!(at((4, 3.0), (2, 6.0)).progress_since(&last));
        assert!(at((5, 3.0 + FOCUS_ROUND_GAIN_DEG), (2, 6.0)).progress_since(&last));
        // an explained worst tet creeping up is not
        assert!(!at((5, 3.0 + FOCUS_ROUND_GAIN_DEG / 2.0), (2, 6.0)).progress_since(&last));
        assert!(!at((6, 3.05), (2, 6.0)).progress_since(&last));
        // of the unexplained ones, fewer or the worst better at all
        assert!(at((5, 3.0), (1, 6.0)).progress_since(&last));
        assert!(at((5, 3.0), (2, 6.001)).progress_since(&last));
        assert!(!at((5, 3.0), (2, 6.0)).progress_since(&last));
        // all of them explained now: only the first rule
        assert!(!at((5, 3.0), (0, f64::INFINITY)).progress_since(&last));
    }
}
