//! What the page's two sides are and what they smooth with: [`Side`] (A and B),
//! [`Choice`] (an objective and its penalty design) and [`Settings`] (the shared controls
//! and each side's choice).

use serde::{Deserialize, Serialize};

use smoothlab::error::{Error, Result};
use smoothlab::objective::{objective_with, Objective, ObjectiveKind, Penalty};
use smoothlab::quality::MeshStats;
use smoothlab::smooth::{Order, SmoothOptions, Strategy};
use smoothlab::target::Target;
use smoothlab::mesh::FEATURE_ANGLE_DEG;
use smoothlab::volume::BoundaryRule;

/// The two panels of the page: the left one (A) and the right one (B), `a` and `b` to the
/// page. Either smooths with its own [`Choice`] of any objective; by default the left runs
/// Chen et al.'s "previous method" (the old max-min objective, Freitag 1997) and the right
/// their new smooth one.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Side {
    /// The left panel, by default Freitag's max-min objective.
    A,
    /// The right panel, by default Chen, Tristano & Kwok's smooth objective.
    B,
}

impl Side {
    pub const BOTH: [Side; 2] = [Side::A, Side::B];
    pub(crate) fn index(self) -> usize {
        self as usize
    }
    /// `A` or `B`, as the page heads its panels.
    pub fn letter(self) -> &'static str {
        match self {
            Side::A => "A",
            Side::B => "B",
        }
    }
    /// The colour of this side wherever it is drawn (meshes' titles, charts, histograms,
    /// legends; the page takes it from here): the Okabe–Ito orange for the left side and
    /// blue for the right, told apart by people with any colour vision.
    pub fn rgb(self) -> [u8; 3] {
        match self {
            Side::A => smoothlab_render::SERIES[1],
            Side::B => smoothlab_render::SERIES[2],
        }
    }
    /// [`rgb`](Self::rgb) as a tiny-skia colour.
    pub fn color(self) -> tiny_skia::Color {
        let [r, g, b] = self.rgb();
        tiny_skia::Color::from_rgba8(r, g, b, 255)
    }
}

/// What a panel smooths with: an objective and, for `new`, the design of its penalty.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Choice {
    /// By its command-line name (`old`, `sine`, `new`, `condition`, …).
    pub objective: ObjectiveKind,
    /// The penalty of `new` (`barrier`, `angle`); absent means the default. Other
    /// objectives have no penalty: it is then the default.
    #[serde(default)]
    pub penalty: Penalty,
}

impl Choice {
    /// The left panel's default: the old max-min objective.
    pub const OLD: Choice = Choice { objective: ObjectiveKind::MaxMinShape, penalty: Penalty::Barrier };
    /// The right panel's default: the new objective with its default penalty.
    pub const NEW: Choice = Choice { objective: ObjectiveKind::SmoothShape, penalty: Penalty::Barrier };

    /// The objective it names.
    pub fn build(self) -> Box<dyn Objective> {
        objective_with(self.objective, self.penalty)
    }

    /// A short label for legends: `old (max-min α/β …)`, `new (…, angle penalty)`.
    pub fn label(self) -> String {
        match self.objective {
            ObjectiveKind::SmoothShape => format!("new, {} penalty", self.penalty.name()),
            k => format!("{} ({})", k.name(), k.describe().split(" (").next().unwrap_or("")),
        }
    }

    /// A title for a picture or a panel: the label and who it is from.
    pub fn title(self) -> String {
        match self.objective {
            ObjectiveKind::SmoothShape => format!("new: {}, {} penalty", self.objective.describe(), self.penalty.name()),
            k => format!("{}: {}", k.name(), k.describe()),
        }
    }

    /// Checks that a penalty is given only to `new` (as the command line refuses it).
    fn validate(self) -> Result<()> {
        if self.objective != ObjectiveKind::SmoothShape && self.penalty != Penalty::default() {
            return Err(Error::invalid(format!(
                "the {} penalty is a design of the new objective; {} has no penalty",
                self.penalty.name(),
                self.objective.name()
            )));
        }
        Ok(())
    }
}

