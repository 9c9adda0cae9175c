//! Why a pipeline stage failed. Every variant names the file, and where it can the face,
//! the entity, the key or the line.

use crate::attributes::{DensityError, SelectError};
use crate::cad::step::StepError;
use crate::io::IoError;
use crate::mesh3d::mesher::MeshingError;
use std::path::PathBuf;

/// An error of [`crate::pipeline`].
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PipelineError {
    /// A mesh file could not be read or written.
    #[error(transparent)]
    Io(#[from] IoError),
    /// A STEP file could not be read.
    #[error(transparent)]
    Step(#[from] StepError),
    /// The input holds no closed surface to mesh (a tet mesh, a point set).
    #[error("{}: a closed surface is needed, this file holds a {kind}", path.display())]
    NotASurface {
        /// The file.
        path: PathBuf,
        /// What it holds.
        kind: &'static str,
    },
    /// The tessellation failed its certificate; the message names the faces and STEP `#id`s.
    #[error("{message}")]
    Certificate {
        /// The file.
        path: PathBuf,
        /// The certificate's failures, one per line.
        message: String,
    },
    /// The volume mesher refused the surface or failed.
    #[error("{}: {source}", path.display())]
    Meshing {
        /// The file.
        path: PathBuf,
        /// Why.
        source: MeshingError,
    },
    /// The octree mesher made no mesh.
    #[error("{}: octree meshing: {source}", path.display())]
    Octree {
        /// The file.
        path: PathBuf,
        /// Why.
        source: crate::mesh3d::octree::OctreeError,
    },
    /// A selector failed.
    #[error("{}: {source}", path.display())]
    Select {
        /// The file the selector was evaluated on.
        path: PathBuf,
        /// Why.
        source: SelectError,
    },
    /// A density could not be built.
    #[error("{}: {source}", path.display())]
    Density {
        /// The file.
        path: PathBuf,
        /// Why.
        source: DensityError,
    },
    /// A job file is wrong: the message names the key, its line and column.
    #[error("{}:{line}:{column}: {message}", path.display())]
    Job {
        /// The job file.
        path: PathBuf,
        /// 1-based line of the offending key or value (0 when unknown).
        line: usize,
        /// 1-based column.
        column: usize,
        /// What is wrong.
        message: String,
    },
    /// An output format that cannot hold what is written (bad usage).
    #[error("{}: {message}", path.display())]
    Usage {
        /// The file.
        path: PathBuf,
        /// What would work.
        message: String,
    },
    /// The mesh falls short of a `require` of the job.
    #[error("{}: {message}", path.display())]
    Requirement {
        /// The input.
        path: PathBuf,
        /// What falls short.
        message: String,
    },
    /// A face asked for by the 2D mesher is missing, not planar, or could not be meshed; the
    /// message names the face and its STEP `#id`.
    #[error("{}: {message}", path.display())]
    Planar {
        /// The file.
        path: PathBuf,
        /// What went wrong, naming the face.
        message: String,
    },
    /// Two solids of an assembly overlap; the message names both solids, their faces (and
    /// those faces' STEP `#id`s), a point and the depth.
    #[error("{}: {source} (STEP faces {step_faces})", path.display())]
    Overlap {
        /// The file.
        path: PathBuf,
        /// The mesher's [`MeshingError::Overlap`].
        source: MeshingError,
        /// The STEP `#id`s of the two faces.
        step_faces: String,
    },
    /// The solver is missing or failed; the message says how to install it or quotes its
    /// errors.
    #[error("{}: {message}", path.display())]
    Solver {
        /// The deck (or the solver binary where it cannot be run).
        path: PathBuf,
        /// What went wrong.
        message: String,
    },
}
