use super::*;
use crate::core::{FaceId, RegionId};
use crate::io::{IoError, Location, MeshData, ReadOptions};
use glam::DVec3;

/// The shared two-tet mesh with tags 1..=3 (no tag 0) and names.
fn two_tets() -> TetMesh {
    let mut m = crate::io::test_meshes::two_tets();
    m.face_tags.iter_mut().for_each(|t| t.0 += 1);
    m.face_names.insert(FaceId(2), "inlet \"main\"");
    m.region_names.insert(RegionId(2), "steel");
    m
}

#[test]
fn volume_round_trip_keeps_order_tags_and_names() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("v.msh");
    let m = two_tets();
    write_volume(&p, &m).unwrap();
    let l = crate::io::read(&p, &ReadOptions::default()).unwrap();
    let mut want = m.clone();
    want.face_names.insert(FaceId(2), "inlet 'main'");
    assert_eq!(l.mesh, MeshData::Volume(want));
    assert!(l.notes.is_empty(), "{:?}", l.notes);
}

#[test]
fn tag_zero_becomes_the_next_free_group() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("z.msh");
    let mut m = two_tets();
    m.face_tags[0] = FaceId(0);
    m.region_tags[0] = RegionId(0);
    write_volume(&p, &m).unwrap();
    let MeshData::Volume(r) = crate::io::read(&p, &ReadOptions::default()).unwrap().mesh else { panic!() };
    assert_eq!(r.face_tags[0], FaceId(4));
    assert_eq!(r.face_names.get(FaceId(4)), Some("tag_0"));
    assert_eq!(r.region_tags, vec![RegionId(3), RegionId(2)]);
    assert_eq!(r.region_names.get(RegionId(3)), Some("tag_0"));
    m.region_tags[0] = RegionId(u32::MAX);
    let e = write_volume(&p, &m).unwrap_err();
    assert!(e.to_string().contains("cannot write tag 4294967295 (Gmsh tags are at most 2147483647) as MSH 4.1"), "{e}");
    m.region_tags[0] = RegionId(1);
    m.tets[0][0] = 9;
    let e = write_volume(&p, &m).unwrap_err();
    assert!(e.to_string().contains("vertex 9 of a mesh with 5"), "{e}");
}

#[test]
fn surface_round_trip() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("s.msh");
    let m = two_tets();
    let mut s = TriSurface { vertices: m.vertices, triangles: m.boundary, face_tags: m.face_tags, ..Default::default() };
    s.face_names.insert(FaceId(3), "wall");
    write_surface(&p, &s).unwrap();
    let l = crate::io::read(&p, &ReadOptions::default().with_weld(None)).unwrap();
    assert_eq!(l.mesh, MeshData::Surface(s));
}

#[test]
fn repeated_names_are_written_unique_per_dimension() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("u.msh");
    let mut m = two_tets();
    m.face_names = [(FaceId(1), "hole"), (FaceId(2), "hole"), (FaceId(3), "hole.2")].into_iter().collect();
    m.region_names = [(RegionId(1), "hole"), (RegionId(2), "hole")].into_iter().collect();
    write_volume(&p, &m).unwrap();
    let MeshData::Volume(r) = crate::io::read(&p, &ReadOptions::default()).unwrap().mesh else { panic!() };
    let faces: Vec<(u32, &str)> = r.face_names.iter().map(|(t, n)| (t.0, n)).collect();
    assert_eq!(faces, [(1, "hole"), (2, "hole.3"), (3, "hole.2")]);
    let regions: Vec<(u32, &str)> = r.region_names.iter().map(|(t, n)| (t.0, n)).collect();
    assert_eq!(regions, [(1, "hole"), (2, "hole.2")]);
}

/// A binary 4.1 file: one tet of volume entity 7 (physical 3, named) and a triangle of surface
/// entity 5 without physical group; nodes numbered 10, 20, 30, 40 (not dense).
fn binary_file(big_endian: bool) -> Vec<u8> {
    let mut b: Vec<u8> = b"$MeshFormat\n4.1 1 8\n".to_vec();
    let int = |b: &mut Vec<u8>, v: i32| b.extend(if big_endian { v.to_be_bytes() } else { v.to_le_bytes() });
    let size = |b: &mut Vec<u8>, v: u64| b.extend(if big_endian { v.to_be_bytes() } else { v.to_le_bytes() });
    let real = |b: &mut Vec<u8>, v: f64| b.extend(if big_endian { v.to_be_bytes() } else { v.to_le_bytes() });
    int(&mut b, 1);
    b.extend(b"\n$EndMeshFormat\n$PhysicalNames\n1\n3 3 \"the body\"\n$EndPhysicalNames\n$Entities\n");
    for n in [0, 0, 1, 1] {
        size(&mut b, n);
    }
    int(&mut b, 5);
    (0..6).for_each(|_| real(&mut b, 0.0));
    size(&mut b, 0);
    size(&mut b, 0);
    int(&mut b, 7);
    (0..6).for_each(|_| real(&mut b, 0.0));
    size(&mut b, 1);
    int(&mut b, 3);
    size(&mut b, 1);
    int(&mut b, 5);
    b.extend(b"\n$EndEntities\n$Nodes\n");
    for n in [1, 4, 10, 40] {
        size(&mut b, n);
    }
    int(&mut b, 3);
    int(&mut b, 7);
    int(&mut b, 1); // parametric: 3 more numbers per node
    size(&mut b, 4);
    for t in [10, 20, 30, 40] {
        size(&mut b, t);
    }
    for p in [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] {
        p.iter().chain(&[9.0, 9.0, 9.0]).for_each(|&x| real(&mut b, x));
    }
    b.extend(b"\n$EndNodes\n$Elements\n");
    for n in [2, 2, 1, 2] {
        size(&mut b, n);
    }
    for (dim, ent, ty, nodes) in [(2, 5, 2, vec![10u64, 30, 20]), (3, 7, 4, vec![10, 20, 30, 40])] {
        int(&mut b, dim);
        int(&mut b, ent);
        int(&mut b, ty);
        size(&mut b, 1);
        size(&mut b, dim as u64 - 1);
        nodes.iter().for_each(|&n| size(&mut b, n));
    }
    b.extend(b"\n$EndElements\n");
    b
}

