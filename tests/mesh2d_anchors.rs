//! fepre's 2D meshers beside the anchors of issue 66, on the `.poly` regions of
//! `cad_fixtures/regions` (written by `tools/gen_regions.py`):
//! - Shewchuk's Triangle (`-q33` at a maximum area): fepre's `delaunay` makes at most 1.05×
//!   Triangle's triangles with every angle ≥ 33° away from small input angles;
//! - CGAL Mesh_2 (`tools/cgal_mesh2`, 30° and the same maximum area): counts within 15 %,
//!   fepre's smallest angle no worse;
//! - the quadtree's all-quad meshes: median scaled Jacobian at least that of gmsh's Blossom
//!   recombination at the same size (the benchmark's, about 10,000 quads per region);
//! - quads written as quads: meshio reads fepre's MSH and VTU quads as `quad` cells (and its
//!   triangles as triangles, the same counts), and gmsh reads the MSH back alike.
//!
//! The tools are found as `tests/common/tools.rs` says (Python with `triangle`, `numpy` and
//! `meshio` through `FEPRE_PYTHON` or `.venv/bin/python`; `gmsh` on `PATH`; the CGAL driver
//! at `FEPRE_CGAL_MESH2` or `tools/cgal_mesh2/cgal_mesh2`, built by `make -C tools/cgal_mesh2`;
//! `tools/install_refs_2d.sh` installs them all). A missing tool skips its check, except under
//! `CI=true`, where it fails.

mod common;

use common::tools::{self, require};
use fepre::io::read_poly;
use std::path::{Path, PathBuf};
use std::process::Command;

const REGIONS: [&str; 7] = ["convex", "l_shape", "comb", "two_holes", "strip", "small_angle", "large"];

/// Triangles per region in these tests (kept small for the dev profile).
const TARGET: f64 = 4000.0;

/// Triangles per region whose maximum area sets the quads' size in the comparison with gmsh's
/// Blossom quads (as in docs/benchmarks.md; at TARGET's coarser size gmsh's quads on the
/// L-shaped region score 0.990 against the quadtree's 0.960).
const QUAD_TARGET: f64 = 20000.0;

fn region(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("cad_fixtures/regions").join(format!("{name}.poly"))
}

/// The region's area, from fepre's own reading of the file.
fn area(name: &str) -> f64 {
    let poly = read_poly(&region(name)).unwrap();
    poly.to_domains().unwrap().iter().map(|(_, d)| d.area()).sum()
}

/// The maximum area for about [`TARGET`] triangles (Triangle's mean area at -q33 is about 0.58
/// of the bound), rounded to 3 digits so that every tool gets the same decimal.
fn max_area(name: &str) -> f64 {
    format!("{:.2e}", 1.7 * area(name) / TARGET).parse().unwrap()
}

