//! The papers' tables as the tour shows them, smoothed now: Freitag's Table 1 (rand2D,
//! the live table and Fig. 3's histograms) and Table 2 (rand3D, the tetrahedral table and
//! its cut pictures). [`super::pictures`] draws them among the other figures.

use smoothlab_render::VolumePicture;
use serde::Serialize;
use tiny_skia::{Color, Pixmap};

use super::pictures::first;
use super::repro;
use smoothlab::error::{Error, Result};
use smoothlab::generate::rand2d;
use crate::lab::views::{pixmap, Canvas};
use crate::lab::SMALL_ANGLE_DEG;
use smoothlab::mesh::Mesh;
use smoothlab::objective::{objective_with, ObjectiveKind, Penalty};
use smoothlab::quality::{mesh_stats, MeshStats};
use smoothlab_render::{
    draw_text, percentages, render_angle_histogram, series_color, text_width, Align, AngleHistogram, HistogramSeries,
    TextStyle, Theme, Valign,
};
use smoothlab::smooth::{Measure, Order, SmoothOptions, Smoother, Strategy};

// ---- Freitag Table 1 and Fig. 3 ------------------------------------------------------

/// One row of the live table: the reproduction's method name (its row in
/// `docs/reproduction.md` §1) and how that row smooths.
#[derive(Clone, Copy, Debug)]
pub struct FreitagMethod {
    pub method: &'static str,
    /// `None`: the mesh as generated.
    run: Option<(Strategy, ObjectiveKind, f64, Order)>,
}

/// The options of a row that smooths with `kind`: judged by the objective's measure
/// ([`Measure::for_run`] of a valid mesh: Freitag's smallest sine for her rows, for the smart
/// Laplacian and the thresholds too), as the page's sides and the reproduction take it.
fn row_options(strategy: Strategy, kind: ObjectiveKind, threshold: f64, order: Order) -> SmoothOptions {
    SmoothOptions::default()
        .with_strategy(strategy)
        .with_order(order)
        .with_threshold_deg(threshold)
        .with_smart_measure(Measure::for_run(kind, true))
}

/// The rows the table shows, as the reproduction runs them: Freitag's own rows (her
/// smallest sine), input order; then the new objective.
pub const FREITAG_METHODS: [FreitagMethod; 9] = {
    use ObjectiveKind::{Sine, SmoothShape};
    use Order::{Input, Priority};
    [
        FreitagMethod { method: "original", run: None },
        FreitagMethod { method: "laplace (plain)", run: Some((Strategy::Laplace, Sine, 30.0, Input)) },
        FreitagMethod { method: "smart (min sine)", run: Some((Strategy::Smart, Sine, 30.0, Input)) },
        FreitagMethod { method: "opt, `sine`", run: Some((Strategy::Opt, Sine, 30.0, Input)) },
        FreitagMethod { method: "C1 30°, `sine`", run: Some((Strategy::C1, Sine, 30.0, Input)) },
        FreitagMethod { method: "C2 30°, `sine`", run: Some((Strategy::C2, Sine, 30.0, Input)) },
        FreitagMethod { method: "C3 30°, `sine`", run: Some((Strategy::C3, Sine, 30.0, Input)) },
        FreitagMethod { method: "opt, `new`", run: Some((Strategy::Opt, SmoothShape, 30.0, Input)) },
        FreitagMethod { method: "rules, `new`, priority", run: Some((Strategy::Rules, SmoothShape, 30.0, Priority)) },
    ]
};

/// The mesh of Freitag's table as the page's `rand2d` sample (seed 1).
fn rand2d_seed1() -> Result<Mesh> {
    rand2d(500, 20, crate::lab::sample::SAMPLE_SEED)
}

/// One row of the table: measured now on seed 1, beside the reproduction's five-seed
/// mean and Freitag's published numbers (both from `docs/reproduction.md` §1).
#[derive(Clone, Debug, Serialize)]
pub struct FreitagRow {
    pub method: &'static str,
    pub min_angle_deg: f64,
    pub max_angle_deg: f64,
    pub laplacian_moves: u32,
    pub optimization_calls: u32,
    /// "mean [min–max]" over seeds 1–5, as the reproduction writes it.
    pub reproduction_min: String,
    pub reproduction_max: String,
    /// Freitag's "min / max (lap / opt)", or "—".
    pub paper: String,
    #[serde(skip)]
    stats: MeshStats,
}

