use super::bernstein::{hex_det_and_slopes, Bezier};
use super::*;
use crate::numeric::SplitMix64;

fn ideal(kind: VolumeKind) -> Vec<DVec3> {
    let r = kind.row();
    let mut p: Vec<DVec3> = r.ideal.iter().map(|&c| DVec3::from(c)).collect();
    for f in r.followers {
        p.push(f.iter().map(|&c| p[c]).sum::<DVec3>() / f.len() as f64);
    }
    p
}

/// The ideal element of `kind`, each node moved by up to `amount` along each axis, times
/// `scale`.
fn perturbed(kind: VolumeKind, rng: &mut SplitMix64, amount: f64, scale: f64) -> Vec<DVec3> {
    ideal(kind)
        .iter()
        .map(|c| (*c + DVec3::new(rng.uniform(-amount, amount), rng.uniform(-amount, amount), rng.uniform(-amount, amount))) * scale)
        .collect()
}

fn pts(a: &[[f64; 3]]) -> Vec<DVec3> {
    a.iter().map(|&c| DVec3::from(c)).collect()
}

#[test]
fn the_ideal_element_of_every_kind_measures_as_ideal() {
    for k in VolumeKind::ALL {
        let m = solid_measures(k, &ideal(k));
        assert!(!m.inverted, "{k:?}");
        assert_eq!(validity(k, &ideal(k)), Validity::Valid, "{k:?}");
        assert!((m.mean_ratio - 1.0).abs() < 1e-12, "{k:?}: {}", m.mean_ratio);
        // κ of an ideal corner is 3 (T a rotation: ‖T‖_F = ‖T⁻¹‖_F = √3)
        assert!((m.condition - 3.0).abs() < 1e-12, "{k:?}: {}", m.condition);
        if !k.is_tet() {
            assert!((m.scaled_jacobian - 1.0).abs() < 1e-12, "{k:?}: {}", m.scaled_jacobian);
        }
    }
    // a cube's dihedral angles are right angles; a right wedge's 90° and 60°
    let cube = solid_measures(VolumeKind::Hex8, &ideal(VolumeKind::Hex8));
    assert_eq!(cube.dihedral_count, 24);
    assert!(cube.dihedral().iter().all(|a| (a - 90.0).abs() < 1e-12));
    let wedge = solid_measures(VolumeKind::Wedge6, &ideal(VolumeKind::Wedge6));
    assert!(wedge.dihedral().iter().all(|a| (a - 90.0).abs() < 1e-12 || (a - 60.0).abs() < 1e-12));
    assert!((wedge.min_dihedral_deg - 60.0).abs() < 1e-12);
}

/// `det J` of a trilinear hexahedron at (u, v, w), by the derivatives of its map.
fn hex_det_at(p: &[DVec3], u: f64, v: f64, w: f64) -> f64 {
    let at = |i: usize, j: usize, k: usize| p[4 * k + [[0, 3], [1, 2]][i][j]];
    let l = |t: f64, i: usize| if i == 1 { t } else { 1.0 - t };
    let mut x = [DVec3::ZERO; 3];
    for a in 0..2 {
        for b in 0..2 {
            x[0] += (at(1, a, b) - at(0, a, b)) * l(v, a) * l(w, b);
            x[1] += (at(a, 1, b) - at(a, 0, b)) * l(u, a) * l(w, b);
            x[2] += (at(a, b, 1) - at(a, b, 0)) * l(u, a) * l(v, b);
        }
    }
    x[0].dot(x[1].cross(x[2]))
}

/// A Bernstein polynomial of degree 2 in each parameter at (u, v, w).
fn eval(b: &Bezier, t: [f64; 3]) -> f64 {
    let basis = |d: usize, t: f64| -> [f64; 3] {
        match d {
            0 => [1.0, 0.0, 0.0],
            _ => [(1.0 - t) * (1.0 - t), 2.0 * t * (1.0 - t), t * t],
        }
    };
    let (bu, bv, bw) = (basis(b.deg[0], t[0]), basis(b.deg[1], t[1]), basis(b.deg[2], t[2]));
    let mut s = 0.0;
    for (ci, u) in b.c.iter().zip(bu) {
        for (cij, v) in ci.iter().zip(bv) {
            for (c, w) in cij.iter().zip(bw) {
                s += c * u * v * w;
            }
        }
    }
    s
}

