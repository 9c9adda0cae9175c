//! Tetrahedral mesh optimisation: raises the smallest dihedral angles and lowers the largest of
//! a valid tet mesh, however it was built, while keeping its boundary exactly.
//!
//! Stage: layer 4 (mesh3d), the last step of volume meshing. Input: a [`TetMesh`] that passes
//! [`TetMesh::validate`]. Output: the same mesh improved in place, and an [`OptimizeReport`].
//!
//! # What is kept
//! - Every tet positively oriented: each local change is checked with the exact
//!   [`orient3d`](crate::core::predicates::orient3d) before it is made.
//! - The boundary: *constrained* faces (hull faces, the mesh's `boundary` triangles and every
//!   face between tets of different regions) are never removed, and their vertices never move,
//!   but with [`OptimizeOptions::slide_boundary`] where the boundary keeps its shape: in the
//!   plane of a flat surface (one face tag, one pair of regions) and along a straight crease
//!   between two flat surfaces (`slide.rs`), and, given the geometry the boundary approximates
//!   ([`optimize_explained`]'s [`BoundaryGeometry`]), on a curved CAD face and along a curved
//!   CAD edge, put back onto it after each move. `boundary` and `face_tags` are left untouched
//!   and stay faces of the mesh; every tagged face keeps its area, or on curved faces the
//!   area its chords have on the CAD face.
//! - Region tags: changes only replace tets of one region by tets of the same region.
//! - The vertices: existing vertices keep their indices; vertices on no constrained face may
//!   move. Vertex insertion (optional, [`OptimizeOptions::insert`]) appends new vertices at the
//!   end of `vertices`, strictly inside one region; no vertex is removed.
//! - The volume: every change replaces a set of tets by another filling the same polyhedron,
//!   so the volume changes by rounding only.
//!
//! # Method
//! After Klingner and Shewchuk ("Aggressive tetrahedral mesh improvement", 2007), with a
//! score per tet that is at least 1 when both dihedral targets and the radius-edge bound are met
//! (`min(θ_min / θ_target_min, (180° − θ_max) / (180° − θ_target_max), ρ / (R / l_min))`; the
//! three measures are bitwise those of [`crate::quality`], so a tet the optimiser counts as good
//! is good by the quality judge too). Passes go over the tets below target, worst first (ties by
//! slot), and for each try, keeping the first that raises the least score of the tets it
//! changes:
//! 1. edge removal for each of its six edges (3-2 and 4-4 flips and their generalisation to
//!    rings of up to 12 tets, best ring triangulation by dynamic programming);
//! 2. the 2-3 flip of each of its four faces;
//! 3. smoothing of each of its free vertices (non-smooth steepest ascent of the star's least
//!    score), and of its sliding boundary vertices within their plane or line, or on their
//!    CAD face or edge;
//! 4. vertex insertion at its circumcentre or centroid, with the new vertex smoothed.
//!
//! No change makes a tet's radius-edge ratio exceed [`OptimizeOptions::max_radius_edge`] unless
//! one of the tets it replaces already did by more (in the second round of [`Focus`], around
//! the tets left under its bound: [`FOCUS_RADIUS_EDGE`] times it). After the first pass, a bad
//! tet is tried again only if a tet at one of its vertices changed since it last failed (its
//! flips and the smoothing of its vertices depend only on those tets), and a vertex is smoothed
//! again only if a tet at it changed.
//! Insertion is allowed once a pass changes nothing, or from the third pass on; then every bad
//! tet is tried once more. Insertion is tried at most once on a tet (the same four vertices).
//! Passes stop when one changes nothing, after [`OptimizeOptions::max_passes`], or when
//! [`OptimizeOptions::max_attempts`] bad tets have been worked on (a budget counted in
//! operations, never in time); then a quarter more of it goes to the tets under half the
//! targets, with insertion, so that the worst are not left where the budget ran out.
//! Last, where every tet meets both dihedral targets, a *polish* works on the tets within
//! [`OptimizeOptions::polish`] (1 %) above the smallest-angle target as if the target were that
//! much higher, a few attempts each: the smallest angle is not left a hair above the target,
//! and it cannot fall (see `Optimizer::polish`).
//! Where tets are left under a bound ([`Focus`]), the tets around them are worked on once more,
//! and last the position of each movable vertex of the tets still under it is searched by
//! deterministic random samples (`search.rs`): no tet of its star ends worse than the star's
//! least before, no more of them under the bound.
//!
//! The defaults aim a little above the usual acceptance figures (smallest dihedral angle 16°,
//! largest 158°, radius-edge 2), so that tets that cannot reach the targets usually still clear
//! 12.9° and 160°.
//!
//! The result is deterministic for a given input and options, bit for bit, whatever the thread
//! count and the machine's load: the work is serial, only the adjacency, the initial scores
//! and, on large meshes, the scan for bad tets use threads and they do not depend on the thread
//! count, and every budget is a count. Clocks are read for [`OptimizeReport::seconds`] only.
//!
//! Adjacency (face neighbours, from face records bucketed by their smallest vertex) is built on
//! entry and dropped on exit; scratch buffers are reused, so the hot loops do not allocate per
//! tet. The work is proportional to the bad tets after that linear set-up.

