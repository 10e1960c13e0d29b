//! The fit to the targets (issue 57): every free node of a valid volume mesh moved at
//! once, before the node passes, to lower the objective summed over the whole mesh.
//!
//! The passes move one node at a time. A graded boundary layer's row heights and shears
//! are long, soft modes of the mesh, which node moves hardly reach: measured against the
//! unmoved layer's own shapes, the passes still left its first row 10 % taller. The fit
//! takes them all at once.
//!
//! - The sum: each corner's term is read in the star of each of its corner tetrahedron's
//!   four nodes ([`CornerStar`]), so the mesh's objective is the sum of every node's star
//!   objective over 4. Its gradient at a node is the node's own star gradient.
//! - The solver: nonlinear conjugate gradients (Polak–Ribière, restarted where the
//!   direction goes uphill), each node's step preconditioned by its star's Hessian
//!   (Newton's step at the node); a backtracking line search from the full step (Armijo).
//! - The rule: a step is taken only where no element is inverted. The fit then keeps the
//!   last of its iterates that reads within what `smoothlab stats` read of the mesh when
//!   it began (smallest and largest dihedral angle, smallest scaled Jacobian:
//!   [`Reading::within`]), its grading within the run's, and no element's volume changed
//!   by more than `1/ρ` ([`MIN_SIZE_RATIO`]); the input where none does. So it never
//!   leaves the mesh worse in what the user reads. The path may pass outside: a layer's
//!   grading rose above the input's on the way to its rows, and fell below it after.
//!   The mean ratio is not bounded: it reads the ideal, which a stretch made on purpose
//!   scores low on (a layer's fit lowered it, then the passes raised it past the input's).
//! - It stops after [`MAX_FIT_STEPS`] steps, when a step lowers the sum by less than
//!   [`FIT_TOLERANCE`] of it, when no step along the direction is taken, or after
//!   [`FIT_PATIENCE`] steps none of which reads within the bounds.
//!
//! Sliding boundary nodes stay where they are in the fit (the passes slide them), and a
//! quadratic mesh is not fitted (its mid-edge nodes follow the corners in the passes).

use glam::DVec3;

use super::VolumeMesh;
use crate::objective::{CornerStar, Objective};
use crate::quality::grading::{solid_size, Size};
use crate::quality::Reading;
use crate::smooth::{DriverStar, SmoothMesh, MIN_SIZE_RATIO};

/// The most steps a fit takes.
pub const MAX_FIT_STEPS: u32 = 50;

/// A fit none of whose first this many steps reads within the mesh's reading stops
/// (a graded layer's first within was its 4th to 6th; Mesquite's `cub_fru.vtk` had none
/// in 50).
pub const FIT_PATIENCE: u32 = 10;

/// A fit stops after a step that lowers the mesh's objective by less than this fraction
/// of it.
pub const FIT_TOLERANCE: f64 = 1e-6;

/// The objective summed over a mesh, its gradient at the nodes the fit moves, and that
/// gradient preconditioned by each node's star Hessian.
struct Sum {
    value: f64,
    gradient: Vec<DVec3>,
    preconditioned: Vec<DVec3>,
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
    fn sum(&mut self, mesh: &VolumeMesh) -> Option<Sum> {
        let n = mesh.node_count();
        let mut value = 0.0;
        let mut gradient = vec![DVec3::ZERO; n];
        let mut preconditioned = vec![DVec3::ZERO; n];
        for i in 0..n {
            self.star.gather(mesh, i);
            let (v, g, h) = self.objective.value_gradient_hessian(&self.star, mesh.nodes()[i])?;
            value += v;
            if self.moves[i] {
                gradient[i] = g;
                // Newton's step at the node where its Hessian is positive, else the gradient's
                let newton = (h.determinant() > 0.0).then(|| h.inverse() * g);
                preconditioned[i] = newton.filter(|s| s.dot(g) > 0.0 && s.is_finite()).unwrap_or(g);
            }
        }
        Some(Sum { value: value / 4.0, gradient, preconditioned })
    }
}

