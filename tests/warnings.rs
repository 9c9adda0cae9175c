//! Warnings are the library's: `fepre::pipeline::mesh_file` (what `fepre mesh`
//! calls) gives them in its report, with their kind and place, and the binary prints the same
//! messages on standard error, each after `WARNING: `.

mod common;

use fepre::attributes::Density;
use fepre::attributes::Positive;
use fepre::pipeline::job::Method;
use fepre::pipeline::{MeshFileReport, mesh_file};
use fepre::pipeline::Plan;
use fepre::pipeline::{Place, WarningKind};
use std::path::Path;
use std::process::Command;

/// `fepre mesh INPUT -o OUT --method octree --size SIZE` by the library: its report.
fn octree_by_library(input: &Path, size: f64, out: &Path) -> MeshFileReport {
    let mut density = Density::default();
    density.size = Positive::new(size);
    let plan = Plan { density, unit: 1.0, method: Method::Octree, ..Plan::default() };
    mesh_file(input, &plan, out).unwrap_or_else(|e| panic!("{e}"))
}

/// The same by the binary: its standard error.
fn octree_by_binary(input: &Path, size: f64, out: &Path) -> String {
    let o = Command::new(env!("CARGO_BIN_EXE_fepre"))
        .args(["mesh", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "--method", "octree", "--size", &size.to_string()])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(o.status.success(), "{stderr}");
    assert!(!String::from_utf8_lossy(&o.stdout).contains("WARNING"), "warnings go to standard error");
    stderr
}

/// The bundled bracket at an octree cell of 10 mm: the cells miss what is thinner, and the
/// mesh's volume is several per cent under the CAD solid's.
#[test]
fn a_volume_more_than_one_percent_off_is_a_warning_of_the_library_and_the_binary() {
    let dir = tempfile::tempdir().unwrap();
    let input = Path::new(env!("CARGO_MANIFEST_DIR")).join("cad_fixtures/bracket.step");
    let r = octree_by_library(&input, 10.0, &dir.path().join("a.mesh"));
    let e = r.summary.volume_error.expect("a CAD part has the CAD solids' volume");
    assert!(e < -0.01, "{e}");
    let volume: Vec<_> = r.warnings.iter().filter(|w| w.kind == WarningKind::VolumeOff).collect();
    assert_eq!(volume.len(), 1, "{:?}", r.warnings);
    assert!(volume[0].message.starts_with(&format!("the mesh's volume is {:+.2}% off the CAD solids'", 100.0 * e)), "{}", volume[0].message);
    // --json carries them
    let json = serde_json::to_value(&r).unwrap();
    assert_eq!(json["warnings"].as_array().map(Vec::len), Some(r.warnings.len()), "{}", json["warnings"]);
    assert!(json["warnings"].as_array().unwrap().iter().any(|w| w["kind"] == "volume_off"), "{}", json["warnings"]);
    // the binary prints the same
    let stderr = octree_by_binary(&input, 10.0, &dir.path().join("b.mesh"));
    for w in &r.warnings {
        assert!(stderr.lines().any(|l| l == format!("WARNING: {}", w.message)), "{w:?} not in\n{stderr}");
    }
    assert_eq!(stderr.lines().filter(|l| l.starts_with("WARNING: ")).count(), r.warnings.len(), "{stderr}");
}

/// The corpus' rabbit at an octree cell of 0.1 (its ears are thinner): the boundary strays
/// farther than a cell from the input, where the report says.
#[test]
fn an_octree_boundary_farther_than_its_cell_is_a_warning_of_the_library_and_the_binary() {
    let Some(input) = common::corpus_file("rabbit.obj") else { return };
    let dir = tempfile::tempdir().unwrap();
    let r = octree_by_library(&input, 0.1, &dir.path().join("a.mesh"));
    let o = r.octree.as_ref().expect("the octree's report");
    assert!(o.hausdorff_over_cell > 1.0 || o.bound_over_cell > 1.0, "{} {}", o.hausdorff_over_cell, o.bound_over_cell);
    let strays: Vec<_> = r.warnings.iter().filter(|w| w.kind == WarningKind::OctreeBoundaryStrays).collect();
    assert_eq!(strays.len(), 1, "{:?}", r.warnings);
    assert!(strays[0].message.starts_with("the boundary strays "), "{}", strays[0].message);
    assert_eq!(strays[0].place, Some(Place::Point(o.deviation.hausdorff_at)));
    let stderr = octree_by_binary(&input, 0.1, &dir.path().join("b.mesh"));
    for w in &r.warnings {
        assert!(stderr.lines().any(|l| l == format!("WARNING: {}", w.message)), "{w:?} not in\n{stderr}");
    }
    assert_eq!(stderr.lines().filter(|l| l.starts_with("WARNING: ")).count(), r.warnings.len(), "{stderr}");
}
