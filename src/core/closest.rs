//! The point of a triangle nearest to a point (after Ericson, "Real-Time Collision
//! Detection", 5.1.5: the Voronoi region of the closest feature), for the selectors' and
//! sizes' distances and the assembly checks; degenerate triangles fall back to their
//! nearest edge.

use glam::DVec3;

/// The distance from `p` to the triangle `t` (closest point by regions, after Ericson).
pub fn point_triangle_distance(p: DVec3, t: [DVec3; 3]) -> f64 {
    closest_point_on_triangle(p, t).distance(p)
}

/// The point of triangle `t` closest to `p`.
pub fn closest_point_on_triangle(p: DVec3, [a, b, c]: [DVec3; 3]) -> DVec3 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return a + v * ab;
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return a + w * ac;
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return b + w * (c - b);
    }
    let denom = va + vb + vc;
    if denom.abs() <= f64::MIN_POSITIVE || !denom.is_finite() {
        // degenerate triangle: the nearest of its edges
        let seg = |u: DVec3, v: DVec3| {
            let d = v - u;
            let s = if d.length_squared() > 0.0 { ((p - u).dot(d) / d.length_squared()).clamp(0.0, 1.0) } else { 0.0 };
            u + s * d
        };
        let cands = [seg(a, b), seg(b, c), seg(c, a)];
        return cands.into_iter().min_by(|x, y| x.distance_squared(p).total_cmp(&y.distance_squared(p))).unwrap_or(a);
    }
    let (v, w) = (vb / denom, vc / denom);
    a + ab * v + ac * w
}

/// The point of the segment `[a, b]` closest to `p` (`a` when the segment has zero length).
pub fn closest_point_on_segment(p: DVec3, a: DVec3, b: DVec3) -> DVec3 {
    let d = b - a;
    let l2 = d.length_squared();
    if l2 > 0.0 && l2.is_finite() { a + ((p - a).dot(d) / l2).clamp(0.0, 1.0) * d } else { a }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closest_points_of_every_region() {
        let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
        // inside the triangle the point comes from barycentric weights: equal up to rounding
        assert!(closest_point_on_triangle(DVec3::new(0.2, 0.2, 3.0), t).distance(DVec3::new(0.2, 0.2, 0.0)) < 1e-15);
        assert_eq!(closest_point_on_triangle(DVec3::new(-1.0, -1.0, 0.0), t), DVec3::ZERO);
        assert_eq!(closest_point_on_triangle(DVec3::new(2.0, -0.5, 0.0), t), DVec3::X);
        assert_eq!(closest_point_on_triangle(DVec3::new(0.5, -2.0, 1.0), t), DVec3::new(0.5, 0.0, 0.0));
        assert!((point_triangle_distance(DVec3::new(1.0, 1.0, 0.0), t) - 0.5f64.sqrt()).abs() < 1e-15);
    }

    #[test]
    fn segment_ends_and_middle() {
        let (a, b) = (DVec3::ZERO, DVec3::X);
        assert_eq!(closest_point_on_segment(DVec3::new(-1.0, 1.0, 0.0), a, b), a);
        assert_eq!(closest_point_on_segment(DVec3::new(2.0, 1.0, 0.0), a, b), b);
        assert_eq!(closest_point_on_segment(DVec3::new(0.25, 1.0, 3.0), a, b), DVec3::new(0.25, 0.0, 0.0));
        assert_eq!(closest_point_on_segment(DVec3::Y, a, a), a);
    }
}
