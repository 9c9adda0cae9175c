//! A CAD part is meshed while its tessellation is certified (`Part::mesh`): the mesh is the
//! one that meshing the certified tessellation afterwards gives.

use fepre::attributes::Density;
use fepre::mesh3d::mesher::MeshOptions;
use fepre::pipeline::Part;
use fepre::pipeline::Plan;
use std::collections::BTreeMap;
use std::path::Path;

#[test]
fn meshing_beside_the_certificate_gives_the_mesh_of_the_certified_surface() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("cad_fixtures/bracket.step");
    let plan = Plan { unit: 1.0, ..Plan::default() };
    let mesh_with = |certify_first: bool| {
        let mut part = Part::open(&path).unwrap();
        let field = part.density_field(&Density::default(), &BTreeMap::new(), 1.0).unwrap();
        let tess = plan.tessellate_options(&part);
        if certify_first {
            assert!(part.tessellate(&field, &tess).unwrap().passed);
        }
        let mesh = part.mesh(&field, &tess, &MeshOptions::default()).unwrap().clone();
        let c = part.certified.as_ref().expect("the certified tessellation");
        assert!(c.certificate.passed);
        assert_eq!(part.surface.as_ref().map(|s| s.triangles.len()), Some(c.tessellation.surface.triangles.len()));
        assert!(part.seconds.certify > 0.0 && part.seconds.mesh > 0.0);
        mesh
    };
    let beside = mesh_with(false);
    let after = mesh_with(true);
    assert_eq!(beside.validate(), Ok(()));
    assert_eq!(beside.vertices, after.vertices);
    assert_eq!(beside.tets, after.tets);
    assert_eq!(beside.boundary, after.boundary);
    assert_eq!(beside.face_tags, after.face_tags);
}
