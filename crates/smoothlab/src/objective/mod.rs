//! Objective functions of one free node over its star.
//!
//! Every objective implements [`Objective`]: per-term values with their gradients
//! (one term per star element for most objectives, several for angle-based ones), and
//! how the terms combine — summed and minimised (smooth objectives, solved by
//! Fletcher–Reeves) or their minimum maximised (the non-smooth max-min objectives, solved
//! by Freitag's active-set ascent). Solvers and drivers see only this trait, so adding
//! an objective never touches them.
//!
//! The objectives, one per file, named as on the command line ([`ObjectiveKind`]):
//!
//! | kind | type | goal | terms |
//! |---|---|---|---|
//! | `old` | [`MaxMinShape`] | max-min | α (triangles) / β (quads) per element — Chen et al.'s previous method |
//! | `sine` | [`MaxMinSine`] | max-min | sine of every corner angle of the star — Freitag 1997 |
//! | `new` | [`ChenTristanoKwok`] | sum | `(1 − α)²` + angle penalty per element — Chen et al. 2003, eqs. (3)–(9); the penalty ([`Penalty`]): a regularised barrier (default) or the first adjusted-angle design |
//! | `condition` | [`ConditionNumber`] (2-norm) | sum | κ² per moving corner — Knupp 1999 |
//! | `condition-max` | [`ConditionNumber`] (∞-norm) | max-min | −κ per moving corner |
//! | `untangle` | [`Untangle`] | sum | `|det| − det` per moving corner — Knupp 1999, §2.7 |
//! | `untangle-mindet` | [`MaxMinDet`] | max-min | det per moving corner — Knupp & Freitag |
//!
//! Every gradient is analytic: the chain rule through the corner edge vectors
//! (see `corners.rs`), with the metric partials from [`crate::quality`]. Quadratic
//! elements are handled through [`StarElement::at`] (mid-side nodes follow) and the edge
//! end tangents of [`crate::quality::corner_edges`].
//!
//! A "moving corner" is a corner of a star element whose edge vectors change with the
//! free node: for a linear triangle all three (they share one area and, with Knupp's
//! ideal weight, one κ), for a quad the free corner and its two neighbours, so a
//! triangle and a quad contribute three corner terms each.

use glam::{DMat2, DVec2};

use crate::mesh::{ElementKind, Mesh, NodeRole};

mod condition;
mod corners;
mod new;
mod old;
mod point;
mod sine;
#[cfg(test)]
mod target_tests;
#[cfg(test)]
pub(crate) mod testing;
mod solid;
mod untangle;

pub use condition::{ConditionNumber, Norm, CONDITION_BARRIER};
pub use new::{
    adjusted_angle, regularised_determinant, AnglePenalty, ChenTristanoKwok, Penalty, PenaltyLength,
    RegularisedBarrier, BARRIER_EPSILON, BARRIER_WEIGHT, EQUILATERAL_PENALTY,
};
pub use old::{CornerTerm, MaxMinShape};
pub use point::{NodeStar, Point};
pub use sine::MaxMinSine;
pub use solid::{describe_solid, solid_form, solid_kinds, solid_objective, CornerStar, RegularisedMeanRatio, StarCorner, StarSolid, SolidObjective};
pub(crate) use solid::framed;
pub use untangle::{MaxMinDet, Untangle, UNTANGLE_BETA};

enum_with_all! {
    /// The objectives smoothlab offers, by their command-line names (serde uses the same names).
    #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
    #[serde(rename_all = "kebab-case")]
    pub enum ObjectiveKind {
        /// `old`: maximise the minimum α/β of the star (Chen et al.'s previous method).
        #[serde(rename = "old")]
        MaxMinShape,
        /// `sine`: maximise the minimum sine of the star's angles (Freitag 1997).
        Sine,
        /// `new`: Chen, Tristano & Kwok's smooth objective (α plus an angle penalty).
        #[serde(rename = "new")]
        SmoothShape,
        /// `condition`: Knupp's condition number, 2-norm (sum of κ² — the average element).
        Condition,
        /// `condition-max`: Knupp's condition number, ∞-norm (the worst corner).
        ConditionMax,
        /// `untangle`: Knupp's Σ(|det| − det), zero once every corner is valid.
        Untangle,
        /// `untangle-mindet`: maximise the minimum corner det (Knupp & Freitag).
        #[serde(rename = "untangle-mindet")]
        UntangleMinDet,
    }
}

