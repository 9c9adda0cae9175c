//! truck-stepio + truck-meshalgo against fepre's STEP reader + tessellator, on every STEP file
//! of a folder (the shared CAD corpus), in one run.
//!
//! ```text
//! truck_bench CORPUS_DIR [--timeout SECONDS] [--mem-gb GB]
//! ```
//!
//! Each file is read and tessellated by each side in a child process of this program (run
//! under `timeout` and `prlimit --as`, since truck never finishes two corpus files and grows
//! past 14 GB on them):
//! - truck: `ruststep` parse, `Table::to_compressed_shell` for every shell,
//!   `triangulation(tol)` with tol = 0.001 × the bounding-box diagonal of a coarse first mesh
//!   (`robust_triangulation(0.01)`, as truck's own step-to-mesh example does; not timed, it
//!   stands for fepre's model size), as the corpus README measured it; then
//!   `put_together_same_attrs` and edge counts; truck ignores the file's length unit, so its
//!   volume is scaled by the unit fepre reads;
//! - fepre: `cad::step::read` and `tessellate` at chord 1e-3 (not the default 2e-4: truck gets the same tolerance; chord 1e-3 × the model's
//!   diagonal: the same deviation), then `mesh::topology`'s report.
//!
//! Times are of reading + tessellating only (not of the checks). "closed" means every shell's
//! mesh has no edge used once or more than twice. Volumes are divided by OpenCASCADE's, taken
//! from the table in the corpus's README.md. A line per file and the totals over the files
//! both sides finished go to stdout.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

/// What one side reports for one file (one JSON line from the child).
#[derive(Default, Debug, Clone)]
struct Outcome {
    ok: bool,
    why: String,
    seconds: f64,
    triangles: u64,
    failed_faces: u64,
    closed: bool,
    volume: f64,
}

fn outcome_json(o: &Outcome) -> String {
    serde_json::json!({"ok": o.ok, "why": o.why, "seconds": o.seconds, "triangles": o.triangles,
        "failed_faces": o.failed_faces, "closed": o.closed, "volume": o.volume})
    .to_string()
}

fn parse_outcome(line: &str) -> Option<Outcome> {
    let v: serde_json::Value = serde_json::from_str(line).ok()?;
    Some(Outcome {
        ok: v["ok"].as_bool()?,
        why: v["why"].as_str().unwrap_or("").to_string(),
        seconds: v["seconds"].as_f64()?,
        triangles: v["triangles"].as_u64()?,
        failed_faces: v["failed_faces"].as_u64()?,
        closed: v["closed"].as_bool()?,
        volume: v["volume"].as_f64()?,
    })
}

