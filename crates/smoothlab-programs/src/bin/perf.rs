//! Performance figures of smoothlab, written as `docs/performance.md` (run by
//! `make performance`; see that file for what is measured and how).
//!
//! ```text
//! cargo run --release --features parallel --example perf -- \
//!     [--sizes 10000,100000,1000000] [--wasm wasm.json] [--page page.json]
//!     [--page-memory page-memory.json] [--before-after before_after.json]
//!     [--out docs/performance.md] [--json native.json]
//! cargo run --release --example perf -- --memory-only [--page-memory page-memory.json]
//! cargo run --release --features parallel --example perf -- --issue33 [--quick] [--wasm wasm.json] [--page page.json]
//!     [--before-after before_after.json]
//! ```
//!
//! Every figure is the median of a few timed passes, each over a fresh copy of the same
//! generated mesh (the copy is not timed), in nanoseconds per node visit. `--wasm` reads the
//! browser bench's JSON (`node tests/browser/bench.mjs`) and adds the wasm/native table.
//! The memory section (alone with `--memory-only`, printed) measures each command in a
//! child process of this program (`--memory-child`), whose peak resident memory it reports.
//! Issue 33's sections (alone, printed, with `--issue33`: about 2 minutes; `--quick` fewer
//! repetitions): the 3D passes on rand3D and on hexahedra, the time to quality of the
//! release binary `smoothlab` (built beside this program: `make performance` builds it),
//! versus Mesquite, and the issue's targets, whose speed-ups are read from
//! `scripts/before_after.py`'s JSON (`--before-after`: the CLI of the issue's day and this
//! tree's timed in one run).

use std::fmt::Write as _;
use std::time::Instant;

use smoothlab::generate::{rand2d, PlateKind};
use smoothlab::mesh::Mesh;
use smoothlab::model::Model;
use smoothlab::objective::{objective, tet_objective, CornerStar, Goal, Objective, ObjectiveKind, Star, Term};
use smoothlab::quality::mesh_stats;
use smoothlab::smooth::parallel::{ColouredSmoother, Execution};
use smoothlab::smooth::{DriverStar, Order, SmoothOptions, Smoother, Strategy, DEFAULT_MAX_ITER};
use smoothlab::volume::{volume_stats, VolumeMesh, VolumeSmoother};

/// The seed of every benchmark mesh (the browser bench uses the same).
const SEED: u64 = 2003;

/// rand2d with `n` nodes in all: `√n` points per side of the square, the rest inside.
fn bench_mesh(n: usize) -> Mesh {
    let per_side = ((n as f64).sqrt() as usize).max(1);
    rand2d(n - 4 * per_side, per_side, SEED).expect("rand2d")
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
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
    ("laplace", Strategy::Laplace, ObjectiveKind::New, Variant::Default),
    ("smart", Strategy::Smart, ObjectiveKind::New, Variant::Default),
    ("opt+new", Strategy::Opt, ObjectiveKind::New, Variant::Default),
    ("opt+old", Strategy::Opt, ObjectiveKind::Old, Variant::Default),
    ("opt+old, 20 it", Strategy::Opt, ObjectiveKind::Old, Variant::MaxIter(20)),
    ("opt+sine", Strategy::Opt, ObjectiveKind::Sine, Variant::Default),
    ("opt+sine, 20 it", Strategy::Opt, ObjectiveKind::Sine, Variant::MaxIter(20)),
    ("opt+condition", Strategy::Opt, ObjectiveKind::Condition, Variant::Default),
    ("opt+condition-max", Strategy::Opt, ObjectiveKind::ConditionMax, Variant::Default),
    ("opt+untangle", Strategy::Opt, ObjectiveKind::Untangle, Variant::Default),
    ("opt+untangle-mindet", Strategy::Opt, ObjectiveKind::UntangleMinDet, Variant::Default),
    ("rules+new", Strategy::Rules, ObjectiveKind::New, Variant::Default),
    (RULES_PRIORITY, Strategy::Rules, ObjectiveKind::New, Variant::Priority),
    ("opt+new, Chen's search", Strategy::Opt, ObjectiveKind::New, Variant::ChenAlone),
    ("rules+new, Chen's search", Strategy::Rules, ObjectiveKind::New, Variant::ChenAlone),
];

/// The row of `rules` + `new` in priority order, the default smoother (per free node).
const RULES_PRIORITY: &str = "rules+new, priority order (per free node)";

/// The pass of [`PASSES`] named `name`.
fn pass_named(name: &str) -> (&'static str, Strategy, ObjectiveKind, Variant) {
    *PASSES.iter().find(|p| p.0 == name).unwrap_or_else(|| panic!("perf: no pass {name}"))
}

/// Peak resident memory of this process, bytes (Linux `VmHWM`).
fn vm_hwm() -> Option<usize> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = s.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: usize = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
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
fn newton_quality() -> Vec<(String, [f64; 4], [f64; 4])> {
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
    let obj = objective(ObjectiveKind::New);
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

/// A row of the ratio table: name, target, and the figure of one mesh size.
type TargetRow<'a> = (&'a str, &'a str, &'a dyn Fn(&SizeReport) -> f64, f64);

#[derive(Default)]
struct SizeReport {
    nodes: usize,
    colours: usize,
    /// Greedy colouring of the free nodes, ns per node (made once per mesh, not in the passes)
    colouring_ns: f64,
    /// (name, ns/visit in file order, ns/visit Hilbert order)
    rows: Vec<(String, f64, f64)>,
    stats_ns: f64,
    levelset: Vec<(String, f64)>,
    /// (name, ns/visit 1 thread, ns/visit all threads)
    parallel: Vec<(String, f64, f64)>,
    /// (objective, evaluations per visit, elements per star) of an `opt` sweep
    evaluations: Vec<(String, f64, f64)>,
    /// `render::render_mesh` into a 1024 × 1024 pixmap, ns per element (Hilbert order)
    render_ns: f64,
}

/// What was tried for the wasm / native ratio (target ≤ 1.3), after its table.
const WASM_TRIED: &str = "Tried: the module is built with 128-bit SIMD (`+simd128`, which tiny-skia's pipelines use, and LLVM's vectoriser where it finds pairs in the core), from the same code as the native build, so the speed-ups of the native kernels (issue 15's Newton trial, the δ memo, the inline triangles, the old objective's corners) carry over (opt+new in Chromium, Hilbert order: 3872 ns a visit in the run before them, the table above now) while the ratio stays about where it was (1.40 for that pass then); the crate built for size is slower still (the page section). Tried for the issue's simd128 kernels, and not kept: the `new` objective's term of two linear triangles at once, each number a pair of lanes with the one-triangle kernel's operations in its order (the same bits: a unit test compared value, gradient and Hessian over 40000 random pairs, δ = 0 and δ > 0, at scales 1e±150); LLVM made its arithmetic `f64x2` instructions (186 `f64x2.mul`, 10 `f64x2.div` in the objective's Hessian function), but in node opt+new was no faster (Hilbert order, three alternating runs: 3107, 3019, 2992 ns a visit before, 3001, 3022, 2998 after; file order and rules+new within the noise) and the module 4.3 KB larger gzipped, with 46 `f64x2.extract_lane` and 18 `replace_lane` to pack and unpack the lanes beside the paired arithmetic. The native half of each ratio is now measured straight after the page (`--native-peers`): with the native figures of the planar table, measured minutes later on this shared machine, the same binaries' ratios had read 1.07–2.80 in one run; measured together, in two runs before this one, the optimizers (smart, opt+new, opt+old, rules+new) ran 1.44–1.87× their native time (once 3.71×, smart in file order) and laplace 1.86–3.05×. V8's baseline compiler is not the cause: with `--no-liftoff` (every function compiled by TurboFan from the start) the bench page was no faster (one run). Where the time goes: the passes profiled in node (`node --cpu-prof`, the module built with its names kept) and natively (`perf record`), the same passes on the same mesh: each function takes about the same share of the pass in both, so the wasm build is slower across the whole of the code rather than at a hot spot; the exception was the inverted test of an element (7.8% of opt+new in wasm against 3.4% natively: its range test's maxima), made cheaper since (the module section above). Tried and not kept: binaryen's `-O4` (3.5 KB larger gzipped and no faster: two alternating runs of four passes in node); reading ahead in node order too, which the drivers do only in a scattered order (natively rules+new in file order 12–20% faster, but laplace 4× slower and every pass in Hilbert order slower; in wasm 0–8% faster in file order and some 6% slower in Hilbert order), and later for every strategy but the two Laplacians alone, whose visits cost more than their reads (natively, the CLI on a rand2D of 20000 points in file order and renumbered along a Hilbert curve, medians of 9 to 15 alternating runs: opt+old with 20 iterations 1.4% faster in file order and level in Hilbert order, opt+new 2% and 4% slower, rules+new in node order 2.5% slower). Where the time goes in a scattered numbering (`perf` on node's code with its jitted functions' listings): in a Laplacian's visit in file order, most of the samples sit on the loads of the neighbours' positions, as natively, but V8's code for a visit is longer (the visit's calls, a stack check in each loop), so fewer visits' loads are in flight at once and the misses cost more. Tried and not kept for it: the smart Laplacian's test reading a star's other corners first and measuring them after, so that the reads go out together (in node, the two modules alternating in one process, 21 sweeps each: smart in file order 730–832 against 772–990 ns a visit, but in Hilbert order, the page's samples' numbering, 2–10% slower, and rules+new in either order within the noise; natively within the noise too; the same meshes).";

/// Why the coloured passes on the small mesh fall short of the target, after their table.
const COLOUR_NOTE: &str = " At 10k nodes a colour holds some 1400 nodes, about a millisecond of `opt`, so handing each colour to the threads and waiting for its slowest node weighs more there (not measured apart); the target is for the passes on the large meshes.";

/// The rows of the targets table whose figures are not met are followed by what was tried.
const TRIED: &str = "What was tried for the figures not met (each measured on the 100k mesh before and after; none changes a smoothed result unless said):

