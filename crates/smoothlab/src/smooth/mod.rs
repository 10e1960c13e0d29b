//! Smoothing drivers: Laplacian, smart (constrained) Laplacian, optimization, Freitag's
//! combined schemes C1/C2/C3 and Chen's rules, visiting nodes in input or priority order.
//!
//! The drivers work with any [`Objective`] and either solver ([`SolverKind`](crate::optimize::SolverKind)): a new
//! objective never touches this module. A [`Smoother`] owns its scratch buffers (the star,
//! the solvers' term vectors, the visit schedule) and runs one [`pass`](Smoother::pass)
//! at a time, so the page can step pass by pass; [`solve_node`] solves one node with its
//! history for the page's level-set view.
//!
//! Nodes move one at a time in place (Gauss–Seidel): a node sees the new positions of the
//! nodes visited before it. Fixed nodes and mid-side nodes are never smoothed; after a
//! corner node moves, the mid-side nodes of its straight edges follow it
//! ([`Mesh::follow_mid_nodes`]); curved boundary edges keep their mid node.
//!
//! The formulas, in one notation: `docs/formulas.md` §4.

use glam::DVec2;

use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::objective::{NodeStar, Objective, Point, Star, Term};
use crate::optimize::{evaluate, SolveResult, Solvers};
use crate::quality::{mesh_stats, Reading};

mod accept;
pub mod fit;
mod guard;
pub mod limits;
mod measure;
mod obstacles;
mod options;
pub mod parallel;
mod plan;
mod records;
mod space;
#[cfg(test)]
mod tests;

pub use accept::{ElementScore, Size, Verdict, MIN_SIZE_RATIO};
use guard::{Along, KeepValid};
pub(crate) use measure::{is_inverted, mesh_element_is_inverted};
pub(crate) use measure::triangle_shape_at;
use measure::triangle_shape_at_both;
pub use measure::StarQuality;
#[cfg(test)]
pub(crate) use measure::{element_measures, element_shape_at, star_quality, star_shape};
pub use fit::{FIT_PATIENCE, FIT_SIZE_WEIGHT, FIT_TOLERANCE, MAX_FIT_STEPS};
pub use obstacles::{untangling_obstacles, volume_untangling_obstacles, Obstacle};
pub use options::{
    Measure, Order, SmoothOptions, Strategy, DEFAULT_MAX_ITER, DEFAULT_PASSES,
    DEFAULT_THRESHOLD_DEG, UNTANGLE_SWEEPS,
};
pub use records::{NodeOutcome, PassRecord, SweepCounts};
pub use space::{DriverStar, FastSmart, SmoothMesh};

/// Centroid of the neighbouring corner nodes of `n` (Laplacian smoothing).
fn centroid<M: SmoothMesh + ?Sized>(mesh: &M, n: usize) -> Option<M::Point> {
    let nb = mesh.neighbours(n);
    if nb.is_empty() {
        return None;
    }
    let s = nb
        .iter()
        .fold(M::Point::ZERO, |s, &m| s + mesh.position(m as usize));
    Some(s / nb.len() as f64)
}

/// Where a driver reads a node's star and puts the node it moved. A planar mesh is its own
/// view ([`Planar`]); a surface flattens each star into its tangent plane first
/// ([`crate::surface`]). The drivers are generic over it, so the planar path pays nothing.
pub(crate) trait StarView {
    /// The mesh the drivers read (planar for a planar mesh and a surface).
    type Mesh: SmoothMesh;
    /// The elements, topology and fixed flags.
    fn mesh(&self) -> &Self::Mesh;
    /// A mesh in which free node `n`'s star — its elements' nodes — has its positions
    /// now (a planar or tetrahedral mesh: itself).
    fn star_mesh(&mut self, n: usize) -> &Self::Mesh;
    /// Moves free node `n` to `x`, a position in the coordinates of the last
    /// [`star_mesh(n)`](Self::star_mesh); the mid-side nodes that follow it follow.
    fn place(&mut self, n: usize, x: <Self::Mesh as SmoothMesh>::Point);
    /// Whether element `e` is inverted now.
    fn is_inverted(&self, e: usize) -> bool;
    /// Whether the view applies the acceptance rule itself, after placing a node
    /// ([`place_if_no_worse`](Self::place_if_no_worse)), rather than the drivers on the
    /// star they gathered: a surface, whose node is projected back onto the reference.
    const CHECKS_ON_PLACING: bool = false;
    /// [`place`](Self::place), kept only when the star gets no worse by `measure` (the
    /// acceptance rule, [`accept`]); returns whether the node moved. Called only where
    /// [`CHECKS_ON_PLACING`](Self::CHECKS_ON_PLACING).
    fn place_if_no_worse(
        &mut self,
        n: usize,
        x: <Self::Mesh as SmoothMesh>::Point,
        _measure: Measure,
    ) -> bool {
        self.place(n, x);
        true
    }
}

