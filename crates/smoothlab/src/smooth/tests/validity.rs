//! Valid and tangled meshes: no valid element folds, and the untangling passes end.

use glam::DVec2;

use super::*;
use crate::objective::Goal;
use crate::optimize::test_objectives::ShapeSum;
use crate::optimize::SolverKind;
use crate::quality::{element_quality, mesh_stats};

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
    // far off, two fixed quads whose areas differ 1000 times: the mesh's grading, so that
    // the rule's bound on it does not decide here (in the file the star is one of many)
    for (x, y) in [(10.0, 0.0), (11.0, 0.0), (11.0, 1.0), (10.0, 1.0), (1011.0, 0.0), (1011.0, 1.0)] {
        b.add_node([x, y, 0.0], 0);
    }
    for q in [[11, 12, 13, 14], [12, 15, 16, 13]] {
        b.add_element(ElementKind::Quad4, &q, 0);
    }
    let mesh = b.build().unwrap();
    assert_eq!(mesh_stats(&mesh).inverted, 0);
    assert_eq!(mesh_stats(&mesh).grading, Some(1000.0));
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
