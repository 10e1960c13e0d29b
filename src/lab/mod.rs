//! The laboratory: old versus new, side by side. The playground page's state in plain
//! Rust (no web types; the wasm layer and the CLI's `render` both call it): the
//! original mesh, and one copy per side — the OLD max-min objective (Freitag 1997, left)
//! and the NEW smooth objective (Chen, Tristano & Kwok 2003, right) — that the page
//! smooths, perturbs and drags side by side.
//!
//! At scale (up to [`MAX_NODES`]): a pass can run in slices of a time budget
//! ([`Playground::begin_pass`], [`Playground::continue_pass`], [`Playground::abort_pass`];
//! the state machine is [`pass`]) with the same result as [`Playground::step`]; each panel keeps the cheap statistics its
//! table shows ([`stats::QuickStats`]) and each element's colour bucket up to date, a
//! version naming its positions, and its last picture ([`raster`] draws fine meshes).

pub mod controls;
pub mod interact;
pub mod pass;
pub mod permalink;
pub mod pick;
pub mod raster;
pub mod sample;
pub mod stats;
pub mod surface;
pub mod tour;
pub mod views;
pub mod volume;

use std::cell::{OnceCell, RefCell};

use glam::DVec2;
use serde::{Deserialize, Serialize};
use tiny_skia::Pixmap;

use crate::error::{Error, Result};
use crate::generate::perturb;
use crate::io::{write_string, Format, WriteOptions};
use crate::mesh::Mesh;
use crate::objective::{objective_with, Objective, ObjectiveKind, Penalty};
use crate::optimize::SolveResult;
use crate::quality::MeshStats;
use crate::smooth::{solve_node, Order, SmoothOptions, Smoother, Strategy};
pub use pass::{PassProgress, PassStage, SideSweep};
use pass::{PassRun, RunKind};
use stats::{quick_stats_and_buckets, QuickStats};
use views::Canvas;

/// Node count above which the page refuses a mesh: the playground holds two copies (and
/// the positions as loaded) and draws every element each frame.
pub const MAX_NODES: usize = 1_000_000;

/// The two panels of the page: the left one (A) and the right one (B). Each smooths
/// with its own [`Choice`] of objective; by default the left runs Chen et al.'s
/// "previous method" (the old max-min objective, Freitag 1997) and the right their new
/// smooth one, so the panels keep the names `old` and `new`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Side {
    /// The left panel (A), by default Freitag's max-min objective.
    Old,
    /// The right panel (B), by default Chen, Tristano & Kwok's smooth objective.
    New,
}

impl Side {
    pub const BOTH: [Side; 2] = [Side::Old, Side::New];
    fn index(self) -> usize {
        self as usize
    }
    /// `A` or `B`, as the page heads its panels.
    pub fn letter(self) -> &'static str {
        match self {
            Side::Old => "A",
            Side::New => "B",
        }
    }
    /// The colour of this side wherever it is drawn (meshes' titles, charts, histograms,
    /// legends; the page takes it from here): the Okabe–Ito orange for the left side and
    /// blue for the right, told apart by people with any colour vision.
    pub fn rgb(self) -> [u8; 3] {
        match self {
            Side::Old => crate::render::SERIES[1],
            Side::New => crate::render::SERIES[2],
        }
    }
    /// [`rgb`](Self::rgb) as a tiny-skia colour.
    pub fn color(self) -> tiny_skia::Color {
        let [r, g, b] = self.rgb();
        tiny_skia::Color::from_rgba8(r, g, b, 255)
    }
}

/// What a panel smooths with: an objective and, for `new`, the design of its penalty.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Choice {
    /// By its command-line name (`old`, `sine`, `new`, `condition`, …).
    pub objective: ObjectiveKind,
    /// The penalty of `new` (`barrier`, `angle`); absent means the default. Other
    /// objectives have no penalty: it is then the default.
    #[serde(default)]
    pub penalty: Penalty,
}

impl Choice {
    /// The left panel's default: the old max-min objective.
    pub const OLD: Choice = Choice { objective: ObjectiveKind::Old, penalty: Penalty::Barrier };
    /// The right panel's default: the new objective with its default penalty.
    pub const NEW: Choice = Choice { objective: ObjectiveKind::New, penalty: Penalty::Barrier };

    /// The objective it names.
    pub fn build(self) -> Box<dyn Objective> {
        objective_with(self.objective, self.penalty)
    }

    /// A short label for legends: `old (max-min α/β …)`, `new (…, angle penalty)`.
    pub fn label(self) -> String {
        match self.objective {
            ObjectiveKind::New => format!("new, {} penalty", self.penalty.name()),
            k => format!("{} ({})", k.name(), k.describe().split(" (").next().unwrap_or("")),
        }
    }

