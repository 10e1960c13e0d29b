//! Smoothing drivers: Laplacian, smart (constrained) Laplacian, optimization, Freitag's
//! combined schemes C1/C2/C3 and Chen's rules, visiting nodes in input or priority order.
//!
//! The drivers work with any [`Objective`] and either solver ([`SolverKind`]): a new
//! objective never touches this module. A [`Smoother`] owns its scratch buffers (the star,
//! the solvers' term vectors, the visit schedule) and runs one [`pass`](Smoother::pass)
//! at a time, so the page can step pass by pass; [`solve_node`] solves one node with its
//! history for the page's level-set view.
//!
//! Nodes move one at a time in place (Gauss–Seidel): a node sees the new positions of the
//! nodes visited before it. Fixed nodes and mid-side nodes are never smoothed; after a
//! corner node moves, the mid-side nodes of its straight edges follow it
//! ([`Mesh::follow_mid_nodes`]); curved boundary edges keep their mid node.
//!
//! The formulas, in one notation: `docs/formulas.md` §4.

use glam::DVec2;
use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::objective::{Objective, Star, StarElement, Term};
use crate::optimize::{evaluate, SolveOptions, SolveResult, SolverKind, Solvers};
use crate::quality::{
    canann_beta_from_corners, corner_edges, lo_alpha_corner, mesh_stats, scaled_jacobian, TWO_SQRT3,
};

mod obstacles;
pub mod parallel;
#[cfg(test)]
mod tests;

pub use obstacles::{untangling_obstacles, Obstacle};

enum_with_all! {
    /// How each free node is smoothed. (De)serialised by its [`name`](Strategy::name).
    #[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
    #[serde(rename_all = "lowercase")]
    pub enum Strategy {
        /// Move to the centroid of the neighbouring corner nodes, unconditionally.
        Laplace,
        /// Constrained ("smart") Laplacian: move to the centroid only if the star's worst
        /// quality ([`SmoothOptions::smart_measure`]) strictly improves and no valid star
        /// element becomes inverted (Freitag 1997; Chen et al. 2003 §1).
        Smart,
        /// Optimise every free node with the objective's solver.
        Opt,
        /// Freitag's combined approach 1: smart Laplacian if the star's minimum angle exceeds
        /// the threshold, optimization otherwise.
        C1,
        /// Freitag's combined approach 2: smart Laplacian always, then optimization if the
        /// star's minimum angle still does not exceed the threshold.
        C2,
        /// Freitag's combined approach 3: nothing if the star's minimum angle exceeds the
        /// threshold; otherwise (plain) Laplacian, then optimization if still not above it —
        /// and the node stays put if the two together left its star worse (by
        /// [`SmoothOptions::smart_measure`], or with more inverted elements) than they found it.
        C3,
        /// Chen et al. (2003) §4.1: optimization when the node (1) is connected to a curved
        /// boundary node, (2) is connected to an invalid element, (3) failed to move under
        /// constrained Laplacian, or (4) the caller forces it; otherwise constrained Laplacian.
        Rules,
    }
}

impl Strategy {
    /// The name used on the command line, in permalinks and on the page.
    pub fn name(self) -> &'static str {
        match self {
            Strategy::Laplace => "laplace",
            Strategy::Smart => "smart",
            Strategy::Opt => "opt",
            Strategy::C1 => "c1",
            Strategy::C2 => "c2",
            Strategy::C3 => "c3",
            Strategy::Rules => "rules",
        }
    }
    /// The strategy called `name` (exact, lowercase).
    pub fn parse(name: &str) -> Option<Strategy> {
        Self::ALL.into_iter().find(|s| s.name() == name)
    }
}

enum_with_all! {
    /// The order in which a pass visits the free nodes.
    #[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
    #[serde(rename_all = "lowercase")]
    pub enum Order {
        /// Node number order, each free node once ("first come first serve").
        Input,
        /// Chen et al. (2003) §4.2, "worst one first": see [`Smoother::plan`].
        Priority,
    }
}

impl Order {
    /// The name used on the command line, in permalinks and on the page.
    pub fn name(self) -> &'static str {
        match self {
            Order::Input => "input",
            Order::Priority => "priority",
        }
    }
    /// The order called `name` (exact, lowercase).
    pub fn parse(name: &str) -> Option<Order> {
        Self::ALL.into_iter().find(|o| o.name() == name)
    }
}

/// The star quality that the smart Laplacian must improve, and that orders nodes by priority.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Measure {
    /// The smallest element shape metric in the star: Lo's α for triangles, Canann's β for
    /// quads (Chen et al. 2003, eqs. 1–2).
    Shape,
    /// The smallest sine of the star's element angles (Freitag 1997).
    MinSine,
}