#[test]
fn the_bernstein_coefficients_are_the_hexahedron_jacobian_determinant() {
    let mut rng = SplitMix64::new(11);
    for _ in 0..50 {
        let p: Vec<DVec3> = perturbed(VolumeKind::Hex8, &mut rng, 0.4, 1.0);
        let b = hex_det(&p);
        for _ in 0..20 {
            let t = [rng.uniform(0.0, 1.0), rng.uniform(0.0, 1.0), rng.uniform(0.0, 1.0)];
            let (a, e) = (eval(&b, t), hex_det_at(&p, t[0], t[1], t[2]));
            assert!((a - e).abs() < 1e-12 * e.abs().max(1.0), "{a} vs {e}");
        }
        // the halves of a split are the polynomial on the halves
        let (lo, hi) = b.split(1);
        let t = [rng.uniform(0.0, 1.0), rng.uniform(0.0, 1.0), rng.uniform(0.0, 1.0)];
        assert!((eval(&lo, t) - hex_det_at(&p, t[0], 0.5 * t[1], t[2])).abs() < 1e-12);
        assert!((eval(&hi, t) - hex_det_at(&p, t[0], 0.5 + 0.5 * t[1], t[2])).abs() < 1e-12);
    }
}

/// Found by searching perturbed cubes: all eight corner determinants ≥ 0.08, yet
/// `det J ≈ −0.18` inside.
const INSIDE_OUT_HEX: [[f64; 3]; 8] = [
    [-0.7, 0.8, 0.2],
    [1.7, -0.2, -0.2],
    [1.6, 1.8, 0.5],
    [0.7, 1.6, 0.5],
    [0.7, 0.5, 0.1],
    [0.4, -0.3, 0.5],
    [1.8, 1.7, 1.1],
    [-0.5, 0.3, 0.2],
];

#[test]
fn a_hexahedron_inverted_inside_with_every_corner_positive_is_found() {
    let p = pts(&INSIDE_OUT_HEX);
    for c in 0..8 {
        assert!(corner_det(&corner_tet(VolumeKind::Hex8, &p, c)) > 0.07, "corner {c}");
    }
    assert!(hex_det_at(&p, 0.5, 0.5, 0.5).min(hex_det_at(&p, 0.3, 0.6, 0.4)) < 0.0 || {
        // somewhere on a grid
        (0..10).any(|i| (0..10).any(|j| (0..10).any(|k| hex_det_at(&p, i as f64 / 9.0, j as f64 / 9.0, k as f64 / 9.0) < 0.0)))
    });
    assert_eq!(validity(VolumeKind::Hex8, &p), Validity::Inverted);
    let m = solid_measures(VolumeKind::Hex8, &p);
    assert!(m.inverted && m.inverted_inside);
    // at every scale alike
    for s in [1e-150, 1e150] {
        let q: Vec<DVec3> = p.iter().map(|x| *x * s).collect();
        assert_eq!(validity(VolumeKind::Hex8, &q), Validity::Inverted, "{s:e}");
        let ok: Vec<DVec3> = ideal(VolumeKind::Hex8).iter().map(|x| *x * s).collect();
        assert_eq!(validity(VolumeKind::Hex8, &ok), Validity::Valid, "{s:e}");
    }
}

/// Found by searching perturbed wedges: all six corner determinants ≥ 0.27, yet
/// `det J ≈ −0.14` inside.
const INSIDE_OUT_WEDGE: [[f64; 3]; 6] =
    [[0.5, 0.6, 0.5], [1.2, 0.4, -0.6], [0.4, 0.5, -0.5], [-0.3, -0.6, 1.7], [0.0, 0.4, 1.2], [1.3, -0.7, 1.1]];

