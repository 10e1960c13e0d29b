//! The corner metrics, written once for 2D and 3D. Each is a function of the corner
//! matrix `T = A·W⁻¹` (Knupp 2001, "Algebraic mesh quality metrics"): `A` holds the
//! corner's edges as columns, `W` the target's ([`crate::target`]). `T` is a 2×2 or a
//! 3×3 matrix ([`CornerMatrix`]), and `d` is its size.
//!
//! - [`scaled_jacobian`]: `det T / Π‖tᵢ‖`, the sine of a planar corner, its 3D analogue.
//! - [`condition_number`]: `κ = ‖T‖_F·‖T⁻¹‖_F`, `d` at the ideal corner (Knupp 1999).
//! - [`mean_ratio`]: `d·det(T)^{2/d} / ‖T‖²_F`, 1 at the ideal corner (Liu & Joe).
//!
//! Each has its gradient `∂q/∂T`, a matrix of `T`'s size. A caller chains it to a node:
//! `∂q/∂A = ∂q/∂T·W⁻ᵀ`, and each column of `A` moves with the node by a scalar weight.
//! Each is also given over `T`'s invariants with their gradients in any space: the
//! objectives pass a node's, worked out at a trial position, and the metric combines
//! them. [`scaled_jacobian_chain`] (`det T`, the columns' `‖tᵢ‖²`),
//! [`condition_number_chain`] (`‖T‖²_F`, `‖T⁻¹‖²_F`), [`planar_condition_chain`] (2D,
//! with the Hessian Newton's trial needs), [`mean_ratio_chain`] (`‖T‖²_F`, `det T`).
//! A test holds each chain to the gradient over `T`.
//!
//! The formulas, in one notation: `docs/formulas.md` §1 (planar), §8 (solids).

use std::fmt::Debug;
use std::ops::{Add, Div, Mul, Sub};

use glam::{DMat2, DMat3, DVec2, DVec3};

/// A corner matrix `T`, 2×2 or 3×3: the linear algebra the metrics need of it.
pub trait CornerMatrix: Copy + Debug + PartialEq + Add<Output = Self> + Sub<Output = Self> + Mul<f64, Output = Self> + Mul<Self, Output = Self> {
    /// A column of the matrix: an edge of the corner.
    type Column: Copy + Mul<f64, Output = Self::Column> + Div<f64, Output = Self::Column> + Sub<Output = Self::Column>;
    /// `d`: 2 or 3.
    const DIM: usize;
    /// The zero matrix.
    const ZERO: Self;
    /// Column `i`, `i < DIM`.
    fn column(&self, i: usize) -> Self::Column;
    /// The matrix whose column `i` is `f(i)`.
    fn from_fn(f: impl FnMut(usize) -> Self::Column) -> Self;
    /// `‖c‖²` of a column.
    fn length_squared(c: Self::Column) -> f64;
    /// The largest `|component|` of a column.
    fn largest_component(c: Self::Column) -> f64;
    fn determinant(&self) -> f64;
    fn transpose(&self) -> Self;
    fn inverse(&self) -> Self;
    /// The cofactor matrix `cof T = det T·T⁻ᵀ`: the gradient of `det T`.
    fn cofactor(&self) -> Self;
    /// `‖adj T‖²_F`, that is `‖T⁻¹‖²_F·det²T`. For a 2×2 matrix the adjugate's entries are
    /// `T`'s, moved and negated, so this is `‖T‖²_F` itself.
    fn adjugate_frobenius2(&self) -> f64;
    /// `det(T)^{2/d}` as a product of two factors, `a·b`, signed as `det T`: `(det T, 1)` in
    /// 2D, `(c, |c|)` with `c = ∛det T` in 3D.
    fn det_power_two_over_dim(det: f64) -> (f64, f64);

    /// `‖T‖²_F`: the columns' squared lengths, summed in order.
    #[inline(always)]
    fn frobenius2(&self) -> f64 {
        (1..Self::DIM).fold(Self::length_squared(self.column(0)), |s, i| s + Self::length_squared(self.column(i)))
    }
}

