//! The pictures of `smoothlab render IN --view …` of a mesh as a [`Model`] holds it, drawn
//! by the lab and the render crate: the command-line tool and the Python package
//! (`smoothlab.render`) both call [`draw`], so they draw the same pixels. Messages name
//! the options by `flag` (the tool's `--node`, Python's `node`).

use tiny_skia::{Pixmap, PixmapPaint, Transform};

use smoothlab::model::Model;
use smoothlab::objective::{objective_with, solid_objective, ObjectiveKind, Penalty};
use smoothlab::quality::mesh_stats;
use smoothlab::smooth::limits::RENDER_PASSES;
use smoothlab::smooth::{
    smooth, Order, SmoothOptions, Strategy, DEFAULT_MAX_ITER, DEFAULT_PASSES, DEFAULT_THRESHOLD_DEG,
};
use smoothlab::surface::{Surface, SurfaceSmoother};
use smoothlab::volume::{smooth_volume, volume_stats, VolumeMesh};
use smoothlab::Mesh;
use smoothlab_render::{
    render_angle_histogram, render_mesh, AngleHistogram, Camera, Cut, HistogramSeries, MeshView,
    Metric, SurfacePicture, SurfaceView, Theme, VolumePicture,
};

use super::pick::worst_free_node;
use super::views::{pixmap, Canvas};
use super::{Choice, Playground, Settings, Side, MAX_NODES};

smoothlab::enum_with_names! {
    /// What `render` draws.
    #[derive(Clone, Copy, Debug, PartialEq, Eq)]
    pub enum View {
        Mesh => ("mesh", "the mesh coloured by quality (after the passes, default 0, of one objective)"),
        Levelset => ("levelset", "level sets of a node's objective, old and new side by side, with the solver's path"),
        History => ("history", "convergence: per-pass curves of old vs new, or with a node one node's solve history"),
        Histogram => ("histogram", "angle histograms (6° bins): as loaded, old, new and plain Laplacian"),
        Compare => ("compare", "old on the left, new on the right, after the passes, with their statistics"),
    }
}

/// What to draw and how: the options of `smoothlab render`.
#[derive(Clone, Debug, PartialEq)]
pub struct Request {
    pub view: View,
    /// The node to study (0-based); `None`: the free node with the worst star.
    pub node: Option<usize>,
    /// The objectives shown: old (A), new (B) or both, in this order.
    pub sides: Vec<Side>,
    pub metric: Metric,
    /// Width and height in CSS pixels; `None`: the view's own.
    pub size: Option<(u32, u32)>,
    pub dpr: f32,
    pub strategy: Strategy,
    pub threshold_deg: f64,
    /// Passes before drawing; `None`: 0 for mesh and levelset, 3 otherwise.
    pub passes: Option<u32>,
    pub order: Order,
    pub max_iter: u32,
    pub penalty: Penalty,
    pub camera: Option<Camera>,
    pub cut: Option<Cut>,
    pub theme: Theme,
}

impl Default for Request {
    /// `smoothlab render`'s defaults: compare, old and new.
    fn default() -> Self {
        Request {
            view: View::Compare,
            node: None,
            sides: Side::BOTH.to_vec(),
            metric: Metric::default(),
            size: None,
            dpr: 1.0,
            strategy: SmoothOptions::default().strategy,
            threshold_deg: DEFAULT_THRESHOLD_DEG,
            passes: None,
            order: Order::Priority,
            max_iter: DEFAULT_MAX_ITER,
            penalty: Penalty::Barrier,
            camera: None,
            cut: None,
            theme: Theme::light(),
        }
    }
}

/// The sides `old`, `new` or `old,new` name, or why not (`flag` names the option).
pub fn sides(spec: &str, flag: &dyn Fn(&str) -> String) -> Result<Vec<Side>, String> {
    let mut out = Vec::new();
    for part in spec.split(',').map(str::trim) {
        let side = match part {
            "old" => Side::A,
            "new" => Side::B,
            other => {
                return Err(format!(
                    "{} {other}: the pictures compare the old max-min objective and the new smooth one; \
                     give old, new or old,new (smooth with other objectives using `smoothlab smooth`)",
                    flag("objective")
                ))
            }
        };
        if !out.contains(&side) {
            out.push(side);
        }
    }
    Ok(out)
}

