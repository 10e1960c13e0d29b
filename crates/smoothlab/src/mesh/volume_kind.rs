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
    /// Whether `W` is the identity (the cube's corner, and its slot 0), so that `A·W⁻¹` is
    /// `A` itself: the product's sums `a·1 + b·0 + c·0` are `a`, bit for bit but for the
    /// sign of a zero entry, which changes a measure of `T` only where the measure is a zero
    /// too (and no comparison tells the two zeros apart).
    pub identity: bool,
}

impl CornerReference {
    /// The reference whose edge vectors are the columns of `w` (a target worked out at run
    /// time, [`crate::target`]): the same fields the kinds' static references hold.
    pub fn of(w: DMat3) -> Self {
        let w_inv = w.inverse();
        CornerReference {
            w,
            w_inv,
            det_w_inv: w_inv.determinant(),
            w_inv_t_one: w_inv.transpose() * DVec3::ONE,
            identity: w == DMat3::IDENTITY,
        }
    }
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
    identity: false,
};

/// The edges of a tetrahedron by local corners, in the order of a 10-node tetrahedron's
/// mid-edge nodes (VTK's `QUADRATIC_TETRA`): (0,1), (1,2), (0,2), (0,3), (1,3), (2,3).
pub const TET10_EDGES: [[usize; 2]; 6] = [[0, 1], [1, 2], [0, 2], [0, 3], [1, 3], [2, 3]];

/// `a·b` of 3×3 matrices given as columns, at compile time.
const fn mat_mul(a: [[f64; 3]; 3], b: [[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let mut c = [[0.0; 3]; 3];
    let mut j = 0;
    while j < 3 {
        let mut i = 0;
        while i < 3 {
            c[j][i] = a[0][i] * b[j][0] + a[1][i] * b[j][1] + a[2][i] * b[j][2];
            i += 1;
        }
        j += 1;
    }
    c
}

/// The inverse of a 3×3 matrix given as columns (its adjugate over its determinant), at
/// compile time.
const fn mat_inverse(m: [[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let (x, y, z) = (m[0], m[1], m[2]);
    // rows of the inverse: y×z, z×x, x×y over det
    let r0 = [y[1] * z[2] - y[2] * z[1], y[2] * z[0] - y[0] * z[2], y[0] * z[1] - y[1] * z[0]];
    let r1 = [z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2], z[0] * x[1] - z[1] * x[0]];
    let r2 = [x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]];
    let det = x[0] * r0[0] + x[1] * r0[1] + x[2] * r0[2];
    [[r0[0] / det, r1[0] / det, r2[0] / det], [r0[1] / det, r1[1] / det, r2[1] / det], [r0[2] / det, r1[2] / det, r2[2] / det]]
}

const fn to_mat(m: [[f64; 3]; 3]) -> DMat3 {
    DMat3::from_cols(DVec3::new(m[0][0], m[0][1], m[0][2]), DVec3::new(m[1][0], m[1][1], m[1][2]), DVec3::new(m[2][0], m[2][1], m[2][2]))
}

const fn from_mat(m: DMat3) -> [[f64; 3]; 3] {
    [[m.x_axis.x, m.x_axis.y, m.x_axis.z], [m.y_axis.x, m.y_axis.y, m.y_axis.z], [m.z_axis.x, m.z_axis.y, m.z_axis.z]]
}

/// Whether `w` is the identity, entry by entry.
const fn is_identity(w: [[f64; 3]; 3]) -> bool {
    let mut j = 0;
    while j < 3 {
        let mut i = 0;
        while i < 3 {
            if w[j][i] != if i == j { 1.0 } else { 0.0 } {
                return false;
            }
            i += 1;
        }
        j += 1;
    }
    true
}

/// The reference of a corner whose ideal edge vectors are the columns of `w`.
const fn reference_of(w: [[f64; 3]; 3]) -> CornerReference {
    let w_inv = to_mat(mat_inverse(w));
    CornerReference { w: to_mat(w), w_inv, det_w_inv: determinant(w_inv), w_inv_t_one: transpose_times_one(w_inv), identity: is_identity(w) }
}

/// The even permutations that put corner `s` of a corner's tetrahedron first
/// (`crate::quality::tet::with_first`'s).
pub const WITH_FIRST: [[usize; 4]; 4] = [[0, 1, 2, 3], [1, 0, 3, 2], [2, 3, 0, 1], [3, 2, 1, 0]];

/// The reference of a corner's tetrahedron `(c, a, b, d)` reordered by
/// [`WITH_FIRST`]`[s]`, so that the point in slot `s` comes first: its edge vectors from
/// that point are `A·M` with `M`'s columns `e_{π(j)} − e_{π(0)}` (`e_0 = 0`), so measuring
/// them against `W·M` gives the same `T = A·W⁻¹` — the same corner, seen from the node the
/// smoother moves.
const fn slot_reference(w: [[f64; 3]; 3], s: usize) -> CornerReference {
    let pi = WITH_FIRST[s];
    let e0 = unit(pi[0]);
    let mut m = [[0.0; 3]; 3];
    let mut j = 1;
    while j < 4 {
        let ej = unit(pi[j]);
        m[j - 1] = [ej[0] - e0[0], ej[1] - e0[1], ej[2] - e0[2]];
        j += 1;
    }
    reference_of(mat_mul(w, m))
}

/// `e_k`: 0 for `k = 0`, else the `k`-th unit vector.
const fn unit(k: usize) -> [f64; 3] {
    let mut e = [0.0; 3];
    if k > 0 {
        e[k - 1] = 1.0;
    }
    e
}

/// The four slot references of corner reference `w` ([`slot_reference`]).
const fn slot_references(w: [[f64; 3]; 3]) -> [CornerReference; 4] {
    [slot_reference(w, 0), slot_reference(w, 1), slot_reference(w, 2), slot_reference(w, 3)]
}

/// The unit cube's corner: W = I (Knupp 1999's hexahedral corner).
const CUBE_W: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
/// The right wedge's corner (an equilateral triangle of unit edge, unit height): its two
/// triangle edges, then the edge across.
const WEDGE_W: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [0.5, 0.866_025_403_784_438_6, 0.0], [0.0, 0.0, 1.0]];
/// A pyramid's base corner, the pyramid of unit edges (a unit square base, the apex at
/// height `1/√2`): its two base edges, then the edge to the apex.
const PYRAMID_W: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.5, 0.5, std::f64::consts::FRAC_1_SQRT_2]];

