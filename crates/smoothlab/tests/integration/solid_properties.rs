//! Issue 31: hexahedra, wedges, pyramids and mixed meshes, smoothed by the drivers of the
//! planar core over Knupp's corner tetrahedra:
//!
//! 1. On a valid mesh of any kind, no strategy but the plain Laplacian inverts an element
//!    (certain validity: the Bernstein coefficients of det J, not the corners alone) or
//!    lowers the worst element's shape (the mean of its corners' mean ratios); fixed nodes
//!    never move; runs repeat bit for bit.
//! 2. Knupp-style random hexahedral grids, every free node moved up to 0.6 mean edge
//!    lengths, end with 0 inverted within 3 passes of the defaults and a smallest corner
//!    scaled Jacobian ≥ 0.3.
//! 3. Every objective's gradient on a star of hexahedral, wedge and pyramid corners agrees
//!    with central differences (the slot references measure the same corner from the
//!    moved node).

use glam::DVec3;
use proptest::prelude::*;
use smoothlab::generate::{hex_grid, mixed_block, perturb_volume, HexBlock};
use smoothlab::mesh::VolumeKind;
use smoothlab::objective::{solid_kinds, solid_objective, CornerStar, ObjectiveKind, CONDITION_BARRIER};
use smoothlab::smooth::{DriverStar, SmoothOptions, Strategy};
use smoothlab::volume::{smooth_volume, volume_stats, VolumeMesh};

/// A block of `n³` cells of the project's generators: hexahedra, or (`mix`) the mixed
/// block of hexahedra, wedges, pyramids and tetrahedra.
fn block(n: usize, mix: bool) -> VolumeMesh {
    let b = HexBlock::cube(n);
    if mix {
        mixed_block(&b).unwrap()
    } else {
        hex_grid(&b).unwrap()
    }
}

fn smoothed(m: &VolumeMesh, strategy: Strategy, kind: ObjectiveKind, passes: u32) -> VolumeMesh {
    let mut t = m.clone();
    smooth_volume(&mut t, &*solid_objective(kind).unwrap(), SmoothOptions::default().with_strategy(strategy), passes, &|| 0.0)
        .unwrap();
    t
}

#[test]
fn the_blocks_are_what_they_say() {
    let hex = block(3, false);
    assert_eq!((hex.element_count(), hex.kinds()), (27, &[VolumeKind::Hex8][..]));
    assert_eq!(hex.free_count(), 8);
    assert_eq!(hex.boundary_faces().len(), 6 * 9);
    let mixed = block(3, true);
    assert_eq!(mixed.kinds(), &[VolumeKind::Tet4, VolumeKind::Hex8, VolumeKind::Wedge6, VolumeKind::Pyramid5]);
    for m in [&hex, &mixed] {
        assert_eq!(volume_stats(m).inverted, 0);
    }
    assert!((volume_stats(&hex).solid.unwrap().min_scaled_jacobian - 1.0).abs() < 1e-12);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn valid_meshes_of_every_kind_never_get_worse(
        mix in any::<bool>(),
        amount in 0.05..0.2f64,
        seed in 0u64..1000,
        strategy in 0..Strategy::ALL.len(),
        objective_kind in 0..solid_kinds().count(),
    ) {
        let m = perturb_volume(&block(3, mix), amount, seed).unwrap();
        let before = volume_stats(&m);
        prop_assume!(before.inverted == 0);
        let (strategy, kind) = (Strategy::ALL[strategy], solid_kinds().nth(objective_kind).unwrap());
        let t = smoothed(&m, strategy, kind, 2);
        for n in 0..m.node_count() {
            prop_assert!(t.nodes()[n].is_finite(), "node {} not finite", n);
            if !m.is_free(n) {
                prop_assert_eq!(t.nodes()[n], m.nodes()[n], "fixed node {} moved", n);
            }
        }
        let again = smoothed(&m, strategy, kind, 2);
        prop_assert_eq!(again.nodes(), t.nodes());
        if strategy != Strategy::Laplace {
            let after = volume_stats(&t);
            prop_assert_eq!(after.inverted, 0, "{:?} {} inverted an element", strategy, kind);
            prop_assert!(
                after.min_quality >= before.min_quality,
                "{:?} {}: worst shape {} → {}", strategy, kind, before.min_quality, after.min_quality
            );
        }
    }
}

