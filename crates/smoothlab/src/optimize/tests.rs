use glam::DVec2;
use proptest::prelude::*;

use super::test_objectives::*;
use super::*;
use crate::mesh::{ElementKind, MeshBuilder};
use crate::objective::Star;

fn d(x: f64, y: f64) -> DVec2 {
    DVec2::new(x, y)
}

fn recording(max_iter: u32) -> SolveOptions {
    SolveOptions::default().with_max_iter(max_iter).with_history(true)
}

// ---------------------------------------------------------------- line search

#[test]
fn line_search_brackets_a_parabola_and_lands_on_its_vertex() {
    let phi = |t: f64| (t - 3.7) * (t - 3.7) + 1.0;
    for t0 in [1e-3, 0.01, 1.0, 3.7 * 0.999, 100.0] {
        let mut accel = 8.0;
        let ls = line_search(phi, phi(0.0), t0, 1e-12, &mut accel, 40).expect("a descent direction");
        assert!((ls.t - 3.7).abs() < 1e-9, "t0 {t0}: {ls:?}");
        let [a, b, c] = ls.bracket.expect("a bracket");
        assert!(a < b && b < c && a <= 3.7 && 3.7 <= c, "{a} {b} {c}");
        assert!(phi(b) < phi(a) && phi(b) <= phi(c), "high-low-high");
        assert!(ls.value < phi(0.0));
    }
    // an overshooting first step is a failure: the factor is halved
    let mut accel = 8.0;
    line_search(phi, phi(0.0), 100.0, 1e-12, &mut accel, 40).unwrap();
    assert!(accel < 8.0);
    let mut accel = 8.0;
    line_search(phi, phi(0.0), 0.01, 1e-12, &mut accel, 40).unwrap();
    assert_eq!(accel, 8.0, "growing is no failure");
}

#[test]
fn line_search_fails_without_descent() {
    let mut accel = 8.0;
    assert!(line_search(|t| t, 0.0, 0.1, 1e-9, &mut accel, 40).is_none());
    let mut accel = 8.0;
    assert!(line_search(|_| 2.0, 2.0, 0.1, 1e-9, &mut accel, 40).is_none(), "flat is not lower");
    let mut accel = 8.0;
    assert!(line_search(|_| f64::NAN, 0.0, 0.1, 1e-9, &mut accel, 40).is_none(), "NaN is high");
}

#[test]
fn line_search_treats_infinity_as_high() {
    // falling until a wall at t = 2: the result stays before the wall
    let wall = |t: f64| if t < 2.0 { -t } else { f64::INFINITY };
    let mut accel = 8.0;
    let ls = line_search(wall, 0.0, 0.01, 1e-12, &mut accel, 60).unwrap();
    assert!(ls.value.is_finite() && ls.t < 2.0 && ls.t > 1.9, "{ls:?}");
    // a minimum inside, with the growth jumping into the wall: bisection then interpolation
    let inside = |t: f64| if t < 1.5 { (t - 1.0) * (t - 1.0) } else { f64::INFINITY };
    let mut accel = 8.0;
    let ls = line_search(inside, 1.0, 0.5, 1e-12, &mut accel, 40).unwrap();
    assert!((ls.t - 1.0).abs() < 1e-9, "{ls:?}");
}

// ---------------------------------------------------------------- Fletcher–Reeves

#[test]
fn fletcher_reeves_round_bowl_in_one_step() {
    let star = unit_star();
    let bowl = Bowl { centre: d(0.2, 0.1), a: [[1.0, 0.0], [0.0, 1.0]] };
    let r = FletcherReeves::new(recording(3)).solve(&bowl, &star, d(0.7, -0.4));
    assert!(r.x.distance(bowl.centre) < 1e-9, "{r:?}");
    assert_eq!(r.history[0].direction, DirectionKind::Gradient);
    assert!(r.value < 1e-16);
}

