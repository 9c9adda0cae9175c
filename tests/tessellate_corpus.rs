//! The tessellator on the shared corpus: for the 20 closed-solid files, at the DEFAULT
//! options, the surface is closed, manifold and consistently oriented with every shell
//! enclosing positive volume (checked by `mesh::topology`), every triangle is tagged with a
//! B-rep face, the solid count is OpenCASCADE's, the enclosed volume is within 0.5 % of
//! OpenCASCADE's, the certificate (`tessellate::certificate`, self-intersections included)
//! passes, and each file takes under 10 s (release build; the budget is for the whole
//! read + tessellate + certify).

mod common;

use fepre::cad::step;
use fepre::mesh::topology::{ReportOptions, surface_report};
use fepre::tessellate::certificate::{CertifyOptions, certify};
use fepre::tessellate::{TessellateOptions, tessellate};

/// file, OCC volume in mm^3, OCC solids (corpus README, cadquery-ocp 8.0.1).
const WATERTIGHT: &[(&str, f64, usize)] = &[
    ("occt-cube.step", 1000.0, 1),
    ("occt-cylinder.step", 125.664, 1),
    ("red_cube_blue_cylinder.step", 1785.4, 2),
    ("base_interface_AP214.STEP", 1.25799e6, 1),
    ("Angled.step", 487805.0, 1),
    ("featuretype.STEP", 190532.0, 1),
    ("Kurbelwelle.stp", 2133.53, 1),
    ("Zylkopf.stp", 3280.66, 1),
    ("wing_fuselage.step", 1.59124e6, 2),
    ("part.step", 360940.0, 1),
    ("t20_data.step", 18388.5, 1),
    ("abc-0035.step", 4.6863e9, 1),
    ("mambo_s34.step", 130791.0, 1),
    ("linkrods.step", 3.847, 1),
    ("box_sides.STEP", 263542.0, 10),
    ("abc-0000.step", 3.16628e6, 6),
    ("bug32745_pmi1.stp", 901.289, 1),
    ("as1-tu-203.stp", 764519.0, 18),
    ("screw.step", 3788.27, 1),
    ("occt-sphere.step", 523.599, 1),
];

#[test]
fn self_intersecting_tori_and_far_nappe_cone_at_default_chord() {
    // screw.step: toroidal surfaces with r > R (inner "lemon" parts) and a cone face past its
    // apex, at the default (coarse) chord as well.
    let Some(path) = common::corpus_file("screw.step") else { return };
    let model = step::read(&path).unwrap();
    let t = tessellate(&model, &TessellateOptions::default());
    let r = surface_report(&t.surface, &ReportOptions::default().with_self_intersections(false));
    let volume: f64 = r.shells.iter().map(|sh| sh.volume).sum();
    assert!(t.failed.is_empty() && r.closed && r.manifold && r.oriented, "{:?} closed {}", t.failed, r.closed);
    assert!(((volume - 3788.27) / 3788.27).abs() < 0.005, "volume {volume}");
}

#[test]
fn watertight_certified_and_volume_close_to_opencascade_at_default_deviation() {
    let Some(dir) = common::corpus_dir() else { return };
    let mut failures = Vec::new();
    for &(name, occ_volume, occ_solids) in WATERTIGHT {
        let t0 = std::time::Instant::now();
        let model = step::read(&dir.join(name)).unwrap();
        let t = tessellate(&model, &TessellateOptions::default());
        let s = &t.surface;
        s.validate().unwrap();
        let cert = certify(&model, &t, &CertifyOptions::default());
        let seconds = t0.elapsed().as_secs_f64();
        let r = surface_report(s, &ReportOptions::default().with_self_intersections(false));
        let volume: f64 = r.shells.iter().map(|sh| sh.volume).sum();
        let tags: std::collections::BTreeSet<_> = s.face_tags.iter().copied().collect();
        eprintln!("{name}: {} triangles, closed {}, volume {volume:.6} (OCC {occ_volume}), certificate {} ({seconds:.3} s)", s.triangles.len(), r.closed, cert.passed);
        if !t.failed.is_empty() {
            failures.push(format!("{name}: failed faces {:?}", t.failed));
        }
        // every shell encloses positive volume: oriented outward (the report's own `outward`
        // also judges nesting, which solids placed through each other's holes confuse)
        let positive = r.shells.iter().all(|sh| sh.volume > 0.0);
        if !(r.closed && r.manifold && r.oriented && positive) {
            failures.push(format!("{name}: closed {} manifold {} oriented {} all shells positive {positive}", r.closed, r.manifold, r.oriented));
        }
        if tags.len() != model.faces.len() {
            failures.push(format!("{name}: {} tags for {} faces", tags.len(), model.faces.len()));
        }
        if model.solids.len() != occ_solids {
            failures.push(format!("{name}: {} solids, OpenCASCADE {occ_solids}", model.solids.len()));
        }
        if ((volume - occ_volume) / occ_volume).abs() > 0.005 {
            failures.push(format!("{name}: volume {volume} vs OpenCASCADE {occ_volume}"));
        }
        if !(cert.passed && cert.self_intersections == Some(0)) {
            failures.push(format!("{name}: certificate fails: {:?}", cert.failures));
        }
        if seconds > 10.0 {
            failures.push(format!("{name}: {seconds:.1} s"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The centroid of the tessellated solids (divergence theorem over the triangles).
fn centroid(s: &fepre::mesh::TriSurface) -> (f64, glam::DVec3) {
    let (mut v, mut c) = (0.0, glam::DVec3::ZERO);
    for t in &s.triangles {
        let [a, b, d] = t.map(|i| s.vertices[i as usize]);
        let vol = a.dot(b.cross(d)) / 6.0;
        v += vol;
        c += vol * (a + b + d) / 4.0;
    }
    (v, c / v)
}

#[test]
fn assembly_placements_match_the_files_validation_centroid() {
    // as1-tu-203.stp carries validation properties: the assembly's centroid is
    // (90, 75, 18.859468) mm (#2146). Wrong placements of its 18 instances would move it.
    let Some(path) = common::corpus_file("as1-tu-203.stp") else { return };
    let model = step::read(&path).unwrap();
    let t = tessellate(&model, &TessellateOptions::default().with_chord_relative(2e-4));
    let (v, c) = centroid(&t.surface);
    let expected = glam::DVec3::new(90.0, 74.999999986, 18.859468252);
    assert!((v - 764518.031066584).abs() / v < 0.005, "volume {v}");
    assert!((c - expected).length() < 0.05, "centroid {c} vs {expected}");
}
