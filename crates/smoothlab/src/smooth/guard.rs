//! The validity guard: an objective seen through the rule that a solver never folds a
//! valid star.

use crate::objective::{Objective, Point, Term};

use super::*;

/// An objective seen through a wrapper says what it is as the wrapped one (`self.inner`):
/// its name, its goal, whether it untangles.
macro_rules! forward_what_it_is {
    () => {
        fn name(&self) -> &'static str {
            self.inner.name()
        }
        fn goal(&self) -> crate::objective::Goal {
            self.inner.goal()
        }
        fn untangles(&self) -> bool {
            self.inner.untangles()
        }
        fn only_untangles(&self) -> bool {
            self.inner.only_untangles()
        }
    };
}

/// An objective seen through [`SmoothOptions::keep_valid`]: the same terms, plus a NaN
/// term at a trial position that raises the star's number of inverted elements — unless
/// [`SmoothOptions::pass_through_folds`] is set, the star was inverted to begin with and
/// the position lowers its [`inversion`]. Both solvers read NaN as the worst value of the goal (+∞ for a sum, −∞ for a
/// minimum), so they never step there; at valid positions values and gradients are the
/// objective's own.
pub(super) struct KeepValid<'a, S: DriverStar> {
    pub(super) inner: &'a dyn Objective<S>,
    /// Inverted star elements when the call began.
    pub(super) limit: usize,
    /// [`SmoothOptions::pass_through_folds`], resolved for the objective.
    pub(super) pass_through_folds: bool,
    /// The star's [`DriverStar::inversion`] at its start, taken once, from the star the solver passes
    /// (a solve passes one star throughout: the gathered one or one rescaled copy).
    pub(super) inversion0: std::cell::OnceCell<f64>,
    /// The last position [`refuses`](Self::refuses) answered, with its answer: Fletcher–Reeves
    /// asks for a Hessian at each trial point and, from an objective without one, then for the
    /// value and gradient at the same point, and each asks the guard.
    refused: std::cell::Cell<Option<(S::Point, bool)>>,
}

impl<S: DriverStar> Objective<S> for KeepValid<'_, S> {
    forward_what_it_is!();
    fn terms(&self, star: &S, x: S::Point, out: &mut Vec<Term<S::Point>>) {
        self.inner.terms(star, x, out);
        if self.refuses(star, x) {
            out.push(Term { elem: 0, value: f64::NAN, grad: S::Point::ZERO });
        }
    }
    fn terms_above(&self, star: &S, x: S::Point, floor: f64, lead: u32, out: &mut Vec<Term<S::Point>>) -> bool {
        // a refused position has a NaN term, which is not above any floor; the objective's
        // own test first, as most trial points fail it
        self.inner.terms_above(star, x, floor, lead, out) && !self.refuses(star, x)
    }
    fn value_and_gradient(&self, star: &S, x: S::Point) -> (f64, S::Point) {
        // a refused position is NaN whatever the objective says there: skip evaluating it
        // (the solvers never use the gradient of a NaN point)
        if self.refuses(star, x) {
            return (f64::NAN, S::Point::ZERO);
        }
        self.inner.value_and_gradient(star, x)
    }
    fn value_gradient_hessian(&self, star: &S, x: S::Point) -> Option<(f64, S::Point, <S::Point as Point>::Hessian)> {
        if self.refuses(star, x) {
            return Some((f64::NAN, S::Point::ZERO, <S::Point as Point>::ZERO_HESSIAN));
        }
        self.inner.value_gradient_hessian(star, x)
    }
}

impl<'a, S: DriverStar> KeepValid<'a, S> {
    /// `inner` guarded for a solve from a star with `limit` inverted elements.
    pub(super) fn new(inner: &'a dyn Objective<S>, limit: usize, pass_through_folds: bool) -> Self {
        KeepValid { inner, limit, pass_through_folds, inversion0: std::cell::OnceCell::new(), refused: std::cell::Cell::new(None) }
    }

    /// Whether a trial position is refused: a valid star must stay valid; an inverted one
    /// may fold another element on the way out, provided its total inversion falls (see
    /// [`SmoothOptions::keep_valid`]).
    fn refuses(&self, star: &S, x: S::Point) -> bool {
        if let Some((at, refused)) = self.refused.get() {
            if at == x {
                return refused;
            }
        }
        let refused = self.refuses_now(star, x);
        self.refused.set(Some((x, refused)));
        refused
    }
    fn refuses_now(&self, star: &S, x: S::Point) -> bool {
        let inverted = star.inverted_at(x);
        // the inversion at the start is taken from the star the solver passes, so that it
        // is in the same frame as at `x` (a solver may pass a rescaled copy: optimize)
        inverted > self.limit
            && (!self.pass_through_folds
                || self.limit == 0
                || star.inversion(x) >= *self.inversion0.get_or_init(|| star.inversion(star.x0())))
    }
}

/// An objective seen by a node that slides on the boundary ([`DriverStar::slides`]): the
/// same values, every gradient and Hessian projected onto the node's tangent
/// ([`DriverStar::along`]). A solver's steps are made of gradients, so it moves the node
/// in the tangent plane or line only; the drivers then put it on the boundary.
pub(super) struct Along<'a, S: DriverStar> {
    pub(super) inner: &'a dyn Objective<S>,
}

impl<S: DriverStar> Objective<S> for Along<'_, S> {
    forward_what_it_is!();
    fn terms(&self, star: &S, x: S::Point, out: &mut Vec<Term<S::Point>>) {
        let from = out.len();
        self.inner.terms(star, x, out);
        for t in &mut out[from..] {
            t.grad = star.along(t.grad);
        }
    }
    fn terms_above(&self, star: &S, x: S::Point, floor: f64, lead: u32, out: &mut Vec<Term<S::Point>>) -> bool {
        let above = self.inner.terms_above(star, x, floor, lead, out);
        for t in out.iter_mut() {
            t.grad = star.along(t.grad);
        }
        above
    }
    fn value_and_gradient(&self, star: &S, x: S::Point) -> (f64, S::Point) {
        let (v, g) = self.inner.value_and_gradient(star, x);
        (v, star.along(g))
    }
    fn value_gradient_hessian(&self, star: &S, x: S::Point) -> Option<(f64, S::Point, <S::Point as Point>::Hessian)> {
        self.inner
            .value_gradient_hessian(star, x)
            .map(|(v, g, h)| (v, star.along(g), star.along_hessian(h)))
    }
}
