//! The page's control sheet: every control's label, range, step and default, and every
//! menu's entries, built from the core's enums and ranges
//! ([`smooth::limits`](smoothlab::smooth::limits)) and the permalink's defaults
//! ([`PageState::default`]). The page builds its inputs from [`page_controls`] and checks
//! what the user types with [`permalink::check_control`](super::permalink::check_control),
//! so a control, a link and the command-line tool are held to the same rules.

use serde::Serialize;

use super::permalink::{control_label, gmsh_sample_name, PageState, GMSH_FILES};
use super::settings::{boundary_words, planar_boundary_words, surface_boundary_words, target_refused, target_words};
use smoothlab::smooth::limits::{
    amount_words, IntRange, AMOUNT_STEP, MAX_AMOUNT, MAX_ITER, PASSES, SEED, THRESHOLDS,
};
use smoothlab::smooth::Strategy;
use smoothlab::target::Target;
use smoothlab::volume::BoundaryRule;

fn label(key: &str) -> &'static str {
    control_label(key).expect("a key the user types into")
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
    /// The menu's text and tooltip ([`Strategy::label`], [`Strategy::describe`]), and the
    /// strategy in words ([`Strategy::words`]); why it ignores the threshold angle
    /// ([`Strategy::threshold_unused`]) and the iteration limit ([`Strategy::max_iter_unused`]),
    /// and why it takes no target but the ideal ([`target_refused`]).
    pub label: &'static str,
    pub title: &'static str,
    pub words: &'static str,
    pub threshold_unused: Option<String>,
    pub max_iter_unused: Option<String>,
    pub target_refused: Option<String>,
}

/// One target of the target menu: its name, its menu entry and what it means in a
/// sentence for the page's users ([`target_words`]), shown beside the menu.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TargetInfo {
    pub name: &'static str,
    pub label: &'static str,
    pub words: &'static str,
}

/// One rule of the boundary menu: its name, its menu entry and what it means in a
/// sentence for the page's users, shown beside the menu: on a volume mesh
/// ([`boundary_words`]), on a surface (its boundary is its curves) and on a planar mesh.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BoundaryInfo {
    pub name: &'static str,
    pub label: &'static str,
    pub words: String,
    pub surface_words: &'static str,
    pub planar_words: String,
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
    pub side: super::Side,
    pub letter: &'static str,
    /// The side's colour in the light theme, and in the dark one (`render::Theme`).
    pub rgb: [u8; 3],
    pub rgb_dark: [u8; 3],
    pub objective: &'static str,
    pub penalty: &'static str,
}

/// A Gmsh file of the page's sample menu: the file (in the site's `samples/`), its name
/// in a permalink ([`gmsh_sample_name`]) and its menu entry.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct GmshSample {
    pub file: &'static str,
    pub name: String,
    pub title: &'static str,
}

/// Everything the page needs to build and check its controls, keyed by the permalink's
/// keys: `{ settings, passes, maxiter, seed, amount, threshold, strategies, orders,
/// targets, boundaries, objectives, penalties, panels, file_extensions, file_extensions_words, max_file_bytes,
/// gmsh_samples, quality_ramp }`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PageControls {
    /// The default settings (strategy, order, …), which the menus start on.
    pub settings: super::Settings,
    pub passes: IntControl,
    pub maxiter: IntControl,
    pub seed: IntControl,
    pub amount: AmountControl,
    pub threshold: ThresholdControl,
    pub strategies: Vec<StrategyInfo>,
    /// Every visit order ([`Order::ALL`](smoothlab::smooth::Order::ALL)).
    pub orders: Vec<MenuEntry>,
    /// Every target ([`Target::ALL`]), the ideal first.
    pub targets: Vec<TargetInfo>,
    /// Every boundary rule ([`BoundaryRule::ALL`]), fixed first.
    pub boundaries: Vec<BoundaryInfo>,
    /// Every objective a panel can run ([`ObjectiveKind::ALL`](smoothlab::objective::ObjectiveKind::ALL)).
    pub objectives: Vec<Named>,
    /// The designs of `new`'s penalty ([`Penalty::ALL`](smoothlab::objective::Penalty::ALL)).
    pub penalties: Vec<Named>,
    /// The left panel (A), then the right (B).
    pub panels: Vec<PanelInfo>,
    /// The file input's extensions (`.msh`, …, every [`Format`](smoothlab::io::Format)'s) and
    /// the same in words.
    pub file_extensions: Vec<String>,
    pub file_extensions_words: String,
    /// The largest file the page reads, in bytes ([`PAGE_MAX_FILE_BYTES`](smoothlab::io::PAGE_MAX_FILE_BYTES)):
    /// a larger one is refused by its size before it is read.
    pub max_file_bytes: u64,
    /// The Gmsh files of the sample menu ([`GMSH_FILES`]), in its order.
    pub gmsh_samples: Vec<GmshSample>,
    /// The quality colour map's anchors (viridis, 0 to 1), for the page's own colour key
    /// where a canvas is too small for the drawn colour bar.
    pub quality_ramp: [[u8; 3]; 9],
}

