//! Tetrahedral meshing of closed surfaces.
//!
//! Stage: layer 4. Input: a closed, tagged [`TriSurface`] (outer boundaries and cavities; each
//! region a connected volume between them, or given by a seed point), a [`SizeField`] and
//! [`MeshOptions`]. Output: a [`TetMesh`] whose tets carry a region tag and whose boundary
//! triangles carry the tag of the input triangle they lie in.
//!
//! Stages, one file each:
//! 1. `input.rs`: the surface must be closed, manifold and free of self-intersections; the
//!    errors name the offending edges or the two crossing triangles and their tags;
//! 2. `tetra.rs`: the Delaunay tetrahedralization of the surface vertices;
//! 3. `recover.rs`: boundary recovery, Steiner points on segments and facets until every
//!    piece of the surface is a face of the tetrahedralization;
//! 4. `carve.rs`: the exterior and the cavities removed by flood fill across the surface,
//!    regions numbered;
//! 5. `refine.rs`: Delaunay refinement inside, with encroachment rules, a radius-edge bound
//!    and the size field; `split_boundary.rs`: encroached subfaces and subsegments split
//!    during refinement (the exterior removed first);
//! 6. `keep.rs` (with `keep_surface`): the boundary Steiner points collapsed back onto the
//!    input vertices, so the surface is exactly the input;
//! 7. the optimisation of [`crate::mesh3d::optimize`] when it exists, then `extract.rs`: the
//!    result as a [`TetMesh`].

mod assembly;
mod bad_queue;
mod carve;
mod extract;
mod input;
mod keep;
mod recover;
mod refine;
mod split_boundary;
mod subface_list;
mod surface_model;
mod tetra;
mod ties;

pub use assembly::{Contact, SolidFace, SolidInfo, Solids, assembly_contacts, merge_solids, mesh_solids, mesh_solids_on, solid_surfaces};

use crate::core::{BoundaryGeometry, FaceId, RegionId, SizeField};
use crate::mesh::{TetMesh, TriSurface};
use glam::DVec3;
use serde::Serialize;
use std::time::Instant;

/// The optimiser's budget: one attempt (a bad tet worked on) per this many tets of the
/// extracted mesh, plus 10,000. A count, not a time: the same input and options give the same
/// mesh on any machine, under any load and with any thread count. Meshes that reach the
/// targets need far less (the PLC tests: 2,663 attempts for 73,874 tets, 15,001 for 467,232);
/// it stops hopeless inputs (tiny input angles: `plate_holes.STL` of the corpus makes 41,651
/// attempts in 16 passes without it), as the time budget it replaces ("half the time so far,
/// or a second") did.
const TETS_PER_OPTIMIZE_ATTEMPT: usize = 8;

/// The optimisation's last phase around the tets it leaves under 10° (a common floor for
/// solver-grade tets): the tets two rings around them worked on toward 30°
/// ([`crate::mesh3d::optimize::Focus`]; the figures in docs/benchmarks.md).
const FOCUS: crate::mesh3d::optimize::Focus = crate::mesh3d::optimize::Focus { below_deg: 10.0, target_deg: 30.0 };

/// Options of [`mesh_surface`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct MeshOptions {
    /// Refine tets whose circumradius-to-shortest-edge ratio exceeds this.
    pub max_radius_edge: f64,
    /// Minimum dihedral angle (degrees) the optimisation aims for.
    pub min_dihedral: f64,
    /// Keep the input surface exactly: no Steiner point stays on it.
    pub keep_surface: bool,
    /// Seed of the randomised insertion order (the result does not depend on it).
    pub seed: u64,
    /// Run the optimisation (flips, smoothing, insertion) after refinement.
    pub optimize: bool,
    /// Without `keep_surface`: cut the surface to the size before meshing (default). Turn it
    /// off for a surface already made of well-shaped triangles of the size wanted (a
    /// tessellation by [`crate::tessellate::tessellate_sized`]): the points that
    /// boundary recovery puts on it are then merged back where they can be, as with
    /// `keep_surface`, and the others stay (their triangles inherit their tags).
    pub presize: bool,
    /// Let the optimisation slide boundary vertices where the boundary stays as it is: in
    /// the plane of a flat face, along a straight edge between two flat faces
    /// ([`crate::mesh3d::optimize::OptimizeOptions::slide_boundary`]). Never with
    /// `keep_surface`; in an assembly, never on faces in contact with another solid.
    pub slide_boundary: bool,
    /// Strips of the input narrower than this length are closed up before meshing
    /// (`crate::mesh::narrow::collapse_narrow`: a sliver face, a step between two faces
    /// that almost meet). `None`: [`NARROW_SHARE`] of the input's diagonal; `Some(0.0)`: off
    /// (as with `keep_surface`, which keeps the input as it is).
    pub narrow_tolerance: Option<f64>,
    /// In an assembly, imprint touching solids on each other where their faces in contact
    /// lie in one plane, so that the merged mesh is conforming there (shared nodes) instead
    /// of tied ([`mesh_solids`]).
    pub imprint: bool,
    /// Set from outside: the run stops at its next stage ([`MeshingError::Abandoned`]).
    pub(crate) abandon: Abandon,
}

