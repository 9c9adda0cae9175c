//! Surface models of the corpus: reported as such, sewn where their edges match, and
//! tessellated conformingly (the certificate checks that an open shell group is open exactly
//! along its free B-rep edges).
//!
//! What sewing finds in the two files (the corpus README calls sewfaces.step a body that
//! "only closes after sewing"):
//! - sewfaces.step: 2 OPEN_SHELLs; 4 pairs of free edges (circle arcs) are the same curve and
//!   are merged; no T-junction. 6 free line edges remain, and they form one hole: a 10 x 10 mm
//!   square at z = 0 (40 mm around, two of its sides in two pieces) that no face of the file
//!   covers. The body does not close by sewing: the file lacks that face. OpenCASCADE's
//!   BRepBuilderAPI_Sewing (tolerance 1e-6 of the size) finds the same: 6 free edges, one
//!   closed free wire of 40 mm centred at (5, 5, 0).
//! - cube_filet.stp: 1 OPEN_SHELL of 17 cylindrical and 8 spherical faces; its 40 free edges
//!   have 40 different pairs of end vertices and no T-junction (the straight ones cut at 50 mm
//!   are cut on their only side), so none can be merged: the openings are where the rounded
//!   box's planar faces (and two fillets and a corner) would be: 3 holes, 28 edges
//!   (1054.2478 mm, three planar openings joined through the missing fillets), 6 and 6 edges
//!   (320 mm each). OpenCASCADE's sewing finds the same 40 free edges in 3 closed wires of
//!   28, 6 and 6 edges, 1054.247780, 320 and 320 mm, centred at (50, 44.3373, 57.8855),
//!   (50, 50, 0) and (50, 100, 50).

mod common;

use fepre::pipeline::tessellate_file;
use fepre::tessellate::TessellateOptions;
use fepre::tessellate::certificate::CertifyOptions;

#[test]
fn surface_models_are_reported_sewn_and_tessellated_conformingly() {
    for (name, shells, merged, free_after) in [("sewfaces.step", 2, 4, 6), ("cube_filet.stp", 1, 0, 40)] {
        let Some(path) = common::corpus_file(name) else { return };
        let (model, c, _) = tessellate_file(&path, &TessellateOptions::default(), None, &CertifyOptions::default()).unwrap();
        assert_eq!(model.solids.len(), 0, "{name}");
        assert_eq!(model.surface_model_shells(), shells, "{name}");
        let sew = model.sewing.clone().expect("open shells are sewn");
        eprintln!("{name}: {sew:?}");
        assert_eq!((sew.merged_edges, sew.free_edges_after), (merged, free_after), "{name}: {sew:?}");
        let cert = &c.certificate;
        assert!(cert.passed, "{name}: {:?}", cert.failures);
        // sewn into one group (sewfaces: its two shells share the merged arcs)
        assert_eq!(cert.shells.len(), 1, "{name}: {:?}", cert.shells.iter().map(|x| &x.brep_shells).collect::<Vec<_>>());
        // no T-junction in either; a surface model alone is not watertight, and says where
        assert!(sew.splits.is_empty(), "{name}: {:?}", sew.splits);
        assert!(!cert.watertight() && cert.open_solids.is_empty(), "{name}");
        assert_eq!(sew.holes.iter().map(|h| h.edges).sum::<usize>(), free_after, "{name}");
        assert!(sew.holes.iter().all(|h| h.closed_ring), "{name}: {:?}", sew.holes);
    }
}

/// The holes left, against OpenCASCADE's free wires after its sewing (module docs).
#[test]
fn the_holes_left_are_opencascades_free_wires() {
    let close = |a: [f64; 3], b: [f64; 3]| (0..3).all(|k| (a[k] - b[k]).abs() < 1e-3);
    for (name, expected) in [
        ("sewfaces.step", vec![(6, 40.0, [5.0, 5.0, 0.0])]),
        ("cube_filet.stp", vec![(28, 1054.247780, [50.0, 44.3373, 57.8855]), (6, 320.0, [50.0, 50.0, 0.0]), (6, 320.0, [50.0, 100.0, 50.0])]),
    ] {
        let Some(path) = common::corpus_file(name) else { return };
        let model = fepre::cad::step::read(&path).unwrap();
        let holes = model.sewing.expect("sewn").holes;
        assert_eq!(holes.len(), expected.len(), "{name}: {holes:?}");
        for (h, (edges, length, near)) in holes.iter().zip(expected) {
            assert_eq!(h.edges, edges, "{name}: {h:?}");
            assert!((h.length - length).abs() < 1e-4, "{name}: {h:?}");
            assert!(close(h.near, near), "{name}: {h:?}");
        }
        // sewfaces: the hole is the 10 x 10 mm square at z = 0 that no face covers
        if name == "sewfaces.step" {
            let h = &holes[0];
            assert_eq!((h.faces.len(), h.shells.len()), (6, 1), "{h:?}");
            eprintln!("{name}: {}", h.describe());
        }
    }
}