/// `fepre mesh2d` with `args`, its `--json` parsed.
fn fepre_json(args: &[&str]) -> serde_json::Value {
    let out = Command::new(env!("CARGO_BIN_EXE_fepre")).arg("mesh2d").args(args).arg("--json").output().unwrap();
    assert!(out.status.success(), "fepre mesh2d {args:?} failed:\n{}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("fepre mesh2d {args:?}: not JSON ({e}):\n{}", String::from_utf8_lossy(&out.stdout)))
}

/// fepre's delaunay at `area` and `angle`: (triangles, smallest angle).
fn fepre_delaunay(name: &str, area: f64, angle: f64) -> (u64, f64) {
    let path = region(name);
    let j = fepre_json(&[path.to_str().unwrap(), "--method", "delaunay", "--max-area", &area.to_string(), "--min-angle", &angle.to_string()]);
    let tris = j["triangles"].as_u64().unwrap_or_else(|| panic!("{name}: no triangle count in {j}"));
    let min = j["quality"]["angle_range"][0].as_f64().unwrap_or_else(|| panic!("{name}: no angle range in {j}"));
    (tris, min)
}

/// Runs `script` with `args` under `python`; its stdout.
fn python(python: &Path, script: &str, args: &[&str]) -> String {
    let out = Command::new(python).arg("-c").arg(script).args(args).output().unwrap();
    assert!(out.status.success(), "python failed:\n{}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap()
}

/// The CGAL Mesh_2 driver, if built.
fn cgal_mesh2() -> Option<PathBuf> {
    let p = match std::env::var_os("FEPRE_CGAL_MESH2") {
        Some(p) => PathBuf::from(p),
        None => Path::new(env!("CARGO_MANIFEST_DIR")).join("tools/cgal_mesh2/cgal_mesh2"),
    };
    p.is_file().then_some(p)
}

#[test]
fn the_regions_are_what_the_generator_writes_and_read_as_valid_domains() {
    let expected = [
        ("convex", 1, 24, 12.0 * 15f64.to_radians().sin()),
        ("l_shape", 1, 6, 3.0),
        ("comb", 1, 16, 3.5 + 4.0 * 0.5 * 2.0),
        ("strip", 1, 4, 2.0),
    ];
    for (name, regions, segments, want) in expected {
        let d = read_poly(&region(name)).unwrap().to_domains().unwrap();
        assert_eq!(d.len(), regions, "{name}");
        assert_eq!(d[0].1.segments.len(), segments, "{name}");
        assert!((d[0].1.area() - want).abs() < 1e-12 * want, "{name}: area {} != {want}", d[0].1.area());
    }
    for name in REGIONS {
        let d = read_poly(&region(name)).unwrap().to_domains().unwrap();
        assert_eq!(d.len(), 1, "{name}: one region");
        d[0].1.validate().unwrap();
    }
    assert!((read_poly(&region("small_angle")).unwrap().to_domains().unwrap()[0].1.smallest_angle_deg() - 10.0).abs() < 1e-9);
    // the committed files are the generator's bytes
    let Some(py) = require(tools::on_path("python3"), "python3", "tools/gen_regions.py") else { return };
    let dir = tempfile::tempdir().unwrap();
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tools/gen_regions.py");
    let out = Command::new(py).arg(&script).arg(dir.path()).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    for name in REGIONS {
        let made = std::fs::read(dir.path().join(format!("{name}.poly"))).unwrap();
        assert!(made == std::fs::read(region(name)).unwrap(), "cad_fixtures/regions/{name}.poly differs from tools/gen_regions.py's output");
    }
}

#[test]
fn delaunay_makes_no_more_than_1_05_times_triangles_at_q33() {
    let Some(py) = require(tools::python_with(&["triangle", "numpy"]), "python with triangle", "the Triangle comparison") else { return };
    let script = "import sys, triangle, numpy as np
d = triangle.load('', sys.argv[1][:-5])
m = triangle.triangulate(d, 'pq33a' + sys.argv[2] + 'Q')
print(len(m['triangles']))";
    for name in REGIONS {
        let a = max_area(name);
        let theirs: u64 = python(&py, script, &[region(name).to_str().unwrap(), &a.to_string()]).trim().parse().unwrap();
        let (ours, min) = fepre_delaunay(name, a, 33.0);
        eprintln!("{name}: max area {a}: Triangle {theirs}, fepre {ours} ({:.3}x), fepre's smallest angle {min:.2}", ours as f64 / theirs as f64);
        assert!(ours as f64 <= 1.05 * theirs as f64, "{name}: fepre {ours} triangles, Triangle {theirs} (more than 1.05x)");
        if name != "small_angle" {
            assert!(min >= 33.0 - 1e-9, "{name}: smallest angle {min} < 33");
        }
    }
}

#[test]
fn delaunay_is_within_15_percent_of_cgal_mesh2_and_no_worse() {
    let Some(cgal) = require(cgal_mesh2(), "tools/cgal_mesh2/cgal_mesh2 (make -C tools/cgal_mesh2)", "the CGAL Mesh_2 comparison") else { return };
    for name in REGIONS {
        let a = max_area(name);
        let out = Command::new(&cgal).arg(region(name)).args(["--area", &a.to_string(), "--min-angle", "30"]).output().unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let (theirs, their_min) = (j["triangles"].as_u64().unwrap(), j["min_angle"].as_f64().unwrap());
        let (ours, min) = fepre_delaunay(name, a, 30.0);
        let rel = (ours as f64 - theirs as f64).abs() / theirs as f64;
        eprintln!("{name}: max area {a}: CGAL {theirs} (min {their_min:.2}), fepre {ours} (min {min:.2}), {:.1} %", 100.0 * rel);
        assert!(rel <= 0.15, "{name}: fepre {ours} triangles, CGAL Mesh_2 {theirs}");
        assert!(min >= their_min - 1e-6, "{name}: fepre's smallest angle {min} < CGAL's {their_min}");
        // CGAL's area mode leaves some angles under 30 (21 to 28 deg here), its size mode does
        // not: fepre must reach the asked 30 wherever no input angle is smaller
        if name != "small_angle" {
            assert!(min >= 30.0 - 1e-9, "{name}: fepre's smallest angle {min} < 30");
        }
    }
}

/// Writes `name`'s `--quads` mesh as `stem.msh` and `stem.vtu` in `dir`; its (triangles,
/// quads): all quads, so no triangles.
fn quads(dir: &Path, name: &str, method: &str) -> (u64, u64) {
    let path = region(name);
    // about TARGET / 2 quads: the edge of an equilateral triangle of 1.2 times the max area
    let h = format!("{:.2e}", (4.8 * max_area(name) / 3f64.sqrt()).sqrt());
    let mut quads = None;
    for ext in ["msh", "vtu"] {
        let out = dir.join(format!("{name}.{ext}"));
        let j = fepre_json(&[path.to_str().unwrap(), "--method", method, "--quads", "--size", &h, "-o", out.to_str().unwrap()]);
        let q = (j["triangles"].as_u64().unwrap(), j["quads"].as_u64().unwrap());
        assert!(q.0 == 0 && q.1 > 0 && quads.is_none_or(|p| p == q), "{name} by {method}: {q:?} triangles and quads");
        quads = Some(q);
    }
    quads.unwrap()
}

#[test]
fn meshio_and_gmsh_read_the_quads_as_quads() {
    let dir = tempfile::tempdir().unwrap();
    let names = ["convex", "l_shape", "two_holes"];
    let methods = ["quadtree", "front", "delaunay"];
    let counts: Vec<(u64, u64)> = names.iter().zip(methods).map(|(n, m)| quads(dir.path(), n, m)).collect();
    if let Some(py) = require(tools::meshio_python(), "python with meshio", "meshio reading the quads") {
        let script = "import sys, meshio
for p in sys.argv[1:]:
    m = meshio.read(p)
    kinds = sorted(set(c.type for c in m.cells if c.type not in ('vertex', 'line')))
    count = lambda t: sum(len(c.data) for c in m.cells if c.type == t)
    print(p, ','.join(kinds), count('triangle'), count('quad'))";
        for (n, q) in names.iter().zip(&counts) {
            for ext in ["msh", "vtu"] {
                let p = dir.path().join(format!("{n}.{ext}"));
                let out = python(&py, script, &[p.to_str().unwrap()]);
                let v: Vec<&str> = out.split_whitespace().collect();
                assert_eq!(v[1], if q.0 > 0 { "quad,triangle" } else { "quad" }, "meshio reads {n}.{ext} as {out}");
                assert_eq!((v[2].parse::<u64>().unwrap(), v[3].parse::<u64>().unwrap()), *q, "{n}.{ext}: {out}");
            }
        }
    }
    let Some(gmsh) = require(tools::gmsh(), "gmsh", "gmsh reading the quads") else { return };
    for (n, q) in names.iter().zip(&counts) {
        let again = dir.path().join(format!("{n}_again.msh"));
        let mut cmd = Command::new(&gmsh);
        cmd.arg(format!("{n}.msh")).args(["-0", "-format", "msh22", "-o"]).arg(&again);
        tools::run_ok(&mut cmd, dir.path());
        // MSH 2.2: "$Elements", the count, then "number type ..." lines
        let text = std::fs::read_to_string(&again).unwrap();
        let body = text.split("$Elements").nth(1).and_then(|s| s.split("$EndElements").next()).unwrap();
        let mut kinds = std::collections::BTreeMap::<u32, u64>::new();
        for l in body.lines().skip(2) {
            if let Some(t) = l.split_whitespace().nth(1) {
                *kinds.entry(t.parse().unwrap()).or_default() += 1;
            }
        }
        kinds.remove(&1); // boundary lines, if written
        kinds.remove(&15); // points
        let want: Vec<(u32, u64)> = [(2, q.0), (3, q.1)].into_iter().filter(|k| k.1 > 0).collect();
        assert_eq!(kinds.into_iter().collect::<Vec<_>>(), want, "gmsh reads {n}.msh back with other elements than {q:?} triangles and quadrangles");
    }
}

#[test]
fn quadtree_quads_have_a_median_scaled_jacobian_at_least_gmsh_blossoms() {
    let Some(py) = require(tools::meshio_python(), "python with meshio", "gmsh's Blossom quads") else { return };
    let Some(gmsh) = require(tools::gmsh(), "gmsh", "gmsh's Blossom quads") else { return };
    // gmsh at the same size h as fepre (tools/bench_mesh2d_anchors.py's run_gmsh: Blossom
    // recombination on algorithm 8, or on 6 where 8 crashes, as 4.8.4 does here)
    let script = "import sys, tempfile
sys.path.insert(0, sys.argv[1])
import bench_mesh2d_anchors as b
with tempfile.TemporaryDirectory() as tmp:
    r = b.run_gmsh(sys.argv[2], sys.argv[3], float(sys.argv[4]), 8, True, tmp)
    if 'error' in r:
        r = b.run_gmsh(sys.argv[2], sys.argv[3], float(sys.argv[4]), 6, True, tmp)
print(r['sj'], r['elements'])";
    let tools_dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tools");
    let mut short = Vec::new();
    for name in REGIONS {
        // the benchmark's size (docs/benchmarks.md): about 10,000 quads per region
        let a: f64 = format!("{:.2e}", 1.7 * area(name) / QUAD_TARGET).parse().unwrap();
        let h = (4.0 * 0.6 * a / 3f64.sqrt()).sqrt();
        let out = python(&py, script, &[tools_dir.to_str().unwrap(), gmsh.to_str().unwrap(), region(name).to_str().unwrap(), &a.to_string()]);
        let v: Vec<f64> = out.split_whitespace().map(|x| x.parse().unwrap()).collect();
        let j = fepre_json(&[region(name).to_str().unwrap(), "--method", "quadtree", "--quads", "--size", &h.to_string()]);
        let ours = j["quality"]["quad_scaled_jacobian"][1].as_f64().unwrap();
        let min = j["quality"]["quad_scaled_jacobian"][0].as_f64().unwrap();
        eprintln!("{name}: gmsh {} quads, median SJ {:.3}; fepre {} quads, median SJ {ours:.3} (min {min:.3})", v[1], v[0], j["quads"]);
        assert_eq!(j["triangles"], 0, "{name}: not all quads");
        assert!(min > 0.0, "{name}: a quad not strictly convex");
        if ours < v[0] {
            short.push(format!("{name}: fepre's median scaled Jacobian {ours:.3} < gmsh's {:.3}", v[0]));
        }
    }
    assert!(short.is_empty(), "{short:?}");
}
