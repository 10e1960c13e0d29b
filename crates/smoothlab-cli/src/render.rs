//! `smoothlab render IN -o OUT.png --view mesh|levelset|history|histogram|compare …`:
//! the page's pictures as PNG files, drawn by the same core code (`lab` and `render`).
//! `smoothlab render --figure NAME -o OUT.png`: a figure of the page's tour
//! (`lab::tour`), drawn from its own state (no input mesh).
//!
//! Node numbers are 0-based in file order, as everywhere in smoothlab.

use smoothlab_render::{SurfacePicture, VolumePicture};
use std::path::PathBuf;

use clap::{Args, ValueEnum};
use smoothlab_page::lab::pick::worst_free_node;
use smoothlab_page::lab::views::{pixmap, Canvas};
use smoothlab_page::lab::{Choice, Playground, Settings, Side, MAX_NODES};
use smoothlab::objective::tet_objective;
use smoothlab::quality::mesh_stats;
use smoothlab_render::{
    encode_png, render_angle_histogram, render_mesh, AngleHistogram, HistogramSeries, MeshView, Metric,
};
use smoothlab_render::{Camera, SurfaceView, Theme};
use smoothlab::smooth::limits::RENDER_PASSES;
use smoothlab::smooth::{smooth, SmoothOptions, Strategy};
use smoothlab::model::Model;
use smoothlab::surface::{Surface, SurfaceSmoother};
use smoothlab::volume::{smooth_volume, volume_stats, VolumeMesh};
use smoothlab_render::{Cut};
use smoothlab::Mesh;
use tiny_skia::{Pixmap, PixmapPaint, Transform};

use crate::args::{named, order_parser, penalty_parser, strategy_parser};

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ViewArg {
    /// The mesh coloured by quality (after --passes, default 0, of one objective)
    Mesh,
    /// Level sets of a node's objective, old and new side by side, with the solver's path
    Levelset,
    /// Convergence: per-pass curves of old vs new, or with --node one node's solve history
    History,
    /// Angle histograms (6° bins): as loaded, old, new and plain Laplacian
    Histogram,
    /// Old on the left, new on the right, after the passes, with their statistics
    Compare,
}

/// The colours a picture is drawn in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ThemeArg {
    /// Black on white, labels at their own sizes
    Light,
    /// For projectors: light ink on a dark paper, labels at least 14 px
    Dark,
}

impl ThemeArg {
    fn theme(self) -> Theme {
        match self {
            ThemeArg::Light => Theme::light(),
            ThemeArg::Dark => Theme::dark(),
        }
    }
}

