//! Tessellates every STEP file of the corpus at the default options and prints, per file,
//! time, triangles, closed/manifold/oriented and the volume against OpenCASCADE's.
//!
//! `cargo run --release --example tessellate_corpus [-- CHORD_RELATIVE]`
//! (corpus: `$FEPRE_CORPUS`, else `../shared/cad_corpus`).

use fepre::mesh::topology::{ReportOptions, surface_report};
use fepre::pipeline::tessellate_file;
use fepre::tessellate::TessellateOptions;
use fepre::tessellate::certificate::CertifyOptions;
use std::path::PathBuf;

/// file, OpenCASCADE volume mm^3 and area mm^2 (cadquery-ocp 8.0.1, `shared/tools/occ/ocpref.py`).
const FILES: &[(&str, f64, f64)] = &[
    ("occt-cube.step", 1.000000e+03, 6.000000e+02),
    ("occt-cylinder.step", 1.256637e+02, 1.507964e+02),
    ("occt-sphere.step", 5.235988e+02, 3.141593e+02),
    ("red_cube_blue_cylinder.step", 1.785398e+03, 1.071239e+03),
    ("base_interface_AP214.STEP", 1.257992e+06, 5.419172e+05),
    ("part.step", 3.609398e+05, 4.961156e+04),
    ("screw.step", 3.788271e+03, 1.929333e+03),
    ("Angled.step", 4.878051e+05, 8.373811e+04),
    ("featuretype.STEP", 1.905320e+05, 3.473360e+04),
    ("t20_data.step", 1.838846e+04, 6.368804e+03),
    ("cube_filet.stp", 2.805961e+05, 1.382301e+04),
    ("Kurbelwelle.stp", 2.133530e+03, 2.347679e+03),
    ("abc-0035.step", 4.686298e+09, 4.291559e+07),
    ("mambo_s34.step", 1.307907e+05, 2.463132e+04),
    ("linkrods.step", 3.847002e+00, 3.215142e+01),
    ("as1-tu-203.stp", 7.645190e+05, 1.410791e+05),
    ("box_sides.STEP", 2.635420e+05, 1.895291e+05),
    ("wing_fuselage.step", 1.591244e+06, 2.687364e+05),
    ("abc-0000.step", 3.166280e+06, 4.048646e+05),
    ("Zylkopf.stp", 3.280664e+03, 3.248964e+03),
    ("sewfaces.step", 9.163566e+02, 5.785398e+02),
    ("bug32745_pmi1.stp", 9.012892e+02, 8.702050e+02),
];

fn main() {
    let dir = std::env::var_os("FEPRE_CORPUS").map_or_else(|| PathBuf::from("../shared/cad_corpus"), PathBuf::from);
    let mut opts = TessellateOptions::default();
    if let Some(c) = std::env::args().nth(1).and_then(|a| a.parse().ok()) {
        opts = opts.with_chord_relative(c);
    }
    println!("{:<28} {:>7} {:>8} {:>8} {:>6} {:>14} {:>9} {:>8} {:>7}", "file", "read s", "tess s", "tris", "closed", "volume", "err %", "area %", "failed");
    for &(name, occ, occ_area) in FILES {
        let (_model, c, seconds) = match tessellate_file(&dir.join(name), &opts, None, &CertifyOptions::default()) {
            Ok(x) => x,
            Err(e) => {
                println!("{name}: {e}");
                continue;
            }
        };
        let (t, cert, cert_s) = (&c.tessellation, &c.certificate, seconds.certify);
        let r = surface_report(&t.surface, &ReportOptions::default().with_self_intersections(false));
        println!(
            "{:<28} {:>7.3} {:>8.3} {:>8} {:>6} {:>14.6} {:>9.4} {:>8.4} {:>7}",
            name,
            seconds.read,
            seconds.tessellate,
            t.surface.triangles.len(),
            r.closed && r.manifold && r.oriented,
            r.volume,
            100.0 * (r.volume - occ) / occ,
            100.0 * (r.area - occ_area) / occ_area,
            t.failed.len()
        );
        println!(
            "    certificate {} ({:.3} s): volume B-rep {:.6} ({:+.4} % vs OCC) area B-rep {:.6} ({:+.4} %), self-x {:?}, contacts {}, euler {:?}",
            cert.passed,
            cert_s,
            cert.volume[1],
            100.0 * (cert.volume[1] - occ) / occ,
            cert.area[1],
            100.0 * (cert.area[1] - occ_area) / occ_area,
            cert.self_intersections,
            cert.solid_contacts,
            cert.shells.iter().map(|x| (x.euler_mesh, x.euler_brep)).collect::<Vec<_>>()
        );
        for f in cert.failures.iter().take(6) {
            println!("      {} {:?} {:?}: {}", f.check, f.face, f.step_id, f.message);
        }
    }
}