/// A flag that stops a mesher run at its next stage, set by work beside it that finds the
/// run useless: a CAD part is meshed while its tessellation is certified, and a failed
/// certificate (or shells to turn) abandons the mesh.
#[derive(Clone, Debug, Default)]
pub(crate) struct Abandon(std::sync::Arc<std::sync::atomic::AtomicBool>);

impl Abandon {
    /// Stops the runs that hold this flag at their next stage.
    pub(crate) fn set(&self) {
        self.0.store(true, std::sync::atomic::Ordering::Relaxed);
    }

    /// [`MeshingError::Abandoned`] once the flag is set.
    fn check(&self) -> Result<(), MeshingError> {
        if self.0.load(std::sync::atomic::Ordering::Relaxed) { Err(MeshingError::Abandoned) } else { Ok(()) }
    }
}

impl PartialEq for Abandon {
    /// Options do not differ by their flags: the flag says nothing of the mesh asked for.
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

/// The default narrow-strip tolerance as a share of the input's bounding-box diagonal: a
/// strip 0.1 mm wide on a part a metre across. Measured on real parts: a step of 0.0001 mm
/// between two coaxial cylinders of a 27 mm part (Inventor, Haserea_Part4) made 18,885 tets
/// under 10° at the defaults; a default tet is about 400 such widths long.
pub const NARROW_SHARE: f64 = 1e-4;

impl Default for MeshOptions {
    fn default() -> Self {
        MeshOptions {
            max_radius_edge: 1.5,
            min_dihedral: 18.0,
            keep_surface: false,
            seed: 0x5eed,
            optimize: true,
            presize: true,
            slide_boundary: true,
            narrow_tolerance: None,
            imprint: true,
            abandon: Abandon::default(),
        }
    }
}

/// The smallest radius-edge bound a mesher can end at (the regular tet has 0.61, but Delaunay
/// refinement cannot end below about 1.1).
pub const MIN_RADIUS_EDGE_BOUND: f64 = 1.1;

/// The largest dihedral angle (degrees) a mesher can work towards or a run can require.
pub const MAX_DIHEDRAL_BOUND: f64 = 35.0;

/// A mesh option no mesher can meet.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error, Serialize)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum MeshOptionError {
    /// A radius-edge bound under [`MIN_RADIUS_EDGE_BOUND`] (or not a finite number).
    #[error("{0} is below 1.1: no tetrahedral mesh reaches it (the regular tet has 0.61, but refinement cannot end below about 1.1)")]
    RadiusEdge(f64),
    /// A dihedral angle outside `[0, MAX_DIHEDRAL_BOUND]` degrees (or not a finite number).
    #[error("{0}° must be in [0, 35]: no mesher can promise more")]
    Dihedral(f64),
}

/// `r` as a radius-edge bound: at least [`MIN_RADIUS_EDGE_BOUND`].
///
/// # Errors
/// [`MeshOptionError::RadiusEdge`] below it, or not a finite number.
pub fn radius_edge_bound(r: f64) -> Result<f64, MeshOptionError> {
    if r.is_finite() && r >= MIN_RADIUS_EDGE_BOUND { Ok(r) } else { Err(MeshOptionError::RadiusEdge(r)) }
}

/// `d` as a dihedral angle to aim at or require (degrees): in `[0, MAX_DIHEDRAL_BOUND]`.
///
/// # Errors
/// [`MeshOptionError::Dihedral`] outside it, or not a finite number.
pub fn dihedral_bound(d: f64) -> Result<f64, MeshOptionError> {
    if d.is_finite() && (0.0..=MAX_DIHEDRAL_BOUND).contains(&d) { Ok(d) } else { Err(MeshOptionError::Dihedral(d)) }
}

