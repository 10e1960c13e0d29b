use glam::DVec3;

use super::*;
use crate::error::Error;
use crate::generate::tet_cube;

#[test]
fn a_cube_of_six_tetrahedra_by_hand() {
    let m = tet_cube(1).unwrap();
    assert_eq!((m.node_count(), m.element_count()), (8, 6));
    // every corner of the cube is on the boundary: nothing to smooth
    assert_eq!(m.free_count(), 0);
    // 12 boundary triangles (2 per cube face), total volume 1, all positive
    assert_eq!(m.boundary_faces().len(), 12);
    let v: f64 = (0..6).map(|e| q3::signed_volume(&m.tet_corners(e))).sum();
    assert!((v - 1.0).abs() < 1e-15);
    assert!((0..6).all(|e| q3::signed_volume(&m.tet_corners(e)) > 0.0));
    // Kuhn's six share the main diagonal 0–7: those two nodes are in every tetrahedron
    // and are neighbours of all others
    assert_eq!(m.node_tets(0).len(), 6);
    assert_eq!(m.node_tets(7).len(), 6);
    assert_eq!(m.neighbours(0), &[1, 2, 3, 4, 5, 6, 7]);
    // a cube corner off the diagonal (1 = x) is in the two tetrahedra of the paths
    // x→xy and x→xz, with neighbours 0, 3 (xy), 5 (xz) and 7
    assert_eq!(m.node_tets(1).len(), 2);
    assert_eq!(m.neighbours(1), &[0, 3, 5, 7]);
}

#[test]
fn a_grid_of_two_cubes_a_side_has_one_free_node() {
    let m = tet_cube(2).unwrap();
    assert_eq!((m.node_count(), m.element_count()), (27, 48));
    let free: Vec<usize> = (0..27).filter(|&n| m.is_free(n)).collect();
    assert_eq!(free, vec![13]); // the centre (1,1,1) of the 3×3×3 lattice
    assert_eq!(m.nodes()[13], DVec3::splat(0.5));
    assert_eq!(m.boundary_faces().len(), 6 * 8);
    // the boundary faces point outward: their area vectors sum to zero, and each one's
    // normal points away from the centre
    for f in m.boundary_faces() {
        let [a, b, c] = f.as_triangle().unwrap().map(|i| m.nodes()[i as usize]);
        let n = (b - a).cross(c - a);
        assert!(n.dot((a + b + c) / 3.0 - DVec3::splat(0.5)) > 0.0);
    }
}

fn parts(nodes: Vec<DVec3>, elements: Vec<u32>) -> SolidParts {
    SolidParts {
        node_lines: (0..nodes.len() as u32).map(|i| i + 2).collect(),
        element_lines: (0..(elements.len() / 4) as u32).map(|i| i + 100).collect(),
        nodes,
        kinds: vec![VolumeKind::Tet4; elements.len() / 4],
        elements,
        fixed: FixedSpec::Boundary,
        faces: Vec::new(),
    }
}

fn unit() -> Vec<DVec3> {
    vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z, DVec3::ONE]
}

#[test]
fn bad_input_gives_errors_naming_the_node_or_element_and_line() {
    let err = |p: SolidParts| VolumeMesh::build(p).unwrap_err().to_string();
    assert_eq!(err(parts(unit(), vec![])), Error::Empty("the mesh has no volume elements".into()).to_string());
    let mut nan = unit();
    nan[2].y = f64::NAN;
    assert!(
        err(parts(nan, vec![0, 1, 2, 3])).starts_with("node 2 (line 4): coordinate"),
        "{}",
        err(parts(unit(), vec![]))
    );
    let e = err(parts(unit(), vec![0, 1, 2, 9]));
    assert!(e.starts_with("element 0 (line 100): node 9 does not exist: the mesh has 5 nodes"), "{e}");
    let e = err(parts(unit(), vec![0, 1, 2, 3, 0, 1, 1, 4]));
    assert!(e.starts_with("element 1 (line 101): node 1 appears twice"), "{e}");
    let mut flat = unit();
    flat[3] = DVec3::new(0.3, 0.3, 0.0);
    let e = err(parts(flat, vec![0, 1, 2, 3]));
    assert!(e.starts_with("element 0 (line 100): the tetrahedron has no volume"), "{e}");
    // three tetrahedra on one face
    let mut three = unit();
    three.push(DVec3::new(0.2, 0.2, -1.0));
    three.push(DVec3::new(0.2, 0.2, 2.0));
    let e = err(parts(three, vec![0, 1, 2, 3, 0, 2, 1, 5, 0, 1, 2, 6]));
    assert!(e.contains("its face [0, 1, 2] is a face of 3 elements"), "{e}");
}

