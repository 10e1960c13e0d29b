//! smoothlab: a mesh-smoothing laboratory.
//!
//! The core is pure Rust with no web types. Modules follow the mathematics:
//! [`mesh`] (model and topology) → [`quality`] (element metrics) → [`objective`]
//! (a node's objective over its star) → [`optimize`] (solvers) → [`smooth`]
//! (drivers: Laplacian, smart, combined, rules with priority). [`io`] reads and writes
//! mesh files, [`generate`] makes sample meshes, [`render`] draws with tiny-skia.
//! The wasm layer (`wasm`, only on `wasm32`) converts types and calls the core.

pub mod error;
pub mod generate;
pub mod io;
pub mod lab;
pub mod limits;
pub mod mesh;
pub mod objective;
pub mod optimize;
pub mod permalink;
pub mod quality;
pub mod render;
pub mod smooth;
#[cfg(target_arch = "wasm32")]
mod wasm;
#[cfg(target_arch = "wasm32")]
mod wasm_bench;

pub use error::{Error, Result};
pub use mesh::{ElementKind, Mesh, MeshBuilder};
