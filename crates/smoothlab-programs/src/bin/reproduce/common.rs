//! What every section uses: runs of passes, the objectives' names, statistics.

use std::path::{Path, PathBuf};
use std::time::Instant;

use smoothlab::objective::{objective_with, Objective, ObjectiveKind, Penalty};
use smoothlab::quality::{corner_edges, element_quality, lo_alpha_corner};
use smoothlab::smooth::{Order, PassRecord, SmoothOptions, Smoother, Strategy};
use smoothlab::Mesh;

/// Milliseconds since the clock was made: the core takes time from its caller.
pub(crate) fn clock() -> impl Fn() -> f64 {
    let t0 = Instant::now();
    move || t0.elapsed().as_secs_f64() * 1e3
}

/// One smoothing run: the mesh after it, the pass records, the wall time of the passes.
pub(crate) struct Run {
    pub(crate) mesh: Mesh,
    pub(crate) passes: Vec<PassRecord>,
}

impl Run {
    pub(crate) fn last_inverted(&self, before: usize) -> usize {
        self.passes.last().map_or(before, |p| p.after.inverted)
    }
    /// Passes until the first with no inverted element, if any.
    pub(crate) fn passes_to_valid(&self) -> Option<usize> {
        self.passes.iter().position(|p| p.after.inverted == 0).map(|i| i + 1)
    }
    pub(crate) fn ms(&self) -> f64 {
        self.passes.iter().map(|p| p.elapsed_ms).sum()
    }
    pub(crate) fn laplacian_moves(&self) -> u32 {
        self.passes.iter().map(|p| p.counts.laplacian_moves).sum()
    }
    pub(crate) fn optimization_calls(&self) -> u32 {
        self.passes.iter().map(|p| p.counts.optimization_calls).sum()
    }
}

/// An objective as the tables name it: a kind, and for `new` the design of its penalty.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Choice {
    pub(crate) kind: ObjectiveKind,
    pub(crate) penalty: Penalty,
}

impl From<ObjectiveKind> for Choice {
    fn from(kind: ObjectiveKind) -> Self {
        Choice { kind, penalty: Penalty::default() }
    }
}

/// `new` with the first design of its penalty (the adjusted angle).
pub(crate) const NEW_ANGLE: Choice = Choice { kind: ObjectiveKind::SmoothShape, penalty: Penalty::Angle };

/// Both designs of `new`, the default first, with the words the tables use.
pub(crate) const NEW_DESIGNS: [(Choice, &str); 2] =
    [(Choice { kind: ObjectiveKind::SmoothShape, penalty: Penalty::Barrier }, "barrier"), (NEW_ANGLE, "angle (first design)")];

/// Runs passes of `strategy` with objective `choice` until `max_passes` or until `stop`
/// says so after a pass.
pub(crate) fn run(
    mesh: &Mesh,
    choice: impl Into<Choice>,
    opts: SmoothOptions,
    max_passes: u32,
    stop: impl Fn(&PassRecord) -> bool,
) -> Run {
    let choice = choice.into();
    run_with(mesh, &*objective_with(choice.kind, choice.penalty), opts, max_passes, stop)
}

/// [`run`] with an objective of the caller's making.
pub(crate) fn run_with(
    mesh: &Mesh,
    obj: &dyn Objective,
    opts: SmoothOptions,
    max_passes: u32,
    stop: impl Fn(&PassRecord) -> bool,
) -> Run {
    let mut m = mesh.clone();
    let mut s = Smoother::new(opts).expect("valid options");
    let c = clock();
    let mut passes = Vec::new();
    for _ in 0..max_passes {
        let r = s.pass(&mut m, obj, &c);
        let done = stop(&r);
        passes.push(r);
        if done {
            break;
        }
    }
    Run { mesh: m, passes }
}

pub(crate) fn opts(strategy: Strategy, order: Order) -> SmoothOptions {
    SmoothOptions::default().with_strategy(strategy).with_order(order)
}

/// Untangling by optimization, input order, an inverted star allowed to pass through a
/// fold when its total inversion falls (`SmoothOptions::pass_through_folds`).
pub(crate) fn untangle_opts() -> SmoothOptions {
    opts(Strategy::Opt, Order::Input).with_pass_through_folds(true)
}

pub(crate) fn never(_: &PassRecord) -> bool {
    false
}

pub(crate) fn untangled(p: &PassRecord) -> bool {
    p.after.inverted == 0
}

/// Mean and range of some numbers, as `mean [min–max]` with `d` decimals.
pub(crate) fn mean_range(v: &[f64], d: usize) -> String {
    let mean = v.iter().sum::<f64>() / v.len() as f64;
    let lo = v.iter().cloned().fold(f64::INFINITY, f64::min);
    let hi = v.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    format!("{mean:.d$} [{lo:.d$}–{hi:.d$}]")
}

pub(crate) fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len() as f64
}

/// Condition numbers of the elements: (worst, mean), ∞ when any element is inverted.
pub(crate) fn kappa(mesh: &Mesh) -> (f64, f64) {
    let mut worst = 0.0f64;
    let mut sum = 0.0;
    for e in 0..mesh.element_count() {
        let k = mesh.kind(e);
        let p = mesh.element_points_array(e);
        let q = element_quality(k, &p[..k.node_count()]);
        worst = worst.max(q.condition);
        sum += q.condition;
    }
    (worst, sum / mesh.element_count().max(1) as f64)
}

pub(crate) fn fmt_kappa(k: f64) -> String {
    if k.is_finite() {
        format!("{k:.3}")
    } else {
        "∞".into()
    }
}

/// The largest |α − 1| over every corner of every element.
pub(crate) fn worst_alpha_error(mesh: &Mesh) -> f64 {
    let mut worst = 0.0f64;
    for e in 0..mesh.element_count() {
        let k = mesh.kind(e);
        let p = mesh.element_points_array(e);
        for (e1, e2) in &corner_edges(k, &p[..k.node_count()])[..k.corners()] {
            worst = worst.max((lo_alpha_corner(*e1, *e2) - 1.0).abs());
        }
    }
    worst
}

pub(crate) fn meshes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/meshes")
}
