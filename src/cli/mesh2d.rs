//! `fepre mesh2d CAD [--face N | --all-planar] [--size H] [-o OUT]`: the lecture's quadtree
//! mesher on the planar faces of a STEP part.
//!
//! Parses, calls [`fepre::pipeline::mesh_planar_faces`], prints a summary (or one
//! JSON object) and writes the faces' meshes lifted back onto their planes as one tagged
//! surface. Exit codes: 0 done, 1 the file could not be read or a face asked for could not
//! be meshed, 2 bad usage.

use crate::cli::usage_error;
use fepre::core::FaceId;
use fepre::mesh2d::quadtree::QuadtreeOptions;
use fepre::pipeline::PipelineError;
use fepre::pipeline::mesh2d_file;
use fepre::pipeline::FaceChoice;
use anyhow::Result;
use std::path::PathBuf;

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

/// Runs `fepre mesh2d`.
///
/// # Errors
/// Bad usage, an unreadable file, a face that cannot be meshed, a failed write.
pub fn run(args: &Args) -> Result<()> {
    let choice = if args.face.is_empty() { FaceChoice::AllPlanar } else { FaceChoice::Faces(args.face.iter().map(|&f| FaceId(f)).collect()) };
    let options = QuadtreeOptions { quads: args.quads, ..QuadtreeOptions::default() };
    let rep = mesh2d_file(&args.cad, &choice, args.size, &options, args.output.as_deref()).map_err(|e| match e {
        PipelineError::Usage { .. } => usage_error(e.to_string()),
        e => anyhow::Error::new(e),
    })?;
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
        outln!("seconds      read+tessellate {:.3}, mesh {:.3}, write {:.3} (total {:.3})", rep.seconds[0], rep.seconds[1], rep.seconds[2], rep.total_seconds);
        if let Some(o) = &rep.output {
            outln!("wrote        {o}");
        }
    }
    crate::cli::print_warnings(&rep.warnings);
    Ok(())
}