#[derive(Args)]
pub struct RenderArgs {
    /// Input mesh (not with --figure)
    #[arg(required_unless_present = "figure", conflicts_with = "figure")]
    pub input: Option<PathBuf>,
    /// A figure of the papers, as the page's tour shows it: chen-2, chen-6, chen-9, chen-10,
    /// chen-11, chen-13, chen-16, chen-18, chen-20, freitag-t1, freitag-t2, freitag-3, knupp-1,
    /// knupp-hex (draws its own state; --size and --dpr apply)
    #[arg(long)]
    pub figure: Option<String>,
    /// Output PNG
    #[arg(short, long)]
    pub output: PathBuf,
    /// What to draw
    #[arg(long, value_enum, default_value = "compare")]
    pub view: ViewArg,
    /// Node to study (0-based, file order); default the free node with the worst star
    #[arg(long)]
    pub node: Option<usize>,
    /// Objectives to show: old, new, or old,new
    #[arg(long, default_value = "old,new")]
    pub objective: String,
    /// Metric that colours the elements
    #[arg(long, value_parser = named(&Metric::ALL, Metric::name, Metric::describe), default_value = Metric::default().name())]
    pub metric: Metric,
    /// Picture size in pixels, WxH (default by view)
    #[arg(long)]
    pub size: Option<String>,
    /// Device-pixel ratio (2 for sharp pictures on HiDPI screens and in print)
    #[arg(long, default_value_t = 1.0)]
    pub dpr: f32,
    /// Smoothing strategy
    #[arg(long, value_parser = strategy_parser(), default_value = smoothlab::smooth::SmoothOptions::default().strategy.name())]
    pub strategy: smoothlab::smooth::Strategy,
    /// Threshold angle of c1/c2/c3, degrees
    #[arg(long, default_value_t = smoothlab::smooth::DEFAULT_THRESHOLD_DEG)]
    pub threshold: f64,
    /// Smoothing passes before drawing (default 0 for mesh and levelset, 3 otherwise)
    #[arg(long)]
    pub passes: Option<u32>,
    /// Node order (default priority)
    #[arg(long, value_parser = order_parser(), default_value = "priority")]
    pub order: smoothlab::smooth::Order,
    /// Solver iterations per optimization call
    #[arg(long, default_value_t = smoothlab::smooth::DEFAULT_MAX_ITER)]
    pub max_iter: u32,
    /// Design of the new objective's penalty: barrier (the default) or angle (the first design)
    #[arg(long, value_parser = penalty_parser(), default_value = "barrier")]
    pub penalty: smoothlab::objective::Penalty,
    /// A surface's 3D view: yaw and pitch in degrees and a zoom factor, YAW,PITCH[,ZOOM]
    /// (default 30,25,1); --view mesh and compare draw surfaces
    #[arg(long, allow_hyphen_values = true)]
    pub camera: Option<String>,
    /// A volume mesh's cut plane, AXIS=FRACTION of its extent (default z=0.5): the
    /// elements beyond it are taken away, the faces it opens coloured by mean ratio
    #[arg(long)]
    pub cut: Option<String>,
    /// Colours: light (black on white) or dark (for projectors, with larger labels)
    #[arg(long, value_enum, default_value = "light")]
    pub theme: ThemeArg,
}

/// Which sides `--objective` asks for.
fn sides(spec: &str) -> Result<Vec<Side>, String> {
    let mut out = Vec::new();
    for part in spec.split(',').map(str::trim) {
        let side = match part {
            "old" => Side::A,
            "new" => Side::B,
            other => {
                return Err(format!(
                    "--objective {other}: the pictures compare the old max-min objective and the new smooth one; \
                     give old, new or old,new (smooth with other objectives using `smoothlab smooth`)"
                ))
            }
        };
        if !out.contains(&side) {
            out.push(side);
        }
    }
    Ok(out)
}

fn size(spec: Option<&str>, default: (u32, u32)) -> Result<(u32, u32), String> {
    let Some(s) = spec else { return Ok(default) };
    let bad = || format!("--size {s}: give WIDTHxHEIGHT in pixels, e.g. 1200x700");
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    Ok((w.trim().parse().map_err(|_| bad())?, h.trim().parse().map_err(|_| bad())?))
}

fn settings(a: &RenderArgs) -> Settings {
    Settings {
        strategy: a.strategy,
        threshold_deg: a.threshold,
        order: a.order,
        max_iter: a.max_iter,
        compare: [Choice::OLD, Choice { penalty: a.penalty, ..Choice::NEW }],
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
        out.draw_pixmap(x as i32, 0, p.as_ref(), &PixmapPaint::default(), Transform::identity(), None);
        x += p.width();
    }
    Ok(out)
}

fn no_such_node(n: usize, mesh: &Mesh) -> String {
    format!("--node {n}: the mesh has nodes 0 to {}", mesh.node_count().saturating_sub(1))
}