#[test]
fn knupp_random_hex_grids_tangled_by_0_6_edges_untangle_in_three_passes() {
    let mut report = Vec::new();
    for seed in 1..=6 {
        let m = perturb_volume(&block(6, false), 0.6, seed).unwrap();
        let before = volume_stats(&m).inverted;
        assert!(before > 0, "seed {seed}: not tangled");
        let mut t = m.clone();
        let options = SmoothOptions::default();
        let records = smooth_volume(&mut t, &*solid_objective(ObjectiveKind::SmoothShape).unwrap(), options, 3, &|| 0.0).unwrap();
        let s = volume_stats(&t);
        let sj = s.solid.as_ref().unwrap().min_scaled_jacobian;
        report.push(format!("seed {seed}: {before} → {:?}, min scaled Jacobian {sj:.3}", records.iter().map(|r| r.after.inverted).collect::<Vec<_>>()));
        assert_eq!(s.inverted, 0, "{report:?}");
        assert!(sj >= 0.3, "{report:?}");
    }
    eprintln!("{}", report.join("\n"));
}

/// A star gathered from a perturbed mesh of `kind`'s block, at its first free node.
fn stars(mix: bool, seed: u64) -> Vec<CornerStar> {
    let m = perturb_volume(&block(3, mix), 0.3, seed).unwrap();
    (0..m.node_count())
        .filter(|&n| m.is_free(n))
        .map(|n| {
            let mut s = CornerStar::default();
            s.gather(&m, n);
            s
        })
        .collect()
}

#[test]
fn every_objective_gradient_agrees_with_central_differences_on_corner_stars() {
    let h = 1e-6;
    let mut checked = 0;
    for (mix, seed) in [(false, 1), (true, 2), (true, 3)] {
        for star in stars(mix, seed) {
            assert!(!star.only_tets());
            for k in solid_kinds() {
                let obj = solid_objective(k).unwrap();
                let x = star.x0 + DVec3::new(0.003, -0.002, 0.001);
                let mut terms = Vec::new();
                obj.terms(&star, x, &mut terms);
                for (i, t) in terms.iter().enumerate() {
                    if t.value.abs() >= CONDITION_BARRIER || !t.value.is_finite() {
                        continue;
                    }
                    let at = |y: DVec3| {
                        let mut v = Vec::new();
                        obj.terms(&star, y, &mut v);
                        v[i].value
                    };
                    let mut fd = DVec3::ZERO;
                    for c in 0..3 {
                        let mut e = DVec3::ZERO;
                        e[c] = h;
                        fd[c] = (at(x + e) - at(x - e)) / (2.0 * h);
                    }
                    let scale = t.grad.length().max(fd.length()).max(1e-3);
                    assert!((fd - t.grad).length() <= 1e-5 * scale, "{k} term {i}: {} vs {fd}", t.grad);
                    checked += 1;
                }
            }
        }
    }
    assert!(checked > 1000, "{checked}");
}

/// The regular 10-node tetrahedron of unit edge (VTK's order: corners, then the middles of
/// edges 01, 12, 02, 03, 13, 23).
fn regular_tet10() -> [DVec3; 10] {
    let c = [DVec3::ZERO, DVec3::X, DVec3::new(0.5, 3f64.sqrt() / 2.0, 0.0), DVec3::new(0.5, 3f64.sqrt() / 6.0, (2.0f64 / 3.0).sqrt())];
    let mut p = [DVec3::ZERO; 10];
    p[..4].copy_from_slice(&c);
    for (m, [a, b]) in [[0, 1], [1, 2], [0, 2], [0, 3], [1, 3], [2, 3]].into_iter().enumerate() {
        p[4 + m] = (c[a] + c[b]) * 0.5;
    }
    p
}

