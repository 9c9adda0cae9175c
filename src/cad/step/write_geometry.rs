//! The geometry half of the STEP writer: points, directions, placements, curves and surfaces
//! of [`crate::cad::geom`] as ISO 10303-42 entities, in millimetres and radians.

use super::writer::{StepWriteError, Writer};
use crate::cad::geom::{BSplineCurve, BSplineSurface, Curve, Frame, Similarity, Surface, TorusPart};
use glam::DVec3;

/// A STEP real: Rust's shortest round-trip form with the exponent as `E` and a decimal point
/// always present (`1.0`, `0.25`, `1.5E-7`, `1.E20`).
pub(super) fn real(x: f64) -> String {
    let s = format!("{x:?}");
    let (mantissa, exp) = match s.find(['e', 'E']) {
        Some(k) => (&s[..k], Some(&s[k + 1..])),
        None => (&s[..], None),
    };
    let mut m = mantissa.to_string();
    if !m.contains('.') {
        m.push('.');
    }
    match exp {
        Some(e) => format!("{m}E{e}"),
        None => m,
    }
}

/// Distinct knots and their multiplicities, as STEP lists them.
fn knots_and_multiplicities(full: &[f64]) -> (Vec<f64>, Vec<usize>) {
    let mut values: Vec<f64> = Vec::new();
    let mut mults: Vec<usize> = Vec::new();
    for &k in full {
        match values.last() {
            Some(&last) if last == k => {
                if let Some(m) = mults.last_mut() {
                    *m += 1;
                }
            }
            _ => {
                values.push(k);
                mults.push(1);
            }
        }
    }
    (values, mults)
}

fn list<T>(items: &[T], f: impl Fn(&T) -> String) -> String {
    let parts: Vec<String> = items.iter().map(f).collect();
    format!("({})", parts.join(","))
}

fn refs(ids: &[u64]) -> String {
    list(ids, |i| format!("#{i}"))
}

impl Writer {
    fn finite(&self, what: &str, v: &[f64]) -> Result<(), StepWriteError> {
        if v.iter().all(|x| x.is_finite()) { Ok(()) } else { Err(StepWriteError::NotFinite { what: what.to_string() }) }
    }

    /// `CARTESIAN_POINT`.
    pub(super) fn point(&mut self, p: DVec3) -> Result<u64, StepWriteError> {
        self.finite("a point", &p.to_array())?;
        Ok(self.add(format!("CARTESIAN_POINT('',({},{},{}))", real(p.x), real(p.y), real(p.z))))
    }

    /// `DIRECTION`.
    pub(super) fn direction(&mut self, d: DVec3) -> Result<u64, StepWriteError> {
        self.finite("a direction", &d.to_array())?;
        Ok(self.add(format!("DIRECTION('',({},{},{}))", real(d.x), real(d.y), real(d.z))))
    }

    /// `AXIS2_PLACEMENT_3D` of a frame.
    pub(super) fn placement(&mut self, f: &Frame) -> Result<u64, StepWriteError> {
        let (o, z, x) = (self.point(f.origin)?, self.direction(f.z)?, self.direction(f.x)?);
        Ok(self.add(format!("AXIS2_PLACEMENT_3D('',#{o},#{z},#{x})")))
    }

