//! STEP geometry (ISO 10303-42) → [`crate::cad::geom`]: points, directions, placements,
//! curves and surfaces, in millimetres, moved by the current instance's placement.

use super::convert::{Args, Converter, Fail, R, drop_entity};
use super::param::Param;
use crate::cad::geom::basis::expand_knots;
use crate::cad::geom::{
    BSplineCurve, BSplineSurface, Circle, Cone, Curve, CurveReplica, Cylinder, Ellipse, Extrusion, Frame, Hyperbola, Interval, Line, Offset, OffsetCurve,
    Parabola, Plane, Polyline, Revolution, Similarity, Sphere, Surface, SurfaceReplica, Torus, TorusPart, wrap_into,
};
use glam::DVec3;

impl Converter<'_> {
    /// `CARTESIAN_POINT`, scaled to mm, in the representation's own frame (2D points get z = 0).
    pub(super) fn point(&self, id: u64) -> R<DVec3> {
        let e = self.entity(id)?;
        let a = Args::of(e, "CARTESIAN_POINT")?;
        let c = a.f64s(1)?;
        if c.is_empty() || c.len() > 3 {
            return Err(drop_entity(e, format!("{} coordinates", c.len())));
        }
        let s = self.ctx.scale;
        Ok(DVec3::new(c[0], c.get(1).copied().unwrap_or(0.0), c.get(2).copied().unwrap_or(0.0)) * s)
    }

    /// `DIRECTION` (not normalised).
    pub(super) fn direction(&self, id: u64) -> R<DVec3> {
        let e = self.entity(id)?;
        let a = Args::of(e, "DIRECTION")?;
        let c = a.f64s(1)?;
        if c.is_empty() || c.len() > 3 {
            return Err(drop_entity(e, format!("{} direction ratios", c.len())));
        }
        Ok(DVec3::new(c[0], c.get(1).copied().unwrap_or(0.0), c.get(2).copied().unwrap_or(0.0)))
    }

    /// `VECTOR`: unit direction times magnitude, in mm.
    pub(super) fn vector(&self, id: u64) -> R<DVec3> {
        let e = self.entity(id)?;
        if e.has("DIRECTION") {
            return self.direction(id).map(|d| d.normalize_or_zero() * self.ctx.scale);
        }
        let a = Args::of(e, "VECTOR")?;
        let d = self.direction(a.id(1)?)?;
        let m = a.f64(2)?;
        let u = d.try_normalize().ok_or_else(|| drop_entity(e, "zero direction"))?;
        Ok(u * m * self.ctx.scale)
    }

    /// `AXIS2_PLACEMENT_3D` (or `_2D`) as a frame, in the representation's own frame.
    pub(super) fn placement(&self, id: u64) -> R<Frame> {
        let e = self.entity(id)?;
        let (origin, axis, refd) = if let Some(r) = e.record("AXIS2_PLACEMENT_3D") {
            let a = Args { e, params: &r.params };
            let axis = a.opt_id(2)?.map(|d| self.direction(d)).transpose()?;
            let refd = a.opt_id(3)?.map(|d| self.direction(d)).transpose()?;
            (self.point(a.id(1)?)?, axis, refd)
        } else if let Some(r) = e.record("AXIS2_PLACEMENT_2D") {
            let a = Args { e, params: &r.params };
            let refd = a.opt_id(2)?.map(|d| self.direction(d)).transpose()?;
            (self.point(a.id(1)?)?, None, refd)
        } else {
            return Err(drop_entity(e, "expected AXIS2_PLACEMENT_3D"));
        };
        Frame::from_axes(origin, axis, refd).ok_or_else(|| drop_entity(e, "zero or parallel axis and ref_direction"))
    }

    /// A curve moved into place, cached per instance: its index in the model and whether it
    /// runs against the STEP curve (a `TRIMMED_CURVE` with `sense_agreement = .F.`).
    /// `None` (after a report) when it cannot be converted.
    pub(super) fn curve_index(&mut self, id: u64) -> Result<Option<(u32, bool)>, Fail> {
        let key = (id, self.ctx.instance);
        if let Some(c) = self.curves.get(&key) {
            return Ok(*c);
        }
        let r = self.curve(id);
        let out = match r {
            Ok((c, rev)) => {
                let c = if self.ctx.place.is_identity() { c } else { c.transformed(&self.ctx.place) };
                self.model.curves.push(c);
                Some((self.model.curves.len() as u32 - 1, rev))
            }
            Err(Fail::Drop(d)) => {
                self.report(d);
                None
            }
            Err(f) => return Err(f),
        };
        self.curves.insert(key, out);
        Ok(out)
    }

    /// A curve in the representation's frame, and whether it runs against the STEP curve.
    pub(super) fn curve(&mut self, id: u64) -> R<(Curve, bool)> {
        self.within(id, |c| c.curve_inner(id))
    }

    fn curve_inner(&mut self, id: u64) -> R<(Curve, bool)> {
        let e = self.entity(id)?;
        let s = self.ctx.scale;
        let name = e.type_name();
        if e.has("B_SPLINE_CURVE") || name == "B_SPLINE_CURVE_WITH_KNOTS" || IMPLIED_KNOT_CURVES.contains(&name) {
            return Ok((Curve::BSpline(self.bspline_curve(id)?), false));
        }
        match name {
            "LINE" => {
                let a = Args::of(e, "LINE")?;
                let origin = self.point(a.id(1)?)?;
                let dir = self.vector(a.id(2)?)?;
                if !(dir.length() > 0.0) {
                    return Err(drop_entity(e, "zero direction"));
                }
                Ok((Curve::Line(Line { origin, direction: dir }), false))
            }
            "CIRCLE" => {
                let a = Args::of(e, "CIRCLE")?;
                let frame = self.placement(a.id(1)?)?;
                let radius = a.f64(2)? * s;
                if !(radius > 0.0) {
                    return Err(drop_entity(e, format!("radius {radius} is not positive")));
                }
                Ok((Curve::Circle(Circle { frame, radius }), false))
            }
            "ELLIPSE" | "HYPERBOLA" => {
                let a = Args::of(e, name)?;
                let frame = self.placement(a.id(1)?)?;
                let (sa, sb) = (a.f64(2)? * s, a.f64(3)? * s);
                if !(sa > 0.0 && sb > 0.0) {
                    return Err(drop_entity(e, "semi-axes must be positive"));
                }
                let c = if name == "ELLIPSE" { Curve::Ellipse(Ellipse { frame, a: sa, b: sb }) } else { Curve::Hyperbola(Hyperbola { frame, a: sa, b: sb }) };
                Ok((c, false))
            }
            "PARABOLA" => {
                let a = Args::of(e, "PARABOLA")?;
                let frame = self.placement(a.id(1)?)?;
                let focal = a.f64(2)? * s;
                if !(focal.is_finite() && focal != 0.0) {
                    return Err(drop_entity(e, "the focal distance must be finite and not zero"));
                }
                Ok((Curve::Parabola(Parabola { frame, focal }), false))
            }
            "POLYLINE" => {
                let a = Args::of(e, "POLYLINE")?;
                let points = a.ids(1)?.into_iter().map(|p| self.point(p)).collect::<R<Vec<_>>>()?;
                if points.len() < 2 {
                    return Err(drop_entity(e, "fewer than two points"));
                }
                Ok((Curve::Polyline(Polyline { points }), false))
            }
            "SURFACE_CURVE" | "SEAM_CURVE" | "INTERSECTION_CURVE" | "BOUNDED_SURFACE_CURVE" => {
                let a = Args::of(e, name)?;
                self.curve(a.id(1)?)
            }
            "TRIMMED_CURVE" => self.trimmed_curve(id),
            "CURVE_REPLICA" => {
                let a = Args::of(e, name)?;
                let (parent, rev) = self.curve(a.id(1)?)?;
                let map = self.operator(a.id(2)?)?;
                // a rigid motion keeps the kind (a replica of a line is a line ...)
                let c = match map.as_rigid() {
                    Some(t) => parent.transformed(&t),
                    None => Curve::Replica(CurveReplica { parent: Box::new(parent), map }),
                };
                Ok((c, rev))
            }
            "OFFSET_CURVE_3D" => {
                let a = Args::of(e, name)?;
                let (basis, rev) = self.curve(a.id(1)?)?;
                let distance = a.f64(2)? * s;
                let direction = self.direction(a.id(4)?)?.try_normalize().ok_or_else(|| drop_entity(e, "zero ref_direction"))?;
                // the offset is across the STEP curve's tangent: ours runs the other way when `rev`
                let distance = if rev { -distance } else { distance };
                Ok((Curve::Offset(OffsetCurve { basis: Box::new(basis), distance, direction }), rev))
            }
            _ => Err(drop_entity(e, "unsupported curve type")),
        }
    }

    fn trimmed_curve(&mut self, id: u64) -> R<(Curve, bool)> {
        let e = self.entity(id)?;
        let a = Args::of(e, "TRIMMED_CURVE")?;
        let (basis, rev) = self.curve(a.id(1)?)?;
        let sense = a.bool_or(4, true);
        let periodic = basis.domain().period;
        let angular = matches!(basis, Curve::Circle(_) | Curve::Ellipse(_));
        let trim = |c: &Self, k: usize| -> R<f64> {
            let list = a.list(k)?;
            // prefer the parameter value; else project the point
            for p in list {
                if let Param::Typed(n, v) = p {
                    if &**n == "PARAMETER_VALUE" {
                        if let Some(t) = v.first().and_then(Param::as_f64) {
                            return Ok(if angular { t * c.ctx.angle } else { t });
                        }
                    }
                }
                if let Some(x) = p.as_f64() {
                    return Ok(if angular { x * c.ctx.angle } else { x });
                }
            }
            for p in list {
                if let Some(pid) = p.as_ref_id() {
                    return Ok(basis.project(c.point(pid)?));
                }
            }
            Err(drop_entity(e, format!("parameter {}: no trimming value", k + 1)))
        };
        let (t1, t2) = (trim(self, 2)?, trim(self, 3)?);
        let (lo, hi) = if sense { (t1, t2) } else { (t2, t1) };
        let interval = match periodic {
            Some(per) => {
                let mut h = wrap_into(hi, lo, per);
                if h - lo <= 1e-12 * per {
                    h = lo + per;
                }
                Interval::new(lo, h)
            }
            None => Interval::new(lo.min(hi), lo.max(hi)),
        };
        Ok((Curve::Trimmed(Box::new(basis), interval), rev ^ !sense))
    }

    fn bspline_curve(&mut self, id: u64) -> R<BSplineCurve> {
        let e = self.entity(id)?;
        // simple form: (name, degree, points, form, closed, self_int, mults, knots, spec), or
        // without the last three for the forms whose knots are implied (QUASI_UNIFORM_CURVE ...)
        // complex form: B_SPLINE_CURVE(degree, points, ...) B_SPLINE_CURVE_WITH_KNOTS(mults, knots, spec)
        let (base, off) = match e.record("B_SPLINE_CURVE") {
            Some(r) => (Args { e, params: &r.params }, 0),
            None if IMPLIED_KNOT_CURVES.contains(&e.type_name()) => (Args::of(e, e.type_name())?, 1),
            None => (Args::of(e, "B_SPLINE_CURVE_WITH_KNOTS")?, 1),
        };
        let degree = base.i64(off)?;
        if !(1..=25).contains(&degree) {
            return Err(drop_entity(e, format!("degree {degree} outside 1..=25")));
        }
        let degree = degree as usize;
        let points = base.ids(off + 1)?.into_iter().map(|p| self.point(p)).collect::<R<Vec<_>>>()?;
        let knots = if off == 1 && e.has("B_SPLINE_CURVE_WITH_KNOTS") {
            let m = base.i64s(6)?;
            let k = base.f64s(7)?;
            expand_knots(&k, &m).map_err(|w| drop_entity(e, w.to_string()))?
        } else if let Some(r) = e.record("B_SPLINE_CURVE_WITH_KNOTS").filter(|_| off == 0) {
            let a = Args { e, params: &r.params };
            expand_knots(&a.f64s(1)?, &a.i64s(0)?).map_err(|w| drop_entity(e, w.to_string()))?
        } else {
            implicit_knots(e, degree, points.len())?
        };
        let weights = match e.record("RATIONAL_B_SPLINE_CURVE") {
            Some(r) => Some(Args { e, params: &r.params }.f64s(0)?),
            None => None,
        };
        BSplineCurve::new(degree, knots, points, weights).map_err(|w| drop_entity(e, w.to_string()))
    }

    /// A surface moved into place, cached per instance; its index in the model.
    pub(super) fn surface_index(&mut self, id: u64) -> R<u32> {
        let key = (id, self.ctx.instance);
        if let Some(&k) = self.surfaces.get(&key) {
            return Ok(k);
        }
        let s = self.surface(id)?;
        let s = if self.ctx.place.is_identity() { s } else { s.transformed(&self.ctx.place) };
        self.model.surfaces.push(s);
        let k = self.model.surfaces.len() as u32 - 1;
        self.surfaces.insert(key, k);
        Ok(k)
    }

    /// A surface in the representation's frame.
    pub(super) fn surface(&mut self, id: u64) -> R<Surface> {
        self.within(id, |c| c.surface_inner(id))
    }

    fn surface_inner(&mut self, id: u64) -> R<Surface> {
        let e = self.entity(id)?;
        let s = self.ctx.scale;
        if e.has("B_SPLINE_SURFACE") || e.type_name() == "B_SPLINE_SURFACE_WITH_KNOTS" || IMPLIED_KNOT_SURFACES.contains(&e.type_name()) {
            return Ok(Surface::BSpline(self.bspline_surface(id)?));
        }
        let name = e.type_name();
        let positive = |x: f64, what: &str| if x > 0.0 { Ok(x) } else { Err(drop_entity(e, format!("{what} {x} is not positive"))) };
        match name {
            "PLANE" => {
                let a = Args::of(e, name)?;
                Ok(Surface::Plane(Plane { frame: self.placement(a.id(1)?)? }))
            }
            "CYLINDRICAL_SURFACE" => {
                let a = Args::of(e, name)?;
                Ok(Surface::Cylinder(Cylinder { frame: self.placement(a.id(1)?)?, radius: positive(a.f64(2)? * s, "radius")? }))
            }
            "CONICAL_SURFACE" => {
                let a = Args::of(e, name)?;
                let semi_angle = a.f64(3)? * self.ctx.angle;
                if !(semi_angle.abs() > 0.0 && semi_angle.abs() < std::f64::consts::FRAC_PI_2) {
                    return Err(drop_entity(e, format!("semi-angle {semi_angle} rad is not in (0, π/2)")));
                }
                let radius = a.f64(2)? * s;
                if radius < 0.0 {
                    return Err(drop_entity(e, "negative radius"));
                }
                Ok(Surface::Cone(Cone { frame: self.placement(a.id(1)?)?, radius, semi_angle }))
            }
            "SPHERICAL_SURFACE" => {
                let a = Args::of(e, name)?;
                Ok(Surface::Sphere(Sphere { frame: self.placement(a.id(1)?)?, radius: positive(a.f64(2)? * s, "radius")? }))
            }
            "TOROIDAL_SURFACE" | "DEGENERATE_TOROIDAL_SURFACE" => {
                let a = Args::of(e, name)?;
                // a negative major radius (SolidWorks writes one for a spindle torus, minor
                // over major) puts each meridian circle's centre across the axis. The torus's
                // formula holds as it is; with the radius's magnitude (as OpenCASCADE reads
                // it) the point set is the same but the normal turns over (the circle of angle
                // u is the positive one's of angle u + π, run the other way), and the faces
                // on it would face inward
                let major = a.f64(2)? * s;
                let minor = positive(a.f64(3)? * s, "minor radius")?;
                let part = if name == "DEGENERATE_TOROIDAL_SURFACE" && minor > major {
                    if a.bool_or(4, true) { TorusPart::Outer } else { TorusPart::Inner }
                } else {
                    TorusPart::Full
                };
                Ok(Surface::Torus(Torus { frame: self.placement(a.id(1)?)?, major, minor, part }))
            }
            "SURFACE_OF_LINEAR_EXTRUSION" => {
                let a = Args::of(e, name)?;
                let (curve, _) = self.curve(a.id(1)?)?;
                let dir = self.vector(a.id(2)?)?;
                Extrusion::new(curve, dir).map(Surface::Extrusion).ok_or_else(|| drop_entity(e, "zero extrusion vector"))
            }
            "SURFACE_OF_REVOLUTION" => {
                let a = Args::of(e, name)?;
                let (curve, _) = self.curve(a.id(1)?)?;
                let ax = self.entity(a.id(2)?)?;
                let axa = Args::of(ax, "AXIS1_PLACEMENT")?;
                let origin = self.point(axa.id(1)?)?;
                let axis = axa.opt_id(2)?.map(|d| self.direction(d)).transpose()?.unwrap_or(DVec3::Z);
                Revolution::new(curve, origin, axis).map(Surface::Revolution).ok_or_else(|| drop_entity(e, "zero axis"))
            }
            "OFFSET_SURFACE" => {
                let a = Args::of(e, name)?;
                let basis = self.surface(a.id(1)?)?;
                Ok(Surface::Offset(Offset { basis: Box::new(basis), distance: a.f64(2)? * s }))
            }
            "RECTANGULAR_TRIMMED_SURFACE" | "CURVE_BOUNDED_SURFACE" => {
                // the face's own bounds trim it; the basis surface is what matters here
                let a = Args::of(e, name)?;
                self.surface(a.id(1)?)
            }
            "SURFACE_REPLICA" => {
                let a = Args::of(e, name)?;
                let parent = self.surface(a.id(1)?)?;
                let map = self.operator(a.id(2)?)?;
                Ok(match map.as_rigid() {
                    Some(t) => parent.transformed(&t),
                    None => Surface::Replica(SurfaceReplica { parent: Box::new(parent), map }),
                })
            }
            _ => Err(drop_entity(e, "unsupported surface type")),
        }
    }

    /// `CARTESIAN_TRANSFORMATION_OPERATOR_3D`: (name, name, description, axis1, axis2,
    /// local_origin, scale, axis3), the two names of its two supertypes both written.
    fn operator(&self, id: u64) -> R<Similarity> {
        let e = self.entity(id)?;
        let a = Args::of(e, "CARTESIAN_TRANSFORMATION_OPERATOR_3D")?;
        if a.params.len() != 8 {
            return Err(drop_entity(e, format!("{} parameters, expected 8", a.params.len())));
        }
        let axis = |k: usize| a.opt_id(k)?.map(|d| self.direction(d)).transpose();
        let (axis1, axis2, axis3) = (axis(3)?, axis(4)?, axis(7)?);
        let origin = self.point(a.id(5)?)?;
        let scale = match a.params.get(6) {
            Some(Param::Unset) | None => None,
            Some(_) => Some(a.f64(6)?),
        };
        Similarity::from_operator(axis1, axis2, axis3, origin, scale).ok_or_else(|| drop_entity(e, "zero or dependent axes, or a scale that is not positive"))
    }

    fn bspline_surface(&mut self, id: u64) -> R<BSplineSurface> {
        let e = self.entity(id)?;
        // simple: (name, du, dv, points, form, uc, vc, si, um, vm, uk, vk, spec)
        // or without the last five for the forms whose knots are implied (QUASI_UNIFORM_SURFACE ...)
        // complex: B_SPLINE_SURFACE(du, dv, points, form, uc, vc, si) B_SPLINE_SURFACE_WITH_KNOTS(um, vm, uk, vk, spec)
        let (base, off) = match e.record("B_SPLINE_SURFACE") {
            Some(r) => (Args { e, params: &r.params }, 0),
            None if IMPLIED_KNOT_SURFACES.contains(&e.type_name()) => (Args::of(e, e.type_name())?, 1),
            None => (Args::of(e, "B_SPLINE_SURFACE_WITH_KNOTS")?, 1),
        };
        let (du, dv) = (base.i64(off)?, base.i64(off + 1)?);
        if !(1..=25).contains(&du) || !(1..=25).contains(&dv) {
            return Err(drop_entity(e, format!("degrees {du}, {dv} outside 1..=25")));
        }
        let rows = base.list(off + 2)?;
        let nu = rows.len();
        let nv = rows.first().and_then(Param::as_list).map_or(0, <[Param]>::len);
        let mut points = Vec::with_capacity(nu * nv);
        for row in rows {
            let row = row.as_list().ok_or_else(|| drop_entity(e, "control points are not a list of lists"))?;
            if row.len() != nv {
                return Err(drop_entity(e, "control point rows differ in length"));
            }
            for p in row {
                let pid = p.as_ref_id().ok_or_else(|| drop_entity(e, "a control point is not a reference"))?;
                points.push(self.point(pid)?);
            }
        }
        let (ku, kv) = if off == 1 && e.has("B_SPLINE_SURFACE_WITH_KNOTS") {
            let ku = expand_knots(&base.f64s(10)?, &base.i64s(8)?).map_err(|w| drop_entity(e, format!("u knots: {w}")))?;
            let kv = expand_knots(&base.f64s(11)?, &base.i64s(9)?).map_err(|w| drop_entity(e, format!("v knots: {w}")))?;
            (ku, kv)
        } else if let Some(r) = e.record("B_SPLINE_SURFACE_WITH_KNOTS").filter(|_| off == 0) {
            let a = Args { e, params: &r.params };
            let ku = expand_knots(&a.f64s(2)?, &a.i64s(0)?).map_err(|w| drop_entity(e, format!("u knots: {w}")))?;
            let kv = expand_knots(&a.f64s(3)?, &a.i64s(1)?).map_err(|w| drop_entity(e, format!("v knots: {w}")))?;
            (ku, kv)
        } else {
            (implicit_knots(e, du as usize, nu)?, implicit_knots(e, dv as usize, nv)?)
        };
        let weights = match e.record("RATIONAL_B_SPLINE_SURFACE") {
            Some(r) => {
                let a = Args { e, params: &r.params };
                let mut w = Vec::with_capacity(nu * nv);
                for row in a.list(0)? {
                    let row = row.as_list().ok_or_else(|| drop_entity(e, "weights are not a list of lists"))?;
                    for x in row {
                        w.push(x.as_f64().ok_or_else(|| drop_entity(e, "a weight is not a number"))?);
                    }
                }
                Some(w)
            }
            None => None,
        };
        BSplineSurface::new(du as usize, dv as usize, ku, kv, nu, nv, points, weights).map_err(|w| drop_entity(e, w.to_string()))
    }
}

