//! Tests of the properties Chen et al. state for the new objective (`docs/formulas.md` §3), one
//! test per property, on stars built from explicit coordinates.

use std::f64::consts::PI;

use proptest::prelude::*;

use super::*;
use crate::mesh::ElementKind;
use crate::objective::testing::*;
use crate::objective::Objective;
use crate::quality::element_quality;

/// The first design (adjusted-angle penalty), whose tests these are unless said.
fn new() -> ChenTristanoKwok {
    ChenTristanoKwok::with_penalty(Penalty::Angle)
}

/// The first design with the literal-reading length.
fn literal() -> ChenTristanoKwok {
    ChenTristanoKwok::Angle(AnglePenalty { length: PenaltyLength::Opposite, ..AnglePenalty::default() })
}

/// The regularised barrier (the default design).
fn barrier() -> ChenTristanoKwok {
    ChenTristanoKwok::default()
}

/// `Σ (1 − α)²` alone: the objective without its penalty.
fn alpha_only() -> ChenTristanoKwok {
    ChenTristanoKwok::without_penalty()
}

/// The star with its free node's current position at `x`: the barrier's δ is taken there,
/// as an optimization call starting at `x` takes it.
fn at_start(s: &Star, x: DVec2) -> Star {
    let mut t = s.clone();
    t.x0 = x;
    t
}

/// Whether every element of the star is valid (no corner with det ≤ 0) at `x`.
fn star_valid(s: &Star, x: DVec2) -> bool {
    s.elems.iter().all(|el| {
        let p = el.at(x);
        !element_quality(el.kind, &p[..el.kind.node_count()]).inverted
    })
}

/// Plain steepest descent with backtracking (Armijo), independent of the real solver.
/// Steps are lengths: at most `step`, halved until the value drops enough.
fn descend(obj: &dyn Objective, s: &Star, mut x: DVec2, step: f64, iters: usize) -> DVec2 {
    let mut len = step;
    for _ in 0..iters {
        let (f, g) = obj.value_and_gradient(s, x);
        let gl = g.length();
        if gl == 0.0 || !gl.is_finite() {
            break;
        }
        let dir = -g / gl;
        len = (len * 2.0).min(step);
        loop {
            let y = x + len * dir;
            if obj.value(s, y) <= f - 1e-4 * len * gl {
                x = y;
                break;
            }
            len *= 0.5;
            if len < 1e-14 {
                return x;
            }
        }
    }
    x
}

/// Strict local minima of `f` sampled on an n×n grid over [lo, hi]² (8 neighbours).
fn grid_minima(f: impl Fn(DVec2) -> f64, lo: DVec2, hi: DVec2, n: usize) -> Vec<DVec2> {
    let at = |i: usize, j: usize| lo + (hi - lo) * d(i as f64, j as f64) / (n - 1) as f64;
    let v: Vec<f64> = (0..n * n).map(|k| f(at(k % n, k / n))).collect();
    let mut out = Vec::new();
    for j in 1..n - 1 {
        for i in 1..n - 1 {
            let c = v[j * n + i];
            let lower_than_all = (j - 1..=j + 1)
                .flat_map(|jj| (i - 1..=i + 1).map(move |ii| (ii, jj)))
                .filter(|&(ii, jj)| (ii, jj) != (i, j))
                .all(|(ii, jj)| c < v[jj * n + ii]);
            if lower_than_all {
                out.push(at(i, j));
            }
        }
    }
    out
}

/// A regular hexagon with its top edge pushed down towards the centre (Chen Fig. 9).
fn pushed_hexagon() -> Star {
    let mut ring = regular_ring(6, 1.0);
    ring[1].y = 0.45;
    ring[2].y = 0.45;
    fan_star(&ring)
}

/// A heptagon with two ring nodes pulled in (two reflex nodes).
fn dented_heptagon() -> Star {
    let mut ring = regular_ring(7, 1.0);
    ring[2] *= 0.5;
    ring[5] *= 0.55;
    fan_star(&ring)
}

/// The square quad star with two edge neighbours pulled in.
fn dented_quads() -> Star {
    let mut q = square_ring();
    q[2] = d(0.0, 0.4);
    q[4] = d(-0.5, 0.0);
    quad_star_from(&q)
}