mod edge_removal;
mod face_removal;
mod focus;
mod insert;
mod measure;
mod search;
mod slide;
mod smooth;
mod star;
mod vertex_slide;
mod work;

#[cfg(test)]
mod tests;

use crate::core::{BoundaryGeometry, FaceId};
use crate::mesh::{MeshError, TetMesh};
use crate::quality::input_angles::InputAngle;
use crate::quality::tetrahedron::TET_EDGES;
use edge_removal::EdgeRemoval;
pub use focus::{FOCUS_RADIUS_EDGE, FOCUS_RINGS, FOCUS_ROUND_GAIN_DEG, FOCUS_SEARCH_ROUNDS, FOCUS_SHARE, FOCUS_TRIES, Focus, SEARCH_VERTICES};
use face_removal::try_flip23;
use insert::Inserter;
use measure::{Targets, cosines, normals};
use search::Searcher;
use serde::Serialize;
use smooth::Smoother;
use std::time::Instant;
use work::Work;
pub(crate) use work::Adjacency;
#[cfg(test)]
pub(crate) use work::adjacency;

/// Vertex insertion joins the other operations once a pass changes nothing, or from this pass
/// on (counted from 0). Measured on the corpus STEP solids with boundary sliding: insertion
/// only after a pass without change never came on some parts (every pass slid a vertex) and
/// left `Angled.step` at 5.99° and 317 tets under 5° on `occt-sphere.step`; from the third pass
/// 13.9° and 34; from the first pass the tets under 5° summed over the corpus rose again
/// (379 against 278), insertion taking the place of cheaper flips.
const INSERT_FROM_PASS: usize = 2;

/// The score under which a tet gets the extra attempts once the budget has run out (half
/// the targets: 9° for a target of 18°), and insertion for it may reach twice the
/// radius-edge bound.
const RESCUE_BELOW: f64 = 0.5;

/// When the passes run out before the work converges, the tets under this score (12.6° or
/// 164.6° for targets of 18° and 158°) get more passes, with insertion, within the budget.
pub(crate) const LAST_PASSES_BELOW: f64 = 0.7;

/// The default [`OptimizeOptions::polish`]: a mesh that reaches 18° is worked on toward
/// 18.18°, so that its smallest angle is not left a hair above the target (featuretype.STL
/// ended at 18.0003°, TetGen's `-q` at 18.0005°).
pub const POLISH_MARGIN: f64 = 0.01;

/// Attempts the polish may spend, per tet under the raised target when it starts.
const POLISH_TRIES: usize = 4;

