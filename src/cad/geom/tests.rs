//! Evaluation and projection round trips of every surface and curve kind, at random
//! parameters: `project(point(u, v)) == (u, v)` to 1e-9 relative, derivatives against
//! differences, normals against `du × dv`, and rigid motions.

use super::*;
use glam::{DVec2, DVec3};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// A small deterministic generator (xorshift64*), so failures reproduce.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.next()
    }
    fn vec(&mut self, s: f64) -> DVec3 {
        DVec3::new(self.range(-s, s), self.range(-s, s), self.range(-s, s))
    }
    fn frame(&mut self) -> Frame {
        loop {
            if let Some(f) = Frame::from_axes(self.vec(50.0), Some(self.vec(1.0)), Some(self.vec(1.0))) {
                return f;
            }
        }
    }
}

fn bspline_patch(rational: bool) -> BSplineSurface {
    // a bicubic 5 × 4 bump with an interior knot in u and a double knot in v
    let (nu, nv) = (5, 5);
    let mut pts = Vec::new();
    let mut w = Vec::new();
    for i in 0..nu {
        for j in 0..nv {
            let (x, y) = (i as f64 * 10.0, j as f64 * 8.0);
            let z = 6.0 * ((i as f64 - 2.0) * 0.7).cos() * ((j as f64 - 2.0) * 0.5).sin();
            pts.push(DVec3::new(x + 0.3 * y, y, z));
            w.push(1.0 + 0.3 * ((i + 2 * j) % 3) as f64);
        }
    }
    let ku = vec![0.0, 0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0, 1.0];
    let kv = vec![-1.0, -1.0, -1.0, 0.5, 0.5, 2.0, 2.0, 2.0];
    BSplineSurface::new(3, 2, ku, kv, nu, nv, pts, rational.then_some(w)).unwrap()
}

fn profile_curve() -> Curve {
    // a cubic B-spline in the xz half-plane, away from the z axis
    let pts = [(5.0, -4.0), (9.0, -1.0), (6.0, 2.0), (8.0, 5.0), (4.0, 8.0)].map(|(x, z)| DVec3::new(x, 0.0, z));
    Curve::BSpline(BSplineCurve::new(3, vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0], pts.to_vec(), None).unwrap())
}

