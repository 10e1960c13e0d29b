//! The page's pictures, drawn by [`smoothlab_render`] into tiny-skia pixmaps: both panels'
//! meshes on one shared scale, one node's level sets with the solver's path (Chen et al.
//! 2003, Figs. 10 and 20), its solve history, the per-pass curves and the angle
//! histograms (Freitag 1997, Fig. 3). Every view paints an opaque background, so the
//! premultiplied pixels are also straight RGBA, as a canvas `ImageData` wants.

use glam::DVec2;
use tiny_skia::Pixmap;

use super::{raster, PassSummary, Playground, Side, WorkDone};
use smoothlab::error::{Error, Result};
use smoothlab::objective::{Goal, Star};
use smoothlab::optimize::{DirectionKind, SolveResult, StopReason};
use smoothlab::quality::MeshStats;
use smoothlab_render::{
    level_set_legend_height, mesh_view, percentages, render_angle_histogram, render_chart, render_compare, render_level_set, render_mesh,
    render_pass_histories_titled, sample_plane, AngleHistogram, Chart, ComparePanel, Frame, HistogramSeries, LevelSet, LevelSetView,
    MeshView, PassHistory, PathKind, PlaneFunction, Series, StarFunction, Theme, View, PASS_TITLES,
};

/// Largest side of a picture, device pixels.
pub const MAX_SIDE: u32 = 4096;
/// Samples per side of the level-set grid: smooth enough at any canvas size, and cheap.
pub const LEVEL_SET_SAMPLES: usize = 161;
/// Room around the feasible region (with the start and the optimum) in the level-set
/// view, as a fraction of its size.
pub const LEVEL_SET_MARGIN: f64 = 0.1;

/// An opaque white pixmap of `w × h` device pixels, or an error saying why not.
pub fn pixmap(w: u32, h: u32) -> Result<Pixmap> {
    if w == 0 || h == 0 || w > MAX_SIDE || h > MAX_SIDE {
        return Err(Error::invalid(format!("a picture of {w} × {h} pixels: give 1 to {MAX_SIDE} on each side")));
    }
    let mut pm = Pixmap::new(w, h).ok_or_else(|| Error::invalid(format!("cannot allocate a {w} × {h} picture")))?;
    pm.fill(tiny_skia::Color::WHITE);
    // a panel at the address of a freed one: its notes are not this one's
    smoothlab_render::layout::forget(&pm);
    Ok(pm)
}

/// Where a mesh panel is drawn: its size and device-pixel ratio, as the page's canvas.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Canvas {
    pub w: u32,
    pub h: u32,
    pub dpr: f32,
}

/// What a node's level-set view says in words.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct NodeSummary {
    pub node: usize,
    pub old: SolveSummary,
    pub new: SolveSummary,
}

/// One side's solve at a node, in numbers.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SolveSummary {
    /// What the side smooths with ([`Choice::label`](super::Choice::label)).
    pub label: String,
    /// `larger` (a max-min objective) or `smaller` (a sum to minimise) is better.
    pub better: &'static str,
    pub value0: f64,
    pub value: f64,
    pub iterations: u32,
    pub stop: String,
}

impl SolveSummary {
    fn text(&self, side: Side) -> String {
        format!(
            "{}, {} ({} is better): {:.4} → {:.4} in {} iterations ({})",
            side.letter(),
            self.label,
            self.better,
            self.value0,
            self.value,
            self.iterations,
            self.stop
        )
    }
}

impl NodeSummary {
    /// One line for the page.
    pub fn text(&self) -> String {
        format!("Node {}: {}; {}.", self.node, self.old.text(Side::A), self.new.text(Side::B))
    }
}

/// The worst condition number as a figure says it (∞ when an element is inverted).
fn kappa_words(k: f64) -> String {
    if k.is_finite() {
        format!("{k:.3}")
    } else {
        "∞ (inverted)".to_string()
    }
}

/// `larger` or `smaller`: which values of an objective are better.
fn better_words(goal: Goal) -> &'static str {
    match goal {
        Goal::MaximizeMin => "larger",
        Goal::MinimizeSum => "smaller",
    }
}

/// Why a solve stopped, as the page says it.
pub fn stop_words(s: StopReason) -> &'static str {
    match s {
        StopReason::MaxIter => "stopped at the iteration limit",
        StopReason::Optimal => "at an optimum",
        StopReason::SmallStep => "the step became too small to help",
        StopReason::SmallImprovement => "the improvement became negligible",
        StopReason::LineSearchFailed => "no better point along the search direction",
        StopReason::NotFinite => "the objective is not finite here (an inverted element)",
        StopReason::DegenerateStar => "the star has no size",
    }
}

