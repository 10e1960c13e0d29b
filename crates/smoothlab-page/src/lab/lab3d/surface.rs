//! A surface in 3D in the [`Lab3d`](super::Lab3d): smoothed by the [`SurfaceSmoother`]
//! (Chen, Tristano & Kwok 2003 smooth surface meshes star by star in the tangent plane),
//! each side's objective its [`Choice`](crate::lab::Choice) with its penalty, coloured by
//! the planar shape measure, perturbed in its tangent planes ([`perturb_surface`]); a node
//! is picked on the face drawn where the pointer is, the near side winning, and its level
//! sets are drawn in its tangent plane, where the drivers flatten its star and solve
//! ([`Surface::tangent_star`]).

use smoothlab_render::SurfacePicture;
use glam::{DVec2, DVec3};
use tiny_skia::Pixmap;

use super::{Histogram3d, Mesh3d, NodeSlice};
use smoothlab::error::{Error, Result};
use smoothlab::generate::perturb_surface;
use smoothlab::io::{write_string, Format, WriteOptions};
use crate::lab::pick::why_not_free;
use crate::lab::views::FigureWords;
use crate::lab::{PassSummary, Settings, Side};
use smoothlab::mesh::{BoundaryNode, BoundaryRule, NodeRole, FEATURE_ANGLE_DEG};
use smoothlab::BoundaryReport;
use smoothlab::objective::{Goal, Objective, Star};
use smoothlab::quality::MeshStats;
use smoothlab_render::{HistogramAxis, Metric, PlaneFunction, Projection, StarFunction, SurfaceView, PASS_TITLES};
use smoothlab::smooth::{solve_planar_star, SmoothOptions};
use smoothlab::surface::{KeptNodes, Surface, SurfaceSmoother};

/// A surface node's objective over its tangent plane: the planar objective of its star
/// flattened there ([`StarFunction`], the star owned).
struct TangentFunction<'a> {
    objective: &'a dyn Objective,
    star: Star,
}