#[test]
fn fletcher_reeves_elongated_bowl_in_two_steps() {
    let star = unit_star();
    for (ratio, angle) in [(10.0, 0.4), (100.0, -1.1), (1000.0, 2.0)] {
        let bowl = Bowl::elongated(d(-0.3, 0.25), ratio, angle);
        let r = FletcherReeves::new(recording(3)).solve(&bowl, &star, d(0.6, 0.5));
        assert!(r.x.distance(bowl.centre) < 1e-7, "ratio {ratio}: {r:?}");
        let kinds: Vec<_> = r.history.iter().map(|i| i.direction).collect();
        assert_eq!(&kinds[..2], &[DirectionKind::Gradient, DirectionKind::Conjugate], "{r:?}");
        // steepest descent alone is far worse on the same bowl
        let sd = SolveOptions { restart_every: 1, ..SolveOptions::default().with_max_iter(2) };
        let s = FletcherReeves::new(sd).solve(&bowl, &star, d(0.6, 0.5));
        assert!(s.x.distance(bowl.centre) > 100.0 * r.x.distance(bowl.centre));
    }
}

#[test]
fn fletcher_reeves_follows_a_curved_valley_downhill() {
    let star = unit_star();
    let f = Rosenbrock { b: 10.0 };
    let r = FletcherReeves::new(recording(300)).solve(&f, &star, d(-0.8, 0.9));
    assert!(r.x.distance(d(1.0, 1.0)) < 1e-4, "{:?} after {} ({:?})", r.x, r.iterations, r.stop);
    let mut last = r.value0;
    for it in &r.history {
        assert!(it.value < last, "every accepted step goes down");
        last = it.value;
    }
    assert!(r.history.iter().any(|i| i.direction == DirectionKind::Conjugate));
}

#[test]
fn fletcher_reeves_stays_inside_a_barrier() {
    let star = unit_star();
    let r = FletcherReeves::new(recording(60)).solve(&LogBarrier, &star, d(0.45, 0.3));
    assert!(r.x.length() < 1e-5, "{r:?}");
    assert!(r.history.iter().all(|i| i.value.is_finite() && i.x.x < 0.5));
    // a hard wall with the minimum beyond it: the solver ends at the wall, never past it
    struct Wall;
    impl Objective for Wall {
        fn name(&self) -> &'static str {
            "wall"
        }
        fn goal(&self) -> Goal {
            Goal::MinimizeSum
        }
        fn terms(&self, _: &Star, x: DVec2, out: &mut Vec<crate::objective::Term>) {
            let (value, grad) = if x.x < 0.5 {
                ((x - d(1.0, 0.0)).length_squared(), 2.0 * (x - d(1.0, 0.0)))
            } else {
                (f64::INFINITY, DVec2::ZERO)
            };
            out.push(crate::objective::Term { elem: 0, value, grad });
        }
    }
    let r = FletcherReeves::new(recording(10)).solve(&Wall, &star, d(-0.5, 0.5));
    assert!(r.value.is_finite() && r.x.x < 0.5 && r.x.x > 0.4, "{r:?}");
    // starting inside the wall: nothing to do, nothing moves
    let r = FletcherReeves::default().solve(&Wall, &star, d(0.7, 0.0));
    assert_eq!((r.stop, r.x, r.iterations), (StopReason::NotFinite, d(0.7, 0.0), 0));
}

#[test]
fn fletcher_reeves_smooths_a_star() {
    let mut star = Star::new();
    star.gather(&hexagon(d(0.3, -0.2)), 0);
    let r = FletcherReeves::new(recording(20)).solve(&ShapeSum, &star, star.x0);
    assert!(r.x.length() < 1e-4, "{r:?}");
}

#[test]
fn empty_star_and_step_api() {
    let empty = Star::new();
    let bowl = Bowl { centre: DVec2::ZERO, a: [[1.0, 0.0], [0.0, 1.0]] };
    assert_eq!(FletcherReeves::default().solve(&bowl, &empty, d(1.0, 0.0)).stop, StopReason::DegenerateStar);
    assert_eq!(NonSmoothAscent::default().solve(&bowl, &empty, d(1.0, 0.0)).stop, StopReason::DegenerateStar);
    // stepping by hand gives the same as solve, bit for bit
    let star = unit_star();
    let bowl = Bowl::elongated(d(0.1, 0.1), 20.0, 0.3);
    let mut fr = FletcherReeves::new(recording(3));
    let whole = fr.solve(&bowl, &star, d(0.5, -0.5));
    let mut st = fr.start(&bowl, &star, d(0.5, -0.5));
    let mut steps = 0;
    while fr.step(&bowl, &star, &mut st) {
        steps += 1;
        assert_eq!(st.history.len(), st.iterations as usize);
    }
    assert!(steps >= 1 && st.is_done());
    assert_eq!(st.into_result(), whole);
    // history off: nothing recorded, nothing allocated
    let quiet = FletcherReeves::default().solve(&bowl, &star, d(0.5, -0.5));
    assert!(quiet.history.is_empty() && quiet.history.capacity() == 0);
    assert_eq!(quiet.x, whole.x);
}

