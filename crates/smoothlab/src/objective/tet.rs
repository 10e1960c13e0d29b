//! The objectives of one free node of a tetrahedral mesh, over its star of tetrahedra:
//! the planar objectives carried to solids, by the same command-line names
//! ([`ObjectiveKind`]), behind the same [`Objective`] trait, so the same solvers and
//! drivers run them ([`tet_objective`]). This is the 3D registry: [`tet_form`] gives a
//! kind's form on tetrahedra, `None` for a kind that is planar only (the command line and
//! the page then refuse it on a volume, [`tet_objective`]'s message).
//!
//! | kind | goal | terms, per tetrahedron of the star |
//! |---|---|---|
//! | `old` | max-min | the mean ratio `q` (the 3D shape measure Chen's α generalises) |
//! | `sine` | max-min | the signed sine of each of the six dihedral angles — Freitag 1997 |
//! | `new` | sum | `(1 − q_δ)² + k1·η_δ²`, the mean ratio with Escobar et al.'s regularised determinant — Chen's form carried to solids |
//! | `condition` | sum | κ², Knupp's condition number against the corner's reference W (the equilateral tetrahedron) |
//! | `condition-max` | max-min | −κ |
//! | `untangle` | sum | Knupp's `(|6V − β| − (6V − β))²`, with the planar shift β |
//! | `untangle-mindet` | max-min | 6V, the Jacobian determinant |
//!
//! Every term is a function of the tetrahedron's four corners with the free node first
//! (the star keeps each tetrahedron in an even permutation of its corners, so its volume
//! keeps its sign: [`crate::quality::tet::with_first`]), and its gradient is analytic. The
//! measures that weigh a corner by its ideal shape take the star's reference
//! ([`CornerStar::reference`]: the mesh's element kind's W, computed once per kind).
//! The formulas, in one notation: `docs/formulas.md` §8.

use glam::{DMat3, DVec3};

use super::{Goal, NodeStar, Objective, ObjectiveKind, Term, BARRIER_EPSILON, BARRIER_WEIGHT, CONDITION_BARRIER};
use crate::error::{Error, Result};
use crate::mesh::VolumeKind;
use crate::quality::solid::{scaled_jacobian_grad0, validity, CornerShapes, CornerSizes, DetForm, ValidBall, Validity};
use crate::quality::tet::{self as q3, outer, CornerForm, CornerReference, WeightedJacobian, EQUILATERAL_TET};

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
    pub fn new(element: u32, pts: [DVec3; 4], reference: &'static CornerReference, simplex: bool) -> Self {
        StarCorner { element, pts, reference, simplex, form: CornerForm::of(&pts, reference) }
    }
    /// [`new`](Self::new) with its form [`CornerForm::PENDING`], for a star the drivers only
    /// measure unless they optimise it ([`CornerStar::complete_forms`]).
    pub fn pending(element: u32, pts: [DVec3; 4], reference: &'static CornerReference, simplex: bool) -> Self {
        StarCorner { element, pts, reference, simplex, form: CornerForm::PENDING }
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
    /// [`q3::is_inverted`] with the free node at `x`, from the form where it decides.
    #[inline]
    pub fn inverted_at(&self, x: DVec3) -> bool {
        self.form.inverted_at(x, self.reference).unwrap_or_else(|| q3::is_inverted(&self.at(x)))
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
    measured: PositionMemo<Validity>,
    shaped: PositionMemo<f64>,
    /// The shape's terms at the last position it was measured at: a corner whose
    /// tetrahedron does not hold the free node keeps its term wherever the node goes.
    /// The position (`None` before any) and the terms there, borrowed and copied field by
    /// field ([`CornerShapes::copy_from`]) rather than copied whole: some 140 bytes, read
    /// at every shape, kept and recalled at every gather.
    terms: std::cell::RefCell<(Option<DVec3>, CornerShapes)>,
    /// The corners' sizes at the last position they were measured at, as `terms`.
    sizes: std::cell::Cell<Option<(DVec3, CornerSizes)>>,
    /// The least corner determinant with its tolerance (the acceptance rule's size screen,
    /// [`least_corner_det`](crate::quality::solid::least_corner_det)) at the last two
    /// positions asked, as `measured`.
    least_det: PositionMemo<Option<(f64, f64)>>,
}

/// A measure of a star's element kept for the last two positions of the free node asked:
/// the drivers ask the same two (as gathered, and the move's) in the smart Laplacian's test
/// and again in the acceptance rule.
#[derive(Clone, Debug, PartialEq)]
pub struct PositionMemo<T: Copy>([std::cell::Cell<Option<(DVec3, T)>>; 2]);

impl<T: Copy> Default for PositionMemo<T> {
    fn default() -> Self {
        PositionMemo([std::cell::Cell::new(None), std::cell::Cell::new(None)])
    }
}

impl<T: Copy> PositionMemo<T> {
    /// The value kept for `x`, else `measure()`, kept (in the first place while it is
    /// empty, then in the second).
    #[inline]
    pub fn get_or(&self, x: DVec3, measure: impl FnOnce() -> T) -> T {
        for m in &self.0 {
            if let Some((at, v)) = m.get() {
                if at == x {
                    return v;
                }
            }
        }
        let v = measure();
        let slot = if self.0[0].get().is_none() { 0 } else { 1 };
        self.0[slot].set(Some((x, v)));
        v
    }
    /// The value kept for `x`, if any.
    #[inline]
    pub fn kept(&self, x: DVec3) -> Option<T> {
        self.0.iter().find_map(|m| m.get().filter(|&(at, _)| at == x).map(|(_, v)| v))
    }
    /// Keeps `v` for `x` in the first place (a memo just made, before any question).
    #[inline]
    fn start_with(&self, x: DVec3, v: T) {
        self.0[0].set(Some((x, v)));
    }
}

/// The validity and shape (with the shape's terms, [`CornerShapes`], and the least corner
/// determinant the acceptance rule screens the size with) of the stars' elements
/// other than tetrahedra, kept from visit to visit: each as the element's last star left
/// it, with the corners it was measured at.
/// A star gathered later starts its element's [`PositionMemo`]s with them where the corners
/// are still those, bit for bit (a neighbour's visit that moved nothing of the element, or
/// the visit that moved it: its measures at the new position), so an element is not
/// measured again at a position it was measured at. Both measures are functions of the
/// kind and the corners alone, so an answer kept is the answer measuring would give.
///
/// Direct-mapped by element number, at most [`KnownSolids::MAX_SLOTS`] slots of 376 bytes
/// (some 25 MB of a mesh of many elements other than tetrahedra), none for a mesh of
/// tetrahedra. A copy starts empty: it is a cache.
#[derive(Default)]
pub(crate) struct KnownSolids {
    slots: Vec<KnownSolid>,
}

// the slot's size that `KnownSolids` states
const _: () = assert!(std::mem::size_of::<KnownSolid>() == 376);

#[derive(Clone, Copy)]
struct KnownSolid {
    element: u32,
    kind: VolumeKind,
    corners: [DVec3; 8],
    validity: Option<Validity>,
    shape: Option<f64>,
    /// The shape's terms, where `has_terms` (a flag beside them rather than an `Option`, so
    /// that they are copied in place: [`CornerShapes::copy_from`]).
    has_terms: bool,
    terms: CornerShapes,
    least_det: Option<Option<(f64, f64)>>,
}

impl KnownSolid {
    const EMPTY: KnownSolid = KnownSolid {
        element: u32::MAX,
        kind: VolumeKind::Tet4,
        corners: [DVec3::ZERO; 8],
        validity: None,
        shape: None,
        has_terms: false,
        terms: CornerShapes::NONE,
        least_det: None,
    };
    /// Whether this slot holds `element` of `kind` at `corners`, bit for bit.
    fn holds(&self, element: u32, kind: VolumeKind, corners: &[DVec3]) -> bool {
        self.element == element && self.kind == kind && self.corners.iter().zip(corners).all(|(a, b)| same_bits(a, b))
    }
    /// [`holds`](Self::holds) of `e` with its free node at `x` (its corners compared where
    /// they are, not copied).
    fn holds_moved(&self, e: &StarSolid, x: DVec3) -> bool {
        let slot = e.slot as usize;
        self.element == e.element
            && self.kind == e.kind
            && self.corners.iter().zip(e.corners(&e.pts)).enumerate().all(|(j, (a, b))| same_bits(a, if j == slot { &x } else { b }))
    }
}

/// Whether `a` and `b` are the same bits.
#[inline]
fn same_bits(a: &DVec3, b: &DVec3) -> bool {
    let bits = |p: &DVec3| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()];
    bits(a) == bits(b)
}

