//! What a lecturer does to the pictures by hand: zoom and pan the meshes and the level
//! sets, undo a move, and smooth one chosen node by one solver call.

use glam::DVec2;

use super::views::{Canvas, LEVEL_SET_MARGIN};
use super::{Playground, Side};
use smoothlab::error::{Error, Result};
use smoothlab::objective::Star;
use smoothlab::optimize::SolveResult;
use smoothlab_render::{feasible_bounds, level_set_view, Frame, View, ZoomPan};

/// Least and greatest magnification of a zoomed view: beyond these a picture shows
/// nothing more (one element over the canvas, or the mesh as a dot).
pub const ZOOM_RANGE: (f64, f64) = (0.5, 1000.0);

/// The part of a star's box a level-set view shows, as fractions of that box (`0..1` on
/// each axis: all of it). Fractions, so both sides, whose stars differ once smoothed,
/// show the same part of their own star.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LevelWindow {
    pub lo: DVec2,
    pub hi: DVec2,
}

impl Default for LevelWindow {
    fn default() -> Self {
        LevelWindow { lo: DVec2::ZERO, hi: DVec2::ONE }
    }
}

impl LevelWindow {
    /// The window inside the world box `b`.
    pub fn within(&self, b: (DVec2, DVec2)) -> (DVec2, DVec2) {
        let size = b.1 - b.0;
        (b.0 + self.lo * size, b.0 + self.hi * size)
    }
    /// Magnified `factor` times about the fraction `at`, which stays where it is; kept
    /// within [`ZOOM_RANGE`].
    pub fn zoomed_at(self, at: DVec2, factor: f64) -> Self {
        let width = (self.hi.x - self.lo.x) / factor;
        let in_range = (1.0 / ZOOM_RANGE.1..=1.0 / ZOOM_RANGE.0).contains(&width);
        if !(factor.is_finite() && factor > 0.0 && at.is_finite() && in_range) {
            return self;
        }
        LevelWindow { lo: at + (self.lo - at) / factor, hi: at + (self.hi - at) / factor }
    }
    /// Moved by `delta` (fractions of the box).
    pub fn shifted(self, delta: DVec2) -> Self {
        if !delta.is_finite() {
            return self;
        }
        LevelWindow { lo: self.lo + delta, hi: self.hi + delta }
    }
    /// Magnified `factor` times about the CSS pixel `at` of a level set of the world box
    /// `whole` drawn with `view` (the point under it stays there).
    pub fn zoomed_in_view(self, whole: (DVec2, DVec2), view: &View, at: DVec2, factor: f64) -> Self {
        let f = (view.css_to_world(at) - whole.0) / (whole.1 - whole.0);
        self.zoomed_at(f, factor)
    }
    /// Moved by `delta` CSS pixels of a level set of the world box `whole` drawn with `view`.
    pub fn panned_in_view(self, whole: (DVec2, DVec2), view: &View, delta: DVec2) -> Self {
        let world = DVec2::new(delta.x, -delta.y) / view.scale();
        self.shifted(-world / (whole.1 - whole.0))
    }
}

/// What undo puts back: positions of one panel's nodes before a move.
#[derive(Clone, Debug)]
pub struct Undo {
    /// The node the user moved (or smoothed).
    pub node: usize,
    /// `(node, position)` of the node and every node of its elements, per side.
    saved: [Vec<(usize, DVec2)>; 2],
}

impl Playground {
    /// The zoom and pan of the mesh panels.
    pub fn zoom(&self) -> ZoomPan {
        self.zoom
    }

    /// Magnifies the mesh panels `factor` times about the CSS pixel `at` of canvas `c`,
    /// which keeps its place (the mouse wheel, a pinch), within [`ZOOM_RANGE`].
    pub fn zoom_meshes_at(&mut self, c: Canvas, at: DVec2, factor: f64) {
        let z = self.panel_view(c).zoomed_at(at, factor);
        if (ZOOM_RANGE.0..=ZOOM_RANGE.1).contains(&z.zoom) && z.pan.is_finite() {
            self.zoom = z;
        }
    }

    /// Moves the mesh panels' pictures by `delta` CSS pixels (a drag on empty space).
    pub fn pan_meshes(&mut self, delta: DVec2) {
        if delta.is_finite() {
            self.zoom = self.zoom.panned(delta);
        }
    }

    /// The part of a star the level-set views show.
    pub fn level_window(&self) -> LevelWindow {
        self.level_window
    }

