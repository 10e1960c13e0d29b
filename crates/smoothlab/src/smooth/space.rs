//! What the drivers need of a mesh and of a free node's star, in any dimension: the
//! planar [`Mesh`] with its [`Star`] of triangles and quads, or a tetrahedral mesh with
//! its star of tetrahedra ([`crate::volume`]). The drivers (Laplacian, smart, opt, C1/C2/C3,
//! rules, priority order, untangling sweeps) are written once over these two traits.

use crate::mesh::Mesh;
use crate::objective::{NodeStar, Point, Star};

use super::measure::{element_measures, element_shape_at, is_inverted, is_inverted_at, star_quality, star_shape};
use super::accept::{ElementScore, Size, Verdict, MIN_SIZE_RATIO};
use crate::quality::Reading;
use super::{Measure, StarQuality};

/// A mesh as the drivers read it: free nodes, their positions and neighbours, and the
/// elements' corners (for the untangling sweeps).
pub trait SmoothMesh {
    /// Where a node is: [`glam::DVec2`] or [`glam::DVec3`].
    type Point: Point;
    fn node_count(&self) -> usize;
    /// A node the smoothers may move: a corner that is not fixed.
    fn is_free(&self, n: usize) -> bool;
    fn position(&self, n: usize) -> Self::Point;
    /// The corner nodes that share an edge with corner `n` (Laplacian smoothing).
    fn neighbours(&self, n: usize) -> &[u32];
    fn element_count(&self) -> usize;
    /// The corner nodes of element `e`.
    fn element_corners(&self, e: usize) -> &[u32];
    /// Whether the mesh has quadratic elements (mid-side nodes follow their corners).
    fn has_quadratic(&self) -> bool;
    /// Whether a quadratic mesh has curved boundary edges (Chen's rule 1). Default false.
    fn has_curved_edges(&self) -> bool {
        false
    }
    /// Chen's rule 1: node `n`, a neighbour, or a node of a star element lies on a curved
    /// boundary edge. Default false.
    fn touches_curved_boundary(&self, _n: usize) -> bool {
        false
    }
    /// Whether its corners have targets other than the ideal ([`crate::target::Target`]):
    /// then `rules` optimises every node it visits, as the Laplacian's centroid is the
    /// ideal's answer. Default false.
    fn has_target(&self) -> bool {
        false
    }
    /// Where free node `n` goes when a driver moves it to `x`: `x`, or for a node that
    /// slides on the boundary the nearest point of the boundary as loaded
    /// ([`crate::volume::BoundaryRule::Slide`]). Default `x`.
    #[inline]
    fn onto_boundary(&self, _n: usize, x: Self::Point) -> Self::Point {
        x
    }
    /// Whether moving free node `n` moves other nodes onto the boundary with it (a
    /// quadratic mesh's sliding node carries its boundary edges' mid-side nodes): its move
    /// is then judged on its star with them moved ([`DriverStar::verdict_in`]). Default
    /// false.
    #[inline]
    fn carries_on_boundary(&self, _n: usize) -> bool {
        false
    }
    /// What the statistics read of the mesh ([`Reading`]): the bounds a move on a valid
    /// star keeps within; `None` for a tangled mesh, whose rule is its count of inverted
    /// elements.
    fn valid_reading(&self) -> Option<Reading>;
    /// Reads part of what a visit of free node `n` will read, so that it is in the cache
    /// when the visit comes: stage 0 the node's own entries, each later stage what the
    /// stage before it brought in (the drivers read a few visits ahead in a scattered
    /// visit order). Returns a value made of what it read, so the reads are made.
    /// Default: reads nothing.
    fn read_ahead(&self, _n: usize, _stage: usize) -> u32 {
        0
    }
}

/// How many visits ahead of the current one each stage of [`SmoothMesh::read_ahead`]
/// reads, in a scattered visit order (Chen's priority order, the untangling sweeps): a
/// visit's reads depend on one another (the node's element list, then the elements'
/// nodes, then their positions), and in worst-first order over a large mesh each is a
/// cache miss; read a few visits ahead, each stage's reads are independent of the
/// current visit's and of one another, so they overlap. The loads change no result.
pub(crate) const READ_AHEAD: [usize; 5] = [32, 16, 8, 4, 2];

