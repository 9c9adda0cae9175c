//! `fepre delaunay POINTS`: the Delaunay tetrahedralization of a point set. Parses, calls
//! [`fepre::pipeline::delaunay_file`], prints.

use crate::cli::progress::Progress;
use crate::cli::usage_error;
use fepre::pipeline::{PipelineError, UsageProblem, delaunay_file};
use anyhow::Result;
use std::path::PathBuf;

/// Examples shown by `fepre delaunay --help`.
pub const EXAMPLES: &str = "\
Examples:
  fepre delaunay points.xyz                      statistics only (points, tets, duplicates, seconds)
  fepre delaunay points.node -o dt.mesh          write the tets (Medit); .ele/.node (TetGen) and .vtu work too
  fepre delaunay points.xyz --threads 1 --json   single-threaded, one JSON object";

/// Arguments of `fepre delaunay`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Points: `.xyz` (x y z per line) or a TetGen `.node`.
    pub points: PathBuf,
    /// Output tet mesh; its extension picks the format (.mesh, .ele/.node, .vtu, .msh).
    #[arg(short, long, value_name = "OUT")]
    pub output: Option<PathBuf>,
    /// Worker threads (default: all cores). The tets are the same for any number.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..))]
    pub threads: Option<u16>,
    /// Print one JSON object on standard output.
    #[arg(long)]
    pub json: bool,
}

/// Runs `fepre delaunay`.
///
/// # Errors
/// Unreadable points, a point set spanning no tetrahedron (exit 1); an output extension that
/// cannot hold tets (exit 2).
pub fn run(args: &Args) -> Result<()> {
    let progress = Progress::start(&format!("reading {}", args.points.display()));
    let report = delaunay_file(&args.points, args.output.as_deref(), args.threads.map(usize::from), &|s| progress.stage(s)).map_err(|e| match e {
        PipelineError::Usage { problem: UsageProblem::TetFormat, .. } => usage_error(e.to_string()),
        e => anyhow::Error::new(e),
    })?;
    progress.finish();
    if args.json {
        outln!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        outln!("points      {}", report.points);
        outln!("tets        {}", report.tets);
        outln!("duplicates  {}", report.duplicates);
        for pair in &report.first_duplicates {
            outln!("  point {} coincides with point {} (left out)", pair[0], pair[1]);
        }
        outln!("kernel      {:?}", report.kernel);
        outln!("threads     {}", report.threads);
        outln!("Delaunay seconds: {:.4}", report.seconds);
        outln!("read seconds:     {:.4}", report.read_seconds);
        if let Some(o) = &report.output {
            outln!("wrote       {o}");
        }
    }
    Ok(())
}