#[test]
fn a_wedge_inverted_inside_with_every_corner_positive_is_found() {
    let p = pts(&INSIDE_OUT_WEDGE);
    for c in 0..6 {
        assert!(corner_det(&corner_tet(VolumeKind::Wedge6, &p, c)) > 0.26, "corner {c}");
    }
    assert_eq!(validity(VolumeKind::Wedge6, &p), Validity::Inverted);
    assert!(solid_measures(VolumeKind::Wedge6, &p).inverted_inside);
}

#[test]
fn validity_agrees_with_dense_sampling_on_random_elements() {
    // where the certain answer is Valid, no sample is ≤ 0; where Inverted, some point is
    // (the sampling may miss a thin one: only the first direction is checked)
    let mut rng = SplitMix64::new(21);
    let (mut valid, mut inverted) = (0, 0);
    for _ in 0..400 {
        let p: Vec<DVec3> = perturbed(VolumeKind::Hex8, &mut rng, 0.6, 1.0);
        let n = 12;
        let sampled_min = (0..=n)
            .flat_map(|i| (0..=n).flat_map(move |j| (0..=n).map(move |k| (i, j, k))))
            .map(|(i, j, k)| hex_det_at(&p, i as f64 / n as f64, j as f64 / n as f64, k as f64 / n as f64))
            .fold(f64::INFINITY, f64::min);
        match validity(VolumeKind::Hex8, &p) {
            Validity::Valid => {
                valid += 1;
                assert!(sampled_min > 0.0, "{p:?}");
            }
            Validity::Inverted => {
                inverted += 1;
            }
            Validity::Undecided => {}
        }
        if sampled_min <= 0.0 {
            assert_ne!(validity(VolumeKind::Hex8, &p), Validity::Valid);
        }
    }
    assert!(valid > 50 && inverted > 50, "{valid} {inverted}");
}

#[test]
fn a_pyramid_is_decided_by_its_base_map() {
    let p = ideal(VolumeKind::Pyramid5);
    assert_eq!(validity(VolumeKind::Pyramid5, &p), Validity::Valid);
    // the apex pushed through the base: inverted
    let mut q = p.clone();
    q[4].z = -0.3;
    assert_eq!(validity(VolumeKind::Pyramid5, &q), Validity::Inverted);
    // a base folded into a bow tie: inverted, though the apex is high above
    let mut r = p.clone();
    r.swap(1, 2);
    assert_eq!(validity(VolumeKind::Pyramid5, &r), Validity::Inverted);
}

#[test]
fn the_scaled_jacobian_gradient_agrees_with_central_differences() {
    let mut rng = SplitMix64::new(7);
    let h = 1e-6;
    for k in [VolumeKind::Tet4, VolumeKind::Hex8, VolumeKind::Wedge6, VolumeKind::Pyramid5] {
        let r = k.reference();
        for _ in 0..40 {
            let p: [DVec3; 4] = std::array::from_fn(|_| DVec3::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)));
            let (v, g) = scaled_jacobian_grad0(&p, r);
            assert!((v - scaled_jacobian(&p, r)).abs() < 1e-12);
            let mut fd = DVec3::ZERO;
            for c in 0..3 {
                let mut e = DVec3::ZERO;
                e[c] = h;
                let (mut a, mut b) = (p, p);
                a[0] += e;
                b[0] -= e;
                fd[c] = (scaled_jacobian(&a, r) - scaled_jacobian(&b, r)) / (2.0 * h);
            }
            assert!((fd - g).length() <= 1e-6 * g.length().max(1.0), "{k:?}: {g} vs {fd}");
        }
    }
}

