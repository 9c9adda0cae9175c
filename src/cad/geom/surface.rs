//! The surface kinds of a B-rep face, behind one enum: evaluation, normals, natural domains
//! and the inverse `project(p) -> (u, v)` the tessellator maps edge points with.

use super::bspline_surface::BSplineSurface;
use super::cone::Cone;
use super::cylinder::Cylinder;
use super::derivs::SurfaceDerivs;
use super::domain::{SurfaceDomain, unwrap_near};
use super::extrusion::Extrusion;
use super::frame::Rigid;
use super::newton::{refine_surface, refine_surface_within};
use super::plane::Plane;
use super::revolution::Revolution;
use super::sphere::Sphere;
use super::torus::{Torus, TorusPart};
use super::similarity::Similarity;
use glam::{DVec2, DVec3};
use std::fmt;

/// A surface in millimetres, in the model frame.
#[derive(Clone, Debug)]
pub enum Surface {
    /// `PLANE`.
    Plane(Plane),
    /// `CYLINDRICAL_SURFACE`.
    Cylinder(Cylinder),
    /// `CONICAL_SURFACE`.
    Cone(Cone),
    /// `SPHERICAL_SURFACE`.
    Sphere(Sphere),
    /// `TOROIDAL_SURFACE` and `DEGENERATE_TOROIDAL_SURFACE`.
    Torus(Torus),
    /// `B_SPLINE_SURFACE_WITH_KNOTS` (rational or not) and its special forms.
    BSpline(BSplineSurface),
    /// `SURFACE_OF_REVOLUTION`.
    Revolution(Revolution),
    /// `SURFACE_OF_LINEAR_EXTRUSION`.
    Extrusion(Extrusion),
    /// `OFFSET_SURFACE`.
    Offset(Offset),
    /// `SURFACE_REPLICA`: a parent surface under a similarity.
    Replica(SurfaceReplica),
}

/// The kind of a [`Surface`], for summaries (`faces_by_surface`).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum SurfaceKind {
    /// Plane.
    Plane,
    /// Cylinder.
    Cylinder,
    /// Cone.
    Cone,
    /// Sphere.
    Sphere,
    /// Ring torus.
    Torus,
    /// Degenerate (self-intersecting) torus.
    DegenerateTorus,
    /// B-spline surface.
    BSpline,
    /// Surface of revolution.
    Revolution,
    /// Surface of linear extrusion.
    Extrusion,
    /// Offset surface.
    Offset,
    /// Replica (a transformed parent surface).
    Replica,
}

impl SurfaceKind {
    /// The name used in reports: `plane`, `cylinder`, `cone`, `sphere`, `torus`,
    /// `degenerate_torus`, `bspline`, `revolution`, `extrusion`, `offset`, `replica`.
    pub fn name(self) -> &'static str {
        match self {
            SurfaceKind::Plane => "plane",
            SurfaceKind::Cylinder => "cylinder",
            SurfaceKind::Cone => "cone",
            SurfaceKind::Sphere => "sphere",
            SurfaceKind::Torus => "torus",
            SurfaceKind::DegenerateTorus => "degenerate_torus",
            SurfaceKind::BSpline => "bspline",
            SurfaceKind::Revolution => "revolution",
            SurfaceKind::Extrusion => "extrusion",
            SurfaceKind::Offset => "offset",
            SurfaceKind::Replica => "replica",
        }
    }
}

impl fmt::Display for SurfaceKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl Surface {
    /// The kind.
    pub fn kind(&self) -> SurfaceKind {
        match self {
            Surface::Plane(_) => SurfaceKind::Plane,
            Surface::Cylinder(_) => SurfaceKind::Cylinder,
            Surface::Cone(_) => SurfaceKind::Cone,
            Surface::Sphere(_) => SurfaceKind::Sphere,
            Surface::Torus(t) if t.part != TorusPart::Full || t.minor >= t.major => SurfaceKind::DegenerateTorus,
            Surface::Torus(_) => SurfaceKind::Torus,
            Surface::BSpline(_) => SurfaceKind::BSpline,
            Surface::Revolution(_) => SurfaceKind::Revolution,
            Surface::Extrusion(_) => SurfaceKind::Extrusion,
            Surface::Offset(_) => SurfaceKind::Offset,
            Surface::Replica(_) => SurfaceKind::Replica,
        }
    }

