//! The tour's pictures (`smoothlab render --figure NAME`, the page's figure panel,
//! `docs/figures/`) and the numbers its captions compute. Each picture is drawn from
//! the figure's own state ([`Figure::playground`]) or, for the 1-D views the playground
//! has no panel for (Chen's Figs. 2 and 6), from the same metrics the objectives use.

use std::f64::consts::PI;

use glam::DVec2;
use serde::Serialize;
use tiny_skia::{Color, Pixmap};

use super::{find, repro, Figure};
use crate::error::{Error, Result};
use crate::generate::rand2d;
use crate::lab::views::{pixmap, Canvas};
use crate::lab::{Side, SMALL_ANGLE_DEG};
use crate::mesh::{ElementKind, Mesh, MeshBuilder};
use crate::objective::{adjusted_angle, objective_with, AnglePenalty, Objective, ObjectiveKind, Penalty, Star, BARRIER_WEIGHT};
use crate::objective::regularised_determinant;
use crate::optimize::SolveResult;
use crate::quality::{lo_alpha, mesh_stats, signed_angle, MeshStats};
use crate::render::{
    percentages, render_angle_histogram, render_chart, render_mesh, render_sketch, render_titled, series_color, AngleHistogram,
    Chart, Frame, HistogramSeries, MeshView, Series, Sketch, SketchLine, Theme,
};
use crate::render::layout::{record, Region};
use crate::render::{draw_text, title_band, Align, TextStyle, Valign};
use crate::smooth::{Measure, Order, SmoothOptions, Smoother, Strategy};

/// The size a figure's picture is drawn at by default, CSS pixels.
pub fn default_size(name: &str) -> (u32, u32) {
    match name {
        "chen-13" => (1400, 760),
        "chen-9" | "chen-10" | "chen-11" | "chen-20" => (1100, 560),
        "freitag-t1" => (1100, 360),
        "freitag-3" => (1000, 520),
        _ => (1400, 460),
    }
}

/// The figure `name`'s picture on a canvas of `c.w × c.h` device pixels, in `theme`.
pub fn render(name: &str, c: Canvas, theme: &Theme) -> Result<Pixmap> {
    let t = theme;
    let (_, fig) = find(name)?;
    pixmap(c.w, c.h)?; // the size is checked before any work
    let title = format!("{} — {}", fig.source, fig.name);
    let parts = match fig.name {
        "chen-2" => chen_2(part(c, 3, 1, t), t)?,
        "chen-6" => chen_6(part(c, 3, 1, t), t)?,
        "chen-9" => super::solves::chen_9(part(c, 2, 1, t), t)?,
        "chen-10" => super::solves::chen_10(part(c, 2, 1, t), t)?,
        "chen-20" => level_sets(fig, part(c, 2, 1, t), t)?,
        "chen-11" => super::solves::chen_11(part(c, 2, 1, t), t)?,
        "chen-13" => chen_13(part(c, 4, 2, t), t)?,
        "chen-16" => chen_16(part(c, CHEN_16_PANELS, 1, t), t)?,
        "freitag-t1" => vec![freitag_table(part(c, 1, 1, t), t)?],
        "freitag-3" => vec![freitag_histogram(part(c, 1, 1, t), t)?],
        "knupp-1" => knupp_1(part(c, 4, 1, t), t)?,
        _ => return Err(Error::invalid(format!("figure {name} has no picture"))),
    };
    let cols = match fig.name {
        "chen-13" => 4,
        _ => parts.len(),
    };
    render_titled(&parts, cols, &title, c.dpr, t).ok_or_else(|| Error::invalid("cannot allocate the figure"))
}

/// The figure `name`'s picture ([`render`]) and where its plots, legends and chart marks
/// lie in it, device pixels, as they were drawn ([`crate::render::layout`]): for the tests
/// that keep legends off the data and find the marks a text promises.
pub fn render_with_layout(name: &str, c: Canvas, theme: &Theme) -> Result<(Pixmap, Vec<Region>)> {
    let (pm, notes) = record(|| render(name, c, theme));
    let pm = pm?;
    let regions = notes.of(&pm);
    Ok((pm, regions))
}

/// The canvas of one of `cols × rows` panels under the title band.
fn part(c: Canvas, cols: u32, rows: u32, t: &Theme) -> Canvas {
    let head = (title_band(t) * c.dpr.max(0.1)).round() as u32;
    Canvas { w: (c.w / cols).max(1), h: (c.h.saturating_sub(head) / rows).max(1), dpr: c.dpr }
}

