//! Running a part through the pipeline: selectors evaluated, the size field built, the CAD
//! part tessellated to it and certified, the volume meshed, the requirements checked, the
//! outputs written. `fepre run job.toml` and `fepre mesh` both come here.

use super::job::{DeckFormat, JobFile, OutputKind};
use super::part::Part;
use super::PipelineError;
use super::assembly::contact_reports;
use super::default_size::default_size;
use super::summary::summarise;
use crate::attributes::Groups;
use crate::cad::brep::FaceEntry;
use crate::core::FaceId;
use crate::mesh3d::mesher::MeshReport;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

pub use super::plan::Plan;
pub use super::summary::MeshSummary;

/// What a run did.
#[derive(Clone, Debug, Default, Serialize)]
pub struct RunReport {
    /// The input file.
    pub input: String,
    /// The faces: id, unique name, colour, STEP `#id`, solid.
    pub face_table: Vec<FaceEntry>,
    /// What each selector selects.
    pub selectors: BTreeMap<String, Vec<FaceId>>,
    /// The global size, in part units.
    pub global_size: f64,
    /// Triangles of the surface meshed.
    pub surface_triangles: usize,
    /// The tessellation's certificate passed (CAD parts).
    pub certificate_passed: Option<bool>,
    /// The tet mesh.
    pub mesh: Option<MeshSummary>,
    /// What the mesher did.
    pub mesher: Option<MeshReport>,
    /// Files written.
    pub outputs: Vec<String>,
    /// Seconds per stage.
    pub seconds: super::part::StageSeconds,
    /// Faces of different solids that touch (a part of several solids).
    pub contacts: Vec<super::assembly::ContactReport>,
    /// The FE model, where the job asks for one (a deck or a step).
    pub fe: Option<super::fe_model::FeSummary>,
    /// What the octree mesher did (method octree).
    pub octree: Option<crate::mesh3d::octree::OctreeReport>,
    /// What the run made but would rather not have (`super::warning`).
    pub warnings: Vec<super::warning::Warning>,
}

/// Runs `plan` on `part`: selectors, size field, tessellation and certificate (CAD), volume
/// mesh, requirements. With `check_only`, stops after the selectors and the size field.
///
/// # Errors
/// A selector or density error, a failed certificate, a mesher error, a requirement not met.
pub fn run_plan(part: &mut Part, plan: &Plan, check_only: bool) -> Result<RunReport, PipelineError> {
    run_plan_writing(part, plan, check_only, None)
}

/// [`run_plan`], then writes the tet mesh to `out` (its extension picks the format) unless a
/// requirement fails: the file is written while the quality is summarised and appears only
/// once the requirements hold (otherwise nothing is left, and a file already at `out` stays).
///
/// # Errors
/// As [`run_plan`]; a format that cannot hold tets, a failed write.
pub fn run_plan_to(part: &mut Part, plan: &Plan, out: &Path) -> Result<RunReport, PipelineError> {
    run_plan_writing(part, plan, false, Some(out))
}

fn run_plan_writing(part: &mut Part, plan: &Plan, check_only: bool, out: Option<&Path>) -> Result<RunReport, PipelineError> {
    let groups = part.groups(&plan.selectors)?;
    run_groups(part, plan, &groups, check_only, out)
}

/// [`run_plan`] with the selectors evaluated already (`groups`).
fn run_groups(part: &mut Part, plan: &Plan, groups: &Groups, check_only: bool, out: Option<&Path>) -> Result<RunReport, PipelineError> {
    let octree = plan.method == super::job::Method::Octree;
    let no_size = default_size(part.diagonal(), part.is_cad(), plan.method);
    let field = part.size_field(&plan.density, groups, plan.unit, no_size.global)?;
    let mut report = RunReport { input: part.path.display().to_string(), face_table: part.face_table(), selectors: groups.as_map().clone(), global_size: field.global(), ..RunReport::default() };
    if check_only {
        return Ok(report);
    }
    let tess = plan.tessellate_options(part);
    let result = if octree { part.mesh_octree(&field, &tess, &plan.octree, if plan.density.size.is_none() { no_size.resolve } else { None }).map(|_| ()) } else { part.mesh(&field, &tess, &plan.mesh).map(|_| ()) };
    report.certificate_passed = part.certified.as_ref().map(|c| c.certificate.passed);
    result?;
    report.surface_triangles = part.surface.as_ref().map_or(0, |s| s.triangles.len());
    let Some(mesh) = part.mesh.as_ref() else {
        return Err(PipelineError::Usage { path: part.path.clone(), problem: crate::pipeline::UsageProblem::NoTetMesh });
    };
    let r = part.mesh_report.clone().unwrap_or_default();
    let cad_volume = part.certified.as_ref().map(|c| c.certificate.volume[1]);
    // the file is written beside the summary (which writes nothing: see io::atomic::deferred)
    let (summarised, written) = rayon::join(
        || summarise(mesh, part.surface.as_ref(), &r, plan, &report.face_table, cad_volume),
        || out.map(|o| crate::io::atomic::deferred(|| part.write(o))),
    );
    report.mesh = Some(summarised.summary.clone());
    report.mesher = Some(r);
    report.contacts = contact_reports(&part.contacts, &report.face_table, &part.solids);
    report.seconds = part.seconds.clone();
    report.octree = part.octree_report.clone();
    report.warnings = super::warning::run_warnings(report.mesh.as_ref(), report.octree.as_ref(), plan.interface);
    summarised.check(&part.path, mesh, plan, &report.face_table)?;
    if let Some(w) = written {
        w?.commit()?;
    }
    Ok(report)
}

