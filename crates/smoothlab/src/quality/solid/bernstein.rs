//! An element's Jacobian determinant `det J` in the Bernstein basis, and its sign decided.
//! The coefficients bound the polynomial on a box; halving a box tightens the bound.

use std::cmp::Ordering;

use glam::DVec3;

use super::{Validity, MAX_BOXES};
use crate::numeric::dyadic::Dyadic;
use crate::numeric::exact::{det3_exact, exact_difference, expansions_suffice_for, Exact, Expansion};

/// A polynomial of degree ≤ 2 in each of three parameters on a box, by its 3×3×3
/// Bernstein coefficients (`deg[k]` 0 where it does not depend on parameter `k`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Bezier {
    pub(super) c: [[[f64; 3]; 3]; 3],
    pub(super) deg: [usize; 3],
}

impl Bezier {
    pub(super) fn min_coefficient(&self) -> f64 {
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
    pub(super) fn min_coefficient_unsigned(&self) -> f64 {
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
    pub(super) fn split(&self, axis: usize) -> (Bezier, Bezier) {
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

pub(super) fn indices(d: [usize; 3]) -> impl Iterator<Item = (usize, usize, usize)> {
    (0..=d[0]).flat_map(move |i| (0..=d[1]).flat_map(move |j| (0..=d[2]).map(move |k| (i, j, k))))
}

/// A trilinear hexahedron's `det J` (corners in VTK's order, parameters u, v, w along
/// edges 0→1, 0→3, 0→4) in the Bernstein basis.
pub(super) fn hex_det(p: &[DVec3]) -> Bezier {
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
pub(super) fn hex_det_and_slopes(p: &[DVec3], slot: usize) -> (Bezier, [DVec3; 27]) {
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
pub(super) fn pyramid_det(p: &[DVec3]) -> Bezier {
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
    PYRAMID.of(&bu, &bv, &to_apex)
}

/// [`pyramid_det`]'s plan: `B_u·(B_v × (apex − B))`.
const PYRAMID: TripleProduct = TripleProduct::new([0, 1, 0], [1, 0, 0], [1, 1, 0]);

/// How far from 0 a coefficient of the Bernstein form of a hexahedron's or pyramid's
/// `det J` with corners `p` may lie by rounding: each is a sum of a few weighted triple
/// products of edges, the edges differences of coordinates, so its rounding is some
/// `10⁻¹⁴ r²(r + M)` (`r` the element's reach from its first corner, `M` its largest
/// coordinate); `2⁻⁴⁰ r²(r + M)` is beyond it. Beyond it the coefficients' signs are the
/// exact ones; within, [`exact_validity`] decides.
pub(super) fn rounding_margin(p: &[DVec3]) -> f64 {
    let r = super::reach(p);
    let m = crate::numeric::largest_component(p.iter().copied());
    2f64.powi(-40) * r * r * (r + m)
}

impl Bezier {
    /// Decides the sign of the polynomial on the box from its rounded coefficients (least
    /// `least`) where the signs it reads are beyond `margin`: a box's corner (a value) below
    /// `−margin` is inverted for certain, a box whose least coefficient is above `margin`
    /// valid for certain, else halved, up to [`MAX_BOXES`] boxes (then not decided); `None`
    /// where a sign it needs lies within `margin` and the exact coefficients must decide
    /// (`docs/formulas.md` §9: the doubles as written).
    pub(super) fn validity_beyond(&self, least: f64, margin: f64) -> Option<Validity> {
        if !(margin >= 0.0 && margin.is_finite()) {
            return None;
        }
        let corner = self.min_corner();
        if corner < -margin {
            return Some(Validity::Inverted);
        }
        if corner.is_nan() || corner <= margin {
            return None;
        }
        if least > margin {
            return Some(Validity::Valid);
        }
        let axes: Vec<usize> = (0..3).filter(|&k| self.deg[k] == 2).collect();
        let mut stack = vec![(*self, 0usize)];
        let mut boxes = 0;
        while let Some((b, depth)) = stack.pop() {
            boxes += 1;
            let corner = b.min_corner();
            if corner < -margin {
                return Some(Validity::Inverted);
            }
            if corner.is_nan() || corner <= margin {
                return None;
            }
            if b.min_coefficient() > margin {
                continue;
            }
            if boxes >= MAX_BOXES || axes.is_empty() {
                return Some(Validity::Undecided);
            }
            let (lo, hi) = b.split(axes[depth % axes.len()]);
            stack.push((hi, depth + 1));
            stack.push((lo, depth + 1));
        }
        Some(Validity::Valid)
    }
}

/// A factor of a [`TripleProduct`] with exact coefficients.
type ExactFactor<N> = [[[[N; 3]; 2]; 2]; 2];

/// The Bernstein coefficients of `det J` exactly, for the boxes the rounded ones leave
/// within rounding of 0 (flat index `9i + 3j + k`).
#[derive(Clone, Debug)]
struct ExactBezier<N> {
    c: Vec<N>,
    deg: [usize; 3],
}

impl TripleProduct {
    /// [`of`](Self::of), exactly: every triple product as an expansion
    /// ([`det3_exact`]), each weight a power of two.
    fn of_exact<N: Exact>(&self, f: &ExactFactor<N>, g: &ExactFactor<N>, h: &ExactFactor<N>) -> ExactBezier<N> {
        let value = |v: &ExactFactor<N>, t: &Terms, a: usize| {
            let [i, j, k] = t.0[a].0;
            v[i][j][k].clone()
        };
        let mut c = vec![N::default(); 27];
        for a in 0..self.f.1 {
            for b in 0..self.g.1 {
                for d in 0..self.h.1 {
                    let n = self.f.0[a].1 + self.g.0[b].1 + self.h.0[d].1;
                    let term = det3_exact(value(f, &self.f, a), value(g, &self.g, b), value(h, &self.h, d));
                    c[n].add(&term.scaled(self.weight[n]));
                }
            }
        }
        ExactBezier { c, deg: self.deg }
    }
}

impl<N: Exact> ExactBezier<N> {
    fn at(&self, i: usize, j: usize, k: usize) -> &N {
        &self.c[9 * i + 3 * j + k]
    }
    fn corners_positive(&self) -> bool {
        let d = self.deg;
        [0, d[0]].iter().all(|&i| [0, d[1]].iter().all(|&j| [0, d[2]].iter().all(|&k| self.at(i, j, k).sign() == Ordering::Greater)))
    }
    fn all_positive(&self) -> bool {
        indices(self.deg).all(|(i, j, k)| self.at(i, j, k).sign() == Ordering::Greater)
    }
    /// The two halves along `axis` (de Casteljau at ½, exact).
    fn split(&self, axis: usize) -> (ExactBezier<N>, ExactBezier<N>) {
        let (mut lo, mut hi) = (self.clone(), self.clone());
        let flat = |t: usize, a: usize, b: usize| match axis {
            0 => 9 * t + 3 * a + b,
            1 => 9 * a + 3 * t + b,
            _ => 9 * a + 3 * b + t,
        };
        let others: Vec<usize> = (0..3).filter(|&k| k != axis).map(|k| self.deg[k]).collect();
        for a in 0..=others[0] {
            for b in 0..=others[1] {
                let (b0, b1, b2) = (&self.c[flat(0, a, b)], &self.c[flat(1, a, b)], &self.c[flat(2, a, b)]);
                let (l1, r1) = (b0.midpoint(b1), b1.midpoint(b2));
                let m = l1.midpoint(&r1);
                lo.c[flat(1, a, b)] = l1;
                lo.c[flat(2, a, b)] = m.clone();
                hi.c[flat(0, a, b)] = m;
                hi.c[flat(1, a, b)] = r1;
            }
        }
        (lo, hi)
    }
    /// The sign of `det J` on the box decided on the exact coefficients: a corner ≤ 0
    /// (a value of `det J`) is inverted, all positive valid, else the halves, up to
    /// [`EXACT_BOXES`] boxes.
    fn validity(&self) -> Validity {
        let axes: Vec<usize> = (0..3).filter(|&k| self.deg[k] == 2).collect();
        let mut stack = vec![(self.clone(), 0usize)];
        let mut boxes = 0;
        while let Some((b, depth)) = stack.pop() {
            boxes += 1;
            if !b.corners_positive() {
                return Validity::Inverted;
            }
            if b.all_positive() {
                continue;
            }
            if boxes >= EXACT_BOXES || axes.is_empty() {
                return Validity::Undecided;
            }
            let (lo, hi) = b.split(axes[depth % axes.len()]);
            stack.push((hi, depth + 1));
            stack.push((lo, depth + 1));
        }
        Validity::Valid
    }
}

/// How many boxes the exact test halves into at most (it is asked only at the margin).
const EXACT_BOXES: usize = 256;

/// The validity of a hexahedron or a pyramid with corners `p` decided on the exact
/// Bernstein coefficients of its `det J` (the doubles as given): where the rounded ones
/// lie within rounding of 0 ([`rounding_margin`]): `p`, the corners `given` times a power of
/// two, as expansions where they are exact, else `given` as [`Dyadic`] numbers (issue 61: a
/// node at 1e200 beside unit edges).
pub(super) fn exact_validity(kind: crate::mesh::VolumeKind, p: &[DVec3], given: &[DVec3]) -> Validity {
    if expansions_suffice_for(given, p, 3) {
        exact_validity_in::<Expansion>(kind, p)
    } else {
        exact_validity_in::<Dyadic>(kind, given)
    }
}

/// [`exact_validity`] in the exact numbers of `N`.
fn exact_validity_in<N: Exact>(kind: crate::mesh::VolumeKind, p: &[DVec3]) -> Validity {
    let z = || -> ExactFactor<N> { std::array::from_fn(|_| std::array::from_fn(|_| std::array::from_fn(|_| std::array::from_fn(|_| N::default())))) };
    let (mut f, mut g, mut h) = (z(), z(), z());
    match kind.linear() {
        crate::mesh::VolumeKind::Hex8 => {
            let at = |i: usize, j: usize, k: usize| p[4 * k + HEX_CORNER[i][j]];
            for a in 0..2 {
                for b in 0..2 {
                    f[0][a][b] = exact_difference(at(1, a, b), at(0, a, b));
                    g[a][0][b] = exact_difference(at(a, 1, b), at(a, 0, b));
                    h[a][b][0] = exact_difference(at(a, b, 1), at(a, b, 0));
                }
            }
            HEX.of_exact(&f, &g, &h).validity()
        }
        crate::mesh::VolumeKind::Pyramid5 => {
            let base = |i: usize, j: usize| p[HEX_CORNER[i][j]];
            for a in 0..2 {
                f[0][a][0] = exact_difference(base(1, a), base(0, a));
                g[a][0][0] = exact_difference(base(a, 1), base(a, 0));
                for (b, t) in h[a].iter_mut().enumerate() {
                    t[0] = exact_difference(p[4], base(a, b));
                }
            }
            PYRAMID.of_exact(&f, &g, &h).validity()
        }
        _ => Validity::Undecided,
    }
}
