//! Smoothing a tetrahedral mesh: the planar drivers ([`crate::smooth`]) over a star of
//! tetrahedra. Nothing here decides where a node goes: the tetrahedral mesh and its star
//! implement the drivers' two traits ([`SmoothMesh`], [`DriverStar`]) and the
//! [`Smoother`] does the rest, strategy by strategy, as for planar meshes.
//!
//! The measures the drivers take of a tetrahedral star, in the planar measures' roles:
//! - the shape ([`Measure::Shape`]: the smart Laplacian, the priority order, Chen's rule
//!   2) is the mean ratio of each tetrahedron (1 for the regular one);
//! - the sine ([`Measure::MinSine`], the thresholds of Freitag's C1/C2/C3) is the
//!   smallest sine of the dihedral angles (Freitag 1997 in 3D);
//! - a tetrahedron is inverted when its signed volume is ≤ 0; the inversion the
//!   validity guard compares is `Σ max(0, −6V)` over the star.
//!
//! Quadratic (10-node) tetrahedra are measured by their corners; their mid-edge nodes
//! follow the corners to the edges' middles.

use glam::DVec3;

use super::{VolumeKind, VolumeMesh};
use crate::error::Result;
use crate::objective::{framed, CornerStar, Objective, StarSolid};
use crate::quality::solid::{self, Validity};
use crate::quality::tet as q3;
use crate::quality::Reading;
use crate::smooth::{
    DriverStar, ElementScore, Measure, PassRecord, Size, SmoothMesh, SmoothOptions, Smoother,
    StarQuality, StarView, SweepCounts, Verdict, MIN_SIZE_RATIO,
};

/// Whether every pair of neighbours with an element of node `n`'s star, the node at `x`,
/// has a size ratio ([`crate::quality::grading`]) of at most `bound`.
fn graded_within(mesh: &VolumeMesh, n: usize, x: DVec3, bound: f64) -> bool {
    use crate::quality::grading::{solid_size, Size};
    if bound == f64::INFINITY {
        return true;
    }
    let star = mesh.node_tets(n);
    // a size reads the corners alone (a quadratic element's are its first), node n at x
    let size = |e: usize| {
        let (kind, ids) = (mesh.element_kind(e), mesh.element(e));
        let mut p = [DVec3::ZERO; 8];
        for (q, &i) in p.iter_mut().zip(&ids[..kind.corners()]) {
            *q = if i as usize == n { x } else { mesh.nodes()[i as usize] };
        }
        solid_size(kind, &p[..kind.corners()])
    };
    // the star's own sizes once: each is a neighbour of others in the star
    let moved: Vec<Option<Size>> = star.iter().map(|&e| size(e as usize)).collect();
    star.iter().zip(&moved).all(|(&e, a)| {
        let Some(a) = *a else { return true };
        mesh.face_neighbours(e as usize).iter().all(|&f| {
            let b = match star.iter().position(|&s| s == f) {
                Some(i) => moved[i],
                None => size(f as usize), // without node n: as it is
            };
            b.map_or(true, |b| Size::ratio(a, b) <= bound)
        })
    })
}

impl SmoothMesh for VolumeMesh {
    fn has_target(&self) -> bool {
        self.target_nodes().is_some()
    }
    type Point = DVec3;
    fn valid_reading(&self) -> Option<Reading> {
        let mut sizes = Vec::with_capacity(self.element_count());
        let r = (0..self.element_count()).try_fold(Reading::default(), |r, e| {
            let (p, count) = self.element_points(e);
            sizes.push(crate::quality::grading::solid_size(self.element_kind(e), &p[..count]));
            (!self.is_inverted(e)).then(|| r.and(Reading::solid(self.element_kind(e), &p[..count])))
        })?;
        Some(r.with_grading(crate::quality::grading::largest_ratio(&sizes, super::stats::face_neighbours(self))))
    }
    #[inline]
    fn node_count(&self) -> usize {
        VolumeMesh::node_count(self)
    }
    #[inline]
    fn is_free(&self, n: usize) -> bool {
        VolumeMesh::is_free(self, n)
    }
    #[inline]
    fn position(&self, n: usize) -> DVec3 {
        self.nodes()[n]
    }
    #[inline]
    fn neighbours(&self, n: usize) -> &[u32] {
        VolumeMesh::neighbours(self, n)
    }
    #[inline]
    fn element_count(&self) -> usize {
        VolumeMesh::element_count(self)
    }
    #[inline]
    fn element_corners(&self, e: usize) -> &[u32] {
        &self.element(e)[..self.element_kind(e).corners()]
    }
    #[inline]
    fn has_quadratic(&self) -> bool {
        self.is_quadratic()
    }
    #[inline]
    fn onto_boundary(&self, n: usize, x: DVec3) -> DVec3 {
        VolumeMesh::onto_boundary(self, n, x)
    }
}

