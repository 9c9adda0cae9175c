//! Unit tests of the STEP reader on small hand-written files.

use super::*;
use crate::cad::geom::SurfaceKind;
use std::path::Path;

/// The tessellated-geometry reader and writer.
mod tessellated;

fn parse(text: &str) -> Result<StepFile, StepError> {
    parser::parse(Path::new("t.stp"), text.as_bytes())
}

const HEAD: &str = "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('x','',(''),(''),'','sys','');\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;\n";

#[test]
fn lexer_traps() {
    let text = "/* comment before */ iso-10303-21;\nheader;\nFILE_SCHEMA(('CONFIG_CONTROL_DESIGN'));\nendsec;\ndata;\n\
        #1 = ANNOTATION_PLANE('it''s',(),$,*, .T., -.5, 1.E-3, 7, \"0A\");\n\
        #2 = ( NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) LENGTH_UNIT() );\n\
        #3 = MEASURE(LENGTH_MEASURE(2.5), #2); /* trailing */\n\
        #4 = NAME('multi\nline');\nendsec;\nend-iso-10303-21;\n";
    let f = parse(text).unwrap();
    assert_eq!(f.schemas, vec!["CONFIG_CONTROL_DESIGN".to_string()]);
    let e = f.get(1).unwrap();
    assert_eq!(e.type_name(), "ANNOTATION_PLANE");
    let p = &e.records[0].params;
    assert_eq!(p[0], Param::Str("it's".into()));
    assert_eq!(p[1], Param::List(vec![]));
    assert_eq!(p[2], Param::Unset);
    assert_eq!(p[3], Param::Derived);
    assert_eq!(p[4].as_bool(), Some(true));
    assert_eq!(p[5], Param::Real(-0.5));
    assert_eq!(p[6], Param::Real(1e-3));
    assert_eq!(p[7], Param::Int(7));
    assert!(f.get(2).unwrap().is_complex() && f.get(2).unwrap().has("SI_UNIT"));
    assert_eq!(f.get(3).unwrap().records[0].params[0].as_f64(), Some(2.5));
    assert_eq!(f.get(4).unwrap().line, 9);
}

#[test]
fn errors_name_line_and_id() {
    let trunc = format!("{HEAD}#1 = CARTESIAN_POINT('',(0.,0.,0.));\n#2 = CARTESIAN_POINT('',(1.,");
    let e = parse(&trunc).unwrap_err();
    assert!(matches!(e, StepError::Truncated { line: 9, .. }), "{e}");
    assert!(e.to_string().contains("#2"), "{e}");
    // a reference to an instance the file does not define: read, noted, and an error
    // naming both ids where it is needed
    let missing = format!("{HEAD}#1 = VERTEX_POINT('',#7);\nENDSEC;\nEND-ISO-10303-21;\n");
    let f = parse(&missing).unwrap();
    assert!(f.notes.iter().any(|n| n.contains("line 8: #1 refers to #7")), "{:?}", f.notes);
    assert!(matches!(f.check_references().unwrap_err(), StepError::MissingEntity { id: 7, from: 1, line: 8, .. }));
    let dup = format!("{HEAD}#1 = A();\n#1 = B();\nENDSEC;\n");
    assert!(matches!(parse(&dup).unwrap_err(), StepError::DuplicateId { id: 1, line: 9, first_line: 8, .. }));
    let bad = format!("{HEAD}#1 = A(,);\nENDSEC;\n");
    assert!(matches!(parse(&bad).unwrap_err(), StepError::Syntax { line: 8, .. }));
    assert!(matches!(parse("solid x\n").unwrap_err(), StepError::NotStep { .. }));
    let no_endsec = format!("{HEAD}#1 = A();\n");
    let e = parse(&no_endsec).unwrap_err();
    assert!(matches!(e, StepError::Truncated { .. }) && e.to_string().contains("#1"), "{e}");
}

