//! The measures the drivers take of a star or one element at a trial position: its worst
//! shape and sine, and whether it is inverted.

use glam::DVec2;

use crate::objective::{Star, StarElement};
use crate::quality::{corner_edges, measure_element, TWO_SQRT3};

use super::*;

/// The worst measures of a star (or one element) at a position.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StarQuality {
    /// Smallest α (triangles) / β (quads).
    pub min_shape: f64,
    /// Smallest sine of a corner angle.
    pub min_sine: f64,
    /// Elements with a corner of `det ≤ 0`.
    pub inverted: u32,
}

impl StarQuality {
    /// Nothing measured yet: every minimum +∞, nothing inverted.
    pub const BEST: StarQuality = StarQuality { min_shape: f64::INFINITY, min_sine: f64::INFINITY, inverted: 0 };
    /// The measure `m` of these.
    pub fn measure(&self, m: Measure) -> f64 {
        match m {
            Measure::Shape => self.min_shape,
            Measure::MinSine => self.min_sine,
        }
    }
    fn merge(&mut self, o: StarQuality) {
        self.min_shape = self.min_shape.min(o.min_shape);
        self.min_sine = self.min_sine.min(o.min_sine);
        self.inverted += o.inverted;
    }
}

/// Shape, smallest sine and validity of one element from its node coordinates — the same
/// definitions as [`crate::quality::element_quality`] without the angles and condition
/// numbers the smoothers do not need.
pub(crate) fn element_measures(kind: crate::mesh::ElementKind, p: &[DVec2; 9]) -> StarQuality {
    let q = measure_element::<false, false, true>(kind, p, |_, _, _| {});
    StarQuality { min_shape: q.shape, min_sine: q.min_sine, inverted: q.inverted as u32 }
}

/// The shape measure (α/β, [`Measure::Shape`]) of a star element with its free node at `x`
/// and whether the element is inverted: what [`element_measures`] gives for them, without
/// the sines. A linear triangle is measured from its three points directly (one cross
/// product: its corners share one determinant), the common case of the smart Laplacian and
/// the priority order, scaled by a power of two when its squared edge lengths would leave
/// the doubles (so the same at every scale); elements of other kinds by
/// [`element_measures`].
#[inline]
pub(crate) fn element_shape_at(e: &StarElement, x: DVec2) -> (f64, bool) {
    if e.kind == crate::mesh::ElementKind::Tri3 {
        let s = e.slot as usize;
        if let Some(q) = triangle_shape_at(e.pts[(s + 1) % 3], e.pts[(s + 2) % 3], x) {
            return q;
        }
    }
    let q = element_measures(e.kind, &e.at(x));
    (q.min_shape, q.inverted > 0)
}

/// The sums of squared edge lengths for which [`triangle_shape_at`] takes its plain
/// formula (2.4e-271, about 2^-899, to 2^900): within it the cross product and the
/// quotient are normal doubles.
const PLAIN_SQUARES: std::ops::RangeInclusive<f64> = 2.409_919_865_102_884e-271..=8.452_712_498_170_644e270;

/// Lo's α of the linear triangle (x, a, b) (the free node at `x`, then the element's next
/// two corners in order) and whether it is inverted, from its three points directly (one
/// cross product: the corners share one determinant), scaled by a power of two when its
/// squared edge lengths would leave the doubles (so the same at every scale); `None` where
/// even that does not bring them back (the general path of [`element_shape_at`] decides).
#[inline(always)]
pub(crate) fn triangle_shape_at(a: DVec2, b: DVec2, x: DVec2) -> Option<(f64, bool)> {
    let (mut u, mut v, mut w) = (a - x, b - x, b - a);
    let squares = |u: DVec2, v: DVec2, w: DVec2| u.length_squared() + v.length_squared() + w.length_squared();
    if u == DVec2::ZERO && v == DVec2::ZERO {
        return Some((0.0, true)); // three coincident points: α 0, as lo_alpha_corner; det 0: inverted
    }
    let mut d = squares(u, v, w);
    if !PLAIN_SQUARES.contains(&d) {
        // the squares leave the doubles: the same formula on the points scaled by a
        // power of two (exact, and before subtracting: differences of tiny coordinates
        // can be subnormal), so α is the same, bit for bit, at every scale
        let m = u.abs().max_element().max(v.abs().max_element()).max(w.abs().max_element());
        if let Some(f) = crate::numeric::unit_factor(m) {
            let (a, b, x) = (f * a, f * b, f * x);
            (u, v, w) = (a - x, b - x, b - a);
            d = squares(u, v, w);
        }
    }
    if PLAIN_SQUARES.contains(&d) {
        let n = u.perp_dot(v);
        return Some((TWO_SQRT3 * n / d, n <= 0.0));
    }
    None
}

