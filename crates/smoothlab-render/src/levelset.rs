//! Level sets of one node's objective over the neighbourhood of its star, as in
//! Chen, Tristano & Kwok (2003), Figures 7, 10 and 20: filled bands and iso-lines,
//! the feasible region's border, the star's edges, the current position, the optimum
//! and the solver's path.
//!
//! The field is sampled on a grid ([`sample_field`]); iso-lines come from marching
//! squares ([`iso_segments`](super::contour::iso_segments)) and the bands from the same
//! bilinear interpolant evaluated per pixel, so lines and bands agree. Samples that are
//! not finite (a barrier objective's +∞, NaN) are masked: no band, no line, a grey hatch.

use glam::DVec2;
use tiny_skia::{Color, PathBuilder, Pixmap, PremultipliedColorU8};

use super::colormap::Colormap;
use super::contour::{chain_segments, iso_segments, Grid};
use super::mesh::bezier_control;
use super::paint::{draw_marker, fill_rect, legend_band, legend_band_height, rgba, stroke, Key, LegendEntry, LegendStyle, Marker, MarkerStyle};
use super::theme::Theme;
use super::text::{draw_text, Align, TextStyle, Valign};
use super::view::{sane_dpr, Frame, View, ZoomPan};
use smoothlab::error::{Error, Result};
use smoothlab::numeric::order::sort_total;
use smoothlab::objective::{Goal, Objective, Star};
use smoothlab::quality::{corner_edges, scaled_jacobian};

/// The most samples [`sample_field`] takes (a 2000 × 2000 grid).
pub const MAX_SAMPLES: usize = 4_000_000;

/// An objective sampled over a rectangle around a node's star.
#[derive(Clone, Debug, PartialEq)]
pub struct Field {
    pub grid: Grid,
    /// The objective at each grid point (row-major, see [`Grid`]); may hold +∞ or NaN.
    pub values: Vec<f64>,
    /// At each grid point, the smallest sine of a corner angle over the star's elements
    /// with the node moved there: positive exactly where no element is inverted, so
    /// its zero level set is the border of the feasible region.
    pub validity: Vec<f64>,
    /// Which way the objective is better (the bands are brightest at the best values).
    pub goal: Goal,
}

/// A square box around the star: the bounding box of its elements' nodes, widened by
/// `margin` (a fraction of its size) on every side. A star with no elements gives the
/// unit box around its node.
pub fn star_bounds(star: &Star, margin: f64) -> (DVec2, DVec2) {
    let mut lo = star.x0;
    let mut hi = star.x0;
    for el in &star.elems {
        for p in &el.pts[..el.kind.node_count()] {
            lo = lo.min(*p);
            hi = hi.max(*p);
        }
    }
    let size = (hi - lo).max_element();
    let size = if size > 0.0 && size.is_finite() { size } else { 1.0 };
    let c = 0.5 * (lo + hi);
    let half = 0.5 * size * (1.0 + 2.0 * margin.max(0.0));
    (c - DVec2::splat(half), c + DVec2::splat(half))
}

/// A node's objective as a function of where the node is in a plane: what a level-set
/// picture draws. The planar view's is a planar star's objective ([`StarFunction`]);
/// a node of a surface or of a volume moves in a plane through it (its tangent plane, a
/// cut plane) and the same picture draws its objective there.
pub trait PlaneFunction {
    /// Which way the objective is better.
    fn goal(&self) -> Goal;
    /// The objective with the node at `x` (may be +∞ or NaN).
    fn value(&self, x: DVec2) -> f64;
    /// Positive exactly where no element of the node's star is inverted with the node at
    /// `x`, continuous through zero: its zero level set is the feasible region's border.
    fn validity(&self, x: DVec2) -> f64;
}

/// A planar star's objective: the node of `star` moved to each point, its validity the
/// smallest corner sine (scaled Jacobian) over the star's elements.
#[derive(Clone, Copy)]
pub struct StarFunction<'a> {
    pub objective: &'a dyn Objective,
    pub star: &'a Star,
}

impl PlaneFunction for StarFunction<'_> {
    fn goal(&self) -> Goal {
        self.objective.goal()
    }
    fn value(&self, x: DVec2) -> f64 {
        self.objective.value(self.star, x)
    }
    fn validity(&self, x: DVec2) -> f64 {
        star_validity(self.star, x)
    }
}

/// A square box framing where the node of `star` can go without inverting an element of
/// it (its feasible region, found on a grid over the star's box) together with the points
/// of `keep` (the start, the optimum found), widened by `margin` (a fraction of its size)
/// on every side: a level-set view's first window, in which the feasible region is not a
/// speck of the star's extent. A star with no feasible point (a tangled one) gets
/// [`star_bounds`]; the box is never smaller than 2% of the star's.
pub fn feasible_bounds(star: &Star, keep: &[DVec2], margin: f64) -> (DVec2, DVec2) {
    feasible_bounds_of(&|p| star_validity(star, p), star, keep, margin)
}

