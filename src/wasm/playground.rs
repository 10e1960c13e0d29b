//! The playground's state in plain Rust (no web types, so it is tested natively): the
//! original mesh, and one copy per side — the OLD max-min objective (Freitag 1997, left)
//! and the NEW smooth objective (Chen, Tristano & Kwok 2003, right) — that the page
//! smooths, perturbs and drags side by side.

use glam::DVec2;
use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::quality::{mesh_stats, MeshStats};

/// Node count above which the page refuses a mesh: the playground holds three copies and
/// draws every element each frame.
pub const MAX_NODES: usize = 1_000_000;

/// The two panels of the page.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Side {
    /// Freitag's max-min objective (the "previous method" of Chen et al.).
    Old,
    /// Chen, Tristano & Kwok's smooth objective.
    New,
}

impl Side {
    pub const BOTH: [Side; 2] = [Side::Old, Side::New];
    fn index(self) -> usize {
        self as usize
    }
}

/// One panel: its current mesh and what has been done to it since the last reset.
#[derive(Clone, Debug)]
pub struct Panel {
    pub mesh: Mesh,
}

/// What a panel's statistics table shows.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PanelStats {
    pub side: Side,
    #[serde(flatten)]
    pub mesh: MeshStats,
}

/// The page's state: see the module docs.
#[derive(Clone, Debug)]
pub struct Playground {
    original: Mesh,
    panels: [Panel; 2],
}

impl Playground {
    /// A playground on `mesh`: both panels start from it.
    pub fn new(mesh: Mesh) -> Result<Self> {
        if mesh.node_count() > MAX_NODES {
            return Err(Error::TooLarge(format!(
                "the mesh has {} nodes; the page takes at most {MAX_NODES} (use the command-line tool)",
                mesh.node_count()
            )));
        }
        let panel = Panel { mesh: mesh.clone() };
        Ok(Playground { panels: [panel.clone(), panel], original: mesh })
    }

    pub fn original(&self) -> &Mesh {
        &self.original
    }

    pub fn panel(&self, side: Side) -> &Panel {
        &self.panels[side.index()]
    }

    /// Statistics of a panel's current mesh.
    pub fn stats(&self, side: Side) -> PanelStats {
        PanelStats { side, mesh: mesh_stats(&self.panel(side).mesh) }
    }

    /// Both panels back to the original mesh.
    pub fn reset(&mut self) {
        for p in &mut self.panels {
            p.mesh = self.original.clone();
        }
    }

    /// Moves a free node to `to` on both panels' current meshes (the mouse drag); its
    /// mid-side nodes follow. Fixed nodes, mid-side nodes and unknown nodes are refused.
    pub fn move_node(&mut self, node: usize, to: DVec2) -> Result<()> {
        let m = &self.original;
        if node >= m.node_count() {
            return Err(Error::node(node, None, format!("no such node: the mesh has {} nodes", m.node_count())));
        }
        if !m.is_free(node) {
            return Err(Error::node(node, None, "is fixed or a mid-side node, so it cannot be dragged"));
        }
        if !to.is_finite() {
            return Err(Error::invalid(format!("cannot move node {node} to a non-finite position {to}")));
        }
        for p in &mut self.panels {
            p.mesh.nodes[node] = to;
            p.mesh.follow_mid_nodes(node);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::wasm::sample::Sample;

    #[test]
    fn panels_start_equal_and_reset_restores_them() {
        let mut pg = Playground::new(Sample::PlateTriTangled.generate().unwrap()).unwrap();
        let before = pg.stats(Side::Old);
        assert_eq!(before.mesh, pg.stats(Side::New).mesh);
        assert!(before.mesh.inverted > 0);
        let free = (0..pg.original().node_count()).find(|&n| pg.original().is_free(n)).unwrap();
        pg.move_node(free, DVec2::new(0.9, 0.9)).unwrap();
        for s in Side::BOTH {
            assert_eq!(pg.panel(s).mesh.nodes[free], DVec2::new(0.9, 0.9));
        }
        pg.reset();
        assert_eq!(pg.stats(Side::Old), before);
        assert_eq!(pg.panel(Side::New).mesh.nodes, pg.original().nodes);
    }

    #[test]
    fn dragging_refuses_fixed_unknown_and_non_finite() {
        let mut pg = Playground::new(Sample::StarRegular.generate().unwrap()).unwrap();
        let n = pg.original().node_count();
        let e = pg.move_node(0, DVec2::ZERO).unwrap_err().to_string();
        assert!(e.contains("node 0") && e.contains("fixed"), "{e}");
        let e = pg.move_node(n, DVec2::ZERO).unwrap_err().to_string();
        assert!(e.contains("no such node"), "{e}");
        assert!(pg.move_node(n - 1, DVec2::new(f64::NAN, 0.0)).is_err());
        assert_eq!(pg.panel(Side::Old).mesh.nodes, pg.original().nodes, "a refused move changes nothing");
    }

    #[test]
    fn quadratic_mid_nodes_follow_a_drag() {
        let mut pg = Playground::new(Sample::PlateQuadratic.generate().unwrap()).unwrap();
        let m = pg.original().clone();
        let free = (0..m.node_count()).find(|&n| m.is_free(n)).unwrap();
        let to = m.nodes[free] + DVec2::new(0.01, -0.02);
        pg.move_node(free, to).unwrap();
        let moved = &pg.panel(Side::New).mesh;
        for e in m.edges() {
            if e.mid != crate::mesh::NONE && (e.a as usize == free || e.b as usize == free) && !e.curved {
                let mid = 0.5 * (moved.nodes[e.a as usize] + moved.nodes[e.b as usize]);
                assert!(moved.nodes[e.mid as usize].distance(mid) < 1e-12);
            }
        }
    }
}
