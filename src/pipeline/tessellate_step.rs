//! `fepre tessellate` as a library call: a watertight, certified triangle surface of a STEP
//! file, every triangle tagged with its B-rep face, written where the certificate passes (or
//! where asked to regardless). The one reader branch (a B-rep, or tessellated geometry only,
//! certified as a mesh) and the pipeline's one tessellation path ([`super::tessellate_model`]).

use super::PipelineError;
use super::tessellated::{MeshCertificate, TessellatedSummary, certify_surface, mesh_failure_message};
use super::warning::Warning;
use super::{failure_message, tessellate_model};
use crate::cad::brep::{Dropped, EntityRef, FaceEntry, Model, Units};
use crate::cad::step;
use crate::core::size_field::UniformSize;
use crate::core::{FaceId, SizeField};
use crate::io::{self, Format, MeshData, WriteOptions};
use crate::tessellate::certificate::{Certificate, CertifyOptions};
use crate::tessellate::{TessellateOptions, Tessellation};
use serde::Serialize;
use std::path::Path;
use std::time::Instant;

/// How [`tessellate_step`] tessellates, and whether it writes a surface that fails its
/// certificate.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TessellateStepOptions {
    /// Largest distance between the triangles and the exact surface, as a fraction of the
    /// model size, exactly this everywhere; `None`: the default, finer on the faces of a solid
    /// that would lose volume.
    pub deviation: Option<f64>,
    /// Longest triangle edge (model units): faces refined to well-shaped triangles of about
    /// this size.
    pub max_edge: Option<f64>,
    /// Write the surface even when the certificate fails.
    pub force: bool,
}

impl TessellateStepOptions {
    /// The tessellator's options: the deviation asked for everywhere (no finer chords where a
    /// solid loses volume), or the defaults.
    pub fn tessellate_options(&self) -> TessellateOptions {
        match self.deviation {
            Some(d) => TessellateOptions::default().with_chord_relative(d).with_volume_relative(0.0),
            None => TessellateOptions::default(),
        }
    }
}

/// What [`tessellate_step`] made: a B-rep's certified tessellation, or a tessellated file's
/// triangles certified as a mesh.
#[derive(Clone, Debug, Serialize)]
#[serde(untagged)]
pub enum TessellateReport {
    /// A file with a B-rep.
    Brep(Box<BrepTessellation>),
    /// A file of tessellated geometry only.
    Tessellated(Box<TessellatedFileReport>),
}

impl TessellateReport {
    /// The warnings of either report.
    pub fn warnings(&self) -> &[Warning] {
        match self {
            TessellateReport::Brep(b) => &b.warnings,
            TessellateReport::Tessellated(t) => &t.warnings,
        }
    }
}

/// A failed [`tessellate_step`]: the error and, where the file was tessellated, the report of
/// what failed (nothing was written).
#[derive(Debug)]
pub struct TessellateFailure {
    /// What was made, where the file was read and tessellated (a failed certificate).
    pub report: Option<Box<TessellateReport>>,
    /// Why nothing was written.
    pub error: PipelineError,
}

impl From<PipelineError> for TessellateFailure {
    fn from(error: PipelineError) -> TessellateFailure {
        TessellateFailure { report: None, error }
    }
}

/// Euler characteristic of one shell group, mesh and B-rep.
#[derive(Clone, Debug, Serialize)]
pub struct EulerEntry {
    /// The B-rep shells of the group.
    pub brep_shells: Vec<EntityRef>,
    /// The mesh's Euler characteristic.
    pub mesh: i64,
    /// The B-rep's Euler characteristic.
    pub brep: i64,
}

/// A face that could not be meshed.
#[derive(Clone, Debug, Serialize)]
pub struct FailedFaceEntry {
    /// The face.
    pub face: FaceId,
    /// Its STEP `#id`.
    pub step_id: EntityRef,
    /// Why.
    pub reason: String,
}

