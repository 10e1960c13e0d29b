//! Scale and robust numerics at the bottom of the core, and its one random generator.
//!
//! Every metric, objective and solver is a ratio of lengths, so it may be evaluated in
//! any scale; these are the helpers that pick that scale by a power of two (exact, so the
//! bits of an ordinary mesh's results do not change) where squares and cross products
//! would leave the doubles, and measure lengths without over- or underflow.
//! [`SplitMix64`] is the deterministic generator behind every seeded sample and every
//! randomised test; [`order`] holds the one sort the orderings by a float and the stable
//! sorts by a key share. [`elementary`] holds `exp` and `atan2` for the metrics' inner
//! loops, and `trig` the generators' `sin` and `cos`, the same bits on every platform.

use glam::{DVec2, DVec3};

pub(crate) mod dyadic;
pub mod elementary;
pub mod exact;
pub mod order;
mod prng;
pub(crate) mod trig;

pub use prng::SplitMix64;

/// Edge vectors whose largest component lies in 2^±200 are measured as they are: every
/// product the metrics take of them is a normal double (see `quality::corner_edges`);
/// beyond it they are brought to unit scale first. One range for every metric and
/// objective.
pub(crate) const SAFE_SCALE: std::ops::RangeInclusive<f64> = 6.223_015_277_861_142e-61..=1.606_938_044_258_990_3e60;

/// The largest `|component|` of `values` (vectors or numbers): the scale the metrics
/// measure edges against, 0 for none. The fold of `f64::max` from 0 over each value's
/// magnitude (a vector's by glam's `abs().max_element()`), bit for bit, not-a-number
/// components included, by one comparison a value: the running largest is always a number
/// ≥ +0, so `f64::max`'s other question, whether it is a number, is never needed, and
/// wasm pays it as a compare and two selects where x86 takes one `maxsd`.
#[inline(always)]
pub(crate) fn largest_component<V: Components>(values: impl IntoIterator<Item = V>) -> f64 {
    values.into_iter().fold(0.0, |m, v| above(m, v.magnitude()))
}

/// What [`largest_component`] reads of a value.
pub(crate) trait Components: Copy {
    /// Its largest component's magnitude (≥ +0, or not a number).
    fn magnitude(self) -> f64;
}

/// `m.max(a)` for a number `m`: a not-a-number `a` leaves `m`.
#[inline(always)]
fn above(m: f64, a: f64) -> f64 {
    if a > m {
        a
    } else {
        m
    }
}

impl Components for f64 {
    #[inline(always)]
    fn magnitude(self) -> f64 {
        self.abs()
    }
}

impl Components for DVec2 {
    #[inline(always)]
    fn magnitude(self) -> f64 {
        self.abs().max_element()
    }
}

impl Components for DVec3 {
    #[inline(always)]
    fn magnitude(self) -> f64 {
        self.abs().max_element()
    }
}

impl<V: Components> Components for &V {
    #[inline(always)]
    fn magnitude(self) -> f64 {
        (*self).magnitude()
    }
}

/// Multiplies the vectors by a power of two (exact) that brings their largest component
/// into [1, 2), and returns it as two finite factors whose product it is (it may itself
/// be beyond the doubles, 2^1074 for the smallest subnormal); leaves the vectors as they
/// are, returning `[1, 1]`, when they are all zero (or not finite).
pub fn to_unit_scale(v: &mut [DVec2]) -> [f64; 2] {
    let m = largest_component(v.iter().flat_map(|p| [p.x, p.y]));
    if m == 0.0 || !m.is_finite() {
        return [1.0, 1.0];
    }
    // from far outside [2^-598, 2^598] in one step first, so the final factor (the inverse
    // of m's power of two) is itself a finite double
    let pre = if m < pow2(-598) {
        pow2(598)
    } else if m > pow2(598) {
        pow2(-598)
    } else {
        1.0
    };
    if pre != 1.0 {
        for p in v.iter_mut() {
            *p *= pre;
        }
    }
    let unit = f64::from_bits((m * pre).to_bits() & 0x7ff0_0000_0000_0000);
    let inv = 1.0 / unit;
    if inv != 1.0 {
        for p in v.iter_mut() {
            *p *= inv;
        }
    }
    [pre, inv]
}

