//! What the page's screen shows of the playground, kept beside it so that every pointer
//! position and every frame is worked out here, in plain Rust: the canvas the meshes were
//! last drawn on (pointer positions map through its view), the chosen node, the canvas its
//! level sets were last drawn on, and what each panel last sent (the same again is neither
//! drawn nor sent again).

use glam::DVec2;
use serde::Serialize;
use tiny_skia::Pixmap;

use super::pick::{why_not_free, Pick};
use super::views::{Canvas, NodeSummary};
use super::{Playground, Side};
use smoothlab::error::{Error, Result};
use smoothlab::volume::BoundaryRule;
use smoothlab_render::{View, ZoomPan};

/// What a mesh panel last sent to the page: its positions' version, its boundary rule (a
/// sliding boundary is marked), the canvas, the highlighted node and the zoom.
type Sent = (u64, BoundaryRule, Canvas, Option<usize>, ZoomPan);

/// The page's view of a playground: see the module docs.
#[derive(Clone, Debug, Default)]
pub struct Screen {
    canvas: Option<Canvas>,
    node: Option<usize>,
    sent: [Option<Sent>; 2],
    level_canvas: Option<Canvas>,
}

/// Both panels' pictures for the page: `None` for a panel whose last picture sent shows
/// the same positions, canvas, highlight and zoom; the milliseconds each took to draw;
/// and whether they carry the colour bar (false: the canvas is too small for it).
pub struct PanelFrame {
    pub pictures: [Option<Pixmap>; 2],
    pub render_ms: [f64; 2],
    pub colour_bar: bool,
}

/// What undo stands at: the node a move took back (`None` when there was none, or when
/// only asked), the node the next undo would put back, and how many moves it can take back.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct UndoSummary {
    pub node: Option<usize>,
    pub next: Option<usize>,
    pub depth: usize,
}

impl Playground {
    /// The node the user chose (its star is highlighted, its level sets shown).
    pub fn chosen_node(&self) -> Option<usize> {
        self.screen.node
    }

    /// Chooses the node whose star is highlighted and whose level sets are shown (`None`:
    /// none); a node that is not free is refused, saying why.
    pub fn choose_node(&mut self, node: Option<usize>) -> Result<()> {
        if let Some(n) = node {
            if let Some(why) = why_not_free(self.topology(), n) {
                return Err(Error::invalid(format!("Node {n} cannot be chosen: {why}.")));
            }
        }
        self.screen.node = node;
        Ok(())
    }

    fn chosen(&self) -> Result<usize> {
        self.screen.node.ok_or_else(|| Error::invalid("no node is chosen: click a free node first"))
    }

    /// The view the meshes were last drawn in ([`frame`](Self::frame)'s canvas).
    pub fn frame_view(&self) -> Result<View> {
        let c = self.screen.canvas.ok_or_else(|| Error::invalid("the mesh has not been drawn yet"))?;
        Ok(self.panel_view(c))
    }

    /// Both panels drawn on canvas `c` (`clock` times each), the chosen node highlighted
    /// with its star; a panel whose last picture sent is the same is not drawn again
    /// (unless `force`). Later pointer positions map through this canvas's view.
    pub fn frame(&mut self, c: Canvas, force: bool, clock: &dyn Fn() -> f64) -> Result<PanelFrame> {
        let mut pictures = [None, None];
        let mut render_ms = [0.0; 2];
        // equal versions, equal positions: after a load or a reset the B panel's picture
        // is A's, drawn once
        let rules = Side::BOTH.map(|s| self.panel(s).mesh.boundary_rule());
        let same = self.version(Side::A) == self.version(Side::B) && rules[0] == rules[1];
        let mut a_picture = None;
        for s in Side::BOTH {
            let i = s.index();
            let key = (self.version(s), rules[i], c, self.screen.node, self.zoom());
            if !force && self.screen.sent[i] == Some(key) {
                continue;
            }
            let t0 = clock();
            let pm = match a_picture.take() {
                Some(pm) => pm,
                None => self.render_panel(s, c, self.screen.node)?,
            };
            if s == Side::A && same {
                a_picture = Some(pm.clone());
            }
            render_ms[i] = clock() - t0;
            pictures[i] = Some(pm);
            self.screen.sent[i] = Some(key);
        }
        self.screen.canvas = Some(c);
        Ok(PanelFrame { pictures, render_ms, colour_bar: self.panel_colour_bar(c) })
    }

    /// Forgets what was sent: the next [`frame`](Self::frame) draws both panels (after the
    /// page cleared or replaced its canvases, or changed the theme).
    pub fn forget_frames(&mut self) {
        self.screen.sent = [None, None];
    }

