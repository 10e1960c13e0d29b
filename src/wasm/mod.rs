//! The WebAssembly face of the core, for the playground page (`www/`).
//!
//! [`playground`] and [`sample`] are plain Rust (tested natively); [`bindings`] (only on
//! `wasm32`) converts types for JavaScript and calls them — nothing else. Long-lived
//! state stays in Rust behind one opaque handle, `Playground`; errors reach JavaScript
//! as `JsError` messages, and a panic is recorded by a hook so the page can report it.

pub mod playground;
pub mod sample;
pub mod views;

#[cfg(target_arch = "wasm32")]
mod bindings;