    /// A title for a picture or a panel: the label and who it is from.
    pub fn title(self) -> String {
        match self.objective {
            ObjectiveKind::New => format!("new: {}, {} penalty", self.objective.describe(), self.penalty.name()),
            k => format!("{}: {}", k.name(), k.describe()),
        }
    }

    /// Checks that a penalty is given only to `new` (as the command line refuses it).
    fn validate(self) -> Result<()> {
        if self.objective != ObjectiveKind::New && self.penalty != Penalty::default() {
            return Err(Error::invalid(format!(
                "the {} penalty is a design of the new objective; {} has no penalty",
                self.penalty.name(),
                self.objective.name()
            )));
        }
        Ok(())
    }
}

/// The shared controls of the page (both sides smooth with the same settings), and what
/// each side smooths with.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Settings {
    /// By its name (`rules`, `c2`, …), as the page's menus give it.
    pub strategy: Strategy,
    /// Freitag's threshold angle θ_t, degrees.
    pub threshold_deg: f64,
    /// `input` or `priority`.
    pub order: Order,
    /// Solver iterations per optimization call.
    pub max_iter: u32,
    /// What the left (A) and the right (B) panel smooth with; absent means old against
    /// new (with the barrier penalty).
    #[serde(default = "default_compare")]
    pub compare: [Choice; 2],
}

fn default_compare() -> [Choice; 2] {
    [Choice::OLD, Choice::NEW]
}

impl Default for Settings {
    /// The core's defaults ([`SmoothOptions::default`]: Chen's algorithm, rules in priority
    /// order, 3 iterations per call; θ_t = 30°); old against new with the barrier penalty.
    fn default() -> Self {
        let d = SmoothOptions::default();
        Settings {
            strategy: d.strategy,
            threshold_deg: d.threshold_deg,
            order: d.order,
            max_iter: d.max_iter,
            compare: default_compare(),
        }
    }
}

impl Settings {
    /// The drivers' options (checked), after checking each side's choice.
    pub fn smooth_options(&self) -> Result<SmoothOptions> {
        for c in self.compare {
            c.validate()?;
        }
        let range = crate::smooth::limits::BATCH_MAX_ITER;
        if !range.contains(self.max_iter.into()) {
            return Err(Error::invalid(format!("{} solver iterations: give {}", self.max_iter, range.words())));
        }
        let o = SmoothOptions::default()
            .with_strategy(self.strategy)
            .with_order(self.order)
            .with_threshold_deg(self.threshold_deg)
            .with_max_iter(self.max_iter);
        o.validate()?;
        Ok(o)
    }

    /// What `side` smooths with.
    pub fn choice(&self, side: Side) -> Choice {
        self.compare[side.index()]
    }

    /// A side's heading: its letter and what it smooths with ([`Choice::title`]).
    pub fn side_title(&self, side: Side) -> String {
        format!("{}: {}", side.letter(), self.choice(side).title())
    }

    /// The same, short ([`Choice::label`]), for a compact page.
    pub fn side_label(&self, side: Side) -> String {
        format!("{}: {}", side.letter(), self.choice(side).label())
    }
}

/// What one pass did on one panel and where its mesh stands after it: the core's record,
/// without the objective total (the page never shows it, and it costs more than a
/// Laplacian pass).
pub type PassSummary = crate::smooth::PassRecord;

/// One panel: its current mesh, its objective and driver, and its passes since the last reset.
pub struct Panel {
    pub mesh: Mesh,
    pub objective: Box<dyn Objective>,
    smoother: Smoother,
    pub records: Vec<PassSummary>,
    /// Names the mesh's current positions: equal versions, equal positions (caches
    /// compare it).
    version: u64,
    /// The table's statistics of the current positions.
    quick: QuickStats,
    /// Each element's colour bucket for the current positions (see [`stats::bucket_of`]).
    buckets: Vec<u8>,
    /// The full statistics (angle histogram included), computed when first asked for.
    full: OnceCell<MeshStats>,
    /// The last mesh picture drawn without a highlight, with the version, canvas and zoom it shows.
    picture: RefCell<Option<(u64, Canvas, crate::render::ZoomPan, Pixmap)>>,
}

impl Panel {
    fn new(
        side: Side,
        mesh: Mesh,
        settings: &Settings,
        version: u64,
        full: &MeshStats,
        buckets: Vec<u8>,
    ) -> Result<Self> {
        Ok(Panel {
            mesh,
            objective: settings.choice(side).build(),
            smoother: Smoother::new(settings.smooth_options()?)?,
            records: Vec::new(),
            version,
            quick: full.quick(),
            buckets,
            full: OnceCell::from(full.clone()),
            picture: RefCell::new(None),
        })
    }

