//! An element's shape terms and sizes corner by corner, and its least corner determinant.
//! A corner that did not move keeps its terms, so the drivers measure only those that did.

use glam::DVec3;

use super::{corner_det, corner_tet, reach};
use crate::mesh::VolumeKind;
use crate::quality::tet as q3;

/// [`solid_shape`]'s terms, its measured corners' mean ratios in corner order, for an
/// element within the safe scale as it is (where each is a function of its own corner's
/// tetrahedron alone, so a corner that did not move keeps its term); with each corner's
/// Jacobian determinant from the same Jacobian, for the size screen
/// ([`least_corner_det`](Self::least_corner_det)).
///
/// [`solid_shape`]: super::solid_shape
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CornerShapes {
    terms: [f64; 8],
    /// `det A` of each measured corner: its weighted Jacobian's `σ = det T` over `det W⁻¹`
    /// (`σ` itself where `W = I`, a hexahedron's), within rounding of [`least_corner_det`]'s
    /// determinant taken directly.
    dets: [f64; 8],
    /// The element's [`reach`].
    reach: f64,
}

impl CornerShapes {
    /// No terms, for room that holds none yet.
    pub const NONE: CornerShapes = CornerShapes { terms: [f64::NAN; 8], dets: [f64::NAN; 8], reach: f64::NAN };
    /// Overwrites these terms with `other`'s, field by field: a whole copy (some 140
    /// bytes) is put together on the stack and moved with calls to `memcpy`, where these
    /// are moves in place.
    #[inline(always)]
    pub fn copy_from(&mut self, other: &CornerShapes) {
        self.terms = other.terms;
        self.dets = other.dets;
        self.reach = other.reach;
    }
    /// The terms of the element of `kind` with corners `p`, each corner's (term,
    /// determinant) from `kept(c)` where it gives them (a corner whose tetrahedron is as it
    /// was), else measured; `None` for an element beyond the safe scale, which
    /// [`solid_shape`] measures in its own scale.
    ///
    /// [`solid_shape`]: super::solid_shape
    pub fn of(kind: VolumeKind, p: &[DVec3], kept: impl Fn(usize) -> Option<(f64, f64)>) -> Option<CornerShapes> {
        let p = &p[..kind.corners()];
        let reach = reach(p);
        if crate::numeric::factors_beyond_safe_scale(reach).is_some() {
            return None;
        }
        let r = kind.reference();
        let (mut terms, mut dets) = ([0.0; 8], [0.0; 8]);
        // each measured corner's `q3::mean_ratio`, its Jacobians first and then their cube
        // roots: the same operations on each corner, but no corner waits on the last one's
        // cube root and division
        let mut parts = [None; 8];
        for (c, parts) in parts.iter_mut().enumerate().take(kind.row().corner_edges.len()) {
            match kept(c) {
                Some((t, d)) => (terms[c], dets[c]) = (t, d),
                None => *parts = Some(q3::MeanRatioParts::of(&corner_tet(kind, p, c), r)),
            }
        }
        for (c, parts) in parts.iter().enumerate() {
            if let Some(parts) = parts {
                terms[c] = parts.mean_ratio();
                dets[c] = if r.identity { parts.sigma } else { parts.sigma / r.det_w_inv };
            }
        }
        Some(CornerShapes { terms, dets, reach })
    }
    /// Corner `c`'s term.
    #[inline]
    pub fn term(&self, c: usize) -> f64 {
        self.terms[c]
    }
    /// Corner `c`'s term and determinant, as [`of`](Self::of) keeps them.
    #[inline]
    pub fn corner(&self, c: usize) -> (f64, f64) {
        (self.terms[c], self.dets[c])
    }
    /// [`solid_shape`] of the element of `kind` from its terms: the same sum in the same
    /// order, so the same bits.
    ///
    /// [`solid_shape`]: super::solid_shape
    pub fn shape(&self, kind: VolumeKind) -> f64 {
        let count = kind.row().corner_edges.len();
        self.terms[..count].iter().copied().sum::<f64>() / count as f64
    }
    /// [`least_corner_det`] of the element of `kind` from the corners' determinants here:
    /// not the same bits (each `det A` by another formula, rounding some 10⁻¹⁶ of the
    /// extent³), but within the same tolerance of each corner's size, some ten thousand
    /// times that rounding, which is all the size screen reads
    /// (`Size::floor_kept_for_certain`: where it decides, the rule's comparison of the
    /// sizes finds the same).
    pub fn least_corner_det(&self, kind: VolumeKind) -> Option<(f64, f64)> {
        let mut least = f64::INFINITY;
        for &d in &self.dets[..kind.row().corner_edges.len()] {
            if d.is_nan() {
                return None;
            }
            least = least.min(d);
        }
        least_det_within(least, self.reach)
    }
}

