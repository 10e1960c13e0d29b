//! Random perturbation of the free nodes: how the tangled test meshes are made.

use crate::numeric::SplitMix64;
use crate::error::{Error, Result};
use crate::mesh::Mesh;

/// A copy of `mesh` with every free node (a corner that is not fixed) moved by a seeded
/// random offset uniformly distributed in the disk of radius
/// `amount × mesh.mean_edge_length()`; fixed nodes never move and mid-side nodes then
/// follow their corners ([`Mesh::update_mid_nodes`]; curved boundary edges keep theirs).
/// This is how Chen, Tristano & Kwok (2003, §5.2, Figure 13) tangle the plate with a
/// hole: "perturbing the nodal locations of each interior node randomly". Amounts of
/// 0.5–1.0 tangle a mesh; 0 returns it unchanged.
///
/// The free nodes draw their offsets in node order from [`SplitMix64`] seeded with
/// `seed`, so the result is the same on every platform. `amount` must be finite and ≥ 0.
///
/// ```
/// use smoothlab::generate::{perturb, rand2d};
/// use smoothlab::quality::mesh_stats;
///
/// let mesh = rand2d(200, 10, 1)?;
/// let tangled = perturb(&mesh, 0.8, 7)?;
/// assert!(mesh_stats(&tangled).inverted > 0, "a large amount tangles the mesh");
/// assert_eq!(tangled.nodes()[0], mesh.nodes()[0], "boundary nodes are fixed");
/// # Ok::<(), smoothlab::Error>(())
/// ```
pub fn perturb(mesh: &Mesh, amount: f64, seed: u64) -> Result<Mesh> {
    let radius = perturbation_radius(amount, mesh.mean_edge_length())?;
    let mut out = mesh.clone();
    let mut rng = SplitMix64::new(seed);
    for n in 0..out.node_count() {
        if out.is_free(n) {
            out.nodes_mut()[n] += radius * rng.in_unit_disk();
        }
    }
    out.update_mid_nodes();
    Ok(out)
}

/// A copy of a volume mesh (any kinds: tetrahedra, hexahedra, wedges, pyramids, mixed,
/// linear or quadratic) with every free node moved by a seeded random offset uniformly
/// distributed in the ball of radius `amount × mean edge length` (the mean over the
/// elements' edges, [`VolumeMesh::mean_edge_length`](crate::volume::VolumeMesh::mean_edge_length));
/// the nodes that follow corners (mid-edge, face and centre nodes) follow them, and fixed
/// nodes never move. A structured cube of tetrahedra or block of hexahedra perturbed by
/// 0.5–1 is Knupp's kind of tangled test mesh (Knupp 1999, §4: "randomly perturbed
/// interior nodes"). Seeded as [`perturb`]: the free nodes draw in node order from
/// [`SplitMix64`].
pub fn perturb_volume(mesh: &crate::volume::VolumeMesh, amount: f64, seed: u64) -> Result<crate::volume::VolumeMesh> {
    let radius = perturbation_radius(amount, mesh.mean_edge_length())?;
    let mut out = mesh.clone();
    let mut rng = SplitMix64::new(seed);
    for n in 0..out.node_count() {
        if out.is_free(n) {
            out.nodes_mut()[n] += radius * rng.in_unit_ball();
            out.follow_mid_nodes(n);
        }
    }
    Ok(out)
}

/// A copy of `surface` with every free node moved in its tangent plane by a seeded random
/// offset in the disk of radius `amount × mean edge length`, then projected back onto the
/// reference (the planar [`perturb`] on a surface); the nodes
/// that follow move with them. Node by node in node order, from [`SplitMix64`].
pub fn perturb_surface(surface: &crate::surface::Surface, amount: f64, seed: u64) -> Result<crate::surface::Surface> {
    let radius = perturbation_radius(amount, surface.mean_edge_length())?;
    let mut out = surface.clone();
    let mut rng = SplitMix64::new(seed);
    for n in 0..out.node_count() {
        if out.flat().is_free(n) {
            let plane = out.tangent_plane(n);
            let p = plane.to_3d(radius * rng.in_unit_disk());
            out.place(n, p);
        }
    }
    Ok(out)
}

