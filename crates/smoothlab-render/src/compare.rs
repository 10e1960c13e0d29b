//! Two mesh panels side by side (e.g. before and after, or old and new smoothing), each
//! with a title and a few lines of statistics under it, drawn at one common scale; the
//! layout itself ([`render_compare_with`]) takes any picture for a panel (the page's
//! figure of two 3D views).

use tiny_skia::Pixmap;

use super::colormap::Colormap;
use super::mesh::{colour_bar_band, draw_colour_bar, render_mesh, MeshView};
use super::paint::fill_rect;
use super::text::{draw_text, Align, TextStyle, Valign};
use super::theme::Theme;
use super::view::{sane_dpr, Frame, View};
use smoothlab::mesh::Mesh;

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
    let bounds = opts.bounds.unwrap_or_else(|| {
        let (a0, a1) = left.mesh.bounds();
        let (b0, b1) = right.mesh.bounds();
        (a0.min(b0), a1.max(b1))
    });
    let mesh = right.mesh;
    let inverted = || {
        (0..mesh.element_count())
            .filter(|&e| {
                let kind = mesh.kind(e);
                smoothlab::quality::element_quality(kind, &mesh.element_points_array(e)[..kind.node_count()]).inverted
            })
            .count()
    };
    let bar = opts.colour_bar.then(|| CompareBar {
        label: opts.metric.label(mesh),
        domain: opts.metric.domain(mesh),
        colormap: opts.colormap,
        inverted: &inverted,
    });
    let text = [CompareText { title: left.title, lines: left.lines }, CompareText { title: right.title, lines: right.lines }];
    let meshes = [left.mesh, right.mesh];
    let mut views = Vec::with_capacity(2);
    render_compare_with(pixmap, &text, frame, s, &opts.theme, bar, |pm, k, mesh_frame| {
        let o = MeshView { frame: Some(mesh_frame), bounds: Some(bounds), colour_bar: false, ..*opts };
        views.push(render_mesh(pm, meshes[k], &o));
    });
    (views[0], views[1])
}

/// The words of one panel of [`render_compare_with`]: its title, and the statistics lines
/// under its picture.
#[derive(Clone, Copy, Debug)]
pub struct CompareText<'a> {
    pub title: &'a str,
    pub lines: &'a [String],
}

/// The colour bar [`render_compare_with`] draws under both panels: its label, the values
/// its ends stand for, the colour map, and the count of inverted elements it reports
/// (asked once the panels are drawn).
#[derive(Clone, Copy)]
pub struct CompareBar<'a> {
    pub label: &'a str,
    pub domain: (f64, f64),
    pub colormap: Colormap,
    pub inverted: &'a dyn Fn() -> usize,
}

/// The layout of a figure of two panels side by side in `frame` (CSS pixels, at ratio
/// `s`): each with its title above and its statistics lines below, and the colour bar
/// (when given) along the bottom; `draw(pixmap, k, frame)` draws panel `k`'s picture
/// (a planar mesh, a 3D view) into the frame left for it.
pub fn render_compare_with(
    pixmap: &mut Pixmap,
    panels: &[CompareText<'_>; 2],
    frame: Frame,
    s: f32,
    theme: &Theme,
    bar: Option<CompareBar<'_>>,
    mut draw: impl FnMut(&mut Pixmap, usize, Frame),
) {
    fill_rect(pixmap, frame.x * s, frame.y * s, frame.w * s, frame.h * s, theme.paper);
    let (title_h, line_h) = (TITLE_H * theme.grow(14.0), LINE_H * theme.grow(11.5));
    let band = bar.as_ref().and_then(|b| colour_bar_band(frame, b.label, theme));
    let bar_h = band.map_or(0.0, |b| b.h);
    let gap = 12.0;
    let col_w = (frame.w - gap) / 2.0;
    let rows = panels[0].lines.len().max(panels[1].lines.len()) as f32;
    let stats_h = if rows > 0.0 { rows * line_h + 8.0 } else { 0.0 };
    for (k, panel) in panels.iter().enumerate() {
        let x = frame.x + k as f32 * (col_w + gap);
        let mesh_frame = Frame::new(x, frame.y + title_h, col_w, frame.h - title_h - stats_h - bar_h);
        draw(pixmap, k, mesh_frame);
        let centre = x + 0.5 * col_w;
        let title = TextStyle::new(theme.text_px(14.0 * s, s)).with_color(theme.ink).with_align(Align::Centre, Valign::Baseline);
        draw_text(pixmap, panel.title, centre * s, (frame.y + 18.0 * theme.grow(14.0)) * s, title);
        let st = TextStyle::new(theme.text_px(11.5 * s, s)).with_color(theme.caption).with_align(Align::Centre, Valign::Baseline);
        for (i, line) in panel.lines.iter().enumerate() {
            let y = frame.bottom() - bar_h - stats_h + 4.0 + line_h * (i as f32 + 0.75);
            draw_text(pixmap, line, centre * s, y * s, st);
        }
    }
    if let (Some(band), Some(bar)) = (band, bar) {
        draw_colour_bar(pixmap, band, bar.colormap, bar.domain, bar.label, (bar.inverted)(), s, theme);
    }
}
