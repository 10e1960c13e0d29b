//! The tour's pictures of one node's solve — Chen, Tristano & Kwok (2003), Fig. 9 (one
//! quadratic edge pushed in), Fig. 10 (a star-shaped configuration) and Figs. 11–12 (the
//! convergence history) — and the numbers their texts quote, computed once for both.
//!
//! Each side's level sets are drawn as the page's node view draws them
//! ([`Playground::render_level_set`]) with what the figure is about added
//! ([`render_level_set_with`]): Fig. 9's end tangents (the paper's dashed lines) and each
//! objective's optimum found by searching the feasible region, with, when Freitag's ascent
//! cannot leave the start, the direction it tried and the one that would rise; Fig. 10's
//! levels spent inside the feasible region; Figs. 11–12's gradient and conjugate steps.

use glam::DVec2;
use tiny_skia::{Color, Pixmap};

use super::{find, repro};
use smoothlab::error::{Error, Result};
use crate::lab::views::{path_kind, pixmap, stop_words, Canvas, LEVEL_SET_SAMPLES};
use crate::lab::{Playground, Side};
use smoothlab::numeric::order::{sort_stable_by_key, total_order_key};
use smoothlab::objective::{CornerTerm, Goal, MaxMinShape, Objective, Star};
use smoothlab::optimize::{min_norm_point, DirectionKind, SolveResult};
use smoothlab_render::{
    feasible_levels, render_chart, render_level_set_with, sample_field, Chart, Frame, LevelSet, LevelSetExtras, LevelSetView, Marker, Overlay,
    PathKind, Series, Theme,
};

/// A figure's playground in `theme`, with the node its state names.
fn figure_state(name: &str, theme: &Theme) -> Result<(Playground, usize)> {
    let (_, fig) = find(name)?;
    let (mut pg, st) = fig.playground()?;
    pg.set_theme(*theme);
    let node = st.node.ok_or_else(|| Error::invalid(format!("figure {name} names no node")))? as usize;
    Ok((pg, node))
}

/// What one side's level-set panel of a figure shows besides the field.
struct SidePanel<'a> {
    side: Side,
    /// The solve whose path is drawn.
    solve: &'a SolveResult,
    /// Where the panel's optimum star goes; `None`: no star (an overlay marks it).
    optimum: Option<DVec2>,
    overlays: &'a [Overlay<'a>],
    /// `Some(n)`: `n` levels inside the feasible region ([`feasible_levels`]).
    feasible_levels: Option<usize>,
    /// The box to frame instead of the page's (the feasible region): a short path's.
    bounds: Option<(DVec2, DVec2)>,
}

/// One side's level sets round `node`, framed as the page frames them (on the feasible
/// region with the start and the solver's end), with `p`'s path, star and overlays.
fn side_panel(pg: &Playground, node: usize, c: Canvas, p: &SidePanel<'_>) -> Result<Pixmap> {
    let panel = pg.panel(p.side);
    let mut star = Star::new();
    star.gather(&panel.mesh, node);
    let bounds = p.bounds.unwrap_or_else(|| pg.level_bounds(p.side, node).1);
    let field = sample_field(panel.objective.as_ref(), &star, bounds, LEVEL_SET_SAMPLES, LEVEL_SET_SAMPLES)?;
    let mut path = vec![(p.solve.x0, PathKind::Start)];
    path.extend(p.solve.history.iter().map(|it| (it.x, path_kind(it.direction))));
    let title = pg.settings().side_title(p.side);
    let levels = p.feasible_levels.map(|n| feasible_levels(&field, n));
    let data = LevelSet { field: &field, star: &star, path: &path, optimum: p.optimum, title: &title };
    let opts = LevelSetView { dpr: c.dpr, clip: true, theme: pg.theme(), ..LevelSetView::default() };
    let mut pm = pixmap(c.w, c.h)?;
    render_level_set_with(&mut pm, &data, &opts, &LevelSetExtras { overlays: p.overlays, levels: levels.as_deref() });
    Ok(pm)
}

