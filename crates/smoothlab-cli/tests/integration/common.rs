//! What the integration tests share: where the repository's test data and the external
//! meshes are.

use std::path::{Path, PathBuf};

/// The repository's root (the workspace: `tests/data`, `www/samples`, `fuzz/`).
pub fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Mesquite's 2D test meshes, read in place from `../shared/meshes/mesquite` beside the
/// repository (they are not copied into it). Absent on a developer's machine, the
/// caller's test says so and returns; absent under `CI=true`, the test fails, so a CI run
/// without the folder cannot pass by skipping what it was meant to check.
#[allow(dead_code)]
pub fn mesquite_meshes() -> Option<PathBuf> {
    shared_meshes("mesquite")
}

/// Mesquite's 3D test meshes, from `../shared/meshes/mesquite3d`, as [`mesquite_meshes`].
#[allow(dead_code)]
pub fn mesquite3d_meshes() -> Option<PathBuf> {
    shared_meshes("mesquite3d")
}

fn shared_meshes(name: &str) -> Option<PathBuf> {
    let dir = repo().join("../shared/meshes").join(name);
    if dir.is_dir() {
        return Some(dir);
    }
    let ci = std::env::var("CI").is_ok_and(|v| !v.is_empty() && v != "false" && v != "0");
    assert!(!ci, "CI is set but the external Mesquite meshes (../shared/meshes/{name}) are missing");
    println!("external Mesquite meshes (../shared/meshes/{name}) not found: skipped");
    None
}

/// The command-line tool built by this crate.
pub fn bin() -> &'static str {
    env!("CARGO_BIN_EXE_smoothlab")
}

/// Runs `smoothlab ARGS`.
pub fn run(args: &[&str]) -> std::process::Output {
    std::process::Command::new(bin()).args(args).output().unwrap()
}

/// Runs `smoothlab ARGS`, which must succeed, and returns what it printed.
pub fn ok(args: &[&str]) -> String {
    let out = run(args);
    assert!(out.status.success(), "smoothlab {args:?} failed: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap()
}

/// Runs `smoothlab ARGS`, which must be refused, and returns its message.
pub fn refused(args: &[&str]) -> String {
    let out = run(args);
    assert!(!out.status.success(), "smoothlab {args:?} was not refused");
    String::from_utf8(out.stderr).unwrap()
}

/// A path as an argument.
pub fn p(path: &Path) -> &str {
    path.to_str().unwrap()
}

/// A folder of the test's own (the tests run in parallel and write files of the same
/// names), named by the test module and the test.
pub fn scratch(module: &str, name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("smoothlab-{module}-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}
