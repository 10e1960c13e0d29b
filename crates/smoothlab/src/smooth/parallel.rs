//! Smoothing in independent sets: the free nodes are coloured so that no two nodes of one
//! colour share an element, and a pass visits the colours in turn. Nodes of one colour
//! read and write disjoint data — a node reads only its star and its neighbours
//! (see [`Smoother::decide`](super::Smoother)) and writes itself and the mid-side nodes of
//! its own edges — so within a colour they can be smoothed in any order, or at once.
//!
//! [`ColouredSmoother`] runs such passes in one of two ways ([`Execution`]): in place, node
//! after node (Gauss–Seidel in the coloured order), or deferred: every node of a colour is
//! decided against the mesh as it was when the colour began, then the moves are written.
//! Deferred execution runs on all cores with rayon when the crate's `parallel` feature is
//! on (native builds only; wasm is single-threaded), and sequentially otherwise. Both
//! give bit-identical meshes, whatever the number of threads; the tests check this.
//!
//! A coloured pass visits every free node once, colour by colour and by node number within
//! a colour; [`SmoothOptions::order`] does not apply (Chen's priority order is inherently
//! sequential: it is planned from the qualities as the pass goes).

use glam::DVec2;

use super::{NodeOutcome, PassRecord, Planar, SmoothOptions, Smoother, StarView, SweepCounts};
use crate::error::Result;
use crate::mesh::{Mesh, NONE};
use crate::objective::Objective;

/// The free nodes of a mesh split into independent sets ("colours"): no two nodes of one
/// colour belong to a common element. Stored flat: the nodes colour by colour, each colour
/// in node order, with offsets.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Colouring {
    start: Vec<u32>,
    nodes: Vec<u32>,
    /// Node and element counts of the mesh it was made for.
    mesh_nodes: usize,
    mesh_elements: usize,
}

impl Colouring {
    /// Greedy colouring of the free nodes in node order: each node takes the smallest
    /// colour not used by an already coloured node of any element of its star. Uses at most
    /// one colour more than the largest number of other free nodes sharing an element with
    /// one node (7–9 colours on a Delaunay triangulation, 4 on a quad grid).
    pub fn greedy(mesh: &Mesh) -> Colouring {
        let n = mesh.node_count();
        let mut colour = vec![NONE; n];
        // stamp[c] == node + 1 when colour c is taken near `node`
        let mut stamp: Vec<u32> = Vec::new();
        let mut colours = 0usize;
        for node in 0..n {
            if !mesh.is_free(node) {
                continue;
            }
            for &e in mesh.node_elements(node) {
                for &m in mesh.element(e as usize) {
                    let c = colour[m as usize];
                    if c != NONE {
                        stamp[c as usize] = node as u32 + 1;
                    }
                }
            }
            let c = (0..colours).find(|&c| stamp[c] != node as u32 + 1).unwrap_or(colours);
            if c == colours {
                colours += 1;
                stamp.push(0);
            }
            colour[node] = c as u32;
        }
        Self::from_colours(mesh, &colour, colours)
    }

    /// The flat form of a per-node colour array (`NONE` for nodes left out).
    fn from_colours(mesh: &Mesh, colour: &[u32], colours: usize) -> Colouring {
        let mut start = vec![0u32; colours + 1];
        for &c in colour {
            if c != NONE {
                start[c as usize + 1] += 1;
            }
        }
        for c in 0..colours {
            start[c + 1] += start[c];
        }
        let mut fill = start.clone();
        let mut nodes = vec![0u32; start[colours] as usize];
        for (node, &c) in colour.iter().enumerate() {
            if c != NONE {
                nodes[fill[c as usize] as usize] = node as u32;
                fill[c as usize] += 1;
            }
        }
        Colouring { start, nodes, mesh_nodes: mesh.node_count(), mesh_elements: mesh.element_count() }
    }

    /// Number of colours (independent sets).
    pub fn colour_count(&self) -> usize {
        self.start.len().saturating_sub(1)
    }

    /// The nodes of colour `c`, in node order.
    pub fn colour(&self, c: usize) -> &[u32] {
        &self.nodes[self.start[c] as usize..self.start[c + 1] as usize]
    }

