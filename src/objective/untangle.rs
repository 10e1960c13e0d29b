//! Knupp's untangling objectives (Knupp 1999, §2.7): they ask only for positive corner
//! determinants, not for good shapes, and are run before a barrier objective.
//!
//! The formulas, in one notation: `docs/formulas.md` §5.

use glam::DVec2;

use super::corners::{CornerJet, ElementJets};
use super::{impl_objective_by_visit, ObjectiveKind, Star, Term};
use crate::mesh::ElementKind;

/// The corner determinants of the moving corners, with their gradients:
/// `det = cross(e1, e2)` (±∞, never NaN, where it overflows: [`crate::quality::corner_det`]), `∂det/∂e1 = −perp(e2)`, `∂det/∂e2 = perp(e1)`.
#[inline(always)]
fn visit_dets(star: &Star, x: DVec2, mut emit: impl FnMut(u32, f64, DVec2)) {
    #[inline(always)]
    fn det(c: &CornerJet) -> (f64, DVec2) {
        (crate::quality::corner_det(c.e1, c.e2), c.chain(-c.e2.perp(), c.e1.perp()))
    }
    for (i, el) in star.elems.iter().enumerate() {
        if matches!(el.kind, ElementKind::Tri3 | ElementKind::Quad4) {
            // the linear elements without the element jets (a 420-byte copy per element):
            // the same corner edge vectors (chords) and weights (1 at the free node, else
            // 0), corner by corner; every corner of a triangle moves, all but the opposite
            // one of a quad
            let (k, s) = (el.kind.corners(), el.slot as usize);
            let mut p = [el.pts[0], el.pts[1], el.pts[2], el.pts[3]];
            p[s] = x;
            let w = |j: usize| if j == s { 1.0 } else { 0.0 };
            for j in (0..k).filter(|&j| k == 3 || j != (s + 2) % 4) {
                let (next, prev) = ((j + 1) % k, (j + k - 1) % k);
                let (d, g) = det(&CornerJet { e1: p[next] - p[j], e2: p[prev] - p[j], c1: w(next) - w(j), c2: w(prev) - w(j) });
                emit(i as u32, d, g);
            }
            continue;
        }
        let j = ElementJets::new(el, x);
        for c in j.corner_jets().iter().filter(|c| c.moves()) {
            let (d, g) = det(c);
            emit(i as u32, d, g);
        }
    }
}

/// Knupp's second untangling objective, `Σ (|det − β| − (det − β))` over the moving
/// corners of the star, minimised (Knupp 1999, §2.7, with Mesquite's shift β ≥ 0, its
/// `UntangleBetaQualityMetric`). Each term is `2·max(0, β − det)`: zero once every
/// moving corner has `det ≥ β`. Piecewise linear in each det; at `det = β` the gradient
/// is that of the valid side (zero). Dimensional (an area), with the plain corner
/// Jacobian `A` (no ideal weight: only signs matter).
///
/// Why the shift: with β = 0 (Knupp's form as published) any configuration with every
/// det ≥ 0 is a minimum, including the *degenerate* ones — a star folded flat, or one
/// whose free node sits on the line of an opposite edge. Node-by-node descent on a
/// randomly placed grid walks into exactly those: the objective total falls by three
/// orders of magnitude while most of the inverted elements stay inverted by a sliver
/// (det ≈ −10⁻⁶ of the star's mean |det|), and no single node can leave the plateau,
/// because every term there has a zero or nearly cancelling gradient. Asking for
/// `det ≥ β > 0` puts the minimum strictly inside the valid region, so a node that
/// reaches it has left every neighbour it can with a margin.
///
/// `beta` is a fraction of the star's mean corner |det| at the node's current position
/// (`Star::elems[..].pts`, not the trial point: β is one constant through a solve, so the
/// objective stays piecewise linear and its gradient exact). `beta = 0` is Knupp's form.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Untangle {
    /// β as a fraction of the star's mean corner |det|. Default [`UNTANGLE_BETA`].
    pub beta: f64,
    /// The power `p` each term is raised to. Default 2.
    pub power: u32,
}

/// The default shift of [`Untangle`], a fraction of the star's mean corner |det|.
pub const UNTANGLE_BETA: f64 = 0.05;

impl Default for Untangle {
    fn default() -> Self {
        Untangle { beta: UNTANGLE_BETA, power: 2 }
    }
}

impl Untangle {
    /// Knupp's form as published, `Σ (|det| − det)` (β = 0).
    pub const KNUPP: Untangle = Untangle { beta: 0.0, power: 1 };

    pub fn kind(&self) -> ObjectiveKind {
        ObjectiveKind::Untangle
    }

    /// The shift β of `star` in area units: `beta` × the mean |det| of the moving corners
    /// with the free node where it is now.
    pub fn shift(&self, star: &Star) -> f64 {
        if self.beta == 0.0 {
            return 0.0;
        }
        // the same at every evaluation of a solve: kept in the star
        let (sum, n) = super::StarMemo::dets(star, |star| {
            let (mut sum, mut n) = (0.0, 0usize);
            visit_dets(star, star.x0, |_, det, _| {
                sum += det.abs();
                n += 1;
            });
            (sum, n)
        });
        if n == 0 {
            0.0
        } else {
            self.beta * sum / n as f64
        }
    }

