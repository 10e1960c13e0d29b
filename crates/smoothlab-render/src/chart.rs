//! Line charts: convergence histories (one node's objective per iteration) and per-pass
//! curves of old vs new smoothing (Chen, Tristano & Kwok 2003, Figures 11–12).

use glam::DVec2;
use tiny_skia::{Color, PathBuilder, Pixmap, Rect, Stroke, StrokeDash, Transform};

use super::axes::{draw_axes, format_tick, nice_range, nice_ticks, Axis, AxisLabels, Scale, Ticks};
use super::paint::{fill_rect, legend_band, legend_band_height, push_marker, rect_mask, solid, Key, LegendEntry, LegendStyle, Marker};
use super::theme::Theme;
use super::text::{draw_text, Align, TextStyle, Valign};
use super::view::{sane_dpr, Frame};

/// One curve: points `(x, y)` joined in order. Points that cannot be shown (non-finite,
/// or `y ≤ 0` on a log axis) break the line.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Series<'a> {
    pub label: &'a str,
    pub points: &'a [DVec2],
    /// Default `None`: the `i`-th series takes the theme's [`Theme::series`]`(i)`.
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
    /// Draw the legend (in a band under the plot, which shrinks to make room). Default true.
    pub legend: bool,
    /// A broken y axis: when some points lie below this value and others at or above it,
    /// the axis spans only the values at or above it, and the points below sit in a band
    /// under a break mark, each with its value written beside it (a mesh as loaded with
    /// an inverted corner of −176° would otherwise squash every later pass into a line).
    /// Default `None`.
    pub y_break: Option<f64>,
    /// Colours and label sizes. Default [`Theme::light`].
    pub theme: Theme,
}