#[test]
fn options_are_validated() {
    assert!(SolveOptions::default().validate().is_ok());
    let o = SolveOptions { acceleration: 1.0, ..Default::default() };
    assert!(o.validate().unwrap_err().to_string().contains("acceleration"));
    let o = SolveOptions { initial_step: f64::NAN, ..Default::default() };
    assert!(o.validate().is_err());
}

// ---------------------------------------------------------------- min-norm point

#[test]
fn min_norm_point_cases() {
    let m = min_norm_point(&[d(3.0, 4.0)]);
    assert_eq!((m.point, m.support), (d(3.0, 4.0), HullPoint::Vertex(0)));
    let m = min_norm_point(&[d(1.0, 1.0), d(1.0, -1.0)]);
    assert!(m.point.distance(d(1.0, 0.0)) < 1e-15 && m.support == HullPoint::Edge(0, 1));
    // the projection falls outside the segment: the nearer end
    let m = min_norm_point(&[d(1.0, 0.0), d(3.0, 1.0)]);
    assert_eq!((m.point, m.support), (d(1.0, 0.0), HullPoint::Vertex(0)));
    // origin inside a triangle: optimal
    let m = min_norm_point(&[d(1.0, 0.0), d(-1.0, 1.0), d(-1.0, -1.0)]);
    assert_eq!((m.point, m.support), (DVec2::ZERO, HullPoint::Interior));
    // a triangle beside the origin: its nearest edge
    let m = min_norm_point(&[d(2.0, -1.0), d(2.0, 1.0), d(4.0, 0.0)]);
    assert!(m.point.distance(d(2.0, 0.0)) < 1e-15 && m.support == HullPoint::Edge(0, 1), "{m:?}");
    // opposite gradients: the origin is on the segment
    let m = min_norm_point(&[d(1.0, 2.0), d(-1.0, -2.0)]);
    assert!(m.point.length() < 1e-15);
    assert_eq!(min_norm_point::<DVec2>(&[]).support, HullPoint::Empty);
    // many repeated and active points
    let many: Vec<_> = (0..12).map(|i| d(1.0, (i % 4) as f64 - 1.5)).collect();
    let m = min_norm_point(&many);
    assert!(m.point.distance(d(1.0, 0.0)) < 1e-15, "{m:?}");
}

proptest! {
    #[test]
    fn min_norm_point_is_the_nearest_hull_point(pts in prop::collection::vec((-3.0f64..3.0, -3.0f64..3.0), 1..8),
                                                 w in prop::collection::vec(0.01f64..1.0, 8)) {
        let pts: Vec<DVec2> = pts.into_iter().map(|(x, y)| d(x, y)).collect();
        let m = min_norm_point(&pts);
        let p = m.point;
        // optimality: the hull lies beyond the line through p normal to p
        for g in &pts {
            prop_assert!(p.dot(*g) >= p.length_squared() - 1e-9);
        }
        // no convex combination is shorter
        let ws: f64 = w[..pts.len()].iter().sum();
        let combo: DVec2 = pts.iter().zip(&w).map(|(g, wi)| *g * (*wi / ws)).sum();
        prop_assert!(p.length() <= combo.length() + 1e-9);
        for g in &pts {
            prop_assert!(p.length() <= g.length() + 1e-12);
        }
    }
}

#[test]
fn min_norm_point_in_three_dimensions() {
    use glam::DVec3;
    let v = DVec3::new;
    // the origin projects inside a triangle in the plane z = 1: the nearest point is (0,0,1)
    let tri = [v(1.0, 0.0, 1.0), v(-1.0, 1.0, 1.0), v(-1.0, -1.0, 1.0)];
    let m = min_norm_point(&tri);
    assert!(m.point.distance(v(0.0, 0.0, 1.0)) < 1e-15 && m.support == HullPoint::Face(0, 1, 2), "{m:?}");
    // a fourth point below the origin closes a tetrahedron around it: optimal
    let m = min_norm_point(&[tri[0], tri[1], tri[2], v(0.0, 0.0, -1.0)]);
    assert_eq!((m.point, m.support), (DVec3::ZERO, HullPoint::Interior));
    // a triangle whose plane projection falls outside it: an edge (x = 1 edge's middle)
    let m = min_norm_point(&[v(1.0, -1.0, 0.0), v(1.0, 1.0, 0.0), v(3.0, 0.0, 2.0)]);
    assert!(m.point.distance(v(1.0, 0.0, 0.0)) < 1e-15 && m.support == HullPoint::Edge(0, 1), "{m:?}");
    // a vertex
    let m = min_norm_point(&[v(0.0, 0.0, 2.0), v(1.0, 1.0, 3.0)]);
    assert_eq!(m.support, HullPoint::Vertex(0));
}