/// Settings of the smoothing drivers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SmoothOptions {
    /// How each node is smoothed. Default [`Strategy::Rules`] (Chen's algorithm).
    pub strategy: Strategy,
    /// Visit order. Default [`Order::Priority`] (Chen §4.2).
    pub order: Order,
    /// Threshold angle θ_t of C1/C2/C3, degrees, in (0, 90]: a star "exceeds" it when the
    /// smallest sine of its angles exceeds sin θ_t (so angles near 180° count as poor too).
    /// Default 30 (Freitag's best results; she also used 5, 10, 15).
    pub threshold_deg: f64,
    /// Solver iterations per optimization call. Default 3 (Chen §3.1).
    pub max_iter: u32,
    /// Which solver optimises. Default [`SolverKind::Auto`] (by the objective's goal).
    pub solver: SolverKind,
    /// What the smart Laplacian must improve. Default [`Measure::Shape`] (Chen's α/β);
    /// [`Measure::MinSine`] is Freitag's choice.
    pub smart_measure: Measure,
    /// Chen's rule 4: the caller forces optimization for every node under
    /// [`Strategy::Rules`]. Default false.
    pub force_optimization: bool,
    /// Number of priority bins for [`Order::Priority`]. Default 5 (Chen §4.2).
    pub priority_bins: u32,
    /// An optimization call may not raise the number of inverted elements of its star:
    /// inside the solver such positions read as the worst value, so the line search (or
    /// the ascent's step halving) stays on the allowed side (but see
    /// [`SmoothOptions::pass_through_folds`]). Default true.
    ///
    /// Chen et al. (2003, §3.2) use no such check: their penalty "keeps nodes out of the
    /// inverted region". With our eq. (8) it does not always — on a star with a sliver
    /// element the penalty of the sliver outweighs the cost of folding a neighbour (the
    /// reproduction of Mesquite's `hole_in_square.vtk` in `docs/reproduction.md`: 0
    /// inverted elements before, 59 after one pass without the check), and Freitag's
    /// max-min ascent may fold a valid element while it raises the minimum of an inverted
    /// one. With the check no optimization step raises the number of inverted elements.
    /// Laplacian steps are not affected: the smart Laplacian has its own check, the plain
    /// Laplacian (`Laplace`, and the first step of `C3`) is the unchecked method itself.
    pub keep_valid: bool,
    /// With [`SmoothOptions::keep_valid`]: a star that is already inverted when the call
    /// begins may fold one more element when that lowers its total inversion
    /// `Σ max(0, −det)` over all its corners. A valid star is still never folded. `None`
    /// (the default): on for objectives built to untangle ([`Objective::untangles`]:
    /// `new` and `untangle`), off for the others; `Some` forces it.
    ///
    /// Untangling often has to pass through such an intermediate state — the free node
    /// crosses an edge of one element to leave the deeper fold of another — and a count
    /// alone cannot see that progress (`docs/reproduction.md` §4 shows what it changes on
    /// Knupp's random grids).
    pub pass_through_folds: Option<bool>,
    /// Untangling sweeps after the planned visits of a pass: while elements are inverted,
    /// revisit the free nodes of the inverted elements and their free neighbours, worst
    /// star first; at most this many sweeps, and none after a sweep that moved no node.
    /// Only strategies that optimise revisit (`laplace` and `smart` cannot untangle).
    /// Default [`UNTANGLE_SWEEPS`]; 0 turns them off.
    pub untangle_sweeps: u32,
}

/// The default number of untangling sweeps per pass ([`SmoothOptions::untangle_sweeps`]).
pub const UNTANGLE_SWEEPS: u32 = 10;

impl Default for SmoothOptions {
    fn default() -> Self {
        SmoothOptions {
            strategy: Strategy::Rules,
            order: Order::Priority,
            threshold_deg: 30.0,
            max_iter: 3,
            solver: SolverKind::Auto,
            smart_measure: Measure::Shape,
            force_optimization: false,
            priority_bins: 5,
            keep_valid: true,
            pass_through_folds: None,
            untangle_sweeps: UNTANGLE_SWEEPS,
        }
    }
}

impl SmoothOptions {
    pub fn with_strategy(mut self, s: Strategy) -> Self {
        self.strategy = s;
        self
    }
    pub fn with_order(mut self, o: Order) -> Self {
        self.order = o;
        self
    }
    pub fn with_threshold_deg(mut self, t: f64) -> Self {
        self.threshold_deg = t;
        self
    }
    pub fn with_max_iter(mut self, n: u32) -> Self {
        self.max_iter = n;
        self
    }
    pub fn with_solver(mut self, s: SolverKind) -> Self {
        self.solver = s;
        self
    }
    pub fn with_smart_measure(mut self, m: Measure) -> Self {
        self.smart_measure = m;
        self
    }
    /// Forces [`SmoothOptions::pass_through_folds`] on or off.
    pub fn with_pass_through_folds(mut self, on: bool) -> Self {
        self.pass_through_folds = Some(on);
        self
    }
    pub fn with_untangle_sweeps(mut self, n: u32) -> Self {
        self.untangle_sweeps = n;
        self
    }
    pub fn with_keep_valid(mut self, on: bool) -> Self {
        self.keep_valid = on;
        self
    }
    /// Checks the settings, naming the first unusable one.
    pub fn validate(&self) -> Result<()> {
        if !(self.threshold_deg.is_finite() && self.threshold_deg > 0.0 && self.threshold_deg <= 90.0) {
            return Err(Error::invalid(format!(
                "threshold angle {}° is out of range: give an angle above 0° and at most 90°",
                self.threshold_deg
            )));
        }
        if self.untangle_sweeps > 1000 {
            return Err(Error::invalid(format!("{} untangling sweeps: give 0 to 1000", self.untangle_sweeps)));
        }
        if self.priority_bins == 0 || self.priority_bins > 1000 {
            return Err(Error::invalid(format!("{} priority bins: give 1 to 1000", self.priority_bins)));
        }
        Ok(())
    }
    /// The solver settings these options imply (history off).
    pub fn solve_options(&self) -> SolveOptions {
        SolveOptions::default().with_max_iter(self.max_iter)
    }
}

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
    fn add_to(self, rec: &mut PassRecord) {
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

/// The worst measures of a star (or one element) at a position.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct StarQuality {
    /// Smallest α (triangles) / β (quads).
    pub min_shape: f64,
    /// Smallest sine of a corner angle.
    pub min_sine: f64,
    /// Elements with a corner of `det ≤ 0`.
    pub inverted: u32,
}

