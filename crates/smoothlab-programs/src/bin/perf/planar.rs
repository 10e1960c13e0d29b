//! The planar passes, timed on rand2D meshes in file and Hilbert order.
//! Also what an `opt` visit costs, and the meshes Newton's first trial gives.

use std::time::Instant;

use smoothlab::generate::rand2d;
use smoothlab::mesh::Mesh;
use smoothlab::objective::{objective, Goal, Objective, ObjectiveKind, Star, Term};
use smoothlab::quality::mesh_stats;
use smoothlab::smooth::parallel::{ColouredSmoother, Execution};
use smoothlab::smooth::{Order, SmoothOptions, Smoother, Strategy};

use crate::common::{median, SEED};

/// rand2d with `n` nodes in all: `√n` points per side of the square, the rest inside.
fn bench_mesh(n: usize) -> Mesh {
    let per_side = ((n as f64).sqrt() as usize).max(1);
    rand2d(n - 4 * per_side, per_side, SEED).expect("rand2d")
}

/// Median ns per visit of `reps` runs of `run` on fresh copies of `mesh` (`run` returns
/// the visits; any mesh: planar or volume).
fn time_ns_per_visit<M: Clone>(mesh: &M, reps: usize, mut run: impl FnMut(&mut M) -> u32) -> f64 {
    let mut out = Vec::new();
    for _ in 0..reps {
        let mut m = mesh.clone();
        let t = Instant::now();
        let visits = run(&mut m);
        out.push(t.elapsed().as_nanos() as f64 / visits.max(1) as f64);
    }
    median(out)
}

/// The bandwidth bound: a Gauss–Seidel sweep that only streams the arrays a Laplacian pass
/// must touch — the fixed flags, the CSR neighbour lists and the positions — and writes
/// each free node's position (the neighbours' mean, no checks, no calls).
fn stream_bound(mesh: &mut Mesh) -> u32 {
    let n = mesh.node_count();
    let mut visits = 0;
    for i in 0..n {
        if mesh.fixed()[i] {
            continue;
        }
        let nb = mesh.topology().neighbours(i);
        let mut s = glam::DVec2::ZERO;
        for &j in nb {
            s += mesh.nodes()[j as usize];
        }
        let p = s / nb.len() as f64;
        mesh.nodes_mut()[i] = p;
        visits += 1;
    }
    visits
}

fn options(strategy: Strategy) -> SmoothOptions {
    SmoothOptions::default().with_strategy(strategy).with_order(Order::Input)
}

/// How a measured pass departs from the input-order defaults of [`options`].
#[derive(Clone, Copy, PartialEq)]
enum Variant {
    /// The default options (Newton's first trial where the objective has a Hessian).
    Default,
    /// Chen's search alone: Newton's first trial off (`SmoothOptions::newton`).
    ChenAlone,
    /// The solver's iterations per call capped at this many (`SmoothOptions::max_iter`,
    /// the CLI's `--max-iter`; 3 by default).
    MaxIter(u32),
    /// Chen's priority order, as the default smoother (and the CLI) runs `rules`; the
    /// figure is then per free node, not per visit (a poor node is visited up to once per
    /// priority bin).
    Priority,
}

impl Variant {
    fn options(self, strategy: Strategy) -> SmoothOptions {
        let o = options(strategy);
        match self {
            Variant::Default => o,
            Variant::ChenAlone => o.with_newton(false),
            Variant::MaxIter(k) => o.with_max_iter(k),
            Variant::Priority => o.with_order(Order::Priority),
        }
    }
}

/// One sweep of `strategy` with objective `kind` and the options of `variant`; returns
/// the visits (the free nodes for [`Variant::Priority`], so its figure is per free node).
fn sweep(mesh: &mut Mesh, strategy: Strategy, kind: ObjectiveKind, variant: Variant) -> u32 {
    let obj = objective(kind);
    let visits = Smoother::new(variant.options(strategy)).expect("options").sweep(mesh, &*obj).visits;
    if variant == Variant::Priority {
        mesh.free_count() as u32
    } else {
        visits
    }
}

