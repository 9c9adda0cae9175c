//! Layer 1: the mesh containers that cross stage boundaries, each with a `validate()` that
//! names the offending element, plus derived topology (the surface report).
//!
//! Containers hold flat arrays (`f64` coordinates, `u32` indices) and parallel tag arrays;
//! adjacency is derived on demand, never stored.

pub(crate) mod caps;
pub(crate) mod narrow;
pub(crate) mod error;
pub(crate) mod mixed_surface;
pub(crate) mod planar_mesh;
pub mod shapes;
pub(crate) mod tet_mesh;
pub mod topology;
pub(crate) mod tri_surface;
pub(crate) mod weld;

pub use error::{Element, MeshError};
pub use mixed_surface::MixedSurface;
pub use planar_mesh::PlanarMesh;
pub use tet_mesh::TetMesh;
pub use tri_surface::TriSurface;
