//! Unit tests of the tessellated-geometry reader and writer on small hand-written files.
#![cfg(test)]

use super::super::*;
use crate::core::FaceId;
use crate::mesh::TriSurface;
use crate::mesh::topology::{ReportOptions, surface_report};
use glam::DVec3;
use std::path::Path;

const HEAD: &str = "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('x','',(''),(''),'','sys','');\nFILE_SCHEMA(('AP242_MANAGED_MODEL_BASED_3D_ENGINEERING_MIM_LF'));\nENDSEC;\nDATA;\n";

/// A context in `unit` (`.MILLI.,.METRE.` or `$,.METRE.`) as `#1`-`#3`, then `body`, then a
/// `TESSELLATED_SHAPE_REPRESENTATION` `#100` of `items`.
fn file(unit: &str, body: &str, items: &str) -> String {
    format!(
        "{HEAD}#1=(LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT({unit}));\n#2=(NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.));\n\
         #3=(GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNIT_ASSIGNED_CONTEXT((#1,#2)) REPRESENTATION_CONTEXT('',''));\n{body}\
         #100=TESSELLATED_SHAPE_REPRESENTATION('',({items}),#3);\nENDSEC;\nEND-ISO-10303-21;\n"
    )
}

fn shape(text: &str) -> Result<Shape, StepError> {
    to_shape(&parser::parse(Path::new("t.stp"), text.as_bytes())?)
}

fn tessellated(text: &str) -> Tessellated {
    match shape(text) {
        Ok(Shape::Tessellated(t)) => t,
        Ok(Shape::Brep(_)) => panic!("expected tessellated geometry"),
        Err(e) => panic!("{e}"),
    }
}

/// What the tests below may fail with.
type TestResult = Result<(), Box<dyn std::error::Error>>;

/// Closed, manifold, oriented outward; its volume and area.
fn closed_volume_area(s: &TriSurface) -> (f64, f64) {
    let r = surface_report(s, &ReportOptions::default());
    assert!(r.closed && r.manifold && r.oriented && r.outward, "{r:?}");
    assert_eq!(r.self_intersections, Some(0));
    (r.volume, r.area)
}

const TETRA_POINTS: &str = "((0.,0.,0.),(1.,0.,0.),(0.,1.,0.),(0.,0.,1.))";

#[test]
fn a_tetrahedron_of_triangulated_faces_without_pnindex() {
    let body = format!(
        "#10=COORDINATES_LIST('',4,{TETRA_POINTS});\n\
         #11=TRIANGULATED_FACE('bottom',#10,4,(),$,(),((1,3,2)));\n\
         #12=TRIANGULATED_FACE('front',#10,4,(),$,(),((1,2,4)));\n\
         #13=TRIANGULATED_FACE('side',#10,4,(),$,(),((1,4,3)));\n\
         #14=TRIANGULATED_FACE('slope',#10,4,((0.577,0.577,0.577)),$,(),((2,3,4)));\n\
         #20=TESSELLATED_SOLID('tetra',(#11,#12,#13,#14),$);\n"
    );
    let t = tessellated(&file(".MILLI.,.METRE.", &body, "#20"));
    assert_eq!((t.faces.len(), t.surface.triangles.len(), t.surface.vertices.len()), (4, 4, 4));
    assert_eq!(t.solids.len(), 1);
    assert_eq!(t.solids[0].name.as_deref(), Some("tetra"));
    assert_eq!(t.solids[0].faces.len(), 4);
    assert_eq!(t.surface.face_names.get(FaceId(4)), Some("slope"));
    assert_eq!(t.faces[0].step_id.0, 11);
    assert_eq!(t.faces[3].solid, Some(1));
    assert_eq!(t.units.length, "millimetre");
    let (v, a) = closed_volume_area(&t.surface);
    assert!((v - 1.0 / 6.0).abs() < 1e-12, "{v}");
    assert!((a - (1.5 + 3f64.sqrt() / 2.0)).abs() < 1e-12, "{a}");
}

