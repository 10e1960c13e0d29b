//! The mesh model: node positions (`glam::DVec2`), elements of five kinds, a per-node
//! `fixed` flag, and the topology built once into flat (CSR-style) arrays.
//!
//! Element node order follows Gmsh and VTK: the corners counter-clockwise, then the
//! mid-side nodes of the edges (corner 0→1, 1→2, …), then (9-node quad) the centre.
//!
//! Orientation is a property of the whole mesh: [`MeshBuilder::build`] makes the total
//! signed area positive by reversing *every* element when it is negative, never one
//! element alone, so a tangled mesh stays tangled until it is smoothed.

use std::sync::Arc;

use glam::DVec2;
use serde::Serialize;

use crate::error::{Error, Result};

/// Marker for "no such index" in the flat arrays.
pub const NONE: u32 = u32::MAX;

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
    fn reversed_order(self) -> &'static [usize] {
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

/// An edge between two corner nodes, with its mid-side node when quadratic.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Edge {
    /// Corner nodes, `a < b`.
    pub a: u32,
    pub b: u32,
    /// Mid-side node, or [`NONE`].
    pub mid: u32,
    /// Used by one element only.
    pub boundary: bool,
    /// A boundary edge whose mid-side node is off the chord (curved boundary).
    pub curved: bool,
}

impl Edge {
    pub fn is_boundary(&self) -> bool {
        self.boundary
    }
}

/// Connectivity, built once from the elements: node → elements, node → neighbour
/// corner nodes, the unique edges, and boundary flags. Flat arrays with offsets.
#[derive(Clone, Debug, Default)]
pub struct Topology {
    node_elem_start: Vec<u32>,
    node_elems: Vec<u32>,
    node_nbr_start: Vec<u32>,
    node_nbrs: Vec<u32>,
    edges: Vec<Edge>,
    role: Vec<NodeRole>,
    boundary: Vec<bool>,
    on_curved: Vec<bool>,
    /// Which element families occur, found once so the per-node queries
    /// ([`Mesh::has_triangles`], …) cost O(1) instead of a scan of all elements.
    kinds_present: KindsPresent,
}

/// One array of a mesh and its size (see [`Mesh::memory_parts`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MemoryPart {
    pub name: &'static str,
    /// Its capacity in bytes.
    pub bytes: usize,
    /// Whether clones of the mesh share it.
    pub shared: bool,
}

/// What a mesh's clones share: the elements and the topology built from them.
#[derive(Debug, Default)]
struct Connectivity {
    kinds: Vec<ElementKind>,
    elem_start: Vec<u32>,
    elem_nodes: Vec<u32>,
    topo: Topology,
}

/// Which element families a mesh holds.
#[derive(Clone, Copy, Debug, Default)]
struct KindsPresent {
    triangles: bool,
    quads: bool,
    quadratic: bool,
}

/// A planar 2D mesh of triangles and quads, linear or quadratic, possibly mixed.
///
/// The elements and the topology never change once built, and clones share them: a
/// clone copies the positions and fixed flags only (17 bytes a node), so the page's
/// two sides hold one connectivity between them.
#[derive(Clone, Debug)]
pub struct Mesh {
    /// Node positions. The smoothers move corner nodes here; mid-side nodes follow.
    pub nodes: Vec<DVec2>,
    /// Nodes that never move.
    pub fixed: Vec<bool>,
    conn: Arc<Connectivity>,
    /// The 3D plane the file's points lay in, when they were not in the xy plane at z = 0
    /// (see [`Mesh::to_3d`]); `None` for a 2D mesh.
    pub plane: Option<Plane>,
}

/// A plane in 3D: the point that 2D coordinates `(0, 0)` stand for and two orthonormal
/// axes along which the mesh's 2D `x` and `y` run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    pub origin: glam::DVec3,
    pub u: glam::DVec3,
    pub w: glam::DVec3,
}

impl Plane {
    /// The 3D point of the plane's 2D coordinates `p`.
    pub fn to_3d(&self, p: DVec2) -> glam::DVec3 {
        self.origin + self.u * p.x + self.w * p.y
    }
}

