//! Why a pipeline stage failed. Every variant names the file, and where it can the face,
//! the entity, the key or the line.

use crate::attributes::{DensityError, SelectError};
use crate::cad::brep::{Dropped, EntityRef};
use crate::cad::step::StepError;
use crate::core::FaceId;
use crate::io::IoError;
use crate::mesh3d::mesher::MeshingError;
use crate::tessellate::certificate::{Certificate, CheckFailure};
use serde::Serialize;
use std::path::{Path, PathBuf};

/// An error of [`crate::pipeline`]. It serializes (serde) with the variant's name as the key;
/// errors of other stages that do not serialize are written as their message.
#[derive(Debug, thiserror::Error, Serialize)]
#[non_exhaustive]
pub enum PipelineError {
    /// A mesh file could not be read or written.
    #[error(transparent)]
    Io(#[from] IoError),
    /// A STEP file could not be read.
    #[error(transparent)]
    Step(#[from] #[serde(serialize_with = "crate::core::error_json::message")] StepError),
    /// The input holds no closed surface to mesh (a tet mesh, a point set).
    #[error("{}: a closed surface is needed, this file holds a {kind}", path.display())]
    NotASurface {
        /// The file.
        path: PathBuf,
        /// What it holds.
        kind: &'static str,
    },
    /// The tessellation failed its certificate; the first failures name the faces and STEP
    /// `#id`s.
    #[error("{}", certificate_text(path, *failure_count, failures, dropped))]
    Certificate {
        /// The file.
        path: PathBuf,
        /// Failed checks in all.
        failure_count: usize,
        /// The first five failures.
        failures: Vec<CheckFailure>,
        /// The first five entities the reader dropped.
        dropped: Vec<Dropped>,
    },
    /// A tessellated-only file's surface failed its mesh certificate (closed, manifold,
    /// oriented outward, no self-intersection, no zero-area triangle).
    #[error("{}", super::tessellated::mesh_failure_message(path, certificate))]
    MeshCertificate {
        /// The file.
        path: PathBuf,
        /// The checks, failed and passed.
        certificate: Box<super::tessellated::MeshCertificate>,
    },
    /// The volume mesher refused the surface or failed.
    #[error("{}: {source}", path.display())]
    Meshing {
        /// The file.
        path: PathBuf,
        /// Why.
        source: MeshingError,
    },
    /// The point set spans no tetrahedron.
    #[error("{}: {source}", path.display())]
    Delaunay {
        /// The points' file.
        path: PathBuf,
        /// Why.
        source: crate::mesh3d::delaunay::DelaunayError,
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
        #[serde(serialize_with = "crate::core::error_json::message")]
        source: SelectError,
    },
    /// A density could not be built.
    #[error("{}: {source}", path.display())]
    Density {
        /// The file.
        path: PathBuf,
        /// Why.
        #[serde(serialize_with = "crate::core::error_json::message")]
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
        /// The key there, where the place is known and a `key =` precedes it on its line.
        key: Option<String>,
        /// What is wrong.
        message: String,
    },
    /// Something the call cannot do with what it was given (bad usage).
    #[error("{}: {problem}", path.display())]
    Usage {
        /// The file.
        path: PathBuf,
        /// What is missing or would work.
        problem: UsageProblem,
    },
    /// The mesh falls short of a `require` of the job.
    #[error("{}: {message}", path.display())]
    Requirement {
        /// The input.
        path: PathBuf,
        /// The requirement not met.
        requirement: Requirement,
        /// What the mesh has (degrees, a share of the volume or a ratio, as `requirement`).
        found: f64,
        /// What is required.
        required: f64,
        /// What falls short, with the worst tet's place.
        message: String,
    },
    /// A Triangle `.poly` file that cannot be read or has no valid regions (the error names
    /// the line, vertex, segment or seed).
    #[error(transparent)]
    Poly(#[from] crate::io::PolyError),
    /// A region of a `.poly` file the 2D method could not mesh.
    #[error("{}: region {region}: {source}", path.display())]
    Region2d {
        /// The file.
        path: PathBuf,
        /// The region's tag.
        region: u32,
        /// Why.
        source: crate::mesh2d::Mesh2dError,
    },
    /// A face asked for by the 2D mesher is missing, not planar, or could not be meshed.
    #[error("{}: {problem}", path.display())]
    Planar {
        /// The file.
        path: PathBuf,
        /// What went wrong, naming the face and its STEP `#id`.
        problem: PlanarProblem,
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
    /// The solver is missing or failed: how to install it, or its errors.
    #[error("{}: {problem}", path.display())]
    Solver {
        /// The deck (or the solver binary where it cannot be run).
        path: PathBuf,
        /// What went wrong.
        problem: SolverProblem,
    },
}

impl PipelineError {
    /// The error of a tessellation whose `certificate` failed, with the entities the reader
    /// `dropped` (the first five of each are kept).
    pub fn certificate(path: &Path, certificate: &Certificate, dropped: &[Dropped]) -> PipelineError {
        PipelineError::Certificate {
            path: path.to_path_buf(),
            failure_count: certificate.failure_count,
            failures: certificate.failures.iter().take(5).cloned().collect(),
            dropped: dropped.iter().take(5).cloned().collect(),
        }
    }
}

/// The text of [`PipelineError::Certificate`]: a line naming the file and the count, one per
/// dropped entity and per failure.
fn certificate_text(path: &Path, failure_count: usize, failures: &[CheckFailure], dropped: &[Dropped]) -> String {
    let mut msg = format!("{}: the tessellation fails its certificate ({} failed checks)", path.display(), failure_count);
    for d in dropped.iter().take(5) {
        msg.push_str(&format!("\n  the reader dropped {} {}: {}", d.id, d.kind, d.why));
    }
    for f in failures.iter().take(5) {
        msg.push_str("\n  ");
        msg.push_str(f.check);
        if let Some(face) = f.face {
            msg.push_str(&format!(" face {}", face.0));
        }
        if let Some(id) = f.step_id {
            msg.push_str(&format!(" ({id})"));
        }
        msg.push_str(": ");
        msg.push_str(&f.message);
    }
    if failure_count > 5 {
        msg.push_str(&format!("\n  ... {} more (--json lists up to 20)", failure_count - 5));
    }
    msg
}

/// What a call lacks or was given wrongly ([`PipelineError::Usage`]).
#[derive(Clone, Debug, PartialEq, thiserror::Error, Serialize)]
#[non_exhaustive]
pub enum UsageProblem {
    /// The input is a surface or mesh file, not a CAD part.
    #[error("not a CAD part: nothing to tessellate")]
    NotCad,
    /// There is no surface to mesh.
    #[error("no surface to mesh")]
    NoSurface,
    /// No solid of the part encloses a volume.
    #[error("no solid to mesh")]
    NoSolid,
    /// The run made no tet mesh.
    #[error("no tet mesh was made")]
    NoTetMesh,
    /// An FE model was asked for where there is no tet mesh.
    #[error("no tet mesh to build an FE model from")]
    NoTetMeshForModel,
    /// The job made no FE model to solve.
    #[error("the job made no FE model")]
    NoFeModel,
    /// An output file whose format holds neither tets nor surfaces.
    #[error("tets are written as .mesh, .ele/.node, .vtu or .msh, surfaces as .stl, .obj, .off, .vtu or .msh")]
    OutputFormat,
    /// The worker threads asked for cannot start.
    #[error("cannot start the worker threads: {why}")]
    Threads {
        /// The thread pool's reason.
        why: String,
    },
    /// A tet mesh's output file of a format that holds no tets.
    #[error("tets are written as .mesh, .ele/.node, .vtu or .msh")]
    TetFormat,
    /// A surface's output file of a format the surface writers do not write.
    #[error("the surface is written as .stl, .obj, .vtu or .msh")]
    SurfaceFormat,
    /// Planar faces' output file of a format that holds no tagged faces.
    #[error("the faces are written as .msh, .vtu, .mesh, .obj or .stl")]
    FacesFormat,
    /// A conversion's output file of a format fepre does not write.
    #[error("fepre cannot write this extension; use one of .stl .obj .off .mesh .node .ele .face .poly .smesh .msh .vtu")]
    ConvertFormat,
    /// The FE model built fails its own checks (our bug).
    #[error("the FE model is inconsistent (a bug): {why}")]
    InconsistentModel {
        /// The model's check.
        why: String,
    },
}

/// A requirement of a job ([`PipelineError::Requirement`]).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize)]
#[non_exhaustive]
pub enum Requirement {
    /// `require_min_dihedral`: the smallest dihedral angle, in degrees.
    MinDihedral,
    /// The default requirement: no tet under 1° that no input angle under 1° explains (found:
    /// the smallest such angle, in degrees).
    NoUnexplainedSliver,
    /// `require_volume_error`: the mesh's volume against the CAD solids', as a share.
    VolumeError,
    /// `require_max_radius_edge`: the largest radius-edge ratio.
    MaxRadiusEdge,
    /// `--require-min-angle` of `mesh2d`: the smallest angle of a 2D mesh, in degrees.
    MinAngle2d,
}

/// Why the 2D mesher could not take a face ([`PipelineError::Planar`]).
#[derive(Clone, Debug, PartialEq, thiserror::Error, Serialize)]
#[non_exhaustive]
pub enum PlanarProblem {
    /// The part has no such face.
    #[error("face {} does not exist (the part has {faces} faces)", face.0)]
    NoSuchFace {
        /// The face asked for.
        face: FaceId,
        /// Faces of the part.
        faces: usize,
    },
    /// The face is not a plane.
    #[error("face {} ({step_id}) is not planar", face.0)]
    NotPlanar {
        /// The face.
        face: FaceId,
        /// Its STEP instance.
        step_id: EntityRef,
    },
    /// The face could not be made a domain or meshed.
    #[error("{reason} (STEP {step_id})")]
    Failed {
        /// The face.
        face: FaceId,
        /// Its STEP instance.
        step_id: EntityRef,
        /// Why (the domain's or the quadtree mesher's error).
        reason: String,
    },
}

/// The environment variable that names the CalculiX binary (default `ccx` on the PATH).
pub const CCX_ENV: &str = "FEPRE_CCX";

/// Why the solver did not run or failed ([`PipelineError::Solver`]).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error, Serialize)]
#[non_exhaustive]
pub enum SolverProblem {
    /// `ccx` cannot be started: how to install it.
    #[error(
        "CalculiX (ccx) cannot be run ({why}): install it (Debian/Ubuntu: `apt install calculix-ccx`; conda: `conda install -c conda-forge calculix`) or set {} to its path",
        CCX_ENV
    )]
    NotInstalled {
        /// The operating system's reason.
        why: String,
    },
    /// The deck's file name cannot be passed to `ccx`.
    #[error("the deck's name is not valid UTF-8")]
    DeckName,
    /// `ccx` could not be started on the deck.
    #[error("cannot run: {why}")]
    CannotRun {
        /// The operating system's reason.
        why: String,
    },
    /// `ccx` failed: its `*ERROR` lines (or its exit status), and where its output is.
    #[error("CalculiX failed: {why} (its output is in {})", log.display())]
    Failed {
        /// Its first `*ERROR` lines joined by `; `, else its exit status.
        why: String,
        /// Its log file.
        log: PathBuf,
    },
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn errors_name_their_entities_in_text_and_json() {
        let e = PipelineError::Planar { path: "p.step".into(), problem: PlanarProblem::NoSuchFace { face: FaceId(9), faces: 4 } };
        assert_eq!(e.to_string(), "p.step: face 9 does not exist (the part has 4 faces)");
        assert_eq!(serde_json::to_value(&e).unwrap(), json!({"Planar": {"path": "p.step", "problem": {"NoSuchFace": {"face": 9, "faces": 4}}}}));
        let e = PipelineError::Usage { path: "m.xyz".into(), problem: UsageProblem::OutputFormat };
        assert_eq!(e.to_string(), "m.xyz: tets are written as .mesh, .ele/.node, .vtu or .msh, surfaces as .stl, .obj, .off, .vtu or .msh");
        assert_eq!(serde_json::to_value(&e).unwrap(), json!({"Usage": {"path": "m.xyz", "problem": "OutputFormat"}}));
        // a foreign error inside is written as its message
        let e = PipelineError::Io(IoError::Read { path: "m.stl".into(), source: std::io::Error::other("gone") });
        assert_eq!(serde_json::to_value(&e).unwrap(), json!({"Io": {"Read": {"path": "m.stl", "source": "gone"}}}));
        let e = PipelineError::Solver { path: "ccx".into(), problem: SolverProblem::CannotRun { why: "no such file".into() } };
        assert_eq!(e.to_string(), "ccx: cannot run: no such file");
    }
}