impl Request {
    fn settings(&self) -> Settings {
        Settings {
            strategy: self.strategy,
            threshold_deg: self.threshold_deg,
            order: self.order,
            max_iter: self.max_iter,
            target: smoothlab::target::Target::Ideal,
            boundary: smoothlab::volume::BoundaryRule::Fixed,
            compare: [
                Choice::OLD,
                Choice {
                    penalty: self.penalty,
                    ..Choice::NEW
                },
            ],
        }
    }
    fn size_or(&self, default: (u32, u32)) -> (u32, u32) {
        self.size.unwrap_or(default)
    }
    fn canvas(&self, w: u32, h: u32) -> Canvas {
        Canvas {
            w: ((w as f32) * self.dpr) as u32,
            h: ((h as f32) * self.dpr) as u32,
            dpr: self.dpr,
        }
    }
}

/// Places `parts` side by side on one picture of `theme`'s paper.
fn side_by_side(parts: &[Pixmap], theme: &Theme) -> Result<Pixmap, String> {
    let w = parts.iter().map(|p| p.width()).sum();
    let h = parts.iter().map(|p| p.height()).max().unwrap_or(1);
    let mut out = pixmap(w, h).map_err(|e| e.to_string())?;
    out.fill(theme.paper);
    let mut x = 0;
    for p in parts {
        out.draw_pixmap(
            x as i32,
            0,
            p.as_ref(),
            &PixmapPaint::default(),
            Transform::identity(),
            None,
        );
        x += p.width();
    }
    Ok(out)
}

fn no_such_node(n: usize, count: usize, flag: &dyn Fn(&str) -> String) -> String {
    format!(
        "{} {n}: the mesh has nodes 0 to {}",
        flag("node"),
        count.saturating_sub(1)
    )
}