/// The stars of the single-minimum and untangling tests.
fn configurations() -> Vec<(&'static str, Star)> {
    vec![
        ("star polygon", fan_star(&star_polygon())),
        ("dented heptagon", dented_heptagon()),
        ("square quads", quad_star()),
        ("dented quads", dented_quads()),
        ("pushed hexagon", pushed_hexagon()),
        ("mixed", mixed_star()),
        ("curved quadratic", curved(&fan_star(&regular_ring(6, 1.0)), 0.15)),
        ("quadratic dented quads", quadratic(&dented_quads())),
    ]
}

// 1. Scale-free -------------------------------------------------------------------------

fn transformed(s: &Star, map: impl Fn(DVec2) -> DVec2) -> Star {
    let mut t = s.clone();
    t.x0 = map(t.x0);
    for e in &mut t.elems {
        for p in &mut e.pts[..e.kind.node_count()] {
            *p = map(*p);
        }
    }
    t
}

#[test]
fn invariant_under_scaling_translation_and_rotation() {
    for obj in [new(), barrier()] {
    let mut rng = SplitMix64::new(23);
    for s in sample_stars() {
        for _ in 0..10 {
            let x = s.x0 + rng.point(1.5); // valid and inverted positions
            let s = at_start(&s, x); // δ > 0 where x is inverted
            let (v, g) = obj.value_and_gradient(&s, x);
            for (angle, scale, shift) in
                [(0.7, 1e-3, d(5.0, -2.0)), (-2.0, 1e3, d(-1e3, 40.0)), (3.0, 0.37, d(0.0, 0.0))]
            {
                let r = DVec2::from_angle(angle);
                let map = |p: DVec2| scale * r.rotate(p) + shift;
                let (tv, tg) = obj.value_and_gradient(&transformed(&s, map), map(x));
                assert!((tv - v).abs() <= 1e-9 * (1.0 + v.abs()), "value {v} became {tv}");
                // the gradient rotates with the star and scales by 1/scale
                let expect = r.rotate(g) / scale;
                assert!((tg - expect).length() <= 1e-8 * (1.0 + expect.length()), "gradient {expect} became {tg}");
            }
        }
    }
    }
}

// 2. Growth of the penalty, and its normalisation on the equilateral triangle -----------

#[test]
fn penalty_grows_towards_zero_and_inverted_angles() {
    let obj = AnglePenalty::default();
    let eq = obj.angle_penalty(PI / 3.0, 1.0);
    assert!((eq - EQUILATERAL_PENALTY).abs() < 1e-12, "ε on the equilateral angle: {eq}");
    let p = |deg: f64| obj.angle_penalty(deg.to_radians(), 1.0);
    // rapid growth as the angle closes, and far more once inverted
    assert!(p(0.0) > 40.0 * eq, "{}", p(0.0) / eq);
    assert!(p(-60.0) > 1500.0 * eq, "{}", p(-60.0) / eq);
    assert!(p(-130.0) > 3e4 * eq, "{}", p(-130.0) / eq);
    // the worst and best angles, sampled every 0.01°
    let (mut worst, mut best) = (0.0, 0.0);
    for i in 0..36000 {
        let deg = -180.0 + 0.01 * i as f64;
        if p(deg) > p(worst) {
            worst = deg;
        }
        if p(deg) < p(best) {
            best = deg;
        }
    }
    // monotone: decreasing all the way from the worst inverted angle to the best valid one …
    let mut prev = f64::INFINITY;
    let mut deg = worst;
    while deg <= best {
        assert!(p(deg) < prev, "not decreasing at {deg}°");
        prev = p(deg);
        deg += 0.05;
    }
    // … and rising again towards 180°, where the triangle is as degenerate as at 0°
    assert!(p(179.99) > 0.99 * p(0.0) && p(179.99) < p(0.0));
    assert!((130.0..132.0).contains(&best) && (-132.0..-130.0).contains(&worst), "{best} {worst}");
}