impl MeshOptions {
    /// Sets [`MeshOptions::max_radius_edge`], checked by [`radius_edge_bound`].
    ///
    /// # Errors
    /// A bound no mesh reaches.
    pub fn try_with_max_radius_edge(self, r: f64) -> Result<Self, MeshOptionError> {
        radius_edge_bound(r).map(|r| self.with_max_radius_edge(r))
    }
    /// Sets [`MeshOptions::min_dihedral`], checked by [`dihedral_bound`].
    ///
    /// # Errors
    /// An angle no mesher can promise.
    pub fn try_with_min_dihedral(self, d: f64) -> Result<Self, MeshOptionError> {
        dihedral_bound(d).map(|d| self.with_min_dihedral(d))
    }
    /// Sets [`MeshOptions::max_radius_edge`].
    pub fn with_max_radius_edge(mut self, r: f64) -> Self {
        self.max_radius_edge = r;
        self
    }
    /// Sets [`MeshOptions::min_dihedral`].
    pub fn with_min_dihedral(mut self, d: f64) -> Self {
        self.min_dihedral = d;
        self
    }
    /// Sets [`MeshOptions::optimize`].
    pub fn with_optimize(mut self, on: bool) -> Self {
        self.optimize = on;
        self
    }
    /// Sets [`MeshOptions::keep_surface`].
    pub fn with_keep_surface(mut self, keep: bool) -> Self {
        self.keep_surface = keep;
        self
    }
    /// Sets [`MeshOptions::slide_boundary`].
    pub fn with_boundary_sliding(mut self, slide: bool) -> Self {
        self.slide_boundary = slide;
        self
    }
    /// Sets [`MeshOptions::presize`].
    pub fn with_presize(mut self, presize: bool) -> Self {
        self.presize = presize;
        self
    }
    /// Sets the flag that abandons the run ([`Abandon`]).
    pub(crate) fn with_abandon(mut self, abandon: Abandon) -> Self {
        self.abandon = abandon;
        self
    }
    /// Sets [`MeshOptions::imprint`].
    pub fn with_imprint(mut self, imprint: bool) -> Self {
        self.imprint = imprint;
        self
    }
    /// Sets [`MeshOptions::narrow_tolerance`].
    pub fn with_narrow_tolerance(mut self, tol: Option<f64>) -> Self {
        self.narrow_tolerance = tol;
        self
    }
    /// The narrow-strip tolerance for `surface`: the option's length, or [`NARROW_SHARE`] of
    /// its diagonal; 0 with `keep_surface`.
    pub fn narrow_length(&self, surface: &TriSurface) -> f64 {
        if self.keep_surface {
            return 0.0;
        }
        self.narrow_tolerance.unwrap_or_else(|| NARROW_SHARE * surface.bbox().diagonal())
    }
}

/// A region given by a point inside it.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct RegionSeed {
    /// A point strictly inside the region.
    pub point: DVec3,
    /// The region's tag.
    pub tag: RegionId,
}

/// Holes and region seeds (from a `.poly` file, or given by the caller).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Seeds {
    /// Points inside volumes that must stay empty (beyond the cavities found by enclosure).
    pub holes: Vec<DVec3>,
    /// Regions by seed point; regions without a seed are numbered by enclosure.
    pub regions: Vec<RegionSeed>,
}

