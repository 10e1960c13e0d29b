//! The star of a free node of a volume mesh, gathered once per visit.
//! It holds the corners the node moves, and the elements other than tetrahedra whole.

use glam::DVec3;

use super::known_solids::{KnownSolids, PositionMemo};
use super::memo::TetMeasureMemo;
use crate::mesh::VolumeKind;
use crate::objective::NodeStar;
use crate::quality::solid::{validity, CornerShapes, CornerSizes, DetForm, ValidBall, Validity};
use crate::quality::tet::{self as q3, CornerForm, CornerReference, EQUILATERAL_TET};

/// One corner of an element of a star, as the tetrahedron of its Jacobian (Knupp 1999):
/// the corner and its three edge neighbours, reordered so that the free node comes first.
/// A tetrahedron is one such corner, the free node's own; a hexahedron, wedge or pyramid
/// gives every measured corner whose tetrahedron holds the free node (its own and those of
/// its edge neighbours), each measured against the reference of its slot
/// ([`crate::mesh::VolumeKindRow::slot_references`]) so that it reads the same `T = A·W⁻¹`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StarCorner {
    /// Element index in the mesh.
    pub element: u32,
    /// The corner's tetrahedron, the free node's position first, in an even permutation.
    pub pts: [DVec3; 4],
    /// The reference its Jacobian is measured against.
    pub reference: &'static CornerReference,
    /// Whether the tetrahedron is the whole element (a tetrahedron): its measures are the
    /// element's (the dihedral sines), not a corner's (the scaled Jacobian).
    pub simplex: bool,
    /// Its weighted Jacobian as a function of the free node's position, worked out from
    /// `pts` and `reference` when made: what the smooth objectives read at a trial position.
    pub form: CornerForm,
}

impl StarCorner {
    /// The corner `pts` (the free node first) of `element`, against `reference`.
    pub fn new(
        element: u32,
        pts: [DVec3; 4],
        reference: &'static CornerReference,
        simplex: bool,
    ) -> Self {
        StarCorner {
            element,
            pts,
            reference,
            simplex,
            form: CornerForm::of(&pts, reference),
        }
    }
    /// [`new`](Self::new) with its form [`CornerForm::PENDING`], for a star the drivers only
    /// measure unless they optimise it ([`CornerStar::complete_forms`]).
    pub fn pending(
        element: u32,
        pts: [DVec3; 4],
        reference: &'static CornerReference,
        simplex: bool,
    ) -> Self {
        StarCorner {
            element,
            pts,
            reference,
            simplex,
            form: CornerForm::PENDING,
        }
    }
    /// A tetrahedron of a star (the free node first), measured against the equilateral
    /// tetrahedron.
    pub fn tet(element: u32, pts: [DVec3; 4]) -> Self {
        StarCorner::new(element, pts, &EQUILATERAL_TET, true)
    }
    /// The corners with the free node at `x`.
    #[inline]
    pub fn at(&self, x: DVec3) -> [DVec3; 4] {
        let mut p = self.pts;
        p[0] = x;
        p
    }
    /// [`q3::is_inverted`] with the free node at `x`, from the form where it decides; `r`
    /// the reference the form was made against ([`CornerStar::reference_of`]).
    #[inline]
    pub fn inverted_at(&self, x: DVec3, r: &CornerReference) -> bool {
        self.form
            .inverted_at(x, r)
            .unwrap_or_else(|| q3::is_inverted(&self.at(x)))
    }
}