impl Mesh {
    /// The 3D position of a 2D point of the mesh: in the plane the file's points lay in
    /// (so a mesh read from 3D is written back where it was), else at z = 0.
    pub fn to_3d(&self, p: DVec2) -> glam::DVec3 {
        match &self.plane {
            Some(plane) => plane.to_3d(p),
            None => glam::DVec3::new(p.x, p.y, 0.0),
        }
    }

    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }
    pub fn element_count(&self) -> usize {
        self.conn.kinds.len()
    }
    pub fn kind(&self, e: usize) -> ElementKind {
        self.conn.kinds[e]
    }
    pub fn kinds(&self) -> &[ElementKind] {
        &self.conn.kinds
    }
    /// The node indices of element `e`, in the order documented at the top of this module.
    pub fn element(&self, e: usize) -> &[u32] {
        &self.conn.elem_nodes[self.conn.elem_start[e] as usize..self.conn.elem_start[e + 1] as usize]
    }
    /// Positions of the nodes of element `e`, copied into `out` (cleared first).
    pub fn element_points(&self, e: usize, out: &mut Vec<DVec2>) {
        out.clear();
        out.extend(self.element(e).iter().map(|&n| self.nodes[n as usize]));
    }
    /// Positions of the nodes of element `e` in a fixed-size array (unused slots are zero).
    pub fn element_points_array(&self, e: usize) -> [DVec2; 9] {
        let mut p = [DVec2::ZERO; 9];
        for (i, &n) in self.element(e).iter().enumerate() {
            p[i] = self.nodes[n as usize];
        }
        p
    }
    pub fn topology(&self) -> &Topology {
        &self.conn.topo
    }
    /// Elements that use node `n` (its star).
    pub fn node_elements(&self, n: usize) -> &[u32] {
        self.conn.topo.node_elements(n)
    }
    /// Corner nodes joined to corner node `n` by an element edge.
    pub fn neighbours(&self, n: usize) -> &[u32] {
        self.conn.topo.neighbours(n)
    }
    pub fn edges(&self) -> &[Edge] {
        &self.conn.topo.edges
    }
    pub fn is_boundary(&self, n: usize) -> bool {
        self.conn.topo.boundary[n]
    }
    pub fn role(&self, n: usize) -> NodeRole {
        self.conn.topo.role[n]
    }
    /// Whether node `n` is an end or mid node of a curved boundary edge.
    pub fn is_on_curved_boundary(&self, n: usize) -> bool {
        self.conn.topo.on_curved[n]
    }
    /// A node the smoothers may move: a corner that is not fixed.
    pub fn is_free(&self, n: usize) -> bool {
        !self.fixed[n] && self.conn.topo.role[n] == NodeRole::Corner
    }
    pub fn free_count(&self) -> usize {
        (0..self.node_count()).filter(|&n| self.is_free(n)).count()
    }
    pub fn has_quadratic(&self) -> bool {
        self.conn.topo.kinds_present.quadratic
    }
    pub fn has_triangles(&self) -> bool {
        self.conn.topo.kinds_present.triangles
    }
    pub fn has_quads(&self) -> bool {
        self.conn.topo.kinds_present.quads
    }
    /// Signed area of the corner polygon of element `e` (positive when counter-clockwise).
    pub fn corner_area(&self, e: usize) -> f64 {
        let k = self.conn.kinds[e].corners();
        let ids = self.element(e);
        polygon_area((0..k).map(|i| self.nodes[ids[i] as usize]))
    }
    /// Mean length of the element edges (corner to corner); 0 for an empty mesh. Each
    /// length by `hypot`, so that it neither overflows near 1e300 nor underflows near
    /// 1e-300 (the renderer decides from it whether edges are drawn).
    pub fn mean_edge_length(&self) -> f64 {
        let edges = &self.conn.topo.edges;
        if edges.is_empty() {
            return 0.0;
        }
        let s: f64 = edges
            .iter()
            .map(|e| {
                let d = self.nodes[e.a as usize] - self.nodes[e.b as usize];
                d.x.hypot(d.y)
            })
            .sum();
        s / edges.len() as f64
    }
    /// Axis-aligned bounds (min, max) of the nodes used by elements.
    pub fn bounds(&self) -> (DVec2, DVec2) {
        let mut lo = DVec2::splat(f64::INFINITY);
        let mut hi = DVec2::splat(f64::NEG_INFINITY);
        for (n, p) in self.nodes.iter().enumerate() {
            if self.conn.topo.role[n] != NodeRole::Unused {
                lo = lo.min(*p);
                hi = hi.max(*p);
            }
        }
        (lo, hi)
    }
    /// Place every mid-side node of an interior (not curved-boundary) edge at the midpoint
    /// of its corners, and every 9-node centre at the mean of its eight edge nodes.
    /// This is the rule by which mid-side nodes follow the corners the smoothers move;
    /// curved boundary edges keep their mid node. Call after moving corner nodes.
    pub fn update_mid_nodes(&mut self) {
        for e in &self.conn.topo.edges {
            if e.mid != NONE && !e.curved && !self.fixed[e.mid as usize] {
                self.nodes[e.mid as usize] = 0.5 * (self.nodes[e.a as usize] + self.nodes[e.b as usize]);
            }
        }
        for el in 0..self.conn.kinds.len() {
            if self.conn.kinds[el] == ElementKind::Quad9 {
                let ids = self.element(el);
                let c = ids[8] as usize;
                if !self.fixed[c] {
                    let s: DVec2 = ids[..8].iter().map(|&n| self.nodes[n as usize]).sum();
                    self.nodes[c] = s / 8.0;
                }
            }
        }
    }
    /// Mid-side nodes that follow corner node `n` (on its non-curved edges), so a
    /// driver can move them right after moving `n`.
    pub fn follow_mid_nodes(&mut self, n: usize) {
        if !self.has_quadratic() {
            return;
        }
        for &el in self.conn.topo.node_elements(n) {
            let el = el as usize;
            let kind = self.conn.kinds[el];
            if !kind.is_quadratic() {
                continue;
            }
            let start = self.conn.elem_start[el] as usize;
            let k = kind.corners();
            for i in 0..k {
                let a = self.conn.elem_nodes[start + i] as usize;
                let b = self.conn.elem_nodes[start + (i + 1) % k] as usize;
                if a != n && b != n {
                    continue;
                }
                let m = self.conn.elem_nodes[start + k + i] as usize;
                if self.fixed[m] || self.conn.topo.on_curved[m] {
                    continue;
                }
                self.nodes[m] = 0.5 * (self.nodes[a] + self.nodes[b]);
            }
            if kind == ElementKind::Quad9 {
                let c = self.conn.elem_nodes[start + 8] as usize;
                if !self.fixed[c] {
                    let s: DVec2 = (0..8).map(|i| self.nodes[self.conn.elem_nodes[start + i] as usize]).sum();
                    self.nodes[c] = s / 8.0;
                }
            }
        }
    }
    /// The same mesh with its nodes renumbered along a Hilbert curve, so that nodes near
    /// each other in the plane are near each other in memory (the smoothers then find a
    /// node's star and neighbours in cache), and its elements sorted by their first node
    /// in the new numbering. Returns the mesh and the permutation `perm`, `perm[new] = old`.
    ///
    /// Positions, fixed flags, element kinds and node orders within elements are kept; node
    /// and element *numbers* change, so a renumbered mesh is for computing on: smooth it,
    /// then put the positions back into the original numbering with
    /// [`restore_positions`](Self::restore_positions). Nodes no element uses go last.
    pub fn renumbered_spatially(&self) -> (Mesh, Vec<u32>) {
        let n = self.nodes.len();
        let (lo, hi) = self.bounds();
        let size = (hi - lo).max_element();
        let cells = (1u32 << HILBERT_ORDER) as f64;
        let scale = if size > 0.0 && size.is_finite() { (cells - 1.0) / size } else { 0.0 };
        let key = |i: usize| -> u64 {
            if self.conn.topo.role[i] == NodeRole::Unused {
                return u64::MAX;
            }
            let q = ((self.nodes[i] - lo) * scale).clamp(DVec2::ZERO, DVec2::splat(cells - 1.0));
            hilbert_index(q.x as u32, q.y as u32)
        };
        let mut order: Vec<(u64, u32)> = (0..n).map(|i| (key(i), i as u32)).collect();
        order.sort_unstable();
        let perm: Vec<u32> = order.iter().map(|&(_, i)| i).collect();
        drop(order);
        let mut inv = vec![0u32; n];
        for (new, &old) in perm.iter().enumerate() {
            inv[old as usize] = new as u32;
        }
        let ne = self.conn.kinds.len();
        let mut elems: Vec<(u32, u32)> = (0..ne).map(|e| (inv[self.element(e)[0] as usize], e as u32)).collect();
        elems.sort_unstable();
        let mut kinds = Vec::with_capacity(ne);
        let mut elem_start = Vec::with_capacity(ne + 1);
        let mut elem_nodes = Vec::with_capacity(self.conn.elem_nodes.len());
        elem_start.push(0);
        for &(_, e) in &elems {
            kinds.push(self.conn.kinds[e as usize]);
            elem_nodes.extend(self.element(e as usize).iter().map(|&i| inv[i as usize]));
            elem_start.push(elem_nodes.len() as u32);
        }
        let mut mesh = Mesh {
            nodes: perm.iter().map(|&i| self.nodes[i as usize]).collect(),
            fixed: perm.iter().map(|&i| self.fixed[i as usize]).collect(),
            conn: Arc::new(Connectivity { kinds, elem_start, elem_nodes, topo: Topology::default() }),
            plane: self.plane,
        };
        // The same elements under other numbers: every check that passed for `self`
        // passes here, so building the topology cannot fail.
        let topo = build_topology(&mesh, &[]).expect("renumbering keeps a valid topology");
        mesh.connectivity_mut().topo = topo;
        (mesh, perm)
    }

    /// The connectivity of a mesh being built, not shared yet.
    fn connectivity_mut(&mut self) -> &mut Connectivity {
        Arc::get_mut(&mut self.conn).expect("a mesh being built shares nothing")
    }

    /// Copies the node positions of `renumbered`, a mesh made by
    /// [`renumbered_spatially`](Self::renumbered_spatially) from this one (and smoothed,
    /// say), back into this mesh's numbering: `self.nodes[perm[i]] = renumbered.nodes[i]`.
    pub fn restore_positions(&mut self, renumbered: &Mesh, perm: &[u32]) -> Result<()> {
        let n = self.nodes.len();
        if renumbered.nodes.len() != n || perm.len() != n {
            return Err(Error::invalid(format!(
                "cannot restore positions: {} nodes here, {} in the renumbered mesh, {} in the permutation",
                n,
                renumbered.nodes.len(),
                perm.len()
            )));
        }
        if let Some(&bad) = perm.iter().find(|&&p| p as usize >= n) {
            return Err(Error::invalid(format!("cannot restore positions: the permutation names node {bad}")));
        }
        for (i, &old) in perm.iter().enumerate() {
            self.nodes[old as usize] = renumbered.nodes[i];
        }
        Ok(())
    }

    /// Bytes held by the mesh: the capacities of all its arrays (positions, flags,
    /// elements and the topology, shared ones included), not counting the `Mesh`
    /// struct itself. [`memory_parts`](Self::memory_parts) says where they are.
    pub fn heap_bytes(&self) -> usize {
        self.memory_parts().iter().map(|p| p.bytes).sum()
    }

    /// Each array of the mesh with the bytes it holds (its capacity), and whether clones
    /// share it (the elements and the topology) or each has its own (positions, flags).
    pub fn memory_parts(&self) -> Vec<MemoryPart> {
        fn part<T>(name: &'static str, v: &Vec<T>, shared: bool) -> MemoryPart {
            MemoryPart { name, bytes: v.capacity() * std::mem::size_of::<T>(), shared }
        }
        let (c, t) = (&*self.conn, &self.conn.topo);
        vec![
            part("node positions (DVec2)", &self.nodes, false),
            part("fixed flags", &self.fixed, false),
            part("element kinds", &c.kinds, true),
            part("element offsets (u32)", &c.elem_start, true),
            part("element nodes (u32)", &c.elem_nodes, true),
            part("node → elements offsets (u32)", &t.node_elem_start, true),
            part("node → elements (u32)", &t.node_elems, true),
            part("node → neighbours offsets (u32)", &t.node_nbr_start, true),
            part("node → neighbours (u32)", &t.node_nbrs, true),
            part("edges (a, b, mid, flags: 16 bytes)", &t.edges, true),
            part("node roles", &t.role, true),
            part("boundary flags", &t.boundary, true),
            part("curved-boundary flags", &t.on_curved, true),
        ]
    }

    /// Checks the invariants of the model; used by the tests (as spade's `sanity_check`).
    pub fn sanity_check(&self) -> std::result::Result<(), String> {
        let n = self.nodes.len();
        if self.fixed.len() != n || self.conn.topo.role.len() != n || self.conn.topo.boundary.len() != n {
            return Err("per-node arrays differ in length".into());
        }
        if self.conn.elem_start.len() != self.conn.kinds.len() + 1 {
            return Err("element offsets".into());
        }
        for e in 0..self.conn.kinds.len() {
            let ids = self.element(e);
            if ids.len() != self.conn.kinds[e].node_count() {
                return Err(format!("element {e} has {} nodes", ids.len()));
            }
            for &i in ids {
                if i as usize >= n {
                    return Err(format!("element {e} refers to node {i}"));
                }
                if !self.node_elements(i as usize).contains(&(e as u32)) {
                    return Err(format!("node {i} does not list element {e}"));
                }
            }
        }
        for p in &self.nodes {
            if !p.is_finite() {
                return Err("non-finite coordinate".into());
            }
        }
        for (i, e) in self.conn.topo.edges.iter().enumerate() {
            if e.a >= e.b {
                return Err(format!("edge {i} not ordered"));
            }
            if !self.neighbours(e.a as usize).contains(&e.b) || !self.neighbours(e.b as usize).contains(&e.a) {
                return Err(format!("edge {i} missing from neighbour lists"));
            }
            if e.is_boundary() && !(self.conn.topo.boundary[e.a as usize] && self.conn.topo.boundary[e.b as usize]) {
                return Err(format!("boundary edge {i} has an interior end"));
            }
        }
        Ok(())
    }
}

