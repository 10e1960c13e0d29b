//! Knupp's untangling objectives (Knupp 1999, §2.7): they ask only for positive corner
//! determinants, not for good shapes, and are run before a barrier objective.
//!
//! The formulas, in one notation: `docs/formulas.md` §5.

use glam::DVec2;

use super::corners::{CornerJet, ElementJets};
use super::{impl_objective_by_visit, ObjectiveKind, Star, Term};
use crate::mesh::ElementKind;

/// The corner determinant of corner jet `c`, with its gradient: `det = cross(e1, e2)` (±∞,
/// never NaN, where it overflows: [`crate::quality::corner_det`]), `∂det/∂e1 = −perp(e2)`,
/// `∂det/∂e2 = perp(e1)`.
#[inline(always)]
fn det(c: &CornerJet) -> (f64, DVec2) {
    (crate::quality::corner_det(c.e1, c.e2), c.chain(-c.e2.perp(), c.e1.perp()))
}

/// The moving corners' determinants of a linear element of `K` corners (3 or 4) with corners
/// `pts`, its free node at `slot` moved to `x`, without the element jets (a 420-byte copy per
/// element): the same corner edge vectors (chords) and weights (1 at the free node, else 0),
/// corner by corner; every corner of a triangle moves, all but the opposite one of a quad.
/// `K` constant, so the corners' indices are known when compiling.
#[inline(always)]
fn linear_dets<const K: usize>(pts: &[DVec2], slot: usize, x: DVec2, mut emit: impl FnMut(f64, DVec2)) {
    let mut p = [DVec2::ZERO; K];
    p.copy_from_slice(&pts[..K]);
    p[slot] = x;
    let w = |j: usize| if j == slot { 1.0 } else { 0.0 };
    for j in 0..K {
        if K == 4 && j == (slot + 2) % 4 {
            continue;
        }
        let (next, prev) = ((j + 1) % K, (j + K - 1) % K);
        let (d, g) = det(&CornerJet { e1: p[next] - p[j], e2: p[prev] - p[j], c1: w(next) - w(j), c2: w(prev) - w(j) });
        emit(d, g);
    }
}

/// The corner determinants of the moving corners, with their gradients ([`det`]).
#[inline(always)]
fn visit_dets(star: &Star, x: DVec2, mut emit: impl FnMut(u32, f64, DVec2)) {
    for (i, el) in star.elems.iter().enumerate() {
        let slot = el.slot as usize;
        match el.kind {
            ElementKind::Tri3 => linear_dets::<3>(&el.pts, slot, x, |d, g| emit(i as u32, d, g)),
            ElementKind::Quad4 => linear_dets::<4>(&el.pts, slot, x, |d, g| emit(i as u32, d, g)),
            _ => {
                let j = ElementJets::new(el, x);
                for c in j.corner_jets().iter().filter(|c| c.moves()) {
                    let (d, g) = det(c);
                    emit(i as u32, d, g);
                }
            }
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
        self.shift_of(super::StarMemo::dets(star, |star| {
            let (mut sum, mut n) = (0.0, 0usize);
            visit_dets(star, star.x0, |_, det, _| {
                sum += det.abs();
                n += 1;
            });
            (sum, n)
        }))
    }

    /// β from the sum of the moving corners' |det| and their number.
    fn shift_of(&self, (sum, n): (f64, usize)) -> f64 {
        if n == 0 {
            0.0
        } else {
            self.beta * sum / n as f64
        }
    }

    /// Calls `emit` with one term per moving corner.
    pub fn visit(&self, star: &Star, x: DVec2, mut emit: impl FnMut(Term)) {
        let term = |beta: f64, elem: u32, det: f64, grad: DVec2| {
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
            Term { elem, value, grad }
        };
        if self.beta != 0.0 && super::StarMemo::same(&x, star) && super::StarMemo::dets_kept(star).is_none() {
            // a solve's first evaluation: the shift's corners are the terms' corners, so
            // one sweep of them gives both (the same dets, summed in the same order)
            const HELD: usize = 48;
            let mut held = [(0u32, 0.0, DVec2::ZERO); HELD];
            let (mut sum, mut n) = (0.0, 0usize);
            visit_dets(star, x, |elem, det, grad| {
                sum += det.abs();
                if let Some(h) = held.get_mut(n) {
                    *h = (elem, det, grad);
                }
                n += 1;
            });
            super::StarMemo::keep_dets(star, (sum, n));
            if n <= HELD {
                let beta = self.shift_of((sum, n));
                for &(elem, det, grad) in &held[..n] {
                    emit(term(beta, elem, det, grad));
                }
                return;
            }
        }
        let beta = self.shift(star);
        visit_dets(star, x, |elem, det, grad| emit(term(beta, elem, det, grad)));
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
    fn a_solves_first_evaluation_has_the_terms_of_the_kept_shift() {
        // the first evaluation where the star is takes the shift and the terms in one sweep
        // (up to 48 corners); every evaluation after it, the shift kept: the same bits
        let mut stars = sample_stars();
        stars.push(fan_star(&regular_ring(60, 1.0)));
        let bits = |ts: &[Term]| ts.iter().map(|t| (t.elem, t.value.to_bits(), t.grad.x.to_bits(), t.grad.y.to_bits())).collect::<Vec<_>>();
        let (mut compared, mut positive) = (0, 0);
        for star in stars {
            for star in [star.clone(), Star { x0: star.x0 + d(0.9, 0.4), ..star }] {
                for u in [Untangle::default(), Untangle { beta: 0.3, power: 1 }, Untangle { beta: 0.05, power: 3 }] {
                    let (fresh, kept) = (star.clone(), star.clone());
                    let mut first = Vec::new();
                    u.visit(&fresh, fresh.x0, |t| first.push(t));
                    let _ = u.shift(&kept);
                    let mut again = Vec::new();
                    u.visit(&kept, kept.x0, |t| again.push(t));
                    assert_eq!(bits(&first), bits(&again));
                    assert_eq!(u.shift(&fresh).to_bits(), u.shift(&kept).to_bits());
                    compared += first.len();
                    positive += first.iter().filter(|t| t.value > 0.0).count();
                }
            }
        }
        assert!(compared > 1000 && positive > 100, "{positive} of {compared} terms positive");
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
