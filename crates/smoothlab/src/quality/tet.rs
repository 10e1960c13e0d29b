//! Quality of a linear tetrahedron, from its four corners: signed volume, the six
//! dihedral angles and their sines (Freitag 1997), Knupp's condition number and the mean
//! ratio of a corner against its reference matrix W (Knupp 1999, §3: a parameter,
//! [`CornerReference`], the equilateral tetrahedron's [`EQUILATERAL_TET`] for both kinds
//! of tetrahedra, computed once per kind); each a pure function of the corners, with its gradient with respect to corner 0 (the free node:
//! callers put it first by an even permutation, [`with_first`], which keeps the volume's
//! sign).
//!
//! A tetrahedron `(p0, p1, p2, p3)` is valid (right-handed) when its signed volume
//! `V = (p1 − p0)·((p2 − p0)×(p3 − p0))/6` is positive, inverted when `V ≤ 0`.
//!
//! The formulas, in one notation: `docs/formulas.md` §8.

use glam::{DMat3, DVec3};

/// The six edges in the order of [`dihedral_angles`] and [`dihedral_sines`]: 01, 02, 03,
/// 12, 13, 23.
pub const TET_EDGES: [[usize; 2]; 6] = [[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]];

/// The corners not on each edge of [`TET_EDGES`]: the dihedral angle at edge `ij` is the
/// angle between the faces opposite `k` and `l`.
const OFF_EDGE: [[usize; 2]; 6] = [[2, 3], [1, 3], [1, 2], [0, 3], [0, 2], [0, 1]];

pub use crate::mesh::{CornerReference, EQUILATERAL_TET, EQUILATERAL_W, EQUILATERAL_W_INVERSE};

/// Signed volume `(p1 − p0)·((p2 − p0)×(p3 − p0))/6`: positive for a valid (right-handed)
/// tetrahedron.
#[inline]
pub fn signed_volume(p: &[DVec3; 4]) -> f64 {
    (p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0])) / 6.0
}

/// Whether the tetrahedron is inverted: `V ≤ 0` (zero volume included), or its volume is
/// not a number. Measured in the tetrahedron's own scale ([`in_unit_scale`]), so a valid
/// tetrahedron whose volume over- or underflows the doubles is not called inverted; and
/// where the rounded volume lies within its rounding of 0, by the exact sign of the
/// doubles as given ([`orient3d`](crate::numeric::exact::orient3d), issue 61).
#[inline]
pub fn is_inverted(p: &[DVec3; 4]) -> bool {
    let q = in_unit_scale(p);
    let v = signed_volume(&q);
    if v.is_nan() {
        return true;
    }
    // 6V is a sum of products of edges, the edges differences of coordinates: its
    // rounding is some 10⁻¹⁴ r²(r + M); beyond 2⁻⁴⁰ r²(r + M) the rounded sign is exact
    let r = crate::numeric::largest_component([q[1] - q[0], q[2] - q[0], q[3] - q[0]]);
    let m = crate::numeric::largest_component(q);
    if (6.0 * v).abs() > 2f64.powi(-40) * r * r * (r + m) {
        return v <= 0.0;
    }
    crate::numeric::exact::orient3d(p[0], p[1], p[2], p[3]) != std::cmp::Ordering::Greater
}

/// What the acceptance rule reads of a tetrahedron besides its quality (the drivers'
/// element score): whether it is inverted ([`is_inverted`]), its inversion
/// `max(0, −det)`, and the determinant of its edges `det` taken directly with their largest
/// component `scale`, from which the rule decides its size floor where they decide beyond
/// their rounding ([`det_within`](Self::det_within)); its size as the rule compares it
/// otherwise is `quality::solid::corner_size`'s, taken then.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TetRuleMeasures {
    pub inverted: bool,
    pub inversion: f64,
    pub det: f64,
    pub scale: f64,
}

impl TetRuleMeasures {
    #[inline]
    pub fn of(p: &[DVec3; 4]) -> Self {
        let e = [p[1] - p[0], p[2] - p[0], p[3] - p[0]];
        let det = e[0].dot(e[1].cross(e[2]));
        TetRuleMeasures { inverted: is_inverted(p), inversion: (-det).max(0.0), det, scale: crate::numeric::largest_component(e) }
    }
    /// Its determinant and scale for the rule's screen ([`super::det_within`]), as
    /// `quality::solid::least_corner_det` gives a solid's.
    #[inline]
    pub fn det_within(&self) -> Option<(f64, f64)> {
        super::det_within(self.det, self.scale, 3)
    }
}

/// The corners in the tetrahedron's own scale, for the measures that are ratios of
/// lengths (angles, sines, the mean ratio, κ, the sign of the volume): as they are when
/// the edges' largest component lies within `numeric::SAFE_SCALE` (2^±200, where
/// every product those measures take is a normal double, so their bits are unchanged);
/// beyond it, the corners multiplied by a power of two (exact) that brings that component
/// to about 1 — the planar metrics' rule (`docs/formulas.md` §1), so a cube of tetrahedra
/// has the same angles at 1e±150 as at 1, to the bit. (Not moved to corner 0 first: the
/// measures' differences of other corners would then round twice, otherwise than at unit
/// scale; issue 61.)
#[inline(always)]
pub fn in_unit_scale(p: &[DVec3; 4]) -> [DVec3; 4] {
    let m = crate::numeric::largest_component([p[1] - p[0], p[2] - p[0], p[3] - p[0]]);
    let Some((f1, f2)) = crate::numeric::factors_beyond_safe_scale(m) else {
        return *p;
    };
    p.map(|x| x * f1 * f2)
}

