//! What a pass did: the counts of its node loop and the record of a whole pass.

use serde::{Deserialize, Serialize};

use crate::quality::QuickStats;

/// What one pass did and where the mesh stands after it: the record of a pass for the CLI
/// (`smooth --json`), the page and the benches alike. In JSON its parts are flattened
/// into one object (`pass`, `visits`, …, `inverted`, `min_angle_deg`, …).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PassRecord {
    /// 1 for the first pass of a [`Smoother`](super::Smoother) (on the page: since the last reset).
    pub pass: u32,
    /// What the node loop did (with [`Order::Priority`](super::Order::Priority) a poor node is visited up to once
    /// per bin; untangling sweeps' visits count in `visits`).
    #[serde(flatten)]
    pub counts: SweepCounts,
    /// Where the mesh stands after the pass.
    #[serde(flatten)]
    pub after: QuickStats,
    /// After the pass: the sum over free nodes of the node objective value (the sum of its
    /// terms, or their minimum for a max-min objective) — the quantity the optimiser works
    /// on, summed over the mesh; +∞ when a barrier objective sees an inverted star. `None`
    /// where it is not measured (the page: it costs more than a Laplacian pass).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub objective_total: Option<f64>,
    /// Time of the node loop (planning the order included), milliseconds by the caller's clock.
    pub elapsed_ms: f64,
    /// Time of the statistics after it, milliseconds.
    pub stats_ms: f64,
}

/// What the node loop of a pass did (the counting part of [`PassRecord`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct SweepCounts {
    /// Node visits.
    pub visits: u32,
    /// Nodes moved by a Laplacian step (plain or smart).
    pub laplacian_moves: u32,
    /// Calls to the solver.
    pub optimization_calls: u32,
    /// Solver iterations, summed over the calls.
    pub solver_iterations: u32,
    /// Visits that moved their node.
    pub moves: u32,
    /// Untangling sweeps ([`SmoothOptions::untangle_sweeps`](crate::smooth::SmoothOptions::untangle_sweeps)).
    pub untangle_sweeps: u32,
    /// Steps of the fit to the targets before the node loop (a volume mesh's first pass
    /// against a target other than the ideal: `crate::volume`'s fit).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub fit_steps: u32,
}

fn is_zero(n: &u32) -> bool {
    *n == 0
}

impl SweepCounts {
    pub(crate) fn add(&mut self, o: NodeOutcome) {
        self.visits += 1;
        self.laplacian_moves += (o.laplacian && o.moved) as u32;
        self.optimization_calls += o.optimized as u32;
        self.solver_iterations += o.iterations;
        self.moves += o.moved as u32;
    }
    pub fn merge(&mut self, o: SweepCounts) {
        self.visits += o.visits;
        self.laplacian_moves += o.laplacian_moves;
        self.optimization_calls += o.optimization_calls;
        self.solver_iterations += o.solver_iterations;
        self.moves += o.moves;
        self.untangle_sweeps += o.untangle_sweeps;
        self.fit_steps += o.fit_steps;
    }
}

/// What happened at one node.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct NodeOutcome {
    /// The node ended somewhere else.
    pub moved: bool,
    /// A Laplacian position (plain or smart) was taken.
    pub laplacian: bool,
    /// The solver was called.
    pub optimized: bool,
    /// Solver iterations.
    pub iterations: u32,
}
