//! The measures of a volume element: its corners' scaled Jacobians, shape and statistics.

use glam::DVec3;

use super::{corner_tet, in_unit_scale, validity, Validity};
use crate::mesh::VolumeKind;
use crate::quality::tet::{self as q3, CornerReference};
use crate::quality::{metric, Reading};

/// The scaled Jacobian of a corner, `det T/(‖t₁‖·‖t₂‖·‖t₃‖)` with `T = A·W⁻¹`: 1 at the
/// ideal corner, in [−1, 1], negative when inverted (the 3D sine of a corner: the volume of
/// the parallelepiped of its unit weighted edges). 0 for a degenerate corner. Where its
/// columns' lengths multiply to beyond 2^±600, each column beyond 2^±300 of unit size is
/// brought near it by a power of two first (exact; the quotient does not change), so a
/// corner of unit edges beside one of 2^660 does not underflow.
pub fn scaled_jacobian(p: &[DVec3; 4], r: &CornerReference) -> f64 {
    let t = q3::weighted_jacobian(&q3::in_unit_scale(p), r);
    let n = metric::column_length_product(&t);
    if !(2f64.powi(-600)..=2f64.powi(600)).contains(&n) {
        return scaled_jacobian_of_columns_near_unit(t);
    }
    metric::scaled_jacobian_over(&t, n)
}

/// [`scaled_jacobian`] of a weighted Jacobian whose column lengths multiply to beyond
/// 2^±600: each column beyond 2^±300 of unit size brought near it first.
#[cold]
#[inline(never)]
fn scaled_jacobian_of_columns_near_unit(t: glam::DMat3) -> f64 {
    let unit = crate::numeric::near_unit_vector;
    let t = glam::DMat3::from_cols(unit(t.x_axis), unit(t.y_axis), unit(t.z_axis));
    let n = metric::column_length_product(&t);
    if !n.is_finite() {
        return 0.0;
    }
    metric::scaled_jacobian_over(&t, n)
}

/// [`scaled_jacobian`] with its gradient with respect to corner 0, through the metric's
/// chain ([`metric::scaled_jacobian_chain`]): with `v = W⁻ᵀ𝟙`, every column `tᵢ` moves by
/// `−vᵢ·dp0`, so `∇ℓᵢ/2 = −vᵢ·tᵢ`; `∇σ` is the corner's ([`q3::WeightedJacobian`]).
pub fn scaled_jacobian_grad0(p: &[DVec3; 4], r: &CornerReference) -> (f64, DVec3) {
    let j = q3::WeightedJacobian::of(p, r);
    let cols = [j.t.x_axis, j.t.y_axis, j.t.z_axis];
    let l2 = cols.map(|c| c.length_squared());
    let v = r.w_inv_t_one;
    metric::scaled_jacobian_chain::<glam::DMat3, _>(j.sigma, j.grad_sigma, |i| l2[i], |i| -(v[i] * cols[i]))
}

/// Every measure of one volume element, for statistics and the page.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolidMeasures {
    /// Not certainly valid ([`validity`]; a 10-node tetrahedron by its corners).
    pub inverted: bool,
    /// Valid at every measured corner, yet not valid inside (the case corner checks miss).
    pub inverted_inside: bool,
    pub min_dihedral_deg: f64,
    pub max_dihedral_deg: f64,
    /// The smallest sine of a dihedral angle (a tetrahedron, Freitag 1997) or scaled
    /// Jacobian of a corner (the other kinds: the 3D sine of a corner).
    pub min_sine: f64,
    /// Knupp's κ, the worst corner's.
    pub condition: f64,
    /// The mean ratio: a tetrahedron's; the other kinds' mean over their measured corners.
    pub mean_ratio: f64,
    /// The smallest scaled Jacobian of a measured corner ([`scaled_jacobian`]).
    pub scaled_jacobian: f64,
    /// The dihedral angles, degrees (the first [`dihedral_count`](Self::dihedral_count)):
    /// a tetrahedron's six; for the other kinds, at each measured corner, the angles of its
    /// tetrahedron at the corner's three edges (the element's dihedral angles there when
    /// its faces are flat).
    pub dihedral_deg: [f64; 24],
    pub dihedral_count: usize,
}

impl SolidMeasures {
    pub fn dihedral(&self) -> &[f64] {
        &self.dihedral_deg[..self.dihedral_count]
    }
}

/// [`SolidMeasures`] of one tetrahedron: κ and the mean ratio against reference `r` (a
/// linear tetrahedron's: [`q3::EQUILATERAL_TET`]), the scaled Jacobian the smallest of its
/// four corners'.
pub fn tet_measures(p: &[DVec3; 4], r: &CornerReference) -> SolidMeasures {
    let sj = (0..4).map(|c| scaled_jacobian(&q3::with_first(p, c), r)).fold(f64::INFINITY, f64::min);
    tet_measures_with(p, r, sj)
}