/// Row `i` of [`FREITAG_METHODS`], measured now.
pub fn freitag_row(i: usize) -> Result<FreitagRow> {
    let m = FREITAG_METHODS.get(i).ok_or_else(|| Error::invalid(format!("the table has rows 0 to {}", FREITAG_METHODS.len() - 1)))?;
    let mut mesh = rand2d_seed1()?;
    let (mut lap, mut opt) = (0, 0);
    if let Some((strategy, kind, threshold, order)) = m.run {
        let mut s = Smoother::new(row_options(strategy, kind, threshold, order))?;
        let obj = objective_with(kind, Penalty::Barrier);
        for _ in 0..3 {
            let r = s.pass(&mut mesh, obj.as_ref(), &|| 0.0);
            lap += r.counts.laplacian_moves;
            opt += r.counts.optimization_calls;
        }
    }
    let stats = mesh_stats(&mesh);
    Ok(FreitagRow {
        method: m.method,
        min_angle_deg: stats.min_angle_deg,
        max_angle_deg: stats.max_angle_deg,
        laplacian_moves: lap,
        optimization_calls: opt,
        reproduction_min: repro(1, &[m.method], "min angle")?,
        reproduction_max: repro(1, &[m.method], "max angle")?,
        paper: repro(1, &[m.method], "paper: min / max (lap / opt)")?,
        stats,
    })
}

/// Where `a` lies against `b` and `c`: "above", "below" (both) or "between" them.
fn against(a: f64, b: f64, c: f64) -> &'static str {
    if a > b.max(c) {
        "above"
    } else if a < b.min(c) {
        "below"
    } else {
        "between"
    }
}

pub(super) fn freitag_t1_measured() -> Result<String> {
    let cell = |row: &str, column: &str| -> Result<String> { Ok(first(&repro(1, &[row], column)?).to_string()) };
    let mean = |row: &str| -> Result<f64> {
        let c = cell(row, "min angle")?;
        c.parse().map_err(|_| Error::invalid(format!("docs/reproduction.md §1, {row}: min angle '{c}' is not a number")))
    };
    let (opt, lap, smart) = ("opt, `sine`", "laplace (plain)", "smart (min sine)");
    // the live rows of this mesh (seed 1): FREITAG_METHODS 3, 1 and 2
    let (live_opt, live_lap, live_smart) = (freitag_row(3)?, freitag_row(1)?, freitag_row(2)?);
    Ok(format!(
        "Measured, the mean of five rand2D meshes (docs/reproduction.md §1): optimization of the smallest sine \
         reaches a min angle of {}° (Freitag {}°), {} the Laplacian's {}° and the smart Laplacian's {}°; C2 and C3 \
         at 30° {}° and {}° with {} and {} of its {} optimization calls. One mesh can go against the mean: on this \
         one (seed 1, the table's live rows) optimization reaches {:.2}°, {} the Laplacian's {:.2}° and the smart \
         Laplacian's {:.2}°; the new objective with Chen's rules averages {}°.",
        cell(opt, "min angle")?,
        repro(1, &[opt], "paper: min / max (lap / opt)")?.split(" / ").next().unwrap_or("—"),
        against(mean(opt)?, mean(lap)?, mean(smart)?),
        cell(lap, "min angle")?,
        cell(smart, "min angle")?,
        cell("C2 30°, `sine`", "min angle")?,
        cell("C3 30°, `sine`", "min angle")?,
        cell("C2 30°, `sine`", "opt. calls")?,
        cell("C3 30°, `sine`", "opt. calls")?,
        cell(opt, "opt. calls")?,
        live_opt.min_angle_deg,
        against(live_opt.min_angle_deg, live_lap.min_angle_deg, live_smart.min_angle_deg),
        live_lap.min_angle_deg,
        live_smart.min_angle_deg,
        cell("rules, `new`, priority", "min angle")?,
    ))
}

/// The methods of Fig. 3's picture (rows of [`FREITAG_METHODS`]).
const FIG3_ROWS: [usize; 5] = [0, 1, 3, 5, 8];