/// A mesh on its own panel with a title and a line of statistics under it.
fn mesh_panel(mesh: &Mesh, title: &str, c: Canvas, t: &Theme) -> Result<Pixmap> {
    let mut pm = pixmap(c.w, c.h)?;
    let s = c.dpr;
    let full = Frame::of_pixmap(&pm, s);
    let st = mesh_stats(mesh);
    let line = format!("inverted {}, angles {:.1}°–{:.1}°", st.inverted, st.min_angle_deg, st.max_angle_deg);
    // the title (13 px) and the line (11 px) above the mesh, grown with the theme's labels
    let (g13, g11) = (t.grow(13.0), t.grow(11.0));
    let head = 22.0 * g13 + 18.0 * g11;
    render_mesh(&mut pm, mesh, &MeshView { theme: *t, ..MeshView::default().with_dpr(s).with_frame(full.inset(0.0, head, 0.0, 0.0)) });
    let style = |size: f32| TextStyle::new(t.text_px(size * s, s)).with_color(t.ink).with_align(Align::Centre, Valign::Top);
    draw_text(&mut pm, title, full.w / 2.0 * s, 4.0 * s, style(13.0));
    draw_text(&mut pm, &line, full.w / 2.0 * s, (4.0 + 18.0 * g13) * s, style(11.0));
    Ok(pm)
}

// ---- Chen Fig. 2: α along two lines --------------------------------------------------

/// The fixed corners of Figs. 2's triangle: C above AB (y > 1) is valid, below inverted.
const A2: DVec2 = DVec2::new(-0.5, 1.0);
const B2: DVec2 = DVec2::new(0.5, 1.0);
/// The lines C moves along (Fig. 2b): y = 2 (valid) and y = 0 (inverted).
const LINES2: [f64; 2] = [2.0, 0.0];
const X2: (f64, f64) = (-3.0, 3.0);
const SAMPLES: usize = 301;

fn xs(lo: f64, hi: f64) -> impl Iterator<Item = f64> {
    (0..SAMPLES).map(move |i| lo + (hi - lo) * i as f64 / (SAMPLES - 1) as f64)
}

/// α of triangle A B C.
fn alpha2(c: DVec2) -> f64 {
    lo_alpha(A2, B2, c)
}

/// The star of the one triangle A B C with C free, gathered with C at `at` (the new
/// objective's regularisation is taken from where the node is).
fn triangle_star(at: DVec2) -> Result<Star> {
    // built with C above AB, where ABC is counter-clockwise (the builder would turn an
    // inverted mesh round), then C is moved to `at`
    let mut b = MeshBuilder::with_capacity(3, 1);
    for p in [A2, B2, DVec2::new(0.0, 2.0)] {
        b.add_node([p.x, p.y, 0.0], 0);
    }
    b.add_element(ElementKind::Tri3, &[0, 1, 2], 0);
    let mesh = b.build()?;
    let mut star = Star::new();
    star.gather(&mesh, 2);
    star.x0 = at;
    for e in &mut star.elems {
        e.move_free_node(at);
    }
    Ok(star)
}

fn chen_2(c: Canvas, t: &Theme) -> Result<Vec<Pixmap>> {
    let colors = [series_color(2), series_color(1)];
    let mut sketch = pixmap(c.w, c.h)?;
    let frame = Frame::of_pixmap(&sketch, c.dpr);
    let lines: Vec<SketchLine<'_>> = LINES2
        .iter()
        .zip(colors)
        .zip(["y = 2 (valid)", "y = 0 (inverted)"])
        .map(|((&y, color), label)| SketchLine { from: DVec2::new(X2.0, y), to: DVec2::new(X2.1, y), color, label })
        .collect();
    render_sketch(
        &mut sketch,
        &Sketch { title: "(a) triangle ABC, C moving", points: &[(A2, "A"), (B2, "B")], lines: &lines, dashed: &[] },
        frame,
        c.dpr,
        t,
    );
    let alpha: Vec<Vec<DVec2>> = LINES2.iter().map(|&y| xs(X2.0, X2.1).map(|x| DVec2::new(x, alpha2(DVec2::new(x, y)))).collect()).collect();
    let new = objective_with(ObjectiveKind::New, Penalty::Barrier);
    let mut f = Vec::new();
    for &y in &LINES2 {
        let star = triangle_star(DVec2::new(-0.5, y))?;
        f.push(xs(X2.0, X2.1).map(|x| DVec2::new(x, new.value(&star, DVec2::new(x, y)))).collect::<Vec<_>>());
    }
    let labels = ["y = 2", "y = 0"];
    let chart = |pts: &[Vec<DVec2>], title: &str, y_label: &str, log_y: bool| -> Result<Pixmap> {
        let mut pm = pixmap(c.w, c.h)?;
        let series: Vec<Series<'_>> =
            pts.iter().zip(labels).zip(colors).map(|((p, l), col)| Series::new(l, p).with_color(col)).collect();
        render_chart(&mut pm, &series, &Chart { title, x_label: "x of C", y_label, log_y, integer_x: false, dpr: c.dpr, theme: *t, ..Chart::default() });
        Ok(pm)
    };
    Ok(vec![
        sketch,
        chart(&alpha, "(b) Lo's α along the lines", "α", false)?,
        chart(&f, "the new objective along them (smaller is better)", "objective", true)?,
    ])
}

