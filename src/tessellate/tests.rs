//! Unit tests of the tessellator on B-reps built by hand.

use super::*;
use crate::cad::brep::{Coedge, Edge, EntityRef, Face, Loop, Shell, Solid, Vertex};
use crate::cad::geom::{Curve, Frame, Interval, Line, Plane, Surface};
use crate::mesh::topology::{ReportOptions, surface_report};

/// The tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1) as a B-rep: 4 planar faces, 6 line
/// edges, faces oriented outward by `same_sense`.
fn tetrahedron() -> Model {
    let p = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
    let mut m = Model::default();
    m.vertices = p.iter().map(|&point| Vertex { point, source: EntityRef(0) }).collect();
    let pairs = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];
    for (k, &(a, b)) in pairs.iter().enumerate() {
        m.curves.push(Curve::Line(Line { origin: p[a], direction: p[b] - p[a] }));
        m.edges.push(Edge {
            curve: Some(k as u32),
            start: a as u32,
            end: b as u32,
            range: Interval::new(0.0, 1.0),
            same_sense: true,
            closed: false,
            seam: false,
            degenerate: false,
            source: EntityRef(k as u64 + 1),
        });
    }
    let edge = |a: u32, b: u32| -> Coedge {
        let k = pairs.iter().position(|&(x, y)| (x, y) == (a as usize, b as usize) || (x, y) == (b as usize, a as usize)).unwrap();
        Coedge { edge: k as u32, forward: pairs[k].0 == a as usize }
    };
    // faces as outward counter-clockwise vertex triples
    let faces = [[0u32, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
    m.shells.push(Shell { faces: Vec::new(), closed: true, solid: Some(0), void: false, source: EntityRef(100) });
    m.solids.push(Solid { shells: vec![0], name: None, instance: 0, source: EntityRef(101) });
    for (k, f) in faces.iter().enumerate() {
        let (a, b, c) = (p[f[0] as usize], p[f[1] as usize], p[f[2] as usize]);
        let n = (b - a).cross(c - a);
        // a plane whose normal is inward for odd faces: same_sense false must flip them back
        let flip = k % 2 == 1;
        let z = if flip { -n } else { n };
        let frame = Frame::from_axes(a, Some(z), Some(b - a)).unwrap();
        m.surfaces.push(Surface::Plane(Plane { frame }));
        let fid = FaceId::from_index(k);
        m.loops.push(Loop {
            face: fid,
            outer: true,
            orientation: true,
            coedges: vec![edge(f[0], f[1]), edge(f[1], f[2]), edge(f[2], f[0])],
            vertex: None,
            source: EntityRef(200 + k as u64),
        });
        m.faces.push(Face { surface: k as u32, same_sense: !flip, loops: vec![k as u32], shell: 0, name: None, colour: None, source: EntityRef(300 + k as u64) });
        m.shells[0].faces.push(fid);
    }
    assert!(m.issues(1e-9).is_empty(), "{:?}", m.issues(1e-9));
    m
}

#[test]
fn tetrahedron_is_closed_outward_and_tagged() {
    let m = tetrahedron();
    let t = tessellate(&m, &TessellateOptions::default());
    assert!(t.failed.is_empty(), "{:?}", t.failed);
    t.surface.validate().unwrap();
    assert_eq!(t.surface.triangles.len(), 4);
    assert_eq!(t.surface.vertices.len(), 4, "planar faces with straight edges add no vertex");
    let r = surface_report(&t.surface, &ReportOptions::default());
    assert!(r.closed && r.manifold && r.oriented && r.outward, "{r:?}");
    let v: f64 = r.shells.iter().map(|s| s.volume).sum();
    assert!((v - 1.0 / 6.0).abs() < 1e-12, "{v}");
    let mut tags = t.surface.face_tags.clone();
    tags.sort();
    assert_eq!(tags, vec![FaceId(1), FaceId(2), FaceId(3), FaceId(4)]);
}

/// A face whose sense flag disagrees with its loops and its neighbours is turned back, and
/// the shell closes outward around the tetrahedron's volume.
#[test]
fn a_face_written_against_its_shell_is_turned() {
    let mut m = tetrahedron();
    m.faces[2].same_sense = !m.faces[2].same_sense;
    let mut t = tessellate(&m, &TessellateOptions::default());
    assert!(!surface_report(&t.surface, &ReportOptions::default()).oriented);
    assert_eq!(orient::turn_misoriented_faces(&mut m, &mut t), vec![FaceId::from_index(2)]);
    assert_eq!(m.faces[2].same_sense, tetrahedron().faces[2].same_sense);
    let r = surface_report(&t.surface, &ReportOptions::default());
    assert!(r.closed && r.oriented && r.outward, "{r:?}");
    let v: f64 = r.shells.iter().map(|s| s.volume).sum();
    assert!((v - 1.0 / 6.0).abs() < 1e-12, "{v}");
    // nothing more to turn
    assert!(orient::turn_misoriented_faces(&mut m, &mut t).is_empty());
}

#[test]
fn constraint_parity_keeps_a_concave_face_concave() {
    // an L-shaped planar face: the notch must stay empty
    let pts = [(0.0, 0.0), (2.0, 0.0), (2.0, 1.0), (1.0, 1.0), (1.0, 2.0), (0.0, 2.0)];
    let mut m = Model::default();
    m.vertices = pts.iter().map(|&(x, y)| Vertex { point: DVec3::new(x, y, 0.0), source: EntityRef(0) }).collect();
    let n = pts.len();
    let mut coedges = Vec::new();
    for i in 0..n {
        let (a, b) = (m.vertices[i].point, m.vertices[(i + 1) % n].point);
        m.curves.push(Curve::Line(Line { origin: a, direction: b - a }));
        m.edges.push(Edge { curve: Some(i as u32), start: i as u32, end: ((i + 1) % n) as u32, range: Interval::new(0.0, 1.0), same_sense: true, closed: false, seam: false, degenerate: false, source: EntityRef(i as u64) });
        coedges.push(Coedge { edge: i as u32, forward: true });
    }
    m.surfaces.push(Surface::Plane(Plane { frame: Frame::WORLD }));
    m.shells.push(Shell { faces: vec![FaceId(1)], closed: false, solid: None, void: false, source: EntityRef(50) });
    m.loops.push(Loop { face: FaceId(1), outer: true, orientation: true, coedges, vertex: None, source: EntityRef(51) });
    m.faces.push(Face { surface: 0, same_sense: true, loops: vec![0], shell: 0, name: None, colour: None, source: EntityRef(52) });
    let t = tessellate(&m, &TessellateOptions::default());
    assert!(t.failed.is_empty());
    let area: f64 = t.surface.triangles.iter().map(|tr| {
        let [a, b, c] = tr.map(|i| t.surface.vertices[i as usize]);
        (b - a).cross(c - a).z / 2.0
    }).sum();
    assert!((area - 3.0).abs() < 1e-12, "area {area}");
}

#[test]
fn certificate_of_the_tetrahedron_passes_with_exact_b_rep_values() {
    let m = tetrahedron();
    let t = tessellate(&m, &TessellateOptions::default());
    let c = certificate::certify(&m, &t, &certificate::CertifyOptions::default());
    assert!(c.passed, "{:?}", c.failures);
    assert_eq!(c.shells.len(), 1);
    let sh = &c.shells[0];
    // V - E + F = 4 - 6 + 4, as the mesh sees it
    assert_eq!((sh.euler_mesh, sh.euler_brep, sh.genus_brep), (2, 2, Some(0)));
    assert!((sh.volume_brep - 1.0 / 6.0).abs() < 1e-12 && (sh.volume_mesh - 1.0 / 6.0).abs() < 1e-12, "{sh:?}");
    let area = 1.5 + 3f64.sqrt() / 2.0;
    assert!((sh.area_brep - area).abs() < 1e-12, "{sh:?}");
}

#[test]
fn certificate_passes_an_edge_curve_off_its_vertices_within_a_file_tolerance() {
    // files place vertices off their edge curves within their tolerance (1e-5 mm is common):
    // the area and volume between the chord through the vertices and the curve is the
    // B-rep's own uncertainty, not a fault of the tessellation
    let mut m = tetrahedron();
    let Curve::Line(l) = &mut m.curves[0] else { unreachable!() };
    l.origin += DVec3::new(0.0, -2e-6, -2e-6);
    let t = tessellate(&m, &TessellateOptions::default());
    let c = certificate::certify(&m, &t, &certificate::CertifyOptions::default());
    assert!(c.passed, "{:?}", c.failures);
    // the deviation reached counts the gap between the curve and the vertices' chord
    assert!(c.deviation >= 2e-6 && c.deviation < 1e-5, "{}", c.deviation);
}

#[test]
fn a_pinched_vertex_counts_once_per_sheet() {
    // a 2-manifold's vertices have one piece of link each
    let m = tetrahedron();
    assert!(brep_topology::vertex_umbrellas(&m, &[0, 0, 0, 0]).is_empty());
    // two triangular faces of one group that touch only at vertex 0: two pieces there
    let p = [DVec3::ZERO, DVec3::X, DVec3::Y, -DVec3::X, DVec3::new(0.0, -1.0, 0.5)];
    let mut m = Model::default();
    m.vertices = p.iter().map(|&point| Vertex { point, source: EntityRef(0) }).collect();
    let pairs = [(0, 1), (1, 2), (2, 0), (0, 3), (3, 4), (4, 0)];
    for (k, &(a, b)) in pairs.iter().enumerate() {
        m.curves.push(Curve::Line(Line { origin: p[a], direction: p[b] - p[a] }));
        m.edges.push(Edge { curve: Some(k as u32), start: a as u32, end: b as u32, range: Interval::new(0.0, 1.0), same_sense: true, closed: false, seam: false, degenerate: false, source: EntityRef(k as u64 + 1) });
    }
    for f in 0..2 {
        m.loops.push(Loop {
            face: FaceId::from_index(f),
            outer: true,
            orientation: true,
            coedges: (0..3).map(|k| Coedge { edge: (3 * f + k) as u32, forward: true }).collect(),
            vertex: None,
            source: EntityRef(200 + f as u64),
        });
    }
    let u = brep_topology::vertex_umbrellas(&m, &[0, 0]);
    assert_eq!(u.len(), 1);
    assert_eq!(u.get(&(0, 0)), Some(&2));
    // in different groups each sheet is whole
    assert!(brep_topology::vertex_umbrellas(&m, &[0, 1]).is_empty());
}

#[test]
fn certificate_names_the_face_of_a_hole() {
    let m = tetrahedron();
    let mut t = tessellate(&m, &TessellateOptions::default());
    // drop face 4's triangle: the closed shell's triangles are open there
    let k = t.surface.face_tags.iter().position(|&f| f == FaceId(4)).unwrap();
    t.surface.triangles.remove(k);
    t.surface.face_tags.remove(k);
    if let Some(d) = t.domains[3].as_mut() {
        d.triangles = 0..0;
    }
    for d in t.domains.iter_mut().flatten() {
        if d.triangles.start > k {
            d.triangles = d.triangles.start - 1..d.triangles.end - 1;
        }
    }
    let c = certificate::certify(&m, &t, &certificate::CertifyOptions::default());
    assert!(!c.passed && !c.closed);
    assert!(c.failures.iter().any(|f| f.check == "closed" && f.face.is_some() && f.step_id.is_some()), "{:?}", c.failures);
}

/// Corner angles (degrees) of a 3D triangle.
fn corner_angles(p: [DVec3; 3]) -> [f64; 3] {
    [0, 1, 2].map(|i| {
        let (a, b) = (p[(i + 1) % 3] - p[i], p[(i + 2) % 3] - p[i]);
        a.angle_between(b).to_degrees()
    })
}

/// The longest triangle edge of a surface.
fn longest_edge(s: &crate::mesh::TriSurface) -> f64 {
    s.triangles.iter().flat_map(|t| [0, 1, 2].map(|k| s.vertices[t[k] as usize].distance(s.vertices[t[(k + 1) % 3] as usize]))).fold(0.0, f64::max)
}

#[test]
fn a_size_field_gives_well_shaped_triangles_of_the_size() {
    // the bracket (planes, holes, a fillet): chord-only triangles are long and thin along the
    // holes; sized they are of the size and well shaped, and still certified
    let parts = crate::cad::parts::default_parts().unwrap();
    let (_, m) = parts.iter().find(|(n, _)| n.contains("bracket")).expect("the bracket");
    let h = m.size() / 25.0;
    let thin = |t: &Tessellation| {
        let s = &t.surface;
        s.triangles.iter().filter(|tri| corner_angles(tri.map(|i| s.vertices[i as usize])).iter().any(|&a| a < 20.0)).count() as f64
            / s.triangles.len() as f64
    };
    let plain = tessellate(m, &TessellateOptions::default());
    let sized = super::tessellate_sized(m, &TessellateOptions::default(), &crate::core::size_field::UniformSize(h));
    assert!(thin(&plain) > 0.05, "chord-only thin share {}", thin(&plain));
    assert!(thin(&sized) < 0.01, "sized thin share {}", thin(&sized));
    let s = &sized.surface;
    let longest = longest_edge(s);
    assert!(longest <= 2.0 * h, "longest edge {longest} for size {h}");
    let c = certificate::certify(m, &sized, &certificate::CertifyOptions::default());
    assert!(c.passed, "{:?}", c.failures);
}

/// A rod whose cylinder face is bounded by its two end circles only (no seam edge, as some
/// CAD systems write it): the face mesher joins the circles by a cut of its own.
const ROD: &str = "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('rod','',(''),(''),'','sys','');\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;\n\
#1=CARTESIAN_POINT('',(0.,0.,0.));\n#2=DIRECTION('',(0.,0.,1.));\n#3=DIRECTION('',(1.,0.,0.));\n\
#4=AXIS2_PLACEMENT_3D('',#1,#2,#3);\n#5=CYLINDRICAL_SURFACE('',#4,5.);\n#6=CIRCLE('',#4,5.);\n\
#7=CARTESIAN_POINT('',(5.,0.,0.));\n#8=VERTEX_POINT('',#7);\n#9=EDGE_CURVE('',#8,#8,#6,.T.);\n\
#10=CARTESIAN_POINT('',(0.,0.,200.));\n#11=AXIS2_PLACEMENT_3D('',#10,#2,#3);\n#12=CIRCLE('',#11,5.);\n\
#13=CARTESIAN_POINT('',(5.,0.,200.));\n#14=VERTEX_POINT('',#13);\n#15=EDGE_CURVE('',#14,#14,#12,.T.);\n\
#16=ORIENTED_EDGE('',*,*,#9,.T.);\n#17=EDGE_LOOP('',(#16));\n#18=FACE_BOUND('',#17,.T.);\n\
#19=ORIENTED_EDGE('',*,*,#15,.F.);\n#20=EDGE_LOOP('',(#19));\n#21=FACE_BOUND('',#20,.T.);\n\
#22=ADVANCED_FACE('',(#18,#21),#5,.T.);\n\
#24=DIRECTION('',(0.,0.,-1.));\n#25=AXIS2_PLACEMENT_3D('',#1,#24,#3);\n#26=PLANE('',#25);\n\
#27=ORIENTED_EDGE('',*,*,#9,.F.);\n#28=EDGE_LOOP('',(#27));\n#29=FACE_OUTER_BOUND('',#28,.T.);\n#30=ADVANCED_FACE('',(#29),#26,.T.);\n\
#31=AXIS2_PLACEMENT_3D('',#10,#2,#3);\n#32=PLANE('',#31);\n\
#33=ORIENTED_EDGE('',*,*,#15,.T.);\n#34=EDGE_LOOP('',(#33));\n#35=FACE_OUTER_BOUND('',#34,.T.);\n#36=ADVANCED_FACE('',(#35),#32,.T.);\n\
#37=CLOSED_SHELL('',(#22,#30,#36));\n#38=MANIFOLD_SOLID_BREP('',#37);\n\
#40=( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );\n\
#41=( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNIT_ASSIGNED_CONTEXT((#40)) REPRESENTATION_CONTEXT('','') );\n\
#42=ADVANCED_BREP_SHAPE_REPRESENTATION('',(#4,#38),#41);\nENDSEC;\nEND-ISO-10303-21;\n";

#[test]
fn a_cut_around_a_cylinder_is_sized_like_an_edge() {
    // the cut between the two circles used to be one chord as long as the rod beside the
    // sized points of the face: a fan of needles 200 long on a face sized to 10
    let m = crate::cad::step::read_bytes(std::path::Path::new("rod.stp"), ROD.as_bytes()).unwrap();
    let h = 10.0;
    let sized = super::tessellate_sized(&m, &TessellateOptions::default(), &crate::core::size_field::UniformSize(h));
    let s = &sized.surface;
    let longest = longest_edge(s);
    assert!(longest <= 2.0 * h, "longest edge {longest} for size {h}");
    let sharpest = s.triangles.iter().flat_map(|t| corner_angles(t.map(|i| s.vertices[i as usize]))).fold(180.0, f64::min);
    assert!(sharpest > 10.0, "a corner of {sharpest}°");
    let c = certificate::certify(&m, &sized, &certificate::CertifyOptions::default());
    assert!(c.passed, "{:?}", c.failures);
    // chord-only, the cut is cut like a straight edge on a curved face
    let plain = tessellate(&m, &TessellateOptions::default());
    let s = &plain.surface;
    let longest = longest_edge(s);
    assert!(longest < 100.0, "longest edge {longest} of a rod 200 long");
}

/// A planar face bounded by a conic arc from `A` = `curve(-1)` to `B` = `curve(1)` and the
/// segment back, as STEP text: `conic` is the `PARABOLA(...)` or `HYPERBOLA(...)` entity on
/// placement `#4` (vertex or centre at the origin, axis `x`).
fn conic_face(conic: &str, a: DVec3, b: DVec3) -> String {
    let p = |v: DVec3| format!("({:?},{:?},0.)", v.x, v.y);
    format!(
        "ISO-10303-21;\nHEADER;\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;\n\
#1=CARTESIAN_POINT('',(0.,0.,0.));#2=DIRECTION('',(0.,0.,1.));#3=DIRECTION('',(1.,0.,0.));\
#4=AXIS2_PLACEMENT_3D('',#1,#2,#3);#5=PLANE('',#4);#6={conic};\
#11=CARTESIAN_POINT('',{});#12=CARTESIAN_POINT('',{});#21=VERTEX_POINT('',#11);#22=VERTEX_POINT('',#12);\
#30=DIRECTION('',(0.,1.,0.));#31=VECTOR('',#30,1.);#32=LINE('',#11,#31);\
#41=EDGE_CURVE('',#21,#22,#32,.T.);#42=EDGE_CURVE('',#21,#22,#6,.T.);\
#51=ORIENTED_EDGE('',*,*,#41,.T.);#52=ORIENTED_EDGE('',*,*,#42,.F.);\
#60=EDGE_LOOP('',(#51,#52));#61=FACE_OUTER_BOUND('',#60,.T.);#62=ADVANCED_FACE('conic',(#61),#5,.T.);\
#70=OPEN_SHELL('',(#62));#71=SHELL_BASED_SURFACE_MODEL('',(#70));\
#80=( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );\
#81=( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNIT_ASSIGNED_CONTEXT((#80)) REPRESENTATION_CONTEXT('','') );\
#90=MANIFOLD_SURFACE_SHAPE_REPRESENTATION('',(#4,#71),#81);\nENDSEC;\nEND-ISO-10303-21;\n",
        p(a),
        p(b)
    )
}

#[test]
fn faces_bounded_by_a_parabola_or_a_hyperbola_have_their_area() {
    let (f, ha, hb) = (2.0f64, 3.0f64, 2.0f64);
    let u = 1.0f64;
    let cases = [
        // the segment of a parabola cut by its latus rectum: 8 f² / 3
        (format!("PARABOLA('',#4,{f:?})"), DVec3::new(f, -2.0 * f, 0.0), DVec3::new(f, 2.0 * f, 0.0), 8.0 * f * f / 3.0),
        // a hyperbola's segment cut at x = a cosh u: a b (sinh 2u / 2 − u)
        (format!("HYPERBOLA('',#4,{ha:?},{hb:?})"), DVec3::new(ha * u.cosh(), -hb * u.sinh(), 0.0), DVec3::new(ha * u.cosh(), hb * u.sinh(), 0.0), ha * hb * ((2.0 * u).sinh() / 2.0 - u)),
    ];
    for (conic, a, b, want) in cases {
        let m = crate::cad::step::read_bytes(std::path::Path::new("conic.stp"), conic_face(&conic, a, b).as_bytes()).unwrap_or_else(|e| panic!("{conic}: {e}"));
        assert!(m.dropped.is_empty(), "{conic}: {:?}", m.dropped);
        let t = tessellate(&m, &TessellateOptions::default());
        assert!(t.failed.is_empty(), "{conic}: {:?}", t.failed);
        let s = &t.surface;
        let area: f64 = s.triangles.iter().map(|tr| 0.5 * (s.vertices[tr[1] as usize] - s.vertices[tr[0] as usize]).cross(s.vertices[tr[2] as usize] - s.vertices[tr[0] as usize]).length()).sum();
        assert!((area / want - 1.0).abs() < 1e-3, "{conic}: area {area} against {want}");
        // the face is read back the same from fepre's own STEP writer
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("conic.step");
        crate::cad::step::write(&path, &m, "conic").unwrap();
        let again = crate::cad::step::read(&path).unwrap();
        assert_eq!(again.curves.iter().map(|c| c.kind()).collect::<Vec<_>>(), m.curves.iter().map(|c| c.kind()).collect::<Vec<_>>());
    }
}

#[test]
fn a_sliver_between_close_arcs_is_meshed_by_splitting_its_crossing_chords() {
    // a planar crescent between an arc of radius 10 over [0, π] and one 0.001 inside it over
    // [0.05, π - 0.05]: the chord tolerance (2e-4 of the model size, about 0.0045) lets the
    // outer chords cut 0.003 inside their arc, across the inner arc's points, so the loop
    // crosses itself until the crossing chords are split
    let (big, d) = (10.0, 0.05);
    let small = big - 0.001;
    let polar = |r: f64, t: f64| DVec3::new(r * t.cos(), r * t.sin(), 0.0);
    let mut m = Model::default();
    let corners = [polar(big, 0.0), polar(big, std::f64::consts::PI), polar(small, std::f64::consts::PI - d), polar(small, d)];
    m.vertices = corners.iter().map(|&point| Vertex { point, source: EntityRef(0) }).collect();
    let circle = |r: f64| Curve::Circle(crate::cad::geom::Circle { frame: Frame::WORLD, radius: r });
    let line = |a: DVec3, b: DVec3| Curve::Line(Line { origin: a, direction: b - a });
    m.curves = vec![circle(big), line(corners[1], corners[2]), circle(small), line(corners[3], corners[0])];
    let ranges = [Interval::new(0.0, std::f64::consts::PI), Interval::new(0.0, 1.0), Interval::new(d, std::f64::consts::PI - d), Interval::new(0.0, 1.0)];
    // edges: outer arc 0 -> 1, line 1 -> 2, inner arc 3 -> 2 (used backwards), line 3 -> 0
    let ends = [(0, 1), (1, 2), (3, 2), (3, 0)];
    for (k, (&(start, end), range)) in ends.iter().zip(ranges).enumerate() {
        m.edges.push(Edge { curve: Some(k as u32), start, end, range, same_sense: true, closed: false, seam: false, degenerate: false, source: EntityRef(k as u64 + 1) });
    }
    let coedges = vec![Coedge { edge: 0, forward: true }, Coedge { edge: 1, forward: true }, Coedge { edge: 2, forward: false }, Coedge { edge: 3, forward: true }];
    m.surfaces.push(Surface::Plane(Plane { frame: Frame::WORLD }));
    m.shells.push(Shell { faces: vec![FaceId(1)], closed: false, solid: None, void: false, source: EntityRef(50) });
    m.loops.push(Loop { face: FaceId(1), outer: true, orientation: true, coedges: coedges.clone(), vertex: None, source: EntityRef(51) });
    m.faces.push(Face { surface: 0, same_sense: true, loops: vec![0], shell: 0, name: None, colour: None, source: EntityRef(52) });
    let t = tessellate(&m, &TessellateOptions::default());
    assert!(t.failed.is_empty(), "{:?}", t.failed);
    // no fold: every triangle faces +z, and together they cover exactly the boundary polygon
    let v = &t.surface.vertices;
    let areas: Vec<f64> = t.surface.triangles.iter().map(|tr| {
        let [a, b, c] = tr.map(|i| v[i as usize]);
        (b - a).cross(c - a).z / 2.0
    }).collect();
    assert!(areas.iter().all(|&a| a > 0.0), "a triangle folds over");
    let mut ring: Vec<DVec3> = Vec::new();
    for c in &coedges {
        let ids = &t.edges[c.edge as usize].ids;
        let ids: Vec<u32> = if c.forward { ids.clone() } else { ids.iter().rev().copied().collect() };
        ring.extend(ids[..ids.len() - 1].iter().map(|&i| v[i as usize]));
    }
    let polygon: f64 = (0..ring.len()).map(|i| ring[i].truncate().perp_dot(ring[(i + 1) % ring.len()].truncate())).sum::<f64>() / 2.0;
    let total: f64 = areas.iter().sum();
    assert!((total - polygon).abs() <= 1e-9 * polygon.abs().max(1e-12) + 1e-15, "triangles {total}, polygon {polygon}");
    assert!(polygon > 0.0, "the boundary polygon turns the wrong way: {polygon}");
}

/// A sphere of radius 10 about the origin written as two lunes between the meridians at
/// azimuths `a1 < a2` (each a half circle from the north pole to the south pole), as several
/// CAD systems write spheres: face 1 spans `u` in `(a1, a2)`, face 2 the rest.
fn sphere_of_two_lunes(a1: f64, a2: f64) -> String {
    let meridian = |k: usize, a: f64| {
        let (c, s) = (a.cos(), a.sin());
        format!(
            "#{d1}=DIRECTION('',({:?},{:?},0.));#{d2}=DIRECTION('',({c:?},{s:?},0.));#{ax}=AXIS2_PLACEMENT_3D('',#1,#{d1},#{d2});\
#{ci}=CIRCLE('',#{ax},10.);#{ec}=EDGE_CURVE('',#21,#22,#{ci},.T.);",
            -s,
            c,
            d1 = 100 + 10 * k,
            d2 = 101 + 10 * k,
            ax = 102 + 10 * k,
            ci = 103 + 10 * k,
            ec = 104 + 10 * k
        )
    };
    format!(
        "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('lunes','',(''),(''),'','','');\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;\n\
#1=CARTESIAN_POINT('',(0.,0.,0.));#2=DIRECTION('',(0.,0.,1.));#3=DIRECTION('',(1.,0.,0.));\
#4=AXIS2_PLACEMENT_3D('',#1,#2,#3);#5=SPHERICAL_SURFACE('',#4,10.);\
#11=CARTESIAN_POINT('',(0.,0.,10.));#12=CARTESIAN_POINT('',(0.,0.,-10.));#21=VERTEX_POINT('',#11);#22=VERTEX_POINT('',#12);\
{}{}\
#51=ORIENTED_EDGE('',*,*,#114,.T.);#52=ORIENTED_EDGE('',*,*,#124,.F.);#53=EDGE_LOOP('',(#51,#52));#54=FACE_OUTER_BOUND('',#53,.T.);\
#55=ADVANCED_FACE('a',(#54),#5,.T.);\
#61=ORIENTED_EDGE('',*,*,#124,.T.);#62=ORIENTED_EDGE('',*,*,#114,.F.);#63=EDGE_LOOP('',(#61,#62));#64=FACE_OUTER_BOUND('',#63,.T.);\
#65=ADVANCED_FACE('b',(#64),#5,.T.);\
#70=CLOSED_SHELL('',(#55,#65));#71=MANIFOLD_SOLID_BREP('',#70);\
#80=( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );\
#81=( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNIT_ASSIGNED_CONTEXT((#80)) REPRESENTATION_CONTEXT('','') );\
#90=ADVANCED_BREP_SHAPE_REPRESENTATION('',(#4,#71),#81);\nENDSEC;\nEND-ISO-10303-21;\n",
        meridian(1, a1),
        meridian(2, a2)
    )
}

#[test]
fn a_sphere_written_as_two_lunes_meshes_each_on_its_own_side() {
    use crate::tessellate::certificate::{CertifyOptions, certify};
    // lunes of half a turn (the jump across the poles is half a turn either way: the loop's
    // sense decides) with a meridian on the seam, off it, and lunes of unequal width
    for (a1, a2) in [(0.0, std::f64::consts::PI), (std::f64::consts::FRAC_PI_2, 1.5 * std::f64::consts::PI), (0.3, 2.0), (-2.5, 0.1)] {
        let m = crate::cad::step::read_bytes(std::path::Path::new("lunes.stp"), sphere_of_two_lunes(a1, a2).as_bytes()).unwrap_or_else(|e| panic!("{a1} {a2}: {e}"));
        let t = tessellate(&m, &TessellateOptions::default());
        assert!(t.failed.is_empty(), "{a1} {a2}: {:?}", t.failed);
        let cert = certify(&m, &t, &CertifyOptions::default());
        assert!(cert.passed, "{a1} {a2}: {:?}", cert.failures.iter().take(5).collect::<Vec<_>>());
        let want = 4.0 / 3.0 * std::f64::consts::PI * 1000.0;
        assert!((cert.volume[0] / want - 1.0).abs() < 5e-3, "{a1} {a2}: volume {} against {want}", cert.volume[0]);
        // every triangle of face 1 lies between the meridians, every one of face 2 outside
        let s = &t.surface;
        for (tr, tag) in s.triangles.iter().zip(&s.face_tags) {
            let c = tr.iter().map(|&i| s.vertices[i as usize]).sum::<DVec3>() / 3.0;
            let inside = (c.y.atan2(c.x) - a1).rem_euclid(std::f64::consts::TAU) < a2 - a1;
            assert_eq!(inside, *tag == FaceId(1), "{a1} {a2}: a triangle of face {tag:?} at {c} is on the wrong side");
        }
    }
}

#[test]
fn a_sized_sphere_has_no_fans_of_needles_at_its_poles() {
    use crate::tessellate::certificate::{CertifyOptions, certify};
    // the domain refinement is isotropic in scaled (u, v), where a whole period of u shrinks
    // to each pole: without the shape improvement a valence near 90 and corners of 2° there
    let m = crate::cad::step::read_bytes(std::path::Path::new("lunes.stp"), sphere_of_two_lunes(0.3, 2.0).as_bytes()).unwrap();
    let h = 1.4;
    let t = super::tessellate_sized(&m, &TessellateOptions::default(), &crate::core::size_field::UniformSize(h));
    assert!(t.failed.is_empty(), "{:?}", t.failed);
    let cert = certify(&m, &t, &CertifyOptions::default());
    assert!(cert.passed, "{:?}", cert.failures.iter().take(5).collect::<Vec<_>>());
    let s = &t.surface;
    let smallest = s.triangles.iter().flat_map(|tri| corner_angles(tri.map(|i| s.vertices[i as usize]))).fold(180.0, f64::min);
    assert!(smallest >= 25.0, "smallest corner {smallest}°");
    let mut valence = vec![0usize; s.vertices.len()];
    for tri in &s.triangles {
        for &i in tri {
            valence[i as usize] += 1;
        }
    }
    for (i, p) in s.vertices.iter().enumerate() {
        if (p.z.abs() - 10.0).abs() < 1e-9 {
            assert!(valence[i] <= 12, "valence {} at the pole {p}", valence[i]);
        }
    }
    assert!(longest_edge(s) <= 2.0 * h, "longest edge {}", longest_edge(s));
}

#[test]
fn a_lens_face_whose_two_edges_are_one_segment_each_is_split_and_meshed() {
    // a planar face between a line and an arc of radius 1000 over the same 1 mm chord (a
    // sliver face like those between a cylinder and a nearly tangent plane): sizing at 5 mm
    // makes each side one piece, the same segment twice; each is split at its middle
    use crate::cad::geom::Circle;
    use crate::core::size_field::UniformSize;
    let (a, b) = (DVec3::ZERO, DVec3::X);
    let r: f64 = 1000.0;
    let delta = (0.5 / r).asin();
    let centre = DVec3::new(0.5, -r * delta.cos(), 0.0);
    let mut m = Model::default();
    m.vertices = [a, b].iter().map(|&point| Vertex { point, source: EntityRef(0) }).collect();
    m.curves.push(Curve::Line(Line { origin: a, direction: b - a }));
    m.curves.push(Curve::Circle(Circle { frame: Frame::from_axes(centre, Some(DVec3::Z), Some(DVec3::X)).unwrap(), radius: r }));
    let edge = |curve: u32, start: u32, end: u32, range: Interval| Edge { curve: Some(curve), start, end, range, same_sense: true, closed: false, seam: false, degenerate: false, source: EntityRef(1 + curve as u64) };
    m.edges.push(edge(0, 0, 1, Interval::new(0.0, 1.0)));
    m.edges.push(edge(1, 1, 0, Interval::new(std::f64::consts::FRAC_PI_2 - delta, std::f64::consts::FRAC_PI_2 + delta)));
    m.surfaces.push(Surface::Plane(Plane { frame: Frame::from_axes(DVec3::ZERO, Some(DVec3::Z), Some(DVec3::X)).unwrap() }));
    let fid = FaceId::from_index(0);
    m.loops.push(Loop { face: fid, outer: true, orientation: true, coedges: vec![Coedge { edge: 0, forward: true }, Coedge { edge: 1, forward: true }], vertex: None, source: EntityRef(10) });
    m.faces.push(Face { surface: 0, same_sense: true, loops: vec![0], shell: 0, name: None, colour: None, source: EntityRef(11) });
    m.shells.push(Shell { faces: vec![fid], closed: false, solid: None, void: false, source: EntityRef(12) });
    let t = tessellate_sized(&m, &TessellateOptions::default(), &UniformSize(5.0));
    assert!(t.failed.is_empty(), "{:?}", t.failed);
    assert!(t.edges.iter().all(|e| e.ids.len() == 3), "{:?}", t.edges.iter().map(|e| e.ids.len()).collect::<Vec<_>>());
    // the midpoints lie on their curves: the lens keeps area, under the exact 2/3 c s
    let area: f64 = t.surface.triangles.iter().map(|tri| 0.5 * (t.surface.vertices[tri[1] as usize] - t.surface.vertices[tri[0] as usize]).cross(t.surface.vertices[tri[2] as usize] - t.surface.vertices[tri[0] as usize]).length()).sum();
    let sagitta = r - r * delta.cos();
    assert!(area > 0.49 * sagitta && area <= 2.0 / 3.0 * sagitta * (1.0 + 1e-6), "{area} against {}", 2.0 / 3.0 * sagitta);
}

/// A band of a torus (R = 3, r = 1, axis z) between its outer equator (v = 0) and its top
/// circle (v = π/2), as STEP text: `quarter` the band between them, else the other three
/// quarters of the tube, chosen by the circles' senses alone.
fn torus_band(quarter: bool) -> String {
    let (a, b) = if quarter { (".T.", ".F.") } else { (".F.", ".T.") };
    format!(
        "ISO-10303-21;\nHEADER;\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;\n\
#1=CARTESIAN_POINT('',(0.,0.,0.));#2=DIRECTION('',(0.,0.,1.));#3=DIRECTION('',(1.,0.,0.));\
#4=AXIS2_PLACEMENT_3D('',#1,#2,#3);#5=TOROIDAL_SURFACE('',#4,3.,1.);\
#6=CARTESIAN_POINT('',(0.,0.,1.));#7=AXIS2_PLACEMENT_3D('',#6,#2,#3);\
#8=CIRCLE('',#4,4.);#9=CIRCLE('',#7,3.);\
#11=CARTESIAN_POINT('',(4.,0.,0.));#12=CARTESIAN_POINT('',(3.,0.,1.));#21=VERTEX_POINT('',#11);#22=VERTEX_POINT('',#12);\
#41=EDGE_CURVE('',#21,#21,#8,.T.);#42=EDGE_CURVE('',#22,#22,#9,.T.);\
#51=ORIENTED_EDGE('',*,*,#41,{a});#52=ORIENTED_EDGE('',*,*,#42,{b});\
#55=EDGE_LOOP('',(#51));#56=EDGE_LOOP('',(#52));#57=FACE_BOUND('',#55,.T.);#58=FACE_BOUND('',#56,.T.);\
#62=ADVANCED_FACE('band',(#57,#58),#5,.T.);\
#70=OPEN_SHELL('',(#62));#71=SHELL_BASED_SURFACE_MODEL('',(#70));\
#80=( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );\
#81=( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNIT_ASSIGNED_CONTEXT((#80)) REPRESENTATION_CONTEXT('','') );\
#90=MANIFOLD_SURFACE_SHAPE_REPRESENTATION('',(#4,#71),#81);\nENDSEC;\nEND-ISO-10303-21;\n"
    )
}

/// Two circles split a torus into two bands: the one on the face's side of its loops is
/// meshed, whichever way round the tube it runs (area 2πr(R·Δv + r·Δsin v)).
#[test]
fn a_torus_band_between_two_circles_is_the_side_its_loops_bound() {
    use std::f64::consts::PI;
    let quarter = 2.0 * PI * (3.0 * PI / 2.0 + 1.0);
    for (q, want) in [(true, quarter), (false, 4.0 * PI * PI * 3.0 - quarter)] {
        let m = crate::cad::step::read_bytes(std::path::Path::new("band.stp"), torus_band(q).as_bytes()).unwrap();
        let t = tessellate(&m, &TessellateOptions::default());
        assert!(t.failed.is_empty(), "{q}: {:?}", t.failed);
        let s = &t.surface;
        let area: f64 = s.triangles.iter().map(|tr| 0.5 * (s.vertices[tr[1] as usize] - s.vertices[tr[0] as usize]).cross(s.vertices[tr[2] as usize] - s.vertices[tr[0] as usize]).length()).sum();
        assert!((area / want - 1.0).abs() < 2e-3, "{q}: area {area} against {want}");
        // outward from the tube (same_sense): the triangles' normals point away from its core
        let c = s.triangles[0].map(|v| s.vertices[v as usize]);
        let n = (c[1] - c[0]).cross(c[2] - c[0]);
        let mid = (c[0] + c[1] + c[2]) / 3.0;
        let core = DVec3::new(mid.x, mid.y, 0.0).normalize() * 3.0;
        assert!(n.dot(mid - core) > 0.0, "{q}");
    }
}

/// A STEP file of one solid: the header, `data` (entities up to the solid `#71` and its
/// placement `#4`) and millimetre units.
fn step_text(name: &str, data: &str) -> String {
    format!(
        "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('{name}','',(''),(''),'','','');\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;\n{data}\
#80=( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );\
#81=( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNIT_ASSIGNED_CONTEXT((#80)) REPRESENTATION_CONTEXT('','') );\
#90=ADVANCED_BREP_SHAPE_REPRESENTATION('',(#4,#71),#81);\nENDSEC;\nEND-ISO-10303-21;\n"
    )
}

/// `step` tessellated plainly and to a uniform size of 1.5, each certified, its triangles
/// within 0.5 % of the volume `want` and its B-rep's quadrature within 1e-4 of it (`label` in
/// the messages).
fn certified_both_ways(step: &str, want: f64, label: &str) -> Vec<Tessellation> {
    use crate::tessellate::certificate::{CertifyOptions, certify};
    let m = crate::cad::step::read_bytes(std::path::Path::new("test.stp"), step.as_bytes()).unwrap_or_else(|e| panic!("{label}: {e}"));
    [false, true]
        .into_iter()
        .map(|sized| {
            let t = if sized { super::tessellate_sized(&m, &TessellateOptions::default(), &crate::core::size_field::UniformSize(1.5)) } else { tessellate(&m, &TessellateOptions::default()) };
            assert!(t.failed.is_empty(), "{label} {sized}: {:?}", t.failed);
            let cert = certify(&m, &t, &CertifyOptions::default());
            assert!(cert.passed, "{label} {sized}: {:?}", cert.failures.iter().take(5).collect::<Vec<_>>());
            assert!((cert.volume[0] / want - 1.0).abs() < 5e-3, "{label} {sized}: volume {} against {want}", cert.volume[0]);
            assert!((cert.volume[1] / want - 1.0).abs() < 1e-4, "{label} {sized}: B-rep volume {} against {want}", cert.volume[1]);
            t
        })
        .collect()
}

/// A ball of radius 10 about the origin, its sphere's axis along `axis` and its seam's side
/// along `seam`, with the caps beyond `x = ±6` cut off flat: the sphere face's two loops
/// (circles of radius 8) are holes in `(u, v)` that go around neither pole, as where a hole is
/// drilled across a ball's axis.
fn ball_cut_across_its_axis(axis: [f64; 3], seam: [f64; 3]) -> String {
    let d = |v: [f64; 3]| format!("({:?},{:?},{:?})", v[0], v[1], v[2]);
    let data = format!(
        "#1=CARTESIAN_POINT('',(0.,0.,0.));#2=DIRECTION('',{});#3=DIRECTION('',{});\
#4=AXIS2_PLACEMENT_3D('',#1,#2,#3);#5=SPHERICAL_SURFACE('',#4,10.);\
#6=DIRECTION('',(1.,0.,0.));#7=DIRECTION('',(0.,1.,0.));\
#11=CARTESIAN_POINT('',(6.,0.,0.));#12=AXIS2_PLACEMENT_3D('',#11,#6,#7);#13=CIRCLE('',#12,8.);#14=PLANE('',#12);\
#15=CARTESIAN_POINT('',(6.,8.,0.));#16=VERTEX_POINT('',#15);#17=EDGE_CURVE('',#16,#16,#13,.T.);\
#21=CARTESIAN_POINT('',(-6.,0.,0.));#22=AXIS2_PLACEMENT_3D('',#21,#6,#7);#23=CIRCLE('',#22,8.);#24=PLANE('',#22);\
#25=CARTESIAN_POINT('',(-6.,8.,0.));#26=VERTEX_POINT('',#25);#27=EDGE_CURVE('',#26,#26,#23,.T.);\
#31=ORIENTED_EDGE('',*,*,#17,.F.);#32=EDGE_LOOP('',(#31));#33=FACE_BOUND('',#32,.T.);\
#34=ORIENTED_EDGE('',*,*,#27,.T.);#35=EDGE_LOOP('',(#34));#36=FACE_BOUND('',#35,.T.);\
#37=ADVANCED_FACE('band',(#33,#36),#5,.T.);\
#41=ORIENTED_EDGE('',*,*,#17,.T.);#42=EDGE_LOOP('',(#41));#43=FACE_OUTER_BOUND('',#42,.T.);#44=ADVANCED_FACE('right',(#43),#14,.T.);\
#51=ORIENTED_EDGE('',*,*,#27,.F.);#52=EDGE_LOOP('',(#51));#53=FACE_OUTER_BOUND('',#52,.T.);#54=ADVANCED_FACE('left',(#53),#24,.F.);\
#70=CLOSED_SHELL('',(#37,#44,#54));#71=MANIFOLD_SOLID_BREP('',#70);",
        d(axis),
        d(seam)
    );
    step_text("ball", &data)
}

#[test]
fn a_ball_cut_across_its_axis_keeps_the_band_between_its_two_openings() {
    // the ball minus two caps of height 4: 4/3 π 1000 − 2 π 4² (30 − 4) / 3 = 1056 π
    let want = 1056.0 * std::f64::consts::PI;
    // the seam's side through the opening at +x (it straddles u = 0), beside it, and a tilted axis
    for (axis, seam) in [([0.0, 0.0, 1.0], [1.0, 0.0, 0.0]), ([0.0, 0.0, 1.0], [0.0, 1.0, 0.0]), ([0.0, 0.6, 0.8], [1.0, 0.0, 0.0])] {
        for t in certified_both_ways(&ball_cut_across_its_axis(axis, seam), want, &format!("{axis:?}")) {
            // every triangle of the sphere face lies between the openings
            let s = &t.surface;
            for (tr, tag) in s.triangles.iter().zip(&s.face_tags) {
                let c = tr.iter().map(|&i| s.vertices[i as usize]).sum::<DVec3>() / 3.0;
                if *tag == FaceId(1) {
                    assert!(c.x.abs() < 6.0, "{axis:?}: a triangle of the band at {c}, beyond an opening");
                }
            }
        }
    }
}

/// Half a ball of radius 10 about the origin, `z ≥ 0`, its sphere's axis along `axis` (in the
/// flat face's plane): the rim is a great circle through both of the sphere's poles, with its
/// one vertex at `(0, 10, 0)`.
fn half_ball_with_its_poles_on_the_rim(axis: [f64; 3], seam: [f64; 3]) -> String {
    let d = |v: [f64; 3]| format!("({:?},{:?},{:?})", v[0], v[1], v[2]);
    let data = format!(
        "#1=CARTESIAN_POINT('',(0.,0.,0.));#2=DIRECTION('',{});#3=DIRECTION('',{});\
#4=AXIS2_PLACEMENT_3D('',#1,#2,#3);#5=SPHERICAL_SURFACE('',#4,10.);\
#6=DIRECTION('',(0.,0.,1.));#7=DIRECTION('',(0.,1.,0.));#8=AXIS2_PLACEMENT_3D('',#1,#6,#7);#9=CIRCLE('',#8,10.);#10=PLANE('',#8);\
#15=CARTESIAN_POINT('',(0.,10.,0.));#16=VERTEX_POINT('',#15);#17=EDGE_CURVE('',#16,#16,#9,.T.);\
#31=ORIENTED_EDGE('',*,*,#17,.T.);#32=EDGE_LOOP('',(#31));#33=FACE_OUTER_BOUND('',#32,.T.);#37=ADVANCED_FACE('dome',(#33),#5,.T.);\
#41=ORIENTED_EDGE('',*,*,#17,.F.);#42=EDGE_LOOP('',(#41));#43=FACE_OUTER_BOUND('',#42,.T.);#44=ADVANCED_FACE('flat',(#43),#10,.F.);\
#70=CLOSED_SHELL('',(#37,#44));#71=MANIFOLD_SOLID_BREP('',#70);",
        d(axis),
        d(seam)
    );
    step_text("dome", &data)
}

#[test]
fn a_half_ball_whose_rim_passes_through_the_spheres_poles_is_closed() {
    let want = 2.0 / 3.0 * std::f64::consts::PI * 1000.0;
    // the poles at ±x and on a slant, the seam's side up and along the flat face
    let slant = [0.6, 0.8, 0.0];
    for (axis, seam) in [([1.0, 0.0, 0.0], [0.0, 0.0, 1.0]), ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]), (slant, [0.0, 0.0, 1.0])] {
        for t in certified_both_ways(&half_ball_with_its_poles_on_the_rim(axis, seam), want, &format!("{axis:?}")) {
            // each pole is a point of the rim, shared by both faces
            for sign in [-1.0, 1.0] {
                let pole = DVec3::from(axis) * 10.0 * sign;
                assert!(t.surface.vertices.iter().any(|v| v.distance(pole) < 1e-9), "{axis:?}: no point at the pole {pole}");
            }
        }
    }
}

