//! The plate with a hole: Chen, Tristano & Kwok (2003), §5.2 and Figure 13, the mesh
//! they perturb at random and untangle, and the page's quadratic curved-boundary sample.

use std::collections::HashMap;

use glam::DVec2;

use super::{check_size, Assembly};
use crate::error::{Error, Result};
use crate::mesh::{ElementKind, Mesh};

/// Half the side of the square plate `[−h, h]²`.
pub const PLATE_HALF_WIDTH: f64 = 1.0;
/// Radius of the circular hole at the centre. Chen's Figure 13 (lost in the text) shows
/// a plate with a hole; these proportions are ours.
pub const PLATE_HOLE_RADIUS: f64 = 0.4;

enum_with_names! {
    /// The elements of a [`plate`].
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
    pub enum PlateKind {
        /// Each O-grid quad split into two triangles by its shorter diagonal.
        #[default]
        Tri => ("tri", "triangles (each O-grid quad split by its shorter diagonal)"),
        /// The O-grid of quads.
        Quad => ("quad", "the O-grid of quads"),
        /// Quads in the inner half of the rings (round the hole), triangles outside.
        Mixed => ("mixed", "quads round the hole, triangles outside"),
    }
}

/// A square plate `[−1, 1]²` with a hole of radius 0.4 at the centre, meshed as an
/// O-grid: `8·resolution` nodes round the hole and round the square (`resolution`
/// segments on each half side, so the four square corners are nodes) joined by straight
/// spokes, with `2·resolution` rings of cells between them. The ring nodes are spaced
/// evenly along each spoke. Cells are quads, triangles or both ([`PlateKind`]), all
/// counter-clockwise; the outer and the hole boundary are fixed.
///
/// `order = 2` adds mid-side nodes (6-node triangles, 8-node quads): on the hole they
/// lie on the circle, so those boundary edges are curved; elsewhere they sit at the edge
/// midpoints. `order` must be 1 or 2, `resolution ≥ 1`.
///
/// Nodes: corners first, ring by ring from the hole outwards, then the mid-side nodes.
/// With `m = 8·resolution` and `R = 2·resolution` there are `(R+1)·m` corner nodes and
/// `R·m` quads or `2·R·m` triangles (mixed: `R·m/2` quads and `R·m` triangles).
pub fn plate(kind: PlateKind, order: u8, resolution: usize) -> Result<Mesh> {
    if order != 1 && order != 2 {
        return Err(Error::invalid(format!("plate: order must be 1 or 2, not {order}")));
    }
    if resolution == 0 {
        return Err(Error::invalid("plate: the resolution must be at least 1"));
    }
    check_size("the plate", node_bound(order, resolution))?;
    let (m, rings) = (8 * resolution, 2 * resolution);
    let mut a = Assembly::with_capacity(m * (rings + 1), 2 * m * rings);
    let mut pos: Vec<DVec2> = Vec::with_capacity(m * (rings + 1));
    for i in 0..=rings {
        for j in 0..m {
            let p = ring_point(i, j, resolution);
            pos.push(p);
            a.node(p);
        }
    }
    let id = |i: usize, j: usize| (i * m + j % m) as u32;
    let mut mids = MidNodes { order, map: HashMap::new(), hole_nodes: m as u32 };
    for i in 0..rings {
        let quad = match kind {
            PlateKind::Quad => true,
            PlateKind::Tri => false,
            PlateKind::Mixed => i < rings / 2,
        };
        for j in 0..m {
            // counter-clockwise: out along spoke j, across, back in along spoke j+1
            let c = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            if quad {
                mids.element(&mut a, &pos, ElementKind::Quad4, &c);
            } else {
                let d02 = pos[c[0] as usize].distance_squared(pos[c[2] as usize]);
                let d13 = pos[c[1] as usize].distance_squared(pos[c[3] as usize]);
                let (t1, t2) = if d02 <= d13 {
                    ([c[0], c[1], c[2]], [c[0], c[2], c[3]])
                } else {
                    ([c[0], c[1], c[3]], [c[1], c[2], c[3]])
                };
                mids.element(&mut a, &pos, ElementKind::Tri3, &t1);
                mids.element(&mut a, &pos, ElementKind::Tri3, &t2);
            }
        }
    }
    a.build()
}

/// An upper bound of the node count: `(R+1)·m` corners and, with order 2, one mid node
/// per edge (`R·m` radial, `(R+1)·m` round, at most `R·m` diagonals); `None` on overflow.
fn node_bound(order: u8, resolution: usize) -> Option<usize> {
    let m = resolution.checked_mul(8)?;
    let rings = resolution.checked_mul(2)?;
    let corners = m.checked_mul(rings.checked_add(1)?)?;
    if order == 1 {
        return Some(corners);
    }
    corners.checked_add(m.checked_mul(rings.checked_mul(3)?.checked_add(1)?)?)
}

