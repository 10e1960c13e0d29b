//! The [`Target::Stretch`](super::Target::Stretch) field: each element's stretch as read,
//! averaged along the mesh's layers, so that a boundary layer's rows and a graded block's
//! stretch are kept while the noise of single nodes is not.
//!
//! - Each valid element's map from its ideal is fitted by least squares: `F`, `D×D`. Its
//!   stretch is the metric `M = F·Fᵀ` scaled to determinant 1: a target sets shape, not size.
//! - Each element's `log M` is averaged with its neighbours' across its facets. A neighbour
//!   weighs `(ℓ_min/ℓ)²`: `ℓ` the shared facet's length (a face's: the square root of its
//!   area), `ℓ_min` the element's shortest. Across a flat element's short facets lie the
//!   elements of its own layer; across its long ones the next layers, nearly unweighted.
//! - Those weights are then balanced (`centre_weights`) so that the neighbours' offsets
//!   cancel: a trend that is linear in space averages to the element's own value, and a
//!   wall's first row, with layers on one side only, is not pulled toward them.
//! - The target is the ideal mapped by `S̄·R`: `S̄ = exp(log M̄ / 2)` the averaged stretch,
//!   `R` the rotation that puts it closest to the element as read (Procrustes).
//! - A hexahedron's `R` is then laid onto the stretch's axes: the signed permutation of
//!   them nearest `R`. Else a thin cell sheared by its jitter gets a target sheared the
//!   same (`S̄·R` is a box only where `R` turns the cube's axes onto `S̄`'s), and the
//!   passes keep the shear. A cube is the same turned from one axis onto another, and
//!   the nearest such turn lays each corner's edges along the axes nearest them. A
//!   wedge's axis across its triangles is laid onto the nearest stretch axis by the
//!   least turn, the turn about it kept: its target is a right prism. Which axes, is the
//!   kind's ([`StretchAxes`]): a planar quadrilateral's as a hexahedron's. With node
//!   moves alone, a 2D layer's first row grew 8–12 % laid onto axes; the fit to the
//!   targets before the passes ([`crate::smooth::fit`]) keeps it within 5 %. Surfaces
//!   get no fit: a surface's quadrilateral keeps its turn.
//! - Whether a mesh is stretched on purpose is read from a broader average ([`BROAD_RINGS`]):
//!   noise averages out over it, a layer does not. Where no element's broad average is
//!   stretched beyond [`LEAST_STRETCH`], every target is the ideal, as with
//!   [`Target::Ideal`](super::Target::Ideal). Where one is, every element keeps its own
//!   averaged stretch, so that the layers in between agree with each other.
//! - An inverted or flat element has no stretch of its own: it takes the ideal.

#![allow(clippy::needless_range_loop)] // small matrices, written index by index as their formulas are

use crate::mesh::StretchAxes;

/// The aspect ratio (the stretch's largest over its smallest singular value) above which
/// an element's broad average ([`BROAD_RINGS`]) is a stretch made on purpose, not noise:
/// Freitag's random triangulations stay under 2.5, the plate's O-grid under 3.1, a
/// boundary layer's first rows lie between 10 and 40.
pub const LEAST_STRETCH: f64 = 4.0;

/// A `D×D` matrix, rows of columns: `m[i][j]` is row `i`, column `j`.
pub type Mat<const D: usize> = [[f64; D]; D];

/// One element as the field reads it.
pub struct StretchElement<'a, const D: usize> {
    /// Its corners' positions as read.
    pub corners: Vec<[f64; D]>,
    /// Its ideal's corners, in the same order.
    pub ideal: &'a [[f64; D]],
    /// Whether every corner is valid (none inverted or flat).
    pub valid: bool,
    /// Its neighbours across its facets, each with the shared facet's length.
    pub neighbours: Vec<(u32, f64)>,
    /// Which of its ideal's axes its target's turn lays onto its stretch's axes.
    pub axes: StretchAxes,
}

