//! `#[wasm_bindgen]` exports: each converts its arguments, calls [`super::playground`]
//! or the core, and converts the answer (serde-wasm-bindgen for records, `Vec<u8>` for
//! pixels). Core errors become `JsError`s carrying the core's message.

use std::sync::Mutex;

use wasm_bindgen::prelude::*;

use super::playground::{self, Settings, Side};
use super::sample::Sample;
use crate::io::{self, Format};

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

/// Milliseconds from the worker's (or window's) `performance.now()`, else the date.
fn now_ms() -> f64 {
    let global = js_sys::global();
    js_sys::Reflect::get(&global, &JsValue::from_str("performance"))
        .ok()
        .and_then(|p| {
            let now = js_sys::Reflect::get(&p, &JsValue::from_str("now")).ok()?;
            let now: js_sys::Function = now.dyn_into().ok()?;
            now.call0(&p).ok()?.as_f64()
        })
        .unwrap_or_else(js_sys::Date::now)
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

    /// A playground on the bytes of a mesh file called `name` (.msh, .vtk, .obj, .off).
    #[wasm_bindgen(js_name = fromBytes)]
    pub fn from_bytes(bytes: &[u8], name: &str) -> Result<Playground, JsError> {
        Ok(Playground { inner: playground::Playground::new(io::read_bytes(bytes, name)?)? })
    }

    /// A playground on a Triangle mesh: the texts of its `.node` and `.ele` files.
    #[wasm_bindgen(js_name = fromTriangle)]
    pub fn from_triangle(node: &str, ele: &str) -> Result<Playground, JsError> {
        Ok(Playground { inner: playground::Playground::new(io::read_triangle(node, ele)?)? })
    }

    /// The shared controls: `{ strategy, threshold_deg, order, max_iter }`.
    #[wasm_bindgen(js_name = setSettings)]
    pub fn set_settings(&mut self, settings: JsValue) -> Result<(), JsError> {
        let s: Settings = serde_wasm_bindgen::from_value(settings).map_err(|e| JsError::new(&format!("settings: {e}")))?;
        Ok(self.inner.set_settings(s)?)
    }

    /// One smoothing pass on both panels; returns their pass records `[old, new]`.
    pub fn step(&mut self) -> Result<JsValue, JsError> {
        Ok(serde_wasm_bindgen::to_value(&self.inner.step(&now_ms))?)
    }

    /// Perturbs the original mesh (`amount` mean edge lengths, seeded) and resets both panels.
    pub fn perturb(&mut self, amount: f64, seed: u32) -> Result<(), JsError> {
        Ok(self.inner.perturb(amount, seed as u64)?)
    }

    /// A panel's current mesh as the text of a `msh` or `vtk` file.
    #[wasm_bindgen(js_name = exportMesh)]
    pub fn export_mesh(&self, panel: &str, format: &str) -> Result<String, JsError> {
        let format = match format {
            "msh" => Format::Msh,
            "vtk" => Format::Vtk,
            _ => return Err(JsError::new(&format!("cannot export as '{format}': use msh or vtk"))),
        };
        Ok(self.inner.export(side(panel)?, format)?)
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