/// Up to this many tets the bad-tet scan is serial; beyond, it runs in chunks in parallel
/// ([`chunked_reduce`](crate::quality::summary::chunked_reduce)). It runs before every pass
/// and is bound by memory: on two cores the parallel scan (waking the pool, joining the
/// pieces) took twice the serial one's time on `part.step` at 97,000 tets (18 ms against 8 ms
/// over 27 calls) and half as much again on `t20_data.step` at 250,000 (82 ms against 50 ms
/// over 51 calls).
const GATHER_SERIAL: usize = 1 << 18;

/// The slots whose score in `q` is under 1 and that `keep`, with their scores, worst first
/// (ties by slot): serial up to `serial` slots, in chunks in parallel beyond. The order is
/// total, so the list is the same either way and for any thread count.
fn gather_bad(q: &[f64], keep: impl Fn(usize) -> bool + Sync, serial: usize) -> Vec<(f64, u32)> {
    let bad_in = |start: usize, end: usize| -> Vec<(f64, u32)> {
        let slots = q[start..end].iter().enumerate().map(|(i, &q)| (start + i, q));
        slots.filter(|&(t, q)| q < 1.0 && keep(t)).map(|(t, q)| (q, t as u32)).collect()
    };
    let mut bad = if q.len() <= serial {
        bad_in(0, q.len())
    } else {
        crate::quality::summary::chunked_reduce(q.len(), Vec::new(), bad_in, |all, part| all.extend(part))
    };
    bad.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    bad
}

/// Options of [`optimize`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct OptimizeOptions {
    /// Target smallest dihedral angle (degrees): tets below it are worked on.
    pub min_dihedral_deg: f64,
    /// Target largest dihedral angle (degrees): tets above it are worked on.
    pub max_dihedral_deg: f64,
    /// Radius-edge bound: no change creates a tet above it, unless a tet it replaces was
    /// already worse.
    pub max_radius_edge: f64,
    /// The most passes over the bad tets.
    pub max_passes: usize,
    /// The most attempts over all passes, an attempt being the work on one bad tet (its edge
    /// removals, face flips, smoothing and insertion tried in turn); `None`: no limit. A count,
    /// so a budget that runs out still gives the same result on any machine. When it runs out,
    /// a quarter more goes to the tets under half the targets.
    pub max_attempts: Option<usize>,
    /// Allow smoothing of free vertices.
    pub smooth: bool,
    /// Allow inserting vertices (appended to `vertices`, strictly inside a region).
    pub insert: bool,
    /// Let boundary vertices slide where that leaves the boundary as it is: in the plane of a
    /// flat surface (one face tag, one pair of regions) and along a straight crease between
    /// two flat surfaces. Off by default: then no vertex of a constrained face moves.
    pub slide_boundary: bool,
    /// With [`OptimizeOptions::slide_boundary`]: boundary triangles with these tags keep their
    /// vertices where they are.
    pub pinned_faces: Vec<FaceId>,
    /// Once every tet meets the targets, the tets within this share above the smallest-angle
    /// target are worked on as if it were that much higher (see `POLISH_TRIES`); `0`: off.
    pub polish: f64,
    /// Where tets under `below` degrees are left, the tets around them are worked on once more
    /// toward a smallest angle of `target` degrees ([`Focus`]); `None`: off.
    pub focus: Option<Focus>,
}

impl Default for OptimizeOptions {
    fn default() -> Self {
        OptimizeOptions {
            min_dihedral_deg: 16.0,
            max_dihedral_deg: 158.0,
            max_radius_edge: 2.0,
            max_passes: 8,
            max_attempts: None,
            smooth: true,
            insert: true,
            slide_boundary: false,
            pinned_faces: Vec::new(),
            polish: POLISH_MARGIN,
            focus: None,
        }
    }
}

impl OptimizeOptions {
    /// Sets [`OptimizeOptions::min_dihedral_deg`].
    pub fn with_min_dihedral(mut self, deg: f64) -> Self {
        self.min_dihedral_deg = deg;
        self
    }

