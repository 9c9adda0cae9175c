use super::poly::triangulate;
use super::*;
use crate::io::{PlcSeeds, ReadOptions, WriteOptions, write};

use crate::io::test_meshes::{two_tets, two_tets_surface as surface};

fn put(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

#[test]
fn volume_round_trips_through_every_extension() {
    let dir = tempfile::tempdir().unwrap();
    let m = two_tets();
    for ext in ["node", "ele", "face"] {
        let p = dir.path().join(format!("v{ext}.{ext}"));
        write(&p, &MeshData::Volume(m.clone()), &WriteOptions::default()).unwrap();
        for read_ext in ["node", "ele"] {
            let l = crate::io::read(&p.with_extension(read_ext), &ReadOptions::default()).unwrap();
            assert_eq!(l.mesh, MeshData::Volume(m.clone()));
            assert!(l.notes.is_empty(), "{:?}", l.notes);
        }
    }
    let e = write(&dir.path().join("v.poly"), &MeshData::Volume(m), &WriteOptions::default()).unwrap_err();
    assert!(matches!(e, IoError::NotRepresentable { .. }), "{e}");
}

#[test]
fn surface_and_points_round_trip() {
    let dir = tempfile::tempdir().unwrap();
    let s = surface();
    for ext in ["poly", "smesh", "face"] {
        let p = dir.path().join(format!("s.{ext}"));
        write(&p, &MeshData::Surface(s.clone()), &WriteOptions::default()).unwrap();
        let l = crate::io::read(&p, &ReadOptions::default().with_weld(None)).unwrap();
        assert_eq!(l.mesh, MeshData::Surface(s.clone()), "{ext}");
        assert_eq!(l.seeds, PlcSeeds::default());
    }
    let p = dir.path().join("p.node");
    write(&p, &MeshData::Points(s.vertices.clone()), &WriteOptions::default()).unwrap();
    assert_eq!(crate::io::read(&p, &ReadOptions::default()).unwrap().mesh, MeshData::Points(s.vertices.clone()));
    let e = write(&dir.path().join("p.ele"), &MeshData::Points(s.vertices), &WriteOptions::default()).unwrap_err();
    assert!(e.to_string().contains("use .node"), "{e}");
}

#[test]
fn zero_based_quadratic_and_reoriented() {
    let dir = tempfile::tempdir().unwrap();
    let mut node = "# zero-based\n5 3 1 1\n".to_string();
    for (i, p) in ["0 0 0", "1 0 0", "0 1 0", "0 0 1", "0.5 0 0"].iter().enumerate() {
        node += &format!("{i} {p} 9.5 2\n");
    }
    put(dir.path(), "q.node", &node);
    // Negatively oriented, ten nodes (the extra node numbers only need to exist).
    let p = put(dir.path(), "q.ele", "1 10 1\n0  0 2 1 3  4 4 4 4 4 4  -0\n");
    let l = crate::io::read(&p, &ReadOptions::default()).unwrap();
    let MeshData::Volume(m) = &l.mesh else { panic!() };
    assert_eq!(m.tets, vec![[0, 2, 3, 1]]);
    assert_eq!(m.region_tags, vec![RegionId(0)]);
    assert!(m.boundary.is_empty());
    assert_eq!(l.notes.len(), 3, "{:?}", l.notes);
}

#[test]
fn poly_polygons_seeds_and_separate_nodes() {
    let dir = tempfile::tempdir().unwrap();
    // An L-shaped facet (non-convex hexagon), a square facet, a segment (skipped).
    put(dir.path(), "l.node", "8 3 0 0\n1 0 0 0\n2 2 0 0\n3 2 1 0\n4 1 1 0\n5 1 2 0\n6 0 2 0\n7 0 0 1\n8 2 0 1\n");
    let text = "0 3 0 0\n3 1\n1 0 4\n6 1 2 3 4 5 6\n2 0 5 # a comment\n4 1 2 7 7\n2 1 7\n1 0\n2 1 7\n\
                1\n1 0.5 0.5 0.5\n2\n1 0.1 0.1 0.1 3 0.01\n2 0.2 0.2 0.2 4 -1\n";
    let e = read(&put(dir.path(), "l.poly", text)).unwrap_err().to_string();
    assert!(e.contains("l.poly:6: facet 2 of 3: polygon uses node 7 twice"), "{e}");
    let text = text.replace("4 1 2 7 7", "4 1 2 8 7");
    let l = read(&put(dir.path(), "l.poly", &text)).unwrap();
    let MeshData::Surface(s) = &l.mesh else { panic!() };
    assert_eq!(s.triangles.len(), 4 + 2);
    assert_eq!(s.face_tags, [4, 4, 4, 4, 5, 5].map(FaceId).to_vec());
    let area: f64 = (0..s.triangles.len())
        .take(4)
        .map(|t| {
            let [a, b, c] = s.corners(t);
            let n = (b - a).cross(c - a);
            assert!(n.z > 0.0, "orientation kept");
            n.length() / 2.0
        })
        .sum();
    assert!((area - 3.0).abs() < 1e-12);
    assert_eq!(l.seeds.holes, vec![DVec3::splat(0.5)]);
    assert_eq!(l.seeds.regions, vec![(DVec3::splat(0.1), RegionId(3), Some(0.01)), (DVec3::splat(0.2), RegionId(4), None)]);
    assert_eq!(l.notes.len(), 2, "{:?}", l.notes);
}

#[test]
fn triangulation_rejects_bad_polygons() {
    let p = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y, DVec3::new(2.0, 0.0, 0.0)];
    assert_eq!(triangulate(&p, &[0, 1, 2, 3]).unwrap().len(), 2);
    assert_eq!(triangulate(&p, &[0, 4, 2, 3]).unwrap().len(), 2);
    // Bow tie.
    assert!(triangulate(&p, &[0, 4, 3, 2]).unwrap_err().contains("not simple"));
    assert!(triangulate(&p, &[0, 2, 1, 3]).unwrap_err().contains("zero area"));
    assert!(triangulate(&p, &[0, 1, 4]).is_ok(), "triangles pass as they are (validate() judges them)");
    assert!(triangulate(&p, &[0, 1, 4, 1]).unwrap_err().contains("twice"));
    assert!(triangulate(&p, &[0, 1, 4, 0]).unwrap_err().contains("twice"));
    // Collinear vertex on an edge.
    let q = [DVec3::ZERO, DVec3::new(0.5, 0.0, 0.0), DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
    assert_eq!(triangulate(&q, &[0, 1, 2, 3, 4]).unwrap().len(), 3);
}

#[test]
fn malformed_inputs_name_file_and_line() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    put(d, "a.node", "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n");
    let check = |name: &str, text: &str, want: &str| {
        let e = read(&put(d, name, text)).unwrap_err().to_string();
        let want = format!("{}{want}", d.display());
        assert!(e.starts_with(&want), "{e}\nwanted: {want}");
    };
    check("a.ele", "1 4 0\n1 1 2 3 5\n", "/a.ele:2: node 5 does not exist: ");
    check("a.ele", "2 4 0\n1 1 2 3 4\n", "/a.ele:3: unexpected end of file: expected tetrahedron 2 of 2");
    check("a.ele", "1 4 1\n1 1 2 3 4\n", "/a.ele:2: expected 6 numbers");
    check("a.ele", "1 4 1\n1 1 2 3 4 -2\n", "/a.ele:2: the region attribute: '-2' is not a tag");
    check("a.ele", "1 5 0\n", "/a.ele:1: 5 nodes per tetrahedron");
    check("a.face", "1 1\n1 1 2 0 1\n", "/a.face:2: node 0 does not exist");
    check("b.node", "2 3 0 0\n1 0 0 0\n2 0 nan 0\n", "/b.node:3: a node coordinate is not a finite number");
    check("c.node", "2 3 0 0\n1 0 0 0\n3 0 0 0\n", "/c.node:3: node numbered 3 where 2 was expected");
    check("d.node", "1 2 0 0\n1 0 0\n", "/d.node:1: unsupported: dimension 2");
    check("e.node", "1 3 0 0\n5 0 0 0\n", "/e.node:2: the first node is numbered 5");
    check("f.poly", "3 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n1 1\n1 1 1\n3 1 2 3\n", "/f.poly:6: unsupported: facet 1 of 1 has 1 holes");
    check("g.smesh", "3 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n1 1\n3 1 2 3 1\n1\n1 0 0\n", "/g.smesh:8: expected a hole coordinate");
    let e = read(&d.join("missing.ele")).unwrap_err();
    assert!(matches!(e, IoError::Read { .. }), "{e}");
}