#[test]
fn a_left_handed_mesh_is_turned_over() {
    // every tetrahedron given with negative volume: the file's convention
    let m = tet_cube(2).unwrap();
    let mirrored: Vec<u32> = (0..m.element_count())
        .flat_map(|e| {
            let t = m.element(e);
            [t[0], t[2], t[1], t[3]]
        })
        .collect();
    let turned = VolumeMesh::build(parts(m.nodes().to_vec(), mirrored)).unwrap();
    assert!((0..turned.element_count()).all(|e| q3::signed_volume(&turned.tet_corners(e)) > 0.0));
    // a single inverted tetrahedron in a right-handed mesh stays inverted (tangled)
    let mut tangled = m.nodes().to_vec();
    tangled[13] = DVec3::new(1.2, 0.5, 0.5);
    let t =
        VolumeMesh::build(parts(tangled, (0..m.element_count()).flat_map(|e| m.element(e).to_vec()).collect())).unwrap();
    assert!((0..t.element_count()).any(|e| q3::signed_volume(&t.tet_corners(e)) < 0.0));
}

mod smoothing {
    use super::*;
    use crate::generate::perturb_volume;
    use crate::objective::{solid_objective, ObjectiveKind};
    use crate::smooth::{SmoothOptions, Strategy};

    fn no_clock() -> f64 {
        0.0
    }

    fn passes(mesh: &mut VolumeMesh, kind: ObjectiveKind, strategy: Strategy, n: u32) -> Vec<crate::smooth::PassRecord> {
        let o = SmoothOptions::default().with_strategy(strategy);
        smooth_volume(mesh, &*solid_objective(kind).unwrap(), o, n, &no_clock).unwrap()
    }

    #[test]
    fn every_strategy_and_objective_keeps_fixed_nodes_and_repeats_exactly() {
        let start = perturb_volume(&tet_cube(3).unwrap(), 0.6, 4).unwrap();
        for strategy in Strategy::ALL {
            for kind in crate::objective::solid_kinds() {
                let mut a = start.clone();
                let mut b = start.clone();
                passes(&mut a, kind, strategy, 2);
                passes(&mut b, kind, strategy, 2);
                assert_eq!(a.nodes(), b.nodes(), "{strategy:?} {kind}: not deterministic");
                for n in 0..a.node_count() {
                    assert!(a.nodes()[n].is_finite(), "{strategy:?} {kind}: node {n} {}", a.nodes()[n]);
                    if !a.is_free(n) {
                        assert_eq!(a.nodes()[n], start.nodes()[n], "{strategy:?} {kind}: fixed node {n} moved");
                    }
                }
            }
        }
    }

    #[test]
    fn no_valid_tetrahedron_is_inverted_by_the_smart_or_guarded_strategies() {
        let start = perturb_volume(&tet_cube(4).unwrap(), 0.25, 2).unwrap();
        assert_eq!(volume_stats(&start).inverted, 0, "the start must be valid");
        for strategy in [Strategy::Smart, Strategy::Opt, Strategy::C1, Strategy::C2, Strategy::C3, Strategy::Rules] {
            for kind in crate::objective::solid_kinds() {
                let mut m = start.clone();
                passes(&mut m, kind, strategy, 2);
                assert_eq!(volume_stats(&m).inverted, 0, "{strategy:?} {kind}");
            }
        }
    }

