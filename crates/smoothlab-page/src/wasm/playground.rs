//! The planar lab's handle: [`Playground`] wraps [`lab::Playground`], which keeps the page's
//! state (the meshes, the pass in slices, the chosen node, the canvases last drawn on, the
//! frames sent); each method converts and calls it.

use glam::DVec2;
use wasm_bindgen::prelude::*;

use super::{css_canvas, frame_object, now_ms, object, perturb_seed, pixels, side, to_js};
use smoothlab::io::{self, Format};
use crate::lab::views::Canvas;
use crate::lab::{self, Side, SideSweep, SlidePlaces, SlideState};
use smoothlab::mesh::Mesh;
use smoothlab_render::Theme;

fn canvas(w: u32, h: u32, dpr: f32) -> Canvas {
    Canvas { w, h, dpr }
}

/// Positions from x and y interleaved (an odd count is refused).
fn positions(xy: &[f64]) -> Result<Vec<DVec2>, JsError> {
    if xy.len() % 2 != 0 {
        return Err(JsError::new(&format!("{} coordinates: give x and y of each position", xy.len())));
    }
    Ok(xy.chunks_exact(2).map(|c| DVec2::new(c[0], c[1])).collect())
}

/// Where a sliding boundary's nodes were put, from its segments and parameters as they
/// travel (none while it is held; parameters absent or empty for a linear mesh).
fn places(segments: Option<Vec<u32>>, params: Option<Vec<f64>>) -> Result<Option<SlidePlaces>, JsError> {
    match (segments, params) {
        (Some(segments), params) => Ok(Some(SlidePlaces { segments, params: params.unwrap_or_default() })),
        (None, None) => Ok(None),
        (None, Some(_)) => Err(JsError::new("boundary parameters travel with their segments: give both")),
    }
}

/// The page's state for a planar mesh: one opaque handle (see [`lab::Playground`]).
#[wasm_bindgen]
pub struct Playground {
    inner: lab::Playground,
}

impl Playground {
    /// The handle of a playground on `mesh`.
    pub(super) fn open(mesh: Mesh) -> smoothlab::Result<Playground> {
        Ok(Playground { inner: lab::Playground::new(mesh)? })
    }

    fn node_view_object(view: ([tiny_skia::Pixmap; 3], lab::views::NodeSummary)) -> Result<JsValue, JsError> {
        let (pictures, summary) = view;
        super::node_view_object(pictures, summary.text(), &summary)
    }
}

#[wasm_bindgen]
impl Playground {
    /// A playground on a Triangle mesh: the texts of its `.node` and `.ele` files.
    #[wasm_bindgen(js_name = fromTriangle)]
    pub fn from_triangle(node: &str, ele: &str) -> Result<Playground, JsError> {
        Ok(Playground::open(io::read_triangle(node, ele)?)?)
    }

    /// The shared controls and what each side smooths with: `{ strategy, threshold_deg,
    /// order, max_iter, compare: [{ objective, penalty }, { objective, penalty }] }`.
    #[wasm_bindgen(js_name = setSettings)]
    pub fn set_settings(&mut self, settings: JsValue) -> Result<(), JsError> {
        Ok(self.inner.set_settings(super::settings(settings)?)?)
    }

    /// One smoothing pass on both panels; returns their pass records `[a, b]`.
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
    /// visits, planned, records }` (`records` `[a, b]` once done).
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
    /// settings), which sweeps panel A (`beginSweep`); run it with `continuePass`
    /// (stage `wait` until `adoptSweep` hands the sweep over). The same result as `step`.
    #[wasm_bindgen(js_name = beginSplitPass)]
    pub fn begin_split_pass(&mut self) {
        self.inner.begin_split_pass();
    }

    /// The positions of panel `side` (`a` or `b`), x and y interleaved.
    #[wasm_bindgen(js_name = panelPositions)]
    pub fn panel_positions(&self, side: &str) -> Result<js_sys::Float64Array, JsError> {
        Ok(js_sys::Float64Array::from(&self.inner.panel_positions(self::side(side)?)[..]))
    }