/// Half a ball of radius 10 about the origin, `z ≥ 0`, its sphere's axis along `z` and its seam's
/// side along `seam`, whose dome is cut open along a meridian: the dome's one loop is the
/// equator, then the meridian from `(10, 0, 0)` up to the pole and back down (an edge used
/// twice, as where a CAD system splits a dome's seam off its parametric one).
fn dome_cut_open_along_a_meridian(seam: [f64; 3]) -> String {
    let data = format!(
        "#1=CARTESIAN_POINT('',(0.,0.,0.));#2=DIRECTION('',(0.,0.,1.));#3=DIRECTION('',({:?},{:?},{:?}));\
#4=AXIS2_PLACEMENT_3D('',#1,#2,#3);#5=SPHERICAL_SURFACE('',#4,10.);\
#6=DIRECTION('',(1.,0.,0.));#7=DIRECTION('',(0.,-1.,0.));#8=AXIS2_PLACEMENT_3D('',#1,#2,#6);#9=CIRCLE('',#8,10.);#10=PLANE('',#8);\
#11=AXIS2_PLACEMENT_3D('',#1,#7,#6);#12=CIRCLE('',#11,10.);\
#15=CARTESIAN_POINT('',(10.,0.,0.));#16=VERTEX_POINT('',#15);#17=CARTESIAN_POINT('',(0.,0.,10.));#18=VERTEX_POINT('',#17);\
#19=EDGE_CURVE('',#16,#16,#9,.T.);#20=EDGE_CURVE('',#16,#18,#12,.T.);\
#31=ORIENTED_EDGE('',*,*,#19,.T.);#32=ORIENTED_EDGE('',*,*,#20,.T.);#33=ORIENTED_EDGE('',*,*,#20,.F.);\
#34=EDGE_LOOP('',(#31,#32,#33));#35=FACE_OUTER_BOUND('',#34,.T.);#37=ADVANCED_FACE('dome',(#35),#5,.T.);\
#41=ORIENTED_EDGE('',*,*,#19,.F.);#42=EDGE_LOOP('',(#41));#43=FACE_OUTER_BOUND('',#42,.T.);#44=ADVANCED_FACE('flat',(#43),#10,.F.);\
#70=CLOSED_SHELL('',(#37,#44));#71=MANIFOLD_SOLID_BREP('',#70);",
        seam[0],
        seam[1],
        seam[2]
    );
    step_text("slit", &data)
}

