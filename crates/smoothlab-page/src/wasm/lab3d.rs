//! The 3D lab's handle: one [`Lab3d`] for a surface or tetrahedra, wrapping
//! [`lab::Lab3d`] of either kind; each method converts and calls it. [`kind`](Lab3d::kind)
//! tells the page which it is; what only tetrahedra have (the cut plane) is refused on a
//! surface, saying so. The node views, the charts and the figure are the playground's
//! methods by the same names, taking and giving the same shapes.

use glam::DVec2;
use wasm_bindgen::prelude::*;

use super::{css_canvas, frame_object, now_ms, object, perturb_seed, pixels, side, to_js};
use crate::lab::lab3d::{Mesh3d, NodeSummary3d};
use crate::lab::views::Canvas;
use crate::lab::{self, Side};
use smoothlab_render::{Camera, Theme};
use smoothlab::surface::Surface;
use smoothlab::volume::VolumeMesh;

/// The lab of either kind (boxed: one handle, its size that of a pointer).
enum Kind {
    Surface(Box<lab::Lab3d<Surface>>),
    Volume(Box<lab::Lab3d<VolumeMesh>>),
}

/// Calls the same method on the lab, whichever its kind.
macro_rules! each {
    ($self:expr, $l:ident => $e:expr) => {
        match $self {
            Kind::Surface($l) => $e,
            Kind::Volume($l) => $e,
        }
    };
}

/// The page's state for a mesh in 3D, a surface or tetrahedra: one opaque handle (see
/// [`lab::Lab3d`]).
#[wasm_bindgen]
pub struct Lab3d {
    inner: Kind,
}

impl Lab3d {
    /// The handle of a lab on a surface.
    pub(super) fn surface(s: Surface) -> smoothlab::Result<Lab3d> {
        Ok(Lab3d { inner: Kind::Surface(Box::new(lab::Lab3d::new(s)?)) })
    }

    /// The handle of a lab on tetrahedra.
    pub(super) fn volume(m: VolumeMesh) -> smoothlab::Result<Lab3d> {
        Ok(Lab3d { inner: Kind::Volume(Box::new(lab::Lab3d::new(m)?)) })
    }

    fn node_view_object(view: ([tiny_skia::Pixmap; 3], NodeSummary3d)) -> Result<JsValue, JsError> {
        let (pictures, summary) = view;
        super::node_view_object(pictures, summary.text(), &summary)
    }

    /// The per-pass chart and every histogram of the kind, both sides, with both tables.
    fn charts_of<M: Mesh3d>(l: &lab::Lab3d<M>, chart: Canvas, hist: Canvas, log_y: bool) -> Result<JsValue, JsError> {
        let pass = pixels(l.render_pass_chart(chart)?);
        let list = js_sys::Array::new();
        let mut first = (JsValue::UNDEFINED, JsValue::UNDEFINED);
        for (i, h) in M::HISTOGRAMS.iter().enumerate() {
            let a = pixels(l.render_histogram(i, Side::A, hist, log_y)?);
            let b = pixels(l.render_histogram(i, Side::B, hist, log_y)?);
            if i == 0 {
                first = (a.clone(), b.clone());
            }
            list.push(&object(&[("title", JsValue::from_str(h.title)), ("a", a), ("b", b)])?);
        }
        let stats = object(&[("a", to_js(&l.table(Side::A))?), ("b", to_js(&l.table(Side::B))?)])?;
        object(&[("pass", pass), ("hist_a", first.0), ("hist_b", first.1), ("histograms", list.into()), ("stats", stats)])
    }
}

#[wasm_bindgen]
impl Lab3d {
    /// The kind of mesh: `surface` or `volume` (tetrahedra, drawn cut by a plane).
    pub fn kind(&self) -> String {
        each!(&self.inner, l => l.kind()).to_string()
    }

    /// Why this mesh's boundary nodes cannot slide (a surface, a quadratic volume mesh),
    /// or undefined: the page shows its boundary menu fixed, disabled, with the reason.
    #[wasm_bindgen(js_name = slideRefused)]
    pub fn slide_refused(&self) -> Option<String> {
        each!(&self.inner, l => l.slide_refused())
    }

