//! One call smooths any mesh: [`Model::smooth`] with a [`Smoothing`].
//!
//! A [`Smoothing`] names the settings of a run: strategy, objective, passes and the rest.
//! Each setting left unset takes the default the command-line tool takes.
//! [`Model::smooth`] picks the driver for the mesh kind (planar, surface or volume).
//! It returns a [`Report`]: one record a pass, the final statistics, and the inverted
//! elements that no move can repair.

use serde::Serialize;

use crate::error::{Error, Result};
use crate::model::Model;
use crate::objective::{check_scale, objective_with, solid_objective, ObjectiveKind, Penalty};
use crate::quality::MeshStats;
use crate::smooth::limits::{threshold_in_range, BATCH_MAX_ITER, BATCH_PASSES};
use crate::smooth::{
    untangling_obstacles, volume_untangling_obstacles, Obstacle, Order, PassRecord, SmoothOptions, Smoother, Strategy,
    DEFAULT_PASSES,
};
use crate::surface::SurfaceSmoother;
use crate::target::Target;
use crate::volume::{BoundaryRule, VolumeSmoother, FEATURE_ANGLE_DEG};

/// The settings of a smoothing run, built by chained calls.
///
/// `Smoothing::default()` is the command-line tool's default run: Chen et al.'s rules with
/// the new objective, in priority order, three passes.
///
/// ```
/// use smoothlab::{ObjectiveKind, Smoothing, Strategy};
///
/// let s = Smoothing::default().strategy(Strategy::Opt).objective(ObjectiveKind::Condition).passes(5);
/// assert_eq!(s.passes_asked(), 5);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Smoothing {
    strategy: Strategy,
    objective: ObjectiveKind,
    passes: u32,
    threshold_deg: Option<f64>,
    order: Option<Order>,
    max_iter: Option<u32>,
    penalty: Option<Penalty>,
    pass_through_folds: Option<bool>,
    slide_curves: bool,
    finish: u32,
    target: Option<Target>,
    boundary: BoundaryRule,
    feature_angle_deg: Option<f64>,
}

impl Default for Smoothing {
    fn default() -> Self {
        Smoothing {
            strategy: SmoothOptions::default().strategy,
            objective: ObjectiveKind::SmoothShape,
            passes: DEFAULT_PASSES,
            threshold_deg: None,
            order: None,
            max_iter: None,
            penalty: None,
            pass_through_folds: None,
            slide_curves: false,
            finish: Smoothing::DEFAULT_FINISH,
            target: None,
            boundary: BoundaryRule::Fixed,
            feature_angle_deg: None,
        }
    }
}

impl Smoothing {
    /// Passes of the finish a default run ends with ([`finish`](Self::finish)).
    pub const DEFAULT_FINISH: u32 = 3;

    /// The finish aimed at the worst element, once a mesh is valid (issue 57): Freitag's
    /// max-min ascent on the smallest sine ([`ObjectiveKind::Sine`]: a corner's scaled
    /// Jacobian in hexahedra, wedges, pyramids and planar elements, a tetrahedron's dihedral
    /// sines), worst star first, a move kept only where the star's smallest sine does not
    /// fall (and, as in every pass, its statistics stay within the mesh's). The measure users
    /// read; the passes before it improve the average element.
    pub const FINISH: (ObjectiveKind, Strategy, Order) =
        (ObjectiveKind::Sine, Strategy::Opt, Order::Priority);

    /// How each node is smoothed.
    pub fn strategy(mut self, strategy: Strategy) -> Self {
        self.strategy = strategy;
        self
    }
    /// The objective of the optimization steps (`laplace` and `smart` only report its total).
    pub fn objective(mut self, objective: ObjectiveKind) -> Self {
        self.objective = objective;
        self
    }
    /// The number of passes over the mesh.
    pub fn passes(mut self, passes: u32) -> Self {
        self.passes = passes;
        self
    }
    /// The threshold angle of `c1`, `c2` and `c3`, in degrees.
    pub fn threshold(mut self, degrees: f64) -> Self {
        self.threshold_deg = Some(degrees);
        self
    }
    /// The node order (default: priority for `rules`, input order otherwise).
    pub fn order(mut self, order: Order) -> Self {
        self.order = Some(order);
        self
    }
    /// The solver iterations per optimization call.
    pub fn max_iter(mut self, iterations: u32) -> Self {
        self.max_iter = Some(iterations);
        self
    }
    /// The design of the new objective's penalty (planar meshes and surfaces).
    pub fn penalty(mut self, penalty: Penalty) -> Self {
        self.penalty = Some(penalty);
        self
    }
    /// Whether an inverted star may fold one more element when that lowers its inversion.
    pub fn pass_through_folds(mut self, on: bool) -> Self {
        self.pass_through_folds = Some(on);
        self
    }
    /// Whether a surface's feature curves and open boundaries slide (surfaces only).
    pub fn slide_curves(mut self, on: bool) -> Self {
        self.slide_curves = on;
        self
    }

