//! Line charts: convergence histories (one node's objective per iteration) and per-pass
//! curves of old vs new smoothing (Chen, Tristano & Kwok 2003, Figures 11–12).

use glam::DVec2;
use tiny_skia::{Color, PathBuilder, Pixmap, Rect, Stroke, StrokeDash, Transform};

use super::axes::{draw_axes, nice_range, nice_ticks, Axis, AxisLabels, Scale, Ticks};
use super::colormap::series_color;
use super::paint::{fill_rect, legend, legend_row, legend_size, push_marker, rect_mask, solid, Key, LegendEntry, Marker};
use super::text::{draw_text, Align, TextStyle, Valign};
use super::view::{sane_dpr, Frame};

/// One curve: points `(x, y)` joined in order. Points that cannot be shown (non-finite,
/// or `y ≤ 0` on a log axis) break the line.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Series<'a> {
    pub label: &'a str,
    pub points: &'a [DVec2],
    /// Default `None`: the `i`-th series takes [`series_color`]`(i)`.
    pub color: Option<Color>,
    /// Default false.
    pub dashed: bool,
    /// A marker at each point. Default `None`.
    pub marker: Option<Marker>,
}

impl<'a> Series<'a> {
    pub fn new(label: &'a str, points: &'a [DVec2]) -> Self {
        Series { label, points, color: None, dashed: false, marker: None }
    }
    pub fn with_color(mut self, c: Color) -> Self {
        self.color = Some(c);
        self
    }
    pub fn with_dash(mut self, dashed: bool) -> Self {
        self.dashed = dashed;
        self
    }
    pub fn with_marker(mut self, m: Marker) -> Self {
        self.marker = Some(m);
        self
    }
}

/// Options of [`render_chart`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Chart<'a> {
    pub title: &'a str,
    pub x_label: &'a str,
    pub y_label: &'a str,
    /// Logarithmic y axis. Default false.
    pub log_y: bool,
    /// Ticks on whole numbers only (iterations, passes). Default true.
    pub integer_x: bool,
    /// Fixed y range instead of the data's. Default `None`.
    pub y_range: Option<(f64, f64)>,
    /// Device-pixel ratio. Default 1.
    pub dpr: f32,
    /// Where to draw, CSS pixels. Default the whole pixmap.
    pub frame: Option<Frame>,
    /// Draw the legend (top right, inside the plot). Default true.
    pub legend: bool,
}

impl Default for Chart<'_> {
    fn default() -> Self {
        Chart { title: "", x_label: "", y_label: "", log_y: false, integer_x: true, y_range: None, dpr: 1.0, frame: None, legend: true }
    }
}

/// A closed range `(min, max)`, `None` when empty.
type Range = Option<(f64, f64)>;