impl ObjectiveKind {
    /// The command-line name.
    pub fn name(self) -> &'static str {
        match self {
            ObjectiveKind::MaxMinShape => "old",
            ObjectiveKind::Sine => "sine",
            ObjectiveKind::SmoothShape => "new",
            ObjectiveKind::Condition => "condition",
            ObjectiveKind::ConditionMax => "condition-max",
            ObjectiveKind::Untangle => "untangle",
            ObjectiveKind::UntangleMinDet => "untangle-mindet",
        }
    }

    /// What it is, in a few words for people (the page's menus and picture titles).
    pub fn describe(self) -> &'static str {
        match self {
            ObjectiveKind::MaxMinShape => "max-min α/β (Freitag's ascent)",
            ObjectiveKind::Sine => "max-min sine (Freitag)",
            ObjectiveKind::SmoothShape => "Chen, Tristano & Kwok (Fletcher–Reeves)",
            ObjectiveKind::Condition => "condition number κ, 2-norm (Knupp)",
            ObjectiveKind::ConditionMax => "condition number κ, worst corner (Knupp)",
            ObjectiveKind::Untangle => "untangling Σ(|det| − det) (Knupp)",
            ObjectiveKind::UntangleMinDet => "max-min det (Knupp & Freitag)",
        }
    }

    /// The kind with command-line name `s` (exact, lowercase), if any.
    pub fn parse(s: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.name() == s)
    }

    /// Whether objectives of this kind are built to untangle (see
    /// [`Objective::untangles`]): `new` (its penalty is finite on inverted stars and falls
    /// as a fold gets shallower) and `untangle`.
    pub fn untangles(self) -> bool {
        matches!(self, ObjectiveKind::SmoothShape | ObjectiveKind::Untangle)
    }

    /// Whether objectives of this kind only untangle (see [`Objective::only_untangles`]):
    /// `untangle` and `untangle-mindet`.
    pub fn only_untangles(self) -> bool {
        matches!(self, ObjectiveKind::Untangle | ObjectiveKind::UntangleMinDet)
    }

    /// How this kind's terms combine (which solver fits it).
    pub fn goal(self) -> Goal {
        match self {
            ObjectiveKind::SmoothShape | ObjectiveKind::Condition | ObjectiveKind::Untangle => Goal::MinimizeSum,
            ObjectiveKind::MaxMinShape | ObjectiveKind::Sine | ObjectiveKind::ConditionMax | ObjectiveKind::UntangleMinDet => {
                Goal::MaximizeMin
            }
        }
    }
}

impl std::fmt::Display for ObjectiveKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// The objective of a kind, with its default parameters, behind the trait (dynamic
/// dispatch: one virtual call per evaluation, against tens of metric evaluations inside).
pub fn objective(kind: ObjectiveKind) -> Box<dyn Objective + Send + Sync> {
    objective_with(kind, Penalty::default())
}

/// [`objective`], with the design of the `new` objective's angle penalty (the other kinds
/// have none and ignore it).
pub fn objective_with(kind: ObjectiveKind, penalty: Penalty) -> Box<dyn Objective + Send + Sync> {
    match kind {
        ObjectiveKind::MaxMinShape => Box::new(MaxMinShape),
        ObjectiveKind::Sine => Box::new(MaxMinSine),
        ObjectiveKind::SmoothShape => Box::new(ChenTristanoKwok::with_penalty(penalty)),
        ObjectiveKind::Condition => Box::new(ConditionNumber { norm: Norm::Two }),
        ObjectiveKind::ConditionMax => Box::new(ConditionNumber { norm: Norm::Infinity }),
        ObjectiveKind::Untangle => Box::new(Untangle::default()),
        ObjectiveKind::UntangleMinDet => Box::new(MaxMinDet),
    }
}

/// Refuses, with the reason, a mesh whose objective values `kind` cannot hold. The
/// untangling objectives work with corner determinants, areas in mesh units: with edges
/// beyond 1e150 they overflow (a pass total of +∞ and −∞ stars is NaN), below 1e-150
/// they vanish. The nodes would still move as at any other scale (the solvers work in
/// each star's own frame), but the totals would mean nothing. Every other objective is a
/// ratio of lengths and takes any scale.
pub fn check_scale(kind: ObjectiveKind, mesh: &Mesh) -> crate::Result<()> {
    if !matches!(kind, ObjectiveKind::Untangle | ObjectiveKind::UntangleMinDet) {
        return Ok(());
    }
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for e in mesh.edges() {
        let d = mesh.nodes()[e.a as usize] - mesh.nodes()[e.b as usize];
        let l = d.x.hypot(d.y);
        hi = hi.max(l);
        if l > 0.0 {
            lo = lo.min(l);
        }
    }
    let why = if hi > 1e150 {
        format!("edges up to {hi:.3e} long")
    } else if lo < 1e-150 {
        format!("edges down to {lo:.3e} long")
    } else {
        return Ok(());
    };
    Err(crate::Error::invalid(format!(
        "{kind} works with element areas, which for {why} are beyond 64-bit floats (edges from 1e-150 to 1e150 \
         are fine): give the mesh in other units, or use an objective that is a ratio of lengths (new, old, …)"
    )))
}

