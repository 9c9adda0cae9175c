//! `fepre mesh2d CAD [--face N | --all-planar] [--size H] [-o OUT]`: the lecture's quadtree
//! mesher on the planar faces of a STEP part.
//!
//! Parses, calls [`crate::pipeline::planar::mesh_planar_faces`], prints a summary (or one
//! JSON object) and writes the faces' meshes lifted back onto their planes as one tagged
//! surface. Exit codes: 0 done, 1 the file could not be read or a face asked for could not
//! be meshed, 2 bad usage.

use crate::cli::usage_error;
use crate::core::FaceId;
use crate::io::{self, Format, MeshData, WriteOptions};
use crate::mesh2d::quadtree::{Angles, QuadtreeOptions, TreeStats};
use crate::pipeline::planar::{mesh_planar_faces, FaceChoice, FailedPlanarFace};
use anyhow::Result;
use serde::Serialize;
use std::path::PathBuf;
use std::time::Instant;

/// Examples shown by `fepre mesh2d --help`.
pub const EXAMPLES: &str = "\
Examples:
  fepre mesh2d part.step --all-planar -o faces.vtu     every planar face, default size (diagonal / 25)
  fepre mesh2d part.step --face 3 --size 0.5 -o f3.msh  face 3 only, quadrants of at most 0.5 mm
  fepre mesh2d part.step --size 2 --json               no file: the JSON summary only
  fepre mesh2d part.step --quads -o faces.mesh         interior quadrants without hanging nodes as quads

The quadtree (Yerry and Shephard) is refined to the size and around the face's boundary
features, balanced so that neighbours differ by at most one level; interior quadrants become
45-degree triangles by the 2:1 templates, the boundary band is triangulated with every CAD
edge point kept. The output (.msh, .vtu, .mesh, .obj, .stl) is the faces' meshes on their
planes, tagged with the face ids (quads written as two triangles).";

/// Arguments of `fepre mesh2d`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// STEP file (.step, .stp).
    pub cad: PathBuf,
    /// Mesh this face (its id, as `fepre cad-info --json` lists them); may be repeated.
    #[arg(long, value_name = "N", conflicts_with = "all_planar")]
    pub face: Vec<u32>,
    /// Mesh every planar face (the default without --face).
    #[arg(long)]
    pub all_planar: bool,
    /// Largest quadrant (model units, mm for STEP); default the part's diagonal over 25.
    #[arg(long, value_name = "H", value_parser = crate::cli::positive)]
    pub size: Option<f64>,
    /// Output surface: .msh, .vtu, .mesh, .obj or .stl.
    #[arg(short, long, value_name = "OUT")]
    pub output: Option<PathBuf>,
    /// Interior quadrants without hanging nodes as quadrilaterals (written as two triangles
    /// by surface formats; counted in the summary).
    #[arg(long)]
    pub quads: bool,
    /// Print one JSON object on standard output.
    #[arg(long)]
    pub json: bool,
}

#[derive(Debug, Serialize)]
struct FaceReport {
    face: FaceId,
    step_id: crate::cad::brep::EntityRef,
    segments: usize,
    vertices: usize,
    triangles: usize,
    quads: usize,
    inside_triangles: usize,
    tree: TreeStats,
    angles: Angles,
    seconds: f64,
}

#[derive(Debug, Serialize)]
struct Report {
    input: String,
    output: Option<String>,
    size: f64,
    faces: usize,
    planar_faces: usize,
    meshed: usize,
    failed: Vec<FailedPlanarFace>,
    triangles: usize,
    quads: usize,
    balanced: bool,
    /// Smallest and largest angle of the template triangles over all faces.
    inside_angles: [f64; 2],
    /// Smallest and largest angle of the band's triangles.
    band_angles: [f64; 2],
    /// Smallest angle of the band's triangles with no vertex on the boundary.
    band_off_boundary_min: f64,
    /// Smallest angle between two boundary segments of the faces' inputs.
    input_smallest_angle: f64,
    levels: [u8; 2],
    seconds: [f64; 3],
    per_face: Vec<FaceReport>,
}

/// Runs `fepre mesh2d`.
///
/// # Errors
/// Bad usage, an unreadable file, a face that cannot be meshed, a failed write.
pub fn run(args: &Args) -> Result<()> {
    if let Some(out) = &args.output {
        if !matches!(Format::from_path(out), Some(Format::Msh | Format::Vtu | Format::Medit | Format::Obj | Format::Stl)) {
            return Err(usage_error(format!("{}: the faces are written as .msh, .vtu, .mesh, .obj or .stl", out.display())));
        }
    }
    let t0 = Instant::now();
    let choice = if args.face.is_empty() { FaceChoice::AllPlanar } else { FaceChoice::Faces(args.face.iter().map(|&f| FaceId(f)).collect()) };
    let options = QuadtreeOptions { quads: args.quads, ..QuadtreeOptions::default() };
    let r = mesh_planar_faces(&args.cad, &choice, args.size, &options)?;
    let t_write = Instant::now();
    if let Some(out) = &args.output {
        io::write(out, &MeshData::Surface(r.surface()), &WriteOptions::default())?;
    }
    let write = t_write.elapsed().as_secs_f64();
    let mut rep = Report {
        input: args.cad.display().to_string(),
        output: args.output.as_ref().map(|o| o.display().to_string()),
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
    if args.json {
        outln!("{}", serde_json::to_string_pretty(&rep)?);
    } else {
        outln!("faces        {} ({} planar, {} meshed, {} failed)", rep.faces, rep.planar_faces, rep.meshed, rep.failed.len());
        for f in &rep.failed {
            outln!("  failed face {} ({}): {}", f.face.0, f.step_id, f.reason);
        }
        outln!("size         {:.6}", rep.size);
        outln!("elements     {} triangles, {} quads", rep.triangles, rep.quads);
        outln!("levels       {}..{}, balanced (neighbours differ by at most one level): {}", rep.levels[0], rep.levels[1], rep.balanced);
        outln!("angles       inside {:.2}..{:.2} deg, band {:.2}..{:.2} deg (off the boundary from {:.2}), smallest input angle {:.2}", rep.inside_angles[0], rep.inside_angles[1], rep.band_angles[0], rep.band_angles[1], rep.band_off_boundary_min, rep.input_smallest_angle);
        outln!("seconds      read+tessellate {:.3}, mesh {:.3}, write {:.3} (total {:.3})", rep.seconds[0], rep.seconds[1], rep.seconds[2], t0.elapsed().as_secs_f64());
        if let Some(o) = &rep.output {
            outln!("wrote        {o}");
        }
    }
    Ok(())
}
