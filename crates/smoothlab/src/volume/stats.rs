//! The statistics of a volume mesh, in the planar [`MeshStats`]' fields (one record
//! for every kind of mesh: the CLI's tables, the pass records and the page read it alike),
//! folded by the one [`MeshStatsBuilder`].

use super::VolumeMesh;
use crate::quality::{ElementStats, MeshCounts, MeshStats, MeshStatsBuilder};

/// The statistics of `mesh`: `min_angle_deg`/`max_angle_deg` and the 6° histogram
/// (Freitag 1997, Fig. 3) are over the dihedral angles, `min_quality`/`mean_quality` over
/// the mean ratio, `max_condition` is Knupp's κ (∞ when a tetrahedron is inverted, as for
/// planar meshes), `inverted` counts the elements not certainly valid (a tetrahedron of
/// volume ≤ 0, a 10-node one measured with its mid-edge nodes; another kind whose
/// Jacobian determinant is ≤ 0 somewhere in it, [`VolumeMesh::measures`]),
/// `volume_kinds` the elements by kind, [`SolidStats`](crate::quality::SolidStats) the
/// scaled Jacobian and the elements inverted inside; `triangles` and `quads` are 0. The
/// dihedral angles of a kind other than the tetrahedron are those at its corners' edges
/// ([`crate::quality::solid::SolidMeasures::dihedral_deg`]), the mean ratio the mean of
/// its corners'.
pub fn volume_stats(mesh: &VolumeMesh) -> MeshStats {
    let elements = mesh.element_count();
    let mut s = MeshStatsBuilder::new(MeshCounts {
        nodes: mesh.node_count(),
        free_nodes: mesh.free_count(),
        // a boundary node that slides is free, not fixed
        fixed_nodes: (0..mesh.node_count())
            .filter(|&n| mesh.fixed()[n] && !mesh.boundary_node(n).is_some_and(|c| c.slides()))
            .count(),
        elements,
        triangles: 0,
        quads: 0,
        quadratic: if mesh.is_quadratic() { elements } else { 0 },
        volume_kinds: crate::mesh::VolumeKindCounts::of((0..elements).map(|e| mesh.element_kind(e))),
    });
    for e in 0..elements {
        let m = mesh.measures(e);
        s.element(ElementStats {
            inverted: m.inverted,
            min_angle_deg: m.min_dihedral_deg,
            max_angle_deg: m.max_dihedral_deg,
            quality: m.mean_ratio,
            condition: if m.inverted { f64::INFINITY } else { m.condition },
        });
        for &a in m.dihedral() {
            s.angle(a.to_radians());
        }
        s.solid(&m);
    }
    let sizes: Vec<_> = (0..elements)
        .map(|e| {
            let (p, n) = mesh.element_points(e);
            crate::quality::grading::solid_size(mesh.element_kind(e), &p[..n])
        })
        .collect();
    s.grading(crate::quality::grading::largest_ratio(&sizes, face_neighbours(mesh)));
    s.finish()
}

/// The pairs of elements that share a face (by its corner nodes).
pub(crate) fn face_neighbours(mesh: &VolumeMesh) -> Vec<(usize, usize)> {
    let mut first: std::collections::HashMap<[u32; 4], usize> = std::collections::HashMap::new();
    let mut pairs = Vec::new();
    for e in 0..mesh.element_count() {
        let kind = mesh.element_kind(e);
        let nodes = mesh.element(e);
        for face in kind.row().faces {
            let mut key = [u32::MAX; 4];
            for (k, &i) in face.iter().filter(|&&i| i < kind.corners()).enumerate().take(4) {
                key[k] = nodes[i];
            }
            key.sort_unstable();
            match first.entry(key) {
                std::collections::hash_map::Entry::Occupied(o) => pairs.push((*o.get(), e)),
                std::collections::hash_map::Entry::Vacant(v) => {
                    v.insert(e);
                }
            }
        }
    }
    pairs
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_histogram_counts_each_elements_own_dihedral_angles_only() {
        // Kuhn's tetrahedra of a cube: dihedral angles of 45°, 60° and 90° only, six each
        let cube = crate::generate::tet_cube(2).unwrap();
        let h = volume_stats(&cube).angle_histogram_6deg;
        assert_eq!(h.iter().sum::<u64>(), 6 * 48);
        assert_eq!(h[0], 0, "no angle of 0°: {h:?}");
        // a hexahedron's 8 corners, 3 angles each: 90° everywhere on the unit cube
        let hex = crate::generate::hex_grid(&crate::generate::HexBlock::cube(2)).unwrap();
        let h = volume_stats(&hex).angle_histogram_6deg;
        assert_eq!((h.iter().sum::<u64>(), h[15]), (24 * 8, 24 * 8), "{h:?}");
    }
}
