use std::cell::Cell;

use glam::DVec2;
use proptest::prelude::prop;
use proptest::prelude::{any, prop_assert, prop_assert_eq, proptest, ProptestConfig};

use super::*;
use crate::mesh::{ElementKind, FixedSpec, MeshBuilder};
use crate::objective::Goal;
use crate::optimize::test_objectives::{hexagon, ShapeMaxMin, ShapeSum};
use crate::optimize::SolverKind;
use crate::quality::{element_quality, mesh_stats};

const NO_CLOCK: &dyn Fn() -> f64 = &|| 0.0;

const ALL: [Strategy; 7] =
    [Strategy::Laplace, Strategy::Smart, Strategy::Opt, Strategy::C1, Strategy::C2, Strategy::C3, Strategy::Rules];

/// A structured grid on integer coordinates (nx × ny cells), interior nodes moved by
/// `jitter` (cycled, in cell units), triangles split along one diagonal, quads, or 6-node
/// triangles with mid-side nodes at the edge midpoints. `extra_fixed` interior nodes (by
/// grid index) are fixed too.
fn grid(nx: usize, ny: usize, kind: ElementKind, jitter: &[(f64, f64)], extra_fixed: &[usize]) -> Mesh {
    let mut b = MeshBuilder::new();
    let id = |i: usize, j: usize| (j * (nx + 1) + i) as u32;
    let mut k = 0;
    let mut coords = Vec::new();
    for j in 0..=ny {
        for i in 0..=nx {
            let (mut x, mut y) = (i as f64, j as f64);
            if i > 0 && i < nx && j > 0 && j < ny && !jitter.is_empty() {
                let (dx, dy) = jitter[k % jitter.len()];
                k += 1;
                x += dx;
                y += dy;
            }
            b.add_node([x, y, 0.0], 0);
            coords.push([x, y]);
        }
    }
    let corners = (nx + 1) * (ny + 1);
    let mut mids = std::collections::HashMap::new();
    let mut pts: Vec<[f64; 3]> = Vec::new();
    let mut elems: Vec<(ElementKind, Vec<u32>)> = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let (a, bb, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            match kind {
                ElementKind::Quad4 => elems.push((kind, vec![a, bb, c, d])),
                _ => {
                    elems.push((kind, vec![a, bb, c]));
                    elems.push((kind, vec![a, c, d]));
                }
            }
        }
    }
    let mut fixed = vec![false; corners];
    for &f in extra_fixed {
        fixed[f] = true;
    }
    if kind == ElementKind::Tri6 {
        for (_, ids) in elems.iter_mut() {
            let c = ids.clone();
            for e in 0..3 {
                let (p, q) = (c[e], c[(e + 1) % 3]);
                let key = (p.min(q), p.max(q));
                let m = *mids.entry(key).or_insert_with(|| {
                    let (a, b2) = (coords[p as usize], coords[q as usize]);
                    pts.push([(a[0] + b2[0]) / 2.0, (a[1] + b2[1]) / 2.0, 0.0]);
                    (corners + pts.len() - 1) as u32
                });
                ids.push(m);
            }
        }
        for p in &pts {
            b.add_node(*p, 0);
        }
        fixed.resize(corners + pts.len(), false);
    }
    for (kind, ids) in &elems {
        b.add_element(*kind, ids, 0);
    }
    b.fixed = FixedSpec::BoundaryAnd(fixed);
    let m = b.build().expect("grid mesh");
    m.sanity_check().unwrap();
    m
}

fn jitter_strategy(max: f64) -> impl proptest::strategy::Strategy<Value = Vec<(f64, f64)>> {
    prop::collection::vec((-max..max, -max..max), 9..20)
}

fn objective_for(strategy: Strategy, i: usize) -> &'static dyn Objective {
    // the max-min objective for Freitag's schemes, both for the rest in turn
    match strategy {
        Strategy::C1 | Strategy::C2 | Strategy::C3 => &ShapeMaxMin,
        _ if i % 2 == 0 => &ShapeSum,
        _ => &ShapeMaxMin,
    }
}

#[test]
fn element_measures_match_element_quality() {
    let d = DVec2::new;
    let cases: Vec<(ElementKind, Vec<DVec2>)> = vec![
        (ElementKind::Tri3, vec![d(0.0, 0.0), d(1.0, 0.1), d(0.3, 0.8)]),
        (ElementKind::Tri3, vec![d(0.0, 0.0), d(0.3, 0.8), d(1.0, 0.1)]),
        (ElementKind::Quad4, vec![d(0.0, 0.0), d(1.2, 0.1), d(1.0, 0.8), d(-0.1, 1.1)]),
        (ElementKind::Quad4, vec![d(0.0, 0.0), d(1.0, 0.0), d(0.0, 1.0), d(1.0, 1.0)]),
        (ElementKind::Tri6, vec![d(0.0, 0.0), d(2.0, 0.0), d(0.0, 2.0), d(1.0, -0.3), d(1.0, 1.0), d(0.0, 1.0)]),
    ];
    for (kind, p) in cases {
        let mut a = [DVec2::ZERO; 9];
        a[..p.len()].copy_from_slice(&p);
        let q = element_quality(kind, &p);
        let m = element_measures(kind, &a);
        assert!((q.shape - m.min_shape).abs() < 1e-14, "{kind:?}");
        assert!((q.min_sine - m.min_sine).abs() < 1e-14, "{kind:?}");
        assert_eq!(q.inverted, m.inverted == 1, "{kind:?}");
    }
}

