//! Bad input through the command line: exit code 1, a message naming the file (and the line or
//! entity), and `convert` leaves no output file behind. Bad usage: exit code 2.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn fepre(args: &[&std::ffi::OsStr]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_fepre")).args(args).output().expect("run fepre")
}

fn check_rejected(input: &Path, must_mention: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.msh");
    for args in [vec![input.as_os_str().to_owned()], vec![input.as_os_str().to_owned(), out.as_os_str().to_owned()]] {
        let cmd = if args.len() == 1 { "inspect" } else { "convert" };
        let mut full: Vec<std::ffi::OsString> = vec![cmd.into()];
        full.extend(args);
        let refs: Vec<&std::ffi::OsStr> = full.iter().map(|s| s.as_os_str()).collect();
        let o = fepre(&refs);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{cmd} {}: expected exit 1, stderr: {err}", input.display());
        let name = input.file_name().unwrap().to_string_lossy();
        assert!(err.contains(&*name), "{cmd}: message does not name the file {name}: {err}");
        for m in must_mention {
            assert!(err.contains(m), "{cmd} {}: message lacks '{m}': {err}", input.display());
        }
        assert!(!out.exists(), "convert left {} behind", out.display());
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0, "convert left a temporary file behind");
    }
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

fn tetra_stl_binary() -> Vec<u8> {
    let tris: [[[f32; 3]; 3]; 4] = [
        [[0., 0., 0.], [0., 1., 0.], [1., 0., 0.]],
        [[0., 0., 0.], [1., 0., 0.], [0., 0., 1.]],
        [[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]],
        [[0., 0., 0.], [0., 0., 1.], [0., 1., 0.]],
    ];
    let mut b = b"solid but actually binary".to_vec();
    b.resize(80, b' ');
    b.extend_from_slice(&4u32.to_le_bytes());
    for t in tris {
        b.extend_from_slice(&[0u8; 12]);
        for v in t {
            for c in v {
                b.extend_from_slice(&c.to_le_bytes());
            }
        }
        b.extend_from_slice(&[0, 0]);
    }
    b
}

#[test]
fn truncated_binary_stl() {
    let dir = tempfile::tempdir().unwrap();
    let good = tetra_stl_binary();
    let ok = write(dir.path(), "good.stl", &good);
    let o = fepre(&["inspect".as_ref(), ok.as_os_str()]);
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    let p = write(dir.path(), "truncated.stl", &good[..good.len() - 20]);
    check_rejected(&p, &["truncated"]);
}

#[test]
fn ascii_stl_with_nan() {
    let dir = tempfile::tempdir().unwrap();
    let text = "solid t\n facet normal 0 0 -1\n  outer loop\n   vertex 0 0 0\n   vertex 0 1 0\n   vertex 1 0 0\n  endloop\n endfacet\n \
                facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 NaN\n   vertex 0 0 1\n  endloop\n endfacet\nendsolid t\n";
    let p = write(dir.path(), "nan.stl", text.as_bytes());
    check_rejected(&p, &["nan.stl:12"]);
}

#[test]
fn obj_with_index_out_of_range() {
    let dir = tempfile::tempdir().unwrap();
    let text = "# a tetrahedron with a bad face\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 9\nf 1 4 3\n";
    let p = write(dir.path(), "bad_index.obj", text.as_bytes());
    check_rejected(&p, &["bad_index.obj:8"]);
}