    /// Calls `emit` with one term per moving corner.
    pub fn visit(&self, star: &Star, x: DVec2, mut emit: impl FnMut(Term)) {
        let beta = self.shift(star);
        visit_dets(star, x, |elem, det, grad| {
            let (value, grad) = if det < beta {
                let t = 2.0 * (beta - det);
                match self.power {
                    1 => (t, -2.0 * grad),
                    // the default power written out: what `powi` gives for 2 and 1, bit
                    // for bit, without its call
                    2 => (t * t, -4.0 * t * grad),
                    p => (t.powi(p as i32), -2.0 * p as f64 * t.powi(p as i32 - 1) * grad),
                }
            } else {
                (0.0, DVec2::ZERO)
            };
            emit(Term { elem, value, grad });
        });
    }
}

impl_objective_by_visit!(Untangle);

/// Knupp and Freitag's first untangling objective: maximise the minimum corner
/// determinant of the moving corners (`max min det`; level sets convex for triangles,
/// Freitag). One term per moving corner, the det itself.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MaxMinDet;

impl MaxMinDet {
    pub fn kind(&self) -> ObjectiveKind {
        ObjectiveKind::UntangleMinDet
    }

    /// Calls `emit` with one term per moving corner.
    pub fn visit(&self, star: &Star, x: DVec2, mut emit: impl FnMut(Term)) {
        visit_dets(star, x, |elem, value, grad| emit(Term { elem, value, grad }));
    }
}

impl_objective_by_visit!(MaxMinDet);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::objective::testing::*;
    use crate::objective::Objective;
    use crate::quality::corner_edges;

    /// Whether every moving corner of the star is valid at `x` (computed independently
    /// of the objective, from the element's own corners).
    fn all_moving_dets_positive(star: &Star, x: DVec2) -> bool {
        star.elems.iter().all(|el| {
            let p = el.at(x);
            let p0 = el.at(x + d(1.0, 0.5));
            let ce = corner_edges(el.kind, &p[..el.kind.node_count()]);
            let ce0 = corner_edges(el.kind, &p0[..el.kind.node_count()]);
            ce.iter().zip(&ce0).take(el.kind.corners()).all(|(c, c0)| c == c0 || c.0.perp_dot(c.1) > 0.0)
        })
    }

    #[test]
    fn zero_exactly_when_all_dets_positive() {
        let mut rng = SplitMix64::new(17);
        let (mut zero, mut positive) = (0, 0);
        for star in sample_stars() {
            for _ in 0..200 {
                let x = star.x0 + rng.point(1.5);
                let v = Untangle::KNUPP.value(&star, x);
                let valid = all_moving_dets_positive(&star, x);
                assert_eq!(v == 0.0, valid, "untangle {v} at {x}, valid: {valid}");
                assert!(v >= 0.0);
                if valid {
                    zero += 1;
                } else {
                    positive += 1;
                }
                // and the max-min det agrees on the sign
                assert_eq!(MaxMinDet.value(&star, x) > 0.0, valid);
            }
        }
        assert!(zero > 100 && positive > 100, "both cases seen: {zero} {positive}");
    }

    #[test]
    fn the_kept_shift_is_the_shift_where_the_star_is() {
        for star in sample_stars() {
            let u = Untangle::default();
            let first = u.shift(&star);
            assert!(first > 0.0);
            assert_eq!(u.shift(&star).to_bits(), first.to_bits(), "kept");
            // a star whose x0 is set after the fact was kept: worked out again there (far
            // enough to fold elements: within the star the dets' sum, twice its area, stays)
            let mut moved = star.clone();
            let _ = u.shift(&moved);
            moved.x0 += d(2.5, 0.3);
            let fresh = u.shift(&Star { x0: moved.x0, ..star.clone() });
            assert_eq!(u.shift(&moved).to_bits(), fresh.to_bits());
            assert_ne!(fresh.to_bits(), first.to_bits());
        }
    }

    #[test]
    fn hand_derived_values() {
        // one unit right triangle with the free node at the right angle: det = 1 at
        // every corner (cross of the two edges); reflected through the far edge it is −1
        let s = star(vec![elem(crate::mesh::ElementKind::Tri3, &[d(0.0, 0.0), d(1.0, 0.0), d(0.0, 1.0)], 0)]);
        let (v, g) = MaxMinDet.value_and_gradient(&s, d(0.0, 0.0));
        assert!((v - 1.0).abs() < 1e-15);
        // d det/dx at the free corner: det = cross(B − x, C − x) → gradient perp(C − B)... = (−1, −1)
        assert!((g - d(-1.0, -1.0)).length() < 1e-15, "{g}");
        let (v, g) = Untangle::KNUPP.value_and_gradient(&s, d(1.0, 1.0));
        // det = cross((0,−1), (−1,0)) = −1 at each of the 3 corners: Σ 2·1 = 6
        assert!((v - 6.0).abs() < 1e-15, "{v}");
        assert!((g - 3.0 * 2.0 * d(1.0, 1.0)).length() < 1e-14, "{g}");
    }

    #[test]
    fn gradients_match_central_differences() {
        let mut rng = SplitMix64::new(19);
        let (mut checked, mut total) = (0, 0);
        for star in sample_stars() {
            for _ in 0..30 {
                let x = star.x0 + rng.point(1.5);
                for obj in [&Untangle::KNUPP as &dyn Objective, &Untangle::default(), &MaxMinDet] {
                    let (c, t) = check_term_gradients(obj, &star, x, 1e-6);
                    checked += c;
                    total += t;
                }
                // the sum is smooth where no det is near zero
                if looks_smooth(|p| Untangle::default().value(&star, p), x, 1e-6) {
                    check_gradient(&Untangle::default(), &star, x, 1e-6);
                }
            }
        }
        assert!(checked * 10 >= total * 9, "{checked} of {total}");
    }
}
