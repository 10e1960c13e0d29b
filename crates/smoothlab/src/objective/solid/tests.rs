use glam::DVec3;

use super::*;
use crate::mesh::VolumeKind;
use crate::numeric::SplitMix64;
use crate::objective::{NodeStar, BARRIER_WEIGHT, CONDITION_BARRIER};
use crate::quality::solid::{validity, CornerSizes};
use crate::quality::tet::{self as q3, WeightedJacobian, EQUILATERAL_W};

/// A point uniform in the cube [−1, 1)³.
fn point(rng: &mut SplitMix64) -> DVec3 {
    let (x, y) = (rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0));
    DVec3::new(x, y, rng.uniform(-1.0, 1.0))
}

/// A star of `n` random tetrahedra around `x0` (each with the free node first).
fn random_star(rng: &mut SplitMix64, n: usize, x0: DVec3) -> CornerStar {
    let tets = (0..n)
        .map(|e| StarCorner::tet(e as u32, [x0, x0 + point(rng), x0 + point(rng), x0 + point(rng)]))
        .collect();
    CornerStar::of_tets(x0, tets)
}

/// The regular tetrahedron's star of one element: every objective at its best.
fn regular_star() -> CornerStar {
    let pts = [DVec3::ZERO, EQUILATERAL_W.x_axis, EQUILATERAL_W.y_axis, EQUILATERAL_W.z_axis];
    CornerStar::of_tets(DVec3::ZERO, vec![StarCorner::tet(0, pts)])
}

#[test]
fn values_on_the_regular_tetrahedron_by_hand() {
    let s = regular_star();
    let v = |k| solid_objective(k).unwrap().value(&s, DVec3::ZERO);
    // q = η = 1: (1 − 1)² + k1·1²
    assert!((v(ObjectiveKind::SmoothShape) - BARRIER_WEIGHT).abs() < 1e-13);
    assert!((v(ObjectiveKind::MaxMinShape) - 1.0).abs() < 1e-14);
    assert!((v(ObjectiveKind::Sine) - 2.0 * 2f64.sqrt() / 3.0).abs() < 1e-14);
    assert!((v(ObjectiveKind::Condition) - 9.0).abs() < 1e-12);
    assert!((v(ObjectiveKind::ConditionMax) + 3.0).abs() < 1e-13);
    assert_eq!(v(ObjectiveKind::Untangle), 0.0);
    // 6V = 6/(6√2)
    assert!((v(ObjectiveKind::UntangleMinDet) - 1.0 / 2f64.sqrt()).abs() < 1e-14);
    // the regular apex is a stationary point of the smooth objectives
    for k in [ObjectiveKind::SmoothShape, ObjectiveKind::Condition] {
        let (_, g) = solid_objective(k).unwrap().value_and_gradient(&s, DVec3::ZERO);
        // a single tetrahedron: moving the apex changes the shape, and the regular
        // one is the best, so the gradient vanishes
        assert!(g.length() < 1e-12, "{k}: {g}");
    }
}

#[test]
fn gradients_agree_with_central_differences() {
    let mut rng = SplitMix64::new(3);
    let h = 1e-6;
    let mut checked = 0;
    for round in 0..80 {
        let x0 = point(&mut rng);
        let star = random_star(&mut rng, 2 + round % 5, x0);
        let tangled = star.tets.iter().any(|t| q3::signed_volume(&t.pts) <= 0.0);
        // steep near a flat tetrahedron: away from those
        if star.tets.iter().any(|t| q3::signed_volume(&t.pts).abs() < 0.02) {
            continue;
        }
        let x = x0 + point(&mut rng) * 0.01;
        for k in solid_kinds() {
            let obj = solid_objective(k).unwrap();
            let mut terms = Vec::new();
            obj.terms(&star, x, &mut terms);
            for (i, t) in terms.iter().enumerate() {
                if t.value.abs() >= CONDITION_BARRIER || !t.value.is_finite() {
                    continue; // behind a barrier: a constant
                }
                let term_at = |y: DVec3| {
                    let mut v = Vec::new();
                    obj.terms(&star, y, &mut v);
                    v[i].value
                };
                let mut fd = DVec3::ZERO;
                for c in 0..3 {
                    let mut e = DVec3::ZERO;
                    e[c] = h;
                    fd[c] = (term_at(x + e) - term_at(x - e)) / (2.0 * h);
                }
                let scale = t.grad.length().max(fd.length()).max(1e-3);
                assert!(
                    (fd - t.grad).length() <= 2e-6 * scale,
                    "{k} term {i} (tangled {tangled}): {} vs {fd}",
                    t.grad
                );
                checked += 1;
            }
        }
    }
    assert!(checked > 500, "{checked}");
}

