//! Element shape metrics: pure functions of an element's corner (and mid-side)
//! coordinates, and the mesh statistics built from them.
//!
//! Conventions (see `docs/formulas.md` §1):
//! - elements are counter-clockwise when valid; every metric is signed so an inverted
//!   element scores below a valid one;
//! - at corner `i` the two edge vectors are `e1` (towards the next corner) and `e2`
//!   (towards the previous corner); the corner's Jacobian is `[e1 e2]`, `det = cross(e1, e2)`;
//! - for quadratic elements `e1`, `e2` are the edges' end tangents scaled to chord length,
//!   `4M − 3P0 − P2`, the derivative at P0 of the edge curve over t ∈ [0, 1] (Chen et al.
//!   2003, §2.3: "interior angles and vectors at nodes are computed using the tangent vector
//!   of the quadratic edge at the given node"); for a straight edge this is exactly
//!   `P2 − P0`, so linear and quadratic agree (dets and lengths included).

use glam::{DMat2, DVec2};
use serde::Serialize;

use crate::mesh::ElementKind;
use crate::numeric::{is_beyond_safe_scale, to_unit_scale, SAFE_SCALE};

pub mod grading;
pub mod metric;
mod reading;
pub mod solid;
mod stats;
pub mod tet;

pub use reading::Reading;
pub use stats::{
    angle_bin, mesh_stats, mesh_stats_with, ElementStats, MeshCounts, MeshStats, MeshStatsBuilder, SolidStats, scaled_jacobian_bin, QuickStats,
};

/// `2√3`, Lo's normalisation so an equilateral triangle has α = 1.
pub const TWO_SQRT3: f64 = 3.464_101_615_137_754_6;

/// α of the right isosceles triangle, `√3/2`: Canann's normalisation so a square has β = 1.
pub const ALPHA_90: f64 = 0.866_025_403_784_438_6;

/// Lo's α of triangle ABC — Chen, Tristano & Kwok (2003), eq. (1):
/// `α = 2√3 · cross(B−A, C−A) / (|AB|² + |BC|² + |CA|²)`. In [−1, 1]; 1 for the
/// equilateral triangle, 0 when degenerate, negative when clockwise (inverted).
pub fn lo_alpha(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    let (e1, e2) = corner_edges(ElementKind::Tri3, &[a, b, c])[0];
    lo_alpha_corner(e1, e2)
}

/// Lo's α of the triangle spanned at a corner by edge vectors `e1`, `e2`:
/// `2√3·cross(e1,e2) / (|e1|² + |e2|² + |e2−e1|²)`. Used for quadratic elements with
/// the edge tangents as `e1`, `e2` (`docs/formulas.md` §1). A zero-size corner gives 0.
#[inline]
pub fn lo_alpha_corner(e1: DVec2, e2: DVec2) -> f64 {
    if let Some((e1, e2, _)) = beyond_safe_scale(e1, e2) {
        return lo_alpha_corner(e1, e2);
    }
    let den = e1.length_squared() + e2.length_squared() + (e2 - e1).length_squared();
    if den <= 0.0 {
        return 0.0;
    }
    TWO_SQRT3 * e1.perp_dot(e2) / den
}

/// A linear triangle's three corners' edge vectors (`(p[1] − p[0], p[2] − p[0])` at
/// corner 0, then round) with each side's squared length once, for the two corners it
/// bounds (the squares of a difference and of its negation are the same bits): the corner
/// metrics of a triangle taken together, each bit for bit the metric of that corner's
/// edges ([`lo_alpha_corner`], [`scaled_jacobian_gradient`]). A corner whose edges are
/// beyond 2^±200, which those bring to unit scale first, gives `None`: the caller then
/// takes the metric of that corner's edges.
#[derive(Clone, Copy, Debug)]
pub struct TriangleCorners {
    /// Corner j's edge towards the next corner, and towards the previous one.
    pub e1: [DVec2; 3],
    pub e2: [DVec2; 3],
    /// The largest component of `e1[j]`, and `|e1[j]|²` (which is also `|e2[j + 1]|²`).
    size: [f64; 3],
    side: [f64; 3],
}

impl TriangleCorners {
    #[inline(always)]
    pub fn of(p: &[DVec2; 3]) -> Self {
        let e1 = [p[1] - p[0], p[2] - p[1], p[0] - p[2]];
        let e2 = [p[2] - p[0], p[0] - p[1], p[1] - p[2]];
        TriangleCorners { e1, e2, size: e1.map(|e| e.x.abs().max(e.y.abs())), side: e1.map(|e| e.length_squared()) }
    }

    /// The corner before `j`, whose `e1` is corner j's `e2` negated.
    #[inline(always)]
    fn prev(j: usize) -> usize {
        (j + 2) % 3
    }

