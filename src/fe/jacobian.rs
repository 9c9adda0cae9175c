//! The Jacobian of a tet element's map from the reference tet, checked at the 4-point Gauss
//! rule's points (where a solver integrates), the corners and the centroid.
//!
//! Barycentric coordinates `L0..L3` with `L1 = ξ`, `L2 = η`, `L3 = ζ`, `L0 = 1 - ξ - η - ζ`.
//! Shape functions of the C3D10: corner `i`: `L_i (2 L_i - 1)`; mid node of edge `a-b`:
//! `4 L_a L_b` (edges in [`TET_EDGES`] order). For a straight element the determinant is
//! `det[v1-v0, v2-v0, v3-v0]` = 6 × volume everywhere.

use super::element::TET_EDGES;
use glam::DVec3;

/// The 4-point Gauss rule's points on the reference tet, as barycentric coordinates.
pub fn gauss_points() -> [[f64; 4]; 4] {
    let a = 0.585_410_196_624_968_5;
    let b = 0.138_196_601_125_010_5;
    [[a, b, b, b], [b, a, b, b], [b, b, a, b], [b, b, b, a]]
}

/// The points where [`min_jacobian`] checks: the Gauss points, the corners, the centroid.
pub fn check_points() -> Vec<[f64; 4]> {
    let mut p: Vec<[f64; 4]> = gauss_points().to_vec();
    for k in 0..4 {
        let mut l = [0.0; 4];
        l[k] = 1.0;
        p.push(l);
    }
    p.push([0.25; 4]);
    p
}

/// The Jacobian determinant at barycentric point `l` of a tet with 4 or 10 nodes.
pub fn jacobian_at(points: &[DVec3], l: [f64; 4]) -> f64 {
    // dX/dL_k for each barycentric coordinate, then dX/dξ_k = dX/dL_k - dX/dL_0
    let mut d = [DVec3::ZERO; 4];
    if points.len() == 10 {
        for i in 0..4 {
            d[i] += points[i] * (4.0 * l[i] - 1.0);
        }
        for (m, &[a, b]) in TET_EDGES.iter().enumerate() {
            d[a] += points[4 + m] * (4.0 * l[b]);
            d[b] += points[4 + m] * (4.0 * l[a]);
        }
    } else {
        d[..4].copy_from_slice(&points[..4]);
    }
    let (x, y, z) = (d[1] - d[0], d[2] - d[0], d[3] - d[0]);
    x.dot(y.cross(z))
}

/// The smallest Jacobian determinant over [`check_points`].
pub fn min_jacobian(points: &[DVec3]) -> f64 {
    check_points().into_iter().map(|l| jacobian_at(points, l)).fold(f64::INFINITY, f64::min)
}

/// [`min_jacobian`] over the straight element's determinant (1 for a straight element, at
/// most 0 for an inverted one); 0 for a flat corner tet.
pub fn min_jacobian_ratio(points: &[DVec3]) -> f64 {
    let straight = jacobian_at(&points[..4], [0.25; 4]);
    if straight > 0.0 { min_jacobian(points) / straight } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quadratic(c: [DVec3; 4]) -> Vec<DVec3> {
        let mut p = c.to_vec();
        p.extend(TET_EDGES.iter().map(|&[a, b]| (c[a] + c[b]) * 0.5));
        p
    }

    #[test]
    fn a_straight_element_has_six_times_its_volume_everywhere() {
        let c = [DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0), DVec3::new(0.0, 3.0, 0.0), DVec3::new(0.0, 0.0, 4.0)];
        let q = quadratic(c);
        for l in check_points() {
            assert!((jacobian_at(&q, l) - 24.0).abs() < 1e-12);
            assert!((jacobian_at(&c, l) - 24.0).abs() < 1e-12);
        }
        assert!((min_jacobian_ratio(&q) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_mid_node_pushed_past_the_opposite_face_inverts_the_element() {
        let c = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
        let mut q = quadratic(c);
        // the mid node of edge 0-1 moved a little outward: still valid
        q[4] += DVec3::new(0.0, -0.05, -0.05);
        assert!(min_jacobian(&q) > 0.0);
        // moved far inward, past the centroid: inverted near a corner
        q[4] = DVec3::new(0.5, 0.6, 0.6);
        assert!(min_jacobian(&q) < 0.0);
        assert!(min_jacobian_ratio(&q) < 0.0);
    }
}