/// Where `objective` is best within the box `b`, whatever a solver found: the best point
/// of a 121 × 121 grid, then of eleven finer 21 × 21 grids, each over four steps of the
/// last round about its best point (the box shrinks a billionfold). Non-finite values
/// (a barrier's +∞) are never best.
pub(crate) fn search_optimum(objective: &dyn Objective, star: &Star, b: (DVec2, DVec2)) -> (DVec2, f64) {
    let better = |a: f64, b: f64| match objective.goal() {
        Goal::MaximizeMin => a > b,
        Goal::MinimizeSum => a < b,
    };
    let (mut lo, mut hi) = b;
    let mut best = (star.x0, f64::NAN);
    let mut n = 121;
    for _ in 0..12 {
        let step = (hi - lo) / (n - 1) as f64;
        for j in 0..n {
            for i in 0..n {
                let x = lo + step * DVec2::new(i as f64, j as f64);
                let v = objective.value(star, x);
                if v.is_finite() && (best.1.is_nan() || better(v, best.1)) {
                    best = (x, v);
                }
            }
        }
        (lo, hi) = (best.0 - 2.0 * step, best.0 + 2.0 * step);
        n = 21;
    }
    best
}

// ---- Fig. 9: one quadratic edge pushed in ----------------------------------------------

/// The end tangents of the dashed lines (Okabe–Ito blue: no band of viridis, no mark of the
/// panel is near it).
const TANGENT: [u8; 3] = [0, 114, 178];
/// The direction Freitag's ascent tried, and the one both tied corners rise along.
const TRIED: [u8; 3] = [213, 94, 0];
const RISE: [u8; 3] = [0, 158, 115];
const OPTIMUM: [u8; 3] = [240, 228, 66];

fn rgb(c: [u8; 3]) -> Color {
    Color::from_rgba8(c[0], c[1], c[2], 255)
}

/// The star's curved edge (a quadratic edge whose mid node is off its chord, away from
/// the free node): its ends `a`, `b` and mid node `m`.
fn curved_edge(star: &Star) -> Option<(DVec2, DVec2, DVec2)> {
    star.elems.iter().find_map(|el| {
        let k = el.kind.corners();
        (0..k).find_map(|i| {
            let j = (i + 1) % k;
            let m = el.pts[el.kind.mid(i)?];
            let (a, b) = (el.pts[i], el.pts[j]);
            let off = (m - 0.5 * (a + b)).length();
            (i != el.slot as usize && j != el.slot as usize && off > 1e-9 * (b - a).length()).then_some((a, m, b))
        })
    })
}

/// Where the end tangents of the quadratic edge `a, m, b` meet: the tangent at `a` is
/// `4m − 3a − b`, at `b` `4m − 3b − a` (the Lagrange edge's derivative at its ends).
fn tangent_meet(a: DVec2, m: DVec2, b: DVec2) -> Option<DVec2> {
    let (ta, tb) = (4.0 * m - 3.0 * a - b, 4.0 * m - 3.0 * b - a);
    let det = ta.perp_dot(tb);
    (det.abs() > 1e-12 * ta.length() * tb.length()).then(|| a + ta * ((b - a).perp_dot(tb) / det))
}

/// Fig. 9's numbers, for its picture and its text alike.
pub(crate) struct Chen9 {
    /// The curved edge's ends and where their tangents (the paper's dashed lines) meet.
    pub ends: (DVec2, DVec2),
    pub meet: DVec2,
    /// Each side's solve from the start, and its optimum found by [`search_optimum`].
    pub old: SolveResult,
    pub new: SolveResult,
    pub old_best: (DVec2, f64),
    pub new_best: (DVec2, f64),
    /// The two smallest corner terms at the start (the worst element's, when they tie).
    pub lowest: [CornerTerm; 2],
    /// Whether they tie: two corners of one element with one α (a kink of max-min α).
    pub tie: bool,
    /// Whether the tied corners are the curved edge's ends.
    pub on_curve: bool,
    /// The direction Freitag's ascent takes at the start: the minimum-norm point of the
    /// hull of the active element terms' gradients (Freitag 1997, Fig. 1).
    pub tried: DVec2,
    /// The rate of the smaller of the two lowest corners' α along `tried`, per unit length.
    pub tried_rate: f64,
    /// The steepest ascent of both lowest corners: the minimum-norm point of the hull of
    /// their gradients.
    pub rise: DVec2,
}

