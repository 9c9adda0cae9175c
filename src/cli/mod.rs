//! Layer 6: the command line. One file per subcommand; this file holds the argument types
//! and the mapping of outcomes to exit codes: 0 ok, 1 the input could not be processed,
//! 2 bad usage.

/// Writes formatted text to standard output, like `print!`, through [`write_out`].
macro_rules! out {
    ($($arg:tt)*) => {
        $crate::cli::write_out(format_args!($($arg)*))
    };
}

/// `out!` and a newline, like `println!`.
macro_rules! outln {
    () => {
        $crate::cli::write_out(format_args!("\n"))
    };
    ($($arg:tt)*) => {
        $crate::cli::write_out(format_args!("{}\n", format_args!($($arg)*)))
    };
}

pub mod cad_info;
mod contacts;
pub mod convert;
pub mod delaunay;
pub mod inspect;
pub mod mesh;
pub mod mesh2d;
pub mod progress;
pub mod run;
pub mod solve;
pub mod tessellate;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// Whether anything went to standard output (with `--json`, a failed command that printed
/// nothing prints its error as a JSON object instead).
static WROTE_OUT: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Writes to standard output. A closed output (a pipe into `head`) ends the process quietly
/// with success, as ripgrep and other command-line tools do, instead of a panic; any other
/// write error ends it with exit 1 and a message. Every output file is in place by then.
pub(crate) fn write_out(args: std::fmt::Arguments) {
    use std::io::Write;
    WROTE_OUT.store(true, std::sync::atomic::Ordering::Relaxed);
    if let Err(e) = std::io::stdout().lock().write_fmt(args) {
        if e.kind() == std::io::ErrorKind::BrokenPipe {
            std::process::exit(0);
        }
        eprintln!("error: writing to standard output: {e}");
        std::process::exit(1);
    }
}

