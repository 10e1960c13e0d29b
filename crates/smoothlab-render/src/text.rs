//! Text labels: glyph outlines of an embedded font rasterized by `ab_glyph`, blended
//! into the pixmap with a colour. tiny-skia has no text of its own.
//!
//! The font is a subset of DejaVu Sans (Latin, Greek, arrows and a few mathematical
//! signs; see `assets/fonts/README.md`), built in as tables (`super::font`).
//! Characters outside the subset draw as the font's missing-glyph box.

use ab_glyph::point;
use tiny_skia::{Color, Pixmap, PixmapPaint, PremultipliedColorU8, Transform};

use super::font::{self, glyph_id, Scaled};

/// Horizontal placement of a label relative to its anchor point.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Align {
    #[default]
    Left,
    Centre,
    Right,
}

/// Vertical placement of a label relative to its anchor point.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Valign {
    /// The anchor is on the top of the tallest letters.
    Top,
    /// The anchor is half-way up the capitals.
    #[default]
    Middle,
    /// The anchor is on the baseline.
    Baseline,
    /// The anchor is under the descenders.
    Bottom,
}

/// How a label is drawn: size in device pixels, colour, placement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextStyle {
    /// Font size (em height) in device pixels. Default 12.
    pub size: f32,
    /// Default black.
    pub color: Color,
    pub align: Align,
    pub valign: Valign,
}

impl Default for TextStyle {
    fn default() -> Self {
        TextStyle { size: 12.0, color: Color::BLACK, align: Align::Left, valign: Valign::Middle }
    }
}

impl TextStyle {
    pub fn new(size: f32) -> Self {
        TextStyle { size, ..Default::default() }
    }
    pub fn with_color(mut self, color: Color) -> Self {
        self.color = color;
        self
    }
    pub fn with_align(mut self, align: Align, valign: Valign) -> Self {
        self.align = align;
        self.valign = valign;
        self
    }
}

/// The font size, at most `size`, at which `text` is at most `width` device pixels wide
/// (a title or count that would not fit its frame is drawn smaller, not clipped).
pub fn size_to_fit(text: &str, size: f32, width: f32) -> f32 {
    let wide = text_width(text, size);
    if wide > width && wide > 0.0 {
        size * width.max(0.0) / wide
    } else {
        size
    }
}

/// `text` as it fits `width` device pixels at `size`: whole when it fits, else as many of
/// its leading words as fit and "…" (a title already drawn at the smallest legible size
/// that would still run past its frame, which clipped it at both ends when centred).
pub fn fit_words(text: &str, size: f32, width: f32) -> std::borrow::Cow<'_, str> {
    if text_width(text, size) <= width {
        return text.into();
    }
    let mut cut = text.len();
    while let Some(space) = text[..cut].rfind(' ') {
        cut = space;
        let shown = format!("{}…", text[..cut].trim_end_matches([',', ':', ';', ' ']));
        if text_width(&shown, size) <= width {
            return shown.into();
        }
    }
    "…".into()
}

/// Width in device pixels of `text` at `size`.
pub fn text_width(text: &str, size: f32) -> f32 {
    let f = Scaled::new(size.max(0.0));
    let mut w = 0.0;
    let mut prev = None;
    for c in text.chars() {
        let id = glyph_id(c);
        if let Some(p) = prev {
            w += f.kern(p, id);
        }
        w += f.h_advance(id);
        prev = Some(id);
    }
    w
}

/// Offset from the anchor to the pen origin (left end of the baseline).
fn origin(text: &str, x: f32, y: f32, style: &TextStyle) -> (f32, f32) {
    let f = Scaled::new(style.size);
    let w = text_width(text, style.size);
    let x0 = match style.align {
        Align::Left => x,
        Align::Centre => x - 0.5 * w,
        Align::Right => x - w,
    };
    // Cap height of DejaVu Sans is 0.729 em.
    let y0 = match style.valign {
        Valign::Top => y + f.ascent(),
        Valign::Middle => y + 0.5 * 0.729 * style.size,
        Valign::Baseline => y,
        Valign::Bottom => y + f.descent(),
    };
    (x0, y0)
}

/// The box `[x, y, w, h]` (device pixels) `text` takes when drawn with its anchor at
/// `(x, y)`: from the top of the tallest letters to under the descenders.
pub(crate) fn text_box(text: &str, x: f32, y: f32, style: &TextStyle) -> [f32; 4] {
    let (x0, base) = origin(text, x, y, style);
    let f = Scaled::new(style.size);
    [x0, base - f.ascent(), text_width(text, style.size), f.ascent() - f.descent()]
}

/// A positive finite size at a finite anchor.
fn drawable(style: &TextStyle, x: f32, y: f32) -> bool {
    style.size.is_finite() && style.size > 0.0 && x.is_finite() && y.is_finite()
}

/// Draws `text` with its anchor at device pixel `(x, y)`. Glyphs are blended into the
/// pixmap by their coverage; parts outside the pixmap are clipped. Its box is noted
/// ([`layout`](super::layout)) when recording.
pub fn draw_text(pixmap: &mut Pixmap, text: &str, x: f32, y: f32, style: TextStyle) {
    if !drawable(&style, x, y) {
        return;
    }
    if !text.trim().is_empty() {
        super::layout::note_text(pixmap, text, x, y, &style);
    }
    draw_glyphs(pixmap, text, x, y, style);
}

