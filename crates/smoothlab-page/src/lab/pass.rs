//! A pass in slices: the state machine that runs one smoothing pass on both panels a
//! time budget at a time (plan the visit order, visit the nodes, run any untangling
//! sweeps, measure), so the page can show progress and answer Stop during a pass on a
//! large mesh. The result is [`Smoother::pass`](smoothlab::smooth::Smoother::pass)'s, bit
//! for bit; the playground ([`super::Playground::begin_pass`], `continue_pass`,
//! `abort_pass`) only holds the run.
//!
//! The two panels' sweeps are independent, so a pass can also be *split* between two
//! engines (the page's two workers, on two cores): one playground sweeps panel A
//! alone ([`super::Playground::begin_sweep`], no statistics, the panel put back after),
//! while the other runs a split pass ([`super::Playground::begin_split_pass`]): the new
//! panel as usual, then panel A's sweep adopted from the first
//! ([`super::Playground::adopt_sweep`]) and measured. The records and positions are the
//! whole pass's, bit for bit.

use std::cell::OnceCell;

use glam::DVec2;
use serde::{Deserialize, Serialize};

use super::stats::{QuickAcc, QuickStats};
use super::{Panel, PassSummary, Side, Versions};
use smoothlab::error::{Error, Result};
use smoothlab::mesh::{Mesh, FEATURE_ANGLE_DEG};
use smoothlab::quality::MeshStats;
use smoothlab::smooth::SweepCounts;
use smoothlab::volume::BoundaryRule;

/// Elements measured per slice of a pass's statistics.
const STATS_SLICE: usize = 32 * 1024;

/// Where a pass in slices stands (see [`super::Playground::continue_pass`]).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PassProgress {
    /// The pass is complete (`records` holds its two records) and the meshes are final.
    pub done: bool,
    /// Of the whole pass (both panels), 0 to 1.
    pub fraction: f64,
    /// The panel being smoothed or measured.
    pub side: Side,
    /// What the pass is doing on that panel.
    pub stage: PassStage,
    /// Node visits done on this panel and planned for it.
    pub visits: usize,
    pub planned: usize,
    /// `[old, new]` when done.
    pub records: Option<[PassSummary; 2]>,
}

/// What a pass in slices is doing, as the page is told ([`PassProgress::stage`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum PassStage {
    /// Planning the visit order (the priority order measures every star).
    Plan,
    /// Visiting the nodes (the planned visits, then any untangling sweeps).
    Smooth,
    /// Measuring the smoothed mesh's statistics.
    Measure,
    /// A split pass waits for the other engine's sweep of panel A
    /// ([`super::Playground::adopt_sweep`]).
    Wait,
    /// The pass is complete.
    Done,
}

/// The sweep of one panel by another engine, for [`super::Playground::adopt_sweep`]: what
/// its node loop did and how long it took (the positions travel beside it).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SideSweep {
    pub counts: SweepCounts,
    /// The node loop's time (planning included), milliseconds.
    pub sweep_ms: f64,
}

/// Where a panel's sliding boundary stands, as a split pass hands it to the engine that
/// sweeps and an abandoned pass puts it back: the positions the boundary was taken from,
/// the boundary segment each node was last put on and, for a quadratic mesh, where on it
/// (the core's [`Mesh::boundary_taken_from`], [`Mesh::boundary_segments`] and
/// [`Mesh::boundary_parameters`]).
#[derive(Clone, Debug, PartialEq)]
pub struct SlideState {
    pub from: Vec<DVec2>,
    pub places: SlidePlaces,
}

/// Where each node of a sliding boundary was last put: its segment ([`NONE`](smoothlab::mesh::NONE)
/// for a node that does not slide) and, on a quadratic mesh, its parameter along it (the
/// mid-side nodes a sliding node carries are placed from them); `params` is empty for a
/// linear mesh.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SlidePlaces {
    pub segments: Vec<u32>,
    pub params: Vec<f64>,
}

impl SlidePlaces {
    /// `mesh`'s; `None` while its boundary is held.
    pub fn of(mesh: &Mesh) -> Option<SlidePlaces> {
        let segments = mesh.boundary_segments()?.to_vec();
        Some(SlidePlaces { segments, params: mesh.boundary_parameters().map_or_else(Vec::new, <[f64]>::to_vec) })
    }
}

impl SlideState {
    /// `mesh`'s; `None` while its boundary is held.
    pub fn of(mesh: &Mesh) -> Option<SlideState> {
        Some(SlideState { from: mesh.boundary_taken_from()?.to_vec(), places: SlidePlaces::of(mesh)? })
    }

    /// Puts `mesh` at `nodes` (one a node) with its boundary as `state` says: held for
    /// `None`, else taken from `state.from` (again only where it was taken from other
    /// positions) with its nodes where `state.places` says. A state that does not fit the
    /// mesh is refused; the mesh must then be put back.
    pub(super) fn give(state: Option<&SlideState>, mesh: &mut Mesh, nodes: &[DVec2]) -> Result<()> {
        let Some(s) = state else {
            mesh.set_boundary(BoundaryRule::Fixed, FEATURE_ANGLE_DEG);
            mesh.nodes_mut().copy_from_slice(nodes);
            return Ok(());
        };
        if s.from.len() != mesh.node_count() || !s.from.iter().all(|p| p.is_finite()) {
            return Err(Error::invalid(format!(
                "the boundary was taken from {} positions for a mesh of {} nodes: give one finite position a node",
                s.from.len(),
                mesh.node_count()
            )));
        }
        if mesh.boundary_taken_from() != Some(&s.from[..]) {
            mesh.nodes_mut().copy_from_slice(&s.from);
            mesh.set_boundary(BoundaryRule::Slide, FEATURE_ANGLE_DEG);
        }
        mesh.nodes_mut().copy_from_slice(nodes);
        mesh.set_boundary_segments(&s.places.segments, &s.places.params)
    }
}

