//! The statistics the page shows after every pass, computed cheaply: the number of
//! inverted elements, the smallest and largest signed corner angle and the smallest
//! element quality — the same values as [`smoothlab::quality::mesh_stats`] (which the page
//! still uses, cached, for the angle histograms) without its per-corner `atan2`s,
//! condition numbers and histogram. Over element ranges, so a pass over a large mesh can
//! measure it in slices.

use std::ops::Range;

use glam::DVec2;

use smoothlab::mesh::{ElementKind, Mesh};
pub use smoothlab::quality::QuickStats;
use smoothlab::quality::{lo_alpha_corner, measure_element, signed_angle, TWO_SQRT3};
use smoothlab_render::bucket;


/// A pseudo-angle of the corner `(cross, dot) = (e1 × e2, e1 · e2)`: a value in [−2, 2]
/// that orders corners as `atan2(cross, dot)` does (signed zeros included), for the
/// price of one division. Only the extreme corners then need their `atan2`.
#[inline]
fn pseudo_angle(cross: f64, dot: f64) -> f64 {
    let s = cross.abs() + dot.abs();
    let p = if s > 0.0 {
        1.0 - dot / s
    } else if dot.is_sign_negative() {
        2.0 // atan2(±0, −0) = ±π
    } else {
        0.0
    };
    if cross.is_sign_negative() {
        -p
    } else {
        p
    }
}

/// Pseudo-angles closer than this may order two corners unlike their `atan2`s (both
/// round): such near-ties are settled by the `atan2`s themselves.
const TIE: f64 = 1e-12;

/// The corner with the extreme angle so far: its pseudo-angle, edge vectors and, once
/// a near-tie needed it, its `atan2`.
#[derive(Clone, Copy, Debug)]
struct Extreme {
    key: f64,
    corner: (DVec2, DVec2),
    angle: Option<f64>,
}

impl Extreme {
    fn angle(&mut self) -> f64 {
        let (e1, e2) = self.corner;
        *self.angle.get_or_insert_with(|| signed_angle(e1, e2))
    }
    /// Offers a corner; `below` is true to keep the smallest angle, false the largest.
    #[inline]
    fn offer(&mut self, key: f64, e1: DVec2, e2: DVec2, below: bool) {
        let (better, tie) = if below {
            (key < self.key - TIE, key <= self.key + TIE)
        } else {
            (key > self.key + TIE, key >= self.key - TIE)
        };
        if better || (tie && !self.key.is_finite()) {
            *self = Extreme { key, corner: (e1, e2), angle: None };
        } else if tie {
            let (old, new) = (self.angle(), signed_angle(e1, e2));
            if (below && new < old) || (!below && new > old) {
                *self = Extreme { key: if below { key.min(self.key) } else { key.max(self.key) }, corner: (e1, e2), angle: Some(new) };
            } else if below {
                self.key = self.key.min(key);
            } else {
                self.key = self.key.max(key);
            }
        }
    }
}

/// The bucket of an inverted element (the others hold [`bucket_of`]).
pub const INVERTED_BUCKET: u8 = 255;

/// What [`QuickAcc::add`] writes for a valid element of shape `q` (α or β, coloured over
/// [0, 1]): its colour bucket ([`smoothlab_render::bucket`]) plus one.
#[inline]
pub fn bucket_of(q: f64) -> u8 {
    bucket(q) as u8 + 1
}

/// [`QuickStats`] accumulated over element ranges, in any order.
///
/// Linear triangles (the large meshes) take a shortcut that keeps the values exact: a
/// corner can only be the smallest (largest) angle if its cotangent `dot / cross` is
/// near or above (below) the best one's, and an element can only hold the smallest α
/// if its α, compared by cross-multiplication, is near or below the best: those few
/// candidates alone are measured as `mesh_stats` measures them.
#[derive(Clone, Copy, Debug)]
pub struct QuickAcc {
    inverted: usize,
    min: Extreme,
    max: Extreme,
    /// Valid corners with `dot < cross × min_cot` cannot be the smallest angle, nor those
    /// with `dot > cross × max_cot` the largest (a margin wider than rounding included).
    min_cot: f64,
    max_cot: f64,
    min_quality: f64,
    /// Triangles with `2√3 cross > quality_bar × den` cannot hold the smallest α.
    quality_bar: f64,
    /// Elements measured so far.
    pub done: usize,
}

impl Default for QuickAcc {
    fn default() -> Self {
        QuickAcc {
            inverted: 0,
            min: Extreme { key: f64::INFINITY, corner: (DVec2::X, DVec2::Y), angle: None },
            max: Extreme { key: f64::NEG_INFINITY, corner: (DVec2::X, DVec2::Y), angle: None },
            min_cot: f64::NEG_INFINITY,
            max_cot: f64::INFINITY,
            quality_bar: f64::INFINITY,
            min_quality: f64::INFINITY,
            done: 0,
        }
    }
}

