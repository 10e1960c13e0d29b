//! The strategies and orders: where each moves a node, what it plans, and what it records.

use std::cell::Cell;

use glam::DVec2;
use proptest::prelude::prop;
use proptest::prelude::{any, prop_assert, prop_assert_eq, proptest, ProptestConfig};

use super::*;
use crate::objective::Goal;
use crate::optimize::test_objectives::{hexagon, ShapeMaxMin, ShapeSum};
use crate::optimize::SolverKind;
use crate::quality::mesh_stats;

const ALL: [Strategy; 7] =
    [Strategy::Laplace, Strategy::Smart, Strategy::Opt, Strategy::C1, Strategy::C2, Strategy::C3, Strategy::Rules];
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
        let ranked = |n: usize| crate::smooth::plan::tie_scale(q[n]);
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
