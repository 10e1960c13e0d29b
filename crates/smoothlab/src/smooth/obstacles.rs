//! Why an inverted element cannot be made valid by moving the free nodes: the cases where
//! untangling is impossible, so `smooth` can name the elements and say why instead of
//! giving a count.

use serde::Serialize;

use crate::mesh::Mesh;
use crate::quality::corner_edges;

/// An inverted element no smoother can make valid, and why.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Obstacle {
    /// Element number, 0-based in file order.
    pub element: usize,
    /// Why, for people (node numbers 0-based in file order).
    pub reason: String,
}

/// The inverted elements of `mesh` that moving its free nodes cannot make valid:
/// - two corners that are fixed and coincide (an edge or a diagonal of no length: some
///   corner's determinant is 0 wherever the other nodes go);
/// - a corner with `det ≤ 0` whose determinant depends only on fixed nodes: the corner
///   and its two neighbouring corners (and so the mid-side nodes of its edges, which move
///   only with their corners) are all fixed.
///
/// Elements left inverted for any other reason are not listed: a position that makes them
/// valid may exist, though the smoother did not find it.
pub fn untangling_obstacles(mesh: &Mesh) -> Vec<Obstacle> {
    let mut out = Vec::new();
    for e in 0..mesh.element_count() {
        let kind = mesh.kind(e);
        let k = kind.corners();
        let ids = &mesh.element(e)[..k];
        let p = mesh.element_points_array(e);
        let edges = corner_edges(kind, &p);
        let fixed = |i: usize| !mesh.is_free(ids[i] as usize);
        let coincident =
            (0..k).flat_map(|i| (i + 1..k).map(move |j| (i, j))).find(|&(i, j)| fixed(i) && fixed(j) && p[i] == p[j]);
        if let Some((i, j)) = coincident {
            if edges[..k].iter().any(|(e1, e2)| e1.perp_dot(*e2) <= 0.0) {
                out.push(Obstacle {
                    element: e,
                    reason: format!(
                        "nodes {} and {} are fixed and at the same point, so the element has a side of no length \
                         wherever its other nodes go",
                        ids[i], ids[j]
                    ),
                });
                continue;
            }
        }
        let stuck = (0..k).find(|&i| {
            let (e1, e2) = edges[i];
            e1.perp_dot(e2) <= 0.0 && fixed(i) && fixed((i + 1) % k) && fixed((i + k - 1) % k)
        });
        if let Some(i) = stuck {
            out.push(Obstacle {
                element: e,
                reason: format!(
                    "its corner at node {} is inverted and is set by nodes {}, {} and {} alone, all fixed",
                    ids[i],
                    ids[(i + k - 1) % k],
                    ids[i],
                    ids[(i + 1) % k]
                ),
            });
        }
    }
    out
}

/// The inverted elements of a volume mesh that moving its free nodes (and sliding its
/// boundary nodes, [`crate::volume::BoundaryRule::Slide`]) cannot make valid: a measured
/// corner whose determinant is ≤ 0 (exactly, [`orient3d`](crate::numeric::exact::orient3d))
/// and depends only on nodes that cannot move — the corner and its three edge neighbours.
/// As for planar meshes, elements left inverted for any other reason are not listed.
pub fn volume_untangling_obstacles(mesh: &crate::volume::VolumeMesh) -> Vec<Obstacle> {
    use crate::numeric::exact::orient3d;
    let mut out = Vec::new();
    for e in (0..mesh.element_count()).filter(|&e| mesh.is_inverted(e)) {
        let kind = mesh.element_kind(e);
        let ids = &mesh.element(e)[..kind.corners()];
        let held = |i: usize| !mesh.is_free(ids[i] as usize);
        let p = mesh.corners(e);
        let stuck = kind.row().corner_edges.iter().enumerate().find(|&(c, &[a, b, d])| {
            let t = crate::quality::solid::corner_tet(kind, &p[..ids.len()], c);
            orient3d(t[0], t[1], t[2], t[3]) != std::cmp::Ordering::Greater && [c, a, b, d].iter().all(|&i| held(i))
        });
        if let Some((c, &[a, b, d])) = stuck {
            out.push(Obstacle {
                element: e,
                reason: format!(
                    "its corner at node {} is inverted and is set by nodes {}, {}, {} and {} alone, none of which can move",
                    ids[c], ids[c], ids[a], ids[b], ids[d]
                ),
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{ElementKind, FixedSpec, MeshBuilder};

    /// Nodes with flags (1 = fixed), triangles by node numbers.
    fn mesh(nodes: &[(f64, f64, u8)], tris: &[[u32; 3]]) -> Mesh {
        let mut b = MeshBuilder::new();
        for &(x, y, _) in nodes {
            b.add_node([x, y, 0.0], 0);
        }
        b.fixed = FixedSpec::Exact(nodes.iter().map(|n| n.2 == 1).collect());
        for t in tris {
            b.add_element(ElementKind::Tri3, t, 0);
        }
        b.build().unwrap()
    }

    #[test]
    fn an_inverted_corner_of_fixed_nodes_is_named() {
        // two triangles about the free node 0, and triangle 2 (1, 4, 3), clockwise and
        // made of fixed nodes only
        let m = mesh(
            &[(0.0, 0.0, 0), (1.0, 0.0, 1), (0.0, 1.0, 1), (-1.0, 0.0, 1), (0.0, -1.0, 1)],
            &[[0, 1, 2], [0, 2, 3], [1, 4, 3]],
        );
        let o = untangling_obstacles(&m);
        assert_eq!(o.len(), 1, "{o:?}");
        assert_eq!(o[0].element, 2);
        assert!(o[0].reason.contains("all fixed"), "{}", o[0].reason);
        // with one of its nodes free it may be untangled: not listed
        let m = mesh(
            &[(0.0, 0.0, 0), (1.0, 0.0, 1), (0.0, 1.0, 1), (-1.0, 0.0, 1), (0.0, -1.0, 0)],
            &[[0, 1, 2], [0, 2, 3], [1, 4, 3]],
        );
        assert_eq!(untangling_obstacles(&m), []);
    }

    #[test]
    fn coincident_fixed_nodes_are_named() {
        // nodes 1 and 3 fixed at the same point: triangle 2 (0, 3, 1) has a side of no length
        let m = mesh(
            &[(0.2, 0.2, 0), (1.0, 0.0, 1), (0.0, 1.0, 1), (1.0, 0.0, 1), (1.0, 1.0, 1)],
            &[[0, 1, 2], [1, 4, 2], [0, 3, 1]],
        );
        let o = untangling_obstacles(&m);
        assert!(o.iter().any(|o| o.element == 2 && o.reason.contains("nodes 3 and 1")), "{o:?}");
        // valid elements are never listed
        assert!(o.iter().all(|o| o.element == 2), "{o:?}");
    }
}
