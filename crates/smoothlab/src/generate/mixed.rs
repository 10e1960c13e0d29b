//! A conforming mesh of every linear volume kind: a block of hexahedra ([`HexBlock`]) with
//! one column of cells cut into wedges and one row of cells cut into pyramids and
//! tetrahedra. What makes it conform:
//!
//! - **the wedge column** (the cells at `i = nx/2`, `j = ny/2`, every `k`): each cell is
//!   cut along the diagonal of its bottom and top faces from corner `(i, j)` to
//!   `(i + 1, j + 1)` into two wedges. The diagonal is the same all the way up, so the
//!   triangles of one cell's top are those of the next cell's bottom; the wedges' other
//!   faces are the cell's own quads, which its neighbours share;
//! - **the pyramid row** (the cells along the bottom front edge, `j = 0`, `k = 0`): each
//!   cell gets a node at the mean of its corners and is cut into the six pyramids from
//!   its faces to that node. A pyramid whose base is a face inside the block keeps it, a
//!   quad its neighbour (a hexahedron, a wedge's side or another pyramid's base) shares;
//!   one whose base is on the block's boundary is cut into two tetrahedra along a
//!   diagonal of that base, which no other element has.
//!
//! So every face inside the block is a face of two elements and the boundary is the
//! block's surface: its quads, but the two ends of the wedge column and the pyramid
//! row's boundary faces, each two triangles.

use glam::DVec3;

use super::hexgrid::{check_mixed, HexBlock};
use crate::error::Result;
use crate::mesh::VolumeKind;
use crate::volume::VolumeMesh;

/// The way out of each face of a hexahedron, in the lattice (`di`, `dj`, `dk`), in the
/// order of the 8-node hexahedron's faces (its row's `faces`: bottom, top, front `j`,
/// right `i + 1`, back `j + 1`, left `i`).
const FACE_OUT: [[i64; 3]; 6] = [[0, 0, -1], [0, 0, 1], [0, -1, 0], [1, 0, 0], [0, 1, 0], [-1, 0, 0]];

/// The cell whose hexahedron is cut into two wedges on each layer: `(nx/2, ny/2)`.
fn wedge_column(b: &HexBlock) -> (usize, usize) {
    (b.cells[0] / 2, b.cells[1] / 2)
}

/// Whether cell `(i, j, k)` is cut into pyramids: the row along the bottom front edge.
fn in_pyramid_row(j: usize, k: usize) -> bool {
    j == 0 && k == 0
}

