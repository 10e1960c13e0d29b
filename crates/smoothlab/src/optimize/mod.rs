//! Solvers for one free node's objective over its star: Fletcher–Reeves conjugate
//! gradients for the smooth objectives (Chen, Tristano & Kwok 2003, §3) and Freitag's
//! active-set steepest ascent for the max-min objectives (Freitag 1997, Figure 1).
//!
//! Both implement [`Solver`] over any `&dyn Objective`; [`Solvers`] holds one of each and
//! picks by [`SolverKind`]. A solve is [`Solver::start`] then [`Solver::step`] until it
//! stops: [`Solver::solve`] runs them, at unit scale or in a rescaled copy of the star, and
//! returns a [`SolveResult`] with the history as data (the page draws that history).
//! History is recorded only when [`SolveOptions::record_history`] is set, so an ordinary
//! smoothing pass allocates nothing per node.
//!
//! Either solver accepts either goal: Fletcher–Reeves minimises the objective's value for
//! [`Goal::MinimizeSum`] and its negation (with the subgradient of one minimal term) for
//! [`Goal::MaximizeMin`] — Chen's "serious convergence problems" made visible; the ascent
//! maximises the minimum of the terms, or the negated sum as a single term.
//!
//! Every length (initial step, smallest step, largest move) is a fraction of the star's
//! size ([`star_scale`](crate::objective::star_scale)), so the solvers are scale-free; and a star far from unit size
//! (beyond 2^±64) is solved in its own frame, multiplied by a power of two to unit size
//! and the result multiplied back ([`Solver::solve`]). Powers of two are exact, so a
//! solve at any scale moves the node exactly as at unit scale: without this the squared
//! lengths and gradient products over- or underflowed and each solver silently stopped
//! moving nodes outside a window of scales (about 1e±75).
//!
//! The formulas, in one notation: `docs/formulas.md` §6.

use glam::DVec2;
use serde::Serialize;

use crate::numeric::unit_factor;
use crate::objective::{Goal, NodeStar, Objective, Point, Star, Term};

mod fletcher_reeves;
mod line_search;
mod nonsmooth;

pub use fletcher_reeves::FletcherReeves;
pub use line_search::{line_search, LineSearch};
pub use nonsmooth::{min_norm_point, HullPoint, MinNorm, NonSmoothAscent};

/// Small objectives with known optima, for the tests of this crate and the picture crate.
#[cfg(any(test, feature = "testing"))]
#[doc(hidden)]
pub mod test_objectives;
#[cfg(test)]
mod tests;

/// Which way a step went.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum DirectionKind {
    /// Steepest descent, `−∇f` (Fletcher–Reeves' first iteration and every restart).
    Gradient,
    /// Fletcher–Reeves conjugate direction, `−∇f_q + r·d_{q−1}` (Chen eq. 11–12).
    Conjugate,
    /// The minimum-norm point of the hull of the active gradients (Freitag, Figure 1).
    ActiveSet,
    /// A full Newton step `−(∇²f)⁻¹∇f`, taken without a line search because it lowered the
    /// objective enough (Armijo); see [`SolveOptions::newton`].
    Newton,
}

/// Why a solve stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum StopReason {
    /// The iteration limit ([`SolveOptions::max_iter`]) was reached.
    MaxIter,
    /// A zero gradient (Fletcher–Reeves) or a zero min-norm direction (the origin lies in
    /// the hull of the active gradients): the point is stationary / optimal.
    Optimal,
    /// The step shrank below [`SolveOptions::min_step`] of the star size without improving.
    SmallStep,
    /// The last accepted step improved the objective by less than
    /// [`SolveOptions::min_improvement`] (relative).
    SmallImprovement,
    /// The line search found no lower point along the direction (no "high-low-high").
    LineSearchFailed,
    /// The objective (or its gradient) is not finite at the starting point, e.g. a
    /// barrier objective on an inverted star.
    NotFinite,
    /// The star is empty or has zero size.
    DegenerateStar,
}

/// One iteration of a solve: where it went and how.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Iterate<V = DVec2> {
    /// Position after the step.
    pub x: V,
    /// The objective's own value there (not negated for max-min objectives).
    pub value: f64,
    pub direction: DirectionKind,
    /// Length of the move, in mesh units (`|x_q − x_{q−1}|`).
    pub step: f64,
}

