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

mod builder;
mod chain;
mod kind;
mod piece;
mod renumber;
mod slide;
pub(crate) use renumber::HilbertGrid;
#[cfg(test)]
mod tests;
mod topology;
mod volume_kind;

pub(crate) use builder::{Flat, SurfaceParts};
pub use builder::{polygon_area, FixedSpec, MeshBuilder, MAX_COORDINATE, PLANAR_TOLERANCE};
pub use kind::{ElementKind, NodeRole};
pub use slide::{BoundaryNode, BoundaryRule, FEATURE_ANGLE_DEG, MIN_CURVE_SEGMENTS};
pub(crate) use slide::{csr, held_nodes, Curves, GivenFlags};
pub use volume_kind::{
    CornerReference, VolumeKind, VolumeKindCounts, VolumeKindRow, CUBE_CORNER, EQUILATERAL_TET, EQUILATERAL_W, EQUILATERAL_W_INVERSE,
    PYRAMID_CORNER, StretchAxes, TET10_EDGES, WEDGE_CORNER, WITH_FIRST,
};
use topology::build_topology;

/// A node that follows a moved corner ([`Mesh::for_each_follower`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Follower {
    /// A mid-side node, placed at the middle of its edge's corners `a` and `b`.
    Mid { mid: usize, a: usize, b: usize },
    /// A 9-node quad's centre, placed at the mean of the element's other eight nodes.
    Centre { centre: usize, element: usize },
}

/// Marker for "no such index" in the flat arrays.
pub const NONE: u32 = u32::MAX;

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
    /// Per element, whether it was reversed when read (a clockwise planar mesh, a surface
    /// element against its neighbours); empty when none was. The writers give the nodes
    /// back in the file's order ([`Mesh::element_as_given`]).
    reversed: Vec<bool>,
}

/// An element's nodes in the order its file gave them ([`Mesh::element_as_given`]).
#[derive(Clone, Copy, Debug)]
pub struct GivenNodes {
    ids: [u32; 9],
    len: usize,
}

impl std::ops::Deref for GivenNodes {
    type Target = [u32];
    fn deref(&self) -> &[u32] {
        &self.ids[..self.len]
    }
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
    /// Node positions, one per node of the topology (see [`Mesh::nodes_mut`]).
    nodes: Vec<DVec2>,
    /// Nodes that never move, one flag per node; set when the mesh is built.
    fixed: Vec<bool>,
    conn: Arc<Connectivity>,
    /// The 3D plane the file's points lay in, when they were not in the xy plane at z = 0
    /// (see [`Mesh::to_3d`]); `None` for a 2D mesh.
    pub plane: Option<Plane>,
    /// The file's 3D points and their 2D coordinates in [`plane`](Self::plane), where
    /// the plane is not the xy plane shifted (whose coordinates come back exactly): a node
    /// still at its 2D coordinates is written back as the file gave it, to the bit
    /// ([`node_3d`](Self::node_3d)), which the plane's rotation cannot promise.
    loaded_3d: Option<Arc<Loaded3d>>,
    /// The corners' targets where they are not the ideal ([`crate::target::Target::Input`]):
    /// every node's position in the mesh the targets were taken from, in the frame of
    /// [`nodes`](Self::nodes) (a surface's star moves them into its tangent plane with the
    /// nodes), and each element's corner frames from them ([`crate::target::element_frames`]).
    target: Option<Box<Targets>>,
    /// The nodes the file itself fixed (its flags), whatever the boundary rule.
    given_fixed: Option<Arc<slide::GivenFlags>>,
    /// The sliding rule, when boundary nodes slide ([`BoundaryRule::Slide`]).
    sliding: Option<Box<slide::PlanarSliding>>,
}

/// Each element's own target positions, node by node ([`crate::target::Target::Stretch`]).
type ElementTargets = Vec<[DVec2; 9]>;

/// The target positions of a mesh's nodes and each element's corner frames from them,
/// node by node in the order of [`Mesh::node_elements`] (a star reads its frames in one
/// run of memory).
#[derive(Clone, Debug)]
struct Targets {
    nodes: Vec<DVec2>,
    /// Each element's own target positions, where they are not its nodes' in
    /// [`nodes`](Self::nodes) ([`crate::target::Target::Stretch`]).
    shapes: Option<Vec<[DVec2; 9]>>,
    frames: Vec<[glam::DMat2; 4]>,
}