/// Every surface kind, with the parameter box random samples are drawn from (inside the
/// domain, away from seams and singular points).
fn surfaces(rng: &mut Rng) -> Vec<(&'static str, Surface, [f64; 4])> {
    let f = rng.frame();
    let angle = [0.05, TAU - 0.05];
    let mut out = vec![
        ("plane", Surface::Plane(Plane { frame: f }), [-100.0, 100.0, -50.0, 50.0]),
        ("cylinder", Surface::Cylinder(Cylinder { frame: rng.frame(), radius: 7.5 }), [angle[0], angle[1], -20.0, 20.0]),
        (
            "cone",
            Surface::Cone(Cone { frame: rng.frame(), radius: 4.0, semi_angle: 0.6 }),
            [angle[0], angle[1], -5.0, 30.0], // apex at v = -4/tan(0.6) ≈ -5.85
        ),
        ("sphere", Surface::Sphere(Sphere { frame: rng.frame(), radius: 12.0 }), [angle[0], angle[1], -FRAC_PI_2 + 0.05, FRAC_PI_2 - 0.05]),
        ("torus", Surface::Torus(Torus { frame: rng.frame(), major: 20.0, minor: 3.0, part: TorusPart::Full }), [angle[0], angle[1], 0.05, TAU - 0.05]),
    ];
    // a degenerate torus like Zylkopf.stp's (R = 9.2, r = 10): apple and lemon
    let (big, small): (f64, f64) = (9.20224530853, 10.0);
    let a = (-big / small).acos();
    out.push((
        "degenerate torus (outer)",
        Surface::Torus(Torus { frame: rng.frame(), major: big, minor: small, part: TorusPart::Outer }),
        [angle[0], angle[1], -a + 0.05, a - 0.05],
    ));
    out.push((
        "degenerate torus (inner)",
        Surface::Torus(Torus { frame: rng.frame(), major: big, minor: small, part: TorusPart::Inner }),
        [angle[0], angle[1], a + 0.01, TAU - a - 0.01],
    ));
    // a negative major radius as SolidWorks writes one (Azsug0x00's Part10: R = -30, r = 100):
    // the tube's centre across the axis; v where R + r cos v > 0 (the lemon, |v| < 1.27),
    // inside the window [0, 2π) that projection gives
    out.push((
        "torus with a negative major radius",
        Surface::Torus(Torus { frame: rng.frame(), major: -3.0, minor: 10.0, part: TorusPart::Full }),
        [angle[0], angle[1], 0.05, 1.2],
    ));
    out.push(("bspline", Surface::BSpline(bspline_patch(false)), [0.0, 1.0, -1.0, 2.0]));
    out.push(("rational bspline", Surface::BSpline(bspline_patch(true)), [0.0, 1.0, -1.0, 2.0]));
    out.push((
        "revolution",
        Surface::Revolution(Revolution::new(profile_curve(), f.origin, f.z).unwrap().transformed(&rng.frame().as_rigid())),
        [angle[0], angle[1], 0.0, 1.0],
    ));
    let circle = Curve::Circle(Circle { frame: rng.frame(), radius: 6.0 });
    out.push(("extrusion of a circle", Surface::Extrusion(Extrusion::new(circle, rng.vec(3.0) + DVec3::splat(4.0)).unwrap()), [angle[0], angle[1], -3.0, 3.0]));
    // unbounded: the sweep's samples stop where cosh would overflow
    let hyperbola = Curve::Hyperbola(Hyperbola { frame: rng.frame(), a: 4.0, b: 3.0 });
    out.push(("extrusion of a hyperbola", Surface::Extrusion(Extrusion::new(hyperbola, DVec3::new(0.5, 1.0, 6.0)).unwrap()), [-1.5, 1.5, -3.0, 3.0]));
    out.push(("extrusion of a bspline", Surface::Extrusion(Extrusion::new(profile_curve(), DVec3::new(1.0, 7.0, 0.5)).unwrap()), [0.0, 1.0, -3.0, 3.0]));
    out.push((
        "offset of a cylinder",
        Surface::Offset(Offset { basis: Box::new(Surface::Cylinder(Cylinder { frame: rng.frame(), radius: 5.0 })), distance: 1.5 }),
        [angle[0], angle[1], -10.0, 10.0],
    ));
    out.push(("offset of a bspline", Surface::Offset(Offset { basis: Box::new(Surface::BSpline(bspline_patch(true))), distance: -0.8 }), [0.05, 0.95, -0.9, 1.9]));
    // a scaled reflection (left-handed axes) and a scaled rotation
    let mirror = Similarity::from_operator(Some(rng.vec(1.0)), Some(rng.vec(1.0)), Some(rng.vec(1.0)), rng.vec(20.0), Some(1.7)).unwrap();
    let m = if mirror.reflects() { mirror } else { Similarity { axes: -mirror.axes, ..mirror } };
    out.push(("replica of a bspline (reflected)", Surface::Replica(SurfaceReplica { parent: Box::new(Surface::BSpline(bspline_patch(true))), map: m }), [0.0, 1.0, -1.0, 2.0]));
    let scaled = Similarity { axes: -m.axes, scale: 0.6, ..m };
    let cylinder = Surface::Cylinder(Cylinder { frame: rng.frame(), radius: 5.0 });
    out.push(("replica of a cylinder (scaled)", Surface::Replica(SurfaceReplica { parent: Box::new(cylinder), map: scaled }), [angle[0], angle[1], -10.0, 10.0]));
    out
}

fn rel_close(a: DVec2, b: DVec2, scale: f64) -> bool {
    (a - b).abs().max_element() <= 1e-9 * scale.max(1.0)
}

