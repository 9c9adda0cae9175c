//! The parts in `cad_fixtures/` are what `cargo run --example make_fixtures` writes today, and
//! the bundled part is what the README says it is.

use fepre::io::{MeshData, ReadOptions, WriteOptions, read, write};
use fepre::mesh::shapes::plate_with_hole;
use fepre::mesh::topology::{ReportOptions, surface_report};
use std::path::Path;

#[test]
fn committed_fixtures_are_up_to_date() {
    let dir = tempfile::tempdir().unwrap();
    let plate = MeshData::Surface(plate_with_hole(64, 40.0, 8.0, 8.0));
    for name in ["plate_with_hole.obj", "plate_with_hole.stl"] {
        let fresh = dir.path().join(name);
        write(&fresh, &plate, &WriteOptions::default().with_ascii(true)).unwrap();
        let committed = Path::new(env!("CARGO_MANIFEST_DIR")).join("cad_fixtures").join(name);
        assert!(
            std::fs::read(&fresh).unwrap() == std::fs::read(&committed).unwrap(),
            "{name} differs from what make_fixtures writes: run `cargo run --example make_fixtures`"
        );
    }
    for (name, model) in fepre::cad::parts::default_parts().unwrap() {
        let fresh = dir.path().join(format!("{name}.step"));
        fepre::cad::step::write(&fresh, &model, name).unwrap();
        let committed = Path::new(env!("CARGO_MANIFEST_DIR")).join("cad_fixtures").join(format!("{name}.step"));
        assert!(
            std::fs::read(&fresh).unwrap() == std::fs::read(&committed).unwrap_or_default(),
            "{name}.step differs from what make_fixtures writes: run `cargo run --example make_fixtures`"
        );
    }
}

#[test]
fn the_bundled_part_is_a_closed_genus_one_plate_with_seven_faces() {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("cad_fixtures/plate_with_hole.obj");
    let MeshData::Surface(s) = read(&p, &ReadOptions::default()).unwrap().mesh else { panic!("not a surface") };
    let r = surface_report(&s, &ReportOptions::default());
    assert!(r.closed && r.manifold && r.oriented && r.outward);
    assert_eq!((r.components, r.genus, r.self_intersections), (1, Some(1), Some(0)));
    assert_eq!(s.tags().len(), 7);
    let polygon = 0.5 * 64.0 * 64.0 * (std::f64::consts::TAU / 64.0).sin(); // area of the 64-gon of radius 8
    let volume = (40.0 * 40.0 - polygon) * 8.0;
    assert!((r.volume - volume).abs() < 1e-9 * volume, "{} vs {volume}", r.volume);
}