/// The numbers of Fig. 2's claim, computed.
pub(super) fn chen_2_measured() -> Result<String> {
    let p = DVec2::new(-0.5, 0.0);
    let (a0, a1, a2) = (alpha2(DVec2::new(0.0, 0.0)), alpha2(p), alpha2(DVec2::new(-3.0, 0.0)));
    let new = objective_with(ObjectiveKind::New, Penalty::Barrier);
    let star = triangle_star(p)?;
    let (_, g) = new.value_and_gradient(&star, p);
    let d = -g.normalize_or_zero();
    Ok(format!(
        "Measured: on y = 0, α is {a0:.3} below the middle of AB, {a1:.3} at x = −0.5 and {a2:.3} at x = −3, so ascending α \
         from x = −0.5 moves C away from AB, as the paper says; the new objective's descent direction there is \
         ({:.2}, {:.2}), towards AB.",
        d.x, d.y
    ))
}

// ---- Chen Figs. 6–7: the angle's jump, the adjusted angle, the penalties -------------

/// Fig. 5/6's fixed corners: the angle at A jumps on the ray x = 0, y > 1.
const A6: DVec2 = DVec2::new(0.0, 1.0);
const B6: DVec2 = DVec2::new(0.0, 0.0);
const Y6: f64 = 2.0;
/// δ of the barrier's curve for a tangled star (the valid star's δ is 0).
const DELTA6: f64 = 0.1;

fn theta_a(c: DVec2) -> f64 {
    signed_angle(B6 - A6, c - A6)
}

/// The barrier's η² term `k1·η²` of a corner with unit edges at angle `theta`, with δ.
fn barrier_of_angle(theta: f64, delta: f64) -> f64 {
    let n = theta.sin();
    let d = 4.0 - 2.0 * theta.cos();
    let h = if delta == 0.0 { n.max(0.0) } else { regularised_determinant(n, delta).0 };
    if h <= 0.0 {
        return f64::INFINITY;
    }
    let eta = d / (2.0 * 3f64.sqrt() * h);
    BARRIER_WEIGHT * eta * eta
}

fn chen_6(c: Canvas, t: &Theme) -> Result<Vec<Pixmap>> {
    let mut sketch = pixmap(c.w, c.h)?;
    let frame = Frame::of_pixmap(&sketch, c.dpr);
    let line = [SketchLine { from: DVec2::new(-2.0, Y6), to: DVec2::new(2.0, Y6), color: series_color(2), label: "C on y = 2" }];
    render_sketch(
        &mut sketch,
        &Sketch {
            title: "the angle θ at A; its jump on the dashed ray",
            points: &[(A6, "A"), (B6, "B")],
            lines: &line,
            dashed: &[(A6, DVec2::new(0.0, 2.6))],
        },
        frame,
        c.dpr,
        t,
    );
    let deg = 180.0 / PI;
    let mut theta = Vec::new();
    let mut omega = Vec::new();
    let mut last: Option<f64> = None;
    for x in xs(-2.0, 2.0) {
        let t = theta_a(DVec2::new(x, Y6));
        if let Some(l) = last {
            if (t - l).abs() > PI {
                theta.push(DVec2::NAN); // the jump: no line across it
            }
        }
        last = Some(t);
        theta.push(DVec2::new(x, t * deg));
        omega.push(DVec2::new(x, adjusted_angle(t).0 * deg));
    }
    let mut a = pixmap(c.w, c.h)?;
    render_chart(
        &mut a,
        &[Series::new("θ at A (signed)", &theta).with_color(series_color(1)), Series::new("adjusted ω = wθ", &omega).with_color(series_color(2))],
        &Chart { title: "θ jumps ±180° at x = 0; ω does not", x_label: "x of C on y = 2", y_label: "degrees", integer_x: false, dpr: c.dpr, theme: *t, ..Chart::default() },
    );
    let angles: Vec<f64> = xs(-179.0, 179.0).collect();
    let design = AnglePenalty::default();
    let curve = |f: &dyn Fn(f64) -> f64| -> Vec<DVec2> { angles.iter().map(|&t| DVec2::new(t, f(t / deg))).collect() };
    let angle_p = curve(&|t| design.angle_penalty(t, 1.0));
    let barrier0 = curve(&|t| barrier_of_angle(t, 0.0));
    let barrier_d = curve(&|t| barrier_of_angle(t, DELTA6));
    let mut b = pixmap(c.w, c.h)?;
    render_chart(
        &mut b,
        &[
            Series::new("angle design", &angle_p).with_color(series_color(1)),
            Series::new("barrier, δ = 0 (valid star)", &barrier0).with_color(series_color(2)),
            Series::new("barrier, δ = 0.1 (tangled)", &barrier_d).with_color(series_color(2)).with_dash(true),
        ],
        &Chart { title: "eq. (8), our two designs", x_label: "angle, degrees", y_label: "penalty", log_y: true, integer_x: false, dpr: c.dpr, theme: *t, ..Chart::default() },
    );
    Ok(vec![sketch, a, b])
}

