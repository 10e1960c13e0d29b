//! The range of every setting of a smoothing run, written once: the command-line tool
//! checks its arguments with them, and the page's permalink, its controls and the
//! playground's settings (the page crate) read them here. The defaults are
//! [`SmoothOptions::default`](super::SmoothOptions) and the page's own.
//!
//! The page and its links allow fewer passes and iterations than the command-line tool:
//! a link opens in a browser tab and runs at once, so it must not run for hours; a batch
//! run is the user's own choice.

use serde::Serialize;

/// A whole-number setting: `min ..= max`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct IntRange {
    pub min: u64,
    pub max: u64,
}

impl IntRange {
    pub fn contains(&self, v: u64) -> bool {
        (self.min..=self.max).contains(&v)
    }
    /// The range in words, as messages say it.
    pub fn words(&self) -> String {
        format!("a whole number from {} to {}", self.min, self.max)
    }
}

/// Smoothing passes of one Run on the page (and in a permalink).
pub const PASSES: IntRange = IntRange { min: 1, max: 100 };
/// Solver iterations per optimization call on the page (and in a permalink).
pub const MAX_ITER: IntRange = IntRange { min: 1, max: 50 };
/// The perturbation's seed.
pub const SEED: IntRange = IntRange { min: 0, max: u64::MAX };
/// Largest perturbation amount, in mean edge lengths (the smallest is 0).
pub const MAX_AMOUNT: f64 = 2.0;
/// The page's slider step for the perturbation amount.
pub const AMOUNT_STEP: f64 = 0.05;
/// The threshold angles the page offers, degrees (any angle in `(0, 90]` is valid:
/// [`threshold_in_range`]).
pub const THRESHOLDS: [f64; 4] = [5.0, 10.0, 15.0, 30.0];
/// A node's number, as the page names the node whose level sets it shows.
pub const NODE: IntRange = IntRange { min: 0, max: u32::MAX as u64 };

/// Passes of one command-line run (`smooth --passes`): far beyond any use, small enough
/// that a typing slip does not run for hours.
pub const BATCH_PASSES: IntRange = IntRange { min: 1, max: 10_000 };
/// Passes before a picture is drawn (`render --passes`; 0 draws the mesh as loaded).
pub const RENDER_PASSES: IntRange = IntRange { min: 0, max: 1000 };
/// Solver iterations per call in a command-line run (`--max-iter`) and in the lab.
pub const BATCH_MAX_ITER: IntRange = IntRange { min: 1, max: 10_000 };

// a link may ask for no more than a batch run allows
const _: () = assert!(BATCH_PASSES.max >= PASSES.max && BATCH_MAX_ITER.max >= MAX_ITER.max);

/// Whether `t` degrees is a threshold angle θ_t of Freitag's combined strategies: finite,
/// above 0 and at most 90 ([`SmoothOptions::threshold_deg`](super::SmoothOptions::threshold_deg)).
pub fn threshold_in_range(t: f64) -> bool {
    t.is_finite() && t > 0.0 && t <= 90.0
}

/// The threshold angle's range in words.
pub const THRESHOLD_WORDS: &str = "an angle in degrees, more than 0 and at most 90";

/// Whether `a` mean edge lengths is a perturbation amount: `0 ..= MAX_AMOUNT`.
pub fn amount_in_range(a: f64) -> bool {
    (0.0..=MAX_AMOUNT).contains(&a)
}

/// The perturbation amount's range in words.
pub fn amount_words() -> String {
    format!("a number from 0 to {MAX_AMOUNT} (mean edge lengths)")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::smooth::{SmoothOptions, Strategy};

    #[test]
    fn the_defaults_lie_in_their_ranges_and_the_threshold_default_is_offered() {
        let d = SmoothOptions::default();
        assert!(PASSES.contains(crate::smooth::DEFAULT_PASSES.into()) && MAX_ITER.contains(d.max_iter.into()));
        assert!(BATCH_PASSES.contains(crate::smooth::DEFAULT_PASSES.into()) && BATCH_MAX_ITER.contains(d.max_iter.into()));
        assert!(THRESHOLDS.contains(&d.threshold_deg) && THRESHOLDS.iter().all(|&t| threshold_in_range(t)));
        assert!(RENDER_PASSES.contains(0) && RENDER_PASSES.contains(crate::smooth::DEFAULT_PASSES.into()));
    }

    #[test]
    fn the_ranges_say_their_ends() {
        assert_eq!(PASSES.words(), "a whole number from 1 to 100");
        assert!(!PASSES.contains(0) && PASSES.contains(100) && !PASSES.contains(101));
        assert!(NODE.contains(u32::MAX.into()) && !NODE.contains(u64::from(u32::MAX) + 1));
        for (t, ok) in [(0.0, false), (1e-300, true), (90.0, true), (90.0001, false), (f64::NAN, false), (f64::INFINITY, false)] {
            assert_eq!(threshold_in_range(t), ok, "{t}");
        }
        for (a, ok) in [(0.0, true), (-0.1, false), (MAX_AMOUNT, true), (2.5, false), (f64::NAN, false)] {
            assert_eq!(amount_in_range(a), ok, "{a}");
        }
        assert_eq!(amount_words(), "a number from 0 to 2 (mean edge lengths)");
    }

    #[test]
    fn only_the_combined_strategies_read_the_threshold_and_the_laplacians_never_solve() {
        let with_threshold: Vec<&str> =
            Strategy::ALL.iter().filter(|s| s.threshold_unused().is_none()).map(|s| s.name()).collect();
        assert_eq!(with_threshold, ["c1", "c2", "c3"]);
        let without_solver: Vec<&str> =
            Strategy::ALL.iter().filter(|s| s.max_iter_unused().is_some()).map(|s| s.name()).collect();
        assert_eq!(without_solver, ["laplace", "smart"]);
        assert!(Strategy::Rules.threshold_unused().unwrap().contains("Chen's rules decide by their own tests"));
        assert_eq!(Strategy::Opt.threshold_unused().unwrap(), "only Freitag's C1, C2 and C3 use a threshold angle, not optimization only");
        assert_eq!(Strategy::Smart.max_iter_unused().unwrap(), "the smart Laplacian never calls the solver, so it has no iterations to limit");
    }
}
