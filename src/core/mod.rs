//! Layer 0: identifiers and the names of tags, exact predicates, bounding boxes, tolerances
//! relative to the model's size, the [`SizeField`] trait and the [`BoundaryGeometry`] trait.
//! Nothing here knows about meshes or files.

pub(crate) mod aabb;
pub(crate) mod array_map;
pub(crate) mod boundary_geometry;
pub(crate) mod bucket_sort;
pub(crate) mod bvh;
pub(crate) mod closest;
pub(crate) mod cdt;
pub(crate) mod error_json;
pub(crate) mod ids;
pub(crate) mod intersection;
pub mod predicates;
pub(crate) mod size_field;
pub(crate) mod spatial_order;
pub(crate) mod tag_names;
pub(crate) mod tolerance;
pub(crate) mod union_find;

pub use aabb::Aabb;
pub use boundary_geometry::{BoundaryGeometry, Hint};
pub use ids::{FaceId, RegionId};
pub use predicates::Sign;
pub use size_field::SizeField;
pub use tag_names::{FaceNames, RegionNames, TagNames, make_unique};
pub use tolerance::Tolerance;
pub use intersection::{SegmentCrossing, segment_crosses_triangle, segment_meets_triangle, segments_meet_2d, triangle_pair_intersects, triangles_meet};
pub use closest::{closest_point_on_triangle, point_triangle_distance};
pub use size_field::UniformSize;
