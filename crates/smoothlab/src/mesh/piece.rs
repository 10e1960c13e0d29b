//! One piece of a boundary curve: a straight segment, or the quadratic through a quadratic
//! element's edge (its isoparametric edge: corners at ξ = 0 and 1, mid-side node at ½),
//! and the point of it nearest a given point.
//!
//! A quadratic piece through `a`, `m`, `b` is `B(t) = a(1 − t)(1 − 2t) + 4m·t(1 − t) +
//! b·t(2t − 1)`, `t ∈ [0, 1]` (Chen, Tristano & Kwok 2003 §5's curved quadratic
//! boundaries). Its nearest point to `p` is where `f(t) = (B(t) − p)·B′(t)` turns from
//! negative to positive, or an end: `f` is a cubic, so the roots of its derivative cut
//! [0, 1] into at most three runs on which it is monotone, and bisection finds its root in
//! each run where it changes sign.

use super::slide::Coords;

/// A piece of a boundary curve, from `a` (`t = 0`) to `b` (`t = 1`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Piece<P> {
    /// The segment from `a` to `b`, `a + (b − a)·t`.
    Straight { a: P, b: P },
    /// The quadratic through `a`, `m` and `b` at `t = 0, ½, 1`.
    Quadratic { a: P, m: P, b: P },
}

impl<P: Coords> Piece<P> {
    /// The point at parameter `t`. A quadratic in its Lagrange form, so its ends and its
    /// middle are its nodes exactly.
    pub(crate) fn at(&self, t: f64) -> P {
        match *self {
            Piece::Straight { a, b } => a + (b - a) * t,
            Piece::Quadratic { a, m, b } => a * ((1.0 - t) * (1.0 - 2.0 * t)) + m * (4.0 * t * (1.0 - t)) + b * (t * (2.0 * t - 1.0)),
        }
    }

    /// `dB/dt` at `t`: `b − a` on a segment, `c₁ + 2c₂t` on a quadratic
    /// (`c₁ = 4m − 3a − b`, `c₂ = 2a + 2b − 4m`).
    pub(crate) fn derivative(&self, t: f64) -> P {
        match *self {
            Piece::Straight { a, b } => b - a,
            Piece::Quadratic { a, m, b } => {
                let (c1, c2) = Self::coefficients(a, m, b);
                c1 + c2 * (2.0 * t)
            }
        }
    }

    /// The direction the piece leaves its end `at_b == false` (`a`) or `at_b` (`b`) in,
    /// pointing into the piece: `b − a` or `a − b` on a segment; `4m − 3a − b` or
    /// `4m − 3b − a` on a quadratic (its end tangents).
    pub(crate) fn leaving(&self, at_b: bool) -> P {
        match (*self, at_b) {
            (Piece::Straight { a, b }, false) => b - a,
            (Piece::Straight { a, b }, true) => a - b,
            (Piece::Quadratic { a, m, b }, false) => m * 4.0 - a * 3.0 - b,
            (Piece::Quadratic { a, m, b }, true) => m * 4.0 - b * 3.0 - a,
        }
    }

    /// The point of the piece nearest `p` and its parameter: the segment's clamped
    /// projection (its `a` where it is a point, as the polylines always took it), the
    /// quadratic's nearest root of `f` or end (the first of equally near ones).
    pub(crate) fn nearest(&self, p: P) -> (P, f64) {
        match *self {
            Piece::Straight { a, b } => {
                let d = b - a;
                let t = ((p - a).dot(d) / d.dot(d)).clamp(0.0, 1.0);
                if t.is_finite() {
                    (a + d * t, t)
                } else {
                    (a, 0.0)
                }
            }
            Piece::Quadratic { a, m, b } => {
                let (c1, c2) = Self::coefficients(a, m, b);
                let r = a - p;
                // f(t) = k3 t³ + k2 t² + k1 t + k0
                let (k3, k2, k1, k0) = (2.0 * c2.dot(c2), 3.0 * c1.dot(c2), c1.dot(c1) + 2.0 * c2.dot(r), c1.dot(r));
                let f = |t: f64| ((k3 * t + k2) * t + k1) * t + k0;
                // [0, 1] cut at the roots of f′ inside it: f is monotone between the cuts
                let mut cuts = [0.0; 4];
                let mut count = 1;
                for t in quadratic_roots(3.0 * k3, 2.0 * k2, k1) {
                    if t > 0.0 && t < 1.0 {
                        cuts[count] = t;
                        count += 1;
                    }
                }
                cuts[1..count].sort_by(f64::total_cmp);
                cuts[count] = 1.0;
                let squared = |t: f64| {
                    let d = self.at(t) - p;
                    d.dot(d)
                };
                let mut best = (squared(0.0), 0.0);
                for w in cuts[..=count].windows(2) {
                    if f(w[0]) < 0.0 && f(w[1]) > 0.0 {
                        let t = bisect(&f, w[0], w[1]);
                        let d = squared(t);
                        if d < best.0 {
                            best = (d, t);
                        }
                    }
                }
                if squared(1.0) < best.0 {
                    best.1 = 1.0;
                }
                (self.at(best.1), best.1)
            }
        }
    }

