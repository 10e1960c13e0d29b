//! Exact signs of determinants of doubles, where rounding would decide them.
//!
//! A sum of products of doubles is evaluated in floating point with a bound on its
//! rounding error; only where the value lies within that bound of 0 is it evaluated again
//! exactly, as an expansion: a sum of doubles whose magnitudes do not overlap (Shewchuk,
//! "Adaptive precision floating-point arithmetic and fast robust geometric predicates",
//! 1997), built by error-free sums (`two_sum`) and products (`two_product`, one fused
//! multiply-add, correctly rounded on every platform). The sign of an expansion is that
//! of its largest component. The values are taken as given, multiplied by a power of two
//! (exact) when they are far from unit size, so the products neither overflow nor, for
//! elements whose coordinates lie within 2^±300 of their largest, underflow.

use std::cmp::Ordering;

use glam::DVec3;

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
    /// `a − b`, exactly.
    pub fn difference(a: f64, b: f64) -> Expansion {
        let (s, e) = two_sum(a, -b);
        Expansion([e, s].into_iter().filter(|&x| x != 0.0).collect())
    }
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
    /// `self + other`, exactly.
    pub fn add(&mut self, other: &Expansion) {
        for &x in &other.0 {
            self.grow(x);
        }
    }
    /// `self · other`, exactly.
    pub fn times(&self, other: &Expansion) -> Expansion {
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
    /// `s·self` for a power of two `s`, exactly (unless a component underflows).
    pub fn scaled(mut self, s: f64) -> Expansion {
        for x in &mut self.0 {
            *x *= s;
        }
        self.0.retain(|&x| x != 0.0);
        self
    }
    /// `(self + other)/2`, exactly (unless a component underflows).
    pub fn midpoint(&self, other: &Expansion) -> Expansion {
        let mut s = self.clone();
        s.add(other);
        s.scaled(0.5)
    }
    /// `−self`.
    pub fn negated(mut self) -> Expansion {
        for x in &mut self.0 {
            *x = -*x;
        }
        self
    }
    /// The sign of the exact value.
    pub fn sign(&self) -> Ordering {
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
    let s = near_unit(m);
    let (a, b, c, d) = (s(a), s(b), s(c), s(d));
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
    det3_exact(
        [Expansion::difference(b.x, a.x), Expansion::difference(b.y, a.y), Expansion::difference(b.z, a.z)],
        [Expansion::difference(c.x, a.x), Expansion::difference(c.y, a.y), Expansion::difference(c.z, a.z)],
        [Expansion::difference(d.x, a.x), Expansion::difference(d.y, a.y), Expansion::difference(d.z, a.z)],
    )
    .sign()
}

/// `u·(v × w)` of three vectors of expansions, exactly.
pub(crate) fn det3_exact(u: [Expansion; 3], v: [Expansion; 3], w: [Expansion; 3]) -> Expansion {
    let mut total = Expansion::default();
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
