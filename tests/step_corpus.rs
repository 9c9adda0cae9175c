//! The STEP reader on the shared corpus: every file reads, face and solid counts equal
//! OpenCASCADE's (cadquery-ocp 8.0.1, instances expanded; `../shared/cad_corpus/README.md`),
//! units are recognised, the topology is consistent, and corrupted copies fail with errors
//! that name the line or `#id`.

mod common;

use fepre::cad::brep::{Summary, VERTEX_ON_CURVE_RELATIVE};
use fepre::cad::step::{self, StepError};
use std::path::Path;
use std::time::Instant;

/// file, OCC faces, OCC solids, length unit of the file.
const EXPECTED: &[(&str, usize, usize, &str)] = &[
    ("occt-cube.step", 6, 1, "millimetre"),
    ("occt-cylinder.step", 3, 1, "millimetre"),
    ("occt-sphere.step", 1, 1, "millimetre"),
    ("red_cube_blue_cylinder.step", 9, 2, "metre"),
    ("base_interface_AP214.STEP", 30, 1, "inch"),
    ("part.step", 26, 1, "metre"),
    ("screw.step", 10, 1, "millimetre"),
    ("Angled.step", 69, 1, "millimetre"),
    ("featuretype.STEP", 96, 1, "inch"),
    ("t20_data.step", 21, 1, "millimetre"),
    ("cube_filet.stp", 25, 0, "millimetre"),
    ("Kurbelwelle.stp", 58, 1, "millimetre"),
    ("abc-0035.step", 82, 1, "metre"),
    ("mambo_s34.step", 46, 1, "millimetre"),
    ("linkrods.step", 37, 1, "millimetre"),
    ("as1-tu-203.stp", 160, 18, "millimetre"),
    ("box_sides.STEP", 417, 10, "inch"),
    ("wing_fuselage.step", 16, 2, "metre"),
    ("abc-0000.step", 25, 6, "metre"),
    ("Zylkopf.stp", 137, 1, "millimetre"),
    ("sewfaces.step", 22, 0, "millimetre"),
    ("bug32745_pmi1.stp", 30, 1, "millimetre"),
];