    #[test]
    fn new_with_rules_untangles_a_tangled_cube_and_improves_it() {
        for seed in 1..=3 {
            let mut m = perturb_volume(&tet_cube(4).unwrap(), 0.8, seed).unwrap();
            let before = volume_stats(&m);
            assert!(before.inverted > 0, "seed {seed}: not tangled");
            let records = passes(&mut m, ObjectiveKind::SmoothShape, Strategy::Rules, 3);
            let after = volume_stats(&m);
            assert_eq!(after.inverted, 0, "seed {seed}: {} inverted after 3 passes ({records:?})", after.inverted);
            assert!(after.min_angle_deg > 5.0, "seed {seed}: {}", after.min_angle_deg);
        }
    }

    #[test]
    fn smart_laplacian_improves_the_worst_tetrahedron_of_each_star() {
        let start = perturb_volume(&tet_cube(4).unwrap(), 0.3, 7).unwrap();
        let mut m = start.clone();
        let o = SmoothOptions::default().with_strategy(Strategy::Smart);
        let mut s = VolumeSmoother::new(o).unwrap();
        s.sweep(&mut m, &*solid_objective(ObjectiveKind::SmoothShape).unwrap());
        assert!(volume_stats(&m).min_quality >= volume_stats(&start).min_quality);
        assert!(m.nodes() != start.nodes());
    }
}

/// Issue 29: `untangle` and `untangle-mindet` moved the nodes of valid tetrahedral meshes
/// (a tetrahedron of 10.18° ended at 0.99°); they now leave a valid mesh where it is.
#[test]
fn untangling_objectives_leave_a_valid_tetrahedral_mesh_where_it_is() {
    use crate::objective::{solid_objective, ObjectiveKind};
    use crate::smooth::{SmoothOptions, Strategy};
    let valid = crate::generate::rand3d(200, 5).unwrap();
    assert_eq!(volume_stats(&valid).inverted, 0);
    for kind in [ObjectiveKind::Untangle, ObjectiveKind::UntangleMinDet] {
        let mut m = valid.clone();
        let opts = SmoothOptions::default().with_strategy(Strategy::Opt);
        let r = smooth_volume(&mut m, &*solid_objective(kind).unwrap(), opts, 2, &|| 0.0).unwrap();
        assert_eq!(m.nodes(), valid.nodes(), "{kind}");
        assert_eq!(r[0].counts.optimization_calls, 0, "{kind}");
    }
}

/// Issue 29: a cube of tetrahedra scaled by 1e100 reported dihedral angles 90°/90°, by
/// 1e-100 "min inf° max −inf°", by 1e-80 45.19°, and by 1e150 was refused as flat. Every
/// statistic is now the same at every scale, as the planar ones are (2^±200 measured as
/// given, beyond it in the tetrahedron's own scale).
#[test]
fn statistics_are_the_same_at_every_scale() {
    let base = tet_cube(2).unwrap();
    let tets: Vec<[u32; 4]> = (0..base.element_count()).map(|e| base.element(e)[..4].try_into().unwrap()).collect();
    let unit = volume_stats(&base);
    assert!((unit.min_angle_deg - 45.0).abs() < 1e-9 && (unit.max_angle_deg - 90.0).abs() < 1e-9, "{unit:?}");
    for s in [1e-300, 1e-150, 1e-100, 1e-80, 2f64.powi(-201), 1e-20, 1e20, 2f64.powi(201), 1e80, 1e100, 1e150, 1e300] {
        let m = VolumeMesh::from_tets(base.nodes().iter().map(|&p| p * s).collect(), &tets).unwrap();
        let st = volume_stats(&m);
        let near = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs().max(1.0);
        assert_eq!(st.inverted, 0, "scale {s:e}");
        assert!(near(st.min_angle_deg, unit.min_angle_deg) && near(st.max_angle_deg, unit.max_angle_deg), "scale {s:e}: {st:?}");
        assert!(near(st.min_quality, unit.min_quality) && near(st.mean_quality, unit.mean_quality), "scale {s:e}: {st:?}");
        assert!(near(st.max_condition, unit.max_condition), "scale {s:e}: {st:?}");
        assert_eq!(st.angle_histogram_6deg, unit.angle_histogram_6deg, "scale {s:e}");
    }
    // exact powers of two give the same bits
    let m = VolumeMesh::from_tets(base.nodes().iter().map(|&p| p * 2f64.powi(-300)).collect(), &tets).unwrap();
    assert_eq!(volume_stats(&m).min_quality.to_bits(), unit.min_quality.to_bits());
}