#[test]
fn a_det_form_decides_as_validity_does_wherever_the_free_corner_goes() {
    // hexahedra and pyramids with each corner free in turn, moved from near to far: every
    // answer the form gives is validity's, and it gives one for most positions
    let mut rng = SplitMix64::new(8);
    let (mut decided, mut asked, mut inverted) = (0, 0, 0);
    for kind in [VolumeKind::Hex8, VolumeKind::Pyramid5] {
        for round in 0..200 {
            let scale = [1.0, 1e-3, 250.0][round % 3];
            let p: Vec<DVec3> = perturbed(kind, &mut rng, 0.3, scale);
            let slot = round % kind.corners();
            let form = DetForm::of(kind, &p, slot).expect("a Bernstein form");
            for _ in 0..20 {
                let reach = rng.uniform(0.0, 1.5) * scale;
                let x = p[slot] + DVec3::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)) * reach;
                let mut q = p.clone();
                q[slot] = x;
                let exact = validity(kind, &q);
                asked += 1;
                inverted += (exact != Validity::Valid) as u32;
                if let Some(v) = form.validity_at(x) {
                    assert_eq!(v, exact, "{kind:?} slot {slot} at {x} of {p:?}");
                    decided += 1;
                }
            }
        }
    }
    assert!(decided * 10 > asked * 9 && inverted * 5 > asked, "{decided} of {asked}, {inverted} not valid");
    // tetrahedra and wedges are decided as they are; beyond the safe scale, in their own
    assert!(DetForm::of(VolumeKind::Tet4, &ideal(VolumeKind::Tet4), 0).is_none());
    assert!(DetForm::of(VolumeKind::Wedge6, &ideal(VolumeKind::Wedge6), 0).is_none());
    let huge: Vec<DVec3> = ideal(VolumeKind::Hex8).iter().map(|c| *c * 1e200).collect();
    assert!(DetForm::of(VolumeKind::Hex8, &huge, 0).is_none());
}

#[test]
fn a_hexahedrons_slopes_are_its_coefficients_differences() {
    // each Bernstein coefficient is affine in a corner: the analytic slopes of the form
    // against the coefficients' differences at a moved corner, every corner in turn
    let mut rng = SplitMix64::new(12);
    for round in 0..400 {
        let scale = [1.0, 1e-3, 250.0][round % 3];
        let p: Vec<DVec3> = perturbed(VolumeKind::Hex8, &mut rng, 0.6, scale);
        let slot = round % 8;
        let (c, slopes) = hex_det_and_slopes(&p, slot);
        assert_eq!(c, hex_det(&p));
        let step = DVec3::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)) * scale;
        let mut q = p.clone();
        q[slot] += step;
        let moved = hex_det(&q);
        let unit = scale * scale * scale;
        for (n, slope) in slopes.iter().enumerate() {
            let (i, j, k) = (n / 9, n / 3 % 3, n % 3);
            let by_slope = c.c[i][j][k] + slope.dot(step);
            assert!((by_slope - moved.c[i][j][k]).abs() <= 1e-12 * unit, "slot {slot} coefficient {n}: {by_slope} vs {}", moved.c[i][j][k]);
        }
    }
}