pub(crate) fn path_kind(d: DirectionKind) -> PathKind {
    match d {
        DirectionKind::Gradient => PathKind::Gradient,
        DirectionKind::Conjugate => PathKind::Conjugate,
        DirectionKind::ActiveSet => PathKind::ActiveSet,
        DirectionKind::Newton => PathKind::Newton,
    }
}

impl Playground {
    /// The mesh view options of a panel: both panels share the original mesh's bounds, so
    /// they compare at one scale and a dragged node does not rescale the picture.
    fn mesh_options(&self, c: Canvas, highlight: Option<usize>) -> MeshView {
        let mut o = MeshView::default().with_dpr(c.dpr).with_highlight(highlight).with_zoom(self.zoom());
        o.bounds = Some(self.bounds());
        o.theme = self.theme();
        o
    }

    /// Draws a panel's mesh coloured by quality, `highlight` with its star. A mesh too
    /// fine for its edges to show (judged on the mesh as loaded) is drawn by
    /// [`raster::render_fine`] (the same picture, much faster), and its picture without
    /// the highlight is kept: drawn again for the same positions and canvas, only the
    /// highlight is added.
    pub fn render_panel(&self, side: Side, c: Canvas, highlight: Option<usize>) -> Result<Pixmap> {
        let mut pm = pixmap(c.w, c.h)?;
        let panel = self.panel(side);
        let opts = self.mesh_options(c, highlight);
        let view = raster::view_of(&pm, &panel.mesh, &opts);
        if !raster::applies(self.mean_edge, &view, &opts) {
            render_mesh(&mut pm, &panel.mesh, &opts);
            return Ok(pm);
        }
        {
            let mut cache = panel.picture.borrow_mut();
            match cache.as_ref() {
                Some((v, cc, z, base)) if *v == panel.version && *cc == c && *z == opts.zoom => pm = base.clone(),
                _ => {
                    raster::render_fine(&mut pm, &panel.mesh, &panel.buckets, &view, &MeshView { highlight: None, ..opts });
                    *cache = Some((panel.version, c, opts.zoom, pm.clone()));
                }
            }
        }
        // the marks of a sliding boundary on top: the kept picture is the positions' alone
        smoothlab_render::draw_sliding_boundary(&mut pm, &panel.mesh, &view, c.dpr, None);
        if let Some(n) = highlight {
            raster::draw_highlight(&mut pm, &panel.mesh, &view, n, c.dpr);
        }
        Ok(pm)
    }

    /// Whether the panels on canvas `c` carry the colour bar (a small canvas leaves it
    /// out, and the page shows the scale beside it).
    pub fn panel_colour_bar(&self, c: Canvas) -> bool {
        smoothlab_render::mesh_colour_bar_shown(c.w, c.h, &self.panel(Side::A).mesh, &self.mesh_options(c, None))
    }

    /// The view the panels are drawn with on canvas `c` (the same for both).
    pub fn panel_view(&self, c: Canvas) -> View {
        mesh_view(c.w, c.h, &self.panel(Side::A).mesh, &self.mesh_options(c, None))
    }

    /// Level sets of one side's objective round `node` (on that side's current mesh),
    /// with the path the solver takes from the node's position.
    pub fn render_level_set(&self, side: Side, node: usize, c: Canvas) -> Result<(Pixmap, SolveResult)> {
        let result = self.solve_node(side, node)?;
        let panel = self.panel(side);
        let mut star = Star::new();
        star.gather(&panel.mesh, node);
        let (_, bounds) = self.level_bounds(side, node);
        let title = self.settings.side_title(side);
        let function = StarFunction { objective: panel.objective.as_ref(), star: &star };
        let (pm, legend_h) = level_set_picture(&function, &star, &result, bounds, &title, c, self.theme())?;
        let mut legend = self.level_legend.get();
        legend[side as usize] = legend_h;
        self.level_legend.set(legend);
        Ok((pm, result))
    }