#[test]
fn surface_projection_round_trips() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    for round in 0..3 {
        for (name, s, [u0, u1, v0, v1]) in surfaces(&mut rng) {
            let scale = (u1 - u0).abs().max((v1 - v0).abs());
            for _ in 0..60 {
                let uv = DVec2::new(rng.range(u0, u1), rng.range(v0, v1));
                let p = s.point(uv.x, uv.y);
                let q = s.project(p);
                assert!(rel_close(q, uv, scale), "{name} (round {round}): project(point{uv}) = {q}, point there {}", s.point(q.x, q.y));
                // near a neighbour across the seam, periodic parameters stay on its side
                let near = uv + DVec2::new(0.01, -0.01);
                let qn = s.project_near(p, near);
                assert!(rel_close(qn, uv, scale), "{name}: project_near gave {qn} for {uv}");
                // a point off the surface along the normal projects back too (offset ≪ curvature radius)
                if let Some(n) = s.normal(uv.x, uv.y) {
                    let q2 = s.project(p + 0.01 * n);
                    assert!((s.point(q2.x, q2.y) - p).length() < 1e-6, "{name}: off-surface projection at {uv} gave {q2}");
                }
            }
        }
    }
}

#[test]
fn surface_derivatives_and_normals() {
    let mut rng = Rng(42);
    for (name, s, [u0, u1, v0, v1]) in surfaces(&mut rng) {
        for _ in 0..20 {
            let (u, v) = (rng.range(u0, u1), rng.range(v0, v1));
            let d = s.derivs(u, v);
            assert!((d.p - s.point(u, v)).length() < 1e-12 * (1.0 + d.p.length()), "{name}");
            let h = 1e-5;
            let fu = (s.point(u + h, v) - s.point(u - h, v)) / (2.0 * h);
            let fv = (s.point(u, v + h) - s.point(u, v - h)) / (2.0 * h);
            let tol = 1e-5 * (1.0 + d.du.length() + d.dv.length());
            assert!((fu - d.du).length() < tol, "{name}: du {} vs {fu}", d.du);
            assert!((fv - d.dv).length() < tol, "{name}: dv {} vs {fv}", d.dv);
            let duu = (s.derivs(u + h, v).du - s.derivs(u - h, v).du) / (2.0 * h);
            let duv = (s.derivs(u, v + h).du - s.derivs(u, v - h).du) / (2.0 * h);
            let dvv = (s.derivs(u, v + h).dv - s.derivs(u, v - h).dv) / (2.0 * h);
            let tol2 = 1e-4 * (1.0 + d.duu.length() + d.dvv.length() + d.duv.length());
            assert!((duu - d.duu).length() < tol2 && (duv - d.duv).length() < tol2 && (dvv - d.dvv).length() < tol2, "{name}: second derivatives");
            let n = s.normal(u, v).unwrap();
            let c = d.du.cross(d.dv).normalize();
            assert!((n - c).length() < 1e-9, "{name}: normal {n} vs du×dv {c}");
        }
    }
}

#[test]
fn rigid_motion_commutes_with_evaluation_and_projection() {
    let mut rng = Rng(7);
    let t = rng.frame().as_rigid();
    for (name, s, [u0, u1, v0, v1]) in surfaces(&mut rng) {
        let m = s.transformed(&t);
        for _ in 0..10 {
            let uv = DVec2::new(rng.range(u0, u1), rng.range(v0, v1));
            let p = t.apply_point(s.point(uv.x, uv.y));
            assert!((m.point(uv.x, uv.y) - p).length() < 1e-9 * (1.0 + p.length()), "{name}");
            assert!(rel_close(m.project(p), uv, (u1 - u0).max(v1 - v0)), "{name}: moved projection");
        }
    }
}

