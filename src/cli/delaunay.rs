//! `fepre delaunay POINTS`: the Delaunay tetrahedralization of a point set.

use crate::cli::progress::Progress;
use crate::cli::usage_error;
use fepre::io::{self, Format, MeshData, ReadOptions, WriteOptions};
use fepre::mesh3d::delaunay::{DelaunayOptions, KernelKind, count_tetrahedra, tetrahedralize};
use anyhow::{Context, Result};
use serde::Serialize;
use std::path::PathBuf;
use std::time::Instant;

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

#[derive(Serialize)]
struct Report {
    points: usize,
    tets: usize,
    duplicates: usize,
    kernel: KernelKind,
    threads: usize,
    /// Time of the tetrahedralization inside the program (ordering, insertion and, when the
    /// tets are written, their canonical ordering).
    seconds: f64,
    read_seconds: f64,
    output: Option<String>,
    timings: fepre::mesh3d::delaunay::DelaunayTimings,
}

/// Runs `fepre delaunay`.
///
/// # Errors
/// Unreadable points, a point set spanning no tetrahedron (exit 1); an output extension that
/// cannot hold tets (exit 2).
pub fn run(args: &Args) -> Result<()> {
    if let Some(out) = &args.output {
        let ok = matches!(Format::from_path(out), Some(Format::Medit | Format::TetGen | Format::Vtu | Format::Msh));
        if !ok {
            return Err(usage_error(format!("{}: tets are written as .mesh, .ele/.node, .vtu or .msh", out.display())));
        }
    }
    let threads = args.threads.map(usize::from).unwrap_or_else(rayon::current_num_threads);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().context("cannot start the worker threads")?;
    pool.install(|| run_in_pool(args, threads))
}

fn run_in_pool(args: &Args, threads: usize) -> Result<()> {
    let progress = Progress::start(&format!("reading {}", args.points.display()));
    let t0 = Instant::now();
    let points = io::read_points(&args.points)?;
    let read_seconds = t0.elapsed().as_secs_f64();
    progress.stage(&format!("tetrahedralizing {} points", points.len()));
    let t1 = Instant::now();
    // without an output file the tets are only counted, as `tetgen -NEF` and CGAL's driver do
    let build = if args.output.is_some() { tetrahedralize } else { count_tetrahedra };
    let d = build(&points, &DelaunayOptions::default()).with_context(|| args.points.display().to_string())?;
    let seconds = t1.elapsed().as_secs_f64();
    if let Some(out) = &args.output {
        progress.stage(&format!("writing {}", out.display()));
        io::write(out, &MeshData::Volume(d.to_tet_mesh(&points)), &WriteOptions::default())?;
    }
    progress.finish();
    let report = Report {
        points: points.len(),
        tets: d.count,
        duplicates: d.duplicates.len(),
        kernel: d.kernel,
        threads,
        seconds,
        read_seconds,
        output: args.output.as_ref().map(|p| p.display().to_string()),
        timings: d.timings.clone(),
    };
    if args.json {
        outln!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        outln!("points      {}", report.points);
        outln!("tets        {}", report.tets);
        outln!("duplicates  {}", report.duplicates);
        for pair in d.duplicates.iter().take(10) {
            outln!("  point {} coincides with point {} (left out)", pair[0], pair[1]);
        }
        outln!("kernel      {:?}", report.kernel);
        outln!("threads     {threads}");
        outln!("Delaunay seconds: {seconds:.4}");
        outln!("read seconds:     {read_seconds:.4}");
        if let Some(o) = &report.output {
            outln!("wrote       {o}");
        }
    }
    let _ = ReadOptions::default();
    Ok(())
}