/// What a solve returns.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SolveResult<V = DVec2> {
    /// Final position: never worse than the start by the solver's own measure.
    pub x: V,
    /// The objective's value at `x`.
    pub value: f64,
    /// Starting position and value.
    pub x0: V,
    pub value0: f64,
    /// Accepted iterations (steps that moved the node).
    pub iterations: u32,
    pub stop: StopReason,
    /// One entry per iteration, when [`SolveOptions::record_history`] is set; empty
    /// (and unallocated) otherwise.
    pub history: Vec<Iterate<V>>,
}

/// Solver settings. Lengths are fractions of the star size ([`star_scale`](crate::objective::star_scale)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolveOptions {
    /// Iterations per call. Default 3 (Chen §3.1: "a constant number of three is used as
    /// the limit of iterations for each optimization-based smoothing call").
    pub max_iter: u32,
    /// Record each iterate in [`SolveResult::history`]. Default false.
    pub record_history: bool,
    /// Fletcher–Reeves: first trial step of the first line search, as a fraction of the
    /// star size; later searches start from the previous move. Default 0.01 (Chen: "the
    /// initial step length is relatively small").
    pub initial_step: f64,
    /// Line search acceleration factor at the start of each solve; halved after each
    /// failure to find a low point (never below 2). Default 8 (Chen §3.2).
    pub acceleration: f64,
    /// Fletcher–Reeves: every `restart_every`-th iteration restarts with the gradient
    /// direction. Default 2 (the dimension: a 2D quadratic is solved exactly in two).
    pub restart_every: u32,
    /// Evaluations allowed per line search. Default 40.
    pub max_evaluations: u32,
    /// Smallest step, as a fraction of the star size. Default 1e-9.
    pub min_step: f64,
    /// Smallest relative improvement `Δf / max(|f|, tiny)` worth another iteration. Default 1e-12.
    pub min_improvement: f64,
    /// Non-smooth ascent: terms within this fraction of the largest |term| of the minimum
    /// are active. Default 1e-6.
    pub active_tolerance: f64,
    /// Non-smooth ascent: largest move of one step, as a fraction of the star size.
    /// Default 0.5.
    pub max_move: f64,
    /// Fletcher–Reeves: when the objective has an analytic Hessian
    /// ([`Objective::value_gradient_hessian`]) that is positive definite at the current
    /// point, first try the Newton step `−(∇²f)⁻¹∇f` (at most one star size long) and take
    /// it when it lowers the objective by at least 10⁻⁴ of the decrease its gradient
    /// promises (Armijo); otherwise the iteration is Chen's, as without. Default false
    /// here (the solver alone is Chen's); the smoother's default turns it on
    /// ([`crate::smooth::SmoothOptions::newton`]).
    pub newton: bool,
}

impl Default for SolveOptions {
    fn default() -> Self {
        SolveOptions {
            max_iter: 3,
            record_history: false,
            initial_step: 0.01,
            acceleration: 8.0,
            restart_every: 2,
            max_evaluations: 40,
            min_step: 1e-9,
            min_improvement: 1e-12,
            active_tolerance: 1e-6,
            max_move: 0.5,
            newton: false,
        }
    }
}

impl SolveOptions {
    pub fn with_max_iter(mut self, n: u32) -> Self {
        self.max_iter = n;
        self
    }
    pub fn with_history(mut self, on: bool) -> Self {
        self.record_history = on;
        self
    }
    /// Checks that every setting is usable, naming the first that is not.
    pub fn validate(&self) -> crate::Result<()> {
        let positive = |v: f64| v.is_finite() && v > 0.0;
        let bad = if !positive(self.initial_step) {
            Some("initial_step must be a positive number")
        } else if !(self.acceleration.is_finite() && self.acceleration > 1.0) {
            Some("acceleration must be a number above 1")
        } else if self.restart_every == 0 {
            Some("restart_every must be at least 1")
        } else if self.max_evaluations < 3 {
            Some("max_evaluations must be at least 3")
        } else if !positive(self.min_step) {
            Some("min_step must be a positive number")
        } else if !(self.min_improvement.is_finite() && self.min_improvement >= 0.0) {
            Some("min_improvement must be a number ≥ 0")
        } else if !(self.active_tolerance.is_finite() && self.active_tolerance >= 0.0) {
            Some("active_tolerance must be a number ≥ 0")
        } else if !positive(self.max_move) {
            Some("max_move must be a positive number")
        } else {
            None
        };
        match bad {
            Some(m) => Err(crate::Error::invalid(format!("solver options: {m}"))),
            None => Ok(()),
        }
    }
}

