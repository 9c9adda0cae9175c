//! Quality measures of a single linear triangle, in space or in the plane.
//!
//! Definitions follow VTK/Verdict (Knupp et al., SAND2007-1751), with `a, b, c` the edge
//! lengths, `A` the area, `R` and `r` the circum- and inradius:
//!
//! | measure | definition | equilateral | degenerate |
//! |---|---|---|---|
//! | angles | interior angles in degrees | 60 | min 0, max 180 |
//! | aspect ratio | `h_max (a+b+c) / (4√3 A)` | 1 | `+∞` |
//! | radius ratio | `R / (2r) = abc (a+b+c) / (16 A²)` | 1 | `+∞` |
//! | scaled Jacobian | `(2/√3) · 2A / max(ab, bc, ca)` | 1 | 0 |
//! | edge ratio | `h_max / h_min` | 1 | `+∞` for a zero edge |
//!
//! In space the area and the scaled Jacobian are non-negative; in the plane
//! ([`tri_measures_2d`]) they carry the orientation's sign (negative for clockwise), as
//! Verdict's do against a surface normal. Angles are computed as `atan2(2A, u·v)`, which stays
//! accurate for needles and caps. A triangle with a zero-length edge or zero computed area
//! gets the degenerate values above; nothing returns `NaN` for finite input.

use glam::{DVec2, DVec3};

const SQRT3: f64 = 1.732_050_807_568_877_2;

/// All quality measures of one triangle. Angles are in degrees.
#[derive(Copy, Clone, Debug, PartialEq, serde::Serialize)]
pub struct TriMeasures {
    /// Area: non-negative in space, signed (positive counter-clockwise) in the plane.
    pub area: f64,
    /// Smallest interior angle (degrees).
    pub min_angle: f64,
    /// Largest interior angle (degrees).
    pub max_angle: f64,
    /// Verdict aspect ratio `h_max (a+b+c) / (4√3 A)`, 1 for equilateral.
    pub aspect_ratio: f64,
    /// Verdict radius ratio `R / (2r)`, 1 for equilateral.
    pub radius_ratio: f64,
    /// Verdict scaled Jacobian, 1 for equilateral; signed in the plane.
    pub scaled_jacobian: f64,
    /// Longest over shortest edge.
    pub edge_ratio: f64,
}

/// Shared evaluation from the edge lengths, the dot products at the corners and twice the
/// (signed) area.
fn from_parts(l: [f64; 3], dots: [f64; 3], area2: f64) -> TriMeasures {
    let lmin = l[0].min(l[1]).min(l[2]);
    let lmax = l[0].max(l[1]).max(l[2]);
    let per = l[0] + l[1] + l[2];
    let abs2 = area2.abs();
    let edge_ratio = if lmin == 0.0 { f64::INFINITY } else { lmax / lmin };
    if lmin == 0.0 || area2 == 0.0 || !area2.is_finite() {
        return TriMeasures {
            area: 0.0,
            min_angle: 0.0,
            max_angle: 180.0,
            aspect_ratio: f64::INFINITY,
            radius_ratio: f64::INFINITY,
            scaled_jacobian: 0.0,
            edge_ratio,
        };
    }
    let ang = dots.map(|d| abs2.atan2(d).to_degrees());
    let min_angle = ang[0].min(ang[1]).min(ang[2]);
    let max_angle = ang[0].max(ang[1]).max(ang[2]);
    let prod = (l[0] * l[1]).max(l[1] * l[2]).max(l[2] * l[0]);
    TriMeasures {
        area: 0.5 * area2,
        min_angle,
        max_angle,
        aspect_ratio: lmax * per / (2.0 * SQRT3 * abs2),
        radius_ratio: l[0] * l[1] * l[2] * per / (4.0 * abs2 * abs2),
        scaled_jacobian: (2.0 / SQRT3 * area2 / prod).clamp(-1.0, 1.0),
        edge_ratio,
    }
}

/// All measures of the triangle `p` in space (area and scaled Jacobian non-negative).
///
/// ```
/// use fepre::quality::tri_measures;
/// use glam::DVec3;
/// let m = tri_measures(&[DVec3::ZERO, DVec3::X, DVec3::new(0.5, 0.75f64.sqrt(), 0.0)]);
/// assert!((m.aspect_ratio - 1.0).abs() < 1e-12 && (m.min_angle - 60.0).abs() < 1e-12);
/// ```
pub fn tri_measures(p: &[DVec3; 3]) -> TriMeasures {
    let (u, v, w) = (p[1] - p[0], p[2] - p[1], p[0] - p[2]);
    let l = [u.length(), v.length(), w.length()];
    // corner k lies between the edge arriving and the edge leaving it
    let dots = [-(w.dot(u)), -(u.dot(v)), -(v.dot(w))];
    let area2 = u.cross(p[2] - p[0]).length();
    from_parts(l, dots, area2)
}

/// All measures of the triangle `p` in the plane (area and scaled Jacobian signed, positive
/// for counter-clockwise).
pub fn tri_measures_2d(p: &[DVec2; 3]) -> TriMeasures {
    let (u, v, w) = (p[1] - p[0], p[2] - p[1], p[0] - p[2]);
    let l = [u.length(), v.length(), w.length()];
    let dots = [-(w.dot(u)), -(u.dot(v)), -(v.dot(w))];
    let area2 = u.perp_dot(p[2] - p[0]);
    from_parts(l, dots, area2)
}

