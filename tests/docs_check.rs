//! The house's own checks, run as tests: `docs/benchmarks.md` names a command that exists for
//! every area and cites every `tools/bench_*.sh` and criterion target, each area fits a screen,
//! and `ARCHITECTURE.md` stays under 12 KiB with its module graph
//! (`tools/check_benchmarks.py`); no two files of `src/` import each other in a circle, but
//! for the recursive geometry types `ARCHITECTURE.md` names (`tools/import_circles.py`).

use std::process::Command;

/// Runs `python3 tools/SCRIPT ROOT` and fails with its output unless it exits 0.
fn script_passes(script: &str) {
    let root = env!("CARGO_MANIFEST_DIR");
    let out = Command::new("python3")
        .arg(format!("{root}/tools/{script}"))
        .arg(root)
        .output()
        .expect("python3 runs (it is on every machine the project builds on)");
    assert!(
        out.status.success(),
        "tools/{script} failed:\n{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn benchmarks_and_architecture_pass_their_check() {
    script_passes("check_benchmarks.py");
}

#[test]
fn no_import_circle_between_files() {
    script_passes("import_circles.py");
}