/// A corner's size as the acceptance rule reads it: `(unit, scale)`, its Jacobian
/// determinant `unit · scale³` with `scale` the largest component of its edges and `unit`
/// the determinant of the edges divided by it (so no product leaves the doubles).
#[inline]
pub fn corner_size(t: &[DVec3; 4]) -> (f64, f64) {
    let e = [t[1] - t[0], t[2] - t[0], t[3] - t[0]];
    let m = crate::numeric::largest_component(e);
    ((e[0] / m).dot((e[1] / m).cross(e[2] / m)), m)
}

/// The smallest of an element's measured corners' Jacobian determinants taken directly
/// (`(t₁ − t₀)·((t₂ − t₀) × (t₃ − t₀))` of each corner's tetrahedron, where [`corner_size`]
/// divides the edges by their largest component first), with its tolerance
/// ([`crate::quality::det_within`], the element's extent for the scale); `None` where a
/// corner's determinant is not a number or the extent is beyond the scales it takes.
pub fn least_corner_det(kind: VolumeKind, p: &[DVec3]) -> Option<(f64, f64)> {
    let p = &p[..kind.corners()];
    let reach = reach(p);
    let mut least = f64::INFINITY;
    for c in 0..kind.row().corner_edges.len() {
        let d = corner_det(&corner_tet(kind, p, c));
        if d.is_nan() {
            return None;
        }
        least = least.min(d);
    }
    least_det_within(least, reach)
}

/// The least corner determinant `least` of an element of reach `reach` with its tolerance
/// ([`crate::quality::det_within`], the element's extent for the scale).
#[inline]
fn least_det_within(least: f64, reach: f64) -> Option<(f64, f64)> {
    // every component of an edge between two corners is at most twice the reach from the
    // first corner (rounded up beyond the reach's own rounding)
    let extent = 2.0 * reach * (1.0 + 1e-9);
    crate::quality::det_within(least, extent, 3)
}

/// The sizes ([`corner_size`]) of an element's measured corners in corner order, as
/// [`CornerShapes`] holds the shape's terms: each a function of its own corner's
/// tetrahedron alone, so a corner that did not move keeps its size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CornerSizes([(f64, f64); 8]);

impl CornerSizes {
    /// The sizes of the element of `kind` with corners `p`, each corner's from `kept(c)`
    /// where it gives one, else measured.
    pub fn of(kind: VolumeKind, p: &[DVec3], kept: impl Fn(usize) -> Option<(f64, f64)>) -> CornerSizes {
        let mut s = [(0.0, 0.0); 8];
        for (c, s) in s.iter_mut().enumerate().take(kind.row().corner_edges.len()) {
            *s = kept(c).unwrap_or_else(|| corner_size(&corner_tet(kind, p, c)));
        }
        CornerSizes(s)
    }
    /// The measured corners' sizes of an element of `kind`, in corner order.
    #[inline]
    pub fn of_kind(&self, kind: VolumeKind) -> &[(f64, f64)] {
        &self.0[..kind.row().corner_edges.len()]
    }
}