/// [`feasible_bounds`] of a node whose star `outline` is drawn in a plane and whose
/// feasible region is where `validity` is positive ([`PlaneFunction::validity`]).
pub fn feasible_bounds_of(validity: &dyn Fn(DVec2) -> f64, outline: &Star, keep: &[DVec2], margin: f64) -> (DVec2, DVec2) {
    const N: usize = 97;
    let whole = star_bounds(outline, margin);
    if outline.is_empty() {
        return whole;
    }
    let (b0, b1) = star_bounds(outline, 0.05);
    let step = (b1 - b0) / (N - 1) as f64;
    let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    for j in 0..N {
        for i in 0..N {
            let p = b0 + step * DVec2::new(i as f64, j as f64);
            if validity(p) > 0.0 {
                lo = lo.min(p);
                hi = hi.max(p);
            }
        }
    }
    if lo.x > hi.x {
        return whole;
    }
    // the border lies within a grid step of the outermost feasible samples
    lo -= step;
    hi += step;
    for p in keep.iter().filter(|p| p.is_finite()) {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    let star_size = (b1 - b0).max_element();
    let size = (hi - lo).max_element().max(0.02 * star_size);
    let c = 0.5 * (lo + hi);
    let half = 0.5 * size * (1.0 + 2.0 * margin.max(0.0));
    (c - DVec2::splat(half), c + DVec2::splat(half))
}

/// Samples `objective` (the node of `star` moved to each grid point) and the star's
/// validity on an `nx × ny` grid over `bounds`.
pub fn sample_field(objective: &dyn Objective, star: &Star, bounds: (DVec2, DVec2), nx: usize, ny: usize) -> Result<Field> {
    let grid = level_grid(bounds, nx, ny)?;
    if star.is_empty() {
        return Err(Error::node(star.node as usize, None, "has no elements around it to draw level sets over"));
    }
    Ok(sample_on(&StarFunction { objective, star }, grid))
}

/// Samples a [`PlaneFunction`] and its validity on an `nx × ny` grid over `bounds`.
pub fn sample_plane(function: &dyn PlaneFunction, bounds: (DVec2, DVec2), nx: usize, ny: usize) -> Result<Field> {
    Ok(sample_on(function, level_grid(bounds, nx, ny)?))
}

/// The grid of a level-set field: at least 2 × 2 and at most [`MAX_SAMPLES`] samples over
/// a finite box with area.
fn level_grid(bounds: (DVec2, DVec2), nx: usize, ny: usize) -> Result<Grid> {
    if nx < 2 || ny < 2 {
        return Err(Error::invalid(format!("a level-set grid needs at least 2 × 2 samples, not {nx} × {ny}")));
    }
    if nx.saturating_mul(ny) > MAX_SAMPLES {
        return Err(Error::TooLarge(format!("a {nx} × {ny} level-set grid is over the {MAX_SAMPLES} sample limit")));
    }
    let (lo, hi) = (bounds.0.min(bounds.1), bounds.0.max(bounds.1));
    if !lo.is_finite() || !hi.is_finite() || hi.x - lo.x <= 0.0 || hi.y - lo.y <= 0.0 {
        return Err(Error::invalid(format!("level-set bounds {lo:?}..{hi:?} are not a finite box with area")));
    }
    Ok(Grid { nx, ny, lo, hi })
}

/// The function and its validity at every point of `grid`.
fn sample_on(function: &dyn PlaneFunction, grid: Grid) -> Field {
    let mut values = Vec::with_capacity(grid.len());
    let mut validity = Vec::with_capacity(grid.len());
    for j in 0..grid.ny {
        for i in 0..grid.nx {
            let x = grid.point(i, j);
            values.push(function.value(x));
            validity.push(function.validity(x));
        }
    }
    Field { grid, values, validity, goal: function.goal() }
}

/// Smallest corner sine over the star's elements with the node at `x`.
fn star_validity(star: &Star, x: DVec2) -> f64 {
    let mut v = f64::INFINITY;
    for el in &star.elems {
        let p = el.at(x);
        let k = el.kind.corners();
        for &(e1, e2) in &corner_edges(el.kind, &p[..el.kind.node_count()])[..k] {
            v = v.min(scaled_jacobian(e1, e2));
        }
    }
    v
}

/// How the levels are spaced.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Levels {
    /// At `n` evenly spaced quantiles of the finite samples: every band covers about the
    /// same area, so both the bowl and the steep penalty walls get lines. The default (14).
    Quantiles(usize),
    /// `n` levels whose distance from the best sample grows geometrically.
    Log(usize),
    /// `n` evenly spaced levels between the smallest and largest finite sample.
    Linear(usize),
}

impl Default for Levels {
    fn default() -> Self {
        Levels::Quantiles(14)
    }
}

