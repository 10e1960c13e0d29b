//! The colours and the label size rule every picture is drawn with: one [`Theme`] in the
//! options of each view (no global state), so a view added later needs the theme and no
//! colour literals of its own.
//!
//! What a theme changes is what sits on the paper: the paper itself, text, frames, grid
//! lines, legend boxes, the first series' colour and the two sides' colours. What sits on
//! the data keeps its colours in every theme: the quality colour map, the inverted
//! elements' red and hatching, the solver's path and markers, the highlighted star.

use std::borrow::Cow;

use tiny_skia::Color;

use super::colormap::SERIES;
use super::text::{fit_words, size_to_fit};

/// The colours and label sizes of every picture. [`Theme::light`] (the default) is the
/// picture as the CLI has always drawn it; [`Theme::dark`] is for projectors.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Theme {
    /// The background every view paints first.
    pub paper: Color,
    /// Titles and text drawn without a colour of its own, marker outlines in legends, a
    /// mesh's boundary edges and a sketch's fixed segment.
    pub ink: Color,
    /// Tick labels, ticks, plot frames, break marks.
    pub text: Color,
    /// Axis labels and the values written beside points in a broken axis's band.
    pub label: Color,
    /// The colour bar's labels and frame and the statistics lines under a mesh.
    pub caption: Color,
    /// Secondary text: a level-set panel's note on which bands are better.
    pub muted: Color,
    /// Text that says something is missing ("no data").
    pub faint: Color,
    /// Grid lines of charts and histograms.
    pub grid: Color,
    /// A legend box's fill.
    pub legend_fill: Color,
    /// A legend box's border.
    pub legend_border: Color,
    /// The band under a broken y axis.
    pub band: Color,
    /// Dashed reference lines (a histogram's 60° and 90°).
    pub reference: Color,
    /// The light fill under a histogram's first (reference) series.
    pub shade: Color,
    /// Dashed segments of a sketch (a discontinuity's ray).
    pub dashed: Color,
    /// The first colour of the series palette ([`SERIES`]'s black in the light theme).
    pub series0: Color,
    /// The colours of the page's two sides (A, B), sRGB.
    pub sides: [[u8; 3]; 2],
    /// The smallest label, CSS pixels: every text is drawn at least this large (times the
    /// pixel ratio), and plots shrink to make room. 0 keeps each label's own size.
    pub min_label_px: f32,
}

impl Default for Theme {
    fn default() -> Self {
        Theme::light()
    }
}

fn rgba(r: u8, g: u8, b: u8, a: u8) -> Color {
    Color::from_rgba8(r, g, b, a)
}

impl Theme {
    /// Black on white, each label at its own size: the pictures as they always were.
    pub fn light() -> Theme {
        Theme {
            paper: Color::WHITE,
            ink: Color::BLACK,
            text: rgba(40, 40, 40, 255),
            label: rgba(20, 20, 20, 255),
            caption: rgba(30, 30, 30, 255),
            muted: rgba(80, 80, 80, 255),
            faint: rgba(120, 120, 120, 255),
            grid: rgba(0, 0, 0, 28),
            legend_fill: rgba(255, 255, 255, 225),
            legend_border: rgba(0, 0, 0, 90),
            band: rgba(238, 238, 238, 255),
            reference: rgba(0, 0, 0, 70),
            shade: rgba(0, 0, 0, 38),
            dashed: rgba(90, 90, 90, 255),
            series0: rgba(SERIES[0][0], SERIES[0][1], SERIES[0][2], 255),
            sides: [SERIES[1], SERIES[2]],
            min_label_px: 0.0,
        }
    }