fn int_control(label: &'static str, r: IntRange, default: u64) -> IntControl {
    IntControl {
        label,
        min: r.min.to_string(),
        max: r.max.to_string(),
        default: default.to_string(),
        words: r.words(),
    }
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
                words: s.words(),
                threshold_unused: s.threshold_unused(),
                max_iter_unused: s.max_iter_unused(),
                target_refused: target_refused(s),
            })
            .collect(),
        orders: smoothlab::smooth::Order::ALL
            .iter()
            .map(|&o| MenuEntry {
                name: o.name(),
                label: o.label(),
                title: o.describe(),
            })
            .collect(),
        targets: Target::ALL
            .iter()
            .map(|&t| TargetInfo {
                name: t.name(),
                label: match t {
                    Target::Ideal => "Ideal shape",
                    Target::Input => "The mesh as loaded",
                    Target::Stretch => "The mesh's stretch",
                },
                words: target_words(t),
            })
            .collect(),
        boundaries: BoundaryRule::ALL
            .iter()
            .map(|&r| BoundaryInfo {
                name: r.name(),
                label: match r {
                    BoundaryRule::Fixed => "Fixed, as loaded",
                    BoundaryRule::Slide => "Slides on the boundary",
                },
                words: boundary_words(r),
                surface_words: surface_boundary_words(r),
                planar_words: planar_boundary_words(r),
            })
            .collect(),
        objectives: smoothlab::objective::ObjectiveKind::ALL
            .iter()
            .map(|k| Named {
                name: k.name(),
                words: k.describe(),
            })
            .collect(),
        penalties: smoothlab::objective::Penalty::ALL
            .iter()
            .map(|p| Named {
                name: p.name(),
                words: p.describe(),
            })
            .collect(),
        panels: super::Side::BOTH
            .iter()
            .zip(d.settings.compare)
            .map(|(&side, c)| PanelInfo {
                side,
                letter: side.letter(),
                rgb: side.rgb(),
                rgb_dark: smoothlab_render::Theme::dark().sides[side as usize],
                objective: c.objective.name(),
                penalty: c.penalty.name(),
            })
            .collect(),
        file_extensions: smoothlab::io::Format::ALL
            .iter()
            .flat_map(|f| f.extensions().iter().map(|e| format!(".{e}")))
            .collect(),
        file_extensions_words: smoothlab::io::extensions_in_words(),
        max_file_bytes: smoothlab::io::PAGE_MAX_FILE_BYTES,
        gmsh_samples: GMSH_FILES
            .iter()
            .map(|g| GmshSample {
                file: g.file,
                name: gmsh_sample_name(g.file),
                title: g.title,
            })
            .collect(),
        quality_ramp: smoothlab_render::VIRIDIS,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_defaults_lie_in_their_ranges_and_the_threshold_default_is_offered() {
        let d = PageState::default();
        assert!(
            PASSES.contains(d.passes.into())
                && MAX_ITER.contains(d.settings.max_iter.into())
                && SEED.contains(d.seed)
        );
        assert!((0.0..=MAX_AMOUNT).contains(&d.amount));
        assert!(THRESHOLDS.contains(&d.settings.threshold_deg));
        assert!(d.validate().is_ok());
    }

    #[test]
    fn every_strategy_says_which_controls_matter() {
        let c = page_controls();
        assert_eq!(c.strategies.len(), Strategy::ALL.len());
        let with_threshold: Vec<&str> = c
            .strategies
            .iter()
            .filter(|s| s.threshold_unused.is_none())
            .map(|s| s.name)
            .collect();
        assert_eq!(with_threshold, ["c1", "c2", "c3"]);
        let without_solver: Vec<&str> = c
            .strategies
            .iter()
            .filter(|s| s.max_iter_unused.is_some())
            .map(|s| s.name)
            .collect();
        assert_eq!(without_solver, ["laplace", "smart"]);
        let with_target: Vec<&str> = c
            .strategies
            .iter()
            .filter(|s| s.target_refused.is_none())
            .map(|s| s.name)
            .collect();
        assert_eq!(with_target, ["opt", "rules"]);
        assert_eq!(c.passes.words, "a whole number from 1 to 100");
        assert_eq!(
            (
                c.maxiter.min.as_str(),
                c.maxiter.max.as_str(),
                c.maxiter.default.as_str()
            ),
            ("1", "50", "3")
        );
        assert_eq!(c.seed.max, u64::MAX.to_string());
    }

    #[test]
    fn the_target_menu_says_what_each_target_means() {
        let c = page_controls();
        let names: Vec<&str> = c.targets.iter().map(|t| t.name).collect();
        assert_eq!(names, ["ideal", "input", "stretch"]);
        assert_eq!(
            c.settings.target.name(),
            "ideal",
            "the menu starts on the ideal"
        );
        for t in &c.targets {
            // one sentence each, which the page shows as it is
            assert!(
                t.words.ends_with('.') && t.words.matches(". ").count() == 0,
                "{}",
                t.words
            );
        }
        assert!(c.targets[0]
            .words
            .contains("equilateral triangle, the square"));
        assert!(
            c.targets[1].words.contains("as loaded") && c.targets[1].words.contains("inverted")
        );
        let c2 = c.strategies.iter().find(|s| s.name == "c2").unwrap();
        assert_eq!(
            c2.target_refused.as_deref(),
            Some("only optimization and Chen's rules measure corners against a target other than the ideal; Freitag's C2 takes Laplacian steps, which aim at the ideal")
        );
        let json = serde_json::to_value(&c).unwrap();
        assert_eq!(json["settings"]["target"], "ideal");
        assert_eq!(json["targets"][1]["label"], "The mesh as loaded");
    }

    #[test]
    fn the_boundary_menu_says_what_each_rule_does() {
        let c = page_controls();
        let names: Vec<&str> = c.boundaries.iter().map(|b| b.name).collect();
        assert_eq!(names, ["fixed", "slide"]);
        assert_eq!(c.settings.boundary, BoundaryRule::Fixed, "the menu starts fixed");
        for b in &c.boundaries {
            assert!(b.words.ends_with('.') && b.words.matches(". ").count() == 0, "{}", b.words);
        }
        assert!(c.boundaries[1].words.contains("feature curves") && c.boundaries[1].words.contains("corners"));
        let json = serde_json::to_value(&c).unwrap();
        assert_eq!(json["settings"]["boundary"], "fixed");
        assert_eq!(json["boundaries"][1]["label"], "Slides on the boundary");
    }

    #[test]
    fn the_sheet_hands_the_page_its_gmsh_samples_and_file_limit() {
        let c = page_controls();
        let files: Vec<&str> = c.gmsh_samples.iter().map(|g| g.file).collect();
        assert_eq!(
            files,
            ["plate_hole_tri.msh", "bracket_quad.msh", "disk_tri6.msh"]
        );
        let names: Vec<&str> = c.gmsh_samples.iter().map(|g| g.name.as_str()).collect();
        assert_eq!(
            names,
            ["gmsh-plate-hole-tri", "gmsh-bracket-quad", "gmsh-disk-tri6"]
        );
        for g in &c.gmsh_samples {
            // the name a link carries opens this very file
            assert_eq!(super::super::permalink::gmsh_file(&g.name), Some(g.file));
            assert!(super::super::permalink::SAMPLES.contains(&g.name.as_str()));
        }
        assert_eq!(
            c.gmsh_samples[2].title,
            "Gmsh: disk, 6-node triangles (curved)"
        );
        assert_eq!(c.max_file_bytes, 256 << 20);
        // as the page receives it: a plain number (exact in a JS number), the lists by field
        let json = serde_json::to_value(&c).unwrap();
        assert_eq!(json["max_file_bytes"].as_u64(), Some(268_435_456));
        assert!(json["max_file_bytes"].as_u64().unwrap() < 1 << 53);
        assert_eq!(json["gmsh_samples"][1]["name"], "gmsh-bracket-quad");
        assert_eq!(json["gmsh_samples"][1]["file"], "bracket_quad.msh");
    }
}
