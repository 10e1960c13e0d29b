//! The 3D lab's handle: one [`Lab3d`] for a surface or tetrahedra, wrapping
//! [`lab::Lab3d`] of either kind; each method converts and calls it. [`kind`](Lab3d::kind)
//! tells the page which it is; what only tetrahedra have (the cut plane, the dihedral
//! histograms) is refused on a surface, saying so.

use glam::DVec2;
use wasm_bindgen::prelude::*;

use super::{frame_object, now_ms, object, perturb_seed, pixels, side, to_js};
use crate::lab::views::Canvas;
use crate::lab::{self, Side};
use crate::render::Theme;
use crate::surface::Surface;
use crate::volume::VolumeMesh;

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
    pub(super) fn surface(s: Surface) -> crate::Result<Lab3d> {
        Ok(Lab3d { inner: Kind::Surface(Box::new(lab::Lab3d::new(s)?)) })
    }

    /// The handle of a lab on tetrahedra.
    pub(super) fn volume(m: VolumeMesh) -> crate::Result<Lab3d> {
        Ok(Lab3d { inner: Kind::Volume(Box::new(lab::Lab3d::new(m)?)) })
    }

    fn tetrahedra(&self) -> Result<&lab::Lab3d<VolumeMesh>, JsError> {
        match &self.inner {
            Kind::Volume(l) => Ok(l),
            Kind::Surface(_) => Err(JsError::new("the cut plane and the dihedral angles take tetrahedral meshes only")),
        }
    }
}

#[wasm_bindgen]
impl Lab3d {
    /// The kind of mesh: `surface` or `volume` (tetrahedra, drawn cut by a plane).
    pub fn kind(&self) -> String {
        each!(&self.inner, l => l.kind()).to_string()
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

    /// The node of a side under the CSS pixel `(x, y)` of the last frame within `radius`
    /// CSS pixels (the near side of a surface winning), or `undefined` (always, in the cut
    /// view of tetrahedra: its faces hide the nodes behind).
    #[wasm_bindgen(js_name = pickNode)]
    pub fn pick_node(&self, panel: &str, x: f64, y: f64, radius: f64) -> Result<Option<u32>, JsError> {
        let s = side(panel)?;
        let at = DVec2::new(x, y);
        Ok(each!(&self.inner, l => l.pick_in_frame(s, at, radius))?.map(|n| n as u32))
    }

    /// Both sides' dihedral angle histograms beside the mesh as loaded, on canvases of
    /// `w × h` device pixels, the percentages on a logarithmic scale when `log_y`:
    /// `{ a, b }` (RGBA pixels). Tetrahedra only.
    pub fn histograms(&self, w: u32, h: u32, dpr: f32, log_y: bool) -> Result<JsValue, JsError> {
        let l = self.tetrahedra()?;
        let c = Canvas { w, h, dpr };
        let a = pixels(l.render_histogram(Side::A, c, log_y)?);
        let b = pixels(l.render_histogram(Side::B, c, log_y)?);
        object(&[("a", a), ("b", b)])
    }

    /// Cuts both sides across `axis` (0, 1, 2: x, y, z) at the fraction `at` of the
    /// extent. Tetrahedra only.
    #[wasm_bindgen(js_name = setCut)]
    pub fn set_cut(&mut self, axis: u32, at: f64) -> Result<(), JsError> {
        self.tetrahedra()?;
        let Kind::Volume(l) = &mut self.inner else { unreachable!("checked: tetrahedra") };
        Ok(l.set_cut(axis as usize, at)?)
    }
}
