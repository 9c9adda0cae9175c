//! Criterion benchmark of the tet mesh optimiser on a sliver-rich input built without TetGen:
//! the Delaunay tetrahedralization of a cube's corners and pseudo-random points inside it (about
//! 6.5 tets per point, a good share of them slivers), the hull faces as tagged boundary. Each
//! sample optimises a fresh copy; the copy is not timed. TetGen's quality meshes of the PLCs are
//! timed by `tests/optimize_tetgen.rs` (run it with `--nocapture`).

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use fepre::core::FaceId;
use fepre::mesh::TetMesh;
use fepre::mesh3d::delaunay::{DelaunayOptions, tetrahedralize};
use fepre::mesh3d::optimize::{OptimizeOptions, optimize};
use glam::DVec3;

fn random_box(n: usize) -> TetMesh {
    let mut s = 0x9e37_79b9_7f4a_7c15u64;
    let mut f = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut p: Vec<DVec3> = (0..8).map(|i| DVec3::new((i & 1) as f64, ((i >> 1) & 1) as f64, (i >> 2) as f64)).collect();
    p.extend((0..n).map(|_| DVec3::new(0.05 + 0.9 * f(), 0.05 + 0.9 * f(), 0.05 + 0.9 * f())));
    let mut m = tetrahedralize(&p, &DelaunayOptions::default()).expect("points span a volume").to_tet_mesh(&p);
    m.boundary = m.hull_faces();
    m.face_tags = vec![FaceId(1); m.boundary.len()];
    m
}

fn bench(c: &mut Criterion) {
    let m = random_box(3_000);
    let mut group = c.benchmark_group("optimize");
    group.sample_size(10);
    for (name, opts) in [
        ("random_box_3k", OptimizeOptions::default()),
        ("random_box_3k_no_insertion", OptimizeOptions::default().with_insertion(false)),
    ] {
        group.bench_function(name, |b| {
            b.iter_batched(|| m.clone(), |mut mesh| optimize(&mut mesh, &opts).expect("a valid mesh"), BatchSize::LargeInput)
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
