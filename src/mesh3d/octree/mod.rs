//! Octree volume meshing by isosurface stuffing (Labelle and Shewchuk, "Isosurface Stuffing:
//! Fast Tetrahedral Meshes with Good Dihedral Angles", SIGGRAPH 2007), with the generalised
//! winding number as the inside/outside oracle, so that open, holed and self-intersecting
//! surfaces mesh as well as clean ones.
//!
//! Stage: layer 4, beside `mesher/`. Input: a tagged [`TriSurface`] (any), a [`SizeField`]
//! and [`OctreeOptions`]. Output: a [`TetMesh`] (one region, tag 1; every boundary triangle
//! tagged with the nearest input triangle's tag; `validate()`d) and an [`OctreeReport`]
//! (counts, the angle bounds promised, the boundary's deviation from the input measured both
//! ways, the feature edges the cell size does not resolve).
//!
//! Stages, one file each:
//! 1. `winding.rs`: the fast generalised winding number (BVH, dipoles far, exact near);
//!    `rows.rs`: its exact integers counted along the lattice's rows, for any surface once
//!    `cap.rs` has closed it into a cycle (the cap's solid angle subtracted);
//! 2. `lattice.rs`: the BCC lattice of cell size `h` over the surface's box;
//! 3. `cut.rs`: signs at the lattice vertices, one cut point per sign-changing edge, the
//!    warping rule with `α_long = 0.24999`, `α_short = 0.41189`;
//! 4. `graded.rs` (graded mode): a 2:1 balanced octree over the lattice's cubes, one cube
//!    wherever the surface comes within a cube, coarser inside, and its background tets;
//! 5. `stencil.rs`: the stencils filling each boundary background tet;
//! 6. `tags.rs`: boundary triangles tagged by the input triangle nearest to their centroid
//!    (found by the deviation's first sample of each);
//! 7. `snap.rs`: boundary vertices moved onto the input's feature corners and edges where
//!    the angle bounds allow;
//! 8. `coarsen.rs` (graded mode): interior vertices collapsed onto a neighbour where every
//!    tet made keeps [15°, 160°], the boundary kept;
//! 9. `deviation.rs`: Hausdorff distance both ways (sampled) and unresolved feature edges.
//!
//! Around them, `resolve.rs` ([`mesh_octree_resolved`]) chooses the cell where no size is
//! given: finer by √2 until the mesh holds the input's volume.
//!
//! # Invariants
//! - Uniform mode: the stencils are the paper's, with its quadrilateral rules (the apex rule
//!   and the parity rule, read off one background face, so the mesh is conforming; see
//!   `stencil.rs`). Tested: with every cut point anywhere in its allowed range `[α, 1 - α]`
//!   and the `0` vertices at their lattice positions, every stencil tet has its dihedral
//!   angles in [[`MIN_DIHEDRAL`], [`MAX_DIHEDRAL`]] = [10.7°, 164.8°], the paper's bounds.
//!   With warped vertices displaced towards their cut points the tests find [9.32°, 161.64°]
//!   (all positive): the cases below 10.7° include single-tet stencils, which no choice of
//!   diagonals changes. The report gives the extremes of every mesh, and the callers check
//!   them against the paper's bounds.
//! - Graded mode: the cut and stencilled tets are the uniform lattice's, so they keep the
//!   uniform mode's angles; the coarser tets are whole, their shapes lie in [30°, 135°] at
//!   the lattice positions, and those with a vertex warped onto the surface are kept only
//!   within [15°, 160°] at the warped positions (`graded.rs`). The boundary is the uniform
//!   mode's at the same cell size, the same triangles: no coarse tet has a vertex that
//!   feature snapping may move (`graded_octree`). Last, coarsening (on by default) collapses
//!   interior vertices where every tet it makes is positive with its angles in [15°, 160°]
//!   and the link condition holds: the boundary's vertices stay, so the boundary triangles
//!   are still the uniform mode's (`coarsen.rs`).
//! - Every output tet is positively oriented, decided exactly; a stencil tet that warping or
//!   a true cut point turns flat or inside out is an error ([`OctreeError::Inverted`]), never
//!   silently flipped.
//! - Reproducible: every stage is computed per vertex, edge or tet in parallel and collected
//!   in index order; the output is the same bytes for any thread count. No clock steers
//!   anything.

mod buried;
mod cap;
pub(crate) mod coarsen;
mod cut;
mod deviation;
mod graded;
mod lattice;
mod merge;
pub(crate) mod resolve;
mod rows;
pub(crate) mod snap;
mod stencil;
mod tags;
mod winding;
mod winding_volume;

