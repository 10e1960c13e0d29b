//! The OLD objective: maximise the minimum element shape of the star — α for
//! triangles, β for quads (Chen, Tristano & Kwok 2003, §5.3, "our previous method";
//! Canann et al. 1998). Non-smooth: the gradient jumps where the worst element changes.
//!
//! The formulas, in one notation: `docs/formulas.md` §2.

use glam::{DMat2, DVec2};

use super::corners::{CornerJet, ElementJets};
use super::{impl_objective_by_visit, ObjectiveKind, Star, StarElement, Term};
use crate::mesh::ElementKind;
use crate::quality::{
    lo_alpha_corner, lo_alpha_corner_gradient, lo_alpha_triangle_corners, ALPHA_90,
};

/// Max-min of the element shapes, one term per star element:
/// - a triangle's term is Lo's α, eq. (1) — for a quadratic triangle the smallest
///   corner α (with edge tangents), as in [`crate::quality::element_quality`];
/// - a quad's term is Canann's β, eq. (2): `min corner α / α90 − n_neg`. Its gradient is
///   that of the minimal corner α over α90; the `− n_neg` part is piecewise constant.
///
/// Term values equal [`crate::quality::element_quality`]`.shape` of the element with the
/// free node at `x`. Where the minimal corner of an element is not unique the gradient
/// is that of the first one (a one-sided derivative).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MaxMinShape;

impl MaxMinShape {
    pub fn kind(&self) -> ObjectiveKind {
        ObjectiveKind::MaxMinShape
    }

    /// Calls `emit` with one term per star element.
    pub fn visit(&self, star: &Star, x: DVec2, mut emit: impl FnMut(Term)) {
        for (i, el) in star.elems.iter().enumerate() {
            emit(element_term(el, star.frames_of(i), i, x, f64::NAN));
        }
    }

    /// [`Objective::terms_above`](crate::objective::Objective::terms_above): the element
    /// `lead` first, then the others in order, stopping at the first term not above
    /// `floor` (which then ends `out`, unless it was `lead`'s); the terms are
    /// [`visit`](Self::visit)'s, bit for bit.
    pub fn terms_above(
        &self,
        star: &Star,
        x: DVec2,
        floor: f64,
        lead: u32,
        out: &mut Vec<Term>,
    ) -> bool {
        out.clear();
        let lead = lead as usize;
        let first = match star.elems.get(lead) {
            Some(el) => element_term(el, star.frames_of(lead), lead, x, floor),
            None => return self.visit_while(star, x, floor, None, out),
        };
        // not `<=`: a NaN term is not above
        let above = first.value > floor;
        if !above {
            return false;
        }
        self.visit_while(star, x, floor, Some(first), out)
    }

    /// Appends the terms to `out` while they are above `floor` (the term of element
    /// `known.elem` taken from `known`); whether all were and there was one.
    #[inline(always)]
    fn visit_while(
        &self,
        star: &Star,
        x: DVec2,
        floor: f64,
        known: Option<Term>,
        out: &mut Vec<Term>,
    ) -> bool {
        for (i, el) in star.elems.iter().enumerate() {
            let t = match known {
                Some(k) if k.elem as usize == i => k,
                _ => element_term(el, star.frames_of(i), i, x, floor),
            };
            out.push(t);
            let above = t.value > floor;
            if !above {
                return false;
            }
        }
        !out.is_empty()
    }
}