fn data_range(series: &[Series<'_>], log_y: bool) -> (Range, Range) {
    let (mut xr, mut yr): (Range, Range) = (None, None);
    let grow = |r: &mut Option<(f64, f64)>, v: f64| {
        *r = Some(match *r {
            Some((a, b)) => (a.min(v), b.max(v)),
            None => (v, v),
        })
    };
    for s in series {
        for p in s.points {
            if p.is_finite() && (!log_y || p.y > 0.0) {
                grow(&mut xr, p.x);
                grow(&mut yr, p.y);
            }
        }
    }
    (xr, yr)
}

/// Ticks for an x axis of whole numbers.
fn integer_ticks(lo: f64, hi: f64) -> Ticks {
    let t = nice_ticks(lo, hi, 8);
    if t.step >= 1.0 {
        t
    } else {
        Ticks { step: 1.0, values: (lo.ceil() as i64..=hi.floor() as i64).map(|v| v as f64).collect() }
    }
}

/// Draws a line chart of `series` and returns nothing: with no drawable point it shows
/// the empty axes and says "no data".
pub fn render_chart(pixmap: &mut Pixmap, series: &[Series<'_>], chart: &Chart<'_>) {
    let s = sane_dpr(chart.dpr);
    let frame = chart.frame.unwrap_or(Frame::of_pixmap(pixmap, s));
    fill_rect(pixmap, frame.x * s, frame.y * s, frame.w * s, frame.h * s, Color::WHITE);
    let top = if chart.title.is_empty() { 12.0 } else { 32.0 };
    let left = if chart.y_label.is_empty() { 48.0 } else { 66.0 };
    let bottom = if chart.x_label.is_empty() { 28.0 } else { 46.0 };
    let plot = frame.inset(left, top, 14.0, bottom);
    let (xr, yr) = data_range(series, chart.log_y);
    let (x0, x1) = match xr {
        Some((a, b)) if chart.integer_x => (a.floor(), b.ceil().max(a.floor() + 1.0)),
        Some((a, b)) => nice_range(a, b, 6),
        None => (0.0, 1.0),
    };
    let scale = if chart.log_y { Scale::Log } else { Scale::Linear };
    let (y0, y1) = match (chart.y_range, yr, chart.log_y) {
        (Some((a, b)), _, _) if a < b && (!chart.log_y || a > 0.0) => (a, b),
        (_, Some((a, b)), true) => {
            let (a, b) = (10f64.powf(a.log10().floor()), 10f64.powf(b.log10().ceil()));
            (a, if b > a { b } else { a * 10.0 })
        }
        (_, Some((a, b)), false) => nice_range(a, b, 5),
        (_, None, true) => (1.0, 10.0),
        (_, None, false) => (0.0, 1.0),
    };
    let xa = Axis { lo: x0, hi: x1, scale: Scale::Linear, p0: plot.x * s, p1: plot.right() * s };
    let ya = Axis { lo: y0, hi: y1, scale, p0: plot.bottom() * s, p1: plot.y * s };
    let xt = if chart.integer_x { integer_ticks(x0, x1) } else { nice_ticks(x0, x1, 6) };
    draw_axes(pixmap, &xa, &ya, AxisLabels { title: chart.title, x: chart.x_label, y: chart.y_label }, &xt, s);

    let clip = Rect::from_xywh(plot.x * s - 4.0 * s, plot.y * s - 4.0 * s, (plot.w + 8.0) * s, (plot.h + 8.0) * s).and_then(|r| rect_mask(pixmap, r));
    let mut drawn = false;
    // device points of the curves, sampled every few pixels, to place the legend
    let mut ink: Vec<(f32, f32)> = Vec::new();
    for (i, ser) in series.iter().enumerate() {
        let color = ser.color.unwrap_or(series_color(i));
        let mut pb = PathBuilder::new();
        let mut marks = PathBuilder::new();
        let mut pen_down = false;
        for p in ser.points {
            match (xa.map(p.x), ya.map(p.y)) {
                (Some(x), Some(y)) => {
                    if let (true, Some(&(px, py))) = (pen_down, ink.last()) {
                        let n = ((x - px).hypot(y - py) / (4.0 * s)).ceil().min(500.0) as usize;
                        for k in 1..n {
                            let t = k as f32 / n as f32;
                            ink.push((px + t * (x - px), py + t * (y - py)));
                        }
                    }
                    ink.push((x, y));
                    if pen_down {
                        pb.line_to(x, y);
                    } else {
                        pb.move_to(x, y);
                        pen_down = true;
                    }
                    if let Some(m) = ser.marker {
                        push_marker(&mut marks, m, x, y, 3.0 * s);
                    }
                    drawn = true;
                }
                _ => pen_down = false,
            }
        }
        let st = Stroke {
            width: 2.0 * s,
            line_join: tiny_skia::LineJoin::Round,
            dash: if ser.dashed { StrokeDash::new(vec![6.0 * s, 4.0 * s], 0.0) } else { None },
            ..Default::default()
        };
        if let Some(path) = pb.finish() {
            pixmap.stroke_path(&path, &solid(color), &st, Transform::identity(), clip.as_ref());
        }
        if let Some(path) = marks.finish() {
            pixmap.fill_path(&path, &solid(color), tiny_skia::FillRule::Winding, Transform::identity(), clip.as_ref());
        }
    }
    if !drawn {
        let st = TextStyle::new(12.0 * s).with_color(Color::from_rgba8(120, 120, 120, 255)).with_align(Align::Centre, Valign::Middle);
        let c = plot.centre();
        draw_text(pixmap, "no data", c.x as f32 * s, c.y as f32 * s, st);
    }
    if chart.legend && series.iter().any(|x| !x.label.is_empty()) {
        let entries: Vec<LegendEntry<'_>> = series
            .iter()
            .enumerate()
            .filter(|(_, x)| !x.label.is_empty())
            .map(|(i, x)| LegendEntry { label: x.label, color: x.color.unwrap_or(series_color(i)), key: Key::Line { dashed: x.dashed, marker: x.marker } })
            .collect();
        let (lw, lh) = legend_size(&entries, s);
        let (l, r, t, b) = ((plot.x + 6.0) * s, (plot.right() - 6.0) * s, (plot.y + 6.0) * s, (plot.bottom() - 6.0) * s);
        // the corner whose box covers the fewest curve samples (top right on ties)
        let corners = [(r - lw, t), (l, t), (r - lw, b - lh), (l, b - lh)];
        let covered = |&(x, y): &(f32, f32)| ink.iter().filter(|(px, py)| *px >= x - 3.0 * s && *px <= x + lw + 3.0 * s && *py >= y - 3.0 * s && *py <= y + lh + 3.0 * s).count();
        let best = corners.iter().min_by_key(|c| covered(c)).copied().unwrap_or(corners[0]);
        legend(pixmap, &entries, best.0, best.1, false, s);
    }
}

/// Picks one statistic out of a [`PassHistory`].
type Column = for<'x> fn(&PassHistory<'x>) -> &'x [f64];

/// The per-pass statistics of one smoothing run; entry 0 is the mesh before the first
/// pass. Angles in degrees.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PassHistory<'a> {
    /// E.g. "old (max-min)" or "new (Chen et al.)".
    pub label: &'a str,
    pub min_angle_deg: &'a [f64],
    pub max_angle_deg: &'a [f64],
    pub min_quality: &'a [f64],
    /// Number of inverted elements.
    pub inverted: &'a [f64],
}

