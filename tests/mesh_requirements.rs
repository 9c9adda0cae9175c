//! Quality requirements and the always-on quality summary of `fepre mesh` and `fepre run`: a
//! requirement the input cannot reach fails (exit 1, nothing written) naming the worst tet's
//! place, its CAD face and edge and the input angle it touches; without one a tet under 1°
//! that touches no input angle under 1° fails the same way, and the summary says the same,
//! warns on standard error about tets under 1°, and says when refinement stopped.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn fepre(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_fepre")).args(args).output().unwrap()
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

/// A prism of height 4 over the triangle (0,0,0) (10,0,0) (10 cos a, 10 sin a, 0): a knife
/// edge of `angle_deg` degrees from (0,0,0) to (0,0,4) between the groups `side_a` (y = 0,
/// tag 3) and `side_c` (tag 5). No tet with a face on each side of it can have a larger
/// dihedral angle.
fn wedge(dir: &Path, angle_deg: f64) -> PathBuf {
    let a = angle_deg.to_radians();
    let base = [[0.0, 0.0, 0.0], [10.0, 0.0, 0.0], [10.0 * a.cos(), 10.0 * a.sin(), 0.0]];
    let mut obj = String::new();
    for z in [0.0, 4.0] {
        for p in base {
            obj.push_str(&format!("v {} {} {}\n", p[0], p[1], p[2] + z));
        }
    }
    for (group, tris) in [
        ("bottom", vec![[1, 3, 2]]),
        ("top", vec![[4, 5, 6]]),
        ("side_a", vec![[1, 2, 5], [1, 5, 4]]),
        ("side_b", vec![[2, 3, 6], [2, 6, 5]]),
        ("side_c", vec![[3, 1, 4], [3, 4, 6]]),
    ] {
        obj.push_str(&format!("g {group}\n"));
        for t in tris {
            obj.push_str(&format!("f {} {} {}\n", t[0], t[1], t[2]));
        }
    }
    let path = dir.join("wedge.obj");
    std::fs::write(&path, obj).unwrap();
    path
}

/// The three numbers of the first `(x, y, z)` after `label` in `s`.
fn point_after(s: &str, label: &str) -> [f64; 3] {
    let at = s.find(label).unwrap_or_else(|| panic!("no {label:?} in {s}"));
    let rest = &s[at..];
    let open = rest.find('(').unwrap();
    let close = rest[open..].find(')').unwrap() + open;
    let v: Vec<f64> = rest[open + 1..close].split(',').map(|x| x.trim().parse().unwrap()).collect();
    [v[0], v[1], v[2]]
}

/// The number right after `label` (up to a `°` or a space).
fn number_after(s: &str, label: &str) -> f64 {
    let at = s.find(label).unwrap_or_else(|| panic!("no {label:?} in {s}")) + label.len();
    let num: String = s[at..].trim_start().chars().take_while(|c| c.is_ascii_digit() || *c == '.' || *c == '-' || *c == 'e').collect();
    num.parse().unwrap_or_else(|_| panic!("no number after {label:?} in {s}"))
}

/// The knife edge's place: `p` inside the prism, within `d` of the edge.
fn near_the_knife_edge(p: [f64; 3], d: f64) -> bool {
    (0.0..=4.0).contains(&p[2]) && p[0] >= 0.0 && p[0] <= 10.0 && p[1] >= 0.0 && p[1] <= 0.6 && p[0].hypot(p[1]) <= d
}

fn only(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    v.sort();
    v
}

