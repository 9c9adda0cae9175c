//! Our STEP writer on real parts: every STEP file of the shared corpus is read, written and
//! read again. The second model has the same solids, shells, faces, loops, edges, vertices,
//! surface kinds and face names, and tessellates (default options) to the same number of
//! triangles and the same volume (up to the rounding of renormalised directions). Where Python
//! with OCP (cadquery-ocp) is found, OpenCASCADE reads every written file as valid, with the
//! faces, solids and volume (within 0.1 %) it reads from the original.

mod common;

use fepre::cad::brep::Model;
use fepre::cad::step;
use fepre::mesh::topology::{ReportOptions, surface_report};
use fepre::tessellate::{TessellateOptions, tessellate};

fn volume(m: &Model) -> (usize, f64) {
    let t = tessellate(m, &TessellateOptions::default());
    let r = surface_report(&t.surface, &ReportOptions::default().with_self_intersections(false));
    (t.surface.triangles.len(), r.volume)
}

#[test]
fn corpus_files_survive_write_and_read() {
    let Some(dir) = common::corpus_dir() else { return };
    let tmp = tempfile::tempdir().unwrap();
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| matches!(x.to_ascii_lowercase().to_str(), Some("step" | "stp"))))
        .collect();
    files.sort();
    let mut failures = Vec::new();
    for path in files {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let m = step::read(&path).unwrap();
        let out = tmp.path().join(&name);
        if let Err(e) = step::write(&out, &m, "corpus") {
            failures.push(format!("{name}: {e}"));
            continue;
        }
        let back = step::read(&out).unwrap();
        let counts = |m: &Model| (m.solids.len(), m.shells.len(), m.faces.len(), m.loops.len(), m.edges.len(), m.vertices.len());
        let kinds = |m: &Model| m.surfaces.iter().map(|s| s.kind()).collect::<Vec<_>>();
        let names = |m: &Model| m.faces.iter().map(|f| f.name.clone()).collect::<Vec<_>>();
        if counts(&back) != counts(&m) || kinds(&back) != kinds(&m) || names(&back) != names(&m) || !back.dropped.is_empty() {
            failures.push(format!("{name}: counts {:?} -> {:?}, dropped {:?}", counts(&m), counts(&back), back.dropped.first()));
            continue;
        }
        let ((ta, va), (tb, vb)) = (volume(&m), volume(&back));
        eprintln!("{name}: {} faces, {ta} / {tb} triangles, volume {va:.6} / {vb:.6}", m.faces.len());
        if ta != tb || (va - vb).abs() > 1e-7 * va.abs().max(1.0) {
            failures.push(format!("{name}: triangles {ta} -> {tb}, volume {va} -> {vb}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The JSON lines of `ocpref.py` for `files`, by file name.
fn ocpref(python: &std::path::Path, files: &[std::path::PathBuf]) -> std::collections::BTreeMap<String, serde_json::Value> {
    let script = common::shared_dir().join("tools/occ/ocpref.py");
    let out = common::tools::run_ok(std::process::Command::new(python).arg(&script).args(files), std::path::Path::new("."));
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .filter_map(|l| serde_json::from_str::<serde_json::Value>(l).ok())
        .filter_map(|v| Some((v["file"].as_str()?.to_string(), v)))
        .collect()
}

#[test]
fn opencascade_reads_the_rewritten_corpus_like_the_original() {
    let Some(dir) = common::corpus_dir() else { return };
    let Some(python) = common::tools::require(common::tools::python_with(&["OCP"]), "Python with OCP (cadquery-ocp)", "the OpenCASCADE check of rewritten corpus files")
    else {
        return;
    };
    let tmp = tempfile::tempdir().unwrap();
    let mut originals: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| matches!(x.to_ascii_lowercase().to_str(), Some("step" | "stp"))))
        .collect();
    originals.sort();
    let mut written = Vec::new();
    for p in &originals {
        let out = tmp.path().join(p.file_name().unwrap());
        step::write(&out, &step::read(p).unwrap(), "corpus").unwrap();
        written.push(out);
    }
    let (a, b) = (ocpref(&python, &originals), ocpref(&python, &written));
    let mut failures = Vec::new();
    for (name, orig) in &a {
        let Some(new) = b.get(name) else {
            failures.push(format!("{name}: no answer for the written file"));
            continue;
        };
        let (va, vb) = (orig["volume_mm3"].as_f64().unwrap_or(f64::NAN), new["volume_mm3"].as_f64().unwrap_or(f64::NAN));
        eprintln!("{name}: OCC volume {va} (original) / {vb} (written), valid {}", new["valid"]);
        let same = new["read"] == "OK" && new["valid"] == true && new["faces"] == orig["faces"] && new["solids"] == orig["solids"];
        let close = (va - vb).abs() <= 1e-3 * va.abs(); // false for NaN
        if !same || !close {
            failures.push(format!("{name}: original {orig}\nwritten {new}"));
        }
    }
    assert_eq!(a.len(), originals.len(), "ocpref.py answered for {} of {} files", a.len(), originals.len());
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
