//! Issue 18: the smoothers' properties on tetrahedra — random cubes of tetrahedra and
//! rand3D samples, perturbed, every strategy × objective:
//!
//! 1. Fixed nodes never move, bit for bit; no NaN or infinity leaves a smoother.
//! 2. Same input, same options → the same output, bit for bit.
//! 3. On a valid mesh, the smart and guarded strategies (everything but the plain
//!    Laplacian) invert no tetrahedron.
//! 4. The smart Laplacian never lowers the smallest measure of a star: the mesh's
//!    smallest mean ratio does not fall.

use proptest::prelude::*;
use smoothlab::generate::{perturb_volume, rand3d, tet_cube};
use smoothlab::objective::{tet_objective, ObjectiveKind};
use smoothlab::smooth::{SmoothOptions, Strategy};
use smoothlab::volume::{smooth_volume, volume_stats, TetMesh};

fn sample(which: usize, cells: usize, amount: f64, seed: u64) -> TetMesh {
    let base = if which == 0 { tet_cube(cells).unwrap() } else { rand3d(60 + 40 * cells, seed).unwrap() };
    perturb_volume(&base, amount, seed).unwrap()
}

fn smoothed(m: &TetMesh, strategy: Strategy, kind: ObjectiveKind) -> TetMesh {
    let mut t = m.clone();
    smooth_volume(&mut t, &*tet_objective(kind), SmoothOptions::default().with_strategy(strategy), 2, &|| 0.0).unwrap();
    t
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn fixed_nodes_stay_and_runs_repeat(
        which in 0usize..2,
        cells in 2usize..5,
        amount in 0.0..1.0f64,
        seed in 0u64..1000,
        strategy in 0..Strategy::ALL.len(),
        objective_kind in 0..ObjectiveKind::ALL.len(),
    ) {
        let m = sample(which, cells, amount, seed);
        let (strategy, kind) = (Strategy::ALL[strategy], ObjectiveKind::ALL[objective_kind]);
        let t = smoothed(&m, strategy, kind);
        for n in 0..m.node_count() {
            prop_assert!(t.nodes()[n].is_finite(), "node {} not finite", n);
            if !m.is_free(n) {
                prop_assert_eq!(t.nodes()[n], m.nodes()[n], "fixed node {} moved", n);
            }
        }
        let again = smoothed(&m, strategy, kind);
        prop_assert_eq!(again.nodes(), t.nodes());
    }

    #[test]
    fn a_valid_mesh_stays_valid(
        which in 0usize..2,
        cells in 2usize..5,
        amount in 0.0..0.3f64,
        seed in 0u64..1000,
        strategy in 1..Strategy::ALL.len(),
        objective_kind in 0..ObjectiveKind::ALL.len(),
    ) {
        let m = sample(which, cells, amount, seed);
        prop_assume!(volume_stats(&m).inverted == 0);
        let (strategy, kind) = (Strategy::ALL[strategy], ObjectiveKind::ALL[objective_kind]);
        prop_assert_ne!(strategy, Strategy::Laplace);
        let t = smoothed(&m, strategy, kind);
        prop_assert_eq!(volume_stats(&t).inverted, 0, "{:?} {} inverted a tetrahedron", strategy, kind);
        if strategy == Strategy::Smart {
            prop_assert!(volume_stats(&t).min_quality >= volume_stats(&m).min_quality);
        }
    }
}
