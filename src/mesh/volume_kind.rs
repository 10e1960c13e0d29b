//! The element kinds of a volume mesh, each one row of data ([`VolumeKindRow`]): its node
//! and corner counts, each corner's three edge neighbours with the reference matrix W its
//! Jacobian is measured against (Knupp 1999's corner view: at corner `c` with edge
//! neighbours `a`, `b`, `d`, the columns `p_a − p_c`, `p_b − p_c`, `p_d − p_c`), its edges
//! and faces, its mirror image, and its type codes in VTK and Gmsh files.
//!
//! The readers, the writers, the mesh's adjacency, the statistics and the objectives read
//! a kind through its row; what differs beyond the data (how an element is measured) is an
//! exhaustive `match` on [`VolumeKind`], so a new kind is its row, its arm in
//! [`VolumeKind::row`] and the arms the compiler then asks for.

use glam::{DMat3, DVec3};
use serde::Serialize;

/// The reference (target) matrix of an element's corner (Knupp 1999): the corner's ideal
/// edge vectors as columns, with `W⁻¹` and `det W⁻¹` computed once per kind, so a measure
/// that takes it costs what one with the matrix built in does.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CornerReference {
    pub w: DMat3,
    pub w_inv: DMat3,
    /// `det W⁻¹`, as [`DMat3::determinant`] computes it.
    pub det_w_inv: f64,
    /// `W⁻ᵀ𝟙` (the column sums of `W⁻¹`), as `w_inv.transpose() * DVec3::ONE` computes it:
    /// the gradient of `‖A·W⁻¹‖²_F` with respect to the corner is `−2·T·W⁻ᵀ𝟙`.
    pub w_inv_t_one: DVec3,
}

/// `det m` as [`DMat3::determinant`] computes it (`x·(y×z)`, the same operations in the
/// same order), at compile time.
const fn determinant(m: DMat3) -> f64 {
    let (x, y, z) = (m.x_axis, m.y_axis, m.z_axis);
    let c = DVec3::new(y.y * z.z - z.y * y.z, y.z * z.x - z.z * y.x, y.x * z.y - z.x * y.y);
    (x.x * c.x) + (x.y * c.y) + (x.z * c.z)
}

/// `mᵀ·𝟙` as `m.transpose() * DVec3::ONE` computes it (each column of `mᵀ` times 1,
/// summed in order), at compile time.
const fn transpose_times_one(m: DMat3) -> DVec3 {
    let (x, y, z) = (m.x_axis, m.y_axis, m.z_axis);
    // component i: mᵀ's columns' i-th entries, i.e. m's column i, summed
    DVec3::new(x.x * 1.0 + x.y * 1.0 + x.z * 1.0, y.x * 1.0 + y.y * 1.0 + y.z * 1.0, z.x * 1.0 + z.y * 1.0 + z.z * 1.0)
}

/// Knupp's ideal weight for tetrahedra (Knupp 1999, §3): the columns are the edge
/// vectors from one corner of the regular tetrahedron of unit edge, `(1, 0, 0)`,
/// `(1/2, √3/2, 0)`, `(1/2, √3/6, √(2/3))`, so `A·W⁻¹` takes the ideal element to the
/// physical one.
pub const EQUILATERAL_W: DMat3 = DMat3::from_cols_array(&[
    1.0,
    0.0,
    0.0,
    0.5,
    0.866_025_403_784_438_6, // √3/2
    0.0,
    0.5,
    0.288_675_134_594_812_9, // √3/6
    0.816_496_580_927_726,   // √(2/3)
]);

/// `W⁻¹` of [`EQUILATERAL_W`], by hand (W is upper triangular): columns `(1, 0, 0)`,
/// `(−1/√3, 2/√3, 0)`, `(−1/√6, −1/√6, √(3/2))`.
pub const EQUILATERAL_W_INVERSE: DMat3 = DMat3::from_cols_array(&[
    1.0,
    0.0,
    0.0,
    -0.577_350_269_189_625_8, // −1/√3
    1.154_700_538_379_251_5,  // 2/√3
    0.0,
    -0.408_248_290_463_863, // −1/√6
    -0.408_248_290_463_863, // −1/√6
    1.224_744_871_391_589,  // √(3/2)
]);

/// The equilateral tetrahedron's corner ([`EQUILATERAL_W`]): the reference of every corner
/// of a tetrahedron, linear or quadratic. A `static`, so every kind that points at it
/// points at one address: where a measure's kind is known only at run time but every kind
/// has this reference, the compiler still sees a constant and folds it into the
/// arithmetic (the measures cost what they did with W built in).
pub static EQUILATERAL_TET: CornerReference = CornerReference {
    w: EQUILATERAL_W,
    w_inv: EQUILATERAL_W_INVERSE,
    det_w_inv: determinant(EQUILATERAL_W_INVERSE),
    w_inv_t_one: transpose_times_one(EQUILATERAL_W_INVERSE),
};

