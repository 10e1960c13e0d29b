//! The acceptance rule (`docs/formulas.md` §4, "Acceptance"): a move the drivers made is
//! kept only if the node's star gets no worse. Written once here; each kind of mesh only
//! measures its elements ([`ElementScore`]: a planar element, a surface element in its own
//! plane, a tetrahedron) before and after the move, and [`Verdict`] decides.
//!
//! - A star valid before the move stays valid, its worst element's quality does not fall —
//!   by the drivers' measure ([`Measure`], the smart Laplacian's: by default the shape,
//!   α/β or a tetrahedron's mean ratio; Freitag's smallest sine where asked) — and no
//!   element shrinks below
//!   [`MIN_SIZE_RATIO`] of its size before the move (its smallest corner Jacobian
//!   determinant: twice a triangle's area, six times a tetrahedron's volume), so no
//!   element is flattened however its shape is read.
//! - A star inverted before the move may not gain an inverted element unless its
//!   inversion `Σ max(0, −det)` over the corners (`Σ max(0, −6V)` for tetrahedra) falls
//!   (the validity guard's measure of a tangled star, by which an untangling star may pass
//!   through a fold, [`SmoothOptions::pass_through_folds`](super::SmoothOptions::pass_through_folds)).
//!   Not more: refusing every move that deepens the inversion by that sum refuses the
//!   moves of Knupp's shifted untangling objective (Mesquite's β) that untangle his random
//!   grids (`docs/reproduction.md` §4: 6 of 10 grids instead of 10). Its elements that
//!   stay valid may not be flattened either (below [`MIN_SIZE_RATIO`] of their size):
//!   `old` + `opt` untangling a perturbed rand3D left valid tetrahedra of `V ≈ 10⁻¹⁵`,
//!   which no reader takes back.
//!
//! It holds for every strategy but the plain Laplacian (which moves unconditionally, as
//! Freitag's and Chen's Laplacian does), with the validity guard on
//! ([`SmoothOptions::keep_valid`](super::SmoothOptions::keep_valid)).

use glam::{DVec2, DVec3};

use super::Measure;
use crate::mesh::ElementKind;
use super::measure::triangle_shape_at;
use crate::mesh::VolumeKind;
use crate::quality::{corner_edge_vectors, measure_element, solid, tet as q3};

/// The smallest size an element of a valid star may keep, as a fraction of its size
/// before the move: a thousandth. A move that keeps the star's worst shape cannot shrink
/// an element so far unless the star's worst shape is below about 0.03 (an element's size
/// after such a move is at least about the worst shape squared of its size before), so
/// the bound only refuses moves that flatten an element.
pub const MIN_SIZE_RATIO: f64 = 1e-3;

/// What the acceptance rule reads of one element (its size `S` a [`Size`], or `()` where the
/// caller decides the size floor itself: [`Verdict::add_deciding_size`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ElementScore<S = Size> {
    /// The element's quality by the drivers' [`Measure`]: its shape (α/β, the worst
    /// corner α of a quadratic element; a tetrahedron's mean ratio) or its smallest sine
    /// (of a corner angle; of a dihedral angle).
    pub quality: f64,
    pub inverted: bool,
    /// `Σ max(0, −det)` over the corners (0 for a valid element).
    pub inversion: f64,
    /// The element's size, its smallest corner determinant, as `unit · scaleᵈ` (`d` 2 for
    /// a planar element, 3 for a tetrahedron): `unit` is the determinant of the edges
    /// divided by `scale`, their largest component, so it is a double at every scale
    /// (not a number for a degenerate element, negative for an inverted one).
    pub size: S,
}

/// An element's size as [`ElementScore::size`] holds it: `unit · scaleᵈ`, compared with
/// another's without forming either product (which leaves the doubles at extreme scales).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Size {
    pub unit: f64,
    pub scale: f64,
    pub dim: i32,
}

