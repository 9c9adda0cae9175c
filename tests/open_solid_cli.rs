//! No silent open result (issue 14, part 5): a solid whose `CLOSED_SHELL` lacks a face is a
//! certificate failure. `fepre tessellate` and `fepre mesh` exit 1 naming the open solid and
//! its free edges; `fepre tessellate --force` writes the surface and says so.
//!
//! The file: our bracket fixture read, one face taken out of its closed shell, written back
//! with our STEP writer.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn fepre(args: &[&std::ffi::OsStr]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_fepre")).args(args).output().expect("run fepre")
}

/// Writes the bracket without its first face of one loop into `dir`; returns the file and
/// the free edges' count (the face's coedges).
fn bracket_without_a_face(dir: &Path) -> (PathBuf, usize) {
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR")).join("cad_fixtures/bracket.step");
    let mut m = fepre::cad::step::read(&fixture).unwrap();
    assert_eq!(m.solids.len(), 1);
    assert!(m.shells[0].closed);
    let victim = m.shells[0].faces.iter().copied().find(|&f| m.face(f).loops.len() == 1).expect("a face of one loop");
    let free: usize = m.face(victim).loops.iter().map(|&l| m.loops[l as usize].coedges.len()).sum();
    m.shells[0].faces.retain(|&f| f != victim);
    let path = dir.join("open_bracket.step");
    fepre::cad::step::write(&path, &m, "open bracket").unwrap();
    (path, free)
}

#[test]
fn a_closed_shell_left_open_exits_1_naming_the_solid_and_its_free_edges() {
    let dir = tempfile::tempdir().unwrap();
    let (step, free) = bracket_without_a_face(dir.path());
    let back = fepre::cad::step::read(&step).unwrap();
    let solid_id = back.solids[0].source.to_string();
    let out = dir.path().join("open.stl");

    // tessellate: exit 1, nothing written, the message names the solid and its free edges
    let o = fepre(&["tessellate".as_ref(), step.as_os_str(), "-o".as_ref(), out.as_os_str()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(!out.exists());
    assert!(err.contains("open_solid"), "{err}");
    assert!(err.contains(&format!("solid {solid_id}")) && err.contains("(CLOSED_SHELL #") && err.contains("does not close"), "{err}");
    assert!(err.contains(&format!("a hole of {free} free edges")), "{err}");
    assert!(err.contains("free edges #"), "{err}");

    // the JSON report says the same before the error
    let o = fepre(&["tessellate".as_ref(), step.as_os_str(), "-o".as_ref(), out.as_os_str(), "--json".as_ref()]);
    assert_eq!(o.status.code(), Some(1));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    assert_eq!(v["watertight"], false);
    assert_eq!(v["watertight_of"], "solids");
    assert_eq!(v["certificate"]["passed"], false);
    let holes = v["certificate"]["open_solids"].as_array().expect("open_solids");
    assert_eq!(holes.len(), 1, "{holes:?}");
    assert_eq!(holes[0]["edges"], free);
    assert_eq!(v["certificate"]["failures"][0]["check"], "open_solid");

    // --force: written, exit 0, and it says so
    let o = fepre(&["tessellate".as_ref(), step.as_os_str(), "-o".as_ref(), out.as_os_str(), "--force".as_ref()]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(out.is_file());
    assert!(text.contains("watertight   false (of the solids)"), "{text}");
    assert!(text.contains("OPEN SOLID") && text.contains(&format!("{free} free edges")), "{text}");
    assert!(text.contains("FAILED (written with --force)") && text.contains("open_solid"), "{text}");

    // mesh: exit 1 naming the open solid, nothing written
    let tets = dir.path().join("open.mesh");
    let o = fepre(&["mesh".as_ref(), step.as_os_str(), "-o".as_ref(), tets.as_os_str()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(!tets.exists());
    assert!(err.contains("open_solid") && err.contains(&format!("solid {solid_id}")) && err.contains("does not close"), "{err}");
}
