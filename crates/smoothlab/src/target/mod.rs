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

use glam::{DMat2, DMat3, DVec2, DVec3};

use crate::mesh::{CornerReference, ElementKind, Mesh};

pub mod stretch;

crate::enum_with_names! {
    /// What each corner is measured against (the command line's `--target`).
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
    #[serde(rename_all = "kebab-case")]
    pub enum Target {
        /// The ideal element of each kind: the equilateral triangle, the square, the
        /// regular tetrahedron, the cube.
        Ideal => ("ideal", "the ideal element of each kind (the papers)"),
        /// Each corner as the mesh was read, where it is valid: its stretch and skew kept.
        Input => ("input", "each corner as the mesh was read, where valid (its stretch and skew kept)"),
        /// Each element's stretch as read, averaged along its layer: a boundary layer's
        /// rows and a graded mesh's stretch kept, single nodes' noise not; the ideal where
        /// the mesh is not stretched ([`stretch`]).
        #[default]
        Stretch => ("stretch", "each element's stretch as read, averaged along its layer (the ideal where not stretched)"),
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

/// The ideal element of `kind` (corner 0 at the origin, its first edge along x), node by
/// node: its corners with [`ideal_pair`]'s edges, its mid-side nodes halfway, a 9-node
/// quad's centre in the middle.
pub fn ideal_points(kind: ElementKind) -> [DVec2; 9] {
    let (a, b) = ideal_pair(kind);
    let mut p = [DVec2::ZERO; 9];
    let k = kind.corners();
    p[1] = a;
    p[k - 1] = b;
    if k == 4 {
        p[2] = a + b;
    }
    for i in 0..k {
        if let Some(m) = kind.mid(i) {
            p[m] = (p[i] + p[(i + 1) % k]) * 0.5;
        }
    }
    if kind.node_count() == 9 {
        p[8] = (a + b) * 0.5;
    }
    p
}

/// Each element's neighbours across its inner edges, with the edge's length (`length` of
/// its two nodes): what [`stretch::StretchElement::neighbours`] holds.
fn edge_neighbours(mesh: &Mesh, length: impl Fn(usize, usize) -> f64) -> Vec<Vec<(u32, f64)>> {
    let mut neighbours: Vec<Vec<(u32, f64)>> = vec![Vec::new(); mesh.element_count()];
    for (edge, e, f) in crate::quality::grading::inner_edges(mesh) {
        let len = length(edge.a as usize, edge.b as usize);
        neighbours[e].push((f as u32, len));
        neighbours[f].push((e as u32, len));
    }
    neighbours
}

/// A map of [`stretch::stretch_maps`] (rows of columns) as a matrix.
fn mat3(m: &stretch::Mat<3>) -> DMat3 {
    DMat3::from_cols_array_2d(&[[m[0][0], m[1][0], m[2][0]], [m[0][1], m[1][1], m[2][1]], [m[0][2], m[1][2], m[2][2]]])
}

/// Each element's target positions with [`Target::Stretch`] for a planar mesh whose nodes
/// are read at `at`: its ideal mapped by [`stretch::stretch_maps`]'s map, or the ideal
/// itself. `None` where no element is stretched on purpose: the ideal holds everywhere.
pub fn planar_stretch_points(mesh: &Mesh, at: &[DVec2]) -> Option<Vec<[DVec2; 9]>> {
    let n = mesh.element_count();
    let neighbours = edge_neighbours(mesh, |a, b| (at[a] - at[b]).length());
    let corners_of = |kind: ElementKind| ideal_points(kind).map(|p| p.to_array());
    let (triangle, square) = (corners_of(ElementKind::Tri3), corners_of(ElementKind::Quad4));
    // a tangled mesh's folds and its noise are one: it is untangled against the ideal
    let mut tangled = false;
    let elements: Vec<stretch::StretchElement<'_, 2>> = (0..n)
        .zip(neighbours)
        .map(|(e, neighbours)| {
            let kind = mesh.kind(e);
            let k = kind.corners();
            let ids = mesh.element(e);
            let mut p = [DVec2::ZERO; 9];
            for (q, &i) in p.iter_mut().zip(ids) {
                *q = at[i as usize];
            }
            let edges = crate::quality::corner_edge_vectors(kind, &p[..kind.node_count()]);
            tangled |= edges[..k].iter().any(|&(a, b)| a.perp_dot(b) <= 0.0);
            let valid = edges[..k].iter().all(|&(a, b)| corner_frame(a, b, ideal_pair(kind)).is_some());
            stretch::StretchElement {
                corners: p[..k].iter().map(|q| q.to_array()).collect(),
                ideal: if k == 3 { &triangle[..3] } else { &square[..4] },
                valid,
                neighbours,
                axes: kind.stretch_axes(),
            }
        })
        .collect();
    if tangled {
        return None;
    }
    let maps = stretch::maps_if_stretched(&elements)?;
    Some(
        maps.iter()
            .enumerate()
            .map(|(e, map)| {
                let mut p = ideal_points(mesh.kind(e));
                if let Some(m) = map {
                    let m = DMat2::from_cols_array_2d(&[[m[0][0], m[1][0]], [m[0][1], m[1][1]]]);
                    p.iter_mut().for_each(|q| *q = m * *q);
                }
                p
            })
            .collect(),
    )
}

/// Each element's target corners with [`Target::Stretch`] for a volume mesh whose nodes
/// are read at `at`: its kind's ideal mapped by [`stretch::stretch_maps`]'s map, or the
/// ideal itself. `None` where no element is stretched on purpose.
pub fn volume_stretch_points(mesh: &crate::volume::VolumeMesh, at: &[glam::DVec3]) -> Option<Vec<[glam::DVec3; 8]>> {
    use glam::DVec3;
    let n = mesh.element_count();
    let corners = |e: usize| &mesh.element(e)[..mesh.element_kind(e).row().corners];
    // a tangled mesh's folds and its noise are one: it is untangled against the ideal
    let mut tangled = false;
    let elements: Vec<stretch::StretchElement<'_, 3>> = (0..n)
        .map(|e| {
            let row = mesh.element_kind(e).row();
            let ids = corners(e);
            let p = |i: usize| at[ids[i] as usize];
            let corner = |(c, &[a, b, d]): (usize, &[usize; 3])| DMat3::from_cols(p(a) - p(c), p(b) - p(c), p(d) - p(c));
            tangled |= row.corner_edges.iter().enumerate().any(|c| corner(c).determinant() <= 0.0);
            let valid = row.corner_edges.iter().enumerate().all(|c| solid_reference(corner(c), row.reference).is_some());
            let neighbours = mesh
                .face_neighbours(e)
                .iter()
                .map(|&f| {
                    // the shared face: the corners both hold, in this element's face order
                    let other = corners(f as usize);
                    let face = row.faces.iter().find(|face| face.iter().all(|&i| other.contains(&ids[i])));
                    let area = face.map_or(0.0, |face| {
                        let q: Vec<DVec3> = face.iter().map(|&i| p(i)).collect();
                        match q.len() {
                            3 => 0.5 * (q[1] - q[0]).cross(q[2] - q[0]).length(),
                            _ => 0.5 * (q[2] - q[0]).cross(q[3] - q[1]).length(),
                        }
                    });
                    (f, area.sqrt())
                })
                .collect();
            let corners = ids.iter().map(|&i| at[i as usize].to_array()).collect();
            stretch::StretchElement { corners, ideal: row.ideal, valid, neighbours, axes: row.stretch_axes }
        })
        .collect();
    if tangled {
        return None;
    }
    let maps = stretch::maps_if_stretched(&elements)?;
    Some(
        maps.iter()
            .enumerate()
            .map(|(e, map)| {
                let ideal = mesh.element_kind(e).row().ideal;
                let m = map.as_ref().map_or(DMat3::IDENTITY, mat3);
                let mut p = [DVec3::ZERO; 8];
                for (q, i) in p.iter_mut().zip(ideal) {
                    *q = m * DVec3::from_array(*i);
                }
                p
            })
            .collect(),
    )
}

/// Each element's target positions with [`Target::Stretch`] for a surface whose points
/// are read at `at`, in 3D: its ideal mapped by [`stretch::stretch_maps`]'s map, or the
/// ideal itself (turned by nothing). `None` where no element is stretched on purpose, or
/// where an element faces away from the surface (a tangled surface is untangled against
/// the ideal).
///
/// The field is the volumes' ([`volume_stretch_points`]) on each element made solid by
/// one more point: its centre moved off it along its normal by the square root of its
/// area, the ideal's the same. The stretch across the element is then its mean stretch
/// within it, so `M` keeps its shape only; the metrics are averaged in 3D, where a bent
/// surface's neighbours lie. A star reads each target in its own tangent plane.
pub fn surface_stretch_points(surface: &crate::surface::Surface, at: &[DVec3]) -> Option<Vec<[DVec3; 9]>> {
    let mesh = surface.flat();
    let n = mesh.element_count();
    let neighbours = edge_neighbours(mesh, |a, b| (at[a] - at[b]).length());
    // the ideals made solid: their corners in z = 0, then their centre lifted by √area
    let solid_ideal = |kind: ElementKind| -> Vec<[f64; 3]> {
        let k = kind.corners();
        let p = ideal_points(kind);
        let area = match k {
            3 => 0.5 * (p[1] - p[0]).perp_dot(p[2] - p[0]),
            _ => 0.5 * (p[2] - p[0]).perp_dot(p[3] - p[1]),
        };
        let centre = p[..k].iter().sum::<DVec2>() / k as f64;
        p[..k].iter().map(|q| [q.x, q.y, 0.0]).chain([[centre.x, centre.y, area.sqrt()]]).collect()
    };
    let (triangle, square) = (solid_ideal(ElementKind::Tri3), solid_ideal(ElementKind::Quad4));
    let mut tangled = false;
    let elements: Vec<stretch::StretchElement<'_, 3>> = (0..n)
        .zip(neighbours)
        .map(|(e, neighbours)| {
            let kind = mesh.kind(e);
            let k = kind.corners();
            let p: Vec<DVec3> = mesh.element(e)[..k].iter().map(|&i| at[i as usize]).collect();
            let normal = match k {
                3 => (p[1] - p[0]).cross(p[2] - p[0]),
                _ => (p[2] - p[0]).cross(p[3] - p[1]),
            };
            tangled |= normal.dot(surface.reference_normal(e)).partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater);
            // a corner is its own where its sine across the element is not too small
            let valid = (0..k).all(|c| {
                let (a, b) = (p[(c + 1) % k] - p[c], p[(c + k - 1) % k] - p[c]);
                a.cross(b).dot(normal.normalize_or_zero()) > LEAST_TARGET_SINE * a.length() * b.length()
            });
            let centre = p.iter().sum::<DVec3>() / k as f64;
            let lifted = centre + normal.normalize_or_zero() * (0.5 * normal.length()).sqrt();
            let corners = p.iter().chain([&lifted]).map(|q| q.to_array()).collect();
            stretch::StretchElement {
                corners,
                ideal: if k == 3 { &triangle } else { &square },
                valid,
                neighbours,
                axes: crate::mesh::StretchAxes::Kept,
            }
        })
        .collect();
    if tangled {
        return None;
    }
    let maps = stretch::maps_if_stretched(&elements)?;
    Some(
        maps.iter()
            .zip(&elements)
            .enumerate()
            .map(|(e, (map, el))| {
                let m = match map {
                    Some(m) => mat3(m),
                    // the ideal in the element's plane, its first edge along the element's
                    None => {
                        let p = |i: usize| DVec3::from_array(el.corners[i]);
                        let k = el.corners.len() - 1;
                        let centre = (0..k).map(p).sum::<DVec3>() / k as f64;
                        let normal = (p(k) - centre).normalize_or_zero();
                        let x = (p(1) - p(0)).normalize_or_zero();
                        DMat3::from_cols(x, normal.cross(x), normal)
                    }
                };
                ideal_points(mesh.kind(e)).map(|q| m * q.extend(0.0))
            })
            .collect(),
    )
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
        assert_eq!(Target::default(), Target::Stretch);
    }
}