/// Issue 61, finding 4: a 10-node tetrahedron turned inside out by a mid-edge node read
/// inverted 1 and mean ratio < 0, but scaled Jacobian 1.0000 and the ideal 70.53° dihedral
/// angles. Every statistic is now taken over the same four tetrahedra of its Jacobian at
/// the corners, signed alike.
#[test]
fn a_ten_node_tetrahedron_inverted_by_a_mid_edge_node_reads_inverted_in_every_statistic() {
    let mut p = regular_tet10();
    // the middle of edge 01 moved to a tenth of the way: the tangent at corner 0 turns back
    p[4] = p[0] + (p[1] - p[0]) * 0.1;
    let m = VolumeMesh::from_elements(p.to_vec(), [(VolumeKind::Tet10, &(0..10).collect::<Vec<u32>>()[..])]).unwrap();
    let s = volume_stats(&m);
    assert_eq!(s.inverted, 1);
    assert!(s.min_quality < 0.0, "mean ratio {}", s.min_quality);
    let solid = s.solid.expect("a volume mesh has solid statistics");
    assert!(solid.min_scaled_jacobian <= 0.0, "scaled Jacobian {}", solid.min_scaled_jacobian);
    assert!(s.min_angle_deg < 0.0, "dihedral angles {}–{}", s.min_angle_deg, s.max_angle_deg);
    // and a straight one reads as the regular tetrahedron
    let s = volume_stats(&VolumeMesh::from_elements(regular_tet10().to_vec(), [(VolumeKind::Tet10, &(0..10).collect::<Vec<u32>>()[..])]).unwrap());
    assert_eq!(s.inverted, 0);
    assert!((s.solid.unwrap().min_scaled_jacobian - 1.0).abs() < 1e-12 && (s.min_angle_deg - 70.528_779_365_509_3).abs() < 1e-9);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// The class: for a tetrahedron of 4 or 10 nodes, however its nodes lie, inverted ⇔
    /// scaled Jacobian ≤ 0 ⇔ mean ratio ≤ 0 ⇔ smallest dihedral angle ≤ 0: no statistic
    /// reads an inverted element as valid or a valid one as inverted.
    #[test]
    fn every_statistic_of_a_tetrahedron_agrees_on_inversion(
        quadratic in any::<bool>(),
        moves in prop::collection::vec((-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0), 10),
        amount in 0.0f64..1.2,
    ) {
        let mut p = regular_tet10();
        for (q, (x, y, z)) in p.iter_mut().zip(&moves) {
            *q += DVec3::new(*x, *y, *z) * amount;
        }
        let (kind, n) = if quadratic { (VolumeKind::Tet10, 10) } else { (VolumeKind::Tet4, 4) };
        let m = smoothlab::quality::solid::solid_measures(kind, &p[..n]);
        prop_assume!(m.mean_ratio.is_finite() && m.min_dihedral_deg.is_finite());
        prop_assert_eq!(m.inverted, m.scaled_jacobian <= 0.0, "{:?}", m);
        prop_assert_eq!(m.inverted, m.mean_ratio <= 0.0, "{:?}", m);
        prop_assert_eq!(m.inverted, m.min_dihedral_deg <= 0.0, "{:?}", m);
    }
}

/// Issue 61, finding 2: a 4×4×4 block of hexahedra with one interior node moved to
/// x = 1e61 read min mean ratio −3.66e−83 (exact: 0.5: the four corners away from the far
/// node are the cube's, the other four degenerate): the element was moved to its first
/// corner before it was scaled, and the differences of differences lost its small corners.
#[test]
fn a_hexahedral_block_with_a_node_far_off_reads_what_it_is() {
    let base = block(4, false);
    let node = (0..base.node_count()).find(|&n| base.nodes()[n] == DVec3::splat(0.5)).expect("the centre node");
    let mut m = base.clone();
    m.nodes_mut()[node].x = 1e61;
    let s = volume_stats(&m);
    assert_eq!(s.inverted, 4, "the four cells the node crossed");
    assert!((s.min_quality - 0.5).abs() < 1e-12, "min mean ratio {:e}", s.min_quality);
}

/// `m` with every node multiplied by 2^`k` (exact).
fn scaled(m: &VolumeMesh, k: i32) -> VolumeMesh {
    let mut t = m.clone();
    for p in t.nodes_mut() {
        *p *= 2f64.powi(k);
    }
    t
}

