//! A CAD part's boundary vertices slide on its curved faces and along its curved edges during
//! optimisation, put back onto the B-rep after each move: never off it.
//!
//! Run in release: `cargo test --release --test mesh_slide_cad -- --include-ignored`.

use fepre::attributes::Density;
use fepre::core::{BoundaryGeometry, FaceId};
use fepre::fe::BrepGeometry;
use fepre::mesh3d::mesher::MeshOptions;
use fepre::pipeline::Part;
use fepre::pipeline::Plan;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

#[test]
#[ignore = "release, one fixture part meshed (about 0.6 s); CI runs it (--include-ignored)"]
fn boundary_vertices_slide_on_curved_cad_faces_and_stay_on_them() {
    // a pipe bend: a torus between two cylinders, flanges
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("cad_fixtures/elbow.step");
    let mut part = Part::open(&path).unwrap();
    let plan = Plan { unit: 1.0, ..Plan::default() };
    let field = part.density_field(&Density::default(), &BTreeMap::new(), 1.0).unwrap();
    let tess = plan.tessellate_options(&part);
    let mesh = part.mesh(&field, &tess, &MeshOptions::default()).unwrap().clone();
    assert_eq!(mesh.validate(), Ok(()));
    let report = part.mesh_report.as_ref().and_then(|r| r.optimize.clone()).expect("the optimiser's report");
    println!("{report:?}");
    assert!(report.curved_boundary_moves > 0, "no vertex slid on a curved face: {report:?}");
    assert!(report.curved_boundary_moves <= report.boundary_moves);
    // every boundary vertex of one face lies on it: the tessellation's on the surface, the
    // recovery's Steiner points on its chords (within the chord deviation), the slid ones back
    // on the surface
    let model = part.model.as_ref().unwrap();
    let geo = BrepGeometry::new(model);
    let deviation = part.mesh_deviation() * part.diagonal();
    let mut faces_of: BTreeMap<u32, BTreeSet<FaceId>> = BTreeMap::new();
    for (t, &f) in mesh.boundary.iter().zip(&mesh.face_tags) {
        for &v in t {
            faces_of.entry(v).or_default().insert(f);
        }
    }
    let (mut on, mut near) = (0, 0);
    for (&v, faces) in &faces_of {
        let [f] = faces.iter().copied().collect::<Vec<_>>()[..] else { continue };
        let p = mesh.vertices[v as usize];
        let q = geo.on_face(f, p, p, p).unwrap();
        let d = p.distance(q);
        assert!(d <= 1.01 * deviation, "vertex {v} at {p} is {d} off face {f:?} (chord deviation {deviation})");
        if d <= 1e-9 * part.diagonal() { on += 1 } else { near += 1 }
    }
    println!("{on} boundary vertices on their face, {near} on its chords");
    assert!(on > near);
    // the volume as the CAD part's, within what the chords take
    let cad = part.catalogue().volume();
    assert!((mesh.volume() - cad).abs() <= 5e-3 * cad, "{} against {cad}", mesh.volume());
}