/// The corners with corner `i` first, by an even permutation (so the signed volume is
/// unchanged): `(0 1 2 3)`, `(1 0 3 2)`, `(2 3 0 1)`, `(3 2 1 0)`.
#[inline]
pub fn with_first(p: &[DVec3; 4], i: usize) -> [DVec3; 4] {
    const EVEN: [[usize; 4]; 4] = [[0, 1, 2, 3], [1, 0, 3, 2], [2, 3, 0, 1], [3, 2, 1, 0]];
    EVEN[i].map(|k| p[k])
}

/// Signed volume with its gradient with respect to corner 0: `∇_{p0} V = −(p2 − p1)×(p3 − p1)/6`
/// (V is affine in each corner).
#[inline]
pub fn signed_volume_grad0(p: &[DVec3; 4]) -> (f64, DVec3) {
    (signed_volume(p), -(p[2] - p[1]).cross(p[3] - p[1]) / 6.0)
}

/// The area vector of the face opposite corner `k`, pointing out of a valid tetrahedron:
/// half the cross product of two of its edges, ordered against the corner.
#[inline]
fn face_area_vector(p: &[DVec3; 4], k: usize) -> DVec3 {
    // faces opposite 0..3, each ordered so that its normal points away from the corner
    const FACES: [[usize; 3]; 4] = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]];
    let [a, b, c] = FACES[k];
    0.5 * (p[b] - p[a]).cross(p[c] - p[a])
}

/// The six interior dihedral angles, radians, at the edges of [`TET_EDGES`]: at edge `ij`,
/// `π` minus the angle between the outward normals of the faces opposite the other two
/// corners, signed as [`dihedral_sines`] are: `atan2(sin θ, cos θ)` with the signed sine,
/// so in (0, π) for a valid tetrahedron and in (−π, 0) for an inverted one (whose
/// normals turn inward together: unsigned, its angles would be its mirror image's, and
/// an inverted regular tetrahedron would read the ideal 70.53°), as a planar element's
/// corner angles are negative when it is inverted. NaN where a face has no area.
pub fn dihedral_angles(p: &[DVec3; 4]) -> [f64; 6] {
    let inverted = volume_is_negative(p);
    dihedral_cosines(p).map(|c| if inverted { -c.acos() } else { c.acos() })
}

/// Whether the signed volume is negative: by the rounded volume where it is not 0, else
/// by the exact sign ([`orient3d`](crate::numeric::exact::orient3d)), so a volume that
/// underflows (edges that differ in scale by 2^600) keeps its sign (issue 61).
#[inline(always)]
pub fn volume_is_negative(p: &[DVec3; 4]) -> bool {
    let v = signed_volume(&in_unit_scale(p));
    v < 0.0 || (v == 0.0 && exactly_negative(p))
}

/// Whether the exact signed volume is negative ([`volume_is_negative`]'s rare case).
#[cold]
#[inline(never)]
fn exactly_negative(p: &[DVec3; 4]) -> bool {
    crate::numeric::exact::orient3d(p[0], p[1], p[2], p[3]) == std::cmp::Ordering::Less
}

/// The first three of [`dihedral_cosines`], at the edges from corner 0, bit for bit: the
/// three faces that hold corner 0, without the fourth. Where a face's area vector is
/// below 2^−500 (edges that differ in scale by 2^600 and more: a node at 1e200 beside unit
/// edges), taken again on the corner's edges brought to unit size one by one (exact; the
/// planes through corner 0 do not change), so its cosines are not 0/0 (issue 61).
#[inline]
pub fn dihedral_cosines_at_corner0(p: &[DVec3; 4]) -> [f64; 3] {
    let q = &in_unit_scale(p);
    let (c, tiny) = cosines_at_corner0(q);
    if !tiny {
        return c;
    }
    cosines_at_corner0_near_unit(q)
}

/// [`dihedral_cosines_at_corner0`]'s rare case: on the edges brought near unit size, and
/// each face's area vector after them (a cosine reads directions only).
#[cold]
#[inline(never)]
fn cosines_at_corner0_near_unit(q: &[DVec3; 4]) -> [f64; 3] {
    let u = edges_near_unit(q);
    let n = [1, 2, 3].map(|k| crate::numeric::near_unit_vector(face_area_vector(&u, k)));
    [[1, 2], [0, 2], [0, 1]].map(|[k, l]: [usize; 2]| (-n[k].dot(n[l]) / (n[k].length() * n[l].length())).clamp(-1.0, 1.0))
}

/// [`dihedral_cosines_at_corner0`] as the faces' area vectors give them, and whether one
/// of those is below 2^−500.
#[inline]
fn cosines_at_corner0(p: &[DVec3; 4]) -> ([f64; 3], bool) {
    let n = [1, 2, 3].map(|k| face_area_vector(p, k));
    let len = n.map(|v| v.length());
    // OFF_EDGE's first three entries, faces 1–3 stored at 0–2
    let c = [[1, 2], [0, 2], [0, 1]].map(|[k, l]: [usize; 2]| {
        let c = -n[k].dot(n[l]) / (len[k] * len[l]);
        c.clamp(-1.0, 1.0)
    });
    (c, len.iter().any(|&l| l < 2f64.powi(-500)))
}

/// The corner tetrahedron `t` with corner 0 at the origin and each edge from it beyond
/// 2^±300 of unit size brought near it by its own power of two (exact).
fn edges_near_unit(t: &[DVec3; 4]) -> [DVec3; 4] {
    let unit = |v: DVec3| crate::numeric::near_unit_vector(v);
    [DVec3::ZERO, unit(t[1] - t[0]), unit(t[2] - t[0]), unit(t[3] - t[0])]
}