    /// A curve entity (lines keep the length of their direction, so parameters are kept).
    pub(super) fn curve(&mut self, c: &Curve) -> Result<u64, StepWriteError> {
        Ok(match c {
            Curve::Line(l) => {
                let o = self.point(l.origin)?;
                let len = l.direction.length();
                let d = self.direction(if len > 0.0 { l.direction / len } else { DVec3::X })?;
                let v = self.add(format!("VECTOR('',#{d},{})", real(len)));
                self.add(format!("LINE('',#{o},#{v})"))
            }
            Curve::Circle(c) => {
                let p = self.placement(&c.frame)?;
                self.add(format!("CIRCLE('',#{p},{})", real(c.radius)))
            }
            Curve::Ellipse(e) => {
                let p = self.placement(&e.frame)?;
                self.add(format!("ELLIPSE('',#{p},{},{})", real(e.a), real(e.b)))
            }
            Curve::Parabola(c) => {
                let p = self.placement(&c.frame)?;
                self.add(format!("PARABOLA('',#{p},{})", real(c.focal)))
            }
            Curve::Hyperbola(c) => {
                let p = self.placement(&c.frame)?;
                self.add(format!("HYPERBOLA('',#{p},{},{})", real(c.a), real(c.b)))
            }
            Curve::BSpline(b) => self.bspline_curve(b)?,
            Curve::Polyline(p) => {
                let ids = p.points.iter().map(|&q| self.point(q)).collect::<Result<Vec<_>, _>>()?;
                self.add(format!("POLYLINE('',{})", refs(&ids)))
            }
            Curve::Trimmed(basis, range) => {
                let b = self.curve(basis)?;
                self.finite("a trimmed curve's range", &[range.min, range.max])?;
                self.add(format!(
                    "TRIMMED_CURVE('',#{b},(PARAMETER_VALUE({})),(PARAMETER_VALUE({})),.T.,.PARAMETER.)",
                    real(range.min),
                    real(range.max)
                ))
            }
            Curve::Replica(r) => {
                let parent = self.curve(&r.parent)?;
                let op = self.operator(&r.map)?;
                self.add(format!("CURVE_REPLICA('',#{parent},#{op})"))
            }
            Curve::Offset(o) => {
                let b = self.curve(&o.basis)?;
                self.finite("an offset curve's distance", &[o.distance])?;
                let d = self.direction(o.direction)?;
                self.add(format!("OFFSET_CURVE_3D('',#{b},{},.F.,#{d})", real(o.distance)))
            }
        })
    }

    /// `CARTESIAN_TRANSFORMATION_OPERATOR_3D` of a similarity (all three axes given).
    fn operator(&mut self, m: &Similarity) -> Result<u64, StepWriteError> {
        self.finite("a transformation's scale", &[m.scale])?;
        let (a1, a2, a3) = (self.direction(m.axes.x_axis)?, self.direction(m.axes.y_axis)?, self.direction(m.axes.z_axis)?);
        let o = self.point(m.origin)?;
        Ok(self.add(format!("CARTESIAN_TRANSFORMATION_OPERATOR_3D('','','',#{a1},#{a2},#{o},{},#{a3})", real(m.scale))))
    }

    fn bspline_curve(&mut self, b: &BSplineCurve) -> Result<u64, StepWriteError> {
        let pts = b.control_points().iter().map(|&p| self.point(p)).collect::<Result<Vec<_>, _>>()?;
        let (k, m) = knots_and_multiplicities(b.knots());
        let (deg, pts, m, k) = (b.degree(), refs(&pts), list(&m, |x| x.to_string()), list(&k, |x| real(*x)));
        Ok(match b.weights() {
            None => self.add(format!("B_SPLINE_CURVE_WITH_KNOTS('',{deg},{pts},.UNSPECIFIED.,.F.,.F.,{m},{k},.UNSPECIFIED.)")),
            Some(w) => self.add(format!(
                "(BOUNDED_CURVE() B_SPLINE_CURVE({deg},{pts},.UNSPECIFIED.,.F.,.F.) B_SPLINE_CURVE_WITH_KNOTS({m},{k},.UNSPECIFIED.) \
                 CURVE() GEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_CURVE({}) REPRESENTATION_ITEM(''))",
                list(w, |x| real(*x))
            )),
        })
    }

