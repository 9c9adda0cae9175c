//! Mesh optimisation on TetGen's quality meshes of the generated PLCs (`shared/tools/data`):
//! the optimised mesh stays valid with the same boundary triangles, tags and volume, and its
//! quality (the judge's definitions, through `fepre::quality::tet_mesh_quality`) is reported
//! before and after. Run in release to see meaningful times:
//! `cargo test --release --test optimize_tetgen -- --nocapture --test-threads 1`. With
//! `FEPRE_OPT_OUT=DIR` the meshes before and after are written to `DIR` as Medit files for the
//! judge (`shared/tools/cgal_ref/tetquality DIR/plc.optimised.mesh`).

mod common;

use common::shared_data;
use common::tools::{require, run_ok, tetgen};
use fepre::io::{MeshData, ReadOptions, WriteOptions, read, write};
use fepre::mesh::TetMesh;
use fepre::mesh3d::optimize::{OptimizeOptions, optimize};
use fepre::quality::{TetQualityReport, tet_mesh_quality};
use std::process::Command;
use std::time::Instant;

/// Meshes `name`.poly with TetGen's `switches` in a temporary folder and reads the result.
fn tetgen_mesh(name: &str, switches: &str) -> Option<TetMesh> {
    let tetgen = require(tetgen(), "tetgen", "optimisation of TetGen meshes")?;
    let poly = shared_data(&format!("{name}.poly"))?;
    let dir = tempfile::tempdir().expect("temporary folder");
    let local = dir.path().join(format!("{name}.poly"));
    std::fs::copy(&poly, &local).expect("copy the PLC");
    run_ok(Command::new(tetgen).arg(switches).arg(&local), dir.path());
    let loaded = read(&dir.path().join(format!("{name}.1.ele")), &ReadOptions::default()).expect("read TetGen's mesh");
    match loaded.mesh {
        MeshData::Volume(m) => Some(m),
        other => panic!("expected a tet mesh, got a {}", other.kind()),
    }
}

fn line(label: &str, q: &TetQualityReport, seconds: Option<f64>) {
    println!(
        "{label:>8}: tets {:>7}  min dihedral {:>8.4}  max dihedral {:>9.4}  max radius-edge {:.4}  <10° {:>4}  <20° {:>5}  re>2 {}{}",
        q.tets,
        q.min_dihedral_deg,
        q.max_dihedral_deg,
        q.max_radius_edge,
        q.tets_min_dihedral_below_10,
        q.tets_min_dihedral_below_20,
        q.tets_radius_edge_over_2,
        seconds.map(|s| format!("  {s:.3} s")).unwrap_or_default()
    );
}

/// Acceptance figures of the volume mesher (measured as `tetquality` does).
const MIN_DIHEDRAL: f64 = 12.9;
const MAX_DIHEDRAL: f64 = 160.0;
const MAX_RADIUS_EDGE: f64 = 2.0;

/// Volume of each region tag, in tag order.
fn region_volumes(m: &TetMesh) -> Vec<(u32, f64)> {
    let mut v: std::collections::BTreeMap<u32, f64> = std::collections::BTreeMap::new();
    for (t, r) in m.tets.iter().zip(&m.region_tags) {
        let [a, b, c, d] = t.map(|i| m.vertices[i as usize]);
        *v.entry(r.0).or_default() += (b - a).dot((c - a).cross(d - a)) / 6.0;
    }
    v.into_iter().collect()
}

/// Optimises `m` and checks everything that must be kept and the acceptance figures; returns
/// the quality after.
fn optimise_and_check(name: &str, mut m: TetMesh, volume: f64) -> TetQualityReport {
    let before = tet_mesh_quality(&m);
    let original = m.clone();
    assert!((before.volume - volume).abs() <= 1e-6 * volume, "{name}: TetGen's volume {} is not {volume}", before.volume);
    let opts = OptimizeOptions::default();
    let t0 = Instant::now();
    let report = optimize(&mut m, &opts).expect("optimize");
    let seconds = t0.elapsed().as_secs_f64();
    println!("{name}: {}", serde_json::to_string(&report).unwrap_or_default());
    let after = tet_mesh_quality(&m);
    if let Some(dir) = std::env::var_os("FEPRE_OPT_OUT") {
        // for the judge: `tetquality DIR/NAME.tetgen.mesh` and `DIR/NAME.optimised.mesh`
        let dir = std::path::PathBuf::from(dir);
        for (tag, mesh) in [("tetgen", &original), ("optimised", &m)] {
            let path = dir.join(format!("{name}.{tag}.mesh"));
            write(&path, &MeshData::Volume(mesh.clone()), &WriteOptions::default()).expect("write the mesh");
        }
    }
    line("TetGen", &before, None);
    line("optimised", &after, Some(seconds));
    assert_eq!(m.validate(), Ok(()), "{name}: the optimised mesh is invalid");
    assert_eq!(m.boundary, original.boundary, "{name}: boundary triangles changed");
    assert_eq!(m.face_tags, original.face_tags, "{name}: boundary tags changed");
    assert_eq!(m.vertices.len(), original.vertices.len() + report.insertions);
    for tri in &original.boundary {
        for &v in tri {
            assert_eq!(m.vertices[v as usize], original.vertices[v as usize], "{name}: boundary vertex {v} moved");
        }
    }
    let (v0, v1) = (original.volume(), m.volume());
    assert!((v1 - v0).abs() <= 1e-9 * v0, "{name}: volume {v0} became {v1}");
    let (r0, r1) = (region_volumes(&original), region_volumes(&m));
    assert_eq!(r0.len(), r1.len(), "{name}: region tags changed");
    for ((t0, a), (t1, b)) in r0.iter().zip(&r1) {
        assert_eq!(t0, t1, "{name}: region tags changed");
        assert!((a - b).abs() <= 1e-9 * a.abs(), "{name}: region {t0} volume {a} became {b}");
    }
    assert_eq!(after.inverted, 0);
    // the report's numbers are the judge's
    assert_eq!(report.min_dihedral_after, after.min_dihedral_deg);
    assert_eq!(report.max_dihedral_after, after.max_dihedral_deg);
    assert_eq!(report.max_radius_edge_after, after.max_radius_edge);
    assert!(after.min_dihedral_deg >= MIN_DIHEDRAL, "{name}: min dihedral {}", after.min_dihedral_deg);
    assert!(after.max_dihedral_deg <= MAX_DIHEDRAL, "{name}: max dihedral {}", after.max_dihedral_deg);
    assert!(after.max_radius_edge <= MAX_RADIUS_EDGE, "{name}: max radius-edge {}", after.max_radius_edge);
    assert_eq!(after.tets_radius_edge_over_2, 0);
    after
}

#[test]
fn optimize_tetgen_plc() {
    // 71,130 tets, min dihedral 6.1°
    let Some(m) = tetgen_mesh("plc", "-pq1.414a0.0005Q") else {
        return;
    };
    optimise_and_check("plc", m, 13.914593);
}

#[test]
fn optimize_tetgen_plc_fine() {
    // 472,804 tets, min dihedral 5.95°
    let Some(m) = tetgen_mesh("plc_fine", "-pq1.414a0.000065Q") else {
        return;
    };
    optimise_and_check("plc_fine", m, 13.907858);
}