/// Which part of a pass a run does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum RunKind {
    /// Both panels: the old one, then the new one.
    Whole,
    /// Panel B, then A's sweep adopted from another engine and measured.
    Split,
    /// The sweep of one panel alone, without statistics, for another engine.
    Sweep(usize),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Stage {
    /// Save the panel and begin planning its visit order.
    Plan,
    /// Plan in slices (the priority order measures every star).
    Planning,
    Smooth,
    Measure,
}

/// A panel as it was when a pass began on it, to put back if the pass is abandoned.
struct Saved {
    nodes: Vec<DVec2>,
    slide: Option<SlideState>,
    version: u64,
    quick: QuickStats,
    buckets: Vec<u8>,
    full: OnceCell<MeshStats>,
}

impl Saved {
    fn of(p: &Panel) -> Saved {
        Saved {
            nodes: p.mesh.nodes().to_vec(),
            slide: SlideState::of(&p.mesh),
            version: p.version,
            quick: p.quick,
            buckets: p.buckets.clone(),
            full: p.full.clone(),
        }
    }
}

impl PassProgress {
    /// A sweep for another engine, complete (its result is taken apart from this).
    pub(super) fn swept(side: Side) -> PassProgress {
        PassProgress {
            done: true,
            fraction: 1.0,
            side,
            stage: PassStage::Done,
            visits: 0,
            planned: 0,
            records: None,
        }
    }
}

/// A pass in progress: panel A's sweep and statistics, then panel B's (in
/// the order of [`RunKind`]).
pub(super) struct PassRun {
    kind: RunKind,
    /// The panels in the order the run takes them, and how many of them it has done.
    order: [usize; 2],
    k: usize,
    /// Panel A's sweep by another engine, once a split run adopted it; a sweep run's
    /// own, once made.
    sweep: Option<SideSweep>,
    stage: Stage,
    schedule: Vec<u32>,
    pos: usize,
    counts: SweepCounts,
    sweep_ms: f64,
    acc: QuickAcc,
    stats_ms: f64,
    /// Node visits per slice, adapted to the time they take.
    slice: usize,
    /// Stars measured per planning slice, adapted likewise.
    plan_slice: usize,
    /// The schedule is an untangling sweep's (after the planned visits).
    untangling: bool,
    saved: [Option<Saved>; 2],
    /// The steps each panel's fit to the targets kept before its sweep (0 but at a run's
    /// first pass against a target: [`smoothlab::smooth::Smoother::fit_first`]).
    fit_steps: [u32; 2],
    done: [Option<(PassSummary, QuickStats)>; 2],
}

/// The next slice size after a slice of `size` took `dt` ms: slices of about a tenth of
/// the budget (at most 20 ms), so the budget is kept to within a slice.
fn adapt_slice(size: usize, dt: f64, budget_ms: f64) -> usize {
    let target = (budget_ms / 10.0).clamp(1.0, 20.0);
    if dt < target / 2.0 {
        (size * 2).min(1 << 20)
    } else if dt > target * 2.0 {
        (size / 2).max(1)
    } else {
        size
    }
}

impl PassRun {
    /// A pass about to begin on panel A.
    pub(super) fn new() -> PassRun {
        PassRun::of(RunKind::Whole)
    }

    /// A run of the given kind about to begin on its first panel.
    pub(super) fn of(kind: RunKind) -> PassRun {
        let order = match kind {
            RunKind::Whole => [0, 1],
            RunKind::Split => [1, 0],
            RunKind::Sweep(side) => [side, side],
        };
        PassRun {
            kind,
            order,
            k: 0,
            sweep: None,
            stage: Stage::Plan,
            schedule: Vec::new(),
            pos: 0,
            counts: SweepCounts::default(),
            sweep_ms: 0.0,
            acc: QuickAcc::default(),
            stats_ms: 0.0,
            slice: 64,
            plan_slice: 1024,
            untangling: false,
            saved: [None, None],
            fit_steps: [0, 0],
            done: [None, None],
        }
    }