/// A planar mesh as its own [`StarView`].
pub(crate) struct Planar<'a>(pub &'a mut Mesh);

impl StarView for Planar<'_> {
    type Mesh = Mesh;
    #[inline]
    fn mesh(&self) -> &Mesh {
        self.0
    }
    #[inline]
    fn star_mesh(&mut self, _: usize) -> &Mesh {
        self.0
    }
    #[inline]
    fn place(&mut self, n: usize, x: DVec2) {
        self.0.nodes_mut()[n] = x;
        if self.0.has_quadratic() {
            self.0.follow_mid_nodes(n);
        }
        self.0.settle(n);
    }
    fn is_inverted(&self, e: usize) -> bool {
        measure::mesh_element_is_inverted(self.0, e)
    }
}

/// A planar mesh seen read-only, for planning (which never places a node).
pub(crate) struct ReadOnly<'a>(pub(crate) &'a Mesh);

impl StarView for ReadOnly<'_> {
    type Mesh = Mesh;
    #[inline]
    fn mesh(&self) -> &Mesh {
        self.0
    }
    #[inline]
    fn star_mesh(&mut self, _: usize) -> &Mesh {
        self.0
    }
    fn place(&mut self, _: usize, _: DVec2) {
        unreachable!("planning does not move nodes")
    }
    fn is_inverted(&self, e: usize) -> bool {
        measure::mesh_element_is_inverted(self.0, e)
    }
}

/// A smoothing driver with its scratch buffers. One `Smoother` serves any number of passes
/// over one mesh (or several meshes in turn); nothing is allocated per node.
///
/// The smoother is generic over the star it gathers ([`DriverStar`]): a planar mesh's
/// [`Star`] (the default) or a tetrahedral mesh's ([`crate::volume`]); every strategy,
/// order and sweep below is written once for both.
#[derive(Clone, Debug)]
pub struct Smoother<S: DriverStar = Star> {
    options: SmoothOptions,
    /// What the statistics read of the mesh at the start of the pass ([`Reading`]), `None`
    /// for a tangled mesh: a move on a valid star keeps its star within it. Taken at the
    /// pass's first such move; forgotten when a pass is planned.
    bounds: std::sync::OnceLock<Option<Reading>>,
    /// The mesh's grading at the run's start ([`Reading::grading`]): a move keeps every
    /// pair of neighbours within it. The run's, not the pass's: the objectives do not aim
    /// at sizes, so a bound that fell pass by pass would freeze them. +∞ for a run that
    /// starts tangled (the rule keeps valid meshes from getting worse).
    pub(super) grading_bound: Option<f64>,
    star: S,
    solvers: Solvers<S>,
    terms: Vec<Term<S::Point>>,
    /// Star quality of each node when the schedule was planned (priority order).
    quality: Vec<f64>,
    /// Free nodes, worst first.
    ranked: Vec<u32>,
    /// Visit sequence of the current (or last) pass.
    schedule: Vec<u32>,
    /// Next node to measure while planning in steps ([`Smoother::plan_some`]).
    plan_next: usize,
    /// Visit sequence of the current (or last) untangling sweep.
    revisits: Vec<u32>,
    /// Per node: whether it is already in `revisits` (scratch, all false between uses).
    marked: Vec<bool>,
    /// The pass's move count when its last untangling sweep was planned (`None` before the
    /// first sweep of a pass): a sweep that added no move ends the sweeps.
    sweep_moves_from: Option<u32>,
    passes: u32,
    /// Per-mesh facts, refreshed each pass.
    quadratic: bool,
    curved: bool,
    /// `sin θ_t` of the combined schemes, computed once (not per visit).
    sine_threshold: f64,
    /// Whether the mesh had an inverted element when the pass was planned
    /// ([`note_tangled`](Self::note_tangled)): the untangling objectives optimise only then.
    tangled: bool,
    /// Whether the run's fit to the targets was tried ([`fit`]): once, at its first pass.
    fit_tried: bool,
}

impl<S: DriverStar> Smoother<S> {
    /// Whether the run's fit to the targets ([`fit`]) is to run now: at the run's first
    /// sweep, on a mesh with targets other than the ideal, where moves are judged (every
    /// strategy but the plain Laplacian, the guard on). Then not again.
    pub(crate) fn fit_due(&mut self, has_target: bool) -> bool {
        let o = self.options;
        let judged = o.keep_valid && o.strategy != Strategy::Laplace;
        !std::mem::replace(&mut self.fit_tried, true) && has_target && judged
    }

    /// Whether the next sweep is the run's first (the fit to the targets not yet tried).
    pub(crate) fn at_run_start(&self) -> bool {
        !self.fit_tried
    }

    /// Sets whether the run's fit to the targets ([`fit`]) is still to be tried: for a
    /// smoother made anew between a run's passes (the page makes one for each pass's
    /// settings), whether this pass is the run's first.
    pub fn set_fit_pending(&mut self, pending: bool) {
        self.fit_tried = !pending;
    }

