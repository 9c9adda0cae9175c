//! The examples run as tests: what a library user copies works.

#[path = "../examples/step_to_mesh.rs"]
#[allow(dead_code)]
mod step_to_mesh;

#[test]
fn step_to_mesh_writes_a_tagged_msh_through_the_library() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("bracket.msh");
    let part = step_to_mesh::step_to_mesh("cad_fixtures/bracket.step".as_ref(), &out).expect("meshes");
    let m = part.mesh.as_ref().unwrap();
    assert_eq!(m.validate(), Ok(()));
    let back = fepre::io::read(&out, &fepre::io::ReadOptions::default()).unwrap();
    let fepre::io::MeshData::Volume(v) = back.mesh else { panic!("not a tet mesh") };
    assert_eq!(v.tets.len(), m.tets.len());
    let tags: std::collections::BTreeSet<u32> = v.face_tags.iter().map(|t| t.0).collect();
    assert_eq!(tags.len(), 17, "a group per CAD face");
    assert!(v.face_names.names().any(|n| n.starts_with("hole_")), "{:?}", v.face_names);
}
