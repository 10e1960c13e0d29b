//! The target `W` of each corner: what an objective measures the corner's Jacobian `A`
//! against, through `T = A·W⁻¹` (Knupp 1999; Knupp's target-matrix paradigm, Mesquite's
//! `TargetCalculator`, MFEM's TMOP).
//!
//! [`Target::Ideal`] is the ideal element of each kind: the papers' setting.
//! [`Target::Input`] is each corner as the mesh was read, where that corner is valid.
//! It keeps the shape each corner had: its stretch and its skew.
//! A corner read inverted or flat takes the ideal shape.
//!
//! Every target has the ideal's determinant: a target sets shape, not size.
//! So the objectives' terms that read sizes (the barriers, the untangling sums) see the
//! corners' sizes as with the ideal target.
//!
//! A planar or surface corner reads its target as a 2×2 matrix `M = W⁻¹·W_ideal` that its
//! edge pair is multiplied by ([`corner_frame`]). The metrics then see `A·M`, whose
//! `(A·M)·W_ideal⁻¹` is `A·W⁻¹`: the formulas of the ideal target, unchanged.
//! A volume corner reads it as its `W` ([`solid_reference`]).

use glam::{DMat2, DMat3, DVec2};

use crate::mesh::{CornerReference, ElementKind};

crate::enum_with_names! {
    /// What each corner is measured against (the command line's `--target`).
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
    #[serde(rename_all = "kebab-case")]
    pub enum Target {
        /// The ideal element of each kind: the equilateral triangle, the square, the
        /// regular tetrahedron, the cube.
        #[default]
        Ideal => ("ideal", "the ideal element of each kind (the papers)"),
        /// Each corner as the mesh was read, where it is valid: its stretch and skew kept.
        Input => ("input", "each corner as the mesh was read, where valid (its stretch and skew kept)"),
    }
}

impl Target {
    /// The target with command-line name `s` (exact, lowercase), if any.
    pub fn parse(s: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|t| t.name() == s)
    }
}

impl std::fmt::Display for Target {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// The smallest sine of a corner angle that a corner of the input may have to be its own
/// target: below it (or inverted) the corner takes the ideal shape.
pub const LEAST_TARGET_SINE: f64 = 1e-3;

/// The frame `M = W⁻¹·W_ideal` of a planar corner whose target is the edge pair
/// `(t1, t2)` (the input's), against the ideal edge pair `(w1, w2)`: the corner's edge pair
/// `[e1 e2]` is measured as `[e1 e2]·M`. `W` is scaled to the ideal's determinant.
/// `None` where the target corner is inverted, flat or not finite: the ideal holds there.
pub fn corner_frame(t1: DVec2, t2: DVec2, ideal: (DVec2, DVec2)) -> Option<DMat2> {
    let det = t1.perp_dot(t2);
    let lengths = t1.length() * t2.length();
    // NaN fails every comparison: a target that is not a number is refused too
    if det.partial_cmp(&(LEAST_TARGET_SINE * lengths)) != Some(std::cmp::Ordering::Greater)
        || !det.is_finite()
        || !lengths.is_finite()
    {
        return None;
    }
    let w_ideal = DMat2::from_cols(ideal.0, ideal.1);
    let w = DMat2::from_cols(t1, t2) * (w_ideal.determinant() / det).sqrt();
    Some(w.inverse() * w_ideal)
}

/// The ideal edge pair of a corner of `kind`, with the first edge along x: the
/// equilateral triangle's, the square's.
pub fn ideal_pair(kind: ElementKind) -> (DVec2, DVec2) {
    if kind.is_triangle() {
        EQUILATERAL_PAIR
    } else {
        (DVec2::X, DVec2::Y)
    }
}

/// The equilateral triangle's edge pair at a corner, the first edge along x.
pub const EQUILATERAL_PAIR: (DVec2, DVec2) = (
    DVec2::new(1.0, 0.0),
    DVec2::new(0.5, 0.866_025_403_784_438_6),
);

/// Each corner's frame ([`corner_frame`]) of an element of `kind` whose nodes' target
/// positions are `t`; the identity where the ideal holds (and past the kind's corners).
pub fn element_frames(kind: ElementKind, t: &[DVec2; 9]) -> [DMat2; 4] {
    let edges = crate::quality::corner_edge_vectors(kind, &t[..kind.node_count()]);
    let ideal = ideal_pair(kind);
    let mut frames = [DMat2::IDENTITY; 4];
    for (f, &(a, b)) in frames.iter_mut().zip(&edges[..kind.corners()]) {
        *f = corner_frame(a, b, ideal).unwrap_or(DMat2::IDENTITY);
    }
    frames
}

/// `[e1 e2]·m`: a corner's edge pair in the frame `m` ([`corner_frame`]). The same
/// arithmetic takes an edge pair's scalar weights (`corners.rs`), so the weights agree
/// with the edges.
#[inline(always)]
pub fn in_frame<V>(m: &DMat2, e1: V, e2: V) -> (V, V)
where
    V: Copy + std::ops::Mul<f64, Output = V> + std::ops::Add<Output = V>,
{
    (
        e1 * m.x_axis.x + e2 * m.x_axis.y,
        e1 * m.y_axis.x + e2 * m.y_axis.y,
    )
}

/// The reference of a volume corner whose target is the input's corner `a` (edge vectors
/// as columns, in the corner's order), scaled to the determinant of `ideal`, the kind's
/// reference for the same slot. `None` where the input corner is inverted, flat or not
/// finite: `ideal` holds there.
pub fn solid_reference(a: DMat3, ideal: &CornerReference) -> Option<CornerReference> {
    let det = a.determinant();
    let lengths = a.x_axis.length() * a.y_axis.length() * a.z_axis.length();
    // NaN fails every comparison: a target that is not a number is refused too
    if det.partial_cmp(&(LEAST_TARGET_SINE * lengths)) != Some(std::cmp::Ordering::Greater)
        || !det.is_finite()
        || !lengths.is_finite()
    {
        return None;
    }
    let w = a * (ideal.w.determinant() / det).cbrt();
    Some(CornerReference::of(w))
}

#[cfg(test)]
mod tests {
    use super::*;