impl QuickAcc {
    /// Measures the elements `range` of `mesh`; with `buckets` (one per element of the
    /// mesh) also writes each element's colour bucket.
    pub fn add(&mut self, mesh: &Mesh, range: Range<usize>, mut buckets: Option<&mut [u8]>) {
        let n = range.len();
        for e in range {
            let kind = mesh.kind(e);
            let b = if kind == ElementKind::Tri3 {
                let ids = mesh.element(e);
                let [a, b, c] = [ids[0], ids[1], ids[2]].map(|i| mesh.nodes()[i as usize]);
                self.triangle(a, b, c)
            } else {
                self.element(kind, &mesh.element_points_array(e)[..kind.node_count()])
            };
            if let Some(out) = buckets.as_deref_mut() {
                out[e] = b;
            }
        }
        self.done += n;
    }

    /// Offers a corner to the smallest and largest angle, as `mesh_stats` orders them.
    #[inline]
    fn corner(&mut self, e1: DVec2, e2: DVec2, cross: f64, dot: f64) {
        let valid = cross > 0.0;
        if !valid || dot >= cross * self.min_cot {
            let key = pseudo_angle(cross, dot);
            if key <= self.min.key + TIE {
                self.min.offer(key, e1, e2, true);
                self.min_cot = cot_bar(self.min.key, true);
            }
        }
        if !valid || dot <= cross * self.max_cot {
            let key = pseudo_angle(cross, dot);
            if key >= self.max.key - TIE {
                self.max.offer(key, e1, e2, false);
                self.max_cot = cot_bar(self.max.key, false);
            }
        }
    }

    /// A linear triangle `abc` (corner edges as `corner_edges` makes them); its bucket.
    #[inline]
    fn triangle(&mut self, a: DVec2, b: DVec2, c: DVec2) -> u8 {
        let corners = [(b - a, c - a), (c - b, a - b), (a - c, b - c)];
        let mut bad = false;
        for &(e1, e2) in &corners {
            let cross = e1.perp_dot(e2);
            bad |= cross <= 0.0;
            self.corner(e1, e2, cross, e1.dot(e2));
        }
        self.inverted += bad as usize;
        // α at the first corner decides the bucket and whether the triangle is a candidate
        let (e1, e2) = corners[0];
        let den = e1.length_squared() + e2.length_squared() + (e2 - e1).length_squared();
        let num = TWO_SQRT3 * e1.perp_dot(e2);
        // not provably above the bar (NaN products included): a candidate
        let above = num.partial_cmp(&(self.quality_bar * den)) == Some(std::cmp::Ordering::Greater);
        if !above {
            let exact = corners.iter().map(|&(e1, e2)| lo_alpha_corner(e1, e2)).fold(f64::INFINITY, f64::min);
            if exact < self.min_quality {
                self.min_quality = exact;
                self.quality_bar = exact + exact.abs() * 1e-9 + 1e-300;
            }
        }
        if bad {
            INVERTED_BUCKET
        } else {
            bucket_of(lo_alpha_corner(e1, e2))
        }
    }

    /// Any element from its node coordinates (element order); its bucket.
    fn element(&mut self, kind: ElementKind, p: &[DVec2]) -> u8 {
        let q = measure_element::<false, false, false>(kind, p, |e1, e2, _| {
            self.corner(e1, e2, e1.perp_dot(e2), e1.dot(e2));
        });
        let (shape, bad) = (q.shape, q.inverted);
        if shape < self.min_quality {
            self.min_quality = shape;
            self.quality_bar = shape + shape.abs() * 1e-9 + 1e-300;
        }
        self.inverted += bad as usize;
        if bad {
            INVERTED_BUCKET
        } else {
            bucket_of(shape)
        }
    }

    /// The statistics of everything added.
    pub fn finish(&self) -> QuickStats {
        let angle = |mut x: Extreme, none: f64| if x.key.is_finite() { x.angle().to_degrees() } else { none };
        QuickStats {
            inverted: self.inverted,
            min_angle_deg: angle(self.min, f64::INFINITY),
            max_angle_deg: angle(self.max, f64::NEG_INFINITY),
            min_quality: self.min_quality,
        }
    }
}