/// An element of a star that is not a tetrahedron, whole, for the validity guard: its
/// corners (the free node's at `slot`) and kind.
#[derive(Clone, Debug, PartialEq)]
pub struct StarSolid {
    pub element: u32,
    pub kind: VolumeKind,
    pub slot: u8,
    pub pts: [DVec3; 8],
    /// Its `det J` as a function of the free node's position ([`DetForm`]), worked out at
    /// the guard's second question beyond the valid ball (a visit of the smart Laplacian
    /// asks none); it holds
    /// wherever the free node goes, as the other corners stay.
    det: std::cell::OnceCell<Option<DetForm>>,
    /// Where a hexahedron is valid for certain by its `det J` with its free node about the
    /// first position the guard asked that the memo did not answer (made there).
    ball: std::cell::OnceCell<Option<ValidBall>>,
    /// A second such ball, about the first position the guard asked beyond the first (its
    /// exact test takes the coefficients there), where the solve's later trials gather.
    second_ball: std::cell::Cell<Option<ValidBall>>,
    /// Whether the guard has asked a position outside the ball: the form is made at the
    /// second such question (the first is answered exactly, which costs less than the form).
    asked_beyond_ball: std::cell::Cell<bool>,
    /// The validity and the shape at the last two positions the drivers asked of
    /// [`validity_measured`](Self::validity_measured) and
    /// [`shape_measured`](Self::shape_measured) (the gathered one and a move's).
    pub(super) measured: PositionMemo<Validity>,
    pub(super) shaped: PositionMemo<f64>,
    /// The shape's terms at the last position it was measured at: a corner whose
    /// tetrahedron does not hold the free node keeps its term wherever the node goes.
    /// The position (`None` before any) and the terms there, borrowed and copied field by
    /// field ([`CornerShapes::copy_from`]) rather than copied whole: some 140 bytes, read
    /// at every shape, kept and recalled at every gather.
    pub(super) terms: std::cell::RefCell<(Option<DVec3>, CornerShapes)>,
    /// The corners' sizes at the last position they were measured at, as `terms`.
    sizes: std::cell::Cell<Option<(DVec3, CornerSizes)>>,
    /// The least corner determinant with its tolerance (the acceptance rule's size screen,
    /// [`least_corner_det`](crate::quality::solid::least_corner_det)) at the last two
    /// positions asked, as `measured`.
    pub(super) least_det: PositionMemo<Option<(f64, f64)>>,
}