/// What [`mesh_surface`] did, for reports.
#[derive(Clone, Debug, Default, Serialize)]
pub struct MeshReport {
    /// Vertices of the result.
    pub nodes: usize,
    /// Tets of the result.
    pub tets: usize,
    /// Steiner points left on the boundary.
    pub boundary_steiner_points: usize,
    /// Steiner points inserted in the volume.
    pub volume_steiner_points: usize,
    /// Boundary points that refinement put where a tet's circumcentre encroached a subface
    /// (counted in `boundary_steiner_points` too).
    pub refinement_boundary_points: usize,
    /// Refinement reached its point budget before every tet met the radius-edge bound (input
    /// angles too small for Delaunay refinement to end); the optimisation still ran.
    pub refinement_stopped: bool,
    /// Regions.
    pub regions: usize,
    /// Seconds per stage: delaunay, recovery, carve, refine, keep, optimize, extract.
    pub stage_seconds: Vec<(String, f64)>,
    /// What the optimisation did, when it ran.
    pub optimize: Option<crate::mesh3d::optimize::OptimizeReport>,
    /// Total wall seconds.
    pub seconds: f64,
    /// Which budget stopped refinement early, when one did.
    pub refinement_stop: Option<RefinementStop>,
    /// Input triangles that were caps (flat, a vertex on their long side), each repaired with
    /// its neighbour (`crate::mesh::caps::repair_caps`).
    pub input_caps_repaired: usize,
    /// The narrow strips closed up before meshing, where there were any
    /// ([`MeshOptions::narrow_tolerance`]).
    pub narrow: Option<crate::mesh::narrow::NarrowReport>,
    /// The most the enclosed volume can differ from the input's because nearly flat input
    /// triangles were merged into facets and retriangulated (TetGen's `-p` rule, 0.1 degrees);
    /// zero when every merged facet is exactly planar, and with `keep_surface`.
    pub flattening_volume: f64,
    /// In an assembly, the most the solids' volumes moved by imprinting them on each other
    /// (points of one solid's contact boundary slid onto the other's, within the gap): the
    /// sum over the solids of the change of each one's enclosed volume.
    pub imprint_volume: f64,
    /// In an assembly: groups of faces in contact, and of them those imprinted (the rest are
    /// tied where the solids touch).
    pub imprinted: Option<(usize, usize)>,
    /// The surface meshed where the checks changed the input (caps repaired, narrow strips
    /// closed), for the summary's input angles ([`prepared_surface`]).
    #[serde(skip)]
    pub(crate) prepared: Option<std::sync::Arc<PreparedInput>>,
}

/// The surface the mesher took where its checks changed the input, with a fingerprint of the
/// input it was made from.
#[derive(Debug)]
pub(crate) struct PreparedInput {
    /// [`fingerprint`] of the input.
    input: u64,
    /// The surface meshed.
    surface: TriSurface,
}

/// A hash of a surface's vertices (their bits), triangles and tags: equal surfaces have equal
/// fingerprints.
fn fingerprint(s: &TriSurface) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut h = rustc_hash::FxHasher::default();
    s.vertices.len().hash(&mut h);
    for p in &s.vertices {
        p.to_array().map(f64::to_bits).hash(&mut h);
    }
    s.triangles.hash(&mut h);
    s.face_tags.hash(&mut h);
    h.finish()
}

/// Which budget stopped refinement early: `"points"` (the mesh reached `max_points`) or
/// `"steps"` (the bound on the bad tets worked on), and the points then.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RefinementStop {
    /// `"points"` or `"steps"`.
    pub budget: &'static str,
    /// Points of the tetrahedralization when it stopped.
    pub points: usize,
    /// The point budget.
    pub max_points: usize,
}

fn refinement_stop(stopped: bool, points: usize, max_points: usize) -> Option<RefinementStop> {
    stopped.then_some(RefinementStop { budget: if points >= max_points { "points" } else { "steps" }, points, max_points })
}