#[test]
fn a_dome_cut_open_along_a_meridian_meshes_around_its_pole() {
    let want = 2.0 / 3.0 * std::f64::consts::PI * 1000.0;
    // the cut a quarter turn from the sphere's seam, on it, and half a turn from it
    for seam in [[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]] {
        assert_eq!(certified_both_ways(&dome_cut_open_along_a_meridian(seam), want, &format!("{seam:?}")).len(), 2);
    }
}

/// A whole ball of radius 10 whose one face is bounded by a single meridian from pole to pole,
/// used there and back (the face slit along it, as a CAD system writes a full sphere), the
/// sphere's seam along `seam`, the bound's flag `bound`.
fn ball_slit_along_a_meridian(seam: [f64; 3], bound: bool) -> String {
    let data = format!(
        "#1=CARTESIAN_POINT('',(0.,0.,0.));#2=DIRECTION('',(0.,0.,1.));#3=DIRECTION('',({:?},{:?},{:?}));\
#4=AXIS2_PLACEMENT_3D('',#1,#2,#3);#5=SPHERICAL_SURFACE('',#4,10.);\
#6=DIRECTION('',(1.,0.,0.));#7=DIRECTION('',(0.,-1.,0.));#11=AXIS2_PLACEMENT_3D('',#1,#7,#6);#12=CIRCLE('',#11,10.);\
#15=CARTESIAN_POINT('',(0.,0.,10.));#16=VERTEX_POINT('',#15);#17=CARTESIAN_POINT('',(0.,0.,-10.));#18=VERTEX_POINT('',#17);\
#20=EDGE_CURVE('',#16,#18,#12,.T.);\
#32=ORIENTED_EDGE('',*,*,#20,.T.);#33=ORIENTED_EDGE('',*,*,#20,.F.);\
#34=EDGE_LOOP('',(#32,#33));#35=FACE_OUTER_BOUND('',#34,{});#37=ADVANCED_FACE('ball',(#35),#5,.T.);\
#70=CLOSED_SHELL('',(#37));#71=MANIFOLD_SOLID_BREP('',#70);",
        seam[0],
        seam[1],
        seam[2],
        if bound { ".T." } else { ".F." }
    );
    step_text("ball", &data)
}

