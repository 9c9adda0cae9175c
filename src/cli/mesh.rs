//! `fepre mesh SURFACE -o OUT`: a quality tetrahedral mesh of the volume a closed surface
//! encloses, boundary tags kept.

use crate::cli::progress::Progress;
use crate::cli::usage_error;
use crate::core::size_field::UniformSize;
use crate::io::{self, Format, MeshData, ReadOptions, WriteOptions};
use crate::mesh3d::mesher::{MeshOptions, MeshReport, RegionSeed, Seeds, mesh_surface};
use crate::quality::tet_mesh_quality;
use anyhow::{Context, Result};
use serde::Serialize;
use std::path::PathBuf;
use std::time::Instant;

/// Examples shown by `fepre mesh --help`.
pub const EXAMPLES: &str = "\
Examples:
  fepre mesh part.stl -o part.mesh                      quality tets (radius-edge 1.5, dihedral 18° aimed at)
  fepre mesh plc.poly -o plc.vtu --size 0.16            edge length about 0.16 everywhere; holes and regions from the .poly
  fepre mesh part.obj -o part.msh --keep-surface        the boundary triangles exactly as given (no Steiner points on them)
  fepre mesh part.stl -o part.1.ele --json              TetGen files; one JSON report on standard output
  fepre mesh part.step -o part.mesh                     a STEP part: tessellated, certified, then meshed; tags = CAD face ids

Every boundary triangle of the result carries the tag of the input triangle it lies in (STL
solid, OBJ group, glTF primitive, .poly facet marker); each tet carries its region.";

/// Arguments of `fepre mesh`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Closed surface: STL, OBJ, GLB/glTF, OFF, TetGen .poly/.smesh, Medit .mesh; or a STEP
    /// part (.step, .stp), tessellated at the default deviation and certified first.
    pub surface: PathBuf,
    /// Output tet mesh; its extension picks the format (.mesh, .ele/.node, .vtu, .msh).
    #[arg(short, long, value_name = "OUT")]
    pub output: PathBuf,
    /// Wanted edge length everywhere (model units); default: as coarse as quality allows.
    #[arg(long, value_name = "H", value_parser = positive)]
    pub size: Option<f64>,
    /// Largest circumradius-to-shortest-edge ratio of a tet (at least 1.1).
    #[arg(long, value_name = "R", default_value_t = 1.5, value_parser = radius_edge)]
    pub max_radius_edge: f64,
    /// Smallest dihedral angle (degrees) the optimisation works towards (0 to 35).
    #[arg(long, value_name = "D", default_value_t = 18.0, value_parser = dihedral)]
    pub min_dihedral: f64,
    /// Keep the input surface exactly: no Steiner point on the boundary.
    #[arg(long)]
    pub keep_surface: bool,
    /// Print one JSON object on standard output.
    #[arg(long)]
    pub json: bool,
}

/// Without `--size`, a STEP part's surface triangles are about its diagonal over this.
const DEFAULT_DIVISIONS: f64 = 25.0;

/// True for a `.step` or `.stp` path (any case).
fn is_step(path: &std::path::Path) -> bool {
    path.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("step") || e.eq_ignore_ascii_case("stp"))
}

pub(crate) fn positive(s: &str) -> Result<f64, String> {
    let x: f64 = s.parse().map_err(|_| format!("'{s}' is not a number"))?;
    if x.is_finite() && x > 0.0 { Ok(x) } else { Err(format!("'{s}' must be a finite number > 0")) }
}

fn radius_edge(s: &str) -> Result<f64, String> {
    let x = positive(s)?;
    if x >= 1.1 { Ok(x) } else { Err(format!("{x} is below 1.1: no tetrahedral mesh reaches it (the regular tet has 0.61, but refinement cannot end below about 1.1)")) }
}

fn dihedral(s: &str) -> Result<f64, String> {
    let x = positive(s).or_else(|e| if s.trim() == "0" { Ok(0.0) } else { Err(e) })?;
    if x <= 35.0 { Ok(x) } else { Err(format!("{x}° is above 35°: no mesher can promise it")) }
}

#[derive(Serialize)]
struct Report {
    input: String,
    output: String,
    nodes: usize,
    tets: usize,
    seconds: f64,
    read_seconds: f64,
    min_dihedral_deg: f64,
    max_dihedral_deg: f64,
    max_radius_edge: f64,
    volume: f64,
    boundary_steiner_points: usize,
    regions: usize,
    /// Per boundary face tag: unique name (and for STEP parts colour, STEP `#id`, solid).
    face_table: Vec<crate::cad::brep::FaceEntry>,
    mesher: MeshReport,
}