/// The three interior angles in degrees (at vertices 0, 1, 2), or `None` when the triangle has
/// a zero-length edge or zero computed area.
pub fn tri_angles(p: &[DVec3; 3]) -> Option<[f64; 3]> {
    let (u, v, w) = (p[1] - p[0], p[2] - p[1], p[0] - p[2]);
    let area2 = u.cross(p[2] - p[0]).length();
    if area2 == 0.0 || u == DVec3::ZERO || v == DVec3::ZERO || w == DVec3::ZERO || !area2.is_finite() {
        return None;
    }
    Some([-(w.dot(u)), -(u.dot(v)), -(v.dot(w))].map(|d| area2.atan2(d).to_degrees()))
}

/// Area of the triangle `p` in space.
pub fn tri_area(p: &[DVec3; 3]) -> f64 {
    0.5 * (p[1] - p[0]).cross(p[2] - p[0]).length()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * b.abs().max(1.0)
    }

    #[test]
    fn equilateral() {
        let p = [DVec3::ZERO, DVec3::X, DVec3::new(0.5, 0.75f64.sqrt(), 0.0)];
        let m = tri_measures(&p);
        for x in [m.aspect_ratio, m.radius_ratio, m.scaled_jacobian, m.edge_ratio] {
            assert!(close(x, 1.0, 1e-12), "{m:?}");
        }
        assert!(close(m.min_angle, 60.0, 1e-12) && close(m.max_angle, 60.0, 1e-12));
        assert!(close(m.area, 0.75f64.sqrt() / 2.0, 1e-15));
        let q = [DVec2::ZERO, DVec2::X, DVec2::new(0.5, 0.75f64.sqrt())];
        let m2 = tri_measures_2d(&q);
        assert!(close(m2.aspect_ratio, 1.0, 1e-12) && m2.area > 0.0);
        let m3 = tri_measures_2d(&[q[0], q[2], q[1]]);
        assert!(close(m3.scaled_jacobian, -1.0, 1e-12) && m3.area < 0.0 && close(m3.radius_ratio, 1.0, 1e-12));
        let a = tri_angles(&p).unwrap();
        assert!(a.iter().all(|x| close(*x, 60.0, 1e-12)));
    }

    #[test]
    fn right_isoceles() {
        let m = tri_measures(&[DVec3::ZERO, DVec3::X, DVec3::Y]);
        assert!(close(m.min_angle, 45.0, 1e-12) && close(m.max_angle, 90.0, 1e-12));
        let s2 = 2f64.sqrt();
        assert!(close(m.aspect_ratio, s2 * (2.0 + s2) / (4.0 * SQRT3 * 0.5), 1e-12));
        // R = √2/2, r = (2 - √2)/2
        assert!(close(m.radius_ratio, (s2 / 2.0) / (2.0 - s2), 1e-12));
        assert!(close(m.scaled_jacobian, 2.0 / SQRT3 / s2, 1e-12));
        assert!(close(m.edge_ratio, s2, 1e-12));
        assert!(close(tri_area(&[DVec3::ZERO, DVec3::X, DVec3::Y]), 0.5, 1e-15));
    }

    #[test]
    fn needle_and_cap_angles() {
        let m = tri_measures(&[DVec3::ZERO, DVec3::X, DVec3::new(0.5, 1e-9, 0.0)]);
        assert!(m.max_angle > 179.99 && m.min_angle < 1e-6 && m.min_angle > 0.0);
        let p = [DVec3::ZERO, DVec3::X, DVec3::new(1e6, 1.0, 0.0)];
        let m = tri_measures(&p);
        assert!(m.min_angle > 0.0 && m.max_angle < 180.0);
        let a = tri_angles(&p).unwrap();
        assert!(close(a[0] + a[1] + a[2], 180.0, 1e-12), "{a:?}");
    }

    #[test]
    fn degenerate_triangles() {
        let collinear = [DVec3::ZERO, DVec3::X, DVec3::X * 2.0];
        let coincident = [DVec3::ZERO, DVec3::X, DVec3::X];
        let point = [DVec3::ONE; 3];
        for p in [collinear, coincident, point] {
            let m = tri_measures(&p);
            assert_eq!((m.min_angle, m.max_angle, m.area, m.scaled_jacobian), (0.0, 180.0, 0.0, 0.0), "{p:?}");
            assert_eq!((m.aspect_ratio, m.radius_ratio), (f64::INFINITY, f64::INFINITY));
            assert!(!m.edge_ratio.is_nan());
            assert!(tri_angles(&p).is_none());
        }
        assert_eq!(tri_measures(&collinear).edge_ratio, 2.0);
        assert_eq!(tri_measures(&coincident).edge_ratio, f64::INFINITY);
        let m = tri_measures_2d(&[DVec2::ZERO, DVec2::X, DVec2::X * 3.0]);
        assert_eq!((m.min_angle, m.max_angle), (0.0, 180.0));
    }
}