/// The shared controls of the page (both sides smooth with the same settings), and what
/// each side smooths with.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Settings {
    /// By its name (`rules`, `c2`, …), as the page's menus give it.
    pub strategy: Strategy,
    /// Freitag's threshold angle θ_t, degrees.
    pub threshold_deg: f64,
    /// `input` or `priority`.
    pub order: Order,
    /// Solver iterations per optimization call.
    pub max_iter: u32,
    /// What every corner is measured against ([`Target`]): the ideal element of its kind,
    /// its own shape in the mesh as loaded (or as last perturbed), or that mesh's stretch;
    /// only the strategies of [`target_refused`] take a target other than the ideal.
    /// Absent means the ideal: the page opens on the papers' setting.
    #[serde(default = "papers_target")]
    pub target: Target,
    /// What a mesh's boundary nodes do ([`BoundaryRule`]): stay where the file put them,
    /// or slide on the boundary as loaded (or as last perturbed), along its feature curves
    /// at the core's default feature angle (a quadratic planar mesh's along its curved
    /// edges); a quadratic volume mesh does not take `slide` (see
    /// [`slide_refused_quadratic`]). Absent means fixed.
    #[serde(default)]
    pub boundary: BoundaryRule,
    /// What the left (A) and the right (B) panel smooth with; absent means old against
    /// new (with the barrier penalty).
    #[serde(default = "default_compare")]
    pub compare: [Choice; 2],
}

fn default_compare() -> [Choice; 2] {
    [Choice::OLD, Choice::NEW]
}

impl Default for Settings {
    /// The core's defaults ([`SmoothOptions::default`]: Chen's algorithm, rules in priority
    /// order, 3 iterations per call; θ_t = 30°); old against new with the barrier penalty.
    fn default() -> Self {
        let d = SmoothOptions::default();
        Settings {
            strategy: d.strategy,
            threshold_deg: d.threshold_deg,
            order: d.order,
            max_iter: d.max_iter,
            target: papers_target(),
            boundary: BoundaryRule::Fixed,
            compare: default_compare(),
        }
    }
}

/// Where a run begins, in what its options read: the grading it keeps
/// ([`MeshStats::grading_to_keep`]) and whether its mesh is valid; and whether its first
/// pass is still to come (that pass fits the mesh to its targets first:
/// [`Smoother::fit_first`](smoothlab::smooth::Smoother::fit_first)). A split pass hands it
/// to the engine that sweeps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunStart {
    pub keep_grading: f64,
    pub valid: bool,
    pub first_pass: bool,
}

impl RunStart {
    /// The start of a run from a mesh with statistics `stats`, before its first pass.
    pub fn of(stats: &MeshStats) -> RunStart {
        RunStart { keep_grading: stats.grading_to_keep(), valid: stats.inverted == 0, first_pass: true }
    }
}

impl Settings {
    /// The drivers' options (checked), after checking each side's choice.
    pub fn smooth_options(&self) -> Result<SmoothOptions> {
        for c in self.compare {
            c.validate()?;
        }
        if self.target != Target::Ideal {
            if let Some(why) = target_refused(self.strategy) {
                return Err(Error::invalid(format!(
                    "the {} target is refused: {why}",
                    self.target.name()
                )));
            }
        }
        let range = smoothlab::smooth::limits::BATCH_MAX_ITER;
        if !range.contains(self.max_iter.into()) {
            return Err(Error::invalid(format!("{} solver iterations: give {}", self.max_iter, range.words())));
        }
        let o = SmoothOptions::default()
            .with_strategy(self.strategy)
            .with_order(self.order)
            .with_threshold_deg(self.threshold_deg)
            .with_max_iter(self.max_iter);
        o.validate()?;
        Ok(o)
    }

    /// The drivers' options for `side`'s run from `start` (checked):
    /// [`smooth_options`](Self::smooth_options), judged by the measure of the side's
    /// objective on such a mesh ([`Measure::for_run`](smoothlab::smooth::Measure::for_run)),
    /// keeping the grading the run found ([`MeshStats::grading_to_keep`]), as `smoothlab
    /// smooth` takes them, whatever settings come between the run's passes.
    pub fn side_options(&self, side: Side, start: RunStart) -> Result<SmoothOptions> {
        let m = smoothlab::smooth::Measure::for_run(self.choice(side).objective, start.valid);
        Ok(SmoothOptions { keep_grading: Some(start.keep_grading), ..self.smooth_options()?.with_smart_measure(m) })
    }

    /// What `side` smooths with.
    pub fn choice(&self, side: Side) -> Choice {
        self.compare[side.index()]
    }

    /// A side's heading: its letter and what it smooths with ([`Choice::title`]).
    pub fn side_title(&self, side: Side) -> String {
        format!("{}: {}", side.letter(), self.choice(side).title())
    }

    /// The same, short ([`Choice::label`]), for a compact page.
    pub fn side_label(&self, side: Side) -> String {
        format!("{}: {}", side.letter(), self.choice(side).label())
    }
}

/// The page's target when none is given: the papers' ideal ([`Settings::target`]).
fn papers_target() -> Target {
    Target::Ideal
}