#[test]
fn a_valid_ball_holds_only_positions_where_the_hexahedron_is_valid() {
    // the positions a ball holds are valid by the exact test and by the form; the ball of a
    // hexahedron near the ideal holds some of the positions tried, an inverted one has none
    let mut rng = SplitMix64::new(13);
    let (mut held, mut asked) = (0, 0);
    for round in 0..300 {
        let scale = [1.0, 1e-3, 250.0][round % 3];
        let p: Vec<DVec3> = perturbed(VolumeKind::Hex8, &mut rng, 0.25, scale);
        let slot = round % 8;
        let Some(ball) = ValidBall::of(VolumeKind::Hex8, &p, slot) else {
            assert_ne!(validity(VolumeKind::Hex8, &p), Validity::Valid, "a valid hexahedron has a ball");
            continue;
        };
        let form = DetForm::of(VolumeKind::Hex8, &p, slot).expect("a form");
        for _ in 0..40 {
            let x = p[slot] + DVec3::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)) * rng.uniform(0.0, 0.5) * scale;
            asked += 1;
            if ball.holds(x) {
                let mut q = p.clone();
                q[slot] = x;
                assert_eq!(validity(VolumeKind::Hex8, &q), Validity::Valid, "slot {slot} at {x} of {p:?}");
                assert_eq!(form.validity_at(x), Some(Validity::Valid));
                held += 1;
            }
        }
    }
    assert!(held * 10 > asked, "{held} of {asked} held");
    let mut flat = ideal(VolumeKind::Hex8);
    flat[6].z = 0.0;
    flat[2].z = 1.0;
    assert!(ValidBall::of(VolumeKind::Hex8, &flat, 0).is_none());
    assert_eq!(ValidBall::validity_and_ball(VolumeKind::Hex8, &flat, 0), (validity(VolumeKind::Hex8, &flat), None));
    assert!(ValidBall::of(VolumeKind::Pyramid5, &ideal(VolumeKind::Pyramid5), 0).is_none());
}

#[test]
fn corner_sizes_are_each_corners_and_kept_ones_the_same() {
    // every kind but the tetrahedron, near the ideal and folded, at three scales: each size
    // is its corner tetrahedron's (unit · scale³ its determinant), measured or kept
    let mut rng = SplitMix64::new(15);
    for kind in [VolumeKind::Hex8, VolumeKind::Wedge6, VolumeKind::Pyramid5] {
        for round in 0..300 {
            let (scale, amount) = ([1.0, 1e-3, 250.0][round % 3], [0.1, 0.6][round % 2]);
            let p = perturbed(kind, &mut rng, amount, scale);
            let s = CornerSizes::of(kind, &p, |_| None);
            assert_eq!(s.of_kind(kind).len(), kind.row().corner_edges.len());
            for (c, &(unit, m)) in s.of_kind(kind).iter().enumerate() {
                let t = corner_tet(kind, &p, c);
                let det = corner_det(&t);
                assert!((unit * m * m * m - det).abs() <= 1e-12 * m * m * m, "{kind:?} corner {c}: {unit} {m} {det}");
                assert_eq!((unit, m), corner_size(&t));
            }
            let again = CornerSizes::of(kind, &p, |c| (c % 2 == 0).then(|| s.of_kind(kind)[c]));
            assert_eq!(again, s);
        }
    }
}

#[test]
fn corner_shapes_are_the_terms_of_the_solid_shape_bit_for_bit() {
    // every kind but the tetrahedron, near the ideal and folded, at three scales: the
    // terms' mean is solid_shape's bits, measured or kept; beyond the safe scale, none
    let mut rng = SplitMix64::new(14);
    for kind in [VolumeKind::Hex8, VolumeKind::Wedge6, VolumeKind::Pyramid5] {
        for round in 0..300 {
            let (scale, amount) = ([1.0, 1e-3, 250.0][round % 3], [0.1, 0.6][round % 2]);
            let p = perturbed(kind, &mut rng, amount, scale);
            let t = CornerShapes::of(kind, &p, |_| None).expect("within the safe scale");
            assert_eq!(t.shape(kind).to_bits(), solid_shape(kind, &p).to_bits(), "{kind:?} {p:?}");
            let again = CornerShapes::of(kind, &p, |c| (c % 2 == 0).then(|| t.corner(c))).unwrap();
            assert_eq!(again, t);
            // the least corner determinant from the shape's Jacobians: the direct one's
            // tolerance, and within rounding of its value, far inside that tolerance
            let ((d, tol), (direct, direct_tol)) = (t.least_corner_det(kind).unwrap(), least_corner_det(kind, &p).unwrap());
            assert_eq!(tol.to_bits(), direct_tol.to_bits());
            assert!((d - direct).abs() <= 1e-3 * tol, "{kind:?}: {d} against {direct} (tolerance {tol})");
        }
        let huge: Vec<DVec3> = ideal(kind).iter().take(kind.corners()).map(|c| *c * 1e200).collect();
        assert!(CornerShapes::of(kind, &huge, |_| None).is_none());
    }
}

