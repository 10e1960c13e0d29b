//! The laboratory: old versus new, side by side. The playground page's state in plain
//! Rust (no web types; the wasm layer and the CLI's `render` both call it): the
//! original mesh, and one copy per side — the OLD max-min objective (Freitag 1997, left)
//! and the NEW smooth objective (Chen, Tristano & Kwok 2003, right) — that the page
//! smooths, perturbs and drags side by side.

pub mod sample;
pub mod views;

use glam::DVec2;
use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::generate::perturb;
use crate::io::{write_string, Format, WriteOptions};
use crate::mesh::Mesh;
use crate::objective::{objective, Objective, ObjectiveKind};
use crate::optimize::SolveResult;
use crate::quality::{mesh_stats, MeshStats};
use crate::smooth::{solve_node, Order, PassRecord, SmoothOptions, Smoother, Strategy};

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
    #[cfg(test)]
    pub const BOTH: [Side; 2] = [Side::Old, Side::New];
    fn index(self) -> usize {
        self as usize
    }
    /// The objective a side smooths with: Chen et al.'s "previous method" (max-min α/β,
    /// Freitag's active-set ascent) or their new smooth one (Fletcher–Reeves).
    pub fn objective_kind(self) -> ObjectiveKind {
        match self {
            Side::Old => ObjectiveKind::Old,
            Side::New => ObjectiveKind::New,
        }
    }
}

/// The page's strategy menu, in the words of [`Strategy`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum StrategyChoice {
    Laplace,
    Smart,
    Opt,
    C1,
    C2,
    C3,
    Rules,
}

impl From<StrategyChoice> for Strategy {
    fn from(s: StrategyChoice) -> Self {
        match s {
            StrategyChoice::Laplace => Strategy::Laplace,
            StrategyChoice::Smart => Strategy::Smart,
            StrategyChoice::Opt => Strategy::Opt,
            StrategyChoice::C1 => Strategy::C1,
            StrategyChoice::C2 => Strategy::C2,
            StrategyChoice::C3 => Strategy::C3,
            StrategyChoice::Rules => Strategy::Rules,
        }
    }
}

/// The page's node-order menu.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum OrderChoice {
    Input,
    Priority,
}

/// The shared controls of the page (both sides smooth with the same settings).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Settings {
    pub strategy: StrategyChoice,
    /// Freitag's threshold angle θ_t, degrees.
    pub threshold_deg: f64,
    pub order: OrderChoice,
    /// Solver iterations per optimization call.
    pub max_iter: u32,
}

impl Default for Settings {
    /// Chen's algorithm: rules, priority order, 3 iterations per call; θ_t = 30°.
    fn default() -> Self {
        Settings { strategy: StrategyChoice::Rules, threshold_deg: 30.0, order: OrderChoice::Priority, max_iter: 3 }
    }
}

impl Settings {
    /// The drivers' options (checked).
    pub fn smooth_options(&self) -> Result<SmoothOptions> {
        if self.max_iter == 0 || self.max_iter > 1000 {
            return Err(Error::invalid(format!("{} solver iterations: give 1 to 1000", self.max_iter)));
        }
        let o = SmoothOptions::default()
            .with_strategy(self.strategy.into())
            .with_order(match self.order {
                OrderChoice::Input => Order::Input,
                OrderChoice::Priority => Order::Priority,
            })
            .with_threshold_deg(self.threshold_deg)
            .with_max_iter(self.max_iter);
        o.validate()?;
        Ok(o)
    }
}

/// One panel: its current mesh, its objective and driver, and its passes since the last reset.
pub struct Panel {
    pub mesh: Mesh,
    pub objective: Box<dyn Objective>,
    smoother: Smoother,
    pub records: Vec<PassRecord>,
}

impl Panel {
    fn new(side: Side, mesh: Mesh, options: SmoothOptions) -> Result<Self> {
        Ok(Panel {
            mesh,
            objective: objective(side.objective_kind()),
            smoother: Smoother::new(options)?,
            records: Vec::new(),
        })
    }
}

