//! `fepre mesh2d` as a library call: one of the lecture's 2D methods on the planar faces of a
//! STEP part ([`super::planar::mesh_planar_faces`]), the meshes written as one tagged surface
//! of triangles and quads, and the report the command prints (counts, the quality figures of
//! [`Quality2d`] over all faces and per face, each method's own figures).

use super::PipelineError;
use super::planar::{FaceChoice, FailedPlanarFace, mesh_planar_faces};
use super::warning::{Place, Warning, WarningKind};
use crate::core::FaceId;
use crate::io::{self, Format, MeshRef, WriteOptions};
use crate::mesh::{MixedSurface, PlanarMesh};
use crate::mesh2d::measure::{measure, Quality2d};
use crate::mesh2d::{Mesh2dOptions, Method};
use serde::Serialize;
use std::path::Path;
use std::time::Instant;

/// One face's (or region's) mesh: counts, quality, the method's figures, seconds.
#[derive(Clone, Debug, Serialize)]
pub struct FaceReport {
    /// The face (a STEP part) or the region's tag (a `.poly` file).
    pub face: FaceId,
    /// Its STEP `#id`, for a face of a part.
    pub step_id: Option<crate::cad::brep::EntityRef>,
    /// Boundary segments of its domain.
    pub segments: usize,
    /// Vertices.
    pub vertices: usize,
    /// Triangles.
    pub triangles: usize,
    /// Quadrilaterals.
    pub quads: usize,
    /// Quality figures.
    pub quality: Quality2d,
    /// The method's own figures.
    pub stats: serde_json::Value,
    /// Seconds meshing it.
    pub seconds: f64,
}

/// What [`mesh2d_file`] made: the JSON object `fepre mesh2d --json` prints.
#[derive(Clone, Debug, Serialize)]
pub struct Mesh2dReport {
    /// The input file.
    pub input: String,
    /// The file written (`None`: nothing written).
    pub output: Option<String>,
    /// The method.
    pub method: Method,
    /// All quadrilaterals asked.
    pub all_quads: bool,
    /// The size used.
    pub size: f64,
    /// Faces of the part.
    pub faces: usize,
    /// Faces whose surface is a plane.
    pub planar_faces: usize,
    /// Faces meshed.
    pub meshed: usize,
    /// The planar faces that failed.
    pub failed: Vec<FailedPlanarFace>,
    /// Vertices of the output (boundary vertices shared between faces counted once).
    pub vertices: usize,
    /// Triangles.
    pub triangles: usize,
    /// Quadrilaterals.
    pub quads: usize,
    /// Quality figures over every face.
    pub quality: Quality2d,
    /// Seconds: read (and tessellate), mesh, write.
    pub seconds: [f64; 3],
    /// Each face's mesh.
    pub per_face: Vec<FaceReport>,
    /// What falls short of what was asked (a minimum angle not reached), by face.
    pub warnings: Vec<Warning>,
    /// Seconds in all.
    #[serde(skip)]
    pub total_seconds: f64,
}

/// The formats `mesh2d` writes (quads as quads in .msh, .vtu, .mesh and .inp).
pub(crate) fn check_output(out: &Path) -> Result<(), PipelineError> {
    let ext = out.extension().and_then(|e| e.to_str()).unwrap_or_default().to_ascii_lowercase();
    if ext == "inp" || matches!(Format::from_path(out), Some(Format::Msh | Format::Vtu | Format::Medit | Format::Obj | Format::Stl)) {
        Ok(())
    } else {
        Err(PipelineError::Usage { path: out.to_path_buf(), problem: super::UsageProblem::FacesFormat })
    }
}

/// Writes a surface of triangles and quads: `.inp` as a CalculiX/Abaqus mesh, the rest by
/// [`io::write_ref`].
pub(crate) fn write_faces(out: &Path, s: &MixedSurface, title: &str) -> Result<(), PipelineError> {
    let is_inp = out.extension().is_some_and(|e| e.eq_ignore_ascii_case("inp"));
    if is_inp {
        crate::deck::write_inp_faces(out, s, title)?;
    } else {
        io::write_ref(out, MeshRef::Mixed(s), &WriteOptions::default())?;
    }
    Ok(())
}

/// One face's report entry.
pub(crate) fn face_report(face: FaceId, step_id: Option<crate::cad::brep::EntityRef>, segments: usize, mesh: &PlanarMesh, stats: &serde_json::Value, size: f64, seconds: f64) -> FaceReport {
    FaceReport {
        face,
        step_id,
        segments,
        vertices: mesh.vertices.len(),
        triangles: mesh.triangles.len(),
        quads: mesh.quads.len(),
        quality: measure(mesh, &|_| size),
        stats: stats.clone(),
        seconds,
    }
}

/// All faces' planar meshes side by side (for the figures over every face).
pub(crate) fn concatenate<'a>(meshes: impl Iterator<Item = &'a PlanarMesh>) -> PlanarMesh {
    let mut all = PlanarMesh::default();
    for m in meshes {
        let base = all.vertices.len() as u32;
        all.vertices.extend_from_slice(&m.vertices);
        all.triangles.extend(m.triangles.iter().map(|t| t.map(|i| i + base)));
        all.triangle_tags.extend_from_slice(&m.triangle_tags);
        all.quads.extend(m.quads.iter().map(|q| q.map(|i| i + base)));
        all.quad_tags.extend_from_slice(&m.quad_tags);
    }
    all
}

