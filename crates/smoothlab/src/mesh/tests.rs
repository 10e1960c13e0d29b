use super::renumber::{hilbert_index, HILBERT_ORDER};
use super::*;
use crate::error::Error;

fn square_two_tris() -> MeshBuilder {
    let mut b = MeshBuilder::new();
    for p in [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]] {
        b.add_node(p, 0);
    }
    b.add_element(ElementKind::Tri3, &[0, 1, 2], 0);
    b.add_element(ElementKind::Tri3, &[0, 2, 3], 0);
    b
}

#[test]
fn topology_of_two_triangles() {
    let m = square_two_tris().build().unwrap();
    m.sanity_check().unwrap();
    assert_eq!(m.edges().len(), 5);
    assert_eq!(m.topology().boundary_edges().count(), 4);
    assert_eq!(m.neighbours(0).len(), 3);
    assert_eq!(m.neighbours(1).len(), 2);
    assert_eq!(m.node_elements(0), &[0, 1]);
    assert!(m.fixed.iter().all(|&f| f));
    assert_eq!(m.free_count(), 0);
}

#[test]
fn clockwise_mesh_is_reversed_as_a_whole() {
    let mut b = MeshBuilder::new();
    for p in [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]] {
        b.add_node(p, 0);
    }
    b.add_element(ElementKind::Tri3, &[0, 2, 1], 0);
    b.add_element(ElementKind::Tri3, &[0, 3, 2], 0);
    let m = b.build().unwrap();
    assert!(m.corner_area(0) > 0.0 && m.corner_area(1) > 0.0);
}

#[test]
fn one_inverted_element_stays_inverted() {
    // three CCW triangles around node 4, one folded over: total area stays positive
    let mut b = MeshBuilder::new();
    for p in [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 2.0, 0.0], [0.0, 2.0, 0.0], [2.5, 1.0, 0.0]] {
        b.add_node(p, 0);
    }
    b.add_element(ElementKind::Tri3, &[0, 1, 4], 0);
    b.add_element(ElementKind::Tri3, &[1, 2, 4], 0);
    b.add_element(ElementKind::Tri3, &[2, 3, 4], 0);
    b.add_element(ElementKind::Tri3, &[3, 0, 4], 0);
    let m = b.build().unwrap();
    assert!(m.corner_area(1) < 0.0, "the folded element must stay folded");
    assert!(m.corner_area(0) > 0.0);
}

#[test]
fn errors_name_the_element_and_line() {
    let mut b = square_two_tris();
    b.add_element(ElementKind::Tri3, &[0, 1, 9], 17);
    let e = b.build().unwrap_err().to_string();
    assert!(e.contains("element 2") && e.contains("line 17") && e.contains("node 9 "), "{e}");
    let mut b = square_two_tris();
    b.add_element(ElementKind::Tri3, &[0, 1, 1], 5);
    let e = b.build().unwrap_err().to_string();
    assert!(e.contains("twice") && e.contains("line 5"), "{e}");
    assert!(matches!(MeshBuilder::new().build(), Err(Error::Empty(_))));
    let mut b = square_two_tris();
    b.add_node([f64::NAN, 0.0, 0.0], 9);
    let e = b.build().unwrap_err().to_string();
    assert!(e.contains("node 4") && e.contains("line 9"), "{e}");
}

#[test]
fn planar_3d_is_mapped_and_non_planar_refused() {
    // a unit square tilted about the x axis by 30 degrees, facing down
    let (s, c) = (30f64.to_radians().sin(), 30f64.to_radians().cos());
    let mut b = MeshBuilder::new();
    for (x, y) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
        b.add_node([x, y * c, -y * s + 3.0], 0);
    }
    b.add_element(ElementKind::Quad4, &[0, 3, 2, 1], 0);
    let m = b.build().unwrap();
    assert!((m.corner_area(0) - 1.0).abs() < 1e-12);
    let mut b = MeshBuilder::new();
    for p in [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.3], [0.0, 1.0, 0.0]] {
        b.add_node(p, 0);
    }
    b.add_element(ElementKind::Quad4, &[0, 1, 2, 3], 0);
    let e = b.build().unwrap_err();
    assert!(matches!(e, Error::NotPlanar { .. }));
    assert!(e.to_string().contains("not planar"), "{e}");
}