/// Issue 29: a 10-node tetrahedron whose mid-edge node sits far off its edge measured as
/// the straight one. Measured with its mid-edge nodes (the corner Jacobians), a straight
/// one measures as its corners (but for rounding), a bent one worse, and one whose
/// mid-edge node crosses its far corner's plane as inverted.
#[test]
fn a_ten_node_tetrahedron_is_measured_with_its_mid_edge_nodes() {
    use crate::quality::solid::{tet10_measures, tet_measures};
    use crate::quality::tet::{CornerReference, EQUILATERAL_TET};
    const R: &CornerReference = &EQUILATERAL_TET;
    let c = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
    let mut p = [DVec3::ZERO; 10];
    p[..4].copy_from_slice(&c);
    for (m, [a, b]) in TET10_EDGES.iter().enumerate() {
        p[4 + m] = 0.5 * (c[*a] + c[*b]);
    }
    let (straight, linear) = (tet10_measures(&p, R), tet_measures(&c, R));
    assert!(!straight.inverted);
    assert!((straight.mean_ratio - linear.mean_ratio).abs() < 1e-15, "{straight:?} {linear:?}");
    assert!((straight.min_dihedral_deg - linear.min_dihedral_deg).abs() < 1e-12);
    // the mid-edge node of edge 0–1 pushed off its edge towards corner 2
    let mut bent = p;
    bent[4] += 0.2 * DVec3::Y;
    let b = tet10_measures(&bent, R);
    assert!(!b.inverted && b.mean_ratio < linear.mean_ratio - 0.05, "{b:?}");
    // slid along its edge past the quarter point: the Jacobian at corner 0 turns over
    bent[4] = DVec3::new(0.1, 0.0, 0.0);
    assert!(tet10_measures(&bent, R).inverted);
    // and the mesh's statistics say so
    let mesh = VolumeMesh::build(SolidParts {
        nodes: bent.to_vec(),
        node_lines: Vec::new(),
        kinds: vec![VolumeKind::Tet10],
        elements: (0..10).collect(),
        element_lines: Vec::new(),
        fixed: FixedSpec::Boundary,
        faces: Vec::new(),
    })
    .unwrap();
    assert_eq!(crate::volume::volume_stats(&mesh).inverted, 1);
}

/// A block of `n³` hexahedra (`generate hexgrid`), its free nodes moved by `jitter` mean
/// edge lengths (seeded).
pub(super) fn hex_block(n: usize, jitter: f64, seed: u64) -> VolumeMesh {
    let block = crate::generate::hex_grid(&crate::generate::HexBlock::cube(n)).unwrap();
    crate::generate::perturb_volume(&block, jitter, seed).unwrap()
}