/// The unit cube's corner (`CUBE_W`: W = I).
pub static CUBE_CORNER: CornerReference = reference_of(CUBE_W);
/// The right wedge's corner (`WEDGE_W`).
pub static WEDGE_CORNER: CornerReference = reference_of(WEDGE_W);
/// The unit pyramid's base corner (`PYRAMID_W`).
pub static PYRAMID_CORNER: CornerReference = reference_of(PYRAMID_W);
static TET_SLOTS: [CornerReference; 4] = slot_references(from_mat(EQUILATERAL_W));
static CUBE_SLOTS: [CornerReference; 4] = slot_references(CUBE_W);
static WEDGE_SLOTS: [CornerReference; 4] = slot_references(WEDGE_W);
static PYRAMID_SLOTS: [CornerReference; 4] = slot_references(PYRAMID_W);

/// Everything a volume element kind is, as data (see the module docs).
#[derive(Debug)]
pub struct VolumeKindRow {
    /// In messages: "4-node tetrahedron".
    pub name: &'static str,
    /// Its family in the plural, in messages: "tetrahedra".
    pub family: &'static str,
    /// Nodes per element.
    pub nodes: usize,
    /// Corner nodes, the first of its nodes; the others follow them ([`followers`](Self::followers)).
    pub corners: usize,
    /// The measured corners' three edge neighbours (corner `c` is the `c`-th), ordered so
    /// that the corner's Jacobian (columns `p_a − p_c`, `p_b − p_c`, `p_d − p_c`) is a
    /// rotation of the reference's on the ideal element, so positive on a valid one. A
    /// pyramid's apex, where four edges meet, is not measured: any three of its edges span
    /// the tetrahedron of a base corner, already measured.
    pub corner_edges: &'static [[usize; 3]],
    /// The reference matrix of every measured corner.
    pub reference: &'static CornerReference,
    /// The reference of a measured corner's tetrahedron reordered to put slot `s` first
    /// ([`WITH_FIRST`]), for each slot.
    pub slot_references: &'static [CornerReference; 4],
    /// The edges by local corners.
    pub edges: &'static [[usize; 2]],
    /// The nodes after the corners: node `corners + i` sits at the mean of the corners
    /// `followers[i]` (an edge's middle, a face's or the element's centre) and follows them.
    pub followers: &'static [&'static [usize]],
    /// The faces by local corners (3 or 4), each ordered so that its normal points out of
    /// a valid element.
    pub faces: &'static [&'static [usize]],
    /// The element's mirror image: node `j` of the mirrored element is node `mirror[j]`
    /// (a left-handed element turned right-handed, its followers in their places).
    pub mirror: &'static [usize],
    /// Its legacy VTK cell type; its node order is ours.
    pub vtk_type: u32,
    /// Its Gmsh element type.
    pub gmsh_type: u32,
    /// Gmsh's node order from ours: Gmsh's node `j` is our node `gmsh_order[j]`.
    pub gmsh_order: &'static [usize],
    /// The corners of the ideal element (the one every measured corner's reference
    /// describes), for tests and generators.
    pub ideal: &'static [[f64; 3]],
    /// Which of the ideal's axes a stretch target lays onto its stretch's axes.
    pub stretch_axes: StretchAxes,
}