/// [`stretch_maps`], or `None` where every target is the ideal.
pub fn maps_if_stretched<const D: usize>(elements: &[StretchElement<'_, D>]) -> Option<Vec<Option<Mat<D>>>> {
    let maps = stretch_maps(elements);
    maps.iter().any(Option::is_some).then_some(maps)
}

/// Each element's target map, `exp(log M̄ / 2)·R` (see the module's text); `None` where
/// the target is the ideal.
pub fn stretch_maps<const D: usize>(elements: &[StretchElement<'_, D>]) -> Vec<Option<Mat<D>>> {
    // each valid element's log-metric and fitted map
    let fits: Vec<Option<(Mat<D>, Mat<D>)>> = elements.iter().map(fit).collect();
    // whether the mesh is stretched on purpose somewhere: then every element keeps its
    // own stretch, so that the layers between agree with each other
    let broad = broad_aspects(elements, &fits);
    if !broad.iter().any(|&a| a > LEAST_STRETCH) {
        return vec![None; elements.len()];
    }
    elements
        .iter()
        .enumerate()
        .map(|(e, el)| {
            // the neighbours with a stretch, their base weights and their offsets
            let shortest = el.neighbours.iter().map(|n| n.1).fold(f64::INFINITY, f64::min);
            let centre = centre_of(&el.corners);
            let mut near: Vec<(usize, f64, [f64; D])> = el
                .neighbours
                .iter()
                .filter(|&&(f, len)| fits[f as usize].is_some() && len > 0.0 && shortest.is_finite())
                .map(|&(f, len)| {
                    let c = centre_of(&elements[f as usize].corners);
                    (f as usize, (shortest / len).powi(2), std::array::from_fn(|i| c[i] - centre[i]))
                })
                .collect();
            centre_weights(&mut near);
            let mut sum = [[0.0; D]; D];
            let mut weight = 0.0;
            let own = fits[e].map(|f| (f.0, 1.0));
            let others = near.iter().map(|&(f, w, _)| (fits[f].expect("kept with a fit").0, w));
            for (log_m, w) in own.into_iter().chain(others) {
                if w > 0.0 && w.is_finite() {
                    add_scaled(&mut sum, &log_m, w);
                    weight += w;
                }
            }
            if weight <= 0.0 {
                return None;
            }
            scale(&mut sum, 1.0 / weight);
            let (values, vectors) = symmetric_eigen(sum);
            let stretch = from_eigen(&vectors, |i| (values[i] / 2.0).exp());
            // the turn that puts the stretched ideal closest to the element as read
            // (Procrustes: the ideal's second moments are isotropic): the polar rotation of
            // S̄·F, in which a long edge's tilt counts and a short one's noise hardly does
            let f = fits[e]?.1;
            let turn = polar_rotation(&mul(&stretch, &f))?;
            let turn = match el.axes {
                StretchAxes::Kept => turn,
                StretchAxes::Every => onto_axes(&vectors, &turn),
                StretchAxes::One(axis) => one_onto_axes(&vectors, &turn, axis),
            };
            Some(mul(&stretch, &turn))
        })
        .collect()
}

/// The mean of points.
fn centre_of<const D: usize>(points: &[[f64; D]]) -> [f64; D] {
    let n = points.len() as f64;
    std::array::from_fn(|i| points.iter().map(|p| p[i]).sum::<f64>() / n)
}

/// Moves the neighbours' weights `(·, b, d)` (base weight `b`, offset `d` from the
/// element's centre) as little as they can go (in `Σ(w − b)²/b`) to weights `w ≥ 0` whose
/// offsets balance, `Σ w·d = 0`: a trend that is linear in space then averages to the
/// element's own value, so a wall's first row is not averaged with the rows above alone.
/// `w = b·(1 − d·λ)` with `(Σ b·d·dᵀ)·λ = Σ b·d`; a neighbour whose weight would turn
/// negative is dropped and the rest solved again.
fn centre_weights<const D: usize>(near: &mut [(usize, f64, [f64; D])]) {
    let base: Vec<f64> = near.iter().map(|n| n.1).collect();
    let mut kept: Vec<bool> = vec![true; near.len()];
    for _ in 0..=near.len() {
        let (mut m, mut r) = ([[0.0; D]; D], [0.0; D]);
        for ((_, _, d), (&b, _)) in near.iter().zip(base.iter().zip(&kept)).filter(|(_, (_, &k))| k) {
            for i in 0..D {
                r[i] += b * d[i];
                for j in 0..D {
                    m[i][j] += b * d[i] * d[j];
                }
            }
        }
        // λ = m⁻¹·r, over the directions m spans (a pseudo-inverse)
        let (values, vectors) = symmetric_eigen(m);
        let top = values.iter().cloned().fold(0.0, f64::max);
        let inverse = from_eigen(&vectors, |i| if values[i] > 1e-9 * top { 1.0 / values[i] } else { 0.0 });
        let lambda: [f64; D] = std::array::from_fn(|i| (0..D).map(|j| inverse[i][j] * r[j]).sum());
        let mut dropped = false;
        for ((n, &b), k) in near.iter_mut().zip(&base).zip(kept.iter_mut()) {
            if !*k {
                n.1 = 0.0;
                continue;
            }
            let w = b * (1.0 - (0..D).map(|i| n.2[i] * lambda[i]).sum::<f64>());
            if w < 0.0 {
                *k = false;
                dropped = true;
            }
            n.1 = w.max(0.0);
        }
        if !dropped {
            return;
        }
    }
}

/// How many facets away the elements lie whose stretch tells design from noise.
pub const BROAD_RINGS: usize = 3;

/// Each element's aspect ratio of the plain mean of `log M` over the elements within
/// [`BROAD_RINGS`] facets of it: noise averages out over those ~40 elements, a stretch
/// made on purpose does not.
fn broad_aspects<const D: usize>(elements: &[StretchElement<'_, D>], fits: &[Option<(Mat<D>, Mat<D>)>]) -> Vec<f64> {
    let mut mark = vec![u32::MAX; elements.len()];
    let mut ring: Vec<u32> = Vec::new();
    let mut next: Vec<u32> = Vec::new();
    (0..elements.len())
        .map(|e| {
            let mut sum = [[0.0; D]; D];
            let mut count = 0.0;
            ring.clear();
            ring.push(e as u32);
            mark[e] = e as u32;
            for depth in 0..=BROAD_RINGS {
                next.clear();
                for &f in &ring {
                    if let Some(fit) = &fits[f as usize] {
                        add_scaled(&mut sum, &fit.0, 1.0);
                        count += 1.0;
                    }
                    if depth < BROAD_RINGS {
                        for &(g, _) in &elements[f as usize].neighbours {
                            if mark[g as usize] != e as u32 {
                                mark[g as usize] = e as u32;
                                next.push(g);
                            }
                        }
                    }
                }
                std::mem::swap(&mut ring, &mut next);
            }
            if count == 0.0 {
                return 1.0;
            }
            scale(&mut sum, 1.0 / count);
            aspect_of(&sum)
        })
        .collect()
}

/// The aspect ratio of a metric given by its logarithm: the largest singular value of its
/// square root over the smallest (`log M`'s eigenvalues are `2·ln σᵢ`).
fn aspect_of<const D: usize>(log_m: &Mat<D>) -> f64 {
    let (values, _) = symmetric_eigen(*log_m);
    let spread = values.iter().cloned().fold(f64::NEG_INFINITY, f64::max) - values.iter().cloned().fold(f64::INFINITY, f64::min);
    (spread / 2.0).exp()
}

/// The element's `log M` and its fitted map `F` (module text); `None` for an invalid or
/// degenerate element.
fn fit<const D: usize>(el: &StretchElement<'_, D>) -> Option<(Mat<D>, Mat<D>)> {
    if !el.valid || el.corners.len() != el.ideal.len() {
        return None;
    }
    let n = el.corners.len() as f64;
    let centre = |ps: &mut dyn Iterator<Item = [f64; D]>| {
        let mut c = [0.0; D];
        for p in ps {
            for i in 0..D {
                c[i] += p[i] / n;
            }
        }
        c
    };
    let cx = centre(&mut el.corners.iter().copied());
    let cxi = centre(&mut el.ideal.iter().copied());
    // F = P·Q⁻¹ with P = Σ x̃·ξ̃ᵀ, Q = Σ ξ̃·ξ̃ᵀ
    let (mut p, mut q) = ([[0.0; D]; D], [[0.0; D]; D]);
    for (x, xi) in el.corners.iter().zip(el.ideal) {
        for i in 0..D {
            for j in 0..D {
                p[i][j] += (x[i] - cx[i]) * (xi[j] - cxi[j]);
                q[i][j] += (xi[i] - cxi[i]) * (xi[j] - cxi[j]);
            }
        }
    }
    let (qv, qe) = symmetric_eigen(q);
    if qv.iter().any(|&v| v.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater)) {
        return None;
    }
    let f = mul(&p, &from_eigen(&qe, |i| 1.0 / qv[i]));
    // M = F·Fᵀ, its logarithm scaled to determinant 1 (trace 0)
    let (mv, me) = symmetric_eigen(mul(&f, &transpose(&f)));
    if mv.iter().any(|&v| !(v > 0.0 && v.is_finite())) || determinant(&f) <= 0.0 {
        return None;
    }
    let mean_log = mv.iter().map(|v| v.ln()).sum::<f64>() / D as f64;
    let log_m = from_eigen(&me, |i| mv[i].ln() - mean_log);
    Some((log_m, f))
}

/// The turn `Q·P` nearest `turn` (largest `tr(turnᵀ·Q·P)`), with `Q` the stretch's axes
/// (columns) and `P` a signed permutation: the ideal's axes laid along the stretch's.
fn onto_axes<const D: usize>(q: &Mat<D>, turn: &Mat<D>) -> Mat<D> {
    let mut best = (f64::NEG_INFINITY, *turn);
    // every map of the axes onto the axes, the permutations among them, with every sign
    for code in 0..D.pow(D as u32) {
        let perm: [usize; D] = std::array::from_fn(|i| code / D.pow(i as u32) % D);
        if (0..D).any(|i| perm[..i].contains(&perm[i])) {
            continue;
        }
        for signs in 0..1 << D {
            let mut p = [[0.0; D]; D];
            for i in 0..D {
                p[perm[i]][i] = if signs >> i & 1 == 1 { -1.0 } else { 1.0 };
            }
            let r = mul(q, &p);
            if determinant(&r) <= 0.0 {
                continue;
            }
            let agreement: f64 = (0..D).flat_map(|i| (0..D).map(move |j| r[i][j] * turn[i][j])).sum();
            if agreement > best.0 {
                best = (agreement, r);
            }
        }
    }
    best.1
}

/// `turn` turned least so that it takes the ideal's axis `axis` onto the nearest of the
/// stretch's axes `q` (columns): the turn about that axis kept. Solids only.
fn one_onto_axes<const D: usize>(q: &Mat<D>, turn: &Mat<D>, axis: usize) -> Mat<D> {
    assert_eq!(D, 3, "only a solid lays one axis");
    let column = |m: &Mat<D>, j: usize| -> [f64; 3] { std::array::from_fn(|i| m[i][j]) };
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let u = column(turn, axis);
    let nearest = (0..D).max_by(|&i, &j| dot(u, column(q, i)).abs().total_cmp(&dot(u, column(q, j)).abs())).unwrap_or(0);
    let v = column(q, nearest);
    let v = if dot(u, v) < 0.0 { v.map(|c| -c) } else { v };
    // Rodrigues: the turn about u × v by the angle between them
    let k = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
    let (sin, cos) = (dot(k, k).sqrt(), dot(u, v));
    if sin == 0.0 {
        return *turn;
    }
    let k = k.map(|c| c / sin);
    let cross = [[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]];
    let a: Mat<D> = std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let delta = if i == j { 1.0 } else { 0.0 };
            cos * delta + sin * cross[i][j] + (1.0 - cos) * k[i] * k[j]
        })
    });
    mul(&a, turn)
}