/// How an objective's terms combine, and which way is better.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Goal {
    /// Minimise the sum of the terms (a smooth objective).
    MinimizeSum,
    /// Maximise the minimum of the terms (a non-smooth max-min objective).
    MaximizeMin,
}

/// One term of an objective at a position, with its gradient with respect to the
/// free node's position.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Term<V = DVec2> {
    /// Index of the element in the star (for a planar star, in [`Star::elems`]) the term
    /// belongs to.
    pub elem: u32,
    pub value: f64,
    pub grad: V,
}

/// One element of a star, with its node coordinates and where the free node sits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StarElement {
    pub kind: ElementKind,
    /// Element index in the mesh.
    pub element: u32,
    /// Node coordinates in element order (first `kind.node_count()` used).
    pub pts: [DVec2; 9],
    /// Local index of the free node (a corner) in the element.
    pub slot: u8,
    /// Whether the mid-side node of the edge leaving the free node forward (to the next
    /// corner) / backward (to the previous corner) follows it, staying at the midpoint
    /// of the straight edge. False on linear elements and on curved boundary edges.
    pub follow_next: bool,
    pub follow_prev: bool,
}

impl StarElement {
    /// The element's node coordinates with the free node at `x` (and following mid-side
    /// nodes at their edge midpoints).
    #[inline]
    pub fn at(&self, x: DVec2) -> [DVec2; 9] {
        let mut p = self.pts;
        Self::place(self.kind, self.slot, self.follow_next, self.follow_prev, &mut p, x);
        p
    }

    /// Moves the free node to `x` in place (mid-side nodes following): `pts` becomes
    /// [`at(x)`](Self::at) without copying the array.
    #[inline]
    pub fn move_free_node(&mut self, x: DVec2) {
        Self::place(self.kind, self.slot, self.follow_next, self.follow_prev, &mut self.pts, x);
    }

    #[inline]
    fn place(kind: ElementKind, slot: u8, follow_next: bool, follow_prev: bool, p: &mut [DVec2; 9], x: DVec2) {
        let k = kind.corners();
        let s = slot as usize;
        p[s] = x;
        if follow_next {
            p[k + s] = 0.5 * (x + p[(s + 1) % k]);
        }
        if follow_prev {
            let prev = (s + k - 1) % k;
            p[k + prev] = 0.5 * (x + p[prev]);
        }
    }
}

/// The star of a free node: the elements that contain it, gathered once per visit.
/// A `Star` is a reusable scratch buffer: [`Star::gather`] clears and refills it.
#[derive(Clone, Debug, Default)]
pub struct Star {
    /// The free node.
    pub node: u32,
    /// Its position when gathered.
    pub x0: DVec2,
    pub elems: Vec<StarElement>,
    /// True when the mesh has both triangles and quads (Chen's ×3 triangle weight applies).
    pub mixed: bool,
    /// What `new` and `untangle` read of the star at `x0` at every evaluation of a solve,
    /// worked out at the first ([`StarMemo`]).
    pub(crate) memo: StarMemo,
    /// Per element, where the mesh has targets other than the ideal
    /// ([`Mesh::target_nodes`]; empty otherwise): its nodes' target positions (a quad's;
    /// zeros for a triangle, whose frames say all).
    pub targets: Vec<[DVec2; 9]>,
    /// Per element, with [`targets`](Self::targets): each corner's frame
    /// ([`crate::target::corner_frame`]; the identity where the ideal holds).
    pub frames: Vec<[DMat2; 4]>,
    /// The unit direction the free node slides along the boundary
    /// ([`Mesh::slide_direction`]; zero where it does not slide).
    pub slide: DVec2,
}

/// Facts of a star at its position [`Star::x0`] that an objective reads at every
/// evaluation of a solve and that do not depend on the trial position: worked out at the
/// first evaluation and kept (a visit of `opt` with `new` evaluates one star some 6
/// times). [`Star::gather`] and the drivers' moves of the star forget them, and so does a
/// clone (a clone is made to be changed); they are kept with the `x0` they were worked out
/// at, and a star whose `x0` was set since gets them worked out again at every evaluation,
/// so they are never read for another position. The same bits come out as without it.
/// `OnceLock`s, so a star can be shared between threads (the coloured passes). One fact
/// a field, each worked out by the objective that reads it: `new`'s
/// ([`new::StarAtRest`]), and `untangle`'s sum of the moving corners' |det| with their
/// number (its shift β, [`Untangle::shift`]).
#[derive(Debug, Default)]
pub(crate) struct StarMemo {
    new: std::sync::OnceLock<(DVec2, new::StarAtRest)>,
    dets: std::sync::OnceLock<(DVec2, (f64, usize))>,
}

impl Clone for StarMemo {
    fn clone(&self) -> Self {
        StarMemo::default()
    }
}

