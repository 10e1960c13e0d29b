//! Axes of the charts: "nice" tick values (the 1-2-5 rule), decade ticks for log
//! scales, tick labels, and the drawing of a plot box with its ticks and labels.

use tiny_skia::{Paint, PathBuilder, Pixmap, Stroke, Transform};

use super::layout::note_label;
use super::text::{draw_text, draw_text_rotated, text_box, Align, TextStyle, Valign};
use super::theme::Theme;

/// Tick values along an axis and their spacing.
#[derive(Clone, Debug, PartialEq)]
pub struct Ticks {
    /// Distance between ticks (for log axes: 1 decade, or the linear step inside one).
    pub step: f64,
    pub values: Vec<f64>,
}

/// The 1-2-5 step for showing `range` with at most about `max_ticks` intervals:
/// the smallest of 1, 2, 5 × 10^k that is at least `range / max_ticks`.
pub fn nice_step(range: f64, max_ticks: usize) -> f64 {
    let range = if range.is_finite() && range > 0.0 { range } else { 1.0 };
    let raw = range / max_ticks.max(1) as f64;
    let mag = 10f64.powf(raw.log10().floor());
    let norm = raw / mag;
    let f = if norm <= 1.0 + 1e-9 {
        1.0
    } else if norm <= 2.0 + 1e-9 {
        2.0
    } else if norm <= 5.0 + 1e-9 {
        5.0
    } else {
        10.0
    };
    f * mag
}

/// Ticks at the multiples of [`nice_step`] that lie in `[lo, hi]` (the order of `lo` and
/// `hi` does not matter). An empty or non-finite range is widened around its value.
pub fn nice_ticks(lo: f64, hi: f64, max_ticks: usize) -> Ticks {
    let (lo, hi) = sane_range(lo, hi);
    let step = nice_step(hi - lo, max_ticks);
    let first = (lo / step - 1e-9).ceil() as i64;
    let last = (hi / step + 1e-9).floor() as i64;
    let values = (first..=last).map(|k| clean(k as f64 * step)).collect();
    Ticks { step, values }
}

/// The range `[lo, hi]` widened outwards to multiples of its nice step.
pub fn nice_range(lo: f64, hi: f64, max_ticks: usize) -> (f64, f64) {
    let (lo, hi) = sane_range(lo, hi);
    let step = nice_step(hi - lo, max_ticks);
    (clean((lo / step + 1e-9).floor() * step), clean((hi / step - 1e-9).ceil() * step))
}

/// Ticks of a log axis over `[lo, hi]` (both > 0): the powers of ten inside, and when
/// the range spans fewer than three decades also 2× and 5× of them.
pub fn log_ticks(lo: f64, hi: f64) -> Ticks {
    let (lo, hi) = sane_log_range(lo, hi);
    let (a, b) = (lo.log10(), hi.log10());
    let (k0, k1) = ((a - 1e-9).floor() as i32, (b + 1e-9).ceil() as i32);
    let dense = b - a < 3.0;
    let mut values = Vec::new();
    for k in k0..=k1 {
        let p = 10f64.powi(k);
        for m in if dense { &[1.0, 2.0, 5.0][..] } else { &[1.0][..] } {
            let v = m * p;
            if v >= lo * (1.0 - 1e-9) && v <= hi * (1.0 + 1e-9) {
                values.push(v);
            }
        }
    }
    Ticks { step: 10.0, values }
}

/// Turns `-0.0` and rounding dust like `0.30000000000000004` into clean values.
fn clean(v: f64) -> f64 {
    if v == 0.0 {
        return 0.0;
    }
    let s = format!("{v:.12e}");
    s.parse().unwrap_or(v)
}

fn sane_range(lo: f64, hi: f64) -> (f64, f64) {
    if !lo.is_finite() || !hi.is_finite() {
        return (0.0, 1.0);
    }
    let (mut lo, mut hi) = (lo.min(hi), lo.max(hi));
    if hi - lo <= 1e-12 * lo.abs().max(hi.abs()) || hi == lo {
        let d = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
        lo -= d;
        hi += d;
    }
    (lo, hi)
}