/// The cosines of [`dihedral_angles`], clamped to [−1, 1]: its angles are their inverse
/// cosines, bit for bit, negated for an inverted tetrahedron. NaN where a face has no area.
pub fn dihedral_cosines(p: &[DVec3; 4]) -> [f64; 6] {
    let p = &in_unit_scale(p);
    let n = [0, 1, 2, 3].map(|k| face_area_vector(p, k));
    OFF_EDGE.map(|[k, l]| {
        let c = -n[k].dot(n[l]) / (n[k].length() * n[l].length());
        c.clamp(-1.0, 1.0)
    })
}

/// The signed sine of each dihedral angle (edges of [`TET_EDGES`]): at edge `e` between
/// the faces of areas `A_k`, `A_l`, `sin θ_e = 3·V·|e| / (2·A_k·A_l)` (from
/// `V = 2·A_k·A_l·sin θ_e / (3|e|)`), with the signed volume, so negative when the
/// tetrahedron is inverted — Freitag's max-min dihedral measure, carried on through
/// inversion. NaN where a face has no area.
pub fn dihedral_sines(p: &[DVec3; 4]) -> [f64; 6] {
    let p = &in_unit_scale(p);
    let v = signed_volume(p);
    let a = [0, 1, 2, 3].map(|k| face_area_vector(p, k).length());
    let mut s = [0.0; 6];
    for (e, [i, j]) in TET_EDGES.iter().enumerate() {
        let [k, l] = OFF_EDGE[e];
        s[e] = 1.5 * v * p[*i].distance(p[*j]) / (a[k] * a[l]);
    }
    s
}

/// [`dihedral_sines`] with the gradient of each with respect to corner 0, by the product
/// rule on `3V|e|/(2 A_k A_l)`: `∇V` from [`signed_volume_grad0`], `∇|e| = (p0 − pj)/|e|`
/// on the edges at corner 0 (else 0), and `∇A = ((b − c) × n̂)/2` for a face `(p0, b, c)`
/// with unit normal `n̂` (else 0).
pub fn dihedral_sines_grad0(p: &[DVec3; 4]) -> [(f64, DVec3); 6] {
    let (v, gv) = signed_volume_grad0(p);
    const FACES: [[usize; 3]; 4] = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]];
    let mut area = [0.0; 4];
    let mut g_area = [DVec3::ZERO; 4];
    for k in 0..4 {
        let n = face_area_vector(p, k);
        let len = n.length();
        area[k] = len;
        if k != 0 && len > 0.0 {
            // the face's corner 0 is first in its order (b, c the other two)
            let [_, b, c] = FACES[k];
            g_area[k] = 0.5 * (p[b] - p[c]).cross(n / len);
        }
    }
    let mut out = [(0.0, DVec3::ZERO); 6];
    for (e, &[i, j]) in TET_EDGES.iter().enumerate() {
        let [k, l] = OFF_EDGE[e];
        let len = p[i].distance(p[j]);
        let g_len = if i == 0 && len > 0.0 { (p[0] - p[j]) / len } else { DVec3::ZERO };
        let denom = area[k] * area[l];
        let s = 1.5 * v * len / denom;
        let g = 1.5 * (gv * len + v * g_len) / denom - s * (g_area[k] / area[k] + g_area[l] / area[l]);
        out[e] = (s, g);
    }
    out
}

/// The weighted corner Jacobian `T = A·W⁻¹` at corner 0, `A = [p1 − p0, p2 − p0, p3 − p0]`,
/// `W` the corner's reference ([`CornerReference`]); `A` itself where `W` is the identity
/// (the cube's corner, a hexahedron's measured corners).
#[inline]
pub(crate) fn weighted_jacobian(p: &[DVec3; 4], r: &CornerReference) -> DMat3 {
    let a = DMat3::from_cols(p[1] - p[0], p[2] - p[0], p[3] - p[0]);
    if r.identity {
        a
    } else {
        a * r.w_inv
    }
}

#[inline]
fn frobenius2(m: &DMat3) -> f64 {
    m.x_axis.length_squared() + m.y_axis.length_squared() + m.z_axis.length_squared()
}

/// The weighted corner Jacobian `T = A·W⁻¹` at corner 0 with `F = ‖T‖²_F` and `σ = det T`,
/// and their gradients with respect to corner 0: every column of `A` moves by `−dp0`, so
/// `∇F = −2·T·W⁻ᵀ𝟙` and `∇σ = 6∇V·det W⁻¹` ([`signed_volume_grad0`]).
#[derive(Clone, Copy, Debug)]
pub struct WeightedJacobian {
    pub t: DMat3,
    pub frob2: f64,
    pub grad_frob2: DVec3,
    pub sigma: f64,
    pub grad_sigma: DVec3,
}

impl WeightedJacobian {
    /// Of the corner `p` (corner 0 and its three edge neighbours) against reference `r`.
    #[inline]
    pub fn of(p: &[DVec3; 4], r: &CornerReference) -> Self {
        let t = weighted_jacobian(p, r);
        let det_w_inv = r.det_w_inv;
        let (v, gv) = signed_volume_grad0(p);
        WeightedJacobian {
            t,
            frob2: frobenius2(&t),
            grad_frob2: -2.0 * (t * r.w_inv_t_one),
            sigma: 6.0 * v * det_w_inv,
            grad_sigma: 6.0 * gv * det_w_inv,
        }
    }
}