/// Why `strategy` cannot measure corners against a target other than the ideal, if it
/// cannot (as the core's [`Smoothing`](smoothlab::Smoothing) refuses it): only
/// optimization and Chen's rules take one (the rules then optimise every node), the
/// others take Laplacian steps, whose centroid is the ideal's answer.
pub fn target_refused(strategy: Strategy) -> Option<String> {
    match strategy {
        Strategy::Opt | Strategy::Rules => None,
        Strategy::Laplace | Strategy::Smart => Some(format!(
            "only optimization and Chen's rules measure corners against a target other than the ideal; {} moves each node to the centre of its neighbours, which aims at the ideal",
            strategy.words()
        )),
        Strategy::C1 | Strategy::C2 | Strategy::C3 => Some(format!(
            "only optimization and Chen's rules measure corners against a target other than the ideal; {} takes Laplacian steps, which aim at the ideal",
            strategy.words()
        )),
    }
}

/// What a [`Target`] means, in a sentence for the page's users (the control's words).
pub fn target_words(target: Target) -> &'static str {
    match target {
        Target::Ideal => {
            "Every element is pulled toward the ideal of its kind: the equilateral triangle, the square (in a volume the regular tetrahedron, the cube), as in the papers."
        }
        Target::Input => {
            "Each corner aims at the shape it had in the mesh as loaded (or as last perturbed), its stretch and skew kept; only a corner that was inverted or flat aims at the ideal."
        }
        Target::Stretch => {
            "Each element aims at the stretch the mesh had where it lies, averaged along its layer: a boundary layer's thin rows stay thin, a single node's noise does not; where the mesh is not stretched, at the ideal; a valid planar or volume mesh of linear elements is first fitted to its targets whole, every node at once."
        }
    }
}

/// What a [`BoundaryRule`] means on a volume mesh, in a sentence for the page's users
/// (the control's words); the feature angle is the core's ([`FEATURE_ANGLE_DEG`]).
pub fn boundary_words(rule: BoundaryRule) -> String {
    match rule {
        BoundaryRule::Fixed => FIXED_WORDS.into(),
        BoundaryRule::Slide => format!(
            "Boundary nodes slide on the boundary as loaded: along its feature curves (where its faces turn by more than {FEATURE_ANGLE_DEG}°) or on its faces between them; the corners where curves meet stay."
        ),
    }
}

/// A fixed boundary, in a sentence: the papers' setting.
const FIXED_WORDS: &str = "Boundary nodes stay where the file put them, as in the papers: only interior nodes move.";

/// What a [`BoundaryRule`] means on a planar mesh, in a sentence for the page: its
/// boundary is its edges of one element, a corner where it turns by more than the core's
/// feature angle ([`FEATURE_ANGLE_DEG`]), a quadratic element's boundary edge the curve
/// through its corners and mid-side node; a tangled mesh's is held until a pass leaves it
/// valid, as the core's run holds it.
pub fn planar_boundary_words(rule: BoundaryRule) -> String {
    match rule {
        BoundaryRule::Fixed => FIXED_WORDS.into(),
        BoundaryRule::Slide => format!(
            "Boundary nodes slide along the boundary as loaded; a corner, where it turns by more than {FEATURE_ANGLE_DEG}°, stays, as does a node the file fixed. A quadratic mesh's boundary is its curved edges: a sliding node keeps to them and carries its edges' mid-side nodes to the middle of their new spans. A tangled mesh's boundary stays until a pass leaves the mesh valid, then slides."
        ),
    }
}

/// What a boundary rule does on a surface, in a sentence for the page: its boundary is
/// its open edges and feature curves.
pub fn surface_boundary_words(rule: BoundaryRule) -> &'static str {
    match rule {
        BoundaryRule::Fixed => "The nodes of the surface's open edges and feature curves stay where the file put them, as in the papers.",
        BoundaryRule::Slide => {
            "The nodes of the surface's open edges and feature curves (where it bends by more than 30°) slide along them as loaded; a node where a curve turns by more than 60°, ends or meets another stays."
        }
    }
}

/// Why a quadratic volume mesh's boundary nodes cannot slide.
pub fn slide_refused_quadratic() -> String {
    "only a linear volume mesh's boundary nodes slide so far; this mesh is quadratic, and its mid-edge nodes would leave its curved faces".into()
}

/// Refuses `rule` where the mesh's boundary cannot slide (`refused`, the reason).
pub(crate) fn check_boundary(rule: BoundaryRule, refused: Option<String>) -> Result<()> {
    match (rule, refused) {
        (BoundaryRule::Slide, Some(why)) => Err(Error::invalid(format!("the boundary cannot slide here: {why}"))),
        _ => Ok(()),
    }
}
