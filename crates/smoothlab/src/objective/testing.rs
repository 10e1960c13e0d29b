//! Shared test helpers for the objectives: stars built from explicit coordinates, a
//! small deterministic random generator, and finite-difference gradient checks.

use glam::DVec2;

use super::{Objective, Star, StarElement, Term};
use crate::mesh::ElementKind;

pub fn d(x: f64, y: f64) -> DVec2 {
    DVec2::new(x, y)
}

/// The tests draw from the crate's one generator, seeded, so failures reproduce.
pub use crate::numeric::SplitMix64;

/// The random points the objectives' tests take.
pub trait SquarePoint {
    /// Uniform in the square [−r, r]² (x drawn first).
    fn point(&mut self, r: f64) -> DVec2;
}

impl SquarePoint for SplitMix64 {
    fn point(&mut self, r: f64) -> DVec2 {
        let x = self.uniform(-r, r);
        d(x, self.uniform(-r, r))
    }
}

/// A star element from explicit node coordinates (element order), free node at `slot`.
/// Quadratic elements get following mid-side nodes on the free node's edges.
pub fn elem(kind: ElementKind, pts: &[DVec2], slot: usize) -> StarElement {
    assert_eq!(pts.len(), kind.node_count());
    let mut p = [DVec2::ZERO; 9];
    p[..pts.len()].copy_from_slice(pts);
    StarElement {
        kind,
        element: 0,
        pts: p,
        slot: slot as u8,
        follow_next: kind.is_quadratic(),
        follow_prev: kind.is_quadratic(),
    }
}

/// A star from elements; `x0` is the free node of the first element, element numbers
/// are their positions, `mixed` is set when both triangles and quads are present.
pub fn star(elems: Vec<StarElement>) -> Star {
    let mut elems = elems;
    for (i, e) in elems.iter_mut().enumerate() {
        e.element = i as u32;
    }
    let mixed =
        elems.iter().any(|e| e.kind.is_triangle()) && elems.iter().any(|e| e.kind.is_quad());
    let x0 = elems
        .first()
        .map(|e| e.pts[e.slot as usize])
        .unwrap_or_default();
    Star {
        node: 0,
        x0,
        elems,
        mixed,
        ..Default::default()
    }
}

/// `k` points on the circle of radius `r` about the origin, the first at angle 0.
pub fn regular_ring(k: usize, r: f64) -> Vec<DVec2> {
    (0..k)
        .map(|i| r * DVec2::from_angle(std::f64::consts::TAU * i as f64 / k as f64))
        .collect()
}

/// Triangles (origin, ring[i], ring[i+1]) around the free node at the origin.
pub fn fan_star(ring: &[DVec2]) -> Star {
    fan_star_at(DVec2::ZERO, ring)
}

/// Triangles (x0, ring[i], ring[i+1]) around the free node at `x0`.
pub fn fan_star_at(x0: DVec2, ring: &[DVec2]) -> Star {
    let k = ring.len();
    star(
        (0..k)
            .map(|i| elem(ElementKind::Tri3, &[x0, ring[i], ring[(i + 1) % k]], 0))
            .collect(),
    )
}

/// Four quads around the free node at the origin from an 8-point ring (counter-clockwise,
/// the edge neighbours at even indices): quad i is (origin, ring[2i], ring[2i+1], ring[2i+2]).
pub fn quad_star_from(ring: &[DVec2; 8]) -> Star {
    star(
        (0..4)
            .map(|i| {
                elem(
                    ElementKind::Quad4,
                    &[
                        DVec2::ZERO,
                        ring[2 * i],
                        ring[2 * i + 1],
                        ring[(2 * i + 2) % 8],
                    ],
                    0,
                )
            })
            .collect(),
    )
}

/// The four unit squares around the origin.
pub fn square_ring() -> [DVec2; 8] {
    [
        d(1.0, 0.0),
        d(1.0, 1.0),
        d(0.0, 1.0),
        d(-1.0, 1.0),
        d(-1.0, 0.0),
        d(-1.0, -1.0),
        d(0.0, -1.0),
        d(1.0, -1.0),
    ]
}

/// The four unit squares around the origin, as a star.
pub fn quad_star() -> Star {
    quad_star_from(&square_ring())
}