#[test]
fn a_required_dihedral_the_input_cannot_reach_fails_naming_the_place() {
    let dir = tempfile::tempdir().unwrap();
    let input = wedge(dir.path(), 3.0);
    let out = dir.path().join("wedge.mesh");
    let o = fepre(&["mesh", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "--require-min-dihedral", "10"]);
    let err = text(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert_eq!(only(dir.path()), ["wedge.obj"], "nothing may be written");
    assert!(err.contains("wedge.obj") && err.contains("below the 10° required") && err.contains("nothing written"), "{err}");
    // the worst tet: its smallest angle (what the head says), at the knife edge
    let worst = number_after(&err, "the smallest dihedral angle is");
    assert!(worst < 3.0 + 1e-6, "{err}");
    assert_eq!(number_after(&err, "min dihedral"), worst, "{err}");
    let at = point_after(&err, "worst tet");
    assert!(near_the_knife_edge(at, 5.0), "the worst tet at {at:?}: {err}");
    // its CAD face (a side at the knife edge, by tag and group name) and feature edge
    let face = &err[err.find("nearest face").unwrap()..];
    assert!(face.starts_with("nearest face   3 \"side_a\"") || face.starts_with("nearest face   5 \"side_c\""), "{err}");
    assert!(err.contains("nearest edge   between faces"), "{err}");
    // the input angle it touches: the 3° dihedral angle between the two sides, at its edge
    assert!(
        err.contains("input angle    3° is the input dihedral angle between faces 3 \"side_a\" and 5 \"side_c\" at the edge (0, 0, 0) to (0, 0, 4); the tet touches it"),
        "{err}"
    );
}

#[test]
fn a_required_radius_edge_names_the_worst_tet_too() {
    let dir = tempfile::tempdir().unwrap();
    let input = wedge(dir.path(), 3.0);
    let out = dir.path().join("wedge.vtu");
    let o = fepre(&["mesh", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "--require-max-radius-edge", "2"]);
    let err = text(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert_eq!(only(dir.path()), ["wedge.obj"]);
    assert!(err.contains("the largest radius-edge ratio is") && err.contains("above the 2 required"), "{err}");
    let r = number_after(&err, "the largest radius-edge ratio is");
    assert!(r > 2.0 && number_after(&err, "°, radius-edge") == r, "{err}");
    assert!(near_the_knife_edge(point_after(&err, "worst tet"), 10.0), "{err}");
    assert!(err.contains("nearest face") && err.contains("input angle"), "{err}");
}

#[test]
fn a_job_requirement_fails_the_same_way_and_writes_no_output() {
    let dir = tempfile::tempdir().unwrap();
    wedge(dir.path(), 3.0);
    let job = dir.path().join("job.toml");
    std::fs::write(&job, "[input]\nfile = \"wedge.obj\"\n[require]\nmin_dihedral = 10\n[[output]]\nfile = \"out.msh\"\n[[output]]\nfile = \"out.json\"\n").unwrap();
    let o = fepre(&["run", job.to_str().unwrap()]);
    let err = text(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert_eq!(only(dir.path()), ["job.toml", "wedge.obj"]);
    assert!(err.contains("below the 10° required") && err.contains("worst tet") && err.contains("3° is the input dihedral angle between faces 3 \"side_a\" and 5 \"side_c\""), "{err}");
}

#[test]
fn the_summary_locates_the_worst_tet_and_warns_under_one_degree() {
    let dir = tempfile::tempdir().unwrap();
    // 3°: the worst tet is over 1°: no warning, exit 0, the place is in the summary
    let input = wedge(dir.path(), 3.0);
    let out = dir.path().join("w.mesh");
    let o = fepre(&["mesh", input.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    let (stdout, stderr) = (text(&o.stdout), text(&o.stderr));
    assert!(o.status.success(), "{stderr}");
    let min = number_after(&stdout, "dihedral        ");
    assert!(min >= 1.0 && min < 3.0 + 1e-6, "{stdout}");
    assert!(!stderr.contains("WARNING"), "{stderr}");
    assert!(near_the_knife_edge(point_after(&stdout, "worst tet"), 5.0), "{stdout}");
    assert!(stdout.contains("input angle      3° is the input dihedral angle between faces 3 \"side_a\" and 5 \"side_c\""), "{stdout}");
    assert!(stdout.contains("input angles     ") && stdout.contains("refinement       ") && stdout.contains("optimisation     "), "{stdout}");
    // the same in the JSON report
    let o = fepre(&["mesh", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    let w = &v["worst_tet"];
    assert_eq!(w["min_dihedral_deg"], v["min_dihedral_deg"], "{v}");
    assert_eq!(w["input_angle"]["kind"], "dihedral", "{w}");
    assert_eq!(w["input_angle"]["touches"], true, "{w}");
    assert!((w["input_angle"]["angle_deg"].as_f64().unwrap() - 3.0).abs() < 1e-9, "{w}");
    assert_eq!(w["input_angle"]["names"], serde_json::json!(["side_a", "side_c"]), "{w}");
    assert!(v["refinement_stopped"].is_boolean() && v.get("tets_under_1_deg").is_some() && v.get("near_degenerate").is_some(), "{v}");

    // 0.5°: tets under 1° across the knife edge's wedge, some of them off its edge: without a
    // requirement they fail the run, naming the place by the knife edge
    let input = wedge(dir.path(), 0.5);
    std::fs::remove_file(&out).unwrap();
    let o = fepre(&["mesh", input.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    let stderr = text(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{stderr}");
    assert!(!out.exists(), "nothing may be written");
    assert!(stderr.contains("touch no input angle under 1°") && stderr.contains("--require-min-dihedral 0"), "{stderr}");
    assert!(near_the_knife_edge(point_after(&stderr, "worst tet"), 5.0), "{stderr}");
    // accepted with --require-min-dihedral 0: a WARNING on standard error, exit 0
    let o = fepre(&["mesh", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "--require-min-dihedral", "0"]);
    let (stdout, stderr) = (text(&o.stdout), text(&o.stderr));
    assert!(o.status.success(), "{stderr}");
    let under1 = stdout.lines().find(|l| l.starts_with("dihedral")).unwrap().to_string();
    assert!(!under1.contains(" 0 under 1°"), "{stdout}");
    let warning = stderr.lines().find(|l| l.starts_with("WARNING: ")).unwrap_or_else(|| panic!("no WARNING line: {stderr}"));
    assert!(warning.contains("under 1°") && warning.contains("--require-min-dihedral D makes this an error"), "{warning}");
    assert!(near_the_knife_edge(point_after(warning, "the smallest"), 5.0), "{warning}");
    assert!(!stdout.contains("WARNING"), "warnings go to standard error: {stdout}");
}

/// In a thin wedge most bad tets lie off its knife edge, between its two sides: the report
/// counts them apart from those that touch no input angle at all.
#[test]
fn tets_between_the_faces_of_a_knife_edge_are_counted_apart() {
    let dir = tempfile::tempdir().unwrap();
    let input = wedge(dir.path(), 0.5);
    let out = dir.path().join("w.mesh");
    let o = fepre(&["mesh", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "--require-min-dihedral", "0", "--json"]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    let n = |k: &str| v[k].as_u64().unwrap_or_else(|| panic!("{k}: {v}"));
    let (unexplained, between) = (n("tets_under_10_deg_unexplained"), n("tets_under_10_deg_between_sides"));
    // the 0.5° knife's wedge is 0.09 wide at its far end: nearly every tet under 10° off its
    // edge has a vertex on each side
    assert!(unexplained > 0 && between <= unexplained && 2 * between > unexplained, "{v}");
    assert_eq!(n("tets_under_bound_between_sides"), 0, "no tet is under 0°: {v}");
    // `inspect` finds the same on the mesh written, from the mesh's own boundary
    let o = fepre(&["inspect", out.to_str().unwrap(), "--json"]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let i: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    for k in ["tets_under_10_deg", "tets_under_10_deg_unexplained", "tets_under_10_deg_between_sides"] {
        assert_eq!(i[k], v[k], "{k}: {i}");
    }
    let o = fepre(&["inspect", out.to_str().unwrap()]);
    assert!(text(&o.stdout).contains(&format!("{unexplained} touch no angle under 10° of the boundary")), "{}", text(&o.stdout));
    let o = fepre(&["mesh", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "--require-min-dihedral", "0"]);
    let stdout = text(&o.stdout);
    assert!(stdout.contains(&format!("of the {unexplained} under 10° touching none, {between} lie between the two sides of an input angle under 10°")), "{stdout}");
    // at the defaults the tets under 1° off the edge still fail the run; the worst of them is
    // placed between the knife's two faces
    std::fs::remove_file(&out).unwrap();
    let o = fepre(&["mesh", input.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    let stderr = text(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("none that the tet touches; it lies between the two sides of 0.5°, the input dihedral angle between faces 3 \"side_a\" and 5 \"side_c\""), "{stderr}");
}

#[test]
fn a_refinement_that_ends_says_so_in_the_text() {
    // (a refinement stopped at a budget: the text of each budget is checked in cli's unit
    // tests; part.step at radius-edge 1.1 ran out of points until the local-feature-size
    // floor of refinement.rs, and now ends)
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("w.mesh");
    let wedge = wedge(dir.path(), 3.0);
    let o = fepre(&["mesh", wedge.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    let stdout = text(&o.stdout);
    assert!(stdout.lines().any(|l| l.starts_with("refinement       ended")), "{stdout}");
}

/// A slender tube meshed at its default size (a twenty-fifth of its length, ten times its
/// outer radius): eight chords round its circles cut off several percent of its volume. The
/// summary says how far the mesh's volume is from the CAD solid's, a warning says it on
/// standard error, and `--require-volume-error` makes it a failure that writes nothing.
#[test]
fn a_volume_far_from_the_cad_solids_is_reported_and_can_be_required() {
    let dir = tempfile::tempdir().unwrap();
    let mut tube = fepre::cad::parts::Tube::default();
    (tube.inner_radius, tube.outer_radius, tube.length, tube.angle_deg) = (1.0, 2.0, 500.0, 360.0);
    let step = dir.path().join("rod.step");
    fepre::cad::step::write(&step, &tube.build().unwrap(), "rod").unwrap();
    let out = dir.path().join("rod.mesh");
    let o = fepre(&["mesh", step.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let stdout = text(&o.stdout);
    let line = stdout.lines().find(|l| l.starts_with("volume")).unwrap();
    let pct: f64 = line.rsplit(':').next().unwrap().trim().trim_end_matches("%)").parse().unwrap();
    assert!(pct < -1.0, "{line}");
    assert!(text(&o.stderr).contains("WARNING: the mesh's volume is"), "{}", text(&o.stderr));
    std::fs::remove_file(&out).unwrap();
    let o = fepre(&["mesh", step.to_str().unwrap(), "-o", out.to_str().unwrap(), "--require-volume-error", "0.01"]);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o.stderr));
    assert!(text(&o.stderr).contains("off the CAD solids'") && !out.exists(), "{}", text(&o.stderr));
    // a size that follows the circles meets it
    let o = fepre(&["mesh", step.to_str().unwrap(), "-o", out.to_str().unwrap(), "--size", "0.5", "--require-volume-error", "0.01"]);
    assert!(o.status.success() && out.exists(), "{}", text(&o.stderr));
}

/// A plate 1 thick whose outline runs along the x axis from the origin to 16, up, back to
/// x = 14 on the circle of radius 20 about (0, 20), and along that circle to the origin,
/// where it meets the axis tangentially: a knife edge of the solid between a flat wall and a
/// cylindrical one that meet at 0° along the z axis, written as STEP to `path`.
fn write_horn(path: &Path) {
    use truck_modeling::{Point3, Vector3, Wire, builder};
    let y = |x: f64| 20.0 - (400.0 - x * x).sqrt();
    let corners = [Point3::new(0.0, 0.0, 0.0), Point3::new(16.0, 0.0, 0.0), Point3::new(16.0, y(14.0), 0.0), Point3::new(14.0, y(14.0), 0.0)];
    let v = corners.map(|p| builder::vertex(p));
    let wire: Wire = vec![builder::line(&v[0], &v[1]), builder::line(&v[1], &v[2]), builder::line(&v[2], &v[3]), builder::circle_arc(&v[3], &v[0], Point3::new(7.0, y(7.0), 0.0))].into();
    let face = builder::try_attach_plane(&[wire]).unwrap();
    let solid = builder::tsweep(&face, Vector3::new(0.0, 0.0, 1.0));
    let model = fepre::cad::parts::solid_to_model(&solid, "horn").unwrap();
    fepre::cad::step::write(path, &model, "horn").unwrap();
}

/// Without a requirement, a tet under 1° that touches no input angle under 1° fails the run
/// (exit 1, nothing written, its place named); `--require-min-dihedral 0` accepts the mesh and
/// keeps the warning. The input is a knife edge where two walls meet tangentially
/// ([`write_horn`]): the tets between the walls a few tenths from the edge are slivers that do
/// not touch it (the corpus' part.step was the input until its face 20's 0.56° corner got
/// strips, 2026-12-04): when a change meshes such an edge without them, this test needs
/// another input with tets the input does not explain.
#[test]
fn an_unexplained_tet_under_one_degree_fails_unless_accepted() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("horn.step");
    write_horn(&input);
    let out = dir.path().join("horn.vtu");
    let o = fepre(&["mesh", input.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    let err = text(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert_eq!(only(dir.path()), vec!["horn.step".to_string()], "nothing may be written");
    assert!(err.contains("horn.step") && err.contains("touch no input angle under 1°") && err.contains("nothing written") && err.contains("--require-min-dihedral 0"), "{err}");
    let worst = number_after(&err, "(the smallest");
    assert!(worst < 1.0 && number_after(&err, "min dihedral") == worst, "{err}");
    assert!(err.contains("nearest face") && err.contains("nearest edge") && err.contains("input angle    none that the tet touches"), "{err}");
    // accepted: written, exit 0, the warning says not all of them touch a small input angle
    let o = fepre(&["mesh", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "--require-min-dihedral", "0"]);
    let err = text(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(out.exists());
    let warning = err.lines().find(|l| l.starts_with("WARNING: ")).unwrap_or_else(|| panic!("no WARNING line: {err}"));
    assert!(warning.contains("under 1°") && !warning.contains("each touching"), "{warning}");
}
