//! The laboratory in 3D: the playground's two sides (the same [`Settings`]: strategy,
//! order, iterations, each side's objective) on a mesh in space, smoothed a pass at a time
//! and drawn by the 3D view with one orbit [`Camera`] both sides share. [`Lab3d`] is written
//! once over the kind of mesh ([`Mesh3d`]); each kind's specifics are in its own file:
//! - [`surface`]: a [`Surface`](crate::surface::Surface), smoothed by the
//!   [`SurfaceSmoother`](crate::surface::SurfaceSmoother) (Chen, Tristano & Kwok 2003 smooth
//!   surface meshes star by star in the tangent plane); a node can be picked on it.
//! - [`volume`]: a [`VolumeMesh`](crate::volume::VolumeMesh), smoothed by the
//!   [`VolumeSmoother`](crate::volume::VolumeSmoother) (the planar drivers over stars of
//!   tetrahedra) and drawn cut by a plane ([`Cut`](crate::volume::Cut)); the two sides'
//!   dihedral angles in Freitag's 6° bins.
//!
//! Smaller than the planar [`Playground`](super::Playground): a pass runs whole (no
//! slices), there is no node dragging and no level-set view (a node moves in a tangent
//! plane or in space, which the planar views do not draw).

pub mod surface;
pub mod volume;

use glam::{DVec2, DVec3};
use tiny_skia::Pixmap;

use super::views::{pixmap, Canvas};
use super::{PanelStats, PanelTable, PassSummary, Settings, Side, TableDetail, WorkDone, MAX_NODES};
use crate::error::{Error, Result};
use crate::io::Format;
use crate::quality::MeshStats;
use crate::render::{Camera, Projection, SurfaceView, Theme};
use crate::smooth::SmoothOptions;

/// A kind of mesh in space that the 3D lab holds: how it is smoothed a pass at a time,
/// measured, perturbed, drawn and written. [`surface`] and [`volume`] implement it.
pub trait Mesh3d: Clone + Sized {
    /// The kind's name for the page (`surface`, `volume`).
    const KIND: &'static str;
    /// What the kind is, in words, for messages (`a surface`, `tetrahedra`).
    const WHAT: &'static str;
    /// The formats a side can be written in.
    const EXPORTS: &'static [Format];
    /// The driver of a pass, made from checked options.
    type Smoother;
    /// What a side smooths with (the objective over the kind's stars).
    type Objective: ?Sized;
    /// The plane the view is cut by, where the kind has one (`()` where it has none).
    type Cut: Copy + Default + std::fmt::Debug + PartialEq;

    /// Refuses a mesh the lab cannot hold, saying why (beyond [`MAX_NODES`], checked by
    /// [`Lab3d::new`]).
    fn check(&self) -> Result<()> {
        Ok(())
    }
    fn node_count(&self) -> usize;
    fn element_count(&self) -> usize;
    /// A driver with the options `o` (checked by [`Settings::smooth_options`]).
    fn smoother(o: SmoothOptions) -> Result<Self::Smoother>;
    /// The objective a side's choice names, for this kind.
    /// A side's objective, or why the kind has none for the side's choice (an objective
    /// without a form on this kind).
    fn objective(settings: &Settings, side: Side) -> Result<Box<Self::Objective>>;
    /// One pass numbered `pass`, with its record; `clock` gives milliseconds.
    fn pass(
        &mut self,
        smoother: &mut Self::Smoother,
        objective: &Self::Objective,
        pass: u32,
        clock: &dyn Fn() -> f64,
    ) -> PassSummary;
    /// The full statistics.
    fn stats(&self) -> MeshStats;
    /// The mesh perturbed, `amount` mean edge lengths, seeded.
    fn perturbed(&self, amount: f64, seed: u64) -> Result<Self>;
    /// A side's heading: its letter and what it smooths with.
    fn side_title(settings: &Settings, side: Side) -> String;
    /// The same, short.
    fn side_label(settings: &Settings, side: Side) -> String;
    /// The colour bar's label (the quality the pictures are coloured by).
    fn quality_label(&self) -> &'static str;
    /// The mesh drawn by the 3D view (cut by `cut` where the kind has one); the projection
    /// it used.
    fn draw(&self, pm: &mut Pixmap, cut: Self::Cut, view: &SurfaceView) -> Projection;
    /// The points a pick chooses among, where the kind's view shows its nodes (`None`
    /// where it does not: a cut volume's faces hide the nodes behind).
    fn pickable_points(&self) -> Option<&[DVec3]>;
    /// The mesh as the text of a file (one of [`EXPORTS`](Self::EXPORTS)).
    fn write(&self, format: Format) -> Result<String>;
    /// Why a file's points were read as this kind, where that needs saying.
    fn not_planar(&self) -> Option<String> {
        None
    }
    /// What the file held that the lab does not smooth, where that needs saying.
    fn file_note(&self) -> Option<String> {
        None
    }
}