/// A 10 mm cube in inches? No: a unit square face on a plane, in metres, as a surface model.
fn square(unit: &str) -> String {
    format!(
        "{HEAD}\
#1=CARTESIAN_POINT('',(0.,0.,0.));#2=DIRECTION('',(0.,0.,1.));#3=DIRECTION('',(1.,0.,0.));\
#4=AXIS2_PLACEMENT_3D('',#1,#2,#3);#5=PLANE('',#4);\
#11=CARTESIAN_POINT('',(0.,0.,0.));#12=CARTESIAN_POINT('',(1.,0.,0.));#13=CARTESIAN_POINT('',(1.,1.,0.));#14=CARTESIAN_POINT('',(0.,1.,0.));\
#21=VERTEX_POINT('',#11);#22=VERTEX_POINT('',#12);#23=VERTEX_POINT('',#13);#24=VERTEX_POINT('',#14);\
#30=DIRECTION('',(1.,0.,0.));#31=VECTOR('',#30,1.);#32=LINE('',#11,#31);\
#33=DIRECTION('',(0.,1.,0.));#34=VECTOR('',#33,1.);#35=LINE('',#12,#34);\
#36=VECTOR('',#30,1.);#37=LINE('',#14,#36);#38=VECTOR('',#33,1.);#39=LINE('',#11,#38);\
#41=EDGE_CURVE('',#21,#22,#32,.T.);#42=EDGE_CURVE('',#22,#23,#35,.T.);#43=EDGE_CURVE('',#24,#23,#37,.T.);#44=EDGE_CURVE('',#21,#24,#39,.T.);\
#51=ORIENTED_EDGE('',*,*,#41,.T.);#52=ORIENTED_EDGE('',*,*,#42,.T.);#53=ORIENTED_EDGE('',*,*,#43,.F.);#54=ORIENTED_EDGE('',*,*,#44,.F.);\
#60=EDGE_LOOP('',(#51,#52,#53,#54));#61=FACE_OUTER_BOUND('',#60,.T.);#62=ADVANCED_FACE('top',(#61),#5,.T.);\
#70=OPEN_SHELL('',(#62));#71=SHELL_BASED_SURFACE_MODEL('',(#70));\
#80=( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT({unit},.METRE.) );\
#81=( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNIT_ASSIGNED_CONTEXT((#80)) REPRESENTATION_CONTEXT('','') );\
#90=MANIFOLD_SURFACE_SHAPE_REPRESENTATION('',(#4,#71),#81);\nENDSEC;\nEND-ISO-10303-21;\n"
    )
}

#[test]
fn square_face_in_metres_is_scaled_to_mm() {
    let m = read_bytes(Path::new("sq.stp"), square("$").as_bytes()).unwrap();
    assert_eq!((m.solids.len(), m.shells.len(), m.faces.len(), m.edges.len(), m.vertices.len()), (0, 1, 1, 4, 4));
    assert_eq!(m.units.length, "metre");
    let (lo, hi) = m.bounds().unwrap();
    assert!((hi - lo - glam::DVec3::new(1000.0, 1000.0, 0.0)).length() < 1e-9);
    let f = m.face(crate::core::FaceId(1));
    assert_eq!(f.name.as_deref(), Some("top"));
    assert_eq!(m.surface(f.surface).kind(), SurfaceKind::Plane);
    let e = &m.edges[0];
    assert!((e.range.max - e.range.min - 1.0).abs() < 1e-12, "line parameters are not scaled: {:?}", e.range);
    assert!(m.edges.iter().all(|e| !e.closed && !e.seam && !e.degenerate));
    let mm = read_bytes(Path::new("sq.stp"), square(".MILLI.").as_bytes()).unwrap();
    assert_eq!(mm.units.length, "millimetre");
    assert!((mm.size() - 2f64.sqrt()).abs() < 1e-12);
}

#[test]
fn unsupported_surface_is_reported_not_silent() {
    let text = square("$").replace("#5=PLANE('',#4);", "#5=RECTANGULAR_COMPOSITE_SURFACE('',());");
    let e = read_bytes(Path::new("sq.stp"), text.as_bytes()).unwrap_err();
    assert!(matches!(e, StepError::NoShape { .. }), "{e}");
    assert!(e.to_string().contains("#62") && e.to_string().contains("RECTANGULAR_COMPOSITE_SURFACE"), "{e}");
    // the shape is there, its only face is not: the message says so, naming it
    assert!(e.to_string().contains("no usable B-rep shape: 1 SHELL_BASED_SURFACE_MODEL (#"), "{e}");
}

