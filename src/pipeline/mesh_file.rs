//! `fepre mesh` as a library call: a file (a surface mesh or a STEP part) read, meshed with a
//! [`Plan`], its requirements checked, the tet mesh written, and the report the command
//! prints, warnings included.

use super::PipelineError;
use super::assembly::ContactReport;
use super::part::{Part, StageSeconds};
use super::run::{MeshSummary, Plan, run_plan_to};
use super::warning::Warning;
use crate::cad::brep::FaceEntry;
use crate::io::Format;
use crate::mesh3d::mesher::MeshReport;
use crate::mesh3d::octree::OctreeReport;
use serde::Serialize;
use std::path::Path;

/// What meshing a file made: the report `fepre mesh --json` prints.
#[derive(Clone, Debug, Serialize)]
pub struct MeshFileReport {
    /// The input file.
    pub input: String,
    /// The tet mesh written.
    pub output: String,
    /// Seconds in all (the stages once each where they ran beside each other).
    pub seconds: f64,
    /// Seconds reading the input.
    pub read_seconds: f64,
    /// Counts, quality, the worst tet's place, refinement and optimisation budgets.
    #[serde(flatten)]
    pub summary: MeshSummary,
    /// Steiner points the mesher put on the boundary.
    pub boundary_steiner_points: usize,
    /// The global size, in part units.
    pub global_size: f64,
    /// Per boundary face tag: unique name (and for STEP parts colour, STEP `#id`, solid).
    pub face_table: Vec<FaceEntry>,
    /// What the mesher did.
    pub mesher: MeshReport,
    /// Faces of different solids that touch (several solids).
    pub contacts: Vec<ContactReport>,
    /// What the octree mesher did (method octree).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub octree: Option<OctreeReport>,
    /// Faces of open surface-model shells beside the solids, left out of the mesh.
    pub open_surface_faces: usize,
    /// What the run made but would rather not have.
    pub warnings: Vec<Warning>,
    /// Seconds per stage (the text report's; the JSON gives `seconds` and `read_seconds`).
    #[serde(skip)]
    pub stage_seconds: StageSeconds,
}

/// Meshes the file at `input` with `plan` and writes the tet mesh to `output` (its extension
/// picks the format: .mesh, .ele/.node, .vtu, .msh); nothing is written when a requirement
/// fails.
///
/// # Errors
/// [`PipelineError::Usage`] for an output format that cannot hold tets (before anything is
/// read); an unreadable, open, non-manifold or self-intersecting surface, a failed
/// certificate, a mesher error, a requirement not met, a failed write.
pub fn mesh_file(input: &Path, plan: &Plan, output: &Path) -> Result<MeshFileReport, PipelineError> {
    if !matches!(Format::from_path(output), Some(Format::Medit | Format::TetGen | Format::Vtu | Format::Msh)) {
        return Err(PipelineError::Usage { path: output.to_path_buf(), problem: super::UsageProblem::TetFormat });
    }
    let mut part = Part::open(input)?;
    let report = run_plan_to(&mut part, plan, output)?;
    let mesher = report.mesher.unwrap_or_default();
    Ok(MeshFileReport {
        input: input.display().to_string(),
        output: output.display().to_string(),
        seconds: part.seconds.total(),
        read_seconds: part.seconds.read,
        summary: report.mesh.unwrap_or_default(),
        boundary_steiner_points: mesher.boundary_steiner_points,
        global_size: report.global_size,
        face_table: report.face_table,
        mesher,
        contacts: report.contacts,
        octree: report.octree,
        open_surface_faces: part.open_surface_faces,
        warnings: report.warnings,
        stage_seconds: part.seconds.clone(),
    })
}
