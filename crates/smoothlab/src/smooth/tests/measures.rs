//! The drivers' own measures and fast paths: each answers as the general measure does.

use glam::DVec2;

use super::*;
use crate::quality::{element_quality, mesh_stats};

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
            let direct = crate::smooth::smart_on_triangles(&mesh, n, Measure::Shape).expect("a star of linear triangles");
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
    assert!((0..quads.node_count()).filter(|&n| quads.is_free(n)).all(|n| crate::smooth::smart_on_triangles(
        &quads,
        n,
        Measure::Shape
    )
    .is_none()));
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