pub fn run(a: RenderArgs) -> Result<(), String> {
    let shown = sides(&a.objective)?;
    if !(a.dpr.is_finite() && a.dpr > 0.0 && a.dpr <= 4.0) {
        return Err(format!("--dpr {}: give a ratio above 0 and at most 4", a.dpr));
    }
    if let Some(name) = &a.figure {
        return figure(name, &a);
    }
    let input = a.input.clone().ok_or("give an input mesh, or --figure NAME")?;
    let passes = a.passes.unwrap_or(match a.view {
        ViewArg::Mesh | ViewArg::Levelset => 0,
        _ => smoothlab::smooth::DEFAULT_PASSES,
    });
    if !RENDER_PASSES.contains(passes.into()) {
        return Err(format!("--passes {passes}: give at most {}", RENDER_PASSES.max));
    }
    let camera = a.camera.as_deref().map(Camera::parse).transpose().map_err(|e| format!("--camera: {e}"))?;
    let mesh = match crate::files::read_model(&input)? {
        Model::Planar(mesh) => {
            if camera.is_some() {
                return Err("--camera turns the 3D view of a surface; this mesh is planar".into());
            }
            mesh
        }
        Model::Surface(s) => return surface(&a, &input, s, camera.unwrap_or_default(), passes, &shown),
        Model::Volume(v) => return volume(&a, &input, v, camera.unwrap_or_default(), passes, &shown),
    };
    if a.cut.is_some() {
        return Err("--cut cuts a volume mesh; this mesh is planar".into());
    }
    // The pictures are drawn by the page's code, which holds at most MAX_NODES nodes: say
    // so in this tool's words, with the file's name (the page's own message pointed to
    // the command-line tool, which this is).
    if mesh.node_count() > MAX_NODES {
        return Err(format!(
            "{}: the mesh has {} nodes; render draws meshes of at most {MAX_NODES} nodes \
             (stats, smooth and convert take larger ones)",
            input.display(),
            mesh.node_count()
        ));
    }
    // a --node that does not exist is refused by every view, not only the ones that use it
    if let Some(n) = a.node.filter(|&n| n >= mesh.node_count()) {
        return Err(no_such_node(n, &mesh));
    }
    let original = mesh.clone();
    let mut lab = Playground::new(mesh).map_err(|e| e.to_string())?;
    lab.set_settings(settings(&a)).map_err(|e| e.to_string())?;
    let theme = a.theme.theme();
    lab.set_theme(theme);
    let start = std::time::Instant::now();
    let clock = move || start.elapsed().as_secs_f64() * 1e3;
    for _ in 0..passes {
        lab.step(&clock);
    }
    let default_size = match a.view {
        ViewArg::Mesh => (900, 800),
        ViewArg::Levelset => (if shown.len() == 2 { 1100 } else { 560 }, 560),
        ViewArg::History => (1000, 640),
        ViewArg::Histogram => (900, 520),
        ViewArg::Compare => (1400, 780),
    };
    let (w, h) = size(a.size.as_deref(), default_size)?;
    let canvas = |w: u32, h: u32| Canvas { w: ((w as f32) * a.dpr) as u32, h: ((h as f32) * a.dpr) as u32, dpr: a.dpr };
    let first = shown[0];
    let node = |side: Side| -> Result<usize, String> {
        let m = &lab.panel(side).mesh;
        match a.node {
            Some(n) if n < m.node_count() && m.is_free(n) => Ok(n),
            Some(n) if n < m.node_count() => {
                Err(format!("--node {n} is not a free corner node: it never moves, so it has no objective to draw"))
            }
            Some(n) => Err(no_such_node(n, m)),
            None => worst_free_node(m).ok_or_else(|| "the mesh has no free node to study".to_string()),
        }
    };
    let picture = match a.view {
        ViewArg::Mesh => {
            let c = canvas(w, h);
            let mut pm = pixmap(c.w, c.h).map_err(|e| e.to_string())?;
            let mut view = MeshView::default().with_dpr(a.dpr).with_highlight(a.node);
            view.metric = a.metric;
            view.theme = theme;
            render_mesh(&mut pm, &lab.panel(first).mesh, &view);
            pm
        }
        ViewArg::Levelset => {
            let n = node(first)?;
            let each = canvas(w / shown.len() as u32, h);
            let mut parts = Vec::new();
            for &side in &shown {
                parts.push(lab.render_level_set(side, n, each).map_err(|e| e.to_string())?.0);
            }
            side_by_side(&parts, &theme)?
        }
        ViewArg::History => match a.node {
            Some(_) => {
                let n = node(first)?;
                // the node view's third picture is its solve history (both objectives)
                let ([_, _, chart], _) =
                    lab.render_node_view(n, canvas(64, 64), canvas(w, h)).map_err(|e| e.to_string())?;
                chart
            }
            None => lab.render_pass_chart(canvas(w, h)).map_err(|e| e.to_string())?,
        },
        ViewArg::Histogram => {
            let as_loaded = mesh_stats(&original).angle_histogram_6deg;
            let mut laplace = original.clone();
            let opts = SmoothOptions::default().with_strategy(Strategy::Laplace);
            let objective = smoothlab::objective::objective_with(smoothlab::objective::ObjectiveKind::SmoothShape, a.penalty);
            smooth(&mut laplace, objective.as_ref(), opts, passes, &|| 0.0).map_err(|e| e.to_string())?;
            let lap = mesh_stats(&laplace).angle_histogram_6deg;
            let old = lab.stats(Side::A).mesh.angle_histogram_6deg;
            let new = lab.stats(Side::B).mesh.angle_histogram_6deg;
            let mut series = vec![HistogramSeries { label: "as loaded", counts: &as_loaded, color: None }];
            for &side in &shown {
                series.push(match side {
                    Side::A => {
                        HistogramSeries { label: "old (max-min)", counts: &old, color: Some(theme.side(0)) }
                    }
                    Side::B => {
                        HistogramSeries { label: "new (Chen et al.)", counts: &new, color: Some(theme.side(1)) }
                    }
                });
            }
            series.push(HistogramSeries { label: "Laplacian", counts: &lap, color: None });
            let c = canvas(w, h);
            let mut pm = pixmap(c.w, c.h).map_err(|e| e.to_string())?;
            let title = format!("Corner angles (6° bins) after {passes} passes");
            render_angle_histogram(
                &mut pm,
                &series,
                &AngleHistogram { title: &title, dpr: a.dpr, theme, ..AngleHistogram::default() },
            )
            .map_err(|e| e.to_string())?;
            pm
        }
        ViewArg::Compare => {
            if shown.len() != 2 {
                return Err("--view compare shows both objectives: use --objective old,new".into());
            }
            lab.render_figure(canvas(w, h)).map_err(|e| e.to_string())?
        }
    };
    let png = encode_png(&picture).map_err(|e| e.to_string())?;
    std::fs::write(&a.output, png).map_err(|e| format!("{}: {e}", a.output.display()))
}