    /// Sets [`OptimizeOptions::max_dihedral_deg`].
    pub fn with_max_dihedral(mut self, deg: f64) -> Self {
        self.max_dihedral_deg = deg;
        self
    }

    /// Sets [`OptimizeOptions::max_radius_edge`].
    pub fn with_max_radius_edge(mut self, ratio: f64) -> Self {
        self.max_radius_edge = ratio;
        self
    }

    /// Sets [`OptimizeOptions::max_passes`].
    pub fn with_max_passes(mut self, passes: usize) -> Self {
        self.max_passes = passes;
        self
    }

    /// Sets [`OptimizeOptions::max_attempts`].
    pub fn with_max_attempts(mut self, attempts: Option<usize>) -> Self {
        self.max_attempts = attempts;
        self
    }

    /// Sets [`OptimizeOptions::smooth`].
    pub fn with_smoothing(mut self, smooth: bool) -> Self {
        self.smooth = smooth;
        self
    }

    /// Sets [`OptimizeOptions::slide_boundary`].
    pub fn with_boundary_sliding(mut self, slide: bool) -> Self {
        self.slide_boundary = slide;
        self
    }

    /// Sets [`OptimizeOptions::pinned_faces`].
    pub fn with_pinned_faces(mut self, faces: Vec<FaceId>) -> Self {
        self.pinned_faces = faces;
        self
    }

    /// Sets [`OptimizeOptions::polish`].
    pub fn with_polish(mut self, share: f64) -> Self {
        self.polish = share;
        self
    }

    /// Sets [`OptimizeOptions::focus`].
    pub fn with_focus(mut self, focus: Option<Focus>) -> Self {
        self.focus = focus;
        self
    }

    /// Sets [`OptimizeOptions::insert`].
    pub fn with_insertion(mut self, insert: bool) -> Self {
        self.insert = insert;
        self
    }
}

/// What [`optimize`] did.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct OptimizeReport {
    /// Tets before.
    pub tets_before: usize,
    /// Tets after.
    pub tets_after: usize,
    /// Smallest dihedral angle before (degrees, the judge's definition).
    pub min_dihedral_before: f64,
    /// Largest dihedral angle before (degrees).
    pub max_dihedral_before: f64,
    /// Smallest dihedral angle after (degrees).
    pub min_dihedral_after: f64,
    /// Largest dihedral angle after (degrees).
    pub max_dihedral_after: f64,
    /// Largest radius-edge ratio before.
    pub max_radius_edge_before: f64,
    /// Largest radius-edge ratio after.
    pub max_radius_edge_after: f64,
    /// Tets missing a target before.
    pub bad_before: usize,
    /// Tets missing a target after.
    pub bad_after: usize,
    /// 2-3 flips.
    pub flips23: usize,
    /// 3-2 flips (edge removal with three tets around the edge).
    pub flips32: usize,
    /// 4-4 flips (edge removal with four tets around the edge).
    pub flips44: usize,
    /// Edge removals with five or more tets around the edge.
    pub edge_removals: usize,
    /// Vertex moves by smoothing.
    pub smoothing_moves: usize,
    /// Of those, moves of boundary vertices within their plane or along their straight edge,
    /// or on their CAD face or edge ([`OptimizeOptions::slide_boundary`]).
    pub boundary_moves: usize,
    /// Of those, moves on a curved CAD face or along a curved CAD edge (with the geometry).
    pub curved_boundary_moves: usize,
    /// Vertices inserted (appended to `vertices`).
    pub insertions: usize,
    /// Bad tets on which insertion was tried (kept or undone).
    pub insertion_attempts: usize,
    /// Passes made.
    pub passes: usize,
    /// Attempts made (bad tets worked on, over all passes).
    pub attempts: usize,
    /// Of those, attempts of the polish ([`OptimizeOptions::polish`]).
    pub polish_attempts: usize,
    /// Of those, attempts of the phase around the worst tets ([`OptimizeOptions::focus`]).
    pub focus_attempts: usize,
    /// Of those, attempts of the phase's second round, against the dihedral targets alone
    /// (its own share of the attempts made before the phase).
    pub focus_dihedral_attempts: usize,
    /// Of those, attempts of the second round's repeats after the search
    /// ([`FOCUS_SEARCH_ROUNDS`]), each within its own share.
    pub focus_repeat_attempts: usize,
    /// Rounds of the phase's second kind run, its first included (at most
    /// [`FOCUS_SEARCH_ROUNDS`]; see [`Focus`] for when it stops sooner).
    pub focus_rounds: usize,
    /// Vertices of the tets left under the focus phase's bound whose position was searched
    /// by samples after its rounds (`search.rs`).
    pub searched_vertices: usize,
    /// Of those, the vertices moved.
    pub search_moves: usize,
    /// True if [`OptimizeOptions::max_attempts`] stopped the work.
    pub out_of_attempts: bool,
    /// Wall-clock seconds, adjacency and summaries included.
    pub seconds: f64,
    /// Of which: checking the input, building the adjacency and scoring every tet.
    pub setup_seconds: f64,
}

