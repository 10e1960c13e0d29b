//! Face swapping by the max-min dihedral angle criterion (Freitag 1997, on rand3D: "we
//! swap the faces of the initial mesh as follows using an in-sphere criterion followed by
//! a maxmin dihedral angle criterion"; Freitag & Ollivier-Gooch 1996): the 2-3 swap (two
//! tetrahedra across a face become three around the edge joining their apexes) and the
//! 3-2 swap (its inverse), each taken where it raises the smallest dihedral angle of the
//! tetrahedra it replaces. Nodes never move; the boundary is untouched (only interior
//! faces and edges are swapped).

use std::collections::HashMap;

use glam::DVec3;

use crate::numeric::order::{pair_key, stable_order};
use crate::quality::tet::{dihedral_angles, signed_volume};

/// The smallest dihedral angle (radians) of a tetrahedron.
fn min_angle(p: &[DVec3], t: [u32; 4]) -> f64 {
    dihedral_angles(&t.map(|v| p[v as usize])).into_iter().fold(f64::INFINITY, f64::min)
}

fn volume(p: &[DVec3], t: [u32; 4]) -> f64 {
    signed_volume(&t.map(|v| p[v as usize]))
}

/// `t` positively oriented (two vertices swapped when its volume is negative).
fn oriented(p: &[DVec3], mut t: [u32; 4]) -> [u32; 4] {
    if volume(p, t) < 0.0 {
        t.swap(0, 1);
    }
    t
}

/// Whether tetrahedra `new` fill exactly the region of `old` (the swap is geometrically
/// possible): every new one has volume, and their volumes add up to the old ones'.
fn fills(p: &[DVec3], old: &[[u32; 4]], new: &[[u32; 4]]) -> bool {
    let before: f64 = old.iter().map(|&t| volume(p, t)).sum();
    let after: f64 = new.iter().map(|&t| volume(p, t)).sum();
    new.iter().all(|&t| volume(p, t) > 1e-12 * before) && (after - before).abs() <= 1e-9 * before
}

