//! `fepre mesh` from the command line: JSON report, exit codes, nothing left behind on errors,
//! and one uniquely named physical group per CAD face as gmsh and meshio read them.

mod common;

use common::tools;
use std::collections::BTreeSet;
use std::process::Command;

fn fepre() -> Command {
    Command::new(env!("CARGO_BIN_EXE_fepre"))
}

#[test]
fn meshes_the_bundled_part_with_a_json_report() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("plate.vtu");
    let o = fepre().args(["mesh", "cad_fixtures/plate_with_hole.obj", "--json", "-o"]).arg(&out).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    for key in ["nodes", "tets", "seconds", "min_dihedral_deg", "max_dihedral_deg", "max_radius_edge", "volume", "boundary_steiner_points", "regions"] {
        assert!(v.get(key).is_some(), "no {key} in {v}");
    }
    assert!(v["tets"].as_u64().unwrap() > 0);
    assert!(v["min_dihedral_deg"].as_f64().unwrap() > 5.0, "{v}");
    assert!(out.is_file());
}

#[test]
fn a_closed_output_pipe_ends_quietly_with_the_file_written() {
    // `fepre mesh ... --json | head -1`: standard output closed before the report is printed
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("plate.mesh");
    let mut child = fepre()
        .args(["mesh", "cad_fixtures/plate_with_hole.obj", "--json", "-o"])
        .arg(&out)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let o = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{:?}: {err}", o.status);
    assert!(!err.contains("panicked"), "{err}");
    assert!(out.is_file());
}

#[test]
fn an_open_surface_is_refused_with_its_edges_and_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let open = dir.path().join("open.obj");
    // a unit cube with one of its twelve triangles missing
    let v = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n";
    let f = "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\n";
    std::fs::write(&open, format!("{v}{f}")).unwrap();
    let out = dir.path().join("open.mesh");
    let o = fepre().arg("mesh").arg(&open).arg("-o").arg(&out).output().unwrap();
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("open") && err.contains("boundary edges") && err.contains("open.obj"), "{err}");
    assert!(!out.exists());
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1, "something was left behind");
}

#[test]
fn bad_usage_exits_2() {
    let o = fepre().args(["mesh", "cad_fixtures/plate_with_hole.obj", "-o", "x.stl"]).output().unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", String::from_utf8_lossy(&o.stderr));
    let o = fepre().args(["mesh", "cad_fixtures/plate_with_hole.obj", "-o", "x.mesh", "--max-radius-edge", "0.9"]).output().unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(!std::path::Path::new("x.mesh").exists());
}

#[test]
fn meshes_the_bundled_step_bracket_the_readme_runs() {
    // the README's main job: STEP -> sized, certified tessellation -> quality tets, CAD face ids
    // as boundary tags
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("bracket.mesh");
    let o = fepre().args(["mesh", "cad_fixtures/bracket.step", "--json", "-o"]).arg(&out).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    let loaded = fepre::io::read(&out, &fepre::io::ReadOptions::default()).unwrap();
    let fepre::io::MeshData::Volume(m) = loaded.mesh else { panic!("not a tet mesh") };
    assert_eq!(m.validate(), Ok(()));
    // the analytic volume of the default bracket, to the tessellation's chord
    let analytic = fepre::cad::parts::Bracket::default().volume();
    assert!((m.volume() - analytic).abs() < 0.005 * analytic, "volume {} vs {analytic}", m.volume());
    let model = fepre::cad::step::read(std::path::Path::new("cad_fixtures/bracket.step")).unwrap();
    let tags: std::collections::BTreeSet<u32> = m.face_tags.iter().map(|t| t.0).collect();
    assert_eq!(tags.len(), model.faces.len(), "every CAD face tags some boundary triangles");
    // quality: a regression guard, measured 12.0 .. 153.5 degrees, radius-edge 2.2
    let (lo, hi, re) = (v["min_dihedral_deg"].as_f64().unwrap(), v["max_dihedral_deg"].as_f64().unwrap(), v["max_radius_edge"].as_f64().unwrap());
    assert!(lo >= 10.0 && hi <= 160.0 && re <= 2.5, "{lo} .. {hi}, radius-edge {re}");
}

