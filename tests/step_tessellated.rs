//! AP242 tessellated geometry end to end: a part built in code (a block with a hole through
//! it), tessellated, written by our writer as a tessellated-only AP242 file (a
//! `TESSELLATED_SOLID` of `TRIANGULATED_FACE`s with `pnindex`, every third face a
//! `COMPLEX_TRIANGULATED_FACE` of strips and fans), read back (same triangles, tags, names),
//! certified as a mesh, reported by `fepre cad-info` and `fepre tessellate`, meshed by
//! `fepre mesh` into a valid tet mesh of the same volume, and compared with OpenCASCADE's
//! volume and area of the same file (`shared/tools/occ/ocpref.py` through `$FEPRE_PYTHON`;
//! skipped when missing, a failure under `CI=true`).

mod common;

use common::tools;
use fepre::cad::parts::Block;
use fepre::cad::step::{self, Shape};
use fepre::core::FaceId;
use fepre::io::{MeshData, ReadOptions};
use fepre::mesh::TriSurface;
use fepre::pipeline::certify_surface;
use fepre::tessellate::{TessellateOptions, tessellate};
use std::path::Path;
use std::process::{Command, Output};

fn fepre(args: &[&std::ffi::OsStr]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_fepre")).args(args).output().expect("run fepre")
}

/// The block's tessellation and the tags written as complex faces.
fn block_surface() -> (TriSurface, Vec<FaceId>) {
    let model = Block::default().with_hole(4.0).build().unwrap();
    let mut s = tessellate(&model, &TessellateOptions::default().with_chord_relative(1e-3)).surface;
    for f in model.face_ids() {
        s.face_names.insert(f, format!("face_{}", f.0));
    }
    let complex: Vec<FaceId> = s.tags().into_iter().filter(|f| f.0 % 3 == 0).collect();
    (s, complex)
}

/// Triangles as sorted (tag, corner coordinates from the smallest index) for comparison.
fn triangles(s: &TriSurface) -> Vec<(u32, [[u64; 3]; 3])> {
    let mut v: Vec<_> = s
        .triangles
        .iter()
        .zip(&s.face_tags)
        .map(|(t, f)| {
            let c = t.map(|i| s.vertices[i as usize].to_array().map(f64::to_bits));
            let r = (0..3).min_by_key(|&k| c[k]).unwrap_or(0);
            (f.0, [c[r], c[(r + 1) % 3], c[(r + 2) % 3]])
        })
        .collect();
    v.sort_unstable();
    v
}

fn write_block(dir: &Path) -> (std::path::PathBuf, TriSurface) {
    let (s, complex) = block_surface();
    let path = dir.join("block_tess.stp");
    step::write_tessellated(&path, &s, "block", &complex).unwrap();
    // FEPRE_TESS_OUT=DIR keeps a copy (docs/benchmarks.md measures it)
    if let Some(keep) = std::env::var_os("FEPRE_TESS_OUT") {
        std::fs::copy(&path, Path::new(&keep).join("block_tess.stp")).unwrap();
    }
    (path, s)
}