/// The passes measured, by name: strategy, objective and how the options depart from the
/// input-order defaults.
const PASSES: [(&str, Strategy, ObjectiveKind, Variant); 15] = [
    ("laplace", Strategy::Laplace, ObjectiveKind::SmoothShape, Variant::Default),
    ("smart", Strategy::Smart, ObjectiveKind::SmoothShape, Variant::Default),
    ("opt+new", Strategy::Opt, ObjectiveKind::SmoothShape, Variant::Default),
    ("opt+old", Strategy::Opt, ObjectiveKind::MaxMinShape, Variant::Default),
    ("opt+old, 20 it", Strategy::Opt, ObjectiveKind::MaxMinShape, Variant::MaxIter(20)),
    ("opt+sine", Strategy::Opt, ObjectiveKind::Sine, Variant::Default),
    ("opt+sine, 20 it", Strategy::Opt, ObjectiveKind::Sine, Variant::MaxIter(20)),
    ("opt+condition", Strategy::Opt, ObjectiveKind::Condition, Variant::Default),
    ("opt+condition-max", Strategy::Opt, ObjectiveKind::ConditionMax, Variant::Default),
    ("opt+untangle", Strategy::Opt, ObjectiveKind::Untangle, Variant::Default),
    ("opt+untangle-mindet", Strategy::Opt, ObjectiveKind::UntangleMinDet, Variant::Default),
    ("rules+new", Strategy::Rules, ObjectiveKind::SmoothShape, Variant::Default),
    (RULES_PRIORITY, Strategy::Rules, ObjectiveKind::SmoothShape, Variant::Priority),
    ("opt+new, Chen's search", Strategy::Opt, ObjectiveKind::SmoothShape, Variant::ChenAlone),
    ("rules+new, Chen's search", Strategy::Rules, ObjectiveKind::SmoothShape, Variant::ChenAlone),
];

/// The row of `rules` + `new` in priority order, the default smoother (per free node).
pub(crate) const RULES_PRIORITY: &str = "rules+new, priority order (per free node)";

/// The pass of [`PASSES`] named `name`.
fn pass_named(name: &str) -> (&'static str, Strategy, ObjectiveKind, Variant) {
    *PASSES.iter().find(|p| p.0 == name).unwrap_or_else(|| panic!("perf: no pass {name}"))
}

/// An objective that counts the evaluations of another (for the cost analysis).
struct Counted<'a> {
    inner: &'a (dyn Objective + Sync),
    calls: std::cell::Cell<u64>,
}

impl Objective for Counted<'_> {
    fn name(&self) -> &'static str {
        self.inner.name()
    }
    fn goal(&self) -> Goal {
        self.inner.goal()
    }
    fn terms(&self, star: &Star, x: glam::DVec2, out: &mut Vec<Term>) {
        self.calls.set(self.calls.get() + 1);
        self.inner.terms(star, x, out)
    }
    fn value_and_gradient(&self, star: &Star, x: glam::DVec2) -> (f64, glam::DVec2) {
        self.calls.set(self.calls.get() + 1);
        self.inner.value_and_gradient(star, x)
    }
    fn value_gradient_hessian(&self, star: &Star, x: glam::DVec2) -> Option<(f64, glam::DVec2, glam::DMat2)> {
        self.calls.set(self.calls.get() + 1);
        self.inner.value_gradient_hessian(star, x)
    }
}

/// Objective evaluations per visit and mean star size of one `opt` sweep with `kind`
/// (the default options, or Chen's search alone).
fn evaluations_per_visit(mesh: &Mesh, kind: ObjectiveKind, chen_alone: bool) -> (f64, f64) {
    let obj = objective(kind);
    let counted = Counted { inner: &*obj, calls: std::cell::Cell::new(0) };
    let mut m = mesh.clone();
    let variant = if chen_alone { Variant::ChenAlone } else { Variant::Default };
    let visits = Smoother::new(variant.options(Strategy::Opt)).expect("options").sweep(&mut m, &counted).visits;
    let elements: usize =
        (0..mesh.node_count()).filter(|&i| mesh.is_free(i)).map(|i| mesh.node_elements(i).len()).sum();
    (counted.calls.get() as f64 / visits.max(1) as f64, elements as f64 / visits.max(1) as f64)
}

