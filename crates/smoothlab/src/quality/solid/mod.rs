//! Every volume element kind measured by its corners (Knupp 1999, §2–3): at each measured
//! corner `c` with edge neighbours `a`, `b`, `d` ([`crate::mesh::VolumeKindRow::corner_edges`]) the
//! tetrahedron `(c, a, b, d)`, its Jacobian `A` (the three edge vectors) weighted by the
//! kind's reference, `T = A·W⁻¹`; and the element's validity decided for certain, not at
//! its corners only: a trilinear hexahedron can be inverted inside with all eight corner
//! determinants positive (Marschner, Palmer, Zhang & Solomon, SGP 2020).
//!
//! **Validity** ([`validity`]) is decided on the Jacobian determinant `det J` of the
//! element's map from its reference element, written in the Bernstein (Bézier) basis:
//! - a tetrahedron: `det J` is constant, six times its volume;
//! - a wedge: `det J` is affine in the triangle's barycentric coordinates and quadratic
//!   along its height, so its minimum is at a triangle corner, on one of three quadratics
//!   whose minimum is exact from their Bernstein coefficients (`c0, c2 > 0` and
//!   `c1 > −√(c0·c2)`): decided exactly;
//! - a hexahedron: `det J = X_u·(X_v × X_w)` with each column bilinear in the other two
//!   parameters, a polynomial of degree 2 in each of u, v, w with 27 Bernstein
//!   coefficients. All positive: valid (a Bernstein polynomial lies within the hull of its
//!   coefficients); a value ≤ 0 at a corner of the box (a corner coefficient is a value):
//!   inverted; else the box is split in half (de Casteljau, exact halving) and each half
//!   decided, up to [`MAX_BOXES`] boxes; where that is not enough (an element within
//!   rounding of flat) the element is [`Validity::Undecided`], which the guard and the
//!   statistics count as inverted;
//! - a pyramid, by its collapsed-hexahedron map `x = (1 − t)·B(u, v) + t·apex` with `B` the
//!   bilinear base: `det J = (1 − t)²·g(u, v)`, `g = B_u·(B_v × (apex − B))` of degree 2 in
//!   u and v, decided as the hexahedron's (the factor vanishes only at the apex).
//!
//! What is not certain: the quadratic kinds' mid-edge, face and centre nodes are taken
//! where they follow their corners to; a 10-node tetrahedron is judged at its four corners'
//! Jacobians ([`tet10_measures`]), a 20- or 27-node hexahedron by its corners' trilinear
//! hexahedron (exact when its edges are straight).
//!
//! `bernstein.rs` holds `det J` in the Bernstein basis. `free_corner.rs` holds its forms
//! as one corner moves ([`DetForm`], [`ValidBall`]). `measures.rs` holds the element's
//! measures ([`solid_measures`]). `corner_terms.rs` holds its terms corner by corner
//! ([`CornerShapes`], [`CornerSizes`]).

use glam::DVec3;

use super::tet as q3;
use crate::mesh::VolumeKind;

mod bernstein;
mod corner_terms;
mod free_corner;
mod measures;
#[cfg(test)]
mod tests;

use bernstein::{hex_det, pyramid_det};
pub use corner_terms::{corner_size, least_corner_det, CornerShapes, CornerSizes};
pub use free_corner::{DetForm, ValidBall};
pub use measures::{scaled_jacobian, scaled_jacobian_grad0, solid_reading, solid_within, solid_measures, solid_min_sine, solid_shape, tet10_measures, tet_measures, SolidMeasures};

/// How many boxes (the whole element, then halves) a hexahedron's or pyramid's validity
/// may examine before it is called [`Validity::Undecided`].
pub const MAX_BOXES: usize = 4096;

/// Whether an element's Jacobian determinant is positive everywhere in it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Validity {
    /// Positive everywhere: certain.
    Valid,
    /// Zero or negative somewhere: certain (at a point of the element).
    Inverted,
    /// Not decided within [`MAX_BOXES`] boxes: the determinant's smallest value is within
    /// rounding of 0. Counted as inverted.
    Undecided,
}

/// The tetrahedron `(c, a, b, d)` of measured corner `c` of an element of `kind` (its
/// corners `p`, in the kind's order).
#[inline(always)]
pub fn corner_tet(kind: VolumeKind, p: &[DVec3], c: usize) -> [DVec3; 4] {
    let [a, b, d] = kind.row().corner_edges[c];
    [p[c], p[a], p[b], p[d]]
}

