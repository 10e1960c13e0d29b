//! What the integration tests share: the repository's test data and the external meshes
//! (the core's helpers, included by path), and the command-line tool.

use std::path::{Path, PathBuf};

#[path = "../../../smoothlab/tests/integration/common.rs"]
mod meshes;
#[allow(unused_imports)]
pub use meshes::{livesu_meshes, mesquite3d_meshes, mesquite_meshes, repo};

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
