//! The surface report on real files: the shared CAD corpus and the generated PLC surfaces.
//!
//! The corpus directory is `../shared/cad_corpus`, or `$FEPRE_CORPUS`. When it is missing
//! the corpus tests skip with a message, or fail under `CI=true`. The generated surfaces
//! (`shared/tools/data/plc*.stl`) must exist under CI and are skipped elsewhere when missing.

use fepre::io::{MeshData, ReadOptions, read};
use fepre::mesh::TriSurface;
use fepre::mesh::shapes::torus;
use fepre::mesh::topology::{ReportOptions, boundary_loops, open_edges_list, surface_report};
use std::path::Path;

mod common;
use common::{corpus_dir, shared_data};

fn load(path: &Path) -> TriSurface {
    match read(path, &ReadOptions::default()) {
        Ok(l) => match l.mesh {
            MeshData::Surface(s) => s,
            other => panic!("{}: expected a surface, got a {}", path.display(), other.kind()),
        },
        Err(e) => panic!("{}: {e}", path.display()),
    }
}


#[test]
fn bunny_is_open_with_42_boundary_edges() {
    let Some(dir) = corpus_dir() else { return };
    let s = load(&dir.join("bunny_binary.stl"));
    let r = surface_report(&s, &ReportOptions::default());
    assert_eq!((r.triangles, r.used_vertices, r.components), (4968, 2503, 1));
    assert!(!r.closed && r.manifold);
    assert_eq!((r.open_edges, r.nonmanifold_edges), (42, 0));
    assert_eq!(open_edges_list(&s).len(), 42);
    assert_eq!(r.boundary_loop_edges.iter().sum::<usize>(), 42);
    assert_eq!((r.boundary_loops, r.boundary_chains), (boundary_loops(&s).len(), 0));
    assert_eq!(r.genus, None);
    eprintln!(
        "bunny: loops {:?}, euler {}, oriented {}, self-intersections {:?}, degenerate {}",
        r.boundary_loop_edges, r.euler, r.oriented, r.self_intersections, r.degenerate_triangles
    );
}

#[test]
fn featuretype_is_closed_single_body() {
    let Some(dir) = corpus_dir() else { return };
    let s = load(&dir.join("featuretype.STL"));
    let r = surface_report(&s, &ReportOptions::default());
    assert_eq!((r.triangles, r.used_vertices), (3476, 1722));
    assert!(r.closed && r.manifold, "{r:?}");
    assert_eq!((r.components, r.open_edges, r.nonmanifold_edges), (1, 0, 0));
    assert!((r.volume.abs() - 11.6277).abs() < 1e-3, "volume {}", r.volume);
    eprintln!(
        "featuretype: euler {}, genus {:?}, oriented {}, outward {}, self-intersections {:?}",
        r.euler, r.genus, r.oriented, r.outward, r.self_intersections
    );
}

/// The generated PLC: a box with a through hole (genus 1) and a spherical cavity (genus 0).
fn check_plc(name: &str, triangles: usize, volume: f64) {
    let Some(path) = shared_data(name) else { return };
    let s = load(&path);
    let r = surface_report(&s, &ReportOptions::default());
    assert_eq!(r.triangles, triangles);
    assert!(r.closed && r.manifold && r.oriented, "{r:?}");
    assert_eq!((r.components, r.euler, r.self_intersections, r.degenerate_triangles), (2, 2, Some(0), 0));
    let outer = r.shells.iter().position(|x| x.genus == Some(1)).expect("a genus-1 shell");
    let cavity = r.shells.iter().position(|x| x.genus == Some(0)).expect("a genus-0 shell");
    assert_eq!((r.shells[outer].depth, r.shells[outer].parent), (Some(0), None));
    assert_eq!((r.shells[cavity].depth, r.shells[cavity].parent), (Some(1), Some(outer)));
    assert!(r.shells[cavity].volume < 0.0 && r.outward, "{r:?}");
    assert_eq!(r.genus, Some(1));
    assert!((r.volume - volume).abs() < 1e-9 * volume, "volume {} vs {volume}", r.volume);
}

#[test]
fn generated_plc_surfaces() {
    check_plc("plc.stl", 7764, 13.9145930912226);
    check_plc("plc_fine.stl", 31364, 13.907857529980182);
}

/// The report of a large surface is the same whatever the number of threads.
#[test]
fn thread_count_does_not_change_the_report() {
    let s = torus(3.0, 1.0, 300, 100);
    let r = surface_report(&s, &ReportOptions::default());
    assert!(r.closed && r.manifold && r.oriented && r.outward);
    assert_eq!((r.self_intersections, r.genus), (Some(0), Some(1)));
    for threads in [1, 3] {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        let again = pool.install(|| surface_report(&s, &ReportOptions::default()));
        assert_eq!(format!("{again:?}"), format!("{r:?}"), "{threads} threads");
    }
}