#[test]
fn a_tessellated_only_file_reads_certifies_and_meshes() {
    let dir = tempfile::tempdir().unwrap();
    let (path, s) = write_block(dir.path());
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("COMPLEX_TRIANGULATED_FACE(") && text.contains("TESSELLATED_SOLID("));
    assert!(!text.contains("ADVANCED_FACE"));
    let Shape::Tessellated(t) = step::read_shape(&path).unwrap() else { panic!("expected tessellated geometry") };
    assert_eq!(triangles(&t.surface), triangles(&s), "same triangles with the same tags");
    assert_eq!(t.surface.vertices.len(), s.vertices.len());
    assert_eq!(t.faces.len(), s.tags().len());
    for f in &t.faces {
        assert_eq!(t.surface.face_names.get(f.face), s.face_names.get(f.face), "name of {}", f.face.0);
    }
    assert_eq!(t.solids.len(), 1);
    assert_eq!(t.solids[0].name.as_deref(), Some("block"));
    let c = certify_surface(&t.surface);
    assert!(c.passed, "{c:?}");
    let exact = Block::default().with_hole(4.0).volume();
    assert!(((c.volume - exact) / exact).abs() < 2e-3, "{} vs {exact}", c.volume);

    // fepre cad-info and fepre tessellate say what the file is
    let out = fepre(&["cad-info".as_ref(), path.as_os_str(), "--json".as_ref()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["tessellated"], true);
    assert_eq!(v["faces"].as_u64(), Some(t.faces.len() as u64));
    assert_eq!(v["triangles"].as_u64(), Some(s.triangles.len() as u64));
    assert_eq!(v["solids"].as_u64(), Some(1));
    assert_eq!(v["certificate"]["passed"], true);
    let stl = dir.path().join("block.stl");
    let out = fepre(&["tessellate".as_ref(), path.as_os_str(), "-o".as_ref(), stl.as_os_str(), "--json".as_ref()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["tessellated"], true);
    assert_eq!(v["certificate"]["closed"], true);
    assert_eq!(v["face_table"][0]["name"], "face_1");
    assert!(v["face_table"][0]["step_id"].as_u64().is_some());
    assert!(stl.is_file());

    // fepre mesh: a valid tet mesh of the same volume
    let mesh = dir.path().join("block.mesh");
    let out = fepre(&["mesh".as_ref(), path.as_os_str(), "-o".as_ref(), mesh.as_os_str()]);
    assert!(out.status.success(), "{}\n{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    let MeshData::Volume(m) = fepre::io::read(&mesh, &ReadOptions::default()).unwrap().mesh else { panic!("expected tets") };
    m.validate().unwrap();
    assert!(((m.volume() - c.volume) / c.volume).abs() < 1e-9, "{} vs {}", m.volume(), c.volume);
    let mut tags: Vec<FaceId> = m.face_tags.clone();
    tags.sort_unstable();
    tags.dedup();
    assert_eq!(tags, s.tags(), "every tessellated face tags the mesh's boundary");
}

#[test]
fn the_tessellated_file_agrees_with_opencascade() {
    let Some(python) = tools::require(tools::python_with(&["OCP"]), "Python with OCP (pip install cadquery-ocp)", "the OpenCASCADE oracle of tessellated files") else { return };
    let script = common::shared_dir().join("tools/occ/ocpref.py");
    if !script.is_file() {
        assert!(!common::in_ci(), "{} is missing (CI=true)", script.display());
        eprintln!("SKIP: {} is missing", script.display());
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let (path, s) = write_block(dir.path());
    let out = Command::new(&python).arg(&script).arg(&path).output().expect("run ocpref.py");
    assert!(out.status.success(), "ocpref.py failed: {}", String::from_utf8_lossy(&out.stderr));
    let line = String::from_utf8_lossy(&out.stdout);
    let r: serde_json::Value = serde_json::from_str(line.lines().next().unwrap_or("{}")).unwrap();
    let c = certify_surface(&s);
    let (occ_v, occ_a) = (r["volume_mm3"].as_f64().unwrap_or(f64::NAN), r["area_mm2"].as_f64().unwrap_or(f64::NAN));
    eprintln!("block_tess.stp: volume {:.9} / OCC {occ_v:.9}, area {:.9} / OCC {occ_a:.9}, faces {} / OCC {}, solids OCC {}", c.volume, c.area, s.tags().len(), r["faces"], r["solids"]);
    assert_eq!(r["faces"].as_u64(), Some(s.tags().len() as u64), "{r}");
    assert_eq!(r["solids"].as_u64(), Some(1), "{r}");
    assert!(((c.volume - occ_v) / occ_v).abs() < 1e-9, "volume {} vs OpenCASCADE {occ_v}", c.volume);
    assert!(((c.area - occ_a) / occ_a).abs() < 1e-9, "area {} vs OpenCASCADE {occ_a}", c.area);
}