pub(super) fn chen_6_measured() -> Result<String> {
    let (l, r) = (theta_a(DVec2::new(-1e-3, Y6)), theta_a(DVec2::new(1e-3, Y6)));
    let (wl, wr) = (adjusted_angle(l).0, adjusted_angle(r).0);
    let design = AnglePenalty::default();
    let at = |deg: f64| design.angle_penalty(deg.to_radians(), 1.0);
    let ratio = at(0.0) / at(60.0);
    Ok(format!(
        "Measured: a thousandth of |AB| either side of the ray θ is {:.1}° and {:.1}°, ω {:.3}° and {:.3}°; the angle design's \
         penalty is {ratio:.0} times its equilateral value at 0°, and the barrier's is infinite there on a valid star. \
         With Chen's rules on rand2D the barrier reaches a min angle of {}° and the angle design {}° (docs/reproduction.md §1).",
        l.to_degrees(),
        r.to_degrees(),
        wl.to_degrees(),
        wr.to_degrees(),
        first(&repro(1, &["rules, `new`, priority"], "min angle")?),
        first(&repro(1, &["rules, `new`, priority (angle design)"], "min angle")?),
    ))
}

/// The mean of a "mean [min–max]" cell.
fn first(cell: &str) -> &str {
    cell.split_whitespace().next().unwrap_or(cell)
}

// ---- level sets: Figs. 9, 10, 20 ------------------------------------------------------

fn level_sets(fig: &Figure, c: Canvas, t: &Theme) -> Result<Vec<Pixmap>> {
    let (mut pg, st) = fig.playground()?;
    pg.set_theme(*t);
    let node = st.node.ok_or_else(|| Error::invalid(format!("figure {} names no node", fig.name)))? as usize;
    let (old, _) = pg.render_level_set(Side::Old, node, c)?;
    let (new, _) = pg.render_level_set(Side::New, node, c)?;
    Ok(vec![old, new])
}

/// Both sides' solves at the figure's node.
fn solves(name: &str) -> Result<(SolveResult, SolveResult)> {
    let (_, fig) = find(name)?;
    let (pg, st) = fig.playground()?;
    let node = st.node.ok_or_else(|| Error::invalid(format!("figure {name} names no node")))? as usize;
    Ok((pg.solve_node(Side::Old, node)?, pg.solve_node(Side::New, node)?))
}

pub(super) fn chen_20_measured() -> Result<String> {
    let (old, new) = solves("chen-20")?;
    Ok(format!(
        "Measured at this node (20 iterations at most): max-min β from {:.3} to {:.3} in {} iterations ({}); the new \
         objective from {:.3} to {:.3} in {} ({}).",
        old.value0,
        old.value,
        old.iterations,
        crate::lab::views::stop_words(old.stop),
        new.value0,
        new.value,
        new.iterations,
        crate::lab::views::stop_words(new.stop),
    ))
}

// ---- Figs. 13–15: the tangled plate, pass by pass --------------------------------------

/// The plate of Figs. 13–15 smoothed by `new` + `rules` in `order`: the mesh as loaded and
/// after each of 3 passes.
fn plate_passes(order: Order) -> Result<Vec<Mesh>> {
    let (_, fig) = find("chen-13")?;
    let (pg, st) = fig.playground()?;
    let mut m = pg.panel(Side::New).mesh.clone();
    let mut s = Smoother::new(st.settings.smooth_options()?.with_order(order))?;
    let obj = objective_with(ObjectiveKind::New, Penalty::Barrier);
    let mut out = vec![m.clone()];
    for _ in 0..3 {
        s.pass(&mut m, obj.as_ref(), &|| 0.0);
        out.push(m.clone());
    }
    Ok(out)
}