impl Topology {
    pub fn node_elements(&self, n: usize) -> &[u32] {
        &self.node_elems[self.node_elem_start[n] as usize..self.node_elem_start[n + 1] as usize]
    }
    pub fn neighbours(&self, n: usize) -> &[u32] {
        &self.node_nbrs[self.node_nbr_start[n] as usize..self.node_nbr_start[n + 1] as usize]
    }
    pub fn edges(&self) -> &[Edge] {
        &self.edges
    }
    pub fn boundary_edges(&self) -> impl Iterator<Item = &Edge> {
        self.edges.iter().filter(|e| e.is_boundary())
    }
}

/// Bits per axis of the Hilbert curve used by [`Mesh::renumbered_spatially`]: a
/// 65 536 × 65 536 grid over the mesh's bounding square.
const HILBERT_ORDER: u32 = 16;

/// Index of cell `(x, y)` along the Hilbert curve of order [`HILBERT_ORDER`] (the classic
/// quadrant-rotation algorithm): consecutive indices are neighbouring cells.
fn hilbert_index(mut x: u32, mut y: u32) -> u64 {
    let n = 1u32 << HILBERT_ORDER;
    let mut d = 0u64;
    let mut s = n / 2;
    while s > 0 {
        let rx = u32::from(x & s > 0);
        let ry = u32::from(y & s > 0);
        d += u64::from(s) * u64::from(s) * u64::from((3 * rx) ^ ry);
        // rotate the quadrant so the curve continues
        if ry == 0 {
            if rx == 1 {
                x = n - 1 - x;
                y = n - 1 - y;
            }
            std::mem::swap(&mut x, &mut y);
        }
        s /= 2;
    }
    d
}

/// Signed area of a polygon given by its vertices in order (shoelace formula).
pub fn polygon_area(pts: impl Iterator<Item = DVec2> + Clone) -> f64 {
    let first = pts.clone().next();
    let Some(first) = first else { return 0.0 };
    let mut s = 0.0;
    let mut prev = first;
    for p in pts.skip(1) {
        s += prev.perp_dot(p);
        prev = p;
    }
    s += prev.perp_dot(first);
    0.5 * s
}

/// How the fixed flags of a mesh are decided.
#[derive(Clone, Debug, Default, PartialEq)]
pub enum FixedSpec {
    /// Boundary nodes (of corner-to-corner edges used by one element, with their mid nodes).
    #[default]
    Boundary,
    /// Exactly as the file says (VTK `POINT_DATA` scalar `fixed`).
    Exact(Vec<bool>),
    /// Boundary nodes plus the nodes the file marks (Gmsh line/point elements,
    /// Triangle boundary markers).
    BoundaryAnd(Vec<bool>),
}

/// The largest coordinate magnitude smoothlab computes with, `f64::MAX / 16` (about
/// 1.1e307): differences of coordinates and the end tangents `4M − 3P0 − P2` of quadratic
/// edges stay finite below it.
pub const MAX_COORDINATE: f64 = f64::MAX / 16.0;

