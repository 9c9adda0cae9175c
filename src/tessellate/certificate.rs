//! The certificate of a tessellation: what is checked, and what was found.
//!
//! Input: the B-rep [`Model`] and its [`Tessellation`]. Output: a [`Certificate`] whose
//! `passed` is true when every check holds; each failure names the B-rep face (`FaceId` and
//! STEP `#id`) or edge it is about. Nothing here panics on a bad tessellation.
//!
//! # Checks
//! - **Every solid closes** (`open_solid`): a shell that should close (a `CLOSED_SHELL`, or
//!   the shell of a `MANIFOLD_SOLID_BREP`) whose B-rep still has free edges after sewing is a
//!   failure, one per hole, naming the solid, its shell, the free edges and where they are
//!   ([`Certificate::open_solids`]). Such a shell counts as closed below, so its open
//!   triangles fail `closed` as well.
//! - **Every face meshed** (none in [`Tessellation::failed`]).
//! - **Closed, manifold, oriented** ([`crate::mesh::topology`]), for every *shell group*
//!   whose B-rep is closed. A shell group is a set of faces joined by shared edges: one B-rep
//!   shell, or several sewn together. An open group (a surface model left open) must instead
//!   have exactly the mesh edges of its free B-rep edges open.
//! - **Outward**: each closed group encloses positive volume (negative for a void).
//! - **No self-intersection** (exact, [`intersecting_pairs`]): between two triangles of the
//!   same solid (or the same group of a surface model). Triangles of different solids that
//!   touch or overlap (assemblies, solids sharing a wall) are counted as
//!   [`Certificate::solid_contacts`], not as failures: the B-rep itself has them.
//! - **Euler characteristic per group** equals the B-rep's own, counted the way the mesh sees
//!   the B-rep: `V − E + Σ_f χ_f` with `V` every vertex of the group's edges and vertex loops
//!   (poles and apexes included; a vertex where sheets of the surface touch, a pinch whose
//!   link falls in pieces, once per piece, as the triangles' fans there are), `E` every edge that is not degenerate (seams included: the
//!   mesh has vertices and edges along them, shared by the face's two sides), and
//!   `χ_f = 2 − 2 g_f − L_f` for each face with `L_f` loops (edge and vertex loops; a face is a
//!   sphere with `L_f` holes cut along its seams) and `g_f = 1` only for a face on a surface
//!   periodic in both directions without any edge loop (a whole torus). Genus `(2 − χ) / 2`.
//!   (A doubly periodic face with holes but no seam and no loop around the surface would be
//!   counted as genus 0: it fails the check rather than pass wrongly; none is in the corpus.)
//! - **Boundary loops per face**: the triangles of one face form a patch whose open edges
//!   make as many loops as the face has trim-loop pieces once seams are glued and degenerate
//!   edges shrunk to points: each loop's coedges without its seam and degenerate coedges fall
//!   into runs, one patch boundary loop each (a cylinder cut by its seam: one trim loop, two
//!   patch loops; a whole sphere: none).
//! - **Volume and area against the B-rep's own values** (`super::quadrature`), with
//!   tolerances made of the deviation each face *reached*, `δ_f`, measured
//!   (`super::reached`), not of the chord asked for. Every point of the mesh is within
//!   about `δ_f` of face `f`, so the enclosed volumes differ by at most the band
//!   `B = Σ_f A_f δ_f` over the group's faces; and a certificate says the volume is right, so
//!   the tolerance never exceeds [`VOLUME_RELATIVE`] of it:
//!
//!   ```text
//!   |V_mesh − V_brep| ≤ min(Σ_f A_f δ_f, VOLUME_RELATIVE · |V_brep|) + 1e-9 |V_brep|
//!   ```
//!
//!   (the last term for rounding). A 1 % volume error never passes, whatever deviation was
//!   asked for: a coarse one that cuts more fails, naming the solid and the face that
//!   deviates most. The area of an inscribed triangle of a surface with normal curvature `κ`
//!   falls short by a fraction of about `δκ` (from `h² κ / 8 = δ` and the normal turning by
//!   `hκ/2` over it), and its boundary chords cut off slivers at most `δ` wide; the area
//!   tolerance of a face is `A_f · max(2 δ_f κ_f, 1e-9) + P_f · δ_f` with `κ_f` the largest
//!   normal curvature sampled over the face's domain and `P_f` its boundary's length; the
//!   whole surface's is their sum.

