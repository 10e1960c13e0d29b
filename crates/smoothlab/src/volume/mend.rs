//! A pass's last move on a tangled volume mesh: the folds its objective does not see.
//!
//! The objectives read an element at its corners. A hexahedron (or a pyramid, a wedge)
//! can have every corner positive and still fold inside, where its trilinear `det J` dips
//! below 0 (issue 58: five of armadillo's stress test's last fifteen). A corner near 0
//! can also hold the solver at its barrier. Here each free corner of an inverted element
//! moves by a compass search that raises the least Bernstein coefficient of `det J` over
//! its star: the guard's measure of a fold, inside or at a corner
//! ([`min_det_coefficient`]). A sliding node searches in its tangent and lands on the
//! boundary, as in the solve.
//!
//! Where that leaves its star folded, a sliding node may also leave the boundary across
//! its tangent, by at most [`LIFT`] of the skin's mean edge. A hexahedron with two
//! faces on a flat part of the boundary has a straight angle where they meet (issue 58:
//! dragon's last ones); a lift of the edge between them by 5 % turns it by some 6°.

use glam::DVec3;

use super::{Tangent, VolumeMesh};
use crate::quality::solid::{min_det_coefficient, validity, Validity};

/// Rounds over the inverted elements.
const ROUNDS: usize = 3;
/// The first step, in the star's smallest element size (its corners' box diagonal).
const FIRST_STEP: f64 = 0.1;
/// The search ends when the step falls below the first step times this.
const LAST_STEP: f64 = 1e-3;
/// At most this many moves kept per search.
const MAX_MOVES: usize = 100;
/// How far a surface node may leave the boundary as loaded, in the skin's mean edge (the
/// bound issue 58 sets).
pub const LIFT: f64 = 0.05;

/// Moves the free corners of each inverted element of a linear `mesh` to raise its
/// star's least `det J` coefficient, each element's in its own size³ (fixed at the
/// search's start). A move is kept where that least coefficient rises and no element of
/// the star that was valid for certain stops being so. A search on the boundary runs until
/// its step is spent (a star barely valid would hold the next pass at its barrier); a
/// search off it ends as soon as its star is valid. Returns the moves kept.
pub(super) fn mend_folds(mesh: &mut VolumeMesh) -> usize {
    if mesh.is_quadratic() {
        return 0;
    }
    let lift = mesh.skin_mean_edge().map_or(0.0, |m| LIFT * m);
    let mut kept = 0;
    for _ in 0..ROUNDS {
        let inverted = super::smooth::inverted_elements(mesh);
        let before = kept;
        for e in (0..inverted.len()).filter(|&e| inverted[e]) {
            let corners = mesh.element_kind(e).corners();
            for c in 0..corners {
                if !mesh.is_inverted(e) {
                    break;
                }
                let n = mesh.element(e)[c] as usize;
                if !mesh.is_free(n) {
                    continue;
                }
                kept += search(mesh, n, 0.0);
                if lift > 0.0 && mesh.tangent(n) != Tangent::Free && mesh.is_inverted(e) {
                    kept += search(mesh, n, lift);
                }
            }
        }
        if kept == before {
            break;
        }
    }
    kept
}