    /// The number of passes asked for.
    /// Passes of the finish aimed at the worst element, run once the passes leave the mesh
    /// valid ([`Smoothing::FINISH`]); 0 runs none.
    pub fn finish(mut self, passes: u32) -> Self {
        self.finish = passes;
        self
    }

    /// What each corner is measured against ([`Target`]). Unset, opt and rules take
    /// [`Target::default`] (the mesh's stretch, the ideal where it has none made on
    /// purpose) and the Laplacian strategies the ideal they aim at; set, a Laplacian
    /// strategy refuses any target but the ideal. The finish keeps the stretch target and
    /// measures the statistics themselves otherwise.
    pub fn target(mut self, target: Target) -> Self {
        self.target = Some(target);
        self
    }

    /// The target the run asks for ([`target`](Self::target)).
    fn asked_target(&self) -> Target {
        match (self.target, self.strategy) {
            (Some(t), _) => t,
            (None, Strategy::Opt | Strategy::Rules) => Target::default(),
            (None, _) => Target::Ideal,
        }
    }

    /// What boundary nodes do ([`BoundaryRule`]; planar meshes, linear volume meshes, and
    /// surfaces, whose boundary is their open edges and feature curves).
    pub fn boundary(mut self, rule: BoundaryRule) -> Self {
        self.boundary = rule;
        self
    }

    /// The angle, degrees, over which two boundary faces meet at a feature curve, with
    /// sliding boundaries (default [`FEATURE_ANGLE_DEG`]).
    pub fn feature_angle(mut self, degrees: f64) -> Self {
        self.feature_angle_deg = Some(degrees);
        self
    }

    pub fn passes_asked(&self) -> u32 {
        self.passes
    }
    /// The node order the run takes.
    pub fn order_taken(&self) -> Order {
        match self.order {
            Some(o) => o,
            None if self.strategy == Strategy::Rules => Order::Priority,
            None => Order::Input,
        }
    }

    /// The drivers' options, or why the settings do not go together.
    pub fn options(&self) -> Result<SmoothOptions> {
        let strategy = self.strategy;
        if !BATCH_PASSES.contains(self.passes.into()) {
            return refuse(
                "passes",
                format!("{} asked: give 1 to {}", self.passes, BATCH_PASSES.max),
            );
        }
        let mut o = SmoothOptions::default()
            .with_strategy(strategy)
            .with_order(self.order_taken());
        if let Some(t) = self.threshold_deg {
            if strategy.threshold_unused().is_some() {
                return refuse(
                    "threshold",
                    format!("c1, c2 and c3 have one, not {}", strategy.name()),
                );
            }
            if !threshold_in_range(t) {
                return refuse(
                    "threshold",
                    format!("{t} asked: give degrees above 0 and at most 90"),
                );
            }
            o = o.with_threshold_deg(t);
        }
        let solver_free = strategy.max_iter_unused().is_some();
        if let Some(k) = self.max_iter {
            if solver_free {
                return refuse(
                    "max_iter",
                    format!("{} never calls the solver", strategy.name()),
                );
            }
            if !BATCH_MAX_ITER.contains(k.into()) {
                return refuse(
                    "max_iter",
                    format!("{k} asked: give 1 to {}", BATCH_MAX_ITER.max),
                );
            }
            o = o.with_max_iter(k);
        }
        if let Some(on) = self.pass_through_folds {
            if solver_free {
                return refuse(
                    "pass_through_folds",
                    format!("{} never calls the solver", strategy.name()),
                );
            }
            o = o.with_pass_through_folds(on);
        }
        if self.penalty.is_some() && self.objective != ObjectiveKind::SmoothShape {
            return refuse("penalty", "it is a design of the new objective".into());
        }
        if self.target.is_some_and(|t| t != Target::Ideal) && !matches!(strategy, Strategy::Opt | Strategy::Rules) {
            return refuse(
                "target",
                format!(
                    "{} takes Laplacian steps; the targets are measured by opt and rules",
                    strategy.name()
                ),
            );
        }
        if u64::from(self.finish) > BATCH_PASSES.max {
            return refuse(
                "finish",
                format!("{} asked: give 0 to {}", self.finish, BATCH_PASSES.max),
            );
        }
        if let Some(a) = self.feature_angle_deg {
            if self.boundary != BoundaryRule::Slide {
                return refuse("feature_angle", "it finds the curves sliding nodes keep to; give boundary slide".into());
            }
            if !(a > 0.0 && a < 180.0) {
                return refuse("feature_angle", format!("{a} asked: give degrees above 0 and below 180"));
            }
        }
        o.validate()?;
        Ok(o)
    }

