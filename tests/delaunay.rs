//! The Delaunay tetrahedralization against TetGen (the same tets, exactly, on points in general
//! position), on the exactly degenerate 50³ grid (valid, volume 49³ exactly, no flat tet),
//! across thread counts (identical arrays), and on small degenerate sets (proptest: always
//! valid).

mod common;

use common::tools::{require, run_ok, tetgen};
use fepre::io::{MeshData, ReadOptions, read, read_points};
use fepre::mesh3d::delaunay::{Delaunay, DelaunayOptions, KernelKind, tetrahedralize};
use glam::DVec3;
use proptest::prelude::*;
use std::path::Path;
use std::process::Command;

fn sorted_quads(tets: &[[u32; 4]]) -> Vec<[u32; 4]> {
    let mut v: Vec<[u32; 4]> = tets
        .iter()
        .map(|t| {
            let mut s = *t;
            s.sort_unstable();
            s
        })
        .collect();
    v.sort_unstable();
    v
}

/// Our tets equal TetGen's as sets of vertex quadruples.
fn same_as_tetgen(name: &str) {
    let Some(src) = common::shared_data(&format!("{name}.node")) else { return };
    let Some(tetgen) = require(tetgen(), "tetgen", "the comparison with TetGen") else { return };
    let points = read_points(&src).unwrap();
    let ours = tetrahedralize(&points, &DelaunayOptions::default()).unwrap();
    ours.validate(&points).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let node = dir.path().join(format!("{name}.node"));
    std::fs::copy(&src, &node).unwrap();
    run_ok(Command::new(tetgen).arg("-Q").arg(&node), dir.path());
    let MeshData::Volume(theirs) = read(&dir.path().join(format!("{name}.1.ele")), &ReadOptions::default()).unwrap().mesh else {
        panic!("TetGen's output is not a tet mesh")
    };
    assert_eq!(theirs.vertices.len(), points.len(), "TetGen keeps every point");
    assert_eq!(ours.tets.len(), theirs.tets.len(), "{name}: tet counts");
    assert!(sorted_quads(&ours.tets) == sorted_quads(&theirs.tets), "{name}: the tets differ from TetGen's");
}

#[test]
fn rand_1e4_equals_tetgen() {
    same_as_tetgen("rand_1e4");
}

#[test]
fn rand_1e5_equals_tetgen() {
    same_as_tetgen("rand_1e5");
}

/// 6 × (signed volume) of a tet of integer points, exactly.
fn det6(p: &[DVec3], t: &[u32; 4]) -> i64 {
    let q = t.map(|i| p[i as usize].as_i64vec3());
    let (a, b, c) = (q[1] - q[0], q[2] - q[0], q[3] - q[0]);
    a.dot(b.cross(c))
}

#[test]
fn grid_50_is_valid_with_exact_volume_and_no_flat_tet() {
    let Some(src) = common::shared_data("grid_50.node") else { return };
    let points = read_points(&src).unwrap();
    let d = tetrahedralize(&points, &DelaunayOptions::default()).unwrap();
    assert_eq!(d.kernel, KernelKind::Integer);
    d.validate(&points).unwrap();
    let dets: Vec<i64> = d.tets.iter().map(|t| det6(&points, t)).collect();
    assert!(dets.iter().all(|&x| x > 0), "a flat or inverted tet");
    assert_eq!(dets.iter().sum::<i64>(), 6 * 49 * 49 * 49, "volume 49³ exactly");
    assert_eq!(d.tets.len(), 6 * 49 * 49 * 49);
    assert!(d.duplicates.is_empty());
}

fn random_points(n: usize, seed: u64) -> Vec<DVec3> {
    let mut s = seed | 1;
    let mut f = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..n).map(|_| DVec3::new(f(), f(), f())).collect()
}

fn with_threads(threads: usize, points: &[DVec3], parallel: bool) -> Delaunay {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
    pool.install(|| tetrahedralize(points, &DelaunayOptions::default().with_parallel(parallel)).unwrap())
}

/// Parallel rounds give the same arrays as the serial insertion, for any number of threads,
/// on random points with duplicates and on an exactly degenerate grid.
#[test]
fn identical_output_for_any_thread_count() {
    let mut random = random_points(60_000, 3);
    for i in 0..500 {
        let j = (i * 97) % 60_000;
        random.push(random[j]); // duplicates
    }
    let grid: Vec<DVec3> = (0..32 * 32 * 32).map(|i| DVec3::new((i % 32) as f64, ((i / 32) % 32) as f64, (i / 1024) as f64)).collect();
    for points in [&random, &grid] {
        let serial = with_threads(1, points, false);
        serial.validate(points).unwrap();
        for threads in [1, 2, 3, 5] {
            let par = with_threads(threads, points, true);
            assert!(par.tets == serial.tets && par.duplicates == serial.duplicates, "{threads} threads: the output differs from the serial one");
        }
    }
}

#[test]
fn reads_xyz_and_node_alike() {
    let (Some(a), Some(b)) = (common::shared_data("rand_1e4.xyz"), common::shared_data("rand_1e4.node")) else { return };
    assert_eq!(read_points(&a).unwrap(), read_points(&b).unwrap());
    assert!(read_points(Path::new("x.stl")).is_err());
}

/// Small point sets from degenerate generators: grids, cospherical points, coplanar slabs,
/// repeated points, at scales from 2^-20 to 2^20.
fn degenerate() -> impl Strategy<Value = Vec<DVec3>> {
    let scale = (-20i32..=20).prop_map(|k| 2f64.powi(k));
    let grid = prop::collection::vec((0i32..4, 0i32..4, 0i32..3), 4..40);
    let sphere: Vec<[i32; 3]> = {
        let mut v = Vec::new();
        for x in -5i32..=5 {
            for y in -5i32..=5 {
                for z in -5i32..=5 {
                    if x * x + y * y + z * z == 25 {
                        v.push([x, y, z]);
                    }
                }
            }
        }
        v
    };
    let cos = prop::collection::vec(0..sphere.len(), 5..40).prop_map(move |ix| ix.into_iter().map(|i| (sphere[i][0], sphere[i][1], sphere[i][2])).collect::<Vec<_>>());
    (prop_oneof![grid, cos], scale).prop_map(|(v, s)| v.into_iter().map(|(x, y, z)| DVec3::new(x as f64, y as f64, z as f64) * s).collect())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn degenerate_sets_always_validate(points in degenerate()) {
        match tetrahedralize(&points, &DelaunayOptions::default()) {
            Ok(d) => {
                if let Err(e) = d.validate(&points) {
                    return Err(TestCaseError::fail(format!("{e}")));
                }
            }
            // sets spanning no tetrahedron (all coplanar, collinear, coincident) are errors
            Err(e) => prop_assert!(e.to_string().contains("no tetrahedron"), "{}", e),
        }
    }
}
