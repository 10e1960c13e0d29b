//! `smoothlab render IN -o OUT.png --view mesh|levelset|history|histogram|compare …`:
//! the page's pictures as PNG files, drawn by the same core code (`lab` and `render`;
//! `lab::picture` draws them, for the Python package too).
//! `smoothlab render --figure NAME -o OUT.png`: a figure of the page's tour
//! (`lab::tour`), drawn from its own state (no input mesh).
//!
//! Node numbers are 0-based in file order, as everywhere in smoothlab.

use std::path::PathBuf;

use clap::{Args, ValueEnum};
use smoothlab_page::lab::picture::{self, Request, View};
use smoothlab_page::lab::views::Canvas;
use smoothlab_render::{encode_png, Camera, Cut, Metric, Theme};

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

fn size(spec: Option<&str>, default: (u32, u32)) -> Result<(u32, u32), String> {
    let Some(s) = spec else { return Ok(default) };
    let bad = || format!("--size {s}: give WIDTHxHEIGHT in pixels, e.g. 1200x700");
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    Ok((w.trim().parse().map_err(|_| bad())?, h.trim().parse().map_err(|_| bad())?))
}

impl ViewArg {
    fn view(self) -> View {
        match self {
            ViewArg::Mesh => View::Mesh,
            ViewArg::Levelset => View::Levelset,
            ViewArg::History => View::History,
            ViewArg::Histogram => View::Histogram,
            ViewArg::Compare => View::Compare,
        }
    }
}

/// An option as this tool names it: `--max-iter`.
fn flag(name: &str) -> String {
    format!("--{}", name.replace('_', "-"))
}

pub fn run(a: RenderArgs) -> Result<(), String> {
    let sides = picture::sides(&a.objective, &flag)?;
    if !(a.dpr.is_finite() && a.dpr > 0.0 && a.dpr <= 4.0) {
        return Err(format!("--dpr {}: give a ratio above 0 and at most 4", a.dpr));
    }
    if let Some(name) = &a.figure {
        return figure(name, &a);
    }
    let input = a.input.clone().ok_or("give an input mesh, or --figure NAME")?;
    let camera = a.camera.as_deref().map(Camera::parse).transpose().map_err(|e| format!("--camera: {e}"))?;
    let cut = a.cut.as_deref().map(Cut::parse).transpose().map_err(|e| format!("--cut: {e}"))?;
    let size = a.size.as_deref().map(|s| size(Some(s), (0, 0))).transpose()?;
    let request = Request {
        view: a.view.view(),
        node: a.node,
        sides,
        metric: a.metric,
        size,
        dpr: a.dpr,
        strategy: a.strategy,
        threshold_deg: a.threshold,
        passes: a.passes,
        order: a.order,
        max_iter: a.max_iter,
        penalty: a.penalty,
        camera,
        cut,
        theme: a.theme.theme(),
    };
    let model = crate::files::read_model(&input)?;
    let start = std::time::Instant::now();
    let clock = move || start.elapsed().as_secs_f64() * 1e3;
    let picture = picture::draw(model, &input.display().to_string(), &request, &clock, &flag)?;
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