pub(crate) fn chen_9_numbers() -> Result<Chen9> {
    let (pg, node) = figure_state("chen-9", &Theme::light())?;
    let mut star = Star::new();
    star.gather(&pg.panel(Side::A).mesh, node);
    let (a, m, b) = curved_edge(&star).ok_or_else(|| Error::invalid("chen-9: the star has no curved edge"))?;
    let meet = tangent_meet(a, m, b).ok_or_else(|| Error::invalid("chen-9: the end tangents are parallel"))?;
    let (old, new) = (pg.solve_node(Side::A, node)?, pg.solve_node(Side::B, node)?);
    let best = |side: Side| {
        let (_, shown) = pg.level_bounds(side, node);
        search_optimum(pg.panel(side).objective.as_ref(), &star, shown)
    };
    let (old_best, new_best) = (best(Side::A), best(Side::B));
    let mut corners = MaxMinShape.corner_terms(&star, star.x0);
    sort_stable_by_key(&mut corners, |p| total_order_key(p.value));
    let lowest = match corners.as_slice() {
        [p, q, ..] => [*p, *q],
        _ => return Err(Error::invalid("chen-9: the star has fewer than two corners")),
    };
    let tie = lowest[0].elem == lowest[1].elem && (lowest[0].value - lowest[1].value).abs() <= 1e-9 * lowest[0].value.abs().max(1.0);
    let el = &star.elems[lowest[0].elem as usize];
    let at = |t: &CornerTerm| el.pts[t.corner as usize];
    let is_end = |p: DVec2| (p - a).length() < 1e-12 || (p - b).length() < 1e-12;
    let on_curve = tie && is_end(at(&lowest[0])) && is_end(at(&lowest[1]));
    // the ascent's direction at the start, as the solver finds it
    let obj = pg.panel(Side::A).objective.as_ref();
    let mut terms = Vec::new();
    obj.terms(&star, star.x0, &mut terms);
    let phi = terms.iter().map(|t| t.value).fold(f64::INFINITY, f64::min);
    let scale = terms.iter().map(|t| t.value.abs()).fold(0.0f64, f64::max);
    let tol = pg.settings().smooth_options()?.solve_options().active_tolerance * scale;
    let active: Vec<DVec2> = terms.iter().filter(|t| t.value <= phi + tol).map(|t| t.grad).collect();
    let tried = min_norm_point(&active).point;
    let d = tried.normalize_or_zero();
    let tried_rate = lowest[0].grad.dot(d).min(lowest[1].grad.dot(d));
    let rise = min_norm_point(&[lowest[0].grad, lowest[1].grad]).point;
    Ok(Chen9 { ends: (a, b), meet, old, new, old_best, new_best, lowest, tie, on_curve, tried, tried_rate, rise })
}

