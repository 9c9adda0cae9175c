//! Layer 4: B-rep → watertight tagged triangle surface.
//!
//! Stages: every edge is discretised once (`edge_points`: chord and angle criteria relative
//! to the model size), so two faces sharing an edge share its points and the surface is
//! watertight by construction; every face is then meshed in its parameter domain
//! (`face_mesh`): its loops are mapped to `(u, v)` (periodic parameters unwrapped along the
//! loop, so seams and closed edges become the two sides of a rectangle), a grid of interior
//! points is added where the surface curves (spacing from the chord tolerance and the
//! surface's second derivatives; points near a boundary segment are skipped, since spade
//! would split the constraint through them and break the edge sharing), spade's constrained Delaunay triangulation is built with the
//! loop segments as constraints, triangles outside the loops are removed (by the parity of constraint edges crossed from
//! the outside, exact where a point-in-polygon test fails on thin triangles), and the rest are
//! lifted to 3D, oriented by the face's sense and tagged with its [`FaceId`].
//!
//! Two loop segments of a face that cross in `(u, v)` although their edges do not meet (chords
//! of two close edges, which cut inside their curves by up to the chord tolerance) are found
//! with exact predicates (module `crossings`); those edge segments are split at their parameter
//! midpoints, on the shared edge points so both faces take the new points, and the faces are
//! meshed again (a few rounds at most).
//!
//! To a size field ([`tessellate_sized`]), faces narrower than the size ask for less
//! (`feature_size`), and so do walls of the solid thinner than a third of it, measured across
//! the solid on a first tessellation (`proximity`): the part is then tessellated again.
//!
//! Faces that cannot be meshed this way (a periodic face bounded by closed edges without a
//! seam, loops that still cross in parameter space) are listed in [`Tessellation::failed`],
//! never left out silently. The result is meant to be checked with [`crate::mesh::topology`].

pub mod certificate;
pub(crate) mod corner_strips;
mod brep_topology;
mod crossings;
pub(crate) mod edge_points;
pub(crate) mod edge_strip;
pub(crate) mod face_error;
pub(crate) mod face_mesh;
mod face_vertices;
mod flat_ears;
pub(crate) mod orient;
mod seams;
mod feature_size;
mod proximity;
pub(crate) mod quadrature;
pub(crate) mod reached;
mod improve;
mod refine;
mod sizing;
mod surface_scales;
mod uv_cdt;
mod uv_loops;
mod uv_polygon;
mod volume_chord;

#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_slender;

use crate::cad::brep::{EntityRef, Model};
use crate::core::{FaceId, FaceNames, SizeField};
use crate::mesh::TriSurface;
use edge_points::EdgePoints;
use glam::DVec3;
use face_vertices::FaceVertices;
use rayon::prelude::*;

/// Tessellation criteria.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct TessellateOptions {
    /// Largest distance between a segment or triangle and the exact geometry, as a fraction
    /// of the model size (default 2e-4). The vertices lie on the surface, so the mesh is
    /// inscribed and encloses less than the B-rep by about `(2/3) δ A` (δ this tolerance in
    /// mm, A the area): a relative volume error of `(2/3) δ A / V`. At 1e-3 that is 0.7 % for
    /// a cylinder of radius a sixth of the model size and 1.5 % for thin parts (the corpus's
    /// wing_fuselage.step, screw.step); 2e-4 keeps every closed corpus solid within 0.35 % of
    /// OpenCASCADE's volume at a tenth of a second or less per part.
    pub chord_relative: f64,
    /// Largest turn of the tangent along one edge segment, degrees (default 20).
    pub max_angle_deg: f64,
    /// Most interior grid points per face direction (default 200).
    pub max_grid: usize,
    /// The share of each closed solid's volume its chords may cut (default 4e-3): a solid
    /// whose triangles enclose a volume further off the B-rep's own (by quadrature) is
    /// tessellated again with its faces' chords shrunk in proportion (slender and thin parts,
    /// whose thickness is small against the model size; see `volume_chord`). 0 leaves the
    /// model-wide chord everywhere, as asked.
    pub volume_relative: f64,
}