    /// The mesh's positions changed (to a new version).
    fn changed(&mut self, version: u64) {
        self.version = version;
        self.quick = quick_stats_and_buckets(&self.mesh, &mut self.buckets);
        self.full = OnceCell::new();
    }
}

/// The work a panel's passes did since the last reset: its records, summed.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct WorkDone {
    pub passes: usize,
    pub laplacian_moves: u64,
    pub optimization_calls: u64,
    pub solver_iterations: u64,
    /// Smoothing time summed over the passes, milliseconds by the caller's clock.
    pub time_ms: f64,
}

impl WorkDone {
    /// The sums of `records`.
    pub fn of(records: &[PassSummary]) -> WorkDone {
        let sum = |f: fn(&PassSummary) -> u32| records.iter().map(|r| f(r) as u64).sum();
        WorkDone {
            passes: records.len(),
            laplacian_moves: sum(|r| r.counts.laplacian_moves),
            optimization_calls: sum(|r| r.counts.optimization_calls),
            solver_iterations: sum(|r| r.counts.solver_iterations),
            time_ms: records.iter().map(|r| r.elapsed_ms).sum(),
        }
    }
}

/// What a panel's statistics table shows: the mesh now and the work done since the last reset.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PanelStats {
    pub side: Side,
    #[serde(flatten)]
    pub mesh: MeshStats,
    #[serde(flatten)]
    pub work: WorkDone,
}

/// The page's statistics table: [`PanelStats`] with the cheap statistics of
/// [`QuickStats`] in place of the full ones.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PanelTable {
    pub side: Side,
    /// The panel's heading: its letter and what it smooths with ([`Choice::title`]).
    pub title: String,
    /// The same, short ([`Choice::label`]), for a compact page.
    pub label: String,
    pub nodes: usize,
    pub elements: usize,
    #[serde(flatten)]
    pub mesh: QuickStats,
    /// The rows that need every corner measured, when they were (see [`TableDetail`]).
    pub detail: Option<TableDetail>,
    /// A surface's largest distance of a node from its reference surface; `None` for a
    /// planar mesh.
    pub max_distance_from_surface: Option<f64>,
    #[serde(flatten)]
    pub work: WorkDone,
}

/// Corners under this angle, degrees, count as poor in the table: Freitag (1997) judges
/// meshes by their angle distribution (Fig. 3), and 18° is three of its 6° bins.
pub const SMALL_ANGLE_DEG: f64 = 18.0;

/// Meshes with at most this many elements have their table's [`TableDetail`] measured
/// after every change; larger ones when their charts are drawn (after a run).
pub const DETAIL_MAX_ELEMENTS: usize = 250_000;

/// The rows of the table that come from the full statistics ([`MeshStats`]), which
/// measure every corner's angle and every element's condition number.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct TableDetail {
    /// Mean element quality α/β.
    pub mean_quality: f64,
    /// Share of corner angles under [`SMALL_ANGLE_DEG`], 0 to 1 (inverted corners count).
    pub small_angle_share: f64,
    /// Worst condition number κ; `None` when an element is inverted (κ = ∞).
    pub max_condition: Option<f64>,
}

impl TableDetail {
    /// The detail rows of full statistics.
    pub fn of(s: &MeshStats) -> TableDetail {
        let bins = (SMALL_ANGLE_DEG / 6.0) as usize;
        let total: u64 = s.angle_histogram_6deg.iter().sum();
        let small: u64 = s.angle_histogram_6deg.iter().take(bins).sum();
        TableDetail {
            mean_quality: s.mean_quality,
            small_angle_share: if total == 0 { 0.0 } else { small as f64 / total as f64 },
            max_condition: s.max_condition.is_finite().then_some(s.max_condition),
        }
    }
}

/// Hands out the numbers that name a panel's positions: each call a new one.
#[derive(Debug)]
struct Versions(u64);

impl Versions {
    fn fresh(&mut self) -> u64 {
        self.0 += 1;
        self.0
    }
}

/// The page's state: see the module docs. The mesh as loaded is kept as positions only
/// (the panels' meshes carry the topology), so a 1M-node mesh is held twice, not three times.
pub struct Playground {
    original: Vec<DVec2>,
    original_version: u64,
    original_stats: MeshStats,
    original_buckets: Vec<u8>,
    bounds: (DVec2, DVec2),
    /// Mean edge length of the mesh as loaded: whether its edges are drawn.
    mean_edge: f64,
    settings: Settings,
    panels: [Panel; 2],
    versions: Versions,
    run: Option<PassRun>,
    /// A completed sweep for another engine ([`begin_sweep`](Self::begin_sweep)): the
    /// panel's swept positions and what the sweep did, until taken.
    swept: Option<(Vec<DVec2>, SideSweep)>,
    /// The user's zoom and pan on the mesh panels (both panels share it).
    zoom: crate::render::ZoomPan,
    /// The part of a star the level-set views show (both sides share it).
    level_window: interact::LevelWindow,
    /// What undo puts back: the latest move last.
    undo: Vec<interact::Undo>,
    /// The colours and label sizes every picture is drawn with.
    theme: crate::render::Theme,
    /// The CSS pixels each side's level-set legend took when it was last drawn, so a
    /// pointer on it maps as it was drawn.
    level_legend: std::cell::Cell<[f32; 2]>,
}