    /// Why these settings cannot smooth `model`, if they cannot.
    fn check(&self, model: &Model) -> Result<()> {
        match model {
            Model::Planar(mesh) if !self.slide_curves => check_scale(self.objective, mesh),
            Model::Volume(v) if self.slide_curves => refuse(
                "slide_curves",
                format!(
                    "a surface's curves slide; this mesh is made of {}",
                    v.family_words()
                ),
            ),
            Model::Volume(_) if self.penalty.is_some() => refuse(
                "penalty",
                "its designs are planar; volume elements take new's barrier".into(),
            ),
            Model::Volume(v) if self.boundary == BoundaryRule::Slide && v.is_quadratic() => refuse(
                "boundary",
                "slide takes linear volume meshes so far; quadratic boundary nodes stay".into(),
            ),
            Model::Volume(_) => Ok(()),
            Model::Surface(_) => Ok(()),
            _ => refuse(
                "slide_curves",
                "a surface's curves slide; this mesh is planar".into(),
            ),
        }
    }
}

/// Why setting `name` cannot be used: `name: why`.
fn refuse<T>(name: &str, why: String) -> Result<T> {
    Err(Error::invalid(format!("{name}: {why}")))
}

/// What a smoothing run did: a record a pass, and where the mesh stands.
///
/// In JSON (`smoothlab smooth --json`) it is one object: `objective`, `strategy`, `target`, `passes`,
/// `final`, `untangling_impossible` and `time_ms`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Report {
    objective: ObjectiveKind,
    strategy: Strategy,
    target: Target,
    /// With sliding boundaries: what slid, and how far from the boundary as loaded.
    #[serde(skip_serializing_if = "Option::is_none")]
    boundary: Option<BoundaryReport>,
    #[serde(skip)]
    order: Order,
    passes: Vec<PassRecord>,
    /// How many of `passes`, the last ones, are the finish ([`Smoothing::FINISH`]).
    finish: u32,
    /// The same object as `smoothlab stats --json` of the smoothed mesh.
    #[serde(rename = "final")]
    final_stats: MeshStats,
    /// Inverted elements no smoother can make valid, and why (empty when there are none).
    untangling_impossible: Vec<Obstacle>,
    time_ms: f64,
}

impl Report {
    /// Inverted elements after the run.
    pub fn inverted(&self) -> usize {
        self.final_stats.inverted
    }
    /// One record a pass, the finish's last.
    pub fn passes(&self) -> &[PassRecord] {
        &self.passes
    }
    /// How many of [`passes`](Self::passes), the last ones, are the finish ([`Smoothing::FINISH`]).
    pub fn finish_passes(&self) -> u32 {
        self.finish
    }
    /// The statistics of the smoothed mesh (what `smoothlab stats` prints).
    pub fn stats(&self) -> &MeshStats {
        &self.final_stats
    }
    /// The inverted elements no move allowed by the fixed nodes can repair, and why.
    pub fn untangling_impossible(&self) -> &[Obstacle] {
        &self.untangling_impossible
    }
    /// What each corner was measured against in the passes before the finish (and in the
    /// finish, with the stretch target): [`Target::Stretch`] only where the mesh had a
    /// stretch made on purpose, else the ideal.
    pub fn target(&self) -> Target {
        self.target
    }
    /// The objective, strategy and node order of the run.
    pub fn settings(&self) -> (ObjectiveKind, Strategy, Order) {
        (self.objective, self.strategy, self.order)
    }
    /// With sliding boundaries ([`BoundaryRule::Slide`]): what slid and how far from the
    /// boundary as loaded; `None` with the boundary fixed.
    pub fn boundary(&self) -> Option<&BoundaryReport> {
        self.boundary.as_ref()
    }
    /// The time of the passes, milliseconds by the run's clock.
    pub fn time_ms(&self) -> f64 {
        self.time_ms
    }
}

