//! Grading: how fast element sizes change from one element to the next. The statistic is
//! the largest ratio of the sizes of two valid elements that share an edge (planar meshes,
//! surfaces) or a face (volumes): areas in 2D, volumes in 3D. It is the "volume ratio"
//! (or "cell volume change") of the mesh checks of CFD codes, where boundary layers are
//! graded on purpose and a jump in size is a fault.
//!
//! A size is kept as a mantissa and a power of two, each element measured in its own
//! scale ([`Size`]), so the ratio is the same at every scale, even where the areas or
//! volumes themselves would leave the doubles.

use glam::{DVec2, DVec3};

use crate::mesh::{ElementKind, Mesh, VolumeKind};

/// A positive area or volume `m·2^e` with `m` in [1, 2), measured with the element
/// brought near unit size by a power of two (exact).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Size {
    m: f64,
    e: i32,
}

impl Size {
    /// The size `x·2^e` of a positive finite `x` measured in unit scale.
    fn of(x: f64, e: i32) -> Option<Size> {
        if !(x > 0.0 && x.is_finite()) {
            return None;
        }
        let k = binary_exponent(x);
        Some(Size { m: times_pow2(x, -k), e: e + k })
    }
    /// `larger / smaller` of two sizes: at least 1; +∞ beyond the doubles.
    pub fn ratio(a: Size, b: Size) -> f64 {
        let (big, small) = if (a.e, a.m) < (b.e, b.m) { (b, a) } else { (a, b) };
        times_pow2(big.m / small.m, big.e - small.e)
    }
}

/// `x·2^e`, a step at a time (beyond the doubles: ∞ or 0, as the product is).
fn times_pow2(mut x: f64, mut e: i32) -> f64 {
    while e > 1000 {
        x *= crate::numeric::pow2(1000);
        e -= 1000;
    }
    while e < -1000 {
        x *= crate::numeric::pow2(-1000);
        e += 1000;
    }
    x * crate::numeric::pow2(e)
}

/// The exponent `k` with `2^k ≤ x < 2^(k+1)`, for a positive finite `x`.
fn binary_exponent(x: f64) -> i32 {
    if x < f64::MIN_POSITIVE {
        return binary_exponent(x * crate::numeric::pow2(64)) - 64;
    }
    ((x.to_bits() >> 52) & 0x7ff) as i32 - 1023
}

/// The exponent `k` of the largest `|component|` `m`, with which `times_pow2(·, −k)` brings
/// an element near unit size; `None` where `m` is 0 or not finite.
fn unit_exponent(m: f64) -> Option<i32> {
    (m > 0.0 && m.is_finite()).then(|| binary_exponent(m))
}

/// The area of a planar element with nodes `p` (its kind's order): the corner polygon's,
/// plus, for a quadratic element, the area each curved edge adds to its chord,
/// `(2/3)·cross(M − P₀, P₂ − P₀)` (the parabola through the edge's three nodes). `None`
/// where it is not positive (an inverted or flat element has no size to compare).
pub fn planar_size(kind: ElementKind, p: &[DVec2]) -> Option<Size> {
    let k = kind.corners();
    let m = (1..kind.node_count()).map(|i| (p[i] - p[0]).abs().max_element()).fold(0.0, f64::max);
    let k_unit = unit_exponent(m)?;
    // one factor where 2^-k is a normal double, else a step at a time
    let f = (k_unit.abs() <= 1000).then(|| crate::numeric::pow2(-k_unit));
    let q = |i: usize| match f {
        Some(f) => (p[i] - p[0]) * f,
        None => (p[i] - p[0]).map(|c| times_pow2(c, -k_unit)),
    };
    let mut twice = 0.0;
    for i in 1..k - 1 {
        twice += q(i).perp_dot(q(i + 1));
    }
    let mut area = 0.5 * twice;
    for i in 0..k {
        if let Some(mid) = kind.mid(i) {
            let (a, b) = (q(i), q((i + 1) % k));
            area += (2.0 / 3.0) * (q(mid) - a).perp_dot(b - a);
        }
    }
    Size::of(area, 2 * k_unit)
}