impl DriverStar for CornerStar {
    type Mesh = VolumeMesh;
    /// The node's corners of each element ([`StarCorner`](crate::objective::StarCorner)): a
    /// tetrahedron's own corner — the node first, then its three edge neighbours in the
    /// kind's order
    /// ([`VolumeKindRow::corner_edges`](crate::mesh::VolumeKindRow)), an even permutation
    /// of a tetrahedron's corners, so the volume keeps its sign; another kind's every
    /// measured corner whose tetrahedron holds the node, reordered to put it first
    /// ([`WITH_FIRST`](crate::mesh::WITH_FIRST)), with the element whole for the guard ([`StarSolid`]).
    fn gather(&mut self, mesh: &VolumeMesh, node: usize) {
        self.gather_for_measures(mesh, node);
        self.complete_forms();
    }
    /// The corners with their forms [`CornerForm::PENDING`](crate::quality::tet::CornerForm::PENDING)
    /// until [`complete`](DriverStar::complete) (a smart Laplacian's visit reads none).
    fn gather_for_measures(&mut self, mesh: &VolumeMesh, node: usize) {
        // the last star's elements as the mesh now has them, for this star and the next
        if let Some(&x) = mesh
            .nodes()
            .get(self.node as usize)
            .filter(|_| !self.elements.is_empty())
        {
            self.keep_known(x, mesh.element_count());
        }
        self.node = node as u32;
        self.tangent = mesh.tangent(node);
        self.forms_pending_at = Some(mesh.nodes()[node]);
        self.x0 = mesh.nodes()[node];
        // the corners overwritten in place, then truncated
        let mut n_corners = 0;
        self.tet_memo.get_mut().clear();
        // the elements other than tetrahedra overwritten in place, then truncated
        let mut solids = 0;
        let nodes = mesh.nodes();
        self.targets.clear();
        let target = mesh.target_nodes();
        // a corner's target: the same corner of the target's positions, where valid
        let reference = |e: u32, ids: [u32; 4], ideal: &'static q3::CornerReference| {
            let t = |n: u32| mesh.target_point(e as usize, n).expect("targets are taken only where the mesh has them");
            let at = |k: usize| t(ids[k]) - t(ids[0]);
            crate::target::solid_reference(glam::DMat3::from_cols(at(1), at(2), at(3)), ideal)
                .unwrap_or(*ideal)
        };
        let (x, corners) = (nodes[node], mesh.node_tet_corners(node));
        for (i, &e) in mesh.node_tets(node).iter().enumerate() {
            // a tetrahedron from the star's own stream of corners (`VolumeMesh::node_tet_corners`)
            if let Some(&[a, b, c]) = corners.get(i).filter(|o| o[0] != u32::MAX) {
                // the corners written in place (below)
                *self.put_corner(n_corners, e, &q3::EQUILATERAL_TET, true) =
                    [x, nodes[a as usize], nodes[b as usize], nodes[c as usize]];
                n_corners += 1;
                if target.is_some() {
                    self.targets
                        .push(reference(e, [node as u32, a, b, c], &q3::EQUILATERAL_TET));
                }
                continue;
            }
            let kind = mesh.element_kind(e as usize);
            let row = kind.row();
            let ids = &mesh.element(e as usize)[..row.corners];
            let Some(slot) = ids.iter().position(|&i| i as usize == node) else {
                continue;
            };
            // the element's corners written where they stay, and its corners' tetrahedra
            // from them, in place too: put together on the stack and moved whole, their
            // 24-byte points were read back in 16-byte pieces, which stalled
            let all = self.put_solid(solids, e, kind, slot as u8);
            for (p, &i) in all.iter_mut().zip(ids) {
                *p = nodes[i as usize];
            }
            for p in &mut all[ids.len()..] {
                *p = DVec3::ZERO;
            }
            for (c, &[a, b, d]) in row.corner_edges.iter().enumerate() {
                let tuple = [c, a, b, d];
                let Some(s) = tuple.iter().position(|&j| j == slot) else {
                    continue;
                };
                self.put_corner_of_solid(n_corners, solids, &row.slot_references[s], tuple, s);
                n_corners += 1;
                if target.is_some() {
                    let order = crate::mesh::WITH_FIRST[s].map(|j| ids[tuple[j]]);
                    self.targets.push(reference(e, order, &row.slot_references[s]));
                }
            }
            self.recall_solid(solids);
            solids += 1;
        }
        self.tets.truncate(n_corners);
        self.elements.truncate(solids);
    }
    fn complete(&mut self) {
        self.complete_forms();
    }
    #[inline]
    fn slides(&self) -> bool {
        self.tangent != super::Tangent::Free
    }
    #[inline]
    fn along(&self, g: DVec3) -> DVec3 {
        self.tangent.along(g)
    }
    #[inline]
    fn along_hessian(&self, h: glam::DMat3) -> glam::DMat3 {
        self.tangent.along_hessian(h)
    }
    #[inline]
    fn x0(&self) -> DVec3 {
        self.x0
    }
    fn restar(&mut self, x: DVec3) {
        self.x0 = x;
        for t in &mut self.tets {
            t.pts[0] = x;
        }
        for e in &mut self.elements {
            e.pts[e.slot as usize] = x;
        }
    }
    fn shape_at(&self, x: DVec3) -> (f64, u32) {
        let (mut min, mut inverted) = (f64::INFINITY, 0);
        for t in self.tets.iter().filter(|t| t.simplex) {
            let p = t.at(x);
            min = min.min(q3::mean_ratio(&p, self.reference()));
            inverted += q3::is_inverted(&p) as u32;
        }
        for e in &self.elements {
            let p = e.at(x);
            let p = e.corners(&p);
            min = min.min(solid::solid_shape(e.kind, p));
            inverted += (solid::validity(e.kind, p) != Validity::Valid) as u32;
        }
        (min, inverted)
    }
    /// The shapes alone: no element's validity (a hexahedron's 27 coefficients) is taken,
    /// and the tetrahedra's least mean ratio exact from those that may be the least
    /// (`LeastMeanRatio`, this module's).
    fn min_shape_at(&self, x: DVec3) -> f64 {
        let (mut min, mut least) = (f64::INFINITY, LeastMeanRatio::default());
        for t in self.tets.iter().filter(|t| t.simplex) {
            min = min.min(least.add(&t.at(x), self.reference()));
        }
        for e in &self.elements {
            min = min.min(e.shape_measured(x));
        }
        min
    }
    fn quality(&self, x: Option<DVec3>) -> StarQuality {
        let mut q = StarQuality::BEST;
        for t in self.tets.iter().filter(|t| t.simplex) {
            let p = x.map_or(t.pts, |x| t.at(x));
            q.min_shape = q.min_shape.min(q3::mean_ratio(&p, self.reference()));
            q.min_sine = q.min_sine.min(
                q3::dihedral_sines(&p)
                    .into_iter()
                    .fold(f64::INFINITY, f64::min),
            );
            q.inverted += q3::is_inverted(&p) as u32;
        }
        for e in &self.elements {
            let p = x.map_or(e.pts, |x| e.at(x));
            let p = e.corners(&p);
            q.min_shape = q.min_shape.min(solid::solid_shape(e.kind, p));
            q.min_sine = q.min_sine.min(solid::solid_min_sine(e.kind, p));
            q.inverted += (solid::validity(e.kind, p) != Validity::Valid) as u32;
        }
        q
    }
    /// The tetrahedra by [`q3::mean_ratio_order`] (the mean ratio's order without its cube
    /// root; the acceptance rule then measures the move exactly).
    fn smart_accepts(&self, c: DVec3, m: Measure) -> bool {
        let min_sine = |p: &[DVec3; 4]| {
            q3::dihedral_sines(p)
                .into_iter()
                .fold(f64::INFINITY, f64::min)
        };
        let (mut before, mut after) = (f64::INFINITY, f64::INFINITY);
        if m == Measure::Shape {
            // kept for the acceptance rule, which asks the same two positions
            let frame = self.frame();
            let mut memo = self.tet_memo.borrow_mut();
            let (b, a) = (
                memo.slot(&self.tets, self.x0, self.reference(), frame),
                memo.slot(&self.tets, c, self.reference(), frame),
            );
            for ((p0, t0), (p1, t1)) in memo.measures(b).iter().zip(memo.measures(a)) {
                if !t0.inverted && t1.inverted {
                    return false;
                }
                before = before.min(p0.order());
                after = after.min(p1.order());
            }
        } else {
            for t in self.tets.iter().filter(|t| t.simplex) {
                let p1 = t.at(c);
                if !q3::is_inverted(&t.pts) && q3::is_inverted(&p1) {
                    return false;
                }
                before = before.min(min_sine(&t.pts));
                after = after.min(min_sine(&p1));
            }
        }
        // the acceptance rule's score but for the sizes: quality, then validity (a move
        // that does not raise the worst quality is refused whatever the validity, and a
        // hexahedron's validity costs more than its shape)
        for e in &self.elements {
            let quality = |x: DVec3| match m {
                Measure::Shape => e.shape_measured(x),
                Measure::MinSine => solid::solid_min_sine(e.kind, e.corners(&e.at(x))),
            };
            // the other kinds' mean ratios in the tetrahedra's order: q³/27
            let order = |q: f64| {
                if m == Measure::Shape {
                    q * q * q / 27.0
                } else {
                    q
                }
            };
            before = before.min(order(quality(e.x())));
            after = after.min(order(quality(c)));
        }
        after > before
            && !self.elements.iter().any(|e| {
                e.validity_measured(e.x()) == Validity::Valid
                    && e.validity_measured(c) != Validity::Valid
            })
    }
    /// The guard's limit, asked as an optimisation starts: the elements' `det J` forms are
    /// made here, as the solve's trials read them.
    fn inverted_now(&self) -> usize {
        self.tets
            .iter()
            .filter(|t| t.simplex && q3::is_inverted(&t.pts))
            .count()
            + self
                .elements
                .iter()
                .filter(|e| e.validity_at(e.x()) != Validity::Valid)
                .count()
    }
    /// [`shape_at`](DriverStar::shape_at)'s count at the gathered position, without the
    /// mean ratios: the same tests of the same corners.
    fn any_inverted_now(&self) -> bool {
        self.tets
            .iter()
            .any(|t| t.simplex && q3::is_inverted(&t.pts))
            || self
                .elements
                .iter()
                .any(|e| e.validity_measured(e.x()) != Validity::Valid)
    }
    /// The other corners are as gathered and the forms depend on them only: moving the
    /// node back to its place in `mesh` is the gather. (This star has no
    /// [`smart_from_mesh`](DriverStar::smart_from_mesh), so a driver that decides a node
    /// has gathered it.)
    fn regather(&mut self, mesh: &VolumeMesh, node: usize) {
        if self.node as usize != node {
            return self.gather(mesh, node);
        }
        self.restar(mesh.nodes()[node]);
    }
    fn inverted_at(&self, x: DVec3) -> usize {
        debug_assert!(self.forms_pending_at.is_none(), "the guard reads the forms");
        self.tets
            .iter()
            .enumerate()
            .filter(|&(i, t)| t.simplex && t.inverted_at(x, self.reference_of(i)))
            .count()
            + self
                .elements
                .iter()
                .filter(|e| e.validity_at(x) != Validity::Valid)
                .count()
    }
    /// In the star's own frame where it is far from unit size (its points multiplied by
    /// the power of two its solves take, [`crate::numeric::unit_factor`]): the sum is
    /// compared only within the star, and its determinants of coordinates near 2^±520
    /// left the doubles (issue 61).
    fn inversion(&self, x: DVec3) -> f64 {
        let f = self.frame();
        let at = |p: [DVec3; 4]| framed(p, f);
        let tets: f64 = self
            .tets
            .iter()
            .filter(|t| t.simplex)
            .map(|t| (-6.0 * q3::signed_volume(&at(t.at(x)))).max(0.0))
            .sum();
        if self.elements.is_empty() {
            return tets;
        }
        tets + self
            .elements
            .iter()
            .map(|e| {
                let mut p = e.at(x);
                if f != 1.0 {
                    p.iter_mut().for_each(|q| *q *= f);
                }
                let p = e.corners(&p);
                solid::solid_inversion(e.kind, p, solid::validity(e.kind, p))
            })
            .sum::<f64>()
    }
    /// The tetrahedra's worst mean ratios exact, each taken only where it may be the worst
    /// (`LeastMeanRatio`, this module's).
    /// Each element's inversion in the star's [`frame`](CornerStar::frame).
    fn verdict(&self, x: DVec3, m: Measure) -> Verdict {
        let mut v = Verdict::default();
        let frame = self.frame();
        if m == Measure::Shape {
            let (mut before, mut after) = (LeastMeanRatio::default(), LeastMeanRatio::default());
            // the measures the smart Laplacian's test took at these positions, or taken here
            let mut memo = self.tet_memo.borrow_mut();
            let (b, a) = (
                memo.slot(&self.tets, self.x0, self.reference(), frame),
                memo.slot(&self.tets, x, self.reference(), frame),
            );
            let tets = self.tets.iter().filter(|t| t.simplex);
            for (t, ((p0, t0), (p1, t1))) in tets.zip(memo.measures(b).iter().zip(memo.measures(a)))
            {
                v.add_deciding_size(&ElementScore::tet_of(t0), &ElementScore::tet_of(t1), || {
                    Size::floor_kept_for_certain(t0.det_within(), t1.det_within())
                        || Size::tet(&t.at(x)).at_least(MIN_SIZE_RATIO, &Size::tet(&t.at(self.x0)))
                });
                v.add_qualities(before.add_parts(p0), after.add_parts(p1));
            }
        } else {
            for t in self.tets.iter().filter(|t| t.simplex) {
                v.add(
                    &ElementScore::tet(&framed(t.pts, frame), self.reference(), m),
                    &ElementScore::tet(&framed(t.at(x), frame), self.reference(), m),
                );
            }
        }
        for e in &self.elements {
            v.add_deciding_size(&e.score(e.x(), m, frame), &e.score(x, m, frame), || e.keeps_size(x));
        }
        v
    }
    /// A 10-node mesh's tetrahedra with their mid-edge nodes (those of the node's edges
    /// following it to their middles, as [`VolumeMesh::follow_mid_nodes`] moves them), so the
    /// rule reads what the statistics read; the other kinds are measured by their corners.
    /// From what the stars kept of their elements (`KnownSolids`): an element other than a
    /// tetrahedron (whose validity is one determinant's sign) measured valid at its corners
    /// as they are now, bit for bit. The last star's elements are kept at the next gather.
    fn known_valid(&self, mesh: &VolumeMesh, e: usize) -> bool {
        let kind = mesh.element_kind(e);
        !kind.is_tet() && self.known_valid_solid(e as u32, kind, &mesh.corners(e)[..kind.corners()])
    }
    /// Every element of the node in `mesh`, the node at `x`
    /// ([`VolumeMesh::element_points_with_node_at`]), as the statistics measure it
    /// ([`solid::solid_within`]).
    fn reads_within(&self, mesh: &VolumeMesh, x: DVec3, bounds: &Reading) -> bool {
        let n = self.node as usize;
        mesh.node_tets(n).iter().all(|&e| {
            let e = e as usize;
            let (p, count) = mesh.element_points_with_node_at(e, n, x);
            solid::solid_within(mesh.element_kind(e), &p[..count], bounds)
        }) && graded_within(mesh, n, x, bounds.grading)
    }
    fn verdict_in(&self, mesh: &VolumeMesh, x: DVec3, m: Measure) -> Verdict {
        if !mesh.kinds().contains(&VolumeKind::Tet10) {
            return self.verdict(x, m);
        }
        let n = self.node;
        let mut v = Verdict::default();
        for t in &self.tets {
            let ids = mesh.element(t.element as usize);
            let row = mesh.element_kind(t.element as usize).row();
            let before: [DVec3; 10] = std::array::from_fn(|j| mesh.nodes()[ids[j] as usize]);
            let mut after = before;
            for (j, &i) in ids[..row.corners].iter().enumerate() {
                if i == n {
                    after[j] = x;
                }
            }
            for (k, &[a, b]) in row.edges.iter().enumerate() {
                let mid = row.corners + k;
                if (ids[a] == n || ids[b] == n) && !mesh.fixed()[ids[mid] as usize] {
                    after[mid] = 0.5 * (after[a] + after[b]);
                }
            }
            let (r, frame) = (self.reference(), self.frame());
            v.add(
                &ElementScore::tet10(&framed(before, frame), r, m),
                &ElementScore::tet10(&framed(after, frame), r, m),
            );
        }
        v
    }
}

