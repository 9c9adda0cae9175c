//! Surface models of the corpus: reported as such, sewn where their edges match, and
//! tessellated conformingly (the certificate checks that an open shell group is open exactly
//! along its free B-rep edges).
//!
//! What sewing finds in the two files (the corpus README calls sewfaces.step a body that
//! "only closes after sewing"):
//! - sewfaces.step: 2 OPEN_SHELLs; 4 pairs of free edges (circle arcs) are the same curve and
//!   are merged; 6 free line edges remain, and they form one loop: a 10 x 10 mm square at
//!   z = 0 that no face of the file covers. The body does not close by sewing.
//! - cube_filet.stp: 1 OPEN_SHELL of 17 cylindrical and 8 spherical faces; its 40 free edges
//!   have 40 different pairs of end vertices, so none can be merged: the openings are where
//!   the rounded box's planar faces would be.

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
    }
}