/// Draws `model` (read from `name`, for messages) as `r` asks; `clock` times the planar
/// passes (milliseconds); `flag` names an option in messages.
pub fn draw(
    model: Model,
    name: &str,
    r: &Request,
    clock: &dyn Fn() -> f64,
    flag: &dyn Fn(&str) -> String,
) -> Result<Pixmap, String> {
    if r.sides.is_empty() {
        return Err(format!("{}: give old, new or old,new", flag("objective")));
    }
    if !(r.dpr.is_finite() && r.dpr > 0.0 && r.dpr <= 4.0) {
        return Err(format!(
            "{} {}: give a ratio above 0 and at most 4",
            flag("dpr"),
            r.dpr
        ));
    }
    let passes = r.passes.unwrap_or(match r.view {
        View::Mesh | View::Levelset => 0,
        _ => DEFAULT_PASSES,
    });
    if !RENDER_PASSES.contains(passes.into()) {
        return Err(format!(
            "{} {passes}: give at most {}",
            flag("passes"),
            RENDER_PASSES.max
        ));
    }
    let mesh = match model {
        Model::Planar(mesh) => {
            if r.camera.is_some() {
                return Err(format!(
                    "{} turns the 3D view of a surface; this mesh is planar",
                    flag("camera")
                ));
            }
            mesh
        }
        Model::Surface(s) => return surface(r, name, s, passes, flag),
        Model::Volume(v) => return volume(r, name, v, passes, flag),
    };
    if r.cut.is_some() {
        return Err(format!(
            "{} cuts a volume mesh; this mesh is planar",
            flag("cut")
        ));
    }
    // The pictures are drawn by the page's code, which holds at most MAX_NODES nodes: said
    // in the caller's words, with the file's name.
    if mesh.node_count() > MAX_NODES {
        return Err(format!(
            "{name}: the mesh has {} nodes; render draws meshes of at most {MAX_NODES} nodes \
             (stats, smooth and convert take larger ones)",
            mesh.node_count()
        ));
    }
    // a node that does not exist is refused by every view, not only the ones that use it
    if let Some(n) = r.node.filter(|&n| n >= mesh.node_count()) {
        return Err(no_such_node(n, mesh.node_count(), flag));
    }
    let original = mesh.clone();
    let mut lab = Playground::new(mesh).map_err(|e| e.to_string())?;
    lab.set_settings(r.settings()).map_err(|e| e.to_string())?;
    let theme = r.theme;
    lab.set_theme(theme);
    for _ in 0..passes {
        lab.step(clock);
    }
    let (w, h) = r.size_or(match r.view {
        View::Mesh => (900, 800),
        View::Levelset => (if r.sides.len() == 2 { 1100 } else { 560 }, 560),
        View::History => (1000, 640),
        View::Histogram => (900, 520),
        View::Compare => (1400, 780),
    });
    let first = r.sides[0];
    let node = |side: Side| -> Result<usize, String> {
        let m = &lab.panel(side).mesh;
        match r.node {
            Some(n) if n < m.node_count() && m.is_free(n) => Ok(n),
            Some(n) if n < m.node_count() => Err(format!(
                "{} {n} is not a free corner node: it never moves, so it has no objective to draw",
                flag("node")
            )),
            Some(n) => Err(no_such_node(n, m.node_count(), flag)),
            None => {
                worst_free_node(m).ok_or_else(|| "the mesh has no free node to study".to_string())
            }
        }
    };
    Ok(match r.view {
        View::Mesh => {
            let c = r.canvas(w, h);
            let mut pm = pixmap(c.w, c.h).map_err(|e| e.to_string())?;
            let mut view = MeshView::default().with_dpr(r.dpr).with_highlight(r.node);
            view.metric = r.metric;
            view.theme = theme;
            render_mesh(&mut pm, &lab.panel(first).mesh, &view);
            pm
        }
        View::Levelset => {
            let n = node(first)?;
            let each = r.canvas(w / r.sides.len() as u32, h);
            let mut parts = Vec::new();
            for &side in &r.sides {
                parts.push(
                    lab.render_level_set(side, n, each)
                        .map_err(|e| e.to_string())?
                        .0,
                );
            }
            side_by_side(&parts, &theme)?
        }
        View::History => match r.node {
            Some(_) => {
                let n = node(first)?;
                // the node view's third picture is its solve history (both objectives)
                let ([_, _, chart], _) = lab
                    .render_node_view(n, r.canvas(64, 64), r.canvas(w, h))
                    .map_err(|e| e.to_string())?;
                chart
            }
            None => lab
                .render_pass_chart(r.canvas(w, h))
                .map_err(|e| e.to_string())?,
        },
        View::Histogram => {
            let as_loaded = mesh_stats(&original).angle_histogram_6deg;
            let mut laplace: Mesh = original.clone();
            let opts = SmoothOptions::default().with_strategy(Strategy::Laplace);
            let objective = objective_with(ObjectiveKind::SmoothShape, r.penalty);
            smooth(&mut laplace, objective.as_ref(), opts, passes, &|| 0.0)
                .map_err(|e| e.to_string())?;
            let lap = mesh_stats(&laplace).angle_histogram_6deg;
            let old = lab.stats(Side::A).mesh.angle_histogram_6deg;
            let new = lab.stats(Side::B).mesh.angle_histogram_6deg;
            let mut series = vec![HistogramSeries {
                label: "as loaded",
                counts: &as_loaded,
                color: None,
            }];
            for &side in &r.sides {
                series.push(match side {
                    Side::A => HistogramSeries {
                        label: "old (max-min)",
                        counts: &old,
                        color: Some(theme.side(0)),
                    },
                    Side::B => HistogramSeries {
                        label: "new (Chen et al.)",
                        counts: &new,
                        color: Some(theme.side(1)),
                    },
                });
            }
            series.push(HistogramSeries {
                label: "Laplacian",
                counts: &lap,
                color: None,
            });
            let c = r.canvas(w, h);
            let mut pm = pixmap(c.w, c.h).map_err(|e| e.to_string())?;
            let title = format!("Corner angles (6° bins) after {passes} passes");
            render_angle_histogram(
                &mut pm,
                &series,
                &AngleHistogram {
                    title: &title,
                    dpr: r.dpr,
                    theme,
                    ..AngleHistogram::default()
                },
            )
            .map_err(|e| e.to_string())?;
            pm
        }
        View::Compare => {
            if r.sides.len() != 2 {
                return Err(format!(
                    "{} compare shows both objectives: use {} old,new",
                    flag("view"),
                    flag("objective")
                ));
            }
            lab.render_figure(r.canvas(w, h))
                .map_err(|e| e.to_string())?
        }
    })
}

