//! Tetrahedral meshes: the model, its statistics, and smoothing by the planar drivers
//! (Freitag 1997's rand3D experiments, Knupp 1999's condition number in 3D).
//!
//! A [`VolumeMesh`] holds elements of one [`VolumeKind`] — linear (4-node) or quadratic
//! (10-node) tetrahedra, each kind a row of data (node and corner counts, each corner's
//! edge neighbours and reference W, edges, faces, file type codes) — with the
//! adjacency the drivers read built once, flat (CSR): the tetrahedra at each corner node,
//! each corner node's edge neighbours and, for quadratic meshes, the mid-edge nodes that
//! follow each corner. Fixed nodes are those of the boundary faces (faces of one
//! tetrahedron), or as the file says.
//!
//! The smoothers are the planar ones: `smooth.rs` implements their two traits for a
//! tetrahedral mesh and its star, so every strategy, order and objective runs unchanged.

use glam::DVec3;

use crate::error::{Error, Result};
pub use crate::mesh::{VolumeKind, TET10_EDGES};
use crate::mesh::{FixedSpec, MeshBuilder, NodeRole};
use crate::quality::tet as q3;

mod picture;
mod smooth;
mod stats;
mod swap;
#[cfg(test)]
mod tests;

pub use picture::{Cut, CutFaces};
pub use smooth::{smooth_volume, VolumeSmoother};
pub use stats::volume_stats;
pub use swap::swap_max_min_dihedral;

/// What a reader found, before it is checked: nodes and tetrahedra with their file lines
/// (0 where none), and how the fixed flags are decided.
#[derive(Clone, Debug)]
pub struct TetParts {
    pub nodes: Vec<DVec3>,
    pub node_lines: Vec<u32>,
    pub kind: VolumeKind,
    /// Node ids, [`VolumeKind::nodes`] per element.
    pub elements: Vec<u32>,
    pub element_lines: Vec<u32>,
    pub fixed: FixedSpec,
    /// The file's triangles and quads (the boundary faces Gmsh writes), kept to be
    /// written back.
    pub faces: Vec<GivenFace>,
}

/// A triangle or quad a tetrahedral mesh's file gave beside its tetrahedra (Gmsh writes
/// the boundary faces, often with their physical groups): its nodes fix those nodes, and
/// the writers write it back after the tetrahedra.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GivenFace {
    pub kind: crate::mesh::ElementKind,
    nodes: [u32; 9],
    /// Its line in the file (0: not from a file).
    pub line: u32,
}

impl GivenFace {
    pub fn new(kind: crate::mesh::ElementKind, nodes: &[u32], line: u32) -> Self {
        let mut f = GivenFace { kind, nodes: [0; 9], line };
        f.nodes[..nodes.len()].copy_from_slice(nodes);
        f
    }
    /// Its nodes, in the file's order.
    pub fn nodes(&self) -> &[u32] {
        &self.nodes[..self.kind.node_count()]
    }
}

/// A mesh of tetrahedra (see the module docs).
#[derive(Clone, Debug)]
pub struct VolumeMesh {
    nodes: Vec<DVec3>,
    kind: VolumeKind,
    elements: Vec<u32>,
    fixed: Vec<bool>,
    role: Vec<NodeRole>,
    /// CSR: the tetrahedra with node n as a corner.
    tet_start: Vec<u32>,
    tets: Vec<u32>,
    /// CSR: the corner nodes sharing an edge with corner n.
    nb_start: Vec<u32>,
    nb: Vec<u32>,
    /// CSR (quadratic meshes): the (mid node, other end) of every edge at corner n.
    follow_start: Vec<u32>,
    follow: Vec<[u32; 2]>,
    /// Faces of one tetrahedron, outward (right-handed seen from outside).
    boundary: Vec<[u32; 3]>,
    /// The file's triangles and quads ([`GivenFace`]).
    faces: Vec<GivenFace>,
}

/// Builds CSR arrays from (key, value) pairs over `n` keys.
fn csr(n: usize, pairs: &mut [(u32, u32)]) -> (Vec<u32>, Vec<u32>) {
    pairs.sort_unstable();
    let mut start = vec![0u32; n + 1];
    for &(k, _) in pairs.iter() {
        start[k as usize + 1] += 1;
    }
    for i in 0..n {
        start[i + 1] += start[i];
    }
    (start, pairs.iter().map(|&(_, v)| v).collect())
}