#[test]
fn poles_and_apexes_have_normals() {
    let s = Surface::Sphere(Sphere { frame: Frame::WORLD, radius: 2.0 });
    assert!((s.normal(1.0, FRAC_PI_2).unwrap() - DVec3::Z).length() < 1e-15);
    assert!((s.normal(0.3, -FRAC_PI_2).unwrap() + DVec3::Z).length() < 1e-15);
    assert_eq!(s.project(DVec3::new(0.0, 0.0, 2.0)), DVec2::new(0.0, FRAC_PI_2));
    let c = Cone { frame: Frame::WORLD, radius: 1.0, semi_angle: PI / 4.0 };
    assert!(c.normal(0.0, -1.0).is_none());
}

fn curves(rng: &mut Rng) -> Vec<(&'static str, Curve, [f64; 2])> {
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let arc = BSplineCurve::new(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 2.0],
        vec![DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y, DVec3::new(-1.0, 1.0, 0.0), DVec3::new(-1.0, 0.0, 0.0)].iter().map(|p| *p * 5.0).collect(),
        Some(vec![1.0, h, 1.0, h, 1.0]),
    )
    .unwrap();
    let circle = Circle { frame: rng.frame(), radius: 3.0 };
    vec![
        ("line", Curve::Line(Line { origin: rng.vec(10.0), direction: rng.vec(2.0) }), [-50.0, 50.0]),
        ("circle", Curve::Circle(circle), [0.05, TAU - 0.05]),
        ("ellipse", Curve::Ellipse(Ellipse { frame: rng.frame(), a: 9.0, b: 2.5 }), [0.05, TAU - 0.05]),
        ("bspline", profile_curve(), [0.0, 1.0]),
        ("rational bspline (half circle)", Curve::BSpline(arc.transformed(&rng.frame().as_rigid())), [0.0, 2.0]),
        ("polyline", Curve::Polyline(Polyline { points: vec![DVec3::ZERO, DVec3::X * 4.0, DVec3::new(4.0, 3.0, 1.0), DVec3::new(9.0, 3.0, 1.0)] }), [0.01, 2.99]),
        ("trimmed circle", Curve::Trimmed(Box::new(Curve::Circle(circle)), Interval::new(5.0, 7.0)), [5.0, 7.0]),
        (
            "replica of an ellipse (scaled, reflected)",
            Curve::Replica(CurveReplica {
                parent: Box::new(Curve::Ellipse(Ellipse { frame: rng.frame(), a: 9.0, b: 2.5 })),
                map: Similarity::from_operator(Some(DVec3::Y), Some(DVec3::X), Some(DVec3::new(0.0, 1.0, 1.0)), rng.vec(5.0), Some(2.5)).unwrap(),
            }),
            [0.05, TAU - 0.05],
        ),
        // V × T of a circle about its own axis points to the centre: a circle of radius 2
        ("offset of a circle", Curve::Offset(OffsetCurve { basis: Box::new(Curve::Circle(circle)), distance: 1.0, direction: circle.frame.z }), [0.05, TAU - 0.05]),
        ("offset of a bspline", Curve::Offset(OffsetCurve { basis: Box::new(profile_curve()), distance: -0.3, direction: DVec3::new(0.2, 0.1, 1.0).normalize() }), [0.0, 1.0]),
    ]
}

#[test]
fn curve_projection_round_trips() {
    let mut rng = Rng(1234567);
    for (name, c, [a, b]) in curves(&mut rng) {
        for _ in 0..100 {
            let t = rng.range(a, b);
            let p = c.point(t);
            let q = c.project(p);
            assert!((q - t).abs() <= 1e-9 * (b - a).max(1.0), "{name}: project(point({t})) = {q}");
            assert!((c.project_near(p, t + 0.01) - t).abs() <= 1e-9 * (b - a).max(1.0), "{name}: project_near");
            let d = c.derivs(t);
            let e = 1e-6;
            // polylines have corners at integers
            if name != "polyline" || (t - t.round()).abs() > 2.0 * e {
                let fd = (c.point(t + e) - c.point(t - e)) / (2.0 * e);
                assert!((fd - d.d1).length() < 1e-5 * (1.0 + d.d1.length()), "{name}: derivative {} vs {fd}", d.d1);
                let fd2 = (c.derivative(t + e) - c.derivative(t - e)) / (2.0 * e);
                assert!((fd2 - d.d2).length() < 1e-4 * (1.0 + d.d2.length()), "{name}: second derivative");
            }
        }
    }
}