    /// The run's grading bound ([`grading_bound`](Self::grading_bound)), set by the first
    /// reading: `grading` where none was set yet.
    pub(crate) fn grading_bound_or(&mut self, grading: f64) -> f64 {
        *self.grading_bound.get_or_insert(grading)
    }

    /// A smoother with checked options.
    pub fn new(options: SmoothOptions) -> Result<Self> {
        options.validate()?;
        let solve = options.solve_options();
        Ok(Smoother {
            options,
            bounds: std::sync::OnceLock::new(),
            grading_bound: None,
            star: S::default(),
            solvers: Solvers::new(solve),
            terms: Vec::new(),
            quality: Vec::new(),
            ranked: Vec::new(),
            schedule: Vec::new(),
            plan_next: 0,
            revisits: Vec::new(),
            marked: Vec::new(),
            sweep_moves_from: None,
            passes: 0,
            quadratic: false,
            curved: false,
            sine_threshold: options.threshold_deg.to_radians().sin(),
            tangled: true,
            fit_tried: false,
        })
    }

    pub fn options(&self) -> &SmoothOptions {
        &self.options
    }

    /// Passes run so far.
    pub fn passes(&self) -> u32 {
        self.passes
    }

    /// The visit sequence planned by the last [`plan`](Self::plan) (or pass).
    pub fn schedule(&self) -> &[u32] {
        &self.schedule
    }

    fn refresh_mesh_facts(&mut self, mesh: &S::Mesh) {
        self.quadratic = mesh.has_quadratic();
        self.curved = self.quadratic && mesh.has_curved_edges();
    }

    /// [`sweep`](Smoother::sweep) over any [`StarView`].
    pub(crate) fn sweep_in<V: StarView<Mesh = S::Mesh>>(
        &mut self,
        view: &mut V,
        objective: &dyn Objective<S>,
    ) -> SweepCounts {
        self.begin_plan(view.mesh());
        while !self.plan_some_in(view, usize::MAX) {}
        let schedule = std::mem::take(&mut self.schedule);
        let mut counts = self.visit_all_in(view, &schedule, objective);
        self.schedule = schedule;
        while self.plan_untangle_sweep_in(view, &mut counts) {
            let revisits = std::mem::take(&mut self.revisits);
            let c = self.visit_all_in(view, &revisits, objective);
            self.revisits = revisits;
            counts.merge(c);
        }
        counts
    }

    pub(crate) fn visit_all_in<V: StarView<Mesh = S::Mesh>>(
        &mut self,
        view: &mut V,
        order: &[u32],
        objective: &dyn Objective<S>,
    ) -> SweepCounts {
        let mut c = SweepCounts::default();
        // node order reads the mesh front to back, as the hardware's prefetchers expect; a
        // worst-first order (the priority order, the untangling sweeps) jumps about it
        let scattered = order.windows(2).any(|w| w[0] > w[1]);
        let mut read = 0u32;
        for (k, &n) in order.iter().enumerate() {
            if scattered {
                for (stage, &ahead) in space::READ_AHEAD.iter().enumerate() {
                    if let Some(&m) = order.get(k + ahead) {
                        read ^= view.mesh().read_ahead(m as usize, stage);
                    }
                }
            }
            c.add(self.visit(view, n as usize, objective));
        }
        std::hint::black_box(read);
        c
    }

    pub(crate) fn objective_total_in<V: StarView<Mesh = S::Mesh>>(
        &mut self,
        view: &mut V,
        objective: &dyn Objective<S>,
    ) -> f64 {
        let mut total = 0.0;
        for n in 0..view.mesh().node_count() {
            if view.mesh().is_free(n) {
                let mesh = view.star_mesh(n);
                self.star.gather(mesh, n);
                total += evaluate(objective, &self.star, mesh.position(n), &mut self.terms).0;
            }
        }
        total
    }

    fn visit<V: StarView<Mesh = S::Mesh>>(
        &mut self,
        view: &mut V,
        n: usize,
        objective: &dyn Objective<S>,
    ) -> NodeOutcome {
        if n >= view.mesh().node_count() || !view.mesh().is_free(n) {
            return NodeOutcome::default();
        }
        if V::CHECKS_ON_PLACING && self.accepts_only_no_worse() {
            let (x, mut out, _) = self.decide_move(view.star_mesh(n), n, objective);
            if out.moved {
                out.moved = view.place_if_no_worse(n, x, self.options.smart_measure);
            }
            return out;
        }
        let (x, out) = self.decide(view.star_mesh(n), n, objective);
        if out.moved {
            view.place(n, x);
        }
        out
    }

    /// Whether moves are kept only by the acceptance rule ([`accept`], by
    /// [`SmoothOptions::smart_measure`]): every strategy but the plain Laplacian, with the
    /// validity guard on.
    fn accepts_only_no_worse(&self) -> bool {
        self.options.keep_valid && self.options.strategy != Strategy::Laplace
    }