    /// Runs the pass for about `budget_ms` milliseconds of `clock` (at least one slice:
    /// a planning, a few node visits or a slice of the statistics). Returns whether both
    /// panels are done: then [`finish`](Self::finish) keeps the records.
    pub(super) fn advance(
        &mut self,
        panels: &mut [Panel; 2],
        versions: &mut Versions,
        clock: &dyn Fn() -> f64,
        budget_ms: f64,
    ) -> bool {
        let start = clock();
        loop {
            let side = self.panel();
            let p = &mut panels[side];
            match self.stage {
                Stage::Plan if self.kind == RunKind::Split && side == 0 => {
                    // panel A was swept by another engine: measure it once adopted
                    let Some(sweep) = self.sweep else {
                        return false;
                    };
                    self.counts = sweep.counts;
                    self.sweep_ms = sweep.sweep_ms;
                    self.stage = Stage::Measure;
                    self.acc = QuickAcc::default();
                    self.stats_ms = 0.0;
                }
                Stage::Plan => {
                    let t0 = clock();
                    if self.saved[side].is_none() {
                        self.saved[side] = Some(Saved::of(p));
                    }
                    // as `Smoother::sweep`: the run's first pass against a target fits first
                    // (the page makes a new smoother for each pass; a sweep for another
                    // engine was told by that engine's run)
                    if !self.is_sweep() {
                        p.smoother.set_fit_pending(p.records.is_empty());
                    }
                    self.fit_steps[side] = p.smoother.fit_first(&mut p.mesh, p.objective.as_ref());
                    if self.fit_steps[side] > 0 {
                        p.version = versions.fresh();
                    }
                    p.smoother.begin_plan(&p.mesh);
                    self.sweep_ms = clock() - t0;
                    self.stage = Stage::Planning;
                }
                Stage::Planning => {
                    let t0 = clock();
                    let done = p.smoother.plan_some(&p.mesh, self.plan_slice);
                    let dt = clock() - t0;
                    self.sweep_ms += dt;
                    self.plan_slice = adapt_slice(self.plan_slice, dt, budget_ms);
                    if done {
                        self.schedule.clear();
                        self.schedule.extend_from_slice(p.smoother.schedule());
                        self.pos = 0;
                        self.counts = SweepCounts { fit_steps: self.fit_steps[side], ..SweepCounts::default() };
                        self.untangling = false;
                        self.stage = Stage::Smooth;
                    }
                }
                Stage::Smooth if self.pos < self.schedule.len() => {
                    if self.pos == 0 && !self.untangling {
                        p.version = versions.fresh();
                    }
                    let t0 = clock();
                    let end = (self.pos + self.slice).min(self.schedule.len());
                    let c = p.smoother.visit_all(
                        &mut p.mesh,
                        &self.schedule[self.pos..end],
                        p.objective.as_ref(),
                    );
                    self.counts.merge(c);
                    self.pos = end;
                    let dt = clock() - t0;
                    self.sweep_ms += dt;
                    self.slice = adapt_slice(self.slice, dt, budget_ms);
                }
                Stage::Smooth => {
                    // the planned visits (or an untangling sweep) are done: another
                    // untangling sweep, as `Smoother::sweep` runs them, or the statistics
                    let t0 = clock();
                    let again = p.smoother.plan_untangle_sweep(&p.mesh, &mut self.counts);
                    self.sweep_ms += clock() - t0;
                    if again {
                        self.untangling = true;
                        self.schedule.clear();
                        self.schedule.extend_from_slice(p.smoother.revisits());
                        self.pos = 0;
                    } else if let RunKind::Sweep(_) = self.kind {
                        // a sweep for another engine ends here: that engine measures
                        self.sweep = Some(SideSweep {
                            counts: self.counts,
                            sweep_ms: self.sweep_ms,
                        });
                        return true;
                    } else {
                        self.stage = Stage::Measure;
                        self.acc = QuickAcc::default();
                        self.stats_ms = 0.0;
                    }
                }
                Stage::Measure => {
                    let t0 = clock();
                    let n = p.mesh.element_count();
                    let from = self.acc.done;
                    self.acc.add(
                        &p.mesh,
                        from..(from + STATS_SLICE).min(n),
                        Some(&mut p.buckets),
                    );
                    self.stats_ms += clock() - t0;
                    if self.acc.done >= n {
                        let q = self.acc.finish();
                        let summary = PassSummary {
                            pass: p.records.len() as u32 + 1,
                            counts: self.counts,
                            after: q,
                            objective_total: None,
                            elapsed_ms: self.sweep_ms,
                            stats_ms: self.stats_ms,
                        };
                        self.done[side] = Some((summary, q));
                        self.k += 1;
                        if self.k == 2 {
                            return true;
                        }
                        self.stage = Stage::Plan;
                        // the slice ends here, so the page can say that the other side's
                        // turn has come before its planning begins
                        return false;
                    }
                }
            }
            if clock() - start >= budget_ms {
                return false;
            }
        }
    }

    /// Keeps the records and statistics of a completed pass in the panels.
    pub(super) fn finish(
        mut self,
        panels: &mut [Panel; 2],
        versions: &mut Versions,
    ) -> PassProgress {
        for (side, p) in panels.iter_mut().enumerate() {
            // a version of its own for the final positions and buckets: nothing drawn
            // during the pass (part-smoothed) can be taken for them
            if self.saved[side]
                .as_ref()
                .is_some_and(|s| s.version != p.version)
            {
                p.version = versions.fresh();
            }
        }
        let records = [0, 1].map(|side| {
            let (summary, q) = self.done[side].take().expect("both panels were measured");
            let p = &mut panels[side];
            p.quick = q;
            p.full = OnceCell::new();
            p.records.push(summary.clone());
            summary
        });
        PassProgress {
            done: true,
            fraction: 1.0,
            side: Side::B,
            stage: PassStage::Done,
            visits: self.counts.visits as usize,
            planned: self.schedule.len(),
            records: Some(records),
        }
    }

    /// A split run adopts panel A's sweep made by another engine: its positions
    /// `nodes`, what it did and, where panel A's boundary slides, where each node was last
    /// put on it (`places`). The panel is saved first, so an abandoned pass puts it back;
    /// it is measured when panel B is done. A refusal changes nothing.
    pub(super) fn adopt(
        &mut self,
        panels: &mut [Panel; 2],
        versions: &mut Versions,
        nodes: &[DVec2],
        sweep: SideSweep,
        places: Option<SlidePlaces>,
    ) -> Result<()> {
        if self.kind != RunKind::Split {
            return Err(Error::invalid("the pass in progress is not split between two engines"));
        }
        if self.sweep.is_some() {
            return Err(Error::invalid("the old side's sweep was adopted already"));
        }
        let p = &mut panels[0];
        let saved = Saved::of(p);
        let slide = match (&saved.slide, places) {
            (Some(s), Some(places)) => Some(SlideState { from: s.from.clone(), places }),
            (None, None) => None,
            (Some(_), None) => return Err(Error::invalid("the old side's boundary slides: give its nodes' boundary segments with its sweep")),
            (None, Some(_)) => return Err(Error::invalid("boundary segments were given, but the old side's boundary is held")),
        };
        if let Err(e) = SlideState::give(slide.as_ref(), &mut p.mesh, nodes) {
            SlideState::give(saved.slide.as_ref(), &mut p.mesh, &saved.nodes).expect("the panel's own boundary fits it");
            return Err(e);
        }
        self.saved[0] = Some(saved);
        p.version = versions.fresh();
        self.sweep = Some(sweep);
        Ok(())
    }

