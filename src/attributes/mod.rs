//! Layer 5: attributes attached to CAD faces through selectors. Today: selectors
//! ([`selector`]) evaluated on a part's face catalogue ([`catalogue`]), and density
//! ([`density`]), the one size field from CAD face to tet. The selection is evaluated once,
//! into [`Groups`], which density and the FE model take. Boundary conditions, loads and
//! materials will join them.

pub mod catalogue;
pub mod density;
pub mod groups;
pub mod selector;
mod source_tree;
pub mod values;

pub use catalogue::{FaceCatalogue, FaceInfo, FaceShape};
pub use density::{Density, DensityError, DensityField};
pub use groups::Groups;
pub use selector::{SelectError, Selection, Selector};
