//! `fepre inspect FILE`: the topology report of a surface (or of a tet mesh's boundary) and,
//! for tet meshes, element quality.

use crate::cli::progress::Progress;
use fepre::core::Tolerance;
use fepre::pipeline::{InspectOptions, InspectReport, inspect_file};
use fepre::quality::NEAR_DEGENERATE_VOLUME_LENGTH;
use fepre::quality::TetPlace;
use anyhow::Result;
use std::fmt::Write as _;
use std::path::PathBuf;

/// Examples shown by `fepre inspect --help`.
pub const EXAMPLES: &str = "\
Examples:
  fepre inspect part.stl                          closed? manifold? genus? volume? self-intersections?
  fepre inspect part.stl --json | jq .genus       one JSON object for scripts
  fepre inspect big.obj --no-self-intersections   skip the exact pairwise test on huge inputs
  fepre inspect scan.stl                          open or overlapping: also the volume its winding number encloses
  fepre inspect big_scan.stl --no-winding-volume  skip that measure (seconds on a large scan)
  fepre inspect mesh.1.ele                        a tet mesh: quality statistics and a dihedral-angle histogram";

/// Arguments of `fepre inspect`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Mesh file (.stl .obj .gltf .glb .off .mesh .node .ele .face .poly .smesh .msh .xyz).
    pub file: PathBuf,
    /// Print one JSON object on standard output instead of the text report.
    #[arg(long)]
    pub json: bool,
    /// Skip the exact self-intersection test (the report then says null).
    #[arg(long)]
    pub no_self_intersections: bool,
    /// Skip the volume an open, overlapping or inward surface's winding number encloses (2.1
    /// million samples; seconds on a large scan).
    #[arg(long)]
    pub no_winding_volume: bool,
    /// List at most N offending pairs, edges or triangles.
    #[arg(long, value_name = "N", default_value_t = 10)]
    pub max_listed: usize,
    /// Keep the file's vertices as they are instead of merging coincident ones.
    #[arg(long)]
    pub no_weld: bool,
    /// Merge vertices closer than REL times the bounding-box diagonal.
    #[arg(long, value_name = "REL", default_value_t = Tolerance::WELD.relative, value_parser = crate::cli::parse_fraction)]
    pub weld: f64,
}

/// Runs `fepre inspect`.
///
/// # Errors
/// An unreadable or invalid input file (exit 1).
pub fn run(args: &Args) -> Result<()> {
    let progress = Progress::start(&format!("reading {}", args.file.display()));
    let options = InspectOptions {
        weld: if args.no_weld { None } else { Some(Tolerance::relative(args.weld)) },
        self_intersections: !args.no_self_intersections,
        winding_volume: !args.no_winding_volume,
        max_listed: args.max_listed,
    };
    let report = inspect_file(&args.file, &options, &|s| progress.stage(s))?;
    progress.finish();
    if args.json {
        outln!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        out!("{}", render(&report));
    }
    crate::cli::print_warnings(&report.warnings);
    Ok(())
}

fn yes(b: bool) -> &'static str {
    if b { "yes" } else { "NO" }
}

fn opt<T: std::fmt::Display>(v: Option<T>) -> String {
    v.map_or_else(|| "-".to_string(), |x| x.to_string())
}