impl CornerMatrix for DMat2 {
    type Column = DVec2;
    const DIM: usize = 2;
    const ZERO: Self = DMat2::ZERO;
    #[inline(always)]
    fn column(&self, i: usize) -> DVec2 {
        self.col(i)
    }
    #[inline(always)]
    fn from_fn(mut f: impl FnMut(usize) -> DVec2) -> Self {
        let c0 = f(0);
        DMat2::from_cols(c0, f(1))
    }
    #[inline(always)]
    fn length_squared(c: DVec2) -> f64 {
        c.length_squared()
    }
    #[inline(always)]
    fn largest_component(c: DVec2) -> f64 {
        c.abs().max_element()
    }
    #[inline(always)]
    fn determinant(&self) -> f64 {
        DMat2::determinant(self)
    }
    #[inline(always)]
    fn transpose(&self) -> Self {
        DMat2::transpose(self)
    }
    #[inline(always)]
    fn inverse(&self) -> Self {
        DMat2::inverse(self)
    }
    #[inline(always)]
    fn cofactor(&self) -> Self {
        // ∂(x₀y₁ − y₀x₁)/∂T: −perp of the other column, perp of the first
        DMat2::from_cols(-self.y_axis.perp(), self.x_axis.perp())
    }
    #[inline(always)]
    fn adjugate_frobenius2(&self) -> f64 {
        self.frobenius2()
    }
    #[inline(always)]
    fn det_power_two_over_dim(det: f64) -> (f64, f64) {
        (det, 1.0)
    }
}

impl CornerMatrix for DMat3 {
    type Column = DVec3;
    const DIM: usize = 3;
    const ZERO: Self = DMat3::ZERO;
    #[inline(always)]
    fn column(&self, i: usize) -> DVec3 {
        self.col(i)
    }
    #[inline(always)]
    fn from_fn(mut f: impl FnMut(usize) -> DVec3) -> Self {
        let (c0, c1) = (f(0), f(1));
        DMat3::from_cols(c0, c1, f(2))
    }
    #[inline(always)]
    fn length_squared(c: DVec3) -> f64 {
        c.length_squared()
    }
    #[inline(always)]
    fn largest_component(c: DVec3) -> f64 {
        c.abs().max_element()
    }
    #[inline(always)]
    fn determinant(&self) -> f64 {
        DMat3::determinant(self)
    }
    #[inline(always)]
    fn transpose(&self) -> Self {
        DMat3::transpose(self)
    }
    #[inline(always)]
    fn inverse(&self) -> Self {
        DMat3::inverse(self)
    }
    #[inline(always)]
    fn cofactor(&self) -> Self {
        DMat3::from_cols(self.y_axis.cross(self.z_axis), self.z_axis.cross(self.x_axis), self.x_axis.cross(self.y_axis))
    }
    #[inline(always)]
    fn adjugate_frobenius2(&self) -> f64 {
        self.cofactor().frobenius2()
    }
    #[inline(always)]
    fn det_power_two_over_dim(det: f64) -> (f64, f64) {
        let c = det.cbrt();
        (c, c.abs())
    }
}

/// A space a metric's gradient lives in: a node's (a vector) or `T`'s (a matrix).
pub trait Gradient: Copy + Add<Output = Self> + Mul<f64, Output = Self> + Div<f64, Output = Self> + Sub<Output = Self> {
    const ZERO: Self;
}

macro_rules! gradient_space {
    ($($t:ty),*) => {$(impl Gradient for $t { const ZERO: Self = <$t>::ZERO; })*};
}
gradient_space!(DVec2, DVec3, DMat2, DMat3);

