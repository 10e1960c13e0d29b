//! The statistics of a mesh ([`MeshStats`]), of every kind — planar, surface, volume —
//! folded from its elements' measures by one builder ([`MeshStatsBuilder`]).

use glam::DVec2;
use serde::Serialize;

use super::{measure_element, ElementQuality};
use crate::mesh::{Mesh, VolumeKindCounts};

/// The statistics `smoothlab stats` prints (and `--json` writes, field for field).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MeshStats {
    pub nodes: usize,
    pub elements: usize,
    pub triangles: usize,
    pub quads: usize,
    /// Elements with mid-side nodes.
    pub quadratic: usize,
    /// Corner nodes the smoothers may move.
    pub free_nodes: usize,
    /// Nodes flagged fixed (boundary, or as the file says; unused nodes too).
    pub fixed_nodes: usize,
    /// Mid-side and centre nodes of quadratic elements that are not fixed: they follow
    /// their corners. `free_nodes + fixed_nodes + following_nodes == nodes`.
    pub following_nodes: usize,
    /// Elements with a corner of `det ≤ 0` (zero-area ones included).
    pub inverted: usize,
    /// Smallest and largest signed corner angle over all elements, degrees.
    pub min_angle_deg: f64,
    pub max_angle_deg: f64,
    /// Smallest and mean α (triangles) / β (quads).
    pub min_quality: f64,
    pub mean_quality: f64,
    /// Largest κ over all elements; `null` in JSON (∞) when any element is inverted.
    pub max_condition: f64,
    /// Grading: the largest ratio of the sizes of two valid neighbours, areas (elements
    /// that share an edge) or volumes (that share a face) ([`super::grading`]); `null`
    /// where no two valid elements are neighbours.
    pub grading: Option<f64>,
    /// Counts (not percentages) of corner angles in 30 bins of 6° over [0°, 180°];
    /// negative angles count in the first bin (Freitag 1997, Figure 3).
    pub angle_histogram_6deg: Vec<u64>,
    /// Whether the mesh is a surface in 3D ([`crate::surface`]), its elements measured each
    /// in its own plane.
    pub surface: bool,
    /// For a surface, the largest distance of a node from the reference surface.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_distance_from_surface: Option<f64>,
    /// For a volume mesh ([`crate::volume`]), its elements by kind (then the angles are
    /// dihedral angles, the quality the mean ratio); absent from JSON for a planar mesh or
    /// a surface.
    #[serde(skip_serializing_if = "no_volume")]
    pub volume_kinds: VolumeKindCounts,
    /// For a volume mesh, what only volumes have (absent from JSON otherwise).
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    pub solid: Option<SolidStats>,
}

/// The statistics only a volume mesh has: the scaled Jacobian, and the elements inverted
/// inside though every corner is positive.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SolidStats {
    /// Elements not certainly valid though every measured corner's determinant is
    /// positive ([`super::solid::validity`]): what a check of the corners alone misses.
    /// Counted in [`MeshStats::inverted`] too.
    pub inverted_inside: usize,
    /// The smallest scaled Jacobian of a measured corner ([`super::solid::scaled_jacobian`]).
    pub min_scaled_jacobian: f64,
    /// Counts of the elements' smallest corner scaled Jacobians in 20 bins of 0.1 over
    /// [−1, 1] ([`scaled_jacobian_bin`]).
    pub scaled_jacobian_histogram: Vec<u64>,
}

/// The bin of a scaled Jacobian in [`SolidStats::scaled_jacobian_histogram`]: 20 bins of
/// 0.1 from −1 (values below −1 or not a number in the first, 1 in the last).
pub fn scaled_jacobian_bin(sj: f64) -> usize {
    if sj.is_nan() || sj <= -1.0 {
        return 0;
    }
    (((sj + 1.0) * 10.0 + 1e-9) as usize).min(19)
}

fn no_volume(c: &VolumeKindCounts) -> bool {
    c.total() == 0
}

impl MeshStats {
    /// Whether these are a volume mesh's statistics (dihedral angles, the mean ratio).
    pub fn is_volume(&self) -> bool {
        !no_volume(&self.volume_kinds)
    }