    /// A projector theme: light ink on a dark paper (#14171b), grid lines that stay
    /// visible, the right side in sky blue (the light theme's blue is too dark on this
    /// paper), labels at least 14 CSS pixels.
    pub fn dark() -> Theme {
        Theme {
            paper: rgba(20, 23, 27, 255),
            ink: rgba(236, 238, 241, 255),
            text: rgba(204, 208, 214, 255),
            label: rgba(222, 225, 230, 255),
            caption: rgba(214, 218, 224, 255),
            muted: rgba(168, 174, 183, 255),
            faint: rgba(140, 146, 155, 255),
            grid: rgba(255, 255, 255, 44),
            legend_fill: rgba(30, 34, 40, 235),
            legend_border: rgba(255, 255, 255, 90),
            band: rgba(44, 49, 57, 255),
            reference: rgba(255, 255, 255, 96),
            shade: rgba(255, 255, 255, 46),
            dashed: rgba(170, 174, 180, 255),
            series0: rgba(236, 238, 241, 255),
            sides: [SERIES[1], SERIES[5]],
            min_label_px: 14.0,
        }
    }

    /// The light or dark theme with labels of at least `label_px` CSS pixels (a value
    /// that is not finite or below 0 counts as 0): what the page asks for.
    pub fn for_page(dark: bool, label_px: f32) -> Theme {
        let base = if dark { Theme::dark() } else { Theme::light() };
        base.with_min_label(label_px)
    }

    /// This theme with labels of at least `px` CSS pixels (clamped to 0..=64).
    pub fn with_min_label(mut self, px: f32) -> Theme {
        self.min_label_px = if px.is_finite() { px.clamp(0.0, 64.0) } else { 0.0 };
        self
    }

    /// The size to draw a label at: `size` device pixels, or the theme's minimum at
    /// pixel ratio `dpr` when that is larger.
    pub fn text_px(&self, size: f32, dpr: f32) -> f32 {
        size.max(self.min_label_px * dpr)
    }