pub(super) fn chen_9(c: Canvas, t: &Theme) -> Result<Vec<Pixmap>> {
    let n = chen_9_numbers()?;
    let (pg, node) = figure_state("chen-9", t)?;
    // each tangent from its end through the meeting point and half as far again
    let (a, b) = n.ends;
    let ta = [a, n.meet + 0.5 * (n.meet - a)];
    let tb = [b, n.meet + 0.5 * (n.meet - b)];
    let tangents = |label| {
        [
            Overlay::Line { points: &ta, color: rgb(TANGENT), dashed: true, label },
            Overlay::Line { points: &tb, color: rgb(TANGENT), dashed: true, label: "" },
            Overlay::Point { at: n.meet, marker: Marker::Diamond, color: rgb(TANGENT), label: "where they meet" },
        ]
    };
    // the arrows a fifth of the shown box long
    let (_, shown) = pg.level_bounds(Side::A, node);
    let len = 0.2 * (shown.1 - shown.0).x;
    let x0 = n.old.x0;
    let mut old_marks = tangents("end tangents (the paper's dashed lines)").to_vec();
    old_marks.push(Overlay::Point { at: n.old_best.0, marker: Marker::Star, color: rgb(OPTIMUM), label: "optimum, found by search" });
    if n.old.iterations == 0 && n.tie {
        old_marks.push(Overlay::Arrow { from: x0, to: x0 + len * n.tried.normalize_or_zero(), color: rgb(TRIED), label: "the ascent's direction: one tied corner's gradient" });
        old_marks.push(Overlay::Arrow { from: x0, to: x0 + len * n.rise.normalize_or_zero(), color: rgb(RISE), label: "both tied corners rise" });
    }
    let mut new_marks = tangents("end tangents (the paper's dashed lines)").to_vec();
    new_marks.push(Overlay::Point { at: n.new_best.0, marker: Marker::Star, color: rgb(OPTIMUM), label: "optimum, found by search" });
    let old = side_panel(&pg, node, c, &SidePanel { side: Side::A, solve: &n.old, optimum: None, overlays: &old_marks, feasible_levels: None, bounds: None })?;
    let new = side_panel(&pg, node, c, &SidePanel { side: Side::B, solve: &n.new, optimum: None, overlays: &new_marks, feasible_levels: None, bounds: None })?;
    Ok(vec![old, new])
}

pub(crate) fn chen_9_measured() -> Result<String> {
    let n = chen_9_numbers()?;
    let side = |y: f64| if y < n.meet.y { "below" } else { "above" };
    let mut s = format!(
        "Measured: the dashed lines meet at y = {:.3}. The new objective's solver ends at y = {:.3} after {} iterations, \
         where a search of the feasible region finds its optimum (y = {:.3}), {} the meeting point. The max-min α's \
         optimum lies at y = {:.3} (α = {:.3}), {} it too",
        n.meet.y,
        n.new.x.y,
        n.new.iterations,
        n.new_best.0.y,
        side(n.new_best.0.y),
        n.old_best.0.y,
        n.old_best.1,
        side(n.old_best.0.y),
    );
    if n.old.iterations == 0 && n.tie {
        let which = if n.on_curve { "the curved edge's ends" } else { "two corners" };
        s += &format!(
            ", but Freitag's ascent stays at the start ({} iterations: {}): there the worst element's corners at {which} \
             tie at α = {:.3}, a kink; the ascent follows one corner's gradient, ({:.2}, {:.2}), along which the other's α \
             falls ({:.2} per unit length), so no step raises the minimum. Both corners rise together along ({:.2}, {:.2}).",
            n.old.iterations,
            stop_words(n.old.stop),
            n.lowest[0].value,
            tidy(n.tried.x),
            tidy(n.tried.y),
            n.tried_rate,
            tidy(n.rise.x),
            tidy(n.rise.y),
        );
    } else {
        s += &format!("; Freitag's ascent reaches y = {:.3} in {} iterations ({}).", n.old.x.y, n.old.iterations, stop_words(n.old.stop));
    }
    Ok(s)
}

/// `v` rounded to two decimals, without a minus sign on a zero.
fn tidy(v: f64) -> f64 {
    (v * 100.0).round() / 100.0 + 0.0
}

// ---- Fig. 10: a star-shaped configuration -----------------------------------------------

/// Levels inside the feasible region on each side of Fig. 10: enough lines there for the
/// max-min side's kinks and the new side's smooth curves to show.
pub const CHEN_10_LEVELS: usize = 24;