/// Which of an ideal element's axes a stretch target lays onto the axes of its stretch
/// (`crate::target::stretch`), so that the target is not sheared by its element's jitter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StretchAxes {
    /// None: the turn fitted to the element is kept.
    Kept,
    /// Every axis (the cube, the same turned from one axis onto another).
    Every,
    /// This axis (its index), the turn about it kept: a wedge's, across its triangles.
    One(usize),
}

/// Faces of a tetrahedron by local corners, each ordered so that its normal points away
/// from the opposite corner (faces opposite corners 0, 1, 2, 3).
const TET_FACES: [&[usize]; 4] = [&[1, 2, 3], &[0, 3, 2], &[0, 1, 3], &[0, 2, 1]];

/// A tetrahedron's corners' edge neighbours: `(c, a, b, d)` is `(0 1 2 3)`, `(1 0 3 2)`,
/// `(2 3 0 1)`, `(3 2 1 0)`, the even permutations that put each corner first.
const TET_CORNER_EDGES: [[usize; 3]; 4] = [[1, 2, 3], [0, 3, 2], [3, 0, 1], [2, 1, 0]];

const TET_IDEAL: [[f64; 3]; 4] =
    [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.5, 0.866_025_403_784_438_6, 0.0], [0.5, 0.288_675_134_594_812_9, 0.816_496_580_927_726]];

const TET4: VolumeKindRow = VolumeKindRow {
    name: "4-node tetrahedron",
    family: "tetrahedra",
    nodes: 4,
    corners: 4,
    corner_edges: &TET_CORNER_EDGES,
    reference: &EQUILATERAL_TET,
    slot_references: &TET_SLOTS,
    edges: &TET10_EDGES,
    followers: &[],
    faces: &TET_FACES,
    mirror: &[0, 2, 1, 3],
    vtk_type: 10,
    gmsh_type: 4,
    gmsh_order: &[0, 1, 2, 3],
    ideal: &TET_IDEAL,
    stretch_axes: StretchAxes::Kept,
};