/// The volume of a volume element with nodes `p` (its kind's order), through its corners:
/// a tetrahedron's, or the (tri)linear element's `∫det J` (a wedge and a pyramid as
/// hexahedra with corners repeated; in closed form, exact). `None` where it is not
/// positive.
pub fn solid_size(kind: VolumeKind, p: &[DVec3]) -> Option<Size> {
    const HEX: [usize; 8] = [0, 1, 2, 3, 4, 5, 6, 7];
    const WEDGE: [usize; 8] = [0, 1, 2, 2, 3, 4, 5, 5];
    const PYRAMID: [usize; 8] = [0, 1, 2, 3, 4, 4, 4, 4];
    let c = kind.corners();
    let m = (1..c).map(|i| (p[i] - p[0]).abs().max_element()).fold(0.0, f64::max);
    let k_unit = unit_exponent(m)?;
    // one factor where 2^-k is a normal double, else a step at a time
    let f = (k_unit.abs() <= 1000).then(|| crate::numeric::pow2(-k_unit));
    let q = |i: usize| match f {
        Some(f) => (p[i] - p[0]) * f,
        None => (p[i] - p[0]).map(|c| times_pow2(c, -k_unit)),
    };
    let volume = match kind {
        VolumeKind::Tet4 | VolumeKind::Tet10 => q(1).dot(q(2).cross(q(3))) / 6.0,
        VolumeKind::Hex8 | VolumeKind::Hex20 | VolumeKind::Hex27 => trilinear_volume(HEX.map(q)),
        VolumeKind::Wedge6 => trilinear_volume(WEDGE.map(q)),
        VolumeKind::Pyramid5 => trilinear_volume(PYRAMID.map(q)),
    };
    Size::of(volume, 3 * k_unit)
}

/// `∫det J` over `[−1, 1]³` of the trilinear map through the eight corners `x` (VTK's
/// hexahedron order), in closed form. With the map's modes
/// `x(u, v, w) = (m + m_u·u + m_v·v + m_w·w + m_uv·uv + m_uw·uw + m_vw·vw + m_uvw·uvw)/8`,
/// every term of `det J` odd in a coordinate integrates to 0, and what is left is
/// `(det(m_u, m_v, m_w) + (det(m_u, m_uv, m_uw) + det(m_uv, m_v, m_vw) + det(m_uw, m_vw, m_w))/3)/64`.
/// The twisted mode `m_uvw` drops out.
fn trilinear_volume(x: [DVec3; 8]) -> f64 {
    // each mode is the corners signed by the product of their coordinates' signs
    let [a, b, c, d, e, f, g, h] = x;
    let m_u = (b - a) + (c - d) + (f - e) + (g - h);
    let m_v = (d - a) + (c - b) + (h - e) + (g - f);
    let m_w = (e - a) + (f - b) + (g - c) + (h - d);
    let m_uv = (a - b) + (c - d) + (e - f) + (g - h);
    let m_uw = (a - b) + (d - c) + (f - e) + (g - h);
    let m_vw = (a - d) + (b - c) + (h - e) + (g - f);
    let det = |p: DVec3, q: DVec3, r: DVec3| p.dot(q.cross(r));
    let twist = det(m_u, m_uv, m_uw) + det(m_uv, m_v, m_vw) + det(m_uw, m_vw, m_w);
    (det(m_u, m_v, m_w) + twist / 3.0) / 64.0
}

/// The largest [`Size::ratio`] over the pairs of neighbours `pairs` whose sizes both
/// exist; `None` where no pair has.
pub fn largest_ratio(sizes: &[Option<Size>], pairs: impl IntoIterator<Item = (usize, usize)>) -> Option<f64> {
    pairs
        .into_iter()
        .filter_map(|(a, b)| Some(Size::ratio(sizes[a]?, sizes[b]?)))
        .fold(None, |m: Option<f64>, r| Some(m.map_or(r, |m| m.max(r))))
}

