//! Star configurations: one free node and the ring of fixed nodes around it, the unit
//! tests of the smoothing papers.

use glam::DVec2;

use super::Assembly;
use crate::error::{Error, Result};
use crate::mesh::{ElementKind, Mesh};

enum_with_names! {
    /// Which star to build with [`star`].
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
    pub enum StarKind {
        /// Mesquite's `equil_tri`: `k` triangles round a regular `k`-gon of radius 2 whose
        /// first node is at (0, 2); the free node starts displaced from the centre (at
        /// (−0.8, −0.8) for `k = 6`, exactly as Mesquite's file). Optimised, the centre is
        /// the answer and, for `k = 6`, every triangle is equilateral.
        #[default]
        Regular => ("regular", "Mesquite's equil_tri: k triangles round a regular k-gon"),
        /// An irregular star-shaped but non-convex ring, like Chen, Tristano & Kwok (2003),
        /// Figure 10 "example with star shaped configuration" (its picture is lost; this is
        /// our reading): `k` nodes (`k` even, ≥ 6) alternating between spikes at radius
        /// 0.85–1.25 and notches at radius 0.25–0.3, angles slightly uneven, so every notch
        /// is a reflex corner and the valid region of the free node (the polygon's kernel)
        /// is a small convex set round the origin. The free node starts off-centre, 60% of
        /// the way from the origin to the kernel's edge in the direction (−0.8, −0.6).
        Chen => ("chen", "a star-shaped, non-convex ring of triangles (Chen et al., Fig. 10)"),
        /// `k` quads round the free node (`k ≥ 3`; 4 gives the 3 × 3 grid), like Chen's
        /// Figure 8 and the "test quadrilateral configuration" of Figure 20a (lost; ours):
        /// spoke nodes at radius 1, the outer corners where the spokes' perpendiculars meet,
        /// the first outer corner pulled out by 1.4 so the star is not symmetric, and the
        /// free node half-way from the origin to the edge of its valid region in the
        /// direction (−0.8, −0.6).
        Quad => ("quad", "k quads round the free node (Chen et al., Figs. 8 and 20a)"),
    }
}

impl StarKind {
    /// The number of elements round the free node the CLI uses by default: 6, 8, 4.
    pub fn default_k(self) -> usize {
        match self {
            StarKind::Regular => 6,
            StarKind::Chen => 8,
            StarKind::Quad => 4,
        }
    }
}

/// Direction in which the Chen and Quad stars displace their free node.
const OFF_CENTRE: DVec2 = DVec2::new(-0.8, -0.6);
/// The largest `k` accepted (a star is a unit test, not a mesh).
const MAX_K: usize = 1000;

