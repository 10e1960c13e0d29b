//! Surface meshes: triangles and quads, linear or quadratic, mixed, open or closed, in 3D
//! — what Chen, Tristano & Kwok (2003) smooth ("quadratic mixed surface meshes", their
//! Figs. 18–19).
//!
//! The planar core serves a surface unchanged. A [`Surface`] keeps its nodes in 3D
//! ([`Surface::points`]) and its elements, topology and fixed flags in a planar [`Mesh`]
//! whose 2D positions are scratch ([`Surface::flat`]): before a driver looks at a free
//! node, the node's star is flattened into its tangent plane there (the normal is the
//! star's area-weighted normal), so every metric, objective, solver and strategy runs on
//! it as on a planar star; the node's new 2D position is lifted back into the plane and
//! projected onto the [`Reference`] surface (`view`). A planar mesh never passes
//! through here, so planar results and speed are what they were.
//!
//! An element's metrics are taken in its own plane, oriented by the reference surface's
//! normal at its centre: an element whose normal opposes the surface's is inverted
//! ([`Surface::element_points_2d`]).

use std::sync::Arc;

use glam::{DVec2, DVec3};

use crate::error::{Error, Result};
use crate::mesh::{Mesh, MeshBuilder, NodeRole, Plane, SurfaceParts};
use crate::quality::{mesh_stats_with, MeshStats};

mod curves;
mod reference;
mod view;

pub use reference::{closest_on_triangle, Analytic, Facets, Fitted, Projected, Reference};
pub use curves::SurfaceBoundary;
pub use view::{smooth_surface, KeptNodes, SurfaceSmoother};

/// Dihedral angle over which an edge between two elements is a feature curve (its nodes
/// stay fixed), degrees.
pub const FEATURE_ANGLE_DEG: f64 = 30.0;

/// A surface mesh in 3D with the surface its nodes stay on (see the module docs).
#[derive(Clone, Debug)]
pub struct Surface {
    points: Vec<DVec3>,
    flat: Mesh,
    /// Shared by clones (the page's two sides).
    reference: Arc<Reference>,
    /// Per node, the facet of the reference its last projection landed on (for an
    /// analytic surface, the smooth part it is on): where its next search starts, and
    /// the part it stays on.
    hint: Vec<u32>,
    /// Per node, whether it lies on a feature curve (an edge whose dihedral angle is
    /// over [`FEATURE_ANGLE_DEG`]).
    feature: Vec<bool>,
    /// Whether the file gave the fixed flags (then it decides which nodes move).
    flags_given: bool,
    /// The edges of the feature curves and open boundaries as loaded: their corner nodes
    /// and whether the edge is straight (1: no mid-side node).
    curve_edges: Arc<Vec<[u32; 3]>>,
    /// The curves the nodes slide along, when they do ([`Surface::slide_along_curves`]).
    curves: Option<Arc<curves::Curves>>,
    /// Per sliding node, the curve edge (as loaded) its last move landed on.
    curve_hint: Vec<[u32; 2]>,
    /// Where the boundary rule set the curves sliding: the angle a curve turns by at a
    /// corner, which holds ([`Surface::slide_along_curves_with`]).
    corner_deg: Option<f64>,
    /// Whether the file's flags were on every curve node and no other, so that under the
    /// boundary rule they only mark the boundary.
    flags_mark_only: bool,
    /// Why the file's points were read as a surface: the node farthest off the plane the
    /// mesh would lie in, and how far (a mistyped coordinate shows here).
    not_planar: Option<String>,
    /// The points the corners' targets are taken from, where they are not the ideal
    /// ([`set_target_points`](Self::set_target_points)).
    target: Option<Arc<Vec<DVec3>>>,
    /// Each element's own target positions in 3D, where they are not its nodes' in
    /// [`target`](Self::target) ([`crate::target::Target::Stretch`]).
    target_shapes: Option<Arc<Vec<[DVec3; 9]>>>,
}

