//! `fepre mesh2d INPUT [--method M] [--quads] [--size H] [--min-angle A] [-o OUT]`: the
//! lecture's 2D methods on the planar faces of a STEP part or the regions of a `.poly` file.
//!
//! Parses, calls [`fepre::pipeline::mesh2d_file`], prints a summary (or one JSON object) and
//! writes the meshes (a part's faces lifted back onto their planes) as one tagged surface of
//! triangles and quads. Exit codes: 0 done, 1 the file could not be read, a face asked for
//! could not be meshed or a requirement was not met, 2 bad usage.

use crate::cli::usage_error;
use anyhow::Result;
use fepre::core::FaceId;
use fepre::mesh2d::{Mesh2dOptions, Method};
use fepre::pipeline::{mesh2d_file, mesh2d_poly, FaceChoice, Mesh2dRequest, PipelineError};
use std::path::PathBuf;

/// Examples shown by `fepre mesh2d --help`.
pub const EXAMPLES: &str = "\
Examples:
  fepre mesh2d part.step -o faces.vtu                  every planar face, default size (diagonal / 25)
  fepre mesh2d part.step --face 3 --size 0.5 -o f3.msh  face 3 only, elements of about 0.5 mm
  fepre mesh2d part.step --method front --quads -o faces.mesh   all quadrilaterals
  fepre mesh2d part.step --size 2 --json               no file: the JSON summary only
  fepre mesh2d part.step --require-min-angle 20 -o f.inp   exit 1, nothing written, under 20 deg
  fepre mesh2d plate.poly --method delaunay --min-angle 33 --max-area 0.01 -o plate.msh
                                                       Triangle's .poly (holes, regions), like -pq33a0.01

Methods (the lecture's section 23.2):
  delaunay    constrained Delaunay triangulation refined (Ruppert/Chew, off-centers) until
              every angle is at least --min-angle (30 deg; at most 34) away from input angles
              under 60 deg, and triangles are within --size and --max-area
  ear         topology decomposition: holes bridged, ears cut, then Delaunay insertion to
              the size and smoothing
  recursive   geometry decomposition by recursive subdivision (Bykat): convex pieces cut
              across their longest axis, nodes on the cuts by the size
  removal     geometry decomposition by iterative removal of elements (Sadek): vertex
              angles under 90 deg cut off, two triangles at angles up to 180 deg
  front       iterative removal of a boundary layer: the advancing front (Lo, Loehner),
              every new triangle checked to be Delaunay, then flips and smoothing
  quadtree    Yerry and Shephard's modified quadtree: 2:1 balanced, 45-degree templates
              inside, the boundary band triangulated (its own cuts of the boundary)

--quads makes all quadrilaterals with any method: its triangles at twice the size are
paired by a maximum-weight matching and split into quads (gmsh's Blossom recombination
plus subdivision); with the quadtree its interior lattice seeds the triangles.

A face's boundary points are the part's tessellation's, so neighbouring faces conform.
The output (.msh, .vtu, .mesh, .inp, .obj, .stl) is the faces' meshes on their planes,
tagged with the face ids; quads are written as quads (MSH type 3, VTU 9, Medit
Quadrilaterals, .inp S4), as two triangles in .obj and .stl.";

/// Arguments of `fepre mesh2d`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// STEP file (.step, .stp): its planar faces; or Triangle's .poly: its regions.
    pub cad: PathBuf,
    /// The 2D method.
    #[arg(long, short = 'm', value_name = "METHOD", default_value = "delaunay", value_parser = parse_method)]
    pub method: Method,
    /// Mesh this face (its id, as `fepre cad-info --json` lists them); may be repeated.
    #[arg(long, value_name = "N", conflicts_with = "all_planar")]
    pub face: Vec<u32>,
    /// Mesh every planar face (the default without --face).
    #[arg(long)]
    pub all_planar: bool,
    /// Element size (model units, mm for STEP); default the part's diagonal over 25.
    #[arg(long, value_name = "H", value_parser = crate::cli::positive)]
    pub size: Option<f64>,
    /// Smallest angle Delaunay refinement aims at, degrees.
    #[arg(long, value_name = "A", value_parser = crate::cli::positive)]
    pub min_angle: Option<f64>,
    /// Largest triangle area (Triangle's -a), besides the size.
    #[arg(long, value_name = "AREA", value_parser = crate::cli::positive)]
    pub max_area: Option<f64>,
    /// All quadrilaterals: the method's triangles at twice the size, paired (a
    /// maximum-weight matching) and split into quads (every edge halved).
    #[arg(long)]
    pub quads: bool,
    /// Exit 1 and write nothing when an angle is under A degrees.
    #[arg(long, value_name = "A", value_parser = crate::cli::positive)]
    pub require_min_angle: Option<f64>,
    /// Output: .msh, .vtu, .mesh, .inp, .obj or .stl.
    #[arg(short, long, value_name = "OUT")]
    pub output: Option<PathBuf>,
    /// Print one JSON object on standard output.
    #[arg(long)]
    pub json: bool,
}