/// The pairs of a planar mesh's elements that share an edge: each inner edge's two.
pub fn edge_neighbours(mesh: &Mesh) -> impl Iterator<Item = (usize, usize)> + '_ {
    inner_edges(mesh).map(|(_, e, f)| (e, f))
}

/// Each inner edge of a planar mesh with its two elements, the lower numbered first, in
/// the order of the mesh's edges.
pub fn inner_edges(mesh: &Mesh) -> impl Iterator<Item = (&crate::mesh::Edge, usize, usize)> + '_ {
    mesh.edges().iter().filter(|edge| !edge.boundary).filter_map(|edge| {
        let (a, b) = (mesh.node_elements(edge.a as usize), mesh.node_elements(edge.b as usize));
        let mut shared = a.iter().filter(|e| b.contains(e));
        Some((edge, *shared.next()? as usize, *shared.next()? as usize))
    })
}

/// The elements that share an edge with element `e` of a planar mesh.
pub fn edge_neighbours_of(mesh: &Mesh, e: usize) -> impl Iterator<Item = usize> + '_ {
    let ids = mesh.element(e);
    let k = mesh.kind(e).corners();
    (0..k).filter_map(move |i| {
        let (a, b) = (ids[i] as usize, ids[(i + 1) % k]);
        mesh.node_elements(a).iter().find(|&&f| f as usize != e && mesh.element(f as usize)[..mesh.kind(f as usize).corners()].contains(&b)).map(|&f| f as usize)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_square() -> [DVec2; 4] {
        [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y]
    }

    #[test]
    fn areas_and_volumes_by_hand() {
        let sq = planar_size(ElementKind::Quad4, &unit_square()).unwrap();
        let tri = planar_size(ElementKind::Tri3, &[DVec2::ZERO, DVec2::X, DVec2::Y]).unwrap();
        assert_eq!(Size::ratio(sq, tri), 2.0);
        assert_eq!(Size::ratio(tri, sq), 2.0);
        // a quadratic triangle whose edge 0–1 bulges out by 0.3 at its middle: + (2/3)·0.3
        let mut p = [DVec2::ZERO, DVec2::X, DVec2::Y, DVec2::new(0.5, -0.3), DVec2::new(0.5, 0.5), DVec2::new(0.0, 0.5)];
        let bulged = planar_size(ElementKind::Tri6, &p).unwrap();
        assert!((Size::ratio(bulged, tri) - (0.5 + 0.2) / 0.5).abs() < 1e-15);
        p[3] = DVec2::new(0.5, 0.0);
        assert_eq!(Size::ratio(planar_size(ElementKind::Tri6, &p).unwrap(), tri), 1.0);
        // the unit cube against its tetrahedra and its halves
        let cube = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y, DVec3::Z, DVec3::new(1.0, 0.0, 1.0), DVec3::ONE, DVec3::new(0.0, 1.0, 1.0)];
        let hex = solid_size(VolumeKind::Hex8, &cube).unwrap();
        let tet = solid_size(VolumeKind::Tet4, &[DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z]).unwrap();
        assert!((Size::ratio(hex, tet) - 6.0).abs() < 1e-14);
        let wedge = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z, DVec3::new(1.0, 0.0, 1.0), DVec3::new(0.0, 1.0, 1.0)];
        assert!((Size::ratio(hex, solid_size(VolumeKind::Wedge6, &wedge).unwrap()) - 2.0).abs() < 1e-14);
        let pyramid = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y, DVec3::new(0.5, 0.5, 1.0)];
        assert!((Size::ratio(hex, solid_size(VolumeKind::Pyramid5, &pyramid).unwrap()) - 3.0).abs() < 1e-14);
        // a hexahedron with its top face twisted: ∫det J is not the corners' prism volume
        let mut twisted = cube;
        twisted[6] += DVec3::new(0.0, 0.0, 0.5);
        let v = Size::ratio(solid_size(VolumeKind::Hex8, &twisted).unwrap(), hex);
        assert!((v - 1.125).abs() < 1e-14, "{v}");
    }

    #[test]
    fn the_closed_form_is_the_gauss_rule_which_is_exact_for_det_j() {
        // det J is at most quadratic in each coordinate: 2 × 2 × 2 Gauss points integrate it
        let gauss = |x: [DVec3; 8]| {
            let shape = |u: f64, v: f64, w: f64, i: usize| {
                let s = [(-1.0, -1.0, -1.0), (1.0, -1.0, -1.0), (1.0, 1.0, -1.0), (-1.0, 1.0, -1.0), (-1.0, -1.0, 1.0), (1.0, -1.0, 1.0), (1.0, 1.0, 1.0), (-1.0, 1.0, 1.0)][i];
                [s.0 * (1.0 + s.1 * v) * (1.0 + s.2 * w), (1.0 + s.0 * u) * s.1 * (1.0 + s.2 * w), (1.0 + s.0 * u) * (1.0 + s.1 * v) * s.2].map(|d| d / 8.0)
            };
            let g = 1.0 / 3f64.sqrt();
            let mut volume = 0.0;
            for (u, v, w) in [-g, g].into_iter().flat_map(|u| [-g, g].into_iter().flat_map(move |v| [-g, g].map(|w| (u, v, w)))) {
                let mut j = [DVec3::ZERO; 3];
                for (i, p) in x.iter().enumerate() {
                    for (c, d) in j.iter_mut().zip(shape(u, v, w, i)) {
                        *c += *p * d;
                    }
                }
                volume += j[0].dot(j[1].cross(j[2]));
            }
            volume
        };
        let cube = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y, DVec3::Z, DVec3::new(1.0, 0.0, 1.0), DVec3::ONE, DVec3::new(0.0, 1.0, 1.0)];
        let mut state = 7u64;
        let mut next = || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for _ in 0..200 {
            let x = cube.map(|p| p + DVec3::new(next(), next(), next()) * 0.6);
            let (closed, reference) = (trilinear_volume(x), gauss(x));
            assert!((closed - reference).abs() <= 1e-14 * reference.abs().max(1.0), "{closed} vs {reference}");
        }
    }

    #[test]
    fn inverted_and_flat_elements_have_no_size() {
        let mut cw = unit_square();
        cw.reverse();
        assert_eq!(planar_size(ElementKind::Quad4, &cw), None);
        assert_eq!(planar_size(ElementKind::Tri3, &[DVec2::ZERO, DVec2::X, DVec2::new(2.0, 0.0)]), None);
        assert_eq!(solid_size(VolumeKind::Tet4, &[DVec3::ZERO, DVec3::Y, DVec3::X, DVec3::Z]), None);
        assert_eq!(largest_ratio(&[None, None], [(0, 1)]), None);
    }

    #[test]
    fn the_ratio_is_the_same_at_every_scale() {
        let big = unit_square().map(|x| x * 3.0);
        for e in [-1070, -1000, -600, -300, 0, 300, 600, 1000] {
            let f = 2f64.powi(e / 2) * 2f64.powi(e - e / 2);
            let a = planar_size(ElementKind::Quad4, &unit_square().map(|x| x * f)).unwrap();
            let b = planar_size(ElementKind::Quad4, &big.map(|x| x * f)).unwrap();
            assert_eq!(Size::ratio(a, b), 9.0, "2^{e}");
        }
        // two neighbours of very different sizes: the ratio as large as it is
        let tiny = planar_size(ElementKind::Quad4, &unit_square().map(|x| x * 2f64.powi(-500))).unwrap();
        let huge = planar_size(ElementKind::Quad4, &unit_square().map(|x| x * 2f64.powi(500))).unwrap();
        assert_eq!(Size::ratio(tiny, huge), f64::INFINITY);
        let small = planar_size(ElementKind::Quad4, &unit_square().map(|x| x * 2f64.powi(-200))).unwrap();
        let large = planar_size(ElementKind::Quad4, &unit_square().map(|x| x * 2f64.powi(200))).unwrap();
        assert_eq!(Size::ratio(small, large), 2f64.powi(800));
    }
}
