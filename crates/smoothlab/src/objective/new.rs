//! The NEW objective of Chen, Tristano & Kwok (2003), §2: smooth, and it untangles and
//! smooths in one process. Two designs of its lost angle penalty, eq. (8): the regularised
//! barrier (`barrier.rs`, the default) and the first, adjusted-angle design (`angle.rs`).
//!
//! The formulas, in one notation: `docs/formulas.md` §3.

use glam::{DMat2, DVec2};
use serde::{Deserialize, Serialize};

use super::corners::ElementJets;
use super::{impl_objective_by_visit, ObjectiveKind, Star, StarElement, Term};
use crate::mesh::ElementKind;

mod angle;
mod barrier;

pub use angle::{adjusted_angle, AnglePenalty, PenaltyLength, EQUILATERAL_PENALTY};
pub use barrier::{regularised_determinant, RegularisedBarrier, BARRIER_EPSILON, BARRIER_WEIGHT};

enum_with_all! {
    /// The designs of the angle penalty (our eq. (8)), by their command-line names.
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
    #[serde(rename_all = "lowercase")]
    pub enum Penalty {
        /// `barrier`: [`RegularisedBarrier`], `k1·η_δ²` (the default).
        #[default]
        Barrier,
        /// `angle`: [`AnglePenalty`], the first design on the adjusted angle of eqs. (6)–(7).
        Angle,
    }
}

impl Penalty {
    /// The name on the command line, in permalinks and on the page.
    pub fn name(self) -> &'static str {
        match self {
            Penalty::Barrier => "barrier",
            Penalty::Angle => "angle",
        }
    }
    /// The design called `name` (exact, lowercase).
    pub fn parse(name: &str) -> Option<Penalty> {
        Self::ALL.into_iter().find(|p| p.name() == name)
    }
    /// What it is, in a few words for people.
    pub fn describe(self) -> &'static str {
        match self {
            Penalty::Barrier => "regularised barrier on 1/α (untangles, never folds a valid star)",
            Penalty::Angle => "adjusted-angle penalty (the first design)",
        }
    }
}

impl std::fmt::Display for Penalty {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Chen, Tristano & Kwok's objective (the `new` objective). For the free node C and each
/// sub-triangle T = (C, A, B) of its star (counter-clockwise),
///
/// `f_T = (1 − α_T)² + penalty_T` — eqs. (3)–(5) —
///
/// where α_T is Lo's α at C and the penalty is our eq. (8): the paper's was lost in
/// extraction, so it is our design — [`RegularisedBarrier`] by default, the first design
/// [`AnglePenalty`] by choice ([`Penalty`]). Quads contribute their three sub-triangles
/// containing the free node D, eq. (9): (D, next, opposite), (D, opposite, previous),
/// (D, next, previous); the triangle of the other three corners is the "dead zone" and
/// is left out. In a mixed star each triangle's contribution is multiplied by 3
/// ([`Star::mixed`]). Quadratic elements: α at C uses the edge end tangents at C (a quad
/// diagonal is a straight chord). One term per star element.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ChenTristanoKwok {
    /// `(1 − α)² + k1·η_δ²` ([`RegularisedBarrier`]).
    Barrier(RegularisedBarrier),
    /// `(1 − α)² + f_θ(A) + f_θ(B)` ([`AnglePenalty`]).
    Angle(AnglePenalty),
}

impl Default for ChenTristanoKwok {
    fn default() -> Self {
        Self::with_penalty(Penalty::default())
    }
}

impl ChenTristanoKwok {
    /// The objective with the default constants of `penalty`.
    pub fn with_penalty(penalty: Penalty) -> Self {
        match penalty {
            Penalty::Barrier => ChenTristanoKwok::Barrier(RegularisedBarrier::default()),
            Penalty::Angle => ChenTristanoKwok::Angle(AnglePenalty::default()),
        }
    }

    /// `Σ (1 − α)²` alone: the objective without its penalty (Chen Fig. 2's failure).
    pub fn without_penalty() -> Self {
        ChenTristanoKwok::Barrier(RegularisedBarrier { k1: 0.0, ..RegularisedBarrier::default() })
    }