pub use buried::{Buried, Side};
pub use coarsen::FLOOR as COARSEN_FLOOR;
pub use deviation::{Deviation, deviation};
pub use lattice::{Lattice, LatticeError};
pub use resolve::{RESOLVE, Resolve, mesh_octree_resolved};
pub use rows::is_cycle;
pub use snap::Snapped;
pub use winding::Winding;
pub use winding_volume::{WindingVolume, winding_volume};

use crate::core::ids::NONE;
use crate::core::predicates::orient3d;
use crate::core::{Aabb, RegionId, SizeField};
use crate::mesh::{TetMesh, TriSurface};
use crate::quality::tetrahedron::{dihedrals_of_extreme_cosines, tet_extreme_dihedral_cosines, tet_min_max_dihedral};
use glam::DVec3;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::time::Instant;
use stencil::Local;

/// The paper's `α_long`: a cut point closer than this fraction of a long edge to an end
/// warps that end onto it.
pub const ALPHA_LONG: f64 = 0.24999;
/// The paper's `α_short`, for short (corner-centre) edges.
pub const ALPHA_SHORT: f64 = 0.41189;
/// The smallest dihedral angle the paper proves for uniform stuffing with these `α`s.
pub const MIN_DIHEDRAL: f64 = 10.7;
/// The largest dihedral angle the paper proves for uniform stuffing with these `α`s.
pub const MAX_DIHEDRAL: f64 = 164.8;

/// Uniform lattice or graded octree.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Grading {
    /// One cell size everywhere (the BCC lattice).
    #[default]
    Uniform,
    /// Fine (the cell size) wherever the surface comes within a cell, coarser inside: a 2:1
    /// balanced octree whose cells double away from the boundary (see `graded.rs`), then
    /// coarsened inside by vertex collapses, the boundary kept (`coarsen.rs`).
    Graded,
}

/// Options of [`mesh_octree`].
#[derive(Clone, Debug, PartialEq)]
pub struct OctreeOptions {
    /// Uniform or graded.
    pub grading: Grading,
    /// Warping threshold on long edges.
    pub alpha_long: f64,
    /// Warping threshold on short edges.
    pub alpha_short: f64,
    /// Input edges whose faces turn by more than this (degrees) are feature edges.
    pub feature_angle_deg: f64,
    /// Move boundary vertices onto the feature edges and corners where the angle bounds
    /// allow (`snap.rs`).
    pub snap: bool,
    /// Graded mode: coarsen the mesh inside by collapsing interior vertices, the boundary
    /// kept (`coarsen.rs`).
    pub coarsen: bool,
}

impl Default for OctreeOptions {
    fn default() -> Self {
        OctreeOptions { grading: Grading::Uniform, alpha_long: ALPHA_LONG, alpha_short: ALPHA_SHORT, feature_angle_deg: 30.0, snap: true, coarsen: true }
    }
}

impl OctreeOptions {
    /// With cells of one size, or graded away from the boundary.
    pub fn with_grading(mut self, grading: Grading) -> Self {
        self.grading = grading;
        self
    }

    /// With or without the graded mode's vertex collapses ([`COARSEN_FLOOR`] bounds the
    /// angles of the tets they make).
    pub fn with_coarsen(mut self, coarsen: bool) -> Self {
        self.coarsen = coarsen;
        self
    }
}