/// The term of star element `el` (index `i` in the star) with the free node at `x`; the
/// gradient of a linear triangle's term is left zero when its value is at most `floor`
/// (the term is then not above it, and [`MaxMinShape::terms_above`] stops; no floor is
/// NaN).
#[inline(always)]
fn element_term(
    el: &StarElement,
    frames: Option<&[DMat2; 4]>,
    i: usize,
    x: DVec2,
    floor: f64,
) -> Term {
    if let (Some(f), ElementKind::Tri3) = (frames, el.kind) {
        // against a target the three corners share one T, so one α: the free corner's pair
        // in its frame, with its weights (both −1 before the frame)
        let s = el.slot as usize;
        let (e1, e2) =
            crate::target::in_frame(&f[s], el.pts[(s + 1) % 3] - x, el.pts[(s + 2) % 3] - x);
        let (c1, c2) = crate::target::in_frame(&f[s], -1.0, -1.0);
        let (value, g1, g2) = lo_alpha_corner_gradient(e1, e2);
        let grad = if value <= floor {
            DVec2::ZERO
        } else {
            c1 * g1 + c2 * g2
        };
        return Term {
            elem: i as u32,
            value,
            grad,
        };
    }
    if el.kind == ElementKind::Tri3 {
        // the common case without the element jets (a 420-byte copy per element): the
        // same corner edge vectors and weights (1 at the free node, else 0), the three
        // αs taken together and the gradient of the worst alone
        let s = el.slot as usize;
        let mut p = [el.pts[0], el.pts[1], el.pts[2]];
        p[s] = x;
        let w = |j: usize| if j == s { 1.0 } else { 0.0 };
        let corner = |j: usize| {
            let (next, prev) = ((j + 1) % 3, (j + 2) % 3);
            CornerJet {
                e1: p[next] - p[j],
                e2: p[prev] - p[j],
                c1: w(next) - w(j),
                c2: w(prev) - w(j),
            }
        };
        let Some(alpha) = lo_alpha_triangle_corners(&p) else {
            let corners = [corner(0), corner(1), corner(2)];
            let (min, worst, _) = worst_corner(&corners);
            let grad = if min <= floor {
                DVec2::ZERO
            } else {
                worst_gradient(&corners, worst)
            };
            return Term {
                elem: i as u32,
                value: min,
                grad,
            };
        };
        // worst_corner's choice: the first of the smallest
        let (mut min, mut worst) = (f64::INFINITY, None);
        for (k, &a) in alpha.iter().enumerate() {
            if a < min {
                (min, worst) = (a, Some(k));
            }
        }
        // a NaN floor (every term wanted) takes every gradient
        let grad = match worst {
            _ if min <= floor => DVec2::ZERO,
            Some(k) => worst_gradient(&[corner(k)], Some(0)),
            None => DVec2::ZERO,
        };
        return Term {
            elem: i as u32,
            value: min,
            grad,
        };
    }
    let mut j = ElementJets::new(el, x);
    if let Some(f) = frames {
        j.in_frames(f);
    }
    let corners = j.corner_jets();
    let (min, worst, neg) = worst_corner(corners);
    let grad = worst_gradient(corners, worst);
    let (value, grad) = if el.kind.is_triangle() {
        (min, grad)
    } else {
        (min / ALPHA_90 - neg as f64, grad / ALPHA_90)
    };
    Term {
        elem: i as u32,
        value,
        grad,
    }
}

/// One corner's α of a star element with the free node at `x`, and its gradient in the
/// free node ([`MaxMinShape::corner_terms`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CornerTerm {
    pub elem: u32,
    /// The corner's index in the element (0 is the element's first node).
    pub corner: u32,
    /// Lo's α at the corner (with edge tangents on a curved edge), over α90 for a quad.
    pub value: f64,
    pub grad: DVec2,
}

impl MaxMinShape {
    /// Every corner of every star element as a term of its own: what the per-element
    /// terms of [`MaxMinShape::visit`] take the smallest of. Where two corners of one
    /// element tie for its smallest α the element's term is not differentiable and its
    /// gradient is that of the first alone — Freitag's ascent (1997, Fig. 1) then sees one
    /// of the two; these terms show both (Chen et al. 2003, Fig. 9's max-min panel).
    pub fn corner_terms(&self, star: &Star, x: DVec2) -> Vec<CornerTerm> {
        let mut out = Vec::new();
        for (i, el) in star.elems.iter().enumerate() {
            let j = star.jets(i, el, x);
            let scale = if el.kind.is_triangle() {
                1.0
            } else {
                1.0 / ALPHA_90
            };
            for (k, c) in j.corner_jets().iter().enumerate() {
                let (a, g1, g2) = lo_alpha_corner_gradient(c.e1, c.e2);
                out.push(CornerTerm {
                    elem: i as u32,
                    corner: k as u32,
                    value: a * scale,
                    grad: c.chain(g1, g2) * scale,
                });
            }
        }
        out
    }
}

/// The smallest corner α of an element (the first, in corner order, of the smallest), that
/// corner's index (`None` when no α is below +∞: a NaN everywhere), and the number of
/// negative corner αs.
#[inline(always)]
fn worst_corner(corners: &[CornerJet]) -> (f64, Option<usize>, u32) {
    let (mut min, mut worst, mut neg) = (f64::INFINITY, None, 0);
    for (k, c) in corners.iter().enumerate() {
        let a = lo_alpha_corner(c.e1, c.e2);
        if a < min {
            min = a;
            worst = Some(k);
        }
        neg += (a < 0.0) as u32;
    }
    (min, worst, neg)
}

