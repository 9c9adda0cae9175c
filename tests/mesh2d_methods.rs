//! Every 2D method of `fepre mesh2d` (issue 66) on the project's test regions
//! (`cad_fixtures/regions/*.poly`) and on the planar faces of every corpus STEP part: a valid,
//! conforming mesh covering each region or face exactly with its boundary points kept (or a
//! refusal naming why), the lifted faces sharing their edge points, sizes near the size asked
//! (median element size within 20 % for the decomposition and front methods), the advancing
//! front's angles at least 25° on the regions; and `--quads` with every method: all quads,
//! covering, conforming across faces, median size within 20 % (but the quadtree's). The corpus comes from `FEPRE_CORPUS` or
//! `../shared/cad_corpus` (skipped when missing, failing under `CI=true`).

mod common;

use fepre::core::RegionId;
use fepre::io::read_poly;
use fepre::mesh2d::measure::measure;
use fepre::mesh2d::{mesh_domain, Boundary, Domain, Mesh2dOptions, Method};
use fepre::pipeline::{mesh2d_poly, mesh_planar_faces, FaceChoice, Mesh2dRequest};
use std::path::{Path, PathBuf};

const REGIONS: &[&str] = &["convex", "l_shape", "comb", "two_holes", "strip", "small_angle"];

fn region_file(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("cad_fixtures/regions").join(format!("{name}.poly"))
}

/// The size each test region is meshed at: its narrowest feature (the strip's 0.2, the
/// comb's 0.5-wide teeth, the holes' 0.2 clearance) over at least four elements.
fn region_size(name: &str) -> f64 {
    if name == "strip" { 0.05 } else { 0.1 }
}

/// Methods whose median element size the issue bounds (within 20 % of the size field).
fn sized(m: Method) -> bool {
    matches!(m.name(), "ear" | "recursive" | "removal" | "front")
}

/// The mesh covers `d` exactly: valid, the same area, every domain point a vertex.
fn check_cover(what: &str, d: &Domain, m: &fepre::mesh::PlanarMesh) {
    m.validate().unwrap_or_else(|e| panic!("{what}: {e}"));
    let rel = (m.area() - d.area()).abs() / d.area();
    assert!(rel < 1e-9, "{what}: area off by {rel:e}");
    let mut verts: Vec<[u64; 2]> = m.vertices.iter().map(|p| [p.x.to_bits(), p.y.to_bits()]).collect();
    verts.sort_unstable();
    for p in &d.points {
        assert!(verts.binary_search(&[p.x.to_bits(), p.y.to_bits()]).is_ok(), "{what}: boundary point {p} is not a vertex");
    }
}

fn regions_by(method: Method, quads: bool) {
    for name in REGIONS {
        let file = read_poly(&region_file(name)).unwrap();
        for r in file.to_regions().unwrap() {
            let h = region_size(name);
            let what = format!("{}{} on {name} at {h}", method.name(), if quads { " --quads" } else { "" });
            // boundary divided by the size and kept (as for regions sharing segments)
            let o = Mesh2dOptions { method, quads, boundary: Boundary::Split, region: RegionId(7), ..Mesh2dOptions::default() };
            let m = match mesh_domain(&r.domain, &|_| h, &o) {
                Ok(m) => m,
                Err(e) => panic!("{what}: {e}"),
            };
            let split = fepre::mesh2d::boundary::split_boundary(&r.domain, &|_| h).unwrap();
            if quads {
                // all quads, covering the region, its boundary points kept
                check_cover(&what, &r.domain, &m.mesh);
                assert!(m.mesh.triangles.is_empty() && !m.mesh.quads.is_empty(), "{what}: {} triangles", m.mesh.triangles.len());
            } else if method != Method::Quadtree {
                check_cover(&what, &split.domain, &m.mesh);
            } else {
                m.mesh.validate().unwrap_or_else(|e| panic!("{what}: {e}"));
            }
            assert!(m.mesh.triangle_tags.iter().chain(&m.mesh.quad_tags).all(|&t| t == RegionId(7)), "{what}: tags");
            let q = measure(&m.mesh, &|_| h);
            // (the quadtree's leaves, and so its quads, are between half the size and the size)
            if sized(method) || (quads && method != Method::Quadtree) {
                assert!((0.8..=1.2).contains(&q.size_ratio[1]), "{what}: median size ratio {:?}", q.size_ratio);
            }
            if method.name() == "front" && !quads && *name != "small_angle" {
                assert!(q.angle_range[0] >= 25.0, "{what}: smallest angle {:?}", q.angle_range);
            }
            // the same input, the same mesh
            let again = mesh_domain(&r.domain, &|_| h, &o).unwrap();
            assert_eq!(again.mesh, m.mesh, "{what}: not deterministic");
        }
    }
}

