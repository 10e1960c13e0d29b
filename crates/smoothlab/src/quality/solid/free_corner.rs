//! The validity of an element as one free corner moves, for the validity guard's trials.
//! [`DetForm`] is `det J` as a function of the corner. [`ValidBall`] is where it is valid.

use glam::DVec3;

use super::bernstein::{hex_det, hex_det_and_slopes, indices, pyramid_det, Bezier};
use super::{reach, validity, Validity};
use crate::mesh::VolumeKind;

/// A hexahedron's or pyramid's `det J` in the Bernstein basis as a function of one
/// corner's position `x`, the others fixed, for the validity guard's trials: every
/// coefficient is a sum of triple products of vectors affine in `x`, and a triple product
/// is affine in a vector that two of its factors share (`x·(x×h) = 0`), so each
/// coefficient is `c₀ + g·(x − o)`. A hexahedron's slopes `g` are the triple products'
/// gradients (`TripleProduct::slopes`); a pyramid's are read off the coefficients one
/// edge length `m` along each axis (exact but for rounding, an affine function's
/// differences).
/// [`validity_at`](Self::validity_at) decides only where every coefficient it reads is
/// beyond rounding of 0, and leaves the rest to [`validity`], so its answers are
/// [`validity`]'s.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DetForm {
    origin: DVec3,
    /// The largest component of an edge from corner 0 when formed: the unit of rounding.
    reach: f64,
    /// The coefficients of the polynomial's degrees, in [`indices`]' order: the first
    /// `len` of `c` and `g`.
    c: [f64; 27],
    g: [DVec3; 27],
    len: usize,
    /// Which of them are the box's corners (bit `t` for the `t`-th).
    corners: u32,
}

impl DetForm {
    /// The form of the element of `kind` with corners `p`, its corner `slot` free; `None`
    /// for kinds decided without Bernstein coefficients (tetrahedra, wedges) and for an
    /// element beyond the safe scale, which [`validity`] measures in its own scale.
    pub fn of(kind: VolumeKind, p: &[DVec3], slot: usize) -> Option<DetForm> {
        let det: fn(&[DVec3]) -> Bezier = match kind.linear() {
            VolumeKind::Hex8 => hex_det,
            VolumeKind::Pyramid5 => pyramid_det,
            _ => return None,
        };
        let n = kind.corners();
        let reach = reach(&p[..n]);
        if reach == 0.0 || !reach.is_finite() || crate::numeric::factors_beyond_safe_scale(reach).is_some() {
            return None;
        }
        let mut q = [DVec3::ZERO; 8];
        q[..n].copy_from_slice(&p[..n]);
        // a hexahedron's slopes analytic; a pyramid's (whose apex is in four of its
        // factor's coefficients) by differences, exact for an affine function up to rounding
        let (c, slopes) = if kind.linear() == VolumeKind::Hex8 {
            hex_det_and_slopes(&q, slot)
        } else {
            let c = det(&q);
            let moved = [0, 1, 2].map(|axis| {
                let mut m = q;
                m[slot][axis] += reach;
                det(&m)
            });
            let mut slopes = [DVec3::ZERO; 27];
            for (n, s) in slopes.iter_mut().enumerate() {
                let (i, j, k) = (n / 9, n / 3 % 3, n % 3);
                let slope = |axis: usize| (moved[axis].c[i][j][k] - c.c[i][j][k]) / reach;
                *s = DVec3::new(slope(0), slope(1), slope(2));
            }
            (c, slopes)
        };
        let deg = c.deg;
        let mut form = DetForm { origin: p[slot], reach, c: [0.0; 27], g: [DVec3::ZERO; 27], len: 0, corners: 0 };
        for (t, (i, j, k)) in indices(deg).enumerate() {
            form.c[t] = c.c[i][j][k];
            form.g[t] = slopes[9 * i + 3 * j + k];
            let corner = (i == 0 || i == deg[0]) && (j == 0 || j == deg[1]) && (k == 0 || k == deg[2]);
            form.corners |= (corner as u32) << t;
            form.len = t + 1;
        }
        Some(form)
    }

    /// [`validity`] of the element with the free corner at `x` where its coefficients
    /// there decide it beyond rounding; `None` where [`validity`] must.
    #[inline]
    pub fn validity_at(&self, x: DVec3) -> Option<Validity> {
        let u = x - self.origin;
        let r = self.reach + u.abs().max_element();
        // every coefficient is a sum of a few triple products of edges within 2r: its
        // rounding is some 10⁻¹² r³, so 10⁻⁹ r³ is beyond any
        let margin = 1e-9 * r * r * r;
        if !(margin > 0.0 && margin.is_finite()) {
            return None;
        }
        let (mut min, mut min_corner) = (f64::INFINITY, f64::INFINITY);
        for (t, (&c, g)) in self.c[..self.len].iter().zip(&self.g[..self.len]).enumerate() {
            let v = c + g.dot(u);
            if v.is_nan() {
                return None;
            }
            min = min.min(v);
            if self.corners >> t & 1 == 1 {
                min_corner = min_corner.min(v);
            }
        }
        if min_corner < -margin {
            Some(Validity::Inverted)
        } else if min > margin {
            Some(Validity::Valid)
        } else {
            None
        }
    }
}

