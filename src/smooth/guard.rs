//! The validity guard: an objective seen through the rule that a solver never folds a
//! valid star.

use glam::DVec2;

use crate::objective::{Objective, Star, Term};

use super::*;

/// An objective seen through [`SmoothOptions::keep_valid`]: the same terms, plus a NaN
/// term at a trial position that raises the star's number of inverted elements — unless
/// [`SmoothOptions::pass_through_folds`] is set, the star was inverted to begin with and
/// the position lowers its [`inversion`]. Both solvers read NaN as the worst value of the goal (+∞ for a sum, −∞ for a
/// minimum), so they never step there; at valid positions values and gradients are the
/// objective's own.
pub(super) struct KeepValid<'a> {
    pub(super) inner: &'a dyn Objective,
    /// Inverted star elements when the call began.
    pub(super) limit: usize,
    /// [`SmoothOptions::pass_through_folds`], resolved for the objective.
    pub(super) pass_through_folds: bool,
    /// The star's [`inversion`] at its start, taken once, from the star the solver passes
    /// (a solve passes one star throughout: the gathered one or one rescaled copy).
    pub(super) inversion0: std::cell::OnceCell<f64>,
}

/// How deeply the star is inverted with its free node at `x`: `Σ max(0, −det)` over every
/// corner of every star element (Knupp's `Σ (|det| − det) / 2`, 0 for a valid star). An
/// area, compared only within one star.
pub(super) fn inversion(star: &Star, x: DVec2) -> f64 {
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
    fn value_gradient_hessian(&self, star: &Star, x: DVec2) -> Option<(f64, DVec2, glam::DMat2)> {
        if self.refuses(star, x) {
            return Some((f64::NAN, DVec2::ZERO, glam::DMat2::ZERO));
        }
        self.inner.value_gradient_hessian(star, x)
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