fn chen_13(c: Canvas, t: &Theme) -> Result<Vec<Pixmap>> {
    let mut parts = Vec::new();
    for (order, name) in [(Order::Priority, "priority order"), (Order::Input, "input order")] {
        for (i, m) in plate_passes(order)?.iter().enumerate() {
            let title = if i == 0 { format!("as loaded ({name})") } else { format!("pass {i}, new + rules, {name}") };
            parts.push(mesh_panel(m, &title, c, t)?);
        }
    }
    Ok(parts)
}

pub(super) fn chen_13_measured() -> Result<String> {
    let inv = |order| -> Result<String> {
        Ok(plate_passes(order)?.iter().map(|m| mesh_stats(m).inverted.to_string()).collect::<Vec<_>>().join(" → "))
    };
    let row = ["tri", "1.5"];
    Ok(format!(
        "Measured here, inverted elements pass by pass: {} in priority order, {} in input order. Over five seeds of the \
         reproduction's coarser plate at this amount ({} inverted at the start) passes to untangle are {} in priority \
         and {} in input order; with the first, angle design of the penalty {} (docs/reproduction.md §2).",
        inv(Order::Priority)?,
        inv(Order::Input)?,
        repro(2, &row, "inverted at start")?,
        repro(2, &row, "barrier: priority")?,
        repro(2, &row, "barrier: input order")?,
        repro(2, &row, "angle design: priority")?,
    ))
}

// ---- Figs. 16–17: a node by a curved boundary ------------------------------------------

/// The panels of Figs. 16–17's picture: as loaded and four runs.
const CHEN_16_PANELS: u32 = 5;
/// The titles of Figs. 16–17's optimization panels, which its text compares.
const CHEN_16_NEW: &str = "optimization, new objective";
const CHEN_16_OLD: &str = "optimization, old (max-min α)";

/// The curved-boundary star as loaded and after one pass of: the plain Laplacian, the
/// smart (constrained) Laplacian, optimization of the new objective, and of the old
/// max-min α — the compare view's two meshes (Chen et al. 2003, Figs. 16–17).
fn curved_runs() -> Result<Vec<(String, Mesh)>> {
    let (_, fig) = find("chen-16")?;
    let (pg, st) = fig.playground()?;
    let m0 = pg.panel(Side::New).mesh.clone();
    let new = objective_with(ObjectiveKind::New, Penalty::Barrier);
    let old = objective_with(ObjectiveKind::Old, Penalty::Barrier);
    let mut out = vec![("as loaded".to_string(), m0.clone())];
    for (strategy, title, obj) in [
        (Strategy::Laplace, "Laplacian", &new),
        (Strategy::Smart, "constrained (smart) Laplacian", &new),
        (Strategy::Opt, CHEN_16_NEW, &new),
        (Strategy::Opt, CHEN_16_OLD, &old),
    ] {
        let mut m = m0.clone();
        let mut s = Smoother::new(st.settings.smooth_options()?.with_strategy(strategy))?;
        s.pass(&mut m, obj.as_ref(), &|| 0.0);
        out.push((title.to_string(), m));
    }
    Ok(out)
}

/// Where one of two meshes is better on the rows the tables judge by (min angle, min
/// quality, worst κ): the rows each wins, in words, e.g. `(["min angle 9.00° vs 7.01°"], [])`.
fn wins(a: &MeshStats, b: &MeshStats) -> (Vec<String>, Vec<String>) {
    let kappa = |k: f64| if k.is_finite() { format!("{k:.3}") } else { "∞".to_string() };
    let rows: [(String, std::cmp::Ordering); 3] = [
        (format!("min angle ({:.2}° vs {:.2}°)", a.min_angle_deg, b.min_angle_deg), a.min_angle_deg.total_cmp(&b.min_angle_deg)),
        (format!("min quality ({:.3} vs {:.3})", a.min_quality, b.min_quality), a.min_quality.total_cmp(&b.min_quality)),
        (format!("worst κ ({} vs {})", kappa(a.max_condition), kappa(b.max_condition)), b.max_condition.total_cmp(&a.max_condition)),
    ];
    let pick = |o: std::cmp::Ordering| rows.iter().filter(|(_, w)| *w == o).map(|(t, _)| t.clone()).collect();
    (pick(std::cmp::Ordering::Greater), pick(std::cmp::Ordering::Less))
}

