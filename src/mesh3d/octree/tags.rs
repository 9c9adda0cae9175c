//! Boundary face tags of the octree mesh: each boundary triangle takes the tag of the input
//! triangle nearest to its centroid.
//!
//! Stage: after the stencils. Input: the input [`TriSurface`], the BVH over its triangles
//! (item `t` is triangle `t`), the [`TetMesh`] with its `boundary`. Output: one [`FaceId`]
//! per boundary triangle.
//!
//! # Invariants
//! - The nearest triangle is found by branch and bound on the BVH with the exact closest
//!   point distance ([`crate::core::closest`]), ties to the lower triangle index: the tags
//!   depend only on the input, computed in parallel and collected in order.

use crate::core::FaceId;
use crate::core::bvh::Bvh;
use crate::core::closest::point_triangle_distance;
use crate::mesh::{TetMesh, TriSurface};
use glam::DVec3;
use rayon::prelude::*;

/// The tag of the input triangle nearest to each boundary triangle's centroid.
pub fn nearest_tags(surface: &TriSurface, bvh: &Bvh, mesh: &TetMesh) -> Vec<FaceId> {
    mesh.boundary
        .par_iter()
        .map(|t| {
            let c = t.iter().map(|&v| mesh.vertices[v as usize]).sum::<DVec3>() / 3.0;
            nearest(surface, bvh, c).map_or(FaceId::UNTAGGED, |(tri, _)| surface.face_tags[tri as usize])
        })
        .collect()
}

/// The input triangle nearest to `p` and its distance.
pub fn nearest(surface: &TriSurface, bvh: &Bvh, p: DVec3) -> Option<(u32, f64)> {
    bvh.nearest(p, |t| point_triangle_distance(p, surface.corners(t as usize)))
}