pub(super) fn freitag_histogram(c: Canvas, t: &Theme) -> Result<Pixmap> {
    let rows: Vec<FreitagRow> = FIG3_ROWS.iter().map(|&i| freitag_row(i)).collect::<Result<_>>()?;
    let labels: Vec<String> = rows.iter().map(|r| r.method.replace('`', "")).collect();
    let series: Vec<HistogramSeries<'_>> = rows
        .iter()
        .zip(&labels)
        .enumerate()
        .map(|(i, (r, l))| HistogramSeries {
            label: l,
            counts: &r.stats.angle_histogram_6deg,
            color: Some(if i == 0 { Color::from_rgba8(150, 150, 150, 255) } else { series_color(i) }),
        })
        .collect();
    let mut pm = pixmap(c.w, c.h)?;
    // the title whole at the theme's smallest label: the long one, or its last words
    let titles = ["rand2D (seed 1): corner angles after 3 passes, 6° bins, log scale", "angles after 3 passes, log scale"];
    let room = c.w as f32 - 120.0 * c.dpr; // the title is centred over the plot, right of its ticks
    let title = titles.into_iter().find(|w| text_width(w, t.text_px(13.0 * c.dpr, c.dpr)) <= room).unwrap_or(titles[1]);
    // a log scale: the claim is in the tails (the few angles near 0° and 180°), which a
    // linear scale draws flat beside the peak of good angles
    render_angle_histogram(&mut pm, &series, &AngleHistogram { title, dpr: c.dpr, log_y: true, theme: *t, ..AngleHistogram::default() })?;
    Ok(pm)
}

/// The share of corner angles under [`SMALL_ANGLE_DEG`], percent.
fn small_share(s: &MeshStats) -> f64 {
    let bins = (SMALL_ANGLE_DEG / 6.0) as usize;
    let p = percentages(&s.angle_histogram_6deg);
    p.iter().take(bins).sum()
}

pub(super) fn freitag_3_measured() -> Result<String> {
    let (orig, lap) = (freitag_row(0)?, freitag_row(1)?);
    let cellp = |row: &str| repro(1, &[row], "angles < 18° (%)").map(|c| first(&c).to_string());
    Ok(format!(
        "Measured: on this mesh {:.2}% of the angles are under 18° as generated and {:.2}% after the Laplacian; over five \
         meshes optimization of the smallest sine leaves {}%, of the new objective {}%, the new objective with Chen's \
         rules {}% (docs/reproduction.md §1).",
        small_share(&orig.stats),
        small_share(&lap.stats),
        cellp("opt, `sine`")?,
        cellp("opt, `new`")?,
        cellp("rules, `new`, priority")?,
    ))
}

// ---- the live tables: Freitag's Table 1 (rand2D) and Table 2 (rand3D) -------------------

/// One row of a live table, its cells written once for the page's table and the picture.
#[derive(Clone, Debug, Serialize)]
pub struct TableRow {
    /// The row's method, as the reproduction names it (its row in `docs/reproduction.md`).
    pub method: &'static str,
    /// The cells under [`table_columns`], the method first.
    pub cells: Vec<String>,
}

/// The column headings of figure `name`'s live table (none: the figure has no table).
pub fn table_columns(name: &str) -> &'static [&'static str] {
    match name {
        "freitag-t1" => &[
            "method",
            "min angle",
            "max angle",
            "Laplacian moves",
            "opt. calls",
            "min angle, seeds 1–5",
            "max angle, seeds 1–5",
            "Freitag: min / max (lap / opt)",
        ],
        "freitag-t2" => &[
            "method",
            "min dihedral",
            "max dihedral",
            "Laplacian moves",
            "opt. calls",
            "min dihedral, seeds 1–5",
            "max dihedral, seeds 1–5",
            "Freitag: min / max (lap / opt)",
        ],
        _ => &[],
    }
}

/// The caption of figure `name`'s live table: what is smoothed now and what is read.
pub fn table_caption(name: &str) -> &'static str {
    match name {
        "freitag-t1" => "rand2D (seed 1), 3 passes, smoothed now in your browser, beside docs/reproduction.md §1 (seeds 1–5) and Freitag's Table 1",
        "freitag-t2" => "rand3D (seed 1), 3 passes, smoothed now in your browser, beside docs/reproduction.md §10 (seeds 1–5) and Freitag's Table 2; of the combined schemes only the 30° rows are run here (§10 has 5°, 10° and 15° too)",
        _ => "",
    }
}

