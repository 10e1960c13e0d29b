//! The tour's pictures (`smoothlab render --figure NAME`, the page's figure panel,
//! `docs/figures/`) and the numbers its captions compute. Each picture is drawn from
//! the figure's own state ([`Figure::playground`]) or, for the 1-D views the playground
//! has no panel for (Chen's Figs. 2 and 6), from the same metrics the objectives use.
//! Freitag's live tables, and the pictures made of them, are in `tables.rs`.

use smoothlab_render::SurfacePicture;
use std::f64::consts::PI;

use glam::DVec2;
use serde::Serialize;
use tiny_skia::Pixmap;

use super::{find, repro, Figure};
use smoothlab::error::{Error, Result};
use crate::lab::views::{pixmap, Canvas};
use crate::lab::Side;
use smoothlab::mesh::{ElementKind, Mesh, MeshBuilder};
use smoothlab::objective::{adjusted_angle, objective_with, AnglePenalty, Objective, ObjectiveKind, Penalty, Star, BARRIER_WEIGHT};
use smoothlab::objective::regularised_determinant;
use smoothlab::optimize::SolveResult;
use smoothlab::quality::{lo_alpha, mesh_stats, signed_angle, MeshStats};
use smoothlab_render::{
    render_chart, render_mesh, render_sketch, render_titled, series_color, Chart, Frame, Marker, MeshView, Series, Sketch,
    SketchLine, Theme,
};
use smoothlab_render::layout::{record, Region};
use smoothlab_render::{draw_text, text_width, title_band, Align, TextStyle, Valign};
use smoothlab::smooth::{Order, SmoothOptions, Smoother, Strategy};
pub use super::tables::{
    freitag3d_row, freitag_row, table_caption, table_columns, table_row, table_rows, Freitag3dMethod, Freitag3dRow,
    FreitagMethod, FreitagRow, TableRow, FREITAG3D_METHODS, FREITAG_METHODS,
};
pub(super) use super::tables::{freitag_3_measured, freitag_t1_measured, freitag_t2_measured};
use super::tables::{freitag_histogram, freitag_t2, table_picture};

/// The size a figure's picture is drawn at by default, CSS pixels.
pub fn default_size(name: &str) -> (u32, u32) {
    match name {
        "chen-13" | "knupp-hex" => (1400, 760),
        "chen-9" | "chen-10" | "chen-11" | "chen-20" => (1100, 560),
        "freitag-t1" => (1100, 360),
        "freitag-t2" => (1200, 760),
        "chen-18" => (1400, 520),
        "freitag-3" => (1000, 520),
        _ => (1400, 460),
    }
}

/// The figure's panels as its default picture lays them out: columns and rows.
fn default_grid(name: &str) -> Result<(u32, u32)> {
    Ok(match name {
        "chen-2" | "chen-6" | "chen-18" => (3, 1),
        "chen-9" | "chen-10" | "chen-11" | "chen-20" => (2, 1),
        "chen-13" => (4, 2),
        "chen-16" => (CHEN_16_PANELS, 1),
        "knupp-1" => (4, 1),
        "knupp-hex" => (super::knupp_hex::columns()? as u32, 2),
        _ => (1, 1),
    })
}

/// The figure's panels, those its claim is about first: a small picture keeps the first
/// ones and drops the rest (the indices are of the default grid, row by row).
fn panel_priority(name: &str, n: usize) -> Vec<usize> {
    let first: &[usize] = match name {
        // the curves of α and of the new objective; the sketch of the triangle last
        "chen-2" | "chen-6" => &[1, 2, 0],
        // the chart of both orders, pass 1 in each, as loaded, then the later passes
        "chen-13" => &[4, 1, 5, 0, 2, 6, 3, 7],
        // the two optimizations and the constrained Laplacian the claim compares
        "chen-16" => &[3, 4, 2, 0, 1],
        // old and new after the passes, then as loaded
        "chen-18" => &[1, 2, 0],
        // the new objective's level sets (whose optimum and path the claims are about),
        // then the old one's
        "chen-9" | "chen-10" | "chen-20" => &[1, 0],
        // the step lengths the claim is about, then the path on the level sets
        "chen-11" => &[1, 0],
        // untangled, then optimized by κ, as loaded, then the new objective
        "knupp-1" => &[1, 2, 0, 3],
        _ => &[],
    };
    let mut out: Vec<usize> = first.iter().copied().filter(|&i| i < n).collect();
    if name == "knupp-hex" {
        // each side's last pass, then each side's start, then the passes between
        let cols = n / 2;
        out = vec![cols - 1, n - 1, 0, cols];
    }
    let rest: Vec<usize> = (0..n).filter(|i| !out.contains(i)).collect();
    out.extend(rest);
    out
}