/// A star of `n` random corners around `x0`: tetrahedra, and corners of hexahedra
/// measured against their slots' references (the free node in every slot).
fn random_mixed_star(rng: &mut SplitMix64, n: usize, x0: DVec3) -> CornerStar {
    let hex = VolumeKind::Hex8.row();
    let tets = (0..n)
        .map(|e| {
            let pts = [x0, x0 + point(rng), x0 + point(rng), x0 + point(rng)];
            match e % 3 {
                0 => StarCorner::tet(e as u32, pts),
                k => StarCorner::new(e as u32, pts, &hex.slot_references[(e + k) % 4], false),
            }
        })
        .collect();
    CornerStar::of_tets(x0, tets)
}

#[test]
fn a_solids_shape_and_sizes_keep_the_terms_of_the_corners_that_did_not_move() {
    // an element of every kind other than the tetrahedron with each corner free in
    // turn, its shape, corner sizes and validity asked at a walk of positions:
    // solid_shape's bits and the sizes measured afresh at each, the terms of the corners
    // whose tetrahedra do not hold the free node kept; the guard's validity (kept where
    // the drivers measured it, the ball about the first position asked, the first
    // question beyond it exactly, then the form) the exact test's
    let mut rng = SplitMix64::new(24);
    for kind in [VolumeKind::Hex8, VolumeKind::Wedge6, VolumeKind::Pyramid5] {
        let ideal = kind.row().ideal;
        for slot in 0..kind.corners() {
            let mut pts = [DVec3::ZERO; 8];
            for (p, c) in pts.iter_mut().zip(ideal) {
                *p = DVec3::from(*c) + point(&mut rng) * 0.1;
            }
            let e = StarSolid::new(0, kind, slot as u8, pts);
            for step in 0..12 {
                let x = pts[slot] + point(&mut rng) * [0.05, 0.5][step % 2];
                let mut p = pts;
                p[slot] = x;
                let exact = crate::quality::solid::solid_shape(kind, &p[..kind.corners()]);
                assert_eq!(e.shape_measured(x).to_bits(), exact.to_bits(), "{kind:?} slot {slot} at {x}");
                let sizes = CornerSizes::of(kind, &p[..kind.corners()], |_| None);
                assert_eq!(e.sizes_measured(x), sizes, "{kind:?} slot {slot} at {x}");
                if step % 3 == 2 {
                    // measured by the drivers first: the guard reads it from the memo
                    e.validity_measured(x);
                }
                assert_eq!(e.validity_at(x), validity(kind, &p[..kind.corners()]), "{kind:?} slot {slot} at {x}");
            }
        }
    }
}