/// `mesh` or `compare` of a surface, in the 3D view: as loaded (or after the passes of the
/// first objective asked for), or old and new side by side after the passes, with the
/// lab's settings (strategy, order, iterations, the new objective's penalty); `levelset`:
/// a node's star in its tangent plane.
fn surface(
    r: &Request,
    name: &str,
    s: Surface,
    passes: u32,
    flag: &dyn Fn(&str) -> String,
) -> Result<Pixmap, String> {
    if s.node_count() > MAX_NODES {
        return Err(format!(
            "{name}: the mesh has {} nodes; render draws meshes of at most {MAX_NODES} nodes",
            s.node_count()
        ));
    }
    let sides: Vec<Side> = match r.view {
        View::Mesh => vec![r.sides[0]],
        View::Compare if r.sides.len() == 2 => r.sides.clone(),
        View::Compare => {
            return Err(format!(
                "{} compare shows both objectives: use {} old,new",
                flag("view"),
                flag("objective")
            ))
        }
        View::Levelset => return surface_level_sets(r, &s, passes, flag),
        other => {
            return Err(format!(
                "{} {}: a surface is drawn by {} mesh, compare or levelset",
                flag("view"),
                other.name(),
                flag("view")
            ))
        }
    };
    let settings = r.settings();
    settings.smooth_options().map_err(|e| e.to_string())?;
    let camera = r.camera.unwrap_or_default();
    let (w, h) = r.size_or(if sides.len() == 2 {
        (1400, 760)
    } else {
        (900, 800)
    });
    let each = w / sides.len() as u32;
    let mut parts = Vec::new();
    for side in sides {
        let mut t = s.clone();
        let choice = settings.compare[side as usize];
        let objective = choice.build();
        let opts = settings.side_options(side, crate::lab::settings::RunStart::of(&s.stats())).map_err(|e| e.to_string())?;
        let mut smoother = SurfaceSmoother::new(opts).map_err(|e| e.to_string())?;
        for _ in 0..passes {
            smoother.pass(&mut t, objective.as_ref(), &|| 0.0);
        }
        let st = t.stats();
        let when = match passes {
            0 => "as loaded".to_string(),
            1 => format!("{}: {} after 1 pass", side.letter(), choice.label()),
            n => format!("{}: {} after {n} passes", side.letter(), choice.label()),
        };
        let title = format!(
            "{when}: {} inverted, angles {:.1}°–{:.1}°",
            st.inverted, st.min_angle_deg, st.max_angle_deg
        );
        let mut pm = pixmap(((each as f32) * r.dpr) as u32, ((h as f32) * r.dpr) as u32)
            .map_err(|e| e.to_string())?;
        let view = SurfaceView {
            camera,
            dpr: r.dpr,
            title: Some(title),
            theme: r.theme,
            ..SurfaceView::default()
        };
        t.render(&mut pm, r.metric, &view);
        parts.push(pm);
    }
    side_by_side(&parts, &r.theme)
}