#[test]
fn reads_binary_in_both_byte_orders() {
    for be in [false, true] {
        let l = read(Path::new("b.msh"), &binary_file(be)).unwrap();
        let MeshData::Volume(m) = &l.mesh else { panic!() };
        assert_eq!(m.vertices, vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z]);
        assert_eq!(m.tets, vec![[0, 1, 2, 3]]);
        assert_eq!(m.region_tags, vec![RegionId(3)]);
        assert_eq!(m.region_names.get(RegionId(3)), Some("the body"));
        assert_eq!(m.face_tags, vec![FaceId(5)]);
        assert_eq!(m.boundary, vec![[0, 2, 1]]);
        assert!(m.validate().is_ok());
    }
    let full = binary_file(false);
    for cut in [30, 200, full.len() - 30] {
        let e = read(Path::new("b.msh"), &full[..cut]).unwrap_err();
        assert!(matches!(e, IoError::Parse { .. }), "{cut}: {e}");
    }
    let e = read(Path::new("b.msh"), &full[..full.len() - 40]).unwrap_err();
    assert!(matches!(&e, IoError::Parse { at: Location::Byte(_), message, .. } if message.contains("$Elements is truncated")), "{e}");
}

const ASCII: &str = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n2 1 \"outer wall\"\n3 2 \"core\"\n$EndPhysicalNames\n\
$Entities\n1 0 1 1\n1 0 0 0 0\n4 0 0 0 1 1 1 1 1 0\n9 0 0 0 1 1 1 1 2 1 4\n$EndEntities\n\
$Comments\nanything $Nodes here\n$EndComments\n\
$Nodes\n2 11 1 20\n0 1 0 1\n20\n0 0 0\n3 9 1 10\n1\n2\n3\n4\n5\n6\n7\n8\n9\n10\n\
1 0 0 0.1 0.2 0.3\n0 1 0 0 0 0\n0 0 1 0 0 0\n0.5 0 0 0 0 0\n0.5 0.5 0 0 0 0\n0 0.5 0 0 0 0\n0 0 0.5 0 0 0\n0.5 0 0.5 0 0 0\n0 0.5 0.5 0 0 0\n0 0 0 0 0 0\n\
$EndNodes\n$Elements\n3 3 1 3\n0 1 15 1\n1 20\n2 4 9 1\n2 2 1 3 5 4 6\n3 9 11 1\n3 10 1 2 3 4 5 6 7 8 9\n$EndElements\n";

#[test]
fn reads_ascii_with_quadratic_elements_and_skipped_parts() {
    let l = read(Path::new("a.msh"), ASCII.as_bytes()).unwrap();
    let MeshData::Volume(m) = &l.mesh else { panic!("{:?}", l.mesh) };
    // Node tags 1..10 and 20 are not dense: file order (tag 20 first).
    assert_eq!(m.vertices.len(), 11);
    assert_eq!(m.vertices[1], DVec3::X);
    assert_eq!(m.tets, vec![[10, 1, 2, 3]]);
    assert_eq!(m.region_tags, vec![RegionId(2)]);
    assert_eq!(m.face_tags, vec![FaceId(1)]);
    assert_eq!(m.face_names.get(FaceId(1)), Some("outer wall"));
    assert_eq!(m.region_names.get(RegionId(2)), Some("core"));
    assert!(m.validate().is_ok());
    let notes = l.notes.join("; ");
    assert!(notes.contains("skipped section $Comments"), "{notes}");
    assert!(notes.contains("1 point (type 15)"), "{notes}");
    assert!(notes.contains("of type 11") && notes.contains("of type 9"), "{notes}");
}

#[test]
fn reads_msh22() {
    let text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n\
                $Elements\n3\n1 15 2 0 1 1\n2 2 2 0 6 1 3 2\n3 4 2 8 1 1 2 3 4\n$EndElements\n";
    let l = read(Path::new("o.msh"), text.as_bytes()).unwrap();
    let MeshData::Volume(m) = &l.mesh else { panic!() };
    assert_eq!(m.face_tags, vec![FaceId(6)], "elementary tag when the physical is 0");
    assert_eq!(m.region_tags, vec![RegionId(8)]);
    assert_eq!(l.notes.len(), 1, "{:?}", l.notes);
}