/// A corner's [`WeightedJacobian`] as a function of corner 0's position `x`, the other
/// three corners fixed: worked out once when a star is gathered, so that an objective's
/// evaluation at a trial position reads no corners (no gather per evaluation). With
/// `u = x − o` (`o` corner 0 when formed) and `v = W⁻ᵀ𝟙`, every column of `A` moves by
/// `−u`, so `T(x) = T₀ − u·vᵀ`,
/// `F = ‖T‖²_F = F₀ − 2u·(T₀v) + |u|²|v|²` is quadratic in `x` (`∇F = −2·T·v`,
/// `∇²F = 2|v|²·I`), and `σ = det T = σ₀ + u·∇σ` is linear: `det(A₀ − u𝟙ᵀ) = det A₀ −
/// u·((a₂ − a₁)×(a₃ − a₁))`, the terms of higher degree cancelling (`docs/formulas.md` §8).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CornerForm {
    /// Corner 0 when formed.
    origin: DVec3,
    /// The largest component of an edge from corner 0 when formed: the unit of rounding.
    reach: f64,
    t0: DMat3,
    /// `T₀·v`.
    t0v: DVec3,
    /// `‖T₀‖²_F`.
    frob2: f64,
    /// `|v|²`.
    vv: f64,
    v: DVec3,
    sigma: f64,
    /// `∇σ`, constant.
    grad_sigma: DVec3,
}

impl CornerForm {
    /// A form not worked out yet: every field not a number, so a reading of it before
    /// [`of`](Self::of) fills it is not a number too (a star gathered for the drivers'
    /// measures only, `DriverStar::gather_for_measures`).
    pub const PENDING: CornerForm = CornerForm {
        origin: DVec3::NAN,
        reach: f64::NAN,
        t0: DMat3::NAN,
        t0v: DVec3::NAN,
        frob2: f64::NAN,
        vv: f64::NAN,
        v: DVec3::NAN,
        sigma: f64::NAN,
        grad_sigma: DVec3::NAN,
    };
    /// Marks a form worked out for other corners as not worked out, where it is overwritten
    /// in place: its origin, which every reading at a position takes first (`x − origin`),
    /// and its constant `∇σ` not a number, so such a reading is not a number, or not decided
    /// by the form, as [`PENDING`](Self::PENDING)'s is ([`of`](Self::of) fills it again).
    #[inline]
    pub fn mark_pending(&mut self) {
        self.origin = DVec3::NAN;
        self.grad_sigma = DVec3::NAN;
    }
    /// The form of the corner `p` (corner 0 and its three edge neighbours) against `r`.
    #[inline]
    pub fn of(p: &[DVec3; 4], r: &CornerReference) -> Self {
        let j = WeightedJacobian::of(p, r);
        let v = r.w_inv_t_one;
        CornerForm {
            origin: p[0],
            reach: crate::numeric::largest_component(p[1..].iter().map(|x| *x - p[0])),
            t0: j.t,
            t0v: j.t * v,
            frob2: j.frob2,
            vv: v.length_squared(),
            v,
            sigma: j.sigma,
            grad_sigma: j.grad_sigma,
        }
    }
    /// Corner 0 when the form was worked out (not a number while it is pending).
    #[inline]
    pub fn origin(&self) -> DVec3 {
        self.origin
    }
    /// The weighted Jacobian with corner 0 at `x`.
    #[inline(always)]
    pub fn at(&self, x: DVec3) -> WeightedJacobian {
        let u = x - self.origin;
        let tv = self.t0v - u * self.vv;
        WeightedJacobian {
            t: self.t0 - outer(u, self.v),
            frob2: self.frob2 - 2.0 * u.dot(self.t0v) + u.length_squared() * self.vv,
            grad_frob2: -2.0 * tv,
            sigma: self.sigma + u.dot(self.grad_sigma),
            grad_sigma: self.grad_sigma,
        }
    }
    /// `σ = det T` with corner 0 at `x` ([`at`](Self::at)'s, alone).
    #[inline(always)]
    pub fn sigma_at(&self, x: DVec3) -> f64 {
        self.sigma + (x - self.origin).dot(self.grad_sigma)
    }
    /// [`is_inverted`] of the corner's tetrahedron with corner 0 at `x` where `σ` there
    /// decides it beyond rounding; `None` where [`is_inverted`] must (near 0, beyond the
    /// safe scale, not a number), so its answers are [`is_inverted`]'s.
    #[inline]
    pub fn inverted_at(&self, x: DVec3, r: &CornerReference) -> Option<bool> {
        let u = x - self.origin;
        let reach = self.reach + u.abs().max_element();
        // σ is a sum of a few products of three edge components within 2·reach, times
        // det W⁻¹: its rounding is some 10⁻¹⁴ of that, so 10⁻⁹ is beyond any
        let margin = 1e-9 * reach * reach * reach * r.det_w_inv.abs();
        if !(margin > 0.0 && margin.is_finite()) {
            return None;
        }
        let sigma = self.sigma_at(x);
        if sigma > margin {
            Some(false)
        } else if sigma < -margin {
            Some(true)
        } else {
            None
        }
    }
    /// The Hessian of `F` in corner 0: `2|v|²` times the identity.
    #[inline(always)]
    pub fn frob2_hessian_diagonal(&self) -> f64 {
        2.0 * self.vv
    }
    /// `det W⁻¹`'s share of `σ`: `σ = 6V·det W⁻¹`, so `6V = σ / det W⁻¹` ([`signed_volume`]).
    #[inline(always)]
    pub fn volume6_at(&self, x: DVec3, r: &CornerReference) -> (f64, DVec3) {
        (self.sigma_at(x) / r.det_w_inv, self.grad_sigma / r.det_w_inv)
    }
}

