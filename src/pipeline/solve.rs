//! `fepre solve`: a job's deck run through CalculiX, its results read back and written for
//! ParaView (VTU with displacement, stress, von Mises, reactions, temperatures, mode shapes)
//! and as a JSON summary (largest displacement and von Mises stress and where, reaction totals
//! per held set, frequencies, temperature range). One step where ccx2paraview is a second
//! tool.

use super::{PipelineError, SolverProblem};
use super::job::{JobFile, OutputKind};
use super::run::{JobOutcome, RunReport, carry_out};
use crate::fe::{Analysis, Bc, FeModel};
use crate::io::ccx_dat::ForceTotal;
use crate::io::frd::{FrdField, FrdResults, FrdStep, FrdStepKind};
use crate::io::vtu::{Grid, write_grid_with_data};
use crate::io::WriteOptions;
use glam::DVec3;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use super::error::CCX_ENV;

/// A value at a node.
#[derive(Clone, Debug, Serialize)]
pub struct AtNode {
    /// The value.
    pub value: f64,
    /// The node (1-based, as in the deck).
    pub node: u32,
    /// Where it is.
    pub at: [f64; 3],
}

/// The results of one step.
#[derive(Clone, Debug, Serialize)]
pub struct StepResults {
    /// The step's name.
    pub name: String,
    /// `static`, `frequency` or `heat`.
    pub analysis: String,
    /// The largest displacement magnitude (static).
    pub max_displacement: Option<AtNode>,
    /// The largest von Mises stress at a node (static; ccx extrapolates stresses to nodes).
    pub max_von_mises: Option<AtNode>,
    /// The sum of the reaction forces over each held node set (static): ccx's own total from
    /// the `.dat` file.
    pub reactions: BTreeMap<String, [f64; 3]>,
    /// Natural frequencies, cycles per time unit (Hz with seconds), lowest first (frequency).
    pub frequencies: Vec<f64>,
    /// The lowest and highest nodal temperature (heat).
    pub temperature_range: Option<[f64; 2]>,
}

/// What `fepre solve` did.
#[derive(Clone, Debug, Serialize)]
pub struct SolveReport {
    /// The run: mesh, FE model, outputs.
    pub run: RunReport,
    /// The deck solved.
    pub deck: String,
    /// The CalculiX results file read.
    pub frd: String,
    /// The VTU written.
    pub results: String,
    /// The JSON summary written.
    pub summary: String,
    /// Per step.
    pub steps: Vec<StepResults>,
}

/// Runs `jf`, writes its CalculiX deck (its first `.inp` output, or the job's name with `.inp`
/// beside the job file), runs `ccx` on it, reads the results and writes the VTU and the JSON
/// summary.
///
/// # Errors
/// As [`super::run::run_job`]; a job without steps; [`PipelineError::Solver`] where `ccx` is
/// missing or fails (with its `*ERROR` lines) or its results cannot be read.
pub fn solve_job(jf: &JobFile) -> Result<SolveReport, PipelineError> {
    if jf.job.step.is_empty() {
        return Err(PipelineError::Job { path: jf.path.clone(), line: 0, column: 0, key: None, message: "`fepre solve` needs at least one [[step]] (boundary conditions and loads on selectors)".into() });
    }
    let ccx = std::env::var_os(CCX_ENV).map_or_else(|| PathBuf::from("ccx"), PathBuf::from);
    ccx_version(&ccx)?;
    let deck = jf.job.output.iter().find(|o| o.kind() == OutputKind::Deck && super::job::deck_format(o.file.get_ref()) == Some(super::job::DeckFormat::Inp)).map(|o| jf.resolve(o.file.get_ref()));
    let JobOutcome { mut report, fe, .. } = carry_out(jf, false)?;
    let Some(model) = fe else {
        return Err(PipelineError::Usage { path: jf.path.clone(), problem: crate::pipeline::error::UsageProblem::NoFeModel });
    };
    let deck = match deck {
        Some(d) => d,
        None => {
            let d = jf.path.with_extension("inp");
            crate::deck::inp::write_inp(&d, &model, &format!("fepre job {}", jf.path.display()))?;
            report.outputs.push(d.display().to_string());
            d
        }
    };
    let frd_path = run_ccx(&ccx, &deck)?;
    let frd = crate::io::frd::read(&frd_path)?;
    // a heat or frequency step prints nothing: an empty `.dat`
    let totals = match crate::io::ccx_dat::read_force_totals(&frd_path.with_extension("dat")) {
        Err(crate::io::IoError::Empty { .. }) => Vec::new(),
        other => other?,
    };
    let steps = step_results(&model, &frd, totals);
    let stem = deck.file_stem().and_then(|s| s.to_str()).unwrap_or("results").to_string();
    let folder = deck.parent().map(Path::to_path_buf).unwrap_or_default();
    let results = jf.job.solve.results.as_ref().map_or_else(|| folder.join(format!("{stem}_results.vtu")), |p| jf.resolve(p.get_ref()));
    let summary = jf.job.solve.summary.as_ref().map_or_else(|| folder.join(format!("{stem}_results.json")), |p| jf.resolve(p.get_ref()));
    write_results(&results, &model, &frd)?;
    let out = SolveReport { run: report, deck: deck.display().to_string(), frd: frd_path.display().to_string(), results: results.display().to_string(), summary: summary.display().to_string(), steps };
    let text = serde_json::to_string_pretty(&out).unwrap_or_default();
    crate::io::atomic::write_atomic(&summary, |w| {
        use std::io::Write as _;
        w.write_all(text.as_bytes()).map_err(crate::io::atomic::write_err(&summary))
    })?;
    Ok(out)
}

