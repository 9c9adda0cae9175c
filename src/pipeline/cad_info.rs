//! `fepre cad-info` as a library call: what fepre reads from a STEP file (solids, shells,
//! faces, edges and vertices, units, faces per surface kind, every item left out with the
//! reason) and, asked for, its surface tessellated by the pipeline's one path
//! ([`super::tessellate_model`]). A file of tessellated geometry only is reported with its
//! triangles certified as a mesh.

use super::PipelineError;
use super::tessellated::{MeshCertificate, TessellatedSummary, certify_surface};
use super::warning::Warning;
use crate::cad::brep::{Dropped, Summary, Units};
use crate::cad::step::{self, TessellatedFace, TessellatedSolid};
use crate::tessellate::certificate::CertifyOptions;
use crate::tessellate::{FailedFace, TessellateOptions};
use serde::Serialize;
use std::path::Path;
use std::time::Instant;

/// What [`cad_info`] does besides reading.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CadInfoOptions {
    /// Also tessellate the faces and report the surface: triangles, closed, volume.
    pub mesh: bool,
    /// The chord deviation of `mesh`, as a fraction of the model size.
    pub deviation: f64,
}

impl Default for CadInfoOptions {
    fn default() -> CadInfoOptions {
        CadInfoOptions { mesh: false, deviation: TessellateOptions::default().chord_relative }
    }
}

/// The surface of a B-rep's tessellation, where [`CadInfoOptions::mesh`] asks for it.
#[derive(Clone, Debug, Serialize)]
pub struct MeshInfo {
    /// Triangles.
    pub triangles: usize,
    /// Vertices.
    pub vertices: usize,
    /// Every edge has two triangles.
    pub closed: bool,
    /// Edge- and vertex-manifold.
    pub manifold: bool,
    /// Consistently oriented.
    pub oriented: bool,
    /// Edges with one triangle.
    pub open_edges: usize,
    /// Volume enclosed, summed over the shells.
    pub volume_mm3: f64,
    /// Area.
    pub area_mm2: f64,
    /// Faces the tessellator could not mesh.
    pub failed_faces: Vec<FailedFace>,
    /// Seconds tessellating.
    pub seconds: f64,
}

/// What a STEP file with a B-rep holds: the JSON object `fepre cad-info --json` prints.
#[derive(Clone, Debug, Serialize)]
pub struct BrepInfo {
    /// The file.
    pub file: String,
    /// Counts, units, surface kinds, sewing.
    #[serde(flatten)]
    pub summary: Summary,
    /// Every item left out, with the reason.
    pub dropped: Vec<Dropped>,
    /// Seconds reading.
    pub seconds: f64,
    /// The tessellated surface, where asked for.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mesh: Option<MeshInfo>,
    /// What the report found but would rather not have (none so far).
    pub warnings: Vec<Warning>,
}

/// What a STEP file of tessellated geometry only holds: the JSON object `fepre cad-info
/// --json` prints for it.
#[derive(Clone, Debug, Serialize)]
pub struct TessellatedInfo {
    /// The file.
    pub file: String,
    /// Always true here: the file holds no B-rep.
    pub tessellated: bool,
    /// The file's units.
    pub units: Units,
    /// Counts.
    #[serde(flatten)]
    pub summary: TessellatedSummary,
    /// The tessellated faces.
    pub faces_table: Vec<TessellatedFace>,
    /// The tessellated solids and shells.
    pub solids_table: Vec<TessellatedSolid>,
    /// The triangles certified as a mesh.
    pub certificate: MeshCertificate,
    /// Every item left out, with the reason.
    pub dropped: Vec<Dropped>,
    /// Seconds reading.
    pub seconds: f64,
    /// What the report found but would rather not have (none so far).
    pub warnings: Vec<Warning>,
    /// The extent of the triangles (mm), where they have one.
    #[serde(skip)]
    pub extent: Option<[f64; 3]>,
}

/// What [`cad_info`] reports: a B-rep's counts, or a tessellated file's.
#[derive(Clone, Debug, Serialize)]
#[serde(untagged)]
pub enum CadInfo {
    /// A file with a B-rep.
    Brep(Box<BrepInfo>),
    /// A file of tessellated geometry only.
    Tessellated(Box<TessellatedInfo>),
}

impl CadInfo {
    /// The warnings of either report.
    pub fn warnings(&self) -> &[Warning] {
        match self {
            CadInfo::Brep(b) => &b.warnings,
            CadInfo::Tessellated(t) => &t.warnings,
        }
    }
}

/// Reads the STEP file at `path` and reports what it holds; with [`CadInfoOptions::mesh`],
/// its tessellated surface too.
///
/// # Errors
/// The file cannot be read as STEP (the message names the line or `#id`).
pub fn cad_info(path: &Path, options: &CadInfoOptions) -> Result<CadInfo, PipelineError> {
    let t0 = Instant::now();
    let model = match step::read_shape(path)? {
        step::Shape::Brep(m) => m,
        step::Shape::Tessellated(t) => return Ok(CadInfo::Tessellated(Box::new(tessellated_info(path, t, t0.elapsed().as_secs_f64())))),
    };
    let seconds = t0.elapsed().as_secs_f64();
    let summary = Summary::of(&model);
    let dropped = model.dropped.clone();
    let mesh = options.mesh.then(|| {
        let t1 = Instant::now();
        let opts = TessellateOptions::default().with_chord_relative(options.deviation);
        let checks = CertifyOptions::default().with_self_intersections(false);
        let (_, c, _) = super::tessellate_model(model, 0.0, &opts, None, &checks);
        let s = &c.tessellation.surface;
        let r = crate::mesh::topology::surface_report(s, &crate::mesh::topology::ReportOptions::default().with_self_intersections(false));
        MeshInfo {
            triangles: s.triangles.len(),
            vertices: s.vertices.len(),
            closed: r.closed,
            manifold: r.manifold,
            oriented: r.oriented,
            open_edges: r.open_edges,
            volume_mm3: r.shells.iter().map(|s| s.volume).sum(),
            area_mm2: r.shells.iter().map(|s| s.area).sum(),
            failed_faces: c.tessellation.failed,
            seconds: t1.elapsed().as_secs_f64(),
        }
    });
    Ok(CadInfo::Brep(Box::new(BrepInfo { file: path.display().to_string(), summary, dropped, seconds, mesh, warnings: Vec::new() })))
}

/// The report of a file of tessellated geometry only: counts, units, and the surface
/// certified as a mesh.
fn tessellated_info(path: &Path, t: step::Tessellated, seconds: f64) -> TessellatedInfo {
    let b = t.surface.bbox();
    let extent = b.diagonal().is_finite().then(|| {
        let e = b.max - b.min;
        [e.x, e.y, e.z]
    });
    TessellatedInfo {
        file: path.display().to_string(),
        tessellated: true,
        summary: TessellatedSummary::of(&t, &t.surface),
        certificate: certify_surface(&t.surface),
        units: t.units,
        faces_table: t.faces,
        solids_table: t.solids,
        dropped: t.dropped,
        seconds,
        warnings: Vec::new(),
        extent,
    }
}
