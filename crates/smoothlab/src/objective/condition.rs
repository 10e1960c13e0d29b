//! Knupp's condition-number objectives (Knupp 1999, §§2.1, 2.6): the condition number
//! κ of each corner Jacobian that moves with the free node, combined over the star as a
//! 2-norm (the average element) or an ∞-norm (the worst element).
//!
//! The formulas, in one notation: `docs/formulas.md` §5.

use glam::{DMat2, DVec2};

use super::{impl_objective_by_visit, ObjectiveKind, Star, Term};
use crate::mesh::ElementKind;
use crate::quality::metric::planar_condition_chain;
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
        match self.norm {
            Norm::Two if !far_from_unit_size(star) => {
                Self::visit_two::<false>(star, x, |i, value, grad, _| {
                    emit(Term {
                        elem: i as u32,
                        value,
                        grad,
                    })
                })
            }
            _ => self.visit_by_quality(star, x, emit),
        }
    }

    /// Value, gradient and Hessian (2×2) of the 2-norm objective `Σ κ²` at `x`; `None` for
    /// the ∞-norm (not smooth) and for a star far from unit size (edges beyond 2^±200 at
    /// the free node), which is evaluated through the scale-safe metrics of
    /// [`crate::quality`] instead. κ is `F/δ` at every corner of every element kind, `F`
    /// quadratic and `δ` linear in the free node (`docs/formulas.md` §5). The value and
    /// gradient are those of [`visit`](Self::visit), bit for bit.
    pub fn with_hessian(&self, star: &Star, x: DVec2) -> Option<(f64, DVec2, DMat2)> {
        if self.norm != Norm::Two || far_from_unit_size(star) {
            return None;
        }
        let mut sum = (0.0, DVec2::ZERO, DMat2::ZERO);
        Self::visit_two::<true>(star, x, |_, v, g, h| {
            sum.0 += v;
            sum.1 += g;
            sum.2 += h;
        });
        Some(sum)
    }

    /// The 2-norm terms `κ²` of a star whose edges are within 2^±200: `emit` gets each
    /// moving corner's element index, value, gradient and (when `HESSIAN`, else zero)
    /// Hessian. Behind the barrier (`det T ≤ 0`, or `κ² ≥ CONDITION_BARRIER`) a term is
    /// `CONDITION_BARRIER` with zero gradient and Hessian.
    #[inline(always)]
    fn visit_two<const HESSIAN: bool>(
        star: &Star,
        x: DVec2,
        mut emit: impl FnMut(usize, f64, DVec2, DMat2),
    ) {
        for (i, el) in star.elems.iter().enumerate() {
            let frames = star.frames_of(i);
            if el.kind == ElementKind::Tri3 {
                // the common case written out: a linear triangle's three corners share
                // one κ = D/(√3·N) (Knupp's weighted-κ theorem), so one corner's term is
                // worked out and emitted three times
                let s = el.slot as usize;
                let (pa, pb) = (el.pts[(s + 1) % 3], el.pts[(s + 2) % 3]);
                let t = match frames {
                    None => {
                        let (a, b, ab) = (pa - x, pb - x, pb - pa);
                        let n = a.perp_dot(b);
                        let dd = a.length_squared() + b.length_squared() + ab.length_squared();
                        // ∇N = perp(B − A), ∇D = −2(a + b), ∇²D = 4·I
                        two_norm_term::<HESSIAN>(dd, n, -2.0 * (a + b), ab.perp(), 4.0, 1.0 / 3.0)
                    }
                    // against a target the corners still share one T: the free corner's
                    // pair in its frame, with its weights (both −1 before the frame)
                    Some(f) => {
                        let (a, b) = crate::target::in_frame(&f[s], pa - x, pb - x);
                        let (wa, wb) = crate::target::in_frame(&f[s], -1.0, -1.0);
                        let ab = b - a;
                        let n = a.perp_dot(b);
                        let dd = a.length_squared() + b.length_squared() + ab.length_squared();
                        let grad_n = wb * a.perp() - wa * b.perp();
                        let grad_d = 2.0 * (wa * a + wb * b + (wb - wa) * ab);
                        let hess_d = 2.0 * (wa * wa + wb * wb + (wb - wa) * (wb - wa));
                        two_norm_term::<HESSIAN>(dd, n, grad_d, grad_n, hess_d, 1.0 / 3.0)
                    }
                };
                for _ in 0..3 {
                    emit(i, t.0, t.1, t.2);
                }
                continue;
            }
            if el.kind == ElementKind::Quad4 {
                // written out too: the three moving corners (all but the opposite one),
                // as `ElementJets` makes them, without its copies and node weights
                let s = el.slot as usize;
                let mut p = [el.pts[0], el.pts[1], el.pts[2], el.pts[3]];
                p[s] = x;
                let w = |k: usize| if k == s { 1.0 } else { 0.0 };
                for c in (0..4).filter(|&c| c != (s + 2) % 4) {
                    let (next, prev) = ((c + 1) % 4, (c + 3) % 4);
                    let (mut e1, mut e2, mut w1, mut w2) = (
                        p[next] - p[c],
                        p[prev] - p[c],
                        w(next) - w(c),
                        w(prev) - w(c),
                    );
                    if let Some(f) = frames {
                        (e1, e2) = crate::target::in_frame(&f[c], e1, e2);
                        (w1, w2) = crate::target::in_frame(&f[c], w1, w2);
                    }
                    let t = corner_term::<HESSIAN>(e1, e2, w1, w2);
                    emit(i, t.0, t.1, t.2);
                }
                continue;
            }
            let triangle = el.kind.is_triangle();
            let j = star.jets(i, el, x);
            for c in j.corner_jets().iter().filter(|c| c.moves()) {
                // T = [t1 t2] = A·W⁻¹, each column affine in x with a scalar weight
                let t = if triangle {
                    corner_term::<HESSIAN>(
                        c.e1,
                        (2.0 * c.e2 - c.e1) * INV_SQRT3,
                        c.c1,
                        (2.0 * c.c2 - c.c1) * INV_SQRT3,
                    )
                } else {
                    corner_term::<HESSIAN>(c.e1, c.e2, c.c1, c.c2)
                };
                emit(i, t.0, t.1, t.2);
            }
        }
    }

    /// The terms of every moving corner through [`condition_number_gradient`], which
    /// brings each corner to unit scale first: the ∞-norm, and the 2-norm of a star far
    /// from unit size.
    fn visit_by_quality(&self, star: &Star, x: DVec2, mut emit: impl FnMut(Term)) {
        for (i, el) in star.elems.iter().enumerate() {
            let ideal = if el.kind.is_triangle() {
                Ideal::Triangle
            } else {
                Ideal::Square
            };
            let j = star.jets(i, el, x);
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
                emit(Term {
                    elem: i as u32,
                    value,
                    grad,
                });
            }
        }
    }
}