    /// Every coloured node, colour by colour: the visit order of a coloured pass.
    pub fn order(&self) -> &[u32] {
        &self.nodes
    }

    /// Whether the colouring was made for a mesh of this size (a cheap guard; the
    /// smoother recolours when it changes).
    fn fits(&self, mesh: &Mesh) -> bool {
        self.mesh_nodes == mesh.node_count() && self.mesh_elements == mesh.element_count()
    }
}

/// How a coloured pass applies the moves of one colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Execution {
    /// Node after node, each move written at once (Gauss–Seidel in the coloured order).
    InPlace,
    /// All nodes of a colour decided first, the moves written after: in parallel with
    /// rayon under the `parallel` feature, sequentially without it.
    Deferred,
}

/// A smoothing driver that visits the free nodes colour by colour ([`Colouring`]), in
/// place or deferred ([`Execution`]). Deferred passes with the `parallel` feature use the
/// current rayon thread pool (all cores unless the caller installs another).
#[derive(Clone, Debug)]
pub struct ColouredSmoother {
    main: Smoother,
    execution: Execution,
    colouring: Colouring,
    /// Moves of the current colour (deferred execution).
    moves: Vec<(DVec2, NodeOutcome)>,
    passes: u32,
}

/// Nodes per unit of parallel work: large enough that a worker's scratch buffers are
/// reused over many nodes, small enough to balance the work of 2–64 threads.
#[cfg(all(feature = "parallel", not(target_arch = "wasm32")))]
const CHUNK: usize = 512;

impl ColouredSmoother {
    /// A coloured smoother for `mesh` (coloured now) with checked options and
    /// [`Execution::Deferred`].
    pub fn new(mesh: &Mesh, options: SmoothOptions) -> Result<Self> {
        Ok(ColouredSmoother {
            main: Smoother::new(options)?,
            execution: Execution::Deferred,
            colouring: Colouring::greedy(mesh),
            moves: Vec::new(),
            passes: 0,
        })
    }

    /// The same smoother with another [`Execution`].
    pub fn with_execution(mut self, execution: Execution) -> Self {
        self.execution = execution;
        self
    }

    pub fn colouring(&self) -> &Colouring {
        &self.colouring
    }

    pub fn options(&self) -> &SmoothOptions {
        self.main.options()
    }

    /// Passes run so far.
    pub fn passes(&self) -> u32 {
        self.passes
    }

    /// Whether deferred passes run on several threads in this build.
    pub fn is_multithreaded() -> bool {
        cfg!(all(feature = "parallel", not(target_arch = "wasm32")))
    }

    /// The node loop of one coloured pass (no statistics).
    pub fn sweep(&mut self, mesh: &mut Mesh, objective: &(dyn Objective + Sync)) -> SweepCounts {
        if !self.colouring.fits(mesh) {
            self.colouring = Colouring::greedy(mesh);
        }
        self.main.refresh_mesh_facts(mesh);
        self.main.note_tangled(&super::ReadOnly(mesh));
        // the pass's bounds, taken once for every unit of work (which copy the driver)
        let reading = super::SmoothMesh::valid_reading(&*mesh);
        self.main.grading_bound_or(reading.map_or(f64::INFINITY, |r| r.grading));
        self.main.bounds = std::sync::OnceLock::from(reading);
        let mut counts = SweepCounts { fit_steps: self.main.fit_first(mesh, objective), ..SweepCounts::default() };
        for c in 0..self.colouring.colour_count() {
            let nodes = self.colouring.colour(c);
            match self.execution {
                Execution::InPlace => counts.merge(self.main.visit_all(mesh, nodes, objective)),
                Execution::Deferred => {
                    self.moves.clear();
                    self.moves.resize(nodes.len(), (DVec2::ZERO, NodeOutcome::default()));
                    decide_all(&mut self.main, mesh, nodes, objective, &mut self.moves);
                    for (&n, &(x, o)) in nodes.iter().zip(&self.moves) {
                        counts.add(o);
                        if o.moved {
                            Planar(&mut *mesh).place(n as usize, x);
                        }
                    }
                }
            }
        }
        counts
    }

