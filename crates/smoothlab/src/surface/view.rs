//! Smoothing a surface with the planar drivers (see the module docs of
//! [`crate::surface`]): a free node's star flattened into its tangent plane, the driver's
//! 2D answer lifted back and projected onto the reference surface.

use glam::{DVec2, DVec3};

use super::Surface;
use crate::error::{Error, Result};
use crate::mesh::{Follower, Mesh, Plane};
use crate::objective::{Objective, Star};
use crate::quality::Reading;
use crate::smooth::{
    is_inverted, ElementScore, Measure, PassRecord, SmoothOptions, Smoother, StarView, Verdict,
};

/// A surface seen by a driver: each star flattened into the tangent plane at its node.
pub(crate) struct SurfaceView<'a> {
    surface: &'a mut Surface,
    /// The tangent plane of the star flattened last.
    plane: Plane,
    /// What the statistics read of the surface's valid elements when first asked: the
    /// bounds a move on a valid star keeps within ([`Reading`]).
    bounds: Option<Option<Reading>>,
    /// The run's grading bound, where the smoother has one ([`Reading::grading`]).
    grading_bound: Option<f64>,
}

impl<'a> SurfaceView<'a> {
    pub(crate) fn new(surface: &'a mut Surface) -> Self {
        SurfaceView {
            surface,
            plane: Plane {
                origin: DVec3::ZERO,
                u: DVec3::X,
                w: DVec3::Y,
            },
            bounds: None,
            grading_bound: None,
        }
    }
}

impl Surface {
    /// The tangent plane at free node `n`: through the node, normal to its star's
    /// area-weighted normal (the sum of its elements' Newell normals, which for a closed
    /// ring of elements depends on the ring alone, not on where the node is, so a tangled
    /// star has one too), or the reference's normal there when that sum is zero or faces
    /// away from the reference.
    pub(crate) fn tangent_plane(&self, n: usize) -> Plane {
        let x = self.points[n];
        let reference = self.project_near(x, n).normal;
        // a reference fitted through the nodes is there because the elements fold: their
        // normals are not the surface's
        if matches!(*self.reference, super::Reference::Fitted(_)) {
            return Plane::with_normal(x, reference);
        }
        let star: DVec3 = self
            .flat
            .node_elements(n)
            .iter()
            .map(|&e| super::element_normal(&self.flat, &self.points, e as usize))
            .sum();
        let normal = match star.try_normalize() {
            Some(s) if s.dot(reference) > 0.0 => s,
            _ => reference,
        };
        Plane::with_normal(x, normal)
    }

    /// Moves node `n` to the projection of `p` onto the reference, and the nodes that
    /// follow it to the projections of their edges' middles (a 9-node quad's centre: of
    /// its eight nodes' mean).
    pub fn place(&mut self, n: usize, p: DVec3) {
        if self.slides(n) {
            // a sliding node's curve edges are straight: no node follows it
            return self.slide_to(n, p);
        }
        self.move_to(n, p);
        if !self.flat.has_quadratic() {
            return;
        }
        let mut follow = Vec::new();
        self.flat.for_each_follower(n, |f| follow.push(f));
        for f in follow {
            match f {
                Follower::Mid { mid, a, b } => {
                    self.move_to(mid, 0.5 * (self.points[a] + self.points[b]))
                }
                Follower::Centre { centre, element } => {
                    let s: DVec3 = self.flat.element(element)[..8]
                        .iter()
                        .map(|&i| self.points[i as usize])
                        .sum();
                    self.move_to(centre, s / 8.0);
                }
            }
        }
    }

    /// [`place`](Self::place), undone when it folds a valid star (measured in 3D, each
    /// element in its own plane), the planar drivers' promise: the planar guard keeps the
    /// flattened star valid, but the projection back onto the surface, of the node and of
    /// the mid-side nodes following it, can still fold an element where the reference
    /// curves or is itself folded (a tangled file). The plain Laplacian's placing. Returns
    /// whether the node moved.
    pub(crate) fn place_keeping_valid(&mut self, n: usize, p: DVec3) -> bool {
        self.place_kept_if(n, p, Measure::Shape, |(before, _), (after, _)| {
            before.iter().any(|b| b.inverted) || after.iter().all(|a| !a.inverted)
        })
    }