    /// Whether corner `j`'s edges are within 2^±200 (where the metrics take them as they are).
    #[inline(always)]
    fn safe(&self, j: usize) -> bool {
        !is_beyond_safe_scale(self.size[j].max(self.size[Self::prev(j)]))
    }

    /// [`lo_alpha_corner`] of corner `j`.
    #[inline(always)]
    pub fn lo_alpha(&self, j: usize) -> Option<f64> {
        if !self.safe(j) {
            return None;
        }
        let (e1, e2) = (self.e1[j], self.e2[j]);
        let den = self.side[j] + self.side[Self::prev(j)] + (e2 - e1).length_squared();
        Some(if den <= 0.0 { 0.0 } else { TWO_SQRT3 * e1.perp_dot(e2) / den })
    }

    /// [`scaled_jacobian_gradient`] of corner `j`, its value first (without its gradient
    /// when `GRADIENT` is false).
    #[inline(always)]
    pub fn scaled_jacobian<const GRADIENT: bool>(&self, j: usize) -> Option<(f64, DVec2, DVec2)> {
        if !self.safe(j) {
            return None;
        }
        Some(sine_and_gradient::<GRADIENT>(self.e1[j], self.e2[j], self.side[j], self.side[Self::prev(j)]))
    }
}

/// The three corner αs of linear triangle `p` ([`TriangleCorners`]).
#[inline(always)]
pub fn lo_alpha_triangle_corners(p: &[DVec2; 3]) -> Option<[f64; 3]> {
    let t = TriangleCorners::of(p);
    let mut alpha = [0.0; 3];
    for (j, a) in alpha.iter_mut().enumerate() {
        *a = t.lo_alpha(j)?;
    }
    Some(alpha)
}

/// Lo's corner α with its partial gradients with respect to the two edge vectors:
/// `(α, ∂α/∂e1, ∂α/∂e2)`. With `N = cross(e1,e2)` and `D = |e1|² + |e2|² + |e2−e1|²`,
/// `∂α/∂e = 2√3 (D ∂N/∂e − N ∂D/∂e) / D²`, `∂N/∂e1 = −perp(e2)`, `∂N/∂e2 = perp(e1)`,
/// `∂D/∂e1 = 4e1 − 2e2`, `∂D/∂e2 = 4e2 − 2e1`. A zero-size corner gives zeros.
#[inline]
pub fn lo_alpha_corner_gradient(e1: DVec2, e2: DVec2) -> (f64, DVec2, DVec2) {
    if let Some((e1, e2, f)) = beyond_safe_scale(e1, e2) {
        let (a, g1, g2) = lo_alpha_corner_gradient(e1, e2);
        return (a, gradient_back(g1, f), gradient_back(g2, f));
    }
    let den = e1.length_squared() + e2.length_squared() + (e2 - e1).length_squared();
    if den <= 0.0 {
        return (0.0, DVec2::ZERO, DVec2::ZERO);
    }
    let num = e1.perp_dot(e2);
    let k = TWO_SQRT3 / (den * den);
    let g1 = k * (den * -e2.perp() - num * (4.0 * e1 - 2.0 * e2));
    let g2 = k * (den * e1.perp() - num * (4.0 * e2 - 2.0 * e1));
    (TWO_SQRT3 * num / den, g1, g2)
}

