//! The fit to the targets of a volume mesh ([`crate::smooth::fit`]): its sum is the
//! objective's own.
//!
//! Each corner's term is read in the star of each of its corner tetrahedron's four nodes
//! ([`CornerStar`]), so the mesh's objective is the sum of every node's star objective
//! over 4. Its gradient at a node is the node's own star gradient, and the star's
//! Hessian preconditions it.

use glam::DVec3;

use super::VolumeMesh;
use crate::objective::{CornerStar, Objective};
use crate::quality::grading::{solid_size, Size};
use crate::smooth::fit::{preconditioned, FitMesh, Sum};
use crate::smooth::DriverStar;

impl FitMesh for VolumeMesh {
    fn points(&self) -> &[DVec3] {
        self.nodes()
    }
    fn points_mut(&mut self) -> &mut [DVec3] {
        self.nodes_mut()
    }
    fn fit_moves(&self, n: usize) -> bool {
        self.is_free(n) && self.tangent(n) == super::Tangent::Free
    }
    fn element_inverted(&self, e: usize) -> bool {
        self.is_inverted(e)
    }
    fn element_size(&self, e: usize) -> Option<Size> {
        let (p, count) = self.element_points(e);
        solid_size(self.element_kind(e), &p[..count])
    }
    fn settle_after_fit(&mut self, n: usize) {
        self.settle(n)
    }
}

/// The fit's state: the nodes it moves, and a star to gather into.
struct Fit<'a> {
    objective: &'a dyn Objective<CornerStar>,
    moves: Vec<bool>,
    star: CornerStar,
}

impl Fit<'_> {
    /// The objective summed over `mesh` (each corner's term once), with its gradient;
    /// `None` where a star has no Hessian (an objective other than `new`'s sum).
    fn sum(&mut self, mesh: &VolumeMesh) -> Option<Sum<DVec3>> {
        let n = mesh.node_count();
        let mut value = 0.0;
        let mut gradient = vec![DVec3::ZERO; n];
        let mut preconditioned_gradient = vec![DVec3::ZERO; n];
        for i in 0..n {
            self.star.gather(mesh, i);
            let (v, g, h) = self.objective.value_gradient_hessian(&self.star, mesh.nodes()[i])?;
            value += v;
            if self.moves[i] {
                gradient[i] = g;
                preconditioned_gradient[i] = preconditioned(g, (h.determinant() > 0.0).then(|| h.inverse() * g));
            }
        }
        Some(Sum { value: value / 4.0, gradient, preconditioned: preconditioned_gradient })
    }
}

/// Fits a valid volume mesh to its targets with `objective` ([`crate::smooth::fit`]),
/// its grading within `grading`. Returns the steps kept.
pub(crate) fn fit_to_targets(mesh: &mut VolumeMesh, objective: &dyn Objective<CornerStar>, grading: f64) -> u32 {
    let moves = (0..mesh.node_count()).map(|i| mesh.fit_moves(i)).collect();
    let mut fit = Fit { objective, moves, star: CornerStar::default() };
    crate::smooth::fit::fit_to_targets(mesh, |m| fit.sum(m), grading)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{hex_grid, HexBlock};
    use crate::smooth::SmoothMesh;
    use crate::objective::{solid_objective, ObjectiveKind};

    /// A block of hexahedra made thin along z, its interior moved by a fixed sequence.
    fn thin_block() -> VolumeMesh {
        let mut m = hex_grid(&HexBlock::cube(4)).unwrap();
        let mut rng = crate::objective::testing::SplitMix64::new(3);
        for p in m.nodes_mut() {
            let inside = p.to_array().iter().all(|&c| c != 0.0 && c != 1.0);
            p.z *= 0.05;
            if inside {
                *p += DVec3::new(rng.uniform(-0.05, 0.05), rng.uniform(-0.05, 0.05), rng.uniform(-0.002, 0.002));
            }
        }
        m
    }

    /// The mesh's sum has the star gradients as its gradient: central differences of the
    /// sum at a few free nodes agree with them.
    #[test]
    fn the_sum_s_gradient_is_each_node_s_star_gradient() {
        let mut m = thin_block();
        let objective = solid_objective(ObjectiveKind::SmoothShape).unwrap();
        let moves = (0..m.node_count()).map(|i| m.is_free(i)).collect();
        let mut fit = Fit { objective: &*objective, moves, star: CornerStar::default() };
        let g = fit.sum(&m).unwrap().gradient;
        let free: Vec<usize> = (0..m.node_count()).filter(|&i| m.is_free(i)).take(4).collect();
        assert_eq!(free.len(), 4);
        for i in free {
            for c in 0..3 {
                let (x0, h) = (m.nodes()[i], 1e-7);
                let mut e = DVec3::ZERO;
                e[c] = h;
                m.nodes_mut()[i] = x0 + e;
                let plus = fit.sum(&m).unwrap().value;
                m.nodes_mut()[i] = x0 - e;
                let minus = fit.sum(&m).unwrap().value;
                m.nodes_mut()[i] = x0;
                let fd = (plus - minus) / (2.0 * h);
                assert!((fd - g[i][c]).abs() <= 1e-5 * g[i][c].abs().max(1.0), "node {i} axis {c}: {fd} vs {}", g[i][c]);
            }
        }
    }

    /// A fit moves free nodes only, lowers the sum, reads within the mesh's reading, and
    /// repeats to the bit.
    #[test]
    fn a_fit_lowers_the_sum_and_leaves_nothing_worse() {
        let input = thin_block();
        let objective = solid_objective(ObjectiveKind::SmoothShape).unwrap();
        let mut m = input.clone();
        let steps = fit_to_targets(&mut m, &*objective, f64::INFINITY);
        assert!(steps > 0);
        let moves = |m: &VolumeMesh| (0..m.node_count()).map(|i| m.is_free(i)).collect();
        let value = |m: &VolumeMesh| Fit { objective: &*objective, moves: moves(m), star: CornerStar::default() }.sum(m).unwrap().value;
        assert!(value(&m) < value(&input));
        for i in (0..m.node_count()).filter(|&i| !m.is_free(i)) {
            assert_eq!(m.nodes()[i], input.nodes()[i], "fixed node {i} moved");
        }
        let (before, after) = (input.valid_reading().unwrap(), m.valid_reading().unwrap());
        assert!(after.within(&before), "{before:?} → {after:?}");
        let mut again = input.clone();
        fit_to_targets(&mut again, &*objective, f64::INFINITY);
        assert_eq!(again.nodes(), m.nodes());
    }

    /// An objective without a Hessian, a tangled mesh: no step.
    #[test]
    fn a_fit_takes_no_step_where_it_cannot_read_the_sum() {
        let objective = solid_objective(ObjectiveKind::Sine).unwrap();
        let mut m = thin_block();
        assert_eq!(fit_to_targets(&mut m, &*objective, f64::INFINITY), 0);
        let objective = solid_objective(ObjectiveKind::SmoothShape).unwrap();
        let mut tangled = thin_block();
        let free = (0..tangled.node_count()).find(|&i| tangled.is_free(i)).unwrap();
        tangled.nodes_mut()[free].z = -1.0;
        let before = tangled.nodes().to_vec();
        assert_eq!(fit_to_targets(&mut tangled, &*objective, f64::INFINITY), 0);
        assert_eq!(tangled.nodes(), &before[..]);
    }
}
