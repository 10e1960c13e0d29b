//! A surface in 3D in the [`Lab3d`](super::Lab3d): smoothed by the [`SurfaceSmoother`]
//! (Chen, Tristano & Kwok 2003 smooth surface meshes star by star in the tangent plane),
//! each side's objective its [`Choice`](crate::lab::Choice) with its penalty, coloured by
//! the planar shape measure, perturbed in its tangent planes ([`perturb_surface`]); a node
//! is picked where it is drawn, the near side winning.

use glam::DVec3;
use tiny_skia::Pixmap;

use super::Mesh3d;
use crate::error::{Error, Result};
use crate::io::{write_string, Format, WriteOptions};
use crate::lab::{PassSummary, Settings, Side};
use crate::objective::Objective;
use crate::quality::MeshStats;
use crate::render::{Metric, Projection, SurfaceView};
use crate::smooth::SmoothOptions;
use crate::generate::perturb_surface;
use crate::surface::{Surface, SurfaceSmoother};

impl Mesh3d for Surface {
    const KIND: &'static str = "surface";
    const WHAT: &'static str = "a surface";
    const EXPORTS: &'static [Format] = &[Format::Msh, Format::Vtk, Format::Obj, Format::Off];
    type Smoother = SurfaceSmoother;
    type Objective = dyn Objective;
    type Cut = ();