/// A job carried out: its report, the part and the FE model.
#[derive(Debug)]
pub struct JobOutcome {
    /// What the run did.
    pub report: RunReport,
    /// The part, meshed.
    pub part: Part,
    /// The FE model, where the job asks for one.
    pub fe: Option<crate::fe::FeModel>,
}

/// Runs a job file: reads the input, runs its plan and writes its outputs (nothing is written
/// when anything fails before).
///
/// # Errors
/// Job errors name the key and line; the others name the file and the face or entity.
pub fn run_job(jf: &JobFile, check_only: bool) -> Result<RunReport, PipelineError> {
    carry_out(jf, check_only).map(|o| o.report)
}

/// [`run_job`], keeping the part and the FE model (for `fepre solve`).
///
/// # Errors
/// As [`run_job`].
pub fn carry_out(jf: &JobFile, check_only: bool) -> Result<JobOutcome, PipelineError> {
    let job = &jf.job;
    let input_section = jf.input()?;
    let input = jf.resolve(input_section.file.get_ref());
    let mut part = Part::open(&input)?;
    let unit = if part.is_step() { job.units.to_mm() } else { job.units.to_mm() / input_section.units.unwrap_or(job.units).to_mm() };
    let plan = Plan {
        selectors: jf.selectors(),
        density: job.density.clone(),
        unit,
        method: jf.method(),
        mesh: {
            let o = jf.mesh_options();
            let tol = o.narrow_tolerance.map(|t| t * unit);
            o.with_narrow_tolerance(tol)
        },
        octree: jf.octree_options(),
        require_min_dihedral: job.require.min_dihedral.as_ref().map(|d| *d.get_ref()),
        require_max_radius_edge: job.require.max_radius_edge.map(|r| r.get()),
        require_volume_error: job.require.volume_error.map(|r| r.get()),
        interface: super::plan::Interface::JobFile,
    };
    let run = part.groups(&plan.selectors).and_then(|groups| run_groups(&mut part, &plan, &groups, check_only, None).map(|r| (r, groups)));
    let (mut report, groups) = match run {
        Ok(r) => r,
        Err(PipelineError::Select { source, .. }) | Err(PipelineError::Density { source: crate::attributes::DensityError::Select(source), .. }) => return Err(jf.select_error(&source)),
        Err(e) => return Err(e),
    };
    if check_only {
        return Ok(JobOutcome { report, part, fe: None });
    }
    let fe = if super::fe_model::wants_fe(jf) {
        let (model, summary) = super::fe_model::build_fe(jf, &part, &groups, unit)?;
        report.fe = Some(summary);
        Some(model)
    } else {
        None
    };
    let mut reports: Vec<PathBuf> = Vec::new();
    for o in &job.output {
        let path = jf.resolve(o.file.get_ref());
        match o.kind() {
            OutputKind::Report => reports.push(path.clone()),
            OutputKind::Mesh => part.write(&path)?,
            OutputKind::Surface => {
                let none = crate::mesh::TriSurface::default();
                let s = part.surface.as_ref().unwrap_or(&none);
                crate::io::write_ref(&path, crate::io::MeshRef::Surface(s), &crate::io::WriteOptions::default())?;
            }
            OutputKind::Deck => {
                let Some(m) = fe.as_ref() else { continue };
                let title = format!("{} (fepre job {})", input.display(), jf.path.display());
                match super::job::deck_format(&path) {
                    Some(DeckFormat::Nastran) => {
                        crate::deck::nastran::write_nastran(&path, m, &crate::deck::nastran::NastranOptions::default().with_large(o.large_fields).with_title(title))?;
                    }
                    Some(DeckFormat::Msh) => crate::deck::msh::write_msh(&path, m)?,
                    Some(DeckFormat::Vtu) => crate::deck::vtu::write_vtu(&path, m)?,
                    _ => crate::deck::inp::write_inp(&path, m, &title)?,
                }
            }
        }
        report.outputs.push(path.display().to_string());
    }
    for path in reports {
        let text = serde_json::to_string_pretty(&report).unwrap_or_default();
        crate::io::atomic::write_atomic(&path, |w| {
            use std::io::Write as _;
            w.write_all(text.as_bytes()).map_err(crate::io::atomic::write_err(&path))
        })?;
    }
    Ok(JobOutcome { report, part, fe })
}
