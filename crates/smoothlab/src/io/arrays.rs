//! A mesh as arrays, for a program that holds meshes as arrays (NumPy, meshio): the points
//! as the `.vtk` writer writes them (2 coordinates for a mesh in the xy plane, else 3: a
//! planar mesh read from 3D is given back in its own plane), the elements in their order
//! as runs of one VTK cell type (meshio's cell blocks), each element's nodes as the `.vtk`
//! writer writes them, and the fixed flags. What a `.vtk` file of the mesh holds, without
//! the text.

use super::Writable;
use crate::volume::VolumeMesh;

/// A run of elements of one VTK cell type: `nodes` holds `per_cell` node numbers a cell.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CellBlock {
    pub vtk_type: u32,
    pub per_cell: usize,
    pub nodes: Vec<u32>,
}

/// A mesh as arrays (see the module's docs).
#[derive(Clone, Debug, PartialEq)]
pub struct MeshArrays {
    /// Coordinates a point: 2 or 3.
    pub dim: usize,
    /// `dim` coordinates a point, point after point.
    pub points: Vec<f64>,
    pub cells: Vec<CellBlock>,
    pub fixed: Vec<bool>,
}

impl MeshArrays {
    /// Appends one cell, starting a new block when its type differs from the last one's.
    fn push(&mut self, vtk_type: u32, nodes: &[u32]) {
        match self.cells.last_mut() {
            Some(b) if b.vtk_type == vtk_type => b.nodes.extend_from_slice(nodes),
            _ => self.cells.push(CellBlock { vtk_type, per_cell: nodes.len(), nodes: nodes.to_vec() }),
        }
    }
}

/// A planar mesh or a surface as arrays: what the `.vtk` writer (`io::vtk::write`) writes of it.
pub fn mesh_arrays<'a>(w: impl Into<Writable<'a>>) -> MeshArrays {
    let w = w.into();
    let mesh = w.mesh;
    let n = mesh.node_count();
    let flat = w.in_xy_plane();
    let dim = if flat { 2 } else { 3 };
    let mut points = Vec::with_capacity(dim * n);
    for i in 0..n {
        if flat {
            let p = mesh.nodes()[i];
            points.extend([p.x, p.y]);
        } else {
            let q = w.xyz(i);
            points.extend([q.x, q.y, q.z]);
        }
    }
    let mut out = MeshArrays { dim, points, cells: Vec::new(), fixed: mesh.fixed().to_vec() };
    for (e, &k) in mesh.kinds().iter().enumerate() {
        out.push(super::vtk::type_of(k), &w.element(e));
    }
    out
}

