//! Issue 32: tangled surfaces untangle as tangled planes do. A tangled file's elements
//! fold but its nodes still lie on the surface it stands for, so its reference is fitted
//! through the nodes (`docs/formulas.md` §7), not taken from its folded facets:
//!
//! 1. Spheres of triangles and of quads tangled by 1.5 mean edge lengths (several seeds),
//!    written and read back, end with none inverted within 3 passes of the defaults, every
//!    node within 2 % of the radius from the sphere; so do tori and capped cylinders
//!    (whose rims the file's fixed flags keep), linear and quadratic.
//! 2. A file without fixed flags (OFF, OBJ): a tangled sphere or torus untangles the same,
//!    none of its nodes taken for a feature (a tangle's folds and slivers turn as a crease
//!    does, so a tangled file's creases come from its fixed flags alone).
//! 3. A valid surface is its own reference as before: its nodes stay on its facets within
//!    1e-9 of its size.
//! 4. Inversion is judged against the reference's normal: a tangled file counts the
//!    elements the generator's exact surface counts (within one, on a fitted normal).

use smoothlab::generate::{perturb_surface, surface, SurfaceKind, SurfaceShape};
use smoothlab::io::{read_model_str, write_model_string, Format, WriteOptions};
use smoothlab::mesh::NONE;
use smoothlab::model::Model;
use smoothlab::objective::{objective, ObjectiveKind};
use smoothlab::smooth::SmoothOptions;
use smoothlab::surface::{smooth_surface, Analytic, Reference, Surface};

/// A generated sample tangled by `amount` mean edge lengths, and its exact surface.
fn tangled(shape: SurfaceShape, kind: SurfaceKind, order: u8, resolution: usize, amount: f64, seed: u64) -> (Surface, Analytic) {
    let base = surface(shape, kind, order, resolution).unwrap();
    let Reference::Analytic(exact) = *base.reference() else { panic!("a generated sample knows its surface") };
    (perturb_surface(&base, amount, seed).unwrap(), exact)
}

/// `s` written in `format` and read back, as a user's file is.
fn through(s: &Surface, format: Format) -> Surface {
    let text = write_model_string(&Model::Surface(s.clone()), format, &WriteOptions::default()).unwrap();
    match read_model_str(&text, format).unwrap() {
        Model::Surface(t) => t,
        _ => panic!("a surface file reads back as a surface"),
    }
}

/// The inverted count before and after each of 3 passes of the defaults.
fn untangle(s: &mut Surface) -> Vec<usize> {
    let mut inverted = vec![s.stats().inverted];
    for _ in 0..3 {
        smooth_surface(s, objective(ObjectiveKind::SmoothShape).as_ref(), SmoothOptions::default(), 1, &|| 0.0).unwrap();
        inverted.push(s.stats().inverted);
    }
    inverted
}

/// The largest distance of a node from the exact surface.
fn farthest(s: &Surface, exact: &Analytic) -> f64 {
    s.points().iter().map(|&p| (exact.project(p, NONE).point - p).length()).fold(0.0, f64::max)
}

#[test]
fn spheres_tangled_by_one_and_a_half_edges_untangle_within_three_passes_on_the_sphere() {
    for kind in [SurfaceKind::Tri, SurfaceKind::Quad] {
        for seed in 1..=4 {
            let (p, exact) = tangled(SurfaceShape::Sphere, kind, 1, 8, 1.5, seed);
            let mut s = through(&p, Format::Vtk);
            assert!(matches!(s.reference(), Reference::Fitted(_)), "a tangled file is fitted: {}", s.reference().describe());
            let inverted = untangle(&mut s);
            assert!(inverted[0] > 50, "{kind:?} seed {seed}: tangled ({inverted:?})");
            assert_eq!(inverted[3], 0, "{kind:?} seed {seed}: inverted per pass {inverted:?}");
            // the sphere's radius is 1
            let far = farthest(&s, &exact);
            assert!(far < 0.02, "{kind:?} seed {seed}: a node {far} from the sphere");
        }
    }
}

#[test]
fn tangled_tori_cylinders_and_quadratic_spheres_untangle_and_keep_their_rims() {
    for (shape, kind, order) in [
        (SurfaceShape::Sphere, SurfaceKind::Mixed, 2),
        (SurfaceShape::Sphere, SurfaceKind::Tri, 2),
        (SurfaceShape::Torus, SurfaceKind::Mixed, 1),
        (SurfaceShape::Cylinder, SurfaceKind::Quad, 1),
        (SurfaceShape::Cylinder, SurfaceKind::Tri, 2),
    ] {
        let resolution = if shape == SurfaceShape::Torus { 6 } else { 4 };
        let (p, exact) = tangled(shape, kind, order, resolution, 1.5, 2);
        let mut s = through(&p, Format::Vtk);
        // the rims: the sample's feature nodes, fixed (a free node may be tangled onto a rim)
        let rims: Vec<usize> = (0..p.node_count()).filter(|&n| p.is_feature(n)).collect();
        assert_eq!(rims.is_empty(), shape != SurfaceShape::Cylinder);
        assert!(rims.iter().all(|&n| s.is_feature(n) && s.flat().is_fixed(n)), "the file's flags keep the rims");
        let before: Vec<_> = rims.iter().map(|&n| s.points()[n]).collect();
        let inverted = untangle(&mut s);
        let name = format!("{shape:?} {kind:?} order {order}");
        assert!(inverted[0] > 0 && inverted[3] == 0, "{name}: inverted per pass {inverted:?}");
        assert!(rims.iter().zip(&before).all(|(&n, &q)| s.points()[n] == q), "{name}: a rim node moved");
        // within 3 % of the radius (1), the torus 5 % of its tube's (0.3; as measured in
        // docs/reproduction.md §9, about 4 %)
        let bound = if shape == SurfaceShape::Torus { 0.05 * 0.3 } else { 0.03 };
        let far = farthest(&s, &exact);
        assert!(far < bound, "{name}: a node {far} from the exact surface");
    }
}