/// Swaps faces and edges of the positively oriented tetrahedra `tets` over points `p`
/// while a swap raises the smallest dihedral angle of the tetrahedra it replaces (by more
/// than 10⁻⁹ rad), in passes of at most one swap per tetrahedron, at most `max_passes`.
/// Returns the number of swaps made.
pub fn swap_max_min_dihedral(p: &[DVec3], tets: &mut Vec<[u32; 4]>, max_passes: usize) -> usize {
    let mut swaps = 0;
    for _ in 0..max_passes {
        let mut touched = vec![false; tets.len()];
        let mut made = 0;
        // 2-3: two tetrahedra across an interior face
        let mut faces: HashMap<[u32; 3], (usize, u32)> = HashMap::with_capacity(2 * tets.len());
        let mut pairs = Vec::new();
        for (i, t) in tets.iter().enumerate() {
            for k in 0..4 {
                let mut f = [0u32; 3];
                let mut m = 0;
                for (j, &v) in t.iter().enumerate() {
                    if j != k {
                        f[m] = v;
                        m += 1;
                    }
                }
                f.sort_unstable();
                match faces.remove(&f) {
                    Some((other, apex)) => pairs.push((f, other, apex, i, t[k])),
                    None => {
                        faces.insert(f, (i, t[k]));
                    }
                }
            }
        }
        for (f, i, d, j, e) in pairs {
            if touched[i] || touched[j] {
                continue;
            }
            let old = [tets[i], tets[j]];
            let new = [[f[0], f[1], d, e], [f[1], f[2], d, e], [f[2], f[0], d, e]].map(|t| oriented(p, t));
            if !fills(p, &old, &new) {
                continue;
            }
            let before = old.iter().map(|&t| min_angle(p, t)).fold(f64::INFINITY, f64::min);
            let after = new.iter().map(|&t| min_angle(p, t)).fold(f64::INFINITY, f64::min);
            if after > before + 1e-9 {
                tets[i] = new[0];
                tets[j] = new[1];
                tets.push(new[2]);
                touched[i] = true;
                touched[j] = true;
                touched.push(true);
                made += 1;
            }
        }
        // 3-2: an interior edge with three tetrahedra around it
        let mut edges: HashMap<[u32; 2], Vec<usize>> = HashMap::with_capacity(6 * tets.len());
        for (i, t) in tets.iter().enumerate() {
            for a in 0..4 {
                for b in a + 1..4 {
                    edges.entry([t[a].min(t[b]), t[a].max(t[b])]).or_default().push(i);
                }
            }
        }
        let mut dead = Vec::new();
        // in the order of the edges (each is once in the map)
        let ring: Vec<_> = edges.into_iter().filter(|(_, around)| around.len() == 3).collect();
        for r in stable_order(ring.len(), |r| pair_key(ring[r].0[0], ring[r].0[1])) {
            let ([d, e], ref around) = ring[r as usize];
            if around.iter().any(|&i| touched[i]) {
                continue;
            }
            // the ring's three other vertices, each in exactly two of the tetrahedra (a
            // closed ring: the edge is interior)
            let mut others: Vec<u32> =
                around.iter().flat_map(|&i| tets[i].into_iter().filter(|&v| v != d && v != e)).collect();
            others.sort_unstable();
            if !(others.len() == 6 && others[0] == others[1] && others[2] == others[3] && others[4] == others[5]) {
                continue;
            }
            let (a, b, c) = (others[0], others[2], others[4]);
            let old: Vec<[u32; 4]> = around.iter().map(|&i| tets[i]).collect();
            let new = [oriented(p, [a, b, c, d]), oriented(p, [a, b, c, e])];
            if !fills(p, &old, &new) {
                continue;
            }
            let before = old.iter().map(|&t| min_angle(p, t)).fold(f64::INFINITY, f64::min);
            let after = new.iter().map(|&t| min_angle(p, t)).fold(f64::INFINITY, f64::min);
            if after > before + 1e-9 {
                tets[around[0]] = new[0];
                tets[around[1]] = new[1];
                dead.push(around[2]);
                for &i in around {
                    touched[i] = true;
                }
                made += 1;
            }
        }
        dead.sort_unstable();
        for i in dead.into_iter().rev() {
            tets.swap_remove(i);
        }
        swaps += made;
        if made == 0 {
            break;
        }
    }
    swaps
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_two_three_swap_by_hand() {
        // a triangle in z = 0 and apexes above and below, the lower one nearly on the
        // plane: the two tetrahedra across the face have a sliver; the three around the
        // edge joining the apexes do not
        let p = vec![
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(-0.5, 0.866, 0.0),
            DVec3::new(-0.5, -0.866, 0.0),
            DVec3::new(0.0, 0.0, 1.0),
            DVec3::new(0.1, 0.0, -0.05),
        ];
        let mut tets = vec![oriented(&p, [0, 1, 2, 3]), oriented(&p, [0, 1, 2, 4])];
        let before = tets.iter().map(|&t| min_angle(&p, t)).fold(f64::INFINITY, f64::min);
        let total: f64 = tets.iter().map(|&t| volume(&p, t)).sum();
        assert_eq!(swap_max_min_dihedral(&p, &mut tets, 5), 1);
        assert_eq!(tets.len(), 3);
        let after = tets.iter().map(|&t| min_angle(&p, t)).fold(f64::INFINITY, f64::min);
        assert!(after > before, "{before} → {after}");
        assert!((tets.iter().map(|&t| volume(&p, t)).sum::<f64>() - total).abs() < 1e-15);
        assert!(tets.iter().all(|&t| volume(&p, t) > 0.0 && t.contains(&3) && t.contains(&4)));
        // and nothing more to gain: the 3-2 swap back would lower it again
        assert_eq!(swap_max_min_dihedral(&p, &mut tets, 5), 0);
    }

    #[test]
    fn an_impossible_swap_is_not_made() {
        // the apexes' edge misses the shared face: a 2-3 swap would overlap
        let p = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(2.0, 2.0, 1.0),
            DVec3::new(2.0, 2.0, -0.01),
        ];
        let mut tets = vec![oriented(&p, [0, 1, 2, 3]), oriented(&p, [0, 1, 2, 4])];
        let kept = tets.clone();
        swap_max_min_dihedral(&p, &mut tets, 5);
        assert_eq!(tets, kept);
    }
}
