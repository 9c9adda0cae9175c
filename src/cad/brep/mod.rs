//! The B-rep as an index arena: solids → shells → faces → loops → coedges → edges → vertices,
//! with the surfaces and curves of [`crate::cad::geom`] in a model frame in millimetres.
//!
//! Invariants the STEP reader guarantees: every index points into its array; a face's first
//! loop is its outer loop when the file marks one; an edge's `range` is increasing and lies in
//! its curve's domain, running from `start` to `end` when `same_sense` (from `end` to `start`
//! otherwise); assembly instances are expanded (each placed copy has its own faces, edges and
//! vertices, in world coordinates). Items the reader could not convert are listed in
//! [`Model::dropped`], never left out silently.

mod append;
mod edge_flags;
mod entity_ref;
mod face_table;
mod model;
mod sew;
mod sew_report;
mod summary;
mod validate;

pub use entity_ref::EntityRef;
pub use model::{Coedge, Dropped, Edge, Face, Loop, Model, Shell, Solid, Units, Vertex};
pub use edge_flags::DEGENERATE_RELATIVE;
pub use face_table::{FaceEntry, face_table_of_names};
pub use sew::SEW_RELATIVE;
pub use sew_report::{EdgeSplit, Hole, SewReport};
pub use summary::Summary;
pub use validate::VERTEX_ON_CURVE_RELATIVE;