    /// Where the strategy moves node `n`, without writing to the mesh: the new position
    /// (the old one when it stays) and what happened. The node's own position is tracked
    /// in the gathered star ([`Star::x0`], kept current by `restar`) and mid-side nodes
    /// that follow it are moved in the star only, so a node reads nothing but its star and
    /// its neighbours. Nodes that share no element can therefore be decided in any order,
    /// or at once ([`crate::smooth::parallel`]), with the same results.
    ///
    /// A move is kept only when the star gets no worse (the acceptance rule, [`accept`],
    /// `docs/formulas.md` §4), measured on the star as it is in `mesh` and with the node
    /// moved; otherwise the node stays.
    pub(crate) fn decide(
        &mut self,
        mesh: &S::Mesh,
        n: usize,
        objective: &dyn Objective<S>,
    ) -> (S::Point, NodeOutcome) {
        let (mut x, mut out, mut kept) = self.decide_move(mesh, n, objective);
        if out.moved {
            // a node that slides goes onto the boundary, and is measured there (with the
            // mid-side nodes it carries, which no test before this one saw)
            let on = mesh.onto_boundary(n, x);
            if on != x || mesh.carries_on_boundary(n) {
                (x, kept) = (on, false);
                out.moved = x != mesh.position(n);
                if !out.moved {
                    return (x, out);
                }
            }
        }
        if out.moved && self.accepts_only_no_worse() {
            // a move the smart Laplacian's test kept was on a valid star
            let (keeps, valid) = if kept {
                (true, true)
            } else {
                self.star.regather(mesh, n);
                let v = self.star.verdict_in(mesh, x, self.options.smart_measure);
                (v.keeps(), v.was_valid())
            };
            let within_bounds = |s: &mut Self| match *s.bounds.get_or_init(|| mesh.valid_reading())
            {
                Some(bounds) => {
                    // the acceptance rule by the shape keeps each star's worst shape already
                    let mut bounds = if s.options.smart_measure == Measure::Shape {
                        bounds.without_quality()
                    } else {
                        bounds
                    };
                    bounds.grading = *s.grading_bound.get_or_insert(bounds.grading);
                    if kept {
                        // the smart Laplacian's test read the mesh, not the star
                        if let Some(within) = S::reads_within_from_mesh(mesh, n, x, &bounds) {
                            return within;
                        }
                        s.star.regather(mesh, n);
                    }
                    s.star.reads_within(mesh, x, &bounds)
                }
                None => {
                    // a run that starts tangled has no grading to keep
                    s.grading_bound.get_or_insert(f64::INFINITY);
                    true
                }
            };
            if !keeps || (valid && !within_bounds(self)) {
                out.moved = false;
                return (mesh.position(n), out);
            }
        }
        (x, out)
    }