    /// The grading a run that starts from a mesh with these statistics keeps
    /// ([`SmoothOptions::keep_grading`](crate::smooth::SmoothOptions::keep_grading)): its
    /// own where it is valid; +∞ (none) where it is tangled or has no two valid neighbours.
    pub fn grading_to_keep(&self) -> f64 {
        match self.grading {
            Some(g) if self.inverted == 0 => g,
            _ => f64::INFINITY,
        }
    }
}

/// Where a mesh stands, in the numbers a pass record carries (and the page's table and
/// per-pass chart show): [`MeshStats`]'s extremes, which the page measures cheaply
/// (`lab::stats`) and the CLI takes from [`mesh_stats`] ([`MeshStats::quick`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct QuickStats {
    /// Elements with a corner of `det ≤ 0`.
    pub inverted: usize,
    /// Smallest and largest signed corner angle, degrees.
    pub min_angle_deg: f64,
    pub max_angle_deg: f64,
    /// Smallest α (triangles) / β (quads).
    pub min_quality: f64,
}

/// Bin of a signed corner angle (radians) in the 6° histogram: bin i holds
/// [6i°, 6i+6°); 180° goes in the last bin, zero and negative angles in the first.
pub fn angle_bin(angle: f64) -> usize {
    let deg = angle.to_degrees();
    if deg.is_nan() || deg <= 0.0 {
        return 0;
    }
    // an angle on a bin edge (60° of an equilateral triangle, computed as 59.99999…)
    // goes to the bin above, whatever the last bit of atan2
    ((deg / 6.0 + 1e-9) as usize).min(29)
}

impl MeshStats {
    /// The extremes a pass record carries.
    pub fn quick(&self) -> QuickStats {
        QuickStats {
            inverted: self.inverted,
            min_angle_deg: self.min_angle_deg,
            max_angle_deg: self.max_angle_deg,
            min_quality: self.min_quality,
        }
    }
}

/// Computes [`MeshStats`] for a mesh: per element the metrics of [`element_quality`](super::element_quality)
/// (the same values to the last bit — a test folds `element_quality` to check), with each
/// corner's signed angle computed once for the extreme angles and the histogram alike,
/// and without the scaled Jacobians no statistic shows.
pub fn mesh_stats(mesh: &Mesh) -> MeshStats {
    mesh_stats_with(mesh, |e| mesh.element_points_array(e))
}

/// [`mesh_stats`] of `mesh`'s elements with element `e`'s nodes at `points(e)` (a
/// surface's elements, each in its own plane).
pub fn mesh_stats_with(mesh: &Mesh, points: impl Fn(usize) -> [DVec2; 9]) -> MeshStats {
    let mut s = MeshStatsBuilder::new(MeshCounts::planar(mesh));
    let mut sizes = Vec::with_capacity(mesh.element_count());
    for e in 0..mesh.element_count() {
        let kind = mesh.kind(e);
        let p = points(e);
        let q = measure_element::<true, true, false>(kind, &p[..kind.node_count()], |_, _, ang| s.angle(ang));
        s.element(ElementStats::planar(&q));
        sizes.push(super::grading::planar_size(kind, &p[..kind.node_count()]));
    }
    s.grading(super::grading::largest_ratio(&sizes, super::grading::edge_neighbours(mesh)));
    s.finish()
}

/// The counts of a mesh that do not depend on its positions: where [`MeshStatsBuilder`]
/// starts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MeshCounts {
    pub nodes: usize,
    pub free_nodes: usize,
    pub fixed_nodes: usize,
    pub elements: usize,
    pub triangles: usize,
    pub quads: usize,
    /// Elements with mid-side (mid-edge) nodes.
    pub quadratic: usize,
    /// A volume mesh's elements by kind (none for a planar mesh or a surface).
    pub volume_kinds: VolumeKindCounts,
}