    pub fn kind(&self) -> ObjectiveKind {
        ObjectiveKind::SmoothShape
    }

    /// Which design of eq. (8) this is.
    pub fn penalty(&self) -> Penalty {
        match self {
            ChenTristanoKwok::Barrier(_) => Penalty::Barrier,
            ChenTristanoKwok::Angle(_) => Penalty::Angle,
        }
    }

    /// The barrier's δ for `star` at its current position (0 for the angle design and
    /// for the objective without penalty).
    pub fn delta(&self, star: &Star) -> f64 {
        match self {
            ChenTristanoKwok::Barrier(b) if b.k1 != 0.0 => barrier_delta(b, star),
            _ => 0.0,
        }
    }

    /// Calls `emit` with one term per star element. A star far from unit size (edges beyond
    /// 2^±200, where the squared lengths of N and D would overflow or underflow) is
    /// evaluated in a copy scaled by a power of two, which is exact: the values are ratios
    /// and come out the same, the gradient is scaled back.
    pub fn visit(&self, star: &Star, x: DVec2, mut emit: impl FnMut(Term)) {
        match extreme_scale_factor(star) {
            Some(f) => {
                let unit = super::scaled_star(star, f);
                self.visit_at_unit_scale::<false>(&unit, f * x, |i, value, grad, _| {
                    emit(Term { elem: i as u32, value, grad: f * grad })
                });
            }
            None => self
                .visit_at_unit_scale::<false>(star, x, |i, value, grad, _| emit(Term { elem: i as u32, value, grad })),
        }
    }

    /// Value, gradient and Hessian (2×2) of the objective at `x`, for the barrier design
    /// (`None` for the angle design, which has no analytic Hessian here). Every vector of a
    /// sub-triangle is affine in the free node with a scalar weight, so N is linear and D
    /// quadratic in it, at every element kind (`barrier.rs`, `RegularisedBarrier::of`).
    /// The value and gradient are those of [`visit`](Self::visit), bit for bit.
    pub fn with_hessian(&self, star: &Star, x: DVec2) -> Option<(f64, DVec2, DMat2)> {
        if !matches!(self, ChenTristanoKwok::Barrier(_)) {
            return None;
        }
        let mut sum = (0.0, DVec2::ZERO, DMat2::ZERO);
        let mut add = |_: usize, v: f64, g: DVec2, h: DMat2| {
            sum.0 += v;
            sum.1 += g;
            sum.2 += h;
        };
        match extreme_scale_factor(star) {
            Some(f) => {
                let unit = super::scaled_star(star, f);
                self.visit_at_unit_scale::<true>(&unit, f * x, |i, v, g, h| add(i, v, f * g, h * (f * f)));
            }
            None => self.visit_at_unit_scale::<true>(star, x, add),
        }
        Some(sum)
    }