use super::Tessellation;
use super::brep_topology::{coincident_edges, expected_patch_loops, face_euler, vertex_umbrellas};
use super::quadrature::{FaceIntegrals, SegmentIndex, face_integrals, oriented};
use super::reached::face_deviation;
use crate::cad::brep::{EntityRef, Model};
use crate::core::FaceId;
use crate::core::union_find::UnionFind;
use crate::mesh::topology::{ReportOptions, intersecting_pairs, surface_report};
use glam::{DVec2, DVec3};
use rustc_hash::FxHashMap;
use serde::Serialize;
use rayon::prelude::*;
use std::time::Instant;

/// The largest share of a closed group's volume its triangles may be off the B-rep's (the
/// acceptance of issue 14: every certified solid within 0.5 % of OpenCASCADE's volume).
pub const VOLUME_RELATIVE: f64 = 5e-3;

/// What to check.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct CertifyOptions {
    /// Run the exact self-intersection test (default `true`).
    pub self_intersections: bool,
    /// Most failures listed (default 20).
    pub max_listed: usize,
    /// The volume tolerance is at most 0.5 % of the volume (default `true`). Off, it is the
    /// band `Σ A_f δ_f` alone: the triangles as far from the B-rep as the deviation they
    /// reached allows, for a boundary meshed to a size (`fepre mesh`), whose volume against
    /// the CAD solids' the mesh summary reports, warns of and can require.
    pub volume_cap: bool,
}

impl Default for CertifyOptions {
    fn default() -> Self {
        CertifyOptions { self_intersections: true, max_listed: 20, volume_cap: true }
    }
}

impl CertifyOptions {
    /// Sets [`CertifyOptions::volume_cap`].
    pub fn with_volume_cap(mut self, on: bool) -> Self {
        self.volume_cap = on;
        self
    }

    /// Sets [`CertifyOptions::self_intersections`].
    pub fn with_self_intersections(mut self, on: bool) -> Self {
        self.self_intersections = on;
        self
    }
}

/// One failed check, with the face or edge it is about.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CheckFailure {
    /// The check (`closed`, `euler`, `boundary_loops`, `self_intersection`, ...).
    pub check: &'static str,
    /// The face, if the failure is about one.
    pub face: Option<FaceId>,
    /// Its STEP instance (`ADVANCED_FACE`), or the edge's or shell's.
    pub step_id: Option<EntityRef>,
    /// What was found.
    pub message: String,
}

/// One shell group: B-rep shells joined by shared edges (one shell unless sewn).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ShellCheck {
    /// The B-rep shells (STEP `#id`s).
    pub brep_shells: Vec<EntityRef>,
    /// Faces in the group.
    pub faces: usize,
    /// The B-rep closes (every edge used twice or as a seam), or one of its shells is a
    /// `CLOSED_SHELL` (then a face the reader dropped leaves the triangles open: a failure).
    pub brep_closed: bool,
    /// One of its shells is a `CLOSED_SHELL` or bounds a solid: it should close.
    pub declared_closed: bool,
    /// One of its shells bounds a solid (`MANIFOLD_SOLID_BREP`, `BREP_WITH_VOIDS`).
    pub solid: bool,
    /// A void of a solid (expected to enclose negative volume).
    pub void: bool,
    /// Edge-connected components of its triangles (1 when right).
    pub mesh_components: usize,
    /// Its triangles close (every edge of them used twice).
    pub mesh_closed: bool,
    /// `V − E + F` of its triangles.
    pub euler_mesh: i64,
    /// The B-rep's own Euler characteristic (see the module docs).
    pub euler_brep: i64,
    /// Genus of the mesh, when closed and the characteristic is even.
    pub genus_mesh: Option<i64>,
    /// Genus of the B-rep.
    pub genus_brep: Option<i64>,
    /// Enclosed volume of the triangles, mm³ (meaningful when closed).
    pub volume_mesh: f64,
    /// Enclosed volume of the B-rep by quadrature, mm³.
    pub volume_brep: f64,
    /// Area of the triangles, mm².
    pub area_mesh: f64,
    /// Area of the B-rep by quadrature, mm².
    pub area_brep: f64,
}