/// The smallest mean ratio of tetrahedra given one by one, exact, with the cube root taken
/// only for those that may be the smallest: a tetrahedron whose order key
/// ([`q3::mean_ratio_order`], `q³/27`, |key| ≤ 1/27) lies beyond the smallest key measured
/// so far by more than 10⁻⁹ of it (and 10⁻²⁹⁰, where keys underflow) has a larger mean
/// ratio than that one, rounded or not; the keys' own rounding is some 10⁻¹⁵.
#[derive(Clone, Copy, Debug)]
struct LeastMeanRatio {
    key: f64,
}

impl Default for LeastMeanRatio {
    fn default() -> Self {
        LeastMeanRatio { key: f64::INFINITY }
    }
}

impl LeastMeanRatio {
    /// The mean ratio of `p` where it may be the smallest so far, +∞ where it cannot.
    #[inline]
    fn add(&mut self, p: &[DVec3; 4], r: &q3::CornerReference) -> f64 {
        self.add_parts(&q3::MeanRatioParts::of(p, r))
    }
    /// [`add`](Self::add) of a tetrahedron's parts taken before.
    #[inline]
    fn add_parts(&mut self, parts: &q3::MeanRatioParts) -> f64 {
        let key = parts.order();
        if key > self.key + 1e-9 * self.key.abs() + 1e-290 {
            return f64::INFINITY;
        }
        self.key = self.key.min(key);
        parts.mean_ratio()
    }
}