/// A ball of positions of a hexahedron's free corner in which the element is valid for
/// certain, from its `det J` where the corner is, without the coefficients at the
/// position asked: each Bernstein coefficient `c_t` is affine in the corner ([`DetForm`]),
/// a sum of triple products of the element's edges whose weights add up to 1 (those of the
/// product of Bernstein polynomials), and a triple product's gradient in one corner is at
/// most the sum of the products of its factors' lengths two by two, so `|∇c_t| ≤ 3E²`
/// with `E` the longest edge. Within `ρ` of the corner every coefficient is at least
/// `m − 3E²ρ`, `m` the smallest there; the radius is half of where that bound reaches 0,
/// kept only where the bound stays beyond twice the form's rounding margin, so a position
/// it holds is one the form or the exact test would call valid too.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ValidBall {
    centre: DVec3,
    radius_squared: f64,
}

impl ValidBall {
    /// The ball of the hexahedron (8, 20 or 27 nodes: its corners' trilinear map) with
    /// corners `p`, its corner `slot` free; `None` for other kinds, an element not valid
    /// beyond rounding where it is, and an element beyond the safe scale.
    pub fn of(kind: VolumeKind, p: &[DVec3], slot: usize) -> Option<ValidBall> {
        let (p, reach) = Self::corners_and_reach(kind, p)?;
        Self::of_least_coefficient(p, slot, reach, hex_det(p).min_coefficient_unsigned())
    }

    /// [`validity`] of the hexahedron with corners `p` and its ball with free corner
    /// `slot` (as [`of`](Self::of)), from one taking of its coefficients: for the guard's
    /// first question that its memo does not answer, whose answer makes the element's first
    /// ball about the position asked, and its first beyond that ball, which makes a second
    /// (where the solve's later trials gather). The same validity as
    /// [`validity`]'s, which takes the same coefficients where the element is within the
    /// safe scale, as a ball asks.
    pub fn validity_and_ball(kind: VolumeKind, p: &[DVec3], slot: usize) -> (Validity, Option<ValidBall>) {
        let Some((corners, reach)) = Self::corners_and_reach(kind, p) else {
            return (validity(kind, p), None);
        };
        let det = hex_det(corners);
        let least = det.min_coefficient_unsigned();
        (super::decided(kind, corners, corners, &det, least), Self::of_least_coefficient(corners, slot, reach, least))
    }

    /// The corners and reach of an element a ball may be made for: a hexahedron (of any
    /// order, by its corners) of positive reach within the safe scale.
    #[inline]
    fn corners_and_reach(kind: VolumeKind, p: &[DVec3]) -> Option<(&[DVec3], f64)> {
        if kind.linear() != VolumeKind::Hex8 {
            return None;
        }
        let p = &p[..8];
        let reach = reach(p);
        (reach != 0.0 && reach.is_finite() && crate::numeric::factors_beyond_safe_scale(reach).is_none()).then_some((p, reach))
    }

    /// The ball from the least coefficient `m` of the hexahedron with corners `p` (within
    /// the safe scale, its reach `reach`).
    fn of_least_coefficient(p: &[DVec3], slot: usize, reach: f64, m: f64) -> Option<ValidBall> {
        // the twelve edges' squares in three running maxima (a maximum is exact)
        let mut longest = [0.0f64; 3];
        for i in 0..4 {
            for (l, (a, b)) in longest.iter_mut().zip([(i, (i + 1) % 4), (i + 4, (i + 1) % 4 + 4), (i, i + 4)]) {
                *l = l.max(p[a].distance_squared(p[b]));
            }
        }
        let longest = longest[0].max(longest[1]).max(longest[2]);
        // the gradients' bound, rounded up beyond its own rounding
        let slope = 3.0 * longest * (1.0 + 1e-9);
        let radius = 0.99 * m / slope;
        let margin = 1e-9 * (reach + radius).powi(3);
        (radius > 0.0 && radius.is_finite() && m - slope * radius > 2.0 * margin)
            .then(|| ValidBall { centre: p[slot], radius_squared: radius * radius })
    }

    /// Whether the element is valid with its free corner at `x` by the ball alone.
    #[inline]
    pub fn holds(&self, x: DVec3) -> bool {
        (x - self.centre).length_squared() < self.radius_squared
    }
}