proptest! {
    #[test]
    fn min_norm_point_is_the_nearest_hull_point_in_3d(
        pts in prop::collection::vec((-3.0f64..3.0, -3.0f64..3.0, -3.0f64..3.0), 1..7),
        w in prop::collection::vec(0.01f64..1.0, 7),
    ) {
        use glam::DVec3;
        let pts: Vec<DVec3> = pts.into_iter().map(|(x, y, z)| DVec3::new(x, y, z)).collect();
        let p = min_norm_point(&pts).point;
        for g in &pts {
            prop_assert!(p.dot(*g) >= p.length_squared() - 1e-9);
        }
        let ws: f64 = w[..pts.len()].iter().sum();
        let combo: DVec3 = pts.iter().zip(&w).map(|(g, wi)| *g * (*wi / ws)).sum();
        prop_assert!(p.length() <= combo.length() + 1e-9);
    }
}

// ---------------------------------------------------------------- non-smooth ascent

#[test]
fn ascent_reaches_the_peak_of_three_planes() {
    let star = unit_star();
    for (scale, x0) in
        [([1.0, 1.0, 1.0], d(0.9, -0.7)), ([1.0, 3.0, 0.5], d(-0.4, 0.6)), ([0.2, 1.0, 5.0], d(0.1, 0.9))]
    {
        let f = ThreePlanes { peak: d(0.25, -0.1), scale };
        let r = NonSmoothAscent::new(recording(20)).solve(&f, &star, x0);
        assert!(r.x.distance(f.peak) < 1e-9, "{scale:?}: {r:?}");
        assert!(r.value.abs() < 1e-9);
        assert!(r.iterations <= 4, "exact prediction on linear terms: {r:?}");
        assert!(matches!(r.stop, StopReason::Optimal | StopReason::SmallImprovement | StopReason::SmallStep), "{r:?}");
        assert!(r.history.iter().all(|i| i.direction == DirectionKind::ActiveSet));
    }
}

#[test]
fn ascent_centres_a_hexagon_star() {
    let mut star = Star::new();
    star.gather(&hexagon(d(0.35, 0.2)), 0);
    let r = NonSmoothAscent::new(recording(60)).solve(&ShapeMaxMin, &star, star.x0);
    let best = ShapeMaxMin.value(&star, DVec2::ZERO);
    assert!(r.value > r.value0 && r.value > best - 1e-9, "{} vs {best}: {r:?}", r.value);
    assert!(r.x.length() < 1e-5, "{r:?}");
    // Chen's three iterations already recover most of the way
    let r3 = NonSmoothAscent::new(recording(3)).solve(&ShapeMaxMin, &star, star.x0);
    assert!(r3.value > r3.value0 + 0.5 * (best - r3.value0), "{r3:?}");
}

