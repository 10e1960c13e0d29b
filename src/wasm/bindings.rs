//! `#[wasm_bindgen]` exports: each converts its arguments, calls [`super::playground`]
//! or the core, and converts the answer (serde-wasm-bindgen for records, `Vec<u8>` for
//! pixels). Core errors become `JsError`s carrying the core's message.

use std::sync::Mutex;

use wasm_bindgen::prelude::*;

use super::playground::{self, Side};
use super::sample::Sample;

/// The message of the last panic, kept by the hook for [`take_panic_message`].
static LAST_PANIC: Mutex<Option<String>> = Mutex::new(None);

/// Installs the panic hook when the module starts: it records the panic's message and
/// location (and logs them to the console) so the page can show what went wrong.
#[wasm_bindgen(start)]
pub fn start() {
    std::panic::set_hook(Box::new(|info| {
        let msg = info.to_string();
        web_sys::console::error_1(&JsValue::from_str(&msg));
        if let Ok(mut slot) = LAST_PANIC.lock() {
            *slot = Some(msg);
        }
    }));
}

/// The message of the last panic, if one happened since the last call (then cleared).
#[wasm_bindgen(js_name = takePanicMessage)]
pub fn take_panic_message() -> Option<String> {
    LAST_PANIC.lock().ok().and_then(|mut s| s.take())
}

/// Panics on purpose: lets the browser tests prove that the page survives a panic.
#[wasm_bindgen(js_name = panicForTest)]
pub fn panic_for_test() {
    panic!("deliberate panic requested by the page's self-test");
}

/// The gallery of generated samples: `[{ name, title }]` in gallery order.
#[wasm_bindgen]
pub fn samples() -> Result<JsValue, JsError> {
    #[derive(serde::Serialize)]
    struct Entry {
        name: Sample,
        title: &'static str,
    }
    let list: Vec<Entry> = Sample::ALL.iter().map(|&s| Entry { name: s, title: s.title() }).collect();
    Ok(serde_wasm_bindgen::to_value(&list)?)
}

fn side(s: &str) -> Result<Side, JsError> {
    serde_wasm_bindgen::from_value(JsValue::from_str(s)).map_err(|_| JsError::new(&format!("no panel '{s}': use old or new")))
}

/// The page's state: one opaque handle (see [`playground::Playground`]).
#[wasm_bindgen]
pub struct Playground {
    inner: playground::Playground,
}

#[wasm_bindgen]
impl Playground {
    /// A playground on a generated sample, by its gallery name (`plate-tri-tangled`, …).
    #[wasm_bindgen(js_name = fromSample)]
    pub fn from_sample(name: &str) -> Result<Playground, JsError> {
        let sample: Sample = serde_wasm_bindgen::from_value(JsValue::from_str(name))
            .map_err(|_| JsError::new(&format!("no sample named '{name}'")))?;
        Ok(Playground { inner: playground::Playground::new(sample.generate()?)? })
    }

    /// Statistics of one panel (`old` or `new`).
    pub fn stats(&self, panel: &str) -> Result<JsValue, JsError> {
        Ok(serde_wasm_bindgen::to_value(&self.inner.stats(side(panel)?))?)
    }

    /// Both panels back to the mesh as loaded.
    pub fn reset(&mut self) {
        self.inner.reset();
    }
}