/// `R = G·(GᵀG)^{-1/2}`, the rotation of the polar decomposition of `G` (`det G > 0`).
fn polar_rotation<const D: usize>(g: &Mat<D>) -> Option<Mat<D>> {
    let (v, e) = symmetric_eigen(mul(&transpose(g), g));
    if determinant(g) <= 0.0 || v.iter().any(|&x| !(x > 0.0 && x.is_finite())) {
        return None;
    }
    Some(mul(g, &from_eigen(&e, |i| 1.0 / v[i].sqrt())))
}

fn identity<const D: usize>() -> Mat<D> {
    let mut m = [[0.0; D]; D];
    for (i, row) in m.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    m
}

fn transpose<const D: usize>(a: &Mat<D>) -> Mat<D> {
    let mut t = [[0.0; D]; D];
    for i in 0..D {
        for j in 0..D {
            t[i][j] = a[j][i];
        }
    }
    t
}

fn mul<const D: usize>(a: &Mat<D>, b: &Mat<D>) -> Mat<D> {
    let mut c = [[0.0; D]; D];
    for i in 0..D {
        for j in 0..D {
            c[i][j] = (0..D).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    c
}

fn add_scaled<const D: usize>(a: &mut Mat<D>, b: &Mat<D>, w: f64) {
    for i in 0..D {
        for j in 0..D {
            a[i][j] += w * b[i][j];
        }
    }
}

fn scale<const D: usize>(a: &mut Mat<D>, w: f64) {
    a.iter_mut().flatten().for_each(|x| *x *= w);
}

fn determinant<const D: usize>(a: &Mat<D>) -> f64 {
    match D {
        2 => a[0][0] * a[1][1] - a[0][1] * a[1][0],
        3 => {
            a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
                + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])
        }
        _ => unreachable!("a corner matrix is 2×2 or 3×3"),
    }
}