/// What [`Mesh::node_3d`] writes back unchanged: the file's points and their images.
#[derive(Debug)]
struct Loaded3d {
    points: Vec<glam::DVec3>,
    flat: Vec<DVec2>,
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
    /// The 2D coordinates of the orthogonal projection of `q` onto the plane.
    pub fn to_2d(&self, q: glam::DVec3) -> DVec2 {
        let d = q - self.origin;
        DVec2::new(d.dot(self.u), d.dot(self.w))
    }
    /// The plane through `origin` with the unit normal `normal`, its axes `u × w = normal`
    /// (`u` in the xy plane's direction nearest to x where it can be).
    pub fn with_normal(origin: glam::DVec3, normal: glam::DVec3) -> Plane {
        let helper = if normal.x.abs() < 0.9 { glam::DVec3::X } else { glam::DVec3::Y };
        let u = (helper - normal * helper.dot(normal)).normalize();
        Plane { origin, u, w: normal.cross(u) }
    }
    /// The plane's unit normal, `u × w`.
    pub fn normal(&self) -> glam::DVec3 {
        self.u.cross(self.w)
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

    /// Node `i` in 3D: as the file gave it while the node is where it was read (a fixed
    /// node, or a mesh converted without smoothing: bit for bit), else its position in
    /// the plane ([`to_3d`](Self::to_3d)).
    pub fn node_3d(&self, i: usize) -> glam::DVec3 {
        let p = self.nodes[i];
        if let Some(l) = &self.loaded_3d {
            if l.flat.get(i) == Some(&p) {
                return l.points[i];
            }
        }
        self.to_3d(p)
    }

    /// Remembers the file's 3D points `points` of the nodes as they are now (see
    /// [`node_3d`](Self::node_3d)).
    pub(crate) fn keep_loaded_3d(&mut self, points: Vec<glam::DVec3>) {
        debug_assert_eq!(points.len(), self.nodes.len());
        self.loaded_3d = Some(Arc::new(Loaded3d { points, flat: self.nodes.clone() }));
    }

    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }
    /// Node positions. The smoothers move corner nodes; mid-side nodes follow.
    pub fn nodes(&self) -> &[DVec2] {
        &self.nodes
    }
    /// Node positions to move. A slice, so the count always matches the topology's.
    pub fn nodes_mut(&mut self) -> &mut [DVec2] {
        &mut self.nodes
    }
    /// Per node, whether it never moves. Fixed when the mesh is built ([`MeshBuilder`]'s
    /// `fixed`) and never changed after, so the free nodes are a property of the mesh.
    pub fn fixed(&self) -> &[bool] {
        &self.fixed
    }
    pub fn is_fixed(&self, n: usize) -> bool {
        self.fixed[n]
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
        let unfixed = match self.boundary_node(n) {
            None | Some(BoundaryNode::Interior) => !self.fixed[n],
            Some(c) => c.slides(),
        };
        unfixed && self.conn.topo.role[n] == NodeRole::Corner
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
        let mut nodes = std::mem::take(&mut self.nodes);
        self.for_each_follower(n, |f| match f {
            Follower::Mid { mid, a, b } => nodes[mid] = 0.5 * (nodes[a] + nodes[b]),
            Follower::Centre { centre, element } => {
                let s: DVec2 = self.element(element)[..8].iter().map(|&i| nodes[i as usize]).sum();
                nodes[centre] = s / 8.0;
            }
        });
        self.nodes = nodes;
    }

    /// Puts every node of corner node `n`'s elements at `at(node)`, then the nodes that
    /// follow `n` where they follow ([`follow_mid_nodes`](Self::follow_mid_nodes)): a
    /// surface's star flattened into this mesh's scratch positions.
    /// Takes every corner's target from the nodes' positions `at` ([`crate::target::Target::Input`];
    /// `None`: the ideal of each kind).
    pub fn set_target_nodes(&mut self, at: Option<Vec<DVec2>>) {
        debug_assert!(at.as_ref().map_or(true, |a| a.len() == self.nodes.len()));
        self.set_targets(at.map(|nodes| (nodes, None)));
    }

    /// Gives every element a target shape of its own, each at the origin until a star
    /// sets it ([`set_target_star_shapes`](Self::set_target_star_shapes)): a surface's
    /// stretch, read in each star's tangent plane.
    pub(crate) fn set_target_shapes(&mut self) {
        let (nodes, shapes) = (vec![DVec2::ZERO; self.nodes.len()], vec![[DVec2::ZERO; 9]; self.element_count()]);
        self.set_targets(Some((nodes, Some(shapes))));
    }

