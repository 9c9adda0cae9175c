//! Layer 5: attributes attached to CAD faces through selectors. Today: selectors
//! (`selector`) evaluated on a part's face catalogue (`catalogue`), and density
//! (`density`), the one size field from CAD face to tet. The selection is evaluated once,
//! into [`Groups`], which density and the FE model take. Boundary conditions, loads and
//! materials will join them.

pub(crate) mod catalogue;
pub(crate) mod density;
pub(crate) mod groups;
pub(crate) mod selector;
mod source_tree;
pub(crate) mod values;

pub use catalogue::{FaceCatalogue, FaceInfo, FaceShape};
pub use density::{BoxSize, DEFAULT_GRADING, Density, DensityError, DensityField, DistanceSize, FaceSize, Fraction, Grading, PointSize, RegionSizes};
pub use groups::Groups;
pub use selector::{Colour, CylinderSelector, Extreme, PlaneSelector, SelectError, Selection, Selector, SolidRef, glob};
pub use values::{BoxError, BoxSpec, Direction, NonNegative, Positive};