impl StarQuality {
    const BEST: StarQuality = StarQuality { min_shape: f64::INFINITY, min_sine: f64::INFINITY, inverted: 0 };
    fn measure(&self, m: Measure) -> f64 {
        match m {
            Measure::Shape => self.min_shape,
            Measure::MinSine => self.min_sine,
        }
    }
    fn merge(&mut self, o: StarQuality) {
        self.min_shape = self.min_shape.min(o.min_shape);
        self.min_sine = self.min_sine.min(o.min_sine);
        self.inverted += o.inverted;
    }
}

/// Shape, smallest sine and validity of one element from its node coordinates — the same
/// definitions as [`crate::quality::element_quality`] without the angles and condition
/// numbers the smoothers do not need.
pub(crate) fn element_measures(kind: crate::mesh::ElementKind, p: &[DVec2; 9]) -> StarQuality {
    let k = kind.corners();
    let ce = corner_edges(kind, p);
    let mut q = StarQuality::BEST;
    let mut min_alpha = f64::INFINITY;
    for &(e1, e2) in &ce[..k] {
        q.min_sine = q.min_sine.min(scaled_jacobian(e1, e2));
        if e1.perp_dot(e2) <= 0.0 {
            q.inverted = 1;
        }
        if k == 3 {
            min_alpha = min_alpha.min(lo_alpha_corner(e1, e2));
        }
    }
    q.min_shape = if k == 3 { min_alpha } else { canann_beta_from_corners(&ce) };
    q
}


/// The shape measure (α/β, [`Measure::Shape`]) of a star element with its free node at `x`
/// and whether the element is inverted: what [`element_measures`] gives for them, without
/// the sines. A linear triangle is measured from its three points directly (one cross
/// product: its corners share one determinant), the common case of the smart Laplacian and
/// the priority order, scaled by a power of two when its squared edge lengths would leave
/// the doubles (so the same at every scale); elements of other kinds by
/// [`element_measures`].
#[inline]
pub(crate) fn element_shape_at(e: &StarElement, x: DVec2) -> (f64, bool) {
    if e.kind == crate::mesh::ElementKind::Tri3 {
        let s = e.slot as usize;
        let (a, b) = (e.pts[(s + 1) % 3], e.pts[(s + 2) % 3]);
        let (mut u, mut v, mut w) = (a - x, b - x, b - a);
        let squares = |u: DVec2, v: DVec2, w: DVec2| u.length_squared() + v.length_squared() + w.length_squared();
        if u == DVec2::ZERO && v == DVec2::ZERO {
            return (0.0, true); // three coincident points: α 0, as lo_alpha_corner; det 0: inverted
        }
        let mut d = squares(u, v, w);
        const LO: f64 = 2.409_919_865_102_884e-271; // 2^-900
        const HI: f64 = 8.452_712_498_170_644e270; // 2^900
        if !(LO..=HI).contains(&d) {
            // the squares leave the doubles: the same formula on the points scaled by a
            // power of two (exact, and before subtracting: differences of tiny coordinates
            // can be subnormal), so α is the same, bit for bit, at every scale
            let m = u.abs().max_element().max(v.abs().max_element()).max(w.abs().max_element());
            if let Some(f) = crate::optimize::unit_factor(m) {
                let (a, b, x) = (f * a, f * b, f * x);
                (u, v, w) = (a - x, b - x, b - a);
                d = squares(u, v, w);
            }
        }
        if (LO..=HI).contains(&d) {
            let n = u.perp_dot(v);
            return (TWO_SQRT3 * n / d, n <= 0.0);
        }
    }
    let q = element_measures(e.kind, &e.at(x));
    (q.min_shape, q.inverted > 0)
}

/// The smallest shape measure (α/β) of the star with its free node at `x` and the number
/// of its inverted elements ([`element_shape_at`] over the star).
pub(crate) fn star_shape(star: &Star, x: DVec2) -> (f64, u32) {
    let (mut min, mut inverted) = (f64::INFINITY, 0);
    for e in &star.elems {
        let (q, inv) = element_shape_at(e, x);
        min = min.min(q);
        inverted += inv as u32;
    }
    (min, inverted)
}

/// The star's worst measures with the free node at its gathered position (`x = None`,
/// the mesh as it is) or moved to `x` (mid-side nodes following).
pub(crate) fn star_quality(star: &Star, x: Option<DVec2>) -> StarQuality {
    let mut q = StarQuality::BEST;
    for e in &star.elems {
        q.merge(element_measures(e.kind, &at(e, x)));
    }
    q
}

