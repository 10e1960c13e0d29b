//! Tetrahedra in the [`Lab3d`]: smoothed by the [`VolumeSmoother`] (the
//! planar drivers over stars of tetrahedra), a side's objective its
//! [`Choice`](crate::lab::Choice)'s kind carried to tetrahedra ([`solid_objective`]; the
//! planar penalty designs do not apply), coloured by the mean ratio and drawn cut by a
//! plane ([`Cut`]); the two sides' dihedral angles in Freitag's 6° bins. A node is picked
//! on the face drawn where the pointer is (the cut or the boundary), and its level sets
//! are drawn over the cut plane moved to pass through it: the node's 3D objective as the
//! node moves in that plane.

use smoothlab_render::VolumePicture;
use glam::{DVec2, DVec3};
use tiny_skia::Pixmap;

use super::{Histogram3d, Lab3d, Mesh3d, NodeSlice};
use smoothlab::error::{Error, Result};
use smoothlab::generate::perturb_volume;
use smoothlab::io::{write_model_string, Format, WriteOptions};
use crate::lab::pick::sentence;
use crate::lab::views::FigureWords;
use crate::lab::{PassSummary, Settings, Side};
use smoothlab::mesh::{ElementKind, NodeRole, Plane};
use smoothlab::model::Model;
use smoothlab::numeric::order::{sort_stable_by_key, total_order_key};
use smoothlab::objective::{describe_solid, solid_objective, CornerStar, Goal, Objective, Star, StarElement};
use smoothlab::optimize::{Iterate, SolveResult};
use smoothlab::quality::MeshStats;
use smoothlab_render::{HistogramAxis, PlaneFunction, Projection, SurfaceView};
use smoothlab::smooth::{solve_corner_star, DriverStar, SmoothOptions};
use smoothlab::volume::{volume_stats, BoundaryNode, BoundaryRule, VolumeMesh, VolumeSmoother, FEATURE_ANGLE_DEG};
use smoothlab::BoundaryReport;
use crate::lab::settings::slide_refused_quadratic;
use smoothlab_render::{Cut};

/// The objective of the tetrahedra's kind, as a side smooths with it.
type SolidObjective = dyn Objective<CornerStar> + Send + Sync;

/// The regular tetrahedron's dihedral angle, arccos(1/3), degrees: the ideal the
/// dihedral histograms mark.
const REGULAR_DIHEDRAL_DEG: f64 = 70.528_779_365_509_31;

/// A node's 3D objective over a plane through it (`plane`, its origin the node): the
/// node of `star` moved to each point of the plane; its validity the star's smallest
/// mean ratio there (signed: negative where a tetrahedron is inverted).
struct CutFunction<'a> {
    objective: &'a SolidObjective,
    star: CornerStar,
    plane: Plane,
}

impl PlaneFunction for CutFunction<'_> {
    fn goal(&self) -> Goal {
        self.objective.goal()
    }
    fn value(&self, x: DVec2) -> f64 {
        self.objective.value(&self.star, self.plane.to_3d(x))
    }
    fn validity(&self, x: DVec2) -> f64 {
        self.star.shape_at(self.plane.to_3d(x)).0
    }
}

/// The plane through `origin` across axis `axis` (0, 1, 2: x, y, z), its 2D axes the
/// other two in turn (y, z across x; z, x across y; x, y across z).
fn axis_plane(origin: DVec3, axis: usize) -> Plane {
    let (u, w) = match axis {
        0 => (DVec3::Y, DVec3::Z),
        1 => (DVec3::Z, DVec3::X),
        _ => (DVec3::X, DVec3::Y),
    };
    Plane { origin, u, w }
}