fn sane_log_range(lo: f64, hi: f64) -> (f64, f64) {
    if !(lo > 0.0 && hi > 0.0 && lo.is_finite() && hi.is_finite()) {
        return (1.0, 10.0);
    }
    let (mut lo, mut hi) = (lo.min(hi), lo.max(hi));
    if lo.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return (1.0, 10.0);
    }
    if hi <= lo * (1.0 + 1e-12) {
        lo /= 2.0;
        hi *= 2.0;
    }
    (lo, hi)
}

/// A tick label: as many decimals as `step` needs, scientific notation for very large
/// or small numbers, and a true minus sign.
pub fn format_tick(v: f64, step: f64) -> String {
    let s = if v == 0.0 {
        "0".to_string()
    } else if v.abs() >= 1e5 || v.abs() < 1e-4 || (step.is_finite() && step > 0.0 && step < 1e-4) {
        let e = format!("{v:e}");
        // 1e-5, 2.5e3: shorten the mantissa to at most 3 significant digits
        match e.split_once('e') {
            Some((m, x)) => {
                let m: f64 = m.parse().unwrap_or(0.0);
                let m = format!("{m:.2}");
                let m = m.trim_end_matches('0').trim_end_matches('.');
                format!("{m}e{x}")
            }
            None => e,
        }
    } else {
        let decimals = if step.is_finite() && step > 0.0 { (-step.log10().floor()).max(0.0) as usize } else { 2 };
        format!("{v:.decimals$}")
    };
    s.replace('-', "\u{2212}")
}

/// A power of ten written `10ⁿ` with a superscript exponent (`10⁻⁵`, `10³`); other
/// values as [`format_tick`].
pub fn format_power_of_ten(v: f64) -> String {
    let e = v.log10().round();
    let power = v > 0.0 && v.is_finite() && (10f64.powf(e) - v).abs() <= 1e-9 * v;
    if !power {
        return format_tick(v, v);
    }
    const SUP: [char; 10] = ['\u{2070}', '\u{b9}', '\u{b2}', '\u{b3}', '\u{2074}', '\u{2075}', '\u{2076}', '\u{2077}', '\u{2078}', '\u{2079}'];
    let mut s = String::from("10");
    if e < 0.0 {
        s.push('\u{207b}');
    }
    for d in format!("{}", e.abs() as i64).bytes() {
        s.push(SUP[(d - b'0') as usize]);
    }
    s
}

/// Labels of ticks on an axis: for a log axis spanning more than three decades every
/// label is a power of ten (`10⁻⁵ … 10¹`), so they read alike.
fn tick_labels(axis: &Axis, ticks: &Ticks) -> Vec<String> {
    let wide_log = axis.scale == Scale::Log
        && ticks.values.len() >= 2
        && ticks.values[ticks.values.len() - 1] / ticks.values[0] > 1e3;
    ticks
        .values
        .iter()
        .map(|&v| match axis.scale {
            Scale::Log if wide_log => format_power_of_ten(v),
            Scale::Log => format_tick(v, v),
            Scale::Linear => format_tick(v, ticks.step),
        })
        .collect()
}

/// Linear or logarithmic mapping of an axis.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Scale {
    #[default]
    Linear,
    Log,
}

/// An axis: a value range, its scale and the pixel span it maps to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Axis {
    pub lo: f64,
    pub hi: f64,
    pub scale: Scale,
    /// Device pixels of `lo` and `hi` (for a y axis `p0` is the bottom).
    pub p0: f32,
    pub p1: f32,
}

impl Axis {
    /// Device pixel of value `v`; `None` when it cannot be shown (non-finite, or ≤ 0 on a
    /// log axis).
    pub fn map(&self, v: f64) -> Option<f32> {
        let t = match self.scale {
            Scale::Linear => {
                if !v.is_finite() {
                    return None;
                }
                (v - self.lo) / (self.hi - self.lo)
            }
            Scale::Log => {
                if v.is_nan() || v <= 0.0 || v.is_infinite() {
                    return None;
                }
                (v.ln() - self.lo.ln()) / (self.hi.ln() - self.lo.ln())
            }
        };
        Some(self.p0 + (self.p1 - self.p0) * t as f32)
    }
    /// Tick values for this axis.
    pub fn ticks(&self, max_ticks: usize) -> Ticks {
        match self.scale {
            Scale::Linear => nice_ticks(self.lo, self.hi, max_ticks),
            Scale::Log => log_ticks(self.lo, self.hi),
        }
    }
}

