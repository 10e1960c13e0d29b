//! Criterion benchmarks of one smoothing pass on Freitag's rand2d meshes of 10k, 100k and
//! 1M nodes (generated, not stored), in Hilbert node order, with throughput in node
//! visits: Laplacian, smart Laplacian, `opt` with each objective, `rules` with `new`, the
//! bandwidth bound (a sweep that only streams the arrays a Laplacian pass reads), the
//! level-set sampling of one node (100 × 100 objective values), a coloured pass, a pass
//! over a tangled surface mesh, the 3D passes on rand3D and on a block of hexahedra, and
//! drawing the mesh (`render::render_mesh`, 1024 × 1024), and passes against the input
//! target beside the ideal.
//!
//! `cargo bench` runs them all (several minutes); `cargo bench -- 10k` only the small mesh.
//! At 1M nodes only the cheap passes (stream, Laplacian, smart) and `opt`/`rules` with
//! `new` run, to keep the run bounded. `examples/perf.rs` makes the tables of
//! `docs/performance.md` from the same passes.

use std::time::Duration;

use criterion::{criterion_group, criterion_main, BatchSize, BenchmarkId, Criterion, Throughput};
use glam::DVec2;
use smoothlab::generate::rand2d;
use smoothlab::mesh::Mesh;
use smoothlab::objective::{objective, objective_with, ObjectiveKind, Penalty, Star};
use smoothlab::smooth::parallel::ColouredSmoother;
use smoothlab::smooth::{Order, SmoothOptions, Smoother, Strategy};

/// rand2d with `n` nodes (as `examples/perf.rs`: √n per side, seed 2003), Hilbert order.
fn bench_mesh(n: usize) -> Mesh {
    let per_side = ((n as f64).sqrt() as usize).max(1);
    rand2d(n - 4 * per_side, per_side, 2003).expect("rand2d").renumbered_spatially().0
}

/// The Laplacian's memory traffic without its work: free flags, CSR neighbours, positions.
fn stream_bound(mesh: &mut Mesh) -> u32 {
    let mut visits = 0;
    for i in 0..mesh.node_count() {
        if mesh.fixed()[i] {
            continue;
        }
        let nb = mesh.topology().neighbours(i);
        let mut s = DVec2::ZERO;
        for &j in nb {
            s += mesh.nodes()[j as usize];
        }
        mesh.nodes_mut()[i] = s / nb.len() as f64;
        visits += 1;
    }
    visits
}