#[test]
fn hilbert_index_walks_neighbouring_cells() {
    // the curve visits every cell of a small corner block once, each step to a side neighbour
    let side = 1u32 << HILBERT_ORDER;
    let mut cells: Vec<(u64, u32, u32)> =
        (0..16).flat_map(|x| (0..16).map(move |y| (hilbert_index(x, y), x, y))).collect();
    cells.sort_unstable();
    // the first 256 indices fill the 16 × 16 corner block
    assert_eq!(cells.iter().map(|c| c.0).collect::<Vec<_>>(), (0..256).collect::<Vec<u64>>());
    for w in cells.windows(2) {
        let d = w[0].1.abs_diff(w[1].1) + w[0].2.abs_diff(w[1].2);
        assert_eq!(d, 1, "{:?} -> {:?}", w[0], w[1]);
    }
    assert_eq!(hilbert_index(side - 1, 0), u64::from(side) * u64::from(side) - 1);
}

#[test]
fn spatial_renumbering_is_a_relabelling() {
    use crate::generate::{plate, rand2d, PlateKind};
    for m in [rand2d(3000, 15, 2).unwrap(), plate(PlateKind::Mixed, 2, 3).unwrap()] {
        let (r, perm) = m.renumbered_spatially();
        r.sanity_check().unwrap();
        let mut sorted = perm.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..m.node_count() as u32).collect::<Vec<_>>(), "a permutation");
        let mut inv = vec![0u32; perm.len()];
        for (new, &old) in perm.iter().enumerate() {
            inv[old as usize] = new as u32;
            assert_eq!(r.nodes[new], m.nodes[old as usize]);
            assert_eq!(r.fixed[new], m.fixed[old as usize]);
            assert_eq!(r.role(new), m.role(old as usize));
            assert_eq!(r.is_boundary(new), m.is_boundary(old as usize));
            assert_eq!(r.neighbours(new).len(), m.neighbours(old as usize).len());
        }
        // the same elements, node order within each kept
        let key = |mesh: &Mesh, e: usize, map: &dyn Fn(u32) -> u32| {
            (mesh.kind(e) as u8, mesh.element(e).iter().map(|&i| map(i)).collect::<Vec<u32>>())
        };
        let mut a: Vec<_> = (0..m.element_count()).map(|e| key(&m, e, &|i| inv[i as usize])).collect();
        let mut b: Vec<_> = (0..r.element_count()).map(|e| key(&r, e, &|i| i)).collect();
        a.sort();
        b.sort();
        assert_eq!(a, b);
        assert_eq!(r.edges().iter().filter(|e| e.curved).count(), m.edges().iter().filter(|e| e.curved).count());
        // and it is local: consecutive nodes are close (mean step a few spacings)
        let step: f64 = r.nodes.windows(2).map(|w| w[0].distance(w[1])).sum::<f64>() / (r.node_count() - 1) as f64;
        let before: f64 = m.nodes.windows(2).map(|w| w[0].distance(w[1])).sum::<f64>() / (m.node_count() - 1) as f64;
        assert!(step < 0.5 * before || step < 4.0 * m.mean_edge_length(), "{step} vs {before}");
        // positions go back into the original numbering
        let mut moved = r.clone();
        for p in &mut moved.nodes {
            *p += DVec2::new(0.25, -0.5);
        }
        let mut back = m.clone();
        back.restore_positions(&moved, &perm).unwrap();
        for (p, q) in back.nodes.iter().zip(&m.nodes) {
            assert_eq!(*p, *q + DVec2::new(0.25, -0.5));
        }
        assert!(back.restore_positions(&moved, &perm[1..]).is_err());
    }
}

#[test]
fn planar_3d_is_mapped_at_any_scale() {
    // the tilted unit square scaled by s: its edges keep length s, its angles 90°
    // (the plane fit once overflowed near 1e154 and underflowed near 1e-160)
    let (sn, cs) = (30f64.to_radians().sin(), 30f64.to_radians().cos());
    for s in [1e-300, 1e-160, 1e-100, 1.0, 1e100, 1e200, 1e300] {
        let mut b = MeshBuilder::new();
        for (x, y) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
            b.add_node([x * s, y * cs * s, (3.0 - y * sn) * s], 0);
        }
        b.add_element(ElementKind::Quad4, &[0, 1, 2, 3], 0);
        let m = b.build().unwrap_or_else(|e| panic!("scale {s:e}: {e}"));
        m.sanity_check().unwrap();
        for i in 0..4 {
            // in units of s, so that the test's own squares neither overflow nor underflow
            let (p, q, r) = (m.nodes[i] / s, m.nodes[(i + 1) % 4] / s, m.nodes[(i + 2) % 4] / s);
            assert!(((q - p).length() - 1.0).abs() < 1e-12, "scale {s:e}: edge {i}");
            let cos = (p - q).normalize().dot((r - q).normalize());
            assert!(cos.abs() < 1e-12, "scale {s:e}: corner {i}");
        }
    }
}

