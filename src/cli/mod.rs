//! Layer 6: the command line. One file per subcommand; this file holds the argument types
//! and the mapping of outcomes to exit codes: 0 ok, 1 the input could not be processed,
//! 2 bad usage.

pub mod cad_info;
mod contacts;
pub mod convert;
pub mod delaunay;
pub mod inspect;
pub mod mesh;
pub mod progress;
pub mod run;
pub mod tessellate;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

const EXAMPLES: &str = "\
Examples:
  fepre inspect part.stl                   report topology: closed, manifold, genus, volume, self-intersections
  fepre inspect part.stl --json            the same report as one JSON object
  fepre inspect mesh.1.ele                 a tet mesh: also dihedral angles, radius-edge ratios, inverted tets
  fepre convert model.glb model.msh        any format fepre reads to any it writes, tags kept
  fepre convert mesh.mesh boundary.stl     a tet mesh's tagged boundary as a surface
  fepre delaunay points.xyz -o dt.mesh     exact Delaunay tetrahedralization of a point set
  fepre mesh part.stl -o part.mesh         quality tet mesh of a closed surface, boundary tags kept
  fepre cad-info part.step                 what fepre reads from a STEP file: counts, units, dropped items
  fepre tessellate part.step -o part.stl   certified watertight surface of a STEP file, face tags kept
  fepre mesh part.step -o part.mesh        STEP straight to quality tets (tessellated and certified first)
  fepre run job.toml                       a job file: selectors on CAD faces, sizes per face, outputs

Exit codes: 0 ok, 1 the input could not be processed, 2 bad usage.";

/// fepre: a finite-element preprocessor. CAD parts and surface meshes in; watertight tagged
/// surfaces, quality tetrahedral meshes and solver decks out.
#[derive(Debug, Parser)]
#[command(name = "fepre", version, about, after_help = EXAMPLES, propagate_version = true)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Report a mesh file's topology (components, closed, manifold, oriented, Euler
    /// characteristic, genus, volume, self-intersections) and, for tet meshes, element quality.
    #[command(after_help = inspect::EXAMPLES)]
    Inspect(inspect::Args),
    /// Delaunay tetrahedralization of a point set (exact, any degeneracy), optionally written
    /// as a tet mesh.
    #[command(after_help = delaunay::EXAMPLES)]
    Delaunay(delaunay::Args),
    /// Quality tetrahedral mesh of the volume a closed surface encloses (boundary recovery,
    /// Delaunay refinement, sliver removal), boundary tags and regions kept.
    #[command(after_help = mesh::EXAMPLES)]
    Mesh(mesh::Args),
    /// Convert a mesh between formats, chosen from the file extensions; tags are kept where the
    /// output format can hold them.
    #[command(after_help = convert::EXAMPLES)]
    Convert(convert::Args),
    /// Read a STEP file (AP203/AP214/AP242) and report solids, shells, faces, edges, vertices,
    /// units, surface kinds and every item left out.
    #[command(after_help = cad_info::EXAMPLES)]
    CadInfo(cad_info::Args),
    /// Tessellate a STEP file into a watertight triangle surface tagged with its B-rep faces,
    /// checked by a certificate (closed, manifold, outward, no self-intersection, Euler,
    /// boundary loops, volume and area against the B-rep's).
    #[command(after_help = tessellate::EXAMPLES)]
    Tessellate(tessellate::Args),
    /// Run a job file (TOML): the input, units, selectors on CAD faces, density (sizes per
    /// face, by distance, by curvature, in boxes), mesh options and outputs.
    #[command(after_help = run::EXAMPLES)]
    Run(run::Args),
}

/// Parses the arguments, runs the command and returns the process exit code.
pub fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            // --help and --version print and succeed; everything else is bad usage (2)
            let _ = e.print();
            return ExitCode::from(if e.use_stderr() { 2 } else { 0 });
        }
    };
    let result = match cli.command {
        Command::Inspect(a) => inspect::run(&a),
        Command::Convert(a) => convert::run(&a),
        Command::Delaunay(a) => delaunay::run(&a),
        Command::Mesh(a) => mesh::run(&a),
        Command::CadInfo(a) => cad_info::run(&a),
        Command::Tessellate(a) => tessellate::run(&a),
        Command::Run(a) => run::run(&a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {}", message(&e));
            ExitCode::from(if e.is::<UsageError>() { 2 } else { 1 })
        }
    }
}

/// The error and its causes, each cause added only where the message does not already say it
/// (library errors such as `IoError` include their cause in their own text).
fn message(e: &anyhow::Error) -> String {
    let mut msg = e.to_string();
    for cause in e.chain().skip(1) {
        let c = cause.to_string();
        if !msg.contains(&c) {
            msg.push_str(": ");
            msg.push_str(&c);
        }
    }
    msg
}

/// A usage error found after parsing (an impossible option value, an output format fepre
/// cannot write): exit code 2.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct UsageError(pub String);

/// Wraps a message as a [`UsageError`].
pub fn usage_error(message: impl Into<String>) -> anyhow::Error {
    anyhow::Error::new(UsageError(message.into()))
}

/// Prints a tet mesh's size and quality, with a warning where refinement stopped early
/// (`max_radius_edge`: the bound it aimed at) or a tet is under 1° (`require`: the option that
/// makes that an error). Shared by `fepre mesh` and `fepre run`.
pub(crate) fn print_mesh_summary(m: &crate::pipeline::run::MeshSummary, max_radius_edge: Option<f64>, require: &str) {
    println!("nodes            {}", m.nodes);
    println!("tets             {}", m.tets);
    println!("regions          {}", m.regions);
    println!("volume           {:.9}", m.volume);
    println!("dihedral         {:.2}° .. {:.2}° ({} tets under 5°, {} under 1°)", m.min_dihedral_deg, m.max_dihedral_deg, m.tets_under_5_deg, m.tets_under_1_deg);
    println!("max radius-edge  {:.3}", m.max_radius_edge);
    if m.refinement_stopped {
        let bound = max_radius_edge.map(|r| format!(" before every tet met radius-edge {r}")).unwrap_or_default();
        println!("warning          refinement stopped at its point budget{bound} (small input angles)");
    }
    if m.tets_under_1_deg > 0 {
        println!("warning          {} tets have a dihedral angle under 1°; {require} makes this an error", m.tets_under_1_deg);
    }
}

/// Parses a finite number `> 0`.
pub fn positive(s: &str) -> Result<f64, String> {
    let x: f64 = s.parse().map_err(|_| format!("'{s}' is not a number"))?;
    if x.is_finite() && x > 0.0 { Ok(x) } else { Err(format!("'{s}' must be a finite number > 0")) }
}

/// Parses a non-negative finite fraction (relative tolerances).
pub fn parse_fraction(s: &str) -> Result<f64, String> {
    let x: f64 = s.parse().map_err(|_| format!("'{s}' is not a number"))?;
    if x.is_finite() && x >= 0.0 { Ok(x) } else { Err(format!("'{s}' must be a finite number >= 0")) }
}
