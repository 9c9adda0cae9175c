//! More STEP entities (issue 14), each in a file written here by hand, read by fepre and by
//! OpenCASCADE and compared as in `step_entities.rs` (volume within 0.5 %, area within
//! 0.25 %, one certified watertight solid, nothing dropped): conics and offset curves as edge
//! curves, curve and surface replicas, trimmed and curve-bounded surfaces, the knot-type
//! enums of B-splines with knots, every orientation flag written `.F.`, names in the Part 21
//! string encodings, and odd headers.
//!
//! Most parts are prisms: a planar profile, counter-clockwise seen from +z, one of its sides
//! the curve under test, extruded by `H` (the curved side a `SURFACE_OF_LINEAR_EXTRUSION` of
//! it, or the surface under test). Where OpenCASCADE does not read a file as the standard
//! means it, the test says so and compares with the exact volume and area instead.
//!
//! Skips with a message where Python with OCP is missing; fails under `CI=true`.

mod common;

use common::step_writer::{Form, HEAD, Writer, agrees_with_opencascade, box_shell, bspline_box_files, box_shell_written, refs, step_file, tessellate, write_file};
use std::f64::consts::PI;

/// The prisms' height.
const H: f64 = 5.0;

/// A curve entity written at height `z`, returning its id.
type CurveAt = Box<dyn Fn(&mut Writer, f64) -> usize>;

/// A surface entity for a curved side, given the bottom curve's id: its id and whether its
/// normal points out of the prism (`ADVANCED_FACE`'s `same_sense`).
type SideSurface = Box<dyn Fn(&mut Writer, usize) -> (usize, bool)>;

/// The top face's surface, given the plane's id (`None`: the plane).
type TopSurface<'a> = Option<&'a dyn Fn(&mut Writer, usize) -> usize>;

/// One side of a prism's profile, from `from` to `to` (counter-clockwise seen from +z).
struct Side {
    from: [f64; 2],
    to: [f64; 2],
    /// `None`: straight. Otherwise the curve, whether its parameter runs from `from` to
    /// `to`, and the side's surface (`None`: the extrusion of the bottom curve).
    curve: Option<(CurveAt, bool, Option<SideSurface>)>,
}

fn line_side(from: [f64; 2], to: [f64; 2]) -> Side {
    Side { from, to, curve: None }
}

fn curve_side(from: [f64; 2], to: [f64; 2], at: CurveAt, along: bool, surface: Option<SideSurface>) -> Side {
    Side { from, to, curve: Some((at, along, surface)) }
}

/// `AXIS2_PLACEMENT_3D` at `o` with axis `z` and reference direction `x`.
fn placement(w: &mut Writer, o: [f64; 3], z: [f64; 3], x: [f64; 3]) -> usize {
    let (p, a, r) = (w.point(o), w.direction(z), w.direction(x));
    w.add(format!("AXIS2_PLACEMENT_3D('',#{p},#{a},#{r})"))
}

fn line(w: &mut Writer, from: [f64; 3], to: [f64; 3]) -> usize {
    let d = [to[0] - from[0], to[1] - from[1], to[2] - from[2]];
    let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    let p = w.point(from);
    let dir = w.direction([d[0] / len, d[1] / len, d[2] / len]);
    let v = w.add(format!("VECTOR('',#{dir},{len:?})"));
    w.add(format!("LINE('',#{p},#{v})"))
}