const INV_SQRT3: f64 = 0.577_350_269_189_625_8;

/// Whether the edges at the free node of `star` (at [`Star::x0`]) reach beyond 2^±200, where
/// `F` and `δ` of a corner, products of two edge components, would leave the doubles (as
/// `new`'s check for the same stars).
#[inline]
fn far_from_unit_size(star: &Star) -> bool {
    let m = super::free_node_extent(star);
    !(m == 0.0 || crate::numeric::SAFE_SCALE.contains(&m))
        && crate::numeric::unit_factor(m).is_some()
}

/// The 2-norm term `κ²` of one corner whose weighted columns are `t1 = w1·x + const`,
/// `t2 = w2·x + const`: `κ = F/δ`, `F = |t1|² + |t2|²`, `δ = cross(t1, t2)`, with
/// `∇F = 2(w1·t1 + w2·t2)`, `∇²F = 2(w1² + w2²)·I`, `∇δ = −perp(w1·t2 − w2·t1)`.
#[inline(always)]
fn corner_term<const HESSIAN: bool>(t1: DVec2, t2: DVec2, w1: f64, w2: f64) -> (f64, DVec2, DMat2) {
    let f = t1.length_squared() + t2.length_squared();
    let det = t1.perp_dot(t2);
    let grad_f = 2.0 * (w1 * t1 + w2 * t2);
    let grad_det = -(w1 * t2 - w2 * t1).perp();
    two_norm_term::<HESSIAN>(f, det, grad_f, grad_det, 2.0 * (w1 * w1 + w2 * w2), 1.0)
}

/// One 2-norm term `w·q²` with `q = F/δ` ([`planar_condition_chain`]): `κ = q` for a
/// corner's `F = ‖T‖²_F`, `δ = det T`; `κ² = q²/3` for a linear triangle's `D/N`. The
/// term's gradient is `2w·q∇q` and its Hessian `2w(∇q∇qᵀ + q∇²q)` (zero unless `HESSIAN`).
/// `(CONDITION_BARRIER, 0, 0)` behind the barrier: `δ ≤ 0` (or NaN), or `w·q² ≥ CONDITION_BARRIER`.
#[inline(always)]
fn two_norm_term<const HESSIAN: bool>(
    f: f64,
    det: f64,
    grad_f: DVec2,
    grad_det: DVec2,
    hess_f: f64,
    w: f64,
) -> (f64, DVec2, DMat2) {
    let barrier = (CONDITION_BARRIER, DVec2::ZERO, DMat2::ZERO);
    if det <= 0.0 {
        return barrier;
    }
    let (q, gq, hq) = planar_condition_chain::<HESSIAN>(f, det, grad_f, grad_det, hess_f);
    let v = w * q * q;
    // NaN (a NaN δ or F) is behind the barrier too, as in `condition_number_gradient`'s use
    if v.is_nan() || v >= CONDITION_BARRIER {
        return barrier;
    }
    let grad = (2.0 * w * q) * gq;
    if !HESSIAN {
        return (v, grad, DMat2::ZERO);
    }
    let k = 2.0 * w;
    let hxx = k * (gq.x * gq.x + q * hq.x_axis.x);
    let hyy = k * (gq.y * gq.y + q * hq.y_axis.y);
    let hxy = k * (gq.x * gq.y + q * hq.x_axis.y);
    (
        v,
        grad,
        DMat2::from_cols(DVec2::new(hxx, hxy), DVec2::new(hxy, hyy)),
    )
}