/// [`tet_measures`] with its scaled Jacobian `sj` given.
fn tet_measures_with(p: &[DVec3; 4], r: &CornerReference, sj: f64) -> SolidMeasures {
    let six = q3::dihedral_angles(p).map(f64::to_degrees);
    let mut dihedral_deg = [0.0; 24];
    dihedral_deg[..6].copy_from_slice(&six);
    SolidMeasures {
        inverted: q3::is_inverted(p),
        inverted_inside: false,
        min_dihedral_deg: six.iter().copied().fold(f64::INFINITY, f64::min),
        max_dihedral_deg: six.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        min_sine: q3::dihedral_sines(p).into_iter().fold(f64::INFINITY, f64::min),
        condition: q3::condition_number(p, r),
        mean_ratio: q3::mean_ratio(p, r),
        scaled_jacobian: sj,
        dihedral_deg,
        dihedral_count: 6,
    }
}

/// [`SolidMeasures`] of a 10-node tetrahedron `p` (corners 0–3, then the mid-edge nodes
/// of edges 01, 12, 02, 03, 13, 23, VTK's order), measured with its mid-edge nodes: at
/// each corner the tetrahedron of the element's Jacobian there — the corner and its three
/// edges' tangents `4·m − 3·x_i − x_k` (Knupp's corner view; the edge itself when its
/// mid-edge node is at its middle) — and the worst of the four by the mean ratio (an
/// inverted one first). A straight 10-node tetrahedron measures as its corners do (but
/// for rounding); one whose mid-edge node sits far off its edge measures as bent. κ and
/// the mean ratio against reference `r` ([`q3::EQUILATERAL_TET`]); its scaled Jacobian the
/// smallest of the four's, as a mid-edge node that inverts one makes it ≤ 0.
pub fn tet10_measures(p: &[DVec3; 10], r: &CornerReference) -> SolidMeasures {
    let corners = q3::tet10_corner_tets(p);
    // the Jacobian's scaled Jacobian at each corner: its corner tetrahedron's at corner 0
    let sj = corners.iter().map(|t| scaled_jacobian(t, r)).fold(f64::INFINITY, f64::min);
    let mut worst: Option<SolidMeasures> = None;
    for corner in &corners {
        let m = tet_measures_with(corner, r, sj);
        let worse = match &worst {
            None => true,
            Some(w) => (m.inverted && !w.inverted) || (m.inverted == w.inverted && m.mean_ratio < w.mean_ratio),
        };
        if worse {
            worst = Some(m);
        }
    }
    worst.expect("four corners")
}

/// [`SolidMeasures`] of an element of `kind` with nodes `p` (all its nodes, in the kind's
/// order).
pub fn solid_measures(kind: VolumeKind, p: &[DVec3]) -> SolidMeasures {
    let r = kind.reference();
    match kind {
        VolumeKind::Tet4 => tet_measures(&[p[0], p[1], p[2], p[3]], r),
        VolumeKind::Tet10 => tet10_measures(&std::array::from_fn(|j| p[j]), r),
        _ => {
            let (q, _) = in_unit_scale(&p[..kind.corners()]);
            let count = kind.row().corner_edges.len();
            let mut out = SolidMeasures {
                inverted: false,
                inverted_inside: false,
                min_dihedral_deg: f64::INFINITY,
                max_dihedral_deg: f64::NEG_INFINITY,
                min_sine: f64::INFINITY,
                condition: 0.0,
                mean_ratio: 0.0,
                scaled_jacobian: f64::INFINITY,
                dihedral_deg: [0.0; 24],
                dihedral_count: 3 * count,
            };
            let mut corner_inverted = false;
            for c in 0..count {
                let t = corner_tet(kind, &q, c);
                corner_inverted |= q3::is_inverted(&t);
                out.mean_ratio += q3::mean_ratio(&t, r) / count as f64;
                out.condition = out.condition.max(q3::condition_number(&t, r));
                out.scaled_jacobian = out.scaled_jacobian.min(scaled_jacobian(&t, r));
                let angles = corner_dihedral_deg(&t);
                out.dihedral_deg[3 * c..3 * c + 3].copy_from_slice(&angles);
                for a in angles {
                    out.min_dihedral_deg = out.min_dihedral_deg.min(a);
                    out.max_dihedral_deg = out.max_dihedral_deg.max(a);
                }
            }
            out.min_sine = out.scaled_jacobian;
            out.inverted = corner_inverted || validity(kind, &q) != Validity::Valid;
            out.inverted_inside = out.inverted && !corner_inverted;
            out
        }
    }
}

/// The dihedral angles, degrees, of a corner's tetrahedron `t` at the corner's three edges
/// ([`q3::dihedral_angles`]' first three, at the edges (0,1), (0,2), (0,3) of
/// [`q3::TET_EDGES`], bit for bit, from the three faces through the corner alone).
#[inline]
pub(super) fn corner_dihedral_deg(t: &[DVec3; 4]) -> [f64; 3] {
    let inverted = q3::volume_is_negative(t);
    q3::dihedral_cosines_at_corner0(t).map(|c| (if inverted { -c.acos() } else { c.acos() }).to_degrees())
}

