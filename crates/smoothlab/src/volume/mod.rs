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

use crate::error::{listed, Error, Numbering, Result};
pub use crate::mesh::{VolumeKind, TET10_EDGES};
use crate::mesh::{csr, FixedSpec, MeshBuilder, NodeRole};
use crate::numeric::order::sort_stable_by_key;
use crate::quality::solid::{solid_measures, validity, SolidMeasures, Validity};
use crate::quality::tet as q3;

mod boundary;
mod fit;
mod mend;
mod smooth;
mod stats;
mod swap;
#[cfg(test)]
mod tests;

pub use boundary::{BoundaryNode, BoundaryRule, Tangent, FEATURE_ANGLE_DEG};
pub use mend::LIFT;
pub use smooth::{smooth_volume, VolumeSmoother};
pub use stats::volume_stats;
pub use swap::swap_max_min_dihedral;

/// What a reader found, before it is checked: nodes and elements with their file lines
/// (0 where none), and how the fixed flags are decided.
#[derive(Clone, Debug)]
pub struct SolidParts {
    pub nodes: Vec<DVec3>,
    pub node_lines: Vec<u32>,
    /// The kind of every element.
    pub kinds: Vec<VolumeKind>,
    /// Node ids, [`VolumeKind::nodes`] per element, one element after another.
    pub elements: Vec<u32>,
    pub element_lines: Vec<u32>,
    pub fixed: FixedSpec,
    /// The file's triangles and quads (the boundary faces Gmsh writes), kept to be
    /// written back.
    pub faces: Vec<GivenFace>,
}

/// A triangle or quad a volume mesh's file gave beside its elements (Gmsh writes
/// the boundary faces, often with their physical groups): its nodes fix those nodes, and
/// the writers write it back after the elements.
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

/// A face of an element by its corner nodes: a triangle or a quadrilateral, ordered so
/// that its normal points out of the element.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Face {
    nodes: [u32; 4],
    len: u8,
}

impl Face {
    fn of(ids: &[u32], local: &[usize]) -> Face {
        let mut nodes = [u32::MAX; 4];
        for (n, &j) in nodes.iter_mut().zip(local) {
            *n = ids[j];
        }
        Face { nodes, len: local.len() as u8 }
    }
    /// Its corner nodes, 3 or 4.
    #[inline]
    pub fn nodes(&self) -> &[u32] {
        &self.nodes[..self.len as usize]
    }
    /// Its nodes sorted: the same for the two elements that share it.
    fn key(&self) -> [u32; 4] {
        let mut k = self.nodes;
        k.sort_unstable();
        k
    }
    /// Its corners when it is a triangle.
    pub fn as_triangle(&self) -> Option<[u32; 3]> {
        (self.len == 3).then(|| [self.nodes[0], self.nodes[1], self.nodes[2]])
    }
    /// The triangles that cover it: itself, or a quad's two halves.
    pub fn triangles(&self) -> impl Iterator<Item = [u32; 3]> + '_ {
        let n = self.nodes;
        let quad = self.len == 4;
        std::iter::once([n[0], n[1], n[2]]).chain(quad.then_some([n[0], n[2], n[3]]))
    }
}

/// A mesh of volume elements (see the module docs).
#[derive(Clone, Debug)]
pub struct VolumeMesh {
    nodes: Vec<DVec3>,
    /// The kind of every element.
    element_kinds: Vec<VolumeKind>,
    /// The kinds present, in [`VolumeKind`]'s order.
    present: Vec<VolumeKind>,
    /// CSR: element `e`'s nodes are `elements[start[e]..start[e + 1]]`.
    start: Vec<u32>,
    elements: Vec<u32>,
    fixed: Vec<bool>,
    role: Vec<NodeRole>,
    /// CSR: the elements with node n as a corner.
    tet_start: Vec<u32>,
    tets: Vec<u32>,
    /// Beside `tets`, where the element is a tetrahedron: its other three corners in the
    /// order of the corner's edges ([`VolumeKindRow::corner_edges`](crate::mesh::VolumeKindRow)),
    /// so a star is read in one stream rather than element by element from
    /// `elements` (`u32::MAX` for another kind; empty when there is no tetrahedron).
    tet_corners: Vec<[u32; 3]>,
    /// CSR: the corner nodes sharing an edge with corner n.
    nb_start: Vec<u32>,
    nb: Vec<u32>,
    /// CSR (quadratic meshes): the nodes that follow corner n (mid-edge, face and centre
    /// nodes of its elements that have it among their corners).
    follow_start: Vec<u32>,
    follow: Vec<u32>,
    /// CSR (quadratic meshes): the corners each follower sits at the mean of.
    parent_start: Vec<u32>,
    parents: Vec<u32>,
    /// Faces of one element, outward (right-handed seen from outside), in the order of
    /// their keys ([`Face::key`]): the build finds them among the faces sorted by key.
    boundary: Vec<Face>,
    /// The file's triangles and quads ([`GivenFace`]).
    faces: Vec<GivenFace>,
    /// How the file numbered the nodes, for the notes about it
    /// ([`stray_faces_note`](Self::stray_faces_note)).
    node_numbers: Numbering,
    /// The positions the corners' targets are taken from, where they are not the ideal
    /// ([`crate::target::Target::Input`]).
    target: Option<std::sync::Arc<Vec<DVec3>>>,
    /// Each element's own target corners, where they are not its nodes' in
    /// [`target`](Self::target) ([`crate::target::Target::Stretch`]).
    target_shapes: Option<std::sync::Arc<Vec<[DVec3; 8]>>>,
    /// The nodes the file itself fixed (its flags), whatever the boundary rule.
    given_fixed: Option<crate::mesh::GivenFlags>,
    /// The sliding rule, when boundary nodes slide ([`BoundaryRule::Slide`]).
    sliding: Option<boundary::Sliding>,
    /// Per element, the elements that share a face with it (CSR), built at first use.
    face_neighbours: std::sync::OnceLock<(Vec<u32>, Vec<u32>)>,
}