/// The level values for `field`: finite, strictly increasing, at most `n` of them
/// (fewer when samples repeat); empty when no sample is finite.
pub fn choose_levels(field: &Field, levels: Levels) -> Vec<f64> {
    let mut v: Vec<f64> = field.values.iter().copied().filter(|x| x.is_finite()).collect();
    if v.len() < 2 {
        return Vec::new();
    }
    sort_total(&mut v);
    let (min, max) = (v[0], v[v.len() - 1]);
    let mut out: Vec<f64> = match levels {
        Levels::Quantiles(n) => (1..=n)
            .map(|k| {
                let q = k as f64 / (n + 1) as f64 * (v.len() - 1) as f64;
                let (i, f) = (q.floor() as usize, q - q.floor());
                v[i] + f * (v[(i + 1).min(v.len() - 1)] - v[i])
            })
            .collect(),
        Levels::Linear(n) => (1..=n).map(|k| min + (max - min) * k as f64 / (n + 1) as f64).collect(),
        Levels::Log(n) => {
            // distances from the best value, spaced geometrically from the 1 % quantile
            // of the positive distances to the largest
            let best = if field.goal == Goal::MaximizeMin { max } else { min };
            let mut d: Vec<f64> = v.iter().map(|x| (x - best).abs()).filter(|d| *d > 0.0).collect();
            sort_total(&mut d);
            if d.is_empty() {
                return Vec::new();
            }
            let (d0, d1) = (d[d.len() / 100], d[d.len() - 1]);
            let d0 = d0.max(d1 * 1e-12);
            (0..n)
                .map(|k| {
                    let t = if n > 1 { k as f64 / (n - 1) as f64 } else { 0.0 };
                    let dist = d0 * (d1 / d0).powf(t);
                    if field.goal == Goal::MaximizeMin {
                        best - dist
                    } else {
                        best + dist
                    }
                })
                .collect()
        }
    };
    out.retain(|x| x.is_finite());
    sort_total(&mut out);
    out.dedup_by(|a, b| (*a - *b).abs() <= 1e-12 * (1.0 + b.abs()));
    out
}

/// `n` levels at evenly spaced quantiles of the finite samples *inside the feasible
/// region* (validity > 0): a figure about the level sets in the feasible region (Chen et
/// al. 2003, Fig. 10: "the level sets in the feasible region") spends every line there,
/// rather than on the infeasible walls around it. [`choose_levels`]`(Quantiles(n))` when
/// fewer than two feasible samples are finite.
pub fn feasible_levels(field: &Field, n: usize) -> Vec<f64> {
    let inside: Vec<f64> =
        field.values.iter().zip(&field.validity).filter(|(v, ok)| v.is_finite() && **ok > 0.0).map(|(v, _)| *v).collect();
    if inside.len() < 2 {
        return choose_levels(field, Levels::Quantiles(n));
    }
    choose_levels(&Field { values: inside, validity: Vec::new(), ..field.clone() }, Levels::Quantiles(n))
}

/// A figure's own mark on a level-set panel, in world coordinates, listed in the legend
/// under its label (none when the label is empty): Chen et al. (2003), Fig. 9's dashed
/// end tangents, an optimum found by search, a direction a solver tried.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Overlay<'a> {
    /// A polyline.
    Line { points: &'a [DVec2], color: Color, dashed: bool, label: &'a str },
    /// An arrow from `from` to `to`.
    Arrow { from: DVec2, to: DVec2, color: Color, label: &'a str },
    /// A point marker.
    Point { at: DVec2, marker: Marker, color: Color, label: &'a str },
}

impl Overlay<'_> {
    fn legend(&self) -> Option<LegendEntry<'_>> {
        let (label, color, key) = match *self {
            Overlay::Line { color, dashed, label, .. } => (label, color, Key::Line { dashed, marker: None }),
            Overlay::Arrow { color, label, .. } => (label, color, Key::Line { dashed: false, marker: None }),
            Overlay::Point { marker, color, label, .. } => (label, color, Key::Marker(marker)),
        };
        (!label.is_empty()).then_some(LegendEntry { label, color, key })
    }
}

/// What [`render_level_set_with`] adds to a panel: marks of its own and, instead of
/// [`LevelSetView::levels`], levels chosen by the caller (e.g. [`feasible_levels`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LevelSetExtras<'a> {
    pub overlays: &'a [Overlay<'a>],
    pub levels: Option<&'a [f64]>,
}

/// The solver's path on a level-set panel: a magenta no band of the colour map and no
/// star edge (black) has.
pub const PATH_RGB: (u8, u8, u8) = (204, 0, 153);
fn path_color() -> Color {
    rgba(PATH_RGB.0, PATH_RGB.1, PATH_RGB.2, 255)
}

/// How the solver got to an iterate of the path drawn on a level-set panel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PathKind {
    /// The starting position.
    Start,
    /// After a steepest-descent (gradient) step.
    Gradient,
    /// After a conjugate-direction step (Fletcher–Reeves).
    Conjugate,
    /// After an active-set step of Freitag's max-min ascent.
    ActiveSet,
    /// After a Newton step (Fletcher–Reeves with Newton's first trial).
    Newton,
    /// After a (smart) Laplacian move.
    Laplacian,
}