/// Issue 61, finding 3: a perturbed mixed block (29 nodes, 87 coordinates) smoothed at
/// unit scale and the same block × 2^520 differed in 9 coordinates. With the defaults
/// (rules, new, 3 passes), tangled or not, at 2^±520 and 2^±600: the same nodes to the bit.
/// So with Freitag's C2 and C3, which differed on tangled blocks after a Laplacian move.
#[test]
fn a_mixed_block_is_smoothed_alike_at_every_scale() {
    for seed in 0..8 {
        for amount in [0.2, 0.5, 0.9, 1.0] {
            let m = perturb_volume(&block(2, true), amount, seed).unwrap();
            for strategy in [Strategy::Rules, Strategy::C2, Strategy::C3] {
                let unit = smoothed(&m, strategy, ObjectiveKind::SmoothShape, 3);
                for k in [-600, -520, 520, 600] {
                    let back = scaled(&smoothed(&scaled(&m, k), strategy, ObjectiveKind::SmoothShape, 3), -k);
                    let differ = (0..m.node_count()).filter(|&n| unit.nodes()[n] != back.nodes()[n]).count();
                    assert_eq!(differ, 0, "seed {seed}, amount {amount}, {strategy:?}, 2^{k}: {differ} of {} nodes differ", m.node_count());
                }
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Issue 61, findings 2 and 3, the class: every volume mesh differed beyond
    /// 2^±512–530. Volume statistics are scale-free to the bit, as the planar ones are
    /// (`docs/formulas.md` §6), at 2^±300, 2^±520 and 2^±600, tangled or not; so are the
    /// drivers, every strategy × objective, on meshes perturbed by up to a third of an edge
    /// and tangled ones (up to a whole edge). Before, `c2` and `c3` on tangled meshes
    /// differed in 156 of 10,584 probe runs: the rule's inversions in mesh units, and
    /// corner forms taken afresh where a Laplacian move had left the node.
    #[test]
    fn volumes_are_scale_free_to_the_bit(
        which in 0usize..3,
        amount in 0.05f64..1.0,
        seed in 0u64..1000,
        k in prop::sample::select(vec![-600, -520, -300, 300, 520, 600]),
        strategy in 0..Strategy::ALL.len(),
        objective_kind in 0..solid_kinds().count(),
    ) {
        let base = match which {
            0 => block(2, true),
            1 => block(2, false),
            _ => smoothlab::generate::tet_cube(2).unwrap(),
        };
        let m = perturb_volume(&base, amount, seed).unwrap();
        let big = scaled(&m, k);
        let (a, b) = (volume_stats(&m), volume_stats(&big));
        prop_assert_eq!(a.inverted, b.inverted);
        prop_assert_eq!(a.min_quality.to_bits(), b.min_quality.to_bits(), "{} {}", a.min_quality, b.min_quality);
        prop_assert_eq!(a.min_angle_deg.to_bits(), b.min_angle_deg.to_bits());
        prop_assert_eq!(&a.angle_histogram_6deg, &b.angle_histogram_6deg);
        prop_assert_eq!(a.solid.map(|s| s.min_scaled_jacobian.to_bits()), b.solid.map(|s| s.min_scaled_jacobian.to_bits()));
        let (strategy, kind) = (Strategy::ALL[strategy], solid_kinds().nth(objective_kind).unwrap());
        let (sa, sb) = (smoothed(&m, strategy, kind, 2), smoothed(&big, strategy, kind, 2));
        let back = scaled(&sb, -k);
        let differ = (0..m.node_count()).filter(|&n| sa.nodes()[n] != back.nodes()[n]).count();
        prop_assert_eq!(differ, 0, "{} of {} nodes differ at 2^{} ({:?}, {:?})", differ, m.node_count(), k, strategy, kind);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(100))]

    /// Issue 61, finding 9, the class: on tangled blocks of every kind, no pass of a
    /// strategy under the acceptance rule ends with more inverted elements than it began
    /// with. (These small blocks did not show the increase without the pass's check in
    /// 150 runs; bust does, `io_livesu`. Here the check is held to its promise on every
    /// kind, strategy and objective, the rollback included.)
    #[test]
    fn no_guarded_pass_ends_with_more_inverted_elements(
        which in 0usize..3,
        amount in 0.5f64..1.2,
        seed in 0u64..1000,
        strategy in prop::sample::select(vec![Strategy::Rules, Strategy::Opt, Strategy::Smart, Strategy::C1, Strategy::C3]),
        objective_kind in 0..solid_kinds().count(),
    ) {
        let base = match which {
            0 => block(3, true),
            1 => block(3, false),
            _ => smoothlab::generate::tet_cube(3).unwrap(),
        };
        let mut m = perturb_volume(&base, amount, seed).unwrap();
        let mut last = volume_stats(&m).inverted;
        let kind = solid_kinds().nth(objective_kind).unwrap();
        let records = smooth_volume(&mut m, &*solid_objective(kind).unwrap(), SmoothOptions::default().with_strategy(strategy), 6, &|| 0.0).unwrap();
        for r in records {
            prop_assert!(r.after.inverted <= last, "{:?} {:?} pass {}: {} inverted after {}", strategy, kind, r.pass, r.after.inverted, last);
            last = r.after.inverted;
        }
    }
}

/// Issue 61, finding 2 at 1e200: the same block read 8 inverted (exact: 4), and dihedral
/// angles of 90° to 90° beside a histogram with 108 angles in 0–6°. Products of three
/// edges of 2^665 and 2^-2 leave the doubles: validity is decided in big integers where
/// they would, and each angle and scaled Jacobian on edges brought to unit size one by
/// one. The node at ±1e61 … ±1e300 reads as at 1e61, histograms included.
#[test]
fn a_hexahedral_block_with_a_node_at_1e200_reads_what_it_is() {
    let base = block(4, false);
    let node = (0..base.node_count()).find(|&n| base.nodes()[n] == DVec3::splat(0.5)).expect("the centre node");
    let at = |x: f64| {
        let mut m = base.clone();
        m.nodes_mut()[node].x = x;
        volume_stats(&m)
    };
    for sign in [1.0, -1.0] {
        let near = at(sign * 1e61);
        assert_eq!(near.inverted, 4);
        assert_eq!(near.solid.as_ref().unwrap().min_scaled_jacobian, -1.0);
        assert_eq!((near.min_angle_deg, near.max_angle_deg), (-90.0, 180.0));
        for x in [1e100, 1e150, 1e200, 1e250, 1e300, f64::MAX] {
            let s = at(sign * x);
            let what = format!("x = {:e}", sign * x);
            assert_eq!(s.inverted, 4, "{what}");
            assert_eq!(s.solid.as_ref().unwrap().min_scaled_jacobian, -1.0, "{what}");
            assert_eq!((s.min_angle_deg, s.max_angle_deg), (near.min_angle_deg, near.max_angle_deg), "{what}");
            assert_eq!(s.angle_histogram_6deg, near.angle_histogram_6deg, "{what}");
            assert_eq!(s.solid.as_ref().unwrap().scaled_jacobian_histogram, near.solid.as_ref().unwrap().scaled_jacobian_histogram, "{what}");
            assert_eq!(s.min_quality, 0.5, "{what}");
        }
    }
}

/// The worst scaled Jacobian of an inverted element of `m` (+∞ when none is inverted).
fn worst_inverted_scaled_jacobian(m: &VolumeMesh) -> f64 {
    (0..m.element_count()).map(|e| m.measures(e)).filter(|s| s.inverted).map(|s| s.scaled_jacobian).fold(f64::INFINITY, f64::min)
}

/// Issue 61, finding 9: with the defaults armadillo's worst scaled Jacobian fell from
/// −0.514 after 3 passes to −0.587 after 10. On tangled blocks of every kind (nodes
/// moved by up to 1.3 edges), pass by pass and for every strategy but the plain
/// Laplacian: no more inverted elements than the pass found, and the worst scaled Jacobian
/// of the inverted ones does not fall (the smart Laplacian let it fall in 11 passes of
/// these blocks before).
#[test]
fn tangled_volumes_lose_no_ground_pass_to_pass() {
    let mut fell = 0;
    for (which, base) in [block(4, false), block(4, true), smoothlab::generate::tet_cube(3).unwrap()].iter().enumerate() {
        for seed in 0..8 {
            let m = perturb_volume(base, 1.3, seed).unwrap();
            for strategy in Strategy::ALL.into_iter().filter(|&s| s != Strategy::Laplace) {
                let mut t = m.clone();
                let (mut inverted, mut worst) = (volume_stats(&t).inverted, worst_inverted_scaled_jacobian(&t));
                let objective = solid_objective(ObjectiveKind::SmoothShape).unwrap();
                let mut s = smoothlab::volume::VolumeSmoother::new(SmoothOptions::default().with_strategy(strategy)).unwrap();
                for pass in 1..=4 {
                    s.sweep(&mut t, &*objective);
                    let (now, w) = (volume_stats(&t).inverted, worst_inverted_scaled_jacobian(&t));
                    let what = format!("mesh {which}, seed {seed}, {strategy:?}, pass {pass}");
                    assert!(now <= inverted, "{what}: {inverted} -> {now} inverted");
                    assert!(w >= worst, "{what}: worst scaled Jacobian {worst} -> {w}");
                    fell += (now < inverted) as usize;
                    (inverted, worst) = (now, w);
                }
            }
        }
    }
    assert!(fell > 20, "the passes untangle: {fell}");
}


