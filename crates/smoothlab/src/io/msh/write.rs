//! The `.msh` writers, one per format version, over any mesh ([`MshSource`]): a planar
//! mesh or a surface ([`super::super::Writable`]) and a volume with its file's faces
//! (`io::volume`). Nodes get tags `1..=n`, elements `1..` in the order they are written,
//! and the fixed flags follow as the `"fixed"` view.

use std::fmt::Write as _;

use crate::io::out::Out;
use crate::io::MshVersion;
use crate::mesh::ElementKind;

/// A 4.1 element block: the elements of `range` whose Gmsh type is `ty`, on the one
/// entity of dimension `dim` (2: the surface, 3: the volume).
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct MshBlock {
    pub dim: u8,
    pub ty: u32,
    pub range: std::ops::Range<usize>,
}

/// What the `.msh` writers read of a mesh. Its elements are numbered `0..element_count()`
/// in the order version 2.2 writes them; version 4.1 writes them block by block
/// ([`blocks`](Self::blocks)), numbered in that order.
pub(crate) trait MshSource {
    fn node_count(&self) -> usize;
    /// Writes node `i`'s coordinates, `x y z`.
    fn write_node(&self, s: &mut Out, i: usize);
    /// Writes the nodes' bounding box, `min_x min_y min_z max_x max_y max_z`, as an
    /// entity of 4.1 gives it.
    fn write_bounds(&self, s: &mut Out);
    fn element_count(&self) -> usize;
    /// Element `e`'s Gmsh type.
    fn element_type(&self, e: usize) -> u32;
    /// Writes element `e`'s node tags (1-based), each after a space, in Gmsh's node order.
    fn write_element_nodes(&self, s: &mut Out, e: usize);
    /// The 4.1 blocks, which together hold every element once.
    fn blocks(&self) -> Vec<MshBlock>;
    fn fixed(&self) -> &[bool];
}

/// Writes `mesh` as a `.msh` file (ASCII) in `version`.
pub(crate) fn write(mesh: &impl MshSource, version: MshVersion, s: &mut Out) {
    match version {
        MshVersion::V22 => write_v22(mesh, s),
        MshVersion::V41 => write_v41(mesh, s),
    }
    write_fixed_view(mesh.fixed(), s);
}

/// Version 2.2: the nodes, then every element in order with its type and two tags
/// (physical 0, elementary 1).
fn write_v22(mesh: &impl MshSource, s: &mut Out) {
    let n = mesh.node_count();
    // Writing to an `Out` cannot fail (a file's error is kept for `Out::finish`).
    let _ = write!(s, "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n");
    let _ = writeln!(s, "$Nodes\n{n}");
    for i in 0..n {
        let _ = write!(s, "{} ", i + 1);
        mesh.write_node(s, i);
        s.push('\n');
    }
    let m = mesh.element_count();
    let _ = writeln!(s, "$EndNodes\n$Elements\n{m}");
    for e in 0..m {
        let _ = write!(s, "{} {} 2 0 1", e + 1, mesh.element_type(e));
        mesh.write_element_nodes(s, e);
        s.push('\n');
    }
    s.push_str("$EndElements\n");
}

