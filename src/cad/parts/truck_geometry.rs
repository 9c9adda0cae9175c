//! truck's geometry → ours, exact where the shape is a known one.
//!
//! truck represents circle arcs as rational quadratic B-splines, the side of a swept arc as a
//! rational B-spline surface and a revolved profile as a `RevolutedCurve`. These are
//! recognised here as the circles, cylinders, planes, spheres and tori they are (checked on
//! samples against a tolerance relative to the part's size); what is not recognised is kept
//! exactly as a (rational) B-spline or a surface of revolution.

use crate::cad::geom::{BSplineCurve, BSplineSurface, Circle, Curve, Cylinder, Frame, Interval, Line, Plane, Revolution, Sphere, Surface, Torus, TorusPart};
use super::GeometryError;
use glam::DVec3;
use std::f64::consts::TAU;
use truck_modeling::{
    BoundedCurve, ParametricCurve, ParametricSurface, ParametricSurface3D, Point3, Transformed, Vector3, Vector4,
};

/// A truck point as ours.
pub(super) fn p3(p: Point3) -> DVec3 {
    DVec3::new(p.x, p.y, p.z)
}

fn v3(v: Vector3) -> DVec3 {
    DVec3::new(v.x, v.y, v.z)
}

/// A curve of ours and the increasing parameter range the truck curve covers, from its front
/// point to its back point.
pub(super) struct ConvertedCurve {
    pub curve: Curve,
    pub range: Interval,
}

/// Samples of a curve over `[t0, t1]`.
fn samples(f: &dyn Fn(f64) -> DVec3, t0: f64, t1: f64, n: usize) -> Vec<DVec3> {
    (0..=n).map(|k| f(t0 + (t1 - t0) * k as f64 / n as f64)).collect()
}

/// The circle through the samples (first, middle and last define it), if every sample lies on
/// it within `tol`, with its frame's `x` towards the first sample and turning towards the
/// middle one, and the angle of the last sample in `(0, 2π]`.
fn circle_through(pts: &[DVec3], tol: f64) -> Option<(Circle, f64)> {
    let (p0, pm, p1) = (pts[0], pts[pts.len() / 2], pts[pts.len() - 1]);
    let (a, b) = (p0 - pm, p1 - pm);
    let axb = a.cross(b);
    let closed = (p1 - p0).length() <= tol;
    let centre = if closed {
        // a full turn: the first, a quarter and the middle sample
        let pq = pts[pts.len() / 4];
        let (a, b) = (pq - p0, pm - p0);
        let axb = a.cross(b);
        if axb.length_squared() == 0.0 {
            return None;
        }
        p0 + (a.length_squared() * b - b.length_squared() * a).cross(axb) / (2.0 * axb.length_squared())
    } else {
        if axb.length_squared() <= (tol * tol) * a.length_squared().max(b.length_squared()) {
            return None;
        }
        pm + (a.length_squared() * b - b.length_squared() * a).cross(axb) / (2.0 * axb.length_squared())
    };
    let radius = (p0 - centre).length();
    let z = (p0 - centre).cross(pm - centre).try_normalize()?;
    let x = (p0 - centre).try_normalize()?;
    let frame = Frame { origin: centre, x, y: z.cross(x), z };
    if pts.iter().any(|p| ((*p - centre).length() - radius).abs() > tol || (*p - centre).dot(z).abs() > tol) {
        return None;
    }
    let l = frame.to_local(p1);
    let mut end = l.y.atan2(l.x);
    if end <= 0.0 {
        end += TAU;
    }
    if closed {
        end = TAU;
    }
    Some((Circle { frame, radius }, end))
}

fn knots_of(k: &[f64]) -> Vec<f64> {
    k.to_vec()
}

