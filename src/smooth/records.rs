//! What a pass did: the counts of its node loop and the record of a whole pass.

use serde::Serialize;

/// What one pass did and where the mesh stands after it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PassRecord {
    /// 1 for the first pass of a [`Smoother`].
    pub pass: u32,
    /// Node visits (with [`Order::Priority`] a poor node is visited up to once per bin).
    pub visits: u32,
    /// After the pass: elements with a corner of `det ≤ 0`.
    pub inverted: usize,
    /// After the pass: smallest and largest signed corner angle, degrees.
    pub min_angle_deg: f64,
    pub max_angle_deg: f64,
    /// After the pass: smallest element α/β.
    pub min_quality: f64,
    /// After the pass: the sum over free nodes of the node objective value (the sum of its
    /// terms, or their minimum for a max-min objective) — the quantity the optimiser works on,
    /// summed over the mesh. +∞ when a barrier objective sees an inverted star.
    pub objective_total: f64,
    /// Nodes moved by a Laplacian step (plain or smart).
    pub laplacian_moves: u32,
    /// Calls to the solver.
    pub optimization_calls: u32,
    /// Solver iterations, summed over the calls.
    pub solver_iterations: u32,
    /// Untangling sweeps run after the planned visits ([`SmoothOptions::untangle_sweeps`]);
    /// their visits are counted in `visits`.
    pub untangle_sweeps: u32,
    /// Time of the node loop (not of the statistics), milliseconds by the caller's clock.
    pub elapsed_ms: f64,
}

/// What the node loop of a pass did (the counting part of [`PassRecord`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
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
    /// Untangling sweeps ([`SmoothOptions::untangle_sweeps`]).
    pub untangle_sweeps: u32,
}

impl SweepCounts {
    pub(crate) fn add(&mut self, o: NodeOutcome) {
        self.visits += 1;
        self.laplacian_moves += (o.laplacian && o.moved) as u32;
        self.optimization_calls += o.optimized as u32;
        self.solver_iterations += o.iterations;
        self.moves += o.moved as u32;
    }
    pub(crate) fn merge(&mut self, o: SweepCounts) {
        self.visits += o.visits;
        self.laplacian_moves += o.laplacian_moves;
        self.optimization_calls += o.optimization_calls;
        self.solver_iterations += o.solver_iterations;
        self.moves += o.moves;
        self.untangle_sweeps += o.untangle_sweeps;
    }
    pub(super) fn add_to(self, rec: &mut PassRecord) {
        rec.visits += self.visits;
        rec.laplacian_moves += self.laplacian_moves;
        rec.optimization_calls += self.optimization_calls;
        rec.solver_iterations += self.solver_iterations;
        rec.untangle_sweeps += self.untangle_sweeps;
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