/// Positions as x, y interleaved, the form in which they travel between two engines.
fn interleaved(nodes: &[DVec2]) -> Vec<f64> {
    nodes.iter().flat_map(|p| [p.x, p.y]).collect()
}

impl Playground {
    /// A playground on `mesh`: both panels start from it.
    pub fn new(mesh: Mesh) -> Result<Self> {
        if mesh.node_count() > MAX_NODES {
            return Err(Error::TooLarge(format!(
                "the mesh has {} nodes; the page takes at most {MAX_NODES} (use the command-line tool)",
                mesh.node_count()
            )));
        }
        let settings = Settings::default();
        let full = crate::quality::mesh_stats(&mesh);
        let mut buckets = Vec::new();
        quick_stats_and_buckets(&mesh, &mut buckets);
        let original = mesh.nodes().to_vec();
        let bounds = mesh.bounds();
        let mean_edge = mesh.mean_edge_length();
        let old = Panel::new(Side::Old, mesh.clone(), &settings, 1, &full, buckets.clone())?;
        let new = Panel::new(Side::New, mesh, &settings, 1, &full, buckets.clone())?;
        Ok(Playground {
            original,
            original_version: 1,
            original_stats: full,
            original_buckets: buckets,
            bounds,
            mean_edge,
            settings,
            panels: [old, new],
            versions: Versions(1),
            run: None,
            swept: None,
            zoom: crate::render::ZoomPan::default(),
            level_window: interact::LevelWindow::default(),
            undo: Vec::new(),
            theme: crate::render::Theme::light(),
            level_legend: std::cell::Cell::new([0.0; 2]),
        })
    }

    /// The theme every later picture is drawn with.
    pub fn theme(&self) -> crate::render::Theme {
        self.theme
    }

    /// Draws every later picture with `theme`, forgetting the kept mesh pictures.
    pub fn set_theme(&mut self, theme: crate::render::Theme) {
        if self.theme != theme {
            self.theme = theme;
            for p in &self.panels {
                p.picture.replace(None);
            }
        }
    }

    fn fresh_version(&mut self) -> u64 {
        self.versions.fresh()
    }

    /// The settings the next passes use.
    pub fn settings(&self) -> Settings {
        self.settings
    }

    /// New settings for the next passes (the meshes stay as they are; a pass in
    /// progress is abandoned).
    pub fn set_settings(&mut self, settings: Settings) -> Result<()> {
        let o = settings.smooth_options()?;
        self.abort_pass();
        for (p, side) in self.panels.iter_mut().zip(Side::BOTH) {
            p.smoother = Smoother::new(o)?;
            p.objective = settings.choice(side).build();
        }
        self.settings = settings;
        Ok(())
    }

    /// One smoothing pass on both panels; `clock` gives milliseconds (the core reads no time).
    pub fn step(&mut self, clock: &dyn Fn() -> f64) -> [PassSummary; 2] {
        self.begin_pass();
        loop {
            let p = self.continue_pass(clock, f64::INFINITY).expect("a pass was begun");
            if let Some(records) = p.records {
                return records;
            }
        }
    }

    /// Starts a pass to be run in slices by [`continue_pass`](Self::continue_pass)
    /// (a pass already in progress is abandoned first). The result is the same as
    /// [`step`](Self::step)'s, bit for bit: the old panel is swept in the order the
    /// smoother plans, then measured, then the new panel ([`pass`] runs it).
    pub fn begin_pass(&mut self) {
        self.abort_pass();
        self.undo.clear(); // a move before a pass is not undone over the pass's work
        self.run = Some(PassRun::new());
    }

    /// Starts a pass split between two engines (the page's two workers): this playground
    /// runs the new panel's pass as [`begin_pass`](Self::begin_pass) does, while another
    /// one, on the same mesh with the same settings, sweeps the old panel
    /// ([`begin_sweep`](Self::begin_sweep)); its result is handed over with
    /// [`adopt_sweep`](Self::adopt_sweep), then measured here. Until then
    /// [`continue_pass`](Self::continue_pass) says [`PassStage::Wait`]. The records and
    /// positions are [`step`](Self::step)'s, bit for bit.
    pub fn begin_split_pass(&mut self) {
        self.abort_pass();
        self.undo.clear();
        self.run = Some(PassRun::of(RunKind::Split));
    }