/// A free node's star as the drivers measure it: gathered from its mesh, moved, and
/// measured at trial positions (the worst shape, the worst sine, inverted elements).
pub trait DriverStar: NodeStar + Default {
    /// The mesh it is gathered from.
    type Mesh: SmoothMesh<Point = Self::Point>;
    /// Fills the star of `node` from `mesh`.
    fn gather(&mut self, mesh: &Self::Mesh, node: usize);
    /// Fills the star of `node` for the drivers' measures ([`shape_at`](Self::shape_at),
    /// [`quality`](Self::quality), the smart Laplacian's test, the acceptance rule), leaving
    /// out what only an objective reads until [`complete`](Self::complete) works it out (a
    /// tetrahedral star's corner forms); the default gathers all of it.
    fn gather_for_measures(&mut self, mesh: &Self::Mesh, node: usize) {
        self.gather(mesh, node)
    }
    /// Works out what [`gather_for_measures`](Self::gather_for_measures) left out, before
    /// an objective reads the star; the default has nothing to do.
    fn complete(&mut self) {}
    /// Whether the free node slides on the boundary: then a solver sees the objective's
    /// gradients [`along`](Self::along) its tangent. Default false.
    fn slides(&self) -> bool {
        false
    }
    /// `g` projected onto the free node's tangent (itself where it does not slide).
    #[inline]
    fn along(&self, g: Self::Point) -> Self::Point {
        g
    }
    /// A Hessian projected onto the free node's tangent, `P·H·P`.
    #[inline]
    fn along_hessian(
        &self,
        h: <Self::Point as crate::objective::Point>::Hessian,
    ) -> <Self::Point as crate::objective::Point>::Hessian {
        h
    }
    /// The free node's position now (gathered, or moved by [`restar`](Self::restar)).
    fn x0(&self) -> Self::Point;
    /// Moves the free node to `x` (mid-side nodes following).
    fn restar(&mut self, x: Self::Point);
    /// The smallest shape measure of the star with its free node at `x`, and its number
    /// of inverted elements (the priority order, Chen's rule 2).
    fn shape_at(&self, x: Self::Point) -> (f64, u32);
    /// [`shape_at`](Self::shape_at)`(x).0` alone (the priority order's key), where a kind of
    /// star can take it without counting inverted elements; the default reads `shape_at`.
    fn min_shape_at(&self, x: Self::Point) -> f64 {
        self.shape_at(x).0
    }
    /// The star's worst measures with the free node where it is (`None`) or at `x`.
    fn quality(&self, x: Option<Self::Point>) -> StarQuality;
    /// The smart Laplacian's test (Freitag 1997): moving the free node to `c` folds no
    /// valid element and raises the star's worst `measure`.
    fn smart_accepts(&self, c: Self::Point, measure: Measure) -> bool;
    /// The number of elements inverted as gathered (the validity guard's limit).
    fn inverted_now(&self) -> usize;
    /// Whether [`shape_at`](Self::shape_at) at the free node's position counts an inverted
    /// element (Chen's rule 2), where a kind of star can tell without measuring the
    /// shapes; the default reads `shape_at`.
    fn any_inverted_now(&self) -> bool {
        self.shape_at(self.x0()).1 > 0
    }
    /// The star of `node` as [`gather`](Self::gather) would fill it from `mesh`, when it
    /// was last gathered from that mesh at that node and the mesh has not changed since
    /// (only [`restar`](Self::restar) moved it): a kind of star whose `restar` is exactly
    /// undone by moving the node back does that; the default gathers again.
    fn regather(&mut self, mesh: &Self::Mesh, node: usize) {
        self.gather(mesh, node)
    }
    /// The number of elements inverted with the free node at `x`.
    fn inverted_at(&self, x: Self::Point) -> usize;
    /// How deeply the star is inverted with the free node at `x`: the sum of the negative
    /// parts of its corner Jacobian determinants (0 for a valid star), compared only
    /// within one star.
    fn inversion(&self, x: Self::Point) -> f64;
    /// The acceptance rule ([`Verdict`], `docs/formulas.md` §4) by `measure` over the star
    /// as gathered and with its free node at `x` (the mid-side nodes that follow it
    /// following).
    fn verdict(&self, x: Self::Point, measure: Measure) -> Verdict;
    /// [`verdict`](Self::verdict) where the star's elements are measured in `mesh` with
    /// nodes the star does not hold (a 10-node tetrahedron's mid-edge nodes); the default
    /// is `verdict`.
    fn verdict_in(&self, _mesh: &Self::Mesh, x: Self::Point, measure: Measure) -> Verdict {
        self.verdict(x, measure)
    }
    /// Whether what the statistics read of the star ([`Reading`]) with its free node at `x`
    /// (the nodes that follow it following, the rest as in `mesh`) lies within `bounds`.
    fn reads_within(&self, mesh: &Self::Mesh, x: Self::Point, bounds: &Reading) -> bool;
    /// [`reads_within`](Self::reads_within) of node `n`'s star read straight from the
    /// mesh, where a kind of star has such a shortcut (a planar star of linear elements:
    /// no node follows `n`); `None` otherwise (the default), and the gathered star decides.
    fn reads_within_from_mesh(_mesh: &Self::Mesh, _n: usize, _x: Self::Point, _bounds: &Reading) -> Option<bool> {
        None
    }
    /// Whether element `e` of `mesh` is known to be valid with its corners where they are
    /// now, from what earlier stars measured of it (a kind of star that keeps its
    /// elements' measures from visit to visit); `false` where nothing is known (the
    /// default), and the caller measures it.
    fn known_valid(&self, _mesh: &Self::Mesh, _e: usize) -> bool {
        false
    }
    /// The smart Laplacian's test read straight from the mesh, where a kind of star has
    /// such a shortcut (the planar star of linear triangles); `None` otherwise (the
    /// default), and the gathered star decides.
    fn smart_from_mesh(_mesh: &Self::Mesh, _n: usize, _measure: Measure) -> Option<FastSmart<Self::Point>> {
        None
    }
    /// [`shape_at`](Self::shape_at)`(x0).0` of node `n`'s star read straight from the mesh,
    /// where a kind of star has such a shortcut; `None` otherwise (the default), and the
    /// gathered star is measured.
    fn shape_from_mesh(_mesh: &Self::Mesh, _n: usize) -> Option<f64> {
        None
    }
}