/// Canann's β of quad abcd — Chen et al. (2003), eq. (2): the α of the four triangles
/// of both diagonals, `β = min(α1..α4)/α90 − n_neg`. 1 for the square.
pub fn canann_beta(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> f64 {
    // corner i of corner_edges is (next − this, previous − this): (b − a, d − a) at a, …
    canann_beta_from_corners(&corner_edges(ElementKind::Quad4, &[a, b, c, d]))
}

/// β from the four corners' edge vectors. The triangle (a,b,c) of eq. (2) is the corner
/// triangle at b, (c,d,a) the one at d, (a,b,d) at a and (b,c,d) at c; so β is the
/// minimum corner α over α90, less the number of negative corner αs.
pub fn canann_beta_from_corners(corners: &[(DVec2, DVec2); 4]) -> f64 {
    let mut min = f64::INFINITY;
    let mut neg = 0;
    for &(e1, e2) in corners {
        let a = lo_alpha_corner(e1, e2);
        min = min.min(a);
        if a < 0.0 {
            neg += 1;
        }
    }
    min / ALPHA_90 - neg as f64
}

/// Signed angle at a corner from `e1` to `e2`: `atan2(cross, dot)`, in (−π, π].
/// Negative means the corner is inverted.
#[inline]
pub fn signed_angle(e1: DVec2, e2: DVec2) -> f64 {
    if let Some((e1, e2, _)) = beyond_safe_scale(e1, e2) {
        return signed_angle(e1, e2);
    }
    crate::numeric::elementary::atan2(e1.perp_dot(e2), e1.dot(e2))
}

/// The signed corner angle with its partial gradients: `(θ, ∂θ/∂e1, ∂θ/∂e2)`.
/// `θ = arg e2 − arg e1` and `∇ arg v = perp(v)/|v|²`, so `∂θ/∂e1 = −perp(e1)/|e1|²`,
/// `∂θ/∂e2 = perp(e2)/|e2|²`. Defined away from the jump at θ = ±π (where the gradient
/// is the same on both sides) and from zero-length edges (zeros there).
#[inline]
pub fn signed_angle_gradient(e1: DVec2, e2: DVec2) -> (f64, DVec2, DVec2) {
    if let Some((e1, e2, f)) = beyond_safe_scale(e1, e2) {
        let (a, g1, g2) = signed_angle_gradient(e1, e2);
        return (a, gradient_back(g1, f), gradient_back(g2, f));
    }
    let (l1, l2) = (e1.length_squared(), e2.length_squared());
    if l1 <= 0.0 || l2 <= 0.0 {
        return (signed_angle(e1, e2), DVec2::ZERO, DVec2::ZERO);
    }
    (signed_angle(e1, e2), -e1.perp() / l1, e2.perp() / l2)
}

/// The corner determinant `cross(e1, e2)` without NaN: where the products overflow (edges
/// beyond about 1e154) it is computed in unit scale and scaled back, giving `±∞` (or `±0`
/// where it underflows) of the right sign instead of `∞ − ∞`.
#[inline]
pub fn corner_det(e1: DVec2, e2: DVec2) -> f64 {
    match beyond_safe_scale(e1, e2) {
        None => e1.perp_dot(e2),
        Some((u1, u2, f)) => {
            let back = 1.0 / (f[0] * f[1]);
            if back.is_finite() && back != 0.0 {
                u1.perp_dot(u2) * back * back
            } else {
                // the factor itself is beyond the doubles: one step at a time
                u1.perp_dot(u2) / f[0] / f[0] / f[1] / f[1]
            }
        }
    }
}

/// Which ideal element the condition number is measured against.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ideal {
    /// The equilateral triangle: `W = [[1, 1/2], [0, √3/2]]`.
    Triangle,
    /// The square: `W = I`.
    Square,
}

/// Knupp's condition number of the corner Jacobian `A = [e1 e2]` weighted by the ideal
/// element, `T = A·W⁻¹`: `κ(T) = ‖T‖²_F / det T` (Knupp 1999, §§3–4, 2D). 2 for the
/// ideal corner; `+∞` when `det T ≤ 0` (the barrier).
pub fn condition_number(e1: DVec2, e2: DVec2, ideal: Ideal) -> f64 {
    if let Some((e1, e2, _)) = beyond_safe_scale(e1, e2) {
        return condition_number(e1, e2, ideal);
    }
    let (t1, t2) = weighted_columns(e1, e2, ideal);
    let t = DMat2::from_cols(t1, t2);
    // the barrier: an inverted corner is not its mirror image here
    if t.determinant() <= 0.0 {
        return f64::INFINITY;
    }
    metric::condition_number(&t)
}

/// Knupp's corner condition number with its partial gradients,
/// `(κ, ∂κ/∂e1, ∂κ/∂e2)`. With `T = [t1 t2]`, `F = |t1|² + |t2|²`, `δ = cross(t1,t2)`:
/// `∂κ/∂t1 = 2t1/δ + F perp(t2)/δ²`, `∂κ/∂t2 = 2t2/δ − F perp(t1)/δ²`, then through
/// `t2 = (2e2 − e1)/√3` for the triangle ideal. `(+∞, 0, 0)` when `det T ≤ 0` (the barrier).
pub fn condition_number_gradient(e1: DVec2, e2: DVec2, ideal: Ideal) -> (f64, DVec2, DVec2) {
    if let Some((e1, e2, f)) = beyond_safe_scale(e1, e2) {
        let (k, g1, g2) = condition_number_gradient(e1, e2, ideal);
        return (k, gradient_back(g1, f), gradient_back(g2, f));
    }
    let (t1, t2) = weighted_columns(e1, e2, ideal);
    let det = t1.perp_dot(t2);
    if det <= 0.0 {
        return (f64::INFINITY, DVec2::ZERO, DVec2::ZERO);
    }
    let f = t1.length_squared() + t2.length_squared();
    let kappa = f / det;
    let g1 = (2.0 * t1 + kappa * t2.perp()) / det;
    let g2 = (2.0 * t2 - kappa * t1.perp()) / det;
    match ideal {
        Ideal::Square => (kappa, g1, g2),
        Ideal::Triangle => {
            const INV_SQRT3: f64 = 0.577_350_269_189_625_8;
            (kappa, g1 - INV_SQRT3 * g2, 2.0 * INV_SQRT3 * g2)
        }
    }
}

