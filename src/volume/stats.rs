//! The statistics of a tetrahedral mesh, in the planar [`MeshStats`]' fields (one record
//! for every kind of mesh: the CLI's tables, the pass records and the page read it alike).

use super::TetMesh;
use crate::quality::{angle_bin, MeshStats};

/// The statistics of `mesh`: `min_angle_deg`/`max_angle_deg` and the 6° histogram
/// (Freitag 1997, Fig. 3) are over the dihedral angles, `min_quality`/`mean_quality` over
/// the mean ratio, `max_condition` is Knupp's κ (∞ when a tetrahedron is inverted, as for
/// planar meshes), `inverted` counts tetrahedra of volume ≤ 0 (a 10-node one measured
/// with its mid-edge nodes, [`TetMesh::measures`]), `tetrahedra` the
/// elements; `triangles` and `quads` are 0.
pub fn volume_stats(mesh: &TetMesh) -> MeshStats {
    let nodes = mesh.node_count();
    let free_nodes = mesh.free_count();
    let fixed_nodes = mesh.fixed().iter().filter(|&&f| f).count();
    let elements = mesh.element_count();
    let mut s = MeshStats {
        nodes,
        elements,
        triangles: 0,
        quads: 0,
        quadratic: if mesh.is_quadratic() { elements } else { 0 },
        free_nodes,
        fixed_nodes,
        following_nodes: nodes - free_nodes - fixed_nodes,
        inverted: 0,
        min_angle_deg: f64::INFINITY,
        max_angle_deg: f64::NEG_INFINITY,
        min_quality: f64::INFINITY,
        mean_quality: 0.0,
        max_condition: 0.0,
        angle_histogram_6deg: vec![0; 30],
        surface: false,
        max_distance_from_surface: None,
        tetrahedra: elements,
    };
    let mut sum = 0.0;
    for e in 0..elements {
        let m = mesh.measures(e);
        s.inverted += m.inverted as usize;
        s.min_angle_deg = s.min_angle_deg.min(m.min_dihedral_deg);
        s.max_angle_deg = s.max_angle_deg.max(m.max_dihedral_deg);
        s.min_quality = s.min_quality.min(m.mean_ratio);
        s.max_condition = s.max_condition.max(if m.inverted { f64::INFINITY } else { m.condition });
        for a in m.dihedral_deg {
            s.angle_histogram_6deg[angle_bin(a.to_radians())] += 1;
        }
        sum += m.mean_ratio;
    }
    if elements > 0 {
        s.mean_quality = sum / elements as f64;
    }
    s
}