impl Default for TessellateOptions {
    fn default() -> Self {
        TessellateOptions { chord_relative: 2e-4, max_angle_deg: 20.0, max_grid: 200, volume_relative: 4e-3 }
    }
}

impl TessellateOptions {
    /// Sets [`TessellateOptions::chord_relative`].
    pub fn with_chord_relative(mut self, r: f64) -> Self {
        self.chord_relative = r;
        self
    }

    /// Sets [`TessellateOptions::volume_relative`] (0: the model-wide chord everywhere, as
    /// asked).
    pub fn with_volume_relative(mut self, eta: f64) -> Self {
        self.volume_relative = eta;
        self
    }

    /// Sets [`TessellateOptions::max_angle_deg`].
    pub fn with_max_angle_deg(mut self, deg: f64) -> Self {
        self.max_angle_deg = deg;
        self
    }
}

/// A face the tessellator could not mesh.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct FailedFace {
    /// The face.
    pub face: FaceId,
    /// Its STEP entity.
    pub source: EntityRef,
    /// Why.
    pub why: String,
}

/// One face's parameter-domain triangulation, kept for the certificate's quadrature.
#[derive(Clone, Debug)]
pub struct FaceDomain {
    /// The face's triangles in [`Tessellation::surface`]: `triangles.start..triangles.end`.
    pub triangles: std::ops::Range<usize>,
    /// The triangles in `(u, v)` and the boundary segments (see `face_mesh::FaceMesh`).
    pub uv: Vec<[glam::DVec2; 3]>,
    /// Boundary segments, face on the left in `(u, v)`: global vertex ids and `(u, v)`.
    pub boundary: Vec<([u32; 2], [glam::DVec2; 2])>,
}

/// The result: the surface and the faces left out.
#[derive(Clone, Debug)]
pub struct Tessellation {
    /// Triangles tagged with their face; vertices shared along B-rep edges.
    pub surface: TriSurface,
    /// Faces that could not be meshed.
    pub failed: Vec<FailedFace>,
    /// The points of every B-rep edge (index = edge index of the model).
    pub edges: Vec<EdgePoints>,
    /// Per face (index `FaceId - 1`), its domain triangulation; `None` for a failed face.
    pub domains: Vec<Option<FaceDomain>>,
    /// The model-wide chord tolerance (`chord_relative` times the model size), mm.
    pub chord: f64,
    /// The chord asked of each face (index `FaceId - 1`), mm: `chord`, or less on slender
    /// and thin solids ([`TessellateOptions::volume_relative`]).
    pub face_chords: Vec<f64>,
    /// Per face (index `FaceId - 1`), the B-rep's own area and volume term over its domain
    /// (`quadrature::surface_integrals` about the centre of the model's bounds) where the
    /// volume check computed them for this tessellation; the certificate computes the rest.
    pub quadrature: Vec<Option<quadrature::FaceIntegrals>>,
}

/// Tessellates every face of `model` by the chord and angle criteria: triangles follow the
/// surface within the chord but may be long and thin (a tessellation for display, volume and
/// area).
pub fn tessellate(model: &Model, opts: &TessellateOptions) -> Tessellation {
    tessellate_with(model, opts, None)
}

/// Tessellates every face of `model` to a size field: edges are spaced by it and faces
/// refined to well-shaped triangles of the local size (angles of 25° and more away from small
/// input angles), never coarser than the chord and angle criteria allow. What a volume mesher
/// wants as its boundary.
pub fn tessellate_sized(model: &Model, opts: &TessellateOptions, size: &dyn SizeField) -> Tessellation {
    tessellate_with(model, opts, Some(size))
}