/// A volume mesh, cut and drawn in the 3D view: `mesh` (as loaded, or after the passes
/// of the first objective asked for), `compare` (old and new side by side after the
/// passes) or `histogram` (the dihedral angles, 6° bins: as loaded, old, new), with the
/// lab's strategy, order and iterations.
fn volume(
    r: &Request,
    name: &str,
    v: VolumeMesh,
    passes: u32,
    flag: &dyn Fn(&str) -> String,
) -> Result<Pixmap, String> {
    if v.node_count() > MAX_NODES {
        return Err(format!(
            "{name}: the mesh has {} nodes; render draws meshes of at most {MAX_NODES} nodes",
            v.node_count()
        ));
    }
    let cut = r.cut.unwrap_or_default();
    let camera = r.camera.unwrap_or_default();
    let sides: Vec<Side> = match r.view {
        View::Mesh => vec![r.sides[0]],
        View::Compare | View::Histogram if r.sides.len() == 2 => r.sides.clone(),
        View::Compare | View::Histogram => {
            return Err(format!(
                "{} compare and histogram show both objectives: use {} old,new",
                flag("view"),
                flag("objective")
            ))
        }
        other => {
            return Err(format!(
                "{} {}: a volume mesh is drawn by {} mesh, compare or histogram",
                flag("view"),
                other.name(),
                flag("view")
            ))
        }
    };
    let settings = r.settings();
    settings.smooth_options().map_err(|e| e.to_string())?;
    let mut smoothed = Vec::new();
    for &side in &sides {
        let opts = settings.side_options(side, crate::lab::settings::RunStart::of(&volume_stats(&v))).map_err(|e| e.to_string())?;
        let mut t = v.clone();
        let kind = settings.compare[side as usize].objective;
        smooth_volume(
            &mut t,
            &*solid_objective(kind).map_err(|e| e.to_string())?,
            opts,
            passes,
            &|| 0.0,
        )
        .map_err(|e| e.to_string())?;
        smoothed.push((side, kind, t));
    }
    if r.view == View::Histogram {
        let (w, h) = r.size_or((900, 520));
        let mut pm = pixmap(((w as f32) * r.dpr) as u32, ((h as f32) * r.dpr) as u32)
            .map_err(|e| e.to_string())?;
        let loaded = volume_stats(&v).angle_histogram_6deg;
        let counts: Vec<(String, Vec<u64>)> = smoothed
            .iter()
            .map(|(side, kind, t)| {
                (
                    format!("{}: {kind}", side.letter()),
                    volume_stats(t).angle_histogram_6deg,
                )
            })
            .collect();
        let mut series = vec![HistogramSeries {
            label: "as loaded",
            counts: &loaded,
            color: None,
        }];
        series.extend(counts.iter().map(|(l, c)| HistogramSeries {
            label: l,
            counts: c,
            color: None,
        }));
        let title = format!("Dihedral angles after {passes} passes");
        let opts = AngleHistogram {
            title: &title,
            dpr: r.dpr,
            theme: r.theme,
            ..AngleHistogram::default()
        };
        render_angle_histogram(&mut pm, &series, &opts).map_err(|e| e.to_string())?;
        return Ok(pm);
    }
    let (w, h) = r.size_or(if sides.len() == 2 {
        (1400, 760)
    } else {
        (900, 800)
    });
    let each = w / sides.len() as u32;
    let mut parts = Vec::new();
    for (side, kind, t) in &smoothed {
        let st = volume_stats(t);
        let when = match passes {
            0 => "as loaded".to_string(),
            1 => format!("{}: {kind} after 1 pass", side.letter()),
            n => format!("{}: {kind} after {n} passes", side.letter()),
        };
        let title = format!(
            "{when}: {} inverted, dihedral {:.1}°–{:.1}°",
            st.inverted, st.min_angle_deg, st.max_angle_deg
        );
        let mut pm = pixmap(((each as f32) * r.dpr) as u32, ((h as f32) * r.dpr) as u32)
            .map_err(|e| e.to_string())?;
        let view = SurfaceView {
            camera,
            dpr: r.dpr,
            title: Some(title),
            theme: r.theme,
            ..SurfaceView::default()
        };
        t.render_cut(&mut pm, cut, &view);
        parts.push(pm);
    }
    side_by_side(&parts, &r.theme)
}

/// `levelset` of a surface: the node's star flattened into its tangent plane, where the
/// drivers see it, with the planar view's level sets of each objective asked for.
fn surface_level_sets(
    r: &Request,
    s: &Surface,
    passes: u32,
    flag: &dyn Fn(&str) -> String,
) -> Result<Pixmap, String> {
    if passes > 0 {
        return Err(format!(
            "{} levelset of a surface draws the mesh as loaded: give no {}",
            flag("view"),
            flag("passes")
        ));
    }
    let node = match r.node {
        Some(n) => n,
        None => s
            .worst_free_node()
            .ok_or("the mesh has no free node to study")?,
    };
    let (star, n) = s
        .star_in_tangent_plane(node)
        .map_err(|e| format!("{} {node}: {e}", flag("node")))?;
    let mut lab = Playground::new(star).map_err(|e| e.to_string())?;
    lab.set_settings(r.settings()).map_err(|e| e.to_string())?;
    lab.set_theme(r.theme);
    let (w, h) = r.size_or((if r.sides.len() == 2 { 1100 } else { 560 }, 560));
    let each = Canvas {
        w: ((w / r.sides.len() as u32) as f32 * r.dpr) as u32,
        h: ((h as f32) * r.dpr) as u32,
        dpr: r.dpr,
    };
    let mut parts = Vec::new();
    for &side in &r.sides {
        parts.push(
            lab.render_level_set(side, n, each)
                .map_err(|e| e.to_string())?
                .0,
        );
    }
    side_by_side(&parts, &r.theme)
}
