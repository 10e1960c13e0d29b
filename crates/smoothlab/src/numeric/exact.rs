//! Exact signs of determinants of doubles, where rounding would decide them.
//!
//! A sum of products of doubles is evaluated in floating point with a bound on its
//! rounding error; only where the value lies within that bound of 0 is it evaluated again
//! exactly, as an expansion: a sum of doubles whose magnitudes do not overlap (Shewchuk,
//! "Adaptive precision floating-point arithmetic and fast robust geometric predicates",
//! 1997), built by error-free sums (`two_sum`) and products (`two_product`, one fused
//! multiply-add, correctly rounded on every platform). The sign of an expansion is that
//! of its largest component. The values are taken as given, multiplied by a power of two
//! (exact) when they are far from unit size, so the products do not overflow. Where the
//! products could still leave the doubles' exponent range (coordinates far apart in
//! scale), the same sums are taken as dyadic numbers (`numeric::dyadic`): big integers
//! times powers of two, exact at any exponent.

use std::cmp::Ordering;

use glam::DVec3;

use super::dyadic::{mantissa_and_exponent, Dyadic};

/// A number type whose sums and products of doubles are exact: [`Expansion`] (fast, within
/// the doubles' exponent range) or [`Dyadic`] (any exponent).
pub(crate) trait Exact: Clone + Default {
    /// `a − b`, exactly.
    fn difference(a: f64, b: f64) -> Self;
    /// `self + other`, exactly.
    fn add(&mut self, other: &Self);
    /// `self · other`, exactly.
    fn times(&self, other: &Self) -> Self;
    /// `s·self` for a power of two `s`, exactly.
    fn scaled(self, s: f64) -> Self;
    /// `(self + other)/2`, exactly.
    fn midpoint(&self, other: &Self) -> Self;
    /// `−self`.
    fn negated(self) -> Self;
    /// The sign of the exact value.
    fn sign(&self) -> Ordering;
}

/// Whether expansions are exact for sums of products of `degree` differences of `values`
/// (products of power-of-two weights and up to 64 halvings included): every product's
/// lowest bit stays above the doubles' least subnormal, its highest below their largest.
/// Not-a-number or infinite values are left to expansions, which read them as they are.
pub(crate) fn expansions_suffice(values: impl IntoIterator<Item = f64>, degree: i64) -> bool {
    let (mut lo, mut hi) = (i64::MAX, i64::MIN);
    for x in values {
        if !x.is_finite() {
            return true;
        }
        let (m, exp) = mantissa_and_exponent(x);
        if m != 0 {
            lo = lo.min(exp + m.trailing_zeros() as i64);
            hi = hi.max(exp + 63 - m.leading_zeros() as i64);
        }
    }
    lo == i64::MAX || (degree * lo - 64 >= -1074 && degree * (hi + 2) + 16 <= 1023)
}

/// Whether expansions of the points `scaled` (the points `given` times one power of two)
/// are exact for the sign of a sum of products of `degree` of their differences: the
/// scaling lost no coordinate to underflow, and [`expansions_suffice`] for them. Where
/// not, the sign is taken in [`Dyadic`] numbers on the points as given.
pub(crate) fn expansions_suffice_for(given: &[DVec3], scaled: &[DVec3], degree: i64) -> bool {
    let kept = given.iter().zip(scaled).all(|(g, s)| (0..3).all(|i| (g[i] == 0.0) == (s[i] == 0.0)));
    kept && expansions_suffice(scaled.iter().flat_map(|p| p.to_array()), degree)
}