/// `V·diag(f(i))·Vᵀ` for the eigenvectors `V` (columns).
fn from_eigen<const D: usize>(v: &Mat<D>, f: impl Fn(usize) -> f64) -> Mat<D> {
    let mut m = [[0.0; D]; D];
    for k in 0..D {
        let s = f(k);
        for i in 0..D {
            for j in 0..D {
                m[i][j] += v[i][k] * s * v[j][k];
            }
        }
    }
    m
}

/// The eigenvalues and eigenvectors (columns) of a symmetric matrix, by Jacobi rotations
/// (Golub & Van Loan, §8.5): exact to rounding for the 2×2 and 3×3 matrices here.
fn symmetric_eigen<const D: usize>(mut a: Mat<D>) -> ([f64; D], Mat<D>) {
    let mut v = identity::<D>();
    for _sweep in 0..32 {
        let off: f64 = (0..D).flat_map(|i| (0..D).filter(move |&j| j != i).map(move |j| (i, j))).map(|(i, j)| a[i][j] * a[i][j]).sum();
        let diag: f64 = (0..D).map(|i| a[i][i] * a[i][i]).sum();
        if off <= 1e-30 * diag || off == 0.0 {
            break;
        }
        for p in 0..D {
            for q in p + 1..D {
                if a[p][q] == 0.0 {
                    continue;
                }
                let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let t = if theta == 0.0 { 1.0 } else { t };
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for k in 0..D {
                    let (akp, akq) = (a[k][p], a[k][q]);
                    a[k][p] = c * akp - s * akq;
                    a[k][q] = s * akp + c * akq;
                }
                for k in 0..D {
                    let (apk, aqk) = (a[p][k], a[q][k]);
                    a[p][k] = c * apk - s * aqk;
                    a[q][k] = s * apk + c * aqk;
                }
                for k in 0..D {
                    let (vkp, vkq) = (v[k][p], v[k][q]);
                    v[k][p] = c * vkp - s * vkq;
                    v[k][q] = s * vkp + c * vkq;
                }
            }
        }
    }
    let mut values = [0.0; D];
    for (i, x) in values.iter_mut().enumerate() {
        *x = a[i][i];
    }
    (values, v)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close<const D: usize>(a: &Mat<D>, b: &Mat<D>, tol: f64) -> bool {
        (0..D).all(|i| (0..D).all(|j| (a[i][j] - b[i][j]).abs() < tol))
    }

    #[test]
    fn eigen_decomposes_symmetric_matrices() {
        let a = [[4.0, 1.0, 0.5], [1.0, 3.0, -0.2], [0.5, -0.2, 1.0]];
        let (values, v) = symmetric_eigen(a);
        assert!(close(&from_eigen(&v, |i| values[i]), &a, 1e-12));
        assert!(close(&mul(&transpose(&v), &v), &identity(), 1e-12));
        let b = [[2.0, 0.0], [0.0, 5.0]];
        let (values, v) = symmetric_eigen(b);
        // a diagonal matrix is its own decomposition, exactly
        assert_eq!(from_eigen(&v, |i| values[i]), b);
    }

    const SQUARE: [[f64; 2]; 4] = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];

    fn cell(x: f64, y: f64, w: f64, h: f64) -> Vec<[f64; 2]> {
        vec![[x, y], [x + w, y], [x + w, y + h], [x, y + h]]
    }

    #[test]
    fn a_layer_keeps_its_stretch_and_its_rows() {
        // three rows of stretched cells, each row 1.2 times the one below: a cell's target
        // is its row's stretch, turned as it lies, whatever the rows above
        let (w, h0) = (1.0, 0.05);
        let mut elements = Vec::new();
        let mut heights = Vec::new();
        let mut y = 0.0;
        for row in 0..3 {
            let h = h0 * 1.2f64.powi(row);
            for col in 0..4 {
                let e = elements.len() as u32;
                let mut neighbours = Vec::new();
                if col > 0 {
                    neighbours.push((e - 1, h));
                }
                if col < 3 {
                    neighbours.push((e + 1, h));
                }
                if row > 0 {
                    neighbours.push((e - 4, w));
                }
                if row < 2 {
                    neighbours.push((e + 4, w));
                }
                elements.push(StretchElement { corners: cell(col as f64 * w, y, w, h), ideal: &SQUARE, valid: true, neighbours, axes: StretchAxes::Kept });
                heights.push(h);
            }
            y += h;
        }
        let maps = stretch_maps(&elements);
        for (map, h) in maps.iter().zip(&heights) {
            let m = map.expect("stretched on purpose");
            // the map's aspect ratio is the row's own to within its neighbours' weight
            let aspect = m[0][0] / m[1][1];
            let own = w / h;
            assert!(m[0][1].abs() < 1e-12 && m[1][0].abs() < 1e-12, "{m:?}");
            assert!((aspect / own - 1.0).abs() < 0.01, "{aspect} against {own}");
        }
        // a square cell is its own ideal: no target
        let square = StretchElement { corners: cell(0.0, 0.0, 1.0, 1.0), ideal: &SQUARE, valid: true, neighbours: vec![], axes: StretchAxes::Kept };
        assert!(stretch_maps(&[square])[0].is_none());
    }

    #[test]
    fn a_turned_cell_is_turned_back() {
        // a 5:1 cell turned by 30°: its map is the stretch times the turn
        let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
        let corners: Vec<[f64; 2]> =
            cell(0.0, 0.0, 5.0, 1.0).iter().map(|p| [c * p[0] - s * p[1], s * p[0] + c * p[1]]).collect();
        let el = StretchElement { corners, ideal: &SQUARE, valid: true, neighbours: vec![], axes: StretchAxes::Kept };
        let m = stretch_maps(&[el])[0].unwrap();
        let scale = 1.0 / 5f64.sqrt();
        let expected = mul(&[[c, -s], [s, c]], &[[5.0 * scale, 0.0], [0.0, scale]]);
        assert!(close(&m, &expected, 1e-12), "{m:?}");
    }

    /// The turn by `deg` about axis `axis` (0, 1, 2: x, y, z).
    fn turn(axis: usize, deg: f64) -> Mat<3> {
        let (c, s) = (deg.to_radians().cos(), deg.to_radians().sin());
        let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
        let mut r = identity::<3>();
        (r[i][i], r[i][j], r[j][i], r[j][j]) = (c, -s, s, c);
        r
    }

    #[test]
    fn a_cube_s_turn_goes_onto_the_nearest_axes() {
        // the stretch's axes: x, y, z; a turn of 10° then 30° about z: the axes, unturned
        let t = mul(&turn(0, 10.0), &turn(2, 30.0));
        assert_eq!(onto_axes(&identity(), &t), identity());
        // 60° about z is nearer the quarter turn
        assert!(close(&onto_axes(&identity(), &turn(2, 60.0)), &turn(2, 90.0), 1e-15));
        // the stretch's axes turned by 20° about y: the turn goes onto them
        let q = turn(1, 20.0);
        assert!(close(&onto_axes(&q, &mul(&q, &turn(0, 5.0))), &q, 1e-15));
    }

    #[test]
    fn a_wedge_s_axis_goes_onto_the_nearest_axis_its_turn_about_it_kept() {
        // tilted 10° about x after a twist of 30° about z: the tilt undone, the twist kept
        let t = mul(&turn(0, 10.0), &turn(2, 30.0));
        assert!(close(&one_onto_axes(&identity(), &t, 2), &turn(2, 30.0), 1e-15));
        // an axis nearer y goes onto y
        let t = turn(0, -80.0);
        let r = one_onto_axes(&identity(), &t, 2);
        assert!(close(&r, &turn(0, -90.0), 1e-15), "{r:?}");
    }
}
