//! Writing tetrahedral meshes ([`crate::volume`]): Gmsh `.msh` 2.2 and 4.1 (types 4 and
//! 11), legacy VTK (cell types 10 and 24) and TetGen's `.node`/`.ele` pair, with the
//! fixed flags as the planar writers keep them (`.msh` and `.vtk`: a `fixed` view; TetGen:
//! boundary markers). The readers are the planar formats' own, which take tetrahedra.
//! Node coordinates are written at full precision, so everything round-trips exactly.

use std::fmt::Write as _;

use crate::io::out::Out;
use crate::io::MshVersion;
use crate::volume::TetMesh;

/// Gmsh's node order of a 10-node tetrahedron from ours (VTK's): Gmsh's last two
/// mid-edge nodes are on edges (3,2) and (3,1), ours on (1,3) and (2,3).
const GMSH_TET10: [usize; 10] = [0, 1, 2, 3, 4, 5, 6, 7, 9, 8];

fn write_point(s: &mut Out, p: glam::DVec3) {
    let _ = write!(s, "{:?} {:?} {:?}", p.x, p.y, p.z);
}

/// A `.msh` text of the tetrahedra (one volume entity in 4.1).
///
/// The file's triangles and quads ([`TetMesh::faces`]) follow the tetrahedra (in 4.1 on
/// one surface entity per kind), numbered after them.
pub(crate) fn write_msh(mesh: &TetMesh, version: MshVersion, s: &mut Out) {
    let n = mesh.node_count();
    let m = mesh.element_count();
    let faces = mesh.faces();
    let face = |s: &mut Out, f: &crate::volume::GivenFace| {
        for &i in f.nodes() {
            let _ = write!(s, " {}", i + 1);
        }
        s.push('\n');
    };
    let (ty, k) = if mesh.is_quadratic() { (11, 10) } else { (4, 4) };
    let element = |s: &mut Out, e: usize| {
        let ids = mesh.element(e);
        for &j in &GMSH_TET10[..k] {
            let _ = write!(s, " {}", ids[j] + 1);
        }
        s.push('\n');
    };
    let v = match version {
        MshVersion::V22 => "2.2",
        MshVersion::V41 => "4.1",
    };
    let _ = write!(s, "$MeshFormat\n{v} 0 8\n$EndMeshFormat\n");
    match version {
        MshVersion::V22 => {
            let _ = writeln!(s, "$Nodes\n{n}");
            for (i, p) in mesh.nodes().iter().enumerate() {
                let _ = write!(s, "{} ", i + 1);
                write_point(s, *p);
                s.push('\n');
            }
            let _ = writeln!(s, "$EndNodes\n$Elements\n{}", m + faces.len());
            for e in 0..m {
                let _ = write!(s, "{} {ty} 2 0 1", e + 1);
                element(s, e);
            }
            for (j, f) in faces.iter().enumerate() {
                let _ = write!(s, "{} {} 2 0 1", m + j + 1, super::msh::type_of(f.kind));
                face(s, f);
            }
        }
        MshVersion::V41 => {
            let (lo, hi) = mesh
                .nodes()
                .iter()
                .fold((glam::DVec3::splat(f64::INFINITY), glam::DVec3::splat(f64::NEG_INFINITY)), |(lo, hi), q| {
                    (lo.min(*q), hi.max(*q))
                });
            // the faces' kinds, each a block on the one surface entity
            let mut kinds: Vec<crate::mesh::ElementKind> = faces.iter().map(|f| f.kind).collect();
            kinds.sort_by_key(|&k| super::msh::type_of(k));
            kinds.dedup();
            let surfaces = usize::from(!faces.is_empty());
            let _ = write!(s, "$Entities\n0 0 {surfaces} 1\n");
            if surfaces == 1 {
                s.push_str("1 ");
                write_point(s, lo);
                s.push(' ');
                write_point(s, hi);
                s.push_str(" 0 0\n");
            }
            s.push_str("1 ");
            write_point(s, lo);
            s.push(' ');
            write_point(s, hi);
            let _ = writeln!(s, " 0 0\n$EndEntities\n$Nodes\n1 {n} 1 {n}\n3 1 0 {n}");
            for i in 0..n {
                let _ = writeln!(s, "{}", i + 1);
            }
            for p in mesh.nodes() {
                write_point(s, *p);
                s.push('\n');
            }
            let total = m + faces.len();
            let _ = writeln!(s, "$EndNodes\n$Elements\n{} {total} 1 {total}\n3 1 {ty} {m}", 1 + kinds.len());
            for e in 0..m {
                let _ = write!(s, "{}", e + 1);
                element(s, e);
            }
            let mut next = m;
            for &kind in &kinds {
                let of_kind = faces.iter().filter(|f| f.kind == kind);
                let _ = writeln!(s, "2 1 {} {}", super::msh::type_of(kind), of_kind.clone().count());
                for f in of_kind {
                    next += 1;
                    let _ = write!(s, "{next}");
                    face(s, f);
                }
            }
        }
    }
    s.push_str("$EndElements\n");
    super::msh::write_fixed_view(mesh.fixed(), s);
}

/// A legacy VTK `UNSTRUCTURED_GRID` of the tetrahedra (cell type 10 or 24), then the
/// file's triangles and quads ([`TetMesh::faces`]).
pub(crate) fn write_vtk(mesh: &TetMesh, s: &mut Out) {
    let n = mesh.node_count();
    let m = mesh.element_count();
    let faces = mesh.faces();
    let face_size: usize = faces.iter().map(|f| f.nodes().len() + 1).sum();
    let (ty, k) = if mesh.is_quadratic() { (24, 10) } else { (10, 4) };
    let _ =
        write!(s, "# vtk DataFile Version 3.0\nsmoothlab mesh\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS {n} double\n");
    for p in mesh.nodes() {
        write_point(s, *p);
        s.push('\n');
    }
    let _ = writeln!(s, "CELLS {} {}", m + faces.len(), m * (k + 1) + face_size);
    for e in 0..m {
        let _ = write!(s, "{k}");
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
    for _ in 0..m {
        let _ = writeln!(s, "{ty}");
    }
    for f in faces {
        let _ = writeln!(s, "{}", super::vtk::type_of(f.kind));
    }
    super::vtk::write_fixed(mesh.fixed(), s);
}

/// TetGen's `.node` (1-based, dimension 3, marker 1 on fixed nodes) and `.ele` texts.
pub(crate) fn write_tetgen(mesh: &TetMesh, node: &mut Out, ele: &mut Out) {
    let _ = writeln!(node, "{} 3 0 1", mesh.node_count());
    for (i, p) in mesh.nodes().iter().enumerate() {
        let _ = write!(node, "{} ", i + 1);
        write_point(node, *p);
        let _ = writeln!(node, " {}", u8::from(mesh.fixed()[i]));
    }
    let k = if mesh.is_quadratic() { 10 } else { 4 };
    let _ = writeln!(ele, "{} {k} 0", mesh.element_count());
    for e in 0..mesh.element_count() {
        let _ = write!(ele, "{}", e + 1);
        for &i in mesh.element(e) {
            let _ = write!(ele, " {}", i + 1);
        }
        ele.push('\n');
    }
}