/// The scaled Jacobian `det T / Π‖tᵢ‖` (the column lengths multiplied in order): the
/// sine of a planar corner's angle, the volume of a solid corner's unit edges. 1 at the
/// ideal corner, in [−1, 1], negative when inverted. 0 where a column has no length.
#[inline(always)]
pub fn scaled_jacobian<T: CornerMatrix>(t: &T) -> f64 {
    scaled_jacobian_over(t, column_length_product(t))
}

/// `Π‖tᵢ‖`, the column lengths multiplied in order: [`scaled_jacobian`]'s denominator (a
/// caller checks its range before it divides by it).
#[inline(always)]
pub fn column_length_product<T: CornerMatrix>(t: &T) -> f64 {
    (1..T::DIM).fold(T::length_squared(t.column(0)).sqrt(), |n, i| n * T::length_squared(t.column(i)).sqrt())
}

/// [`scaled_jacobian`] with its denominator `n` given: `det T/n`, 0 where `n ≤ 0`.
#[inline(always)]
pub fn scaled_jacobian_over<T: CornerMatrix>(t: &T, n: f64) -> f64 {
    if n <= 0.0 {
        return 0.0;
    }
    t.determinant() / n
}

/// [`scaled_jacobian`] with its gradient: with `ℓᵢ = ‖tᵢ‖²` and `n = √Πℓᵢ`,
/// `∂s/∂tᵢ = (cof T)ᵢ/n − s·tᵢ/ℓᵢ`. `(0, 0)` where `n` is 0 or not finite.
#[inline(always)]
pub fn scaled_jacobian_gradient<T: CornerMatrix>(t: &T) -> (f64, T) {
    scaled_jacobian_with::<T, true>(t, |i| T::length_squared(t.column(i)))
}

/// [`scaled_jacobian_gradient`] with the columns' squared lengths `l2(i)` given (a
/// triangle's corners share their sides), its denominator `√Πℓᵢ`; the gradient left 0
/// unless `GRADIENT`.
#[inline(always)]
pub fn scaled_jacobian_with<T: CornerMatrix, const GRADIENT: bool>(t: &T, l2: impl Fn(usize) -> f64) -> (f64, T) {
    let n = (1..T::DIM).fold(l2(0), |p, i| p * l2(i)).sqrt();
    if !(n > 0.0 && n.is_finite()) {
        return (0.0, T::ZERO);
    }
    let s = t.determinant() / n;
    if !GRADIENT {
        return (s, T::ZERO);
    }
    let cof = t.cofactor();
    (s, T::from_fn(|i| cof.column(i) / n - t.column(i) * s / l2(i)))
}

/// [`scaled_jacobian`] with its gradient in any space where its invariants' gradients are
/// given (a node's): `σ = det T` with `∇σ`, and each column's `ℓᵢ = ‖tᵢ‖²` with half its
/// gradient, `∇ℓᵢ/2`. With `n = √Πℓᵢ`, `∇s = ∇σ/n − s·Σ(∇ℓᵢ/2)/ℓᵢ`. In `T`'s own space
/// `∇σ = cof T` and `∇ℓᵢ/2` is `tᵢ` in column `i` ([`scaled_jacobian_gradient`]); at a
/// solid corner's own node, `−vᵢ·tᵢ` with `v = W⁻ᵀ𝟙`. `(0, 0)` where `n` is 0 or not
/// finite.
#[inline(always)]
pub fn scaled_jacobian_chain<T: CornerMatrix, V: Gradient>(
    det: f64,
    grad_det: V,
    l2: impl Fn(usize) -> f64,
    half_grad_l2: impl Fn(usize) -> V,
) -> (f64, V) {
    let n = (1..T::DIM).fold(l2(0), |p, i| p * l2(i)).sqrt();
    if !(n > 0.0 && n.is_finite()) {
        return (0.0, V::ZERO);
    }
    let s = det / n;
    let spread = (1..T::DIM).fold(half_grad_l2(0) / l2(0), |sum, i| sum + half_grad_l2(i) / l2(i));
    (s, grad_det / n - spread * s)
}