    /// Starts the sweep of panel `side` alone from `nodes` (the other engine's positions,
    /// x and y interleaved), for a split pass; run it with `continuePass`, then `takeSweep`.
    /// `target` is the other engine's `targetPositions` (null with the ideal target);
    /// `keepGrading`, `startValid` and `firstPass` its `runStart`; `slideFrom`, `slideSegments` and
    /// `slideParams` its `slideState` of the side (all undefined while its boundary is held;
    /// `slideParams` empty for a linear mesh).
    #[wasm_bindgen(js_name = beginSweep)]
    #[allow(clippy::too_many_arguments)]
    pub fn begin_sweep(
        &mut self,
        side: &str,
        nodes: &[f64],
        target: Option<Vec<f64>>,
        keep_grading: f64,
        start_valid: bool,
        first_pass: bool,
        slide_from: Option<Vec<f64>>,
        slide_segments: Option<Vec<u32>>,
        slide_params: Option<Vec<f64>>,
    ) -> Result<(), JsError> {
        let start = crate::lab::settings::RunStart { keep_grading, valid: start_valid, first_pass };
        let slide = match (slide_from, places(slide_segments, slide_params)?) {
            (Some(from), Some(places)) => Some(SlideState { from: positions(&from)?, places }),
            (None, None) => None,
            _ => return Err(JsError::new("a sliding boundary travels as slideFrom, slideSegments and slideParams together")),
        };
        Ok(self.inner.begin_sweep(self::side(side)?, nodes, target.as_deref(), start, slide.as_ref())?)
    }

    /// Where the sliding boundary of panel `side` stands: `{ from: Float64Array, segments:
    /// Uint32Array, params: Float64Array }` (the positions it was taken from, x and y
    /// interleaved, the boundary segment each node was last put on and, for a quadratic
    /// mesh, its parameter there; empty for a linear one), or null while it is held. A
    /// split pass hands panel A's to `beginSweep`.
    #[wasm_bindgen(js_name = slideState)]
    pub fn slide_state(&self, side: &str) -> Result<JsValue, JsError> {
        match self.inner.slide_state(self::side(side)?) {
            Some(s) => {
                let from: Vec<f64> = s.from.iter().flat_map(|p| [p.x, p.y]).collect();
                object(&[
                    ("from", js_sys::Float64Array::from(&from[..]).into()),
                    ("segments", js_sys::Uint32Array::from(&s.places.segments[..]).into()),
                    ("params", js_sys::Float64Array::from(&s.places.params[..]).into()),
                ])
            }
            None => Ok(JsValue::NULL),
        }
    }

    /// Where this engine's runs begin, the mesh as loaded or as last perturbed: the grading
    /// they keep (+∞, none, where it was tangled), whether it was valid, and whether the
    /// run's first pass is still to come (it fits the mesh to its targets first), as
    /// `[keepGrading, startValid, firstPass]`. A split pass hands them to `beginSweep`.
    #[wasm_bindgen(js_name = runStart)]
    pub fn run_start(&self) -> js_sys::Array {
        let s = self.inner.run_start();
        js_sys::Array::of3(&s.keep_grading.into(), &s.valid.into(), &s.first_pass.into())
    }

    /// The positions every corner is measured against (x and y interleaved: the mesh as
    /// loaded or as last perturbed) when the settings' target is `input`; null with the
    /// ideal target. A split pass hands them to the engine that sweeps (`beginSweep`).
    #[wasm_bindgen(js_name = targetPositions)]
    pub fn target_positions(&self) -> Option<js_sys::Float64Array> {
        self.inner
            .target_positions()
            .map(|t| js_sys::Float64Array::from(&t[..]))
    }

    /// The completed sweep: `{ nodes: Float64Array, sweep: { counts, sweep_ms }, segments:
    /// Uint32Array | null, params: Float64Array | null }` (where the boundary slides: the
    /// boundary segment each node was last put on and, for a quadratic mesh, its parameter
    /// there), or undefined when there is none.
    #[wasm_bindgen(js_name = takeSweep)]
    pub fn take_sweep(&mut self) -> Result<JsValue, JsError> {
        match self.inner.take_sweep() {
            Some((nodes, sweep, places)) => object(&[
                ("nodes", js_sys::Float64Array::from(&nodes[..]).into()),
                ("sweep", to_js(&sweep)?),
                ("segments", places.as_ref().map_or(JsValue::NULL, |p| js_sys::Uint32Array::from(&p.segments[..]).into())),
                ("params", places.as_ref().map_or(JsValue::NULL, |p| js_sys::Float64Array::from(&p.params[..]).into())),
            ]),
            None => Ok(JsValue::UNDEFINED),
        }
    }