/// Chen's search alone against Newton's first trial (the default) on the meshes of
/// quality: (family, Chen's figures, Newton's) with the figures the means over the
/// family of the smallest angle, the largest angle and the mean α/β after 3 passes of
/// `new` with the default smoother (rules, priority order), and how many meshes end
/// tangled.
pub(crate) fn newton_quality() -> Vec<(String, [f64; 4], [f64; 4])> {
    use smoothlab::generate::{perturb, plate, random_grid, GridKind, PlateKind};
    let mut families: Vec<(String, Vec<Mesh>)> = Vec::new();
    for (kind, name) in [(PlateKind::Quad, "quads"), (PlateKind::Tri, "triangles"), (PlateKind::Mixed, "mixed")] {
        let plate = plate(kind, 1, 5).expect("a plate");
        let meshes = (1..=20).map(|seed| perturb(&plate, 0.5, seed).expect("perturbed")).collect();
        families.push((format!("tangled plate, {name} (seeds 1–20)"), meshes));
    }
    families.push((
        "Knupp's random grid, 10 × 10 (seeds 1–10)".into(),
        (1..=10).map(|seed| random_grid(10, GridKind::Quad, seed).expect("a grid")).collect(),
    ));
    families.push(("rand2D, 2000 + 4 × 40 points (seeds 1–5)".into(), (1..=5).map(|seed| rand2d(2000, 40, seed).expect("rand2d")).collect()));
    // Freitag's size (`docs/reproduction.md` §1 runs seeds 1–5 of it)
    families.push(("rand2D, 500 + 4 × 20 points (seeds 1–40)".into(), (1..=40).map(|seed| rand2d(500, 20, seed).expect("rand2d")).collect()));
    let obj = objective(ObjectiveKind::SmoothShape);
    let run = |m: &Mesh, newton: bool| {
        let mut m = m.clone();
        let mut s = Smoother::new(SmoothOptions::default().with_newton(newton)).expect("options");
        for _ in 0..3 {
            s.pass(&mut m, &*obj, &|| 0.0);
        }
        mesh_stats(&m)
    };
    families
        .into_iter()
        .map(|(name, meshes)| {
            let mean = |newton: bool| {
                let mut f = [0.0; 4];
                for m in &meshes {
                    let st = run(m, newton);
                    f[0] += st.min_angle_deg / meshes.len() as f64;
                    f[1] += st.max_angle_deg / meshes.len() as f64;
                    f[2] += st.mean_quality / meshes.len() as f64;
                    f[3] += (st.inverted > 0) as u32 as f64;
                }
                f
            };
            (name, mean(false), mean(true))
        })
        .collect()
}

#[derive(Default)]
pub(crate) struct SizeReport {
    pub(crate) nodes: usize,
    pub(crate) colours: usize,
    /// Greedy colouring of the free nodes, ns per node (made once per mesh, not in the passes)
    pub(crate) colouring_ns: f64,
    /// (name, ns/visit in file order, ns/visit Hilbert order)
    pub(crate) rows: Vec<(String, f64, f64)>,
    pub(crate) stats_ns: f64,
    pub(crate) levelset: Vec<(String, f64)>,
    /// (name, ns/visit 1 thread, ns/visit all threads)
    pub(crate) parallel: Vec<(String, f64, f64)>,
    /// (objective, evaluations per visit, elements per star) of an `opt` sweep
    pub(crate) evaluations: Vec<(String, f64, f64)>,
    /// `render::render_mesh` into a 1024 × 1024 pixmap, ns per element (Hilbert order)
    pub(crate) render_ns: f64,
}

