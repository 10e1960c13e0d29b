//! The first design of the lost eq. (8): an angle penalty on the adjusted angle of
//! Chen et al.'s eqs. (6)–(7). Kept selectable ([`super::Penalty::Angle`]) so the page and
//! the reproduction can show why the penalty's shape matters; the default is now the
//! regularised barrier of `barrier.rs`.
//!
//! The formulas, in one notation: `docs/formulas.md` §3.

use std::f64::consts::PI;

use glam::DVec2;

use super::SubTriangle;
use crate::numeric::elementary::exp;
use crate::quality::signed_angle_gradient;

/// √3.
const SQRT3: f64 = 1.732_050_807_568_877_2;

/// Chen et al.'s adjusted angle (eqs. 6–7), made continuous across the ±π ray:
/// `ω(θ) = θ·w(θ)`, `w(θ) = (1 − e^{−2(π−θ)})·(1 − e^{−2(π+θ)})`. Returns `(ω, dω/dθ)`.
///
/// The first factor is eq. (6) as printed; it vanishes at θ = +π only, so with it alone
/// ω jumps from 0 to −π across the ray. The second factor is its mirror image: ω is then
/// odd, vanishes on both sides of the ray (ω(±π) = 0) and its derivative is even, so the
/// penalty built on it is continuous with a continuous gradient across the ray, and C∞
/// everywhere else. For θ ≥ 0 the mirror factor differs from 1 by less than
/// e^{−2π} ≈ 0.19%. ω rises from 0 to its maximum ≈ 1.87 at θ ≈ 131° and returns to 0
/// at 180°; it is negative, down to ≈ −1.87 at −131°, for inverted angles.
#[inline]
pub fn adjusted_angle(theta: f64) -> (f64, f64) {
    // ω is odd and ω' even: evaluate at |θ| so the symmetry is exact in floating point,
    // with e^{−2(π+a)} = e^{−4π} / e^{−2(π−a)} (one exponential for both factors; for
    // a ≤ π the quotient is at most 1)
    let a = theta.abs();
    let ep = exp(-2.0 * (PI - a));
    let em = EXP_MINUS_4PI / ep;
    let w = (1.0 - ep) * (1.0 - em);
    let dw = -2.0 * ep * (1.0 - em) + 2.0 * em * (1.0 - ep);
    let omega = a * w;
    (if theta < 0.0 { -omega } else { omega }, w + a * dw)
}

/// e^{−4π}.
const EXP_MINUS_4PI: f64 = 3.487_342_356_208_997_3e-6;

/// Which length scales an angle's penalty: `(ℓ/c)²` with `c = |AB|`, the edge opposite the
/// free node C, and ℓ one of the edges at C.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PenaltyLength {
    /// ℓ = |CA| for the angle at A: the edge joining the free node to the angle's node.
    /// The penalty then vanishes (to second order) as C approaches A, where the angle at A
    /// is undefined, so the objective is continuous with a continuous gradient at A and B.
    #[default]
    Adjacent,
    /// ℓ = |CB| for the angle at A: the edge opposite A, the literal reading of the
    /// extracted text ("a is the edge length opposite the node where θ is computed").
    /// The penalty then keeps a direction-dependent limit at A — a jump — and the sampled
    /// objective has spurious local minima just outside reflex nodes of a star (see the
    /// tests); kept for comparison.
    Opposite,
}