    /// Starts the sweep of one panel alone, from the positions `nodes` (x, y interleaved: the
    /// other engine's panel), for a split pass: run it with
    /// [`continue_pass`](Self::continue_pass), then [`take_sweep`](Self::take_sweep). No
    /// statistics are taken, and this playground's panels are left as they were.
    pub fn begin_sweep(&mut self, side: Side, nodes: &[f64]) -> Result<()> {
        self.abort_pass();
        let nodes = self.positions_from(nodes)?;
        self.swept = None;
        let mut run = PassRun::of(RunKind::Sweep(side.index()));
        // the sweep starts from the other engine's positions; the run saves the panel's
        // own, and puts them back when the sweep is taken or abandoned
        run.save(&self.panels);
        self.panels[side.index()].mesh.nodes_mut().copy_from_slice(&nodes);
        self.run = Some(run);
        Ok(())
    }

    /// The sweep begun by [`begin_sweep`](Self::begin_sweep), once
    /// [`continue_pass`](Self::continue_pass) said it is done: the swept positions (x, y
    /// interleaved) and what the sweep did. `None` before that, and after it was taken.
    pub fn take_sweep(&mut self) -> Option<(Vec<f64>, SideSweep)> {
        self.swept.take().map(|(nodes, sweep)| (interleaved(&nodes), sweep))
    }

    /// Hands the old panel's sweep, made by another engine, to the split pass in progress
    /// ([`begin_split_pass`](Self::begin_split_pass)): its positions (x, y interleaved)
    /// and what it did.
    pub fn adopt_sweep(&mut self, nodes: &[f64], sweep: SideSweep) -> Result<()> {
        let nodes = self.positions_from(nodes)?;
        let run =
            self.run.as_mut().ok_or_else(|| Error::invalid("no pass is in progress: begin a split pass first"))?;
        run.adopt(&mut self.panels, &mut self.versions, &nodes, sweep).map_err(Error::invalid)
    }

    /// The positions of a panel, x and y interleaved (what [`begin_sweep`](Self::begin_sweep) takes).
    pub fn panel_positions(&self, side: Side) -> Vec<f64> {
        interleaved(self.panels[side.index()].mesh.nodes())
    }

    /// Positions from x, y interleaved ([`interleaved`]'s form), checked against the mesh:
    /// one pair per node, finite.
    fn positions_from(&self, xy: &[f64]) -> Result<Vec<DVec2>> {
        let n = self.panels[0].mesh.node_count();
        if xy.len() != 2 * n {
            return Err(Error::invalid(format!(
                "{} coordinates for a mesh of {n} nodes: give x and y of each",
                xy.len()
            )));
        }
        let nodes: Vec<DVec2> = xy.chunks_exact(2).map(|c| DVec2::new(c[0], c[1])).collect();
        if let Some(i) = nodes.iter().position(|p| !p.is_finite()) {
            return Err(Error::invalid(format!("node {i} has a coordinate that is not a finite number")));
        }
        Ok(nodes)
    }

    /// Whether a pass is in progress.
    pub fn pass_in_progress(&self) -> bool {
        self.run.is_some()
    }

    /// Runs the pass begun by [`begin_pass`](Self::begin_pass) for about `budget_ms`
    /// milliseconds of `clock` (at least one slice: a planning, a few node visits or a
    /// slice of the statistics), and says where it stands. When it is done the records
    /// are kept, as after [`step`](Self::step). While a pass is in progress the panels'
    /// meshes are part-smoothed and their statistics those before the pass.
    pub fn continue_pass(&mut self, clock: &dyn Fn() -> f64, budget_ms: f64) -> Result<PassProgress> {
        let run = self.run.as_mut().ok_or_else(|| Error::invalid("no pass is in progress: begin one first"))?;
        if run.advance(&mut self.panels, &mut self.versions, clock, budget_ms) {
            let run = self.run.take().expect("the pass just advanced");
            if run.is_sweep() {
                let side = run.side();
                self.swept = Some(run.finish_sweep(&mut self.panels));
                return Ok(PassProgress::swept(side));
            }
            return Ok(run.finish(&mut self.panels, &mut self.versions));
        }
        Ok(run.progress(&self.panels))
    }

    /// Abandons the pass in progress, if any: both panels go back to where they were
    /// before it (positions, statistics and version), so it leaves no trace.
    pub fn abort_pass(&mut self) {
        if let Some(run) = self.run.take() {
            run.undo(&mut self.panels);
        }
    }

