//! Structured grids on the unit square.

use glam::DVec2;

use super::{check_size, Assembly};
use crate::error::{Error, Result};
use crate::mesh::{ElementKind, Mesh};

enum_with_names! {
    /// The elements of a [`grid`].
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
    pub enum GridKind {
        /// Each square split into two triangles by its diagonal from lower left to upper
        /// right: one fixed direction, so every interior node has six neighbours.
        #[default]
        Tri => ("tri", "two triangles per square, split lower-left to upper-right"),
        /// One quad per square.
        Quad => ("quad", "one quad per square"),
    }
}

/// A structured `nx × ny` grid on the unit square `[0,1]²`: `(nx+1)(ny+1)` nodes, numbered
/// row by row from the lower left, and `nx·ny` quads or `2·nx·ny` triangles, all
/// counter-clockwise; boundary nodes fixed. `nx, ny ≥ 1`.
pub fn grid(nx: usize, ny: usize, kind: GridKind) -> Result<Mesh> {
    if nx == 0 || ny == 0 {
        return Err(Error::invalid(format!("a grid needs at least one cell each way, not {nx} × {ny}")));
    }
    check_size("the grid", nx.checked_add(1).zip(ny.checked_add(1)).and_then(|(a, b)| a.checked_mul(b)))?;
    let cells = nx * ny;
    let elements = if kind == GridKind::Tri { 2 * cells } else { cells };
    let mut a = Assembly::with_capacity((nx + 1) * (ny + 1), elements);
    for j in 0..=ny {
        for i in 0..=nx {
            a.node(DVec2::new(i as f64 / nx as f64, j as f64 / ny as f64));
        }
    }
    let id = |i: usize, j: usize| (j * (nx + 1) + i) as u32;
    for j in 0..ny {
        for i in 0..nx {
            let (p00, p10, p11, p01) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            match kind {
                GridKind::Quad => a.element(ElementKind::Quad4, &[p00, p10, p11, p01]),
                GridKind::Tri => {
                    a.element(ElementKind::Tri3, &[p00, p10, p11]);
                    a.element(ElementKind::Tri3, &[p00, p11, p01]);
                }
            }
        }
    }
    a.build()
}

/// Knupp (1999), Fig. 1: an `n × n` [`grid`] of the unit square with every interior node
/// placed uniformly at random in the square (seeded), boundary fixed — a tangled mesh,
/// unlike the other generators' (the reproduction's §4 uses `n = 10`, seeds 1–5).
pub fn random_grid(n: usize, kind: GridKind, seed: u64) -> Result<Mesh> {
    let mut m = grid(n, n, kind)?;
    let mut rng = crate::numeric::SplitMix64::new(seed);
    for i in 0..m.node_count() {
        if m.is_free(i) {
            m.nodes_mut()[i] = DVec2::new(rng.next_f64(), rng.next_f64());
        }
    }
    Ok(m)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::test_util::assert_valid;
    use crate::quality::mesh_stats;

    #[test]
    fn counts_and_validity() {
        for (nx, ny) in [(1, 1), (3, 2), (10, 7)] {
            let q = grid(nx, ny, GridKind::Quad).unwrap();
            assert_valid(&q);
            assert_eq!(q.node_count(), (nx + 1) * (ny + 1));
            assert_eq!(q.element_count(), nx * ny);
            assert_eq!(q.free_count(), (nx - 1) * (ny - 1));
            let t = grid(nx, ny, GridKind::Tri).unwrap();
            assert_valid(&t);
            assert_eq!(t.node_count(), (nx + 1) * (ny + 1));
            assert_eq!(t.element_count(), 2 * nx * ny);
            assert_eq!(t.free_count(), (nx - 1) * (ny - 1));
            // the cells tile the unit square
            let area: f64 = (0..t.element_count()).map(|e| t.corner_area(e)).sum();
            assert!((area - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn square_grid_is_ideal() {
        let q = mesh_stats(&grid(4, 4, GridKind::Quad).unwrap());
        assert!((q.min_quality - 1.0).abs() < 1e-12, "squares have β = 1");
        let t = grid(4, 4, GridKind::Tri).unwrap();
        // fixed diagonal direction: interior nodes have six neighbours
        for n in 0..t.node_count() {
            if t.is_free(n) {
                assert_eq!(t.neighbours(n).len(), 6);
            }
        }
        let s = mesh_stats(&t);
        assert!((s.min_angle_deg - 45.0).abs() < 1e-9 && (s.max_angle_deg - 90.0).abs() < 1e-9);
    }

    #[test]
    fn bad_sizes_are_errors() {
        assert!(matches!(grid(0, 3, GridKind::Tri), Err(Error::Invalid(_))));
        assert!(matches!(grid(100_000, 100_000, GridKind::Quad), Err(Error::TooLarge(_))));
        assert!(matches!(grid(usize::MAX, 2, GridKind::Quad), Err(Error::TooLarge(_))));
    }
}
