//! The flat (CSR-style) topology, built once: node → elements, node → neighbours, edges.

use crate::error::{listed, Error, Result};

use super::builder::FileNames;
use super::*;

/// The topology of the mesh's elements; an edge of more than two elements, or two that
/// disagree on its mid-side node, is refused naming them as the file does (`names`).
pub(super) fn build_topology(mesh: &Mesh, names: FileNames<'_>) -> Result<Topology> {
    let n = mesh.nodes.len();
    let ne = mesh.conn.kinds.len();
    // node -> elements (counting sort)
    let mut count = vec![0u32; n + 1];
    for e in 0..ne {
        for &i in mesh.element(e) {
            count[i as usize + 1] += 1;
        }
    }
    for i in 0..n {
        count[i + 1] += count[i];
    }
    let node_elem_start = count.clone();
    let mut node_elems = vec![0u32; *count.last().unwrap() as usize];
    let mut fill = count;
    for e in 0..ne {
        for &i in mesh.element(e) {
            node_elems[fill[i as usize] as usize] = e as u32;
            fill[i as usize] += 1;
        }
    }
    // roles
    let mut role = vec![NodeRole::Unused; n];
    for e in 0..ne {
        let k = mesh.conn.kinds[e];
        for (j, &i) in mesh.element(e).iter().enumerate() {
            let r = if j < k.corners() {
                NodeRole::Corner
            } else if j < 2 * k.corners() {
                NodeRole::Mid
            } else {
                NodeRole::Centre
            };
            let slot = &mut role[i as usize];
            *slot = match (*slot, r) {
                (NodeRole::Unused, r) => r,
                (NodeRole::Corner, _) | (_, NodeRole::Corner) => NodeRole::Corner,
                (s, _) => s,
            };
        }
    }
    // edges: every corner edge (a, b), a < b, of every element, as (b, element·4 + local
    // edge) filed under a by a counting sort (8 bytes a use: the largest temporary of
    // the topology, 48 MB for 2M triangles), then each node's short list sorted, so that
    // edges come out ordered by (a, b) with their elements in increasing order; they are
    // counted first so that their array is allocated once, exactly.
    if ne >= 1 << 30 {
        return Err(Error::TooLarge(format!("the mesh has {ne} elements; smoothlab takes at most 2^30 (1073741824)")));
    }
    let corner_edges = |e: usize| {
        let ids = mesh.element(e);
        let c = mesh.conn.kinds[e].corners();
        (0..c).map(move |i| (ids[i].min(ids[(i + 1) % c]), ids[i].max(ids[(i + 1) % c]), i as u32))
    };
    let mut use_start = vec![0u32; n + 1];
    for e in 0..ne {
        for (a, _, _) in corner_edges(e) {
            use_start[a as usize + 1] += 1;
        }
    }
    for i in 0..n {
        use_start[i + 1] += use_start[i];
    }
    let mut uses = vec![(0u32, 0u32); use_start[n] as usize];
    {
        let mut fill = use_start.clone();
        for e in 0..ne {
            for (a, b, i) in corner_edges(e) {
                uses[fill[a as usize] as usize] = (b, (e as u32) << 2 | i);
                fill[a as usize] += 1;
            }
        }
    }
    let mut edge_count = 0usize;
    for a in 0..n {
        let recs = &mut uses[use_start[a] as usize..use_start[a + 1] as usize];
        recs.sort_unstable();
        edge_count += recs.iter().enumerate().filter(|&(k, r)| k == 0 || recs[k - 1].0 != r.0).count();
    }
    let mid_of = |r: u32| {
        let e = (r >> 2) as usize;
        mesh.conn.kinds[e].mid((r & 3) as usize).map(|m| mesh.element(e)[m]).unwrap_or(NONE)
    };
    let line = |e: u32| names.line(e as usize);
    let number = |e: u32| names.element(e as usize);
    let node = |i: u32| names.node(i as usize);
    let mut edges = Vec::with_capacity(edge_count);
    for a in 0..n {
        let recs = &uses[use_start[a] as usize..use_start[a + 1] as usize];
        let mut i = 0;
        while i < recs.len() {
            let mut j = i + 1;
            while j < recs.len() && recs[j].0 == recs[i].0 {
                j += 1;
            }
            let (a, b, e0, m0) = (a as u32, recs[i].0, recs[i].1 >> 2, mid_of(recs[i].1));
            if j - i > 2 {
                let third = recs[i + 2].1 >> 2;
                return Err(Error::element(
                    number(third),
                    line(third),
                    format!(
                        "edge between nodes {} and {} is shared by {} elements ({}); a 2D mesh edge belongs to one or two",
                        node(a),
                        node(b),
                        j - i,
                        listed(recs[i..j].iter().map(|r| number(r.1 >> 2)), j - i)
                    ),
                ));
            }
            if j - i == 2 && mid_of(recs[i + 1].1) != m0 {
                let (m1, other) = (mid_of(recs[i + 1].1), recs[i + 1].1 >> 2);
                let desc = |m: u32| if m == NONE { "none".to_string() } else { node(m).to_string() };
                return Err(Error::element(
                    number(other),
                    line(other),
                    format!(
                        "shares the edge between nodes {} and {} with element {} but they disagree on its mid-side node ({} vs {})",
                        node(a),
                        node(b),
                        number(e0),
                        desc(m1),
                        desc(m0)
                    ),
                ));
            }
            edges.push(Edge { a, b, mid: m0, boundary: j - i == 1, curved: false });
            i = j;
        }
    }
    debug_assert_eq!(edges.len(), edge_count);
    drop(uses);
    drop(use_start);
    // boundary flags and curved boundary edges
    let mut boundary = vec![false; n];
    let mut on_curved = vec![false; n];
    for e in edges.iter_mut() {
        if e.is_boundary() {
            boundary[e.a as usize] = true;
            boundary[e.b as usize] = true;
            if e.mid != NONE {
                boundary[e.mid as usize] = true;
                let (pa, pb, pm) = (mesh.nodes[e.a as usize], mesh.nodes[e.b as usize], mesh.nodes[e.mid as usize]);
                let chord = pb - pa;
                let off = (pm - pa).perp_dot(chord).abs() / chord.length().max(f64::MIN_POSITIVE);
                if off > 1e-6 * chord.length() {
                    e.curved = true;
                    on_curved[e.a as usize] = true;
                    on_curved[e.b as usize] = true;
                    on_curved[e.mid as usize] = true;
                }
            }
        }
    }
    // node -> neighbour corners via edges (CSR)
    let mut deg = vec![0u32; n + 1];
    for e in &edges {
        deg[e.a as usize + 1] += 1;
        deg[e.b as usize + 1] += 1;
    }
    for i in 0..n {
        deg[i + 1] += deg[i];
    }
    let node_nbr_start = deg.clone();
    let mut node_nbrs = vec![0u32; *deg.last().unwrap() as usize];
    let mut fill = deg;
    for e in &edges {
        node_nbrs[fill[e.a as usize] as usize] = e.b;
        fill[e.a as usize] += 1;
        node_nbrs[fill[e.b as usize] as usize] = e.a;
        fill[e.b as usize] += 1;
    }
    let kinds_present = KindsPresent {
        triangles: mesh.conn.kinds.iter().any(|k| k.is_triangle()),
        quads: mesh.conn.kinds.iter().any(|k| k.is_quad()),
        quadratic: mesh.conn.kinds.iter().any(|k| k.is_quadratic()),
    };
    Ok(Topology {
        node_elem_start,
        node_elems,
        node_nbr_start,
        node_nbrs,
        edges,
        role,
        boundary,
        on_curved,
        kinds_present,
    })
}