    const EQUILATERAL: (DVec2, DVec2) = EQUILATERAL_PAIR;

    #[test]
    fn a_corner_in_its_own_frame_is_the_ideal() {
        // a stretched, skewed corner: measured against itself, it reads as the ideal pair
        let (t1, t2) = (DVec2::new(3.0, 0.2), DVec2::new(0.4, 0.5));
        let m = corner_frame(t1, t2, EQUILATERAL).unwrap();
        let (a, b) = in_frame(&m, t1, t2);
        let scale = (t1.perp_dot(t2) / EQUILATERAL.0.perp_dot(EQUILATERAL.1)).sqrt();
        assert!(a.abs_diff_eq(EQUILATERAL.0 * scale, 1e-12), "{a}");
        assert!(b.abs_diff_eq(EQUILATERAL.1 * scale, 1e-12), "{b}");
        // the same corner rotated reads as the ideal rotated: same lengths, same angle
        let r = DMat2::from_angle(0.7);
        let (a, b) = in_frame(&m, r * t1, r * t2);
        assert!((a.length() - scale).abs() < 1e-12 && (b.length() - scale).abs() < 1e-12);
        assert!((a.angle_to(b) - std::f64::consts::FRAC_PI_3).abs() < 1e-12);
        // the frame keeps areas
        assert!((m.determinant() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn inverted_or_flat_targets_are_refused() {
        let ideal = (DVec2::X, DVec2::Y);
        assert!(corner_frame(DVec2::Y, DVec2::X, ideal).is_none());
        assert!(corner_frame(DVec2::X, DVec2::new(1.0, 1e-6), ideal).is_none());
        assert!(corner_frame(DVec2::X, DVec2::new(f64::NAN, 1.0), ideal).is_none());
        assert!(corner_frame(DVec2::X, DVec2::new(1.0, 1.0), ideal).is_some());
    }

    #[test]
    fn a_solid_corner_is_its_own_target() {
        let ideal = crate::mesh::CUBE_CORNER;
        let a = DMat3::from_cols_array(&[2.0, 0.1, 0.0, 0.3, 0.5, 0.0, 0.1, 0.2, 0.25]);
        let r = solid_reference(a, &ideal).unwrap();
        let t = a * r.w_inv;
        // T = A·W⁻¹ is a multiple of the identity; W has the cube's determinant
        let s = t.x_axis.x;
        assert!(
            t.abs_diff_eq(DMat3::from_diagonal(glam::DVec3::splat(s)), 1e-12),
            "{t}"
        );
        assert!((r.w.determinant() - 1.0).abs() < 1e-12);
        assert!(solid_reference(-a, &ideal).is_none());
        assert_eq!(Target::parse("input"), Some(Target::Input));
        assert_eq!(Target::default(), Target::Ideal);
    }
}
