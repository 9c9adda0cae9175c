//! Benchmarks of the foundation: exact predicates on random and degenerate input, the surface
//! report (with and without the exact self-intersection test), whole-mesh quality, and reading
//! a large binary STL. Run with `cargo bench --bench foundation`; figures are recorded in
//! `docs/benchmarks.md`.

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use fepre::core::predicates::{insphere, insphere_sos, orient3d};
use fepre::io::{MeshData, ReadOptions, WriteOptions, read, write};
use fepre::mesh::shapes::{kuhn_cube, torus};
use fepre::mesh::topology::{ReportOptions, surface_report};
use fepre::quality::tet_mesh_quality;
use glam::DVec3;
use std::hint::black_box;

fn lcg(seed: &mut u64) -> f64 {
    *seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
    (*seed >> 11) as f64 / (1u64 << 53) as f64
}

fn predicates(c: &mut Criterion) {
    let mut s = 1u64;
    let random: Vec<DVec3> = (0..5000).map(|_| DVec3::new(lcg(&mut s), lcg(&mut s), lcg(&mut s))).collect();
    let grid: Vec<DVec3> = (0..5000).map(|i| DVec3::new((i % 17) as f64, ((i / 17) % 17) as f64, (i / 289) as f64)).collect();
    let mut g = c.benchmark_group("predicates");
    for (name, p) in [("random", &random), ("grid", &grid)] {
        g.bench_function(format!("orient3d_{name}"), |b| {
            b.iter(|| (0..p.len() - 4).map(|i| orient3d(p[i], p[i + 1], p[i + 2], p[i + 3]) as i32).sum::<i32>())
        });
        g.bench_function(format!("insphere_{name}"), |b| {
            b.iter(|| (0..p.len() - 5).map(|i| insphere(p[i], p[i + 1], p[i + 2], p[i + 3], p[i + 4]) as i32).sum::<i32>())
        });
        g.bench_function(format!("insphere_sos_{name}"), |b| {
            b.iter(|| {
                (0..p.len() - 5)
                    .map(|i| {
                        let id = [i as u32, i as u32 + 1, i as u32 + 2, i as u32 + 3, i as u32 + 4];
                        insphere_sos([p[i], p[i + 1], p[i + 2], p[i + 3], p[i + 4]], id) as i32
                    })
                    .sum::<i32>()
            })
        });
    }
    g.finish();
}

fn surface(c: &mut Criterion) {
    let s = torus(3.0, 1.0, 1000, 500); // 1e6 triangles
    let mut g = c.benchmark_group("surface_report_torus_1e6");
    g.sample_size(10);
    g.bench_function("topology_only", |b| b.iter(|| surface_report(black_box(&s), &ReportOptions::default().with_self_intersections(false))));
    g.bench_function("with_self_intersections", |b| b.iter(|| surface_report(black_box(&s), &ReportOptions::default())));
    g.finish();
}

fn quality(c: &mut Criterion) {
    let m = kuhn_cube(55, 0.25, 12345); // 998,250 tets
    let mut g = c.benchmark_group("tet_quality");
    g.sample_size(10);
    g.bench_function("kuhn_cube_1e6", |b| b.iter(|| tet_mesh_quality(black_box(&m))));
    g.finish();
}

fn io(c: &mut Criterion) {
    let dir = tempfile::tempdir().expect("temporary directory");
    let path = dir.path().join("torus.stl");
    let s = torus(3.0, 1.0, 1000, 250); // 5e5 triangles
    write(&path, &MeshData::Surface(s), &WriteOptions::default()).expect("write");
    let mut g = c.benchmark_group("read");
    g.sample_size(10);
    g.bench_function("binary_stl_5e5_welded", |b| {
        b.iter_batched(|| (), |_| read(&path, &ReadOptions::default()).expect("read"), BatchSize::SmallInput)
    });
    g.finish();
}

criterion_group!(benches, predicates, surface, quality, io);
criterion_main!(benches);