/// The smallest panel, CSS pixels, that holds a chart's or a mesh's title, ticks and
/// legend at labels of 14 px without cutting a title.
const MIN_PANEL_CSS: (f32, f32) = (220.0, 180.0);
/// The smallest level-set panel, CSS pixels: its legend's widest entry ("the ascent's
/// direction: one tied corner's gradient") at 14 px.
const MIN_LEVEL_SET_PANEL_CSS: (f32, f32) = (340.0, 200.0);

/// The smallest panel of figure `name` in `t`, CSS pixels.
fn min_panel(name: &str, t: &Theme) -> Result<(f32, f32)> {
    Ok(match name {
        "chen-9" | "chen-10" | "chen-11" | "chen-20" => MIN_LEVEL_SET_PANEL_CSS,
        // its meshes with their colour bar, the key to their quality colours
        "chen-16" => keyed_min_panel(&find("chen-16")?.1.playground()?.0.panel(Side::B).mesh, t),
        _ => MIN_PANEL_CSS,
    })
}

/// How a figure's panels fill a canvas: which are kept (indices of the default grid, in
/// its order) and in how many columns and rows.
#[derive(Clone, Debug, PartialEq)]
pub struct Arrangement {
    pub keep: Vec<usize>,
    pub cols: u32,
    pub rows: u32,
}

/// The arrangement of figure `name`'s panels on canvas `c`: as many panels as fit at
/// `MIN_PANEL_CSS` or larger (those of `panel_priority` first), in the columns that
/// draw them largest for the shape of the default grid's panel; the default grid when
/// the canvas is the default size. Dropping panels rather than shrinking them keeps every
/// label at the theme's smallest size.
pub fn arrangement(name: &str, c: Canvas, t: &Theme) -> Result<Arrangement> {
    let (dc, dr) = default_grid(name)?;
    let n = (dc * dr) as usize;
    let (w0, h0) = default_size(name);
    let head = title_band(t);
    let ideal = (w0 as f32 / dc as f32, (h0 as f32 - head) / dr as f32);
    let s = c.dpr.max(0.1);
    let (w, h) = (c.w as f32 / s, c.h as f32 / s - head);
    let order = panel_priority(name, n);
    let (min_w, min_h) = min_panel(name, t)?;
    let mut best: Option<(f32, Arrangement)> = None;
    for k in (1..=n).rev() {
        for cols in 1..=k as u32 {
            let rows = (k as u32).div_ceil(cols);
            if cols * rows - k as u32 >= cols {
                continue; // a whole row empty
            }
            let (pw, ph) = (w / cols as f32, h / rows as f32);
            let fits = pw >= min_w && ph >= min_h;
            if !fits && k > 1 {
                continue;
            }
            // the default grid wins a tie; a canvas too small for one panel still draws one
            let score = (pw / ideal.0).min(ph / ideal.1) + if (cols, rows) == (dc, dr) { 1e-3 } else { 0.0 };
            if !best.as_ref().is_some_and(|(b, _)| score <= *b) {
                let mut keep: Vec<usize> = order[..k].to_vec();
                keep.sort_unstable();
                best = Some((score, Arrangement { keep, cols, rows }));
            }
        }
        if best.is_some() {
            break;
        }
    }
    best.map(|(_, a)| a).ok_or_else(|| Error::invalid(format!("figure {name} has no panel")))
}