/// The edges of a tetrahedron by local corners, in the order of a 10-node tetrahedron's
/// mid-edge nodes (VTK's `QUADRATIC_TETRA`): (0,1), (1,2), (0,2), (0,3), (1,3), (2,3).
pub const TET10_EDGES: [[usize; 2]; 6] = [[0, 1], [1, 2], [0, 2], [0, 3], [1, 3], [2, 3]];

/// Everything a volume element kind is, as data (see the module docs).
#[derive(Debug)]
pub struct VolumeKindRow {
    /// In messages: "4-node tetrahedron".
    pub name: &'static str,
    /// Its family in the plural, in messages: "tetrahedra".
    pub family: &'static str,
    /// Nodes per element.
    pub nodes: usize,
    /// Corner nodes, the first of its nodes; the others are mid-edge nodes.
    pub corners: usize,
    /// Each corner's three edge neighbours, ordered so that the corner's Jacobian
    /// (columns `p_a − p_c`, `p_b − p_c`, `p_d − p_c`) has a positive determinant on a
    /// valid element: corner `c` first, then these, is an even permutation of the
    /// corners of a tetrahedron.
    pub corner_edges: &'static [[usize; 3]],
    /// The reference matrix of every corner.
    pub reference: &'static CornerReference,
    /// The edges by local corners; with mid-edge nodes, node `corners + m` is the middle
    /// of edge `m`.
    pub edges: &'static [[usize; 2]],
    /// Whether nodes `corners..` are the edges' middles.
    pub mid_edge_nodes: bool,
    /// The faces by local corners, each ordered so that its normal points out of a valid
    /// element.
    pub faces: &'static [[usize; 3]],
    /// The element's mirror image: node `j` of the mirrored element is node `mirror[j]`
    /// (a left-handed element turned right-handed, its mid-edge nodes on their edges).
    pub mirror: &'static [usize],
    /// Its legacy VTK cell type.
    pub vtk_type: u32,
    /// Its Gmsh element type.
    pub gmsh_type: u32,
    /// Gmsh's node order from ours: Gmsh's node `j` is our node `gmsh_order[j]`.
    pub gmsh_order: &'static [usize],
}

/// Faces of a tetrahedron by local corners, each ordered so that its normal points away
/// from the opposite corner (faces opposite corners 0, 1, 2, 3).
const TET_FACES: [[usize; 3]; 4] = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]];

/// A tetrahedron's corners' edge neighbours: `(c, a, b, d)` is `(0 1 2 3)`, `(1 0 3 2)`,
/// `(2 3 0 1)`, `(3 2 1 0)`, the even permutations that put each corner first.
const TET_CORNER_EDGES: [[usize; 3]; 4] = [[1, 2, 3], [0, 3, 2], [3, 0, 1], [2, 1, 0]];

const TET4: VolumeKindRow = VolumeKindRow {
    name: "4-node tetrahedron",
    family: "tetrahedra",
    nodes: 4,
    corners: 4,
    corner_edges: &TET_CORNER_EDGES,
    reference: &EQUILATERAL_TET,
    edges: &TET10_EDGES,
    mid_edge_nodes: false,
    faces: &TET_FACES,
    mirror: &[0, 2, 1, 3],
    vtk_type: 10,
    gmsh_type: 4,
    gmsh_order: &[0, 1, 2, 3],
};

const TET10: VolumeKindRow = VolumeKindRow {
    name: "10-node tetrahedron",
    family: "tetrahedra",
    nodes: 10,
    corners: 4,
    corner_edges: &TET_CORNER_EDGES,
    reference: &EQUILATERAL_TET,
    edges: &TET10_EDGES,
    mid_edge_nodes: true,
    faces: &TET_FACES,
    // corners 1 and 2 swapped: edges (0,1)↔(0,2) and (1,3)↔(2,3); (1,2) and (0,3) stay
    mirror: &[0, 2, 1, 3, 6, 5, 4, 7, 9, 8],
    vtk_type: 24,
    gmsh_type: 11,
    // Gmsh's last two mid-edge nodes are on edges (3,2) and (3,1), ours on (1,3), (2,3)
    gmsh_order: &[0, 1, 2, 3, 4, 5, 6, 7, 9, 8],
};

/// The element kinds of a volume mesh (one kind per mesh).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub enum VolumeKind {
    /// The linear tetrahedron: 4 corners.
    Tet4,
    /// The quadratic tetrahedron: 4 corners, then the middles of the edges of
    /// [`TET10_EDGES`].
    Tet10,
}