/// The simple B-spline curve entities whose knots are implied by their form (AP203/214/242:
/// subtypes of `B_SPLINE_CURVE` beside `B_SPLINE_CURVE_WITH_KNOTS`); see [`implicit_knots`].
const IMPLIED_KNOT_CURVES: [&str; 3] = ["UNIFORM_CURVE", "QUASI_UNIFORM_CURVE", "BEZIER_CURVE"];

/// The same for surfaces.
const IMPLIED_KNOT_SURFACES: [&str; 3] = ["UNIFORM_SURFACE", "QUASI_UNIFORM_SURFACE", "BEZIER_SURFACE"];

/// Knots of the B-spline forms that give none: `BEZIER_*` (clamped, pieces of `degree`),
/// `UNIFORM_*` (-degree, 1 - degree, ...) and `QUASI_UNIFORM_*` (clamped uniform).
fn implicit_knots(e: &super::table::Entity, degree: usize, n: usize) -> R<Vec<f64>> {
    let has = |suffix: &str| e.records.iter().any(|r| r.name.starts_with(suffix));
    if n < degree + 1 {
        return Err(drop_entity(e, "too few control points"));
    }
    if has("UNIFORM_") {
        // ISO 10303-42: knots -degree, 1 - degree, ..., each once
        return Ok((0..n + degree + 1).map(|k| k as f64 - degree as f64).collect());
    }
    if has("QUASI_UNIFORM_") || has("BEZIER_") {
        let inner = n - degree - 1;
        let mut k = vec![0.0; degree + 1];
        if has("BEZIER_") && (n - 1) % degree == 0 {
            // piecewise Bézier: interior knots of multiplicity `degree`
            let pieces = (n - 1) / degree;
            k = vec![0.0; degree + 1];
            for i in 1..pieces {
                k.extend(std::iter::repeat_n(i as f64, degree));
            }
            k.extend(std::iter::repeat_n(pieces as f64, degree + 1));
            return Ok(k);
        }
        k.extend((1..=inner).map(|i| i as f64));
        k.extend(std::iter::repeat_n((inner + 1) as f64, degree + 1));
        return Ok(k);
    }
    Err(drop_entity(e, "a B-spline without knots of a form fepre does not know"))
}