#[test]
fn little_to_no_effect_on_the_equilateral_triangle() {
    // one triangle (C, A, B) with C free at the equilateral apex
    let (a, b) = (d(0.0, 0.0), d(1.0, 0.0));
    let apex = d(0.5, 3f64.sqrt() / 2.0);
    let s = star(vec![elem(ElementKind::Tri3, &[apex, a, b], 0)]);
    let (v, g) = new().value_and_gradient(&s, apex);
    // (1 − α)² = 0 and each of the two penalties is ε
    assert!((v - 2.0 * EQUILATERAL_PENALTY).abs() < 1e-12, "{v}");
    // k2 makes the penalty's gradient vanish there: the apex stays a stationary point
    assert!(g.length() < 1e-12, "{g}");
    // and the equilateral apex is this triangle's minimiser among nearby positions
    for p in regular_ring(16, 0.02) {
        assert!(new().value(&s, apex + p) > v);
    }
    // the same holds for the literal-reading length
    assert!(literal().value_and_gradient(&s, apex).1.length() < 1e-12);
    // and for the barrier: (1 − α)² = 0, η = 1, so the value is k1 and the gradient 0
    let (v, g) = barrier().value_and_gradient(&s, apex);
    assert!((v - BARRIER_WEIGHT).abs() < 1e-15 && g.length() < 1e-12, "{v} {g}");
    for p in regular_ring(16, 0.02) {
        assert!(barrier().value(&s, apex + p) > v);
    }
}

// 3. Continuity across the ±π ray --------------------------------------------------------

#[test]
fn adjusted_angle_is_continuous_across_the_ray() {
    for delta in [1e-6, 1e-9] {
        let (w1, d1) = adjusted_angle(PI - delta);
        let (w2, d2) = adjusted_angle(-PI + delta);
        assert!(w1.abs() < 1e-5 && w2.abs() < 1e-5, "ω → 0 on both sides: {w1} {w2}");
        assert!((d1 - d2).abs() < 1e-5, "ω' agrees: {d1} {d2}");
    }
    // odd, close to the printed eq. (6) on the positive side
    for t in [0.3, 1.0, 2.0, 3.0] {
        assert_eq!(adjusted_angle(-t).0, -adjusted_angle(t).0);
        let printed = t * (1.0 - (-2.0 * (PI - t)).exp());
        assert!((adjusted_angle(t).0 - printed).abs() <= 0.002 * printed.abs());
    }
}

#[test]
fn value_and_gradient_continuous_across_the_ray() {
    let obj = new();
    // single triangle (C, A, B), A at the origin, B = (1, 0): the angle at A jumps from
    // +π to −π across the ray beyond A, {(−t, 0)}
    let s1 = star(vec![elem(ElementKind::Tri3, &[d(0.5, 0.8), d(0.0, 0.0), d(1.0, 0.0)], 0)]);
    // the hexagon star, its free node beyond the ring node (1, 0) on the ray from (0.5, 0.866)
    let hex = fan_star(&regular_ring(6, 1.0));
    let ring = regular_ring(6, 1.0);
    let beyond = |t: f64| ring[0] + t * (ring[0] - ring[1]);
    let hex6 = quadratic(&hex);
    let cases: Vec<(&Star, DVec2, DVec2)> = vec![
        (&s1, d(-0.5, 0.0), d(0.0, 1.0)),
        (&s1, d(-3.0, 0.0), d(0.0, 1.0)),
        (&hex, beyond(0.4), (ring[0] - ring[1]).perp().normalize()),
        (&hex6, beyond(0.8), (ring[0] - ring[1]).perp().normalize()),
    ];
    for (s, on_ray, normal) in cases {
        let delta = 1e-8;
        let (v1, g1) = obj.value_and_gradient(s, on_ray + delta * normal);
        let (v2, g2) = obj.value_and_gradient(s, on_ray - delta * normal);
        assert!((v1 - v2).abs() <= 1e-6 * (1.0 + v1.abs()), "values {v1} {v2}");
        assert!((g1 - g2).length() <= 1e-5 * (1.0 + g1.length()), "gradients {g1} {g2}");
    }
    // the penalty is large but finite on the ray, as in the inverted region around it
    assert!(obj.value(&s1, d(-0.5, 0.0)).is_finite());
}

