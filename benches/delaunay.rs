//! Criterion benchmarks of the Delaunay tetrahedralization: random points (float kernel) and a
//! grid (integer kernel, every cell cospherical), counted and in canonical form, serial and on
//! the default thread pool. Whole-process comparisons with TetGen and CGAL are in
//! `tools/bench_delaunay.sh`; figures in `docs/benchmarks.md`.

use criterion::{Criterion, criterion_group, criterion_main};
use fepre::mesh3d::delaunay::{DelaunayOptions, count_tetrahedra, tetrahedralize};
use glam::DVec3;
use std::hint::black_box;

fn random(n: usize) -> Vec<DVec3> {
    let mut s = 0x9e37_79b9_7f4a_7c15u64;
    let mut f = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..n).map(|_| DVec3::new(f(), f(), f())).collect()
}

fn grid(n: usize) -> Vec<DVec3> {
    (0..n * n * n).map(|i| DVec3::new((i % n) as f64, ((i / n) % n) as f64, (i / (n * n)) as f64)).collect()
}

fn delaunay(c: &mut Criterion) {
    let r = random(100_000);
    let g = grid(30);
    let serial = DelaunayOptions::default().with_parallel(false);
    let mut group = c.benchmark_group("delaunay");
    group.sample_size(10);
    group.bench_function("random_1e5_count_serial", |b| b.iter(|| count_tetrahedra(black_box(&r), &serial)));
    group.bench_function("random_1e5_tets_serial", |b| b.iter(|| tetrahedralize(black_box(&r), &serial)));
    group.bench_function("random_1e5_count_parallel", |b| b.iter(|| count_tetrahedra(black_box(&r), &DelaunayOptions::default())));
    group.bench_function("grid_30_count_serial", |b| b.iter(|| count_tetrahedra(black_box(&g), &serial)));
    group.finish();
}

criterion_group!(benches, delaunay);
criterion_main!(benches);
