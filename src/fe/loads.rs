//! Consistent nodal loads: a total force spread over an element-face surface as a uniform
//! traction, integrated against each face's shape functions on the face's actual (curved,
//! for C3D10) geometry. On a flat 3-node face each corner gets a third; on a flat 6-node face
//! the corners get nothing and each mid node a third, the textbook result.

use super::element::{ElementKind, face_corners_outward, face_nodes_outward_quadratic};
use super::model::{ElementFace, FeModel};
use glam::DVec3;
use std::collections::BTreeMap;

/// The 6-point rule of degree 4 on a triangle (Dunavant): barycentric points and weights that
/// sum to 1.
fn triangle_rule() -> [([f64; 3], f64); 6] {
    let (a1, b1, w1) = (0.108_103_018_168_070, 0.445_948_490_915_965, 0.223_381_589_678_011);
    let (a2, b2, w2) = (0.816_847_572_980_459, 0.091_576_213_509_771, 0.109_951_743_655_322);
    [([a1, b1, b1], w1), ([b1, a1, b1], w1), ([b1, b1, a1], w1), ([a2, b2, b2], w2), ([b2, a2, b2], w2), ([b2, b2, a2], w2)]
}

/// The local node indices of a face, outward: 3 corners, or 3 corners and 3 mid nodes.
pub fn face_nodes(kind: ElementKind, face: u8) -> Vec<usize> {
    match kind {
        ElementKind::C3D4 => face_corners_outward(face).to_vec(),
        ElementKind::C3D10 => face_nodes_outward_quadratic(face).to_vec(),
    }
}

/// `∫ N_i dA` for each node of one face (the face's nodes in [`face_nodes`] order), and the
/// face's area.
pub fn face_weights(points: &[DVec3]) -> (Vec<f64>, f64) {
    if points.len() == 3 {
        let a = 0.5 * (points[1] - points[0]).cross(points[2] - points[0]).length();
        return (vec![a / 3.0; 3], a);
    }
    let mut w = vec![0.0; 6];
    let mut area = 0.0;
    for (l, weight) in triangle_rule() {
        let n = [l[0] * (2.0 * l[0] - 1.0), l[1] * (2.0 * l[1] - 1.0), l[2] * (2.0 * l[2] - 1.0), 4.0 * l[0] * l[1], 4.0 * l[1] * l[2], 4.0 * l[2] * l[0]];
        // derivatives with respect to l1 and l2 (l0 = 1 - l1 - l2)
        let dl = |i: usize| -> [f64; 3] {
            // dN_i / d(l0, l1, l2)
            match i {
                0 => [4.0 * l[0] - 1.0, 0.0, 0.0],
                1 => [0.0, 4.0 * l[1] - 1.0, 0.0],
                2 => [0.0, 0.0, 4.0 * l[2] - 1.0],
                3 => [4.0 * l[1], 4.0 * l[0], 0.0],
                4 => [0.0, 4.0 * l[2], 4.0 * l[1]],
                _ => [4.0 * l[2], 0.0, 4.0 * l[0]],
            }
        };
        let (mut xs, mut xt) = (DVec3::ZERO, DVec3::ZERO);
        for (i, p) in points.iter().enumerate() {
            let d = dl(i);
            xs += *p * (d[1] - d[0]);
            xt += *p * (d[2] - d[0]);
        }
        // the reference triangle has area 1/2
        let da = 0.5 * weight * xs.cross(xt).length();
        area += da;
        for i in 0..6 {
            w[i] += n[i] * da;
        }
    }
    (w, area)
}

/// The area of a surface, integrated on the faces' geometry.
pub fn surface_area(m: &FeModel, faces: &[ElementFace]) -> f64 {
    faces.iter().map(|f| face_weights(&face_points(m, *f)).1).sum()
}

/// The positions of one element face's nodes, in [`face_nodes`] order.
pub fn face_points(m: &FeModel, f: ElementFace) -> Vec<DVec3> {
    let el = m.element(f.element as usize);
    face_nodes(m.kind, f.face).into_iter().map(|k| m.nodes[el[k] as usize]).collect()
}

/// The nodal forces that spread `total` over `faces` as a uniform traction: node and force,
/// nodes increasing; the forces sum to `total` up to rounding. Empty when the surface has no
/// area.
pub fn consistent_forces(m: &FeModel, faces: &[ElementFace], total: DVec3) -> Vec<(u32, DVec3)> {
    let mut weight: BTreeMap<u32, f64> = BTreeMap::new();
    let mut area = 0.0;
    for f in faces {
        let el = m.element(f.element as usize);
        let (w, a) = face_weights(&face_points(m, *f));
        area += a;
        for (k, wi) in face_nodes(m.kind, f.face).into_iter().zip(w) {
            *weight.entry(el[k]).or_default() += wi;
        }
    }
    if !(area > 0.0) {
        return Vec::new();
    }
    let t = total / area;
    // a flat 6-node face's corners get nothing: drop the rounding left of it
    let negligible = 1e-12 * area;
    weight.into_iter().filter(|(_, w)| w.abs() > negligible).map(|(v, w)| (v, t * w)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_flat_six_node_face_loads_its_mid_nodes_only() {
        let c = [DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0), DVec3::new(0.0, 2.0, 0.0)];
        let p = vec![c[0], c[1], c[2], (c[0] + c[1]) * 0.5, (c[1] + c[2]) * 0.5, (c[2] + c[0]) * 0.5];
        let (w, a) = face_weights(&p);
        assert!((a - 2.0).abs() < 1e-12);
        for (i, wi) in w.iter().enumerate() {
            let want = if i < 3 { 0.0 } else { 2.0 / 3.0 };
            assert!((wi - want).abs() < 1e-12, "node {i}: {wi}");
        }
    }

    #[test]
    fn a_curved_face_integrates_its_area() {
        // a 6-node triangle on the unit sphere's octant: area of the curved patch is more
        // than the flat triangle's and the weights sum to it
        let c = [DVec3::X, DVec3::Y, DVec3::Z];
        let mid = |a: DVec3, b: DVec3| (a + b).normalize();
        let p = vec![c[0], c[1], c[2], mid(c[0], c[1]), mid(c[1], c[2]), mid(c[2], c[0])];
        let (w, a) = face_weights(&p);
        let flat = 0.5 * (c[1] - c[0]).cross(c[2] - c[0]).length();
        assert!(a > flat && a < std::f64::consts::PI / 2.0, "{a}");
        assert!((w.iter().sum::<f64>() - a).abs() < 1e-12);
    }
}