    /// [`decide`](Self::decide) without the acceptance rule (a surface's view applies it
    /// after projecting the node back onto the surface), and whether the move is already
    /// known to pass it (the smart Laplacian's test read from the mesh found the star
    /// valid, its worst shape raised and no element shrunk below the rule's floor:
    /// [`FastSmart::kept`]).
    fn decide_move(
        &mut self,
        mesh: &S::Mesh,
        n: usize,
        objective: &dyn Objective<S>,
    ) -> (S::Point, NodeOutcome, bool) {
        let mut out = NodeOutcome::default();
        let mut kept = false;
        if n >= mesh.node_count() || !mesh.is_free(n) {
            return (S::Point::ZERO, out, kept);
        }
        let x0 = mesh.position(n);
        let mut x = x0;
        let sine_t = self.sine_threshold;
        match self.options.strategy {
            Strategy::Laplace => {
                if let Some(c) = self.laplace(mesh, n, &mut out) {
                    x = c;
                }
            }
            Strategy::Smart => match S::smart_from_mesh(mesh, n, self.options.smart_measure) {
                Some(t) => {
                    if let Some(c) = t.to {
                        out.laplacian = true;
                        x = c;
                        kept = t.kept;
                    }
                }
                None => {
                    self.star.gather(mesh, n);
                    self.smart(mesh, n, &mut out);
                    x = self.star.x0();
                }
            },
            Strategy::Opt => {
                self.star.gather(mesh, n);
                self.optimize(objective, &mut out);
                x = self.star.x0();
            }
            Strategy::C1 => {
                self.star.gather(mesh, n);
                if self.star.quality(None).min_sine > sine_t {
                    self.smart(mesh, n, &mut out);
                } else {
                    self.optimize(objective, &mut out);
                }
                x = self.star.x0();
            }
            Strategy::C2 => {
                self.star.gather(mesh, n);
                self.smart(mesh, n, &mut out);
                if self.star.quality(None).min_sine <= sine_t {
                    self.optimize(objective, &mut out);
                }
                x = self.star.x0();
            }
            Strategy::C3 => {
                self.star.gather(mesh, n);
                let before = self.star.quality(None);
                if before.min_sine <= sine_t {
                    if let Some(c) = self.laplace(mesh, n, &mut out) {
                        self.restar(c);
                    }
                    if self.star.quality(None).min_sine <= sine_t {
                        self.optimize(objective, &mut out);
                    }
                    // Freitag's C3 starts with the plain Laplacian, which may fold an element
                    // or lower the star's quality (the smart Laplacian's measure), and the
                    // optimization from there may not win it back. Like the other combined
                    // schemes, C3 never leaves a star worse than it found it: then the node
                    // stays where it was.
                    let after = self.star.quality(None);
                    let m = self.options.smart_measure;
                    if after.inverted > before.inverted || after.measure(m) < before.measure(m) {
                        self.restar(x0);
                    }
                }
                x = self.star.x0();
            }
            Strategy::Rules => {
                // rule 1 (a curved boundary node next to it) or the caller's force:
                // optimised without trying the Laplacian
                // (and with a target other than the ideal, whose answer the Laplacian's is not)
                let forced = self.options.force_optimization
                    || mesh.has_target()
                    || self.touches_curved_boundary(mesh, n);
                // the smart Laplacian from the mesh where it can; the star is gathered only
                // when the node is optimised (rule 2: an inverted element; rule 3: the smart
                // Laplacian did not move it)
                match (!forced)
                    .then(|| S::smart_from_mesh(mesh, n, self.options.smart_measure))
                    .flatten()
                {
                    Some(FastSmart {
                        inverted: 0,
                        to: Some(c),
                        kept: k,
                    }) => {
                        out.laplacian = true;
                        x = c;
                        kept = k;
                    }
                    Some(_) => {
                        self.star.gather(mesh, n);
                        self.optimize(objective, &mut out);
                        x = self.star.x0();
                    }
                    None => {
                        self.star.gather_for_measures(mesh, n);
                        let optimise = forced || self.star.any_inverted_now();
                        if optimise || !self.smart(mesh, n, &mut out) {
                            self.optimize(objective, &mut out);
                        }
                        x = self.star.x0();
                    }
                }
            }
        }
        out.moved = x != x0;
        (x, out, kept)
    }

    /// Moves the gathered star's free node to `x` (after a move), keeping the star valid.
    fn restar(&mut self, x: S::Point) {
        self.star.restar(x);
    }

    /// Plain Laplacian: the centroid when the node moves there, `None` when it stays.
    fn laplace(&mut self, mesh: &S::Mesh, n: usize, out: &mut NodeOutcome) -> Option<S::Point> {
        match centroid(mesh, n) {
            Some(c) if c.is_finite() && c != mesh.position(n) => {
                out.laplacian = true;
                Some(c)
            }
            _ => None,
        }
    }

    /// Smart Laplacian on the gathered star; returns whether the node moved (the star is
    /// moved with it). The star's quality now is measured at the star's position; at the
    /// centroid with the mid-side nodes of straight edges following
    /// ([`DriverStar::smart_accepts`]).
    fn smart(&mut self, mesh: &S::Mesh, n: usize, out: &mut NodeOutcome) -> bool {
        let Some(c) = centroid(mesh, n) else {
            return false;
        };
        if !c.is_finite() || c == self.star.x0() {
            return false;
        }
        if self.star.smart_accepts(c, self.options.smart_measure) {
            self.restar(c);
            out.laplacian = true;
            true
        } else {
            false
        }
    }

    /// Optimization with the chosen solver on the gathered star, from the star's position.
    /// With [`SmoothOptions::keep_valid`] the solver sees the objective through
    /// [`KeepValid`].
    ///
    /// An objective that only untangles ([`Objective::only_untangles`]: flat, or blind to
    /// shape, on valid stars) leaves a valid mesh where it is, as Mesquite's untangler
    /// stops at once on a valid mesh: it optimises only while the mesh was tangled when the
    /// pass was planned ([`note_tangled`](Self::note_tangled)).
    fn optimize(&mut self, objective: &dyn Objective<S>, out: &mut NodeOutcome) {
        if objective.only_untangles() && !self.tangled {
            return;
        }
        self.star.complete();
        let x0 = self.star.x0();
        let guarded;
        let objective: &dyn Objective<S> = if self.options.keep_valid {
            // by the corner edges scaled to unit size (the gathered star is in mesh units,
            // where a triangle's own cross products can underflow)
            let limit = self.star.inverted_now();
            let pass_through_folds = self
                .options
                .pass_through_folds
                .unwrap_or_else(|| objective.untangles());
            guarded = KeepValid::new(objective, limit, pass_through_folds);
            &guarded
        } else {
            objective
        };
        let along;
        let objective: &dyn Objective<S> = if self.star.slides() {
            along = Along { inner: objective };
            &along
        } else {
            objective
        };
        let r = self
            .solvers
            .get(self.options.solver, objective.goal())
            .solve(objective, &self.star, x0);
        out.optimized = true;
        out.iterations += r.iterations;
        if r.x.is_finite() && r.x != x0 {
            self.restar(r.x);
        }
    }

