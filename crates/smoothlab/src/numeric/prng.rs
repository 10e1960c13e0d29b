//! SplitMix64, the tiny deterministic generator behind every seeded sample mesh and every
//! randomised test.
//!
//! SplitMix64 (Steele, Lea & Flood, "Fast splittable pseudorandom number generators",
//! OOPSLA 2014; the constants of Vigna's public-domain C version) is a 64-bit counter
//! passed through a bijective mixer. It is written out here rather than taken from a
//! crate so its stream can never change under us: the same seed gives the same bits on
//! every platform and with every compiler, and the sample meshes built from it use only
//! exactly rounded arithmetic (`+ − × ÷`, comparisons), never `sin`/`cos`/`sqrt`, on the
//! random numbers. It is not a cryptographic generator.

use glam::DVec2;

/// The SplitMix64 generator: 64 bits of state, one `u64` per step.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SplitMix64 {
    state: u64,
}

impl SplitMix64 {
    /// A generator whose stream is fixed by `seed` (any value, 0 included).
    pub fn new(seed: u64) -> Self {
        SplitMix64 { state: seed }
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A uniform number in `[0, 1)`: the top 53 bits scaled by `2⁻⁵³` (exact).
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// A uniform number in `[lo, hi)` (rounding aside): `lo + (hi − lo)·u` with `u` from
    /// [`next_f64`](Self::next_f64).
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next_f64()
    }

    /// A point uniformly distributed in the open unit disk, by rejection from the
    /// square `[−1, 1)²` (on average 1.27 pairs of draws; exact arithmetic only).
    pub fn in_unit_disk(&mut self) -> DVec2 {
        loop {
            let p = DVec2::new(2.0 * self.next_f64() - 1.0, 2.0 * self.next_f64() - 1.0);
            if p.length_squared() < 1.0 {
                return p;
            }
        }
    }

    /// A point uniformly distributed in the open unit ball, by rejection from the cube
    /// `[−1, 1)³` (on average 1.91 triples of draws).
    pub fn in_unit_ball(&mut self) -> glam::DVec3 {
        loop {
            let p =
                glam::DVec3::new(2.0 * self.next_f64() - 1.0, 2.0 * self.next_f64() - 1.0, 2.0 * self.next_f64() - 1.0);
            if p.length_squared() < 1.0 {
                return p;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_the_reference_stream() {
        // First outputs of Vigna's splitmix64.c seeded with 0.
        let mut g = SplitMix64::new(0);
        assert_eq!(g.next_u64(), 0xE220_A839_7B1D_CDAF);
        assert_eq!(g.next_u64(), 0x6E78_9E6A_A1B9_65F4);
        assert_eq!(g.next_u64(), 0x06C4_5D18_8009_454F);
    }

    #[test]
    fn unit_interval_and_disk() {
        let mut g = SplitMix64::new(42);
        let (mut lo, mut hi, mut sum) = (1.0f64, 0.0f64, 0.0);
        for _ in 0..10_000 {
            let u = g.next_f64();
            assert!((0.0..1.0).contains(&u));
            lo = lo.min(u);
            hi = hi.max(u);
            sum += u;
        }
        assert!(lo < 0.01 && hi > 0.99, "covers the interval: {lo} {hi}");
        assert!((sum / 10_000.0 - 0.5).abs() < 0.02, "mean near 1/2: {}", sum / 10_000.0);
        // uniform in the disk: a quarter of the points within radius 1/2
        let inner = (0..10_000)
            .map(|_| g.in_unit_disk())
            .inspect(|p| assert!(p.length_squared() < 1.0))
            .filter(|p| p.length() < 0.5)
            .count();
        assert!((inner as f64 / 10_000.0 - 0.25).abs() < 0.02, "{inner}");
    }
}