/// The determinant of the corner's Jacobian `A` (six times its tetrahedron's volume).
#[inline]
fn corner_det(t: &[DVec3; 4]) -> f64 {
    (t[1] - t[0]).dot((t[2] - t[0]).cross(t[3] - t[0]))
}

/// The corners in their own scale, as [`q3::in_unit_scale`] does for a tetrahedron: as
/// they are when the edges' largest component lies within the safe scale, else multiplied
/// by a power of two (exact), so signs and ratios are the same at every scale, to the bit.
/// Not moved to the first corner: a difference of differences rounds twice, which lost a
/// whole element's corners next to a node at 1e61 (issue 61), and rounds otherwise than
/// the unit-scale mesh's one difference.
fn in_unit_scale(p: &[DVec3]) -> ([DVec3; 8], usize) {
    let mut q = [DVec3::ZERO; 8];
    let n = p.len().min(8);
    match crate::numeric::factors_beyond_safe_scale(reach(&p[..n])) {
        None => q[..n].copy_from_slice(&p[..n]),
        Some((f1, f2)) => {
            for i in 0..n {
                q[i] = p[i] * f1 * f2;
            }
        }
    }
    (q, n)
}

/// The largest component of an edge from the first corner: the element's extent, which
/// decides whether it is within the safe scale.
#[inline]
fn reach(p: &[DVec3]) -> f64 {
    crate::numeric::largest_component(p[1..].iter().map(|x| *x - p[0]))
}
/// A wedge's validity, exact (see the module docs).
fn wedge_validity(p: &[DVec3], given: &[DVec3]) -> Validity {
    // VTK's wedge: the triangle 0 1 2 turns clockwise seen from 3 4 5 above it, so
    // det J = −(∂ξ × ∂η)·∂ζ
    let e1 = [p[1] - p[0], p[4] - p[3]];
    let e2 = [p[2] - p[0], p[5] - p[3]];
    let c = [e1[0].cross(e2[0]), 0.5 * (e1[0].cross(e2[1]) + e1[1].cross(e2[0])), e1[1].cross(e2[1])];
    // signs read beyond their rounding, else the exact ones decide (issue 61)
    let margin = bernstein::rounding_margin(p);
    let mut undecided = false;
    for i in 0..3 {
        let up = p[i + 3] - p[i];
        let [c0, c1, c2] = c.map(|ck| -ck.dot(up));
        if c0 < -margin || c2 < -margin || c0.is_nan() || c1.is_nan() || c2.is_nan() {
            return Validity::Inverted;
        }
        if c0 <= margin || c2 <= margin {
            return wedge_validity_exact(p, given);
        }
        if c1 <= margin {
            // the quadratic's minimum may be inside: positive iff c1² < c0·c2
            let (sq, prod) = (c1 * c1, c0 * c2);
            let big = c0.abs().max(c1.abs()).max(c2.abs());
            if (sq - prod).abs() <= 4.0 * margin * big + 1e-14 * big * big {
                return wedge_validity_exact(p, given);
            }
            if c1 <= 0.0 && sq >= prod {
                return Validity::Inverted;
            }
            undecided |= !sq.is_finite() || !prod.is_finite();
        }
    }
    if undecided {
        Validity::Undecided
    } else {
        Validity::Valid
    }
}

/// [`wedge_validity`] on the exact values of the doubles as given (`p` times a power of
/// two, or `given`; as [`bernstein`]'s exact validity chooses): on each vertical edge
/// `det J` is the quadratic of Bernstein coefficients `c₀ = −(a₀ × b₀)·u`,
/// `c₁ = −½(a₀ × b₁ + a₁ × b₀)·u`, `c₂ = −(a₁ × b₁)·u` (`a`, `b` the triangles' edges, `u`
/// the vertical edge), positive on [0, 1] iff `c₀ > 0`, `c₂ > 0` and `c₁ > 0` or
/// `c₁² < c₀c₂`.
fn wedge_validity_exact(p: &[DVec3], given: &[DVec3]) -> Validity {
    use crate::numeric::{dyadic::Dyadic, exact::{expansions_suffice_for, Expansion}};
    // c₁² − c₀c₂: products of six differences
    if expansions_suffice_for(given, p, 6) {
        wedge_validity_in::<Expansion>(p)
    } else {
        wedge_validity_in::<Dyadic>(given)
    }
}

