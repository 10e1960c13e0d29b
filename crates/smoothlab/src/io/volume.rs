//! Writing volume meshes ([`crate::volume`]), element by element whatever their kinds:
//! Gmsh `.msh` 2.2 and 4.1 by the one writer per version (a [`VolumeMesh`] is an
//! [`MshSource`]), legacy VTK and TetGen's `.node`/`.ele` pair (tetrahedra only), the type
//! codes and node orders from the element kind's row ([`crate::mesh::VolumeKindRow`]), with
//! the fixed flags as the planar writers keep them (`.msh` and `.vtk`: a `fixed` view;
//! TetGen: boundary markers). The readers are the planar formats' own, which take volume
//! elements through the same rows ([`volume_codes`] lists them for their messages).
//! Node coordinates are written at full precision, so everything round-trips exactly.

use std::fmt::Write as _;

use crate::io::msh::{self, MshBlock, MshSource};
use crate::io::out::Out;
use crate::mesh::{VolumeKind, VolumeKindRow};
use crate::volume::VolumeMesh;

/// The most nodes a volume element of any kind has (the 27-node hexahedron's): the size
/// of the readers' buffer for one element's nodes.
pub(crate) const MAX_VOLUME_NODES: usize = {
    let mut most = 0;
    let mut i = 0;
    while i < VolumeKind::ALL.len() {
        if VolumeKind::ALL[i].nodes() > most {
            most = VolumeKind::ALL[i].nodes();
        }
        i += 1;
    }
    most
};

/// The type codes of every volume element kind in a format (`code` picks it from the
/// row), ascending, for the readers' messages: "10, 12, 13, 14, 24, 25, 29".
pub(crate) fn volume_codes(code: fn(&VolumeKindRow) -> u32) -> String {
    let mut codes: Vec<u32> = VolumeKind::ALL.iter().map(|k| code(k.row())).collect();
    codes.sort_unstable();
    codes.iter().map(u32::to_string).collect::<Vec<_>>().join(", ")
}

fn write_point(s: &mut Out, p: glam::DVec3) {
    let _ = write!(s, "{:?} {:?} {:?}", p.x, p.y, p.z);
}

/// A volume for the `.msh` writers: its elements (their Gmsh type and node order from
/// their kind's row), then the file's triangles and quads ([`VolumeMesh::faces`]), numbered
/// after them; in 4.1 the elements on one volume entity, the faces on one surface entity,
/// a block per face kind.
impl MshSource for VolumeMesh {
    fn node_count(&self) -> usize {
        VolumeMesh::node_count(self)
    }
    fn write_node(&self, s: &mut Out, i: usize) {
        write_point(s, self.nodes()[i]);
    }
    fn write_bounds(&self, s: &mut Out) {
        let (lo, hi) = self
            .nodes()
            .iter()
            .fold((glam::DVec3::splat(f64::INFINITY), glam::DVec3::splat(f64::NEG_INFINITY)), |(lo, hi), q| {
                (lo.min(*q), hi.max(*q))
            });
        write_point(s, lo);
        s.push(' ');
        write_point(s, hi);
    }
    fn element_count(&self) -> usize {
        VolumeMesh::element_count(self) + self.faces().len()
    }
    fn element_type(&self, e: usize) -> u32 {
        match e.checked_sub(VolumeMesh::element_count(self)) {
            None => self.element_kind(e).row().gmsh_type,
            Some(f) => msh::type_of(self.faces()[f].kind),
        }
    }
    fn write_element_nodes(&self, s: &mut Out, e: usize) {
        let ids = match e.checked_sub(VolumeMesh::element_count(self)) {
            None => {
                let ids = self.element(e);
                for &j in self.element_kind(e).row().gmsh_order {
                    let _ = write!(s, " {}", ids[j] + 1);
                }
                return;
            }
            Some(f) => self.faces()[f].nodes(),
        };
        for &i in ids {
            let _ = write!(s, " {}", i + 1);
        }
    }
    fn blocks(&self) -> Vec<MshBlock> {
        let m = VolumeMesh::element_count(self);
        let mut types: Vec<u32> = self.faces().iter().map(|f| msh::type_of(f.kind)).collect();
        types.sort_unstable();
        types.dedup();
        // a block per run of one kind, so a mixed mesh's elements keep their order
        let mut blocks: Vec<MshBlock> = Vec::new();
        for e in 0..m {
            let ty = self.element_kind(e).row().gmsh_type;
            match blocks.last_mut() {
                Some(b) if b.ty == ty => b.range.end = e + 1,
                _ => blocks.push(MshBlock { dim: 3, ty, range: e..e + 1 }),
            }
        }
        blocks.extend(types.into_iter().map(|ty| MshBlock { dim: 2, ty, range: m..m + self.faces().len() }));
        blocks
    }
    fn fixed(&self) -> &[bool] {
        VolumeMesh::fixed(self)
    }
}