/// What to write around a plot box.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AxisLabels<'a> {
    pub title: &'a str,
    pub x: &'a str,
    pub y: &'a str,
    /// The y axis is labelled only above this device pixel (a broken axis's band lies
    /// under it, with labels of its own). Default `None`.
    pub y_floor: Option<f32>,
}

/// At most how many intervals a y axis of `height` device pixels is cut into, so that
/// its tick labels (`label_px` high) stand apart: 6, fewer when the axis is short.
pub(crate) fn y_tick_room(height: f32, label_px: f32) -> usize {
    const SPACING: f32 = 1.6; // label heights from one tick to the next, at least
    let fit = (height / (SPACING * label_px.max(1.0))).floor();
    if fit.is_finite() { (fit as usize).clamp(1, 6) } else { 1 }
}

/// Whether the box `b` (`[x, y, w, h]`) meets any of `kept`, inside (touching edges do not).
fn meets_any(b: &[f32; 4], kept: &[[f32; 4]]) -> bool {
    kept.iter().any(|k| b[0] < k[0] + k[2] && k[0] < b[0] + b[2] && b[1] < k[1] + k[3] && k[1] < b[1] + b[3])
}

/// Draws the plot box (`x` and `y` axes in device pixels), light grid lines at the ticks,
/// tick labels and axis titles. `s` is the device-pixel ratio for sizes.
pub(crate) fn draw_axes(pixmap: &mut Pixmap, x: &Axis, y: &Axis, labels: AxisLabels<'_>, x_ticks: &Ticks, s: f32, theme: &Theme) {
    let (l, r) = (x.p0.min(x.p1), x.p0.max(x.p1));
    let (t, b) = (y.p0.min(y.p1), y.p0.max(y.p1));
    let mut grid = PathBuilder::new();
    let mut ticks = PathBuilder::new();
    let tick_px = theme.text_px(11.0 * s, s);
    let small = TextStyle::new(tick_px).with_color(theme.text);
    // a label that would meet one already written is left out (its tick stays)
    let mut written: Vec<[f32; 4]> = Vec::new();
    for (&v, label) in x_ticks.values.iter().zip(tick_labels(x, x_ticks)) {
        if let Some(px) = x.map(v) {
            grid.move_to(px, t);
            grid.line_to(px, b);
            ticks.move_to(px, b);
            ticks.line_to(px, b + 4.0 * s);
            let st = small.with_align(Align::Centre, Valign::Top);
            let bx = text_box(&label, px, b + 6.0 * s, &st);
            if !meets_any(&bx, &written) {
                draw_text(pixmap, &label, px, b + 6.0 * s, st);
                note_label(pixmap, &label, px, b + 6.0 * s, &st);
                written.push(bx);
            }
        }
    }
    let floor = labels.y_floor.unwrap_or(f32::INFINITY);
    let yt = y.ticks(y_tick_room(floor.min(b) - t, tick_px));
    let y_labels = tick_labels(y, &yt);
    for (&v, label) in yt.values.iter().zip(&y_labels) {
        if let Some(py) = y.map(v) {
            let st = small.with_align(Align::Right, Valign::Middle);
            let bx = text_box(label, l - 6.0 * s, py, &st);
            if bx[1] + bx[3] > floor {
                continue; // in a broken axis's band
            }
            grid.move_to(l, py);
            grid.line_to(r, py);
            ticks.move_to(l - 4.0 * s, py);
            ticks.line_to(l, py);
            if !meets_any(&bx, &written) {
                draw_text(pixmap, label, l - 6.0 * s, py, st);
                note_label(pixmap, label, l - 6.0 * s, py, &st);
                written.push(bx);
            }
        }
    }
    let mut paint = Paint::default();
    paint.set_color(theme.grid);
    if let Some(p) = grid.finish() {
        pixmap.stroke_path(&p, &paint, &Stroke { width: 1.0 * s, ..Default::default() }, Transform::identity(), None);
    }
    paint.set_color(theme.text);
    let stroke = Stroke { width: 1.0 * s, ..Default::default() };
    if let Some(p) = ticks.finish() {
        pixmap.stroke_path(&p, &paint, &stroke, Transform::identity(), None);
    }
    if let Some(rect) = tiny_skia::Rect::from_ltrb(l, t, r, b) {
        let p = PathBuilder::from_rect(rect);
        pixmap.stroke_path(&p, &paint, &stroke, Transform::identity(), None);
    }
    let label = TextStyle::new(theme.text_px(12.0 * s, s)).with_color(theme.label);
    // below the tick labels, however large the theme makes them
    let below = 22.0 * s * theme.grow(11.0);
    if !labels.x.is_empty() {
        draw_text(pixmap, labels.x, 0.5 * (l + r), b + below, label.with_align(Align::Centre, Valign::Top));
    }
    if !labels.y.is_empty() {
        // left of the widest tick label
        let widest = y_labels.iter().map(|l| super::text::text_width(l, tick_px)).fold(0.0f32, f32::max);
        let lx = l - 10.0 * s - widest - 8.0 * s;
        draw_text_rotated(pixmap, labels.y, lx, 0.5 * (t + b), label.with_align(Align::Centre, Valign::Bottom), -90.0);
    }
    if !labels.title.is_empty() {
        let cx = 0.5 * (l + r);
        let (shown, size) = theme.fit_title(labels.title, 14.0 * s, title_room(cx, pixmap.width() as f32, s), s);
        let title = TextStyle::new(size).with_color(theme.ink).with_align(Align::Centre, Valign::Bottom);
        draw_text(pixmap, &shown, cx, t - 8.0 * s, title);
    }
}