impl VolumeMesh {
    /// The tetrahedral mesh of a builder's tetrahedra (a file's: see
    /// [`MeshBuilder::has_tets`]), its triangles and quads kept as the given faces whose
    /// nodes are fixed; checked as [`build`](Self::build) checks.
    pub fn from_builder(builder: MeshBuilder) -> Result<VolumeMesh> {
        let p = builder.build_volume_parts()?;
        let faces = (0..p.face_kinds.len())
            .map(|e| {
                let ids = &p.face_nodes[p.face_start[e] as usize..p.face_start[e + 1] as usize];
                GivenFace::new(p.face_kinds[e], ids, p.face_lines.get(e).copied().unwrap_or(0))
            })
            .collect();
        VolumeMesh::build(TetParts {
            faces,
            nodes: p.points.iter().map(|&x| DVec3::from(x)).collect(),
            node_lines: p.point_lines,
            kind: p.kind,
            elements: p.tets,
            element_lines: p.tet_lines,
            fixed: p.fixed,
        })
    }

    /// Checks what a reader found and builds the mesh. Errors name the node or element
    /// and its file line: no tetrahedra, a coordinate that is not a finite number (or too
    /// large to compute with), a node id out of range, a node repeated in a tetrahedron,
    /// a node that is a corner of one tetrahedron and a mid-edge node of another, a
    /// tetrahedron without volume, a face of more than two tetrahedra. A mesh given
    /// left-handed (negative total volume) is turned over, every tetrahedron with it;
    /// single inverted tetrahedra stay (a tangled mesh is the smoothers' input).
    pub fn build(parts: TetParts) -> Result<VolumeMesh> {
        let TetParts { nodes, node_lines, kind, mut elements, element_lines, fixed, faces: given_faces } = parts;
        let row = kind.row();
        let (k, corners) = (row.nodes, row.corners);
        let line = |lines: &[u32], i: usize| lines.get(i).copied().filter(|&l| l > 0).map(|l| l as usize);
        if elements.is_empty() {
            return Err(Error::Empty("the mesh has no tetrahedra".into()));
        }
        debug_assert_eq!(elements.len() % k, 0);
        for (i, p) in nodes.iter().enumerate() {
            if !p.is_finite() {
                return Err(Error::node(i, line(&node_lines, i), format!("coordinate {p} is not a finite number")));
            }
            if p.abs().max_element() > crate::mesh::MAX_COORDINATE {
                return Err(Error::node(
                    i,
                    line(&node_lines, i),
                    format!("coordinate {p} is too large to compute with"),
                ));
            }
        }
        let n = nodes.len();
        let count = elements.len() / k;
        let mut role = vec![NodeRole::Unused; n];
        for e in 0..count {
            let ids = &elements[e * k..(e + 1) * k];
            for (j, &id) in ids.iter().enumerate() {
                if id as usize >= n {
                    return Err(Error::element(
                        e,
                        line(&element_lines, e),
                        format!("node {id} does not exist: the mesh has {n} nodes (0 to {})", n.saturating_sub(1)),
                    ));
                }
                if ids[..j].contains(&id) {
                    return Err(Error::element(
                        e,
                        line(&element_lines, e),
                        format!("node {id} appears twice in the tetrahedron"),
                    ));
                }
            }
        }
        for e in 0..count {
            for (j, &id) in elements[e * k..(e + 1) * k].iter().enumerate() {
                let r = if j < corners { NodeRole::Corner } else { NodeRole::Mid };
                match (role[id as usize], r) {
                    (NodeRole::Unused, r) => role[id as usize] = r,
                    (a, b) if a != b => {
                        return Err(Error::element(
                            e,
                            line(&element_lines, e),
                            format!("node {id} is a corner of one tetrahedron and a mid-edge node of another"),
                        ))
                    }
                    _ => {}
                }
            }
        }
        // volume, in units of each tetrahedron's own size, and the whole mesh's handedness
        // (a kind that is not a tetrahedron needs its own measure of validity here)
        let corner_points = |els: &[u32], e: usize| match kind {
            VolumeKind::Tet4 | VolumeKind::Tet10 => [0, 1, 2, 3].map(|j| nodes[els[e * k + j] as usize]),
        };
        let mut total = 0.0;
        for e in 0..count {
            // in the tetrahedron's own scale: a cube of 1e150 has volumes beyond the doubles
            let p = q3::in_unit_scale(&corner_points(&elements, e));
            let v = q3::signed_volume(&p);
            let size = q3::TET_EDGES.iter().map(|&[a, b]| p[a].distance(p[b])).sum::<f64>() / 6.0;
            if v.abs() <= 1e-12 * size * size * size || v.is_nan() {
                return Err(Error::element(
                    e,
                    line(&element_lines, e),
                    "the tetrahedron has no volume: its four corners lie in a plane",
                ));
            }
            total += v / (size * size * size);
        }
        if total < 0.0 {
            let mut old = [0u32; 32];
            for e in 0..count {
                let t = &mut elements[e * k..(e + 1) * k];
                old[..k].copy_from_slice(t);
                for (to, &from) in t.iter_mut().zip(row.mirror) {
                    *to = old[from];
                }
            }
        }
        // faces: boundary (one tetrahedron) or shared (two); more is not a manifold
        let mut faces: Vec<([u32; 3], u32, u8)> = Vec::with_capacity(row.faces.len() * count);
        for e in 0..count {
            for (f, loc) in row.faces.iter().enumerate() {
                let mut key = loc.map(|j| elements[e * k + j]);
                key.sort_unstable();
                faces.push((key, e as u32, f as u8));
            }
        }
        faces.sort_unstable();
        let mut boundary = Vec::new();
        let mut i = 0;
        while i < faces.len() {
            let mut j = i + 1;
            while j < faces.len() && faces[j].0 == faces[i].0 {
                j += 1;
            }
            if j - i > 2 {
                let e = faces[i + 2].1 as usize;
                return Err(Error::element(
                    e,
                    line(&element_lines, e),
                    format!("its face {:?} is a face of {} tetrahedra (at most two share a face)", faces[i].0, j - i),
                ));
            }
            if j - i == 1 {
                let (_, e, f) = faces[i];
                boundary.push(row.faces[f as usize].map(|c| elements[e as usize * k + c]));
            }
            i = j;
        }
        // fixed flags
        let mut on_boundary = vec![false; n];
        for f in &boundary {
            for &c in f {
                on_boundary[c as usize] = true;
            }
        }
        if row.mid_edge_nodes {
            // a mid-edge node is on the boundary when both ends of its edge are on a
            // boundary face together
            let mut edge_on_boundary = std::collections::HashSet::new();
            for f in &boundary {
                for (a, b) in [(f[0], f[1]), (f[1], f[2]), (f[2], f[0])] {
                    edge_on_boundary.insert((a.min(b), a.max(b)));
                }
            }
            for e in 0..count {
                let t = &elements[e * k..(e + 1) * k];
                for (m, &[a, b]) in row.edges.iter().enumerate() {
                    let (a, b) = (t[a], t[b]);
                    if edge_on_boundary.contains(&(a.min(b), a.max(b))) {
                        on_boundary[t[corners + m] as usize] = true;
                    }
                }
            }
        }
        let mut fixed = match fixed {
            FixedSpec::Boundary => on_boundary,
            FixedSpec::Exact(f) => f,
            FixedSpec::BoundaryAnd(f) => on_boundary.iter().zip(&f).map(|(a, b)| *a || *b).collect(),
        };
        fixed.resize(n, false);
        for (f, r) in fixed.iter_mut().zip(&role) {
            *f |= *r == NodeRole::Unused;
        }
        // adjacency, flat
        let mut pairs: Vec<(u32, u32)> = Vec::with_capacity(corners * count);
        for e in 0..count {
            for j in 0..corners {
                pairs.push((elements[e * k + j], e as u32));
            }
        }
        let (tet_start, tets) = csr(n, &mut pairs);
        pairs.clear();
        for e in 0..count {
            for &[a, b] in row.edges {
                let (a, b) = (elements[e * k + a], elements[e * k + b]);
                pairs.push((a, b));
                pairs.push((b, a));
            }
        }
        pairs.sort_unstable();
        pairs.dedup();
        let (nb_start, nb) = csr(n, &mut pairs);
        let (mut follow_start, mut follow) = (vec![0u32; n + 1], Vec::new());
        if row.mid_edge_nodes {
            let mut triples: Vec<(u32, u32, u32)> = Vec::with_capacity(2 * row.edges.len() * count);
            for e in 0..count {
                let t = &elements[e * k..(e + 1) * k];
                for (m, &[a, b]) in row.edges.iter().enumerate() {
                    triples.push((t[a], t[corners + m], t[b]));
                    triples.push((t[b], t[corners + m], t[a]));
                }
            }
            triples.sort_unstable();
            triples.dedup();
            for &(c, _, _) in &triples {
                follow_start[c as usize + 1] += 1;
            }
            for i in 0..n {
                follow_start[i + 1] += follow_start[i];
            }
            follow = triples.iter().map(|&(_, m, o)| [m, o]).collect();
        }
        Ok(VolumeMesh {
            nodes,
            kind,
            elements,
            fixed,
            role,
            tet_start,
            tets,
            nb_start,
            nb,
            follow_start,
            follow,
            boundary,
            faces: given_faces,
        })
    }