/// Four small charts (min angle, max angle, min quality, inverted elements against
/// the pass) with one curve per run, under `chart.title` and one shared legend row.
/// `chart`'s axis labels, `log_y` and `y_range` are not used.
pub fn render_pass_histories(pixmap: &mut Pixmap, runs: &[PassHistory<'_>], chart: &Chart<'_>) {
    let s = sane_dpr(chart.dpr);
    let frame = chart.frame.unwrap_or(Frame::of_pixmap(pixmap, s));
    fill_rect(pixmap, frame.x * s, frame.y * s, frame.w * s, frame.h * s, Color::WHITE);
    let title_h = if chart.title.is_empty() { 0.0 } else { 26.0 };
    if title_h > 0.0 {
        let st = TextStyle::new(15.0 * s).with_align(Align::Centre, Valign::Baseline);
        draw_text(pixmap, chart.title, (frame.x + 0.5 * frame.w) * s, (frame.y + 19.0) * s, st);
    }
    let run_key = |i: usize| Key::Line { dashed: i % 2 == 1, marker: Some(if i % 2 == 0 { Marker::Circle } else { Marker::Triangle }) };
    let entries: Vec<LegendEntry<'_>> = runs.iter().enumerate().map(|(i, r)| LegendEntry { label: r.label, color: series_color(i + 1), key: run_key(i) }).collect();
    let legend_h = if chart.legend && !entries.is_empty() { 20.0 } else { 0.0 };
    if legend_h > 0.0 {
        legend_row(pixmap, &entries, (frame.x + 0.5 * frame.w) * s, (frame.y + title_h + 8.0) * s, s);
    }
    let top = title_h + legend_h;
    let body = frame.inset(0.0, top, 0.0, 0.0);
    let panels: [(&str, Column); 4] = [
        ("min angle (\u{b0})", |r| r.min_angle_deg),
        ("max angle (\u{b0})", |r| r.max_angle_deg),
        ("min quality (\u{3b1} / \u{3b2})", |r| r.min_quality),
        ("inverted elements", |r| r.inverted),
    ];
    let points: Vec<Vec<Vec<DVec2>>> = panels
        .iter()
        .map(|(_, get)| runs.iter().map(|r| get(r).iter().enumerate().map(|(i, v)| DVec2::new(i as f64, *v)).collect()).collect())
        .collect();
    for (k, (title, _)) in panels.iter().enumerate() {
        let cell = body.row(k / 2, 2, 4.0).column(k % 2, 2, 8.0);
        let series: Vec<Series<'_>> = runs
            .iter()
            .enumerate()
            .map(|(i, r)| Series {
                label: r.label,
                points: &points[k][i],
                color: Some(series_color(i + 1)),
                dashed: i % 2 == 1,
                marker: Some(if i % 2 == 0 { Marker::Circle } else { Marker::Triangle }),
            })
            .collect();
        let sub = Chart { title, x_label: "pass", y_label: "", log_y: false, integer_x: true, y_range: None, dpr: s, frame: Some(cell), legend: false };
        render_chart(pixmap, &series, &sub);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_skip_what_cannot_be_drawn() {
        let pts = [DVec2::new(0.0, -1.0), DVec2::new(1.0, 0.0), DVec2::new(2.0, 1e-3), DVec2::new(f64::NAN, 5.0), DVec2::new(3.0, 10.0)];
        let ser = [Series::new("a", &pts)];
        let (x, y) = data_range(&ser, false);
        assert_eq!(x, Some((0.0, 3.0)));
        assert_eq!(y, Some((-1.0, 10.0)));
        let (x, y) = data_range(&ser, true);
        assert_eq!(x, Some((2.0, 3.0)));
        assert_eq!(y, Some((1e-3, 10.0)));
        assert_eq!(data_range(&[], true), (None, None));
    }

    #[test]
    fn integer_axes_never_show_fractions() {
        assert_eq!(integer_ticks(0.0, 3.0).values, vec![0.0, 1.0, 2.0, 3.0]);
        assert!(integer_ticks(0.0, 40.0).values.iter().all(|v| v.fract() == 0.0));
        assert_eq!(integer_ticks(0.0, 40.0).step, 5.0);
    }

    #[test]
    fn empty_and_degenerate_charts_draw_without_panicking() {
        let mut p = Pixmap::new(200, 120).unwrap();
        render_chart(&mut p, &[], &Chart::default());
        let one = [DVec2::new(0.0, 2.0)];
        render_chart(&mut p, &[Series::new("x", &one)], &Chart { log_y: true, ..Default::default() });
        let bad = [DVec2::new(f64::NAN, f64::INFINITY), DVec2::new(1.0, -1.0)];
        render_chart(&mut p, &[Series::new("x", &bad)], &Chart { log_y: true, dpr: f32::NAN, ..Default::default() });
        render_pass_histories(&mut p, &[], &Chart::default());
    }
}