/// The number of rows of figure `name`'s live table (0: none).
pub fn table_rows(name: &str) -> usize {
    match name {
        "freitag-t1" => FREITAG_METHODS.len(),
        "freitag-t2" => FREITAG3D_METHODS.len(),
        _ => 0,
    }
}

/// Row `i` of figure `name`'s live table, smoothed now.
pub fn table_row(name: &str, i: usize) -> Result<TableRow> {
    let (method, min, max, lap, opt, rmin, rmax, paper) = match name {
        "freitag-t1" => {
            let r = freitag_row(i)?;
            (r.method, r.min_angle_deg, r.max_angle_deg, r.laplacian_moves, r.optimization_calls, r.reproduction_min, r.reproduction_max, r.paper)
        }
        "freitag-t2" => {
            let r = freitag3d_row(i)?;
            (r.method, r.min_dihedral_deg, r.max_dihedral_deg, r.laplacian_moves, r.optimization_calls, r.reproduction_min, r.reproduction_max, r.paper)
        }
        _ => return Err(Error::invalid(format!("figure {name} has no table"))),
    };
    Ok(TableRow {
        method,
        cells: vec![
            method.replace('`', ""),
            format!("{min:.2}°"),
            format!("{max:.1}°"),
            lap.to_string(),
            opt.to_string(),
            rmin,
            rmax,
            paper,
        ],
    })
}

/// The columns of a live table, those the claims quote first (method, min angle,
/// Freitag's numbers, the five-seed min, …): a narrow picture keeps the first that fit.
const COLUMN_PRIORITY: [usize; 8] = [0, 1, 7, 5, 2, 6, 3, 4];

/// The rows of figure `name`'s live table, those its claim is about first: a short
/// picture keeps the first that fit.
fn row_priority(name: &str) -> &'static [usize] {
    match name {
        // optimization, the Laplacian, as generated, C2, C3, Chen's rules, …
        "freitag-t1" => &[3, 1, 0, 5, 6, 8, 2, 4, 7],
        // optimization, the Laplacian, C2, C3, as generated, the smart Laplacian, …
        _ => &[3, 1, 5, 6, 0, 2, 8, 9, 4, 7],
    }
}

/// A live table drawn for its canvas (the picture of `smoothlab render --figure`, and of
/// an embed): each column as wide as its widest cell, the text as large as the width
/// allows (at most 13 px, at least the theme's smallest label). Where even the smallest
/// label does not fit, the columns and rows the claims quote least are dropped, so no
/// heading is cut off and no text is shrunk past reading.
pub(super) fn table_picture(name: &str, c: Canvas, theme: &Theme) -> Result<Pixmap> {
    let head = table_columns(name);
    let all: Vec<TableRow> = (0..table_rows(name)).map(|i| table_row(name, i)).collect::<Result<_>>()?;
    let mut pm = pixmap(c.w, c.h)?;
    pm.fill(theme.paper);
    let s = c.dpr;
    let (w, h) = (c.w as f32 / s, c.h as f32 / s);
    let gap = 1.6; // between columns, in ems
    let floor = theme.min_label_px;
    // the columns: the most of COLUMN_PRIORITY whose layout fits the width at the floor
    let width10 = |k: usize| all.iter().map(|r| text_width(&r.cells[k], 10.0)).fold(text_width(head[k], 10.0), f32::max);
    let total10 = |cols: &[usize]| cols.iter().map(|&k| width10(k)).sum::<f32>() + gap * 10.0 * (cols.len() - 1) as f32;
    let mut cols: Vec<usize> = (0..head.len()).collect();
    for n in (2..=head.len()).rev() {
        let mut pick: Vec<usize> = COLUMN_PRIORITY.iter().copied().filter(|&k| k < head.len()).take(n).collect();
        pick.sort_unstable();
        cols = pick;
        if 10.0 * (w - 16.0) / total10(&cols) >= floor {
            break;
        }
    }
    // the rows: as many of the claim's as fit the height at the floor
    let fit_rows = (((h - 8.0) / (floor * 1.25).max(1.0)).floor() as usize).saturating_sub(1).max(1);
    let mut keep: Vec<usize> = row_priority(name).iter().copied().filter(|&i| i < all.len()).take(fit_rows.min(all.len())).collect();
    keep.sort_unstable();
    let rows: Vec<&TableRow> = keep.iter().map(|&i| &all[i]).collect();
    let line = ((h - 8.0) / (rows.len() + 1) as f32).min(30.0);
    let size = (10.0 * (w - 16.0) / total10(&cols)).min(line * 0.5).min(13.0);
    let size = theme.text_px(size, 1.0);
    let mut x = 8.0;
    let mut xs = Vec::new();
    for &k in &cols {
        xs.push(x);
        x += width10(k) * size / 10.0 + gap * size;
    }
    let text = |pm: &mut Pixmap, t: &str, col: usize, row: usize| {
        let style = TextStyle::new(size * s).with_color(theme.ink).with_align(Align::Left, Valign::Middle);
        draw_text(pm, t, xs[col] * s, (4.0 + line * (row as f32 + 0.5)) * s, style);
    };
    for (j, &k) in cols.iter().enumerate() {
        text(&mut pm, head[k], j, 0);
    }
    for (i, r) in rows.iter().enumerate() {
        for (j, &k) in cols.iter().enumerate() {
            text(&mut pm, &r.cells[k], j, i + 1);
        }
    }
    Ok(pm)
}