fn corpus_by(method: Method, quads: bool) {
    let Some(dir) = common::corpus_dir() else { return };
    let mut parts: Vec<PathBuf> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().path()).filter(|p| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("step") || e.eq_ignore_ascii_case("stp"))).collect();
    parts.sort();
    assert!(parts.len() >= 20, "{} STEP parts in the corpus", parts.len());
    let mut faces = 0;
    for part in &parts {
        let name = part.file_name().unwrap().to_string_lossy().to_string();
        let o = Mesh2dOptions { method, quads, ..Mesh2dOptions::default() };
        let r = match mesh_planar_faces(part, &FaceChoice::AllPlanar, None, &o) {
            Ok(r) => r,
            Err(e) => panic!("{} on {name}: {e}", method.name()),
        };
        assert!(r.failed.is_empty(), "{} on {name}: {:?}", method.name(), r.failed);
        for m in &r.meshed {
            let what = format!("{} on {name} face {}", method.name(), m.planar.face.0);
            if method != Method::Quadtree || quads {
                check_cover(&what, &m.planar.domain, &m.meshed.mesh);
            }
            if quads {
                assert!(m.meshed.mesh.triangles.is_empty(), "{what}: {} triangles", m.meshed.mesh.triangles.len());
            }
            faces += 1;
        }
        let s = r.surface();
        s.validate().unwrap_or_else(|e| panic!("{} on {name}: lifted surface: {e}", method.name()));
        if method != Method::Quadtree || quads {
            assert_eq!(r.unshared_boundary_points(), 0, "{} on {name}: faces do not conform", method.name());
        }
    }
    assert!(faces > 500, "{faces} planar faces meshed");
}

macro_rules! method_tests {
    ($($regions:ident, $corpus:ident, $quad_regions:ident, $quad_corpus:ident, $name:literal;)*) => {$(
        #[test]
        fn $regions() {
            regions_by($name.parse().unwrap(), false);
        }
        #[test]
        fn $corpus() {
            corpus_by($name.parse().unwrap(), false);
        }
        #[test]
        fn $quad_regions() {
            regions_by($name.parse().unwrap(), true);
        }
        #[test]
        fn $quad_corpus() {
            corpus_by($name.parse().unwrap(), true);
        }
    )*};
}

method_tests! {
    quadtree_on_regions, quadtree_on_corpus_faces, quadtree_quads_on_regions, quadtree_quads_on_corpus_faces, "quadtree";
    removal_on_regions, removal_on_corpus_faces, removal_quads_on_regions, removal_quads_on_corpus_faces, "removal";
    front_on_regions, front_on_corpus_faces, front_quads_on_regions, front_quads_on_corpus_faces, "front";
    ear_on_regions, ear_on_corpus_faces, ear_quads_on_regions, ear_quads_on_corpus_faces, "ear";
    recursive_on_regions, recursive_on_corpus_faces, recursive_quads_on_regions, recursive_quads_on_corpus_faces, "recursive";
    delaunay_on_regions, delaunay_on_corpus_faces, delaunay_quads_on_regions, delaunay_quads_on_corpus_faces, "delaunay";
}

#[test]
fn every_method_is_tested_here() {
    let tested = ["quadtree", "removal", "front", "ear", "recursive", "delaunay"];
    for m in Method::ALL {
        assert!(tested.contains(&m.name()), "{} has no tests in this file", m.name());
    }
}

#[test]
fn poly_cli_writes_quads_and_refuses_bad_input() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("th.msh");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_fepre")).args(["mesh2d", region_file("two_holes").to_str().unwrap(), "--method", "quadtree", "--quads", "--json", "-o", out.to_str().unwrap()]).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!(v["quads"].as_u64().unwrap() > 0);
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.contains("\n2 1 3 "), "a block of quads (type 3) in entity 1");
    // a .poly whose segments cross: exit 1, the segments named, nothing written
    let bad = dir.path().join("bad.poly");
    std::fs::write(&bad, "4 2 0 0\n1 0 0\n2 1 1\n3 1 0\n4 0 1\n4 0\n1 1 2\n2 2 3\n3 3 4\n4 4 1\n0\n").unwrap();
    let out2 = dir.path().join("bad.msh");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_fepre")).args(["mesh2d", bad.to_str().unwrap(), "-o", out2.to_str().unwrap()]).output().unwrap();
    assert_eq!(o.status.code(), Some(1), "{}", String::from_utf8_lossy(&o.stderr));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("bad.poly") && err.contains("segment"), "{err}");
    assert!(!out2.exists());
    // a requirement not met: exit 1, nothing written
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_fepre")).args(["mesh2d", region_file("small_angle").to_str().unwrap(), "--require-min-angle", "40", "-o", out2.to_str().unwrap()]).output().unwrap();
    assert_eq!(o.status.code(), Some(1), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stderr).contains("under the 40 deg required"));
    assert!(!out2.exists());
}