/// [`triangle_shape_at`] of one triangle at two positions `x` and `y` of its free corner,
/// the two divisions in the lanes of one vector division (IEEE quotients, so the same bits
/// as two scalar ones): the smart Laplacian's test of a linear triangle before and after.
/// The scalar function decides where either position needs more than the plain formula.
#[inline]
pub(crate) fn triangle_shape_at_both(a: DVec2, b: DVec2, x: DVec2, y: DVec2) -> Option<((f64, bool), (f64, bool))> {
    let (u0, v0, u1, v1, w) = (a - x, b - x, a - y, b - y, b - a);
    let squares = |u: DVec2, v: DVec2| u.length_squared() + v.length_squared() + w.length_squared();
    let (d0, d1) = (squares(u0, v0), squares(u1, v1));
    let plain = |u: DVec2, v: DVec2, d: f64| !(u == DVec2::ZERO && v == DVec2::ZERO) && PLAIN_SQUARES.contains(&d);
    if plain(u0, v0, d0) && plain(u1, v1, d1) {
        let (n0, n1) = (u0.perp_dot(v0), u1.perp_dot(v1));
        let q = DVec2::new(TWO_SQRT3 * n0, TWO_SQRT3 * n1) / DVec2::new(d0, d1);
        return Some(((q.x, n0 <= 0.0), (q.y, n1 <= 0.0)));
    }
    Some((triangle_shape_at(a, b, x)?, triangle_shape_at(a, b, y)?))
}

/// The smallest shape measure (α/β) of the star with its free node at `x` and the number
/// of its inverted elements ([`element_shape_at`] over the star).
pub(crate) fn star_shape(star: &Star, x: DVec2) -> (f64, u32) {
    let (mut min, mut inverted) = (f64::INFINITY, 0);
    for e in &star.elems {
        let (q, inv) = element_shape_at(e, x);
        min = min.min(q);
        inverted += inv as u32;
    }
    (min, inverted)
}

/// The star's worst measures with the free node at its gathered position (`x = None`,
/// the mesh as it is) or moved to `x` (mid-side nodes following).
pub(crate) fn star_quality(star: &Star, x: Option<DVec2>) -> StarQuality {
    let mut q = StarQuality::BEST;
    for e in &star.elems {
        q.merge(element_measures(e.kind, &at(e, x)));
    }
    q
}

pub(super) fn at(e: &StarElement, x: Option<DVec2>) -> [DVec2; 9] {
    match x {
        Some(x) => e.at(x),
        None => e.pts,
    }
}

/// Whether an element has a corner with `det ≤ 0` (the definition of
/// [`crate::quality::ElementQuality::inverted`]).
pub(crate) fn is_inverted(kind: crate::mesh::ElementKind, p: &[DVec2; 9]) -> bool {
    let linear = match kind {
        crate::mesh::ElementKind::Tri3 => linear_is_inverted::<3>(p),
        crate::mesh::ElementKind::Quad4 => linear_is_inverted::<4>(p),
        _ => None,
    };
    linear.unwrap_or_else(|| corner_edges(kind, p)[..kind.corners()].iter().any(|(e1, e2)| e1.perp_dot(*e2) <= 0.0))
}

/// [`is_inverted`] of element `e` of `mesh`: a linear triangle or quadrilateral from its
/// corners read straight from the mesh, where the general path copies the element's nine
/// points (the same vectors, so the same answer). The whole-mesh scans for inverted
/// elements (the untangling objectives' test, the untangling sweeps) ask it of every
/// element.
pub(crate) fn mesh_element_is_inverted(mesh: &crate::mesh::Mesh, e: usize) -> bool {
    let (kind, ids, nodes) = (mesh.kind(e), mesh.element(e), mesh.nodes());
    let linear = match kind {
        crate::mesh::ElementKind::Tri3 => linear_is_inverted::<3>(&std::array::from_fn::<_, 3, _>(|i| nodes[ids[i] as usize])),
        crate::mesh::ElementKind::Quad4 => linear_is_inverted::<4>(&std::array::from_fn::<_, 4, _>(|i| nodes[ids[i] as usize])),
        _ => None,
    };
    linear.unwrap_or_else(|| is_inverted(kind, &mesh.element_points_array(e)))
}

/// [`is_inverted`] of a linear element of `K` corners (the first `K` of `p`): corner_edges'
/// raw vectors and range test written out (the same vectors, so the same answer); `None`
/// beyond the range, where the general path decides.
#[inline(always)]
fn linear_is_inverted<const K: usize>(p: &[DVec2]) -> Option<bool> {
    let e: [(DVec2, DVec2); K] = std::array::from_fn(|i| (p[(i + 1) % K] - p[i], p[(i + K - 1) % K] - p[i]));
    let m = crate::numeric::largest_component(e.iter().flat_map(|(u, v)| [*u, *v]));
    crate::numeric::SAFE_SCALE.contains(&m).then(|| e.iter().any(|(u, v)| u.perp_dot(*v) <= 0.0))
}

/// [`is_inverted`] of a star element with its free node at `x`; a linear triangle without
/// the general element machinery (the same corner edge vectors, so the same answer).
pub(super) fn is_inverted_at(el: &crate::objective::StarElement, x: DVec2) -> bool {
    if el.kind == crate::mesh::ElementKind::Quad4 {
        // without copying the element's 9 points
        let mut p = [el.pts[0], el.pts[1], el.pts[2], el.pts[3]];
        p[el.slot as usize] = x;
        return linear_is_inverted::<4>(&p).unwrap_or_else(|| is_inverted(el.kind, &el.at(x)));
    }
    if el.kind != crate::mesh::ElementKind::Tri3 {
        return is_inverted(el.kind, &el.at(x));
    }
    let s = el.slot as usize;
    let (a, b) = (el.pts[(s + 1) % 3], el.pts[(s + 2) % 3]);
    // corners C (free), A, B: (next − this, previous − this)
    (a - x).perp_dot(b - x) <= 0.0 || (b - a).perp_dot(x - a) <= 0.0 || (x - b).perp_dot(a - b) <= 0.0
}