    /// [`place`](Self::place), undone unless the star gets no worse by the drivers'
    /// acceptance rule ([`Verdict`], `docs/formulas.md` §4 and §7), measured after the
    /// projection back onto the surface (the node's and its following mid-side nodes'),
    /// each element in its own plane: every strategy's placing but the plain Laplacian's.
    /// Returns whether the node moved.
    pub(crate) fn place_if_no_worse(
        &mut self,
        n: usize,
        p: DVec3,
        measure: Measure,
        bounds: Option<&Reading>,
    ) -> bool {
        self.place_kept_if(n, p, measure, |(before, _), (after, read_after)| {
            let mut v = Verdict::default();
            for (b, a) in before.iter().zip(after) {
                v.add(b, a);
            }
            v.keeps() && (!v.was_valid() || bounds.map_or(true, |b| read_after.within(b) && read_after.grading <= b.grading))
        })
    }

    /// [`place`](Self::place), kept when `keep` says so of the star's elements' scores by
    /// `measure` before and after (in the order of the node's elements), else undone.
    fn place_kept_if(
        &mut self,
        n: usize,
        p: DVec3,
        measure: Measure,
        keep: impl Fn(&(Vec<ElementScore>, Reading), &(Vec<ElementScore>, Reading)) -> bool,
    ) -> bool {
        let star: Vec<usize> = self
            .flat
            .node_elements(n)
            .iter()
            .map(|&e| e as usize)
            .collect();
        // the reading is asked of the star after the move only
        let scores = |s: &Surface, read: bool| -> (Vec<ElementScore>, Reading) {
            let mut reading = Reading::default();
            let scores = star
                .iter()
                .map(|&e| {
                    let (kind, q) = (s.flat.kind(e), s.element_points_2d(e));
                    if read {
                        reading = reading.and(Reading::planar(kind, &q).0);
                    }
                    ElementScore::planar(kind, &q, measure)
                })
                .collect();
            if read {
                reading.grading = s.star_grading(&star);
            }
            (scores, reading)
        };
        let before = scores(self, false);
        let saved = self.keep_around(n);
        self.place(n, p);
        if !keep(&before, &scores(self, true)) {
            self.put_back(saved);
            return false;
        }
        true
    }

    /// What a move of node `n` changes (placing it: the node and the nodes
    /// that follow it, their positions and where their projections start), as it is now:
    /// [`put_back`](Self::put_back) restores it exactly.
    pub fn keep_around(&self, n: usize) -> KeptNodes {
        let mut moved = vec![n];
        self.flat.for_each_follower(n, |f| {
            moved.push(match f {
                Follower::Mid { mid, .. } => mid,
                Follower::Centre { centre, .. } => centre,
            })
        });
        let nodes = moved
            .iter()
            .map(|&m| (m, self.points[m], self.hint[m]))
            .collect();
        KeptNodes {
            node: n,
            nodes,
            curve_hint: self.curve_hint.get(n).copied(),
        }
    }

    /// Puts back what [`keep_around`](Self::keep_around) kept (of this surface: the
    /// positions of another surface's nodes are refused by their numbers, not checked).
    pub fn put_back(&mut self, kept: KeptNodes) {
        for (m, q, h) in kept.nodes {
            if m < self.points.len() {
                self.points[m] = q;
                self.hint[m] = h;
            }
        }
        if let (Some(c), Some(slot)) = (kept.curve_hint, self.curve_hint.get_mut(kept.node)) {
            *slot = c;
        }
    }

    fn move_to(&mut self, n: usize, p: DVec3) {
        let q = self.project_near(p, n);
        self.points[n] = q.point;
        self.hint[n] = q.face;
    }
}