/// The corner node of ring `i` (0 on the hole, `2n` on the square), spoke `j`: from the
/// hole point at angle `2πj/m` straight to [`square_point`] `j`, evenly spaced.
fn ring_point(i: usize, j: usize, n: usize) -> DVec2 {
    let (m, rings) = (8 * n, 2 * n);
    let theta = std::f64::consts::TAU * j as f64 / m as f64;
    let (sin, cos) = crate::numeric::trig::sin_cos(theta);
    let hole = PLATE_HOLE_RADIUS * DVec2::new(cos, sin);
    if i == 0 {
        hole
    } else if i == rings {
        square_point(j, n)
    } else {
        hole.lerp(square_point(j, n), i as f64 / rings as f64)
    }
}

/// Point `j` of `8·n` equally spaced points on the square's perimeter, counter-clockwise
/// from `(h, 0)`: `n` steps per half side, so points `n, 3n, 5n, 7n` are the corners.
fn square_point(j: usize, n: usize) -> DVec2 {
    let h = PLATE_HALF_WIDTH;
    let m = 8 * n;
    let j = j % m;
    // shift so each side of 2n steps starts at a corner: side s runs from corner s
    let k = (j + n) % m;
    let (side, s) = (k / (2 * n), k % (2 * n));
    let u = h * (s as f64 / n as f64 - 1.0); // −h … h along the side
    match side {
        0 => DVec2::new(h, u),
        1 => DVec2::new(-u, h),
        2 => DVec2::new(-h, -u),
        _ => DVec2::new(u, -h),
    }
}

/// Adds elements, creating one mid-side node per edge when `order == 2`.
struct MidNodes {
    order: u8,
    map: HashMap<(u32, u32), u32>,
    /// Nodes below this index are on the hole.
    hole_nodes: u32,
}