/// The angle penalty of our first eq. (8), for the free node C and each triangle
/// (C, A, B) of its star (counter-clockwise):
///
/// `f_θ(A) = k1 · (|CA|/|AB|)² · exp(−k2 · ω(θ_A))`, and the same at B,
///
/// where θ_A is the signed interior angle at A and ω the adjusted angle of
/// [`adjusted_angle`] (eqs. 6–7). Quadratic elements: the angle at A uses the edge end
/// tangents at A; lengths are chords.
///
/// # Why it was replaced
/// The length factor `(|CA|/|AB|)²` vanishes as C reaches A, so on tangled meshes folded
/// nodes are pulled onto their neighbours (measured: a quarter of the free nodes of the
/// elements left inverted sat on a neighbour), and the minimum of a tangled star is often
/// a *deeper* fold. [`super::barrier::RegularisedBarrier`] has neither defect.
///
/// # The design and its properties (each a test in `tests.rs`)
/// - *Scale-free*: a ratio of lengths times a function of an angle.
/// - *Grows rapidly as an angle at A or B → 0 and into the inverted region*:
///   `exp(−k2 ω)` grows as ω decreases — as θ falls from 131° (where ω peaks at ≈ 1.87)
///   to 0 and on into negative angles, down to ω ≈ −1.87 at θ ≈ −131°. It also grows as
///   θ → 180° (ω → 0), a degenerate triangle too. Relative to its equilateral value the
///   factor is ≈ 42 at θ = 0, ≈ 1.8·10³ at −60° and ≈ 3.8·10⁴ at worst.
/// - *Little to no effect on an equilateral triangle; k1, k2 normalise it*:
///   `k2 = 2√3 / ω'(60°) ≈ 3.634` is the one rate for which the penalty of a triangle,
///   `f_θ(A) + f_θ(B)`, has **zero gradient** at the equilateral apex (the outward pull
///   of the length factor and the inward pull of the angle factor cancel; the same `k2`
///   for both [`PenaltyLength`]s); `k1 = ε·e^{k2 ω(60°)} ≈ 0.85` makes each angle's
///   penalty worth ε = [`EQUILATERAL_PENALTY`] = 0.02 there.
/// - *Continuous, with continuous derivatives except at A and B*: ω is continuous with its
///   derivative across the ±π ray; the squared length is a polynomial.
/// - *Coercive*: the squared length grows without bound far from the star, where
///   `(1 − α)²` alone is bounded and, on the inverted side, leads the node away (Fig. 2).
///
/// Where it departs from the text: the text names "the edge length opposite the node
/// where θ is computed" (|CB| for the angle at A, [`PenaltyLength::Opposite`]); with it
/// the sampled objective has spurious minima just outside reflex nodes (a test shows
/// them), so the default is |CA| ([`PenaltyLength::Adjacent`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AnglePenalty {
    /// Scale; default `ε·e^{k2 ω(60°)}`.
    pub k1: f64,
    /// Rate; default `2√3 / ω'(60°)` ≈ 3.634.
    pub k2: f64,
    /// Which edge scales the penalty; default [`PenaltyLength::Adjacent`].
    pub length: PenaltyLength,
}

/// The value of one angle's penalty on an equilateral triangle, ε.
pub const EQUILATERAL_PENALTY: f64 = 0.02;

impl Default for AnglePenalty {
    fn default() -> Self {
        Self::with_equilateral_penalty(EQUILATERAL_PENALTY)
    }
}

impl AnglePenalty {
    /// `k2` as documented and `k1` such that each angle penalty of an equilateral
    /// triangle is `eps`.
    pub fn with_equilateral_penalty(eps: f64) -> Self {
        let (w60, dw60) = adjusted_angle(PI / 3.0);
        let k2 = 2.0 * SQRT3 / dw60;
        AnglePenalty { k1: eps * exp(k2 * w60), k2, length: PenaltyLength::Adjacent }
    }

    /// One angle's penalty `k1 · ratio2 · exp(−k2 ω(θ))`, `ratio2` the squared length ratio.
    pub fn angle_penalty(&self, theta: f64, ratio2: f64) -> f64 {
        self.k1 * ratio2 * exp(-self.k2 * adjusted_angle(theta).0)
    }

    /// `f_θ(A) + f_θ(B)` of the sub-triangle, with its gradient.
    pub(super) fn of(&self, t: &SubTriangle) -> (f64, DVec2) {
        let (ab, cab) = t.ab;
        let ab2 = ab.length_squared();
        if self.k1 == 0.0 || ab2 <= 0.0 {
            return (0.0, DVec2::ZERO); // no penalty, or A and B coincide: no angle to speak of
        }
        let (len_a, len_b) = match self.length {
            PenaltyLength::Adjacent => (t.ca, t.cb),
            PenaltyLength::Opposite => (t.cb, t.ca),
        };
        let inv_ab2 = 1.0 / ab2;
        // at A: from the edge towards B to the edge towards C
        let (va, ga) = self.penalty(t.a_to_b, t.a_to_c, len_a, (ab, cab, inv_ab2));
        // at B: from the edge towards C to the edge towards A
        let (vb, gb) = self.penalty(t.b_to_c, t.b_to_a, len_b, (ab, cab, inv_ab2));
        (va + vb, ga + gb)
    }

    /// `k1 (ℓ/c)² exp(−k2 ω(θ))` for the corner angle θ from `e1` to `e2`, with `len` the
    /// chord of length ℓ and `c` the chord AB (vector, weight, 1/|AB|²), and its gradient.
    #[inline]
    fn penalty(
        &self,
        (e1, c1): (DVec2, f64),
        (e2, c2): (DVec2, f64),
        (len, clen): (DVec2, f64),
        (ab, cab, inv_ab2): (DVec2, f64, f64),
    ) -> (f64, DVec2) {
        let (theta, gt1, gt2) = signed_angle_gradient(e1, e2);
        let grad_theta = c1 * gt1 + c2 * gt2;
        let (omega, domega) = adjusted_angle(theta);
        let r = len.length_squared() * inv_ab2;
        // ∇(ℓ²/c²) = (2 clen ℓ − r · 2 cab c) / c²; cab = 0 unless A or B moves with C
        let grad_r = (2.0 * inv_ab2) * (clen * len - r * cab * ab);
        let e = self.k1 * exp(-self.k2 * omega);
        (e * r, e * (grad_r - self.k2 * domega * r * grad_theta))
    }
}