/// A minimal valid GLB holding one triangle.
fn glb_triangle() -> Vec<u8> {
    let mut bin = Vec::new();
    for v in [[0f32, 0., 0.], [1., 0., 0.], [0., 1., 0.]] {
        for c in v {
            bin.extend_from_slice(&c.to_le_bytes());
        }
    }
    let json = r#"{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],
"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36}],"buffers":[{"byteLength":36}]}"#;
    let mut j = json.as_bytes().to_vec();
    while j.len() % 4 != 0 {
        j.push(b' ');
    }
    let total = 12 + 8 + j.len() + 8 + bin.len();
    let mut g = Vec::new();
    g.extend_from_slice(b"glTF");
    g.extend_from_slice(&2u32.to_le_bytes());
    g.extend_from_slice(&(total as u32).to_le_bytes());
    g.extend_from_slice(&(j.len() as u32).to_le_bytes());
    g.extend_from_slice(b"JSON");
    g.extend_from_slice(&j);
    g.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    g.extend_from_slice(b"BIN\0");
    g.extend_from_slice(&bin);
    g
}

#[test]
fn glb_with_broken_chunk() {
    let dir = tempfile::tempdir().unwrap();
    let good = glb_triangle();
    let ok = write(dir.path(), "good.glb", &good);
    let o = fepre(&["inspect".as_ref(), ok.as_os_str()]);
    assert_eq!(o.status.code(), Some(0), "a valid GLB must load: {}", String::from_utf8_lossy(&o.stderr));
    // the BIN chunk claims more bytes than the file has
    let mut broken = good.clone();
    let json_len = u32::from_le_bytes(good[12..16].try_into().unwrap()) as usize;
    let bin_header = 20 + json_len;
    broken[bin_header..bin_header + 4].copy_from_slice(&4000u32.to_le_bytes());
    let p = write(dir.path(), "broken_chunk.glb", &broken);
    check_rejected(&p, &["chunk"]);
}

#[test]
fn empty_file_directory_and_missing_file() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(dir.path(), "empty.stl", b"");
    check_rejected(&p, &["empty"]);
    let sub = dir.path().join("a_directory.obj");
    std::fs::create_dir(&sub).unwrap();
    check_rejected(&sub, &["directory"]);
    let missing = dir.path().join("no_such_file.off");
    check_rejected(&missing, &[]);
}

#[test]
fn bad_usage_exits_2() {
    let dir = tempfile::tempdir().unwrap();
    let ok = write(dir.path(), "good.stl", &tetra_stl_binary());
    let out = dir.path().join("out.xyz");
    let o = fepre(&["convert".as_ref(), ok.as_os_str(), out.as_os_str()]);
    assert_eq!(o.status.code(), Some(2), "unwritable output extension: {}", String::from_utf8_lossy(&o.stderr));
    assert!(!out.exists());
    assert_eq!(fepre(&["inspect".as_ref()]).status.code(), Some(2));
    assert_eq!(fepre(&["--no-such-flag".as_ref()]).status.code(), Some(2));
    assert_eq!(fepre(&["convert".as_ref(), ok.as_os_str(), "x.stl".as_ref(), "--weld".as_ref(), "-1".as_ref()]).status.code(), Some(2));
    let h = fepre(&["--help".as_ref()]);
    assert_eq!(h.status.code(), Some(0));
    assert!(String::from_utf8_lossy(&h.stdout).contains("Examples:"));
}

#[test]
fn a_failure_with_json_prints_its_error_as_json() {
    // a machine reading standard output gets the reason, not an empty output
    let dir = tempfile::tempdir().unwrap();
    let open = write(dir.path(), "open.stl", b"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n");
    let out = dir.path().join("open.mesh");
    let o = fepre(&["mesh".as_ref(), open.as_os_str(), "-o".as_ref(), out.as_os_str(), "--json".as_ref()]);
    assert_eq!(o.status.code(), Some(1), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("one JSON object on standard output");
    let msg = v["error"].as_str().unwrap_or_default();
    assert!(msg.contains("open.stl") && msg.contains("open"), "{v}");
    assert_eq!(v["exit_code"], 1);
    assert!(!out.exists());
    // without --json, nothing on standard output
    let o = fepre(&["mesh".as_ref(), open.as_os_str(), "-o".as_ref(), out.as_os_str()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(o.stdout.is_empty(), "{}", String::from_utf8_lossy(&o.stdout));
}