/// The outer product `a·bᵀ`.
#[inline(always)]
pub fn outer(a: DVec3, b: DVec3) -> DMat3 {
    DMat3::from_cols(a * b.x, a * b.y, a * b.z)
}

/// Knupp's condition number of the corner, `κ = ‖T‖_F·‖T⁻¹‖_F` with `T = A·W⁻¹`
/// (Knupp 1999, §3: with the equilateral weight [`EQUILATERAL_TET`], the same at every
/// corner of a tetrahedron, and `3/κ` is a shape measure): 3 for the ideal corner,
/// growing without bound as it degenerates; +∞ for zero volume. An inverted corner has
/// the κ of its mirror image: the objectives put their barrier on the sign of the volume.
pub fn condition_number(p: &[DVec3; 4], r: &CornerReference) -> f64 {
    super::metric::condition_number(&weighted_jacobian(&in_unit_scale(p), r))
}

/// [`condition_number`] with its gradient with respect to corner 0. With `F = ‖T‖²`,
/// `G = ‖T⁻¹‖²`, `κ = √(FG)`: every column of `A` moves by `−dp0`, so
/// `∇F = −2·T·W⁻ᵀ𝟙` and, with `B = A⁻¹` and `S = W·B = T⁻¹`, `∇G = 2·Bᵀ·Wᵀ·S·Bᵀ·𝟙`;
/// the metric's chain ([`condition_number_chain`](super::metric::condition_number_chain))
/// makes `κ` and `∇κ` of them. (+∞, 0) for zero volume.
pub fn condition_number_grad0(p: &[DVec3; 4], r: &CornerReference) -> (f64, DVec3) {
    let a = DMat3::from_cols(p[1] - p[0], p[2] - p[0], p[3] - p[0]);
    let det = a.determinant();
    if det == 0.0 || !det.is_finite() {
        return (if det.is_nan() { f64::NAN } else { f64::INFINITY }, DVec3::ZERO);
    }
    let j = WeightedJacobian::of(p, r);
    let b = a.inverse();
    let s = r.w * b;
    let (f, g, grad_f) = (j.frob2, frobenius2(&s), j.grad_frob2);
    let grad_g = 2.0 * (b.transpose() * r.w.transpose() * s * b.transpose() * DVec3::ONE);
    super::metric::condition_number_chain(f, grad_f, g, grad_g)
}

/// The mean ratio `q = 3·σ^{2/3}/‖T‖²_F` with `σ = det T`, `T = A·W⁻¹` (Liu & Joe; the
/// inverse of Escobar et al.'s η), `W` the corner's reference: 1 for the ideal corner (the
/// regular tetrahedron against [`EQUILATERAL_TET`]), 0 for a flat one, and negative for
/// an inverted one (`σ^{2/3}` taken as `sign(σ)·|σ|^{2/3}`), so it falls on continuously
/// through inversion. 0 when the four corners coincide.
pub fn mean_ratio(p: &[DVec3; 4], r: &CornerReference) -> f64 {
    MeanRatioParts::of(p, r).mean_ratio()
}

/// What [`mean_ratio`] and [`mean_ratio_order`] are made of: `F = ‖T‖²_F` and `σ = det T`
/// of the weighted Jacobian in the tetrahedron's own scale, so a caller that orders many
/// tetrahedra by the key takes the exact mean ratio of the few it needs from the same
/// Jacobian.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeanRatioParts {
    pub frob2: f64,
    pub sigma: f64,
}

impl MeanRatioParts {
    #[inline(always)]
    pub fn of(p: &[DVec3; 4], r: &CornerReference) -> Self {
        let t = weighted_jacobian(&in_unit_scale(p), r);
        MeanRatioParts { frob2: frobenius2(&t), sigma: t.determinant() }
    }
    /// [`mean_ratio`].
    #[inline]
    pub fn mean_ratio(&self) -> f64 {
        super::metric::mean_ratio_of::<DMat3>(self.frob2, self.sigma)
    }
    /// [`mean_ratio_order`].
    #[inline]
    pub fn order(&self) -> f64 {
        if self.frob2 == 0.0 {
            return 0.0;
        }
        let a = self.sigma / self.frob2;
        a * a.abs() / self.frob2
    }
}

/// A number in the order of [`mean_ratio`] without its cube root: `q³/27 = σ·|σ|/F³`
/// (`q³` rises with `q` through 0), taken as `(σ/F)·|σ/F|/F` so it stays a double at every
/// scale the tetrahedron's own measures take. Where two tetrahedra's mean ratios differ by
/// more than a few rounding errors their keys are in the same order (`|key| ≤ 1/27`; it
/// underflows only where `q` is below about 10⁻¹⁰²); for a test that only
/// asks which is larger and is followed by the exact rule (the smart Laplacian's, before
/// the acceptance rule, `docs/formulas.md` §4). 0 when the four corners coincide.
#[inline]
pub fn mean_ratio_order(p: &[DVec3; 4], r: &CornerReference) -> f64 {
    MeanRatioParts::of(p, r).order()
}

/// [`mean_ratio`] with its gradient with respect to corner 0:
/// `∇q = q·((2/3)·∇σ/σ − ∇F/F)`, `∇σ = −cof(A)𝟙·det W⁻¹` (from [`signed_volume_grad0`]:
/// `σ = 6V·det W⁻¹`), `∇F = −2·T·W⁻ᵀ𝟙`. At σ = 0 the gradient is not finite (the
/// measure has a vertical tangent there) and is returned as 0.
pub fn mean_ratio_grad0(p: &[DVec3; 4], r: &CornerReference) -> (f64, DVec3) {
    mean_ratio_grad(&WeightedJacobian::of(p, r))
}

