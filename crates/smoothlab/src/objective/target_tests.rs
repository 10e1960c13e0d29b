//! The objectives against targets other than the ideal ([`crate::target`]): gradients and
//! Hessians by central differences, a star at its targets stationary, 2D and 3D.

use glam::{DMat2, DMat3, DVec2, DVec3};

use super::testing::*;
use super::solid::{solid_kinds, solid_objective, CornerStar, StarCorner};
use super::*;
use crate::target::{element_frames, solid_reference};

/// `s` with targets: each element's nodes moved by `map` (a stretch and shear, so the
/// frames are not the identity).
fn with_targets(s: &Star, map: impl Fn(DVec2) -> DVec2) -> Star {
    let mut t = s.clone();
    for el in &s.elems {
        let mut p = [DVec2::ZERO; 9];
        for (q, &r) in p.iter_mut().zip(&el.pts) {
            *q = map(r);
        }
        t.frames.push(element_frames(el.kind, &p));
        t.targets.push(p);
    }
    t
}

/// A stretch by 3 along a direction at 20°, with a shear.
fn stretch(p: DVec2) -> DVec2 {
    let m = DMat2::from_angle(0.35)
        * DMat2::from_cols(DVec2::new(3.0, 0.0), DVec2::new(0.4, 1.0))
        * DMat2::from_angle(-0.35);
    m * p
}

#[test]
fn planar_gradients_against_targets_agree_with_central_differences() {
    let mut rng = SplitMix64::new(29);
    let mut checked = 0;
    for star in sample_stars() {
        let s = with_targets(&star, stretch);
        assert!(s.frames.iter().flatten().any(|m| *m != DMat2::IDENTITY));
        for kind in ObjectiveKind::ALL {
            let obj = objective(kind);
            for _ in 0..4 {
                let x = star.x0 + rng.point(0.05);
                if obj.goal() == Goal::MinimizeSum && looks_smooth(|p| obj.value(&s, p), x, 1e-6) {
                    check_gradient(&*obj, &s, x, 2e-5);
                    if obj.value_gradient_hessian(&s, x).is_some() {
                        check_hessian(&*obj, &s, x, 2e-4);
                    }
                }
                checked += check_term_gradients(&*obj, &s, x, 2e-5).0;
            }
        }
    }
    assert!(checked > 1000, "{checked}");
}

#[test]
fn a_planar_star_at_its_targets_is_stationary() {
    // the stretched star is its own target: every corner is its target's shape, so the
    // smooth shape objectives are at a minimum there, whatever the stretch
    for star in sample_stars()
        .into_iter()
        .filter(|s| s.elems.iter().all(|e| !e.kind.is_quadratic()))
    {
        let mut stretched = star.clone();
        stretched.x0 = stretch(star.x0);
        for el in &mut stretched.elems {
            for p in &mut el.pts {
                *p = stretch(*p);
            }
        }
        let s = with_targets(&stretched, |p| p);
        for kind in [ObjectiveKind::Condition, ObjectiveKind::SmoothShape] {
            let ideal = objective(kind)
                .value_and_gradient(&stretched, stretched.x0)
                .1;
            let (_, g) = objective(kind).value_and_gradient(&s, s.x0);
            let size = s.size();
            assert!(
                g.length() * size < 1e-9 * (1.0 + ideal.length() * size),
                "{kind}: {g} (ideal target {ideal})"
            );
        }
    }
}

/// `star` with each corner's target the same corner with its points moved by `map`.
fn with_solid_targets(star: &CornerStar, map: impl Fn(DVec3) -> DVec3) -> CornerStar {
    let mut s = star.clone();
    s.targets = star
        .tets
        .iter()
        .map(|t| {
            let q = t.pts.map(&map);
            let a = DMat3::from_cols(q[1] - q[0], q[2] - q[0], q[3] - q[0]);
            solid_reference(a, t.reference).unwrap_or(*t.reference)
        })
        .collect();
    s.forms_pending_at = Some(s.x0);
    s.complete_forms();
    s
}

fn stretch3(p: DVec3) -> DVec3 {
    DMat3::from_cols(
        DVec3::new(2.5, 0.0, 0.0),
        DVec3::new(0.3, 1.0, 0.0),
        DVec3::new(0.0, 0.2, 0.6),
    ) * p
}

