//! The figures tour ([`crate::lab::tour`]): its menu, each figure's card, picture and live
//! table rows.

use wasm_bindgen::prelude::*;

use super::{css_canvas, object, pixels, to_js};
use crate::lab::tour;
use smoothlab_render::Theme;

/// The figures tour's menu: `[{ name, source }]` ([`crate::lab::tour`]).
#[wasm_bindgen(js_name = tourFigures)]
pub fn tour_figures() -> Result<JsValue, JsError> {
    to_js(&tour::entries())
}

/// One figure of the tour: `{ name, index, count, prev, next, source, caption, hash, view,
/// run, look, claim, measured, rows }` (`hash` the playground state to open).
#[wasm_bindgen(js_name = tourCard)]
pub fn tour_card(name: &str) -> Result<JsValue, JsError> {
    let (i, fig) = tour::find(name)?;
    to_js(&fig.card(i)?)
}

/// A figure's picture, `w × h` CSS pixels at ratio `dpr`, in the dark or the light theme
/// with labels of at least `label_px` CSS pixels (as the playground's `setTheme`):
/// `{ pixels, w, h }` (device pixels).
#[wasm_bindgen(js_name = tourPicture)]
pub fn tour_picture(name: &str, w: u32, h: u32, dpr: f32, dark: bool, label_px: f32) -> Result<JsValue, JsError> {
    let c = css_canvas(w, h, dpr)?;
    let pm = tour::pictures::render(name, c, &Theme::for_page(dark, label_px))?;
    let (pw, ph) = (pm.width(), pm.height());
    object(&[("pixels", pixels(pm)), ("w", JsValue::from(pw)), ("h", JsValue::from(ph))])
}

/// Where a figure's picture, drawn as [`tour_picture`] draws it, put its plots, legends
/// and marks: `{ w, h, regions: [{ kind: "plot" | "legend" | "mark", x, y, w, h, rgb }] }`,
/// device pixels ([`smoothlab_render::layout`]) — for the page's tests, which check that no
/// legend lies over the data and that the marks a figure's text promises are drawn.
#[wasm_bindgen(js_name = tourPictureLayout)]
pub fn tour_picture_layout(name: &str, w: u32, h: u32, dpr: f32, dark: bool, label_px: f32) -> Result<JsValue, JsError> {
    let c = css_canvas(w, h, dpr)?;
    let (pm, regions) = tour::pictures::render_with_layout(name, c, &Theme::for_page(dark, label_px))?;
    #[derive(serde::Serialize)]
    struct Layout {
        w: u32,
        h: u32,
        regions: Vec<smoothlab_render::layout::Region>,
    }
    to_js(&Layout { w: pm.width(), h: pm.height(), regions })
}

/// Row `i` of Freitag's Table 1, smoothed now: `{ method, min_angle_deg, max_angle_deg,
/// laplacian_moves, optimization_calls, reproduction_min, reproduction_max, paper }`.
#[wasm_bindgen(js_name = tourRow)]
pub fn tour_row(i: u32) -> Result<JsValue, JsError> {
    to_js(&tour::pictures::freitag_row(i as usize)?)
}

/// Row `i` of figure `name`'s live table (Freitag's Table 1 or 2), smoothed now:
/// `{ method, cells }`, the cells under the card's `columns`.
#[wasm_bindgen(js_name = tourTableRow)]
pub fn tour_table_row(name: &str, i: u32) -> Result<JsValue, JsError> {
    to_js(&tour::pictures::table_row(name, i as usize)?)
}

/// The default size of a figure's picture, CSS pixels: `[w, h]`.
#[wasm_bindgen(js_name = tourPictureSize)]
pub fn tour_picture_size(name: &str) -> Result<JsValue, JsError> {
    let (_, fig) = tour::find(name)?;
    to_js(&tour::pictures::default_size(fig.name))
}