#[test]
fn a_job_with_mesh2d_writes_the_mesh_and_the_report() {
    let dir = tempfile::tempdir().unwrap();
    let job = dir.path().join("plate.toml");
    std::fs::write(&job, format!("[input]\nfile = {:?}\n[density]\nsize = 0.2\n[mesh2d]\nmethod = \"quadtree\"\n[[output]]\nfile = \"plate.inp\"\n[[output]]\nfile = \"plate.json\"\n", region_file("l_shape"))).unwrap();
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_fepre")).args(["run", job.to_str().unwrap()]).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let inp = std::fs::read_to_string(dir.path().join("plate.inp")).unwrap();
    assert!(inp.contains("*ELEMENT, TYPE=CPS3, ELSET=REGION_1"), "{}", &inp[..inp.len().min(400)]);
    let rep: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(dir.path().join("plate.json")).unwrap()).unwrap();
    assert_eq!(rep["size"], 0.2);
    assert_eq!(rep["method"], "quadtree");
    // a method that does not exist is named with its line
    std::fs::write(&job, format!("[input]\nfile = {:?}\n[mesh2d]\nmethod = \"paving2\"\n", region_file("l_shape"))).unwrap();
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_fepre")).args(["run", job.to_str().unwrap()]).output().unwrap();
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("paving2") && err.contains(":4:"), "{err}");
    // the library call the job makes, on a lone region with the defaults
    let r = mesh2d_poly(&region_file("convex"), &Mesh2dRequest::default(), None).unwrap();
    assert_eq!(r.meshed, 1);
    assert!(r.triangles > 100, "{}", r.triangles);
}

#[test]
fn the_same_bytes_for_one_and_two_threads() {
    let dir = tempfile::tempdir().unwrap();
    let part = Path::new(env!("CARGO_MANIFEST_DIR")).join("cad_fixtures/bracket.step");
    let inputs = [(part.clone(), "delaunay", false), (part, "front", true), (region_file("two_holes"), "delaunay", false), (region_file("comb"), "ear", true)];
    for (k, (input, method, quads)) in inputs.iter().enumerate() {
        let mut outs = Vec::new();
        for threads in ["1", "2"] {
            let out = dir.path().join(format!("{k}_{threads}.msh"));
            let mut cmd = std::process::Command::new(env!("CARGO_BIN_EXE_fepre"));
            cmd.env("RAYON_NUM_THREADS", threads).args(["mesh2d", input.to_str().unwrap(), "--method", method, "-o", out.to_str().unwrap()]);
            if *quads {
                cmd.arg("--quads");
            }
            let o = cmd.output().unwrap();
            assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
            outs.push(std::fs::read(&out).unwrap());
        }
        assert!(outs[0] == outs[1], "{} by {method}: the output differs between 1 and 2 threads", input.display());
    }
}

#[test]
fn a_job_meshes_its_own_polygons() {
    let dir = tempfile::tempdir().unwrap();
    let job = dir.path().join("plate.toml");
    let run = |text: &str, extra: &[&str]| {
        std::fs::write(&job, text).unwrap();
        std::process::Command::new(env!("CARGO_BIN_EXE_fepre")).arg("run").arg(&job).args(extra).output().unwrap()
    };
    let region = "[[mesh2d.region]]\nouter = [[0, 0], [4, 0], [4, 2], [0, 2]]\nholes = [[[1, 0.5], [1.5, 0.5], [1.5, 1.5], [1, 1.5]]]\ntag = 5\n";
    let text = format!("units = \"cm\"\n[density]\nsize = 0.2\n[mesh2d]\nmethod = \"front\"\nquads = true\n{region}[[output]]\nfile = \"plate.inp\"\n[[output]]\nfile = \"plate.json\"\n");
    let o = run(&text, &["--check"]);
    assert!(o.status.success() && String::from_utf8_lossy(&o.stdout).contains("1 polygon region"), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(!dir.path().join("plate.inp").exists(), "--check wrote the mesh");
    let o = run(&text, &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let inp = std::fs::read_to_string(dir.path().join("plate.inp")).unwrap();
    assert!(inp.contains("*ELEMENT, TYPE=CPS4, ELSET=REGION_5"), "{}", &inp[..inp.len().min(400)]);
    let rep: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(dir.path().join("plate.json")).unwrap()).unwrap();
    assert_eq!(rep["triangles"], 0);
    // the polygon and the mesh in the job's units (cm): the plate's area less the hole's
    let area = rep["quality"]["area"].as_f64().unwrap();
    assert!((area - 7.5).abs() < 1e-9, "area {area}");
    assert_eq!(rep["size"], 0.2);
    // a hole outside the boundary, and polygons beside an [input] file: exit 1, the line named
    let bad = format!("[mesh2d]\n[[mesh2d.region]]\nouter = [[0, 0], [4, 0], [4, 2], [0, 2]]\nholes = [[[5, 0.5], [6, 0.5], [6, 1.5]]]\n[[output]]\nfile = \"bad.msh\"\n");
    let o = run(&bad, &[]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("hole") && err.contains(":2:"), "{err}");
    assert!(!dir.path().join("bad.msh").exists());
    let o = run(&format!("[input]\nfile = \"a.poly\"\n[mesh2d]\n{region}"), &[]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("one or the other"), "{}", String::from_utf8_lossy(&o.stderr));
}