/// A rational B-spline from truck's homogeneous control points `(w x, w y, w z, w)`.
fn rational(degree: usize, knots: &[f64], hom: &[Vector4]) -> Result<BSplineCurve, GeometryError> {
    let points = hom.iter().map(|h| DVec3::new(h.x / h.w, h.y / h.w, h.z / h.w)).collect();
    let weights = hom.iter().map(|h| h.w).collect();
    BSplineCurve::new(degree, knots_of(knots), points, Some(weights)).map_err(spline)
}

/// The B-spline constructors' reason as ours.
fn spline(why: impl std::fmt::Display) -> GeometryError {
    GeometryError::Spline { why: why.to_string() }
}

/// Converts a truck curve; `tol` is the distance within which a sampled shape is accepted.
pub(super) fn curve(c: &truck_modeling::Curve, tol: f64) -> Result<ConvertedCurve, GeometryError> {
    use truck_modeling::Curve as T;
    match c {
        T::Line(l) => {
            let (a, b) = (p3(l.0), p3(l.1));
            if (b - a).length() == 0.0 {
                return Err(GeometryError::ZeroLengthLine);
            }
            Ok(ConvertedCurve { curve: Curve::Line(Line { origin: a, direction: b - a }), range: Interval::new(0.0, 1.0) })
        }
        T::BSplineCurve(b) => {
            let (t0, t1) = b.range_tuple();
            let f = |t: f64| p3(b.subs(t));
            if let Some(c) = recognised_circle(&f, t0, t1, tol) {
                return Ok(c);
            }
            let points = b.control_points().iter().map(|p| p3(*p)).collect();
            let curve = BSplineCurve::new(b.degree(), knots_of(b.knot_vec()), points, None).map_err(spline)?;
            Ok(ConvertedCurve { curve: Curve::BSpline(curve), range: Interval::new(t0, t1) })
        }
        T::NurbsCurve(n) => {
            let (t0, t1) = n.range_tuple();
            let f = |t: f64| p3(n.subs(t));
            if let Some(c) = recognised_circle(&f, t0, t1, tol) {
                return Ok(c);
            }
            let curve = rational(n.degree(), n.knot_vec(), n.control_points())?;
            Ok(ConvertedCurve { curve: Curve::BSpline(curve), range: Interval::new(t0, t1) })
        }
        T::IntersectionCurve(_) => Err(GeometryError::IntersectionCurve),
    }
}

fn recognised_circle(f: &dyn Fn(f64) -> DVec3, t0: f64, t1: f64, tol: f64) -> Option<ConvertedCurve> {
    let pts = samples(f, t0, t1, 16);
    let (circle, end) = circle_through(&pts, tol)?;
    Some(ConvertedCurve { curve: Curve::Circle(circle), range: Interval::new(0.0, end) })
}

