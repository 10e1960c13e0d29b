//! The objectives of a tetrahedral star, as one enum ([`SolidObjective`]).
//! Its `new` is the regularised mean ratio ([`RegularisedMeanRatio`]).

use glam::{DMat3, DVec3};

use super::{CornerStar, StarCorner};
use crate::objective::{
    Goal, Objective, ObjectiveKind, Term, BARRIER_EPSILON, BARRIER_WEIGHT, CONDITION_BARRIER,
};
use crate::quality::solid::scaled_jacobian_grad0;
use crate::quality::tet::{self as q3, outer, CornerReference, WeightedJacobian, EQUILATERAL_TET};

/// Chen, Tristano & Kwok's objective carried to solids: per tetrahedron
/// `(1 − q_δ)² + k1·η_δ²` with `η_δ = ‖T‖²_F / (3·h_δ(σ)^{2/3})` and `q_δ = 1/η_δ`, where
/// `T = A·W⁻¹` is the corner Jacobian weighted by the equilateral tetrahedron (Knupp
/// 1999), `σ = det T` and `h_δ(σ) = (σ + √(σ² + 4δ²))/2` the regularised determinant of
/// Escobar, Rodríguez, Montenegro, Montero & González-Yuste (2003), who state exactly this
/// `η_δ` for tetrahedra. With δ = 0 it is the mean ratio `q` (1 for the regular
/// tetrahedron) and a barrier (+∞ where σ ≤ 0); with δ > 0 it is finite and smooth on
/// inverted stars and falls as a fold gets shallower, so one process untangles and
/// smooths — the planar design ([`crate::objective::RegularisedBarrier`]) in 3D.
///
/// δ is set once per solve from the star as gathered, as in the plane: with `m = ε·mean|σ|`
/// and `σ_min` the smallest σ, `δ = √(m(m − σ_min))` when `σ_min < m`, else 0 (the worst
/// tetrahedron counts as a valid sliver of determinant `m`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RegularisedMeanRatio {
    /// Weight of `η_δ²`; default the planar [`BARRIER_WEIGHT`].
    pub k1: f64,
    /// Fraction of the star's mean |σ| that sets δ; default the planar [`BARRIER_EPSILON`].
    pub epsilon: f64,
}

impl Default for RegularisedMeanRatio {
    fn default() -> Self {
        RegularisedMeanRatio {
            k1: BARRIER_WEIGHT,
            epsilon: BARRIER_EPSILON,
        }
    }
}

/// The objectives of a tetrahedral star (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SolidObjective {
    MeanRatio,
    DihedralSine,
    Regularised(RegularisedMeanRatio),
    Condition,
    ConditionMax,
    Untangle { beta: f64 },
    MinDet,
}

impl RegularisedMeanRatio {
    /// δ of a star at its position `x0` (see the type docs).
    pub fn delta(&self, star: &CornerStar) -> f64 {
        if star.tets.is_empty() || self.epsilon == 0.0 {
            return 0.0;
        }
        let (mut sum, mut min) = (0.0, f64::INFINITY);
        for t in &star.tets {
            let s = t.form.sigma_at(star.x0);
            sum += s.abs();
            min = min.min(s);
        }
        let m = self.epsilon * sum / star.tets.len() as f64;
        if m > 0.0 && m.is_finite() && min < m {
            (m * (m - min)).sqrt()
        } else {
            0.0
        }
    }