/// A star configuration of `k` elements round one free node (the last node); the ring
/// nodes are fixed and counter-clockwise. See [`StarKind`] for the three shapes and the
/// valid `k` of each. All elements are valid (counter-clockwise) at the start.
pub fn star(kind: StarKind, k: usize) -> Result<Mesh> {
    let min = if kind == StarKind::Chen { 6 } else { 3 };
    if k < min || (kind == StarKind::Chen && k % 2 == 1) {
        let need = if kind == StarKind::Chen { "an even number of at least 6" } else { "at least 3" };
        return Err(Error::invalid(format!("a {kind:?} star needs {need} elements, not {k}")));
    }
    if k > MAX_K {
        return Err(Error::TooLarge(format!("a star of {k} elements; the limit is {MAX_K}")));
    }
    let step = std::f64::consts::TAU / k as f64;
    let polar = |r: f64, a: f64| {
        let (sin, cos) = crate::numeric::trig::sin_cos(a);
        r * DVec2::new(cos, sin)
    };
    let (ring, centre, quads) = match kind {
        StarKind::Regular => {
            let ring: Vec<DVec2> = (0..k).map(|i| polar(2.0, std::f64::consts::FRAC_PI_2 + step * i as f64)).collect();
            // Mesquite's displacement for k = 6, scaled with the inradius for other k
            let centre = DVec2::new(-0.8, -0.8)
                * (crate::numeric::trig::cos(std::f64::consts::PI / k as f64) / crate::numeric::trig::cos(std::f64::consts::PI / 6.0));
            (ring, centre, false)
        }
        StarKind::Chen => {
            const JITTER: [f64; 7] = [0.0, 0.1, -0.08, 0.05, -0.1, 0.08, -0.05];
            const SPIKE: [f64; 3] = [1.0, 1.25, 0.85];
            const NOTCH: [f64; 2] = [0.3, 0.25];
            let ring: Vec<DVec2> = (0..k)
                .map(|i| {
                    let r = if i % 2 == 0 { SPIKE[(i / 2) % 3] } else { NOTCH[(i / 2) % 2] };
                    polar(r, step * (i as f64 + JITTER[i % 7]))
                })
                .collect();
            let reach = kernel_reach(&ring, OFF_CENTRE);
            (ring, 0.6 * reach * OFF_CENTRE, false)
        }
        StarKind::Quad => {
            let mut ring = Vec::with_capacity(2 * k);
            let scale = 1.0 / (1.0 + crate::numeric::trig::cos(step));
            for i in 0..k {
                let (e0, e1) = (polar(1.0, step * i as f64), polar(1.0, step * (i + 1) as f64));
                ring.push(e0);
                ring.push((e0 + e1) * scale * if i == 0 { 1.4 } else { 1.0 });
            }
            // valid where the outer polygon's kernel meets that of the spoke nodes' polygon
            let spokes: Vec<DVec2> = ring.iter().step_by(2).copied().collect();
            let reach = kernel_reach(&ring, OFF_CENTRE).min(kernel_reach(&spokes, OFF_CENTRE));
            (ring, 0.5 * reach * OFF_CENTRE, true)
        }
    };
    let mut a = Assembly::with_capacity(ring.len() + 1, k);
    for p in &ring {
        a.node(*p);
    }
    let c = a.node(centre);
    let r = ring.len() as u32;
    for i in 0..k as u32 {
        if quads {
            a.element(ElementKind::Quad4, &[c, 2 * i, 2 * i + 1, (2 * i + 2) % r]);
        } else {
            a.element(ElementKind::Tri3, &[c, i, (i + 1) % r]);
        }
    }
    a.build()
}

/// The quadratic (6-node triangle) stars of Chen, Tristano & Kwok (2003), whose pictures
/// are lost; these are our readings of their captions. Ring nodes fixed, the centre free;
/// mid-side nodes of the spokes follow the centre.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum QuadraticStar {
    /// Figure 9, "configuration with one quadratic edge": six triangles round the centre
    /// of a regular hexagon of radius 1 with a horizontal top edge, that edge curved in
    /// towards the centre (its mid node at height [`PUSHED_MID_HEIGHT`] instead of
    /// √3/2). Its end tangents meet at (0, 2h − √3/2): "the best location for the
    /// center node is below the intersection of the two dash lines". The centre starts
    /// at the hexagon's centre.
    PushedEdge,
    /// Figure 16, "a node with three edges close to a curved boundary and two quadratic
    /// boundary edges": the centre joined to (−1, 0), (0, 0), (1, 0) of a bottom boundary
    /// whose two quadratic edges bulge up to [`CURVED_BULGE`], and to (1, 1), (0, 1),
    /// (−1, 1) above. The end tangents of the bulges leave (±1, 0) at 31° from the
    /// horizontal, so the centre must stay above those lines: it starts at (0.25, 0.85),
    /// and the Laplacian's centroid, (0, 0.5), lies below them (an inverted element).
    CurvedBoundary,
}

/// Height of the pushed-in top edge's mid node ([`QuadraticStar::PushedEdge`]).
pub const PUSHED_MID_HEIGHT: f64 = 0.5;
/// Height of the bottom edges' mid nodes ([`QuadraticStar::CurvedBoundary`]).
pub const CURVED_BULGE: f64 = 0.15;

