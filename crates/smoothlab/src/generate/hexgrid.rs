//! A structured block of trilinear hexahedra, straight or bent like a curved beam: the
//! hexahedral test grid Knupp (1999) tangles by moving its interior nodes at random
//! ([`perturb_volume`](super::perturb_volume)), and the lattice the mixed sample
//! ([`mixed_block`](super::mixed_block)) is cut from.
//!
//! **The bend.** The straight block is `[0, Lx] × [0, Ly] × [0, Lz]`. Bent by the angle θ
//! (radians, `bend` degrees) it is curved about the axis parallel to y through
//! `(0, ·, −R)`, `R = Lx/θ`: the point `(x, y, z)` goes to
//!
//! ```text
//! ((R + z)·sin φ,  y,  (R + z)·cos φ − R),   φ = x/R,
//! ```
//!
//! so the bottom face `z = 0` keeps its length `Lx` along an arc of radius `R` and angle
//! θ, each line across the block (x and y fixed) stays straight and of length `Lz`, and
//! y is untouched. The map's Jacobian determinant is `(R + z)/R > 0`, and a cell spanning
//! the angle `θ/nx < 180°` has its corners on a convex trapezoid prism, so every
//! hexahedron stays valid (at θ → 0 the map tends to the identity; θ = 0 is the straight
//! block itself).

use glam::DVec3;

use super::check_size;
use crate::numeric::trig::sin_cos;
use crate::error::{Error, Result};
use crate::mesh::VolumeKind;
use crate::volume::VolumeMesh;

/// The most cells along one side of a block.
pub const MAX_BLOCK_CELLS: usize = 200;
/// The largest bend, degrees: three quarters of a ring.
pub const MAX_BEND_DEG: f64 = 270.0;

/// A block of `cells[0] × cells[1] × cells[2]` hexahedral cells of total size `size`,
/// bent by `bend` degrees (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HexBlock {
    pub cells: [usize; 3],
    pub size: DVec3,
    /// Degrees, 0 to [`MAX_BEND_DEG`]: 0 is straight.
    pub bend: f64,
}

impl Default for HexBlock {
    /// The unit cube in 8 × 8 × 8 cells, straight.
    fn default() -> Self {
        HexBlock { cells: [8; 3], size: DVec3::ONE, bend: 0.0 }
    }
}

impl HexBlock {
    /// The unit cube in `n × n × n` cells, straight.
    pub fn cube(n: usize) -> Self {
        HexBlock { cells: [n; 3], ..HexBlock::default() }
    }

    /// The same block bent by `bend` degrees.
    pub fn bent(self, bend: f64) -> Self {
        HexBlock { bend, ..self }
    }

    /// Checks the block, saying what is wrong: cells from 1 to [`MAX_BLOCK_CELLS`] a side
    /// (at least `min_cells`), a finite positive size, a bend of 0 to [`MAX_BEND_DEG`]
    /// degrees with less than 180° a cell, and nodes within [`super::MAX_GENERATED_NODES`].
    fn check(&self, what: &str, min_cells: usize) -> Result<()> {
        for (axis, &n) in ["x", "y", "z"].iter().zip(&self.cells) {
            if !(min_cells..=MAX_BLOCK_CELLS).contains(&n) {
                return Err(Error::invalid(format!(
                    "{what}: {n} cells along {axis}: give {min_cells} to {MAX_BLOCK_CELLS}"
                )));
            }
        }
        if !(self.size.is_finite() && self.size.min_element() > 0.0) {
            return Err(Error::invalid(format!("{what}: size {} must be three finite numbers > 0", self.size)));
        }
        if !(0.0..=MAX_BEND_DEG).contains(&self.bend) {
            return Err(Error::invalid(format!("{what}: a bend of {}°: give 0 to {MAX_BEND_DEG}", self.bend)));
        }
        if self.bend / self.cells[0] as f64 >= 180.0 {
            return Err(Error::invalid(format!(
                "{what}: a bend of {}° over {} cell(s) along x turns a cell by 180° or more, which folds it: give more cells along x",
                self.bend, self.cells[0]
            )));
        }
        let [a, b, c] = self.cells.map(|n| n + 1);
        check_size(what, a.checked_mul(b).and_then(|ab| ab.checked_mul(c)))
    }

    /// The point `p` of the straight block `[0, Lx] × [0, Ly] × [0, Lz]` on the bent one.
    pub fn map(&self, p: DVec3) -> DVec3 {
        if self.bend == 0.0 {
            return p;
        }
        let r = self.size.x / self.bend.to_radians();
        let (s, c) = sin_cos(p.x / r);
        DVec3::new((r + p.z) * s, p.y, (r + p.z) * c - r)
    }