/// What the octree mesher did.
#[derive(Clone, Debug, Default, Serialize)]
pub struct OctreeReport {
    /// `"uniform"` or `"graded"`.
    pub grading: String,
    /// Solids meshed one by one (the solids of a CAD assembly; 1 otherwise).
    pub solids: usize,
    /// Solids of an assembly left out because no lattice vertex lies inside them (thinner
    /// than the cell size); their volume is in `input_volume`, not in `volume`.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub empty_solids: Vec<EmptySolid>,
    /// The lattice's cell size (long edge).
    pub cell_size: f64,
    /// Lattice vertices (all, inside or not).
    pub lattice_vertices: usize,
    /// Graded mode: the octree's cells per level (one cube, two per side, ...); empty in
    /// uniform mode.
    pub cells_per_level: Vec<usize>,
    /// Graded mode: the tets of cells coarser than one cube (whole background tets), before
    /// coarsening. The others lie in one-cube cells: the band along the surface that the
    /// stencils need, the layer inside it, and what alignment and balance keep fine: the
    /// floor of the octree's grading at this cell, which coarsening goes under. 0 in uniform
    /// mode.
    #[serde(skip_serializing_if = "is_zero")]
    pub coarse_tets: usize,
    /// Graded mode: the interior vertices collapsed after the stencils and snapping, and the
    /// tets that went with them (`coarsen.rs`); `tets` counts what is left.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub coarsened: Option<coarsen::Coarsened>,
    /// Lattice edges the surface crosses (before warping).
    pub crossing_edges: usize,
    /// Cut points kept after warping.
    pub cut_points: usize,
    /// Cut points found by bisecting the winding number (where the surface is open or the
    /// edge passes through a triangle's edge); the rest lie on input triangles.
    pub bisected_cut_points: usize,
    /// Lattice vertices warped onto the surface.
    pub warped_vertices: usize,
    /// Boundary vertices snapped onto the input's feature corners and edges.
    pub snapped: Snapped,
    /// Background tets whose four vertices were all warped onto the surface, kept whole
    /// because their centroid is inside and their angles within the paper's bounds (the
    /// others, slivers flat on the surface, are left out).
    pub all_zero_tets: usize,
    /// Tets and nodes of the result.
    pub tets: usize,
    /// Nodes of the result.
    pub nodes: usize,
    /// Boundary triangles.
    pub boundary_triangles: usize,
    /// The dihedral angle bounds the paper proves for this mode, degrees.
    pub promised_dihedral: [f64; 2],
    /// The smallest and largest dihedral angle of the result, degrees.
    pub dihedral: [f64; 2],
    /// Volume of the result.
    pub volume: f64,
    /// The input's signed volume by the divergence theorem (the integral of its winding
    /// number; the enclosed volume for a closed outward surface).
    pub input_volume: f64,
    /// The surface enclosed a negative volume (its triangles face inward) and was meshed
    /// turned outward (the pipeline's decision, for one surface meshed whole).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub turned_outward: bool,
    /// The volume the winding number encloses reaches the lattice's box (a lattice corner on
    /// its faces is inside): the surface does not close it there (a surface model, an open
    /// or inward-facing sheet), and the mesh is cut off by the box, whose faces are then part
    /// of its boundary.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub reaches_box: bool,
    /// Two solids of an assembly overlap (the pipeline's check, its message): each was
    /// meshed on its own, so the overlap is meshed in both; no contacts are listed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub overlap: Option<String>,
    /// Whether `input_volume` is the volume the mesh approximates: the surface is closed and
    /// consistently oriented (a 2-cycle) and its winding number is 0 or 1 at every lattice
    /// vertex (no nested or overlapping shells). Not so for an open or self-overlapping
    /// surface, whose stuffed volume is where the winding number exceeds one half.
    pub input_volume_exact: bool,
    /// Where `input_volume` is not exact: the volume the input's winding number encloses
    /// (`w > 1/2`, [`winding_volume`] on [`REPORT_WINDING_CELLS`]³ cells), the reference of
    /// the mesh's volume; in an assembly, where every solid has one, their sum.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub winding_volume: Option<WindingVolume>,
    /// Where the boundary's bound passes the cell: how many input triangles another input
    /// triangle crosses or touches away from what they share (walls that cross leave gaps a
    /// cell cannot follow at any size); in an assembly, summed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub input_crossings: Option<usize>,
    /// Where no size was given: the cell sizes tried, coarsest first, the last the one
    /// meshed (`resolve`; solid by solid in an assembly); empty when the cell came from a
    /// size.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub cell_tries: Vec<CellTry>,
    /// The sampled Hausdorff distance over the cell size (the largest of the solids', each
    /// against its own cell).
    pub hausdorff_over_cell: f64,
    /// The Hausdorff distance's bound over the cell size (likewise).
    pub bound_over_cell: f64,
    /// The boundary's deviation from the input.
    pub deviation: Deviation,
    /// Seconds per stage.
    pub stage_seconds: Vec<(String, f64)>,
}

/// One cell size tried while choosing the default cell (`resolve`).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct CellTry {
    /// The solid (region tag) of an assembly meshed solid by solid; `None` otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub solid: Option<u32>,
    /// The cell size.
    pub cell: f64,
    /// Lattice vertices.
    pub lattice_vertices: usize,
    /// The relative volume error where the input volume is exact
    /// ([`OctreeReport::input_volume_exact`]); `None` otherwise.
    pub volume_error: Option<f64>,
    /// Where the input volume is not exact: the relative change of the mesh's volume from
    /// the try before (`None` for the first with lattice vertices inside).
    pub volume_change: Option<f64>,
    /// No lattice vertex was inside at this cell.
    pub empty: bool,
    /// The Hausdorff distance's bound over the cell size.
    pub bound_over_cell: f64,
    /// This try's mesh is the one kept.
    pub kept: bool,
}