impl StarMemo {
    /// The facts `new` reads of `star` at `star.x0`, from `work` unless kept for that position.
    #[inline]
    pub(crate) fn get(star: &Star, work: impl Fn(&Star) -> new::StarAtRest) -> new::StarAtRest {
        Self::kept(&star.memo.new, star, work)
    }

    /// The sum of the |det| of `star`'s moving corners at `star.x0` and their number, from
    /// `work` unless kept for that position.
    #[inline]
    pub(crate) fn dets(star: &Star, work: impl Fn(&Star) -> (f64, usize)) -> (f64, usize) {
        Self::kept(&star.memo.dets, star, work)
    }

    /// The sum and number of [`dets`](Self::dets) where they are kept for `star.x0`.
    #[inline]
    pub(crate) fn dets_kept(star: &Star) -> Option<(f64, usize)> {
        star.memo.dets.get().filter(|(at, _)| Self::same(at, star)).map(|&(_, facts)| facts)
    }

    /// Keeps `facts` as [`dets`](Self::dets) of `star` at `star.x0` where nothing is kept.
    #[inline]
    pub(crate) fn keep_dets(star: &Star, facts: (f64, usize)) {
        let _ = star.memo.dets.set((star.x0, facts));
    }

    /// Whether `at` is `star.x0`, bit for bit.
    #[inline]
    pub(crate) fn same(at: &DVec2, star: &Star) -> bool {
        at.x.to_bits() == star.x0.x.to_bits() && at.y.to_bits() == star.x0.y.to_bits()
    }

    #[inline]
    fn kept<T: Copy>(cell: &std::sync::OnceLock<(DVec2, T)>, star: &Star, work: impl Fn(&Star) -> T) -> T {
        match cell.get() {
            Some((at, facts)) if Self::same(at, star) => *facts,
            Some(_) => work(star),
            None => {
                let facts = work(star);
                let _ = cell.set((star.x0, facts));
                facts
            }
        }
    }

    /// Forgets the facts (the star is about to move or be refilled).
    #[inline]
    pub(crate) fn forget(&mut self) {
        self.new.take();
        self.dets.take();
    }
}

impl Star {
    pub fn new() -> Self {
        Self::default()
    }
    /// Fills the star of `node` from `mesh`.
    pub fn gather(&mut self, mesh: &Mesh, node: usize) {
        self.node = node as u32;
        self.x0 = mesh.nodes()[node];
        self.slide = mesh.slide_direction(node);
        self.mixed = mesh.has_triangles() && mesh.has_quads();
        self.memo.forget();
        self.elems.clear();
        self.targets.clear();
        self.frames.clear();
        let target = mesh.star_target_frames(node);
        for (j, &e) in mesh.node_elements(node).iter().enumerate() {
            let e = e as usize;
            let kind = mesh.kind(e);
            let ids = mesh.element(e);
            let k = kind.corners();
            let Some(slot) = ids[..k].iter().position(|&i| i as usize == node) else {
                continue; // the node is a mid-side node of this element: not a corner star
            };
            // a mid-side node the node carries along the boundary follows it too: the
            // objective sees its edge straight, the acceptance rule on the curve
            let follows = |edge: usize| {
                kind.mid(edge).is_some_and(|m| {
                    let mid = ids[m] as usize;
                    mesh.role(mid) == NodeRole::Mid
                        && ((!mesh.fixed()[mid] && !mesh.is_on_curved_boundary(mid)) || mesh.carries(node, mid))
                })
            };
            // filled in place: a StarElement is 160 bytes, built once where it lives
            self.elems.push(StarElement {
                kind,
                element: e as u32,
                pts: [DVec2::ZERO; 9],
                slot: slot as u8,
                follow_next: follows(slot),
                follow_prev: follows((slot + k - 1) % k),
            });
            let pts = &mut self.elems.last_mut().expect("just pushed").pts;
            for (p, &n) in pts.iter_mut().zip(ids) {
                *p = mesh.nodes()[n as usize];
            }
            if let Some(frames) = target {
                // only a quad's targets are read (new's sub-triangles): a triangle's frames
                // are all it needs
                let t = match kind.is_triangle() {
                    true => [DVec2::ZERO; 9],
                    false => mesh.element_target_points(e).expect("a mesh with frames has targets"),
                };
                self.frames.push(frames[j]);
                self.targets.push(t);
            }
        }
    }

    /// Whether its corners have targets other than the ideal ([`Star::frames`]).
    #[inline(always)]
    pub fn targeted(&self) -> bool {
        !self.frames.is_empty()
    }

    /// The corner frames of element `i`, where it has a target other than the ideal.
    #[inline(always)]
    pub fn frames_of(&self, i: usize) -> Option<&[DMat2; 4]> {
        self.frames.get(i)
    }