    /// The result of a completed [`RunKind::Sweep`]: the panel's swept positions, what
    /// the sweep did and where its nodes were last put on the boundary where it slides;
    /// the panel itself is put back as it was.
    pub(super) fn finish_sweep(self, panels: &mut [Panel; 2]) -> (Vec<DVec2>, SideSweep, Option<SlidePlaces>) {
        let mesh = &panels[self.panel()].mesh;
        let (nodes, places) = (mesh.nodes().to_vec(), SlidePlaces::of(mesh));
        let sweep = self.sweep.unwrap_or_default();
        self.undo(panels);
        (nodes, sweep, places)
    }

    /// Saves the panel of a sweep run as it is before the run (it gets the other engine's
    /// positions after this).
    pub(super) fn save(&mut self, panels: &[Panel; 2]) {
        let side = self.panel();
        self.saved[side] = Some(Saved::of(&panels[side]));
    }

    /// The index of the panel the run is on.
    fn panel(&self) -> usize {
        self.order[self.k.min(1)]
    }

    /// The panel the run is on.
    pub(super) fn side(&self) -> Side {
        Side::BOTH[self.panel()]
    }

    /// Whether this run sweeps one panel for another engine.
    pub(super) fn is_sweep(&self) -> bool {
        matches!(self.kind, RunKind::Sweep(_))
    }

    /// Puts both panels back where they were before the pass (positions, statistics and
    /// version), so an abandoned pass leaves no trace.
    pub(super) fn undo(self, panels: &mut [Panel; 2]) {
        for (p, saved) in panels.iter_mut().zip(self.saved) {
            if let Some(s) = saved {
                SlideState::give(s.slide.as_ref(), &mut p.mesh, &s.nodes).expect("the panel's own boundary fits it");
                p.version = s.version;
                p.quick = s.quick;
                p.buckets = s.buckets;
                p.full = s.full;
            }
        }
    }

    /// How far the run is: each panel is an equal share, its sweep nine tenths of that and
    /// its statistics the rest (a panel not yet planned counts as not begun; a sweep for
    /// another engine is its whole share).
    pub(super) fn progress(&self, panels: &[Panel; 2]) -> PassProgress {
        let side = self.panel();
        let waiting = self.kind == RunKind::Split && side == 0 && self.sweep.is_none();
        let sweep = match self.stage {
            _ if waiting => 0.0,
            Stage::Plan | Stage::Planning => 0.0,
            _ if self.schedule.is_empty() || self.untangling => 1.0,
            _ => self.pos as f64 / self.schedule.len() as f64,
        };
        let elements = panels[side].mesh.element_count().max(1);
        let measure = if self.stage == Stage::Measure {
            self.acc.done as f64 / elements as f64
        } else {
            0.0
        };
        let (within, shares) = if self.is_sweep() {
            (sweep, 1.0)
        } else {
            (0.9 * sweep + 0.1 * measure, 2.0)
        };
        PassProgress {
            done: false,
            fraction: ((self.k as f64 + within) / shares).clamp(0.0, 1.0),
            side: Side::BOTH[side],
            stage: match self.stage {
                _ if waiting => PassStage::Wait,
                Stage::Plan | Stage::Planning => PassStage::Plan,
                Stage::Smooth => PassStage::Smooth,
                Stage::Measure => PassStage::Measure,
            },
            visits: self.pos,
            planned: self.schedule.len(),
            records: None,
        }
    }
}

#[cfg(test)]
mod tests {

    use super::super::sample::Sample;
    use super::super::{stats, Playground, Settings};
    use super::*;
    use smoothlab::smooth::{Order, Strategy};

    fn no_clock() -> f64 {
        0.0
    }

    /// A clock that advances 1 ms per reading, so budgets end passes in many slices.
    fn ticking() -> impl Fn() -> f64 {
        let t = std::cell::Cell::new(0.0);
        move || {
            t.set(t.get() + 1.0);
            t.get()
        }
    }

    /// The records of the pass begun on `pg`, run to its end in slices of 3 ms of `clock`.
    fn records_of(pg: &mut Playground, clock: &dyn Fn() -> f64) -> [PassSummary; 2] {
        loop {
            if let Some(r) = pg.continue_pass(clock, 3.0).unwrap().records {
                return r;
            }
        }
    }

    /// `helper`'s sweep of `primary`'s panel A for the split pass `primary` began, measured
    /// against `primary`'s target, run to its end.
    fn swept_for(primary: &Playground, helper: &mut Playground, clock: &dyn Fn() -> f64) -> (Vec<f64>, SideSweep, Option<SlidePlaces>) {
        let target = primary.target_positions();
        helper.begin_sweep(Side::A, &primary.panel_positions(Side::A), target.as_deref(), primary.run_start(), None).unwrap();
        while !helper.continue_pass(clock, 3.0).unwrap().done {}
        helper.take_sweep().unwrap()
    }

