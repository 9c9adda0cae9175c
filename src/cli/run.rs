//! `fepre run job.toml`: runs a job file through [`fepre::pipeline`] and prints what it did.

use fepre::pipeline::job::JobFile;
use fepre::pipeline::{RunReport, run_job};
use anyhow::Result;
use std::path::PathBuf;

/// Examples shown by `fepre run --help`.
pub const EXAMPLES: &str = "\
Examples:
  fepre run cad_fixtures/bracket.toml          the bracket with half the size on its holes
  fepre run job.toml --check                   check the job and print what each selector selects; mesh nothing
  fepre run job.toml --json                    one JSON report (faces, selectors, sizes, quality, outputs)

A job file (every key in docs/job-file.md):
  units = \"mm\"
  [input]
  file = \"bracket.step\"                        # relative to the job file
  [selectors]
  holes = { name = \"hole_*\" }                  # also: faces, colour, step_id, solid, plane, cylinder,
                                               # inside, nearest, largest, smallest, union, intersection, difference
  [density]
  size = 4.5                                   # global; grading, min, max, curvature, deviation
  face = [{ faces = \"holes\", size = 2.25 }]    # also: distance, point, box
  [mesh]
  method = \"delaunay\"                          # max_radius_edge, min_dihedral, keep_surface, narrow_tolerance
  [[output]]
  file = \"bracket.msh\"                         # .msh .vtu .mesh .ele (tets), .stl .obj (surface), .json (report),
                                               # .inp (CalculiX/Abaqus deck: needs [materials], [[section]], [[step]])

Errors in the job name the key with its line and column; nothing is written then.";

/// Arguments of `fepre run`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The job file (TOML).
    pub job: PathBuf,
    /// Check the job and print what each selector selects; mesh and write nothing.
    #[arg(long)]
    pub check: bool,
    /// Print one JSON object on standard output.
    #[arg(long)]
    pub json: bool,
}

/// Runs `fepre run`.
///
/// # Errors
/// A job error (naming the key and line), an unreadable input, a selector that selects
/// nothing, a failed certificate, a mesher error, a requirement not met: exit 1.
pub fn run(args: &Args) -> Result<()> {
    let progress = crate::cli::progress::Progress::start(&format!("running {}", args.job.display()));
    let jf = JobFile::read(&args.job)?;
    let polygons = jf.job.mesh2d.as_ref().is_some_and(|m| !m.region.is_empty());
    if polygons && args.check {
        let n = fepre::pipeline::check_mesh2d_regions(&jf)?;
        progress.finish();
        outln!("job OK: {n} polygon region(s) for [mesh2d]");
        return Ok(());
    }
    if jf.job.mesh2d.is_some() && !args.check {
        // a 2D job: the lecture's 2D methods on the part's planar faces or a .poly's regions
        let report = fepre::pipeline::mesh2d_job(&jf)?;
        progress.finish();
        if args.json {
            outln!("{}", serde_json::to_string_pretty(&report)?);
        } else {
            crate::cli::mesh2d::print(&report, polygons || report.input.to_ascii_lowercase().ends_with(".poly"));
        }
        crate::cli::print_warnings(&report.warnings);
        return Ok(());
    }
    let report = run_job(&jf, args.check)?;
    progress.finish();
    if args.json {
        outln!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print(&report, args.check);
    }
    crate::cli::print_warnings(&report.warnings);
    Ok(())
}

fn print(r: &RunReport, check: bool) {
    outln!("input            {}", r.input);
    outln!("faces            {}", r.face_table.len());
    for (name, faces) in &r.selectors {
        let names: Vec<String> = faces
            .iter()
            .map(|f| match r.face_table.iter().find(|x| x.face == *f).and_then(|x| x.name.clone()) {
                Some(n) => format!("{} ({n})", f.0),
                None => f.0.to_string(),
            })
            .collect();
        outln!("selector         {name}: {} faces: {}", faces.len(), names.join(", "));
    }
    outln!("size             {:.4} (global)", r.global_size);
    if check {
        outln!("check            the job is valid; nothing meshed or written");
        return;
    }
    if let Some(m) = &r.mesh {
        outln!("surface          {} triangles{}", r.surface_triangles, if r.certificate_passed == Some(true) { ", certificate passed" } else { "" });
        crate::cli::print_mesh_summary(m, r.octree.is_none());
    }
    crate::cli::contacts::print(&r.contacts);
    if let Some(fe) = &r.fe {
        crate::cli::print_fe_summary(fe);
    }
    for o in &r.outputs {
        outln!("wrote            {o}");
    }
}
