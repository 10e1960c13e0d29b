//! The range of every setting, written once: the page's controls (their `min`, `max` and
//! `step` come from [`page_controls`]), the permalink's decoder, the playground's
//! [`Settings`](crate::lab::Settings) and the command-line tool all read them here. The
//! defaults are [`PageState::default`](crate::permalink::PageState) (itself built on
//! [`SmoothOptions::default`](crate::smooth::SmoothOptions)).
//!
//! The page and its links allow fewer passes and iterations than the command-line tool:
//! a link opens in a browser tab and runs at once, so it must not run for hours; a batch
//! run is the user's own choice.

use serde::Serialize;

use crate::permalink::PageState;
use crate::smooth::Strategy;

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
/// The threshold angles the page offers, degrees (any angle in `(0, 90]` is valid).
pub const THRESHOLDS: [f64; 4] = [5.0, 10.0, 15.0, 30.0];

/// Passes of one command-line run (`smooth --passes`, `render --passes`): far beyond any
/// use, small enough that a typing slip does not run for hours.
pub const BATCH_PASSES: IntRange = IntRange { min: 1, max: 10_000 };
/// Solver iterations per call in a command-line run (`--max-iter`) and in the lab.
pub const BATCH_MAX_ITER: IntRange = IntRange { min: 1, max: 10_000 };

/// Why the threshold angle does nothing for `s`, if it does nothing (only Freitag's
/// combined strategies C1–C3 compare a star's minimum angle with it).
pub fn threshold_unused(s: Strategy) -> Option<String> {
    match s {
        Strategy::C1 | Strategy::C2 | Strategy::C3 => None,
        Strategy::Rules => {
            Some("Chen's rules decide by their own tests (curved boundary, invalid element, Laplacian failed), not by an angle".into())
        }
        Strategy::Laplace | Strategy::Smart | Strategy::Opt => {
            Some(format!("only Freitag's C1, C2 and C3 use a threshold angle, not {}", strategy_words(s)))
        }
    }
}

/// Why the solver's iteration limit does nothing for `s`, if it does nothing (the
/// Laplacian strategies never call the solver).
pub fn max_iter_unused(s: Strategy) -> Option<String> {
    match s {
        Strategy::Laplace | Strategy::Smart => {
            Some(format!("{} never calls the solver, so it has no iterations to limit", strategy_words(s)))
        }
        Strategy::Opt | Strategy::C1 | Strategy::C2 | Strategy::C3 | Strategy::Rules => None,
    }
}

// a link may ask for no more than a batch run allows
const _: () = assert!(BATCH_PASSES.max >= PASSES.max && BATCH_MAX_ITER.max >= MAX_ITER.max);

/// A strategy as people name it.
pub fn strategy_words(s: Strategy) -> &'static str {
    match s {
        Strategy::Laplace => "the Laplacian",
        Strategy::Smart => "the smart Laplacian",
        Strategy::Opt => "optimization only",
        Strategy::C1 => "Freitag's C1",
        Strategy::C2 => "Freitag's C2",
        Strategy::C3 => "Freitag's C3",
        Strategy::Rules => "Chen's rules",
    }
}

/// The label of each control the user types into, by its permalink key: in the page's
/// tooltips and in every message about the control.
const CONTROL_LABELS: [(&str, &str); 5] = [
    ("passes", "Passes"),
    ("maxiter", "Max iterations"),
    ("seed", "Seed"),
    ("tangle", "Perturb amount"),
    ("threshold", "Threshold angle"),
];

/// The label of the control behind a permalink key, if the user types it.
pub fn control_label(key: &str) -> Option<&'static str> {
    CONTROL_LABELS.iter().find(|(k, _)| *k == key).map(|(_, l)| *l)
}

fn label(key: &str) -> &'static str {
    control_label(key).expect("a key of CONTROL_LABELS")
}

/// A whole-number control of the page.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct IntControl {
    pub label: &'static str,
    /// Limits as text: a seed may be beyond what a JS number holds exactly.
    pub min: String,
    pub max: String,
    pub default: String,
    pub words: String,
}

/// The perturbation amount's slider.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct AmountControl {
    pub label: &'static str,
    pub min: f64,
    pub max: f64,
    pub step: f64,
    pub default: f64,
    pub words: String,
}

/// The threshold menu.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ThresholdControl {
    pub label: &'static str,
    pub options: Vec<f64>,
    pub default: f64,
}

/// One strategy: its name, its menu entry, and why each control does nothing with it
/// (`null`: it matters).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StrategyInfo {
    pub name: &'static str,
    /// The menu's text and tooltip ([`Strategy::label`], [`Strategy::describe`]).
    pub label: &'static str,
    pub title: &'static str,
    pub words: &'static str,
    pub threshold_unused: Option<String>,
    pub max_iter_unused: Option<String>,
}

/// A name a menu offers, with its words for people.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Named {
    pub name: &'static str,
    pub words: &'static str,
}

/// An entry of a menu: the value, its text and its tooltip.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MenuEntry {
    pub name: &'static str,
    pub label: &'static str,
    pub title: &'static str,
}

/// One panel of the page: its permalink letter, its colour everywhere, and what it
/// compares by default (`objective`, `penalty`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PanelInfo {
    pub side: crate::lab::Side,
    pub letter: &'static str,
    /// The side's colour in the light theme, and in the dark one (`render::Theme`).
    pub rgb: [u8; 3],
    pub rgb_dark: [u8; 3],
    pub objective: &'static str,
    pub penalty: &'static str,
}

