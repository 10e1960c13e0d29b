//! A structured tetrahedral mesh of the unit cube: `n³` cubes of six tetrahedra each
//! (Kuhn's subdivision along every cube's main diagonal), conforming across the cubes.
//! With its interior nodes moved at random it is a Knupp-style tangled test mesh
//! ([`crate::volume::perturb_volume`]).

use glam::DVec3;

use crate::error::{Error, Result};
use crate::volume::VolumeMesh;

/// Kuhn's six tetrahedra of a cube with corners numbered by bits (x = 1, y = 2, z = 4):
/// the paths from corner 0 to corner 7 along the axes in each order.
const KUHN: [[usize; 4]; 6] = [[0, 1, 3, 7], [0, 1, 5, 7], [0, 2, 3, 7], [0, 2, 6, 7], [0, 4, 5, 7], [0, 4, 6, 7]];

/// The unit cube cut into `n` cubes a side, each into Kuhn's six tetrahedra, every
/// tetrahedron right-handed; boundary nodes fixed. `n` from 1 to 100.
pub fn tet_cube(n: usize) -> Result<VolumeMesh> {
    if !(1..=100).contains(&n) {
        return Err(Error::invalid(format!("a cube of {n} cells a side: give 1 to 100")));
    }
    let m = n + 1;
    let id = |i: usize, j: usize, k: usize| (i + m * (j + m * k)) as u32;
    let h = 1.0 / n as f64;
    let mut nodes = Vec::with_capacity(m * m * m);
    for k in 0..m {
        for j in 0..m {
            for i in 0..m {
                nodes.push(DVec3::new(i as f64, j as f64, k as f64) * h);
            }
        }
    }
    let mut tets = Vec::with_capacity(6 * n * n * n);
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                let corner = |b: usize| id(i + (b & 1), j + ((b >> 1) & 1), k + ((b >> 2) & 1));
                for t in KUHN {
                    let mut ids = t.map(corner);
                    let p = ids.map(|v| nodes[v as usize]);
                    if crate::quality::tet::signed_volume(&p) < 0.0 {
                        ids.swap(1, 2);
                    }
                    tets.push(ids);
                }
            }
        }
    }
    VolumeMesh::from_tets(nodes, &tets)
}
