//! Why one face could not be meshed in its parameter domain ([`FaceError`]). The tessellator
//! lists the face with this reason in [`super::Tessellation::failed`].

use crate::cad::brep::EntityRef;
use serde::Serialize;

/// Why a face could not be meshed.
#[derive(Clone, Debug, PartialEq, Serialize, thiserror::Error)]
#[non_exhaustive]
pub enum FaceError {
    /// Boundary segments cross or touch in parameter space: those segments, as the global
    /// vertex ids of their ends (the tessellator splits the edge segments among them and
    /// meshes again).
    #[error("boundary segments cross in parameter space ({} segments)", .0.len())]
    Crossing(Vec<[u32; 2]>),
    /// A boundary loop that maps to fewer than two points.
    #[error("loop {edge_loop} has fewer than two points")]
    LoopTooShort {
        /// The loop (STEP `#id`).
        edge_loop: EntityRef,
    },
    /// A loop that goes once around a closed (not periodic) B-spline surface, across its seam.
    #[error("loop {edge_loop} goes once around a closed B-spline surface in {direction} (across its seam): not supported yet")]
    AcrossSeam {
        /// The loop (STEP `#id`).
        edge_loop: EntityRef,
        /// `"u"` or `"v"`.
        direction: &'static str,
    },
    /// A loop that goes once around a surface periodic in `v`.
    #[error("loop {edge_loop} goes once around the surface in v: not supported yet")]
    AroundInV {
        /// The loop (STEP `#id`).
        edge_loop: EntityRef,
    },
    /// A face without edge loops on a surface with an unbounded parameter domain.
    #[error("a face without edge loops on an unbounded surface")]
    UnboundedWithoutLoops,
    /// Hole loops only, which between them cover every parameter of a closed direction.
    #[error("the face's loops are all holes and cover every {direction} of its closed surface: not supported yet")]
    HolesCoverClosed {
        /// `"u"` or `"v"`.
        direction: &'static str,
    },
    /// A loop around a periodic surface with no pole on the face's side to cut to.
    #[error("a loop goes once around a periodic surface that has no pole on the face's side: not supported yet")]
    NoPoleOnSide,
    /// More loops around a periodic surface than one.
    #[error("{loops} loops go around a periodic surface: not supported yet")]
    ManyAround {
        /// How many go around.
        loops: usize,
    },
    /// Boundary parameters that are not finite.
    #[error("parameters of the boundary are not finite")]
    NonFiniteParameters,
    /// A point the triangulation refused.
    #[error("cannot insert a {point}: {reason}")]
    Insert {
        /// Which point: `"boundary point"`, `"interior point"` or `"refinement point"`.
        point: &'static str,
        /// Why (the triangulation's words).
        reason: String,
    },
    /// No triangle left inside the loops.
    #[error("no triangle inside the face's loops")]
    NoTriangle,
}