#[test]
fn a_step_part_meshes_to_the_same_bytes_for_any_thread_count_and_load() {
    // no clock steers the result: one thread on a quiet machine and two threads beside a
    // thread spinning flat out give the same file, byte for byte
    use std::sync::Arc;
    use std::sync::atomic::{AtomicBool, Ordering};
    let dir = tempfile::tempdir().unwrap();
    let mesh = |threads: &str| {
        let out = dir.path().join(format!("bracket_{threads}.mesh"));
        let o = fepre().env("RAYON_NUM_THREADS", threads).args(["mesh", "cad_fixtures/bracket.step", "-o"]).arg(&out).output().unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        std::fs::read(&out).unwrap()
    };
    let quiet = mesh("1");
    let stop = Arc::new(AtomicBool::new(false));
    let spinner = {
        let stop = stop.clone();
        std::thread::spawn(move || {
            let mut x = 0u64;
            while !stop.load(Ordering::Relaxed) {
                x = std::hint::black_box(x.wrapping_mul(6364136223846793005).wrapping_add(1));
            }
            x
        })
    };
    let busy = mesh("2");
    stop.store(true, Ordering::Relaxed);
    spinner.join().unwrap();
    assert!(!quiet.is_empty());
    assert!(quiet == busy, "the mesh depends on the thread count or the load ({} and {} bytes)", quiet.len(), busy.len());
}

/// The physical names of dimension 2 in an MSH file's `$PhysicalNames` section.
fn surface_physical_names(msh: &str) -> Vec<String> {
    let Some(start) = msh.find("$PhysicalNames") else { return Vec::new() };
    let section = &msh[start..msh[start..].find("$EndPhysicalNames").map_or(msh.len(), |e| start + e)];
    section
        .lines()
        .skip(2)
        .filter_map(|l| l.strip_prefix("2 "))
        .filter_map(|l| Some(l.split_once(' ')?.1.trim().trim_matches('"').to_string()))
        .collect()
}

#[test]
fn bracket_msh_has_one_uniquely_named_group_per_face() {
    // the bracket names faces 9 and 10 both `hole_1`: the MSH file must still hold 17 groups
    // with 17 distinct names, as fepre, gmsh and meshio read it, and the JSON face table must
    // name them the same way
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("b.msh");
    let o = fepre().args(["mesh", "cad_fixtures/bracket.step", "--json", "-o"]).arg(&out).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    let model = fepre::cad::step::read(std::path::Path::new("cad_fixtures/bracket.step")).unwrap();
    assert_eq!(model.faces.len(), 17);
    let raw: Vec<&str> = model.faces.iter().filter_map(|f| f.name.as_deref()).collect();
    assert_eq!(raw.iter().filter(|n| **n == "hole_1").count(), 2, "the fixture repeats a name: {raw:?}");

    let table = v["face_table"].as_array().expect("a face_table in the JSON report");
    assert_eq!(table.len(), 17);
    let json_names: Vec<String> = table.iter().map(|e| e["name"].as_str().expect("every bracket face is named").to_string()).collect();
    assert_eq!(json_names.iter().collect::<BTreeSet<_>>().len(), 17, "{json_names:?}");
    assert!(json_names.contains(&"hole_1".into()) && json_names.contains(&"hole_1.2".into()), "{json_names:?}");
    for (k, e) in table.iter().enumerate() {
        assert_eq!(e["face"], k + 1);
        assert_eq!(e["step_id"], model.faces[k].source.0);
        assert_eq!(e["solid"], 1, "solids are numbered from 1");
    }

    // fepre reads back 17 named face groups with the table's names
    let fepre::io::MeshData::Volume(m) = fepre::io::read(&out, &fepre::io::ReadOptions::default()).unwrap().mesh else { panic!("not a tet mesh") };
    let back: Vec<String> = m.face_names.names().map(str::to_string).collect();
    assert_eq!(back, json_names);
    assert_eq!(surface_physical_names(&std::fs::read_to_string(&out).unwrap()), json_names);

    if let Some(gmsh) = tools::require(tools::gmsh(), "gmsh", "the gmsh check of the bracket's .msh") {
        let check = tools::run_ok(Command::new(&gmsh).args(["-check", "b.msh"]), dir.path());
        let log = String::from_utf8_lossy(&check.stdout).to_string() + &String::from_utf8_lossy(&check.stderr);
        assert!(!log.contains("Error"), "gmsh -check b.msh:\n{log}");
        // gmsh's own model, saved again: its physical names of dimension 2
        tools::run_ok(Command::new(&gmsh).args(["b.msh", "-0", "-format", "msh41", "-o", "g.msh"]), dir.path());
        let names = surface_physical_names(&std::fs::read_to_string(dir.path().join("g.msh")).unwrap());
        assert_eq!(names.len(), 17, "gmsh's physical surface names: {names:?}");
        assert_eq!(names.iter().collect::<BTreeSet<_>>(), json_names.iter().collect::<BTreeSet<_>>());
    }
    if let Some(python) = tools::require(tools::meshio_python(), "Python with meshio", "the meshio check of the bracket's .msh") {
        let script = "import json, sys, meshio\nm = meshio.read(sys.argv[1])\nprint(json.dumps(sorted(n for n, (tag, dim) in m.field_data.items() if dim == 2)))";
        let o = tools::run_ok(Command::new(&python).arg("-c").arg(script).arg("b.msh"), dir.path());
        let names: Vec<String> = serde_json::from_slice(&o.stdout).expect("meshio's names as JSON");
        assert_eq!(names.len(), 17, "meshio keeps every group: {names:?}");
        let mut want = json_names.clone();
        want.sort();
        assert_eq!(names, want);
    }
}