impl Surface {
    /// A surface from its points and its elements with their topology and fixed flags
    /// (as the builder makes them). The elements are oriented consistently — across every
    /// edge two elements run opposite ways — each closed part outward, each open part as
    /// most of its elements were given; a non-orientable surface is refused. Boundary
    /// edges whose mid-side node is off the chord are curved. The reference is `analytic`
    /// when given, else the elements as they are now.
    ///
    /// Feature curves are the exact surface's, else found by their dihedral angles
    /// ([`Features::is_edge`]); their nodes are fixed. When the file gave the fixed flags (`flags_given`), the file
    /// decides: only edges between two nodes it fixed can be feature curves, and no node
    /// is fixed besides its own — so a tangled surface written with its flags and read
    /// back keeps its folds free, where the angles alone would take them for creases.
    pub(crate) fn from_parts(
        points: Vec<DVec3>,
        mut flat: Mesh,
        analytic: Option<Analytic>,
        flags_given: bool,
        numbers: &crate::error::Numbering,
    ) -> Result<Surface> {
        orient(&mut flat, &points, numbers)?;
        flat.mark_curved_boundary(|e| {
            let (a, b, m) = (points[e.a as usize], points[e.b as usize], points[e.mid as usize]);
            let chord = b - a;
            let off = (m - a).cross(chord).length() / chord.length().max(f64::MIN_POSITIVE);
            off > 1e-6 * chord.length()
        });
        let given = flags_given.then(|| flat.fixed().to_vec());
        let mut features = Features::new(&flat, &points, given.as_deref(), Judge::Angles);
        // the reference: the exact surface when known; else the elements as loaded, unless
        // one is folded (a tangled file), whose angles are the tangle's: then the surface
        // fitted through the nodes, its feature curves the edges between two nodes the file
        // fixed ([`Judge::Tangled`])
        let reference = match analytic {
            Some(a) => Reference::Analytic(a),
            None => {
                let (part, side) = (features.parts(), features.sides());
                let facets = Facets::new(&points, flat.kinds(), |e| flat.element(e), |e| part[e], |e| side[e]);
                if facets.is_folded() {
                    features = Features::new(&flat, &points, given.as_deref(), Judge::Tangled);
                    let part = features.parts();
                    Reference::Fitted(Box::new(Fitted::new(&points, &flat, |e| part[e])))
                } else {
                    Reference::Facets(Box::new(facets))
                }
            }
        };
        // an exact surface knows its feature curves (the cylinder's rims); else the angles say
        let feature: Vec<bool> = match analytic {
            Some(a) => points.iter().map(|&p| a.on_feature(p)).collect(),
            None => features.nodes(),
        };
        // the curves: open boundaries, and feature edges (each interior edge once)
        let mut curve_edges = Vec::new();
        for e in 0..flat.element_count() {
            let (ids, kind) = (flat.element(e), flat.kind(e));
            let k = kind.corners();
            for i in 0..k {
                let (a, b) = (ids[i], ids[(i + 1) % k]);
                let straight = kind.mid(i).is_none() as u32;
                let on_curve = match across(&flat, e, a, b) {
                    None => true,
                    Some((f, _)) if a < b => match analytic {
                        Some(an) => an.on_feature(points[a as usize]) && an.on_feature(points[b as usize]),
                        None => features.is_edge(e, f, a, b),
                    },
                    Some(_) => false,
                };
                if on_curve {
                    curve_edges.push([a, b, straight]);
                }
            }
        }
        if !flags_given {
            flat.fix_also(|n| feature[n]);
        }
        let hint = match &reference {
            Reference::Facets(f) => (0..points.len()).map(|n| f.triangle_at_vertex(n)).collect(),
            Reference::Fitted(f) => (0..points.len()).map(|n| f.fit_at_node(n)).collect(),
            Reference::Analytic(a) => points.iter().map(|&p| a.part_of(p)).collect(),
        };
        Ok(Surface {
            points,
            flat,
            reference: Arc::new(reference),
            hint,
            feature,
            flags_given,
            curve_edges: Arc::new(curve_edges),
            curves: None,
            curve_hint: Vec::new(),
            corner_deg: None,
            flags_mark_only: false,
            not_planar: None,
            target: None,
            target_shapes: None,
        })
    }