    /// The box a level set of `node` on one side starts from (the feasible region round
    /// the node, its position and the optimum the side's solver finds:
    /// [`feasible_bounds`]), and the part of it shown.
    pub(crate) fn level_bounds(&self, side: Side, node: usize) -> ((DVec2, DVec2), (DVec2, DVec2)) {
        let mut star = Star::new();
        star.gather(&self.panel(side).mesh, node);
        let mut keep = vec![star.x0];
        if let Ok(r) = self.solve_node(side, node) {
            keep.push(r.x);
        }
        let whole = feasible_bounds(&star, &keep, LEVEL_SET_MARGIN);
        (whole, self.level_window.within(whole))
    }

    /// The view a level set of `node` on `side` is drawn with on canvas `c`.
    fn level_view(&self, side: Side, node: usize, c: Canvas) -> ((DVec2, DVec2), View) {
        let (whole, shown) = self.level_bounds(side, node);
        let frame = Frame::new(0.0, 0.0, c.w as f32 / c.dpr, c.h as f32 / c.dpr);
        (whole, level_set_view(frame, shown.0, shown.1, c.dpr, &self.theme(), self.level_legend.get()[side as usize]))
    }

    /// Magnifies the level-set views `factor` times about the CSS pixel `at` of `side`'s
    /// level set of `node` on canvas `c`.
    pub fn zoom_level_sets_at(&mut self, side: Side, node: usize, c: Canvas, at: DVec2, factor: f64) {
        let (whole, view) = self.level_view(side, node, c);
        self.level_window = self.level_window.zoomed_in_view(whole, &view, at, factor);
    }

    /// Moves the level-set views by `delta` CSS pixels of `side`'s level set of `node`.
    pub fn pan_level_sets(&mut self, side: Side, node: usize, c: Canvas, delta: DVec2) {
        let (whole, view) = self.level_view(side, node, c);
        self.level_window = self.level_window.panned_in_view(whole, &view, delta);
    }

    /// Both views as fitted again (a double-click).
    pub fn reset_zoom(&mut self) {
        self.zoom = ZoomPan::default();
        self.level_window = LevelWindow::default();
    }

    /// Keeps the positions round `node` on both sides, for [`undo`](Self::undo) to put
    /// back: call it before a move (a drag calls it once, as it starts).
    pub fn remember_before_move(&mut self, node: usize) -> Result<()> {
        self.check_movable(node)?;
        let m = self.topology();
        let mut ids = vec![node];
        for &e in m.node_elements(node) {
            ids.extend(m.element(e as usize).iter().map(|&n| n as usize));
        }
        ids.sort_unstable();
        ids.dedup();
        let saved = Side::BOTH.map(|s| ids.iter().map(|&n| (n, self.panel(s).mesh.nodes()[n])).collect());
        self.undo.push(Undo { node, saved });
        Ok(())
    }

    /// How many moves undo can take back (none after a pass, a reset or a perturbation).
    pub fn undo_depth(&self) -> usize {
        self.undo.len()
    }

    /// The node the next undo would put back, if any.
    pub fn undo_node(&self) -> Option<usize> {
        self.undo.last().map(|u| u.node)
    }

    /// Takes back the latest move: both sides' positions as they were before it. Returns
    /// the node it moved, or `None` when there is nothing to undo.
    pub fn undo(&mut self) -> Option<usize> {
        let u = self.undo.pop()?;
        self.abort_pass();
        for side in Side::BOTH {
            let v = self.fresh_version();
            let p = &mut self.panels[side.index()];
            for &(n, x) in &u.saved[side.index()] {
                p.mesh.nodes_mut()[n] = x;
            }
            p.changed(v);
        }
        Some(u.node)
    }

