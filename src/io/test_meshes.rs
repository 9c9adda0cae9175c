//! Small meshes shared by the format tests.

use crate::core::{FaceId, RegionId};
use crate::mesh::{TetMesh, TriSurface};
use glam::DVec3;

/// Two tets sharing a face, in regions 1 and 2, with their six hull faces as boundary tagged
/// 0, 1, 2, 0, 1, 2 (tag 0 included on purpose: some formats must map it).
pub(crate) fn two_tets() -> TetMesh {
    let mut m = TetMesh {
        vertices: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z, DVec3::new(1.0, 1.0, 1.0)],
        tets: vec![[0, 1, 2, 3], [1, 4, 2, 3]],
        region_tags: vec![RegionId(1), RegionId(2)],
        ..Default::default()
    };
    m.boundary = m.hull_faces();
    m.face_tags = (0..m.boundary.len() as u32).map(|i| FaceId(i % 3)).collect();
    m
}

/// The boundary of [`two_tets`] as a tagged surface over the same five vertices.
pub(crate) fn two_tets_surface() -> TriSurface {
    let m = two_tets();
    TriSurface { vertices: m.vertices, triangles: m.boundary, face_tags: m.face_tags, ..Default::default() }
}