/// Which solver optimises a node.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub enum SolverKind {
    /// By the objective's goal: Fletcher–Reeves for [`Goal::MinimizeSum`],
    /// non-smooth ascent for [`Goal::MaximizeMin`].
    #[default]
    Auto,
    FletcherReeves,
    NonSmoothAscent,
}

/// One solver of each kind, built once from the same [`SolveOptions`] and chosen per call
/// by [`SolverKind`]: the drivers hold one of these, so a new solver is one field here and
/// one arm of [`Solvers::get`] (which the compiler asks for), not an edit of each driver.
#[derive(Clone, Debug)]
pub struct Solvers<S: NodeStar = Star> {
    fletcher_reeves: FletcherReeves,
    non_smooth_ascent: NonSmoothAscent<S::Point>,
}

impl<S: NodeStar> Solvers<S> {
    /// Every solver with options `o`.
    pub fn new(o: SolveOptions) -> Self {
        Solvers { fletcher_reeves: FletcherReeves::new(o), non_smooth_ascent: NonSmoothAscent::new(o) }
    }
    /// The solver `kind` names for an objective of `goal` ([`SolverKind::Auto`] resolved).
    pub fn get(&mut self, kind: SolverKind, goal: Goal) -> &mut dyn Solver<S> {
        match (kind, goal) {
            (SolverKind::FletcherReeves, _) | (SolverKind::Auto, Goal::MinimizeSum) => &mut self.fletcher_reeves,
            (SolverKind::NonSmoothAscent, _) | (SolverKind::Auto, Goal::MaximizeMin) => &mut self.non_smooth_ascent,
        }
    }
}

/// The state of a solve between steps. Public fields are for display; the rest is the
/// solver's working memory.
#[derive(Clone, Debug)]
pub struct SolveState<V: Point = DVec2> {
    /// Current position.
    pub x: V,
    /// The objective's value at `x`.
    pub value: f64,
    /// Accepted iterations so far.
    pub iterations: u32,
    /// Set when the solve has stopped.
    pub stop: Option<StopReason>,
    /// Iterates so far (empty unless recording).
    pub history: Vec<Iterate<V>>,
    x0: V,
    value0: f64,
    /// Star size, the unit of every length.
    scale: f64,
    /// Fletcher–Reeves: merit (value, negated for max-min) and its gradient at `x`.
    merit: f64,
    grad: V,
    /// Fletcher–Reeves with [`SolveOptions::newton`]: the merit's Hessian at `x`, when the
    /// objective has one.
    hess: Option<V::Hessian>,
    /// Fletcher–Reeves: previous direction and previous gradient.
    dir: V,
    grad_prev: V,
    /// Conjugate iterations since the last gradient step.
    since_restart: u32,
    /// Force a gradient direction at the next step.
    restart: bool,
    /// Line search acceleration factor (carried across iterations of one solve).
    accel: f64,
    /// Length of the last accepted move (0 before the first).
    last_move: f64,
}

impl<V: Point> SolveState<V> {
    /// A solve of `star` (of size `scale`, its [`star_scale`](crate::objective::star_scale)) from `x0`, already stopped ([`StopReason::DegenerateStar`]) when
    /// the star is empty or has no finite positive size: what every solver's `start`
    /// checks first.
    fn begin<S: NodeStar<Point = V>>(star: &S, x0: V, scale: f64, options: &SolveOptions) -> Self {
        let mut st = SolveState::new(x0, scale, options.acceleration);
        if star.is_empty() || !(st.scale.is_finite() && st.scale > 0.0) {
            st.stop = Some(StopReason::DegenerateStar);
        }
        st
    }
    /// Whether another iteration may run: false once stopped; at `max_iter` iterations the
    /// solve stops with [`StopReason::MaxIter`]. What every solver's `step` checks first.
    fn may_iterate(&mut self, options: &SolveOptions) -> bool {
        if self.stop.is_some() {
            return false;
        }
        if self.iterations >= options.max_iter {
            self.stop = Some(StopReason::MaxIter);
            return false;
        }
        true
    }
    fn new(x0: V, scale: f64, accel: f64) -> Self {
        SolveState {
            x: x0,
            value: f64::NAN,
            iterations: 0,
            stop: None,
            history: Vec::new(),
            x0,
            value0: f64::NAN,
            scale,
            merit: f64::NAN,
            grad: V::ZERO,
            hess: None,
            dir: V::ZERO,
            grad_prev: V::ZERO,
            since_restart: 0,
            restart: true,
            accel,
            last_move: 0.0,
        }
    }
    /// Whether the solve has stopped.
    pub fn is_done(&self) -> bool {
        self.stop.is_some()
    }
    /// The star size used as the unit of length.
    pub fn scale(&self) -> f64 {
        self.scale
    }
    /// The finished result (a running solve reports [`StopReason::MaxIter`]).
    pub fn into_result(self) -> SolveResult<V> {
        SolveResult {
            x: self.x,
            value: self.value,
            x0: self.x0,
            value0: self.value0,
            iterations: self.iterations,
            stop: self.stop.unwrap_or(StopReason::MaxIter),
            history: self.history,
        }
    }
}

