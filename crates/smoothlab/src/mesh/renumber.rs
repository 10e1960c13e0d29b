//! Renumbering along a Hilbert curve (nodes near in the plane near in memory) and back.

use std::sync::Arc;

use glam::DVec2;

use crate::error::{Error, Result};

use super::*;

impl Mesh {
    /// The same mesh with its nodes renumbered along a Hilbert curve, so that nodes near
    /// each other in the plane are near each other in memory (the smoothers then find a
    /// node's star and neighbours in cache), and its elements sorted by their first node
    /// in the new numbering. Returns the mesh and the permutation `perm`, `perm[new] = old`.
    ///
    /// Positions, fixed flags, element kinds and node orders within elements are kept; node
    /// and element *numbers* change, so a renumbered mesh is for computing on: smooth it,
    /// then put the positions back into the original numbering with
    /// [`restore_positions`](Self::restore_positions). Nodes no element uses go last.
    pub fn renumbered_spatially(&self) -> (Mesh, Vec<u32>) {
        let n = self.nodes.len();
        let (lo, hi) = self.bounds();
        let grid = HilbertGrid::over(lo, hi);
        let key = |i: usize| -> u64 {
            if self.conn.topo.role[i] == NodeRole::Unused {
                return u64::MAX;
            }
            grid.key(self.nodes[i])
        };
        let mut order: Vec<(u64, u32)> = (0..n).map(|i| (key(i), i as u32)).collect();
        order.sort_unstable();
        let perm: Vec<u32> = order.iter().map(|&(_, i)| i).collect();
        drop(order);
        let mut inv = vec![0u32; n];
        for (new, &old) in perm.iter().enumerate() {
            inv[old as usize] = new as u32;
        }
        let ne = self.conn.kinds.len();
        let mut elems: Vec<(u32, u32)> = (0..ne).map(|e| (inv[self.element(e)[0] as usize], e as u32)).collect();
        elems.sort_unstable();
        let mut kinds = Vec::with_capacity(ne);
        let mut elem_start = Vec::with_capacity(ne + 1);
        let mut elem_nodes = Vec::with_capacity(self.conn.elem_nodes.len());
        elem_start.push(0);
        for &(_, e) in &elems {
            kinds.push(self.conn.kinds[e as usize]);
            elem_nodes.extend(self.element(e as usize).iter().map(|&i| inv[i as usize]));
            elem_start.push(elem_nodes.len() as u32);
        }
        let mut mesh = Mesh {
            nodes: perm.iter().map(|&i| self.nodes[i as usize]).collect(),
            fixed: perm.iter().map(|&i| self.fixed[i as usize]).collect(),
            conn: Arc::new(Connectivity { kinds, elem_start, elem_nodes, topo: Topology::default(), reversed: Vec::new() }),
            plane: self.plane,
            // a working copy: its nodes go back to `self`, which writes them
            loaded_3d: None,
            target: None,
            given_fixed: None,
            sliding: None,
        };
        // The same elements under other numbers: every check that passed for `self`
        // passes here, so building the topology cannot fail.
        let topo = build_topology(&mesh, super::builder::FileNames::NONE).expect("renumbering keeps a valid topology");
        mesh.connectivity_mut().topo = topo;
        (mesh, perm)
    }

    /// The connectivity of a mesh being built, not shared yet.
    pub(super) fn connectivity_mut(&mut self) -> &mut Connectivity {
        Arc::get_mut(&mut self.conn).expect("a mesh being built shares nothing")
    }

    /// Copies the node positions of `renumbered`, a mesh made by
    /// [`renumbered_spatially`](Self::renumbered_spatially) from this one (and smoothed,
    /// say), back into this mesh's numbering: `self.nodes[perm[i]] = renumbered.nodes[i]`.
    pub fn restore_positions(&mut self, renumbered: &Mesh, perm: &[u32]) -> Result<()> {
        let n = self.nodes.len();
        if renumbered.nodes.len() != n || perm.len() != n {
            return Err(Error::invalid(format!(
                "cannot restore positions: {} nodes here, {} in the renumbered mesh, {} in the permutation",
                n,
                renumbered.nodes.len(),
                perm.len()
            )));
        }
        if let Some(&bad) = perm.iter().find(|&&p| p as usize >= n) {
            return Err(Error::invalid(format!("cannot restore positions: the permutation names node {bad}")));
        }
        for (i, &old) in perm.iter().enumerate() {
            self.nodes[old as usize] = renumbered.nodes[i];
        }
        Ok(())
    }
}

/// The cells of a Hilbert curve of order [`HILBERT_ORDER`] laid over a bounding box's
/// square: [`key`](Self::key) numbers points along the curve, so sorting by it puts points
/// near in the plane near in the order ([`Mesh::renumbered_spatially`], and generators
/// that number their nodes so, `generate::rand2d_spatial`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct HilbertGrid {
    lo: DVec2,
    scale: f64,
}

impl HilbertGrid {
    /// The grid over the box from `lo` to `hi`.
    pub(crate) fn over(lo: DVec2, hi: DVec2) -> HilbertGrid {
        let size = (hi - lo).max_element();
        let cells = (1u32 << HILBERT_ORDER) as f64;
        HilbertGrid { lo, scale: if size > 0.0 && size.is_finite() { (cells - 1.0) / size } else { 0.0 } }
    }

    /// The index along the curve of the cell holding `p` (points outside go to the nearest cell).
    pub(crate) fn key(&self, p: DVec2) -> u64 {
        let cells = (1u32 << HILBERT_ORDER) as f64;
        let q = ((p - self.lo) * self.scale).clamp(DVec2::ZERO, DVec2::splat(cells - 1.0));
        hilbert_index(q.x as u32, q.y as u32)
    }
}

/// Bits per axis of the Hilbert curve used by [`Mesh::renumbered_spatially`]: a
/// 65 536 × 65 536 grid over the mesh's bounding square.
pub(super) const HILBERT_ORDER: u32 = 16;

/// Index of cell `(x, y)` along the Hilbert curve of order [`HILBERT_ORDER`] (the classic
/// quadrant-rotation algorithm): consecutive indices are neighbouring cells.
pub(super) fn hilbert_index(mut x: u32, mut y: u32) -> u64 {
    let n = 1u32 << HILBERT_ORDER;
    let mut d = 0u64;
    let mut s = n / 2;
    while s > 0 {
        let rx = u32::from(x & s > 0);
        let ry = u32::from(y & s > 0);
        d += u64::from(s) * u64::from(s) * u64::from((3 * rx) ^ ry);
        // rotate the quadrant so the curve continues
        if ry == 0 {
            if rx == 1 {
                x = n - 1 - x;
                y = n - 1 - y;
            }
            std::mem::swap(&mut x, &mut y);
        }
        s /= 2;
    }
    d
}
