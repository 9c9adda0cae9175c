//! No clock, thread count or load steers a mesh: `fepre mesh Kurbelwelle.stp`, `fepre mesh
//! Angled.step` and `fepre mesh plate_holes.STL` (corpus) with one and two rayon threads, twice
//! each, while a thread of this process spins flat out, write one file each, byte for byte.

mod common;

use std::process::Command;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// FNV-1a, 64 bits: a fingerprint of the bytes for the message (the test compares the bytes).
fn fingerprint(b: &[u8]) -> u64 {
    b.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &x| (h ^ u64::from(x)).wrapping_mul(0x0100_0000_01b3))
}

#[test]
#[ignore = "release, four meshings of a corpus part; run with --include-ignored (CI does)"]
fn a_corpus_part_meshes_to_the_same_bytes_for_any_thread_count_under_load() {
    // two STEP parts, and a surface mesh whose boundary refinement splits
    for name in ["Kurbelwelle.stp", "Angled.step", "plate_holes.STL"] {
        if let Some(part) = common::corpus_file(name) {
            same_bytes_under_load(&part);
        }
    }
}

fn same_bytes_under_load(part: &std::path::Path) {
    let dir = tempfile::tempdir().unwrap();
    let stop = Arc::new(AtomicBool::new(false));
    let spinner = {
        let stop = stop.clone();
        std::thread::spawn(move || {
            let mut x = 0u64;
            while !stop.load(Ordering::Relaxed) {
                x = std::hint::black_box(x.wrapping_mul(6364136223846793005).wrapping_add(1));
            }
            x
        })
    };
    let mut runs: Vec<(String, Vec<u8>)> = Vec::new();
    for (k, threads) in ["1", "2", "1", "2"].into_iter().enumerate() {
        let out = dir.path().join(format!("k{k}.mesh"));
        let o = Command::new(env!("CARGO_BIN_EXE_fepre")).env("RAYON_NUM_THREADS", threads).arg("mesh").arg(part).arg("-o").arg(&out).output().unwrap();
        assert!(o.status.success(), "{threads} threads: {}", String::from_utf8_lossy(&o.stderr));
        runs.push((threads.to_string(), std::fs::read(&out).unwrap()));
    }
    stop.store(true, Ordering::Relaxed);
    spinner.join().unwrap();
    let first = &runs[0].1;
    assert!(!first.is_empty());
    for (threads, bytes) in &runs[1..] {
        let at = first.iter().zip(bytes).position(|(a, b)| a != b);
        assert!(
            bytes == first,
            "{}: with {threads} threads the mesh differs: {} bytes (fingerprint {:016x}) against {} ({:016x}), first difference at byte {at:?}",
            part.display(),
            bytes.len(),
            fingerprint(bytes),
            first.len(),
            fingerprint(first)
        );
    }
}
