//! Fletcher–Reeves conjugate gradients as Chen, Tristano & Kwok (2003, §3) use it for
//! their smooth objective.
//!
//! The formulas, in one notation: `docs/formulas.md` §3.

use super::{line_search, merit_of, DirectionKind, Iterate, SolveOptions, SolveState, Solver, StopReason};
use crate::objective::{Goal, NodeStar, Objective, Point};

/// Powell's restart test: restart when consecutive gradients are far from orthogonal,
/// `|g_q·g_{q−1}| ≥ 0.2·|g_q|²` — the conjugate directions have stopped helping.
const POWELL_RESTART: f64 = 0.2;
/// A gradient this small relative to the merit (per unit of star size) is zero.
const GRADIENT_TOLERANCE: f64 = 1e-13;
/// Armijo's constant for a Newton step: accepted when it lowers the merit by at least this
/// fraction of the decrease the gradient promises, `f(x + p) ≤ f(x) + c·∇f·p`.
const NEWTON_ARMIJO: f64 = 1e-4;
/// A Newton step whose fall exceeds the quadratic model's promise by this factor is
/// extended by a line search along it.
const NEWTON_EXTEND: f64 = 1.1;

/// Fletcher–Reeves conjugate gradients (Chen et al. 2003, eqs. 10–12):
/// `x_q = x_{q−1} + s·d_q`, `d_q = −∇f(x_q) + r_q·d_{q−1}`, `r_q = |∇f(x_q)|²/|∇f(x_{q−1})|²`.
///
/// - The first iteration uses the gradient direction, the next ones the conjugate one.
/// - Restart rule ("after a number of iterations the convergence speed using the conjugate
///   gradient direction actually slows down … a new gradient direction is used", §3.1):
///   every [`SolveOptions::restart_every`]-th iteration is a gradient step (2, the
///   dimension: g, c, g, c, …), and a gradient step is also taken when consecutive gradients fail Powell's orthogonality
///   test `|g_q·g_{q−1}| ≥ 0.2|g_q|²`, when the conjugate direction is not a descent
///   direction, and after a line search along a conjugate direction fails.
/// - The step `s` comes from [`line_search`] (high-low-high bracket grown by an
///   acceleration factor of 8, halved on failure; quadratic interpolation). The first
///   trial step is [`SolveOptions::initial_step`] of the star size, later ones the previous
///   move. A value of +∞ (a barrier) or NaN is "high", so the search never steps into it.
/// - Every accepted step lowers the objective, so the result is never worse than the start.
///
/// For a [`Goal::MaximizeMin`] objective it minimises the negated minimum with the
/// gradient of one minimal term, for comparison only: that objective is not smooth.
#[derive(Clone, Debug, Default)]
pub struct FletcherReeves {
    pub options: SolveOptions,
}

impl FletcherReeves {
    pub fn new(options: SolveOptions) -> Self {
        FletcherReeves { options }
    }

    fn eval<S: NodeStar>(&mut self, objective: &dyn Objective<S>, star: &S, x: S::Point) -> (f64, f64, S::Point) {
        let goal = objective.goal();
        // the folded value and gradient (no terms collected; a NaN term gives NaN)
        let (v, g) = objective.value_and_gradient(star, x);
        let g = if goal == Goal::MaximizeMin { -g } else { g };
        (v, merit_of(goal, v), g)
    }

    /// [`eval`](Self::eval) with the Hessian, when Newton steps are on and the objective
    /// (smooth: [`Goal::MinimizeSum`]) has one.
    #[allow(clippy::type_complexity)]
    fn eval_hessian<S: NodeStar>(
        &mut self,
        objective: &dyn Objective<S>,
        star: &S,
        x: S::Point,
    ) -> (f64, f64, S::Point, Option<<S::Point as Point>::Hessian>) {
        if self.options.newton && objective.goal() == Goal::MinimizeSum {
            if let Some((v, g, h)) = objective.value_gradient_hessian(star, x) {
                return (v, merit_of(Goal::MinimizeSum, v), g, Some(h));
            }
        }
        let (v, m, g) = self.eval(objective, star, x);
        (v, m, g, None)
    }
}

impl<S: NodeStar> Solver<S> for FletcherReeves {
    fn options(&self) -> &SolveOptions {
        &self.options
    }

    fn evaluate_start(&mut self, objective: &dyn Objective<S>, star: &S, st: &mut SolveState<S::Point>) {
        let (v, m, g, h) = self.eval_hessian(objective, star, st.x);
        st.value = v;
        st.value0 = v;
        st.merit = m;
        st.grad = g;
        st.hess = h;
        if !(m.is_finite() && g.is_finite()) {
            st.stop = Some(StopReason::NotFinite);
        }
    }