/// A solid of an assembly the lattice does not reach into.
#[derive(Clone, Debug, Default, Serialize)]
pub struct EmptySolid {
    /// Its number (region tag).
    pub solid: u32,
    /// Its name.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Its volume (its surface's, by the divergence theorem).
    pub volume: f64,
}

/// Why the octree mesher made no mesh.
#[derive(Debug, thiserror::Error, Serialize)]
#[non_exhaustive]
pub enum OctreeError {
    /// No lattice for this size (too fine for the box, or not a size).
    #[error(transparent)]
    Lattice(#[from] LatticeError),
    /// Nothing is inside.
    #[error("no lattice vertex is inside the surface at cell size {0:.4e}: a finer size, or a surface that encloses a volume")]
    Empty(f64),
    /// Nothing is inside at the finest default cell the lattice budget allows.
    #[error("no lattice vertex is inside the surface down to cell size {h:.4e}, where the default cell stops (a finer one would build more than {budget} lattice vertices): give --size, or check that the surface encloses a volume")]
    EmptyWithin {
        /// The last cell tried.
        h: f64,
        /// The budget of lattice vertices.
        budget: u64,
    },
    /// A stencil tet came out flat or inside out.
    #[error("{count} tets came out flat or inverted after warping (first near ({:.6}, {:.6}, {:.6})); the angle guarantee does not hold for this surface at cell size {h:.4e}", at.x, at.y, at.z)]
    Inverted {
        /// How many.
        count: usize,
        /// Where the first is.
        at: DVec3,
        /// The cell size.
        h: f64,
    },
    /// One solid of an assembly could not be meshed.
    #[error("solid {solid}{}: {source}", name.as_ref().map(|n| format!(" ({n:?})")).unwrap_or_default())]
    InSolid {
        /// The solid's number (its region tag).
        solid: u32,
        /// Its name.
        name: Option<String>,
        /// Why.
        source: Box<OctreeError>,
    },
    /// Our own bug: the stencils and the cut points disagree.
    #[error("internal error in the octree mesher: {0}")]
    Internal(String),
    /// The result failed its own check.
    #[error("the octree mesh is invalid: {0}")]
    Invalid(#[from] crate::mesh::MeshError),
}

/// The cell size for `size`: the smallest size the field asks for at the surface's vertices
/// (the boundary resolution).
pub fn cell_size(surface: &TriSurface, size: &dyn SizeField) -> f64 {
    surface.vertices.par_iter().map(|&p| size.size_at(p)).reduce(|| f64::INFINITY, f64::min)
}

/// Meshes the volume `surface` encloses (winding number above one half) by isosurface
/// stuffing; see the module docs.
///
/// # Errors
/// See [`OctreeError`].
pub fn mesh_octree(surface: &TriSurface, size: &dyn SizeField, opts: &OctreeOptions) -> Result<(TetMesh, OctreeReport), OctreeError> {
    let t = Instant::now();
    let (oracle, cycle) = rayon::join(|| Winding::new(surface), || rows::is_cycle(surface));
    let (mesh, mut report) = mesh_at(&oracle, cycle, cell_size(surface, size), opts, t.elapsed().as_secs_f64())?;
    add_winding_volume(&mut report, &oracle);
    Ok((mesh, report))
}

/// Cells per axis of the report's winding-number volume (262,144 samples: a few tenths of a
/// per cent on a part that fills its box, a fraction of the meshing's time).
pub const REPORT_WINDING_CELLS: usize = 64;

/// Where the input volume is not exact, the report gets the winding number's volume.
fn add_winding_volume(report: &mut OctreeReport, oracle: &Winding) {
    if !report.input_volume_exact {
        report.winding_volume = winding_volume::winding_volume_of(oracle, REPORT_WINDING_CELLS);
    }
}

/// [`mesh_octree`] at cell size `h`, with the surface's oracle and whether it is a cycle
/// ([`rows::is_cycle`]) made once by the caller (`resolve.rs` meshes one surface at several
/// cells); `prepared` is the seconds that took, reported as the `winding_bvh` stage.
fn mesh_at(oracle: &Winding, cycle: bool, h: f64, opts: &OctreeOptions, prepared: f64) -> Result<(TetMesh, OctreeReport), OctreeError> {
    let surface = oracle.surface();
    let t_all = Instant::now();
    let mut stages = vec![("winding_bvh".to_string(), prepared)];
    let mut stage = |name: &str, t: &mut Instant| {
        stages.push((name.to_string(), t.elapsed().as_secs_f64()));
        *t = Instant::now();
    };
    let mut t = Instant::now();
    let lattice = Lattice::covering(&surface.bbox(), h)?;
    let n = lattice.num_vertices();
    let w = winding_at_lattice(&lattice, oracle);
    // the divergence theorem gives the stuffed volume where the winding number is 0 or 1
    let input_volume_exact = cycle && w.par_iter().all(|&x| x > -0.5 && x < 1.5);
    stage("winding", &mut t);
    // the input's feature edges (for the octree, snapping and the deviation) beside the cuts
    let (cuts, features) = rayon::join(
        || cut::cut_and_warp(&lattice, oracle, &w, opts.alpha_long, opts.alpha_short),
        || deviation::feature_edges_with_triangles(surface, opts.feature_angle_deg),
    );
    stage("cut_warp", &mut t);
    if !cuts.sign.contains(&-1) {
        return Err(OctreeError::Empty(h));
    }
    // a corner on the outer layer is on the box's faces
    let reaches_box = (0..lattice.num_corners() as u32).into_par_iter().any(|v| cuts.sign[v as usize] == -1 && lattice.on_outer_layer(v));
    let tree = (opts.grading == Grading::Graded).then(|| graded_octree(surface, &lattice, &cuts, &features, h, opts));
    if tree.is_some() {
        stage("octree", &mut t);
    }
    let (mut mesh, all_zero, coarse_tets, inner, minus) = fill(&lattice, tree.as_ref(), &cuts, oracle)?;
    stage("stencils", &mut t);
    mesh.boundary = boundary_faces(&mesh, &inner, &minus);
    stage("boundary", &mut t);
    let mut snapped = Snapped::default();
    if opts.snap {
        snapped = snap::snap_features(surface, oracle.bvh(), &mut mesh, h, opts.feature_angle_deg, &features);
        stage("snap", &mut t);
    }
    let coarsened = (tree.is_some() && opts.coarsen).then(|| {
        let c = coarsen::coarsen(&mut mesh);
        stage("coarsen", &mut t);
        c
    });
    let buried = buried::Buried::new(oracle, h / 16.0);
    // the cells are checked while the boundary is measured (both read the mesh), the tags
    // after
    let ((dev, nearest), valid) = rayon::join(|| deviation(surface, oracle.bvh(), &mesh, h, opts.feature_angle_deg, &features, Some(&buried)), || mesh.validate_cells());
    valid?;
    mesh.face_tags = tags::tags_of(surface, &nearest);
    mesh.face_names = surface.face_names.clone();
    mesh.validate_face_tags()?;
    stage("deviation_tags_validate", &mut t);
    // fixed chunks summed in order: the volume's last bits do not depend on the threads; the
    // extreme cosines folded and their angles taken once (the same bits as the tets' angles:
    // the angle is non-decreasing in the cosine), a degenerate tet counting as 0° and 180°
    let (lo_c, hi_c, flat, volume) = crate::quality::summary::chunked_reduce(
        mesh.tets.len(),
        (f64::INFINITY, f64::NEG_INFINITY, false, 0.0f64),
        |a, b| {
            mesh.tets[a..b].iter().fold((f64::INFINITY, f64::NEG_INFINITY, false, 0.0f64), |acc, t| {
                let p = t.map(|v| mesh.vertices[v as usize]);
                let volume = acc.3 + crate::quality::tetrahedron::tet_volume(&p);
                match tet_extreme_dihedral_cosines(&p) {
                    Some((lo, hi)) => (acc.0.min(lo), acc.1.max(hi), acc.2, volume),
                    None => (acc.0, acc.1, true, volume),
                }
            })
        },
        |acc, x| *acc = (acc.0.min(x.0), acc.1.max(x.1), acc.2 || x.2, acc.3 + x.3),
    );
    let (mut lo, mut hi) = (180.0f64, 0.0f64);
    if lo_c <= hi_c {
        let (a, b) = dihedrals_of_extreme_cosines(lo_c, hi_c);
        (lo, hi) = (lo.min(a), hi.max(b));
    }
    if flat {
        (lo, hi) = (lo.min(0.0), hi.max(180.0));
    }
    let input_volume = surface.signed_volume();
    stages.push(("total".to_string(), prepared + t_all.elapsed().as_secs_f64()));
    let report = OctreeReport {
        grading: if tree.is_some() { "graded" } else { "uniform" }.into(),
        solids: 1,
        empty_solids: Vec::new(),
        cell_size: h,
        lattice_vertices: n,
        cells_per_level: tree.as_ref().map(|t| t.cells_per_level()).unwrap_or_default(),
        coarse_tets,
        coarsened,
        crossing_edges: cuts.crossing_edges,
        cut_points: cuts.edges.len(),
        bisected_cut_points: cuts.bisected,
        warped_vertices: cuts.num_warped,
        snapped,
        all_zero_tets: all_zero,
        tets: mesh.tets.len(),
        nodes: mesh.vertices.len(),
        boundary_triangles: mesh.boundary.len(),
        promised_dihedral: [MIN_DIHEDRAL, MAX_DIHEDRAL],
        dihedral: [lo, hi],
        volume,
        input_volume,
        input_volume_exact,
        winding_volume: None,
        input_crossings: (dev.hausdorff_bound > h).then(|| oracle.meets().iter().filter(|l| !l.is_empty()).count()),
        turned_outward: false,
        reaches_box,
        overlap: None,
        cell_tries: Vec::new(),
        hausdorff_over_cell: dev.hausdorff / h,
        bound_over_cell: dev.hausdorff_bound / h,
        deviation: dev,
        stage_seconds: stages,
    };
    Ok((mesh, report))
}

/// The graded octree over `lattice` for `cuts`. With snapping on, a vertex warped within
/// reach of a feature edge counts as outside for the octree: snapping may move it, weighing
/// every tet at it, and where those are the uniform mesh's it decides as in uniform mode,
/// so the graded mesh keeps the uniform mesh's boundary.
fn graded_octree(surface: &TriSurface, lattice: &Lattice, cuts: &Cuts, features: &[deviation::Feature], h: f64, opts: &OctreeOptions) -> graded::Octree {
    let position = |v: u32| cuts.position(lattice, v);
    if !opts.snap || features.is_empty() {
        return graded::Octree::build(lattice, &cuts.sign, &position);
    }
    // (each vertex's answer is its own: the map's order does not matter)
    let warped: Vec<(u32, DVec3)> = cuts.warped.iter().map(|(&v, &p)| (v, p)).collect();
    let points: Vec<DVec3> = warped.iter().map(|w| w.1).collect();
    let mut sign = cuts.sign.clone();
    for (&(v, _), near) in warped.iter().zip(snap::within_reach(surface, features, h, &points)) {
        if near {
            sign[v as usize] = 1;
        }
    }
    graded::Octree::build(lattice, &sign, &position)
}

/// The stencils over every background tet (the lattice's, or the graded octree's when
/// `tree` is given); the result's vertices are the used lattice vertices (in lattice order)
/// then the used cut points (in edge order). Returns the mesh (no boundary yet), the number
/// of all-zero tets kept, the number of tets of coarse octree cells, and per output tet
/// whether it is a whole background tet of four inside vertices.
#[allow(clippy::type_complexity)]
fn fill(lattice: &Lattice, tree: Option<&graded::Octree>, cuts: &Cuts, oracle: &Winding) -> Result<(TetMesh, usize, usize, Vec<bool>, Vec<Minus>), OctreeError> {
    let nl = lattice.num_vertices() as u32;
    // per centre: the output tets as global corner ids (lattice id, or nl + cut index)
    // centres in runs of CENTRES_PER_TASK: one set of buffers per run, results in order
    const CENTRES_PER_TASK: usize = 512;
    let centres = lattice.num_centres();
    let chunks: Vec<(Vec<[u32; 4]>, [usize; 2], Vec<DVec3>, Vec<bool>, Vec<DVec3>)> = (0..centres.div_ceil(CENTRES_PER_TASK))
        .into_par_iter()
        .map(|run| {
            let mut background: Vec<graded::Background> = Vec::with_capacity(12);
            let mut bcc = Vec::with_capacity(12);
            let mut out = Vec::new();
            let mut local = Vec::new();
            let mut zero = 0;
            let mut coarse = 0;
            let mut bad = Vec::new();
            let mut inner = Vec::new();
            let mut missing = Vec::new();
            for i in run * CENTRES_PER_TASK..((run + 1) * CENTRES_PER_TASK).min(centres) {
                background.clear();
                match tree {
                    Some(tree) => tree.tets_of(lattice, i, &mut background),
                    None => {
                        bcc.clear();
                        lattice.tets_around(i, &mut bcc);
                        background.extend(bcc.iter().map(|&t| (t, true)));
                    }
                }
                for &(t, bcc) in &background {
                    let s = each4(t, |v| cuts.sign[v as usize]);
                    if s == [-1; 4] {
                        out.push(t);
                        inner.push(true);
                        coarse += usize::from(!bcc);
                        continue;
                    }
                    if !bcc {
                        // a coarse cell is deep (graded.rs): never cut, and its tets at
                        // vertices warped onto the surface are whole, positive and within
                        // the warped floor (the stencil of no vertex outside is the tet)
                        if s.contains(&1) || s == [0; 4] {
                            missing.push(lattice.position(t[0]));
                            continue;
                        }
                        let before = out.len();
                        push_checked(t, lattice, cuts, &mut out, &mut bad);
                        inner.resize(inner.len() + out.len() - before, false);
                        coarse += out.len() - before;
                        continue;
                    }
                    let before = out.len();
                    if s == [0; 4] {
                        // four vertices on the surface: kept when inside and not a sliver (flat
                        // on a flat piece of surface it holds no volume; across an edge it does)
                        let p = t.map(|v| cuts.position(lattice, v));
                        let c = (p[0] + p[1] + p[2] + p[3]) / 4.0;
                        let (lo, hi) = if orient3d(p[0], p[1], p[2], p[3]).is_positive() { tet_min_max_dihedral(&p) } else { (0.0, 180.0) };
                        if lo >= MIN_DIHEDRAL && hi <= MAX_DIHEDRAL && oracle.inside(c) {
                            zero += 1;
                            let before = out.len();
                            push_checked(t, lattice, cuts, &mut out, &mut bad);
                            inner.resize(inner.len() + out.len() - before, false);
                        }
                        continue;
                    }
                    local.clear();
                    let refs = each4(t, |v| lattice.coords(v));
                    stencil::stuff(s, refs, &mut local);
                    // `None` where a stencil asks for a cut point its edge lacks (our bug)
                    let global = |local: &[[Local; 4]]| -> Option<Vec<[u32; 4]>> {
                        local
                            .iter()
                            .map(|l| {
                                let mut g = [0u32; 4];
                                for (k, c) in l.iter().enumerate() {
                                    g[k] = match *c {
                                        Local::Vertex(k) => t[k as usize],
                                        Local::Cut(a, b) => nl + cuts.cut(t[a as usize], t[b as usize])?,
                                    };
                                }
                                Some(g)
                            })
                            .collect()
                    };
                    let Some(chosen) = global(&local) else {
                        missing.push(lattice.position(t[0]));
                        continue;
                    };
                    for g in chosen {
                        push_checked(g, lattice, cuts, &mut out, &mut bad);
                    }
                    inner.resize(inner.len() + out.len() - before, false);
                }
            }
            (out, [zero, coarse], bad, inner, missing)
        })
        .collect();
    if let Some(&at) = chunks.iter().find_map(|c| c.4.first()) {
        return Err(OctreeError::Internal(format!(
            "a stencil asked for a cut point on a lattice edge without one, or a coarse octree cell is cut, near ({:.6}, {:.6}, {:.6})",
            at.x, at.y, at.z
        )));
    }
    let bad: Vec<DVec3> = chunks.iter().flat_map(|c| c.2.iter().copied()).collect();
    if let Some(&at) = bad.first() {
        return Err(OctreeError::Inverted { count: bad.len(), at, h: lattice.h });
    }
    let zero = chunks.iter().map(|c| c.1[0]).sum();
    let coarse = chunks.iter().map(|c| c.1[1]).sum();
    let total: usize = chunks.iter().map(|c| c.0.len()).sum();
    let mut tets = Vec::with_capacity(total);
    let mut inner = Vec::with_capacity(total);
    for c in chunks {
        tets.extend(c.0);
        inner.extend(c.3);
    }
    // compact: used lattice vertices, then used cut points
    let mut map = vec![NONE; nl as usize + cuts.edges.len()];
    for t in &tets {
        for &v in t {
            map[v as usize] = 0;
        }
    }
    let mut vertices = Vec::new();
    let mut minus = Vec::new();
    for (v, m) in map.iter_mut().enumerate() {
        if *m == 0 {
            *m = vertices.len() as u32;
            vertices.push(corner_position(v as u32, lattice, cuts));
            minus.push(if v >= nl as usize || cuts.sign[v] != -1 {
                Minus::No
            } else if lattice.on_outer_layer(v as u32) {
                Minus::OnLatticeBoundary
            } else {
                Minus::Interior
            });
        }
    }
    tets.par_iter_mut().for_each(|t| *t = t.map(|v| map[v as usize]));
    let n = tets.len();
    Ok((TetMesh { vertices, tets, region_tags: vec![RegionId(1); n], ..TetMesh::default() }, zero, coarse, inner, minus))
}

/// The faces of one tet only, outward, in the order of their sorted vertices. Faces at a
/// lattice vertex inside (sign -1, never warped) whose background tets all lie in the
/// lattice are not sorted: such a vertex is interior to the mesh, since every background
/// tet at it is kept whole or stuffed with the part of it on the vertex's side of the cut
/// points, all at least `α` of an edge away, so no face at it is seen once. So a whole
/// background tet (`inner`, four inside vertices) is looked at only where it reaches the
/// lattice's outer layer: a surface that is not closed (a surface model) can have its
/// winding number above one half out there, and the mesh then ends at the lattice's faces.
fn boundary_faces(mesh: &TetMesh, inner: &[bool], minus: &[Minus]) -> Vec<[u32; 3]> {
    use crate::mesh::tet_mesh::TET_FACES;
    let records = || {
        mesh.tets.iter().zip(inner).filter(|(tet, inner)| !**inner || tet.iter().any(|&v| minus[v as usize] == Minus::OnLatticeBoundary)).flat_map(|(tet, _)| {
            TET_FACES.iter().filter_map(move |f| {
                let v = [tet[f[0]], tet[f[1]], tet[f[2]]];
                if v.iter().any(|&x| minus[x as usize] == Minus::Interior) {
                    return None;
                }
                let mut k = v;
                k.sort_unstable();
                Some((k, v))
            })
        })
    };
    let rec = crate::core::bucket_sort::collect_sorted_by_lead(mesh.vertices.len(), records, |r| r.0[0]);
    rec.chunk_by(|x, y| x.0 == y.0).filter_map(|run| if let [(_, v)] = run { Some(*v) } else { None }).collect()
}

/// Whether a mesh vertex is a lattice vertex inside (sign -1), and where: the boundary's
/// faces are sought only away from the interior ones.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
enum Minus {
    /// A cut point, or a lattice vertex on the surface (warped) or outside.
    No,
    /// Inside, on the lattice's outer layer (a surface that is not closed can have its
    /// winding number above one half there): the background tets around it stop at the
    /// lattice's faces.
    OnLatticeBoundary,
    /// Inside, with every background tet around it in the lattice.
    Interior,
}

use cut::Cuts;

/// The winding number at every lattice vertex: the integers of the surface closed into a
/// cycle by its cap ([`Winding::closed`]; the surface itself where it is one), counted along
/// the lattice's rows (`rows.rs`), less the cap's solid angle. A degenerate row sums the
/// solid angles at its vertices, with [`winding::BETA`] where a triangle's box comes within
/// a cell, [`winding::FAR_BETA`] farther.
fn winding_at_lattice(lattice: &Lattice, oracle: &Winding) -> Vec<f64> {
    let h = lattice.h;
    let (cycle, cap) = oracle.closed();
    let cap_at = |v: u32| cap.map_or(0.0, |c| c.at(lattice.position(v)));
    let one = |v: u32| {
        let q = lattice.position(v);
        let near = Aabb { min: q - DVec3::splat(h), max: q + DVec3::splat(h) };
        oracle.at_with(q, if oracle.bvh().any_overlapping(&near) { winding::BETA } else { winding::FAR_BETA }) + cap_at(v)
    };
    let mut w = rows::winding_by_rows(lattice, cycle, &one);
    if cap.is_some() {
        w.par_iter_mut().enumerate().for_each(|(v, x)| *x -= cap_at(v as u32));
    }
    w
}

/// The position of a global corner id (a lattice vertex, or the lattice count plus a cut
/// index).
fn corner_position(v: u32, lattice: &Lattice, cuts: &Cuts) -> DVec3 {
    let nl = lattice.num_vertices() as u32;
    if v < nl { cuts.position(lattice, v) } else { cuts.edges[(v - nl) as usize].1 }
}

/// Pushes `t` when it is positively oriented at the true positions (exact), else records
/// where it is.
fn push_checked(t: [u32; 4], lattice: &Lattice, cuts: &Cuts, out: &mut Vec<[u32; 4]>, bad: &mut Vec<DVec3>) {
    let p = each4(t, |v| corner_position(v, lattice, cuts));
    if orient3d(p[0], p[1], p[2], p[3]).is_positive() {
        out.push(t);
    } else {
        bad.push((p[0] + p[1] + p[2] + p[3]) / 4.0);
    }
}

/// `t.map(f)` for the stencils' inner loop, written out so that it is inlined whatever
/// the code units (`[T; N]::map` was left out of line there once, a third slower).
#[inline(always)]
fn each4<T: Copy, U>(t: [T; 4], f: impl Fn(T) -> U) -> [U; 4] {
    [f(t[0]), f(t[1]), f(t[2]), f(t[3])]
}

/// For serde: leaves a zero count out.
fn is_zero(n: &usize) -> bool {
    *n == 0
}

#[cfg(test)]
pub(crate) mod tests;