#[test]
fn quadratic_hexahedra_follow_their_corners() {
    let linear = hex_block(3, 0.2, 5);
    for (serendipity, kind, nodes) in [(true, VolumeKind::Hex20, 20), (false, VolumeKind::Hex27, 27)] {
        let mut q = linear.to_quadratic(serendipity).unwrap();
        assert_eq!(q.kinds(), &[kind]);
        assert_eq!(q.element(0).len(), nodes);
        // shared: 4³ corners, 3·3·4² edges' middles (and 3·3·4 faces', 27 centres)
        let (edges, faces, centres) = (3 * 3 * 16, 3 * 4 * 9, 27);
        let expect = 64 + edges + if serendipity { 0 } else { faces + centres };
        assert_eq!(q.node_count(), expect, "{kind:?}");
        assert_eq!(q.free_count(), linear.free_count());
        let before = crate::volume::volume_stats(&q);
        assert_eq!((before.inverted, before.quadratic), (0, 27));
        crate::volume::smooth_volume(&mut q, &*crate::objective::solid_objective(crate::objective::ObjectiveKind::SmoothShape).unwrap(), Default::default(), 2, &|| 0.0).unwrap();
        // every follower at the mean of its corners, boundary ones where they were
        for e in 0..q.element_count() {
            let ids = q.element(e);
            for (m, ps) in kind.row().followers.iter().enumerate() {
                let at = ps.iter().map(|&c| q.nodes()[ids[c] as usize]).sum::<DVec3>() / ps.len() as f64;
                assert!(at.distance(q.nodes()[ids[8 + m] as usize]) < 1e-12, "{kind:?} element {e} follower {m}");
            }
        }
        let after = crate::volume::volume_stats(&q);
        assert!(after.inverted == 0 && after.min_quality >= before.min_quality);
    }
    // wedges have no quadratic kind here: refused in words
    let wedge = VolumeMesh::from_elements(
        vec![DVec3::ZERO, DVec3::new(0.5, 0.8, 0.0), DVec3::X, DVec3::Z, DVec3::new(0.5, 0.8, 1.0), DVec3::new(1.0, 0.0, 1.0)],
        [(VolumeKind::Wedge6, &[0u32, 1, 2, 3, 4, 5][..])],
    )
    .unwrap();
    assert!(wedge.to_quadratic(false).unwrap_err().to_string().contains("wedges have no quadratic kind"));
}

#[test]
fn a_mixed_mesh_of_a_quadratic_kind_and_another_is_refused_naming_the_line() {
    let mut b = crate::mesh::MeshBuilder::new();
    for p in [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z] {
        b.add_node([p.x, p.y, p.z], 0);
    }
    b.add_volume_element(VolumeKind::Tet4, &[0, 1, 2, 3], 7).unwrap();
    let e = b.add_volume_element(VolumeKind::Hex20, &[0; 20], 8).unwrap_err().to_string();
    assert!(e.contains("line 8") && e.contains("a quadratic mesh is of one kind"), "{e}");
    // linear kinds mix
    assert!(b.add_volume_element(VolumeKind::Hex8, &[0; 8], 9).is_ok());
}

/// The stream of each node's tetrahedra's other corners is the elements' own, in the order
/// of the node's edges, in a mesh of every kind; empty without tetrahedra.
#[test]
fn the_tetrahedra_corner_stream_is_the_elements() {
    let mesh = crate::generate::mixed_block(&crate::generate::HexBlock::cube(3)).unwrap();
    let mut tets = 0;
    for n in 0..mesh.node_count() {
        let corners = mesh.node_tet_corners(n);
        assert_eq!(corners.len(), mesh.node_tets(n).len());
        for (&e, others) in mesh.node_tets(n).iter().zip(corners) {
            let (kind, ids) = (mesh.element_kind(e as usize), mesh.element(e as usize));
            if !kind.is_tet() {
                assert_eq!(*others, [u32::MAX; 3]);
                continue;
            }
            tets += 1;
            let slot = ids[..4].iter().position(|&i| i as usize == n).unwrap();
            assert_eq!(*others, kind.row().corner_edges[slot].map(|k| ids[k]));
        }
    }
    assert!(tets > 0, "the mixed block has tetrahedra");
    assert!(hex_block(2, 0.0, 1).node_tet_corners(13).is_empty());
}
