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
//! Jacobians (`tet::tet10_measures`), a 20- or 27-node hexahedron by its corners' trilinear
//! hexahedron (exact when its edges are straight).

use glam::DVec3;

use super::tet::{self as q3, CornerReference};
use crate::mesh::VolumeKind;

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
/// they are when the edges' largest component lies within the safe scale, else moved to
/// the first corner and multiplied by a power of two (exact), so signs and ratios are the
/// same at every scale.
fn in_unit_scale(p: &[DVec3]) -> ([DVec3; 8], usize) {
    let mut q = [DVec3::ZERO; 8];
    let n = p.len().min(8);
    match crate::numeric::factors_beyond_safe_scale(reach(&p[..n])) {
        None => q[..n].copy_from_slice(&p[..n]),
        Some((f1, f2)) => {
            for i in 0..n {
                q[i] = (p[i] - p[0]) * f1 * f2;
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

/// A polynomial of degree ≤ 2 in each of three parameters on a box, by its 3×3×3
/// Bernstein coefficients (`deg[k]` 0 where it does not depend on parameter `k`).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Bezier {
    c: [[[f64; 3]; 3]; 3],
    deg: [usize; 3],
}

impl Bezier {
    fn min_coefficient(&self) -> f64 {
        if self.deg == [2, 2, 2] {
            // a hexahedron's: all 27, in the loop's order
            return self.c.as_flattened().as_flattened().iter().fold(f64::INFINITY, |m, &v| m.min(v));
        }
        let mut m = f64::INFINITY;
        for i in 0..=self.deg[0] {
            for j in 0..=self.deg[1] {
                for k in 0..=self.deg[2] {
                    m = m.min(self.c[i][j][k]);
                }
            }
        }
        m
    }
    /// [`min_coefficient`](Self::min_coefficient) of a hexahedron's 27 in four running
    /// minima rather than one chain of 27 (their latency, where the validity guard makes a
    /// ball at every visit): the same least value, not-a-number coefficients skipped as the
    /// fold skips them, but for the sign of a zero, which a comparison with zero and the
    /// ball's radius do not see.
    #[inline]
    fn min_coefficient_unsigned(&self) -> f64 {
        if self.deg != [2, 2, 2] {
            return self.min_coefficient();
        }
        let c = self.c.as_flattened().as_flattened();
        let mut m = [f64::INFINITY; 4];
        for run in c.chunks(4) {
            for (m, &v) in m.iter_mut().zip(run) {
                *m = m.min(v);
            }
        }
        m[0].min(m[1]).min(m[2].min(m[3]))
    }
    /// The smallest of its values at the box's corners (its corner coefficients).
    fn min_corner(&self) -> f64 {
        let mut m = f64::INFINITY;
        for i in [0, self.deg[0]] {
            for j in [0, self.deg[1]] {
                for k in [0, self.deg[2]] {
                    m = m.min(self.c[i][j][k]);
                }
            }
        }
        m
    }
    /// The two halves along parameter `axis` (de Casteljau at ½).
    fn split(&self, axis: usize) -> (Bezier, Bezier) {
        let (mut lo, mut hi) = (*self, *self);
        let at = |c: &[[[f64; 3]; 3]; 3], t: usize, a: usize, b: usize| match axis {
            0 => c[t][a][b],
            1 => c[a][t][b],
            _ => c[a][b][t],
        };
        let (na, nb) = match axis {
            0 => (self.deg[1], self.deg[2]),
            1 => (self.deg[0], self.deg[2]),
            _ => (self.deg[0], self.deg[1]),
        };
        for a in 0..=na {
            for b in 0..=nb {
                let (b0, b1, b2) = (at(&self.c, 0, a, b), at(&self.c, 1, a, b), at(&self.c, 2, a, b));
                let (l1, r1) = (0.5 * (b0 + b1), 0.5 * (b1 + b2));
                let m = 0.5 * (l1 + r1);
                let set = |c: &mut [[[f64; 3]; 3]; 3], t: usize, v: f64| match axis {
                    0 => c[t][a][b] = v,
                    1 => c[a][t][b] = v,
                    _ => c[a][b][t] = v,
                };
                set(&mut lo.c, 1, l1);
                set(&mut lo.c, 2, m);
                set(&mut hi.c, 0, m);
                set(&mut hi.c, 1, r1);
            }
        }
        (lo, hi)
    }

    /// Decides the sign of the polynomial on the box: positive everywhere, ≤ 0 somewhere,
    /// or not decided within [`MAX_BOXES`] boxes.
    fn validity(&self) -> Validity {
        self.validity_with_least(self.min_coefficient_unsigned())
    }
    /// [`validity`](Self::validity) with its least coefficient `least` taken
    /// ([`min_coefficient_unsigned`](Self::min_coefficient_unsigned)), for a caller that
    /// reads it too.
    fn validity_with_least(&self, least: f64) -> Validity {
        // the first box decides most elements: without the subdivision's stack
        let corner = self.min_corner();
        if corner <= 0.0 || corner.is_nan() {
            return Validity::Inverted;
        }
        if least > 0.0 {
            return Validity::Valid;
        }
        let axes: Vec<usize> = (0..3).filter(|&k| self.deg[k] == 2).collect();
        let mut stack = vec![(*self, 0usize)];
        let mut boxes = 0;
        while let Some((b, depth)) = stack.pop() {
            boxes += 1;
            if b.min_corner() <= 0.0 || b.min_corner().is_nan() {
                return Validity::Inverted;
            }
            if b.min_coefficient() > 0.0 {
                continue;
            }
            if boxes >= MAX_BOXES || axes.is_empty() {
                return Validity::Undecided;
            }
            let (lo, hi) = b.split(axes[depth % axes.len()]);
            stack.push((hi, depth + 1));
            stack.push((lo, depth + 1));
        }
        Validity::Valid
    }
}

/// The Bernstein coefficients of `f·(g × h)` over a box, `f`, `g`, `h` vector polynomials
/// by their coefficients of degrees `df`, `dg`, `dh` ≤ 1 in each parameter (the products'
/// degrees ≤ 2). The product of Bernstein polynomials of degrees `m₁ + m₂ + m₃ = n` along a
/// parameter has the weight `C(m₁, i₁)·C(m₂, i₂)·C(m₃, i₃)/C(n, i)` at index `i = i₁ + i₂ +
/// i₃`: with every `m ≤ 1` the numerator is 1, so the weight is ½ at the middle index of
/// degree 2 and 1 elsewhere (powers of two: exact). Which coefficients take part, where
/// each product lands and its weight depend on the degrees alone: a [`TripleProduct`]
/// worked out when compiling, so the loops here have known lengths and indices.
struct TripleProduct {
    deg: [usize; 3],
    /// Each factor's coefficients `(i, j, k)` in [`indices`]' order (the first `n`), with
    /// their flat indices `9i + 3j + k`.
    f: Terms,
    g: Terms,
    h: Terms,
    /// The weight at each flat index of the product.
    weight: [f64; 27],
}

/// A factor's coefficients of degrees `d` ≤ 1: `(i, j, k)` and `9i + 3j + k` each, and how
/// many.
type Terms = ([([usize; 3], usize); 8], usize);

/// A factor of a [`TripleProduct`]: a vector polynomial by its coefficients of degree ≤ 1
/// in each parameter.
type Factor = [[[DVec3; 2]; 2]; 2];

impl TripleProduct {
    const fn new(df: [usize; 3], dg: [usize; 3], dh: [usize; 3]) -> Self {
        let deg = [df[0] + dg[0] + dh[0], df[1] + dg[1] + dh[1], df[2] + dg[2] + dh[2]];
        let mut weight = [1.0; 27];
        let mut n = 0;
        while n < 27 {
            let (s, mut halves, mut k) = ([n / 9, n / 3 % 3, n % 3], 0, 0);
            while k < 3 {
                halves += (deg[k] == 2 && s[k] == 1) as usize;
                k += 1;
            }
            weight[n] = [1.0, 0.5, 0.25, 0.125][halves];
            n += 1;
        }
        TripleProduct { deg, f: Self::terms(df), g: Self::terms(dg), h: Self::terms(dh), weight }
    }

    const fn terms(d: [usize; 3]) -> Terms {
        let mut out = ([([0; 3], 0); 8], 0);
        let mut i = 0;
        while i <= d[0] {
            let mut j = 0;
            while j <= d[1] {
                let mut k = 0;
                while k <= d[2] {
                    out.0[out.1] = ([i, j, k], 9 * i + 3 * j + k);
                    out.1 += 1;
                    k += 1;
                }
                j += 1;
            }
            i += 1;
        }
        out
    }

    /// The coefficients of `f·(g × h)`: the cross products `g × h` taken once each and the
    /// coefficients summed in the order of `f`, `g`, `h`.
    #[inline(always)]
    fn of(&self, f: &Factor, g: &Factor, h: &Factor) -> Bezier {
        let value = |v: &Factor, t: &Terms, a: usize| {
            let [i, j, k] = t.0[a].0;
            v[i][j][k]
        };
        let mut cross = [[DVec3::ZERO; 8]; 8];
        for (a, row) in cross.iter_mut().enumerate().take(self.g.1) {
            for (b, x) in row.iter_mut().enumerate().take(self.h.1) {
                *x = value(g, &self.g, a).cross(value(h, &self.h, b));
            }
        }
        let mut c = [0.0; 27];
        for a in 0..self.f.1 {
            let fv = value(f, &self.f, a);
            for (b, row) in cross.iter().enumerate().take(self.g.1) {
                for (d, x) in row.iter().enumerate().take(self.h.1) {
                    let n = self.f.0[a].1 + self.g.0[b].1 + self.h.0[d].1;
                    c[n] += self.weight[n] * fv.dot(*x);
                }
            }
        }
        let mut out = Bezier { c: [[[0.0; 3]; 3]; 3], deg: self.deg };
        for (n, v) in c.into_iter().enumerate() {
            out.c[n / 9][n / 3 % 3][n % 3] = v;
        }
        out
    }

    /// The gradients of the coefficients of `f·(g × h)` (at flat indices) in a point that
    /// moves one coefficient of each factor, `moved[0]` of `f` and so on: its index in
    /// the factor's [`Terms`] and its sign (the point is an edge's head, +1, or its tail,
    /// −1). A product of three terms is affine in the point (`x·(x × v) = 0`), with the
    /// gradient `σ_f (g × h) + σ_g (h × f) + σ_h (f × g)`.
    #[inline(always)]
    fn slopes(&self, f: &Factor, g: &Factor, h: &Factor, moved: [(usize, f64); 3]) -> [DVec3; 27] {
        let value = |v: &Factor, t: &Terms, a: usize| {
            let [i, j, k] = t.0[a].0;
            v[i][j][k]
        };
        let mut s = [DVec3::ZERO; 27];
        let (a, sign) = moved[0];
        for b in 0..self.g.1 {
            for d in 0..self.h.1 {
                let n = self.f.0[a].1 + self.g.0[b].1 + self.h.0[d].1;
                s[n] += value(g, &self.g, b).cross(value(h, &self.h, d)) * (sign * self.weight[n]);
            }
        }
        let (b, sign) = moved[1];
        for a in 0..self.f.1 {
            for d in 0..self.h.1 {
                let n = self.f.0[a].1 + self.g.0[b].1 + self.h.0[d].1;
                s[n] += value(h, &self.h, d).cross(value(f, &self.f, a)) * (sign * self.weight[n]);
            }
        }
        let (d, sign) = moved[2];
        for a in 0..self.f.1 {
            for b in 0..self.g.1 {
                let n = self.f.0[a].1 + self.g.0[b].1 + self.h.0[d].1;
                s[n] += value(f, &self.f, a).cross(value(g, &self.g, b)) * (sign * self.weight[n]);
            }
        }
        s
    }
}

fn indices(d: [usize; 3]) -> impl Iterator<Item = (usize, usize, usize)> {
    (0..=d[0]).flat_map(move |i| (0..=d[1]).flat_map(move |j| (0..=d[2]).map(move |k| (i, j, k))))
}

/// A trilinear hexahedron's `det J` (corners in VTK's order, parameters u, v, w along
/// edges 0→1, 0→3, 0→4) in the Bernstein basis.
fn hex_det(p: &[DVec3]) -> Bezier {
    let (xu, xv, xw) = hex_columns(p);
    HEX.of(&xu, &xv, &xw)
}

/// [`hex_det`]'s plan: `X_u·(X_v × X_w)`, each column constant along its own parameter.
const HEX: TripleProduct = TripleProduct::new([0, 1, 1], [1, 0, 1], [1, 1, 0]);

/// A trilinear hexahedron's columns `X_u`, `X_v`, `X_w`, each by its coefficients: the
/// element's edges along u, v and w.
#[inline(always)]
fn hex_columns(p: &[DVec3]) -> (Factor, Factor, Factor) {
    // the corner at (i, j, k) ∈ {0, 1}³
    let at = |i: usize, j: usize, k: usize| p[4 * k + HEX_CORNER[i][j]];
    let z = [[[DVec3::ZERO; 2]; 2]; 2];
    let (mut xu, mut xv, mut xw) = (z, z, z);
    for a in 0..2 {
        for b in 0..2 {
            xu[0][a][b] = at(1, a, b) - at(0, a, b);
            xv[a][0][b] = at(a, 1, b) - at(a, 0, b);
            xw[a][b][0] = at(a, b, 1) - at(a, b, 0);
        }
    }
    (xu, xv, xw)
}

/// The hexahedron's corner at `(i, j, k)` ∈ {0, 1}³ is corner `4k + HEX_CORNER[i][j]`.
const HEX_CORNER: [[usize; 2]; 2] = [[0, 3], [1, 2]];

/// [`hex_det`] with its coefficients' gradients in corner `slot` (at flat indices).
fn hex_det_and_slopes(p: &[DVec3], slot: usize) -> (Bezier, [DVec3; 27]) {
    let (xu, xv, xw) = hex_columns(p);
    let (i, j, k) = ((slot % 4 == 1 || slot % 4 == 2) as usize, (slot % 4 >= 2) as usize, slot / 4);
    let sign = |end: usize| if end == 1 { 1.0 } else { -1.0 };
    // each column's moving edge: its index in the plan's terms (flat 9i + 3j + k order
    // over the column's own degrees: the two parameters it varies along)
    let moved = [(2 * j + k, sign(i)), (2 * i + k, sign(j)), (2 * i + j, sign(k))];
    (HEX.of(&xu, &xv, &xw), HEX.slopes(&xu, &xv, &xw, moved))
}

/// A pyramid's `g(u, v) = B_u·(B_v × (apex − B))` (see the module docs) in the Bernstein
/// basis.
fn pyramid_det(p: &[DVec3]) -> Bezier {
    let base = |i: usize, j: usize| p[HEX_CORNER[i][j]];
    let z = [[[DVec3::ZERO; 2]; 2]; 2];
    let (mut bu, mut bv, mut to_apex) = (z, z, z);
    for a in 0..2 {
        bu[0][a][0] = base(1, a) - base(0, a);
        bv[a][0][0] = base(a, 1) - base(a, 0);
        for (b, t) in to_apex[a].iter_mut().enumerate() {
            t[0] = p[4] - base(a, b);
        }
    }
    const PYRAMID: TripleProduct = TripleProduct::new([0, 1, 0], [1, 0, 0], [1, 1, 0]);
    PYRAMID.of(&bu, &bv, &to_apex)
}

/// A wedge's validity, exact (see the module docs).
fn wedge_validity(p: &[DVec3]) -> Validity {
    // VTK's wedge: the triangle 0 1 2 turns clockwise seen from 3 4 5 above it, so
    // det J = −(∂ξ × ∂η)·∂ζ
    let e1 = [p[1] - p[0], p[4] - p[3]];
    let e2 = [p[2] - p[0], p[5] - p[3]];
    let c = [e1[0].cross(e2[0]), 0.5 * (e1[0].cross(e2[1]) + e1[1].cross(e2[0])), e1[1].cross(e2[1])];
    let mut undecided = false;
    for i in 0..3 {
        let up = p[i + 3] - p[i];
        let [c0, c1, c2] = c.map(|ck| -ck.dot(up));
        if c0 <= 0.0 || c2 <= 0.0 || c0.is_nan() || c1.is_nan() || c2.is_nan() {
            return Validity::Inverted;
        }
        if c1 <= 0.0 {
            // the quadratic's minimum is inside: positive iff c1² < c0·c2
            let (sq, prod) = (c1 * c1, c0 * c2);
            if sq >= prod {
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

/// A hexahedron's or pyramid's `det J` in the Bernstein basis as a function of one
/// corner's position `x`, the others fixed, for the validity guard's trials: every
/// coefficient is a sum of triple products of vectors affine in `x`, and a triple product
/// is affine in a vector that two of its factors share (`x·(x×h) = 0`), so each
/// coefficient is `c₀ + g·(x − o)`. A hexahedron's slopes `g` are the triple products'
/// gradients (`TripleProduct::slopes`); a pyramid's are read off the coefficients one
/// edge length `m` along each axis (exact but for rounding, an affine function's
/// differences).
/// [`validity_at`](Self::validity_at) decides only where every coefficient it reads is
/// beyond rounding of 0, and leaves the rest to [`validity`], so its answers are
/// [`validity`]'s.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DetForm {
    origin: DVec3,
    /// The largest component of an edge from corner 0 when formed: the unit of rounding.
    reach: f64,
    /// The coefficients of the polynomial's degrees, in [`indices`]' order: the first
    /// `len` of `c` and `g`.
    c: [f64; 27],
    g: [DVec3; 27],
    len: usize,
    /// Which of them are the box's corners (bit `t` for the `t`-th).
    corners: u32,
}

impl DetForm {
    /// The form of the element of `kind` with corners `p`, its corner `slot` free; `None`
    /// for kinds decided without Bernstein coefficients (tetrahedra, wedges) and for an
    /// element beyond the safe scale, which [`validity`] measures in its own scale.
    pub fn of(kind: VolumeKind, p: &[DVec3], slot: usize) -> Option<DetForm> {
        let det: fn(&[DVec3]) -> Bezier = match kind.linear() {
            VolumeKind::Hex8 => hex_det,
            VolumeKind::Pyramid5 => pyramid_det,
            _ => return None,
        };
        let n = kind.corners();
        let reach = reach(&p[..n]);
        if reach == 0.0 || !reach.is_finite() || crate::numeric::factors_beyond_safe_scale(reach).is_some() {
            return None;
        }
        let mut q = [DVec3::ZERO; 8];
        q[..n].copy_from_slice(&p[..n]);
        // a hexahedron's slopes analytic; a pyramid's (whose apex is in four of its
        // factor's coefficients) by differences, exact for an affine function up to rounding
        let (c, slopes) = if kind.linear() == VolumeKind::Hex8 {
            hex_det_and_slopes(&q, slot)
        } else {
            let c = det(&q);
            let moved = [0, 1, 2].map(|axis| {
                let mut m = q;
                m[slot][axis] += reach;
                det(&m)
            });
            let mut slopes = [DVec3::ZERO; 27];
            for (n, s) in slopes.iter_mut().enumerate() {
                let (i, j, k) = (n / 9, n / 3 % 3, n % 3);
                let slope = |axis: usize| (moved[axis].c[i][j][k] - c.c[i][j][k]) / reach;
                *s = DVec3::new(slope(0), slope(1), slope(2));
            }
            (c, slopes)
        };
        let deg = c.deg;
        let mut form = DetForm { origin: p[slot], reach, c: [0.0; 27], g: [DVec3::ZERO; 27], len: 0, corners: 0 };
        for (t, (i, j, k)) in indices(deg).enumerate() {
            form.c[t] = c.c[i][j][k];
            form.g[t] = slopes[9 * i + 3 * j + k];
            let corner = (i == 0 || i == deg[0]) && (j == 0 || j == deg[1]) && (k == 0 || k == deg[2]);
            form.corners |= (corner as u32) << t;
            form.len = t + 1;
        }
        Some(form)
    }

    /// [`validity`] of the element with the free corner at `x` where its coefficients
    /// there decide it beyond rounding; `None` where [`validity`] must.
    #[inline]
    pub fn validity_at(&self, x: DVec3) -> Option<Validity> {
        let u = x - self.origin;
        let r = self.reach + u.abs().max_element();
        // every coefficient is a sum of a few triple products of edges within 2r: its
        // rounding is some 10⁻¹² r³, so 10⁻⁹ r³ is beyond any
        let margin = 1e-9 * r * r * r;
        if !(margin > 0.0 && margin.is_finite()) {
            return None;
        }
        let (mut min, mut min_corner) = (f64::INFINITY, f64::INFINITY);
        for (t, (&c, g)) in self.c[..self.len].iter().zip(&self.g[..self.len]).enumerate() {
            let v = c + g.dot(u);
            if v.is_nan() {
                return None;
            }
            min = min.min(v);
            if self.corners >> t & 1 == 1 {
                min_corner = min_corner.min(v);
            }
        }
        if min_corner < -margin {
            Some(Validity::Inverted)
        } else if min > margin {
            Some(Validity::Valid)
        } else {
            None
        }
    }
}

/// A ball of positions of a hexahedron's free corner in which the element is valid for
/// certain, from its `det J` where the corner is, without the coefficients at the
/// position asked: each Bernstein coefficient `c_t` is affine in the corner ([`DetForm`]),
/// a sum of triple products of the element's edges whose weights add up to 1 (those of the
/// product of Bernstein polynomials), and a triple product's gradient in one corner is at
/// most the sum of the products of its factors' lengths two by two, so `|∇c_t| ≤ 3E²`
/// with `E` the longest edge. Within `ρ` of the corner every coefficient is at least
/// `m − 3E²ρ`, `m` the smallest there; the radius is half of where that bound reaches 0,
/// kept only where the bound stays beyond twice the form's rounding margin, so a position
/// it holds is one the form or the exact test would call valid too.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ValidBall {
    centre: DVec3,
    radius_squared: f64,
}

impl ValidBall {
    /// The ball of the hexahedron (8, 20 or 27 nodes: its corners' trilinear map) with
    /// corners `p`, its corner `slot` free; `None` for other kinds, an element not valid
    /// beyond rounding where it is, and an element beyond the safe scale.
    pub fn of(kind: VolumeKind, p: &[DVec3], slot: usize) -> Option<ValidBall> {
        let (p, reach) = Self::corners_and_reach(kind, p)?;
        Self::of_least_coefficient(p, slot, reach, hex_det(p).min_coefficient_unsigned())
    }

    /// [`validity`] of the hexahedron with corners `p` and its ball with free corner
    /// `slot` (as [`of`](Self::of)), from one taking of its coefficients: for the guard's
    /// first question that its memo does not answer, whose answer makes the element's first
    /// ball about the position asked, and its first beyond that ball, which makes a second
    /// (where the solve's later trials gather). The same validity as
    /// [`validity`]'s, which takes the same coefficients where the element is within the
    /// safe scale, as a ball asks.
    pub fn validity_and_ball(kind: VolumeKind, p: &[DVec3], slot: usize) -> (Validity, Option<ValidBall>) {
        let Some((corners, reach)) = Self::corners_and_reach(kind, p) else {
            return (validity(kind, p), None);
        };
        let det = hex_det(corners);
        let least = det.min_coefficient_unsigned();
        (det.validity_with_least(least), Self::of_least_coefficient(corners, slot, reach, least))
    }

    /// The corners and reach of an element a ball may be made for: a hexahedron (of any
    /// order, by its corners) of positive reach within the safe scale.
    #[inline]
    fn corners_and_reach(kind: VolumeKind, p: &[DVec3]) -> Option<(&[DVec3], f64)> {
        if kind.linear() != VolumeKind::Hex8 {
            return None;
        }
        let p = &p[..8];
        let reach = reach(p);
        (reach != 0.0 && reach.is_finite() && crate::numeric::factors_beyond_safe_scale(reach).is_none()).then_some((p, reach))
    }

    /// The ball from the least coefficient `m` of the hexahedron with corners `p` (within
    /// the safe scale, its reach `reach`).
    fn of_least_coefficient(p: &[DVec3], slot: usize, reach: f64, m: f64) -> Option<ValidBall> {
        // the twelve edges' squares in three running maxima (a maximum is exact)
        let mut longest = [0.0f64; 3];
        for i in 0..4 {
            for (l, (a, b)) in longest.iter_mut().zip([(i, (i + 1) % 4), (i + 4, (i + 1) % 4 + 4), (i, i + 4)]) {
                *l = l.max(p[a].distance_squared(p[b]));
            }
        }
        let longest = longest[0].max(longest[1]).max(longest[2]);
        // the gradients' bound, rounded up beyond its own rounding
        let slope = 3.0 * longest * (1.0 + 1e-9);
        let radius = 0.99 * m / slope;
        let margin = 1e-9 * (reach + radius).powi(3);
        (radius > 0.0 && radius.is_finite() && m - slope * radius > 2.0 * margin)
            .then(|| ValidBall { centre: p[slot], radius_squared: radius * radius })
    }

    /// Whether the element is valid with its free corner at `x` by the ball alone.
    #[inline]
    pub fn holds(&self, x: DVec3) -> bool {
        (x - self.centre).length_squared() < self.radius_squared
    }
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
        VolumeKind::Wedge6 => wedge_validity(&q),
        VolumeKind::Hex8 => hex_det(&q).validity(),
        VolumeKind::Pyramid5 => pyramid_det(&q).validity(),
        VolumeKind::Tet10 | VolumeKind::Hex20 | VolumeKind::Hex27 => unreachable!("linear() is linear"),
    }
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

/// The scaled Jacobian of a corner, `det T/(‖t₁‖·‖t₂‖·‖t₃‖)` with `T = A·W⁻¹`: 1 at the
/// ideal corner, in [−1, 1], negative when inverted (the 3D sine of a corner: the volume of
/// the parallelepiped of its unit weighted edges). 0 for a degenerate corner.
pub fn scaled_jacobian(p: &[DVec3; 4], r: &CornerReference) -> f64 {
    let t = q3::WeightedJacobian::of(&q3::in_unit_scale(p), r).t;
    let n = t.x_axis.length() * t.y_axis.length() * t.z_axis.length();
    if n == 0.0 || !n.is_finite() {
        return 0.0;
    }
    t.determinant() / n
}

/// [`scaled_jacobian`] with its gradient with respect to corner 0: with `s = W⁻ᵀ𝟙`, every
/// column `t_i` moves by `−s_i·dp0`, so `∇ln SJ = ∇σ/σ + Σ s_i·t_i/‖t_i‖²`.
pub fn scaled_jacobian_grad0(p: &[DVec3; 4], r: &CornerReference) -> (f64, DVec3) {
    let j = q3::WeightedJacobian::of(p, r);
    let cols = [j.t.x_axis, j.t.y_axis, j.t.z_axis];
    let l2 = cols.map(|c| c.length_squared());
    let n = (l2[0] * l2[1] * l2[2]).sqrt();
    if n == 0.0 || !n.is_finite() {
        return (0.0, DVec3::ZERO);
    }
    let sj = j.sigma / n;
    let s = r.w_inv_t_one;
    // ∇(σ/n) = ∇σ/n − σ/n·∇ln n, ∇ln n = Σ −s_i t_i/‖t_i‖²
    let grad_ln_n = -(s.x * cols[0] / l2[0] + s.y * cols[1] / l2[1] + s.z * cols[2] / l2[2]);
    (sj, j.grad_sigma / n - sj * grad_ln_n)
}

/// Every measure of one volume element, for statistics and the page.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolidMeasures {
    /// Not certainly valid ([`validity`]; a 10-node tetrahedron by its corners).
    pub inverted: bool,
    /// Valid at every measured corner, yet not valid inside (the case corner checks miss).
    pub inverted_inside: bool,
    pub min_dihedral_deg: f64,
    pub max_dihedral_deg: f64,
    /// The smallest sine of a dihedral angle (a tetrahedron, Freitag 1997) or scaled
    /// Jacobian of a corner (the other kinds: the 3D sine of a corner).
    pub min_sine: f64,
    /// Knupp's κ, the worst corner's.
    pub condition: f64,
    /// The mean ratio: a tetrahedron's; the other kinds' mean over their measured corners.
    pub mean_ratio: f64,
    /// The smallest scaled Jacobian of a measured corner ([`scaled_jacobian`]).
    pub scaled_jacobian: f64,
    /// The dihedral angles, degrees (the first [`dihedral_count`](Self::dihedral_count)):
    /// a tetrahedron's six; for the other kinds, at each measured corner, the angles of its
    /// tetrahedron at the corner's three edges (the element's dihedral angles there when
    /// its faces are flat).
    pub dihedral_deg: [f64; 24],
    pub dihedral_count: usize,
}

impl SolidMeasures {
    pub fn dihedral(&self) -> &[f64] {
        &self.dihedral_deg[..self.dihedral_count]
    }
}

/// The indices, in [`q3::dihedral_angles`]' order, of the dihedral angles at the edges
/// from corner 0 of a tetrahedron: (0,1), (0,2), (0,3).
const EDGES_AT_CORNER_0: [usize; 3] = {
    let mut out = [0; 3];
    let mut n = 0;
    let mut i = 0;
    while i < 6 {
        if q3::TET_EDGES[i][0] == 0 {
            out[n] = i;
            n += 1;
        }
        i += 1;
    }
    out
};

/// [`SolidMeasures`] of an element of `kind` with nodes `p` (all its nodes, in the kind's
/// order).
pub fn solid_measures(kind: VolumeKind, p: &[DVec3]) -> SolidMeasures {
    let r = kind.reference();
    let sj_min = |ts: &mut dyn Iterator<Item = [DVec3; 4]>, r: &CornerReference| ts.map(|t| scaled_jacobian(&t, r)).fold(f64::INFINITY, f64::min);
    match kind {
        VolumeKind::Tet4 | VolumeKind::Tet10 => {
            let m = match kind {
                VolumeKind::Tet4 => q3::tet_measures(&[p[0], p[1], p[2], p[3]], r),
                _ => q3::tet10_measures(&std::array::from_fn(|j| p[j]), r),
            };
            let corners = [p[0], p[1], p[2], p[3]];
            let sj = sj_min(&mut (0..4).map(|c| q3::with_first(&corners, c)), r);
            let mut dihedral_deg = [0.0; 24];
            dihedral_deg[..6].copy_from_slice(&m.dihedral_deg);
            SolidMeasures {
                inverted: m.inverted,
                inverted_inside: false,
                min_dihedral_deg: m.min_dihedral_deg,
                max_dihedral_deg: m.max_dihedral_deg,
                min_sine: m.min_sine,
                condition: m.condition,
                mean_ratio: m.mean_ratio,
                scaled_jacobian: sj,
                dihedral_deg,
                dihedral_count: 6,
            }
        }
        _ => {
            let (q, _) = in_unit_scale(&p[..kind.corners()]);
            let count = kind.row().corner_edges.len();
            let mut out = SolidMeasures {
                inverted: false,
                inverted_inside: false,
                min_dihedral_deg: f64::INFINITY,
                max_dihedral_deg: f64::NEG_INFINITY,
                min_sine: f64::INFINITY,
                condition: 0.0,
                mean_ratio: 0.0,
                scaled_jacobian: f64::INFINITY,
                dihedral_deg: [0.0; 24],
                dihedral_count: 3 * count,
            };
            let mut corner_inverted = false;
            for c in 0..count {
                let t = corner_tet(kind, &q, c);
                corner_inverted |= q3::is_inverted(&t);
                out.mean_ratio += q3::mean_ratio(&t, r) / count as f64;
                out.condition = out.condition.max(q3::condition_number(&t, r));
                out.scaled_jacobian = out.scaled_jacobian.min(scaled_jacobian(&t, r));
                let angles = q3::dihedral_angles(&t);
                for (k, &i) in EDGES_AT_CORNER_0.iter().enumerate() {
                    let a = angles[i].to_degrees();
                    out.dihedral_deg[3 * c + k] = a;
                    out.min_dihedral_deg = out.min_dihedral_deg.min(a);
                    out.max_dihedral_deg = out.max_dihedral_deg.max(a);
                }
            }
            out.min_sine = out.scaled_jacobian;
            out.inverted = corner_inverted || validity(kind, &q) != Validity::Valid;
            out.inverted_inside = out.inverted && !corner_inverted;
            out
        }
    }
}

/// The shape of an element that is not a tetrahedron, as the drivers read it (the smart
/// Laplacian, the priority order, the acceptance rule): the mean of its measured corners'
/// mean ratios (1 for the ideal element, falling through 0 as corners invert).
pub fn solid_shape(kind: VolumeKind, p: &[DVec3]) -> f64 {
    let (q, _) = in_unit_scale(p);
    let (r, count) = (kind.reference(), kind.row().corner_edges.len());
    (0..count).map(|c| q3::mean_ratio(&corner_tet(kind, &q, c), r)).sum::<f64>() / count as f64
}

/// [`solid_shape`]'s terms, its measured corners' mean ratios in corner order, for an
/// element within the safe scale as it is (where each is a function of its own corner's
/// tetrahedron alone, so a corner that did not move keeps its term); with each corner's
/// Jacobian determinant from the same Jacobian, for the size screen
/// ([`least_corner_det`](Self::least_corner_det)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CornerShapes {
    terms: [f64; 8],
    /// `det A` of each measured corner: its weighted Jacobian's `σ = det T` over `det W⁻¹`
    /// (`σ` itself where `W = I`, a hexahedron's), within rounding of [`least_corner_det`]'s
    /// determinant taken directly.
    dets: [f64; 8],
    /// The element's [`reach`].
    reach: f64,
}

impl CornerShapes {
    /// No terms, for room that holds none yet.
    pub const NONE: CornerShapes = CornerShapes { terms: [f64::NAN; 8], dets: [f64::NAN; 8], reach: f64::NAN };
    /// Overwrites these terms with `other`'s, field by field: a whole copy (some 140
    /// bytes) is put together on the stack and moved with calls to `memcpy`, where these
    /// are moves in place.
    #[inline(always)]
    pub fn copy_from(&mut self, other: &CornerShapes) {
        self.terms = other.terms;
        self.dets = other.dets;
        self.reach = other.reach;
    }
    /// The terms of the element of `kind` with corners `p`, each corner's (term,
    /// determinant) from `kept(c)` where it gives them (a corner whose tetrahedron is as it
    /// was), else measured; `None` for an element beyond the safe scale, which
    /// [`solid_shape`] measures in its own scale.
    pub fn of(kind: VolumeKind, p: &[DVec3], kept: impl Fn(usize) -> Option<(f64, f64)>) -> Option<CornerShapes> {
        let p = &p[..kind.corners()];
        let reach = reach(p);
        if crate::numeric::factors_beyond_safe_scale(reach).is_some() {
            return None;
        }
        let r = kind.reference();
        let (mut terms, mut dets) = ([0.0; 8], [0.0; 8]);
        // each measured corner's `q3::mean_ratio`, its Jacobians first and then their cube
        // roots: the same operations on each corner, but no corner waits on the last one's
        // cube root and division
        let mut parts = [None; 8];
        for (c, parts) in parts.iter_mut().enumerate().take(kind.row().corner_edges.len()) {
            match kept(c) {
                Some((t, d)) => (terms[c], dets[c]) = (t, d),
                None => *parts = Some(q3::MeanRatioParts::of(&corner_tet(kind, p, c), r)),
            }
        }
        for (c, parts) in parts.iter().enumerate() {
            if let Some(parts) = parts {
                terms[c] = parts.mean_ratio();
                dets[c] = if r.identity { parts.sigma } else { parts.sigma / r.det_w_inv };
            }
        }
        Some(CornerShapes { terms, dets, reach })
    }
    /// Corner `c`'s term.
    #[inline]
    pub fn term(&self, c: usize) -> f64 {
        self.terms[c]
    }
    /// Corner `c`'s term and determinant, as [`of`](Self::of) keeps them.
    #[inline]
    pub fn corner(&self, c: usize) -> (f64, f64) {
        (self.terms[c], self.dets[c])
    }
    /// [`solid_shape`] of the element of `kind` from its terms: the same sum in the same
    /// order, so the same bits.
    pub fn shape(&self, kind: VolumeKind) -> f64 {
        let count = kind.row().corner_edges.len();
        self.terms[..count].iter().copied().sum::<f64>() / count as f64
    }
    /// [`least_corner_det`] of the element of `kind` from the corners' determinants here:
    /// not the same bits (each `det A` by another formula, rounding some 10⁻¹⁶ of the
    /// extent³), but within the same tolerance of each corner's size, some ten thousand
    /// times that rounding, which is all the size screen reads
    /// (`Size::floor_kept_for_certain`: where it decides, the rule's comparison of the
    /// sizes finds the same).
    pub fn least_corner_det(&self, kind: VolumeKind) -> Option<(f64, f64)> {
        let mut least = f64::INFINITY;
        for &d in &self.dets[..kind.row().corner_edges.len()] {
            if d.is_nan() {
                return None;
            }
            least = least.min(d);
        }
        least_det_within(least, self.reach)
    }
}

/// A corner's size as the acceptance rule reads it: `(unit, scale)`, its Jacobian
/// determinant `unit · scale³` with `scale` the largest component of its edges and `unit`
/// the determinant of the edges divided by it (so no product leaves the doubles).
#[inline]
pub fn corner_size(t: &[DVec3; 4]) -> (f64, f64) {
    let e = [t[1] - t[0], t[2] - t[0], t[3] - t[0]];
    let m = crate::numeric::largest_component(e);
    ((e[0] / m).dot((e[1] / m).cross(e[2] / m)), m)
}

/// The smallest of an element's measured corners' Jacobian determinants taken directly
/// (`(t₁ − t₀)·((t₂ − t₀) × (t₃ − t₀))` of each corner's tetrahedron, where [`corner_size`]
/// divides the edges by their largest component first), with its tolerance
/// ([`super::det_within`], the element's extent for the scale); `None` where a corner's
/// determinant is not a number or the extent is beyond the scales it takes.
pub fn least_corner_det(kind: VolumeKind, p: &[DVec3]) -> Option<(f64, f64)> {
    let p = &p[..kind.corners()];
    let reach = reach(p);
    let mut least = f64::INFINITY;
    for c in 0..kind.row().corner_edges.len() {
        let d = corner_det(&corner_tet(kind, p, c));
        if d.is_nan() {
            return None;
        }
        least = least.min(d);
    }
    least_det_within(least, reach)
}

/// The least corner determinant `least` of an element of reach `reach` with its tolerance
/// ([`super::det_within`], the element's extent for the scale).
#[inline]
fn least_det_within(least: f64, reach: f64) -> Option<(f64, f64)> {
    // every component of an edge between two corners is at most twice the reach from the
    // first corner (rounded up beyond the reach's own rounding)
    let extent = 2.0 * reach * (1.0 + 1e-9);
    super::det_within(least, extent, 3)
}

/// The sizes ([`corner_size`]) of an element's measured corners in corner order, as
/// [`CornerShapes`] holds the shape's terms: each a function of its own corner's
/// tetrahedron alone, so a corner that did not move keeps its size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CornerSizes([(f64, f64); 8]);

impl CornerSizes {
    /// The sizes of the element of `kind` with corners `p`, each corner's from `kept(c)`
    /// where it gives one, else measured.
    pub fn of(kind: VolumeKind, p: &[DVec3], kept: impl Fn(usize) -> Option<(f64, f64)>) -> CornerSizes {
        let mut s = [(0.0, 0.0); 8];
        for (c, s) in s.iter_mut().enumerate().take(kind.row().corner_edges.len()) {
            *s = kept(c).unwrap_or_else(|| corner_size(&corner_tet(kind, p, c)));
        }
        CornerSizes(s)
    }
    /// The measured corners' sizes of an element of `kind`, in corner order.
    #[inline]
    pub fn of_kind(&self, kind: VolumeKind) -> &[(f64, f64)] {
        &self.0[..kind.row().corner_edges.len()]
    }
}

/// The smallest scaled Jacobian of the element's measured corners (its "sine").
pub fn solid_min_sine(kind: VolumeKind, p: &[DVec3]) -> f64 {
    let r = kind.reference();
    (0..kind.row().corner_edges.len()).map(|c| scaled_jacobian(&corner_tet(kind, p, c), r)).fold(f64::INFINITY, f64::min)
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

#[cfg(test)]
mod tests;