fn at(e: &StarElement, x: Option<DVec2>) -> [DVec2; 9] {
    match x {
        Some(x) => e.at(x),
        None => e.pts,
    }
}

/// Centroid of the neighbouring corner nodes of `n` (Laplacian smoothing).
fn centroid(mesh: &Mesh, n: usize) -> Option<DVec2> {
    let nb = mesh.neighbours(n);
    if nb.is_empty() {
        return None;
    }
    let s: DVec2 = nb.iter().map(|&m| mesh.nodes[m as usize]).sum();
    Some(s / nb.len() as f64)
}

/// A smoothing driver with its scratch buffers. One `Smoother` serves any number of passes
/// over one mesh (or several meshes in turn); nothing is allocated per node.
#[derive(Clone, Debug)]
pub struct Smoother {
    options: SmoothOptions,
    star: Star,
    solvers: Solvers,
    terms: Vec<Term>,
    /// Star quality of each node when the schedule was planned (priority order).
    quality: Vec<f64>,
    /// Free nodes, worst first.
    ranked: Vec<u32>,
    /// Visit sequence of the current (or last) pass.
    schedule: Vec<u32>,
    /// Next node to measure while planning in steps ([`Smoother::plan_some`]).
    plan_next: usize,
    /// Visit sequence of the current (or last) untangling sweep.
    revisits: Vec<u32>,
    /// Per node: whether it is already in `revisits` (scratch, all false between uses).
    marked: Vec<bool>,
    /// The pass's move count when its last untangling sweep was planned (`None` before the
    /// first sweep of a pass): a sweep that added no move ends the sweeps.
    sweep_moves_from: Option<u32>,
    passes: u32,
    /// Per-mesh facts, refreshed each pass.
    quadratic: bool,
    curved: bool,
    /// `sin θ_t` of the combined schemes, computed once (not per visit).
    sine_threshold: f64,
}

impl Smoother {
    /// A smoother with checked options.
    pub fn new(options: SmoothOptions) -> Result<Self> {
        options.validate()?;
        let solve = options.solve_options();
        Ok(Smoother {
            options,
            star: Star::new(),
            solvers: Solvers::new(solve),
            terms: Vec::new(),
            quality: Vec::new(),
            ranked: Vec::new(),
            schedule: Vec::new(),
            plan_next: 0,
            revisits: Vec::new(),
            marked: Vec::new(),
            sweep_moves_from: None,
            passes: 0,
            quadratic: false,
            curved: false,
            sine_threshold: options.threshold_deg.to_radians().sin(),
        })
    }

    pub fn options(&self) -> &SmoothOptions {
        &self.options
    }

    /// Passes run so far.
    pub fn passes(&self) -> u32 {
        self.passes
    }

    /// The visit sequence planned by the last [`plan`](Self::plan) (or pass).
    pub fn schedule(&self) -> &[u32] {
        &self.schedule
    }

    fn refresh_mesh_facts(&mut self, mesh: &Mesh) {
        self.quadratic = mesh.has_quadratic();
        self.curved = self.quadratic && mesh.edges().iter().any(|e| e.curved);
    }

    /// Plans the visit sequence of the next pass, returns it (also kept in
    /// [`schedule`](Self::schedule)).
    ///
    /// [`Order::Input`]: the free nodes in node order.
    ///
    /// [`Order::Priority`] — our reading of Chen et al. (2003) §4.2: the priority is computed
    /// once per pass from each free node's star quality (the smallest α/β of its elements).
    /// The range [worst, best] of these is split linearly into `B` =
    /// [`SmoothOptions::priority_bins`] (5) equal bins; the worst bin has the highest
    /// priority `B−1`, the best bin priority 0 (all nodes get priority 0 when every star is
    /// equally good). An inner loop lowers the current priority from `B−1` to 0 and smooths
    /// every node whose priority is at or above it ("if the current node's priority is less
    /// than that of the current priority, it will not be smoothed in the inner priority
    /// loop"). So the worst nodes are visited up to `B` times a pass, the best once; within
    /// one inner loop nodes go worst first (ties by node number).
    pub fn plan(&mut self, mesh: &Mesh) -> &[u32] {
        self.begin_plan(mesh);
        while !self.plan_some(mesh, usize::MAX) {}
        &self.schedule
    }

    /// Starts planning the next pass in steps: [`plan_some`](Self::plan_some) until it
    /// returns true gives the same [`schedule`](Self::schedule) as [`plan`](Self::plan),
    /// for a caller that must stay responsive (the page: measuring every star of a
    /// 1M-node mesh for the priority order takes seconds).
    pub fn begin_plan(&mut self, mesh: &Mesh) {
        self.schedule.clear();
        self.sweep_moves_from = None;
        self.ranked.clear();
        self.plan_next = 0;
        if self.options.order == Order::Priority {
            self.quality.clear();
            self.quality.resize(mesh.node_count(), f64::NAN);
        }
    }

