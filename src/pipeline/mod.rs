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
//! use fepre::pipeline::{Part, Plan, run_plan};
//! let mut part = Part::open("part.step".as_ref())?;
//! let report = run_plan(&mut part, &Plan { unit: 1.0, ..Plan::default() }, false)?;
//! part.write("part.msh".as_ref())?;
//! # Ok::<(), fepre::pipeline::PipelineError>(())
//! ```

pub(crate) mod assembly;
pub(crate) mod cad_info;
pub(crate) mod convert;
pub(crate) mod default_size;
pub(crate) mod delaunay_file;
pub(crate) mod describe;
mod error;
pub(crate) mod fe_model;
pub(crate) mod inspect;
pub mod job;
pub(crate) mod job_fe;
pub(crate) mod mesh2d_file;
pub(crate) mod mesh2d_job;
pub(crate) mod mesh2d_regions;
pub(crate) mod mesh_file;
pub(crate) mod octree;
pub(crate) mod part;
pub(crate) mod plan;
pub(crate) mod planar;
pub(crate) mod run;
pub(crate) mod solve;
mod summary;
pub(crate) mod tessellate_step;
pub(crate) mod tessellated;
pub(crate) mod warning;

pub use assembly::{ContactReport, ContactSide, gap_of, solids_of};
pub use cad_info::{BrepInfo, CadInfo, CadInfoOptions, MeshInfo, TessellatedInfo, cad_info};
pub use convert::{ConvertOptions, ConvertReport, convert_file};
pub use delaunay_file::{DelaunayFileReport, LISTED_DUPLICATES, delaunay_file};
pub use default_size::{DEFAULT_DIVISIONS, DefaultSize, default_size};
pub use describe::{cell_choice, refinement_text};
pub use error::{CCX_ENV, PipelineError, PlanarProblem, Requirement, SolverProblem, UsageProblem};
pub use fe_model::{FeSummary, SolidSummary, StepSummary};
pub use inspect::{InspectOptions, InspectReport, TagInfo, TetKeys, inspect_file};
pub use job::{JobFile, Method};
pub use mesh2d_file::{FaceReport, Mesh2dReport, Mesh2dRequest, mesh2d_file};
pub use mesh2d_regions::mesh2d_poly;
pub use mesh2d_job::{check_mesh2d_regions, mesh2d_job};
pub use mesh_file::{MeshFileReport, mesh_file};
pub use part::{Certified, Part, StageSeconds, failure_message, tessellate_file, tessellate_model};
pub use plan::{Interface, Plan};
pub use planar::{FaceChoice, FailedPlanarFace, MeshedFace, PlanarFaces, mesh_planar_faces};
pub use run::{JobOutcome, RunReport, carry_out, run_job, run_plan, run_plan_to};
pub use solve::{AtNode, SolveReport, StepResults, solve_job};
pub use summary::MeshSummary;
pub use tessellate_step::{
    BrepTessellation, EulerEntry, FailedFaceEntry, OpenSurface, TessellateFailure, TessellateReport, TessellateStepOptions, TessellatedFileReport,
    tessellate_step,
};
pub use tessellated::{MeshCertificate, TessellatedSummary, certify_surface, mesh_failure_message};
pub use warning::{Place, VOLUME_WARNING, Warning, WarningKind};