/// One row of Freitag's Table 2 as the reproduction runs it (`docs/reproduction.md` §10):
/// her measure (the smallest dihedral sine) for the smart Laplacian and the thresholds,
/// input order; then the new objective and Knupp's condition number.
#[derive(Clone, Copy, Debug)]
pub struct Freitag3dMethod {
    pub method: &'static str,
    /// `None`: the mesh as generated.
    run: Option<(Strategy, ObjectiveKind, f64, Order)>,
}

/// The rows the live Table 2 smooths: every row of §10 but the combined schemes at 5°,
/// 10° and 15° (in §10 alone), which keeps the browser's part to about ten 3-pass
/// runs on 1086 nodes.
pub const FREITAG3D_METHODS: [Freitag3dMethod; 10] = {
    use ObjectiveKind::{Condition, Sine, SmoothShape};
    use Order::{Input, Priority};
    [
        Freitag3dMethod { method: "original", run: None },
        Freitag3dMethod { method: "laplace (plain)", run: Some((Strategy::Laplace, Sine, 30.0, Input)) },
        Freitag3dMethod { method: "smart (min sine)", run: Some((Strategy::Smart, Sine, 30.0, Input)) },
        Freitag3dMethod { method: "opt, `sine`", run: Some((Strategy::Opt, Sine, 30.0, Input)) },
        Freitag3dMethod { method: "C1 30°, `sine`", run: Some((Strategy::C1, Sine, 30.0, Input)) },
        Freitag3dMethod { method: "C2 30°, `sine`", run: Some((Strategy::C2, Sine, 30.0, Input)) },
        Freitag3dMethod { method: "C3 30°, `sine`", run: Some((Strategy::C3, Sine, 30.0, Input)) },
        Freitag3dMethod { method: "opt, `new`", run: Some((Strategy::Opt, SmoothShape, 30.0, Input)) },
        Freitag3dMethod { method: "rules, `new`, priority", run: Some((Strategy::Rules, SmoothShape, 30.0, Priority)) },
        Freitag3dMethod { method: "opt, `condition`", run: Some((Strategy::Opt, Condition, 30.0, Input)) },
    ]
};

/// rand3D as the page's sample (seed 1), made once: its Delaunay tetrahedralization and
/// face swaps cost more than a row's smoothing.
fn rand3d_seed1() -> Result<smoothlab::volume::VolumeMesh> {
    static MESH: std::sync::OnceLock<smoothlab::volume::VolumeMesh> = std::sync::OnceLock::new();
    if let Some(m) = MESH.get() {
        return Ok(m.clone());
    }
    let m = smoothlab::generate::rand3d(smoothlab::generate::RAND3D_POINTS, crate::lab::sample::SAMPLE_SEED)?;
    Ok(MESH.get_or_init(|| m).clone())
}

/// One row of the live Table 2: measured now on seed 1, beside the reproduction's five-seed
/// mean and Freitag's published numbers (both from `docs/reproduction.md` §10).
#[derive(Clone, Debug, Serialize)]
pub struct Freitag3dRow {
    pub method: &'static str,
    pub min_dihedral_deg: f64,
    pub max_dihedral_deg: f64,
    pub inverted: usize,
    pub laplacian_moves: u32,
    pub optimization_calls: u32,
    pub reproduction_min: String,
    pub reproduction_max: String,
    pub paper: String,
}

