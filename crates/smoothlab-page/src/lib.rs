//! The playground page: its state, free of web types ([`lab`]: the two sides A and B, the
//! pass in slices, the tour of the papers' figures, permalinks), and on `wasm32` the
//! `#[wasm_bindgen]` layer that converts types and calls it.

pub mod lab;
#[cfg(target_arch = "wasm32")]
mod wasm;