/// Why a coordinate cannot be computed with, if it cannot: beyond [`MAX_COORDINATE`].
/// (Tiny ones are fine: a subnormal next to 1e-300 is a jittered zero, and the metrics
/// work in each element's own scale.)
fn beyond_arithmetic(c: f64) -> Option<String> {
    (c.abs() > MAX_COORDINATE).then(|| {
        format!(
            "coordinate {c:e} is too large to compute with: smoothlab takes magnitudes up to {MAX_COORDINATE:.1e} \
             (differences and quadratic edge tangents of larger ones overflow 64-bit floats)"
        )
    })
}

/// Relative tolerance within which 3D points count as planar: of the size of a node's
/// elements, or of its coordinates' magnitude (rounding), whichever is larger.
pub const PLANAR_TOLERANCE: f64 = 1e-5;

/// Collects what a reader found in a file, then validates it and builds a [`Mesh`].
/// Readers record the file line of every node and element so that errors found here
/// can still name the line.
#[derive(Clone, Debug, Default)]
pub struct MeshBuilder {
    points: Vec<[f64; 3]>,
    point_lines: Vec<u32>,
    kinds: Vec<ElementKind>,
    elem_start: Vec<u32>,
    elem_nodes: Vec<u32>,
    elem_lines: Vec<u32>,
    /// How fixed flags are decided.
    pub fixed: FixedSpec,
}

impl MeshBuilder {
    pub fn new() -> Self {
        MeshBuilder { elem_start: vec![0], ..Default::default() }
    }
    /// A builder with room reserved for the given counts, capped (at 2¹⁶ of each) so a
    /// header that claims large counts costs a fixed amount until the data is seen;
    /// beyond that the arrays grow as nodes and elements are added.
    pub fn with_capacity(nodes: usize, elements: usize) -> Self {
        const CAP: usize = 1 << 16;
        let mut b = Self::new();
        b.points.reserve(nodes.min(CAP));
        b.point_lines.reserve(nodes.min(CAP));
        b.kinds.reserve(elements.min(CAP));
        b.elem_lines.reserve(elements.min(CAP));
        b
    }
    /// Reserves room for exactly this many more nodes, elements and element node ids (for
    /// counts that are known, not claimed by a file): no array then grows by doubling,
    /// which in wasm copies it and holds both copies for a moment.
    pub(crate) fn reserve_exact(&mut self, nodes: usize, elements: usize, element_nodes: usize) {
        self.points.reserve_exact(nodes);
        self.point_lines.reserve_exact(nodes);
        self.kinds.reserve_exact(elements);
        self.elem_start.reserve_exact(elements);
        self.elem_lines.reserve_exact(elements);
        self.elem_nodes.reserve_exact(element_nodes);
    }
    /// Adds a node given in 3D (`z = 0` for 2D formats); `line` is its file line (0 if none).
    pub fn add_node(&mut self, p: [f64; 3], line: usize) -> usize {
        self.points.push(p);
        self.point_lines.push(line as u32);
        self.points.len() - 1
    }
    pub fn node_count(&self) -> usize {
        self.points.len()
    }
    pub fn element_count(&self) -> usize {
        self.kinds.len()
    }
    /// The file line of every node added (0 where none was given).
    pub(crate) fn node_lines(&self) -> &[u32] {
        &self.point_lines
    }
    /// Adds an element with 0-based node indices (checked in [`build`](Self::build)).
    pub fn add_element(&mut self, kind: ElementKind, nodes: &[u32], line: usize) {
        debug_assert_eq!(nodes.len(), kind.node_count());
        self.kinds.push(kind);
        self.elem_nodes.extend_from_slice(nodes);
        self.elem_start.push(self.elem_nodes.len() as u32);
        self.elem_lines.push(line as u32);
    }
    fn line_of_elem(&self, e: usize) -> Option<usize> {
        self.elem_lines.get(e).copied().filter(|&l| l > 0).map(|l| l as usize)
    }
    fn line_of_node(&self, n: usize) -> Option<usize> {
        self.point_lines.get(n).copied().filter(|&l| l > 0).map(|l| l as usize)
    }

    /// Validates (finite coordinates, indices in range, no repeated node in an element,
    /// at least one element, planarity), maps 3D points to the mesh's plane, orients
    /// the mesh counter-clockwise as a whole, builds the topology and the fixed flags.
    pub fn build(mut self) -> Result<Mesh> {
        if self.kinds.is_empty() {
            return Err(Error::Empty(if self.points.is_empty() {
                "no nodes and no elements".into()
            } else {
                format!("{} nodes but no triangle or quad elements", self.points.len())
            }));
        }
        for (i, p) in self.points.iter().enumerate() {
            if !p.iter().all(|c| c.is_finite()) {
                return Err(Error::node(i, self.line_of_node(i), format!("coordinate is not a finite number: {p:?}")));
            }
            if let Some(why) = p.iter().find_map(|&c| beyond_arithmetic(c)) {
                return Err(Error::node(i, self.line_of_node(i), why));
            }
        }
        let n = self.points.len();
        for e in 0..self.kinds.len() {
            let ids = &self.elem_nodes[self.elem_start[e] as usize..self.elem_start[e + 1] as usize];
            for &i in ids {
                if i as usize >= n {
                    return Err(Error::element(
                        e,
                        self.line_of_elem(e),
                        format!("refers to node {} but the mesh has {} nodes", i as u64 + 1, n),
                    ));
                }
            }
            for a in 0..ids.len() {
                if ids[a + 1..].contains(&ids[a]) {
                    return Err(Error::element(
                        e,
                        self.line_of_elem(e),
                        format!("{} uses node {} twice", self.kinds[e].name(), ids[a] as u64 + 1),
                    ));
                }
            }
        }
        let (nodes, plane) = self.to_plane()?;
        // the 3D points are not needed past the plane: let them go before the topology is
        // built (24 bytes a node), and give back what the readers' growing left unused
        self.points = Vec::new();
        let (mut kinds, mut elem_start, mut elem_nodes) = (self.kinds, self.elem_start, self.elem_nodes);
        kinds.shrink_to_fit();
        elem_start.shrink_to_fit();
        elem_nodes.shrink_to_fit();
        let mut mesh = Mesh {
            plane,
            nodes,
            fixed: vec![false; n],
            conn: Arc::new(Connectivity { kinds, elem_start, elem_nodes, topo: Topology::default() }),
        };
        // Orientation of the whole mesh by its total signed area, decided by the sign of
        // total − (total of the reversed mesh), each summed as its own corner order gives:
        // reversing negates that difference exactly, so a mesh reversed here is never
        // reversed again when written and read back. (The sign of the total alone flipped
        // back and forth when huge coordinates left a total of rounding noise.)
        // The areas are taken in units of the largest coordinate (a power of two, exact):
        // near 1e-200 they underflowed to 0 and a clockwise mesh stayed clockwise.
        let unit = {
            let m = mesh.nodes.iter().fold(0.0f64, |m, p| m.max(p.x.abs()).max(p.y.abs()));
            let mut v = [DVec2::new(m, 0.0)];
            let f = crate::quality::to_unit_scale(&mut v);
            f[0] * f[1]
        };
        let area_in = |e: usize, order: &[usize]| {
            let ids = mesh.element(e);
            polygon_area(order.iter().map(|&j| mesh.nodes[ids[j] as usize] * unit))
        };
        let forward: f64 = (0..mesh.conn.kinds.len()).map(|e| area_in(e, &[0, 1, 2, 3][..mesh.conn.kinds[e].corners()])).sum();
        let backward: f64 = (0..mesh.conn.kinds.len())
            .map(|e| area_in(e, &mesh.conn.kinds[e].reversed_order()[..mesh.conn.kinds[e].corners()]))
            .sum();
        if forward - backward < 0.0 {
            let c = mesh.connectivity_mut();
            for e in 0..c.kinds.len() {
                let s = c.elem_start[e] as usize;
                let k = c.kinds[e];
                let mut old = [0u32; 9];
                old[..k.node_count()].copy_from_slice(&c.elem_nodes[s..s + k.node_count()]);
                for (i, &j) in k.reversed_order().iter().enumerate() {
                    c.elem_nodes[s + i] = old[j];
                }
            }
        }
        let topo = build_topology(&mesh, &self.elem_lines)?;
        mesh.connectivity_mut().topo = topo;
        let boundary = mesh.conn.topo.boundary.clone();
        mesh.fixed = match self.fixed {
            FixedSpec::Boundary => boundary,
            FixedSpec::Exact(f) => {
                if f.len() != n {
                    return Err(Error::invalid(format!("{} fixed flags for {} nodes", f.len(), n)));
                }
                f
            }
            FixedSpec::BoundaryAnd(f) => boundary.iter().zip(f.iter().chain(std::iter::repeat(&false))).map(|(a, b)| *a || *b).collect(),
        };
        // Nodes no element uses never move.
        for i in 0..n {
            if mesh.conn.topo.role[i] == NodeRole::Unused {
                mesh.fixed[i] = true;
            }
        }
        Ok(mesh)
    }