/// The section of the star's elements by `plane` (through the free node): each
/// tetrahedron the plane passes through inside cuts it in a triangle with a corner at
/// the node; another kind's element in the polygon through the points where the plane
/// meets its edges (a triangle or a quad with the node first, a larger polygon as a fan
/// from the node), drawn as a star in the plane's coordinates (the node at 0).
fn section(star: &CornerStar, plane: &Plane) -> Star {
    let normal = plane.normal();
    let size = star.tets.iter().flat_map(|t| t.pts[1..].iter().map(|p| p.distance(star.x0))).fold(0.0, f64::max);
    let eps = 1e-12 * size.max(f64::MIN_POSITIVE);
    let mut out = Star::new();
    out.node = star.node;
    out.x0 = plane.to_2d(star.x0);
    let push = |out: &mut Star, element: u32, ring: &[DVec2]| {
        let kind = if ring.len() == 3 { ElementKind::Quad4 } else { ElementKind::Tri3 };
        let mut pts = [DVec2::ZERO; 9];
        pts[0] = out.x0;
        pts[1..ring.len() + 1].copy_from_slice(ring);
        out.elems.push(StarElement { kind, element, pts, slot: 0, follow_next: false, follow_prev: false });
    };
    for t in star.tets.iter().filter(|t| t.simplex) {
        let p = [t.pts[1], t.pts[2], t.pts[3]];
        let d = p.map(|q| (q - star.x0).dot(normal));
        let mut hits: Vec<DVec3> = Vec::with_capacity(3);
        for i in 0..3 {
            if d[i].abs() <= eps {
                hits.push(p[i]);
            }
            let j = (i + 1) % 3;
            if (d[i] > eps && d[j] < -eps) || (d[i] < -eps && d[j] > eps) {
                hits.push(p[i] + (p[j] - p[i]) * (d[i] / (d[i] - d[j])));
            }
        }
        if hits.len() != 2 {
            continue; // the plane touches the tetrahedron at the node (or along an edge) only
        }
        push(&mut out, t.element, &[plane.to_2d(hits[0]), plane.to_2d(hits[1])]);
    }
    for e in &star.elements {
        let p = e.corners(&e.pts);
        let d: Vec<f64> = p.iter().map(|q| (*q - star.x0).dot(normal)).collect();
        let mut hits: Vec<DVec2> = Vec::new();
        for (i, di) in d.iter().enumerate() {
            if i != e.slot as usize && di.abs() <= eps {
                hits.push(plane.to_2d(p[i]));
            }
        }
        for &[i, j] in e.kind.row().edges {
            if (d[i] > eps && d[j] < -eps) || (d[i] < -eps && d[j] > eps) {
                hits.push(plane.to_2d(p[i] + (p[j] - p[i]) * (d[i] / (d[i] - d[j]))));
            }
        }
        if hits.len() < 2 {
            continue;
        }
        // the polygon's points in turn around it, from the node
        let centre = (hits.iter().sum::<DVec2>() + out.x0) / (hits.len() + 1) as f64;
        let angle = |q: DVec2| (q - centre).y.atan2((q - centre).x);
        let a0 = angle(out.x0);
        let turn = |q: DVec2| (angle(q) - a0).rem_euclid(std::f64::consts::TAU);
        sort_stable_by_key(&mut hits, |&q| total_order_key(turn(q)));
        if hits.len() <= 3 {
            push(&mut out, e.element, &hits);
        } else {
            for w in hits.windows(2) {
                push(&mut out, e.element, w);
            }
        }
    }
    out
}

/// A solve in space seen in `plane`: its positions projected onto it (the values and
/// step lengths as they were).
fn projected(r: SolveResult<DVec3>, plane: &Plane) -> SolveResult {
    SolveResult {
        x: plane.to_2d(r.x),
        value: r.value,
        x0: plane.to_2d(r.x0),
        value0: r.value0,
        iterations: r.iterations,
        stop: r.stop,
        history: r.history.iter().map(|it| Iterate { x: plane.to_2d(it.x), value: it.value, direction: it.direction, step: it.step }).collect(),
    }
}

impl Mesh3d for VolumeMesh {
    const KIND: &'static str = "volume";
    const WHAT: &'static str = "a volume mesh";
    const EXPORTS: &'static [Format] = &[Format::Msh, Format::Vtk];
    type Smoother = VolumeSmoother;
    type Objective = dyn Objective<CornerStar> + Send + Sync;
    type Cut = Cut;