    /// Builds a surface in 3D from a builder's triangles and quads whatever their points
    /// (a generator's, on `analytic`'s exact surface when given): the checks of a planar
    /// mesh, then `from_parts`. A file's mesh, planar or not, is built
    /// by `Model::build` (in `model`, above this module).
    pub fn build(builder: MeshBuilder, analytic: Option<Analytic>) -> Result<Surface> {
        Self::from_surface_parts(builder.build_surface_parts()?, analytic)
    }

    /// The surface of the parts a builder made, with why its points were not planar.
    pub(crate) fn from_surface_parts(parts: SurfaceParts, analytic: Option<Analytic>) -> Result<Surface> {
        let SurfaceParts { points, mesh, element_numbers, flags_given, not_planar } = parts;
        let mut s = Self::from_parts(points, mesh, analytic, flags_given, &element_numbers)?;
        s.not_planar = not_planar;
        Ok(s)
    }

    /// Why a file's points were read as a surface, when they were: the node farthest off
    /// the plane the mesh would lie in, how far, and how that compares with its elements.
    pub fn not_planar(&self) -> Option<&str> {
        self.not_planar.as_deref()
    }
    /// Takes every corner's target from the points `at` ([`crate::target::Target::Input`];
    /// `None`: the ideal of each kind). A star measures them in its tangent plane.
    pub fn set_target_points(&mut self, at: Option<Vec<DVec3>>) {
        self.flat
            .set_target_nodes(at.as_ref().map(|a| vec![glam::DVec2::ZERO; a.len()]));
        self.target = at.map(Arc::new);
        self.target_shapes = None;
    }

    /// Measures every corner against `target` taken from the points `at`: the ideal, the
    /// corners at `at` ([`set_target_points`](Self::set_target_points)), or each element's
    /// stretch there ([`crate::target::surface_stretch_points`]; the ideal where the
    /// surface has none made on purpose).
    pub fn set_target_from(&mut self, target: crate::target::Target, at: Vec<DVec3>) {
        use crate::target::Target;
        match target {
            Target::Ideal => self.set_target_points(None),
            Target::Input => self.set_target_points(Some(at)),
            Target::Stretch => match crate::target::surface_stretch_points(self, &at) {
                None => self.set_target_points(None),
                Some(shapes) => {
                    self.flat.set_target_shapes();
                    self.target = Some(Arc::new(at));
                    self.target_shapes = Some(Arc::new(shapes));
                }
            },
        }
    }

    /// Node `n`'s star's targets in the tangent plane `plane`, where there are targets.
    pub(crate) fn set_target_star(flat: &mut Mesh, target: Option<&[DVec3]>, shapes: Option<&[[DVec3; 9]]>, n: usize, plane: &crate::mesh::Plane) {
        match (target, shapes) {
            (_, Some(shapes)) => flat.set_target_star_shapes(n, |e, i| plane.to_2d(shapes[e][i])),
            (Some(target), None) => flat.set_target_star(n, |m| plane.to_2d(target[m])),
            (None, None) => {}
        }
    }
    /// Node positions in 3D.
    pub fn points(&self) -> &[DVec3] {
        &self.points
    }
    /// The elements, topology and fixed flags as a planar mesh. Its 2D positions are
    /// scratch (the star last flattened), not the surface's: read [`points`](Self::points).
    pub fn flat(&self) -> &Mesh {
        &self.flat
    }
    pub fn reference(&self) -> &Reference {
        &self.reference
    }
    /// Whether node `n` lies on a feature curve.
    pub fn is_feature(&self, n: usize) -> bool {
        self.feature[n]
    }
    pub fn node_count(&self) -> usize {
        self.points.len()
    }
    pub fn element_count(&self) -> usize {
        self.flat.element_count()
    }

    /// The nearest point of the reference to `p`, searched from node `n`'s last facet.
    pub(crate) fn project_near(&self, p: DVec3, n: usize) -> Projected {
        self.reference.project(p, self.hint[n])
    }

