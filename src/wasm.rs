//! `#[wasm_bindgen]` exports: each converts its arguments, calls [`crate::lab`]
//! or the core, and converts the answer (serde-wasm-bindgen for records, `Vec<u8>` for
//! pixels). Core errors become `JsError`s carrying the core's message.

use std::sync::Mutex;

use serde::Serialize;
use wasm_bindgen::prelude::*;

use crate::lab::{self as playground, Settings, Side};
use crate::lab::sample::Sample;
use crate::lab::views::Canvas;
use crate::io::{self, Format};
use glam::DVec2;

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
    to_js(&list)
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
    serde_wasm_bindgen::from_value(JsValue::from_str(s))
        .map_err(|_| JsError::new(&format!("no panel '{s}': use old or new")))
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
        js_sys::Reflect::set(&o, &JsValue::from_str(k), v)
            .map_err(|_| JsError::new("cannot build the result object"))?;
    }
    Ok(o.into())
}

/// Pixels for a canvas `ImageData` (opaque, so straight RGBA).
fn pixels(pm: tiny_skia::Pixmap) -> JsValue {
    js_sys::Uint8Array::from(pm.data()).into()
}

fn canvas(w: u32, h: u32, dpr: f32) -> Canvas {
    Canvas { w, h, dpr }
}

/// The page's state: one opaque handle (see [`playground::Playground`]), with the
/// canvas the meshes were last drawn on (pointer positions map through its view) and
/// the node the user chose.
#[wasm_bindgen]
pub struct Playground {
    inner: playground::Playground,
    canvas: Option<Canvas>,
    node: Option<usize>,
}

impl Playground {
    fn wrap(inner: playground::Playground) -> Playground {
        Playground { inner, canvas: None, node: None }
    }
    fn view(&self) -> Result<crate::render::View, JsError> {
        let c = self.canvas.ok_or_else(|| JsError::new("the mesh has not been drawn yet"))?;
        Ok(self.inner.panel_view(c))
    }
}

#[wasm_bindgen]
impl Playground {
    /// A playground on a generated sample, by its gallery name (`plate-tri-tangled`, …).
    #[wasm_bindgen(js_name = fromSample)]
    pub fn from_sample(name: &str) -> Result<Playground, JsError> {
        let sample: Sample = serde_wasm_bindgen::from_value(JsValue::from_str(name))
            .map_err(|_| JsError::new(&format!("no sample named '{name}'")))?;
        Ok(Playground::wrap(playground::Playground::new(sample.generate()?)?))
    }

    /// A playground on the bytes of a mesh file called `name` (.msh, .vtk, .obj, .off).
    #[wasm_bindgen(js_name = fromBytes)]
    pub fn from_bytes(bytes: &[u8], name: &str) -> Result<Playground, JsError> {
        Ok(Playground::wrap(playground::Playground::new(io::read_bytes(bytes, name)?)?))
    }

    /// A playground on a Triangle mesh: the texts of its `.node` and `.ele` files.
    #[wasm_bindgen(js_name = fromTriangle)]
    pub fn from_triangle(node: &str, ele: &str) -> Result<Playground, JsError> {
        Ok(Playground::wrap(playground::Playground::new(io::read_triangle(node, ele)?)?))
    }

    /// The shared controls: `{ strategy, threshold_deg, order, max_iter }`.
    #[wasm_bindgen(js_name = setSettings)]
    pub fn set_settings(&mut self, settings: JsValue) -> Result<(), JsError> {
        let s: Settings =
            serde_wasm_bindgen::from_value(settings).map_err(|e| JsError::new(&format!("settings: {e}")))?;
        Ok(self.inner.set_settings(s)?)
    }

    /// One smoothing pass on both panels; returns their pass records `[old, new]`.
    pub fn step(&mut self) -> Result<JsValue, JsError> {
        to_js(&self.inner.step(&now_ms))
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
        to_js(&self.inner.stats(side(panel)?))
    }

    /// Both panels back to the mesh as loaded.
    pub fn reset(&mut self) {
        self.inner.reset();
    }

    /// Draws both panels' meshes on canvases of `w × h` device pixels at ratio `dpr`:
    /// `{ old, new }` RGBA pixels. The chosen node is highlighted with its star.
    pub fn frame(&mut self, w: u32, h: u32, dpr: f32) -> Result<JsValue, JsError> {
        let c = canvas(w, h, dpr);
        let old = self.inner.render_panel(Side::Old, c, self.node)?;
        let new = self.inner.render_panel(Side::New, c, self.node)?;
        self.canvas = Some(c);
        object(&[("old", pixels(old)), ("new", pixels(new))])
    }

    /// The free node of a panel nearest to the CSS pixel `(x, y)` of the last frame, if
    /// one is within the pick radius.
    #[wasm_bindgen(js_name = pickNode)]
    pub fn pick_node(&self, panel: &str, x: f64, y: f64) -> Result<Option<u32>, JsError> {
        let view = self.view()?;
        Ok(self.inner.pick_free_node(side(panel)?, &view, DVec2::new(x, y)).map(|n| n as u32))
    }

    /// Moves a free node to the CSS pixel `(x, y)` of the last frame, on both panels.
    #[wasm_bindgen(js_name = dragNode)]
    pub fn drag_node(&mut self, node: u32, x: f64, y: f64) -> Result<(), JsError> {
        let to = self.view()?.css_to_world(DVec2::new(x, y));
        Ok(self.inner.move_node(node as usize, to)?)
    }

    /// Chooses the node whose star is highlighted and whose level sets are shown (`undefined`: none).
    #[wasm_bindgen(js_name = selectNode)]
    pub fn select_node(&mut self, node: Option<u32>) -> Result<(), JsError> {
        if let Some(n) = node {
            let m = self.inner.original();
            if n as usize >= m.node_count() || !m.is_free(n as usize) {
                return Err(JsError::new(&format!(
                    "node {n} cannot be chosen: pick a free (interior) node, 0 to {}",
                    m.node_count().saturating_sub(1)
                )));
            }
        }
        self.node = node.map(|n| n as usize);
        Ok(())
    }

    /// The chosen node's level sets (old, new: `w × h`), its solve history chart
    /// (`cw × ch`) and a one-line summary: `{ level_old, level_new, chart, summary }`.
    #[wasm_bindgen(js_name = nodeView)]
    pub fn node_view(&self, w: u32, h: u32, cw: u32, ch: u32, dpr: f32) -> Result<JsValue, JsError> {
        let node = self.node.ok_or_else(|| JsError::new("no node is chosen"))?;
        let ([lo, ln, chart], summary) = self.inner.render_node_view(node, canvas(w, h, dpr), canvas(cw, ch, dpr))?;
        object(&[
            ("level_old", pixels(lo)),
            ("level_new", pixels(ln)),
            ("chart", pixels(chart)),
            ("summary", JsValue::from_str(&summary.text())),
            ("solve", to_js(&summary)?),
        ])
    }

    /// The per-pass chart (`w × h`) and both angle histograms (`hw × hh`):
    /// `{ pass, hist_old, hist_new, records }`.
    pub fn charts(&self, w: u32, h: u32, hw: u32, hh: u32, dpr: f32) -> Result<JsValue, JsError> {
        let hc = canvas(hw, hh, dpr);
        object(&[
            ("pass", pixels(self.inner.render_pass_chart(canvas(w, h, dpr))?)),
            ("hist_old", pixels(self.inner.render_histogram(Side::Old, hc)?)),
            ("hist_new", pixels(self.inner.render_histogram(Side::New, hc)?)),
        ])
    }
}