/// Converts a truck surface.
pub(super) fn surface(s: &truck_modeling::Surface, tol: f64) -> Result<Surface, GeometryError> {
    use truck_modeling::Surface as T;
    match s {
        T::Plane(p) => {
            let frame = Frame::from_axes(p3(p.origin()), Some(v3(p.normal())), Some(v3(p.u_axis()))).ok_or(GeometryError::DegeneratePlane)?;
            Ok(Surface::Plane(Plane { frame }))
        }
        T::RevolutedCurve(proc) => {
            let m = *proc.transform();
            let rc = proc.entity();
            let profile = rc.entity_curve().transformed(m);
            let origin = p3(truck_modeling::Transform::transform_point(&m, rc.origin()));
            let axis = v3(truck_modeling::Transform::transform_vector(&m, rc.axis())).try_normalize().ok_or(GeometryError::ZeroAxis)?;
            let profile = curve(&profile, tol)?;
            Ok(revolved(profile.curve, origin, axis, tol))
        }
        T::BSplineSurface(b) => {
            let (u, v) = b.try_range_tuple();
            let unbounded = GeometryError::Unbounded { surface: "B-spline surface" };
            let (u, v) = (u.ok_or(unbounded.clone())?, v.ok_or(unbounded)?);
            if let Some(s) = recognised(s, u, v, tol) {
                return Ok(s);
            }
            let (ku, kv) = b.knot_vecs();
            let cp = b.control_points();
            let (nu, nv) = (cp.len(), cp.first().map_or(0, Vec::len));
            let points = cp.iter().flatten().map(|p| p3(*p)).collect();
            let (du, dv) = b.degrees();
            Ok(Surface::BSpline(BSplineSurface::new(du, dv, knots_of(ku), knots_of(kv), nu, nv, points, None).map_err(spline)?))
        }
        T::NurbsSurface(n) => {
            let (u, v) = n.try_range_tuple();
            let unbounded = GeometryError::Unbounded { surface: "NURBS surface" };
            let (u, v) = (u.ok_or(unbounded.clone())?, v.ok_or(unbounded)?);
            if let Some(s) = recognised(s, u, v, tol) {
                return Ok(s);
            }
            let (ku, kv) = n.knot_vecs();
            let cp = n.control_points();
            let (nu, nv) = (cp.len(), cp.first().map_or(0, Vec::len));
            let points = cp.iter().flatten().map(|h| DVec3::new(h.x / h.w, h.y / h.w, h.z / h.w)).collect();
            let weights = cp.iter().flatten().map(|h| h.w).collect();
            let (du, dv) = n.degrees();
            Ok(Surface::BSpline(BSplineSurface::new(du, dv, knots_of(ku), knots_of(kv), nu, nv, points, Some(weights)).map_err(spline)?))
        }
    }
}

/// A profile turned about an axis: a cylinder (line parallel to the axis), a plane (line
/// across it), a sphere or torus (circle in a plane through the axis), else a surface of
/// revolution.
fn revolved(profile: Curve, origin: DVec3, axis: DVec3, tol: f64) -> Surface {
    let foot = |p: DVec3| origin + (p - origin).dot(axis) * axis;
    match &profile {
        Curve::Line(l) => {
            let d = l.direction.normalize();
            let radial = l.origin - foot(l.origin);
            if d.cross(axis).length() * l.direction.length() <= tol && radial.length() > tol {
                let x = radial.normalize();
                return Surface::Cylinder(Cylinder { frame: Frame { origin: foot(l.origin), x, y: axis.cross(x), z: axis }, radius: radial.length() });
            }
            if d.dot(axis).abs() * l.direction.length() <= tol {
                if let Some(frame) = Frame::from_axes(foot(l.origin), Some(axis), None) {
                    return Surface::Plane(Plane { frame });
                }
            }
        }
        Curve::Circle(c) => {
            let in_axis_plane = c.frame.z.dot(axis).abs() * c.radius <= tol && (origin - c.frame.origin).dot(c.frame.z).abs() <= tol;
            if in_axis_plane {
                let f = foot(c.frame.origin);
                let radial = c.frame.origin - f;
                if radial.length() <= tol {
                    if let Some(frame) = Frame::from_axes(c.frame.origin, Some(axis), None) {
                        return Surface::Sphere(Sphere { frame, radius: c.radius });
                    }
                } else {
                    let x = radial.normalize();
                    let frame = Frame { origin: f, x, y: axis.cross(x), z: axis };
                    return Surface::Torus(Torus { frame, major: radial.length(), minor: c.radius, part: TorusPart::Full });
                }
            }
        }
        _ => {}
    }
    match Revolution::new(profile, origin, axis) {
        Some(r) => Surface::Revolution(r),
        None => unreachable!("the axis was normalised above"),
    }
}