/// [`wedge_validity_exact`] in the exact numbers of `N`.
fn wedge_validity_in<N: crate::numeric::exact::Exact>(p: &[DVec3]) -> Validity {
    use crate::numeric::exact::{det3_exact, exact_difference};
    use std::cmp::Ordering;
    let edge = |b: DVec3, a: DVec3| exact_difference::<N>(b, a);
    let (a0, a1, b0, b1) = (edge(p[1], p[0]), edge(p[4], p[3]), edge(p[2], p[0]), edge(p[5], p[3]));
    for i in 0..3 {
        let up = || edge(p[i + 3], p[i]);
        // −(a × b)·u = −u·(a × b) = u·(b × a)
        let c0 = det3_exact(up(), b0.clone(), a0.clone());
        let c2 = det3_exact(up(), b1.clone(), a1.clone());
        let mut c1 = det3_exact(up(), b1.clone(), a0.clone());
        c1.add(&det3_exact(up(), b0.clone(), a1.clone()));
        let c1 = c1.scaled(0.5);
        if c0.sign() != Ordering::Greater || c2.sign() != Ordering::Greater {
            return Validity::Inverted;
        }
        if c1.sign() != Ordering::Greater {
            let mut d = c0.times(&c2);
            d.add(&c1.times(&c1).negated());
            if d.sign() != Ordering::Greater {
                return Validity::Inverted;
            }
        }
    }
    Validity::Valid
}

/// Whether the element of `kind` with corners `p` (its first [`VolumeKind::corners`]
/// nodes) is valid everywhere, for certain (see the module docs).
pub fn validity(kind: VolumeKind, p: &[DVec3]) -> Validity {
    let (q, _) = in_unit_scale(&p[..kind.corners()]);
    match kind.linear() {
        VolumeKind::Tet4 => {
            if q3::is_inverted(&[q[0], q[1], q[2], q[3]]) {
                Validity::Inverted
            } else {
                Validity::Valid
            }
        }
        VolumeKind::Wedge6 => wedge_validity(&q, p),
        VolumeKind::Hex8 | VolumeKind::Pyramid5 => {
            let det = if kind.linear() == VolumeKind::Hex8 { hex_det(&q[..8]) } else { pyramid_det(&q[..5]) };
            decided(kind, &q[..kind.corners()], &p[..kind.corners()], &det, det.min_coefficient_unsigned())
        }
        VolumeKind::Tet10 | VolumeKind::Hex20 | VolumeKind::Hex27 => unreachable!("linear() is linear"),
    }
}

/// The validity of a hexahedron or pyramid with corners `p` (in unit scale; `given` as
/// given) from its `det J`'s rounded Bernstein form `det` (least coefficient `least`) where
/// that decides beyond rounding, else from the exact one of the corners as given (issue 61:
/// two hexahedra of smoothlab's outputs had `det J < 0` exactly, −1.2e−17 on a scale of 1,
/// yet counted as valid).
fn decided(kind: VolumeKind, p: &[DVec3], given: &[DVec3], det: &bernstein::Bezier, least: f64) -> Validity {
    det.validity_beyond(least, bernstein::rounding_margin(p)).unwrap_or_else(|| bernstein::exact_validity(kind, p, given))
}

/// The smallest Bernstein coefficient of the element's `det J` (its corners' determinants
/// for a tetrahedron or a wedge's three quadratics), in the element's units³: ≤ 0 when the
/// element is not certified by its first box; the validity guard's measure of how far an
/// element is folded.
pub fn min_det_coefficient(kind: VolumeKind, p: &[DVec3]) -> f64 {
    match kind.linear() {
        VolumeKind::Hex8 => hex_det(p).min_coefficient(),
        VolumeKind::Pyramid5 => pyramid_det(p).min_coefficient(),
        _ => (0..kind.row().corner_edges.len()).map(|c| corner_det(&corner_tet(kind, p, c))).fold(f64::INFINITY, f64::min),
    }
}
/// How far an element that is not certainly valid is folded, for the validity guard: 0
/// when [`Validity::Valid`], else `Σ max(0, −det)` over its measured corners plus
/// `max(0, −c_min)`, the smallest Bernstein coefficient of its Jacobian determinant (in
/// the element's units³), so a fold inside the element that its corners do not see
/// counts too.
pub fn solid_inversion(kind: VolumeKind, p: &[DVec3], validity: Validity) -> f64 {
    if validity == Validity::Valid {
        return 0.0;
    }
    let corners: f64 = (0..kind.row().corner_edges.len()).map(|c| (-corner_det(&corner_tet(kind, p, c))).max(0.0)).sum();
    corners + (-min_det_coefficient(kind, p)).max(0.0)
}