/// Knupp's condition number `κ = ‖T‖_F·‖T⁻¹‖_F`, taken as `√(‖T‖²_F·‖adj T‖²_F)/|det T|`:
/// `d` at the ideal corner, growing without bound as the corner degenerates; +∞ where
/// `det T = 0`. An inverted corner has its mirror image's κ: a caller that wants a
/// barrier puts it on the sign of `det T`.
#[inline(always)]
pub fn condition_number<T: CornerMatrix>(t: &T) -> f64 {
    let det = t.determinant();
    let product = t.frobenius2() * t.adjugate_frobenius2();
    if !(det.is_normal() && product.is_normal()) {
        return condition_number_in_unit_scale(t);
    }
    product.sqrt() / det.abs()
}

/// [`condition_number`] where `det T` or `‖T‖²_F·‖adj T‖²_F` is not a normal double (zero,
/// or a product of `d` or `2d` entries beyond the doubles: 3D entries beyond about
/// 2^±170): `T` times the power of two that brings
/// its largest entry near 1 (exact, and κ does not change with scale).
#[cold]
#[inline(never)]
fn condition_number_in_unit_scale<T: CornerMatrix>(t: &T) -> f64 {
    let largest = (0..T::DIM).map(|i| T::largest_component(t.column(i))).fold(0.0, f64::max);
    let t = crate::numeric::unit_factor(largest).map_or(*t, |f| *t * f);
    let det = t.determinant();
    if det == 0.0 || !det.is_finite() {
        return if det.is_nan() { f64::NAN } else { f64::INFINITY };
    }
    (t.frobenius2() * t.adjugate_frobenius2()).sqrt() / det.abs()
}

/// [`condition_number`] with its gradient: with `F = ‖T‖²_F`, `G = ‖T⁻¹‖²_F` and
/// `S = T⁻¹`, `∂κ/∂T = κ·(T/F − Sᵀ·S·Sᵀ/G)`. `(+∞, 0)` where `det T = 0`.
pub fn condition_number_gradient<T: CornerMatrix>(t: &T) -> (f64, T) {
    let kappa = condition_number(t);
    if !kappa.is_finite() {
        return (kappa, T::ZERO);
    }
    let s = t.inverse();
    let st = s.transpose();
    (kappa, (*t * (1.0 / t.frobenius2()) - st * s * st * (1.0 / s.frobenius2())) * kappa)
}

/// [`condition_number`] with its gradient in any space where its invariants' gradients
/// are given (a node's): `F = ‖T‖²_F` and `G = ‖T⁻¹‖²_F`. `κ = √(F·G)` and
/// `∇κ = (G·∇F + F·∇G)/(2κ)`; in `T`'s own space `∇F = 2T` and `∇G = −2·SᵀSSᵀ`, `S = T⁻¹`
/// ([`condition_number_gradient`]). The caller has checked `det T ≠ 0`; `(κ, 0)` where
/// `κ` is not a positive finite number.
#[inline(always)]
pub fn condition_number_chain<V: Gradient>(frob2: f64, grad_frob2: V, inv_frob2: f64, grad_inv_frob2: V) -> (f64, V) {
    let kappa = (frob2 * inv_frob2).sqrt();
    if !(kappa > 0.0 && kappa.is_finite()) {
        return (kappa, V::ZERO);
    }
    (kappa, (grad_frob2 * inv_frob2 + grad_inv_frob2 * frob2) / (2.0 * kappa))
}