    /// Nodes along each axis.
    fn points(&self) -> [usize; 3] {
        self.cells.map(|n| n + 1)
    }

    /// The id of lattice node `(i, j, k)`: x fastest, then y, then z.
    pub(super) fn id(&self, i: usize, j: usize, k: usize) -> u32 {
        let [a, b, _] = self.points();
        (i + a * (j + b * k)) as u32
    }

    /// The point of the straight block at fractional lattice coordinates `(i, j, k)`.
    fn straight(&self, i: f64, j: f64, k: f64) -> DVec3 {
        let [nx, ny, nz] = self.cells.map(|n| n as f64);
        DVec3::new(i / nx * self.size.x, j / ny * self.size.y, k / nz * self.size.z)
    }

    /// The lattice's nodes, bent, in [`id`](Self::id)'s order.
    pub(super) fn nodes(&self) -> Vec<DVec3> {
        let [a, b, c] = self.points();
        let mut out = Vec::with_capacity(a * b * c);
        for k in 0..c {
            for j in 0..b {
                for i in 0..a {
                    out.push(self.map(self.straight(i as f64, j as f64, k as f64)));
                }
            }
        }
        out
    }

    /// The corners of cell `(i, j, k)` in the hexahedron's order (the bottom `k` anticlockwise
    /// seen from the top `k + 1`, VTK's): right-handed, as the row's ideal cube.
    pub(super) fn cell(&self, i: usize, j: usize, k: usize) -> [u32; 8] {
        let bottom = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)];
        std::array::from_fn(|c| {
            let (a, b) = bottom[c % 4];
            self.id(a, b, k + c / 4)
        })
    }

    /// Every cell, z slowest, then y, x fastest.
    pub(super) fn cells(&self) -> impl Iterator<Item = (usize, usize, usize)> {
        let [nx, ny, nz] = self.cells;
        (0..nz).flat_map(move |k| (0..ny).flat_map(move |j| (0..nx).map(move |i| (i, j, k))))
    }
}

/// The block in `cells[0] · cells[1] · cells[2]` trilinear hexahedra (8-node), boundary
/// nodes fixed, every element valid.
pub fn hex_grid(block: &HexBlock) -> Result<VolumeMesh> {
    block.check("a block of hexahedra", 1)?;
    let cells: Vec<[u32; 8]> = block.cells().map(|(i, j, k)| block.cell(i, j, k)).collect();
    VolumeMesh::from_elements(block.nodes(), cells.iter().map(|c| (VolumeKind::Hex8, &c[..])))
}

