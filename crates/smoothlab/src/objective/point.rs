//! What the solvers need of a free node's position and of its star, in any dimension: the
//! planar core (and the surfaces it serves) moves a node in the plane ([`DVec2`], a
//! [`Star`](super::Star) of triangles and quads), a tetrahedral mesh moves it in space
//! ([`DVec3`], a [`CornerStar`](super::CornerStar)). Objectives, solvers and their
//! results are generic over [`NodeStar`] with the planar star as the default, so the
//! planar code reads as before and is compiled as before (monomorphised: no indirection).

use std::fmt::Debug;
use std::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub};

use glam::{DMat2, DMat3, DVec2, DVec3};
use serde::Serialize;

/// A position of a free node, and the vector arithmetic the solvers do with it.
pub trait Point:
    Copy
    + PartialEq
    + Debug
    + Default
    + Serialize
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Neg<Output = Self>
    + Mul<f64, Output = Self>
    + Div<f64, Output = Self>
    + AddAssign
    + MulAssign<f64>
{
    /// The origin.
    const ZERO: Self;
    /// The number of coordinates: 2 or 3.
    const DIM: usize;
    /// The Hessian of an objective at a position: a symmetric `DIM × DIM` matrix.
    type Hessian: Copy + Debug + PartialEq + Send + Sync;
    /// The zero matrix.
    const ZERO_HESSIAN: Self::Hessian;
    fn dot(self, other: Self) -> f64;
    fn length(self) -> f64;
    fn length_squared(self) -> f64;
    fn distance(self, other: Self) -> f64;
    fn is_finite(self) -> bool;
    /// The Newton step `−H⁻¹g` when `H` is positive definite (Sylvester's criterion on its
    /// leading minors) and the step is finite, nonzero and at most `limit` long.
    fn newton_step(g: Self, h: Self::Hessian, limit: f64) -> Option<Self>;
}

macro_rules! point_by_glam {
    ($v:ty, $m:ty, $dim:expr, $positive_definite:expr) => {
        impl Point for $v {
            const ZERO: Self = <$v>::ZERO;
            const DIM: usize = $dim;
            type Hessian = $m;
            const ZERO_HESSIAN: $m = <$m>::ZERO;
            #[inline]
            fn dot(self, other: Self) -> f64 {
                <$v>::dot(self, other)
            }
            #[inline]
            fn length(self) -> f64 {
                <$v>::length(self)
            }
            #[inline]
            fn length_squared(self) -> f64 {
                <$v>::length_squared(self)
            }
            #[inline]
            fn distance(self, other: Self) -> f64 {
                <$v>::distance(self, other)
            }
            #[inline]
            fn is_finite(self) -> bool {
                <$v>::is_finite(self)
            }
            fn newton_step(g: Self, h: $m, limit: f64) -> Option<Self> {
                let det = h.determinant();
                let positive_definite: fn(&$m) -> bool = $positive_definite;
                if !(positive_definite(&h) && det > 0.0 && det.is_finite()) {
                    return None;
                }
                let p = -(h.inverse() * g);
                (p.is_finite() && p.length() <= limit && p != <$v>::ZERO).then_some(p)
            }
        }
    };
}

point_by_glam!(DVec2, DMat2, 2, |h| h.x_axis.x > 0.0);
point_by_glam!(DVec3, DMat3, 3, |h| h.x_axis.x > 0.0 && h.x_axis.x * h.y_axis.y - h.x_axis.y * h.y_axis.x > 0.0);

/// A free node's star as the solvers see it: whether it has elements, its size (the unit
/// of every solver length) and a copy scaled by a power of two (solves far from unit size
/// run in the star's own frame; see [`crate::optimize`]).
pub trait NodeStar: Clone {
    /// Where the free node can be.
    type Point: Point;
    /// The number of elements.
    fn len(&self) -> usize;
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// The star's size: the mean length of the edges at the free node, at its gathered
    /// position; 0 for an empty star.
    fn size(&self) -> f64;
    /// A copy with every coordinate multiplied by `f` (a power of two: exact).
    fn scaled(&self, f: f64) -> Self;
}