#[test]
fn a_step_narrower_than_the_narrow_tolerance_is_closed_up_and_reported() {
    // a unit box whose top steps up by 1e-5 halfway (a face 1e-5 high, group "step"), as a
    // CAD model leaves where two faces almost meet
    let dir = tempfile::tempdir().unwrap();
    let e = 1e-5_f64;
    let h = 1.0 + e;
    let points = [
        [0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0], [0.5, 0.0, 1.0], [0.5, 1.0, 1.0], [0.0, 1.0, 1.0],
        [0.5, 0.0, h], [1.0, 0.0, h], [1.0, 1.0, h], [0.5, 1.0, h],
    ];
    let faces: [(&str, &[usize]); 8] = [("bottom", &[0, 3, 2, 1]), ("low", &[4, 5, 6, 7]), ("high", &[8, 9, 10, 11]), ("step", &[5, 8, 11, 6]), ("front", &[5, 4, 0, 1, 9, 8]), ("back", &[6, 11, 10, 2, 3, 7]), ("left", &[0, 4, 7, 3]), ("right", &[1, 2, 10, 9])];
    let mut obj = String::new();
    for p in points {
        obj += &format!("v {} {} {}\n", p[0], p[1], p[2]);
    }
    for (name, poly) in faces {
        obj += &format!("g {name}\n");
        for k in 1..poly.len() - 1 {
            obj += &format!("f {} {} {}\n", poly[0] + 1, poly[k] + 1, poly[k + 1] + 1);
        }
    }
    let input = dir.path().join("stepped.obj");
    std::fs::write(&input, obj).unwrap();
    let out = dir.path().join("m.mesh");
    let run = |extra: &[&str]| {
        let o = fepre().arg("mesh").arg(&input).arg("-o").arg(&out).args(["--size", "0.25", "--json"]).args(extra).output().unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        serde_json::from_slice::<serde_json::Value>(&o.stdout).expect("JSON")
    };
    // the default tolerance, 1e-4 of the diagonal
    let v = run(&[]);
    let tol = v["narrow"]["tolerance"].as_f64().unwrap_or_else(|| panic!("no narrow report in {v}"));
    assert!((tol - 1e-4 * (2.0 + h * h).sqrt()).abs() < 1e-12, "{tol}");
    assert!(v["narrow"]["collapses"].as_u64().unwrap() > 0, "{v}");
    assert!(v["min_dihedral_deg"].as_f64().unwrap() >= 10.0, "{v}");
    // the text report says so
    let o = fepre().arg("mesh").arg(&input).arg("-o").arg(&out).args(["--size", "0.25"]).output().unwrap();
    assert!(o.status.success());
    assert!(String::from_utf8_lossy(&o.stdout).contains("narrow strips"), "{}", String::from_utf8_lossy(&o.stdout));
    // 0 keeps the step
    let v = run(&["--narrow-tol", "0", "--require-min-dihedral", "0"]);
    assert!(v["narrow"].is_null(), "{v}");
    // a negative width is bad usage, nothing written
    let bad = dir.path().join("bad.mesh");
    let o = fepre().arg("mesh").arg(&input).arg("-o").arg(&bad).args(["--narrow-tol", "-1"]).output().unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(!bad.exists());
}