/// The certificate (see the module docs for each check).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Certificate {
    /// Every check holds.
    pub passed: bool,
    /// Every face was meshed.
    pub all_faces_meshed: bool,
    /// Every group whose B-rep closes is closed; open groups are open exactly along their
    /// free edges.
    pub closed: bool,
    /// Edge- and vertex-manifold.
    pub manifold: bool,
    /// Consistently oriented.
    pub oriented: bool,
    /// Every closed group encloses positive volume (negative for a void).
    pub outward: bool,
    /// Intersecting triangle pairs within one solid (`None` when not tested).
    pub self_intersections: Option<usize>,
    /// Intersecting or touching triangle pairs of different solids (not a failure).
    pub solid_contacts: usize,
    /// Euler characteristic of every group equals the B-rep's.
    pub euler_matches: bool,
    /// Every face's patch has as many boundary loops as expected.
    pub boundary_loops_match: bool,
    /// Volume within tolerance of the B-rep's, for every closed group.
    pub volume_matches: bool,
    /// Area within tolerance of the B-rep's, for every face.
    pub area_matches: bool,
    /// The model-wide chord tolerance asked for, mm.
    pub chord: f64,
    /// The largest deviation reached on any face, measured (`super::reached`), mm.
    pub deviation: f64,
    /// Total enclosed volume of the closed groups: triangles, B-rep, tolerance, mm³.
    pub volume: [f64; 3],
    /// Total area: triangles, B-rep, tolerance, mm².
    pub area: [f64; 3],
    /// One entry per shell group.
    pub shells: Vec<ShellCheck>,
    /// The failures (at most [`CertifyOptions::max_listed`] listed; `failure_count` counts all).
    pub failures: Vec<CheckFailure>,
    /// Number of failures.
    pub failure_count: usize,
    /// Holes (free edges grouped) of the shells that should close: each is an
    /// `open_solid` failure.
    pub open_solids: Vec<crate::cad::brep::Hole>,
    /// Closed shells the file oriented inside out (an outer shell enclosing negative volume, a
    /// void positive), turned before this certificate was made (`super::orient`).
    pub reoriented: Vec<Reoriented>,
    /// Faces whose sense disagreed with their neighbours' across most of their shared edges
    /// (STEP `#id`s), turned before this certificate was made (`super::orient`).
    pub turned_faces: Vec<EntityRef>,
    /// Time spent, seconds.
    pub seconds: f64,
}

impl Certificate {
    /// The surface is watertight where it should be: closed, manifold and oriented, and every
    /// shell group it speaks of closes. With solids in the model it speaks of the solids'
    /// groups (open surface shells beside them are reported apart); a surface model's
    /// groups otherwise.
    pub fn watertight(&self) -> bool {
        let any_solid = self.shells.iter().any(|x| x.solid);
        self.closed && self.manifold && self.oriented && self.open_solids.is_empty() && self.shells.iter().filter(|x| x.solid || !any_solid).all(|x| x.brep_closed)
    }
}

/// A shell group turned (`super::orient::turn_inside_out_shells`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Reoriented {
    /// Its B-rep shells (STEP `#id`s).
    pub brep_shells: Vec<EntityRef>,
    /// A void of a solid (it should enclose negative volume).
    pub void: bool,
    /// Its faces.
    pub faces: usize,
    /// The volume its triangles enclosed as the file oriented them, mm³.
    pub volume_as_written: f64,
}

/// Faces joined by shared (non-degenerate) edges: the group index of every face.
pub(crate) fn face_groups(model: &Model) -> (Vec<u32>, usize) {
    let n = model.faces.len();
    let mut uf = UnionFind::new(n);
    let mut first_face_of_edge: FxHashMap<u32, u32> = FxHashMap::default();
    for (f, face) in model.faces.iter().enumerate() {
        for &l in &face.loops {
            for c in &model.loops[l as usize].coedges {
                if model.edges[c.edge as usize].degenerate {
                    continue;
                }
                let g = *first_face_of_edge.entry(c.edge).or_insert(f as u32);
                uf.union(g, f as u32);
            }
        }
    }
    uf.labels()
}