/// What tessellating a STEP file with a B-rep made: the JSON object `fepre tessellate --json`
/// prints.
#[derive(Clone, Debug, Serialize)]
pub struct BrepTessellation {
    /// The input file.
    pub input: String,
    /// The file written (`None`: nothing written).
    pub output: Option<String>,
    /// Solids.
    pub solids: usize,
    /// Shells not bounding a solid (surface models).
    pub surface_model_shells: usize,
    /// What sewing the open shells did.
    pub sewing: Option<crate::cad::brep::SewReport>,
    /// Faces.
    pub faces: usize,
    /// Per face: unique name, colour, STEP `#id`, solid.
    pub face_table: Vec<FaceEntry>,
    /// Triangles.
    pub triangles: usize,
    /// Vertices.
    pub vertices: usize,
    /// Closed, manifold, oriented where it should be ([`Certificate::watertight`]).
    pub watertight: bool,
    /// What `watertight` speaks of: `solids` (open surface shells beside them are reported
    /// in `open_surface`), or `surface model`.
    pub watertight_of: &'static str,
    /// The shells of a surface model (no solid) left open after sewing: their free edges
    /// grouped into holes.
    pub open_surface: Option<OpenSurface>,
    /// Euler characteristic.
    pub euler: Vec<EulerEntry>,
    /// Volume of the closed shells (mm³).
    pub volume: f64,
    /// Area.
    pub area: f64,
    /// The file's units.
    pub units: Units,
    /// The chord deviation asked for, as a fraction of the model size.
    pub deviation: f64,
    /// The longest triangle edge asked for.
    pub max_edge: Option<f64>,
    /// The chord deviation used (mm).
    pub chord_mm: f64,
    /// Every item the reader left out, with the reason.
    pub dropped: Vec<Dropped>,
    /// What was odd about the file as written but read anyway ([`Model::notes`]).
    pub notes: Vec<String>,
    /// Faces the tessellator could not mesh.
    pub failed_faces: Vec<FailedFaceEntry>,
    /// Seconds in all.
    pub seconds: f64,
    /// Seconds reading.
    pub read_seconds: f64,
    /// Seconds tessellating.
    pub tessellate_seconds: f64,
    /// The checks and what failed.
    pub certificate: Certificate,
    /// What the run made but would rather not have (none so far: a failed check fails the
    /// run, or is in `certificate` with `--force`).
    pub warnings: Vec<Warning>,
    /// The certificate's failures as the error of a failed run gives them (`None` where it
    /// passed).
    #[serde(skip)]
    pub failure_message: Option<String>,
}

/// Open shells of a surface model after sewing.
#[derive(Clone, Debug, Serialize)]
pub struct OpenSurface {
    /// Shells that bound no solid and do not close.
    pub shells: usize,
    /// Their free edges.
    pub free_edges: usize,
    /// The free edges grouped into holes, largest first.
    pub holes: Vec<crate::cad::brep::Hole>,
}

/// The open surface-model shells of `m`, or `None` when every one closes (or there is none).
fn open_surface(m: &Model) -> Option<OpenSurface> {
    let holes = m.holes(|s| s.solid.is_none() && !s.closed);
    if holes.is_empty() {
        return None;
    }
    let mut shells: Vec<EntityRef> = holes.iter().flat_map(|h| h.shells.iter().copied()).collect();
    shells.sort_unstable();
    shells.dedup();
    Some(OpenSurface { shells: shells.len(), free_edges: holes.iter().map(|h| h.edges).sum(), holes })
}

/// What tessellating a B-rep made: the B-rep, its certified tessellation, the seconds.
struct Made {
    model: Model,
    tessellation: Tessellation,
    certificate: Certificate,
    seconds: [f64; 2],
}


/// What tessellating a STEP file of tessellated geometry only made: the JSON object
/// `fepre tessellate --json` prints for it.
#[derive(Clone, Debug, Serialize)]
pub struct TessellatedFileReport {
    /// The input file.
    pub input: String,
    /// The file written (`None`: nothing written).
    pub output: Option<String>,
    /// Always true here: the surface is the file's own triangles, certified as a mesh.
    pub tessellated: bool,
    #[serde(flatten)]
    /// Counts.
    pub summary: TessellatedSummary,
    /// Per face: unique name, colour, STEP `#id`, solid.
    pub face_table: Vec<FaceEntry>,
    /// The file's units.
    pub units: Units,
    /// The checks and what failed.
    pub certificate: MeshCertificate,
    /// Every item the reader left out, with the reason.
    pub dropped: Vec<Dropped>,
    /// Seconds in all.
    pub seconds: f64,
    /// What the run made but would rather not have (none so far).
    pub warnings: Vec<Warning>,
    /// The checks' failures as the error of a failed run gives them (`None` where they
    /// passed).
    #[serde(skip)]
    pub failure_message: Option<String>,
}

