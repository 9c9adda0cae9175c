//! The surface writers without tags or with text tags (STL binary and ASCII, OBJ, OFF), read
//! back by independent readers: meshio (counts, OBJ groups as cell blocks) and trimesh (ASCII
//! STL solids by name). The volume formats are checked in `io_roundtrip_external.rs`.

mod common;

use common::tools::{python_with, require, run_ok};
use fepre::io::{MeshData, ReadOptions, WriteOptions, read, write};
use fepre::mesh::TriSurface;
use std::path::Path;
use std::process::Command;

fn fixture() -> TriSurface {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("cad_fixtures/plate_with_hole.obj");
    match read(&p, &ReadOptions::default()).unwrap().mesh {
        MeshData::Surface(s) => s,
        other => panic!("expected a surface, got a {}", other.kind()),
    }
}

#[test]
fn meshio_and_trimesh_read_our_surface_files() {
    let Some(python) = require(python_with(&["meshio", "trimesh", "numpy"]), "python with meshio and trimesh", "surface round trips")
    else {
        return;
    };
    let s = fixture();
    let tags = s.tags();
    let per_tag: Vec<usize> = tags.iter().map(|t| s.face_tags.iter().filter(|x| *x == t).count()).collect();
    let names: Vec<String> = tags.iter().map(|t| s.face_names.get(*t).expect("every tag is named").to_string()).collect();
    assert_eq!(per_tag.len(), 7);
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mesh = MeshData::Surface(s.clone());
    write(&d.join("b.stl"), &mesh, &WriteOptions::default()).unwrap();
    write(&d.join("a.stl"), &mesh, &WriteOptions::default().with_ascii(true)).unwrap();
    write(&d.join("s.obj"), &mesh, &WriteOptions::default()).unwrap();
    write(&d.join("s.off"), &mesh, &WriteOptions::default()).unwrap();
    let script = r#"
import sys, json, warnings
warnings.simplefilter("ignore")
import meshio, trimesh
out = {}
for f in ["b.stl", "a.stl", "s.obj", "s.off"]:
    m = meshio.read(f)
    out[f] = {"points": len(m.points), "blocks": [[c.type, len(c.data)] for c in m.cells]}
scene = trimesh.load("a.stl", force="scene")
out["solids"] = [[k, len(g.faces)] for k, g in scene.geometry.items()]
print(json.dumps(out))
"#;
    let o = run_ok(Command::new(python).arg("-c").arg(script), d);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let nv = s.vertices.len() as u64;
    let nt = s.triangles.len() as u64;
    for f in ["b.stl", "a.stl", "s.off"] {
        assert_eq!(v[f]["points"], nv, "{f}: points");
        let blocks = v[f]["blocks"].as_array().unwrap();
        let total: u64 = blocks.iter().map(|b| b[1].as_u64().unwrap()).sum();
        assert!(blocks.iter().all(|b| b[0] == "triangle"), "{f}: {blocks:?}");
        assert_eq!(total, nt, "{f}: triangles");
    }
    // OBJ: one meshio cell block per group, in tag order
    assert_eq!(v["s.obj"]["points"], nv);
    let obj: Vec<u64> = v["s.obj"]["blocks"].as_array().unwrap().iter().map(|b| b[1].as_u64().unwrap()).collect();
    assert_eq!(obj, per_tag.iter().map(|&n| n as u64).collect::<Vec<_>>(), "OBJ groups as meshio cell blocks");
    // ASCII STL: one solid per tag, named after it
    let solids: Vec<(String, u64)> =
        v["solids"].as_array().unwrap().iter().map(|x| (x[0].as_str().unwrap().to_string(), x[1].as_u64().unwrap())).collect();
    let want: Vec<(String, u64)> = names.iter().cloned().zip(per_tag.iter().map(|&n| n as u64)).collect();
    assert_eq!(solids, want, "ASCII STL solids as trimesh geometries");
}