    /// A label of `size` device pixels fitted to `room` device pixels, and the size to draw
    /// it at: smaller where it is wider, never below this theme's smallest label
    /// ([`text_px`](Self::text_px)), and where even that is too wide, its leading words and
    /// "…": shrunk or cut in a narrow frame, never clipped.
    pub fn fit_label<'a>(&self, text: &'a str, size: f32, room: f32, dpr: f32) -> (Cow<'a, str>, f32) {
        let size = self.text_px(size_to_fit(text, size, room), dpr);
        (fit_words(text, size, room), size)
    }

    /// A title fitted to `room` device pixels as [`fit_label`](Self::fit_label) fits it, but
    /// where it is too wide at the smallest label, its leading clauses (up to a ",", ":",
    /// ";" or " (") that fit, whole words that read as a title — so long as the clauses
    /// left out hold no digit: a title's numbers (a count, a pass, a value) are its point,
    /// and a title that cannot keep them all is cut with "…", which shows (and which the
    /// layout records as cut). "…" too when even the first clause is too wide.
    pub fn fit_title<'a>(&self, text: &'a str, size: f32, room: f32, dpr: f32) -> (Cow<'a, str>, f32) {
        let (shown, size) = self.fit_label(text, size, room, dpr);
        if shown == text {
            return (shown, size);
        }
        let mut ends = text.match_indices([',', ':', ';', '(']).map(|(i, c)| if c == "(" { i.saturating_sub(1) } else { i });
        let keeps_numbers = |i: usize| !text[i..].contains(|c: char| c.is_ascii_digit());
        let fitting = ends.rfind(|&i| i > 0 && keeps_numbers(i) && super::text::text_width(&text[..i], size) <= room);
        match fitting {
            Some(i) => (text[..i].trim_end().into(), size),
            None => (shown, size),
        }
    }

    /// How much a label meant to be `css` CSS pixels grows under this theme: 1 when it is
    /// at least the minimum, else minimum / `css`. Room made for such a label (a margin,
    /// a line height) grows by the same factor.
    pub fn grow(&self, css: f32) -> f32 {
        if css > 0.0 && self.min_label_px > css {
            self.min_label_px / css
        } else {
            1.0
        }
    }

    /// The colour of series `i` ([`SERIES`] in turn, its first colour the theme's).
    pub fn series(&self, i: usize) -> Color {
        if i % SERIES.len() == 0 {
            self.series0
        } else {
            super::colormap::series_color(i)
        }
    }

    /// The colour of side `i` (0: A, 1: B).
    pub fn side(&self, i: usize) -> Color {
        let [r, g, b] = self.sides[i.min(1)];
        rgba(r, g, b, 255)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn light_keeps_every_size_and_dark_raises_them() {
        let l = Theme::light();
        for (size, dpr) in [(9.9f32, 1.0f32), (11.0, 2.0), (14.0, 1.5)] {
            assert_eq!(l.text_px(size * dpr, dpr), size * dpr);
            assert_eq!(l.grow(size), 1.0);
        }
        let d = Theme::dark();
        assert_eq!(d.text_px(11.0 * 2.0, 2.0), 28.0);
        assert_eq!(d.text_px(15.0, 1.0), 15.0);
        assert!((d.grow(11.0) - 14.0 / 11.0).abs() < 1e-6);
        assert_eq!(Theme::for_page(false, 14.0).min_label_px, 14.0);
        assert_eq!(Theme::for_page(true, f32::NAN).min_label_px, 0.0);
        assert_eq!(Theme::for_page(true, 14.0).paper, Theme::dark().paper);
    }

    #[test]
    fn a_title_too_wide_keeps_its_leading_clauses() {
        let t = Theme::light().with_min_label(14.0);
        let title = "B: new: Chen, Tristano & Kwok (Fletcher–Reeves), barrier";
        let room = super::super::text::text_width("B: new: Chen, Tristano & Kwok", 14.0) + 4.0;
        assert_eq!(t.fit_title(title, 14.0, room, 1.0).0, "B: new: Chen, Tristano & Kwok");
        assert_eq!(t.fit_title(title, 14.0, 1000.0, 1.0).0, title);
        assert!(t.fit_title("one long clause without a comma", 14.0, 60.0, 1.0).0.ends_with('…'));
    }

    #[test]
    fn a_title_never_drops_a_clause_that_holds_a_number() {
        // issue 59: "A, pass 1: 63 inverted" kept as "A, pass 1" lost its count, unseen
        let t = Theme::light().with_min_label(14.0);
        let width = |s: &str| super::super::text::text_width(s, 14.0);
        let title = "A, pass 1: 63 inverted";
        let shown = t.fit_title(title, 14.0, width("A, pass 1") + 4.0, 1.0).0;
        assert!(shown.ends_with('…'), "{shown}");
        // a clause without a number still goes, the numbers kept
        let title = "after 3 passes: 12 inverted, both orders";
        let kept = "after 3 passes: 12 inverted";
        assert_eq!(t.fit_title(title, 14.0, width(kept) + 4.0, 1.0).0, kept);
        for room in (40..400).step_by(7) {
            let shown = t.fit_title(title, 14.0, room as f32, 1.0).0;
            let digits = |s: &str| s.chars().filter(char::is_ascii_digit).collect::<String>();
            assert!(shown.ends_with('…') || digits(&shown) == digits(title), "{room} px: {shown}");
        }
    }

    #[test]
    fn dark_ink_and_grid_stand_out_from_the_paper_and_the_sides_apart() {
        let luma = |c: Color| 0.2126 * c.red() + 0.7152 * c.green() + 0.0722 * c.blue();
        let d = Theme::dark();
        let paper = luma(d.paper);
        for c in [d.ink, d.text, d.label, d.caption, d.muted, d.faint, d.series0] {
            assert!(luma(c) - paper > 0.45, "{c:?} on the dark paper");
        }
        // a grid line over the paper: at least 10 levels of 255 lighter
        let over = d.grid.alpha() * (d.grid.red() - d.paper.red());
        assert!(over * 255.0 >= 10.0, "grid {over}");
        let (a, b) = (d.side(0), d.side(1));
        assert!(luma(a) - paper > 0.3 && luma(b) - paper > 0.3);
        assert!((a.red() - b.red()).abs() + (a.blue() - b.blue()).abs() > 0.8, "the sides differ");
    }
}