    /// The original mesh perturbed ([`perturb`]: `amount` mean edge lengths, seeded);
    /// both panels start again from it.
    pub fn perturb(&mut self, amount: f64, seed: u64) -> Result<()> {
        self.abort_pass();
        let mesh = &mut self.panels[0].mesh;
        mesh.nodes_mut().copy_from_slice(&self.original);
        let perturbed = perturb(mesh, amount, seed)?;
        self.original_stats = crate::quality::mesh_stats(&perturbed);
        quick_stats_and_buckets(&perturbed, &mut self.original_buckets);
        self.mean_edge = perturbed.mean_edge_length();
        self.original = perturbed.nodes().to_vec();
        self.original_version = self.fresh_version();
        self.reset();
        Ok(())
    }

    /// A panel's current mesh as the text of a `.msh` (2.2) or `.vtk` file.
    pub fn export(&self, side: Side, format: Format) -> Result<String> {
        write_string(&self.panel(side).mesh, format, &WriteOptions::default())
    }

    /// Solves one node of a panel's mesh with the solver's history (for the level-set view),
    /// without moving it.
    pub fn solve_node(&self, side: Side, node: usize) -> Result<SolveResult> {
        let p = self.panel(side);
        solve_node(&p.mesh, node, p.objective.as_ref(), &self.settings.smooth_options()?)
    }

    /// The node positions as loaded (or as last perturbed).
    pub fn original_nodes(&self) -> &[DVec2] {
        &self.original
    }

    /// The mesh's topology and fixed flags (the panels share them; positions differ).
    pub fn topology(&self) -> &Mesh {
        &self.panels[0].mesh
    }

    /// Bounds of the mesh as loaded: both panels are drawn at this scale.
    pub fn bounds(&self) -> (DVec2, DVec2) {
        self.bounds
    }

    /// Statistics of the mesh as loaded (or as last perturbed).
    pub fn original_stats(&self) -> &MeshStats {
        &self.original_stats
    }

    pub fn panel(&self, side: Side) -> &Panel {
        &self.panels[side.index()]
    }

    /// The version of a panel's positions: it changes whenever they do.
    pub fn version(&self, side: Side) -> u64 {
        self.panel(side).version
    }

    /// The full statistics of a panel's current mesh (computed once per version).
    pub fn full_stats(&self, side: Side) -> &MeshStats {
        let p = self.panel(side);
        p.full.get_or_init(|| crate::quality::mesh_stats(&p.mesh))
    }

    /// Statistics of a panel's current mesh, with the work done since the last reset.
    pub fn stats(&self, side: Side) -> PanelStats {
        PanelStats { side, mesh: self.full_stats(side).clone(), work: WorkDone::of(&self.panel(side).records) }
    }

    /// The table's detail rows of a panel: measured now for a mesh of at most
    /// [`DETAIL_MAX_ELEMENTS`] elements, else only when the full statistics are at hand;
    /// never during a pass (its mesh is part-smoothed).
    fn detail(&self, side: Side) -> Option<TableDetail> {
        let p = self.panel(side);
        if self.run.is_some() {
            return None;
        }
        if let Some(full) = p.full.get() {
            return Some(TableDetail::of(full));
        }
        (p.mesh.element_count() <= DETAIL_MAX_ELEMENTS).then(|| TableDetail::of(self.full_stats(side)))
    }

    /// What the page's statistics table shows of a panel (cheap: kept up to date).
    pub fn table(&self, side: Side) -> PanelTable {
        let p = self.panel(side);
        PanelTable {
            side,
            title: self.settings.side_title(side),
            label: self.side_label(side),
            nodes: p.mesh.node_count(),
            elements: p.mesh.element_count(),
            mesh: p.quick,
            detail: self.detail(side),
            max_distance_from_surface: None,
            work: WorkDone::of(&p.records),
        }
    }

    /// Both panels back to the original mesh, their records cleared.
    pub fn reset(&mut self) {
        self.abort_pass();
        self.undo.clear();
        let o = self.settings.smooth_options().expect("the settings were checked when set");
        let quick = self.original_stats.quick();
        for p in &mut self.panels {
            p.mesh.nodes_mut().copy_from_slice(&self.original);
            p.version = self.original_version;
            p.quick = quick;
            p.buckets.clone_from(&self.original_buckets);
            p.full = OnceCell::from(self.original_stats.clone());
            p.records.clear();
            p.smoother = Smoother::new(o).expect("the settings were checked when set");
        }
    }

    /// Moves a free node to `to` on both panels' current meshes (the mouse drag); its
    /// mid-side nodes follow. Fixed nodes, mid-side nodes and unknown nodes are refused.
    pub fn move_node(&mut self, node: usize, to: DVec2) -> Result<()> {
        self.check_movable(node)?;
        if !to.is_finite() {
            return Err(Error::invalid(format!("cannot move node {node} to a non-finite position {to}")));
        }
        self.abort_pass();
        for side in Side::BOTH {
            self.place(side, node, to);
        }
        Ok(())
    }