/// Version 4.1: one entity per dimension the blocks use (tag 1, the nodes' bounding box),
/// the nodes on the highest, then the blocks.
fn write_v41(mesh: &impl MshSource, s: &mut Out) {
    let n = mesh.node_count();
    let _ = write!(s, "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");
    let blocks = mesh.blocks();
    let has = |dim: u8| blocks.iter().any(|b| b.dim == dim);
    let (surfaces, volumes) = (usize::from(has(2)), usize::from(has(3)));
    let _ = write!(s, "$Entities\n0 0 {surfaces} {volumes}\n");
    for _ in 0..surfaces + volumes {
        s.push_str("1 ");
        mesh.write_bounds(s);
        s.push_str(" 0 0\n");
    }
    let top = if volumes == 1 { 3 } else { 2 };
    let _ = writeln!(s, "$EndEntities\n$Nodes\n1 {n} 1 {n}\n{top} 1 0 {n}");
    for i in 0..n {
        let _ = writeln!(s, "{}", i + 1);
    }
    for i in 0..n {
        mesh.write_node(s, i);
        s.push('\n');
    }
    fn of_block<'a>(mesh: &'a impl MshSource, b: &'a MshBlock) -> impl Iterator<Item = usize> + 'a {
        b.range.clone().filter(move |&e| mesh.element_type(e) == b.ty)
    }
    let total: usize = blocks.iter().map(|b| of_block(mesh, b).count()).sum();
    let _ = writeln!(s, "$EndNodes\n$Elements\n{} {total} 1 {total}", blocks.len());
    let mut tag = 0;
    for b in &blocks {
        let _ = writeln!(s, "{} 1 {} {}", b.dim, b.ty, of_block(mesh, b).count());
        for e in of_block(mesh, b) {
            tag += 1;
            let _ = write!(s, "{tag}");
            mesh.write_element_nodes(s, e);
            s.push('\n');
        }
    }
    s.push_str("$EndElements\n");
}

/// The fixed flags as a one-component `$NodeData` view named `"fixed"` (1 = fixed).
fn write_fixed_view(fixed: &[bool], s: &mut Out) {
    let _ = writeln!(s, "$NodeData\n1\n\"fixed\"\n1\n0\n3\n0\n1\n{}", fixed.len());
    for (i, &f) in fixed.iter().enumerate() {
        let _ = writeln!(s, "{} {}", i + 1, u8::from(f));
    }
    s.push_str("$EndNodeData\n");
}

/// A planar mesh or a surface: its elements in order, one block per run of equal kinds
/// (so 4.1 keeps the order), on one surface entity.
impl MshSource for super::super::Writable<'_> {
    fn node_count(&self) -> usize {
        self.mesh.node_count()
    }
    fn write_node(&self, s: &mut Out, i: usize) {
        self.write_xyz(s, i);
    }
    /// In 3D; a 2D mesh's z as `0`.
    fn write_bounds(&self, s: &mut Out) {
        let (lo, hi) = (0..self.mesh.node_count())
            .map(|i| self.xyz(i))
            .fold((glam::DVec3::splat(f64::INFINITY), glam::DVec3::splat(f64::NEG_INFINITY)), |(lo, hi), q| {
                (lo.min(q), hi.max(q))
            });
        let z = |v: f64| if self.in_xy_plane() { "0".to_string() } else { format!("{v:?}") };
        let _ = write!(s, "{:?} {:?} {} {:?} {:?} {}", lo.x, lo.y, z(lo.z), hi.x, hi.y, z(hi.z));
    }
    fn element_count(&self) -> usize {
        self.mesh.element_count()
    }
    fn element_type(&self, e: usize) -> u32 {
        type_of(self.mesh.kind(e))
    }
    fn write_element_nodes(&self, s: &mut Out, e: usize) {
        for &i in self.element(e).iter() {
            let _ = write!(s, " {}", i + 1);
        }
    }
    fn blocks(&self) -> Vec<MshBlock> {
        let kinds = self.mesh.kinds();
        runs(kinds).into_iter().map(|(a, b)| MshBlock { dim: 2, ty: type_of(kinds[a]), range: a..b }).collect()
    }
    fn fixed(&self) -> &[bool] {
        self.mesh.fixed()
    }
}

/// Maximal runs `[a, b)` of equal kinds.
pub(super) fn runs(kinds: &[ElementKind]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut a = 0;
    for i in 1..=kinds.len() {
        if i == kinds.len() || kinds[i] != kinds[a] {
            out.push((a, i));
            a = i;
        }
    }
    out
}

/// The Gmsh type of a planar element kind.
pub(crate) fn type_of(kind: ElementKind) -> u32 {
    match kind {
        ElementKind::Tri3 => 2,
        ElementKind::Quad4 => 3,
        ElementKind::Tri6 => 9,
        ElementKind::Quad8 => 16,
        ElementKind::Quad9 => 10,
    }
}