/// A legacy VTK `UNSTRUCTURED_GRID` of the elements (each its kind's cell type, our node
/// order being VTK's), then the file's triangles and quads ([`VolumeMesh::faces`]).
pub(crate) fn write_vtk(mesh: &VolumeMesh, s: &mut Out) {
    let n = mesh.node_count();
    let m = mesh.element_count();
    let faces = mesh.faces();
    let face_size: usize = faces.iter().map(|f| f.nodes().len() + 1).sum();
    let size: usize = (0..m).map(|e| mesh.element(e).len() + 1).sum();
    let _ =
        write!(s, "# vtk DataFile Version 3.0\nsmoothlab mesh\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS {n} double\n");
    for p in mesh.nodes() {
        write_point(s, *p);
        s.push('\n');
    }
    let _ = writeln!(s, "CELLS {} {}", m + faces.len(), size + face_size);
    for e in 0..m {
        let _ = write!(s, "{}", mesh.element(e).len());
        for &i in mesh.element(e) {
            let _ = write!(s, " {i}");
        }
        s.push('\n');
    }
    for f in faces {
        let _ = write!(s, "{}", f.nodes().len());
        for &i in f.nodes() {
            let _ = write!(s, " {i}");
        }
        s.push('\n');
    }
    let _ = writeln!(s, "CELL_TYPES {}", m + faces.len());
    for e in 0..m {
        let _ = writeln!(s, "{}", mesh.element_kind(e).row().vtk_type);
    }
    for f in faces {
        let _ = writeln!(s, "{}", super::vtk::type_of(f.kind));
    }
    super::vtk::write_fixed(mesh.fixed(), s);
}

/// TetGen's `.node` (1-based, dimension 3, marker 1 on fixed nodes) and `.ele` texts (a
/// mesh of tetrahedra: [`super::write_tetgen`] refuses the other kinds).
pub(crate) fn write_tetgen(mesh: &VolumeMesh, node: &mut Out, ele: &mut Out) {
    let _ = writeln!(node, "{} 3 0 1", mesh.node_count());
    for (i, p) in mesh.nodes().iter().enumerate() {
        let _ = write!(node, "{} ", i + 1);
        write_point(node, *p);
        let _ = writeln!(node, " {}", u8::from(mesh.fixed()[i]));
    }
    let k = mesh.element(0).len();
    let _ = writeln!(ele, "{} {k} 0", mesh.element_count());
    for e in 0..mesh.element_count() {
        let _ = write!(ele, "{}", e + 1);
        for &i in mesh.element(e) {
            let _ = write!(ele, " {}", i + 1);
        }
        ele.push('\n');
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_readers_lists_of_codes_and_buffer_fit_every_kind() {
        assert_eq!(volume_codes(|r| r.vtk_type), "10, 12, 13, 14, 24, 25, 29");
        assert_eq!(volume_codes(|r| r.gmsh_type), "4, 5, 6, 7, 11, 12, 17");
        assert_eq!(MAX_VOLUME_NODES, 27);
    }
}