/// Why a surface could not be meshed.
#[derive(Clone, Debug, PartialEq, thiserror::Error, serde::Serialize)]
#[non_exhaustive]
pub enum MeshingError {
    /// The surface is not closed: it has edges used by one triangle only.
    #[error("the surface is open: {count} boundary edges, e.g. {}{}; close it (or fill its holes) before meshing", edges_text(edges, at), faces_text(faces))]
    Open {
        /// Number of boundary edges.
        count: usize,
        /// The first boundary edges (vertex pairs).
        edges: Vec<[u32; 2]>,
        /// Their end points, as `edges`.
        at: Vec<[[f64; 3]; 2]>,
        /// The faces the open edges border (tags, with their names where known), in tag
        /// order, the first ten.
        faces: Vec<(FaceId, Option<String>)>,
    },
    /// An edge is used by more than two triangles.
    #[error("edge ({}, {}) is shared by {count} triangles (non-manifold); separate the bodies or merge the duplicated faces", edge[0], edge[1])]
    NonManifold {
        /// The edge.
        edge: [u32; 2],
        /// Triangles on it.
        count: usize,
    },
    /// Two triangles cross.
    #[error("triangles {a} ({tag_a}) and {b} ({tag_b}) intersect; {count} crossing pairs in all: repair the surface")]
    SelfIntersecting {
        /// One triangle.
        a: u32,
        /// The other.
        b: u32,
        /// Tag of `a`.
        tag_a: FaceId,
        /// Tag of `b`.
        tag_b: FaceId,
        /// Crossing pairs in all.
        count: usize,
    },
    /// The surface is degenerate: a zero-area triangle, or all vertices in one plane.
    #[error("degenerate surface: {0}")]
    Degenerate(String),
    /// Boundary recovery failed near a triangle.
    #[error("boundary recovery failed near input triangle {triangle} ({tag}): {message}")]
    Recovery {
        /// The input triangle.
        triangle: usize,
        /// Its tag.
        tag: FaceId,
        /// What went wrong.
        message: String,
    },
    /// Keep-surface: some Steiner points that recovery needed on the boundary could not be
    /// merged back into the input vertices.
    #[error("the surface cannot be kept exactly: {left} of the {recovered} points that boundary recovery put on it could not be removed again; mesh without --keep-surface (split triangles inherit their tags)")]
    KeepSurface {
        /// Points left on the boundary.
        left: usize,
        /// Points recovery put there.
        recovered: usize,
    },
    /// A bug of fepre (an invariant broke); please report it with the input.
    #[error("internal error: {0}")]
    Internal(String),
    /// The run was stopped from outside ([`MeshOptions`]' abandon flag): its surface is not
    /// the one to mesh (its certificate failed, or its shells are to be turned).
    #[error("meshing was abandoned: the surface is not the one to mesh (its certificate failed, or its shells are to be turned)")]
    Abandoned,
    /// Two solids of an assembly overlap: a point of one lies deeper than the gap inside the
    /// other (on its surface or inside both).
    #[error("{a} and {b} overlap: the point ({}, {}, {}) lies {depth:.3e} deep inside both (within {gap:.3e} of a surface is contact, deeper is overlap); move the solids apart or cut one out of the other", point[0], point[1], point[2])]
    Overlap {
        /// The first solid and its face at the point.
        a: SolidFace,
        /// The second solid and its face nearest the point.
        b: SolidFace,
        /// A point inside both.
        point: [f64; 3],
        /// How deep it lies inside the solids (at least the gap).
        depth: f64,
        /// The gap within which touching surfaces are contact.
        gap: f64,
    },
    /// One solid of an assembly cannot be meshed; triangle and vertex numbers are the whole
    /// surface's.
    #[error("solid {}{}: {source}", solid.0, name.as_ref().map(|n| format!(" ({n:?})")).unwrap_or_default())]
    InSolid {
        /// The solid's region tag.
        solid: RegionId,
        /// Its name.
        name: Option<String>,
        /// What is wrong with it.
        source: Box<MeshingError>,
    },
}

fn edges_text(e: &[[u32; 2]], at: &[[[f64; 3]; 2]]) -> String {
    use crate::quality::worst_tet::fmt_point;
    e.iter()
        .enumerate()
        .take(3)
        .map(|(k, x)| match at.get(k) {
            Some([a, b]) => format!("vertices {} {} to {} {}", x[0], fmt_point(*a), x[1], fmt_point(*b)),
            None => format!("({}, {})", x[0], x[1]),
        })
        .collect::<Vec<_>>()
        .join(", ")
}

fn faces_text(faces: &[(FaceId, Option<String>)]) -> String {
    if faces.is_empty() {
        return String::new();
    }
    let list: Vec<String> = faces.iter().map(|(f, name)| match name {
        Some(n) => format!("{} \"{n}\"", f.0),
        None => f.0.to_string(),
    }).collect();
    format!(" (along face{} {})", if faces.len() == 1 { "" } else { "s" }, list.join(", "))
}

/// The surface [`mesh_surface`] meshed for `surface`, as its `report` says: the caps repaired
/// and the narrow strips closed up at the report's tolerance where it did so (the same steps,
/// deterministic, without the checks the mesher made), or `None` where it meshed `surface` as
/// it is.
///
/// The mesher keeps the surface it took in its report; where `surface` is the one it was
/// given, that is returned instead of being made again.
pub(crate) fn prepared_surface<'a>(surface: &'a TriSurface, report: &'a MeshReport) -> Option<std::borrow::Cow<'a, TriSurface>> {
    if let Some(p) = report.prepared.as_deref().filter(|p| p.input == fingerprint(surface)) {
        return Some(std::borrow::Cow::Borrowed(&p.surface));
    }
    made_again(surface, report).map(std::borrow::Cow::Owned)
}