#[test]
fn forms_give_the_corners_weighted_jacobian_anywhere() {
    let mut rng = SplitMix64::new(21);
    for _ in 0..50 {
        let x0 = point(&mut rng);
        let star = random_mixed_star(&mut rng, 6, x0);
        let x = x0 + point(&mut rng) * 0.3;
        for t in &star.tets {
            let (a, b) = (t.form.at(x), WeightedJacobian::of(&t.at(x), t.reference));
            let close = |u: f64, v: f64| (u - v).abs() <= 1e-13 * (1.0 + v.abs());
            assert!(close(a.frob2, b.frob2) && close(a.sigma, b.sigma), "{a:?} {b:?}");
            assert!((a.grad_frob2 - b.grad_frob2).length() <= 1e-13 * (1.0 + b.grad_frob2.length()));
            assert!((a.grad_sigma - b.grad_sigma).length() <= 1e-13 * (1.0 + b.grad_sigma.length()));
            assert!((a.t - b.t).to_cols_array().iter().all(|d| d.abs() <= 1e-13), "{a:?} {b:?}");
            let v6 = t.form.volume6_at(x, t.reference).0;
            assert!(close(v6, 6.0 * q3::signed_volume(&t.at(x))), "{v6}");
        }
    }
}

#[test]
fn corners_decide_inversion_as_their_tetrahedra_do() {
    // every answer a form gives is is_inverted's, at every scale, and it gives one
    // for most positions
    let mut rng = SplitMix64::new(4);
    let (mut asked, mut decided, mut inverted) = (0, 0, 0);
    for round in 0..300 {
        let scale = [1.0, 1e-4, 1e5][round % 3];
        let x0 = point(&mut rng) * scale;
        for t in random_mixed_star(&mut rng, 3, DVec3::ZERO).tets {
            let t = StarCorner::new(t.element, t.pts.map(|p| x0 + p * scale), t.reference, t.simplex);
            for _ in 0..5 {
                let x = x0 + point(&mut rng) * scale * rng.uniform(0.0, 2.0);
                let exact = q3::is_inverted(&t.at(x));
                if let Some(v) = t.form.inverted_at(x, t.reference) {
                    assert_eq!(v, exact, "{:?} at {x}", t.pts);
                    decided += 1;
                }
                asked += 1;
                inverted += exact as u32;
            }
        }
    }
    assert!(decided * 100 > asked * 99 && inverted * 5 > asked && inverted * 5 < 4 * asked, "{decided} {inverted} of {asked}");
    // beyond the safe scale: left to is_inverted
    let t = StarCorner::tet(0, [DVec3::ZERO, DVec3::X * 1e200, DVec3::Y * 1e200, DVec3::Z * 1e200]);
    assert_eq!(t.form.inverted_at(DVec3::ZERO, t.reference), None);
    assert!(!t.inverted_at(DVec3::ZERO, t.reference));
}

#[test]
fn terms_above_answers_as_the_terms_do() {
    let mut rng = SplitMix64::new(30);
    let mut stopped = 0;
    for round in 0..60 {
        let x0 = point(&mut rng);
        let star = if round % 2 == 0 { random_star(&mut rng, 5, x0) } else { random_mixed_star(&mut rng, 5, x0) };
        let x = x0 + point(&mut rng) * 0.2;
        for k in solid_kinds() {
            let obj = solid_objective(k).unwrap();
            let mut all = Vec::new();
            obj.terms(&star, x, &mut all);
            let min = all.iter().fold(f64::INFINITY, |m, t| m.min(t.value));
            for floor in [min - 1.0, min, min + 1e-3, f64::NEG_INFINITY] {
                for lead in [0, 3, 4, 9] {
                    let mut out = Vec::new();
                    let above = obj.terms_above(&star, x, floor, lead, &mut out);
                    assert_eq!(above, all.iter().all(|t| t.value > floor), "{k} floor {floor} lead {lead}");
                    if above {
                        assert_eq!(out, all, "{k}");
                    } else {
                        stopped += 1;
                    }
                }
            }
        }
    }
    assert!(stopped > 100, "{stopped}");
}