/// An element's corner determinants' sum, in units of its own size, and whether it has
/// no volume: a tetrahedron's 6V exactly 0 (its four corners in a plane), another kind's
/// measured corners' determinants all exactly 0 — decided on the doubles as given
/// ([`orient3d`](crate::numeric::exact::orient3d)), not against a tolerance: a tangled
/// element of small volume beside large ones is a smoother's input, not a flat one
/// (issue 61: a tetrahedron of volume 0.017 next to a node at x = 1e4 was refused).
fn signed_size(kind: VolumeKind, p: &[DVec3]) -> (f64, bool) {
    use crate::numeric::exact::orient3d;
    use std::cmp::Ordering;
    let r = kind.row();
    if kind.is_tet() {
        // in the tetrahedron's own scale: a cube of 1e150 has volumes beyond the doubles
        let flat = orient3d(p[0], p[1], p[2], p[3]) == Ordering::Equal;
        let p = q3::in_unit_scale(&[p[0], p[1], p[2], p[3]]);
        let v = q3::signed_volume(&p);
        let size = q3::TET_EDGES.iter().map(|&[a, b]| p[a].distance(p[b])).sum::<f64>() / 6.0;
        return (v / (size * size * size), flat);
    }
    let (mut total, mut flat) = (0.0, true);
    for c in 0..r.corner_edges.len() {
        let given = crate::quality::solid::corner_tet(kind, p, c);
        flat &= orient3d(given[0], given[1], given[2], given[3]) == Ordering::Equal;
        let t = q3::in_unit_scale(&given);
        let det = 6.0 * q3::signed_volume(&t);
        let size = (1..4).map(|j| t[j].distance(t[0])).sum::<f64>() / 3.0;
        let cube = size * size * size;
        total += det / cube;
    }
    (total, flat)
}

