//! `#[wasm_bindgen]` exports: each converts its arguments, calls [`crate::lab`] or the
//! core, and converts the answer (serde-wasm-bindgen for records, `Vec<u8>` for pixels).
//! Core errors become `JsError`s carrying the core's message. No state of the page lives
//! here: the handles wrap the lab's types, which keep it (and native tests see it).
//!
//! One file a concern: this one the panic hook, opening a mesh and the conversions the
//! others share; [`page`] the lists and checks the page is built from (samples, controls,
//! permalinks); [`playground`] the planar lab's handle; [`lab3d`] the 3D lab's handle (a
//! surface or tetrahedra); [`tour`] the figures tour; [`bench`] the benchmark page's mesh.

mod bench;
mod lab3d;
mod page;
mod playground;
mod tour;

use std::sync::Mutex;

use serde::Serialize;
use wasm_bindgen::prelude::*;

use smoothlab::io;
use crate::lab::sample::Sample;
use crate::lab::views::Canvas;
use crate::lab::Side;
use smoothlab::model::Model;

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

/// The handle for a model: a [`playground::Playground`] for a planar mesh, a
/// [`lab3d::Lab3d`] for a surface or tetrahedra.
fn open(model: Model) -> Result<JsValue, JsError> {
    Ok(match model {
        Model::Planar(m) => playground::Playground::open(m)?.into(),
        Model::Surface(s) => lab3d::Lab3d::surface(s)?.into(),
        Model::Volume(v) => lab3d::Lab3d::volume(v)?.into(),
    })
}

/// A gallery sample by its name: a `Playground`, or a `Lab3d` for a surface or tetrahedra.
#[wasm_bindgen(js_name = openSample)]
pub fn open_sample(name: &str) -> Result<JsValue, JsError> {
    open(sample(name)?.model()?)
}

/// The bytes of a mesh file called `name` (.msh, .vtk, .obj, .off, .mesh): a `Playground` for a
/// planar mesh, a `Lab3d` for a surface in 3D or tetrahedra.
#[wasm_bindgen(js_name = openBytes)]
pub fn open_bytes(bytes: &[u8], name: &str) -> Result<JsValue, JsError> {
    open(io::read_model_bytes(bytes, name)?)
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

/// The Perturb controls checked as the permalink checks them: the seed as a number (a
/// whole number up to 2^64 − 1, beyond what a JS number holds exactly, so given as text).
fn perturb_seed(amount: f64, seed: &str) -> Result<u64, JsError> {
    crate::lab::permalink::check_control("seed", seed).map_err(|e| JsError::new(&e))?;
    crate::lab::permalink::check_control("tangle", &amount.to_string()).map_err(|e| JsError::new(&e))?;
    seed.trim().parse().map_err(|_| JsError::new("Seed: enter a whole number"))
}

/// A side by its name on the page: `a` or `b`.
fn side(s: &str) -> Result<Side, JsError> {
    serde_wasm_bindgen::from_value(JsValue::from_str(s)).map_err(|_| JsError::new(&format!("no panel '{s}': use a or b")))
}

/// The settings as the page sends them (see [`crate::lab::Settings`]).
fn settings(value: JsValue) -> Result<crate::lab::Settings, JsError> {
    serde_wasm_bindgen::from_value(value).map_err(|e| JsError::new(&format!("settings: {e}")))
}

/// A record as a plain JS object (maps too, so `#[serde(flatten)]` fields read as properties).
fn to_js<T: Serialize>(value: &T) -> Result<JsValue, JsError> {
    let ser = serde_wasm_bindgen::Serializer::new().serialize_maps_as_objects(true);
    Ok(value.serialize(&ser)?)
}

/// A JS object `{ key: value, … }` (for results that mix pixels and records).
fn object(entries: &[(&str, JsValue)]) -> Result<JsValue, JsError> {
    let o = js_sys::Object::new();
    for (k, v) in entries {
        js_sys::Reflect::set(&o, &JsValue::from_str(k), v).map_err(|_| JsError::new("cannot build the result object"))?;
    }
    Ok(o.into())
}

/// Pixels for a canvas `ImageData` (opaque, so straight RGBA): one copy out of the wasm
/// memory into a buffer of its own, which the worker then moves (not copies) to the page.
/// A node view's pictures and summary as the page takes them (the playground's and the
/// 3D lab's alike): both level sets, the solve chart, the summary in words and whole.
fn node_view_object<S: Serialize>(pictures: [tiny_skia::Pixmap; 3], text: String, summary: &S) -> Result<JsValue, JsError> {
    let [la, lb, chart] = pictures;
    object(&[
        ("level_a", pixels(la)),
        ("level_b", pixels(lb)),
        ("chart", pixels(chart)),
        ("summary", JsValue::from_str(&text)),
        ("solve", to_js(summary)?),
    ])
}

/// A mesh as arrays for the page's host (a notebook's widget): `{ dim, points:
/// Float64Array, cells: [{ vtk_type, per_cell, nodes: Uint32Array }], fixed: Uint8Array }`.
fn arrays_object(a: smoothlab::io::MeshArrays) -> Result<JsValue, JsError> {
    let cells = js_sys::Array::new();
    for b in &a.cells {
        cells.push(&object(&[
            ("vtk_type", JsValue::from(b.vtk_type)),
            ("per_cell", JsValue::from(b.per_cell as u32)),
            ("nodes", js_sys::Uint32Array::from(&b.nodes[..]).into()),
        ])?);
    }
    let fixed: Vec<u8> = a.fixed.iter().map(|&f| u8::from(f)).collect();
    object(&[
        ("dim", JsValue::from(a.dim as u32)),
        ("points", js_sys::Float64Array::from(&a.points[..]).into()),
        ("cells", cells.into()),
        ("fixed", js_sys::Uint8Array::from(&fixed[..]).into()),
    ])
}

fn pixels(pm: tiny_skia::Pixmap) -> JsValue {
    js_sys::Uint8Array::from(pm.data()).into()
}

/// Both sides' pictures (`None`: not sent again, `null` to the page) as the page's frame:
/// `{ a, b, render_ms: [a, b], copy_ms, colour_bar }`, `copy_ms` the time the pixels took
/// to copy out of the wasm memory.
fn frame_object(pictures: [Option<tiny_skia::Pixmap>; 2], render_ms: [f64; 2], colour_bar: bool) -> Result<JsValue, JsError> {
    let t0 = now_ms();
    let [a, b] = pictures.map(|p| p.map_or(JsValue::NULL, pixels));
    let copy_ms = now_ms() - t0;
    object(&[
        ("a", a),
        ("b", b),
        ("render_ms", to_js(&render_ms)?),
        ("copy_ms", JsValue::from_f64(copy_ms)),
        ("colour_bar", JsValue::from_bool(colour_bar)),
    ])
}

/// A canvas of `w × h` CSS pixels at ratio `dpr` in device pixels, the ratio checked.
fn css_canvas(w: u32, h: u32, dpr: f32) -> Result<Canvas, JsError> {
    if !(dpr.is_finite() && dpr > 0.0 && dpr <= 4.0) {
        return Err(JsError::new(&format!("a pixel ratio of {dpr}: give one above 0 and at most 4")));
    }
    Ok(Canvas { w: ((w as f32) * dpr).round() as u32, h: ((h as f32) * dpr).round() as u32, dpr })
}

fn sample(name: &str) -> Result<Sample, JsError> {
    serde_wasm_bindgen::from_value(JsValue::from_str(name)).map_err(|_| JsError::new(&format!("no sample named '{name}'")))
}
