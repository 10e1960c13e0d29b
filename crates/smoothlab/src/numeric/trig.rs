//! `sin` and `cos` in plain arithmetic, for the generators: the platform's own functions
//! differ in the last bit between the native C library and WebAssembly, and a sample
//! that differs by one bit in one coordinate is smoothed to a visibly different result
//! (the page's tangled plate ended with another smallest angle in the browser than in the
//! CLI). With these a generated sample is the same mesh, bit for bit, everywhere.

use std::f64::consts::FRAC_PI_2;

/// π/2 in three parts (Cody–Waite, as fdlibm): the first two rounded to 33 bits, so
/// `k·PIO2_HI` and `k·PIO2_LO` are exact for |k| < 2^20; the sum is π/2 to about 2^-120.
const PIO2_HI: f64 = 1.570_796_326_734_125_6;
const PIO2_LO: f64 = 6.077_100_506_303_966e-11;
const PIO2_LO2: f64 = 2.022_266_248_795_950_6e-21;

/// `(sin x, cos x)` within about one unit in the last place for |x| < 2^20 (the
/// generators' angles are a few turns at most), from Taylor polynomials on [−π/4, π/4]
/// after reduction by multiples of π/2. The same on every platform: only `+ − ×` and
/// rounding to nearest, in a fixed order.
pub(crate) fn sin_cos(x: f64) -> (f64, f64) {
    let k = (x / FRAC_PI_2).round();
    let r = ((x - k * PIO2_HI) - k * PIO2_LO) - k * PIO2_LO2;
    let r2 = r * r;
    // sin r = r − r³/3! + … − r¹⁹/19!, cos r = 1 − r²/2! + … + r²⁰/20!: the first
    // omitted terms are below 2^-60 for |r| ≤ π/4
    const S: [f64; 9] = [
        -1.0 / 6.0,
        1.0 / 120.0,
        -1.0 / 5040.0,
        1.0 / 362_880.0,
        -1.0 / 39_916_800.0,
        1.0 / 6_227_020_800.0,
        -1.0 / 1_307_674_368_000.0,
        1.0 / 355_687_428_096_000.0,
        -1.0 / 121_645_100_408_832_000.0,
    ];
    const C: [f64; 10] = [
        -1.0 / 2.0,
        1.0 / 24.0,
        -1.0 / 720.0,
        1.0 / 40_320.0,
        -1.0 / 3_628_800.0,
        1.0 / 479_001_600.0,
        -1.0 / 87_178_291_200.0,
        1.0 / 20_922_789_888_000.0,
        -1.0 / 6_402_373_705_728_000.0,
        1.0 / 2_432_902_008_176_640_000.0,
    ];
    let s = r + r * r2 * S.iter().rev().fold(0.0, |acc, &c| acc * r2 + c);
    let c = 1.0 + r2 * C.iter().rev().fold(0.0, |acc, &c| acc * r2 + c);
    match (k as i64).rem_euclid(4) {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

/// `cos x` ([`sin_cos`]).
pub(crate) fn cos(x: f64) -> f64 {
    sin_cos(x).1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn agrees_with_the_platform_to_an_ulp_or_two() {
        let mut worst: f64 = 0.0;
        for i in -20_000..=20_000 {
            let x = i as f64 * 0.000_73 + 0.1 * (i % 7) as f64;
            let (s, c) = sin_cos(x);
            worst = worst.max((s - x.sin()).abs()).max((c - x.cos()).abs());
        }
        assert!(worst < 4.0 * f64::EPSILON, "worst difference {worst:e}");
    }

    #[test]
    fn exact_at_the_quadrants_and_symmetric() {
        assert_eq!(sin_cos(0.0), (0.0, 1.0));
        let (s, c) = sin_cos(FRAC_PI_2);
        assert!((s - 1.0).abs() <= f64::EPSILON && c.abs() < 1e-16);
        for x in [0.3, 1.1, 2.9, 7.7] {
            let (s, c) = sin_cos(x);
            let (sn, cn) = sin_cos(-x);
            assert_eq!((sn, cn), (-s, c), "odd sine, even cosine at {x}");
            assert!((s * s + c * c - 1.0).abs() < 4.0 * f64::EPSILON);
        }
    }
}