const TET10: VolumeKindRow = VolumeKindRow {
    name: "10-node tetrahedron",
    family: "tetrahedra",
    nodes: 10,
    corners: 4,
    corner_edges: &TET_CORNER_EDGES,
    reference: &EQUILATERAL_TET,
    slot_references: &TET_SLOTS,
    edges: &TET10_EDGES,
    followers: &[&[0, 1], &[1, 2], &[0, 2], &[0, 3], &[1, 3], &[2, 3]],
    faces: &TET_FACES,
    // corners 1 and 2 swapped: edges (0,1)↔(0,2) and (1,3)↔(2,3); (1,2) and (0,3) stay
    mirror: &[0, 2, 1, 3, 6, 5, 4, 7, 9, 8],
    vtk_type: 24,
    gmsh_type: 11,
    // Gmsh's last two mid-edge nodes are on edges (3,2) and (3,1), ours on (1,3), (2,3)
    gmsh_order: &[0, 1, 2, 3, 4, 5, 6, 7, 9, 8],
    ideal: &TET_IDEAL,
    stretch_axes: StretchAxes::Kept,
};

/// A hexahedron's edges in VTK's order (its 20-node kind's mid-edge nodes 8–19):
/// the bottom ring, the top ring, then the four edges across.
const HEX_EDGES: [[usize; 2]; 12] =
    [[0, 1], [1, 2], [2, 3], [3, 0], [4, 5], [5, 6], [6, 7], [7, 4], [0, 4], [1, 5], [2, 6], [3, 7]];
/// A hexahedron's corners' edge neighbours (bottom 0–3 anticlockwise seen from the top
/// 4–7, as VTK and Gmsh number it).
const HEX_CORNER_EDGES: [[usize; 3]; 8] =
    [[1, 3, 4], [2, 0, 5], [3, 1, 6], [0, 2, 7], [7, 5, 0], [4, 6, 1], [5, 7, 2], [6, 4, 3]];
const HEX_FACES: [&[usize]; 6] = [&[0, 3, 2, 1], &[4, 5, 6, 7], &[0, 1, 5, 4], &[1, 2, 6, 5], &[2, 3, 7, 6], &[3, 0, 4, 7]];
const HEX_IDEAL: [[f64; 3]; 8] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [1.0, 1.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [1.0, 0.0, 1.0],
    [1.0, 1.0, 1.0],
    [0.0, 1.0, 1.0],
];
const HEX_EDGE_FOLLOWERS: [&[usize]; 12] =
    [&[0, 1], &[1, 2], &[2, 3], &[3, 0], &[4, 5], &[5, 6], &[6, 7], &[7, 4], &[0, 4], &[1, 5], &[2, 6], &[3, 7]];

const HEX8: VolumeKindRow = VolumeKindRow {
    name: "8-node hexahedron",
    family: "hexahedra",
    nodes: 8,
    corners: 8,
    corner_edges: &HEX_CORNER_EDGES,
    reference: &CUBE_CORNER,
    slot_references: &CUBE_SLOTS,
    edges: &HEX_EDGES,
    followers: &[],
    faces: &HEX_FACES,
    mirror: &[4, 5, 6, 7, 0, 1, 2, 3],
    vtk_type: 12,
    gmsh_type: 5,
    gmsh_order: &[0, 1, 2, 3, 4, 5, 6, 7],
    ideal: &HEX_IDEAL,
    stretch_axes: StretchAxes::Every,
};

/// Mid-edge nodes 8–19 (VTK's `QUADRATIC_HEXAHEDRON`); mirrored top to bottom, the
/// bottom ring's and the top ring's swap.
const HEX20_MIRROR: [usize; 20] = [4, 5, 6, 7, 0, 1, 2, 3, 12, 13, 14, 15, 8, 9, 10, 11, 16, 17, 18, 19];
/// Gmsh's edges of a 20-node hexahedron are (0,1), (0,3), (0,4), (1,2), (1,5), (2,3),
/// (2,6), (3,7), (4,5), (4,7), (5,6), (6,7).
const HEX20_GMSH: [usize; 20] = [0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 16, 9, 17, 10, 18, 19, 12, 15, 13, 14];