impl Clone for KnownSolids {
    fn clone(&self) -> Self {
        KnownSolids::default()
    }
}

impl std::fmt::Debug for KnownSolids {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "KnownSolids({} slots)", self.slots.len())
    }
}

impl KnownSolids {
    /// The most slots kept.
    pub const MAX_SLOTS: usize = 1 << 16;

    /// The slot of `element` (direct-mapped: its number modulo the power of two of slots).
    #[inline]
    fn slot(&self, element: u32) -> usize {
        element as usize & self.slots.len().wrapping_sub(1)
    }

    /// Starts `e`'s memos with what is known of it at its corners now.
    fn recall(&self, e: &StarSolid) {
        let Some(k) = self.slots.get(self.slot(e.element)) else { return };
        if k.holds(e.element, e.kind, e.corners(&e.pts)) {
            let x = e.x();
            if let Some(v) = k.validity {
                e.measured.start_with(x, v);
            }
            if let Some(q) = k.shape {
                e.shaped.start_with(x, q);
            }
            let mut terms = e.terms.borrow_mut();
            terms.0 = k.has_terms.then_some(x);
            if k.has_terms {
                terms.1.copy_from(&k.terms);
            }
            if let Some(d) = k.least_det {
                e.least_det.start_with(x, d);
            }
        }
    }

    /// Whether `element` of `kind` was measured valid at `corners`, bit for bit.
    fn valid_at(&self, element: u32, kind: VolumeKind, corners: &[DVec3]) -> bool {
        self.slots.get(self.slot(element)).is_some_and(|k| k.validity == Some(Validity::Valid) && k.holds(element, kind, corners))
    }

    /// Keeps what `e`'s memos know of it with its free node at `x`, in a mesh of
    /// `elements` elements.
    fn keep(&mut self, e: &StarSolid, x: DVec3, elements: usize) {
        let (validity, shape) = (e.measured.kept(x), e.shaped.kept(x));
        let terms = e.terms.borrow();
        let terms = (terms.0 == Some(x)).then_some(&terms.1);
        let least_det = e.least_det.kept(x);
        if validity.is_none() && shape.is_none() {
            return;
        }
        let want = elements.next_power_of_two().min(Self::MAX_SLOTS);
        if self.slots.len() < want {
            // the slots move with the length: start again (once a mesh)
            self.slots.clear();
            self.slots.resize(want, KnownSolid::EMPTY);
        }
        let i = self.slot(e.element);
        let k = &mut self.slots[i];
        if k.holds_moved(e, x) {
            k.validity = validity.or(k.validity);
            k.shape = shape.or(k.shape);
            if let Some(t) = terms {
                k.has_terms = true;
                k.terms.copy_from(t);
            }
            k.least_det = least_det.or(k.least_det);
        } else {
            // field by field in place (a whole slot put together first is one more copy);
            // the corners past the kind's are not read
            (k.element, k.kind) = (e.element, e.kind);
            k.corners = e.pts;
            k.corners[e.slot as usize] = x;
            (k.validity, k.shape, k.has_terms, k.least_det) = (validity, shape, terms.is_some(), least_det);
            if let Some(t) = terms {
                k.terms.copy_from(t);
            }
        }
    }
}

/// The measures of a star's tetrahedra (the corners that are whole elements, in the
/// star's order) that the smart Laplacian's test and the acceptance rule read: the mean
/// ratio's parts ([`q3::MeanRatioParts`]) and the rule's other measures
/// ([`q3::TetRuleMeasures`]), with the free node at up to two positions. The test asks
/// where the node is and the centroid, and the rule that follows asks the same two
/// positions again (after an optimisation, where the node is and where the solve ended).
/// Each is a function of the corners and the position alone, so a measure kept is the
/// measure taking it would give, bit for bit; a gather forgets them
/// ([`clear`](Self::clear)).
#[derive(Clone, Debug, Default)]
pub(crate) struct TetMeasures {
    /// The positions held (their bits), and which of the two was asked last.
    at: [Option<[u64; 3]>; 2],
    last: usize,
    measures: [Vec<(q3::MeanRatioParts, q3::TetRuleMeasures)>; 2],
}

impl TetMeasures {
    /// Forgets the positions held (the star's corners are gathered anew).
    pub(crate) fn clear(&mut self) {
        self.at = [None, None];
    }
    /// Which of the two holds the measures of `tets`' tetrahedra with the free node at
    /// `x`, taken against `r` where not held (in place of the position asked less
    /// recently).
    pub(crate) fn slot(&mut self, tets: &[StarCorner], x: DVec3, r: &CornerReference) -> usize {
        let key = [x.x.to_bits(), x.y.to_bits(), x.z.to_bits()];
        let i = match self.at.iter().position(|&a| a == Some(key)) {
            Some(i) => i,
            None => {
                let i = 1 - self.last;
                let measures = &mut self.measures[i];
                measures.clear();
                for t in tets.iter().filter(|t| t.simplex) {
                    let p = t.at(x);
                    measures.push((q3::MeanRatioParts::of(&p, r), q3::TetRuleMeasures::of(&p)));
                }
                self.at[i] = Some(key);
                i
            }
        };
        self.last = i;
        i
    }
    /// The measures held in `slot`.
    #[inline]
    pub(crate) fn measures(&self, slot: usize) -> &[(q3::MeanRatioParts, q3::TetRuleMeasures)] {
        &self.measures[slot]
    }
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
        self.measured.get_or(x, || self.validity_by(self.ball.get().and_then(|b| b.as_ref()), self.det.get().and_then(|f| f.as_ref()), x))
    }
    /// The validity at `x`: valid where `ball` holds it, else from `form` where it decides,
    /// else exactly.
    #[inline]
    fn validity_by(&self, ball: Option<&ValidBall>, form: Option<&DetForm>, x: DVec3) -> Validity {
        if ball.is_some_and(|b| b.holds(x)) || self.second_ball.get().is_some_and(|b| b.holds(x)) {
            return Validity::Valid;
        }
        form.and_then(|d| d.validity_at(x)).unwrap_or_else(|| validity(self.kind, self.corners(&self.at(x))))
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
                CornerShapes::of(self.kind, corners, |c| (kept.0.is_some() && !self.moves(c)).then(|| kept.1.corner(c)))
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
        let s = CornerSizes::of(self.kind, self.corners(&p), |c| kept.filter(|_| !self.moves(c)).map(|(_, s)| s.of_kind(self.kind)[c]));
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
            let (v, first) = ValidBall::validity_and_ball(self.kind, &self.at(x), self.slot as usize);
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
            let (v, second) = ValidBall::validity_and_ball(self.kind, &self.at(x), self.slot as usize);
            self.second_ball.set(second);
            return v;
        }
        let form = self.det.get_or_init(|| DetForm::of(self.kind, &self.pts, self.slot as usize));
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
/// [`Star`](super::Star)).
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
    pub(crate) tet_measures: std::cell::RefCell<TetMeasures>,
}