impl StarSolid {
    /// The element `element` of `kind`, its corners `pts` with the free node at `slot`.
    pub fn new(element: u32, kind: VolumeKind, slot: u8, pts: [DVec3; 8]) -> Self {
        StarSolid {
            element,
            kind,
            slot,
            pts,
            det: std::cell::OnceCell::new(),
            ball: std::cell::OnceCell::new(),
            second_ball: std::cell::Cell::new(None),
            asked_beyond_ball: std::cell::Cell::new(false),
            measured: PositionMemo::default(),
            shaped: PositionMemo::default(),
            terms: std::cell::RefCell::new((None, CornerShapes::NONE)),
            sizes: std::cell::Cell::new(None),
            least_det: PositionMemo::default(),
        }
    }
    /// This element made [`new`](Self::new) in place, but for its corners, which the caller
    /// writes: the lazy forms' room is not written.
    fn reset(&mut self, element: u32, kind: VolumeKind, slot: u8) {
        (self.element, self.kind, self.slot) = (element, kind, slot);
        self.det = std::cell::OnceCell::new();
        self.ball = std::cell::OnceCell::new();
        self.second_ball = std::cell::Cell::new(None);
        self.asked_beyond_ball = std::cell::Cell::new(false);
        self.measured = PositionMemo::default();
        self.shaped = PositionMemo::default();
        self.terms.get_mut().0 = None;
        self.sizes = std::cell::Cell::new(None);
        self.least_det = PositionMemo::default();
    }
    /// [`validity`](crate::quality::solid::validity) with the free node at `x` as the
    /// drivers' measures ask it (the star as gathered, a move's position): from the
    /// [`ValidBall`] or the [`DetForm`] where the guard has made them and they decide, else
    /// exactly; each answer kept for the next question at the same position (the smart
    /// Laplacian's test and the acceptance rule ask the same positions). Without making them,
    /// which cost more than the exact test of a visit that optimises nothing.
    pub fn validity_measured(&self, x: DVec3) -> Validity {
        self.measured.get_or(x, || {
            self.validity_by(
                self.ball.get().and_then(|b| b.as_ref()),
                self.det.get().and_then(|f| f.as_ref()),
                x,
            )
        })
    }
    /// The validity at `x`: valid where `ball` holds it, else from `form` where it decides,
    /// else exactly.
    #[inline]
    fn validity_by(&self, ball: Option<&ValidBall>, form: Option<&DetForm>, x: DVec3) -> Validity {
        if ball.is_some_and(|b| b.holds(x)) || self.second_ball.get().is_some_and(|b| b.holds(x)) {
            return Validity::Valid;
        }
        form.and_then(|d| d.validity_at(x))
            .unwrap_or_else(|| validity(self.kind, self.corners(&self.at(x))))
    }
    /// [`solid_shape`](crate::quality::solid::solid_shape) with the free node at `x`, kept
    /// for the position as [`validity_measured`](Self::validity_measured) keeps its answer;
    /// the terms of the corners whose tetrahedra do not hold the free node taken from the
    /// last position measured (the same bits: [`CornerShapes`]).
    pub fn shape_measured(&self, x: DVec3) -> f64 {
        self.shaped.get_or(x, || {
            let p = self.at(x);
            let corners = self.corners(&p);
            let terms = {
                let kept = self.terms.borrow();
                CornerShapes::of(self.kind, corners, |c| {
                    (kept.0.is_some() && !self.moves(c)).then(|| kept.1.corner(c))
                })
            };
            match terms {
                Some(t) => {
                    let mut kept = self.terms.borrow_mut();
                    kept.0 = Some(x);
                    kept.1.copy_from(&t);
                    t.shape(self.kind)
                }
                None => crate::quality::solid::solid_shape(self.kind, corners),
            }
        })
    }
    /// Its corners' sizes with the free node at `x` (for the acceptance rule's size of the
    /// element), those of the corners whose tetrahedra do not hold the free node taken from
    /// the last position measured (the same bits: [`CornerSizes`]).
    pub fn sizes_measured(&self, x: DVec3) -> CornerSizes {
        let kept = self.sizes.get();
        if let Some((_, s)) = kept.filter(|&(at, _)| at == x) {
            return s;
        }
        let p = self.at(x);
        let s = CornerSizes::of(self.kind, self.corners(&p), |c| {
            kept.filter(|_| !self.moves(c))
                .map(|(_, s)| s.of_kind(self.kind)[c])
        });
        self.sizes.set(Some((x, s)));
        s
    }
    /// [`least_corner_det`](crate::quality::solid::least_corner_det) with the free node at
    /// `x`, kept for the position as [`validity_measured`](Self::validity_measured) keeps
    /// its answer (the rule asks it where the node is at every visit: kept from the visit
    /// that moved the node there, `KnownSolids`); from the shape's corners where the shape
    /// was measured at `x` (the rule asks the shape first: [`CornerShapes::least_corner_det`],
    /// within the same tolerance).
    pub fn least_corner_det_measured(&self, x: DVec3) -> Option<(f64, f64)> {
        self.least_det.get_or(x, || {
            let terms = self.terms.borrow();
            if terms.0 == Some(x) {
                terms.1.least_corner_det(self.kind)
            } else {
                crate::quality::solid::least_corner_det(self.kind, self.corners(&self.at(x)))
            }
        })
    }
    /// Whether its measured corner `c`'s tetrahedron holds the free node (the corner or one
    /// of its edge neighbours is the free node's slot).
    #[inline]
    fn moves(&self, c: usize) -> bool {
        let slot = self.slot as usize;
        c == slot || self.kind.row().corner_edges[c].contains(&slot)
    }
    /// [`validity`](crate::quality::solid::validity) with the free node at `x`: the answer
    /// kept for `x` where the drivers measured it there (as gathered, mostly: kept from the
    /// visit that moved the node there, `KnownSolids`); else for a hexahedron exactly at
    /// the first position asked, whose coefficients make its [`ValidBall`]; valid where that
    /// ball holds `x` or its second ball does, else exactly at the first position beyond the
    /// first ball (whose coefficients make the second), then from its [`DetForm`] (made at
    /// the second) where it decides. Every way gives the exact test's answer.
    #[inline]
    pub fn validity_at(&self, x: DVec3) -> Validity {
        if let Some(v) = self.measured.kept(x) {
            return v;
        }
        if self.ball.get().is_none() && self.kind.linear() == VolumeKind::Hex8 {
            // the ball about the first position asked rather than where the node was
            // gathered, which the memo mostly answers: the solve's trials gather there
            let (v, first) =
                ValidBall::validity_and_ball(self.kind, &self.at(x), self.slot as usize);
            if first.is_none() {
                // no ball (not valid there, or beyond the safe scale): the form next
                self.asked_beyond_ball.set(true);
            }
            let _ = self.ball.set(first);
            return v;
        }
        let ball = self.ball.get().copied().flatten();
        if ball.is_some_and(|b| b.holds(x)) || self.second_ball.get().is_some_and(|b| b.holds(x)) {
            // the form is made only where the balls do not decide
            return Validity::Valid;
        }
        if self.det.get().is_none() && !self.asked_beyond_ball.replace(true) {
            // the first position beyond the ball: exactly (a form pays from the second), and
            // the coefficients taken there make the second ball
            let (v, second) =
                ValidBall::validity_and_ball(self.kind, &self.at(x), self.slot as usize);
            self.second_ball.set(second);
            return v;
        }
        let form = self
            .det
            .get_or_init(|| DetForm::of(self.kind, &self.pts, self.slot as usize));
        self.validity_by(None, form.as_ref(), x)
    }
    /// Its free node's position as gathered (then as the driver moves it).
    #[inline]
    pub fn x(&self) -> DVec3 {
        self.pts[self.slot as usize]
    }
    /// Its corners with the free node at `x`.
    #[inline]
    pub fn at(&self, x: DVec3) -> [DVec3; 8] {
        let mut p = self.pts;
        p[self.slot as usize] = x;
        p
    }
    /// Its first [`VolumeKind::corners`] corners of `p`.
    #[inline]
    pub fn corners<'a>(&self, p: &'a [DVec3; 8]) -> &'a [DVec3] {
        &p[..self.kind.corners()]
    }
}