impl Model {
    /// Smooths the mesh, whatever its kind, as `smoothlab smooth` does.
    ///
    /// Natively the passes are timed by the system's clock; in WebAssembly they read 0
    /// ([`smooth_with_clock`](Self::smooth_with_clock) takes a clock).
    pub fn smooth(&mut self, smoothing: &Smoothing) -> Result<Report> {
        #[cfg(not(target_arch = "wasm32"))]
        {
            let t0 = std::time::Instant::now();
            self.smooth_with_clock(smoothing, &move || t0.elapsed().as_secs_f64() * 1e3)
        }
        #[cfg(target_arch = "wasm32")]
        self.smooth_with_clock(smoothing, &|| 0.0)
    }

    /// The passes numbered `numbers` of one smoother with `options` and the objective of
    /// `kind`, the driver the mesh kind takes.
    fn passes(
        &mut self,
        kind: ObjectiveKind,
        penalty: Penalty,
        options: SmoothOptions,
        numbers: std::ops::Range<u32>,
        clock: &dyn Fn() -> f64,
    ) -> Result<Vec<PassRecord>> {
        Ok(match self {
            Model::Planar(mesh) => {
                let objective = objective_with(kind, penalty);
                let mut smoother = Smoother::new(options)?;
                numbers
                    .map(|_| smoother.pass(mesh, &*objective, clock))
                    .collect()
            }
            Model::Surface(surface) => {
                let objective = objective_with(kind, penalty);
                let mut smoother = SurfaceSmoother::new(options)?;
                numbers
                    .map(|_| smoother.pass(surface, &*objective, clock))
                    .collect()
            }
            Model::Volume(mesh) => {
                let objective = solid_objective(kind)?;
                let mut smoother = VolumeSmoother::new(options)?;
                numbers
                    .map(|p| smoother.pass(mesh, &*objective, p, clock))
                    .collect()
            }
        })
    }

    /// Sets what the boundary nodes of a planar or volume mesh do, where that changes (a
    /// surface's are not set by this rule).
    fn set_boundary(&mut self, rule: BoundaryRule, angle: f64) {
        match self {
            Model::Planar(m) if m.boundary_rule() != rule || m.feature_curves().is_some_and(|(a, _)| a != angle) => {
                m.set_boundary(rule, angle)
            }
            Model::Volume(v) if v.boundary_rule() != rule || v.feature_curves().is_some_and(|(a, _)| a != angle) => {
                v.set_boundary(rule, angle)
            }
            _ => {}
        }
    }

    /// The passes of `smoothing` over a tangled planar mesh with its boundary held, one at
    /// a time, until one leaves it valid; its boundary slides in the rest.
    fn passes_sliding_once_valid(
        &mut self,
        smoothing: &Smoothing,
        opts: SmoothOptions,
        clock: &dyn Fn() -> f64,
    ) -> Result<Vec<PassRecord>> {
        let (kind, penalty) = (smoothing.objective, smoothing.penalty.unwrap_or_default());
        let mut records = Vec::new();
        for p in 1..=smoothing.passes {
            records.extend(self.passes(kind, penalty, opts, p..p + 1, clock)?);
            if records.last().is_some_and(|r| r.after.inverted == 0) {
                self.set_boundary(BoundaryRule::Slide, smoothing.feature_angle_deg.unwrap_or(FEATURE_ANGLE_DEG));
                records.extend(self.passes(kind, penalty, opts, p + 1..smoothing.passes + 1, clock)?);
                break;
            }
        }
        Ok(records)
    }

