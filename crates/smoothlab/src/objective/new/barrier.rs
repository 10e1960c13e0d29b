//! Our eq. (8), second design (the default): a regularised barrier on the inverse of Lo's α.
//!
//! The formulas, in one notation: `docs/formulas.md` §3.

use glam::{DMat2, DVec2};

use super::SubTriangle;
use crate::quality::TWO_SQRT3;


/// Default weight `k1` of the barrier: its value on an equilateral triangle (η = 1).
/// Chosen by measurement (`docs/reproduction.md`, §7).
pub const BARRIER_WEIGHT: f64 = 0.15;

/// Default `ε` of the regularisation δ: the worst sub-triangle of a star counts as if its
/// doubled area were `ε` times the star's mean.
pub const BARRIER_EPSILON: f64 = 0.01;

/// The angle penalty of Chen, Tristano & Kwok's objective as we now define it (the
/// paper's eq. (8) was lost in extraction; this is our design, documented as such).
///
/// For each sub-triangle T = (C, A, B) of the star (C the free node; a triangle, or one
/// of a quad's three sub-triangles of eq. (9)), with
/// `N = cross(A − C, B − C)` (twice the signed area) and
/// `D = |A − C|² + |B − C|² + |B − A|²`, so that Lo's α = 2√3·N/D,
///
/// `f_T = (1 − α_T)² + k1 · η_δ,T²`,  `η_δ = D / (2√3 · h_δ(N))`,
/// `h_δ(N) = (N + √(N² + 4δ²)) / 2`,
///
/// the regularised determinant of Escobar, Rodríguez, Montenegro, Montero and
/// González-Yuste, "Simultaneous untangling and smoothing of tetrahedral meshes",
/// Comput. Methods Appl. Mech. Engrg. 192 (2003) 2775–2787, carried to the plane.
/// `η_0 = 1/α` is the inverse of the mean-ratio quality (Knupp's "shape" metric).
/// Quadratic sub-triangles: N and D at each of C, A and B from the edge end tangents at
/// that corner, `η²` averaged over the three (equal for straight sides).
///
/// # Why this shape (each property is a test in `tests.rs`)
/// - *An angle penalty in Chen's sense*: for a straight triangle
///   `η = (cot A + cot B + cot C)/√3`; it is 1 on the equilateral triangle, grows without
///   bound as any angle goes to 0, and on into inversion; its gradient is zero at the
///   equilateral apex and at the centre of a regular k-star, so `k1` only adds a constant
///   per ideal triangle and leaves the ideal position in place.
/// - *A true barrier when δ = 0*: `h_0(N) = max(N, 0)`, so η is +∞ wherever a
///   sub-triangle folds: the solver cannot fold a valid star, and no node is drawn onto a
///   neighbour (the defect of the first design, whose length factor vanished there).
/// - *Finite and smooth on inverted stars when δ > 0*: `h_δ > 0` everywhere, C∞ in N, and
///   `η_δ` grows with the depth of the fold (`h_δ(N) ≈ δ²/|N|` for N ≪ −δ), so the
///   minimum of a tangled star is a shallower fold, then none.
/// - *Scale-free*: N, D and δ² are all areas squared or areas, η is a ratio.
/// - *No transcendental functions*: one square root per corner; cheaper than the first
///   design's `atan2` and two `exp` per angle.
///
/// # δ, once per optimization call
/// From the star at the node's current position ([`crate::objective::Star::x0`], one
/// constant through a solve, as Escobar et al. fix δ per node visit): with ρ the mean |N|
/// over the star's sub-triangle corners, `N_min` the smallest N and `m = ε·ρ`,
///
/// `δ = √(m·(m − N_min))` when `N_min < m`, else 0.
///
/// This δ makes `h_δ(N_min) = m` exactly: the worst corner counts as a valid sliver of
/// doubled area ερ. A star whose every sub-triangle has `N ≥ ερ` gets δ = 0, the pure
/// barrier; a tangled or near-degenerate star gets the smallest δ that keeps its
/// objective finite and well scaled. ε = [`BARRIER_EPSILON`] = 0.01.
///
/// # Constants
/// `k1` = [`BARRIER_WEIGHT`] = 0.15, chosen by measurement (`docs/reproduction.md` §7
/// scans 0.02 to 1 on Freitag's rand2D, Knupp's random grids and the page's tangled plate):
/// the smallest and largest angles improve as k1 grows to about 0.15 and stay nearly flat
/// beyond, because η² is itself a shape measure that weighs the worst elements most, so
/// the mean α does not suffer. Untangling does not hinge on the weight: the barrier's
/// growth does it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RegularisedBarrier {
    /// Weight of `η²`; default [`BARRIER_WEIGHT`]. 0 leaves `Σ (1 − α)²` alone.
    pub k1: f64,
    /// Fraction of the star's mean |N| that sets δ; default [`BARRIER_EPSILON`]. 0 makes
    /// δ = 0 always (the pure barrier: +∞ on every inverted star).
    pub epsilon: f64,
}

