//! The quality of a meshed part as reports give it, and the requirements checked on it.
//!
//! Every run gives the summary: counts, dihedral angles, radius-edge ratios, the tets under 5°
//! and 1°, near-degenerate tets, where the worst tet sits (its centroid, the nearest CAD face
//! or input tag, the nearest feature edge, the small input angle in its reach) and whether
//! refinement or the optimisation stopped at a budget. A requirement that fails is an error
//! naming the same place.

use super::PipelineError;
use super::plan::Plan;
use crate::cad::brep::FaceEntry;
use crate::core::FaceId;
use crate::mesh::{TetMesh, TriSurface};
use crate::mesh3d::mesher::{MeshReport, RefinementStop};
use crate::quality::explained::{Explained, explained_among};
use crate::quality::extremes::{TetExtremes, tet_mesh_extremes};
use crate::quality::input_angles::{InputAngle, small_input_angles};
use crate::quality::tetrahedron::tet_radius_edge;
use crate::quality::worst_tet::{BoundaryIndex, TetPlace, fmt_num};
use serde::Serialize;
use std::path::Path;

/// The quality of a tet mesh, as reports give it.
#[derive(Clone, Debug, Default, Serialize)]
pub struct MeshSummary {
    /// Nodes.
    pub nodes: usize,
    /// Tets.
    pub tets: usize,
    /// Regions.
    pub regions: usize,
    /// Volume.
    pub volume: f64,
    /// The CAD solids' own volume (the B-rep's, by quadrature), for a CAD part.
    pub cad_volume: Option<f64>,
    /// `volume / cad_volume − 1`: what the tessellation's chords cut off curved faces (negative)
    /// or add.
    pub volume_error: Option<f64>,
    /// Smallest dihedral angle, degrees.
    pub min_dihedral_deg: f64,
    /// Largest dihedral angle, degrees.
    pub max_dihedral_deg: f64,
    /// Largest radius-edge ratio.
    pub max_radius_edge: f64,
    /// Tets with a dihedral angle under 5°.
    pub tets_under_5_deg: usize,
    /// Tets with a dihedral angle under 1°.
    pub tets_under_1_deg: usize,
    /// Of the tets under 5°, those that touch no input angle under 5° (see
    /// `crate::quality::worst_tet::touches_angle_below`): the ones the input does not explain.
    pub tets_under_5_deg_unexplained: usize,
    /// Of the tets under 1°, those that touch no input angle under 1°.
    pub tets_under_1_deg_unexplained: usize,
    /// Tets with a dihedral angle under 10°.
    pub tets_under_10_deg: usize,
    /// Of the tets under 10°, those that touch no input angle under 10°.
    pub tets_under_10_deg_unexplained: usize,
    /// Tets with a dihedral angle under [`MeshSummary::input_angle_bound_deg`] (the angle
    /// required, else the one aimed at).
    pub tets_under_bound: usize,
    /// Of those, the ones that touch no input angle under that bound: where the mesh falls
    /// short of it and the input does not explain why.
    pub tets_under_bound_unexplained: usize,
    /// Of the tets under 10° that touch no input angle under 10°, those that lie between the
    /// two sides of one, off its vertex or edge (a thin wedge, a sliver face, a knife edge:
    /// `crate::quality::between_sides`). Counted apart: they are in
    /// `tets_under_10_deg_unexplained` too.
    pub tets_under_10_deg_between_sides: usize,
    /// Likewise of `tets_under_bound_unexplained`.
    pub tets_under_bound_between_sides: usize,
    /// Near-degenerate tets (volume-length ratio under
    /// `crate::quality::mesh_quality::NEAR_DEGENERATE_VOLUME_LENGTH`).
    pub near_degenerate: usize,
    /// Refinement stopped at its budget before every tet met the radius-edge bound.
    pub refinement_stopped: bool,
    /// Which budget stopped it, when one did.
    pub refinement_stop: Option<RefinementStop>,
    /// The radius-edge bound refinement aimed at.
    pub radius_edge_bound: f64,
    /// Tets above it in the result.
    pub tets_above_radius_edge_bound: usize,
    /// The optimisation stopped at its budget of attempts.
    pub optimize_out_of_attempts: bool,
    /// Attempts the optimisation made.
    pub optimize_attempts: usize,
    /// Input angles are listed below this (degrees): the required smallest dihedral angle,
    /// else the one the optimisation aimed at.
    pub input_angle_bound_deg: f64,
    /// Input angles (dihedral and corner) below that bound.
    pub small_input_angles: usize,
    /// The smallest of them.
    pub smallest_input_angle: Option<InputAngle>,
    /// The tet with the smallest dihedral angle, and where it sits.
    pub worst_tet: Option<TetPlace>,
    /// Of the tets under 1° that touch no input angle under 1°, the one with the smallest
    /// angle, and where it sits: what fails a run that did not set its own requirement.
    pub worst_unexplained_tet: Option<TetPlace>,
    /// Of the tets under 10° that touch no input angle under 10°, the one with the smallest
    /// angle, and where it sits (the input angle it lies between the sides of, if any): where
    /// the solver-grade rule's "every angle ≥ 10° but at small input angles" fails.
    pub worst_unexplained_tet_under_10_deg: Option<TetPlace>,
    /// Likewise under the bound ([`MeshSummary::input_angle_bound_deg`]): named by a failed
    /// `--require-min-dihedral` where the worst tet itself is explained.
    pub worst_unexplained_tet_under_bound: Option<TetPlace>,
    /// Input triangles that were caps (flat up to rounding, a vertex on their long side),
    /// each repaired with its neighbour before meshing.
    pub input_caps_repaired: usize,
    /// The strips narrower than the narrow tolerance closed up before meshing (a sliver face,
    /// a step between two faces that almost meet), where there were any.
    pub narrow: Option<crate::mesh::narrow::NarrowReport>,
    /// The most the volume can differ from the input's by merging nearly flat input triangles
    /// into facets (TetGen's `-p` rule, 0.1 degrees); zero for exactly flat ones.
    pub flattening_volume: f64,
    /// An assembly's: the most imprinting its solids on each other moved their volumes
    /// (summed over the solids).
    pub imprint_volume: f64,
    /// An assembly's: groups of faces in contact, and of them those imprinted (conforming).
    pub imprinted: Option<(usize, usize)>,
}