    /// A surface entity.
    pub(super) fn surface(&mut self, s: &Surface) -> Result<u64, StepWriteError> {
        Ok(match s {
            Surface::Plane(p) => {
                let a = self.placement(&p.frame)?;
                self.add(format!("PLANE('',#{a})"))
            }
            Surface::Cylinder(c) => {
                let a = self.placement(&c.frame)?;
                self.add(format!("CYLINDRICAL_SURFACE('',#{a},{})", real(c.radius)))
            }
            Surface::Cone(c) => {
                let a = self.placement(&c.frame)?;
                self.add(format!("CONICAL_SURFACE('',#{a},{},{})", real(c.radius), real(c.semi_angle)))
            }
            Surface::Sphere(c) => {
                let a = self.placement(&c.frame)?;
                self.add(format!("SPHERICAL_SURFACE('',#{a},{})", real(c.radius)))
            }
            Surface::Torus(t) => {
                let a = self.placement(&t.frame)?;
                let (big, small) = (real(t.major), real(t.minor));
                match t.part {
                    TorusPart::Full => self.add(format!("TOROIDAL_SURFACE('',#{a},{big},{small})")),
                    TorusPart::Outer => self.add(format!("DEGENERATE_TOROIDAL_SURFACE('',#{a},{big},{small},.T.)")),
                    TorusPart::Inner => self.add(format!("DEGENERATE_TOROIDAL_SURFACE('',#{a},{big},{small},.F.)")),
                }
            }
            Surface::BSpline(b) => self.bspline_surface(b)?,
            Surface::Revolution(r) => {
                let c = self.curve(&r.curve)?;
                let (o, d) = (self.point(r.origin)?, self.direction(r.axis)?);
                let ax = self.add(format!("AXIS1_PLACEMENT('',#{o},#{d})"));
                self.add(format!("SURFACE_OF_REVOLUTION('',#{c},#{ax})"))
            }
            Surface::Extrusion(e) => {
                let c = self.curve(&e.curve)?;
                let len = e.direction.length();
                let d = self.direction(e.direction / len)?;
                let v = self.add(format!("VECTOR('',#{d},{})", real(len)));
                self.add(format!("SURFACE_OF_LINEAR_EXTRUSION('',#{c},#{v})"))
            }
            Surface::Offset(o) => {
                let b = self.surface(&o.basis)?;
                self.add(format!("OFFSET_SURFACE('',#{b},{},.F.)", real(o.distance)))
            }
            Surface::Replica(r) => {
                let parent = self.surface(&r.parent)?;
                let op = self.operator(&r.map)?;
                self.add(format!("SURFACE_REPLICA('',#{parent},#{op})"))
            }
        })
    }

    fn bspline_surface(&mut self, b: &BSplineSurface) -> Result<u64, StepWriteError> {
        let [nu, nv] = b.counts();
        let [du, dv] = b.degrees();
        let cp = b.control_points();
        let mut rows = Vec::with_capacity(nu);
        for i in 0..nu {
            let ids = (0..nv).map(|j| self.point(cp[i * nv + j])).collect::<Result<Vec<_>, _>>()?;
            rows.push(refs(&ids));
        }
        let pts = format!("({})", rows.join(","));
        let [ku, kv] = b.knots();
        let ((ku, mu), (kv, mv)) = (knots_and_multiplicities(ku), knots_and_multiplicities(kv));
        let (mu, mv, ku, kv) = (list(&mu, |x| x.to_string()), list(&mv, |x| x.to_string()), list(&ku, |x| real(*x)), list(&kv, |x| real(*x)));
        Ok(match b.weights() {
            None => self.add(format!("B_SPLINE_SURFACE_WITH_KNOTS('',{du},{dv},{pts},.UNSPECIFIED.,.F.,.F.,.F.,{mu},{mv},{ku},{kv},.UNSPECIFIED.)")),
            Some(w) => {
                let wrows: Vec<String> = (0..nu).map(|i| list(&w[i * nv..(i + 1) * nv], |x| real(*x))).collect();
                self.add(format!(
                    "(BOUNDED_SURFACE() B_SPLINE_SURFACE({du},{dv},{pts},.UNSPECIFIED.,.F.,.F.,.F.) \
                     B_SPLINE_SURFACE_WITH_KNOTS({mu},{mv},{ku},{kv},.UNSPECIFIED.) GEOMETRIC_REPRESENTATION_ITEM() \
                     RATIONAL_B_SPLINE_SURFACE(({})) REPRESENTATION_ITEM('') SURFACE())",
                    wrows.join(",")
                ))
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reals_have_a_point_and_an_upper_case_exponent() {
        assert_eq!(real(1.0), "1.0");
        assert_eq!(real(-0.25), "-0.25");
        assert_eq!(real(1.5e-7), "1.5E-7");
        assert_eq!(real(1e20), "1.E20");
        assert_eq!(real(0.1).parse::<f64>().unwrap(), 0.1);
    }

    #[test]
    fn knots_compress() {
        assert_eq!(knots_and_multiplicities(&[0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0]), (vec![0.0, 0.5, 1.0], vec![3, 1, 3]));
    }
}
