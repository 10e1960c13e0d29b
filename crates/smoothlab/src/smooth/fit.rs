//! The fit to the targets (issue 57): every free node of a valid mesh moved at once,
//! before the node passes, to lower an objective summed over the whole mesh.
//!
//! The passes move one node at a time. A graded boundary layer's row heights and shears
//! are long, soft modes of the mesh, which node moves hardly reach: measured against the
//! unmoved layer's own shapes, the passes still left its first row 10 % taller. The fit
//! takes them all at once.
//!
//! - The sum: a volume mesh's is its objective's ([`crate::volume`]'s fit); a planar
//!   mesh's is `planar_sum`, each corner's regularised mean ratio against its target,
//!   its size held to the mesh's own.
//! - The solver: nonlinear conjugate gradients (Polak–Ribière, restarted where the
//!   direction goes uphill), each node's step preconditioned by its block of the sum's
//!   Hessian (Newton's step at the node); a backtracking line search from the full step
//!   (Armijo).
//! - The rule: a step is taken only where no element is inverted. The fit then keeps the
//!   last of its iterates that reads within what `smoothlab stats` read of the mesh when
//!   it began (smallest and largest angle, smallest scaled Jacobian: [`Reading::within`]),
//!   its grading within the run's, and no element's size changed by more than `1/ρ`
//!   ([`MIN_SIZE_RATIO`]); the input where none does. So it never leaves the mesh worse
//!   in what the user reads. The path may pass outside: a layer's grading rose above the
//!   input's on the way to its rows, and fell below it after. The mean ratio is not
//!   bounded: it reads the ideal, which a stretch made on purpose scores low on.
//! - It stops after [`MAX_FIT_STEPS`] steps, when a step lowers the sum by less than
//!   [`FIT_TOLERANCE`] of it, when no step along the direction is taken, or after
//!   [`FIT_PATIENCE`] steps none of which reads within the bounds.
//!
//! Sliding boundary nodes stay where they are in the fit (the passes slide them), and a
//! quadratic mesh is not fitted (its mid-side nodes follow the corners in the passes).

use glam::{DMat2, DVec2};

use super::{SmoothMesh, MIN_SIZE_RATIO};
use crate::mesh::Mesh;
use crate::objective::{Point, BARRIER_WEIGHT};
use crate::quality::grading::Size;
use crate::quality::metric::{planar_condition_chain, CornerMatrix};
use crate::quality::Reading;

/// The most steps a fit takes.
pub const MAX_FIT_STEPS: u32 = 50;

/// A fit none of whose first this many steps reads within the mesh's reading stops
/// (a graded layer's first within was its 4th to 6th; Mesquite's `cub_fru.vtk` had none
/// in 50).
pub const FIT_PATIENCE: u32 = 10;

/// A fit stops after a step that lowers the mesh's objective by less than this fraction
/// of it.
pub const FIT_TOLERANCE: f64 = 1e-6;

/// An objective summed over a mesh, its gradient at the nodes the fit moves (zero at the
/// others), and that gradient preconditioned by each node's block of the Hessian.
pub(crate) struct Sum<P> {
    pub value: f64,
    pub gradient: Vec<P>,
    pub preconditioned: Vec<P>,
}

/// `g` preconditioned by a node's Hessian block `H`: `newton`, the step `H⁻¹g` where
/// `det H > 0`, if it is finite and goes downhill, else `g` itself.
pub(crate) fn preconditioned<P: Point>(g: P, newton: Option<P>) -> P {
    newton.filter(|s| s.dot(g) > 0.0 && s.is_finite()).unwrap_or(g)
}

