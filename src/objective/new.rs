//! The NEW objective of Chen, Tristano & Kwok (2003), §2: smooth, and it untangles and
//! smooths in one process. (Design notes below in [`ChenTristanoKwok`].)

use std::f64::consts::PI;

use glam::DVec2;

use super::corners::ElementJets;
use super::{impl_objective_by_visit, ObjectiveKind, Star, Term};
use crate::mesh::ElementKind;
use crate::quality::elementary::exp;
use crate::quality::{lo_alpha_corner_gradient, signed_angle_gradient};

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

/// Chen, Tristano & Kwok's objective (the `new` objective). For the free node C and each
/// triangle (C, A, B) of its star (counter-clockwise),
///
/// `f = (1 − α_C)² + f_θ(A) + f_θ(B)` — eqs. (3)–(5) — with the angle penalty (our eq. (8))
///
/// `f_θ(A) = k1 · (|CA|/|AB|)² · exp(−k2 · ω(θ_A))`,
///
/// where α_C is Lo's α at C, θ_A the signed interior angle at A and ω the adjusted angle
/// of [`adjusted_angle`] (eqs. 6–7). Quads contribute their three sub-triangles containing
/// the free node D, eq. (9): (D, next, opposite), (D, opposite, previous),
/// (D, next, previous); the triangle of the other three corners is the "dead zone" and is
/// left out. In a mixed star each triangle's contribution is multiplied by 3
/// ([`Star::mixed`]). Quadratic elements: α at C and the angle at A use the edge end
/// tangents at C and at A (a quad diagonal is a straight chord); lengths are chords.
/// One term per star element.
///
/// # Eq. (8), lost in extraction: our choice and why
/// The text says what `f_θ` must do; each property is a test in this module.
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
///   for both [`PenaltyLength`]s), so the equilateral position stays a stationary point of
///   the whole objective; `k1 = ε·e^{k2 ω(60°)} ≈ 0.85` makes each angle's penalty worth
///   ε = [`EQUILATERAL_PENALTY`] = 0.02 there (0.04 per equilateral triangle, against
///   `(1 − α)²` values up to 4).
/// - *Continuous, with continuous derivatives except at A and B*: ω is continuous with its
///   derivative across the ±π ray; the squared length is a polynomial.
/// - *One minimum; untangles*: the squared length grows without bound far from the star,
///   so the objective is coercive, where `(1 − α)²` alone is bounded and, on the inverted
///   side, leads the node away (Chen Fig. 2).
///
/// Where we depart from the text: it names `a`, "the edge length opposite the node where
/// θ is computed" (|CB| for the angle at A). With that length the penalty at A keeps a
/// direction-dependent value as C → A, and on non-convex (star-shaped) stars the sampled
/// objective has many local minima just outside the reflex nodes, where plain descent from
/// inverted starts stalls. With |CA| instead ([`PenaltyLength::Adjacent`], the default) the
/// penalty at A fades as C reaches A while the one at B tends to a single value, so the
/// objective is C¹ everywhere; on every star we sample it has one minimum and descent
/// untangles from every inverted start we tried. The exponent 2 keeps the length factor a
/// polynomial (smooth where the length is 0). ε: every value from 0.005 to 0.1 untangled
/// all our test stars with one minimum; smaller ε keeps the minimiser of an irregular star
/// nearer that of `(1 − α)²` alone, so we took a small round value in that range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChenTristanoKwok {
    /// Scale of the angle penalty; default `ε·e^{k2 ω(60°)}` (see the type docs). 0 leaves
    /// `Σ (1 − α)²` alone.
    pub k1: f64,
    /// Rate of the angle penalty; default `2√3 / ω'(60°)` ≈ 3.634.
    pub k2: f64,
    /// Which edge scales the penalty; default [`PenaltyLength::Adjacent`].
    pub length: PenaltyLength,
}

/// The value of one angle's penalty on an equilateral triangle, ε.
pub const EQUILATERAL_PENALTY: f64 = 0.02;

impl Default for ChenTristanoKwok {
    fn default() -> Self {
        Self::with_equilateral_penalty(EQUILATERAL_PENALTY)
    }
}

impl ChenTristanoKwok {
    /// The objective with `k2` as documented and `k1` such that each angle penalty of an
    /// equilateral triangle is `eps`.
    pub fn with_equilateral_penalty(eps: f64) -> Self {
        let (w60, dw60) = adjusted_angle(PI / 3.0);
        let k2 = 2.0 * SQRT3 / dw60;
        ChenTristanoKwok { k1: eps * exp(k2 * w60), k2, length: PenaltyLength::Adjacent }
    }

    /// The same objective with the penalty scaled by `length`.
    pub fn with_length(self, length: PenaltyLength) -> Self {
        ChenTristanoKwok { length, ..self }
    }

    pub fn kind(&self) -> ObjectiveKind {
        ObjectiveKind::New
    }

    /// One angle's penalty `k1 · ratio2 · exp(−k2 ω(θ))`, `ratio2` the squared length ratio.
    pub fn angle_penalty(&self, theta: f64, ratio2: f64) -> f64 {
        self.k1 * ratio2 * exp(-self.k2 * adjusted_angle(theta).0)
    }