impl Size {
    /// Whether this size is at least `ratio` times `before` (false where either is not a
    /// number): `unit · (scale / before.scale)ᵈ ≥ ratio · before.unit`. The quotient of the
    /// scales is a double for any two elements of one star before and after a move; where
    /// it leaves them the element grew or shrank by more than 2^±1000, and the answer
    /// (infinity or zero) is still the right one.
    #[inline]
    pub fn at_least(&self, ratio: f64, before: &Size) -> bool {
        self.unit * (self.scale / before.scale).powi(self.dim) >= ratio * before.unit
    }
    /// The size of a solid of `kind`: its smallest measured corner's ([`solid::CornerSizes`]),
    /// the last of equals in corner order.
    pub fn least_corner(kind: VolumeKind, sizes: &solid::CornerSizes) -> Size {
        let mut size: Option<Size> = None;
        for &(unit, scale) in sizes.of_kind(kind) {
            let s = Size { unit, scale, dim: 3 };
            size = Some(match size {
                Some(old) if !old.at_least(1.0, &s) => old,
                _ => s,
            });
        }
        size.expect("every kind measures a corner")
    }
    /// A tetrahedron's size, `quality::solid::corner_size` of its corners.
    #[inline]
    pub fn tet(p: &[DVec3; 4]) -> Size {
        let (unit, scale) = solid::corner_size(p);
        Size { unit, scale, dim: 3 }
    }
    /// Whether an element, valid before a move, keeps at least [`MIN_SIZE_RATIO`] of its
    /// size for certain, from its least corner determinant taken directly before and after
    /// the move, each with its tolerance ([`ElementScore::planar_unsized`]'s; a solid's
    /// [`solid::least_corner_det`]; a tetrahedron's [`q3::TetRuleMeasures::det_within`]):
    /// `true` where they decide that the rule's comparison of the two sizes finds it so;
    /// `false` where they do not decide (the caller measures the sizes).
    ///
    /// Why it is the rule's answer: each corner's `unit · scaleᵈ` lies within the tolerance
    /// `t` of its determinant taken directly, so the size after is at least `a − t` (`a` the
    /// least determinant after) and the size before, the least corner up to the rounding of
    /// the comparisons that chose it among near ties, at most `b + 2t`; the comparison in
    /// [`at_least`](Self::at_least) rounds some six ulps, and with `a − t ≥ t` the power of
    /// the scales' quotient it takes stays far from underflow.
    #[inline]
    pub fn floor_kept_for_certain(before: Option<(f64, f64)>, after: Option<(f64, f64)>) -> bool {
        let (Some((b, tb)), Some((a, ta))) = (before, after) else {
            return false;
        };
        let t = tb.max(ta);
        b > 0.0 && a - t >= t && (a - t) * (1.0 - 1e-9) > MIN_SIZE_RATIO * (b + 2.0 * t) * (1.0 + 1e-9)
    }
}

impl ElementScore {
    /// A planar element (or a surface element in its own plane) with nodes `p`.
    pub fn planar(kind: ElementKind, p: &[DVec2; 9], measure: Measure) -> Self {
        Self::planar_parts::<true>(kind, p, measure).0
    }

    /// [`planar`](Self::planar) but for its size, with its least corner determinant taken
    /// directly and its tolerance, for [`Size::floor_kept_for_certain`] (`None` where not a
    /// number or beyond the scales it takes): the size's divisions are left to the caller
    /// that needs them (where the screen does not decide).
    #[inline]
    pub fn planar_unsized(kind: ElementKind, p: &[DVec2; 9], measure: Measure) -> (ElementScore<()>, Option<(f64, f64)>) {
        let (s, det) = Self::planar_parts::<false>(kind, p, measure);
        (ElementScore { quality: s.quality, inverted: s.inverted, inversion: s.inversion, size: () }, det)
    }

    /// The planar score (its size's `unit` taken where `SIZED`, else not a number, which
    /// [`planar_unsized`](Self::planar_unsized) drops) and the least corner determinant
    /// taken directly with its tolerance ([`crate::quality::det_within`]).
    #[inline(always)]
    fn planar_parts<const SIZED: bool>(kind: ElementKind, p: &[DVec2; 9], measure: Measure) -> (Self, Option<(f64, f64)>) {
        if let Some(score) = Self::valid_triangle::<SIZED>(kind, p, measure) {
            return score;
        }
        let (quality, inverted) = match measure {
            Measure::Shape => {
                let q = measure_element::<false, false, false>(kind, p, |_, _, _| {});
                (q.shape, q.inverted)
            }
            Measure::MinSine => {
                let q = measure_element::<false, false, true>(kind, p, |_, _, _| {});
                (q.min_sine, q.inverted)
            }
        };
        let k = kind.corners();
        let edges = corner_edge_vectors(kind, p);
        let m = crate::numeric::largest_component(edges[..k].iter().flat_map(|(a, b)| [*a, *b]));
        let (mut inversion, mut smallest, mut least) = (0.0, f64::INFINITY, f64::INFINITY);
        for (e1, e2) in &edges[..k] {
            let det = e1.perp_dot(*e2);
            inversion += (-det).max(0.0);
            // a determinant that is not a number leaves the least one so (and the screen
            // to the sizes)
            least = if det.is_nan() || least.is_nan() { f64::NAN } else { least.min(det) };
            if SIZED {
                smallest = smallest.min((*e1 / m).perp_dot(*e2 / m));
            }
        }
        let unit = if SIZED { smallest } else { f64::NAN };
        (ElementScore { quality, inverted, inversion, size: Size { unit, scale: m, dim: 2 } }, crate::quality::det_within(least, m, 2))
    }