    /// Point and first and second partial derivatives at `(u, v)`.
    pub fn derivs(&self, u: f64, v: f64) -> SurfaceDerivs {
        match self {
            Surface::Plane(s) => s.derivs(u, v),
            Surface::Cylinder(s) => s.derivs(u, v),
            Surface::Cone(s) => s.derivs(u, v),
            Surface::Sphere(s) => s.derivs(u, v),
            Surface::Torus(s) => s.derivs(u, v),
            Surface::BSpline(s) => s.derivs(u, v),
            Surface::Revolution(s) => s.derivs(u, v),
            Surface::Extrusion(s) => s.derivs(u, v),
            Surface::Offset(s) => s.derivs(u, v),
            Surface::Replica(s) => s.derivs(u, v),
        }
    }

    /// Point at `(u, v)`.
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        match self {
            Surface::Plane(s) => s.point(u, v),
            Surface::Cylinder(s) => s.point(u, v),
            Surface::Cone(s) => s.point(u, v),
            Surface::Sphere(s) => s.point(u, v),
            Surface::Torus(s) => s.point(u, v),
            Surface::BSpline(s) => s.point(u, v),
            Surface::Revolution(s) => s.point(u, v),
            Surface::Extrusion(s) => s.point(u, v),
            Surface::Offset(s) => s.point(u, v),
            Surface::Replica(s) => s.point(u, v),
        }
    }

    /// First partial derivatives `(∂S/∂u, ∂S/∂v)`.
    pub fn first_derivatives(&self, u: f64, v: f64) -> (DVec3, DVec3) {
        let (_, du, dv) = self.point_and_tangents(u, v);
        (du, dv)
    }

    /// The point and the first partial derivatives at `(u, v)` in one evaluation (a
    /// B-spline's without the second derivatives).
    pub fn point_and_tangents(&self, u: f64, v: f64) -> (DVec3, DVec3, DVec3) {
        let d = match self {
            Surface::BSpline(s) => s.derivs_to(u, v, 1),
            _ => self.derivs(u, v),
        };
        (d.p, d.du, d.dv)
    }

    /// The unit normal of the parametrization, `∂S/∂u × ∂S/∂v` normalised (a face's outward
    /// normal is this, negated where the face's `same_sense` is false). Exact at the poles of
    /// spheres; elsewhere where the parametrization is singular (a cone's apex, a collapsed
    /// B-spline edge) the normal just inside the domain, or `None` if there is none.
    pub fn normal(&self, u: f64, v: f64) -> Option<DVec3> {
        match self {
            Surface::Plane(s) => Some(s.normal()),
            Surface::Cylinder(s) => Some(s.normal(u)),
            Surface::Cone(s) => s.normal(u, v),
            Surface::Sphere(s) => Some(s.normal(u, v)),
            Surface::Torus(s) => s.normal(u, v),
            Surface::Replica(s) => s.normal(u, v),
            _ => {
                if let Some(n) = self.derivs(u, v).normal() {
                    return Some(n);
                }
                // a singular point: step towards the middle of the domain
                let d = self.domain();
                let mid = |a: f64, b: f64, x: f64| if a.is_finite() && b.is_finite() { x + 1e-7 * ((a + b) / 2.0 - x) } else { x };
                let (u2, v2) = (mid(d.u.min, d.u.max, u), mid(d.v.min, d.v.max, v));
                self.derivs(u2, v2).normal()
            }
        }
    }

    /// The natural parameter domain (see each kind for its parametrization).
    pub fn domain(&self) -> SurfaceDomain {
        match self {
            Surface::Plane(s) => s.domain(),
            Surface::Cylinder(s) => s.domain(),
            Surface::Cone(s) => s.domain(),
            Surface::Sphere(s) => s.domain(),
            Surface::Torus(s) => s.domain(),
            Surface::BSpline(s) => s.domain(),
            Surface::Revolution(s) => s.domain(),
            Surface::Extrusion(s) => s.domain(),
            Surface::Offset(s) => s.domain(),
            Surface::Replica(s) => s.domain(),
        }
    }

    /// Parameters `(u, v)` of the point of the surface closest to `p`. Closed form for planes,
    /// cylinders, cones, spheres and tori; Newton from a sampled start for B-spline, swept and
    /// offset surfaces. Periodic parameters are returned in the domain's window (`[0, 2π)` for
    /// angles); use [`Surface::project_near`] to keep them next to a neighbour's.
    pub fn project(&self, p: DVec3) -> DVec2 {
        match self {
            Surface::Plane(s) => s.project(p),
            Surface::Cylinder(s) => s.project(p),
            Surface::Cone(s) => s.project(p),
            Surface::Sphere(s) => s.project(p),
            Surface::Torus(s) => s.project(p),
            Surface::BSpline(s) => s.project(p),
            Surface::Revolution(s) => s.project(p),
            Surface::Extrusion(s) => s.project(p),
            Surface::Offset(s) => s.project(p),
            Surface::Replica(s) => s.project(p),
        }
    }

    /// Like [`Surface::project`], but with periodic parameters unwrapped to within half a
    /// period of `near`, and for B-splines Newton started at `near` (falling back to the
    /// global search when that ends farther away).
    pub fn project_near(&self, p: DVec3, near: DVec2) -> DVec2 {
        let q = match self {
            Surface::BSpline(s) => {
                let local = s.project_near(p, near);
                let dl = (s.point(local.x, local.y) - p).length();
                // trust the local answer when it lies on the surface (up to rounding)
                if dl <= 1e-9 * (1.0 + p.length()) {
                    local
                } else {
                    let global = s.project(p);
                    if (s.point(global.x, global.y) - p).length() < dl { global } else { local }
                }
            }
            Surface::Replica(s) => s.project_near(p, near),
            _ => self.project(p),
        };
        let d = self.domain();
        let q = DVec2::new(
            d.u_period.map_or(q.x, |per| unwrap_near(q.x, near.x, per)),
            d.v_period.map_or(q.y, |per| unwrap_near(q.y, near.y, per)),
        );
        // closed without a period (a B-spline whose first and last rows of control points
        // coincide): a point on the seam has both ends' parameters; the global search may
        // return the far one
        DVec2::new(
            if d.u_closed && d.u_period.is_none() { seam_side_near(q.x, near.x, d.u.min, d.u.max) } else { q.x },
            if d.v_closed && d.v_period.is_none() { seam_side_near(q.y, near.y, d.v.min, d.v.max) } else { q.y },
        )
    }

    /// Refines `(u, v)` by Newton towards the point closest to `p`, without a global search.
    pub fn refine(&self, p: DVec3, start: DVec2) -> DVec2 {
        refine_surface(|u, v| self.derivs(u, v), &self.domain(), p, start)
    }

    /// [`Surface::refine`] until a step would move the point by `tol` relative or less.
    pub fn refine_within(&self, p: DVec3, start: DVec2, tol: f64) -> DVec2 {
        refine_surface_within(|u, v| self.derivs(u, v), &self.domain(), p, start, tol)
    }

    /// The surface moved.
    pub fn transformed(&self, t: &Rigid) -> Surface {
        match self {
            Surface::Plane(s) => Surface::Plane(s.transformed(t)),
            Surface::Cylinder(s) => Surface::Cylinder(s.transformed(t)),
            Surface::Cone(s) => Surface::Cone(s.transformed(t)),
            Surface::Sphere(s) => Surface::Sphere(s.transformed(t)),
            Surface::Torus(s) => Surface::Torus(s.transformed(t)),
            Surface::BSpline(s) => Surface::BSpline(s.transformed(t)),
            Surface::Revolution(s) => Surface::Revolution(s.transformed(t)),
            Surface::Extrusion(s) => Surface::Extrusion(s.transformed(t)),
            Surface::Offset(s) => Surface::Offset(s.transformed(t)),
            Surface::Replica(s) => Surface::Replica(s.transformed(t)),
        }
    }
}