/// `2^e` for a normal exponent (|e| ≤ 1022).
#[inline]
pub(crate) fn pow2(e: i32) -> f64 {
    f64::from_bits(((e + 1023) as u64) << 52)
}

/// Two finite powers of two whose product brings a positive finite `m` to about 1 (the
/// product itself may be beyond the doubles: 2^1074 for the smallest subnormal).
pub(crate) fn unit_factors(m: f64) -> (f64, f64) {
    let k = m.log2().floor() as i32;
    (2f64.powi(-k / 2), 2f64.powi(-k - (-k / 2)))
}

/// Whether vectors whose largest component is `m` need bringing to unit scale: `m` lies
/// beyond [`SAFE_SCALE`], and is neither zero nor non-finite (which no factor helps:
/// such vectors are taken as they are).
#[inline]
pub(crate) fn is_beyond_safe_scale(m: f64) -> bool {
    !(SAFE_SCALE.contains(&m) || m == 0.0 || !m.is_finite())
}

/// [`unit_factors`] of a size `m` (a largest component) when it
/// [`is_beyond_safe_scale`]; `None` otherwise.
#[inline]
pub(crate) fn factors_beyond_safe_scale(m: f64) -> Option<(f64, f64)> {
    is_beyond_safe_scale(m).then(|| unit_factors(m))
}

/// A vector whose largest component lies beyond 2^±300 multiplied by a power of two
/// (exact) that brings it near 1; as it is within. Quotients of its components, and its
/// direction, do not change.
#[inline]
pub(crate) fn near_unit_vector(v: DVec3) -> DVec3 {
    exact::near_unit(largest_component([v]))(v)
}

/// Vectors of size beyond [`SAFE_SCALE`] multiplied by one power of two (exact) that
/// brings their largest component to about 1, so that their cross products and squares
/// are normal doubles; as they are inside it.
pub(crate) fn in_unit_scale_3d<const N: usize>(v: [DVec3; N]) -> [DVec3; N] {
    let m = largest_component(v);
    match factors_beyond_safe_scale(m) {
        None => v,
        Some((f1, f2)) => v.map(|x| x * f1 * f2),
    }
}

/// The unit vector along `v`, zero when `v` is zero or not finite: `normalize_or_zero`
/// at every magnitude. Where `v`'s squared length would leave the doubles (a normal of
/// elements of size 1e±80 is a cross product of size 1e±160) `v` is first multiplied by a
/// power of two (exact), which changes neither its direction nor, where it was not
/// needed, the bits of the result.
pub fn direction(v: DVec3) -> DVec3 {
    let m = v.abs().max_element();
    if !(m > 0.0 && m.is_finite()) {
        return DVec3::ZERO;
    }
    if (pow2(-500)..=pow2(500)).contains(&m) {
        return v.normalize_or_zero();
    }
    let (f1, f2) = unit_factors(m);
    (v * f1 * f2).normalize_or_zero()
}

/// The power of two that brings a star of size `scale` to [1, 2), when the size is
/// beyond 2^±64 (and the factor and its inverse are finite); `None` otherwise.
pub fn unit_factor(scale: f64) -> Option<f64> {
    const WINDOW: f64 = 18_446_744_073_709_551_616.0; // 2^64
    if !scale.is_normal() || (1.0 / WINDOW..=WINDOW).contains(&scale) {
        return None;
    }
    let e = ((scale.to_bits() >> 52) & 0x7ff) as i32 - 1023;
    // 2^-e and 2^e are both finite normal numbers for |e| ≤ 1022
    (e.abs() <= 1022).then(|| 2f64.powi(-e))
}

/// `|v|` without overflow or underflow of the squares.
pub(crate) fn robust_length(v: DVec2) -> f64 {
    let m = v.x.abs().max(v.y.abs());
    if m == 0.0 || !m.is_finite() {
        return m;
    }
    m * (v / m).length()
}