    /// [`planar`](Self::planar)'s score of a valid linear triangle by [`Measure::Shape`],
    /// the drivers' common case, from its three points directly ([`triangle_shape_at`]:
    /// one cross product, which its three corners share; the general measure's α but for
    /// a few ulps, as it is taken from another corner); `None` for any other element or
    /// measure, or an inverted
    /// triangle. A valid star's elements are all scored here before and after a move that
    /// keeps them valid, so the rule compares like with like. With `planar_parts`' second
    /// part, and its size's `unit` as there.
    #[inline]
    fn valid_triangle<const SIZED: bool>(kind: ElementKind, p: &[DVec2; 9], measure: Measure) -> Option<(Self, Option<(f64, f64)>)> {
        if kind != ElementKind::Tri3 || measure != Measure::Shape {
            return None;
        }
        let (quality, inverted) = triangle_shape_at(p[1], p[2], p[0])?;
        if inverted {
            return None;
        }
        let (u, v, w) = (p[1] - p[0], p[2] - p[0], p[2] - p[1]);
        let m = u.abs().max_element().max(v.abs().max_element()).max(w.abs().max_element());
        let unit = if SIZED { (u / m).perp_dot(v / m) } else { f64::NAN };
        let score = ElementScore { quality, inverted, inversion: 0.0, size: Size { unit, scale: m, dim: 2 } };
        Some((score, crate::quality::det_within(u.perp_dot(v), m, 2)))
    }

    /// A tetrahedron with corners `p` (a quadratic one by its corners), its shape against
    /// reference `r` (its kind's W).
    pub fn tet(p: &[DVec3; 4], r: &q3::CornerReference, measure: Measure) -> Self {
        let quality = match measure {
            Measure::Shape => q3::mean_ratio(p, r),
            Measure::MinSine => q3::dihedral_sines(p).into_iter().fold(f64::INFINITY, f64::min),
        };
        ElementScore { quality, ..Self::tet_unmeasured(p) }
    }

    /// [`tet`](Self::tet) but for its quality, +∞ (no minimum sees it; the caller gives it
    /// to [`Verdict::add_qualities`] where it may be the worst).
    #[inline]
    pub fn tet_unmeasured(p: &[DVec3; 4]) -> Self {
        let t = ElementScore::tet_of(&q3::TetRuleMeasures::of(p));
        ElementScore { quality: t.quality, inverted: t.inverted, inversion: t.inversion, size: Size::tet(p) }
    }
    /// [`tet_unmeasured`](Self::tet_unmeasured) of a tetrahedron's measures taken before,
    /// but for its size (for [`Verdict::add_deciding_size`], with
    /// [`Size::floor_kept_for_certain`]).
    #[inline]
    pub fn tet_of(t: &q3::TetRuleMeasures) -> ElementScore<()> {
        ElementScore { quality: f64::INFINITY, inverted: t.inverted, inversion: t.inversion, size: () }
    }
}

impl ElementScore {
    /// An element of another kind than a tetrahedron, by its corners `p` (in its kind's
    /// order): the mean of its corners' mean ratios or its smallest corner scaled Jacobian
    /// ([`solid`]), inverted unless certainly valid ([`solid::validity`]: a fold inside
    /// counts, not its corners only), its inversion [`solid::solid_inversion`], its size
    /// its smallest corner determinant.
    pub fn solid(kind: VolumeKind, p: &[DVec3], measure: Measure) -> Self {
        let quality = match measure {
            Measure::Shape => solid::solid_shape(kind, p),
            Measure::MinSine => solid::solid_min_sine(kind, p),
        };
        let size = Size::least_corner(kind, &solid::CornerSizes::of(kind, p, |_| None));
        ElementScore { quality, ..Self::solid_sized(kind, solid::validity(kind, p), size, || p) }
    }