/// Everything the page needs to build and check its controls, keyed by the permalink's
/// keys: `{ settings, passes, maxiter, seed, amount, threshold, strategies, orders,
/// objectives, penalties, panels }`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PageControls {
    /// The default settings (strategy, order, …), which the menus start on.
    pub settings: crate::lab::Settings,
    pub passes: IntControl,
    pub maxiter: IntControl,
    pub seed: IntControl,
    pub amount: AmountControl,
    pub threshold: ThresholdControl,
    pub strategies: Vec<StrategyInfo>,
    /// Every visit order ([`Order::ALL`](crate::smooth::Order::ALL)).
    pub orders: Vec<MenuEntry>,
    /// Every objective a panel can run ([`ObjectiveKind::ALL`](crate::objective::ObjectiveKind::ALL)).
    pub objectives: Vec<Named>,
    /// The designs of `new`'s penalty ([`Penalty::ALL`](crate::objective::Penalty::ALL)).
    pub penalties: Vec<Named>,
    /// The left panel (A), then the right (B).
    pub panels: Vec<PanelInfo>,
    /// The file input's extensions (`.msh`, …, every [`Format`](crate::io::Format)'s) and
    /// the same in words.
    pub file_extensions: Vec<String>,
    pub file_extensions_words: String,
    /// The quality colour map's anchors (viridis, 0 to 1), for the page's own colour key
    /// where a canvas is too small for the drawn colour bar.
    pub quality_ramp: [[u8; 3]; 9],
}

fn int_control(label: &'static str, r: IntRange, default: u64) -> IntControl {
    IntControl { label, min: r.min.to_string(), max: r.max.to_string(), default: default.to_string(), words: r.words() }
}

/// The page's controls with their ranges and defaults (see the module notes).
pub fn page_controls() -> PageControls {
    let d = PageState::default();
    PageControls {
        settings: d.settings,
        passes: int_control(label("passes"), PASSES, d.passes.into()),
        maxiter: int_control(label("maxiter"), MAX_ITER, d.settings.max_iter.into()),
        seed: int_control(label("seed"), SEED, d.seed),
        amount: AmountControl {
            label: label("tangle"),
            min: 0.0,
            max: MAX_AMOUNT,
            step: AMOUNT_STEP,
            default: d.amount,
            words: amount_words(),
        },
        threshold: ThresholdControl {
            label: label("threshold"),
            options: THRESHOLDS.to_vec(),
            default: d.settings.threshold_deg,
        },
        strategies: Strategy::ALL
            .iter()
            .map(|&s| StrategyInfo {
                name: s.name(),
                label: s.label(),
                title: s.describe(),
                words: strategy_words(s),
                threshold_unused: threshold_unused(s),
                max_iter_unused: max_iter_unused(s),
            })
            .collect(),
        orders: crate::smooth::Order::ALL
            .iter()
            .map(|&o| MenuEntry { name: o.name(), label: o.label(), title: o.describe() })
            .collect(),
        objectives: crate::objective::ObjectiveKind::ALL.iter().map(|k| Named { name: k.name(), words: k.describe() }).collect(),
        penalties: crate::objective::Penalty::ALL.iter().map(|p| Named { name: p.name(), words: p.describe() }).collect(),
        panels: crate::lab::Side::BOTH
            .iter()
            .zip(d.settings.compare)
            .map(|(&side, c)| PanelInfo {
                side,
                letter: side.letter(),
                rgb: side.rgb(),
                rgb_dark: crate::render::Theme::dark().sides[side as usize],
                objective: c.objective.name(),
                penalty: c.penalty.name(),
            })
            .collect(),
        file_extensions: crate::io::Format::ALL
            .iter()
            .flat_map(|f| f.extensions().iter().map(|e| format!(".{e}")))
            .collect(),
        file_extensions_words: crate::io::extensions_in_words(),
        quality_ramp: crate::render::VIRIDIS,
    }
}

/// The perturbation amount's range in words.
pub fn amount_words() -> String {
    format!("a number from 0 to {MAX_AMOUNT} (mean edge lengths)")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_defaults_lie_in_their_ranges_and_the_threshold_default_is_offered() {
        let d = PageState::default();
        assert!(PASSES.contains(d.passes.into()) && MAX_ITER.contains(d.settings.max_iter.into()) && SEED.contains(d.seed));
        assert!((0.0..=MAX_AMOUNT).contains(&d.amount));
        assert!(THRESHOLDS.contains(&d.settings.threshold_deg));
        assert!(d.validate().is_ok());
    }

    #[test]
    fn every_strategy_says_which_controls_matter() {
        let c = page_controls();
        assert_eq!(c.strategies.len(), Strategy::ALL.len());
        let with_threshold: Vec<&str> =
            c.strategies.iter().filter(|s| s.threshold_unused.is_none()).map(|s| s.name).collect();
        assert_eq!(with_threshold, ["c1", "c2", "c3"]);
        let without_solver: Vec<&str> =
            c.strategies.iter().filter(|s| s.max_iter_unused.is_some()).map(|s| s.name).collect();
        assert_eq!(without_solver, ["laplace", "smart"]);
        assert_eq!(c.passes.words, "a whole number from 1 to 100");
        assert_eq!((c.maxiter.min.as_str(), c.maxiter.max.as_str(), c.maxiter.default.as_str()), ("1", "50", "3"));
        assert_eq!(c.seed.max, u64::MAX.to_string());
    }
}
