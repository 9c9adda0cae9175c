//! `fepre cad-info FILE`: what fepre reads from a STEP file: solids, shells, faces, edges and
//! vertices (assembly instances expanded), units, faces per surface kind, and every item it
//! left out with the reason.

use fepre::pipeline::{BrepInfo, CadInfo, CadInfoOptions, TessellatedInfo, cad_info};
use anyhow::Result;
use std::fmt::Write as _;
use std::path::PathBuf;

/// Examples shown by `fepre cad-info --help`.
pub const EXAMPLES: &str = "\
Examples:
  fepre cad-info part.step                 counts, units, surface kinds, dropped items
  fepre cad-info assembly.stp --json       the same as one JSON object
  fepre cad-info part.step --mesh          tessellate too: closed? volume? (fepre tessellate writes it, certified)";

/// Arguments of `fepre cad-info`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// STEP file (.step, .stp; AP203, AP214, AP242).
    pub file: PathBuf,
    /// Print one JSON object on standard output instead of the text report.
    #[arg(long)]
    pub json: bool,
    /// List at most N dropped items in the text report (the JSON lists them all).
    #[arg(long, value_name = "N", default_value_t = 20)]
    pub max_listed: usize,
    /// Also tessellate the faces and report the surface: triangles, closed, volume.
    #[arg(long)]
    pub mesh: bool,
    /// Chord deviation of `--mesh`, as a fraction of the model size (as `fepre tessellate`).
    #[arg(long, value_name = "REL", alias = "chord", default_value_t = 2e-4, value_parser = crate::cli::parse_fraction)]
    pub deviation: f64,
}

/// Runs `fepre cad-info`.
///
/// # Errors
/// When the file cannot be read as STEP (the message names the line or `#id`).
pub fn run(args: &Args) -> Result<()> {
    let info = cad_info(&args.file, &CadInfoOptions { mesh: args.mesh, deviation: args.deviation })?;
    if args.json {
        outln!("{}", serde_json::to_string_pretty(&info)?);
    } else {
        match &info {
            CadInfo::Brep(r) => out!("{}", text(r, args.max_listed)),
            CadInfo::Tessellated(r) => out!("{}", tessellated_text(r, args.max_listed)),
        }
    }
    crate::cli::print_warnings(info.warnings());
    Ok(())
}

/// The text report of a file of tessellated geometry only.
fn tessellated_text(r: &TessellatedInfo, max_listed: usize) -> String {
    let (s, c) = (&r.summary, &r.certificate);
    let mut out = String::new();
    let _ = writeln!(out, "file        {}", r.file);
    let _ = writeln!(out, "geometry    tessellated only (AP242): no B-rep; meshed as a surface mesh is");
    let _ = writeln!(out, "units       {} (x{} to mm)", r.units.length, r.units.to_mm);
    let _ = writeln!(out, "solids      {} TESSELLATED_SOLID, {} TESSELLATED_SHELL", s.solids, s.shells);
    let _ = writeln!(out, "faces       {} ({} triangles, {} vertices)", s.faces, s.triangles, s.vertices);
    if let Some(e) = r.extent {
        let _ = writeln!(out, "extent mm   {:.6} x {:.6} x {:.6}", e[0], e[1], e[2]);
    }
    let _ = writeln!(out, "mesh        closed {}, manifold {}, oriented {}, outward {}, {} open edges, {} self-intersections", c.closed, c.manifold, c.oriented, c.outward, c.open_edges, c.self_intersections);
    let _ = writeln!(out, "volume mm3  {:.6}  area mm2 {:.6}", c.volume, c.area);
    let _ = writeln!(out, "certificate {}", if c.passed { "passed (as a mesh)" } else { "FAILED" });
    let _ = writeln!(out, "dropped     {}", r.dropped.len());
    for d in r.dropped.iter().take(max_listed) {
        let _ = writeln!(out, "  {} {}: {}", d.id, d.kind, d.why);
    }
    let _ = writeln!(out, "seconds     {:.3}", r.seconds);
    out
}

fn text(r: &BrepInfo, max_listed: usize) -> String {
    let s = &r.summary;
    let mut out = String::new();
    let _ = writeln!(out, "file       {}", r.file);
    let _ = writeln!(out, "units      {} (x{} to mm), angles in {}", s.units.length, s.units.to_mm, s.units.angle);
    let _ = writeln!(out, "solids     {}", s.solids);
    let _ = writeln!(out, "shells     {} ({} of a surface model)", s.shells, s.surface_model_shells);
    if let Some(sw) = &s.sewing {
        let _ = writeln!(out, "sewn       {} edges, {} vertices merged (tolerance {:.3e} mm); free edges {} -> {}", sw.merged_edges, sw.merged_vertices, sw.tolerance, sw.free_edges_before, sw.free_edges_after);
        for line in sw.detail_lines(max_listed) {
            let _ = writeln!(out, "           {line}");
        }
    }
    let _ = writeln!(out, "faces      {}", s.faces);
    let _ = writeln!(out, "edges      {} ({} closed, {} seam, {} degenerate)", s.edges, s.closed_edges, s.seam_edges, s.degenerate_edges);
    let _ = writeln!(out, "vertices   {}", s.vertices);
    if let Some([lo, hi]) = s.bounds {
        let _ = writeln!(out, "extent mm  {:.6} x {:.6} x {:.6}", hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
    }
    let kinds: Vec<String> = s.faces_by_surface.iter().map(|(k, n)| format!("{k} {n}")).collect();
    let _ = writeln!(out, "surfaces   {}", kinds.join(", "));
    let _ = writeln!(out, "dropped    {}", r.dropped.len());
    for d in r.dropped.iter().take(max_listed) {
        let _ = writeln!(out, "  {} {}: {}", d.id, d.kind, d.why);
    }
    if r.dropped.len() > max_listed {
        let _ = writeln!(out, "  ... {} more (--json lists all)", r.dropped.len() - max_listed);
    }
    let _ = writeln!(out, "seconds    {:.3}", r.seconds);
    if let Some(m) = &r.mesh {
        let _ = writeln!(out, "mesh       {} triangles, {} vertices, closed {}, manifold {}, oriented {}, {} open edges", m.triangles, m.vertices, m.closed, m.manifold, m.oriented, m.open_edges);
        let _ = writeln!(out, "volume mm3 {:.6}  area mm2 {:.6}  ({:.3} s)", m.volume_mm3, m.area_mm2, m.seconds);
        let _ = writeln!(out, "failed     {} faces", m.failed_faces.len());
        for f in m.failed_faces.iter().take(max_listed) {
            let _ = writeln!(out, "  {} {}: {}", f.face, f.source, f.why);
        }
    }
    out
}
