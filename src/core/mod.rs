//! Layer 0: identifiers and the names of tags, exact predicates, bounding boxes, tolerances
//! relative to the model's size, the [`SizeField`] trait and the [`BoundaryGeometry`] trait.
//! Nothing here knows about meshes or files.

pub mod aabb;
pub mod array_map;
pub mod boundary_geometry;
pub mod bucket_sort;
pub mod bvh;
pub mod closest;
pub(crate) mod cdt;
pub(crate) mod error_json;
pub mod ids;
pub mod intersection;
pub mod predicates;
pub mod size_field;
pub mod spatial_order;
pub mod tag_names;
pub mod tolerance;
pub(crate) mod union_find;

pub use aabb::Aabb;
pub use boundary_geometry::{BoundaryGeometry, Hint};
pub use ids::{FaceId, RegionId};
pub use predicates::Sign;
pub use size_field::SizeField;
pub use tag_names::{FaceNames, RegionNames, TagNames};
pub use tolerance::Tolerance;