/// Two quads above, three triangles below: a mixed star (Chen's ×3 triangle weight applies).
pub fn mixed_star() -> Star {
    let o = DVec2::ZERO;
    star(vec![
        elem(
            ElementKind::Quad4,
            &[o, d(1.0, 0.0), d(1.0, 1.0), d(0.0, 1.0)],
            0,
        ),
        elem(
            ElementKind::Quad4,
            &[o, d(0.0, 1.0), d(-1.0, 1.0), d(-1.0, 0.0)],
            0,
        ),
        elem(ElementKind::Tri3, &[o, d(-1.0, 0.0), d(-0.5, -0.9)], 0),
        elem(ElementKind::Tri3, &[o, d(-0.5, -0.9), d(0.5, -0.9)], 0),
        elem(ElementKind::Tri3, &[o, d(0.5, -0.9), d(1.0, 0.0)], 0),
    ])
}

/// The same star with quadratic elements (Tri6, Quad8), mid-side nodes at the edge
/// midpoints, those on the free node's edges following it.
pub fn quadratic(s: &Star) -> Star {
    let elems = s
        .elems
        .iter()
        .map(|e| {
            let kind = if e.kind.is_triangle() {
                ElementKind::Tri6
            } else {
                ElementKind::Quad8
            };
            let k = kind.corners();
            let mut p = [DVec2::ZERO; 9];
            p[..k].copy_from_slice(&e.pts[..k]);
            for i in 0..k {
                p[k + i] = 0.5 * (p[i] + p[(i + 1) % k]);
            }
            elem(kind, &p[..kind.node_count()], e.slot as usize)
        })
        .collect();
    Star { elems, ..s.clone() }
}

/// A quadratic star made curved: the mid-side nodes of the edges away from the free node
/// pushed outward by `bulge` (times the edge length), and on every other element the free
/// node's edges do not follow it (as on a curved boundary), so they bend as it moves.
pub fn curved(s: &Star, bulge: f64) -> Star {
    let mut q = quadratic(s);
    for (n, e) in q.elems.iter_mut().enumerate() {
        let k = e.kind.corners();
        let slot = e.slot as usize;
        for i in 0..k {
            let (a, b) = (i, (i + 1) % k);
            if a == slot || b == slot {
                continue;
            }
            let chord = e.pts[b] - e.pts[a];
            e.pts[k + i] += bulge * -chord.perp();
        }
        if n % 2 == 1 {
            e.follow_next = false;
            e.follow_prev = false;
        }
    }
    q
}

/// A 5-pointed star polygon around the free node (outer radius 1, inner 0.45): a
/// non-convex "star-shaped configuration" whose kernel is a small pentagon about the centre.
pub fn star_polygon() -> Vec<DVec2> {
    (0..10)
        .map(|i| {
            let r = if i % 2 == 0 { 1.0 } else { 0.45 };
            r * DVec2::from_angle(std::f64::consts::PI * i as f64 / 5.0 + 0.1)
        })
        .collect()
}

/// A varied set of stars for gradient checks: perturbed triangle fans, quads, mixed,
/// quadratic (straight and curved).
pub fn sample_stars() -> Vec<Star> {
    let mut rng = SplitMix64::new(3);
    let mut out = Vec::new();
    for k in [3, 5, 6, 7] {
        let ring: Vec<DVec2> = regular_ring(k, 1.0)
            .into_iter()
            .map(|p| p + rng.point(0.2))
            .collect();
        out.push(fan_star(&ring));
    }
    let mut ring = square_ring();
    for p in ring.iter_mut() {
        *p += rng.point(0.2);
    }
    out.push(quad_star_from(&ring));
    out.push(mixed_star());
    out.push(fan_star(&star_polygon()));
    let lin = out.clone();
    for s in &lin[..] {
        out.push(quadratic(s));
    }
    out.push(curved(&lin[1], 0.15));
    out.push(curved(&lin[4], -0.1));
    out.push(curved(&lin[5], 0.1));
    out
}

/// Central-difference gradient of `f` at `x` with step `h`.
pub fn fd_grad(f: impl Fn(DVec2) -> f64, x: DVec2, h: f64) -> DVec2 {
    let dx = d(h, 0.0);
    let dy = d(0.0, h);
    d(
        (f(x + dx) - f(x - dx)) / (2.0 * h),
        (f(x + dy) - f(x - dy)) / (2.0 * h),
    )
}