impl_objective_by_visit!(ConditionNumber, with_hessian);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::objective::testing::*;
    use crate::objective::{Goal, Objective};

    const TWO: ConditionNumber = ConditionNumber { norm: Norm::Two };
    const INF: ConditionNumber = ConditionNumber {
        norm: Norm::Infinity,
    };

    #[test]
    fn ideal_corners_have_kappa_two() {
        // regular hexagon of equilateral triangles: 6 × 3 corners, each κ = 2
        let hex = fan_star(&regular_ring(6, 1.0));
        let mut t = Vec::new();
        TWO.terms(&hex, DVec2::ZERO, &mut t);
        assert_eq!(t.len(), 18);
        assert!(
            t.iter().all(|t| (t.value - 4.0).abs() < 1e-12),
            "κ² = 4 at each corner"
        );
        let (v, g) = INF.value_and_gradient(&hex, DVec2::ZERO);
        assert!((v + 2.0).abs() < 1e-12 && g.length() < 1e-12);
        // the square star: three moving corners per quad, κ = 2
        let mut t = Vec::new();
        TWO.terms(&quad_star(), DVec2::ZERO, &mut t);
        assert_eq!(t.len(), 12);
        assert!(t.iter().all(|t| (t.value - 4.0).abs() < 1e-12));
        assert_eq!(
            (TWO.goal(), INF.goal()),
            (Goal::MinimizeSum, Goal::MaximizeMin)
        );
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

    #[test]
    fn hessians_match_central_differences() {
        let mut rng = SplitMix64::new(17);
        let mut checks = 0;
        for star in sample_stars() {
            for _ in 0..30 {
                let x = star.x0 + rng.point(0.15);
                if TWO.value(&star, x) < CONDITION_BARRIER {
                    // the tolerance is relative to each column's size: κ² grows like
                    // 1/det², so near a barrier the entries are large
                    check_hessian(&TWO, &star, x, 1e-5);
                    checks += 1;
                }
            }
        }
        assert!(checks > 200, "{checks}");
        // the ∞-norm is not smooth: no Hessian, so no Newton trial
        assert!(INF
            .value_gradient_hessian(&quad_star(), DVec2::ZERO)
            .is_none());
    }

    #[test]
    fn written_out_terms_agree_with_the_quality_metrics() {
        // the 2-norm's own arithmetic (κ = F/δ, and D/(√3·N) for linear triangles) against
        // `condition_number_gradient`, term by term, at valid and inverted positions
        let mut rng = SplitMix64::new(19);
        let (mut finite, mut barrier) = (0, 0);
        for star in sample_stars() {
            for _ in 0..30 {
                let x = star.x0 + rng.point(0.6);
                let (mut fast, mut slow) = (Vec::new(), Vec::new());
                TWO.visit(&star, x, |t| fast.push(t));
                TWO.visit_by_quality(&star, x, |t| slow.push(t));
                assert_eq!(fast.len(), slow.len());
                for (a, b) in fast.iter().zip(&slow) {
                    assert_eq!(a.elem, b.elem);
                    if b.value >= CONDITION_BARRIER {
                        assert_eq!(
                            (a.value, a.grad),
                            (CONDITION_BARRIER, DVec2::ZERO),
                            "at {x}"
                        );
                        barrier += 1;
                        continue;
                    }
                    assert!(
                        (a.value - b.value).abs() <= 1e-12 * b.value,
                        "{} {} at {x}",
                        a.value,
                        b.value
                    );
                    assert!(
                        (a.grad - b.grad).length() <= 1e-10 * (1.0 + b.grad.length()),
                        "{} {} at {x}",
                        a.grad,
                        b.grad
                    );
                    finite += 1;
                }
            }
        }
        assert!(
            finite > 2000 && barrier > 100,
            "{finite} finite, {barrier} behind the barrier"
        );
    }

    #[test]
    fn stars_far_from_unit_size_take_the_scale_safe_metrics() {
        // edges of 2^±300: κ is a ratio and comes out as at unit size, with no Hessian
        // (no Newton trial) where F and δ would leave the doubles
        let star = sample_stars().swap_remove(2);
        let x = star.x0 + d(0.05, -0.03);
        let (v, g) = TWO.value_and_gradient(&star, x);
        for f in [2f64.powi(300), 2f64.powi(-300)] {
            let big = crate::objective::scaled_star(&star, f);
            assert!(TWO.value_gradient_hessian(&big, f * x).is_none());
            let (vb, gb) = TWO.value_and_gradient(&big, f * x);
            assert!((vb - v).abs() <= 1e-12 * v, "{vb} {v}");
            assert!((gb * f - g).length() <= 1e-10 * g.length(), "{gb} {g}");
        }
        assert!(TWO.value_gradient_hessian(&star, x).is_some());
    }
}
