//! Freitag's max-min angle objective: maximise the minimum sine of the angles of the
//! star's elements (Freitag 1997, §3: "the minimum sine of the angles in the incident
//! elements … small near the angles of 0° and 180°").
//!
//! The formulas, in one notation: `docs/formulas.md` §2.

use glam::{DMat2, DVec2};

use super::corners::{CornerJet, ElementJets};
use super::{impl_objective_by_visit, ObjectiveKind, Star, StarElement, Term};
use crate::mesh::ElementKind;
use crate::quality::{scaled_jacobian_gradient, TriangleCorners};

/// Max-min of the sines of every corner angle of every star element — not only the free
/// node's corners: a quad's far corner and a triangle's other corners count too (their
/// terms have zero gradient when they do not move). One term per corner, `elem` naming
/// its element. The sine is signed (`cross/(|e1||e2|)`), so an inverted corner is negative.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MaxMinSine;

impl MaxMinSine {
    pub fn kind(&self) -> ObjectiveKind {
        ObjectiveKind::Sine
    }

    /// Calls `emit` with one term per corner of every star element.
    pub fn visit(&self, star: &Star, x: DVec2, mut emit: impl FnMut(Term)) {
        for (i, el) in star.elems.iter().enumerate() {
            element_terms(el, star.frames_of(i), i, x, f64::NAN, &mut emit);
        }
    }

    /// [`Objective::terms_above`](crate::objective::Objective::terms_above): the corners of
    /// element `lead` first, then the others in order, stopping at the first term not
    /// above `floor`; the terms are [`visit`](Self::visit)'s, bit for bit.
    pub fn terms_above(&self, star: &Star, x: DVec2, floor: f64, lead: u32, out: &mut Vec<Term>) -> bool {
        out.clear();
        let lead = lead as usize;
        let mut first = [Term { elem: 0, value: 0.0, grad: DVec2::ZERO }; 4];
        let mut n = 0;
        if let Some(el) = star.elems.get(lead) {
            let mut above = true;
            element_terms(el, star.frames_of(lead), lead, x, floor, |t| {
                // not `<=`: a NaN term is not above
                above &= t.value > floor;
                first[n] = t;
                n += 1;
            });
            if !above {
                return false;
            }
        }
        for (i, el) in star.elems.iter().enumerate() {
            if i == lead {
                out.extend_from_slice(&first[..n]);
                continue;
            }
            let mut above = true;
            element_terms(el, star.frames_of(i), i, x, floor, |t| {
                above &= t.value > floor;
                out.push(t);
            });
            if !above {
                return false;
            }
        }
        !out.is_empty()
    }
}