const HEX20: VolumeKindRow = VolumeKindRow {
    name: "20-node hexahedron",
    family: "hexahedra",
    nodes: 20,
    corners: 8,
    corner_edges: &HEX_CORNER_EDGES,
    reference: &CUBE_CORNER,
    slot_references: &CUBE_SLOTS,
    edges: &HEX_EDGES,
    followers: &HEX_EDGE_FOLLOWERS,
    faces: &HEX_FACES,
    mirror: &HEX20_MIRROR,
    vtk_type: 25,
    gmsh_type: 17,
    gmsh_order: &HEX20_GMSH,
    ideal: &HEX_IDEAL,
    stretch_axes: StretchAxes::Every,
};

const HEX27: VolumeKindRow = VolumeKindRow {
    name: "27-node hexahedron",
    family: "hexahedra",
    nodes: 27,
    corners: 8,
    corner_edges: &HEX_CORNER_EDGES,
    reference: &CUBE_CORNER,
    slot_references: &CUBE_SLOTS,
    edges: &HEX_EDGES,
    // VTK's `TRIQUADRATIC_HEXAHEDRON`: the mid-edge nodes, then the faces' centres
    // x = 0, x = 1, y = 0, y = 1, z = 0, z = 1, then the element's centre
    followers: &[
        &[0, 1],
        &[1, 2],
        &[2, 3],
        &[3, 0],
        &[4, 5],
        &[5, 6],
        &[6, 7],
        &[7, 4],
        &[0, 4],
        &[1, 5],
        &[2, 6],
        &[3, 7],
        &[0, 3, 7, 4],
        &[1, 2, 6, 5],
        &[0, 1, 5, 4],
        &[3, 2, 6, 7],
        &[0, 1, 2, 3],
        &[4, 5, 6, 7],
        &[0, 1, 2, 3, 4, 5, 6, 7],
    ],
    faces: &HEX_FACES,
    mirror: &[4, 5, 6, 7, 0, 1, 2, 3, 12, 13, 14, 15, 8, 9, 10, 11, 16, 17, 18, 19, 20, 21, 22, 23, 25, 24, 26],
    vtk_type: 29,
    gmsh_type: 12,
    // Gmsh's face centres: z = 0, y = 0, x = 0, x = 1, y = 1, z = 1
    gmsh_order: &[0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 16, 9, 17, 10, 18, 19, 12, 15, 13, 14, 24, 22, 20, 21, 23, 25, 26],
    ideal: &HEX_IDEAL,
    stretch_axes: StretchAxes::Every,
};

const WEDGE6: VolumeKindRow = VolumeKindRow {
    name: "6-node wedge",
    family: "wedges",
    nodes: 6,
    corners: 6,
    // VTK's wedge: the triangle 0 1 2 turns clockwise seen from the triangle 3 4 5 above it
    corner_edges: &[[2, 1, 3], [0, 2, 4], [1, 0, 5], [4, 5, 0], [5, 3, 1], [3, 4, 2]],
    reference: &WEDGE_CORNER,
    slot_references: &WEDGE_SLOTS,
    edges: &[[0, 1], [1, 2], [2, 0], [3, 4], [4, 5], [5, 3], [0, 3], [1, 4], [2, 5]],
    followers: &[],
    faces: &[&[0, 1, 2], &[3, 5, 4], &[0, 2, 5, 3], &[2, 1, 4, 5], &[1, 0, 3, 4]],
    mirror: &[3, 4, 5, 0, 1, 2],
    vtk_type: 13,
    gmsh_type: 6,
    // Gmsh's prism turns its first triangle the other way (anticlockwise seen from the
    // second)
    gmsh_order: &[0, 2, 1, 3, 5, 4],
    ideal: &[
        [0.0, 0.0, 0.0],
        [0.5, 0.866_025_403_784_438_6, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.5, 0.866_025_403_784_438_6, 1.0],
        [1.0, 0.0, 1.0],
    ],
    stretch_axes: StretchAxes::One(2),
};