#[test]
fn volume_gradients_against_targets_agree_with_central_differences() {
    let mut rng = SplitMix64::new(31);
    let hex = crate::mesh::VolumeKind::Hex8.row();
    let mut checked = 0;
    for round in 0..40 {
        let x0 = DVec3::new(
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
        );
        // valid corners about x0: a tetrahedron's, and hexahedron corners in every slot
        let tets = (0..3 + round % 4)
            .map(|e| {
                let j = |rng: &mut SplitMix64| {
                    DVec3::new(
                        rng.uniform(-0.2, 0.2),
                        rng.uniform(-0.2, 0.2),
                        rng.uniform(-0.2, 0.2),
                    )
                };
                let pts = [
                    x0,
                    x0 + DVec3::X + j(&mut rng),
                    x0 + DVec3::Y + j(&mut rng),
                    x0 + DVec3::Z + j(&mut rng),
                ];
                match e % 2 {
                    0 => StarCorner::tet(e as u32, pts),
                    _ => StarCorner::new(e as u32, pts, &hex.slot_references[0], false),
                }
            })
            .collect();
        let star = with_solid_targets(&CornerStar::of_tets(x0, tets), stretch3);
        assert!(star.targeted());
        let x = x0
            + DVec3::new(
                rng.uniform(-0.01, 0.01),
                rng.uniform(-0.01, 0.01),
                rng.uniform(-0.01, 0.01),
            );
        for k in solid_kinds() {
            let obj = solid_objective(k).unwrap();
            let mut terms = Vec::new();
            obj.terms(&star, x, &mut terms);
            for (i, t) in terms.iter().enumerate() {
                if t.value.abs() >= CONDITION_BARRIER || !t.value.is_finite() {
                    continue;
                }
                let term_at = |y: DVec3| {
                    let mut v = Vec::new();
                    obj.terms(&star, y, &mut v);
                    v[i].value
                };
                let h = 1e-6;
                let fd = DVec3::new(
                    (term_at(x + DVec3::X * h) - term_at(x - DVec3::X * h)) / (2.0 * h),
                    (term_at(x + DVec3::Y * h) - term_at(x - DVec3::Y * h)) / (2.0 * h),
                    (term_at(x + DVec3::Z * h) - term_at(x - DVec3::Z * h)) / (2.0 * h),
                );
                let scale = t.grad.length().max(fd.length()).max(1e-3);
                assert!(
                    (fd - t.grad).length() <= 2e-6 * scale,
                    "{k} term {i}: {} vs {fd}",
                    t.grad
                );
                checked += 1;
            }
        }
    }
    assert!(checked > 300, "{checked}");
}

#[test]
fn a_volume_star_at_its_targets_is_stationary() {
    // a stretched star of tetrahedra (the octahedron's eight), the free node off its
    // centre: the ideal pulls it back, its own corners as targets hold it
    let c = stretch3(DVec3::new(0.2, -0.1, 0.15));
    let mut tets = Vec::new();
    for sx in [1.0, -1.0] {
        for sy in [1.0, -1.0] {
            for sz in [1.0, -1.0] {
                let (a, b, c3) = (DVec3::X * sx, DVec3::Y * sy, DVec3::Z * sz);
                // the free node first, in an even order (positive volume)
                let (b, c3) = if sx * sy * sz > 0.0 { (b, c3) } else { (c3, b) };
                tets.push(StarCorner::tet(
                    tets.len() as u32,
                    [c, stretch3(a), stretch3(b), stretch3(c3)],
                ));
            }
        }
    }
    let stretched = CornerStar::of_tets(c, tets);
    let s = with_solid_targets(&stretched, |p| p);
    for k in [ObjectiveKind::Condition, ObjectiveKind::SmoothShape] {
        let ideal = solid_objective(k)
            .unwrap()
            .value_and_gradient(&stretched, c)
            .1;
        let (_, g) = solid_objective(k).unwrap().value_and_gradient(&s, c);
        assert!(ideal.length() > 1e-3, "{k}: the ideal pulls ({ideal})");
        assert!(g.length() < 1e-10, "{k}: {g}");
    }
}
