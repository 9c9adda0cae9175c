//! `fepre solve job.toml`: the job's deck solved by CalculiX, results written for ParaView and
//! summarised.

use fepre::pipeline::job::JobFile;
use fepre::pipeline::{SolveReport, solve_job};
use anyhow::Result;
use std::path::PathBuf;

/// Examples shown by `fepre solve --help`.
pub const EXAMPLES: &str = "\
Examples:
  fepre solve cad_fixtures/bracket_load.toml   the bracket, fixed at one end, loaded at the other
  fepre solve job.toml --json                   the summary as one JSON object

The job file needs materials, a section and a step (docs/job-file.md):
  [materials.steel]
  young = 210000                                # consistent units: mm, N, MPa, tonne/mm³
  poisson = 0.3
  [[section]]
  material = \"steel\"                            # every solid; `solid = NAME or NUMBER` picks one
  [[step]]
  type = \"static\"                               # or \"frequency\" (modes = 10), \"heat\"
  fixed = [{ faces = \"clamp\" }]                 # selectors; dofs = [1, 2, 3]
  force = [{ faces = \"tip\", total = [0, 0, -1000] }]
  pressure = [{ faces = \"bore\", value = 10 }]

CalculiX (ccx) must be on the PATH (Debian/Ubuntu: apt install calculix-ccx), or named by
FEPRE_CCX. Writes the deck (the job's .inp output, or JOB.inp), DECK_results.vtu (displacement,
stress, von_mises, reaction, mode shapes, temperature) and DECK_results.json.";

/// Arguments of `fepre solve`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The job file (TOML).
    pub job: PathBuf,
    /// Print one JSON object on standard output.
    #[arg(long)]
    pub json: bool,
}

/// Runs `fepre solve`.
///
/// # Errors
/// As `fepre run`; a missing or failing `ccx`: exit 1.
pub fn run(args: &Args) -> Result<()> {
    let progress = crate::cli::progress::Progress::start(&format!("solving {}", args.job.display()));
    let jf = JobFile::read(&args.job)?;
    let report = solve_job(&jf)?;
    progress.finish();
    if args.json {
        outln!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print(&report);
    }
    Ok(())
}

fn print(r: &SolveReport) {
    if let Some(m) = &r.run.mesh {
        outln!("tets             {} (dihedral {:.2}° .. {:.2}°)", m.tets, m.min_dihedral_deg, m.max_dihedral_deg);
    }
    if let Some(fe) = &r.run.fe {
        crate::cli::print_fe_summary(fe);
    }
    outln!("deck             {}", r.deck);
    for s in &r.steps {
        outln!("step             {} ({})", s.name, s.analysis);
        if let Some(d) = &s.max_displacement {
            outln!("  displacement   max {:.6e} at node {} ({:.4}, {:.4}, {:.4})", d.value, d.node, d.at[0], d.at[1], d.at[2]);
        }
        if let Some(v) = &s.max_von_mises {
            outln!("  von Mises      max {:.6e} at node {} ({:.4}, {:.4}, {:.4})", v.value, v.node, v.at[0], v.at[1], v.at[2]);
        }
        for (set, f) in &s.reactions {
            outln!("  reaction       {set}: {:.6e} {:.6e} {:.6e}", f[0], f[1], f[2]);
        }
        if !s.frequencies.is_empty() {
            let f: Vec<String> = s.frequencies.iter().map(|x| format!("{x:.6}")).collect();
            outln!("  frequencies    {}", f.join(", "));
        }
        if let Some([lo, hi]) = s.temperature_range {
            outln!("  temperature    {lo:.6} .. {hi:.6}");
        }
    }
    outln!("wrote            {}", r.results);
    outln!("wrote            {}", r.summary);
}