/// Draws `text` as [`draw_text`] does, unnoted (a scratch pixmap's text).
fn draw_glyphs(pixmap: &mut Pixmap, text: &str, x: f32, y: f32, style: TextStyle) {
    #[cfg(test)]
    if !text.trim().is_empty() {
        SMALLEST.with(|c| c.set(c.get().min(style.size)));
    }
    let (mut caret, base) = origin(text, x, y, &style);
    let f = Scaled::new(style.size);
    let (w, h) = (pixmap.width() as i64, pixmap.height() as i64);
    let c = style.color;
    let (r, g, b, a) = (c.red(), c.green(), c.blue(), c.alpha());
    let pixels = pixmap.pixels_mut();
    let mut prev = None;
    for ch in text.chars() {
        let id = glyph_id(ch);
        if let Some(p) = prev {
            caret += f.kern(p, id);
        }
        let glyph = id.with_scale_and_position(style.size, point(caret, base));
        caret += f.h_advance(id);
        prev = Some(id);
        let Some(outlined) = font::outline_glyph(glyph) else { continue };
        let bb = outlined.px_bounds();
        let (bx, by) = (bb.min.x as i64, bb.min.y as i64);
        outlined.draw(|gx, gy, cov| {
            let (px, py) = (bx + gx as i64, by + gy as i64);
            if px < 0 || py < 0 || px >= w || py >= h {
                return;
            }
            let sa = a * cov.clamp(0.0, 1.0);
            if sa <= 0.0 {
                return;
            }
            let d = &mut pixels[(py * w + px) as usize];
            let k = 1.0 - sa;
            let to = |s: f32, dc: u8| ((s * sa) * 255.0 + dc as f32 * k).round().clamp(0.0, 255.0) as u8;
            let na = to(1.0, d.alpha());
            let (nr, ng, nb) = (to(r, d.red()).min(na), to(g, d.green()).min(na), to(b, d.blue()).min(na));
            if let Some(p) = PremultipliedColorU8::from_rgba(nr, ng, nb, na) {
                *d = p;
            }
        });
    }
}

#[cfg(test)]
thread_local! {
    /// The smallest size (device pixels) of a non-blank text drawn on this thread since
    /// [`take_smallest_text`] was last called: what the label size tests read.
    static SMALLEST: std::cell::Cell<f32> = const { std::cell::Cell::new(f32::INFINITY) };
}

/// The smallest size (device pixels) of a non-blank text drawn on this thread since the
/// last call (∞ when none was), and starts again.
#[cfg(test)]
pub(crate) fn take_smallest_text() -> f32 {
    SMALLEST.with(|c| c.replace(f32::INFINITY))
}

/// Draws `text` turned by `angle_deg` (clockwise on screen, e.g. −90 for a y-axis
/// label read bottom to top) about its anchor `(x, y)`.
pub fn draw_text_rotated(pixmap: &mut Pixmap, text: &str, x: f32, y: f32, style: TextStyle, angle_deg: f32) {
    if !drawable(&style, x, y) || !angle_deg.is_finite() {
        return;
    }
    let f = Scaled::new(style.size);
    let tw = text_width(text, style.size).ceil() + 4.0;
    let th = (f.ascent() - f.descent()).ceil() + 4.0;
    let Some(mut tmp) = Pixmap::new(tw.max(1.0) as u32, th.max(1.0) as u32) else { return };
    // Draw unrotated at (2, 2 + ascent) in the scratch pixmap, then place it so the anchor
    // lands on (x, y).
    let local = TextStyle { align: Align::Left, valign: Valign::Baseline, ..style };
    draw_glyphs(&mut tmp, text, 2.0, 2.0 + f.ascent(), local);
    let (ox, oy) = origin(text, 0.0, 0.0, &style);
    // anchor in scratch coordinates
    let (ax, ay) = (2.0 - ox, 2.0 + f.ascent() - oy);
    let t = Transform::from_translate(x, y).pre_rotate(angle_deg).pre_translate(-ax, -ay);
    let paint = PixmapPaint { quality: tiny_skia::FilterQuality::Bilinear, ..Default::default() };
    pixmap.draw_pixmap(0, 0, tmp.as_ref(), &paint, t, None);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn embedded_font_has_the_glyphs_we_label_with() {
        for c in "αβκθω°−0123456789.,()/%ABCxyz≤∞→".chars() {
            assert_ne!(glyph_id(c).0, 0, "missing glyph for {c:?}");
        }
    }

    #[test]
    fn width_grows_with_text_and_size() {
        let a = text_width("min angle", 12.0);
        assert!(a > 40.0 && a < 80.0, "{a}");
        assert!((text_width("min angle", 24.0) - 2.0 * a).abs() < 0.5);
        assert_eq!(text_width("", 12.0), 0.0);
    }

    #[test]
    fn draws_inside_its_box_and_clips() {
        let mut p = Pixmap::new(80, 30).unwrap();
        p.fill(Color::WHITE);
        draw_text(&mut p, "Hg", 10.0, 15.0, TextStyle::new(16.0));
        let dark: Vec<(u32, u32)> = (0..30u32)
            .flat_map(|y| (0..80u32).map(move |x| (x, y)))
            .filter(|&(x, y)| p.pixel(x, y).unwrap().red() < 128)
            .collect();
        assert!(dark.len() > 20);
        let w = text_width("Hg", 16.0);
        assert!(dark.iter().all(|&(x, _)| x >= 10 && (x as f32) <= 10.0 + w + 1.0));
        // off-pixmap text is clipped, not a panic
        draw_text(&mut p, "clipped", -30.0, -5.0, TextStyle::new(16.0));
        draw_text(&mut p, "clipped", 70.0, 29.0, TextStyle::new(16.0));
        draw_text_rotated(&mut p, "y label", 5.0, 15.0, TextStyle::new(10.0), -90.0);
    }
}
