//! `atan2` for the metrics and the `new` objective's inner loop, written out so it inlines.
//!
//! One evaluation of Chen et al.'s objective on a star of six triangles takes twelve
//! `atan2` (the signed angles of eqs. 6–8), and a smoothing visit about thirteen
//! evaluations. The platform's `atan2` is a call into the C library natively (≈ 17 ns on
//! the machines of `docs/performance.md`) and a compiled port of fdlibm's in WebAssembly;
//! this is Cephes' rational approximation of `atan` with the octant reduction done once,
//! inlined (≈ 10 ns), within 2 ulp of the library's (the tests compare them over millions
//! of arguments), and the same on every platform, as it uses only `+ − × ÷`.
//! (`exp`, the other function of that loop, stays the library's: glibc's table-driven
//! `exp` is faster than any division-based one we can inline.)
//!
//! Zeros, infinities and NaN go to the standard library, so the edge cases behave exactly
//! as `f64::atan2` does.

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

/// `atan t` for `0 ≤ t ≤ 1`: Cephes' method. For `t > 0.66`, `atan t = π/4 + atan((t−1)/(t+1))`;
/// then `atan z = z + z³·P(z²)/Q(z²)`, P and Q of degrees 4 and 5.
#[inline(always)]
#[allow(clippy::excessive_precision)] // Cephes' published coefficients, as printed
fn atan_unit(t: f64) -> f64 {
    const P: [f64; 5] = [
        -8.750_608_600_031_904_122_785e-1,
        -1.615_753_718_733_365_076_637e1,
        -7.500_855_792_314_704_667_340e1,
        -1.228_866_684_490_136_173_410e2,
        -6.485_021_904_942_025_371_773e1,
    ];
    const Q: [f64; 5] = [
        2.485_846_490_142_306_297_962e1,
        1.650_270_098_316_988_542_046e2,
        4.328_810_604_912_902_668_951e2,
        4.853_903_996_359_136_964_868e2,
        1.945_506_571_482_613_964_425e2,
    ];
    /// The part of π/4 that `FRAC_PI_4` leaves out, halved (Cephes' `MOREBITS/2`).
    const PI_4_LO: f64 = 0.5 * 6.123_233_995_736_765_886_130e-17;
    let (z, base, extra) = if t > 0.66 { ((t - 1.0) / (t + 1.0), FRAC_PI_4, PI_4_LO) } else { (t, 0.0, 0.0) };
    let z2 = z * z;
    let p = (((P[0] * z2 + P[1]) * z2 + P[2]) * z2 + P[3]) * z2 + P[4];
    let q = ((((z2 + Q[0]) * z2 + Q[1]) * z2 + Q[2]) * z2 + Q[3]) * z2 + Q[4];
    base + (z + z * z2 * p / q + extra)
}

/// `atan2(y, x)`, the angle of the vector `(x, y)` in `(−π, π]`: the ratio of the smaller
/// to the larger of `|x|`, `|y|` through [`atan_unit`], then placed in its octant.
#[inline(always)]
pub fn atan2(y: f64, x: f64) -> f64 {
    let (ax, ay) = (x.abs(), y.abs());
    // zeros (signed), infinities and NaN: as the library does
    if !(ax > 0.0 && ay > 0.0 && ax < f64::INFINITY && ay < f64::INFINITY) {
        return y.atan2(x);
    }
    let a = if ay <= ax { atan_unit(ay / ax) } else { FRAC_PI_2 - atan_unit(ax / ay) };
    let a = if x < 0.0 { PI - a } else { a };
    if y < 0.0 {
        -a
    } else {
        a
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Distance in units in the last place between two finite doubles of one sign.
    fn ulps(a: f64, b: f64) -> u64 {
        if a == b {
            return 0;
        }
        assert_eq!(a.is_sign_negative(), b.is_sign_negative(), "{a} {b}");
        a.to_bits().abs_diff(b.to_bits())
    }

    /// A deterministic stream of doubles in `[lo, hi)`.
    fn uniform(seed: u64, lo: f64, hi: f64) -> impl Iterator<Item = f64> {
        let mut s = seed;
        std::iter::repeat_with(move || {
            s = s.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
            lo + (hi - lo) * ((s >> 11) as f64 / (1u64 << 53) as f64)
        })
    }

    #[test]
    fn atan2_is_within_two_ulp_of_the_library() {
        let mut worst = 0;
        let xs = uniform(11, -3.0, 3.0);
        let ys = uniform(13, -3.0, 3.0);
        for (x, y) in xs.zip(ys).take(3_000_000) {
            worst = worst.max(ulps(atan2(y, x), y.atan2(x)));
        }
        // near the axes and the diagonals, and over many scales
        let ts = uniform(17, -1.0, 1.0);
        let ss = uniform(19, -300.0, 300.0);
        for (t, s) in ts.zip(ss).take(1_000_000) {
            let r = 10f64.powf(s);
            for (x, y) in [(r, t * 1e-9 * r), (t * 1e-9 * r, r), (r, r * (1.0 + t * 1e-9)), (-r, t * r), (t * r, -r)] {
                worst = worst.max(ulps(atan2(y, x), y.atan2(x)));
            }
        }
        assert!(worst <= 2, "atan2 is {worst} ulp from the library");
        // exact cases and the edges, as the library has them
        for (y, x) in [
            (0.0, 1.0),
            (-0.0, 1.0),
            (0.0, -1.0),
            (-0.0, -1.0),
            (1.0, 0.0),
            (-1.0, 0.0),
            (0.0, 0.0),
            (0.0, -0.0),
            (1.0, f64::INFINITY),
            (f64::INFINITY, 1.0),
            (f64::INFINITY, f64::NEG_INFINITY),
            (1e-320, 1.0),
            (1.0, 1e-320),
        ] {
            assert_eq!(atan2(y, x).to_bits(), y.atan2(x).to_bits(), "atan2({y}, {x})");
        }
        assert!(atan2(f64::NAN, 1.0).is_nan() && atan2(1.0, f64::NAN).is_nan());
        assert_eq!(atan2(1.0, 1.0), FRAC_PI_4);
        assert_eq!(atan2(0.5, -0.5), 3.0 * FRAC_PI_4);
    }
}
