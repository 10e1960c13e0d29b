//! A mesh as arrays, for a program that holds meshes as arrays (NumPy, meshio): the points
//! as the `.vtk` writer writes them (2 coordinates for a mesh in the xy plane, else 3: a
//! planar mesh read from 3D is given back in its own plane), the elements in their order
//! as runs of one VTK cell type (meshio's cell blocks), each element's nodes as the `.vtk`
//! writer writes them, and the fixed flags. What a `.vtk` file of the mesh holds, without
//! the text. [`model_from_arrays`] goes the other way: arrays in, the model a `.vtk` file
//! holding them reads as.

use super::Writable;
use crate::error::{Error, Result};
use crate::mesh::{FixedSpec, MeshBuilder, VolumeKind};
use crate::model::Model;
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

/// The model that a legacy `.vtk` file holding these arrays reads as (planar, surface or
/// volume): `dim` (2 or 3) coordinates a point in `points`, the cells as runs of one VTK
/// cell type, each cell's nodes in VTK's order (the inverse of [`mesh_arrays`] and
/// [`volume_arrays`]), and `fixed` one flag a point (`None`: the boundary and the points
/// of vertex and line cells, as a file without flags). The checks are the readers': an
/// error names the element by its place among all the cells (`element 3: …`) or the node.
///
/// ```
/// use smoothlab::io::{model_from_arrays, CellBlock};
/// use smoothlab::Model;
///
/// // four triangles round a free node
/// let points = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.8, 0.7];
/// let cells = [CellBlock { vtk_type: 5, per_cell: 3, nodes: vec![0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4] }];
/// let model = model_from_arrays(2, &points, &cells, None)?;
/// assert!(matches!(model, Model::Planar(_)));
/// assert_eq!(model.stats().free_nodes, 1);
/// # Ok::<(), smoothlab::Error>(())
/// ```
pub fn model_from_arrays(dim: usize, points: &[f64], cells: &[CellBlock], fixed: Option<&[bool]>) -> Result<Model> {
    if !(dim == 2 || dim == 3) {
        return Err(Error::invalid(format!("points have 2 or 3 coordinates, not {dim}")));
    }
    if points.len() % dim != 0 {
        return Err(Error::invalid(format!("{} coordinates do not make points of {dim}", points.len())));
    }
    let n = points.len() / dim;
    let mut builder = MeshBuilder::with_capacity(n, cells.iter().map(|b| b.nodes.len() / b.per_cell.max(1)).sum());
    for p in points.chunks_exact(dim) {
        builder.add_node([p[0], p[1], if dim == 3 { p[2] } else { 0.0 }], 0);
    }
    let mut marked: Option<Vec<bool>> = None;
    let mut element = 0;
    for b in cells {
        if b.per_cell == 0 || b.nodes.len() % b.per_cell != 0 {
            return Err(Error::invalid(format!(
                "a block of VTK cell type {} holds {} node numbers, not a whole number of cells of {}",
                b.vtk_type,
                b.nodes.len(),
                b.per_cell
            )));
        }
        let planar = super::vtk::planar_kind(b.vtk_type.into());
        let solid = VolumeKind::from_vtk_type(b.vtk_type.into());
        let wanted = match (planar, solid) {
            (Some(k), _) => Some(k.node_count()),
            (None, Some(k)) => Some(k.nodes()),
            _ => None,
        };
        if let Some(k) = wanted.filter(|&k| k != b.per_cell) {
            return Err(Error::element(
                element,
                None,
                format!("cell type {} needs {k} points, but the cell lists {}", b.vtk_type, b.per_cell),
            ));
        }
        for cell in b.nodes.chunks_exact(b.per_cell) {
            if let Some(&v) = cell.iter().find(|&&v| v as usize >= n) {
                return Err(Error::element(
                    element,
                    None,
                    format!("point index {v} is out of range: there are {n} points (0 to {})", n.saturating_sub(1)),
                ));
            }
            match (planar, solid) {
                (Some(kind), _) => builder.add_element(kind, cell, 0),
                (None, Some(kind)) => builder.add_volume_element(kind, cell, 0)?,
                _ if super::vtk::is_marker(b.vtk_type.into()) => {
                    let m = marked.get_or_insert_with(|| vec![false; n]);
                    for &v in cell {
                        m[v as usize] = true;
                    }
                }
                _ => {
                    return Err(Error::unsupported(
                        None,
                        format!(
                            "VTK cell type {} of element {element} is not supported: smoothlab reads types 5, 9, 22, 23, \
                             28, the volume elements {} and the vertex and line cells 1, 2, 3, 4, 21",
                            b.vtk_type,
                            super::volume::volume_codes(|r| r.vtk_type)
                        ),
                    ))
                }
            }
            element += 1;
        }
    }
    builder.fixed = match (fixed, marked) {
        (Some(f), _) if f.len() != n => {
            return Err(Error::invalid(format!("{} fixed flags for {n} points: give one a point", f.len())))
        }
        (Some(f), _) => FixedSpec::Exact(f.to_vec()),
        (None, Some(m)) => FixedSpec::BoundaryAnd(m),
        (None, None) => FixedSpec::Boundary,
    };
    Model::build(builder)
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

    /// Arrays in give the model their `.vtk` text reads as: the same text written back.
    #[test]
    fn arrays_back_in_give_what_their_vtk_text_reads_as() {
        use crate::generate::{mixed_block, perturb_surface, surface, HexBlock, SurfaceKind, SurfaceShape};
        let torus = surface(SurfaceShape::Torus, SurfaceKind::Mixed, 1, 2).unwrap();
        let models = [
            Model::Surface(perturb_surface(&torus, 0.3, 1).unwrap()),
            Model::Volume(mixed_block(&HexBlock::cube(3)).unwrap()),
            read_model_str(
                "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 5 double\n\
                 0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.8 0.7 0\nCELLS 4 16\n3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\n\
                 CELL_TYPES 4\n5\n5\n5\n5\n",
                Format::Vtk,
            )
            .unwrap(),
        ];
        for model in models {
            let a = match &model {
                Model::Planar(m) => mesh_arrays(m),
                Model::Surface(s) => mesh_arrays(s),
                Model::Volume(v) => volume_arrays(v),
            };
            let back = model_from_arrays(a.dim, &a.points, &a.cells, Some(&a.fixed)).unwrap();
            let text = |m: &Model| write_model_string(m, Format::Vtk, &WriteOptions::default()).unwrap();
            assert_eq!(text(&back), text(&model));
        }
    }

    #[test]
    fn bad_arrays_are_refused_naming_the_element() {
        let points = [0.0, 0.0, 1.0, 0.0, 0.0, 1.0];
        let tri = |nodes: Vec<u32>| CellBlock { vtk_type: 5, per_cell: 3, nodes };
        let err = |cells: &[CellBlock], fixed: Option<&[bool]>| model_from_arrays(2, &points, cells, fixed).unwrap_err().to_string();
        assert_eq!(err(&[tri(vec![0, 1, 2, 0, 1, 7])], None), "element 1: point index 7 is out of range: there are 3 points (0 to 2)");
        assert!(err(&[tri(vec![0, 1, 1])], None).starts_with("element 0: "));
        assert!(err(&[CellBlock { vtk_type: 7, per_cell: 3, nodes: vec![0, 1, 2] }], None).contains("VTK cell type 7 of element 0"));
        assert!(err(&[CellBlock { vtk_type: 9, per_cell: 3, nodes: vec![0, 1, 2] }], None).contains("needs 4 points"));
        assert_eq!(err(&[tri(vec![0, 1, 2])], Some(&[true])), "1 fixed flags for 3 points: give one a point");
        assert!(model_from_arrays(4, &points, &[], None).is_err());
        assert!(model_from_arrays(2, &points[..5], &[], None).is_err());
    }
}