/// Why [`optimize`] refused a mesh.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum OptimizeError {
    /// The input mesh is invalid (what [`TetMesh::validate`] would report).
    #[error("cannot optimise an invalid mesh: {0}")]
    InvalidMesh(#[from] MeshError),
    /// The mesh has more tets than the optimiser's adjacency can address.
    #[error("the mesh has {tets} tetrahedra; the optimiser handles at most {max}")]
    TooLarge {
        /// Tets in the mesh.
        tets: usize,
        /// The most the optimiser handles.
        max: usize,
    },
}

/// The optimiser's state and scratch.
struct Optimizer<'a> {
    w: Work<'a>,
    opts: &'a OptimizeOptions,
    er: EdgeRemoval,
    sm: Smoother,
    search: Searcher,
    ins: Inserter,
    report: OptimizeReport,
    /// Per tet slot, the [`Work::clock`] when [`Optimizer::improve`] last failed on it.
    failed: Vec<u32>,
    /// The tets (sorted vertices) on which insertion failed: it is not tried on them again.
    insert_failed: rustc_hash::FxHashSet<[u32; 4]>,
    /// During [`Optimizer::focus`]: the vertices of its region (vertices inserted since are in
    /// it); only tets with a vertex in it are worked on.
    region: Option<Vec<bool>>,
    /// The radius-edge bound of every change ([`OptimizeOptions::max_radius_edge`];
    /// [`FOCUS_RADIUS_EDGE`] times it in the focus phase's second round).
    max_re: f64,
    /// Gives the input's small angles ([`optimize_explained`]), called at most once.
    angles: &'a dyn Fn() -> Vec<InputAngle>,
    /// What [`Optimizer::angles`] gave, once asked.
    input_angles: Option<Vec<InputAngle>>,
}