/// Refuses a corner node off the boundary whose elements form more than one fan: sheets
/// of a surface that meet at the node alone (two spheres touching at a vertex), where
/// smoothing would pull it from both — as an edge of three elements is refused. On the
/// boundary such a node is fixed, and harmless. Asked of surfaces: in a plane two fans
/// round an inner node overlap, and checking every node of a large planar mesh costs a
/// third of its loading (its elements' corners read in the nodes' order).
pub(super) fn check_fans(mesh: &Mesh, names: FileNames<'_>) -> Result<()> {
    for v in 0..mesh.node_count() {
        if mesh.is_boundary(v) || mesh.role(v) != NodeRole::Corner {
            continue;
        }
        if let Some((e0, e1)) = second_fan(mesh, v as u32, mesh.node_elements(v)) {
            return Err(Error::element(
                names.element(e1 as usize),
                names.line(e1 as usize),
                format!(
                    "meets element {} only at node {}: the elements round the node form separate fans that share no edge (a non-manifold vertex); the elements round an inner node of a surface form one",
                    names.element(e0 as usize),
                    names.node(v)
                ),
            ));
        }
    }
    Ok(())
}

/// Whether the elements `elems` round corner node `v` form more than one fan (elements
/// joined across the edges they share at `v`): then an element of the first fan and one
/// of another. The elements of an edge-manifold mesh share an edge `v`–`w` where they
/// share the corner `w` beside `v`.
fn second_fan(mesh: &Mesh, v: u32, elems: &[u32]) -> Option<(u32, u32)> {
    const MAX: usize = 64;
    if elems.len() < 2 || elems.len() > MAX {
        return None; // a star of more than 64 elements is not looked at
    }
    let mut sides = [[0u32; 2]; MAX];
    for (s, &e) in sides.iter_mut().zip(elems) {
        let ids = mesh.element(e as usize);
        let c = mesh.conn.kinds[e as usize].corners();
        let i = ids[..c].iter().position(|&x| x == v)?;
        *s = [ids[(i + 1) % c], ids[(i + c - 1) % c]];
    }
    let m = elems.len();
    let mut reached = 1u64;
    let mut stack = [0usize; MAX];
    let mut top = 1;
    while top > 0 {
        top -= 1;
        let k = stack[top];
        for j in 0..m {
            if reached & (1 << j) == 0 && sides[j].iter().any(|w| sides[k].contains(w)) {
                reached |= 1 << j;
                stack[top] = j;
                top += 1;
            }
        }
    }
    (reached.count_ones() as usize != m).then(|| (elems[0], elems[(!reached).trailing_zeros() as usize]))
}