    /// Node `n`'s star's element shapes set by `at(e, i)` (element `e`'s node `i`), and
    /// their frames worked out again, where the elements have shapes of their own
    /// ([`set_target_shapes`](Self::set_target_shapes)).
    pub(crate) fn set_target_star_shapes(&mut self, n: usize, at: impl Fn(usize, usize) -> DVec2) {
        let Some(mut target) = self.target.take() else {
            return;
        };
        let start = self.conn.topo.node_elem_start[n] as usize;
        for (j, &e) in self.conn.topo.node_elements(n).iter().enumerate() {
            let e = e as usize;
            if let Some(shapes) = &mut target.shapes {
                for (i, q) in shapes[e].iter_mut().enumerate().take(self.kind(e).node_count()) {
                    *q = at(e, i);
                }
            }
            let p = Self::element_target_in(&target, e, self.element(e));
            target.frames[start + j] = crate::target::element_frames(self.kind(e), &p);
        }
        self.target = Some(target);
    }

    /// Measures every corner against `target` taken from the nodes' positions `at`
    /// ([`crate::target::Target`]); the ideal where `target` leaves every corner at it.
    pub fn set_target_from(&mut self, target: crate::target::Target, at: Vec<DVec2>) {
        use crate::target::Target;
        match target {
            Target::Ideal => self.set_targets(None),
            Target::Input => self.set_targets(Some((at, None))),
            Target::Stretch => {
                let shapes = crate::target::planar_stretch_points(self, &at);
                self.set_targets(shapes.map(|s| (at, Some(s))));
            }
        }
    }

    /// Sets the targets: the positions they are taken from and each element's own, where
    /// they are not its nodes'.
    fn set_targets(&mut self, at: Option<(Vec<DVec2>, Option<ElementTargets>)>) {
        self.target = at.map(|(nodes, shapes)| {
            let topo = &self.conn.topo;
            let mut t = Box::new(Targets {
                nodes,
                shapes,
                frames: Vec::with_capacity(topo.node_elems.len()),
            });
            for &e in &topo.node_elems {
                let p = Self::element_target_in(&t, e as usize, self.element(e as usize));
                t.frames.push(crate::target::element_frames(self.kind(e as usize), &p));
            }
            t
        });
    }

    /// The nodes of `ids` at the target positions.
    fn target_points_in(t: &Targets, ids: &[u32]) -> [DVec2; 9] {
        let mut p = [DVec2::ZERO; 9];
        for (q, &n) in p.iter_mut().zip(ids) {
            *q = t.nodes[n as usize];
        }
        p
    }

    /// Element `e` (nodes `ids`) at its targets: its own shape where it has one, else its
    /// nodes at the target positions.
    fn element_target_in(t: &Targets, e: usize, ids: &[u32]) -> [DVec2; 9] {
        match &t.shapes {
            Some(s) => s[e],
            None => Self::target_points_in(t, ids),
        }
    }

    /// Element `e`'s target positions, node by node, where the mesh has targets other
    /// than the ideal.
    pub fn element_target_points(&self, e: usize) -> Option<[DVec2; 9]> {
        self.target.as_deref().map(|t| Self::element_target_in(t, e, self.element(e)))
    }

    /// The positions the corners' targets are taken from, where they are not the ideal.
    pub fn target_nodes(&self) -> Option<&[DVec2]> {
        self.target.as_deref().map(|t| t.nodes.as_slice())
    }

    /// The corner frames of the elements of node `n`'s star, in the order of
    /// [`node_elements`](Self::node_elements) ([`crate::target::element_frames`]), where the
    /// mesh has targets other than the ideal.
    #[inline]
    pub fn star_target_frames(&self, n: usize) -> Option<&[[glam::DMat2; 4]]> {
        let topo = &self.conn.topo;
        self.target.as_deref().map(|t| {
            &t.frames[topo.node_elem_start[n] as usize..topo.node_elem_start[n + 1] as usize]
        })
    }

    /// [`set_star`](Self::set_star) of the target's positions, where there is a target:
    /// node `n`'s star's frames worked out again from them (what its star reads).
    pub(crate) fn set_target_star(&mut self, n: usize, at: impl Fn(usize) -> DVec2) {
        let Some(mut target) = self.target.take() else {
            return;
        };
        for &e in self.conn.topo.node_elements(n) {
            let e = e as usize;
            for &m in &self.conn.elem_nodes
                [self.conn.elem_start[e] as usize..self.conn.elem_start[e + 1] as usize]
            {
                target.nodes[m as usize] = at(m as usize);
            }
        }
        let start = self.conn.topo.node_elem_start[n] as usize;
        for (j, &e) in self.conn.topo.node_elements(n).iter().enumerate() {
            let p = Self::target_points_in(&target, self.element(e as usize));
            target.frames[start + j] = crate::target::element_frames(self.kind(e as usize), &p);
        }
        self.target = Some(target);
    }