/// The compass search of node `n` (see [`mend_folds`]); the moves it kept. A surface node
/// may leave the boundary along its normal by up to `lift`.
fn search(mesh: &mut VolumeMesh, n: usize, lift: f64) -> usize {
    let star: Vec<usize> = mesh.node_tets(n).iter().map(|&e| e as usize).collect();
    let size = |e: usize| {
        let k = mesh.element_kind(e).corners();
        let c = mesh.corners(e);
        let (lo, hi) = c[1..k].iter().fold((c[0], c[0]), |(lo, hi), &p| (lo.min(p), hi.max(p)));
        (hi - lo).length()
    };
    let sizes: Vec<f64> = star.iter().map(|&e| size(e)).collect();
    let smallest = sizes.iter().copied().fold(f64::INFINITY, f64::min);
    if !(smallest > 0.0 && smallest.is_finite()) {
        return 0;
    }
    let was_valid: Vec<bool> = star.iter().map(|&e| !mesh.is_inverted(e)).collect();
    if was_valid.iter().all(|&v| v) {
        return 0;
    }
    let points_at = |mesh: &VolumeMesh, e: usize, x: DVec3| {
        let (p, _) = mesh.element_points_with_node_at(e, n, x);
        p
    };
    let score = |mesh: &VolumeMesh, x: DVec3| {
        star.iter().zip(&sizes).fold(f64::INFINITY, |m, (&e, &s)| {
            let kind = mesh.element_kind(e);
            m.min(min_det_coefficient(kind, &points_at(mesh, e, x)[..kind.corners()]) / (s * s * s))
        })
    };
    let keeps_valid = |mesh: &VolumeMesh, x: DVec3| {
        star.iter().zip(&was_valid).filter(|(_, &v)| v).all(|(&e, _)| {
            let kind = mesh.element_kind(e);
            validity(kind, &points_at(mesh, e, x)[..kind.corners()]) == Validity::Valid
        })
    };
    let star_valid = |mesh: &VolumeMesh| star.iter().all(|&e| !mesh.is_inverted(e));
    let mut x = mesh.nodes()[n];
    let mut best = score(mesh, x);
    let mut step = FIRST_STEP * smallest;
    let mut moves = 0;
    while step > LAST_STEP * FIRST_STEP * smallest && moves < MAX_MOVES {
        let tangent = mesh.tangent(n);
        // where the node lies off the boundary, and the directions it may leave it by
        let on = if lift > 0.0 { mesh.onto_boundary(n, x) } else { x };
        let off = x - on;
        let across: [DVec3; 2] = match tangent {
            _ if lift == 0.0 => [DVec3::ZERO; 2],
            Tangent::Plane(normal) => [normal, DVec3::ZERO],
            Tangent::Line(t) => {
                let (a, b) = t.any_orthonormal_pair();
                [a, b]
            }
            Tangent::Free => [DVec3::ZERO; 2],
        };
        let slid = [DVec3::X, DVec3::Y, DVec3::Z, DVec3::NEG_X, DVec3::NEG_Y, DVec3::NEG_Z].map(|axis| {
            let along = tangent.along(axis);
            (along.length_squared() >= 1e-6).then(|| mesh.onto_boundary(n, x + along.normalize() * step) + off)
        });
        let lifted = [across[0], across[1], -across[0], -across[1]].map(|d| {
            let to = off + d * step;
            let to = if to.length() > lift { to * (lift / to.length()) } else { to };
            (d != DVec3::ZERO && to != off).then(|| on + to)
        });
        let mut moved = false;
        for to in slid.into_iter().chain(lifted).flatten() {
            let s = score(mesh, to);
            if s > best && keeps_valid(mesh, to) {
                x = to;
                best = s;
                mesh.nodes_mut()[n] = to;
                mesh.settle(n);
                moves += 1;
                moved = true;
                break;
            }
        }
        if moved {
            if lift > 0.0 && star_valid(mesh) {
                break;
            }
        } else {
            step *= 0.5;
        }
    }
    moves
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::quality::solid::corner_tet;

    use crate::volume::smooth::inverted_elements as inverted;
    use crate::volume::tests::hex_block;

    /// Whether element `e`'s corners are all positive while it folds inside.
    fn folds_inside_only(mesh: &VolumeMesh, e: usize) -> bool {
        let kind = mesh.element_kind(e);
        let p = mesh.corners(e);
        let corners_positive = (0..8).all(|c| {
            let t = corner_tet(kind, &p, c);
            (t[1] - t[0]).dot((t[2] - t[0]).cross(t[3] - t[0])) > 0.0
        });
        corners_positive && mesh.is_inverted(e)
    }

    /// Tangled blocks: fixed nodes never move, no valid element is folded, the count
    /// falls, a fold that only the inside shows is mended, and a second run repeats the
    /// first to the bit.
    #[test]
    fn folds_are_mended_without_folding_a_valid_element_or_moving_a_fixed_node() {
        let (mut fewer, mut inside_mended, mut inside_seen) = (0, 0, 0);
        for seed in 1..=12 {
            let mut mesh = hex_block(4, 0.6, seed);
            let (before, start) = (inverted(&mesh), mesh.nodes().to_vec());
            let inside: Vec<usize> = (0..mesh.element_count()).filter(|&e| folds_inside_only(&mesh, e)).collect();
            let mut again = mesh.clone();
            let kept = mend_folds(&mut mesh);
            assert_eq!(mend_folds(&mut again), kept, "seed {seed}");
            assert_eq!(again.nodes(), mesh.nodes(), "seed {seed}: the same moves");
            for (n, &at) in start.iter().enumerate() {
                if mesh.fixed()[n] {
                    assert_eq!(mesh.nodes()[n], at, "seed {seed}: fixed node {n} moved");
                }
            }
            let after = inverted(&mesh);
            for e in 0..after.len() {
                assert!(before[e] || !after[e], "seed {seed}: element {e} was valid and is not");
            }
            let count = |v: &[bool]| v.iter().filter(|&&i| i).count();
            assert!(count(&after) <= count(&before), "seed {seed}");
            fewer += (count(&after) < count(&before)) as usize;
            inside_seen += inside.len();
            inside_mended += inside.iter().filter(|&&e| !after[e]).count();
        }
        assert!(fewer >= 10, "fewer inverted on {fewer} of 12 seeds");
        assert!(inside_seen > 0 && inside_mended * 2 > inside_seen, "{inside_mended} of {inside_seen} folded inside only mended");
    }

    /// A valid mesh is left where it is.
    #[test]
    fn a_valid_mesh_is_left_where_it_is() {
        let mut mesh = hex_block(3, 0.2, 3);
        assert!(!inverted(&mesh).contains(&true));
        let start = mesh.nodes().to_vec();
        assert_eq!(mend_folds(&mut mesh), 0);
        assert_eq!(mesh.nodes(), &start[..]);
    }
}