/// A star's element other than a tetrahedron as the acceptance rule scores it.
trait SolidScore {
    /// [`ElementScore::solid`] with the free node at `x` but for its size, its validity as
    /// the drivers measure it ([`StarSolid::validity_measured`]: the same answer as
    /// [`solid::validity`], kept for the position, from the `det J` form once the guard has
    /// made it), its inversion of its corners times the star's `frame`.
    fn score(&self, x: DVec3, m: Measure, frame: f64) -> ElementScore<()>;
    /// Whether the element, valid as gathered, keeps at least [`MIN_SIZE_RATIO`] of its size
    /// ([`Size::least_corner`]) with the free node at `x`: from its corners' determinants
    /// where they decide ([`Size::floor_kept_for_certain`]), else from the sizes
    /// measured ([`StarSolid::sizes_measured`]), the same answer.
    fn keeps_size(&self, x: DVec3) -> bool;
}

impl SolidScore for StarSolid {
    fn score(&self, x: DVec3, m: Measure, frame: f64) -> ElementScore<()> {
        // the corners with the free node at `x`, copied only where a measure reads them
        let p = std::cell::OnceCell::new();
        let corners = || self.corners(p.get_or_init(|| framed(self.at(x), frame)));
        let score = ElementScore::solid_sized(self.kind, self.validity_measured(x), (), corners);
        let quality = match m {
            Measure::Shape => self.shape_measured(x),
            Measure::MinSine => solid::solid_min_sine(self.kind, corners()),
        };
        ElementScore { quality, ..score }
    }
    fn keeps_size(&self, x: DVec3) -> bool {
        Size::floor_kept_for_certain(
            self.least_corner_det_measured(self.x()),
            self.least_corner_det_measured(x),
        ) || {
            let before = Size::least_corner(self.kind, &self.sizes_measured(self.x()));
            Size::least_corner(self.kind, &self.sizes_measured(x)).at_least(MIN_SIZE_RATIO, &before)
        }
    }
}