    pub(crate) fn set_star(&mut self, n: usize, at: impl Fn(usize) -> DVec2) {
        for &e in self.conn.topo.node_elements(n) {
            let e = e as usize;
            for &m in &self.conn.elem_nodes[self.conn.elem_start[e] as usize..self.conn.elem_start[e + 1] as usize] {
                self.nodes[m as usize] = at(m as usize);
            }
        }
        self.follow_mid_nodes(n);
    }

    /// The nodes that follow corner node `n` when it moves, in the order they are to be
    /// placed: per element of its star, the mid-side node of each of its edges at `n`
    /// (unless fixed or on a curved boundary edge), then a 9-node quad's centre (unless
    /// fixed). The one rule for planar meshes ([`follow_mid_nodes`](Self::follow_mid_nodes))
    /// and surfaces.
    pub(crate) fn for_each_follower(&self, n: usize, mut f: impl FnMut(Follower)) {
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
                f(Follower::Mid { mid: m, a, b });
            }
            if kind == ElementKind::Quad9 {
                let c = self.conn.elem_nodes[start + 8] as usize;
                if !self.fixed[c] {
                    f(Follower::Centre { centre: c, element: el });
                }
            }
        }
    }

    /// Marks the boundary edges `curved` says are curved, with their nodes (a surface
    /// decides in 3D, where the planar test of the builder cannot). Only while the mesh
    /// is being built: its topology is not shared yet.
    pub(crate) fn mark_curved_boundary(&mut self, curved: impl Fn(&Edge) -> bool) {
        let topo = &mut self.connectivity_mut().topo;
        for e in topo.edges.iter_mut().filter(|e| e.boundary && e.mid != NONE) {
            if curved(e) {
                e.curved = true;
                for n in [e.a, e.b, e.mid] {
                    topo.on_curved[n as usize] = true;
                }
            }
        }
    }
    /// Fixes the nodes `also` says, besides those fixed already (a surface's feature
    /// curves). Only while the mesh is being built.
    pub(crate) fn fix_also(&mut self, also: impl Fn(usize) -> bool) {
        for (n, f) in self.fixed.iter_mut().enumerate() {
            *f |= also(n);
        }
    }
    /// Frees the nodes `free` says (a surface's nodes sliding along its curves). Only
    /// while a surface is being made.
    pub(crate) fn release(&mut self, free: impl Fn(usize) -> bool) {
        for (n, f) in self.fixed.iter_mut().enumerate() {
            if free(n) {
                *f = false;
            }
        }
    }
    /// Fixes the nodes for which `hold` is true: the inverse of [`release`](Self::release).
    pub(crate) fn hold(&mut self, hold: impl Fn(usize) -> bool) {
        for (n, f) in self.fixed.iter_mut().enumerate() {
            if hold(n) {
                *f = true;
            }
        }
    }
    /// Reverses the order of the nodes of element `e` (its orientation). Only while the
    /// mesh is being built.
    pub(crate) fn reverse_element(&mut self, e: usize) {
        let c = self.connectivity_mut();
        let s = c.elem_start[e] as usize;
        let k = c.kinds[e];
        let mut old = [0u32; 9];
        old[..k.node_count()].copy_from_slice(&c.elem_nodes[s..s + k.node_count()]);
        for (i, &j) in k.reversed_order().iter().enumerate() {
            c.elem_nodes[s + i] = old[j];
        }
        if c.reversed.is_empty() {
            c.reversed = vec![false; c.kinds.len()];
        }
        c.reversed[e] = !c.reversed[e];
    }

    /// Element `e`'s nodes in the order its file gave them: [`element`](Self::element),
    /// put back where the element was reversed when read (each kind's reversal is its own
    /// inverse), so that what smoothlab writes keeps its input's orientation.
    pub fn element_as_given(&self, e: usize) -> GivenNodes {
        let ids = self.element(e);
        let mut given = GivenNodes { ids: [0; 9], len: ids.len() };
        if self.conn.reversed.get(e).copied().unwrap_or(false) {
            for (i, &j) in self.kind(e).reversed_order().iter().enumerate() {
                given.ids[i] = ids[j];
            }
        } else {
            given.ids[..ids.len()].copy_from_slice(ids);
        }
        given
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