pub(crate) fn measure(n: usize, quick: bool) -> SizeReport {
    let mesh = bench_mesh(n);
    assert_eq!(mesh_stats(&mesh).inverted, 0, "rand2d is untangled");
    let (spatial, _) = mesh.renumbered_spatially();
    let reps = if n >= 1_000_000 {
        1
    } else if n >= 100_000 {
        3
    } else {
        7
    };
    let reps = if quick { 1 } else { reps };
    let mut rows = Vec::new();
    let both = |f: &dyn Fn(&mut Mesh) -> u32| (time_ns_per_visit(&mesh, reps, f), time_ns_per_visit(&spatial, reps, f));
    let (a, b) = both(&stream_bound);
    rows.push(("stream bound".to_string(), a, b));
    for (name, strategy, kind, variant) in PASSES {
        let (a, b) = both(&|m: &mut Mesh| sweep(m, strategy, kind, variant));
        rows.push((name.to_string(), a, b));
    }
    // the statistics a full pass adds (mesh_stats + objective total), per free node
    let obj = objective(ObjectiveKind::SmoothShape);
    let t = Instant::now();
    let _ = mesh_stats(&spatial);
    let _ = Smoother::new(options(Strategy::Laplace)).expect("options").objective_total(&spatial, &*obj);
    let stats_ns = t.elapsed().as_nanos() as f64 / spatial.free_count() as f64;
    // level sets: the objective of one node sampled on a 100 × 100 grid over its star
    let mut levelset = Vec::new();
    let node = (0..spatial.node_count()).find(|&i| spatial.is_free(i)).expect("a free node");
    let mut star = Star::new();
    star.gather(&spatial, node);
    let (mut lo, mut hi) = (star.x0, star.x0);
    for e in &star.elems {
        for p in &e.pts[..e.kind.node_count()] {
            lo = lo.min(*p);
            hi = hi.max(*p);
        }
    }
    for kind in [ObjectiveKind::SmoothShape, ObjectiveKind::MaxMinShape] {
        let o = objective(kind);
        let t = Instant::now();
        let mut acc = 0.0;
        for j in 0..100 {
            for i in 0..100 {
                let x = lo + (hi - lo) * glam::DVec2::new(i as f64 / 99.0, j as f64 / 99.0);
                acc += o.value(&star, x);
            }
        }
        std::hint::black_box(acc);
        levelset.push((kind.name().to_string(), t.elapsed().as_nanos() as f64 / 1e4));
    }
    // coloured passes: deferred on 1 thread and on all threads
    let mut parallel = Vec::new();
    let t = Instant::now();
    let colours = smoothlab::smooth::parallel::Colouring::greedy(&spatial).colour_count();
    let colouring_ns = t.elapsed().as_nanos() as f64 / spatial.free_count() as f64;
    if ColouredSmoother::is_multithreaded() {
        for (name, strategy, kind, _) in ["laplace", "opt+new", "opt+old", "rules+new"].map(pass_named) {
            let obj = objective(kind);
            // coloured once, outside the timing (the colouring depends on the topology only)
            let coloured =
                ColouredSmoother::new(&spatial, options(strategy)).expect("options").with_execution(Execution::Deferred);
            let time = |threads: usize| {
                let mut s = coloured.clone();
                with_threads(threads, || time_ns_per_visit(&spatial, reps, |m: &mut Mesh| s.sweep(m, &*obj).visits))
            };
            let one = time(1);
            let all = time(0);
            parallel.push((name.to_string(), one, all));
        }
    }
    let evaluations = [(ObjectiveKind::SmoothShape, false), (ObjectiveKind::MaxMinShape, false), (ObjectiveKind::SmoothShape, true)]
        .into_iter()
        .map(|(k, chen_alone)| {
            let (e, s) = evaluations_per_visit(&spatial, k, chen_alone);
            let how = if chen_alone { " with Chen's search alone" } else if k == ObjectiveKind::SmoothShape { " (Newton's first trial)" } else { "" };
            (format!("`{}`{how}", k.name()), e, s)
        })
        .collect();
    let render_ns = {
        let mut pixmap = tiny_skia::Pixmap::new(1024, 1024).expect("a pixmap");
        let view = smoothlab_render::MeshView::default();
        let mut times = Vec::new();
        for _ in 0..reps {
            let t = Instant::now();
            smoothlab_render::render_mesh(&mut pixmap, &spatial, &view);
            times.push(t.elapsed().as_nanos() as f64 / spatial.element_count() as f64);
        }
        median(times)
    };
    SizeReport {
        render_ns,
        evaluations,
        nodes: mesh.node_count(),
        colours,
        colouring_ns,
        rows,
        stats_ns,
        levelset,
        parallel,
    }
}

#[cfg(feature = "parallel")]
fn with_threads<R: Send>(threads: usize, f: impl FnOnce() -> R + Send) -> R {
    rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("a thread pool").install(f)
}

#[cfg(not(feature = "parallel"))]
fn with_threads<R: Send>(_threads: usize, f: impl FnOnce() -> R + Send) -> R {
    f()
}

/// The passes `names` of [`PASSES`] alone on the planar mesh of `n` nodes, both orders (the
/// rest of the report left empty).
pub(crate) fn measure_rows(n: usize, names: &[&str], quick: bool) -> SizeReport {
    let mesh = bench_mesh(n);
    let (spatial, _) = mesh.renumbered_spatially();
    let reps = if quick { 1 } else { 3 };
    let rows = names
        .iter()
        .map(|&name| {
            let (_, strategy, kind, variant) = pass_named(name);
            let f = |m: &mut Mesh| sweep(m, strategy, kind, variant);
            (name.to_string(), time_ns_per_visit(&mesh, reps, f), time_ns_per_visit(&spatial, reps, f))
        })
        .collect();
    SizeReport { nodes: mesh.node_count(), rows, ..SizeReport::default() }
}