/// A planar corner's [`condition_number`] over its invariants, with its gradient and
/// Hessian in the free node's plane: in 2D `‖adj T‖_F = ‖T‖_F`, so `κ = F/δ` with
/// `F = ‖T‖²_F` quadratic in the node (gradient `∇F`, Hessian `hf·I`) and `δ = det T`
/// linear in it (gradient `∇δ`). Then `∇κ = (∇F − κ∇δ)/δ` and
/// `∇²κ = (∇²F − ∇κ∇δᵀ − ∇δ∇κᵀ)/δ` (the zero matrix unless `HESSIAN`; `docs/formulas.md`
/// §5). A linear triangle's `D/N` is `√3·κ` the same way. The caller has checked `δ > 0`.
#[inline(always)]
pub fn planar_condition_chain<const HESSIAN: bool>(f: f64, det: f64, grad_f: DVec2, grad_det: DVec2, hf: f64) -> (f64, DVec2, DMat2) {
    let inv = 1.0 / det;
    let q = f * inv;
    let gq = (grad_f - q * grad_det) * inv;
    if !HESSIAN {
        return (q, gq, DMat2::ZERO);
    }
    // ∇q∇δᵀ + ∇δ∇qᵀ, symmetric
    let cross_xx = 2.0 * gq.x * grad_det.x;
    let cross_yy = 2.0 * gq.y * grad_det.y;
    let cross_xy = gq.x * grad_det.y + gq.y * grad_det.x;
    let (xx, yy, xy) = ((hf - cross_xx) * inv, (hf - cross_yy) * inv, -cross_xy * inv);
    (q, gq, DMat2::from_cols(DVec2::new(xx, xy), DVec2::new(xy, yy)))
}

/// The mean ratio `d·det(T)^{2/d}/‖T‖²_F`, the power signed as `det T`: 1 at the ideal
/// corner, 0 for a flat one, negative when inverted (it falls on continuously through
/// inversion). 0 when `T = 0`.
#[inline(always)]
pub fn mean_ratio<T: CornerMatrix>(t: &T) -> f64 {
    mean_ratio_of::<T>(t.frobenius2(), t.determinant())
}

/// [`mean_ratio`] from `T`'s invariants: `F = ‖T‖²_F` and `σ = det T`.
#[inline(always)]
pub fn mean_ratio_of<T: CornerMatrix>(frob2: f64, det: f64) -> f64 {
    if frob2 == 0.0 {
        return 0.0;
    }
    let (a, b) = T::det_power_two_over_dim(det);
    T::DIM as f64 * a * b / frob2
}

/// [`mean_ratio`] with its gradient in any space where the invariants' gradients are
/// given (`T`'s own, or a node's): `∇q = q·((2/d)·∇σ/σ − ∇F/F)`. At `σ = 0` the gradient
/// is not finite (the measure has a vertical tangent there) and is returned as 0.
#[inline(always)]
pub fn mean_ratio_chain<T: CornerMatrix, V: Gradient>(frob2: f64, grad_frob2: V, det: f64, grad_det: V) -> (f64, V)
where
    f64: Mul<V, Output = V>,
{
    if frob2 == 0.0 {
        return (0.0, V::ZERO);
    }
    let q = mean_ratio_of::<T>(frob2, det);
    if det == 0.0 {
        return (q, V::ZERO);
    }
    (q, q * ((2.0 / T::DIM as f64) * grad_det / det - grad_frob2 / frob2))
}