const PYRAMID5: VolumeKindRow = VolumeKindRow {
    name: "5-node pyramid",
    family: "pyramids",
    nodes: 5,
    corners: 5,
    // the base 0 1 2 3 turns anticlockwise seen from the apex 4; the apex is not measured
    corner_edges: &[[1, 3, 4], [2, 0, 4], [3, 1, 4], [0, 2, 4]],
    reference: &PYRAMID_CORNER,
    slot_references: &PYRAMID_SLOTS,
    edges: &[[0, 1], [1, 2], [2, 3], [3, 0], [0, 4], [1, 4], [2, 4], [3, 4]],
    followers: &[],
    faces: &[&[0, 3, 2, 1], &[0, 1, 4], &[1, 2, 4], &[2, 3, 4], &[3, 0, 4]],
    mirror: &[0, 3, 2, 1, 4],
    vtk_type: 14,
    gmsh_type: 7,
    gmsh_order: &[0, 1, 2, 3, 4],
    ideal: &[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0], [0.5, 0.5, std::f64::consts::FRAC_1_SQRT_2]],
    stretch_axes: StretchAxes::Kept,
};

/// The element kinds of a volume mesh. A mesh may mix the linear kinds (a hexahedral
/// mesh with pyramids and tetrahedra); a quadratic mesh is of one kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, PartialOrd, Ord)]
pub enum VolumeKind {
    /// The linear tetrahedron: 4 corners.
    Tet4,
    /// The quadratic tetrahedron: 4 corners, then the middles of the edges of
    /// [`TET10_EDGES`].
    Tet10,
    /// The trilinear hexahedron: 8 corners.
    Hex8,
    /// The 20-node (serendipity) hexahedron: 8 corners, then the middles of its 12 edges.
    Hex20,
    /// The 27-node (triquadratic) hexahedron: 8 corners, the middles of its 12 edges, of
    /// its 6 faces, and its centre.
    Hex27,
    /// The wedge (triangular prism): 6 corners.
    Wedge6,
    /// The pyramid: a quadrilateral base and an apex.
    Pyramid5,
}

impl VolumeKind {
    pub const ALL: [VolumeKind; 7] = [
        VolumeKind::Tet4,
        VolumeKind::Tet10,
        VolumeKind::Hex8,
        VolumeKind::Hex20,
        VolumeKind::Hex27,
        VolumeKind::Wedge6,
        VolumeKind::Pyramid5,
    ];

    /// The kind's row of data.
    #[inline]
    pub const fn row(self) -> &'static VolumeKindRow {
        match self {
            VolumeKind::Tet4 => &TET4,
            VolumeKind::Tet10 => &TET10,
            VolumeKind::Hex8 => &HEX8,
            VolumeKind::Hex20 => &HEX20,
            VolumeKind::Hex27 => &HEX27,
            VolumeKind::Wedge6 => &WEDGE6,
            VolumeKind::Pyramid5 => &PYRAMID5,
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
    /// Whether the kind is a tetrahedron: its one corner's tetrahedron is the element.
    #[inline]
    pub const fn is_tet(self) -> bool {
        matches!(self, VolumeKind::Tet4 | VolumeKind::Tet10)
    }
    /// Whether the kind has nodes after its corners (they follow the corners).
    #[inline]
    pub const fn is_quadratic(self) -> bool {
        !self.row().followers.is_empty()
    }
    /// The linear kind of its corners (a 20-node hexahedron's is the hexahedron).
    pub const fn linear(self) -> VolumeKind {
        match self {
            VolumeKind::Tet4 | VolumeKind::Tet10 => VolumeKind::Tet4,
            VolumeKind::Hex8 | VolumeKind::Hex20 | VolumeKind::Hex27 => VolumeKind::Hex8,
            VolumeKind::Wedge6 => VolumeKind::Wedge6,
            VolumeKind::Pyramid5 => VolumeKind::Pyramid5,
        }
    }
    #[inline]
    pub const fn reference(self) -> &'static CornerReference {
        self.row().reference
    }
    pub fn name(self) -> &'static str {
        self.row().name
    }
    /// Two kinds in one phrase, fewer nodes first: "4-node and 10-node tetrahedra".
    pub fn mix_words(a: VolumeKind, b: VolumeKind) -> String {
        let (a, b) = if a.nodes() <= b.nodes() { (a.row(), b.row()) } else { (b.row(), a.row()) };
        if a.family == b.family {
            format!("{}-node and {}-node {}", a.nodes, b.nodes, a.family)
        } else {
            format!("{}-node {} and {}-node {}", a.nodes, a.family, b.nodes, b.family)
        }
    }
    /// Whether elements of kinds `a` and `b` may share a mesh: linear kinds mix freely; a
    /// quadratic kind only with itself.
    pub fn mixes_with(a: VolumeKind, b: VolumeKind) -> bool {
        a == b || !(a.is_quadratic() || b.is_quadratic())
    }
    /// The kind of Gmsh element type `t`, if it is one.
    pub fn from_gmsh_type(t: u64) -> Option<VolumeKind> {
        VolumeKind::ALL.into_iter().find(|k| u64::from(k.row().gmsh_type) == t)
    }
    /// The kind of legacy VTK cell type `t`, if it is one.
    pub fn from_vtk_type(t: u64) -> Option<VolumeKind> {
        VolumeKind::ALL.into_iter().find(|k| u64::from(k.row().vtk_type) == t)
    }
    /// The tetrahedron with `n` nodes (files that say only the count, TetGen's `.ele`).
    pub fn with_nodes(n: usize) -> Option<VolumeKind> {
        [VolumeKind::Tet4, VolumeKind::Tet10].into_iter().find(|k| k.nodes() == n)
    }
}

