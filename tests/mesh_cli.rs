//! `fepre mesh` from the command line: JSON report, exit codes, nothing left behind on errors.

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