#[test]
fn a_toroidal_surface_with_a_negative_major_radius_is_read_as_written() {
    // SolidWorks writes a spindle torus's major radius negative: read, not dropped
    let text = square("$").replace("#5=PLANE('',#4);", "#5=TOROIDAL_SURFACE('',#4,-0.03,0.1);");
    let m = read_bytes(Path::new("sq.stp"), text.as_bytes()).unwrap();
    let f = m.face(crate::core::FaceId(1));
    match m.surface(f.surface) {
        crate::cad::geom::Surface::Torus(t) => assert!((t.major + 30.0).abs() < 1e-9 && (t.minor - 100.0).abs() < 1e-9, "{t:?}"),
        s => panic!("not a torus: {s:?}"),
    }
}

#[test]
fn cycle_is_an_error_naming_the_id() {
    let text = square("$").replace("#5=PLANE('',#4);", "#5=OFFSET_SURFACE('',#5,1.,.F.);");
    let e = read_bytes(Path::new("sq.stp"), text.as_bytes()).unwrap_err();
    assert!(matches!(e, StepError::Cycle { id: 5, .. }), "{e}");
    assert!(e.to_string().contains("#5 -> #5"), "{e}");
}

#[test]
fn strings_decode_the_control_directives() {
    // ISO 10303-21 6.4.3: \S\ (the next character + 128, an apostrophe after it doubled or
    // not), \X\hh, \X2\…\X0\, \X4\…\X0\, \\, page switches; as CAD systems write names
    let names = [
        (r"'M\S\dller'", "Mäller".to_string()),
        (r"'Gr\X\F6\X\DFe'", "Größe".to_string()),
        (r"'h\X2\00E4\X0\t\X2\00FC00DF\X0\'", "hätüß".to_string()),
        (r"'\X4\0001F600\X0\ ok'", "\u{1F600} ok".to_string()),
        (r"'a\\b'", "a\\b".to_string()),
        (r"'\PA\caf\S\i'", "café".to_string()),
        (r"'x\S\'y'", "x\u{a7}y".to_string()),
        (r"'x\S\''y'", "x\u{a7}y".to_string()),
        (r"'plain ''quoted'' name'", "plain 'quoted' name".to_string()),
        // a bare apostrophe inside, a malformed \X2\ (three digits): kept as text
        (r"'it's'", "it's".to_string()),
        (r"'A\X2\0C4\X0\'h'", "A0C4\\X0\\'h".to_string()),
        (r"''", String::new()),
    ];
    for (raw, want) in names {
        let text = format!("{HEAD}#1 = PRODUCT({raw},'b','c',());\nENDSEC;\nEND-ISO-10303-21;\n");
        let f = parse(&text).unwrap_or_else(|e| panic!("{raw}: {e}"));
        assert_eq!(f.get(1).unwrap().records[0].params[0], Param::Str(want.clone().into()), "{raw}");
    }
}

#[test]
fn odd_headers_are_read_with_a_note() {
    let data = "#1 = PRODUCT('a','b','c',());\nENDSEC;\nEND-ISO-10303-21;\n";
    let ok = parse(&format!("{HEAD}{data}")).unwrap();
    assert!(ok.notes.is_empty(), "{:?}", ok.notes);
    let cases = [
        (HEAD.replace("FILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\n", ""), "lacks FILE_SCHEMA"),
        (HEAD.replace("HEADER;\nFILE_DESCRIPTION((''),'2;1');\n", "HEADER;\n"), "lacks FILE_DESCRIPTION"),
        (HEAD.replace("'sys','');", "'sys','','extra');"), "FILE_NAME has 8 parameters"),
        ("ISO-10303-21;\nDATA;\n".to_string(), "no HEADER section"),
    ];
    for (head, want) in cases {
        let f = parse(&format!("{head}{data}")).unwrap_or_else(|e| panic!("{want}: {e}"));
        assert!(f.notes.len() == 1 && f.notes[0].contains(want), "{want}: {:?}", f.notes);
        assert!(f.get(1).is_some());
    }
}