    /// Both sides' level sets at `node` and a chart of their solve histories.
    pub fn render_node_view(&self, node: usize, level: Canvas, chart: Canvas) -> Result<([Pixmap; 3], NodeSummary)> {
        let (old_pm, old) = self.render_level_set(Side::A, node, level)?;
        let (new_pm, new) = self.render_level_set(Side::B, node, level)?;
        let labels = Side::BOTH.map(|side| self.settings.choice(side).label());
        let goals = Side::BOTH.map(|side| self.settings.choice(side).objective.goal());
        let pm = solve_chart([&old, &new], [&labels[0], &labels[1]], goals, chart, self.theme())?;
        let summary = |side: Side, r: &SolveResult| SolveSummary::of(&labels[side.index()], goals[side.index()], r);
        Ok(([old_pm, new_pm, pm], NodeSummary { node, old: summary(Side::A, &old), new: summary(Side::B, &new) }))
    }

    /// Per-pass curves of both sides (min/max angle, min quality, inverted elements;
    /// pass 0 is the mesh as loaded).
    pub fn render_pass_chart(&self, c: Canvas) -> Result<Pixmap> {
        let records = Side::BOTH.map(|side| &self.panel(side).records[..]);
        let labels = Side::BOTH.map(|side| self.side_label(side));
        pass_chart(self.original_stats(), records, &labels, &PASS_TITLES, c, self.theme())
    }

    /// The figure for slides: A's mesh on the left and B's on the right, on one scale,
    /// each titled with what it runs and how many passes, with its statistics under it and
    /// the quality colour bar ([`render_compare`]; `smoothlab render --view compare`).
    pub fn render_figure(&self, c: Canvas) -> Result<Pixmap> {
        let lines = |side: Side| figure_lines(self.full_stats(side), &self.table(side).work, FigureWords::PLANAR);
        let title = |side: Side| figure_title(&self.side_label(side), self.panel(side).records.len());
        let (lo, ln) = (lines(Side::A), lines(Side::B));
        let (to, tn) = (title(Side::A), title(Side::B));
        let mut pm = pixmap(c.w, c.h)?;
        render_compare(
            &mut pm,
            &ComparePanel { mesh: &self.panel(Side::A).mesh, title: &to, lines: &lo },
            &ComparePanel { mesh: &self.panel(Side::B).mesh, title: &tn, lines: &ln },
            &MeshView { theme: self.theme(), ..MeshView::default().with_dpr(c.dpr) },
        );
        Ok(pm)
    }

    /// `A: old (max-min α/β)`, as legends name a side.
    pub fn side_label(&self, side: Side) -> String {
        self.settings.side_label(side)
    }

    /// The y scale both angle histograms share: the largest percentage in any bin of
    /// either side or of the mesh as loaded, so the two pictures compare at a glance.
    pub fn histogram_top(&self) -> f64 {
        let counts = Side::BOTH.map(|s| &self.full_stats(s).angle_histogram_6deg[..]);
        histogram_top(&self.original_stats().angle_histogram_6deg, counts)
    }

    /// The angle histogram of a side's mesh over that of the mesh as loaded, on the
    /// scale both sides share ([`histogram_top`](Self::histogram_top)), linear or
    /// logarithmic.
    pub fn render_histogram(&self, side: Side, c: Canvas, log_y: bool) -> Result<Pixmap> {
        let start = &self.original_stats().angle_histogram_6deg;
        let now = &self.full_stats(side).angle_histogram_6deg;
        let label = self.side_label(side);
        let theme = self.theme();
        let series = HistogramSeries { label: &label, counts: now, color: Some(theme.side(side as usize)) };
        let opts = AngleHistogram { title: "Corner angles (6° bins)", y_top: Some(self.histogram_top()), log_y, ..AngleHistogram::default() };
        histogram_picture(start, series, opts, c, theme)
    }
}

/// A level set of a node's objective over `bounds` of the plane it moves in, its star
/// drawn (`outline`, the node at its position), the path of the solve `result` and its
/// optimum, titled `title`, on canvas `c`; and the CSS pixels its legend took (pointer
/// positions on the picture map through it). The planar view's and the 3D lab's.
pub(crate) fn level_set_picture(
    function: &dyn PlaneFunction,
    outline: &Star,
    result: &SolveResult,
    bounds: (DVec2, DVec2),
    title: &str,
    c: Canvas,
    theme: Theme,
) -> Result<(Pixmap, f32)> {
    if outline.is_empty() {
        return Err(Error::node(outline.node as usize, None, "has no elements around it to draw level sets over"));
    }
    let field = sample_plane(function, bounds, LEVEL_SET_SAMPLES, LEVEL_SET_SAMPLES)?;
    let mut path = Vec::with_capacity(result.history.len() + 1);
    path.push((result.x0, PathKind::Start));
    path.extend(result.history.iter().map(|it| (it.x, path_kind(it.direction))));
    let data = LevelSet { field: &field, star: outline, path: &path, optimum: Some(result.x), title };
    let mut pm = pixmap(c.w, c.h)?;
    // the window frames the feasible region, not the whole star: what lies outside it
    // is not drawn
    let opts = LevelSetView { dpr: c.dpr, clip: true, theme, ..LevelSetView::default() };
    let legend = level_set_legend_height(&data, &opts, c.w as f32 / smoothlab_render::view::sane_dpr(c.dpr));
    render_level_set(&mut pm, &data, &opts);
    Ok((pm, legend))
}