impl MidNodes {
    fn element(&mut self, a: &mut Assembly, pos: &[DVec2], linear: ElementKind, corners: &[u32]) {
        if self.order == 1 {
            a.element(linear, corners);
            return;
        }
        let k = corners.len();
        let mut ids = [0u32; 8];
        ids[..k].copy_from_slice(corners);
        for i in 0..k {
            let (p, q) = (corners[i], corners[(i + 1) % k]);
            let key = (p.min(q), p.max(q));
            let hole = self.hole_nodes;
            ids[k + i] = *self.map.entry(key).or_insert_with(|| {
                let (pp, pq) = (pos[p as usize], pos[q as usize]);
                let mid = if p < hole && q < hole {
                    // a hole edge: its mid node on the circle, halfway round the arc
                    PLATE_HOLE_RADIUS * (pp + pq).normalize()
                } else {
                    0.5 * (pp + pq)
                };
                a.node(mid)
            });
        }
        let kind = if k == 3 { ElementKind::Tri6 } else { ElementKind::Quad8 };
        a.element(kind, &ids[..2 * k]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::test_util::assert_valid;
    use crate::mesh::NodeRole;
    use crate::quality::mesh_stats;

    const KINDS: [PlateKind; 3] = [PlateKind::Tri, PlateKind::Quad, PlateKind::Mixed];

    fn on_hole(p: DVec2) -> bool {
        (p.length() - PLATE_HOLE_RADIUS).abs() < 1e-12
    }
    fn on_square(p: DVec2) -> bool {
        (p.abs().max_element() - PLATE_HALF_WIDTH).abs() < 1e-12
    }

    #[test]
    fn counts_and_validity() {
        for n in 1..=4 {
            let (m, r) = (8 * n, 2 * n);
            for kind in KINDS {
                let (quads, tris) = match kind {
                    PlateKind::Quad => (r * m, 0),
                    PlateKind::Tri => (0, 2 * r * m),
                    PlateKind::Mixed => (r / 2 * m, 2 * (r - r / 2) * m),
                };
                let diagonals = tris / 2;
                for order in [1, 2] {
                    let p = plate(kind, order, n).unwrap();
                    assert_valid(&p);
                    let s = mesh_stats(&p);
                    assert_eq!((s.quads, s.triangles), (quads, tris), "{kind:?} n={n}");
                    let edges = (2 * r + 1) * m + diagonals;
                    assert_eq!(p.edges().len(), edges);
                    // an annulus: V − E + F = 0 on the corner graph
                    assert_eq!((r + 1) * m + quads + tris, edges);
                    let expect_nodes = (r + 1) * m + if order == 2 { edges } else { 0 };
                    assert_eq!(p.node_count(), expect_nodes, "{kind:?} order {order} n={n}");
                    assert_eq!(s.quadratic, if order == 2 { quads + tris } else { 0 });
                    assert_eq!(p.free_count(), (r - 1) * m);
                }
            }
        }
    }

    #[test]
    fn boundary_is_the_hole_and_the_square() {
        for kind in KINDS {
            let p = plate(kind, 1, 3).unwrap();
            for (i, &q) in p.nodes().iter().enumerate() {
                let bnd = on_hole(q) || on_square(q);
                assert_eq!(p.is_boundary(i), bnd, "node {i} at {q}");
                assert_eq!(p.fixed()[i], bnd, "node {i}");
            }
            // the cells fill the square less the hole's inscribed 24-gon
            let m = 24.0;
            let hole = 0.5 * m * PLATE_HOLE_RADIUS.powi(2) * (std::f64::consts::TAU / m).sin();
            let area: f64 = (0..p.element_count()).map(|e| p.corner_area(e)).sum();
            assert!((area - (4.0 * PLATE_HALF_WIDTH.powi(2) - hole)).abs() < 1e-12, "{area}");
            // the four corners of the square are nodes
            for c in [DVec2::new(1.0, 1.0), DVec2::new(-1.0, 1.0), DVec2::new(-1.0, -1.0), DVec2::new(1.0, -1.0)] {
                assert!(p.nodes().iter().any(|q| q.distance(c) < 1e-15), "{c}");
            }
        }
    }

    #[test]
    fn mixed_has_quads_round_the_hole() {
        let p = plate(PlateKind::Mixed, 1, 2).unwrap();
        for e in 0..p.element_count() {
            let touches_hole = p.element(e).iter().any(|&i| on_hole(p.nodes()[i as usize]));
            let touches_square = p.element(e).iter().any(|&i| on_square(p.nodes()[i as usize]));
            if touches_hole {
                assert!(p.kind(e).is_quad());
            }
            if touches_square {
                assert!(p.kind(e).is_triangle());
            }
        }
    }

    #[test]
    fn quadratic_hole_is_curved() {
        for kind in KINDS {
            let p = plate(kind, 2, 2).unwrap();
            let m = 16;
            let mut curved = 0;
            for e in p.edges() {
                assert_ne!(e.mid, crate::mesh::NONE);
                let (a, b, c) = (p.nodes()[e.a as usize], p.nodes()[e.b as usize], p.nodes()[e.mid as usize]);
                assert_eq!(p.role(e.mid as usize), NodeRole::Mid);
                if on_hole(a) && on_hole(b) {
                    assert!((c.length() - PLATE_HOLE_RADIUS).abs() < 1e-12, "hole mid node on the circle");
                    // halfway round the arc
                    assert!((c.distance(a) - c.distance(b)).abs() < 1e-12);
                    assert!(e.curved && e.is_boundary() && p.fixed()[e.mid as usize]);
                    curved += 1;
                } else {
                    assert!(c.distance(0.5 * (a + b)) < 1e-15, "straight edges have mid nodes at the midpoint");
                    assert!(!e.curved);
                }
            }
            assert_eq!(curved, m);
            // mid nodes stay where update_mid_nodes would put them
            let mut q = p.clone();
            q.update_mid_nodes();
            assert_eq!(q.nodes(), p.nodes());
        }
    }

    #[test]
    fn reasonable_shapes() {
        // not only valid: a fair starting mesh. The O-grid's corner cells have the 45°
        // between a diagonal spoke and the square's side; splitting by the shorter
        // diagonal keeps triangle angles above 15°.
        for kind in KINDS {
            for order in [1, 2] {
                let s = mesh_stats(&plate(kind, order, 4).unwrap());
                assert!(s.min_angle_deg > 15.0 && s.max_angle_deg < 140.0, "{kind:?}: {s:?}");
                assert!(s.min_quality > 0.4 && s.mean_quality > 0.6, "{kind:?}: {s:?}");
            }
        }
    }

    #[test]
    fn bad_requests_are_errors() {
        assert!(matches!(plate(PlateKind::Tri, 3, 2), Err(Error::Invalid(_))));
        assert!(matches!(plate(PlateKind::Quad, 1, 0), Err(Error::Invalid(_))));
        assert!(matches!(plate(PlateKind::Quad, 2, 100_000), Err(Error::TooLarge(_))));
        assert!(matches!(plate(PlateKind::Quad, 2, usize::MAX / 3), Err(Error::TooLarge(_))));
    }
}