    fn check(&self) -> Result<()> {
        if self.element_count() == 0 {
            return Err(Error::invalid("the surface has no elements"));
        }
        Ok(())
    }
    fn node_count(&self) -> usize {
        Surface::node_count(self)
    }
    fn element_count(&self) -> usize {
        Surface::element_count(self)
    }
    fn smoother(o: SmoothOptions) -> Result<SurfaceSmoother> {
        SurfaceSmoother::new(o)
    }
    fn objective(settings: &Settings, side: Side) -> Result<Box<dyn Objective>> {
        Ok(settings.choice(side).build())
    }
    fn pass(
        &mut self,
        smoother: &mut SurfaceSmoother,
        objective: &dyn Objective,
        pass: u32,
        clock: &dyn Fn() -> f64,
    ) -> PassSummary {
        let mut r = smoother.pass(self, objective, clock);
        r.pass = pass;
        r
    }
    fn stats(&self) -> MeshStats {
        Surface::stats(self)
    }
    fn perturbed(&self, amount: f64, seed: u64) -> Result<Surface> {
        perturb_surface(self, amount, seed)
    }
    fn side_title(settings: &Settings, side: Side) -> String {
        settings.side_title(side)
    }
    fn side_label(settings: &Settings, side: Side) -> String {
        settings.side_label(side)
    }
    fn quality_label(&self) -> &'static str {
        Metric::Shape.label(self.flat())
    }
    fn draw(&self, pm: &mut Pixmap, _cut: (), view: &SurfaceView) -> Projection {
        self.render(pm, Metric::Shape, view)
    }
    fn pickable_points(&self) -> Option<&[DVec3]> {
        Some(self.points())
    }
    fn write(&self, format: Format) -> Result<String> {
        write_string(self, format, &WriteOptions::default())
    }
    fn not_planar(&self) -> Option<String> {
        Surface::not_planar(self).map(str::to_string)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;
    use crate::lab::views::Canvas;
    use crate::lab::Lab3d;
    use crate::render::Camera;
    use crate::lab::sample::Sample;
    use crate::lab::Choice;
    use crate::objective::ObjectiveKind;
    use crate::model::Model;

    fn lab(sample: Sample) -> Lab3d<Surface> {
        let Model::Surface(s) = sample.model().unwrap() else { panic!("{sample:?} is not a surface") };
        Lab3d::new(s).unwrap()
    }

    fn no_clock() -> f64 {
        0.0
    }

    #[test]
    fn passes_untangle_the_tangled_sphere_and_reset_restores_it_bit_for_bit() {
        let mut l = lab(Sample::SphereTangled);
        let start = l.stats(Side::B);
        assert!(start.mesh.inverted > 0 && start.mesh.surface);
        let before: Vec<_> = l.mesh(Side::B).points().to_vec();
        let mut last = None;
        for _ in 0..3 {
            last = Some(l.step(&no_clock));
        }
        let [old, new] = last.unwrap();
        assert_eq!((old.pass, new.pass), (3, 3));
        assert_eq!(new.after.inverted, 0, "the new objective untangles the sphere");
        let t = l.table(Side::B);
        assert_eq!((t.mesh.inverted, t.work.passes), (0, 3));
        assert!(t.max_distance_from_surface.unwrap() < 1e-9, "the nodes stay on the sphere");
        assert_ne!(l.mesh(Side::B).points(), &before[..]);
        l.reset();
        assert_eq!(l.mesh(Side::B).points(), &before[..]);
        assert_eq!(l.mesh(Side::A).points(), &before[..]);
        assert_eq!(l.stats(Side::B), start);
        let [_, again] = l.step(&no_clock);
        assert_eq!(again.pass, 1, "passes count again from the reset");
    }

    #[test]
    fn the_two_sides_differ_by_their_objective() {
        let mut l = lab(Sample::TorusTangled);
        l.step(&no_clock);
        assert_ne!(l.mesh(Side::A).points(), l.mesh(Side::B).points());
        // the same objective on both sides: the same surface, bit for bit
        let same = Settings { compare: [Choice::NEW, Choice::NEW], ..Settings::default() };
        l.set_settings(same).unwrap();
        l.reset();
        l.step(&no_clock);
        assert_eq!(l.mesh(Side::A).points(), l.mesh(Side::B).points());
        assert_eq!(l.table(Side::A).title.replacen('A', "B", 1), l.table(Side::B).title);
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
        let (a, proj) = l.render(Side::A, c).unwrap();
        assert_eq!((a.width(), a.height()), (300, 320));
        // the node nearest the viewer is picked where it is drawn
        let pts = l.mesh(Side::A).points();
        let front = (0..pts.len()).min_by(|&i, &j| proj.depth(pts[i]).total_cmp(&proj.depth(pts[j]))).unwrap();
        let at = proj.to_css(pts[front]);
        assert_eq!(l.pick(Side::A, c, at, 3.0).unwrap(), Some(front));
        assert_eq!(l.pick(Side::A, c, DVec2::new(-50.0, -50.0), 3.0).unwrap(), None);
        l.orbit(90.0, 0.0);
        let (turned, _) = l.render(Side::A, c).unwrap();
        assert_ne!(turned.data(), a.data(), "an orbit changes the picture");
        assert!(l.render(Side::A, Canvas { w: 0, h: 10, dpr: 1.0 }).is_err());
    }

    #[test]
    fn export_writes_the_side_surface_that_reads_back_as_a_surface() {
        let mut l = lab(Sample::SphereTangled);
        l.step(&no_clock);
        for format in [Format::Msh, Format::Vtk, Format::Obj, Format::Off] {
            let text = l.export(Side::B, format).unwrap();
            let Model::Surface(back) = crate::io::read_model_str(&text, format).unwrap() else {
                panic!("{format:?} did not read back as a surface")
            };
            assert_eq!(back.node_count(), l.mesh(Side::B).node_count());
            let d = back.points().iter().zip(l.mesh(Side::B).points()).map(|(a, b)| a.distance(*b)).fold(0.0, f64::max);
            assert!(d < 1e-9, "{format:?} keeps the smoothed positions ({d})");
        }
    }

    #[test]
    fn perturb_replaces_the_original_and_refuses_bad_amounts() {
        let mut l = lab(Sample::CylinderCapped);
        l.step(&no_clock);
        l.perturb(0.3, 5).unwrap();
        assert_eq!(l.stats(Side::A).work.passes, 0);
        assert_eq!(l.mesh(Side::B).points(), l.original().points());
        let kept = l.original().points().to_vec();
        assert!(l.perturb(f64::NAN, 1).is_err());
        assert_eq!(l.original().points(), &kept[..], "a refused perturbation changes nothing");
    }

    #[test]
    fn a_frame_draws_both_sides_and_picks_map_through_its_canvas() {
        let mut l = lab(Sample::SphereTangled);
        assert_eq!(l.kind(), "surface");
        assert!(l.pick_in_frame(Side::A, DVec2::ZERO, 3.0).is_err(), "nothing drawn yet");
        let c = Canvas { w: 240, h: 200, dpr: 1.0 };
        let f = l.frame(c, &no_clock).unwrap();
        assert_eq!(f.pictures[0].data(), l.render(Side::A, c).unwrap().0.data());
        assert_eq!(f.colour_bar, l.colour_bar_shown(c));
        let (_, proj) = l.render(Side::B, c).unwrap();
        let pts = l.mesh(Side::B).points();
        let front = (0..pts.len()).min_by(|&i, &j| proj.depth(pts[i]).total_cmp(&proj.depth(pts[j]))).unwrap();
        // a radius that is not positive and finite is the page's default
        assert_eq!(l.pick_in_frame(Side::B, proj.to_css(pts[front]), f64::NAN).unwrap(), Some(front));
        assert!(l.export_named(Side::A, "obj").unwrap().contains("\nf "));
        let e = l.export_named(Side::A, "node").unwrap_err().to_string();
        assert!(e.contains("cannot export a surface as 'node': use msh, vtk, obj or off"), "{e}");
    }
}