#[test]
fn corpus_counts_equal_opencascade() {
    let Some(dir) = common::corpus_dir() else { return };
    let mut failures = Vec::new();
    for &(name, faces, solids, unit) in EXPECTED {
        let path = dir.join(name);
        let t0 = Instant::now();
        let model = match step::read(&path) {
            Ok(m) => m,
            Err(e) => {
                failures.push(format!("{name}: {e}"));
                continue;
            }
        };
        let seconds = t0.elapsed().as_secs_f64();
        let s = Summary::of(&model);
        eprintln!("{name}: {} faces, {} solids, {} edges, {} dropped, {seconds:.3} s", s.faces, s.solids, s.edges, model.dropped.len());
        if (s.faces, s.solids) != (faces, solids) {
            failures.push(format!("{name}: {} faces / {} solids, OpenCASCADE {faces} / {solids}", s.faces, s.solids));
        }
        if s.units.length != unit {
            failures.push(format!("{name}: unit {} (expected {unit})", s.units.length));
        }
        if !model.dropped.is_empty() {
            failures.push(format!("{name}: dropped {:?}", model.dropped));
        }
        let issues = model.issues(VERTEX_ON_CURVE_RELATIVE);
        if !issues.is_empty() {
            failures.push(format!("{name}: {} topology/geometry issues, first: {}", issues.len(), issues[0]));
        }
        // generous: release builds read the largest file in a few hundredths of a second
        if seconds > 2.0 {
            failures.push(format!("{name}: read in {seconds:.2} s"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn units_scale_to_millimetres() {
    let Some(dir) = common::corpus_dir() else { return };
    // red_cube_blue_cylinder: a 10 mm cube and an r = 5 mm cylinder, written in metres
    let m = step::read(&dir.join("red_cube_blue_cylinder.step")).unwrap();
    let (lo, hi) = m.bounds().unwrap();
    let ext = hi - lo;
    assert!((ext.x - 25.0).abs() < 1e-6 && (ext.y - 10.0).abs() < 1e-6 && (ext.z - 10.0).abs() < 1e-6, "{ext:?}");
    // occt-sphere: r = 5 mm, one face bounded by a vertex loop
    let m = step::read(&dir.join("occt-sphere.step")).unwrap();
    assert!((m.size() - 10.0 * 3f64.sqrt()).abs() < 1e-6, "{}", m.size());
}

#[test]
fn closed_seam_and_pole_edges() {
    let Some(dir) = common::corpus_dir() else { return };
    let m = step::read(&dir.join("occt-cylinder.step")).unwrap();
    let s = Summary::of(&m);
    assert_eq!((s.edges, s.closed_edges, s.seam_edges), (3, 2, 1));
    for e in m.edges.iter().filter(|e| e.closed) {
        assert!((e.range.length() - std::f64::consts::TAU).abs() < 1e-9, "{:?}", e.range);
    }
    let z = step::read(&dir.join("Zylkopf.stp")).unwrap();
    assert_eq!(Summary::of(&z).faces_by_surface.get("degenerate_torus"), Some(&2));
}

fn corrupted(name: &str, edit: impl Fn(&str) -> String) -> Option<StepError> {
    let path = common::corpus_file(name)?;
    let text = std::fs::read_to_string(&path).unwrap();
    let bad = edit(&text);
    Some(step::read_bytes(Path::new("bad.step"), bad.as_bytes()).expect_err("a corrupted file must fail"))
}

#[test]
fn truncated_file_names_the_instance() {
    let Some(e) = corrupted("occt-cube.step", |t| t[..t.find("#40 =").unwrap() + 12].to_string()) else { return };
    let msg = e.to_string();
    assert!(matches!(e, StepError::Truncated { .. }), "{msg}");
    assert!(msg.starts_with("bad.step:") && msg.contains("#40"), "{msg}");
}

#[test]
fn missing_reference_names_both_ids() {
    // the cube's first face refers to a plane that no longer exists
    let Some(e) = corrupted("occt-cube.step", |t| {
        let start = t.find("\n#").unwrap();
        let line_start = t[start + 1..].find("PLANE(").map(|k| t[..start + 1 + k].rfind('\n').unwrap() + 1).unwrap();
        let line_end = t[line_start..].find('\n').unwrap() + line_start;
        format!("{}{}", &t[..line_start], &t[line_end + 1..])
    }) else {
        return;
    };
    let msg = e.to_string();
    assert!(matches!(e, StepError::MissingEntity { .. }), "{msg}");
    assert!(msg.contains("refers to #") && msg.contains("which the file does not define"), "{msg}");
}

#[test]
fn an_unneeded_reference_to_nothing_is_read_and_noted() {
    // some exporters write #18446744073709551615 (an unsigned -1) for "none"; OpenCASCADE reads
    // such files, and so does fepre where the reference is not needed
    let Some(path) = common::corpus_file("occt-cube.step") else { return };
    let text = std::fs::read_to_string(&path).unwrap();
    let end = text.find("ENDSEC;\nEND-ISO").or_else(|| text.rfind("ENDSEC;")).unwrap();
    let edited = format!("{}#999999 = PRODUCT_RELATED_PRODUCT_CATEGORY('part',$,(#18446744073709551615));\n{}", &text[..end], &text[end..]);
    let model = step::read_bytes(Path::new("none.step"), edited.as_bytes()).unwrap();
    let clean = step::read_bytes(&path, text.as_bytes()).unwrap();
    assert_eq!(model.faces.len(), clean.faces.len());
    assert!(model.notes.iter().any(|n| n.contains("#999999 refers to #18446744073709551615")), "{:?}", model.notes);
}

#[test]
fn reference_cycle_names_the_id() {
    // a B-spline surface's control point replaced by... a surface that is its own basis
    let Some(e) = corrupted("occt-cylinder.step", |t| {
        let k = t.find("CYLINDRICAL_SURFACE(").unwrap();
        let id_start = t[..k].rfind('#').unwrap();
        let id: String = t[id_start + 1..].chars().take_while(char::is_ascii_digit).collect();
        let end = t[k..].find(';').unwrap() + k;
        format!("{}OFFSET_SURFACE('',#{id},1.,.F.){}", &t[..k], &t[end..])
    }) else {
        return;
    };
    let msg = e.to_string();
    assert!(matches!(e, StepError::Cycle { .. }), "{msg}");
    assert!(msg.contains(" -> #"), "{msg}");
}

fn fepre(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_fepre")).args(args).output().expect("run fepre")
}

#[test]
fn cad_info_reports_and_rejects() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("cut.step");
    std::fs::write(&bad, "ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n#1=CARTESIAN_POINT('',(0.,0.,").unwrap();
    let o = fepre(&["cad-info", bad.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("cut.step:5") && err.contains("truncated") && err.contains("#1"), "{err}");
    let Some(path) = common::corpus_file("as1-tu-203.stp") else { return };
    let o = fepre(&["cad-info", path.to_str().unwrap(), "--json"]);
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["solids"], 18);
    assert_eq!(v["faces"], 160);
    assert_eq!(v["units"]["length"], "millimetre");
    assert!(v["dropped"].as_array().unwrap().is_empty());
    assert!(v["seconds"].as_f64().unwrap() >= 0.0);
    assert_eq!(v["faces_by_surface"]["plane"], 90);
}

#[test]
fn face_colours_from_styled_items() {
    // a red cube and a blue cylinder
    let Some(path) = common::corpus_file("red_cube_blue_cylinder.step") else { return };
    let m = step::read(&path).unwrap();
    let colours: Vec<[f32; 3]> = m.faces.iter().map(|f| f.colour.expect("every face is styled")).collect();
    let red = colours.iter().filter(|c| c[0] > c[1] && c[0] > c[2]).count();
    let blue = colours.iter().filter(|c| c[2] > c[0] && c[2] > c[1]).count();
    assert_eq!((red, blue), (6, 3), "{colours:?}");
}

#[test]
fn truncations_anywhere_give_errors_not_panics() {
    let Some(path) = common::corpus_file("part.step") else { return };
    let bytes = std::fs::read(path).unwrap();
    // every 997th byte: inside strings, numbers, lists, keywords and between instances
    // (cuts inside the first keyword are "not a STEP file", also an error)
    for cut in (20..bytes.len()).step_by(997) {
        let r = step::read_bytes(Path::new("cut.step"), &bytes[..cut]);
        match r {
            Err(StepError::Truncated { .. }) => {}
            Err(e) => panic!("cut at {cut}: expected Truncated, got {e}"),
            Ok(_) => panic!("cut at {cut}: a truncated file was accepted"),
        }
    }
}