impl Default for RegularisedBarrier {
    fn default() -> Self {
        RegularisedBarrier { k1: BARRIER_WEIGHT, epsilon: BARRIER_EPSILON }
    }
}

/// N and D at one corner from its two edge vectors `u1` (towards the next corner) and
/// `u2` (towards the previous one), with their weights `u = c·x + const`, and their
/// gradients with respect to the free node.
#[derive(Clone, Copy, Debug)]
pub(super) struct CornerND {
    pub n: f64,
    pub d: f64,
    pub grad_n: DVec2,
    pub grad_d: DVec2,
    /// The Hessian of D is this multiple of the identity (each edge vector is linear in the
    /// free node with a scalar weight, so D is quadratic in it); N is linear, its Hessian 0.
    pub hess_d: f64,
}

impl CornerND {
    #[inline(always)]
    pub(super) fn of((u1, c1): (DVec2, f64), (u2, c2): (DVec2, f64)) -> Self {
        let n = u1.perp_dot(u2);
        let w = u2 - u1;
        let d = u1.length_squared() + u2.length_squared() + w.length_squared();
        // ∂N/∂u1 = −perp(u2), ∂N/∂u2 = perp(u1); ∂D/∂u1 = 4u1 − 2u2, ∂D/∂u2 = 4u2 − 2u1
        let grad_n = c1 * -u2.perp() + c2 * u1.perp();
        let grad_d = c1 * (4.0 * u1 - 2.0 * u2) + c2 * (4.0 * u2 - 2.0 * u1);
        // D = |u1|² + |u2|² + |u2 − u1|², u = c·x + const: ∇²D = 2(c1² + c2² + (c2 − c1)²) I
        let hess_d = 2.0 * (c1 * c1 + c2 * c2 + (c2 - c1) * (c2 - c1));
        CornerND { n, d, grad_n, grad_d, hess_d }
    }

    /// Lo's α = 2√3·N/D and its gradient (0 when the corner has no extent).
    #[inline(always)]
    pub(super) fn alpha(&self) -> (f64, DVec2) {
        if self.d <= 0.0 {
            return (0.0, DVec2::ZERO);
        }
        let inv_d = 1.0 / self.d;
        let alpha = TWO_SQRT3 * self.n * inv_d;
        (alpha, (TWO_SQRT3 * self.grad_n - alpha * self.grad_d) * inv_d)
    }

    /// The Hessian of α from [`alpha`](Self::alpha)'s value and gradient: differentiating
    /// `D·∇α = 2√3·∇N − α·∇D` (∇N constant) gives
    /// `∇²α = −(∇α ∇Dᵀ + ∇D ∇αᵀ + α ∇²D) / D` (0 when the corner has no extent).
    #[inline(always)]
    pub(super) fn alpha_hessian(&self, alpha: f64, grad_alpha: DVec2) -> DMat2 {
        if self.d <= 0.0 {
            return DMat2::ZERO;
        }
        let sym = outer(grad_alpha, self.grad_d) + outer(self.grad_d, grad_alpha);
        (sym + DMat2::from_diagonal(DVec2::splat(alpha * self.hess_d))) * (-1.0 / self.d)
    }
}

/// The outer product `a bᵀ`.
#[inline(always)]
pub(super) fn outer(a: DVec2, b: DVec2) -> DMat2 {
    DMat2::from_cols(a * b.x, a * b.y)
}

/// `h_δ(N) = (N + √(N² + 4δ²))/2` and `s = √(N² + 4δ²)` (so `dh/dN = h/s`), without
/// cancellation for N < 0 (`h = 2δ²/(s − N)`).
#[inline]
pub fn regularised_determinant(n: f64, delta: f64) -> (f64, f64) {
    let s = (n * n + 4.0 * delta * delta).sqrt();
    let h = if n >= 0.0 { 0.5 * (n + s) } else { 2.0 * delta * delta / (s - n) };
    (h, s)
}