/// `--figure NAME`: the tour's picture of that figure.
fn figure(name: &str, a: &RenderArgs) -> Result<(), String> {
    let fig = smoothlab_page::lab::tour::find(name).map_err(|e| format!("--figure {name}: {e}"))?.1;
    let (w, h) = size(a.size.as_deref(), smoothlab_page::lab::tour::pictures::default_size(fig.name))?;
    let c = Canvas { w: ((w as f32) * a.dpr) as u32, h: ((h as f32) * a.dpr) as u32, dpr: a.dpr };
    let picture = smoothlab_page::lab::tour::pictures::render(fig.name, c, &a.theme.theme()).map_err(|e| e.to_string())?;
    let png = encode_png(&picture).map_err(|e| e.to_string())?;
    std::fs::write(&a.output, png).map_err(|e| format!("{}: {e}", a.output.display()))
}

/// `--view mesh` or `compare` of a surface, in the 3D view: as loaded (or after the
/// passes of the first objective asked for), or old and new side by side after the
/// passes, with the lab's settings (strategy, order, iterations, the new objective's penalty).
fn surface(
    a: &RenderArgs,
    input: &std::path::Path,
    s: Surface,
    camera: Camera,
    passes: u32,
    shown: &[Side],
) -> Result<(), String> {
    if s.node_count() > MAX_NODES {
        return Err(format!(
            "{}: the mesh has {} nodes; render draws meshes of at most {MAX_NODES} nodes",
            input.display(),
            s.node_count()
        ));
    }
    let sides: Vec<Side> = match a.view {
        ViewArg::Mesh => vec![shown[0]],
        ViewArg::Compare if shown.len() == 2 => shown.to_vec(),
        ViewArg::Compare => return Err("--view compare shows both objectives: use --objective old,new".into()),
        ViewArg::Levelset => return surface_level_sets(a, &s, passes, shown),
        other => {
            return Err(format!(
                "--view {}: a surface is drawn by --view mesh, compare or levelset",
                format!("{other:?}").to_lowercase()
            ))
        }
    };
    let settings = settings(a);
    let opts = settings.smooth_options().map_err(|e| e.to_string())?;
    let (w, h) = size(a.size.as_deref(), if sides.len() == 2 { (1400, 760) } else { (900, 800) })?;
    let each = w / sides.len() as u32;
    let mut parts = Vec::new();
    for side in sides {
        let mut t = s.clone();
        let choice = settings.compare[side as usize];
        let objective = choice.build();
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
        let title =
            format!("{when}: {} inverted, angles {:.1}°–{:.1}°", st.inverted, st.min_angle_deg, st.max_angle_deg);
        let mut pm = pixmap(((each as f32) * a.dpr) as u32, ((h as f32) * a.dpr) as u32).map_err(|e| e.to_string())?;
        let view = SurfaceView { camera, dpr: a.dpr, title: Some(title), theme: a.theme.theme(), ..SurfaceView::default() };
        t.render(&mut pm, a.metric, &view);
        parts.push(pm);
    }
    let picture = side_by_side(&parts, &a.theme.theme())?;
    let png = encode_png(&picture).map_err(|e| e.to_string())?;
    std::fs::write(&a.output, png).map_err(|e| format!("{}: {e}", a.output.display()))
}