/// The cube root to within one unit in the last place, for the smooth objectives' terms,
/// where it is about five times cheaper than [`f64::cbrt`] (correctly rounded: what the
/// statistics and the max-min objectives keep using, so their bits never depend on this).
///
/// Bruce Evans' method (FreeBSD's `s_cbrt.c`, also musl's): a first guess from the
/// exponent's bits divided by 3, a polynomial that takes it to 23 bits, rounded to 21 bits
/// so the next step's products are exact, then one Halley step (error below 0.667 ulp).
/// Zero, infinities and NaN are returned as `f64::cbrt` returns them; subnormals are scaled
/// by 2^54 first.
#[inline]
pub fn cbrt_fast(x: f64) -> f64 {
    // the exponent's bits over 3, biased so the guess is within 4 % of the root
    const B1: u32 = 715_094_163; // (1023 − 1023/3 − 0.03306235651)·2^20
    const B2: u32 = 696_219_795; // (1023 − 1023/3 − 54/3 − 0.03306235651)·2^20
    // |1/cbrt(r) − p(r)| < 2^−23.5 on the guess's range
    const P0: f64 = 1.875_951_824_271_77;
    const P1: f64 = -1.884_979_795_433_771_7;
    const P2: f64 = 1.621_429_720_105_354_5;
    const P3: f64 = -0.758_397_934_778_766;
    const P4: f64 = 0.145_996_192_886_612_45;
    let bits = x.to_bits();
    let mut hx = (bits >> 32) as u32 & 0x7fff_ffff;
    if hx >= 0x7ff0_0000 {
        return x + x; // infinity or NaN
    }
    if hx < 0x0010_0000 {
        // zero or subnormal
        let scaled = (x * f64::from_bits(0x4350_0000_0000_0000)).to_bits(); // 2^54
        hx = (scaled >> 32) as u32 & 0x7fff_ffff;
        if hx == 0 {
            return x;
        }
        hx = hx / 3 + B2;
    } else {
        hx = hx / 3 + B1;
    }
    let mut t = f64::from_bits((bits & (1 << 63)) | (u64::from(hx) << 32));
    // to 23 bits: t·p(t³/x)
    let r = (t * t) * (t / x);
    t *= (P0 + r * (P1 + r * P2)) + ((r * r) * r) * (P3 + r * P4);
    // round t away from zero to 21 bits, so t·t is exact and |t| > |cbrt(x)| slightly
    t = f64::from_bits((t.to_bits().wrapping_add(0x8000_0000)) & 0xffff_ffff_c000_0000);
    // one Halley step: t + t·(x/t² − t)/(2t + x/t²)
    let s = t * t;
    let r = x / s;
    let w = t + t;
    let r = (r - t) / (w + r);
    t + t * r
}

#[cfg(test)]
mod tests {
    /// The largest component by comparisons is the fold of `f64::max` from 0 that the
    /// metrics took before, bit for bit: over vectors of random bits (every scale, both
    /// signs and zeros, infinities and NaNs among them) and of ordinary numbers.
    #[test]
    fn largest_component_is_the_max_fold() {
        use glam::{DVec2, DVec3};
        let mut rng = SplitMix64::new(5);
        let special = |rng: &mut SplitMix64| match rng.next_u64() % 8 {
            0 => f64::NAN,
            1 => -0.0,
            2 => 0.0,
            3 => f64::INFINITY * if rng.next_u64() % 2 == 0 { 1.0 } else { -1.0 },
            4 | 5 => f64::from_bits(rng.next_u64()),
            _ => rng.uniform(-2.0, 2.0),
        };
        let mut nan_skipped = 0;
        for round in 0..20_000 {
            let n = round % 7;
            let v2: Vec<DVec2> = (0..n).map(|_| DVec2::new(special(&mut rng), special(&mut rng))).collect();
            let v3: Vec<DVec3> = (0..n).map(|_| DVec3::new(special(&mut rng), special(&mut rng), special(&mut rng))).collect();
            let fold2 = v2.iter().fold(0.0f64, |m, v| m.max(v.abs().max_element()));
            let fold3 = v3.iter().fold(0.0f64, |m, v| m.max(v.abs().max_element()));
            let scalars: Vec<f64> = v3.iter().flat_map(|v| v.to_array()).collect();
            let fold1 = scalars.iter().fold(0.0f64, |m, c| m.max(c.abs()));
            assert_eq!(largest_component(&v2).to_bits(), fold2.to_bits(), "{v2:?}");
            assert_eq!(largest_component(&v3).to_bits(), fold3.to_bits(), "{v3:?}");
            assert_eq!(largest_component(&scalars).to_bits(), fold1.to_bits(), "{scalars:?}");
            nan_skipped += v3.iter().any(|v| v.is_nan()) as u32;
        }
        assert!(nan_skipped > 1000, "NaNs among the inputs: {nan_skipped}");
        assert_eq!(largest_component(std::iter::empty::<f64>()).to_bits(), 0.0f64.to_bits());
    }