    /// 2D coordinates of the points: as given when every z is equal, else in the plane of
    /// the elements; refuses non-planar input naming the node farthest off, how far, and
    /// how that compares with the size of its elements. With them the plane to map them
    /// back into 3D (`None` when every z is 0), so writers put the mesh back where it was.
    ///
    /// The plane is fitted robustly, so that one node far off (a mistyped exponent) can
    /// neither tilt it nor hide behind the size it gives the mesh: its normal is the
    /// component-wise median of the elements' unit normals (each element one vote,
    /// whatever its size; signs aligned), and its offset the median of the nodes'
    /// offsets. Each node must then lie within [`PLANAR_TOLERANCE`] of the size of the
    /// largest element it belongs to (measured in the plane), or of its own coordinates'
    /// magnitude, whichever is larger: rounding in the file is excused, an outlier is not,
    /// however large the mesh around it.
    fn to_plane(&self) -> Result<(Vec<DVec2>, Option<Plane>)> {
        let z0 = self.points.first().map(|p| p[2]).unwrap_or(0.0);
        if self.points.iter().all(|p| p[2] == z0) {
            let plane = (z0 != 0.0).then_some(Plane { origin: glam::DVec3::new(0.0, 0.0, z0), u: glam::DVec3::X, w: glam::DVec3::Y });
            return Ok((self.points.iter().map(|p| DVec2::new(p[0], p[1])).collect(), plane));
        }
        // Work in units of the largest coordinate magnitude, so that the cross products
        // and distances below neither overflow (coordinates near 1e200 once gave NaN
        // coordinates) nor underflow (near 1e-160, "no area") for any finite input.
        // The z values differ, so some coordinate is nonzero and the scale is positive.
        let scale = self.points.iter().flatten().fold(0.0f64, |m, c| m.max(c.abs()));
        let v = |p: &[f64; 3]| glam::DVec3::new(p[0] / scale, p[1] / scale, p[2] / scale);
        let elem = |e: usize| &self.elem_nodes[self.elem_start[e] as usize..self.elem_start[e + 1] as usize];
        // Each element's unit normal (Newell's method on its corner polygon, in units of
        // its own extent from its first corner, so that tiny elements do not underflow).
        let mut normals = Vec::with_capacity(self.kinds.len());
        for e in 0..self.kinds.len() {
            let ids = elem(e);
            let k = self.kinds[e].corners();
            let o = v(&self.points[ids[0] as usize]);
            let extent = ids[..k].iter().fold(0.0f64, |m, &i| m.max((v(&self.points[i as usize]) - o).abs().max_element()));
            if extent == 0.0 {
                continue;
            }
            let mut n = glam::DVec3::ZERO;
            for i in 0..k {
                let a = (v(&self.points[ids[i] as usize]) - o) / extent;
                let b = (v(&self.points[ids[(i + 1) % k] as usize]) - o) / extent;
                n += a.cross(b);
            }
            if norm(n) > 1e-12 {
                normals.push(n / norm(n));
            }
        }
        if normals.is_empty() {
            return Err(Error::invalid("cannot find the plane of the mesh: its elements have no area"));
        }
        // Two rounds: align the signs to a guess, take the median, align to that.
        let mut normal = normals[0];
        for _ in 0..2 {
            let aligned = |c: usize| normals.iter().map(move |n| if n.dot(normal) < 0.0 { -n[c] } else { n[c] });
            let m = glam::DVec3::new(median(aligned(0).collect()), median(aligned(1).collect()), median(aligned(2).collect()));
            if norm(m) > 0.0 {
                normal = m / norm(m);
            }
        }
        // The mesh faces +normal where its elements do by area (Newell over all of them),
        // so that elements come out counter-clockwise as they were drawn.
        let mut facing = 0.0;
        for e in 0..self.kinds.len() {
            let ids = elem(e);
            let k = self.kinds[e].corners();
            for i in 0..k {
                facing += v(&self.points[ids[i] as usize]).cross(v(&self.points[ids[(i + 1) % k] as usize])).dot(normal);
            }
        }
        if facing < 0.0 {
            normal = -normal;
        }
        let offset = median(self.points.iter().map(|p| v(p).dot(normal)).collect());
        // In-plane basis (u, w) with u × w = normal.
        let helper = if normal.x.abs() < 0.9 { glam::DVec3::X } else { glam::DVec3::Y };
        let u = (helper - normal * helper.dot(normal)).normalize();
        let w = normal.cross(u);
        let centre = normal * offset;
        let flat: Vec<DVec2> = self.points.iter().map(|p| v(p) - centre).map(|d| DVec2::new(d.dot(u), d.dot(w))).collect();
        // Each node's size: the largest element it belongs to, in the plane (the diagonal
        // of the element's bounding box there). Unused nodes get the largest element's.
        let mut size = vec![0.0f64; self.points.len()];
        let mut largest = 0.0f64;
        for e in 0..self.kinds.len() {
            let ids = elem(e);
            let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
            for &i in ids {
                lo = lo.min(flat[i as usize]);
                hi = hi.max(flat[i as usize]);
            }
            let d = (hi - lo).length();
            largest = largest.max(d);
            for &i in ids {
                size[i as usize] = size[i as usize].max(d);
            }
        }
        let mut worst: Option<(usize, f64, f64)> = None;
        for (i, p) in self.points.iter().enumerate() {
            let distance = (v(p).dot(normal) - offset).abs();
            let own = if size[i] > 0.0 { size[i] } else { largest };
            let allowed = PLANAR_TOLERANCE * own.max(v(p).abs().max_element()).max(centre.abs().max_element());
            if distance > allowed && worst.map_or(true, |(_, d, _)| distance > d) {
                worst = Some((i, distance, own));
            }
        }
        if let Some((node, distance, own)) = worst {
            return Err(Error::NotPlanar {
                node,
                line: self.line_of_node(node),
                max_distance: distance * scale,
                relative: if own > 0.0 { distance / own } else { f64::INFINITY },
                tolerance: PLANAR_TOLERANCE,
            });
        }
        let mut out = Vec::with_capacity(self.points.len());
        for (i, q) in flat.iter().enumerate() {
            let q = *q * scale;
            if !q.is_finite() {
                return Err(Error::node(
                    i,
                    self.line_of_node(i),
                    format!("its coordinates in the plane of the mesh are too large for a 64-bit float: {:?}", self.points[i]),
                ));
            }
            out.push(q);
        }
        Ok((out, Some(Plane { origin: centre * scale, u, w })))
    }
}