/// The text report.
fn render(r: &InspectReport) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "{} ({}, {})", r.file, r.format, r.kind);
    if r.kind == "point set" {
        let _ = writeln!(s, "  points              {}", r.vertices);
        if let Some([lo, hi]) = r.bbox {
            let _ = writeln!(s, "  bbox                [{}, {}, {}] to [{}, {}, {}]", lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
        }
        for n in &r.notes {
            let _ = writeln!(s, "  note: {n}");
        }
        return s;
    }
    let welded = if r.file_vertices != r.vertices { format!(" ({} in the file)", r.file_vertices) } else { String::new() };
    let _ = writeln!(s, "  vertices            {}{welded}", r.vertices);
    if r.tets > 0 {
        let _ = writeln!(s, "  tetrahedra          {}", r.tets);
        let _ = writeln!(s, "  boundary triangles  {} (tagged: {})", r.triangles, r.tet.as_ref().map_or(0, |t| t.boundary_triangles));
    } else {
        let _ = writeln!(s, "  triangles           {}", r.triangles);
    }
    let _ = writeln!(s, "  components          {}", r.components);
    let _ = writeln!(
        s,
        "  closed {}   manifold {}   oriented {}   outward {}",
        yes(r.closed),
        yes(r.manifold),
        yes(r.oriented),
        yes(r.outward)
    );
    let _ = writeln!(s, "  euler               {}   genus {}", r.euler, opt(r.genus));
    let _ = writeln!(s, "  volume              {:.9e}", r.volume);
    if let Some(w) = r.winding_volume {
        let _ = writeln!(s, "  winding volume      {:.6e} ± {:.1e} (where the winding number exceeds 1/2, what --method octree meshes; {}³ cells)", w.volume, w.error, w.cells_per_axis);
    }
    let _ = writeln!(s, "  area                {:.9e}", r.area);
    if let Some([lo, hi]) = r.bbox {
        let _ = writeln!(s, "  bbox                [{}, {}, {}] to [{}, {}, {}]", lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
    }
    if r.open_edges + r.nonmanifold_edges + r.nonmanifold_vertices + r.degenerate_triangles > 0 || r.boundary_loops > 0 {
        let _ = writeln!(
            s,
            "  open edges {} in {} loops, non-manifold edges {}, non-manifold vertices {}, degenerate triangles {}",
            r.open_edges, r.boundary_loops, r.nonmanifold_edges, r.nonmanifold_vertices, r.degenerate_triangles
        );
    }
    match r.self_intersections {
        None => {
            let _ = writeln!(s, "  self-intersections  not tested");
        }
        Some(n) => {
            let _ = writeln!(s, "  self-intersections  {n}");
            for p in &r.first_intersections {
                let _ = writeln!(s, "    triangle {} ({}) crosses triangle {} ({})", p.a, p.tag_a, p.b, p.tag_b);
            }
        }
    }
    if r.shells.len() > 1 {
        let _ = writeln!(s, "  shells:");
        let _ = writeln!(s, "    {:>3} {:>10} {:>7} {:>6} {:>7} {:>16} {:>8}", "#", "triangles", "closed", "euler", "genus", "volume", "outward");
        for (i, sh) in r.shells.iter().enumerate().take(20) {
            let _ = writeln!(
                s,
                "    {:>3} {:>10} {:>7} {:>6} {:>7} {:>16.9e} {:>8}",
                i,
                sh.triangles,
                yes(sh.closed),
                sh.euler,
                opt(sh.genus),
                sh.volume,
                sh.outward.map_or("-", yes)
            );
        }
        if r.shells.len() > 20 {
            let _ = writeln!(s, "    … {} more", r.shells.len() - 20);
        }
    }
    if !r.tags.is_empty() {
        let _ = writeln!(s, "  face tags:");
        for t in r.tags.iter().take(30) {
            let _ = writeln!(s, "    {:>6}  {:>9} triangles  {}", t.tag, t.triangles, t.name.as_deref().unwrap_or(""));
        }
        if r.tags.len() > 30 {
            let _ = writeln!(s, "    … {} more", r.tags.len() - 30);
        }
    }
    if let Some(t) = &r.tet {
        let _ = writeln!(s, "  regions:");
        for g in &t.regions {
            let _ = writeln!(s, "    {:>6}  {:>9} tets  {}", g.tag, g.triangles, g.name.as_deref().unwrap_or(""));
        }
        let _ = writeln!(
            s,
            "  dihedral            {:.2}° .. {:.2}° ({} tets under 5°, {} under 1°)",
            t.min_dihedral_deg, t.max_dihedral_deg, t.tets_under_5_deg, t.tets_under_1_deg
        );
        if t.tets_under_10_deg > 0 {
            let _ = writeln!(
                s,
                "  under 10°           {} tets; {} touch no angle under 10° of the boundary ({} such angles), {} of those lie between the two sides of one",
                t.tets_under_10_deg, t.tets_under_10_deg_unexplained, t.input_angles_under_10_deg, t.tets_under_10_deg_between_sides
            );
        }
        let _ = writeln!(s, "  max radius-edge     {:.3}", t.max_radius_edge);
        let _ = writeln!(
            s,
            "  near-degenerate     {} tets (volume-length under {NEAR_DEGENERATE_VOLUME_LENGTH}; exactly flat {}), inverted {}",
            t.near_degenerate, t.quality.degenerate, t.inverted
        );
        for (label, text) in t.worst_tet.as_ref().map(TetPlace::lines).unwrap_or_default() {
            let _ = writeln!(s, "  {label:<19} {text}");
        }
        let _ = writeln!(s, "  quality:");
        for line in t.quality.render().lines() {
            let _ = writeln!(s, "    {line}");
        }
    }
    for n in &r.notes {
        let _ = writeln!(s, "  note: {n}");
    }
    let _ = writeln!(s, "  ({:.3} s)", r.seconds);
    s
}