    /// The file's triangles and quads, written back after the tetrahedra.
    pub fn faces(&self) -> &[GivenFace] {
        &self.faces
    }

    /// What the file's triangles and quads fixed inside the volume: those that are not a
    /// boundary face of the tetrahedra fix their nodes as the file asks (where the file
    /// gave no fixed flags of its own), and this says which nodes off the boundary that
    /// fixed (`None` when none).
    pub fn stray_faces_note(&self) -> Option<String> {
        let mut on_boundary: Vec<[u32; 3]> = self.boundary.iter().map(|f| sorted3(*f)).collect();
        on_boundary.sort_unstable();
        let mut boundary_node = vec![false; self.nodes.len()];
        for f in &self.boundary {
            for &i in f {
                boundary_node[i as usize] = true;
            }
        }
        let inner_fixed = |f: &GivenFace| -> Vec<u32> {
            f.nodes().iter().copied().filter(|&i| self.fixed[i as usize] && !boundary_node[i as usize]).collect()
        };
        let stray: Vec<(&GivenFace, Vec<u32>)> = self
            .faces
            .iter()
            .filter(|f| {
                let c = &f.nodes[..f.kind.corners()];
                c.len() != 3 || on_boundary.binary_search(&sorted3([c[0], c[1], c[2]])).is_err()
            })
            .map(|f| (f, inner_fixed(f)))
            .filter(|(_, inner)| !inner.is_empty())
            .collect();
        let (first, inner) = stray.first()?;
        let at = if first.line > 0 { format!(" (line {})", first.line) } else { String::new() };
        let nodes: Vec<String> = inner.iter().map(|i| (i + 1).to_string()).collect();
        Some(format!(
            "{} of the file's triangles and quads {} not on the boundary of the tetrahedra and {} nodes inside the volume, as the file asks: the first{at} fixes node {}",
            stray.len(),
            if stray.len() == 1 { "is" } else { "are" },
            if stray.len() == 1 { "fixes" } else { "fix" },
            nodes.join(", "),
        ))
    }

