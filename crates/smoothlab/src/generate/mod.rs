//! Sample meshes: Freitag's `rand2d`, structured grids, Chen's plate with a hole (linear
//! or quadratic with a curved hole), single-node star configurations, surfaces, Freitag's
//! rand3D, a cube of tetrahedra, a block of hexahedra (straight or bent) and a mixed block
//! of every linear volume kind, and the random perturbation that tangles a mesh.
//!
//! Everything here is deterministic: the seeded generators draw from [`SplitMix64`](crate::numeric::SplitMix64),
//! whose stream is fixed by this crate, so a seed names the same mesh on every platform.
//! Every generated mesh is counter-clockwise with no inverted element (but those of
//! [`perturb`] and [`random_grid`], made to be tangled), and its boundary nodes are fixed
//! (the stars: every node but the centre).

mod cube;
mod grid;
mod hexgrid;
mod mixed;
mod perturb;
mod plate;
mod rand2d;
mod rand3d;
mod star;
mod surface;

pub use cube::tet_cube;
pub use grid::{grid, random_grid, GridKind};
pub use hexgrid::{hex_grid, HexBlock, MAX_BEND_DEG, MAX_BLOCK_CELLS};
pub use mixed::mixed_block;
pub use perturb::{perturb, perturb_surface, perturb_volume};
pub use plate::{plate, PlateKind, PLATE_HALF_WIDTH, PLATE_HOLE_RADIUS};
pub use rand2d::{rand2d, rand2d_spatial};
pub use rand3d::{delaunay_tetrahedra, rand3d, RAND3D_POINTS};
pub use star::{quadratic_star, star, QuadraticStar, StarKind, CURVED_BULGE, PUSHED_MID_HEIGHT};
pub use surface::{surface, SurfaceKind, SurfaceShape, MAX_SURFACE_RESOLUTION};

use glam::DVec2;

use crate::error::{Error, Result};
use crate::mesh::{ElementKind, Mesh, MeshBuilder};

/// The largest number of nodes a generator makes; larger requests are refused with
/// [`Error::TooLarge`] before anything is allocated (the page runs in wasm's 4 GiB).
pub const MAX_GENERATED_NODES: usize = 4_000_000;

fn check_size(what: &str, nodes: Option<usize>) -> Result<()> {
    match nodes {
        Some(n) if n <= MAX_GENERATED_NODES => Ok(()),
        Some(n) => Err(Error::TooLarge(format!("{what} would have {n} nodes; the limit is {MAX_GENERATED_NODES}"))),
        None => Err(Error::TooLarge(format!("{what}: the node count overflows"))),
    }
}

/// Collects planar nodes and elements, then builds the mesh (boundary nodes fixed).
struct Assembly {
    b: MeshBuilder,
}

impl Assembly {
    /// Room for `nodes` nodes and `elements` elements of three nodes (more grow as needed).
    fn with_capacity(nodes: usize, elements: usize) -> Self {
        let mut b = MeshBuilder::new();
        b.reserve_exact(nodes, elements, 3 * elements);
        Assembly { b }
    }
    fn node(&mut self, p: DVec2) -> u32 {
        self.b.add_node([p.x, p.y, 0.0], 0) as u32
    }
    fn element(&mut self, kind: ElementKind, ids: &[u32]) {
        self.b.add_element(kind, ids, 0);
    }
    fn build(self) -> Result<Mesh> {
        self.b.build()
    }
}

#[cfg(test)]
pub(crate) mod test_util {
    use crate::mesh::Mesh;
    use crate::quality::mesh_stats;

    /// The invariants every generated mesh keeps: the model's own checks, no inverted
    /// element, every element counter-clockwise, and boundary nodes fixed.
    pub fn assert_valid(m: &Mesh) {
        m.sanity_check().unwrap();
        assert_eq!(mesh_stats(m).inverted, 0, "inverted elements");
        for e in 0..m.element_count() {
            assert!(m.corner_area(e) > 0.0, "element {e} is not counter-clockwise");
        }
        for n in 0..m.node_count() {
            if m.is_boundary(n) {
                assert!(m.fixed()[n], "boundary node {n} is free");
            }
        }
    }

    /// The invariants of a generated volume mesh: no inverted element (certain validity),
    /// and the fixed nodes exactly those of the boundary faces.
    pub fn assert_volume_valid(m: &crate::volume::VolumeMesh) {
        let inverted: Vec<usize> = (0..m.element_count()).filter(|&e| m.is_inverted(e)).collect();
        assert!(inverted.is_empty(), "inverted elements {inverted:?}");
        let mut on_boundary = vec![false; m.node_count()];
        for f in m.boundary_faces() {
            for &n in f.nodes() {
                on_boundary[n as usize] = true;
            }
        }
        assert_eq!(on_boundary.as_slice(), m.fixed(), "fixed nodes are the boundary's");
    }
}