/// The objective per iteration of each side's solve at one node, one chart a side, in
/// the side's colour: `labels` say what each side smooths with, `goals` which way is better.
pub(crate) fn solve_chart(results: [&SolveResult; 2], labels: [&str; 2], goals: [Goal; 2], chart: Canvas, theme: Theme) -> Result<Pixmap> {
    let mut pm = pixmap(chart.w, chart.h)?;
    let full = Frame::of_pixmap(&pm, chart.dpr);
    let series = |r: &SolveResult| -> Vec<DVec2> {
        std::iter::once(DVec2::new(0.0, r.value0))
            .chain(r.history.iter().enumerate().map(|(i, it)| DVec2::new(i as f64 + 1.0, it.value)))
            .collect()
    };
    for (i, side) in Side::BOTH.into_iter().enumerate() {
        let points = series(results[i]);
        let label = format!("{}: {}", side.letter(), labels[i]);
        let title = format!("{label}, per iteration ({} is better)", better_words(goals[i]));
        render_chart(
            &mut pm,
            &[Series::new(&label, &points).with_color(theme.side(side as usize))],
            &Chart {
                title: &title,
                x_label: "iteration",
                y_label: "objective",
                dpr: chart.dpr,
                frame: Some(full.row(i, 2, 4.0)),
                legend: false,
                theme,
                ..Chart::default()
            },
        );
    }
    Ok(pm)
}

impl SolveSummary {
    /// A side's solve in numbers: `label` what it smooths with, `goal` which way is better.
    pub fn of(label: &str, goal: Goal, r: &SolveResult) -> SolveSummary {
        SolveSummary {
            label: label.to_string(),
            better: better_words(goal),
            value0: r.value0,
            value: r.value,
            iterations: r.iterations,
            stop: stop_words(r.stop).to_string(),
        }
    }
}

/// Per-pass curves of both sides from the statistics as loaded (`start`, pass 0) and each
/// side's pass records, in the sides' colours, the four charts titled `titles` (the
/// planar words, [`PASS_TITLES`], or another kind's).
pub(crate) fn pass_chart(
    start: &MeshStats,
    records: [&[PassSummary]; 2],
    labels: &[String; 2],
    titles: &[&str; 4],
    c: Canvas,
    theme: Theme,
) -> Result<Pixmap> {
    let hist = |side: Side| {
        let r = records[side.index()];
        let col = |f0: f64, f: &dyn Fn(&PassSummary) -> f64| -> Vec<f64> { std::iter::once(f0).chain(r.iter().map(f)).collect() };
        [
            col(start.min_angle_deg, &|r| r.after.min_angle_deg),
            col(start.max_angle_deg, &|r| r.after.max_angle_deg),
            col(start.min_quality, &|r| r.after.min_quality),
            col(start.inverted as f64, &|r| r.after.inverted as f64),
        ]
    };
    let cols = [hist(Side::A), hist(Side::B)];
    let runs: Vec<PassHistory<'_>> = Side::BOTH
        .iter()
        .map(|&side| {
            let c = &cols[side as usize];
            PassHistory {
                label: &labels[side as usize],
                min_angle_deg: &c[0],
                max_angle_deg: &c[1],
                min_quality: &c[2],
                inverted: &c[3],
                color: Some(theme.side(side as usize)),
            }
        })
        .collect();
    let mut pm = pixmap(c.w, c.h)?;
    render_pass_histories_titled(&mut pm, &runs, &Chart { title: "Per pass (0 = as loaded)", dpr: c.dpr, theme, ..Chart::default() }, titles);
    Ok(pm)
}

/// The largest percentage in any bin of the counts as loaded (`start`) or of either side's
/// (`now`): the y scale both sides' histograms share.
pub(crate) fn histogram_top(start: &[u64], now: [&[u64]; 2]) -> f64 {
    let top = |c: &[u64]| percentages(c).into_iter().fold(0.0, f64::max);
    now.iter().map(|c| top(c)).fold(top(start), f64::max)
}