#[test]
fn a_ball_whose_one_face_is_slit_along_a_meridian_is_the_whole_sphere() {
    let want = 4.0 / 3.0 * std::f64::consts::PI * 1000.0;
    // the meridian a quarter turn from the sphere's seam, half a turn from it, and on it; the
    // bound either way (the loop retraces itself, so both are the same face)
    for seam in [[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]] {
        for bound in [true, false] {
            assert_eq!(certified_both_ways(&ball_slit_along_a_meridian(seam, bound), want, &format!("{seam:?} {bound}")).len(), 2);
        }
    }
}

/// A planar face of a surface model whose one loop passes through a vertex twice: two
/// triangles `(0,0) (2,0) (1,1)` and `(1,1) (2,2) (0,2)` joined at `(1,1)` (a hole touching the
/// outer boundary at a point makes such a loop).
fn face_pinched_at_a_vertex() -> String {
    let pts = [(0.0, 0.0), (2.0, 0.0), (1.0, 1.0), (2.0, 2.0), (0.0, 2.0)];
    let mut data = String::from("#1=CARTESIAN_POINT('',(0.,0.,0.));#2=DIRECTION('',(0.,0.,1.));#3=DIRECTION('',(1.,0.,0.));#4=AXIS2_PLACEMENT_3D('',#1,#2,#3);#5=PLANE('',#4);");
    for (i, (x, y)) in pts.iter().enumerate() {
        data += &format!("#{}=CARTESIAN_POINT('',({x:?},{y:?},0.));#{}=VERTEX_POINT('',#{});", 100 + i, 110 + i, 100 + i);
    }
    // the loop A B P C D P
    let order = [0usize, 1, 2, 3, 4, 2];
    let mut oriented = Vec::new();
    for k in 0..order.len() {
        let (a, b) = (order[k], order[(k + 1) % order.len()]);
        let (pa, pb) = (pts[a], pts[b]);
        let n = 200 + 10 * k;
        data += &format!(
            "#{}=DIRECTION('',({:?},{:?},0.));#{}=VECTOR('',#{},1.);#{}=LINE('',#{},#{});#{}=EDGE_CURVE('',#{},#{},#{},.T.);#{}=ORIENTED_EDGE('',*,*,#{},.T.);",
            n, pb.0 - pa.0, pb.1 - pa.1, n + 1, n, n + 2, 100 + a, n + 1, n + 3, 110 + a, 110 + b, n + 2, n + 4, n + 3
        );
        oriented.push(format!("#{}", n + 4));
    }
    data += &format!("#60=EDGE_LOOP('',({}));#61=FACE_OUTER_BOUND('',#60,.T.);#62=ADVANCED_FACE('bowtie',(#61),#5,.T.);#70=OPEN_SHELL('',(#62));#71=SHELL_BASED_SURFACE_MODEL('',(#70));", oriented.join(","));
    step_text("pinched", &data)
}

