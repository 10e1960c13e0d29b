//! The laboratory in 3D: the playground's two sides (the same [`Settings`]: strategy,
//! order, iterations, each side's objective) on a mesh in space, smoothed a pass at a time
//! and drawn by the 3D view with one orbit [`Camera`] both sides share. [`Lab3d`] is written
//! once over the kind of mesh ([`Mesh3d`]); each kind's specifics are in its own file:
//! - [`surface`]: a [`Surface`](smoothlab::surface::Surface), smoothed by the
//!   [`SurfaceSmoother`](smoothlab::surface::SurfaceSmoother) (Chen, Tristano & Kwok 2003 smooth
//!   surface meshes star by star in the tangent plane).
//! - [`volume`]: a [`VolumeMesh`](smoothlab::volume::VolumeMesh), smoothed by the
//!   [`VolumeSmoother`](smoothlab::volume::VolumeSmoother) (the planar drivers over stars of
//!   tetrahedra) and drawn cut by a plane ([`Cut`](smoothlab_render::Cut)).
//!
//! A node is chosen by pointing at it (the nearest node of the face drawn there), and the
//! planar page's views of one node work here too, by the same code ([`super::views`]):
//! the level sets of each side's objective over a plane through the node ([`NodeSlice`]:
//! a surface's tangent plane, where its drivers solve; a volume's cut plane moved to pass
//! through the node), the solve's path and history, one solver call on the node (undoable),
//! the per-pass chart, the histograms of each side's elements ([`Histogram3d`]) and the
//! figure for slides. Smaller than the planar [`Playground`](super::Playground): a pass
//! runs whole (no slices) and a node is not dragged (a drag turns the view).

mod mesh3d;
pub mod surface;
pub mod volume;

pub use mesh3d::Mesh3d;

use std::cell::Cell;

use glam::{DVec2, DVec3};
use serde::Serialize;
use tiny_skia::Pixmap;

use super::interact::LevelWindow;
use super::pick::{sentence, Pick};
use super::screen::UndoSummary;
use super::views::{
    figure_lines, figure_title, histogram_picture, histogram_top, level_set_picture, pass_chart, pixmap, solve_chart, Canvas,
    NodeSummary, SolveSummary, LEVEL_SET_MARGIN,
};
use super::{PanelStats, PanelTable, PassSummary, Settings, Side, TableDetail, WorkDone, MAX_NODES};
use smoothlab::error::{Error, Result};
use smoothlab::io::Format;
use smoothlab::objective::Star;
use smoothlab::optimize::SolveResult;
use smoothlab::quality::MeshStats;
use smoothlab_render::{
    draw_node_mark, feasible_bounds_of, level_set_view, render_compare_with, AngleHistogram, Camera, Colormap, CompareBar, CompareText, Frame,
    HistogramAxis, HistogramSeries, PlaneFunction, Projection, SurfaceView, Theme, View,
};
use smoothlab::BoundaryReport;

/// A node's objective on one side over a plane through the node, where the page draws
/// its level sets (the planar level-set picture, of a function of the plane): a surface's
/// tangent plane, where its drivers flatten the star and solve; a volume's cut plane moved
/// to pass through the node, the 3D objective as the node moves in that plane.
pub struct NodeSlice<'a> {
    /// The star as drawn in the plane (its node at `outline.x0`).
    pub outline: Star,
    /// The side's objective with the node moved in the plane, and the star's validity.
    pub function: Box<dyn PlaneFunction + 'a>,
    /// The side's solve from where the node is, in the plane's coordinates (a volume's
    /// solve moves the node in space: its path and optimum are projected onto the plane).
    pub solve: SolveResult,
    /// Where the solve puts the node, in space.
    pub target: DVec3,
    /// The plane in words, for the summary ("its tangent plane").
    pub plane: String,
}

/// One histogram of the elements of each side the page draws beside the mesh as loaded
/// (both sides on one scale): its title, the counts of the statistics it draws and the
/// range of its bins. Another per-element measure is one more entry of
/// [`Mesh3d::HISTOGRAMS`].
#[derive(Clone, Copy, Debug)]
pub struct Histogram3d {
    pub title: &'static str,
    pub counts: fn(&MeshStats) -> &[u64],
    pub axis: HistogramAxis<'static>,
}