/// The scaled Jacobian (sine of the corner angle) with its partial gradients,
/// `(s, ∂s/∂e1, ∂s/∂e2)`: `s = N/(|e1||e2|)`, `∂s/∂e1 = −perp(e2)/(|e1||e2|) − s e1/|e1|²`,
/// `∂s/∂e2 = perp(e1)/(|e1||e2|) − s e2/|e2|²`. Zeros for a zero-length edge.
pub fn scaled_jacobian_gradient(e1: DVec2, e2: DVec2) -> (f64, DVec2, DVec2) {
    if let Some((e1, e2, f)) = beyond_safe_scale(e1, e2) {
        let (v, g1, g2) = scaled_jacobian_gradient(e1, e2);
        return (v, gradient_back(g1, f), gradient_back(g2, f));
    }
    sine_and_gradient::<true>(e1, e2, e1.length_squared(), e2.length_squared())
}

/// [`scaled_jacobian_gradient`] at unit scale from the edges' squared lengths `l1`, `l2`
/// (its gradient left zero when `GRADIENT` is false).
#[inline(always)]
fn sine_and_gradient<const GRADIENT: bool>(e1: DVec2, e2: DVec2, l1: f64, l2: f64) -> (f64, DVec2, DVec2) {
    let (s, g) = metric::scaled_jacobian_with::<_, GRADIENT>(&DMat2::from_cols(e1, e2), |i| [l1, l2][i]);
    (s, g.x_axis, g.y_axis)
}

/// Columns of `T = [e1 e2]·W⁻¹`. For the triangle `W⁻¹ = [[1, −1/√3], [0, 2/√3]]`.
pub fn weighted_columns(e1: DVec2, e2: DVec2, ideal: Ideal) -> (DVec2, DVec2) {
    match ideal {
        Ideal::Square => (e1, e2),
        Ideal::Triangle => {
            const INV_SQRT3: f64 = 0.577_350_269_189_625_8;
            (e1, (2.0 * e2 - e1) * INV_SQRT3)
        }
    }
}

/// Scaled Jacobian of a corner: `cross(e1,e2) / (|e1||e2|)`, the sine of the signed
/// corner angle. 0 for a zero-length edge.
pub fn scaled_jacobian(e1: DVec2, e2: DVec2) -> f64 {
    if let Some((e1, e2, _)) = beyond_safe_scale(e1, e2) {
        return scaled_jacobian(e1, e2);
    }
    metric::scaled_jacobian(&DMat2::from_cols(e1, e2))
}

/// Edge vectors `(e1, e2)` at each corner of an element, from its node coordinates in
/// the element's node order (tangents for quadratic elements), in the element's own
/// scale: multiplied by a power of two that brings the largest component to [1, 2). Every
/// metric here is a ratio of lengths, so its value is that of the element as given; the
/// power of two is exact, so for elements of ordinary size the values are bit for bit
/// those of the raw edges, and at sizes near 1e±200, where squared lengths and cross
/// products over- or underflowed (α null, κ 0, a valid triangle "inverted"), they are
/// still right. Only the first `kind.corners()` entries are meaningful.
#[inline]
pub fn corner_edges(kind: ElementKind, p: &[DVec2]) -> [(DVec2, DVec2); 4] {
    // Ordinary elements: the edges as they are. Their components lie within 2^±200, where
    // every product the metrics take is a normal double, so each scale-free result (a
    // ratio, an angle, a sign) has exactly the bits it has at unit scale.
    let k = kind.corners();
    let raw = corner_edge_vectors(kind, p);
    let m = crate::numeric::largest_component(raw[..k].iter().flat_map(|(a, b)| [*a, *b]));
    if SAFE_SCALE.contains(&m) {
        return raw;
    }
    // the points in units of their magnitude, so that the differences (and the tangents'
    // 4M − 3P0 − P2) cannot overflow, then the edges in units of their own size
    let mut q = [DVec2::ZERO; 9];
    let n = p.len().min(9);
    q[..n].copy_from_slice(&p[..n]);
    to_unit_scale(&mut q[..n]);
    let mut out = corner_edge_vectors(kind, &q[..n]);
    let mut flat = [DVec2::ZERO; 8];
    for i in 0..k {
        (flat[2 * i], flat[2 * i + 1]) = out[i];
    }
    to_unit_scale(&mut flat[..2 * k]);
    for i in 0..k {
        out[i] = (flat[2 * i], flat[2 * i + 1]);
    }
    out
}

/// Corner edge vectors brought to unit scale when their size is beyond 2^±200, where the
/// metrics' squares and products of squares would over- or underflow: `(e1, e2, f)` with
/// the factors `f` (as [`to_unit_scale`] returns them), `None` when they are fine as they
/// are (so ordinary elements take no detour and keep their bits).
#[inline]
fn beyond_safe_scale(e1: DVec2, e2: DVec2) -> Option<(DVec2, DVec2, [f64; 2])> {
    let m = e1.x.abs().max(e1.y.abs()).max(e2.x.abs()).max(e2.y.abs());
    if !is_beyond_safe_scale(m) {
        return None;
    }
    let mut v = [e1, e2];
    let f = to_unit_scale(&mut v);
    Some((v[0], v[1], f))
}