    /// Smooths the mesh as [`smooth`](Self::smooth), timed by `clock` (milliseconds).
    pub fn smooth_with_clock(
        &mut self,
        smoothing: &Smoothing,
        clock: &dyn Fn() -> f64,
    ) -> Result<Report> {
        let mut opts = smoothing.options()?;
        smoothing.check(self)?;
        let kind = smoothing.objective;
        let start = clock();
        // the grading the whole run keeps, passes and finish alike: the mesh's as found
        let found = self.stats();
        opts.keep_grading = Some(found.grading_to_keep());
        // Freitag's `sine` on a valid mesh judges its moves by the smallest sine, as she
        // runs it (the page's sides and the reproduction's rows read the same rule)
        opts.smart_measure = crate::smooth::Measure::for_run(kind, found.inverted == 0);
        if let Model::Surface(surface) = self {
            // a surface's boundary is its curves: open edges and feature curves; the rule's
            // feature angle holds the corners where a curve turns sharply
            if smoothing.boundary == BoundaryRule::Slide {
                surface.slide_along_curves_with(Some(smoothing.feature_angle_deg.unwrap_or(FEATURE_ANGLE_DEG)));
            } else if smoothing.slide_curves {
                surface.slide_along_curves();
            }
        }
        // a tangled planar mesh's boundary edges are folded with it: its boundary is held
        // while it is tangled, and slides from the pass after the first that leaves it valid
        // (Mesquite's tangled quads: 2 inverted left sliding from the start, 0 so)
        let slide_once_valid = smoothing.boundary == BoundaryRule::Slide
            && matches!(&*self, Model::Planar(m) if (0..m.element_count()).any(|e| crate::smooth::mesh_element_is_inverted(m, e)));
        let rule = if slide_once_valid { BoundaryRule::Fixed } else { smoothing.boundary };
        self.set_boundary(rule, smoothing.feature_angle_deg.unwrap_or(FEATURE_ANGLE_DEG));
        let penalty = smoothing.penalty.unwrap_or_default();
        // the stretch target is the ideal where the mesh has no stretch made on purpose:
        // the report says which the corners were measured against
        let asked = smoothing.asked_target();
        self.set_target(asked);
        let target = if asked == Target::Stretch && !self.has_target() { Target::Ideal } else { asked };
        let passes = if slide_once_valid {
            self.passes_sliding_once_valid(smoothing, opts, clock)
        } else {
            self.passes(kind, penalty, opts, 1..smoothing.passes + 1, clock)
        };
        let mut passes = passes?;
        let valid = passes
            .last()
            .map_or_else(|| self.stats().inverted, |r| r.after.inverted)
            == 0;
        let main_passes = passes.len();
        // the finish measures against a target that reads the mesh's design (its stretch);
        // against the input's own corners it would find nothing to lift, so it lifts the
        // smallest sine the statistics read
        if target != Target::Stretch {
            self.set_target(Target::Ideal);
        }
        if smoothing.finish > 0 && valid {
            let (kind, strategy, order) = Smoothing::FINISH;
            let o = SmoothOptions {
                max_iter: opts.max_iter,
                keep_grading: opts.keep_grading,
                ..SmoothOptions::default()
            }
            .with_strategy(strategy)
            .with_order(order)
            .with_smart_measure(crate::smooth::Measure::MinSine);
            let first = passes.len() as u32 + 1;
            passes.extend(self.passes(
                kind,
                Penalty::default(),
                o,
                first..first + smoothing.finish,
                clock,
            )?);
        }
        self.set_target(Target::Ideal);
        for (i, r) in passes.iter_mut().enumerate() {
            r.pass = i as u32 + 1;
        }
        let finish = (passes.len() - main_passes) as u32;
        let time_ms = clock() - start;
        let final_stats = self.stats();
        // the obstacles are found in the plane (a surface's fixed nodes have no common one)
        let untangling_impossible = match &*self {
            Model::Planar(mesh) if final_stats.inverted > 0 => untangling_obstacles(mesh),
            Model::Volume(mesh) if final_stats.inverted > 0 => volume_untangling_obstacles(mesh),
            _ => Vec::new(),
        };
        let boundary = match &*self {
            Model::Volume(mesh) if mesh.boundary_rule() == BoundaryRule::Slide => Some(BoundaryReport::of(mesh)),
            Model::Planar(mesh) if mesh.boundary_rule() == BoundaryRule::Slide => Some(BoundaryReport::of_planar(mesh)),
            Model::Surface(s) if s.boundary_corner_deg().is_some() => Some(BoundaryReport::of_surface(s)),
            _ => None,
        };
        Ok(Report {
            objective: kind,
            strategy: smoothing.strategy,
            target,
            boundary,
            order: opts.order,
            passes,
            finish,
            final_stats,
            untangling_impossible,
            time_ms,
        })
    }
}