pub(super) fn chen_10(c: Canvas, t: &Theme) -> Result<Vec<Pixmap>> {
    let (pg, node) = figure_state("chen-10", t)?;
    [Side::A, Side::B]
        .iter()
        .map(|&side| {
            let r = pg.solve_node(side, node)?;
            side_panel(&pg, node, c, &SidePanel { side, solve: &r, optimum: Some(r.x), overlays: &[], feasible_levels: Some(CHEN_10_LEVELS), bounds: None })
        })
        .collect()
}

pub(crate) fn chen_10_measured() -> Result<String> {
    let (pg, node) = figure_state("chen-10", &Theme::light())?;
    let (old, new) = (pg.solve_node(Side::A, node)?, pg.solve_node(Side::B, node)?);
    Ok(format!(
        "Measured at this node (20 iterations at most): the max-min objective takes {} iterations ({}), the new one {} \
         ({}); on Mesquite's equil_tri the new objective needs {} solver iterations where max-min α needs {} \
         (docs/reproduction.md §5).",
        old.iterations,
        stop_words(old.stop),
        new.iterations,
        stop_words(new.stop),
        repro(5, &["equil_tri.vtk", "`new`"], "solver iterations")?,
        repro(5, &["equil_tri.vtk", "`old`"], "solver iterations")?,
    ))
}

// ---- Figs. 11–12: one solve's history ----------------------------------------------------

/// The letter a step is marked with in the text: g, c, a or n.
pub(crate) fn letter(d: DirectionKind) -> &'static str {
    match d {
        DirectionKind::Gradient => "g",
        DirectionKind::Conjugate => "c",
        DirectionKind::ActiveSet => "a",
        DirectionKind::Newton => "n",
    }
}

/// The legend's words for a step's mark.
fn mark_label(d: DirectionKind) -> &'static str {
    match d {
        DirectionKind::Gradient => "g: gradient step",
        DirectionKind::Conjugate => "c: conjugate step",
        DirectionKind::ActiveSet => "a: active-set step",
        DirectionKind::Newton => "n: Newton step",
    }
}

/// Figs. 11–12's two solves of the new objective at the figure's node: Chen's search
/// alone (Fletcher–Reeves, no Newton step: the paper's iteration) and our default, with
/// Newton's step tried first.
pub(crate) struct Chen11 {
    pub chen: SolveResult,
    pub newton: SolveResult,
}

fn chen_11_solves(pg: &Playground, node: usize) -> Result<Chen11> {
    let options = pg.settings().smooth_options()?.with_newton(false);
    let p = pg.panel(Side::B);
    let chen = smoothlab::smooth::solve_node(&p.mesh, node, p.objective.as_ref(), &options)?;
    Ok(Chen11 { chen, newton: pg.solve_node(Side::B, node)? })
}

pub(crate) fn chen_11_numbers() -> Result<Chen11> {
    let (pg, node) = figure_state("chen-11", &Theme::light())?;
    chen_11_solves(&pg, node)
}

/// The share of a solve's whole decrease made by the start of each iteration, percent
/// (iteration 0: the start, 0 %; the last: 100 %).
fn decrease_shares(r: &SolveResult) -> Vec<DVec2> {
    let total = r.value0 - r.value;
    let share = |v: f64| if total > 0.0 { 100.0 * (r.value0 - v) / total } else { 100.0 };
    std::iter::once(DVec2::new(0.0, 0.0)).chain(r.history.iter().enumerate().map(|(i, it)| DVec2::new(i as f64 + 1.0, share(it.value)))).collect()
}

