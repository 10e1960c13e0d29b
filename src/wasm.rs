//! `#[wasm_bindgen]` exports: each converts its arguments, calls [`crate::lab`]
//! or the core, and converts the answer (serde-wasm-bindgen for records, `Vec<u8>` for
//! pixels). Core errors become `JsError`s carrying the core's message.

use std::sync::Mutex;

use serde::Serialize;
use wasm_bindgen::prelude::*;

use crate::io::{self, Format};
use crate::lab::sample::Sample;
use crate::lab::surface as surface_lab;
use crate::lab::views::Canvas;
use crate::lab::volume as volume_lab;
use crate::lab::{self as playground, Settings, Side, SideSweep};
use crate::permalink;
use crate::render::Theme;
use crate::model::Model;
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

/// The figures tour's menu: `[{ name, source }]` ([`crate::lab::tour`]).
#[wasm_bindgen(js_name = tourFigures)]
pub fn tour_figures() -> Result<JsValue, JsError> {
    to_js(&crate::lab::tour::entries())
}

/// One figure of the tour: `{ name, index, count, prev, next, source, caption, hash, view,
/// run, look, claim, measured, rows }` (`hash` the playground state to open).
#[wasm_bindgen(js_name = tourCard)]
pub fn tour_card(name: &str) -> Result<JsValue, JsError> {
    let (i, fig) = crate::lab::tour::find(name)?;
    to_js(&fig.card(i)?)
}

/// A figure's picture, `w × h` CSS pixels at ratio `dpr`, in the dark or the light theme
/// with labels of at least `label_px` CSS pixels (as [`Playground::set_theme`]):
/// `{ pixels, w, h }` (device pixels).
#[wasm_bindgen(js_name = tourPicture)]
pub fn tour_picture(name: &str, w: u32, h: u32, dpr: f32, dark: bool, label_px: f32) -> Result<JsValue, JsError> {
    if !(dpr.is_finite() && dpr > 0.0 && dpr <= 4.0) {
        return Err(JsError::new(&format!("a pixel ratio of {dpr}: give one above 0 and at most 4")));
    }
    let c = Canvas { w: ((w as f32) * dpr).round() as u32, h: ((h as f32) * dpr).round() as u32, dpr };
    let pm = crate::lab::tour::pictures::render(name, c, &Theme::for_page(dark, label_px))?;
    let (pw, ph) = (pm.width(), pm.height());
    object(&[("pixels", pixels(pm)), ("w", JsValue::from(pw)), ("h", JsValue::from(ph))])
}

/// Where a figure's picture, drawn as [`tour_picture`] draws it, put its plots, legends
/// and marks: `{ w, h, regions: [{ kind: "plot" | "legend" | "mark", x, y, w, h, rgb }] }`,
/// device pixels ([`crate::render::layout`]) — for the page's tests, which check that no
/// legend lies over the data and that the marks a figure's text promises are drawn.
#[wasm_bindgen(js_name = tourPictureLayout)]
pub fn tour_picture_layout(name: &str, w: u32, h: u32, dpr: f32, dark: bool, label_px: f32) -> Result<JsValue, JsError> {
    if !(dpr.is_finite() && dpr > 0.0 && dpr <= 4.0) {
        return Err(JsError::new(&format!("a pixel ratio of {dpr}: give one above 0 and at most 4")));
    }
    let c = Canvas { w: ((w as f32) * dpr).round() as u32, h: ((h as f32) * dpr).round() as u32, dpr };
    let (pm, regions) = crate::lab::tour::pictures::render_with_layout(name, c, &Theme::for_page(dark, label_px))?;
    #[derive(serde::Serialize)]
    struct Layout {
        w: u32,
        h: u32,
        regions: Vec<crate::render::layout::Region>,
    }
    to_js(&Layout { w: pm.width(), h: pm.height(), regions })
}

/// Row `i` of Freitag's Table 1, smoothed now: `{ method, min_angle_deg, max_angle_deg,
/// laplacian_moves, optimization_calls, reproduction_min, reproduction_max, paper }`.
#[wasm_bindgen(js_name = tourRow)]
pub fn tour_row(i: u32) -> Result<JsValue, JsError> {
    to_js(&crate::lab::tour::pictures::freitag_row(i as usize)?)
}

/// Row `i` of figure `name`'s live table (Freitag's Table 1 or 2), smoothed now:
/// `{ method, cells }`, the cells under the card's `columns`.
#[wasm_bindgen(js_name = tourTableRow)]
pub fn tour_table_row(name: &str, i: u32) -> Result<JsValue, JsError> {
    to_js(&crate::lab::tour::pictures::table_row(name, i as usize)?)
}