impl PathKind {
    const ALL: [PathKind; 6] =
        [PathKind::Start, PathKind::Gradient, PathKind::Conjugate, PathKind::ActiveSet, PathKind::Newton, PathKind::Laplacian];
    pub fn marker(self) -> Marker {
        match self {
            PathKind::Start => Marker::Circle,
            PathKind::Gradient => Marker::Circle,
            PathKind::Conjugate => Marker::Triangle,
            PathKind::ActiveSet => Marker::Square,
            PathKind::Newton => Marker::Triangle,
            PathKind::Laplacian => Marker::Diamond,
        }
    }
    pub fn color(self) -> Color {
        match self {
            PathKind::Start => Color::WHITE,
            PathKind::Gradient => rgba(86, 180, 233, 255),
            PathKind::Conjugate => rgba(230, 159, 0, 255),
            PathKind::ActiveSet => rgba(204, 121, 167, 255),
            PathKind::Newton => rgba(213, 94, 0, 255),
            PathKind::Laplacian => rgba(0, 158, 115, 255),
        }
    }
    pub fn label(self) -> &'static str {
        match self {
            PathKind::Start => "start",
            PathKind::Gradient => "gradient step",
            PathKind::Conjugate => "conjugate step",
            PathKind::ActiveSet => "active-set step",
            PathKind::Newton => "Newton step",
            PathKind::Laplacian => "Laplacian move",
        }
    }
}

/// The data of one level-set panel.
#[derive(Clone, Copy, Debug)]
pub struct LevelSet<'a> {
    pub field: &'a Field,
    /// The star whose edges are drawn (at its gathered position `x0`).
    pub star: &'a Star,
    /// The solver's iterates in order, each with how it was reached.
    pub path: &'a [(DVec2, PathKind)],
    /// The optimum found, if any.
    pub optimum: Option<DVec2>,
    /// Panel title (e.g. "new objective (Chen et al.)").
    pub title: &'a str,
}

/// Options of [`render_level_set`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LevelSetView {
    /// Default [`Levels::Quantiles`]`(14)`.
    pub levels: Levels,
    /// Default viridis.
    pub colormap: Colormap,
    /// Device-pixel ratio. Default 1.
    pub dpr: f32,
    /// Where to draw, CSS pixels. Default the whole pixmap.
    pub frame: Option<Frame>,
    /// Draw iso-lines over the bands. Default true.
    pub isolines: bool,
    /// Draw the legend (in a band under the plot, which shrinks to make room). Default true.
    pub legend: bool,
    /// Whiten what the star and the path draw outside the field's box (a zoomed view
    /// samples only the part of the star it shows). Default false.
    pub clip: bool,
    /// Colours and label sizes. Default [`Theme::light`].
    pub theme: Theme,
}

impl Default for LevelSetView {
    fn default() -> Self {
        LevelSetView { levels: Levels::default(), colormap: Colormap::Viridis, dpr: 1.0, frame: None, isolines: true, legend: true, clip: false, theme: Theme::light() }
    }
}

/// The baselines of a level-set panel's title and note and the height of the band they
/// take above the plot, CSS pixels: 18, 33 and 40, grown with the theme's labels.
fn title_band(theme: &Theme) -> (f32, f32, f32) {
    let (g_title, g_note) = (theme.grow(14.0), theme.grow(10.5));
    let title = 18.0 * g_title;
    let note = title + 15.0 * g_note;
    (title, note, note + 7.0 * g_note)
}

/// The view a level-set panel of `frame` (CSS pixels) draws the world box `lo..hi` with,
/// its legend taking `legend_h` CSS pixels under the plot ([`level_set_legend_height`]):
/// the one [`render_level_set`] uses for a field sampled over that box.
pub fn level_set_view(frame: Frame, lo: DVec2, hi: DVec2, dpr: f32, theme: &Theme, legend_h: f32) -> View {
    View::fit(lo, hi, plot_frame(frame, theme, legend_h), 8.0, ZoomPan::default(), sane_dpr(dpr))
}

/// The plot of a level-set panel: the frame less the title band and the legend's.
fn plot_frame(frame: Frame, theme: &Theme, legend_h: f32) -> Frame {
    frame.inset(0.0, title_band(theme).2, 0.0, legend_h.max(0.0))
}

