//! Quality of a planar mesh, the same figures for every 2D method: angles, the Verdict
//! library's scaled Jacobian and aspect ratio, and element sizes against the size field.
//!
//! - Element size: the mean length of an element's edges; its ratio to the size field at
//!   the element's centroid is reported by quantiles (a method meshes "to the size" when
//!   the median ratio is near 1).
//! - Scaled Jacobian (Verdict): per corner, the cross product of the two edges leaving it
//!   over the product of their lengths; the element's value is the smallest over its corners,
//!   scaled for triangles by 2/√3 so that the equilateral triangle scores 1 (a square scores 1).
//! - Aspect ratio (Verdict): a triangle's longest edge times its perimeter over 4√3 times its
//!   area (1 for the equilateral triangle).

use crate::mesh::PlanarMesh;
use glam::DVec2;

/// Quality figures of a [`PlanarMesh`] (see the module docs).
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct Quality2d {
    /// Vertices.
    pub vertices: usize,
    /// Triangles.
    pub triangles: usize,
    /// Quadrilaterals.
    pub quads: usize,
    /// Sum of the elements' areas.
    pub area: f64,
    /// Smallest and largest corner angle over all elements, degrees.
    pub angle_range: [f64; 2],
    /// Triangles with a corner angle under 20° and 30°.
    pub triangles_under: [usize; 2],
    /// Smallest and median scaled Jacobian of the triangles (1 = equilateral).
    pub triangle_scaled_jacobian: [f64; 2],
    /// Largest and median aspect ratio of the triangles (1 = equilateral).
    pub triangle_aspect_ratio: [f64; 2],
    /// Smallest and median scaled Jacobian of the quads (1 = square).
    pub quad_scaled_jacobian: [f64; 2],
    /// Element size over the size field: 10 %, 50 % and 90 % quantiles.
    pub size_ratio: [f64; 3],
}

/// The corner angles of a polygon, degrees.
pub fn corner_angles(p: &[DVec2]) -> Vec<f64> {
    let n = p.len();
    (0..n).map(|i| {
        let (a, b) = (p[(i + n - 1) % n] - p[i], p[(i + 1) % n] - p[i]);
        b.perp_dot(a).atan2(b.dot(a)).to_degrees().abs()
    }).collect()
}

/// The smallest corner value of `cross(e_next, e_prev) / (|e_next| |e_prev|)` of a polygon
/// (counter-clockwise: positive when convex), unscaled.
pub fn min_corner_jacobian(p: &[DVec2]) -> f64 {
    let n = p.len();
    (0..n).map(|i| {
        let (a, b) = (p[(i + 1) % n] - p[i], p[(i + n - 1) % n] - p[i]);
        a.perp_dot(b) / (a.length() * b.length())
    }).fold(f64::INFINITY, f64::min)
}

/// The scaled Jacobian of a triangle (1 = equilateral).
pub fn triangle_scaled_jacobian(p: [DVec2; 3]) -> f64 {
    min_corner_jacobian(&p) * 2.0 / 3f64.sqrt()
}

/// The aspect ratio of a triangle (1 = equilateral).
pub fn triangle_aspect_ratio(p: [DVec2; 3]) -> f64 {
    let e = [p[0].distance(p[1]), p[1].distance(p[2]), p[2].distance(p[0])];
    let area = 0.5 * (p[1] - p[0]).perp_dot(p[2] - p[0]);
    let lmax = e[0].max(e[1]).max(e[2]);
    lmax * (e[0] + e[1] + e[2]) / (4.0 * 3f64.sqrt() * area)
}

fn median(v: &mut [f64]) -> f64 {
    quantile(v, 0.5)
}

/// The value at rank `round((n - 1) q)` of `v` in `total_cmp` order (a selection, not a sort).
fn quantile(v: &mut [f64], q: f64) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    let k = ((v.len() - 1) as f64 * q).round() as usize;
    *v.select_nth_unstable_by(k, f64::total_cmp).1
}

/// The angle between `a` and `b`, degrees.
fn angle(a: DVec2, b: DVec2) -> f64 {
    b.perp_dot(a).atan2(b.dot(a)).to_degrees().abs()
}

/// Corner angles compared without trigonometry: a corner's cosine (from its two edges) orders
/// the angles the other way round; the extreme corners' angles are taken exactly at the end,
/// and a cosine within rounding of a threshold's is settled by the angle itself.
struct Corners {
    /// The smallest angle's corner: its cosine and its edges.
    widest_cos: (f64, DVec2, DVec2),
    /// The largest angle's corner.
    narrowest_cos: (f64, DVec2, DVec2),
}

impl Corners {
    fn new() -> Corners {
        Corners { widest_cos: (f64::NEG_INFINITY, DVec2::ZERO, DVec2::ZERO), narrowest_cos: (f64::INFINITY, DVec2::ZERO, DVec2::ZERO) }
    }

    /// Takes one corner of edges `a`, `b`; its cosine.
    fn add(&mut self, a: DVec2, b: DVec2) -> f64 {
        let c = a.dot(b) / (a.length_squared() * b.length_squared()).sqrt();
        if c > self.widest_cos.0 {
            self.widest_cos = (c, a, b);
        }
        if c < self.narrowest_cos.0 {
            self.narrowest_cos = (c, a, b);
        }
        c
    }

    fn range(&self) -> [f64; 2] {
        if self.widest_cos.0.is_infinite() {
            return [f64::NAN, f64::NAN];
        }
        [angle(self.widest_cos.1, self.widest_cos.2), angle(self.narrowest_cos.1, self.narrowest_cos.2)]
    }
}