impl Default for Chart<'_> {
    fn default() -> Self {
        Chart { title: "", x_label: "", y_label: "", log_y: false, integer_x: true, y_range: None, dpr: 1.0, frame: None, legend: true, y_break: None, theme: Theme::light() }
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

/// For a y axis broken at `b`: `Some((below, above))`, the ranges of the finite values
/// below `b` and at or above it, when there are both.
fn broken_range(series: &[Series<'_>], b: f64) -> Option<((f64, f64), (f64, f64))> {
    let (mut lo, mut hi): (Range, Range) = (None, None);
    for p in series.iter().flat_map(|s| s.points).filter(|p| p.is_finite()) {
        let r = if p.y < b { &mut lo } else { &mut hi };
        *r = Some(match *r {
            Some((a, c)) => (a.min(p.y), c.max(p.y)),
            None => (p.y, p.y),
        });
    }
    let (lo, hi) = (lo?, hi?);
    // worth it only when the values below would take more than half the axis
    (hi.0 - lo.0 > 2.0 * (hi.1 - hi.0).max(f64::MIN_POSITIVE)).then_some((lo, hi))
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
    let theme = &chart.theme;
    fill_rect(pixmap, frame.x * s, frame.y * s, frame.w * s, frame.h * s, theme.paper);
    // room for the labels, grown with them when the theme makes them larger
    let top = if chart.title.is_empty() { 12.0 } else { 32.0 * theme.grow(14.0) };
    let left = if chart.y_label.is_empty() { 48.0 } else { 66.0 } * theme.grow(11.0);
    let bottom = if chart.x_label.is_empty() { 28.0 } else { 46.0 } * theme.grow(11.0);
    // the legend's band under the axes: never over the curves
    let ls = LegendStyle::new(theme, s, s);
    let entries: Vec<LegendEntry<'_>> = if chart.legend {
        series
            .iter()
            .enumerate()
            .filter(|(_, x)| !x.label.is_empty())
            .map(|(i, x)| LegendEntry { label: x.label, color: x.color.unwrap_or(theme.series(i)), key: Key::Line { dashed: x.dashed, marker: x.marker } })
            .collect()
    } else {
        Vec::new()
    };
    let legend_h = legend_band_height(&entries, (frame.w - 16.0) * s, &ls) / s;
    let plot = frame.inset(left, top, 14.0, bottom + legend_h);
    super::layout::note(pixmap, super::layout::RegionKind::Plot, plot.x * s, plot.y * s, plot.w * s, plot.h * s);
    let (xr, mut yr) = data_range(series, chart.log_y);
    // the values below a break, if the axis is broken: the range is of the others
    let below = match (chart.y_break, chart.log_y) {
        (Some(b), false) => broken_range(series, b),
        _ => None,
    };
    if let Some((_, above)) = below {
        yr = Some(above);
    }
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
    // a broken axis keeps a band of BAND css pixels at the bottom: the axis is extended
    // linearly over it, so values at or above the break map as they would without it
    const BAND: f32 = 18.0;
    let (y0, band_value) = match below {
        Some(_) if plot.h > 3.0 * BAND => {
            let ext = (y1 - y0) * BAND as f64 / (plot.h - BAND) as f64;
            (y0 - ext, Some(y0 - ext / 2.0))
        }
        _ => (y0, None),
    };
    let xa = Axis { lo: x0, hi: x1, scale: Scale::Linear, p0: plot.x * s, p1: plot.right() * s };
    let ya = Axis { lo: y0, hi: y1, scale, p0: plot.bottom() * s, p1: plot.y * s };
    let xt = if chart.integer_x { integer_ticks(x0, x1) } else { nice_ticks(x0, x1, 6) };
    let band_top = band_value.map(|_| (plot.bottom() - BAND) * s);
    draw_axes(pixmap, &xa, &ya, AxisLabels { title: chart.title, x: chart.x_label, y: chart.y_label, y_floor: band_top }, &xt, s, theme);
    let mut band_labels: Vec<(f32, f32, String)> = Vec::new();
    if let Some(top) = band_top {
        // the band: no ticks nor grid in it, a shaded strip and a break mark on the axis
        let l = plot.x * s;
        fill_rect(pixmap, l + 0.5 * s, top, plot.w * s - s, BAND * s - 0.5 * s, theme.band);
        let mut zig = PathBuilder::new();
        let y = top;
        zig.move_to(l - 6.0 * s, y + 3.0 * s);
        zig.line_to(l - 2.0 * s, y - 3.0 * s);
        zig.line_to(l + 2.0 * s, y + 3.0 * s);
        zig.line_to(l + 6.0 * s, y - 3.0 * s);
        if let Some(path) = zig.finish() {
            pixmap.stroke_path(&path, &solid(theme.text), &Stroke { width: 1.5 * s, ..Default::default() }, Transform::identity(), None);
        }
    }
    // where a point is drawn: in the band when it is below the break
    let place = |p: &DVec2| -> Option<(f32, f32)> {
        let y = match (band_value, chart.y_break) {
            (Some(v), Some(b)) if p.y < b => v,
            _ => p.y,
        };
        Some((xa.map(p.x)?, ya.map(y)?))
    };

    let mut marked: Vec<(f32, f32)> = Vec::new();
    let clip = Rect::from_xywh(plot.x * s - 4.0 * s, plot.y * s - 4.0 * s, (plot.w + 8.0) * s, (plot.h + 8.0) * s).and_then(|r| rect_mask(pixmap, r));
    let mut drawn = false;
    for (i, ser) in series.iter().enumerate() {
        let color = ser.color.unwrap_or(theme.series(i));
        let mut pb = PathBuilder::new();
        let mut marks = PathBuilder::new();
        let mut pen_down = false;
        for p in ser.points {
            match place(p) {
                Some((x, y)) => {
                    if band_value.is_some() && chart.y_break.is_some_and(|b| p.y < b) && p.y.is_finite() {
                        let text = format_tick(p.y, if p.y.abs() >= 10.0 { 1.0 } else { 0.1 });
                        if !band_labels.iter().any(|(bx, _, t)| (*bx - x).abs() < 1.0 && *t == text) {
                            band_labels.push((x, y, text));
                        }
                    }
                    if pen_down {
                        pb.line_to(x, y);
                    } else {
                        pb.move_to(x, y);
                        pen_down = true;
                    }
                    marked.push((x, y));
                    if let Some(m) = ser.marker {
                        push_marker(&mut marks, m, x, y, 3.0 * s);
                        super::layout::note_mark(pixmap, x, y, color);
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
    draw_band_labels(pixmap, &band_labels, &marked, plot.x * s, s, theme);
    if !drawn {
        let st = TextStyle::new(theme.text_px(12.0 * s, s)).with_color(theme.faint).with_align(Align::Centre, Valign::Middle);
        let c = plot.centre();
        draw_text(pixmap, "no data", c.x as f32 * s, c.y as f32 * s, st);
    }
    if !entries.is_empty() {
        legend_band(pixmap, &entries, (frame.x + 8.0) * s, (frame.bottom() - legend_h) * s, (frame.w - 16.0) * s, &ls);
    }
}

/// Writes the values of the points in a broken axis's band (`labels`: where each point is
/// drawn and its value), clear of every drawn point (`marked`): a point on the axis at
/// `left` (pass 0, the mesh as loaded) has its value written left of the axis, where the
/// tick labels are; another, right of its point, or left of it when a point lies there.
fn draw_band_labels(pixmap: &mut Pixmap, labels: &[(f32, f32, String)], marked: &[(f32, f32)], left: f32, s: f32, theme: &Theme) {
    let st = TextStyle::new(theme.text_px(10.0 * s, s)).with_color(theme.label);
    let reach = 4.0 * s; // a marker's half size, and a little room
    let clear = |b: &[f32; 4]| !marked.iter().any(|&(x, y)| b[0] < x + reach && x - reach < b[0] + b[2] && b[1] < y + reach && y - reach < b[1] + b[3]);
    let mut written: Vec<[f32; 4]> = Vec::new();
    let meets = |b: &[f32; 4], w: &[[f32; 4]]| w.iter().any(|k| b[0] < k[0] + k[2] && k[0] < b[0] + b[2] && b[1] < k[1] + k[3] && k[1] < b[1] + b[3]);
    let mut write = |text: &str, x: f32, y: f32, st: TextStyle, written: &mut Vec<[f32; 4]>| {
        draw_text(pixmap, text, x, y, st);
        super::layout::note_label(pixmap, text, x, y, &st);
        written.push(super::text::text_box(text, x, y, &st));
    };
    // on the axis: the values, once each, in the tick labels' column
    let mut on_axis: Vec<&str> = Vec::new();
    let mut y_axis = 0.0;
    for (x, y, text) in labels {
        if (x - left).abs() < 1.0 && !on_axis.contains(&text.as_str()) {
            on_axis.push(text);
            y_axis = *y;
        }
    }
    if !on_axis.is_empty() {
        let st = st.with_align(Align::Right, Valign::Middle);
        write(&on_axis.join(" / "), left - 6.0 * s, y_axis, st, &mut written);
    }
    for (x, y, text) in labels.iter().filter(|(x, _, _)| (x - left).abs() >= 1.0) {
        let right = (x + reach, st.with_align(Align::Left, Valign::Middle));
        let leftwards = (x - reach, st.with_align(Align::Right, Valign::Middle));
        for (ax, st) in [right, leftwards] {
            let b = super::text::text_box(text, ax, *y, &st);
            if clear(&b) && !meets(&b, &written) {
                write(text, ax, *y, st, &mut written);
                break;
            }
        }
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
    /// Its colour; `None`: the theme's series palette, by position (from the second).
    pub color: Option<Color>,
}

/// The titles of [`render_pass_histories`]' four charts: the planar (and surface) words.
pub const PASS_TITLES: [&str; 4] = ["min angle (\u{b0})", "max angle (\u{b0})", "min quality (\u{3b1} / \u{3b2})", "inverted elements"];

/// Four small charts (min angle, max angle, min quality, inverted elements against
/// the pass) with one curve per run, under `chart.title` and one shared legend row.
/// `chart`'s axis labels, `log_y` and `y_range` are not used.
pub fn render_pass_histories(pixmap: &mut Pixmap, runs: &[PassHistory<'_>], chart: &Chart<'_>) {
    render_pass_histories_titled(pixmap, runs, chart, &PASS_TITLES);
}

/// [`render_pass_histories`] with the four charts' titles in the words of another kind
/// of mesh (for tetrahedra: dihedral angles, the mean ratio, inverted tetrahedra).
pub fn render_pass_histories_titled(pixmap: &mut Pixmap, runs: &[PassHistory<'_>], chart: &Chart<'_>, titles: &[&str; 4]) {
    let s = sane_dpr(chart.dpr);
    let frame = chart.frame.unwrap_or(Frame::of_pixmap(pixmap, s));
    let theme = &chart.theme;
    fill_rect(pixmap, frame.x * s, frame.y * s, frame.w * s, frame.h * s, theme.paper);
    let title_h = if chart.title.is_empty() { 0.0 } else { 26.0 * theme.grow(15.0) };
    if title_h > 0.0 {
        let st = TextStyle::new(theme.text_px(15.0 * s, s)).with_color(theme.ink).with_align(Align::Centre, Valign::Baseline);
        draw_text(pixmap, chart.title, (frame.x + 0.5 * frame.w) * s, (frame.y + 19.0 * theme.grow(15.0)) * s, st);
    }
    let run_key = |i: usize| Key::Line { dashed: i % 2 == 1, marker: Some(if i % 2 == 0 { Marker::Circle } else { Marker::Triangle }) };
    let entries: Vec<LegendEntry<'_>> = runs.iter().enumerate().map(|(i, r)| LegendEntry { label: r.label, color: r.color.unwrap_or(theme.series(i + 1)), key: run_key(i) }).collect();
    let ls = LegendStyle::new(theme, s, s);
    let entries = if chart.legend { entries } else { Vec::new() };
    let legend_h = legend_band_height(&entries, (frame.w - 16.0) * s, &ls) / s;
    legend_band(pixmap, &entries, (frame.x + 8.0) * s, (frame.y + title_h) * s, (frame.w - 16.0) * s, &ls);
    let top = title_h + legend_h;
    let body = frame.inset(0.0, top, 0.0, 0.0);
    // the angle charts break their axis at 0°: an inverted corner as loaded (−176°) sits
    // in a band below, and the passes after it keep the whole height
    let panels: [(&str, Column, Option<f64>); 4] = [
        (titles[0], |r| r.min_angle_deg, Some(0.0)),
        (titles[1], |r| r.max_angle_deg, Some(0.0)),
        (titles[2], |r| r.min_quality, None),
        (titles[3], |r| r.inverted, None),
    ];
    let points: Vec<Vec<Vec<DVec2>>> = panels
        .iter()
        .map(|(_, get, _)| runs.iter().map(|r| get(r).iter().enumerate().map(|(i, v)| DVec2::new(i as f64, *v)).collect()).collect())
        .collect();
    for (k, &(title, _, y_break)) in panels.iter().enumerate() {
        let cell = body.row(k / 2, 2, 4.0).column(k % 2, 2, 8.0);
        let series: Vec<Series<'_>> = runs
            .iter()
            .enumerate()
            .map(|(i, r)| Series {
                label: r.label,
                points: &points[k][i],
                color: Some(r.color.unwrap_or(theme.series(i + 1))),
                dashed: i % 2 == 1,
                marker: Some(if i % 2 == 0 { Marker::Circle } else { Marker::Triangle }),
            })
            .collect();
        let sub = Chart { title, x_label: "pass", y_label: "", log_y: false, integer_x: true, y_range: None, dpr: s, frame: Some(cell), legend: false, y_break, theme: *theme };
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

    /// Rows of the chart where colour `c` is drawn in column `x`.
    fn rows_of(p: &Pixmap, x: u32, c: (u8, u8, u8)) -> Vec<u32> {
        (0..p.height()).filter(|&y| {
            let px = p.pixel(x, y).unwrap();
            (px.red(), px.green(), px.blue()) == c
        }).collect()
    }

    #[test]
    fn a_broken_axis_keeps_the_passes_readable_beside_a_folded_start() {
        // pass 0: an inverted corner of −176°; passes 1–3 between 20° and 30°
        let pts = [DVec2::new(0.0, -176.0), DVec2::new(1.0, 20.0), DVec2::new(2.0, 25.0), DVec2::new(3.0, 30.0)];
        let blue = Color::from_rgba8(0, 0, 255, 255);
        let ser = [Series::new("", &pts).with_color(blue)];
        let draw = |y_break| {
            let mut p = Pixmap::new(300, 240).unwrap();
            render_chart(&mut p, &ser, &Chart { legend: false, y_break, ..Chart::default() });
            p
        };
        // the plot spans x = 48 … 286 for passes 0 … 3: pass 1 at 127, pass 3 at 286
        let spread = |p: &Pixmap| {
            let (a, b) = (rows_of(p, 127, (0, 0, 255)), rows_of(p, 283, (0, 0, 255)));
            a.iter().sum::<u32>() as f64 / a.len() as f64 - b.iter().sum::<u32>() as f64 / b.len() as f64
        };
        let (plain, broken) = (spread(&draw(None)), spread(&draw(Some(0.0))));
        assert!(plain < 30.0, "without the break the passes are squashed: {plain} px");
        assert!(broken > 100.0, "with it they use the height: {broken} px");
        // a start above the break needs none: the same picture
        let above = [DVec2::new(0.0, 5.0), DVec2::new(1.0, 20.0)];
        let mut a = Pixmap::new(200, 150).unwrap();
        let mut b = a.clone();
        render_chart(&mut a, &[Series::new("", &above)], &Chart::default());
        render_chart(&mut b, &[Series::new("", &above)], &Chart { y_break: Some(0.0), ..Chart::default() });
        assert_eq!(a.data(), b.data());
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

    use crate::layout::{record, Region, RegionKind};

    /// The regions of `kind` the pixmap's notes hold.
    fn regions(notes: &crate::layout::Notes, p: &Pixmap, kind: RegionKind) -> Vec<Region> {
        notes.of(p).into_iter().filter(|r| r.kind == kind).collect()
    }

    /// Pairs of labels whose boxes meet.
    fn overlapping(labels: &[Region]) -> Vec<(Region, Region)> {
        let mut out = Vec::new();
        for (i, a) in labels.iter().enumerate() {
            for b in &labels[i + 1..] {
                if a.overlaps(b) {
                    out.push((*a, *b));
                }
            }
        }
        out
    }

    #[test]
    fn the_band_values_stand_clear_of_the_points_and_of_each_other() {
        // the page's per-pass chart after 3 passes of a tangled mesh: both sides start at
        // −179° (in the band), and one stays inverted a pass longer
        let (a_min, b_min) = ([-179.2, -150.0, 12.0, 14.0], [-179.2, 18.0, 20.0, 21.0]);
        let (a_max, b_max) = ([179.9, 170.0, 150.0, 140.0], [179.9, 140.0, 130.0, 128.0]);
        let (q, inv) = ([-0.9, -0.2, 0.3, 0.4], [60.0, 3.0, 0.0, 0.0]);
        let runs = [
            PassHistory { label: "A: old", min_angle_deg: &a_min, max_angle_deg: &a_max, min_quality: &q, inverted: &inv, color: None },
            PassHistory { label: "B: new", min_angle_deg: &b_min, max_angle_deg: &b_max, min_quality: &q, inverted: &inv, color: None },
        ];
        for (w, h, dpr) in [(600, 300, 1.0), (1300, 560, 1.0), (400, 400, 1.0), (800, 600, 2.0)] {
            let mut p = Pixmap::new(w, h).unwrap();
            let ((), notes) = record(|| render_pass_histories(&mut p, &runs, &Chart { dpr, ..Chart::default() }));
            let (labels, marks) = (regions(&notes, &p, RegionKind::Label), regions(&notes, &p, RegionKind::Mark));
            let r = 3.0 * dpr; // a marker's half size
            for l in &labels {
                for m in &marks {
                    let mut mark = m.shifted(-r, -r);
                    (mark.w, mark.h) = (2.0 * r, 2.0 * r);
                    assert!(!l.overlaps(&mark), "{w}×{h}@{dpr}: a label {l:?} over a point {m:?}");
                }
            }
            assert!(overlapping(&labels).is_empty(), "{w}×{h}@{dpr}: {:?}", overlapping(&labels));
            // −179 is written, left of the pass-0 points, on the row of the band
            let first = marks.iter().map(|m| m.x).fold(f32::INFINITY, f32::min);
            // the min angle chart is the top left one: its pass-0 points lie in its band
            let band_row = marks.iter().filter(|m| m.x == first && m.y < 0.5 * h as f32).map(|m| m.y).fold(f32::NEG_INFINITY, f32::max);
            assert!(
                labels.iter().any(|l| l.x + l.w <= first && l.y < band_row && band_row < l.y + l.h),
                "{w}×{h}@{dpr}: no value left of the pass-0 point in the band"
            );
        }
    }

    #[test]
    fn y_labels_stand_apart_at_any_height() {
        // the page's solver history: two charts in one picture, as short as a narrow column makes them
        let pts: Vec<DVec2> = (0..4).map(|i| DVec2::new(i as f64, 190.0 / (1.0 + 8.0 * i as f64))).collect();
        for (w, h, dpr) in [(300, 225, 1.0), (320, 240, 2.0), (400, 300, 1.0), (660, 495, 1.0), (200, 90, 1.0)] {
            let mut p = Pixmap::new(w, h).unwrap();
            let full = Frame::of_pixmap(&p, dpr);
            let ((), notes) = record(|| {
                for i in 0..2 {
                    let chart = Chart { title: "per iteration", x_label: "iteration", y_label: "objective", dpr, frame: Some(full.row(i, 2, 4.0)), legend: false, ..Chart::default() };
                    render_chart(&mut p, &[Series::new("a", &pts)], &chart);
                }
            });
            let labels = regions(&notes, &p, RegionKind::Label);
            assert!(overlapping(&labels).is_empty(), "{w}×{h}@{dpr}: {:?}", overlapping(&labels));
            // each chart keeps a y label at least at both ends of its range
            let left = labels.iter().map(|l| l.x + l.w).fold(f32::INFINITY, f32::min);
            let y_labels = labels.iter().filter(|l| (l.x + l.w - left).abs() < 20.0 * dpr).count();
            assert!(y_labels >= 4, "{w}×{h}@{dpr}: {y_labels} y labels");
        }
    }
}
