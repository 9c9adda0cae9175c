//! Helpers shared by the integration tests (`mod common;` in each test file that needs them).

#![allow(dead_code)]

use std::path::{Path, PathBuf};

/// True when running under CI (`CI=true` or `CI=1`), where missing test inputs and tools fail
/// instead of skipping.
pub fn in_ci() -> bool {
    std::env::var("CI").is_ok_and(|v| v.eq_ignore_ascii_case("true") || v == "1")
}

/// The shared folder beside the checkout: `$FEPRE_SHARED`, else `../shared`.
pub fn shared_dir() -> PathBuf {
    match std::env::var_os("FEPRE_SHARED") {
        Some(d) => PathBuf::from(d),
        None => Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared"),
    }
}

/// A generated reference input in `shared/tools/data` (written by `shared/tools/gen/make_all.sh`,
/// which `.ci/run` runs). `None` after a skip message when it is missing, except under CI,
/// where that fails the test.
pub fn shared_data(name: &str) -> Option<PathBuf> {
    let path = shared_dir().join("tools/data").join(name);
    if path.is_file() {
        return Some(path);
    }
    assert!(!in_ci(), "the generated input {} is missing (CI=true: run shared/tools/gen/make_all.sh)", path.display());
    eprintln!("skipping: the generated input {} is missing (run shared/tools/gen/make_all.sh)", path.display());
    None
}

/// The shared CAD and mesh corpus: `$FEPRE_CORPUS`, else `../shared/cad_corpus` beside the
/// checkout. Returns `None` after printing a skip message when it is missing, except under CI
/// (`CI=true`), where a missing corpus fails the test.
pub fn corpus_dir() -> Option<PathBuf> {
    let dir = match std::env::var_os("FEPRE_CORPUS") {
        Some(d) => PathBuf::from(d),
        None => Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/cad_corpus"),
    };
    if dir.is_dir() {
        return Some(dir);
    }
    assert!(!in_ci(), "the corpus {} is missing (CI=true: set FEPRE_CORPUS or put ../shared beside the checkout)", dir.display());
    eprintln!("skipping: the corpus {} is missing (set FEPRE_CORPUS to run this test)", dir.display());
    None
}

/// A file of the corpus, or `None` (after a skip message) as for [`corpus_dir`].
pub fn corpus_file(name: &str) -> Option<PathBuf> {
    let path = corpus_dir()?.join(name);
    if path.is_file() {
        return Some(path);
    }
    assert!(!in_ci(), "the corpus file {} is missing (CI=true)", path.display());
    eprintln!("skipping: the corpus file {} is missing", path.display());
    None
}

/// Hand-written STEP files and their comparison with OpenCASCADE (`step_entities*.rs`).
pub mod step_writer;
/// Discovery of the external tools (gmsh, tetgen, Python with meshio) some tests check files with.
pub mod tools;

/// The STEP sweep (real STEP exports, `occ.jsonl` beside them): `$FEPRE_SWEEP`, else
/// `../shared/step_sweep` beside the checkout. `None` after a skip message when it is missing,
/// except under CI, where that fails the test.
pub fn sweep_dir() -> Option<PathBuf> {
    let dir = match std::env::var_os("FEPRE_SWEEP") {
        Some(d) => PathBuf::from(d),
        None => Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/step_sweep"),
    };
    if dir.is_dir() {
        return Some(dir);
    }
    assert!(!in_ci(), "the STEP sweep {} is missing (CI=true: set FEPRE_SWEEP or put ../shared beside the checkout)", dir.display());
    eprintln!("skipping: the STEP sweep {} is missing (set FEPRE_SWEEP to run this test)", dir.display());
    None
}
