//! The laboratory on a tetrahedral mesh: the playground's two sides (the same
//! [`Settings`]: strategy, order, iterations, each side's objective) on a [`TetMesh`],
//! smoothed by the [`VolumeSmoother`] (the planar drivers over stars of tetrahedra) and
//! drawn by the 3D view cut by a plane ([`Cut`]) with one orbit [`Camera`] both sides share;
//! and the two sides' dihedral angles in Freitag's 6° bins.
//!
//! As the surface lab ([`super::surface::SurfaceLab`]): a pass runs whole, there is no node
//! dragging and no level-set view; a side's objective is its [`Choice`](super::Choice)'s
//! kind carried to tetrahedra ([`tet_objective`]; the planar penalty designs do not apply).

use tiny_skia::Pixmap;

use super::views::{pixmap, Canvas};
use super::{PanelStats, PanelTable, PassSummary, Settings, Side, TableDetail, WorkDone, MAX_NODES};
use crate::error::{Error, Result};
use crate::generate::perturb_volume;
use crate::io::{write_model_string, Format, WriteOptions};
use crate::objective::{describe_tet, tet_objective, Objective, TetStar};
use crate::quality::MeshStats;
use crate::render::{render_angle_histogram, AngleHistogram, Camera, HistogramSeries, Projection, SurfaceView};
use crate::surface::Model;
use crate::volume::{volume_stats, Cut, TetMesh, VolumeSmoother};

/// One side: its mesh now, its objective and smoother, its passes since the last reset.
struct VolumeSide {
    mesh: TetMesh,
    objective: Box<dyn Objective<TetStar> + Send + Sync>,
    smoother: VolumeSmoother,
    records: Vec<PassSummary>,
    stats: MeshStats,
}

impl VolumeSide {
    fn new(side: Side, mesh: TetMesh, stats: MeshStats, settings: &Settings) -> Result<Self> {
        Ok(VolumeSide {
            mesh,
            objective: tet_objective(settings.choice(side).objective)?,
            smoother: VolumeSmoother::new(settings.smooth_options()?)?,
            records: Vec::new(),
            stats,
        })
    }
}

/// The page's state for a tetrahedral mesh: see the module docs.
pub struct VolumeLab {
    /// The mesh as loaded (or as last perturbed), and its statistics.
    original: TetMesh,
    original_stats: MeshStats,
    settings: Settings,
    sides: [VolumeSide; 2],
    camera: Camera,
    cut: Cut,
    /// The colours and label sizes every picture is drawn with.
    theme: crate::render::Theme,
}

impl VolumeLab {
    /// What the file's triangles and quads fixed off the boundary
    /// ([`TetMesh::stray_faces_note`]), for the page to say.
    pub fn file_note(&self) -> Option<String> {
        self.original.stray_faces_note()
    }

    /// A lab on `mesh`: both sides start from it, seen by the default camera, cut half
    /// way up z.
    pub fn new(mesh: TetMesh) -> Result<Self> {
        if mesh.node_count() > MAX_NODES {
            return Err(Error::TooLarge(format!(
                "the mesh has {} nodes; the page takes at most {MAX_NODES} (use the command-line tool)",
                mesh.node_count()
            )));
        }
        let settings = Settings::default();
        let stats = volume_stats(&mesh);
        let sides = [
            VolumeSide::new(Side::Old, mesh.clone(), stats.clone(), &settings)?,
            VolumeSide::new(Side::New, mesh.clone(), stats.clone(), &settings)?,
        ];
        Ok(VolumeLab {
            original: mesh,
            original_stats: stats,
            settings,
            sides,
            camera: Camera::default(),
            cut: Cut::default(),
            theme: crate::render::Theme::light(),
        })
    }

    fn side(&self, side: Side) -> &VolumeSide {
        &self.sides[side.index()]
    }

    /// A side's heading: its letter and what it smooths with, in 3D's words
    /// ([`describe_tet`]; the planar penalty designs do not apply).
    pub fn side_title(&self, side: Side) -> String {
        let kind = self.settings.choice(side).objective;
        // a planar-only kind never gets here: set_settings refuses it
        format!("{}: {kind}: {}", side.letter(), describe_tet(kind).unwrap_or("planar only"))
    }

    /// The same, short: the letter and the objective's name.
    pub fn side_label(&self, side: Side) -> String {
        format!("{}: {}", side.letter(), self.settings.choice(side).objective)
    }

    /// The settings the next passes use.
    pub fn settings(&self) -> Settings {
        self.settings
    }