    fn node_count(&self) -> usize {
        VolumeMesh::node_count(self)
    }
    fn element_count(&self) -> usize {
        VolumeMesh::element_count(self)
    }
    fn smoother(o: SmoothOptions) -> Result<VolumeSmoother> {
        VolumeSmoother::new(o)
    }
    fn objective(settings: &Settings, side: Side) -> Result<Box<dyn Objective<CornerStar> + Send + Sync>> {
        solid_objective(settings.choice(side).objective)
    }
    fn pass(
        &mut self,
        smoother: &mut VolumeSmoother,
        objective: &(dyn Objective<CornerStar> + Send + Sync),
        pass: u32,
        clock: &dyn Fn() -> f64,
    ) -> PassSummary {
        // the page makes a new smoother for each pass's settings: the run's first pass
        // fits the mesh to its targets first, as `smoothlab smooth` runs it
        smoother.set_fit_pending(pass == 1);
        smoother.pass(self, objective, pass, clock)
    }
    fn stats(&self) -> MeshStats {
        volume_stats(self)
    }
    fn aim_at(&mut self, target: smoothlab::target::Target, at: &VolumeMesh) {
        self.set_target_from(target, at.nodes().to_vec());
    }
    fn slide_refused(&self) -> Option<String> {
        self.is_quadratic().then(slide_refused_quadratic)
    }
    /// The core's rule at its default feature angle ([`FEATURE_ANGLE_DEG`]), as
    /// `smoothlab smooth --boundary slide` takes it.
    fn set_boundary_rule(&mut self, rule: BoundaryRule) {
        if self.boundary_rule() != rule {
            self.set_boundary(rule, FEATURE_ANGLE_DEG);
        }
    }
    fn boundary_report(&self) -> Option<BoundaryReport> {
        (self.boundary_rule() == BoundaryRule::Slide).then(|| BoundaryReport::of(self))
    }
    /// The interior perturbed as `smoothlab generate perturb` perturbs the file: the
    /// boundary stays whatever the rule (a sliding node is free, but not to be thrown off
    /// the boundary), and a sliding rule is taken again on the perturbed mesh.
    fn perturbed(&self, amount: f64, seed: u64) -> Result<VolumeMesh> {
        let rule = self.boundary_rule();
        if rule == BoundaryRule::Fixed {
            return perturb_volume(self, amount, seed);
        }
        let mut fixed = self.clone();
        fixed.set_boundary(BoundaryRule::Fixed, FEATURE_ANGLE_DEG);
        let mut out = perturb_volume(&fixed, amount, seed)?;
        out.set_boundary(rule, FEATURE_ANGLE_DEG);
        Ok(out)
    }
    /// The letter and what the side smooths with, in 3D's words ([`describe_solid`]; the
    /// planar penalty designs do not apply).
    fn side_title(settings: &Settings, side: Side) -> String {
        let kind = settings.choice(side).objective;
        // a planar-only kind never gets here: set_settings refuses it
        format!("{}: {kind}: {}", side.letter(), describe_solid(kind).unwrap_or("planar only"))
    }
    fn side_label(settings: &Settings, side: Side) -> String {
        format!("{}: {}", side.letter(), settings.choice(side).objective)
    }
    fn quality_label(&self) -> &'static str {
        "mean ratio"
    }
    fn draw(&self, pm: &mut Pixmap, cut: Cut, view: &SurfaceView) -> Projection {
        self.render_cut(pm, cut, view)
    }
    /// The nearest node of the face drawn there: a face the cut opens, or the boundary.
    fn pick(&self, cut: Cut, proj: &Projection, at: DVec2, _radius: f64) -> Option<usize> {
        let faces = self.cut_faces(cut, proj.forward());
        proj.pick_on_faces(&faces.faces(self.nodes()), at.x, at.y)
    }
    fn point(&self, n: usize) -> DVec3 {
        self.nodes()[n]
    }
    fn why_not_free(&self, n: usize) -> Option<String> {
        if n >= self.node_count() {
            return Some(format!("there is no node {n}: the nodes are numbered 0 to {}", self.node_count().saturating_sub(1)));
        }
        if self.is_free(n) {
            return None;
        }
        match self.boundary_node(n) {
            Some(BoundaryNode::Corner) => {
                return Some(format!(
                    "node {n} is a corner of the boundary (where feature curves meet, turn or end): it stays while the other boundary nodes slide"
                ))
            }
            Some(BoundaryNode::Held) if self.role(n) == NodeRole::Corner => {
                return Some(format!("node {n} is fixed by the file: it stays while the boundary slides"))
            }
            _ => {}
        }
        Some(match self.role(n) {
            NodeRole::Corner => format!(
                "node {n} is fixed: it is on the boundary of the volume (or the file fixes it), and smoothing keeps it in place"
            ),
            NodeRole::Unused => format!("node {n} belongs to no tetrahedron"),
            _ => format!("node {n} is a mid-edge node of a quadratic tetrahedron: it follows the two corners of its edge, so choose a corner"),
        })
    }
    /// The free node whose star has the smallest mean ratio.
    fn worst_free_node(&self) -> Option<usize> {
        let mut star = CornerStar::default();
        (0..self.node_count())
            .filter(|&n| self.is_free(n))
            .map(|n| {
                star.gather(self, n);
                (n, star.shape_at(star.x0).0)
            })
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(n, _)| n)
    }
    /// The edges from the node to the other corners of its tetrahedra.
    fn star_lines(&self, n: usize) -> Vec<Vec<DVec3>> {
        if n >= self.node_count() {
            return Vec::new();
        }
        let mut star = CornerStar::default();
        star.gather(self, n);
        star.tets.iter().flat_map(|t| t.pts[1..].iter().map(|&p| vec![t.pts[0], p])).collect()
    }
    /// The cut plane moved to pass through the node: the node's objective as it moves in
    /// that plane, the section of its tetrahedra by it, and the solve in space (its path
    /// and optimum projected onto the plane).
    fn slice<'a>(&self, objective: &'a SolidObjective, node: usize, cut: Cut, options: &SmoothOptions) -> Result<NodeSlice<'a>> {
        if let Some(why) = self.why_not_free(node) {
            return Err(Error::invalid(sentence(&why)));
        }
        let mut star = CornerStar::default();
        star.gather(self, node);
        let axis = cut.axis.min(2);
        let plane = axis_plane(star.x0, axis);
        let solve = solve_corner_star(objective, &star, star.x0, options)?;
        let target = solve.x;
        let outline = section(&star, &plane);
        let name = ["x", "y", "z"][axis];
        Ok(NodeSlice {
            outline,
            solve: projected(solve, &plane),
            target,
            function: Box::new(CutFunction { objective, star, plane }),
            plane: format!(
                "the plane across {name} through the node (the cut's axis), its elements' section drawn; the solve moves the node in space, its path projected onto the plane"
            ),
        })
    }
    /// The kind's name and what it is, in 3D's words.
    fn objective_label(settings: &Settings, side: Side) -> String {
        let kind = settings.choice(side).objective;
        format!("{kind} ({})", describe_solid(kind).unwrap_or("planar only").split(" (").next().unwrap_or(""))
    }
    /// The node at `to` (a node that slides at the nearest point of its curve or part of
    /// the boundary as loaded), its mid-edge nodes at their edges' middles.
    fn place_node(&mut self, node: usize, to: DVec3) {
        self.nodes_mut()[node] = self.onto_boundary(node, to);
        self.settle(node);
        self.follow_mid_nodes(node);
    }
    /// The positions of the node and of every node of its tetrahedra.
    type Kept = Vec<(usize, DVec3)>;
    fn keep_around(&self, node: usize) -> Vec<(usize, DVec3)> {
        let mut star = CornerStar::default();
        star.gather(self, node);
        let mut ids: Vec<usize> = std::iter::once(node)
            .chain(star.tets.iter().flat_map(|t| self.element(t.element as usize).iter().map(|&m| m as usize)))
            .collect();
        ids.sort_unstable();
        ids.dedup();
        ids.into_iter().map(|m| (m, self.nodes()[m])).collect()
    }
    fn put_back(&mut self, kept: Vec<(usize, DVec3)>) {
        for (m, p) in kept {
            if let Some(slot) = self.nodes_mut().get_mut(m) {
                *slot = p;
                self.settle(m); // a sliding node's tangent where it is again
            }
        }
    }
    const PASS_TITLES: [&'static str; 4] = ["min dihedral angle (°)", "max dihedral angle (°)", "min mean ratio", "inverted elements"];
    const FIGURE_WORDS: FigureWords =
        FigureWords { angles: "dihedral angles", min_quality: "min mean ratio", mean_quality: "average mean ratio" };
    const HISTOGRAMS: &'static [Histogram3d] = &[Histogram3d {
        title: "Dihedral angles (6° bins)",
        counts: |s| &s.angle_histogram_6deg,
        axis: HistogramAxis {
            x_label: "dihedral angle (°)",
            y_label: "dihedral angles (%)",
            marks: &[REGULAR_DIHEDRAL_DEG],
            ..HistogramAxis::ANGLES
        },
    }, Histogram3d {
        // each element's worst corner (`SolidStats::scaled_jacobian_histogram`): 1 for a
        // cube's, a right wedge's or the regular tetrahedron's best corner; ≤ 0 inverted
        title: "Scaled Jacobian, worst corner (0.1 bins)",
        counts: |s| s.solid.as_ref().map_or(&[], |v| &v.scaled_jacobian_histogram),
        axis: HistogramAxis {
            lo: -1.0,
            hi: 1.0,
            step: 0.5,
            x_label: "scaled Jacobian",
            y_label: "elements (%)",
            marks: &[0.0, 1.0],
        },
    }];
    fn write(&self, format: Format) -> Result<String> {
        write_model_string(&Model::Volume(self.clone()), format, &WriteOptions::default())
    }
    fn arrays(&self) -> smoothlab::io::MeshArrays {
        smoothlab::io::volume_arrays(self)
    }
    /// What the file's triangles and quads fixed off the boundary
    /// ([`VolumeMesh::stray_faces_note`]).
    fn file_note(&self) -> Option<String> {
        self.stray_faces_note()
    }
}

