//! Layer 5: the FE model. A tagged tet mesh becomes nodes and C3D4 or C3D10 elements (boundary
//! mid nodes on the CAD geometry), node sets, element sets and element-face surfaces per named
//! group of CAD faces, ties between surfaces of solids that touch without sharing nodes,
//! materials, sections and steps with boundary conditions and loads. The
//! deck writers (`deck/`) write it; nothing here knows a file format.

pub(crate) mod build;
pub(crate) mod element;
pub(crate) mod geometry;
pub(crate) mod jacobian;
pub(crate) mod loads;
pub(crate) mod model;
pub(crate) mod quadratic;
pub(crate) mod restraint;
pub(crate) mod step;
pub(crate) mod ties;

pub use build::{Built, GroupSets, build_model};
pub use element::{ABAQUS_FACE_MIDS, ABAQUS_FACES, ElementKind, TET_EDGES, face_corners_outward, face_nodes_outward_quadratic};
pub use loads::{consistent_forces, surface_area};
pub use geometry::{BoundaryGeometry, BrepGeometry};
pub use model::{CurvingReport, ElementFace, FeModel, FeModelError, Material, Section, Tie};
pub use step::{Analysis, Bc, Load, Step};
pub use ties::{TieSummary, tie_contacts};