impl StarView for SurfaceView<'_> {
    type Mesh = Mesh;
    fn mesh(&self) -> &Mesh {
        &self.surface.flat
    }

    fn star_mesh(&mut self, n: usize) -> &Mesh {
        // the nodes that follow n sit where they will be put in the plane, so the star is
        // the same at n's position whether it moved there or not
        let plane = self.surface.tangent_plane(n);
        let points = &self.surface.points;
        self.surface.flat.set_star(n, |m| plane.to_2d(points[m]));
        let s = &mut *self.surface;
        Surface::set_target_star(&mut s.flat, s.target.as_deref().map(|t| &t[..]), s.target_shapes.as_deref().map(|t| &t[..]), n, &plane);
        self.plane = plane;
        &self.surface.flat
    }

    fn place(&mut self, n: usize, x: DVec2) {
        let p = self.plane.to_3d(x);
        self.surface.place_keeping_valid(n, p);
    }

    const CHECKS_ON_PLACING: bool = true;

    fn place_if_no_worse(&mut self, n: usize, x: DVec2, measure: Measure) -> bool {
        let p = self.plane.to_3d(x);
        let surface = &*self.surface;
        let bounds = *self.bounds.get_or_insert_with(|| {
            Reading::planar_mesh(&surface.flat, |e| surface.element_points_2d(e))
        });
        let grading_bound = self.grading_bound;
        let bounds = bounds.map(|b| {
            let b = Reading { grading: grading_bound.unwrap_or(b.grading), ..b };
            if measure == Measure::Shape {
                b.without_quality()
            } else {
                b
            }
        });
        self.surface
            .place_if_no_worse(n, p, measure, bounds.as_ref())
    }

    fn is_inverted(&self, e: usize) -> bool {
        is_inverted(
            self.surface.flat.kind(e),
            &self.surface.element_points_2d(e),
        )
    }
}

/// A [`Smoother`] for surfaces: every strategy, order and objective of the planar driver,
/// on each star flattened into its tangent plane.
#[derive(Clone, Debug)]
pub struct SurfaceSmoother {
    smoother: Smoother,
    passes: u32,
    /// The surface's grading when first read valid in the run ([`Reading::grading`]).
    grading_bound: Option<f64>,
}

impl SurfaceSmoother {
    pub fn new(options: SmoothOptions) -> Result<Self> {
        Ok(SurfaceSmoother {
            smoother: Smoother::new(options)?,
            passes: 0,
            grading_bound: None,
        })
    }

    /// One pass over the surface, with its record (as [`Smoother::pass`]).
    pub fn pass(
        &mut self,
        surface: &mut Surface,
        objective: &dyn Objective,
        clock: &dyn Fn() -> f64,
    ) -> PassRecord {
        self.passes += 1;
        let t0 = clock();
        let o = self.smoother.options();
        let guard = o.keep_valid && o.strategy != crate::smooth::Strategy::Laplace;
        let start = guard.then(|| {
            (
                surface.points.clone(),
                surface.hint.clone(),
                surface.curve_hint.clone(),
                surface.inverted_elements(),
            )
        });
        // the run's grading: as the first pass found the surface (none if tangled)
        let keep = self.smoother.options().keep_grading;
        let grading = *self.grading_bound.get_or_insert_with(|| {
            keep.unwrap_or_else(|| Reading::planar_mesh(&surface.flat, |e| surface.element_points_2d(e)).map_or(f64::INFINITY, |r| r.grading))
        });
        let mut view = SurfaceView::new(surface);
        view.grading_bound = Some(grading);
        let counts = self.smoother.sweep_in(&mut view, objective);
        if let Some((points, hint, curve_hint, was)) = start {
            crate::smooth::undo_new_inversions(
                surface,
                &was,
                Surface::inverted_elements,
                |s, e| s.flat.element(e).to_vec(),
                |s, i| {
                    s.points[i] = points[i];
                    s.hint[i] = hint[i];
                    if let (Some(c), Some(&h)) = (s.curve_hint.get_mut(i), curve_hint.get(i)) {
                        *c = h;
                    }
                },
            );
        }
        let elapsed_ms = clock() - t0;
        let t1 = clock();
        let after = surface.stats().quick();
        let objective_total = Some(
            self.smoother
                .objective_total_in(&mut SurfaceView::new(surface), objective),
        );
        PassRecord {
            pass: self.passes,
            counts,
            after,
            objective_total,
            elapsed_ms,
            stats_ms: clock() - t1,
        }
    }
}

/// Runs `passes` passes of a new [`SurfaceSmoother`] over `surface`.
pub fn smooth_surface(
    surface: &mut Surface,
    objective: &dyn Objective,
    options: SmoothOptions,
    passes: u32,
    clock: &dyn Fn() -> f64,
) -> Result<Vec<PassRecord>> {
    let mut s = SurfaceSmoother::new(options)?;
    Ok((0..passes)
        .map(|_| s.pass(surface, objective, clock))
        .collect())
}