    /// The jets of element `i` (`el`) with the free node at `x`, each corner in its frame
    /// where the star has targets ([`corners::ElementJets::in_frames`]).
    #[inline]
    pub(crate) fn jets(&self, i: usize, el: &StarElement, x: DVec2) -> corners::ElementJets {
        let mut j = corners::ElementJets::new(el, x);
        if let Some(f) = self.frames_of(i) {
            j.in_frames(f);
        }
        j
    }
    pub fn len(&self) -> usize {
        self.elems.len()
    }
    pub fn is_empty(&self) -> bool {
        self.elems.is_empty()
    }
}

impl NodeStar for Star {
    type Point = DVec2;
    #[inline]
    fn len(&self) -> usize {
        self.elems.len()
    }
    #[inline]
    fn size(&self) -> f64 {
        star_scale(self)
    }
    fn scaled(&self, f: f64) -> Self {
        scaled_star(self, f)
    }
}

/// A copy of the star with every coordinate multiplied by `f` (a power of two: exact).
pub(crate) fn scaled_star(star: &Star, f: f64) -> Star {
    let mut s = star.clone();
    s.x0 *= f;
    for e in &mut s.elems {
        for p in &mut e.pts {
            *p *= f;
        }
    }
    s
}

/// The size of a star: the mean length of the corner edges at the free node (the edges
/// to the next and previous corner of every star element), measured at [`Star::x0`].
/// 0 for an empty star.
pub fn star_scale(star: &Star) -> f64 {
    let mut sum = 0.0;
    let mut n = 0usize;
    for e in &star.elems {
        let k = e.kind.corners();
        let s = e.slot as usize;
        // halved before summing, so that sizes near the largest double do not overflow
        sum +=
            0.5 * crate::numeric::robust_length(e.pts[(s + 1) % k] - star.x0) + 0.5 * crate::numeric::robust_length(e.pts[(s + k - 1) % k] - star.x0);
        n += 2;
    }
    if n == 0 {
        0.0
    } else {
        sum / (n / 2) as f64
    }
}

/// The largest edge component at the free node of `star` at [`Star::x0`] (to the next and
/// previous corner of every element): how far the objectives' products of two edge
/// components are from leaving the doubles (beyond 2^±200, [`crate::numeric::SAFE_SCALE`]).
#[inline]
pub(crate) fn free_node_extent(star: &Star) -> f64 {
    crate::numeric::largest_component(star.elems.iter().flat_map(|e| {
        let (k, s) = (e.kind.corners(), e.slot as usize);
        [e.pts[(s + 1) % k] - star.x0, e.pts[(s + k - 1) % k] - star.x0]
    }))
}

/// An objective of a free node's position over its star (see the module docs).
pub trait Objective<S: NodeStar = Star> {
    /// A short name, as on the command line (`new`, `old`, …).
    fn name(&self) -> &'static str;
    /// How the terms combine.
    fn goal(&self) -> Goal;
    /// Whether the objective is built to untangle: finite, and lower, as a fold gets
    /// shallower. Drivers then let an already inverted star pass through one more fold
    /// when its total inversion falls (`SmoothOptions::pass_through_folds`, unless set).
    /// Default false.
    fn untangles(&self) -> bool {
        false
    }
    /// Whether the objective only untangles (Knupp 1999 §2.7's untangling functions): its
    /// value is flat on valid stars (`untangle`: zero once every corner is valid, up to
    /// its shift) or blind to their shape (`untangle-mindet`: the smallest determinant, an
    /// area), so the drivers leave a valid mesh where it is (`docs/formulas.md` §4).
    /// Default false.
    fn only_untangles(&self) -> bool {
        false
    }
    /// Appends the terms at position `x` (values and gradients) to `out`.
    fn terms(&self, star: &S, x: S::Point, out: &mut Vec<Term<S::Point>>);
    /// The objective value at `x`: the sum or the minimum of the terms.
    fn value(&self, star: &S, x: S::Point) -> f64 {
        self.value_and_gradient(star, x).0
    }
    /// Value and gradient at `x`. For a max-min objective the gradient is that of one
    /// active (minimum) term — a subgradient; Freitag's solver uses [`terms`](Self::terms).
    fn value_and_gradient(&self, star: &S, x: S::Point) -> (f64, S::Point) {
        let mut t = Vec::with_capacity(star.len() * 3);
        self.terms(star, x, &mut t);
        combine(self.goal(), &t)
    }
    /// Value, gradient and Hessian (symmetric) at `x`, for a smooth objective that has
    /// an analytic Hessian (`new` with its barrier, `condition`); `None` otherwise (the default). The
    /// value and gradient are [`value_and_gradient`](Self::value_and_gradient)'s. Newton's
    /// first trial in Fletcher–Reeves ([`crate::optimize::SolveOptions::newton`]) uses it.
    #[allow(clippy::type_complexity)]
    fn value_gradient_hessian(&self, _star: &S, _x: S::Point) -> Option<(f64, S::Point, <S::Point as Point>::Hessian)> {
        None
    }
    /// Whether every term at `x` is above `floor` (at least one term, none NaN): for a
    /// max-min objective, whether `x` is better than a point of value `floor`. When it is,
    /// `out` holds the terms at `x` as [`terms`](Self::terms) appends them to an empty
    /// vector; when not, `out` holds anything. Freitag's ascent (1997, Fig. 1) halves its
    /// step until a trial point is better, and most trial points are not: an objective may
    /// stop at the first term not above `floor`, trying the terms of star element `lead`
    /// (an index into the star's elements, as [`Term::elem`]) first — the ascent passes
    /// the element of the worst term where it stands, then that of a term not above its
    /// floor at the last trial, when `out` ended with one. The answer is the same either way.
    /// Default: every term, then the test.
    fn terms_above(&self, star: &S, x: S::Point, floor: f64, lead: u32, out: &mut Vec<Term<S::Point>>) -> bool {
        let _ = lead;
        out.clear();
        self.terms(star, x, out);
        !out.is_empty() && out.iter().all(|t| t.value > floor)
    }
}