impl MeshCounts {
    /// The counts of a planar mesh (or a surface's flat mesh), by kind too.
    pub fn planar(mesh: &Mesh) -> MeshCounts {
        let triangles = mesh.kinds().iter().filter(|k| k.is_triangle()).count();
        MeshCounts {
            nodes: mesh.node_count(),
            free_nodes: mesh.free_count(),
            // a boundary node that slides is free, not fixed
            fixed_nodes: (0..mesh.node_count())
                .filter(|&n| mesh.fixed()[n] && !mesh.boundary_node(n).is_some_and(|c| c.slides()))
                .count(),
            elements: mesh.element_count(),
            triangles,
            quads: mesh.element_count() - triangles,
            quadratic: mesh.kinds().iter().filter(|k| k.is_quadratic()).count(),
            volume_kinds: VolumeKindCounts::default(),
        }
    }
}

/// One element's measures as the statistics fold them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ElementStats {
    pub inverted: bool,
    /// Its smallest and largest angle, degrees (corner angles; dihedral for a solid).
    pub min_angle_deg: f64,
    pub max_angle_deg: f64,
    /// Its shape quality (α, β; the mean ratio of a solid).
    pub quality: f64,
    /// Its κ (∞ for an inverted element).
    pub condition: f64,
}

impl ElementStats {
    /// Of a planar element's [`ElementQuality`].
    #[inline]
    pub fn planar(q: &ElementQuality) -> ElementStats {
        ElementStats {
            inverted: q.inverted,
            min_angle_deg: q.min_angle.to_degrees(),
            max_angle_deg: q.max_angle.to_degrees(),
            quality: q.shape,
            condition: q.condition,
        }
    }
}

/// Builds [`MeshStats`] by folding element measures in, whatever the mesh: the planar
/// and surface statistics ([`mesh_stats_with`]) and the volume ones
/// (`volume::volume_stats`) are this fold, so every kind of mesh is counted alike.
#[derive(Clone, Debug)]
pub struct MeshStatsBuilder {
    stats: MeshStats,
    quality_sum: f64,
}