/// The sizes of `mesh`'s elements, as its grading reads them.
fn sizes(mesh: &VolumeMesh) -> Vec<Option<Size>> {
    (0..mesh.element_count())
        .map(|e| {
            let (p, count) = mesh.element_points(e);
            solid_size(mesh.element_kind(e), &p[..count])
        })
        .collect()
}

/// Fits `mesh` to its targets with `objective` (see the module's text), keeping it within
/// `bounds` (its reading when the fit began) and its grading within `grading`. Returns
/// the steps kept. A mesh with an inverted element, and an objective without a Hessian,
/// take none.
pub(crate) fn fit_to_targets(mesh: &mut VolumeMesh, objective: &dyn Objective<CornerStar>, grading: f64) -> u32 {
    let Some(bounds) = mesh.valid_reading() else {
        return 0;
    };
    if mesh.is_quadratic() {
        return 0;
    }
    let n = mesh.node_count();
    let moves = (0..n).map(|i| mesh.is_free(i) && mesh.tangent(i) == super::Tangent::Free).collect();
    let mut fit = Fit { objective, moves, star: CornerStar::default() };
    let Some(mut sum) = fit.sum(mesh) else {
        return 0;
    };
    let before = sizes(mesh);
    let grading = grading.min(bounds.grading.max(1.0));
    // the mean ratio reads the ideal, which a stretch made on purpose scores low on
    let bounds = Reading { grading: f64::INFINITY, ..bounds.without_quality() };
    let kept = |m: &VolumeMesh| -> bool {
        let Some(reading) = m.valid_reading() else {
            return false;
        };
        reading.within(&bounds)
            && reading.grading <= grading
            && sizes(m).iter().zip(&before).all(|(a, b)| match (a, b) {
                (Some(a), Some(b)) => Size::ratio(*a, *b) <= 1.0 / MIN_SIZE_RATIO,
                (None, Some(_)) => false,
                _ => true,
            })
    };
    let dot = |a: &[DVec3], b: &[DVec3]| a.iter().zip(b).map(|(x, y)| x.dot(*y)).sum::<f64>();
    let mut direction: Vec<DVec3> = sum.preconditioned.iter().map(|&s| -s).collect();
    let mut steps = 0;
    // the last iterate that reads within the bounds, and its step
    let mut best = (0, mesh.nodes().to_vec());
    while steps < MAX_FIT_STEPS {
        let mut slope = dot(&sum.gradient, &direction);
        if slope >= 0.0 {
            // uphill: start again from the preconditioned gradient
            direction = sum.preconditioned.iter().map(|&s| -s).collect();
            slope = dot(&sum.gradient, &direction);
            if slope >= 0.0 {
                break;
            }
        }
        let start = mesh.nodes().to_vec();
        let mut t = 1.0;
        let mut next = None;
        for _ in 0..30 {
            for ((x, &x0), &d) in mesh.nodes_mut().iter_mut().zip(&start).zip(&direction) {
                *x = x0 + d * t;
            }
            if (0..mesh.element_count()).all(|e| !mesh.is_inverted(e)) {
                if let Some(s) = fit.sum(mesh).filter(|s| s.value <= sum.value + 1e-4 * t * slope) {
                    next = Some(s);
                    break;
                }
            }
            t *= 0.5;
        }
        let Some(next) = next else {
            break;
        };
        steps += 1;
        if kept(mesh) {
            best = (steps, mesh.nodes().to_vec());
        } else if best.0 == 0 && steps >= FIT_PATIENCE {
            break;
        }
        // Polak–Ribière, preconditioned, never below 0
        let beta = (dot(&next.gradient, &next.preconditioned) - dot(&next.gradient, &sum.preconditioned))
            / dot(&sum.gradient, &sum.preconditioned);
        let beta = if beta.is_finite() { beta.max(0.0) } else { 0.0 };
        direction = next.preconditioned.iter().zip(&direction).map(|(&s, &d)| -s + d * beta).collect();
        let small = sum.value - next.value < FIT_TOLERANCE * sum.value.abs();
        sum = next;
        if small {
            break;
        }
    }
    mesh.nodes_mut().copy_from_slice(&best.1);
    for i in 0..n {
        mesh.settle(i);
    }
    best.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{hex_grid, HexBlock};
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