fn tessellate_with(model: &Model, opts: &TessellateOptions, size: Option<&dyn SizeField>) -> Tessellation {
    let t = tessellate_volume(model, opts, size, &[]);
    // to a size: walls of the solid thinner than a third of it (measured across the solid on
    // this tessellation) ask for less, and the model is tessellated again
    let Some(h) = size else { return t };
    let walls = proximity::wall_samples(&t.surface, h, t.chord);
    if walls.is_empty() {
        return t;
    }
    tessellate_volume(model, opts, size, &walls)
}

/// [`tessellate_with`] without the walls' sizes: by the chord, angle and size criteria, again
/// with smaller chords on solids whose volume falls short.
fn tessellate_volume(model: &Model, opts: &TessellateOptions, size: Option<&dyn SizeField>, walls: &[(DVec3, f64)]) -> Tessellation {
    let tol = opts.chord_relative * model.size();
    let uniform = vec![tol; model.faces.len()];
    if !(opts.volume_relative > 0.0) {
        return tessellate_chords(model, opts, size, walls, tol, &uniform);
    }
    // solids that lose more than `volume_relative` of their volume: again with smaller
    // chords on their faces (see `volume_chord`), aiming at three quarters of it; with a
    // size field just under it (chords finer than the size make thin triangles beside it)
    let aim = if size.is_some() { 0.9 } else { 0.75 };
    let mut chords = uniform;
    let mut t = tessellate_chords(model, opts, size, walls, tol, &chords);
    let mut prev_loss = Vec::new();
    for _ in 0..volume_chord::ROUNDS {
        let (next, quadrature) = volume_chord::shrink_chords(model, &t, &chords, tol, opts.volume_relative, aim, &mut prev_loss);
        let Some(next) = next else {
            t.quadrature = quadrature;
            break;
        };
        chords = next;
        t = tessellate_chords(model, opts, size, walls, tol, &chords);
    }
    t
}

