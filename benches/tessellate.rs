//! Benchmarks of B-rep import and tessellation: reading and tessellating (default options)
//! our own STEP parts (`cad_fixtures/*.step`, always there) and a few corpus files of each
//! level (skipped with a message when the corpus is missing: set `FEPRE_CORPUS`), and building
//! a part in code; and the sized tessellation a volume mesh starts from (`tessellate_sized` at
//! the mesh's default size, a 25th of the diagonal: the feature-size field's samples and
//! queries, the refinement and the shape improvement of each face). Run with `cargo bench --bench tessellate`; figures are recorded in
//! `docs/benchmarks.md`, beside the truck comparison of `tools/bench_tessellate.sh`.

use criterion::{Criterion, criterion_group, criterion_main};
use fepre::cad::step;
use fepre::core::UniformSize;
use fepre::tessellate::{TessellateOptions, tessellate, tessellate_sized};
use std::hint::black_box;
use std::path::{Path, PathBuf};

fn corpus() -> Option<PathBuf> {
    let dir = match std::env::var_os("FEPRE_CORPUS") {
        Some(d) => PathBuf::from(d),
        None => Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/cad_corpus"),
    };
    if dir.is_dir() {
        Some(dir)
    } else {
        eprintln!("skipping the corpus files: {} is missing (set FEPRE_CORPUS)", dir.display());
        None
    }
}

fn read_and_tessellate(c: &mut Criterion) {
    let mut files: Vec<PathBuf> =
        ["bracket.step", "flange.step", "elbow.step"].iter().map(|n| Path::new(env!("CARGO_MANIFEST_DIR")).join("cad_fixtures").join(n)).collect();
    if let Some(dir) = corpus() {
        files.extend(["occt-cylinder.step", "Angled.step", "featuretype.STEP", "t20_data.step", "Zylkopf.stp", "as1-tu-203.stp"].iter().map(|n| dir.join(n)));
    }
    let mut g = c.benchmark_group("read_tessellate");
    g.sample_size(10);
    for f in files.iter().filter(|f| f.is_file()) {
        let name = f.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        g.bench_function(name, |b| {
            b.iter(|| {
                let m = step::read(black_box(f)).expect("readable");
                tessellate(&m, &TessellateOptions::default()).surface.triangles.len()
            })
        });
    }
    g.finish();
}

fn sized_tessellation(c: &mut Criterion) {
    let mut files: Vec<PathBuf> = ["bracket.step", "flange.step"].iter().map(|n| Path::new(env!("CARGO_MANIFEST_DIR")).join("cad_fixtures").join(n)).collect();
    if let Some(dir) = corpus() {
        files.extend(["part.step", "t20_data.step", "Kurbelwelle.stp"].iter().map(|n| dir.join(n)));
    }
    let mut g = c.benchmark_group("tessellate_sized");
    g.sample_size(10);
    for f in files.iter().filter(|f| f.is_file()) {
        let name = f.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        let m = step::read(f).expect("readable");
        let size = UniformSize(m.size() / 25.0);
        g.bench_function(name, |b| b.iter(|| tessellate_sized(black_box(&m), &TessellateOptions::default(), &size).surface.triangles.len()));
    }
    g.finish();
}

fn build_parts(c: &mut Criterion) {
    let mut g = c.benchmark_group("parts");
    g.bench_function("build_bracket", |b| b.iter(|| fepre::cad::parts::Bracket::default().build().expect("default bracket")));
    g.bench_function("write_step_flange", |b| {
        let m = fepre::cad::parts::Flange::default().build().expect("default flange");
        b.iter(|| step::to_string(black_box(&m), "flange").expect("writable").len())
    });
    g.finish();
}

criterion_group!(benches, read_and_tessellate, sized_tessellation, build_parts);
criterion_main!(benches);