/// The default size of a figure's picture, CSS pixels: `[w, h]`.
#[wasm_bindgen(js_name = tourPictureSize)]
pub fn tour_picture_size(name: &str) -> Result<JsValue, JsError> {
    let (_, fig) = crate::lab::tour::find(name)?;
    to_js(&crate::lab::tour::pictures::default_size(fig.name))
}

/// Reads a permalink hash (`#sample=…&passes=…`) with [`crate::permalink::decode`]: the
/// [`PageState`](crate::permalink::PageState) as it is, `sample`/`node` null when absent,
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
/// (fields left out take their defaults), with [`crate::permalink::encode`] after checking
/// every value as the decoder would.
#[wasm_bindgen(js_name = encodePermalink)]
pub fn encode_permalink(state: JsValue) -> Result<String, JsError> {
    let state: permalink::PageState =
        serde_wasm_bindgen::from_value(state).map_err(|e| JsError::new(&format!("permalink: {e}")))?;
    state.validate()?;
    Ok(permalink::encode(&state))
}

/// The page's controls: their ranges, defaults and labels, and which strategy uses which
/// control (see [`crate::limits::page_controls`]): the page builds its inputs from this.
#[wasm_bindgen]
pub fn controls() -> Result<JsValue, JsError> {
    to_js(&crate::limits::page_controls())
}