    /// The length of the piece: `|b − a|`, or the integral of `|B′(t)|` by 5-point
    /// Gauss–Legendre quadrature (exact for a straight quadratic, within 10⁻⁶ for the
    /// gentle bends of a boundary edge).
    pub(crate) fn length(&self) -> f64 {
        match *self {
            Piece::Straight { a, b } => (b - a).dot(b - a).sqrt(),
            Piece::Quadratic { .. } => {
                const NODES: [(f64, f64); 5] = [
                    (0.0, 0.568_888_888_888_888_9),
                    (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
                    (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
                    (0.906_179_845_938_664, 0.236_926_885_056_189_1),
                    (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
                ];
                NODES
                    .iter()
                    .map(|&(x, w)| {
                        let d = self.derivative(0.5 * (x + 1.0));
                        0.5 * w * d.dot(d).sqrt()
                    })
                    .sum()
            }
        }
    }

    /// `c₁` and `c₂` of `B(t) = a + c₁t + c₂t²`.
    fn coefficients(a: P, m: P, b: P) -> (P, P) {
        (m * 4.0 - a * 3.0 - b, (a + b) * 2.0 - m * 4.0)
    }
}

/// The real roots of `a t² + b t + c` (one where `a` is 0, none where both are), in no
/// order; NaN where there is none.
fn quadratic_roots(a: f64, b: f64, c: f64) -> [f64; 2] {
    if a == 0.0 {
        return [if b != 0.0 { -c / b } else { f64::NAN }, f64::NAN];
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return [f64::NAN; 2];
    }
    // the root of the larger magnitude first, the other from the product (no cancellation)
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    if q == 0.0 {
        return [0.0, f64::NAN];
    }
    [q / a, c / q]
}

/// The root of `f` in `[lo, hi]`, where `f(lo) < 0 < f(hi)`, by bisection to the last bit.
fn bisect(f: &impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if f(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    fn d(x: f64, y: f64) -> DVec2 {
        DVec2::new(x, y)
    }

    /// The parabola `y = 1 − x²` from (−1, 0) to (1, 0): its mid node (0, 1) sits at the
    /// chord's middle in `x`, so `x = 2t − 1` and the piece is the parabola itself.
    fn parabola() -> Piece<DVec2> {
        Piece::Quadratic { a: d(-1.0, 0.0), m: d(0.0, 1.0), b: d(1.0, 0.0) }
    }

    #[test]
    fn a_quadratic_piece_passes_through_its_nodes_and_its_derivative_is_the_difference_quotient() {
        let q = Piece::Quadratic { a: d(0.3, -0.2), m: d(1.1, 0.9), b: d(2.0, 0.1) };
        assert_eq!(q.at(0.0), d(0.3, -0.2));
        assert_eq!(q.at(0.5), d(1.1, 0.9));
        assert_eq!(q.at(1.0), d(2.0, 0.1));
        let h = 1e-6;
        for t in [0.0, 0.2, 0.5, 0.77, 1.0] {
            let fd = (q.at(t + h) - q.at(t - h)) / (2.0 * h);
            assert!((fd - q.derivative(t)).length() < 1e-8, "t {t}: {fd} vs {}", q.derivative(t));
        }
        // the end tangents point into the piece
        assert!((q.leaving(false) - q.derivative(0.0)).length() < 1e-12);
        assert!((q.leaving(true) + q.derivative(1.0)).length() < 1e-12);
    }

    #[test]
    fn a_piece_s_length_is_its_arc_s() {
        // the parabola y = 1 − x² over [−1, 1]: √5 + asinh(2)/2
        let exact = 5f64.sqrt() + 0.5 * 2f64.asinh();
        assert!((parabola().length() - exact).abs() < 1e-3 * exact, "{} vs {exact}", parabola().length());
        // a quarter circle's quadratic through its ends and middle: about π/2
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let arc = Piece::Quadratic { a: d(1.0, 0.0), m: d(h, h), b: d(0.0, 1.0) };
        assert!((arc.length() - std::f64::consts::FRAC_PI_2).abs() < 1e-2);
        assert_eq!(Piece::Straight { a: d(0.0, 0.0), b: d(3.0, 4.0) }.length(), 5.0);
    }

    #[test]
    fn the_nearest_point_of_a_parabola_is_found_by_hand() {
        let q = parabola();
        // above the vertex: the vertex
        let (at, t) = q.nearest(d(0.0, 2.0));
        assert!((at - d(0.0, 1.0)).length() < 1e-15 && (t - 0.5).abs() < 1e-15, "{at} at {t}");
        // from (2, 1): minimise (x − 2)² + x⁴, so 2x³ + x − 2 = 0, x = 0.835122…
        let (at, t) = q.nearest(d(2.0, 1.0));
        let x = 2.0 * t - 1.0;
        assert!((2.0 * x * x * x + x - 2.0).abs() < 1e-12, "x {x}");
        assert!((at - d(x, 1.0 - x * x)).length() < 1e-15);
        // beyond an end: the end, exactly
        assert_eq!(q.nearest(d(-3.0, -1.0)), (d(-1.0, 0.0), 0.0));
        assert_eq!(q.nearest(d(3.0, -1.0)), (d(1.0, 0.0), 1.0));
        // on the piece: itself
        let on = q.at(0.3);
        assert!((q.nearest(on).0 - on).length() < 1e-15);
        // below the vertex the vertex is farthest, not nearest: x² + (1.2 − x²)² is least
        // at x² = 0.7 (0.95, against 1.44 at x = 0); of the two the first
        let x = 2.0 * q.nearest(d(0.0, -0.2)).1 - 1.0;
        assert!((x + 0.7f64.sqrt()).abs() < 1e-12, "x {x}");
    }

    #[test]
    fn the_nearest_point_is_a_stationary_point_no_sample_beats() {
        let mut rng = crate::numeric::SplitMix64::new(58);
        for _ in 0..200 {
            let mut r = || d(rng.next_f64() * 4.0 - 2.0, rng.next_f64() * 4.0 - 2.0);
            let q = Piece::Quadratic { a: r(), m: r(), b: r() };
            let p = r();
            let t = q.nearest(p).1;
            let dist = |t: f64| (q.at(t) - p).length();
            let best = (0..=4000).map(|i| dist(i as f64 / 4000.0)).fold(f64::INFINITY, f64::min);
            assert!(dist(t) <= best + 1e-12, "t {t}: {} > sampled {best}", dist(t));
            // inside the piece the distance is stationary: a central difference of zero
            if t > 1e-4 && t < 1.0 - 1e-4 {
                let h = 1e-5;
                let slope = (dist(t + h) - dist(t - h)) / (2.0 * h);
                assert!(slope.abs() < 1e-6 * (1.0 + q.derivative(t).length()), "t {t}: slope {slope}");
            }
        }
    }

    #[test]
    fn a_straight_piece_projects_as_the_polylines_do() {
        let s = Piece::Straight { a: d(0.0, 0.0), b: d(2.0, 0.0) };
        assert_eq!(s.nearest(d(0.5, 3.0)), (d(0.5, 0.0), 0.25));
        assert_eq!(s.nearest(d(-1.0, 0.0)), (d(0.0, 0.0), 0.0));
        assert_eq!(Piece::Straight { a: d(1.0, 1.0), b: d(1.0, 1.0) }.nearest(d(0.0, 0.0)), (d(1.0, 1.0), 0.0));
        // a quadratic whose mid node is its chord's middle is the segment
        let q = Piece::Quadratic { a: d(0.0, 0.0), m: d(1.0, 0.0), b: d(2.0, 0.0) };
        assert!((q.nearest(d(0.5, 3.0)).1 - 0.25).abs() < 1e-15);
    }
}