/// What a panel's statistics table shows: the mesh now and the work done since the last reset.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PanelStats {
    pub side: Side,
    #[serde(flatten)]
    pub mesh: MeshStats,
    pub passes: usize,
    pub laplacian_moves: u64,
    pub optimization_calls: u64,
    pub solver_iterations: u64,
    /// Smoothing time summed over the passes, milliseconds by the caller's clock.
    pub time_ms: f64,
}

/// The page's state: see the module docs.
pub struct Playground {
    original: Mesh,
    settings: Settings,
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
        let settings = Settings::default();
        let o = settings.smooth_options()?;
        Ok(Playground {
            panels: [Panel::new(Side::Old, mesh.clone(), o)?, Panel::new(Side::New, mesh.clone(), o)?],
            original: mesh,
            settings,
        })
    }

    #[cfg(test)]
    pub fn settings(&self) -> Settings {
        self.settings
    }

    /// New settings for the next passes (the meshes stay as they are).
    pub fn set_settings(&mut self, settings: Settings) -> Result<()> {
        let o = settings.smooth_options()?;
        for p in &mut self.panels {
            p.smoother = Smoother::new(o)?;
        }
        self.settings = settings;
        Ok(())
    }

    /// One smoothing pass on both panels; `clock` gives milliseconds (the core reads no time).
    pub fn step(&mut self, clock: &dyn Fn() -> f64) -> [PassRecord; 2] {
        self.panels.each_mut().map(|p| {
            let mut rec = p.smoother.pass(&mut p.mesh, p.objective.as_ref(), clock);
            rec.pass = p.records.len() as u32 + 1;
            p.records.push(rec.clone());
            rec
        })
    }

    /// The original mesh perturbed ([`perturb`]: `amount` mean edge lengths, seeded);
    /// both panels start again from it.
    pub fn perturb(&mut self, amount: f64, seed: u64) -> Result<()> {
        self.original = perturb(&self.original, amount, seed)?;
        self.reset();
        Ok(())
    }

    /// A panel's current mesh as the text of a `.msh` (2.2) or `.vtk` file.
    pub fn export(&self, side: Side, format: Format) -> Result<String> {
        write_string(&self.panel(side).mesh, format, &WriteOptions::default())
    }

    /// Solves one node of a panel's mesh with the solver's history (for the level-set view),
    /// without moving it.
    pub fn solve_node(&self, side: Side, node: usize) -> Result<SolveResult> {
        let p = self.panel(side);
        solve_node(&p.mesh, node, p.objective.as_ref(), &self.settings.smooth_options()?)
    }

    pub fn original(&self) -> &Mesh {
        &self.original
    }

    pub fn panel(&self, side: Side) -> &Panel {
        &self.panels[side.index()]
    }

    /// Statistics of a panel's current mesh.
    pub fn stats(&self, side: Side) -> PanelStats {
        let p = self.panel(side);
        let r = &p.records;
        PanelStats {
            side,
            mesh: mesh_stats(&p.mesh),
            passes: r.len(),
            laplacian_moves: r.iter().map(|r| r.laplacian_moves as u64).sum(),
            optimization_calls: r.iter().map(|r| r.optimization_calls as u64).sum(),
            solver_iterations: r.iter().map(|r| r.solver_iterations as u64).sum(),
            time_ms: r.iter().map(|r| r.elapsed_ms).sum(),
        }
    }

    /// Both panels back to the original mesh, their records cleared.
    pub fn reset(&mut self) {
        let o = self.settings.smooth_options().expect("the settings were checked when set");
        for p in &mut self.panels {
            p.mesh = self.original.clone();
            p.records.clear();
            p.smoother = Smoother::new(o).expect("the settings were checked when set");
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
    use crate::lab::sample::Sample;

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

    fn no_clock() -> f64 {
        0.0
    }

    #[test]
    fn three_passes_untangle_the_tangled_plate_on_the_new_side() {
        let mut pg = Playground::new(Sample::PlateTriTangled.generate().unwrap()).unwrap();
        let start = pg.stats(Side::New).mesh.inverted;
        assert!(start > 0);
        let mut last = None;
        for _ in 0..3 {
            last = Some(pg.step(&no_clock));
        }
        let [old, new] = last.unwrap();
        assert_eq!((old.pass, new.pass), (3, 3));
        assert_eq!(new.inverted, 0, "Chen et al. untangle the perturbed plate in 3 passes");
        let s = pg.stats(Side::New);
        assert_eq!(s.mesh.inverted, 0);
        assert_eq!(s.passes, 3);
        assert!(s.optimization_calls > 0);
        assert_eq!(pg.stats(Side::Old).passes, 3);
        pg.reset();
        assert_eq!(pg.stats(Side::New).passes, 0);
        assert_eq!(pg.stats(Side::New).mesh.inverted, start);
    }

    #[test]
    fn settings_are_checked_and_kept_on_error() {
        let mut pg = Playground::new(Sample::StarRegular.generate().unwrap()).unwrap();
        let bad = Settings { threshold_deg: 0.0, ..Settings::default() };
        assert!(pg.set_settings(bad).is_err());
        assert!(pg.set_settings(Settings { max_iter: 0, ..Settings::default() }).is_err());
        assert_eq!(pg.settings(), Settings::default());
        let s: Settings =
            serde_json::from_str(r#"{"strategy":"c2","threshold_deg":10,"order":"input","max_iter":5}"#).unwrap();
        pg.set_settings(s).unwrap();
        assert_eq!(pg.settings().strategy, StrategyChoice::C2);
        assert!(serde_json::from_str::<Settings>(
            r#"{"strategy":"magic","threshold_deg":10,"order":"input","max_iter":5}"#
        )
        .is_err());
    }

    #[test]
    fn node_solve_moves_towards_better_and_leaves_the_mesh() {
        let pg = Playground::new(Sample::StarRegular.generate().unwrap()).unwrap();
        let free = pg.original().node_count() - 1;
        let before = pg.panel(Side::New).mesh.nodes.clone();
        let new = pg.solve_node(Side::New, free).unwrap();
        assert!(new.value <= new.value0 && !new.history.is_empty());
        let old = pg.solve_node(Side::Old, free).unwrap();
        assert!(old.value >= old.value0, "max-min: the minimum never drops");
        assert_eq!(pg.panel(Side::New).mesh.nodes, before);
        assert!(pg.solve_node(Side::New, 0).is_err(), "a fixed node has no solve");
    }

    #[test]
    fn perturb_replaces_the_original_and_resets() {
        let mut pg = Playground::new(Sample::PlateQuad.generate().unwrap()).unwrap();
        pg.step(&no_clock);
        pg.perturb(1.0, 7).unwrap();
        assert!(pg.stats(Side::Old).mesh.inverted > 0);
        assert_eq!(pg.stats(Side::Old).passes, 0);
        assert_eq!(pg.panel(Side::New).mesh.nodes, pg.original().nodes);
        assert!(pg.perturb(f64::NAN, 1).is_err());
    }

    #[test]
    fn export_writes_the_panel_mesh_that_reads_back() {
        let mut pg = Playground::new(Sample::PlateMixedTangled.generate().unwrap()).unwrap();
        pg.step(&no_clock);
        for format in [Format::Msh, Format::Vtk] {
            let text = pg.export(Side::New, format).unwrap();
            let back = crate::io::read_str(&text, format).unwrap();
            assert_eq!(back.node_count(), pg.panel(Side::New).mesh.node_count());
            assert_eq!(back.nodes, pg.panel(Side::New).mesh.nodes, "{format:?} keeps the smoothed positions");
            assert_ne!(back.nodes, pg.panel(Side::Old).mesh.nodes);
        }
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