    /// [`visit`](Self::visit) for a star whose edges are within 2^±200: `emit` gets each
    /// element's index, value, gradient and (when `HESSIAN`, else zero) Hessian.
    #[inline(always)]
    fn visit_at_unit_scale<const HESSIAN: bool>(
        &self,
        star: &Star,
        x: DVec2,
        mut emit: impl FnMut(usize, f64, DVec2, DMat2),
    ) {
        let w = if star.mixed { 3.0 } else { 1.0 };
        let delta = self.delta(star);
        for (i, el) in star.elems.iter().enumerate() {
            if el.kind == ElementKind::Tri3 {
                // the common case inline (the same arithmetic as through each_sub_triangle,
                // whose closure the compiler keeps apart, passing the sub-triangle through
                // memory: a quarter of the time of `opt` went there)
                let s = el.slot as usize;
                let mut t = SubTriangle::linear(x, el.pts[(s + 1) % 3], el.pts[(s + 2) % 3]);
                if let Some(f) = star.frames_of(i) {
                    // straight: the pair at C in its frame says the whole triangle
                    let (ca, cb) = crate::target::in_frame(
                        &f[s],
                        el.pts[(s + 1) % 3] - x,
                        el.pts[(s + 2) % 3] - x,
                    );
                    let (wa, wb) = crate::target::in_frame(&f[s], -1.0, -1.0);
                    t = SubTriangle::straight(ca, cb, wa, wb);
                }
                let (v, g, h) = self.sub_triangle::<HESSIAN>(&t, delta);
                // added to zero as the general path sums, so a −0 comes out as +0 there too
                let (v, g, h) = (0.0 + v, DVec2::ZERO + g, DMat2::ZERO + h);
                emit(i, w * v, w * g, if HESSIAN { h * w } else { DMat2::ZERO });
                continue;
            }
            let (mut value, mut grad, mut hess) = (0.0, DVec2::ZERO, DMat2::ZERO);
            each_target_sub_triangle(star, i, el, x, |t| {
                let (v, g, h) = self.sub_triangle::<HESSIAN>(t, delta);
                value += v;
                grad += g;
                if HESSIAN {
                    hess += h;
                }
            });
            if el.kind.is_triangle() {
                (value, grad) = (w * value, w * grad);
                if HESSIAN {
                    hess *= w;
                }
            }
            emit(i, value, grad, hess);
        }
    }

    /// The term of one sub-triangle (C, A, B), C the free corner, with its gradient (and
    /// Hessian when `HESSIAN`: the barrier design only, zero for the angle design).
    /// Inlined into the loops, so that the vectors a design does not read are never made.
    #[inline(always)]
    fn sub_triangle<const HESSIAN: bool>(&self, t: &SubTriangle, delta: f64) -> (f64, DVec2, DMat2) {
        match self {
            ChenTristanoKwok::Barrier(b) => b.of::<HESSIAN>(t, delta),
            ChenTristanoKwok::Angle(a) => {
                let at_c = barrier::CornerND::of(t.c_to_a, t.c_to_b);
                let (alpha, grad_alpha) = at_c.alpha();
                let (p, gp) = a.of(t);
                ((1.0 - alpha) * (1.0 - alpha) + p, -2.0 * (1.0 - alpha) * grad_alpha + gp, DMat2::ZERO)
            }
        }
    }
}

/// The power of two that brings `star` to unit size when its largest edge component at the
/// free node lies outside 2^±200 (squares of such lengths leave the doubles); `None` for
/// the stars of every ordinary mesh.
#[inline]
fn extreme_scale_factor(star: &Star) -> Option<f64> {
    let m = StarAtRest::of(star).extent;
    if m == 0.0 || crate::numeric::SAFE_SCALE.contains(&m) {
        None
    } else {
        crate::numeric::unit_factor(m)
    }
}

/// δ of `star` at its current position: the corner N values of its sub-triangles there.
#[inline]
fn barrier_delta(b: &RegularisedBarrier, star: &Star) -> f64 {
    let r = StarAtRest::of(star);
    b.delta_from(r.n_sum, r.n_count, r.n_min)
}

/// What the objective reads of a star at its position [`Star::x0`], the same at every
/// evaluation of a solve: worked out once per position ([`crate::objective::StarMemo`]).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct StarAtRest {
    /// The largest edge component at the free node (to the next and previous corner of
    /// every element), for [`extreme_scale_factor`].
    extent: f64,
    /// The corner N values of the star's sub-triangles, for δ
    /// ([`RegularisedBarrier::delta_from`]): the sum of |N|, their number, the smallest.
    n_sum: f64,
    n_count: usize,
    n_min: f64,
}

impl StarAtRest {
    /// The facts of `star` at `star.x0`, kept in the star between evaluations.
    #[inline]
    fn of(star: &Star) -> StarAtRest {
        crate::objective::StarMemo::get(star, StarAtRest::work_out)
    }

