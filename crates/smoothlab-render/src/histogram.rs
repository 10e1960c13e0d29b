//! Angle histograms as in Freitag (1997), Figure 3: the percentage of element angles
//! in each 6° bin over [0°, 180°], several meshes (original, Laplacian, old, new)
//! overlaid as step outlines. The bins may span another measure's range
//! ([`HistogramAxis`]): the same picture of any per-element measure.

use tiny_skia::{Color, PathBuilder, Pixmap};

use super::axes::{draw_axes, nice_range, Axis, AxisLabels, Scale, Ticks};
use super::paint::{fill, fill_rect, legend_band, legend_band_height, stroke, Key, LegendEntry, LegendStyle};
use super::theme::Theme;
use super::view::{sane_dpr, Frame};
use smoothlab::error::{Error, Result};

/// One mesh's angle counts per bin, e.g.
/// [`MeshStats::angle_histogram_6deg`](smoothlab::quality::MeshStats::angle_histogram_6deg).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HistogramSeries<'a> {
    pub label: &'a str,
    /// Counts (not percentages) of equal bins spanning the axis ([`HistogramAxis`]:
    /// [0°, 180°] for angles).
    pub counts: &'a [u64],
    /// Its colour; `None`: the theme's series palette, by position.
    pub color: Option<Color>,
}

/// What the bins of a histogram span: the measure's range, its ticks, the words under
/// the axes and the dashed reference lines (the ideal values).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HistogramAxis<'a> {
    /// The range the bins divide equally.
    pub lo: f64,
    pub hi: f64,
    /// The distance between ticks, from `lo`.
    pub step: f64,
    /// Under the x axis, and beside the y axis.
    pub x_label: &'a str,
    pub y_label: &'a str,
    /// Values marked by dashed lines.
    pub marks: &'a [f64],
}

impl HistogramAxis<'_> {
    /// Angles in degrees, 0° to 180° (ticks every 30°, the equilateral triangle's 60° and
    /// the square's 90° marked): Freitag's Fig. 3.
    pub const ANGLES: HistogramAxis<'static> =
        HistogramAxis { lo: 0.0, hi: 180.0, step: 30.0, x_label: "angle (\u{b0})", y_label: "angles (%)", marks: &[60.0, 90.0] };
}

/// Options of [`render_angle_histogram`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AngleHistogram<'a> {
    /// Default "Angle distribution".
    pub title: &'a str,
    /// Device-pixel ratio. Default 1.
    pub dpr: f32,
    /// Where to draw, CSS pixels. Default the whole pixmap.
    pub frame: Option<Frame>,
    /// Default true.
    pub legend: bool,
    /// The largest percentage the y axis must show (several pictures on one scale);
    /// `None`: this picture's own largest. Default `None`.
    pub y_top: Option<f64>,
    /// A logarithmic percentage axis (down to `LOG_FLOOR_PCT`; empty bins sit on the
    /// axis), which shows the few very poor angles beside the many good ones. Default false.
    pub log_y: bool,
    /// Colours and label sizes. Default [`Theme::light`].
    pub theme: Theme,
    /// What the bins span. Default [`HistogramAxis::ANGLES`].
    pub axis: HistogramAxis<'a>,
}

impl Default for AngleHistogram<'_> {
    fn default() -> Self {
        AngleHistogram {
            title: "Angle distribution",
            dpr: 1.0,
            frame: None,
            legend: true,
            y_top: None,
            log_y: false,
            theme: Theme::light(),
            axis: HistogramAxis::ANGLES,
        }
    }
}

/// The bottom of a logarithmic histogram axis, percent: one angle in 100,000.
pub const LOG_FLOOR_PCT: f64 = 1e-3;

/// Percentages per bin (0 everywhere when the counts are all zero).
pub fn percentages(counts: &[u64]) -> Vec<f64> {
    let total: u64 = counts.iter().sum();
    counts.iter().map(|&c| if total == 0 { 0.0 } else { 100.0 * c as f64 / total as f64 }).collect()
}