fn parse_method(s: &str) -> Result<Method, String> {
    s.parse().map_err(|e: fepre::mesh2d::UnknownMethod| e.to_string())
}

/// Runs `fepre mesh2d`.
///
/// # Errors
/// Bad usage, an unreadable file, a face that cannot be meshed, a requirement not met, a
/// failed write.
pub fn run(args: &Args) -> Result<()> {
    let faces = if args.face.is_empty() { FaceChoice::AllPlanar } else { FaceChoice::Faces(args.face.iter().map(|&f| FaceId(f)).collect()) };
    let options = Mesh2dOptions { method: args.method, quads: args.quads, min_angle: args.min_angle, max_area: args.max_area, ..Mesh2dOptions::default() };
    let request = Mesh2dRequest { faces, size: args.size, options, require_min_angle: args.require_min_angle };
    let is_poly = args.cad.extension().is_some_and(|e| e.eq_ignore_ascii_case("poly"));
    if is_poly && !args.face.is_empty() {
        return Err(usage_error("--face picks faces of a STEP part; a .poly file's regions are all meshed"));
    }
    let result = if is_poly { mesh2d_poly(&args.cad, &request, args.output.as_deref()) } else { mesh2d_file(&args.cad, &request, args.output.as_deref()) };
    let rep = result.map_err(|e| match e {
        PipelineError::Usage { .. } => usage_error(e.to_string()),
        e => anyhow::Error::new(e),
    })?;
    if args.json {
        outln!("{}", serde_json::to_string_pretty(&rep)?);
    } else {
        print(&rep, is_poly);
    }
    crate::cli::print_warnings(&rep.warnings);
    Ok(())
}

/// The summary `fepre mesh2d` (and `fepre run` on a `[mesh2d]` job) prints.
pub fn print(rep: &fepre::pipeline::Mesh2dReport, is_poly: bool) {
    {
        let q = &rep.quality;
        outln!("method       {}{}", rep.method, if rep.all_quads { " (quads)" } else { "" });
        if is_poly {
            outln!("regions      {}", rep.meshed);
        } else {
            outln!("faces        {} ({} planar, {} meshed, {} failed)", rep.faces, rep.planar_faces, rep.meshed, rep.failed.len());
        }
        for f in &rep.failed {
            outln!("  failed face {} ({}): {}", f.face.0, f.step_id, f.reason);
        }
        outln!("size         {:.6}", rep.size);
        outln!("elements     {} triangles, {} quads, {} vertices", rep.triangles, rep.quads, rep.vertices);
        outln!("angles       {:.2}..{:.2} deg ({} triangles under 20 deg, {} under 30)", q.angle_range[0], q.angle_range[1], q.triangles_under[0], q.triangles_under[1]);
        if rep.quads > 0 {
            outln!("quads        scaled Jacobian min {:.3}, median {:.3}", q.quad_scaled_jacobian[0], q.quad_scaled_jacobian[1]);
        }
        outln!("size ratio   {:.2} / {:.2} / {:.2} (10 / 50 / 90 % of element size over the size asked)", q.size_ratio[0], q.size_ratio[1], q.size_ratio[2]);
        outln!("seconds      read {:.3}, mesh {:.3}, write {:.3} (total {:.3})", rep.seconds[0], rep.seconds[1], rep.seconds[2], rep.total_seconds);
        if let Some(o) = &rep.output {
            outln!("wrote        {o}");
        }
    }
}