impl VolumeMesh {
    /// The volume mesh of a builder's volume elements (a file's: see
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
        let parts = SolidParts {
            faces,
            nodes: p.points.iter().map(|&x| DVec3::from(x)).collect(),
            node_lines: p.point_lines,
            kinds: p.kinds,
            elements: p.tets,
            element_lines: p.tet_lines,
            fixed: p.fixed,
        };
        VolumeMesh::build_numbered(parts, &p.node_numbers, &p.volume_numbers)
    }

    /// Checks what a reader found and builds the mesh. Errors name the node or element
    /// and its file line: no elements, a coordinate that is not a finite number (or too
    /// large to compute with), a node id out of range, a node repeated in an element, a
    /// node that is a corner of one element and a mid-edge node of another, an element
    /// without volume, a face of more than two elements. A mesh given left-handed
    /// (negative total volume) is turned over, every element with it; single inverted
    /// elements stay (a tangled mesh is the smoothers' input).
    pub fn build(parts: SolidParts) -> Result<VolumeMesh> {
        Self::build_numbered(parts, &Numbering::default(), &Numbering::default())
    }

    /// [`build`](Self::build), its messages naming nodes and elements as the file numbers
    /// them (`node_numbers`, `element_numbers`).
    pub(crate) fn build_numbered(
        parts: SolidParts,
        node_numbers: &Numbering,
        element_numbers: &Numbering,
    ) -> Result<VolumeMesh> {
        let SolidParts { nodes, node_lines, kinds, mut elements, element_lines, fixed, faces: given_faces } = parts;
        let line = |lines: &[u32], i: usize| lines.get(i).copied().filter(|&l| l > 0).map(|l| l as usize);
        let (node, number) = (|i: u32| node_numbers.of(i as usize), |e: usize| element_numbers.of(e));
        if kinds.is_empty() {
            return Err(Error::Empty("the mesh has no volume elements".into()));
        }
        let mut start = Vec::with_capacity(kinds.len() + 1);
        start.push(0u32);
        for k in &kinds {
            start.push(start.last().copied().unwrap_or(0) + k.nodes() as u32);
        }
        debug_assert_eq!(*start.last().unwrap_or(&0) as usize, elements.len());
        // in `VolumeKind`'s order, which is `ALL`'s
        let mut seen = [false; VolumeKind::ALL.len()];
        for &k in &kinds {
            seen[k as usize] = true;
        }
        let present: Vec<VolumeKind> = VolumeKind::ALL.into_iter().filter(|&k| seen[k as usize]).collect();
        let family = |e: usize| kinds[e].row().name;
        for (i, p) in nodes.iter().enumerate() {
            if !p.is_finite() {
                return Err(Error::node(
                    node(i as u32),
                    line(&node_lines, i),
                    format!("coordinate {p} is not a finite number"),
                ));
            }
            if p.abs().max_element() > crate::mesh::MAX_COORDINATE {
                return Err(Error::node(
                    node(i as u32),
                    line(&node_lines, i),
                    format!("coordinate {p} is too large to compute with"),
                ));
            }
        }
        let n = nodes.len();
        let count = kinds.len();
        let range = |e: usize| start[e] as usize..start[e + 1] as usize;
        let mut role = vec![NodeRole::Unused; n];
        for e in 0..count {
            let ids = &elements[range(e)];
            for (j, &id) in ids.iter().enumerate() {
                if id as usize >= n {
                    return Err(Error::element(
                        number(e),
                        line(&element_lines, e),
                        format!(
                            "node {} does not exist: the mesh has {n} nodes ({} to {})",
                            node(id),
                            node(0),
                            node(n.saturating_sub(1) as u32)
                        ),
                    ));
                }
                if ids[..j].contains(&id) {
                    return Err(Error::element(
                        number(e),
                        line(&element_lines, e),
                        format!("node {} appears twice in the {}", node(id), family(e)),
                    ));
                }
            }
        }
        for e in 0..count {
            let corners = kinds[e].corners();
            for (j, &id) in elements[range(e)].iter().enumerate() {
                let r = if j < corners { NodeRole::Corner } else { NodeRole::Mid };
                match (role[id as usize], r) {
                    (NodeRole::Unused, r) => role[id as usize] = r,
                    (a, b) if a != b => {
                        return Err(Error::element(
                            number(e),
                            line(&element_lines, e),
                            format!("node {} is a corner of one element and a mid-edge node of another", node(id)),
                        ))
                    }
                    _ => {}
                }
            }
        }
        // volume, in units of each element's own size, and the whole mesh's handedness
        let mut total = 0.0;
        let mut scratch = [DVec3::ZERO; 8];
        for e in 0..count {
            let k = kinds[e];
            let ids = &elements[range(e)];
            for (s, &i) in scratch.iter_mut().zip(&ids[..k.corners()]) {
                *s = nodes[i as usize];
            }
            let (v, flat) = signed_size(k, &scratch[..k.corners()]);
            if flat {
                let what = if k.is_tet() {
                    "the tetrahedron has no volume: its four corners lie in a plane".to_string()
                } else {
                    format!("the {} has no volume: every corner's three edges lie in a plane", family(e))
                };
                return Err(Error::element(number(e), line(&element_lines, e), what));
            }
            total += v;
        }
        if total < 0.0 {
            let mut old = [0u32; 32];
            for e in 0..count {
                let row = kinds[e].row();
                let t = &mut elements[range(e)];
                old[..t.len()].copy_from_slice(t);
                for (to, &from) in t.iter_mut().zip(row.mirror) {
                    *to = old[from];
                }
            }
        }
        // faces: boundary (one element) or shared (two); more is not a manifold
        let mut faces: Vec<([u32; 4], u32, u8)> = Vec::with_capacity(6 * count);
        for e in 0..count {
            let ids = &elements[range(e)];
            for (f, loc) in kinds[e].row().faces.iter().enumerate() {
                faces.push((Face::of(ids, loc).key(), e as u32, f as u8));
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
                let nodes: Vec<u64> = faces[i].0.iter().copied().filter(|&x| x != u32::MAX).map(node).collect();
                return Err(Error::element(
                    number(e),
                    line(&element_lines, e),
                    format!(
                        "its face {nodes:?} is a face of {} elements ({}; at most two share a face)",
                        j - i,
                        listed(faces[i..j].iter().map(|f| number(f.1 as usize)), j - i)
                    ),
                ));
            }
            if j - i == 1 {
                let (_, e, f) = faces[i];
                let e = e as usize;
                boundary.push(Face::of(&elements[range(e)], kinds[e].row().faces[f as usize]));
            }
            i = j;
        }
        // fixed flags
        let mut on_boundary = vec![false; n];
        for f in &boundary {
            for &c in f.nodes() {
                on_boundary[c as usize] = true;
            }
        }
        let quadratic = present.iter().any(|k| k.is_quadratic());
        if quadratic {
            // a follower is on the boundary when all the corners it follows are on one
            // boundary face together
            let mut face_keys = std::collections::HashSet::new();
            for f in &boundary {
                let c = f.nodes();
                for a in 0..c.len() {
                    let b = (a + 1) % c.len();
                    face_keys.insert(vec![c[a].min(c[b]), c[a].max(c[b])]);
                }
                let mut all = c.to_vec();
                all.sort_unstable();
                face_keys.insert(all);
            }
            for e in 0..count {
                let row = kinds[e].row();
                let t = &elements[range(e)];
                for (m, parents) in row.followers.iter().enumerate() {
                    let mut key: Vec<u32> = parents.iter().map(|&c| t[c]).collect();
                    key.sort_unstable();
                    if face_keys.contains(&key) {
                        on_boundary[t[row.corners + m] as usize] = true;
                    }
                }
            }
        }
        // the file's triangles and quads fix their nodes (unless the file gave the flags
        // exactly); those on the boundary skin only mark it, so the sliding rule
        // ([`BoundaryRule::Slide`]) holds only the nodes of the others
        let skin: std::collections::HashSet<[u32; 4]> = boundary.iter().map(|f| f.key()).collect();
        let mut marked = vec![false; n];
        let mut marked_inside = vec![false; n];
        for f in &given_faces {
            let corners = &f.nodes()[..f.kind.corners()];
            let on_skin = corners.len() <= 4 && skin.contains(&Face::of(corners, &[0, 1, 2, 3][..corners.len()]).key());
            for &i in f.nodes() {
                if let Some(m) = marked.get_mut(i as usize) {
                    *m = true;
                    marked_inside[i as usize] |= !on_skin;
                }
            }
        }
        let (fixed, given_fixed) = match fixed {
            FixedSpec::Exact(f) => (f.clone(), Some(crate::mesh::GivenFlags { flags: f, exact: true })),
            FixedSpec::Boundary | FixedSpec::BoundaryAnd(_) => {
                let flags = match fixed {
                    FixedSpec::BoundaryAnd(mut f) => {
                        f.resize(n, false);
                        f
                    }
                    _ => vec![false; n],
                };
                let fixed = (0..n).map(|i| on_boundary[i] || flags[i] || marked[i]).collect();
                let given = (0..n).map(|i| flags[i] || marked_inside[i]).collect::<Vec<bool>>();
                (fixed, given.iter().any(|&g| g).then_some(crate::mesh::GivenFlags { flags: given, exact: false }))
            }
        };
        let mut given_fixed = given_fixed;
        if let Some(g) = &mut given_fixed {
            g.flags.resize(n, false);
        }
        let mut fixed: Vec<bool> = fixed;
        fixed.resize(n, false);
        for (f, r) in fixed.iter_mut().zip(&role) {
            *f |= *r == NodeRole::Unused;
        }
        // adjacency, flat
        let mut pairs: Vec<(u32, u32)> = Vec::with_capacity(8 * count);
        for e in 0..count {
            let c = kinds[e].corners();
            for &id in &elements[range(e)][..c] {
                pairs.push((id, e as u32));
            }
        }
        let (tet_start, tets) = csr(n, &mut pairs);
        let mut tet_corners = Vec::new();
        if present.iter().any(|k| k.is_tet()) {
            tet_corners.reserve_exact(tets.len());
            for node in 0..n {
                for &e in &tets[tet_start[node] as usize..tet_start[node + 1] as usize] {
                    let (kind, ids) = (kinds[e as usize], &elements[range(e as usize)]);
                    let slot = ids[..kind.corners()].iter().position(|&i| i as usize == node);
                    tet_corners.push(match slot {
                        Some(slot) if kind.is_tet() => kind.row().corner_edges[slot].map(|k| ids[k]),
                        _ => [u32::MAX; 3],
                    });
                }
            }
        }
        pairs.clear();
        for e in 0..count {
            let ids = &elements[range(e)];
            for &[a, b] in kinds[e].row().edges {
                let (a, b) = (ids[a], ids[b]);
                pairs.push((a, b));
                pairs.push((b, a));
            }
        }
        pairs.sort_unstable();
        pairs.dedup();
        let (nb_start, nb) = csr(n, &mut pairs);
        let (mut follow_start, mut follow) = (vec![0u32; n + 1], Vec::new());
        let (mut parent_start, mut parents) = (vec![0u32; n + 1], Vec::new());
        if quadratic {
            pairs.clear();
            let mut of: Vec<(u32, u32, u32)> = Vec::new();
            for e in 0..count {
                let row = kinds[e].row();
                let t = &elements[range(e)];
                for (m, ps) in row.followers.iter().enumerate() {
                    let follower = t[row.corners + m];
                    for (slot, &c) in ps.iter().enumerate() {
                        pairs.push((t[c], follower));
                        of.push((follower, slot as u32, t[c]));
                    }
                }
            }
            pairs.sort_unstable();
            pairs.dedup();
            (follow_start, follow) = csr(n, &mut pairs);
            // each follower's corners, as the first element that has it lists them
            sort_stable_by_key(&mut of, |&(f, _, _)| f as u64);
            let mut seen = vec![false; n];
            let mut list: Vec<(u32, u32)> = Vec::new();
            let mut i = 0;
            while i < of.len() {
                let f = of[i].0;
                let mut j = i;
                while j < of.len() && of[j].0 == f {
                    j += 1;
                }
                if !seen[f as usize] {
                    seen[f as usize] = true;
                    // the first element's entries are the first `len` with slots 0, 1, …
                    let mut k = i;
                    let mut slot = 0;
                    while k < j && of[k].1 == slot {
                        list.push((f, of[k].2));
                        slot += 1;
                        k += 1;
                    }
                }
                i = j;
            }
            // in followers' order already (made from `of`, sorted by follower), each
            // follower's corners in their order
            debug_assert!(list.windows(2).all(|w| w[0].0 <= w[1].0));
            for &(f, _) in &list {
                parent_start[f as usize + 1] += 1;
            }
            for i in 0..n {
                parent_start[i + 1] += parent_start[i];
            }
            parents = list.iter().map(|&(_, c)| c).collect();
        }
        Ok(VolumeMesh {
            nodes,
            element_kinds: kinds,
            present,
            start,
            elements,
            fixed,
            role,
            tet_start,
            tets,
            tet_corners,
            nb_start,
            nb,
            follow_start,
            follow,
            parent_start,
            parents,
            boundary,
            faces: given_faces,
            node_numbers: node_numbers.clone(),
            target: None,
            target_shapes: None,
            given_fixed,
            sliding: None,
            face_neighbours: std::sync::OnceLock::new(),
        })
    }

    /// The elements that share a face with element `e` (by their corner nodes).
    pub fn face_neighbours(&self, e: usize) -> &[u32] {
        let (start, nb) = self.face_neighbours.get_or_init(|| {
            let mut lists = vec![Vec::new(); self.element_count()];
            for (a, b) in stats::face_neighbours(self) {
                lists[a].push(b as u32);
                lists[b].push(a as u32);
            }
            let mut start = Vec::with_capacity(lists.len() + 1);
            start.push(0u32);
            for l in &lists {
                start.push(start.last().unwrap() + l.len() as u32);
            }
            (start, lists.concat())
        });
        &nb[start[e] as usize..start[e + 1] as usize]
    }

    /// Takes every corner's target from the nodes' positions `at` ([`crate::target::Target::Input`];
    /// `None`: the ideal of each kind).
    pub fn set_target_nodes(&mut self, at: Option<Vec<DVec3>>) {
        self.target = at.map(std::sync::Arc::new);
        self.target_shapes = None;
    }

    /// Measures every corner against `target` taken from the nodes' positions `at`
    /// ([`crate::target::Target`]); the ideal where `target` leaves every corner at it.
    pub fn set_target_from(&mut self, target: crate::target::Target, at: Vec<DVec3>) {
        use crate::target::Target;
        match target {
            Target::Ideal => self.set_target_nodes(None),
            Target::Input => self.set_target_nodes(Some(at)),
            Target::Stretch => {
                let shapes = crate::target::volume_stretch_points(self, &at);
                self.set_target_nodes(shapes.is_some().then_some(at));
                self.target_shapes = shapes.map(std::sync::Arc::new);
            }
        }
    }

    /// Where node `n` of element `e` is in the targets, where the mesh has them.
    #[inline]
    pub fn target_point(&self, e: usize, n: u32) -> Option<DVec3> {
        let t = self.target.as_deref()?;
        Some(match self.target_shapes.as_deref() {
            Some(shapes) => {
                let slot = self.element(e).iter().position(|&m| m == n).expect("a node of the element");
                shapes[e][slot]
            }
            None => t[n as usize],
        })
    }

    /// The positions the corners' targets are taken from, where they are not the ideal.
    pub fn target_nodes(&self) -> Option<&[DVec3]> {
        self.target.as_deref().map(|v| v.as_slice())
    }

    /// The file's triangles and quads, written back after the tetrahedra.
    pub fn faces(&self) -> &[GivenFace] {
        &self.faces
    }

    /// What the file's triangles and quads fixed inside the volume: those that are not a
    /// boundary face of the elements fix their nodes as the file asks (where the file
    /// gave no fixed flags of its own), and this says which nodes off the boundary that
    /// fixed (`None` when none).
    pub fn stray_faces_note(&self) -> Option<String> {
        let on_boundary: Vec<[u32; 4]> = self.boundary.iter().map(Face::key).collect();
        debug_assert!(on_boundary.windows(2).all(|w| w[0] < w[1]), "the boundary in its keys' order");
        let mut boundary_node = vec![false; self.nodes.len()];
        for f in &self.boundary {
            for &i in f.nodes() {
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
                let local: Vec<usize> = (0..c.len()).collect();
                on_boundary.binary_search(&Face::of(c, &local).key()).is_err()
            })
            .map(|f| (f, inner_fixed(f)))
            .filter(|(_, inner)| !inner.is_empty())
            .collect();
        let (first, inner) = stray.first()?;
        let at = if first.line > 0 { format!(" (line {})", first.line) } else { String::new() };
        let nodes: Vec<String> = inner.iter().map(|&i| self.node_numbers.of(i as usize).to_string()).collect();
        Some(format!(
            "{} of the file's triangles and quads {} not on the boundary of the {} and {} nodes inside the volume, as the file asks: the first{at} fixes node {}",
            stray.len(),
            if stray.len() == 1 { "is" } else { "are" },
            self.family_words(),
            if stray.len() == 1 { "fixes" } else { "fix" },
            nodes.join(", "),
        ))
    }

    /// The families of its elements in words: "tetrahedra", "hexahedra and pyramids".
    pub fn family_words(&self) -> String {
        let mut fams: Vec<&str> = self.present.iter().map(|k| k.row().family).collect();
        fams.dedup();
        match fams.as_slice() {
            [one] => one.to_string(),
            [rest @ .., last] => format!("{} and {last}", rest.join(", ")),
            [] => String::new(),
        }
    }

    /// A linear mesh from points and tetrahedra (generators), boundary nodes fixed.
    pub fn from_tets(nodes: Vec<DVec3>, tets: &[[u32; 4]]) -> Result<VolumeMesh> {
        VolumeMesh::from_elements(nodes, tets.iter().map(|t| (VolumeKind::Tet4, &t[..])))
    }

    /// A mesh from points and elements of any kinds (generators), boundary nodes fixed.
    pub fn from_elements<'a>(nodes: Vec<DVec3>, elements: impl IntoIterator<Item = (VolumeKind, &'a [u32])>) -> Result<VolumeMesh> {
        let (mut kinds, mut ids) = (Vec::new(), Vec::new());
        for (k, e) in elements {
            kinds.push(k);
            ids.extend_from_slice(e);
        }
        VolumeMesh::build(SolidParts {
            node_lines: Vec::new(),
            nodes,
            kinds,
            elements: ids,
            element_lines: Vec::new(),
            fixed: FixedSpec::Boundary,
            faces: Vec::new(),
        })
    }

    /// The quadratic mesh of a linear one — 10-node tetrahedra, 27-node hexahedra (with
    /// `serendipity`, 20-node ones): a node at the middle of every edge (and of every face
    /// and element of a 27-node hexahedron), shared by the elements around it, fixed on the
    /// boundary; a quadratic mesh comes back as it is. Wedges and pyramids have no
    /// quadratic kind here: refused.
    pub fn to_quadratic(&self, serendipity: bool) -> Result<VolumeMesh> {
        if self.is_quadratic() {
            return Ok(self.clone());
        }
        let mut nodes = self.nodes.clone();
        let mut shared = std::collections::HashMap::new();
        let (mut kinds, mut elements) = (Vec::with_capacity(self.element_count()), Vec::new());
        for e in 0..self.element_count() {
            let to = match self.element_kinds[e] {
                VolumeKind::Tet4 => VolumeKind::Tet10,
                VolumeKind::Hex8 if serendipity => VolumeKind::Hex20,
                VolumeKind::Hex8 => VolumeKind::Hex27,
                k => return Err(Error::invalid(format!("{} have no quadratic kind in smoothlab", k.row().family))),
            };
            let t = self.element(e);
            kinds.push(to);
            elements.extend_from_slice(t);
            for ps in to.row().followers {
                let mut key: Vec<u32> = ps.iter().map(|&c| t[c]).collect();
                key.sort_unstable();
                let id = *shared.entry(key).or_insert_with(|| {
                    nodes.push(mean(ps.iter().map(|&c| self.nodes[t[c] as usize])));
                    (nodes.len() - 1) as u32
                });
                elements.push(id);
            }
        }
        let mut fixed = self.fixed.clone();
        fixed.resize(nodes.len(), false);
        VolumeMesh::build(SolidParts {
            nodes,
            node_lines: Vec::new(),
            kinds,
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
        self.element_kinds.len()
    }
    /// The kinds its elements are of, in [`VolumeKind`]'s order (each once).
    pub fn kinds(&self) -> &[VolumeKind] {
        &self.present
    }
    /// The kind of element `e`.
    #[inline]
    pub fn element_kind(&self, e: usize) -> VolumeKind {
        self.element_kinds[e]
    }
    /// Whether every element is a tetrahedron (of one kind: a mesh does not mix orders).
    #[inline]
    pub fn is_tets(&self) -> bool {
        self.present.iter().all(|k| k.is_tet())
    }
    /// Whether the elements have nodes that follow their corners.
    pub fn is_quadratic(&self) -> bool {
        self.present.iter().any(|k| k.is_quadratic())
    }
    pub fn nodes(&self) -> &[DVec3] {
        &self.nodes
    }
    /// The positions, to move nodes (the smoothers' `place`).
    pub fn nodes_mut(&mut self) -> &mut [DVec3] {
        &mut self.nodes
    }
    /// The node ids of element `e`, in its kind's order.
    #[inline]
    pub fn element(&self, e: usize) -> &[u32] {
        &self.elements[self.start[e] as usize..self.start[e + 1] as usize]
    }
    /// The positions of element `e`'s nodes (up to 27).
    pub fn element_points(&self, e: usize) -> ([DVec3; 27], usize) {
        let ids = self.element(e);
        let mut p = [DVec3::ZERO; 27];
        for (q, &i) in p.iter_mut().zip(ids) {
            *q = self.nodes[i as usize];
        }
        (p, ids.len())
    }
    /// The measures of element `e` as the statistics take them
    /// ([`crate::quality::solid::solid_measures`]: a 10-node tetrahedron with its
    /// mid-edge nodes, the others by their corners, validity certain).
    pub fn measures(&self, e: usize) -> SolidMeasures {
        let (p, n) = self.element_points(e);
        solid_measures(self.element_kinds[e], &p[..n])
    }
    /// [`element_points`](Self::element_points) with corner `n` at `x` and the nodes that
    /// follow `n` and are not fixed at the means of their corners, as
    /// [`follow_mid_nodes`](Self::follow_mid_nodes) would put them.
    pub fn element_points_with_node_at(&self, e: usize, n: usize, x: DVec3) -> ([DVec3; 27], usize) {
        let at = |i: u32| if i as usize == n { x } else { self.nodes[i as usize] };
        let ids = self.element(e);
        let mut p = [DVec3::ZERO; 27];
        let follows = self.followers(n);
        for (q, &i) in p.iter_mut().zip(ids) {
            *q = if follows.contains(&i) && !self.fixed[i as usize] { mean(self.parents(i as usize).iter().map(|&c| at(c))) } else { at(i) };
        }
        (p, ids.len())
    }
    /// Whether element `e` is inverted: not certainly valid (a tetrahedron's volume ≤ 0; a
    /// hexahedron's, wedge's or pyramid's Jacobian determinant ≤ 0 somewhere or not
    /// decided, [`crate::quality::solid::validity`]).
    pub fn is_inverted(&self, e: usize) -> bool {
        let k = self.element_kinds[e];
        let c = self.corners(e);
        if k.is_tet() {
            q3::is_inverted(&[c[0], c[1], c[2], c[3]])
        } else {
            validity(k, &c[..k.corners()]) != Validity::Valid
        }
    }

    /// The corners of element `e` (the first [`VolumeKind::corners`] entries).
    #[inline]
    pub fn corners(&self, e: usize) -> [DVec3; 8] {
        let ids = self.element(e);
        let mut p = [DVec3::ZERO; 8];
        for (q, &i) in p.iter_mut().zip(&ids[..self.element_kinds[e].corners()]) {
            *q = self.nodes[i as usize];
        }
        p
    }
    /// The corners of tetrahedron `e` (of a mesh of tetrahedra).
    #[inline]
    pub fn tet_corners(&self, e: usize) -> [DVec3; 4] {
        let ids = self.element(e);
        [0, 1, 2, 3].map(|j| self.nodes[ids[j] as usize])
    }
    pub fn fixed(&self) -> &[bool] {
        &self.fixed
    }
    pub fn role(&self, n: usize) -> NodeRole {
        self.role[n]
    }
    /// A node the smoothers may move: a corner that is not fixed, or that slides
    /// ([`BoundaryRule::Slide`]).
    #[inline]
    pub fn is_free(&self, n: usize) -> bool {
        let unfixed = match &self.sliding {
            None => !self.fixed[n],
            Some(s) => match s.class(n) {
                BoundaryNode::Interior => !self.fixed[n],
                c => c.slides(),
            },
        };
        unfixed && self.role[n] == NodeRole::Corner
    }
    pub fn free_count(&self) -> usize {
        (0..self.node_count()).filter(|&n| self.is_free(n)).count()
    }
    /// The elements with corner `n`.
    pub fn node_tets(&self, n: usize) -> &[u32] {
        &self.tets[self.tet_start[n] as usize..self.tet_start[n + 1] as usize]
    }
    /// Beside [`node_tets`](Self::node_tets)`(n)`: for each tetrahedron, its corners other
    /// than `n` in the order of `n`'s edges (an even permutation after `n`); `u32::MAX`
    /// for an element of another kind. Empty when the mesh has no tetrahedron.
    pub fn node_tet_corners(&self, n: usize) -> &[[u32; 3]] {
        if self.tet_corners.is_empty() {
            return &[];
        }
        &self.tet_corners[self.tet_start[n] as usize..self.tet_start[n + 1] as usize]
    }
    /// The corner nodes sharing an edge with corner `n`.
    pub fn neighbours(&self, n: usize) -> &[u32] {
        &self.nb[self.nb_start[n] as usize..self.nb_start[n + 1] as usize]
    }
    /// The boundary faces (faces of one element), outward.
    pub fn boundary_faces(&self) -> &[Face] {
        &self.boundary
    }
    /// The nodes that follow corner `n` (nothing for a linear mesh).
    pub fn followers(&self, n: usize) -> &[u32] {
        &self.follow[self.follow_start[n] as usize..self.follow_start[n + 1] as usize]
    }
    /// The corners follower `m` sits at the mean of.
    pub fn parents(&self, m: usize) -> &[u32] {
        &self.parents[self.parent_start[m] as usize..self.parent_start[m + 1] as usize]
    }
    /// Puts the nodes that follow corner `n` and are not fixed at the means of their
    /// corners (after `n` moved). Nothing for a linear mesh.
    pub fn follow_mid_nodes(&mut self, n: usize) {
        for i in self.follow_start[n] as usize..self.follow_start[n + 1] as usize {
            let m = self.follow[i] as usize;
            if !self.fixed[m] {
                let ps = &self.parents[self.parent_start[m] as usize..self.parent_start[m + 1] as usize];
                self.nodes[m] = mean(ps.iter().map(|&c| self.nodes[c as usize]));
            }
        }
    }
    /// The largest smallest corner scaled Jacobian of its hexahedra that any smoother can
    /// reach with the fixed nodes where they are: a corner whose node and two of its edge
    /// neighbours are fixed has a scaled Jacobian of at most the sine of the angle between
    /// those two edges (`det[a b c] ≤ |a × b|·|c|`), and one whose four nodes are fixed
    /// keeps its own. +∞ where no hexahedron's corner is so held. (Hexahedra only: their
    /// corners' reference is the cube's, so the edges are the corner matrix's columns.)
    pub fn scaled_jacobian_cap(&self) -> f64 {
        let mut cap = f64::INFINITY;
        for e in 0..self.element_count() {
            if !matches!(self.element_kinds[e], VolumeKind::Hex8 | VolumeKind::Hex20 | VolumeKind::Hex27) {
                continue;
            }
            let (ids, row) = (self.element(e), self.element_kinds[e].row());
            for (c, nb) in row.corner_edges.iter().enumerate() {
                if !self.fixed[ids[c] as usize] {
                    continue;
                }
                let at = |k: usize| self.nodes[ids[k] as usize] - self.nodes[ids[c] as usize];
                let mut held = nb.iter().copied().filter(|&k| self.fixed[ids[k] as usize]);
                let bound = match (held.next(), held.next(), held.next()) {
                    (Some(a), Some(b), Some(d)) => at(a).cross(at(b)).dot(at(d)) / (at(a).length() * at(b).length() * at(d).length()),
                    (Some(a), Some(b), None) => at(a).cross(at(b)).length() / (at(a).length() * at(b).length()),
                    _ => continue,
                };
                cap = cap.min(bound);
            }
        }
        cap
    }
    /// The mean length of the elements' edges (each edge counted once per element it
    /// belongs to); 0 for an empty mesh.
    pub fn mean_edge_length(&self) -> f64 {
        let (mut sum, mut edges) = (0.0, 0usize);
        for e in 0..self.element_count() {
            let k = self.element_kinds[e];
            let p = self.corners(e);
            let list: &[[usize; 2]] = if k.is_tet() { &q3::TET_EDGES } else { k.row().edges };
            sum += list.iter().map(|&[a, b]| p[a].distance(p[b])).sum::<f64>();
            edges += list.len();
        }
        if edges == 0 {
            0.0
        } else {
            sum / edges as f64
        }
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

/// The mean of 2, 4 or 8 points (a follower's corners): their sum, first to last, times
/// the power of two (exact), so an edge's middle is `0.5·(a + b)` to the bit.
fn mean(mut points: impl Iterator<Item = DVec3>) -> DVec3 {
    let first = points.next().unwrap_or(DVec3::ZERO);
    let (sum, n) = points.fold((first, 1usize), |(s, n), p| (s + p, n + 1));
    sum * (1.0 / n as f64)
}