    fn work_out(star: &Star) -> StarAtRest {
        let extent = super::free_node_extent(star);
        let (mut sum, mut count, mut min) = (0.0, 0usize, f64::INFINITY);
        for el in &star.elems {
            if el.kind == ElementKind::Tri3 {
                // the N of SubTriangle::linear at x0, without making the rest of it
                let (s, x0) = (el.slot as usize, star.x0);
                let n = (el.pts[(s + 1) % 3] - x0).perp_dot(el.pts[(s + 2) % 3] - x0);
                sum += n.abs();
                count += 1;
                min = min.min(n);
                continue;
            }
            each_sub_triangle(el, star.x0, |t| {
                let mut add = |n: f64| {
                    sum += n.abs();
                    count += 1;
                    min = min.min(n);
                };
                add(t.c_to_a.0.perp_dot(t.c_to_b.0));
                if !t.straight {
                    add(t.a_to_b.0.perp_dot(t.a_to_c.0));
                    add(t.b_to_c.0.perp_dot(t.b_to_a.0));
                }
            });
        }
        StarAtRest { extent, n_sum: sum, n_count: count, n_min: min }
    }
}

/// Calls `f` with each sub-triangle of a star element whose free node is at `x`: the
/// element itself for a triangle, the three of eq. (9) for a quad.
#[inline(always)]
fn each_sub_triangle(el: &StarElement, x: DVec2, mut f: impl FnMut(&SubTriangle)) {
    if el.kind == ElementKind::Tri3 {
        // the common case, without the general element machinery (same arithmetic)
        let s = el.slot as usize;
        f(&SubTriangle::linear(x, el.pts[(s + 1) % 3], el.pts[(s + 2) % 3]));
        return;
    }
    let j = ElementJets::new(el, x);
    let c = j.slot;
    let straight = !el.kind.is_quadratic();
    if el.kind.is_triangle() {
        f(&SubTriangle::of(&j, c, (c + 1) % 3, (c + 2) % 3, straight));
    } else {
        let (n, o, p) = ((c + 1) % 4, (c + 2) % 4, (c + 3) % 4);
        f(&SubTriangle::of(&j, c, n, o, straight));
        f(&SubTriangle::of(&j, c, o, p, straight));
        f(&SubTriangle::of(&j, c, n, p, straight));
    }
}

/// [`each_sub_triangle`] as the star's targets measure them ([`Star::frames`]): each
/// corner's pair of a triangle in that corner's frame; a quad's sub-triangles each against
/// the same sub-triangle of the target, whose corners are measured against the equilateral.
#[inline(always)]
fn each_target_sub_triangle(
    star: &Star,
    i: usize,
    el: &StarElement,
    x: DVec2,
    mut f: impl FnMut(&SubTriangle),
) {
    let (Some(frames), Some(target)) = (star.frames_of(i), star.targets.get(i)) else {
        return each_sub_triangle(el, x, f);
    };
    let k = el.kind.corners();
    if el.kind.is_triangle() {
        return each_sub_triangle(el, x, |t| {
            let s = el.slot as usize;
            f(&t.in_frames(&frames[s], &frames[(s + 1) % k], &frames[(s + 2) % k]))
        });
    }
    let mut input = *el;
    input.pts = *target;
    let mut theirs = [SubTriangle::linear(DVec2::ZERO, DVec2::X, DVec2::Y); 3];
    let mut n = 0;
    each_sub_triangle(&input, target[el.slot as usize], |t| {
        theirs[n] = *t;
        n += 1;
    });
    let mut n = 0;
    each_sub_triangle(el, x, |t| {
        let of = |(a, b): ((DVec2, f64), (DVec2, f64))| {
            crate::target::corner_frame(a.0, b.0, crate::target::EQUILATERAL_PAIR)
                .unwrap_or(DMat2::IDENTITY)
        };
        let u = &theirs[n];
        n += 1;
        f(&t.in_frames(
            &of((u.c_to_a, u.c_to_b)),
            &of((u.a_to_b, u.a_to_c)),
            &of((u.b_to_c, u.b_to_a)),
        ))
    });
}

impl_objective_by_visit!(ChenTristanoKwok, with_hessian);