    /// The reference surface's unit normal at the centre of element `e`, on the element's
    /// own smooth part: searched from the element's own facet where the reference is the
    /// loaded mesh (from its first corner's last facet, a corner on a feature curve may
    /// start on the other part: a cylinder cap's element next to the rim read the side's
    /// normal and counted as inverted), else from its first corner.
    pub fn reference_normal(&self, e: usize) -> DVec3 {
        let ids = self.flat.element(e);
        let k = self.flat.kind(e).corners();
        let centre = ids[..k].iter().map(|&i| self.points[i as usize]).sum::<DVec3>() / k as f64;
        match self.reference.element_hint(e) {
            Some(hint) => self.reference.project(centre, hint).normal,
            None => self.project_near(centre, ids[0] as usize).normal,
        }
    }

    /// The largest size ratio ([`crate::quality::grading`]) of an element of `star` and
    /// an edge neighbour, each in its own plane; −∞ where no pair has sizes.
    pub(crate) fn star_grading(&self, star: &[usize]) -> f64 {
        use crate::quality::grading::{edge_neighbours_of, planar_size, Size};
        let size = |e: usize| {
            let kind = self.flat.kind(e);
            planar_size(kind, &self.element_points_2d(e)[..kind.node_count()])
        };
        star.iter()
            .filter_map(|&e| Some((e, size(e)?)))
            .flat_map(|(e, a)| edge_neighbours_of(&self.flat, e).filter_map(move |f| Some(Size::ratio(a, size(f)?))))
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// Element `e`'s nodes in its own plane (2D), oriented so that the element reads as
    /// inverted there when its normal opposes the reference surface's: the plane through
    /// its corners' centre with the normal of its corner polygon (Newell's, the best-fit
    /// plane's for a warped quad), turned to face the way the reference does. Unused
    /// slots are zero, as [`Mesh::element_points_array`].
    pub fn element_points_2d(&self, e: usize) -> [DVec2; 9] {
        let ids = self.flat.element(e);
        let k = self.flat.kind(e).corners();
        let corner = |i: usize| self.points[ids[i] as usize];
        let centre = (0..k).map(corner).sum::<DVec3>() / k as f64;
        // the corners about the centre in units of their size where it is beyond 2^±200
        // (the cross products' squares would leave the doubles; `docs/formulas.md` §1)
        let mut d = [DVec3::ZERO; 4];
        for (i, v) in d[..k].iter_mut().enumerate() {
            *v = corner(i) - centre;
        }
        let d = crate::numeric::in_unit_scale_3d(d);
        let own = (0..k).map(|i| d[i].cross(d[(i + 1) % k])).sum::<DVec3>();
        let towards = self.reference_normal(e);
        let normal = match Some(crate::numeric::direction(own)).filter(|n| *n != DVec3::ZERO) {
            Some(n) if n.dot(towards) < 0.0 => -n,
            Some(n) => n,
            None => towards,
        };
        let plane = Plane::with_normal(centre, normal);
        let mut p = [DVec2::ZERO; 9];
        for (q, &i) in p.iter_mut().zip(ids) {
            *q = plane.to_2d(self.points[i as usize]);
        }
        p
    }

    /// The largest distance of a node (used by an element) from the reference surface.
    pub fn max_distance_from_reference(&self) -> f64 {
        (0..self.points.len())
            .filter(|&n| self.flat.role(n) != NodeRole::Unused)
            .map(|n| (self.project_near(self.points[n], n).point - self.points[n]).length())
            .fold(0.0, f64::max)
    }

    /// The edge of the bounding box of the nodes used by elements, longest side.
    pub fn size(&self) -> f64 {
        let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        for (n, p) in self.points.iter().enumerate() {
            if self.flat.role(n) != NodeRole::Unused {
                lo = lo.min(*p);
                hi = hi.max(*p);
            }
        }
        (hi - lo).max_element().max(0.0)
    }

    /// [`MeshStats`] with every element measured in its own plane
    /// ([`element_points_2d`](Self::element_points_2d)), `surface` set and the largest
    /// distance from the reference.
    pub fn stats(&self) -> MeshStats {
        let mut s = mesh_stats_with(&self.flat, |e| self.element_points_2d(e));
        s.surface = true;
        s.max_distance_from_surface = Some(self.max_distance_from_reference());
        s
    }

    /// The mean length of the corner-to-corner edges, in 3D.
    pub fn mean_edge_length(&self) -> f64 {
        let edges = self.flat.edges();
        if edges.is_empty() {
            return 0.0;
        }
        edges.iter().map(|e| (self.points[e.a as usize] - self.points[e.b as usize]).length()).sum::<f64>()
            / edges.len() as f64
    }
}

/// The normal of element `e`'s corner polygon, its length twice the area (Newell's sum
/// about the first corner).
fn element_normal(mesh: &Mesh, points: &[DVec3], e: usize) -> DVec3 {
    let ids = mesh.element(e);
    let k = mesh.kind(e).corners();
    let o = points[ids[0] as usize];
    (0..k).map(|i| (points[ids[i] as usize] - o).cross(points[ids[(i + 1) % k] as usize] - o)).sum()
}

/// The other element across corner edge `a → b` of an element, and whether it runs the
/// edge the same way (`a → b` too).
fn across(mesh: &Mesh, e: usize, a: u32, b: u32) -> Option<(usize, bool)> {
    for &f in mesh.node_elements(a as usize) {
        let f = f as usize;
        if f == e {
            continue;
        }
        let ids = mesh.element(f);
        let k = mesh.kind(f).corners();
        let Some(i) = ids[..k].iter().position(|&x| x == a) else { continue };
        if ids[(i + 1) % k] == b {
            return Some((f, true));
        }
        if ids[(i + k - 1) % k] == b {
            return Some((f, false));
        }
    }
    None
}

/// Orients the elements consistently (see [`Surface::from_parts`]); a surface that cannot
/// be is refused naming two elements as the file numbers them (`numbers`).
fn orient(mesh: &mut Mesh, points: &[DVec3], numbers: &crate::error::Numbering) -> Result<()> {
    let ne = mesh.element_count();
    // per element: its part (connected by edges) and whether it is reversed
    let (mut part, mut flip) = (vec![u32::MAX; ne], vec![false; ne]);
    let mut parts = 0u32;
    let mut queue = Vec::new();
    for seed in 0..ne {
        if part[seed] != u32::MAX {
            continue;
        }
        part[seed] = parts;
        queue.push(seed);
        let (mut members, mut flipped, mut closed, mut volume) = (Vec::new(), 0usize, true, 0.0);
        while let Some(e) = queue.pop() {
            members.push(e);
            flipped += flip[e] as usize;
            let ids = mesh.element(e);
            let k = mesh.kind(e).corners();
            for i in 0..k {
                let (a, b) = (ids[i], ids[(i + 1) % k]);
                let Some((f, same)) = across(mesh, e, a, b) else {
                    closed = false;
                    continue;
                };
                // same direction: the two disagree unless exactly one is reversed
                let want = flip[e] ^ same;
                if part[f] == u32::MAX {
                    part[f] = parts;
                    flip[f] = want;
                    queue.push(f);
                } else if flip[f] != want {
                    return Err(Error::element(
                        numbers.of(f),
                        None,
                        format!(
                            "cannot be oriented with element {}: the surface is not orientable (a Möbius band?)",
                            numbers.of(e)
                        ),
                    ));
                }
            }
        }
        for &e in &members {
            // the part's signed volume about its first node, as it will be oriented
            let ids = mesh.element(e);
            let k = mesh.kind(e).corners();
            let o = points[mesh.element(members[0])[0] as usize];
            let p = |i: usize| points[ids[i] as usize] - o;
            let v: f64 = (1..k - 1).map(|i| p(0).dot(p(i).cross(p(i + 1)))).sum();
            volume += if flip[e] { -v } else { v };
        }
        let reverse_part = if closed { volume < 0.0 } else { 2 * flipped > members.len() };
        if reverse_part {
            for &e in &members {
                flip[e] = !flip[e];
            }
        }
        parts += 1;
    }
    for (e, &f) in flip.iter().enumerate() {
        if f {
            mesh.reverse_element(e);
        }
    }
    Ok(())
}

/// Turn of the normal across an edge above which the edge is a fold, degrees: one
/// element lying (nearly) over the other. A fold is a tangle unless it parts two sheets of
/// at least [`FOLD_SHEET_ELEMENTS`] elements each, which no path across edges that are not
/// folds joins (then the surface turns back on itself there, a feature curve; a tangled
/// patch turns back to its surroundings through creases, or is small).
pub const FOLD_ANGLE_DEG: f64 = 150.0;

/// The fewest elements each side of a fold must hold, in a sheet joined across edges that
/// are not folds, for the fold to be a feature curve: twice a node's star in a regular
/// mesh, so a flipped element or a flipped star (the tangles perturbation makes) is not a
/// sheet, and a strip folded back on itself is.
pub const FOLD_SHEET_ELEMENTS: u32 = 12;

/// Finds a surface's feature curves and the smooth parts between them.
struct Features<'a> {
    mesh: &'a Mesh,
    points: &'a [DVec3],
    /// The file's fixed flags, when it gave them: only edges between fixed nodes qualify.
    fixed: Option<&'a [bool]>,
    /// Per element, its unit normal (`None` for an element without area), worked out
    /// once: every edge is asked about several times.
    normal: Vec<Option<DVec3>>,
    /// Per element, its sheet (the elements joined to it across edges that are not
    /// folds) and the number of elements in it.
    sheet: Vec<u32>,
    sheet_elements: Vec<u32>,
    judge: Judge,
}