#[test]
fn heap_bytes_count_every_array() {
    let m = square_two_tris().build().unwrap();
    let b = m.heap_bytes();
    // 4 positions (64 bytes) and 6 element node ids (24) at the least
    assert!(b >= 4 * 16 + 6 * 4, "{b}");
    assert!(b < 4096, "{b}");
    // 5 edges of 16 bytes, exactly as many as there are
    let edges = m.memory_parts().into_iter().find(|p| p.name.starts_with("edges")).unwrap();
    assert_eq!(edges.bytes, 5 * 16);
    assert_eq!(std::mem::size_of::<Edge>(), 16);
}

#[test]
fn clones_share_the_connectivity() {
    let m = square_two_tris().build().unwrap();
    let mut c = m.clone();
    assert!(Arc::ptr_eq(&m.conn, &c.conn));
    c.nodes[0].x += 0.5;
    assert_eq!(m.nodes[0].x, 0.0, "positions are each clone's own");
    let own: usize = m.memory_parts().iter().filter(|p| !p.shared).map(|p| p.bytes).sum();
    assert_eq!(own, m.nodes.capacity() * 16 + m.fixed.capacity());
}

#[test]
fn orientation_is_stable_under_reversal() {
    // zero-width triangles far from the origin: the total area is rounding noise, and
    // whatever build decides, building the result again must not reverse it back
    let x = -2.777777777777778e88;
    for ys in
        [[0.15825648112409307, -0.4235812421140439, -0.05955188067518902, 0.136728447068453], [0.1, -0.7, 0.45, 0.5]]
    {
        let mut b = MeshBuilder::new();
        for y in ys {
            b.add_node([x, y, 0.0], 0);
        }
        b.add_element(ElementKind::Tri3, &[0, 1, 2], 0);
        b.add_element(ElementKind::Tri3, &[1, 3, 2], 0);
        let once = b.build().unwrap();
        let mut again = MeshBuilder::new();
        for p in &once.nodes {
            again.add_node([p.x, p.y, 0.0], 0);
        }
        for e in 0..once.element_count() {
            again.add_element(once.kind(e), once.element(e), 0);
        }
        let twice = again.build().unwrap();
        for e in 0..once.element_count() {
            assert_eq!(once.element(e), twice.element(e), "{ys:?}: element {e}");
        }
    }
}

#[test]
fn quadratic_edges_know_mid_nodes_and_curvature() {
    // one 6-node triangle with its 0-1 edge bowed out
    let mut b = MeshBuilder::new();
    for p in [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0], [1.0, -0.3, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]] {
        b.add_node(p, 0);
    }
    b.add_element(ElementKind::Tri6, &[0, 1, 2, 3, 4, 5], 0);
    let m = b.build().unwrap();
    m.sanity_check().unwrap();
    let curved: Vec<_> = m.edges().iter().filter(|e| e.curved).collect();
    assert_eq!(curved.len(), 1);
    assert_eq!(curved[0].mid, 3);
    assert!(m.is_on_curved_boundary(0) && !m.is_on_curved_boundary(2));
    assert_eq!(m.role(3), NodeRole::Mid);
    assert_eq!(m.neighbours(0).len(), 2, "mid nodes are not neighbours");
}

/// The smoothers' read-ahead (`SmoothMesh::read_ahead`) stays within the mesh's arrays: it
/// answers for every node of quadratic and mixed meshes (mid-side, boundary and fixed
/// nodes included) at every stage and beyond, and reads nothing for a node past the end.
#[test]
fn read_ahead_reads_every_node_at_every_stage() {
    use crate::generate::{plate, PlateKind};
    use crate::smooth::SmoothMesh;
    for m in [square_two_tris().build().unwrap(), plate(PlateKind::Mixed, 2, 2).unwrap(), plate(PlateKind::Tri, 1, 2).unwrap()] {
        let read = (0..m.node_count()).flat_map(|n| (0..8).map(move |stage| (n, stage)));
        let all = read.fold(0, |a, (n, stage)| a ^ m.read_ahead(n, stage));
        std::hint::black_box(all);
        for n in [m.node_count(), m.node_count() + 1, usize::MAX] {
            assert_eq!((0..8).map(|stage| m.read_ahead(n, stage)).collect::<Vec<_>>(), [0; 8], "node {n}");
        }
    }
}