/// A gradient taken at edges multiplied by `f` (see [`beyond_safe_scale`]) brought back to
/// the edges as given, for a metric that is a ratio of lengths: `∂q/∂e = f ∂q/∂(f e)`.
#[inline]
fn gradient_back(g: DVec2, f: [f64; 2]) -> DVec2 {
    g * f[0] * f[1]
}

/// An element's least corner determinant `det`, taken directly from edges whose largest
/// component is at most `scale`, with how far the acceptance rule's size (`unit · scaleᵈ`,
/// `unit` from the edges divided by their largest component) may lie from it: `10⁻¹²
/// scaleᵈ`, some hundred times the rounding of either. `None` where `det` is not a number
/// or `scale` lies outside [10⁻⁸⁰, 10⁸⁰], where the products could leave the doubles'
/// normal range. For the rule's screen of its size floor (`smooth::Size::floor_kept_for_certain`).
#[inline]
pub fn det_within(det: f64, scale: f64, dim: i32) -> Option<(f64, f64)> {
    ((1e-80..=1e80).contains(&scale) && !det.is_nan()).then_some((det, 1e-12 * scale.powi(dim)))
}

/// The corner edge vectors of [`corner_edges`] in the mesh's own units (the objectives'
/// derivatives need the true lengths): chords, or for quadratic elements the end tangents
/// `4M − 3P0 − P2`.
#[inline]
pub fn corner_edge_vectors(kind: ElementKind, p: &[DVec2]) -> [(DVec2, DVec2); 4] {
    let k = kind.corners();
    let mut out = [(DVec2::ZERO, DVec2::ZERO); 4];
    for i in 0..k {
        let next = (i + 1) % k;
        let prev = (i + k - 1) % k;
        out[i] = match (kind.mid(i), kind.mid(prev)) {
            (Some(m_next), Some(m_prev)) => {
                (4.0 * p[m_next] - 3.0 * p[i] - p[next], 4.0 * p[m_prev] - 3.0 * p[i] - p[prev])
            }
            _ => (p[next] - p[i], p[prev] - p[i]),
        };
    }
    out
}

/// Every metric of one element, computed at once from its corner edge vectors.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ElementQuality {
    /// α for triangles (minimum corner α; equal at all corners when straight-sided),
    /// β for quads.
    pub shape: f64,
    /// Smallest and largest signed corner angle, radians.
    pub min_angle: f64,
    pub max_angle: f64,
    /// Smallest sine of the corner angles (Freitag's measure).
    pub min_sine: f64,
    /// Largest corner condition number κ (∞ when any corner is inverted).
    pub condition: f64,
    /// Smallest corner scaled Jacobian; for triangles scaled by 2/√3 so the equilateral
    /// triangle has 1.
    pub scaled_jacobian: f64,
    /// Any corner with `det ≤ 0`.
    pub inverted: bool,
}

impl ElementQuality {
    /// `2/κ`, a shape quality in [0, 1] (0 when inverted).
    pub fn inverse_condition(&self) -> f64 {
        if self.condition.is_finite() {
            2.0 / self.condition
        } else {
            0.0
        }
    }
}

/// All metrics of an element of `kind` with node coordinates `p` (element node order).
///
/// ```
/// use glam::DVec2;
/// use smoothlab::quality::element_quality;
/// use smoothlab::ElementKind;
///
/// // the equilateral triangle: every angle 60°, Lo's α = 1, Knupp's κ = 2
/// let p = [DVec2::ZERO, DVec2::X, DVec2::new(0.5, 3f64.sqrt() / 2.0)];
/// let q = element_quality(ElementKind::Tri3, &p);
/// assert!((q.min_angle.to_degrees() - 60.0).abs() < 1e-9);
/// assert!((q.shape - 1.0).abs() < 1e-12 && (q.condition - 2.0).abs() < 1e-12);
/// assert!(!q.inverted);
/// ```
pub fn element_quality(kind: ElementKind, p: &[DVec2]) -> ElementQuality {
    measure_element::<true, true, true>(kind, p, |_, _, _| {})
}