/// STEP entity references as a message writes them: `#12, #40`.
fn refs(r: &[EntityRef]) -> String {
    r.iter().map(ToString::to_string).collect::<Vec<_>>().join(", ")
}

/// Boundary loops of a patch of oriented triangles: the pieces its open edges make, joined
/// where they share a vertex. A loop that passes through a vertex twice (a hole touching the
/// outer boundary at a point) is one, whichever way a walk would split it there, as
/// [`expected_patch_loops`] counts the face's trim loops.
fn patch_loops(tris: &[[u32; 3]]) -> usize {
    let mut directed: Vec<(u32, u32)> = tris.iter().flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])]).collect();
    directed.sort_unstable();
    let has = |e: (u32, u32)| directed.binary_search(&e).is_ok();
    let open: Vec<(u32, u32)> = directed.iter().copied().filter(|&(a, b)| !has((b, a))).collect();
    let mut at: Vec<u32> = open.iter().flat_map(|&(a, b)| [a, b]).collect();
    at.sort_unstable();
    at.dedup();
    let index = |v: u32| at.binary_search(&v).unwrap_or(0) as u32;
    let mut uf = UnionFind::new(at.len());
    for &(a, b) in &open {
        uf.union(index(a), index(b));
    }
    uf.labels().1
}