/// [`mean_ratio_grad0`] of a corner's weighted Jacobian `j` (of its corners, or of its
/// [`CornerForm`] at a trial position).
#[inline]
pub fn mean_ratio_grad(j: &WeightedJacobian) -> (f64, DVec3) {
    super::metric::mean_ratio_chain::<DMat3, _>(j.frob2, j.grad_frob2, j.sigma, j.grad_sigma)
}

/// The tetrahedra of a 10-node tetrahedron's Jacobian at its four corners (see
/// [`tet10_measures`](crate::quality::solid::tet10_measures)): corner `i` first (an even permutation, as [`with_first`]), then
/// `x_i` plus the tangents `4·m_ik − 3·x_i − x_k` of its three edges.
pub fn tet10_corner_tets(p: &[DVec3; 10]) -> [[DVec3; 4]; 4] {
    // the mid-edge node of edge (i, k)
    const MID: [[usize; 4]; 4] = [[0, 4, 6, 7], [4, 0, 5, 8], [6, 5, 0, 9], [7, 8, 9, 0]];
    const EVEN: [[usize; 4]; 4] = [[0, 1, 2, 3], [1, 0, 3, 2], [2, 3, 0, 1], [3, 2, 1, 0]];
    EVEN.map(|order| {
        let i = order[0];
        let x = p[i];
        order.map(|k| if k == i { x } else { x + (4.0 * p[MID[i][k]] - 3.0 * x - p[k]) })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    // the measures against the equilateral tetrahedron, the reference of both kinds today
    const R: &CornerReference = &EQUILATERAL_TET;
    fn condition_number(p: &[DVec3; 4]) -> f64 {
        super::condition_number(p, R)
    }
    fn condition_number_grad0(p: &[DVec3; 4]) -> (f64, DVec3) {
        super::condition_number_grad0(p, R)
    }
    fn mean_ratio(p: &[DVec3; 4]) -> f64 {
        super::mean_ratio(p, R)
    }
    fn mean_ratio_grad0(p: &[DVec3; 4]) -> (f64, DVec3) {
        super::mean_ratio_grad0(p, R)
    }
    fn tet_measures(p: &[DVec3; 4]) -> crate::quality::solid::SolidMeasures {
        crate::quality::solid::tet_measures(p, R)
    }

    fn regular() -> [DVec3; 4] {
        // the regular tetrahedron of unit edge, W's columns from the origin: right-handed
        [DVec3::ZERO, EQUILATERAL_W.x_axis, EQUILATERAL_W.y_axis, EQUILATERAL_W.z_axis]
    }
    fn corner() -> [DVec3; 4] {
        [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z]
    }

    use crate::numeric::SplitMix64;

    /// A point uniform in the cube [−1, 1)³.
    fn point(rng: &mut SplitMix64) -> DVec3 {
        let (x, y) = (rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0));
        DVec3::new(x, y, rng.uniform(-1.0, 1.0))
    }

    /// Only the cube's corner and its slot 0 have `W = I`; where one does, the weighted
    /// Jacobian is the edges themselves, the matrix product's bits (the corners here have
    /// no zero edge component, whose sign alone could differ).
    #[test]
    fn an_identity_reference_takes_the_edges_as_the_product_would() {
        use crate::mesh::VolumeKind;
        let identities: Vec<(VolumeKind, usize)> =
            VolumeKind::ALL.iter().flat_map(|&k| (0..4).filter(move |&s| k.row().slot_references[s].identity).map(move |s| (k, s))).collect();
        assert_eq!(identities, [(VolumeKind::Hex8, 0), (VolumeKind::Hex20, 0), (VolumeKind::Hex27, 0)]);
        assert!(crate::mesh::CUBE_CORNER.identity && !EQUILATERAL_TET.identity);
        let mut rng = SplitMix64::new(41);
        for _ in 0..2000 {
            let p = [point(&mut rng), point(&mut rng), point(&mut rng), point(&mut rng)];
            let a = DMat3::from_cols(p[1] - p[0], p[2] - p[0], p[3] - p[0]);
            let product = a * crate::mesh::CUBE_CORNER.w_inv;
            let t = weighted_jacobian(&p, &crate::mesh::CUBE_CORNER);
            assert_eq!(t.to_cols_array().map(f64::to_bits), product.to_cols_array().map(f64::to_bits));
            assert_eq!(t, a);
        }
    }

    /// The mean ratio's order key is `q³/27` and sorts tetrahedra as their mean ratios do,
    /// inverted ones and flat ones included, at every scale.
    #[test]
    fn mean_ratio_order_is_the_mean_ratios_order() {
        let mut rng = SplitMix64::new(29);
        let tets: Vec<[DVec3; 4]> = (0..400).map(|_| [point(&mut rng), point(&mut rng), point(&mut rng), point(&mut rng)]).collect();
        let r = &EQUILATERAL_TET;
        for p in &tets {
            let (q, k) = (mean_ratio(p), mean_ratio_order(p, r));
            assert!((k - q * q * q / 27.0).abs() <= 1e-13 * (1.0 + k.abs()), "{k} against q³/27 = {}", q * q * q / 27.0);
            for s in [1e-120, 1e120] {
                let scaled = p.map(|x| x * s);
                assert!((mean_ratio_order(&scaled, r) - k).abs() <= 1e-13 * (1.0 + k.abs()), "at scale {s}");
            }
        }
        for a in &tets {
            for b in &tets {
                let (qa, qb) = (mean_ratio(a), mean_ratio(b));
                if (qa - qb).abs() > 1e-12 {
                    assert_eq!(qa < qb, mean_ratio_order(a, r) < mean_ratio_order(b, r), "{qa} and {qb}");
                }
            }
        }
        let flat = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 0.0)];
        assert_eq!(mean_ratio_order(&flat, r), 0.0);
        assert_eq!(mean_ratio_order(&[DVec3::ONE; 4], r), 0.0);
    }

    #[test]
    fn w_inverse_is_the_inverse_of_w() {
        let i = EQUILATERAL_W * EQUILATERAL_W_INVERSE;
        assert!(i.abs_diff_eq(DMat3::IDENTITY, 1e-15), "{i}");
        // W's columns have unit length and meet at 60°
        for c in [EQUILATERAL_W.x_axis, EQUILATERAL_W.y_axis, EQUILATERAL_W.z_axis] {
            assert!((c.length() - 1.0).abs() < 1e-15);
        }
        assert!((EQUILATERAL_W.y_axis.dot(EQUILATERAL_W.z_axis) - 0.5).abs() < 1e-15);
    }

    #[test]
    fn the_regular_tetrahedron_by_hand() {
        let p = regular();
        // V = a³/(6√2)
        assert!((signed_volume(&p) - 1.0 / (6.0 * 2f64.sqrt())).abs() < 1e-15);
        // every dihedral angle arccos(1/3) = 70.5288°, sine 2√2/3
        for a in dihedral_angles(&p) {
            assert!((a - (1.0f64 / 3.0).acos()).abs() < 1e-14, "{a}");
        }
        for s in dihedral_sines(&p) {
            assert!((s - 2.0 * 2f64.sqrt() / 3.0).abs() < 1e-14, "{s}");
        }
        // T = W·W⁻¹ = I: κ = ‖I‖‖I‖ = 3, mean ratio 3·1/3 = 1
        assert!((condition_number(&p) - 3.0).abs() < 1e-14);
        assert!((3.0 / condition_number(&p) - 1.0).abs() < 1e-14);
        assert!((mean_ratio(&p) - 1.0).abs() < 1e-14);
    }

    #[test]
    fn the_right_corner_tetrahedron_by_hand() {
        // (0,0,0), e1, e2, e3: the faces at the origin are the coordinate planes, so the
        // dihedral angles at edges 01, 02, 03 are 90°; at edge 12 the faces are z = 0
        // (normal −e3) and x + y + z = 1 (normal (1,1,1)/√3): cos θ = −(−e3)·(1,1,1)/√3...
        // the interior angle has cos θ = 1/√3, θ = 54.7356°; the same at 13 and 23.
        let p = corner();
        assert!((signed_volume(&p) - 1.0 / 6.0).abs() < 1e-16);
        let a = dihedral_angles(&p);
        for e in 0..3 {
            assert!((a[e].to_degrees() - 90.0).abs() < 1e-12, "{a:?}");
        }
        for e in 3..6 {
            assert!((a[e] - (1.0 / 3f64.sqrt()).acos()).abs() < 1e-14, "{a:?}");
        }
        // sines: 1 at the right angles; √(2/3) at the others (sin of arccos(1/√3))
        let s = dihedral_sines(&p);
        for (e, s) in s.iter().enumerate() {
            let expected = if e < 3 { 1.0 } else { (2.0f64 / 3.0).sqrt() };
            assert!((s - expected).abs() < 1e-14, "edge {e}: {s}");
        }
        // T = W⁻¹: ‖W⁻¹‖² = 1 + 1/3 + 4/3 + 1/6 + 1/6 + 3/2 = 9/2, ‖W‖² = 3,
        // κ = √(27/2); det T = det W⁻¹ = 1/(1·(√3/2)·√(2/3)) = √2, mean ratio 3·2^{1/3}/(9/2)
        assert!((condition_number(&p) - (27.0f64 / 2.0).sqrt()).abs() < 1e-13);
        assert!((mean_ratio(&p) - 3.0 * 2f64.cbrt() / 4.5).abs() < 1e-14);
    }

    #[test]
    fn flat_and_inverted_tetrahedra() {
        let flat = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(0.3, 0.3, 0.0)];
        assert_eq!(signed_volume(&flat), 0.0);
        assert!(is_inverted(&flat));
        assert_eq!(condition_number(&flat), f64::INFINITY);
        assert_eq!(mean_ratio(&flat), 0.0);
        assert!(dihedral_sines(&flat).iter().all(|s| *s == 0.0));
        // swapping two corners mirrors it: volume, sines, mean ratio and angles change
        // sign (the angles are the mirror image's, negated: issue 61); κ is the mirror
        // image's
        let p = regular();
        let m = [p[1], p[0], p[2], p[3]];
        assert!(signed_volume(&m) < 0.0 && is_inverted(&m));
        assert!(dihedral_sines(&m).iter().all(|s| *s < 0.0));
        assert!((mean_ratio(&m) + 1.0).abs() < 1e-14);
        assert!((condition_number(&m) - 3.0).abs() < 1e-13);
        for a in dihedral_angles(&m) {
            assert!((a + (1.0f64 / 3.0).acos()).abs() < 1e-14, "{a}");
        }
        // NaN in, NaN out: no panic
        let nan = [DVec3::NAN, DVec3::X, DVec3::Y, DVec3::Z];
        assert!(is_inverted(&nan));
        assert!(condition_number(&nan).is_nan() && mean_ratio(&nan).is_nan());
        let _ = (dihedral_angles(&nan), dihedral_sines_grad0(&nan), condition_number_grad0(&nan), tet_measures(&nan));
    }

    #[test]
    fn measures_are_invariant_to_motion_scale_and_the_even_permutations() {
        let mut rng = SplitMix64::new(7);
        for _ in 0..50 {
            let p = [point(&mut rng), point(&mut rng), point(&mut rng), point(&mut rng)];
            let rot = glam::DQuat::from_axis_angle(point(&mut rng).normalize(), rng.uniform(-1.0, 1.0) * 3.0);
            let shift = point(&mut rng) * 10.0;
            let moved = p.map(|x| rot * x * 3.5 + shift);
            let rel = |a: f64, b: f64| (a - b).abs() <= 1e-10 * a.abs().max(1.0);
            assert!(rel(condition_number(&p), condition_number(&moved)));
            assert!(rel(mean_ratio(&p), mean_ratio(&moved)));
            for (a, b) in dihedral_sines(&p).iter().zip(dihedral_sines(&moved)) {
                assert!(rel(*a, b));
            }
            // κ and the mean ratio are the same at every corner (Knupp's theorem)
            for i in 0..4 {
                let q = with_first(&p, i);
                assert_eq!(signed_volume(&q).signum(), signed_volume(&p).signum());
                assert!((signed_volume(&q) - signed_volume(&p)).abs() <= 1e-14);
                assert!(rel(condition_number(&q), condition_number(&p)), "corner {i}");
                assert!(rel(mean_ratio(&q), mean_ratio(&p)), "corner {i}");
            }
        }
    }

    /// Central differences of `f` at corner 0 against the analytic gradient.
    fn check(f: impl Fn(&[DVec3; 4]) -> f64, g: DVec3, p: &[DVec3; 4], what: &str) {
        let h = 1e-6;
        let mut fd = DVec3::ZERO;
        for k in 0..3 {
            let mut a = *p;
            let mut b = *p;
            a[0][k] += h;
            b[0][k] -= h;
            fd[k] = (f(&a) - f(&b)) / (2.0 * h);
        }
        let scale = g.length().max(fd.length()).max(1e-3);
        assert!((fd - g).length() <= 1e-6 * scale, "{what}: analytic {g} vs differences {fd} at {p:?}");
    }

    #[test]
    fn gradients_agree_with_central_differences() {
        let mut rng = SplitMix64::new(11);
        let mut inverted = 0;
        for _ in 0..200 {
            let p = [point(&mut rng), point(&mut rng), point(&mut rng), point(&mut rng)];
            let v = signed_volume(&p);
            // away from the flat configurations, where the measures are steep
            if v.abs() < 0.02 {
                continue;
            }
            inverted += (v < 0.0) as u32;
            check(signed_volume, signed_volume_grad0(&p).1, &p, "volume");
            for (e, (s, g)) in dihedral_sines_grad0(&p).into_iter().enumerate() {
                assert!((s - dihedral_sines(&p)[e]).abs() < 1e-14);
                check(|q| dihedral_sines(q)[e], g, &p, "sine");
            }
            let (k, g) = condition_number_grad0(&p);
            assert!((k - condition_number(&p)).abs() <= 1e-12 * k);
            check(condition_number, g, &p, "condition number");
            let (q, g) = mean_ratio_grad0(&p);
            assert!((q - mean_ratio(&p)).abs() < 1e-14);
            check(mean_ratio, g, &p, "mean ratio");
        }
        assert!(inverted > 20, "inverted tetrahedra checked: {inverted}");
    }

    #[test]
    fn tet_measures_gathers_them() {
        let m = tet_measures(&corner());
        assert!((m.min_dihedral_deg - 54.735_610_317_245_35).abs() < 1e-10);
        assert!((m.max_dihedral_deg - 90.0).abs() < 1e-12);
        assert!(!m.inverted && (signed_volume(&corner()) - 1.0 / 6.0).abs() < 1e-16);
        assert_eq!(m.dihedral().len(), 6);
        // every corner of the regular tetrahedron is its target's
        assert!((tet_measures(&regular()).scaled_jacobian - 1.0).abs() < 1e-15);
        assert!((m.min_sine - (2.0f64 / 3.0).sqrt()).abs() < 1e-14);
    }

    /// A form marked not worked out (a gather's overwritten corner) reads as the all-NaN
    /// pending form does at any position: not a number, and the inversion test left to the
    /// exact one; worked out again, it reads the corners' own.
    #[test]
    fn a_form_marked_pending_reads_as_pending() {
        let p = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
        let mut f = CornerForm::of(&p, R);
        f.mark_pending();
        for x in [DVec3::ZERO, DVec3::new(0.1, -0.2, 0.3), DVec3::splat(1e6)] {
            for form in [f, CornerForm::PENDING] {
                let j = form.at(x);
                assert!(j.sigma.is_nan() && j.frob2.is_nan() && j.grad_sigma.is_nan() && j.grad_frob2.is_nan(), "{x}");
                let (v6, g6) = form.volume6_at(x, R);
                assert!(form.sigma_at(x).is_nan() && v6.is_nan() && g6.is_nan());
                assert_eq!(form.inverted_at(x, R), None);
            }
        }
        let (a, b) = (CornerForm::of(&p, R).at(DVec3::ZERO), WeightedJacobian::of(&p, R));
        assert!(a.sigma.is_finite() && (a.sigma, a.frob2) == (b.sigma, b.frob2));
    }
}