    /// Refuses a node the user cannot move: unknown, fixed or mid-side.
    fn check_movable(&self, node: usize) -> Result<()> {
        let m = self.topology();
        if node >= m.node_count() {
            return Err(Error::node(node, None, format!("no such node: the mesh has {} nodes", m.node_count())));
        }
        if !m.is_free(node) {
            return Err(Error::node(node, None, "is fixed or a mid-side node, so it cannot be dragged"));
        }
        Ok(())
    }

    /// Puts a node of one panel at `to` (its mid-side nodes follow): a new version.
    fn place(&mut self, side: Side, node: usize, to: DVec2) {
        let v = self.fresh_version();
        let p = &mut self.panels[side.index()];
        p.mesh.nodes_mut()[node] = to;
        p.mesh.follow_mid_nodes(node);
        p.changed(v);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lab::sample::Sample;

    #[test]
    fn panels_start_equal_and_reset_restores_them() {
        let mut pg = Playground::new(Sample::PlateTriTangled.generate().unwrap()).unwrap();
        let before = pg.stats(Side::Old);
        assert_eq!(before.mesh, pg.stats(Side::New).mesh);
        assert!(before.mesh.inverted > 0);
        let free = (0..pg.topology().node_count()).find(|&n| pg.topology().is_free(n)).unwrap();
        pg.move_node(free, DVec2::new(0.9, 0.9)).unwrap();
        for s in Side::BOTH {
            assert_eq!(pg.panel(s).mesh.nodes()[free], DVec2::new(0.9, 0.9));
        }
        pg.reset();
        assert_eq!(pg.stats(Side::Old), before);
        assert_eq!(pg.panel(Side::New).mesh.nodes(), pg.original_nodes());
    }

    fn no_clock() -> f64 {
        0.0
    }

    #[test]
    fn three_passes_untangle_the_tangled_plate_on_the_new_side() {
        let mut pg = Playground::new(Sample::DEFAULT.generate().unwrap()).unwrap();
        let start = pg.stats(Side::New).mesh.inverted;
        assert!(start > 0);
        let mut last = None;
        for _ in 0..3 {
            last = Some(pg.step(&no_clock));
        }
        let [old, new] = last.unwrap();
        assert_eq!((old.pass, new.pass), (3, 3));
        assert_eq!(new.after.inverted, 0, "Chen et al. untangle the perturbed plate in 3 passes");
        // the page's default sample (issue 11): the new side beats the max-min objective on
        // what both sides are judged by: smallest and largest angle, worst and mean quality
        let (o, n) = (pg.full_stats(Side::Old).clone(), pg.full_stats(Side::New).clone());
        assert!(n.min_angle_deg > o.min_angle_deg, "min angle: new {} old {}", n.min_angle_deg, o.min_angle_deg);
        assert!(n.min_quality > o.min_quality, "min quality: new {} old {}", n.min_quality, o.min_quality);
        assert!(n.mean_quality > o.mean_quality + 0.01, "mean quality: new {} old {}", n.mean_quality, o.mean_quality);
        assert!(n.max_angle_deg < o.max_angle_deg - 1.0, "max angle: new {} old {}", n.max_angle_deg, o.max_angle_deg);
        let s = pg.stats(Side::New);
        assert_eq!(s.mesh.inverted, 0);
        assert_eq!(s.work.passes, 3);
        assert!(s.work.optimization_calls > 0);
        assert_eq!(pg.stats(Side::Old).work.passes, 3);
        pg.reset();
        assert_eq!(pg.stats(Side::New).work.passes, 0);
        assert_eq!(pg.stats(Side::New).mesh.inverted, start);
    }

    #[test]
    fn settings_are_checked_and_kept_on_error() {
        let mut pg = Playground::new(Sample::StarRegular.generate().unwrap()).unwrap();
        let bad = Settings { threshold_deg: 0.0, ..Settings::default() };
        assert!(pg.set_settings(bad).is_err());
        assert!(pg.set_settings(Settings { max_iter: 0, ..Settings::default() }).is_err());
        assert_eq!(pg.settings(), Settings::default());
        let s: Settings =
            serde_json::from_str(r#"{"strategy":"c2","threshold_deg":10,"order":"input","max_iter":5}"#).unwrap();
        pg.set_settings(s).unwrap();
        assert_eq!(pg.settings().strategy, Strategy::C2);
        assert!(serde_json::from_str::<Settings>(
            r#"{"strategy":"magic","threshold_deg":10,"order":"input","max_iter":5}"#
        )
        .is_err());
    }

    #[test]
    fn node_solve_moves_towards_better_and_leaves_the_mesh() {
        let pg = Playground::new(Sample::StarRegular.generate().unwrap()).unwrap();
        let free = pg.topology().node_count() - 1;
        let before = pg.panel(Side::New).mesh.nodes().to_vec();
        let new = pg.solve_node(Side::New, free).unwrap();
        assert!(new.value <= new.value0 && !new.history.is_empty());
        let old = pg.solve_node(Side::Old, free).unwrap();
        assert!(old.value >= old.value0, "max-min: the minimum never drops");
        assert_eq!(pg.panel(Side::New).mesh.nodes(), before);
        assert!(pg.solve_node(Side::New, 0).is_err(), "a fixed node has no solve");
    }

    #[test]
    fn perturb_replaces_the_original_and_resets() {
        let mut pg = Playground::new(Sample::PlateQuad.generate().unwrap()).unwrap();
        pg.step(&no_clock);
        pg.perturb(1.0, 7).unwrap();
        assert!(pg.stats(Side::Old).mesh.inverted > 0);
        assert_eq!(pg.stats(Side::Old).work.passes, 0);
        assert_eq!(pg.panel(Side::New).mesh.nodes(), pg.original_nodes());
        assert!(pg.perturb(f64::NAN, 1).is_err());
    }

    #[test]
    fn export_writes_the_panel_mesh_that_reads_back() {
        let mut pg = Playground::new(Sample::PlateMixedTangled.generate().unwrap()).unwrap();
        pg.step(&no_clock);
        for format in [Format::Msh, Format::Vtk] {
            let text = pg.export(Side::New, format).unwrap();
            let back = crate::io::read_str(&text, format).unwrap();
            assert_eq!(back.node_count(), pg.panel(Side::New).mesh.node_count());
            assert_eq!(back.nodes(), pg.panel(Side::New).mesh.nodes(), "{format:?} keeps the smoothed positions");
            assert_ne!(back.nodes(), pg.panel(Side::Old).mesh.nodes());
        }
    }

    #[test]
    fn dragging_refuses_fixed_unknown_and_non_finite() {
        let mut pg = Playground::new(Sample::StarRegular.generate().unwrap()).unwrap();
        let n = pg.topology().node_count();
        let e = pg.move_node(0, DVec2::ZERO).unwrap_err().to_string();
        assert!(e.contains("node 0") && e.contains("fixed"), "{e}");
        let e = pg.move_node(n, DVec2::ZERO).unwrap_err().to_string();
        assert!(e.contains("no such node"), "{e}");
        assert!(pg.move_node(n - 1, DVec2::new(f64::NAN, 0.0)).is_err());
        assert_eq!(pg.panel(Side::Old).mesh.nodes(), pg.original_nodes(), "a refused move changes nothing");
    }

    #[test]
    fn quadratic_mid_nodes_follow_a_drag() {
        let mut pg = Playground::new(Sample::PlateQuadratic.generate().unwrap()).unwrap();
        let m = pg.topology().clone();
        let free = (0..m.node_count()).find(|&n| m.is_free(n)).unwrap();
        let to = m.nodes()[free] + DVec2::new(0.01, -0.02);
        pg.move_node(free, to).unwrap();
        let moved = &pg.panel(Side::New).mesh;
        for e in m.edges() {
            if e.mid != crate::mesh::NONE && (e.a as usize == free || e.b as usize == free) && !e.curved {
                let mid = 0.5 * (moved.nodes()[e.a as usize] + moved.nodes()[e.b as usize]);
                assert!(moved.nodes()[e.mid as usize].distance(mid) < 1e-12);
            }
        }
    }

    #[test]
    fn versions_name_positions_and_reset_returns_to_the_first() {
        let mut pg = Playground::new(Sample::PlateTri.generate().unwrap()).unwrap();
        let v0 = pg.version(Side::Old);
        assert_eq!(v0, pg.version(Side::New));
        pg.step(&no_clock);
        let v1 = pg.version(Side::Old);
        assert_ne!(v1, v0);
        assert_ne!(pg.version(Side::New), v1, "each panel's positions have their own version");
        let free = (0..pg.topology().node_count()).find(|&n| pg.topology().is_free(n)).unwrap();
        pg.move_node(free, DVec2::new(0.2, 0.3)).unwrap();
        assert_ne!(pg.version(Side::Old), v1);
        assert_eq!(pg.table(Side::Old).mesh, stats::quick_stats(&pg.panel(Side::Old).mesh));
        pg.reset();
        assert_eq!((pg.version(Side::Old), pg.version(Side::New)), (v0, v0));
        assert_eq!(pg.full_stats(Side::New), pg.original_stats());
    }
}
