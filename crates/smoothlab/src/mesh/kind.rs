//! The element kinds and the parts nodes play in them.

use serde::Serialize;

/// The element kinds smoothlab reads, smooths and draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub enum ElementKind {
    /// 3-node triangle.
    Tri3,
    /// 4-node quadrilateral.
    Quad4,
    /// 6-node (quadratic) triangle: corners, then mid-sides of 0-1, 1-2, 2-0.
    Tri6,
    /// 8-node (serendipity) quadrilateral: corners, then mid-sides of 0-1, 1-2, 2-3, 3-0.
    Quad8,
    /// 9-node (biquadratic) quadrilateral: as `Quad8` plus the centre node.
    Quad9,
}

impl ElementKind {
    /// Number of corner nodes (3 or 4).
    pub fn corners(self) -> usize {
        match self {
            ElementKind::Tri3 | ElementKind::Tri6 => 3,
            _ => 4,
        }
    }
    /// Which of the ideal's axes a stretch target lays onto its stretch's axes
    /// ([`super::StretchAxes`]): both of a quadrilateral's, as a hexahedron's (a boundary
    /// layer's fit then keeps its first row: `docs/formulas.md`, Targets); a triangle's turn
    /// is kept.
    pub fn stretch_axes(self) -> super::StretchAxes {
        match self.corners() {
            4 => super::StretchAxes::Every,
            _ => super::StretchAxes::Kept,
        }
    }
    /// Number of nodes of the element.
    pub fn node_count(self) -> usize {
        match self {
            ElementKind::Tri3 => 3,
            ElementKind::Quad4 => 4,
            ElementKind::Tri6 => 6,
            ElementKind::Quad8 => 8,
            ElementKind::Quad9 => 9,
        }
    }
    pub fn is_triangle(self) -> bool {
        self.corners() == 3
    }
    pub fn is_quad(self) -> bool {
        self.corners() == 4
    }
    /// True for the elements with mid-side nodes.
    pub fn is_quadratic(self) -> bool {
        matches!(self, ElementKind::Tri6 | ElementKind::Quad8 | ElementKind::Quad9)
    }
    /// Local index of the mid-side node of edge `i` (corner `i` → corner `i+1`), if any.
    pub fn mid(self, i: usize) -> Option<usize> {
        if self.is_quadratic() {
            Some(self.corners() + i)
        } else {
            None
        }
    }
    /// The element of the same family with mid-side nodes, or without.
    pub fn from_parts(corners: usize, quadratic: bool, centre: bool) -> Option<ElementKind> {
        match (corners, quadratic, centre) {
            (3, false, false) => Some(ElementKind::Tri3),
            (4, false, false) => Some(ElementKind::Quad4),
            (3, true, false) => Some(ElementKind::Tri6),
            (4, true, false) => Some(ElementKind::Quad8),
            (4, true, true) => Some(ElementKind::Quad9),
            _ => None,
        }
    }
    /// A short lowercase name, as used in messages.
    pub fn name(self) -> &'static str {
        match self {
            ElementKind::Tri3 => "3-node triangle",
            ElementKind::Quad4 => "4-node quad",
            ElementKind::Tri6 => "6-node triangle",
            ElementKind::Quad8 => "8-node quad",
            ElementKind::Quad9 => "9-node quad",
        }
    }
    /// Local node order of the same element with its orientation reversed:
    /// corners `0, n-1, …, 1`, mid-sides re-attached to the reversed edges.
    pub(super) fn reversed_order(self) -> &'static [usize] {
        match self {
            ElementKind::Tri3 => &[0, 2, 1],
            ElementKind::Quad4 => &[0, 3, 2, 1],
            ElementKind::Tri6 => &[0, 2, 1, 5, 4, 3],
            ElementKind::Quad8 => &[0, 3, 2, 1, 7, 6, 5, 4],
            ElementKind::Quad9 => &[0, 3, 2, 1, 7, 6, 5, 4, 8],
        }
    }
}

/// What part a node plays in the elements that use it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum NodeRole {
    /// A corner of at least one element: the nodes the smoothers move.
    Corner,
    /// A mid-side node of quadratic elements: follows its edge.
    Mid,
    /// The centre node of a 9-node quad: follows its element.
    Centre,
    /// Not used by any element (kept so node numbers stay as in the file).
    Unused,
}
