//! The OLD objective: maximise the minimum element shape of the star — α for
//! triangles, β for quads (Chen, Tristano & Kwok 2003, §5.3, "our previous method";
//! Canann et al. 1998). Non-smooth: the gradient jumps where the worst element changes.
//!
//! The formulas, in one notation: `docs/formulas.md` §2.

use glam::DVec2;

use super::corners::ElementJets;
use super::{impl_objective_by_visit, ObjectiveKind, Star, Term};
use crate::quality::{lo_alpha_corner_gradient, ALPHA_90};

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
        ObjectiveKind::Old
    }

    /// Calls `emit` with one term per star element.
    pub fn visit(&self, star: &Star, x: DVec2, mut emit: impl FnMut(Term)) {
        for (i, el) in star.elems.iter().enumerate() {
            let j = ElementJets::new(el, x);
            let mut min = f64::INFINITY;
            let mut grad = DVec2::ZERO;
            let mut neg = 0;
            for c in j.corner_jets() {
                let (a, g1, g2) = lo_alpha_corner_gradient(c.e1, c.e2);
                if a < min {
                    min = a;
                    grad = c.chain(g1, g2);
                }
                if a < 0.0 {
                    neg += 1;
                }
            }
            let (value, grad) =
                if el.kind.is_triangle() { (min, grad) } else { (min / ALPHA_90 - neg as f64, grad / ALPHA_90) };
            emit(Term { elem: i as u32, value, grad });
        }
    }
}

impl_objective_by_visit!(MaxMinShape);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::ElementKind;
    use crate::objective::testing::*;
    use crate::objective::{Goal, Objective};
    use crate::quality::element_quality;

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
        let mut rng = Lcg::new(7);
        for star in sample_stars() {
            for _ in 0..20 {
                let x = rng.point(1.6);
                let mut t = Vec::new();
                MaxMinShape.terms(&star, x, &mut t);
                assert_eq!(t.len(), star.len());
                for (term, el) in t.iter().zip(&star.elems) {
                    let p = el.at(x);
                    let q = element_quality(el.kind, &p[..el.kind.node_count()]);
                    assert!((term.value - q.shape).abs() < 1e-12, "{} {}", term.value, q.shape);
                }
            }
        }
    }

    #[test]
    fn term_gradients_match_central_differences() {
        let mut rng = Lcg::new(11);
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
        assert!(checked * 10 >= total * 8, "only {checked} of {total} terms were away from kinks");
    }

    #[test]
    fn quadratic_straight_star_matches_linear() {
        let lin = fan_star(&regular_ring(5, 1.0));
        let quad = quadratic(&lin);
        assert!(quad.elems.iter().all(|e| e.kind == ElementKind::Tri6 && e.follow_next && e.follow_prev));
        for x in [DVec2::new(0.1, 0.2), DVec2::new(-0.4, 0.3), DVec2::new(1.4, 0.0)] {
            let (a, ga) = MaxMinShape.value_and_gradient(&lin, x);
            let (b, gb) = MaxMinShape.value_and_gradient(&quad, x);
            assert!((a - b).abs() < 1e-12 && (ga - gb).length() < 1e-10);
        }
    }
}