/// [`mean_ratio`] with its gradient `∂q/∂T` (`∇F = 2T`, `∇σ = cof T`).
pub fn mean_ratio_gradient<T: CornerMatrix>(t: &T) -> (f64, T) {
    let det = t.determinant();
    let frob2 = t.frobenius2();
    if frob2 == 0.0 {
        return (0.0, T::ZERO);
    }
    let q = mean_ratio_of::<T>(frob2, det);
    if det == 0.0 {
        return (q, T::ZERO);
    }
    (q, (t.cofactor() * ((2.0 / T::DIM as f64) / det) - *t * (2.0 / frob2)) * q)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::SplitMix64;

    fn random2(rng: &mut SplitMix64) -> DMat2 {
        DMat2::from_cols_array(&[0; 4].map(|_| rng.uniform(-2.0, 2.0)))
    }
    fn random3(rng: &mut SplitMix64) -> DMat3 {
        DMat3::from_cols_array(&[0; 9].map(|_| rng.uniform(-2.0, 2.0)))
    }

    /// Central differences of `f` at `t`, entry by entry, against the analytic `g`.
    fn check_gradient<T: CornerMatrix>(t: T, f: impl Fn(&T) -> f64, g: T, entries: fn(&T) -> Vec<f64>, set: fn(&mut T, usize, f64)) {
        let h = 1e-6;
        let scale = entries(&t).iter().fold(1.0f64, |m, x| m.max(x.abs()));
        for (k, gk) in entries(&g).into_iter().enumerate() {
            let (mut plus, mut minus) = (t, t);
            let x = entries(&t)[k];
            set(&mut plus, k, x + h);
            set(&mut minus, k, x - h);
            let fd = (f(&plus) - f(&minus)) / (2.0 * h);
            assert!((fd - gk).abs() < 1e-5 * (1.0 + fd.abs()) * scale, "entry {k}: {fd} vs {gk} at {t:?}");
        }
    }
    fn entries2(m: &DMat2) -> Vec<f64> {
        m.to_cols_array().to_vec()
    }
    fn set2(m: &mut DMat2, k: usize, v: f64) {
        let mut a = m.to_cols_array();
        a[k] = v;
        *m = DMat2::from_cols_array(&a);
    }
    fn entries3(m: &DMat3) -> Vec<f64> {
        m.to_cols_array().to_vec()
    }
    fn set3(m: &mut DMat3, k: usize, v: f64) {
        let mut a = m.to_cols_array();
        a[k] = v;
        *m = DMat3::from_cols_array(&a);
    }

    #[test]
    fn the_ideal_corner_reads_one_and_its_dimension() {
        for t in [DMat2::IDENTITY, DMat2::from_angle(0.7) * 3.0] {
            assert!((scaled_jacobian(&t) - 1.0).abs() < 1e-15);
            assert!((condition_number(&t) - 2.0).abs() < 1e-15);
            assert!((mean_ratio(&t) - 1.0).abs() < 1e-15);
        }
        for t in [DMat3::IDENTITY, DMat3::from_rotation_y(0.4) * 0.25] {
            assert!((scaled_jacobian(&t) - 1.0).abs() < 1e-15);
            assert!((condition_number(&t) - 3.0).abs() < 1e-14);
            assert!((mean_ratio(&t) - 1.0).abs() < 1e-15);
        }
    }

    #[test]
    fn values_by_hand() {
        // T = diag(2, 1): sine 1, κ = √5·√(5/4) = 5/2, q = 2·2/5
        let t = DMat2::from_diagonal(DVec2::new(2.0, 1.0));
        assert_eq!(scaled_jacobian(&t), 1.0);
        assert_eq!(condition_number(&t), 2.5);
        assert_eq!(mean_ratio(&t), 0.8);
        // a 45° shear: sine 1/√2; the mirror image keeps κ and negates the sine and q
        let s = DMat2::from_cols(DVec2::X, DVec2::new(1.0, 1.0));
        assert!((scaled_jacobian(&s) - 0.5f64.sqrt()).abs() < 1e-15);
        let m = DMat2::from_cols(DVec2::X, DVec2::new(1.0, -1.0));
        assert_eq!(condition_number(&m), condition_number(&s));
        assert_eq!(mean_ratio(&m), -mean_ratio(&s));
        // T = diag(1, 1, 8): sine 1, κ = √66·√(2 + 1/64), q = 3·4/66
        let t = DMat3::from_diagonal(DVec3::new(1.0, 1.0, 8.0));
        assert_eq!(scaled_jacobian(&t), 1.0);
        assert!((condition_number(&t) - (66.0f64 * (2.0 + 1.0 / 64.0)).sqrt()).abs() < 1e-13);
        assert!((mean_ratio(&t) - 12.0 / 66.0).abs() < 1e-15);
        // flat corners
        assert_eq!(condition_number(&DMat3::from_cols(DVec3::X, DVec3::Y, DVec3::X)), f64::INFINITY);
        assert_eq!(scaled_jacobian(&DMat2::ZERO), 0.0);
        assert_eq!(mean_ratio(&DMat3::ZERO), 0.0);
    }

    #[test]
    fn the_condition_number_is_the_same_at_every_scale() {
        let mut rng = SplitMix64::new(3);
        for _ in 0..50 {
            let (t2, t3) = (random2(&mut rng), random3(&mut rng));
            let (k2, k3) = (condition_number(&t2), condition_number(&t3));
            for e in [-1000, -600, -400, -180, 180, 400, 600, 1000] {
                let f = 2f64.powi(e);
                assert_eq!(condition_number(&(t2 * f)), k2, "2^{e}");
                assert_eq!(condition_number(&(t3 * f)), k3, "2^{e}");
            }
        }
    }

    #[test]
    fn gradients_agree_with_central_differences_in_2d_and_3d() {
        let mut rng = SplitMix64::new(7);
        for _ in 0..200 {
            let t = random2(&mut rng);
            if t.determinant().abs() < 0.05 {
                continue;
            }
            check_gradient(t, scaled_jacobian, scaled_jacobian_gradient(&t).1, entries2, set2);
            check_gradient(t, condition_number, condition_number_gradient(&t).1, entries2, set2);
            check_gradient(t, mean_ratio, mean_ratio_gradient(&t).1, entries2, set2);
            let t = random3(&mut rng);
            if t.determinant().abs() < 0.05 {
                continue;
            }
            check_gradient(t, scaled_jacobian, scaled_jacobian_gradient(&t).1, entries3, set3);
            check_gradient(t, condition_number, condition_number_gradient(&t).1, entries3, set3);
            check_gradient(t, mean_ratio, mean_ratio_gradient(&t).1, entries3, set3);
        }
    }

    #[test]
    fn the_scaled_jacobian_and_condition_chains_are_the_gradients_over_t() {
        fn agree<T: CornerMatrix + Gradient>(t: T) {
            let (s, g) = scaled_jacobian_gradient(&t);
            let column = |i: usize| T::from_fn(|k| if k == i { t.column(i) } else { t.column(i) * 0.0 });
            let (sc, gc) = scaled_jacobian_chain::<T, T>(t.determinant(), t.cofactor(), |i| T::length_squared(t.column(i)), column);
            assert_eq!(s, sc);
            let dg = gc - g;
            assert!((0..T::DIM).all(|i| T::length_squared(dg.column(i)) < 1e-24), "{g:?} vs {gc:?}");
            let (k, g) = condition_number_gradient(&t);
            let inv = t.inverse();
            let it = inv.transpose();
            let (kc, gc) = condition_number_chain(t.frobenius2(), t * 2.0, inv.frobenius2(), it * inv * it * -2.0);
            assert!((k - kc).abs() < 1e-12 * k, "{k} vs {kc}");
            let dg = gc - g;
            assert!((0..T::DIM).all(|i| T::length_squared(dg.column(i)) < 1e-20 * k * k), "{g:?} vs {gc:?}");
        }
        let mut rng = SplitMix64::new(13);
        for _ in 0..100 {
            let (t2, t3) = (random2(&mut rng), random3(&mut rng));
            if t2.determinant().abs() > 0.05 {
                agree(t2);
            }
            if t3.determinant().abs() > 0.05 {
                agree(t3);
            }
        }
    }

    #[test]
    fn the_chain_over_invariants_is_the_gradient_over_t() {
        let mut rng = SplitMix64::new(11);
        for _ in 0..100 {
            let t = random3(&mut rng);
            let (q, g) = mean_ratio_gradient(&t);
            let (qc, gc) = mean_ratio_chain::<DMat3, DMat3>(t.frobenius2(), t * 2.0, t.determinant(), t.cofactor());
            assert_eq!(q, qc);
            assert!((g - gc).to_cols_array().iter().all(|x| x.abs() < 1e-12 * (1.0 + q.abs())));
        }
    }
}