/// One solve's chart: the length of each iteration's step on a log axis (Chen et al.'s
/// claim is about them: a short gradient step, a much longer conjugate one, a restart),
/// every step marked by its kind (the level-set path's mark and colour), the count of
/// iterations in its title.
fn history_chart(pm: &mut Pixmap, r: &SolveResult, title: &str, frame: Frame, c: Canvas, t: &Theme) {
    let line: Vec<DVec2> = r.history.iter().enumerate().map(|(i, it)| DVec2::new(i as f64 + 1.0, it.step)).collect();
    // each kind's points apart (NaN between them: no line joins the marks)
    let kinds = [DirectionKind::Gradient, DirectionKind::Conjugate, DirectionKind::Newton, DirectionKind::ActiveSet];
    let marks: Vec<(DirectionKind, Vec<DVec2>)> = kinds
        .iter()
        .map(|&k| {
            let pts = r.history.iter().zip(&line).filter(|(it, _)| it.direction == k).flat_map(|(_, p)| [*p, DVec2::NAN]).collect();
            (k, pts)
        })
        .filter(|(_, p): &(DirectionKind, Vec<DVec2>)| !p.is_empty())
        .collect();
    let mut series = vec![Series::new("", &line).with_color(t.side(Side::B as usize))];
    for (k, pts) in &marks {
        let kind = path_kind(*k);
        series.push(Series::new(mark_label(*k), pts).with_color(kind.color()).with_marker(kind.marker()));
    }
    render_chart(
        pm,
        &series,
        &Chart {
            title,
            x_label: "iteration",
            y_label: "step length",
            log_y: true,
            dpr: c.dpr,
            frame: Some(frame),
            theme: *t,
            ..Chart::default()
        },
    );
}

/// The title of a solve's chart: what ran and how many iterations it took.
fn history_title(what: &str, r: &SolveResult) -> String {
    format!("{what}: {} iterations", r.iterations)
}

/// A square box round a solve's path (its start and every step), the path taking about
/// the middle half of it.
fn path_box(r: &SolveResult) -> (DVec2, DVec2) {
    let pts: Vec<DVec2> = std::iter::once(r.x0).chain(r.history.iter().map(|it| it.x)).collect();
    let (lo, hi) = pts.iter().fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(l, h), &p| (l.min(p), h.max(p)));
    let half = ((hi - lo).max_element() * 1.0).max(1e-6);
    let mid = 0.5 * (lo + hi);
    (mid - DVec2::splat(half), mid + DVec2::splat(half))
}

/// The height, CSS pixels, of the smallest step-length chart that keeps its ticks apart.
const TWO_CHARTS_MIN_CSS_H: f32 = 200.0;

pub(super) fn chen_11(c: Canvas, t: &Theme) -> Result<Vec<Pixmap>> {
    let (pg, node) = figure_state("chen-11", t)?;
    let s = chen_11_solves(&pg, node)?;
    // framed on the path, not the feasible region (where its steps are a few pixels):
    // each step's length and mark are seen, the conjugate step's against the gradient's
    let bounds = Some(path_box(&s.chen));
    let level = side_panel(&pg, node, c, &SidePanel { side: Side::B, solve: &s.chen, optimum: Some(s.chen.x), overlays: &[], feasible_levels: None, bounds })?;
    let mut chart = pixmap(c.w, c.h)?;
    let full = Frame::of_pixmap(&chart, c.dpr);
    // two charts one above the other need room for two sets of ticks: a short panel
    // shows Chen's search alone, the one the claim is about
    if full.h >= 2.0 * TWO_CHARTS_MIN_CSS_H {
        history_chart(&mut chart, &s.chen, &history_title(CHEN_SEARCH, &s.chen), full.row(0, 2, 6.0), c, t);
        history_chart(&mut chart, &s.newton, &history_title(NEWTON_FIRST, &s.newton), full.row(1, 2, 6.0), c, t);
    } else {
        history_chart(&mut chart, &s.chen, &history_title(CHEN_SEARCH, &s.chen), full, c, t);
    }
    Ok(vec![level, chart])
}

/// A step's length as the text writes it: four decimals, or two significant digits of a
/// power of ten below a thousandth (the chart's log axis shows them apart).
fn step_words(step: f64) -> String {
    if step >= 1e-3 {
        format!("{step:.4}")
    } else {
        format!("{step:.1e}")
    }
}

