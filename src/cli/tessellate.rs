//! `fepre tessellate CAD -o OUT`: a watertight, certified triangle surface of a STEP file,
//! every triangle tagged with its B-rep face.
//!
//! Reads the STEP file, tessellates every face at the chord deviation asked for, checks the
//! result with [`fepre::tessellate::certificate`] and writes it only when the certificate
//! passes (or with `--force`). Exit codes: 0 written, 1 the file could not be read or the
//! certificate failed (the message names the face and its STEP `#id`, or the solid left open
//! and its free edges; no file is written), 2 bad usage. A surface model left open after
//! sewing exits 0 with `watertight: false` and its holes listed (`open_surface`); open
//! surface shells beside solids are listed the same way, and `watertight` speaks of the
//! solids.

use crate::cli::usage_error;
use fepre::pipeline::PipelineError;
use fepre::pipeline::{BrepTessellation, TessellateFailure, TessellateReport, TessellateStepOptions, TessellatedFileReport, tessellate_step};
use anyhow::Result;
use std::path::PathBuf;

/// Examples shown by `fepre tessellate --help`.
pub const EXAMPLES: &str = "\
Examples:
  fepre tessellate part.step -o part.stl                 certified surface, default deviation (2e-4 of the model size, less on slender parts)
  fepre tessellate part.step -o part.msh --deviation 5e-5  finer; MSH 4.1 keeps each face as a physical group
  fepre tessellate part.stp -o part.vtu --json           one JSON report: Euler per shell, volume, area, checks
  fepre tessellate part.step -o part.obj --force         write even when a check fails (the report says which)
  fepre tessellate part.step -o part.stl --max-edge 2    well-shaped triangles of edge about 2 mm (a volume mesher's input)

The output format follows the extension: .stl, .obj (one group per face), .vtu (face ids as
cell data), .msh (MSH 4.1, one physical group per face). The file is written only when the
certificate passes: closed, manifold, oriented outward, no self-intersection, Euler
characteristic and boundary loops as the B-rep's, volume and area within tolerance of the
B-rep's own (quadrature over the exact surfaces).";

/// Arguments of `fepre tessellate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// STEP file (.step, .stp; AP203, AP214, AP242).
    pub cad: PathBuf,
    /// Output surface: .stl, .obj, .vtu or .msh.
    #[arg(short, long, value_name = "OUT")]
    pub output: PathBuf,
    /// Largest distance between the triangles and the exact surface, as a fraction of the
    /// model size (the diagonal of its bounding box). Without it, 2e-4, and smaller on the
    /// faces of a solid that would lose more than 0.4 % of its volume (slender and thin
    /// parts); with it, exactly this everywhere: a deviation so coarse that a solid's volume
    /// is off by more than 0.5 % fails the certificate.
    #[arg(long, value_name = "REL", value_parser = positive_fraction)]
    pub deviation: Option<f64>,
    /// Longest triangle edge (model units, mm for STEP): edges are cut to it and faces refined
    /// to well-shaped triangles of about this size, as a volume mesher wants its boundary;
    /// smaller on faces narrower than it and across walls of the solid thinner than a third
    /// of it (1.5 times their width or thickness, down to 1/256 of it across a face and 1/64
    /// across the solid).
    #[arg(long, value_name = "H", value_parser = crate::cli::positive)]
    pub max_edge: Option<f64>,
    /// Print one JSON object on standard output.
    #[arg(long)]
    pub json: bool,
    /// Write the surface even when the certificate fails (exit code 0, failures reported).
    #[arg(long)]
    pub force: bool,
}

/// clap's adapter for [`fepre::attributes::Fraction::new`].
fn positive_fraction(s: &str) -> Result<f64, String> {
    let x = crate::cli::parse_fraction(s)?;
    fepre::attributes::Fraction::new(x).map(|f| f.0).ok_or_else(|| format!("'{s}' must be in (0, 0.1]"))
}

/// The lines that say where a surface is open.
fn print_open(r: &BrepTessellation) {
    if let Some(o) = &r.open_surface {
        let beside = if r.watertight_of == "solids" { " beside the solids (not part of `watertight`)" } else { "" };
        outln!("open shells  {}{beside}: {} free edges in {} hole{}", o.shells, o.free_edges, o.holes.len(), if o.holes.len() == 1 { "" } else { "s" });
        for h in o.holes.iter().take(10) {
            outln!("  hole       {}", h.describe());
        }
        if o.holes.len() > 10 {
            outln!("  ... {} more holes (--json lists all)", o.holes.len() - 10);
        }
    }
    for h in r.certificate.open_solids.iter().take(10) {
        outln!("OPEN SOLID   {}: {}", h.shells.iter().map(|s| format!("shell {s}")).collect::<Vec<_>>().join(", "), h.describe());
    }
}