/// The passes benched: a name, the strategy, the objective (with the design of `new`'s
/// penalty) and the node order.
type Pass = (&'static str, Strategy, ObjectiveKind, Penalty, Order);

fn passes(large: bool) -> Vec<Pass> {
    let new = |name, strategy, order| (name, strategy, ObjectiveKind::SmoothShape, Penalty::Barrier, order);
    let mut v = vec![new("laplace", Strategy::Laplace, Order::Input), new("smart", Strategy::Smart, Order::Input)];
    if large {
        v.push(new("opt+new", Strategy::Opt, Order::Input));
    } else {
        for k in ObjectiveKind::ALL {
            v.push((Box::leak(format!("opt+{k}").into_boxed_str()), Strategy::Opt, k, Penalty::Barrier, Order::Input));
        }
        // the first design of the new objective's penalty, for the comparison of the two
        v.push(("opt+new (angle penalty)", Strategy::Opt, ObjectiveKind::SmoothShape, Penalty::Angle, Order::Input));
        // Freitag's combined schemes, with her objective
        for (name, strategy) in [("c1+sine", Strategy::C1), ("c2+sine", Strategy::C2), ("c3+sine", Strategy::C3)] {
            v.push((name, strategy, ObjectiveKind::Sine, Penalty::Barrier, Order::Input));
        }
    }
    v.push(new("rules+new", Strategy::Rules, Order::Input));
    v.push(new("rules+new, priority", Strategy::Rules, Order::Priority));
    v
}

fn smoothing(c: &mut Criterion) {
    for (label, n) in [("10k", 10_000usize), ("100k", 100_000), ("1M", 1_000_000)] {
        let mesh = bench_mesh(n);
        let free = mesh.free_count() as u64;
        let mut g = c.benchmark_group(format!("pass/{label}"));
        g.sample_size(10).throughput(Throughput::Elements(free));
        g.measurement_time(Duration::from_secs(if n >= 1_000_000 { 20 } else { 5 }));
        g.warm_up_time(Duration::from_millis(500));
        g.bench_function("stream bound", |b| b.iter_batched_ref(|| mesh.clone(), stream_bound, BatchSize::LargeInput));
        for (name, strategy, kind, penalty, order) in passes(n >= 1_000_000) {
            let obj = objective_with(kind, penalty);
            let options = SmoothOptions::default().with_strategy(strategy).with_order(order);
            let mut s = Smoother::new(options).expect("options");
            g.bench_function(name, |b| {
                b.iter_batched_ref(|| mesh.clone(), |m| s.sweep(m, &*obj), BatchSize::LargeInput)
            });
        }
        if n <= 100_000 {
            let obj = objective(ObjectiveKind::SmoothShape);
            let options = SmoothOptions::default().with_strategy(Strategy::Opt);
            let mut s = ColouredSmoother::new(&mesh, options).expect("options");
            g.bench_function(
                BenchmarkId::new(
                    "coloured opt+new",
                    if ColouredSmoother::is_multithreaded() { "parallel" } else { "sequential" },
                ),
                |b| b.iter_batched_ref(|| mesh.clone(), |m| s.sweep(m, &*obj), BatchSize::LargeInput),
            );
        }
        g.finish();
    }
}

/// One pass over a tangled surface (issue 17): a cube-sphere of 3 × 32 × 32 quads, split
/// into triangles every other one, perturbed in its tangent planes, `rules` + `new` and
/// `laplace` — each star flattened into its tangent plane, each move projected back onto
/// the sphere. Throughput in node visits, to read beside the planar passes.
fn surfaces(c: &mut Criterion) {
    use smoothlab::generate::{surface, SurfaceKind, SurfaceShape};
    use smoothlab::generate::perturb_surface;
    use smoothlab::surface::SurfaceSmoother;
    let sample = surface(SurfaceShape::Sphere, SurfaceKind::Mixed, 1, 32).expect("a sample");
    let tangled = perturb_surface(&sample, 0.5, 1).expect("perturbed");
    let mut g = c.benchmark_group("surface pass/sphere 6k");
    g.sample_size(10).throughput(Throughput::Elements(tangled.flat().free_count() as u64));
    g.measurement_time(Duration::from_secs(5));
    for (name, strategy) in [("laplace", Strategy::Laplace), ("rules+new", Strategy::Rules)] {
        let obj = objective(ObjectiveKind::SmoothShape);
        let options = SmoothOptions::default().with_strategy(strategy).with_order(Order::Priority);
        let mut s = SurfaceSmoother::new(options).expect("options");
        g.bench_function(name, |b| {
            b.iter_batched_ref(|| tangled.clone(), |t| s.pass(t, &*obj, &|| 0.0), BatchSize::LargeInput)
        });
    }
    g.finish();
}

/// One pass over Freitag's rand3D (1086 points, about 5900 tetrahedra) with each of her
/// strategies and the new objective with Chen's rules: the planar drivers on tetrahedra;
/// then issue 33's 3D passes (`old` capped at 20 iterations, `condition`, `untangle`) and
/// the same kernels on a valid block of hexahedra (`hexahedra`), as `examples/perf.rs`'s
/// 3D section measures them.
fn tetrahedra(c: &mut Criterion) {
    use smoothlab::generate::{hex_grid, perturb_volume, rand3d, HexBlock, RAND3D_POINTS};
    use smoothlab::objective::solid_objective;
    use smoothlab::volume::{VolumeMesh, VolumeSmoother};
    // name, strategy, objective, solver iterations per call
    let passes = [
        ("laplace", Strategy::Laplace, ObjectiveKind::Sine, 3),
        ("smart", Strategy::Smart, ObjectiveKind::Sine, 3),
        ("opt+sine", Strategy::Opt, ObjectiveKind::Sine, 3),
        ("opt+new", Strategy::Opt, ObjectiveKind::SmoothShape, 3),
        ("rules+new", Strategy::Rules, ObjectiveKind::SmoothShape, 3),
        ("opt+old, 20 it", Strategy::Opt, ObjectiveKind::MaxMinShape, 20),
        ("opt+condition", Strategy::Opt, ObjectiveKind::Condition, 3),
        ("opt+untangle", Strategy::Opt, ObjectiveKind::Untangle, 3),
    ];
    // a 10 × 10 × 10 block (1331 nodes, about rand3D's), free nodes moved by 0.2 mean edge
    // lengths: every hexahedron valid
    let block = perturb_volume(&hex_grid(&HexBlock::cube(10)).expect("hex grid"), 0.2, 1).expect("perturbed");
    let meshes: [(&str, VolumeMesh); 2] =
        [("volume pass/rand3d", rand3d(RAND3D_POINTS, 1).expect("rand3d")), ("volume pass/hexahedra", block)];
    for (group, mesh) in meshes {
        let mut g = c.benchmark_group(group);
        g.sample_size(10).throughput(Throughput::Elements(mesh.free_count() as u64));
        g.measurement_time(Duration::from_secs(5));
        for (name, strategy, kind, max_iter) in passes {
            let obj = solid_objective(kind).expect("a form on tetrahedra");
            // Freitag's strategies in node order, as her table ran them; Chen's rules worst first
            let order = if strategy == Strategy::Rules { Order::Priority } else { Order::Input };
            let options = SmoothOptions::default().with_strategy(strategy).with_order(order).with_max_iter(max_iter);
            let mut s = VolumeSmoother::new(options).expect("options");
            g.bench_function(name, |b| b.iter_batched_ref(|| mesh.clone(), |m| s.sweep(m, &*obj), BatchSize::LargeInput));
        }
        g.finish();
    }
}

/// A pass against the ideal and against a target taken from the mesh (issue 57: the
/// input target costs at most 1.2× the ideal a node pass). The target is a perturbed
/// copy of the mesh, so that every corner is off its target and the solver works as hard
/// as against the ideal (a uniform stretch would not do: every corner equally off is a
/// max-min optimum); rand2d's 10k nodes and a perturbed 10³ block of hexahedra, `opt`
/// with `new`, `condition` and `old`.
fn targets(c: &mut Criterion) {
    use smoothlab::generate::{hex_grid, perturb_volume, HexBlock};
    use smoothlab::objective::solid_objective;
    use smoothlab::volume::VolumeSmoother;
    let kinds = [
        ObjectiveKind::SmoothShape,
        ObjectiveKind::Condition,
        ObjectiveKind::MaxMinShape,
    ];
    let options = SmoothOptions::default().with_strategy(Strategy::Opt);
    let mesh = bench_mesh(10_000);
    let mut targeted = mesh.clone();
    let target = smoothlab::generate::perturb(&mesh, 0.2, 7).expect("perturbed");
    targeted.set_target_nodes(Some(target.nodes().to_vec()));
    let mut g = c.benchmark_group("target pass/10k");
    g.sample_size(10)
        .throughput(Throughput::Elements(mesh.free_count() as u64));
    g.measurement_time(Duration::from_secs(5));
    for kind in kinds {
        let obj = objective(kind);
        for (label, m) in [("ideal", &mesh), ("input", &targeted)] {
            let mut s = Smoother::new(options).expect("options");
            g.bench_function(format!("opt+{kind}, {label}"), |b| {
                b.iter_batched_ref(|| m.clone(), |m| s.sweep(m, &*obj), BatchSize::LargeInput)
            });
        }
    }
    g.finish();
    let block = perturb_volume(&hex_grid(&HexBlock::cube(10)).expect("hex grid"), 0.2, 1)
        .expect("perturbed");
    let mut targeted = block.clone();
    let target = perturb_volume(&block, 0.2, 7).expect("perturbed");
    targeted.set_target_nodes(Some(target.nodes().to_vec()));
    let mut g = c.benchmark_group("target pass/hexahedra");
    g.sample_size(10)
        .throughput(Throughput::Elements(block.free_count() as u64));
    g.measurement_time(Duration::from_secs(5));
    for kind in kinds {
        let obj = solid_objective(kind).expect("a volume objective");
        for (label, m) in [("ideal", &block), ("input", &targeted)] {
            let mut s = VolumeSmoother::new(options).expect("options");
            g.bench_function(format!("opt+{kind}, {label}"), |b| {
                b.iter_batched_ref(|| m.clone(), |m| s.sweep(m, &*obj), BatchSize::LargeInput)
            });
        }
    }
    g.finish();
}

/// The level-set view of one node: its objective sampled on a 100 × 100 grid over its star.
fn level_sets(c: &mut Criterion) {
    let mesh = bench_mesh(10_000);
    let node = (0..mesh.node_count()).find(|&i| mesh.is_free(i)).expect("a free node");
    let mut star = Star::new();
    star.gather(&mesh, node);
    let (mut lo, mut hi) = (star.x0, star.x0);
    for e in &star.elems {
        for p in &e.pts[..e.kind.node_count()] {
            lo = lo.min(*p);
            hi = hi.max(*p);
        }
    }
    let mut g = c.benchmark_group("level set 100x100");
    g.sample_size(10).throughput(Throughput::Elements(10_000));
    for kind in [ObjectiveKind::SmoothShape, ObjectiveKind::MaxMinShape] {
        let obj = objective(kind);
        g.bench_function(kind.name(), |b| {
            b.iter(|| {
                let mut acc = 0.0;
                for j in 0..100 {
                    for i in 0..100 {
                        let x = lo + (hi - lo) * DVec2::new(i as f64 / 99.0, j as f64 / 99.0);
                        acc += obj.value(&star, x);
                    }
                }
                acc
            })
        });
    }
    g.finish();
}

/// Drawing a whole mesh: `render::render_mesh` into a 1024 × 1024 pixmap.
fn rendering(c: &mut Criterion) {
    let mut g = c.benchmark_group("render 1024x1024");
    g.sample_size(10);
    for (label, n) in [("10k", 10_000usize), ("100k", 100_000)] {
        let mesh = bench_mesh(n);
        let mut pixmap = tiny_skia::Pixmap::new(1024, 1024).expect("a pixmap");
        let view = smoothlab_render::MeshView::default();
        g.throughput(Throughput::Elements(mesh.element_count() as u64));
        g.bench_function(label, |b| b.iter(|| smoothlab_render::render_mesh(&mut pixmap, &mesh, &view)));
    }
    g.finish();
}

criterion_group!(benches, smoothing, surfaces, tetrahedra, targets, level_sets, rendering);
criterion_main!(benches);
