//! Knupp's condition-number objectives (Knupp 1999, §§2.1, 2.6): the condition number
//! κ of each corner Jacobian that moves with the free node, combined over the star as a
//! 2-norm (the average element) or an ∞-norm (the worst element).
//!
//! The formulas, in one notation: `docs/formulas.md` §5.

use glam::DVec2;

use super::corners::ElementJets;
use super::{impl_objective_by_visit, ObjectiveKind, Star, Term};
use crate::quality::{condition_number_gradient, Ideal};

/// The value a corner term takes behind the barrier (`det ≤ 0`, where κ = ∞), with zero
/// gradient: `CONDITION_BARRIER` for the 2-norm terms, `−CONDITION_BARRIER` for the ∞-norm
/// terms. Knupp's κ is +∞ there; a huge finite value keeps a line search's arithmetic
/// (quadratic interpolation through a "high" point, differences of values) free of
/// `inf − inf` and `NaN`, while still above any finite κ² a valid corner can have
/// (finite terms are capped at this value too). Sums of up to ~10¹⁰⁸ such terms stay
/// finite. Inverted corners are counted by it: two inverted corners weigh twice one.
pub const CONDITION_BARRIER: f64 = 1e100;

/// How the corner condition numbers combine over the star (Knupp 1999, §2.1).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Norm {
    /// `Σ κ²`, minimised: optimises the average corner (smooth where valid).
    #[default]
    Two,
    /// `max κ`, minimised — here `min(−κ)` maximised: optimises the worst corner.
    Infinity,
}

/// Knupp's condition number `κ(T) = ‖T‖_F ‖T⁻¹‖_F = ‖T‖²_F / det T` of every corner
/// Jacobian of the star that moves with the free node, `T = A·W⁻¹` with the equilateral
/// ideal `W` for triangles and `T = A` for quads ([`crate::quality::condition_number`]).
/// κ ≥ 2, equal to 2 for the ideal corner, which is a stationary point; barrier at
/// `det T ≤ 0` (see [`CONDITION_BARRIER`]). One term per moving corner: the three corners of a
/// triangle (equal κ for a straight-sided triangle, by Knupp's weighted-κ theorem), the
/// free corner and its two neighbours for a quad.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ConditionNumber {
    pub norm: Norm,
}

impl ConditionNumber {
    pub fn kind(&self) -> ObjectiveKind {
        match self.norm {
            Norm::Two => ObjectiveKind::Condition,
            Norm::Infinity => ObjectiveKind::ConditionMax,
        }
    }

    /// Calls `emit` with one term per moving corner: `κ²` (2-norm) or `−κ` (∞-norm).
    pub fn visit(&self, star: &Star, x: DVec2, mut emit: impl FnMut(Term)) {
        for (i, el) in star.elems.iter().enumerate() {
            let ideal = if el.kind.is_triangle() { Ideal::Triangle } else { Ideal::Square };
            let j = ElementJets::new(el, x);
            for c in j.corner_jets().iter().filter(|c| c.moves()) {
                let (kappa, g1, g2) = condition_number_gradient(c.e1, c.e2, ideal);
                let grad = c.chain(g1, g2);
                let (value, grad) = match self.norm {
                    Norm::Two => {
                        let v = kappa * kappa;
                        if v < CONDITION_BARRIER {
                            (v, 2.0 * kappa * grad)
                        } else {
                            (CONDITION_BARRIER, DVec2::ZERO)
                        }
                    }
                    Norm::Infinity => {
                        if kappa < CONDITION_BARRIER {
                            (-kappa, -grad)
                        } else {
                            (-CONDITION_BARRIER, DVec2::ZERO)
                        }
                    }
                };
                emit(Term { elem: i as u32, value, grad });
            }
        }
    }
}

impl_objective_by_visit!(ConditionNumber);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::objective::testing::*;
    use crate::objective::{Goal, Objective};

    const TWO: ConditionNumber = ConditionNumber { norm: Norm::Two };
    const INF: ConditionNumber = ConditionNumber { norm: Norm::Infinity };

    #[test]
    fn ideal_corners_have_kappa_two() {
        // regular hexagon of equilateral triangles: 6 × 3 corners, each κ = 2
        let hex = fan_star(&regular_ring(6, 1.0));
        let mut t = Vec::new();
        TWO.terms(&hex, DVec2::ZERO, &mut t);
        assert_eq!(t.len(), 18);
        assert!(t.iter().all(|t| (t.value - 4.0).abs() < 1e-12), "κ² = 4 at each corner");
        let (v, g) = INF.value_and_gradient(&hex, DVec2::ZERO);
        assert!((v + 2.0).abs() < 1e-12 && g.length() < 1e-12);
        // the square star: three moving corners per quad, κ = 2
        let mut t = Vec::new();
        TWO.terms(&quad_star(), DVec2::ZERO, &mut t);
        assert_eq!(t.len(), 12);
        assert!(t.iter().all(|t| (t.value - 4.0).abs() < 1e-12));
        assert_eq!((TWO.goal(), INF.goal()), (Goal::MinimizeSum, Goal::MaximizeMin));
    }

    #[test]
    fn ideal_position_is_stationary_on_regular_stars() {
        // the hexagon and the square star are ideal; the other regular stars are not,
        // but their centre is still where the 2-norm is stationary
        for star in [fan_star(&regular_ring(6, 1.0)), quad_star()] {
            let (_, g) = TWO.value_and_gradient(&star, DVec2::ZERO);
            assert!(g.length() < 1e-12, "{g}");
        }
        for k in 4..=8 {
            let star = fan_star(&regular_ring(k, 1.0));
            let (v0, g) = TWO.value_and_gradient(&star, DVec2::ZERO);
            assert!(g.length() < 1e-10, "k = {k}: {g}");
            // and a minimum: every nearby position is worse
            for p in regular_ring(12, 0.05) {
                assert!(TWO.value(&star, p) > v0);
            }
        }
    }

    #[test]
    fn barrier_when_inverted() {
        let hex = fan_star(&regular_ring(6, 1.0));
        let x = d(1.2, 0.1); // outside the hexagon: some triangles inverted
        let (v, _) = TWO.value_and_gradient(&hex, x);
        assert!(v >= CONDITION_BARRIER && v.is_finite());
        let (v, _) = INF.value_and_gradient(&hex, x);
        assert_eq!(v, -CONDITION_BARRIER);
        // just across a ring edge is behind the barrier; just inside, κ is finite but huge
        let mid = 0.5 * (regular_ring(6, 1.0)[0] + regular_ring(6, 1.0)[1]);
        assert!(TWO.value(&hex, mid * (1.0 + 1e-9)) >= CONDITION_BARRIER);
        let inside = TWO.value(&hex, mid * (1.0 - 1e-6));
        assert!(inside > 1e10 && inside < CONDITION_BARRIER, "{inside}");
    }

    #[test]
    fn gradients_match_central_differences() {
        let mut rng = SplitMix64::new(13);
        let mut smooth_checks = 0;
        let (mut checked, mut total) = (0, 0);
        for star in sample_stars() {
            for _ in 0..30 {
                // valid positions near the centre, where the 2-norm is smooth
                let x = star.x0 + rng.point(0.15);
                if TWO.value(&star, x) < CONDITION_BARRIER {
                    check_gradient(&TWO, &star, x, 1e-5);
                    smooth_checks += 1;
                }
                let (c, t) = check_term_gradients(&INF, &star, x, 1e-5);
                checked += c;
                total += t;
            }
        }
        assert!(smooth_checks > 200, "{smooth_checks}");
        assert!(checked * 10 >= total * 9, "{checked} of {total}");
    }
}