    /// As the playground's `setSettings` (for tetrahedra each side's objective carried to
    /// tetrahedra).
    #[wasm_bindgen(js_name = setSettings)]
    pub fn set_settings(&mut self, settings: JsValue) -> Result<(), JsError> {
        let s = super::settings(settings)?;
        Ok(each!(&mut self.inner, l => l.set_settings(s))?)
    }

    /// One smoothing pass on both sides; returns their pass records `[a, b]`.
    pub fn step(&mut self) -> Result<JsValue, JsError> {
        each!(&mut self.inner, l => to_js(&l.step(&now_ms)))
    }

    /// Both sides back to the mesh as loaded.
    pub fn reset(&mut self) {
        each!(&mut self.inner, l => l.reset());
    }

    /// Perturbs the mesh as loaded (a surface in its tangent planes, tetrahedra's free
    /// nodes in space), checked as the playground's `perturb`.
    pub fn perturb(&mut self, amount: f64, seed: &str) -> Result<(), JsError> {
        let seed = perturb_seed(amount, seed)?;
        Ok(each!(&mut self.inner, l => l.perturb(amount, seed))?)
    }

    /// A side's mesh as the text of a file: `msh`, `vtk`, and for a surface `obj` or `off`.
    #[wasm_bindgen(js_name = exportMesh)]
    pub fn export_mesh(&self, panel: &str, format: &str) -> Result<String, JsError> {
        let s = side(panel)?;
        Ok(each!(&self.inner, l => l.export_named(s, format))?)
    }

    /// A side's mesh as arrays, as the playground's `meshArrays`.
    #[wasm_bindgen(js_name = meshArrays)]
    pub fn mesh_arrays(&self, panel: &str) -> Result<JsValue, JsError> {
        let s = side(panel)?;
        super::arrays_object(each!(&self.inner, l => l.arrays(s)))
    }

    /// The statistics table of one side (`a` or `b`), as the playground's `stats` (for a
    /// surface with `max_distance_from_surface`; for tetrahedra the dihedral angles and the
    /// mean ratio).
    pub fn stats(&self, panel: &str) -> Result<JsValue, JsError> {
        let s = side(panel)?;
        each!(&self.inner, l => to_js(&l.table(s)))
    }

    /// Both sides drawn by the shared camera (tetrahedra cut by the plane) on canvases of
    /// `w × h` device pixels at ratio `dpr`: `{ a, b, render_ms: [a, b], copy_ms,
    /// colour_bar }` (RGBA pixels).
    pub fn frame(&mut self, w: u32, h: u32, dpr: f32) -> Result<JsValue, JsError> {
        let c = Canvas { w, h, dpr };
        let f = each!(&mut self.inner, l => l.frame(c, &now_ms))?;
        let [a, b] = f.pictures;
        frame_object([Some(a), Some(b)], f.render_ms, f.colour_bar)
    }

    /// Turns the shared camera by a drag of `(dx, dy)` CSS pixels.
    pub fn orbit(&mut self, dx: f64, dy: f64) {
        each!(&mut self.inner, l => l.orbit(dx, dy));
    }

    /// Magnifies both views `factor` times (within the camera's range).
    pub fn zoom(&mut self, factor: f64) {
        each!(&mut self.inner, l => l.zoom(factor));
    }

    /// Draws every later picture in the dark (projector) or the light theme, every label
    /// at least `label_px` CSS pixels (as the playground's `setTheme`).
    #[wasm_bindgen(js_name = setTheme)]
    pub fn set_theme(&mut self, dark: bool, label_px: f32) {
        each!(&mut self.inner, l => l.set_theme(Theme::for_page(dark, label_px)));
    }

    /// The camera as it starts.
    #[wasm_bindgen(js_name = resetZoom)]
    pub fn reset_zoom(&mut self) {
        each!(&mut self.inner, l => l.reset_camera());
    }

    /// Why the file's points were read as a surface (the node farthest off the plane the
    /// mesh would lie in, and how far), or `undefined` (a sample, or tetrahedra).
    #[wasm_bindgen(js_name = notPlanar)]
    pub fn not_planar(&self) -> Option<String> {
        each!(&self.inner, l => l.not_planar())
    }

