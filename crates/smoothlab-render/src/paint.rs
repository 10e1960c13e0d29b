//! Small drawing helpers shared by the views: solid fills and strokes of whole paths,
//! point markers, and legends in a band of their own.

use tiny_skia::{Color, FillRule, Paint, PathBuilder, Pixmap, Rect, Stroke, StrokeDash, Transform};

use super::text::{draw_text, text_width, Align, TextStyle, Valign};
use super::theme::Theme;

/// The shape of a point marker.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Marker {
    #[default]
    Circle,
    Square,
    /// Pointing up.
    Triangle,
    Diamond,
    /// A five-pointed star.
    Star,
}

pub(crate) fn solid(c: Color) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color(c);
    p
}

pub(crate) fn rgba(r: u8, g: u8, b: u8, a: u8) -> Color {
    Color::from_rgba8(r, g, b, a)
}

/// Fills the path in `pb` (nonzero winding) and clears nothing: `pb` is consumed.
pub(crate) fn fill(pixmap: &mut Pixmap, pb: PathBuilder, c: Color, anti_alias: bool) {
    if let Some(path) = pb.finish() {
        let mut p = solid(c);
        p.anti_alias = anti_alias;
        pixmap.fill_path(&path, &p, FillRule::Winding, Transform::identity(), None);
    }
}

/// Strokes the path in `pb` with `width` device pixels, dashed when `dash` is given
/// (on, off lengths in device pixels).
pub(crate) fn stroke(pixmap: &mut Pixmap, pb: PathBuilder, c: Color, width: f32, dash: Option<[f32; 2]>) {
    if let Some(path) = pb.finish() {
        let s = Stroke {
            width,
            line_join: tiny_skia::LineJoin::Round,
            line_cap: tiny_skia::LineCap::Round,
            dash: dash.and_then(|d| StrokeDash::new(vec![d[0], d[1]], 0.0)),
            ..Default::default()
        };
        pixmap.stroke_path(&path, &solid(c), &s, Transform::identity(), None);
    }
}

/// Adds a marker of half-size `r` centred at `(x, y)` to `pb`.
pub(crate) fn push_marker(pb: &mut PathBuilder, m: Marker, x: f32, y: f32, r: f32) {
    if !(x.is_finite() && y.is_finite() && r > 0.0) {
        return;
    }
    match m {
        Marker::Circle => pb.push_circle(x, y, r),
        Marker::Square => {
            let r = 0.85 * r;
            if let Some(rect) = Rect::from_ltrb(x - r, y - r, x + r, y + r) {
                pb.push_rect(rect);
            }
        }
        Marker::Triangle => {
            pb.move_to(x, y - 1.15 * r);
            pb.line_to(x - r, y + 0.75 * r);
            pb.line_to(x + r, y + 0.75 * r);
            pb.close();
        }
        Marker::Diamond => {
            pb.move_to(x, y - 1.2 * r);
            pb.line_to(x + r, y);
            pb.line_to(x, y + 1.2 * r);
            pb.line_to(x - r, y);
            pb.close();
        }
        Marker::Star => {
            for k in 0..10 {
                let a = std::f32::consts::PI * (k as f32 / 5.0 - 0.5);
                let rr = if k % 2 == 0 { 1.3 * r } else { 0.55 * r };
                let (px, py) = (x + rr * a.cos(), y + rr * a.sin());
                if k == 0 {
                    pb.move_to(px, py);
                } else {
                    pb.line_to(px, py);
                }
            }
            pb.close();
        }
    }
}

/// How a marker is painted: half-size, fill, outline colour and width (device pixels).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct MarkerStyle {
    pub r: f32,
    pub fill: Color,
    pub edge: Color,
    pub width: f32,
}

/// A marker centred at `(x, y)`, filled and outlined.
pub(crate) fn draw_marker(pixmap: &mut Pixmap, m: Marker, x: f32, y: f32, st: MarkerStyle) {
    let mut pb = PathBuilder::new();
    push_marker(&mut pb, m, x, y, st.r);
    let pb2 = pb.clone();
    fill(pixmap, pb, st.fill, true);
    stroke(pixmap, pb2, st.edge, st.width, None);
}

/// What a legend entry shows beside its label.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Key {
    /// A line sample, dashed or solid, with an optional marker on it.
    Line { dashed: bool, marker: Option<Marker> },
    /// A marker alone.
    Marker(Marker),
    /// A filled square with a hatch.
    Hatched,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct LegendEntry<'a> {
    pub label: &'a str,
    pub color: Color,
    pub key: Key,
}