    /// Chen's rule 1: the node, a neighbour, or a node of a star element lies on a curved
    /// boundary edge.
    fn touches_curved_boundary(&self, mesh: &S::Mesh, n: usize) -> bool {
        self.curved && mesh.touches_curved_boundary(n)
    }
}

/// The smart Laplacian's test ([`DriverStar::smart_accepts`]) on a planar star of linear
/// triangles, read from the mesh without gathering the star: per element the two other
/// corners, where a gathered star copies 160 bytes. The same arithmetic in the same order
/// ([`triangle_shape_at`], what [`element_shape_at`] computes for a linear triangle), so
/// the same answer. `None` when an element of the star is not a linear triangle, a
/// triangle needs the general measure (squares beyond the doubles even when scaled), or
/// the measure is not [`Measure::Shape`]: the gathered star decides then.
fn smart_on_triangles(mesh: &Mesh, n: usize, measure: Measure) -> Option<FastSmart<DVec2>> {
    if measure != Measure::Shape {
        return None;
    }
    let x0 = mesh.nodes()[n];
    let c = centroid(mesh, n).filter(|c| c.is_finite() && *c != x0);
    let t = triangles_at(mesh, n, c)?;
    let to = c.filter(|_| !t.folds && t.after > t.before);
    Some(FastSmart {
        inverted: t.inverted,
        to,
        kept: to.is_some() && t.inverted == 0 && !t.shrinks,
    })
}

/// The smallest shape measure (α) of a planar star of linear triangles at the node's
/// position, read from the mesh as [`smart_on_triangles`] reads it: what
/// [`DriverStar::shape_at`] of the gathered star gives, bit for bit (the priority order
/// measures every star so). `None` where [`smart_on_triangles`] is.
pub(crate) fn shape_on_triangles(mesh: &Mesh, n: usize) -> Option<f64> {
    triangles_at(mesh, n, None).map(|t| t.before)
}

/// What the smart Laplacian's test reads of a star of linear triangles (see
/// [`smart_on_triangles`]): the smallest α now and with the node at `c`, the elements
/// inverted now, whether the move folds one, and whether it may shrink one valid now below
/// the acceptance rule's floor ([`MIN_SIZE_RATIO`] of its area; also where the areas are
/// not plain doubles, and the rule measures).
struct TrianglesAt {
    before: f64,
    after: f64,
    inverted: u32,
    folds: bool,
    shrinks: bool,
}

#[inline]
fn triangles_at(mesh: &Mesh, n: usize, c: Option<DVec2>) -> Option<TrianglesAt> {
    let x0 = mesh.nodes()[n];
    let mut t = TrianglesAt {
        before: f64::INFINITY,
        after: f64::INFINITY,
        inverted: 0,
        folds: false,
        shrinks: false,
    };
    for &e in mesh.node_elements(n) {
        let e = e as usize;
        if mesh.kind(e) != crate::mesh::ElementKind::Tri3 {
            return None;
        }
        let ids = mesh.element(e);
        let s = ids.iter().position(|&i| i as usize == n)?;
        let (a, b) = (
            mesh.nodes()[ids[(s + 1) % 3] as usize],
            mesh.nodes()[ids[(s + 2) % 3] as usize],
        );
        let Some(c) = c else {
            let (q0, inv0) = triangle_shape_at(a, b, x0)?;
            t.inverted += inv0 as u32;
            t.before = t.before.min(q0);
            continue;
        };
        let ((q0, inv0), (q1, inv1)) = triangle_shape_at_both(a, b, x0, c)?;
        t.inverted += inv0 as u32;
        t.before = t.before.min(q0);
        t.folds |= !inv0 && inv1;
        t.after = t.after.min(q1);
        let (n0, n1) = ((a - x0).perp_dot(b - x0), (a - c).perp_dot(b - c));
        let floor = MIN_SIZE_RATIO * n0;
        let kept = floor.is_normal() && n0.is_finite() && n1 >= floor;
        t.shrinks |= !inv0 && !kept;
    }
    Some(t)
}

/// The planar mesh's entry points: a pass with its record, a sweep, one node.
impl Smoother<Star> {
    /// One pass over the mesh: plan the visit order, smooth each visit, then measure.
    /// `clock` returns milliseconds (any origin); the core never reads system time.
    pub fn pass(
        &mut self,
        mesh: &mut Mesh,
        objective: &dyn Objective,
        clock: &dyn Fn() -> f64,
    ) -> PassRecord {
        self.passes += 1;
        let t0 = clock();
        let counts = self.sweep(mesh, objective);
        let elapsed = clock() - t0;
        self.record(mesh, objective, self.passes, counts, elapsed, clock)
    }