/// A node's move as it can be taken back: see [`Surface::keep_around`].
#[derive(Clone, Debug, PartialEq)]
pub struct KeptNodes {
    node: usize,
    nodes: Vec<(usize, DVec3, u32)>,
    curve_hint: Option<[u32; 2]>,
}

impl Surface {
    /// Which elements are inverted, as the statistics count them ([`Surface::stats`]).
    pub fn inverted_elements(&self) -> Vec<bool> {
        (0..self.flat.element_count())
            .map(|e| {
                let kind = self.flat.kind(e);
                crate::quality::element_quality(
                    kind,
                    &self.element_points_2d(e)[..kind.node_count()],
                )
                .inverted
            })
            .collect()
    }

    /// Free node `n`'s star as the drivers see it: flattened into its tangent plane at `n`
    /// (the nodes that follow `n` where they will follow), gathered as a planar [`Star`],
    /// and that plane (its origin the node, so the node is at 2D `0`): the star's objective
    /// over the plane is the one a pass minimises or maximises at `n`, and
    /// [`Plane::to_3d`] lifts a 2D answer back into space (then placing it
    /// projects it onto the surface, as the drivers do).
    pub fn tangent_star(&self, n: usize) -> Result<(Star, Plane)> {
        if n >= self.node_count() {
            return Err(Error::node(
                n,
                None,
                format!("no such node: the mesh has {} nodes", self.node_count()),
            ));
        }
        if !self.flat.is_free(n) {
            return Err(Error::node(
                n,
                None,
                "is fixed or not an element corner, so it is never smoothed",
            ));
        }
        let plane = self.tangent_plane(n);
        let mut flat = self.flat.clone();
        flat.set_star(n, |m| plane.to_2d(self.points[m]));
        Surface::set_target_star(&mut flat, self.target.as_deref().map(|t| &t[..]), self.target_shapes.as_deref().map(|t| &t[..]), n, &plane);
        let mut star = Star::new();
        star.gather(&flat, n);
        Ok((star, plane))
    }

    /// Free node `n`'s star flattened into its tangent plane, as a planar mesh of its own
    /// with every node fixed but `n` (its number in that mesh comes second): what the drivers
    /// see of the node, for the planar views of one node (the level sets of its objective,
    /// its solver's path).
    pub fn star_in_tangent_plane(&self, n: usize) -> Result<(Mesh, usize)> {
        if n >= self.node_count() {
            return Err(Error::node(
                n,
                None,
                format!("no such node: the mesh has {} nodes", self.node_count()),
            ));
        }
        if !self.flat.is_free(n) {
            return Err(Error::node(
                n,
                None,
                "is fixed or not an element corner, so it is never smoothed",
            ));
        }
        let mut s = self.clone();
        let flat = SurfaceView::new(&mut s).star_mesh(n).clone();
        let mut local = vec![u32::MAX; flat.node_count()];
        let mut b = crate::mesh::MeshBuilder::new();
        let mut fixed = Vec::new();
        for &e in flat.node_elements(n) {
            let ids: Vec<u32> = flat
                .element(e as usize)
                .iter()
                .map(|&m| {
                    if local[m as usize] == u32::MAX {
                        let p = flat.nodes()[m as usize];
                        local[m as usize] = b.add_node([p.x, p.y, 0.0], 0) as u32;
                        fixed.push(m as usize != n);
                    }
                    local[m as usize]
                })
                .collect();
            b.add_element(flat.kind(e as usize), &ids, 0);
        }
        b.fixed = crate::mesh::FixedSpec::Exact(fixed);
        Ok((b.build()?, local[n] as usize))
    }

    /// The free node whose star has the worst element (smallest α/β, each element in its
    /// own plane), as the planar views choose by default.
    pub fn worst_free_node(&self) -> Option<usize> {
        let q: Vec<f64> = (0..self.element_count())
            .map(|e| {
                let kind = self.flat.kind(e);
                crate::quality::element_quality(
                    kind,
                    &self.element_points_2d(e)[..kind.node_count()],
                )
                .shape
            })
            .collect();
        (0..self.node_count())
            .filter(|&n| self.flat.is_free(n))
            .map(|n| {
                (
                    n,
                    self.flat
                        .node_elements(n)
                        .iter()
                        .map(|&e| q[e as usize])
                        .fold(f64::INFINITY, f64::min),
                )
            })
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(n, _)| n)
    }
}