/// What the fit reads and writes of a mesh, beyond what the drivers read.
pub(crate) trait FitMesh: SmoothMesh {
    fn points(&self) -> &[Self::Point];
    fn points_mut(&mut self) -> &mut [Self::Point];
    /// Whether the fit moves node `n`: a free node that does not slide.
    fn fit_moves(&self, n: usize) -> bool;
    /// Whether element `e` is inverted, as the statistics count it.
    fn element_inverted(&self, e: usize) -> bool;
    /// Element `e`'s size, as its grading reads it.
    fn element_size(&self, e: usize) -> Option<Size>;
    /// What follows node `n` once the fit has moved it (a volume's boundary state).
    fn settle_after_fit(&mut self, _n: usize) {}
}

/// Fits `mesh` to its targets by the objective `sum` reads (see the module's text),
/// keeping it within its reading when the fit began and its grading within `grading`.
/// Returns the steps kept. A mesh with an inverted element, a quadratic mesh, and a `sum`
/// that returns `None` (an objective without a Hessian) take none.
pub(crate) fn fit_to_targets<M: FitMesh>(mesh: &mut M, mut sum: impl FnMut(&M) -> Option<Sum<M::Point>>, grading: f64) -> u32 {
    let Some(bounds) = mesh.valid_reading() else {
        return 0;
    };
    if mesh.has_quadratic() {
        return 0;
    }
    let Some(mut now) = sum(mesh) else {
        return 0;
    };
    let sizes = |m: &M| (0..m.element_count()).map(|e| m.element_size(e)).collect::<Vec<_>>();
    let before = sizes(mesh);
    let grading = grading.min(bounds.grading.max(1.0));
    // the mean ratio reads the ideal, which a stretch made on purpose scores low on
    let bounds = Reading { grading: f64::INFINITY, ..bounds.without_quality() };
    let kept = |m: &M| -> bool {
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
    let dot = |a: &[M::Point], b: &[M::Point]| a.iter().zip(b).map(|(x, y)| x.dot(*y)).sum::<f64>();
    let mut direction: Vec<M::Point> = now.preconditioned.iter().map(|&s| -s).collect();
    let mut steps = 0;
    // the last iterate that reads within the bounds, and its step
    let mut best = (0, mesh.points().to_vec());
    while steps < MAX_FIT_STEPS {
        let mut slope = dot(&now.gradient, &direction);
        if slope >= 0.0 {
            // uphill: start again from the preconditioned gradient
            direction = now.preconditioned.iter().map(|&s| -s).collect();
            slope = dot(&now.gradient, &direction);
            if slope >= 0.0 {
                break;
            }
        }
        let start = mesh.points().to_vec();
        let mut t = 1.0;
        let mut next = None;
        for _ in 0..30 {
            for ((x, &x0), &d) in mesh.points_mut().iter_mut().zip(&start).zip(&direction) {
                *x = x0 + d * t;
            }
            if (0..mesh.element_count()).all(|e| !mesh.element_inverted(e)) {
                if let Some(s) = sum(mesh).filter(|s| s.value <= now.value + 1e-4 * t * slope) {
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
            best = (steps, mesh.points().to_vec());
        } else if best.0 == 0 && steps >= FIT_PATIENCE {
            break;
        }
        // Polak–Ribière, preconditioned, never below 0
        let beta = (dot(&next.gradient, &next.preconditioned) - dot(&next.gradient, &now.preconditioned))
            / dot(&now.gradient, &now.preconditioned);
        let beta = if beta.is_finite() { beta.max(0.0) } else { 0.0 };
        direction = next.preconditioned.iter().zip(&direction).map(|(&s, &d)| -s + d * beta).collect();
        let small = now.value - next.value < FIT_TOLERANCE * now.value.abs();
        now = next;
        if small {
            break;
        }
    }
    mesh.points_mut().copy_from_slice(&best.1);
    for i in 0..mesh.node_count() {
        mesh.settle_after_fit(i);
    }
    best.0
}

impl FitMesh for Mesh {
    fn points(&self) -> &[DVec2] {
        self.nodes()
    }
    fn points_mut(&mut self) -> &mut [DVec2] {
        self.nodes_mut()
    }
    fn fit_moves(&self, n: usize) -> bool {
        self.is_free(n) && self.slide_direction(n) == DVec2::ZERO
    }
    fn element_inverted(&self, e: usize) -> bool {
        super::mesh_element_is_inverted(self, e)
    }
    fn element_size(&self, e: usize) -> Option<Size> {
        let kind = self.kind(e);
        crate::quality::grading::planar_size(kind, &self.element_points_array(e)[..kind.node_count()])
    }
}

/// The weight of a planar corner's size term in the fit (`planar_sum`): the square of
/// the log of its area over its area as read. At 1, the 2D quad layer's first row stayed
/// within 5 % on six seeds (−0.3 … +4.6 %; without it, one seed −5.2 %); at 3 its cells
/// were further from rectangles (73.70° against 78.92° at the worst seed).
pub const FIT_SIZE_WEIGHT: f64 = 1.0;

/// A planar mesh's sum for the fit: each corner's shape, `(1 − q)² + k1·η²` with
/// `η = ‖T‖²_F/(2·det T)`, `q = 1/η` and `T = A·W⁻¹` — the solids' `new` at δ = 0
/// ([`crate::objective::solid`]'s regularised mean ratio) in the plane — and its size,
/// `γ·ln²(det A/det A₀)` ([`FIT_SIZE_WEIGHT`]). `A` is the corner's edge pair (to the
/// next corner, then the previous), `W` its target's
/// ([`Mesh::element_target_points`]), or the ideal's ([`crate::target::ideal_pair`])
/// where the target corner is inverted or flat ([`crate::target::corner_frame`]). `A₀`
/// is the corner as the targets were taken ([`Mesh::target_nodes`]): a target has a
/// shape, not a size, so the size is the mesh's own (no size term where `A₀` is not
/// valid). Each node's Hessian block is exact: `T` is linear in one node and
/// `η = κ/2` ([`planar_condition_chain`]). `None` where the mesh has no targets; +∞
/// where a corner is inverted or flat.
pub(crate) fn planar_sum(mesh: &Mesh, moves: &[bool]) -> Option<Sum<DVec2>> {
    let n = mesh.node_count();
    let (mut gradient, mut hessian) = (vec![DVec2::ZERO; n], vec![DMat2::ZERO; n]);
    let mut value = 0.0;
    let at_start = mesh.target_nodes()?;
    for e in 0..mesh.element_count() {
        let kind = mesh.kind(e);
        let target = mesh.element_target_points(e)?;
        let (ids, p) = (mesh.element(e), mesh.element_points_array(e));
        let k = kind.corners();
        for c in 0..k {
            let (next, prev) = ((c + 1) % k, (c + k - 1) % k);
            let ideal = crate::target::ideal_pair(kind);
            let (t1, t2) = (target[next] - target[c], target[prev] - target[c]);
            // the passes' rule: the ideal where the target corner is inverted or flat
            let w = match crate::target::corner_frame(t1, t2, ideal) {
                Some(_) => DMat2::from_cols(t1, t2),
                None => DMat2::from_cols(ideal.0, ideal.1),
            };
            let w_inv = w.inverse();
            let a = DMat2::from_cols(p[next] - p[c], p[prev] - p[c]);
            let t = a * w_inv;
            let (frob2, det) = (t.frobenius2(), CornerMatrix::determinant(&t));
            if !(det > 0.0 && det.is_finite()) {
                return Some(Sum { value: f64::INFINITY, gradient, preconditioned: vec![DVec2::ZERO; n] });
            }
            let eta = frob2 / (2.0 * det);
            let q = 1.0 / eta;
            // ln(det A/det A₀); 0 where A₀ is not valid (no size term)
            let from = |m: usize| at_start[ids[m] as usize] - at_start[ids[c] as usize];
            let size = (a.determinant() / from(next).perp_dot(from(prev))).ln();
            let (size, gamma) = if size.is_finite() { (size, FIT_SIZE_WEIGHT) } else { (0.0, 0.0) };
            value += (1.0 - q).powi(2) + BARRIER_WEIGHT * eta * eta + gamma * size * size;
            // f(η) = (1 − 1/η)² + k1·η²: its first and second derivatives
            let d1 = 2.0 * (1.0 - q) * q * q + 2.0 * BARRIER_WEIGHT * eta;
            let d2 = 2.0 * q.powi(4) - 4.0 * (1.0 - q) * q.powi(3) + 2.0 * BARRIER_WEIGHT;
            // node `m` moves T by u·vᵀ, v the row of W⁻¹ it takes: (−1, −1), (1, 0), (0, 1)
            let cof = t.cofactor();
            for (m, r) in [(c, DVec2::new(-1.0, -1.0)), (next, DVec2::X), (prev, DVec2::Y)] {
                let node = ids[m] as usize;
                if !moves[node] {
                    continue;
                }
                let v = w_inv.transpose() * r;
                let (grad_f, grad_det, hf) = (2.0 * (t * v), cof * v, 2.0 * v.length_squared());
                let (_, g_kappa, h_kappa) = planar_condition_chain::<true>(frob2, det, grad_f, grad_det, hf);
                let (g_eta, h_eta) = (g_kappa / 2.0, h_kappa * 0.5);
                // the size term: det A is det T times a constant, linear in the node
                let g_size = grad_det / det;
                gradient[node] += g_eta * d1 + g_size * (2.0 * gamma * size);
                hessian[node] += DMat2::from_cols(g_eta * g_eta.x, g_eta * g_eta.y) * d2
                    + h_eta * d1
                    + DMat2::from_cols(g_size * g_size.x, g_size * g_size.y) * (2.0 * gamma * (1.0 - size));
            }
        }
    }
    let preconditioned =
        gradient.iter().zip(&hessian).map(|(&g, &h)| preconditioned(g, (h.determinant() > 0.0).then(|| h.inverse() * g))).collect();
    Some(Sum { value, gradient, preconditioned })
}

/// Fits a valid planar mesh to its targets ([`fit_to_targets`] on [`planar_sum`]).
pub(crate) fn fit_planar(mesh: &mut Mesh, grading: f64) -> u32 {
    if mesh.target_nodes().is_none() {
        return 0;
    }
    let moves: Vec<bool> = (0..mesh.node_count()).map(|i| mesh.fit_moves(i)).collect();
    fit_to_targets(mesh, |m| planar_sum(m, &moves), grading)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{grid, GridKind};
    use crate::target::Target;

    /// A 6 × 6 grid of `kind` made 20 times thinner along y, its interior moved by a fixed
    /// sequence, measured against the stretch target.
    fn thin_grid(kind: GridKind) -> Mesh {
        let mut m = grid(6, 6, kind).unwrap();
        let mut rng = crate::objective::testing::SplitMix64::new(5);
        for p in m.nodes_mut() {
            let inside = p.to_array().iter().all(|&c| c != 0.0 && c != 1.0);
            p.y *= 0.05;
            if inside {
                *p += DVec2::new(rng.uniform(-0.03, 0.03), rng.uniform(-0.0015, 0.0015));
            }
        }
        m.set_target_from(Target::Stretch, m.nodes().to_vec());
        assert!(m.target_nodes().is_some(), "{kind:?}: stretched on purpose");
        m
    }

    /// The fit is due once a run (a target, moves judged), and again when a smoother made
    /// anew is told that its next pass is the run's first.
    #[test]
    fn the_fit_is_due_once_a_run_and_again_when_told() {
        use crate::smooth::{SmoothOptions, Smoother, Strategy};
        let mut s: Smoother = Smoother::new(SmoothOptions::default()).unwrap();
        assert!(s.fit_due(true));
        assert!(!s.fit_due(true), "once");
        s.set_fit_pending(true);
        assert!(!s.fit_due(false), "not without a target");
        s.set_fit_pending(true);
        assert!(s.fit_due(true), "again when told");
        let mut laplace: Smoother = Smoother::new(SmoothOptions::default().with_strategy(Strategy::Laplace)).unwrap();
        assert!(!laplace.fit_due(true), "not where moves are not judged");
    }

    /// Central differences of the sum agree with its gradient, and of the gradient with
    /// each node's Hessian block (the preconditioner is its Newton step).
    #[test]
    fn the_planar_sum_s_gradient_and_hessian_are_its_derivatives() {
        for kind in [GridKind::Quad, GridKind::Tri] {
            let mut m = thin_grid(kind);
            let moves: Vec<bool> = (0..m.node_count()).map(|i| m.is_free(i)).collect();
            let at = |m: &Mesh| planar_sum(m, &moves).unwrap();
            let sum = at(&m);
            for i in (0..m.node_count()).filter(|&i| moves[i]).take(6) {
                let (x0, h) = (m.nodes()[i], 1e-8);
                let mut columns = [DVec2::ZERO; 2];
                for c in 0..2 {
                    let mut e = DVec2::ZERO;
                    e[c] = h;
                    m.nodes_mut()[i] = x0 + e;
                    let plus = at(&m);
                    m.nodes_mut()[i] = x0 - e;
                    let minus = at(&m);
                    m.nodes_mut()[i] = x0;
                    let fd = (plus.value - minus.value) / (2.0 * h);
                    let g = sum.gradient[i][c];
                    assert!((fd - g).abs() <= 1e-5 * g.abs().max(1.0), "{kind:?} node {i} axis {c}: {fd} vs {g}");
                    columns[c] = (plus.gradient[i] - minus.gradient[i]) / (2.0 * h);
                }
                // the preconditioned gradient is H⁻¹g with H from the gradient's differences
                let hessian = DMat2::from_cols(columns[0], columns[1]);
                let newton = hessian.inverse() * sum.gradient[i];
                let p = sum.preconditioned[i];
                assert!((newton - p).length() <= 1e-4 * p.length(), "{kind:?} node {i}: {newton} vs {p}");
            }
        }
    }

    /// A fit moves free nodes only, lowers the sum, reads within the mesh's reading, and
    /// repeats to the bit; a mesh without targets or with an inverted element takes none.
    #[test]
    fn a_planar_fit_lowers_the_sum_and_leaves_nothing_worse() {
        let input = thin_grid(GridKind::Quad);
        let mut m = input.clone();
        assert!(fit_planar(&mut m, f64::INFINITY) > 0);
        let moves: Vec<bool> = (0..m.node_count()).map(|i| m.is_free(i)).collect();
        assert!(planar_sum(&m, &moves).unwrap().value < planar_sum(&input, &moves).unwrap().value);
        for i in (0..m.node_count()).filter(|&i| !m.is_free(i)) {
            assert_eq!(m.nodes()[i], input.nodes()[i], "fixed node {i} moved");
        }
        let (before, after) = (input.valid_reading().unwrap(), m.valid_reading().unwrap());
        assert!(after.within(&before.without_quality()), "{before:?} → {after:?}");
        assert!(after.min_angle_deg > before.min_angle_deg + 10.0, "{before:?} → {after:?}");
        let mut again = input.clone();
        fit_planar(&mut again, f64::INFINITY);
        assert_eq!(again.nodes(), m.nodes());
        let mut ideal = input.clone();
        ideal.set_target_from(Target::Ideal, input.nodes().to_vec());
        assert_eq!(fit_planar(&mut ideal, f64::INFINITY), 0);
        let mut tangled = input.clone();
        let free = (0..tangled.node_count()).find(|&i| tangled.is_free(i)).unwrap();
        tangled.nodes_mut()[free].y = -1.0;
        let before = tangled.nodes().to_vec();
        assert_eq!(fit_planar(&mut tangled, f64::INFINITY), 0);
        assert_eq!(tangled.nodes(), &before[..]);
    }
}