/// What the page's node view says of a chosen node: the planar summary, and the plane
/// the pictures are in.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NodeSummary3d {
    #[serde(flatten)]
    pub solves: NodeSummary,
    pub plane: String,
}

impl NodeSummary3d {
    /// One line for the page.
    pub fn text(&self) -> String {
        format!("{} Level sets over {}.", self.solves.text(), self.plane)
    }
}

/// What undo puts back: the move of one node, on both sides.
struct Undo3d<K> {
    node: usize,
    kept: [K; 2],
    stats: [MeshStats; 2],
}

/// One side: its mesh now, its objective and smoother, its passes since the last reset.
struct Side3d<M: Mesh3d> {
    mesh: M,
    objective: Box<M::Objective>,
    smoother: M::Smoother,
    records: Vec<PassSummary>,
    stats: MeshStats,
    /// The boundary's report, with the statistics ([`Mesh3d::boundary_report`]).
    boundary: Option<BoundaryReport>,
}

impl<M: Mesh3d> Side3d<M> {
    fn new(side: Side, mesh: M, stats: MeshStats, settings: &Settings) -> Result<Self> {
        Ok(Side3d {
            boundary: mesh.boundary_report(),
            mesh,
            objective: M::objective(settings, side)?,
            smoother: M::smoother(settings.side_options(side, crate::lab::settings::RunStart::of(&stats))?)?,
            records: Vec::new(),
            stats,
        })
    }

    /// Measures the mesh as it is now: its statistics and its boundary's report.
    fn measure(&mut self) {
        self.stats = self.mesh.stats();
        self.boundary = self.mesh.boundary_report();
    }
}

/// Both sides drawn on one canvas: their pictures, the milliseconds each took, and whether
/// they carry the colour bar (a small canvas leaves it out, and the page shows the scale
/// beside it).
pub struct Frame3d {
    pub pictures: [Pixmap; 2],
    pub render_ms: [f64; 2],
    pub colour_bar: bool,
}

/// The page's state for a mesh in space: see the module docs.
pub struct Lab3d<M: Mesh3d> {
    /// The mesh as loaded (or as last perturbed), and its statistics.
    original: M,
    original_stats: MeshStats,
    settings: Settings,
    sides: [Side3d<M>; 2],
    camera: Camera,
    cut: M::Cut,
    /// The colours and label sizes every picture is drawn with.
    theme: Theme,
    /// The canvas of the last [`frame`](Self::frame) (pointer positions map through it).
    canvas: Option<Canvas>,
    /// The chosen node (marked on both sides, its level sets shown).
    node: Option<usize>,
    /// The part of the level sets' box shown (both sides share it).
    level_window: LevelWindow,
    /// The canvas the level sets were last drawn on, and each side's legend's height there.
    level_canvas: Option<Canvas>,
    level_legend: Cell<[f32; 2]>,
    /// What undo puts back: the latest move last.
    undo: Vec<Undo3d<M::Kept>>,
}

impl<M: Mesh3d> Lab3d<M> {
    /// A lab on `mesh`: both sides start from it, seen by the default camera (and cut
    /// by the default plane, where the kind has one).
    pub fn new(mesh: M) -> Result<Self> {
        if mesh.node_count() > MAX_NODES {
            return Err(Error::TooLarge(format!(
                "the mesh has {} nodes; the page takes at most {MAX_NODES} (use the command-line tool)",
                mesh.node_count()
            )));
        }
        mesh.check()?;
        let settings = Settings::default();
        let stats = mesh.stats();
        let sides = [
            Side3d::new(Side::A, mesh.clone(), stats.clone(), &settings)?,
            Side3d::new(Side::B, mesh.clone(), stats.clone(), &settings)?,
        ];
        Ok(Lab3d {
            original: mesh,
            original_stats: stats,
            settings,
            sides,
            camera: Camera::default(),
            cut: M::Cut::default(),
            theme: Theme::light(),
            canvas: None,
            node: None,
            level_window: LevelWindow::default(),
            level_canvas: None,
            level_legend: Cell::new([0.0; 2]),
            undo: Vec::new(),
        })
    }