/// Draws the overlaid histograms. The first series is filled lightly (the reference,
/// usually the original mesh); the others are outlines, alternately dashed. Fails when
/// there are no bins or the series disagree on the number of bins.
pub fn render_angle_histogram(pixmap: &mut Pixmap, series: &[HistogramSeries<'_>], opts: &AngleHistogram<'_>) -> Result<()> {
    let bins = series.first().map(|s| s.counts.len()).unwrap_or(30);
    if bins == 0 {
        return Err(Error::invalid("an angle histogram needs at least one bin"));
    }
    if let Some(bad) = series.iter().find(|s| s.counts.len() != bins) {
        return Err(Error::invalid(format!(
            "angle histogram series \"{}\" has {} bins but \"{}\" has {}",
            bad.label,
            bad.counts.len(),
            series[0].label,
            bins
        )));
    }
    let s = sane_dpr(opts.dpr);
    let frame = opts.frame.unwrap_or(Frame::of_pixmap(pixmap, s));
    let theme = &opts.theme;
    fill_rect(pixmap, frame.x * s, frame.y * s, frame.w * s, frame.h * s, theme.paper);
    // room for the labels, grown with them when the theme makes them larger
    let (g_tick, g_title) = (theme.grow(11.0), theme.grow(14.0));
    let top = if opts.title.is_empty() { 12.0 } else { 32.0 * g_title };
    // the legend's band under the axes: never over the bars
    let ls = LegendStyle::new(theme, s, s);
    let entries: Vec<LegendEntry<'_>> = if opts.legend {
        series
            .iter()
            .enumerate()
            .map(|(i, ser)| LegendEntry { label: ser.label, color: ser.color.unwrap_or(theme.series(i)), key: Key::Line { dashed: i % 2 == 0 && i > 0, marker: None } })
            .collect()
    } else {
        Vec::new()
    };
    let legend_h = legend_band_height(&entries, (frame.w - 16.0) * s, &ls) / s;
    let plot = frame.inset(62.0 * g_tick, top, 14.0, 46.0 * g_tick + legend_h);
    super::layout::note(pixmap, super::layout::RegionKind::Plot, plot.x * s, plot.y * s, plot.w * s, plot.h * s);
    let pct: Vec<Vec<f64>> = series.iter().map(|x| percentages(x.counts)).collect();
    let own = pct.iter().flatten().copied().fold(0.0f64, f64::max);
    let top = match opts.y_top {
        Some(t) if t.is_finite() => own.max(t),
        _ => own,
    };
    let ax = &opts.axis;
    if !(ax.lo.is_finite() && ax.hi.is_finite() && ax.hi > ax.lo && ax.step > 0.0 && (ax.hi - ax.lo) / ax.step <= 100.0) {
        return Err(Error::invalid(format!("a histogram axis from {} to {} in steps of {}", ax.lo, ax.hi, ax.step)));
    }
    let xa = Axis { lo: ax.lo, hi: ax.hi, scale: Scale::Linear, p0: plot.x * s, p1: plot.right() * s };
    let ya = if opts.log_y {
        let hi = 10f64.powf(top.max(LOG_FLOOR_PCT * 10.0).log10().ceil());
        Axis { lo: LOG_FLOOR_PCT, hi, scale: Scale::Log, p0: plot.bottom() * s, p1: plot.y * s }
    } else {
        let (_, ymax) = nice_range(0.0, top.max(1.0), 5);
        Axis { lo: 0.0, hi: ymax, scale: Scale::Linear, p0: plot.bottom() * s, p1: plot.y * s }
    };
    let ticks = ((ax.hi - ax.lo) / ax.step + 1e-9).floor() as usize;
    let xt = Ticks { step: ax.step, values: (0..=ticks).map(|k| ax.lo + ax.step * k as f64).collect() };
    draw_axes(pixmap, &xa, &ya, AxisLabels { title: opts.title, x: ax.x_label, y: ax.y_label, y_floor: None }, &xt, s, theme);

    // reference lines at the ideal values (the angles 60° and 90°)
    let mut refs = PathBuilder::new();
    for &a in ax.marks {
        if let Some(x) = xa.map(a) {
            refs.move_to(x, plot.y * s);
            refs.line_to(x, plot.bottom() * s);
        }
    }
    stroke(pixmap, refs, theme.reference, 1.0 * s, Some([3.0 * s, 3.0 * s]));

    let width = (ax.hi - ax.lo) / bins as f64;
    for (i, (ser, p)) in series.iter().zip(&pct).enumerate() {
        let color = ser.color.unwrap_or(theme.series(i));
        let mut pb = PathBuilder::new();
        // the axis line: 0 on a linear axis, the floor on a log one (empty bins sit there)
        let (bx, by) = (xa.map(ax.lo).unwrap_or(0.0), plot.bottom() * s);
        pb.move_to(bx, by);
        for (b, v) in p.iter().enumerate() {
            let (xl, xr) = (xa.map(ax.lo + b as f64 * width).unwrap_or(bx), xa.map(ax.lo + (b + 1) as f64 * width).unwrap_or(bx));
            let y = ya.map(v.max(ya.lo)).unwrap_or(by).min(by);
            pb.line_to(xl, y);
            pb.line_to(xr, y);
        }
        pb.line_to(xa.map(ax.hi).unwrap_or(bx), by);
        let dashed = i % 2 == 0 && i > 0;
        if i == 0 {
            let mut area = pb.clone();
            area.close();
            fill(pixmap, area, theme.shade, true);
        }
        stroke(pixmap, pb, color, if i == 0 { 1.6 * s } else { 2.2 * s }, dashed.then_some([6.0 * s, 3.0 * s]));
    }
    legend_band(pixmap, &entries, (frame.x + 8.0) * s, (frame.bottom() - legend_h) * s, (frame.w - 16.0) * s, &ls);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percentages_sum_to_100() {
        let p = percentages(&[1, 3, 0, 4]);
        assert_eq!(p, vec![12.5, 37.5, 0.0, 50.0]);
        assert_eq!(percentages(&[0, 0]), vec![0.0, 0.0]);
    }

    #[test]
    fn mismatched_series_are_refused() {
        let mut p = Pixmap::new(100, 80).unwrap();
        let a = [1u64; 30];
        let b = [1u64; 29];
        let e = render_angle_histogram(&mut p, &[HistogramSeries { label: "a", counts: &a, color: None }, HistogramSeries { label: "b", counts: &b, color: None }], &AngleHistogram::default())
            .unwrap_err();
        assert!(e.to_string().contains("\"b\" has 29 bins"), "{e}");
        assert!(render_angle_histogram(&mut p, &[HistogramSeries { label: "a", counts: &[], color: None }], &AngleHistogram::default()).is_err());
        render_angle_histogram(&mut p, &[], &AngleHistogram::default()).unwrap();
    }

    /// The height of a bar's top above the axis, device pixels, for counts `c` in `bin`.
    fn bar_height(counts: &[u64], bin: usize, opts: &AngleHistogram<'_>) -> u32 {
        let mut p = Pixmap::new(300, 200).unwrap();
        let c = Color::from_rgba8(0, 0, 255, 255);
        let series = [HistogramSeries { label: "", counts, color: Some(c) }];
        render_angle_histogram(&mut p, &series, &AngleHistogram { title: "", legend: false, ..*opts }).unwrap();
        // the bin's middle column: the topmost blue pixel
        let plot_x0 = 62.0;
        let x = (plot_x0 + (300.0 - 62.0 - 14.0) * (bin as f64 + 0.5) / counts.len() as f64) as u32;
        let top = (0..200).find(|&y| {
            let px = p.pixel(x, y).unwrap();
            px.blue() > 200 && px.red() < 60
        });
        200 - top.expect("the bar is drawn")
    }

    #[test]
    fn a_shared_top_puts_two_histograms_on_one_scale() {
        // 50% in a bin: on its own scale it reaches the top; with a shared top of 100% half as high
        let counts = [1u64, 1, 0, 0, 0, 0];
        let own = bar_height(&counts, 0, &AngleHistogram::default());
        let shared = bar_height(&counts, 0, &AngleHistogram { y_top: Some(100.0), ..AngleHistogram::default() });
        assert!(shared < own, "own {own}, shared {shared}");
        // 50% of a 0..100 axis: half the plot (200 − 12 − 46 = 142 px) above the axis at y = 154
        assert!((shared as i32 - (46 + 71)).abs() <= 2, "{shared}");
    }

    #[test]
    fn a_log_axis_shows_a_rare_bin_that_a_linear_one_flattens() {
        // one angle in 10,000 in the first bin
        let counts = [1u64, 9999, 0];
        let lin = bar_height(&counts, 0, &AngleHistogram::default());
        let log = bar_height(&counts, 0, &AngleHistogram { log_y: true, ..AngleHistogram::default() });
        // 0.01% is one decade above the floor of five: a fifth of the 142-px plot
        assert!(log > lin + 20, "linear {lin}, log {log}");
    }
}