/// The vectors one triangle (C, A, B) of the objective reads, each with its weight
/// (`v = c·x + const`, see `corners.rs`): the directions at each corner towards the
/// others (edge vectors, or end tangents of quadratic edges) and the chords.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct SubTriangle {
    c_to_a: (DVec2, f64),
    c_to_b: (DVec2, f64),
    a_to_b: (DVec2, f64),
    a_to_c: (DVec2, f64),
    b_to_c: (DVec2, f64),
    b_to_a: (DVec2, f64),
    /// Chords AB, CA, CB.
    ab: (DVec2, f64),
    ca: (DVec2, f64),
    cb: (DVec2, f64),
    /// Every direction is a chord (a linear element): the three corners' N and D agree.
    straight: bool,
}

impl SubTriangle {
    /// Corners `c`, `a`, `b` of a star element's jets.
    #[inline]
    fn of(j: &ElementJets, c: usize, a: usize, b: usize, straight: bool) -> Self {
        SubTriangle {
            c_to_a: j.dir(c, a),
            c_to_b: j.dir(c, b),
            a_to_b: j.dir(a, b),
            a_to_c: j.dir(a, c),
            b_to_c: j.dir(b, c),
            b_to_a: j.dir(b, a),
            ab: j.chord(a, b),
            ca: j.chord(c, a),
            cb: j.chord(c, b),
            straight,
        }
    }

    /// The sub-triangle as its targets measure it: the pair at C in frame `c`, at A in
    /// `a`, at B in `b` ([`crate::target::in_frame`]); the chords from C in `c`.
    #[inline(always)]
    fn in_frames(&self, c: &DMat2, a: &DMat2, b: &DMat2) -> Self {
        let pair = |m: &DMat2, u: (DVec2, f64), v: (DVec2, f64)| {
            let (p, q) = crate::target::in_frame(m, u.0, v.0);
            let (wp, wq) = crate::target::in_frame(m, u.1, v.1);
            ((p, wp), (q, wq))
        };
        let (c_to_a, c_to_b) = pair(c, self.c_to_a, self.c_to_b);
        let (a_to_b, a_to_c) = pair(a, self.a_to_b, self.a_to_c);
        let (b_to_c, b_to_a) = pair(b, self.b_to_c, self.b_to_a);
        let (ca, cb) = pair(c, self.ca, self.cb);
        let ab = (cb.0 - ca.0, cb.1 - ca.1);
        SubTriangle {
            c_to_a,
            c_to_b,
            a_to_b,
            a_to_c,
            b_to_c,
            b_to_a,
            ab,
            ca,
            cb,
            straight: self.straight,
        }
    }

    /// A straight-sided triangle whose directions from C are `ca` and `cb`, with weights
    /// `wa` and `wb`; the other directions are their differences.
    #[inline(always)]
    fn straight(ca: DVec2, cb: DVec2, wa: f64, wb: f64) -> Self {
        let ab = (cb - ca, wb - wa);
        SubTriangle {
            c_to_a: (ca, wa),
            c_to_b: (cb, wb),
            a_to_b: ab,
            a_to_c: (-ca, -wa),
            b_to_c: (-cb, -wb),
            b_to_a: (ca - cb, wa - wb),
            ab,
            ca: (ca, wa),
            cb: (cb, wb),
            straight: true,
        }
    }

    /// A straight-sided triangle with the free node C at `x` and A, B fixed: what
    /// [`SubTriangle::of`] gives for a linear triangle, computed directly.
    #[inline(always)]
    fn linear(x: DVec2, a: DVec2, b: DVec2) -> Self {
        let (ca, cb, ab) = (a - x, b - x, b - a);
        SubTriangle {
            c_to_a: (ca, -1.0),
            c_to_b: (cb, -1.0),
            a_to_b: (ab, 0.0),
            a_to_c: (x - a, 1.0),
            b_to_c: (x - b, 1.0),
            b_to_a: (a - b, 0.0),
            ab: (ab, 0.0),
            ca: (ca, -1.0),
            cb: (cb, -1.0),
            straight: true,
        }
    }
}

#[cfg(test)]
mod tests;