#[test]
fn laplace_on_a_regular_grid_is_a_fixed_point() {
    for kind in [ElementKind::Tri3, ElementKind::Quad4, ElementKind::Tri6] {
        let mut mesh = grid(5, 4, kind, &[], &[]);
        let before = mesh.nodes().to_vec();
        let opts = SmoothOptions::default().with_strategy(Strategy::Laplace).with_order(Order::Input);
        let recs = smooth(&mut mesh, &ShapeSum, opts, 2, NO_CLOCK).unwrap();
        for (a, b) in before.iter().zip(mesh.nodes()) {
            assert!(a.distance(*b) < 1e-14, "{kind:?}: {a} → {b}");
        }
        assert_eq!(recs[1].counts.laplacian_moves, 0);
    }
}

#[test]
fn laplace_moves_to_the_centroid_and_mid_nodes_follow() {
    let jit = [(0.3, -0.2), (-0.25, 0.1), (0.1, 0.3)];
    let mut mesh = grid(4, 4, ElementKind::Tri6, &jit, &[]);
    let mut s =
        Smoother::new(SmoothOptions::default().with_strategy(Strategy::Laplace).with_order(Order::Input)).unwrap();
    let n = (0..mesh.node_count()).find(|&n| mesh.is_free(n)).unwrap();
    let nb: DVec2 =
        mesh.neighbours(n).iter().map(|&m| mesh.nodes()[m as usize]).sum::<DVec2>() / mesh.neighbours(n).len() as f64;
    let o = s.smooth_node(&mut mesh, n, &ShapeSum);
    assert!(o.moved && o.laplacian && !o.optimized);
    assert_eq!(mesh.nodes()[n], nb);
    s.pass(&mut mesh, &ShapeSum, NO_CLOCK);
    for e in mesh.edges() {
        if e.mid != crate::mesh::NONE && !e.is_boundary() {
            let mid = 0.5 * (mesh.nodes()[e.a as usize] + mesh.nodes()[e.b as usize]);
            assert!(mesh.nodes()[e.mid as usize].distance(mid) < 1e-15, "mid node {} off its edge", e.mid);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    /// Every strategy, both orders, triangles and quads: fixed nodes stay bit-exact, no
    /// NaN appears, and the same input gives the same output bit for bit.
    #[test]
    fn drivers_keep_fixed_nodes_and_are_deterministic(jit in jitter_strategy(0.35), quads in any::<bool>(), pick in 0usize..4) {
        let kind = if quads { ElementKind::Quad4 } else { ElementKind::Tri3 };
        let mesh0 = grid(4, 4, kind, &jit, &[7, 12]);
        for (i, strategy) in ALL.into_iter().enumerate() {
            for order in [Order::Input, Order::Priority] {
                let opts = SmoothOptions::default().with_strategy(strategy).with_order(order);
                let obj = objective_for(strategy, i + pick);
                let mut a = mesh0.clone();
                let ra = smooth(&mut a, obj, opts, 2, NO_CLOCK).unwrap();
                let mut b = mesh0.clone();
                let rb = smooth(&mut b, obj, opts, 2, NO_CLOCK).unwrap();
                prop_assert_eq!(&ra, &rb);
                for n in 0..a.node_count() {
                    prop_assert!(a.nodes()[n].is_finite());
                    prop_assert_eq!(a.nodes()[n].to_array().map(f64::to_bits), b.nodes()[n].to_array().map(f64::to_bits));
                    if a.fixed()[n] {
                        prop_assert_eq!(a.nodes()[n].to_array().map(f64::to_bits), mesh0.nodes()[n].to_array().map(f64::to_bits));
                    }
                }
                prop_assert!(ra.iter().all(|r| r.objective_total.is_some_and(|t| !t.is_nan())));
            }
        }
    }

    /// The smart Laplacian never lowers a star's worst quality nor inverts a valid
    /// element — node by node, and therefore for the whole mesh.
    #[test]
    fn smart_never_makes_a_star_worse(jit in jitter_strategy(0.95), quads in any::<bool>(), sine in any::<bool>()) {
        let kind = if quads { ElementKind::Quad4 } else { ElementKind::Tri3 };
        let mut mesh = grid(4, 4, kind, &jit, &[]);
        let measure = if sine { Measure::MinSine } else { Measure::Shape };
        let opts = SmoothOptions::default().with_strategy(Strategy::Smart).with_order(Order::Input).with_smart_measure(measure);
        let mut s = Smoother::new(opts).unwrap();
        let mut star = Star::new();
        for _pass in 0..2 {
            let stats0 = mesh_stats(&mesh);
            for n in 0..mesh.node_count() {
                if !mesh.is_free(n) {
                    continue;
                }
                star.gather(&mesh, n);
                let before: Vec<_> = star.elems.iter().map(|e| element_measures(e.kind, &e.pts)).collect();
                // the measure as the smart Laplacian takes it
                let measured = |star: &Star| match measure {
                    Measure::Shape => star_shape(star, star.x0).0,
                    Measure::MinSine => star_quality(star, None).min_sine,
                };
                let q0 = measured(&star);
                let o = s.smooth_node(&mut mesh, n, &ShapeSum);
                star.gather(&mesh, n);
                let q1 = measured(&star);
                prop_assert!(!o.optimized);
                if o.moved {
                    prop_assert!(q1 > q0, "node {}: {} → {}", n, q0, q1);
                } else {
                    prop_assert_eq!(q1, q0);
                }
                for (b, e) in before.iter().zip(&star.elems) {
                    let a = element_measures(e.kind, &e.pts);
                    prop_assert!(!(b.inverted == 0 && a.inverted > 0), "node {} inverted element {}", n, e.element);
                }
            }
            let stats1 = mesh_stats(&mesh);
            prop_assert!(stats1.inverted <= stats0.inverted);
            if measure == Measure::Shape {
                prop_assert!(stats1.min_quality >= stats0.min_quality);
            }
        }
    }

    /// Priority order: the worst star is visited first, the worst bin once per bin, and
    /// a worse node is visited at least as often as a better one.
    #[test]
    fn priority_order_visits_worst_first(jit in jitter_strategy(0.45), quads in any::<bool>()) {
        let kind = if quads { ElementKind::Quad4 } else { ElementKind::Tri3 };
        let mesh = grid(5, 5, kind, &jit, &[]);
        let mut s = Smoother::new(SmoothOptions::default().with_order(Order::Priority)).unwrap();
        let schedule = s.plan(&mesh).to_vec();
        let mut star = Star::new();
        let q: Vec<f64> = (0..mesh.node_count())
            .map(|n| {
                if !mesh.is_free(n) {
                    return f64::NAN;
                }
                star.gather(&mesh, n);
                star_shape(&star, star.x0).0
            })
            .collect();
        // ranked as the order ranks them: within rounding (2^-40) a tie, to the lower node
        let ranked = |n: usize| super::plan::tie_scale(q[n]);
        let worst = (0..mesh.node_count()).filter(|&n| mesh.is_free(n)).min_by(|&a, &b| ranked(a).total_cmp(&ranked(b))).unwrap();
        prop_assert_eq!(schedule[0] as usize, worst);
        let mut visits = vec![0u32; mesh.node_count()];
        for &n in &schedule {
            visits[n as usize] += 1;
        }
        let bins = s.options().priority_bins;
        prop_assert_eq!(visits[worst], bins);
        for a in 0..mesh.node_count() {
            prop_assert_eq!(visits[a] > 0, mesh.is_free(a), "every free node once at least");
            prop_assert!(visits[a] <= bins);
            for b in 0..mesh.node_count() {
                if mesh.is_free(a) && mesh.is_free(b) && ranked(a) < ranked(b) {
                    prop_assert!(visits[a] >= visits[b]);
                }
            }
        }
        // the schedule is one worst-first prefix of the ranking per inner loop, growing
        let mut order: Vec<usize> = (0..mesh.node_count()).filter(|&n| mesh.is_free(n)).collect();
        order.sort_by(|&a, &b| ranked(a).total_cmp(&ranked(b)).then(a.cmp(&b)));
        let mut lengths = Vec::new();
        let mut pos = 0;
        while pos < schedule.len() {
            let mut len = 0;
            while pos + len < schedule.len() && len < order.len() && schedule[pos + len] as usize == order[len] {
                len += 1;
            }
            prop_assert!(len > 0, "a segment must start with the worst node");
            lengths.push(len);
            pos += len;
        }
        prop_assert_eq!(lengths.len() as u32, bins);
        prop_assert!(lengths.windows(2).all(|w| w[0] <= w[1]));
        prop_assert_eq!(*lengths.last().unwrap(), order.len());
    }
}

/// Planning in steps of any size gives the plan of one call, in both orders, and a
/// smoother reused after a plan in steps plans the next pass afresh.
#[test]
fn planning_in_steps_gives_the_same_schedule() {
    let mesh = grid(7, 6, ElementKind::Tri3, &[(0.3, -0.2), (0.1, 0.25), (-0.35, 0.1)], &[9]);
    for order in [Order::Priority, Order::Input] {
        let mut whole = Smoother::new(SmoothOptions::default().with_order(order)).unwrap();
        let want = whole.plan(&mesh).to_vec();
        assert!(!want.is_empty());
        for step in [1, 2, 5, 1000] {
            let mut s = Smoother::new(SmoothOptions::default().with_order(order)).unwrap();
            for _ in 0..2 {
                s.begin_plan(&mesh);
                let mut calls = 1;
                while !s.plan_some(&mesh, step) {
                    calls += 1;
                    assert!(calls <= mesh.node_count() + 1, "planning must end");
                }
                assert!(s.plan_some(&mesh, step), "a finished plan stays finished");
                assert_eq!(s.schedule(), &want[..], "{order:?}, steps of {step}");
                if order == Order::Priority && step == 1 {
                    assert!(calls > 20, "steps of one star: {calls} calls");
                }
            }
        }
    }
}

#[test]
fn input_order_is_node_order() {
    let mesh = grid(3, 3, ElementKind::Tri3, &[(0.1, 0.1)], &[5]);
    let mut s = Smoother::new(SmoothOptions::default().with_order(Order::Input)).unwrap();
    let free: Vec<u32> = (0..mesh.node_count() as u32).filter(|&n| mesh.is_free(n as usize)).collect();
    assert_eq!(s.plan(&mesh), &free[..]);
    assert!(!free.contains(&5));
}

#[test]
fn rules_untangle_a_folded_star_by_optimization() {
    // the centre of a hexagon pushed outside it: some star triangles are inverted
    let mut mesh = hexagon(DVec2::new(1.3, 0.4));
    assert!(mesh_stats(&mesh).inverted > 0);
    let opts = SmoothOptions::default().with_strategy(Strategy::Rules).with_max_iter(20);
    let mut s = Smoother::new(opts).unwrap();
    let r1 = s.pass(&mut mesh, &ShapeMaxMin, NO_CLOCK);
    assert_eq!(r1.counts.optimization_calls, 1, "rule 2: an invalid element calls optimization");
    assert_eq!(r1.counts.laplacian_moves, 0);
    let mut last = r1;
    for _ in 0..5 {
        last = s.pass(&mut mesh, &ShapeMaxMin, NO_CLOCK);
    }
    assert_eq!(last.after.inverted, 0, "{last:?}");
    assert!(mesh.nodes()[0].length() < 0.05, "{}", mesh.nodes()[0]);
    // once valid, the constrained Laplacian takes over (the centroid is the best place)
    let mut mesh = hexagon(DVec2::new(0.2, 0.1));
    let r = s.pass(&mut mesh, &ShapeMaxMin, NO_CLOCK);
    assert_eq!((r.counts.laplacian_moves, r.counts.optimization_calls), (1, 0));
    // and a node where the Laplacian cannot help goes to optimization (rule 3)
    let r = s.pass(&mut mesh, &ShapeMaxMin, NO_CLOCK);
    assert_eq!((r.counts.laplacian_moves, r.counts.optimization_calls), (0, 1));
    // rule 4: forced
    let forced = SmoothOptions { force_optimization: true, ..opts };
    let mut mesh = hexagon(DVec2::new(0.2, 0.1));
    let r = Smoother::new(forced).unwrap().pass(&mut mesh, &ShapeMaxMin, NO_CLOCK);
    assert_eq!((r.counts.laplacian_moves, r.counts.optimization_calls), (0, 1));
}

#[test]
fn rules_optimize_next_to_a_curved_boundary() {
    // interior nodes 5, 6, 9 in place, node 10 = grid (2, 2) pushed off its centroid
    let mut mesh = grid(3, 3, ElementKind::Tri6, &[(0.0, 0.0), (0.0, 0.0), (0.0, 0.0), (0.2, 0.15)], &[]);
    // bow out the mid node of the bottom edge 0–1
    let e = *mesh.edges().iter().find(|e| e.a == 0 && e.b == 1).unwrap();
    let mut b = MeshBuilder::new();
    for (i, p) in mesh.nodes().iter().enumerate() {
        let p = if i == e.mid as usize { *p + DVec2::new(0.0, -0.2) } else { *p };
        b.add_node([p.x, p.y, 0.0], 0);
    }
    for el in 0..mesh.element_count() {
        b.add_element(mesh.kind(el), mesh.element(el), 0);
    }
    let mut flat = std::mem::replace(&mut mesh, b.build().unwrap());
    assert!(mesh.edges().iter().any(|e| e.curved) && !flat.edges().iter().any(|e| e.curved));
    let opts = SmoothOptions::default().with_strategy(Strategy::Rules).with_order(Order::Input);
    let mut s = Smoother::new(opts).unwrap();
    let near = 5; // grid node (1, 1): corner of the element with the curved edge
    assert!(mesh.is_free(near));
    let o = s.smooth_node(&mut mesh, near, &ShapeSum);
    assert!(o.optimized && !o.laplacian, "rule 1: {o:?}");
    // the same node with the edge straight: the smart Laplacian does it
    let o = s.smooth_node(&mut flat, near, &ShapeSum);
    assert!(o.laplacian && !o.optimized, "{o:?}");
    let far = 10; // grid node (2, 2): no curved boundary in reach, the smart Laplacian helps
    let o = s.smooth_node(&mut mesh, far, &ShapeSum);
    assert!(o.laplacian && o.moved && !o.optimized, "{o:?}");
    let mid_before = mesh.nodes()[e.mid as usize];
    s.pass(&mut mesh, &ShapeSum, NO_CLOCK);
    assert_eq!(mesh.nodes()[e.mid as usize], mid_before, "the curved edge keeps its mid node");
}

#[test]
fn combined_schemes_respect_the_threshold() {
    // a regular right-triangle grid: every angle ≥ 45°, above a 30° threshold
    let good = grid(4, 4, ElementKind::Tri3, &[], &[]);
    for strategy in [Strategy::C1, Strategy::C2, Strategy::C3] {
        let mut mesh = good.clone();
        let opts = SmoothOptions::default().with_strategy(strategy).with_threshold_deg(30.0).with_order(Order::Input);
        let r = Smoother::new(opts).unwrap().pass(&mut mesh, &ShapeMaxMin, NO_CLOCK);
        assert_eq!(r.counts.optimization_calls, 0, "{strategy:?}");
        assert_eq!(mesh.nodes(), good.nodes(), "{strategy:?}");
    }
    // one bad node: every scheme optimizes it, C3 leaves the rest alone
    let mut bad = good.clone();
    bad.nodes_mut()[6] += DVec2::new(0.45, 0.4);
    for strategy in [Strategy::C1, Strategy::C2, Strategy::C3] {
        let mut mesh = bad.clone();
        let opts = SmoothOptions::default().with_strategy(strategy).with_threshold_deg(30.0).with_order(Order::Input);
        let mut s = Smoother::new(opts).unwrap();
        let o = s.smooth_node(&mut mesh, 6, &ShapeMaxMin);
        let mut star = Star::new();
        star.gather(&bad, 6);
        let q0 = star_quality(&star, None).min_sine;
        star.gather(&mesh, 6);
        let q1 = star_quality(&star, None).min_sine;
        assert!(o.moved && q1 > q0, "{strategy:?}: {o:?} {q0} → {q1}");
        if strategy == Strategy::C1 {
            assert!(o.optimized && !o.laplacian);
        }
        if strategy == Strategy::C3 {
            let far = 18; // grid node (3, 3), with a good star
            assert_eq!(s.smooth_node(&mut mesh, far, &ShapeMaxMin), NodeOutcome::default());
        }
    }
}

#[test]
fn pass_record_and_clock() {
    let mut mesh = grid(4, 4, ElementKind::Quad4, &[(0.2, -0.1), (-0.15, 0.2)], &[]);
    let t = Cell::new(0.0);
    let clock = || {
        t.set(t.get() + 2.5);
        t.get()
    };
    let mut s = Smoother::new(SmoothOptions::default().with_order(Order::Input)).unwrap();
    let total0 = s.objective_total(&mesh, &ShapeSum);
    let r = s.pass(&mut mesh, &ShapeSum, &clock);
    assert_eq!(r.pass, 1);
    assert_eq!(r.elapsed_ms, 2.5);
    assert_eq!(r.counts.visits as usize, mesh.free_count());
    let t = r.objective_total.expect("the core measures it");
    assert!(t.is_finite() && t < total0, "{total0} → {t}");
    assert!(r.counts.laplacian_moves + r.counts.optimization_calls > 0);
    let st = mesh_stats(&mesh);
    assert_eq!(
        (r.after.inverted, r.after.min_quality, r.after.min_angle_deg),
        (st.inverted, st.min_quality, st.min_angle_deg)
    );
    let json = serde_json::to_string(&r).unwrap();
    assert!(json.contains("\"objective_total\"") && json.contains("\"solver_iterations\""), "{json}");
    assert_eq!(s.pass(&mut mesh, &ShapeSum, &clock).pass, 2);
}

#[test]
fn solve_node_returns_history_and_names_bad_nodes() {
    let mesh = hexagon(DVec2::new(0.3, -0.2));
    let before = mesh.nodes().to_vec();
    let opts = SmoothOptions::default().with_max_iter(10);
    let r = solve_node(&mesh, 0, &ShapeMaxMin, &opts).unwrap();
    assert_eq!(r.history.len(), r.iterations as usize);
    assert!(r.iterations > 0 && r.value > r.value0);
    assert_eq!(mesh.nodes(), before);
    let r = solve_node(&mesh, 0, &ShapeSum, &opts).unwrap();
    assert!(r.history.iter().any(|i| i.direction == crate::optimize::DirectionKind::Gradient));
    let r = solve_node(&mesh, 0, &ShapeSum, &opts.with_solver(SolverKind::NonSmoothAscent)).unwrap();
    assert!(r.value < r.value0 && r.history.iter().all(|i| i.direction == crate::optimize::DirectionKind::ActiveSet));
    let e = solve_node(&mesh, 3, &ShapeSum, &opts).unwrap_err().to_string();
    assert!(e.contains("node 3") && e.contains("fixed"), "{e}");
    let e = solve_node(&mesh, 99, &ShapeSum, &opts).unwrap_err().to_string();
    assert!(e.contains("node 99") && e.contains("7 nodes"), "{e}");
    assert_eq!(ShapeSum.goal(), Goal::MinimizeSum);
}

#[test]
fn bad_options_are_refused() {
    for t in [0.0, -5.0, 120.0, f64::NAN] {
        let e = Smoother::<Star>::new(SmoothOptions::default().with_threshold_deg(t)).unwrap_err().to_string();
        assert!(e.contains("threshold"), "{e}");
    }
    let o = SmoothOptions { priority_bins: 0, ..Default::default() };
    assert!(Smoother::<Star>::new(o).is_err());
}

/// Found by search: moving the centre to the centroid raises the star's worst α (an
/// inverted element gets less inverted) but inverts a valid element — the smart
/// Laplacian must refuse the move.
#[test]
fn smart_refuses_a_move_that_inverts_a_valid_element() {
    let ring = [(0.64, 0.38), (0.9, 0.51), (-0.46, 0.48), (-1.39, -0.16), (-0.4, -1.06), (0.62, -0.77)];
    let mut b = MeshBuilder::new();
    b.add_node([-1.34, 0.8, 0.0], 0);
    for (x, y) in ring {
        b.add_node([x, y, 0.0], 0);
    }
    for i in 0..6u32 {
        b.add_element(ElementKind::Tri3, &[0, 1 + i, 1 + (i + 1) % 6], 0);
    }
    let mut mesh = b.build().unwrap();
    let mut star = Star::new();
    star.gather(&mesh, 0);
    let c = centroid(&mesh, 0).unwrap();
    let (q0, q1) = (star_quality(&star, None), star_quality(&star, Some(c)));
    assert!(q1.min_shape > q0.min_shape, "the centroid improves the worst α");
    assert!(star
        .elems
        .iter()
        .any(|e| element_measures(e.kind, &e.pts).inverted == 0 && element_measures(e.kind, &e.at(c)).inverted == 1));
    let before = mesh.nodes().to_vec();
    for strategy in [Strategy::Smart, Strategy::C2] {
        let opts = SmoothOptions::default().with_strategy(strategy).with_max_iter(0);
        let o = Smoother::new(opts).unwrap().smooth_node(&mut mesh, 0, &ShapeSum);
        assert!(!o.laplacian && mesh.nodes() == before, "{strategy:?}: {o:?}");
    }
    // and fixed nodes are left alone when asked directly
    let o = Smoother::new(SmoothOptions::default().with_strategy(Strategy::Laplace))
        .unwrap()
        .smooth_node(&mut mesh, 3, &ShapeSum);
    assert_eq!((o, mesh.nodes()[3]), (NodeOutcome::default(), before[3]));
}

/// Found by the reproduction (Mesquite's `hole_in_square.vtk`, node 63 of the first pass):
/// a valid star of five quads, one of them a sliver (two of its corners 0.1 apart). With
/// our eq. (8) the penalty of the sliver's sub-triangles falls fastest by folding two
/// neighbours, so the unguarded optimizer inverts two valid elements; with
/// [`SmoothOptions::keep_valid`] (the default) it improves the objective and inverts none.
#[test]
fn keep_valid_stops_the_new_objective_folding_a_valid_star() {
    let d = DVec2::new(1.77273368847903, 1.47674961243878);
    let ring = [
        (0.6191798838377767, 1.9635892912613109),
        (1.1582019613742722, 1.1315519496993298),
        (2.952745259697628, 0.9328888840885995),
        (5.0, 2.0),
        (5.0, 1.0),
        (2.54992164088809, 2.11978452722374),
        (5.0, 3.0),
        (0.722398398237359, 1.92569837299114),
        (-0.594151124169511, 2.47974288002622),
        (0.486939211174313, 2.96446619685306),
    ];
    let mut b = MeshBuilder::new();
    b.add_node([d.x, d.y, 0.0], 0);
    for (x, y) in ring {
        b.add_node([x, y, 0.0], 0);
    }
    for q in [[0, 1, 2, 3], [4, 0, 3, 5], [6, 0, 4, 7], [0, 8, 9, 1], [6, 10, 8, 0]] {
        b.add_element(ElementKind::Quad4, &q, 0);
    }
    let mesh = b.build().unwrap();
    assert_eq!(mesh_stats(&mesh).inverted, 0);
    assert_eq!(mesh.free_count(), 1);
    // the first design of eq. (8), which folds this star without the guard
    let new = crate::objective::ChenTristanoKwok::with_penalty(crate::objective::Penalty::Angle);
    let mut star = Star::new();
    star.gather(&mesh, 0);
    let f0 = new.value(&star, d);
    // the barrier (the default design) never folds it, guard or not
    let barrier = crate::objective::ChenTristanoKwok::default();
    for keep in [false, true] {
        let mut m = mesh.clone();
        let opts = SmoothOptions::default().with_strategy(Strategy::Opt).with_keep_valid(keep);
        let o = Smoother::new(opts).unwrap().smooth_node(&mut m, 0, &barrier);
        assert!(o.optimized && o.moved, "barrier, keep_valid {keep}: {o:?}");
        assert_eq!(mesh_stats(&m).inverted, 0, "barrier, keep_valid {keep}");
    }
    // unguarded, the first design folds two elements
    let mut m = mesh.clone();
    let opts = SmoothOptions::default().with_strategy(Strategy::Opt).with_keep_valid(false);
    let o = Smoother::new(opts).unwrap().smooth_node(&mut m, 0, &new);
    assert!(o.optimized && o.moved, "{o:?}");
    assert_eq!(mesh_stats(&m).inverted, 2);
    assert!(new.value(&star, m.nodes()[0]) < f0, "the objective must fall");
    // guarded, the solver finds a lower objective among valid positions, but a lower worst
    // β too: the acceptance rule (issue 29) keeps the node where it was
    let guarded = KeepValid::new(&new, 0, false);
    let r = Solvers::new(SmoothOptions::default().solve_options()).get(SolverKind::FletcherReeves, Goal::MinimizeSum).solve(
        &guarded,
        &star,
        d,
    );
    assert!(new.value(&star, r.x) < f0 && star.inverted_at(r.x) == 0);
    assert!(star.shape_at(r.x).0 < star.shape_at(d).0, "the guarded solve lowers the worst β");
    let mut m = mesh.clone();
    let o = Smoother::new(SmoothOptions::default().with_strategy(Strategy::Opt)).unwrap().smooth_node(&mut m, 0, &new);
    assert!(o.optimized && !o.moved, "{o:?}");
    assert_eq!(m.nodes(), mesh.nodes());
}

/// A 6 × 6 grid (quads or triangles) of the unit square, boundary fixed, every interior
/// node placed uniformly at random in the square (Knupp 1999, Fig. 1, smaller).
fn random_grid(kind: crate::generate::GridKind, seed: u64) -> Mesh {
    let mut m = crate::generate::grid(6, 6, kind).unwrap();
    let mut rng = crate::numeric::SplitMix64::new(seed);
    for n in 0..m.node_count() {
        if m.is_free(n) {
            m.nodes_mut()[n] = DVec2::new(rng.next_f64(), rng.next_f64());
        }
    }
    m
}

/// Passes of `objective` by optimization, input order, until no element is inverted.
fn passes_to_valid(mesh: &mut Mesh, objective: &dyn Objective, opts: SmoothOptions, max: u32) -> Option<u32> {
    let mut s = Smoother::new(opts.with_strategy(Strategy::Opt).with_order(Order::Input)).unwrap();
    (1..=max).find(|_| s.pass(mesh, objective, NO_CLOCK).after.inverted == 0)
}

#[test]
fn untangle_untangles_random_grids_node_by_node() {
    use crate::generate::GridKind;
    use crate::objective::Untangle;
    let mut untangled = 0;
    let mut cases = 0;
    for kind in [GridKind::Quad, GridKind::Tri] {
        for seed in 1..=4 {
            let m0 = random_grid(kind, seed);
            let start = mesh_stats(&m0).inverted;
            assert!(start > 5, "{kind:?} {seed}: a tangled start ({start})");
            let mut m = m0.clone();
            let p = passes_to_valid(
                &mut m,
                &Untangle::default(),
                SmoothOptions::default().with_pass_through_folds(true),
                60,
            );
            cases += 1;
            if p.is_some() {
                untangled += 1;
                // fixed nodes stay put
                for n in 0..m.node_count() {
                    if !m.is_free(n) {
                        assert_eq!(m.nodes()[n], m0.nodes()[n]);
                    }
                }
            }
        }
    }
    assert_eq!(untangled, cases, "untangled {untangled} of {cases}");
}

#[test]
fn the_keep_valid_exception_lets_an_inverted_star_pass_through_a_fold() {
    // `pass_through_folds` lets an inverted star fold one more element on the way out,
    // never a valid one.
    use crate::generate::GridKind;
    use crate::objective::Untangle;
    let mut m = random_grid(GridKind::Tri, 7);
    let mut s =
        Smoother::new(SmoothOptions::default().with_strategy(Strategy::Opt).with_pass_through_folds(true)).unwrap();
    for _ in 0..20 {
        for n in 0..m.node_count() {
            if !m.is_free(n) {
                continue;
            }
            let star_inverted = |m: &Mesh| {
                m.node_elements(n)
                    .iter()
                    .filter(|&&e| {
                        let p = m.element_points_array(e as usize);
                        let k = m.kind(e as usize);
                        element_quality(k, &p[..k.node_count()]).inverted
                    })
                    .count()
            };
            let before = star_inverted(&m);
            s.smooth_node(&mut m, n, &Untangle::default());
            if before == 0 {
                assert_eq!(star_inverted(&m), 0, "node {n}: a valid star was folded");
            }
        }
    }
}

/// Untangling sweeps end: at the limit, or after a sweep that moved no node, and never
/// when nothing is inverted or the strategy cannot optimise.
#[test]
fn untangling_sweeps_terminate() {
    use crate::mesh::FixedSpec;
    // a fan of four triangles round the free node 0, plus a clockwise triangle of fixed
    // nodes that no smoother can change: every pass has an inverted element left
    let mut b = MeshBuilder::new();
    for (x, y) in [(0.1, 0.05), (1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)] {
        b.add_node([x, y, 0.0], 0);
    }
    for t in [[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 1], [1, 4, 3]] {
        b.add_element(ElementKind::Tri3, &t, 0);
    }
    b.fixed = FixedSpec::Exact(vec![false, true, true, true, true]);
    let mesh = b.build().unwrap();
    assert!(mesh_stats(&mesh).inverted > 0);
    let new = crate::objective::ChenTristanoKwok::default();
    for (limit, strategy) in [(UNTANGLE_SWEEPS, Strategy::Rules), (3, Strategy::Opt), (0, Strategy::Rules)] {
        let mut m = mesh.clone();
        let opts = SmoothOptions::default().with_strategy(strategy).with_untangle_sweeps(limit);
        let r = Smoother::new(opts).unwrap().pass(&mut m, &new, &|| 0.0);
        assert!(r.after.inverted > 0);
        // the free node settles within a sweep or two; then a sweep moves nothing and ends them
        assert!(
            r.counts.untangle_sweeps <= limit.min(3),
            "{strategy:?}, limit {limit}: {} sweeps",
            r.counts.untangle_sweeps
        );
        assert!(limit == 0 || r.counts.untangle_sweeps >= 1);
    }
    // strategies that never optimise do not sweep
    for strategy in [Strategy::Laplace, Strategy::Smart] {
        let mut m = mesh.clone();
        let r = Smoother::new(SmoothOptions::default().with_strategy(strategy)).unwrap().pass(&mut m, &new, &|| 0.0);
        assert_eq!(r.counts.untangle_sweeps, 0, "{strategy:?}");
    }
    // a valid mesh never sweeps
    let mut g = crate::generate::grid(4, 4, crate::generate::GridKind::Tri).unwrap();
    let r = Smoother::new(SmoothOptions::default()).unwrap().pass(&mut g, &new, &|| 0.0);
    assert_eq!((r.after.inverted, r.counts.untangle_sweeps), (0, 0));
    // and the limit is checked
    assert!(Smoother::<Star>::new(SmoothOptions::default().with_untangle_sweeps(1001)).is_err());
}

/// The smart Laplacian's and the priority order's shape measure of a linear triangle is the
/// same, bit for bit, at every scale (the squares are taken in the triangle's own scale).
#[test]
fn linear_triangle_shape_is_the_same_at_every_scale() {
    use crate::objective::testing::{elem, SplitMix64, SquarePoint};
    let mut rng = SplitMix64::new(17);
    for _ in 0..200 {
        let pts = [rng.point(1.0), rng.point(1.0), rng.point(1.0)];
        let x = rng.point(1.0);
        let el = elem(ElementKind::Tri3, &pts, 0);
        let unit = element_shape_at(&el, x);
        for e in (-1000..=1000).step_by(50) {
            let f = 2f64.powi(e);
            let scaled = elem(ElementKind::Tri3, &pts.map(|p| f * p), 0);
            assert_eq!(element_shape_at(&scaled, f * x), unit, "2^{e}: {pts:?} {x}");
        }
    }
}

/// The smart Laplacian read from the mesh (stars of linear triangles, not gathered) decides
/// as the gathered star does, node by node: the same inverted count (Chen's rule 2) and the
/// same move, bit for bit, on a valid and on a tangled mesh.
#[test]
fn smart_from_the_mesh_decides_as_the_gathered_star() {
    use crate::generate::{perturb, rand2d};
    let valid = rand2d(300, 12, 7).unwrap();
    let tangled = perturb(&valid, 0.5, 3).unwrap();
    for mesh in [valid, tangled] {
        let mut s: Smoother = Smoother::new(SmoothOptions::default().with_strategy(Strategy::Smart)).unwrap();
        let (mut moved, mut inverted) = (0, 0);
        for n in (0..mesh.node_count()).filter(|&n| mesh.is_free(n)) {
            let direct = super::smart_on_triangles(&mesh, n, Measure::Shape).expect("a star of linear triangles");
            s.star.gather(&mesh, n);
            assert_eq!(direct.inverted, star_shape(&s.star, s.star.x0).1, "node {n}");
            let mut out = NodeOutcome::default();
            let gathered = s.smart(&mesh, n, &mut out).then_some(s.star.x0);
            assert_eq!(direct.to, gathered, "node {n}");
            moved += gathered.is_some() as usize;
            inverted += direct.inverted;
        }
        assert!(moved > 50, "{moved}");
        assert!(inverted > 0 || mesh_stats(&mesh).inverted == 0);
    }
    // a quad star is not read from the mesh
    let quads = grid(3, 3, ElementKind::Quad4, &[(0.1, -0.1)], &[]);
    assert!((0..quads.node_count()).filter(|&n| quads.is_free(n)).all(|n| super::smart_on_triangles(
        &quads,
        n,
        Measure::Shape
    )
    .is_none()));
}

/// Issue 29: Knupp's untangling objectives are flat (`untangle`) or blind to shape
/// (`untangle-mindet`) on a valid star, and moved the nodes of valid meshes, lowering
/// their quality; like Mesquite's untangler they now leave a valid mesh where it is.
#[test]
fn untangling_objectives_leave_a_valid_mesh_where_it_is() {
    use crate::generate::rand2d;
    use crate::objective::{objective, ObjectiveKind};
    let valid = rand2d(60, 6, 3).unwrap();
    assert_eq!(mesh_stats(&valid).inverted, 0);
    for kind in [ObjectiveKind::Untangle, ObjectiveKind::UntangleMinDet] {
        assert!(kind.only_untangles());
        let obj = objective(kind);
        let mut m = valid.clone();
        let r = smooth(&mut m, &*obj, SmoothOptions::default().with_strategy(Strategy::Opt), 2, &|| 0.0).unwrap();
        assert_eq!(m.nodes(), valid.nodes(), "{kind}");
        assert_eq!(r[0].counts.optimization_calls, 0, "{kind}");
    }
    // and they still untangle
    let tangled = crate::generate::perturb(&rand2d(60, 6, 3).unwrap(), 1.5, 3).unwrap();
    assert!(mesh_stats(&tangled).inverted > 0);
    let mut m = tangled.clone();
    let obj = objective(ObjectiveKind::Untangle);
    smooth(&mut m, &*obj, SmoothOptions::default().with_strategy(Strategy::Opt), 3, &|| 0.0).unwrap();
    assert!(mesh_stats(&m).inverted < mesh_stats(&tangled).inverted);
    assert!(ObjectiveKind::ALL.iter().filter(|k| k.only_untangles()).count() == 2);
}

/// The whole-mesh scans' inverted test, which reads a linear element's corners straight
/// from the mesh, answers as the general test on the element's nine points, element by
/// element: triangles, quads, mixed and quadratic plates, valid and tangled, and a
/// triangle far below the safe scale (where the general path measures at unit scale).
#[test]
fn the_mesh_scan_finds_the_inverted_elements_the_general_test_finds() {
    use crate::generate::{perturb, plate, PlateKind};
    let mut checked = [0usize; 2];
    for kind in [PlateKind::Tri, PlateKind::Quad, PlateKind::Mixed] {
        for order in [1, 2] {
            let valid = plate(kind, order, 6).unwrap();
            for amount in [0.0, 0.6, 1.5] {
                let mut mesh = if amount == 0.0 { valid.clone() } else { perturb(&valid, amount, 4).unwrap() };
                for scale in [1.0, 1e-250] {
                    for p in mesh.nodes_mut() {
                        *p *= scale;
                    }
                    for e in 0..mesh.element_count() {
                        let general = measure::is_inverted(mesh.kind(e), &mesh.element_points_array(e));
                        assert_eq!(measure::mesh_element_is_inverted(&mesh, e), general, "{kind:?} order {order} element {e}");
                        checked[general as usize] += 1;
                    }
                }
            }
        }
    }
    assert!(checked[0] > 1000 && checked[1] > 100, "valid and inverted elements both checked: {checked:?}");
}