impl Optimizer<'_> {
    /// The edges of live tet `t`, worst dihedral angle first (by its score term).
    fn edges_worst_first(&self, t: u32) -> [usize; 6] {
        let p = self.w.corners(&self.w.tets[t as usize]);
        let mut order = [0, 1, 2, 3, 4, 5];
        if let Some(c) = cosines(&normals(&p)) {
            let tg = &self.w.tg;
            let bad = |e: usize| {
                let th = measure::angle(c[e]);
                (th * tg.inv_min).min((180.0 - th) * tg.inv_max)
            };
            let key = [0, 1, 2, 3, 4, 5].map(bad);
            order.sort_by(|&a, &b| key[a].total_cmp(&key[b]));
        }
        order
    }

    /// Works on the bad live tet `t`; true if anything changed.
    fn improve(&mut self, t: u32, allow_insert: bool) -> bool {
        let max_re = self.max_re;
        let tet = self.w.tets[t as usize];
        for e in self.edges_worst_first(t) {
            let [i, j] = TET_EDGES[e];
            if let Some(n) = self.er.try_remove(&mut self.w, t, tet[i], tet[j], max_re) {
                match n {
                    3 => self.report.flips32 += 1,
                    4 => self.report.flips44 += 1,
                    _ => self.report.edge_removals += 1,
                }
                return true;
            }
        }
        for k in 0..4 {
            if try_flip23(&mut self.w, t, k, max_re) {
                self.report.flips23 += 1;
                return true;
            }
        }
        let mut changed = false;
        if self.opts.smooth {
            for v in tet {
                if self.sm.try_smooth(&mut self.w, v, max_re) {
                    self.report.smoothing_moves += 1;
                    self.report.boundary_moves += usize::from(self.w.fixed[v as usize]);
                    self.report.curved_boundary_moves += usize::from(self.w.slide[v as usize].is_some_and(|s| s.curved()));
                    changed = true;
                    if self.w.q[t as usize] >= 1.0 {
                        return true;
                    }
                }
            }
        }
        // insertion is tried once per tet (its four vertices): a second try in a later pass
        // kept or undid a vertex in 4% of attempts on fandisk.obj and took half the
        // optimiser's time there
        let key = {
            let mut k = tet;
            k.sort_unstable();
            k
        };
        if !changed && allow_insert && !self.insert_failed.contains(&key) && {
            self.report.insertion_attempts += 1;
            let ok = self.ins.try_insert(&mut self.w, &mut self.sm, t, max_re);
            if !ok {
                self.insert_failed.insert(key);
            }
            ok
        } {
            self.report.insertions += 1;
            return true;
        }
        changed
    }

    /// The live tets below target, worst first (ties by slot): serial up to [`GATHER_SERIAL`]
    /// tets, in chunks in parallel beyond ([`gather_bad`]).
    fn bad_tets(&self) -> Vec<(f64, u32)> {
        let (w, region) = (&self.w, self.region.as_deref());
        // in the region being worked on (everywhere but during `Optimizer::focus`)
        let in_region = |t: usize| region.is_none_or(|r| w.tets[t].iter().any(|&v| r.get(v as usize).copied().unwrap_or(true)));
        gather_bad(&w.q, |t| w.alive(t as u32) && in_region(t), GATHER_SERIAL)
    }

    /// One pass over the bad tets `bad` (worst first), up to `limit` attempts in all; true if
    /// anything changed. Sets `out_of_attempts` when the limit stops it.
    fn pass(&mut self, bad: &[(f64, u32)], try_all: bool, insert_now: bool, limit: usize) -> bool {
        self.report.passes += 1;
        if self.failed.len() < self.w.tets.len() {
            self.failed.resize(self.w.tets.len(), 0);
        }
        let mut changed = false;
        for &(_, t) in bad {
            if !self.w.alive(t) || self.w.q[t as usize] >= 1.0 {
                continue;
            }
            if !try_all && !self.w.touched_after(t, self.failed[t as usize]) {
                continue;
            }
            if self.report.attempts >= limit {
                self.report.out_of_attempts = true;
                break;
            }
            self.report.attempts += 1;
            if self.improve(t, insert_now) {
                changed = true;
            } else {
                self.failed[t as usize] = self.w.clock;
            }
        }
        changed
    }

    fn run(&mut self) {
        let max_attempts = self.opts.max_attempts.unwrap_or(usize::MAX);
        let mut insert_now = false;
        // every bad tet is tried in the first pass and when insertion is first allowed; later,
        // only those that are new or had a tet at a vertex change since they last failed
        let mut try_all = true;
        let mut converged = false;
        for pass in 0..self.opts.max_passes {
            if !insert_now && self.opts.insert && pass >= INSERT_FROM_PASS {
                // passes that each still change something (sliding boundary vertices keep
                // moving) must not keep insertion out until the passes run out
                insert_now = true;
                try_all = true;
            }
            let bad = self.bad_tets();
            if bad.is_empty() || self.report.out_of_attempts {
                converged = bad.is_empty();
                break;
            }
            let changed = self.pass(&bad, try_all, insert_now, max_attempts);
            try_all = false;
            if !changed {
                if insert_now || !self.opts.insert {
                    converged = true;
                    break;
                }
                insert_now = true;
                try_all = true;
            }
        }
        // the worst tets are not left where the passes stopped: when the budget ran out on the
        // many tets a little under target, a quarter more of it goes to the few far under
        // (score under RESCUE_BELOW); when the passes ran out while small changes went on
        // (sliding vertices), the rest of it goes to the tets under LAST_PASSES_BELOW (those
        // that fail the usual acceptance figures); with insertion either way
        let rescue = if self.report.out_of_attempts {
            Some((max_attempts + max_attempts / 4, RESCUE_BELOW))
        } else if !converged {
            Some((max_attempts, LAST_PASSES_BELOW))
        } else {
            None
        };
        if let Some((limit, below)) = rescue.filter(|_| max_attempts != usize::MAX) {
            self.passes_below(below, limit);
        }
        if self.opts.polish > 0.0 {
            self.polish();
        }
        if let Some(f) = self.opts.focus {
            self.focus(f);
        }
    }
}