/// A side's histogram (`series`) over the counts as loaded (`start`, "as loaded"), with
/// `opts` (its title, scale and axis; drawn at `c`'s ratio in `theme`).
pub(crate) fn histogram_picture(start: &[u64], series: HistogramSeries<'_>, opts: AngleHistogram<'_>, c: Canvas, theme: Theme) -> Result<Pixmap> {
    let mut pm = pixmap(c.w, c.h)?;
    render_angle_histogram(
        &mut pm,
        &[HistogramSeries { label: "as loaded", counts: start, color: None }, series],
        &AngleHistogram { dpr: c.dpr, theme, ..opts },
    )?;
    Ok(pm)
}

/// The words a figure's statistics lines name a kind's measures by.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FigureWords {
    pub angles: &'static str,
    pub min_quality: &'static str,
    pub mean_quality: &'static str,
}

impl FigureWords {
    /// A planar mesh's (and a surface's): corner angles, α/β.
    pub const PLANAR: FigureWords = FigureWords { angles: "angles", min_quality: "min quality", mean_quality: "mean quality" };
}

/// A panel's statistics under it in the figure for slides.
pub(crate) fn figure_lines(s: &MeshStats, work: &WorkDone, words: FigureWords) -> Vec<String> {
    let FigureWords { angles, min_quality, mean_quality } = words;
    vec![
        format!("inverted {}   {min_quality} {:.3}   {mean_quality} {:.3}", s.inverted, s.min_quality, s.mean_quality),
        format!("{angles} {:.1}° – {:.1}°   worst κ {}", s.min_angle_deg, s.max_angle_deg, kappa_words(s.max_condition)),
        format!("Laplacian moves {}   optimization calls {}", work.laplacian_moves, work.optimization_calls),
    ]
}

/// A panel's title in the figure for slides: the side's label and its passes.
pub(crate) fn figure_title(label: &str, passes: usize) -> String {
    format!("{label}, {passes} pass{}", if passes == 1 { "" } else { "es" })
}
#[cfg(test)]
mod tests {
    use super::*;
    use crate::lab::sample::Sample;
    use crate::lab::PassStage;
    use smoothlab_render::PICK_RADIUS;
    use std::collections::HashSet;

    fn colours(pm: &Pixmap) -> usize {
        pm.pixels().iter().map(|p| (p.red(), p.green(), p.blue(), p.alpha())).collect::<HashSet<_>>().len()
    }
    fn opaque(pm: &Pixmap) -> bool {
        pm.pixels().iter().all(|p| p.alpha() == 255)
    }
    const C: Canvas = Canvas { w: 300, h: 300, dpr: 1.0 };

    #[test]
    fn panels_are_drawn_opaque_and_a_pick_finds_the_free_node_drawn_there() {
        let pg = Playground::new(Sample::StarRegular.generate().unwrap()).unwrap();
        for side in Side::BOTH {
            let pm = pg.render_panel(side, C, None).unwrap();
            assert!(opaque(&pm), "straight alpha = premultiplied only when opaque");
            assert!(colours(&pm) > 8);
        }
        let view = pg.panel_view(C);
        let free = pg.topology().node_count() - 1;
        let at = view.to_css(pg.original_nodes()[free]);
        assert_eq!(pg.pick(Side::B, &view, at + DVec2::new(3.0, -2.0), PICK_RADIUS).node, Some(free));
        assert_eq!(
            pg.pick(Side::B, &view, view.to_css(pg.original_nodes()[0]), PICK_RADIUS).node,
            None,
            "fixed nodes are not picked"
        );
        assert_eq!(pg.pick(Side::B, &view, DVec2::new(f64::NAN, 0.0), PICK_RADIUS).node, None);
    }

    #[test]
    fn node_view_draws_both_level_sets_and_the_history() {
        let pg = Playground::new(Sample::StarChen.generate().unwrap()).unwrap();
        let free = pg.topology().node_count() - 1;
        let ([lo, ln, ch], s) = pg.render_node_view(free, C, Canvas { w: 300, h: 240, dpr: 1.0 }).unwrap();
        for pm in [&lo, &ln, &ch] {
            assert!(opaque(pm) && colours(pm) > 20);
        }
        assert_ne!(lo.data(), ln.data());
        assert!(s.new.value <= s.new.value0 && s.old.value >= s.old.value0);
        assert!(s.text().contains(&format!("Node {free}")));
        assert!(!s.text().contains("MaxIter") && !s.text().contains("LineSearch"), "{}", s.text());
        assert!(pg.render_node_view(0, C, C).is_err(), "fixed node");
    }