/// Row `i` of [`FREITAG3D_METHODS`], smoothed now (3 passes, as §10).
pub fn freitag3d_row(i: usize) -> Result<Freitag3dRow> {
    Ok(freitag3d_run(i)?.0)
}

/// Row `i` of [`FREITAG3D_METHODS`] and the mesh it measured: one run for the table's
/// row and the picture's panel of it.
fn freitag3d_run(i: usize) -> Result<(Freitag3dRow, smoothlab::volume::VolumeMesh)> {
    let m = FREITAG3D_METHODS
        .get(i)
        .ok_or_else(|| Error::invalid(format!("the table has rows 0 to {}", FREITAG3D_METHODS.len() - 1)))?;
    let mut mesh = rand3d_seed1()?;
    let (mut lap, mut opt) = (0, 0);
    if let Some((strategy, kind, threshold, order)) = m.run {
        let obj = smoothlab::objective::solid_objective(kind)?;
        let o = row_options(strategy, kind, threshold, order);
        for r in smoothlab::volume::smooth_volume(&mut mesh, obj.as_ref(), o, 3, &|| 0.0)? {
            lap += r.counts.laplacian_moves;
            opt += r.counts.optimization_calls;
        }
    }
    let stats = smoothlab::volume::volume_stats(&mesh);
    let row = Freitag3dRow {
        method: m.method,
        min_dihedral_deg: stats.min_angle_deg,
        max_dihedral_deg: stats.max_angle_deg,
        inverted: stats.inverted,
        laplacian_moves: lap,
        optimization_calls: opt,
        reproduction_min: repro(10, &[m.method], "min dihedral")?,
        reproduction_max: repro(10, &[m.method], "max dihedral")?,
        paper: repro(10, &[m.method], "paper: min / max (lap / opt)")?,
    };
    Ok((row, mesh))
}

/// The rows of [`FREITAG3D_METHODS`] the page's meshes show with the figure's settings:
/// A optimization of the smallest dihedral sine, B of the new objective.
const T2_PANEL_ROWS: [(usize, &str); 2] = [(3, "A: opt, sine, 3 passes"), (7, "B: opt, new, 3 passes")];

/// A volume mesh cut by `cut`, drawn by the 3D view with its title.
pub(super) fn cut_panel(mesh: &smoothlab::volume::VolumeMesh, cut: smoothlab_render::Cut, title: &str, c: Canvas, t: &Theme) -> Result<Pixmap> {
    let mut pm = pixmap(c.w, c.h)?;
    let view = smoothlab_render::SurfaceView { dpr: c.dpr, title: Some(title.to_string()), theme: *t, ..smoothlab_render::SurfaceView::default() };
    mesh.render_cut(&mut pm, cut, &view);
    Ok(pm)
}

/// The height, CSS pixels, under which Table 2's picture drops its cut panels.
const CUT_PANELS_MIN_CSS_H: f32 = 560.0;

/// Table 2's picture: rand3D cut half way up z as generated and after 3 passes of the two
/// methods the page's meshes show (A: optimization of the smallest dihedral sine, B: of the
/// new objective), above the live table.
pub(super) fn freitag_t2(c: Canvas, t: &Theme) -> Result<Pixmap> {
    // the cut panels need room for their titles and a mesh: a short picture is the table
    if (c.h as f32) < CUT_PANELS_MIN_CSS_H * c.dpr.max(0.1) {
        return table_picture("freitag-t2", c, t);
    }
    let m0 = rand3d_seed1()?;
    let top = Canvas { w: c.w / 3, h: (c.h as f32 * 0.52) as u32, dpr: c.dpr };
    let mut parts = vec![cut_panel(&m0, smoothlab_render::Cut::default(), "rand3D as generated, cut at z = 0.5", top, t)?];
    // the table's rows of the two methods: the panels draw the meshes those rows measured
    for (row, title) in T2_PANEL_ROWS {
        let (_, m) = freitag3d_run(row)?;
        parts.push(cut_panel(&m, smoothlab_render::Cut::default(), title, top, t)?);
    }
    let table = table_picture("freitag-t2", Canvas { w: c.w, h: c.h.saturating_sub(top.h).max(1), dpr: c.dpr }, t)?;
    let mut out = pixmap(c.w, c.h)?;
    out.fill(t.paper);
    for (i, p) in parts.iter().enumerate() {
        out.draw_pixmap((i as u32 * top.w) as i32, 0, p.as_ref(), &tiny_skia::PixmapPaint::default(), tiny_skia::Transform::identity(), None);
    }
    out.draw_pixmap(0, top.h as i32, table.as_ref(), &tiny_skia::PixmapPaint::default(), tiny_skia::Transform::identity(), None);
    Ok(out)
}