fn solver_error(path: &Path, problem: SolverProblem) -> PipelineError {
    PipelineError::Solver { path: path.to_path_buf(), problem }
}

/// Checks that `ccx` runs.
fn ccx_version(ccx: &Path) -> Result<(), PipelineError> {
    match Command::new(ccx).arg("-v").output() {
        Ok(_) => Ok(()),
        Err(e) => Err(solver_error(ccx, SolverProblem::NotInstalled { why: e.to_string() })),
    }
}

/// Runs `ccx -i STEM` in the deck's folder; its output goes to `STEM.log` there. Returns the
/// `.frd` file.
fn run_ccx(ccx: &Path, deck: &Path) -> Result<PathBuf, PipelineError> {
    let folder = deck.parent().filter(|p| !p.as_os_str().is_empty()).map_or_else(|| PathBuf::from("."), Path::to_path_buf);
    let stem = deck.file_stem().and_then(|s| s.to_str()).ok_or_else(|| solver_error(deck, SolverProblem::DeckName))?;
    let frd = folder.join(format!("{stem}.frd"));
    let _ = std::fs::remove_file(&frd);
    let out = Command::new(ccx).arg("-i").arg(stem).current_dir(&folder).output().map_err(|e| solver_error(ccx, SolverProblem::CannotRun { why: e.to_string() }))?;
    let mut log = out.stdout.clone();
    log.extend_from_slice(&out.stderr);
    let log_path = folder.join(format!("{stem}.log"));
    let _ = std::fs::write(&log_path, &log);
    let text = String::from_utf8_lossy(&log);
    let errors: Vec<&str> = text.lines().filter(|l| l.contains("*ERROR")).map(str::trim).take(5).collect();
    if !out.status.success() || !errors.is_empty() || !frd.is_file() {
        let why = if errors.is_empty() { format!("exit status {}", out.status) } else { errors.join("; ") };
        return Err(solver_error(deck, SolverProblem::Failed { why, log: log_path }));
    }
    Ok(frd)
}

/// The frd steps of analysis step `k` (1-based); a file without step records gives all.
fn of_step(frd: &FrdResults, k: u32) -> Vec<&FrdStep> {
    let tagged = frd.steps.iter().any(|s| s.analysis_step.is_some());
    frd.steps.iter().filter(|s| !tagged || s.analysis_step == Some(k)).collect()
}

/// Values of `field` per model node (0-based), `width` each; nodes the field lacks get 0.
fn per_model_node(field: &FrdField, nodes: usize) -> Vec<f64> {
    let w = field.width();
    let mut out = vec![0.0; nodes * w];
    for (n, v) in field.per_node() {
        if let Some(i) = (n as usize).checked_sub(1).filter(|&i| i < nodes) {
            out[i * w..i * w + w].copy_from_slice(v);
        }
    }
    out
}

/// The von Mises stress per node of stresses given `width` values per node (six: SXX SYY
/// SZZ SXY SYZ SZX; other widths have none).
fn von_mises_of(values: &[f64], width: usize) -> Option<Vec<f64>> {
    (width == 6).then(|| values.chunks(6).map(|x| crate::io::frd::von_mises([x[0], x[1], x[2], x[3], x[4], x[5]])).collect())
}

fn largest(values: impl Iterator<Item = f64>, m: &FeModel) -> Option<AtNode> {
    let (i, v) = values.enumerate().filter(|(_, v)| v.is_finite()).max_by(|a, b| a.1.total_cmp(&b.1))?;
    Some(AtNode { value: v, node: i as u32 + 1, at: m.nodes[i].to_array() })
}

