//! Freitag's optimization-based smoothing for max-min objectives (Freitag 1997, Figure 1
//! and §"Optimization-based Smoothing"): steepest ascent of `φ(x) = min_i q_i(x)` along
//! the minimum-norm point of the convex hull of the active gradients.
//!
//! The formulas, in one notation: `docs/formulas.md` §2.

use glam::DVec2;
use serde::Serialize;

use super::{DirectionKind, Iterate, SolveOptions, SolveState, Solver, StopReason};
use crate::objective::{Goal, NodeStar, Objective, Point, Term};

/// Where the minimum-norm point of a convex hull lies.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum HullPoint {
    /// No points were given.
    Empty,
    /// At point `i` itself.
    Vertex(usize),
    /// Inside the segment between points `i` and `j`.
    Edge(usize, usize),
    /// Inside the triangle of points `i`, `j` and `k` (in 3D only).
    Face(usize, usize, usize),
    /// The origin is in the hull (inside a triangle of three of the points in 2D, a
    /// tetrahedron of four in 3D, or on a segment or face): the minimum-norm point is the
    /// origin.
    Interior,
}

/// The minimum-norm point of the convex hull of some points, and where it lies.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct MinNorm<V = DVec2> {
    pub point: V,
    pub support: HullPoint,
}

/// The minimum-norm point of the convex hull of `points` — the small quadratic program of
/// Freitag's search direction, solved exactly in 2D and in 3D.
///
/// When the origin is outside the hull the answer lies on the hull's boundary, i.e. at a
/// point, on a segment between two points or (in 3D) inside a triangle of three: every
/// point and the projection of the origin onto every segment (and, in 3D, onto the plane
/// of every triangle, when it falls inside it) are tried, and the shortest is kept. It is
/// the true minimum iff it passes the optimality test `p·g_k ≥ |p|²` for every point `g_k`
/// (the hull lies beyond the plane through `p` normal to `p`); if that fails, the origin
/// is inside the hull (inside a triangle of three points in 2D, a tetrahedron of four in
/// 3D — Carathéodory: no more are needed) and the answer is the origin. O(n²) in the
/// number of points in 2D, O(n³) in 3D, exact for any number of them.
pub fn min_norm_point<V: Point>(points: &[V]) -> MinNorm<V> {
    if points.is_empty() {
        return MinNorm { point: V::ZERO, support: HullPoint::Empty };
    }
    let mut best = MinNorm { point: points[0], support: HullPoint::Vertex(0) };
    let mut best2 = points[0].length_squared();
    let mut scale2 = 0.0f64;
    for (i, g) in points.iter().enumerate() {
        let l2 = g.length_squared();
        scale2 = scale2.max(l2);
        if l2 < best2 {
            best2 = l2;
            best = MinNorm { point: *g, support: HullPoint::Vertex(i) };
        }
    }
    for i in 0..points.len() {
        for j in i + 1..points.len() {
            let (a, d) = (points[i], points[j] - points[i]);
            let dd = d.length_squared();
            if dd <= 0.0 {
                continue;
            }
            let lambda = -a.dot(d) / dd;
            if lambda > 0.0 && lambda < 1.0 {
                let p = a + d * lambda;
                let l2 = p.length_squared();
                if l2 < best2 {
                    best2 = l2;
                    best = MinNorm { point: p, support: HullPoint::Edge(i, j) };
                }
            }
        }
    }
    if V::DIM == 3 {
        for i in 0..points.len() {
            for j in i + 1..points.len() {
                for k in j + 1..points.len() {
                    if let Some(p) = origin_onto_triangle(points[i], points[j], points[k]) {
                        let l2 = p.length_squared();
                        if l2 < best2 {
                            best2 = l2;
                            best = MinNorm { point: p, support: HullPoint::Face(i, j, k) };
                        }
                    }
                }
            }
        }
    }
    // optimality: every point on the far side of the supporting line (plane) through p
    let tol = 1e-12 * scale2;
    if best2 <= tol || points.iter().any(|g| best.point.dot(*g) < best2 - tol) {
        return MinNorm { point: V::ZERO, support: HullPoint::Interior };
    }
    best
}

