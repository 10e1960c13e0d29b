//! `exp` and `atan2` for the metrics and the `new` objective's inner loop.
//!
//! One evaluation of Chen et al.'s objective on a star of six triangles takes twelve
//! `atan2` and twenty-four `exp` (the signed angles and penalties of eqs. 6–8), and a
//! smoothing visit about thirteen evaluations. Natively these forward to the C library,
//! whose functions are the fastest we measured (glibc picks FMA versions at run time: an
//! `opt`+`new` pass on a 100k rand2d took 1.35–1.42 s with them, 1.38–1.54 s with the
//! inlined `atan2` below and 1.78–1.97 s with the inlined `exp`). In WebAssembly the
//! library is a compiled port of fdlibm, whose `exp` waits on a division; there
//! [`exp_inline`] (table-driven, no division) and [`atan2_inline`] (Cephes' rational `atan`,
//! octant reduction done once) are used: the wasm bench's `opt`+`new` went from 25 to
//! 17 µs per visit. Both use only `+ − × ÷`, table lookups and bit operations, and are
//! tested against the library over millions of arguments: within 2 ulp.
//!
//! Zeros, infinities, NaN and arguments beyond the fast paths' ranges go to the standard
//! library, so the edge cases behave exactly as `f64::exp`/`f64::atan2` do.

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

/// `e^x`: the library's natively, [`exp_inline`] in WebAssembly (see the module docs).
#[inline(always)]
pub fn exp(x: f64) -> f64 {
    if cfg!(target_arch = "wasm32") {
        exp_inline(x)
    } else {
        x.exp()
    }
}

/// `atan2(y, x)`: the library's natively, [`atan2_inline`] in WebAssembly.
#[inline(always)]
pub fn atan2(y: f64, x: f64) -> f64 {
    if cfg!(target_arch = "wasm32") {
        atan2_inline(y, x)
    } else {
        y.atan2(x)
    }
}

/// `2^(j/64)`, j = 0..63, correctly rounded.
#[allow(clippy::excessive_precision, clippy::approx_constant)]
const EXP2_64THS: [f64; 64] = [
    1.0, 1.0108892860517005, 1.0218971486541166, 1.0330248790212284,
    1.0442737824274138, 1.0556451783605572, 1.0671404006768237, 1.0787607977571199,
    1.0905077326652577, 1.102382583307841, 1.1143867425958924, 1.1265216186082418,
    1.1387886347566916, 1.1511892299529827, 1.1637248587775775, 1.1763969916502812,
    1.189207115002721, 1.202156731452703, 1.215247359980469, 1.22848053610687,
    1.241857812073484, 1.255380757024691, 1.2690509571917332, 1.2828700160787783,
    1.2968395546510096, 1.3109612115247644, 1.3252366431597413, 1.339667524053303,
    1.3542555469368927, 1.3690024229745905, 1.383909881963832, 1.3989796725383112,
    1.4142135623730951, 1.42961333839197, 1.4451808069770467, 1.460917794180647,
    1.4768261459394993, 1.4929077282912648, 1.5091644275934228, 1.5255981507445384,
    1.5422108254079407, 1.559004400237837, 1.5759808451078865, 1.593142151342267,
    1.6104903319492543, 1.6280274218573478, 1.645755478153965, 1.6636765803267364,
    1.681792830507429, 1.7001063537185235, 1.718619298122478, 1.7373338352737062,
    1.7562521603732995, 1.7753764925265212, 1.7947090750031072, 1.8142521755003989,
    1.8340080864093424, 1.8539791250833855, 1.8741676341103, 1.8945759815869656,
    1.9152065613971474, 1.9360617934922943, 1.9571441241754002, 1.978456026387951,
];