impl MeshSummary {
    /// Whether merging the input's flat facets moved the volume measurably (by more than 1e-9
    /// of it): the text report then says by how much.
    pub fn flattening_moved_volume(&self) -> bool {
        self.flattening_volume > 1e-9 * self.volume.abs()
    }
}

/// The summary of `mesh` (made from `surface` with `plan`, `report` the mesher's), and the
/// indexes a requirement error needs again.
pub(crate) struct Summarised {
    /// The summary.
    pub summary: MeshSummary,
    quality: TetExtremes,
    boundary: BoundaryIndex,
    angles: Vec<InputAngle>,
    /// The bound `angles` are under.
    bound: f64,
}

/// Summarises a meshed part. `face_table` names the faces (unique names, as the writers give
/// them); a tag not in it keeps the mesh's own name.
pub(crate) fn summarise(mesh: &TetMesh, surface: Option<&TriSurface>, report: &MeshReport, plan: &Plan, face_table: &[FaceEntry], cad_volume: Option<f64>) -> Summarised {
    let bound = plan.require_min_dihedral.unwrap_or(plan.mesh.min_dihedral);
    // the angles of the surface the mesher took: where it repaired caps or closed narrow
    // strips, prepared the same way (their zero angles are gone); found while the tets are
    // judged
    let prepared = surface.and_then(|s| crate::mesh3d::mesher::prepared_surface(s, report));
    let surface = prepared.as_deref().or(surface);
    let r_bound = plan.mesh.max_radius_edge;
    // the tets' pass (in parallel) beside the input's angles and the boundary's index, each
    // on one thread
    let (q, (angles, boundary)) = rayon::join(
        || tet_mesh_extremes(mesh, bound, r_bound),
        || rayon::join(|| surface.map(|s| small_input_angles(s, bound, !plan.mesh.keep_surface)).unwrap_or_default(), || BoundaryIndex::new(mesh)),
    );
    let name = namer(mesh, face_table);
    let worst_tet = q.min_dihedral.1.map(|t| boundary.locate(mesh, t, &angles, bound, &name));
    // a second pass over the tets, with the input angles under 10° as well where the bound is
    // lower
    let mut angles_10 = None;
    let counts = if !(q.min_dihedral.0 < bound.max(10.0)) {
        Explained::default()
    } else if bound >= 10.0 && angles.is_empty() {
        // no input angle under the bound: no tet touches one, the quality pass counted them
        let under = [q.under[0], q.under[1], q.under[2], q.under_dihedral].map(|n| (n, n));
        let worst = [1.0, 5.0, 10.0, bound].map(|limit| q.min_dihedral.1.filter(|_| q.min_dihedral.0 < limit).map(|t| (q.min_dihedral.0, t)));
        Explained { under, between: [0, 0], worst }
    } else if bound >= 10.0 {
        explained_among(mesh, Some(&q.low), boundary.sides(), &angles, bound)
    } else {
        let a10 = angles_10.insert(surface.map(|s| small_input_angles(s, 10.0, !plan.mesh.keep_surface)).unwrap_or_default());
        explained_among(mesh, Some(&q.low), boundary.sides(), a10, bound)
    };
    // most often the worst tet itself, already located
    let place = |found: Option<(f64, usize)>, angles: &[InputAngle], limit: f64| {
        found.map(|(_, t)| match &worst_tet {
            Some(w) if w.tet == t && limit == bound => w.clone(),
            _ => boundary.locate(mesh, t, angles, limit, &name),
        })
    };
    let worst_unexplained_tet = place(counts.worst[0], &angles, bound);
    let worst_unexplained_tet_under_10_deg = place(counts.worst[2], angles_10.as_deref().unwrap_or(&angles), 10.0);
    let worst_unexplained_tet_under_bound = place(counts.worst[3], &angles, bound);
    let above = q.above_radius_edge;
    let opt = report.optimize.as_ref();
    let volume = mesh.volume();
    let summary = MeshSummary {
        nodes: mesh.vertices.len(),
        tets: mesh.tets.len(),
        regions: report.regions,
        volume,
        cad_volume,
        volume_error: cad_volume.filter(|v| *v > 0.0).map(|v| volume / v - 1.0),
        min_dihedral_deg: q.min_dihedral.0,
        max_dihedral_deg: q.max_dihedral.0,
        max_radius_edge: q.max_radius_edge.0,
        tets_under_5_deg: q.under[1],
        tets_under_1_deg: q.under[0],
        tets_under_5_deg_unexplained: counts.under[1].1,
        tets_under_1_deg_unexplained: counts.under[0].1,
        tets_under_10_deg: counts.under[2].0,
        tets_under_10_deg_unexplained: counts.under[2].1,
        tets_under_bound: counts.under[3].0,
        tets_under_bound_unexplained: counts.under[3].1,
        tets_under_10_deg_between_sides: counts.between[0],
        tets_under_bound_between_sides: counts.between[1],
        near_degenerate: q.near_degenerate,
        refinement_stopped: report.refinement_stopped,
        refinement_stop: report.refinement_stop.clone(),
        radius_edge_bound: r_bound,
        tets_above_radius_edge_bound: above,
        optimize_out_of_attempts: opt.is_some_and(|o| o.out_of_attempts),
        optimize_attempts: opt.map_or(0, |o| o.attempts),
        input_angle_bound_deg: bound,
        small_input_angles: angles.len(),
        smallest_input_angle: angles.first().cloned(),
        worst_tet,
        worst_unexplained_tet,
        worst_unexplained_tet_under_10_deg,
        worst_unexplained_tet_under_bound,
        input_caps_repaired: report.input_caps_repaired,
        narrow: report.narrow.clone(),
        flattening_volume: report.flattening_volume,
        imprint_volume: report.imprint_volume,
        imprinted: report.imprinted,
    };
    Summarised { summary, quality: q, boundary, angles, bound }
}

