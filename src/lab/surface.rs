//! The laboratory on a surface in 3D: the playground's two sides (the same [`Settings`]
//! and [`Choice`]s: strategy, order, iterations, each side's objective and penalty) on a
//! [`Surface`], smoothed by the [`SurfaceSmoother`] (Chen, Tristano & Kwok 2003 smooth
//! surface meshes star by star in the tangent plane) and drawn by the 3D view with one
//! orbit [`Camera`] both sides share.
//!
//! Smaller than the planar [`Playground`](super::Playground): a pass runs whole (no
//! slices), there is no node dragging and no level-set view (a surface node moves in its
//! tangent plane, which the planar views do not draw).

use glam::DVec2;
use tiny_skia::Pixmap;

use super::views::{pixmap, Canvas};
use super::{PanelStats, PanelTable, PassSummary, Settings, Side, TableDetail, WorkDone, MAX_NODES};
use crate::error::{Error, Result};
use crate::io::{write_string, Format, WriteOptions};
use crate::objective::Objective;
use crate::quality::MeshStats;
use crate::render::{Camera, Metric, Projection, SurfaceView};
use crate::generate::perturb_surface;
use crate::surface::{Surface, SurfaceSmoother};

/// One side: its surface now, its objective and smoother, its passes since the last reset.
struct SurfaceSide {
    surface: Surface,
    objective: Box<dyn Objective>,
    smoother: SurfaceSmoother,
    records: Vec<PassSummary>,
    stats: MeshStats,
}

impl SurfaceSide {
    fn new(side: Side, surface: Surface, stats: MeshStats, settings: &Settings) -> Result<Self> {
        Ok(SurfaceSide {
            surface,
            objective: settings.choice(side).build(),
            smoother: SurfaceSmoother::new(settings.smooth_options()?)?,
            records: Vec::new(),
            stats,
        })
    }
}

/// The page's state for a surface: see the module docs.
pub struct SurfaceLab {
    /// The surface as loaded (or as last perturbed), and its statistics.
    original: Surface,
    original_stats: MeshStats,
    settings: Settings,
    sides: [SurfaceSide; 2],
    camera: Camera,
    /// The colours and label sizes every picture is drawn with.
    theme: crate::render::Theme,
}

impl SurfaceLab {
    /// A lab on `surface`: both sides start from it, seen by the default camera.
    pub fn new(surface: Surface) -> Result<Self> {
        if surface.node_count() > MAX_NODES {
            return Err(Error::TooLarge(format!(
                "the mesh has {} nodes; the page takes at most {MAX_NODES} (use the command-line tool)",
                surface.node_count()
            )));
        }
        if surface.element_count() == 0 {
            return Err(Error::invalid("the surface has no elements"));
        }
        let settings = Settings::default();
        let stats = surface.stats();
        let sides = [
            SurfaceSide::new(Side::Old, surface.clone(), stats.clone(), &settings)?,
            SurfaceSide::new(Side::New, surface.clone(), stats.clone(), &settings)?,
        ];
        Ok(SurfaceLab { original: surface, original_stats: stats, settings, sides, camera: Camera::default(), theme: crate::render::Theme::light() })
    }

    fn side(&self, side: Side) -> &SurfaceSide {
        &self.sides[side.index()]
    }

    /// The settings the next passes use.
    pub fn settings(&self) -> Settings {
        self.settings
    }

    /// New settings for the next passes (the surfaces stay as they are); refused
    /// settings change nothing.
    pub fn set_settings(&mut self, settings: Settings) -> Result<()> {
        let o = settings.smooth_options()?;
        for (s, side) in self.sides.iter_mut().zip(Side::BOTH) {
            s.smoother = SurfaceSmoother::new(o)?;
            s.objective = settings.choice(side).build();
        }
        self.settings = settings;
        Ok(())
    }

    /// One smoothing pass on both sides; `clock` gives milliseconds (the core reads no time).
    pub fn step(&mut self, clock: &dyn Fn() -> f64) -> [PassSummary; 2] {
        Side::BOTH.map(|side| {
            let s = &mut self.sides[side.index()];
            let mut r = s.smoother.pass(&mut s.surface, s.objective.as_ref(), clock);
            // numbered since the last reset, whatever settings came between (as the planar lab)
            r.pass = s.records.len() as u32 + 1;
            r.objective_total = None; // as the planar lab: the page never shows it
            s.stats = s.surface.stats();
            s.records.push(r.clone());
            r
        })
    }

    /// Both sides back to the surface as loaded (or as last perturbed), their records cleared.
    pub fn reset(&mut self) {
        let o = self.settings.smooth_options().expect("the settings were checked when set");
        for s in &mut self.sides {
            s.surface.clone_from(&self.original);
            s.stats.clone_from(&self.original_stats);
            s.records.clear();
            s.smoother = SurfaceSmoother::new(o).expect("the settings were checked when set");
        }
    }