// 4. Finite-difference gradient checks ----------------------------------------------------

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]
    #[test]
    fn gradient_matches_central_differences(which in 0usize..16, px in -1.6f64..1.6, py in -1.6f64..1.6) {
        let stars = sample_stars();
        let s = &stars[which % stars.len()];
        let x = s.x0 + d(px, py);
        // keep off the ring nodes themselves (C¹ there, but central differences straddle them)
        let near_node = s.elems.iter().any(|e| e.pts[..e.kind.corners()].iter().any(|p| p.distance(x) < 1e-3 && *p != s.x0));
        prop_assume!(!near_node);
        check_gradient(&new(), s, x, 1e-5);
        check_gradient(&literal(), s, x, 1e-5);
        check_gradient(&alpha_only(), s, x, 1e-5);
        // the barrier: δ = 0 where the star is valid at x (and x its start), δ > 0 where
        // it is inverted (the start of an untangling call)
        let start = at_start(s, x);
        check_gradient(&barrier(), &start, x, 1e-5);
        // its Hessian (Newton's step), there and without the penalty
        check_hessian(&barrier(), &start, x, 1e-5);
        check_hessian(&alpha_only(), s, x, 1e-5);
        prop_assert!(new().value_gradient_hessian(s, x).is_none());
        // and δ from the star's own position (δ = 0: the pure barrier) where the star is
        // valid, away from the barrier's pole (central differences cannot follow a value
        // that grows a thousandfold within their step)
        let v = barrier().value(s, x);
        if v.is_finite() && v < 1e3 && star_valid(s, x) {
            check_gradient(&barrier(), s, x, 1e-5);
            check_hessian(&barrier(), s, x, 1e-5);
        }
    }
}

#[test]
fn gradient_checks_cover_inverted_positions() {
    // the property test samples the square around each star's node; make sure that box
    // holds inverted positions for every kind of star, so the checks above cover them
    let mut rng = SplitMix64::new(29);
    for s in sample_stars() {
        let inverted = (0..200).filter(|_| !star_valid(&s, s.x0 + rng.point(1.6))).count();
        assert!(inverted > 20, "{inverted}");
        for _ in 0..20 {
            let x = s.x0 + rng.point(1.6);
            check_gradient(&new(), &s, x, 1e-5);
            check_gradient(&barrier(), &at_start(&s, x), x, 1e-5);
        }
    }
}

// 5. Minimum at the centre of a regular star ----------------------------------------------

#[test]
fn centre_of_a_regular_star_is_the_minimiser() {
    for obj in [new(), barrier()] {
    for k in 4..=8 {
        let s = fan_star(&regular_ring(k, 1.0));
        let (v0, g) = obj.value_and_gradient(&s, DVec2::ZERO);
        assert!(g.length() < 1e-12, "k = {k}: {g}");
        // fine grid over the star's neighbourhood, the centre one of its points
        let n = 161;
        let mut best = (f64::INFINITY, DVec2::ZERO);
        for j in 0..n {
            for i in 0..n {
                let p = d(i as f64, j as f64) * (2.4 / (n - 1) as f64) - d(1.2, 1.2);
                let v = obj.value(&s, p);
                if v < best.0 {
                    best = (v, p);
                }
            }
        }
        assert!(best.1.length() < 1e-12 && (best.0 - v0).abs() < 1e-12, "k = {k}: minimum {} at {}", best.0, best.1);
    }
    let (_, g) = obj.value_and_gradient(&quad_star(), DVec2::ZERO);
    assert!(g.length() < 1e-12);
    }
}

// 6. One minimum ----------------------------------------------------------------------------

#[test]
fn single_minimum_on_star_shaped_and_quad_configurations() {
    let obj = new();
    for (name, s) in configurations() {
        let minima = grid_minima(|p| obj.value(&s, p), d(-1.3, -1.3), d(1.3, 1.3), 131);
        assert_eq!(minima.len(), 1, "{name}: sampled local minima at {minima:?}");
        // and it is where the valid elements are
        assert!(star_valid(&s, minima[0]), "{name}");
    }
}

#[test]
fn literal_opposite_length_has_spurious_minima() {
    // why the default departs from the extracted text (see `PenaltyLength::Opposite`)
    let lit = literal();
    let s = fan_star(&star_polygon());
    let minima = grid_minima(|p| lit.value(&s, p), d(-1.3, -1.3), d(1.3, 1.3), 131);
    assert!(minima.len() > 3, "{minima:?}");
    assert!(minima.iter().filter(|&&m| !star_valid(&s, m)).count() >= 3);
}

// 7. Untangling from inverted starts ------------------------------------------------------

/// Inverted starting points: a fixed set of random points in [−3, 3]² around the node.
fn inverted_starts(s: &Star, seed: u64, count: usize) -> Vec<DVec2> {
    let mut rng = SplitMix64::new(seed);
    std::iter::repeat_with(|| s.x0 + rng.point(3.0)).filter(|&x| !star_valid(s, x)).take(count).collect()
}

