//! What a smoothing run is asked to do: the strategy, the node order, the measures and
//! the options of the drivers, checked.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::optimize::{SolveOptions, SolverKind};

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
    /// As the page's menu shows it.
    pub fn label(self) -> &'static str {
        match self {
            Strategy::Laplace => "Laplacian",
            Strategy::Smart => "Smart Laplacian",
            Strategy::Opt => "Optimization only",
            Strategy::C1 => "Freitag C1",
            Strategy::C2 => "Freitag C2",
            Strategy::C3 => "Freitag C3",
            Strategy::Rules => "Chen's rules (smart Laplacian, else optimize)",
        }
    }
    /// What it does, in a sentence (the menu's tooltip and the command line's help).
    pub fn describe(self) -> &'static str {
        match self {
            Strategy::Laplace => "Move each node to the centre of its neighbours (may tangle the mesh)",
            Strategy::Smart => "Move each node to the centre of its neighbours only where that does not worsen its star",
            Strategy::Opt => "Optimize every free node with the chosen objectives",
            Strategy::C1 => {
                "Freitag's C1: smart Laplacian where the star's smallest angle is above the threshold, else optimization"
            }
            Strategy::C2 => {
                "Freitag's C2: smart Laplacian, then optimization where the smallest angle is still not above the threshold"
            }
            Strategy::C3 => {
                "Freitag's C3: only stars whose smallest angle is not above the threshold: Laplacian, then optimization if still not above it"
            }
            Strategy::Rules => {
                "Chen's rules: optimize a node next to an inverted element or a curved boundary, or one the constrained Laplacian could not move; else the constrained Laplacian"
            }
        }
    }
    /// As people name it in a sentence ("the smart Laplacian", "Freitag's C1").
    pub fn words(self) -> &'static str {
        match self {
            Strategy::Laplace => "the Laplacian",
            Strategy::Smart => "the smart Laplacian",
            Strategy::Opt => "optimization only",
            Strategy::C1 => "Freitag's C1",
            Strategy::C2 => "Freitag's C2",
            Strategy::C3 => "Freitag's C3",
            Strategy::Rules => "Chen's rules",
        }
    }
    /// Why the threshold angle ([`SmoothOptions::threshold_deg`]) does nothing for this
    /// strategy, if it does nothing (only Freitag's combined strategies C1–C3 compare a
    /// star's minimum angle with it).
    pub fn threshold_unused(self) -> Option<String> {
        match self {
            Strategy::C1 | Strategy::C2 | Strategy::C3 => None,
            Strategy::Rules => Some(
                "Chen's rules decide by their own tests (curved boundary, invalid element, Laplacian failed), not by an angle"
                    .into(),
            ),
            Strategy::Laplace | Strategy::Smart | Strategy::Opt => {
                Some(format!("only Freitag's C1, C2 and C3 use a threshold angle, not {}", self.words()))
            }
        }
    }
    /// Why the solver's iteration limit ([`SmoothOptions::max_iter`]) does nothing for
    /// this strategy, if it does nothing (the Laplacian strategies never call the solver).
    pub fn max_iter_unused(self) -> Option<String> {
        match self {
            Strategy::Laplace | Strategy::Smart => {
                Some(format!("{} never calls the solver, so it has no iterations to limit", self.words()))
            }
            Strategy::Opt | Strategy::C1 | Strategy::C2 | Strategy::C3 | Strategy::Rules => None,
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
        /// Chen et al. (2003) §4.2, "worst one first": see [`Smoother::plan`](crate::smooth::Smoother::plan).
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
    /// As the page's menu shows it.
    pub fn label(self) -> &'static str {
        match self {
            Order::Input => "Input order",
            Order::Priority => "Priority (worst first)",
        }
    }
    /// What it does, in a sentence (the menu's tooltip and the command line's help).
    pub fn describe(self) -> &'static str {
        match self {
            Order::Input => "In the order of the file",
            Order::Priority => "Worst star first, in bins of quality (Chen et al. §4.2)",
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

impl Measure {
    /// The measure a run optimizing objective `kind` from a mesh that is `valid` (no
    /// element inverted) judges its moves and ranks its nodes by: Freitag's smallest sine
    /// for her `sine` on a valid mesh, her setting (her optimization keeps a move only
    /// where the star's smallest sine does not fall; her smart Laplacian and thresholds
    /// read it too); the shape for every other objective, and for `sine` on a tangled
    /// mesh, where the sine judged moves worse (the comparison script's tangled runs of
    /// `sine`: mean quality 26 better, 60 worse, the tangled quad sphere with `c1` left
    /// with 2 inverted). The finish's max-min sine passes read the sine as well.
    pub fn for_run(kind: crate::objective::ObjectiveKind, valid: bool) -> Measure {
        use crate::objective::ObjectiveKind as K;
        match kind {
            K::Sine if valid => Measure::MinSine,
            K::Sine => Measure::Shape,
            K::MaxMinShape | K::SmoothShape | K::Condition | K::ConditionMax | K::Untangle | K::UntangleMinDet => {
                Measure::Shape
            }
        }
    }
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
    /// [`Measure::MinSine`] is Freitag's choice. A run of an objective takes
    /// [`Measure::for_run`].
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
    ///
    /// With the check, every strategy but `Laplace` also keeps a node's move only when
    /// its star gets no worse (the acceptance rule, `docs/formulas.md` §4, by
    /// [`SmoothOptions::smart_measure`]): a valid star's worst element not worse and none
    /// flattened, an inverted star no more deeply inverted.
    pub keep_valid: bool,
    /// With [`SmoothOptions::keep_valid`]: a star that is already inverted when the call
    /// begins may fold one more element when that lowers its total inversion
    /// `Σ max(0, −det)` over all its corners. A valid star is still never folded. `None`
    /// (the default): on for objectives built to untangle ([`Objective::untangles`](crate::objective::Objective::untangles):
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
    /// Fletcher–Reeves tries a Newton step first where the objective has an analytic
    /// Hessian ([`SolveOptions::newton`]; `new`'s barrier design). Default true: as good
    /// as Chen's search alone on the meshes of quality and about 1.5× faster, measured in
    /// `docs/performance.md`; false runs Chen's search alone.
    pub newton: bool,
    /// The grading a run keeps every pair of neighbouring elements within, on a valid mesh
    /// ([`crate::quality::Reading::grading`]): the mesh's as the run found it, so that its
    /// passes and its finish share it. `None` (the default): the mesh's at the smoother's
    /// first pass; +∞ keeps none.
    pub keep_grading: Option<f64>,
}

/// The default number of untangling sweeps per pass ([`SmoothOptions::untangle_sweeps`]).
pub const UNTANGLE_SWEEPS: u32 = 10;

/// Passes of a run unless asked otherwise: Chen et al. untangle the plate in 3 (§5.2), and
/// Freitag's Table 1 runs 3 (the CLI's `--passes`, the page's passes control).
pub const DEFAULT_PASSES: u32 = 3;
/// Solver iterations per optimization call: Chen et al.'s 3 (§4.1).
pub const DEFAULT_MAX_ITER: u32 = 3;
/// Threshold angle of Freitag's combined schemes, degrees: her best rows use 30°.
pub const DEFAULT_THRESHOLD_DEG: f64 = 30.0;

impl Default for SmoothOptions {
    fn default() -> Self {
        SmoothOptions {
            strategy: Strategy::Rules,
            order: Order::Priority,
            threshold_deg: DEFAULT_THRESHOLD_DEG,
            max_iter: DEFAULT_MAX_ITER,
            solver: SolverKind::Auto,
            smart_measure: Measure::Shape,
            force_optimization: false,
            priority_bins: 5,
            keep_valid: true,
            pass_through_folds: None,
            untangle_sweeps: UNTANGLE_SWEEPS,
            newton: true,
            keep_grading: None,
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
    pub fn with_newton(mut self, on: bool) -> Self {
        self.newton = on;
        self
    }
    /// Checks the settings, naming the first unusable one.
    pub fn validate(&self) -> Result<()> {
        if !super::limits::threshold_in_range(self.threshold_deg) {
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
        SolveOptions { newton: self.newton, ..SolveOptions::default().with_max_iter(self.max_iter) }
    }
}