#[test]
fn a_tetrahedron_with_pnindex_and_a_coordinate_list_per_face_in_metres() {
    // each face indexes its own list through pnindex; the points are welded back together
    let body = "#10=COORDINATES_LIST('',5,((9.,9.,9.),(0.,0.,0.),(1.,0.,0.),(0.,1.,0.),(0.,0.,1.)));\n\
         #11=TRIANGULATED_FACE('a',#10,3,(),$,(2,4,3),((1,2,3)));\n\
         #12=TRIANGULATED_FACE('b',#10,3,(),$,(5,2,3),((2,3,1)));\n\
         #15=COORDINATES_LIST('',3,((0.,0.,0.),(0.,0.,1.),(0.,1.,0.)));\n\
         #13=TRIANGULATED_FACE('c',#15,3,(),$,(1,2,3),((1,2,3)));\n\
         #14=TRIANGULATED_FACE('d',#10,3,(),$,(3,4,5),((1,2,3)));\n\
         #20=TESSELLATED_SHELL('shell',(#11,#12,#13,#14),$);\n";
    let t = tessellated(&file("$,.METRE.", body, "#20"));
    assert_eq!((t.faces.len(), t.surface.triangles.len(), t.surface.vertices.len()), (4, 4, 4));
    assert!(!t.solids[0].solid);
    let (v, _) = closed_volume_area(&t.surface);
    assert!((v / 1e9 - 1.0 / 6.0).abs() < 1e-12, "{v}");
}

/// A 10 mm cube: three faces as one strip each, three as one fan each, one strip stitched
/// from two with a repeated index.
fn cube_text() -> String {
    // outward quads (a, b, c, d): strip a d b c, fan a d c b
    let quads = [[1, 4, 3, 2], [5, 6, 7, 8], [1, 2, 6, 5], [2, 3, 7, 6], [3, 4, 8, 7], [4, 1, 5, 8]];
    let mut body = String::from("#10=COORDINATES_LIST('',8,((0.,0.,0.),(10.,0.,0.),(10.,10.,0.),(0.,10.,0.),(0.,0.,10.),(10.,0.,10.),(10.,10.,10.),(0.,10.,10.)));\n");
    let mut items = Vec::new();
    for (k, [a, b, c, d]) in quads.iter().enumerate() {
        let id = 11 + k;
        let (strips, fans) = if k < 3 { (format!("(({a},{d},{b},{c}))"), "()".to_string()) } else { ("()".to_string(), format!("(({a},{d},{c},{b}))")) };
        body.push_str(&format!("#{id}=COMPLEX_TRIANGULATED_FACE('q{k}',#10,8,(),$,(),{strips},{fans});\n"));
        items.push(format!("#{id}"));
    }
    body.push_str(&format!("#20=TESSELLATED_SOLID('cube',({}),$);\n", items.join(",")));
    file(".MILLI.,.METRE.", &body, "#20")
}

#[test]
fn a_cube_of_complex_triangulated_faces_with_strips_and_fans() {
    let t = tessellated(&cube_text());
    assert_eq!((t.faces.len(), t.surface.triangles.len(), t.surface.vertices.len()), (6, 12, 8));
    let (v, a) = closed_volume_area(&t.surface);
    assert!((v - 1000.0).abs() < 1e-9 && (a - 600.0).abs() < 1e-9, "{v} {a}");
    // a strip stitched with a repeated index: (1 2 4 3 3 3) skips the degenerate triangles
    let stitched = cube_text().replace("((1,2,4,3))", "((1,2,4,3,3,3))");
    let t = tessellated(&stitched);
    assert_eq!(t.surface.triangles.len(), 12);
    assert_eq!(t.skipped_degenerate, 2);
}

#[test]
fn an_index_out_of_range_names_the_instance_and_its_line() -> TestResult {
    let body = format!("#10=COORDINATES_LIST('',4,{TETRA_POINTS});\n#11=TRIANGULATED_FACE('f',#10,4,(),$,(),((1,3,5)));\n#20=TESSELLATED_SOLID('',(#11),$);\n");
    let e = shape(&file(".MILLI.,.METRE.", &body, "#20")).unwrap_err();
    let msg = e.to_string();
    assert!(matches!(e, StepError::Tessellation { id: 11, line: 12, .. }), "{msg}");
    assert!(msg.starts_with("t.stp:12: #11: index 5 is outside the 4 points of COORDINATES_LIST #10"), "{msg}");
    // a pnindex value out of range, a strip index beyond pnindex
    let body = format!("#10=COORDINATES_LIST('',4,{TETRA_POINTS});\n#11=TRIANGULATED_FACE('f',#10,3,(),$,(1,2,7),((1,2,3)));\n#20=TESSELLATED_SOLID('',(#11),$);\n");
    assert!(shape(&file(".MILLI.,.METRE.", &body, "#20")).unwrap_err().to_string().contains("pnindex value 7"));
    let body = format!("#10=COORDINATES_LIST('',4,{TETRA_POINTS});\n#11=COMPLEX_TRIANGULATED_FACE('f',#10,2,(),$,(1,2),((1,2,3)),());\n#20=TESSELLATED_SOLID('',(#11),$);\n");
    assert!(shape(&file(".MILLI.,.METRE.", &body, "#20")).unwrap_err().to_string().contains("index 3 is outside the 2 entries of pnindex"));
    // the B-rep reader says what the file holds
    let text = cube_text();
    let e = to_model(&parser::parse(Path::new("t.stp"), text.as_bytes())?).unwrap_err();
    assert!(e.to_string().contains("tessellated geometry only (6 faces, 12 triangles)"), "{e}");
    Ok(())
}