    /// What a tetrahedral file's triangles and quads fixed that is not on the boundary, or
    /// `undefined`.
    #[wasm_bindgen(js_name = fileNote)]
    pub fn file_note(&self) -> Option<String> {
        each!(&self.inner, l => l.file_note())
    }

    /// The shared camera: `{ yaw, pitch, zoom }` (degrees, degrees, factor).
    pub fn camera(&self) -> Result<JsValue, JsError> {
        let c = each!(&self.inner, l => l.camera());
        object(&[("yaw", c.yaw.into()), ("pitch", c.pitch.into()), ("zoom", c.zoom.into())])
    }

    /// The node of a side under the CSS pixel `(x, y)` of the last frame: the nearest
    /// node of the face drawn there, `{ node, nearest, message }` as the playground's
    /// (see [`crate::lab::pick::Pick`]; `radius` CSS pixels reach a surface's nodes beside
    /// its faces).
    #[wasm_bindgen(js_name = pickNode)]
    pub fn pick_node(&self, panel: &str, x: f64, y: f64, radius: f64) -> Result<JsValue, JsError> {
        let s = side(panel)?;
        let at = DVec2::new(x, y);
        to_js(&each!(&self.inner, l => l.pick_in_frame(s, at, radius))?)
    }

    /// Chooses the node marked on both sides whose level sets are shown (`undefined`: none).
    #[wasm_bindgen(js_name = selectNode)]
    pub fn select_node(&mut self, node: Option<u32>) -> Result<(), JsError> {
        let n = node.map(|n| n as usize);
        Ok(each!(&mut self.inner, l => l.choose_node(n))?)
    }

    /// The chosen node's level sets (A, B: `w × h`) over its plane, its solve history
    /// chart (`cw × ch`) and a summary: `{ level_a, level_b, chart, summary, solve }`.
    #[wasm_bindgen(js_name = nodeView)]
    pub fn node_view(&mut self, w: u32, h: u32, cw: u32, ch: u32, dpr: f32) -> Result<JsValue, JsError> {
        let (level, chart) = (Canvas { w, h, dpr }, Canvas { w: cw, h: ch, dpr });
        Self::node_view_object(each!(&mut self.inner, l => l.chosen_node_view(level, chart))?)
    }

    /// One solver call on the chosen node on each side, which then moves to what it found
    /// (a surface's back onto the surface): the node view of that call, as `nodeView`.
    #[wasm_bindgen(js_name = smoothNode)]
    pub fn smooth_node(&mut self, w: u32, h: u32, cw: u32, ch: u32, dpr: f32) -> Result<JsValue, JsError> {
        let (level, chart) = (Canvas { w, h, dpr }, Canvas { w: cw, h: ch, dpr });
        Self::node_view_object(each!(&mut self.inner, l => l.smooth_chosen_node(level, chart))?)
    }

    /// Takes back the latest move: `{ node, next, depth }` as the playground's.
    pub fn undo(&mut self) -> Result<JsValue, JsError> {
        each!(&mut self.inner, l => {
            let node = l.undo();
            to_js(&l.undo_summary(node))
        })
    }

    /// `{ next, depth }`: the node the next undo moves back, and how many moves it can take back.
    #[wasm_bindgen(js_name = undoSummary)]
    pub fn undo_summary(&self) -> Result<JsValue, JsError> {
        each!(&self.inner, l => to_js(&l.undo_summary(None)))
    }

    /// Magnifies both level sets `factor` times about the CSS pixel `(x, y)` of `panel`'s
    /// level set as last drawn.
    #[wasm_bindgen(js_name = zoomLevelSets)]
    pub fn zoom_level_sets(&mut self, panel: &str, x: f64, y: f64, factor: f64) -> Result<(), JsError> {
        let s = side(panel)?;
        Ok(each!(&mut self.inner, l => l.zoom_level_sets_in_frame(s, DVec2::new(x, y), factor))?)
    }

