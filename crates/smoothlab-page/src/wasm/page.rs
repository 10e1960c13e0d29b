//! What the page is built from and checks its inputs by: the gallery of samples, the
//! controls' sheet and checks, and the permalink's reader and writer.

use serde::Serialize;
use wasm_bindgen::prelude::*;

use super::to_js;
use crate::lab::sample::Sample;
use crate::lab::permalink;

/// The gallery of generated samples: `[{ name, title }]` in gallery order (a permalink
/// names every one, `permalink::SAMPLES`).
#[wasm_bindgen]
pub fn samples() -> Result<JsValue, JsError> {
    #[derive(serde::Serialize)]
    struct Entry {
        name: Sample,
        title: &'static str,
    }
    let list: Vec<Entry> = Sample::GALLERY.iter().map(|&s| Entry { name: s, title: s.title() }).collect();
    to_js(&list)
}

/// Reads a permalink hash (`#sample=…&passes=…`) with [`crate::lab::permalink::decode`]: the
/// [`PageState`](crate::lab::permalink::PageState) as it is, `sample`/`node` null when absent,
/// `seed` a number (a BigInt beyond 2^53 − 1). A malformed value is an error naming its key.
#[wasm_bindgen(js_name = decodePermalink)]
pub fn decode_permalink(hash: &str) -> Result<JsValue, JsError> {
    let state = permalink::decode(hash)?;
    let big = state.seed > (1u64 << 53) - 1;
    let ser = serde_wasm_bindgen::Serializer::new()
        .serialize_missing_as_null(true)
        .serialize_large_number_types_as_bigints(big);
    Ok(state.serialize(&ser)?)
}

/// Writes the hash (with its `#`) of an object shaped as [`decode_permalink`] returns
/// (fields left out take their defaults), with [`crate::lab::permalink::encode`] after checking
/// every value as the decoder would.
#[wasm_bindgen(js_name = encodePermalink)]
pub fn encode_permalink(state: JsValue) -> Result<String, JsError> {
    let state: permalink::PageState =
        serde_wasm_bindgen::from_value(state).map_err(|e| JsError::new(&format!("permalink: {e}")))?;
    state.validate()?;
    Ok(permalink::encode(&state))
}

/// The page's controls: their ranges, defaults and labels, and which strategy uses which
/// control (see [`crate::lab::controls::page_controls`]): the page builds its inputs from this.
#[wasm_bindgen]
pub fn controls() -> Result<JsValue, JsError> {
    to_js(&crate::lab::controls::page_controls())
}

/// Checks the text of one control (by its permalink key) as the permalink would read it:
/// `null` when it is valid, else a message for people with the allowed range in words.
#[wasm_bindgen(js_name = checkControl)]
pub fn check_control(key: &str, text: &str) -> Option<String> {
    permalink::check_control(key, text).err()
}