/// The largest move of a perturbation of `amount` mean edge lengths (the one check of the
/// amount, for planar meshes and surfaces).
pub(crate) fn perturbation_radius(amount: f64, mean_edge_length: f64) -> Result<f64> {
    if !(amount.is_finite() && amount >= 0.0) {
        return Err(Error::invalid(format!("the perturbation amount must be a finite number ≥ 0, not {amount}")));
    }
    Ok(amount * mean_edge_length)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{grid, hex_grid, mixed_block, plate, rand2d, GridKind, HexBlock, PlateKind};
    use crate::volume::VolumeMesh;
    use crate::mesh::{NodeRole, NONE};
    use crate::quality::mesh_stats;
    use proptest::prelude::*;

    /// Fixed nodes stay bit for bit, free ones move at most `amount × mean edge`.
    fn check_moves(before: &Mesh, after: &Mesh, amount: f64) {
        let r = amount * before.mean_edge_length();
        for n in 0..before.node_count() {
            let d = before.nodes()[n].distance(after.nodes()[n]);
            if before.fixed()[n] {
                assert_eq!(before.nodes()[n], after.nodes()[n], "fixed node {n} moved");
            } else if before.role(n) == NodeRole::Corner {
                assert!(d <= r * (1.0 + 1e-12), "node {n} moved {d} > {r}");
            }
        }
    }

    #[test]
    fn fixed_stay_free_move_within_the_amount() {
        let m = rand2d(500, 20, 1).unwrap();
        let p = perturb(&m, 0.7, 3).unwrap();
        p.sanity_check().unwrap();
        check_moves(&m, &p, 0.7);
        let moved = (0..m.node_count()).filter(|&n| m.nodes()[n] != p.nodes()[n]).count();
        assert_eq!(moved, m.free_count());
        // uniform in the disk: E|offset|² = r²/2
        let r = 0.7 * m.mean_edge_length();
        let mean_sq = (0..m.node_count())
            .filter(|&n| m.is_free(n))
            .map(|n| m.nodes()[n].distance_squared(p.nodes()[n]))
            .sum::<f64>()
            / m.free_count() as f64;
        assert!((mean_sq / (r * r) - 0.5).abs() < 0.05, "{}", mean_sq / (r * r));
    }

    #[test]
    fn seeded_and_deterministic() {
        let m = grid(8, 8, GridKind::Quad).unwrap();
        let a = perturb(&m, 0.3, 11).unwrap();
        assert_eq!(a.nodes(), perturb(&m, 0.3, 11).unwrap().nodes());
        let b = perturb(&m, 0.3, 12).unwrap();
        let differ = (0..m.node_count()).filter(|&n| a.nodes()[n] != b.nodes()[n]).count();
        assert_eq!(differ, m.free_count());
        assert_eq!(perturb(&m, 0.0, 5).unwrap().nodes(), m.nodes());
    }

    #[test]
    fn large_amounts_tangle_the_plate() {
        let m = plate(PlateKind::Tri, 1, 4).unwrap();
        assert_eq!(mesh_stats(&m).inverted, 0);
        let t = perturb(&m, 1.0, 1).unwrap();
        assert!(mesh_stats(&t).inverted > 10, "{}", mesh_stats(&t).inverted);
        let small = perturb(&m, 0.05, 1).unwrap();
        assert_eq!(mesh_stats(&small).inverted, 0, "a small amount keeps the mesh valid");
    }

    #[test]
    fn mid_nodes_follow_and_the_curved_hole_stays() {
        let m = plate(PlateKind::Mixed, 2, 2).unwrap();
        let p = perturb(&m, 0.8, 2).unwrap();
        p.sanity_check().unwrap();
        check_moves(&m, &p, 0.8);
        for e in p.edges() {
            assert_ne!(e.mid, NONE);
            let (a, b, c) = (p.nodes()[e.a as usize], p.nodes()[e.b as usize], p.nodes()[e.mid as usize]);
            if e.curved {
                assert_eq!(c, m.nodes()[e.mid as usize], "curved boundary mid nodes stay");
            } else {
                assert!(c.distance(0.5 * (a + b)) < 1e-12, "mid node follows its corners");
            }
        }
    }

    #[test]
    fn bad_amounts_are_errors() {
        let m = grid(2, 2, GridKind::Tri).unwrap();
        for a in [-0.1, f64::NAN, f64::INFINITY] {
            assert!(matches!(perturb(&m, a, 1), Err(Error::Invalid(_))), "{a}");
        }
    }

    /// Fixed nodes of a volume mesh stay bit for bit, free ones move at most
    /// `amount × mean edge`, followers sit at the mean of their corners.
    fn check_volume_moves(before: &VolumeMesh, after: &VolumeMesh, amount: f64) {
        let r = amount * before.mean_edge_length();
        for n in 0..before.node_count() {
            let (p, q) = (before.nodes()[n], after.nodes()[n]);
            if before.fixed()[n] {
                assert_eq!(p, q, "fixed node {n} moved");
            } else if before.is_free(n) {
                assert!(p.distance(q) <= r * (1.0 + 1e-12), "node {n} moved {} > {r}", p.distance(q));
            } else {
                let ps = after.parents(n);
                let mean = ps.iter().map(|&c| after.nodes()[c as usize]).sum::<glam::DVec3>() / ps.len() as f64;
                assert!(q.distance(mean) < 1e-12, "follower {n} is off its corners' mean");
            }
        }
    }

    #[test]
    fn a_hex_grid_perturbed_by_0_6_edge_lengths_tangles_and_keeps_its_boundary() {
        let m = hex_grid(&HexBlock::cube(6)).unwrap();
        let p = perturb_volume(&m, 0.6, 1).unwrap();
        check_volume_moves(&m, &p, 0.6);
        let moved = (0..m.node_count()).filter(|&n| m.nodes()[n] != p.nodes()[n]).count();
        assert_eq!(moved, m.free_count());
        assert_eq!(m.free_count(), 125);
        let inverted = (0..p.element_count()).filter(|&e| p.is_inverted(e)).count();
        assert!(inverted > 0, "0.6 edge lengths inverts hexahedra");
        let small = perturb_volume(&m, 0.05, 1).unwrap();
        assert_eq!((0..small.element_count()).filter(|&e| small.is_inverted(e)).count(), 0);
        // seeded: the same seed, the same mesh; another seed moves every free node elsewhere
        assert_eq!(perturb_volume(&m, 0.6, 1).unwrap().nodes(), p.nodes());
        let q = perturb_volume(&m, 0.6, 2).unwrap();
        assert_eq!((0..m.node_count()).filter(|&n| q.nodes()[n] != p.nodes()[n]).count(), m.free_count());
        assert_eq!(perturb_volume(&m, 0.0, 5).unwrap().nodes(), m.nodes());
        for a in [-0.1, f64::NAN, f64::INFINITY] {
            assert!(matches!(perturb_volume(&m, a, 1), Err(Error::Invalid(_))), "{a}");
        }
    }

    #[test]
    fn every_kind_is_perturbed_its_followers_following() {
        let hex27 = hex_grid(&HexBlock::cube(3)).unwrap().to_quadratic(false).unwrap();
        let hex20 = hex_grid(&HexBlock::cube(3).bent(60.0)).unwrap().to_quadratic(true).unwrap();
        let mixed = mixed_block(&HexBlock::cube(3)).unwrap();
        for m in [hex27, hex20, mixed] {
            let p = perturb_volume(&m, 0.4, 7).unwrap();
            check_volume_moves(&m, &p, 0.4);
            assert!((0..m.node_count()).filter(|&n| m.is_free(n)).all(|n| m.nodes()[n] != p.nodes()[n]));
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]
        #[test]
        fn any_seed_any_amount(seed in any::<u64>(), amount in 0.0f64..3.0, n in 2usize..6) {
            let m = grid(n, n + 1, GridKind::Tri).unwrap();
            let p = perturb(&m, amount, seed).unwrap();
            check_moves(&m, &p, amount);
            prop_assert!(p.sanity_check().is_ok());
        }
    }
}