#[test]
fn the_second_ball_comes_with_the_exact_validity_and_holds_only_valid_positions() {
    // the guard's first question beyond the first ball: the same validity as the exact
    // test, and a ball about the position asked that holds only valid positions, at every
    // scale (beyond the safe scale, no ball: the exact test's own scaling answers)
    let mut rng = SplitMix64::new(17);
    let (mut balls, mut held) = (0, 0);
    for round in 0..300 {
        let kind = [VolumeKind::Hex8, VolumeKind::Hex20, VolumeKind::Wedge6][round % 3];
        let scale = [1.0, 1e-3, 250.0, 1e-70, 1e70][round % 5];
        let p: Vec<DVec3> = perturbed(kind, &mut rng, 0.35, scale);
        let slot = round % 6;
        let (v, ball) = ValidBall::validity_and_ball(kind, &p, slot);
        assert_eq!(v, validity(kind, &p), "{kind:?} {p:?}");
        let Some(ball) = ball else { continue };
        assert_eq!(kind.linear(), VolumeKind::Hex8);
        assert_eq!(v, Validity::Valid, "a ball only about a valid position");
        assert_eq!(Some(ball), ValidBall::of(kind, &p, slot), "the ball `of` makes");
        balls += 1;
        for _ in 0..20 {
            let x = p[slot] + DVec3::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)) * rng.uniform(0.0, 0.5) * scale;
            if ball.holds(x) {
                let mut q = p.clone();
                q[slot] = x;
                assert_eq!(validity(kind, &q), Validity::Valid);
                held += 1;
            }
        }
    }
    assert!(balls > 20 && held > 100, "{balls} balls, {held} held");
}

/// Issue 61, finding 8: two hexahedra of smoothlab's own outputs had `det J < 0` in exact
/// arithmetic on the written doubles (−1.2e−17 and −4.0e−17 on a `det J` scale of 1), yet
/// counted as valid: their rounded Bernstein coefficients were all positive. A corner put
/// on the plane of its three neighbours in doubles lies on one side of it or the other
/// exactly; where the rounded corner determinant says "above" and the exact one "below",
/// the element is inverted, and so is the tetrahedron of that corner.
#[test]
fn validity_at_the_margin_is_the_exact_sign_of_the_doubles() {
    use crate::numeric::exact::orient3d;
    use std::cmp::Ordering;
    let mut rng = SplitMix64::new(61);
    let (mut rounded_wrong, mut checked) = (0, 0);
    for _ in 0..20_000 {
        let mut p = perturbed(VolumeKind::Hex8, &mut rng, 0.1, 1.0);
        // corner 0 into the plane of its neighbours 1, 3 and 4, in doubles
        let (s, t) = (rng.uniform(0.1, 0.4), rng.uniform(0.1, 0.4));
        p[0] = p[1] + (p[3] - p[1]) * s + (p[4] - p[1]) * t;
        let tet = corner_tet(VolumeKind::Hex8, &p, 0);
        let exact = orient3d(tet[0], tet[1], tet[2], tet[3]);
        let rounded = corner_det(&tet);
        checked += 1;
        if exact == Ordering::Greater {
            continue;
        }
        // inverted, or (its determinant exactly 0) not valid: never valid
        assert_ne!(validity(VolumeKind::Hex8, &p), Validity::Valid, "exact {exact:?}, rounded {rounded:e}");
        assert!(q3::is_inverted(&tet), "exact {exact:?}, rounded {rounded:e}");
        rounded_wrong += (rounded > 0.0) as usize;
    }
    // the case the issue found, many times over: rounding said valid
    assert!(rounded_wrong > 100, "{rounded_wrong} of {checked}");
}