#[test]
fn a_file_without_fixed_flags_takes_no_fold_for_a_crease() {
    for (shape, kind, bound) in [
        (SurfaceShape::Sphere, SurfaceKind::Tri, 0.02),
        (SurfaceShape::Sphere, SurfaceKind::Quad, 0.02),
        (SurfaceShape::Sphere, SurfaceKind::Mixed, 0.02),
        (SurfaceShape::Torus, SurfaceKind::Tri, 0.05 * 0.3),
    ] {
        for seed in [1, 3] {
            let (p, exact) = tangled(shape, kind, 1, 6, 1.5, seed);
            let mut s = through(&p, Format::Off);
            let name = format!("{shape:?} {kind:?} seed {seed}");
            assert!((0..s.node_count()).all(|n| !s.is_feature(n) && !s.flat().is_fixed(n)), "{name}: a fold read as a crease");
            let inverted = untangle(&mut s);
            assert_eq!(inverted[3], 0, "{name}: {inverted:?}");
            assert!(farthest(&s, &exact) < bound, "{name}");
        }
    }
}

#[test]
fn a_valid_surface_file_stays_on_its_facets() {
    for (shape, kind, order) in [(SurfaceShape::Sphere, SurfaceKind::Quad, 1), (SurfaceShape::Torus, SurfaceKind::Mixed, 2)] {
        let (p, _) = tangled(shape, kind, order, 4, 0.2, 1);
        let mut s = through(&p, Format::Vtk);
        assert_eq!(s.stats().inverted, 0);
        assert!(matches!(s.reference(), Reference::Facets(_)), "{}", s.reference().describe());
        smooth_surface(&mut s, objective(ObjectiveKind::SmoothShape).as_ref(), SmoothOptions::default(), 3, &|| 0.0).unwrap();
        let far = s.max_distance_from_reference();
        assert!(far <= 1e-9 * s.size(), "{shape:?}: {far}");
    }
}

#[test]
fn a_tangled_file_counts_the_inverted_elements_the_exact_surface_counts() {
    for (shape, kind) in [(SurfaceShape::Sphere, SurfaceKind::Tri), (SurfaceShape::Torus, SurfaceKind::Quad)] {
        for amount in [0.5, 1.0, 1.5] {
            let (p, _) = tangled(shape, kind, 1, 6, amount, 1);
            let truth = p.stats().inverted;
            let loaded = through(&p, Format::Vtk);
            // the fitted surface passes through the nodes: a file as loaded lies on it
            assert_eq!(loaded.max_distance_from_reference(), 0.0, "{shape:?} {kind:?} {amount}");
            let read = loaded.stats().inverted;
            assert!(read.abs_diff(truth) <= 1, "{shape:?} {kind:?} {amount}: {read} inverted against the surface's {truth}");
        }
    }
}

#[test]
fn a_fitted_reference_projects_near_the_nodes_from_anywhere() {
    let (p, _) = tangled(SurfaceShape::Cylinder, SurfaceKind::Mixed, 1, 4, 1.5, 4);
    let s = through(&p, Format::Off);
    let Reference::Fitted(fitted) = s.reference() else { panic!("{}", s.reference().describe()) };
    let spacing = s.mean_edge_length();
    let mut rng = smoothlab::numeric::SplitMix64::new(7);
    for n in 0..s.node_count() {
        for _ in 0..8 {
            let offset = rng.in_unit_ball() * 3.0 * spacing;
            let q = fitted.project(s.points()[n] + offset, fitted.fit_at_node(n));
            assert!(q.point.is_finite() && (q.normal.length() - 1.0).abs() < 1e-9, "node {n}: {q:?}");
            let nearest = s.points().iter().map(|&x| (x - q.point).length()).fold(f64::INFINITY, f64::min);
            assert!(nearest < 4.0 * spacing, "node {n}: a projection {nearest} from every node");
        }
    }
}

/// The max-min objective throws nodes through the folds; each is still put on the fitted
/// surface, and stays there when projected again (a projection that walked the tangled
/// mesh's rings, neighbours in the mesh but not in space, left nodes 0.1 off it and 4 %
/// off the sphere).
#[test]
fn the_old_objective_keeps_a_tangled_sphere_on_its_fitted_surface() {
    use smoothlab::smooth::Strategy;
    for seed in 1..=3 {
        let (p, exact) = tangled(SurfaceShape::Sphere, SurfaceKind::Tri, 1, 8, 1.5, seed);
        let mut s = through(&p, Format::Vtk);
        let opts = SmoothOptions::default().with_strategy(Strategy::Opt);
        smooth_surface(&mut s, objective(ObjectiveKind::MaxMinShape).as_ref(), opts, 3, &|| 0.0).unwrap();
        let off = s.max_distance_from_reference();
        assert!(off < 1e-3, "seed {seed}: a node {off} off the fitted surface it was put on");
        let far = farthest(&s, &exact);
        assert!(far < 0.01, "seed {seed}: a node {far} off the sphere");
    }
}