#[test]
fn curve_domains() {
    let mut rng = Rng(5);
    let cs = curves(&mut rng);
    let dom = |name: &str| cs.iter().find(|c| c.0 == name).unwrap().1.domain();
    assert_eq!(dom("circle").period, Some(TAU));
    assert_eq!(dom("line").range, Interval::ALL);
    assert_eq!(dom("bspline").range, Interval::new(0.0, 1.0));
    assert_eq!(dom("polyline").range, Interval::new(0.0, 3.0));
    assert_eq!(dom("trimmed circle").range, Interval::new(5.0, 7.0));
    assert!(!dom("rational bspline (half circle)").closed);
    assert_eq!(dom("offset of a circle").period, Some(TAU));
    let offset = &cs.iter().find(|c| c.0 == "offset of a circle").unwrap().1;
    let Curve::Offset(o) = offset else { unreachable!() };
    let Curve::Circle(c) = o.basis.as_ref() else { unreachable!() };
    for t in [0.3, 2.0, 5.0] {
        assert!(((offset.point(t) - c.frame.origin).length() - 2.0).abs() < 1e-12, "the offset circle's radius at {t}");
    }
}

#[test]
fn cartesian_operators_follow_iso_10303_42_base_axis() {
    // defaults: the identity
    let m = Similarity::from_operator(None, None, None, DVec3::ZERO, None).unwrap();
    assert_eq!((m.axes, m.scale), (glam::DMat3::IDENTITY, 1.0));
    assert!(m.as_rigid().is_some_and(|r| r.is_identity()));
    // axis1 not orthogonal to axis3 is projected; axis2 keeps its sign: here a reflection
    let m = Similarity::from_operator(Some(DVec3::new(1.0, 0.0, 1.0)), Some(DVec3::new(0.0, -3.0, 0.0)), Some(DVec3::Z * 2.0), DVec3::ONE, Some(2.0)).unwrap();
    assert!((m.axes.x_axis - DVec3::X).length() < 1e-15 && (m.axes.y_axis + DVec3::Y).length() < 1e-15 && m.reflects());
    assert!(m.as_rigid().is_none());
    let p = DVec3::new(1.0, 2.0, 3.0);
    assert!((m.apply_point(p) - DVec3::new(3.0, -3.0, 7.0)).length() < 1e-14);
    assert!((m.invert_point(m.apply_point(p)) - p).length() < 1e-14);
    // no axis3: +Z, and axis1 along it is refused, as are a zero axis and a scale ≤ 0
    assert!(Similarity::from_operator(Some(DVec3::Z), None, None, DVec3::ZERO, None).is_none());
    assert!(Similarity::from_operator(Some(DVec3::ZERO), None, None, DVec3::ZERO, None).is_none());
    assert!(Similarity::from_operator(None, None, None, DVec3::ZERO, Some(0.0)).is_none());
}

#[test]
fn cone_projection_reaches_the_far_nappe() {
    use crate::cad::geom::{Cone, Frame};
    let c = Cone { frame: Frame::WORLD, radius: 7.5, semi_angle: std::f64::consts::FRAC_PI_4 };
    // below the apex (v < -7.5) the radius is negative: the point lies at the opposite angle
    for &(u, v) in &[(0.3, -12.0), (2.0, -20.0), (4.0, 3.0)] {
        let p = c.point(u, v);
        let q = c.project(p);
        assert!((c.point(q.x, q.y) - p).length() < 1e-9, "({u}, {v}) -> {q:?}");
    }
}

#[test]
fn self_intersecting_full_torus_projects_onto_its_lemon() {
    use crate::cad::geom::{Frame, Torus, TorusPart};
    let t = Torus { frame: Frame::WORLD, major: 2.0, minor: 5.0, part: TorusPart::Full };
    for &(u, v) in &[(0.5, 0.3), (1.0, 2.5), (4.0, 3.6), (5.5, 5.9)] {
        let p = t.point(u, v);
        let q = t.project(p);
        assert!((t.point(q.x, q.y) - p).length() < 1e-9, "({u}, {v}) -> {q:?}");
    }
}