/// The cotangent bar of [`QuickAcc`] for the best pseudo-angle `key`: valid corners
/// beyond it cannot be the extreme one. Keys at or below 0 (an inverted corner) leave no
/// valid corner a chance to be smaller; keys at π/2 and beyond map through `dot < 0`.
fn cot_bar(key: f64, below: bool) -> f64 {
    if !key.is_finite() {
        return if below { f64::NEG_INFINITY } else { f64::INFINITY };
    }
    if key <= 0.0 {
        // the best is an inverted (or flat) corner: no valid corner is smaller, and every
        // valid corner is larger
        return f64::INFINITY;
    }
    if key >= 2.0 {
        // an angle of π: any valid corner is smaller, none is larger
        return f64::NEG_INFINITY;
    }
    // key = 1 − dot/(cross + |dot|) for cross > 0, so cot = dot/cross = u/(1 − |u|), u = 1 − key
    let u = 1.0 - key;
    let cot = u / (1.0 - u.abs());
    // a generous margin: rounding of the key and of the products
    let margin = cot.abs() * 1e-6 + 1e-6;
    if below {
        cot - margin
    } else {
        cot + margin
    }
}

/// [`QuickStats`] of a whole mesh.
pub fn quick_stats(mesh: &Mesh) -> QuickStats {
    let mut acc = QuickAcc::default();
    acc.add(mesh, 0..mesh.element_count(), None);
    acc.finish()
}

/// [`QuickStats`] of a whole mesh and each element's colour bucket (see [`bucket_of`]).
pub fn quick_stats_and_buckets(mesh: &Mesh, buckets: &mut Vec<u8>) -> QuickStats {
    buckets.clear();
    buckets.resize(mesh.element_count(), 0);
    let mut acc = QuickAcc::default();
    acc.add(mesh, 0..mesh.element_count(), Some(buckets));
    acc.finish()
}

#[cfg(test)]
mod tests {
    use super::*;
    use smoothlab::generate::{grid, perturb, plate, rand2d, star, GridKind, PlateKind, StarKind};
    use smoothlab::quality::mesh_stats;

    fn same_as_mesh_stats(m: &Mesh) {
        let q = quick_stats(m);
        let s = mesh_stats(m);
        assert_eq!(q.inverted, s.inverted);
        assert_eq!(q.min_angle_deg, s.min_angle_deg);
        assert_eq!(q.max_angle_deg, s.max_angle_deg);
        assert_eq!(q.min_quality, s.min_quality);
    }

    #[test]
    fn equals_mesh_stats_on_every_kind_of_mesh() {
        for k in [PlateKind::Tri, PlateKind::Quad, PlateKind::Mixed] {
            let m = plate(k, 1, 5).unwrap();
            same_as_mesh_stats(&m);
            for seed in 1..6 {
                same_as_mesh_stats(&perturb(&m, 0.8, seed).unwrap());
            }
        }
        let quadratic = plate(PlateKind::Tri, 2, 5).unwrap();
        same_as_mesh_stats(&quadratic);
        same_as_mesh_stats(&perturb(&quadratic, 0.6, 3).unwrap());
        same_as_mesh_stats(&rand2d(3000, 30, 7).unwrap());
        same_as_mesh_stats(&perturb(&rand2d(3000, 30, 7).unwrap(), 1.2, 2).unwrap());
        for s in [StarKind::Regular, StarKind::Chen, StarKind::Quad] {
            same_as_mesh_stats(&star(s, s.default_k()).unwrap());
        }
        // structured meshes: every angle ties with many others
        for k in [GridKind::Tri, GridKind::Quad] {
            let g = grid(30, 20, k).unwrap();
            same_as_mesh_stats(&g);
            same_as_mesh_stats(&perturb(&g, 0.3, 5).unwrap());
        }
    }

    #[test]
    fn ranges_in_any_order_give_the_same_statistics() {
        let m = perturb(&rand2d(2000, 20, 3).unwrap(), 1.0, 9).unwrap();
        let whole = quick_stats(&m);
        let mut acc = QuickAcc::default();
        let n = m.element_count();
        for r in [n / 2..n, 0..7, 7..n / 2] {
            acc.add(&m, r, None);
        }
        assert_eq!(acc.done, n);
        assert_eq!(acc.finish(), whole);
    }

    #[test]
    fn pseudo_angle_orders_as_atan2_with_signed_zeros() {
        let cases = [
            (0.0, 1.0),
            (-0.0, 1.0),
            (0.0, -1.0),
            (-0.0, -1.0),
            (0.0, 0.0),
            (-0.0, -0.0),
            (1.0, 0.0),
            (-1.0, 0.0),
            (1e-300, -1.0),
            (-1e-300, -1.0),
            (3.0, 4.0),
            (3.0, -4.0),
            (-3.0, 4.0),
            (-3.0, -4.0),
            (1.0, 1e-17),
        ];
        for &(c1, d1) in &cases {
            for &(c2, d2) in &cases {
                let (a1, a2) = (f64::atan2(c1, d1), f64::atan2(c2, d2));
                let (p1, p2) = (pseudo_angle(c1, d1), pseudo_angle(c2, d2));
                assert_eq!(a1 < a2, p1 < p2, "({c1}, {d1}) vs ({c2}, {d2}): {a1} {a2} / {p1} {p2}");
            }
        }
    }
}