#[test]
fn malformed_inputs_name_the_place() {
    let cases: Vec<(String, &str)> = vec![
        ("$MeshFormat\n4 0 8\n$EndMeshFormat\n".into(), "x.msh:2: unsupported: MSH 4.0; re-export as MSH 4.1"),
        ("$MeshFormat\n2.2 1 8\n".into(), "x.msh:2: unsupported: binary MSH 2.2"),
        ("solid x\n".into(), "x.msh:1: not a Gmsh MSH file: expected $MeshFormat, found 'solid'"),
        (ASCII.replace("0.5 0.5 0 0 0 0", "0.5 nan 0 0 0 0"), "x.msh:38: a node coordinate is not a finite number"),
        (ASCII.replace("3 10 1 2 3 4 5 6 7 8 9", "3 10 1 2 99 4 5 6 7 8 9"), "x.msh (element 3): node 99 is not defined in $Nodes"),
        (ASCII.replace("3 10 1 2 3 4 5 6 7 8 9", "3 10 1 2 3 4 5 6 7 8"), "x.msh:52: element 3 of type 11 should have 10 nodes, found 9"),
        (ASCII.replace("$EndElements\n", ""), "x.msh:53: unexpected end of file: expected $EndElements"),
        (ASCII.replace("$Nodes\n2 11", "$Nodes\n2 12"), "x.msh:19: $Nodes counts 12 nodes but its blocks hold 11"),
        (ASCII.replace("$EndComments", "$EndComment"), "x.msh:15: section $Comments has no $EndComments"),
        (ASCII.replace("\n2\n3\n4\n", "\n2\n2\n4\n"), "x.msh (node 2): the node tag appears twice"),
    ];
    for (text, want) in cases {
        let e = read(Path::new("x.msh"), text.as_bytes()).unwrap_err().to_string();
        assert!(e.starts_with(want), "{e}\nwanted: {want}");
    }
}

#[test]
fn mangled_input_never_panics() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("w.msh");
    write_volume(&p, &two_tets()).unwrap();
    let written = std::fs::read(&p).unwrap();
    for file in [binary_file(false), binary_file(true), ASCII.as_bytes().to_vec(), written] {
        for cut in 0..file.len() {
            let _ = read(Path::new("m.msh"), &file[..cut]);
        }
        for i in 0..file.len() {
            for b in [0u8, 0xff, b'9', b'-', b'\n', b'$'] {
                let mut f = file.clone();
                f[i] = b;
                let _ = read(Path::new("m.msh"), &f);
            }
        }
    }
}

#[test]
fn points_only_and_empty_meshes() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("p.msh");
    let s = TriSurface { vertices: vec![DVec3::ZERO, DVec3::X], ..Default::default() };
    write_surface(&p, &s).unwrap();
    let l = crate::io::read(&p, &ReadOptions::default()).unwrap();
    assert_eq!(l.mesh, MeshData::Points(s.vertices));
    write_surface(&p, &TriSurface::default()).unwrap();
    let text = std::fs::read_to_string(&p).unwrap();
    assert!(!text.contains("$Nodes") && !text.contains("$Elements"), "{text}");
    let e = crate::io::read(&p, &ReadOptions::default()).unwrap_err();
    assert!(e.to_string().ends_with("the file has no nodes"), "{e}");
}

#[test]
fn mixed_surface_lists_each_entity_once_with_a_block_per_type() {
    use crate::mesh::{MixedSurface, PlanarMesh};
    use glam::DVec2;
    let m = PlanarMesh {
        vertices: vec![DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y, DVec2::new(2.0, 0.5), DVec2::new(2.0, 2.0)],
        triangles: vec![[1, 4, 2], [2, 4, 5]],
        triangle_tags: vec![RegionId(1), RegionId(2)],
        quads: vec![[0, 1, 2, 3]],
        quad_tags: vec![RegionId(1)],
        region_names: [(RegionId(1), "plate")].into_iter().collect(),
    };
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("m.msh");
    write_mixed(&p, &MixedSurface::from_planar(&m)).unwrap();
    let t = std::fs::read_to_string(&p).unwrap();
    assert!(t.contains("$PhysicalNames\n1\n2 1 \"plate\"\n$EndPhysicalNames"), "{t}");
    assert!(t.contains("$Entities\n0 0 2 0\n1 0 0 0 2 1 0 1 1 0\n2 1 0.5 0 2 2 0 1 2 0\n$EndEntities"), "{t}");
    // entity 1 holds its triangle (type 2) and its quad (type 3); element tags: triangles first
    assert!(t.contains("$Elements\n3 3 1 3\n2 1 2 1\n1 2 5 3\n2 2 2 1\n2 3 5 6\n2 1 3 1\n3 1 2 3 4\n$EndElements"), "{t}");
    // every node in exactly one block
    assert!(t.contains("$Nodes\n2 6 1 6\n2 1 0 5\n"), "{t}");
}