/// The one per-corner loop behind every element measure (statistics, the smoothers' star
/// measures, the mesh view, the page's statistics): the corner edges of `kind` at `p`, then
/// per corner `on_corner(e1, e2, angle)` (the signed angle with `ANGLES`, NaN without;
/// e.g. for a histogram), the signed angle's extremes (`ANGLES`), the sine and
/// scaled Jacobian (`SINES`), the condition number (`CONDITION`), the inverted test and
/// Lo's α; β for quads. What a caller does not ask for is left at its starting value
/// (angles ±∞, sines +∞, condition 0) and costs nothing: the flags are constants.
#[inline]
pub fn measure_element<const ANGLES: bool, const CONDITION: bool, const SINES: bool>(
    kind: ElementKind,
    p: &[DVec2],
    mut on_corner: impl FnMut(DVec2, DVec2, f64),
) -> ElementQuality {
    let k = kind.corners();
    let ce = corner_edges(kind, p);
    let ideal = if k == 3 { Ideal::Triangle } else { Ideal::Square };
    let mut q = ElementQuality {
        shape: 0.0,
        min_angle: f64::INFINITY,
        max_angle: f64::NEG_INFINITY,
        min_sine: f64::INFINITY,
        condition: 0.0,
        scaled_jacobian: f64::INFINITY,
        inverted: false,
    };
    let mut min_alpha = f64::INFINITY;
    for &(e1, e2) in &ce[..k] {
        let ang = if ANGLES { signed_angle(e1, e2) } else { f64::NAN };
        if ANGLES {
            q.min_angle = q.min_angle.min(ang);
            q.max_angle = q.max_angle.max(ang);
        }
        on_corner(e1, e2, ang);
        if SINES {
            let s = scaled_jacobian(e1, e2);
            q.min_sine = q.min_sine.min(s);
            q.scaled_jacobian = q.scaled_jacobian.min(s);
        }
        if CONDITION {
            q.condition = q.condition.max(condition_number(e1, e2, ideal));
        }
        q.inverted |= e1.perp_dot(e2) <= 0.0;
        if k == 3 {
            min_alpha = min_alpha.min(lo_alpha_corner(e1, e2));
        }
    }
    if k == 3 {
        q.shape = min_alpha;
        q.scaled_jacobian *= 2.0 / 3f64.sqrt();
    } else {
        q.shape = canann_beta_from_corners(&ce);
    }
    q
}

#[cfg(test)]
mod tests {
    use super::*;

    use std::f64::consts::PI;

    fn d(x: f64, y: f64) -> DVec2 {
        DVec2::new(x, y)
    }
    const EPS: f64 = 1e-12;

