//! The laboratory: A versus B, side by side. The playground page's state in plain
//! Rust (no web types; the wasm layer and the CLI's `render` both call it): the
//! original mesh, and one copy per side, each smoothed with its own objective — by
//! default the old max-min objective (Freitag 1997) on the left (A) and the new smooth
//! objective (Chen, Tristano & Kwok 2003) on the right (B) — that the page smooths,
//! perturbs and drags side by side ([`settings`]: the sides and what they run). A mesh in
//! space has its own lab, [`Lab3d`], written once for surfaces and tetrahedra.
//!
//! At scale (up to [`MAX_NODES`]): a pass can run in slices of a time budget
//! ([`Playground::begin_pass`], [`Playground::continue_pass`], [`Playground::abort_pass`];
//! the state machine is [`pass`]) with the same result as [`Playground::step`]; each panel keeps the cheap statistics its
//! table shows ([`stats::QuickStats`]) and each element's colour bucket up to date, a
//! version naming its positions, and its last picture ([`raster`] draws fine meshes).

pub mod controls;
pub mod interact;
pub mod lab3d;
pub mod pass;
pub mod permalink;
pub mod pick;
pub mod picture;
pub mod raster;
pub mod sample;
pub mod screen;
pub mod settings;
pub mod stats;
pub mod table;
pub mod tour;
pub mod views;

use std::cell::{OnceCell, RefCell};

use glam::DVec2;
use tiny_skia::Pixmap;

pub use lab3d::{Frame3d, Lab3d, Mesh3d};
pub use pass::{PassProgress, PassStage, SideSweep, SlidePlaces, SlideState};
use pass::{PassRun, RunKind};
pub use settings::{Choice, Settings, Side};
use smoothlab::error::{Error, Result};
use smoothlab::generate::perturb;
use smoothlab::io::{write_string, Format, WriteOptions};
use smoothlab::mesh::{Mesh, FEATURE_ANGLE_DEG};
use smoothlab::objective::Objective;
use smoothlab::optimize::SolveResult;
use smoothlab::quality::MeshStats;
use smoothlab::smooth::{solve_node, Smoother};
use smoothlab::target::Target;
use smoothlab::volume::BoundaryRule;
use smoothlab::BoundaryReport;
use stats::{quick_stats_and_buckets, QuickStats};
pub use table::{
    PanelStats, PanelTable, TableDetail, WorkDone, DETAIL_MAX_ELEMENTS, SMALL_ANGLE_DEG,
};
use views::Canvas;

/// Node count above which the page refuses a mesh: the playground holds two copies (and
/// the positions as loaded) and draws every element each frame.
pub const MAX_NODES: usize = 1_000_000;