/// The median of the values (the upper one of the middle two for an even count); NaN-free
/// input.
fn median(mut values: Vec<f64>) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    let mid = values.len() / 2;
    *values.select_nth_unstable_by(mid, f64::total_cmp).1
}

/// Euclidean length without underflow or overflow of the squares (scaled by the
/// largest component first).
fn norm(v: glam::DVec3) -> f64 {
    let m = v.abs().max_element();
    if m > 0.0 && m.is_finite() {
        m * (v / m).length()
    } else {
        m
    }
}

fn build_topology(mesh: &Mesh, elem_lines: &[u32]) -> Result<Topology> {
    let n = mesh.nodes.len();
    let ne = mesh.conn.kinds.len();
    // node -> elements (counting sort)
    let mut count = vec![0u32; n + 1];
    for e in 0..ne {
        for &i in mesh.element(e) {
            count[i as usize + 1] += 1;
        }
    }
    for i in 0..n {
        count[i + 1] += count[i];
    }
    let node_elem_start = count.clone();
    let mut node_elems = vec![0u32; *count.last().unwrap() as usize];
    let mut fill = count;
    for e in 0..ne {
        for &i in mesh.element(e) {
            node_elems[fill[i as usize] as usize] = e as u32;
            fill[i as usize] += 1;
        }
    }
    // roles
    let mut role = vec![NodeRole::Unused; n];
    for e in 0..ne {
        let k = mesh.conn.kinds[e];
        for (j, &i) in mesh.element(e).iter().enumerate() {
            let r = if j < k.corners() {
                NodeRole::Corner
            } else if j < 2 * k.corners() {
                NodeRole::Mid
            } else {
                NodeRole::Centre
            };
            let slot = &mut role[i as usize];
            *slot = match (*slot, r) {
                (NodeRole::Unused, r) => r,
                (NodeRole::Corner, _) | (_, NodeRole::Corner) => NodeRole::Corner,
                (s, _) => s,
            };
        }
    }
    // edges: every corner edge (a, b), a < b, of every element, as (b, element·4 + local
    // edge) filed under a by a counting sort (8 bytes a use: the largest temporary of
    // the topology, 48 MB for 2M triangles), then each node's short list sorted, so that
    // edges come out ordered by (a, b) with their elements in increasing order; they are
    // counted first so that their array is allocated once, exactly.
    if ne >= 1 << 30 {
        return Err(Error::TooLarge(format!("the mesh has {ne} elements; smoothlab takes at most 2^30 (1073741824)")));
    }
    let corner_edges = |e: usize| {
        let ids = mesh.element(e);
        let c = mesh.conn.kinds[e].corners();
        (0..c).map(move |i| (ids[i].min(ids[(i + 1) % c]), ids[i].max(ids[(i + 1) % c]), i as u32))
    };
    let mut use_start = vec![0u32; n + 1];
    for e in 0..ne {
        for (a, _, _) in corner_edges(e) {
            use_start[a as usize + 1] += 1;
        }
    }
    for i in 0..n {
        use_start[i + 1] += use_start[i];
    }
    let mut uses = vec![(0u32, 0u32); use_start[n] as usize];
    {
        let mut fill = use_start.clone();
        for e in 0..ne {
            for (a, b, i) in corner_edges(e) {
                uses[fill[a as usize] as usize] = (b, (e as u32) << 2 | i);
                fill[a as usize] += 1;
            }
        }
    }
    let mut edge_count = 0usize;
    for a in 0..n {
        let recs = &mut uses[use_start[a] as usize..use_start[a + 1] as usize];
        recs.sort_unstable();
        edge_count += recs.iter().enumerate().filter(|&(k, r)| k == 0 || recs[k - 1].0 != r.0).count();
    }
    let mid_of = |r: u32| {
        let e = (r >> 2) as usize;
        mesh.conn.kinds[e].mid((r & 3) as usize).map(|m| mesh.element(e)[m]).unwrap_or(NONE)
    };
    let line = |e: u32| elem_lines.get(e as usize).copied().filter(|&l| l > 0).map(|l| l as usize);
    let mut edges = Vec::with_capacity(edge_count);
    for a in 0..n {
        let recs = &uses[use_start[a] as usize..use_start[a + 1] as usize];
        let mut i = 0;
        while i < recs.len() {
            let mut j = i + 1;
            while j < recs.len() && recs[j].0 == recs[i].0 {
                j += 1;
            }
            let (a, b, e0, m0) = (a as u32, recs[i].0, recs[i].1 >> 2, mid_of(recs[i].1));
            if j - i > 2 {
                let es: Vec<String> = recs[i..j].iter().map(|r| (r.1 >> 2).to_string()).collect();
                let third = recs[i + 2].1 >> 2;
                return Err(Error::element(
                    third as usize,
                    line(third),
                    format!(
                        "edge between nodes {} and {} is shared by {} elements ({}); a 2D mesh edge belongs to one or two",
                        a + 1,
                        b + 1,
                        j - i,
                        es.join(", ")
                    ),
                ));
            }
            if j - i == 2 && mid_of(recs[i + 1].1) != m0 {
                let (m1, other) = (mid_of(recs[i + 1].1), recs[i + 1].1 >> 2);
                let desc = |m: u32| if m == NONE { "none".to_string() } else { (m + 1).to_string() };
                return Err(Error::element(
                    other as usize,
                    line(other),
                    format!(
                        "shares the edge between nodes {} and {} with element {} but they disagree on its mid-side node ({} vs {})",
                        a + 1,
                        b + 1,
                        e0,
                        desc(m1),
                        desc(m0)
                    ),
                ));
            }
            edges.push(Edge { a, b, mid: m0, boundary: j - i == 1, curved: false });
            i = j;
        }
    }
    debug_assert_eq!(edges.len(), edge_count);
    drop(uses);
    drop(use_start);
    // boundary flags and curved boundary edges
    let mut boundary = vec![false; n];
    let mut on_curved = vec![false; n];
    for e in edges.iter_mut() {
        if e.is_boundary() {
            boundary[e.a as usize] = true;
            boundary[e.b as usize] = true;
            if e.mid != NONE {
                boundary[e.mid as usize] = true;
                let (pa, pb, pm) = (mesh.nodes[e.a as usize], mesh.nodes[e.b as usize], mesh.nodes[e.mid as usize]);
                let chord = pb - pa;
                let off = (pm - pa).perp_dot(chord).abs() / chord.length().max(f64::MIN_POSITIVE);
                if off > 1e-6 * chord.length() {
                    e.curved = true;
                    on_curved[e.a as usize] = true;
                    on_curved[e.b as usize] = true;
                    on_curved[e.mid as usize] = true;
                }
            }
        }
    }
    // node -> neighbour corners via edges (CSR)
    let mut deg = vec![0u32; n + 1];
    for e in &edges {
        deg[e.a as usize + 1] += 1;
        deg[e.b as usize + 1] += 1;
    }
    for i in 0..n {
        deg[i + 1] += deg[i];
    }
    let node_nbr_start = deg.clone();
    let mut node_nbrs = vec![0u32; *deg.last().unwrap() as usize];
    let mut fill = deg;
    for e in &edges {
        node_nbrs[fill[e.a as usize] as usize] = e.b;
        fill[e.a as usize] += 1;
        node_nbrs[fill[e.b as usize] as usize] = e.a;
        fill[e.b as usize] += 1;
    }
    let kinds_present = KindsPresent {
        triangles: mesh.conn.kinds.iter().any(|k| k.is_triangle()),
        quads: mesh.conn.kinds.iter().any(|k| k.is_quad()),
        quadratic: mesh.conn.kinds.iter().any(|k| k.is_quadratic()),
    };
    Ok(Topology { node_elem_start, node_elems, node_nbr_start, node_nbrs, edges, role, boundary, on_curved, kinds_present })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square_two_tris() -> MeshBuilder {
        let mut b = MeshBuilder::new();
        for p in [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]] {
            b.add_node(p, 0);
        }
        b.add_element(ElementKind::Tri3, &[0, 1, 2], 0);
        b.add_element(ElementKind::Tri3, &[0, 2, 3], 0);
        b
    }

    #[test]
    fn topology_of_two_triangles() {
        let m = square_two_tris().build().unwrap();
        m.sanity_check().unwrap();
        assert_eq!(m.edges().len(), 5);
        assert_eq!(m.topology().boundary_edges().count(), 4);
        assert_eq!(m.neighbours(0).len(), 3);
        assert_eq!(m.neighbours(1).len(), 2);
        assert_eq!(m.node_elements(0), &[0, 1]);
        assert!(m.fixed.iter().all(|&f| f));
        assert_eq!(m.free_count(), 0);
    }

    #[test]
    fn clockwise_mesh_is_reversed_as_a_whole() {
        let mut b = MeshBuilder::new();
        for p in [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]] {
            b.add_node(p, 0);
        }
        b.add_element(ElementKind::Tri3, &[0, 2, 1], 0);
        b.add_element(ElementKind::Tri3, &[0, 3, 2], 0);
        let m = b.build().unwrap();
        assert!(m.corner_area(0) > 0.0 && m.corner_area(1) > 0.0);
    }

    #[test]
    fn one_inverted_element_stays_inverted() {
        // three CCW triangles around node 4, one folded over: total area stays positive
        let mut b = MeshBuilder::new();
        for p in [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 2.0, 0.0], [0.0, 2.0, 0.0], [2.5, 1.0, 0.0]] {
            b.add_node(p, 0);
        }
        b.add_element(ElementKind::Tri3, &[0, 1, 4], 0);
        b.add_element(ElementKind::Tri3, &[1, 2, 4], 0);
        b.add_element(ElementKind::Tri3, &[2, 3, 4], 0);
        b.add_element(ElementKind::Tri3, &[3, 0, 4], 0);
        let m = b.build().unwrap();
        assert!(m.corner_area(1) < 0.0, "the folded element must stay folded");
        assert!(m.corner_area(0) > 0.0);
    }

    #[test]
    fn errors_name_the_element_and_line() {
        let mut b = square_two_tris();
        b.add_element(ElementKind::Tri3, &[0, 1, 9], 17);
        let e = b.build().unwrap_err().to_string();
        assert!(e.contains("element 2") && e.contains("line 17") && e.contains("node 10"), "{e}");
        let mut b = square_two_tris();
        b.add_element(ElementKind::Tri3, &[0, 1, 1], 5);
        let e = b.build().unwrap_err().to_string();
        assert!(e.contains("twice") && e.contains("line 5"), "{e}");
        assert!(matches!(MeshBuilder::new().build(), Err(Error::Empty(_))));
        let mut b = square_two_tris();
        b.add_node([f64::NAN, 0.0, 0.0], 9);
        let e = b.build().unwrap_err().to_string();
        assert!(e.contains("node 4") && e.contains("line 9"), "{e}");
    }

    #[test]
    fn planar_3d_is_mapped_and_non_planar_refused() {
        // a unit square tilted about the x axis by 30 degrees, facing down
        let (s, c) = (30f64.to_radians().sin(), 30f64.to_radians().cos());
        let mut b = MeshBuilder::new();
        for (x, y) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
            b.add_node([x, y * c, -y * s + 3.0], 0);
        }
        b.add_element(ElementKind::Quad4, &[0, 3, 2, 1], 0);
        let m = b.build().unwrap();
        assert!((m.corner_area(0) - 1.0).abs() < 1e-12);
        let mut b = MeshBuilder::new();
        for p in [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.3], [0.0, 1.0, 0.0]] {
            b.add_node(p, 0);
        }
        b.add_element(ElementKind::Quad4, &[0, 1, 2, 3], 0);
        let e = b.build().unwrap_err();
        assert!(matches!(e, Error::NotPlanar { .. }));
        assert!(e.to_string().contains("not planar"), "{e}");
    }

    #[test]
    fn hilbert_index_walks_neighbouring_cells() {
        // the curve visits every cell of a small corner block once, each step to a side neighbour
        let side = 1u32 << HILBERT_ORDER;
        let mut cells: Vec<(u64, u32, u32)> =
            (0..16).flat_map(|x| (0..16).map(move |y| (hilbert_index(x, y), x, y))).collect();
        cells.sort_unstable();
        // the first 256 indices fill the 16 × 16 corner block
        assert_eq!(cells.iter().map(|c| c.0).collect::<Vec<_>>(), (0..256).collect::<Vec<u64>>());
        for w in cells.windows(2) {
            let d = w[0].1.abs_diff(w[1].1) + w[0].2.abs_diff(w[1].2);
            assert_eq!(d, 1, "{:?} -> {:?}", w[0], w[1]);
        }
        assert_eq!(hilbert_index(side - 1, 0), u64::from(side) * u64::from(side) - 1);
    }

    #[test]
    fn spatial_renumbering_is_a_relabelling() {
        use crate::generate::{plate, rand2d, PlateKind};
        for m in [rand2d(3000, 15, 2).unwrap(), plate(PlateKind::Mixed, 2, 3).unwrap()] {
            let (r, perm) = m.renumbered_spatially();
            r.sanity_check().unwrap();
            let mut sorted = perm.clone();
            sorted.sort_unstable();
            assert_eq!(sorted, (0..m.node_count() as u32).collect::<Vec<_>>(), "a permutation");
            let mut inv = vec![0u32; perm.len()];
            for (new, &old) in perm.iter().enumerate() {
                inv[old as usize] = new as u32;
                assert_eq!(r.nodes[new], m.nodes[old as usize]);
                assert_eq!(r.fixed[new], m.fixed[old as usize]);
                assert_eq!(r.role(new), m.role(old as usize));
                assert_eq!(r.is_boundary(new), m.is_boundary(old as usize));
                assert_eq!(r.neighbours(new).len(), m.neighbours(old as usize).len());
            }
            // the same elements, node order within each kept
            let key = |mesh: &Mesh, e: usize, map: &dyn Fn(u32) -> u32| {
                (mesh.kind(e) as u8, mesh.element(e).iter().map(|&i| map(i)).collect::<Vec<u32>>())
            };
            let mut a: Vec<_> = (0..m.element_count()).map(|e| key(&m, e, &|i| inv[i as usize])).collect();
            let mut b: Vec<_> = (0..r.element_count()).map(|e| key(&r, e, &|i| i)).collect();
            a.sort();
            b.sort();
            assert_eq!(a, b);
            assert_eq!(r.edges().iter().filter(|e| e.curved).count(), m.edges().iter().filter(|e| e.curved).count());
            // and it is local: consecutive nodes are close (mean step a few spacings)
            let step: f64 = r.nodes.windows(2).map(|w| w[0].distance(w[1])).sum::<f64>() / (r.node_count() - 1) as f64;
            let before: f64 = m.nodes.windows(2).map(|w| w[0].distance(w[1])).sum::<f64>() / (m.node_count() - 1) as f64;
            assert!(step < 0.5 * before || step < 4.0 * m.mean_edge_length(), "{step} vs {before}");
            // positions go back into the original numbering
            let mut moved = r.clone();
            for p in &mut moved.nodes {
                *p += DVec2::new(0.25, -0.5);
            }
            let mut back = m.clone();
            back.restore_positions(&moved, &perm).unwrap();
            for (p, q) in back.nodes.iter().zip(&m.nodes) {
                assert_eq!(*p, *q + DVec2::new(0.25, -0.5));
            }
            assert!(back.restore_positions(&moved, &perm[1..]).is_err());
        }
    }

    #[test]
    fn planar_3d_is_mapped_at_any_scale() {
        // the tilted unit square scaled by s: its edges keep length s, its angles 90°
        // (the plane fit once overflowed near 1e154 and underflowed near 1e-160)
        let (sn, cs) = (30f64.to_radians().sin(), 30f64.to_radians().cos());
        for s in [1e-300, 1e-160, 1e-100, 1.0, 1e100, 1e200, 1e300] {
            let mut b = MeshBuilder::new();
            for (x, y) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
                b.add_node([x * s, y * cs * s, (3.0 - y * sn) * s], 0);
            }
            b.add_element(ElementKind::Quad4, &[0, 1, 2, 3], 0);
            let m = b.build().unwrap_or_else(|e| panic!("scale {s:e}: {e}"));
            m.sanity_check().unwrap();
            for i in 0..4 {
                // in units of s, so that the test's own squares neither overflow nor underflow
                let (p, q, r) = (m.nodes[i] / s, m.nodes[(i + 1) % 4] / s, m.nodes[(i + 2) % 4] / s);
                assert!(((q - p).length() - 1.0).abs() < 1e-12, "scale {s:e}: edge {i}");
                let cos = (p - q).normalize().dot((r - q).normalize());
                assert!(cos.abs() < 1e-12, "scale {s:e}: corner {i}");
            }
        }
    }

    #[test]
    fn heap_bytes_count_every_array() {
        let m = square_two_tris().build().unwrap();
        let b = m.heap_bytes();
        // 4 positions (64 bytes) and 6 element node ids (24) at the least
        assert!(b >= 4 * 16 + 6 * 4, "{b}");
        assert!(b < 4096, "{b}");
        // 5 edges of 16 bytes, exactly as many as there are
        let edges = m.memory_parts().into_iter().find(|p| p.name.starts_with("edges")).unwrap();
        assert_eq!(edges.bytes, 5 * 16);
        assert_eq!(std::mem::size_of::<Edge>(), 16);
    }

    #[test]
    fn clones_share_the_connectivity() {
        let m = square_two_tris().build().unwrap();
        let mut c = m.clone();
        assert!(Arc::ptr_eq(&m.conn, &c.conn));
        c.nodes[0].x += 0.5;
        assert_eq!(m.nodes[0].x, 0.0, "positions are each clone's own");
        let own: usize = m.memory_parts().iter().filter(|p| !p.shared).map(|p| p.bytes).sum();
        assert_eq!(own, m.nodes.capacity() * 16 + m.fixed.capacity());
    }

    #[test]
    fn orientation_is_stable_under_reversal() {
        // zero-width triangles far from the origin: the total area is rounding noise, and
        // whatever build decides, building the result again must not reverse it back
        let x = -2.777777777777778e88;
        for ys in [[0.15825648112409307, -0.4235812421140439, -0.05955188067518902, 0.136728447068453], [0.1, -0.7, 0.45, 0.5]] {
            let mut b = MeshBuilder::new();
            for y in ys {
                b.add_node([x, y, 0.0], 0);
            }
            b.add_element(ElementKind::Tri3, &[0, 1, 2], 0);
            b.add_element(ElementKind::Tri3, &[1, 3, 2], 0);
            let once = b.build().unwrap();
            let mut again = MeshBuilder::new();
            for p in &once.nodes {
                again.add_node([p.x, p.y, 0.0], 0);
            }
            for e in 0..once.element_count() {
                again.add_element(once.kind(e), once.element(e), 0);
            }
            let twice = again.build().unwrap();
            for e in 0..once.element_count() {
                assert_eq!(once.element(e), twice.element(e), "{ys:?}: element {e}");
            }
        }
    }

    #[test]
    fn quadratic_edges_know_mid_nodes_and_curvature() {
        // one 6-node triangle with its 0-1 edge bowed out
        let mut b = MeshBuilder::new();
        for p in [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0], [1.0, -0.3, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]] {
            b.add_node(p, 0);
        }
        b.add_element(ElementKind::Tri6, &[0, 1, 2, 3, 4, 5], 0);
        let m = b.build().unwrap();
        m.sanity_check().unwrap();
        let curved: Vec<_> = m.edges().iter().filter(|e| e.curved).collect();
        assert_eq!(curved.len(), 1);
        assert_eq!(curved[0].mid, 3);
        assert!(m.is_on_curved_boundary(0) && !m.is_on_curved_boundary(2));
        assert_eq!(m.role(3), NodeRole::Mid);
        assert_eq!(m.neighbours(0).len(), 2, "mid nodes are not neighbours");
    }
}