impl MeshStatsBuilder {
    /// No element measured yet: the extremes at their starting values.
    pub fn new(c: MeshCounts) -> MeshStatsBuilder {
        MeshStatsBuilder {
            stats: MeshStats {
                nodes: c.nodes,
                elements: c.elements,
                triangles: c.triangles,
                quads: c.quads,
                quadratic: c.quadratic,
                free_nodes: c.free_nodes,
                fixed_nodes: c.fixed_nodes,
                following_nodes: c.nodes - c.free_nodes - c.fixed_nodes,
                inverted: 0,
                min_angle_deg: f64::INFINITY,
                max_angle_deg: f64::NEG_INFINITY,
                min_quality: f64::INFINITY,
                mean_quality: 0.0,
                max_condition: 0.0,
                grading: None,
                angle_histogram_6deg: vec![0; 30],
                surface: false,
                max_distance_from_surface: None,
                volume_kinds: c.volume_kinds,
                solid: (c.volume_kinds.total() > 0).then(|| SolidStats {
                    inverted_inside: 0,
                    min_scaled_jacobian: f64::INFINITY,
                    scaled_jacobian_histogram: vec![0; 20],
                }),
            },
            quality_sum: 0.0,
        }
    }
    /// Counts one angle (radians) in the 6° histogram ([`angle_bin`]).
    #[inline]
    pub fn angle(&mut self, radians: f64) {
        self.stats.angle_histogram_6deg[angle_bin(radians)] += 1;
    }
    /// Folds one element's measures in (its angles go to [`angle`](Self::angle)).
    #[inline]
    pub fn element(&mut self, m: ElementStats) {
        let s = &mut self.stats;
        s.inverted += m.inverted as usize;
        s.min_angle_deg = s.min_angle_deg.min(m.min_angle_deg);
        s.max_angle_deg = s.max_angle_deg.max(m.max_angle_deg);
        s.min_quality = s.min_quality.min(m.quality);
        s.max_condition = s.max_condition.max(m.condition);
        self.quality_sum += m.quality;
    }
    /// Folds one volume element's scaled Jacobian and inside inversion in (a volume mesh's
    /// statistics only: [`MeshCounts::volume_kinds`]).
    pub fn solid(&mut self, m: &super::solid::SolidMeasures) {
        if let Some(s) = &mut self.stats.solid {
            s.inverted_inside += m.inverted_inside as usize;
            s.min_scaled_jacobian = s.min_scaled_jacobian.min(m.scaled_jacobian);
            s.scaled_jacobian_histogram[scaled_jacobian_bin(m.scaled_jacobian)] += 1;
        }
    }
    /// Sets the grading ([`MeshStats::grading`]), taken over the whole mesh at once.
    pub fn grading(&mut self, grading: Option<f64>) {
        self.stats.grading = grading;
    }
    /// The statistics, the mean quality over the elements counted.
    pub fn finish(mut self) -> MeshStats {
        if self.stats.elements > 0 {
            self.stats.mean_quality = self.quality_sum / self.stats.elements as f64;
        }
        self.stats
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::quality::{corner_edges, element_quality, signed_angle};
    use std::f64::consts::PI;

    /// `mesh_stats` by folding [`element_quality`] element by element: what
    /// `mesh_stats` must equal bit for bit.
    fn mesh_stats_by_element_quality(mesh: &Mesh) -> MeshStats {
        let mut s = MeshStats {
            angle_histogram_6deg: vec![0; 30],
            ..MeshStatsBuilder::new(MeshCounts::planar(mesh)).finish()
        };
        let mut sum = 0.0;
        for e in 0..mesh.element_count() {
            let kind = mesh.kind(e);
            let p = mesh.element_points_array(e);
            let p = &p[..kind.node_count()];
            let q = element_quality(kind, p);
            s.inverted += q.inverted as usize;
            s.min_angle_deg = s.min_angle_deg.min(q.min_angle.to_degrees());
            s.max_angle_deg = s.max_angle_deg.max(q.max_angle.to_degrees());
            s.min_quality = s.min_quality.min(q.shape);
            s.max_condition = s.max_condition.max(q.condition);
            sum += q.shape;
            for (e1, e2) in &corner_edges(kind, p)[..kind.corners()] {
                s.angle_histogram_6deg[angle_bin(signed_angle(*e1, *e2))] += 1;
            }
        }
        // the neighbours found afresh: every pair of elements with two corners in common
        let n = mesh.element_count();
        let sizes: Vec<_> = (0..n)
            .map(|e| crate::quality::grading::planar_size(mesh.kind(e), &mesh.element_points_array(e)[..mesh.kind(e).node_count()]))
            .collect();
        let corners = |e: usize| &mesh.element(e)[..mesh.kind(e).corners()];
        let pairs = (0..n).flat_map(|a| (a + 1..n).map(move |b| (a, b)));
        let pairs = pairs.filter(|&(a, b)| corners(a).iter().filter(|i| corners(b).contains(i)).count() >= 2);
        s.grading = crate::quality::grading::largest_ratio(&sizes, pairs);
        if s.elements > 0 {
            s.mean_quality = sum / s.elements as f64;
        }
        s
    }

    #[test]
    fn mesh_stats_equals_element_quality_folded() {
        use crate::generate::{grid, perturb, plate, rand2d, GridKind, PlateKind};
        let mut meshes = vec![rand2d(300, 12, 4).unwrap(), grid(6, 5, GridKind::Quad).unwrap()];
        for k in [PlateKind::Tri, PlateKind::Quad, PlateKind::Mixed] {
            meshes.push(plate(k, 1, 3).unwrap());
            meshes.push(plate(k, 2, 3).unwrap());
        }
        let tangled: Vec<Mesh> = meshes.iter().map(|m| perturb(m, 0.6, 5).unwrap()).collect();
        meshes.extend(tangled);
        for m in &meshes {
            assert_eq!(mesh_stats(m), mesh_stats_by_element_quality(m));
        }
    }

    #[test]
    fn histogram_bins() {
        assert_eq!(angle_bin(-0.1), 0);
        assert_eq!(angle_bin(0.0), 0);
        assert_eq!(angle_bin(PI / 3.0), 10);
        assert_eq!(angle_bin(PI), 29);
        assert_eq!(angle_bin(5.99f64.to_radians()), 0);
        assert_eq!(angle_bin(6.01f64.to_radians()), 1);
    }
}
