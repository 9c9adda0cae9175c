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
pub(crate) fn print_mesh_summary(m: &crate::pipeline::run::MeshSummary, delaunay: bool) {
    use crate::quality::worst_tet::{fmt_num, fmt_point};
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
    if m.flattening_volume > 1e-9 * m.volume.abs() {
        outln!("flat facets      input triangles flat within 0.1° merged and retriangulated (TetGen's -p rule): the volume moves by at most {} ({:.2e} of it)", fmt_num(m.flattening_volume), m.flattening_volume / m.volume.abs().max(f64::MIN_POSITIVE));
    }
    if !delaunay {
        return;
    }
    outln!("refinement       {}", refinement_text(m));
    if m.optimize_out_of_attempts {
        outln!("optimisation     stopped early: its budget of attempts (one per 8 tets, plus 10,000) ran out after {}", m.optimize_attempts);
    } else {
        outln!("optimisation     ended after {} attempts, within its budget", m.optimize_attempts);
    }
}

/// Prints what the FE model holds: element kind, counts, second order, each selector's sets,
/// each solid's material, each step's forces. Shared by `fepre run` and `fepre solve`.
pub(crate) fn print_fe_summary(fe: &crate::pipeline::fe_model::FeSummary) {
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

/// Whether refinement ended, or which budget stopped it, and what is left above its bound.
fn refinement_text(m: &crate::pipeline::run::MeshSummary) -> String {
    let (r, above) = (m.radius_edge_bound, m.tets_above_radius_edge_bound);
    match &m.refinement_stop {
        Some(s) if s.budget == "points" => format!("stopped early: its point budget ({} points) ran out before every tet met radius-edge {r} (input angles too small for it to end); {above} tets are above it", s.max_points),
        Some(s) => format!("stopped early: its bound on the bad tets worked on ran out at {} points, before every tet met radius-edge {r}; {above} tets are above it", s.points),
        None if m.refinement_stopped => format!("stopped early at its budget before every tet met radius-edge {r}; {above} tets are above it"),
        None if above > 0 => format!("ended; {above} tets are above radius-edge {r} (refinement leaves tets under a tenth of the shortest boundary edge, and points that would crowd the boundary or come nearer a vertex than a share of the local feature size; the optimisation allows up to {})", fmt_radius_edge_allowed(r)),
        None => format!("ended: every tet meets radius-edge {r}"),
    }
}

fn fmt_radius_edge_allowed(r: f64) -> String {
    crate::quality::worst_tet::fmt_num(r.max(2.0))
}

/// A mesh whose volume is farther than this fraction from the CAD solids' gets a warning.
const VOLUME_WARNING: f64 = 0.01;

/// Warns on standard error about a volume more than 1 % off the CAD solids' and about a tet
/// under 1° (`require`: the option that makes the latter an error), with where the worst one
/// sits.
/// `octree`: the octree mesher made the mesh (its cells are a cause too).
pub(crate) fn warn_mesh_summary(m: &crate::pipeline::run::MeshSummary, require: &str, octree: bool) {
    if let Some(e) = m.volume_error.filter(|e| e.abs() > VOLUME_WARNING) {
        let cause = if octree {
            "the tessellation's chords cut the curved faces, and octree cells miss what is thinner than a cell"
        } else {
            "the tessellation's chords cut the curved faces, and at this size a slender or thin part's circles have few sides"
        };
        eprintln!(
            "WARNING: the mesh's volume is {:+.2}% off the CAD solids' ({cause}; give a smaller size, a curvature size or a smaller deviation); --require-volume-error F makes this an error",
            100.0 * e
        );
    }
    if m.tets_under_1_deg == 0 {
        return;
    }
    let at = m.worst_tet.as_ref().map(|w| {
        let face = w.nearest_face.as_ref().map(|f| format!(", near face {}{}", f.face.0, f.name.as_ref().map(|n| format!(" \"{n}\"")).unwrap_or_default())).unwrap_or_default();
        format!(" (the smallest {}° at {}{face})", crate::quality::worst_tet::fmt_num(w.min_dihedral_deg), crate::quality::worst_tet::fmt_point(w.point))
    });
    let why = if m.tets_under_1_deg_unexplained == 0 { ", each touching an input angle under 1°" } else { "" };
    eprintln!("WARNING: {} tets have a dihedral angle under 1°{}{why}; {require} makes this an error", m.tets_under_1_deg, at.unwrap_or_default());
}

/// Warns on standard error about the solids of an assembly the octree mesher left out, and
/// about a boundary farther than a cell from the input.
pub(crate) fn warn_octree(o: Option<&crate::mesh3d::octree::OctreeReport>) {
    for line in octree_warnings(o) {
        eprintln!("{line}");
    }
}

/// The warnings of [`warn_octree`]: solids left out, and a boundary farther from the input
/// than the cell size (where, and the first feature edge it misses).
fn octree_warnings(o: Option<&crate::mesh3d::octree::OctreeReport>) -> Vec<String> {
    let Some(o) = o else { return Vec::new() };
    let mut out = Vec::new();
    if !o.empty_solids.is_empty() {
        let names: Vec<String> = o.empty_solids.iter().map(|e| format!("{}{} ({:.4e})", e.solid, e.name.as_ref().map(|n| format!(" {n:?}")).unwrap_or_default(), e.volume)).collect();
        out.push(format!(
            "WARNING: {} solids left out, thinner than the cell size {:.4e} (no lattice vertex inside; a smaller size reaches them): {}",
            o.empty_solids.len(),
            o.cell_size,
            names.join(", ")
        ));
    }
    if let Some(m) = &o.overlap {
        out.push(format!("WARNING: {m}; each solid was meshed on its own (isosurface stuffing), so the overlap is meshed in both and no contacts are listed"));
    }
    if o.turned_outward {
        out.push("WARNING: the surface encloses a negative volume (its triangles face inward): meshed turned outward".to_string());
    }
    if o.reaches_box {
        out.push("WARNING: the volume the surface's winding number encloses reaches the lattice's box: the surface does not close it (a surface model, or an open sheet), so the mesh is cut off by the box and its boundary there is not the input's".to_string());
    }
    let resolve = crate::mesh3d::octree::RESOLVE;
    let short: Vec<String> = kept_tries(o)
        .into_iter()
        .filter(|t| !resolve.holds(t))
        .map(|t| {
            let solid = t.solid.map(|s| format!("solid {s} ")).unwrap_or_default();
            let what = match (t.empty, t.volume_error, t.volume_change) {
                (true, _, _) => "no lattice vertex inside".to_string(),
                (false, Some(e), _) => format!("{:.3} % off", 100.0 * e),
                (false, None, Some(c)) => format!("its volume still changing by {:.3} % from the cell before", 100.0 * c),
                (false, None, None) => "one cell only".to_string(),
            };
            // what stopped it: the tries an inexact volume gets, or the budget
            let inside = o.cell_tries.iter().filter(|u| u.solid == t.solid && !u.empty).count();
            let why = if !t.empty && t.volume_error.is_none() && inside > resolve.change_tries {
                format!("the last of {inside} tries for a volume without an exact reference")
            } else {
                format!("the next cell would pass the budget of {} lattice vertices or {} tets a solid", resolve.max_lattice_vertices, resolve.max_tets)
            };
            format!("{solid}at {:.4e}, {what} ({why})", t.cell)
        })
        .collect();
    if !short.is_empty() {
        out.push(format!("WARNING: the default cell stopped before the volume was within {} %: {}; give --size for a finer cell", 100.0 * resolve.volume_error, short.join(", ")));
    }
    let d = &o.deviation;
    // the bound, not only the sample: it is what the default cell is chosen by
    if o.hausdorff_over_cell > 1.0 || o.bound_over_cell > 1.0 || d.unresolved_feature_edges > 0 {
        use crate::quality::worst_tet::fmt_point;
        let mut w = format!("WARNING: the boundary strays {:.4e} from the input at {} (sampled), {:.3} times the cell size there", d.hausdorff, fmt_point(d.hausdorff_at), o.hausdorff_over_cell);
        w += &format!(" (at most {:.3} times)", o.bound_over_cell);
        if let Some([a, b]) = d.unresolved_examples.first() {
            w += &format!("; {} of {} feature edges are farther than a cell from it, the first from {} to {}", d.unresolved_feature_edges, d.feature_edges, fmt_point(*a), fmt_point(*b));
        }
        w += ": walls or features thinner or sharper than a cell; a smaller size follows them closer";
        if let Some(n) = o.input_crossings.filter(|&n| n > 0) {
            w += &format!(" (but {n} input triangles cross or touch others: the gaps between crossing walls may be thinner than any cell; `fepre inspect` lists them)");
        }
        out.push(w);
    }
    out
}

/// The try kept for each solid (for the part where its solids were not meshed one by one).
fn kept_tries(o: &crate::mesh3d::octree::OctreeReport) -> Vec<&crate::mesh3d::octree::CellTry> {
    o.cell_tries.iter().filter(|t| t.kept).collect()
}

/// The line that says how the default cell was chosen; `None` where a size was given.
pub(crate) fn cell_choice(o: &crate::mesh3d::octree::OctreeReport) -> Option<String> {
    let first = o.cell_tries.first()?;
    let last = kept_tries(o);
    let resolve = crate::mesh3d::octree::RESOLVE;
    let held = last.iter().filter(|t| resolve.holds(t)).count();
    let why = if held == last.len() && last.iter().all(|t| t.volume_error.is_some()) {
        format!("the volume within {} %", 100.0 * resolve.volume_error)
    } else if held == last.len() {
        // no exact reference: what was checked, and where the winding number's volume stands
        let against = o.winding_volume.map(|w| format!(", {:+.3} % from the winding number's", 100.0 * (o.volume / w.volume - 1.0))).unwrap_or_default();
        format!("the volume settled within {} % of the cell before{against}", 100.0 * resolve.volume_error)
    } else {
        format!("{} of {} stopped short of it (WARNING below)", last.len() - held, last.len())
    };
    let (lo, hi) = last.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), t| (lo.min(t.cell), hi.max(t.cell)));
    Some(if last.len() == 1 {
        format!("{} tries from {:.4e}, kept {:.4e}: {why}", o.cell_tries.len(), first.cell, lo)
    } else {
        format!("per solid, {} tries from {:.4e}, kept cells of {:.4e} to {:.4e}: {why}", o.cell_tries.len(), first.cell, lo, hi)
    })
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh3d::mesher::RefinementStop;
    use crate::pipeline::run::MeshSummary;

    #[test]
    fn octree_warnings_name_the_place() {
        use crate::mesh3d::octree::OctreeReport;
        let mut o = OctreeReport { cell_size: 1.0, hausdorff_over_cell: 0.5, ..OctreeReport::default() };
        o.deviation.hausdorff = 0.5;
        assert!(octree_warnings(Some(&o)).is_empty(), "within the cell");
        assert!(octree_warnings(None).is_empty());
        // the sample within the cell, its bound not: said, with the bound
        o.bound_over_cell = 1.2;
        let w = octree_warnings(Some(&o));
        assert!(w.len() == 1 && w[0].contains("0.500 times the cell size there (at most 1.200 times)"), "{w:?}");
        o.deviation.hausdorff = 2.5;
        o.hausdorff_over_cell = 2.5;
        o.deviation.hausdorff_at = [1.0, 2.0, 3.0];
        o.deviation.feature_edges = 9;
        o.deviation.unresolved_feature_edges = 2;
        o.deviation.unresolved_examples = vec![[[0.0, 0.0, 0.0], [4.0, 0.0, 0.0]]];
        let w = octree_warnings(Some(&o));
        assert_eq!(w.len(), 1, "{w:?}");
        assert!(w[0].starts_with("WARNING: the boundary strays 2.5000e0 from the input at (1, 2, 3) (sampled), 2.500 times the cell size there"), "{}", w[0]);
        assert!(w[0].contains("2 of 9 feature edges are farther than a cell from it, the first from (0, 0, 0) to (4, 0, 0)"), "{}", w[0]);
        assert!(!w[0].contains("cross"), "{}", w[0]);
        // an input whose triangles cross: said, since a smaller size may not help
        o.input_crossings = Some(12);
        let w = octree_warnings(Some(&o));
        assert!(w[0].ends_with("a smaller size follows them closer (but 12 input triangles cross or touch others: the gaps between crossing walls may be thinner than any cell; `fepre inspect` lists them)"), "{}", w[0]);
    }

    #[test]
    fn octree_warnings_say_where_the_default_cell_stopped() {
        use crate::mesh3d::octree::{CellTry, OctreeReport};
        let mut o = OctreeReport { cell_size: 1.0, ..OctreeReport::default() };
        assert_eq!(cell_choice(&o), None, "a size given");
        o.turned_outward = true;
        assert_eq!(octree_warnings(Some(&o)), vec!["WARNING: the surface encloses a negative volume (its triangles face inward): meshed turned outward".to_string()]);
        o.turned_outward = false;
        o.reaches_box = true;
        assert_eq!(octree_warnings(Some(&o)), vec!["WARNING: the volume the surface's winding number encloses reaches the lattice's box: the surface does not close it (a surface model, or an open sheet), so the mesh is cut off by the box and its boundary there is not the input's".to_string()]);
        o.reaches_box = false;
        o.overlap = Some("a.step: solid 1 and solid 2 overlap".into());
        assert_eq!(octree_warnings(Some(&o)), vec!["WARNING: a.step: solid 1 and solid 2 overlap; each solid was meshed on its own (isosurface stuffing), so the overlap is meshed in both and no contacts are listed".to_string()]);
        o.overlap = None;
        o.cell_tries = vec![CellTry { cell: 2.0, empty: true, ..CellTry::default() }, CellTry { cell: 1.0, volume_error: Some(0.004), kept: true, ..CellTry::default() }];
        assert!(octree_warnings(Some(&o)).is_empty(), "the last try holds");
        assert_eq!(cell_choice(&o).unwrap(), "2 tries from 2.0000e0, kept 1.0000e0: the volume within 1 %");
        o.cell_tries[1].volume_error = Some(0.0234);
        let w = octree_warnings(Some(&o));
        assert_eq!(w.len(), 1, "{w:?}");
        assert_eq!(w[0], "WARNING: the default cell stopped before the volume was within 1 %: at 1.0000e0, 2.340 % off (the next cell would pass the budget of 33554432 lattice vertices or 33554432 tets a solid); give --size for a finer cell");
        o.cell_tries[1] = CellTry { cell: 1.0, volume_change: Some(0.05), kept: true, ..CellTry::default() };
        assert!(octree_warnings(Some(&o))[0].contains(": at 1.0000e0, its volume still changing by 5.000 % from the cell before (the next cell would pass the budget of"));
        // an inexact volume stopped by its tries, not the budget: said so
        let tries = o.cell_tries.clone();
        o.cell_tries = (0..7).map(|k| CellTry { cell: 1.0 / (k + 1) as f64, volume_change: (k > 0).then_some(0.05), kept: k == 6, ..CellTry::default() }).collect();
        assert!(octree_warnings(Some(&o))[0].contains(": at 1.4286e-1, its volume still changing by 5.000 % from the cell before (the last of 7 tries for a volume without an exact reference); give --size"));
        o.cell_tries = tries;
        // an inexact volume that settled: said so, with the winding number's figure
        o.cell_tries[1].volume_change = Some(0.004);
        (o.volume, o.winding_volume) = (0.99, Some(crate::mesh3d::octree::WindingVolume { volume: 1.0, error: 0.001, cells_per_axis: 64 }));
        assert_eq!(cell_choice(&o).unwrap(), "2 tries from 2.0000e0, kept 1.0000e0: the volume settled within 1 % of the cell before, -1.000 % from the winding number's");
        o.cell_tries[1] = CellTry { cell: 1.0, volume_error: Some(0.0234), kept: true, ..CellTry::default() };
        // solid by solid: the last try of each
        o.cell_tries = vec![
            CellTry { solid: Some(1), cell: 2.0, volume_error: Some(0.2), ..CellTry::default() },
            CellTry { solid: Some(1), cell: 1.0, volume_error: Some(0.002), kept: true, ..CellTry::default() },
            CellTry { solid: Some(1), cell: 0.7, volume_error: Some(0.001), ..CellTry::default() },
            CellTry { solid: Some(2), cell: 2.0, empty: true, kept: true, ..CellTry::default() },
        ];
        assert!(octree_warnings(Some(&o))[0].ends_with("before the volume was within 1 %: solid 2 at 2.0000e0, no lattice vertex inside (the next cell would pass the budget of 33554432 lattice vertices or 33554432 tets a solid); give --size for a finer cell"));
        assert_eq!(cell_choice(&o).unwrap(), "per solid, 4 tries from 2.0000e0, kept cells of 1.0000e0 to 2.0000e0: 1 of 2 stopped short of it (WARNING below)");
    }

    #[test]
    fn the_refinement_line_says_which_budget_stopped_it() {
        let mut m = MeshSummary { radius_edge_bound: 1.1, tets_above_radius_edge_bound: 12, ..MeshSummary::default() };
        m.refinement_stop = Some(RefinementStop { budget: "points", points: 29_305, max_points: 29_305 });
        m.refinement_stopped = true;
        let t = refinement_text(&m);
        assert!(t.starts_with("stopped early: its point budget (29305 points) ran out before every tet met radius-edge 1.1") && t.ends_with("; 12 tets are above it"), "{t}");
        m.refinement_stop = Some(RefinementStop { budget: "steps", points: 1_000, max_points: 29_305 });
        assert!(refinement_text(&m).starts_with("stopped early: its bound on the bad tets worked on ran out at 1000 points"));
        m.refinement_stop = None;
        m.refinement_stopped = false;
        assert!(refinement_text(&m).starts_with("ended; 12 tets are above radius-edge 1.1"));
        m.tets_above_radius_edge_bound = 0;
        assert_eq!(refinement_text(&m), "ended: every tet meets radius-edge 1.1");
    }
}