/// A volume mesh, cut (`--cut`) and drawn in the 3D view: `--view mesh` (as loaded,
/// or after the passes of the first objective asked for), `compare` (old and new side by
/// side after the passes) or `histogram` (the dihedral angles, 6° bins: as loaded, old,
/// new), with the lab's strategy, order and iterations.
fn volume(
    a: &RenderArgs,
    input: &std::path::Path,
    v: VolumeMesh,
    camera: Camera,
    passes: u32,
    shown: &[Side],
) -> Result<(), String> {
    if v.node_count() > MAX_NODES {
        return Err(format!(
            "{}: the mesh has {} nodes; render draws meshes of at most {MAX_NODES} nodes",
            input.display(),
            v.node_count()
        ));
    }
    let cut = a.cut.as_deref().map(Cut::parse).transpose().map_err(|e| format!("--cut: {e}"))?.unwrap_or_default();
    let sides: Vec<Side> = match a.view {
        ViewArg::Mesh => vec![shown[0]],
        ViewArg::Compare | ViewArg::Histogram if shown.len() == 2 => shown.to_vec(),
        ViewArg::Compare | ViewArg::Histogram => {
            return Err("--view compare and histogram show both objectives: use --objective old,new".into())
        }
        other => {
            return Err(format!(
                "--view {}: a volume mesh is drawn by --view mesh, compare or histogram",
                format!("{other:?}").to_lowercase()
            ))
        }
    };
    let settings = settings(a);
    let opts = settings.smooth_options().map_err(|e| e.to_string())?;
    let mut smoothed = Vec::new();
    for &side in &sides {
        let mut t = v.clone();
        let kind = settings.compare[side as usize].objective;
        smooth_volume(&mut t, &*tet_objective(kind).map_err(|e| e.to_string())?, opts, passes, &|| 0.0).map_err(|e| e.to_string())?;
        smoothed.push((side, kind, t));
    }
    let picture = if a.view == ViewArg::Histogram {
        let (w, h) = size(a.size.as_deref(), (900, 520))?;
        let mut pm = pixmap(((w as f32) * a.dpr) as u32, ((h as f32) * a.dpr) as u32).map_err(|e| e.to_string())?;
        let loaded = volume_stats(&v).angle_histogram_6deg;
        let counts: Vec<(String, Vec<u64>)> = smoothed
            .iter()
            .map(|(side, kind, t)| (format!("{}: {kind}", side.letter()), volume_stats(t).angle_histogram_6deg))
            .collect();
        let mut series = vec![HistogramSeries { label: "as loaded", counts: &loaded, color: None }];
        series.extend(counts.iter().map(|(l, c)| HistogramSeries { label: l, counts: c, color: None }));
        let title = format!("Dihedral angles after {passes} passes");
        let opts = AngleHistogram { title: &title, dpr: a.dpr, theme: a.theme.theme(), ..AngleHistogram::default() };
        render_angle_histogram(&mut pm, &series, &opts).map_err(|e| e.to_string())?;
        pm
    } else {
        let (w, h) = size(a.size.as_deref(), if sides.len() == 2 { (1400, 760) } else { (900, 800) })?;
        let each = w / sides.len() as u32;
        let mut parts = Vec::new();
        for (side, kind, t) in &smoothed {
            let st = volume_stats(t);
            let when = match passes {
                0 => "as loaded".to_string(),
                1 => format!("{}: {kind} after 1 pass", side.letter()),
                n => format!("{}: {kind} after {n} passes", side.letter()),
            };
            let title =
                format!("{when}: {} inverted, dihedral {:.1}°–{:.1}°", st.inverted, st.min_angle_deg, st.max_angle_deg);
            let mut pm =
                pixmap(((each as f32) * a.dpr) as u32, ((h as f32) * a.dpr) as u32).map_err(|e| e.to_string())?;
            let view = SurfaceView { camera, dpr: a.dpr, title: Some(title), theme: a.theme.theme(), ..SurfaceView::default() };
            t.render_cut(&mut pm, cut, &view);
            parts.push(pm);
        }
        side_by_side(&parts, &a.theme.theme())?
    };
    let png = encode_png(&picture).map_err(|e| e.to_string())?;
    std::fs::write(&a.output, png).map_err(|e| format!("{}: {e}", a.output.display()))
}