/// `a + b = s + e` exactly, `s` the rounded sum.
#[inline]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// `a·b = p + e` exactly (unless `e` underflows), `p` the rounded product.
#[inline]
fn two_product(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// An exact sum of doubles: components of increasing magnitude that do not overlap.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Expansion(Vec<f64>);

impl Expansion {
    /// Adds one double, exactly (Shewchuk's Grow-Expansion, zeros dropped).
    pub fn grow(&mut self, b: f64) {
        let mut q = b;
        let mut out = Vec::with_capacity(self.0.len() + 1);
        for &e in &self.0 {
            let (s, h) = two_sum(q, e);
            if h != 0.0 {
                out.push(h);
            }
            q = s;
        }
        if q != 0.0 {
            out.push(q);
        }
        self.0 = out;
    }
}

impl Exact for Expansion {
    fn difference(a: f64, b: f64) -> Expansion {
        let (s, e) = two_sum(a, -b);
        Expansion([e, s].into_iter().filter(|&x| x != 0.0).collect())
    }
    fn add(&mut self, other: &Expansion) {
        for &x in &other.0 {
            self.grow(x);
        }
    }
    fn times(&self, other: &Expansion) -> Expansion {
        let mut out = Expansion::default();
        for &a in &self.0 {
            for &b in &other.0 {
                let (p, e) = two_product(a, b);
                out.grow(e);
                out.grow(p);
            }
        }
        out
    }
    /// Exact unless a component underflows.
    fn scaled(mut self, s: f64) -> Expansion {
        for x in &mut self.0 {
            *x *= s;
        }
        self.0.retain(|&x| x != 0.0);
        self
    }
    /// Exact unless a component underflows.
    fn midpoint(&self, other: &Expansion) -> Expansion {
        let mut s = self.clone();
        s.add(other);
        s.scaled(0.5)
    }
    fn negated(mut self) -> Expansion {
        for x in &mut self.0 {
            *x = -*x;
        }
        self
    }
    fn sign(&self) -> Ordering {
        self.0.last().map_or(Ordering::Equal, |x| x.partial_cmp(&0.0).unwrap_or(Ordering::Equal))
    }
}

/// Values whose largest magnitude is `m` multiplied by powers of two (exact) that bring
/// it near 1 when it lies beyond 2^±300; as they are within.
pub(crate) fn near_unit(m: f64) -> impl Fn(DVec3) -> DVec3 {
    let (f1, f2) = if m.is_finite() && m > 0.0 && !(2f64.powi(-300)..=2f64.powi(300)).contains(&m) {
        super::unit_factors(m)
    } else {
        (1.0, 1.0)
    };
    move |x| x * f1 * f2
}

/// The sign of `det [b − a, c − a, d − a] = (b − a)·((c − a) × (d − a))`, six times the
/// signed volume of the tetrahedron `(a, b, c, d)`, exact for the doubles given.
/// Not-a-number coordinates give `Equal`.
pub fn orient3d(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Ordering {
    let m = super::largest_component([a, b, c, d]);
    if !m.is_finite() {
        return Ordering::Equal;
    }
    let given = [a, b, c, d];
    let s = near_unit(m);
    let (a, b, c, d) = (s(a), s(b), s(c), s(d));
    if !expansions_suffice_for(&given, &[a, b, c, d], 3) {
        // products beyond the doubles' range at any one scale
        return orient3d_exact::<Dyadic>(given[0], given[1], given[2], given[3]);
    }
    // Shewchuk's orient3d with `a` as the apex: its forward error bound
    let (u, v, w) = (b - a, c - a, d - a);
    let (vw_x, wv_x) = (v.y * w.z, v.z * w.y);
    let (vw_y, wv_y) = (v.z * w.x, v.x * w.z);
    let (vw_z, wv_z) = (v.x * w.y, v.y * w.x);
    let det = u.x * (vw_x - wv_x) + u.y * (vw_y - wv_y) + u.z * (vw_z - wv_z);
    let permanent = (vw_x.abs() + wv_x.abs()) * u.x.abs()
        + (vw_y.abs() + wv_y.abs()) * u.y.abs()
        + (vw_z.abs() + wv_z.abs()) * u.z.abs();
    const EPS: f64 = f64::EPSILON / 2.0;
    let bound = (7.0 + 56.0 * EPS) * EPS * permanent;
    if det > bound {
        return Ordering::Greater;
    }
    if -det > bound {
        return Ordering::Less;
    }
    orient3d_exact::<Expansion>(a, b, c, d)
}

/// [`orient3d`]'s sign from the exact numbers of `N`.
fn orient3d_exact<N: Exact>(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Ordering {
    det3_exact(exact_difference::<N>(b, a), exact_difference(c, a), exact_difference(d, a)).sign()
}

/// `b − a`, exactly, component by component.
pub(crate) fn exact_difference<N: Exact>(b: DVec3, a: DVec3) -> [N; 3] {
    [N::difference(b.x, a.x), N::difference(b.y, a.y), N::difference(b.z, a.z)]
}

/// `u·(v × w)` of three vectors of exact numbers, exactly.
pub(crate) fn det3_exact<N: Exact>(u: [N; 3], v: [N; 3], w: [N; 3]) -> N {
    let mut total = N::default();
    for (i, j, k) in [(0, 1, 2), (1, 2, 0), (2, 0, 1)] {
        // u_i (v_j w_k − v_k w_j)
        let mut minor = v[j].times(&w[k]);
        minor.add(&v[k].times(&w[j]).negated());
        total.add(&u[i].times(&minor));
    }
    total
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::SplitMix64;

    /// The exact sign against rationals by hand: points on a line of slope 1/3 in doubles
    /// that are not exactly collinear, and a tetrahedron 2^-60 off flat at 1e4.
    #[test]
    fn signs_are_exact_where_rounding_decides() {
        let o = DVec3::ZERO;
        // exactly flat: four corners in the plane z = x + y, any scale
        for s in [1.0, 2f64.powi(-800), 2f64.powi(800), 2f64.powi(-1060)] {
            let p = |x: f64, y: f64| DVec3::new(x, y, x + y) * s;
            assert_eq!(orient3d(p(0.0, 0.0), p(1.0, 0.0), p(0.0, 1.0), p(0.25, 0.5)), Ordering::Equal, "{s}");
        }
        // the apex one ulp above the plane of a large base
        let base = [DVec3::new(1e4, 0.0, 0.0), DVec3::new(0.0, 1e4, 0.0), DVec3::new(0.0, 0.0, 0.0)];
        let up = DVec3::new(0.1, 0.1, f64::from_bits(1));
        let above = orient3d(DVec3::new(0.1, 0.1, 1.0), base[0], base[1], base[2]);
        assert_ne!(above, Ordering::Equal);
        assert_eq!(orient3d(up, base[0], base[1], base[2]), above);
        let below = DVec3::new(0.1, 0.1, -f64::from_bits(1));
        assert_eq!(orient3d(below, base[0], base[1], base[2]), above.reverse());
        assert_eq!(orient3d(DVec3::new(0.1, 0.1, 0.0), base[0], base[1], base[2]), Ordering::Equal);
        // (b − a) and its rounding: a + (b − a) differs from b, the sign does not
        let a = DVec3::new(0.1, 0.2, 0.3);
        let b = a + DVec3::new(1.0 / 3.0, 0.0, 0.0);
        let c = a + DVec3::new(0.0, 1.0 / 3.0, 0.0);
        let mid = (b + c) * 0.5;
        let sign = orient3d(a, b, c, mid);
        // exact by expansions directly
        let d = |p: DVec3, q: DVec3| [Expansion::difference(p.x, q.x), Expansion::difference(p.y, q.y), Expansion::difference(p.z, q.z)];
        assert_eq!(sign, det3_exact(d(b, a), d(c, a), d(mid, a)).sign());
        let _ = o;
    }

    /// Coordinates 2^2000 apart in scale: the determinant 2^-3000 is beyond every double,
    /// its sign is not (issue 61: big integers take what expansions cannot).
    #[test]
    fn signs_are_exact_beyond_the_exponent_range() {
        let (s, big) = (2f64.powi(-1000), 2f64.powi(1000));
        let (a, b, c) = (DVec3::ZERO, DVec3::new(s, 0.0, 0.0), DVec3::new(0.0, s, 0.0));
        for d in [DVec3::new(big, 0.0, s), DVec3::new(0.0, big, s), DVec3::new(0.0, 0.0, s)] {
            assert_eq!(orient3d(a, b, c, d), Ordering::Greater, "{d}");
            assert_eq!(orient3d(a, c, b, d), Ordering::Less, "{d}");
            assert_eq!(orient3d(a, b, c, DVec3::new(d.x, d.y, 0.0)), Ordering::Equal, "{d}");
        }
    }

    /// Against the rounded determinant where that is far from 0, and against swaps (an odd
    /// permutation turns the sign) everywhere, on random and on nearly flat tetrahedra.
    #[test]
    fn signs_agree_with_rounding_when_clear_and_turn_with_odd_permutations() {
        let mut rng = SplitMix64::new(61);
        for i in 0..4000 {
            let mut p = [DVec3::ZERO; 4];
            for q in &mut p {
                *q = DVec3::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0));
            }
            if i % 2 == 1 {
                // the fourth nearly in the plane of the others
                let (u, v) = (rng.next_f64(), rng.next_f64());
                p[3] = p[0] + (p[1] - p[0]) * u + (p[2] - p[0]) * v;
            }
            let s = orient3d(p[0], p[1], p[2], p[3]);
            let det = (p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0]));
            if det.abs() > 1e-9 {
                assert_eq!(s, det.partial_cmp(&0.0).unwrap());
            }
            assert_eq!(orient3d(p[1], p[0], p[2], p[3]), s.reverse());
            assert_eq!(orient3d(p[0], p[1], p[3], p[2]), s.reverse());
            assert_eq!(orient3d(p[1], p[2], p[0], p[3]), s, "an even permutation");
            for k in [2f64.powi(-600), 2f64.powi(600)] {
                assert_eq!(orient3d(p[0] * k, p[1] * k, p[2] * k, p[3] * k), s, "scale {k}");
            }
        }
    }
}