#[test]
fn a_face_whose_loop_passes_through_a_vertex_twice_has_one_boundary_loop() {
    use crate::tessellate::certificate::{CertifyOptions, certify};
    let m = crate::cad::step::read_bytes(std::path::Path::new("test.stp"), face_pinched_at_a_vertex().as_bytes()).unwrap_or_else(|e| panic!("{e}"));
    for sized in [false, true] {
        let t = if sized { super::tessellate_sized(&m, &TessellateOptions::default(), &crate::core::size_field::UniformSize(0.3)) } else { tessellate(&m, &TessellateOptions::default()) };
        assert!(t.failed.is_empty(), "{sized}: {:?}", t.failed);
        let cert = certify(&m, &t, &CertifyOptions::default());
        let loops: Vec<_> = cert.failures.iter().filter(|f| f.check == "boundary_loops").collect();
        assert!(loops.is_empty(), "{sized}: {loops:?}");
        let area: f64 = t.surface.triangles.iter().map(|tri| 0.5 * (t.surface.vertices[tri[1] as usize] - t.surface.vertices[tri[0] as usize]).cross(t.surface.vertices[tri[2] as usize] - t.surface.vertices[tri[0] as usize]).length()).sum();
        assert!((area - 2.0).abs() < 1e-9, "{sized}: area {area}");
    }
}
