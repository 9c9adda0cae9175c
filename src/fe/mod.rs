//! Layer 5: the FE model. A tagged tet mesh becomes nodes and C3D4 or C3D10 elements (boundary
//! mid nodes on the CAD geometry), node sets, element sets and element-face surfaces per named
//! group of CAD faces, ties between surfaces of solids that touch without sharing nodes,
//! materials, sections and steps with boundary conditions and loads. The
//! deck writers (`deck/`) write it; nothing here knows a file format.

pub mod build;
pub mod element;
pub mod geometry;
pub mod jacobian;
pub mod loads;
pub mod model;
pub mod quadratic;
pub mod restraint;
pub mod step;
pub mod ties;

pub use build::{Built, GroupSets, build_model};
pub use element::ElementKind;
pub use geometry::{BoundaryGeometry, BrepGeometry};
pub use model::{CurvingReport, ElementFace, FeModel, FeModelError, Material, Section, Tie};
pub use step::{Analysis, Bc, Load, Step};
pub use ties::{TieSummary, tie_contacts};