/// One side: its mesh now, its objective and smoother, its passes since the last reset.
struct Side3d<M: Mesh3d> {
    mesh: M,
    objective: Box<M::Objective>,
    smoother: M::Smoother,
    records: Vec<PassSummary>,
    stats: MeshStats,
}

impl<M: Mesh3d> Side3d<M> {
    fn new(side: Side, mesh: M, stats: MeshStats, settings: &Settings) -> Result<Self> {
        Ok(Side3d {
            mesh,
            objective: M::objective(settings, side)?,
            smoother: M::smoother(settings.smooth_options()?)?,
            records: Vec::new(),
            stats,
        })
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
    /// (an objective without a form on this kind among them) change nothing.
    pub fn set_settings(&mut self, settings: Settings) -> Result<()> {
        let o = settings.smooth_options()?;
        let objectives = [M::objective(&settings, Side::A)?, M::objective(&settings, Side::B)?];
        for (s, objective) in self.sides.iter_mut().zip(objectives) {
            s.smoother = M::smoother(o)?;
            s.objective = objective;
        }
        self.settings = settings;
        Ok(())
    }

    /// One smoothing pass on both sides; `clock` gives milliseconds (the core reads no time).
    pub fn step(&mut self, clock: &dyn Fn() -> f64) -> [PassSummary; 2] {
        Side::BOTH.map(|side| {
            let s = &mut self.sides[side.index()];
            // numbered since the last reset, whatever settings came between (as the planar lab)
            let pass = s.records.len() as u32 + 1;
            let mut r = s.mesh.pass(&mut s.smoother, s.objective.as_ref(), pass, clock);
            r.objective_total = None; // as the planar lab: the page never shows it
            s.stats = s.mesh.stats();
            s.records.push(r.clone());
            r
        })
    }

    /// Both sides back to the mesh as loaded (or as last perturbed), their records cleared.
    pub fn reset(&mut self) {
        let o = self.settings.smooth_options().expect("the settings were checked when set");
        for s in &mut self.sides {
            s.mesh.clone_from(&self.original);
            s.stats.clone_from(&self.original_stats);
            s.records.clear();
            s.smoother = M::smoother(o).expect("the settings were checked when set");
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

    /// The camera as it starts.
    pub fn reset_camera(&mut self) {
        self.camera = Camera::default();
    }

    /// The plane both sides are cut by (`()` for a kind without one).
    pub fn cut(&self) -> M::Cut {
        self.cut
    }

    /// Whether a side drawn on canvas `c` carries the colour bar (a small canvas leaves it
    /// out, and the page shows the scale beside it).
    pub fn colour_bar_shown(&self, c: Canvas) -> bool {
        let frame = crate::render::Frame::new(0.0, 0.0, c.w as f32 / c.dpr, c.h as f32 / c.dpr);
        // under the title's band, as the 3D view lays it out
        let top = 26.0 * self.theme.grow(14.0);
        crate::render::colour_bar_band(frame.inset(0.0, top, 0.0, 0.0), self.original.quality_label(), &self.theme)
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
    /// `c.w × c.h` device pixels, coloured by element quality, with its title; and the
    /// projection it used.
    pub fn render(&self, side: Side, c: Canvas) -> Result<(Pixmap, Projection)> {
        let mut pm = pixmap(c.w, c.h)?;
        let proj = self.mesh(side).draw(&mut pm, self.cut, &self.view(side, c));
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
    /// `c`, within `radius` CSS pixels, the near side winning ([`Projection::pick`]);
    /// always `None` for a kind whose view does not show its nodes (a cut volume).
    pub fn pick(&self, side: Side, c: Canvas, at: DVec2, radius: f64) -> Result<Option<usize>> {
        let Some(points) = self.mesh(side).pickable_points() else { return Ok(None) };
        let (_, proj) = self.render(side, c)?;
        Ok(proj.pick(points, at.x, at.y, radius))
    }

    /// As [`pick`](Self::pick) on the canvas of the last [`frame`](Self::frame); a
    /// radius that is not positive and finite is the page's default, and at most 64.
    pub fn pick_in_frame(&self, side: Side, at: DVec2, radius: f64) -> Result<Option<usize>> {
        let c = self.canvas.ok_or_else(|| Error::invalid("the mesh has not been drawn yet"))?;
        let radius = if radius.is_finite() && radius > 0.0 { radius.min(64.0) } else { crate::render::PICK_RADIUS };
        self.pick(side, c, at, radius)
    }

    /// A side's mesh as the text of a mesh file.
    pub fn export(&self, side: Side, format: Format) -> Result<String> {
        self.mesh(side).write(format)
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