impl Optimizer<'_> {
    /// Passes with insertion over the tets scoring under `below`, every one tried in the
    /// first, until one changes nothing, the passes run out or `limit` attempts are made.
    fn passes_below(&mut self, below: f64, limit: usize) {
        let mut try_all = true;
        for _ in 0..self.opts.max_passes {
            let bad: Vec<(f64, u32)> = self.bad_tets().into_iter().filter(|&(q, _)| q < below).collect();
            if bad.is_empty() || self.report.attempts >= limit {
                break;
            }
            let changed = self.pass(&bad, try_all, self.opts.insert, limit);
            try_all = false;
            if !changed {
                break;
            }
        }
    }

    /// With every tet at both dihedral targets, raises the smallest-angle target by
    /// [`OptimizeOptions::polish`] and works on the tets under it, up to [`POLISH_TRIES`]
    /// attempts each, then restores the targets.
    ///
    /// It cannot lower the mesh's smallest dihedral angle. Its score leaves out the
    /// radius-edge term (the bound still holds as a rule of every change), so at the start
    /// the least score over the mesh is the smallest angle over the raised target, every other
    /// term being at least 1. Every change raises the least score of the tets it replaces, so
    /// the least over the mesh never falls, and with it the smallest angle. A largest angle
    /// may pass its target by at most `(180° − target) · (1 − least score)` (0.2° from 158°
    /// at 18.0003° of 18.18°).
    fn polish(&mut self) {
        let tg = self.w.tg;
        let worst = self.w.worst();
        if !(worst.lo >= self.opts.min_dihedral_deg && worst.hi <= self.opts.max_dihedral_deg) {
            return;
        }
        let raised = Targets::new(self.opts.min_dihedral_deg * (1.0 + self.opts.polish), self.opts.max_dihedral_deg);
        self.w.retarget(raised);
        let start = self.report.attempts;
        let limit = start.saturating_add(POLISH_TRIES.saturating_mul(self.bad_tets().len()));
        let out_of_attempts = self.report.out_of_attempts;
        self.passes_below(1.0, limit);
        // the polish's own limit is not the budget running out
        self.report.out_of_attempts = out_of_attempts;
        self.report.polish_attempts = self.report.attempts - start;
        self.w.retarget(tg);
    }

}

