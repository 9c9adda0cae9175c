//! Layer 5: attributes attached to CAD faces through selectors. Today: selectors
//! ([`selector`]) evaluated on a part's face catalogue ([`catalogue`]), and density
//! ([`density`]), the one size field from CAD face to tet. Boundary conditions, loads and
//! materials will join them.

pub mod catalogue;
pub mod density;
pub mod selector;
mod source_tree;
pub mod values;

pub use catalogue::{FaceCatalogue, FaceInfo, FaceShape};
pub use density::{Density, DensityError, DensityField};
pub use selector::{SelectError, Selection, Selector};
