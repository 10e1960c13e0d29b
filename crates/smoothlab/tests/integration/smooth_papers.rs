//! The headline results of `docs/reproduction.md`, pinned robustly (invariants and
//! generous bounds, never timings): the `equil_tri` meshes become equilateral, the
//! perturbed plate and Mesquite's tangled meshes that `new` + `rules` untangles stay
//! untangled within the stated passes, and the new objective's average quality on
//! Freitag's rand2D beats the max-min objectives'. Mesquite's files are read from
//! `../shared/meshes`; when that folder is absent those tests say so and return, and fail
//! under `CI=true` ([`crate::common::mesquite_meshes`]).



use smoothlab::generate::{perturb, plate, rand2d, star, PlateKind, StarKind};
use smoothlab::io;
use smoothlab::objective::{objective, ObjectiveKind};
use smoothlab::quality::{corner_edges, lo_alpha_corner, mesh_stats};
use smoothlab::smooth::{Measure, Order, SmoothOptions, Smoother, Strategy};
use smoothlab::Mesh;

const NO_CLOCK: &dyn Fn() -> f64 = &|| 0.0;


fn worst_alpha_error(mesh: &Mesh) -> f64 {
    (0..mesh.element_count())
        .flat_map(|e| {
            let k = mesh.kind(e);
            let p = mesh.element_points_array(e);
            corner_edges(k, &p[..k.node_count()])[..k.corners()]
                .iter()
                .map(|(e1, e2)| (lo_alpha_corner(*e1, *e2) - 1.0).abs())
                .collect::<Vec<_>>()
        })
        .fold(0.0, f64::max)
}

/// `opt` passes (20 solver iterations a call) until every α is within 1e-6 of 1, at
/// most 50; returns the worst |α − 1|.
fn make_equilateral(mesh: &Mesh, kind: ObjectiveKind) -> f64 {
    let mut m = mesh.clone();
    let obj = objective(kind);
    let mut s = Smoother::new(SmoothOptions::default().with_strategy(Strategy::Opt).with_max_iter(20)).unwrap();
    for _ in 0..50 {
        if worst_alpha_error(&m) <= 1e-6 {
            break;
        }
        s.pass(&mut m, &*obj, NO_CLOCK);
    }
    worst_alpha_error(&m)
}

#[test]
fn the_regular_star_becomes_equilateral_under_every_objective() {
    let m = star(StarKind::Regular, 6).unwrap();
    assert!(worst_alpha_error(&m) > 0.1);
    for kind in [ObjectiveKind::SmoothShape, ObjectiveKind::MaxMinShape, ObjectiveKind::Condition] {
        let e = make_equilateral(&m, kind);
        assert!(e <= 1e-6, "{kind}: worst |α − 1| = {e}");
    }
}

#[test]
fn mesquite_equil_tri_meshes_become_equilateral() {
    let Some(dir) = crate::common::mesquite_meshes() else { return };
    for file in ["equil_tri.vtk", "equil_tri2.vtk"] {
        let m = io::read_path(&dir.join("tris/untangled").join(file)).unwrap();
        for kind in [ObjectiveKind::SmoothShape, ObjectiveKind::MaxMinShape, ObjectiveKind::Condition] {
            let e = make_equilateral(&m, kind);
            assert!(e <= 1e-6, "{file}, {kind}: worst |α − 1| = {e}");
        }
    }
}

/// Passes of `new` + `rules` (priority order) until no element is inverted, at most
/// `max`; checks on the way that the inverted count never rises.
fn passes_to_untangle(mesh: &Mesh, max: u32) -> Option<u32> {
    let mut m = mesh.clone();
    let obj = objective(ObjectiveKind::SmoothShape);
    let mut s = Smoother::new(SmoothOptions::default()).unwrap();
    let mut last = mesh_stats(&m).inverted;
    for p in 1..=max {
        let r = s.pass(&mut m, &*obj, NO_CLOCK);
        assert!(r.after.inverted <= last, "the inverted count rose {last} → {} in pass {p}", r.after.inverted);
        last = r.after.inverted;
        if r.after.inverted == 0 {
            return Some(p);
        }
    }
    None
}

#[test]
fn the_perturbed_plate_is_untangled_by_new_rules() {
    // Chen et al. Figs 13–15; the reproduction's mixed quadratic plate at amount 0.6
    for (kind, order) in [(PlateKind::Mixed, 2), (PlateKind::Tri, 1)] {
        let base = plate(kind, order, 4).unwrap();
        for seed in [2, 4] {
            let m = perturb(&base, 0.6, seed).unwrap();
            assert!(mesh_stats(&m).inverted > 20, "the plate must start tangled");
            let p = passes_to_untangle(&m, 3);
            assert!(p.is_some(), "{kind:?} order {order} seed {seed}: not untangled in 3 passes");
        }
    }
}