    /// One solver call on `node` on each side, with its history, from where the node is
    /// (the level-set view's solve), the node then moved to what it found. Undoable.
    pub fn smooth_one_node(&mut self, node: usize) -> Result<[SolveResult; 2]> {
        self.check_movable(node)?;
        let results = [self.solve_node(Side::A, node)?, self.solve_node(Side::B, node)?];
        if let Some(r) = results.iter().find(|r| !r.x.is_finite()) {
            return Err(Error::node(node, None, format!("the solver found no finite position ({})", r.x)));
        }
        self.remember_before_move(node)?;
        self.abort_pass();
        for (side, r) in Side::BOTH.into_iter().zip(&results) {
            self.place(side, node, r.x);
        }
        Ok(results)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lab::sample::Sample;

    fn perturbed_plate() -> Playground {
        let mut pg = Playground::new(Sample::PlateTri.generate().unwrap()).unwrap();
        pg.perturb(0.3, 5).unwrap();
        pg
    }

    fn worst(pg: &Playground) -> usize {
        crate::lab::pick::worst_free_node(&pg.panel(Side::B).mesh).unwrap()
    }

    #[test]
    fn undo_puts_back_every_position_a_move_changed_on_both_sides() {
        let mut pg = perturbed_plate();
        let before = Side::BOTH.map(|s| pg.panel(s).mesh.nodes().to_vec());
        let n = worst(&pg);
        pg.remember_before_move(n).unwrap();
        pg.move_node(n, pg.panel(Side::A).mesh.nodes()[n] + DVec2::new(0.01, -0.02)).unwrap();
        pg.move_node(n, pg.panel(Side::A).mesh.nodes()[n] + DVec2::new(0.01, 0.0)).unwrap();
        assert_ne!(pg.panel(Side::A).mesh.nodes(), before[0]);
        assert_eq!((pg.undo_depth(), pg.undo_node()), (1, Some(n)));
        assert_eq!(pg.undo(), Some(n));
        for s in Side::BOTH {
            assert_eq!(pg.panel(s).mesh.nodes(), before[s.index()], "bit for bit");
        }
        assert_eq!(pg.undo(), None);
        // a pass ends what can be undone
        pg.remember_before_move(n).unwrap();
        pg.step(&|| 0.0);
        assert_eq!(pg.undo_depth(), 0);
        // a fixed node is refused
        let fixed = (0..pg.topology().node_count()).find(|&k| !pg.topology().is_free(k)).unwrap();
        assert!(pg.remember_before_move(fixed).is_err());
    }

    #[test]
    fn smoothing_one_node_moves_it_to_the_solvers_answer_on_each_side() {
        let mut pg = perturbed_plate();
        let n = worst(&pg);
        let solved = [pg.solve_node(Side::A, n).unwrap(), pg.solve_node(Side::B, n).unwrap()];
        let results = pg.smooth_one_node(n).unwrap();
        for s in Side::BOTH {
            let r = &results[s.index()];
            assert_eq!(r.x, solved[s.index()].x, "the same call as the level-set view's");
            assert!(!r.history.is_empty(), "with its history");
            assert_eq!(pg.panel(s).mesh.nodes()[n], r.x);
        }
        // the new objective is a sum to minimise: it did not get worse
        let r = &results[Side::B.index()];
        assert!(r.value <= r.value0, "{} → {}", r.value0, r.value);
        assert_eq!(pg.undo(), Some(n));
    }

    #[test]
    fn zoom_keeps_the_point_under_the_pointer_and_stays_in_range() {
        let mut pg = perturbed_plate();
        let c = Canvas { w: 600, h: 600, dpr: 1.0 };
        let at = DVec2::new(170.0, 240.0);
        let w = pg.panel_view(c).css_to_world(at);
        pg.zoom_meshes_at(c, at, 3.0);
        assert!((pg.panel_view(c).css_to_world(at) - w).length() < 1e-12);
        assert!((pg.zoom().zoom - 3.0).abs() < 1e-12);
        pg.zoom_meshes_at(c, at, 1e6);
        assert!((pg.zoom().zoom - 3.0).abs() < 1e-12, "beyond the range: refused");
        let pan = pg.zoom().pan;
        pg.pan_meshes(DVec2::new(10.0, -4.0));
        assert_eq!(pg.zoom().pan, pan + DVec2::new(10.0, -4.0));
        // the level sets: the fraction under the pointer stays
        let n = worst(&pg);
        let (whole, view) = pg.level_view(Side::A, n, c);
        let p = view.css_to_world(at);
        pg.zoom_level_sets_at(Side::A, n, c, at, 2.0);
        let (_, shown) = pg.level_bounds(Side::A, n);
        assert!(((shown.1 - shown.0) - 0.5 * (whole.1 - whole.0)).length() < 1e-12);
        let (_, view2) = pg.level_view(Side::A, n, c);
        assert!((view2.css_to_world(at) - p).length() < 1e-9 * (whole.1 - whole.0).length());
        pg.reset_zoom();
        assert_eq!((pg.zoom(), pg.level_window()), (ZoomPan::default(), LevelWindow::default()));
    }

    #[test]
    fn the_figure_is_drawn_at_the_size_asked() {
        let pg = perturbed_plate();
        let pm = pg.render_figure(Canvas { w: 800, h: 450, dpr: 2.0 }).unwrap();
        assert_eq!((pm.width(), pm.height()), (800, 450));
        assert!(pg.render_figure(Canvas { w: 5000, h: 450, dpr: 1.0 }).is_err());
    }
}