impl PlaneFunction for TangentFunction<'_> {
    fn goal(&self) -> Goal {
        self.objective.goal()
    }
    fn value(&self, x: DVec2) -> f64 {
        StarFunction { objective: self.objective, star: &self.star }.value(x)
    }
    fn validity(&self, x: DVec2) -> f64 {
        StarFunction { objective: self.objective, star: &self.star }.validity(x)
    }
}

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
    fn aim_at(&mut self, target: smoothlab::target::Target, at: &Surface) {
        self.set_target_from(target, at.points().to_vec());
    }
    /// A surface's curves (its open edges and feature curves) slide by the rule.
    fn slide_refused(&self) -> Option<String> {
        None
    }
    /// The core's rule at its default feature angle ([`FEATURE_ANGLE_DEG`]: a curve node
    /// where the curve turns by more than it stays), as `smoothlab smooth --boundary slide`
    /// takes it; fixed holds the curves again.
    fn set_boundary_rule(&mut self, rule: BoundaryRule) {
        match rule {
            BoundaryRule::Slide => self.slide_along_curves_with(Some(FEATURE_ANGLE_DEG)),
            BoundaryRule::Fixed => self.hold_curves(),
        }
    }
    fn boundary_report(&self) -> Option<BoundaryReport> {
        self.boundary_corner_deg().map(|_| BoundaryReport::of_surface(self))
    }
    /// Perturbed in the tangent planes as `smoothlab generate perturb` perturbs the file:
    /// the curves stay whatever the rule (a sliding node is free, but not to be thrown off
    /// its curve), and a sliding rule is taken again on the perturbed surface.
    fn perturbed(&self, amount: f64, seed: u64) -> Result<Surface> {
        if self.boundary_corner_deg().is_none() {
            return perturb_surface(self, amount, seed);
        }
        let mut held = self.clone();
        held.hold_curves();
        let mut out = perturb_surface(&held, amount, seed)?;
        out.set_boundary_rule(BoundaryRule::Slide);
        Ok(out)
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
    fn quality_domain(&self) -> (f64, f64) {
        Metric::Shape.domain(self.flat())
    }
    fn draw(&self, pm: &mut Pixmap, _cut: (), view: &SurfaceView) -> Projection {
        self.render(pm, Metric::Shape, view)
    }
    /// The nearest node of the face drawn there; beside the surface, the node drawn
    /// within `radius` (the near side winning).
    fn pick(&self, _cut: (), proj: &Projection, at: DVec2, radius: f64) -> Option<usize> {
        let faces = self.faces(Metric::Shape);
        proj.pick_on_faces(&faces.faces(self.points()), at.x, at.y).or_else(|| proj.pick(self.points(), at.x, at.y, radius))
    }
    fn point(&self, n: usize) -> DVec3 {
        self.points()[n]
    }
    /// The planar page's reasons, and a feature curve's: its nodes are fixed.
    fn why_not_free(&self, n: usize) -> Option<String> {
        let m = self.flat();
        if n < m.node_count() && !m.is_free(n) {
            match self.curve_nodes().map(|c| c[n]) {
                Some(BoundaryNode::Corner) => {
                    return Some(format!("node {n} is a corner of a curve (where it turns by more than {FEATURE_ANGLE_DEG}° or ends): it stays while the other curve nodes slide"))
                }
                Some(BoundaryNode::Held) => return Some(format!("node {n} is fixed by the file: it stays while the curves slide")),
                _ => {}
            }
        }
        if n < m.node_count() && !m.is_free(n) && m.role(n) == NodeRole::Corner && self.is_feature(n) {
            return Some(format!(
                "node {n} is fixed: it lies on a feature curve (where the surface bends by more than 30°), which smoothing keeps in place"
            ));
        }
        why_not_free(m, n)
    }
    fn worst_free_node(&self) -> Option<usize> {
        Surface::worst_free_node(self)
    }
    /// The outlines of the node's elements (their corners).
    fn star_lines(&self, n: usize) -> Vec<Vec<DVec3>> {
        let m = self.flat();
        if n >= m.node_count() {
            return Vec::new();
        }
        m.node_elements(n)
            .iter()
            .map(|&e| {
                let ids = m.element(e as usize);
                let k = m.kind(e as usize).corners();
                (0..=k).map(|i| self.points()[ids[i % k] as usize]).collect()
            })
            .collect()
    }
    /// The node's star flattened into its tangent plane, where the drivers solve: the
    /// solve is the one a pass makes there.
    fn slice<'a>(&self, objective: &'a dyn Objective, node: usize, _cut: (), options: &SmoothOptions) -> Result<NodeSlice<'a>> {
        let (star, plane) = self.tangent_star(node)?;
        let solve = solve_planar_star(objective, &star, star.x0, options)?;
        let target = plane.to_3d(solve.x);
        Ok(NodeSlice {
            outline: star.clone(),
            function: Box::new(TangentFunction { objective, star }),
            solve,
            target,
            plane: "its tangent plane (the star flattened there, as the smoother sees it)".into(),
        })
    }
    fn objective_label(settings: &Settings, side: Side) -> String {
        settings.choice(side).label()
    }
    /// Lifted onto the surface (its projection), as the smoother puts a node, the nodes
    /// that follow it projected from their edges' middles.
    fn place_node(&mut self, node: usize, to: DVec3) {
        self.place(node, to);
    }
    type Kept = KeptNodes;
    fn keep_around(&self, node: usize) -> KeptNodes {
        Surface::keep_around(self, node)
    }
    fn put_back(&mut self, kept: KeptNodes) {
        Surface::put_back(self, kept);
    }
    const PASS_TITLES: [&'static str; 4] = PASS_TITLES;
    const FIGURE_WORDS: FigureWords = FigureWords::PLANAR;
    const HISTOGRAMS: &'static [Histogram3d] =
        &[Histogram3d { title: "Corner angles (6° bins)", counts: |s| &s.angle_histogram_6deg, axis: HistogramAxis::ANGLES }];
    fn write(&self, format: Format) -> Result<String> {
        write_string(self, format, &WriteOptions::default())
    }
    fn arrays(&self) -> smoothlab::io::MeshArrays {
        smoothlab::io::mesh_arrays(self)
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
    use smoothlab_render::Camera;
    use crate::lab::sample::Sample;
    use crate::lab::screen::UndoSummary;
    use crate::lab::Choice;
    use smoothlab::objective::ObjectiveKind;
    use smoothlab::model::Model;

    fn lab(sample: Sample) -> Lab3d<Surface> {
        let Model::Surface(s) = sample.model().unwrap() else { panic!("{sample:?} is not a surface") };
        Lab3d::new(s).unwrap()
    }

    fn no_clock() -> f64 {
        0.0
    }

    #[test]
    fn the_input_target_is_the_mesh_as_last_perturbed_for_the_whole_run_as_the_cli_takes_it() {
        use smoothlab::target::Target;
        let mut l = lab(Sample::CylinderCapped);
        l.perturb(0.3, 3).unwrap();
        let settings = Settings {
            strategy: smoothlab::smooth::Strategy::Rules,
            target: Target::Input,
            ..Settings::default()
        };
        l.set_settings(settings).unwrap();
        for _ in 0..2 {
            l.step(&no_clock);
        }
        for side in Side::BOTH {
            let c = settings.choice(side);
            let mut model = Model::Surface(l.original().clone());
            let mut smoothing = smoothlab::Smoothing::default()
                .objective(c.objective)
                .strategy(settings.strategy)
                .target(Target::Input)
                .passes(2)
                .finish(0);
            if c.objective == ObjectiveKind::SmoothShape {
                smoothing = smoothing.penalty(c.penalty);
            }
            model.smooth(&smoothing).unwrap();
            let Model::Surface(cli) = model else {
                unreachable!()
            };
            assert_eq!(l.mesh(side).points(), cli.points(), "{side:?}");
            assert_ne!(
                l.mesh(side).points(),
                l.original().points(),
                "{side:?} moved"
            );
        }
        // back to the ideal: the sides are measured as before, a pass as the ideal's
        l.set_settings(Settings::default()).unwrap();
        l.reset();
        let [_, b] = l.step(&no_clock);
        let mut model = Model::Surface(l.original().clone());
        let c = Settings::default().choice(Side::B);
        let smoothing = smoothlab::Smoothing::default()
            .objective(c.objective)
            .penalty(c.penalty)
            .passes(1)
            .finish(0);
        model.smooth(&smoothing).unwrap();
        let Model::Surface(cli) = model else {
            unreachable!()
        };
        assert_eq!(l.mesh(Side::B).points(), cli.points());
        assert_eq!(b.pass, 1);
    }

    #[test]
    fn the_curves_slide_as_the_cli_slides_them_and_hold_again() {
        use smoothlab::volume::BoundaryRule;
        let sample = || match Sample::CylinderCapped.model().unwrap() {
            Model::Surface(s) => s,
            _ => unreachable!(),
        };
        let mut l = lab(Sample::CylinderCapped);
        let c = Canvas { w: 320, h: 280, dpr: 1.0 };
        let fixed = l.render(Side::B, c).unwrap().0;
        let slide = Settings { boundary: BoundaryRule::Slide, ..Settings::default() };
        l.set_settings(slide).unwrap();
        let b = l.table(Side::B).boundary.expect("the boundary's report");
        // the two rims, each a closed curve that turns nowhere sharply: every node slides
        assert_eq!((b.curves, b.corners, b.held, b.surface_nodes), (2, 0, 0, 0));
        assert!(b.curve_nodes > 20, "{b:?}");
        for _ in 0..2 {
            // the page sends its settings before each Step
            l.set_settings(slide).unwrap();
            l.step(&no_clock);
        }
        for side in Side::BOTH {
            let c = slide.choice(side);
            let mut model = Model::Surface(sample());
            let mut smoothing = smoothlab::Smoothing::default().objective(c.objective).boundary(BoundaryRule::Slide).passes(2).finish(0);
            if c.objective == ObjectiveKind::SmoothShape {
                smoothing = smoothing.penalty(c.penalty);
            }
            let report = model.smooth(&smoothing).unwrap();
            let Model::Surface(cli) = model else { unreachable!() };
            assert_eq!(l.mesh(side).points(), cli.points(), "{side:?}");
            assert_eq!(l.table(side).boundary.as_ref(), report.boundary(), "{side:?}");
        }
        let (m, o) = (l.mesh(Side::B).clone(), l.original().clone());
        let rim: Vec<usize> = (0..m.node_count()).filter(|&n| m.slides(n)).collect();
        assert!(rim.iter().filter(|&&n| m.points()[n] != o.points()[n]).count() > 10, "the rims' nodes moved");
        assert!(l.table(Side::B).boundary.unwrap().max_distance < 1e-12);
        // the curves and their nodes are marked
        let sliding = l.render(Side::B, c).unwrap().0;
        let purple = |pm: &Pixmap| pm.pixels().iter().filter(|p| [p.red(), p.green(), p.blue()] == smoothlab_render::MARK_LINE_RGB).count();
        assert_eq!(purple(&fixed), 0);
        assert!(purple(&sliding) > 50, "{} pixels", purple(&sliding));
        // a perturbation moves the rest only, and the curves slide on the new surface
        l.perturb(0.3, 5).unwrap();
        let p = l.original();
        assert!(rim.iter().all(|&n| p.points()[n] == o.points()[n] && p.slides(n)));
        // back to fixed: the rims hold again, saying why
        l.set_settings(Settings::default()).unwrap();
        assert!(l.table(Side::A).boundary.is_none());
        assert!(rim.iter().all(|&n| !l.original().slides(n) && !l.original().flat().is_free(n)));
        let e = l.choose_node(Some(rim[0])).unwrap_err().to_string();
        assert!(e.contains("feature curve"), "{e}");
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
        assert_eq!(l.settings().compare[0].objective, ObjectiveKind::SmoothShape, "a refused setting changes nothing");
    }

    #[test]
    fn the_camera_orbits_and_zooms_within_its_limits() {
        let mut l = lab(Sample::CylinderCapped);
        let c0 = l.camera();
        l.orbit(20.0, 10.0);
        assert_eq!((l.camera().yaw, l.camera().pitch), (c0.yaw - 10.0, c0.pitch + 5.0));
        l.orbit(0.0, 1e6);
        assert_eq!(l.camera().pitch, smoothlab_render::MAX_DRAG_PITCH);
        l.orbit(f64::NAN, f64::INFINITY);
        assert_eq!(l.camera().pitch, smoothlab_render::MAX_DRAG_PITCH, "a non-finite drag changes nothing");
        l.zoom(1e9);
        assert_eq!(l.camera().zoom, smoothlab_render::ZOOM_RANGE.1);
        l.zoom(-2.0);
        l.zoom(f64::NAN);
        assert_eq!(l.camera().zoom, smoothlab_render::ZOOM_RANGE.1);
        l.zoom(1e-12);
        assert_eq!(l.camera().zoom, smoothlab_render::ZOOM_RANGE.0);
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
        assert_eq!(l.pick(Side::A, c, at, 3.0).unwrap().node, Some(front));
        let none = l.pick(Side::A, c, DVec2::new(-50.0, -50.0), 3.0).unwrap();
        assert_eq!((none.node, none.nearest), (None, None));
        assert!(none.message.unwrap().starts_with("No face of a surface there"));
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
            let Model::Surface(back) = smoothlab::io::read_model_str(&text, format).unwrap() else {
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
        assert_eq!(l.pick_in_frame(Side::B, proj.to_css(pts[front]), f64::NAN).unwrap().node, Some(front));
        assert!(l.export_named(Side::A, "obj").unwrap().contains("\nf "));
        let e = l.export_named(Side::A, "node").unwrap_err().to_string();
        assert!(e.contains("cannot export a surface as 'node': use msh, vtk, obj or off"), "{e}");
    }

    /// The tangled sphere's lab drawn on a canvas, and the node picked at its middle.
    fn picked_in_the_middle() -> (Lab3d<Surface>, usize) {
        let mut l = lab(Sample::SphereTangled);
        let c = Canvas { w: 300, h: 300, dpr: 1.0 };
        l.frame(c, &no_clock).unwrap();
        let p = l.pick_in_frame(Side::A, DVec2::new(150.0, 160.0), 14.0).unwrap();
        (l, p.node.expect("every node of the closed sphere is free"))
    }

    #[test]
    fn a_click_picks_the_nearest_node_of_the_face_drawn_there() {
        let (l, n) = picked_in_the_middle();
        let c = Canvas { w: 300, h: 300, dpr: 1.0 };
        let (_, proj) = l.render(Side::A, c).unwrap();
        let at = DVec2::new(150.0, 160.0);
        let faces = l.mesh(Side::A).faces(Metric::Shape);
        let faces = faces.faces(l.mesh(Side::A).points());
        let f = proj.face_at(&faces, at.x, at.y).unwrap();
        let ring = faces.ring(f).unwrap();
        assert!(ring.contains(&(n as u32)), "node {n} is a node of the face clicked");
        let d = |m: u32| proj.to_css(l.mesh(Side::A).points()[m as usize]).distance(at);
        assert!(ring.iter().all(|&m| d(m) >= d(n as u32)), "and the nearest of them");
        // the face is on the near side: its centroid is nearer than the sphere's centre
        let z = ring.iter().map(|&m| proj.depth(l.mesh(Side::A).points()[m as usize])).sum::<f64>() / ring.len() as f64;
        assert!(z < 0.0, "the clicked face faces the viewer ({z})");
        // a click on another node picks it, wherever the camera turned
        let mut l = l;
        l.orbit(40.0, -10.0);
        l.frame(c, &no_clock).unwrap();
        let (at, behind) = l.node_on_screen(Side::B, n).unwrap().unwrap();
        if behind < 30.0 {
            assert_eq!(l.pick_in_frame(Side::B, at, 14.0).unwrap().node, Some(n));
        }
        assert_eq!(l.node_on_screen(Side::B, 1 << 30).unwrap(), None);
    }

    #[test]
    fn the_node_view_draws_both_objectives_in_the_tangent_plane() {
        let (mut l, n) = picked_in_the_middle();
        assert!(l.choose_node(Some(1 << 30)).is_err());
        assert_eq!(l.chosen_node(), None, "a refused choice changes nothing");
        let level = Canvas { w: 260, h: 260, dpr: 1.0 };
        let chart = Canvas { w: 260, h: 200, dpr: 1.0 };
        assert!(l.chosen_node_view(level, chart).is_err(), "no node is chosen yet");
        let before = l.render(Side::A, level).unwrap().0;
        l.choose_node(Some(n)).unwrap();
        assert_ne!(l.render(Side::A, level).unwrap().0.data(), before.data(), "the chosen node is marked");
        let ([la, lb, ch], summary) = l.chosen_node_view(level, chart).unwrap();
        for pm in [&la, &lb, &ch] {
            assert!(colours(pm) > 20, "a picture is blank");
        }
        assert_ne!(la.data(), lb.data(), "old and new differ");
        let text = summary.text();
        assert!(text.starts_with(&format!("Node {n}: A, old")) && text.contains("tangent plane"), "{text}");
        // the solve is the one the drivers make: in the plane of the flattened star
        let (star, plane) = l.mesh(Side::B).tangent_star(n).unwrap();
        assert_eq!(star.x0, DVec2::ZERO);
        assert!((plane.origin - l.mesh(Side::B).points()[n]).length() < 1e-15);
        // zoom and pan act on both level sets
        l.zoom_level_sets_in_frame(Side::A, DVec2::new(130.0, 130.0), 2.0).unwrap();
        let ([zoomed, _, _], _) = l.chosen_node_view(level, chart).unwrap();
        assert_ne!(zoomed.data(), la.data());
        l.pan_level_sets_in_frame(Side::B, DVec2::new(10.0, 0.0)).unwrap();
        l.reset_camera();
        let ([again, _, _], _) = l.chosen_node_view(level, chart).unwrap();
        assert_eq!(again.data(), la.data(), "a double-click fits them again");
        // a fixed node of the capped cylinder's rims is refused with its reason
        let mut cyl = lab(Sample::CylinderCapped);
        let fixed = (0..cyl.mesh(Side::A).node_count()).find(|&m| !cyl.mesh(Side::A).flat().is_free(m)).unwrap();
        let e = cyl.choose_node(Some(fixed)).unwrap_err().to_string();
        assert!(e.contains("feature curve") || e.contains("boundary"), "{e}");
    }

    #[test]
    fn smoothing_the_node_moves_it_on_the_surface_and_undo_puts_it_back() {
        let (mut l, n) = picked_in_the_middle();
        l.choose_node(Some(n)).unwrap();
        let before = Side::BOTH.map(|s| l.mesh(s).points().to_vec());
        let stats = Side::BOTH.map(|s| l.stats(s));
        let level = Canvas { w: 200, h: 200, dpr: 1.0 };
        let (_, summary) = l.smooth_chosen_node(level, level).unwrap();
        for s in Side::BOTH {
            let p = l.mesh(s).points()[n];
            assert_ne!(p, before[s.index()][n], "side {s:?} moved the node");
            assert!((p.length() - 1.0).abs() < 1e-9, "on the unit sphere: {}", p.length());
        }
        assert!(summary.solves.new.value <= summary.solves.new.value0, "new is a sum to minimise");
        assert_eq!(l.undo_summary(None), UndoSummary { node: None, next: Some(n), depth: 1 });
        assert_eq!(l.undo(), Some(n));
        for s in Side::BOTH {
            assert_eq!(l.mesh(s).points(), &before[s.index()][..], "bit for bit");
            assert_eq!(l.stats(s), stats[s.index()]);
        }
        assert_eq!(l.undo(), None);
        // a pass ends what can be undone
        l.smooth_chosen_node(level, level).unwrap();
        l.step(&no_clock);
        assert_eq!(l.undo_summary(None).depth, 0);
    }

    #[test]
    fn charts_histograms_and_the_figure_follow_the_passes() {
        let mut l = lab(Sample::TorusTangled);
        let c = Canvas { w: 320, h: 240, dpr: 1.0 };
        let chart0 = l.render_pass_chart(c).unwrap();
        let hist0 = l.render_histogram(0, Side::B, c, false).unwrap();
        assert!(l.render_histogram(1, Side::B, c, false).is_err(), "a surface has one histogram");
        l.step(&no_clock);
        assert_ne!(l.render_pass_chart(c).unwrap().data(), chart0.data());
        let hist1 = l.render_histogram(0, Side::B, c, false).unwrap();
        assert!(colours(&hist1) > 8);
        assert_ne!(hist1.data(), hist0.data());
        assert_ne!(l.render_histogram(0, Side::B, c, true).unwrap().data(), hist1.data(), "the log scale");
        let fig = l.render_figure(Canvas { w: 700, h: 400, dpr: 2.0 }).unwrap();
        assert_eq!((fig.width(), fig.height()), (700, 400));
        assert!(colours(&fig) > 50);
        assert!(l.render_figure(Canvas { w: 0, h: 400, dpr: 1.0 }).is_err());
    }

    fn colours(pm: &Pixmap) -> usize {
        pm.pixels().iter().map(|p| (p.red(), p.green(), p.blue())).collect::<std::collections::HashSet<_>>().len()
    }
}