/// The figure `name`'s picture on a canvas of `c.w × c.h` device pixels, in `theme`: its
/// panels arranged for the canvas ([`arrangement`]).
pub fn render(name: &str, c: Canvas, theme: &Theme) -> Result<Pixmap> {
    let t = theme;
    let (_, fig) = find(name)?;
    pixmap(c.w, c.h)?; // the size is checked before any work
    // the title whole at the smallest label, or the paper's figure alone, or the name
    let room = c.w as f32 - 16.0 * c.dpr;
    let floor = (t.min_label_px * c.dpr).max(1.0);
    let title = [format!("{} — {}", fig.source, fig.name), fig.source.to_string(), fig.name.to_string()]
        .into_iter()
        .find(|w| text_width(w, floor) <= room)
        .unwrap_or_else(|| fig.name.to_string());
    let a = arrangement(fig.name, c, t)?;
    let pc = part(c, a.cols, a.rows, t);
    let parts = match fig.name {
        "chen-2" => chen_2(pc, t)?,
        "chen-6" => chen_6(pc, t)?,
        "chen-9" => super::solves::chen_9(pc, t)?,
        "chen-10" => super::solves::chen_10(pc, t)?,
        "chen-20" => level_sets(fig, pc, t)?,
        "chen-11" => super::solves::chen_11(pc, t)?,
        "chen-13" => chen_13(pc, t)?,
        "chen-16" => chen_16(pc, t)?,
        "freitag-t1" => vec![table_picture("freitag-t1", pc, t)?],
        "freitag-t2" => vec![freitag_t2(pc, t)?],
        "chen-18" => chen_18(pc, t)?,
        "freitag-3" => vec![freitag_histogram(pc, t)?],
        "knupp-1" => knupp_1(pc, t)?,
        "knupp-hex" => super::knupp_hex::knupp_hex(pc, t)?,
        _ => return Err(Error::invalid(format!("figure {name} has no picture"))),
    };
    let kept: Vec<Pixmap> = parts.into_iter().enumerate().filter(|(i, _)| a.keep.contains(i)).map(|(_, p)| p).collect();
    render_titled(&kept, a.cols as usize, &title, c.dpr, t).ok_or_else(|| Error::invalid("cannot allocate the figure"))
}

/// The figure `name`'s picture ([`render`]) and where its plots, legends and chart marks
/// lie in it, device pixels, as they were drawn ([`smoothlab_render::layout`]): for the tests
/// that keep legends off the data and find the marks a text promises.
pub fn render_with_layout(name: &str, c: Canvas, theme: &Theme) -> Result<(Pixmap, Vec<Region>)> {
    let (pm, notes) = record(|| render(name, c, theme));
    let pm = pm?;
    let regions = notes.of(&pm);
    Ok((pm, regions))
}

/// The canvas of one of `cols × rows` panels under the title band.
pub(super) fn part(c: Canvas, cols: u32, rows: u32, t: &Theme) -> Canvas {
    let head = (title_band(t) * c.dpr.max(0.1)).round() as u32;
    Canvas { w: (c.w / cols).max(1), h: (c.h.saturating_sub(head) / rows).max(1), dpr: c.dpr }
}

/// A mesh on its own panel with a title and a line of statistics under it.
pub(super) fn mesh_panel(mesh: &Mesh, title: &str, c: Canvas, t: &Theme) -> Result<Pixmap> {
    titled_mesh_panel(mesh, title, c, t, false)
}

/// The height, CSS pixels, of a mesh panel's title and line above its mesh in `t`: the
/// title (13 px) and the line (11 px), grown with the theme's labels.
fn mesh_panel_head(t: &Theme) -> f32 {
    22.0 * t.grow(13.0) + 18.0 * t.grow(11.0)
}

/// The least height, CSS pixels, a mesh keeps above the colour bar [`keyed_mesh_panel`]
/// puts under it.
const MIN_KEYED_MESH_CSS_H: f32 = 80.0;

/// The colour bar of `mesh` (the key to its colours: the metric, its range, the inverted
/// swatch and count) at the foot of `frame` (CSS pixels) in `t`, as the renderer sizes
/// it: `None` where the frame's width does not hold it or the mesh would keep less than
/// [`MIN_KEYED_MESH_CSS_H`] above it. The renderer's own bar takes at most a share of the
/// frame's short side; a wide, low mesh leaves most of a panel's height empty, so this
/// one asks for the height the mesh needs instead.
fn key_band(mesh: &Mesh, frame: Frame, t: &Theme) -> Option<Frame> {
    let title = MeshView::default().metric.label(mesh);
    let band = smoothlab_render::colour_bar_band(Frame::new(frame.x, frame.y, frame.w, frame.w.max(frame.h)), title, t)?;
    (frame.h - band.h >= MIN_KEYED_MESH_CSS_H).then(|| Frame::new(frame.x, frame.bottom() - band.h, frame.w, band.h))
}

/// The smallest panel, CSS pixels, of a figure whose meshes carry their colour bar
/// ([`keyed_mesh_panel`]): as wide as the bar for `mesh` needs in `t`.
fn keyed_min_panel(mesh: &Mesh, t: &Theme) -> (f32, f32) {
    let (min_w, min_h) = MIN_PANEL_CSS;
    let tall = |w: f32| Frame::new(0.0, 0.0, w, 4.0 * min_h);
    let w = (min_w as u32..4 * min_w as u32).map(|w| w as f32).find(|&w| key_band(mesh, tall(w), t).is_some()).unwrap_or(4.0 * min_w);
    let band = key_band(mesh, tall(w), t).map_or(0.0, |b| b.h);
    (w, min_h.max(mesh_panel_head(t) + MIN_KEYED_MESH_CSS_H + band))
}