/// Whether the corner of edges `a`, `b` and cosine `c` is under `deg` degrees (cosine `cos_deg`).
fn under(c: f64, cos_deg: f64, a: DVec2, b: DVec2, deg: f64) -> bool {
    if (c - cos_deg).abs() > 1e-9 {
        c > cos_deg
    } else {
        angle(a, b) < deg
    }
}

/// Measures `mesh` against the size field `size` (see [`Quality2d`]).
pub fn measure(mesh: &PlanarMesh, size: &dyn Fn(DVec2) -> f64) -> Quality2d {
    let v = |i: u32| mesh.vertices[i as usize];
    let mut q = Quality2d { vertices: mesh.vertices.len(), triangles: mesh.triangles.len(), quads: mesh.quads.len(), ..Quality2d::default() };
    let mut ratios = Vec::with_capacity(mesh.triangles.len() + mesh.quads.len());
    let mut sj = Vec::with_capacity(mesh.triangles.len());
    let mut ar = Vec::with_capacity(mesh.triangles.len());
    let mut corners = Corners::new();
    let (cos20, cos30) = (20f64.to_radians().cos(), 30f64.to_radians().cos());
    for t in &mesh.triangles {
        let p = [v(t[0]), v(t[1]), v(t[2])];
        let e = [p[1] - p[0], p[2] - p[1], p[0] - p[2]];
        let l = [e[0].length(), e[1].length(), e[2].length()];
        let twice_area = e[0].perp_dot(-e[2]);
        q.area += 0.5 * twice_area;
        let perimeter = l[0] + l[1] + l[2];
        ratios.push(perimeter / 3.0 / size((p[0] + p[1] + p[2]) / 3.0));
        // the smallest angle is at the corner of the largest cosine
        let mut worst = (f64::NEG_INFINITY, DVec2::ZERO, DVec2::ZERO);
        for k in 0..3 {
            let (a, b) = (e[k], -e[(k + 2) % 3]);
            let c = corners.add(a, b);
            if c > worst.0 {
                worst = (c, a, b);
            }
        }
        if under(worst.0, cos20, worst.1, worst.2, 20.0) {
            q.triangles_under[0] += 1;
        }
        if under(worst.0, cos30, worst.1, worst.2, 30.0) {
            q.triangles_under[1] += 1;
        }
        // Verdict: the smallest corner sine (twice the area over the two edges' lengths)
        let sine = (twice_area / (l[0] * l[2])).min(twice_area / (l[0] * l[1])).min(twice_area / (l[1] * l[2]));
        sj.push(sine * 2.0 / 3f64.sqrt());
        let lmax = l[0].max(l[1]).max(l[2]);
        ar.push(lmax * perimeter / (4.0 * 3f64.sqrt() * 0.5 * twice_area));
    }
    let mut qsj = Vec::with_capacity(mesh.quads.len());
    for quad in &mesh.quads {
        let p = [v(quad[0]), v(quad[1]), v(quad[2]), v(quad[3])];
        let mut perimeter = 0.0;
        let mut twice_area = 0.0;
        for i in 0..4 {
            perimeter += p[i].distance(p[(i + 1) % 4]);
            twice_area += p[i].perp_dot(p[(i + 1) % 4]);
            corners.add(p[(i + 3) % 4] - p[i], p[(i + 1) % 4] - p[i]);
        }
        q.area += 0.5 * twice_area;
        ratios.push(perimeter / 4.0 / size(p.iter().copied().sum::<DVec2>() / 4.0));
        qsj.push(min_corner_jacobian(&p));
    }
    q.angle_range = corners.range();
    let min = |v: &[f64]| v.iter().copied().fold(f64::NAN, f64::min);
    let max = |v: &[f64]| v.iter().copied().fold(f64::NAN, f64::max);
    q.triangle_scaled_jacobian = [min(&sj), median(&mut sj)];
    q.triangle_aspect_ratio = [max(&ar), median(&mut ar)];
    q.quad_scaled_jacobian = [min(&qsj), median(&mut qsj)];
    q.size_ratio = [quantile(&mut ratios, 0.1), quantile(&mut ratios, 0.5), quantile(&mut ratios, 0.9)];
    q
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::RegionId;

    #[test]
    fn equilateral_and_square_score_one() {
        let s = 3f64.sqrt() / 2.0;
        let t = [DVec2::ZERO, DVec2::X, DVec2::new(0.5, s)];
        assert!((triangle_scaled_jacobian(t) - 1.0).abs() < 1e-12);
        assert!((triangle_aspect_ratio(t) - 1.0).abs() < 1e-12);
        assert!((min_corner_jacobian(&[DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y]) - 1.0).abs() < 1e-12);
        let a = corner_angles(&t);
        assert!(a.iter().all(|x| (x - 60.0).abs() < 1e-9), "{a:?}");
    }

    #[test]
    fn measure_counts_and_sizes() {
        let mesh = PlanarMesh {
            vertices: vec![DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y, DVec2::new(2.0, 0.0)],
            triangles: vec![[1, 4, 2]],
            triangle_tags: vec![RegionId(1)],
            quads: vec![[0, 1, 2, 3]],
            quad_tags: vec![RegionId(1)],
            region_names: Default::default(),
        };
        let q = measure(&mesh, &|_| 1.0);
        assert_eq!((q.triangles, q.quads, q.vertices), (1, 1, 5));
        assert!((q.area - 1.5).abs() < 1e-12);
        assert!((q.angle_range[0] - 45.0).abs() < 1e-9 && (q.angle_range[1] - 90.0).abs() < 1e-9);
        assert_eq!(q.triangles_under, [0, 0]);
        assert!((q.quad_scaled_jacobian[0] - 1.0).abs() < 1e-12);
        assert!((q.size_ratio[0] - 1.0).abs() < 1e-12, "{:?}", q.size_ratio);
    }
}