/// [`prepared_surface`] made again from `surface` by the report's steps.
fn made_again(surface: &TriSurface, report: &MeshReport) -> Option<TriSurface> {
    let repaired = if report.input_caps_repaired > 0 { crate::mesh::caps::repair_caps(surface).map(|r| r.0) } else { None };
    let Some(n) = &report.narrow else { return repaired };
    crate::mesh::narrow::collapse_narrow(repaired.as_ref().unwrap_or(surface), n.tolerance, &[]).map(|r| r.0).or(repaired)
}

/// Meshes the volume enclosed by `surface`.
///
/// # Errors
/// [`MeshingError`] for open, non-manifold, self-intersecting or degenerate surfaces, and when
/// the boundary cannot be recovered.
pub fn mesh_surface(
    surface: &TriSurface,
    seeds: &Seeds,
    size: &dyn SizeField,
    options: &MeshOptions,
) -> Result<(TetMesh, MeshReport), MeshingError> {
    mesh_surface_pinned(surface, seeds, size, options, &[], None)
}

/// [`mesh_surface`] on the geometry the surface approximates (a B-rep whose face ids are the
/// surface's tags): the optimiser's boundary vertices then slide on curved faces and along
/// curved edges too, put back onto the geometry after each move
/// ([`MeshOptions::slide_boundary`]).
///
/// # Errors
/// As [`mesh_surface`].
pub fn mesh_surface_on(
    surface: &TriSurface,
    seeds: &Seeds,
    size: &dyn SizeField,
    options: &MeshOptions,
    geometry: Option<&dyn BoundaryGeometry>,
) -> Result<(TetMesh, MeshReport), MeshingError> {
    mesh_surface_pinned(surface, seeds, size, options, &[], geometry)
}

