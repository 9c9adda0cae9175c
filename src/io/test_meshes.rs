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

/// Two tets touching along a face without sharing its nodes (a non-conforming contact), in
/// regions 1 and 2: the touching faces are tagged 10 (region 1) and 20 (region 2), the other
/// faces 1 and 2 after their region.
pub(crate) fn touching_tets() -> TetMesh {
    let (x, y, z) = (DVec3::X, DVec3::Y, DVec3::Z);
    let mut m = TetMesh {
        vertices: vec![DVec3::ZERO, x, y, z, x, y, z, DVec3::new(1.0, 1.0, 1.0)],
        tets: vec![[0, 1, 2, 3], [4, 7, 5, 6]],
        region_tags: vec![RegionId(1), RegionId(2)],
        ..Default::default()
    };
    m.boundary = m.hull_faces();
    m.face_tags = m
        .boundary
        .iter()
        .map(|t| match (t.iter().all(|v| (1..4).contains(v)), t.iter().all(|v| (4..7).contains(v)), t.iter().all(|&v| v < 4)) {
            (true, _, _) => FaceId(10),
            (_, true, _) => FaceId(20),
            (_, _, true) => FaceId(1),
            _ => FaceId(2),
        })
        .collect();
    m
}

/// The boundary of [`two_tets`] as a tagged surface over the same five vertices.
pub(crate) fn two_tets_surface() -> TriSurface {
    let m = two_tets();
    TriSurface { vertices: m.vertices, triangles: m.boundary, face_tags: m.face_tags, ..Default::default() }
}