/// The projection of the origin onto the plane of the triangle `a b c`, when it falls
/// strictly inside the triangle: `a + λ(b − a) + μ(c − a)` with the normal equations
/// `[u·u u·v; u·v v·v][λ μ]ᵀ = −[a·u a·v]ᵀ` solved by Cramer's rule; `None` for a
/// degenerate triangle or a projection outside it.
fn origin_onto_triangle<V: Point>(a: V, b: V, c: V) -> Option<V> {
    let (u, v) = (b - a, c - a);
    let (uu, uv, vv) = (u.dot(u), u.dot(v), v.dot(v));
    let det = uu * vv - uv * uv;
    if det.is_nan() || det <= 1e-14 * uu * vv {
        return None;
    }
    let (au, av) = (a.dot(u), a.dot(v));
    let lambda = (-au * vv + av * uv) / det;
    let mu = (-av * uu + au * uv) / det;
    (lambda > 0.0 && mu > 0.0 && lambda + mu < 1.0).then(|| a + u * lambda + v * mu)
}

/// Freitag's active-set steepest ascent for `φ(x) = min_i q_i(x)` (Freitag 1997, Figure 1):
///
/// - active set: the terms within [`SolveOptions::active_tolerance`] (relative to the
///   largest |q_i|) of the minimum φ;
/// - direction `s`: the minimum-norm point of the hull of the active gradients
///   ([`min_norm_point`]); `s = 0` means x is optimal;
/// - initial step: the smallest positive `α_j = (q_j − φ)/((g_A − g_j)·s)` over the
///   non-active terms with `(g_A − g_j)·s > 0`, where `g_A·s = |s|²` is the rate of the
///   active value along s (the first-order prediction of where the active set changes);
///   at most [`SolveOptions::max_move`] of the star size;
/// - accept when φ improves, else halve α until the move is below
///   [`SolveOptions::min_step`] of the star size;
/// - stop on `max_iter`, a tiny step, a tiny improvement (MIN_IMP) or a zero direction.
///
/// Only improving steps are taken, so the result is never worse than the start. A NaN
/// term reads as −∞. For a [`Goal::MinimizeSum`] objective the negated sum is the one
/// term (plain steepest descent with halving).
#[derive(Clone, Debug, Default)]
pub struct NonSmoothAscent<V = DVec2> {
    pub options: SolveOptions,
    /// Terms at the current point and at the trial point (swapped on acceptance).
    terms: Vec<Term<V>>,
    trial: Vec<Term<V>>,
    /// Active gradients.
    active: Vec<V>,
}

impl<V: Point> NonSmoothAscent<V> {
    pub fn new(options: SolveOptions) -> Self {
        NonSmoothAscent { options, ..Default::default() }
    }
}

/// Fills `buf` with the terms to maximise the minimum of at `x`, returning φ.
fn max_min_terms<S: NodeStar>(
    objective: &dyn Objective<S>,
    star: &S,
    x: S::Point,
    buf: &mut Vec<Term<S::Point>>,
) -> f64 {
    buf.clear();
    objective.terms(star, x, buf);
    if objective.goal() == Goal::MinimizeSum {
        let (v, g) = crate::objective::combine(Goal::MinimizeSum, buf);
        buf.clear();
        buf.push(Term { elem: 0, value: -v, grad: -g });
    }
    if buf.is_empty() {
        return f64::NAN;
    }
    buf.iter().fold(f64::INFINITY, |m, t| if t.value.is_nan() { f64::NEG_INFINITY } else { m.min(t.value) })
}

/// The objective's own value from φ.
fn own_value(goal: Goal, phi: f64) -> f64 {
    match goal {
        Goal::MaximizeMin => phi,
        Goal::MinimizeSum => -phi,
    }
}