/// The largest normal curvature sampled over the `(u, v)` box of a face's domain.
fn face_curvature(model: &Model, f: usize, uv: &[[DVec2; 3]]) -> f64 {
    let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    for p in uv.iter().flatten() {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    if !(lo.is_finite() && hi.is_finite()) {
        return 0.0;
    }
    super::surface_scales::surface_scales(model.surface(model.faces[f].surface), lo, hi).2
}

/// Checks `t`, the tessellation of `model` (see the module docs).
pub fn certify(model: &Model, t: &Tessellation, opts: &CertifyOptions) -> Certificate {
    let t0 = Instant::now();
    let s = &t.surface;
    let delta = t.chord;
    let mut failures: Vec<CheckFailure> = Vec::new();
    let face_ref = |f: FaceId| model.try_face(f).map(|x| x.source);
    // shells that should close and do not: one failure per hole, first
    let should_close = |sh: &crate::cad::brep::Shell| sh.closed || sh.solid.is_some();
    let open_solids = model.holes(should_close);
    for h in &open_solids {
        let shell = h.shells.first().and_then(|&src| model.shells.iter().find(|s| s.source == src));
        let solid = shell.and_then(|s| s.solid).and_then(|k| model.solids.get(k as usize));
        let what = match (solid, shell) {
            (Some(so), Some(sh)) => format!(
                "solid {}{} ({} {}) does not close",
                so.source,
                so.name.as_ref().map_or(String::new(), |n| format!(" '{n}'")),
                if sh.closed { "CLOSED_SHELL" } else { "OPEN_SHELL" },
                sh.source
            ),
            (None, Some(sh)) => format!("CLOSED_SHELL {} does not close", sh.source),
            _ => "a shell that should close does not".to_string(),
        };
        let edges: Vec<String> = h.step_edges.iter().take(8).map(|e| e.to_string()).collect();
        let more = if h.step_edges.len() > 8 { " ..." } else { "" };
        failures.push(CheckFailure {
            check: "open_solid",
            face: None,
            step_id: solid.map(|so| so.source).or(shell.map(|sh| sh.source)),
            message: format!("{what}: a hole of {}; free edges {}{more}", h.describe(), edges.join(" ")),
        });
    }
    for ff in &t.failed {
        failures.push(CheckFailure { check: "face_meshed", face: Some(ff.face), step_id: Some(ff.source), message: ff.why.clone() });
    }
    let (group, ngroups) = face_groups(model);
    let group_of_face = |f: FaceId| f.index().filter(|&k| k < model.faces.len()).map(|k| group[k]);
    let centre = model.bounds().map_or(DVec3::ZERO, |(lo, hi)| 0.5 * (lo + hi));
    let index = SegmentIndex::new(&t.edges);

    // per face: mesh area, B-rep area and volume term, patch loops
    let mut area_ok = true;
    let mut loops_ok = true;
    let mut area_tol_total = 0.0;
    let mut g_area = vec![[0.0f64; 2]; ngroups];
    let mut g_volume = vec![[0.0f64; 2]; ngroups];
    // per group: the band Σ A_f δ_f, and its face deviating most (δ_f A_f, δ_f, face)
    let mut g_band = vec![0.0f64; ngroups];
    let mut g_worst: Vec<Option<(f64, f64, FaceId)>> = vec![None; ngroups];
    let mut deviation_max: f64 = 0.0;
    // the quadrature and the deviation reached, face by face on every core (the sums below
    // run in face order: the same bits for any thread count)
    let measured: Vec<Option<(FaceIntegrals, f64)>> = t
        .domains
        .par_iter()
        .enumerate()
        .map(|(f, dom)| {
            let dom = dom.as_ref()?;
            let fid = FaceId::from_index(f);
            let tris = s.triangles.get(dom.triangles.clone()).unwrap_or(&[]);
            // the volume check's where it made them for this tessellation (about the same
            // centre), else here
            let q = match t.quadrature.get(f).copied().flatten() {
                Some(q) => oriented(model, fid, q),
                None => face_integrals(model, fid, dom, &t.edges, &index, centre),
            };
            let corners: Vec<[DVec3; 3]> = tris.iter().map(|tr| tr.map(|i| s.vertices.get(i as usize).copied().unwrap_or(DVec3::NAN))).collect();
            Some((q, face_deviation(model, fid, dom, &corners, &s.vertices, &t.edges, &index)))
        })
        .collect();
    for (f, dom) in t.domains.iter().enumerate() {
        let (Some(dom), Some((q, dev))) = (dom, measured[f]) else { continue };
        let fid = FaceId::from_index(f);
        let g = group[f] as usize;
        let tris = s.triangles.get(dom.triangles.clone()).unwrap_or(&[]);
        let (mut a_mesh, mut v_mesh) = (0.0, 0.0);
        for tr in tris {
            let [a, b, c] = tr.map(|i| s.vertices.get(i as usize).copied().unwrap_or(DVec3::NAN) - centre);
            a_mesh += (b - a).cross(c - a).length() / 2.0;
            v_mesh += a.dot(b.cross(c)) / 6.0;
        }
        deviation_max = deviation_max.max(dev);
        let band = q.area.abs() * dev;
        g_band[g] += band;
        if g_worst[g].is_none_or(|(b, _, _)| band > b) {
            g_worst[g] = Some((band, dev, fid));
        }
        g_area[g][0] += a_mesh;
        g_area[g][1] += q.area;
        g_volume[g][0] += v_mesh;
        g_volume[g][1] += q.volume;
        let perimeter: f64 = dom
            .boundary
            .iter()
            .map(|([a, b], _)| match (s.vertices.get(*a as usize), s.vertices.get(*b as usize)) {
                (Some(p), Some(q)) => (*p - *q).length(),
                _ => 0.0,
            })
            .sum();
        let tol = q.area.abs() * (2.0 * dev * face_curvature(model, f, &dom.uv)).max(1e-9) + perimeter * dev;
        area_tol_total += tol;
        let d = (a_mesh - q.area).abs();
        if d.is_nan() || d > tol {
            area_ok = false;
            failures.push(CheckFailure {
                check: "area",
                face: Some(fid),
                step_id: face_ref(fid),
                message: format!("area {a_mesh:.9e} of its triangles, {:.9e} by quadrature over the face (tolerance {tol:.3e}, deviation reached {dev:.3e} mm)", q.area),
            });
        }
        let (found, expected) = (patch_loops(tris), expected_patch_loops(model, f));
        if found != expected {
            loops_ok = false;
            failures.push(CheckFailure {
                check: "boundary_loops",
                face: Some(fid),
                step_id: face_ref(fid),
                message: format!("its triangles have {found} boundary loops, the face's trim loops make {expected}"),
            });
        }
    }

    // topology of the triangles, per component, gathered per group
    let report = surface_report(s, &ReportOptions::default().with_self_intersections(false).with_max_listed(opts.max_listed));
    let mut shells: Vec<ShellCheck> = (0..ngroups)
        .map(|_| ShellCheck {
            brep_shells: Vec::new(),
            faces: 0,
            brep_closed: true,
            declared_closed: false,
            solid: false,
            void: false,
            mesh_components: 0,
            mesh_closed: false,
            euler_mesh: 0,
            euler_brep: 0,
            genus_mesh: None,
            genus_brep: None,
            volume_mesh: 0.0,
            volume_brep: 0.0,
            area_mesh: 0.0,
            area_brep: 0.0,
        })
        .collect();
    let mut comp_closed = vec![true; ngroups];
    for sh in &report.shells {
        let Some(g) = sh.tags.first().and_then(|&f| group_of_face(f)) else { continue };
        let x = &mut shells[g as usize];
        x.mesh_components += 1;
        x.euler_mesh += sh.euler;
        comp_closed[g as usize] &= sh.closed;
    }
    // B-rep counts per group
    let mut edge_uses: FxHashMap<u32, u32> = FxHashMap::default();
    for face in &model.faces {
        for &l in &face.loops {
            for c in &model.loops[l as usize].coedges {
                *edge_uses.entry(c.edge).or_insert(0) += 1;
            }
        }
    }
    let mut g_solid: Vec<Option<EntityRef>> = vec![None; ngroups];
    let mut verts: Vec<Vec<u32>> = vec![Vec::new(); ngroups];
    let mut edges: Vec<Vec<u32>> = vec![Vec::new(); ngroups];
    for (f, face) in model.faces.iter().enumerate() {
        let g = group[f] as usize;
        let x = &mut shells[g];
        x.faces += 1;
        x.euler_brep += face_euler(model, f);
        let shell = &model.shells[face.shell as usize];
        if !x.brep_shells.contains(&shell.source) {
            x.brep_shells.push(shell.source);
        }
        x.void |= shell.void;
        x.declared_closed |= should_close(shell);
        x.solid |= shell.solid.is_some();
        if let Some(so) = shell.solid.and_then(|k| model.solids.get(k as usize)) {
            g_solid[g].get_or_insert(so.source);
        }
        for &l in &face.loops {
            let lp = &model.loops[l as usize];
            verts[g].extend(lp.vertex);
            for c in &lp.coedges {
                let e = &model.edges[c.edge as usize];
                verts[g].extend([e.start, e.end]);
                if !e.degenerate {
                    edges[g].push(c.edge);
                    if !e.seam && edge_uses[&c.edge] != 2 {
                        x.brep_closed = false;
                    }
                }
            }
        }
    }
    let umbrellas = vertex_umbrellas(model, &group);
    let mut closed_ok = true;
    let mut euler_ok = true;
    let mut outward_ok = true;
    let mut volume_ok = true;
    let (mut vol_total, mut area_total) = ([0.0f64; 3], [0.0f64; 2]);
    for (g, x) in shells.iter_mut().enumerate() {
        x.brep_closed |= x.declared_closed;
        verts[g].sort_unstable();
        verts[g].dedup();
        edges[g].sort_unstable();
        edges[g].dedup();
        // a vertex where sheets of the surface touch (its link in several pieces, a pinch)
        // counts once per piece: the triangles there are the surface's sheets, each with its
        // own fan, and V - E + F is the manifold's
        let extra: i64 = verts[g].iter().map(|&v| umbrellas.get(&(g as u32, v)).map_or(0, |&k| k as i64 - 1)).sum();
        x.euler_brep += verts[g].len() as i64 + extra - edges[g].len() as i64;
        [x.area_mesh, x.area_brep] = g_area[g];
        [x.volume_mesh, x.volume_brep] = g_volume[g];
        area_total[0] += x.area_mesh;
        area_total[1] += x.area_brep;
        let closed = x.mesh_components > 0 && comp_closed[g];
        x.mesh_closed = closed;
        let even = |e: i64| (e % 2 == 0 && e <= 2).then_some((2 - e) / 2);
        x.genus_brep = if x.brep_closed { even(x.euler_brep) } else { None };
        x.genus_mesh = if closed { even(x.euler_mesh) } else { None };
        let shell_ref = x.brep_shells.first().copied();
        if x.brep_closed && !closed {
            closed_ok = false;
            failures.push(CheckFailure { check: "closed", face: None, step_id: shell_ref, message: format!("shell group {}: its B-rep closes, its triangles do not", refs(&x.brep_shells)) });
        }
        if x.mesh_components != 1 || x.euler_mesh != x.euler_brep {
            euler_ok = false;
            failures.push(CheckFailure {
                check: "euler",
                face: None,
                step_id: shell_ref,
                message: format!("shell group {}: {} mesh components, Euler characteristic {} of the triangles, {} of the B-rep", refs(&x.brep_shells), x.mesh_components, x.euler_mesh, x.euler_brep),
            });
        }
        if x.brep_closed {
            let positive = if x.void { x.volume_mesh < 0.0 } else { x.volume_mesh > 0.0 };
            if !positive {
                outward_ok = false;
                failures.push(CheckFailure { check: "outward", face: None, step_id: shell_ref, message: format!("shell group {} encloses volume {:.6e} (void: {})", refs(&x.brep_shells), x.volume_mesh, x.void) });
            }
            let cap = if opts.volume_cap { VOLUME_RELATIVE * x.volume_brep.abs() } else { f64::INFINITY };
            let tol = g_band[g].min(cap) + 1e-9 * x.volume_brep.abs();
            vol_total[0] += x.volume_mesh;
            vol_total[1] += x.volume_brep;
            vol_total[2] += tol;
            let d = (x.volume_mesh - x.volume_brep).abs();
            if d.is_nan() || d > tol {
                volume_ok = false;
                let solid = g_solid[g].map_or(String::new(), |so| format!("solid {so}, "));
                let worst = match g_worst[g] {
                    Some((_, dev, fid)) => format!("; its faces deviate up to {dev:.3e} mm ({fid}, {})", face_ref(fid).unwrap_or_default()),
                    None => String::new(),
                };
                failures.push(CheckFailure {
                    check: "volume",
                    face: g_worst[g].map(|w| w.2),
                    step_id: shell_ref,
                    message: format!(
                        "{solid}shell group {}: volume {:.9e} of the triangles, {:.9e} of the B-rep: {:+.3} % off, tolerance {tol:.3e} = min(band Σ area x deviation reached {:.3e}, {} % of the volume {cap:.3e}){worst}",
                        refs(&x.brep_shells),
                        x.volume_mesh,
                        x.volume_brep,
                        100.0 * (x.volume_mesh - x.volume_brep) / x.volume_brep.abs(),
                        g_band[g],
                        100.0 * VOLUME_RELATIVE
                    ),
                });
            }
        }
    }
    // open and non-manifold mesh edges, named by a face that has them
    let mut edge_count: FxHashMap<(u32, u32), (u32, u32)> = FxHashMap::default();
    for (k, tr) in s.triangles.iter().enumerate() {
        for i in 0..3 {
            let (a, b) = (tr[i], tr[(i + 1) % 3]);
            edge_count.entry((a.min(b), a.max(b))).or_insert((0, k as u32)).0 += 1;
        }
    }
    let mut bad_edges: Vec<((u32, u32), (u32, u32))> = edge_count.into_iter().filter(|(_, (n, _))| *n != 2).collect();
    bad_edges.sort_unstable();
    // an open group is open exactly along its free B-rep edges: as many open mesh edges as
    // those edges have segments (faces that do not conform along a shared edge add more)
    let mut free_segments = vec![0usize; ngroups];
    let mut open_in_group = vec![0usize; ngroups];
    for (f, face) in model.faces.iter().enumerate() {
        for &l in &face.loops {
            for c in &model.loops[l as usize].coedges {
                if edge_uses.get(&c.edge) == Some(&1) {
                    free_segments[group[f] as usize] += t.edges.get(c.edge as usize).map_or(0, |ep| ep.ids.len().saturating_sub(1));
                }
            }
        }
    }
    let coincident = coincident_edges(model);
    for &(x, y) in &coincident {
        let (ex, ey) = (&model.edges[x], &model.edges[y]);
        let (p, q) = (model.vertices[ex.start as usize].point, model.vertices[ex.end as usize].point);
        failures.push(CheckFailure {
            check: "manifold",
            face: None,
            step_id: Some(ex.source),
            message: format!("B-rep edges {} and {} run along the same line from {p} to {q}: the solid touches itself there (a non-manifold solid, which fepre does not tessellate yet; thicken the contact or cut it apart in the CAD model)", ex.source, ey.source),
        });
    }
    for ((a, b), (n, k)) in bad_edges {
        let fid = s.face_tags.get(k as usize).copied().unwrap_or_default();
        let open_group_ok = n == 1 && group_of_face(fid).is_some_and(|g| !shells[g as usize].brep_closed);
        if open_group_ok {
            if let Some(g) = group_of_face(fid) {
                open_in_group[g as usize] += 1;
            }
            continue;
        }
        let p = s.vertices.get(a as usize).copied().unwrap_or(DVec3::NAN);
        let q = s.vertices.get(b as usize).copied().unwrap_or(DVec3::NAN);
        closed_ok &= n != 1;
        let message = format!("mesh edge {a}-{b} ({p} to {q}) has {n} triangles");
        failures.push(CheckFailure { check: if n == 1 { "closed" } else { "manifold" }, face: Some(fid), step_id: face_ref(fid), message });
    }
    for (g, x) in shells.iter().enumerate() {
        if !x.brep_closed && open_in_group[g] != free_segments[g] {
            closed_ok = false;
            failures.push(CheckFailure {
                check: "closed",
                face: None,
                step_id: x.brep_shells.first().copied(),
                message: format!("open shell group {}: {} open mesh edges, its free B-rep edges have {} segments (faces do not conform along a shared edge)", refs(&x.brep_shells), open_in_group[g], free_segments[g]),
            });
        }
    }
    let manifold = report.manifold && coincident.is_empty();
    if !report.vertex_manifold {
        failures.push(CheckFailure { check: "manifold", face: None, step_id: None, message: format!("{} non-manifold vertices", report.nonmanifold_vertices) });
    }
    if !report.oriented {
        failures.push(CheckFailure { check: "oriented", face: None, step_id: None, message: format!("{} edges traversed twice in one direction", report.misoriented_edges) });
    }
    // self-intersections within a solid; contacts between solids
    let solid_key = |f: FaceId| -> Option<i64> {
        let face = model.try_face(f)?;
        match model.shells.get(face.shell as usize)?.solid {
            Some(k) => Some(i64::from(k)),
            None => Some(-1 - i64::from(group_of_face(f)?)),
        }
    };
    let (mut self_x, mut contacts) = (None, 0);
    if opts.self_intersections {
        let mut n = 0;
        for [a, b] in intersecting_pairs(s) {
            let (fa, fb) = (s.face_tags[a as usize], s.face_tags[b as usize]);
            if solid_key(fa) != solid_key(fb) {
                contacts += 1;
                continue;
            }
            n += 1;
            failures.push(CheckFailure {
                check: "self_intersection",
                face: Some(fa),
                step_id: face_ref(fa),
                message: format!("triangle {a} of face {fa} ({}) intersects triangle {b} of face {fb} ({})", face_ref(fa).unwrap_or_default(), face_ref(fb).unwrap_or_default()),
            });
        }
        self_x = Some(n);
    }
    let failure_count = failures.len();
    failures.truncate(opts.max_listed);
    let passed = failure_count == 0;
    Certificate {
        passed,
        all_faces_meshed: t.failed.is_empty(),
        closed: closed_ok,
        manifold,
        oriented: report.oriented,
        outward: outward_ok,
        self_intersections: self_x,
        solid_contacts: contacts,
        euler_matches: euler_ok,
        boundary_loops_match: loops_ok,
        volume_matches: volume_ok,
        area_matches: area_ok,
        chord: delta,
        deviation: deviation_max,
        volume: vol_total,
        area: [area_total[0], area_total[1], area_tol_total],
        shells,
        failures,
        failure_count,
        open_solids,
        reoriented: Vec::new(),
        turned_faces: Vec::new(),
        seconds: t0.elapsed().as_secs_f64(),
    }
}