/// The gradient in the free node of the α of corner `worst` ([`worst_corner`]'s), taken
/// at that corner alone: [`lo_alpha_corner`] gives the α that [`lo_alpha_corner_gradient`]
/// gives, bit for bit.
#[inline(always)]
fn worst_gradient(corners: &[CornerJet], worst: Option<usize>) -> DVec2 {
    worst.map_or(DVec2::ZERO, |k| {
        let c = &corners[k];
        let (_, g1, g2) = lo_alpha_corner_gradient(c.e1, c.e2);
        c.chain(g1, g2)
    })
}

impl_objective_by_visit!(MaxMinShape, terms_above = terms_above);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::ElementKind;
    use crate::objective::testing::*;
    use crate::objective::{Goal, Objective};
    use crate::quality::element_quality;

    #[test]
    fn corner_terms_are_what_each_element_term_takes_the_least_of() {
        let star = fan_star(&regular_ring(5, 1.0));
        for x in [DVec2::ZERO, DVec2::new(0.3, -0.2), DVec2::new(1.5, 0.1)] {
            let corners = MaxMinShape.corner_terms(&star, x);
            assert_eq!(corners.len(), 3 * star.elems.len());
            let mut terms = Vec::new();
            MaxMinShape.terms(&star, x, &mut terms);
            for t in &terms {
                let least = corners
                    .iter()
                    .filter(|c| c.elem == t.elem)
                    .min_by(|a, b| a.value.total_cmp(&b.value))
                    .unwrap();
                assert_eq!(least.value, t.value, "element {} at {x}", t.elem);
                assert!(
                    (least.grad - t.grad).length() < 1e-12,
                    "element {} at {x}: {} vs {}",
                    t.elem,
                    least.grad,
                    t.grad
                );
            }
        }
    }

    #[test]
    fn equilateral_star_centre_is_one() {
        let star = fan_star(&regular_ring(6, 1.0));
        let (v, g) = MaxMinShape.value_and_gradient(&star, DVec2::ZERO);
        assert!((v - 1.0).abs() < 1e-12, "{v}");
        assert!(g.length() < 1e-12);
        // the square quad star too (β = 1)
        let (v, _) = MaxMinShape.value_and_gradient(&quad_star(), DVec2::ZERO);
        assert!((v - 1.0).abs() < 1e-12, "{v}");
        assert_eq!(MaxMinShape.goal(), Goal::MaximizeMin);
    }

    #[test]
    fn terms_are_the_element_shapes() {
        let mut rng = SplitMix64::new(7);
        for star in sample_stars() {
            for _ in 0..20 {
                let x = rng.point(1.6);
                let mut t = Vec::new();
                MaxMinShape.terms(&star, x, &mut t);
                assert_eq!(t.len(), star.len());
                for (term, el) in t.iter().zip(&star.elems) {
                    let p = el.at(x);
                    let q = element_quality(el.kind, &p[..el.kind.node_count()]);
                    assert!(
                        (term.value - q.shape).abs() < 1e-12,
                        "{} {}",
                        term.value,
                        q.shape
                    );
                }
            }
        }
    }

    #[test]
    fn term_gradients_match_central_differences() {
        let mut rng = SplitMix64::new(11);
        let mut checked = 0;
        let mut total = 0;
        for star in sample_stars() {
            for _ in 0..40 {
                let x = rng.point(1.6);
                let (c, t) = check_term_gradients(&MaxMinShape, &star, x, 1e-5);
                checked += c;
                total += t;
            }
        }
        // kinks (a quad's minimal corner changing, n_neg jumping) are rare at random points
        assert!(
            checked * 10 >= total * 8,
            "only {checked} of {total} terms were away from kinks"
        );
    }

    #[test]
    fn quadratic_straight_star_matches_linear() {
        let lin = fan_star(&regular_ring(5, 1.0));
        let quad = quadratic(&lin);
        assert!(quad
            .elems
            .iter()
            .all(|e| e.kind == ElementKind::Tri6 && e.follow_next && e.follow_prev));
        for x in [
            DVec2::new(0.1, 0.2),
            DVec2::new(-0.4, 0.3),
            DVec2::new(1.4, 0.0),
        ] {
            let (a, ga) = MaxMinShape.value_and_gradient(&lin, x);
            let (b, gb) = MaxMinShape.value_and_gradient(&quad, x);
            assert!((a - b).abs() < 1e-12 && (ga - gb).length() < 1e-10);
        }
    }
}