    /// Plans on from where [`begin_plan`](Self::begin_plan) or the last call left off,
    /// measuring at most `max_stars` more stars (at least one) for the priority order.
    /// Returns true when the schedule is complete.
    pub fn plan_some(&mut self, mesh: &Mesh, max_stars: usize) -> bool {
        let n = mesh.node_count();
        if self.plan_next >= n {
            return true;
        }
        match self.options.order {
            Order::Input => {
                self.schedule.extend((0..n as u32).filter(|&i| mesh.is_free(i as usize)));
                self.plan_next = n;
                true
            }
            Order::Priority => {
                let mut measured = 0usize;
                while self.plan_next < n && measured < max_stars.max(1) {
                    let i = self.plan_next;
                    if mesh.is_free(i) {
                        self.star.gather(mesh, i);
                        self.quality[i] = star_shape(&self.star, self.star.x0).0;
                        self.ranked.push(i as u32);
                        measured += 1;
                    }
                    self.plan_next += 1;
                }
                if self.plan_next < n {
                    return false;
                }
                self.schedule_by_priority();
                true
            }
        }
    }

    /// The priority schedule from the measured star qualities (see [`plan`](Self::plan)).
    fn schedule_by_priority(&mut self) {
        let q = &self.quality;
        self.ranked.sort_unstable_by(|&a, &b| q[a as usize].total_cmp(&q[b as usize]).then(a.cmp(&b)));
        let bins = self.options.priority_bins;
        let (Some(&first), Some(&last)) = (self.ranked.first(), self.ranked.last()) else {
            return;
        };
        let (lo, hi) = (q[first as usize], q[last as usize]);
        let range = hi - lo;
        let priority = |v: f64| -> u32 {
            if !(range > 0.0 && range.is_finite()) {
                return 0;
            }
            let bin = ((v - lo) / range * bins as f64).floor();
            let bin = if bin.is_nan() { 0 } else { (bin.max(0.0) as u32).min(bins - 1) };
            bins - 1 - bin
        };
        for level in (0..bins).rev() {
            for &i in &self.ranked {
                if priority(q[i as usize]) < level {
                    break; // ranked worst first: the rest have lower priority
                }
                self.schedule.push(i);
            }
        }
    }

    /// One pass over the mesh: plan the visit order, smooth each visit, then measure.
    /// `clock` returns milliseconds (any origin); the core never reads system time.
    pub fn pass(&mut self, mesh: &mut Mesh, objective: &dyn Objective, clock: &dyn Fn() -> f64) -> PassRecord {
        self.passes += 1;
        let t0 = clock();
        let counts = self.sweep(mesh, objective);
        let elapsed = clock() - t0;
        self.record(mesh, objective, self.passes, counts, elapsed)
    }

    /// The record of a pass: its counts and time, and the mesh's statistics now.
    pub(crate) fn record(
        &mut self,
        mesh: &Mesh,
        objective: &dyn Objective,
        pass: u32,
        counts: SweepCounts,
        elapsed_ms: f64,
    ) -> PassRecord {
        let mut rec = PassRecord {
            pass,
            visits: 0,
            inverted: 0,
            min_angle_deg: 0.0,
            max_angle_deg: 0.0,
            min_quality: 0.0,
            objective_total: 0.0,
            laplacian_moves: 0,
            optimization_calls: 0,
            solver_iterations: 0,
            untangle_sweeps: 0,
            elapsed_ms,
        };
        counts.add_to(&mut rec);
        let stats = mesh_stats(mesh);
        rec.inverted = stats.inverted;
        rec.min_angle_deg = stats.min_angle_deg;
        rec.max_angle_deg = stats.max_angle_deg;
        rec.min_quality = stats.min_quality;
        rec.objective_total = self.objective_total(mesh, objective);
        rec
    }

    /// The node loop of a pass alone: plans the visit order and smooths each visit, without
    /// the statistics [`pass`](Self::pass) adds (a whole-mesh [`mesh_stats`] and
    /// [`objective_total`](Self::objective_total), which cost more than a Laplacian sweep).
    /// Counts as [`pass`](Self::pass) does; does not count as a pass.
    pub fn sweep(&mut self, mesh: &mut Mesh, objective: &dyn Objective) -> SweepCounts {
        self.refresh_mesh_facts(mesh);
        self.plan(mesh);
        let schedule = std::mem::take(&mut self.schedule);
        let mut counts = self.visit_all(mesh, &schedule, objective);
        self.schedule = schedule;
        while self.plan_untangle_sweep(mesh, &mut counts) {
            let revisits = std::mem::take(&mut self.revisits);
            let c = self.visit_all(mesh, &revisits, objective);
            self.revisits = revisits;
            counts.merge(c);
        }
        counts
    }