/// Combines terms by the goal: sum (with summed gradient) or minimum (with the gradient
/// of the first minimal term). An empty set gives 0; a NaN term makes the value NaN (the
/// solvers read it as the worst value of the goal).
pub fn combine<V: Point>(goal: Goal, terms: &[Term<V>]) -> (f64, V) {
    let (v, g) = match goal {
        Goal::MinimizeSum => terms.iter().fold((0.0, V::ZERO), |(v, g), t| (v + t.value, g + t.grad)),
        Goal::MaximizeMin => terms
            .iter()
            .fold(None, |best: Option<&Term<V>>, t| match best {
                Some(b) if b.value <= t.value => Some(b),
                _ => Some(t),
            })
            .map(|t| (t.value, t.grad))
            .unwrap_or((0.0, V::ZERO)),
    };
    if goal == Goal::MaximizeMin && terms.iter().any(|t| t.value.is_nan()) {
        return (f64::NAN, g);
    }
    (v, g)
}

/// Implements [`Objective`] for a type with inherent `kind(&self) -> ObjectiveKind` and
/// `visit(&self, &Star, DVec2, impl FnMut(Term))`: `terms` collects the visited terms,
/// `value_and_gradient` folds them without allocating. A second argument names an inherent
/// `fn(&self, &Star, DVec2) -> Option<(f64, DVec2, DMat2)>` that gives
/// `value_gradient_hessian`; or, as `terms_above = name`, an inherent
/// `fn(&self, &Star, DVec2, f64, u32, &mut Vec<Term>) -> bool` that gives `terms_above`.
macro_rules! impl_objective_by_visit {
    (@impl $t:ty, $($hessian_fn:item)?) => {
        impl $crate::objective::Objective for $t {
            fn name(&self) -> &'static str {
                self.kind().name()
            }
            fn goal(&self) -> $crate::objective::Goal {
                self.kind().goal()
            }
            fn untangles(&self) -> bool {
                self.kind().untangles()
            }
            fn only_untangles(&self) -> bool {
                self.kind().only_untangles()
            }
            fn terms(&self, star: &$crate::objective::Star, x: glam::DVec2, out: &mut Vec<$crate::objective::Term>) {
                self.visit(star, x, |t| out.push(t));
            }
            fn value_and_gradient(&self, star: &$crate::objective::Star, x: glam::DVec2) -> (f64, glam::DVec2) {
                let mut fold = $crate::objective::Fold::new(self.kind().goal());
                self.visit(star, x, |t| fold.add(t));
                fold.finish()
            }
            $($hessian_fn)?
        }
    };
    ($t:ty, terms_above = $above:ident) => {
        impl_objective_by_visit!(@impl $t, fn terms_above(
            &self,
            star: &$crate::objective::Star,
            x: glam::DVec2,
            floor: f64,
            lead: u32,
            out: &mut Vec<$crate::objective::Term>,
        ) -> bool {
            self.$above(star, x, floor, lead, out)
        });
    };
    ($t:ty, $hessian:ident) => {
        impl_objective_by_visit!(@impl $t, fn value_gradient_hessian(
            &self,
            star: &$crate::objective::Star,
            x: glam::DVec2,
        ) -> Option<(f64, glam::DVec2, glam::DMat2)> {
            self.$hessian(star, x)
        });
    };
    ($t:ty) => {
        impl_objective_by_visit!(@impl $t,);
    };
}
pub(crate) use impl_objective_by_visit;

/// Folds terms as [`combine`] does, one at a time, so objectives can evaluate
/// [`Objective::value_and_gradient`] without collecting their terms.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Fold<V = DVec2> {
    goal: Goal,
    value: f64,
    grad: V,
    any: bool,
    nan: bool,
}