/// What a level-set panel's legend lists for `data` and `extras`.
fn legend_entries<'a>(data: &LevelSet<'a>, extras: &LevelSetExtras<'a>) -> Vec<LegendEntry<'a>> {
    let field = data.field;
    let mut entries = vec![
        LegendEntry { label: "current position", color: Color::WHITE, key: Key::Marker(Marker::Circle) },
        LegendEntry { label: "feasible border", color: rgba(228, 26, 28, 255), key: Key::Line { dashed: true, marker: None } },
        LegendEntry { label: "an element inverted", color: rgba(33, 144, 141, 255), key: Key::Hatched },
    ];
    // +∞ is a barrier's value where a valid element would fold (the `new` objective on a
    // valid star); NaN is a value the objective does not define
    if field.values.iter().any(|v| v.is_nan()) {
        entries.push(LegendEntry { label: "objective undefined", color: rgba(225, 225, 225, 255), key: Key::Hatched });
    } else if field.values.iter().any(|v| v.is_infinite()) {
        entries.push(LegendEntry { label: "+∞: the barrier", color: rgba(225, 225, 225, 255), key: Key::Hatched });
    }
    if data.path.len() > 1 {
        entries.push(LegendEntry { label: "solver's path", color: path_color(), key: Key::Line { dashed: false, marker: None } });
    }
    for kind in PathKind::ALL {
        if kind != PathKind::Start && data.path.iter().any(|(_, k)| *k == kind) {
            entries.push(LegendEntry { label: kind.label(), color: kind.color(), key: Key::Marker(kind.marker()) });
        }
    }
    if data.optimum.is_some() {
        entries.push(LegendEntry { label: "optimum", color: rgba(240, 228, 66, 255), key: Key::Marker(Marker::Star) });
    }
    entries.extend(extras.overlays.iter().filter_map(Overlay::legend));
    entries
}

/// The CSS pixels the legend of `data` takes under the plot of a panel `frame_w` CSS
/// pixels wide drawn with `opts` (0 without a legend): what [`level_set_view`] needs to
/// map pointer positions as [`render_level_set`] drew them.
pub fn level_set_legend_height(data: &LevelSet<'_>, opts: &LevelSetView, frame_w: f32) -> f32 {
    level_set_legend_height_with(data, opts, &LevelSetExtras::default(), frame_w)
}

/// [`level_set_legend_height`] of a panel drawn by [`render_level_set_with`].
pub fn level_set_legend_height_with(data: &LevelSet<'_>, opts: &LevelSetView, extras: &LevelSetExtras<'_>, frame_w: f32) -> f32 {
    if !opts.legend {
        return 0.0;
    }
    let s = sane_dpr(opts.dpr);
    let ls = LegendStyle::new(&opts.theme, s * 0.9, s);
    legend_band_height(&legend_entries(data, extras), (frame_w - 8.0) * s, &ls) / s
}

/// Draws one level-set panel and returns its view (world ↔ pixels).
pub fn render_level_set(pixmap: &mut Pixmap, data: &LevelSet<'_>, opts: &LevelSetView) -> View {
    render_level_set_with(pixmap, data, opts, &LevelSetExtras::default())
}