/// What [`DriverStar::smart_from_mesh`] found: the star's inverted elements at the node's
/// position, and the centroid when the smart Laplacian moves the node there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FastSmart<P> {
    pub inverted: u32,
    pub to: Option<P>,
    /// The move to [`to`](Self::to) passes the acceptance rule ([`Verdict`]) as measured
    /// here: the star is valid, the move folds none of it, raises its worst shape and
    /// shrinks no element below the rule's floor.
    pub kept: bool,
}

impl SmoothMesh for Mesh {
    fn has_target(&self) -> bool {
        self.target_nodes().is_some()
    }
    #[inline]
    fn onto_boundary(&self, n: usize, x: glam::DVec2) -> glam::DVec2 {
        Mesh::onto_boundary(self, n, x)
    }
    #[inline]
    fn carries_on_boundary(&self, n: usize) -> bool {
        self.carries_mid_nodes(n)
    }
    type Point = glam::DVec2;
    fn valid_reading(&self) -> Option<Reading> {
        Reading::planar_mesh(self, |e| self.element_points_array(e))
    }
    #[inline]
    fn node_count(&self) -> usize {
        Mesh::node_count(self)
    }
    #[inline]
    fn is_free(&self, n: usize) -> bool {
        Mesh::is_free(self, n)
    }
    #[inline]
    fn position(&self, n: usize) -> glam::DVec2 {
        self.nodes()[n]
    }
    #[inline]
    fn neighbours(&self, n: usize) -> &[u32] {
        Mesh::neighbours(self, n)
    }
    #[inline]
    fn element_count(&self) -> usize {
        Mesh::element_count(self)
    }
    #[inline]
    fn element_corners(&self, e: usize) -> &[u32] {
        &self.element(e)[..self.kind(e).corners()]
    }
    #[inline]
    fn has_quadratic(&self) -> bool {
        Mesh::has_quadratic(self)
    }
    fn has_curved_edges(&self) -> bool {
        self.edges().iter().any(|e| e.curved)
    }
    /// Stage 0: the node's flags, position and list starts; 1: its element and neighbour
    /// lists; 2: its elements' kinds and node-list starts; 3: their node lists; 4 and on:
    /// their nodes' positions (the neighbours' among them). 0 for a node past the end.
    #[inline]
    fn read_ahead(&self, n: usize, stage: usize) -> u32 {
        if n >= Mesh::node_count(self) {
            return 0;
        }
        let elems = || self.node_elements(n).iter().map(|&e| e as usize);
        let first = |v: &[u32]| v.first().copied().unwrap_or(0);
        match stage {
            0 => {
                let lists = self.node_elements(n).len() ^ Mesh::neighbours(self, n).len();
                lists as u32 ^ self.fixed()[n] as u32 ^ self.role(n) as u32 ^ self.nodes()[n].x.to_bits() as u32
            }
            1 => first(self.node_elements(n)) ^ first(Mesh::neighbours(self, n)),
            2 => elems().fold(0, |a, e| a ^ self.kind(e) as u32 ^ self.element(e).len() as u32),
            3 => elems().fold(0, |a, e| a ^ first(self.element(e))),
            _ => elems().flat_map(|e| self.element(e)).fold(0, |a, &m| a ^ self.nodes()[m as usize].x.to_bits() as u32),
        }
    }
    fn touches_curved_boundary(&self, n: usize) -> bool {
        self.is_on_curved_boundary(n)
            || Mesh::neighbours(self, n).iter().any(|&m| self.is_on_curved_boundary(m as usize))
            || self
                .node_elements(n)
                .iter()
                .any(|&e| self.element(e as usize).iter().any(|&m| self.is_on_curved_boundary(m as usize)))
    }
}