    /// [`solid`](Self::solid) where the element's [`solid::validity`] and size
    /// ([`Size::least_corner`], or `()` where the caller decides the floor itself) are known
    /// (a star's element answers the validity from its `det J` form where that decides:
    /// the same answers), but for its quality, +∞ (the caller sets it, where it knows it).
    /// Its corners `p()` are asked only for the inversion of an element not valid (a valid
    /// one's is 0), so a caller that would copy them for it does not copy them for every
    /// valid element.
    pub fn solid_sized<'a, S>(kind: VolumeKind, validity: solid::Validity, size: S, p: impl FnOnce() -> &'a [DVec3]) -> ElementScore<S> {
        let valid = validity == solid::Validity::Valid;
        ElementScore { quality: f64::INFINITY, inverted: !valid, inversion: if valid { 0.0 } else { solid::solid_inversion(kind, p(), validity) }, size }
    }

    /// A 10-node tetrahedron `p` (VTK's node order) with its mid-edge nodes: its four
    /// corner Jacobians' tetrahedra ([`q3::tet10_corner_tets`]) — the worst quality, any
    /// inverted, their inversions summed, the smallest size.
    pub fn tet10(p: &[DVec3; 10], r: &q3::CornerReference, measure: Measure) -> Self {
        let mut score: Option<ElementScore> = None;
        for corner in q3::tet10_corner_tets(p) {
            let c = ElementScore::tet(&corner, r, measure);
            score = Some(match score {
                None => c,
                Some(s) => ElementScore {
                    quality: if c.quality.is_nan() || c.quality < s.quality { c.quality } else { s.quality },
                    inverted: s.inverted || c.inverted,
                    inversion: s.inversion + c.inversion,
                    size: if s.size.at_least(1.0, &c.size) { c.size } else { s.size },
                },
            });
        }
        score.expect("four corners")
    }
}

/// The acceptance rule over a star: fed each element before and after a move
/// ([`add`](Self::add)), it says whether the move is kept ([`keeps`](Self::keeps)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Verdict {
    /// Elements inverted before and after the move.
    inverted_before: u32,
    inverted_after: u32,
    quality_before: f64,
    quality_after: f64,
    inversion_before: f64,
    inversion_after: f64,
    /// Some element valid before the move ends below [`MIN_SIZE_RATIO`] of its size.
    flattened: bool,
    /// Some element valid before and after the move ends below [`MIN_SIZE_RATIO`] of its
    /// size (a flattening the inverted star's own rule would not see).
    shrunk: bool,
}

impl Default for Verdict {
    fn default() -> Self {
        Verdict {
            inverted_before: 0,
            inverted_after: 0,
            quality_before: f64::INFINITY,
            quality_after: f64::INFINITY,
            inversion_before: 0.0,
            inversion_after: 0.0,
            flattened: false,
            shrunk: false,
        }
    }
}

impl Verdict {
    /// One element of the star, before and after the move.
    pub fn add(&mut self, before: &ElementScore, after: &ElementScore) {
        // a size that is not a number (a degenerate element) is below the floor
        self.add_deciding_size(before, after, || after.size.at_least(MIN_SIZE_RATIO, &before.size));
    }

    /// [`add`](Self::add) with the size floor decided by `keeps_size` (asked only of an
    /// element valid before the move: whether it keeps at least [`MIN_SIZE_RATIO`] of its
    /// size, as [`Size::at_least`] answers it) rather than from the scores' sizes.
    pub fn add_deciding_size<S>(&mut self, before: &ElementScore<S>, after: &ElementScore<S>, keeps_size: impl FnOnce() -> bool) {
        self.inverted_before += before.inverted as u32;
        self.inverted_after += after.inverted as u32;
        self.add_qualities(before.quality, after.quality);
        self.inversion_before += before.inversion;
        self.inversion_after += after.inversion;
        if !before.inverted && !keeps_size() {
            self.flattened = true;
            self.shrunk |= !after.inverted;
        }
    }

    /// One element's qualities before and after the move, where they are not in its
    /// [`ElementScore`] (given as +∞ there, which no minimum sees): a caller that measures
    /// exactly only the elements that may be the worst.
    #[inline]
    pub fn add_qualities(&mut self, before: f64, after: f64) {
        self.quality_before = self.quality_before.min(before);
        // a quality that is not a number is the worst there is
        self.quality_after = if after.is_nan() { f64::NEG_INFINITY } else { self.quality_after.min(after) };
    }

    /// Whether the star was valid before the move (the statistics' reading then decides
    /// too, [`crate::quality::Reading`]).
    #[inline]
    pub fn was_valid(&self) -> bool {
        self.inverted_before == 0
    }