    /// Calls `emit` with one term per star element.
    pub fn visit(&self, star: &Star, x: DVec2, mut emit: impl FnMut(Term)) {
        let w = if star.mixed { 3.0 } else { 1.0 };
        for (i, el) in star.elems.iter().enumerate() {
            let (value, grad) = if el.kind == ElementKind::Tri3 {
                // the common case, without the general element machinery (same arithmetic)
                let s = el.slot as usize;
                let (v, g) = self.sub_triangle(&SubTriangle::linear(x, el.pts[(s + 1) % 3], el.pts[(s + 2) % 3]));
                (w * v, w * g)
            } else {
                let j = ElementJets::new(el, x);
                let f = j.slot;
                if el.kind.is_triangle() {
                    let (v, g) = self.sub_triangle(&SubTriangle::of(&j, f, (f + 1) % 3, (f + 2) % 3));
                    (w * v, w * g)
                } else {
                    let (n, o, p) = ((f + 1) % 4, (f + 2) % 4, (f + 3) % 4);
                    let (v1, g1) = self.sub_triangle(&SubTriangle::of(&j, f, n, o));
                    let (v2, g2) = self.sub_triangle(&SubTriangle::of(&j, f, o, p));
                    let (v3, g3) = self.sub_triangle(&SubTriangle::of(&j, f, n, p));
                    (v1 + v2 + v3, g1 + g2 + g3)
                }
            };
            emit(Term { elem: i as u32, value, grad });
        }
    }

    /// `(1 − α_C)² + f_θ(A) + f_θ(B)` of the counter-clockwise triangle (C, A, B), C the
    /// free corner, with its gradient.
    fn sub_triangle(&self, t: &SubTriangle) -> (f64, DVec2) {
        let ((u1, cu1), (u2, cu2)) = (t.c_to_a, t.c_to_b);
        let (alpha, g1, g2) = lo_alpha_corner_gradient(u1, u2);
        let mut value = (1.0 - alpha) * (1.0 - alpha);
        let mut grad = -2.0 * (1.0 - alpha) * (cu1 * g1 + cu2 * g2);
        if self.k1 == 0.0 {
            return (value, grad);
        }
        let (ab, cab) = t.ab;
        let ab2 = ab.length_squared();
        if ab2 <= 0.0 {
            return (value, grad); // A and B coincide: no angle to speak of
        }
        let (len_a, len_b) = match self.length {
            PenaltyLength::Adjacent => (t.ca, t.cb),
            PenaltyLength::Opposite => (t.cb, t.ca),
        };
        let inv_ab2 = 1.0 / ab2;
        // at A: from the edge towards B to the edge towards C
        let (v, g) = self.penalty(t.a_to_b, t.a_to_c, len_a, (ab, cab, inv_ab2));
        value += v;
        grad += g;
        // at B: from the edge towards C to the edge towards A
        let (v, g) = self.penalty(t.b_to_c, t.b_to_a, len_b, (ab, cab, inv_ab2));
        (value + v, grad + g)
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

impl_objective_by_visit!(ChenTristanoKwok);

/// The vectors one triangle (C, A, B) of the objective reads, each with its weight
/// (`v = c·x + const`, see `corners.rs`): the directions at each corner towards the
/// others (edge vectors, or end tangents of quadratic edges) and the chords.
#[derive(Clone, Copy, Debug, PartialEq)]
struct SubTriangle {
    c_to_a: (DVec2, f64),
    c_to_b: (DVec2, f64),
    a_to_b: (DVec2, f64),
    a_to_c: (DVec2, f64),
    b_to_c: (DVec2, f64),
    b_to_a: (DVec2, f64),
    /// Chords AB, CA, CB.
    ab: (DVec2, f64),
    ca: (DVec2, f64),
    cb: (DVec2, f64),
}

impl SubTriangle {
    /// Corners `c`, `a`, `b` of a star element's jets.
    #[inline]
    fn of(j: &ElementJets, c: usize, a: usize, b: usize) -> Self {
        SubTriangle {
            c_to_a: j.dir(c, a),
            c_to_b: j.dir(c, b),
            a_to_b: j.dir(a, b),
            a_to_c: j.dir(a, c),
            b_to_c: j.dir(b, c),
            b_to_a: j.dir(b, a),
            ab: j.chord(a, b),
            ca: j.chord(c, a),
            cb: j.chord(c, b),
        }
    }

    /// A straight-sided triangle with the free node C at `x` and A, B fixed: what
    /// [`SubTriangle::of`] gives for a linear triangle, computed directly.
    #[inline]
    fn linear(x: DVec2, a: DVec2, b: DVec2) -> Self {
        let (ca, cb, ab) = (a - x, b - x, b - a);
        SubTriangle {
            c_to_a: (ca, -1.0),
            c_to_b: (cb, -1.0),
            a_to_b: (ab, 0.0),
            a_to_c: (x - a, 1.0),
            b_to_c: (x - b, 1.0),
            b_to_a: (a - b, 0.0),
            ab: (ab, 0.0),
            ca: (ca, -1.0),
            cb: (cb, -1.0),
        }
    }
}

#[cfg(test)]
mod tests;