/// Reads the STEP file at `input`, tessellates it and certifies the result, and writes the
/// surface to `output` (.stl, .obj, .vtu or .msh) where the certificate passes or
/// [`TessellateStepOptions::force`] asks for it. A file of tessellated geometry only gives
/// its own triangles, certified as a mesh.
///
/// # Errors
/// [`PipelineError::Usage`] for an output format that cannot hold a surface (before anything
/// is read); an unreadable STEP file; a failed certificate without `force`
/// ([`PipelineError::Certificate`], with the report); a failed write.
pub fn tessellate_step(input: &Path, options: &TessellateStepOptions, output: &Path) -> Result<TessellateReport, TessellateFailure> {
    if !matches!(Format::from_path(output), Some(Format::Stl | Format::Obj | Format::Vtu | Format::Msh)) {
        return Err(PipelineError::Usage { path: output.to_path_buf(), problem: super::UsageProblem::SurfaceFormat }.into());
    }
    let t0 = Instant::now();
    let model = match step::read_shape(input).map_err(PipelineError::from)? {
        step::Shape::Brep(m) => m,
        step::Shape::Tessellated(t) => return tessellated(input, options, t, output, t0).map(|r| TessellateReport::Tessellated(Box::new(r))),
    };
    let read = t0.elapsed().as_secs_f64();
    let size = options.max_edge.map(UniformSize);
    let (model, c, seconds) = tessellate_model(model, read, &options.tessellate_options(), size.as_ref().map(|s| s as &dyn SizeField), &CertifyOptions::default());
    let c = Made { model, tessellation: c.tessellation, certificate: c.certificate, seconds: [seconds.read, seconds.tessellate] };
    if !c.certificate.passed && !options.force {
        let report = brep_report(input, options, &c, None, t0);
        let error = PipelineError::certificate(input, &c.certificate, &c.model.dropped);
        return Err(TessellateFailure { report: Some(Box::new(TessellateReport::Brep(Box::new(report)))), error });
    }
    io::write(output, &MeshData::Surface(c.tessellation.surface.clone()), &WriteOptions::default()).map_err(PipelineError::from)?;
    Ok(TessellateReport::Brep(Box::new(brep_report(input, options, &c, Some(output.display().to_string()), t0))))
}

/// [`tessellate_step`] of a file of tessellated geometry only: its triangles, certified as a
/// mesh (closed, manifold, oriented outward, no self-intersection), written when they pass.
fn tessellated(input: &Path, options: &TessellateStepOptions, t: step::Tessellated, output: &Path, t0: Instant) -> Result<TessellatedFileReport, TessellateFailure> {
    let certificate = certify_surface(&t.surface);
    let mut face_table = crate::cad::brep::face_table_of_names(&t.surface.face_names, t.surface.face_tags.iter().copied());
    for e in &mut face_table {
        if let Some(f) = e.face.index().and_then(|k| t.faces.get(k)) {
            e.step_id = Some(f.step_id);
            e.solid = f.solid;
        }
    }
    let passed = certificate.passed;
    let message = (!passed).then(|| mesh_failure_message(input, &certificate));
    let mut r = TessellatedFileReport {
        input: input.display().to_string(),
        output: None,
        tessellated: true,
        summary: TessellatedSummary::of(&t, &t.surface),
        face_table,
        units: t.units.clone(),
        certificate,
        dropped: t.dropped.clone(),
        seconds: 0.0,
        warnings: Vec::new(),
        failure_message: message.clone(),
    };
    if message.is_some() && !options.force {
        r.seconds = t0.elapsed().as_secs_f64();
        let error = PipelineError::MeshCertificate { path: input.to_path_buf(), certificate: Box::new(r.certificate.clone()) };
        return Err(TessellateFailure { report: Some(Box::new(TessellateReport::Tessellated(Box::new(r)))), error });
    }
    io::write(output, &MeshData::Surface(t.surface), &WriteOptions::default()).map_err(PipelineError::from)?;
    r.output = Some(output.display().to_string());
    r.seconds = t0.elapsed().as_secs_f64();
    Ok(r)
}

fn brep_report(input: &Path, options: &TessellateStepOptions, c: &Made, output: Option<String>, t0: Instant) -> BrepTessellation {
    let s = &c.tessellation.surface;
    let cert = c.certificate.clone();
    let volume: f64 = cert.shells.iter().filter(|x| x.brep_closed).map(|x| x.volume_mesh).sum();
    BrepTessellation {
        input: input.display().to_string(),
        output,
        solids: c.model.solids.len(),
        surface_model_shells: c.model.surface_model_shells(),
        sewing: c.model.sewing.clone(),
        faces: c.model.faces.len(),
        face_table: c.model.face_table(),
        triangles: s.triangles.len(),
        vertices: s.vertices.len(),
        watertight: cert.watertight(),
        watertight_of: if cert.shells.iter().any(|x| x.solid) { "solids" } else { "surface model" },
        open_surface: open_surface(&c.model),
        euler: cert.shells.iter().map(|x| EulerEntry { brep_shells: x.brep_shells.clone(), mesh: x.euler_mesh, brep: x.euler_brep }).collect(),
        volume,
        area: cert.area[0],
        units: c.model.units.clone(),
        deviation: options.deviation.unwrap_or(TessellateOptions::default().chord_relative),
        max_edge: options.max_edge,
        chord_mm: c.tessellation.chord,
        dropped: c.model.dropped.clone(),
        notes: c.model.notes.clone(),
        failed_faces: c.tessellation.failed.iter().map(|f| FailedFaceEntry { face: f.face, step_id: f.source, reason: f.why.clone() }).collect(),
        seconds: t0.elapsed().as_secs_f64(),
        read_seconds: c.seconds[0],
        tessellate_seconds: c.seconds[1],
        failure_message: (!cert.passed).then(|| failure_message(input, &cert, &c.model.dropped)),
        certificate: cert,
        warnings: Vec::new(),
    }
}