    /// Plans the next untangling sweep of a pass whose visits so far `counts` holds (see
    /// [`SmoothOptions::untangle_sweeps`]): the free nodes of every inverted element and
    /// the free neighbours of its corners, worst star first (smallest α/β, ties by node
    /// number), into [`revisits`](Self::revisits), counted in `counts.untangle_sweeps`.
    /// Returns false — no sweep — when no element is inverted, the sweeps are at their
    /// limit, the last sweep moved no node, or the strategy never optimises. The one
    /// place that decides, for [`sweep`](Self::sweep) and for the page's sliced pass.
    pub fn plan_untangle_sweep(&mut self, mesh: &Mesh, counts: &mut SweepCounts) -> bool {
        self.revisits.clear();
        let stalled = self.sweep_moves_from.is_some_and(|m| counts.moves == m);
        if stalled
            || counts.untangle_sweeps >= self.options.untangle_sweeps
            || matches!(self.options.strategy, Strategy::Laplace | Strategy::Smart)
        {
            return false;
        }
        self.marked.clear();
        self.marked.resize(mesh.node_count(), false);
        for e in 0..mesh.element_count() {
            let kind = mesh.kind(e);
            if !is_inverted(kind, &mesh.element_points_array(e)) {
                continue;
            }
            for &c in &mesh.element(e)[..kind.corners()] {
                let c = c as usize;
                for m in std::iter::once(c).chain(mesh.neighbours(c).iter().map(|&m| m as usize)) {
                    if mesh.is_free(m) && !self.marked[m] {
                        self.marked[m] = true;
                        self.revisits.push(m as u32);
                    }
                }
            }
        }
        let mut ranked: Vec<(f64, u32)> = Vec::with_capacity(self.revisits.len());
        for &n in &self.revisits {
            self.marked[n as usize] = false;
            self.star.gather(mesh, n as usize);
            ranked.push((star_shape(&self.star, self.star.x0).0, n));
        }
        ranked.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        self.revisits.clear();
        self.revisits.extend(ranked.iter().map(|&(_, n)| n));
        if self.revisits.is_empty() {
            return false;
        }
        counts.untangle_sweeps += 1;
        self.sweep_moves_from = Some(counts.moves);
        true
    }

    /// The visit sequence of the last untangling sweep planned.
    pub fn revisits(&self) -> &[u32] {
        &self.revisits
    }

    /// Visits the nodes of `order` in turn (the mesh facts must be fresh).
    pub(crate) fn visit_all(&mut self, mesh: &mut Mesh, order: &[u32], objective: &dyn Objective) -> SweepCounts {
        let mut c = SweepCounts::default();
        for &n in order {
            c.add(self.visit(mesh, n as usize, objective));
        }
        c
    }

    /// The sum over free nodes of the node objective value (see [`PassRecord::objective_total`]).
    pub fn objective_total(&mut self, mesh: &Mesh, objective: &dyn Objective) -> f64 {
        let mut total = 0.0;
        for n in 0..mesh.node_count() {
            if mesh.is_free(n) {
                self.star.gather(mesh, n);
                total += evaluate(objective, &self.star, mesh.nodes[n], &mut self.terms).0;
            }
        }
        total
    }

    /// Smooths one node by the strategy (fixed nodes and mid-side nodes are left alone).
    pub fn smooth_node(&mut self, mesh: &mut Mesh, node: usize, objective: &dyn Objective) -> NodeOutcome {
        self.refresh_mesh_facts(mesh);
        self.visit(mesh, node, objective)
    }

    fn visit(&mut self, mesh: &mut Mesh, n: usize, objective: &dyn Objective) -> NodeOutcome {
        let (x, out) = self.decide(mesh, n, objective);
        if out.moved {
            self.place(mesh, n, x);
        }
        out
    }

    /// Where the strategy moves node `n`, without writing to the mesh: the new position
    /// (the old one when it stays) and what happened. The node's own position is tracked
    /// in the gathered star ([`Star::x0`], kept current by `restar`) and mid-side nodes
    /// that follow it are moved in the star only, so a node reads nothing but its star and
    /// its neighbours. Nodes that share no element can therefore be decided in any order,
    /// or at once ([`crate::smooth::parallel`]), with the same results.
    pub(crate) fn decide(&mut self, mesh: &Mesh, n: usize, objective: &dyn Objective) -> (DVec2, NodeOutcome) {
        let mut out = NodeOutcome::default();
        if n >= mesh.node_count() || !mesh.is_free(n) {
            return (DVec2::ZERO, out);
        }
        let x0 = mesh.nodes[n];
        let mut x = x0;
        let sine_t = self.sine_threshold;
        match self.options.strategy {
            Strategy::Laplace => {
                if let Some(c) = self.laplace(mesh, n, &mut out) {
                    x = c;
                }
            }
            Strategy::Smart => {
                self.star.gather(mesh, n);
                self.smart(mesh, n, &mut out);
                x = self.star.x0;
            }
            Strategy::Opt => {
                self.star.gather(mesh, n);
                self.optimize(objective, &mut out);
                x = self.star.x0;
            }
            Strategy::C1 => {
                self.star.gather(mesh, n);
                if star_quality(&self.star, None).min_sine > sine_t {
                    self.smart(mesh, n, &mut out);
                } else {
                    self.optimize(objective, &mut out);
                }
                x = self.star.x0;
            }
            Strategy::C2 => {
                self.star.gather(mesh, n);
                self.smart(mesh, n, &mut out);
                if star_quality(&self.star, None).min_sine <= sine_t {
                    self.optimize(objective, &mut out);
                }
                x = self.star.x0;
            }
            Strategy::C3 => {
                self.star.gather(mesh, n);
                let before = star_quality(&self.star, None);
                if before.min_sine <= sine_t {
                    if let Some(c) = self.laplace(mesh, n, &mut out) {
                        self.restar(c);
                    }
                    if star_quality(&self.star, None).min_sine <= sine_t {
                        self.optimize(objective, &mut out);
                    }
                    // Freitag's C3 starts with the plain Laplacian, which may fold an element
                    // or lower the star's quality (the smart Laplacian's measure), and the
                    // optimization from there may not win it back. Like the other combined
                    // schemes, C3 never leaves a star worse than it found it: then the node
                    // stays where it was.
                    let after = star_quality(&self.star, None);
                    let m = self.options.smart_measure;
                    if after.inverted > before.inverted || after.measure(m) < before.measure(m) {
                        self.restar(x0);
                    }
                }
                x = self.star.x0;
            }
            Strategy::Rules => {
                self.star.gather(mesh, n);
                let forced = self.options.force_optimization
                    || self.touches_curved_boundary(mesh, n)
                    || star_shape(&self.star, self.star.x0).1 > 0;
                if forced || !self.smart(mesh, n, &mut out) {
                    self.optimize(objective, &mut out);
                }
                x = self.star.x0;
            }
        }
        out.moved = x != x0;
        (x, out)
    }