/// The star of a free node of a volume mesh: the corners of its elements that it moves
/// ([`StarCorner`]), and the elements other than tetrahedra whole ([`StarSolid`]),
/// gathered once per visit (reusable scratch buffers, as the planar
/// [`Star`](crate::objective::Star)).
#[derive(Clone, Debug)]
pub struct CornerStar {
    /// The free node.
    pub node: u32,
    /// Its position (when gathered, then as the driver moves it).
    pub x0: DVec3,
    pub tets: Vec<StarCorner>,
    /// The elements that are not tetrahedra (empty in a mesh of tetrahedra).
    pub elements: Vec<StarSolid>,
    /// Where the free node was gathered while the corners' forms wait to be worked out
    /// ([`complete_forms`](Self::complete_forms)); `None` when they are.
    pub forms_pending_at: Option<DVec3>,
    /// What the stars gathered before measured of their elements other than tetrahedra.
    pub(crate) known: KnownSolids,
    /// The tetrahedra's measures at the positions the drivers asked last.
    pub(crate) tet_memo: std::cell::RefCell<TetMeasureMemo>,
    /// Per corner, where the mesh has targets other than the ideal
    /// ([`VolumeMesh::target_nodes`](crate::volume::VolumeMesh::target_nodes); empty
    /// otherwise): the reference its target gives ([`crate::target::solid_reference`]).
    pub targets: Vec<CornerReference>,
    /// The tangent the free node slides in ([`Tangent::Free`](crate::volume::Tangent)
    /// unless it slides on the boundary).
    pub tangent: crate::volume::Tangent,
}

impl Default for CornerStar {
    /// An empty star, until one is gathered.
    fn default() -> Self {
        CornerStar::of_tets(DVec3::ZERO, Vec::new())
    }
}

impl CornerStar {
    /// The power of two that brings the star near unit size where it is far from it
    /// ([`crate::numeric::unit_factor`]), 1 otherwise: the frame the acceptance rule sums
    /// its elements' inversions in, so determinants of coordinates near 2^±520 do not leave
    /// the doubles (issue 61). The sums are compared only within the star.
    pub fn frame(&self) -> f64 {
        crate::numeric::unit_factor(crate::objective::NodeStar::size(self)).unwrap_or(1.0)
    }