const CHEN_SEARCH: &str = "Chen's search alone";
const NEWTON_FIRST: &str = "Newton's step first";

pub(crate) fn chen_11_measured() -> Result<String> {
    let s = chen_11_numbers()?;
    let steps = |r: &SolveResult| -> String { r.history.iter().map(|it| format!("{} {}", letter(it.direction), step_words(it.step))).collect::<Vec<_>>().join(", ") };
    let share = |r: &SolveResult| decrease_shares(r).get(3).map_or(100.0, |p| p.y);
    let ratio = match s.chen.history.as_slice() {
        [a, b, ..] if a.step > 0.0 => b.step / a.step,
        _ => f64::NAN,
    };
    Ok(format!(
        "Measured: {CHEN_SEARCH} (no Newton step; the path drawn) takes {} iterations, their steps by mark and length: {}. The \
         first conjugate step is {ratio:.1} times the gradient step before it, and our solver restarts with the \
         gradient every second iteration (Chen et al. restart when progress slows); the first three iterations make \
         {:.1}% of the decrease. {NEWTON_FIRST} (our default): {} iterations, {}; the first three make {:.1}% of the decrease.",
        s.chen.iterations,
        steps(&s.chen),
        share(&s.chen),
        s.newton.iterations,
        steps(&s.newton),
        share(&s.newton),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use smoothlab_render::layout::{record, RegionKind};

    /// The legend rule (issue 28): in every figure of the tour, in both themes and at the
    /// sizes the page and its embeds draw them, no legend or colour bar lies over a plot.
    #[test]
    fn no_legend_of_any_figure_lies_over_its_data() {
        use crate::lab::tour::{pictures, FIGURES};
        for f in &FIGURES {
            let (w, h) = pictures::default_size(f.name);
            // as `smoothlab render` draws it, and as the page's 800 × 450 and 520 × 520 embeds
            // do (labels of at least 14 CSS px; the picture fitted to the frame's width)
            let fit = |css_w: u32, dpr: f32| {
                let css_h = css_w * h / w;
                Canvas { w: (css_w as f32 * dpr) as u32, h: (css_h as f32 * dpr) as u32, dpr }
            };
            for (c, theme) in [(Canvas { w, h, dpr: 1.0 }, Theme::light()), (fit(780, 1.0), Theme::for_page(true, 14.0)), (fit(500, 2.0), Theme::for_page(false, 14.0))] {
                let (pm, regions) = pictures::render_with_layout(f.name, c, &theme).unwrap_or_else(|e| panic!("{}: {e}", f.name));
                let of = |k: RegionKind| regions.iter().filter(move |r| r.kind == k);
                assert!(of(RegionKind::Plot).count() > 0 || of(RegionKind::Legend).count() == 0, "{}: a legend and no plot", f.name);
                for l in of(RegionKind::Legend) {
                    assert!(l.x >= -0.5 && l.y >= -0.5 && l.x + l.w <= pm.width() as f32 + 0.5 && l.y + l.h <= pm.height() as f32 + 0.5, "{}: legend {l:?} outside the picture", f.name);
                    for p in of(RegionKind::Plot) {
                        assert!(!l.overlaps(p), "{} at {c:?}: legend {l:?} over plot {p:?}", f.name);
                    }
                }
            }
        }
    }

    #[test]
    fn chen_9_optima_lie_below_the_meeting_point_and_the_kink_is_computed() {
        let n = chen_9_numbers().unwrap();
        let h = smoothlab::generate::PUSHED_MID_HEIGHT;
        assert!((n.meet - DVec2::new(0.0, 2.0 * h - 3f64.sqrt() / 2.0)).length() < 1e-12, "{}", n.meet);
        assert!(n.new_best.0.y < n.meet.y && n.old_best.0.y < n.meet.y);
        // the new objective's solver ends at its optimum; the max-min optimum is better
        // than the start by the objective's own measure
        assert!((n.new.x - n.new_best.0).length() < 1e-3, "{} vs {}", n.new.x, n.new_best.0);
        assert!(n.old_best.1 > n.old.value + 0.1, "{} vs {}", n.old_best.1, n.old.value);
        // the start is a kink: two corners of one element tie, the ascent's direction
        // lowers one of them, and the hull of both points straight down
        assert!(n.tie && n.on_curve && n.old.iterations == 0);
        assert!(n.tried_rate < 0.0 && n.rise.y < 0.0 && n.rise.x.abs() < 1e-9, "{} {}", n.tried_rate, n.rise);
        let text = chen_9_measured().unwrap();
        for v in [n.meet.y, n.new.x.y, n.old_best.0.y, n.lowest[0].value] {
            assert!(text.contains(&format!("{v:.3}")), "{v:.3} not in: {text}");
        }
    }

    #[test]
    fn chen_10_frames_the_feasible_region_and_spends_its_levels_there() {
        let (pg, node) = figure_state("chen-10", &Theme::light()).unwrap();
        for side in [Side::A, Side::B] {
            let mut star = Star::new();
            star.gather(&pg.panel(side).mesh, node);
            let (_, b) = pg.level_bounds(side, node);
            let f = sample_field(pg.panel(side).objective.as_ref(), &star, b, 81, 81).unwrap();
            let inside = f.validity.iter().filter(|v| **v > 0.0).count() as f64 / f.validity.len() as f64;
            assert!(inside > 0.4, "{side:?}: the feasible region is {:.0}% of the picture", 100.0 * inside);
            let levels = feasible_levels(&f, CHEN_10_LEVELS);
            let (lo, hi) = f.values.iter().zip(&f.validity).filter(|(v, ok)| v.is_finite() && **ok > 0.0).fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), (v, _)| (a.min(*v), b.max(*v)));
            assert!(levels.len() >= CHEN_10_LEVELS - 2 && levels.iter().all(|l| (lo..=hi).contains(l)), "{side:?}: {levels:?}");
        }
    }

    #[test]
    fn chen_11_marks_every_step_and_the_text_counts_them() {
        let s = chen_11_numbers().unwrap();
        let c = Canvas { w: 1100, h: 560, dpr: 1.0 };
        let (parts, notes) = record(|| chen_11(c, &Theme::light()).unwrap());
        let marks = notes.of(&parts[1]).into_iter().filter(|r| r.kind == RegionKind::Mark).collect::<Vec<_>>();
        let text = chen_11_measured().unwrap();
        for (k, r) in [(DirectionKind::Gradient, &s.chen), (DirectionKind::Conjugate, &s.chen), (DirectionKind::Newton, &s.newton)] {
            let u = path_kind(k).color().to_color_u8();
            let drawn = marks.iter().filter(|m| m.rgb == Some([u.red(), u.green(), u.blue()])).count();
            let steps = r.history.iter().filter(|it| it.direction == k).count();
            assert_eq!(drawn, steps, "{k:?}");
            assert!(steps > 0, "{k:?}: Fig. 11 is about this step");
        }
        assert!(text.contains(&format!("takes {} iterations", s.chen.iterations)) && text.contains(&format!("default): {} iterations", s.newton.iterations)), "{text}");
        // every step in the text, with its mark: "g 0.0050, c 0.0100, …"
        let marked = text
            .split([',', ':', ';'])
            .filter(|w| {
                let mut words = w.split_whitespace();
                let (mark, n) = (words.next(), words.next().map(|n| n.trim_end_matches('.')));
                matches!(mark, Some("g" | "c" | "n")) && n.is_some_and(|n| n.parse::<f64>().is_ok())
            })
            .count();
        assert_eq!(marked, s.chen.history.len() + s.newton.history.len(), "{text}");
    }
}