    /// The node of a panel nearest to the CSS pixel `at` of the last frame within `radius`
    /// CSS pixels (a radius that is not positive and finite is the page's default; at
    /// most 64).
    pub fn pick_in_frame(&self, side: Side, at: DVec2, radius: f64) -> Result<Pick> {
        let view = self.frame_view()?;
        let radius = if radius.is_finite() && radius > 0.0 { radius.min(64.0) } else { smoothlab_render::PICK_RADIUS };
        Ok(self.pick(side, &view, at, radius))
    }

    /// Moves a free node to the CSS pixel `at` of the last frame, on both panels.
    pub fn drag_in_frame(&mut self, node: usize, at: DVec2) -> Result<()> {
        let to = self.frame_view()?.css_to_world(at);
        self.move_node(node, to)
    }

    /// Moves the chosen node by `delta` CSS pixels of the last frame from where it is on
    /// `side`, on both panels (the arrow keys), undoably.
    pub fn nudge_chosen(&mut self, side: Side, delta: DVec2) -> Result<()> {
        let node = self.chosen()?;
        let view = self.frame_view()?;
        let from = self.panel(side).mesh.nodes()[node];
        let to = from + DVec2::new(delta.x, -delta.y) / view.scale();
        self.remember_before_move(node)?;
        self.move_node(node, to)
    }

    /// Magnifies both meshes `factor` times about the CSS pixel `at` of the last frame.
    pub fn zoom_meshes_in_frame(&mut self, at: DVec2, factor: f64) -> Result<()> {
        let c = self.screen.canvas.ok_or_else(|| Error::invalid("the mesh has not been drawn yet"))?;
        self.zoom_meshes_at(c, at, factor);
        Ok(())
    }

    /// The chosen node and the canvas its level sets were last drawn on.
    fn level_drawn(&self) -> Result<(usize, Canvas)> {
        let node = self.screen.node.ok_or_else(|| Error::invalid("no node is chosen"))?;
        let c = self.screen.level_canvas.ok_or_else(|| Error::invalid("the level sets have not been drawn yet"))?;
        Ok((node, c))
    }

    /// Magnifies both level sets `factor` times about the CSS pixel `at` of `side`'s
    /// level set as last drawn.
    pub fn zoom_level_sets_in_frame(&mut self, side: Side, at: DVec2, factor: f64) -> Result<()> {
        let (node, c) = self.level_drawn()?;
        self.zoom_level_sets_at(side, node, c, at, factor);
        Ok(())
    }

    /// Moves both level sets by `delta` CSS pixels of `side`'s level set as last drawn.
    pub fn pan_level_sets_in_frame(&mut self, side: Side, delta: DVec2) -> Result<()> {
        let (node, c) = self.level_drawn()?;
        self.pan_level_sets(side, node, c, delta);
        Ok(())
    }

    /// The chosen node's level sets (A, B: on canvas `level`), its solve history chart
    /// (on `chart`) and a summary; pointer positions on the level sets map through `level`.
    pub fn chosen_node_view(&mut self, level: Canvas, chart: Canvas) -> Result<([Pixmap; 3], NodeSummary)> {
        let node = self.screen.node.ok_or_else(|| Error::invalid("no node is chosen"))?;
        self.screen.level_canvas = Some(level);
        self.render_node_view(node, level, chart)
    }

    /// One solver call on the chosen node on each side, which then moves to what it
    /// found: the node view of that call (as [`chosen_node_view`](Self::chosen_node_view),
    /// drawn before the move, so its history is the call's).
    pub fn smooth_chosen_node(&mut self, level: Canvas, chart: Canvas) -> Result<([Pixmap; 3], NodeSummary)> {
        let node = self.chosen()?;
        let view = self.chosen_node_view(level, chart)?;
        self.smooth_one_node(node)?;
        Ok(view)
    }