/// Tessellates with the chord `face_chord[f]` on face `f` (its edges: the smallest of their
/// faces'), `tol` the model-wide chord; with a size, `walls` are the sizes the solid's
/// thickness asks for (`proximity`).
fn tessellate_chords(model: &Model, opts: &TessellateOptions, size: Option<&dyn SizeField>, walls: &[(DVec3, f64)], tol: f64, face_chord: &[f64]) -> Tessellation {
    let model_size = model.size();
    let edge_chord = volume_chord::edge_chords(model, face_chord, tol);
    let mut vertices: Vec<DVec3> = model.vertices.iter().map(|v| v.point).collect();
    // straight edges bounding a curved face: pieces of at most sqrt(8 tol size) / 4, the
    // grid spacing of a face curved with radius size / 16
    let mut on_curved = vec![false; model.edges.len()];
    for face in &model.faces {
        if !matches!(model.surface(face.surface), crate::cad::geom::Surface::Plane(_)) {
            for &l in &face.loops {
                for c in &model.loops[l as usize].coedges {
                    on_curved[c.edge as usize] = true;
                }
            }
        }
    }
    let max_straight = (8.0 * tol * model_size).sqrt() / 4.0;
    let discretise = |size: Option<&dyn SizeField>, strips: &[edge_strip::EdgeStrip], vertices: &mut Vec<DVec3>| -> Vec<EdgePoints> {
        model
            .edges
            .iter()
            .enumerate()
            .zip(&on_curved)
            .zip(&edge_chord)
            .map(|(((i, e), &curved), &chord)| {
                let straight = if curved { max_straight } else { 0.0 };
                edge_points::discretise(model, e, chord, opts.max_angle_deg, straight, size, strips.get(i), vertices)
            })
            .collect()
    };
    // to a size: faces narrower than it (strips, chamfers, holes near a side) ask for less,
    // measured on the chords of the edges, and so do the strips at small corners of a face
    // (`corner_strips`), whose points face each other across them
    let narrow;
    let mut strips = Vec::new();
    let size: Option<&dyn SizeField> = match size {
        Some(h) => {
            let mut chords = vertices.clone();
            let edges = discretise(None, &[], &mut chords);
            let widths = feature_size::FeatureSize::new(model, &edges, &chords, h, walls);
            let found = corner_strips::corner_strips(model, &edges, &chords, &widths, tol);
            narrow = widths.with_samples(found.samples);
            strips = found.edges;
            Some(&narrow)
        }
        None => None,
    };
    let mut edges = discretise(size, &strips, &mut vertices);
    edge_points::through_poles(model, &mut edges, &mut vertices);
    split_digons(model, &mut edges, &mut vertices);
    // boundary segments that cross in a face's (u, v) are split on their edges (shared by the
    // faces on both sides, so the surface stays watertight) and the faces on a split edge
    // meshed again: the others have the same edge points, so the same mesh (kept, their own
    // points renumbered after the new edge points)
    let mut each: Vec<Option<FaceResult>> = vec![None; model.faces.len()];
    let edge_faces = model.edge_faces();
    let mut round = 0;
    loop {
        let edge_vertices = vertices.len();
        let mut meshed = mesh_faces(model, &edges, tol, face_chord, max_straight, opts, size, &mut each, &mut vertices);
        if meshed.split.iter().all(Vec::is_empty) || round == SPLIT_ROUNDS {
            let Meshed { triangles, face_tags, face_names, failed, domains, .. } = meshed;
            return Tessellation { surface: TriSurface { vertices, triangles, face_tags, face_names }, failed, edges, domains, chord: tol, face_chords: face_chord.to_vec(), quadrature: vec![None; model.faces.len()] };
        }
        // the faces' interior vertices go: the next round makes them again, or renumbers them
        vertices.truncate(edge_vertices);
        for (e, ks) in meshed.split.iter_mut().enumerate() {
            if !ks.is_empty() {
                edge_points::split_segments(model, &model.edges[e], &mut edges[e], ks, &mut vertices);
                for &f in &edge_faces[e] {
                    each[f as usize] = None;
                }
            }
        }
        round += 1;
    }
}

/// A loop of two edges (a lens: a sliver face between two curves that meet at both ends)
/// whose edges are one segment each would be the same segment twice, with no triangle
/// between: each such edge is split at its middle. Sizing coarsens a short curve that is
/// straight within the chord to one piece (a 0.3 mm lens on a cylinder of a real part).
fn split_digons(model: &Model, edges: &mut [EdgePoints], vertices: &mut Vec<DVec3>) {
    for face in &model.faces {
        for &l in &face.loops {
            let lp = &model.loops[l as usize];
            let [a, b] = match lp.coedges.as_slice() {
                [a, b] => [a.edge as usize, b.edge as usize],
                _ => continue,
            };
            if a == b || [a, b].iter().any(|&e| edges.get(e).is_none_or(|ep| ep.ids.len() != 2)) {
                continue;
            }
            for e in [a, b] {
                edge_points::split_segments(model, &model.edges[e], &mut edges[e], &mut [0], vertices);
            }
        }
    }
}

/// One face's mesh, its own points, and the number of shared points (the model's vertices and
/// edge points) its own ids were counted after.
#[derive(Clone)]
struct FaceResult {
    mesh: Result<face_mesh::FaceMesh, face_error::FaceError>,
    own: Vec<DVec3>,
    shared: usize,
}

/// Most rounds of splitting edge segments that cross in a face's parameter domain (each
/// halves them: at most 64 times finer there).
const SPLIT_ROUNDS: usize = 6;

/// Every face meshed on the given edge points, and per edge the segments (index `k`: between
/// its points `k` and `k + 1`) to split because they cross another boundary segment of a face.
struct Meshed {
    triangles: Vec<[u32; 3]>,
    face_tags: Vec<FaceId>,
    face_names: FaceNames,
    failed: Vec<FailedFace>,
    domains: Vec<Option<FaceDomain>>,
    split: Vec<Vec<usize>>,
}

