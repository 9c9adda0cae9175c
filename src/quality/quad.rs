//! Quality measures of a single planar quadrilateral (for [`crate::mesh::PlanarMesh`]).
//!
//! Definitions follow VTK/Verdict (Knupp et al., SAND2007-1751), for the corners `p0..p3` in
//! counter-clockwise order, edges `e_k = p_{k+1} − p_k` of lengths `L_k`, area `A`:
//!
//! | measure | definition | square | degenerate |
//! |---|---|---|---|
//! | angles | interior angles in degrees, reflex ones above 180 | 90 | min 0, max 180 |
//! | aspect ratio | `L_max (L_0+L_1+L_2+L_3) / (4 |A|)` | 1 | `+∞` |
//! | scaled Jacobian | `min_k (e_k × −e_{k−1}) / (L_k L_{k−1})` | 1 | 0 |
//! | edge ratio | `L_max / L_min` | 1 | `+∞` for a zero edge |
//!
//! The area is signed (positive counter-clockwise). The scaled Jacobian is negative at a
//! reflex corner and for a clockwise quad. A quad with a zero-length edge gets the degenerate
//! values; nothing returns `NaN` for finite input.

use glam::DVec2;

/// All quality measures of one quadrilateral. Angles are in degrees.
#[derive(Copy, Clone, Debug, PartialEq, serde::Serialize)]
pub struct QuadMeasures {
    /// Signed area (shoelace), positive for counter-clockwise corners.
    pub area: f64,
    /// Smallest interior angle (degrees).
    pub min_angle: f64,
    /// Largest interior angle (degrees); above 180 at a reflex corner.
    pub max_angle: f64,
    /// Verdict aspect ratio, 1 for a square.
    pub aspect_ratio: f64,
    /// Verdict scaled Jacobian (minimum over the corners), 1 for a rectangle.
    pub scaled_jacobian: f64,
    /// Longest over shortest edge.
    pub edge_ratio: f64,
}

/// The four interior angles in degrees (at corners 0..3), or `None` with a zero-length edge.
/// For counter-clockwise corners, a reflex corner's angle exceeds 180°.
pub fn quad_angles(p: &[DVec2; 4]) -> Option<[f64; 4]> {
    let e: [DVec2; 4] = std::array::from_fn(|k| p[(k + 1) % 4] - p[k]);
    if e.contains(&DVec2::ZERO) {
        return None;
    }
    Some(std::array::from_fn(|k| {
        let (next, prev) = (e[k], -e[(k + 3) % 4]);
        let a = next.perp_dot(prev).atan2(next.dot(prev)).to_degrees();
        if a < 0.0 { a + 360.0 } else { a }
    }))
}

/// All measures of the quadrilateral `p` (corners counter-clockwise for a positive area).
///
/// ```
/// use fepre::quality::quad_measures;
/// use glam::DVec2;
/// let m = quad_measures(&[DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y]);
/// assert_eq!((m.min_angle, m.max_angle, m.aspect_ratio, m.scaled_jacobian), (90.0, 90.0, 1.0, 1.0));
/// ```
pub fn quad_measures(p: &[DVec2; 4]) -> QuadMeasures {
    let e: [DVec2; 4] = std::array::from_fn(|k| p[(k + 1) % 4] - p[k]);
    let l = e.map(|v| v.length());
    let lmin = l.iter().copied().fold(f64::INFINITY, f64::min);
    let lmax = l.iter().copied().fold(0.0, f64::max);
    let area = 0.5 * (0..4).map(|k| p[k].perp_dot(p[(k + 1) % 4])).sum::<f64>();
    let edge_ratio = if lmin == 0.0 { f64::INFINITY } else { lmax / lmin };
    let angles = match quad_angles(p) {
        Some(a) if lmin > 0.0 => a,
        _ => {
            return QuadMeasures {
                area,
                min_angle: 0.0,
                max_angle: 180.0,
                aspect_ratio: f64::INFINITY,
                scaled_jacobian: 0.0,
                edge_ratio,
            };
        }
    };
    let min_angle = angles.iter().copied().fold(f64::INFINITY, f64::min);
    let max_angle = angles.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let scaled_jacobian = (0..4)
        .map(|k| {
            let j = (k + 3) % 4;
            e[k].perp_dot(-e[j]) / (l[k] * l[j])
        })
        .fold(f64::INFINITY, f64::min)
        .clamp(-1.0, 1.0);
    let per = l[0] + l[1] + l[2] + l[3];
    let aspect_ratio = if area == 0.0 { f64::INFINITY } else { lmax * per / (4.0 * area.abs()) };
    QuadMeasures { area, min_angle, max_angle, aspect_ratio, scaled_jacobian, edge_ratio }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * b.abs().max(1.0)
    }

    #[test]
    fn square_rectangle_rhombus() {
        let sq = [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y];
        let m = quad_measures(&sq);
        assert_eq!(m.area, 1.0);
        assert_eq!(m.edge_ratio, 1.0);
        let r = quad_measures(&sq.map(|p| p * DVec2::new(3.0, 1.0)));
        assert!(close(r.aspect_ratio, 3.0 * 8.0 / 12.0, 1e-15) && close(r.scaled_jacobian, 1.0, 1e-15));
        assert!(close(r.edge_ratio, 3.0, 1e-15));
        // rhombus with 60° and 120° corners
        let h = 0.75f64.sqrt();
        let rh = [DVec2::ZERO, DVec2::X, DVec2::new(1.5, h), DVec2::new(0.5, h)];
        let m = quad_measures(&rh);
        assert!(close(m.min_angle, 60.0, 1e-12) && close(m.max_angle, 120.0, 1e-12), "{m:?}");
        assert!(close(m.scaled_jacobian, h, 1e-12));
        assert!(close(m.aspect_ratio, 4.0 / (4.0 * h), 1e-12));
        let a = quad_angles(&rh).unwrap();
        assert!(close(a.iter().sum::<f64>(), 360.0, 1e-12));
    }

    #[test]
    fn reflex_and_clockwise() {
        let dart = [DVec2::ZERO, DVec2::new(2.0, 0.0), DVec2::new(0.5, 0.5), DVec2::new(0.0, 2.0)];
        let m = quad_measures(&dart);
        assert!(m.max_angle > 180.0 && m.scaled_jacobian < 0.0 && m.area > 0.0, "{m:?}");
        let a = quad_angles(&dart).unwrap();
        assert!(close(a.iter().sum::<f64>(), 360.0, 1e-12), "{a:?}");
        let cw = [DVec2::ZERO, DVec2::Y, DVec2::ONE, DVec2::X];
        let m = quad_measures(&cw);
        assert!(m.area < 0.0 && m.scaled_jacobian == -1.0 && m.aspect_ratio == 1.0);
    }

    #[test]
    fn degenerate_quads() {
        let collapsed = [DVec2::ZERO, DVec2::X, DVec2::X, DVec2::Y];
        let m = quad_measures(&collapsed);
        assert_eq!((m.min_angle, m.max_angle, m.scaled_jacobian), (0.0, 180.0, 0.0));
        assert_eq!((m.aspect_ratio, m.edge_ratio), (f64::INFINITY, f64::INFINITY));
        assert!(quad_angles(&collapsed).is_none());
        let flat = [DVec2::ZERO, DVec2::X, DVec2::X * 2.0, DVec2::X * 3.0];
        let m = quad_measures(&flat);
        assert_eq!(m.area, 0.0);
        assert_eq!(m.aspect_ratio, f64::INFINITY);
        assert!(!m.min_angle.is_nan() && !m.scaled_jacobian.is_nan());
    }
}
