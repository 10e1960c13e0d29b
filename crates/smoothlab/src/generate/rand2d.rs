//! Freitag's `rand2d`: the Delaunay triangulation of random points in the unit square.

use glam::DVec2;
use spade::{DelaunayTriangulation, Point2, Triangulation};

use super::{check_size, Assembly};
use crate::numeric::SplitMix64;
use crate::error::{Error, Result};
use crate::mesh::{ElementKind, Mesh};

/// Interior points closer than this fraction of the mean point spacing to an earlier
/// point, or to the boundary, are drawn again. It only guards against (near-)duplicate
/// points that would make triangles of vanishing area; at 10⁻³ of the spacing about
/// one draw in 300 000 is rejected, so the points stay Freitag's uniform ones.
const MIN_SEPARATION: f64 = 1e-3;

/// Freitag (1997), §"Meshes generated from random point sets": the Delaunay
/// triangulation of `interior` seeded uniform random points in the unit square plus
/// `per_side` equally spaced points on each side (spacing `1/per_side`, each corner
/// counted once), so the mesh has `n = interior + 4·per_side` nodes and `2n − h − 2`
/// triangles with `h = 4·per_side` boundary nodes. Freitag's mesh, `rand2d(500, 20, _)`,
/// has 580 nodes and 1078 triangles. Boundary nodes are fixed.
///
/// Nodes are numbered boundary first (counter-clockwise from the origin), then the
/// interior points in the order drawn. The triangulation is spade's, with exact
/// predicates; the points come from [`SplitMix64`] seeded with `seed`.
///
/// ```
/// let mesh = smoothlab::generate::rand2d(500, 20, 1)?;
/// assert_eq!((mesh.node_count(), mesh.element_count()), (580, 1078));
/// # Ok::<(), smoothlab::Error>(())
/// ```
pub fn rand2d(interior: usize, per_side: usize, seed: u64) -> Result<Mesh> {
    rand2d_numbered(interior, per_side, seed, false)
}

/// [`rand2d`]'s mesh with its nodes numbered along a Hilbert curve instead: the same
/// points, so the same triangulation, but a node's star and neighbours lie near it in
/// memory (as after [`Mesh::renumbered_spatially`], without building the mesh twice).
/// The page's large samples are made so: a smoother visiting their nodes finds what it
/// reads in cache, where [`rand2d`]'s numbering (the order drawn) scatters it over the
/// whole mesh.
pub fn rand2d_spatial(interior: usize, per_side: usize, seed: u64) -> Result<Mesh> {
    rand2d_numbered(interior, per_side, seed, true)
}

fn rand2d_numbered(interior: usize, per_side: usize, seed: u64, spatial: bool) -> Result<Mesh> {
    if per_side == 0 {
        return Err(Error::invalid("rand2d needs at least one boundary point per side (the corners)"));
    }
    let boundary = per_side.checked_mul(4);
    let total = boundary.and_then(|b| b.checked_add(interior));
    check_size("rand2d", total)?;
    let total = total.unwrap_or(0);
    let mut pts: Vec<DVec2> = Vec::with_capacity(total);
    let p = per_side as f64;
    for side in 0..4 {
        for s in 0..per_side {
            let t = s as f64 / p;
            pts.push(match side {
                0 => DVec2::new(t, 0.0),
                1 => DVec2::new(1.0, t),
                2 => DVec2::new(1.0 - t, 1.0),
                _ => DVec2::new(0.0, 1.0 - t),
            });
        }
    }
    draw_interior(&mut pts, interior, seed)?;
    if spatial {
        let grid = crate::mesh::HilbertGrid::over(DVec2::ZERO, DVec2::ONE);
        pts.sort_by_cached_key(|&q| grid.key(q));
    }

    let vertices: Vec<Point2<f64>> = pts.iter().map(|q| Point2::new(q.x, q.y)).collect();
    let dt = DelaunayTriangulation::<Point2<f64>>::bulk_load_stable(vertices)
        .map_err(|e| Error::invalid(format!("rand2d: the Delaunay triangulation failed: {e:?}")))?;
    if dt.num_vertices() != pts.len() {
        return Err(Error::invalid("rand2d: duplicate points reached the triangulation"));
    }
    let mut a = Assembly::with_capacity(pts.len(), dt.num_inner_faces());
    for q in &pts {
        a.node(*q);
    }
    drop(pts);
    for f in dt.inner_faces() {
        // spade's faces are counter-clockwise; `bulk_load_stable` keeps our numbering
        let [v0, v1, v2] = f.vertices();
        a.element(ElementKind::Tri3, &[v0.index() as u32, v1.index() as u32, v2.index() as u32]);
    }
    // the triangulation (about 200 bytes a point) is let go before the topology is built
    drop(dt);
    a.build()
}