/// Edges used once or more than twice, over triangles given as position indices.
fn bad_edges(tris: &[[usize; 3]]) -> usize {
    let mut uses: BTreeMap<(usize, usize), u32> = BTreeMap::new();
    for t in tris {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *uses.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    uses.values().filter(|&&n| n != 2).count()
}

fn truck_one(path: &Path) -> Outcome {
    use truck_meshalgo::prelude::*;
    use truck_stepio::r#in::*;
    let text = match std::fs::read_to_string(path) {
        Ok(t) => t,
        Err(e) => return Outcome { why: format!("read: {e}"), ..Default::default() },
    };
    // the tolerance: 0.001 x the diagonal of a coarse first mesh, as truck's own step-to-mesh
    // example measures it (not timed: the counterpart of fepre's model size)
    let parsed = Instant::now();
    let exchange = match ruststep::parser::parse(&text) {
        Ok(x) => x,
        Err(e) => return Outcome { why: format!("parse: {}", e.to_string().lines().next().unwrap_or("")), ..Default::default() },
    };
    let Some(data) = exchange.data.first() else { return Outcome { why: "no data section".into(), ..Default::default() } };
    let table = Table::from_data_section(data);
    let mut ids: Vec<_> = table.shell.keys().copied().collect();
    ids.sort_unstable();
    let mut shells = Vec::new();
    for id in ids {
        match table.to_compressed_shell(&table.shell[&id]) {
            Ok(s) => shells.push(s),
            Err(e) => return Outcome { why: format!("shell #{id}: {e:?}"), ..Default::default() },
        }
    }
    let mut seconds = parsed.elapsed().as_secs_f64();
    let mut meshed = Vec::new();
    for shell in &shells {
        let coarse = shell.robust_triangulation(0.01).to_polygon();
        let tol = (0.001 * coarse.bounding_box().diameter()).max(1e-6);
        let start = Instant::now();
        meshed.push(shell.triangulation(tol));
        seconds += start.elapsed().as_secs_f64();
    }
    let (mut triangles, mut failed, mut closed, mut volume) = (0u64, 0u64, true, 0.0);
    for shell in &meshed {
        failed += shell.faces.iter().filter(|f| f.surface.is_none()).count() as u64;
        let mut poly = shell.to_polygon();
        poly.put_together_same_attrs(TOLERANCE * 50.0).remove_degenerate_faces().remove_unused_attrs();
        let tris: Vec<[usize; 3]> = poly.faces().triangle_iter().map(|t| [t[0].pos, t[1].pos, t[2].pos]).collect();
        triangles += tris.len() as u64;
        closed &= failed == 0 && bad_edges(&tris) == 0;
        volume += poly.volume();
    }
    // truck ignores the file's length unit: scale its volume to mm^3 by the unit fepre reads
    let to_mm = fepre::cad::step::read(path).map_or(1.0, |m| m.units.to_mm);
    volume *= to_mm.powi(3);
    Outcome { ok: true, why: String::new(), seconds, triangles, failed_faces: failed, closed, volume }
}

fn fepre_one(path: &Path) -> Outcome {
    use fepre::mesh::topology::{ReportOptions, surface_report};
    use fepre::tessellate::{TessellateOptions, tessellate};
    let start = Instant::now();
    let model = match fepre::cad::step::read(path) {
        Ok(m) => m,
        Err(e) => return Outcome { why: e.to_string(), ..Default::default() },
    };
    let t = tessellate(&model, &TessellateOptions::default().with_chord_relative(1e-3));
    let seconds = start.elapsed().as_secs_f64();
    let r = surface_report(&t.surface, &ReportOptions::default().with_self_intersections(false));
    Outcome {
        ok: true,
        why: String::new(),
        seconds,
        triangles: t.surface.triangles.len() as u64,
        failed_faces: t.failed.len() as u64,
        closed: t.failed.is_empty() && r.closed && r.manifold,
        volume: r.volume,
    }
}

/// Runs `exe --SIDE file` under the time-out and memory cap; the child's JSON line, or why not.
fn run_child(exe: &Path, side: &str, file: &Path, timeout: u64, mem_gb: f64) -> Outcome {
    let bytes = (mem_gb * 1024.0 * 1024.0 * 1024.0) as u64;
    let wall = Instant::now();
    let out = Command::new("prlimit")
        .arg(format!("--as={bytes}"))
        .arg("timeout")
        .arg(format!("{timeout}"))
        .arg(exe)
        .arg(format!("--{side}"))
        .arg(file)
        .output();
    let out = match out {
        Ok(o) => o,
        Err(e) => return Outcome { why: format!("cannot start prlimit/timeout: {e}"), ..Default::default() },
    };
    let text = String::from_utf8_lossy(&out.stdout);
    if let Some(o) = text.lines().rev().find_map(parse_outcome) {
        return o;
    }
    let why = match out.status.code() {
        Some(124) => format!("time-out ({timeout} s)"),
        Some(c) => format!("exit {c}{}", if wall.elapsed() < Duration::from_secs(timeout) { " (memory cap or crash)" } else { "" }),
        None => format!("killed ({})", if out.status.to_string().contains("signal: 6") { "memory cap" } else { "signal" }),
    };
    Outcome { why, ..Default::default() }
}

/// OpenCASCADE volumes by file name, from the STEP table of the corpus README (the column
/// headed "OCC volume mm^3").
fn occ_volumes(readme: &Path) -> BTreeMap<String, f64> {
    let mut out = BTreeMap::new();
    let Ok(text) = std::fs::read_to_string(readme) else { return out };
    let mut column = None;
    for line in text.lines() {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        if let Some(k) = cells.iter().position(|c| *c == "OCC volume mm^3") {
            column = Some(k);
            continue;
        }
        let Some(k) = column else { continue };
        if !line.starts_with('|') {
            column = None;
            continue;
        }
        let (Some(name), Some(v)) = (cells.get(2), cells.get(k)) else { continue };
        if let Ok(v) = v.parse::<f64>() {
            out.insert(name.trim_matches('`').to_string(), v);
        }
    }
    out
}

fn ratio(v: f64, occ: Option<f64>, closed: bool) -> String {
    match occ {
        Some(o) if closed && o > 0.0 => format!("{:.3}", v / o),
        _ if !closed => "open".into(),
        _ => "-".into(),
    }
}

fn cell(o: &Outcome) -> (String, String) {
    if o.ok {
        (format!("{:.3}", o.seconds), if o.closed { "yes".into() } else { format!("no ({} faces failed)", o.failed_faces) })
    } else {
        ("-".into(), o.why.clone())
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.len() == 3 && (args[1] == "--truck" || args[1] == "--fepre") {
        let path = PathBuf::from(&args[2]);
        let o = if args[1] == "--truck" { truck_one(&path) } else { fepre_one(&path) };
        println!("{}", outcome_json(&o));
        return;
    }
    let mut dir = None;
    let (mut timeout, mut mem_gb) = (20u64, 4.0f64);
    let mut k = 1;
    while k < args.len() {
        match args[k].as_str() {
            "--timeout" => {
                timeout = args.get(k + 1).and_then(|s| s.parse().ok()).unwrap_or(timeout);
                k += 1;
            }
            "--mem-gb" => {
                mem_gb = args.get(k + 1).and_then(|s| s.parse().ok()).unwrap_or(mem_gb);
                k += 1;
            }
            d => dir = Some(PathBuf::from(d)),
        }
        k += 1;
    }
    let Some(dir) = dir else {
        eprintln!("usage: truck_bench CORPUS_DIR [--timeout SECONDS] [--mem-gb GB]");
        std::process::exit(2);
    };
    let exe = std::env::current_exe().expect("own path");
    let occ = occ_volumes(&dir.join("README.md"));
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("cannot list {}: {e}", dir.display()))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| matches!(x.to_ascii_lowercase().to_str(), Some("step" | "stp"))))
        .collect();
    files.sort_by_key(|p| p.file_name().map(|n| n.to_ascii_lowercase()));
    println!("truck-stepio 0.3 + truck-meshalgo 0.4 (tol 0.001 x bbox diagonal) vs fepre read + tessellate (chord 1e-3 x diagonal)");
    println!("each side in a child process under timeout {timeout} s and a {mem_gb} GB address-space cap\n");
    println!("| file | truck s | fepre s | truck/fepre | truck closed | fepre closed | truck vol/OCC | fepre vol/OCC | truck tris | fepre tris |");
    println!("|---|---|---|---|---|---|---|---|---|---|");
    let (mut tt, mut tf, mut both, mut closed_t, mut closed_f) = (0.0, 0.0, 0, 0, 0);
    for f in &files {
        let name = f.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        let t = run_child(&exe, "truck", f, timeout, mem_gb);
        let p = run_child(&exe, "fepre", f, timeout, mem_gb);
        let o = occ.get(&name).copied();
        let speed = if t.ok && p.ok && p.seconds > 0.0 { format!("{:.1}", t.seconds / p.seconds) } else { "-".into() };
        if t.ok && p.ok {
            tt += t.seconds;
            tf += p.seconds;
            both += 1;
        }
        closed_t += usize::from(t.ok && t.closed);
        closed_f += usize::from(p.ok && p.closed);
        let ((ts, tc), (ps, pc)) = (cell(&t), cell(&p));
        println!(
            "| {name} | {ts} | {ps} | {speed} | {tc} | {pc} | {} | {} | {} | {} |",
            if t.ok { ratio(t.volume, o, t.closed) } else { "-".into() },
            if p.ok { ratio(p.volume, o, p.closed) } else { "-".into() },
            t.triangles,
            p.triangles
        );
    }
    println!(
        "\ntotals: {} files; closed: truck {closed_t}, fepre {closed_f}; over the {both} files both finished: truck {tt:.2} s, fepre {tf:.2} s, ratio {:.1}",
        files.len(),
        if tf > 0.0 { tt / tf } else { 0.0 }
    );
}