/// [`render_level_set`] with a figure's own marks and levels ([`LevelSetExtras`]).
pub fn render_level_set_with(pixmap: &mut Pixmap, data: &LevelSet<'_>, opts: &LevelSetView, extras: &LevelSetExtras<'_>) -> View {
    let s = sane_dpr(opts.dpr);
    let frame = opts.frame.unwrap_or(Frame::of_pixmap(pixmap, s));
    let theme = &opts.theme;
    fill_rect(pixmap, frame.x * s, frame.y * s, frame.w * s, frame.h * s, theme.paper);
    let (title_y, note_y, _) = title_band(theme);
    let legend_h = level_set_legend_height_with(data, opts, extras, frame.w);
    let plot = plot_frame(frame, theme, legend_h);
    super::layout::note(pixmap, super::layout::RegionKind::Plot, plot.x * s, plot.y * s, plot.w * s, plot.h * s);
    let field = data.field;
    let grid = field.grid;
    let view = level_set_view(frame, grid.lo, grid.hi, s, theme, legend_h);
    let levels = extras.levels.map_or_else(|| choose_levels(field, opts.levels), <[f64]>::to_vec);

    draw_bands(pixmap, field, &levels, &view, plot, opts.colormap, s);

    let mut segs = Vec::new();
    let tol = 1e-9 * (grid.hi - grid.lo).max_element();
    let to_path = |segs: &[[DVec2; 2]]| {
        let mut pb = PathBuilder::new();
        for line in chain_segments(segs, tol) {
            for (i, p) in line.iter().enumerate() {
                let (x, y) = view.device_xy(*p);
                if i == 0 {
                    pb.move_to(x, y);
                } else {
                    pb.line_to(x, y);
                }
            }
        }
        pb
    };
    if opts.isolines {
        for &l in &levels {
            iso_segments(&grid, &field.values, l, &mut segs);
        }
        stroke(pixmap, to_path(&segs), rgba(0, 0, 0, 120), 0.8 * s, None);
    }
    // the star's edges at the node's gathered position
    let mut edges = PathBuilder::new();
    for el in &data.star.elems {
        let k = el.kind.corners();
        let pts: Vec<(f32, f32)> = el.pts[..el.kind.node_count()].iter().map(|p| view.device_xy(*p)).collect();
        edges.move_to(pts[0].0, pts[0].1);
        for i in 0..k {
            let b = pts[(i + 1) % k];
            match el.kind.mid(i) {
                Some(m) => {
                    let c = bezier_control(pts[i], pts[m], b);
                    edges.quad_to(c.0, c.1, b.0, b.1);
                }
                None => edges.line_to(b.0, b.1),
            }
        }
        edges.close();
    }
    stroke(pixmap, edges.clone(), rgba(255, 255, 255, 200), 3.2 * s, None);
    stroke(pixmap, edges, rgba(0, 0, 0, 255), 1.4 * s, None);

    // the feasible border over the star edges it may run along
    segs.clear();
    iso_segments(&grid, &field.validity, 0.0, &mut segs);
    let border = to_path(&segs);
    stroke(pixmap, border, rgba(228, 26, 28, 255), 2.4 * s, Some([6.0 * s, 4.0 * s]));
    draw_overlay_lines(pixmap, extras.overlays, &view, s);

    // the path, then its iterates
    if data.path.len() > 1 {
        let mut pb = PathBuilder::new();
        for (i, (p, _)) in data.path.iter().enumerate() {
            let (x, y) = view.device_xy(*p);
            if i == 0 {
                pb.move_to(x, y);
            } else {
                pb.line_to(x, y);
            }
        }
        // in a colour of its own (the star's edges are black: a step along one of them
        // vanished into it), with an arrowhead where each step ends
        let mut heads = PathBuilder::new();
        for w in data.path.windows(2) {
            let (a, b) = (view.device_xy(w[0].0), view.device_xy(w[1].0));
            let (dx, dy) = (b.0 - a.0, b.1 - a.1);
            let len = (dx * dx + dy * dy).sqrt();
            if len < 9.0 * s {
                continue;
            }
            let (ux, uy) = (dx / len, dy / len);
            let (bx, by) = (b.0 - ux * 4.0 * s, b.1 - uy * 4.0 * s);
            heads.move_to(bx, by);
            heads.line_to(bx - ux * 8.0 * s - uy * 4.0 * s, by - uy * 8.0 * s + ux * 4.0 * s);
            heads.line_to(bx - ux * 8.0 * s + uy * 4.0 * s, by - uy * 8.0 * s - ux * 4.0 * s);
            heads.close();
        }
        stroke(pixmap, pb.clone(), Color::WHITE, 4.5 * s, None);
        stroke(pixmap, pb, path_color(), 2.2 * s, None);
        if let Some(h) = heads.finish() {
            pixmap.fill_path(&h, &super::paint::solid(path_color()), tiny_skia::FillRule::Winding, tiny_skia::Transform::identity(), None);
        }
    }
    for (p, kind) in data.path {
        let (x, y) = view.device_xy(*p);
        draw_marker(pixmap, kind.marker(), x, y, MarkerStyle { r: 4.0 * s, fill: kind.color(), edge: Color::BLACK, width: s });
    }
    let (cx, cy) = view.device_xy(data.star.x0);
    let mut ring = PathBuilder::new();
    ring.push_circle(cx, cy, 6.5 * s);
    stroke(pixmap, ring.clone(), Color::WHITE, 3.5 * s, None);
    stroke(pixmap, ring, Color::BLACK, 1.6 * s, None);
    if let Some(o) = data.optimum {
        let (x, y) = view.device_xy(o);
        draw_marker(pixmap, Marker::Star, x, y, MarkerStyle { r: 6.5 * s, fill: rgba(240, 228, 66, 255), edge: Color::BLACK, width: 1.2 * s });
        super::layout::note_mark(pixmap, x, y, rgba(240, 228, 66, 255));
    }
    for o in extras.overlays {
        if let Overlay::Point { at, marker, color, .. } = *o {
            let (x, y) = view.device_xy(at);
            draw_marker(pixmap, marker, x, y, MarkerStyle { r: 6.5 * s, fill: color, edge: Color::BLACK, width: 1.2 * s });
            super::layout::note_mark(pixmap, x, y, color);
        }
    }

    if opts.clip {
        // what lies outside the sampled box is not part of this view
        let (a, b) = (view.device_xy(grid.lo), view.device_xy(grid.hi));
        let (x0, x1, y0, y1) = (a.0.min(b.0), a.0.max(b.0), a.1.min(b.1), a.1.max(b.1));
        let (fx, fy, fr, fb) = (frame.x * s, frame.y * s, frame.right() * s, frame.bottom() * s);
        fill_rect(pixmap, fx, fy, frame.w * s, y0 - fy, theme.paper);
        fill_rect(pixmap, fx, y1, frame.w * s, fb - y1, theme.paper);
        fill_rect(pixmap, fx, y0, x0 - fx, y1 - y0, theme.paper);
        fill_rect(pixmap, x1, y0, fr - x1, y1 - y0, theme.paper);
    }

    // title and a one-line key to the bands
    // both shrink to fit a narrow frame (an embedded view) rather than be clipped
    let room = (frame.w - 8.0) * s;
    let (shown, size) = theme.fit_title(data.title, 14.0 * s, room, s);
    let title = TextStyle::new(size).with_color(theme.ink).with_align(Align::Centre, Valign::Baseline);
    draw_text(pixmap, &shown, (frame.x + 0.5 * frame.w) * s, (frame.y + title_y) * s, title);
    let better = if field.goal == Goal::MaximizeMin { "maximised" } else { "minimised" };
    let note = format!("{better}: the brighter the band, the better");
    let (shown, size) = theme.fit_title(&note, 10.5 * s, room, s);
    let sub = TextStyle::new(size).with_color(theme.muted).with_align(Align::Centre, Valign::Baseline);
    draw_text(pixmap, &shown, (frame.x + 0.5 * frame.w) * s, (frame.y + note_y) * s, sub);

    if opts.legend {
        let ls = LegendStyle::new(theme, s * 0.9, s);
        legend_band(pixmap, &legend_entries(data, extras), (frame.x + 4.0) * s, (frame.bottom() - legend_h) * s, (frame.w - 8.0) * s, &ls);
    }
    view
}