/// `x`, a parameter of a surface closed but not periodic over `lo..hi`, moved to the other
/// end when it lies on the seam (within 1e-7 of the range) and `near` is closer to that end.
fn seam_side_near(x: f64, near: f64, lo: f64, hi: f64) -> f64 {
    let len = hi - lo;
    if !(len.is_finite() && len > 0.0) {
        return x;
    }
    let eps = 1e-7 * len;
    if (x - lo).abs() <= eps && (hi - near) < (near - lo) {
        x + len
    } else if (hi - x).abs() <= eps && (near - lo) < (hi - near) {
        x - len
    } else {
        x
    }
}

// Offset surfaces (STEP `OFFSET_SURFACE`).

/// `S(u, v) + d · N(u, v)`: a basis surface moved by `distance` along its unit normal.
#[derive(Clone, Debug)]
pub struct Offset {
    /// The basis surface.
    pub basis: Box<Surface>,
    /// The offset distance in mm (signed, along the basis' parametric normal).
    pub distance: f64,
}

impl Offset {
    /// Point and first derivatives (exact, from the basis' second derivatives); the second
    /// derivatives by central differences of the first.
    pub fn derivs(&self, u: f64, v: f64) -> SurfaceDerivs {
        let (p, du, dv) = self.first(u, v);
        let h = 1e-6;
        let (_, du_p, dv_p) = self.first(u + h, v);
        let (_, du_m, dv_m) = self.first(u - h, v);
        let (_, _, dv_vp) = self.first(u, v + h);
        let (_, _, dv_vm) = self.first(u, v - h);
        SurfaceDerivs { p, du, dv, duu: (du_p - du_m) / (2.0 * h), duv: (dv_p - dv_m) / (2.0 * h), dvv: (dv_vp - dv_vm) / (2.0 * h) }
    }