/// The room, device pixels, for a plot's title centred at `cx` in a picture `width` device
/// pixels wide: as far as the nearer edge allows, on both sides (a panel of a figure drawn
/// in a narrow frame on the page had its title cut off by the edge).
fn title_room(cx: f32, width: f32, s: f32) -> f32 {
    (2.0 * cx.min(width - cx) - 8.0 * s).max(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_title_stays_inside_the_picture() {
        let theme = Theme::light();
        let title = "the new objective along them (smaller is better)";
        // room enough: the whole title at 14 px, as before
        let (shown, size) = theme.fit_label(title, 14.0, title_room(600.0, 1200.0, 1.0), 1.0);
        assert_eq!((shown.as_ref(), size), (title, theme.text_px(14.0, 1.0)));
        // near the right edge: within the picture, smaller or cut, never below the smallest label
        for (cx, width, s) in [(1117.0, 1170.0, 1.0), (700.0, 800.0, 2.0), (60.0, 900.0, 1.0)] {
            let (shown, size) = theme.fit_label(title, 14.0 * s, title_room(cx, width, s), s);
            let half = 0.5 * super::super::text::text_width(&shown, size);
            assert!(cx - half >= 0.0 && cx + half <= width, "{shown:?} at {size} px about {cx} of {width}");
            assert!(size >= theme.text_px(0.0, s) && size <= 14.0 * s);
        }
    }

    fn close(a: &[f64], b: &[f64]) -> bool {
        a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-12 * (1.0 + y.abs()))
    }

    #[test]
    fn one_two_five_steps() {
        let t = nice_ticks(0.0, 1.0, 5);
        assert_eq!(t.step, 0.2);
        assert!(close(&t.values, &[0.0, 0.2, 0.4, 0.6, 0.8, 1.0]), "{:?}", t.values);
        assert_eq!(nice_ticks(0.0, 100.0, 5).step, 20.0);
        let t = nice_ticks(-3.7, 12.1, 6);
        assert_eq!(t.step, 5.0);
        assert!(close(&t.values, &[0.0, 5.0, 10.0]), "{:?}", t.values);
        assert!(t.values[0].is_sign_positive(), "no −0");
        let t = nice_ticks(0.001, 0.0042, 4);
        assert!((t.step - 0.001).abs() < 1e-15);
        assert!(close(&t.values, &[0.001, 0.002, 0.003, 0.004]), "{:?}", t.values);
        // reversed, huge, tiny, degenerate and nonsense ranges
        assert_eq!(nice_ticks(180.0, 0.0, 6), nice_ticks(0.0, 180.0, 6));
        assert_eq!(nice_ticks(0.0, 180.0, 6).values, vec![0.0, 50.0, 100.0, 150.0]);
        assert_eq!(nice_ticks(2e9, 7e9, 5).step, 1e9);
        assert!((nice_ticks(1e-9, 3e-9, 4).step - 5e-10).abs() < 1e-24);
        let t = nice_ticks(5.0, 5.0, 5);
        assert!(t.values.contains(&5.0) && t.values.len() >= 2);
        assert_eq!(nice_ticks(f64::NAN, 1.0, 5).values, nice_ticks(0.0, 1.0, 5).values);
        // every step is 1, 2 or 5 times a power of ten, and ticks never exceed the budget by much
        for (lo, hi, n) in [(0.0, 7.3, 5), (-12.0, 0.3, 4), (0.13, 0.19, 6), (1.0, 1000.0, 8)] {
            let t = nice_ticks(lo, hi, n);
            let m = t.step / 10f64.powf(t.step.log10().floor());
            assert!([1.0, 2.0, 5.0].iter().any(|f| (m - f).abs() < 1e-9), "{lo}..{hi}: step {}", t.step);
            assert!(t.values.len() <= n + 1 && t.values.len() >= n / 2, "{lo}..{hi}: {:?}", t.values);
            assert!(t.values.iter().all(|v| *v >= lo - 1e-12 && *v <= hi + 1e-12));
        }
    }

    #[test]
    fn nice_range_contains_the_data() {
        assert_eq!(nice_range(0.13, 0.87, 5), (0.0, 1.0));
        assert_eq!(nice_range(3.0, 47.0, 5), (0.0, 50.0));
        let (a, b) = nice_range(-0.7, 2.2, 6);
        assert!(a <= -0.7 && b >= 2.2 && (a, b) == (-1.0, 2.5), "{a} {b}");
    }

    #[test]
    fn decade_ticks() {
        let t = log_ticks(1e-6, 10.0);
        assert!(close(&t.values, &[1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 1e-1, 1.0, 10.0]), "{:?}", t.values);
        let t = log_ticks(0.3, 40.0);
        assert!(close(&t.values, &[0.5, 1.0, 2.0, 5.0, 10.0, 20.0]), "{:?}", t.values);
        assert!(!log_ticks(-1.0, 0.0).values.is_empty());
    }

    #[test]
    fn labels() {
        assert_eq!(format_tick(0.4, 0.2), "0.4");
        assert_eq!(format_tick(30.0, 30.0), "30");
        assert_eq!(format_tick(-0.5, 0.5), "\u{2212}0.5");
        assert_eq!(format_tick(1e-6, 1e-6), "1e\u{2212}6");
        assert_eq!(format_tick(2.5e6, 5e5), "2.5e6");
        assert_eq!(format_tick(0.0, 0.1), "0");
        assert_eq!(format_tick(0.001, 0.001), "0.001");
        assert_eq!(format_power_of_ten(1e-5), "10\u{207b}\u{2075}");
        assert_eq!(format_power_of_ten(1e12), "10\u{b9}\u{b2}");
        assert_eq!(format_power_of_ten(1.0), "10\u{2070}");
        assert_eq!(format_power_of_ten(0.5), "0.5");
    }

    #[test]
    fn axis_mapping() {
        let a = Axis { lo: 0.0, hi: 10.0, scale: Scale::Linear, p0: 100.0, p1: 0.0 };
        assert_eq!(a.map(5.0), Some(50.0));
        assert_eq!(a.map(f64::NAN), None);
        let l = Axis { lo: 1e-3, hi: 10.0, scale: Scale::Log, p0: 0.0, p1: 400.0 };
        assert!((l.map(1e-1).unwrap() - 200.0).abs() < 1e-3);
        assert_eq!(l.map(0.0), None);
        assert_eq!(l.map(-1.0), None);
    }
}