    /// A star of tetrahedra (each with the free node first).
    pub fn of_tets(x0: DVec3, tets: Vec<StarCorner>) -> Self {
        CornerStar {
            node: 0,
            x0,
            tets,
            elements: Vec::new(),
            forms_pending_at: None,
            known: KnownSolids::default(),
            tet_memo: Default::default(),
            targets: Vec::new(),
            tangent: crate::volume::Tangent::Free,
        }
    }
    /// The reference W of a tetrahedron's corners, the equilateral tetrahedron's (every
    /// kind of tetrahedron's).
    #[inline]
    pub fn reference(&self) -> &'static CornerReference {
        &EQUILATERAL_TET
    }
    /// The reference corner `i` is measured against: its target's where the star has
    /// targets ([`targets`](Self::targets)), else its kind's.
    #[inline(always)]
    pub fn reference_of(&self, i: usize) -> &CornerReference {
        match self.targets.get(i) {
            Some(r) => r,
            None => self.tets[i].reference,
        }
    }
    /// Whether its corners have targets other than the ideal.
    #[inline(always)]
    pub fn targeted(&self) -> bool {
        !self.targets.is_empty()
    }
    /// Works out the corners' forms if they wait ([`StarCorner::pending`]), each from its
    /// corners with the free node where it was gathered, as a gather that makes them does.
    pub fn complete_forms(&mut self) {
        if let Some(x) = self.forms_pending_at.take() {
            for (i, t) in self.tets.iter_mut().enumerate() {
                let mut p = t.pts;
                p[0] = x;
                t.form = CornerForm::of(&p, self.targets.get(i).unwrap_or(t.reference));
            }
        }
    }
    /// Makes the `n`-th corner (`n` at most their number) one of `element` against
    /// `reference`, its form not worked out ([`StarCorner::pending`]), and returns its
    /// corners to fill. A corner already there is overwritten in place, its form marked
    /// ([`CornerForm::mark_pending`]) rather than written whole: a gather keeps the last
    /// star's corners and truncates them after.
    #[inline]
    pub(crate) fn put_corner(
        &mut self,
        n: usize,
        element: u32,
        reference: &'static CornerReference,
        simplex: bool,
    ) -> &mut [DVec3; 4] {
        Self::corner_in(&mut self.tets, n, element, reference, simplex)
    }
    /// [`put_corner`](Self::put_corner) of `tets`.
    #[inline]
    fn corner_in<'a>(
        tets: &'a mut Vec<StarCorner>,
        n: usize,
        element: u32,
        reference: &'static CornerReference,
        simplex: bool,
    ) -> &'a mut [DVec3; 4] {
        if n == tets.len() {
            tets.push(StarCorner::pending(
                element,
                [DVec3::ZERO; 4],
                reference,
                simplex,
            ));
        } else {
            let t = &mut tets[n];
            (t.element, t.reference, t.simplex) = (element, reference, simplex);
            t.form.mark_pending();
        }
        &mut tets[n].pts
    }
    /// Makes the `n`-th corner ([`put_corner`](Self::put_corner)) the tetrahedron `tuple`,
    /// `(c, a, b, d)` by local corners, of the `solid`-th element other than a tetrahedron
    /// ([`put_solid`](Self::put_solid), its corners filled), reordered to put the free
    /// node's place `s` in it first ([`WITH_FIRST`](crate::mesh::WITH_FIRST)), against `reference`.
    #[inline]
    pub(crate) fn put_corner_of_solid(
        &mut self,
        n: usize,
        solid: usize,
        reference: &'static CornerReference,
        tuple: [usize; 4],
        s: usize,
    ) {
        let e = &self.elements[solid];
        let pts = Self::corner_in(&mut self.tets, n, e.element, reference, false);
        for (p, &j) in pts.iter_mut().zip(&crate::mesh::WITH_FIRST[s]) {
            *p = e.pts[tuple[j]];
        }
    }
    /// Keeps what this star's elements other than tetrahedra measured with the free node at
    /// `x` (where the node now is in the mesh, of `elements` elements) for the stars
    /// gathered next ([`KnownSolids`]).
    pub(crate) fn keep_known(&mut self, x: DVec3, elements: usize) {
        for e in &self.elements {
            self.known.keep(e, x, elements);
        }
    }
    /// Whether `element` of `kind` (other than a tetrahedron) is known valid at `corners`,
    /// bit for bit ([`KnownSolids`]).
    pub(crate) fn known_valid_solid(
        &self,
        element: u32,
        kind: VolumeKind,
        corners: &[DVec3],
    ) -> bool {
        self.known.valid_at(element, kind, corners)
    }
    /// Makes `StarSolid::new(element, kind, slot, ·)` the `n`-th element other than a
    /// tetrahedron (`n` at most their number), and returns its corners to fill: its memos
    /// start with what is known of it once they are filled ([`recall_solid`](Self::recall_solid)).
    /// An element already there is overwritten in place: a gather keeps the last star's
    /// elements and truncates them after, as a solid (some 1.4 kB with its lazy forms) is
    /// costly to move, and its corners are written where they stay (put together on the
    /// stack and copied, they were read back in other widths than written, which stalls).
    #[inline]
    pub(crate) fn put_solid(
        &mut self,
        n: usize,
        element: u32,
        kind: VolumeKind,
        slot: u8,
    ) -> &mut [DVec3; 8] {
        match self.elements.get_mut(n) {
            Some(e) => e.reset(element, kind, slot),
            None => self
                .elements
                .push(StarSolid::new(element, kind, slot, [DVec3::ZERO; 8])),
        }
        &mut self.elements[n].pts
    }
    /// Starts the `n`-th element's memos with what is known of it at its corners now
    /// ([`KnownSolids`]).
    #[inline]
    pub(crate) fn recall_solid(&self, n: usize) {
        self.known.recall(&self.elements[n]);
    }
    /// Whether every element is a tetrahedron measured against the ideal: then every
    /// corner is measured against [`reference`](Self::reference), which the measures see
    /// as a constant.
    #[inline]
    pub fn only_tets(&self) -> bool {
        self.elements.is_empty() && self.targets.is_empty()
    }
}