impl<S: NodeStar> Solver<S> for NonSmoothAscent<S::Point> {
    fn options(&self) -> &SolveOptions {
        &self.options
    }

    fn evaluate_start(&mut self, objective: &dyn Objective<S>, star: &S, st: &mut SolveState<S::Point>) {
        let phi = max_min_terms(objective, star, st.x, &mut self.terms);
        st.value = own_value(objective.goal(), phi);
        st.value0 = st.value;
        st.merit = -phi;
        if !phi.is_finite() {
            st.stop = Some(StopReason::NotFinite);
        }
    }

    fn step(&mut self, objective: &dyn Objective<S>, star: &S, st: &mut SolveState<S::Point>) -> bool {
        if !st.may_iterate(&self.options) {
            return false;
        }
        let o = self.options;
        let phi = -st.merit;
        // active set and direction
        let q_scale = crate::numeric::largest_component(self.terms.iter().map(|t| t.value).filter(|v| v.is_finite()));
        let tol = o.active_tolerance * q_scale;
        self.active.clear();
        let mut g_scale = 0.0f64;
        for t in &self.terms {
            if t.value <= phi + tol {
                if !t.grad.is_finite() {
                    st.stop = Some(StopReason::NotFinite);
                    return false;
                }
                g_scale = g_scale.max(t.grad.length());
                self.active.push(t.grad);
            }
        }
        let s = min_norm_point(&self.active).point;
        let sl = s.length();
        if sl <= 1e-12 * g_scale || sl == 0.0 {
            st.stop = Some(StopReason::Optimal);
            return false;
        }
        // predicted step: where a non-active term falls to the active value
        let s2 = sl * sl;
        let mut alpha = o.max_move * st.scale / sl;
        for t in &self.terms {
            if t.value > phi + tol && t.value.is_finite() && t.grad.is_finite() {
                let rate = s2 - t.grad.dot(s);
                if rate > 0.0 {
                    let a = (t.value - phi) / rate;
                    if a > 0.0 && a < alpha {
                        alpha = a;
                    }
                }
            }
        }
        // halve until φ improves; a max-min objective tells whether a trial point is better
        // without its every term (`terms_above`), trying first the element of the worst
        // term here
        let min_move = o.min_step * st.scale;
        let x = st.x;
        let max_min = objective.goal() == Goal::MaximizeMin;
        let lead = self.terms.iter().fold(None, |w: Option<&Term<S::Point>>, t| match w {
            Some(w) if w.value <= t.value => Some(w),
            _ => Some(t),
        });
        let mut lead = lead.map_or(0, |t| t.elem);
        let phi_new = loop {
            if alpha * sl < min_move {
                st.stop = Some(StopReason::SmallStep);
                return false;
            }
            let xt = x + s * alpha;
            if max_min {
                if objective.terms_above(star, xt, phi, lead, &mut self.trial) {
                    break self.trial.iter().fold(f64::INFINITY, |m, t| m.min(t.value));
                }
                // the element that was not above is tried first at the next trial
                if let Some(t) = self.trial.last().filter(|t| t.value <= phi) {
                    lead = t.elem;
                }
            } else {
                let p = max_min_terms(objective, star, xt, &mut self.trial);
                if p > phi {
                    break p;
                }
            }
            alpha *= 0.5;
        };
        std::mem::swap(&mut self.terms, &mut self.trial);
        let x_new = x + s * alpha;
        st.x = x_new;
        st.merit = -phi_new;
        st.value = own_value(objective.goal(), phi_new);
        st.iterations += 1;
        st.last_move = alpha * sl;
        if o.record_history {
            st.history.push(Iterate {
                x: x_new,
                value: st.value,
                direction: DirectionKind::ActiveSet,
                step: alpha * sl,
            });
        }
        if phi_new - phi <= o.min_improvement * phi_new.abs().max(q_scale).max(f64::MIN_POSITIVE) {
            st.stop = Some(StopReason::SmallImprovement);
        }
        st.stop.is_none()
    }
}