/// Improves `mesh` in place: see the [module documentation](self) for what is kept and how.
///
/// # Errors
/// [`OptimizeError::InvalidMesh`] if the mesh fails the checks of [`TetMesh::validate`] (the
/// mesh is then left as it was), [`OptimizeError::TooLarge`] beyond 2³⁰ − 1 tets.
pub fn optimize(mesh: &mut TetMesh, opts: &OptimizeOptions) -> Result<OptimizeReport, OptimizeError> {
    optimize_explained(mesh, opts, &Vec::new, None)
}

/// [`optimize`], told where the input explains a tet: `angles` gives the input's angles under
/// [`Focus::below_deg`]
/// (`small_input_angles` of the surface
/// meshed). A tet that touches one
/// (`touches_angle_below`) is explained by
/// the input, and does not keep [`Focus`]'s repeats going on its own. `angles` is called at
/// most once, and only where the focus phase leaves tets under its bound. `geometry`, where
/// the boundary approximates one (a B-rep whose face ids are the boundary's tags), lets
/// [`OptimizeOptions::slide_boundary`] slide vertices on curved faces and edges too.
///
/// # Errors
/// As [`optimize`].
pub fn optimize_explained(
    mesh: &mut TetMesh,
    opts: &OptimizeOptions,
    angles: &dyn Fn() -> Vec<InputAngle>,
    geometry: Option<&dyn BoundaryGeometry>,
) -> Result<OptimizeReport, OptimizeError> {
    optimize_explained_with(mesh, opts, angles, geometry, None)
}

/// [`optimize_explained`], given the mesh's adjacency where the caller has it
/// ([`Work::build_with`]).
pub(crate) fn optimize_explained_with(
    mesh: &mut TetMesh,
    opts: &OptimizeOptions,
    angles: &dyn Fn() -> Vec<InputAngle>,
    geometry: Option<&dyn BoundaryGeometry>,
    adjacency: Option<Adjacency>,
) -> Result<OptimizeReport, OptimizeError> {
    let start = Instant::now();
    if mesh.tets.len() > work::MAX_TETS {
        return Err(OptimizeError::TooLarge { tets: mesh.tets.len(), max: work::MAX_TETS });
    }
    let tg = Targets::new(opts.min_dihedral_deg, opts.max_dihedral_deg).with_radius_edge(opts.max_radius_edge);
    let mut w = Work::build_with(mesh, tg, adjacency)?;
    if opts.slide_boundary && opts.smooth {
        (w.slide, w.fans) = slide::slides(mesh, &w, &opts.pinned_faces, geometry);
        w.geo = geometry;
    }
    let setup_seconds = start.elapsed().as_secs_f64();
    let before = w.worst();
    let bad_before = w.q.iter().filter(|&&q| q < 1.0).count();
    let report = OptimizeReport {
        tets_before: mesh.tets.len(),
        min_dihedral_before: before.lo,
        max_dihedral_before: before.hi,
        max_radius_edge_before: before.re,
        bad_before,
        setup_seconds,
        ..Default::default()
    };
    let nv = mesh.vertices.len();
    let mut o = Optimizer {
        w,
        opts,
        er: EdgeRemoval::default(),
        sm: Smoother::default(),
        search: Searcher::default(),
        ins: Inserter::default(),
        report,
        failed: Vec::new(),
        insert_failed: rustc_hash::FxHashSet::default(),
        region: None,
        max_re: opts.max_radius_edge,
        angles,
        input_angles: None,
    };
    o.run();
    let mut report = o.report;
    report.bad_after = o.w.live_slots().filter(|&t| o.w.q[t as usize] < 1.0).count();
    let after = o.w.worst();
    o.w.write_back(mesh);
    debug_assert_eq!(mesh.vertices.len(), nv + report.insertions);
    report.tets_after = mesh.tets.len();
    report.min_dihedral_after = after.lo;
    report.max_dihedral_after = after.hi;
    report.max_radius_edge_after = after.re;
    report.seconds = start.elapsed().as_secs_f64();
    Ok(report)
}