    /// Moves both level sets by `(dx, dy)` CSS pixels of `panel`'s level set as last drawn.
    #[wasm_bindgen(js_name = panLevelSets)]
    pub fn pan_level_sets(&mut self, panel: &str, dx: f64, dy: f64) -> Result<(), JsError> {
        let s = side(panel)?;
        Ok(each!(&mut self.inner, l => l.pan_level_sets_in_frame(s, DVec2::new(dx, dy)))?)
    }

    /// The free node with the worst star (on B's mesh), or `undefined`.
    #[wasm_bindgen(js_name = worstFreeNode)]
    pub fn worst_free_node(&self) -> Option<u32> {
        each!(&self.inner, l => l.worst_free_node()).map(|n| n as u32)
    }

    /// The per-pass chart (`w × h`) and each histogram of the kind's (`hw × hh`, both
    /// sides on one scale, logarithmic when `log_y`), with both statistics tables:
    /// `{ pass, hist_a, hist_b, histograms: [{ title, a, b }], stats: { a, b } }` (`hist_a`
    /// and `hist_b` the first histogram's, as the playground's).
    pub fn charts(&self, w: u32, h: u32, hw: u32, hh: u32, dpr: f32, log_y: bool) -> Result<JsValue, JsError> {
        let (chart, hist) = (Canvas { w, h, dpr }, Canvas { w: hw, h: hh, dpr });
        each!(&self.inner, l => Self::charts_of(l, chart, hist, log_y))
    }

    /// The figure for slides: A | B in 3D with titles, statistics and the colour bar,
    /// `w × h` CSS pixels at ratio `dpr`: `{ pixels, w, h }` (device pixels).
    pub fn figure(&self, w: u32, h: u32, dpr: f32) -> Result<JsValue, JsError> {
        let c = css_canvas(w, h, dpr)?;
        let pm = each!(&self.inner, l => l.render_figure(c))?;
        object(&[("pixels", pixels(pm)), ("w", JsValue::from(c.w)), ("h", JsValue::from(c.h))])
    }

    /// Sees both sides by the camera `yaw`, `pitch` (degrees) and `zoom` (a permalink's).
    #[wasm_bindgen(js_name = setCamera)]
    pub fn set_camera(&mut self, yaw: f64, pitch: f64, zoom: f64) -> Result<(), JsError> {
        Ok(each!(&mut self.inner, l => l.set_camera(Camera { yaw, pitch, zoom }))?)
    }

    /// Where node `node` of `panel` is drawn in the last frame: `{ x, y, behind }` (CSS
    /// pixels; how far behind the side's front-most node, CSS pixels), or `undefined` when
    /// there is no such node. For the browser tests, which click on a node.
    #[wasm_bindgen(js_name = nodeOnScreen)]
    pub fn node_on_screen(&self, panel: &str, node: u32) -> Result<JsValue, JsError> {
        let s = side(panel)?;
        match each!(&self.inner, l => l.node_on_screen(s, node as usize))? {
            Some((p, behind)) => object(&[("x", p.x.into()), ("y", p.y.into()), ("behind", behind.into())]),
            None => Ok(JsValue::UNDEFINED),
        }
    }

    /// Node `node`'s position on `panel`'s mesh, `[x, y, z]` (for the tests), or `undefined`.
    #[wasm_bindgen(js_name = nodePoint)]
    pub fn node_point(&self, panel: &str, node: u32) -> Result<Option<Vec<f64>>, JsError> {
        let s = side(panel)?;
        let n = node as usize;
        Ok(each!(&self.inner, l => (n < l.mesh(s).node_count()).then(|| l.mesh(s).point(n).to_array().to_vec())))
    }

    /// Cuts both sides across `axis` (0, 1, 2: x, y, z) at the fraction `at` of the
    /// extent. Tetrahedra only.
    #[wasm_bindgen(js_name = setCut)]
    pub fn set_cut(&mut self, axis: u32, at: f64) -> Result<(), JsError> {
        let Kind::Volume(l) = &mut self.inner else {
            return Err(JsError::new("the cut plane takes tetrahedral meshes only"));
        };
        Ok(l.set_cut(axis as usize, at)?)
    }
}