/// A plane or a cylinder fitted to a grid of samples and normals of `s`, if every sample
/// agrees within `tol`.
fn recognised(s: &truck_modeling::Surface, (u0, u1): (f64, f64), (v0, v1): (f64, f64), tol: f64) -> Option<Surface> {
    const N: usize = 6;
    let mut pts = Vec::new();
    let mut normals = Vec::new();
    for i in 0..=N {
        for j in 0..=N {
            let (u, v) = (u0 + (u1 - u0) * i as f64 / N as f64, v0 + (v1 - v0) * j as f64 / N as f64);
            pts.push(p3(s.subs(u, v)));
            normals.push(v3(s.normal(u, v)).try_normalize()?);
        }
    }
    let size = pts.iter().map(|p| (*p - pts[0]).length()).fold(0.0, f64::max).max(tol);
    let angle_tol = tol / size;
    // a plane: one normal, every point on it
    let n0 = normals[0];
    if normals.iter().all(|n| n.cross(n0).length() <= angle_tol) && pts.iter().all(|p| (*p - pts[0]).dot(n0).abs() <= tol) {
        return Frame::from_axes(pts[0], Some(n0), None).map(|frame| Surface::Plane(Plane { frame }));
    }
    // a cylinder: every normal across one axis, every point at one distance from it
    let k = (0..normals.len()).max_by(|&a, &b| n0.cross(normals[a]).length().total_cmp(&n0.cross(normals[b]).length()))?;
    let axis = n0.cross(normals[k]).try_normalize()?;
    if normals.iter().any(|n| n.dot(axis).abs() > angle_tol) {
        return None;
    }
    let dn = n0 - normals[k];
    let flat = |w: DVec3| w - w.dot(axis) * axis;
    let r = flat(pts[0] - pts[k]).dot(dn) / dn.length_squared();
    let centre = pts[0] - r * n0;
    let radius = r.abs();
    if pts.iter().any(|p| (flat(*p - centre).length() - radius).abs() > tol) {
        return None;
    }
    let x = flat(pts[0] - centre).try_normalize()?;
    Some(Surface::Cylinder(Cylinder { frame: Frame { origin: centre, x, y: axis.cross(x), z: axis }, radius }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use truck_modeling::builder;

    #[test]
    fn a_truck_arc_is_a_circle_and_its_sweep_a_cylinder() {
        let a = builder::vertex(Point3::new(2.0, 0.0, 0.0));
        let b = builder::vertex(Point3::new(-2.0, 0.0, 0.0));
        let arc = builder::circle_arc(&a, &b, Point3::new(0.0, 2.0, 0.0));
        let c = curve(&arc.curve(), 1e-9).unwrap();
        let Curve::Circle(circle) = c.curve else { panic!("not a circle: {:?}", c.curve) };
        assert!((circle.radius - 2.0).abs() < 1e-12 && circle.frame.origin.length() < 1e-12);
        assert!((c.range.max - std::f64::consts::PI).abs() < 1e-12);
        assert!((circle.point(c.range.max) - DVec3::new(-2.0, 0.0, 0.0)).length() < 1e-12);
        let face: truck_modeling::Face = builder::tsweep(&arc, Vector3::new(0.0, 0.0, 3.0));
        let Surface::Cylinder(cyl) = surface(&face.surface(), 1e-9).unwrap() else { panic!("not a cylinder") };
        assert!((cyl.radius - 2.0).abs() < 1e-9 && cyl.frame.z.cross(DVec3::Z).length() < 1e-9);
    }

    #[test]
    fn a_revolved_arc_is_a_torus() {
        let a = builder::vertex(Point3::new(5.0, 0.0, 1.0));
        let b = builder::vertex(Point3::new(5.0, 0.0, -1.0));
        let arc = builder::circle_arc(&a, &b, Point3::new(6.0, 0.0, 0.0));
        let shell = builder::rsweep(&arc, Point3::new(0.0, 0.0, 0.0), Vector3::unit_z(), truck_modeling::Rad(1.0));
        let Surface::Torus(t) = surface(&shell[0].surface(), 1e-9).unwrap() else { panic!("not a torus") };
        assert!((t.major - 5.0).abs() < 1e-9 && (t.minor - 1.0).abs() < 1e-9);
    }
}