/// Appends `count` uniform points of the open unit square, each at least
/// `MIN_SEPARATION × spacing` from every point already in `pts` and from the boundary.
/// A bucket grid of cell size `spacing` keeps the check local.
fn draw_interior(pts: &mut Vec<DVec2>, count: usize, seed: u64) -> Result<()> {
    let total = pts.len() + count;
    let spacing = 1.0 / (total as f64).sqrt();
    let min_sep = MIN_SEPARATION * spacing;
    let cells = ((1.0 / spacing).ceil() as usize).max(1);
    let mut buckets: Vec<Vec<u32>> = vec![Vec::new(); cells * cells];
    let cell_of = |q: DVec2| -> (usize, usize) {
        let c = |v: f64| ((v * cells as f64) as usize).min(cells - 1);
        (c(q.x), c(q.y))
    };
    for (i, q) in pts.iter().enumerate() {
        let (cx, cy) = cell_of(*q);
        buckets[cy * cells + cx].push(i as u32);
    }
    let mut rng = SplitMix64::new(seed);
    let max_draws = count.saturating_mul(4).saturating_add(1000);
    let mut draws = 0usize;
    let mut added = 0;
    while added < count {
        draws += 1;
        if draws > max_draws {
            return Err(Error::invalid(format!(
                "rand2d: could not place {count} separated points after {max_draws} draws"
            )));
        }
        let q = DVec2::new(rng.next_f64(), rng.next_f64());
        if q.min_element() < min_sep || q.max_element() > 1.0 - min_sep {
            continue;
        }
        let (cx, cy) = cell_of(q);
        let mut clash = false;
        'search: for y in cy.saturating_sub(1)..=(cy + 1).min(cells - 1) {
            for x in cx.saturating_sub(1)..=(cx + 1).min(cells - 1) {
                if buckets[y * cells + x].iter().any(|&i| pts[i as usize].distance_squared(q) < min_sep * min_sep) {
                    clash = true;
                    break 'search;
                }
            }
        }
        if clash {
            continue;
        }
        buckets[cy * cells + cx].push(pts.len() as u32);
        pts.push(q);
        added += 1;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::test_util::assert_valid;

    #[test]
    fn the_spatial_numbering_is_the_same_mesh_with_neighbours_near_in_memory() {
        let (drawn, spatial) = (rand2d(3000, 30, 7).unwrap(), rand2d_spatial(3000, 30, 7).unwrap());
        assert_valid(&spatial);
        assert_eq!((spatial.node_count(), spatial.element_count()), (drawn.node_count(), drawn.element_count()));
        assert_eq!(spatial.free_count(), drawn.free_count());
        // the same triangles, as sets of points
        let triangles = |m: &Mesh| {
            let mut t: Vec<[(u64, u64); 3]> = (0..m.element_count())
                .map(|e| {
                    let mut c = [0, 1, 2].map(|k| {
                        let p = m.nodes()[m.element(e)[k] as usize];
                        (p.x.to_bits(), p.y.to_bits())
                    });
                    c.sort_unstable();
                    c
                })
                .collect();
            t.sort_unstable();
            t
        };
        assert_eq!(triangles(&spatial), triangles(&drawn));
        // an edge joins nodes far fewer numbers apart
        let spread =
            |m: &Mesh| m.edges().iter().map(|e| (e.a as f64 - e.b as f64).abs()).sum::<f64>() / m.edges().len() as f64;
        assert!(spread(&spatial) * 10.0 < spread(&drawn), "{} vs {}", spread(&spatial), spread(&drawn));
        assert_eq!(spatial.nodes(), rand2d_spatial(3000, 30, 7).unwrap().nodes(), "deterministic");
    }

    #[test]
    fn freitag_counts() {
        let m = rand2d(500, 20, 1).unwrap();
        assert_valid(&m);
        assert_eq!(m.node_count(), 580);
        assert_eq!(m.element_count(), 1078);
        assert_eq!(m.free_count(), 500);
        assert!(m.kinds().iter().all(|&k| k == ElementKind::Tri3));
    }

    #[test]
    fn euler_count_for_other_sizes() {
        for (interior, per_side, seed) in [(0, 1, 0), (0, 5, 3), (1, 1, 9), (37, 3, 5), (2000, 40, 77)] {
            let m = rand2d(interior, per_side, seed).unwrap();
            assert_valid(&m);
            let n = interior + 4 * per_side;
            assert_eq!(m.node_count(), n);
            assert_eq!(m.element_count(), 2 * n - 4 * per_side - 2, "{interior} {per_side}");
            let area: f64 = (0..m.element_count()).map(|e| m.corner_area(e)).sum();
            assert!((area - 1.0).abs() < 1e-12, "triangles tile the square: {area}");
        }
    }

    #[test]
    fn boundary_is_the_square_and_fixed() {
        let m = rand2d(200, 10, 4).unwrap();
        for (i, p) in m.nodes().iter().enumerate() {
            let on_square = p.x == 0.0 || p.x == 1.0 || p.y == 0.0 || p.y == 1.0;
            assert_eq!(on_square, i < 40, "node {i} at {p}");
            assert_eq!(m.fixed()[i], on_square, "node {i}");
            assert_eq!(m.is_boundary(i), on_square, "node {i}");
        }
    }

    #[test]
    fn seeded_and_deterministic() {
        let a = rand2d(300, 10, 7).unwrap();
        let b = rand2d(300, 10, 7).unwrap();
        assert_eq!(a.nodes(), b.nodes());
        for e in 0..a.element_count() {
            assert_eq!(a.element(e), b.element(e));
        }
        let c = rand2d(300, 10, 8).unwrap();
        assert_eq!(a.nodes()[..40], c.nodes()[..40], "the boundary does not depend on the seed");
        let moved = a.nodes().iter().zip(c.nodes()).filter(|(p, q)| p != q).count();
        assert_eq!(moved, 300, "every interior point differs with another seed");
    }

    #[test]
    fn points_are_uniform_and_separated() {
        let m = rand2d(4000, 10, 11).unwrap();
        let inner = &m.nodes()[40..];
        // each quarter of the square holds about a quarter of the points (σ ≈ 27)
        let q = inner.iter().filter(|p| p.x < 0.5 && p.y < 0.5).count();
        assert!((q as i64 - 1000).abs() < 150, "{q}");
        let spacing = 1.0 / (m.node_count() as f64).sqrt();
        for (i, p) in inner.iter().enumerate() {
            assert!(p.min_element() >= MIN_SEPARATION * spacing && p.max_element() <= 1.0 - MIN_SEPARATION * spacing);
            for q in &inner[i + 1..] {
                assert!(p.distance(*q) >= MIN_SEPARATION * spacing);
            }
        }
    }

    #[test]
    fn bad_requests_are_errors() {
        assert!(matches!(rand2d(10, 0, 1), Err(Error::Invalid(_))));
        assert!(matches!(rand2d(usize::MAX, 20, 1), Err(Error::TooLarge(_))));
        assert!(matches!(rand2d(10, usize::MAX / 2, 1), Err(Error::TooLarge(_))));
    }
}