/// How a legend is drawn: the theme's colours and label rule, `s` scaling its sizes
/// (the device-pixel ratio, or a fraction of it) and `dpr` the device-pixel ratio the
/// theme's smallest label is measured at.
#[derive(Clone, Copy, Debug)]
pub(crate) struct LegendStyle<'a> {
    pub theme: &'a Theme,
    pub s: f32,
    pub dpr: f32,
    /// The largest label size, device pixels ([`LegendStyle::fitted`]); infinite: none.
    pub cap: f32,
}

impl<'a> LegendStyle<'a> {
    pub fn new(theme: &'a Theme, s: f32, dpr: f32) -> Self {
        LegendStyle { theme, s, dpr, cap: f32::INFINITY }
    }

    /// This style with its labels made small enough for the widest of `entries` to fit
    /// `width` device pixels: below the theme's smallest label if it must, for a legend
    /// that runs out of its band runs over the data beside it (a narrow panel of a figure
    /// in a small embed). Unchanged when every entry fits.
    pub fn fitted(&self, entries: &[LegendEntry<'_>], width: f32) -> Self {
        let widest = entries.iter().map(|e| text_width(e.label, self.text())).fold(0.0f32, f32::max);
        let room = width - 30.0 * self.s - 12.0 * self.s;
        if widest <= room || widest <= 0.0 {
            return *self;
        }
        LegendStyle { cap: (self.text() * room / widest).max(1.0), ..*self }
    }

    /// The label size, device pixels.
    pub fn text(&self) -> f32 {
        self.theme.text_px(11.0 * self.s, self.dpr).min(self.cap)
    }
    /// How much the labels grew over their own size (1 when they did not).
    pub fn grow(&self) -> f32 {
        self.text() / (11.0 * self.s)
    }
    /// The height of one entry, device pixels.
    pub fn line_h(&self) -> f32 {
        16.0 * self.s * self.grow()
    }
    /// The width of one entry: key, gap, label.
    pub fn entry_w(&self, e: &LegendEntry<'_>) -> f32 {
        24.0 * self.s + 6.0 * self.s + text_width(e.label, self.text())
    }
}

/// Entries in one row centred on `cx`, at height `cy` (device pixels), without a box.
pub(crate) fn legend_row(pixmap: &mut Pixmap, entries: &[LegendEntry<'_>], cx: f32, cy: f32, st: &LegendStyle<'_>) {
    let gap = 18.0 * st.s;
    let widths: Vec<f32> = entries.iter().map(|e| st.entry_w(e)).collect();
    let total = widths.iter().sum::<f32>() + gap * entries.len().saturating_sub(1) as f32;
    let mut x = cx - 0.5 * total;
    for (e, w) in entries.iter().zip(widths) {
        legend_entry(pixmap, e, x, cy, st);
        x += w + gap;
    }
}

/// The rows of a legend laid out in `width` device pixels: as many entries on a row as
/// fit (at least one), rows top to bottom.
pub(crate) fn legend_rows(entries: &[LegendEntry<'_>], width: f32, st: &LegendStyle<'_>) -> Vec<std::ops::Range<usize>> {
    let gap = 18.0 * st.s;
    let mut rows = Vec::new();
    let (mut start, mut used) = (0, 0.0f32);
    for (i, e) in entries.iter().enumerate() {
        let w = st.entry_w(e);
        if i > start && used + gap + w > width {
            rows.push(start..i);
            start = i;
            used = w;
        } else {
            used += if i > start { gap + w } else { w };
        }
    }
    if start < entries.len() {
        rows.push(start..entries.len());
    }
    rows
}

/// The height in device pixels of the band [`legend_band`] draws `entries` in, `width`
/// device pixels wide (0 with no entries).
pub(crate) fn legend_band_height(entries: &[LegendEntry<'_>], width: f32, st: &LegendStyle<'_>) -> f32 {
    let st = &st.fitted(entries, width);
    let rows = legend_rows(entries, width, st).len();
    if rows == 0 {
        0.0
    } else {
        rows as f32 * st.line_h() + 4.0 * st.s
    }
}

/// A legend outside the data: rows of entries, each row centred, in a band of `width`
/// device pixels whose top-left corner is `(x, y)`, without a box. Returns its height.
pub(crate) fn legend_band(pixmap: &mut Pixmap, entries: &[LegendEntry<'_>], x: f32, y: f32, width: f32, st: &LegendStyle<'_>) -> f32 {
    let st = &st.fitted(entries, width);
    let rows = legend_rows(entries, width, st);
    let line_h = st.line_h();
    let gap = 18.0 * st.s;
    let widest = rows
        .iter()
        .map(|r| entries[r.clone()].iter().map(|e| st.entry_w(e)).sum::<f32>() + gap * (r.len().saturating_sub(1)) as f32)
        .fold(0.0f32, f32::max);
    let h = legend_band_height(entries, width, st);
    // the box: 6 pixels of the style's scale round the widest row, within the band
    let (left, right) = ((x + 0.5 * (width - widest) - 6.0 * st.s).max(x), (x + 0.5 * (width + widest) + 6.0 * st.s).min(x + width));
    if let Some(r) = Rect::from_ltrb(left, y, right, y + h) {
        super::layout::note(pixmap, super::layout::RegionKind::Legend, r.x(), r.y(), r.width(), r.height());
        let pb = PathBuilder::from_rect(r);
        pixmap.fill_path(&pb, &solid(st.theme.legend_fill), FillRule::Winding, Transform::identity(), None);
        pixmap.stroke_path(&pb, &solid(st.theme.legend_border), &Stroke { width: st.s, ..Default::default() }, Transform::identity(), None);
    }
    for (k, r) in rows.iter().enumerate() {
        let cy = y + 2.0 * st.s + line_h * (k as f32 + 0.5);
        legend_row(pixmap, &entries[r.clone()], x + 0.5 * width, cy, st);
    }
    h
}

/// One legend entry: its key from `kx`, its label after it, centred on `cy`.
fn legend_entry(pixmap: &mut Pixmap, e: &LegendEntry<'_>, kx: f32, cy: f32, st: &LegendStyle<'_>) {
    let s = st.s;
    let size = st.text();
    let key_w = 24.0 * s;
    let pad = 6.0 * s;
    {
        match e.key {
            Key::Line { dashed, marker } => {
                let mut pb = PathBuilder::new();
                pb.move_to(kx, cy);
                pb.line_to(kx + key_w, cy);
                stroke(pixmap, pb, e.color, 2.0 * s, dashed.then_some([5.0 * s, 3.0 * s]));
                if let Some(m) = marker {
                    draw_marker(pixmap, m, kx + 0.5 * key_w, cy, MarkerStyle { r: 3.5 * s, fill: e.color, edge: e.color, width: s });
                }
            }
            Key::Marker(m) => draw_marker(pixmap, m, kx + 0.5 * key_w, cy, MarkerStyle { r: 4.5 * s, fill: e.color, edge: st.theme.ink, width: s }),
            Key::Hatched => {
                if let Some(r) = Rect::from_xywh(kx + 4.0 * s, cy - 5.0 * s, key_w - 8.0 * s, 10.0 * s) {
                    let pb = PathBuilder::from_rect(r);
                    pixmap.fill_path(&pb, &solid(e.color), FillRule::Winding, Transform::identity(), None);
                    {
                        let mut h = PathBuilder::new();
                        let mut t = r.left() - r.height();
                        while t < r.right() {
                            h.move_to(t, r.bottom());
                            h.line_to(t + r.height(), r.top());
                            t += 4.0 * s;
                        }
                        if let (Some(path), Some(mask)) = (h.finish(), rect_mask(pixmap, r)) {
                            let st = Stroke { width: 1.2 * s, ..Default::default() };
                            pixmap.stroke_path(&path, &solid(rgba(0, 0, 0, 255)), &st, Transform::identity(), Some(&mask));
                        }
                    }
                    pixmap.stroke_path(&pb, &solid(rgba(0, 0, 0, 160)), &Stroke { width: s, ..Default::default() }, Transform::identity(), None);
                }
            }
        }
        let style = TextStyle::new(size).with_color(st.theme.ink).with_align(Align::Left, Valign::Middle);
        draw_text(pixmap, e.label, kx + key_w + pad, cy, style);
    }
}

/// A mask that lets through only the rectangle `r`.
pub(crate) fn rect_mask(pixmap: &Pixmap, r: Rect) -> Option<tiny_skia::Mask> {
    let mut m = tiny_skia::Mask::new(pixmap.width(), pixmap.height())?;
    m.fill_path(&PathBuilder::from_rect(r), FillRule::Winding, false, Transform::identity());
    Some(m)
}

/// Fills the device rectangle `(x, y, w, h)` (ignored when empty).
pub(crate) fn fill_rect(pixmap: &mut Pixmap, x: f32, y: f32, w: f32, h: f32, c: Color) {
    if let Some(r) = Rect::from_xywh(x, y, w, h) {
        pixmap.fill_rect(r, &solid(c), Transform::identity(), None);
    }
}