    /// Within one unit in the last place of the correctly rounded root, over every scale
    /// (subnormals included) and both signs; special values as `f64::cbrt`.
    #[test]
    fn cbrt_fast_is_within_one_ulp() {
        let ulps = |a: f64, b: f64| (a.to_bits() as i64 - b.to_bits() as i64).abs();
        let mut rng = SplitMix64::new(33);
        let mut worst = 0;
        for _ in 0..200_000 {
            let bits = rng.next_u64() & !(1 << 63);
            let x = f64::from_bits(bits);
            if !x.is_finite() {
                continue;
            }
            for x in [x, -x] {
                worst = worst.max(ulps(cbrt_fast(x), x.cbrt()));
            }
        }
        for k in 1..=1000 {
            let x = k as f64 * 0.37;
            worst = worst.max(ulps(cbrt_fast(x), x.cbrt()));
            let cube = (k * k * k) as f64;
            assert_eq!(cbrt_fast(cube), k as f64, "the cube of {k}");
        }
        assert!(worst <= 1, "{worst} ulps");
        for x in [0.0, -0.0, f64::INFINITY, f64::NEG_INFINITY, f64::MIN_POSITIVE / 8.0, 5e-324] {
            assert_eq!(cbrt_fast(x).to_bits(), x.cbrt().to_bits(), "{x}");
        }
        assert!(cbrt_fast(f64::NAN).is_nan());
    }

    use super::*;

    #[test]
    fn the_safe_scale_is_two_to_the_plus_minus_200() {
        assert_eq!((*SAFE_SCALE.start(), *SAFE_SCALE.end()), (pow2(-200), pow2(200)));
    }

    #[test]
    fn beyond_the_safe_scale_the_factors_bring_the_size_to_about_one() {
        for m in [1.0, pow2(-200), pow2(200), 0.0, f64::INFINITY, f64::NAN] {
            assert_eq!(factors_beyond_safe_scale(m), None, "{m}");
        }
        for m in [pow2(201) * 1.5, 1e300, pow2(-201), 1e-300, 5e-324] {
            let (f1, f2) = factors_beyond_safe_scale(m).unwrap();
            let unit = m * f1 * f2;
            assert!((0.5..=2.0).contains(&unit), "{m}: {unit}");
        }
    }

    #[test]
    fn lengths_and_directions_at_every_scale() {
        for s in [1.0, 1e-300, 1e300, 5e-324] {
            let v = DVec2::new(3.0, 4.0) * s;
            let l = robust_length(v);
            assert!((l / s - 5.0).abs() < 1e-12 || s == 5e-324, "{s}: {l}");
            let d = direction(DVec3::new(3.0, 0.0, 4.0) * s);
            assert!((d - DVec3::new(0.6, 0.0, 0.8)).length() < 1e-15, "{s}: {d}");
        }
        assert_eq!(robust_length(DVec2::ZERO), 0.0);
        assert_eq!(direction(DVec3::ZERO), DVec3::ZERO);
        assert_eq!(unit_factor(1.0), None);
        assert_eq!(unit_factor(1e30), Some(pow2(-99)));
        assert_eq!(1e-30 * unit_factor(1e-30).unwrap(), 1e-30 * pow2(100));
    }
}