#[test]
fn a_torus_with_a_negative_major_radius_is_the_positive_ones_point_set_turned_over() {
    use crate::cad::geom::{Frame, Torus, TorusPart};
    let neg = Torus { frame: Frame::WORLD, major: -3.0, minor: 10.0, part: TorusPart::Full };
    let pos = Torus { major: 3.0, ..neg };
    for &(u, v) in &[(0.5, 0.3), (1.0, 1.1), (4.0, -0.9), (5.5, 2.5), (2.0, 3.5)] {
        // the circle of angle u is the positive torus's of angle u + π, run the other way
        let (p, q) = (neg.point(u, v), pos.point(u + std::f64::consts::PI, std::f64::consts::PI - v));
        assert!((p - q).length() < 1e-9, "({u}, {v}): {p} against {q}");
        let (Some(n), Some(m)) = (neg.normal(u, v), pos.normal(u + std::f64::consts::PI, std::f64::consts::PI - v)) else { panic!("no normal at ({u}, {v})") };
        assert!((n + m).length() < 1e-9, "({u}, {v}): normals {n} and {m} are not opposite");
        // the normal is du x dv, and projection comes back to the point
        let d = neg.derivs(u, v);
        assert!((d.du.cross(d.dv).normalize() - n).length() < 1e-9);
        let w = neg.project(p);
        assert!((neg.point(w.x, w.y) - p).length() < 1e-9, "({u}, {v}) -> {w:?}");
    }
}

#[test]
fn unbounded_curves_sweep_samples_stay_finite() {
    // a hyperbola's cosh overflows at |t| ≈ 710: its samples stop before, reaching 1e6 mm
    let h = Curve::Hyperbola(Hyperbola { frame: Frame::WORLD, a: 4.0, b: 3.0 });
    let s = h.sweep_samples();
    assert!(s.p.iter().all(|p| p.is_finite()), "non-finite samples");
    let (lo, hi) = (s.t[0], s.t[s.t.len() - 1]);
    assert!(lo < -5.0 && hi > 5.0 && hi < 20.0, "{lo}..{hi}");
    // a line: out to about 1e6 mm either way, as before
    let l = Curve::Line(Line { origin: DVec3::ZERO, direction: DVec3::X });
    let s = l.sweep_samples();
    assert!(s.t[0] <= -5e5 && s.t[s.t.len() - 1] >= 5e5);
}

#[test]
fn a_point_on_a_sheet_that_folds_back_near_another_projects_onto_its_own_sheet() {
    // a hairpin in u: five pieces out along x at y = 0, a 0.01 fold, one piece back at
    // y = 0.01; the samples nearest a point of the way back all lie on the way out
    let d = 0.01;
    let xs: Vec<(f64, f64)> = vec![(0.0, 0.0), (2.0, 0.0), (4.0, 0.0), (6.0, 0.0), (8.0, 0.0), (10.0, 0.0), (10.0, d), (0.0, d)];
    let mut pts = Vec::new();
    for &(x, y) in &xs {
        for z in [0.0, 1.0] {
            pts.push(DVec3::new(x, y, z));
        }
    }
    let mut ku = vec![0.0, 0.0];
    ku.extend((1..7).map(|i| f64::from(i) / 7.0));
    ku.extend([1.0, 1.0]);
    let s = crate::cad::geom::BSplineSurface::new(1, 1, ku, vec![0.0, 0.0, 1.0, 1.0], 8, 2, pts, None).unwrap();
    for x in [4.3, 5.0, 5.7] {
        let p = DVec3::new(x, d, 0.5);
        let q = s.project(p);
        assert!(s.point(q.x, q.y).distance(p) < 1e-9, "{p}: projected to {q} at {}", s.point(q.x, q.y));
    }
}
