//! `fepre run job.toml`: the worked bracket job meets its sizes, job errors name the key and
//! its line and write nothing, `--check` lists what selectors select, and the output does not
//! depend on the thread count.

use fepre::core::point_triangle_distance;
use fepre::io::{MeshData, ReadOptions, read};
use fepre::mesh::TetMesh;
use glam::DVec3;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn fepre(args: &[&str], env: &[(&str, &str)]) -> Output {
    let mut c = Command::new(env!("CARGO_BIN_EXE_fepre"));
    c.args(args);
    for (k, v) in env {
        c.env(k, v);
    }
    c.output().expect("runs fepre")
}

fn bracket_step() -> String {
    std::fs::canonicalize("cad_fixtures/bracket.step").unwrap().display().to_string()
}

fn median(mut v: Vec<f64>) -> f64 {
    assert!(!v.is_empty());
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn tet_mesh(path: &Path) -> TetMesh {
    match read(path, &ReadOptions::default()).unwrap().mesh {
        MeshData::Volume(m) => m,
        other => panic!("{}: {}", path.display(), other.kind()),
    }
}

#[test]
fn the_bracket_job_meets_its_sizes() {
    // the README's second main job: half the global size (4.5) on the four holes
    let o = fepre(&["run", "cad_fixtures/bracket.toml", "--json"], &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let report: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    let (global, hole) = (4.5, 2.25);
    let holes: BTreeSet<u32> = report["face_table"].as_array().unwrap().iter().filter(|f| f["name"].as_str().is_some_and(|n| n.starts_with("hole_"))).map(|f| f["face"].as_u64().unwrap() as u32).collect();
    assert_eq!(holes.len(), 8, "four holes of two half cylinders");
    let sel: BTreeSet<u32> = report["selectors"]["holes"].as_array().unwrap().iter().map(|x| x.as_u64().unwrap() as u32).collect();
    assert_eq!(sel, holes);
    let m = tet_mesh(Path::new("target/bracket.msh"));
    assert_eq!(m.validate(), Ok(()));
    let p = |v: u32| m.vertices[v as usize];
    let edges = |t: &[u32]| -> Vec<f64> { (0..t.len()).flat_map(|i| (i + 1..t.len()).map(move |j| (i, j))).map(|(i, j)| p(t[i]).distance(p(t[j]))).collect() };
    // boundary triangles: hole faces at the hole size, faces away from the holes at the global size
    let hole_vertices: BTreeSet<u32> = m.boundary.iter().zip(&m.face_tags).filter(|(_, g)| holes.contains(&g.0)).flat_map(|(t, _)| *t).collect();
    let (mut on_holes, mut away) = (Vec::new(), Vec::new());
    let mut away_faces = BTreeSet::new();
    for (t, g) in m.boundary.iter().zip(&m.face_tags) {
        if holes.contains(&g.0) {
            on_holes.extend(edges(t));
        } else if !m.boundary.iter().zip(&m.face_tags).any(|(u, h)| h == g && u.iter().any(|v| hole_vertices.contains(v))) {
            away.extend(edges(t));
            away_faces.insert(g.0);
        }
    }
    assert!(away_faces.len() >= 5, "faces away from the holes: {away_faces:?}");
    let (mh, ma) = (median(on_holes), median(away));
    println!("median boundary edge: holes {mh:.3} (asked {hole}), away {ma:.3} (asked {global})");
    assert!((mh - hole).abs() <= 0.15 * hole, "hole faces: median edge {mh}");
    assert!((ma - global).abs() <= 0.15 * global, "faces away from the holes: median edge {ma}");
    // tets within 1 mm of a hole face
    let hole_tris: Vec<[DVec3; 3]> = m.boundary.iter().zip(&m.face_tags).filter(|(_, g)| holes.contains(&g.0)).map(|(t, _)| t.map(p)).collect();
    let mut near = Vec::new();
    for t in &m.tets {
        let c = t.iter().map(|&v| p(v)).sum::<DVec3>() / 4.0;
        if hole_tris.iter().any(|tri| point_triangle_distance(c, *tri) < 1.0) {
            near.extend(edges(t));
        }
    }
    let mt = median(near);
    println!("median edge of tets near the holes {mt:.3} (asked {hole})");
    assert!((mt - hole).abs() <= 0.2 * hole, "tets near the holes: median edge {mt}");
    // the quality the mesher promises, and the report says so
    assert!(report["mesh"]["min_dihedral_deg"].as_f64().unwrap() >= 10.0, "{}", report["mesh"]);
    assert_eq!(report["mesh"]["tets_under_1_deg"].as_u64(), Some(0));
    assert!(Path::new("target/bracket.json").is_file());
}

/// A job in a fresh folder, reading the bracket by absolute path and writing `out.msh` there.
fn job(dir: &Path, body: &str) -> PathBuf {
    let text = format!("[input]\nfile = \"{}\"\n{body}\n[[output]]\nfile = \"out.msh\"\n", bracket_step());
    let path = dir.join("job.toml");
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn job_errors_name_the_key_and_its_line_and_write_nothing() {
    // (the job's body, the line the error is on, words the message must hold)
    let cases: [(&str, usize, &[&str]); 7] = [
        ("[density]\nsise = 3", 4, &["sise"]),
        ("[density]\nsize = \"big\"", 4, &["size"]),
        ("[density]\nsize = 0", 4, &["size", "> 0"]),
        ("[density]\nbox = [{ min = [0, 0, 9], max = [10, 10, 1], size = 1 }]", 4, &["above max"]),
        ("[selectors]\nnone = { name = \"no_such_face*\" }\n[density]\nface = [{ faces = \"none\", size = 1 }]", 4, &["none", "selects no face"]),
        ("[density]\nface = [{ faces = \"undefined\", size = 1 }]", 4, &["undefined", "is defined"]),
        ("[selectors]\nx = { faces = [99] }", 4, &["no face 99"]),
    ];
    for (body, line, words) in cases {
        let dir = tempfile::tempdir().unwrap();
        let path = job(dir.path(), body);
        let o = fepre(&["run", path.to_str().unwrap()], &[]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{body}: {err}");
        assert!(err.contains(&format!("job.toml:{line}:")), "{body}: the line is not named: {err}");
        for w in words {
            assert!(err.contains(w), "{body}: '{w}' is not in: {err}");
        }
        assert!(!dir.path().join("out.msh").exists(), "{body}: an output was written");
    }
}

#[test]
fn check_lists_what_each_selector_selects_and_meshes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let path = job(dir.path(), "[selectors]\nholes = { name = \"hole_*\" }\nend = { plane = { normal = [1, 0, 0], offset = 80 } }\nbig = { largest = {} }\nround = { cylinder = { axis = [0, 0, 1], radius = 4.5 } }\nboth = { intersection = [\"holes\", \"round\"] }\nnear = { nearest = [80, 15, 4] }");
    let o = fepre(&["run", path.to_str().unwrap(), "--check", "--json"], &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let r: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let sel = |n: &str| r["selectors"][n].as_array().unwrap().iter().map(|x| x.as_u64().unwrap()).collect::<Vec<_>>();
    assert_eq!(sel("holes").len(), 8);
    assert_eq!(sel("round"), sel("holes"), "the holes are the cylinders of radius 4.5");
    assert_eq!(sel("both"), sel("holes"));
    let name = |id: u64| r["face_table"].as_array().unwrap().iter().find(|f| f["face"].as_u64() == Some(id)).and_then(|f| f["name"].as_str()).unwrap().to_string();
    assert_eq!(sel("end").iter().map(|&i| name(i)).collect::<Vec<_>>(), ["end_x"]);
    assert_eq!(sel("near"), sel("end"));
    assert_eq!(sel("big").len(), 1);
    assert!(["top", "bottom"].contains(&name(sel("big")[0]).as_str()));
    assert!(r["mesh"].is_null());
    assert!(!dir.path().join("out.msh").exists());
    // a difference that selects nothing is an error naming it
    let o = fepre(&["run", path.to_str().unwrap(), "--check"], &[]);
    assert!(o.status.success());
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("holes: 8 faces") && text.contains("(hole_1)"), "{text}");
    let dir2 = tempfile::tempdir().unwrap();
    let bad = job(dir2.path(), "[selectors]\nholes = { name = \"hole_*\" }\nround = { cylinder = { radius = 4.5 } }\nrest = { difference = [\"round\", \"holes\"] }");
    let o = fepre(&["run", bad.to_str().unwrap(), "--check"], &[]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("'rest' selects no face"), "{}", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn the_same_job_gives_the_same_bytes_for_any_thread_count_and_load() {
    let dir = tempfile::tempdir().unwrap();
    let path = job(dir.path(), "[selectors]\nholes = { name = \"hole_*\" }\n[density]\nsize = 6\nface = [{ faces = \"holes\", size = 2 }]");
    // a busy thread beside the runs
    let stop = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    let busy = {
        let stop = stop.clone();
        std::thread::spawn(move || {
            let mut x = 0u64;
            while !stop.load(std::sync::atomic::Ordering::Relaxed) {
                x = x.wrapping_mul(6364136223846793005).wrapping_add(1);
            }
            x
        })
    };
    let mut outputs = Vec::new();
    for threads in ["1", "2", "1", "2"] {
        let o = fepre(&["run", path.to_str().unwrap()], &[("RAYON_NUM_THREADS", threads)]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        outputs.push(std::fs::read(dir.path().join("out.msh")).unwrap());
    }
    stop.store(true, std::sync::atomic::Ordering::Relaxed);
    busy.join().unwrap();
    assert!(outputs.windows(2).all(|w| w[0] == w[1]), "the outputs differ");
}