/// `e^x`. `x = (64k + j)·ln2/64 + r` with `|r| ≤ ln2/128` (ln2/64 split in a high part
/// exact in products with the integer and a low part), `e^x = 2^k · 2^(j/64) · e^r`, and
/// `e^r − 1` by its Taylor polynomial of degree 5 (the next term is below 4·10⁻¹⁷ of 1).
#[inline(always)]
#[allow(clippy::excessive_precision)] // fdlibm's split of ln 2, as printed
pub fn exp_inline(x: f64) -> f64 {
    const INV_LN2_64: f64 = 64.0 * std::f64::consts::LOG2_E;
    // fdlibm's split of ln 2 (the high part has 32 significant bits), divided by 64 (exact)
    const LN2_64_HI: f64 = 6.931_471_803_691_238_164_90e-1 / 64.0;
    const LN2_64_LO: f64 = 1.908_214_929_270_587_700_02e-10 / 64.0;
    // the library handles overflow, underflow, subnormals and NaN
    if x.is_nan() || x.abs() >= 708.0 {
        return x.exp();
    }
    // nearest integer to 64x/ln2 (a cast: `round` is a library call on baseline x86-64);
    // |m| < 2^17, so m·LN2_64_HI is exact
    let t = x * INV_LN2_64;
    let m = (t + if t < 0.0 { -0.5 } else { 0.5 }) as i64;
    let mf = m as f64;
    let r = (x - mf * LN2_64_HI) - mf * LN2_64_LO;
    let p = r + r * r * (0.5 + r * (1.0 / 6.0 + r * (1.0 / 24.0 + r * (1.0 / 120.0))));
    let two_j = EXP2_64THS[(m & 63) as usize];
    // m >> 6 is floor(m / 64): |k| ≤ 1022, so 2^k is a normal number
    let scale = f64::from_bits((((m >> 6) + 1023) as u64) << 52);
    (two_j + two_j * p) * scale
}

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
/// to the larger of `|x|`, `|y|` through `atan_unit`, then placed in its octant.
#[inline(always)]
pub fn atan2_inline(y: f64, x: f64) -> f64 {
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
        let mut g = crate::numeric::SplitMix64::new(seed);
        std::iter::repeat_with(move || g.uniform(lo, hi))
    }

    #[test]
    fn exp_is_within_two_ulp_of_the_library() {
        let mut worst = 0;
        // the objective's range (|−k2 ω| < 7, 2θ − 2π in [−4π, 0]) densely, then everything
        for (lo, hi, n) in [(-13.0, 8.0, 2_000_000), (-708.0, 708.0, 1_000_000), (-1e-6, 1e-6, 100_000)] {
            for x in uniform(7, lo, hi).take(n) {
                worst = worst.max(ulps(exp_inline(x), x.exp()));
            }
        }
        assert!(worst <= 2, "exp is {worst} ulp from the library");
        for x in [0.0, -0.0, 1.0, -1.0, 700.0, -700.0, 707.9, -707.9, 708.0, 709.5, 710.0, -745.0, -746.0, 1e300, -1e300] {
            let (a, b) = (exp_inline(x), x.exp());
            assert!(a == b || ulps(a, b) <= 2, "exp({x}) = {a}, library {b}");
        }
        assert_eq!(exp_inline(0.0), 1.0);
        assert_eq!(exp_inline(f64::INFINITY), f64::INFINITY);
        assert_eq!(exp_inline(f64::NEG_INFINITY), 0.0);
        assert!(exp_inline(f64::NAN).is_nan());
    }

    #[test]
    fn atan2_is_within_two_ulp_of_the_library() {
        let mut worst = 0;
        let xs = uniform(11, -3.0, 3.0);
        let ys = uniform(13, -3.0, 3.0);
        for (x, y) in xs.zip(ys).take(3_000_000) {
            worst = worst.max(ulps(atan2_inline(y, x), y.atan2(x)));
        }
        // near the axes and the diagonals, and over many scales
        let ts = uniform(17, -1.0, 1.0);
        let ss = uniform(19, -300.0, 300.0);
        for (t, s) in ts.zip(ss).take(1_000_000) {
            let r = 10f64.powf(s);
            for (x, y) in [(r, t * 1e-9 * r), (t * 1e-9 * r, r), (r, r * (1.0 + t * 1e-9)), (-r, t * r), (t * r, -r)] {
                worst = worst.max(ulps(atan2_inline(y, x), y.atan2(x)));
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
            assert_eq!(atan2_inline(y, x).to_bits(), y.atan2(x).to_bits(), "atan2({y}, {x})");
        }
        assert!(atan2_inline(f64::NAN, 1.0).is_nan() && atan2_inline(1.0, f64::NAN).is_nan());
        assert_eq!(atan2_inline(1.0, 1.0), FRAC_PI_4);
        assert_eq!(atan2_inline(0.5, -0.5), 3.0 * FRAC_PI_4);
    }
}