/// The rows of the reproduction's table in section `number` that has the column `column`.
fn section_rows(number: u32, column: &str) -> Result<usize> {
    let doc = super::measured::reproduction()?;
    doc.section(number)
        .and_then(|s| s.tables.iter().find(|t| t.header.iter().any(|h| h == column)))
        .map(|t| t.rows.len())
        .ok_or_else(|| Error::invalid(format!("docs/reproduction.md §{number} has no table with a '{column}' column")))
}

pub(super) fn freitag_t2_measured() -> Result<String> {
    let cellm = |row: &str| -> Result<String> { Ok(first(&repro(10, &[row], "min dihedral")?).to_string()) };
    let paper_min = |row: &str| -> Result<String> {
        Ok(repro(10, &[row], "paper: min / max (lap / opt)")?.split(" / ").next().unwrap_or("—").to_string())
    };
    Ok(format!(
        "Measured over five rand3D meshes (docs/reproduction.md §10): optimization of the smallest dihedral sine \
         reaches {}° (Freitag {}°), C2 and C3 at 30° {}° and {}° (hers {}° and {}°), the new objective with Chen's \
         rules {}° and Knupp's condition number {}°; optimization costs {} times the smart Laplacian (Freitag: about \
         ten). The table runs {} of §10's {} rows here (3 passes on seed 1): of the combined schemes only those at \
         30°, the others in §10 alone.",
        cellm("opt, `sine`")?,
        paper_min("opt, `sine`")?,
        cellm("C2 30°, `sine`")?,
        cellm("C3 30°, `sine`")?,
        paper_min("C2 30°, `sine`")?,
        paper_min("C3 30°, `sine`")?,
        cellm("rules, `new`, priority")?,
        cellm("opt, `condition`")?,
        repro(10, &["opt, `sine`"], "ratio")?,
        FREITAG3D_METHODS.len(),
        section_rows(10, "min dihedral")?,
    ))
}


#[cfg(test)]
mod tests {
    use super::*;
    use crate::lab::Side;

    /// One number for one run (issue 59): the live panels of Freitag's tables, run by the
    /// page with the figure's settings, are the table's rows of the same methods.
    #[test]
    fn the_live_panels_are_the_tables_rows_of_their_methods() {
        let (_, t1) = super::super::find("freitag-t1").unwrap();
        let (mut pg, st) = t1.playground().unwrap();
        for _ in 0..st.passes {
            pg.step(&|| 0.0);
        }
        for (side, row) in [(Side::A, 3), (Side::B, 7)] {
            let (live, r) = (mesh_stats(&pg.panel(side).mesh), freitag_row(row).unwrap());
            assert_eq!((live.min_angle_deg, live.max_angle_deg), (r.min_angle_deg, r.max_angle_deg), "freitag-t1 {side:?}: {}", r.method);
        }
        let (_, t2) = super::super::find("freitag-t2").unwrap();
        let st = t2.state().unwrap();
        let smoothlab::model::Model::Volume(v) = super::super::gallery_sample(t2.name).unwrap().model().unwrap() else {
            panic!("rand3D is a volume mesh")
        };
        let mut lab = crate::lab::Lab3d::new(v).unwrap();
        lab.set_settings(st.settings).unwrap();
        for _ in 0..st.passes {
            lab.step(&|| 0.0);
        }
        for (side, (row, title)) in Side::BOTH.into_iter().zip(T2_PANEL_ROWS) {
            let (live, r) = (smoothlab::volume::volume_stats(lab.mesh(side)), freitag3d_row(row).unwrap());
            assert_eq!((live.min_angle_deg, live.max_angle_deg), (r.min_dihedral_deg, r.max_dihedral_deg), "freitag-t2 {side:?}: {}", r.method);
            assert!(title.starts_with(side.letter()) && title.contains(&r.method.replace('`', "")), "{title}: {}", r.method);
        }
    }
}