/// How many elements of each [`VolumeKind`] a mesh has (the statistics' count by kind).
/// In JSON a map from the kind's name to its count, kinds without elements left out.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct VolumeKindCounts([usize; VolumeKind::ALL.len()]);

impl VolumeKindCounts {
    /// The counts of the kinds `kinds` lists, one element each.
    pub fn of(kinds: impl IntoIterator<Item = VolumeKind>) -> VolumeKindCounts {
        let mut c = VolumeKindCounts::default();
        for k in kinds {
            c.0[k as usize] += 1;
        }
        c
    }
    /// The number of elements of kind `k`.
    pub fn get(&self, k: VolumeKind) -> usize {
        self.0[k as usize]
    }
    /// Every element counted.
    pub fn total(&self) -> usize {
        self.0.iter().sum()
    }
    /// The kinds with elements and their counts, in [`VolumeKind`]'s order.
    pub fn present(&self) -> impl Iterator<Item = (VolumeKind, usize)> + '_ {
        VolumeKind::ALL.into_iter().map(|k| (k, self.get(k))).filter(|&(_, n)| n > 0)
    }
    /// The counts in words, kinds in [`VolumeKind`]'s order: "305 8-node hexahedra,
    /// 1 5-node pyramid".
    pub fn words(&self) -> String {
        let each: Vec<String> = self
            .present()
            .map(|(k, n)| {
                let r = k.row();
                if n == 1 {
                    format!("1 {}", r.name)
                } else {
                    format!("{n} {}-node {}", r.nodes, r.family)
                }
            })
            .collect();
        each.join(", ")
    }
}

impl Serialize for VolumeKindCounts {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut m = s.serialize_map(Some(self.present().count()))?;
        for (k, n) in self.present() {
            m.serialize_entry(&k, &n)?;
        }
        m.end()
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

    fn ideal(k: VolumeKind) -> Vec<DVec3> {
        let r = k.row();
        let mut p: Vec<DVec3> = r.ideal.iter().map(|&c| DVec3::from(c)).collect();
        for f in r.followers {
            p.push(f.iter().map(|&c| p[c]).sum::<DVec3>() / f.len() as f64);
        }
        p
    }

    /// `T = A·W⁻¹` of corner `c` of element `p`.
    fn corner_t(k: VolumeKind, p: &[DVec3], c: usize) -> DMat3 {
        let [a, b, d] = k.row().corner_edges[c];
        DMat3::from_cols(p[a] - p[c], p[b] - p[c], p[d] - p[c]) * k.reference().w_inv
    }