/// `--view levelset` of a surface: the node's star flattened into its tangent plane,
/// where the drivers see it, with the planar view's level sets of each objective asked for.
fn surface_level_sets(a: &RenderArgs, s: &Surface, passes: u32, shown: &[Side]) -> Result<(), String> {
    if passes > 0 {
        return Err("--view levelset of a surface draws the mesh as loaded: give no --passes".into());
    }
    let node = match a.node {
        Some(n) => n,
        None => s.worst_free_node().ok_or("the mesh has no free node to study")?,
    };
    let (star, n) = s.star_in_tangent_plane(node).map_err(|e| format!("--node {node}: {e}"))?;
    let mut lab = Playground::new(star).map_err(|e| e.to_string())?;
    lab.set_settings(settings(a)).map_err(|e| e.to_string())?;
    lab.set_theme(a.theme.theme());
    let (w, h) = size(a.size.as_deref(), (if shown.len() == 2 { 1100 } else { 560 }, 560))?;
    let each =
        Canvas { w: ((w / shown.len() as u32) as f32 * a.dpr) as u32, h: ((h as f32) * a.dpr) as u32, dpr: a.dpr };
    let mut parts = Vec::new();
    for &side in shown {
        parts.push(lab.render_level_set(side, n, each).map_err(|e| e.to_string())?.0);
    }
    let picture = side_by_side(&parts, &a.theme.theme())?;
    let png = encode_png(&picture).map_err(|e| e.to_string())?;
    std::fs::write(&a.output, png).map_err(|e| format!("{}: {e}", a.output.display()))
}