/// A volume mesh as arrays: what the `.vtk` writer (`io::volume::write_vtk`) writes of it (the elements,
/// then the file's boundary faces).
pub fn volume_arrays(mesh: &VolumeMesh) -> MeshArrays {
    let points = mesh.nodes().iter().flat_map(|p| [p.x, p.y, p.z]).collect();
    let mut out = MeshArrays { dim: 3, points, cells: Vec::new(), fixed: mesh.fixed().to_vec() };
    for e in 0..mesh.element_count() {
        out.push(mesh.element_kind(e).row().vtk_type, mesh.element(e));
    }
    for f in mesh.faces() {
        out.push(super::vtk::type_of(f.kind), f.nodes());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::{read_model_str, write_model_string, Format, WriteOptions};
    use crate::model::Model;

    /// The arrays hold what the `.vtk` text of the same mesh holds: its points, its cells
    /// with their types, and its fixed flags, read back from the text by hand.
    fn same_as_vtk(model: &Model, arrays: &MeshArrays) {
        let text = write_model_string(model, Format::Vtk, &WriteOptions::default()).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        let at = |key: &str| lines.iter().position(|l| l.starts_with(key)).unwrap();
        let n = arrays.fixed.len();
        let p0 = at("POINTS") + 1;
        let mut points = Vec::new();
        for l in &lines[p0..p0 + n] {
            let xyz: Vec<f64> = l.split(' ').map(|t| t.parse().unwrap()).collect();
            points.extend_from_slice(&xyz[..arrays.dim]);
            if arrays.dim == 2 {
                assert_eq!(xyz[2], 0.0);
            }
        }
        assert_eq!(points, arrays.points);
        let c0 = at("CELLS") + 1;
        let t0 = at("CELL_TYPES") + 1;
        let cells: Vec<(u32, Vec<u32>)> = (0..t0 - 1 - c0)
            .map(|i| {
                let ids: Vec<u32> = lines[c0 + i].split(' ').skip(1).map(|t| t.parse().unwrap()).collect();
                (lines[t0 + i].parse().unwrap(), ids)
            })
            .collect();
        let mine: Vec<(u32, Vec<u32>)> = arrays
            .cells
            .iter()
            .flat_map(|b| b.nodes.chunks(b.per_cell).map(move |c| (b.vtk_type, c.to_vec())))
            .collect();
        assert_eq!(mine, cells);
        let f0 = at("LOOKUP_TABLE") + 1;
        let fixed: Vec<bool> = lines[f0..f0 + n].iter().map(|l| *l == "1").collect();
        assert_eq!(fixed, arrays.fixed);
    }

    #[test]
    fn a_planar_mesh_gives_two_coordinates_and_runs_of_one_kind() {
        // two triangles, a quad, a triangle: three blocks, in the file's order
        let vtk = "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 7 double\n\
                   0 0 0\n1 0 0\n2 0 0\n0 1 0\n1 1 0\n2 1 0\n1 2 0\n\
                   CELLS 4 17\n3 0 1 4\n3 0 4 3\n4 1 2 5 4\n3 3 4 6\nCELL_TYPES 4\n5\n5\n9\n5\n";
        let model = read_model_str(vtk, Format::Vtk).unwrap();
        let Model::Planar(m) = &model else { panic!("planar") };
        let a = mesh_arrays(m);
        assert_eq!(a.dim, 2);
        assert_eq!(a.points.len(), 14);
        let kinds: Vec<(u32, usize, usize)> = a.cells.iter().map(|b| (b.vtk_type, b.per_cell, b.nodes.len())).collect();
        assert_eq!(kinds, [(5, 3, 6), (9, 4, 4), (5, 3, 3)]);
        assert_eq!(a.cells[0].nodes, [0, 1, 4, 0, 4, 3]);
        // every node is on the boundary of this fan, so every node is fixed
        assert!(a.fixed.iter().all(|&f| f));
        same_as_vtk(&model, &a);
    }

    #[test]
    fn a_planar_mesh_read_from_3d_is_given_back_in_its_plane() {
        let vtk = "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n\
                   0 0 1\n1 0 1\n1 1 1\n0 1 1\nCELLS 2 8\n3 0 1 2\n3 0 2 3\nCELL_TYPES 2\n5\n5\n";
        let model = read_model_str(vtk, Format::Vtk).unwrap();
        let Model::Planar(m) = &model else { panic!("planar") };
        let a = mesh_arrays(m);
        assert_eq!(a.dim, 3);
        assert_eq!(a.points, [0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 1.0, 1.0, 1.0, 0.0, 1.0, 1.0]);
        same_as_vtk(&model, &a);
    }

    #[test]
    fn surfaces_and_volumes_give_what_their_vtk_text_holds() {
        use crate::generate::{mixed_block, perturb_surface, perturb_volume, surface, HexBlock, SurfaceKind, SurfaceShape};
        let torus = surface(SurfaceShape::Torus, SurfaceKind::Mixed, 1, 2).unwrap();
        let model = Model::Surface(perturb_surface(&torus, 0.3, 1).unwrap());
        let Model::Surface(sf) = &model else { panic!("a surface") };
        let a = mesh_arrays(sf);
        assert_eq!(a.dim, 3);
        // a torus of quads and triangles: more than one block
        assert!(a.cells.iter().any(|b| b.vtk_type == 5) && a.cells.iter().any(|b| b.vtk_type == 9));
        same_as_vtk(&model, &a);
        let block = mixed_block(&HexBlock::cube(4)).unwrap();
        let model = Model::Volume(perturb_volume(&block, 0.3, 1).unwrap());
        let Model::Volume(v) = &model else { panic!("a volume") };
        let a = volume_arrays(v);
        let types: std::collections::BTreeSet<u32> = a.cells.iter().map(|b| b.vtk_type).collect();
        assert!([10, 12, 13, 14].iter().all(|t| types.contains(t)), "{types:?}");
        same_as_vtk(&model, &a);
    }
}