/// A mesh panel with the colour bar under its mesh wherever the panel has room for it
/// ([`key_band`]); without, where it has not.
pub(super) fn keyed_mesh_panel(mesh: &Mesh, title: &str, c: Canvas, t: &Theme) -> Result<Pixmap> {
    titled_mesh_panel(mesh, title, c, t, true)
}

fn titled_mesh_panel(mesh: &Mesh, title: &str, c: Canvas, t: &Theme, keyed: bool) -> Result<Pixmap> {
    let mut pm = pixmap(c.w, c.h)?;
    let s = c.dpr;
    let full = Frame::of_pixmap(&pm, s);
    let st = mesh_stats(mesh);
    let line = format!("inverted {}, angles {:.1}°–{:.1}°", st.inverted, st.min_angle_deg, st.max_angle_deg);
    let g13 = t.grow(13.0);
    let below_head = full.inset(0.0, mesh_panel_head(t), 0.0, 0.0);
    let key = if keyed { key_band(mesh, below_head, t) } else { None };
    let view = MeshView { theme: *t, ..MeshView::default().with_dpr(s) };
    match key {
        Some(band) => {
            let area = Frame::new(below_head.x, below_head.y, below_head.w, band.y - below_head.y);
            render_mesh(&mut pm, mesh, &MeshView { colour_bar: false, ..view.with_frame(area) });
            // one count of inverted elements: the statistics' (the line above says the same)
            let metric = view.metric;
            smoothlab_render::draw_colour_bar(&mut pm, band, view.colormap, metric.domain(mesh), metric.label(mesh), st.inverted, s, t);
        }
        None => {
            render_mesh(&mut pm, mesh, &view.with_frame(below_head));
        }
    }
    // each shrunk or cut to the panel's width (four panels side by side in a narrow frame)
    let room = (full.w - 8.0).max(0.0) * s;
    let style = |size: f32| TextStyle::new(size).with_color(t.ink).with_align(Align::Centre, Valign::Top);
    let (shown, size) = t.fit_title(title, 13.0 * s, room, s);
    draw_text(&mut pm, &shown, full.w / 2.0 * s, 4.0 * s, style(size));
    let (shown, size) = t.fit_label(&line, 11.0 * s, room, s);
    draw_text(&mut pm, &shown, full.w / 2.0 * s, (4.0 + 18.0 * g13) * s, style(size));
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
    let new = objective_with(ObjectiveKind::SmoothShape, Penalty::Barrier);
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
        chart(&f, "(c) new objective, smaller is better", "objective", true)?,
    ])
}