    /// New settings for the next passes (the meshes stay as they are); refused settings
    /// (an objective without a form on tetrahedra among them) change nothing.
    pub fn set_settings(&mut self, settings: Settings) -> Result<()> {
        let o = settings.smooth_options()?;
        let objectives = [tet_objective(settings.choice(Side::Old).objective)?, tet_objective(settings.choice(Side::New).objective)?];
        for (s, objective) in self.sides.iter_mut().zip(objectives) {
            s.smoother = VolumeSmoother::new(o)?;
            s.objective = objective;
        }
        self.settings = settings;
        Ok(())
    }

    /// One smoothing pass on both sides; `clock` gives milliseconds.
    pub fn step(&mut self, clock: &dyn Fn() -> f64) -> [PassSummary; 2] {
        Side::BOTH.map(|side| {
            let s = &mut self.sides[side.index()];
            // numbered since the last reset, as the other labs
            let pass = s.records.len() as u32 + 1;
            let mut r = s.smoother.pass(&mut s.mesh, s.objective.as_ref(), pass, clock);
            r.objective_total = None;
            s.stats = volume_stats(&s.mesh);
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
            s.smoother = VolumeSmoother::new(o).expect("the settings were checked when set");
        }
    }

    /// The mesh as loaded with its free nodes moved at random ([`perturb_volume`]:
    /// `amount` mean edge lengths, seeded); both sides start again from it.
    pub fn perturb(&mut self, amount: f64, seed: u64) -> Result<()> {
        let perturbed = perturb_volume(&self.original, amount, seed)?;
        self.original_stats = volume_stats(&perturbed);
        self.original = perturbed;
        self.reset();
        Ok(())
    }

    /// A side's mesh now.
    pub fn mesh(&self, side: Side) -> &TetMesh {
        &self.side(side).mesh
    }

    /// The full statistics of a side's mesh now (dihedral angles, mean ratio).
    pub fn full_stats(&self, side: Side) -> &MeshStats {
        &self.side(side).stats
    }

    /// Statistics of a side, with the work done since the last reset.
    pub fn stats(&self, side: Side) -> PanelStats {
        let s = self.side(side);
        PanelStats { side, mesh: s.stats.clone(), work: WorkDone::of(&s.records) }
    }

    /// What the page's statistics table shows of a side: the planar table's record, its
    /// angles the dihedral angles and its quality the mean ratio.
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
            max_distance_from_surface: None,
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

    /// Magnifies the view `factor` times ([`Camera::zoomed`]).
    pub fn zoom(&mut self, factor: f64) {
        self.camera = self.camera.zoomed(factor);
    }

    /// Whether a side drawn on canvas `c` carries the colour bar (a small canvas leaves it
    /// out, and the page shows the scale beside it).
    pub fn colour_bar_shown(&self, c: Canvas) -> bool {
        let frame = crate::render::Frame::new(0.0, 0.0, c.w as f32 / c.dpr, c.h as f32 / c.dpr);
        // under the title's band, as the 3D view lays it out
        let top = 26.0 * self.theme.grow(14.0);
        crate::render::colour_bar_band(frame.inset(0.0, top, 0.0, 0.0), "mean ratio", &self.theme).is_some()
    }

    /// The theme every later picture is drawn with.
    pub fn theme(&self) -> crate::render::Theme {
        self.theme
    }

    /// Draws every later picture with `theme`.
    pub fn set_theme(&mut self, theme: crate::render::Theme) {
        self.theme = theme;
    }

    /// The camera as it starts.
    pub fn reset_camera(&mut self) {
        self.camera = Camera::default();
    }

    /// The plane both sides are cut by.
    pub fn cut(&self) -> Cut {
        self.cut
    }

    /// Cuts both sides across `axis` (0, 1, 2: x, y, z) at the fraction `at` of the mesh's
    /// extent; anything else is refused, saying why.
    pub fn set_cut(&mut self, axis: usize, at: f64) -> Result<()> {
        if axis > 2 || !(0.0..=1.0).contains(&at) {
            return Err(Error::invalid(format!("cut across axis {axis} at {at}: give axis 0, 1 or 2 and 0 to 1")));
        }
        self.cut = Cut { axis, at };
        Ok(())
    }

    /// A side's mesh cut and drawn by the 3D view on a canvas of `c.w × c.h` device
    /// pixels, coloured by mean ratio, with its title; and the projection it used.
    pub fn render(&self, side: Side, c: Canvas) -> Result<(Pixmap, Projection)> {
        let mut pm = pixmap(c.w, c.h)?;
        let view = SurfaceView {
            camera: self.camera,
            dpr: c.dpr,
            title: Some(self.side_title(side)),
            theme: self.theme,
            ..SurfaceView::default()
        };
        let proj = self.mesh(side).render_cut(&mut pm, self.cut, &view);
        Ok((pm, proj))
    }

    /// A side's dihedral angles (6° bins, Freitag's Fig. 3) beside the mesh as loaded, on
    /// a canvas of `c.w × c.h` device pixels; both sides on one percentage scale, linear or
    /// logarithmic (`log_y`, as the planar angle histograms).
    pub fn render_histogram(&self, side: Side, c: Canvas, log_y: bool) -> Result<Pixmap> {
        let mut pm = pixmap(c.w, c.h)?;
        let pct = |h: &[u64]| {
            let total: u64 = h.iter().sum();
            h.iter().map(|&n| 100.0 * n as f64 / total.max(1) as f64).fold(0.0, f64::max)
        };
        let top = Side::BOTH
            .iter()
            .map(|&s| pct(&self.side(s).stats.angle_histogram_6deg))
            .fold(pct(&self.original_stats.angle_histogram_6deg), f64::max);
        let label = self.side_label(side);
        let series = [
            HistogramSeries { label: "as loaded", counts: &self.original_stats.angle_histogram_6deg, color: None },
            HistogramSeries { label: &label, counts: &self.side(side).stats.angle_histogram_6deg, color: None },
        ];
        let title = format!("Dihedral angles, {}", self.side_title(side));
        let opts = AngleHistogram { title: &title, dpr: c.dpr, y_top: Some(top), log_y, theme: self.theme, ..AngleHistogram::default() };
        render_angle_histogram(&mut pm, &series, &opts)?;
        Ok(pm)
    }

    /// A side's mesh as the text of a `msh` or `vtk` file.
    pub fn export(&self, side: Side, format: Format) -> Result<String> {
        write_model_string(&Model::Volume(self.mesh(side).clone()), format, &WriteOptions::default())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lab::sample::Sample;

    fn lab() -> VolumeLab {
        let Model::Volume(m) = Sample::Rand3d.model().unwrap() else { panic!("rand3d is tetrahedral") };
        VolumeLab::new(m).unwrap()
    }

    fn no_clock() -> f64 {
        0.0
    }

    #[test]
    fn passes_improve_the_sample_and_reset_restores_it() {
        let mut l = lab();
        let start = l.stats(Side::New);
        assert!(start.mesh.tetrahedra > 5000);
        let before = l.mesh(Side::New).nodes().to_vec();
        let [old, new] = l.step(&no_clock);
        assert_eq!((old.pass, new.pass), (1, 1));
        assert_eq!(new.after.inverted, 0);
        assert!(new.after.min_angle_deg > start.mesh.min_angle_deg);
        assert_eq!(l.table(Side::New).work.passes, 1);
        l.reset();
        assert_eq!(l.mesh(Side::New).nodes(), &before[..]);
        assert_eq!(l.stats(Side::New), start);
    }

    #[test]
    fn cuts_pictures_and_exports() {
        let mut l = lab();
        assert!(l.set_cut(3, 0.5).is_err() && l.set_cut(0, 1.5).is_err());
        l.set_cut(0, 0.4).unwrap();
        assert_eq!(l.cut(), Cut { axis: 0, at: 0.4 });
        let c = Canvas { w: 300, h: 240, dpr: 1.0 };
        let (pm, _) = l.render(Side::Old, c).unwrap();
        // not blank: the cut is coloured
        assert!(pm.pixels().iter().any(|p| p.red() != p.green() || p.green() != p.blue()));
        let h = l.render_histogram(Side::New, c, false).unwrap();
        assert_eq!((h.width(), h.height()), (300, 240));
        // the log scale draws the same counts differently (the small bins stand taller)
        let log = l.render_histogram(Side::New, c, true).unwrap();
        assert_eq!((log.width(), log.height()), (300, 240));
        assert_ne!(h.data(), log.data(), "the log scale changes the picture");
        let text = l.export(Side::New, Format::Vtk).unwrap();
        let Model::Volume(back) = crate::io::read_model_str(&text, Format::Vtk).unwrap() else {
            panic!("not tetrahedra")
        };
        assert_eq!(back.nodes(), l.mesh(Side::New).nodes());
        assert!(l.export(Side::New, Format::Obj).is_err());
        l.perturb(0.8, 3).unwrap();
        assert!(l.stats(Side::Old).mesh.inverted > 0);
    }
}