    /// The record of a pass: its counts and time, and the mesh's statistics now.
    pub(crate) fn record(
        &mut self,
        mesh: &Mesh,
        objective: &dyn Objective,
        pass: u32,
        counts: SweepCounts,
        elapsed_ms: f64,
        clock: &dyn Fn() -> f64,
    ) -> PassRecord {
        let t0 = clock();
        let after = mesh_stats(mesh).quick();
        let objective_total = Some(self.objective_total(mesh, objective));
        PassRecord {
            pass,
            counts,
            after,
            objective_total,
            elapsed_ms,
            stats_ms: clock() - t0,
        }
    }

    /// The node loop of a pass alone: plans the visit order and smooths each visit, without
    /// the statistics [`pass`](Self::pass) adds (a whole-mesh [`mesh_stats`] and
    /// [`objective_total`](Self::objective_total), which cost more than a Laplacian sweep).
    /// Counts as [`pass`](Self::pass) does; does not count as a pass.
    ///
    /// A tangled mesh never ends it with more inverted elements than it began with
    /// (the elements it inverted go back where it found their nodes; every strategy but the
    /// plain Laplacian, the guard on).
    pub fn sweep(&mut self, mesh: &mut Mesh, objective: &dyn Objective) -> SweepCounts {
        let o = self.options;
        if !(o.keep_valid && o.strategy != Strategy::Laplace) {
            return self.sweep_in(&mut Planar(mesh), objective);
        }
        let fit_steps = self.fit_first(mesh, objective);
        let (start, was) = (mesh.nodes().to_vec(), planar_inverted(mesh));
        let mut counts = self.sweep_in(&mut Planar(mesh), objective);
        counts.fit_steps = fit_steps;
        undo_new_inversions(
            mesh,
            &was,
            planar_inverted,
            |m, e| m.element(e).to_vec(),
            |m, i| m.nodes_mut()[i] = start[i],
        );
        counts
    }

    /// The run's fit to the targets ([`fit`]), where it is due: at the first sweep of a
    /// run on a mesh with targets other than the ideal, with an objective that has a
    /// Hessian (`new`). Returns the steps it kept (0 where it did not run).
    /// [`sweep`](Self::sweep) runs it; a pass run in steps runs it before planning.
    pub fn fit_first(&mut self, mesh: &mut Mesh, objective: &dyn Objective) -> u32 {
        if !self.fit_due(mesh.has_target()) {
            return 0;
        }
        // as a volume's: only where the objective has a Hessian (`new`'s sum)
        let Some(free) = (0..mesh.node_count()).find(|&i| mesh.is_free(i)) else {
            return 0;
        };
        self.star.gather(mesh, free);
        if objective.value_gradient_hessian(&self.star, mesh.nodes()[free]).is_none() {
            return 0;
        }
        fit::fit_planar(mesh, self.options.keep_grading.unwrap_or(f64::INFINITY))
    }

    /// Visits the nodes of `order` in turn (the mesh facts must be fresh).
    pub fn visit_all(
        &mut self,
        mesh: &mut Mesh,
        order: &[u32],
        objective: &dyn Objective,
    ) -> SweepCounts {
        self.visit_all_in(&mut Planar(mesh), order, objective)
    }

    /// The sum over free nodes of the node objective value (see [`PassRecord::objective_total`]).
    pub fn objective_total(&mut self, mesh: &Mesh, objective: &dyn Objective) -> f64 {
        self.objective_total_in(&mut ReadOnly(mesh), objective)
    }

    /// Smooths one node by the strategy (fixed nodes and mid-side nodes are left alone).
    pub fn smooth_node(
        &mut self,
        mesh: &mut Mesh,
        node: usize,
        objective: &dyn Objective,
    ) -> NodeOutcome {
        self.refresh_mesh_facts(mesh);
        if objective.only_untangles() {
            self.note_tangled(&ReadOnly(mesh));
        }
        self.visit(&mut Planar(mesh), node, objective)
    }
}

/// Runs `passes` passes of a new [`Smoother`] over `mesh`, returning their records.
pub fn smooth(
    mesh: &mut Mesh,
    objective: &dyn Objective,
    options: SmoothOptions,
    passes: u32,
    clock: &dyn Fn() -> f64,
) -> Result<Vec<PassRecord>> {
    let mut s = Smoother::new(options)?;
    Ok((0..passes)
        .map(|_| s.pass(mesh, objective, clock))
        .collect())
}

/// Solves the objective at one free node with its history recorded, without moving it
/// (for the page's level-set view and convergence chart). The solver is chosen by
/// [`SmoothOptions::solver`]; [`SmoothOptions::max_iter`] limits the iterations.
pub fn solve_node(
    mesh: &Mesh,
    node: usize,
    objective: &dyn Objective,
    options: &SmoothOptions,
) -> Result<SolveResult> {
    if node >= mesh.node_count() {
        return Err(Error::node(
            node,
            None,
            format!("no such node: the mesh has {} nodes", mesh.node_count()),
        ));
    }
    if !mesh.is_free(node) {
        return Err(Error::node(
            node,
            None,
            "is fixed or not an element corner, so it is never smoothed",
        ));
    }
    let mut star = Star::new();
    star.gather(mesh, node);
    solve_star(objective, &star, mesh.nodes()[node], options)
}