    /// A linear mesh from points and tetrahedra (generators), boundary nodes fixed.
    pub fn from_tets(nodes: Vec<DVec3>, tets: &[[u32; 4]]) -> Result<VolumeMesh> {
        VolumeMesh::build(TetParts {
            node_lines: Vec::new(),
            nodes,
            kind: VolumeKind::Tet4,
            elements: tets.iter().flatten().copied().collect(),
            element_lines: Vec::new(),
            fixed: FixedSpec::Boundary,
            faces: Vec::new(),
        })
    }

    /// The 10-node mesh of a linear one: a node at the middle of every edge (shared by
    /// the tetrahedra around it, fixed when the edge lies on the boundary); a quadratic
    /// mesh comes back as it is.
    pub fn to_quadratic(&self) -> Result<VolumeMesh> {
        if self.is_quadratic() {
            return Ok(self.clone());
        }
        let mut nodes = self.nodes.clone();
        let mut mid = std::collections::HashMap::new();
        let mut elements = Vec::with_capacity(10 * self.element_count());
        for e in 0..self.element_count() {
            let t: [u32; 4] = self.element(e).try_into().expect("a linear mesh has 4 nodes a tetrahedron");
            elements.extend_from_slice(&t);
            for [a, b] in TET10_EDGES {
                let key = (t[a].min(t[b]), t[a].max(t[b]));
                let id = *mid.entry(key).or_insert_with(|| {
                    nodes.push(0.5 * (self.nodes[t[a] as usize] + self.nodes[t[b] as usize]));
                    (nodes.len() - 1) as u32
                });
                elements.push(id);
            }
        }
        let mut fixed = self.fixed.clone();
        fixed.resize(nodes.len(), false);
        VolumeMesh::build(TetParts {
            nodes,
            node_lines: Vec::new(),
            kind: VolumeKind::Tet10,
            elements,
            element_lines: Vec::new(),
            fixed: FixedSpec::BoundaryAnd(fixed),
            faces: self.faces.clone(),
        })
    }

    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }
    pub fn element_count(&self) -> usize {
        self.elements.len() / self.kind.nodes()
    }
    /// The kind of every element.
    pub fn kind(&self) -> VolumeKind {
        self.kind
    }
    /// Whether the elements have mid-edge nodes (they follow their corners).
    pub fn is_quadratic(&self) -> bool {
        self.kind.is_quadratic()
    }
    pub fn nodes(&self) -> &[DVec3] {
        &self.nodes
    }
    /// The positions, to move nodes (the smoothers' `place`).
    pub fn nodes_mut(&mut self) -> &mut [DVec3] {
        &mut self.nodes
    }
    /// The node ids of tetrahedron `e`: 4, or 10 in [`TET10_EDGES`]' order.
    pub fn element(&self, e: usize) -> &[u32] {
        let k = self.kind.nodes();
        &self.elements[e * k..(e + 1) * k]
    }
    /// The measures of tetrahedron `e` as the statistics take them: by its corners, a
    /// 10-node one with its mid-edge nodes ([`q3::tet10_measures`]), against its kind's
    /// reference W.
    pub fn measures(&self, e: usize) -> q3::TetMeasures {
        let r = self.kind.reference();
        match self.kind {
            VolumeKind::Tet4 => q3::tet_measures(&self.corners(e), r),
            VolumeKind::Tet10 => {
                let ids = self.element(e);
                q3::tet10_measures(&std::array::from_fn(|j| self.nodes[ids[j] as usize]), r)
            }
        }
    }

    /// The corners of tetrahedron `e`.
    pub fn corners(&self, e: usize) -> [DVec3; 4] {
        let ids = self.element(e);
        match self.kind {
            // a tetrahedron's corners are its first four nodes
            VolumeKind::Tet4 | VolumeKind::Tet10 => [0, 1, 2, 3].map(|j| self.nodes[ids[j] as usize]),
        }
    }
    pub fn fixed(&self) -> &[bool] {
        &self.fixed
    }
    pub fn role(&self, n: usize) -> NodeRole {
        self.role[n]
    }
    /// A node the smoothers may move: a corner that is not fixed.
    pub fn is_free(&self, n: usize) -> bool {
        !self.fixed[n] && self.role[n] == NodeRole::Corner
    }
    pub fn free_count(&self) -> usize {
        (0..self.node_count()).filter(|&n| self.is_free(n)).count()
    }
    /// The tetrahedra with corner `n`.
    pub fn node_tets(&self, n: usize) -> &[u32] {
        &self.tets[self.tet_start[n] as usize..self.tet_start[n + 1] as usize]
    }
    /// The corner nodes sharing an edge with corner `n`.
    pub fn neighbours(&self, n: usize) -> &[u32] {
        &self.nb[self.nb_start[n] as usize..self.nb_start[n + 1] as usize]
    }
    /// The boundary faces (faces of one tetrahedron), outward.
    pub fn boundary_faces(&self) -> &[[u32; 3]] {
        &self.boundary
    }
    /// Puts the mid-edge nodes of corner `n`'s edges that are not fixed at their edges'
    /// middles (after `n` moved). Nothing for a linear mesh.
    pub fn follow_mid_nodes(&mut self, n: usize) {
        for i in self.follow_start[n] as usize..self.follow_start[n + 1] as usize {
            let [m, o] = self.follow[i];
            if !self.fixed[m as usize] {
                self.nodes[m as usize] = 0.5 * (self.nodes[n] + self.nodes[o as usize]);
            }
        }
    }
    /// The mean length of the tetrahedra's edges (each edge counted once per tetrahedron
    /// it belongs to); 0 for an empty mesh.
    pub fn mean_edge_length(&self) -> f64 {
        let count = self.element_count();
        if count == 0 {
            return 0.0;
        }
        let sum: f64 = (0..count)
            .map(|e| {
                let p = self.corners(e);
                q3::TET_EDGES.iter().map(|&[a, b]| p[a].distance(p[b])).sum::<f64>()
            })
            .sum();
        sum / (6 * count) as f64
    }
    /// The length of the bounding box's diagonal.
    pub fn size(&self) -> f64 {
        let (lo, hi) =
            self.nodes.iter().fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(l, h), p| (l.min(*p), h.max(*p)));
        if self.nodes.is_empty() {
            0.0
        } else {
            lo.distance(hi)
        }
    }
}

fn sorted3(mut f: [u32; 3]) -> [u32; 3] {
    f.sort_unstable();
    f
}