    fn first(&self, u: f64, v: f64) -> (DVec3, DVec3, DVec3) {
        let b = self.basis.derivs(u, v);
        let n = b.du.cross(b.dv);
        let len = n.length();
        if !(len > 0.0) {
            let nn = self.basis.normal(u, v).unwrap_or(DVec3::ZERO);
            return (b.p + self.distance * nn, b.du, b.dv);
        }
        let unit = n / len;
        let nu = b.duu.cross(b.dv) + b.du.cross(b.duv);
        let nv = b.duv.cross(b.dv) + b.du.cross(b.dvv);
        let unit_u = (nu - unit * unit.dot(nu)) / len;
        let unit_v = (nv - unit * unit.dot(nv)) / len;
        (b.p + self.distance * unit, b.du + self.distance * unit_u, b.dv + self.distance * unit_v)
    }

    /// Point at `(u, v)`.
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        let n = self.basis.normal(u, v).unwrap_or(DVec3::ZERO);
        self.basis.point(u, v) + self.distance * n
    }

    /// The basis' domain.
    pub fn domain(&self) -> SurfaceDomain {
        self.basis.domain()
    }

    /// The basis' closest point (the same parameters for offsets smaller than the curvature
    /// radius), refined by Newton on the offset surface.
    pub fn project(&self, p: DVec3) -> DVec2 {
        let start = self.basis.project(p);
        refine_surface(|u, v| self.derivs(u, v), &self.domain(), p, start)
    }

    /// The surface moved.
    pub fn transformed(&self, t: &Rigid) -> Offset {
        Offset { basis: Box::new(self.basis.transformed(t)), distance: self.distance }
    }
}


// Surface replicas (STEP `SURFACE_REPLICA`): a parent surface under a [`Similarity`].

/// A surface under a similarity (same parameters as the parent; a reflection turns the
/// parametric normal `∂S/∂u × ∂S/∂v` round with it).
#[derive(Clone, Debug)]
pub struct SurfaceReplica {
    /// The parent surface.
    pub parent: Box<Surface>,
    /// The transformation.
    pub map: Similarity,
}

impl SurfaceReplica {
    /// Point and derivatives.
    pub fn derivs(&self, u: f64, v: f64) -> SurfaceDerivs {
        let d = self.parent.derivs(u, v);
        let m = |x: DVec3| self.map.apply_vector(x);
        SurfaceDerivs { p: self.map.apply_point(d.p), du: m(d.du), dv: m(d.dv), duu: m(d.duu), duv: m(d.duv), dvv: m(d.dvv) }
    }

    /// Point at `(u, v)`.
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        self.map.apply_point(self.parent.point(u, v))
    }

    /// The unit normal: the parent's, turned (and reversed by a reflection).
    pub fn normal(&self, u: f64, v: f64) -> Option<DVec3> {
        let n = self.map.axes * self.parent.normal(u, v)?;
        Some(if self.map.reflects() { -n } else { n })
    }

    /// The parent's domain.
    pub fn domain(&self) -> SurfaceDomain {
        self.parent.domain()
    }

    /// The parent's closest point to the point moved back.
    pub fn project(&self, p: DVec3) -> DVec2 {
        self.parent.project(self.map.invert_point(p))
    }

    /// Like [`SurfaceReplica::project`], near `near`.
    pub fn project_near(&self, p: DVec3, near: DVec2) -> DVec2 {
        self.parent.project_near(self.map.invert_point(p), near)
    }

    /// The replica moved.
    pub fn transformed(&self, t: &Rigid) -> SurfaceReplica {
        SurfaceReplica { parent: self.parent.clone(), map: self.map.then(t) }
    }
}