impl<V: Point> Fold<V> {
    pub(crate) fn new(goal: Goal) -> Self {
        Fold { goal, value: 0.0, grad: V::ZERO, any: false, nan: false }
    }
    pub(crate) fn add(&mut self, t: Term<V>) {
        match self.goal {
            Goal::MinimizeSum => {
                self.value += t.value;
                self.grad += t.grad;
            }
            Goal::MaximizeMin => {
                self.nan |= t.value.is_nan();
                // strictly smaller replaces: the first minimal term wins, as in `combine`
                if !self.any || t.value < self.value {
                    self.value = t.value;
                    self.grad = t.grad;
                }
            }
        }
        self.any = true;
    }
    pub(crate) fn finish(self) -> (f64, V) {
        (if self.nan { f64::NAN } else { self.value }, self.grad)
    }
}

/// Forwards every method of [`Objective`] through a pointer type, so a boxed objective
/// and a reference to one are objectives too.
macro_rules! forward_objective {
    ($($ptr:ty),+) => {$(
        impl<S: NodeStar, O: Objective<S> + ?Sized> Objective<S> for $ptr {
            fn name(&self) -> &'static str {
                (**self).name()
            }
            fn goal(&self) -> Goal {
                (**self).goal()
            }
            fn untangles(&self) -> bool {
                (**self).untangles()
            }
            fn only_untangles(&self) -> bool {
                (**self).only_untangles()
            }
            fn terms(&self, star: &S, x: S::Point, out: &mut Vec<Term<S::Point>>) {
                (**self).terms(star, x, out)
            }
            fn value(&self, star: &S, x: S::Point) -> f64 {
                (**self).value(star, x)
            }
            fn value_and_gradient(&self, star: &S, x: S::Point) -> (f64, S::Point) {
                (**self).value_and_gradient(star, x)
            }
            fn value_gradient_hessian(
                &self,
                star: &S,
                x: S::Point,
            ) -> Option<(f64, S::Point, <S::Point as Point>::Hessian)> {
                (**self).value_gradient_hessian(star, x)
            }
            fn terms_above(&self, star: &S, x: S::Point, floor: f64, lead: u32, out: &mut Vec<Term<S::Point>>) -> bool {
                (**self).terms_above(star, x, floor, lead, out)
            }
        }
    )+};
}
forward_objective!(Box<O>, &O);

#[cfg(test)]
mod tests {
    use super::testing::*;
    use super::*;
    use crate::mesh::MeshBuilder;

