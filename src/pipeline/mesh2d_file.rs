//! `fepre mesh2d` as a library call: the quadtree mesher on the planar faces of a STEP part
//! ([`super::planar::mesh_planar_faces`]), the faces' meshes written as one tagged surface, and
//! the report the command prints (counts, levels, angles over all faces and per face).

use super::PipelineError;
use super::planar::{FaceChoice, FailedPlanarFace, mesh_planar_faces};
use super::warning::Warning;
use crate::core::FaceId;
use crate::io::{self, Format, MeshData, WriteOptions};
use crate::mesh2d::quadtree::{Angles, QuadtreeOptions, TreeStats};
use serde::Serialize;
use std::path::Path;
use std::time::Instant;

/// One face's mesh: counts, the quadtree, angles, seconds.
#[derive(Clone, Debug, Serialize)]
pub struct FaceReport {
    /// The face.
    pub face: FaceId,
    /// Its STEP `#id`.
    pub step_id: crate::cad::brep::EntityRef,
    /// Boundary segments of its domain.
    pub segments: usize,
    /// Vertices.
    pub vertices: usize,
    /// Triangles.
    pub triangles: usize,
    /// Quadrilaterals.
    pub quads: usize,
    /// Triangles of the interior templates.
    pub inside_triangles: usize,
    /// The quadtree.
    pub tree: TreeStats,
    /// Its angles.
    pub angles: Angles,
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
    /// The size used.
    pub size: f64,
    /// Faces.
    pub faces: usize,
    /// Faces whose surface is a plane.
    pub planar_faces: usize,
    /// Faces meshed.
    pub meshed: usize,
    /// The planar faces that failed.
    pub failed: Vec<FailedPlanarFace>,
    /// Triangles.
    pub triangles: usize,
    /// Quadrilaterals.
    pub quads: usize,
    /// Every quadtree balanced (neighbours differ by at most one level).
    pub balanced: bool,
    /// Smallest and largest angle of the template triangles over all faces.
    pub inside_angles: [f64; 2],
    /// Smallest and largest angle of the band's triangles.
    pub band_angles: [f64; 2],
    /// Smallest angle of the band's triangles with no vertex on the boundary.
    pub band_off_boundary_min: f64,
    /// Smallest angle between two boundary segments of the faces' inputs.
    pub input_smallest_angle: f64,
    /// The coarsest and finest quadtree levels.
    pub levels: [u8; 2],
    /// Seconds: read and tessellate, mesh, write.
    pub seconds: [f64; 3],
    /// Each face's mesh.
    pub per_face: Vec<FaceReport>,
    /// What the run made but would rather not have (none so far: the failed faces are in
    /// `failed`).
    pub warnings: Vec<Warning>,
    /// Seconds in all.
    #[serde(skip)]
    pub total_seconds: f64,
}

/// Meshes the chosen planar faces of the STEP file `cad` at the uniform size `size` (`None`:
/// the part's diagonal over 25) and writes them to `output` (.msh, .vtu, .mesh, .obj or .stl)
/// where given.
///
/// # Errors
/// [`PipelineError::Usage`] for an output format that cannot hold the faces (before anything
/// is read); an unreadable file, a face asked for that cannot be meshed, a failed write.
pub fn mesh2d_file(cad: &Path, choice: &FaceChoice, size: Option<f64>, options: &QuadtreeOptions, output: Option<&Path>) -> Result<Mesh2dReport, PipelineError> {
    if let Some(out) = output {
        if !matches!(Format::from_path(out), Some(Format::Msh | Format::Vtu | Format::Medit | Format::Obj | Format::Stl)) {
            return Err(PipelineError::Usage { path: out.to_path_buf(), problem: super::UsageProblem::FacesFormat });
        }
    }
    let t0 = Instant::now();
    let r = mesh_planar_faces(cad, choice, size, options)?;
    let t_write = Instant::now();
    if let Some(out) = output {
        io::write(out, &MeshData::Surface(r.surface()), &WriteOptions::default())?;
    }
    let write = t_write.elapsed().as_secs_f64();
    let mut rep = Mesh2dReport {
        input: cad.display().to_string(),
        output: output.map(|o| o.display().to_string()),
        size: r.size,
        faces: r.model.faces.len(),
        planar_faces: r.planar_faces,
        meshed: r.meshed.len(),
        failed: r.failed.clone(),
        triangles: 0,
        quads: 0,
        balanced: true,
        inside_angles: [f64::INFINITY, f64::NEG_INFINITY],
        band_angles: [f64::INFINITY, f64::NEG_INFINITY],
        band_off_boundary_min: f64::INFINITY,
        input_smallest_angle: f64::INFINITY,
        levels: [u8::MAX, 0],
        seconds: [r.seconds[0], r.seconds[1], write],
        per_face: Vec::new(),
        warnings: Vec::new(),
        total_seconds: 0.0,
    };
    for m in &r.meshed {
        let pm = &m.mesh.mesh;
        let a = m.angles;
        rep.triangles += pm.triangles.len();
        rep.quads += pm.quads.len();
        rep.balanced &= m.mesh.stats.balanced;
        rep.inside_angles = [rep.inside_angles[0].min(a.inside[0]), rep.inside_angles[1].max(a.inside[1])];
        rep.band_angles = [rep.band_angles[0].min(a.band[0]), rep.band_angles[1].max(a.band[1])];
        rep.band_off_boundary_min = rep.band_off_boundary_min.min(a.band_off_boundary[0]);
        rep.input_smallest_angle = rep.input_smallest_angle.min(a.input_smallest);
        rep.levels = [rep.levels[0].min(m.mesh.stats.levels[0]), rep.levels[1].max(m.mesh.stats.levels[1])];
        rep.per_face.push(FaceReport {
            face: m.planar.face,
            step_id: r.model.face(m.planar.face).source,
            segments: m.planar.domain.segments.len(),
            vertices: pm.vertices.len(),
            triangles: pm.triangles.len(),
            quads: pm.quads.len(),
            inside_triangles: m.mesh.inside_triangles,
            tree: m.mesh.stats,
            angles: a,
            seconds: m.seconds,
        });
    }
    rep.total_seconds = t0.elapsed().as_secs_f64();
    Ok(rep)
}