impl Default for CornerStar {
    /// An empty star, until one is gathered.
    fn default() -> Self {
        CornerStar { node: 0, x0: DVec3::ZERO, tets: Vec::new(), elements: Vec::new(), forms_pending_at: None, known: KnownSolids::default(), tet_measures: Default::default() }
    }
}

impl CornerStar {
    /// A star of tetrahedra (each with the free node first).
    pub fn of_tets(x0: DVec3, tets: Vec<StarCorner>) -> Self {
        CornerStar { node: 0, x0, tets, elements: Vec::new(), forms_pending_at: None, known: KnownSolids::default(), tet_measures: Default::default() }
    }
    /// The reference W of a tetrahedron's corners, the equilateral tetrahedron's (every
    /// kind of tetrahedron's).
    #[inline]
    pub fn reference(&self) -> &'static CornerReference {
        &EQUILATERAL_TET
    }
    /// Works out the corners' forms if they wait ([`StarCorner::pending`]), each from its
    /// corners with the free node where it was gathered, as a gather that makes them does.
    pub fn complete_forms(&mut self) {
        if let Some(x) = self.forms_pending_at.take() {
            for t in &mut self.tets {
                let mut p = t.pts;
                p[0] = x;
                t.form = CornerForm::of(&p, t.reference);
            }
        }
    }
    /// Makes the `n`-th corner (`n` at most their number) one of `element` against
    /// `reference`, its form not worked out ([`StarCorner::pending`]), and returns its
    /// corners to fill. A corner already there is overwritten in place, its form marked
    /// ([`CornerForm::mark_pending`]) rather than written whole: a gather keeps the last
    /// star's corners and truncates them after.
    #[inline]
    pub(crate) fn put_corner(&mut self, n: usize, element: u32, reference: &'static CornerReference, simplex: bool) -> &mut [DVec3; 4] {
        Self::corner_in(&mut self.tets, n, element, reference, simplex)
    }
    /// [`put_corner`](Self::put_corner) of `tets`.
    #[inline]
    fn corner_in<'a>(tets: &'a mut Vec<StarCorner>, n: usize, element: u32, reference: &'static CornerReference, simplex: bool) -> &'a mut [DVec3; 4] {
        if n == tets.len() {
            tets.push(StarCorner::pending(element, [DVec3::ZERO; 4], reference, simplex));
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
    pub(crate) fn put_corner_of_solid(&mut self, n: usize, solid: usize, reference: &'static CornerReference, tuple: [usize; 4], s: usize) {
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
    pub(crate) fn known_valid_solid(&self, element: u32, kind: VolumeKind, corners: &[DVec3]) -> bool {
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
    pub(crate) fn put_solid(&mut self, n: usize, element: u32, kind: VolumeKind, slot: u8) -> &mut [DVec3; 8] {
        match self.elements.get_mut(n) {
            Some(e) => e.reset(element, kind, slot),
            None => self.elements.push(StarSolid::new(element, kind, slot, [DVec3::ZERO; 8])),
        }
        &mut self.elements[n].pts
    }
    /// Starts the `n`-th element's memos with what is known of it at its corners now
    /// ([`KnownSolids`]).
    #[inline]
    pub(crate) fn recall_solid(&self, n: usize) {
        self.known.recall(&self.elements[n]);
    }
    /// Whether every element is a tetrahedron: then every corner is measured against
    /// [`reference`](Self::reference), which the measures see as a constant.
    #[inline]
    pub fn only_tets(&self) -> bool {
        self.elements.is_empty()
    }
}

impl NodeStar for CornerStar {
    type Point = DVec3;
    #[inline]
    fn len(&self) -> usize {
        self.tets.len()
    }
    /// The mean length of the edges from the free node to the other corners, at `x0`.
    fn size(&self) -> f64 {
        if self.tets.is_empty() {
            return 0.0;
        }
        let sum: f64 = self.tets.iter().map(|t| t.pts[1..].iter().map(|p| p.distance(self.x0)).sum::<f64>()).sum();
        sum / (3 * self.tets.len()) as f64
    }
    fn scaled(&self, f: f64) -> Self {
        let mut s = self.clone();
        s.complete_forms();
        s.tet_measures.get_mut().clear();
        s.x0 *= f;
        for t in &mut s.tets {
            for p in &mut t.pts {
                *p *= f;
            }
            t.form = CornerForm::of(&t.pts, t.reference);
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

/// The 3D registry: the form of objective `kind` on tetrahedral meshes, with its default
/// parameters, or `None` when `kind` is planar only (a kind added to [`ObjectiveKind`]
/// gets its arm here, `None` until it has a tetrahedral form).
pub fn tet_form(kind: ObjectiveKind) -> Option<TetObjective> {
    Some(match kind {
        ObjectiveKind::Old => TetObjective::MeanRatio,
        ObjectiveKind::Sine => TetObjective::DihedralSine,
        ObjectiveKind::New => TetObjective::Regularised(RegularisedMeanRatio::default()),
        ObjectiveKind::Condition => TetObjective::Condition,
        ObjectiveKind::ConditionMax => TetObjective::ConditionMax,
        ObjectiveKind::Untangle => TetObjective::Untangle { beta: super::UNTANGLE_BETA },
        ObjectiveKind::UntangleMinDet => TetObjective::MinDet,
    })
}

/// The objective kinds that have a form on tetrahedra ([`tet_form`]), in
/// [`ObjectiveKind::ALL`]'s order: the choices on a volume.
pub fn tet_kinds() -> impl Iterator<Item = ObjectiveKind> {
    ObjectiveKind::ALL.into_iter().filter(|&k| tet_form(k).is_some())
}

/// The objective of `kind` for tetrahedral meshes ([`tet_form`]), boxed for the drivers;
/// refused, naming the kinds that have a tetrahedral form, when `kind` is planar only.
pub fn tet_objective(kind: ObjectiveKind) -> Result<Box<dyn Objective<CornerStar> + Send + Sync>> {
    match tet_form(kind) {
        Some(o) => Ok(Box::new(o)),
        None => Err(Error::Invalid(format!(
            "the objective {kind} is planar only: on tetrahedra choose {}",
            tet_kinds().map(|k| k.name()).collect::<Vec<_>>().join(", ")
        ))),
    }
}

/// What the objective of `kind` is on tetrahedra, in a few words for people (the page's
/// headings of a tetrahedral mesh; the planar words are [`ObjectiveKind::describe`]);
/// `None` when `kind` is planar only.
pub fn describe_tet(kind: ObjectiveKind) -> Option<&'static str> {
    tet_form(kind).map(|o| o.describe())
}

/// Chen, Tristano & Kwok's objective carried to solids: per tetrahedron
/// `(1 − q_δ)² + k1·η_δ²` with `η_δ = ‖T‖²_F / (3·h_δ(σ)^{2/3})` and `q_δ = 1/η_δ`, where
/// `T = A·W⁻¹` is the corner Jacobian weighted by the equilateral tetrahedron (Knupp
/// 1999), `σ = det T` and `h_δ(σ) = (σ + √(σ² + 4δ²))/2` the regularised determinant of
/// Escobar, Rodríguez, Montenegro, Montero & González-Yuste (2003), who state exactly this
/// `η_δ` for tetrahedra. With δ = 0 it is the mean ratio `q` (1 for the regular
/// tetrahedron) and a barrier (+∞ where σ ≤ 0); with δ > 0 it is finite and smooth on
/// inverted stars and falls as a fold gets shallower, so one process untangles and
/// smooths — the planar design ([`super::RegularisedBarrier`]) in 3D.
///
/// δ is set once per solve from the star as gathered, as in the plane: with `m = ε·mean|σ|`
/// and `σ_min` the smallest σ, `δ = √(m(m − σ_min))` when `σ_min < m`, else 0 (the worst
/// tetrahedron counts as a valid sliver of determinant `m`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RegularisedMeanRatio {
    /// Weight of `η_δ²`; default the planar [`BARRIER_WEIGHT`].
    pub k1: f64,
    /// Fraction of the star's mean |σ| that sets δ; default the planar [`BARRIER_EPSILON`].
    pub epsilon: f64,
}

impl Default for RegularisedMeanRatio {
    fn default() -> Self {
        RegularisedMeanRatio { k1: BARRIER_WEIGHT, epsilon: BARRIER_EPSILON }
    }
}

/// The objectives of a tetrahedral star (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TetObjective {
    MeanRatio,
    DihedralSine,
    Regularised(RegularisedMeanRatio),
    Condition,
    ConditionMax,
    Untangle { beta: f64 },
    MinDet,
}

impl RegularisedMeanRatio {
    /// δ of a star at its position `x0` (see the type docs).
    pub fn delta(&self, star: &CornerStar) -> f64 {
        if star.tets.is_empty() || self.epsilon == 0.0 {
            return 0.0;
        }
        let (mut sum, mut min) = (0.0, f64::INFINITY);
        for t in &star.tets {
            let s = t.form.sigma_at(star.x0);
            sum += s.abs();
            min = min.min(s);
        }
        let m = self.epsilon * sum / star.tets.len() as f64;
        if m > 0.0 && m.is_finite() && min < m {
            (m * (m - min)).sqrt()
        } else {
            0.0
        }
    }

    /// The term of one corner with its gradient, and its Hessian when `HESSIAN` (the zero
    /// matrix otherwise; the value and gradient are the same arithmetic either way), from
    /// the corner's weighted Jacobian `j` and `∇²F = hf·I` ([`CornerForm`]). With
    /// `L = ln η = ln F − ln 3 − (2/3) ln h` and `dh/dσ = h/s`:
    /// `∇L = ∇F/F − (2/3)·∇σ/s`, and, `∇σ` being constant and `ds/dσ = σ/s`,
    /// `∇²L = (hf/F)·I − ∇F∇Fᵀ/F² + (2/3)(σ/s³)·∇σ∇σᵀ`; the term `g(L) = (1 − e^{−L})² +
    /// k1·e^{2L}` has `g′ = 2(1 − q)q + 2k1η²` and `g″ = −2q + 4q² + 4k1η²`, so its Hessian
    /// is `g″·∇L∇Lᵀ + g′·∇²L` (`docs/formulas.md` §8).
    #[inline(always)]
    fn term<const HESSIAN: bool>(&self, j: &WeightedJacobian, hf: f64, delta: f64) -> (f64, DVec3, DMat3) {
        if j.frob2 <= 0.0 {
            return (0.0, DVec3::ZERO, DMat3::ZERO); // four coincident corners: no shape to penalise
        }
        let (h, s) =
            if delta == 0.0 { (j.sigma.max(0.0), j.sigma) } else { super::regularised_determinant(j.sigma, delta) };
        if h <= 0.0 || h.is_nan() {
            return (f64::INFINITY, DVec3::ZERO, DMat3::ZERO);
        }
        // q = 1/η = 3 h^{2/3} / F, by reciprocals taken once (a division costs several
        // multiplications)
        let c = crate::numeric::cbrt_fast(h);
        let inv_f = 1.0 / j.frob2;
        let q = 3.0 * c * c * inv_f;
        let eta = 1.0 / q;
        let grad_f = j.grad_frob2 * inv_f;
        let two_thirds_inv_s = (2.0 / 3.0) / s;
        let grad_ln = grad_f - j.grad_sigma * two_thirds_inv_s;
        // (1 − q)², ∇q = −q ∇ln η
        let k1_eta2 = self.k1 * eta * eta;
        let value = (1.0 - q) * (1.0 - q) + k1_eta2;
        let d1 = 2.0 * (1.0 - q) * q + 2.0 * k1_eta2;
        if !HESSIAN {
            return (value, d1 * grad_ln, DMat3::ZERO);
        }
        let d2 = -2.0 * q + 4.0 * q * q + 4.0 * k1_eta2;
        // (2/3)·σ/s³
        let curvature = two_thirds_inv_s * j.sigma / (s * s);
        let hess_ln = DMat3::from_diagonal(DVec3::splat(hf * inv_f)) - outer(grad_f, grad_f)
            + outer(j.grad_sigma, j.grad_sigma * curvature);
        (value, d1 * grad_ln, outer(grad_ln, grad_ln * d2) + hess_ln * d1)
    }

    /// The objective over `star` at `x` with its gradient and, when `HESSIAN`, its Hessian:
    /// the sum of [`term`](Self::term) over the star's corners, each read from its form.
    #[inline(always)]
    fn sum<const HESSIAN: bool>(&self, star: &CornerStar, x: DVec3) -> (f64, DVec3, DMat3) {
        debug_assert!(star.forms_pending_at.is_none(), "an objective reads the corners' forms");
        let delta = self.delta(star);
        let (mut value, mut grad, mut hess) = (0.0, DVec3::ZERO, DMat3::ZERO);
        for t in &star.tets {
            let (v, g, h) = self.term::<HESSIAN>(&t.form.at(x), t.form.frob2_hessian_diagonal(), delta);
            value += v;
            grad += g;
            if HESSIAN {
                hess += h;
            }
        }
        (value, grad, hess)
    }
}

impl TetObjective {
    /// What it is, in a few words for people ([`describe_tet`]).
    pub fn describe(&self) -> &'static str {
        match self {
            TetObjective::MeanRatio => "max-min mean ratio (Freitag's ascent)",
            TetObjective::DihedralSine => "max-min dihedral sine (Freitag)",
            TetObjective::Regularised(_) => "Chen, Tristano & Kwok in 3D (Fletcher–Reeves)",
            TetObjective::Condition => "condition number κ, 2-norm (Knupp)",
            TetObjective::ConditionMax => "condition number κ, worst tetrahedron (Knupp)",
            TetObjective::Untangle { .. } => "untangling Σ(|6V| − 6V) (Knupp)",
            TetObjective::MinDet => "max-min 6V (Knupp & Freitag)",
        }
    }

    fn kind(&self) -> ObjectiveKind {
        match self {
            TetObjective::MeanRatio => ObjectiveKind::Old,
            TetObjective::DihedralSine => ObjectiveKind::Sine,
            TetObjective::Regularised(_) => ObjectiveKind::New,
            TetObjective::Condition => ObjectiveKind::Condition,
            TetObjective::ConditionMax => ObjectiveKind::ConditionMax,
            TetObjective::Untangle { .. } => ObjectiveKind::Untangle,
            TetObjective::MinDet => ObjectiveKind::UntangleMinDet,
        }
    }

    /// Calls `emit` with every term at `x`.
    fn visit(&self, star: &CornerStar, x: DVec3, emit: impl FnMut(Term<DVec3>)) {
        debug_assert!(star.forms_pending_at.is_none(), "an objective reads the corners' forms");
        if star.only_tets() {
            // every corner against the one static reference, a constant the measures fold
            self.visit_with(star, x, emit, |_| &EQUILATERAL_TET, |_| true)
        } else {
            self.visit_with(star, x, emit, |t| t.reference, |t| t.simplex)
        }
    }

    /// [`visit`](Self::visit) with each corner's reference and whether it is a whole
    /// tetrahedron.
    #[inline(always)]
    fn visit_with(
        &self,
        star: &CornerStar,
        x: DVec3,
        mut emit: impl FnMut(Term<DVec3>),
        reference: impl Fn(&StarCorner) -> &'static CornerReference,
        simplex: impl Fn(&StarCorner) -> bool,
    ) {
        match *self {
            TetObjective::Regularised(r) => {
                let delta = r.delta(star);
                for (i, t) in star.tets.iter().enumerate() {
                    let (value, grad, _) = r.term::<false>(&t.form.at(x), t.form.frob2_hessian_diagonal(), delta);
                    emit(Term { elem: i as u32, value, grad });
                }
            }
            TetObjective::MeanRatio
            | TetObjective::DihedralSine
            | TetObjective::Condition
            | TetObjective::ConditionMax
            | TetObjective::MinDet => {
                for (i, t) in star.tets.iter().enumerate() {
                    self.corner_terms(t, i as u32, x, reference(t), simplex(t), &mut emit);
                }
            }
            TetObjective::Untangle { beta } => {
                // β: a fraction of the star's mean |6V| as gathered, one constant per solve
                let shift = if star.tets.is_empty() {
                    0.0
                } else {
                    beta * star.tets.iter().map(|t| t.form.volume6_at(star.x0, t.reference).0.abs()).sum::<f64>()
                        / star.tets.len() as f64
                };
                for (i, t) in star.tets.iter().enumerate() {
                    let (det, gdet) = t.form.volume6_at(x, t.reference);
                    let (value, grad) = if det < shift {
                        let d = 2.0 * (shift - det);
                        (d * d, -4.0 * d * gdet)
                    } else {
                        (0.0, DVec3::ZERO)
                    };
                    emit(Term { elem: i as u32, value, grad });
                }
            }
        }
    }
}

impl TetObjective {
    /// The terms of one corner (index `i` in the star) at `x`, for the objectives whose
    /// terms are the corners' own (every kind but `new` and `untangle`, which read the
    /// whole star for δ and β), against reference `r`, `simplex` when it is a whole
    /// tetrahedron.
    #[inline(always)]
    fn corner_terms(&self, t: &StarCorner, i: u32, x: DVec3, r: &CornerReference, simplex: bool, emit: &mut impl FnMut(Term<DVec3>)) {
        match *self {
            TetObjective::MeanRatio => {
                // of the corners themselves, not the form: the max-min ascent follows its
                // active set, which rounding can change (on a tangled mesh, the whole path)
                let (value, grad) = q3::mean_ratio_grad0(&t.at(x), r);
                emit(Term { elem: i, value, grad });
            }
            TetObjective::DihedralSine => {
                if simplex {
                    for (value, grad) in q3::dihedral_sines_grad0(&t.at(x)) {
                        emit(Term { elem: i, value, grad });
                    }
                } else {
                    // a corner of another kind: its scaled Jacobian, the 3D sine of a corner
                    let (value, grad) = scaled_jacobian_grad0(&t.at(x), r);
                    emit(Term { elem: i, value, grad });
                }
            }
            TetObjective::Condition | TetObjective::ConditionMax => {
                let max = matches!(self, TetObjective::ConditionMax);
                let p = t.at(x);
                let (kappa, g) = q3::condition_number_grad0(&p, r);
                // behind the barrier (σ ≤ 0, or κ² beyond it): a huge finite value with
                // zero gradient, as in the plane ([`CONDITION_BARRIER`])
                let valid = q3::signed_volume(&p) > 0.0 && kappa.is_finite() && kappa * kappa < CONDITION_BARRIER;
                let (value, grad) = match (max, valid) {
                    (false, true) => (kappa * kappa, 2.0 * kappa * g),
                    (false, false) => (CONDITION_BARRIER, DVec3::ZERO),
                    (true, true) => (-kappa, -g),
                    (true, false) => (-CONDITION_BARRIER, DVec3::ZERO),
                };
                emit(Term { elem: i, value, grad });
            }
            TetObjective::MinDet => {
                let (value, grad) = t.form.volume6_at(x, t.reference);
                emit(Term { elem: i, value, grad });
            }
            TetObjective::Regularised(_) | TetObjective::Untangle { .. } => unreachable!("read the whole star"),
        }
    }

    /// [`Objective::terms_above`] of a max-min objective: the terms of corner `lead` first,
    /// then the others in the star's order (the lead's as already taken), stopping at the
    /// first that is not above `floor`; the terms pushed are [`Objective::terms`]' own.
    fn max_min_terms_above(&self, star: &CornerStar, x: DVec3, floor: f64, lead: u32, out: &mut Vec<Term<DVec3>>) -> bool {
        out.clear();
        let only_tets = star.only_tets();
        let r = |t: &StarCorner| if only_tets { &EQUILATERAL_TET } else { t.reference };
        let simplex = |t: &StarCorner| only_tets || t.simplex;
        let mut above = true;
        // a corner has at most six terms (a tetrahedron's dihedral sines)
        let (mut lead_terms, mut n) = ([Term { elem: lead, value: 0.0, grad: DVec3::ZERO }; 6], 0);
        if let Some(t) = star.tets.get(lead as usize) {
            // not `<=`: a NaN term is not above
            self.corner_terms(t, lead, x, r(t), simplex(t), &mut |term| {
                above &= term.value > floor;
                lead_terms[n] = term;
                n += 1;
            });
            if !above {
                return false;
            }
        }
        for (i, t) in star.tets.iter().enumerate() {
            if i == lead as usize {
                out.extend_from_slice(&lead_terms[..n]);
                continue;
            }
            self.corner_terms(t, i as u32, x, r(t), simplex(t), &mut |term| {
                above &= term.value > floor;
                out.push(term);
            });
            if !above {
                return false;
            }
        }
        !out.is_empty()
    }
}

impl Objective<CornerStar> for TetObjective {
    fn name(&self) -> &'static str {
        self.kind().name()
    }
    fn goal(&self) -> Goal {
        self.kind().goal()
    }
    fn untangles(&self) -> bool {
        self.kind().untangles()
    }
    fn only_untangles(&self) -> bool {
        self.kind().only_untangles()
    }
    fn terms(&self, star: &CornerStar, x: DVec3, out: &mut Vec<Term<DVec3>>) {
        self.visit(star, x, |t| out.push(t));
    }
    fn value_and_gradient(&self, star: &CornerStar, x: DVec3) -> (f64, DVec3) {
        if let TetObjective::Regularised(r) = self {
            let (v, g, _) = r.sum::<false>(star, x);
            return (v, g);
        }
        let mut fold = super::Fold::new(self.goal());
        self.visit(star, x, |t| fold.add(t));
        fold.finish()
    }
    fn terms_above(&self, star: &CornerStar, x: DVec3, floor: f64, lead: u32, out: &mut Vec<Term<DVec3>>) -> bool {
        if self.goal() != Goal::MaximizeMin {
            out.clear();
            self.terms(star, x, out);
            return !out.is_empty() && out.iter().all(|t| t.value > floor);
        }
        self.max_min_terms_above(star, x, floor, lead, out)
    }
    /// The regularised mean ratio's Hessian (the sum of its corners' terms' Hessians), for Newton's
    /// first trial; `None` for the others.
    fn value_gradient_hessian(&self, star: &CornerStar, x: DVec3) -> Option<(f64, DVec3, DMat3)> {
        match self {
            TetObjective::Regularised(r) => Some(r.sum::<true>(star, x)),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::quality::tet::EQUILATERAL_W;

    use crate::numeric::SplitMix64;

    /// A point uniform in the cube [−1, 1)³.
    fn point(rng: &mut SplitMix64) -> DVec3 {
        let (x, y) = (rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0));
        DVec3::new(x, y, rng.uniform(-1.0, 1.0))
    }

    /// A star of `n` random tetrahedra around `x0` (each with the free node first).
    fn random_star(rng: &mut SplitMix64, n: usize, x0: DVec3) -> CornerStar {
        let tets = (0..n)
            .map(|e| StarCorner::tet(e as u32, [x0, x0 + point(rng), x0 + point(rng), x0 + point(rng)]))
            .collect();
        CornerStar::of_tets(x0, tets)
    }

    /// The regular tetrahedron's star of one element: every objective at its best.
    fn regular_star() -> CornerStar {
        let pts = [DVec3::ZERO, EQUILATERAL_W.x_axis, EQUILATERAL_W.y_axis, EQUILATERAL_W.z_axis];
        CornerStar::of_tets(DVec3::ZERO, vec![StarCorner::tet(0, pts)])
    }

    #[test]
    fn values_on_the_regular_tetrahedron_by_hand() {
        let s = regular_star();
        let v = |k| tet_objective(k).unwrap().value(&s, DVec3::ZERO);
        // q = η = 1: (1 − 1)² + k1·1²
        assert!((v(ObjectiveKind::New) - BARRIER_WEIGHT).abs() < 1e-13);
        assert!((v(ObjectiveKind::Old) - 1.0).abs() < 1e-14);
        assert!((v(ObjectiveKind::Sine) - 2.0 * 2f64.sqrt() / 3.0).abs() < 1e-14);
        assert!((v(ObjectiveKind::Condition) - 9.0).abs() < 1e-12);
        assert!((v(ObjectiveKind::ConditionMax) + 3.0).abs() < 1e-13);
        assert_eq!(v(ObjectiveKind::Untangle), 0.0);
        // 6V = 6/(6√2)
        assert!((v(ObjectiveKind::UntangleMinDet) - 1.0 / 2f64.sqrt()).abs() < 1e-14);
        // the regular apex is a stationary point of the smooth objectives
        for k in [ObjectiveKind::New, ObjectiveKind::Condition] {
            let (_, g) = tet_objective(k).unwrap().value_and_gradient(&s, DVec3::ZERO);
            // a single tetrahedron: moving the apex changes the shape, and the regular
            // one is the best, so the gradient vanishes
            assert!(g.length() < 1e-12, "{k}: {g}");
        }
    }

    #[test]
    fn gradients_agree_with_central_differences() {
        let mut rng = SplitMix64::new(3);
        let h = 1e-6;
        let mut checked = 0;
        for round in 0..80 {
            let x0 = point(&mut rng);
            let star = random_star(&mut rng, 2 + round % 5, x0);
            let tangled = star.tets.iter().any(|t| q3::signed_volume(&t.pts) <= 0.0);
            // steep near a flat tetrahedron: away from those
            if star.tets.iter().any(|t| q3::signed_volume(&t.pts).abs() < 0.02) {
                continue;
            }
            let x = x0 + point(&mut rng) * 0.01;
            for k in tet_kinds() {
                let obj = tet_objective(k).unwrap();
                let mut terms = Vec::new();
                obj.terms(&star, x, &mut terms);
                for (i, t) in terms.iter().enumerate() {
                    if t.value.abs() >= CONDITION_BARRIER || !t.value.is_finite() {
                        continue; // behind a barrier: a constant
                    }
                    let term_at = |y: DVec3| {
                        let mut v = Vec::new();
                        obj.terms(&star, y, &mut v);
                        v[i].value
                    };
                    let mut fd = DVec3::ZERO;
                    for c in 0..3 {
                        let mut e = DVec3::ZERO;
                        e[c] = h;
                        fd[c] = (term_at(x + e) - term_at(x - e)) / (2.0 * h);
                    }
                    let scale = t.grad.length().max(fd.length()).max(1e-3);
                    assert!(
                        (fd - t.grad).length() <= 2e-6 * scale,
                        "{k} term {i} (tangled {tangled}): {} vs {fd}",
                        t.grad
                    );
                    checked += 1;
                }
            }
        }
        assert!(checked > 500, "{checked}");
    }

    /// A star of `n` random corners around `x0`: tetrahedra, and corners of hexahedra
    /// measured against their slots' references (the free node in every slot).
    fn random_mixed_star(rng: &mut SplitMix64, n: usize, x0: DVec3) -> CornerStar {
        let hex = VolumeKind::Hex8.row();
        let tets = (0..n)
            .map(|e| {
                let pts = [x0, x0 + point(rng), x0 + point(rng), x0 + point(rng)];
                match e % 3 {
                    0 => StarCorner::tet(e as u32, pts),
                    k => StarCorner::new(e as u32, pts, &hex.slot_references[(e + k) % 4], false),
                }
            })
            .collect();
        CornerStar::of_tets(x0, tets)
    }

    #[test]
    fn a_solids_shape_and_sizes_keep_the_terms_of_the_corners_that_did_not_move() {
        // an element of every kind other than the tetrahedron with each corner free in
        // turn, its shape, corner sizes and validity asked at a walk of positions:
        // solid_shape's bits and the sizes measured afresh at each, the terms of the corners
        // whose tetrahedra do not hold the free node kept; the guard's validity (kept where
        // the drivers measured it, the ball about the first position asked, the first
        // question beyond it exactly, then the form) the exact test's
        let mut rng = SplitMix64::new(24);
        for kind in [VolumeKind::Hex8, VolumeKind::Wedge6, VolumeKind::Pyramid5] {
            let ideal = kind.row().ideal;
            for slot in 0..kind.corners() {
                let mut pts = [DVec3::ZERO; 8];
                for (p, c) in pts.iter_mut().zip(ideal) {
                    *p = DVec3::from(*c) + point(&mut rng) * 0.1;
                }
                let e = StarSolid::new(0, kind, slot as u8, pts);
                for step in 0..12 {
                    let x = pts[slot] + point(&mut rng) * [0.05, 0.5][step % 2];
                    let mut p = pts;
                    p[slot] = x;
                    let exact = crate::quality::solid::solid_shape(kind, &p[..kind.corners()]);
                    assert_eq!(e.shape_measured(x).to_bits(), exact.to_bits(), "{kind:?} slot {slot} at {x}");
                    let sizes = CornerSizes::of(kind, &p[..kind.corners()], |_| None);
                    assert_eq!(e.sizes_measured(x), sizes, "{kind:?} slot {slot} at {x}");
                    if step % 3 == 2 {
                        // measured by the drivers first: the guard reads it from the memo
                        e.validity_measured(x);
                    }
                    assert_eq!(e.validity_at(x), validity(kind, &p[..kind.corners()]), "{kind:?} slot {slot} at {x}");
                }
            }
        }
    }

    #[test]
    fn forms_give_the_corners_weighted_jacobian_anywhere() {
        let mut rng = SplitMix64::new(21);
        for _ in 0..50 {
            let x0 = point(&mut rng);
            let star = random_mixed_star(&mut rng, 6, x0);
            let x = x0 + point(&mut rng) * 0.3;
            for t in &star.tets {
                let (a, b) = (t.form.at(x), WeightedJacobian::of(&t.at(x), t.reference));
                let close = |u: f64, v: f64| (u - v).abs() <= 1e-13 * (1.0 + v.abs());
                assert!(close(a.frob2, b.frob2) && close(a.sigma, b.sigma), "{a:?} {b:?}");
                assert!((a.grad_frob2 - b.grad_frob2).length() <= 1e-13 * (1.0 + b.grad_frob2.length()));
                assert!((a.grad_sigma - b.grad_sigma).length() <= 1e-13 * (1.0 + b.grad_sigma.length()));
                assert!((a.t - b.t).to_cols_array().iter().all(|d| d.abs() <= 1e-13), "{a:?} {b:?}");
                let v6 = t.form.volume6_at(x, t.reference).0;
                assert!(close(v6, 6.0 * q3::signed_volume(&t.at(x))), "{v6}");
            }
        }
    }

    #[test]
    fn corners_decide_inversion_as_their_tetrahedra_do() {
        // every answer a form gives is is_inverted's, at every scale, and it gives one
        // for most positions
        let mut rng = SplitMix64::new(4);
        let (mut asked, mut decided, mut inverted) = (0, 0, 0);
        for round in 0..300 {
            let scale = [1.0, 1e-4, 1e5][round % 3];
            let x0 = point(&mut rng) * scale;
            for t in random_mixed_star(&mut rng, 3, DVec3::ZERO).tets {
                let t = StarCorner::new(t.element, t.pts.map(|p| x0 + p * scale), t.reference, t.simplex);
                for _ in 0..5 {
                    let x = x0 + point(&mut rng) * scale * rng.uniform(0.0, 2.0);
                    let exact = q3::is_inverted(&t.at(x));
                    if let Some(v) = t.form.inverted_at(x, t.reference) {
                        assert_eq!(v, exact, "{:?} at {x}", t.pts);
                        decided += 1;
                    }
                    asked += 1;
                    inverted += exact as u32;
                }
            }
        }
        assert!(decided * 100 > asked * 99 && inverted * 5 > asked && inverted * 5 < 4 * asked, "{decided} {inverted} of {asked}");
        // beyond the safe scale: left to is_inverted
        let t = StarCorner::tet(0, [DVec3::ZERO, DVec3::X * 1e200, DVec3::Y * 1e200, DVec3::Z * 1e200]);
        assert_eq!(t.form.inverted_at(DVec3::ZERO, t.reference), None);
        assert!(!t.inverted_at(DVec3::ZERO));
    }

    #[test]
    fn terms_above_answers_as_the_terms_do() {
        let mut rng = SplitMix64::new(30);
        let mut stopped = 0;
        for round in 0..60 {
            let x0 = point(&mut rng);
            let star = if round % 2 == 0 { random_star(&mut rng, 5, x0) } else { random_mixed_star(&mut rng, 5, x0) };
            let x = x0 + point(&mut rng) * 0.2;
            for k in tet_kinds() {
                let obj = tet_objective(k).unwrap();
                let mut all = Vec::new();
                obj.terms(&star, x, &mut all);
                let min = all.iter().fold(f64::INFINITY, |m, t| m.min(t.value));
                for floor in [min - 1.0, min, min + 1e-3, f64::NEG_INFINITY] {
                    for lead in [0, 3, 4, 9] {
                        let mut out = Vec::new();
                        let above = obj.terms_above(&star, x, floor, lead, &mut out);
                        assert_eq!(above, all.iter().all(|t| t.value > floor), "{k} floor {floor} lead {lead}");
                        if above {
                            assert_eq!(out, all, "{k}");
                        } else {
                            stopped += 1;
                        }
                    }
                }
            }
        }
        assert!(stopped > 100, "{stopped}");
    }

    #[test]
    fn hessian_of_new_agrees_with_central_differences() {
        let obj = tet_objective(ObjectiveKind::New).unwrap();
        let mut rng = SplitMix64::new(13);
        let (h, mut checked, mut tangled) = (1e-6, 0, 0);
        for round in 0..120 {
            let x0 = point(&mut rng);
            let star = random_mixed_star(&mut rng, 2 + round % 6, x0);
            if star.tets.iter().any(|t| t.form.sigma_at(x0).abs() < 0.05) {
                continue; // steep near a flat corner: away from those
            }
            tangled += star.tets.iter().any(|t| t.form.sigma_at(x0) < 0.0) as u32;
            let x = x0 + point(&mut rng) * 0.01;
            let (v, g, hess) = obj.value_gradient_hessian(&star, x).expect("a Hessian");
            assert_eq!((v, g), obj.value_and_gradient(&star, x));
            // the fold is the sum of the terms, in their order
            let mut terms = Vec::new();
            obj.terms(&star, x, &mut terms);
            assert_eq!(v, terms.iter().fold(0.0, |s, t| s + t.value));
            if !v.is_finite() {
                continue;
            }
            assert!((hess - hess.transpose()).to_cols_array().iter().all(|d| d.abs() <= 1e-9 * (1.0 + hess.abs().to_cols_array().iter().fold(0.0f64, |a, &b| a.max(b)))));
            for c in 0..3 {
                let mut e = DVec3::ZERO;
                e[c] = h;
                let fd = (obj.value_and_gradient(&star, x + e).1 - obj.value_and_gradient(&star, x - e).1) / (2.0 * h);
                let col = hess.col(c);
                assert!((col - fd).length() <= 1e-5 * (1.0 + fd.length()), "column {c}: {col} vs {fd}");
            }
            checked += 1;
        }
        assert!(checked > 60 && tangled > 10, "{checked} {tangled}");
        // the max-min objectives have no Hessian
        assert!(tet_objective(ObjectiveKind::Old).unwrap().value_gradient_hessian(&regular_star(), DVec3::ZERO).is_none());
    }

    #[test]
    fn new_is_finite_on_a_tangled_star_and_a_barrier_on_a_valid_one() {
        let mut rng = SplitMix64::new(9);
        let obj = tet_objective(ObjectiveKind::New).unwrap();
        let mut tangled_seen = 0;
        for _ in 0..50 {
            let x0 = point(&mut rng);
            let star = random_star(&mut rng, 4, x0);
            let inverted = star.tets.iter().filter(|t| q3::signed_volume(&t.pts) <= 0.0).count();
            let (v, g) = obj.value_and_gradient(&star, x0);
            if inverted > 0 {
                tangled_seen += 1;
                assert!(v.is_finite() && g.is_finite(), "{v} {g}");
            } else {
                assert!(v.is_finite() && g.is_finite(), "{v} {g}");
            }
        }
        assert!(tangled_seen > 10, "{tangled_seen}");
        // a known crossing: the regular apex moved through the opposite face
        let s = regular_star();
        let beyond = (EQUILATERAL_W.x_axis + EQUILATERAL_W.y_axis + EQUILATERAL_W.z_axis) / 3.0 * 2.0;
        assert_eq!(obj.value(&s, beyond), f64::INFINITY);
    }

    #[test]
    fn scaled_star_keeps_shape_values() {
        let mut rng = SplitMix64::new(5);
        let star = random_star(&mut rng, 5, DVec3::new(0.1, 0.2, 0.3));
        let f = 2f64.powi(40);
        let big = star.scaled(f);
        assert_eq!(big.size(), star.size() * f);
        for k in [ObjectiveKind::New, ObjectiveKind::Old, ObjectiveKind::Sine, ObjectiveKind::Condition] {
            let (a, b) = (tet_objective(k).unwrap().value(&star, star.x0), tet_objective(k).unwrap().value(&big, big.x0));
            assert!((a - b).abs() <= 1e-12 * a.abs().max(1.0), "{k}: {a} {b}");
        }
    }

    /// The tetrahedra's measures a star keeps for two positions ([`TetMeasures`]) are those
    /// measured afresh: the smart Laplacian's test then the acceptance rule at the same
    /// positions, a third position in place of one, and the star moved there and back (as
    /// a kept move and the rule's regather do), each rule's verdict the same as a fresh
    /// star's; a gather forgets them.
    #[test]
    fn kept_tet_measures_are_the_measures_taken_afresh() {
        use crate::smooth::{DriverStar, ElementScore, Measure, Verdict};
        let mesh = crate::generate::rand3d(300, 4).unwrap();
        // the rule's verdict from every tetrahedron's whole score, measured here
        let fresh = |n: usize, x: DVec3| {
            let mut s = CornerStar::default();
            s.gather_for_measures(&mesh, n);
            let mut v = Verdict::default();
            for t in &s.tets {
                v.add(&ElementScore::tet(&t.pts, &EQUILATERAL_TET, Measure::Shape), &ElementScore::tet(&t.at(x), &EQUILATERAL_TET, Measure::Shape));
            }
            v
        };
        let mut rng = SplitMix64::new(11);
        let (mut star, mut checked, mut moved) = (CornerStar::default(), 0, 0);
        for n in (0..mesh.node_count()).filter(|&n| mesh.is_free(n)) {
            star.gather_for_measures(&mesh, n);
            assert_eq!(star.tet_measures.borrow().at, [None, None], "a gather forgets");
            let x0 = star.x0;
            let h = star.size();
            let mut near = || x0 + h * 0.3 * DVec3::new(rng.next_f64() - 0.5, rng.next_f64() - 0.5, rng.next_f64() - 0.5);
            let (c, x) = (near(), near());
            let accepts = star.smart_accepts(c, Measure::Shape);
            assert_eq!(star.verdict(c, Measure::Shape), fresh(n, c), "node {n}");
            assert_eq!(star.verdict(x, Measure::Shape), fresh(n, x), "node {n}");
            // kept, then put back
            star.restar(c);
            star.restar(x0);
            assert_eq!(star.verdict(c, Measure::Shape), fresh(n, c), "node {n}");
            // what is held is what measuring gives
            let memo = star.tet_measures.borrow();
            assert!(memo.at.iter().all(|a| a.is_some()), "node {n}");
            for (i, at) in memo.at.iter().enumerate().filter_map(|(i, a)| Some((i, (*a)?))) {
                let at = DVec3::new(f64::from_bits(at[0]), f64::from_bits(at[1]), f64::from_bits(at[2]));
                let measured: Vec<_> = star.tets.iter().map(|t| (q3::MeanRatioParts::of(&t.at(at), &EQUILATERAL_TET), q3::TetRuleMeasures::of(&t.at(at)))).collect();
                assert_eq!(memo.measures(i), &measured[..], "node {n}");
            }
            checked += 1;
            moved += accepts as usize;
        }
        assert!(checked > 100 && moved > 0, "{checked} {moved}");
    }

    /// A star's elements other than tetrahedra start with what an earlier star measured of
    /// them ([`KnownSolids`]) exactly where their corners are still those: a neighbour's
    /// star recalls the shared hexahedra, the same numbers as measuring; after a corner
    /// moved, nothing is recalled.
    #[test]
    fn known_solids_are_recalled_only_at_the_corners_measured() {
        use crate::quality::solid::solid_shape;
        use crate::smooth::DriverStar;
        let block = crate::generate::hex_grid(&crate::generate::HexBlock::cube(3)).unwrap();
        let mut mesh = crate::generate::perturb_volume(&block, 0.2, 5).unwrap();
        let free: Vec<usize> = (0..mesh.node_count()).filter(|&n| mesh.is_free(n)).collect();
        let (n, m) = (free[0], *mesh.neighbours(free[0]).iter().find(|&&m| mesh.is_free(m as usize)).unwrap() as usize);
        let exact = |e: &StarSolid| (validity(e.kind, e.corners(&e.pts)), solid_shape(e.kind, e.corners(&e.pts)));
        let mut star = CornerStar::default();
        star.gather_for_measures(&mesh, n);
        let measured: Vec<u32> = star.elements.iter().map(|e| e.element).collect();
        for e in &star.elements {
            assert_eq!(e.shaped.kept(e.x()), None, "a first star knows nothing");
            e.validity_measured(e.x());
            e.shape_measured(e.x());
        }
        // the neighbour's star: the shared elements recalled, the others measured afresh
        star.gather_for_measures(&mesh, m);
        let mut recalled = 0;
        for e in &star.elements {
            let known = (e.measured.kept(e.x()), e.shaped.kept(e.x()));
            if measured.contains(&e.element) {
                let (v, q) = exact(e);
                assert_eq!(known, (Some(v), Some(q)), "element {}", e.element);
                recalled += 1;
            } else {
                assert_eq!(known, (None, None), "element {}", e.element);
            }
        }
        assert!(recalled >= 2, "{recalled}");
        // node n moves (a little): none of its elements is recalled
        let x = mesh.nodes()[n];
        mesh.nodes_mut()[n] = DVec3::new(x.x + 1e-9, x.y, x.z);
        star.gather_for_measures(&mesh, n);
        assert!(star.elements.iter().all(|e| e.measured.kept(e.x()).is_none() && e.shaped.kept(e.x()).is_none()));
    }

    /// What the stars keep of their elements from visit to visit answers as measuring does:
    /// after visits that measure each star where its node is and where it moves, as the
    /// acceptance rule does, an element known valid at its corners now is valid by the exact
    /// test (the untangling sweeps' planning reads it, `DriverStar::known_valid`), one
    /// measured folded is not known valid, and the least corner determinant a star recalls
    /// is the one taken now.
    #[test]
    fn what_is_known_after_visits_is_what_measuring_gives() {
        use crate::quality::solid::least_corner_det;
        use crate::smooth::DriverStar;
        let block = crate::generate::hex_grid(&crate::generate::HexBlock::cube(4)).unwrap();
        // moved by 0.9 mean edge lengths: some hexahedra folded
        let mut mesh = crate::generate::perturb_volume(&block, 0.9, 2).unwrap();
        let mut star = CornerStar::default();
        let free: Vec<usize> = (0..mesh.node_count()).filter(|&n| mesh.is_free(n)).collect();
        for (i, &n) in free.iter().enumerate() {
            star.gather_for_measures(&mesh, n);
            let x = star.x0() + DVec3::new(1e-3, -2e-3, 1.5e-3) * (i % 3) as f64;
            for e in &star.elements {
                for at in [e.x(), x] {
                    e.validity_measured(at);
                    e.least_corner_det_measured(at);
                }
            }
            mesh.nodes_mut()[n] = x;
        }
        // the last star's elements are kept at the next gather
        star.gather_for_measures(&mesh, free[0]);
        let (mut known, mut folded) = (0, 0);
        for e in 0..mesh.element_count() {
            let inverted = mesh.is_inverted(e);
            folded += inverted as usize;
            if star.known_valid(&mesh, e) {
                assert!(!inverted, "element {e} known valid");
                known += 1;
            }
        }
        assert!(known > mesh.element_count() / 2 && folded > 0, "{known} known valid, {folded} folded");
        let mut recalled = 0;
        for &n in &free {
            star.gather_for_measures(&mesh, n);
            for e in &star.elements {
                if let Some(d) = e.least_det.kept(e.x()) {
                    assert_eq!(d, least_corner_det(e.kind, e.corners(&e.pts)), "element {}", e.element);
                    recalled += 1;
                }
            }
        }
        assert!(recalled > 0);
    }
}