    /// One coloured pass with the statistics of [`Smoother::pass`]. `clock` returns
    /// milliseconds; [`PassRecord::elapsed_ms`] times the node loop.
    pub fn pass(&mut self, mesh: &mut Mesh, objective: &(dyn Objective + Sync), clock: &dyn Fn() -> f64) -> PassRecord {
        self.passes += 1;
        let t0 = clock();
        let counts = self.sweep(mesh, objective);
        let elapsed = clock() - t0;
        self.main.record(mesh, objective, self.passes, counts, elapsed, clock)
    }
}

/// Decides every node of one colour against the mesh as it is, into `out`: on the rayon
/// pool when built with `parallel` (each unit of work with its own copy of the driver's
/// scratch buffers), else in order on this thread.
fn decide_all(
    s: &mut Smoother,
    mesh: &Mesh,
    nodes: &[u32],
    objective: &(dyn Objective + Sync),
    out: &mut [(DVec2, NodeOutcome)],
) {
    let decide = |w: &mut Smoother, out: &mut [(DVec2, NodeOutcome)], nodes: &[u32]| {
        for (o, &n) in out.iter_mut().zip(nodes) {
            *o = w.decide(mesh, n as usize, objective);
        }
    };
    #[cfg(all(feature = "parallel", not(target_arch = "wasm32")))]
    {
        use rayon::prelude::*;
        let template: &Smoother = s;
        out.par_chunks_mut(CHUNK)
            .zip(nodes.par_chunks(CHUNK))
            .for_each_init(|| template.clone(), |w, (out, nodes)| decide(w, out, nodes));
    }
    #[cfg(not(all(feature = "parallel", not(target_arch = "wasm32"))))]
    decide(s, out, nodes);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{perturb, plate, rand2d, GridKind, PlateKind};
    use crate::objective::{objective, ObjectiveKind};
    use crate::smooth::Strategy;

    fn meshes() -> Vec<(&'static str, Mesh)> {
        let r = rand2d(1500, 20, 3).unwrap();
        vec![
            ("rand2d", r.clone()),
            ("rand2d perturbed", perturb(&r, 0.45, 9).unwrap()),
            ("quad grid", perturb(&crate::generate::grid(24, 20, GridKind::Quad).unwrap(), 0.3, 4).unwrap()),
            ("quadratic mixed plate", perturb(&plate(PlateKind::Mixed, 2, 3).unwrap(), 0.2, 6).unwrap()),
        ]
    }

    #[test]
    fn colours_are_independent_sets_covering_the_free_nodes() {
        for (name, mesh) in meshes() {
            let col = Colouring::greedy(&mesh);
            let mut colour_of = vec![NONE; mesh.node_count()];
            for c in 0..col.colour_count() {
                assert!(!col.colour(c).is_empty(), "{name}: empty colour {c}");
                assert!(col.colour(c).windows(2).all(|w| w[0] < w[1]), "{name}: colour {c} not in node order");
                for &n in col.colour(c) {
                    assert_eq!(colour_of[n as usize], NONE, "{name}: node {n} coloured twice");
                    colour_of[n as usize] = c as u32;
                }
            }
            for (n, &c) in colour_of.iter().enumerate() {
                assert_eq!(c != NONE, mesh.is_free(n), "{name}: node {n}");
            }
            for e in 0..mesh.element_count() {
                let mut seen: Vec<u32> =
                    mesh.element(e).iter().map(|&m| colour_of[m as usize]).filter(|&c| c != NONE).collect();
                let k = seen.len();
                seen.sort_unstable();
                seen.dedup();
                assert_eq!(seen.len(), k, "{name}: element {e} has two nodes of one colour");
            }
            assert!(col.colour_count() <= 12, "{name}: {} colours", col.colour_count());
        }
    }

    /// The deferred pass (parallel under the `parallel` feature, on 4 threads) gives the
    /// same mesh, bit for bit, as the in-place pass in the same coloured order.
    #[test]
    fn deferred_pass_equals_in_place_pass_bit_for_bit() {
        let strategies = [
            (Strategy::Laplace, ObjectiveKind::SmoothShape),
            (Strategy::Smart, ObjectiveKind::SmoothShape),
            (Strategy::Opt, ObjectiveKind::SmoothShape),
            (Strategy::Opt, ObjectiveKind::MaxMinShape),
            (Strategy::Rules, ObjectiveKind::SmoothShape),
            (Strategy::C2, ObjectiveKind::Sine),
        ];
        for (name, mesh) in meshes() {
            for (strategy, kind) in strategies {
                let obj = objective(kind);
                let opts = SmoothOptions::default().with_strategy(strategy);
                let mut a = mesh.clone();
                let mut b = mesh.clone();
                let mut sa = ColouredSmoother::new(&a, opts).unwrap().with_execution(Execution::InPlace);
                let mut sb = ColouredSmoother::new(&b, opts).unwrap().with_execution(Execution::Deferred);
                for _ in 0..2 {
                    let ca = sa.sweep(&mut a, &*obj);
                    let cb = in_pool(|| sb.sweep(&mut b, &*obj));
                    assert_eq!(ca, cb, "{name} {strategy:?} {kind}");
                }
                let same = a
                    .nodes()
                    .iter()
                    .zip(b.nodes())
                    .all(|(p, q)| p.x.to_bits() == q.x.to_bits() && p.y.to_bits() == q.y.to_bits());
                assert!(same, "{name} {strategy:?} {kind}: deferred and in-place passes differ");
                assert!(
                    a.nodes() != mesh.nodes(),
                    "{name} {strategy:?} {kind}: nothing moved, the check shows nothing"
                );
            }
        }
    }

    #[cfg(all(feature = "parallel", not(target_arch = "wasm32")))]
    fn in_pool<R: Send>(f: impl FnOnce() -> R + Send) -> R {
        rayon::ThreadPoolBuilder::new().num_threads(4).build().unwrap().install(f)
    }

    #[cfg(not(all(feature = "parallel", not(target_arch = "wasm32"))))]
    fn in_pool<R>(f: impl FnOnce() -> R) -> R {
        f()
    }

    /// The check above has teeth: with every free node in one "colour" (not independent)
    /// a deferred pass is a Jacobi sweep and differs from the in-place one.
    #[test]
    fn deferred_pass_over_dependent_nodes_differs() {
        let mesh = perturb(&rand2d(400, 10, 5).unwrap(), 0.3, 2).unwrap();
        let free: Vec<u32> =
            (0..mesh.node_count() as u32).map(|n| if mesh.is_free(n as usize) { 0 } else { NONE }).collect();
        let one = Colouring::from_colours(&mesh, &free, 1);
        let obj = objective(ObjectiveKind::SmoothShape);
        let opts = SmoothOptions::default().with_strategy(Strategy::Laplace);
        let run = |execution| {
            let mut m = mesh.clone();
            let mut s = ColouredSmoother::new(&m, opts).unwrap().with_execution(execution);
            s.colouring = one.clone();
            s.sweep(&mut m, &*obj);
            m
        };
        assert_ne!(run(Execution::InPlace).nodes(), run(Execution::Deferred).nodes());
    }

    #[test]
    fn coloured_pass_records_and_recolours_another_mesh() {
        let mut small = rand2d(200, 8, 1).unwrap();
        let obj = objective(ObjectiveKind::SmoothShape);
        let mut s = ColouredSmoother::new(&small, SmoothOptions::default()).unwrap();
        let r = s.pass(&mut small, &*obj, &|| 0.0);
        assert_eq!(r.pass, 1);
        assert_eq!(r.counts.visits as usize, small.free_count());
        assert_eq!(r.after.inverted, 0);
        let mut big = rand2d(500, 10, 2).unwrap();
        let r = s.pass(&mut big, &*obj, &|| 0.0);
        assert_eq!(r.counts.visits as usize, big.free_count(), "the colouring follows the mesh");
        assert_eq!(s.colouring().order().len(), big.free_count());
    }
}