    fn side(&self, side: Side) -> &Side3d<M> {
        &self.sides[side.index()]
    }

    /// The kind of mesh (`surface`, `volume`: [`Mesh3d::KIND`]).
    pub fn kind(&self) -> &'static str {
        M::KIND
    }

    /// A side's heading: its letter and what it smooths with, in the kind's words.
    pub fn side_title(&self, side: Side) -> String {
        M::side_title(&self.settings, side)
    }

    /// The same, short: the letter and the objective's name.
    pub fn side_label(&self, side: Side) -> String {
        M::side_label(&self.settings, side)
    }

    /// The settings the next passes use.
    pub fn settings(&self) -> Settings {
        self.settings
    }

    /// New settings for the next passes (the meshes stay as they are); refused settings
    /// (an objective without a form on this kind among them, a boundary that cannot
    /// slide) change nothing. A new boundary rule is taken on the mesh as loaded (or as
    /// last perturbed), whose boundary is the one sliding nodes stay on, and both sides
    /// start again from it: a pass is then the core's pass with that rule, as
    /// `smoothlab smooth --boundary slide` runs it on the same file.
    pub fn set_settings(&mut self, settings: Settings) -> Result<()> {
        let o = [settings.side_options(Side::A, crate::lab::settings::RunStart::of(&self.original_stats))?, settings.side_options(Side::B, crate::lab::settings::RunStart::of(&self.original_stats))?];
        super::settings::check_boundary(settings.boundary, self.original.slide_refused())?;
        let objectives = [M::objective(&settings, Side::A)?, M::objective(&settings, Side::B)?];
        for ((s, objective), o) in self.sides.iter_mut().zip(objectives).zip(o) {
            s.smoother = M::smoother(o)?;
            s.objective = objective;
        }
        let retarget = settings.target != self.settings.target;
        let rebound = settings.boundary != self.settings.boundary;
        self.settings = settings;
        if rebound {
            self.original.set_boundary_rule(settings.boundary);
            self.original_stats = self.original.stats();
            self.reset(); // which gives both sides the target again
        } else if retarget {
            self.aim();
        }
        Ok(())
    }

    /// Why this mesh's boundary nodes cannot slide, if they cannot ([`Mesh3d::slide_refused`]).
    pub fn slide_refused(&self) -> Option<String> {
        self.original.slide_refused()
    }

    /// Gives both sides the settings' target, taken from the mesh as loaded (or as last
    /// perturbed), never from the sides' own positions, so passes after the first leave
    /// it where the run began.
    fn aim(&mut self) {
        for s in &mut self.sides {
            s.mesh.aim_at(self.settings.target, &self.original);
        }
    }

    /// One smoothing pass on both sides; `clock` gives milliseconds (the core reads no time).
    pub fn step(&mut self, clock: &dyn Fn() -> f64) -> [PassSummary; 2] {
        self.undo.clear(); // a pass ends what can be undone, as on the planar page
        Side::BOTH.map(|side| {
            let s = &mut self.sides[side.index()];
            // numbered since the last reset, whatever settings came between (as the planar lab)
            let pass = s.records.len() as u32 + 1;
            let mut r = s.mesh.pass(&mut s.smoother, s.objective.as_ref(), pass, clock);
            r.objective_total = None; // as the planar lab: the page never shows it
            s.measure();
            s.records.push(r.clone());
            r
        })
    }

    /// Both sides back to the mesh as loaded (or as last perturbed), their records cleared.
    pub fn reset(&mut self) {
        self.undo.clear();
        let o = Side::BOTH.map(|side| self.settings.side_options(side, crate::lab::settings::RunStart::of(&self.original_stats)).expect("the settings were checked when set"));
        let boundary = self.original.boundary_report();
        for (s, o) in self.sides.iter_mut().zip(o) {
            s.mesh.clone_from(&self.original);
            s.stats.clone_from(&self.original_stats);
            s.boundary = boundary;
            s.records.clear();
            s.smoother = M::smoother(o).expect("the settings were checked when set");
        }
        // the meshes are the original's copies, without a target: the settings' is set again
        if self.settings.target != smoothlab::target::Target::Ideal {
            self.aim();
        }
    }

    /// The mesh as loaded perturbed ([`Mesh3d::perturbed`]: a surface in its tangent
    /// planes, tetrahedra's free nodes in space; `amount` mean edge lengths, seeded); both
    /// sides start again from it. A refused perturbation changes nothing.
    pub fn perturb(&mut self, amount: f64, seed: u64) -> Result<()> {
        let perturbed = self.original.perturbed(amount, seed)?;
        self.original_stats = perturbed.stats();
        self.original = perturbed;
        self.reset();
        Ok(())
    }

    /// A side's mesh now.
    pub fn mesh(&self, side: Side) -> &M {
        &self.side(side).mesh
    }

    /// The mesh as loaded (or as last perturbed).
    pub fn original(&self) -> &M {
        &self.original
    }

    /// Why the file's points were read as this kind, or `None` ([`Mesh3d::not_planar`]).
    pub fn not_planar(&self) -> Option<String> {
        self.original.not_planar()
    }

    /// What the file held that is not smoothed, or `None` ([`Mesh3d::file_note`]).
    pub fn file_note(&self) -> Option<String> {
        self.original.file_note()
    }

    /// The full statistics of a side's mesh now.
    pub fn full_stats(&self, side: Side) -> &MeshStats {
        &self.side(side).stats
    }

    /// Statistics of a side, with the work done since the last reset.
    pub fn stats(&self, side: Side) -> PanelStats {
        let s = self.side(side);
        PanelStats { side, mesh: s.stats.clone(), work: WorkDone::of(&s.records) }
    }

    /// What the page's statistics table shows of a side: the planar table's record (for
    /// tetrahedra its angles the dihedral angles and its quality the mean ratio; for a
    /// surface with the largest distance from the reference surface).
    pub fn table(&self, side: Side) -> PanelTable {
        let s = self.side(side);
        PanelTable {
            side,
            title: self.side_title(side),
            label: self.side_label(side),
            nodes: s.mesh.node_count(),
            elements: s.mesh.element_count(),
            mesh: s.stats.quick(),
            detail: Some(TableDetail::of(&s.stats)),
            max_distance_from_surface: s.stats.max_distance_from_surface,
            boundary: s.boundary,
            work: WorkDone::of(&s.records),
        }
    }

    /// The camera both sides are seen by.
    pub fn camera(&self) -> Camera {
        self.camera
    }

    /// Turns the camera by a drag of `(dx, dy)` CSS pixels ([`Camera::orbited`]).
    pub fn orbit(&mut self, dx: f64, dy: f64) {
        self.camera = self.camera.orbited(dx, dy);
    }

    /// Magnifies the view `factor` times ([`Camera::zoomed`]: clamped; a factor that is
    /// not positive and finite changes nothing).
    pub fn zoom(&mut self, factor: f64) {
        self.camera = self.camera.zoomed(factor);
    }

    /// The camera as it starts, and the level sets fitted again (a double-click).
    pub fn reset_camera(&mut self) {
        self.camera = Camera::default();
        self.level_window = LevelWindow::default();
    }

    /// Sees both sides by `camera` (a permalink's): its pitch within ±90° and its zoom
    /// within [`ZOOM_RANGE`](smoothlab_render::ZOOM_RANGE); a camera that is not finite is
    /// refused, changing nothing.
    pub fn set_camera(&mut self, camera: Camera) -> Result<()> {
        let Camera { yaw, pitch, zoom } = camera;
        if !(yaw.is_finite() && (-90.0..=90.0).contains(&pitch) && zoom.is_finite() && zoom > 0.0) {
            return Err(Error::invalid(format!(
                "a camera at yaw {yaw}°, pitch {pitch}°, zoom {zoom}: give a finite yaw, a pitch from -90 to 90 and a zoom above 0"
            )));
        }
        let (lo, hi) = smoothlab_render::ZOOM_RANGE;
        self.camera = Camera { yaw, pitch, zoom: zoom.clamp(lo, hi) };
        Ok(())
    }

    /// The plane both sides are cut by (`()` for a kind without one).
    pub fn cut(&self) -> M::Cut {
        self.cut
    }

    /// Whether a side drawn on canvas `c` carries the colour bar (a small canvas leaves it
    /// out, and the page shows the scale beside it).
    pub fn colour_bar_shown(&self, c: Canvas) -> bool {
        let frame = smoothlab_render::Frame::new(0.0, 0.0, c.w as f32 / c.dpr, c.h as f32 / c.dpr);
        // under the title's band, as the 3D view lays it out
        let top = 26.0 * self.theme.grow(14.0);
        smoothlab_render::colour_bar_band(frame.inset(0.0, top, 0.0, 0.0), self.original.quality_label(), &self.theme)
            .is_some()
    }

    /// The theme every later picture is drawn with.
    pub fn theme(&self) -> Theme {
        self.theme
    }

    /// Draws every later picture with `theme`.
    pub fn set_theme(&mut self, theme: Theme) {
        self.theme = theme;
    }

    /// The options a side is drawn with on canvas `c`: the shared camera, the side's title.
    fn view(&self, side: Side, c: Canvas) -> SurfaceView {
        SurfaceView {
            camera: self.camera,
            dpr: c.dpr,
            title: Some(self.side_title(side)),
            theme: self.theme,
            ..SurfaceView::default()
        }
    }

    /// A side's mesh drawn by the 3D view (cut, where the kind has a cut) on a canvas of
    /// `c.w × c.h` device pixels, coloured by element quality, with its title, the chosen
    /// node marked with its star; and the projection it used.
    pub fn render(&self, side: Side, c: Canvas) -> Result<(Pixmap, Projection)> {
        let mut pm = pixmap(c.w, c.h)?;
        let mesh = self.mesh(side);
        let proj = mesh.draw(&mut pm, self.cut, &self.view(side, c));
        if let Some(n) = self.node {
            draw_node_mark(&mut pm, &proj, mesh.point(n), &mesh.star_lines(n), c.dpr);
        }
        Ok((pm, proj))
    }

    /// Both sides drawn on canvas `c` (`clock` times each), which later picks map through.
    pub fn frame(&mut self, c: Canvas, clock: &dyn Fn() -> f64) -> Result<Frame3d> {
        let mut render_ms = [0.0; 2];
        let mut draw = |side: Side| -> Result<Pixmap> {
            let t0 = clock();
            let pm = self.render(side, c)?.0;
            render_ms[side.index()] = clock() - t0;
            Ok(pm)
        };
        let pictures = [draw(Side::A)?, draw(Side::B)?];
        self.canvas = Some(c);
        Ok(Frame3d { pictures, render_ms, colour_bar: self.colour_bar_shown(c) })
    }

    /// The node of a side's mesh under the CSS pixel `at` of a picture drawn on canvas
    /// `c` ([`Mesh3d::pick`]: the nearest node of the face drawn there): chosen when it is
    /// free, otherwise said why not, as the planar page's [`Pick`].
    pub fn pick(&self, side: Side, c: Canvas, at: DVec2, radius: f64) -> Result<Pick> {
        let (_, proj) = self.render(side, c)?;
        let mesh = self.mesh(side);
        Ok(match mesh.pick(self.cut, &proj, at, radius) {
            None => Pick {
                node: None,
                nearest: None,
                message: Some(format!("No face of {} there: click on the mesh (a drag turns it, the wheel zooms).", M::WHAT)),
            },
            Some(n) => match mesh.why_not_free(n) {
                None => Pick { node: Some(n), nearest: Some(n), message: None },
                Some(why) => Pick { node: None, nearest: Some(n), message: Some(sentence(&why)) },
            },
        })
    }

    /// As [`pick`](Self::pick) on the canvas of the last [`frame`](Self::frame); a
    /// radius that is not positive and finite is the page's default, and at most 64.
    pub fn pick_in_frame(&self, side: Side, at: DVec2, radius: f64) -> Result<Pick> {
        let c = self.canvas.ok_or_else(|| Error::invalid("the mesh has not been drawn yet"))?;
        let radius = if radius.is_finite() && radius > 0.0 { radius.min(64.0) } else { smoothlab_render::PICK_RADIUS };
        self.pick(side, c, at, radius)
    }

    /// Where node `n` of a side is drawn on the canvas of the last frame, CSS pixels
    /// (`None` for no such node), and how far it is behind the nearest point of that
    /// side's mesh, CSS pixels (0 for the nearest).
    pub fn node_on_screen(&self, side: Side, n: usize) -> Result<Option<(DVec2, f64)>> {
        let c = self.canvas.ok_or_else(|| Error::invalid("the mesh has not been drawn yet"))?;
        let mesh = self.mesh(side);
        if n >= mesh.node_count() {
            return Ok(None);
        }
        let (_, proj) = self.render(side, c)?;
        let front = (0..mesh.node_count()).map(|m| proj.depth(mesh.point(m))).fold(f64::INFINITY, f64::min);
        Ok(Some((proj.to_css(mesh.point(n)), (proj.depth(mesh.point(n)) - front) * proj.scale())))
    }

    /// The node chosen (marked on both sides, its level sets shown).
    pub fn chosen_node(&self) -> Option<usize> {
        self.node
    }

    /// Chooses the node whose level sets are shown (`None`: none); a node that is not
    /// free is refused, saying why, and changes nothing.
    pub fn choose_node(&mut self, node: Option<usize>) -> Result<()> {
        if let Some(n) = node {
            if let Some(why) = self.original.why_not_free(n) {
                return Err(Error::invalid(format!("Node {n} cannot be chosen: {why}.")));
            }
        }
        self.node = node;
        Ok(())
    }

    /// The free node with the worst star on B's mesh, if any (an embedded level-set view
    /// opens on it).
    pub fn worst_free_node(&self) -> Option<usize> {
        self.mesh(Side::B).worst_free_node()
    }

    fn chosen(&self) -> Result<usize> {
        self.node.ok_or_else(|| Error::invalid("no node is chosen: click a node first"))
    }

    /// A side's [`NodeSlice`] at `node`: its objective over the plane through the node
    /// and its solve from where the node is.
    pub fn node_slice(&self, side: Side, node: usize) -> Result<NodeSlice<'_>> {
        let s = self.side(side);
        let options = self.settings.side_options(side, crate::lab::settings::RunStart::of(&self.original_stats))?;
        s.mesh.slice(s.objective.as_ref(), node, self.cut, &options)
    }

    /// The box a level set of `slice` starts from (the feasible region round the node, its
    /// position and the optimum found), and the part of it shown.
    fn level_bounds(&self, slice: &NodeSlice<'_>) -> ((DVec2, DVec2), (DVec2, DVec2)) {
        let keep = [slice.outline.x0, slice.solve.x];
        let whole = feasible_bounds_of(&|p| slice.function.validity(p), &slice.outline, &keep, LEVEL_SET_MARGIN);
        (whole, self.level_window.within(whole))
    }

    /// Level sets of one side's objective at `node` over its plane ([`NodeSlice`]), with
    /// the path of its solve, on canvas `c` (the planar view's picture); and the slice.
    pub fn render_level_set(&self, side: Side, node: usize, c: Canvas) -> Result<(Pixmap, NodeSlice<'_>)> {
        let slice = self.node_slice(side, node)?;
        let (_, bounds) = self.level_bounds(&slice);
        let title = self.side_title(side);
        let (pm, legend_h) = level_set_picture(slice.function.as_ref(), &slice.outline, &slice.solve, bounds, &title, c, self.theme)?;
        let mut legend = self.level_legend.get();
        legend[side.index()] = legend_h;
        self.level_legend.set(legend);
        Ok((pm, slice))
    }

    /// Both sides' level sets at `node` (on canvas `level`) and a chart of their solves'
    /// histories (on `chart`), with a summary; the solves' targets in space.
    pub fn render_node_view(&self, node: usize, level: Canvas, chart: Canvas) -> Result<([Pixmap; 3], NodeSummary3d, [DVec3; 2])> {
        let (la, a) = self.render_level_set(Side::A, node, level)?;
        let (lb, b) = self.render_level_set(Side::B, node, level)?;
        let labels = Side::BOTH.map(|side| M::objective_label(&self.settings, side));
        let goals = [a.function.goal(), b.function.goal()];
        let pm = solve_chart([&a.solve, &b.solve], [&labels[0], &labels[1]], goals, chart, self.theme)?;
        let solves = NodeSummary {
            node,
            old: SolveSummary::of(&labels[0], goals[0], &a.solve),
            new: SolveSummary::of(&labels[1], goals[1], &b.solve),
        };
        Ok(([la, lb, pm], NodeSummary3d { solves, plane: a.plane.clone() }, [a.target, b.target]))
    }

    /// The chosen node's level sets (A, B: on canvas `level`), its solve history chart (on
    /// `chart`) and a summary; pointer positions on the level sets map through `level`.
    pub fn chosen_node_view(&mut self, level: Canvas, chart: Canvas) -> Result<([Pixmap; 3], NodeSummary3d)> {
        let node = self.chosen()?;
        self.level_canvas = Some(level);
        let (pictures, summary, _) = self.render_node_view(node, level, chart)?;
        Ok((pictures, summary))
    }

    /// One solver call on the chosen node on each side (each side's objective and
    /// solver, from where the node is), which then moves there as the kind's smoother
    /// puts a node (the nodes that follow it following; on a surface, put back on the
    /// surface): the node view of that call, drawn before the move. Undoable.
    pub fn smooth_chosen_node(&mut self, level: Canvas, chart: Canvas) -> Result<([Pixmap; 3], NodeSummary3d)> {
        let node = self.chosen()?;
        self.level_canvas = Some(level);
        let (pictures, summary, targets) = self.render_node_view(node, level, chart)?;
        if let Some(t) = targets.iter().find(|t| !t.is_finite()) {
            return Err(Error::node(node, None, format!("the solver found no finite position ({t})")));
        }
        self.remember_before_move(node);
        for (side, to) in Side::BOTH.into_iter().zip(targets) {
            let s = &mut self.sides[side.index()];
            s.mesh.place_node(node, to);
            s.measure();
        }
        Ok((pictures, summary))
    }

    /// Keeps what a move of `node` changes on both sides, for [`undo`](Self::undo).
    fn remember_before_move(&mut self, node: usize) {
        let kept = Side::BOTH.map(|side| self.mesh(side).keep_around(node));
        let stats = Side::BOTH.map(|side| self.side(side).stats.clone());
        self.undo.push(Undo3d { node, kept, stats });
    }

    /// Takes back the latest move: both sides as they were before it. Returns the node it
    /// moved, or `None` when there is nothing to undo.
    pub fn undo(&mut self) -> Option<usize> {
        let u = self.undo.pop()?;
        for ((s, kept), stats) in self.sides.iter_mut().zip(u.kept).zip(u.stats) {
            s.mesh.put_back(kept);
            s.stats = stats;
            s.boundary = s.mesh.boundary_report();
        }
        Some(u.node)
    }

    /// Where undo stands, `node` the node a move just took back ([`undo`](Self::undo)'s
    /// answer; `None` to only ask).
    pub fn undo_summary(&self, node: Option<usize>) -> UndoSummary {
        UndoSummary { node, next: self.undo.last().map(|u| u.node), depth: self.undo.len() }
    }

    /// The chosen node and the canvas its level sets were last drawn on, with the view
    /// `side`'s level set was drawn in and its box.
    fn level_drawn(&self, side: Side) -> Result<((DVec2, DVec2), View)> {
        let node = self.chosen()?;
        let c = self.level_canvas.ok_or_else(|| Error::invalid("the level sets have not been drawn yet"))?;
        let slice = self.node_slice(side, node)?;
        let (whole, shown) = self.level_bounds(&slice);
        let frame = Frame::new(0.0, 0.0, c.w as f32 / c.dpr, c.h as f32 / c.dpr);
        Ok((whole, level_set_view(frame, shown.0, shown.1, c.dpr, &self.theme, self.level_legend.get()[side.index()])))
    }

    /// Magnifies both level sets `factor` times about the CSS pixel `at` of `side`'s
    /// level set as last drawn.
    pub fn zoom_level_sets_in_frame(&mut self, side: Side, at: DVec2, factor: f64) -> Result<()> {
        let (whole, view) = self.level_drawn(side)?;
        self.level_window = self.level_window.zoomed_in_view(whole, &view, at, factor);
        Ok(())
    }

    /// Moves both level sets by `delta` CSS pixels of `side`'s level set as last drawn.
    pub fn pan_level_sets_in_frame(&mut self, side: Side, delta: DVec2) -> Result<()> {
        let (whole, view) = self.level_drawn(side)?;
        self.level_window = self.level_window.panned_in_view(whole, &view, delta);
        Ok(())
    }

    /// Per-pass curves of both sides (pass 0 the mesh as loaded), in the kind's words.
    pub fn render_pass_chart(&self, c: Canvas) -> Result<Pixmap> {
        let records = Side::BOTH.map(|side| &self.side(side).records[..]);
        let labels = Side::BOTH.map(|side| self.side_label(side));
        pass_chart(&self.original_stats, records, &labels, &M::PASS_TITLES, c, self.theme)
    }

    /// A side's histogram `which` of [`Mesh3d::HISTOGRAMS`] over the mesh as loaded, both
    /// sides on one scale, linear or logarithmic (`log_y`).
    pub fn render_histogram(&self, which: usize, side: Side, c: Canvas, log_y: bool) -> Result<Pixmap> {
        let h = M::HISTOGRAMS.get(which).ok_or_else(|| Error::invalid(format!("no histogram {which}: there are {}", M::HISTOGRAMS.len())))?;
        let start = (h.counts)(&self.original_stats);
        let top = histogram_top(start, Side::BOTH.map(|s| (h.counts)(self.full_stats(s))));
        let label = self.side_label(side);
        let series = HistogramSeries { label: &label, counts: (h.counts)(self.full_stats(side)), color: Some(self.theme.side(side.index())) };
        let opts = AngleHistogram { title: h.title, y_top: Some(top), log_y, axis: h.axis, ..AngleHistogram::default() };
        histogram_picture(start, series, opts, c, self.theme)
    }

    /// The figure for slides: A's 3D view on the left and B's on the right (the shared
    /// camera and cut), each titled with what it runs and how many passes, with its
    /// statistics under it and the colour bar, as the planar figure lays them out.
    pub fn render_figure(&self, c: Canvas) -> Result<Pixmap> {
        let mut pm = pixmap(c.w, c.h)?;
        let s = smoothlab_render::view::sane_dpr(c.dpr);
        let lines = Side::BOTH.map(|side| figure_lines(&self.side(side).stats, &WorkDone::of(&self.side(side).records), M::FIGURE_WORDS));
        let titles = Side::BOTH.map(|side| figure_title(&self.side_label(side), self.side(side).records.len()));
        let text = [CompareText { title: &titles[0], lines: &lines[0] }, CompareText { title: &titles[1], lines: &lines[1] }];
        let inverted = || self.side(Side::B).stats.inverted;
        let bar = CompareBar {
            label: self.original.quality_label(),
            domain: self.original.quality_domain(),
            colormap: Colormap::Viridis,
            inverted: &inverted,
        };
        let frame = Frame::of_pixmap(&pm, s);
        render_compare_with(&mut pm, &text, frame, s, &self.theme, Some(bar), |pm, k, f| {
            let view = SurfaceView { camera: self.camera, dpr: s, frame: Some(f), colour_bar: false, theme: self.theme, ..SurfaceView::default() };
            self.mesh(Side::BOTH[k]).draw(pm, self.cut, &view);
        });
        Ok(pm)
    }

    /// A side's mesh as the text of a mesh file.
    pub fn export(&self, side: Side, format: Format) -> Result<String> {
        self.mesh(side).write(format)
    }

    /// A side's mesh as arrays ([`smoothlab::io::MeshArrays`]).
    pub fn arrays(&self, side: Side) -> smoothlab::io::MeshArrays {
        self.mesh(side).arrays()
    }

    /// A side's mesh as the text of a file named by its extension (`msh`, `vtk`, …), one
    /// of [`Mesh3d::EXPORTS`]; any other is refused, naming those.
    pub fn export_named(&self, side: Side, format: &str) -> Result<String> {
        match Format::from_name(&format!("mesh.{format}")) {
            Some(f) if M::EXPORTS.contains(&f) => self.export(side, f),
            _ => {
                let names: Vec<&str> = M::EXPORTS.iter().map(|f| f.extensions()[0]).collect();
                let words = match names.split_last() {
                    Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
                    _ => names.join(""),
                };
                Err(Error::invalid(format!("cannot export {} as '{format}': use {words}", M::WHAT)))
            }
        }
    }
}