#[test]
fn the_writer_round_trips_a_tagged_surface() -> TestResult {
    // the cube read back, written with faces 2 and 5 complex, read again
    let cube = tessellated(&cube_text()).surface;
    let text = tessellated_to_string(&cube, "cube", &[FaceId(2), FaceId(5)])?;
    assert_eq!(text, tessellated_to_string(&cube, "cube", &[FaceId(2), FaceId(5)])?, "deterministic");
    assert_eq!(text.matches("COMPLEX_TRIANGULATED_FACE(").count(), 2);
    assert_eq!(text.matches("TRIANGULATED_FACE(").count(), 6);
    let back = tessellated(&text);
    assert_eq!(back.surface.vertices, cube.vertices);
    assert_eq!(back.surface.face_names.get(FaceId(3)), Some("q2"));
    let key = |s: &TriSurface| {
        let mut v: Vec<(FaceId, [u32; 3])> = s.triangles.iter().zip(&s.face_tags).map(|(t, &f)| {
            let r = (0..3).min_by_key(|&i| t[i]).unwrap_or(0);
            (f, [t[r], t[(r + 1) % 3], t[(r + 2) % 3]])
        }).collect();
        v.sort_unstable();
        v
    };
    assert_eq!(key(&back.surface), key(&cube));
    let (v, _) = closed_volume_area(&back.surface);
    assert!((v - 1000.0).abs() < 1e-9);
    // non-finite coordinates are refused
    let mut bad = cube.clone();
    bad.vertices[0] = DVec3::new(f64::NAN, 0.0, 0.0);
    assert!(tessellated_to_string(&bad, "x", &[]).is_err());
    Ok(())
}

#[test]
fn a_file_with_a_brep_and_tessellation_gives_the_brep_and_lists_the_tessellation() -> TestResult {
    let model = crate::cad::parts::Block::default().build()?;
    let text = writer::to_string(&model, "block")?;
    let id_of = |entity: &str| text.lines().find(|l| l.contains(entity)).and_then(|l| l.split('=').next()).map(str::to_string).ok_or(format!("no {entity} in the written file"));
    let rep = id_of("=ADVANCED_BREP_SHAPE_REPRESENTATION(")?;
    let ctx = id_of("GEOMETRIC_REPRESENTATION_CONTEXT")?;
    let extra = format!(
        "#9010=COORDINATES_LIST('',4,{TETRA_POINTS});\n#9011=TRIANGULATED_FACE('f',#9010,4,(),$,(),((1,3,2),(1,2,4),(1,4,3),(2,3,4)));\n\
         #9020=TESSELLATED_SOLID('',(#9011),$);\n#9030=TESSELLATED_SHAPE_REPRESENTATION('',(#9020),{ctx});\n\
         #9031=SHAPE_REPRESENTATION_RELATIONSHIP('','',{rep},#9030);\nENDSEC;\nEND-ISO-10303-21;\n"
    );
    let both = text.replace("ENDSEC;\nEND-ISO-10303-21;\n", &extra);
    let Shape::Brep(m) = shape(&both)? else { panic!("expected the B-rep") };
    assert_eq!(m.faces.len(), model.faces.len());
    let d: Vec<_> = m.dropped.iter().filter(|d| d.id.0 == 9020).collect();
    assert_eq!(d.len(), 1, "{:?}", m.dropped);
    assert!(d[0].why.contains("fepre reads the B-rep"));
    Ok(())
}