#[allow(clippy::too_many_arguments)]
fn mesh_faces(
    model: &Model,
    edges: &[EdgePoints],
    tol: f64,
    face_chord: &[f64],
    max_straight: f64,
    opts: &TessellateOptions,
    size: Option<&dyn SizeField>,
    each: &mut [Option<FaceResult>],
    vertices: &mut Vec<DVec3>,
) -> Meshed {
    // edge segments by their end vertices
    let mut segment: rustc_hash::FxHashMap<(u32, u32), (usize, usize)> = rustc_hash::FxHashMap::default();
    for (e, ep) in edges.iter().enumerate() {
        for (k, w) in ep.ids.windows(2).enumerate() {
            if w[0] != w[1] {
                segment.insert((w[0].min(w[1]), w[0].max(w[1])), (e, k));
            }
        }
    }
    let mut out = Meshed { triangles: Vec::new(), face_tags: Vec::new(), face_names: FaceNames::new(), failed: Vec::new(), domains: Vec::with_capacity(model.faces.len()), split: vec![Vec::new(); edges.len()] };
    // the faces side by side, each on the shared edge points with its own new points; then
    // gathered in face order, own points numbered after the points before them: the same
    // ids, and bits, as one face after the other
    let shared = vertices.len();
    let faces: Vec<FaceId> = model.face_ids().collect();
    let todo: Vec<usize> = (0..faces.len()).filter(|&k| each.get(k).is_none_or(Option::is_none)).collect();
    let meshes: Vec<FaceResult> = todo
        .par_iter()
        .map(|&k| {
            let fid = faces[k];
            let chord = fid.index().and_then(|k| face_chord.get(k)).copied().unwrap_or(tol);
            let mut own = FaceVertices::new(vertices);
            let mesh = face_mesh::mesh_face(model, fid, edges, chord, max_straight, opts, size, &mut own);
            FaceResult { mesh, own: own.into_own(), shared }
        })
        .collect();
    for (k, r) in todo.into_iter().zip(meshes) {
        if let Some(slot) = each.get_mut(k) {
            *slot = Some(r);
        }
    }
    for (k, &fid) in faces.iter().enumerate() {
        // kept for a later round: the mesh is copied out, the points read in place
        let Some(FaceResult { mesh, own, shared: counted }) = each.get(k).and_then(Option::as_ref) else { continue };
        let face = model.face(fid);
        let start = vertices.len();
        let id = |i: u32| FaceVertices::renumber(i, *counted, start);
        vertices.extend_from_slice(own);
        let r = mesh.clone().map(|mut fm| {
            for t in &mut fm.triangles {
                *t = t.map(id);
            }
            for (ab, _) in &mut fm.boundary {
                *ab = ab.map(id);
            }
            fm
        });
        match r {
            Ok(fm) => {
                let start = out.triangles.len();
                out.face_tags.extend(std::iter::repeat_n(fid, fm.triangles.len()));
                out.triangles.extend(fm.triangles);
                if let Some(n) = &face.name {
                    out.face_names.insert(fid, n.clone());
                }
                out.domains.push(Some(FaceDomain { triangles: start..out.triangles.len(), uv: fm.uv, boundary: fm.boundary }));
            }
            Err(why) => {
                if let face_error::FaceError::Crossing(segs) = &why {
                    for &[a, b] in segs {
                        let (a, b) = (id(a), id(b));
                        if let Some(&(e, k)) = segment.get(&(a.min(b), a.max(b))) {
                            out.split[e].push(k);
                        }
                    }
                }
                out.failed.push(FailedFace { face: fid, source: face.source, why: why.to_string() });
                out.domains.push(None);
            }
        }
    }
    out
}
