//! Contact between solids: the area over which two facing triangles of different solids lie
//! within the gap of each other, summed per pair of faces.
//!
//! Two triangles *face* each other when their outward normals are within 60° of opposite
//! (`na · nb ≤ -1/2`): the tessellations of one curved contact surface seen from its two
//! solids differ by their chords, so their normals differ by up to twice the tessellator's
//! angle. Their contact is measured in the plane whose normal `n` bisects `na` and `-nb`:
//! both triangles are projected onto it, their overlap is clipped (convex polygons), and the
//! part where the two triangles' heights along `n` differ by at most the gap is kept: the
//! height difference is linear over the plane, so that is two more half-plane clips. Over a
//! contact the two tessellations' triangles overlay each other once, so the pieces add up to
//! the contact's area (exactly for coincident plane faces).

use glam::{DVec2, DVec3};

/// Largest `na · nb` of two facing triangles.
pub(crate) const FACING_DOT: f64 = -0.5;

/// The area over which triangle `a` (outward normal `na`) and triangle `b` (`nb`) face each
/// other within `gap`; 0 unless they face each other.
pub(crate) fn facing_area(a: [DVec3; 3], na: DVec3, b: [DVec3; 3], nb: DVec3, gap: f64) -> f64 {
    if na.dot(nb) > FACING_DOT {
        return 0.0;
    }
    let n = (na - nb).normalize();
    let u = n.any_orthonormal_vector();
    let v = n.cross(u);
    let flat = |p: DVec3| DVec2::new(p.dot(u), p.dot(v));
    let pa = ccw(a.map(flat));
    let pb = ccw(b.map(flat));
    let mut poly: Vec<DVec2> = pa.to_vec();
    for k in 0..3 {
        let (p, q) = (pb[k], pb[(k + 1) % 3]);
        // keep the left side of p -> q
        poly = clip(&poly, |x| (q - p).perp_dot(x - p));
        if poly.len() < 3 {
            return 0.0;
        }
    }
    // height along n of the point of a triangle's plane above x: h(x) = (na·a0 - na·(x_u u + x_v v)) / (na·n)
    let height = |t: &[DVec3; 3], nt: DVec3| {
        let den = nt.dot(n);
        let c0 = nt.dot(t[0]) / den;
        let (cu, cv) = (-nt.dot(u) / den, -nt.dot(v) / den);
        move |x: DVec2| c0 + cu * x.x + cv * x.y
    };
    let (ha, hb) = (height(&a, na), height(&b, nb));
    poly = clip(&poly, |x| gap - (ha(x) - hb(x)));
    if poly.len() < 3 {
        return 0.0;
    }
    poly = clip(&poly, |x| gap + (ha(x) - hb(x)));
    area(&poly)
}

/// The triangle counter-clockwise.
fn ccw(t: [DVec2; 3]) -> [DVec2; 3] {
    if (t[1] - t[0]).perp_dot(t[2] - t[0]) < 0.0 { [t[0], t[2], t[1]] } else { t }
}

/// The part of the convex polygon `poly` where `f ≥ 0` (`f` affine): Sutherland–Hodgman
/// against one half-plane.
fn clip(poly: &[DVec2], f: impl Fn(DVec2) -> f64) -> Vec<DVec2> {
    let mut out = Vec::with_capacity(poly.len() + 1);
    for k in 0..poly.len() {
        let (p, q) = (poly[k], poly[(k + 1) % poly.len()]);
        let (fp, fq) = (f(p), f(q));
        if fp >= 0.0 {
            out.push(p);
        }
        if (fp >= 0.0) != (fq >= 0.0) {
            out.push(p + (q - p) * (fp / (fp - fq)));
        }
    }
    out
}

/// The area of a simple polygon (shoelace, absolute).
fn area(poly: &[DVec2]) -> f64 {
    let mut s = 0.0;
    for k in 0..poly.len() {
        s += poly[k].perp_dot(poly[(k + 1) % poly.len()]);
    }
    0.5 * s.abs()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn normal(t: [DVec3; 3]) -> DVec3 {
        (t[1] - t[0]).cross(t[2] - t[0]).normalize()
    }

    #[test]
    fn coincident_faces_touch_over_their_overlap() {
        // a: the lower-left half of the unit square in z = 0, outward -z (the top of a solid
        // below would be +z: here a is the bottom face of the solid above)
        let a = [DVec3::ZERO, DVec3::Y, DVec3::X];
        let b = [DVec3::ZERO, DVec3::X, DVec3::Y];
        assert!((facing_area(a, normal(a), b, normal(b), 1e-9) - 0.5).abs() < 1e-12);
        // b shifted by half along x: overlap is a triangle of legs 0.5
        let b2 = b.map(|p| p + DVec3::new(0.5, 0.0, 0.0));
        assert!((facing_area(a, normal(a), b2, normal(b2), 1e-9) - 0.125).abs() < 1e-12);
    }

    #[test]
    fn a_gap_wider_than_allowed_is_no_contact_and_same_side_faces_are_none() {
        let a = [DVec3::ZERO, DVec3::Y, DVec3::X];
        let b = [DVec3::ZERO, DVec3::X, DVec3::Y].map(|p| p - DVec3::Z * 0.1);
        assert_eq!(facing_area(a, normal(a), b, normal(b), 0.05), 0.0);
        assert!((facing_area(a, normal(a), b, normal(b), 0.2) - 0.5).abs() < 1e-12);
        assert_eq!(facing_area(a, normal(a), a, normal(a), 0.2), 0.0);
    }

    #[test]
    fn a_tilted_face_touches_where_it_is_close() {
        // b rises from 0 at x = 0 to 1 at x = 1: within 0.25 of a for x <= 0.25
        let a = [DVec3::ZERO, DVec3::Y, DVec3::X];
        let b = [DVec3::ZERO, DVec3::new(1.0, 0.0, 1.0), DVec3::Y];
        let got = facing_area(a, normal(a), b, normal(b), 0.25);
        // the strip x <= h(x) <= 0.25 measured in the bisecting plane: close to the part of a
        // with x <= 0.25 (0.25 - 0.25^2 / 2 = 0.21875), a little more for the tilt
        assert!(got > 0.2 && got < 0.26, "{got}");
    }
}