/// Runs `fepre mesh`.
///
/// # Errors
/// An unreadable, open, non-manifold or self-intersecting surface (exit 1); an output format
/// that cannot hold tets (exit 2).
pub fn run(args: &Args) -> Result<()> {
    let out = &args.output;
    if !matches!(Format::from_path(out), Some(Format::Medit | Format::TetGen | Format::Vtu | Format::Msh)) {
        return Err(usage_error(format!("{}: tets are written as .mesh, .ele/.node, .vtu or .msh", out.display())));
    }
    let progress = Progress::start(&format!("reading {}", args.surface.display()));
    let t0 = Instant::now();
    let (surface, seeds, face_table) = if is_step(&args.surface) {
        // a CAD part: tessellated at the default deviation into well-shaped triangles of the
        // size (or, without one, a 25th of the part's diagonal), and certified first; its
        // faces' ids become the boundary tags
        let size = args.size;
        let edge = move |model_size: f64| size.unwrap_or(model_size / DEFAULT_DIVISIONS);
        let opts = crate::tessellate::TessellateOptions::default();
        let c = crate::cli::tessellate::read_and_certify_with(&args.surface, &opts, Some(&edge))?;
        if !c.certificate.passed {
            anyhow::bail!("{}", crate::cli::tessellate::failure_message(&args.surface, &c.certificate, &c.model.dropped));
        }
        let table = c.model.face_table();
        (c.tessellation.surface, Seeds::default(), table)
    } else {
        let loaded = io::read(&args.surface, &ReadOptions::default())?;
        let surface = match loaded.mesh {
            MeshData::Surface(s) => s,
            other => anyhow::bail!("{}: a closed surface is needed, this file holds a {}", args.surface.display(), other.kind()),
        };
        let seeds = Seeds {
            holes: loaded.seeds.holes.clone(),
            regions: loaded.seeds.regions.iter().map(|&(point, tag, _)| RegionSeed { point, tag }).collect(),
        };
        let table = crate::cad::brep::face_table_of_names(&surface.face_names, surface.face_tags.iter().copied());
        (surface, seeds, table)
    };
    let read_seconds = t0.elapsed().as_secs_f64();
    let options = MeshOptions::default()
        .with_max_radius_edge(args.max_radius_edge)
        .with_min_dihedral(args.min_dihedral)
        .with_keep_surface(args.keep_surface)
        .with_presize(!is_step(&args.surface));
    progress.stage(&format!("meshing {} triangles", surface.triangles.len()));
    let size = UniformSize(args.size.unwrap_or(f64::INFINITY));
    let (mesh, report) = mesh_surface(&surface, &seeds, &size, &options).with_context(|| args.surface.display().to_string())?;
    progress.stage(&format!("writing {}", out.display()));
    io::write(out, &MeshData::Volume(mesh.clone()), &WriteOptions::default())?;
    progress.finish();
    let q = tet_mesh_quality(&mesh);
    let r = Report {
        input: args.surface.display().to_string(),
        output: out.display().to_string(),
        nodes: mesh.vertices.len(),
        tets: mesh.tets.len(),
        seconds: report.seconds,
        read_seconds,
        min_dihedral_deg: q.min_dihedral_deg,
        max_dihedral_deg: q.max_dihedral_deg,
        max_radius_edge: q.max_radius_edge,
        volume: mesh.volume(),
        boundary_steiner_points: report.boundary_steiner_points,
        regions: report.regions,
        face_table,
        mesher: report,
    };
    if args.json {
        println!("{}", serde_json::to_string_pretty(&r)?);
    } else {
        println!("nodes            {}", r.nodes);
        println!("tets             {}", r.tets);
        println!("regions          {}", r.regions);
        println!("volume           {:.9}", r.volume);
        println!("dihedral         {:.2}° .. {:.2}°", r.min_dihedral_deg, r.max_dihedral_deg);
        println!("max radius-edge  {:.3}", r.max_radius_edge);
        println!("boundary Steiner {}", r.boundary_steiner_points);
        println!("seconds          {:.3} (read {:.3})", r.seconds, r.read_seconds);
        for (stage, s) in &r.mesher.stage_seconds {
            println!("  {stage:<10} {s:.3}");
        }
        println!("wrote            {}", r.output);
    }
    Ok(())
}