#[test]
fn mangled_input_never_panics() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write(&d.join("w.poly"), &MeshData::Surface(surface()), &WriteOptions::default()).unwrap();
    write(&d.join("w.smesh"), &MeshData::Surface(surface()), &WriteOptions::default()).unwrap();
    write(&d.join("w.ele"), &MeshData::Volume(two_tets()), &WriteOptions::default()).unwrap();
    let mut poly = std::fs::read(d.join("w.poly")).unwrap();
    poly.extend(b"1\n1 0.5 0.5 0.5\n1\n1 0.1 0.1 0.1 3 0.01\n");
    let smesh = std::fs::read(d.join("w.smesh")).unwrap();
    let node = std::fs::read(d.join("w.node")).unwrap();
    let nodes = {
        let mut l = Lines::new(Path::new("w.node"), &node);
        let h = l.next("h").unwrap();
        read_nodes(&mut l, &h).unwrap()
    };
    let ele = std::fs::read(d.join("w.ele")).unwrap();
    let face = std::fs::read(d.join("w.face")).unwrap();
    let check = |f: &dyn Fn(&[u8]), file: &[u8]| {
        for cut in 0..file.len() {
            f(&file[..cut]);
        }
        for i in 0..file.len() {
            for b in [0u8, 0xff, b'9', b'-', b'\n', b'#', b' '] {
                let mut m = file.to_vec();
                m[i] = b;
                f(&m);
            }
        }
    };
    check(&|b| drop(poly::read(Path::new("m.poly"), b, false)), &poly);
    check(&|b| drop(poly::read(Path::new("m.smesh"), b, true)), &smesh);
    check(&|b| drop(read_ele(Path::new("m.ele"), b, &nodes)), &ele);
    check(&|b| drop(read_faces(Path::new("m.face"), b, &nodes)), &face);
    check(
        &|b| {
            let mut l = Lines::new(Path::new("m.node"), b);
            if let Ok(h) = l.next("h") {
                let _ = read_nodes(&mut l, &h);
            }
        },
        &node,
    );
}