    /// Moves the gathered star's free node to `x` (after a move), keeping the star valid.
    fn restar(&mut self, x: DVec2) {
        self.star.x0 = x;
        for e in &mut self.star.elems {
            e.move_free_node(x);
        }
    }

    fn place(&mut self, mesh: &mut Mesh, n: usize, x: DVec2) {
        mesh.nodes[n] = x;
        if self.quadratic {
            mesh.follow_mid_nodes(n);
        }
    }

    /// Plain Laplacian: the centroid when the node moves there, `None` when it stays.
    fn laplace(&mut self, mesh: &Mesh, n: usize, out: &mut NodeOutcome) -> Option<DVec2> {
        match centroid(mesh, n) {
            Some(c) if c.is_finite() && c != mesh.nodes[n] => {
                out.laplacian = true;
                Some(c)
            }
            _ => None,
        }
    }

    /// Smart Laplacian on the gathered star; returns whether the node moved (the star is
    /// moved with it). The star's quality now is measured at the star's position; at the
    /// centroid with the mid-side nodes of straight edges following.
    fn smart(&mut self, mesh: &Mesh, n: usize, out: &mut NodeOutcome) -> bool {
        let Some(c) = centroid(mesh, n) else { return false };
        if !c.is_finite() || c == self.star.x0 {
            return false;
        }
        let m = self.options.smart_measure;
        let (mut before, mut after) = (f64::INFINITY, f64::INFINITY);
        let x0 = self.star.x0;
        for e in &self.star.elems {
            let ((q0, inv0), (q1, inv1)) = match m {
                Measure::Shape => (element_shape_at(e, x0), element_shape_at(e, c)),
                Measure::MinSine => {
                    let (q0, q1) = (element_measures(e.kind, &e.pts), element_measures(e.kind, &e.at(c)));
                    ((q0.min_sine, q0.inverted > 0), (q1.min_sine, q1.inverted > 0))
                }
            };
            if !inv0 && inv1 {
                return false;
            }
            before = before.min(q0);
            after = after.min(q1);
        }
        if after > before {
            self.restar(c);
            out.laplacian = true;
            true
        } else {
            false
        }
    }

    /// Optimization with the chosen solver on the gathered star, from the star's position.
    /// With [`SmoothOptions::keep_valid`] the solver sees the objective through
    /// [`KeepValid`].
    fn optimize(&mut self, objective: &dyn Objective, out: &mut NodeOutcome) {
        let x0 = self.star.x0;
        let guarded;
        let objective: &dyn Objective = if self.options.keep_valid {
            let limit = self.star.elems.iter().filter(|e| is_inverted(e.kind, &e.pts)).count();
            let pass_through_folds = self.options.pass_through_folds.unwrap_or_else(|| objective.untangles());
            guarded = KeepValid {
                inner: objective,
                limit,
                pass_through_folds,
                inversion0: std::cell::OnceCell::new(),
            };
            &guarded
        } else {
            objective
        };
        let r = self.solvers.get(self.options.solver, objective.goal()).solve(objective, &self.star, x0);
        out.optimized = true;
        out.iterations += r.iterations;
        if r.x.is_finite() && r.x != x0 {
            self.restar(r.x);
        }
    }

    /// Chen's rule 1: the node, a neighbour, or a node of a star element lies on a curved
    /// boundary edge.
    fn touches_curved_boundary(&self, mesh: &Mesh, n: usize) -> bool {
        self.curved
            && (mesh.is_on_curved_boundary(n)
                || mesh.neighbours(n).iter().any(|&m| mesh.is_on_curved_boundary(m as usize))
                || mesh
                    .node_elements(n)
                    .iter()
                    .any(|&e| mesh.element(e as usize).iter().any(|&m| mesh.is_on_curved_boundary(m as usize))))
    }
}

/// Whether an element has a corner with `det ≤ 0` (the definition of
/// [`crate::quality::ElementQuality::inverted`]).
fn is_inverted(kind: crate::mesh::ElementKind, p: &[DVec2; 9]) -> bool {
    corner_edges(kind, p)[..kind.corners()].iter().any(|(e1, e2)| e1.perp_dot(*e2) <= 0.0)
}

