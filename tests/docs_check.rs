//! The docs a newcomer reads: `docs/benchmarks.md` names a command that exists for every area
//! and cites every `tools/bench_*.sh` and criterion target, each area fits a screen, and
//! `ARCHITECTURE.md` stays under 12 KiB with its module graph (`tools/check_benchmarks.py`).

use std::process::Command;

#[test]
fn benchmarks_and_architecture_pass_their_check() {
    let root = env!("CARGO_MANIFEST_DIR");
    let out = Command::new("python3")
        .arg(format!("{root}/tools/check_benchmarks.py"))
        .arg(root)
        .output()
        .expect("python3 runs (it is on every machine the project builds on)");
    assert!(
        out.status.success(),
        "tools/check_benchmarks.py failed:\n{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}