/// The closed shell of the prism over `sides` (the top face's surface `top` of the plane's
/// id where given); returns the shell's id.
fn prism(w: &mut Writer, sides: &[Side], top: TopSurface) -> usize {
    let n = sides.len();
    let at = |k: usize, z: f64| [sides[k].from[0], sides[k].from[1], z];
    let vertex = |w: &mut Writer, p: [f64; 3]| {
        let q = w.point(p);
        w.add(format!("VERTEX_POINT('',#{q})"))
    };
    let bottom_v: Vec<usize> = (0..n).map(|k| vertex(w, at(k, 0.0))).collect();
    let top_v: Vec<usize> = (0..n).map(|k| vertex(w, at(k, H))).collect();
    let up: Vec<usize> = (0..n)
        .map(|k| {
            let c = line(w, at(k, 0.0), at(k, H));
            w.add(format!("EDGE_CURVE('',#{},#{},#{c},.T.)", bottom_v[k], top_v[k]))
        })
        .collect();
    let mut bottom_e = Vec::new();
    let mut top_e = Vec::new();
    let mut faces = Vec::new();
    for (k, s) in sides.iter().enumerate() {
        let next = (k + 1) % n;
        let (from0, to0) = ([s.from[0], s.from[1], 0.0], [s.to[0], s.to[1], 0.0]);
        let (from1, to1) = ([s.from[0], s.from[1], H], [s.to[0], s.to[1], H]);
        let (c0, c1, along) = match &s.curve {
            None => (line(w, from0, to0), line(w, from1, to1), true),
            Some((curve, along, _)) => (curve(w, 0.0), curve(w, H), *along),
        };
        let flag = if along { ".T." } else { ".F." };
        let e0 = w.add(format!("EDGE_CURVE('',#{},#{},#{c0},{flag})", bottom_v[k], bottom_v[next]));
        let e1 = w.add(format!("EDGE_CURVE('',#{},#{},#{c1},{flag})", top_v[k], top_v[next]));
        bottom_e.push(e0);
        top_e.push(e1);
        // the side: outward is right of the travel, T × z
        let (surface, sense) = match &s.curve {
            None => {
                let d = [s.to[0] - s.from[0], s.to[1] - s.from[1]];
                let len = d[0].hypot(d[1]);
                let p = placement(w, from0, [d[1] / len, -d[0] / len, 0.0], [d[0] / len, d[1] / len, 0.0]);
                (w.add(format!("PLANE('',#{p})")), true)
            }
            Some((_, _, Some(surface))) => surface(w, c0),
            Some((_, along, None)) => {
                let z = w.direction([0.0, 0.0, 1.0]);
                let v = w.add(format!("VECTOR('',#{z},{H:?})"));
                (w.add(format!("SURFACE_OF_LINEAR_EXTRUSION('',#{c0},#{v})")), *along)
            }
        };
        let oriented = [(e0, ".T."), (up[next], ".T."), (e1, ".F."), (up[k], ".F.")].map(|(e, o)| w.add(format!("ORIENTED_EDGE('',*,*,#{e},{o})")));
        faces.push(face(w, &oriented, surface, sense));
    }
    let bottom: Vec<usize> = bottom_e.iter().rev().map(|e| w.add(format!("ORIENTED_EDGE('',*,*,#{e},.F.)"))).collect();
    let p = placement(w, [0.0; 3], [0.0, 0.0, -1.0], [1.0, 0.0, 0.0]);
    let plane = w.add(format!("PLANE('',#{p})"));
    faces.push(face(w, &bottom, plane, true));
    let topo: Vec<usize> = top_e.iter().map(|e| w.add(format!("ORIENTED_EDGE('',*,*,#{e},.T.)"))).collect();
    let p = placement(w, [0.0, 0.0, H], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
    let plane = w.add(format!("PLANE('',#{p})"));
    let surface = match top {
        Some(f) => f(w, plane),
        None => plane,
    };
    faces.push(face(w, &topo, surface, true));
    w.add(format!("CLOSED_SHELL('',{})", refs(&faces)))
}

fn face(w: &mut Writer, oriented: &[usize], surface: usize, sense: bool) -> usize {
    let lp = w.add(format!("EDGE_LOOP('',{})", refs(oriented)));
    let bound = w.add(format!("FACE_OUTER_BOUND('',#{lp},.T.)"));
    w.add(format!("ADVANCED_FACE('',(#{bound}),#{surface},{})", if sense { ".T." } else { ".F." }))
}

/// The file of the prism over `sides`.
fn prism_file(name: &str, sides: &[Side], top: TopSurface) -> String {
    step_file(name, |w| {
        let shell = prism(w, sides, top);
        w.add(format!("MANIFOLD_SOLID_BREP('{name}',#{shell})"))
    })
}

/// `∫ f` over `[a, b]` by Simpson's rule on 2000 intervals.
fn integral(a: f64, b: f64, f: impl Fn(f64) -> f64) -> f64 {
    let n = 2000;
    let h = (b - a) / n as f64;
    (0..=n).map(|k| f(a + k as f64 * h) * if k == 0 || k == n { 1.0 } else if k % 2 == 1 { 4.0 } else { 2.0 }).sum::<f64>() * h / 3.0
}

/// A volume range ±1 % around `v` (the check that the file means what the test says).
fn around(v: f64) -> [f64; 2] {
    [v * 0.99, v * 1.01]
}

/// The D-shaped profile: the diameter along the x axis from `(-r, 0)` to `(r, 0)`, then the
/// upper half circle `arc` back (its parameter running from `(r, 0)` at 0 to `(-r, 0)` at π).
fn half_disc(r: f64, arc: CurveAt, surface: Option<SideSurface>) -> Vec<Side> {
    vec![line_side([-r, 0.0], [r, 0.0]), curve_side([r, 0.0], [-r, 0.0], arc, true, surface)]
}

/// A `CIRCLE` of radius `r` about the z axis at height `z`.
fn circle(r: f64) -> CurveAt {
    Box::new(move |w, z| {
        let p = placement(w, [0.0, 0.0, z], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
        w.add(format!("CIRCLE('',#{p},{r:?})"))
    })
}

/// `CARTESIAN_TRANSFORMATION_OPERATOR_3D` (both names and the description written, as
/// ISO 10303-42 has them).
fn operator(w: &mut Writer, axes: [[f64; 3]; 3], origin: [f64; 3], scale: f64) -> usize {
    let [a1, a2, a3] = axes.map(|a| w.direction(a));
    let o = w.point(origin);
    w.add(format!("CARTESIAN_TRANSFORMATION_OPERATOR_3D('','','',#{a1},#{a2},#{o},{scale:?},#{a3})"))
}

const X: [f64; 3] = [1.0, 0.0, 0.0];
const Y: [f64; 3] = [0.0, 1.0, 0.0];
const Z: [f64; 3] = [0.0, 0.0, 1.0];

/// The parent circle and cylinder of the replicas: radius 6 about the x axis through
/// (100, 50, 20), reference direction +y; `ONTO` puts them onto the z axis at height `z`
/// (x ↦ z, y ↦ x, z ↦ y).
const PARENT: [f64; 3] = [100.0, 50.0, 20.0];
fn onto(w: &mut Writer, z: f64) -> usize {
    operator(w, [Z, X, Y], [-PARENT[1], -PARENT[2], z - PARENT[0]], 1.0)
}

/// The prism over the upper half of the `OFFSET_CURVE_3D` of the ellipse (8 cos t, 5 sin t)
/// across z by -1 (ISO 10303-42: C + d (V × T)/|V × T|, V × T pointing into the ellipse):
/// 1 mm outside it, from (9, 0) to (-9, 0), closed by the x axis; and its exact volume and
/// area (the profile's area is half the ellipse's widened by 1, (πab + perimeter + π)/2).
fn offset_curve_file() -> (String, [f64; 2]) {
    let offset: CurveAt = Box::new(|w, z| {
        let p = placement(w, [0.0, 0.0, z], Z, X);
        let e = w.add(format!("ELLIPSE('',#{p},8.,5.)"));
        let v = w.direction(Z);
        w.add(format!("OFFSET_CURVE_3D('',#{e},-1.,.F.,#{v})"))
    });
    let perimeter = integral(0.0, 2.0 * PI, |t| (64.0 * t.sin().powi(2) + 25.0 * t.cos().powi(2)).sqrt());
    let offset_area = (PI * 40.0 + perimeter + PI) / 2.0;
    let text = prism_file("offset_curve_3d", &[line_side([-9.0, 0.0], [9.0, 0.0]), curve_side([9.0, 0.0], [-9.0, 0.0], offset, true, None)], None);
    let half_perimeter = (perimeter + 2.0 * PI) / 2.0;
    (text, [offset_area * H, 2.0 * offset_area + (18.0 + half_perimeter) * H])
}

#[test]
fn conics_and_offset_curves_as_edge_curves_agree_with_opencascade() {
    // PARABOLA (focal 2.5: (2.5 t², 5 t)) from t = -2 to 2, closed by the line x = 10
    let parabola: CurveAt = Box::new(|w, z| {
        let p = placement(w, [0.0, 0.0, z], Z, X);
        w.add(format!("PARABOLA('',#{p},2.5)"))
    });
    let parabola_area = integral(-10.0, 10.0, |y| 10.0 - y * y / 10.0);
    let parabola = prism_file("parabola", &[line_side([10.0, -10.0], [10.0, 10.0]), curve_side([10.0, 10.0], [10.0, -10.0], parabola, false, None)], None);
    // HYPERBOLA (4 cosh t, 3 sinh t) from t = -1 to 1, closed by the line x = 4 cosh 1
    let (hx, hy) = (4.0 * 1f64.cosh(), 3.0 * 1f64.sinh());
    let hyperbola: CurveAt = Box::new(|w, z| {
        let p = placement(w, [0.0, 0.0, z], Z, X);
        w.add(format!("HYPERBOLA('',#{p},4.,3.)"))
    });
    let hyperbola_area = integral(-hy, hy, |y| hx - 4.0 * (1.0 + y * y / 9.0).sqrt());
    let hyperbola = prism_file("hyperbola", &[line_side([hx, -hy], [hx, hy]), curve_side([hx, hy], [hx, -hy], hyperbola, false, None)], None);
    let (offset, [offset_volume, _]) = offset_curve_file();
    let files = [
        ("parabola".to_string(), parabola, 0, around(parabola_area * H)),
        ("hyperbola".to_string(), hyperbola, 0, around(hyperbola_area * H)),
        ("offset_curve_3d".to_string(), offset, 0, around(offset_volume)),
    ];
    agrees_with_opencascade("step_entities_conics", &files);
}

#[test]
fn replicas_agree_with_opencascade() {
    // CURVE_REPLICA: the half circle's arcs replicas of a circle about the x axis far away
    // (the top one a replica of the bottom one, moved up by H: replicas of replicas); the
    // side the extrusion of the bottom replica
    let replica: CurveAt = Box::new(|w, z| {
        let p = placement(w, PARENT, X, Y);
        let parent = w.add(format!("CIRCLE('',#{p},6.)"));
        let bottom_op = onto(w, 0.0);
        let bottom = w.add(format!("CURVE_REPLICA('',#{parent},#{bottom_op})"));
        if z == 0.0 {
            return bottom;
        }
        let up = operator(w, [X, Y, Z], [0.0, 0.0, z], 1.0);
        w.add(format!("CURVE_REPLICA('',#{bottom},#{up})"))
    });
    let curve_replica = prism_file("curve_replica", &half_disc(6.0, replica, None), None);
    // SURFACE_REPLICA: the curved side on a replica of the cylinder about the x axis far away
    let cylinder: SideSurface = Box::new(|w, _| {
        let p = placement(w, PARENT, X, Y);
        let parent = w.add(format!("CYLINDRICAL_SURFACE('',#{p},6.)"));
        let op = onto(w, 0.0);
        (w.add(format!("SURFACE_REPLICA('',#{parent},#{op})")), true)
    });
    let surface_replica = prism_file("surface_replica", &half_disc(6.0, circle(6.0), Some(cylinder)), None);
    let files = [("curve_replica".to_string(), curve_replica, 0, around(HALF_DISC[0])), ("surface_replica".to_string(), surface_replica, 0, around(HALF_DISC[0]))];
    agrees_with_opencascade("step_entities_replicas", &files);
}

/// The half-disc prism of radius 6 below the x axis, its arc and curved side replicas of a
/// circle and a cylinder of radius 3 under the operator (x, -y, z), scale 2 (see below).
fn scaled_replica_file() -> String {
    let arc: CurveAt = Box::new(|w, z| {
        let p = placement(w, [0.0; 3], Z, X);
        let parent = w.add(format!("CIRCLE('',#{p},3.)"));
        let op = operator(w, [X, [0.0, -1.0, 0.0], Z], [0.0, 0.0, z], 2.0);
        w.add(format!("CURVE_REPLICA('',#{parent},#{op})"))
    });
    let cylinder: SideSurface = Box::new(|w, _| {
        let p = placement(w, [0.0; 3], Z, X);
        let parent = w.add(format!("CYLINDRICAL_SURFACE('',#{p},3.)"));
        let op = operator(w, [X, [0.0, -1.0, 0.0], Z], [0.0; 3], 2.0);
        (w.add(format!("SURFACE_REPLICA('',#{parent},#{op})")), false)
    });
    let sides = [line_side([6.0, 0.0], [-6.0, 0.0]), curve_side([-6.0, 0.0], [6.0, 0.0], arc, false, Some(cylinder))];
    prism_file("scaled_replica", &sides, None)
}

#[test]
fn scaled_and_reflected_replicas_have_the_exact_volume() {
    // OpenCASCADE's cartesian operator (StepToGeom's MakeTransformation3d) ignores the scale
    // and axis2, so a scaled or left-handed replica is read there as a rigid motion; fepre
    // follows ISO 10303-42 and the check is the exact volume and area. The operator: scale
    // 2, axes (x, -y, z): the circle of radius 3 becomes one of 6 run clockwise, so the half
    // circle from (6, 0) at 0 to (-6, 0) at π is the lower one, and the cylinder's
    // parametric normal points into it (same_sense .F.).
    agrees_with_exact("step_entities_scaled_replica", "scaled_replica", &scaled_replica_file(), HALF_DISC);
}

/// The volume and area of the half-disc prism of radius 6.
const HALF_DISC: [f64; 2] = [PI * 18.0 * H, PI * 36.0 + PI * 6.0 * H + 12.0 * H];

/// Where OpenCASCADE does not read a file as ISO 10303-42 means it: fepre's certified
/// tessellation, one watertight solid, nothing dropped or turned, against the exact
/// `[volume, area]` (within 0.5 % and 0.25 %).
fn agrees_with_exact(test: &str, name: &str, text: &str, [exact_v, exact_a]: [f64; 2]) {
    let j = tessellate(&write_file(test, name, text)).unwrap_or_else(|e| panic!("{name}: {e}"));
    let (volume, area) = (j["volume"].as_f64().unwrap_or(f64::NAN), j["area"].as_f64().unwrap_or(f64::NAN));
    let (dv, da) = ((volume - exact_v) / exact_v, (area - exact_a) / exact_a);
    eprintln!("{name}: volume {volume:.6} / exact {exact_v:.6} ({:+.4} %), area {area:.6} / exact {exact_a:.6} ({:+.4} %)", 100.0 * dv, 100.0 * da);
    assert_eq!((j["solids"].as_u64(), &j["watertight"]), (Some(1), &serde_json::Value::Bool(true)), "{name}: {j}");
    assert_eq!(j["certificate"]["reoriented"].as_array().map(Vec::len), Some(0), "{name}: {}", j["certificate"]);
    assert!(j["dropped"].as_array().is_some_and(Vec::is_empty), "{name}: {}", j["dropped"]);
    assert!(dv.abs() <= 0.005 && da.abs() <= 0.0025, "{name}: volume {volume}, area {area}");
}

#[test]
fn trimmed_and_curve_bounded_surfaces_agree_with_opencascade() {
    // RECTANGULAR_TRIMMED_SURFACE: the curved side on the cylinder trimmed to u in [0, π],
    // v in [0, H]
    let trimmed: SideSurface = Box::new(|w, _| {
        let p = placement(w, [0.0; 3], Z, X);
        let c = w.add(format!("CYLINDRICAL_SURFACE('',#{p},6.)"));
        (w.add(format!("RECTANGULAR_TRIMMED_SURFACE('',#{c},0.,{PI:?},0.,{H:?},.T.,.T.)")), true)
    });
    let rectangular = prism_file("rectangular_trimmed", &half_disc(6.0, circle(6.0), Some(trimmed)), None);
    // CURVE_BOUNDED_SURFACE: the top face's plane bounded by the composite of its edges'
    // curves (written again; the face's own loop bounds it). OpenCASCADE (7.x through OCP)
    // leaves such a face out (StepToGeom makes no surface of a curve_bounded_surface): the
    // shell stays open, no solid; the check is the exact volume and area
    let bounded = |w: &mut Writer, plane: usize| {
        let diameter = line(w, [-6.0, 0.0, H], [6.0, 0.0, H]);
        let arc = circle(6.0)(w, H);
        let segments = [diameter, arc].map(|c| w.add(format!("COMPOSITE_CURVE_SEGMENT(.CONTINUOUS.,.T.,#{c})")));
        let boundary = w.add(format!("OUTER_BOUNDARY_CURVE('',{},.F.)", refs(&segments)));
        w.add(format!("CURVE_BOUNDED_SURFACE('',#{plane},(#{boundary}),.F.)"))
    };
    let curve_bounded = prism_file("curve_bounded", &half_disc(6.0, circle(6.0), None), Some(&bounded));
    agrees_with_opencascade("step_entities_bounded", &[("rectangular_trimmed".to_string(), rectangular, 0, around(HALF_DISC[0]))]);
    agrees_with_exact("step_entities_bounded", "curve_bounded", &curve_bounded, HALF_DISC);
}

/// B-splines with knots whose knot type is not `.UNSPECIFIED.`; the knots as the type says.
const KNOT_TYPES: [Form; 4] = [
    Form {
        // two Bézier pieces: interior knot of multiplicity 2
        name: "piecewise_bezier_knots",
        degree: 2,
        n: 5,
        surface: |d, rows| format!("B_SPLINE_SURFACE_WITH_KNOTS('',{d},{d},{rows},.UNSPECIFIED.,.F.,.F.,.F.,(3,2,3),(3,2,3),(0.,1.,2.),(0.,1.,2.),.PIECEWISE_BEZIER_KNOTS.)"),
        curve: |d, pts| format!("B_SPLINE_CURVE_WITH_KNOTS('',{d},{pts},.UNSPECIFIED.,.F.,.F.,(3,2,3),(0.,1.,2.),.PIECEWISE_BEZIER_KNOTS.)"),
    },
    Form {
        name: "quasi_uniform_knots",
        degree: 2,
        n: 5,
        surface: |d, rows| format!("B_SPLINE_SURFACE_WITH_KNOTS('',{d},{d},{rows},.UNSPECIFIED.,.F.,.F.,.F.,(3,1,1,3),(3,1,1,3),(0.,1.,2.,3.),(0.,1.,2.,3.),.QUASI_UNIFORM_KNOTS.)"),
        curve: |d, pts| format!("B_SPLINE_CURVE_WITH_KNOTS('',{d},{pts},.UNSPECIFIED.,.F.,.F.,(3,1,1,3),(0.,1.,2.,3.),.QUASI_UNIFORM_KNOTS.)"),
    },
    Form {
        // degree 1: uniform knots interpolate the control points
        name: "uniform_knots",
        degree: 1,
        n: 3,
        surface: |d, rows| format!("B_SPLINE_SURFACE_WITH_KNOTS('',{d},{d},{rows},.UNSPECIFIED.,.F.,.F.,.F.,(1,1,1,1,1),(1,1,1,1,1),(-1.,0.,1.,2.,3.),(-1.,0.,1.,2.,3.),.UNIFORM_KNOTS.)"),
        curve: |d, pts| format!("B_SPLINE_CURVE_WITH_KNOTS('',{d},{pts},.UNSPECIFIED.,.F.,.F.,(1,1,1,1,1),(-1.,0.,1.,2.,3.),.UNIFORM_KNOTS.)"),
    },
    Form {
        name: "rational_piecewise_bezier_knots",
        degree: 2,
        n: 5,
        surface: |d, rows| {
            let w = "((1.,1.,1.,1.,1.),(1.,1.,1.,1.,1.),(1.,1.,2.,1.,1.),(1.,1.,1.,1.,1.),(1.,1.,1.,1.,1.))";
            format!("( BOUNDED_SURFACE() B_SPLINE_SURFACE({d},{d},{rows},.UNSPECIFIED.,.F.,.F.,.F.) B_SPLINE_SURFACE_WITH_KNOTS((3,2,3),(3,2,3),(0.,1.,2.),(0.,1.,2.),.PIECEWISE_BEZIER_KNOTS.) GEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_SURFACE({w}) REPRESENTATION_ITEM('') SURFACE() )")
        },
        curve: |d, pts| format!("( BOUNDED_CURVE() B_SPLINE_CURVE({d},{pts},.UNSPECIFIED.,.F.,.F.) B_SPLINE_CURVE_WITH_KNOTS((3,2,3),(0.,1.,2.),.PIECEWISE_BEZIER_KNOTS.) CURVE() GEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_CURVE((1.,1.,1.,1.,1.)) REPRESENTATION_ITEM('') )"),
    },
];

#[test]
fn bspline_knot_types_agree_with_opencascade() {
    let files = bspline_box_files(&KNOT_TYPES);
    agrees_with_opencascade("step_entities_knot_types", &files);
}

#[test]
fn every_orientation_flag_written_false_agrees_with_opencascade() {
    // ADVANCED_FACE .F. on planes whose axes point in, FACE_BOUND .F. on loops written
    // backwards, EDGE_CURVE .F. on lines written from the far end, ORIENTED_EDGE .F.: the
    // same box, nothing to turn; with a B-spline top too
    let flags = step_file("flags", |w| {
        let shell = box_shell_written(w, [0.0; 3], 10.0, None, true, true);
        w.add(format!("MANIFOLD_SOLID_BREP('box',#{shell})"))
    });
    let flagged = |kind: &str| flags.lines().filter(|l| l.contains(kind)).map(|l| l.ends_with(".F.);")).collect::<Vec<_>>();
    assert_eq!((flagged("=FACE_BOUND("), flagged("=ADVANCED_FACE("), flagged("=EDGE_CURVE(")), (vec![true; 6], vec![true; 6], vec![true; 12]));
    assert!(flagged("=ORIENTED_EDGE(").contains(&true) && !flags.contains("FACE_OUTER_BOUND"));
    let top = &KNOT_TYPES[0];
    let flags_bspline = step_file("flags_bspline", |w| {
        let shell = box_shell_written(w, [0.0; 3], 10.0, Some(top), true, true);
        w.add(format!("MANIFOLD_SOLID_BREP('box',#{shell})"))
    });
    let files = [("flags".to_string(), flags, 0, [999.0, 1001.0]), ("flags_bspline".to_string(), flags_bspline, 0, [1015.0, 1200.0])];
    agrees_with_opencascade("step_entities_flags", &files);
}

/// The 10 mm box with the names of its faces and product replaced by `names` (raw Part 21
/// strings, in the order the faces are written).
fn named_box(names: &[&str]) -> String {
    let mut text = step_file("names", |w| {
        let shell = box_shell(w, [0.0; 3], 10.0, None, true);
        w.add(format!("MANIFOLD_SOLID_BREP('box',#{shell})"))
    });
    for n in names {
        text = text.replacen("ADVANCED_FACE('',", &format!("ADVANCED_FACE('{n}',"), 1);
    }
    text.replace("PRODUCT('names','names'", &format!("PRODUCT('{}','{}'", names[0], names[1]))
}

#[test]
fn names_in_every_string_encoding_agree_with_opencascade() {
    // ISO 10303-21 6.4.3: \X2\ (UCS-2), \X4\ (UCS-4), \X\hh (ISO 8859-1), \S\ (+128), \P?\
    // (the 8859 part for \S\), as CAD systems write non-ASCII names
    let raw = [r"h\X2\00E4\X0\t", r"\X4\0001F600\X0\ ok", r"Gr\X\F6\X\DFe", r"M\S\dller", r"\PA\caf\S\i", r"a\\b"];
    let decoded = ["hät", "\u{1F600} ok", "Größe", "Mäller", "café", "a\\b"];
    let text = named_box(&raw);
    let files = [("names".to_string(), text.clone(), 0, [999.0, 1001.0])];
    agrees_with_opencascade("step_entities_names", &files);
    let path = write_file("step_entities_names", "names_again", &text);
    let j = tessellate(&path).unwrap_or_else(|e| panic!("{e}"));
    let names: Vec<&str> = j["face_table"].as_array().map(|t| t.iter().filter_map(|f| f["name"].as_str()).collect()).unwrap_or_default();
    assert_eq!(names, decoded, "{}", j["face_table"]);
}

#[test]
fn odd_headers_are_read_with_a_note_and_agree_with_opencascade() {
    let body = step_file("header", |w| {
        let shell = box_shell(w, [0.0; 3], 10.0, None, true);
        w.add(format!("MANIFOLD_SOLID_BREP('box',#{shell})"))
    });
    let schema = "FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\n";
    assert!(body.starts_with(HEAD) && HEAD.contains(schema));
    let no_schema = body.replacen(schema, "", 1);
    let long_name = body.replacen("'fepre tests','');", "'fepre tests','','an eighth field');", 1);
    let files = [
        ("no_file_schema".to_string(), no_schema, 0, [999.0, 1001.0]),
        ("file_name_eight_fields".to_string(), long_name, 0, [999.0, 1001.0]),
    ];
    agrees_with_opencascade("step_entities_headers", &files);
    // no HEADER at all: OpenCASCADE refuses the file ("unexpected DATA, expecting HEADER",
    // read status 3); fepre reads it with a note, checked against the exact box
    let no_header = body.replacen(&HEAD["ISO-10303-21;\n".len()..HEAD.len() - "DATA;\n".len()], "", 1);
    assert!(no_header.starts_with("ISO-10303-21;\nDATA;\n"));
    agrees_with_exact("step_entities_headers", "no_header", &no_header, [1000.0, 600.0]);
    let files = [files[0].clone(), files[1].clone(), ("no_header".to_string(), no_header, 0, [0.0; 2])];
    for ((name, text, _, _), want) in files.iter().zip(["lacks FILE_SCHEMA", "FILE_NAME has 8 parameters", "no HEADER section"]) {
        let j = tessellate(&write_file("step_entities_headers", &format!("{name}_again"), text)).unwrap_or_else(|e| panic!("{name}: {e}"));
        let notes = j["notes"].as_array().cloned().unwrap_or_default();
        assert!(notes.len() == 1 && notes[0].as_str().is_some_and(|n| n.contains(want)), "{name}: notes {notes:?}");
    }
}

#[test]
fn replicas_and_offset_curves_survive_our_writer() {
    // what fepre reads it writes back as the same entities (a scaled, reflected replica stays
    // a replica, with its operator; an offset curve an OFFSET_CURVE_3D), and reads again as
    // the same solid
    let (offset, offset_exact) = offset_curve_file();
    let cases = [("scaled_replica", scaled_replica_file(), HALF_DISC, ["CURVE_REPLICA(", "SURFACE_REPLICA("]), ("offset_curve_3d", offset, offset_exact, ["OFFSET_CURVE_3D(", "OFFSET_CURVE_3D("])];
    for (name, text, exact, entities) in cases {
        let model = fepre::cad::step::read_bytes(std::path::Path::new(name), text.as_bytes()).unwrap_or_else(|e| panic!("{name}: {e}"));
        let written = fepre::cad::step::to_string(&model, name).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(entities.iter().all(|e| written.contains(e)), "{name}: {entities:?} not written");
        assert!(!entities[0].contains("REPLICA") || written.contains("CARTESIAN_TRANSFORMATION_OPERATOR_3D('','','',"), "{name}: no operator");
        agrees_with_exact("step_entities_rewritten", &format!("{name}_rewritten"), &written, exact);
    }
}