/// What tells a feature curve.
#[derive(Clone, Copy, PartialEq)]
enum Judge {
    /// The turn of the elements' normals across the edge (and the file's fixed flags,
    /// when it gave them).
    Angles,
    /// A file whose elements are folded (a tangled file): their angles are the tangle's
    /// (folds, slivers, twisted quads turn as much as a crease does), so they tell nothing.
    /// An edge between two nodes the file fixed is a feature curve; a file without fixed
    /// flags has none (the surface fitted through its nodes is one smooth surface).
    Tangled,
}

/// How the normals of two elements across an edge turn.
#[derive(Clone, Copy, PartialEq)]
enum Turn {
    Smooth,
    Crease,
    Fold,
}

impl<'a> Features<'a> {
    fn new(mesh: &'a Mesh, points: &'a [DVec3], fixed: Option<&'a [bool]>, judge: Judge) -> Self {
        let normal = (0..mesh.element_count()).map(|e| element_normal(mesh, points, e).try_normalize()).collect();
        let mut f = Features {
            mesh,
            points,
            fixed,
            normal,
            sheet: Vec::new(),
            sheet_elements: Vec::new(),
            judge,
        };
        let sheet = f.components(|f, e, g, _, _| f.turn(e, g) != Turn::Fold);
        let mut count = vec![0u32; mesh.element_count()];
        for &s in &sheet {
            count[s as usize] += 1;
        }
        f.sheet_elements = sheet.iter().map(|&s| count[s as usize]).collect();
        f.sheet = sheet;
        f
    }