    /// Hands panel A's sweep (`takeSweep`'s `nodes`, `sweep`, `segments` and `params`, from
    /// the other engine) to the split pass in progress.
    #[wasm_bindgen(js_name = adoptSweep)]
    pub fn adopt_sweep(&mut self, nodes: &[f64], sweep: JsValue, segments: Option<Vec<u32>>, params: Option<Vec<f64>>) -> Result<(), JsError> {
        let sweep: SideSweep =
            serde_wasm_bindgen::from_value(sweep).map_err(|e| JsError::new(&format!("a sweep's record: {e}")))?;
        Ok(self.inner.adopt_sweep(nodes, sweep, places(segments, params)?)?)
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

    /// A panel's current mesh as arrays: `{ dim, points, cells, fixed }` (what its `.vtk`
    /// text holds, [`smoothlab::io::MeshArrays`]).
    #[wasm_bindgen(js_name = meshArrays)]
    pub fn mesh_arrays(&self, panel: &str) -> Result<JsValue, JsError> {
        super::arrays_object(self.inner.arrays(side(panel)?))
    }

    /// The statistics table of one panel (`a` or `b`): nodes, elements, inverted,
    /// min/max angle, min quality and the work of the passes.
    pub fn stats(&self, panel: &str) -> Result<JsValue, JsError> {
        to_js(&self.inner.table(side(panel)?))
    }

    /// Both panels back to the mesh as loaded.
    pub fn reset(&mut self) {
        self.inner.reset();
    }

    /// Draws both panels' meshes on canvases of `w × h` device pixels at ratio `dpr`:
    /// `{ a, b, render_ms: [a, b], copy_ms, colour_bar }`, RGBA pixels of each panel,
    /// `colour_bar` whether the pictures carry the colour bar (false: the canvas is too
    /// small for it, show the scale beside it), or `null` for a panel whose last picture
    /// sent shows the same positions, canvas and highlight (unless `force`). The chosen
    /// node is highlighted with its star ([`lab::Playground::frame`]).
    pub fn frame(&mut self, w: u32, h: u32, dpr: f32, force: bool) -> Result<JsValue, JsError> {
        let f = self.inner.frame(canvas(w, h, dpr), force, &now_ms)?;
        frame_object(f.pictures, f.render_ms, f.colour_bar)
    }

    /// Draws every later picture (meshes, level sets, charts, histograms, the figure) in
    /// the dark (projector) or the light theme, every label at least `label_px` CSS
    /// pixels (0: each label its own size); forgets the frames sent, so the next
    /// [`frame`](Self::frame) draws both panels.
    #[wasm_bindgen(js_name = setTheme)]
    pub fn set_theme(&mut self, dark: bool, label_px: f32) {
        self.inner.set_theme(Theme::for_page(dark, label_px));
        self.inner.forget_frames();
    }

    /// Forgets what was sent: the next [`frame`](Self::frame) draws both panels (after
    /// the page cleared or replaced its canvases).
    #[wasm_bindgen(js_name = forgetFrames)]
    pub fn forget_frames(&mut self) {
        self.inner.forget_frames();
    }

    /// The node of a panel nearest to the CSS pixel `(x, y)` of the last frame within
    /// `radius` CSS pixels: `{ node, nearest, message }` (see [`crate::lab::pick::Pick`]).
    #[wasm_bindgen(js_name = pickNode)]
    pub fn pick_node(&self, panel: &str, x: f64, y: f64, radius: f64) -> Result<JsValue, JsError> {
        to_js(&self.inner.pick_in_frame(side(panel)?, DVec2::new(x, y), radius)?)
    }

    /// Moves a free node to the CSS pixel `(x, y)` of the last frame, on both panels.
    #[wasm_bindgen(js_name = dragNode)]
    pub fn drag_node(&mut self, node: u32, x: f64, y: f64) -> Result<(), JsError> {
        Ok(self.inner.drag_in_frame(node as usize, DVec2::new(x, y))?)
    }

    /// Moves the chosen node by `(dx, dy)` CSS pixels of the last frame from where it is on
    /// `panel`, on both panels (the arrow keys), undoably.
    #[wasm_bindgen(js_name = nudgeNode)]
    pub fn nudge_node(&mut self, panel: &str, dx: f64, dy: f64) -> Result<(), JsError> {
        Ok(self.inner.nudge_chosen(side(panel)?, DVec2::new(dx, dy))?)
    }

    /// Chooses the node whose star is highlighted and whose level sets are shown (`undefined`: none).
    #[wasm_bindgen(js_name = selectNode)]
    pub fn select_node(&mut self, node: Option<u32>) -> Result<(), JsError> {
        Ok(self.inner.choose_node(node.map(|n| n as usize))?)
    }

    /// The chosen node's level sets (A, B: `w × h`), its solve history chart (`cw × ch`)
    /// and a one-line summary: `{ level_a, level_b, chart, summary, solve }`.
    #[wasm_bindgen(js_name = nodeView)]
    pub fn node_view(&mut self, w: u32, h: u32, cw: u32, ch: u32, dpr: f32) -> Result<JsValue, JsError> {
        Self::node_view_object(self.inner.chosen_node_view(canvas(w, h, dpr), canvas(cw, ch, dpr))?)
    }

    /// The free node with the worst star (on B's mesh), or `undefined` when none is free.
    #[wasm_bindgen(js_name = worstFreeNode)]
    pub fn worst_free_node(&self) -> Option<u32> {
        crate::lab::pick::worst_free_node(&self.inner.panel(Side::B).mesh).map(|n| n as u32)
    }

    /// Magnifies both meshes `factor` times about the CSS pixel `(x, y)` of the last frame.
    #[wasm_bindgen(js_name = zoomMeshes)]
    pub fn zoom_meshes(&mut self, x: f64, y: f64, factor: f64) -> Result<(), JsError> {
        Ok(self.inner.zoom_meshes_in_frame(DVec2::new(x, y), factor)?)
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
        Ok(self.inner.zoom_level_sets_in_frame(side(panel)?, DVec2::new(x, y), factor)?)
    }

    /// Moves both level sets by `(dx, dy)` CSS pixels of `panel`'s level set as last drawn.
    #[wasm_bindgen(js_name = panLevelSets)]
    pub fn pan_level_sets(&mut self, panel: &str, dx: f64, dy: f64) -> Result<(), JsError> {
        Ok(self.inner.pan_level_sets_in_frame(side(panel)?, DVec2::new(dx, dy))?)
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

    /// Takes back the latest move: `{ node, next, depth }` (`node` the node moved back,
    /// undefined when there was none; `next` the node the next undo moves back; `depth`:
    /// moves left to undo).
    pub fn undo(&mut self) -> Result<JsValue, JsError> {
        let node = self.inner.undo();
        to_js(&self.inner.undo_summary(node))
    }

    /// `{ next, depth }`: the node the next undo moves back, and how many moves it can take
    /// back ([`lab::screen::UndoSummary`]).
    #[wasm_bindgen(js_name = undoSummary)]
    pub fn undo_summary(&self) -> Result<JsValue, JsError> {
        to_js(&self.inner.undo_summary(None))
    }

    /// One solver call on the chosen node on each side, which then moves to what it
    /// found: the node view of that call (as [`node_view`](Self::node_view), drawn
    /// before the move, so its history is the call's).
    #[wasm_bindgen(js_name = smoothNode)]
    pub fn smooth_node(&mut self, w: u32, h: u32, cw: u32, ch: u32, dpr: f32) -> Result<JsValue, JsError> {
        Self::node_view_object(self.inner.smooth_chosen_node(canvas(w, h, dpr), canvas(cw, ch, dpr))?)
    }

    /// The figure for slides: A | B with titles, the colour bar and statistics
    /// (`smoothlab render --view compare`), `w × h` CSS pixels at ratio `dpr`:
    /// `{ pixels, w, h }` (device pixels).
    pub fn figure(&self, w: u32, h: u32, dpr: f32) -> Result<JsValue, JsError> {
        let c = css_canvas(w, h, dpr)?;
        let pm = self.inner.render_figure(c)?;
        object(&[("pixels", pixels(pm)), ("w", JsValue::from(c.w)), ("h", JsValue::from(c.h))])
    }

    /// The per-pass chart (`w × h`) and both angle histograms (`hw × hh`, on one scale,
    /// logarithmic when `log_y`), with both statistics tables (measured in full now):
    /// `{ pass, hist_a, hist_b, stats: { a, b } }`.
    pub fn charts(&self, w: u32, h: u32, hw: u32, hh: u32, dpr: f32, log_y: bool) -> Result<JsValue, JsError> {
        let hc = canvas(hw, hh, dpr);
        let pass = pixels(self.inner.render_pass_chart(canvas(w, h, dpr))?);
        let hist_a = pixels(self.inner.render_histogram(Side::A, hc, log_y)?);
        let hist_b = pixels(self.inner.render_histogram(Side::B, hc, log_y)?);
        // after the histograms: the full statistics are at hand for the tables' detail
        let stats = object(&[("a", self.stats("a")?), ("b", self.stats("b")?)])?;
        object(&[("pass", pass), ("hist_a", hist_a), ("hist_b", hist_b), ("stats", stats)])
    }
}