/// What the statistics read of one element ([`Reading`]), taken as [`solid_measures`]
/// takes it (the same functions, bit for bit), without what a reading leaves out
/// (validity, κ). The mean ratio is taken only where `with_quality`.
pub fn solid_reading(kind: VolumeKind, p: &[DVec3], with_quality: bool) -> Reading {
    let r = kind.reference();
    match kind {
        VolumeKind::Tet4 => {
            let corners = [p[0], p[1], p[2], p[3]];
            let angles = q3::dihedral_angles(&corners).map(f64::to_degrees);
            Reading {
                min_angle_deg: angles.iter().copied().fold(f64::INFINITY, f64::min),
                max_angle_deg: angles.iter().copied().fold(f64::NEG_INFINITY, f64::max),
                min_scaled_jacobian: (0..4).map(|c| scaled_jacobian(&q3::with_first(&corners, c), r)).fold(f64::INFINITY, f64::min),
                min_quality: if with_quality { q3::mean_ratio(&corners, r) } else { f64::INFINITY },
                grading: f64::NEG_INFINITY,
            }
        }
        VolumeKind::Tet10 => {
            let m = solid_measures(kind, p);
            Reading { min_angle_deg: m.min_dihedral_deg, max_angle_deg: m.max_dihedral_deg, min_scaled_jacobian: m.scaled_jacobian, min_quality: m.mean_ratio, grading: f64::NEG_INFINITY }
        }
        _ => {
            let (q, _) = in_unit_scale(&p[..kind.corners()]);
            let count = kind.row().corner_edges.len();
            let mut out = Reading { min_quality: if with_quality { 0.0 } else { f64::INFINITY }, ..Reading::default() };
            for c in 0..count {
                let t = corner_tet(kind, &q, c);
                if with_quality {
                    out.min_quality += q3::mean_ratio(&t, r) / count as f64;
                }
                out.min_scaled_jacobian = out.min_scaled_jacobian.min(scaled_jacobian(&t, r));
                for a in corner_dihedral_deg(&t) {
                    out.min_angle_deg = out.min_angle_deg.min(a);
                    out.max_angle_deg = out.max_angle_deg.max(a);
                }
            }
            out
        }
    }
}

/// Whether an element reads within `bounds` ([`Reading::within`]): the answer of comparing
/// its [`solid_reading`] with them, bit for bit, without the inverse cosines of the
/// angles far from a bound, and with the mean ratio only where the bound has one (above
/// −∞). It stops at the first corner beyond them.
pub fn solid_within(kind: VolumeKind, p: &[DVec3], bounds: &Reading) -> bool {
    let with_quality = bounds.min_quality > f64::NEG_INFINITY;
    let (cos_lo, cos_hi) = (bounds.min_angle_deg.to_radians().cos(), bounds.max_angle_deg.to_radians().cos());
    let r = kind.reference();
    match kind {
        VolumeKind::Tet4 => {
            let corners = [p[0], p[1], p[2], p[3]];
            if q3::volume_is_negative(&corners) {
                // its angles read negative: the reading decides
                return solid_reading(kind, p, with_quality).within(bounds);
            }
            q3::dihedral_cosines(&corners).iter().all(|&c| bounds.angle_within(c, cos_lo, cos_hi))
                && (0..4).all(|c| scaled_jacobian(&q3::with_first(&corners, c), r) >= bounds.min_scaled_jacobian)
                && (!with_quality || q3::mean_ratio(&corners, r) >= bounds.min_quality)
        }
        VolumeKind::Tet10 => solid_reading(kind, p, with_quality).within(bounds),
        _ => {
            let (q, _) = in_unit_scale(&p[..kind.corners()]);
            let count = kind.row().corner_edges.len();
            let mut mean_ratio = 0.0;
            (0..count).all(|c| {
                let t = corner_tet(kind, &q, c);
                if q3::volume_is_negative(&t) {
                    // its angles read negative: the reading decides
                    return solid_reading(kind, p, with_quality).within(bounds);
                }
                if with_quality {
                    mean_ratio += q3::mean_ratio(&t, r) / count as f64;
                }
                q3::dihedral_cosines_at_corner0(&t).iter().all(|&c| bounds.angle_within(c, cos_lo, cos_hi))
                    && scaled_jacobian(&t, r) >= bounds.min_scaled_jacobian
            }) && (!with_quality || mean_ratio >= bounds.min_quality)
        }
    }
}

/// The shape of an element that is not a tetrahedron, as the drivers read it (the smart
/// Laplacian, the priority order, the acceptance rule): the mean of its measured corners'
/// mean ratios (1 for the ideal element, falling through 0 as corners invert).
pub fn solid_shape(kind: VolumeKind, p: &[DVec3]) -> f64 {
    let (q, _) = in_unit_scale(p);
    let (r, count) = (kind.reference(), kind.row().corner_edges.len());
    (0..count).map(|c| q3::mean_ratio(&corner_tet(kind, &q, c), r)).sum::<f64>() / count as f64
}
/// The smallest scaled Jacobian of the element's measured corners (its "sine").
pub fn solid_min_sine(kind: VolumeKind, p: &[DVec3]) -> f64 {
    let r = kind.reference();
    (0..kind.row().corner_edges.len()).map(|c| scaled_jacobian(&corner_tet(kind, p, c), r)).fold(f64::INFINITY, f64::min)
}
