//! Layer 6: the pipeline as a library. Typed stages, after the lecture's "FE analysis in a
//! CAD environment" figure: read ([`Part::open`]: a STEP part or a surface mesh) → selectors
//! and density ([`Part::density_field`]) → tessellate and certify ([`Part::tessellate`], CAD
//! parts) → mesh ([`Part::mesh`]) → write ([`Part::write`]); later the FE model and decks.
//! [`Part`] keeps the B-rep, the certified surface, the certificate, the mesh and every
//! report. Job files ([`job`]) describe a run in TOML; [`run::run_job`] carries one out.
//!
//! `cli/` parses arguments, calls this and prints: no meshing decision is made there. Each
//! subcommand is one call here: [`inspect::inspect_file`], [`convert::convert_file`],
//! [`mesh_file::mesh_file`], [`mesh2d_file::mesh2d_file`], [`cad_info::cad_info`],
//! [`tessellate_step::tessellate_step`], [`run::run_job`], [`solve::solve_job`]; every report
//! carries its `warnings` ([`warning::Warning`]: kind, message, place), which the binary
//! prints on standard error and `--json` carries.
//!
//! ```no_run
//! use fepre::pipeline::{Part, run::{Plan, run_plan}};
//! let mut part = Part::open("part.step".as_ref())?;
//! let report = run_plan(&mut part, &Plan { unit: 1.0, ..Plan::default() }, false)?;
//! part.write("part.msh".as_ref())?;
//! # Ok::<(), fepre::pipeline::PipelineError>(())
//! ```

pub mod assembly;
pub mod cad_info;
pub mod convert;
pub mod default_size;
pub mod describe;
mod error;
pub mod fe_model;
pub mod inspect;
pub mod job;
pub mod job_fe;
pub mod mesh2d_file;
pub mod mesh_file;
pub mod octree;
pub mod part;
pub mod plan;
pub mod planar;
pub mod run;
pub mod solve;
mod summary;
pub mod tessellate_step;
pub mod tessellated;
pub mod warning;

pub use error::{PipelineError, PlanarProblem, Requirement, SolverProblem, UsageProblem};
pub use part::{Certified, Part, failure_message, tessellate_file, tessellate_model};