    /// The turn of the normals of elements `e` and `f`: smooth up to
    /// [`FEATURE_ANGLE_DEG`], a fold beyond [`FOLD_ANGLE_DEG`], a crease between (and
    /// smooth where either has no normal).
    fn turn(&self, e: usize, f: usize) -> Turn {
        let (cos, fold) = (FEATURE_ANGLE_DEG.to_radians().cos(), FOLD_ANGLE_DEG.to_radians().cos());
        let (Some(n1), Some(n2)) = (self.normal[e], self.normal[f]) else { return Turn::Smooth };
        let c = n1.dot(n2);
        if c >= cos {
            Turn::Smooth
        } else if c > fold {
            Turn::Crease
        } else {
            Turn::Fold
        }
    }

    /// Whether the edge `a`–`b` between elements `e` and `f` is on a feature curve. Judged
    /// by [`Judge::Angles`]: their normals turn by more than [`FEATURE_ANGLE_DEG`], and a
    /// turn beyond [`FOLD_ANGLE_DEG`] parts two sheets ([`FOLD_SHEET_ELEMENTS`]); when the
    /// file fixed nodes, it fixed both ends. By [`Judge::Tangled`]: both ends fixed by the
    /// file.
    fn is_edge(&self, e: usize, f: usize, a: u32, b: u32) -> bool {
        match (self.judge, self.fixed) {
            (Judge::Tangled, fixed) => fixed.is_some_and(|fixed| fixed[a as usize] && fixed[b as usize]),
            (Judge::Angles, Some(fixed)) if !(fixed[a as usize] && fixed[b as usize]) => false,
            (Judge::Angles, _) => match self.turn(e, f) {
                Turn::Smooth => false,
                Turn::Crease => true,
                Turn::Fold => self.parts_sheets(e, f),
            },
        }
    }