/// What only tetrahedra have: the cut plane.
impl Lab3d<VolumeMesh> {
    /// Cuts both sides across `axis` (0, 1, 2: x, y, z) at the fraction `at` of the mesh's
    /// extent; anything else is refused, saying why.
    pub fn set_cut(&mut self, axis: usize, at: f64) -> Result<()> {
        if axis > 2 || !(0.0..=1.0).contains(&at) {
            return Err(Error::invalid(format!("cut across axis {axis} at {at}: give axis 0, 1 or 2 and 0 to 1")));
        }
        self.cut = Cut { axis, at };
        Ok(())
    }

}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lab::sample::Sample;
    use crate::lab::views::Canvas;
    use smoothlab_render::{Metric, VolumePicture};

    fn lab() -> Lab3d<VolumeMesh> {
        let Model::Volume(m) = Sample::Rand3d.model().unwrap() else { panic!("rand3d is tetrahedral") };
        Lab3d::new(m).unwrap()
    }

    fn no_clock() -> f64 {
        0.0
    }

    #[test]
    fn the_input_target_is_the_mesh_as_last_perturbed_for_the_whole_run_as_the_cli_takes_it() {
        use smoothlab::target::Target;
        let mut l = lab();
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
            let mut model = Model::Volume(l.original().clone());
            let smoothing = smoothlab::Smoothing::default()
                .objective(c.objective)
                .strategy(settings.strategy)
                .target(Target::Input)
                .passes(2)
                .finish(0);
            model.smooth(&smoothing).unwrap();
            let Model::Volume(cli) = model else {
                unreachable!()
            };
            assert_eq!(l.mesh(side).nodes(), cli.nodes(), "{side:?}");
            assert_ne!(l.mesh(side).nodes(), l.original().nodes(), "{side:?} moved");
        }
        // back to the ideal: the sides are measured as before, a pass as the ideal's
        l.set_settings(Settings::default()).unwrap();
        l.reset();
        let [_, b] = l.step(&no_clock);
        let mut model = Model::Volume(l.original().clone());
        let c = Settings::default().choice(Side::B);
        let smoothing = smoothlab::Smoothing::default()
            .objective(c.objective)
            .passes(1)
            .finish(0);
        model.smooth(&smoothing).unwrap();
        let Model::Volume(cli) = model else {
            unreachable!()
        };
        assert_eq!(l.mesh(Side::B).nodes(), cli.nodes());
        assert_eq!(b.pass, 1);
    }

    /// A 3D boundary layer of hexahedra against its stretch: the page makes a new smoother
    /// for each pass's settings, yet only the run's first pass fits the mesh to its
    /// targets, as `smoothlab smooth` runs it (two passes, node for node).
    #[test]
    fn only_the_run_s_first_pass_fits_to_the_targets_as_the_cli_runs_it() {
        use smoothlab::generate::{hex_grid, HexBlock};
        use smoothlab::target::Target;
        let mut m = hex_grid(&HexBlock { cells: [4, 4, 6], size: glam::DVec3::new(1.0, 1.0, 0.3), bend: 0.0 }).unwrap();
        let mut rng = smoothlab::numeric::SplitMix64::new(7);
        for p in m.nodes_mut() {
            let inside = p.x > 0.0 && p.x < 1.0 && p.y > 0.0 && p.y < 1.0 && p.z > 0.0 && p.z < 0.3;
            p.z = 0.3 * (1.6f64.powf(p.z / 0.05) - 1.0) / (1.6f64.powi(6) - 1.0);
            if inside {
                p.x += rng.uniform(-0.03, 0.03);
                p.y += rng.uniform(-0.03, 0.03);
            }
        }
        let mut l = Lab3d::new(m).unwrap();
        let settings = Settings {
            strategy: smoothlab::smooth::Strategy::Rules,
            target: Target::Stretch,
            compare: [crate::lab::settings::Choice::NEW; 2],
            ..Settings::default()
        };
        let mut fits = Vec::new();
        for _ in 0..2 {
            l.set_settings(settings).unwrap();
            fits.push(l.step(&no_clock)[1].counts.fit_steps);
        }
        assert!(fits[0] > 0 && fits[1] == 0, "fit steps by pass: {fits:?}");
        let mut model = Model::Volume(l.original().clone());
        let report = model.smooth(&smoothlab::Smoothing::default().strategy(settings.strategy).target(Target::Stretch).passes(2).finish(0)).unwrap();
        assert_eq!(report.target(), Target::Stretch);
        let Model::Volume(cli) = model else { unreachable!() };
        assert_eq!(l.mesh(Side::B).nodes(), cli.nodes());
    }

    /// A block of 4³ hexahedra bent by 60° (curved faces, twelve feature curves), its
    /// interior tangled, as a file without fixed flags reads: the boundary is the skin.
    fn bent_block() -> VolumeMesh {
        let block = smoothlab::generate::HexBlock { bend: 60.0, ..smoothlab::generate::HexBlock::cube(4) };
        perturb_volume(&smoothlab::generate::hex_grid(&block).unwrap(), 0.6, 3).unwrap()
    }

    #[test]
    fn a_sliding_boundary_steps_as_the_cli_takes_it_on_the_mesh_as_loaded() {
        let mut l = Lab3d::new(bent_block()).unwrap();
        let slide = Settings { boundary: BoundaryRule::Slide, ..Settings::default() };
        l.step(&no_clock); // the rule starts both sides again, from the mesh as loaded
        l.set_settings(slide).unwrap();
        assert_eq!(l.table(Side::B).work.passes, 0);
        assert_eq!(l.original().boundary_rule(), BoundaryRule::Slide);
        let b = l.table(Side::B).boundary.expect("the boundary's report");
        assert_eq!((b.curves, b.corners, b.curve_nodes, b.surface_nodes), (12, 8, 12 * 3, 6 * 9));
        for _ in 0..2 {
            // settings between passes (the page sends them before each Step) start no new
            // run: the passes keep the grading the run found, as the tool's do
            l.set_settings(slide).unwrap();
            l.step(&no_clock);
        }
        for side in Side::BOTH {
            let c = slide.choice(side);
            let mut model = Model::Volume(bent_block());
            let smoothing = smoothlab::Smoothing::default().objective(c.objective).boundary(BoundaryRule::Slide).passes(2).finish(0);
            let report = model.smooth(&smoothing).unwrap();
            let Model::Volume(cli) = model else { unreachable!() };
            assert_eq!(l.mesh(side).nodes(), cli.nodes(), "{side:?}");
            assert_eq!(l.table(side).boundary.as_ref(), report.boundary(), "{side:?}");
        }
        // boundary nodes moved, the corners did not
        let (m, o) = (l.mesh(Side::B).clone(), l.original().clone());
        let moved = |k: BoundaryNode| (0..m.node_count()).filter(|&n| m.boundary_node(n) == Some(k) && m.nodes()[n] != o.nodes()[n]).count();
        assert!(moved(BoundaryNode::Surface) > 20 && moved(BoundaryNode::Curve) > 5, "{} {}", moved(BoundaryNode::Surface), moved(BoundaryNode::Curve));
        assert_eq!(moved(BoundaryNode::Corner), 0);
        // a corner cannot be chosen, saying why; a sliding node can, and Smooth this node
        // keeps it on the boundary
        let corner = (0..m.node_count()).find(|&n| m.boundary_node(n) == Some(BoundaryNode::Corner)).unwrap();
        let e = l.choose_node(Some(corner)).unwrap_err().to_string();
        assert!(e.contains("is a corner of the boundary"), "{e}");
        let on_face = (0..m.node_count()).find(|&n| m.boundary_node(n) == Some(BoundaryNode::Surface)).unwrap();
        l.choose_node(Some(on_face)).unwrap();
        let c = Canvas { w: 160, h: 160, dpr: 1.0 };
        l.smooth_chosen_node(c, c).unwrap();
        assert!(l.table(Side::B).boundary.unwrap().max_distance < 1e-12);
        // a perturbation moves the interior only, and the boundary slides on the new mesh
        let skin: Vec<DVec3> = (0..o.node_count()).filter(|&n| o.boundary_node(n) != Some(BoundaryNode::Interior)).map(|n| o.nodes()[n]).collect();
        l.perturb(0.3, 5).unwrap();
        let p = l.original();
        assert_eq!(p.boundary_rule(), BoundaryRule::Slide);
        let after: Vec<DVec3> = (0..p.node_count()).filter(|&n| p.boundary_node(n) != Some(BoundaryNode::Interior)).map(|n| p.nodes()[n]).collect();
        assert_eq!(skin, after, "the perturbation leaves the boundary where it was");
        // back to fixed: both sides start again, held
        l.set_settings(Settings::default()).unwrap();
        assert!(l.table(Side::A).boundary.is_none() && l.original().boundary_rule() == BoundaryRule::Fixed);
    }

    #[test]
    fn the_marks_of_a_sliding_boundary_are_drawn_and_a_fixed_one_draws_as_before() {
        let mut l = Lab3d::new(bent_block()).unwrap();
        let c = Canvas { w: 320, h: 280, dpr: 1.0 };
        let fixed = l.render(Side::B, c).unwrap().0;
        let plain = {
            let mut pm = Pixmap::new(c.w, c.h).unwrap();
            let view = SurfaceView { title: Some(l.side_title(Side::B)), ..SurfaceView::default() };
            smoothlab_render::render_surface(&mut pm, &l.mesh(Side::B).cut_faces(l.cut(), view.camera.basis().2).faces(l.mesh(Side::B).nodes()), &SurfaceView { bar_title: "mean ratio".into(), ..view });
            pm
        };
        assert_eq!(fixed.data(), plain.data(), "a fixed boundary draws no mark");
        l.set_settings(Settings { boundary: BoundaryRule::Slide, ..Settings::default() }).unwrap();
        let sliding = l.render(Side::B, c).unwrap().0;
        let purple = |pm: &Pixmap| pm.pixels().iter().filter(|p| [p.red(), p.green(), p.blue()] == smoothlab_render::MARK_LINE_RGB).count();
        assert_eq!(purple(&fixed), 0);
        assert!(purple(&sliding) > 50, "the feature curves are drawn: {} pixels", purple(&sliding));
    }

    #[test]
    fn only_a_linear_volume_mesh_s_boundary_slides() {
        let slide = Settings { boundary: BoundaryRule::Slide, ..Settings::default() };
        let q = smoothlab::generate::tet_cube(2).unwrap().to_quadratic(false).unwrap();
        assert!(q.is_quadratic());
        let mut quadratic = Lab3d::new(q).unwrap();
        let e = quadratic.set_settings(slide).unwrap_err().to_string();
        assert!(e.contains("the boundary cannot slide here: only a linear volume mesh's boundary nodes slide so far"), "{e}");
        assert_eq!(quadratic.settings().boundary, BoundaryRule::Fixed, "a refusal changes nothing");
        assert!(lab().slide_refused().is_none());
    }

    #[test]
    fn passes_improve_the_sample_and_reset_restores_it() {
        let mut l = lab();
        let start = l.stats(Side::B);
        assert!(start.mesh.volume_kinds.get(smoothlab::mesh::VolumeKind::Tet4) > 5000);
        let before = l.mesh(Side::B).nodes().to_vec();
        let [old, new] = l.step(&no_clock);
        assert_eq!((old.pass, new.pass), (1, 1));
        assert_eq!(new.after.inverted, 0);
        assert!(new.after.min_angle_deg > start.mesh.min_angle_deg);
        assert_eq!(l.table(Side::B).work.passes, 1);
        l.reset();
        assert_eq!(l.mesh(Side::B).nodes(), &before[..]);
        assert_eq!(l.stats(Side::B), start);
    }

    #[test]
    fn cuts_pictures_and_exports() {
        let mut l = lab();
        assert!(l.set_cut(3, 0.5).is_err() && l.set_cut(0, 1.5).is_err());
        l.set_cut(0, 0.4).unwrap();
        assert_eq!(l.cut(), Cut { axis: 0, at: 0.4 });
        let c = Canvas { w: 300, h: 240, dpr: 1.0 };
        let (pm, _) = l.render(Side::A, c).unwrap();
        // not blank: the cut is coloured
        assert!(pm.pixels().iter().any(|p| p.red() != p.green() || p.green() != p.blue()));
        let h = l.render_histogram(0, Side::B, c, false).unwrap();
        assert_eq!((h.width(), h.height()), (300, 240));
        // the log scale draws the same counts differently (the small bins stand taller)
        let log = l.render_histogram(0, Side::B, c, true).unwrap();
        assert_eq!((log.width(), log.height()), (300, 240));
        assert_ne!(h.data(), log.data(), "the log scale changes the picture");
        // the second histogram, each element's worst corner scaled Jacobian: every element
        // counted once, a picture of its own
        let sj = (VolumeMesh::HISTOGRAMS[1].counts)(l.full_stats(Side::B));
        assert_eq!((sj.len(), sj.iter().sum::<u64>()), (20, l.mesh(Side::B).element_count() as u64));
        assert_ne!(l.render_histogram(1, Side::B, c, false).unwrap().data(), h.data());
        assert!(l.render_histogram(2, Side::B, c, false).is_err());
        let text = l.export(Side::B, Format::Vtk).unwrap();
        let Model::Volume(back) = smoothlab::io::read_model_str(&text, Format::Vtk).unwrap() else {
            panic!("not tetrahedra")
        };
        assert_eq!(back.nodes(), l.mesh(Side::B).nodes());
        assert!(l.export(Side::B, Format::Obj).is_err());
        l.perturb(0.8, 3).unwrap();
        assert!(l.stats(Side::A).mesh.inverted > 0);
    }

    #[test]
    fn a_frame_draws_both_sides_and_exports_tetrahedral_formats_only() {
        let mut l = lab();
        assert_eq!(l.kind(), "volume");
        let c = Canvas { w: 200, h: 160, dpr: 1.0 };
        let f = l.frame(c, &no_clock).unwrap();
        assert_eq!(f.pictures[1].data(), l.render(Side::B, c).unwrap().0.data());
        let outside = l.pick_in_frame(Side::A, DVec2::new(2.0, 80.0), 64.0).unwrap();
        assert_eq!((outside.node, outside.nearest), (None, None), "beside the mesh: no face, no node");
        assert!(l.export_named(Side::B, "msh").unwrap().starts_with("$MeshFormat"));
        let e = l.export_named(Side::B, "obj").unwrap_err().to_string();
        assert!(e.contains("cannot export a volume mesh as 'obj': use msh or vtk"), "{e}");
        assert_eq!(l.not_planar(), None);
    }

    /// rand3D drawn on a canvas, cut half way up z, and a node picked on a face of the cut
    /// (its middle, as the test finds it).
    fn picked_on_the_cut() -> (Lab3d<VolumeMesh>, usize, DVec2) {
        let mut l = lab();
        let c = Canvas { w: 320, h: 320, dpr: 1.0 };
        l.frame(c, &no_clock).unwrap();
        let (_, proj) = l.render(Side::A, c).unwrap();
        let m = l.mesh(Side::A);
        let faces = m.cut_faces(l.cut(), proj.forward());
        // a face the cut opens (not the faded boundary) near the middle of the picture
        let mid = DVec2::new(160.0, 170.0);
        let centroid = |f: usize| {
            let ring = &faces.rings[faces.ring_start[f] as usize..faces.ring_start[f + 1] as usize];
            ring.iter().map(|&n| proj.to_css(m.nodes()[n as usize])).sum::<DVec2>() / ring.len() as f64
        };
        let f = (0..faces.values.len()).filter(|&f| !faces.faded[f]).min_by(|&a, &b| centroid(a).distance(mid).total_cmp(&centroid(b).distance(mid))).unwrap();
        let at = centroid(f);
        let p = l.pick_in_frame(Side::A, at, 14.0).unwrap();
        let ring = &faces.rings[faces.ring_start[f] as usize..faces.ring_start[f + 1] as usize];
        let n = p.node.expect("a node of the cut is inside the cube: free");
        assert!(ring.contains(&(n as u32)), "node {n} is a node of the face clicked {ring:?}");
        (l, n, at)
    }

    #[test]
    fn a_hexahedral_node_s_section_is_its_elements_faces_in_the_plane() {
        // a z-plane through a node of a straight block holds a face of each of its eight
        // hexahedra: the section is those quads, the node first, its edge neighbours next
        let m = smoothlab::generate::hex_grid(&smoothlab::generate::HexBlock::cube(2)).unwrap();
        let n = (0..m.node_count()).find(|&n| m.is_free(n)).unwrap();
        let l = Lab3d::new(m).unwrap();
        let slice = l.node_slice(Side::B, n).unwrap();
        assert_eq!(slice.outline.elems.len(), 8, "{:?}", slice.outline.elems.iter().map(|e| (e.kind, e.pts[..4].to_vec())).collect::<Vec<_>>());
        for e in &slice.outline.elems {
            assert_eq!(e.kind, ElementKind::Quad4, "{:?}", &e.pts[..4]);
            let p = &e.pts[..4];
            // a unit square's quarter: the node, two edge neighbours and the diagonal
            let side = 0.5;
            assert!((p[1].length() - side).abs() < 1e-12 && (p[3].length() - side).abs() < 1e-12, "{p:?}");
            assert!((p[2].length() - side * 2f64.sqrt()).abs() < 1e-12, "{p:?}");
        }
    }

    #[test]
    fn a_click_on_the_cut_picks_a_node_of_the_face_and_its_level_sets_are_drawn_in_the_moved_cut_plane() {
        let (mut l, n, _) = picked_on_the_cut();
        let level = Canvas { w: 260, h: 260, dpr: 1.0 };
        let chart = Canvas { w: 260, h: 200, dpr: 1.0 };
        let before = l.render(Side::B, level).unwrap().0;
        l.choose_node(Some(n)).unwrap();
        assert_ne!(l.render(Side::B, level).unwrap().0.data(), before.data(), "the node is marked");
        let ([la, lb, ch], summary) = l.chosen_node_view(level, chart).unwrap();
        for pm in [&la, &lb, &ch] {
            let colours = pm.pixels().iter().map(|p| (p.red(), p.green(), p.blue())).collect::<std::collections::HashSet<_>>().len();
            assert!(colours > 20, "a picture is blank ({colours} colours)");
        }
        assert!(summary.text().contains("plane across z through the node"), "{}", summary.text());
        // the plane passes through the node across the cut's axis: the section of its star
        // has the node at 0, and the function there is the 3D objective at the node
        let slice = l.node_slice(Side::B, n).unwrap();
        assert_eq!(slice.outline.x0, DVec2::ZERO);
        assert!(!slice.outline.elems.is_empty(), "the plane cuts the node's tetrahedra");
        let mut star = CornerStar::default();
        star.gather(l.mesh(Side::B), n);
        let objective = solid_objective(l.settings().compare[1].objective).unwrap();
        assert_eq!(slice.function.value(DVec2::ZERO), objective.value(&star, star.x0));
        assert!(slice.function.validity(DVec2::ZERO) > 0.0, "rand3D is valid");
        drop(slice);
        // across x the plane's axes are y and z: a move along the plane's first axis is along y
        l.set_cut(0, 0.5).unwrap();
        let across_x = l.node_slice(Side::B, n).unwrap();
        assert!(across_x.plane.contains("across x"));
        let x0 = star.x0;
        assert_eq!(across_x.function.value(DVec2::new(1e-3, 0.0)), objective.value(&star, x0 + DVec3::new(0.0, 1e-3, 0.0)));
        drop(across_x);
        // a boundary node is refused, saying why
        let fixed = (0..l.mesh(Side::A).node_count()).find(|&m| !l.mesh(Side::A).is_free(m)).unwrap();
        let e = l.choose_node(Some(fixed)).unwrap_err().to_string();
        assert!(e.contains("on the boundary of the volume"), "{e}");
    }

    #[test]
    fn smoothing_the_node_moves_it_in_space_and_undo_puts_it_back() {
        let (mut l, n, _) = picked_on_the_cut();
        l.perturb(0.4, 2).unwrap();
        l.choose_node(Some(n)).unwrap();
        let before = Side::BOTH.map(|s| l.mesh(s).nodes().to_vec());
        let c = Canvas { w: 200, h: 200, dpr: 1.0 };
        let (_, summary) = l.smooth_chosen_node(c, c).unwrap();
        assert_ne!(l.mesh(Side::B).nodes()[n], before[1][n], "B moved the node");
        assert!(summary.solves.new.value <= summary.solves.new.value0);
        assert!(summary.solves.old.value >= summary.solves.old.value0, "old is a max-min");
        // only the node moved
        let moved = (0..before[1].len()).filter(|&m| l.mesh(Side::B).nodes()[m] != before[1][m]).count();
        assert_eq!(moved, 1);
        assert_eq!(l.undo(), Some(n));
        for s in Side::BOTH {
            assert_eq!(l.mesh(s).nodes(), &before[s.index()][..], "bit for bit");
        }
    }

    #[test]
    fn the_volume_charts_and_figure_are_in_its_words() {
        let mut l = lab();
        let c = Canvas { w: 320, h: 240, dpr: 1.0 };
        let chart0 = l.render_pass_chart(c).unwrap();
        l.step(&no_clock);
        assert_ne!(l.render_pass_chart(c).unwrap().data(), chart0.data());
        let fig = l.render_figure(Canvas { w: 640, h: 360, dpr: 1.0 }).unwrap();
        assert_eq!((fig.width(), fig.height()), (640, 360));
        assert!(l.worst_free_node().is_some_and(|n| l.mesh(Side::B).is_free(n)));
        let _ = Metric::Shape;
    }
}
