//! Boundary face tags of the octree mesh: each boundary triangle takes the tag of the input
//! triangle nearest to its centroid.
//!
//! Stage: after the stencils. Input: the input [`TriSurface`] and, per boundary triangle, the
//! input triangle nearest to its centroid, which the deviation's first sample of that
//! triangle finds ([`super::deviation::deviation`]). Output: one [`FaceId`] per boundary
//! triangle.
//!
//! # Invariants
//! - The nearest triangle is found by branch and bound on the input's BVH with the exact
//!   closest point distance ([`crate::core::closest`]), ties to the lower triangle index: the
//!   tags depend only on the input.

use crate::core::FaceId;
use crate::mesh::TriSurface;

/// The tag of each boundary triangle from the input triangle nearest to its centroid
/// ([`FaceId::UNTAGGED`] where there is none: an empty input).
pub fn tags_of(surface: &TriSurface, nearest: &[Option<u32>]) -> Vec<FaceId> {
    nearest.iter().map(|t| t.map_or(FaceId::UNTAGGED, |t| surface.face_tags[t as usize])).collect()
}