    #[test]
    fn charts_and_histograms_follow_the_passes() {
        let mut pg = Playground::new(Sample::PlateTriTangled.generate().unwrap()).unwrap();
        let before = pg.render_pass_chart(C).unwrap();
        pg.step(&|| 0.0);
        let after = pg.render_pass_chart(C).unwrap();
        assert_ne!(before.data(), after.data());
        let h = pg.render_histogram(Side::B, C, false).unwrap();
        assert!(opaque(&h) && colours(&h) > 8);
    }

    #[test]
    fn the_colour_bar_legend_is_not_cut_off_at_the_right_edge() {
        // a tangled plate with dozens of inverted elements: "inverted" and its count must
        // end inside the picture at every width and pixel ratio
        let pg = Playground::new(Sample::PlateTriTangled.generate().unwrap()).unwrap();
        assert!(pg.table(Side::A).mesh.inverted >= 10);
        for dpr in [1.0f32, 1.5, 2.0, 3.0] {
            for css in [240u32, 300, 390, 520, 640] {
                let side = (css as f32 * dpr) as u32;
                let pm = pg.render_panel(Side::A, Canvas { w: side, h: side, dpr }, None).unwrap();
                let edge = (2.0 * dpr).ceil() as u32;
                for y in 0..side {
                    for x in side - edge..side {
                        let p = pm.pixel(x, y).unwrap();
                        assert!(
                            p.red() > 200 && p.green() > 200 && p.blue() > 200,
                            "dpr {dpr}, {css} px: ink at the right edge ({x}, {y})"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn the_old_solvers_path_shows_where_it_runs_along_a_star_edge() {
        // nodes 200 and 320 of the tangled plate: the old solver's first step runs along a
        // star edge (black), and its later iterates sit under the optimum
        let pg = Playground::new(Sample::PlateTriTangled.generate().unwrap()).unwrap();
        let (r, g, b) = smoothlab_render::PATH_RGB;
        for node in [200, 320] {
            let (pm, res) = pg.render_level_set(Side::A, node, Canvas { w: 400, h: 400, dpr: 1.0 }).unwrap();
            assert!(res.x.distance(res.x0) > 1e-3, "node {node} moved");
            let ink = pm.pixels().iter().filter(|p| (p.red(), p.green(), p.blue()) == (r, g, b)).count();
            assert!(ink > 40, "node {node}: {ink} pixels of the path");
        }
    }

    #[test]
    fn bad_sizes_are_errors_not_panics() {
        let pg = Playground::new(Sample::StarQuad.generate().unwrap()).unwrap();
        for (w, h) in [(0, 10), (10, 0), (MAX_SIDE + 1, 10)] {
            assert!(pg.render_panel(Side::A, Canvas { w, h, dpr: 1.0 }, None).is_err());
        }
        assert!(pg.render_panel(Side::A, Canvas { w: 50, h: 50, dpr: f32::NAN }, None).is_ok());
    }

    #[test]
    fn a_picture_drawn_during_a_pass_is_not_reused_after_it() {
        let mesh = smoothlab::generate::rand2d(20000, 140, 4).unwrap();
        let mut pg = Playground::new(mesh).unwrap();
        let c = Canvas { w: 200, h: 200, dpr: 1.0 };
        let t = std::cell::Cell::new(0.0);
        let clock = || {
            t.set(t.get() + 1.0);
            t.get()
        };
        pg.begin_pass();
        let mut p = pg.continue_pass(&clock, 2.0).unwrap();
        while p.stage != PassStage::Measure || p.side != Side::A {
            p = pg.continue_pass(&clock, 2.0).unwrap();
        }
        let during = pg.render_panel(Side::A, c, None).unwrap();
        while !pg.continue_pass(&clock, 50.0).unwrap().done {}
        let after = pg.render_panel(Side::A, c, None).unwrap();
        let panel = pg.panel(Side::A);
        let opts = pg.mesh_options(c, None);
        let mut fresh = pixmap(c.w, c.h).unwrap();
        let view = raster::view_of(&fresh, &panel.mesh, &opts);
        raster::render_fine(&mut fresh, &panel.mesh, &panel.buckets, &view, &opts);
        assert_eq!(after.data(), fresh.data());
        assert_ne!(during.data(), after.data(), "the colours changed with the statistics");
    }
}