/// What one pass did on one panel and where its mesh stands after it: the core's record,
/// without the objective total (the page never shows it, and it costs more than a
/// Laplacian pass).
pub type PassSummary = smoothlab::smooth::PassRecord;

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
    picture: RefCell<Option<(u64, Canvas, smoothlab_render::ZoomPan, Pixmap)>>,
    /// The last report of a sliding boundary, with the version it measured.
    boundary: RefCell<Option<(u64, BoundaryReport)>>,
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
            smoother: Smoother::new(settings.side_options(side, settings::RunStart::of(full))?)?,
            records: Vec::new(),
            version,
            quick: full.quick(),
            buckets,
            full: OnceCell::from(full.clone()),
            picture: RefCell::new(None),
            boundary: RefCell::new(None),
        })
    }

    /// The mesh's positions changed (to a new version).
    fn changed(&mut self, version: u64) {
        self.version = version;
        self.quick = quick_stats_and_buckets(&self.mesh, &mut self.buckets);
        self.full = OnceCell::new();
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
    /// panel's swept positions, what the sweep did and where its nodes were last put on the
    /// boundary (where it slides), until taken.
    swept: Option<(Vec<DVec2>, SideSweep, Option<SlidePlaces>)>,
    /// The user's zoom and pan on the mesh panels (both panels share it).
    zoom: smoothlab_render::ZoomPan,
    /// The part of a star the level-set views show (both sides share it).
    level_window: interact::LevelWindow,
    /// What undo puts back: the latest move last.
    undo: Vec<interact::Undo>,
    /// The colours and label sizes every picture is drawn with.
    theme: smoothlab_render::Theme,
    /// The CSS pixels each side's level-set legend took when it was last drawn, so a
    /// pointer on it maps as it was drawn.
    level_legend: std::cell::Cell<[f32; 2]>,
    /// What the page's screen shows of it: the canvases, the chosen node, the frames sent.
    screen: screen::Screen,
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
        let full = smoothlab::quality::mesh_stats(&mesh);
        let mut buckets = Vec::new();
        quick_stats_and_buckets(&mesh, &mut buckets);
        let original = mesh.nodes().to_vec();
        let bounds = mesh.bounds();
        let mean_edge = mesh.mean_edge_length();
        let old = Panel::new(Side::A, mesh.clone(), &settings, 1, &full, buckets.clone())?;
        let new = Panel::new(Side::B, mesh, &settings, 1, &full, buckets.clone())?;
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
            zoom: smoothlab_render::ZoomPan::default(),
            level_window: interact::LevelWindow::default(),
            undo: Vec::new(),
            theme: smoothlab_render::Theme::light(),
            level_legend: std::cell::Cell::new([0.0; 2]),
            screen: screen::Screen::default(),
        })
    }

    /// The theme every later picture is drawn with.
    pub fn theme(&self) -> smoothlab_render::Theme {
        self.theme
    }

    /// Draws every later picture with `theme`, forgetting the kept mesh pictures.
    pub fn set_theme(&mut self, theme: smoothlab_render::Theme) {
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
    /// progress is abandoned). A new target takes effect at once: with
    /// [`Target::Input`] every corner is measured against the mesh as loaded (or as last
    /// perturbed, [`original_nodes`](Self::original_nodes)), whatever the panels went
    /// through since. A new boundary rule starts both panels again from the mesh as loaded
    /// ([`reset`](Self::reset)): every planar mesh's boundary can slide, a quadratic one's
    /// along its curved edges.
    pub fn set_settings(&mut self, settings: Settings) -> Result<()> {
        let o = [settings.side_options(Side::A, self.run_start())?, settings.side_options(Side::B, self.run_start())?];
        self.abort_pass();
        for (p, side) in self.panels.iter_mut().zip(Side::BOTH) {
            p.smoother = Smoother::new(o[side.index()])?;
            p.objective = settings.choice(side).build();
        }
        let retarget = settings.target != self.settings.target;
        let rebound = settings.boundary != self.settings.boundary;
        self.settings = settings;
        if rebound {
            self.reset(); // which gives both panels the rule, and the target again
        } else if retarget {
            for i in 0..2 {
                self.aim(i);
            }
        }
        Ok(())
    }

    /// The boundary rule a run from the mesh as loaded (or as last perturbed) begins with:
    /// the settings', but a tangled mesh's boundary is held until a pass leaves the panel
    /// valid ([`slide_once_valid`](Self::slide_once_valid)), as `smoothlab smooth
    /// --boundary slide` holds it.
    fn starting_rule(&self) -> BoundaryRule {
        if self.original_stats.inverted > 0 {
            BoundaryRule::Fixed
        } else {
            self.settings.boundary
        }
    }

    /// Lets the boundary of each panel whose last pass left it valid slide, where the
    /// settings slide it and it is still held: taken on the panel's positions now, as
    /// the core's run takes it after such a pass.
    fn slide_once_valid(&mut self) {
        if self.settings.boundary != BoundaryRule::Slide {
            return;
        }
        for p in &mut self.panels {
            if p.mesh.boundary_rule() == BoundaryRule::Fixed && p.records.last().is_some_and(|r| r.after.inverted == 0) {
                p.mesh.set_boundary(BoundaryRule::Slide, FEATURE_ANGLE_DEG);
            }
        }
    }

    /// Where a panel's sliding boundary stands ([`SlideState`]), `None` while it is held.
    /// A split pass hands panel A's to the engine that sweeps
    /// ([`begin_sweep`](Self::begin_sweep)).
    pub fn slide_state(&self, side: Side) -> Option<SlideState> {
        SlideState::of(&self.panel(side).mesh)
    }

    /// A panel's boundary report ([`BoundaryReport::of_planar`], as the core's run
    /// reports it) while its boundary slides; measured once per version of its positions,
    /// and during a pass the one before it.
    fn boundary_report(&self, side: Side) -> Option<BoundaryReport> {
        let p = self.panel(side);
        if p.mesh.boundary_rule() != BoundaryRule::Slide {
            return None;
        }
        let mut kept = p.boundary.borrow_mut();
        match *kept {
            Some((v, r)) if v == p.version || self.run.is_some() => Some(r),
            _ => {
                let r = BoundaryReport::of_planar(&p.mesh);
                *kept = Some((p.version, r));
                Some(r)
            }
        }
    }

    /// The positions every corner is measured against, with the settings' target
    /// ([`Target::Input`]: the mesh as loaded or as last perturbed), x and y interleaved as
    /// [`begin_sweep`](Self::begin_sweep) takes them; `None` with the ideal target.
    pub fn target_positions(&self) -> Option<Vec<f64>> {
        (self.settings.target != Target::Ideal).then(|| interleaved(&self.original))
    }

    /// Where the panels' runs begin ([`settings::RunStart`]): the mesh as loaded or as last
    /// perturbed. A split pass hands it to the engine that sweeps
    /// ([`begin_sweep`](Self::begin_sweep)).
    pub fn run_start(&self) -> settings::RunStart {
        // both panels take every pass: panel A's records count the run's
        settings::RunStart { first_pass: self.panels[0].records.is_empty(), ..settings::RunStart::of(&self.original_stats) }
    }

    /// Gives panel `i`'s mesh the settings' target: the original positions for
    /// [`Target::Input`], none (the ideal of each kind) for [`Target::Ideal`]. They are
    /// never taken from the panel itself, so passes after the first, a drag or a pass
    /// abandoned leave the target where the run began.
    fn aim(&mut self, i: usize) {
        let (target, at) = (self.settings.target, self.original.clone());
        self.panels[i].mesh.set_target_from(target, at);
    }

    /// One smoothing pass on both panels; `clock` gives milliseconds (the core reads no time).
    pub fn step(&mut self, clock: &dyn Fn() -> f64) -> [PassSummary; 2] {
        self.begin_pass();
        loop {
            let p = self
                .continue_pass(clock, f64::INFINITY)
                .expect("a pass was begun");
            if let Some(records) = p.records {
                return records;
            }
        }
    }

    /// Starts a pass to be run in slices by [`continue_pass`](Self::continue_pass)
    /// (a pass already in progress is abandoned first). The result is the same as
    /// [`step`](Self::step)'s, bit for bit: panel A is swept in the order the
    /// smoother plans, then measured, then panel B ([`pass`] runs it).
    pub fn begin_pass(&mut self) {
        self.abort_pass();
        self.undo.clear(); // a move before a pass is not undone over the pass's work
        self.run = Some(PassRun::new());
    }

    /// Starts a pass split between two engines (the page's two workers): this playground
    /// runs panel B's pass as [`begin_pass`](Self::begin_pass) does, while another
    /// one, on the same mesh with the same settings, sweeps panel A
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
    ///
    /// `target` is the other engine's [`target_positions`](Self::target_positions): given
    /// exactly when the settings' target is [`Target::Input`] (the other engine's mesh
    /// may have been perturbed since this one loaded it), and measured against during the
    /// sweep only. `start` is the other engine's [`run_start`](Self::run_start): its
    /// run's, not this one's; `slide` its panel's [`slide_state`](Self::slide_state).
    pub fn begin_sweep(
        &mut self,
        side: Side,
        nodes: &[f64],
        target: Option<&[f64]>,
        start: settings::RunStart,
        slide: Option<&SlideState>,
    ) -> Result<()> {
        self.abort_pass();
        let options = self.settings.side_options(side, start)?;
        let nodes = self.positions_from(nodes)?;
        let target = match (self.settings.target, target) {
            (Target::Input | Target::Stretch, Some(t)) => Some(
                self.positions_from(t)
                    .map_err(|e| Error::invalid(format!("the target's positions: {e}")))?,
            ),
            (Target::Ideal, None) => None,
            (Target::Input | Target::Stretch, None) => {
                return Err(Error::invalid(
                    "the settings measure corners against the mesh as loaded: give its positions with the sweep",
                ))
            }
            (Target::Ideal, Some(_)) => {
                return Err(Error::invalid(
                    "target positions were given, but the settings measure corners against the ideal",
                ))
            }
        };
        self.swept = None;
        let mut run = PassRun::of(RunKind::Sweep(side.index()));
        // the sweep starts from the other engine's positions (and target); the run saves
        // the panel's own positions, and puts them back when the sweep is taken or
        // abandoned (and this playground's target with them: see `abort_pass`)
        run.save(&self.panels);
        let p = &mut self.panels[side.index()];
        if let Err(e) = SlideState::give(slide, &mut p.mesh, &nodes) {
            run.undo(&mut self.panels);
            return Err(e);
        }
        let p = &mut self.panels[side.index()];
        p.smoother = Smoother::new(options)?;
        // the other engine's run's first pass fits the panel to its targets first
        p.smoother.set_fit_pending(start.first_pass);
        if let Some(t) = target {
            p.mesh.set_target_from(self.settings.target, t);
        }
        self.run = Some(run);
        Ok(())
    }

    /// The sweep begun by [`begin_sweep`](Self::begin_sweep), once
    /// [`continue_pass`](Self::continue_pass) said it is done: the swept positions (x, y
    /// interleaved), what the sweep did, and where each node was last put on the boundary
    /// where it slides ([`SlideState::places`]). `None` before that, and after it was taken.
    pub fn take_sweep(&mut self) -> Option<(Vec<f64>, SideSweep, Option<SlidePlaces>)> {
        self.swept
            .take()
            .map(|(nodes, sweep, places)| (interleaved(&nodes), sweep, places))
    }

    /// Hands panel A's sweep, made by another engine, to the split pass in progress
    /// ([`begin_split_pass`](Self::begin_split_pass)): its positions (x, y interleaved),
    /// what it did and, where panel A's boundary slides, where its nodes were last put on
    /// it ([`take_sweep`](Self::take_sweep)'s).
    pub fn adopt_sweep(&mut self, nodes: &[f64], sweep: SideSweep, places: Option<SlidePlaces>) -> Result<()> {
        let nodes = self.positions_from(nodes)?;
        let run = self
            .run
            .as_mut()
            .ok_or_else(|| Error::invalid("no pass is in progress: begin a split pass first"))?;
        run.adopt(&mut self.panels, &mut self.versions, &nodes, sweep, places)
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
            return Err(Error::invalid(format!(
                "node {i} has a coordinate that is not a finite number"
            )));
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
    pub fn continue_pass(
        &mut self,
        clock: &dyn Fn() -> f64,
        budget_ms: f64,
    ) -> Result<PassProgress> {
        let run = self
            .run
            .as_mut()
            .ok_or_else(|| Error::invalid("no pass is in progress: begin one first"))?;
        if run.advance(&mut self.panels, &mut self.versions, clock, budget_ms) {
            let run = self.run.take().expect("the pass just advanced");
            if run.is_sweep() {
                let side = run.side();
                self.swept = Some(run.finish_sweep(&mut self.panels));
                self.aim(side.index()); // its own target back, after the other engine's
                return Ok(PassProgress::swept(side));
            }
            let done = run.finish(&mut self.panels, &mut self.versions);
            self.slide_once_valid();
            return Ok(done);
        }
        Ok(run.progress(&self.panels))
    }

    /// Abandons the pass in progress, if any: both panels go back to where they were
    /// before it (positions, statistics and version), so it leaves no trace.
    pub fn abort_pass(&mut self) {
        if let Some(run) = self.run.take() {
            let swept = run.is_sweep().then(|| run.side());
            run.undo(&mut self.panels);
            if let Some(side) = swept {
                self.aim(side.index()); // a sweep measured against the other engine's target
            }
        }
    }

    /// The original mesh perturbed ([`perturb`]: `amount` mean edge lengths, seeded);
    /// both panels start again from it.
    pub fn perturb(&mut self, amount: f64, seed: u64) -> Result<()> {
        self.abort_pass();
        let mesh = &mut self.panels[0].mesh;
        mesh.nodes_mut().copy_from_slice(&self.original);
        // the interior only, whatever the rule: a sliding node is free, but not to be
        // thrown off the boundary (the reset below takes the rule again)
        mesh.set_boundary(BoundaryRule::Fixed, FEATURE_ANGLE_DEG);
        let perturbed = perturb(mesh, amount, seed)?;
        self.original_stats = smoothlab::quality::mesh_stats(&perturbed);
        quick_stats_and_buckets(&perturbed, &mut self.original_buckets);
        self.mean_edge = perturbed.mean_edge_length();
        self.original = perturbed.nodes().to_vec();
        self.original_version = self.fresh_version();
        self.reset();
        Ok(())
    }

    /// A panel's current mesh as arrays ([`smoothlab::io::MeshArrays`]: what its `.vtk` text holds).
    pub fn arrays(&self, side: Side) -> smoothlab::io::MeshArrays {
        smoothlab::io::mesh_arrays(&self.panel(side).mesh)
    }

    /// A panel's current mesh as the text of a `.msh` (2.2) or `.vtk` file.
    pub fn export(&self, side: Side, format: Format) -> Result<String> {
        write_string(&self.panel(side).mesh, format, &WriteOptions::default())
    }

    /// Solves one node of a panel's mesh with the solver's history (for the level-set view),
    /// without moving it.
    pub fn solve_node(&self, side: Side, node: usize) -> Result<SolveResult> {
        let p = self.panel(side);
        solve_node(
            &p.mesh,
            node,
            p.objective.as_ref(),
            &self.settings.side_options(side, self.run_start())?,
        )
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
        p.full
            .get_or_init(|| smoothlab::quality::mesh_stats(&p.mesh))
    }

    /// Statistics of a panel's current mesh, with the work done since the last reset.
    pub fn stats(&self, side: Side) -> PanelStats {
        PanelStats {
            side,
            mesh: self.full_stats(side).clone(),
            work: WorkDone::of(&self.panel(side).records),
        }
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
        (p.mesh.element_count() <= DETAIL_MAX_ELEMENTS)
            .then(|| TableDetail::of(self.full_stats(side)))
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
            boundary: self.boundary_report(side),
            work: WorkDone::of(&p.records),
        }
    }

    /// Both panels back to the original mesh, their records cleared, their boundary under
    /// the rule a run begins with: the settings', but held while the mesh is tangled.
    pub fn reset(&mut self) {
        self.abort_pass();
        self.undo.clear();
        let o = Side::BOTH.map(|side| self.settings.side_options(side, self.run_start()).expect("the settings were checked when set"));
        let quick = self.original_stats.quick();
        let rule = self.starting_rule();
        for (p, o) in self.panels.iter_mut().zip(o) {
            p.mesh.nodes_mut().copy_from_slice(&self.original);
            p.mesh.set_boundary(rule, FEATURE_ANGLE_DEG);
            p.version = self.original_version;
            p.quick = quick;
            p.buckets.clone_from(&self.original_buckets);
            p.full = OnceCell::from(self.original_stats.clone());
            p.records.clear();
            p.smoother = Smoother::new(o).expect("the settings were checked when set");
        }
        // the original may be new (a perturbation): the target is taken from it again
        if self.settings.target != Target::Ideal {
            for i in 0..2 {
                self.aim(i);
            }
        }
    }

    /// Moves a free node to `to` on both panels' current meshes (the mouse drag); its
    /// mid-side nodes follow. Fixed nodes, mid-side nodes and unknown nodes are refused.
    pub fn move_node(&mut self, node: usize, to: DVec2) -> Result<()> {
        self.check_movable(node)?;
        if !to.is_finite() {
            return Err(Error::invalid(format!(
                "cannot move node {node} to a non-finite position {to}"
            )));
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
            return Err(Error::node(
                node,
                None,
                format!("no such node: the mesh has {} nodes", m.node_count()),
            ));
        }
        if m.boundary_node(node).is_some_and(|c| c.slides()) {
            return Err(Error::node(node, None, "slides along the boundary with the passes, so it cannot be dragged"));
        }
        if !m.is_free(node) {
            return Err(Error::node(
                node,
                None,
                "is fixed or a mid-side node, so it cannot be dragged",
            ));
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
    use smoothlab::smooth::Strategy;

    #[test]
    fn panels_start_equal_and_reset_restores_them() {
        let mut pg = Playground::new(Sample::PlateTriTangled.generate().unwrap()).unwrap();
        let before = pg.stats(Side::A);
        assert_eq!(before.mesh, pg.stats(Side::B).mesh);
        assert!(before.mesh.inverted > 0);
        let free = (0..pg.topology().node_count())
            .find(|&n| pg.topology().is_free(n))
            .unwrap();
        pg.move_node(free, DVec2::new(0.9, 0.9)).unwrap();
        for s in Side::BOTH {
            assert_eq!(pg.panel(s).mesh.nodes()[free], DVec2::new(0.9, 0.9));
        }
        pg.reset();
        assert_eq!(pg.stats(Side::A), before);
        assert_eq!(pg.panel(Side::B).mesh.nodes(), pg.original_nodes());
    }

    fn no_clock() -> f64 {
        0.0
    }

    #[test]
    fn one_step_on_the_opening_sample_leaves_old_inverted_and_new_untangled() {
        let mut pg = Playground::new(Sample::DEFAULT.generate().unwrap()).unwrap();
        assert_eq!((pg.topology().element_count(), pg.stats(Side::B).mesh.inverted), (400, 219), "HARD_TANGLE_AMOUNT's words");
        let [old, new] = pg.step(&no_clock);
        assert_eq!((old.after.inverted, new.after.inverted), (15, 0), "the opening's lesson");
        assert_eq!(pg.full_stats(Side::A).inverted, 15);
    }

    #[test]
    fn three_passes_untangle_the_tangled_plate_on_the_new_side() {
        let mut pg = Playground::new(Sample::DEFAULT.generate().unwrap()).unwrap();
        let start = pg.stats(Side::B).mesh.inverted;
        assert!(start > 0);
        let mut last = None;
        for _ in 0..3 {
            last = Some(pg.step(&no_clock));
        }
        let [old, new] = last.unwrap();
        assert_eq!((old.pass, new.pass), (3, 3));
        assert_eq!(
            new.after.inverted, 0,
            "Chen et al. untangle the perturbed plate in 3 passes"
        );
        // the page's default sample (issue 11): the new side beats the max-min objective on
        // what both sides are judged by: smallest and largest angle, worst and mean quality
        let (o, n) = (
            pg.full_stats(Side::A).clone(),
            pg.full_stats(Side::B).clone(),
        );
        assert!(
            n.min_angle_deg > o.min_angle_deg,
            "min angle: new {} old {}",
            n.min_angle_deg,
            o.min_angle_deg
        );
        assert!(
            n.min_quality > o.min_quality,
            "min quality: new {} old {}",
            n.min_quality,
            o.min_quality
        );
        assert!(
            n.mean_quality > o.mean_quality + 0.01,
            "mean quality: new {} old {}",
            n.mean_quality,
            o.mean_quality
        );
        assert!(
            n.max_angle_deg < o.max_angle_deg - 1.0,
            "max angle: new {} old {}",
            n.max_angle_deg,
            o.max_angle_deg
        );
        let s = pg.stats(Side::B);
        assert_eq!(s.mesh.inverted, 0);
        assert_eq!(s.work.passes, 3);
        assert!(s.work.optimization_calls > 0);
        assert_eq!(pg.stats(Side::A).work.passes, 3);
        pg.reset();
        assert_eq!(pg.stats(Side::B).work.passes, 0);
        assert_eq!(pg.stats(Side::B).mesh.inverted, start);
    }

    #[test]
    fn settings_are_checked_and_kept_on_error() {
        let mut pg = Playground::new(Sample::StarRegular.generate().unwrap()).unwrap();
        let bad = Settings {
            threshold_deg: 0.0,
            ..Settings::default()
        };
        assert!(pg.set_settings(bad).is_err());
        assert!(pg
            .set_settings(Settings {
                max_iter: 0,
                ..Settings::default()
            })
            .is_err());
        assert_eq!(pg.settings(), Settings::default());
        let s: Settings = serde_json::from_str(
            r#"{"strategy":"c2","threshold_deg":10,"order":"input","max_iter":5}"#,
        )
        .unwrap();
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
        let before = pg.panel(Side::B).mesh.nodes().to_vec();
        let new = pg.solve_node(Side::B, free).unwrap();
        assert!(new.value <= new.value0 && !new.history.is_empty());
        let old = pg.solve_node(Side::A, free).unwrap();
        assert!(old.value >= old.value0, "max-min: the minimum never drops");
        assert_eq!(pg.panel(Side::B).mesh.nodes(), before);
        assert!(
            pg.solve_node(Side::B, 0).is_err(),
            "a fixed node has no solve"
        );
    }

    #[test]
    fn perturb_replaces_the_original_and_resets() {
        let mut pg = Playground::new(Sample::PlateQuad.generate().unwrap()).unwrap();
        pg.step(&no_clock);
        pg.perturb(1.0, 7).unwrap();
        assert!(pg.stats(Side::A).mesh.inverted > 0);
        assert_eq!(pg.stats(Side::A).work.passes, 0);
        assert_eq!(pg.panel(Side::B).mesh.nodes(), pg.original_nodes());
        assert!(pg.perturb(f64::NAN, 1).is_err());
    }

    #[test]
    fn export_writes_the_panel_mesh_that_reads_back() {
        let mut pg = Playground::new(Sample::PlateMixedTangled.generate().unwrap()).unwrap();
        pg.step(&no_clock);
        for format in [Format::Msh, Format::Vtk] {
            let text = pg.export(Side::B, format).unwrap();
            let back = smoothlab::io::read_str(&text, format).unwrap();
            assert_eq!(back.node_count(), pg.panel(Side::B).mesh.node_count());
            assert_eq!(
                back.nodes(),
                pg.panel(Side::B).mesh.nodes(),
                "{format:?} keeps the smoothed positions"
            );
            assert_ne!(back.nodes(), pg.panel(Side::A).mesh.nodes());
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
        assert_eq!(
            pg.panel(Side::A).mesh.nodes(),
            pg.original_nodes(),
            "a refused move changes nothing"
        );
    }

    #[test]
    fn quadratic_mid_nodes_follow_a_drag() {
        let mut pg = Playground::new(Sample::PlateQuadratic.generate().unwrap()).unwrap();
        let m = pg.topology().clone();
        let free = (0..m.node_count()).find(|&n| m.is_free(n)).unwrap();
        let to = m.nodes()[free] + DVec2::new(0.01, -0.02);
        pg.move_node(free, to).unwrap();
        let moved = &pg.panel(Side::B).mesh;
        for e in m.edges() {
            if e.mid != smoothlab::mesh::NONE
                && (e.a as usize == free || e.b as usize == free)
                && !e.curved
            {
                let mid = 0.5 * (moved.nodes()[e.a as usize] + moved.nodes()[e.b as usize]);
                assert!(moved.nodes()[e.mid as usize].distance(mid) < 1e-12);
            }
        }
    }

    /// The command-line tool's run on `mesh` (`smoothlab smooth --target T --boundary B
    /// --passes N --finish 0`) with a side's settings: its positions after the passes.
    fn smoothed_as_the_cli(mesh: &Mesh, settings: Settings, side: Side, passes: u32) -> Mesh {
        run_as_the_cli(mesh, settings, side, passes).0
    }

    /// [`smoothed_as_the_cli`], with the run's report.
    fn run_as_the_cli(mesh: &Mesh, settings: Settings, side: Side, passes: u32) -> (Mesh, smoothlab::Report) {
        let c = settings.choice(side);
        let mut model = smoothlab::Model::Planar(mesh.clone());
        // the page's threshold is the tool's default, and only new takes a penalty
        assert_eq!(settings.threshold_deg, Settings::default().threshold_deg);
        let mut smoothing = smoothlab::Smoothing::default()
            .objective(c.objective)
            .strategy(settings.strategy)
            .order(settings.order)
            .max_iter(settings.max_iter)
            .target(settings.target)
            .boundary(settings.boundary)
            .passes(passes)
            .finish(0);
        if c.objective == smoothlab::ObjectiveKind::SmoothShape {
            smoothing = smoothing.penalty(c.penalty);
        }
        let report = model.smooth(&smoothing).unwrap();
        let smoothlab::Model::Planar(m) = model else {
            unreachable!()
        };
        (m, report)
    }

    #[test]
    fn a_sliding_boundary_steps_as_the_cli_takes_it_valid_or_tangled() {
        // the quad plate perturbed a little (valid: its boundary slides from the first
        // pass) and heavily (tangled: held until a pass leaves a side valid, then sliding)
        let slide = Settings { boundary: BoundaryRule::Slide, ..Settings::default() };
        for (amount, tangled) in [(0.3, false), (0.8, true)] {
            let mut pg = Playground::new(Sample::PlateQuad.generate().unwrap()).unwrap();
            pg.perturb(amount, 5).unwrap();
            assert_eq!(pg.original_stats().inverted > 0, tangled, "{amount}");
            let loaded = pg.topology().clone();
            pg.set_settings(slide).unwrap();
            let on_boundary: Vec<usize> = (0..loaded.node_count()).filter(|&n| loaded.is_boundary(n)).collect();
            let boundary_moved = |m: &Mesh| on_boundary.iter().filter(|&&n| m.nodes()[n] != loaded.nodes()[n]).count();
            for pass in 1..=2 {
                // settings between passes (the page sends them before each Step) change nothing
                pg.set_settings(slide).unwrap();
                pg.step(&no_clock);
                if pass == 1 {
                    for side in Side::BOTH {
                        let moved = boundary_moved(&pg.panel(side).mesh);
                        assert_eq!(moved == 0, tangled, "{amount} {side:?}: {moved} boundary nodes moved in the first pass");
                    }
                }
            }
            let mut slid = 0;
            for side in Side::BOTH {
                let what = format!("{amount} {side:?}");
                let (cli, report) = run_as_the_cli(&loaded, slide, side, 2);
                let m = &pg.panel(side).mesh;
                assert_eq!(m.nodes(), cli.nodes(), "{what}");
                assert_eq!(pg.table(side).boundary.as_ref(), report.boundary(), "{what}");
                for n in (0..m.node_count()).filter(|&n| !m.is_free(n)) {
                    assert_eq!(m.nodes()[n], loaded.nodes()[n], "{what}: node {n} is held, but moved");
                }
                slid += boundary_moved(m);
            }
            assert!(slid > 10, "{amount}: {slid} boundary nodes slid");
            let b = pg.table(Side::B).boundary.expect("B's boundary slides");
            assert!(b.corners == 4 && b.curve_nodes > 20 && b.max_distance < 1e-12 * b.mean_edge, "{b:?}");
            // a perturbation moves the interior only; fixed holds the boundary again
            pg.perturb(0.2, 9).unwrap();
            assert!(on_boundary.iter().all(|&n| pg.original_nodes()[n] == loaded.nodes()[n]), "the perturbation moved the boundary");
            pg.set_settings(Settings::default()).unwrap();
            pg.step(&no_clock);
            for side in Side::BOTH {
                assert!(pg.slide_state(side).is_none() && pg.table(side).boundary.is_none());
                assert_eq!(boundary_moved(&pg.panel(side).mesh), 0, "{side:?}: fixed, yet the boundary moved");
            }
        }
    }

    #[test]
    fn a_sliding_node_is_neither_dragged_nor_chosen_linear_or_quadratic() {
        for sample in [Sample::PlateTri, Sample::PlateQuadratic] {
            let mut pg = Playground::new(sample.generate().unwrap()).unwrap();
            pg.set_settings(Settings { boundary: BoundaryRule::Slide, ..Settings::default() }).unwrap();
            assert_eq!(pg.settings().boundary, BoundaryRule::Slide, "{sample:?}");
            let m = pg.topology().clone();
            let sliding = (0..m.node_count()).find(|&n| m.boundary_node(n).is_some_and(|c| c.slides())).unwrap();
            let e = pg.move_node(sliding, DVec2::ZERO).unwrap_err().to_string();
            assert!(e.contains("slides along the boundary"), "{sample:?}: {e}");
            let why = pick::why_not_free(&m, sliding).unwrap();
            assert!(why.contains("slides along the boundary"), "{sample:?}: {why}");
            assert!(pick::worst_free_node(&m).is_some_and(|n| !m.is_boundary(n)), "{sample:?}");
            // a boundary edge's mid-side node is no more draggable than it was
            if let Some(mid) = m.topology().boundary_edges().map(|e| e.mid as usize).find(|&v| v != smoothlab::mesh::NONE as usize) {
                assert!(pg.move_node(mid, DVec2::ZERO).is_err(), "{sample:?}");
            }
            assert_eq!(pg.panel(Side::A).mesh.nodes(), pg.original_nodes(), "{sample:?}: a refused drag changes nothing");
        }
    }

    /// The quadratic plate (6-node triangles, its hole a curved boundary) perturbed a
    /// little (valid) or heavily (tangled), as the page holds it with the boundary sliding.
    fn sliding_quadratic_plate(amount: f64) -> Playground {
        let mut pg = Playground::new(Sample::PlateQuadratic.generate().unwrap()).unwrap();
        pg.perturb(amount, 5).unwrap();
        pg.set_settings(Settings { boundary: BoundaryRule::Slide, ..Settings::default() }).unwrap();
        pg
    }

    #[test]
    fn a_quadratic_mesh_s_boundary_steps_as_the_cli_slides_it_valid_or_tangled() {
        // Chen's curved boundaries on the page: each boundary edge is the quadratic through
        // its corners and mid-side node, a sliding corner carries its edges' mid-side nodes;
        // the page's Steps are `Model::smooth`'s to the bit, report included, and a tangled
        // plate's boundary is held until a pass leaves a side valid
        let slide = Settings { boundary: BoundaryRule::Slide, ..Settings::default() };
        for (amount, tangled) in [(0.3, false), (0.6, true)] {
            let mut pg = sliding_quadratic_plate(amount);
            assert!(pg.topology().has_quadratic());
            assert_eq!(pg.original_stats().inverted > 0, tangled, "{amount}");
            let loaded = pg.topology().clone();
            let mut on_boundary: Vec<usize> = loaded.topology().boundary_edges().flat_map(|e| [e.a, e.mid, e.b]).map(|v| v as usize).collect();
            on_boundary.sort_unstable();
            on_boundary.dedup();
            let mids: Vec<usize> = loaded.topology().boundary_edges().map(|e| e.mid as usize).collect();
            let moved = |m: &Mesh, nodes: &[usize]| nodes.iter().filter(|&&n| m.nodes()[n] != loaded.nodes()[n]).count();
            for pass in 1..=3 {
                pg.set_settings(slide).unwrap();
                pg.step(&no_clock);
                if pass == 1 {
                    for side in Side::BOTH {
                        let n = moved(&pg.panel(side).mesh, &on_boundary);
                        assert_eq!(n == 0, tangled, "{amount} {side:?}: {n} boundary nodes moved in the first pass");
                    }
                }
                for side in Side::BOTH {
                    let what = format!("{amount} pass {pass} {side:?}");
                    let (cli, report) = run_as_the_cli(&loaded, slide, side, pass);
                    let m = &pg.panel(side).mesh;
                    let bits = |m: &Mesh| m.nodes().iter().map(|p| [p.x.to_bits(), p.y.to_bits()]).collect::<Vec<_>>();
                    assert_eq!(bits(m), bits(&cli), "{what}");
                    assert_eq!(pg.table(side).boundary.as_ref(), report.boundary(), "{what}");
                    assert_eq!(pg.panel(side).records.last().unwrap().after.inverted, report.stats().inverted, "{what}");
                }
            }
            for side in Side::BOTH {
                let m = &pg.panel(side).mesh;
                let (all, carried) = (moved(m, &on_boundary), moved(m, &mids));
                assert!(all > carried && carried > 10, "{amount} {side:?}: {all} boundary nodes moved, {carried} of them mid-side nodes");
                let b = pg.table(side).boundary.expect("the boundary slides");
                assert!(b.corners == 4 && b.curve_nodes > 20 && b.max_distance < 1e-9 * b.mean_edge, "{amount} {side:?}: {b:?}");
            }
            // Reset puts the boundary back as loaded, sliding (or held while tangled)
            pg.reset();
            for side in Side::BOTH {
                assert_eq!(moved(&pg.panel(side).mesh, &on_boundary), 0, "{amount} {side:?}");
                assert_eq!(pg.slide_state(side).is_some(), !tangled, "{amount} {side:?}");
            }
        }
    }

    #[test]
    fn the_stretch_target_steps_as_the_cli_takes_it() {
        // rows graded ×1.6 from the wall, the interior moved a little: stretched on purpose
        let mut m = smoothlab::generate::grid(10, 8, smoothlab::generate::GridKind::Quad).unwrap();
        for p in m.nodes_mut() {
            p.y = (1.6f64.powf(p.y * 8.0) - 1.0) / (1.6f64.powi(8) - 1.0);
        }
        let mut pg = Playground::new(m).unwrap();
        pg.perturb(0.05, 3).unwrap();
        assert_eq!(pg.original_stats().inverted, 0);
        let mesh = pg.topology().clone();
        let settings = Settings { target: Target::Stretch, ..Settings::default() };
        pg.set_settings(settings).unwrap();
        pg.reset();
        for _ in 0..2 {
            pg.step(&no_clock);
        }
        for side in Side::BOTH {
            let cli = smoothed_as_the_cli(&mesh, settings, side, 2);
            assert_eq!(pg.panel(side).mesh.nodes(), cli.nodes(), "{side:?}");
            let ideal = smoothed_as_the_cli(&mesh, Settings { target: Target::Ideal, ..settings }, side, 2);
            assert_ne!(cli.nodes(), ideal.nodes(), "{side:?}: the layer is read as stretched");
        }
    }

    #[test]
    fn the_input_target_is_the_mesh_as_loaded_for_the_whole_run_as_the_cli_takes_it() {
        // the plate's O-grid of quads, tangled: its corners are not squares, so the two
        // targets lead to different meshes, and the inverted ones move the nodes in every
        // pass against the input too
        let mut pg = Playground::new(Sample::PlateQuad.generate().unwrap()).unwrap();
        pg.perturb(0.8, 5).unwrap();
        assert!(pg.original_stats().inverted > 0);
        let loaded = pg.original_nodes().to_vec();
        let mesh = pg.topology().clone();
        for strategy in [Strategy::Rules, Strategy::Opt] {
            let settings = Settings {
                strategy,
                target: Target::Input,
                ..Settings::default()
            };
            pg.set_settings(settings).unwrap();
            pg.reset();
            for side in Side::BOTH {
                assert_eq!(pg.panel(side).mesh.target_nodes(), Some(&loaded[..]));
            }
            for _ in 0..3 {
                pg.step(&no_clock);
            }
            for side in Side::BOTH {
                let what = format!("{strategy:?} {side:?}");
                // not taken again from the positions of a later pass
                assert_eq!(
                    pg.panel(side).mesh.target_nodes(),
                    Some(&loaded[..]),
                    "{what}"
                );
                let cli = smoothed_as_the_cli(&mesh, settings, side, 3);
                assert_eq!(pg.panel(side).mesh.nodes(), cli.nodes(), "{what}");
                // a target taken again before every pass would be another run
                let mut again = mesh.clone();
                for _ in 0..3 {
                    again = smoothed_as_the_cli(&again, settings, side, 1);
                }
                assert_ne!(again.nodes(), cli.nodes(), "{what}: the retaken target");
                let ideal = smoothed_as_the_cli(
                    &mesh,
                    Settings {
                        target: Target::Ideal,
                        ..settings
                    },
                    side,
                    3,
                );
                assert_ne!(cli.nodes(), ideal.nodes(), "{what}: the target matters");
            }
        }
        // a drag moves a node, not the target; back to the ideal, no target is left
        let free = (0..mesh.node_count()).find(|&n| mesh.is_free(n)).unwrap();
        pg.move_node(free, pg.original_nodes()[free] + DVec2::splat(0.01))
            .unwrap();
        pg.step(&no_clock);
        assert_eq!(pg.panel(Side::A).mesh.target_nodes(), Some(&loaded[..]));
        let ideal = Settings {
            target: Target::Ideal,
            ..pg.settings()
        };
        pg.set_settings(ideal).unwrap();
        assert!(Side::BOTH
            .iter()
            .all(|&s| pg.panel(s).mesh.target_nodes().is_none()));
        assert_eq!(pg.target_positions(), None);
        // a new perturbation is the new target
        pg.set_settings(Settings {
            target: Target::Input,
            ..ideal
        })
        .unwrap();
        pg.perturb(0.2, 9).unwrap();
        assert_ne!(pg.original_nodes(), &loaded[..]);
        assert_eq!(
            pg.panel(Side::B).mesh.target_nodes(),
            Some(pg.original_nodes())
        );
        assert_eq!(
            pg.target_positions(),
            Some(interleaved(pg.original_nodes()))
        );
        // a strategy that takes Laplacian steps refuses it, and the settings stay
        let before = pg.settings();
        let e = pg
            .set_settings(Settings {
                strategy: Strategy::C1,
                ..before
            })
            .unwrap_err()
            .to_string();
        assert!(e.contains("Freitag's C1 takes Laplacian steps"), "{e}");
        assert_eq!(pg.settings(), before);
    }

    #[test]
    fn the_ideal_target_leaves_every_pass_as_it_was() {
        let mesh = Sample::PlateMixedTangled.generate().unwrap();
        let mut pg = Playground::new(mesh.clone()).unwrap();
        for _ in 0..2 {
            pg.step(&no_clock);
        }
        for side in Side::BOTH {
            assert!(pg.panel(side).mesh.target_nodes().is_none());
            let cli = smoothed_as_the_cli(&mesh, Settings::default(), side, 2);
            assert_eq!(pg.panel(side).mesh.nodes(), cli.nodes(), "{side:?}");
        }
    }

    #[test]
    fn versions_name_positions_and_reset_returns_to_the_first() {
        let mut pg = Playground::new(Sample::PlateTri.generate().unwrap()).unwrap();
        let v0 = pg.version(Side::A);
        assert_eq!(v0, pg.version(Side::B));
        pg.step(&no_clock);
        let v1 = pg.version(Side::A);
        assert_ne!(v1, v0);
        assert_ne!(
            pg.version(Side::B),
            v1,
            "each panel's positions have their own version"
        );
        let free = (0..pg.topology().node_count())
            .find(|&n| pg.topology().is_free(n))
            .unwrap();
        pg.move_node(free, DVec2::new(0.2, 0.3)).unwrap();
        assert_ne!(pg.version(Side::A), v1);
        assert_eq!(
            pg.table(Side::A).mesh,
            stats::quick_stats(&pg.panel(Side::A).mesh)
        );
        pg.reset();
        assert_eq!((pg.version(Side::A), pg.version(Side::B)), (v0, v0));
        assert_eq!(pg.full_stats(Side::B), pg.original_stats());
    }
}