- *opt+new*: Newton's step as the first trial of each Fletcher–Reeves iteration, from the analytic 2 × 2 Hessian of `new` (its N is linear and D quadratic in the node's position at every element kind; `SmoothOptions::newton`): kept on Armijo's condition, extended by Chen's search from t = 1 when the fall beats the quadratic model's promise by 1.1× (a barrier seen from afar), else Chen's iteration. It halves the evaluations per visit (below) and speeds `opt+new` by about 1.5× and `rules+new` by about 1.4× (against the *Chen's search* rows above). It is the default since issue 15 (\"Chen's search stays the default if it wins\"), decided on the smoothed meshes (the table below, and `docs/reproduction.md`): level with Chen's search on the tangled plates and on rand2D of 2000 points (its largest angle about 1° larger), far better on Knupp's random grids (untangled in 1 pass instead of up to 2, the smallest angle some 15° larger); every promise of the reproduction then still met (Freitag's best row beaten then; since issue 29's acceptance rule the min angle ends at the figure of `docs/reproduction.md` §1, just short of it; 150 of 150 plates untangled in the first pass, Mesquite's 13 tangled files, the ten random grids). Where Chen's search wins: rand2D at Freitag's size, whose smallest angle ends a fraction of a degree lower on average over 40 seeds (the table's last row), and about 1° lower over the 5 seeds of the reproduction's Table 1 (then still above Freitag's best row), from a few seeds (2, 6 and 9 of the 40) where Chen's search, stopped after its 3 iterations, leaves a node short of the objective's minimum with a larger smallest angle: given 10 iterations per call, Chen's search ends within 0.1° of where Newton's first trial does in 3 (measured once on those seeds; the smallest angle is not what `new` minimises; its mean α is level); and Mesquite's `hole_in_square_tanglap`, untangled in 3 passes instead of 2. Chen's search alone stays an option (`SmoothOptions::with_newton(false)`). Also made: the star's size measured once per solve, not twice (about 2%). Then, each bit for bit the same meshes (a pass's positions compared before and after) and measured in one run before and after on the 100k mesh: the barrier's δ and the star's extent (the 2^±200 check), which depend on the star's position alone, worked out once per position and kept in the star (`StarMemo`), not at every evaluation (2043 → 1862 ns a visit); the linear triangles of `new` evaluated in the element loop itself, where the compiler had kept the closure of `each_sub_triangle` apart and passed each sub-triangle through memory (two 8-byte stores read back as one 16-byte load: a quarter of the time of `opt` went to those loads), and the validity guard's `is_inverted` written out for triangles (1862 → 1208 ns). What is left is the arithmetic of about 6 evaluations of value, gradient and 2 × 2 Hessian over the star per visit (half the time), the guard's cross products at each trial (6%), the star's size and gather (8%).
- *smart / laplace*: the smart Laplacian on stars of linear triangles reads the two other corners of each triangle from the mesh instead of gathering the star (160 bytes an element) and measures them inline: about 1.9× faster. Then the two quotients of each triangle (its α before and after the move) are taken in the two lanes of one vector division (the same IEEE quotients, so the same decisions): 112 → 107.5 ns a visit. What is left is two Lo α per triangle against the Laplacian's one mean, and reading each element's node numbers (a cache miss per element at 1M, where the Laplacian reads only the neighbours). A division-free comparison of the worst α was not made: it could decide near-ties otherwise than the measure the rest of the smoother uses.
- *rules+new / smart*: `rules` is the smart Laplacian plus the optimization of the nodes it cannot move (about 4 in 10 of them on a fresh rand2D), so a faster smart Laplacian raises this ratio; Newton's first trial and the faster evaluation of `new` above lower it (against the *Chen's search* row).
- *opt+old* (not a target, but the old side of the page's default Step): the max-min objective built the element jets (a 420-byte copy) of every element at every evaluation and took the gradient of all three corner αs of a triangle to keep one; triangles now read their corners directly and every element takes the gradient of its worst corner alone (`lo_alpha_corner` gives `lo_alpha_corner_gradient`'s α bit for bit): 2308 → 1765 ns a visit, the same meshes.
- *opt+condition* (issue 33: at least 3× faster per node visit in 2D, with equal or better meshes; the table above predates it): the 2-norm of Knupp's condition number got an analytic 2 × 2 Hessian (κ = F/δ at every corner, F quadratic and δ linear in the node's position; `docs/formulas.md` §5), so Fletcher–Reeves tries Newton's step first as for `new`; a linear triangle's three corners, which share one κ = D/(√3·N), are worked out once, and linear triangles and quads are evaluated in the element loop itself, without the element jets (stars beyond 2^±200 keep the scale-safe metrics, without a Hessian). Measured in instructions (callgrind, deterministic where the shared cores make times noise): `valgrind --tool=callgrind smoothlab smooth r.vtk -o o.vtk --objective condition --strategy opt --passes 1` on a rand2d of 20000 points (seed 7), before and after, the node loop (`Smoother::sweep`, inclusive) from 91956 to 18020 instructions a visit, 5.1× fewer (the whole run less reading and writing, which `smoothlab convert` of the same file measures: 3.8×, the pass's statistics and objective total included); on a plate of 2208 free nodes (`generate plate --kind tri --resolution 12`, then `perturb --amount 0.25`) 5.5×, and on a tangled mixed plate (`--kind mixed`, `perturb --amount 0.6`) 3.4×, whose inverted stars stay behind the barrier and whose visits go to the validity guard's quads. The meshes differ, as Newton's trial finds each star's minimum where Chen's search stops short of it in 3 iterations: 3 passes of `opt`, means over 20 seeds, the objective Σκ² lower on 69 of the 80 valid meshes (higher on the others); rand2D of 500 + 4 × 20 points, smallest angle 16.93° → 17.15°, largest 135.04° → 134.92°, largest κ 4.830 → 4.771; on plates perturbed by 0.2 (valid) the smallest angle level or higher (17.56° → 17.58° triangles, 44.56° → 44.65° quads, 17.58° → 17.59° mixed) but the largest angle higher (106.87° → 106.98°, 134.38° → 134.61°, 119.38° → 120.28°), and on quads the smallest quality 0.4556 → 0.4550 and the largest κ 3.776 → 3.782; plates perturbed by 0.3 (a few inverted elements, which `condition` cannot untangle) level. That larger largest angle is the objective's: Chen's search alone given 10 iterations per call ends at the same meshes as Newton's trial in 3 (the same means to the third decimal, measured once on those 60 plates), so it was not kept as a reason for Chen's search.
- *opt+old* (issue 33: at least 2× faster per node visit in 2D with 20 iterations, with equal or better meshes): Freitag's ascent halves its step until a trial point is better, and most trial points are not (on the rand2D below, 558k of 775k trials); it now asks a max-min objective whether a point is better (`Objective::terms_above`) instead of for its every term, and `old` answers from the element of the worst term where the ascent stands first, then the others in order, stopping at the first term not above φ (most failing trials are told by that one element); the validity guard's cross products are taken only after the objective's own test passes, and a linear triangle's gradient only when its α is above φ. Measured in instructions (callgrind): `valgrind --tool=callgrind smoothlab smooth r.vtk -o o.vtk --objective old --strategy opt --passes 1 --max-iter 20` on a rand2d of 20000 points (seed 7), the node loop (`Smoother::sweep`, inclusive) from 180606 to 80793 instructions a visit, 2.24× fewer. The same meshes bit for bit (the written files compared, and 2 passes on tangled plates of triangles, quads and mixed, 3 seeds each, and 3 rand2D seeds with opt, rules and c2). Then, the same meshes bit for bit (449 written meshes compared with the previous commit's CLI: Mesquite's 2D files, tangled plates of every kind and order, rand2D, rand3D and tangled blocks of hexahedra and mixed solids, with opt, rules, c1, c2 and c3): the ascent passes the element that failed the last trial point as the one to test first (`terms_above`'s answer does not depend on the order, and a halved step usually fails on that element again), and a linear triangle's three corner αs are taken together (`quality::TriangleCorners`: each side's squared length once for the two corners it bounds, the squares of a difference and of its negation being the same bits; each α the corner function's bit for bit, which a unit test checks on random, degenerate, huge and NaN triangles): the node loop 1617M → 1595M (the order) → 1306M instructions (65300 a visit). In wall time that was some 7% (five alternating runs of the two CLIs), less than the instructions, as the divisions' latency stays. What is left: the 3 corner αs of each linear triangle (one α mathematically, but which corner is the least is decided by rounding, so working it out once would change the meshes; not made), the successful trials' whole evaluation with the guard, and the ascent's step (the active set, the hull's minimum-norm point).
- *opt+sine* (issue 33: at least 2× with 20 iterations): the same test of a trial point (`terms_above`, the worst term's element first), and linear triangles evaluated in the element loop without the element jets (a 420-byte copy and `corner_edge_vectors` per element). `valgrind --tool=callgrind smoothlab smooth r.vtk -o o.vtk --objective sine --strategy opt --passes 1 --max-iter 20`, the same rand2d: 183000 → 70102 instructions a visit, 2.61× fewer; the same meshes bit for bit. Then a linear triangle's three corner sines taken together (`quality::TriangleCorners`, each side's squared length once), their gradients only where the element's three terms are all above the ascent's floor (most trial points fail, and the gradients of a failing element are not used), and the failing element tested first as for `old`: 70102 → 62406 instructions a visit (1403M → 1248M), the same meshes bit for bit.
- *opt+untangle* (issue 33: at least 2×): on a valid mesh `untangle` leaves every star where it is (the untangling objectives optimise only while the mesh is tangled), so rand2D's visits cost the visit alone (1664 → 1668 instructions a visit on the rand2d above) and the target was measured on a tangled mesh: `generate plate --kind mixed --resolution 12`, `perturb --amount 0.6` (2208 free nodes, 637 inverted elements), `valgrind --tool=callgrind smoothlab smooth tp.vtk -o o.vtk --objective untangle --strategy opt --passes 1`: 47729 → 21692 instructions a visit, 2.20× fewer, the same meshes bit for bit. Made: the shift β's mean corner |det|, which depends on the star at x0 alone, kept in the star (`StarMemo`) instead of worked out at every evaluation (half the element jets built); linear triangles and quads evaluated in the element loop; p = 2 squared without `powi`'s call (the same bits); the validity guard's `is_inverted` written out for linear quads as it was for triangles (the raw corner edges within 2^±200, which `corner_edges` returns unchanged). Not made: Newton's first trial from an analytic Hessian (each term is piecewise quadratic in the node, with a Hessian of 8∇det∇detᵀ where det < β): it would change the meshes and needs their comparison over many seeds; the evaluations per visit (about 46 on that plate, Chen's search on a piecewise quadratic) are what is left. Then (the row's 2D figure had come out at 1.97×, 2.03×, 2.05× and 2.25× in four runs: a 9 ms pass on a shared machine), each leaving every written mesh byte for byte the same (`cmp` against the previous commit's CLI: 960 runs, every objective with `opt` and `rules` on tangled and valid plates of each kind and order, rand2D, rand3D, hexahedra, mixed solids and Mesquite's files): the validity guard answers each trial position once (`KeepValid` keeps its last answer: Fletcher–Reeves asks every trial point for a Hessian and, from an objective without one, then for the value and gradient, and each asked the guard, whose count of inverted elements took a sixth of the loop); a linear element's corners evaluated with its corner count a constant (`linear_dets::<3>` and `::<4>`: the corners' indices known when compiling); and a solve's first evaluation, where the star is, takes β's mean |det| and the terms in one sweep of the corners (the same dets, summed in the same order). The node loop (`Smoother::sweep`, inclusive) of that pass, 54.4M → 49.2M → 46.6M → 44.6M instructions (18% fewer); its wall time, against the previous commit's CLI, about 11% less (medians of ten alternating runs, 8.9 → 8.0 ms).
- *3D opt+new and rules+new* (issue 33: at least 3× faster, Newton's first trial from the analytic 3 × 3 Hessian, no gather per evaluation): each corner of a tetrahedral star is kept, when gathered, as the coefficients of its weighted Jacobian in the free node's position (`quality::tet::CornerForm`: ‖T‖² quadratic, det T linear, the terms of higher degree cancelling; `docs/formulas.md` §8), so an evaluation of `new` reads no corners and δ comes from the forms; `new` has the Hessian of its terms, so Fletcher–Reeves tries Newton's step first as in 2D; the validity guard decides a trial from the forms where they decide beyond rounding (a tetrahedron's det T; a hexahedron's or pyramid's 27 Bernstein coefficients of det J, each affine in one corner: `quality::solid::DetForm`, made at the first trial that asks), else as before; and a hexahedron's Bernstein coefficients are taken 9× cheaper (each cross product once, the weights from a table: the same coefficients bit for bit). Then the drivers' own costs: the mesh keeps each node's tetrahedra's other corners in one stream beside its element list (`VolumeMesh::node_tet_corners`, 12 bytes an incidence: the gather read each tetrahedron's nodes from the element array, two dependent cache misses a tetrahedron, a fifth of opt+new's cycles in `perf` on 8000 points); a visit of `rules` that only tries the smart Laplacian, and the priority order's measuring, leave the forms unmade (`DriverStar::gather_for_measures`, made at the solve's start); after a move the star is put back by moving its node rather than gathered again (`regather`); Chen's rule 2 counts inverted elements without taking every mean ratio; the smart Laplacian's test orders stars by `q³/27` (`quality::tet::mean_ratio_order`, no cube root; the acceptance rule that follows is exact); the acceptance rule takes the exact mean ratio only of the tetrahedra that may be the worst by that key (`LeastMeanRatio`: the same minimum bit for bit), reads a hexahedron's, wedge's or pyramid's validity from its `det J` form where the guard has made it and it decides (the same answers), and keeps each such element's validity and shape for the two positions that the smart Laplacian's test and the rule both ask (`PositionMemo`); the priority order takes the stars' shapes alone (`min_shape_at`), without certifying every hexahedron; and `new`'s term takes its cube root by Evans' method (`numeric::cbrt_fast`, within 1 ulp; the statistics and the max-min objectives keep the correctly rounded one) and its divisions as reciprocals once. Measured in instructions (callgrind), the node loop (`Smoother::visit_all_in`, inclusive) of one pass, `valgrind --tool=callgrind smoothlab smooth X.vtk -o o.vtk --strategy opt|rules --objective new --passes 1`, before (the issue's commit 0e0ec36) and after: on rand3D (`generate rand3d --seed 1`, 934 free nodes) opt+new 270.0M → 80.9M (3.34× fewer), rules+new 666.7M → 225.5M (2.96×); on a 10³ block of hexahedra (`generate hexgrid --cells 10`, `perturb --amount 0.3 --seed 3`, 729 free nodes, all valid) opt+new 2293M → 314M (7.3×), rules+new 3039M → 586M (5.2×). The wall times are the targets table's, above. The meshes differ from the issue's day's, as Newton's trial ends each solve nearer the objective's minimum: after the defaults' 3 passes (rules+new) the smallest mean ratio on rand3D seeds 1–3 0.4387 → 0.4431, 0.3982 → 0.4008, 0.4109 → 0.4162, tangled by 0.4: 0.4564 → 0.4476, 0.3865 → 0.3890, 0.3826 → 0.3831, 6³ hexahedra tangled by 1.0: 0.9987 → 0.9986, 0.9990 → 0.9982, 0.9998 → 0.9997; every run 0 inverted (the last round's drivers' changes left every mesh byte for byte the same; with the faster cube root these minima, and the smallest dihedral angles, are the same to six digits). Then `rules`' smart Laplacian and its acceptance rule share their measures, each written mesh the same bytes as before (`cmp` against the previous commit's CLI: the 1020 runs of every objective with `opt` and `rules` on plates, rand2D, rand3D, hexahedra, mixed solids and Mesquite's files, and the 675 runs on volume meshes with `opt`, `rules`, `smart`, `c1` and `c3`): the smart Laplacian's test took each tetrahedron's mean ratio parts where the node is and at the centroid, and the acceptance rule that follows asked the same two positions again (and, after an optimisation, where the node is again), so the gathered star keeps each tetrahedron's parts and the rule's other measures (inverted or not, inversion, size: `quality::tet::TetRuleMeasures`) for the two positions last asked (`TetMeasures`; a gather forgets them, and a unit test compares the rule's verdicts with every tetrahedron measured afresh). The node loop on rand3D: rules+new 225.9M → 215.1M (the parts) → 203.3M (the rule's other measures too), 3.28× fewer than the issue's day; opt+new 81.1M → 81.8M (writing what it keeps, which the rule after a solve reads once). What is left: the solve itself (the terms, a third of rules' loop) and the acceptance rule's scores where the node moved (each tetrahedron's size, the rule's floor, by nine divisions).
- *3D opt+old with 20 iterations* (issue 33: at least 2×): the tetrahedral max-min objectives answer Freitag's ascent's test of a trial point corner by corner, the worst corner first (`terms_above`, as the planar ones), and the guard's forms, the hexahedra's coefficients and the drivers' changes above serve it too: `valgrind --tool=callgrind smoothlab smooth X.vtk -o o.vtk --strategy opt --objective old --passes 1 --max-iter 20`, rand3D 623.1M → 283.4M (2.20× fewer), the hexahedra 5100M → 649M (7.9×); the written meshes byte for byte the same. Tried and not kept: `old` read from the corners' forms (a further 1.45×), which changed its max-min path by rounding (the knupp-hex tour's old side then ends at 128 → 60 → 55 → 53 inverted instead of 128 → 63 → 50 → 40).
- *hexahedra per corner, and `pave1`'s time to quality* (issue 33: not slower than tetrahedra; `pave1` ≤ 0.54 s): the same kernels serve both (the corners' forms, the guard's forms). A hexahedron's validity is certified over the whole element (27 Bernstein coefficients of det J, where a tetrahedron's is the sign of one determinant) and its shape is the mean of eight corners' mean ratios, each with a correctly rounded cube root. Made this round, each leaving every written mesh byte for byte the same (`cmp` against the previous commit's CLI on Mesquite's 3D files and perturbed blocks of hexahedra, bent, mixed and quadratic, with six or seven strategy/objective pairs each: 164 runs): a star's elements other than tetrahedra keep their validity and shape from visit to visit (`KnownSolids`: what the last star measured of each, with the corners it measured them at; a new star starts each element's memo with it where the corners are the same bits, so an element is not measured again where a neighbour's visit left it, and the priority order measures each element once rather than once per corner node); the smart Laplacian's test refuses a move that does not raise the worst quality before certifying validity at the centroid; the Bernstein coefficients come from a triple-product plan worked out when compiling (`TripleProduct`: the loops' lengths, indices and weights constant, the same sums in the same order; `hex_det` some 3.1k instructions before), and the guard's `DetForm` keeps its coefficients flat. `valgrind --tool=callgrind smoothlab smooth X.vtk -o o.vtk --strategy opt|rules --objective new --passes 1`, the node loop (`Smoother::visit_all_in`, inclusive), before and after this round: on the 10³ block of hexahedra above opt+new 309M → 186M, rules+new 583M → 316M; on rand3D opt+new 80.9M and rules+new 225.4M, unchanged. Per free node and corner (22.5 corners a free node on rand3D, 32 on the hexahedra) opt+new now takes about 3.9k instructions a tetrahedron's corner and 8.0k a hexahedron's (issue 33's day: 12.8k and 98.3k; last round 13.2k): 2.1× (before 7.6×), **not met**. On `pave1` (7110 hexahedra), the whole command of one default pass: 4011M → 2474M instructions (the cache 3267M, the test's order 3159M, the plan 2728M, the flat form 2474M), the pass 598 → 384 ms and the whole command 744 → 515 ms (medians of five runs of each CLI, alternating). What is left on `pave1`: the statistics before and after the pass (the exact dihedral angles, validity and shape of every element: 17% of the command's instructions), reading the file (10%), the shapes' cube roots at the moves' positions, the forms' four evaluations of det J and the acceptance rule's sizes. Then, each leaving every written mesh byte for byte the same (`cmp` against the previous commit's CLI: 675 runs on blocks of hexahedra straight, bent, of 27 nodes and tangled, the mixed solids and Mesquite's 3D files, with `new`, `old`, `sine`, `condition` and `untangle` by `opt`, `rules`, `smart`, `c1` and `c3`): the guard's form of a hexahedron takes its slopes as the triple products' gradients in the free corner (`TripleProduct::slopes`: σ_f (g × h) + σ_g (h × f) + σ_h (f × g) for the one moving coefficient of each factor) where it took three more determinants at moved corners; before the form, a ball about the corner in which the element is valid for certain (`quality::solid::ValidBall`: each coefficient is affine in the corner with weights adding up to 1 over triple products of edges, so its gradient is at most 3E², E the longest edge, and within 0.99 m/3E² of the corner, m the smallest coefficient there, every coefficient stays above twice the form's rounding margin: a position it holds is one the form or the exact test would call valid), which spares the form of a third of the hexahedra and most trials' 27 coefficients; and the shape keeps the terms of the corners that did not move (`quality::solid::CornerShapes`: a corner whose tetrahedron does not hold the free node has the same mean ratio wherever the node goes; summed in `solid_shape`'s order, the same bits; kept with the element in `KnownSolids` too). The node loop (`Smoother::visit_all_in`, inclusive), before and after: on the block of hexahedra above (perturbed by 0.3, seed 3) opt+new 184.9M → 152.4M, rules+new 314.1M → 235.3M, old with 20 iterations 445.0M → 402.4M; on the section's block below (perturbed by 0.2, seed 1) 180.3M → 130.6M, 292.7M → 217.4M and 436.9M → 351.3M; on rand3D unchanged (81.0M). Per corner opt+new now takes about 6.5k and 5.6k instructions a hexahedron's corner on those two blocks against 3.9k a tetrahedron's: 1.7× and 1.45× (2.1× before), **not met**; on `pave1` the whole command of one default pass 2464M → 2107M. Then, with every written mesh the same bytes again (the same 675 runs): the star's elements other than tetrahedra are overwritten in place (a push copied each whole, some 1.4 kB with its lazy form's room); the acceptance rule's size of a solid keeps the sizes of the corners whose tetrahedra do not hold the free node (`quality::solid::CornerSizes`, as the shape's terms, and in `KnownSolids` too: a slot 424 bytes, some 28 MB at most); the guard answers a hexahedron's first position beyond its ball exactly and makes the form only at the second (two in three forms served one or two questions, and a form costs about two exact tests); and the exact test's Bernstein check reads a hexahedron's 27 coefficients as one flat run and decides the first box before allocating its subdivision's stack. The node loop on the section's block (0.2, seed 1), before and after: opt+new 130.2M → 129.1M → 125.4M → 118.5M → 112.4M, rules+new 215.9M → 182.8M, old with 20 iterations 350.7M → 346.7M; rand3D 81.0M → 81.1M; on `pave1` the whole command of one default pass 2102M → 1932M. Per corner opt+new now takes about 4.8k instructions a hexahedron's corner against 3.9k a tetrahedron's (1.25×), **not met**, and the time's ratio is larger than the instructions' (the table: the sizes' divisions and the shapes' cube roots are slow instructions, which a tetrahedron's corner does not take). What is left for the hexahedra beyond the tetrahedra's kernels: the acceptance rule's sizes and their fold (divisions), the shapes' moving corners (cube roots), the gather (the corners' tetrahedra and the known solids' slots, some 21k instructions a star) and the ball's det J at every visit. Then, with every written mesh the same bytes (`cmp` against the previous commit's CLI: every generated sample, their statistics and 1926 `smooth` runs, 18 strategy/objective pairs on them and on Mesquite's 2D and 3D files), the acceptance rule decides a solid's size floor from its corners' Jacobian determinants taken directly where they decide beyond their rounding (`Size::floor_kept_for_certain`, `quality::solid::least_corner_det`: each corner's `unit · scale³` lies within 10⁻¹² extent³ of its determinant, some hundred times the rounding of either, the least corner's choice among near ties within twice that, and the comparison rounds some six ulps; unit tests compare it with the rule's own comparison over moved corners and over shrinks within ulps of the floor, at scales 10⁻⁷⁰ to 10⁷⁰, and a screen without its margins fails them), and measures the sizes (nine divisions a moved corner, a division and a cube a comparison) only where they do not, which on these blocks is never; and `corner_tet` is always inlined (the new loop had left it a call whose result stalled on the store). `opt`+`new` on the section's block (0.2, seed 1), one pass: 19.4 → 17.6 µs a free node (medians of 31 passes, three alternating runs of each build), while the node loop's instructions went only 112.7M → 112.0M: the time was the divisions' latency, not their count. The same screen then serves a tetrahedron (`TetRuleMeasures` keeps its determinant and scale, `det_within`; rand3D opt+new 11.30 → 11.07 µs a free node, rules+new 27.8 → 26.9 µs) and a planar element (`ElementScore::planar_unsized`; a 100k rand2D in Hilbert order, opt+new 1798 → 1690 ns a visit, rules+new 572 → 565), with the same bytes in the same 1926 runs. And the validity guard's first exact test beyond a hexahedron's ball makes a second ball about the position it asked, from the same coefficients (`ValidBall::validity_and_ball`; the same answers, the same bytes in the same runs): the node loop's instructions on the block, opt+old with 20 iterations 343.0M → 308.6M (50.3 against 53.1 µs a free node), opt+new and rules+new about the same (112.5M and 183.6M: their few trials mostly leave both balls). Tried and not kept: the shapes screened as `LeastMeanRatio` screens the tetrahedra, by an estimate with the fast cube root, measured exactly only where an element may be the star's worst (21.4 against 17.7 µs: a shape not measured at a move's position is not kept for the next visit, whose star then measures all eight corners again); and the correctly rounded cube root as `cbrt_fast`'s root certified by its residual in double-double (Dekker's products, no fused multiply-add; the same bits as `f64::cbrt` over 1.2 million values and the midpoints' neighbourhoods), which was slower (18.3–18.9 against 17.7 µs: the standard library's root, CORE-MATH's, costs less than the fast root's two divisions and the certificate); and the valid ball made without the 27 coefficients where the element's last ball gives a floor of them at its moved corners (`m − 3E²·|Δx|`, kept with the element in `KnownSolids`): the floor falls fast (3E² is a loose bound on the coefficients' gradients), so one ball in ten was made from it, the smaller balls asked more forms (the forms 4.2M → 5.6M instructions) and the node loop took more (112.0M → 114.3M). Then, with every written mesh the same bytes (the same 1926 runs against the round's first CLI): the shape's corners take their Jacobians first and their cube roots and divisions after (`CornerShapes::of`: the same operations on each corner, where each waited on the last one's cube root and division); the guard's ball takes its 27 coefficients' least in four running minima and the longest edge in three running maxima (minima are exact); the gather writes a star's corner tetrahedra in place (put together on the stack and moved whole, their 24-byte points were read back in 16-byte pieces: a stall on the store, 64% of a tetrahedral star's gather by `perf annotate`, the same in a hexahedron's); `KnownSolids` keeps the least corner determinant the size screen takes (`StarSolid::least_corner_det_measured`), so the rule's before side is the one the visit that moved the node there took, and no longer keeps the corners' sizes (asked only where the screen does not decide; a 136-byte copy at every recall and keep; slots 424 → 312 bytes); the untangling sweeps' planning reads an element's validity from what the stars kept (`DriverStar::known_valid`) where it took a hexahedron's 27 coefficients again after every sweep; the guard answers a position the drivers measured from that memo (mostly where the node was gathered) and makes a hexahedron's first ball about the first position the memo does not answer, from the exact test there (`ValidBall::validity_and_ball`), rather than about the gathered position, which two hexahedra in three left (3901 exact tests beyond it for 5832 balls); the mean ratio's parts are always inlined (`MeanRatioParts::of`, which the tetrahedra's measures call 45 times a visit); and a gather overwrites the star's corners in place, marking an overwritten corner's form not worked out by its origin and its constant ∇σ (`CornerForm::mark_pending`: a reading at any position is then not a number, as the all-NaN pending form's is) where it wrote a whole 200-byte pending form at every corner of every gather. The node loop's instructions on the section's block (0.2, seed 1), the round's first CLI and its last: opt+new 113.1M → 102.6M, opt+old with 20 iterations 309.3M → 302.7M, rules+new in priority order 183.8M → 168.2M; rand3D opt+new 82.7M → 82.1M. One pass of opt+new (medians of 61 and 21 passes, alternating runs of the builds): the hexahedra 17.8 → 15.2 µs a free node, rand3D 10.97 → 10.45 (the inlined parts and the corners in place sped the tetrahedra too: the inlined parts gave rand3D 3.7% and the hexahedra 2.4%). Tried and not kept: a ball kept with the element in `KnownSolids` and used about the next visit's corner (its radius is a function of the corners alone): the corners it was made at are the ones a visit leaves in 3% of the balls (a node that did not move, or ended at the second ball's centre); and the corners' determinants kept as the shape's terms are, so the size screen's after side takes only the moved corners': more instructions (least determinant 5.4M → 5.9M), the determinants cost less than the memo. Then, with every written mesh the same bytes (the same 1926 runs against the last round's CLI, after each change): a corner whose reference is the identity (a hexahedron's measured corners, and the slot of its corner node) takes its weighted Jacobian as its edges, without the product by W⁻¹ (`CornerReference::identity`: `a·1 + b·0 + c·0` is `a`, the product's bits but for a zero's sign; a unit test compares them); the guard's exact test and its ball take a hexahedron's least coefficient once (`Bezier::validity_with_least`), where each took it from the 27; fewer copies of a star's solids (a kept slot compared with the element's corners where they are and written field by field, a score that copies the corners only for an element not valid, a gather that writes a solid's corners where they stay and takes its corners' tetrahedra from them, and the shape's terms borrowed and copied field by field, `CornerShapes::copy_from`, where a whole copy of their 140 bytes went through a temporary and two calls to `memcpy`: the gather's calls to `memcpy` 49 → 9 a visit); and the size screen's least corner determinant, at a position where the shape was measured, comes from the shape's own Jacobians (`CornerShapes::least_corner_det`: each corner's det A is its σ over det W⁻¹, σ itself for a hexahedron, within some 10⁻¹⁶ extent³ of the determinant taken directly, far inside the screen's tolerance, so its answers are the rule's as before; unit tests run the screen's test on it and compare the two least determinants). Unlike last round's kept determinants, these cost no determinant: the shape takes σ anyway (slots 312 → 376 bytes, some 25 MB at most). The node loop's instructions on the section's block (0.2, seed 1), the round's first CLI and its last: opt+new 102.6M → 94.0M, opt+old with 20 iterations 302.7M → 290.2M, rules+new in priority order 168.2M → 148.2M; rand3D opt+new 82.1M → 82.2M. One pass of opt+new (medians of 21 passes, alternating runs of the builds): the hexahedra 15.3 → 14.7 µs a free node, rand3D unchanged (10.6). Tried and not kept: a hexahedron's other corner forms taking W⁻¹ (entries −1, 0 and 1 for the cube's slots) as signed sums of the edges rather than a product, the same bits but for zeros' signs: more instructions (100.0M → 100.6M, the dispatch on the slot cost more than the products saved), and the loops over a hexahedron's eight corners with its table as a constant (the same instructions). What is left for the hexahedra: the guard's exact test at the first position asked at every visit (27 coefficients, some 880 instructions, for each of the eight hexahedra) and beyond its ball, the shapes' cube roots at the moved corners (the standard library's correctly rounded root, with its fused multiply-adds in software on this target: the same algorithm built for the processor's FMA took 10 against 14 ns in a microbenchmark, the same bits, but it needs the crate's first `unsafe`, for some 1% here) and the corners' forms, which the tetrahedra share.
- *wasm ≤ 1.3× native, the module ≤ 649 KB, one default Step on the 1M sample ≤ 5 s* (issue 33): the wasm build shares the kernels above (the same code). For the 1M Step: in Chen's priority order the reads of a visit (the node's element list, then the elements' nodes, then their positions) are cache misses one after the other, as worst first jumps over the whole mesh; the drivers now read each of them a few visits ahead in such an order (`SmoothMesh::read_ahead`, stages 32, 16, 8, 4 and 2 visits ahead; loads only, every mesh the same bit for bit), so the misses overlap. One `rules` pass in priority order on a 1M-node rand2D (Hilbert-numbered, after 3 smart passes; natively, without and with, alternating): old 11.7 → 7.6 s and new 9.5 → 6.8 s, a second time 9.8 → 7.8 s and 9.5 → 5.6 s; the page's default Step on the 1M sample 25.5 → 22.4 s (the page bench, one run each; old side 14.5 → 12.6 s, new side 10.0 → 8.8 s), less than natively as a visit in wasm costs more in arithmetic. What is left is the order itself: visiting each priority level's nodes in node order rather than worst first took the same two passes to 6.0 and 5.6 s natively, but that is not Chen's \"worst one first\" and would change every result of the default smoother, so it was not made. The issue's baseline of 10 s is the page's figure of 2026-11-24 (commit 0180a51: old side 5.8 s, new 3.8 s); that commit's own CLI, run on this machine on the page's 1M mesh (`rand2d_spatial(996000, 1000, 1)` after 3 smart passes, one `rules` pass with `old` in priority order), does the same work as this tree's (1.17M of the 1.62M visits optimized, 3.49M iterations) in 10.2 s natively, where this tree takes 8.4–9.4 s and the issue's day's 11.5–12.1 s (one to four runs each, alternating): the 10 s were measured on a faster or quieter machine, not lost by the code since, and against what this machine measures the target asks for more than 4×. The same read-ahead for volume meshes was tried and not kept: a tetrahedral visit costs more in arithmetic than in misses (`rules`+`new` in priority order on a 100k-point rand3D, 17 µs a visit: 4.7–5.3 s a pass without, 5.3–5.5 s with, alternating; the same bytes). The figures are this run's, in the sections below. What was tried for them before is in the wasm and page sections. The module's growth since issue 33's day (649 → 814 KB gzipped) was traced by the functions' sizes in the name section of the crate's own `.wasm` (before wasm-bindgen), the commit of the 2026-11-24 figure (e72d68b) against this one: code 1.78 → 2.08 MB, data 196 → 225 KB (the labels' font subset and the reproduction text the tour quotes). By module: the lab (the 3D lab's views, the tour's tables) +66 KB, the sort functions' copies (`core::slice`, one per element type and order) +50 KB, the objectives (3D objectives, forms and Hessians) +47 KB, surfaces +34 KB, the wasm layer (the 3D lab, the notebook's arrays) +31 KB, volume meshes +29 KB, quality (the other volume kinds' measures, exact statistics) +25 KB. It is the code of the work since that day (surfaces, every volume kind, the 3D lab, the notebook widget), spread over the modules, not one change's regression. Not made: building for size (`opt-level = \"z\"`: every pass in Chromium 1.2–1.6× slower, measured before) or leaving features out of the page's module. Made since, each leaving every result the same bits (the same 1020 + 675 written meshes, the generators' samples and the statistics compared with `cmp`): the orderings by a float and the stable sorts by a key share one sort (`numeric::order`: `(u64 key, u32 index)` pairs, a float's key the order `f64::total_cmp` makes, equal keys in index order as a stable sort leaves them), so the module carries one copy of the standard library's sort for them instead of one per element type and comparator (fifteen copies); two sorts of lists already in order became debug checks; the readers' integer parser is one function rather than a copy inlined into every reader. The module, built by `make site` from the same tree before and after: 826474 → 792262 bytes gzipped, the crate's code 1.886 → 1.771 MB. Left: the sorts whose ties are not in index order (`rand3d`'s cavity faces, 6.7 KB), the volume build's face sort (8.2 KB, on the load path), the builder's median (a selection, not a sort), and the sorts inside spade and tiny-skia (some 27 KB). Then, with the same pixels (the golden images, compared exactly) and the same tour: the labels' font read with `ab_glyph`'s `libm` feature rather than `std`, which turned on every table of `ttf-parser` (variable fonts, OpenType and Apple layout, glyph names) that the embedded subset's plain outlines never use (793388 → 775673 bytes gzipped); and the tour's quotes of `docs/reproduction.md` built in as its headings and tables alone (`build.rs`, `lab::tour::tables_only`; a test asks every cell of every table of both texts and finds the same), where the module carried the whole 47 KB document (775673 → 769512). Tried and not kept: binaryen's `-Os` instead of `-O3` (8 KB smaller, every pass in Chromium some 3–8% slower: three alternating runs of the bench page each); the dependencies built at `opt-level = \"s\"` (tiny-skia, ttf-parser, spade, serde and the rest: 18 KB *larger* after the crate's link-time optimisation). What is left is the code of the page's features (the lab and its tour some 285 KB before gzip, tiny-skia 180 KB, the objectives 150 KB, the readers and writers 140 KB, drawing 115 KB, surfaces 100 KB, volume meshes 85 KB): 120 KB gzipped over the target. Then, each leaving every result the same bits (`cmp` against the previous commit's CLI: every generated sample, their statistics and 1764 `smooth` runs (1710 written meshes; Mesquite's three files of polygons refused by both alike), 18 strategy/objective pairs on planar, quadratic, mixed, tetrahedral, hexahedral and mixed solid samples, straight and tangled, and Mesquite's 2D and 3D files): the twelve folds that took the largest component of a set of edges (the scale every metric measures against) share one function (`numeric::largest_component`) that takes it by one comparison a value, where `f64::max` also asked whether the running largest was a number, which wasm pays as a compare and two selects (and, before wasm-opt inlines it, as a call to libm's `fmax`); a unit test compares it with the old fold over random bits, not-a-number components among them (769727 → 767344 bytes gzipped); and the whole-mesh scans for inverted elements (the untangling objectives' test before a pass, the untangling sweeps' after it) read a linear triangle's or quad's corners straight from the mesh rather than copying its nine points. With both, in node (the bench page's mesh and passes, the module of the round's start and this one alternating, medians of five passes, three runs each): opt+old in Hilbert order 3968 → 3886 ns a visit, opt+new 3023 → 2993, rules+new in file order 1619 → 1550. Then the labels' font, with the same pixels (the golden images, compared exactly, and the CLI's tour figures and every `--view` of a plate and a rand3D, compared byte for byte with the previous commit's CLI): `build.rs` reads the embedded subset of DejaVu Sans with `ab_glyph` into tables (`render::font`: each character's glyph, the advances and each outline's curves as zigzag-coded differences in half font units, 41 KB), and `ab_glyph` scales and rasterizes them as before, so the module carries neither the 25 KB file nor `ttf-parser` (some 44 KB of code, with the CFF and table parsers that the subset's plain outlines never used); a unit test compares every table, and the coverage drawn from them at several sizes, with the font as `ab_glyph` reads it (779608 → 763783 bytes gzipped, zlib at level 9 as the page bench measures: the code 1716 → 1672 KB, 678.5 → 660.0 KB gzipped, the data 207 → 230 KB, 86.2 → 89.7 KB gzipped). Outlines stored as 16-bit coordinates rather than differences took some 10 KB more gzipped (the curves alone 25.7 against 16.2 KB), not kept. Then the site's `wasm-opt` is told that the lowest kilobyte of memory is never addressed (`--low-memory-unused`: the crate's stack lies first and ends at 1 MB, its data after it, and Rust's pointers never wrap round to 0), so that a constant added to an address becomes the load's or store's offset: 763783 → 758813 bytes gzipped, as fast (in node, the bench's passes in both orders, the two modules alternating in one process, medians of 15 sweeps, two runs: within ±1% each, laplace, opt+new, opt+old, rules+new). What is left is 109 KB gzipped over the target; among it (sizes in the crate's own `.wasm`, before wasm-bindgen), the copies of the standard library's sorts, one per element type (the crate's own: pairs of node numbers, faces with their numbers, the shared key order, `usize` and the builder's median, some 36 KB before gzip; spade's and tiny-skia's some 20 KB), and the wasm layer's serde conversions (some 44 KB before gzip). Tried and not kept: LLVM told to inline less and unroll less in the wasm build alone (`-C llvm-args=-inline-threshold=N`, `-unroll-threshold=50`; the native build untouched). The module gzipped: 758820 bytes as built, inline threshold 100 → 730765, 50 → 714415, the unroll threshold alone → 744040, both with 100 → 712731, with 50 → 697178. But the passes slowed (in node, the two modules alternating in one process, medians of 7 to 9 sweeps of the bench's passes): with the inline threshold at 100, laplace in Hilbert order 47.6 → 67.9 ns a visit, rules+new in file order 1838 → 2055, opt+new in file order 4383 → 4778; at 50 with the unroll threshold, laplace 49.1 → 72.2, opt+old in file order 4876 → 5629; at 100 with the unroll threshold and `#[inline]` on the meshes' accessors and four of the solvers' helpers (717811 bytes), laplace still 47.7 → 58.4, opt+old in Hilbert order 4121 → 4593, rules+new in file order 2025 → 2210. The name section showed some eighty more functions of the smoothers' paths left as calls (the solvers' start, the guard's test, Newton's step, the objectives' terms, 3D's as much as 2D's), each wanting its own hint, and the 3D passes are not timed by the bench page.
- *file order / Hilbert order at 100k and 1M*: the worst pass is a memory-bound one (each visit reads the node's elements and neighbours, scattered over the whole mesh in file order). The page's own 100k and 1M samples are now numbered along a Hilbert curve when generated (`generate::rand2d_spatial`: the same points sorted before the Delaunay triangulation, so no second build), which took one default Step on the 1M sample from 14.9 to 10.9 s (page bench, one run each). Renumbering inside the smoother was not made: it rebuilds the mesh's topology, about 1.2 µs a node at 1M (measured once, some 30 Laplacian passes), so it cannot bring one pass within 1.5× of the Hilbert-ordered pass; renumbering once before the passes (`Mesh::renumbered_spatially`, above) is the way for large meshes.
";

fn measure(n: usize, quick: bool) -> SizeReport {
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
    let obj = objective(ObjectiveKind::New);
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
    for kind in [ObjectiveKind::New, ObjectiveKind::Old] {
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
    let evaluations = [(ObjectiveKind::New, false), (ObjectiveKind::Old, false), (ObjectiveKind::New, true)]
        .into_iter()
        .map(|(k, chen_alone)| {
            let (e, s) = evaluations_per_visit(&spatial, k, chen_alone);
            let how = if chen_alone { " with Chen's search alone" } else if k == ObjectiveKind::New { " (Newton's first trial)" } else { "" };
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

fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .map(|l| l.split(':').nth(1).unwrap_or("").trim().to_string())
        })
        .unwrap_or_else(|| "unknown".into());
    let cores = std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1);
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    let load: Vec<&str> = load.split_whitespace().take(3).collect();
    format!("{cores} cores ({cpu}); load average {} at the start", load.join(" "))
}

fn today() -> String {
    std::process::Command::new("date")
        .arg("+%Y-%m-%d")
        .output()
        .ok()
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .map(|s| s.trim().to_string())
        .unwrap_or_else(|| "unknown date".into())
}

fn fmt_ns(v: f64) -> String {
    if v >= 1e4 {
        format!("{:.1} µs", v / 1e3)
    } else if v >= 100.0 {
        format!("{v:.0}")
    } else {
        format!("{v:.1}")
    }
}

fn main() {
    let mut sizes = vec![10_000, 100_000, 1_000_000];
    let mut wasm: Option<String> = None;
    let mut page: Option<String> = None;
    let mut page_only = false;
    let mut memory_only = false;
    let mut page_memory: Option<String> = None;
    let mut out: Option<String> = None;
    let mut json_out: Option<String> = None;
    let mut quick = false;
    let mut issue33_only = false;
    let mut before_after: Option<String> = None;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--sizes" => sizes = args.next().unwrap_or_default().split(',').filter_map(|s| s.parse().ok()).collect(),
            "--wasm" => wasm = args.next(),
            "--page" => page = args.next(),
            "--page-only" => page_only = true,
            "--memory-only" => memory_only = true,
            "--page-memory" => page_memory = args.next(),
            "--memory-child" => {
                memory_child(&args.by_ref().collect::<Vec<_>>());
                return;
            }
            "--out" => out = args.next(),
            "--json" => json_out = args.next(),
            "--quick" => quick = true,
            "--issue33" => issue33_only = true,
            "--native-peers" => {
                native_peers(&args.next().unwrap_or_else(|| panic!("--native-peers needs the bench page's JSON file")));
                return;
            }
            "--before-after" => before_after = args.next(),
            other => {
                eprintln!("perf: unknown argument {other}");
                std::process::exit(2);
            }
        }
    }
    if page_only {
        // the "In the page" section alone, from the page bench's JSON (no native run)
        print!("{}", page_section(page.as_deref()));
        return;
    }
    if memory_only {
        // the memory section alone (no timing), as the whole run writes it
        print!("{}", memory_section(page_memory.as_deref()));
        return;
    }
    if issue33_only {
        // issue 33's sections alone: the planar passes they read (100k nodes, both orders),
        // the 3D passes, the time to quality, versus Mesquite and the targets
        eprintln!("perf: {PLANAR_NODES} nodes, the passes of issue 33 …");
        let reports = [measure_rows(PLANAR_NODES, &ISSUE33_PLANAR, quick)];
        // the planar passes these sections read (the full run's table has them all)
        println!("## The planar passes of issue 33, {PLANAR_NODES} nodes, ns per node-pass\n\n| pass | file order | Hilbert |\n|---|---:|---:|");
        for (name, a, b) in &reports[0].rows {
            println!("| {name} | {} | {} |", fmt_ns(*a), fmt_ns(*b));
        }
        println!();
        print!("{}", issue33_sections(&reports, quick, wasm.as_deref(), page.as_deref(), before_after.as_deref()));
        return;
    }
    let machine = machine();
    let mut reports = Vec::new();
    for &n in &sizes {
        eprintln!("perf: {n} nodes …");
        let r = measure(n, quick);
        reports.push(r);
    }
    eprintln!("perf: Newton's first trial against Chen's search, quality …");
    let quality = newton_quality();
    let memory = memory_section(page_memory.as_deref());
    // issue 33's sections read the planar passes of the 100k mesh: measured apart when
    // that size is not among --sizes
    let extra = (!reports.iter().any(|r| r.nodes == PLANAR_NODES)).then(|| {
        eprintln!("perf: {PLANAR_NODES} nodes, the passes of issue 33 …");
        measure_rows(PLANAR_NODES, &ISSUE33_PLANAR, quick)
    });
    let issue33 = match extra {
        Some(r) => issue33_sections(&[r], quick, wasm.as_deref(), page.as_deref(), before_after.as_deref()),
        None => issue33_sections(&reports, quick, wasm.as_deref(), page.as_deref(), before_after.as_deref()),
    };
    let doc = render(&machine, &reports, &quality, &memory, wasm.as_deref()) + &issue33 + &page_section(page.as_deref());
    match out {
        Some(p) => std::fs::write(&p, &doc).unwrap_or_else(|e| panic!("cannot write {p}: {e}")),
        None => print!("{doc}"),
    }
    if let Some(p) = json_out {
        let mut j = serde_json::Map::new();
        for r in &reports {
            let mut m = serde_json::Map::new();
            for (name, a, b) in &r.rows {
                m.insert(name.clone(), serde_json::json!({"file_order_ns": a, "hilbert_ns": b}));
            }
            j.insert(r.nodes.to_string(), serde_json::Value::Object(m));
        }
        std::fs::write(&p, serde_json::to_string_pretty(&j).expect("json"))
            .unwrap_or_else(|e| panic!("cannot write {p}: {e}"));
    }
}

/// The native ns/visit of pass `name` on the mesh of `nodes` nodes, file order.
fn native(reports: &[SizeReport], nodes: usize, name: &str) -> Option<(f64, f64)> {
    let r = reports.iter().find(|r| r.nodes == nodes)?;
    r.rows.iter().find(|row| row.0 == name).map(|row| (row.1, row.2))
}

fn render(
    machine: &str,
    reports: &[SizeReport],
    quality: &[(String, [f64; 4], [f64; 4])],
    memory: &str,
    wasm: Option<&str>,
) -> String {
    let mut d = String::new();
    let w = &mut d;
    let _ = writeln!(w, "# Performance\n");
    let _ = writeln!(
        w,
        "Generated by `make performance` (`examples/perf.rs`, `tests/browser/bench.mjs`); do not edit by hand.\n"
    );
    let _ = writeln!(w, "- Date: {}", today());
    let _ = writeln!(w, "- Machine: {machine}");
    let _ = writeln!(w, "- Native: `cargo run --release --features parallel --example perf -- --out docs/performance.md --wasm target/perf/wasm.json`");
    let _ = writeln!(w, "- Browser: `node tests/browser/bench.mjs > target/perf/wasm.json` (headless Chromium, the release wasm of `make site`), then straight after it the same passes natively into that file: `cargo run --release --features parallel --example perf -- --native-peers target/perf/wasm.json`");
    let _ = writeln!(w, "- CLI: `cargo build --release --features parallel --bin smoothlab` first: the time to quality runs the release binary as the user does");
    let _ = writeln!(w, "- Issue 33's sections alone: `cargo run --release --features parallel --example perf -- --issue33 [--quick] [--before-after target/perf/before_after.json]` (about 2 minutes); its speed-ups before and after in one run: `python3 scripts/before_after.py > target/perf/before_after.json` (builds the CLI of the issue's day beside this tree's)");
    let _ = writeln!(w, "- Criterion benches of the same passes: `cargo bench` (`benches/smoothing.rs`).\n");
    let _ = writeln!(w, "Meshes: Freitag's `rand2d` (Delaunay of uniform random points in the unit square, √n points per side, seed {SEED}), untangled. ");
    let _ = writeln!(w, "A pass is one input-order sweep over the free nodes (`Smoother::sweep`, no statistics); each figure is the median of a few passes, each on a fresh copy of the mesh, in **nanoseconds per node visit**. ");
    let _ = writeln!(w, "*File order* is the numbering rand2d gives (interior points in the random order drawn); *Hilbert* is the same mesh after `Mesh::renumbered_spatially()`.\n");
    let _ = writeln!(w, "Node numbers: smoothlab never renumbers on its own, so `--node N` and written files keep the input's numbering. Renumbering is an explicit step for large meshes: `Mesh::renumbered_spatially()` returns the Hilbert-ordered mesh and the permutation (`perm[new] = old`), and `Mesh::restore_positions` puts smoothed positions back into the input numbering.\n");
    let _ = writeln!(w, "## Native, ns per node-pass\n");
    let mut head = String::from("| pass |");
    let mut rule = String::from("|---|");
    for r in reports {
        let _ = write!(head, " {}k file order | {}k Hilbert |", r.nodes / 1000, r.nodes / 1000);
        rule.push_str("---:|---:|");
    }
    let _ = writeln!(w, "{head}\n{rule}");
    if let Some(first) = reports.first() {
        for (i, (name, _, _)) in first.rows.iter().enumerate() {
            let mut line = format!("| {name} |");
            for r in reports {
                let (_, a, b) = &r.rows[i];
                let _ = write!(line, " {} | {} |", fmt_ns(*a), fmt_ns(*b));
            }
            let _ = writeln!(w, "{line}");
        }
    }
    let _ = writeln!(w, "\nThe statistics a full `Smoother::pass` adds after the node loop (`mesh_stats` and the objective total, `new`), ns per free node:");
    for r in reports {
        let _ = write!(w, " {}k: {};", r.nodes / 1000, fmt_ns(r.stats_ns));
    }
    let _ = writeln!(
        w,
        "\n\n## Against the targets of the optimization issue (native, Hilbert order unless said)\n\n\
         Each cell: the figure, then ✓ where it meets the target and ✗ where it does not.\n"
    );
    let _ = writeln!(
        w,
        "| figure | target |{}",
        reports.iter().map(|r| format!(" {}k |", r.nodes / 1000)).collect::<String>()
    );
    let _ = writeln!(w, "|---|---|{}", "---:|".repeat(reports.len()));
    let get = |r: &SizeReport, name: &str| r.rows.iter().find(|x| x.0 == name).map(|x| x.2).unwrap_or(f64::NAN);
    // file order over Hilbert order, the worst over the passes
    let file_over_hilbert = |r: &SizeReport| {
        r.rows.iter().filter(|x| x.0 != "stream bound").map(|x| x.1 / x.2).fold(0.0f64, f64::max)
    };
    let mark = |ok: bool| if ok { "✓" } else { "✗" };
    let target_rows: [TargetRow; 6] = [
        ("opt+new, ns per visit", "≤ 1000", &|r| get(r, "opt+new"), 1000.0),
        ("opt+new with Chen's search alone (the default before issue 15)", "≤ 1000", &|r| get(r, "opt+new, Chen's search"), 1000.0),
        ("smart / laplace", "≤ 5", &|r| get(r, "smart") / get(r, "laplace"), 5.0),
        ("rules+new / smart (first pass of a fresh rand2D)", "≤ 3", &|r| get(r, "rules+new") / get(r, "smart"), 3.0),
        ("laplace / stream bound", "≤ 3", &|r| get(r, "laplace") / get(r, "stream bound"), 3.0),
        ("file order / Hilbert order, the worst pass", "≤ 1.5", &file_over_hilbert, 1.5),
    ];
    for (name, target, f, limit) in target_rows {
        let cells: String = reports
            .iter()
            .map(|r| {
                let v = f(r);
                let shown = if limit >= 1000.0 { fmt_ns(v) } else { format!("{v:.2}") };
                // where not met, by how much: the figure over the target
                let by = if v <= limit { String::new() } else { format!(" ({:.1}× the target)", v / limit) };
                format!(" {shown} {}{by} |", mark(v <= limit))
            })
            .collect();
        let _ = writeln!(w, "| {name} | {target} |{cells}");
    }
    let _ = write!(w, "\n{TRIED}");
    let _ = writeln!(
        w,
        "\nThe wasm / native ratios (target ≤ 1.3) and the page's figures (one default Step: ≤ 1 s at 100k, ≤ 10 s at \
         1M; Stop ≤ 150 ms; first mesh ≤ 500 ms) are in their sections below, and the coloured passes (target ≥ 1.8× \
         on 2 cores) in theirs."
    );
    if let Some(r) = reports.first() {
        let _ = writeln!(w, "\nWhere the time of `opt` goes ({}k mesh): every visit runs the solver for 3 iterations (Chen §3.1); each iteration's line search evaluates the objective over the whole star several times.", r.nodes / 1000);
        for (k, e, s) in &r.evaluations {
            let _ = write!(w, " {k}: {e:.1} evaluations per visit over {s:.1} elements;");
        }
        let _ = writeln!(w, " one evaluation of `new` (the barrier design of eq. (8)) costs per sub-triangle one Lo α and one η² with their gradients: a handful of divisions, and a square root only where the star started inverted or near-degenerate (δ > 0). Chen's high-low-high search needs at least three evaluations per iteration (a low point, a high point, the parabola's vertex), so a visit of 3 iterations takes at least 10 evaluations. Newton's first trial takes one evaluation for an iteration whose Newton step is kept as it is, more where Chen's search extends it or takes over.");
    }
    let _ = writeln!(
        w,
        "\nThe smoothed meshes with Chen's search alone and with Newton's first trial (the default): `new`, the default \
         smoother (rules, priority order), 3 passes; the means over each family of the smallest and largest angle and \
         the mean α/β, and the meshes still tangled after.\n"
    );
    let _ = writeln!(w, "| meshes | smallest angle, Chen / Newton | largest angle | mean α/β | still tangled |");
    let _ = writeln!(w, "|---|---:|---:|---:|---:|");
    for (name, c, n) in quality {
        let _ = writeln!(
            w,
            "| {name} | {:.2}° / {:.2}° | {:.2}° / {:.2}° | {:.4} / {:.4} | {} / {} |",
            c[0], n[0], c[1], n[1], c[2], n[2], c[3], n[3]
        );
    }
    let _ = write!(w, "\n{memory}");
    let _ = writeln!(w, "## Level-set sampling\n");
    let _ = writeln!(
        w,
        "The objective of one node sampled on a 100 × 100 grid over its star (`Objective::value`), ns per sample:"
    );
    if let Some(r) = reports.first() {
        for (k, v) in &r.levelset {
            let _ = write!(w, " `{k}` {};", fmt_ns(*v));
        }
    }
    let _ = writeln!(w, "\n\nRendering: `render::render_mesh` (default `MeshView`: elements filled by quality, edges drawn) into a 1024 × 1024 pixmap, ns per element:");
    for r in reports {
        let _ = write!(w, " {}k: {};", r.nodes / 1000, fmt_ns(r.render_ns));
    }
    let _ = writeln!(w, "\n");
    let _ = writeln!(w, "## Multi-core: coloured passes\n");
    if reports.iter().all(|r| r.parallel.is_empty()) {
        let _ = writeln!(w, "Not measured: build with `--features parallel`.\n");
    } else {
        let _ = writeln!(w, "Free nodes coloured greedily so that no two of one colour share an element; each colour smoothed on all threads (rayon), moves written after (`ColouredSmoother`, `Execution::Deferred`; bit-identical to the in-place pass in the same order). Hilbert order. ns per node visit on 1 thread → all threads, and the speed-up; the colouring is made once per mesh and not timed in the passes ({}):\n", reports.iter().map(|r| format!("{}k: {:.0} ns per node", r.nodes / 1000, r.colouring_ns)).collect::<Vec<_>>().join(", "));
        let _ = writeln!(
            w,
            "| pass |{}",
            reports.iter().map(|r| format!(" {}k ({} colours) |", r.nodes / 1000, r.colours)).collect::<String>()
        );
        let _ = writeln!(w, "|---|{}", "---|".repeat(reports.len()));
        if let Some(first) = reports.first() {
            for (i, (name, _, _)) in first.parallel.iter().enumerate() {
                let mut line = format!("| {name} |");
                for r in reports {
                    let (_, a, b) = &r.parallel[i];
                    let _ = write!(line, " {} → {} ({:.2}×) |", fmt_ns(*a), fmt_ns(*b), a / b);
                }
                let _ = writeln!(w, "{line}");
            }
        }
        let _ = writeln!(w, "\nTarget (issue 15): ≥ 1.8× on 2 cores for `opt` and `rules`. The machine's load average at the start is given above: other work on the same cores lowers the speed-up.{COLOUR_NOTE}\n");
    }
    let _ = writeln!(w, "## WebAssembly in headless Chromium\n");
    match wasm.map(std::fs::read_to_string) {
        Some(Ok(text)) => match serde_json::from_str::<serde_json::Value>(&text) {
            Ok(v) => wasm_table(w, &v, reports),
            Err(e) => {
                let _ = writeln!(w, "The browser bench's output could not be read ({e}).\n");
            }
        },
        Some(Err(e)) => {
            let _ = writeln!(w, "The browser bench's output could not be read ({e}).\n");
        }
        None => {
            let _ = writeln!(w, "Not measured in this run (no `--wasm` file).\n");
        }
    }
    d
}

/// The wasm table: the bench page's ns/visit against the native figure of the same pass
/// on the same mesh and numbering.
fn wasm_table(w: &mut String, v: &serde_json::Value, reports: &[SizeReport]) {
    let nodes = v["nodes"].as_u64().unwrap_or(0) as usize;
    let _ = writeln!(
        w,
        "The bench page (`www/bench.html`) generates the same rand2d mesh ({} nodes, seed {}) in wasm and times one pass with `performance.now()`, median of {} passes on fresh copies. {} {}\n",
        nodes,
        v["seed"],
        v["reps"],
        v["browser"].as_str().map(|b| format!("Browser: {b}.")).unwrap_or_default(),
        if v["passes"].as_array().into_iter().flatten().any(|r| r["native_ns_per_visit"].is_f64()) {
            "The native figures were measured straight after the page (`perf --native-peers`: the same passes on the same mesh and numbering, \
             the median of a few passes each), so each ratio compares two figures of the same minute on this shared machine."
        } else {
            "The native figures are this run's planar table's, measured some minutes after the page."
        }
    );
    let _ = writeln!(w, "| pass | order | wasm ns/visit | native ns/visit | wasm / native (target ≤ 1.3) |");
    let _ = writeln!(w, "|---|---|---:|---:|---:|");
    let mut ratios = Vec::new();
    for (name, hilbert, ns, nat) in wasm_rows(v, reports) {
        let (nat_s, ratio) = match nat {
            Some(n) => {
                ratios.push(ns / n);
                (fmt_ns(n), format!("{:.2}", ns / n))
            }
            None => ("not measured".into(), "—".into()),
        };
        let _ = writeln!(
            w,
            "| {name} | {} | {} | {nat_s} | {ratio} |",
            if hilbert { "Hilbert" } else { "file" },
            fmt_ns(ns)
        );
    }
    let (lo, hi) = ratios.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &r| (lo.min(r), hi.max(r)));
    if hi > WASM_NATIVE_TARGET {
        let _ = writeln!(w, "\nNot met: the strategies run {lo:.2}–{hi:.2}× their native time in Chromium (the table). {WASM_TRIED}");
    }
    let _ = writeln!(w);
}

/// The mesh of the memory figures: the 1M-node rand2D of the memory issue (Freitag's
/// rand2d with 999 576 points inside and 1000 per side, seed 2003: 1 003 576 nodes).
const MEMORY_MESH: (usize, usize, u64) = (999_576, 1000, SEED);

/// The commands whose peak resident memory the memory section reports, each run in a
/// child process (`--memory-child`): (what it does, its words for `memory_child`).
const MEMORY_COMMANDS: [(&str, &[&str]); 6] = [
    ("`smoothlab generate rand2d` (spade's Delaunay), written as .msh", &["generate"]),
    ("`smoothlab stats` (read the .msh, statistics)", &["stats"]),
    ("`smoothlab smooth`: read, 3 passes of rules + new in priority order (the default), write", &["smooth", "rules"]),
    ("`smooth --strategy laplace`: read, 3 passes, write", &["smooth", "laplace"]),
    ("`smooth --strategy opt`: read, 3 passes, write", &["smooth", "opt"]),
    ("`smooth --strategy smart`: read, 3 passes, write", &["smooth", "smart"]),
];

/// A command of [`MEMORY_COMMANDS`] as `smoothlab` runs it (the library calls of its
/// `generate`, `stats` and `smooth`), then prints this process's peak resident memory.
/// Words: `generate OUT`, `stats IN`, `smooth STRATEGY IN OUT`.
fn memory_child(words: &[String]) {
    let w: Vec<&str> = words.iter().map(String::as_str).collect();
    let opts = smoothlab::io::WriteOptions::default();
    match w.as_slice() {
        ["generate", out] => {
            let (inside, per_side, seed) = MEMORY_MESH;
            let mesh = rand2d(inside, per_side, seed).expect("rand2d");
            smoothlab::io::write_path(&mesh, std::path::Path::new(out), &opts).expect("write");
        }
        ["stats", input] => {
            let mesh = smoothlab::io::read_path(std::path::Path::new(input)).expect("read");
            std::hint::black_box(mesh_stats(&mesh));
        }
        ["smooth", strategy, input, out] => {
            let mut mesh = smoothlab::io::read_path(std::path::Path::new(input)).expect("read");
            let (strategy, order) = match *strategy {
                "rules" => (Strategy::Rules, Order::Priority),
                "laplace" => (Strategy::Laplace, Order::Input),
                "opt" => (Strategy::Opt, Order::Input),
                "smart" => (Strategy::Smart, Order::Input),
                other => panic!("perf: no strategy {other}"),
            };
            let obj = objective(ObjectiveKind::New);
            let mut smoother =
                Smoother::new(SmoothOptions::default().with_strategy(strategy).with_order(order)).expect("options");
            let t0 = Instant::now();
            let clock = move || t0.elapsed().as_secs_f64() * 1e3;
            for _ in 0..3 {
                std::hint::black_box(smoother.pass(&mut mesh, &*obj, &clock));
            }
            smoothlab::io::write_path(&mesh, std::path::Path::new(out), &opts).expect("write");
            std::hint::black_box(mesh_stats(&mesh));
        }
        _ => panic!("perf: --memory-child generate OUT | stats IN | smooth STRATEGY IN OUT"),
    }
    println!("{}", vm_hwm().unwrap_or(0));
}

/// The peak resident memory, bytes, of a child running `memory_child` with `words`.
fn child_peak(words: &[&str]) -> Option<usize> {
    let exe = std::env::current_exe().ok()?;
    let out = std::process::Command::new(exe).arg("--memory-child").args(words).output().ok()?;
    if !out.status.success() {
        eprintln!("perf: --memory-child {}: {}", words.join(" "), String::from_utf8_lossy(&out.stderr));
        return None;
    }
    String::from_utf8(out.stdout).ok()?.trim().parse().ok()
}

/// The memory section: the bytes of each array of the 1M-node mesh per node and per
/// element, the peak resident memory of each command on it, and the page's wasm memory
/// (from `tests/browser/page_memory.mjs`'s JSON, when given).
fn memory_section(page_memory: Option<&str>) -> String {
    let mut w = String::new();
    let (inside, per_side, seed) = MEMORY_MESH;
    eprintln!("perf: memory …");
    let mesh = rand2d(inside, per_side, seed).expect("rand2d");
    let (n, e) = (mesh.node_count(), mesh.element_count());
    let _ = writeln!(w, "## Memory\n");
    let _ = writeln!(
        w,
        "The 1M-node rand2D of the memory issue (rand2d with {inside} points inside and {per_side} per side, seed {seed}: {n} nodes, {e} triangles, {} edges). \
         Each array of the mesh (`Mesh::memory_parts`, capacities) in bytes per node and per element; *shared* arrays are shared by the mesh's clones \
         (`Mesh` keeps the elements and the topology behind one `Arc`: a clone copies positions and fixed flags only, so the page's two sides hold them once).\n",
        mesh.edges().len()
    );
    let _ = writeln!(w, "| array | MB | bytes per node | bytes per element | shared |\n|---|---:|---:|---:|---|");
    let parts = mesh.memory_parts();
    for p in &parts {
        let _ = writeln!(
            w,
            "| {} | {:.1} | {:.2} | {:.2} | {} |",
            p.name,
            p.bytes as f64 / 1e6,
            p.bytes as f64 / n as f64,
            p.bytes as f64 / e as f64,
            if p.shared { "yes" } else { "no" }
        );
    }
    let total: usize = parts.iter().map(|p| p.bytes).sum();
    let own: usize = parts.iter().filter(|p| !p.shared).map(|p| p.bytes).sum();
    let _ = writeln!(
        w,
        "| **the mesh** (`Mesh::heap_bytes`) | **{:.1}** | **{:.1}** | **{:.1}** | |\n| a clone's own arrays | {:.1} | {:.1} | {:.1} | |\n",
        total as f64 / 1e6,
        total as f64 / n as f64,
        total as f64 / e as f64,
        own as f64 / 1e6,
        own as f64 / n as f64,
        own as f64 / e as f64
    );
    // the commands, each in a child process, on the mesh written as .msh
    let dir = std::env::temp_dir().join(format!("smoothlab-perf-memory-{}", std::process::id()));
    let _ = std::fs::create_dir_all(&dir);
    let file = dir.join("rand2d-1m.msh");
    let out = dir.join("smoothed.msh");
    smoothlab::io::write_path(&mesh, &file, &smoothlab::io::WriteOptions::default()).expect("write the test mesh");
    drop(mesh);
    let size = std::fs::metadata(&file).map(|m| m.len()).unwrap_or(0);
    let _ = writeln!(
        w,
        "Peak resident memory of each command on that mesh ({:.0} MB as .msh 2.2), the whole process: the library calls of `smoothlab`'s commands run in a child process of `examples/perf.rs`, whose `VmHWM` (what `/usr/bin/time -v` reports as maximum resident set size) is read at its end. \
         Target of the memory issue: read, 3 passes and written in ≤ 250 MB.\n",
        size as f64 / 1e6
    );
    let _ = writeln!(w, "| command | peak RSS | ≤ 250 MB |\n|---|---:|---|");
    let (f, o) = (file.to_string_lossy().into_owned(), out.to_string_lossy().into_owned());
    let gen_out = dir.join("generated.msh").to_string_lossy().into_owned();
    for (what, words) in MEMORY_COMMANDS {
        let mut args: Vec<&str> = words.to_vec();
        match words[0] {
            "generate" => args.push(&gen_out),
            "stats" => args.push(&f),
            _ => {
                args.push(&f);
                args.push(&o);
            }
        }
        eprintln!("perf: memory of {}", args.join(" "));
        let peak = child_peak(&args);
        let shown = peak.map(|b| format!("{:.0} MB", b as f64 / 1e6)).unwrap_or_else(|| "failed".into());
        let met = match (words[0], peak) {
            ("smooth", Some(b)) => if b as f64 <= 250e6 { "✓" } else { "✗" },
            _ => "",
        };
        let _ = writeln!(w, "| {what} | {shown} | {met} |");
    }
    let _ = std::fs::remove_dir_all(&dir);
    let _ = writeln!(
        w,
        "\nWhere the bytes of a command go (by heaptrack): the peak of every command that reads a file is in reading, where the file's text is held whole \
         with what has been read (the nodes with their lines and tags, the elements as node indices); the text is let go before the mesh is built. \
         Building the topology holds the mesh being built and the edge uses filed by node (8 bytes a use, 24 bytes a triangle); a pass adds the smoother's \
         visit order and the statistics' arrays; writing adds a 64 KiB buffer (the text goes to the file in chunks).\n"
    );
    // the page
    let _ = writeln!(w, "The page (`node tests/browser/page_memory.mjs`): the worker's wasm memory (`memory.buffer.byteLength`, which never shrinks) with the 1M-node sample (generated in wasm), both sides, in one worker (the page splits a pass between two workers from 20k to 500k nodes only, and each of the two then holds its own copy of the mesh). Target: ≤ 400 MiB.\n");
    let v: Option<serde_json::Value> =
        page_memory.and_then(|p| std::fs::read_to_string(p).ok()).and_then(|t| serde_json::from_str(&t).ok());
    match v {
        None => {
            let _ = writeln!(w, "Not measured in this run (no `--page-memory` file).\n");
        }
        Some(v) => {
            let mib = |x: &serde_json::Value| x.as_f64().map(|b| b / (1u64 << 20) as f64).unwrap_or(f64::NAN);
            let mark = |x: f64| if x <= 400.0 { "✓" } else { "✗" };
            let (loaded, smoothed) = (mib(&v["loaded"]["peak_bytes"]), mib(&v["smoothed"]["peak_bytes"]));
            let _ = writeln!(
                w,
                "| {} ({} nodes, {} elements) | wasm memory | ≤ 400 MiB |\n|---|---:|---|\n| the sample loaded and drawn | {loaded:.0} MiB | {} |\n| after one Step (rules, priority order, both sides) | {smoothed:.0} MiB | {} |\n",
                v["browser"].as_str().unwrap_or("Chromium"),
                v["nodes"],
                v["elements"],
                mark(loaded),
                mark(smoothed)
            );
        }
    }
    w
}

/// The "In the page" section from the JSON of `node tests/browser/page_bench.mjs`
/// (`--page FILE`; `--page-only` prints this section alone, without a native run): the
/// playground page itself at 100k and 1M nodes.
fn page_section(path: Option<&str>) -> String {
    let mut w = String::new();
    let _ = writeln!(w, "## In the page
");
    let v: serde_json::Value = match path.map(std::fs::read_to_string) {
        None => {
            let _ = writeln!(w, "Not measured in this run (no `--page` file).\n");
            return w;
        }
        Some(Err(e)) => {
            let _ = writeln!(w, "The page bench's output could not be read ({e}).\n");
            return w;
        }
        Some(Ok(text)) => match serde_json::from_str(&text) {
            Ok(v) => v,
            Err(e) => {
                let _ = writeln!(w, "The page bench's output could not be read ({e}).\n");
                return w;
            }
        },
    };
    let f = |x: &serde_json::Value| x.as_f64().unwrap_or(f64::NAN);
    let ms = |x: &serde_json::Value| format!("{:.0}", f(x));
    let pair = |x: &serde_json::Value| format!("{} / {}", ms(&x[0]), ms(&x[1]));
    let h = &v["hundred_k"];
    let steps = h["steps"].as_array().cloned().unwrap_or_default();
    let canvas = steps.first().map(|s| &s["median"]["canvas"]).cloned().unwrap_or_default();
    let _ = writeln!(
        w,
        "The playground page itself (`www/index.html`), driven as a user drives it by `node tests/browser/page_bench.mjs` \
         ({}, viewport {}×{}, mesh canvases {}×{} device pixels); the figures are the page's own measurements \
         (`window.smoothlab.metrics`). A pass runs in the worker in slices of {} ms, so the progress bar moves and Stop is \
         heard during a pass; the statistics after a pass are the table's (inverted elements, extreme angles, smallest quality, \
         one pass over the elements), the angle histograms are computed when the charts are drawn.\n",
        v["browser"].as_str().unwrap_or("Chromium"),
        v["viewport"][0],
        v["viewport"][1],
        canvas[0],
        canvas[1],
        v["slice_ms"]
    );
    let _ = writeln!(
        w,
        "### One pass + redraw, {} nodes ({} elements)\n\nStep on the mesh as loaded: from the click to both meshes and both statistics tables redrawn (target < 100 ms), \
         median of {} clicks; then where the time went, old / new side, ms. The charts (per-pass curves, two angle histograms) are drawn after.\n",
        h["nodes"],
        h["elements"],
        steps.first().map(|s| s["reps"].clone()).unwrap_or_default()
    );
    let _ = writeln!(w, "| settings | click → redrawn | < 100 ms | all but smoothing | smoothing | statistics | rendering | copy out of wasm | messages | putImageData | charts after |");
    let _ = writeln!(w, "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    for s in &steps {
        let m = &s["median"];
        let wall = f(&m["wall_ms"]);
        let _ = writeln!(
            w,
            "| {} | {:.0} ms | {} | {:.0} ms | {} | {} | {} | {:.1} | {:.1} | {:.1} / {:.1} | {} |",
            s["name"].as_str().unwrap_or("?"),
            wall,
            if wall < 100.0 { "met" } else { "not met" },
            // per click, then the median (medians of the parts need not add up); in two
            // workers the two sides' sweeps overlap, and the longer one is the smoothing's time
            median(
                s["runs"]
                    .as_array()
                    .map(|runs| runs
                        .iter()
                        .map(|r| {
                            let (a, b) = (f(&r["sweep_ms"][0]), f(&r["sweep_ms"][1]));
                            f(&r["wall_ms"]) - if f(&r["workers"]) == 2.0 { a.max(b) } else { a + b }
                        })
                        .collect())
                    .unwrap_or_else(|| vec![f64::NAN])
            ),
            pair(&m["sweep_ms"]),
            pair(&m["stats_ms"]),
            pair(&m["render_ms"]),
            f(&m["copy_ms"]),
            f(&m["messaging_ms"]) + f(&m["transfer_ms"]),
            f(&m["paint_ms"][0]),
            f(&m["paint_ms"][1]),
            ms(&m["charts_ms"])
        );
    }
    let _ = writeln!(
        w,
        "\nBoth sides smooth with the same settings: the default is Chen's rules in priority order, with the max-min objective on the \
         old side and the new objective on the new side. *Smoothing* is the node loop of each side (planning the order included): the \
         strategies' own cost per node visit, measured natively and in wasm in the sections above. *All but smoothing* is the rest of the \
         click's time: statistics, drawing both meshes, copying and moving the pixels, the worker's messages, painting and the tables \
         (in two workers, the click's time less the longer side's smoothing)."
    );
    let ready = &h["second_worker_ready_ms"];
    let workers = steps.first().map(|s| f(&s["median"]["workers"])).unwrap_or(f64::NAN);
    let _ = writeln!(
        w,
        "\nA planar mesh of 20k to 500k nodes is smoothed in two workers (`www/app/workers.js`, `SPLIT_MIN_NODES`): after a load a second \
         worker loads the same mesh in the background{}; each pass then sends it the old side's positions, it sweeps them while \
         the first worker smooths the new side, and the first adopts its sweep and measures it (`lab::pass`, the same records and \
         meshes as one worker, bit for bit: a unit test and a browser test compare them). The default Step above ran in {} worker(s); \
         its *smoothing* of the old side is the second worker's, at the same time as the new side's.",
        if ready.is_null() { String::new() } else { format!(" (here ready {} ms after the load, before the first Step was timed)", ms(ready)) },
        if workers.is_nan() { "?".to_string() } else { format!("{workers:.0}") }
    );
    let st = &v["startup"]["median"];
    if !st.is_null() {
        let first = f(&st["first_mesh_ms"]);
        let _ = writeln!(
            w,
            "\nThe first visit, from the navigation to the first mesh drawn (target ≤ 500 ms): {} ms, {}, median of {} fresh pages \
             ({}: the engine (worker and wasm module) answered after {} ms, the menus were filled by {} ms, the first frame of both \
             meshes took {} ms). The module: {} bytes, {} bytes gzipped (zlib level 9; target ≤ 400 KB).",
            ms(&st["first_mesh_ms"]),
            if first <= 500.0 { "met" } else { "not met" },
            v["startup"]["runs"],
            st["sample"].as_str().unwrap_or("the default sample"),
            ms(&st["engine_ready_ms"]),
            ms(&st["menus_ms"]),
            ms(&st["first_frame_ms"]),
            v["wasm"]["bytes"],
            v["wasm"]["gzip_bytes"]
        );
    }
    let targets = |got: f64, target: f64, unit: &str| {
        if got.is_nan() {
            "not measured".to_string()
        } else if got <= target {
            format!("{got:.0} {unit}, met")
        } else {
            format!("{got:.0} {unit}, not met ({:.1}× the target)", got / target)
        }
    };
    let million_step = f(&v["million"]["default_step"]["wall_ms"]) / 1000.0;
    let _ = writeln!(
        w,
        "\nIssue 15's targets in this run{}: one default Step at 100k ≤ 1000 ms: {}; at 1M ≤ 10 s: {}; the first mesh ≤ 500 ms: {}; \
         the module ≤ 400 KB gzipped: {}.",
        v["load_average"].as_array().map(|l| format!(" (load average {} at the start)", l.first().map(|x| x.to_string()).unwrap_or_default())).unwrap_or_default(),
        targets(f(&steps.first().map(|s| s["median"]["wall_ms"].clone()).unwrap_or_default()), 1000.0, "ms"),
        targets(million_step, 10.0, "s"),
        targets(f(&st["first_mesh_ms"]), 500.0, "ms"),
        targets(f(&v["wasm"]["gzip_bytes"]) / 1000.0, 400.0, "KB")
    );
    let _ = writeln!(
        w,
        "\nWhat was tried for these targets (issue 15), each measured on its own: the site build runs binaryen's `wasm-opt -O3` (npm's; \
         601 → 560 KB gzipped; `-Oz` 4 KB smaller and no faster; `opt-level = \"s\"` for the crate 21 KB smaller after wasm-opt, \
         its speed not measured, not kept); the module is built with 128-bit SIMD, which tiny-skia's `simd` feature uses (560 → 513 KB \
         gzipped, node visits and drawing faster); after a load or Reset the two panels show the same positions and the mesh is drawn once for both. \
         What is left of the module is code the page uses: the core's file readers and writers, tiny-skia's pipelines (lowp and \
         highp, ~350 KB before gzip) and glyph outlines for the labels, the charts, the tour's pictures. The crate built for size \
         (`opt-level = \"z\"`, after wasm-opt -O3) makes the module 531 KB gzipped (from 637 at the time), but every pass in Chromium 1.2–1.6× \
         slower (opt+old 1.54×, rules+new 1.26×, Hilbert order, one run each), not kept; the dependencies alone at `\"z\"` or \
         `\"s\"`: 629 and 660 KB, not kept. Sweeping the two sides of a pass in two workers was first measured on this machine \
         with other builds running (no gain then); on an idle machine the two sweeps take the two cores (two 100k sweeps of opt, \
         old and new: 460 ms one after the other, 270 ms at once), so it is kept, from 20k to 500k nodes (above). The 1M mesh \
         stays in one worker: two copies of it would take the page past its 400 MiB (the memory section). For the 1M Step in one worker: the sample \
         is numbered along a Hilbert curve (the file-order row above), and Chen's priority order, which measures every star \
         before a pass, reads a planar star of linear triangles straight from the mesh and sorts the ranking by key (planning \
         1M nodes natively: 200 → 152 ms, the same order)."
    );
    let load = &h["load"];
    let _ = writeln!(
        w,
        "\nLoading the {}-node sample (generated in wasm, statistics, first drawing): {} ms; the main thread's longest gap between animation frames meanwhile {} ms.\n",
        h["nodes"],
        ms(&load["ms"]),
        ms(&load["longest_frame_gap_ms"])
    );
    let m = &v["million"];
    if m.is_null() {
        let _ = writeln!(w, "The 1M-node sample was not measured in this run.\n");
        return w;
    }
    let _ = writeln!(w, "### 1M nodes: load, 3 passes, Stop\n");
    let load = &m["load"];
    let mib = |x: &serde_json::Value| format!("{:.0} MiB", f(x) / 1048576.0);
    let _ = writeln!(
        w,
        "- The sample ({} nodes, {} elements, generated in wasm) loads and is drawn in {:.1} s; the main thread's longest gap between animation frames meanwhile {} ms, a 50 ms interval at most {} ms late.",
        m["nodes"],
        m["elements"],
        f(&load["ms"]) / 1000.0,
        ms(&load["longest_frame_gap_ms"]),
        ms(&load["worst_interval_lateness_ms"])
    );
    let run = &m["run"];
    let passes = run["passes"].as_array().cloned().unwrap_or_default();
    let _ = writeln!(
        w,
        "- Run, 3 passes of {}: {:.1} s in all (charts included). The main thread's longest gap between frames during the run {} ms, a 50 ms interval at most {} ms late.",
        m["strategy"].as_str().unwrap_or("?"),
        f(&run["total_ms"]) / 1000.0,
        ms(&run["longest_frame_gap_ms"]),
        ms(&run["worst_interval_lateness_ms"])
    );
    let _ = writeln!(w, "\n| pass | pass + redraw | slices | progress updates during the pass | smoothing old / new | statistics old / new | rendering old / new |");
    let _ = writeln!(w, "|---:|---:|---:|---:|---:|---:|---:|");
    for (i, p) in passes.iter().enumerate() {
        let _ = writeln!(
            w,
            "| {} | {:.1} s | {} | {} | {} ms | {} ms | {} ms |",
            p["pass"],
            f(&p["wall_ms"]) / 1000.0,
            p["slices"],
            run["progress_updates_within_pass"][i],
            pair(&p["sweep_ms"]),
            pair(&p["stats_ms"]),
            pair(&p["render_ms"])
        );
    }
    let stop = &m["stop"];
    let _ = writeln!(
        w,
        "\n- Stop during a pass: the page is idle again after {} ms (the pass is undone: both meshes as before it).",
        ms(&stop["to_idle_ms"])
    );
    if let Some(ms_) = m["stop_while_ordering"]["to_status_ms"].as_f64() {
        let _ = writeln!(
            w,
            "- Stop right after a click with the default settings (rules, priority order), while the smoother orders the nodes worst first \
             (`Smoother::begin_plan`/`plan_some`, in slices like the sweep): {ms_:.0} ms."
        );
    }
    let d = &m["default_step"];
    if !d.is_null() {
        let _ = writeln!(
            w,
            "- One Step with the default settings, on the mesh as the run above left it: {:.1} s to the redrawn meshes (smoothing old {:.1} s, new {:.1} s; {} node visits a side in \
             priority order), in {} slices; the main thread's longest gap between frames meanwhile {} ms.",
            f(&d["wall_ms"]) / 1000.0,
            f(&d["sweep_ms"][0]) / 1000.0,
            f(&d["sweep_ms"][1]) / 1000.0,
            d["visits"][0],
            d["slices"],
            ms(&d["longest_frame_gap_ms"])
        );
    }
    let _ = writeln!(
        w,
        "- wasm memory (`memory.buffer.byteLength`, which never shrinks): {} at the end, {} at most. The two sides share the mesh's elements and topology (clones of a `Mesh` share them) and each holds its own positions; the mesh as loaded is kept as positions only.\n",
        mib(&m["memory"]["bytes"]),
        mib(&m["memory"]["peak_bytes"])
    );
    w
}

// ---------------------------------------------------------------------------------------
// Issue 33: performance versus Mesquite. The 3D passes (tetrahedra and hexahedra), the
// time to quality of the CLI's defaults, the "versus Mesquite" table and the targets.

/// Issue 33's targets for the browser: the wasm / native ratio of every pass, the module's
/// gzipped bytes (its size on the issue's day) and one default Step on the 1M sample.
const WASM_NATIVE_TARGET: f64 = 1.3;
const MODULE_GZIP_TARGET: f64 = 649_479.0;
const STEP_1M_TARGET_S: f64 = 5.0;

/// The seed of rand3D, as `benches/smoothing.rs` (`tetrahedra`) and Freitag's Table 2's first.
const RAND3D_SEED: u64 = 1;
/// The block of hexahedra: `HEX_CELLS³` cells of the unit cube (about rand3D's node count),
/// every free node moved by up to `HEX_AMOUNT` mean edge lengths (`perturb_volume`,
/// seed 1), a perturbation small enough that every hexahedron stays valid.
const HEX_CELLS: usize = 10;
const HEX_AMOUNT: f64 = 0.2;

/// The 3D passes: name, strategy, objective, order and solver iterations per call.
const VOLUME_PASSES: [(&str, Strategy, ObjectiveKind, Order, u32); 8] = [
    ("laplace", Strategy::Laplace, ObjectiveKind::New, Order::Input, DEFAULT_MAX_ITER),
    ("smart", Strategy::Smart, ObjectiveKind::New, Order::Input, DEFAULT_MAX_ITER),
    ("opt+new", Strategy::Opt, ObjectiveKind::New, Order::Input, DEFAULT_MAX_ITER),
    ("rules+new, priority order", Strategy::Rules, ObjectiveKind::New, Order::Priority, DEFAULT_MAX_ITER),
    ("opt+old, 20 it", Strategy::Opt, ObjectiveKind::Old, Order::Input, 20),
    ("opt+sine", Strategy::Opt, ObjectiveKind::Sine, Order::Input, DEFAULT_MAX_ITER),
    ("opt+condition", Strategy::Opt, ObjectiveKind::Condition, Order::Input, DEFAULT_MAX_ITER),
    ("opt+untangle", Strategy::Opt, ObjectiveKind::Untangle, Order::Input, DEFAULT_MAX_ITER),
];

/// A volume mesh measured by the 3D section: its words, sizes and the measured corners of
/// its free nodes' stars.
struct VolumeBench {
    what: String,
    mesh: VolumeMesh,
    free: usize,
    /// Σ over the free nodes of their stars' measured corners (`CornerStar::tets`: one
    /// per tetrahedron; a hexahedron's corners whose corner tetrahedron holds the node).
    corners: usize,
}

impl VolumeBench {
    fn new(what: String, mesh: VolumeMesh) -> Self {
        let mut star = CornerStar::default();
        let free = mesh.free_count();
        let corners = (0..mesh.node_count())
            .filter(|&n| mesh.is_free(n))
            .map(|n| {
                star.gather(&mesh, n);
                star.tets.len()
            })
            .sum();
        VolumeBench { what, mesh, free, corners }
    }
    fn corners_per_node(&self) -> f64 {
        self.corners as f64 / self.free.max(1) as f64
    }
}

/// One 3D pass on one mesh: ns per free node, visits per free node, ns per measured corner.
#[derive(Clone, Copy)]
struct VolumeFigure {
    ns_per_node: f64,
    visits_per_node: f64,
    ns_per_corner: f64,
}

struct VolumeReport {
    meshes: [VolumeBench; 2],
    reps: usize,
    /// (pass, [rand3D, hexahedra])
    rows: Vec<(&'static str, [VolumeFigure; 2])>,
}

impl VolumeReport {
    /// The figure of pass `name` on mesh `i` (0 rand3D, 1 hexahedra).
    fn get(&self, name: &str, i: usize) -> Option<VolumeFigure> {
        self.rows.iter().find(|r| r.0 == name).map(|r| r.1[i])
    }
}

/// The 3D passes on rand3D and on a valid block of hexahedra: one sweep
/// (`VolumeSmoother::sweep`, no statistics), median of a few on fresh copies.
fn measure_volume(quick: bool) -> VolumeReport {
    use smoothlab::generate::{hex_grid, perturb_volume, rand3d, HexBlock, RAND3D_POINTS};
    let tet = rand3d(RAND3D_POINTS, RAND3D_SEED).expect("rand3d");
    let tet_words = format!(
        "Freitag's rand3D (`rand3d({RAND3D_POINTS}, {RAND3D_SEED})`, as the criterion bench): {} nodes, {} tetrahedra",
        tet.node_count(),
        tet.element_count()
    );
    let block = hex_grid(&HexBlock::cube(HEX_CELLS)).expect("a block of hexahedra");
    let hex = perturb_volume(&block, HEX_AMOUNT, 1).expect("perturbed");
    assert_eq!(volume_stats(&hex).inverted, 0, "the perturbed block of hexahedra is valid");
    let hex_words = format!(
        "a block of hexahedra (`hex_grid(&HexBlock::cube({HEX_CELLS}))`, every free node moved by up to {HEX_AMOUNT} mean edge lengths by `perturb_volume`, seed 1; every hexahedron valid): {} nodes, {} hexahedra",
        hex.node_count(),
        hex.element_count()
    );
    let meshes = [VolumeBench::new(tet_words, tet), VolumeBench::new(hex_words, hex)];
    let reps = if quick { 3 } else { 21 };
    let rows = VOLUME_PASSES
        .iter()
        .map(|&(name, strategy, kind, order, max_iter)| {
            let obj = tet_objective(kind).expect("a form on tetrahedra");
            let o = SmoothOptions::default().with_strategy(strategy).with_order(order).with_max_iter(max_iter);
            let mut smoothers = [0, 1].map(|_| VolumeSmoother::new(o).expect("options"));
            // the two meshes' passes alternate, so that both see the machine as it is (the
            // ratio of their medians is what the target reads); per free node, the visits
            // kept apart
            let (mut ns, mut visits) = ([Vec::new(), Vec::new()], [0; 2]);
            for _ in 0..reps {
                for (i, s) in smoothers.iter_mut().enumerate() {
                    let mut m = meshes[i].mesh.clone();
                    let t = Instant::now();
                    visits[i] = s.sweep(&mut m, &*obj).visits;
                    ns[i].push(t.elapsed().as_nanos() as f64 / meshes[i].free.max(1) as f64);
                }
            }
            let figures = [0, 1].map(|i| {
                let (b, ns) = (&meshes[i], median(std::mem::take(&mut ns[i])));
                VolumeFigure {
                    ns_per_node: ns,
                    visits_per_node: visits[i] as f64 / b.free.max(1) as f64,
                    ns_per_corner: ns / b.corners_per_node(),
                }
            });
            (name, figures)
        })
        .collect();
    VolumeReport { meshes, reps, rows }
}

fn volume_section(v: &VolumeReport) -> String {
    let mut w = String::new();
    let [tet, hex] = &v.meshes;
    let _ = writeln!(w, "## Tetrahedra and hexahedra, ns per free node and pass (issue 33)\n");
    let _ = writeln!(
        w,
        "The 3D passes on {} ({} free nodes, {:.1} measured corners per free node), and on {} ({} free nodes, {:.1} measured corners per free node). \
         A pass is one sweep over the free nodes (`VolumeSmoother::sweep`, no statistics), the median of {} passes each on a fresh copy of the mesh, the two meshes' passes alternating (so that both see the machine in the same state: their ratio is what the target reads), \
         per **free node** (the visits per free node beside it: `rules` in priority order visits a poor node up to once per bin). \
         *Per corner* divides by the measured corners of the node's star (`CornerStar::tets`, what the kernels evaluate): a tetrahedron is one corner, its free node's; \
         a hexahedron gives every corner whose corner tetrahedron (the corner and its three edge neighbours) holds the free node, its own and its three \
         edge neighbours', so 4. Issue 33's target: the same kernels serve the hexahedra, which must not be slower per corner than tetrahedra (hex / tet ≤ 1).\n",
        tet.what,
        tet.free,
        tet.corners_per_node(),
        hex.what,
        hex.free,
        hex.corners_per_node(),
        v.reps
    );
    let _ = writeln!(w, "| pass | rand3D per free node | visits per free node | per corner | hexahedra per free node | visits per free node | per corner | hex / tet per corner (target ≤ 1) |");
    let _ = writeln!(w, "|---|---:|---:|---:|---:|---:|---:|---:|");
    for (name, [t, h]) in &v.rows {
        let ratio = h.ns_per_corner / t.ns_per_corner;
        let _ = writeln!(
            w,
            "| {name} | {} | {:.2} | {} | {} | {:.2} | {} | {ratio:.2} {} |",
            fmt_ns(t.ns_per_node),
            t.visits_per_node,
            fmt_ns(t.ns_per_corner),
            fmt_ns(h.ns_per_node),
            h.visits_per_node,
            fmt_ns(h.ns_per_corner),
            if ratio <= 1.0 { "✓" } else { "✗" }
        );
    }
    let _ = writeln!(w, "\nFigures in ns unless marked µs. The criterion benches of the same passes: `cargo bench -- volume` (`benches/smoothing.rs`).\n");
    w
}

// ---- time to quality ------------------------------------------------------------------

/// The release binary `smoothlab` beside this program (`target/release/smoothlab` for
/// `target/release/examples/perf`), which `make performance` builds first.
fn smoothlab_binary() -> Option<std::path::PathBuf> {
    let exe = std::env::current_exe().ok()?;
    let bin = exe.parent()?.parent()?.join(format!("smoothlab{}", std::env::consts::EXE_SUFFIX));
    bin.is_file().then_some(bin)
}

/// The passes to try before saying a mesh is not untangled, as the reproduction's.
const MAX_PASSES_TO_VALID: u32 = 10;

/// One run of `smoothlab smooth IN -o OUT --passes N --json`: each pass's inverted count
/// after it, the smoothing time it reports (`time_ms`) and the process's wall time.
struct CliRun {
    inverted: Vec<u64>,
    time_ms: f64,
    wall_ms: f64,
}

fn cli_smooth(bin: &std::path::Path, input: &std::path::Path, out: &std::path::Path, passes: u32) -> Result<CliRun, String> {
    let t = Instant::now();
    let o = std::process::Command::new(bin)
        .arg("smooth")
        .arg(input)
        .arg("-o")
        .arg(out)
        .args(["--passes", &passes.to_string(), "--json"])
        .output()
        .map_err(|e| e.to_string())?;
    let wall_ms = t.elapsed().as_secs_f64() * 1e3;
    if !o.status.success() {
        return Err(String::from_utf8_lossy(&o.stderr).trim().to_string());
    }
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).map_err(|e| e.to_string())?;
    let inverted = v["passes"].as_array().into_iter().flatten().map(|p| p["inverted"].as_u64().unwrap_or(u64::MAX)).collect();
    Ok(CliRun { inverted, time_ms: v["time_ms"].as_f64().unwrap_or(f64::NAN), wall_ms })
}

/// A mesh's time to quality with the CLI's defaults.
struct ToValid {
    inverted0: usize,
    /// Passes to 0 inverted (0: valid as read), or `None` when not within
    /// [`MAX_PASSES_TO_VALID`], with what is left.
    passes: Option<u32>,
    left: u64,
    /// Median wall time of `smoothlab smooth --passes K` and the smoothing time it reports, ms.
    wall_ms: f64,
    smoothing_ms: f64,
}

/// The passes the defaults take to 0 inverted, then `smoothlab smooth --passes K` timed
/// `reps` times. K is found by runs of [`PROBE_PASSES`] passes in turn (each run's `--json`
/// gives every pass's inverted count, so a run of N passes finds any K ≤ N); the run that
/// found K counts as one of the timed runs when it ran K passes.
fn time_to_valid(bin: &std::path::Path, input: &std::path::Path, dir: &std::path::Path, inverted0: usize, reps: usize) -> Result<ToValid, String> {
    let ext = input.extension().map(|e| e.to_string_lossy().into_owned()).unwrap_or_else(|| "vtk".into());
    let out = dir.join(format!("smoothed.{ext}"));
    let (mut runs, mut passes, mut left) = (Vec::new(), None, 0);
    for n in PROBE_PASSES {
        let run = cli_smooth(bin, input, &out, n)?;
        left = run.inverted.last().copied().unwrap_or(0);
        passes = if inverted0 == 0 { Some(0) } else { run.inverted.iter().position(|&i| i == 0).map(|k| k as u32 + 1) };
        if passes.is_some_and(|k| k.max(1) == n) || (passes.is_none() && n == MAX_PASSES_TO_VALID) {
            runs.push(run);
        }
        if passes.is_some() {
            break;
        }
    }
    let timed = passes.unwrap_or(MAX_PASSES_TO_VALID).max(1);
    while runs.len() < reps {
        runs.push(cli_smooth(bin, input, &out, timed)?);
    }
    Ok(ToValid {
        inverted0,
        passes,
        left,
        wall_ms: median(runs.iter().map(|r| r.wall_ms).collect()),
        smoothing_ms: median(runs.iter().map(|r| r.time_ms).collect()),
    })
}

/// The runs that look for the passes to 0 inverted, in turn: 1, 2, the CLI's default 3,
/// then [`MAX_PASSES_TO_VALID`].
const PROBE_PASSES: [u32; 4] = [1, 2, 3, MAX_PASSES_TO_VALID];

fn fmt_ratio(x: f64) -> String {
    if x >= 10.0 {
        format!("{x:.0}")
    } else if x >= 1.0 {
        format!("{x:.1}")
    } else {
        format!("{x:.2}")
    }
}

fn fmt_ms(ms: f64) -> String {
    if ms >= 1000.0 {
        format!("{:.2} s", ms / 1000.0)
    } else if ms >= 10.0 {
        format!("{ms:.0} ms")
    } else {
        format!("{ms:.1} ms")
    }
}

fn fmt_passes(t: &ToValid) -> String {
    match t.passes {
        Some(0) => "valid as read".into(),
        Some(k) => k.to_string(),
        None => format!("not in {MAX_PASSES_TO_VALID} ({} left)", t.left),
    }
}

/// The tangled plates of the reproduction (`docs/reproduction.md` §2): kind, order.
const TANGLED_PLATES: [(&str, PlateKind, u8); 6] = [
    ("triangles", PlateKind::Tri, 1),
    ("quads", PlateKind::Quad, 1),
    ("mixed", PlateKind::Mixed, 1),
    ("triangles, order 2", PlateKind::Tri, 2),
    ("quads, order 2", PlateKind::Quad, 2),
    ("mixed, order 2", PlateKind::Mixed, 2),
];
/// Their perturbation amounts and seeds (§2's: 150 plates).
const PLATE_AMOUNTS: [f64; 5] = [0.6, 0.8, 1.0, 1.25, 1.5];
const PLATE_SEEDS: [u64; 5] = [1, 2, 3, 4, 5];

/// Mesquite's meshes, read in place beside the crate (as `examples/reproduce.rs` and the tests).
fn mesquite_dir(name: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/meshes").join(name)
}

/// The `.vtk` files of `root/group/tangled` for each group, sorted, as `group/tangled/NAME`.
fn tangled_files(root: &std::path::Path, groups: &[&str]) -> Vec<(String, std::path::PathBuf)> {
    let mut files = Vec::new();
    for group in groups {
        let Ok(rd) = std::fs::read_dir(root.join(group).join("tangled")) else { continue };
        let mut names: Vec<std::path::PathBuf> =
            rd.filter_map(|e| e.ok().map(|e| e.path())).filter(|p| p.extension().is_some_and(|e| e == "vtk")).collect();
        names.sort();
        for p in names {
            files.push((format!("{group}/tangled/{}", p.file_name().unwrap_or_default().to_string_lossy()), p));
        }
    }
    files
}

/// Mesquite's ShapeImprover on `pave1.e.vtk` (`../shared/meshes/README.md`: 56 → 0
/// inverted in 5.4 s), and issue 33's target: 10× below it.
const PAVE1_MESQUITE_S: f64 = 5.4;

/// The time-to-quality rows: (family or file, mesh words, its figures), and pave1's wall time.
struct QualityReport {
    text: String,
    pave1_ms: Option<f64>,
    /// (meshes reaching 0 inverted, meshes, most passes taken)
    reached: (usize, usize, u32),
}

fn time_to_quality(quick: bool) -> QualityReport {
    use smoothlab::generate::{perturb, plate};
    let mut w = String::new();
    let mut reached = (0usize, 0usize, 0u32);
    let mut pave1_ms = None;
    let _ = writeln!(w, "## Time to quality (issue 33)\n");
    let Some(bin) = smoothlab_binary() else {
        let _ = writeln!(
            w,
            "Not measured in this run: the release binary `smoothlab` was not found beside this program (`make performance` builds it first: `cargo build --release --features parallel --bin smoothlab`).\n"
        );
        return QualityReport { text: w, pave1_ms, reached };
    };
    let reps = if quick { 1 } else { 3 };
    let _ = writeln!(
        w,
        "The user's figure: the wall time of `smoothlab smooth IN -o OUT --passes K`, the release binary run by this program as a child process \
         with every other option the default (`rules` with `new`, priority order; the whole command: reading, the K passes with their statistics, writing), \
         where K is the number of passes the defaults take to 0 inverted elements, found by runs of {} passes with `--json` in turn \
         (whose records give each pass's inverted count; a mesh valid as read is timed for 1 pass). *Smoothing* is the passes' own time as the command \
         reports it (`time_ms`, the passes' statistics included). Median of {reps} run(s) of each mesh.\n",
        PROBE_PASSES.map(|n| n.to_string()).join(", then ")
    );
    // the meshes tangled at start (some files of the tangled folders are valid as read)
    let record = |reached: &mut (usize, usize, u32), t: &ToValid| {
        if t.inverted0 == 0 {
            return;
        }
        reached.1 += 1;
        if let Some(k) = t.passes {
            reached.0 += 1;
            reached.2 = reached.2.max(k);
        }
    };
    let dir = std::env::temp_dir().join(format!("smoothlab-perf-quality-{}", std::process::id()));
    let _ = std::fs::create_dir_all(&dir);
    // the tangled plates of the reproduction, generated and written as .msh
    let _ = writeln!(
        w,
        "**Tangled plates** (`docs/reproduction.md` §2: `plate(kind, order, 4)`, every interior node moved by `perturb` by {} mean edge lengths, seeds {}: {} plates of each kind), each run once:\n",
        PLATE_AMOUNTS.map(|a| a.to_string()).join(", "),
        PLATE_SEEDS.map(|s| s.to_string()).join(", "),
        PLATE_AMOUNTS.len() * PLATE_SEEDS.len()
    );
    let _ = writeln!(w, "| plates | nodes | inverted at start | passes to 0: most (plates untangled) | wall time: median / largest | smoothing: median / largest |");
    let _ = writeln!(w, "|---|---:|---:|---:|---:|---:|");
    for (name, kind, order) in TANGLED_PLATES {
        let base = plate(kind, order, 4).expect("a plate");
        let mut runs = Vec::new();
        for amount in PLATE_AMOUNTS {
            for seed in PLATE_SEEDS {
                let m = perturb(&base, amount, seed).expect("perturbed");
                let file = dir.join("plate.msh");
                smoothlab::io::write_path(&m, &file, &smoothlab::io::WriteOptions::default()).expect("write a plate");
                match time_to_valid(&bin, &file, &dir, mesh_stats(&m).inverted, 1) {
                    Ok(t) => runs.push(t),
                    Err(e) => eprintln!("perf: smoothlab smooth on a {name} plate: {e}"),
                }
            }
        }
        runs.iter().for_each(|t| record(&mut reached, t));
        let inv: Vec<usize> = runs.iter().map(|t| t.inverted0).collect();
        let most = runs.iter().filter_map(|t| t.passes).max().unwrap_or(0);
        let done = runs.iter().filter(|t| t.passes.is_some()).count();
        let wall: Vec<f64> = runs.iter().map(|t| t.wall_ms).collect();
        let sm: Vec<f64> = runs.iter().map(|t| t.smoothing_ms).collect();
        let max = |v: &[f64]| v.iter().copied().fold(f64::NAN, f64::max);
        let _ = writeln!(
            w,
            "| {name} | {} | {}–{} | {most} ({done} of {}) | {} / {} | {} / {} |",
            base.node_count(),
            inv.iter().min().unwrap_or(&0),
            inv.iter().max().unwrap_or(&0),
            runs.len(),
            fmt_ms(median(wall.clone())),
            fmt_ms(max(&wall)),
            fmt_ms(median(sm.clone())),
            fmt_ms(max(&sm))
        );
    }
    // Mesquite's tangled files
    for (folder, groups, what) in [
        ("mesquite", &["tris", "quads", "mixed"][..], "Mesquite's tangled planar files"),
        ("mesquite3d", &["hexes", "mixed"][..], "Mesquite's tangled 3D files (hexahedra; a mixed mesh)"),
    ] {
        let root = mesquite_dir(folder);
        let _ = writeln!(w, "\n**{what}** (`../shared/meshes/{folder}`, every `.vtk` of its `*/tangled` folders, read with their `fixed` flags):\n");
        if !root.is_dir() {
            let _ = writeln!(w, "*Not measured: the external Mesquite meshes (`../shared/meshes/{folder}`) were not found.*");
            continue;
        }
        let _ = writeln!(w, "| file | nodes | elements | inverted at start | passes to 0 | wall time | smoothing |");
        let _ = writeln!(w, "|---|---:|---:|---:|---:|---:|---:|");
        for (name, path) in tangled_files(&root, groups) {
            let model = match smoothlab::io::read_model_path(&path) {
                Ok(m) => m,
                Err(e) => {
                    let _ = writeln!(w, "| `{name}` | cannot be read: {e} | | | | | |");
                    continue;
                }
            };
            let (nodes, elements) = match &model {
                Model::Planar(m) => (m.node_count(), m.element_count()),
                Model::Surface(s) => (s.flat().node_count(), s.flat().element_count()),
                Model::Volume(v) => (v.node_count(), v.element_count()),
            };
            eprintln!("perf: time to quality, {name} …");
            match time_to_valid(&bin, &path, &dir, model.stats().inverted, reps) {
                Ok(t) => {
                    record(&mut reached, &t);
                    if name.ends_with("pave1.e.vtk") && t.passes.is_some() {
                        pave1_ms = Some(t.wall_ms);
                    }
                    let _ = writeln!(
                        w,
                        "| `{name}` | {nodes} | {elements} | {} | {} | {} | {} |",
                        t.inverted0,
                        fmt_passes(&t),
                        fmt_ms(t.wall_ms),
                        fmt_ms(t.smoothing_ms)
                    );
                }
                Err(e) => {
                    let _ = writeln!(w, "| `{name}` | {nodes} | {elements} | `smoothlab smooth` failed: {e} | | | |");
                }
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    let _ = writeln!(
        w,
        "\n{} of the {} meshes tangled at start end with 0 inverted with the defaults, in at most {} pass(es). Issue 33's target on hexahedra: below Mesquite's ShapeImprover's \
         {PAVE1_MESQUITE_S} s on `pave1` by 10×, ≤ {:.2} s: {}.\n",
        reached.0,
        reached.1,
        reached.2,
        PAVE1_MESQUITE_S / 10.0,
        match pave1_ms {
            Some(ms) => format!("{} {}", fmt_ms(ms), target_mark(ms / 1e3, PAVE1_MESQUITE_S / 10.0)),
            None => "not measured (the file was not found or not untangled)".into(),
        }
    );
    QualityReport { text: w, pave1_ms, reached }
}

/// ✓, or ✗ and by how much the figure misses an upper bound.
fn target_mark(got: f64, limit: f64) -> String {
    if got.is_nan() {
        "not measured".into()
    } else if got <= limit {
        "✓".into()
    } else {
        format!("✗ ({:.2}× the target)", got / limit)
    }
}

// ---- versus Mesquite and the targets ---------------------------------------------------

/// The planar mesh of the comparisons: rand2d of 100k nodes, Hilbert order (the wasm
/// bench's size).
const PLANAR_NODES: usize = 100_000;

/// The pairs of issue 33's table: (pair, smoothlab's planar pass, its 3D pass, the issue's
/// ratio in 2D, in 3D), ratio = Mesquite's time / smoothlab's, measured before this work.
const MESQUITE_PAIRS: [(&str, &str, Option<&str>, &str, &str); 8] = [
    ("Laplace (same algorithm, equal output)", "laplace", Some("laplace"), "39–62×", "130–174×"),
    ("smart Laplace", "smart", Some("smart"), "5.2–12.4×", "3.2–3.7×"),
    ("`new` 3 it vs FeasibleNewton 3 it (mean ratio)", "opt+new", Some("opt+new"), "4.1–4.8×", "1.0–1.1×"),
    ("`rules` (the default) vs FeasibleNewton", RULES_PRIORITY, Some("rules+new, priority order"), "1.8–2.4×", "0.3–0.6×"),
    ("`condition` 3 it vs Mesquite's CG on Σ(1/α)²", "opt+condition", Some("opt+condition"), "1.2–1.6×", "2.1–2.2×"),
    ("`old` vs NonSmoothDescent, both capped at 20 iterations", "opt+old, 20 it", Some("opt+old, 20 it"), "0.6–0.9×", "0.5–0.9×"),
    ("`sine` 20 it vs NonSmoothDescent on max-min sine", "opt+sine, 20 it", None, "0.7–1.1×", "—"),
    ("`untangle` vs UntangleWrapper's body", "opt+untangle", Some("opt+untangle"), "0.7–1.7×", "8–11×"),
];

/// The planar passes the issue-33 sections read (the wasm bench's and the pairs' and the
/// targets'), for a run that measures those alone (`--issue33`).
const ISSUE33_PLANAR: [&str; 11] = [
    "laplace",
    "smart",
    "opt+new",
    "opt+old",
    "opt+old, 20 it",
    "opt+sine",
    "opt+sine, 20 it",
    "opt+condition",
    "opt+untangle",
    "rules+new",
    RULES_PRIORITY,
];

/// The passes `names` of [`PASSES`] alone on the planar mesh of `n` nodes, both orders (the
/// rest of the report left empty).
fn measure_rows(n: usize, names: &[&str], quick: bool) -> SizeReport {
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

/// Issue 33's speed-ups measured before and after in one run by `scripts/before_after.py`
/// (`make performance`): the CLI of the issue's day (a base commit) and this tree's, one pass
/// of each target on the same file, alternating, the median of a few runs of the pass's own
/// time; rows by target, `"{2D|3D|hexahedra} {pass}"`.
struct BeforeAfter {
    base: String,
    reps: u64,
    /// (target, mesh, options, before ms, after ms, runs of each binary)
    rows: Vec<(String, String, String, f64, f64, u64)>,
}

impl BeforeAfter {
    fn read(path: Option<&str>) -> Self {
        let v = read_json(path).unwrap_or(serde_json::Value::Null);
        let text = |r: &serde_json::Value, k: &str| r[k].as_str().unwrap_or("?").to_string();
        let rows = v["rows"]
            .as_array()
            .into_iter()
            .flatten()
            .filter_map(|r| {
                let runs = r["runs"].as_u64().unwrap_or(v["reps"].as_u64().unwrap_or(0));
                Some((text(r, "target"), text(r, "mesh"), text(r, "options"), r["before_ms"].as_f64()?, r["after_ms"].as_f64()?, runs))
            })
            .collect();
        BeforeAfter { base: v["base"].as_str().unwrap_or("?").to_string(), reps: v["reps"].as_u64().unwrap_or(0), rows }
    }
    /// Before / after of `pass` in `dim` (2D, 3D, hexahedra), when measured.
    fn speedup(&self, dim: &str, pass: &str) -> Option<f64> {
        let name = format!("{dim} {pass}");
        self.rows.iter().find(|r| r.0 == name).map(|r| r.3 / r.4)
    }
    /// The table of every measured target.
    fn table(&self) -> String {
        let mut w = String::new();
        if self.rows.is_empty() {
            let _ = writeln!(w, "Before and after in one run: not measured (no `--before-after` file: `scripts/before_after.py` writes it).\n");
            return w;
        }
        let _ = writeln!(
            w,
            "Before and after in one run (`scripts/before_after.py`, which `make performance` runs first): the `smoothlab` CLI of the issue's day \
             (commit {}, built beside this tree) and this tree's, `smoothlab smooth MESH --passes 1 --json OPTIONS`, one pass of each target on the \
             same file, the two binaries alternating, the median of the runs of each (at least {}, and for a short pass about a second of \
             this tree's time in all, at most 25: a few runs of a pass of some milliseconds on a shared machine are mostly noise) of the \
             pass's own time (`elapsed_ms`: the node loop, without reading, writing or statistics):\n",
            self.base, self.reps
        );
        let _ = writeln!(w, "| target | mesh | options | runs | before | after | speed-up |");
        let _ = writeln!(w, "|---|---|---|---:|---:|---:|---:|");
        for (t, mesh, options, b, a, runs) in &self.rows {
            let _ = writeln!(w, "| {t} | {mesh} | `{options}` | {runs} | {} | {} | {:.2}× |", fmt_ms(*b), fmt_ms(*a), b / a);
        }
        w.push('\n');
        w
    }
}

/// smoothlab's figure of `pass` in this run: 2D on rand2d 100k Hilbert, 3D on rand3D.
fn this_run(planar: Option<&SizeReport>, volume: &VolumeReport, dim: &str, pass: &str) -> Option<f64> {
    if dim == "3D" {
        volume.get(pass, 0).map(|f| f.ns_per_node)
    } else {
        planar?.rows.iter().find(|r| r.0 == pass).map(|r| r.2)
    }
}

fn versus_mesquite(planar: Option<&SizeReport>, volume: &VolumeReport, before_after: &BeforeAfter) -> String {
    let mut w = String::new();
    let _ = writeln!(w, "## Versus Mesquite (issue 33)\n");
    let _ = writeln!(
        w,
        "**ratio = Mesquite's time per free node and pass / smoothlab's time per free node and pass**, both on the same mesh, on the same \
         machine, one process at a time (> 1: smoothlab faster). Mesquite is not built by this project (its code is not committed), so \
         `make performance` does not re-measure Mesquite's half: the ratios below are issue 33's, measured before this work (Mesquite \
         built -O3, on its own meshes and smoothlab's), and smoothlab's half is this run's: 2D on rand2d of {PLANAR_NODES} nodes in Hilbert \
         order (the planar table above), 3D on rand3D (the 3D section). Where smoothlab's speed-up since that day was measured (before and \
         after in one run, the targets section below), *estimate now* is the issue's ratio times that speed-up: an estimate (Mesquite's \
         half not re-measured, smoothlab's speed-up measured on its own meshes), not a measurement.\n"
    );
    let _ = writeln!(w, "| pair | smoothlab 2D | issue's ratio 2D | estimate now 2D | smoothlab 3D | issue's ratio 3D | estimate now 3D |");
    let _ = writeln!(w, "|---|---:|---:|---:|---:|---:|---:|");
    let scaled = |ratio: &str, dim: &str, pass: &str| -> String {
        let Some(s) = before_after.speedup(dim, pass) else { return "—".into() };
        let parts: Vec<f64> = ratio.trim_end_matches('×').split('–').filter_map(|x| x.parse().ok()).collect();
        match parts.as_slice() {
            [a, b] => format!("{}–{}×", fmt_ratio(a * s), fmt_ratio(b * s)),
            [a] => format!("{}×", fmt_ratio(a * s)),
            _ => "—".into(),
        }
    };
    let ns = |v: Option<f64>| v.map_or("not measured".to_string(), fmt_ns);
    for (pair, p2, p3, r2, r3) in MESQUITE_PAIRS {
        let n2 = this_run(planar, volume, "2D", p2);
        let n3 = p3.and_then(|p| this_run(planar, volume, "3D", p));
        let _ = writeln!(
            w,
            "| {pair} | {} | {r2} | {} | {} | {r3} | {} |",
            ns(n2),
            scaled(r2, "2D", p2),
            if p3.is_some() { ns(n3) } else { "—".into() },
            p3.map_or("—".into(), |p| scaled(r3, "3D", p))
        );
    }
    let _ = writeln!(
        w,
        "\nFigures in ns unless marked µs. smoothlab's passes: the rows of the same names above (`rules` in priority order, as the default and as \
         the CLI runs it, per free node). Peak memory at 1M planar nodes (issue 33, before this work): smoothlab 199 MB, Mesquite 311 MB; \
         smoothlab's figures of this run are in the memory section.\n"
    );
    w
}

/// Measures natively the passes of the bench page's JSON at `path` (`tests/browser/bench.mjs`'s
/// output) on the same mesh and numbering, and writes each pass's figure into that JSON
/// (`native_ns_per_visit`, read by [`wasm_rows`]). `make performance` runs it straight
/// after the bench page, so a wasm / native ratio compares two figures of the same minute
/// on a shared machine rather than of minutes apart (the same binaries' ratios moved by
/// some 0.5 between runs when the native half came from the planar table).
fn native_peers(path: &str) {
    let mut v = read_json(Some(path)).unwrap_or_else(|| panic!("cannot read the bench page's JSON {path}"));
    let nodes = v["nodes"].as_u64().unwrap_or(0) as usize;
    let mut names: Vec<String> = Vec::new();
    for row in v["passes"].as_array().into_iter().flatten() {
        let name = row["name"].as_str().unwrap_or("?").to_string();
        if !names.contains(&name) {
            names.push(name);
        }
    }
    let refs: Vec<&str> = names.iter().map(String::as_str).collect();
    eprintln!("perf: the bench page's passes natively, {nodes} nodes …");
    let report = measure_rows(nodes, &refs, false);
    assert_eq!(report.nodes, nodes, "the native mesh is the bench page's");
    for row in v["passes"].as_array_mut().into_iter().flatten() {
        let name = row["name"].as_str().unwrap_or("?").to_string();
        let hilbert = row["hilbert"].as_bool().unwrap_or(false);
        if let Some((a, b)) = native(std::slice::from_ref(&report), nodes, &name) {
            row["native_ns_per_visit"] = serde_json::json!(if hilbert { b } else { a });
        }
    }
    let text = serde_json::to_string_pretty(&v).expect("json");
    std::fs::write(path, text).unwrap_or_else(|e| panic!("cannot write {path}: {e}"));
}

/// The bench page's rows: (pass, Hilbert order, wasm ns/visit, native ns/visit): the
/// native figure measured beside the page ([`native_peers`]) when there is one, else this
/// run's planar table's.
fn wasm_rows(v: &serde_json::Value, reports: &[SizeReport]) -> Vec<(String, bool, f64, Option<f64>)> {
    let nodes = v["nodes"].as_u64().unwrap_or(0) as usize;
    v["passes"]
        .as_array()
        .into_iter()
        .flatten()
        .map(|row| {
            let name = row["name"].as_str().unwrap_or("?").to_string();
            let hilbert = row["hilbert"].as_bool().unwrap_or(false);
            let beside = row["native_ns_per_visit"].as_f64();
            let nat = beside.or_else(|| native(reports, nodes, &name).map(|(a, b)| if hilbert { b } else { a }));
            (name, hilbert, row["ns_per_visit"].as_f64().unwrap_or(f64::NAN), nat)
        })
        .collect()
}

fn read_json(path: Option<&str>) -> Option<serde_json::Value> {
    serde_json::from_str(&std::fs::read_to_string(path?).ok()?).ok()
}

/// Issue 33's targets in one table.
fn issue33_targets(
    reports: &[SizeReport],
    volume: &VolumeReport,
    quality: &QualityReport,
    before_after: &BeforeAfter,
    wasm: Option<&str>,
    page: Option<&str>,
    load: &str,
) -> String {
    let mut w = String::new();
    let _ = writeln!(w, "## Against the targets of issue 33 (performance versus Mesquite)\n");
    w += &before_after.table();
    let _ = writeln!(
        w,
        "Each row below: the figure, then ✓ where it meets the target and ✗ where it does not, with how far. The speed-ups are the table \
         above's (before and after in one run, on this machine: the load average was {load} when this section's 3D passes began); the \
         instructions of the same passes by callgrind are in the *What was tried* bullets.\n"
    );
    let _ = writeln!(w, "| target | before | after | figure | met |");
    let _ = writeln!(w, "|---|---:|---:|---:|---|");
    let speedups: [(&str, &str, &str, f64); 7] = [
        ("3D: `opt`+`new` ≥ 3× faster", "3D", "opt+new", 3.0),
        ("3D: `rules`+`new` (priority order) ≥ 3× faster", "3D", "rules+new, priority order", 3.0),
        ("3D: `old` with 20 iterations ≥ 2× faster", "3D", "opt+old, 20 it", 2.0),
        ("2D: `condition` ≥ 3× faster", "2D", "opt+condition", 3.0),
        ("2D: `old` with 20 iterations ≥ 2× faster per node-pass", "2D", "opt+old, 20 it", 2.0),
        ("2D: `sine` with 20 iterations ≥ 2× faster per node-pass", "2D", "opt+sine, 20 it", 2.0),
        ("2D: `untangle` ≥ 2× faster", "2D", "opt+untangle", 2.0),
    ];
    for (what, dim, pass, target) in speedups {
        let name = format!("{dim} {pass}");
        let cells = match before_after.rows.iter().find(|r| r.0 == name) {
            Some((_, _, _, b, a, _)) => {
                let s = b / a;
                let met = if s >= target { "✓".to_string() } else { format!("✗ ({:.2}× of the {target}×)", s) };
                format!("{} | {} | {s:.2}× | {met}", fmt_ms(*b), fmt_ms(*a))
            }
            None => "not measured | not measured | — | not measured (no `--before-after` file)".to_string(),
        };
        let _ = writeln!(w, "| {what} | {cells} |");
    }
    // hexahedra per corner, the worst of the passes the target names
    let worst = ["opt+new", "rules+new, priority order", "opt+old, 20 it"]
        .iter()
        .filter_map(|&p| Some((p, volume.get(p, 1)?.ns_per_corner / volume.get(p, 0)?.ns_per_corner)))
        .max_by(|a, b| a.1.total_cmp(&b.1));
    if let Some((p, r)) = worst {
        let _ = writeln!(
            w,
            "| 3D: hexahedra not slower per corner than tetrahedra (`opt`+`new`, `rules`+`new`, `old` 20 it; the worst) | — | {r:.2} ({p}) | hex / tet per corner ≤ 1 | {} |",
            target_mark(r, 1.0)
        );
    }
    let (ok, all, most) = quality.reached;
    let _ = writeln!(
        w,
        "| time to quality: the tangled plates and Mesquite's tangled files to 0 inverted with the defaults (reported with the passes) | — | {ok} of the {all} tangled at start, at most {most} pass(es) | the section above | {} |",
        if all == 0 { "not measured" } else if ok == all { "✓" } else { "✗" }
    );
    let _ = writeln!(
        w,
        "| time to quality on `pave1`: below Mesquite's ShapeImprover's {PAVE1_MESQUITE_S} s by 10× | {PAVE1_MESQUITE_S} s (Mesquite) | {} | ≤ {:.2} s | {} |",
        quality.pave1_ms.map_or("not measured".into(), fmt_ms),
        PAVE1_MESQUITE_S / 10.0,
        quality.pave1_ms.map_or("not measured".into(), |ms| target_mark(ms / 1e3, PAVE1_MESQUITE_S / 10.0))
    );
    // wasm: the worst ratio of the browser bench's passes
    let mut wasm_unmet = false;
    match read_json(wasm) {
        Some(v) => {
            let ratios: Vec<(String, f64)> = wasm_rows(&v, reports)
                .into_iter()
                .filter_map(|(n, h, ns, nat)| Some((format!("{n}, {}", if h { "Hilbert" } else { "file order" }), ns / nat?)))
                .collect();
            let worst = ratios.iter().max_by(|a, b| a.1.total_cmp(&b.1));
            wasm_unmet = worst.is_some_and(|(_, r)| *r > WASM_NATIVE_TARGET);
            let _ = writeln!(
                w,
                "| wasm in Chromium ≤ {WASM_NATIVE_TARGET}× native for every strategy | 1.36–2.40× | {} | ≤ {WASM_NATIVE_TARGET} | {} |",
                worst.map_or("not measured".into(), |(n, r)| format!("{r:.2}× at most ({n})")),
                worst.map_or("not measured".into(), |(_, r)| target_mark(*r, WASM_NATIVE_TARGET))
            );
        }
        None => {
            let _ = writeln!(w, "| wasm in Chromium ≤ {WASM_NATIVE_TARGET}× native for every strategy | 1.36–2.40× | not measured (no `--wasm` file) | ≤ {WASM_NATIVE_TARGET} | not measured |");
        }
    }
    let page = read_json(page);
    let gz = page.as_ref().and_then(|v| v["wasm"]["gzip_bytes"].as_f64());
    let _ = writeln!(
        w,
        "| the module no larger gzipped than issue 33's day | {MODULE_GZIP_TARGET} bytes (`docs/performance.md` of 2026-11-24) | {} | ≤ {MODULE_GZIP_TARGET} bytes | {} |",
        gz.map_or("not measured (no `--page` file)".into(), |b| format!("{b:.0} bytes")),
        gz.map_or("not measured".into(), |b| target_mark(b, MODULE_GZIP_TARGET))
    );
    let step = page.as_ref().and_then(|v| v["million"]["default_step"]["wall_ms"].as_f64());
    let _ = writeln!(
        w,
        "| the page: one default Step on the 1M sample ≤ {STEP_1M_TARGET_S} s | 10.0 s (`docs/performance.md` of 2026-11-24) | {} | ≤ {STEP_1M_TARGET_S} s | {} |",
        step.map_or("not measured (no `--page` file)".into(), fmt_ms),
        step.map_or("not measured".into(), |ms| target_mark(ms / 1e3, STEP_1M_TARGET_S))
    );
    let _ = writeln!(w, "\nNo test asserts a time: these figures are measured and reported here only.\n");
    let unmet = [
        (
            wasm_unmet,
            "wasm ≤ 1.3× native: the wasm build runs the native build's kernels (the same code), so each of this issue's speed-ups reached the page too, but V8's code for them is slower throughout a pass rather than at a hot spot (profiled in both builds, each function takes about the same share of the pass), and slowest where a scattered numbering leaves each visit waiting on memory (V8's longer visit keeps fewer loads in flight). The issue's simd128 kernels were tried (the `new` term of two triangles at once, the same bits) and were no faster; so were binaryen's `-O4`, reading ahead in node order and the smart test reading first (*What was tried*, and the WebAssembly section).",
        ),
        (
            gz.is_some_and(|b| b > MODULE_GZIP_TARGET),
            "the module: it grew after the issue's day with the page's features (surfaces, every volume kind, the 3D lab, the tour, the notebook widget; some 826 KB gzipped at its largest), and one sort for the orderings, a lighter font reader and then the font as tables, the tour's tables alone and `wasm-opt`'s flags brought it back to this run's figure. What is left is those features' code. Building for size slows every pass (at `opt-level = \"z\"` 1.2–1.6× in Chromium), and inlining less slows the passes by up to 1.4× (LLVM's inline threshold at 100, in node); leaving features out of the page's module was not done.",
        ),
        (
            step.is_some_and(|ms| ms / 1e3 > STEP_1M_TARGET_S),
            "the 1M Step: both sides in Chen's worst-first order, in one worker (two workers would each hold the 1M mesh, which takes the page past its 400 MiB), each side's time being its visits (some 1.6M a side) at wasm's cost a visit; the two sides in two workers would still take the longer side's smoothing (the 1M section below gives each side's).",
        ),
    ];
    if unmet.iter().any(|(u, _)| *u) {
        let _ = writeln!(w, "What stands in the way of the rows not met, in brief (every attempt, with its figures, is in *What was tried* above and in the WebAssembly and page sections):\n");
        for (_, why) in unmet.iter().filter(|(u, _)| *u) {
            let _ = writeln!(w, "- {why}");
        }
        let _ = writeln!(w);
    }
    w
}

/// Issue 33's sections: the 3D passes, the time to quality, versus Mesquite and the targets
/// (the planar figures from `reports`, the 100k one).
fn issue33_sections(reports: &[SizeReport], quick: bool, wasm: Option<&str>, page: Option<&str>, before_after: Option<&str>) -> String {
    let before_after = BeforeAfter::read(before_after);
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    let load = load.split_whitespace().take(3).collect::<Vec<_>>().join(" ");
    eprintln!("perf: tetrahedra and hexahedra …");
    let volume = measure_volume(quick);
    eprintln!("perf: time to quality …");
    let quality = time_to_quality(quick);
    let planar = reports.iter().find(|r| r.nodes == PLANAR_NODES);
    volume_section(&volume)
        + &quality.text
        + &versus_mesquite(planar, &volume, &before_after)
        + &issue33_targets(reports, &volume, &quality, &before_after, wasm, page, &load)
}