/// Runs `fepre tessellate`.
///
/// # Errors
/// An unreadable STEP file or a failed certificate without `--force` (exit 1); an output
/// format that cannot hold a surface (exit 2).
pub fn run(args: &Args) -> Result<()> {
    let out = &args.output;
    let options = TessellateStepOptions { deviation: args.deviation, max_edge: args.max_edge, force: args.force };
    let r = match tessellate_step(&args.cad, &options, out) {
        Ok(TessellateReport::Brep(r)) => r,
        Ok(TessellateReport::Tessellated(r)) => return print_tessellated(args, &r),
        Err(TessellateFailure { report, error }) => {
            if let (Some(report), true) = (report, args.json) {
                outln!("{}", serde_json::to_string_pretty(&report)?);
            }
            return Err(match error {
                e @ PipelineError::Usage { .. } => usage_error(e.to_string()),
                e => anyhow::Error::new(e),
            });
        }
    };
    let passed = r.certificate.passed;
    if args.json {
        outln!("{}", serde_json::to_string_pretty(&r)?);
    } else {
        outln!("solids       {} ({} surface-model shells)", r.solids, r.surface_model_shells);
        if let Some(sw) = &r.sewing {
            outln!("sewn         {} edges and {} vertices merged (tolerance {:.3e} mm), free edges {} -> {}", sw.merged_edges, sw.merged_vertices, sw.tolerance, sw.free_edges_before, sw.free_edges_after);
            for x in sw.splits.iter().take(10) {
                outln!("  split      edge {} at vertex {} ({:.6}, {:.6}, {:.6})", x.edge, x.vertex, x.at[0], x.at[1], x.at[2]);
            }
        }
        for x in &r.certificate.reoriented {
            let shells: Vec<String> = x.brep_shells.iter().map(|s| s.to_string()).collect();
            let what = if x.void { "void, enclosed" } else { "enclosed" };
            outln!("reoriented   shell {} ({} faces, {what} {:.6e} mm3 as written): its face senses disagree with its geometry: turned (OpenCASCADE turns it too)", shells.join(" "), x.faces, x.volume_as_written);
        }
        if !r.certificate.turned_faces.is_empty() {
            let faces: Vec<String> = r.certificate.turned_faces.iter().map(|s| s.to_string()).collect();
            outln!("turned       {} faces ({}): their sense disagreed with their loops and their neighbours across most shared edges: turned", faces.len(), faces.join(" "));
        }
        outln!("faces        {} ({} failed)", r.faces, r.failed_faces.len());
        outln!("triangles    {} ({} vertices)", r.triangles, r.vertices);
        outln!("watertight   {} (of the {})", r.watertight, r.watertight_of);
        print_open(&r);
        let e: Vec<String> = r.euler.iter().map(|e| format!("{}/{}", e.mesh, e.brep)).collect();
        outln!("euler        {} (mesh/B-rep per shell)", e.join(" "));
        outln!("volume mm3   {:.9} (B-rep {:.9})", r.volume, r.certificate.volume[1]);
        outln!("area mm2     {:.9} (B-rep {:.9})", r.area, r.certificate.area[1]);
        outln!("certificate  {}", if passed { "passed" } else { "FAILED (written with --force)" });
        if let Some(m) = &r.failure_message {
            outln!("{m}");
        }
        outln!("dropped      {}", r.dropped.len());
        for n in &r.notes {
            outln!("note         {n}");
        }
        outln!("seconds      {:.3}", r.seconds);
        outln!("wrote        {}", out.display());
    }
    crate::cli::print_warnings(&r.warnings);
    Ok(())
}

/// Prints what `fepre tessellate` made of a file of tessellated geometry only.
fn print_tessellated(args: &Args, r: &TessellatedFileReport) -> Result<()> {
    if args.json {
        outln!("{}", serde_json::to_string_pretty(r)?);
        crate::cli::print_warnings(&r.warnings);
        return Ok(());
    }
    let out = &args.output;
    let (s, c) = (&r.summary, &r.certificate);
    outln!("geometry     tessellated only (AP242): the file's triangles, certified as a mesh (--deviation and --max-edge do not apply)");
    outln!("solids       {} TESSELLATED_SOLID, {} TESSELLATED_SHELL", s.solids, s.shells);
    outln!("faces        {}", s.faces);
    outln!("triangles    {} ({} vertices)", s.triangles, s.vertices);
    outln!("watertight   {}", c.closed && c.manifold && c.oriented && c.outward);
    outln!("volume mm3   {:.9}", c.volume);
    outln!("area mm2     {:.9}", c.area);
    outln!("certificate  {}", if c.passed { "passed (as a mesh)" } else { "FAILED (written with --force)" });
    if let Some(m) = &r.failure_message {
        outln!("{m}");
    }
    outln!("dropped      {}", r.dropped.len());
    outln!("seconds      {:.3}", r.seconds);
    outln!("wrote        {}", out.display());
    crate::cli::print_warnings(&r.warnings);
    Ok(())
}