/// The block as hexahedra, wedges, pyramids and tetrahedra in one conforming mesh (see the
/// module docs); boundary nodes fixed, every element valid. At least 2 cells along each
/// axis (so the wedge column and the pyramid row are apart).
pub fn mixed_block(block: &HexBlock) -> Result<VolumeMesh> {
    check_mixed(block)?;
    let mut nodes = block.nodes();
    let (iw, jw) = wedge_column(block);
    let mut elements: Vec<(VolumeKind, Vec<u32>)> = Vec::new();
    let faces = VolumeKind::Hex8.row().faces;
    for (i, j, k) in block.cells() {
        let h = block.cell(i, j, k);
        if (i, j) == (iw, jw) {
            // bottom a b c d anticlockwise seen from above, diagonal a–c; a wedge's first
            // triangle turns clockwise seen from its second (the row's order)
            let [a, b, c, d, a1, b1, c1, d1] = h;
            elements.push((VolumeKind::Wedge6, vec![a, c, b, a1, c1, b1]));
            elements.push((VolumeKind::Wedge6, vec![a, d, c, a1, d1, c1]));
        } else if in_pyramid_row(j, k) {
            let centre = h.iter().map(|&n| nodes[n as usize]).sum::<DVec3>() / 8.0;
            nodes.push(centre);
            let apex = (nodes.len() - 1) as u32;
            for (face, out) in faces.iter().zip(FACE_OUT) {
                // the face turns outward: reversed, it turns anticlockwise seen from the
                // centre, as a pyramid's base seen from its apex
                let base: Vec<u32> = face.iter().rev().map(|&c| h[c]).collect();
                let next = [i as i64 + out[0], j as i64 + out[1], k as i64 + out[2]];
                let outside = next.iter().zip(block.cells).any(|(&x, n)| x < 0 || x >= n as i64);
                if outside {
                    elements.push((VolumeKind::Tet4, vec![base[0], base[1], base[2], apex]));
                    elements.push((VolumeKind::Tet4, vec![base[0], base[2], base[3], apex]));
                } else {
                    elements.push((VolumeKind::Pyramid5, vec![base[0], base[1], base[2], base[3], apex]));
                }
            }
        } else {
            elements.push((VolumeKind::Hex8, h.to_vec()));
        }
    }
    VolumeMesh::from_elements(nodes, elements.iter().map(|(k, ids)| (*k, &ids[..])))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::test_util::assert_volume_valid as assert_valid;
    use proptest::prelude::*;

    fn count(m: &VolumeMesh, kind: VolumeKind) -> usize {
        (0..m.element_count()).filter(|&e| m.element_kind(e) == kind).count()
    }

    /// The area of a boundary face (a planar triangle or quad).
    fn area(m: &VolumeMesh, f: &crate::volume::Face) -> f64 {
        let p = |i: u32| m.nodes()[i as usize];
        f.triangles().map(|[a, b, c]| 0.5 * (p(b) - p(a)).cross(p(c) - p(a)).length()).sum()
    }

    #[test]
    fn face_out_points_out_of_each_face_of_the_row() {
        let row = VolumeKind::Hex8.row();
        for (face, out) in row.faces.iter().zip(FACE_OUT) {
            let mid = face.iter().map(|&c| DVec3::from(row.ideal[c])).sum::<DVec3>() / face.len() as f64;
            let dir = DVec3::new(out[0] as f64, out[1] as f64, out[2] as f64);
            assert_eq!((mid - DVec3::splat(0.5)) * 2.0, dir, "{face:?}");
        }
    }

    #[test]
    fn three_cubed_counted_by_hand() {
        // 27 cells: the wedge column (1, 1, k) is 3 cells of 2 wedges; the pyramid row
        // (i, 0, 0) 3 cells, with 2 boundary faces each (bottom and front) and one more at
        // each end (left, right): 8 bases cut into 16 tetrahedra, 18 − 8 = 10 pyramids
        let m = mixed_block(&HexBlock::cube(3)).unwrap();
        let counts = VolumeKind::ALL.map(|k| count(&m, k));
        assert_eq!(counts[VolumeKind::ALL.iter().position(|&k| k == VolumeKind::Hex8).unwrap()], 21);
        assert_eq!(count(&m, VolumeKind::Wedge6), 6);
        assert_eq!(count(&m, VolumeKind::Pyramid5), 10);
        assert_eq!(count(&m, VolumeKind::Tet4), 16);
        assert_eq!(m.element_count(), 21 + 6 + 10 + 16);
        assert_eq!(m.kinds(), &[VolumeKind::Tet4, VolumeKind::Hex8, VolumeKind::Wedge6, VolumeKind::Pyramid5]);
        // 4³ lattice nodes and 3 centres; the inner lattice nodes and the centres are free
        assert_eq!(m.node_count(), 67);
        assert_eq!(m.free_count(), 8 + 3);
        assert_valid(&m);
        // the surface: 54 quads, but the wedge column's two ends (2 triangles each) and
        // the pyramid row's 8 boundary faces (2 triangles each)
        let b = m.boundary_faces();
        let tris = b.iter().filter(|f| f.nodes().len() == 3).count();
        let quads = b.len() - tris;
        assert_eq!((quads, tris), (54 - 2 - 8, 2 * (2 + 8)));
        let total: f64 = b.iter().map(|f| area(&m, f)).sum();
        assert!((total - 6.0).abs() < 1e-12, "the boundary is the cube's surface: {total}");
        assert_eq!(m.family_words(), "tetrahedra, hexahedra, wedges and pyramids");
    }

    #[test]
    fn every_inner_face_is_shared_by_two_elements() {
        // faces of the elements: each inner one twice, each boundary one once
        let m = mixed_block(&HexBlock { cells: [4, 3, 2], ..HexBlock::default() }).unwrap();
        let mut seen = std::collections::HashMap::new();
        for e in 0..m.element_count() {
            let ids = m.element(e);
            for f in m.element_kind(e).row().faces {
                let mut key: Vec<u32> = f.iter().map(|&c| ids[c]).collect();
                key.sort_unstable();
                *seen.entry(key).or_insert(0) += 1;
            }
        }
        let once = seen.values().filter(|&&n| n == 1).count();
        assert!(seen.values().all(|&n| n == 1 || n == 2));
        assert_eq!(once, m.boundary_faces().len());
        // the block's surface 2(12 + 6 + 8) = 52 quads; the wedge column's ends and the
        // pyramid row's 2·4 + 2 boundary faces in two triangles each
        assert_eq!(once, 52 + 2 + 10);
    }

    #[test]
    fn too_few_cells_are_refused() {
        let e = mixed_block(&HexBlock { cells: [2, 1, 2], ..HexBlock::default() }).unwrap_err().to_string();
        assert!(e.contains("a mixed block: 1 cells along y: give 2 to 200"), "{e}");
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(16))]
        #[test]
        fn every_block_and_bend_is_valid_and_has_every_kind(nx in 2usize..5, ny in 2usize..4, nz in 2usize..4,
                                                            bend in 0.0f64..270.0) {
            let m = mixed_block(&HexBlock { cells: [nx, ny, nz], size: DVec3::ONE, bend }).unwrap();
            assert_valid(&m);
            prop_assert_eq!(m.kinds().len(), 4);
            prop_assert_eq!(count(&m, VolumeKind::Wedge6), 2 * nz);
            prop_assert_eq!(count(&m, VolumeKind::Tet4), 2 * (2 * nx + 2));
            prop_assert_eq!(count(&m, VolumeKind::Pyramid5), 6 * nx - (2 * nx + 2));
            let tris = m.boundary_faces().iter().filter(|f| f.nodes().len() == 3).count();
            prop_assert_eq!(m.boundary_faces().len() - tris / 2, 2 * (nx * ny + ny * nz + nx * nz));
        }
    }
}