/// What a run with sliding boundaries did to the boundary (JSON key `boundary`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct BoundaryReport {
    /// The feature angle the curves were found by, degrees.
    pub feature_angle_deg: f64,
    /// Feature curves found on the boundary.
    pub curves: usize,
    /// Boundary nodes that slid on a surface, along a curve, and corners held.
    pub surface_nodes: usize,
    pub curve_nodes: usize,
    pub corners: usize,
    /// Boundary nodes held by the file's own flags.
    pub held: usize,
    /// The largest distance of a sliding node from the boundary as loaded.
    pub max_distance: f64,
    /// The mean length of the boundary's edges, to read `max_distance` by: a volume's
    /// skin as loaded, a planar mesh's boundary edges now, a surface's edges now.
    pub mean_edge: f64,
}

impl BoundaryReport {
    /// What `mesh`'s boundary rule holds now: its counts, and how far its sliding nodes
    /// are from the boundary as loaded (the page reports a side's mesh by it, as here).
    pub fn of(mesh: &crate::volume::VolumeMesh) -> BoundaryReport {
        let mut skin = vec![false; mesh.node_count()];
        for f in mesh.boundary_faces() {
            for &v in f.nodes() {
                skin[v as usize] = true;
            }
        }
        BoundaryReport::counted(
            mesh.feature_curves(),
            &skin,
            |n| mesh.boundary_node(n),
            mesh.max_distance_from_boundary(),
            mesh.skin_mean_edge().unwrap_or_else(|| mesh.mean_edge_length()),
        )
    }

    /// [`of`](Self::of) a planar mesh: its boundary edges are its curves.
    pub fn of_planar(mesh: &crate::Mesh) -> BoundaryReport {
        let mut on_boundary = vec![false; mesh.node_count()];
        let (mut length, mut edges) = (0.0, 0usize);
        for e in mesh.topology().boundary_edges() {
            on_boundary[e.a as usize] = true;
            on_boundary[e.b as usize] = true;
            length += mesh.nodes()[e.a as usize].distance(mesh.nodes()[e.b as usize]);
            edges += 1;
        }
        BoundaryReport::counted(
            mesh.feature_curves(),
            &on_boundary,
            |n| mesh.boundary_node(n),
            mesh.max_distance_from_boundary(),
            if edges == 0 { mesh.mean_edge_length() } else { length / edges as f64 },
        )
    }

    /// [`of`](Self::of) a surface: its curves (open edges and feature curves) are its
    /// boundary, the nodes on them slide along them, and its corners hold.
    pub fn of_surface(surface: &crate::surface::Surface) -> BoundaryReport {
        let c = surface.boundary_counts();
        BoundaryReport {
            feature_angle_deg: surface.boundary_corner_deg().unwrap_or(0.0),
            curves: c.curves,
            surface_nodes: 0,
            curve_nodes: c.sliding,
            corners: c.corners,
            held: c.held,
            max_distance: surface.max_distance_from_curves(),
            mean_edge: surface.mean_edge_length(),
        }
    }

    fn counted(
        curves: Option<(f64, usize)>,
        on_boundary: &[bool],
        class: impl Fn(usize) -> Option<crate::mesh::BoundaryNode>,
        max_distance: f64,
        mean_edge: f64,
    ) -> BoundaryReport {
        use crate::mesh::BoundaryNode as B;
        let (angle, curves) = curves.unwrap_or((0.0, 0));
        let on = |c: B| (0..on_boundary.len()).filter(|&n| class(n) == Some(c)).count();
        let held = (0..on_boundary.len()).filter(|&n| on_boundary[n] && class(n) == Some(B::Held)).count();
        BoundaryReport {
            feature_angle_deg: angle,
            curves,
            surface_nodes: on(B::Surface),
            curve_nodes: on(B::Curve),
            corners: on(B::Corner),
            held,
            max_distance,
            mean_edge,
        }
    }
}