    #[test]
    fn kinds_round_trip_through_their_names() {
        let mut names: Vec<&str> = ObjectiveKind::ALL.iter().map(|k| k.name()).collect();
        for k in ObjectiveKind::ALL {
            assert_eq!(ObjectiveKind::parse(k.name()), Some(k));
            assert_eq!(k.to_string(), k.name());
            // serde (the page, the lab's settings) uses the command-line names
            assert_eq!(serde_json::to_string(&k).unwrap(), format!("\"{}\"", k.name()));
            let obj = objective(k);
            assert_eq!(obj.name(), k.name());
            assert_eq!(obj.goal(), k.goal());
        }
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), ObjectiveKind::ALL.len());
        for bad in ["", "New", "condition_max", "untangle-min", "old "] {
            assert_eq!(ObjectiveKind::parse(bad), None);
        }
    }

    #[test]
    fn value_and_gradient_agree_with_combine_over_terms() {
        let mut rng = SplitMix64::new(41);
        let mut t = Vec::new();
        for star in sample_stars() {
            for _ in 0..10 {
                let x = star.x0 + rng.point(1.5);
                // evaluated where a solve starting at x evaluates it: the barrier of `new`
                // is +∞ at inverted positions of a star that starts valid
                let star = Star { x0: x, ..star.clone() };
                for k in ObjectiveKind::ALL {
                    let obj = objective(k);
                    t.clear();
                    obj.terms(&star, x, &mut t);
                    assert!(t.iter().all(|t| (t.elem as usize) < star.len()));
                    let (v, g) = combine(obj.goal(), &t);
                    let (v2, g2) = obj.value_and_gradient(&star, x);
                    assert!(v == v2 && g == g2, "{k}: {v} {v2}");
                    assert_eq!(obj.value(&star, x), v);
                    assert!(v.is_finite() && g.is_finite(), "{k} at {x}");
                }
            }
        }
        // an empty star gives 0, as combine does
        let empty = Star::new();
        for k in ObjectiveKind::ALL {
            assert_eq!(objective(k).value_and_gradient(&empty, DVec2::ZERO), (0.0, DVec2::ZERO));
        }
    }

    #[test]
    fn terms_above_answers_as_the_terms_do() {
        // every kind (the max-min ones stop early, the others take the default): the same
        // answer as the terms' minimum against the floor, and the same terms when above
        let mut rng = SplitMix64::new(47);
        let (mut t, mut above) = (Vec::new(), Vec::new());
        let (mut yes, mut no) = (0, 0);
        for star in sample_stars() {
            for _ in 0..10 {
                let x = star.x0 + rng.point(1.5);
                let star = Star { x0: x, ..star.clone() };
                let y = x + rng.point(0.3);
                for k in ObjectiveKind::ALL {
                    let obj = objective(k);
                    t.clear();
                    obj.terms(&star, y, &mut t);
                    let min = t.iter().fold(f64::INFINITY, |m, t| if t.value.is_nan() { f64::NEG_INFINITY } else { m.min(t.value) });
                    for floor in [min - 1e-3, min, min + 1e-3, f64::NEG_INFINITY] {
                        for lead in 0..star.len() as u32 {
                            let is = obj.terms_above(&star, y, floor, lead, &mut above);
                            assert_eq!(is, !t.is_empty() && min > floor, "{k} at {y}, floor {floor}, lead {lead}");
                            if is {
                                assert_eq!(above, t, "{k} at {y}");
                                yes += 1;
                            } else {
                                no += 1;
                            }
                        }
                    }
                }
            }
        }
        assert!(yes > 100 && no > 100, "{yes} {no}");
        // an empty star is never above
        assert!(!MaxMinShape.terms_above(&Star::new(), DVec2::ZERO, f64::NEG_INFINITY, 0, &mut above));
        assert!(!MaxMinSine.terms_above(&Star::new(), DVec2::ZERO, f64::NEG_INFINITY, 0, &mut above));
    }

    /// A hexagon of six 6-node triangles around node 0, built as a mesh.
    fn tri6_hexagon() -> Mesh {
        let ring = regular_ring(6, 1.0);
        let mut b = MeshBuilder::new();
        let mut node = |p: DVec2| b.add_node([p.x, p.y, 0.0], 0) as u32;
        let centre = node(DVec2::ZERO);
        let r: Vec<u32> = ring.iter().map(|&p| node(p)).collect();
        let spoke: Vec<u32> = ring.iter().map(|&p| node(0.5 * p)).collect();
        let rim: Vec<u32> = (0..6).map(|i| node(0.5 * (ring[i] + ring[(i + 1) % 6]))).collect();
        for i in 0..6 {
            let j = (i + 1) % 6;
            b.add_element(ElementKind::Tri6, &[centre, r[i], r[j], spoke[i], rim[i], spoke[j]], 0);
        }
        b.build().expect("a valid mesh")
    }

    #[test]
    fn stars_gathered_from_a_mesh_match_explicit_stars() {
        let mesh = tri6_hexagon();
        let mut gathered = Star::new();
        gathered.gather(&mesh, 0);
        assert_eq!(gathered.len(), 6);
        assert!(gathered.elems.iter().all(|e| e.follow_next && e.follow_prev && e.kind == ElementKind::Tri6));
        let explicit = quadratic(&fan_star(&regular_ring(6, 1.0)));
        let mut rng = SplitMix64::new(43);
        for _ in 0..20 {
            let x = rng.point(1.2);
            let (from_mesh, built) = (Star { x0: x, ..gathered.clone() }, Star { x0: x, ..explicit.clone() });
            for k in ObjectiveKind::ALL {
                let obj = objective(k);
                let (a, ga) = obj.value_and_gradient(&from_mesh, x);
                let (b, gb) = obj.value_and_gradient(&built, x);
                assert!((a - b).abs() <= 1e-12 * (1.0 + a.abs()), "{k}: {a} {b}");
                assert!((ga - gb).length() <= 1e-10 * (1.0 + ga.length()), "{k}");
            }
        }
        // and moving the node in the mesh (mid nodes following) gives the same objective
        // values as evaluating the gathered star at the new position
        let mut moved = mesh.clone();
        moved.nodes_mut()[0] = d(0.2, -0.1);
        moved.follow_mid_nodes(0);
        let mut again = Star::new();
        again.gather(&moved, 0);
        let obj = ChenTristanoKwok::default();
        assert!((obj.value(&again, again.x0) - obj.value(&gathered, d(0.2, -0.1))).abs() < 1e-12);
    }

    #[test]
    fn boxed_and_borrowed_objectives_forward() {
        let star = fan_star(&regular_ring(5, 1.0));
        let x = d(0.1, 0.2);
        let direct = MaxMinShape.value_and_gradient(&star, x);
        let boxed: Box<dyn Objective> = objective(ObjectiveKind::MaxMinShape);
        fn generic<O: Objective>(o: O, s: &Star, x: DVec2) -> (f64, DVec2) {
            o.value_and_gradient(s, x)
        }
        let borrowed: &dyn Objective = &*boxed;
        assert_eq!(generic(borrowed, &star, x), direct);
        assert_eq!(generic(boxed, &star, x), direct);
    }
}