impl DriverStar for Star {
    type Mesh = Mesh;
    #[inline]
    fn gather(&mut self, mesh: &Mesh, node: usize) {
        Star::gather(self, mesh, node)
    }
    #[inline]
    fn slides(&self) -> bool {
        self.slide != glam::DVec2::ZERO
    }
    /// `g` along the boundary's direction, `t·tᵀ·g`.
    #[inline]
    fn along(&self, g: glam::DVec2) -> glam::DVec2 {
        self.slide * g.dot(self.slide)
    }
    /// `P·H·P` with `P = t·tᵀ`: `(tᵀHt)·t·tᵀ`.
    #[inline]
    fn along_hessian(&self, h: glam::DMat2) -> glam::DMat2 {
        let t = self.slide;
        let c = t.dot(h * t);
        glam::DMat2::from_cols(t * (c * t.x), t * (c * t.y))
    }
    #[inline]
    fn x0(&self) -> glam::DVec2 {
        self.x0
    }
    #[inline]
    fn restar(&mut self, x: glam::DVec2) {
        self.x0 = x;
        self.memo.forget();
        for e in &mut self.elems {
            e.move_free_node(x);
        }
    }
    #[inline]
    fn shape_at(&self, x: glam::DVec2) -> (f64, u32) {
        star_shape(self, x)
    }
    #[inline]
    fn quality(&self, x: Option<glam::DVec2>) -> StarQuality {
        star_quality(self, x)
    }
    fn smart_accepts(&self, c: glam::DVec2, m: Measure) -> bool {
        let (mut before, mut after) = (f64::INFINITY, f64::INFINITY);
        let x0 = self.x0;
        for e in &self.elems {
            let ((q0, inv0), (q1, inv1)) = match m {
                Measure::Shape => (element_shape_at(e, x0), element_shape_at(e, c)),
                Measure::MinSine => {
                    let (q0, q1) = (element_measures(e.kind, &e.pts), element_measures(e.kind, &e.at(c)));
                    ((q0.min_sine, q0.inverted > 0), (q1.min_sine, q1.inverted > 0))
                }
            };
            if !inv0 && inv1 {
                return false;
            }
            before = before.min(q0);
            after = after.min(q1);
        }
        after > before
    }
    fn inverted_now(&self) -> usize {
        self.elems.iter().filter(|e| is_inverted(e.kind, &e.pts)).count()
    }
    fn inverted_at(&self, x: glam::DVec2) -> usize {
        self.elems.iter().filter(|e| is_inverted_at(e, x)).count()
    }
    fn inversion(&self, x: glam::DVec2) -> f64 {
        let mut t = 0.0;
        for e in &self.elems {
            let p = e.at(x);
            for (e1, e2) in &crate::quality::corner_edge_vectors(e.kind, &p)[..e.kind.corners()] {
                t += (-e1.perp_dot(*e2)).max(0.0);
            }
        }
        t
    }
    fn verdict(&self, x: glam::DVec2, m: Measure) -> Verdict {
        self.verdict_carrying(x, m, &[None; 2], &|_| &[])
    }
    /// [`verdict`](DriverStar::verdict) with the mid-side nodes the free node carries along
    /// the boundary ([`Mesh::carried_mid_nodes`]) where they go.
    fn verdict_in(&self, mesh: &Mesh, x: glam::DVec2, m: Measure) -> Verdict {
        let carried = mesh.carried_mid_nodes(self.node as usize, x);
        self.verdict_carrying(x, m, &carried, &|e| mesh.element(e))
    }
    fn reads_within(&self, mesh: &Mesh, x: glam::DVec2, bounds: &Reading) -> bool {
        let carried = mesh.carried_mid_nodes(self.node as usize, x);
        let at = |e: &crate::objective::StarElement| at_carrying(e, x, &carried, &|e| mesh.element(e));
        self.elems.iter().all(|e| Reading::planar_within(e.kind, &at(e), bounds))
            && planar_graded_within(mesh, bounds.grading, self.elems.iter().map(|e| (e.element as usize, at(e))))
    }
    fn reads_within_from_mesh(mesh: &Mesh, n: usize, x: glam::DVec2, bounds: &Reading) -> Option<bool> {
        let elems = mesh.node_elements(n);
        if elems.iter().any(|&e| mesh.kind(e as usize).node_count() > mesh.kind(e as usize).corners()) {
            return None;
        }
        Some(elems.iter().all(|&e| {
            let e = e as usize;
            let mut p = mesh.element_points_array(e);
            for (q, &i) in p.iter_mut().zip(mesh.element(e)) {
                if i as usize == n {
                    *q = x;
                }
            }
            Reading::planar_within(mesh.kind(e), &p, bounds)
        }) && planar_graded_within(
            mesh,
            bounds.grading,
            elems.iter().map(|&e| {
                let mut p = mesh.element_points_array(e as usize);
                for (q, &i) in p.iter_mut().zip(mesh.element(e as usize)) {
                    if i as usize == n {
                        *q = x;
                    }
                }
                (e as usize, p)
            }),
        ))
    }
    fn smart_from_mesh(mesh: &Mesh, n: usize, measure: Measure) -> Option<FastSmart<glam::DVec2>> {
        super::smart_on_triangles(mesh, n, measure)
    }
    fn shape_from_mesh(mesh: &Mesh, n: usize) -> Option<f64> {
        super::shape_on_triangles(mesh, n)
    }
}

