//! Two mesh panels side by side (e.g. before and after, or old and new smoothing), each
//! with a title and a few lines of statistics under it, drawn at one common scale.

use tiny_skia::Pixmap;

use super::mesh::{colour_bar_band, draw_colour_bar, render_mesh, MeshView};
use super::paint::fill_rect;
use super::text::{draw_text, Align, TextStyle, Valign};
use super::view::{sane_dpr, Frame, View};
use crate::mesh::Mesh;

/// One panel of [`render_compare`].
#[derive(Clone, Copy, Debug)]
pub struct ComparePanel<'a> {
    pub mesh: &'a Mesh,
    pub title: &'a str,
    /// Statistics lines shown under the mesh (e.g. "min angle 18.2°").
    pub lines: &'a [String],
}

const TITLE_H: f32 = 26.0;
const LINE_H: f32 = 16.0;

/// Draws `left` and `right` with the options of `opts` (its frame, or the whole pixmap),
/// both fitted to the union of their bounds (unless `opts.bounds` is set) and sharing
/// one colour bar along the bottom (it counts the right panel's inverted elements).
/// Returns the two views.
pub fn render_compare(pixmap: &mut Pixmap, left: &ComparePanel<'_>, right: &ComparePanel<'_>, opts: &MeshView) -> (View, View) {
    let s = sane_dpr(opts.dpr);
    let frame = opts.frame.unwrap_or(Frame::of_pixmap(pixmap, s));
    let theme = &opts.theme;
    fill_rect(pixmap, frame.x * s, frame.y * s, frame.w * s, frame.h * s, theme.paper);
    let (title_h, line_h) = (TITLE_H * theme.grow(14.0), LINE_H * theme.grow(11.5));
    let bounds = opts.bounds.unwrap_or_else(|| {
        let (a0, a1) = left.mesh.bounds();
        let (b0, b1) = right.mesh.bounds();
        (a0.min(b0), a1.max(b1))
    });
    let bar = opts.colour_bar.then(|| colour_bar_band(frame, opts.metric.label(right.mesh), theme)).flatten();
    let bar_h = bar.map_or(0.0, |b| b.h);
    let gap = 12.0;
    let col_w = (frame.w - gap) / 2.0;
    let rows = left.lines.len().max(right.lines.len()) as f32;
    let stats_h = if rows > 0.0 { rows * line_h + 8.0 } else { 0.0 };
    let mut views = Vec::with_capacity(2);
    for (k, panel) in [left, right].into_iter().enumerate() {
        let x = frame.x + k as f32 * (col_w + gap);
        let mesh_frame = Frame::new(x, frame.y + title_h, col_w, frame.h - title_h - stats_h - bar_h);
        let o = MeshView { frame: Some(mesh_frame), bounds: Some(bounds), colour_bar: false, ..*opts };
        views.push(render_mesh(pixmap, panel.mesh, &o));
        let centre = x + 0.5 * col_w;
        let title = TextStyle::new(theme.text_px(14.0 * s, s)).with_color(theme.ink).with_align(Align::Centre, Valign::Baseline);
        draw_text(pixmap, panel.title, centre * s, (frame.y + 18.0 * theme.grow(14.0)) * s, title);
        let st = TextStyle::new(theme.text_px(11.5 * s, s)).with_color(theme.caption).with_align(Align::Centre, Valign::Baseline);
        for (i, line) in panel.lines.iter().enumerate() {
            let y = frame.bottom() - bar_h - stats_h + 4.0 + line_h * (i as f32 + 0.75);
            draw_text(pixmap, line, centre * s, y * s, st);
        }
    }
    if let Some(bar) = bar {
        let mesh = right.mesh;
        let n_inverted = (0..mesh.element_count())
            .filter(|&e| {
                let kind = mesh.kind(e);
                crate::quality::element_quality(kind, &mesh.element_points_array(e)[..kind.node_count()]).inverted
            })
            .count();
        draw_colour_bar(pixmap, bar, opts.colormap, opts.metric.domain(mesh), opts.metric.label(mesh), n_inverted, s, theme);
    }
    (views[0], views[1])
}