/// `a`, `a and b`, `a, b and c`.
fn and_list(items: &[String]) -> String {
    match items {
        [] => String::new(),
        [one] => one.clone(),
        [init @ .., last] => format!("{} and {last}", init.join(", ")),
    }
}

fn chen_16(c: Canvas, theme: &Theme) -> Result<Vec<Pixmap>> {
    curved_runs()?.iter().map(|(t, m)| mesh_panel(m, t, c, theme)).collect()
}

pub(super) fn chen_16_measured() -> Result<String> {
    let runs = curved_runs()?;
    let words: Vec<String> = runs
        .iter()
        .map(|(t, m)| {
            let s = mesh_stats(m);
            format!("{t}: min angle {:.1}°, {} inverted", s.min_angle_deg, s.inverted)
        })
        .collect();
    let stats = |title: &str| runs.iter().find(|(t, _)| t == title).map(|(_, m)| mesh_stats(m));
    let (Some(old), Some(new)) = (stats(CHEN_16_OLD), stats(CHEN_16_NEW)) else {
        return Err(Error::invalid("chen-16: an optimization panel is missing"));
    };
    // one pass of each objective, as the meshes below show: say which wins where
    let (old_wins, new_wins) = wins(&old, &new);
    let verdict = match (old_wins.is_empty(), new_wins.is_empty()) {
        (true, true) => "After one pass the two objectives tie on min angle, min quality and worst κ.".to_string(),
        (false, true) => format!("After one pass the old objective wins here on {} (old vs new).", and_list(&old_wins)),
        (true, false) => format!("After one pass the new objective wins here on {} (new vs old).", and_list(&wins(&new, &old).0)),
        (false, false) => format!(
            "After one pass the old objective wins here on {} (old vs new), the new one on {} (new vs old).",
            and_list(&old_wins),
            and_list(&wins(&new, &old).0)
        ),
    };
    Ok(format!("Measured (angles at curved corners by their end tangents): {}. {verdict}", words.join("; ")))
}

// ---- Freitag Table 1 and Fig. 3 ------------------------------------------------------

/// One row of the live table: the reproduction's method name (its row in
/// `docs/reproduction.md` §1) and how that row smooths.
#[derive(Clone, Copy, Debug)]
pub struct FreitagMethod {
    pub method: &'static str,
    /// `None`: the mesh as generated.
    run: Option<(Strategy, ObjectiveKind, f64, Order, bool)>,
}