impl VolumeKind {
    pub const ALL: [VolumeKind; 2] = [VolumeKind::Tet4, VolumeKind::Tet10];

    /// The kind's row of data.
    #[inline]
    pub const fn row(self) -> &'static VolumeKindRow {
        match self {
            VolumeKind::Tet4 => &TET4,
            VolumeKind::Tet10 => &TET10,
        }
    }
    #[inline]
    pub const fn nodes(self) -> usize {
        self.row().nodes
    }
    #[inline]
    pub const fn corners(self) -> usize {
        self.row().corners
    }
    /// Whether the kind has mid-edge nodes (they follow their corners).
    #[inline]
    pub const fn is_quadratic(self) -> bool {
        self.row().mid_edge_nodes
    }
    #[inline]
    pub const fn reference(self) -> &'static CornerReference {
        self.row().reference
    }
    pub fn name(self) -> &'static str {
        self.row().name
    }
    /// Two kinds in one phrase, fewer nodes first: "4-node and 10-node tetrahedra" (a
    /// file that mixes them is refused).
    pub fn mix_words(a: VolumeKind, b: VolumeKind) -> String {
        let (a, b) = if a.nodes() <= b.nodes() { (a.row(), b.row()) } else { (b.row(), a.row()) };
        if a.family == b.family {
            format!("{}-node and {}-node {}", a.nodes, b.nodes, a.family)
        } else {
            format!("{}-node {} and {}-node {}", a.nodes, a.family, b.nodes, b.family)
        }
    }
    /// The kind of Gmsh element type `t`, if it is one.
    pub fn from_gmsh_type(t: u64) -> Option<VolumeKind> {
        VolumeKind::ALL.into_iter().find(|k| u64::from(k.row().gmsh_type) == t)
    }
    /// The kind of legacy VTK cell type `t`, if it is one.
    pub fn from_vtk_type(t: u64) -> Option<VolumeKind> {
        VolumeKind::ALL.into_iter().find(|k| u64::from(k.row().vtk_type) == t)
    }
    /// The kind with `n` nodes (files that say only the count, TetGen's `.ele`).
    pub fn with_nodes(n: usize) -> Option<VolumeKind> {
        VolumeKind::ALL.into_iter().find(|k| k.nodes() == n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_reference_determinant_is_the_one_glam_computes() {
        for k in VolumeKind::ALL {
            let r = k.reference();
            assert_eq!(r.det_w_inv.to_bits(), r.w_inv.determinant().to_bits(), "{k:?}");
            let one = r.w_inv.transpose() * DVec3::ONE;
            assert_eq!(r.w_inv_t_one.to_array().map(f64::to_bits), one.to_array().map(f64::to_bits), "{k:?}");
            let i = r.w * r.w_inv;
            assert!(i.abs_diff_eq(DMat3::IDENTITY, 1e-15), "{k:?}: W·W⁻¹ = {i}");
        }
    }

    #[test]
    fn every_row_is_consistent() {
        for k in VolumeKind::ALL {
            let r = k.row();
            assert_eq!(r.corner_edges.len(), r.corners, "{k:?}");
            assert_eq!(r.nodes, r.corners + if r.mid_edge_nodes { r.edges.len() } else { 0 }, "{k:?}");
            for perm in [r.mirror, r.gmsh_order] {
                let mut p = perm.to_vec();
                p.sort_unstable();
                assert_eq!(p, (0..r.nodes).collect::<Vec<_>>(), "{k:?}: not a permutation");
            }
            // every corner's edge neighbours are its edges
            for (c, ns) in r.corner_edges.iter().enumerate() {
                for &n in ns {
                    assert!(r.edges.iter().any(|&[a, b]| (a, b) == (c, n) || (a, b) == (n, c)), "{k:?}");
                }
            }
            // mirrored mid-edge nodes stay on their (mirrored) edges
            if r.mid_edge_nodes {
                for (m, &[a, b]) in r.edges.iter().enumerate() {
                    let src = r.mirror[r.corners + m] - r.corners;
                    let [c, d] = r.edges[src];
                    let (ma, mb) = (r.mirror[a], r.mirror[b]);
                    assert!((c, d) == (ma, mb) || (c, d) == (mb, ma), "{k:?}: edge {m}");
                }
            }
            assert_eq!(VolumeKind::from_gmsh_type(u64::from(r.gmsh_type)), Some(k));
            assert_eq!(VolumeKind::from_vtk_type(u64::from(r.vtk_type)), Some(k));
            assert_eq!(VolumeKind::with_nodes(r.nodes), Some(k));
        }
    }
}
