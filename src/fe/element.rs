//! Element kinds and their node and face numbering, written once: every deck writer, the
//! surface builder and the load integrator read it from here.
//!
//! Nodes are numbered as Abaqus and CalculiX number them (0-based here):
//! - C3D4: corners 0-3, positively oriented (`det[v1-v0, v2-v0, v3-v0] > 0`, the convention of
//!   [`crate::mesh::TetMesh`]).
//! - C3D10: the corners, then the mid-edge nodes of edges 0-1, 1-2, 2-0, 0-3, 1-3, 2-3 (VTK's
//!   quadratic tetra and Nastran's CTETRA with ten grids use the same order).
//!
//! Faces (Abaqus `S1`..`S4`, used by `*SURFACE, TYPE=ELEMENT` and `*DSLOAD`): `S1` = 1-2-3,
//! `S2` = 1-4-2, `S3` = 2-4-3, `S4` = 3-4-1 (1-based corners). Seen from outside, each runs
//! clockwise; [`face_corners_outward`] gives them counter-clockwise.

use serde::Serialize;

/// The element kinds fepre writes.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize)]
pub enum ElementKind {
    /// Linear tetrahedron, 4 nodes.
    C3D4,
    /// Quadratic tetrahedron, 10 nodes.
    C3D10,
}

impl ElementKind {
    /// Nodes per element.
    pub fn nodes(self) -> usize {
        match self {
            ElementKind::C3D4 => 4,
            ElementKind::C3D10 => 10,
        }
    }

    /// The name Abaqus and CalculiX use.
    pub fn name(self) -> &'static str {
        match self {
            ElementKind::C3D4 => "C3D4",
            ElementKind::C3D10 => "C3D10",
        }
    }

    /// The polynomial order: 1 or 2.
    pub fn order(self) -> u8 {
        match self {
            ElementKind::C3D4 => 1,
            ElementKind::C3D10 => 2,
        }
    }
}

/// The corners of each edge of a tet, in the order of the C3D10 mid-edge nodes 4..9.
pub const TET_EDGES: [[usize; 2]; 6] = [[0, 1], [1, 2], [2, 0], [0, 3], [1, 3], [2, 3]];

/// Abaqus faces `S1`..`S4` (index 0..3): their corners, 0-based, in Abaqus order.
pub const ABAQUS_FACES: [[usize; 3]; 4] = [[0, 1, 2], [0, 3, 1], [1, 3, 2], [2, 3, 0]];

/// The mid-edge nodes (indices 4..9 of a C3D10) of Abaqus face `S1`..`S4`, after its corners:
/// edge a-b, b-c, c-a of the corners in [`ABAQUS_FACES`] order.
pub const ABAQUS_FACE_MIDS: [[usize; 3]; 4] = [[4, 5, 6], [7, 8, 4], [8, 9, 5], [9, 7, 6]];

/// The Abaqus face (0-based: 0 is `S1`) opposite corner `k`.
pub const fn abaqus_face_opposite(k: usize) -> u8 {
    // S1 lacks corner 3, S2 corner 2, S3 corner 0, S4 corner 1
    [2, 3, 1, 0][k]
}

/// The corners of Abaqus face `face` (0-based), counter-clockwise seen from outside the
/// element (the outward normal by the right-hand rule).
pub fn face_corners_outward(face: u8) -> [usize; 3] {
    let [a, b, c] = ABAQUS_FACES[face as usize];
    [a, c, b]
}

/// The six nodes of Abaqus face `face` (0-based) as a 6-node triangle, counter-clockwise seen
/// from outside: corners a, b, c then the mid nodes of a-b, b-c, c-a.
pub fn face_nodes_outward_quadratic(face: u8) -> [usize; 6] {
    let [a, b, c] = ABAQUS_FACES[face as usize];
    let [ab, bc, ca] = ABAQUS_FACE_MIDS[face as usize];
    // reversed: a, c, b with mids a-c (= ca), c-b (= bc), b-a (= ab)
    [a, c, b, ca, bc, ab]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn faces_and_mid_nodes_agree() {
        for (f, corners) in ABAQUS_FACES.iter().enumerate() {
            // the face opposite the missing corner
            let missing = (0..4).find(|k| !corners.contains(k)).unwrap();
            assert_eq!(abaqus_face_opposite(missing) as usize, f);
            // each mid node of the face sits on the edge between consecutive corners
            for i in 0..3 {
                let (a, b) = (corners[i], corners[(i + 1) % 3]);
                let m = ABAQUS_FACE_MIDS[f][i];
                let e = TET_EDGES[m - 4];
                assert!((e[0] == a && e[1] == b) || (e[0] == b && e[1] == a), "face {f} mid {m}");
            }
        }
    }

    #[test]
    fn outward_faces_point_away_from_the_fourth_corner() {
        use glam::DVec3;
        let p = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
        assert!((p[1] - p[0]).cross(p[2] - p[0]).dot(p[3] - p[0]) > 0.0);
        for f in 0..4u8 {
            let [a, b, c] = face_corners_outward(f);
            let n = (p[b] - p[a]).cross(p[c] - p[a]);
            let missing = (0..4).find(|k| ![a, b, c].contains(k)).unwrap();
            assert!(n.dot(p[missing] - p[a]) < 0.0, "face S{}", f + 1);
        }
    }
}