/// Names a face tag: the face table's unique name, else the mesh's.
fn namer<'a>(mesh: &'a TetMesh, face_table: &'a [FaceEntry]) -> impl Fn(FaceId) -> Option<String> + 'a {
    move |f: FaceId| match face_table.iter().find(|e| e.face == f) {
        Some(e) => e.name.clone(),
        None => mesh.face_names.get(f).map(str::to_string),
    }
}

impl Summarised {
    /// Checks the requirements of `plan`; the error names the worst tet's place.
    ///
    /// # Errors
    /// [`PipelineError::Requirement`] for the first requirement not met.
    pub(crate) fn check(&self, path: &Path, mesh: &TetMesh, plan: &Plan, face_table: &[FaceEntry]) -> Result<(), PipelineError> {
        let s = &self.summary;
        if let Some(d) = plan.require_min_dihedral {
            if !(s.min_dihedral_deg >= d) {
                let head = format!(
                    "the smallest dihedral angle is {}°, below the {d}° required ({} tets under 5°, {} under 1°); nothing written",
                    fmt_num(s.min_dihedral_deg),
                    s.tets_under_5_deg,
                    s.tets_under_1_deg
                );
                let mut message = with_place(head, s.worst_tet.as_ref());
                // the worst tet at a small input angle: the worst one the input does not
                // explain is what a better mesh could change
                if let Some(u) = s.worst_unexplained_tet_under_bound.as_ref().filter(|u| s.worst_tet.as_ref().is_none_or(|w| w.tet != u.tet)) {
                    message.push_str(&format!("\n  {} tets under {d}° touch no input angle as small; the worst of them:", s.tets_under_bound_unexplained));
                    for (i, (label, text)) in u.lines().into_iter().enumerate() {
                        let label = if i == 0 { "unexplained tet" } else { label };
                        message.push_str(&format!("\n  {label:<14} {text}"));
                    }
                }
                return Err(PipelineError::Requirement { path: path.to_path_buf(), requirement: crate::pipeline::Requirement::MinDihedral, found: s.min_dihedral_deg, required: d, message });
            }
        } else if s.tets_under_1_deg_unexplained > 0 {
            // the default requirement: no tet under 1° that no input angle under 1° explains
            let head = format!(
                "{} tets have a dihedral angle under 1° and touch no input angle under 1° (the smallest {}°; {} tets under 1° in all): a solver would get near-singular elements; nothing written (--require-min-dihedral 0 writes the mesh as it is)",
                s.tets_under_1_deg_unexplained,
                fmt_num(s.worst_unexplained_tet.as_ref().map_or(0.0, |w| w.min_dihedral_deg)),
                s.tets_under_1_deg
            );
            return Err(PipelineError::Requirement { path: path.to_path_buf(), requirement: crate::pipeline::Requirement::NoUnexplainedSliver, found: s.worst_unexplained_tet.as_ref().map_or(0.0, |w| w.min_dihedral_deg), required: 1.0, message: with_place(head, s.worst_unexplained_tet.as_ref()) });
        }
        if let (Some(r), Some(e), Some(v)) = (plan.require_volume_error, s.volume_error, s.cad_volume) {
            if !(e.abs() <= r) {
                let head = format!(
                    "the mesh's volume {} is {:+.3}% off the CAD solids' {} (more than the {} required): the tessellation's chords cut the curved faces; give a smaller size, a curvature size or a smaller deviation; nothing written",
                    fmt_num(s.volume),
                    100.0 * e,
                    fmt_num(v),
                    fmt_num(r)
                );
                return Err(PipelineError::Requirement { path: path.to_path_buf(), requirement: crate::pipeline::Requirement::VolumeError, found: e, required: r, message: head });
            }
        }
        if let Some(r) = plan.require_max_radius_edge {
            if !(self.quality.max_radius_edge.0 <= r) {
                let name = namer(mesh, face_table);
                let place = self.quality.max_radius_edge.1.map(|t| self.boundary.locate(mesh, t, &self.angles, self.bound, &name));
                let over = mesh.tets.iter().filter(|t| !(tet_radius_edge(&t.map(|v| mesh.vertices[v as usize])) <= r)).count();
                let head = format!("the largest radius-edge ratio is {}, above the {r} required ({over} tets above it); nothing written", fmt_num(self.quality.max_radius_edge.0));
                return Err(PipelineError::Requirement { path: path.to_path_buf(), requirement: crate::pipeline::Requirement::MaxRadiusEdge, found: self.quality.max_radius_edge.0, required: r, message: with_place(head, place.as_ref()) });
            }
        }
        Ok(())
    }
}

/// `head`, then the place's lines, indented.
fn with_place(head: String, place: Option<&TetPlace>) -> String {
    let mut m = head;
    for (label, text) in place.map(TetPlace::lines).unwrap_or_default() {
        m.push_str(&format!("\n  {label:<14} {text}"));
    }
    m
}
