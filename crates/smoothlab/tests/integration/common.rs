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

/// Livesu et al.'s hexahedral meshes (2015, `*_in.mesh`, Medit, as HexaLab serves them),
/// from `../shared/meshes/livesu2015`, as [`mesquite_meshes`].
#[allow(dead_code)]
pub fn livesu_meshes() -> Option<PathBuf> {
    shared_meshes("livesu2015")
}

fn shared_meshes(name: &str) -> Option<PathBuf> {
    let dir = repo().join("../shared/meshes").join(name);
    if dir.is_dir() {
        return Some(dir);
    }
    let ci = std::env::var("CI").is_ok_and(|v| !v.is_empty() && v != "false" && v != "0");
    assert!(!ci, "CI is set but the external meshes ../shared/meshes/{name} are missing");
    println!("external meshes ../shared/meshes/{name} not found: skipped");
    None
}