    #[test]
    fn a_triangles_corner_metrics_together_are_each_corners_bit_for_bit() {
        let mut rng = crate::numeric::SplitMix64::new(33);
        let mut taken = 0;
        for n in 0..20000 {
            // random, near-degenerate, repeated points, huge and tiny scales, NaN
            let scale = [1.0, 1e-3, 1e40, 1e-40, 1e100, 1e-100][n % 6];
            let mut p = [0; 3].map(|_| d(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)) * scale);
            match n % 7 {
                1 => p[2] = p[0],
                2 => p[2] = (p[0] + p[1]) * 0.5,
                3 => p[1].x = f64::NAN,
                4 => p[0] = d(0.0, 0.0),
                _ => {}
            }
            let edges = |j: usize| (p[(j + 1) % 3] - p[j], p[(j + 2) % 3] - p[j]);
            let each = [0, 1, 2].map(|j| lo_alpha_corner(edges(j).0, edges(j).1));
            let bits = |(s, g1, g2): (f64, DVec2, DVec2)| [s, g1.x, g1.y, g2.x, g2.y].map(f64::to_bits);
            let t = TriangleCorners::of(&p);
            match lo_alpha_triangle_corners(&p) {
                Some(together) => {
                    taken += 1;
                    assert_eq!(together.map(f64::to_bits), each.map(f64::to_bits), "{p:?}");
                    for j in 0..3 {
                        let sine = scaled_jacobian_gradient(edges(j).0, edges(j).1);
                        assert_eq!(t.scaled_jacobian::<true>(j).map(bits), Some(bits(sine)), "{p:?}");
                        assert_eq!(t.scaled_jacobian::<false>(j).map(|s| s.0.to_bits()), Some(sine.0.to_bits()));
                    }
                }
                // beyond 2^±200 (about 1.6e±60)
                None => {
                    assert!(!(1e-60..=1e60).contains(&scale), "refused at scale {scale}: {p:?}");
                    assert!((0..3).any(|j| t.scaled_jacobian::<false>(j).is_none()));
                }
            }
        }
        assert!(taken > 13000, "{taken}");
    }

    fn equilateral() -> [DVec2; 3] {
        [d(0.0, 0.0), d(1.0, 0.0), d(0.5, 3f64.sqrt() / 2.0)]
    }

    #[test]
    fn hand_derived_values() {
        let [a, b, c] = equilateral();
        assert!((lo_alpha(a, b, c) - 1.0).abs() < EPS);
        // right isosceles: 2√3·1 / (1 + 1 + 2) = √3/2
        assert!((lo_alpha(d(0.0, 0.0), d(1.0, 0.0), d(0.0, 1.0)) - 3f64.sqrt() / 2.0).abs() < EPS);
        // reflected: negative
        assert!((lo_alpha(a, c, b) + 1.0).abs() < EPS);
        // square
        assert!((canann_beta(d(0.0, 0.0), d(1.0, 0.0), d(1.0, 1.0), d(0.0, 1.0)) - 1.0).abs() < EPS);
        // ideal triangle κ = 2, square κ = 2
        let q = element_quality(ElementKind::Tri3, &equilateral());
        assert!((q.condition - 2.0).abs() < 1e-12, "{}", q.condition);
        assert!((q.inverse_condition() - 1.0).abs() < 1e-12);
        assert!((q.scaled_jacobian - 1.0).abs() < 1e-12);
        assert!((q.min_angle - PI / 3.0).abs() < 1e-12 && (q.max_angle - PI / 3.0).abs() < 1e-12);
        let sq = [d(0.0, 0.0), d(1.0, 0.0), d(1.0, 1.0), d(0.0, 1.0)];
        let q = element_quality(ElementKind::Quad4, &sq);
        assert!((q.condition - 2.0).abs() < EPS && (q.shape - 1.0).abs() < EPS && !q.inverted);
        // right isosceles triangle: κ at the right-angle corner of T = A W^-1 with
        // A = I: T = [[1, -1/√3], [0, 2/√3]], |T|² = 1 + 1/3 + 4/3 = 8/3, det = 2/√3 → κ = 4/√3
        let ri = [d(0.0, 0.0), d(1.0, 0.0), d(0.0, 1.0)];
        assert!((condition_number(ri[1] - ri[0], ri[2] - ri[0], Ideal::Triangle) - 4.0 / 3f64.sqrt()).abs() < EPS);
    }

    #[test]
    fn inverted_elements_are_flagged() {
        let [a, b, c] = equilateral();
        let q = element_quality(ElementKind::Tri3, &[a, c, b]);
        assert!(q.inverted && q.shape < 0.0 && q.condition.is_infinite() && q.min_angle < 0.0);
        // a bow-tie quad: two negative corner triangles
        let bow = [d(0.0, 0.0), d(1.0, 0.0), d(0.0, 1.0), d(1.0, 1.0)];
        let q = element_quality(ElementKind::Quad4, &bow);
        assert!(q.inverted && q.shape < -1.0, "{}", q.shape);
        // zero-area triangle counts as inverted (det = 0), α = 0
        let q = element_quality(ElementKind::Tri3, &[d(0.0, 0.0), d(1.0, 0.0), d(2.0, 0.0)]);
        assert!(q.inverted && q.shape == 0.0);
        // coincident nodes: no NaN
        let q = element_quality(ElementKind::Tri3, &[d(1.0, 1.0), d(1.0, 1.0), d(1.0, 1.0)]);
        assert!(q.inverted && q.shape == 0.0 && !q.min_sine.is_nan());
    }

    #[test]
    fn invariant_under_translation_rotation_and_scale() {
        let tri = [d(0.1, 0.2), d(1.3, -0.1), d(0.4, 0.9)];
        let quad = [d(0.0, 0.0), d(1.2, 0.1), d(1.0, 0.8), d(-0.1, 1.1)];
        let q0t = element_quality(ElementKind::Tri3, &tri);
        let q0q = element_quality(ElementKind::Quad4, &quad);
        for (ang, s, t) in [(0.3, 2.5, d(4.0, -7.0)), (2.0, 1e-3, d(-1e3, 5.0)), (-1.1, 1e4, d(0.0, 0.0))] {
            let r = DVec2::from_angle(ang);
            let map = |p: &DVec2| r.rotate(*p) * s + t;
            let tq = element_quality(ElementKind::Tri3, &tri.iter().map(map).collect::<Vec<_>>());
            let qq = element_quality(ElementKind::Quad4, &quad.iter().map(map).collect::<Vec<_>>());
            for (a, b) in [(q0t, tq), (q0q, qq)] {
                assert!((a.shape - b.shape).abs() < 1e-9);
                assert!((a.min_angle - b.min_angle).abs() < 1e-9);
                assert!((a.condition - b.condition).abs() < 1e-9 * a.condition);
                assert!((a.scaled_jacobian - b.scaled_jacobian).abs() < 1e-9);
            }
        }
    }

    #[test]
    fn quadratic_straight_edges_match_linear() {
        let [a, b, c] = equilateral();
        let p6 = [a, b, c, (a + b) / 2.0, (b + c) / 2.0, (c + a) / 2.0];
        let q6 = element_quality(ElementKind::Tri6, &p6);
        assert!((q6.shape - 1.0).abs() < EPS);
        // bowing one edge outward lowers the corner angles' quality
        let mut bent = p6;
        bent[3] += d(0.0, -0.2);
        let qb = element_quality(ElementKind::Tri6, &bent);
        assert!(qb.shape < 0.95 && qb.max_angle > q6.max_angle);
        let sq = [d(0.0, 0.0), d(1.0, 0.0), d(1.0, 1.0), d(0.0, 1.0)];
        let mut p8 = [DVec2::ZERO; 9];
        p8[..4].copy_from_slice(&sq);
        for i in 0..4 {
            p8[4 + i] = (sq[i] + sq[(i + 1) % 4]) / 2.0;
        }
        p8[8] = d(0.5, 0.5);
        assert!((element_quality(ElementKind::Quad8, &p8[..8]).shape - 1.0).abs() < EPS);
        assert!((element_quality(ElementKind::Quad9, &p8).shape - 1.0).abs() < EPS);
    }

    #[test]
    fn straight_quadratic_tangents_are_the_chords() {
        let [a, b, c] = equilateral();
        let p6 = [a, b, c, (a + b) / 2.0, (b + c) / 2.0, (c + a) / 2.0];
        let lin = corner_edges(ElementKind::Tri3, &p6[..3]);
        let quad = corner_edges(ElementKind::Tri6, &p6);
        for i in 0..3 {
            assert!((lin[i].0 - quad[i].0).length() < EPS && (lin[i].1 - quad[i].1).length() < EPS);
        }
    }

    /// Central differences of a function of `(e1, e2)` with respect to each component.
    fn fd(f: impl Fn(DVec2, DVec2) -> f64, e1: DVec2, e2: DVec2) -> (DVec2, DVec2) {
        let h = 1e-6;
        let dx = d(h, 0.0);
        let dy = d(0.0, h);
        let c = |a: f64, b: f64| (a - b) / (2.0 * h);
        (
            d(c(f(e1 + dx, e2), f(e1 - dx, e2)), c(f(e1 + dy, e2), f(e1 - dy, e2))),
            d(c(f(e1, e2 + dx), f(e1, e2 - dx)), c(f(e1, e2 + dy), f(e1, e2 - dy))),
        )
    }

    #[test]
    fn metric_gradients_match_central_differences() {
        let corners = [
            (d(1.0, 0.1), d(0.3, 0.9)),
            (d(2.0, -0.5), d(-0.4, 1.3)),
            (d(0.7, 0.2), d(0.9, -0.6)),  // inverted
            (d(-1.0, 0.05), d(1.0, 0.3)), // near 180°
            (d(0.01, 1.0), d(-1.0, 0.02)),
        ];
        let close = |a: DVec2, b: DVec2, scale: f64| (a - b).length() <= 1e-6 * scale.max(1.0);
        for (e1, e2) in corners {
            let (v, g1, g2) = lo_alpha_corner_gradient(e1, e2);
            assert!((v - lo_alpha_corner(e1, e2)).abs() < EPS);
            let (f1, f2) = fd(lo_alpha_corner, e1, e2);
            assert!(close(g1, f1, 1.0) && close(g2, f2, 1.0), "α {g1} {f1} {g2} {f2}");

            let (v, g1, g2) = signed_angle_gradient(e1, e2);
            assert!((v - signed_angle(e1, e2)).abs() < EPS);
            let (f1, f2) = fd(signed_angle, e1, e2);
            assert!(close(g1, f1, 1.0) && close(g2, f2, 1.0), "θ {g1} {f1} {g2} {f2}");

            let (v, g1, g2) = scaled_jacobian_gradient(e1, e2);
            assert!((v - scaled_jacobian(e1, e2)).abs() < EPS);
            let (f1, f2) = fd(scaled_jacobian, e1, e2);
            assert!(close(g1, f1, 1.0) && close(g2, f2, 1.0), "sine {g1} {f1} {g2} {f2}");

            for ideal in [Ideal::Triangle, Ideal::Square] {
                let (v, g1, g2) = condition_number_gradient(e1, e2, ideal);
                let k = condition_number(e1, e2, ideal);
                if k.is_finite() {
                    assert!((v - k).abs() < EPS * k);
                    let (f1, f2) = fd(|a, b| condition_number(a, b, ideal), e1, e2);
                    let s = g1.length() + g2.length();
                    assert!(close(g1, f1, s) && close(g2, f2, s), "κ {g1} {f1} {g2} {f2}");
                } else {
                    assert!(v.is_infinite() && g1 == DVec2::ZERO && g2 == DVec2::ZERO);
                }
            }
        }
        // the ideal corners are stationary points of κ (Knupp 1999, §2.6)
        let (k, g1, g2) = condition_number_gradient(d(1.0, 0.0), d(0.5, 3f64.sqrt() / 2.0), Ideal::Triangle);
        assert!((k - 2.0).abs() < EPS && g1.length() + g2.length() < 1e-12);
    }
}