/// [`solve_star`] on a planar star (a planar mesh's, or a surface's flattened into its
/// tangent plane). It is compiled in this crate, so a caller in another crate shares the
/// solvers' code with the drivers instead of compiling a copy of its own.
pub fn solve_planar_star(
    objective: &dyn Objective,
    star: &Star,
    x0: DVec2,
    options: &SmoothOptions,
) -> Result<SolveResult> {
    solve_star(objective, star, x0, options)
}

/// [`solve_star`] on a volume mesh's star of element corners, compiled in this crate (see
/// [`solve_planar_star`]). A node that slides on the boundary is solved in its tangent
/// plane or line, as the drivers solve it (`guard::Along`); the caller puts the result on
/// the boundary.
pub fn solve_corner_star(
    objective: &dyn Objective<crate::objective::CornerStar>,
    star: &crate::objective::CornerStar,
    x0: glam::DVec3,
    options: &SmoothOptions,
) -> Result<SolveResult<glam::DVec3>> {
    if DriverStar::slides(star) {
        return solve_star(&guard::Along { inner: objective }, star, x0, options);
    }
    solve_star(objective, star, x0, options)
}

/// [`solve_node`] on a star already gathered (of any kind: a surface's star flattened into
/// its tangent plane, a star of tetrahedra), from `x0`, with the solver's history.
pub fn solve_star<S: NodeStar>(
    objective: &dyn Objective<S>,
    star: &S,
    x0: S::Point,
    options: &SmoothOptions,
) -> Result<SolveResult<S::Point>> {
    let solve = options.solve_options().with_history(true);
    solve.validate()?;
    Ok(Solvers::<S>::new(solve)
        .get(options.solver, objective.goal())
        .solve(objective, star, x0))
}

/// Which elements of `mesh` are inverted, as its statistics count them.
fn planar_inverted(mesh: &Mesh) -> Vec<bool> {
    (0..mesh.element_count())
        .map(|e| {
            let kind = mesh.kind(e);
            let mut p = [glam::DVec2::ZERO; 9];
            for (q, &n) in p.iter_mut().zip(mesh.element(e)) {
                *q = mesh.nodes()[n as usize];
            }
            measure::element_measures(kind, &p).inverted > 0
        })
        .collect()
}

/// Where a pass left more inverted elements than `was` marked (issue 61: a move keeps its
/// star no worse, but an inverted star may fold a valid element where its inversion falls,
/// and later moves need not mend it), puts the nodes (`nodes_of`) of the elements the pass
/// inverted back where the pass found them (`restore`), until the count (`now`) is no
/// larger; at the fourth round those of every inverted element; at worst every node the
/// pass moved goes back ([`undo_what_got_worse`]).
pub(crate) fn undo_new_inversions<M: ?Sized>(
    mesh: &mut M,
    was: &[bool],
    now: impl Fn(&M) -> Vec<bool>,
    nodes_of: impl Fn(&M, usize) -> Vec<u32>,
    restore: impl FnMut(&mut M, usize),
) {
    let before = was.iter().filter(|&&i| i).count();
    let judge = |m: &M, round: usize| {
        let inverted = now(m);
        (inverted.iter().filter(|&&i| i).count() > before)
            .then(|| (0..inverted.len()).filter(|&e| inverted[e] && (!was[e] || round == 3)).collect())
    };
    undo_what_got_worse(mesh, was.len(), judge, nodes_of, restore);
}

/// Puts back, where the pass found them (`restore`), the nodes (`nodes_of`) of the
/// elements `judge` names, round after round, until it names none (`None`: the mesh is no
/// worse than the pass found it); after four rounds every node of the mesh's `elements`
/// goes back (the pass undone, which no judge finds worse).
pub(crate) fn undo_what_got_worse<M: ?Sized>(
    mesh: &mut M,
    elements: usize,
    judge: impl Fn(&M, usize) -> Option<Vec<usize>>,
    nodes_of: impl Fn(&M, usize) -> Vec<u32>,
    mut restore: impl FnMut(&mut M, usize),
) {
    for round in 0..4 {
        let Some(culprits) = judge(mesh, round) else {
            return;
        };
        for e in culprits {
            for i in nodes_of(mesh, e) {
                restore(mesh, i as usize);
            }
        }
    }
    if judge(mesh, 4).is_some() {
        let all: std::collections::BTreeSet<u32> = (0..elements).flat_map(|e| nodes_of(mesh, e)).collect();
        for i in all {
            restore(mesh, i as usize);
        }
    }
}