impl NodeStar for CornerStar {
    type Point = DVec3;
    #[inline]
    fn len(&self) -> usize {
        self.tets.len()
    }
    /// The mean length of the edges from the free node to the other corners, at `x0`;
    /// where their squares leave the doubles (beyond 2^±400), each taken without them
    /// (halved before summing), so a star at 2^±600 still has its size and is solved in
    /// its own frame, as a planar star is (issue 61).
    fn size(&self) -> f64 {
        if self.tets.is_empty() {
            return 0.0;
        }
        let sum: f64 = self
            .tets
            .iter()
            .map(|t| t.pts[1..].iter().map(|p| p.distance(self.x0)).sum::<f64>())
            .sum();
        let plain = sum / (3 * self.tets.len()) as f64;
        if plain.is_finite() && (2f64.powi(-400)..=2f64.powi(400)).contains(&plain) {
            return plain;
        }
        let robust = |v: DVec3| {
            let m = v.abs().max_element();
            if m == 0.0 || !m.is_finite() {
                m
            } else {
                m * (v / m).length()
            }
        };
        let half: f64 = self
            .tets
            .iter()
            .map(|t| {
                t.pts[1..]
                    .iter()
                    .map(|p| 0.5 * robust(*p - self.x0))
                    .sum::<f64>()
            })
            .sum();
        half / (1.5 * self.tets.len() as f64)
    }
    fn scaled(&self, f: f64) -> Self {
        let mut s = self.clone();
        s.complete_forms();
        s.tet_memo.get_mut().clear();
        s.x0 *= f;
        for (i, t) in s.tets.iter_mut().enumerate() {
            // the form from where the star in mesh units took it (its origin), so both
            // read a position with the same rounding (issue 61: a form taken from where a
            // Laplacian move left the node read the last bits otherwise)
            let mut q = t.pts;
            let origin = t.form.origin();
            if origin.is_finite() {
                q[0] = origin;
            }
            for p in &mut t.pts {
                *p *= f;
            }
            t.form = CornerForm::of(&q.map(|p| p * f), s.targets.get(i).unwrap_or(t.reference));
        }
        for e in &mut s.elements {
            for p in &mut e.pts {
                *p *= f;
            }
            e.det = std::cell::OnceCell::new();
            e.ball = std::cell::OnceCell::new();
            e.second_ball = std::cell::Cell::new(None);
            e.measured = PositionMemo::default();
            e.shaped = PositionMemo::default();
            e.terms.get_mut().0 = None;
            e.least_det = PositionMemo::default();
        }
        s
    }
}