/// A quadratic star (see [`QuadraticStar`]): the ring's corners first
/// (counter-clockwise), then the free centre, then the mid-side nodes.
pub fn quadratic_star(kind: QuadraticStar) -> Result<Mesh> {
    let (ring, centre, curved): (Vec<DVec2>, DVec2, Vec<(usize, DVec2)>) = match kind {
        QuadraticStar::PushedEdge => {
            let step = std::f64::consts::TAU / 6.0;
            let ring = (0..6).map(|i| {
                let a = step * (i as f64 + 0.5) - std::f64::consts::FRAC_PI_2;
                DVec2::new(a.cos(), a.sin())
            });
            let ring: Vec<DVec2> = ring.collect();
            // corners at −60°, 0°, 60°, …: the edge from ring[2] (60°) to ring[3] (120°) is the top one
            (ring, DVec2::ZERO, vec![(2, DVec2::new(0.0, PUSHED_MID_HEIGHT))])
        }
        QuadraticStar::CurvedBoundary => {
            let ring = [(-1.0, 0.0), (0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (-1.0, 1.0)];
            let ring: Vec<DVec2> = ring.iter().map(|&(x, y)| DVec2::new(x, y)).collect();
            (
                ring,
                DVec2::new(0.25, 0.85),
                vec![(0, DVec2::new(-0.5, CURVED_BULGE)), (1, DVec2::new(0.5, CURVED_BULGE))],
            )
        }
    };
    let k = ring.len();
    let mut a = Assembly::with_capacity(3 * k + 1, k);
    for p in &ring {
        a.node(*p);
    }
    let c = a.node(centre);
    let spoke: Vec<u32> = ring.iter().map(|p| a.node(0.5 * (*p + centre))).collect();
    let outer: Vec<u32> = (0..k)
        .map(|i| {
            let mid = curved.iter().find(|(e, _)| *e == i).map_or(0.5 * (ring[i] + ring[(i + 1) % k]), |(_, m)| *m);
            a.node(mid)
        })
        .collect();
    for i in 0..k {
        let j = (i + 1) % k;
        a.element(ElementKind::Tri6, &[c, i as u32, j as u32, spoke[i], outer[i], spoke[j]]);
    }
    a.build()
}

/// How far from the origin one can go in the unit direction `d` and stay inside the
/// kernel of the counter-clockwise polygon `ring` (which must contain the origin in its
/// kernel): the kernel is the intersection of the half-planes left of each edge `a → b`,
/// `cross(b − a, t·d − a) > 0`, i.e. `t < cross(a, b) / cross(d, b − a)` where that is
/// positive.
fn kernel_reach(ring: &[DVec2], d: DVec2) -> f64 {
    let d = d.normalize();
    let mut t = f64::INFINITY;
    for (i, &a) in ring.iter().enumerate() {
        let b = ring[(i + 1) % ring.len()];
        let c1 = d.perp_dot(b - a);
        if c1 > 0.0 {
            t = t.min(a.perp_dot(b) / c1);
        }
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::test_util::assert_valid;
    use crate::quality::{lo_alpha, mesh_stats};

    fn free_node(m: &Mesh) -> usize {
        let free: Vec<usize> = (0..m.node_count()).filter(|&n| m.is_free(n)).collect();
        assert_eq!(free.len(), 1, "one free node");
        free[0]
    }

    #[test]
    fn one_free_node_and_k_elements() {
        for kind in [StarKind::Regular, StarKind::Chen, StarKind::Quad] {
            for k in (3..=16).filter(|&k| star(kind, k).is_ok()) {
                let m = star(kind, k).unwrap();
                assert_valid(&m);
                assert_eq!(m.element_count(), k);
                let c = free_node(&m);
                assert_eq!(c, m.node_count() - 1, "the free node is the last");
                assert_eq!(m.node_elements(c).len(), k);
                assert_eq!(m.node_count(), if kind == StarKind::Quad { 2 * k + 1 } else { k + 1 });
                assert!(m.nodes()[c].length() > 0.05, "{kind:?} k={k}: the free node starts off-centre");
            }
        }
        assert!(star(StarKind::Chen, 8).is_ok() && star(StarKind::Quad, 4).is_ok());
    }

    #[test]
    fn regular_six_is_mesquites_equil_tri() {
        let m = star(StarKind::Regular, 6).unwrap();
        let s3 = 3f64.sqrt();
        let expect = [(0.0, 2.0), (-s3, 1.0), (-s3, -1.0), (0.0, -2.0), (s3, -1.0), (s3, 1.0), (-0.8, -0.8)];
        for (p, (x, y)) in m.nodes().iter().zip(expect) {
            assert!(p.distance(DVec2::new(x, y)) < 1e-12, "{p}");
        }
        // with the free node at the centre every triangle is equilateral
        for i in 0..6 {
            assert!((lo_alpha(DVec2::ZERO, m.nodes()[i], m.nodes()[(i + 1) % 6]) - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn chen_star_is_star_shaped_and_not_convex() {
        for k in (6..=20).step_by(2) {
            let m = star(StarKind::Chen, k).unwrap();
            let ring = &m.nodes()[..k];
            for i in 0..k {
                let (prev, p, next) = (ring[(i + k - 1) % k], ring[i], ring[(i + 1) % k]);
                let turn = (p - prev).perp_dot(next - p);
                // spikes are convex corners, every notch a reflex one
                assert_eq!(turn < 0.0, i % 2 == 1, "k={k} corner {i}: {turn}");
            }
            // star-shaped about the origin and about the start: every triangle valid
            let c = m.nodes()[k];
            for i in 0..k {
                assert!(lo_alpha(DVec2::ZERO, ring[i], ring[(i + 1) % k]) > 0.0);
                assert!(lo_alpha(c, ring[i], ring[(i + 1) % k]) > 0.0);
            }
            // the start is inside the kernel, and the kernel ends not far beyond it
            let beyond = c / 0.6 * 1.01;
            assert!((0..k).any(|i| lo_alpha(beyond, ring[i], ring[(i + 1) % k]) < 0.0), "k={k}");
        }
    }

    #[test]
    fn quad_star_four_is_a_distorted_three_by_three_grid() {
        let m = star(StarKind::Quad, 4).unwrap();
        let expect =
            [(1.0, 0.0), (1.4, 1.4), (0.0, 1.0), (-1.0, 1.0), (-1.0, 0.0), (-1.0, -1.0), (0.0, -1.0), (1.0, -1.0)];
        for (p, (x, y)) in m.nodes().iter().zip(expect) {
            assert!(p.distance(DVec2::new(x, y)) < 1e-12, "{p}");
        }
        let s = mesh_stats(&m);
        assert!(s.min_quality > 0.0 && s.min_quality < 0.9, "valid but not ideal: {}", s.min_quality);
        // the free node lies half-way to where some quad corner would fold
        let c = m.nodes()[8];
        let mut beyond = m.clone();
        beyond.nodes_mut()[8] = c * 2.02;
        assert!(mesh_stats(&beyond).inverted > 0);
        beyond.nodes_mut()[8] = c * 1.98;
        assert_eq!(mesh_stats(&beyond).inverted, 0);
    }

    #[test]
    fn quadratic_stars_are_valid_with_one_free_node_by_their_curved_edges() {
        for kind in [QuadraticStar::PushedEdge, QuadraticStar::CurvedBoundary] {
            let m = quadratic_star(kind).unwrap();
            assert_valid(&m);
            assert_eq!(free_node(&m), 6, "{kind:?}: the centre follows the ring");
            assert_eq!(m.element_count(), 6);
            let curved = m.edges().iter().filter(|e| e.curved).count();
            assert_eq!(curved, if kind == QuadraticStar::PushedEdge { 1 } else { 2 }, "{kind:?}");
            assert!(m.has_quadratic());
        }
    }

    #[test]
    fn bad_k_is_an_error() {
        for (kind, k) in [(StarKind::Regular, 2), (StarKind::Quad, 0), (StarKind::Chen, 4), (StarKind::Chen, 7)] {
            assert!(matches!(star(kind, k), Err(Error::Invalid(_))), "{kind:?} {k}");
        }
        assert!(matches!(star(StarKind::Regular, 1_000_000), Err(Error::TooLarge(_))));
    }
}