    /// Whether elements `e` and `f` lie in different sheets of at least
    /// [`FOLD_SHEET_ELEMENTS`] elements each.
    fn parts_sheets(&self, e: usize, f: usize) -> bool {
        self.sheet[e] != self.sheet[f] && self.sheet_elements[e].min(self.sheet_elements[f]) >= FOLD_SHEET_ELEMENTS
    }

    /// Nodes on feature curves: the ends (and mid-side node) of every feature edge.
    fn nodes(&self) -> Vec<bool> {
        let mesh = self.mesh;
        let mut feature = vec![false; self.points.len()];
        for e in 0..mesh.element_count() {
            let ids = mesh.element(e);
            let k = mesh.kind(e).corners();
            for i in 0..k {
                let (a, b) = (ids[i], ids[(i + 1) % k]);
                // each interior edge once, from the element that runs it a → b with a < b
                if a > b {
                    continue;
                }
                let Some((f, _)) = across(mesh, e, a, b) else { continue };
                if self.is_edge(e, f, a, b) {
                    feature[a as usize] = true;
                    feature[b as usize] = true;
                    if let Some(m) = mesh.kind(e).mid(i) {
                        feature[ids[m] as usize] = true;
                    }
                }
            }
        }
        feature
    }

    /// The smooth parts: elements joined by edges that are not feature edges, numbered
    /// from 0 (per element, its part).
    fn parts(&self) -> Vec<u32> {
        self.components(|f, e, g, a, b| !f.is_edge(e, g, a, b))
    }

    /// The sides of the folds that are feature curves: elements joined across every other
    /// edge, numbered from 0 (per element, its side).
    fn sides(&self) -> Vec<u32> {
        self.components(|f, e, g, a, b| f.turn(e, g) != Turn::Fold || !f.is_edge(e, g, a, b))
    }

    /// The elements joined across the edges `a`–`b` between elements `e` and `f` where
    /// `join(self, e, f, a, b)`, numbered from 0 (per element, its component).
    fn components(&self, join: impl Fn(&Self, usize, usize, u32, u32) -> bool) -> Vec<u32> {
        let mesh = self.mesh;
        let mut part = vec![u32::MAX; mesh.element_count()];
        let mut parts = 0;
        let mut queue = Vec::new();
        for seed in 0..mesh.element_count() {
            if part[seed] != u32::MAX {
                continue;
            }
            part[seed] = parts;
            queue.push(seed);
            while let Some(e) = queue.pop() {
                let ids = mesh.element(e);
                let k = mesh.kind(e).corners();
                for i in 0..k {
                    let (a, b) = (ids[i], ids[(i + 1) % k]);
                    if let Some((f, _)) = across(mesh, e, a, b) {
                        if part[f] == u32::MAX && join(self, e, f, a, b) {
                            part[f] = parts;
                            queue.push(f);
                        }
                    }
                }
            }
            parts += 1;
        }
        part
    }
}

#[cfg(test)]
mod tests;