const EXAMPLES: &str = "\
Examples:
  fepre inspect part.stl                   report topology: closed, manifold, genus, volume, self-intersections
  fepre inspect part.stl --json            the same report as one JSON object
  fepre inspect mesh.1.ele                 a tet mesh: also dihedral angles, radius-edge ratios, inverted tets
  fepre convert model.glb model.msh        any format fepre reads to any it writes, tags kept
  fepre convert mesh.mesh boundary.stl     a tet mesh's tagged boundary as a surface
  fepre delaunay points.xyz -o dt.mesh     exact Delaunay tetrahedralization of a point set
  fepre mesh part.stl -o part.mesh         quality tet mesh of a closed surface, boundary tags kept
  fepre mesh2d part.step -o faces.vtu      the lecture's quadtree 2D mesher on every planar face
  fepre cad-info part.step                 what fepre reads from a STEP file: counts, units, dropped items
  fepre tessellate part.step -o part.stl   certified watertight surface of a STEP file, face tags kept
  fepre mesh part.step -o part.mesh        STEP straight to quality tets (tessellated and certified first)
  fepre run job.toml                       a job file: selectors on CAD faces, sizes per face, outputs
                                           (materials, BCs and loads on selectors: a CalculiX .inp deck)
  fepre solve job.toml                     the job's deck solved by CalculiX; results as VTU and JSON

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
    /// The lecture's quadtree 2D mesher (Yerry and Shephard) on the planar faces of a STEP
    /// part: balanced quadrants, templates inside, the boundary kept.
    #[command(name = "mesh2d", after_help = mesh2d::EXAMPLES)]
    Mesh2d(mesh2d::Args),
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
    /// Run a job file, write its CalculiX deck, solve it with ccx and write the results
    /// (VTU for ParaView, a JSON summary: largest displacement and stress, reactions,
    /// frequencies).
    #[command(after_help = solve::EXAMPLES)]
    Solve(solve::Args),
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
    let json = match &cli.command {
        Command::Inspect(a) => a.json,
        Command::Convert(a) => a.json,
        Command::Delaunay(a) => a.json,
        Command::Mesh(a) => a.json,
        Command::Mesh2d(a) => a.json,
        Command::CadInfo(a) => a.json,
        Command::Tessellate(a) => a.json,
        Command::Run(a) => a.json,
        Command::Solve(a) => a.json,
    };
    let result = match cli.command {
        Command::Inspect(a) => inspect::run(&a),
        Command::Convert(a) => convert::run(&a),
        Command::Delaunay(a) => delaunay::run(&a),
        Command::Mesh(a) => mesh::run(&a),
        Command::Mesh2d(a) => mesh2d::run(&a),
        Command::CadInfo(a) => cad_info::run(&a),
        Command::Tessellate(a) => tessellate::run(&a),
        Command::Run(a) => run::run(&a),
        Command::Solve(a) => solve::run(&a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            let code: u8 = if e.is::<UsageError>() { 2 } else { 1 };
            eprintln!("error: {}", message(&e));
            if json && !WROTE_OUT.load(std::sync::atomic::Ordering::Relaxed) {
                // a machine reading the JSON gets the reason too, not an empty output
                let report = serde_json::json!({ "error": message(&e), "exit_code": code });
                if let Ok(text) = serde_json::to_string_pretty(&report) {
                    write_out(format_args!("{text}\n"));
                }
            }
            ExitCode::from(code)
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

/// Prints a tet mesh's size and quality: counts, dihedral angles, radius-edge, where the
/// worst tet sits, the small input angles, and whether refinement and the optimisation ended
/// or stopped at a budget (and which). Shared by `fepre mesh` and `fepre run`.
///
/// `delaunay`: the mesh came from the Delaunay mesher, whose refinement and optimisation lines
/// follow (the octree mesher has neither).
pub(crate) fn print_mesh_summary(m: &fepre::pipeline::MeshSummary, delaunay: bool) {
    use fepre::quality::{fmt_num, fmt_point};
    outln!("nodes            {}", m.nodes);
    outln!("tets             {}", m.tets);
    outln!("regions          {}", m.regions);
    match (m.cad_volume, m.volume_error) {
        (Some(v), Some(e)) => outln!("volume           {:.9} (CAD solids {v:.9}: {:+.3}%)", m.volume, 100.0 * e),
        _ => outln!("volume           {:.9}", m.volume),
    }
    outln!("dihedral         {:.2}° .. {:.2}° ({} tets under 5°, {} under 1°, {} near-degenerate)", m.min_dihedral_deg, m.max_dihedral_deg, m.tets_under_5_deg, m.tets_under_1_deg, m.near_degenerate);
    if m.tets_under_5_deg > 0 {
        outln!("                 of those under 5°, {} touch no input angle under 5°; of those under 1°, {} touch none under 1°", m.tets_under_5_deg_unexplained, m.tets_under_1_deg_unexplained);
    }
    if m.tets_under_bound > 0 {
        outln!("                 {} tets under {}°, {} of them touching no input angle as small; {} under 10°, {} of them touching none under 10°", m.tets_under_bound, m.input_angle_bound_deg, m.tets_under_bound_unexplained, m.tets_under_10_deg, m.tets_under_10_deg_unexplained);
    }
    if m.tets_under_10_deg_unexplained > 0 {
        outln!("                 of the {} under 10° touching none, {} lie between the two sides of an input angle under 10° (a thin wedge, a sliver face or a knife edge of the part)", m.tets_under_10_deg_unexplained, m.tets_under_10_deg_between_sides);
    }
    outln!("max radius-edge  {:.3} ({} tets above the {} aimed at)", m.max_radius_edge, m.tets_above_radius_edge_bound, m.radius_edge_bound);
    for (label, text) in m.worst_tet.as_ref().map(|w| w.lines()).unwrap_or_default() {
        outln!("{label:<16} {text}");
    }
    // where the worst tet sits at a small input angle, the worst one the input does not explain
    if let Some(u) = m.worst_unexplained_tet_under_10_deg.as_ref().filter(|u| m.worst_tet.as_ref().is_none_or(|w| w.tet != u.tet)) {
        for (i, (label, text)) in u.lines().into_iter().enumerate() {
            if i == 0 {
                outln!("unexplained tet  {text} (the worst of the {} under 10° touching no input angle under 10°)", m.tets_under_10_deg_unexplained);
            } else {
                outln!("  {label:<14} {text}");
            }
        }
    }
    match &m.smallest_input_angle {
        Some(a) => outln!("input angles     {} under {}°, the smallest {}° at {}", m.small_input_angles, m.input_angle_bound_deg, fmt_num(a.angle_deg), fmt_point(a.at[0])),
        None => outln!("input angles     none under {}°", m.input_angle_bound_deg),
    }
    if m.input_caps_repaired > 0 {
        outln!("input caps       {} flat input triangles with a vertex on their long side, each repaired with its neighbour", m.input_caps_repaired);
    }
    if let Some(n) = &m.narrow {
        let mut faces = n.faces.clone();
        faces.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
        let list: Vec<String> = faces.iter().take(6).map(|(f, k)| format!("{} ({k})", f.0)).collect();
        let more = if faces.len() > 6 { format!(" and {} more", faces.len() - 6) } else { String::new() };
        outln!(
            "narrow strips    input narrower than {} closed up (--narrow-tol; 0 keeps them): {} short edges collapsed, {} flat triangles given to their neighbours; triangles lost by face {}{more}",
            fmt_num(n.tolerance),
            n.collapses,
            n.caps,
            list.join(", ")
        );
    }
    if m.flattening_moved_volume() {
        outln!("flat facets      input triangles flat within 0.1° merged and retriangulated (TetGen's -p rule): the volume moves by at most {} ({:.2e} of it)", fmt_num(m.flattening_volume), m.flattening_volume / m.volume.abs().max(f64::MIN_POSITIVE));
    }
    if let Some((groups, imprinted)) = m.imprinted {
        outln!(
            "imprint          {imprinted} of {groups} groups of faces in contact imprinted (shared nodes; the rest tied, curved contacts for now); the solids' volumes move by {} ({:.2e} of the volume)",
            fmt_num(m.imprint_volume),
            m.imprint_volume / m.volume.abs().max(f64::MIN_POSITIVE)
        );
    }
    if !delaunay {
        return;
    }
    outln!("refinement       {}", fepre::pipeline::refinement_text(m));
    if m.optimize_out_of_attempts {
        outln!("optimisation     stopped early: its budget of attempts (one per 8 tets, plus 10,000) ran out after {}", m.optimize_attempts);
    } else {
        outln!("optimisation     ended after {} attempts, within its budget", m.optimize_attempts);
    }
}

/// Prints what the FE model holds: element kind, counts, second order, each selector's sets,
/// each solid's material, each step's forces. Shared by `fepre run` and `fepre solve`.
pub(crate) fn print_fe_summary(fe: &fepre::pipeline::FeSummary) {
    outln!("FE model         {} nodes, {} {} elements", fe.nodes, fe.elements, fe.element);
    if let Some(c) = &fe.curving {
        outln!("second order     {} mid nodes on CAD faces, {} on CAD edges, {} left on the chord; {} moved back to the chord in {} elements that curving would distort; smallest Jacobian ratio {:.3}", c.on_faces, c.on_edges, c.left_straight, c.straightened, c.straightened_elements, c.min_jacobian_ratio);
    }
    for (name, g) in &fe.selectors {
        outln!("sets             {name}: node set {}, surface {} ({} element faces{})", g.node_set, g.surface, g.boundary_faces, if g.interface_faces > 0 { format!(", {} on interfaces", g.interface_faces) } else { String::new() });
    }
    for s in &fe.solids {
        outln!("solid            {} ({} elements): material {}", s.element_set, s.elements, s.material.as_deref().unwrap_or("none"));
    }
    for t in &fe.ties {
        outln!("tie              {}: {} ({} faces, solid {} face {}) to {} ({} faces, solid {} face {}), area {:.4} not sharing nodes", t.name, t.slave, t.slave_faces, t.slave_side.0, t.slave_side.1.0, t.master, t.master_faces, t.master_side.0, t.master_side.1.0, t.tied_area);
    }
    for s in &fe.steps {
        outln!("step             {} ({})", s.name, s.analysis);
        for (sel, f) in &s.forces {
            outln!("  force          {sel}: {:.6e} {:.6e} {:.6e} in consistent nodal loads", f[0], f[1], f[2]);
        }
    }
}

/// Prints each warning on standard error, as `WARNING: ` and its message.
pub(crate) fn print_warnings(warnings: &[fepre::pipeline::Warning]) {
    for w in warnings {
        eprintln!("{w}");
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