impl Star {
    /// The acceptance rule over the star with its free node at `x` and the mid-side nodes
    /// `carried` where they go (each found among its element's nodes, `nodes(element)`).
    fn verdict_carrying<'m>(
        &self,
        x: glam::DVec2,
        m: Measure,
        carried: &[Option<(usize, glam::DVec2)>; 2],
        nodes: &dyn Fn(usize) -> &'m [u32],
    ) -> Verdict {
        let mut v = Verdict::default();
        for e in &self.elems {
            let at = at_carrying(e, x, carried, nodes);
            let (before, b) = ElementScore::planar_unsized(e.kind, &e.pts, m);
            let (after, a) = ElementScore::planar_unsized(e.kind, &at, m);
            // the sizes measured only where their determinants do not decide
            v.add_deciding_size(&before, &after, || {
                Size::floor_kept_for_certain(b, a) || ElementScore::planar(e.kind, &at, m).size.at_least(MIN_SIZE_RATIO, &ElementScore::planar(e.kind, &e.pts, m).size)
            });
        }
        v
    }
}

/// Star element `e`'s nodes with its free node at `x` ([`StarElement::at`](crate::objective::StarElement::at))
/// and the mid-side nodes `carried` of its own where they go (found among its nodes,
/// `nodes(element)`).
#[inline]
fn at_carrying<'m>(
    e: &crate::objective::StarElement,
    x: glam::DVec2,
    carried: &[Option<(usize, glam::DVec2)>; 2],
    nodes: &dyn Fn(usize) -> &'m [u32],
) -> [glam::DVec2; 9] {
    let mut p = e.at(x);
    for &(mid, to) in carried.iter().flatten() {
        if let Some(i) = nodes(e.element as usize).iter().position(|&v| v as usize == mid) {
            p[i] = to;
        }
    }
    p
}

/// Whether every pair of neighbours with a moved element has a size ratio
/// ([`crate::quality::grading`]) of at most `bound`: `moved` gives each element of the
/// star with its nodes after the move; the other elements are as in `mesh`.
pub(crate) fn planar_graded_within(mesh: &Mesh, bound: f64, moved: impl Iterator<Item = (usize, [glam::DVec2; 9])>) -> bool {
    use crate::quality::grading::{edge_neighbours_of, planar_size, Size};
    if bound == f64::INFINITY {
        return true;
    }
    let size = |e: usize, p: &[glam::DVec2; 9]| planar_size(mesh.kind(e), &p[..mesh.kind(e).node_count()]);
    // the star's own sizes once: each is a neighbour of others in the star
    let moved: Vec<(usize, Option<Size>)> = moved.map(|(e, p)| (e, size(e, &p))).collect();
    moved.iter().all(|&(e, a)| {
        let Some(a) = a else { return true };
        edge_neighbours_of(mesh, e).all(|f| {
            let b = match moved.iter().find(|(m, _)| *m == f) {
                Some(&(_, b)) => b,
                None => size(f, &mesh.element_points_array(f)),
            };
            b.map_or(true, |b| Size::ratio(a, b) <= bound)
        })
    })
}