impl RegularisedBarrier {
    /// `η_δ²` of one corner with its gradient, and its Hessian when `HESSIAN` (a zero matrix
    /// otherwise; the value and gradient are the same arithmetic either way); +∞ (gradient
    /// 0) where `h_δ = 0`, which is only where δ = 0 and N ≤ 0. With `ln η = ln D − ln h − ln 2√3`,
    /// `∇ ln η = ∇D/D − ∇N/s` (as `dh/dN = h/s`) and, ∇N being constant and `ds/dN = N/s`,
    /// `∇² ln η = ∇²D/D − ∇D ∇Dᵀ/D² + (N/s³) ∇N ∇Nᵀ`; then
    /// `∇² η² = 2η² (2 ∇ln η ∇ln ηᵀ + ∇² ln η)`.
    #[inline(always)]
    pub(super) fn eta2<const HESSIAN: bool>(c: &CornerND, delta: f64) -> (f64, DVec2, DMat2) {
        if c.d <= 0.0 {
            return (0.0, DVec2::ZERO, DMat2::ZERO); // the three corners coincide: no shape to penalise
        }
        // δ = 0 (every valid star with margin): h = s = N, no square root
        let (h, s) = if delta == 0.0 { (c.n.max(0.0), c.n) } else { regularised_determinant(c.n, delta) };
        if h <= 0.0 || h.is_nan() {
            return (f64::INFINITY, DVec2::ZERO, DMat2::ZERO);
        }
        let (inv_d, inv_s) = (1.0 / c.d, 1.0 / s);
        let eta = c.d / (TWO_SQRT3 * h);
        let eta2 = eta * eta;
        // ∇η = η (∇D/D − ∇N/s)
        let grad_ln = c.grad_d * inv_d - c.grad_n * inv_s;
        let hess = if HESSIAN {
            let hess_ln = DMat2::from_diagonal(DVec2::splat(c.hess_d * inv_d)) - outer(c.grad_d, c.grad_d) * (inv_d * inv_d)
                + outer(c.grad_n, c.grad_n) * (c.n * inv_s * inv_s * inv_s);
            (outer(grad_ln, grad_ln) * 2.0 + hess_ln) * (2.0 * eta2)
        } else {
            DMat2::ZERO
        };
        (eta2, 2.0 * eta2 * grad_ln, hess)
    }

    /// `(1 − α_C)² + k1 η²` of the sub-triangle with its gradient, `delta` from
    /// [`RegularisedBarrier::delta_from`]; with the Hessian when `HESSIAN` (zero otherwise): `∇²(1 − α)² =
    /// 2 ∇α ∇αᵀ − 2(1 − α) ∇²α`, plus `k1` times the Hessians of [`eta2`](Self::eta2).
    #[inline(always)]
    pub(super) fn of<const HESSIAN: bool>(&self, t: &SubTriangle, delta: f64) -> (f64, DVec2, DMat2) {
        let at_c = CornerND::of(t.c_to_a, t.c_to_b);
        let (alpha, grad_alpha) = at_c.alpha();
        let value = (1.0 - alpha) * (1.0 - alpha);
        let grad = -2.0 * (1.0 - alpha) * grad_alpha;
        let hess = if HESSIAN {
            outer(grad_alpha, grad_alpha) * 2.0 - at_c.alpha_hessian(alpha, grad_alpha) * (2.0 * (1.0 - alpha))
        } else {
            DMat2::ZERO
        };
        if self.k1 == 0.0 {
            return (value, grad, hess);
        }
        let (p, gp, hp) = if t.straight {
            Self::eta2::<HESSIAN>(&at_c, delta)
        } else {
            let (pc, gc, hc) = Self::eta2::<HESSIAN>(&at_c, delta);
            let (pa, ga, ha) = Self::eta2::<HESSIAN>(&CornerND::of(t.a_to_b, t.a_to_c), delta);
            let (pb, gb, hb) = Self::eta2::<HESSIAN>(&CornerND::of(t.b_to_c, t.b_to_a), delta);
            ((pc + pa + pb) / 3.0, (gc + ga + gb) / 3.0, (hc + ha + hb) * (1.0 / 3.0))
        };
        (value + self.k1 * p, grad + self.k1 * gp, hess + hp * self.k1)
    }

    /// δ of a star whose sub-triangle corners at the node's current position have N
    /// values summing to `sum_abs` in absolute value, `count` of them, the smallest
    /// `min_n` (see the type docs). 0 for an empty star or one with no area.
    pub fn delta_from(&self, sum_abs: f64, count: usize, min_n: f64) -> f64 {
        if count == 0 || self.epsilon == 0.0 {
            return 0.0;
        }
        let m = self.epsilon * sum_abs / count as f64;
        if m > 0.0 && m.is_finite() && min_n < m {
            (m * (m - min_n)).sqrt()
        } else {
            0.0
        }
    }
}