#[test]
fn descent_from_inverted_starts_untangles() {
    let obj = new();
    for (name, s) in configurations() {
        for x0 in inverted_starts(&s, 31, 25) {
            let x = descend(&obj, &s, x0, 0.2, 4000);
            assert!(star_valid(&s, x), "{name}: from {x0} descent stopped at {x}, still inverted");
        }
    }
}

#[test]
fn without_the_penalty_descent_does_not_untangle() {
    // Chen Fig. 2: on the inverted side (1 − α)² can fall as the node moves further away.
    // From (3, 1), outside the hexagon star, descent on it alone runs off to infinity;
    // with the penalty it comes back to the centre.
    let s = fan_star(&regular_ring(6, 1.0));
    let x0 = d(3.0, 1.0);
    let plain = descend(&alpha_only(), &s, x0, 0.2, 4000);
    assert!(!star_valid(&s, plain) && plain.length() > 100.0, "(1 − α)² alone went to {plain}");
    let full = descend(&new(), &s, x0, 0.2, 4000);
    assert!(star_valid(&s, full) && full.length() < 1e-3, "{full}");
    // over whole stars: (1 − α)² alone leaves many inverted starts inverted; with the
    // penalty none (the test above)
    let mut failures = 0;
    let mut total = 0;
    for (_, s) in configurations() {
        for x0 in inverted_starts(&s, 31, 25) {
            total += 1;
            if !star_valid(&s, descend(&alpha_only(), &s, x0, 0.2, 4000)) {
                failures += 1;
            }
        }
    }
    assert!(failures * 4 > total, "(1 − α)² alone failed only {failures} of {total}");
}

// Structure: eq. (9), the ×3 weight, quadratic elements -----------------------------------

#[test]
fn quad_term_is_its_three_sub_triangles() {
    for obj in [new(), barrier()] {
    let mut ring = square_ring();
    let mut rng = SplitMix64::new(37);
    for p in ring.iter_mut() {
        *p += rng.point(0.2);
    }
    let qs = quad_star_from(&ring);
    for _ in 0..20 {
        let x = rng.point(1.2);
        let mut t = Vec::new();
        obj.terms(&qs, x, &mut t);
        for (term, el) in t.iter().zip(&qs.elems) {
            let [c, n, o, p] = [el.pts[0], el.pts[1], el.pts[2], el.pts[3]];
            // the three triangles that contain the free node, as a triangle star;
            // (n, o, p), the dead zone, is left out
            let tris = star(vec![
                elem(ElementKind::Tri3, &[c, n, o], 0),
                elem(ElementKind::Tri3, &[c, o, p], 0),
                elem(ElementKind::Tri3, &[c, n, p], 0),
            ]);
            // both stars start where the quad star's node is (valid, with margin), so the
            // barrier's δ is 0 for both and the sums must agree, +∞ included
            assert_eq!((obj.delta(&qs), obj.delta(&tris)), (0.0, 0.0));
            let (v, g) = obj.value_and_gradient(&tris, x);
            if v.is_infinite() {
                assert_eq!(term.value, v);
                continue;
            }
            assert!(
                (term.value - v).abs() <= 1e-12 * (1.0 + v.abs())
                    && (term.grad - g).length() <= 1e-10 * (1.0 + g.length())
            );
        }
    }
    }
}

#[test]
fn triangles_weigh_three_times_in_a_mixed_star() {
    let obj = new();
    let m = mixed_star();
    let mut alone = m.clone();
    alone.mixed = false;
    for x in [d(0.1, 0.05), d(-0.3, 0.2), d(0.9, -0.8)] {
        let (mut tm, mut ta) = (Vec::new(), Vec::new());
        obj.terms(&m, x, &mut tm);
        obj.terms(&alone, x, &mut ta);
        for ((a, b), el) in tm.iter().zip(&ta).zip(&m.elems) {
            let w = if el.kind.is_triangle() { 3.0 } else { 1.0 };
            assert!((a.value - w * b.value).abs() < 1e-12 * (1.0 + a.value.abs()));
        }
    }
}