pub(super) fn check_mixed(block: &HexBlock) -> Result<()> {
    block.check("a mixed block", 2)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::test_util::assert_volume_valid as assert_valid;
    use proptest::prelude::*;

    /// The total volume of a mesh of hexahedra, each split into its six Kuhn tetrahedra
    /// (exact for a hexahedron with flat faces; the bent block's faces are flat: planar
    /// trapezoids and rectangles).
    fn hex_volume(m: &VolumeMesh) -> f64 {
        const KUHN: [[usize; 4]; 6] = [[0, 1, 2, 6], [0, 2, 3, 6], [0, 3, 7, 6], [0, 7, 4, 6], [0, 4, 5, 6], [0, 5, 1, 6]];
        (0..m.element_count())
            .map(|e| {
                let c = m.corners(e);
                KUHN.iter().map(|t| crate::quality::tet::signed_volume(&t.map(|i| c[i]))).sum::<f64>()
            })
            .sum()
    }

    #[test]
    fn the_unit_cube_in_n_cubed_hexahedra() {
        let m = hex_grid(&HexBlock::cube(3)).unwrap();
        assert_eq!((m.node_count(), m.element_count(), m.free_count()), (64, 27, 8));
        assert_eq!(m.kinds(), &[VolumeKind::Hex8]);
        assert_valid(&m);
        // every corner of every cell is the unit cube's corner: scaled Jacobian 1
        for e in 0..m.element_count() {
            let s = m.measures(e);
            assert!((s.scaled_jacobian - 1.0).abs() < 1e-12 && (s.condition - 3.0).abs() < 1e-12, "{e}: {s:?}");
        }
        // 6 faces of 9 quads on the surface
        assert_eq!(m.boundary_faces().len(), 54);
        assert!((hex_volume(&m) - 1.0).abs() < 1e-12);
        assert!((m.mean_edge_length() - 1.0 / 3.0).abs() < 1e-14);
    }

    #[test]
    fn sizes_and_cell_counts_per_axis() {
        let b = HexBlock { cells: [4, 2, 1], size: DVec3::new(2.0, 1.0, 0.5), bend: 0.0 };
        let m = hex_grid(&b).unwrap();
        assert_eq!((m.node_count(), m.element_count()), (5 * 3 * 2, 8));
        assert_eq!(m.free_count(), 0, "one cell thick: every node on the boundary");
        assert!((hex_volume(&m) - 1.0).abs() < 1e-12);
        let top = m.nodes().iter().fold(DVec3::ZERO, |a, &p| a.max(p));
        assert_eq!(top, DVec3::new(2.0, 1.0, 0.5));
        assert_valid(&m);
    }

    #[test]
    fn the_bend_keeps_the_bottom_length_and_bends_the_block_onto_an_arc() {
        // 90° over a unit length: R = 2/π; the far end's bottom edge at (R, ·, −R)
        let b = HexBlock::cube(4).bent(90.0);
        let m = hex_grid(&b).unwrap();
        assert_valid(&m);
        let r = 2.0 / std::f64::consts::PI;
        let far = m.nodes()[b.id(4, 0, 0) as usize];
        assert!(far.distance(DVec3::new(r, 0.0, -r)) < 1e-15, "{far}");
        let far_top = m.nodes()[b.id(4, 4, 4) as usize];
        assert!(far_top.distance(DVec3::new(r + 1.0, 1.0, -r)) < 1e-15, "{far_top}");
        // every node at its radius R + z from the axis, the start face untouched
        for k in 0..=4 {
            for i in 0..=4 {
                let p = m.nodes()[b.id(i, 2, k) as usize];
                let rad = DVec3::new(p.x, 0.0, p.z + r).length();
                assert!((rad - (r + k as f64 / 4.0)).abs() < 1e-14, "node ({i}, 2, {k}) at radius {rad}");
            }
            let start = m.nodes()[b.id(0, 3, k) as usize];
            assert!(start.distance(DVec3::new(0.0, 0.75, k as f64 / 4.0)) < 1e-15, "{start}");
        }
        // the volume of the straight-edged ring sector: 4 cells a side, each a trapezoid
        // prism of angle π/8: (R_o² − R_i²)/2 · sin(π/8) · 4 cells · Ly
        let (s, _) = sin_cos(std::f64::consts::PI / 8.0);
        let want: f64 = (0..4).map(|k| {
            let (ri, ro) = (r + k as f64 / 4.0, r + (k + 1) as f64 / 4.0);
            4.0 * 0.5 * (ro * ro - ri * ri) * s
        }).sum();
        assert!((hex_volume(&m) - want).abs() < 1e-12, "{} vs {want}", hex_volume(&m));
        // the bent block's corners are no longer cubes: scaled Jacobians below 1
        assert!((0..m.element_count()).any(|e| m.measures(e).scaled_jacobian < 0.999));
    }

    #[test]
    fn bad_blocks_are_refused_in_words() {
        let e = |b: HexBlock| hex_grid(&b).unwrap_err().to_string();
        assert!(e(HexBlock::cube(0)).contains("0 cells along x: give 1 to 200"));
        assert!(e(HexBlock { cells: [2, 201, 2], ..HexBlock::default() }).contains("201 cells along y"));
        assert!(e(HexBlock { size: DVec3::new(1.0, 0.0, 1.0), ..HexBlock::default() }).contains("finite numbers > 0"));
        assert!(e(HexBlock { size: DVec3::new(1.0, f64::NAN, 1.0), ..HexBlock::default() }).contains("finite numbers > 0"));
        for bend in [-1.0, 271.0, f64::NAN, f64::INFINITY] {
            assert!(e(HexBlock::cube(4).bent(bend)).contains("give 0 to 270"), "{bend}");
        }
        assert!(e(HexBlock { cells: [1, 2, 2], ..HexBlock::cube(1) }.bent(180.0)).contains("give more cells along x"));
        assert!(hex_grid(&HexBlock { cells: [1, 2, 2], ..HexBlock::cube(1) }.bent(179.0)).is_ok());
        let big = e(HexBlock::cube(200));
        assert!(big.contains("8120601 nodes"), "{big}");
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(24))]
        #[test]
        fn every_block_and_bend_is_valid(nx in 1usize..5, ny in 1usize..4, nz in 1usize..4, bend in 0.0f64..270.0,
                                          sx in 0.1f64..10.0, sz in 0.1f64..10.0) {
            prop_assume!(bend / (nx as f64) < 179.0);
            let b = HexBlock { cells: [nx, ny, nz], size: DVec3::new(sx, 1.0, sz), bend };
            let m = hex_grid(&b).unwrap();
            prop_assert_eq!(m.element_count(), nx * ny * nz);
            assert_valid(&m);
            prop_assert_eq!(m.boundary_faces().len(), 2 * (nx * ny + ny * nz + nx * nz));
        }
    }
}