/// Checks the text of one control (by its permalink key) as the permalink would read it:
/// `null` when it is valid, else a message for people with the allowed range in words.
#[wasm_bindgen(js_name = checkControl)]
pub fn check_control(key: &str, text: &str) -> Option<String> {
    permalink::check_control(key, text).err()
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

/// The Perturb controls checked as the permalink checks them: the seed as a number.
fn perturb_seed(amount: f64, seed: &str) -> Result<u64, JsError> {
    permalink::check_control("seed", seed).map_err(|e| JsError::new(&e))?;
    permalink::check_control("tangle", &amount.to_string()).map_err(|e| JsError::new(&e))?;
    seed.trim().parse().map_err(|_| JsError::new("Seed: enter a whole number"))
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

/// Pixels for a canvas `ImageData` (opaque, so straight RGBA): one copy out of the wasm
/// memory into a buffer of its own, which the worker then moves (not copies) to the page.
fn pixels(pm: tiny_skia::Pixmap) -> JsValue {
    js_sys::Uint8Array::from(pm.data()).into()
}

fn sample(name: &str) -> Result<Sample, JsError> {
    serde_wasm_bindgen::from_value(JsValue::from_str(name))
        .map_err(|_| JsError::new(&format!("no sample named '{name}'")))
}

/// The handle for a model: a [`Playground`] for a planar mesh, a [`SurfaceLab`] for a surface.
fn open(model: Model) -> Result<JsValue, JsError> {
    Ok(match model {
        Model::Planar(m) => Playground::wrap(playground::Playground::new(m)?).into(),
        Model::Surface(s) => SurfaceLab { inner: surface_lab::SurfaceLab::new(s)?, canvas: None }.into(),
        Model::Volume(v) => VolumeLab { inner: volume_lab::VolumeLab::new(v)? }.into(),
    })
}

/// A gallery sample by its name: a `Playground`, or a `SurfaceLab` for a surface sample.
#[wasm_bindgen(js_name = openSample)]
pub fn open_sample(name: &str) -> Result<JsValue, JsError> {
    open(sample(name)?.model()?)
}

/// The bytes of a mesh file called `name` (.msh, .vtk, .obj, .off): a `Playground` for a
/// planar mesh, a `SurfaceLab` for a surface in 3D.
#[wasm_bindgen(js_name = openBytes)]
pub fn open_bytes(bytes: &[u8], name: &str) -> Result<JsValue, JsError> {
    open(io::read_model_bytes(bytes, name)?)
}

/// What a mesh panel last sent to the page: its positions' version, the canvas, the
/// highlighted node and the zoom. The same again is not drawn nor sent again.
type Shown = (u64, Canvas, Option<usize>, crate::render::ZoomPan);

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
    shown: [Option<Shown>; 2],
    /// The canvas the level sets were last drawn on (pointer positions map through it).
    level_canvas: Option<Canvas>,
}

impl Playground {
    /// The chosen node and the canvas its level sets were last drawn on.
    fn level_drawn(&self) -> Result<(usize, Canvas), JsError> {
        let node = self.node.ok_or_else(|| JsError::new("no node is chosen"))?;
        let c = self.level_canvas.ok_or_else(|| JsError::new("the level sets have not been drawn yet"))?;
        Ok((node, c))
    }
    fn undo_state(&self, node: Option<usize>) -> Result<JsValue, JsError> {
        let node = node.map_or(JsValue::UNDEFINED, |n| JsValue::from(n as u32));
        let next = self.inner.undo_node().map_or(JsValue::UNDEFINED, |n| JsValue::from(n as u32));
        object(&[("node", node), ("next", next), ("depth", JsValue::from(self.inner.undo_depth() as u32))])
    }
    fn wrap(inner: playground::Playground) -> Playground {
        Playground { inner, canvas: None, node: None, shown: [None, None], level_canvas: None }
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
        Ok(Playground::wrap(playground::Playground::new(sample(name)?.generate()?)?))
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

    /// The shared controls and what each side smooths with: `{ strategy, threshold_deg,
    /// order, max_iter, compare: [{ objective, penalty }, { objective, penalty }] }`.
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

    /// Starts a pass to be run in slices by [`continue_pass`](Self::continue_pass)
    /// (the same result as [`step`](Self::step)); a pass in progress is abandoned.
    #[wasm_bindgen(js_name = beginPass)]
    pub fn begin_pass(&mut self) {
        self.inner.begin_pass();
    }

    /// Runs the pass for about `budget_ms` milliseconds: `{ done, fraction, side, stage,
    /// visits, planned, records }` (`records` `[old, new]` once done).
    #[wasm_bindgen(js_name = continuePass)]
    pub fn continue_pass(&mut self, budget_ms: f64) -> Result<JsValue, JsError> {
        if budget_ms.is_nan() || budget_ms <= 0.0 {
            return Err(JsError::new(&format!("a pass slice of {budget_ms} ms: give a positive budget")));
        }
        to_js(&self.inner.continue_pass(&now_ms, budget_ms)?)
    }

    /// The number of nodes of the mesh.
    #[wasm_bindgen(js_name = nodeCount)]
    pub fn node_count(&self) -> usize {
        self.inner.topology().node_count()
    }

    /// Starts a pass split with a second engine (another worker, on the same mesh and
    /// settings), which sweeps the old panel (`beginSweep`); run it with `continuePass`
    /// (stage `wait` until `adoptSweep` hands the sweep over). The same result as `step`.
    #[wasm_bindgen(js_name = beginSplitPass)]
    pub fn begin_split_pass(&mut self) {
        self.inner.begin_split_pass();
    }

    /// The positions of panel `side` (`old` or `new`), x and y interleaved.
    #[wasm_bindgen(js_name = panelPositions)]
    pub fn panel_positions(&self, side: &str) -> Result<js_sys::Float64Array, JsError> {
        Ok(js_sys::Float64Array::from(&self.inner.panel_positions(self::side(side)?)[..]))
    }

    /// Starts the sweep of panel `side` alone from `nodes` (the other engine's positions,
    /// x and y interleaved), for a split pass; run it with `continuePass`, then `takeSweep`.
    #[wasm_bindgen(js_name = beginSweep)]
    pub fn begin_sweep(&mut self, side: &str, nodes: &[f64]) -> Result<(), JsError> {
        Ok(self.inner.begin_sweep(self::side(side)?, nodes)?)
    }

    /// The completed sweep: `{ nodes: Float64Array, sweep: { counts, sweep_ms } }`, or
    /// undefined when there is none.
    #[wasm_bindgen(js_name = takeSweep)]
    pub fn take_sweep(&mut self) -> Result<JsValue, JsError> {
        match self.inner.take_sweep() {
            Some((nodes, sweep)) => {
                object(&[("nodes", js_sys::Float64Array::from(&nodes[..]).into()), ("sweep", to_js(&sweep)?)])
            }
            None => Ok(JsValue::UNDEFINED),
        }
    }

    /// Hands the old panel's sweep (`takeSweep`'s `nodes` and `sweep`, from the other
    /// engine) to the split pass in progress.
    #[wasm_bindgen(js_name = adoptSweep)]
    pub fn adopt_sweep(&mut self, nodes: &[f64], sweep: JsValue) -> Result<(), JsError> {
        let sweep: SideSweep =
            serde_wasm_bindgen::from_value(sweep).map_err(|e| JsError::new(&format!("a sweep's record: {e}")))?;
        Ok(self.inner.adopt_sweep(nodes, sweep)?)
    }

    /// Abandons the pass in progress: both panels as before it.
    #[wasm_bindgen(js_name = abortPass)]
    pub fn abort_pass(&mut self) {
        self.inner.abort_pass();
    }

    /// Perturbs the original mesh (`amount` mean edge lengths, seeded) and resets both
    /// panels. The seed is the control's text (a whole number up to 2^64 − 1, beyond what
    /// a JS number holds exactly), checked as the permalink checks it.
    pub fn perturb(&mut self, amount: f64, seed: &str) -> Result<(), JsError> {
        let seed = perturb_seed(amount, seed)?;
        Ok(self.inner.perturb(amount, seed)?)
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

    /// The statistics table of one panel (`old` or `new`): nodes, elements, inverted,
    /// min/max angle, min quality and the work of the passes.
    pub fn stats(&self, panel: &str) -> Result<JsValue, JsError> {
        to_js(&self.inner.table(side(panel)?))
    }

    /// Both panels back to the mesh as loaded.
    pub fn reset(&mut self) {
        self.inner.reset();
    }

    /// Draws both panels' meshes on canvases of `w × h` device pixels at ratio `dpr`:
    /// `{ old, new, render_ms: [old, new], copy_ms, colour_bar }`, RGBA pixels of each
    /// panel, `colour_bar` whether the pictures carry the colour bar (false: the canvas is
    /// too small for it, show the scale beside it), or
    /// `null` for a panel whose last picture sent shows the same positions, canvas and
    /// highlight (unless `force`). The chosen node is highlighted with its star.
    pub fn frame(&mut self, w: u32, h: u32, dpr: f32, force: bool) -> Result<JsValue, JsError> {
        let c = canvas(w, h, dpr);
        let mut out = Vec::new();
        let mut render_ms = [0.0; 2];
        let mut copy_ms = 0.0;
        // equal versions, equal positions: after a load or a reset the new panel's picture
        // is the old one's, drawn once
        let same = self.inner.version(Side::Old) == self.inner.version(Side::New);
        let mut old_picture = None;
        for s in [Side::Old, Side::New] {
            let i = s as usize;
            let key = (self.inner.version(s), c, self.node, self.inner.zoom());
            if !force && self.shown[i] == Some(key) {
                out.push(JsValue::NULL);
                continue;
            }
            let t0 = now_ms();
            let pm = match old_picture.take() {
                Some(pm) => pm,
                None => self.inner.render_panel(s, c, self.node)?,
            };
            if s == Side::Old && same {
                old_picture = Some(pm.clone());
            }
            let t1 = now_ms();
            out.push(pixels(pm));
            copy_ms += now_ms() - t1;
            render_ms[i] = t1 - t0;
            self.shown[i] = Some(key);
        }
        self.canvas = Some(c);
        let new = out.pop().unwrap_or(JsValue::NULL);
        let old = out.pop().unwrap_or(JsValue::NULL);
        object(&[
            ("old", old),
            ("new", new),
            ("render_ms", to_js(&render_ms)?),
            ("copy_ms", JsValue::from_f64(copy_ms)),
            ("colour_bar", JsValue::from_bool(self.inner.panel_colour_bar(c))),
        ])
    }

    /// Draws every later picture (meshes, level sets, charts, histograms, the figure) in
    /// the dark (projector) or the light theme, every label at least `label_px` CSS
    /// pixels (0: each label its own size); forgets the frames sent, so the next
    /// [`frame`](Self::frame) draws both panels.
    #[wasm_bindgen(js_name = setTheme)]
    pub fn set_theme(&mut self, dark: bool, label_px: f32) {
        self.inner.set_theme(Theme::for_page(dark, label_px));
        self.shown = [None, None];
    }

    /// Forgets what was sent: the next [`frame`](Self::frame) draws both panels (after
    /// the page cleared or replaced its canvases).
    #[wasm_bindgen(js_name = forgetFrames)]
    pub fn forget_frames(&mut self) {
        self.shown = [None, None];
    }

    /// The node of a panel nearest to the CSS pixel `(x, y)` of the last frame within
    /// `radius` CSS pixels: `{ node, nearest, message }` (see [`crate::lab::pick::Pick`]).
    #[wasm_bindgen(js_name = pickNode)]
    pub fn pick_node(&self, panel: &str, x: f64, y: f64, radius: f64) -> Result<JsValue, JsError> {
        let view = self.view()?;
        let radius = if radius.is_finite() && radius > 0.0 { radius.min(64.0) } else { crate::render::PICK_RADIUS };
        to_js(&self.inner.pick(side(panel)?, &view, DVec2::new(x, y), radius))
    }

    /// Moves a free node to the CSS pixel `(x, y)` of the last frame, on both panels.
    #[wasm_bindgen(js_name = dragNode)]
    pub fn drag_node(&mut self, node: u32, x: f64, y: f64) -> Result<(), JsError> {
        let to = self.view()?.css_to_world(DVec2::new(x, y));
        Ok(self.inner.move_node(node as usize, to)?)
    }

    /// Moves the chosen node by `(dx, dy)` CSS pixels of the last frame from where it is on
    /// `panel`, on both panels (the arrow keys), undoably.
    #[wasm_bindgen(js_name = nudgeNode)]
    pub fn nudge_node(&mut self, panel: &str, dx: f64, dy: f64) -> Result<(), JsError> {
        let node = self.node.ok_or_else(|| JsError::new("no node is chosen: click a free node first"))?;
        let view = self.view()?;
        let from = self.inner.panel(side(panel)?).mesh.nodes()[node];
        let to = from + DVec2::new(dx, -dy) / view.scale();
        self.inner.remember_before_move(node)?;
        Ok(self.inner.move_node(node, to)?)
    }

    /// Chooses the node whose star is highlighted and whose level sets are shown (`undefined`: none).
    #[wasm_bindgen(js_name = selectNode)]
    pub fn select_node(&mut self, node: Option<u32>) -> Result<(), JsError> {
        if let Some(n) = node {
            if let Some(why) = crate::lab::pick::why_not_free(self.inner.topology(), n as usize) {
                return Err(JsError::new(&format!("Node {n} cannot be chosen: {why}.")));
            }
        }
        self.node = node.map(|n| n as usize);
        Ok(())
    }

    /// The chosen node's level sets (old, new: `w × h`), its solve history chart
    /// (`cw × ch`) and a one-line summary: `{ level_old, level_new, chart, summary }`.
    #[wasm_bindgen(js_name = nodeView)]
    pub fn node_view(&mut self, w: u32, h: u32, cw: u32, ch: u32, dpr: f32) -> Result<JsValue, JsError> {
        let node = self.node.ok_or_else(|| JsError::new("no node is chosen"))?;
        self.level_canvas = Some(canvas(w, h, dpr));
        let ([lo, ln, chart], summary) = self.inner.render_node_view(node, canvas(w, h, dpr), canvas(cw, ch, dpr))?;
        object(&[
            ("level_old", pixels(lo)),
            ("level_new", pixels(ln)),
            ("chart", pixels(chart)),
            ("summary", JsValue::from_str(&summary.text())),
            ("solve", to_js(&summary)?),
        ])
    }

    /// The free node with the worst star (on B's mesh), or `undefined` when none is free.
    #[wasm_bindgen(js_name = worstFreeNode)]
    pub fn worst_free_node(&self) -> Option<u32> {
        crate::lab::pick::worst_free_node(&self.inner.panel(Side::New).mesh).map(|n| n as u32)
    }

    /// Magnifies both meshes `factor` times about the CSS pixel `(x, y)` of the last frame.
    #[wasm_bindgen(js_name = zoomMeshes)]
    pub fn zoom_meshes(&mut self, x: f64, y: f64, factor: f64) -> Result<(), JsError> {
        let c = self.canvas.ok_or_else(|| JsError::new("the mesh has not been drawn yet"))?;
        self.inner.zoom_meshes_at(c, DVec2::new(x, y), factor);
        Ok(())
    }

    /// Moves both meshes' pictures by `(dx, dy)` CSS pixels.
    #[wasm_bindgen(js_name = panMeshes)]
    pub fn pan_meshes(&mut self, dx: f64, dy: f64) {
        self.inner.pan_meshes(DVec2::new(dx, dy));
    }

    /// Magnifies both level sets `factor` times about the CSS pixel `(x, y)` of `panel`'s
    /// level set as last drawn.
    #[wasm_bindgen(js_name = zoomLevelSets)]
    pub fn zoom_level_sets(&mut self, panel: &str, x: f64, y: f64, factor: f64) -> Result<(), JsError> {
        let (node, c) = self.level_drawn()?;
        self.inner.zoom_level_sets_at(side(panel)?, node, c, DVec2::new(x, y), factor);
        Ok(())
    }

    /// Moves both level sets by `(dx, dy)` CSS pixels of `panel`'s level set as last drawn.
    #[wasm_bindgen(js_name = panLevelSets)]
    pub fn pan_level_sets(&mut self, panel: &str, dx: f64, dy: f64) -> Result<(), JsError> {
        let (node, c) = self.level_drawn()?;
        self.inner.pan_level_sets(side(panel)?, node, c, DVec2::new(dx, dy));
        Ok(())
    }

    /// The meshes and the level sets as fitted again.
    #[wasm_bindgen(js_name = resetZoom)]
    pub fn reset_zoom(&mut self) {
        self.inner.reset_zoom();
    }

    /// Keeps the positions round `node` for [`undo`](Self::undo) (a drag, as it starts).
    #[wasm_bindgen(js_name = rememberBeforeMove)]
    pub fn remember_before_move(&mut self, node: u32) -> Result<(), JsError> {
        Ok(self.inner.remember_before_move(node as usize)?)
    }

    /// Takes back the latest move: `{ node, depth }` (`node` undefined when there was none;
    /// `depth`: moves left to undo).
    pub fn undo(&mut self) -> Result<JsValue, JsError> {
        let node = self.inner.undo();
        self.undo_state(node)
    }

    /// `{ node, depth }`: the node the next undo moves back, and how many moves it can take back.
    #[wasm_bindgen(js_name = undoState)]
    pub fn undo_info(&self) -> Result<JsValue, JsError> {
        self.undo_state(self.inner.undo_node())
    }

    /// One solver call on the chosen node on each side, which then moves to what it
    /// found: the node view of that call (as [`node_view`](Self::node_view), drawn
    /// before the move, so its history is the call's).
    #[wasm_bindgen(js_name = smoothNode)]
    pub fn smooth_node(&mut self, w: u32, h: u32, cw: u32, ch: u32, dpr: f32) -> Result<JsValue, JsError> {
        let node = self.node.ok_or_else(|| JsError::new("no node is chosen: click a free node first"))?;
        let view = self.node_view(w, h, cw, ch, dpr)?;
        self.inner.smooth_one_node(node)?;
        Ok(view)
    }

    /// The figure for slides: A | B with titles, the colour bar and statistics
    /// (`smoothlab render --view compare`), `w × h` CSS pixels at ratio `dpr`:
    /// `{ pixels, w, h }` (device pixels).
    pub fn figure(&self, w: u32, h: u32, dpr: f32) -> Result<JsValue, JsError> {
        if !(dpr.is_finite() && dpr > 0.0 && dpr <= 4.0) {
            return Err(JsError::new(&format!("a pixel ratio of {dpr}: give one above 0 and at most 4")));
        }
        let c = canvas(((w as f32) * dpr).round() as u32, ((h as f32) * dpr).round() as u32, dpr);
        let pm = self.inner.render_figure(c)?;
        object(&[("pixels", pixels(pm)), ("w", JsValue::from(c.w)), ("h", JsValue::from(c.h))])
    }

    /// The per-pass chart (`w × h`) and both angle histograms (`hw × hh`, on one scale,
    /// logarithmic when `log_y`), with both statistics tables (measured in full now):
    /// `{ pass, hist_old, hist_new, stats: { old, new } }`.
    pub fn charts(&self, w: u32, h: u32, hw: u32, hh: u32, dpr: f32, log_y: bool) -> Result<JsValue, JsError> {
        let hc = canvas(hw, hh, dpr);
        let pass = pixels(self.inner.render_pass_chart(canvas(w, h, dpr))?);
        let hist_old = pixels(self.inner.render_histogram(Side::Old, hc, log_y)?);
        let hist_new = pixels(self.inner.render_histogram(Side::New, hc, log_y)?);
        // after the histograms: the full statistics are at hand for the tables' detail
        let stats = object(&[("old", self.stats("old")?), ("new", self.stats("new")?)])?;
        object(&[("pass", pass), ("hist_old", hist_old), ("hist_new", hist_new), ("stats", stats)])
    }
}

/// Both sides drawn by `render`: `{ old, new, render_ms: [old, new], copy_ms, colour_bar }`
/// (RGBA pixels; `colour_bar` whether they carry the colour bar), the 3D views' frame.
fn both_sides(render: impl Fn(Side) -> crate::Result<tiny_skia::Pixmap>, colour_bar: bool) -> Result<JsValue, JsError> {
    let mut out = Vec::new();
    let (mut render_ms, mut copy_ms) = ([0.0; 2], 0.0);
    for s in Side::BOTH {
        let t0 = now_ms();
        let pm = render(s)?;
        let t1 = now_ms();
        out.push(pixels(pm));
        copy_ms += now_ms() - t1;
        render_ms[s as usize] = t1 - t0;
    }
    let new = out.pop().unwrap_or(JsValue::NULL);
    let old = out.pop().unwrap_or(JsValue::NULL);
    object(&[
        ("old", old),
        ("new", new),
        ("render_ms", to_js(&render_ms)?),
        ("copy_ms", JsValue::from_f64(copy_ms)),
        ("colour_bar", JsValue::from_bool(colour_bar)),
    ])
}

/// The page's state for a surface in 3D: one opaque handle (see
/// [`surface_lab::SurfaceLab`]), with the canvas its sides were last drawn on.
#[wasm_bindgen]
pub struct SurfaceLab {
    inner: surface_lab::SurfaceLab,
    canvas: Option<Canvas>,
}

#[wasm_bindgen]
impl SurfaceLab {
    /// As [`Playground::set_settings`].
    #[wasm_bindgen(js_name = setSettings)]
    pub fn set_settings(&mut self, settings: JsValue) -> Result<(), JsError> {
        let s: Settings =
            serde_wasm_bindgen::from_value(settings).map_err(|e| JsError::new(&format!("settings: {e}")))?;
        Ok(self.inner.set_settings(s)?)
    }

    /// One smoothing pass on both sides; returns their pass records `[old, new]`.
    pub fn step(&mut self) -> Result<JsValue, JsError> {
        to_js(&self.inner.step(&now_ms))
    }

    /// Both sides back to the surface as loaded.
    pub fn reset(&mut self) {
        self.inner.reset();
    }

    /// Perturbs the surface as loaded in its tangent planes (as [`Playground::perturb`]).
    pub fn perturb(&mut self, amount: f64, seed: &str) -> Result<(), JsError> {
        let seed = perturb_seed(amount, seed)?;
        Ok(self.inner.perturb(amount, seed)?)
    }

    /// A side's surface as the text of a `msh`, `vtk`, `obj` or `off` file.
    #[wasm_bindgen(js_name = exportMesh)]
    pub fn export_mesh(&self, panel: &str, format: &str) -> Result<String, JsError> {
        let f = match Format::from_name(&format!("mesh.{format}")) {
            Some(f) if f != Format::Triangle => f,
            _ => return Err(JsError::new(&format!("cannot export a surface as '{format}': use msh, vtk, obj or off"))),
        };
        Ok(self.inner.export(side(panel)?, f)?)
    }

    /// The statistics table of one side (`old` or `new`), as [`Playground::stats`], with
    /// `max_distance_from_surface`.
    pub fn stats(&self, panel: &str) -> Result<JsValue, JsError> {
        to_js(&self.inner.table(side(panel)?))
    }

    /// Both sides drawn by the shared camera on canvases of `w × h` device pixels at
    /// ratio `dpr`: `{ old, new, render_ms: [old, new], copy_ms, colour_bar }` (RGBA pixels).
    pub fn frame(&mut self, w: u32, h: u32, dpr: f32) -> Result<JsValue, JsError> {
        let c = canvas(w, h, dpr);
        let f = both_sides(|s| Ok(self.inner.render(s, c)?.0), self.inner.colour_bar_shown(c))?;
        self.canvas = Some(c);
        Ok(f)
    }

    /// Turns the shared camera by a drag of `(dx, dy)` CSS pixels.
    pub fn orbit(&mut self, dx: f64, dy: f64) {
        self.inner.orbit(dx, dy);
    }

    /// Magnifies both views `factor` times (within the camera's range).
    pub fn zoom(&mut self, factor: f64) {
        self.inner.zoom(factor);
    }

    /// Draws every later picture in the dark (projector) or the light theme, every label
    /// at least `label_px` CSS pixels (as [`Playground::set_theme`]).
    #[wasm_bindgen(js_name = setTheme)]
    pub fn set_theme(&mut self, dark: bool, label_px: f32) {
        self.inner.set_theme(Theme::for_page(dark, label_px));
    }

    /// The camera as it starts.
    #[wasm_bindgen(js_name = resetZoom)]
    pub fn reset_zoom(&mut self) {
        self.inner.reset_camera();
    }

    /// Why the file's points were read as a surface (the node farthest off the plane the
    /// mesh would lie in, and how far), or `undefined` for a sample.
    #[wasm_bindgen(js_name = notPlanar)]
    pub fn not_planar(&self) -> Option<String> {
        self.inner.original().not_planar().map(str::to_string)
    }

    /// The shared camera: `{ yaw, pitch, zoom }` (degrees, degrees, factor).
    pub fn camera(&self) -> Result<JsValue, JsError> {
        let c = self.inner.camera();
        object(&[("yaw", c.yaw.into()), ("pitch", c.pitch.into()), ("zoom", c.zoom.into())])
    }

    /// The node of a side under the CSS pixel `(x, y)` of the last frame within `radius`
    /// CSS pixels (the near side of the surface winning), or `undefined`.
    #[wasm_bindgen(js_name = pickNode)]
    pub fn pick_node(&self, panel: &str, x: f64, y: f64, radius: f64) -> Result<Option<u32>, JsError> {
        let c = self.canvas.ok_or_else(|| JsError::new("the surface has not been drawn yet"))?;
        let radius = if radius.is_finite() && radius > 0.0 { radius.min(64.0) } else { crate::render::PICK_RADIUS };
        Ok(self.inner.pick(side(panel)?, c, DVec2::new(x, y), radius)?.map(|n| n as u32))
    }
}

/// The page's state for a tetrahedral mesh: one opaque handle (see
/// [`volume_lab::VolumeLab`]), with the surface lab's methods (the worker treats both as
/// the 3D view) and the cut plane's and the dihedral histograms'.
#[wasm_bindgen]
pub struct VolumeLab {
    inner: volume_lab::VolumeLab,
}

#[wasm_bindgen]
impl VolumeLab {
    /// As [`Playground::set_settings`] (each side's objective carried to tetrahedra).
    #[wasm_bindgen(js_name = setSettings)]
    pub fn set_settings(&mut self, settings: JsValue) -> Result<(), JsError> {
        let s: Settings =
            serde_wasm_bindgen::from_value(settings).map_err(|e| JsError::new(&format!("settings: {e}")))?;
        Ok(self.inner.set_settings(s)?)
    }

    /// One smoothing pass on both sides; returns their pass records `[old, new]`.
    pub fn step(&mut self) -> Result<JsValue, JsError> {
        to_js(&self.inner.step(&now_ms))
    }

    /// What the file's triangles and quads fixed that is not on the boundary, or
    /// `undefined`.
    #[wasm_bindgen(js_name = fileNote)]
    pub fn file_note(&self) -> Option<String> {
        self.inner.file_note()
    }

    /// Both sides back to the mesh as loaded.
    pub fn reset(&mut self) {
        self.inner.reset();
    }

    /// Moves the free nodes of the mesh as loaded at random (as [`Playground::perturb`]).
    pub fn perturb(&mut self, amount: f64, seed: &str) -> Result<(), JsError> {
        let seed = perturb_seed(amount, seed)?;
        Ok(self.inner.perturb(amount, seed)?)
    }

    /// A side's mesh as the text of a `msh` or `vtk` file.
    #[wasm_bindgen(js_name = exportMesh)]
    pub fn export_mesh(&self, panel: &str, format: &str) -> Result<String, JsError> {
        let f = match Format::from_name(&format!("mesh.{format}")) {
            Some(f @ (Format::Msh | Format::Vtk)) => f,
            _ => return Err(JsError::new(&format!("cannot export tetrahedra as '{format}': use msh or vtk"))),
        };
        Ok(self.inner.export(side(panel)?, f)?)
    }

    /// The statistics table of one side (`old` or `new`): dihedral angles, mean ratio.
    pub fn stats(&self, panel: &str) -> Result<JsValue, JsError> {
        to_js(&self.inner.table(side(panel)?))
    }

    /// Both sides cut and drawn by the shared camera on canvases of `w × h` device pixels
    /// at ratio `dpr`: `{ old, new, render_ms: [old, new], copy_ms, colour_bar }` (RGBA pixels).
    pub fn frame(&mut self, w: u32, h: u32, dpr: f32) -> Result<JsValue, JsError> {
        let c = canvas(w, h, dpr);
        both_sides(|s| Ok(self.inner.render(s, c)?.0), self.inner.colour_bar_shown(c))
    }

    /// Both sides' dihedral angle histograms beside the mesh as loaded, on canvases of
    /// `w × h` device pixels, the percentages on a logarithmic scale when `log_y`:
    /// `{ old, new }` (RGBA pixels).
    pub fn histograms(&self, w: u32, h: u32, dpr: f32, log_y: bool) -> Result<JsValue, JsError> {
        let c = canvas(w, h, dpr);
        let old = pixels(self.inner.render_histogram(Side::Old, c, log_y)?);
        let new = pixels(self.inner.render_histogram(Side::New, c, log_y)?);
        object(&[("old", old), ("new", new)])
    }

    /// Cuts both sides across `axis` (0, 1, 2: x, y, z) at the fraction `at` of the extent.
    #[wasm_bindgen(js_name = setCut)]
    pub fn set_cut(&mut self, axis: u32, at: f64) -> Result<(), JsError> {
        Ok(self.inner.set_cut(axis as usize, at)?)
    }

    /// Turns the shared camera by a drag of `(dx, dy)` CSS pixels.
    pub fn orbit(&mut self, dx: f64, dy: f64) {
        self.inner.orbit(dx, dy);
    }

    /// Magnifies both views `factor` times (within the camera's range).
    pub fn zoom(&mut self, factor: f64) {
        self.inner.zoom(factor);
    }

    /// Draws every later picture in the dark (projector) or the light theme, every label
    /// at least `label_px` CSS pixels (as [`Playground::set_theme`]).
    #[wasm_bindgen(js_name = setTheme)]
    pub fn set_theme(&mut self, dark: bool, label_px: f32) {
        self.inner.set_theme(Theme::for_page(dark, label_px));
    }

    /// The camera as it starts.
    #[wasm_bindgen(js_name = resetZoom)]
    pub fn reset_zoom(&mut self) {
        self.inner.reset_camera();
    }

    /// Always `undefined`: a tetrahedral mesh is not read as a surface.
    #[wasm_bindgen(js_name = notPlanar)]
    pub fn not_planar(&self) -> Option<String> {
        None
    }

    /// The shared camera: `{ yaw, pitch, zoom }` (degrees, degrees, factor).
    pub fn camera(&self) -> Result<JsValue, JsError> {
        let c = self.inner.camera();
        object(&[("yaw", c.yaw.into()), ("pitch", c.pitch.into()), ("zoom", c.zoom.into())])
    }

    /// No node is picked in the cut view (`undefined`): its faces hide the nodes behind.
    #[wasm_bindgen(js_name = pickNode)]
    pub fn pick_node(&self, _panel: &str, _x: f64, _y: f64, _radius: f64) -> Option<u32> {
        None
    }
}