/// [`mesh_surface`] with the vertices of faces tagged `pinned` kept where they are (an
/// assembly's faces in contact with another solid, whose nodes must stay shared or tied).
pub(crate) fn mesh_surface_pinned(
    surface: &TriSurface,
    seeds: &Seeds,
    size: &dyn SizeField,
    options: &MeshOptions,
    pinned: &[FaceId],
    geometry: Option<&dyn BoundaryGeometry>,
) -> Result<(TetMesh, MeshReport), MeshingError> {
    let start = Instant::now();
    let mut report = MeshReport::default();
    let stage = |report: &mut MeshReport, name: &str, t: &mut Instant| {
        report.stage_seconds.push((name.to_string(), t.elapsed().as_secs_f64()));
        *t = Instant::now();
    };
    // the input's checks, and beside them the tetrahedralization of its vertices where the
    // boundary is meshed as it is (not cut to the size first), or else the feature scale that
    // presizing needs: the checks decide whether these stand, and a surface they change is
    // worked on again
    let early = options.keep_surface || !options.presize;
    let ((prepared, check_s), (early_tr, early_scale)) = rayon::join(
        || {
            let t = Instant::now();
            (input::prepare(surface, options, pinned), t.elapsed().as_secs_f64())
        },
        || {
            if surface.validate().is_err() {
                (None, None)
            } else if early {
                let t = Instant::now();
                let ranks = ties::ranks(&surface.vertices, &surface.triangles);
                (Some((tetra::Tetra::new(surface.vertices.clone(), ranks, options.seed), t.elapsed().as_secs_f64())), None)
            } else {
                (None, Some(feature_scale(surface, options.seed)))
            }
        },
    );
    let prepared = prepared?;
    options.abandon.check()?;
    let input_fingerprint = prepared.surface.as_ref().map(|_| fingerprint(surface));
    report.stage_seconds.push(("check".to_string(), check_s));
    let mut clock = Instant::now();
    let early_tr = early_tr.filter(|_| prepared.surface.is_none());
    let early_scale = early_scale.filter(|_| prepared.surface.is_none());
    let surface = prepared.surface.as_ref().unwrap_or(surface);
    let caps = prepared.caps;
    // the surface model, and beside it the feature scale that presizing needs where the
    // checks changed the surface
    let presizing = !options.keep_surface && options.presize;
    let (mut sm, scale) = rayon::join(
        || surface_model::SurfaceModel::new(&surface.vertices, &surface.triangles, &surface.face_tags, !options.keep_surface),
        || presizing.then(|| early_scale.unwrap_or_else(|| feature_scale(surface, options.seed))),
    );
    let (tr, delaunay_s) = match early_tr {
        Some((tr, seconds)) => (tr, seconds + clock.elapsed().as_secs_f64()),
        None => {
            let mut points = surface.vertices.clone();
            if let Some(scale) = scale {
                // the boundary may change: cut it to the size, and its thin triangles into
                // better ones
                let h = |p: DVec3| size.size_at(p);
                sm.presize(&mut points, &h, &scale);
                stage(&mut report, "presize", &mut clock);
            }
            let mut ranks = ties::ranks(&surface.vertices, &surface.triangles);
            ranks.extend(surface.vertices.len() as u32..points.len() as u32);
            (tetra::Tetra::new(points, ranks, options.seed), clock.elapsed().as_secs_f64())
        }
    };
    let mut tr = tr.map_err(|e| MeshingError::Degenerate(e.to_string()))?;
    report.stage_seconds.push(("delaunay".to_string(), delaunay_s));
    clock = Instant::now();
    let budget = 50 * surface.triangles.len() + 10_000;
    let rec = recover::recover(&mut tr, &mut sm, budget)?;
    stage(&mut report, "recovery", &mut clock);
    options.abandon.check()?;
    let mut labels = carve::carve(&mut tr, &sm, seeds)?;
    recover::unfold_flat_tets(&mut tr, &mut sm, &mut labels);
    stage(&mut report, "carve", &mut clock);
    options.abandon.check()?;
    // a tenth of the shortest boundary edge: the smallest tet refinement splits
    let r_min = 0.1 * sm.all_subsegments().map(|(_, [a, b])| tr.point(a).distance(tr.point(b))).fold(f64::INFINITY, f64::min);
    // a budget of points: four times the boundary's for quality, plus what the size asks for
    // (the tets of the size in the box, summed over an 8^3 grid of cells)
    let max_points = {
        let (lo, hi) = surface.vertices.iter().fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(l, h), &p| (l.min(p), h.max(p)));
        let cell = (hi - lo) / 8.0;
        let mut by_size = 0.0;
        for i in 0..8 {
            for j in 0..8 {
                for k in 0..8 {
                    let c = lo + cell * DVec3::new(i as f64 + 0.5, j as f64 + 0.5, k as f64 + 0.5);
                    let h = size.size_at(c);
                    if h.is_finite() && h > 0.0 {
                        by_size += 3.0 * cell.x * cell.y * cell.z / (0.118 * h * h * h) / 5.0;
                    }
                }
            }
        }
        4 * tr.num_points() + 10_000 + by_size.min(5e7) as usize
    };
    // refinement splits the boundary where the boundary may change and is made of its facets:
    // not with keep-surface, nor on a tessellation sized already (a STEP part's curved faces,
    // whose new points belong on the CAD face, not on its chords: measured, splits there made
    // part.step 31 -> 234 tets under 5° and linkrods.step 65 -> 172). The exterior goes first:
    // boundary splits work on the material side.
    let splits = !options.keep_surface && options.presize;
    if splits {
        keep::drop_exterior(&mut tr, &labels);
    }
    // the input's small angles, which the optimiser's focus phase asks for, found beside
    // refinement
    let (refined, focus_angles) = rayon::join(
        || refine::refine(&mut tr, &mut labels, size, options, r_min, max_points, splits.then_some(&mut sm)),
        || options.optimize.then(|| crate::quality::input_angles::small_input_angles(surface, FOCUS.below_deg, !options.keep_surface)),
    );
    let mut refined = refined?;
    let mut stop = refinement_stop(refined.stopped, tr.num_points(), max_points);
    stage(&mut report, "refine", &mut clock);
    options.abandon.check()?;
    if !splits {
        keep::drop_exterior(&mut tr, &labels);
    }
    if options.keep_surface {
        // merging is easiest once the material has points of its own near the boundary
        let left = keep::keep_surface(&mut tr, &mut sm, false);
        if left > 0 {
            return Err(MeshingError::KeepSurface { left, recovered: rec.segment_points + rec.facet_points });
        }
        stage(&mut report, "keep", &mut clock);
    } else if !options.presize {
        // a surface sized already: recovery's points go back where they can
        keep::keep_surface(&mut tr, &mut sm, true);
        stage(&mut report, "keep", &mut clock);
    }
    {
        let again = refine::refine(&mut tr, &mut labels, size, options, r_min, max_points, None)?;
        refined.volume_points += again.volume_points;
        refined.stopped |= again.stopped;
        stop = stop.or(refinement_stop(again.stopped, tr.num_points(), max_points));
    }
    stage(&mut report, "refine", &mut clock);
    // validated here, or by the optimiser: it builds its working mesh checking orientation
    // and coordinates, and takes the adjacency (faces, boundary triangles) from the
    // tetrahedralization's links, which every mesher test checks against the sorted faces
    let extract::Extracted { mut mesh, adjacency } = extract::extract(&tr, &sm, &labels, surface, !options.optimize)?;
    // every mesher test checks the links' adjacency against the faces' sorted
    #[cfg(test)]
    assert_eq!(Ok(adjacency.clone()), crate::mesh3d::optimize::adjacency(&mesh), "the tetrahedralization's adjacency is the mesh's");
    stage(&mut report, "extract", &mut clock);
    options.abandon.check()?;
    if options.optimize {
        let opts = crate::mesh3d::optimize::OptimizeOptions::default()
            .with_min_dihedral(options.min_dihedral)
            .with_max_radius_edge(options.max_radius_edge.max(2.0))
            .with_max_passes(16)
            // hopeless inputs (tiny input angles) must not take forever: a count of attempts
            // proportional to the tets, never a time, so that the mesh is the same on any
            // machine under any load
            .with_max_attempts(Some(mesh.tets.len() / TETS_PER_OPTIMIZE_ATTEMPT + 10_000))
            .with_boundary_sliding(options.slide_boundary && !options.keep_surface)
            .with_pinned_faces(pinned.to_vec())
            .with_focus(Some(FOCUS));
        // tets at the input's small angles do not keep the focus phase's repeats going
        let angles = || focus_angles.clone().unwrap_or_else(|| crate::quality::input_angles::small_input_angles(surface, FOCUS.below_deg, !options.keep_surface));
        let r = crate::mesh3d::optimize::optimize_explained_with(&mut mesh, &opts, &angles, geometry, Some(adjacency)).map_err(|e| match e {
            crate::mesh3d::optimize::OptimizeError::InvalidMesh(m) => MeshingError::Internal(format!("the mesh does not validate: {m}")),
            e => MeshingError::Internal(e.to_string()),
        })?;
        report.optimize = Some(r);
        stage(&mut report, "optimize", &mut clock);
    }
    report.nodes = mesh.vertices.len();
    report.tets = mesh.tets.len();
    report.boundary_steiner_points = sm.boundary_steiner_points();
    report.input_caps_repaired = caps;
    report.narrow = prepared.narrow;
    report.prepared = prepared.surface.zip(input_fingerprint).map(|(surface, input)| std::sync::Arc::new(PreparedInput { input, surface }));
    report.flattening_volume = sm.flattening_volume;
    report.volume_steiner_points = refined.volume_points;
    report.refinement_boundary_points = refined.boundary_points;
    report.refinement_stopped = refined.stopped;
    report.refinement_stop = stop;
    report.regions = labels.regions;
    report.seconds = start.elapsed().as_secs_f64();
    Ok((mesh, report))
}