    /// The term of one corner with its gradient, and its Hessian when `HESSIAN` (the zero
    /// matrix otherwise; the value and gradient are the same arithmetic either way), from
    /// the corner's weighted Jacobian `j` and `∇²F = hf·I` ([`CornerForm`]). With
    /// `L = ln η = ln F − ln 3 − (2/3) ln h` and `dh/dσ = h/s`:
    /// `∇L = ∇F/F − (2/3)·∇σ/s`, and, `∇σ` being constant and `ds/dσ = σ/s`,
    /// `∇²L = (hf/F)·I − ∇F∇Fᵀ/F² + (2/3)(σ/s³)·∇σ∇σᵀ`; the term `g(L) = (1 − e^{−L})² +
    /// k1·e^{2L}` has `g′ = 2(1 − q)q + 2k1η²` and `g″ = −2q + 4q² + 4k1η²`, so its Hessian
    /// is `g″·∇L∇Lᵀ + g′·∇²L` (`docs/formulas.md` §8).
    #[inline(always)]
    fn term<const HESSIAN: bool>(
        &self,
        j: &WeightedJacobian,
        hf: f64,
        delta: f64,
    ) -> (f64, DVec3, DMat3) {
        if j.frob2 <= 0.0 {
            return (0.0, DVec3::ZERO, DMat3::ZERO); // four coincident corners: no shape to penalise
        }
        let (h, s) = if delta == 0.0 {
            (j.sigma.max(0.0), j.sigma)
        } else {
            crate::objective::regularised_determinant(j.sigma, delta)
        };
        if h <= 0.0 || h.is_nan() {
            return (f64::INFINITY, DVec3::ZERO, DMat3::ZERO);
        }
        // q = 1/η = 3 h^{2/3} / F, by reciprocals taken once (a division costs several
        // multiplications)
        let c = crate::numeric::cbrt_fast(h);
        let inv_f = 1.0 / j.frob2;
        let q = 3.0 * c * c * inv_f;
        let eta = 1.0 / q;
        let grad_f = j.grad_frob2 * inv_f;
        let two_thirds_inv_s = (2.0 / 3.0) / s;
        let grad_ln = grad_f - j.grad_sigma * two_thirds_inv_s;
        // (1 − q)², ∇q = −q ∇ln η
        let k1_eta2 = self.k1 * eta * eta;
        let value = (1.0 - q) * (1.0 - q) + k1_eta2;
        let d1 = 2.0 * (1.0 - q) * q + 2.0 * k1_eta2;
        if !HESSIAN {
            return (value, d1 * grad_ln, DMat3::ZERO);
        }
        let d2 = -2.0 * q + 4.0 * q * q + 4.0 * k1_eta2;
        // (2/3)·σ/s³
        let curvature = two_thirds_inv_s * j.sigma / (s * s);
        let hess_ln = DMat3::from_diagonal(DVec3::splat(hf * inv_f)) - outer(grad_f, grad_f)
            + outer(j.grad_sigma, j.grad_sigma * curvature);
        (
            value,
            d1 * grad_ln,
            outer(grad_ln, grad_ln * d2) + hess_ln * d1,
        )
    }

    /// The objective over `star` at `x` with its gradient and, when `HESSIAN`, its Hessian:
    /// the sum of [`term`](Self::term) over the star's corners, each read from its form.
    #[inline(always)]
    fn sum<const HESSIAN: bool>(&self, star: &CornerStar, x: DVec3) -> (f64, DVec3, DMat3) {
        debug_assert!(
            star.forms_pending_at.is_none(),
            "an objective reads the corners' forms"
        );
        let delta = self.delta(star);
        let (mut value, mut grad, mut hess) = (0.0, DVec3::ZERO, DMat3::ZERO);
        for t in &star.tets {
            let (v, g, h) =
                self.term::<HESSIAN>(&t.form.at(x), t.form.frob2_hessian_diagonal(), delta);
            value += v;
            grad += g;
            if HESSIAN {
                hess += h;
            }
        }
        (value, grad, hess)
    }
}