#[test]
fn hessian_of_new_agrees_with_central_differences() {
    let obj = solid_objective(ObjectiveKind::SmoothShape).unwrap();
    let mut rng = SplitMix64::new(13);
    let (h, mut checked, mut tangled) = (1e-6, 0, 0);
    for round in 0..120 {
        let x0 = point(&mut rng);
        let star = random_mixed_star(&mut rng, 2 + round % 6, x0);
        if star.tets.iter().any(|t| t.form.sigma_at(x0).abs() < 0.05) {
            continue; // steep near a flat corner: away from those
        }
        tangled += star.tets.iter().any(|t| t.form.sigma_at(x0) < 0.0) as u32;
        let x = x0 + point(&mut rng) * 0.01;
        let (v, g, hess) = obj.value_gradient_hessian(&star, x).expect("a Hessian");
        assert_eq!((v, g), obj.value_and_gradient(&star, x));
        // the fold is the sum of the terms, in their order
        let mut terms = Vec::new();
        obj.terms(&star, x, &mut terms);
        assert_eq!(v, terms.iter().fold(0.0, |s, t| s + t.value));
        if !v.is_finite() {
            continue;
        }
        assert!((hess - hess.transpose()).to_cols_array().iter().all(|d| d.abs() <= 1e-9 * (1.0 + hess.abs().to_cols_array().iter().fold(0.0f64, |a, &b| a.max(b)))));
        for c in 0..3 {
            let mut e = DVec3::ZERO;
            e[c] = h;
            let fd = (obj.value_and_gradient(&star, x + e).1 - obj.value_and_gradient(&star, x - e).1) / (2.0 * h);
            let col = hess.col(c);
            assert!((col - fd).length() <= 1e-5 * (1.0 + fd.length()), "column {c}: {col} vs {fd}");
        }
        checked += 1;
    }
    assert!(checked > 60 && tangled > 10, "{checked} {tangled}");
    // the max-min objectives have no Hessian
    assert!(solid_objective(ObjectiveKind::MaxMinShape).unwrap().value_gradient_hessian(&regular_star(), DVec3::ZERO).is_none());
}

#[test]
fn new_is_finite_on_a_tangled_star_and_a_barrier_on_a_valid_one() {
    let mut rng = SplitMix64::new(9);
    let obj = solid_objective(ObjectiveKind::SmoothShape).unwrap();
    let mut tangled_seen = 0;
    for _ in 0..50 {
        let x0 = point(&mut rng);
        let star = random_star(&mut rng, 4, x0);
        let inverted = star.tets.iter().filter(|t| q3::signed_volume(&t.pts) <= 0.0).count();
        let (v, g) = obj.value_and_gradient(&star, x0);
        if inverted > 0 {
            tangled_seen += 1;
            assert!(v.is_finite() && g.is_finite(), "{v} {g}");
        } else {
            assert!(v.is_finite() && g.is_finite(), "{v} {g}");
        }
    }
    assert!(tangled_seen > 10, "{tangled_seen}");
    // a known crossing: the regular apex moved through the opposite face
    let s = regular_star();
    let beyond = (EQUILATERAL_W.x_axis + EQUILATERAL_W.y_axis + EQUILATERAL_W.z_axis) / 3.0 * 2.0;
    assert_eq!(obj.value(&s, beyond), f64::INFINITY);
}

#[test]
fn scaled_star_keeps_shape_values() {
    let mut rng = SplitMix64::new(5);
    let star = random_star(&mut rng, 5, DVec3::new(0.1, 0.2, 0.3));
    let f = 2f64.powi(40);
    let big = star.scaled(f);
    assert_eq!(big.size(), star.size() * f);
    for k in [ObjectiveKind::SmoothShape, ObjectiveKind::MaxMinShape, ObjectiveKind::Sine, ObjectiveKind::Condition] {
        let (a, b) = (solid_objective(k).unwrap().value(&star, star.x0), solid_objective(k).unwrap().value(&big, big.x0));
        assert!((a - b).abs() <= 1e-12 * a.abs().max(1.0), "{k}: {a} {b}");
    }
}