    /// The surface as loaded perturbed ([`perturb_surface`]: `amount` mean edge lengths in
    /// the tangent planes, seeded); both sides start again from it.
    pub fn perturb(&mut self, amount: f64, seed: u64) -> Result<()> {
        let perturbed = perturb_surface(&self.original, amount, seed)?;
        self.original_stats = perturbed.stats();
        self.original = perturbed;
        self.reset();
        Ok(())
    }

    /// A side's surface now.
    pub fn surface(&self, side: Side) -> &Surface {
        &self.side(side).surface
    }

    /// The surface as loaded (or as last perturbed).
    pub fn original(&self) -> &Surface {
        &self.original
    }

    /// The full statistics of a side's surface now (`surface` set, with the largest
    /// distance from the reference surface).
    pub fn full_stats(&self, side: Side) -> &MeshStats {
        &self.side(side).stats
    }

    /// Statistics of a side's surface, with the work done since the last reset.
    pub fn stats(&self, side: Side) -> PanelStats {
        let s = self.side(side);
        PanelStats { side, mesh: s.stats.clone(), work: WorkDone::of(&s.records) }
    }

    /// What the page's statistics table shows of a side: the planar table's record.
    pub fn table(&self, side: Side) -> PanelTable {
        let s = self.side(side);
        PanelTable {
            side,
            title: self.settings.side_title(side),
            label: self.settings.side_label(side),
            nodes: s.surface.node_count(),
            elements: s.surface.element_count(),
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

    /// Whether a side drawn on canvas `c` carries the colour bar (a small canvas leaves it
    /// out, and the page shows the scale beside it).
    pub fn colour_bar_shown(&self, c: Canvas) -> bool {
        let frame = crate::render::Frame::new(0.0, 0.0, c.w as f32 / c.dpr, c.h as f32 / c.dpr);
        // under the title's band, as the 3D view lays it out
        let top = 26.0 * self.theme.grow(14.0);
        crate::render::colour_bar_band(frame.inset(0.0, top, 0.0, 0.0), crate::render::Metric::Shape.label(self.original.flat()), &self.theme).is_some()
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

    /// The options a side is drawn with on canvas `c`: the shared camera, the side's title.
    fn view(&self, side: Side, c: Canvas) -> SurfaceView {
        SurfaceView { camera: self.camera, dpr: c.dpr, title: Some(self.settings.side_title(side)), theme: self.theme, ..SurfaceView::default() }
    }

    /// A side's surface drawn by the 3D view on a canvas of `c.w × c.h` device pixels,
    /// coloured by element quality, with its title; and the projection it used.
    pub fn render(&self, side: Side, c: Canvas) -> Result<(Pixmap, Projection)> {
        let mut pm = pixmap(c.w, c.h)?;
        let proj = self.surface(side).render(&mut pm, Metric::Shape, &self.view(side, c));
        Ok((pm, proj))
    }

    /// The node of a side's surface under the CSS pixel `at` of a picture drawn on canvas
    /// `c`, within `radius` CSS pixels, the near side winning ([`Projection::pick`]).
    pub fn pick(&self, side: Side, c: Canvas, at: DVec2, radius: f64) -> Result<Option<usize>> {
        let (_, proj) = self.render(side, c)?;
        Ok(proj.pick(self.surface(side).points(), at.x, at.y, radius))
    }

    /// A side's surface as the text of a mesh file (`msh`, `vtk`, `obj`, `off`).
    pub fn export(&self, side: Side, format: Format) -> Result<String> {
        write_string(self.surface(side), format, &WriteOptions::default())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lab::sample::Sample;
    use crate::lab::Choice;
    use crate::objective::ObjectiveKind;
    use crate::model::Model;

    fn lab(sample: Sample) -> SurfaceLab {
        let Model::Surface(s) = sample.model().unwrap() else { panic!("{sample:?} is not a surface") };
        SurfaceLab::new(s).unwrap()
    }

    fn no_clock() -> f64 {
        0.0
    }

    #[test]
    fn passes_untangle_the_tangled_sphere_and_reset_restores_it_bit_for_bit() {
        let mut l = lab(Sample::SphereTangled);
        let start = l.stats(Side::New);
        assert!(start.mesh.inverted > 0 && start.mesh.surface);
        let before: Vec<_> = l.surface(Side::New).points().to_vec();
        let mut last = None;
        for _ in 0..3 {
            last = Some(l.step(&no_clock));
        }
        let [old, new] = last.unwrap();
        assert_eq!((old.pass, new.pass), (3, 3));
        assert_eq!(new.after.inverted, 0, "the new objective untangles the sphere");
        let t = l.table(Side::New);
        assert_eq!((t.mesh.inverted, t.work.passes), (0, 3));
        assert!(t.max_distance_from_surface.unwrap() < 1e-9, "the nodes stay on the sphere");
        assert_ne!(l.surface(Side::New).points(), &before[..]);
        l.reset();
        assert_eq!(l.surface(Side::New).points(), &before[..]);
        assert_eq!(l.surface(Side::Old).points(), &before[..]);
        assert_eq!(l.stats(Side::New), start);
        let [_, again] = l.step(&no_clock);
        assert_eq!(again.pass, 1, "passes count again from the reset");
    }

    #[test]
    fn the_two_sides_differ_by_their_objective() {
        let mut l = lab(Sample::TorusTangled);
        l.step(&no_clock);
        assert_ne!(l.surface(Side::Old).points(), l.surface(Side::New).points());
        // the same objective on both sides: the same surface, bit for bit
        let same = Settings { compare: [Choice::NEW, Choice::NEW], ..Settings::default() };
        l.set_settings(same).unwrap();
        l.reset();
        l.step(&no_clock);
        assert_eq!(l.surface(Side::Old).points(), l.surface(Side::New).points());
        assert_eq!(l.table(Side::Old).title.replacen('A', "B", 1), l.table(Side::New).title);
        let bad = Settings { max_iter: 0, ..Settings::default() };
        assert!(l.set_settings(bad).is_err());
        assert_eq!(l.settings().compare[0].objective, ObjectiveKind::New, "a refused setting changes nothing");
    }

    #[test]
    fn the_camera_orbits_and_zooms_within_its_limits() {
        let mut l = lab(Sample::CylinderCapped);
        let c0 = l.camera();
        l.orbit(20.0, 10.0);
        assert_eq!((l.camera().yaw, l.camera().pitch), (c0.yaw - 10.0, c0.pitch + 5.0));
        l.orbit(0.0, 1e6);
        assert_eq!(l.camera().pitch, crate::render::MAX_DRAG_PITCH);
        l.orbit(f64::NAN, f64::INFINITY);
        assert_eq!(l.camera().pitch, crate::render::MAX_DRAG_PITCH, "a non-finite drag changes nothing");
        l.zoom(1e9);
        assert_eq!(l.camera().zoom, crate::render::ZOOM_RANGE.1);
        l.zoom(-2.0);
        l.zoom(f64::NAN);
        assert_eq!(l.camera().zoom, crate::render::ZOOM_RANGE.1);
        l.zoom(1e-12);
        assert_eq!(l.camera().zoom, crate::render::ZOOM_RANGE.0);
        l.reset_camera();
        assert_eq!(l.camera(), Camera::default());
    }

    #[test]
    fn both_sides_are_drawn_by_the_shared_camera_and_a_node_is_picked_on_the_near_side() {
        let mut l = lab(Sample::SphereTangled);
        let c = Canvas { w: 300, h: 320, dpr: 1.0 };
        let (a, proj) = l.render(Side::Old, c).unwrap();
        assert_eq!((a.width(), a.height()), (300, 320));
        // the node nearest the viewer is picked where it is drawn
        let pts = l.surface(Side::Old).points();
        let front = (0..pts.len()).min_by(|&i, &j| proj.depth(pts[i]).total_cmp(&proj.depth(pts[j]))).unwrap();
        let at = proj.to_css(pts[front]);
        assert_eq!(l.pick(Side::Old, c, at, 3.0).unwrap(), Some(front));
        assert_eq!(l.pick(Side::Old, c, DVec2::new(-50.0, -50.0), 3.0).unwrap(), None);
        l.orbit(90.0, 0.0);
        let (turned, _) = l.render(Side::Old, c).unwrap();
        assert_ne!(turned.data(), a.data(), "an orbit changes the picture");
        assert!(l.render(Side::Old, Canvas { w: 0, h: 10, dpr: 1.0 }).is_err());
    }

    #[test]
    fn export_writes_the_side_surface_that_reads_back_as_a_surface() {
        let mut l = lab(Sample::SphereTangled);
        l.step(&no_clock);
        for format in [Format::Msh, Format::Vtk, Format::Obj, Format::Off] {
            let text = l.export(Side::New, format).unwrap();
            let Model::Surface(back) = crate::io::read_model_str(&text, format).unwrap() else {
                panic!("{format:?} did not read back as a surface")
            };
            assert_eq!(back.node_count(), l.surface(Side::New).node_count());
            let d = back.points().iter().zip(l.surface(Side::New).points()).map(|(a, b)| a.distance(*b)).fold(0.0, f64::max);
            assert!(d < 1e-9, "{format:?} keeps the smoothed positions ({d})");
        }
    }

    #[test]
    fn perturb_replaces_the_original_and_refuses_bad_amounts() {
        let mut l = lab(Sample::CylinderCapped);
        l.step(&no_clock);
        l.perturb(0.3, 5).unwrap();
        assert_eq!(l.stats(Side::Old).work.passes, 0);
        assert_eq!(l.surface(Side::New).points(), l.original().points());
        let kept = l.original().points().to_vec();
        assert!(l.perturb(f64::NAN, 1).is_err());
        assert_eq!(l.original().points(), &kept[..], "a refused perturbation changes nothing");
    }
}