#[test]
fn straight_quadratic_elements_match_linear() {
    let obj = new();
    for lin in [fan_star(&regular_ring(5, 1.0)), dented_quads(), mixed_star()] {
        let quad = quadratic(&lin);
        for x in [d(0.1, 0.2), d(-0.4, 0.3), d(1.4, 0.0)] {
            let (a, ga) = obj.value_and_gradient(&lin, x);
            let (b, gb) = obj.value_and_gradient(&quad, x);
            assert!((a - b).abs() <= 1e-12 * (1.0 + a.abs()) && (ga - gb).length() <= 1e-10 * (1.0 + ga.length()));
        }
    }
    // curved edges count through their tangents: far edges bowed inward close the angles
    // at the ring nodes (more penalty), bowed outward open them (less)
    let hex = fan_star(&regular_ring(6, 1.0));
    let straight = obj.value(&hex, DVec2::ZERO);
    assert!(obj.value(&curved(&hex, -0.15), DVec2::ZERO) > straight + 0.01);
    assert!(obj.value(&curved(&hex, 0.15), DVec2::ZERO) < straight - 0.01);
}

// The linear-triangle fast path -----------------------------------------------------------

/// `SubTriangle::linear` is an optimisation only: for every slot of the free node and any
/// position (valid, inverted, degenerate) it gives bit for bit what the general element
/// machinery gives, so the objective's values and gradients cannot differ between them.
#[test]
fn linear_triangle_fast_path_equals_the_general_jets() {
    let mut rng = SplitMix64::new(97);
    for _ in 0..500 {
        let pts = [rng.point(2.0), rng.point(2.0), rng.point(2.0)];
        for slot in 0..3 {
            let el = elem(ElementKind::Tri3, &pts, slot);
            for x in [rng.point(3.0), pts[(slot + 1) % 3], 0.5 * (pts[(slot + 1) % 3] + pts[(slot + 2) % 3])] {
                let j = crate::objective::corners::ElementJets::new(&el, x);
                let general = SubTriangle::of(&j, slot, (slot + 1) % 3, (slot + 2) % 3, true);
                let fast = SubTriangle::linear(x, pts[(slot + 1) % 3], pts[(slot + 2) % 3]);
                assert_eq!(general, fast, "slot {slot}, x {x}");
            }
        }
    }
    // and through the objective: its folded value and gradient over a star of linear
    // triangles are the sums of the general path's sub-triangles
    for obj in [new(), barrier()] {
        for _ in 0..50 {
            let x = rng.point(1.5);
            let s = at_start(&fan_star(&regular_ring(6, 1.0)), x);
            let delta = obj.delta(&s);
            let (v, g) = obj.value_and_gradient(&s, x);
            let (mut v2, mut g2) = (0.0, DVec2::ZERO);
            for el in &s.elems {
                let j = crate::objective::corners::ElementJets::new(el, x);
                let f = j.slot;
                let (a, b, _) = obj.sub_triangle::<false>(&SubTriangle::of(&j, f, (f + 1) % 3, (f + 2) % 3, true), delta);
                v2 += a;
                g2 += b;
            }
            assert_eq!((v, g), (v2, g2));
        }
    }
}

// The regularised barrier (the default design of eq. (8)) ---------------------------------

/// `η_δ²` of the straight triangle (C, A, B), C free.
fn eta2_of(c: DVec2, a: DVec2, b: DVec2, delta: f64) -> f64 {
    let t = SubTriangle::linear(c, a, b);
    barrier::RegularisedBarrier::eta2::<false>(&barrier::CornerND::of(t.c_to_a, t.c_to_b), delta).0
}

#[test]
fn eta_is_the_cotangent_sum_and_the_inverse_of_alpha() {
    let mut rng = SplitMix64::new(101);
    for _ in 0..500 {
        let (c, a, b) = (rng.point(2.0), rng.point(2.0), rng.point(2.0));
        let (c, a, b) = if (a - c).perp_dot(b - c) > 0.0 { (c, a, b) } else { (c, b, a) };
        // the cotangent of the angle at p, as the ratio of the dot and cross products of
        // its sides (by way of the angle, cos/sin loses digits on needle-like triangles)
        let cot = |p: DVec2, q: DVec2, r: DVec2| (q - p).dot(r - p) / (q - p).perp_dot(r - p).abs();
        let eta = (cot(c, a, b) + cot(a, b, c) + cot(b, c, a)) / 3f64.sqrt();
        let got = eta2_of(c, a, b, 0.0).sqrt();
        assert!((got - eta).abs() <= 1e-9 * eta, "{got} {eta}");
        let q = element_quality(ElementKind::Tri3, &[c, a, b]);
        assert!((got * q.shape - 1.0).abs() < 1e-9, "η·α = {}", got * q.shape);
    }
    // hand-derived: equilateral 1; right isosceles (45°, 45°, 90°): (1 + 1 + 0)/√3
    assert!((eta2_of(d(0.5, 3f64.sqrt() / 2.0), d(0.0, 0.0), d(1.0, 0.0), 0.0) - 1.0).abs() < 1e-15);
    assert!((eta2_of(d(0.0, 1.0), d(0.0, 0.0), d(1.0, 0.0), 0.0) - 4.0 / 3.0).abs() < 1e-15);
}

