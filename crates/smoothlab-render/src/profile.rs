//! The views of a figure the playground has no panel for: a sketch of a triangle with
//! the lines its free corner C moves along (Chen et al. 2003, Figs. 2, 5, 6), so that a
//! 1-D curve of a metric along such a line ([`render_chart`](super::render_chart)) can
//! be read beside it, and a titled grid of pictures ([`render_titled`]).

use glam::DVec2;
use tiny_skia::{Color, PathBuilder, Pixmap, PixmapPaint, Transform};

use super::paint::{draw_marker, fill_rect, stroke, MarkerStyle};
use super::text::{draw_text, size_to_fit, Align, TextStyle, Valign};
use super::theme::Theme;
use super::view::{sane_dpr, Frame, View, ZoomPan};
use super::Marker;

/// A line along which the free corner moves, from `from` to `to`, with its colour and label.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SketchLine<'a> {
    pub from: DVec2,
    pub to: DVec2,
    pub color: Color,
    pub label: &'a str,
}

/// What [`render_sketch`] draws: the fixed corners (labelled), the lines C moves along,
/// and dashed rays (a discontinuity, as Fig. 6's ray x = 0, y > 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sketch<'a> {
    pub title: &'a str,
    /// Fixed points with their labels (A, B).
    pub points: &'a [(DVec2, &'a str)],
    pub lines: &'a [SketchLine<'a>],
    /// Dashed segments.
    pub dashed: &'a [(DVec2, DVec2)],
}

/// Draws `sketch` into `frame` (CSS pixels) at pixel ratio `dpr` in `theme`: the segment
/// joining the fixed points, each line in its colour with its label at its end, the
/// dashed segments.
pub fn render_sketch(pixmap: &mut Pixmap, sketch: &Sketch<'_>, frame: Frame, dpr: f32, theme: &Theme) {
    let s = sane_dpr(dpr);
    fill_rect(pixmap, frame.x * s, frame.y * s, frame.w * s, frame.h * s, theme.paper);
    let (shown, size) = theme.fit_title(sketch.title, 13.0 * s, (frame.w - 8.0) * s, s);
    draw_text(
        pixmap,
        &shown,
        (frame.x + frame.w / 2.0) * s,
        (frame.y + 4.0) * s,
        TextStyle::new(size).with_color(theme.ink).with_align(Align::Centre, Valign::Top),
    );
    let inner = frame.inset(0.0, 24.0 * theme.grow(13.0), 0.0, 0.0);
    let mut lo = DVec2::splat(f64::INFINITY);
    let mut hi = DVec2::splat(f64::NEG_INFINITY);
    let pts = sketch.points.iter().map(|p| p.0).chain(sketch.lines.iter().flat_map(|l| [l.from, l.to]));
    for p in pts.chain(sketch.dashed.iter().flat_map(|d| [d.0, d.1])) {
        lo = lo.min(p);
        hi = hi.max(p);
    }
    let view = View::fit(lo, hi, inner, 24.0, ZoomPan::default(), s);
    super::layout::note(pixmap, super::layout::RegionKind::Plot, inner.x * s, inner.y * s, inner.w * s, inner.h * s);
    let xy = |p: DVec2| view.device_xy(p);
    for &(a, b) in sketch.dashed {
        let mut pb = PathBuilder::new();
        let (x0, y0) = xy(a);
        let (x1, y1) = xy(b);
        pb.move_to(x0, y0);
        pb.line_to(x1, y1);
        stroke(pixmap, pb, theme.dashed, 1.2 * s, Some([5.0 * s, 4.0 * s]));
    }
    for l in sketch.lines {
        let mut pb = PathBuilder::new();
        let (x0, y0) = xy(l.from);
        let (x1, y1) = xy(l.to);
        pb.move_to(x0, y0);
        pb.line_to(x1, y1);
        stroke(pixmap, pb, l.color, 2.0 * s, None);
        draw_text(pixmap, l.label, x1 - 2.0 * s, y1 - 3.0 * s, TextStyle::new(theme.text_px(11.0 * s, s)).with_color(l.color).with_align(Align::Right, Valign::Bottom));
    }
    if sketch.points.len() > 1 {
        let mut pb = PathBuilder::new();
        for (i, (p, _)) in sketch.points.iter().enumerate() {
            let (x, y) = xy(*p);
            if i == 0 {
                pb.move_to(x, y);
            } else {
                pb.line_to(x, y);
            }
        }
        stroke(pixmap, pb, theme.ink, 2.0 * s, None);
    }
    for (p, label) in sketch.points {
        let (x, y) = xy(*p);
        draw_marker(pixmap, Marker::Circle, x, y, MarkerStyle { r: 4.0 * s, fill: theme.ink, edge: theme.paper, width: 1.0 * s });
        draw_text(pixmap, label, x + 6.0 * s, y - 4.0 * s, TextStyle::new(theme.text_px(13.0 * s, s)).with_color(theme.ink).with_align(Align::Left, Valign::Bottom));
    }
}

/// Places `parts` (pictures at pixel ratio `dpr`) in a grid of `cols` columns under a
/// title, on `theme`'s paper, each cell the size of the largest part: one picture of
/// several panels.
pub fn render_titled(parts: &[Pixmap], cols: usize, title: &str, dpr: f32, theme: &Theme) -> Option<Pixmap> {
    let s = sane_dpr(dpr);
    let cols = cols.clamp(1, parts.len().max(1));
    let rows = parts.len().div_ceil(cols).max(1);
    let cw = parts.iter().map(|p| p.width()).max()?;
    let ch = parts.iter().map(|p| p.height()).max()?;
    let head = (title_band(theme) * s).round() as u32;
    let mut out = Pixmap::new(cw * cols as u32, head + ch * rows as u32)?;
    super::layout::forget(&out);
    out.fill(theme.paper);
    let size = size_to_fit(title, 15.0, out.width() as f32 / s - 16.0);
    let mid = out.width() as f32 / 2.0;
    let style = TextStyle::new(theme.text_px(size * s, s)).with_color(theme.ink).with_align(Align::Centre, Valign::Top);
    draw_text(&mut out, title, mid, 6.0 * s, style);
    for (i, p) in parts.iter().enumerate() {
        let (x, y) = ((i % cols) as u32 * cw, head + (i / cols) as u32 * ch);
        out.draw_pixmap(x as i32, y as i32, p.as_ref(), &PixmapPaint::default(), Transform::identity(), None);
        super::layout::adopt(p, &out, x as f32, y as f32);
    }
    Some(out)
}

/// The height of [`render_titled`]'s title band, CSS pixels: 28, grown with the theme's
/// labels.
pub fn title_band(theme: &Theme) -> f32 {
    28.0 * theme.grow(15.0)
}