/// The lines and arrows of `overlays`, each over a white halo so it reads on any band.
fn draw_overlay_lines(pixmap: &mut Pixmap, overlays: &[Overlay<'_>], view: &View, s: f32) {
    for o in overlays {
        let (pts, color, dashed, arrow) = match *o {
            Overlay::Line { points, color, dashed, .. } => (points.to_vec(), color, dashed, false),
            Overlay::Arrow { from, to, color, .. } => (vec![from, to], color, false, true),
            Overlay::Point { .. } => continue,
        };
        let dev: Vec<(f32, f32)> = pts.iter().map(|p| view.device_xy(*p)).collect();
        let mut pb = PathBuilder::new();
        for (i, &(x, y)) in dev.iter().enumerate() {
            if i == 0 {
                pb.move_to(x, y);
            } else {
                pb.line_to(x, y);
            }
        }
        let dash = dashed.then_some([9.0 * s, 6.0 * s]);
        stroke(pixmap, pb.clone(), rgba(255, 255, 255, 230), 4.6 * s, dash);
        stroke(pixmap, pb, color, 2.4 * s, dash);
        if let (true, [.., a, b]) = (arrow, dev.as_slice()) {
            let (dx, dy) = (b.0 - a.0, b.1 - a.1);
            let len = (dx * dx + dy * dy).sqrt();
            if len > 1.0 {
                let (ux, uy) = (dx / len, dy / len);
                let mut head = PathBuilder::new();
                head.move_to(b.0, b.1);
                head.line_to(b.0 - ux * 12.0 * s - uy * 6.0 * s, b.1 - uy * 12.0 * s + ux * 6.0 * s);
                head.line_to(b.0 - ux * 12.0 * s + uy * 6.0 * s, b.1 - uy * 12.0 * s - ux * 6.0 * s);
                head.close();
                let halo = head.clone();
                stroke(pixmap, halo, rgba(255, 255, 255, 230), 2.0 * s, None);
                super::paint::fill(pixmap, head, color, true);
            }
        }
    }
}

/// Per-pixel bands of the bilinear interpolant; masked samples in hatched grey, the
/// infeasible region striped dark.
fn draw_bands(pixmap: &mut Pixmap, field: &Field, levels: &[f64], view: &View, plot: Frame, map: Colormap, s: f32) {
    let (w, h) = (pixmap.width() as i64, pixmap.height() as i64);
    let x0 = ((plot.x * s).floor() as i64).clamp(0, w);
    let x1 = ((plot.right() * s).ceil() as i64).clamp(0, w);
    let y0 = ((plot.y * s).floor() as i64).clamp(0, h);
    let y1 = ((plot.bottom() * s).ceil() as i64).clamp(0, h);
    let n = levels.len();
    let better_high = field.goal == Goal::MaximizeMin;
    let colours: Vec<[u8; 3]> = (0..=n)
        .map(|k| {
            let t = if n == 0 { 0.5 } else { k as f64 / n as f64 };
            map.rgb(if better_high { t } else { 1.0 - t })
        })
        .collect();
    let stripe = (6.0 * s).max(3.0) as i64;
    let pixels = pixmap.pixels_mut();
    for py in y0..y1 {
        for px in x0..x1 {
            let p = view.device_to_world(DVec2::new(px as f64 + 0.5, py as f64 + 0.5));
            let inside = p.x >= field.grid.lo.x && p.x <= field.grid.hi.x && p.y >= field.grid.lo.y && p.y <= field.grid.hi.y;
            if !inside {
                continue;
            }
            let v = field.grid.bilinear(&field.values, p);
            let on_stripe = (px + py).rem_euclid(stripe) < (stripe / 3).max(1);
            let mut c = if v.is_finite() {
                colours[levels.partition_point(|l| *l <= v)]
            } else if on_stripe {
                [150, 150, 150]
            } else {
                [225, 225, 225]
            };
            let valid = field.grid.bilinear(&field.validity, p);
            let infeasible = valid.is_nan() || valid <= 0.0;
            if v.is_finite() && infeasible && on_stripe {
                // stripes that contrast with the band: dark on light bands, light on dark
                let luma = (2 * c[0] as u32 + 7 * c[1] as u32 + c[2] as u32) / 10;
                c = if luma > 100 { c.map(|x| x / 3) } else { c.map(|x| ((x as u32 + 2 * 255) / 3) as u8) };
            }
            if let Some(q) = PremultipliedColorU8::from_rgba(c[0], c[1], c[2], 255) {
                pixels[(py * w + px) as usize] = q;
            }
        }
    }
}

/// Two level-set panels side by side (old and new objectives), each with its title.
pub fn render_level_sets_side_by_side(pixmap: &mut Pixmap, left: &LevelSet<'_>, right: &LevelSet<'_>, opts: &LevelSetView) -> (View, View) {
    let s = sane_dpr(opts.dpr);
    let frame = opts.frame.unwrap_or(Frame::of_pixmap(pixmap, s));
    fill_rect(pixmap, frame.x * s, frame.y * s, frame.w * s, frame.h * s, opts.theme.paper);
    let a = render_level_set(pixmap, left, &LevelSetView { frame: Some(frame.column(0, 2, 12.0)), ..*opts });
    let b = render_level_set(pixmap, right, &LevelSetView { frame: Some(frame.column(1, 2, 12.0)), ..*opts });
    (a, b)
}

#[cfg(test)]
mod tests {
    use super::*;
    use smoothlab::optimize::test_objectives::{unit_star as hexagon_star, WalledBowl as Bowl};

    #[test]
    fn sampling_checks_its_input() {
        let star = hexagon_star();
        let obj = Bowl { c: DVec2::ZERO, wall: 10.0 };
        let b = star_bounds(&star, 0.1);
        assert!(matches!(sample_field(&obj, &star, b, 1, 5), Err(Error::Invalid(_))));
        assert!(matches!(sample_field(&obj, &star, b, 5000, 5000), Err(Error::TooLarge(_))));
        assert!(sample_field(&obj, &star, (DVec2::ZERO, DVec2::new(1.0, 0.0)), 5, 5).is_err());
        assert!(sample_field(&obj, &star, (DVec2::ZERO, DVec2::splat(f64::NAN)), 5, 5).is_err());
        let e = sample_field(&obj, &Star::new(), b, 5, 5).unwrap_err();
        assert!(e.to_string().contains("node 0"), "{e}");
    }

    #[test]
    fn feasible_region_is_the_hexagon_kernel() {
        // For a convex hexagon star the node may move anywhere inside the hexagon: the
        // zero line of the validity runs along its edges (apothem √3/2).
        let star = hexagon_star();
        let obj = Bowl { c: DVec2::ZERO, wall: 10.0 };
        let f = sample_field(&obj, &star, star_bounds(&star, 0.1), 121, 121).unwrap();
        assert!(f.grid.bilinear(&f.validity, DVec2::ZERO) > 0.8);
        assert!(f.grid.bilinear(&f.validity, DVec2::new(0.0, 0.95)) < 0.0);
        let mut segs = Vec::new();
        iso_segments(&f.grid, &f.validity, 0.0, &mut segs);
        assert!(!segs.is_empty());
        let apothem = 3f64.sqrt() / 2.0;
        let h = f.grid.spacing().x;
        for p in segs.iter().flatten() {
            // distance to the hexagon boundary along the normal of the nearest edge
            let a = p.y.atan2(p.x).rem_euclid(std::f64::consts::PI / 3.0) - std::f64::consts::PI / 6.0;
            let r = p.length() * a.cos();
            assert!((r - apothem).abs() < 2.0 * h, "border point {p:?} at {r}");
        }
    }

    #[test]
    fn levels_are_increasing_and_masked_samples_ignored() {
        let star = hexagon_star();
        let obj = Bowl { c: DVec2::new(0.1, -0.2), wall: 0.5 };
        let f = sample_field(&obj, &star, star_bounds(&star, 0.1), 41, 41).unwrap();
        assert!(f.values.iter().any(|v| v.is_infinite()));
        for lv in [Levels::Quantiles(10), Levels::Log(10), Levels::Linear(10)] {
            let l = choose_levels(&f, lv);
            assert!(l.len() >= 8 && l.len() <= 10, "{lv:?}: {l:?}");
            assert!(l.windows(2).all(|w| w[0] < w[1]) && l.iter().all(|v| v.is_finite()), "{lv:?}: {l:?}");
        }
        // quantile levels split the finite samples into bands of about equal counts
        let l = choose_levels(&f, Levels::Quantiles(4));
        let finite: Vec<f64> = f.values.iter().copied().filter(|v| v.is_finite()).collect();
        for (k, lv) in l.iter().enumerate() {
            let below = finite.iter().filter(|v| *v <= lv).count() as f64 / finite.len() as f64;
            assert!((below - (k + 1) as f64 / 5.0).abs() < 0.03, "level {k}: {below}");
        }
        // log levels crowd near the best value
        let l = choose_levels(&f, Levels::Log(10));
        assert!(l[1] - l[0] < l[9] - l[8]);
        let empty = Field { values: vec![f64::NAN; f.values.len()], ..f.clone() };
        assert!(choose_levels(&empty, Levels::default()).is_empty());
    }
}