/// The exact test agrees with the rounded one wherever the rounded one decides beyond
/// rounding, on random hexahedra and pyramids valid, folded and inverted inside.
#[test]
fn the_exact_bernstein_test_agrees_where_rounding_decides() {
    let mut rng = SplitMix64::new(8);
    let (mut valid, mut inverted) = (0, 0);
    for kind in [VolumeKind::Hex8, VolumeKind::Pyramid5] {
        for i in 0..1500 {
            let p = perturbed(kind, &mut rng, [0.2, 0.5, 0.8][i % 3], 1.0);
            let det = if kind == VolumeKind::Hex8 { super::bernstein::hex_det(&p) } else { super::bernstein::pyramid_det(&p) };
            let Some(rounded) = det.validity_beyond(det.min_coefficient(), super::bernstein::rounding_margin(&p)) else { continue };
            if rounded == Validity::Undecided {
                continue;
            }
            valid += (rounded == Validity::Valid) as usize;
            inverted += (rounded == Validity::Inverted) as usize;
            assert_eq!(super::bernstein::exact_validity(kind, &p, &p), rounded, "{kind:?} {p:?}");
        }
    }
    assert!(valid > 100 && inverted > 100, "{valid} valid, {inverted} inverted");
}

/// The wedge's exact test (issue 61): a corner of the top triangle put on the plane of the
/// bottom one's corner edges in doubles reads not valid wherever the exact determinant
/// there is not positive, whatever its rounding says; and it agrees with the rounded test
/// wherever that decides beyond rounding.
#[test]
fn a_wedge_is_decided_exactly_at_the_margin() {
    use crate::numeric::exact::orient3d;
    use std::cmp::Ordering;
    let mut rng = SplitMix64::new(13);
    let mut rounded_wrong = 0;
    for _ in 0..20_000 {
        let mut p = perturbed(VolumeKind::Wedge6, &mut rng, 0.1, 1.0);
        let (s, t) = (rng.uniform(0.1, 0.4), rng.uniform(0.1, 0.4));
        p[3] = p[0] + (p[1] - p[0]) * s + (p[2] - p[0]) * t;
        // det J at corner 0 is −((p₁ − p₀) × (p₂ − p₀))·(p₃ − p₀): the orientation of (p₀, p₂, p₁, p₃)
        let exact = orient3d(p[0], p[2], p[1], p[3]);
        if exact == Ordering::Greater {
            continue;
        }
        assert_ne!(validity(VolumeKind::Wedge6, &p), Validity::Valid, "exact {exact:?}");
        rounded_wrong += (-(p[1] - p[0]).cross(p[2] - p[0]).dot(p[3] - p[0]) > 0.0) as usize;
    }
    assert!(rounded_wrong > 100, "{rounded_wrong}");
    let (mut valid, mut inverted) = (0, 0);
    for i in 0..3000 {
        let p = perturbed(VolumeKind::Wedge6, &mut rng, [0.2, 0.5, 0.8][i % 3], 1.0);
        let v = validity(VolumeKind::Wedge6, &p);
        assert_eq!(super::wedge_validity_exact(&p, &p), v, "{p:?}");
        valid += (v == Validity::Valid) as usize;
        inverted += (v == Validity::Inverted) as usize;
    }
    assert!(valid > 100 && inverted > 100, "{valid} valid, {inverted} inverted");
}


/// A corner's dihedral angles from its three faces are the tetrahedron's first three
/// ([`q3::dihedral_angles`]), bit for bit, valid or inverted.
#[test]
fn corner_angles_are_the_tetrahedron_s_first_three() {
    let mut rng = crate::numeric::SplitMix64::new(9);
    for _ in 0..5000 {
        let t: [DVec3; 4] = std::array::from_fn(|_| DVec3::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)));
        let all = crate::quality::tet::dihedral_angles(&t);
        let corner = super::measures::corner_dihedral_deg(&t);
        for i in 0..3 {
            assert_eq!(corner[i].to_bits(), all[i].to_degrees().to_bits(), "{t:?}");
        }
    }
}