/// A solver of one node's objective. Implementations own their scratch buffers, so one
/// solver object serves a whole smoothing pass without allocating per node.
pub trait Solver<S: NodeStar = Star> {
    /// The solver's settings.
    fn options(&self) -> &SolveOptions;
    /// Evaluates the objective at `x0` and prepares a solve (which may already be stopped,
    /// e.g. [`StopReason::NotFinite`]).
    fn start(&mut self, objective: &dyn Objective<S>, star: &S, x0: S::Point) -> SolveState<S::Point> {
        self.start_at_scale(objective, star, x0, star.size())
    }
    /// [`start`](Self::start) for a star whose size ([`NodeStar::size`]) the caller has at
    /// hand ([`solve`](Self::solve) measures it once for both the frame and the solve).
    fn start_at_scale(
        &mut self,
        objective: &dyn Objective<S>,
        star: &S,
        x0: S::Point,
        scale: f64,
    ) -> SolveState<S::Point> {
        let mut st = SolveState::begin(star, x0, scale, self.options());
        if !st.is_done() {
            self.evaluate_start(objective, star, &mut st);
        }
        st
    }
    /// Evaluates the objective at the start `st.x` into `st` (value, merit, and what the
    /// solver keeps), stopping it when that is not finite. Called by
    /// [`start_at_scale`](Self::start_at_scale) unless `SolveState::begin` stopped it.
    fn evaluate_start(&mut self, objective: &dyn Objective<S>, star: &S, st: &mut SolveState<S::Point>);
    /// One iteration. Returns false once the solve has stopped (see [`SolveState::stop`]).
    fn step(&mut self, objective: &dyn Objective<S>, star: &S, state: &mut SolveState<S::Point>) -> bool;
    /// Runs a whole solve from `x0`. A star beyond 2^±64 in size is solved in its own
    /// frame (see the module docs): positions and step lengths come back in mesh units;
    /// objective values are those of the star in its own frame, the same for every
    /// objective that is a ratio of lengths (all but `untangle` and `untangle-mindet`,
    /// whose dets are then in units of the star size squared).
    fn solve(&mut self, objective: &dyn Objective<S>, star: &S, x0: S::Point) -> SolveResult<S::Point> {
        let scale = star.size();
        if let Some(f) = unit_factor(scale) {
            let scaled = star.scaled(f);
            let mut state = self.start(objective, &scaled, x0 * f);
            while self.step(objective, &scaled, &mut state) {}
            let mut r = state.into_result();
            let back = 1.0 / f;
            r.x *= back;
            r.x0 = x0;
            for it in &mut r.history {
                it.x *= back;
                it.step *= back;
            }
            return r;
        }
        let mut state = self.start_at_scale(objective, star, x0, scale);
        while self.step(objective, star, &mut state) {}
        state.into_result()
    }
}

/// Evaluates the terms of `objective` at `x` into `buf` and combines them by `goal`
/// (through [`Objective::terms`] so the scratch buffer is reused; a NaN value reads as the
/// worst value of the goal).
pub(crate) fn evaluate<S: NodeStar>(
    objective: &dyn Objective<S>,
    star: &S,
    x: S::Point,
    buf: &mut Vec<Term<S::Point>>,
) -> (f64, S::Point) {
    buf.clear();
    objective.terms(star, x, buf);
    let goal = objective.goal();
    let (v, g) = crate::objective::combine(goal, buf);
    let v = if buf.iter().any(|t| t.value.is_nan()) { f64::NAN } else { v };
    (v, g)
}

/// The value a minimiser sees: the objective for [`Goal::MinimizeSum`], its negation for
/// [`Goal::MaximizeMin`]; NaN reads as +∞ ("high").
pub(crate) fn merit_of(goal: Goal, value: f64) -> f64 {
    let m = match goal {
        Goal::MinimizeSum => value,
        Goal::MaximizeMin => -value,
    };
    if m.is_nan() {
        f64::INFINITY
    } else {
        m
    }
}