/// Warnings where a face's smallest angle is under the one asked.
pub(crate) fn angle_warnings(options: &Mesh2dOptions, faces: &[FaceReport], what: &str) -> Vec<Warning> {
    let Some(asked) = options.min_angle else { return Vec::new() };
    faces
        .iter()
        .filter(|f| f.quality.angle_range[0] < asked)
        .map(|f| Warning::new(WarningKind::MinAngle2d, format!("{what} {}: smallest angle {:.2} deg, under the {asked} deg asked ({} triangles under 30 deg); its stats name the input angles that force it", f.face.0, f.quality.angle_range[0], f.quality.triangles_under[1]), Some(Place::Face(f.face))))
        .collect()
}

/// What `fepre mesh2d` is asked: which faces, the size, the method and its options, and the
/// smallest angle below which nothing is written.
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh2dRequest {
    /// Which planar faces of a part (ignored for a `.poly` file: every region).
    pub faces: FaceChoice,
    /// The uniform size (`None`: the input's default).
    pub size: Option<f64>,
    /// The method and its options.
    pub options: Mesh2dOptions,
    /// Fail (exit 1, nothing written) when an angle is under this, degrees.
    pub require_min_angle: Option<f64>,
}

impl Default for Mesh2dRequest {
    fn default() -> Self {
        Mesh2dRequest { faces: FaceChoice::AllPlanar, size: None, options: Mesh2dOptions::default(), require_min_angle: None }
    }
}

/// The error when the smallest angle is under the one required.
pub(crate) fn check_min_angle(input: &Path, required: Option<f64>, quality: &Quality2d, faces: &[FaceReport]) -> Result<(), PipelineError> {
    let Some(required) = required else { return Ok(()) };
    let found = quality.angle_range[0];
    if found >= required {
        return Ok(());
    }
    let worst = faces.iter().min_by(|a, b| a.quality.angle_range[0].total_cmp(&b.quality.angle_range[0])).map(|f| f.face.0).unwrap_or(0);
    Err(PipelineError::Requirement {
        path: input.to_path_buf(),
        requirement: super::Requirement::MinAngle2d,
        found,
        required,
        message: format!("the smallest angle is {found:.2} deg (face or region {worst}), under the {required} deg required; nothing written"),
    })
}

/// Meshes the chosen planar faces of the STEP file `cad` by the request's method at its uniform
/// size (`None`: the part's default) and writes them to `output` (.msh, .vtu, .mesh, .inp,
/// .obj or .stl; quads as quads except in .obj and .stl) where given.
///
/// # Errors
/// [`PipelineError::Usage`] for an output format that cannot hold the faces (before anything
/// is read); an unreadable file, a face asked for that cannot be meshed, an angle under the
/// one required (nothing written), a failed write.
pub fn mesh2d_file(cad: &Path, request: &Mesh2dRequest, output: Option<&Path>) -> Result<Mesh2dReport, PipelineError> {
    if let Some(out) = output {
        check_output(out)?;
    }
    let options = &request.options;
    let t0 = Instant::now();
    let r = mesh_planar_faces(cad, &request.faces, request.size, options)?;
    let surface = r.surface();
    let per_face: Vec<FaceReport> = r
        .meshed
        .iter()
        .map(|m| face_report(m.planar.face, Some(r.model.face(m.planar.face).source), m.planar.domain.segments.len(), &m.meshed.mesh, &m.meshed.stats, r.size, m.seconds))
        .collect();
    let all = concatenate(r.meshed.iter().map(|m| &m.meshed.mesh));
    let quality = measure(&all, &|_| r.size);
    check_min_angle(cad, request.require_min_angle, &quality, &per_face)?;
    let t_write = Instant::now();
    if let Some(out) = output {
        write_faces(out, &surface, &format!("{}: planar faces meshed by fepre mesh2d --method {}", cad.display(), options.method))?;
    }
    let write = t_write.elapsed().as_secs_f64();
    let mut warnings = angle_warnings(options, &per_face, "face");
    let unshared = r.unshared_boundary_points();
    if unshared > 0 {
        warnings.push(Warning::new(WarningKind::FacesNotConforming, format!("{unshared} points the {} method put on the faces' boundaries are not shared by the neighbouring faces: the surface does not conform there (the other methods keep the part's edge points)", options.method), None));
    }
    Ok(Mesh2dReport {
        input: cad.display().to_string(),
        output: output.map(|o| o.display().to_string()),
        method: options.method,
        all_quads: options.quads,
        size: r.size,
        faces: r.model.faces.len(),
        planar_faces: r.planar_faces,
        meshed: r.meshed.len(),
        failed: r.failed.clone(),
        vertices: surface.vertices.len(),
        triangles: surface.triangles.len(),
        quads: surface.quads.len(),
        quality,
        seconds: [r.seconds[0], r.seconds[1], write],
        per_face,
        warnings,
        total_seconds: t0.elapsed().as_secs_f64(),
    })
}