    #[test]
    fn every_corner_of_the_ideal_element_is_its_reference_turned() {
        for k in VolumeKind::ALL {
            let p = ideal(k);
            for c in 0..k.row().corner_edges.len() {
                let t = corner_t(k, &p, c);
                assert!((t.transpose() * t).abs_diff_eq(DMat3::IDENTITY, 1e-12), "{k:?} corner {c}: {t}");
                assert!((t.determinant() - 1.0).abs() < 1e-12, "{k:?} corner {c}");
            }
        }
    }

    #[test]
    fn a_slot_reference_measures_the_same_corner() {
        let mut rng = crate::numeric::SplitMix64::new(4);
        for k in VolumeKind::ALL {
            let r = k.row();
            for _ in 0..10 {
                let p: [DVec3; 4] = std::array::from_fn(|_| {
                    DVec3::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0))
                });
                let t = |q: [DVec3; 4], w: &CornerReference| DMat3::from_cols(q[1] - q[0], q[2] - q[0], q[3] - q[0]) * w.w_inv;
                let t0 = t(p, r.reference);
                for (s, perm) in WITH_FIRST.iter().enumerate() {
                    let q = perm.map(|j| p[j]);
                    assert!(t(q, &r.slot_references[s]).abs_diff_eq(t0, 1e-12), "{k:?} slot {s}");
                }
            }
        }
    }

    #[test]
    fn kind_counts_say_each_kind_once_in_its_order() {
        use VolumeKind::*;
        let c = VolumeKindCounts::of([Pyramid5, Hex8, Tet4, Hex8, Tet4, Tet4]);
        assert_eq!((c.get(Tet4), c.get(Hex8), c.get(Pyramid5), c.get(Wedge6), c.total()), (3, 2, 1, 0, 6));
        assert_eq!(c.words(), "3 4-node tetrahedra, 2 8-node hexahedra, 1 5-node pyramid");
        assert_eq!(serde_json::to_string(&c).unwrap(), r#"{"Tet4":3,"Hex8":2,"Pyramid5":1}"#);
        assert_eq!(VolumeKindCounts::default().words(), "");
    }

    #[test]
    fn every_row_is_consistent() {
        for k in VolumeKind::ALL {
            let r = k.row();
            assert!(r.corner_edges.len() == r.corners || k == VolumeKind::Pyramid5, "{k:?}");
            assert_eq!(r.nodes, r.corners + r.followers.len(), "{k:?}");
            assert_eq!(r.ideal.len(), r.corners, "{k:?}");
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
            // the ideal element's faces point out (away from its centroid), and its
            // mirror image, renumbered by `mirror`, is the right way round again
            let p = ideal(k);
            let centre = p[..r.corners].iter().sum::<DVec3>() / r.corners as f64;
            for f in r.faces {
                let n = (p[f[1]] - p[f[0]]).cross(p[f[2]] - p[f[0]]);
                assert!(n.dot(p[f[0]] - centre) > 0.0, "{k:?}: face {f:?} points in");
            }
            let mirrored: Vec<DVec3> = p.iter().map(|q| DVec3::new(q.x, q.y, -q.z)).collect();
            let renumbered: Vec<DVec3> = r.mirror.iter().map(|&j| mirrored[j]).collect();
            for c in 0..r.corner_edges.len() {
                assert!(corner_t(k, &renumbered, c).determinant() > 0.0, "{k:?}: mirrored corner {c}");
            }
            // the followers, renumbered, still sit at the means of their corners
            for (i, f) in r.followers.iter().enumerate() {
                let at = f.iter().map(|&c| renumbered[c]).sum::<DVec3>() / f.len() as f64;
                assert!(at.distance(renumbered[r.corners + i]) < 1e-12, "{k:?}: follower {i}");
            }
            assert_eq!(VolumeKind::from_gmsh_type(u64::from(r.gmsh_type)), Some(k));
            assert_eq!(VolumeKind::from_vtk_type(u64::from(r.vtk_type)), Some(k));
        }
    }
}