#[test]
fn delta_makes_the_worst_corner_a_sliver_of_eps_rho() {
    // h_δ(N_min) = ε·ρ exactly, for any inverted start
    let obj = RegularisedBarrier::default();
    let mut rng = SplitMix64::new(103);
    for s in sample_stars() {
        for _ in 0..20 {
            let x = s.x0 + rng.point(1.6);
            let start = at_start(&s, x);
            let delta = ChenTristanoKwok::Barrier(obj).delta(&start);
            let mut ns = Vec::new();
            for el in &start.elems {
                each_sub_triangle(el, x, |t| {
                    ns.push(t.c_to_a.0.perp_dot(t.c_to_b.0));
                    if !t.straight {
                        ns.push(t.a_to_b.0.perp_dot(t.a_to_c.0));
                        ns.push(t.b_to_c.0.perp_dot(t.b_to_a.0));
                    }
                });
            }
            let rho = ns.iter().map(|n| n.abs()).sum::<f64>() / ns.len() as f64;
            let n_min = ns.iter().copied().fold(f64::INFINITY, f64::min);
            let m = BARRIER_EPSILON * rho;
            if n_min >= m {
                assert_eq!(delta, 0.0);
            } else {
                assert!(delta > 0.0);
                let (h, _) = regularised_determinant(n_min, delta);
                assert!((h - m).abs() <= 1e-9 * m, "h(N_min) = {h}, ερ = {m}");
            }
        }
    }
    // a valid star with margin: δ = 0
    assert_eq!(barrier().delta(&fan_star(&regular_ring(6, 1.0))), 0.0);
}

#[test]
fn barrier_on_valid_stars() {
    // δ = 0 at a valid start: +∞ at every position that folds a sub-triangle, finite at
    // every valid one, and growing without bound towards the fold
    let obj = barrier();
    let mut rng = SplitMix64::new(107);
    for (name, s) in configurations() {
        assert_eq!(obj.delta(&s), 0.0, "{name}");
        for _ in 0..300 {
            let x = s.x0 + rng.point(1.6);
            let v = obj.value(&s, x);
            assert_eq!(v.is_finite(), star_valid(&s, x), "{name} at {x}: {v}");
        }
    }
    // approaching the edge AB of a triangle from inside
    let (a, b) = (d(0.0, 0.0), d(1.0, 0.0));
    let tri = star(vec![elem(ElementKind::Tri3, &[d(0.5, 0.8), a, b], 0)]);
    let mut prev = 0.0;
    for h in [0.5, 0.1, 1e-2, 1e-4, 1e-8] {
        let v = obj.value(&tri, d(0.3, h));
        assert!(v > prev && v.is_finite(), "{h}: {v}");
        prev = v;
    }
    assert!(prev > 1e12);
    assert_eq!(obj.value(&tri, d(0.3, 0.0)), f64::INFINITY);
}

#[test]
fn finite_on_inverted_stars_and_growing_with_the_depth_of_the_fold() {
    let obj = barrier();
    let mut rng = SplitMix64::new(109);
    for (name, s) in configurations() {
        for x0 in inverted_starts(&s, 113, 10) {
            let start = at_start(&s, x0);
            assert!(obj.delta(&start) > 0.0, "{name}");
            for _ in 0..50 {
                let x = x0 + rng.point(2.0);
                let (v, g) = obj.value_and_gradient(&start, x);
                assert!(v.is_finite() && g.is_finite(), "{name} at {x}");
            }
        }
    }
    // one triangle, δ fixed: the value grows as C goes deeper through AB
    let (a, b) = (d(0.0, 0.0), d(1.0, 0.0));
    let tri = at_start(&star(vec![elem(ElementKind::Tri3, &[d(0.5, 0.8), a, b], 0)]), d(0.5, -0.1));
    let mut prev = 0.0;
    for depth in [-0.05, -0.1, -0.2, -0.4, -0.8, -1.6] {
        let v = obj.value(&tri, d(0.5, depth));
        assert!(v > prev, "{depth}: {v}");
        prev = v;
    }
}