    /// Where undo stands, `node` the node a move just took back ([`undo`](Self::undo)'s
    /// answer; `None` to only ask).
    pub fn undo_summary(&self, node: Option<usize>) -> UndoSummary {
        UndoSummary { node, next: self.undo_node(), depth: self.undo_depth() }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lab::sample::Sample;

    fn no_clock() -> f64 {
        0.0
    }

    #[test]
    fn a_frame_is_sent_once_until_something_changes() {
        let mut pg = Playground::new(Sample::StarRegular.generate().unwrap()).unwrap();
        let c = Canvas { w: 200, h: 150, dpr: 1.0 };
        assert!(pg.frame_view().is_err(), "no pointer maps before the first frame");
        let f = pg.frame(c, false, &no_clock).unwrap();
        assert!(f.pictures.iter().all(Option::is_some));
        let [a, b] = f.pictures.map(Option::unwrap);
        assert_eq!(a.data(), b.data(), "equal positions: one picture");
        assert!(pg.frame(c, false, &no_clock).unwrap().pictures.iter().all(Option::is_none), "the same again is not sent");
        assert!(pg.frame(c, true, &no_clock).unwrap().pictures.iter().all(Option::is_some), "unless forced");
        pg.step(&no_clock);
        assert!(pg.frame(c, false, &no_clock).unwrap().pictures.iter().all(Option::is_some), "a pass changes both");
        pg.forget_frames();
        assert!(pg.frame(c, false, &no_clock).unwrap().pictures.iter().all(Option::is_some));
        let free = (0..pg.topology().node_count()).find(|&n| pg.topology().is_free(n)).unwrap();
        pg.choose_node(Some(free)).unwrap();
        assert!(pg.frame(c, false, &no_clock).unwrap().pictures.iter().all(Option::is_some), "a highlight changes both");
        // a new boundary rule changes both, at the positions as loaded: a sliding boundary
        // is marked, its edges in the marks' reddish purple
        let purple = |pm: &Pixmap| pm.pixels().iter().filter(|p| [p.red(), p.green(), p.blue()] == smoothlab_render::MARK_LINE_RGB).count();
        pg.reset();
        let fixed = pg.frame(c, false, &no_clock).unwrap().pictures.map(Option::unwrap);
        pg.set_settings(crate::lab::Settings { boundary: BoundaryRule::Slide, ..crate::lab::Settings::default() }).unwrap();
        let slid = pg.frame(c, false, &no_clock).unwrap().pictures.map(|p| p.expect("a new rule: both are sent again"));
        assert_eq!(purple(&fixed[0]) + purple(&fixed[1]), 0);
        assert!(slid.iter().all(|pm| purple(pm) > 50), "{}", purple(&slid[0]));
    }

    #[test]
    fn pointers_map_through_the_last_frame_and_undo_says_where_it_stands() {
        let mut pg = Playground::new(Sample::StarRegular.generate().unwrap()).unwrap();
        let free = pg.topology().node_count() - 1;
        assert!(pg.choose_node(Some(0)).unwrap_err().to_string().contains("Node 0 cannot be chosen"));
        assert_eq!(pg.chosen_node(), None, "a refused choice changes nothing");
        assert!(pg.nudge_chosen(Side::A, DVec2::new(1.0, 0.0)).is_err(), "no node is chosen");
        pg.choose_node(Some(free)).unwrap();
        assert!(pg.nudge_chosen(Side::A, DVec2::new(1.0, 0.0)).is_err(), "nothing drawn yet");
        let c = Canvas { w: 300, h: 300, dpr: 1.0 };
        pg.frame(c, false, &no_clock).unwrap();
        let at = pg.frame_view().unwrap().to_css(pg.panel(Side::A).mesh.nodes()[free]);
        assert_eq!(pg.pick_in_frame(Side::B, at, f64::NAN).unwrap().node, Some(free));
        assert_eq!(pg.undo_summary(None), UndoSummary { node: None, next: None, depth: 0 });
        let before = pg.panel(Side::B).mesh.nodes()[free];
        pg.nudge_chosen(Side::B, DVec2::new(10.0, -5.0)).unwrap();
        let moved = pg.panel(Side::B).mesh.nodes()[free] - before;
        assert!(moved.x > 0.0 && moved.y > 0.0, "right and up on the screen: {moved}");
        assert_eq!(pg.undo_summary(None), UndoSummary { node: None, next: Some(free), depth: 1 });
        let back = pg.undo();
        assert_eq!(pg.undo_summary(back), UndoSummary { node: Some(free), next: None, depth: 0 });
        assert_eq!(pg.panel(Side::B).mesh.nodes()[free], before);
        assert!(pg.zoom_level_sets_in_frame(Side::A, at, 2.0).is_err(), "the level sets are not drawn yet");
        let level = Canvas { w: 120, h: 120, dpr: 1.0 };
        let ([la, lb, _], _) = pg.chosen_node_view(level, Canvas { w: 120, h: 80, dpr: 1.0 }).unwrap();
        assert_eq!((la.width(), lb.height()), (120, 120));
        pg.zoom_level_sets_in_frame(Side::A, DVec2::new(60.0, 60.0), 2.0).unwrap();
        pg.drag_in_frame(free, at).unwrap();
        assert!(pg.panel(Side::A).mesh.nodes()[free].distance(before) < 1e-9, "a drag to where the node was drawn puts it there");
    }
}