    fn step(&mut self, objective: &dyn Objective<S>, star: &S, st: &mut SolveState<S::Point>) -> bool {
        if !st.may_iterate(&self.options) {
            return false;
        }
        let o = self.options;
        let g = st.grad;
        let g2 = g.length_squared();
        if g2 == 0.0 || g.length() * st.scale <= GRADIENT_TOLERANCE * st.merit.abs().max(f64::MIN_POSITIVE) {
            st.stop = Some(StopReason::Optimal);
            return false;
        }
        // Newton's step first, when there is a Hessian and it is positive definite
        if let Some(p) = st.hess.and_then(|h| S::Point::newton_step(g, h, st.scale)) {
            let x = st.x;
            let first = self.eval_hessian(objective, star, x + p);
            let (_, m1, _, _) = first;
            if m1.is_finite() && m1 <= st.merit + NEWTON_ARMIJO * g.dot(p) {
                // the quadratic model promises −½ g·p; a fall well beyond that (a barrier
                // seen from afar: Newton's step is then a fraction of the way) asks for a
                // longer step along p, by Chen's search from t = 1 with acceleration 2
                let mut best = (1.0, first);
                if (st.merit - m1) > NEWTON_EXTEND * (-0.5 * g.dot(p)) {
                    let mut accel = 2.0;
                    let mut phi = |t: f64| {
                        if t == 1.0 {
                            return m1;
                        }
                        let e = self.eval_hessian(objective, star, x + p * t);
                        if e.1 < best.1 .1 {
                            best = (t, e);
                        }
                        e.1
                    };
                    let _ = line_search(&mut phi, st.merit, 1.0, 1.0, &mut accel, o.max_evaluations);
                }
                let (t, (v_new, m_new, g_new, h_new)) = best;
                // a conjugate direction after a Newton step means nothing: restart
                st.restart = true;
                st.since_restart = 0;
                return self.accept(st, x + p * t, p, (v_new, m_new, g_new, h_new), DirectionKind::Newton);
            }
        }
        // direction
        let mut kind = DirectionKind::Gradient;
        let mut d = -g;
        let prev2 = st.grad_prev.length_squared();
        let restart = st.restart
            || st.since_restart + 1 >= o.restart_every
            || prev2 == 0.0
            || g.dot(st.grad_prev).abs() >= POWELL_RESTART * g2;
        if !restart {
            let conj = -g + st.dir * (g2 / prev2);
            if conj.dot(g) < 0.0 && conj.is_finite() {
                d = conj;
                kind = DirectionKind::Conjugate;
            }
        }
        // line search along d, keeping the gradient of the lowest point seen
        let dl = d.length();
        let first = if st.last_move > 0.0 { st.last_move } else { o.initial_step * st.scale };
        let t0 = first / dl;
        let t_min = o.min_step * st.scale / dl;
        let x = st.x;
        let mut best = (f64::INFINITY, f64::NAN, S::Point::ZERO, None); // (merit, value, grad, Hessian)
        let mut best_t = 0.0;
        let found = {
            let mut phi = |t: f64| {
                let (v, m, gr, h) = self.eval_hessian(objective, star, x + d * t);
                if m < best.0 {
                    best = (m, v, gr, h);
                    best_t = t;
                }
                m
            };
            line_search(&mut phi, st.merit, t0, t_min, &mut st.accel, o.max_evaluations)
        };
        let Some(ls) = found else {
            if kind == DirectionKind::Conjugate {
                // try again along the gradient before giving up
                st.restart = true;
                return true;
            }
            st.stop = Some(StopReason::LineSearchFailed);
            return false;
        };
        debug_assert_eq!(ls.t, best_t);
        let (m_new, v_new, g_new, h_new) = best;
        st.restart = false;
        st.since_restart = if kind == DirectionKind::Conjugate { st.since_restart + 1 } else { 0 };
        self.accept(st, x + d * best_t, d, (v_new, m_new, g_new, h_new), kind)
    }
}

impl FletcherReeves {
    /// Moves the solve to the accepted point `x_new`, reached along `dir`, where the
    /// objective is `(value, merit, gradient, Hessian)`; records the iterate and says
    /// whether the solve goes on ([`check_stop`](Self::check_stop)).
    fn accept<V: Point>(
        &self,
        st: &mut SolveState<V>,
        x_new: V,
        dir: V,
        (v_new, m_new, g_new, h_new): (f64, f64, V, Option<V::Hessian>),
        kind: DirectionKind,
    ) -> bool {
        let moved = x_new.distance(st.x);
        let improvement = st.merit - m_new;
        st.grad_prev = st.grad;
        st.dir = dir;
        st.grad = g_new;
        st.hess = h_new;
        st.x = x_new;
        st.value = v_new;
        st.merit = m_new;
        st.last_move = moved;
        st.iterations += 1;
        if self.options.record_history {
            st.history.push(Iterate { x: x_new, value: v_new, direction: kind, step: moved });
        }
        self.check_stop(st, improvement, m_new, g_new, moved)
    }

    /// After an accepted step: stops on a gradient that is not finite, too small an
    /// improvement or too short a move; returns whether the solve goes on.
    fn check_stop<V: Point>(&self, st: &mut SolveState<V>, improvement: f64, m_new: f64, g_new: V, moved: f64) -> bool {
        let o = &self.options;
        if !g_new.is_finite() {
            st.stop = Some(StopReason::NotFinite);
        } else if improvement <= o.min_improvement * m_new.abs().max(f64::MIN_POSITIVE) {
            st.stop = Some(StopReason::SmallImprovement);
        } else if moved <= o.min_step * st.scale {
            st.stop = Some(StopReason::SmallStep);
        }
        st.stop.is_none()
    }
}