    #[test]
    fn a_pass_in_slices_is_the_smoothers_pass_bit_for_bit() {
        use smoothlab::smooth::Smoother;
        let samples = [
            Sample::PlateMixedTangled,
            Sample::PlateQuadratic,
            Sample::Rand2dTangled,
        ];
        let strategies = Strategy::ALL;
        for sample in samples {
            let mesh = sample.generate().unwrap();
            for strategy in strategies {
                for order in [Order::Input, Order::Priority] {
                    let settings = Settings {
                        strategy,
                        order,
                        ..Settings::default()
                    };
                    let mut pg = Playground::new(mesh.clone()).unwrap();
                    pg.set_settings(settings).unwrap();
                    let clock = ticking();
                    for pass in 1..=2u32 {
                        pg.begin_pass();
                        let mut slices = 0;
                        let records = loop {
                            slices += 1;
                            let p = pg.continue_pass(&clock, 3.0).unwrap();
                            assert!((0.0..=1.0).contains(&p.fraction));
                            if let Some(r) = p.records {
                                break r;
                            }
                        };
                        assert!(slices > 2, "{sample:?} {strategy:?}: {slices} slices");
                        assert!(!pg.pass_in_progress());
                        for side in Side::BOTH {
                            let mut m = mesh.clone();
                            let mut s = Smoother::new(settings.side_options(side, crate::lab::settings::RunStart::of(&smoothlab::quality::mesh_stats(&mesh))).unwrap()).unwrap();
                            let obj = settings.choice(side).build();
                            let mut rec = None;
                            for _ in 0..pass {
                                rec = Some(s.pass(&mut m, obj.as_ref(), &|| 0.0));
                            }
                            let rec = rec.unwrap();
                            let what =
                                format!("{sample:?} {strategy:?} {order:?} pass {pass} {side:?}");
                            assert_eq!(pg.panel(side).mesh.nodes(), m.nodes(), "{what}");
                            let got = &records[side as usize];
                            assert_eq!(
                                (
                                    got.pass,
                                    got.counts.visits,
                                    got.counts.laplacian_moves,
                                    got.counts.optimization_calls,
                                    got.counts.solver_iterations
                                ),
                                (
                                    pass,
                                    rec.counts.visits,
                                    rec.counts.laplacian_moves,
                                    rec.counts.optimization_calls,
                                    rec.counts.solver_iterations
                                ),
                                "{what}"
                            );
                            assert_eq!(
                                (
                                    got.after.inverted,
                                    got.after.min_angle_deg,
                                    got.after.max_angle_deg,
                                    got.after.min_quality
                                ),
                                (
                                    rec.after.inverted,
                                    rec.after.min_angle_deg,
                                    rec.after.max_angle_deg,
                                    rec.after.min_quality
                                ),
                                "{what}"
                            );
                            let mut buckets = Vec::new();
                            assert_eq!(
                                pg.table(side).mesh,
                                stats::quick_stats_and_buckets(&m, &mut buckets),
                                "{what}"
                            );
                            assert_eq!(pg.panel(side).buckets, buckets, "{what}");
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn an_abandoned_pass_leaves_no_trace() {
        let mut pg = Playground::new(Sample::Rand2dTangled.generate().unwrap()).unwrap();
        pg.step(&no_clock);
        let before = [
            pg.panel(Side::A).mesh.nodes().to_vec(),
            pg.panel(Side::B).mesh.nodes().to_vec(),
        ];
        let versions = [pg.version(Side::A), pg.version(Side::B)];
        let tables = [pg.table(Side::A), pg.table(Side::B)];
        let clock = ticking();
        pg.begin_pass();
        let mut p = pg.continue_pass(&clock, 2.0).unwrap();
        while p.side == Side::A {
            p = pg.continue_pass(&clock, 2.0).unwrap();
        }
        assert!(!p.done && p.fraction >= 0.5);
        assert_ne!(
            pg.panel(Side::A).mesh.nodes(),
            before[0],
            "panel A was smoothed"
        );
        pg.abort_pass();
        assert!(!pg.pass_in_progress());
        for side in Side::BOTH {
            assert_eq!(pg.panel(side).mesh.nodes(), before[side as usize]);
            assert_eq!(pg.version(side), versions[side as usize]);
            assert_eq!(pg.table(side), tables[side as usize]);
        }
        assert!(
            pg.continue_pass(&clock, 1.0).is_err(),
            "nothing to continue"
        );
        // a drag, a reset or new settings abandon a pass in progress too
        pg.begin_pass();
        pg.continue_pass(&clock, 2.0).unwrap();
        pg.set_settings(Settings::default()).unwrap();
        assert!(!pg.pass_in_progress());
        assert_eq!(pg.panel(Side::A).mesh.nodes(), before[0]);
    }

    #[test]
    fn a_pass_split_between_two_engines_is_the_whole_pass_bit_for_bit() {
        let samples = [
            Sample::PlateMixedTangled,
            Sample::Rand2dTangled,
            Sample::PlateQuadratic,
        ];
        for sample in samples {
            let mesh = sample.generate().unwrap();
            for (strategy, order) in [
                (Strategy::Rules, Order::Priority),
                (Strategy::Opt, Order::Input),
                (Strategy::C2, Order::Input),
            ] {
                let settings = Settings {
                    strategy,
                    order,
                    ..Settings::default()
                };
                let [mut whole, mut primary, mut helper] =
                    [(); 3].map(|_| Playground::new(mesh.clone()).unwrap());
                for pg in [&mut whole, &mut primary, &mut helper] {
                    pg.set_settings(settings).unwrap();
                }
                let clock = ticking();
                for pass in 1..=2u32 {
                    let what = format!("{sample:?} {strategy:?} {order:?} pass {pass}");
                    let expected = whole.step(&clock);
                    primary.begin_split_pass();
                    let helper_before = helper.panel(Side::A).mesh.nodes().to_vec();
                    helper
                        .begin_sweep(Side::A, &primary.panel_positions(Side::A), None, primary.run_start(), None)
                        .unwrap();
                    // the first pass hands the sweep over while panel B is smoothed,
                    // the second once the split pass waits for it
                    if pass == 2 {
                        while primary.continue_pass(&clock, 3.0).unwrap().stage != PassStage::Wait {
                        }
                        let p = primary.continue_pass(&clock, 3.0).unwrap();
                        assert_eq!(
                            (p.stage, p.done, p.fraction),
                            (PassStage::Wait, false, 0.5),
                            "{what}"
                        );
                    }
                    assert!(helper.take_sweep().is_none(), "not before it is done");
                    while !helper.continue_pass(&clock, 3.0).unwrap().done {}
                    assert_eq!(
                        helper.panel(Side::A).mesh.nodes(),
                        helper_before,
                        "{what}: the helper is put back"
                    );
                    let (nodes, sweep, places) = helper.take_sweep().unwrap();
                    assert!(helper.take_sweep().is_none());
                    primary.adopt_sweep(&nodes, sweep, places.clone()).unwrap();
                    assert!(primary.adopt_sweep(&nodes, sweep, places.clone()).is_err(), "adopted once");
                    let records = loop {
                        let p = primary.continue_pass(&clock, 3.0).unwrap();
                        assert!((0.0..=1.0).contains(&p.fraction));
                        if let Some(r) = p.records {
                            break r;
                        }
                    };
                    for side in Side::BOTH {
                        let (got, want) = (&records[side as usize], &expected[side as usize]);
                        assert_eq!(
                            primary.panel(side).mesh.nodes(),
                            whole.panel(side).mesh.nodes(),
                            "{what} {side:?}"
                        );
                        assert_eq!(
                            (got.pass, got.counts, got.after),
                            (want.pass, want.counts, want.after),
                            "{what} {side:?}"
                        );
                        // the same but for the times the ticking clock gave
                        let untimed = |mut t: super::super::PanelTable| {
                            t.work.time_ms = 0.0;
                            t
                        };
                        assert_eq!(
                            untimed(primary.table(side)),
                            untimed(whole.table(side)),
                            "{what} {side:?}"
                        );
                        assert_eq!(
                            primary.panel(side).buckets,
                            whole.panel(side).buckets,
                            "{what} {side:?}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn a_split_pass_slides_the_boundary_as_the_whole_pass_does() {
        // the quad plate and the quadratic plate (its hole a curved boundary, whose sliding
        // nodes carry their edges' mid-side nodes) perturbed a little (the boundary slides
        // from the start) and tangled (held until a pass leaves a side valid): the helper,
        // never perturbed, is handed panel A's boundary with each sweep and hands back
        // where its nodes were put on it
        let slide = Settings { boundary: BoundaryRule::Slide, ..Settings::default() };
        for (sample, amount) in [(Sample::PlateQuad, 0.3), (Sample::PlateQuad, 0.8), (Sample::PlateQuadratic, 0.3), (Sample::PlateQuadratic, 0.6)] {
            let [mut whole, mut primary, mut helper] = [(); 3].map(|_| Playground::new(sample.generate().unwrap()).unwrap());
            let quadratic = whole.topology().has_quadratic();
            for pg in [&mut whole, &mut primary] {
                pg.perturb(amount, 5).unwrap();
            }
            for pg in [&mut whole, &mut primary, &mut helper] {
                pg.set_settings(slide).unwrap();
            }
            let clock = ticking();
            let mut handed = 0;
            for pass in 1..=3 {
                let what = format!("{sample:?} {amount} pass {pass}");
                let expected = whole.step(&clock);
                // Stop during a pass leaves no trace, the boundary's places too
                let before = primary.slide_state(Side::B);
                primary.begin_pass();
                loop {
                    let p = primary.continue_pass(&clock, 1.0).unwrap();
                    assert!(!p.done, "{what}");
                    if p.side == Side::B && p.stage == PassStage::Smooth && p.visits > 0 {
                        break;
                    }
                }
                primary.abort_pass();
                assert_eq!(primary.slide_state(Side::B), before, "{what}");
                primary.begin_split_pass();
                let a = primary.slide_state(Side::A);
                handed += usize::from(a.is_some());
                let nodes = primary.panel_positions(Side::A);
                if let Some(a) = &a {
                    assert_eq!(a.places.params.len(), if quadratic { a.places.segments.len() } else { 0 }, "{what}");
                    let short = SlideState { from: a.from[1..].to_vec(), places: a.places.clone() };
                    let e = helper.begin_sweep(Side::A, &nodes, None, primary.run_start(), Some(&short)).unwrap_err().to_string();
                    assert!(e.contains("positions for a mesh of"), "{e}");
                    let wrong = SlideState { from: a.from.clone(), places: SlidePlaces { segments: vec![0; a.places.segments.len()], ..a.places.clone() } };
                    assert!(helper.begin_sweep(Side::A, &nodes, None, primary.run_start(), Some(&wrong)).is_err());
                    // a quadratic boundary's parameters must travel with its segments
                    let params = if quadratic { Vec::new() } else { vec![0.5; a.places.segments.len()] };
                    let unplaced = SlideState { from: a.from.clone(), places: SlidePlaces { segments: a.places.segments.clone(), params } };
                    assert!(helper.begin_sweep(Side::A, &nodes, None, primary.run_start(), Some(&unplaced)).is_err(), "{what}");
                    assert!(!helper.pass_in_progress(), "a refused sweep leaves nothing begun");
                }
                helper.begin_sweep(Side::A, &nodes, None, primary.run_start(), a.as_ref()).unwrap();
                while !helper.continue_pass(&clock, 3.0).unwrap().done {}
                let (nodes, sweep, places) = helper.take_sweep().unwrap();
                assert_eq!(places.is_some(), a.is_some(), "{what}");
                if let Some(places) = &places {
                    assert!(primary.adopt_sweep(&nodes, sweep, None).is_err(), "{what}: the places are needed");
                    if quadratic {
                        let dropped = SlidePlaces { params: Vec::new(), ..places.clone() };
                        assert!(primary.adopt_sweep(&nodes, sweep, Some(dropped)).is_err(), "{what}: the parameters are needed");
                    }
                }
                primary.adopt_sweep(&nodes, sweep, places).unwrap();
                let records = records_of(&mut primary, &clock);
                for side in Side::BOTH {
                    let i = side as usize;
                    let bits = |pg: &Playground| pg.panel(side).mesh.nodes().iter().map(|p| [p.x.to_bits(), p.y.to_bits()]).collect::<Vec<_>>();
                    assert_eq!(bits(&primary), bits(&whole), "{what} {side:?}");
                    assert_eq!((records[i].counts, records[i].after), (expected[i].counts, expected[i].after), "{what} {side:?}");
                    assert_eq!(primary.slide_state(side), whole.slide_state(side), "{what} {side:?}");
                    assert_eq!(primary.table(side).boundary, whole.table(side).boundary, "{what} {side:?}");
                }
            }
            assert!(handed >= 2, "{sample:?} {amount}: panel A's boundary slid in {handed} of 3 passes");
        }
    }

    #[test]
    fn a_split_pass_against_the_input_is_the_whole_pass_though_the_helper_was_not_perturbed() {
        use smoothlab::target::Target;
        let mesh = Sample::PlateQuad.generate().unwrap();
        let settings = Settings {
            strategy: Strategy::Rules,
            target: Target::Input,
            ..Settings::default()
        };
        let [mut whole, mut primary, mut helper] =
            [(); 3].map(|_| Playground::new(mesh.clone()).unwrap());
        for pg in [&mut whole, &mut primary, &mut helper] {
            pg.set_settings(settings).unwrap();
        }
        // as on the page: the helper holds the mesh as loaded, the other two perturbed it
        for pg in [&mut whole, &mut primary] {
            pg.perturb(0.3, 4).unwrap();
        }
        let own_target = helper.target_positions().unwrap();
        let target = primary.target_positions().unwrap();
        assert_ne!(own_target, target);
        let clock = ticking();
        let nodes = primary.panel_positions(Side::A);
        let e = helper
            .begin_sweep(Side::A, &nodes, None, primary.run_start(), None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("give its positions"), "{e}");
        let e = helper
            .begin_sweep(Side::A, &nodes, Some(&target[2..]), primary.run_start(), None)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("the target's positions:"), "{e}");
        for pass in 1..=2 {
            let expected = whole.step(&clock);
            primary.begin_split_pass();
            let (nodes, sweep, places) = swept_for(&primary, &mut helper, &clock);
            // the helper's own target is back after the sweep
            assert_eq!(helper.target_positions().unwrap(), own_target);
            assert_eq!(
                helper.panel(Side::A).mesh.target_nodes(),
                Some(helper.original_nodes())
            );
            primary.adopt_sweep(&nodes, sweep, places.clone()).unwrap();
            let records = records_of(&mut primary, &clock);
            for side in Side::BOTH {
                let what = format!("pass {pass} {side:?}");
                assert_eq!(
                    primary.panel(side).mesh.nodes(),
                    whole.panel(side).mesh.nodes(),
                    "{what}"
                );
                let (got, want) = (&records[side as usize], &expected[side as usize]);
                assert_eq!((got.counts, got.after), (want.counts, want.after), "{what}");
            }
        }
        // an abandoned sweep gives the helper its own target back too
        helper
            .begin_sweep(Side::A, &primary.panel_positions(Side::A), Some(&target), primary.run_start(), None)
            .unwrap();
        helper.continue_pass(&clock, 1.0).unwrap();
        helper.abort_pass();
        assert_eq!(
            helper.panel(Side::A).mesh.target_nodes(),
            Some(helper.original_nodes())
        );
        // with the ideal target no positions go with a sweep
        helper.set_settings(Settings::default()).unwrap();
        assert!(helper
            .begin_sweep(Side::A, &primary.panel_positions(Side::A), Some(&target), primary.run_start(), None)
            .is_err());
        assert!(helper.panel(Side::A).mesh.target_nodes().is_none());
    }

    /// A 40 × 30 boundary layer: rows graded ×1.2 from a wall row 28 times thinner than
    /// wide, its interior moved by up to a fifth of its cell (a fixed sequence).
    fn layer() -> Mesh {
        let (nx, ny, ratio) = (40usize, 30i32, 1.2f64);
        let top = |j: usize| (ratio.powi(j as i32) - 1.0) / (ratio.powi(ny) - 1.0);
        let mut m = smoothlab::generate::grid(nx, ny as usize, smoothlab::generate::GridKind::Quad).unwrap();
        let mut rng = smoothlab::numeric::SplitMix64::new(11);
        for p in m.nodes_mut() {
            let (i, j) = ((p.x * nx as f64).round() as usize, (p.y * ny as f64).round() as usize);
            let mut q = DVec2::new(p.x, top(j));
            if 0 < i && i < nx && 0 < j && j < ny as usize {
                let h = (top(j) - top(j - 1)).min(top(j + 1) - top(j));
                q += DVec2::new(rng.uniform(-0.2, 0.2) / nx as f64, rng.uniform(-0.2, 0.2) * h);
            }
            *p = q;
        }
        m
    }

    /// Against the stretch target, both panels `new`: the run's first pass fits each panel
    /// to its targets first, and only the first, as the core's smoother runs it — whole, in
    /// slices, or split (the engine that sweeps panel A told by the run's start), each
    /// pass after new settings, as the page's worker gives them, to the bit.
    #[test]
    fn a_pass_against_a_stretch_fits_first_whole_in_slices_or_split() {
        use smoothlab::smooth::Smoother;
        use smoothlab::target::Target;
        let settings = Settings {
            strategy: Strategy::Rules,
            target: Target::Stretch,
            compare: [super::super::settings::Choice::NEW; 2],
            ..Settings::default()
        };
        let mut core = layer();
        core.set_target_from(Target::Stretch, core.nodes().to_vec());
        let start = super::super::settings::RunStart::of(&smoothlab::quality::mesh_stats(&core));
        let mut smoother = Smoother::new(settings.side_options(Side::B, start).unwrap()).unwrap();
        let objective = settings.choice(Side::B).build();
        let [mut whole, mut primary, mut helper] = [(); 3].map(|_| Playground::new(layer()).unwrap());
        let clock = ticking();
        for pass in 1..=2 {
            let record = smoother.pass(&mut core, objective.as_ref(), &no_clock);
            assert_eq!(record.counts.fit_steps > 0, pass == 1, "pass {pass}: fit steps {}", record.counts.fit_steps);
            for pg in [&mut whole, &mut primary, &mut helper] {
                pg.set_settings(settings).unwrap();
            }
            let expected = whole.step(&clock);
            primary.begin_split_pass();
            let (nodes, sweep, places) = swept_for(&primary, &mut helper, &clock);
            primary.adopt_sweep(&nodes, sweep, places).unwrap();
            let split = records_of(&mut primary, &clock);
            for side in Side::BOTH {
                let what = format!("pass {pass} {side:?}");
                assert_eq!(whole.panel(side).mesh.nodes(), core.nodes(), "{what}: the page's whole pass");
                assert_eq!(expected[side as usize].counts, record.counts, "{what}");
                assert_eq!(primary.panel(side).mesh.nodes(), core.nodes(), "{what}: split");
                assert_eq!((split[side as usize].counts, split[side as usize].after), (expected[side as usize].counts, expected[side as usize].after), "{what}: split");
            }
        }
    }

    #[test]
    fn an_abandoned_split_pass_leaves_no_trace_and_bad_sweeps_are_refused() {
        let mesh = Sample::Rand2dTangled.generate().unwrap();
        let (mut primary, mut helper) = (
            Playground::new(mesh.clone()).unwrap(),
            Playground::new(mesh).unwrap(),
        );
        let before = [
            primary.panel(Side::A).mesh.nodes().to_vec(),
            primary.panel(Side::B).mesh.nodes().to_vec(),
        ];
        let tables = [primary.table(Side::A), primary.table(Side::B)];
        let n = before[0].len();
        let clock = ticking();
        helper
            .begin_sweep(Side::A, &primary.panel_positions(Side::A), None, primary.run_start(), None)
            .unwrap();
        while !helper.continue_pass(&clock, 2.0).unwrap().done {}
        let (nodes, sweep, places) = helper.take_sweep().unwrap();
        assert!(sweep.counts.visits > 0 && nodes != primary.panel_positions(Side::A));
        assert!(
            primary.adopt_sweep(&nodes, sweep, places.clone()).is_err(),
            "no split pass in progress"
        );
        primary.begin_pass();
        assert!(
            primary.adopt_sweep(&nodes, sweep, places.clone()).is_err(),
            "a whole pass adopts nothing"
        );
        primary.begin_split_pass();
        assert!(
            primary.adopt_sweep(&nodes[1..], sweep, places.clone()).is_err(),
            "one coordinate short"
        );
        let mut nan = nodes.clone();
        nan[7] = f64::NAN;
        let e = primary.adopt_sweep(&nan, sweep, places.clone()).unwrap_err().to_string();
        assert!(e.contains("node 3"), "{e}");
        assert!(helper
            .begin_sweep(Side::A, &vec![0.0; 2 * n + 2], None, primary.run_start(), None)
            .is_err());
        primary.continue_pass(&clock, 2.0).unwrap();
        primary.adopt_sweep(&nodes, sweep, places.clone()).unwrap();
        primary.continue_pass(&clock, 2.0).unwrap();
        primary.abort_pass();
        assert!(!primary.pass_in_progress());
        for side in Side::BOTH {
            assert_eq!(primary.panel(side).mesh.nodes(), before[side as usize]);
            assert_eq!(primary.table(side), tables[side as usize]);
        }
        // an abandoned sweep puts the helper back too
        helper.begin_sweep(Side::A, &nodes, None, primary.run_start(), None).unwrap();
        helper.continue_pass(&clock, 1.0).unwrap();
        helper.abort_pass();
        assert_eq!(helper.panel(Side::A).mesh.nodes(), before[0]);
        assert!(helper.take_sweep().is_none());
    }
}