/// Calls `emit` with the term of each corner of star element `el` (index `i` in the star)
/// with the free node at `x`; a linear triangle's terms come without their gradients
/// when one of them is at most `floor` (the element's terms are then not all above it, and
/// [`MaxMinSine::terms_above`] stops; no floor is NaN).
#[inline(always)]
fn element_terms(
    el: &StarElement,
    frames: Option<&[DMat2; 4]>,
    i: usize,
    x: DVec2,
    floor: f64,
    mut emit: impl FnMut(Term),
) {
    let corner = |c: &CornerJet| {
        let (s, g1, g2) = scaled_jacobian_gradient(c.e1, c.e2);
        Term { elem: i as u32, value: s, grad: c.chain(g1, g2) }
    };
    if let (Some(f), ElementKind::Tri3) = (frames, el.kind) {
        // against a target the corners share one T: the triangle in the target's frame is
        // the free corner's pair in its frame (weights both −1 before it), and its other two
        // corners' pairs are differences of that pair
        let s = el.slot as usize;
        let (a, b) =
            crate::target::in_frame(&f[s], el.pts[(s + 1) % 3] - x, el.pts[(s + 2) % 3] - x);
        let (wa, wb) = crate::target::in_frame(&f[s], -1.0, -1.0);
        let mut jets = [CornerJet::default(); 3];
        jets[s] = CornerJet {
            e1: a,
            e2: b,
            c1: wa,
            c2: wb,
        };
        jets[(s + 1) % 3] = CornerJet {
            e1: b - a,
            e2: -a,
            c1: wb - wa,
            c2: -wa,
        };
        jets[(s + 2) % 3] = CornerJet {
            e1: -b,
            e2: a - b,
            c1: -wb,
            c2: wa - wb,
        };
        for c in &jets {
            emit(corner(c));
        }
        return;
    }
    if el.kind == ElementKind::Tri3 {
        // the common case without the element jets (a 420-byte copy per element): the
        // same corner edge vectors and weights, corner by corner
        let s = el.slot as usize;
        let mut p = [el.pts[0], el.pts[1], el.pts[2]];
        p[s] = x;
        let w = |j: usize| if j == s { 1.0 } else { 0.0 };
        let jet = |j: usize| {
            let (next, prev) = ((j + 1) % 3, (j + 2) % 3);
            CornerJet { e1: p[next] - p[j], e2: p[prev] - p[j], c1: w(next) - w(j), c2: w(prev) - w(j) }
        };
        let t = TriangleCorners::of(&p);
        let mut values = [0.0; 3];
        for (j, v) in values.iter_mut().enumerate() {
            let Some((value, ..)) = t.scaled_jacobian::<false>(j) else {
                // beyond 2^±200: corner by corner, brought to unit scale
                for j in 0..3 {
                    emit(corner(&jet(j)));
                }
                return;
            };
            *v = value;
        }
        if values.iter().any(|&v| v <= floor) {
            for value in values {
                emit(Term { elem: i as u32, value, grad: DVec2::ZERO });
            }
            return;
        }
        for j in 0..3 {
            let (value, g1, g2) = t.scaled_jacobian::<true>(j).unwrap_or_default();
            emit(Term { elem: i as u32, value, grad: jet(j).chain(g1, g2) });
        }
        return;
    }
    let mut j = ElementJets::new(el, x);
    if let Some(f) = frames {
        j.in_frames(f);
    }
    for c in j.corner_jets() {
        emit(corner(c));
    }
}

impl_objective_by_visit!(MaxMinSine, terms_above = terms_above);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::objective::testing::*;
    use crate::objective::Objective;

    #[test]
    fn regular_hexagon_centre_is_sin_60() {
        let star = fan_star(&regular_ring(6, 1.0));
        let mut t = Vec::new();
        MaxMinSine.terms(&star, DVec2::ZERO, &mut t);
        assert_eq!(t.len(), 18, "every corner of every element");
        let (v, _) = MaxMinSine.value_and_gradient(&star, DVec2::ZERO);
        assert!((v - (std::f64::consts::PI / 3.0).sin()).abs() < 1e-12);
        // moving the node lowers the minimum
        assert!(MaxMinSine.value(&star, d(0.1, 0.05)) < v);
        // the far corners count: a square star's minimum is sin 90° = 1 everywhere
        let (v, _) = MaxMinSine.value_and_gradient(&quad_star(), DVec2::ZERO);
        assert!((v - 1.0).abs() < 1e-12);
        // an angle near 180° is as bad as one near 0°: on the square star, at (0.5, 0.49)
        // the first quad's free corner is almost straight while its other angles are ≥ 45°
        let near_flat = MaxMinSine.value(&quad_star(), d(0.5, 0.49));
        assert!(near_flat > 0.0 && near_flat < 0.02, "{near_flat}");
    }

    #[test]
    fn inverted_corners_are_negative() {
        let star = fan_star(&regular_ring(6, 1.0));
        assert!(MaxMinSine.value(&star, d(1.3, 0.1)) < 0.0);
    }

    #[test]
    fn term_gradients_match_central_differences() {
        let mut rng = SplitMix64::new(5);
        let (mut checked, mut total) = (0, 0);
        for star in sample_stars() {
            for _ in 0..30 {
                let (c, t) = check_term_gradients(&MaxMinSine, &star, rng.point(1.6), 1e-5);
                checked += c;
                total += t;
            }
        }
        assert!(checked * 10 >= total * 9, "{checked} of {total}");
    }
}
