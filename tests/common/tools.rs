//! Finding the external tools that integration tests check fepre's files with: `gmsh`,
//! `tetgen`, CalculiX's `ccx` and a Python interpreter with meshio.
//!
//! A missing tool makes a check print a skip message and return, except under `CI=true`,
//! where it fails: CI images must have the tools.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

pub use super::in_ci;

/// An executable named `name` on `PATH`.
pub fn on_path(name: &str) -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path).map(|d| d.join(name)).find(|p| is_executable(p))
}

fn is_executable(p: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        p.metadata().is_ok_and(|m| m.is_file() && m.permissions().mode() & 0o111 != 0)
    }
    #[cfg(not(unix))]
    {
        p.is_file()
    }
}

/// `gmsh`, if installed.
pub fn gmsh() -> Option<PathBuf> {
    on_path("gmsh")
}

/// `tetgen`, if installed.
pub fn tetgen() -> Option<PathBuf> {
    on_path("tetgen")
}

/// CalculiX's solver `ccx`, if installed.
pub fn ccx() -> Option<PathBuf> {
    on_path("ccx")
}

/// A Python interpreter that imports every module of `modules`: `$FEPRE_PYTHON` if set,
/// else `.venv/bin/python` in the crate's directory if it exists.
pub fn python_with(modules: &[&str]) -> Option<PathBuf> {
    let python = match std::env::var_os("FEPRE_PYTHON") {
        Some(p) => PathBuf::from(p),
        None => Path::new(env!("CARGO_MANIFEST_DIR")).join(".venv/bin/python"),
    };
    if !python.exists() && python.components().count() > 1 {
        return None;
    }
    let probe = format!("import {}", modules.join(", "));
    let ok = Command::new(&python).args(["-c", &probe]).output().is_ok_and(|o| o.status.success());
    ok.then_some(python)
}

/// Python with meshio and numpy.
pub fn meshio_python() -> Option<PathBuf> {
    python_with(&["meshio", "numpy"])
}

/// `tool` if found; otherwise prints why the check named `check` is skipped and returns
/// `None`, or panics under CI.
pub fn require(tool: Option<PathBuf>, name: &str, check: &str) -> Option<PathBuf> {
    if tool.is_none() {
        assert!(!in_ci(), "{name} not found, needed for {check} (CI=true requires it: install it, or set FEPRE_PYTHON for Python)");
        eprintln!("SKIP: {name} not found: skipping {check}");
    }
    tool
}

/// Runs `cmd` in `dir`, panicking with its output if it cannot start or fails.
pub fn run_ok(cmd: &mut Command, dir: &Path) -> Output {
    let shown = format!("{cmd:?}");
    let out = cmd.current_dir(dir).output().unwrap_or_else(|e| panic!("cannot run {shown}: {e}"));
    assert!(
        out.status.success(),
        "{shown} failed ({}):\n--- stdout\n{}\n--- stderr\n{}",
        out.status,
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    out
}