/// [`is_inverted`] of a star element with its free node at `x`; a linear triangle without
/// the general element machinery (the same corner edge vectors, so the same answer).
fn is_inverted_at(el: &crate::objective::StarElement, x: DVec2) -> bool {
    if el.kind != crate::mesh::ElementKind::Tri3 {
        return is_inverted(el.kind, &el.at(x));
    }
    let s = el.slot as usize;
    let (a, b) = (el.pts[(s + 1) % 3], el.pts[(s + 2) % 3]);
    // corners C (free), A, B: (next − this, previous − this)
    (a - x).perp_dot(b - x) <= 0.0 || (b - a).perp_dot(x - a) <= 0.0 || (x - b).perp_dot(a - b) <= 0.0
}

/// An objective seen through [`SmoothOptions::keep_valid`]: the same terms, plus a NaN
/// term at a trial position that raises the star's number of inverted elements — unless
/// [`SmoothOptions::pass_through_folds`] is set, the star was inverted to begin with and
/// the position lowers its [`inversion`]. Both solvers read NaN as the worst value of the goal (+∞ for a sum, −∞ for a
/// minimum), so they never step there; at valid positions values and gradients are the
/// objective's own.
struct KeepValid<'a> {
    inner: &'a dyn Objective,
    /// Inverted star elements when the call began.
    limit: usize,
    /// [`SmoothOptions::pass_through_folds`], resolved for the objective.
    pass_through_folds: bool,
    /// The star's [`inversion`] at its start, taken once, from the star the solver passes
    /// (a solve passes one star throughout: the gathered one or one rescaled copy).
    inversion0: std::cell::OnceCell<f64>,
}

/// How deeply the star is inverted with its free node at `x`: `Σ max(0, −det)` over every
/// corner of every star element (Knupp's `Σ (|det| − det) / 2`, 0 for a valid star). An
/// area, compared only within one star.
fn inversion(star: &Star, x: DVec2) -> f64 {
    let mut t = 0.0;
    for e in &star.elems {
        let p = e.at(x);
        for (e1, e2) in &crate::quality::corner_edge_vectors(e.kind, &p)[..e.kind.corners()] {
            t += (-e1.perp_dot(*e2)).max(0.0);
        }
    }
    t
}

impl Objective for KeepValid<'_> {
    fn name(&self) -> &'static str {
        self.inner.name()
    }
    fn goal(&self) -> crate::objective::Goal {
        self.inner.goal()
    }
    fn untangles(&self) -> bool {
        self.inner.untangles()
    }
    fn terms(&self, star: &Star, x: DVec2, out: &mut Vec<Term>) {
        self.inner.terms(star, x, out);
        if self.refuses(star, x) {
            out.push(Term { elem: 0, value: f64::NAN, grad: DVec2::ZERO });
        }
    }
    fn value_and_gradient(&self, star: &Star, x: DVec2) -> (f64, DVec2) {
        // a refused position is NaN whatever the objective says there: skip evaluating it
        // (the solvers never use the gradient of a NaN point)
        if self.refuses(star, x) {
            return (f64::NAN, DVec2::ZERO);
        }
        self.inner.value_and_gradient(star, x)
    }
}

impl KeepValid<'_> {
    /// Whether a trial position is refused: a valid star must stay valid; an inverted one
    /// may fold another element on the way out, provided its total inversion falls (see
    /// [`SmoothOptions::keep_valid`]).
    fn refuses(&self, star: &Star, x: DVec2) -> bool {
        let inverted = star.elems.iter().filter(|e| is_inverted_at(e, x)).count();
        // the inversion at the start is taken from the star the solver passes, so that it
        // is in the same frame as at `x` (a solver may pass a rescaled copy: optimize)
        inverted > self.limit
            && (!self.pass_through_folds
                || self.limit == 0
                || inversion(star, x) >= *self.inversion0.get_or_init(|| inversion(star, star.x0)))
    }
}

/// Runs `passes` passes of a new [`Smoother`] over `mesh`, returning their records.
pub fn smooth(
    mesh: &mut Mesh,
    objective: &dyn Objective,
    options: SmoothOptions,
    passes: u32,
    clock: &dyn Fn() -> f64,
) -> Result<Vec<PassRecord>> {
    let mut s = Smoother::new(options)?;
    Ok((0..passes).map(|_| s.pass(mesh, objective, clock)).collect())
}

/// Solves the objective at one free node with its history recorded, without moving it
/// (for the page's level-set view and convergence chart). The solver is chosen by
/// [`SmoothOptions::solver`]; [`SmoothOptions::max_iter`] limits the iterations.
pub fn solve_node(mesh: &Mesh, node: usize, objective: &dyn Objective, options: &SmoothOptions) -> Result<SolveResult> {
    if node >= mesh.node_count() {
        return Err(Error::node(node, None, format!("no such node: the mesh has {} nodes", mesh.node_count())));
    }
    if !mesh.is_free(node) {
        return Err(Error::node(node, None, "is fixed or not an element corner, so it is never smoothed"));
    }
    let mut star = Star::new();
    star.gather(mesh, node);
    let solve = options.solve_options().with_history(true);
    solve.validate()?;
    Ok(Solvers::new(solve).get(options.solver, objective.goal()).solve(objective, &star, mesh.nodes[node]))
}