/// Each step's results; reaction totals from ccx's own sums in the `.dat` file (`totals`, in
/// file order: per static step, one per held set in the order of its boundary conditions),
/// else summed from the `.frd`'s nodal forces.
fn step_results(m: &FeModel, frd: &FrdResults, totals: Vec<ForceTotal>) -> Vec<StepResults> {
    let nn = m.nodes.len();
    let mut totals: std::collections::VecDeque<ForceTotal> = totals.into();
    let mut out = Vec::new();
    for (k, step) in m.steps.iter().enumerate() {
        let blocks = of_step(frd, k as u32 + 1);
        let mut r = StepResults { name: step.name.clone(), analysis: String::new(), max_displacement: None, max_von_mises: None, reactions: BTreeMap::new(), frequencies: Vec::new(), temperature_range: None };
        match step.analysis {
            Analysis::Frequency { .. } => {
                r.analysis = "frequency".into();
                r.frequencies = blocks.iter().filter(|b| b.kind == FrdStepKind::Frequency).map(|b| b.value).collect();
            }
            Analysis::Heat => {
                r.analysis = "heat".into();
                if let Some(t) = blocks.last().and_then(|b| b.field("NDTEMP")) {
                    let v = per_model_node(t, nn);
                    r.temperature_range = Some([v.iter().copied().fold(f64::INFINITY, f64::min), v.iter().copied().fold(f64::NEG_INFINITY, f64::max)]);
                }
            }
            Analysis::Static => {
                r.analysis = "static".into();
                let last = blocks.last();
                if let Some(d) = last.and_then(|b| b.field("DISP")) {
                    let v = per_model_node(d, nn);
                    r.max_displacement = largest(v.chunks(3).map(|u| DVec3::new(u[0], u[1], u[2]).length()), m);
                }
                if let Some(vm) = last.and_then(|b| b.field("STRESS")).and_then(|s| von_mises_of(&per_model_node(s, nn), s.width())) {
                    r.max_von_mises = largest(vm.into_iter(), m);
                }
                let forc = last.and_then(|b| b.field("FORC")).map(|f| per_model_node(f, nn));
                for bc in &step.bcs {
                    if let Bc::Fixed { nodes, .. } | Bc::Displacement { nodes, .. } = bc {
                        let printed = totals.iter().position(|t| t.set.eq_ignore_ascii_case(nodes)).and_then(|k| totals.remove(k));
                        let sum = match (printed, &forc) {
                            (Some(t), _) => Some(t.total),
                            (None, Some(v)) => Some(m.node_sets[nodes].iter().fold(DVec3::ZERO, |s, &n| s + DVec3::from_slice(&v[3 * n as usize..3 * n as usize + 3])).to_array()),
                            (None, None) => None,
                        };
                        if let Some(sum) = sum {
                            r.reactions.insert(nodes.clone(), sum);
                        }
                    }
                }
            }
        }
        out.push(r);
    }
    out
}

/// The VTU of the results: the model's elements and, per step (prefixed by the step's name
/// where there are several), `displacement`, `stress`, `von_mises`, `reaction` (static),
/// `mode_K` (frequency), `temperature` and `heat_flux` (heat); the `region` of each element.
fn write_results(path: &Path, m: &FeModel, frd: &FrdResults) -> Result<(), PipelineError> {
    let nn = m.nodes.len();
    let several = m.steps.len() > 1;
    let mut arrays: Vec<(String, usize, Vec<f64>)> = Vec::new();
    for (k, step) in m.steps.iter().enumerate() {
        let prefix = if several { format!("{}/", step.name) } else { String::new() };
        let blocks = of_step(frd, k as u32 + 1);
        let array = |name: &str, f: &FrdField| (format!("{prefix}{name}"), f.width(), per_model_node(f, nn));
        match step.analysis {
            Analysis::Frequency { .. } => {
                for (j, b) in blocks.iter().filter(|b| b.kind == FrdStepKind::Frequency).enumerate() {
                    if let Some(d) = b.field("DISP") {
                        arrays.push(array(&format!("mode_{}", j + 1), d));
                    }
                }
            }
            Analysis::Heat => {
                if let Some(b) = blocks.last() {
                    if let Some(t) = b.field("NDTEMP") {
                        arrays.push(array("temperature", t));
                    }
                    if let Some(q) = b.field("FLUX") {
                        arrays.push(array("heat_flux", q));
                    }
                }
            }
            Analysis::Static => {
                if let Some(b) = blocks.last() {
                    if let Some(d) = b.field("DISP") {
                        arrays.push(array("displacement", d));
                    }
                    if let Some(s) = b.field("STRESS") {
                        let stress = array("stress", s);
                        let vm = von_mises_of(&stress.2, stress.1);
                        arrays.push(stress);
                        if let Some(vm) = vm {
                            arrays.push((format!("{prefix}von_mises"), 1, vm));
                        }
                    }
                    if let Some(f) = b.field("FORC") {
                        arrays.push(array("reaction", f));
                    }
                }
            }
        }
    }
    let regions: Vec<i32> = m.element_regions.iter().map(|r| r.0.min(i32::MAX as u32) as i32).collect();
    let mut grid = Grid::new(&m.nodes, &m.elements, m.kind.nodes()).with_cell_ints("region", &regions);
    for (name, w, v) in &arrays {
        grid = grid.with_point_data(name, *w, v);
    }
    write_grid_with_data(path, &grid, &WriteOptions::default())?;
    Ok(())
}