/// The numbers of Fig. 2's claim, computed.
pub(super) fn chen_2_measured() -> Result<String> {
    let p = DVec2::new(-0.5, 0.0);
    let (a0, a1, a2) = (alpha2(DVec2::new(0.0, 0.0)), alpha2(p), alpha2(DVec2::new(-3.0, 0.0)));
    let new = objective_with(ObjectiveKind::SmoothShape, Penalty::Barrier);
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
pub(super) fn first(cell: &str) -> &str {
    cell.split_whitespace().next().unwrap_or(cell)
}

// ---- level sets: Figs. 9, 10, 20 ------------------------------------------------------

fn level_sets(fig: &Figure, c: Canvas, t: &Theme) -> Result<Vec<Pixmap>> {
    let (mut pg, st) = fig.playground()?;
    pg.set_theme(*t);
    let node = st.node.ok_or_else(|| Error::invalid(format!("figure {} names no node", fig.name)))? as usize;
    let (old, _) = pg.render_level_set(Side::A, node, c)?;
    let (new, _) = pg.render_level_set(Side::B, node, c)?;
    Ok(vec![old, new])
}

/// Both sides' solves at the figure's node.
fn solves(name: &str) -> Result<(SolveResult, SolveResult)> {
    let (_, fig) = find(name)?;
    let (pg, st) = fig.playground()?;
    let node = st.node.ok_or_else(|| Error::invalid(format!("figure {name} names no node")))? as usize;
    Ok((pg.solve_node(Side::A, node)?, pg.solve_node(Side::B, node)?))
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

/// The most passes the figure runs in either order before it says "not untangled".
pub const CHEN13_MAX_PASSES: usize = 10;
/// The seeds the figure's text runs besides the plate drawn (seed 1), as the reproduction's §2.
const CHEN13_SEEDS: std::ops::RangeInclusive<u64> = 1..=5;

/// The smoothing of Figs. 13–15 as Chen et al. publish it: `new` + `rules` with the
/// figure's settings, but without our untangling sweeps (`SmoothOptions::untangle_sweeps`,
/// which revisit the inverted elements' nodes up to 10 times a pass and untangle every
/// plate of `docs/reproduction.md` §2 in the first pass in either order) and with Chen's
/// line search alone (no Newton step first, §3). `examples/chen13_search.rs` varied the
/// plate (kind, element order, resolution), the amount, the seed, the solver and the
/// iterations per call: the sweeps decide it — with them no configuration shows the
/// paper's contrast, without them priority order needs fewer passes on nearly every
/// plate, and here (tri, amount 1.5, Chen's search) on each of seeds 1–8, 1 pass against 3.
fn chen13_options(settings: &crate::lab::Settings, order: Order) -> Result<SmoothOptions> {
    Ok(settings.smooth_options()?.with_order(order).with_untangle_sweeps(0).with_newton(false))
}

/// The figure's plate (its hash: sample, amount) perturbed with `seed`.
fn chen13_plate(seed: u64) -> Result<Mesh> {
    let (_, fig) = find("chen-13")?;
    let st = fig.state()?;
    let (pg, _) = fig.playground()?;
    if seed == st.seed {
        return Ok(pg.panel(Side::B).mesh.clone());
    }
    let name = st.sample.clone().unwrap_or_default();
    let sample: crate::lab::sample::Sample = serde_json::from_value(serde_json::Value::String(name))
        .map_err(|_| Error::invalid("chen-13: its sample is not generated"))?;
    smoothlab::generate::perturb(&sample.generate()?, st.amount, seed)
}

/// The plate of Figs. 13–15 smoothed in `order` ([`chen13_options`]): the mesh as
/// loaded and after each pass, at least 3 passes (Chen's Figs. 14–15 show three) and on
/// until no element is inverted (at most [`CHEN13_MAX_PASSES`]).
fn plate_passes_from(m0: &Mesh, order: Order) -> Result<Vec<Mesh>> {
    let (_, fig) = find("chen-13")?;
    let st = fig.state()?;
    let mut m = m0.clone();
    let mut s = Smoother::new(chen13_options(&st.settings, order)?)?;
    let obj = objective_with(ObjectiveKind::SmoothShape, Penalty::Barrier);
    let mut out = vec![m.clone()];
    while out.len() <= CHEN13_MAX_PASSES && (out.len() <= 3 || mesh_stats(&m).inverted > 0) {
        s.pass(&mut m, obj.as_ref(), &|| 0.0);
        out.push(m.clone());
    }
    Ok(out)
}

/// Inverted elements before and after each pass of the figure's plate, in priority and
/// in input order (what the picture and the text show; the page's tests read it).
#[derive(Clone, Debug, Serialize)]
pub struct Chen13Counts {
    pub priority: Vec<u32>,
    pub input: Vec<u32>,
}

/// Passes to 0 inverted of a count list (its first 0), `None` when not untangled.
fn passes_to_zero(c: &[u32]) -> Option<usize> {
    c.iter().position(|&n| n == 0)
}

/// The per-pass counts of the plate drawn (seed 1).
pub fn chen_13_counts() -> Result<Chen13Counts> {
    let m0 = chen13_plate(find("chen-13")?.1.state()?.seed)?;
    let count = |order| -> Result<Vec<u32>> {
        Ok(plate_passes_from(&m0, order)?.iter().map(|m| mesh_stats(m).inverted as u32).collect())
    };
    Ok(Chen13Counts { priority: count(Order::Priority)?, input: count(Order::Input)? })
}

/// The chart of inverted elements per pass, both orders.
fn chen13_chart(counts: &Chen13Counts, c: Canvas, t: &Theme) -> Result<Pixmap> {
    let pts = |v: &[u32]| -> Vec<DVec2> { v.iter().enumerate().map(|(i, &n)| DVec2::new(i as f64, n as f64)).collect() };
    let (p, i) = (pts(&counts.priority), pts(&counts.input));
    let words = |v: &[u32]| v.iter().map(u32::to_string).collect::<Vec<_>>().join(" → ");
    let (lp, li) = (format!("priority: {}", words(&counts.priority)), format!("input: {}", words(&counts.input)));
    let mut pm = pixmap(c.w, c.h)?;
    render_chart(
        &mut pm,
        &[
            Series::new(&lp, &p).with_color(series_color(2)).with_marker(Marker::Circle),
            Series::new(&li, &i).with_color(series_color(1)).with_marker(Marker::Square).with_dash(true),
        ],
        &Chart { title: "inverted after each pass", x_label: "pass (0: as loaded)", y_label: "inverted", dpr: c.dpr, theme: *t, ..Chart::default() },
    );
    Ok(pm)
}

/// Figs. 13–15: row 1 the plate as loaded then passes 1–3 in priority order; row 2 the
/// chart of both orders' counts, then passes 1–3 in input order. Each panel's title says
/// its count.
fn chen_13(c: Canvas, t: &Theme) -> Result<Vec<Pixmap>> {
    let m0 = chen13_plate(find("chen-13")?.1.state()?.seed)?;
    let runs = [(Order::Priority, "priority order"), (Order::Input, "input order")].map(|(o, n)| (plate_passes_from(&m0, o), n));
    let counts = chen_13_counts()?;
    let mut parts = Vec::new();
    for (row, (run, name)) in runs.into_iter().enumerate() {
        let run = run?;
        parts.push(if row == 0 { mesh_panel(&m0, "as loaded (both orders)", c, t)? } else { chen13_chart(&counts, c, t)? });
        for (k, m) in run.iter().enumerate().skip(1).take(3) {
            parts.push(mesh_panel(m, &format!("{name}, pass {k}"), c, t)?);
        }
    }
    Ok(parts)
}

pub(super) fn chen_13_measured() -> Result<String> {
    let counts = chen_13_counts()?;
    let words = |v: &[u32]| v.iter().map(u32::to_string).collect::<Vec<_>>().join(" → ");
    let passes = |v: &[u32]| passes_to_zero(v).map_or(format!("not in {CHEN13_MAX_PASSES}"), |n| n.to_string());
    // the other seeds, as the reproduction's §2 runs five
    let (mut ps, mut is) = (Vec::new(), Vec::new());
    for seed in CHEN13_SEEDS {
        let m0 = chen13_plate(seed)?;
        for (order, out) in [(Order::Priority, &mut ps), (Order::Input, &mut is)] {
            let run = plate_passes_from(&m0, order)?;
            let inv: Vec<u32> = run.iter().map(|m| mesh_stats(m).inverted as u32).collect();
            out.push(passes(&inv));
        }
    }
    let row = ["tri", "1.5"];
    Ok(format!(
        "Measured with Chen's algorithm as published (no untangling sweeps, which are ours, and Chen's line search \
         alone), inverted elements pass by pass: {} in priority order, {} in input order — {} {} against {}; \
         seeds {}–{} of this plate take {} passes in priority order and {} in input order. With our sweeps (the page's default, the live panels) \
         every plate of the reproduction untangles in the first pass in either order: {} and {} passes over its five \
         seeds at this amount (docs/reproduction.md §2).",
        words(&counts.priority),
        words(&counts.input),
        passes(&counts.priority),
        if passes_to_zero(&counts.priority) == Some(1) { "pass" } else { "passes" },
        passes(&counts.input),
        CHEN13_SEEDS.start(),
        CHEN13_SEEDS.end(),
        ps.join(", "),
        is.join(", "),
        first(&repro(2, &row, "barrier: priority")?),
        first(&repro(2, &row, "barrier: input order")?),
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
    let m0 = pg.panel(Side::B).mesh.clone();
    let new = objective_with(ObjectiveKind::SmoothShape, Penalty::Barrier);
    let old = objective_with(ObjectiveKind::MaxMinShape, Penalty::Barrier);
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
    curved_runs()?.iter().map(|(t, m)| keyed_mesh_panel(m, t, c, theme)).collect()
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

// ---- Chen Figs. 18–19: a tangled quadratic surface ---------------------------------------

/// The surface lab of `chen-18`: its gallery sample (a quadratic mixed torus, tangled in
/// its tangent planes) with the figure's settings, and the inverted elements of each side
/// after each of the figure's passes (the first count: as loaded).
fn chen18_run() -> Result<(crate::lab::Lab3d<smoothlab::surface::Surface>, [Vec<usize>; 2])> {
    let (_, fig) = find("chen-18")?;
    let st = fig.state()?;
    let sample = super::gallery_sample(fig.name).ok_or_else(|| Error::invalid("chen-18 names no gallery sample"))?;
    let smoothlab::model::Model::Surface(s) = sample.model()? else {
        return Err(Error::invalid("chen-18: its sample is not a surface"));
    };
    let mut lab = crate::lab::Lab3d::new(s)?;
    lab.set_settings(st.settings)?;
    let start = lab.original().stats().inverted;
    let mut counts = [vec![start], vec![start]];
    for _ in 0..st.passes {
        let r = lab.step(&|| 0.0);
        for (c, r) in counts.iter_mut().zip(&r) {
            c.push(r.after.inverted);
        }
    }
    Ok((lab, counts))
}

/// Figs. 18–19 (our reading: the paper shows a surface mesh made with the new smoother and
/// a head; its subject is quadratic mixed surface meshes): the tangled quadratic torus as
/// loaded, then each side after the figure's passes, in 3D with one camera.
fn chen_18(c: Canvas, t: &Theme) -> Result<Vec<Pixmap>> {
    let (mut lab, counts) = chen18_run()?;
    lab.set_theme(*t);
    let passes = counts[0].len() - 1;
    let settings = lab.settings();
    let camera = facing_inverted(lab.mesh(Side::A)).unwrap_or_else(|| lab.camera());
    let draw = |s: &smoothlab::surface::Surface, title: String| -> Result<Pixmap> {
        let mut pm = pixmap(c.w, c.h)?;
        let view = smoothlab_render::SurfaceView { camera, dpr: c.dpr, title: Some(title), theme: *t, ..smoothlab_render::SurfaceView::default() };
        s.render(&mut pm, smoothlab_render::Metric::Shape, &view);
        Ok(pm)
    };
    let after = |side: Side| {
        format!("{}: {}, {passes} passes: {} inverted", side.letter(), settings.choice(side).objective, counts[side.index()][passes])
    };
    Ok(vec![
        draw(lab.original(), format!("as loaded: {} inverted", counts[0][0]))?,
        draw(lab.mesh(Side::A), after(Side::A))?,
        draw(lab.mesh(Side::B), after(Side::B))?,
    ])
}

/// A camera from above the side of `s` where its inverted elements lie (the mean of their
/// nodes, seen from the mesh's centre), so the elements the claim is about face the
/// viewer; `None` when none is inverted.
fn facing_inverted(s: &smoothlab::surface::Surface) -> Option<smoothlab_render::Camera> {
    let (pts, flat) = (s.points(), s.flat());
    let centre = pts.iter().copied().sum::<glam::DVec3>() / pts.len().max(1) as f64;
    let inverted: Vec<usize> = s.inverted_elements().iter().enumerate().filter(|(_, b)| **b).map(|(e, _)| e).collect();
    let nodes: Vec<glam::DVec3> = inverted.iter().flat_map(|&e| flat.element(e).iter().map(|&n| pts[n as usize])).collect();
    if nodes.is_empty() {
        return None;
    }
    let d = nodes.iter().copied().sum::<glam::DVec3>() / nodes.len() as f64 - centre;
    // the viewer stands at (sin yaw, −cos yaw) about the centre (render::Camera::basis),
    // high enough to see into a torus's hole
    let yaw = d.x.atan2(-d.y).to_degrees().rem_euclid(360.0);
    Some(smoothlab_render::Camera { yaw, pitch: 50.0, zoom: 1.0 })
}

/// The text's numbers: each side's count pass by pass, its smallest angle after, and §9.
pub(super) fn chen_18_measured() -> Result<String> {
    let (lab, counts) = chen18_run()?;
    let words = |v: &[usize]| v.iter().map(usize::to_string).collect::<Vec<_>>().join(" → ");
    let s = lab.original();
    let row = ["torus mixed order 2"];
    let (a, b) = (lab.full_stats(Side::A), lab.full_stats(Side::B));
    Ok(format!(
        "Measured on this torus ({} nodes, {} elements), inverted elements pass by pass: {} with the old max-min \
         objective, {} with the new one; after the last pass the smallest angle is {:.1}° (old) and {:.1}° (new), \
         every node within {:.0e} of the torus. On finer tori (docs/reproduction.md §9: {} nodes, {} inverted on \
         average) the new objective untangled {} runs, in at most {} pass.",
        s.node_count(),
        s.element_count(),
        words(&counts[0]),
        words(&counts[1]),
        a.min_angle_deg,
        b.min_angle_deg,
        a.max_distance_from_surface.unwrap_or(0.0).max(b.max_distance_from_surface.unwrap_or(0.0)),
        repro(9, &row, "nodes")?,
        repro(9, &row, "inverted before")?,
        repro(9, &row, "untangled")?,
        repro(9, &row, "passes")?,
    ))
}

// ---- Knupp Fig. 1 ------------------------------------------------------------------------

/// The random grid as loaded, untangled (passes of `untangle` until no element is
/// inverted, at most 100), then after 10 passes of `condition`; and `new` + `rules`
/// after 10 passes — as the reproduction's §4.
fn knupp_runs() -> Result<Vec<(String, Mesh)>> {
    let (_, fig) = find("knupp-1")?;
    let (pg, _) = fig.playground()?;
    let m0 = pg.panel(Side::B).mesh.clone();
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
    let new = objective_with(ObjectiveKind::SmoothShape, Penalty::Barrier);
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

    #[test]
    fn chen_2_alpha_leads_an_inverted_apex_away_and_the_new_objective_back() {
        let (near, far) = (alpha2(DVec2::new(-0.5, 0.0)), alpha2(DVec2::new(-3.0, 0.0)));
        assert!(near < far && far < 0.0, "α rises towards 0 away from AB: {near} {far}");
        let new = objective_with(ObjectiveKind::SmoothShape, Penalty::Barrier);
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
    fn chen_13_priority_untangles_in_fewer_passes_than_input_order() {
        // Chen et al. §4.2: 3 (or 4) passes in priority order against 7 in input order;
        // the figure's configuration shows the contrast, measured
        let c = chen_13_counts().unwrap();
        assert_eq!(c.priority[0], c.input[0], "one plate for both orders");
        assert!(c.priority[0] > 100, "the plate starts tangled: {:?}", c.priority);
        let (p, i) = (passes_to_zero(&c.priority).unwrap(), passes_to_zero(&c.input).unwrap());
        assert!(p < i, "priority {:?} against input {:?}", c.priority, c.input);
        let text = chen_13_measured().unwrap();
        let words = |v: &[u32]| v.iter().map(u32::to_string).collect::<Vec<_>>().join(" → ");
        assert!(text.contains(&words(&c.priority)) && text.contains(&words(&c.input)), "{text}");
    }

    #[test]
    fn chen_18_the_new_objective_untangles_the_quadratic_torus_and_the_old_does_not() {
        let (_, [old, new]) = chen18_run().unwrap();
        assert!(old[0] > 50 && old[0] == new[0], "{old:?} {new:?}");
        assert_eq!(new[1], 0, "the new objective untangles in the first pass: {new:?}");
        assert!(*old.last().unwrap() > 0, "the old one does not: {old:?}");
        let text = chen_18_measured().unwrap();
        let words = |v: &[usize]| v.iter().map(usize::to_string).collect::<Vec<_>>().join(" → ");
        assert!(text.contains(&words(&old)) && text.contains(&words(&new)), "{text}");
    }

    #[test]
    fn chen_16_keeps_the_colour_bar_under_every_panel_it_keeps() {
        // the canvases of the picture in an embed of 1280×720, 800×450 and 520×520 and on
        // a phone (about), and its default; labels at the page's 14 px and unraised
        use smoothlab_render::layout::RegionKind;
        for t in [Theme::for_page(false, 14.0), Theme::light()] {
            for (w, h) in [(1400, 460), (1246, 420), (766, 266), (486, 250), (360, 430), (200, 160)] {
                let c = Canvas { w, h, dpr: 1.0 };
                let a = arrangement("chen-16", c, &t).unwrap();
                let (_, regions) = render_with_layout("chen-16", c, &t).unwrap();
                let bars = regions.iter().filter(|r| r.kind == RegionKind::Legend).count();
                let (pw, ph) = (w as f32 / a.cols as f32, (h as f32 - title_band(&t)) / a.rows as f32);
                let fits = |min: (f32, f32)| pw >= min.0 && ph >= min.1;
                let mesh = find("chen-16").unwrap().1.playground().unwrap().0.panel(Side::B).mesh.clone();
                if fits(keyed_min_panel(&mesh, &t)) {
                    assert_eq!(bars, a.keep.len(), "{w}×{h}, {} px labels: {a:?}", t.min_label_px);
                }
                if (w, h) == (200, 160) {
                    assert_eq!((a.keep.len(), bars), (1, 0), "too small for a panel with its bar: one without it");
                }
            }
        }
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