impl SolidObjective {
    /// What it is, in a few words for people ([`describe_solid`](super::describe_solid)).
    pub fn describe(&self) -> &'static str {
        match self {
            SolidObjective::MeanRatio => "max-min mean ratio (Freitag's ascent)",
            SolidObjective::DihedralSine => "max-min dihedral sine (Freitag)",
            SolidObjective::Regularised(_) => "Chen, Tristano & Kwok in 3D (Fletcher–Reeves)",
            SolidObjective::Condition => "condition number κ, 2-norm (Knupp)",
            SolidObjective::ConditionMax => "condition number κ, worst tetrahedron (Knupp)",
            SolidObjective::Untangle { .. } => "untangling Σ(|6V| − 6V) (Knupp)",
            SolidObjective::MinDet => "max-min 6V (Knupp & Freitag)",
        }
    }

    fn kind(&self) -> ObjectiveKind {
        match self {
            SolidObjective::MeanRatio => ObjectiveKind::MaxMinShape,
            SolidObjective::DihedralSine => ObjectiveKind::Sine,
            SolidObjective::Regularised(_) => ObjectiveKind::SmoothShape,
            SolidObjective::Condition => ObjectiveKind::Condition,
            SolidObjective::ConditionMax => ObjectiveKind::ConditionMax,
            SolidObjective::Untangle { .. } => ObjectiveKind::Untangle,
            SolidObjective::MinDet => ObjectiveKind::UntangleMinDet,
        }
    }

    /// Calls `emit` with every term at `x`.
    fn visit(&self, star: &CornerStar, x: DVec3, emit: impl FnMut(Term<DVec3>)) {
        debug_assert!(
            star.forms_pending_at.is_none(),
            "an objective reads the corners' forms"
        );
        if star.only_tets() {
            // every corner against the one static reference, a constant the measures fold
            self.visit_with(star, x, emit, |_| &EQUILATERAL_TET, |_| true)
        } else {
            // a targeted tetrahedron's sine is its corner's scaled Jacobian against the target
            let targeted = star.targeted();
            self.visit_with(
                star,
                x,
                emit,
                |i| star.reference_of(i),
                |t| t.simplex && !targeted,
            )
        }
    }

    /// [`visit`](Self::visit) with each corner's reference and whether it is a whole
    /// tetrahedron.
    #[inline(always)]
    fn visit_with<'a>(
        &self,
        star: &'a CornerStar,
        x: DVec3,
        mut emit: impl FnMut(Term<DVec3>),
        reference: impl Fn(usize) -> &'a CornerReference,
        simplex: impl Fn(&StarCorner) -> bool,
    ) {
        match *self {
            SolidObjective::Regularised(r) => {
                let delta = r.delta(star);
                for (i, t) in star.tets.iter().enumerate() {
                    let (value, grad, _) =
                        r.term::<false>(&t.form.at(x), t.form.frob2_hessian_diagonal(), delta);
                    emit(Term {
                        elem: i as u32,
                        value,
                        grad,
                    });
                }
            }
            SolidObjective::MeanRatio
            | SolidObjective::DihedralSine
            | SolidObjective::Condition
            | SolidObjective::ConditionMax
            | SolidObjective::MinDet => {
                for (i, t) in star.tets.iter().enumerate() {
                    self.corner_terms(t, i as u32, x, reference(i), simplex(t), &mut emit);
                }
            }
            SolidObjective::Untangle { beta } => {
                // β: a fraction of the star's mean |6V| as gathered, one constant per solve
                let shift = if star.tets.is_empty() {
                    0.0
                } else {
                    beta * (0..star.tets.len())
                        .map(|i| star.tets[i].form.volume6_at(star.x0, reference(i)).0.abs())
                        .sum::<f64>()
                        / star.tets.len() as f64
                };
                for (i, t) in star.tets.iter().enumerate() {
                    let (det, gdet) = t.form.volume6_at(x, reference(i));
                    let (value, grad) = if det < shift {
                        let d = 2.0 * (shift - det);
                        (d * d, -4.0 * d * gdet)
                    } else {
                        (0.0, DVec3::ZERO)
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
}

impl SolidObjective {
    /// The terms of one corner (index `i` in the star) at `x`, for the objectives whose
    /// terms are the corners' own (every kind but `new` and `untangle`, which read the
    /// whole star for δ and β), against reference `r`, `simplex` when it is a whole
    /// tetrahedron.
    #[inline(always)]
    fn corner_terms(
        &self,
        t: &StarCorner,
        i: u32,
        x: DVec3,
        r: &CornerReference,
        simplex: bool,
        emit: &mut impl FnMut(Term<DVec3>),
    ) {
        match *self {
            SolidObjective::MeanRatio => {
                // of the corners themselves, not the form: the max-min ascent follows its
                // active set, which rounding can change (on a tangled mesh, the whole path)
                let (value, grad) = q3::mean_ratio_grad0(&t.at(x), r);
                emit(Term {
                    elem: i,
                    value,
                    grad,
                });
            }
            SolidObjective::DihedralSine => {
                if simplex {
                    for (value, grad) in q3::dihedral_sines_grad0(&t.at(x)) {
                        emit(Term {
                            elem: i,
                            value,
                            grad,
                        });
                    }
                } else {
                    // a corner of another kind: its scaled Jacobian, the 3D sine of a corner
                    let (value, grad) = scaled_jacobian_grad0(&t.at(x), r);
                    emit(Term {
                        elem: i,
                        value,
                        grad,
                    });
                }
            }
            SolidObjective::Condition | SolidObjective::ConditionMax => {
                let max = matches!(self, SolidObjective::ConditionMax);
                let p = t.at(x);
                let (kappa, g) = q3::condition_number_grad0(&p, r);
                // behind the barrier (σ ≤ 0, or κ² beyond it): a huge finite value with
                // zero gradient, as in the plane ([`CONDITION_BARRIER`])
                let valid = q3::signed_volume(&p) > 0.0
                    && kappa.is_finite()
                    && kappa * kappa < CONDITION_BARRIER;
                let (value, grad) = match (max, valid) {
                    (false, true) => (kappa * kappa, 2.0 * kappa * g),
                    (false, false) => (CONDITION_BARRIER, DVec3::ZERO),
                    (true, true) => (-kappa, -g),
                    (true, false) => (-CONDITION_BARRIER, DVec3::ZERO),
                };
                emit(Term {
                    elem: i,
                    value,
                    grad,
                });
            }
            SolidObjective::MinDet => {
                let (value, grad) = t.form.volume6_at(x, r);
                emit(Term {
                    elem: i,
                    value,
                    grad,
                });
            }
            SolidObjective::Regularised(_) | SolidObjective::Untangle { .. } => {
                unreachable!("read the whole star")
            }
        }
    }

    /// [`Objective::terms_above`] of a max-min objective: the terms of corner `lead` first,
    /// then the others in the star's order (the lead's as already taken), stopping at the
    /// first that is not above `floor`; the terms pushed are [`Objective::terms`]' own.
    fn max_min_terms_above(
        &self,
        star: &CornerStar,
        x: DVec3,
        floor: f64,
        lead: u32,
        out: &mut Vec<Term<DVec3>>,
    ) -> bool {
        out.clear();
        let only_tets = star.only_tets();
        let r = |i: usize| {
            if only_tets {
                &EQUILATERAL_TET
            } else {
                star.reference_of(i)
            }
        };
        let simplex = |t: &StarCorner| only_tets || (t.simplex && !star.targeted());
        let mut above = true;
        // a corner has at most six terms (a tetrahedron's dihedral sines)
        let (mut lead_terms, mut n) = (
            [Term {
                elem: lead,
                value: 0.0,
                grad: DVec3::ZERO,
            }; 6],
            0,
        );
        if let Some(t) = star.tets.get(lead as usize) {
            // not `<=`: a NaN term is not above
            self.corner_terms(t, lead, x, r(lead as usize), simplex(t), &mut |term| {
                above &= term.value > floor;
                lead_terms[n] = term;
                n += 1;
            });
            if !above {
                return false;
            }
        }
        for (i, t) in star.tets.iter().enumerate() {
            if i == lead as usize {
                out.extend_from_slice(&lead_terms[..n]);
                continue;
            }
            self.corner_terms(t, i as u32, x, r(i), simplex(t), &mut |term| {
                above &= term.value > floor;
                out.push(term);
            });
            if !above {
                return false;
            }
        }
        !out.is_empty()
    }
}

impl Objective<CornerStar> for SolidObjective {
    fn name(&self) -> &'static str {
        self.kind().name()
    }
    fn goal(&self) -> Goal {
        self.kind().goal()
    }
    fn untangles(&self) -> bool {
        self.kind().untangles()
    }
    fn only_untangles(&self) -> bool {
        self.kind().only_untangles()
    }
    fn terms(&self, star: &CornerStar, x: DVec3, out: &mut Vec<Term<DVec3>>) {
        self.visit(star, x, |t| out.push(t));
    }
    fn value_and_gradient(&self, star: &CornerStar, x: DVec3) -> (f64, DVec3) {
        if let SolidObjective::Regularised(r) = self {
            let (v, g, _) = r.sum::<false>(star, x);
            return (v, g);
        }
        let mut fold = crate::objective::Fold::new(self.goal());
        self.visit(star, x, |t| fold.add(t));
        fold.finish()
    }
    fn terms_above(
        &self,
        star: &CornerStar,
        x: DVec3,
        floor: f64,
        lead: u32,
        out: &mut Vec<Term<DVec3>>,
    ) -> bool {
        if self.goal() != Goal::MaximizeMin {
            out.clear();
            self.terms(star, x, out);
            return !out.is_empty() && out.iter().all(|t| t.value > floor);
        }
        self.max_min_terms_above(star, x, floor, lead, out)
    }
    /// The regularised mean ratio's Hessian (the sum of its corners' terms' Hessians), for Newton's
    /// first trial; `None` for the others.
    fn value_gradient_hessian(&self, star: &CornerStar, x: DVec3) -> Option<(f64, DVec3, DMat3)> {
        match self {
            SolidObjective::Regularised(r) => Some(r.sum::<true>(star, x)),
            _ => None,
        }
    }
}