    /// Whether the move is kept: a valid star stays valid, no worse in its worst quality and
    /// with no element flattened; an inverted star gains no inverted element unless its
    /// inversion falls, and flattens none of its valid elements.
    pub fn keeps(&self) -> bool {
        if self.inverted_before > 0 {
            (self.inverted_after <= self.inverted_before || self.inversion_after < self.inversion_before) && !self.shrunk
        } else {
            self.inverted_after == 0 && self.quality_after >= self.quality_before && !self.flattened
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> [DVec2; 9] {
        let mut p = [DVec2::ZERO; 9];
        p[0] = DVec2::from(a);
        p[1] = DVec2::from(b);
        p[2] = DVec2::from(c);
        p
    }

    fn verdict(pairs: &[([DVec2; 9], [DVec2; 9])]) -> Verdict {
        let mut v = Verdict::default();
        for (b, a) in pairs {
            let score = |p| ElementScore::planar(ElementKind::Tri3, p, Measure::Shape);
            v.add(&score(b), &score(a));
        }
        v
    }

    #[test]
    fn a_valid_star_keeps_a_move_that_raises_its_worst_shape_and_refuses_one_that_lowers_it() {
        let h = 3f64.sqrt() / 2.0;
        let good = tri([0.0, 0.0], [1.0, 0.0], [0.5, h]);
        let poorer = tri([0.0, 0.0], [1.0, 0.0], [0.5, 0.3]);
        assert!(verdict(&[(poorer, good)]).keeps());
        assert!(!verdict(&[(good, poorer)]).keeps());
        // the same element: no worse
        assert!(verdict(&[(good, good)]).keeps());
        // folding a valid element is refused
        let folded = tri([0.0, 0.0], [1.0, 0.0], [0.5, -0.3]);
        assert!(!verdict(&[(good, folded)]).keeps());
    }

    /// A triangle of apex height `h`·`s` shrunk to an equilateral one `f` times its base:
    /// a better shape, at `f²` of the area (about).
    fn shrunk(s: f64, h: f64, f: f64) -> ([DVec2; 9], [DVec2; 9]) {
        let e = 3f64.sqrt() / 2.0;
        (tri([0.0, 0.0], [s, 0.0], [0.5 * s, h * s]), tri([0.0, 0.0], [s * f, 0.0], [0.5 * s * f, e * s * f]))
    }

    #[test]
    fn a_valid_star_refuses_a_move_that_shrinks_an_element_below_the_floor() {
        // a better shape at a two-thousandth of the area (edges ÷ √2000 ≈ 44.7): refused
        // for its size alone; at a five-hundredth it is kept
        assert!(!verdict(&[shrunk(1.0, 0.7, 1.0 / 2000f64.sqrt())]).keeps());
        assert!(verdict(&[shrunk(1.0, 0.7, 1.0 / 500f64.sqrt())]).keeps());
    }

    #[test]
    fn the_size_floor_is_the_same_at_every_scale() {
        for s in [1e-150, 1e-100, 1e-20, 1.0, 1e20, 1e100, 1e150] {
            assert!(!verdict(&[shrunk(s, 0.7, 1.0 / 2000f64.sqrt())]).keeps(), "scale {s:e}");
            assert!(verdict(&[shrunk(s, 0.7, 1.0 / 500f64.sqrt())]).keeps(), "scale {s:e}");
        }
    }

    #[test]
    fn an_inverted_star_keeps_its_count_of_inverted_elements_or_its_inversion_falls() {
        let shallow = tri([0.0, 0.0], [1.0, 0.0], [0.5, -0.1]);
        let deep = tri([0.0, 0.0], [1.0, 0.0], [0.5, -0.5]);
        let valid = tri([0.0, 0.0], [1.0, 0.0], [0.5, 0.1]);
        let good = tri([0.0, 0.0], [1.0, 0.0], [0.5, 0.8]);
        let slightly = tri([0.0, 0.0], [1.0, 0.0], [0.5, -0.05]);
        assert!(verdict(&[(deep, shallow)]).keeps());
        assert!(verdict(&[(deep, valid)]).keeps());
        // the same count, deeper: kept (an untangling objective's way through)
        assert!(verdict(&[(shallow, deep)]).keeps());
        // one element more where the total falls: kept; where it rises: refused
        assert!(verdict(&[(deep, shallow), (good, slightly)]).keeps());
        assert!(!verdict(&[(shallow, deep), (good, slightly)]).keeps());
        assert!(!verdict(&[(shallow, shallow), (good, slightly)]).keeps());
        // nor may it flatten one of its valid elements, whatever its inversion does
        let flat = tri([0.0, 0.0], [1.0, 0.0], [0.5, 1e-5]);
        assert!(!verdict(&[(deep, shallow), (good, flat)]).keeps());
    }

    #[test]
    fn a_valid_triangle_scores_as_the_general_measure_scores_it() {
        let mut rng = crate::numeric::SplitMix64::new(29);
        for s in [1e-200, 1e-30, 1.0, 1e30, 1e200] {
            for _ in 0..2000 {
                let mut r = || s * (rng.next_f64() * 2.0 - 1.0);
                let p = tri([r(), r()], [r(), r()], [r(), r()]);
                let Some((fast, _)) = ElementScore::valid_triangle::<true>(ElementKind::Tri3, &p, Measure::Shape) else { continue };
                let q = measure_element::<false, false, false>(ElementKind::Tri3, &p, |_, _, _| {});
                assert_eq!(fast.inverted, q.inverted, "{p:?}");
                // measured from another corner (and scaled otherwise at extreme sizes): the
                // cross product a rounding of the squared edges apart, α (≤ 1) a few ulps
                assert!((fast.quality - q.shape).abs() <= 16.0 * f64::EPSILON, "{p:?} {} {}", fast.quality, q.shape);
                let edges = corner_edge_vectors(ElementKind::Tri3, &p);
                let m = edges[..3].iter().fold(0.0f64, |m, (a, b)| m.max(a.abs().max_element()).max(b.abs().max_element()));
                assert_eq!(fast.size.scale, m);
                let general = edges[..3].iter().map(|(a, b)| (*a / m).perp_dot(*b / m)).fold(f64::INFINITY, f64::min);
                // the three corners share one determinant, but for a rounding each
                assert!((fast.size.unit - general).abs() <= 16.0 * f64::EPSILON, "{p:?}");
            }
        }
    }

    #[test]
    fn a_flattened_tetrahedron_is_refused() {
        // the reproducer in miniature: the free node moved into the plane of its
        // three neighbours keeps a positive volume of ~1e-19 and is not inverted
        let p = [DVec3::new(0.2, 0.3, 0.9), DVec3::ZERO, DVec3::Y, DVec3::X];
        let flat = [DVec3::new(0.2, 0.3, 1e-18), DVec3::ZERO, DVec3::Y, DVec3::X];
        let (b, a) = (ElementScore::tet(&p, &q3::EQUILATERAL_TET, Measure::Shape), ElementScore::tet(&flat, &q3::EQUILATERAL_TET, Measure::Shape));
        assert!(!a.inverted && a.quality > 0.0);
        let mut v = Verdict::default();
        v.add(&b, &a);
        assert!(!v.keeps());
        let mut v = Verdict::default();
        v.add(&a, &b);
        assert!(v.keeps());
    }

    /// The rule's own answer for the size floor of an element of a volume mesh, and the
    /// screen's: a tetrahedron by its measures ([`q3::TetRuleMeasures`], [`Size::tet`]),
    /// another kind by its least corners' sizes.
    fn floor_kept(kind: VolumeKind, before: &[DVec3], after: &[DVec3]) -> bool {
        if kind == VolumeKind::Tet4 {
            let tet = |p: &[DVec3]| Size::tet(&[p[0], p[1], p[2], p[3]]);
            return tet(after).at_least(MIN_SIZE_RATIO, &tet(before));
        }
        let size = |p: &[DVec3]| Size::least_corner(kind, &solid::CornerSizes::of(kind, p, |_| None));
        size(after).at_least(MIN_SIZE_RATIO, &size(before))
    }
    /// The screen from the least corner determinant taken directly, or (`from_shapes`) from
    /// the shape's corners where it has them ([`solid::CornerShapes::least_corner_det`]).
    fn certain(kind: VolumeKind, before: &[DVec3], after: &[DVec3], from_shapes: bool) -> bool {
        let within = |p: &[DVec3]| match kind {
            VolumeKind::Tet4 => q3::TetRuleMeasures::of(&[p[0], p[1], p[2], p[3]]).det_within(),
            _ if from_shapes => solid::CornerShapes::of(kind, p, |_| None).map_or_else(|| solid::least_corner_det(kind, p), |t| t.least_corner_det(kind)),
            _ => solid::least_corner_det(kind, p),
        };
        Size::floor_kept_for_certain(within(before), within(after))
    }

    #[test]
    fn the_size_floor_kept_for_certain_is_the_rules_answer() {
        let mut rng = crate::numeric::SplitMix64::new(41);
        let kinds = [VolumeKind::Tet4, VolumeKind::Hex8, VolumeKind::Wedge6, VolumeKind::Pyramid5, VolumeKind::Hex20];
        for (kind, from_shapes) in kinds.into_iter().flat_map(|k| [(k, false), (k, true)]) {
            let ideal: Vec<DVec3> = kind.row().ideal.iter().map(|c| DVec3::from(*c)).collect();
            let (mut decided, mut moves) = (0, 0);
            for scale in [1e-70, 1e-20, 1e-3, 1.0, 7.5, 1e20, 1e70] {
                let mut r = || rng.next_f64() * 2.0 - 1.0;
                let before: Vec<DVec3> = ideal.iter().map(|c| (*c + 0.15 * DVec3::new(r(), r(), r())) * scale).collect();
                // a corner moved, as the drivers move one: ordinary steps and long ones that
                // press the element flat or through itself
                for corner in 0..kind.corners() {
                    for step in [0.05, 0.2, 0.5, 1.0, 2.0] {
                        let mut after = before.clone();
                        after[corner] += step * scale * DVec3::new(r(), r(), r());
                        let sure = certain(kind, &before, &after, from_shapes);
                        assert!(!sure || floor_kept(kind, &before, &after), "{kind:?} {before:?} -> {after:?}");
                        moves += 1;
                        decided += sure as usize;
                    }
                }
                // the whole element shrunk about its first corner to near the floor: the
                // rule's answer turns within a few ulps of s³ = 10⁻³
                for k in -64..=64 {
                    let s = (MIN_SIZE_RATIO * (1.0 + k as f64 * f64::EPSILON)).cbrt();
                    let after: Vec<DVec3> = before.iter().map(|p| before[0] + s * (*p - before[0])).collect();
                    let sure = certain(kind, &before, &after, from_shapes);
                    assert!(!sure || floor_kept(kind, &before, &after), "{kind:?} shrunk {k} ulps: {before:?}");
                }
                for f in [0.99, 1.01] {
                    let s = (f * MIN_SIZE_RATIO).cbrt();
                    let after: Vec<DVec3> = before.iter().map(|p| before[0] + s * (*p - before[0])).collect();
                    // decided where the two answers are a percent apart, as the rule's
                    assert_eq!(certain(kind, &before, &after, from_shapes), f > 1.0, "{kind:?} shrunk to {f}·floor");
                    assert_eq!(floor_kept(kind, &before, &after), f > 1.0);
                }
            }
            // the screen is worth its work: it decides most moves of a valid element
            assert!(decided * 10 > moves * 6, "{kind:?}: {decided} of {moves}");
        }
        // beyond the scales it takes, it decides nothing
        for (kind, from_shapes) in [VolumeKind::Tet4, VolumeKind::Hex8].into_iter().flat_map(|k| [(k, false), (k, true)]) {
            let p: Vec<DVec3> = kind.row().ideal.iter().map(|c| DVec3::from(*c) * 1e-90).collect();
            assert!(!certain(kind, &p, &p, from_shapes));
            let mut nan: Vec<DVec3> = p.iter().map(|c| *c * 1e90).collect();
            assert!(certain(kind, &nan, &nan, from_shapes));
            nan[3].y = f64::NAN;
            assert!(!certain(kind, &nan, &nan, from_shapes));
        }
    }

    /// The planar screen as the drivers' verdict uses it, against the rule's own answer:
    /// triangles (valid, which take the fast path, and inverted), quadrilaterals and
    /// quadratic triangles, at every scale the screen takes and beyond.
    #[test]
    fn the_planar_size_floor_kept_for_certain_is_the_rules_answer() {
        let mut rng = crate::numeric::SplitMix64::new(43);
        let floor_kept = |kind, b: &[DVec2; 9], a: &[DVec2; 9], m| ElementScore::planar(kind, a, m).size.at_least(MIN_SIZE_RATIO, &ElementScore::planar(kind, b, m).size);
        let certain = |kind, b: &[DVec2; 9], a: &[DVec2; 9], m| Size::floor_kept_for_certain(ElementScore::planar_unsized(kind, b, m).1, ElementScore::planar_unsized(kind, a, m).1);
        let ideal = |kind| -> [DVec2; 9] {
            let mut p = [DVec2::ZERO; 9];
            let corners: &[[f64; 2]] = match kind {
                ElementKind::Quad4 => &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
                _ => &[[0.0, 0.0], [1.0, 0.0], [0.5, 0.8660254037844386]],
            };
            for (q, c) in p.iter_mut().zip(corners) {
                *q = DVec2::from(*c);
            }
            if kind == ElementKind::Tri6 {
                for (k, (i, j)) in [(0, 1), (1, 2), (2, 0)].into_iter().enumerate() {
                    p[3 + k] = 0.5 * (p[i] + p[j]);
                }
            }
            p
        };
        let (mut decided, mut moves) = (0, 0);
        for kind in [ElementKind::Tri3, ElementKind::Quad4, ElementKind::Tri6] {
            for measure in [Measure::Shape, Measure::MinSine] {
                for scale in [1e-70, 1e-20, 1e-3, 1.0, 7.5, 1e20, 1e70] {
                    let mut r = || rng.next_f64() * 2.0 - 1.0;
                    let mut before = ideal(kind);
                    for q in &mut before[..kind.node_count()] {
                        *q = (*q + 0.15 * DVec2::new(r(), r())) * scale;
                    }
                    for corner in 0..kind.corners() {
                        for step in [0.05, 0.2, 0.5, 1.0, 2.0] {
                            let mut after = before;
                            after[corner] += step * scale * DVec2::new(r(), r());
                            let sure = certain(kind, &before, &after, measure);
                            assert!(!sure || floor_kept(kind, &before, &after, measure), "{kind:?} {before:?} -> {after:?}");
                            moves += 1;
                            decided += sure as usize;
                        }
                    }
                    for k in -64..=64 {
                        let s = (MIN_SIZE_RATIO * (1.0 + k as f64 * f64::EPSILON)).sqrt();
                        let after = before.map(|p| before[0] + s * (p - before[0]));
                        let sure = certain(kind, &before, &after, measure);
                        assert!(!sure || floor_kept(kind, &before, &after, measure), "{kind:?} shrunk {k} ulps: {before:?}");
                    }
                    for f in [0.99, 1.01] {
                        let s = (f * MIN_SIZE_RATIO).sqrt();
                        let after = before.map(|p| before[0] + s * (p - before[0]));
                        let sure = certain(kind, &before, &after, measure);
                        assert!(!sure || floor_kept(kind, &before, &after, measure));
                        // a valid element (the rule's floor is for those): decided where the
                        // two answers are a percent apart, as the rule's
                        if !ElementScore::planar(kind, &before, measure).inverted {
                            assert_eq!(sure, f > 1.0, "{kind:?} shrunk to {f}·floor");
                            assert_eq!(floor_kept(kind, &before, &after, measure), f > 1.0);
                        }
                    }
                }
            }
        }
        assert!(decided * 10 > moves * 6, "{decided} of {moves}");
        let tiny = ideal(ElementKind::Tri3).map(|p| p * 1e-90);
        assert!(!certain(ElementKind::Tri3, &tiny, &tiny, Measure::Shape));
        let mut nan = ideal(ElementKind::Quad4);
        assert!(certain(ElementKind::Quad4, &nan, &nan, Measure::Shape));
        // corners whose determinants are not numbers, before or after the others
        for k in 0..4 {
            let mut q = nan;
            q[k].y = f64::NAN;
            assert!(!certain(ElementKind::Quad4, &q, &q, Measure::Shape), "node {k}");
        }
        nan[2].y = f64::NAN;
        assert!(!certain(ElementKind::Quad4, &nan, &nan, Measure::Shape));
    }

    #[test]
    fn a_solids_size_is_its_smallest_corners() {
        // a hexahedron with one corner pressed in, at three scales: the size is a corner's,
        // every corner is at least as large, and the element's score reads it
        for scale in [1.0, 1e-3, 250.0] {
            let mut p: Vec<DVec3> = VolumeKind::Hex8.row().ideal.iter().take(8).map(|c| DVec3::from(*c) * scale).collect();
            p[6] -= DVec3::splat(0.3 * scale);
            let sizes = solid::CornerSizes::of(VolumeKind::Hex8, &p, |_| None);
            let least = Size::least_corner(VolumeKind::Hex8, &sizes);
            assert!(sizes.of_kind(VolumeKind::Hex8).iter().any(|&(unit, scale)| Size { unit, scale, dim: 3 } == least));
            for &(unit, scale) in sizes.of_kind(VolumeKind::Hex8) {
                assert!(Size { unit, scale, dim: 3 }.at_least(1.0, &least));
            }
            assert_eq!(ElementScore::solid(VolumeKind::Hex8, &p, Measure::Shape).size, least);
        }
    }
}