/// A local feature size at every input vertex: 0.7 times the distance to the nearest vertex
/// it is joined to in the Delaunay tetrahedralization of the surface vertices without being
/// joined on the surface (across a thin wall, a slot, a hole), infinite where there is none.
fn feature_scale(surface: &TriSurface, seed: u64) -> Vec<f64> {
    let n = surface.vertices.len();
    let mut scale = vec![f64::INFINITY; n];
    let ranks = ties::ranks(&surface.vertices, &surface.triangles);
    let Ok(tr) = tetra::Tetra::new(surface.vertices.clone(), ranks, seed) else { return scale };
    let mut on_surface: rustc_hash::FxHashSet<(u32, u32)> = rustc_hash::FxHashSet::default();
    for t in &surface.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            on_surface.insert((a.min(b), a.max(b)));
        }
    }
    for t in tr.live() {
        let v = tr.tets[t as usize].v;
        for (i, j) in [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)] {
            let (a, b) = (v[i].min(v[j]), v[i].max(v[j]));
            if on_surface.contains(&(a, b)) {
                continue;
            }
            let d = 0.7 * tr.point(a).distance(tr.point(b));
            scale[a as usize] = scale[a as usize].min(d);
            scale[b as usize] = scale[b as usize].min(d);
        }
    }
    scale
}

#[cfg(test)]
mod tests;