/// Whether `f` looks smooth at `x` along both axes: the one-sided differences agree
/// (a kink shows a jump of the slope, a smooth point only `h·f''`).
pub fn looks_smooth(f: impl Fn(DVec2) -> f64, x: DVec2, h: f64) -> bool {
    let f0 = f(x);
    [d(h, 0.0), d(0.0, h)].iter().all(|&s| {
        let fwd = (f(x + s) - f0) / h;
        let bwd = (f0 - f(x - s)) / h;
        fwd.is_finite()
            && bwd.is_finite()
            && (fwd - bwd).abs() <= 1e-3 * (1.0 + fwd.abs().max(bwd.abs()))
    })
}

/// Checks the analytic gradient of the objective's value (a smooth objective) against
/// central differences: `|g − g_fd| ≤ tol·(1 + |g_fd|)`. Panics with the position on failure.
pub fn check_gradient(obj: &dyn Objective, s: &Star, x: DVec2, tol: f64) {
    let h = 1e-6;
    let (_, g) = obj.value_and_gradient(s, x);
    let fd = fd_grad(|p| obj.value(s, p), x, h);
    assert!(
        (g - fd).length() <= tol * (1.0 + fd.length()),
        "{}: gradient {g} but central differences {fd} at {x}",
        obj.name()
    );
}

/// Checks the analytic Hessian of a smooth objective ([`Objective::value_gradient_hessian`],
/// which must give one) against central differences of its analytic gradient, column by
/// column: `|H e_i − (g(x + h e_i) − g(x − h e_i))/2h| ≤ tol·(1 + |that|)`; and that its value
/// and gradient are `value_and_gradient`'s, bit for bit. Panics with the position on failure.
pub fn check_hessian(obj: &dyn Objective, s: &Star, x: DVec2, tol: f64) {
    let h = 1e-6;
    let (v, g, hess) = obj
        .value_gradient_hessian(s, x)
        .expect("an analytic Hessian");
    assert_eq!(
        (v, g),
        obj.value_and_gradient(s, x),
        "{}: value and gradient at {x}",
        obj.name()
    );
    assert!(
        hess.x_axis.y == hess.y_axis.x
            || (hess.x_axis.y - hess.y_axis.x).abs() <= 1e-12 * hess.x_axis.y.abs(),
        "symmetric"
    );
    for (i, col) in [hess.x_axis, hess.y_axis].into_iter().enumerate() {
        let e = if i == 0 { d(h, 0.0) } else { d(0.0, h) };
        let fd =
            (obj.value_and_gradient(s, x + e).1 - obj.value_and_gradient(s, x - e).1) / (2.0 * h);
        assert!(
            (col - fd).length() <= tol * (1.0 + fd.length()),
            "{}: Hessian column {i} {col} but central differences {fd} at {x}",
            obj.name()
        );
    }
}

/// The value of term `i` at `x`.
pub fn term_value(obj: &dyn Objective, s: &Star, x: DVec2, i: usize) -> f64 {
    let mut t: Vec<Term> = Vec::new();
    obj.terms(s, x, &mut t);
    t[i].value
}

/// Checks each term's gradient against central differences of that term, skipping terms
/// at kinks or barriers; returns (terms checked, terms seen).
pub fn check_term_gradients(obj: &dyn Objective, s: &Star, x: DVec2, tol: f64) -> (usize, usize) {
    let h = 1e-6;
    let mut t = Vec::new();
    obj.terms(s, x, &mut t);
    let mut checked = 0;
    for (i, term) in t.iter().enumerate() {
        let f = |p: DVec2| term_value(obj, s, p, i);
        if !term.value.is_finite() || !looks_smooth(f, x, h) {
            continue;
        }
        let fd = fd_grad(f, x, h);
        assert!(
            (term.grad - fd).length() <= tol * (1.0 + fd.length()),
            "{}: term {i} gradient {} but central differences {fd} at {x}",
            obj.name(),
            term.grad
        );
        checked += 1;
    }
    (checked, t.len())
}
