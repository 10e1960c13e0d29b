//! A pass in slices: the state machine that runs one smoothing pass on both panels a
//! time budget at a time (plan the visit order, visit the nodes, run any untangling
//! sweeps, measure), so the page can show progress and answer Stop during a pass on a
//! large mesh. The result is [`Smoother::pass`](crate::smooth::Smoother::pass)'s, bit
//! for bit; the playground ([`super::Playground::begin_pass`], `continue_pass`,
//! `abort_pass`) only holds the run.

use std::cell::OnceCell;

use glam::DVec2;
use serde::Serialize;

use super::stats::{QuickAcc, QuickStats};
use super::{Panel, PassSummary, Side, Versions};
use crate::quality::MeshStats;
use crate::smooth::SweepCounts;

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
    /// The pass is complete.
    Done,
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
    version: u64,
    quick: QuickStats,
    buckets: Vec<u8>,
    full: OnceCell<MeshStats>,
}

/// A pass in progress: the old panel's sweep and statistics, then the new panel's.
pub(super) struct PassRun {
    side: usize,
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
    /// A pass about to begin on the old panel.
    pub(super) fn new() -> PassRun {
        PassRun {
            side: 0,
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
            let side = self.side;
            let p = &mut panels[side];
            match self.stage {
                Stage::Plan => {
                    let t0 = clock();
                    self.saved[side] = Some(Saved {
                        nodes: p.mesh.nodes().to_vec(),
                        version: p.version,
                        quick: p.quick,
                        buckets: p.buckets.clone(),
                        full: p.full.clone(),
                    });
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
                        self.counts = SweepCounts::default();
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
                    let c = p.smoother.visit_all(&mut p.mesh, &self.schedule[self.pos..end], p.objective.as_ref());
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
                    self.acc.add(&p.mesh, from..(from + STATS_SLICE).min(n), Some(&mut p.buckets));
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
                        if side == 1 {
                            return true;
                        }
                        self.side = 1;
                        self.stage = Stage::Plan;
                        // the slice ends here, so the page can say that the new side's
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
    pub(super) fn finish(mut self, panels: &mut [Panel; 2], versions: &mut Versions) -> PassProgress {
        for (side, p) in panels.iter_mut().enumerate() {
            // a version of its own for the final positions and buckets: nothing drawn
            // during the pass (part-smoothed) can be taken for them
            if self.saved[side].as_ref().is_some_and(|s| s.version != p.version) {
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
            side: Side::New,
            stage: PassStage::Done,
            visits: self.counts.visits as usize,
            planned: self.schedule.len(),
            records: Some(records),
        }
    }

    /// Puts both panels back where they were before the pass (positions, statistics and
    /// version), so an abandoned pass leaves no trace.
    pub(super) fn undo(self, panels: &mut [Panel; 2]) {
        for (p, saved) in panels.iter_mut().zip(self.saved) {
            if let Some(s) = saved {
                p.mesh.nodes_mut().copy_from_slice(&s.nodes);
                p.version = s.version;
                p.quick = s.quick;
                p.buckets = s.buckets;
                p.full = s.full;
            }
        }
    }

    /// How far the pass is: each panel is half, its sweep nine tenths of that and its
    /// statistics the rest (a panel not yet planned counts as not begun).
    pub(super) fn progress(&self, panels: &[Panel; 2]) -> PassProgress {
        let side = self.side;
        let sweep = match self.stage {
            Stage::Plan | Stage::Planning => 0.0,
            _ if self.schedule.is_empty() || self.untangling => 1.0,
            _ => self.pos as f64 / self.schedule.len() as f64,
        };
        let elements = panels[side].mesh.element_count().max(1);
        let measure = if self.stage == Stage::Measure { self.acc.done as f64 / elements as f64 } else { 0.0 };
        let within = 0.9 * sweep + 0.1 * measure;
        PassProgress {
            done: false,
            fraction: ((side as f64 + within) / 2.0).clamp(0.0, 1.0),
            side: if side == 0 { Side::Old } else { Side::New },
            stage: match self.stage {
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
    use crate::smooth::{Order, Strategy};

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

    #[test]
    fn a_pass_in_slices_is_the_smoothers_pass_bit_for_bit() {
        use crate::smooth::Smoother;
        let samples = [Sample::PlateMixedTangled, Sample::PlateQuadratic, Sample::Rand2dTangled];
        let strategies = Strategy::ALL;
        for sample in samples {
            let mesh = sample.generate().unwrap();
            for strategy in strategies {
                for order in [Order::Input, Order::Priority] {
                    let settings = Settings { strategy, order, ..Settings::default() };
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
                            let mut s = Smoother::new(settings.smooth_options().unwrap()).unwrap();
                            let obj = settings.choice(side).build();
                            let mut rec = None;
                            for _ in 0..pass {
                                rec = Some(s.pass(&mut m, obj.as_ref(), &|| 0.0));
                            }
                            let rec = rec.unwrap();
                            let what = format!("{sample:?} {strategy:?} {order:?} pass {pass} {side:?}");
                            assert_eq!(pg.panel(side).mesh.nodes(), m.nodes(), "{what}");
                            let got = &records[side as usize];
                            assert_eq!(
                                (got.pass, got.counts.visits, got.counts.laplacian_moves, got.counts.optimization_calls, got.counts.solver_iterations),
                                (pass, rec.counts.visits, rec.counts.laplacian_moves, rec.counts.optimization_calls, rec.counts.solver_iterations),
                                "{what}"
                            );
                            assert_eq!(
                                (got.after.inverted, got.after.min_angle_deg, got.after.max_angle_deg, got.after.min_quality),
                                (rec.after.inverted, rec.after.min_angle_deg, rec.after.max_angle_deg, rec.after.min_quality),
                                "{what}"
                            );
                            let mut buckets = Vec::new();
                            assert_eq!(pg.table(side).mesh, stats::quick_stats_and_buckets(&m, &mut buckets), "{what}");
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
        let before = [pg.panel(Side::Old).mesh.nodes().to_vec(), pg.panel(Side::New).mesh.nodes().to_vec()];
        let versions = [pg.version(Side::Old), pg.version(Side::New)];
        let tables = [pg.table(Side::Old), pg.table(Side::New)];
        let clock = ticking();
        pg.begin_pass();
        let mut p = pg.continue_pass(&clock, 2.0).unwrap();
        while p.side == Side::Old {
            p = pg.continue_pass(&clock, 2.0).unwrap();
        }
        assert!(!p.done && p.fraction >= 0.5);
        assert_ne!(pg.panel(Side::Old).mesh.nodes(), before[0], "the old panel was smoothed");
        pg.abort_pass();
        assert!(!pg.pass_in_progress());
        for side in Side::BOTH {
            assert_eq!(pg.panel(side).mesh.nodes(), before[side as usize]);
            assert_eq!(pg.version(side), versions[side as usize]);
            assert_eq!(pg.table(side), tables[side as usize]);
        }
        assert!(pg.continue_pass(&clock, 1.0).is_err(), "nothing to continue");
        // a drag, a reset or new settings abandon a pass in progress too
        pg.begin_pass();
        pg.continue_pass(&clock, 2.0).unwrap();
        pg.set_settings(Settings::default()).unwrap();
        assert!(!pg.pass_in_progress());
        assert_eq!(pg.panel(Side::Old).mesh.nodes(), before[0]);
    }
}