/// A tetrahedral mesh as its own [`StarView`].
pub(crate) struct Solid<'a>(pub &'a mut VolumeMesh);

impl StarView for Solid<'_> {
    type Mesh = VolumeMesh;
    #[inline]
    fn mesh(&self) -> &VolumeMesh {
        self.0
    }
    #[inline]
    fn star_mesh(&mut self, _: usize) -> &VolumeMesh {
        self.0
    }
    fn place(&mut self, n: usize, x: DVec3) {
        self.0.nodes_mut()[n] = x;
        if self.0.is_quadratic() {
            self.0.follow_mid_nodes(n);
        }
        self.0.settle(n);
    }
    fn is_inverted(&self, e: usize) -> bool {
        self.0.is_inverted(e)
    }
}

/// A smoother of tetrahedral meshes: the planar drivers' [`Smoother`] over tetrahedral
/// stars, with the same options, pass by pass.
#[derive(Clone, Debug)]
pub struct VolumeSmoother {
    smoother: Smoother<CornerStar>,
}

impl VolumeSmoother {
    /// A smoother with checked options.
    pub fn new(options: SmoothOptions) -> Result<Self> {
        Ok(VolumeSmoother {
            smoother: Smoother::new(options)?,
        })
    }
    pub fn options(&self) -> &SmoothOptions {
        self.smoother.options()
    }
    /// [`Smoother::set_fit_pending`]: whether this smoother's next sweep is the run's first.
    pub fn set_fit_pending(&mut self, pending: bool) {
        self.smoother.set_fit_pending(pending);
    }
    /// The node loop of a pass (the planned order, then the untangling sweeps). With the
    /// acceptance rule on (every strategy but the plain Laplacian, the guard on), a pass
    /// never ends with more inverted elements than it began with: each move keeps its
    /// star no worse, but an inverted star may fold a valid element where its inversion
    /// falls, and later moves need not mend it (issue 61: bust went from 1 inverted to 2
    /// at pass 4). Then the elements inverted by the pass go back to where the pass found
    /// their nodes, until the count is no larger (at worst, the whole pass is undone). So
    /// do the inverted elements whose scaled Jacobian ends below the worst an inverted
    /// element had when the pass began (issue 61: armadillo's worst fell from −0.514 after
    /// 3 passes to −0.587 after 10). Before that judgement, a pass after the run's first
    /// that began tangled, with optimization steps of an objective built to untangle, ends
    /// with the mend of the folds left (`mend::mend_folds`). The first pass is left
    /// without: Livesu et al.'s block stress test kept 5 of 2371 folds after it, which the
    /// second pass undoes; mended at once, one hexahedron stayed barely valid and the
    /// smallest scaled Jacobian ended 0.110, not 0.373.
    pub fn sweep(
        &mut self,
        mesh: &mut VolumeMesh,
        objective: &dyn Objective<CornerStar>,
    ) -> SweepCounts {
        let o = self.smoother.options();
        if !(o.keep_valid && o.strategy != crate::smooth::Strategy::Laplace) {
            return self.smoother.sweep_in(&mut Solid(mesh), objective);
        }
        // after the run's first pass, an objective built to untangle, with optimization
        // steps, mends what it left folded (the first pass leaves what the next would undo)
        let mends = o.strategy != crate::smooth::Strategy::Smart && objective.untangles() && !self.smoother.at_run_start();
        // the first pass against a target other than the ideal fits the mesh to it first
        let grading = o.keep_grading.unwrap_or(f64::INFINITY);
        let fit_steps = if self.smoother.fit_due(mesh.has_target()) {
            super::fit::fit_to_targets(mesh, objective, grading)
        } else {
            0
        };
        let (start, was) = (mesh.nodes().to_vec(), inverted_elements(mesh));
        let before = was.iter().filter(|&&i| i).count();
        // the worst scaled Jacobian of an inverted element, as the statistics read it
        let scaled_jacobian = |m: &VolumeMesh, e: usize| m.measures(e).scaled_jacobian;
        let floor = (0..was.len()).filter(|&e| was[e]).map(|e| scaled_jacobian(mesh, e)).fold(f64::INFINITY, f64::min);
        let mut counts = self.smoother.sweep_in(&mut Solid(mesh), objective);
        counts.fit_steps = fit_steps;
        if before > 0 && mends {
            super::mend::mend_folds(mesh);
        }
        let judge = |m: &VolumeMesh, round: usize| {
            let inverted = inverted_elements(m);
            let more = inverted.iter().filter(|&&i| i).count() > before;
            let culprits: Vec<usize> = (0..inverted.len())
                .filter(|&e| inverted[e])
                .filter(|&e| (more && (!was[e] || round == 3)) || scaled_jacobian(m, e) < floor)
                .collect();
            (more || !culprits.is_empty()).then_some(culprits)
        };
        crate::smooth::undo_what_got_worse(
            mesh,
            was.len(),
            judge,
            |m, e| m.element(e).to_vec(),
            |m, i| {
                m.nodes_mut()[i] = start[i];
                m.settle(i);
            },
        );
        counts
    }
    /// One pass with its record: counts and time, and the mesh's statistics after it
    /// ([`super::volume_stats`]: the angles are dihedral angles, the quality the mean
    /// ratio). `clock` returns milliseconds.
    pub fn pass(
        &mut self,
        mesh: &mut VolumeMesh,
        objective: &dyn Objective<CornerStar>,
        pass: u32,
        clock: &dyn Fn() -> f64,
    ) -> PassRecord {
        let t0 = clock();
        let counts = self.sweep(mesh, objective);
        let elapsed_ms = clock() - t0;
        let t1 = clock();
        let after = super::volume_stats(mesh).quick();
        let objective_total = Some(
            self.smoother
                .objective_total_in(&mut Solid(mesh), objective),
        );
        PassRecord {
            pass,
            counts,
            after,
            objective_total,
            elapsed_ms,
            stats_ms: clock() - t1,
        }
    }
}

/// Which elements of `mesh` are inverted, as its statistics count them.
pub(super) fn inverted_elements(mesh: &VolumeMesh) -> Vec<bool> {
    (0..mesh.element_count())
        .map(|e| {
            if mesh.is_quadratic() {
                mesh.measures(e).inverted
            } else {
                mesh.is_inverted(e)
            }
        })
        .collect()
}

/// Runs `passes` passes of a new [`VolumeSmoother`] over `mesh`, returning their records.
pub fn smooth_volume(
    mesh: &mut VolumeMesh,
    objective: &dyn Objective<CornerStar>,
    options: SmoothOptions,
    passes: u32,
    clock: &dyn Fn() -> f64,
) -> Result<Vec<PassRecord>> {
    let mut s = VolumeSmoother::new(options)?;
    Ok((1..=passes)
        .map(|p| s.pass(mesh, objective, p, clock))
        .collect())
}