/// Optimization calls as the driver makes them: each starts where the last ended (δ taken
/// there) and descends at most `iters` steps.
fn untangle_by_calls(obj: &dyn Objective, s: &Star, mut x: DVec2, calls: usize, iters: usize) -> DVec2 {
    for _ in 0..calls {
        if star_valid(s, x) {
            break;
        }
        x = descend(obj, &at_start(s, x), x, 0.2, iters);
    }
    x
}

#[test]
fn barrier_descent_from_inverted_starts_untangles() {
    let obj = barrier();
    for (name, s) in configurations() {
        for x0 in inverted_starts(&s, 31, 25) {
            let x = untangle_by_calls(&obj, &s, x0, 10, 400);
            assert!(star_valid(&s, x), "{name}: from {x0} descent stopped at {x}, still inverted");
        }
    }
    // from (3, 1), outside the hexagon star, where (1 − α)² alone runs off (Fig. 2)
    let s = fan_star(&regular_ring(6, 1.0));
    let x = untangle_by_calls(&obj, &s, d(3.0, 1.0), 10, 400);
    assert!(star_valid(&s, x));
    let x = descend(&obj, &at_start(&s, x), x, 0.2, 4000);
    assert!(x.length() < 1e-3, "{x}");
}

#[test]
fn barrier_has_one_minimum_on_star_shaped_and_quad_configurations() {
    let obj = barrier();
    for (name, s) in configurations() {
        // δ = 0 (a valid start)
        let minima = grid_minima(|p| obj.value(&s, p), d(-1.3, -1.3), d(1.3, 1.3), 131);
        assert_eq!(minima.len(), 1, "{name}: sampled local minima at {minima:?}");
        assert!(star_valid(&s, minima[0]), "{name}");
        // δ > 0 (an inverted start): still one minimum
        let x0 = inverted_starts(&s, 127, 1)[0];
        let start = at_start(&s, x0);
        let minima = grid_minima(|p| obj.value(&start, p), d(-1.3, -1.3), d(1.3, 1.3), 131);
        assert_eq!(minima.len(), 1, "{name} from {x0}: sampled local minima at {minima:?}");
    }
}

#[test]
fn barrier_on_quadratic_elements_sees_curved_edges() {
    let obj = barrier();
    for lin in [fan_star(&regular_ring(5, 1.0)), dented_quads(), mixed_star()] {
        let quad = quadratic(&lin);
        for x in [d(0.1, 0.2), d(-0.2, 0.1)] {
            let (a, ga) = obj.value_and_gradient(&lin, x);
            let (b, gb) = obj.value_and_gradient(&quad, x);
            assert!((a - b).abs() <= 1e-12 * (1.0 + a.abs()) && (ga - gb).length() <= 1e-9 * (1.0 + ga.length()));
        }
    }
    // the corners at the ring nodes are measured with the far edge's tangent: bowing it
    // either way makes them less equilateral, so the penalty rises, and more with the bow
    // (the first design read an outward bow as an opened angle, a gain)
    let hex = fan_star(&regular_ring(6, 1.0));
    let at = |bulge: f64| obj.value(&curved(&hex, bulge), DVec2::ZERO);
    assert!((at(0.0) - 6.0 * BARRIER_WEIGHT).abs() < 1e-12, "{}", at(0.0));
    assert!(at(-0.15) > at(-0.05) && at(-0.05) > at(0.0) + 1e-3);
    assert!(at(0.15) > at(0.05) && at(0.05) > at(0.0) + 1e-3);
}

#[test]
fn values_are_the_same_at_extreme_scales() {
    // beyond 2^±200 the squares of N and D leave the doubles; a star there is evaluated in
    // a copy scaled by a power of two, so the values are those at unit scale, bit for bit
    for obj in [new(), barrier()] {
        let mut rng = SplitMix64::new(131);
        for s in sample_stars() {
            let x = s.x0 + rng.point(1.0);
            let s = at_start(&s, x);
            let (v, g) = obj.value_and_gradient(&s, x);
            for e in [-900, -600, -250, 250, 600, 900] {
                let f = 2f64.powi(e);
                let (tv, tg) = obj.value_and_gradient(&transformed(&s, |p| f * p), f * x);
                assert_eq!(tv, v, "2^{e}");
                assert_eq!(tg, g / f, "2^{e}");
            }
        }
    }
}