#[test]
fn mesquite_tangled_meshes_new_rules_untangles_in_three_passes() {
    let Some(dir) = crate::common::mesquite_meshes() else { return };
    for file in [
        "tris/tangled/horse-tri-1.vtk",
        "tris/tangled/horseshoe.vtk",
        "tris/tangled/tangled_tri.vtk",
        "quads/tangled/tangled_quad.vtk",
        "mixed/tangled/hybrid_3quad_1tri_tangled.vtk",
        "quads/untangled/shest_grid32.vtk",
    ] {
        let m = io::read_path(&dir.join(file)).unwrap();
        assert!(mesh_stats(&m).inverted > 0, "{file} starts tangled");
        let p = passes_to_untangle(&m, 3);
        assert!(p.is_some(), "{file}: not untangled in 3 passes");
    }
    // the hybrid mesh's three free nodes start on one point: the new objective still
    // gives each a direction (Mesquite's pipelines fail there)
    let m = io::read_path(&dir.join("mixed/tangled/hybrid_3quad_1tri_tangled.vtk")).unwrap();
    let free: Vec<usize> = (0..m.node_count()).filter(|&n| m.is_free(n)).collect();
    assert_eq!(free.len(), 3);
    assert!(free.iter().all(|&n| m.nodes()[n] == m.nodes()[free[0]]));
    // the others: never worse, pass after pass
    for file in [
        "quads/tangled/hole_in_square_tanglap.vtk",
        "quads/tangled/inverted-hole-1.vtk",
        "quads/tangled/inverted-hole-2.vtk",
        "quads/tangled/tangled_horse1.vtk",
        "quads/tangled/rotsq.vtk",
    ] {
        let m = io::read_path(&dir.join(file)).unwrap();
        passes_to_untangle(&m, 4);
    }
}

#[test]
fn on_rand2d_the_new_objective_has_the_best_mean_alpha_and_every_method_opens_the_smallest_angle() {
    for seed in [1, 2] {
        let m = rand2d(500, 20, seed).unwrap();
        let s0 = mesh_stats(&m);
        assert!(s0.min_angle_deg < 1.0, "rand2d starts with a sliver: {}", s0.min_angle_deg);
        let run = |kind: ObjectiveKind, o: SmoothOptions| {
            let mut m = m.clone();
            smoothlab::smooth::smooth(&mut m, &*objective(kind), o, 3, NO_CLOCK).unwrap();
            mesh_stats(&m)
        };
        let freitag = |s: Strategy| {
            SmoothOptions::default().with_strategy(s).with_order(Order::Input).with_smart_measure(Measure::MinSine)
        };
        let sine = run(ObjectiveKind::Sine, freitag(Strategy::Opt));
        let c2 = run(ObjectiveKind::Sine, freitag(Strategy::C2));
        let new = run(ObjectiveKind::SmoothShape, SmoothOptions::default());
        for (name, s) in [("opt sine", &sine), ("c2 30° sine", &c2), ("rules new", &new)] {
            assert!(s.inverted == 0 && s.min_angle_deg > 5.0, "seed {seed}, {name}: {}", s.min_angle_deg);
            assert!(s.max_angle_deg < s0.max_angle_deg, "seed {seed}, {name}");
        }
        assert!(
            new.mean_quality > sine.mean_quality + 0.02,
            "seed {seed}: {} vs {}",
            new.mean_quality,
            sine.mean_quality
        );
        assert!(new.mean_quality > c2.mean_quality + 0.01, "seed {seed}: {} vs {}", new.mean_quality, c2.mean_quality);
    }
}

/// The front door runs Freitag's `sine` as her Table 2 is reproduced: each move judged by
/// the smallest sine ([`Measure::for_run`]), so `smoothlab smooth --objective sine`,
/// the page's side and the reproduction's row are one run (issue 59: the page's rand3D
/// panel read 16.56° where the table's row, judged by the sine, read 18.30°).
#[test]
fn the_front_door_judges_sine_by_the_sine_as_freitag() {
    use smoothlab::volume::{smooth_volume, volume_stats};
    let v = smoothlab::generate::rand3d(smoothlab::generate::RAND3D_POINTS, 1).unwrap();
    let o = SmoothOptions::default().with_strategy(Strategy::Opt).with_order(Order::Input);
    let row = |m: Measure| {
        let mut t = v.clone();
        let obj = smoothlab::objective::solid_objective(ObjectiveKind::Sine).unwrap();
        smooth_volume(&mut t, obj.as_ref(), o.with_smart_measure(m), 3, NO_CLOCK).unwrap();
        volume_stats(&t).min_angle_deg
    };
    let mut model = smoothlab::Model::Volume(v.clone());
    let smoothing = smoothlab::Smoothing::default().strategy(Strategy::Opt).order(Order::Input).objective(ObjectiveKind::Sine).passes(3).finish(0);
    let report = model.smooth(&smoothing).unwrap();
    let (sine, shape) = (row(Measure::MinSine), row(Measure::Shape));
    assert_ne!(sine, shape, "the measures judge rand3D's moves alike: the test tells nothing");
    assert_eq!(report.stats().min_angle_deg, sine, "judged by the shape: {shape}");
    assert_eq!(Measure::for_run(ObjectiveKind::SmoothShape, true), Measure::Shape);
    assert_eq!(Measure::for_run(ObjectiveKind::Sine, false), Measure::Shape);
}