/// The rows the table shows, as the reproduction runs them: Freitag's own rows with her
/// measure (the smallest sine, for the smart Laplacian and the thresholds too), input
/// order; then the new objective.
pub const FREITAG_METHODS: [FreitagMethod; 9] = {
    use ObjectiveKind::{New, Sine};
    use Order::{Input, Priority};
    [
        FreitagMethod { method: "original", run: None },
        FreitagMethod { method: "laplace (plain)", run: Some((Strategy::Laplace, Sine, 30.0, Input, true)) },
        FreitagMethod { method: "smart (min sine)", run: Some((Strategy::Smart, Sine, 30.0, Input, true)) },
        FreitagMethod { method: "opt, `sine`", run: Some((Strategy::Opt, Sine, 30.0, Input, true)) },
        FreitagMethod { method: "C1 30°, `sine`", run: Some((Strategy::C1, Sine, 30.0, Input, true)) },
        FreitagMethod { method: "C2 30°, `sine`", run: Some((Strategy::C2, Sine, 30.0, Input, true)) },
        FreitagMethod { method: "C3 30°, `sine`", run: Some((Strategy::C3, Sine, 30.0, Input, true)) },
        FreitagMethod { method: "opt, `new`", run: Some((Strategy::Opt, New, 30.0, Input, false)) },
        FreitagMethod { method: "rules, `new`, priority", run: Some((Strategy::Rules, New, 30.0, Priority, false)) },
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
    if let Some((strategy, kind, threshold, order, her_measure)) = m.run {
        let mut o = SmoothOptions::default().with_strategy(strategy).with_order(order).with_threshold_deg(threshold);
        if her_measure {
            o = o.with_smart_measure(Measure::MinSine);
        }
        let mut s = Smoother::new(o)?;
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

fn freitag_table(c: Canvas, theme: &Theme) -> Result<Pixmap> {
    let mut pm = pixmap(c.w, c.h)?;
    pm.fill(theme.paper);
    let s = c.dpr;
    let w = c.w as f32 / s;
    let cols = [0.0, 0.25, 0.38, 0.51, 0.61, 0.71, 0.86];
    let head = ["method", "min angle, seed 1", "max angle, seed 1", "Lap. moves", "opt. calls", "min angle, seeds 1–5", "Freitag: min / max (lap / opt)"];
    let rows = FREITAG_METHODS.len() + 1;
    let line = ((c.h as f32 / s - 8.0) / rows as f32).min(30.0);
    let size = theme.text_px((line * 0.5).clamp(8.0, 13.0), 1.0);
    let text = |pm: &mut Pixmap, t: &str, col: usize, row: usize| {
        draw_text(pm, t, (8.0 + cols[col] * (w - 16.0)) * s, (4.0 + line * (row as f32 + 0.5)) * s, TextStyle::new(size * s).with_color(theme.ink).with_align(Align::Left, Valign::Middle));
    };
    for (i, h) in head.iter().enumerate() {
        text(&mut pm, h, i, 0);
    }
    for i in 0..FREITAG_METHODS.len() {
        let r = freitag_row(i)?;
        let cells = [
            r.method.replace('`', ""),
            format!("{:.2}°", r.min_angle_deg),
            format!("{:.1}°", r.max_angle_deg),
            r.laplacian_moves.to_string(),
            r.optimization_calls.to_string(),
            r.reproduction_min.clone(),
            r.paper.clone(),
        ];
        for (k, t) in cells.iter().enumerate() {
            text(&mut pm, t, k, i + 1);
        }
    }
    Ok(pm)
}

pub(super) fn freitag_t1_measured() -> Result<String> {
    let cellm = |row: &str| -> Result<String> { Ok(first(&repro(1, &[row], "min angle")?).to_string()) };
    Ok(format!(
        "Measured over five rand2D meshes (docs/reproduction.md §1): optimization of the smallest sine reaches a min \
         angle of {}° (Freitag {}), C2 and C3 at 30° {}° and {}°, and the new objective with Chen's rules {}°.",
        cellm("opt, `sine`")?,
        repro(1, &["opt, `sine`"], "paper: min / max (lap / opt)")?.split(" / ").next().unwrap_or("—"),
        cellm("C2 30°, `sine`")?,
        cellm("C3 30°, `sine`")?,
        cellm("rules, `new`, priority")?,
    ))
}

/// The methods of Fig. 3's picture (rows of [`FREITAG_METHODS`]).
const FIG3_ROWS: [usize; 5] = [0, 1, 3, 5, 8];

fn freitag_histogram(c: Canvas, t: &Theme) -> Result<Pixmap> {
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
    render_angle_histogram(
        &mut pm,
        &series,
        &AngleHistogram { title: "rand2D (seed 1): corner angles after 3 passes, 6° bins", dpr: c.dpr, theme: *t, ..AngleHistogram::default() },
    )?;
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

// ---- Knupp Fig. 1 ------------------------------------------------------------------------

/// The random grid as loaded, untangled (passes of `untangle` until no element is
/// inverted, at most 100), then after 10 passes of `condition`; and `new` + `rules`
/// after 10 passes — as the reproduction's §4.
fn knupp_runs() -> Result<Vec<(String, Mesh)>> {
    let (_, fig) = find("knupp-1")?;
    let (pg, _) = fig.playground()?;
    let m0 = pg.panel(Side::New).mesh.clone();
    let opt = SmoothOptions::default().with_strategy(Strategy::Opt).with_order(Order::Input);
    let mut m = m0.clone();
    let mut s = Smoother::new(opt.with_pass_through_folds(true))?;
    let untangle = objective_with(ObjectiveKind::Untangle, Penalty::Barrier);
    let mut passes = 0;
    while passes < 100 {
        passes += 1;
        if s.pass(&mut m, untangle.as_ref(), &|| 0.0).after.inverted == 0 {
            break;
        }
    }
    let untangled = m.clone();
    let cond = objective_with(ObjectiveKind::Condition, Penalty::Barrier);
    let mut s = Smoother::new(opt)?;
    for _ in 0..10 {
        s.pass(&mut m, cond.as_ref(), &|| 0.0);
    }
    let mut n = m0.clone();
    let mut s = Smoother::new(SmoothOptions::default())?;
    let new = objective_with(ObjectiveKind::New, Penalty::Barrier);
    for _ in 0..10 {
        s.pass(&mut n, new.as_ref(), &|| 0.0);
    }
    Ok(vec![
        ("1a. initial tangled mesh".into(), m0),
        (format!("1b. untangled ({passes} passes of untangle)"), untangled),
        ("1c. optimized with κ (10 passes)".into(), m),
        ("new + rules, 10 passes".into(), n),
    ])
}

fn knupp_1(c: Canvas, theme: &Theme) -> Result<Vec<Pixmap>> {
    knupp_runs()?.iter().map(|(t, m)| mesh_panel(m, t, c, theme)).collect()
}

pub(super) fn knupp_1_measured() -> Result<String> {
    let row = ["quad", "1"];
    Ok(format!(
        "Measured on this grid (docs/reproduction.md §4): {} elements inverted at the start; `untangle` (passes, inverted \
         after, of which flat) {}, leaving worst / mean κ {}; then `condition` (inverted, worst / mean κ) {}; `new` + \
         `rules` (passes to 0 inverted, worst / mean κ after 10 passes) {}.",
        repro(4, &row, "inverted at start")?,
        repro(4, &row, "`untangle`: passes, inverted after (of which flat)")?,
        repro(4, &row, "worst / mean κ after untangle")?,
        repro(4, &row, "after `condition`: inverted, worst / mean κ")?,
        repro(4, &row, "`new`+`rules`: passes to 0, worst / mean κ after 10 passes")?,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lab::tour::FIGURES;

    /// "13.14 [7.42–18.22]" → (7.42, 18.22).
    fn range(cell: &str) -> (f64, f64) {
        let inner = cell.split('[').nth(1).unwrap().trim_end_matches(']');
        let (a, b) = inner.split_once('–').unwrap();
        (a.parse().unwrap(), b.parse().unwrap())
    }

    #[test]
    fn the_live_table_smooths_as_the_reproduction_did() {
        // seed 1 is one of the reproduction's five seeds: its value lies in each row's range
        for i in 1..FREITAG_METHODS.len() {
            let r = freitag_row(i).unwrap();
            let (lo, hi) = range(&r.reproduction_min);
            assert!((lo - 0.005..=hi + 0.005).contains(&r.min_angle_deg), "{}: {} not in {lo}–{hi}", r.method, r.min_angle_deg);
            let (lo, hi) = range(&r.reproduction_max);
            assert!((lo - 0.05..=hi + 0.05).contains(&r.max_angle_deg), "{}: {} not in {lo}–{hi}", r.method, r.max_angle_deg);
        }
        assert!(freitag_row(FREITAG_METHODS.len()).is_err());
    }

    #[test]
    fn chen_2_alpha_leads_an_inverted_apex_away_and_the_new_objective_back() {
        let (near, far) = (alpha2(DVec2::new(-0.5, 0.0)), alpha2(DVec2::new(-3.0, 0.0)));
        assert!(near < far && far < 0.0, "α rises towards 0 away from AB: {near} {far}");
        let new = objective_with(ObjectiveKind::New, Penalty::Barrier);
        let p = DVec2::new(-0.5, 0.0);
        let (_, g) = new.value_and_gradient(&triangle_star(p).unwrap(), p);
        assert!(-g.y > 0.0, "the new objective descends towards AB: {g}");
    }

    #[test]
    fn chen_6_the_angle_jumps_and_the_adjusted_angle_does_not() {
        let (l, r) = (theta_a(DVec2::new(-1e-6, Y6)), theta_a(DVec2::new(1e-6, Y6)));
        assert!((l + PI).abs() < 1e-5 && (r - PI).abs() < 1e-5, "{l} {r}");
        assert!(adjusted_angle(l).0.abs() < 1e-4 && adjusted_angle(r).0.abs() < 1e-4);
        assert!((barrier_of_angle(PI / 3.0, 0.0) - BARRIER_WEIGHT).abs() < 1e-12, "η = 1 on the equilateral corner");
        assert!(barrier_of_angle(0.0, 0.0).is_infinite() && barrier_of_angle(0.0, DELTA6).is_finite());
    }

    #[test]
    fn every_figure_draws_a_picture_with_ink() {
        for f in &FIGURES {
            let pm = render(f.name, Canvas { w: 900, h: 420, dpr: 1.0 }, &Theme::light()).unwrap_or_else(|e| panic!("{}: {e}", f.name));
            let dark = pm.pixels().iter().filter(|p| p.red() < 128 && p.green() < 128).count();
            let colours: std::collections::HashSet<_> = pm.pixels().iter().map(|p| (p.red(), p.green(), p.blue())).collect();
            assert!(dark > 500 && colours.len() > 20, "{}: {dark} dark pixels, {} colours", f.name, colours.len());
        }
        assert!(render("chen-2", Canvas { w: 0, h: 10, dpr: 1.0 }, &Theme::light()).is_err());
    }
}