#[test]
fn solvers_are_scale_free() {
    for s in [1e-6, 1.0, 1e5] {
        let mut b = MeshBuilder::new();
        b.add_node([0.3 * s, 0.2 * s, 0.0], 0);
        for i in 0..6 {
            let a = i as f64 * std::f64::consts::PI / 3.0;
            b.add_node([s * a.cos(), s * a.sin(), 0.0], 0);
        }
        for i in 0..6u32 {
            b.add_element(ElementKind::Tri3, &[0, 1 + i, 1 + (i + 1) % 6], 0);
        }
        let mut star = Star::new();
        star.gather(&b.build().unwrap(), 0);
        let r = NonSmoothAscent::new(SolveOptions::default().with_max_iter(10)).solve(&ShapeMaxMin, &star, star.x0);
        assert!(r.value > r.value0 + 0.05, "scale {s}: {r:?}");
        let f = FletcherReeves::new(SolveOptions::default().with_max_iter(10)).solve(&ShapeSum, &star, star.x0);
        assert!(f.x.length() / s < 1e-3, "scale {s}: {f:?}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    /// Neither solver ever ends worse than it started, on random stars and starts.
    #[test]
    fn solvers_never_get_worse(ring in prop::collection::vec((-0.25f64..0.25, -0.25f64..0.25), 6),
                               start in (-0.9f64..0.9, -0.9f64..0.9)) {
        let mut b = MeshBuilder::new();
        b.add_node([start.0, start.1, 0.0], 0);
        for (i, (dx, dy)) in ring.iter().enumerate() {
            let a = i as f64 * std::f64::consts::PI / 3.0;
            b.add_node([a.cos() + dx, a.sin() + dy, 0.0], 0);
        }
        for i in 0..6u32 {
            b.add_element(ElementKind::Tri3, &[0, 1 + i, 1 + (i + 1) % 6], 0);
        }
        let mut star = Star::new();
        star.gather(&b.build().unwrap(), 0);
        let r = NonSmoothAscent::new(recording(8)).solve(&ShapeMaxMin, &star, star.x0);
        prop_assert!(r.value >= r.value0 && r.x.is_finite());
        let mut last = r.value0;
        for it in &r.history {
            prop_assert!(it.value > last);
            last = it.value;
        }
        let f = FletcherReeves::new(recording(8)).solve(&ShapeSum, &star, star.x0);
        prop_assert!(f.value <= f.value0 && f.x.is_finite());
        // Fletcher–Reeves on the max-min objective too (its subgradient): never worse
        let g = FletcherReeves::new(recording(8)).solve(&ShapeMaxMin, &star, star.x0);
        prop_assert!(g.value >= g.value0);
    }
}

// ---------------------------------------------------------------- Newton's first trial

#[test]
fn newton_solves_a_bowl_in_one_step_and_falls_back_without_a_hessian() {
    let star = unit_star();
    let newton = SolveOptions { newton: true, ..recording(3) };
    for (ratio, angle) in [(1.0, 0.0), (20.0, 0.3), (300.0, -1.1)] {
        let bowl = Bowl::elongated(d(0.1, -0.05), ratio, angle);
        let r = FletcherReeves::new(newton).solve(&bowl, &star, d(-0.2, 0.2));
        assert_eq!(r.history[0].direction, DirectionKind::Newton);
        assert!(r.history[0].x.distance(d(0.1, -0.05)) < 1e-12, "{ratio}: {:?}", r.history[0]);
        assert!(r.value <= 1e-24 && r.value < r.value0);
        // Chen's search alone needs its iterations for the same bowl, and never says Newton
        let c = FletcherReeves::new(recording(3)).solve(&bowl, &star, d(-0.2, 0.2));
        assert!(c.history.iter().all(|i| i.direction != DirectionKind::Newton));
    }
    // an objective without a Hessian: the same iterations as without the option
    let rb = Rosenbrock { b: 10.0 };
    let with = FletcherReeves::new(newton).solve(&rb, &star, d(-0.5, 0.5));
    let without = FletcherReeves::new(recording(3)).solve(&rb, &star, d(-0.5, 0.5));
    assert_eq!(with, without);
}

#[test]
fn newton_steps_never_leave_a_barrier_star_worse() {
    // the new objective on stars of every kind, from positions around their nodes: every
    // solve with Newton's first trial ends finite and no higher than it started, and
    // Newton's steps are taken
    use crate::objective::testing::{sample_stars, SplitMix64, SquarePoint};
    use crate::objective::ChenTristanoKwok;
    let obj = ChenTristanoKwok::default();
    let mut rng = SplitMix64::new(5);
    let mut newton_steps = 0;
    for star in sample_stars() {
        for _ in 0..20 {
            let x = star.x0 + rng.point(0.3);
            let star = Star { x0: x, ..star.clone() };
            let r = FletcherReeves::new(SolveOptions { newton: true, ..recording(3) }).solve(&obj, &star, x);
            if !r.value0.is_finite() {
                continue;
            }
            assert!(r.value <= r.value0 && r.value.is_finite(), "{r:?}");
            newton_steps += r.history.iter().filter(|i| i.direction == DirectionKind::Newton).count();
        }
    }
    assert!(newton_steps > 100, "{newton_steps}");
}
