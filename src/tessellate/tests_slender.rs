//! Slender parts keep their volume at the default deviation, and a certificate fails a
//! tessellation that does not (issue 14, part 6).

use super::certificate::{CertifyOptions, VOLUME_RELATIVE, certify};
use super::{TessellateOptions, tessellate};
use crate::cad::brep::Model;
use std::f64::consts::PI;
use truck_modeling::{Point3, Vector3, builder};

/// A solid round rod of `radius` and `length` along z, mm, built in code.
fn rod(radius: f64, length: f64) -> Model {
    let (c, x, y) = (Point3::new(0.0, 0.0, 0.0), Vector3::unit_x(), Vector3::unit_y());
    let a = builder::vertex(c + radius * x);
    let b = builder::vertex(c - radius * x);
    let wire: truck_modeling::Wire = vec![builder::circle_arc(&a, &b, c + radius * y), builder::circle_arc(&b, &a, c - radius * y)].into();
    let face = builder::try_attach_plane(&[wire]).unwrap();
    let solid = builder::tsweep(&face, Vector3::new(0.0, 0.0, length));
    crate::cad::parts::solid_to_model(&solid, "rod").unwrap()
}

/// The triangles' enclosed volume.
fn mesh_volume(s: &crate::mesh::TriSurface) -> f64 {
    s.triangles.iter().map(|t| s.vertices[t[0] as usize].dot(s.vertices[t[1] as usize].cross(s.vertices[t[2] as usize])) / 6.0).sum()
}

#[test]
fn a_ten_metre_rod_keeps_its_volume_at_the_default_deviation() {
    // 10 m long, 0.1 m across: the model-wide chord (2e-4 of the diagonal) is 2 mm, 4 % of
    // the radius; its inscribed polygons alone would lose over 5 %
    let (r, l) = (50.0, 10_000.0);
    let m = rod(r, l);
    let exact = PI * r * r * l;
    let t = tessellate(&m, &TessellateOptions::default());
    assert!(t.failed.is_empty(), "{:?}", t.failed);
    let v = mesh_volume(&t.surface);
    assert!((v / exact - 1.0).abs() < 5e-3, "volume {v} against {exact}: {:+.3} %", 100.0 * (v / exact - 1.0));
    // the faces' chords were shrunk below the model-wide one, not the whole model's
    assert!(t.face_chords.iter().all(|&d| d < 0.25 * t.chord), "{:?} against {}", t.face_chords, t.chord);
    let c = certify(&m, &t, &CertifyOptions::default());
    assert!(c.passed, "{:?}", c.failures);
    // (truck's circles are rational B-splines: the quadrature is off the exact cylinder by 2e-5)
    assert!((c.volume[1] / exact - 1.0).abs() < 1e-4, "quadrature {} against {exact}", c.volume[1]);
    // and not at the cost of a mesh: the cylinder is a strip between its circles
    assert!(t.surface.triangles.len() < 5_000, "{} triangles", t.surface.triangles.len());
}

#[test]
fn a_coarse_deviation_that_loses_volume_fails_the_certificate() {
    let (r, l) = (50.0, 10_000.0);
    let m = rod(r, l);
    // the model-wide chord, as asked, without the volume bound: 2 mm on a radius of 50 mm
    let t = tessellate(&m, &TessellateOptions::default().with_volume_relative(0.0));
    let v = mesh_volume(&t.surface);
    let exact = PI * r * r * l;
    assert!(v < exact * (1.0 - 2.0 * VOLUME_RELATIVE), "the coarse rod keeps {v} of {exact}");
    let c = certify(&m, &t, &CertifyOptions::default());
    assert!(!c.passed && !c.volume_matches, "{:?}", c.failures);
    // the other checks still hold: only the volume is wrong
    assert!(c.watertight() && c.euler_matches && c.boundary_loops_match, "{:?}", c.failures);
    let f = c.failures.iter().find(|f| f.check == "volume").expect("a volume failure");
    // it names the solid, the face deviating most and the figures
    let solid = m.solids[0].source;
    assert!(f.message.contains(&format!("solid {solid}")), "{}", f.message);
    assert!(f.face.is_some() && f.message.contains("% off") && f.message.contains("deviate up to"), "{}", f.message);
    // a deviation reached of about the chord asked for
    assert!(c.deviation > 0.5 * t.chord && c.deviation < 1.5 * t.chord, "deviation {} against the chord {}", c.deviation, t.chord);
}

#[test]
fn the_volume_tolerance_never_exceeds_the_relative_bound() {
    // far coarser still: the band Σ A δ is 20 % of the volume, the tolerance stays 0.5 %
    let m = rod(50.0, 10_000.0);
    let t = tessellate(&m, &TessellateOptions::default().with_chord_relative(1e-3).with_volume_relative(0.0));
    let c = certify(&m, &t, &CertifyOptions::default());
    assert!(c.volume[2] <= (VOLUME_RELATIVE + 1e-9) * c.volume[1].abs(), "tolerance {} of {}", c.volume[2], c.volume[1]);
    assert!(!c.volume_matches);
}
