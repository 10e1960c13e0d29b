//! The reference surface of a tangled surface mesh, fitted through its nodes: a tangle
//! folds the elements, not the nodes, which still lie on the surface the mesh stands for.
//! Each node carries a quadric height field fitted through it and its neighbours, and a
//! point is projected onto the weighted blend of the fits of the nodes near it (a moving
//! least-squares surface, `docs/formulas.md` §7).

use glam::DVec3;

use super::grid::Grid;
use super::Projected;
use crate::mesh::{Mesh, NodeRole, Plane, NONE};
use crate::numeric::order::{sort_stable_by_key, stable_order, total_order_key};

/// The fewest neighbours a node's fit is made of: its ring of elements' nodes, topped up
/// with the nearest nodes of the next ring (a linear triangle's six neighbours alone would
/// leave one point over the quadric's five coefficients).
const MIN_FIT_POINTS: usize = 12;

/// Steps of a projection's foot from fit to fit before the blend ([`Fitted::project`]).
const MAX_SETTLE: usize = 8;

/// Gauss–Newton steps of the nearest point on one fit.
const FIT_ITERATIONS: usize = 3;

/// The steepest slope (`|∇h|` at the node, in the fit's frame) and the largest second-order
/// coefficient a fit may have, in the fit's units (its reach): a smooth surface sampled by
/// its nodes turns less than this over a node's neighbourhood in the frame of its spread,
/// and a quadric steeper or more curved was fitted to points nearly in a line (it passes
/// through them and anywhere beyond). Such a frame takes its plane fit, or none.
const MAX_SLOPE: f64 = 2.0;
const MAX_CURVATURE: f64 = 2.0;

/// How far from its node a fit is used, in units of its reach (the farthest of the
/// points it was fitted to): a quadric is a good surface near the points it was fitted
/// to and nothing beyond, so a nearest point farther out is pulled back to this circle
/// about the node in the fit's plane (a tangled node's request may land anywhere).
const FIT_REACH: f64 = 1.5;

/// One node's quadric on one smooth part: in the frame `origin + s·(x·u + y·w + z·n)`
/// (`s` the reach of its neighbours, so the coefficients are of unit scale) the surface is
/// `z = h(x, y) = q₀x + q₁y + q₂x² + q₃xy + q₄y²`, through the node.
#[derive(Clone, Debug)]
struct Fit {
    plane: Plane,
    normal: DVec3,
    scale: f64,
    q: [f64; 5],
    part: u32,
    /// The mean distance to its ring's nodes: with the nearest fit's distance, the reach
    /// of the blend.
    spacing: f64,
}

impl Fit {
    fn height(&self, x: f64, y: f64) -> (f64, f64, f64) {
        let q = &self.q;
        (
            q[0] * x + q[1] * y + q[2] * x * x + q[3] * x * y + q[4] * y * y,
            q[0] + 2.0 * q[2] * x + q[3] * y,
            q[1] + q[3] * x + 2.0 * q[4] * y,
        )
    }

    /// The nearest point of the quadric to `p` (Gauss–Newton from straight below `p`),
    /// within [`FIT_REACH`] of its node, and the quadric's unit normal there.
    fn nearest(&self, p: DVec3) -> (DVec3, DVec3) {
        let d = (p - self.plane.origin) / self.scale;
        let (px, py, pz) = (d.dot(self.plane.u), d.dot(self.plane.w), d.dot(self.normal));
        let within = |x: f64, y: f64| -> (f64, f64) {
            let r = (x * x + y * y).sqrt();
            match r > FIT_REACH {
                true if r.is_finite() => (x * FIT_REACH / r, y * FIT_REACH / r),
                true => (0.0, 0.0),
                false if r.is_nan() => (0.0, 0.0),
                false => (x, y),
            }
        };
        let (mut x, mut y) = within(px, py);
        for _ in 0..FIT_ITERATIONS {
            let (h, hx, hy) = self.height(x, y);
            // residual r = S(x, y) − p, J = [(1, 0, hx), (0, 1, hy)]
            let r = [x - px, y - py, h - pz];
            let (a, b, c) = (1.0 + hx * hx, hx * hy, 1.0 + hy * hy);
            let (g0, g1) = (r[0] + hx * r[2], r[1] + hy * r[2]);
            let det = a * c - b * b;
            if !(det.is_finite() && det > 0.0) {
                break;
            }
            (x, y) = within(x - (c * g0 - b * g1) / det, y - (a * g1 - b * g0) / det);
        }
        let (h, hx, hy) = self.height(x, y);
        let h = h.clamp(-FIT_REACH, FIT_REACH);
        let point = self.plane.origin
            + self.scale * (x * self.plane.u + y * self.plane.w + h * self.normal);
        let normal = crate::numeric::direction(self.normal - hx * self.plane.u - hy * self.plane.w);
        (point, normal)
    }
}

/// How many times the distance to the nearest other node in space a fit's spacing may be
/// ([`Fitted::new`]).
const SPACING_CAP: f64 = 4.0;

/// The surface fitted through a tangled mesh's nodes (see the module docs).
#[derive(Clone, Debug)]
pub struct Fitted {
    fits: Vec<Fit>,
    /// Node → its fits, one per smooth part it lies on (CSR: node `n`'s are
    /// `node_start[n]..node_start[n + 1]`, numbered node by node).
    node_start: Vec<u32>,
    /// Per element, the fit of its first corner on its part.
    element_fit: Vec<u32>,
    grid: Grid,
}

impl Fitted {
    /// The fits of `mesh`'s nodes at `points`, each element on the smooth part `part(e)`.
    pub fn new(points: &[DVec3], mesh: &Mesh, part: impl Fn(usize) -> u32) -> Fitted {
        let nn = points.len();
        // per node, its parts (sorted) and so its fits
        let mut node_parts: Vec<Vec<u32>> = vec![Vec::new(); nn];
        for (n, parts) in node_parts.iter_mut().enumerate() {
            if mesh.role(n) == NodeRole::Unused {
                continue;
            }
            parts.extend(mesh.node_elements(n).iter().map(|&e| part(e as usize)));
            parts.sort_unstable();
            parts.dedup();
        }
        let mut node_start = vec![0u32; nn + 1];
        for n in 0..nn {
            node_start[n + 1] = node_start[n] + node_parts[n].len() as u32;
        }
        let fit_of = |n: usize, k: u32| -> u32 {
            let i = node_parts[n]
                .iter()
                .position(|&x| x == k)
                .expect("a node's part");
            node_start[n] + i as u32
        };
        // the ring of node n on part k: the nodes of its elements on k
        let ring_of = |n: usize, k: u32, out: &mut Vec<u32>| {
            out.clear();
            for &e in mesh.node_elements(n) {
                if part(e as usize) == k {
                    out.extend(
                        mesh.element(e as usize)
                            .iter()
                            .copied()
                            .filter(|&m| m as usize != n),
                    );
                }
            }
            out.sort_unstable();
            out.dedup();
        };
        let (mut fits, mut ring_start, mut ring) = (Vec::new(), vec![0u32], Vec::new());
        let (mut one, mut two, mut more) = (Vec::new(), Vec::new(), Vec::new());
        for n in 0..nn {
            for &k in &node_parts[n] {
                ring_of(n, k, &mut one);
                ring.extend(one.iter().map(|&m| fit_of(m as usize, k)));
                ring_start.push(ring.len() as u32);
                let mut near: Vec<u32> = one.clone();
                if near.len() < MIN_FIT_POINTS {
                    two.clear();
                    for &m in &one {
                        ring_of(m as usize, k, &mut more);
                        two.extend(
                            more.iter()
                                .copied()
                                .filter(|&x| x as usize != n && !one.contains(&x)),
                        );
                    }
                    two.sort_unstable();
                    two.dedup();
                    let d = |m: u32| (points[m as usize] - points[n]).length();
                    sort_stable_by_key(&mut two, |&m| total_order_key(d(m))); // ties ascending, as they are
                    near.extend(two.iter().take(MIN_FIT_POINTS - near.len()));
                }
                let spacing = if one.is_empty() {
                    0.0
                } else {
                    one.iter()
                        .map(|&m| (points[m as usize] - points[n]).length())
                        .sum::<f64>()
                        / one.len() as f64
                };
                fits.push(fit(
                    points[n],
                    near.iter().map(|&m| points[m as usize]),
                    k,
                    spacing,
                ));
            }
        }
        orient_fits(&mut fits, &ring_start, &ring, points, mesh, &part, fit_of);
        let element_fit = (0..mesh.element_count())
            .map(|e| fit_of(mesh.element(e)[0] as usize, part(e)))
            .collect();
        let origins: Vec<DVec3> = fits.iter().map(|f| f.plane.origin).collect();
        let dots: Vec<[u32; 3]> = (0..origins.len() as u32).map(|i| [i; 3]).collect();
        let grid = Grid::new(&origins, &dots);
        // a ring's spacing is the mesh's, which a tangle stretches across the surface: the
        // blend's reach is held to a few times the nearest other node's distance in space
        // (issue 61: a shuffled sphere's rings span it, and every projection blended every
        // fit, a cost quadratic in the mesh)
        for fit in &mut fits {
            let o = fit.plane.origin;
            let nearest = grid.nearest(o, |g| {
                (origins[g as usize] != o).then_some(origins[g as usize])
            });
            if let Some(&q) = origins.get(nearest as usize) {
                let cap = SPACING_CAP * (q - o).length();
                if cap > 0.0 && fit.spacing > cap {
                    fit.spacing = cap;
                }
            }
        }
        Fitted {
            fits,
            node_start,
            element_fit,
            grid,
        }
    }

    /// A node's first fit (its hint before it has moved); [`NONE`] for an unused node.
    pub fn fit_at_node(&self, n: usize) -> u32 {
        match (self.node_start.get(n), self.node_start.get(n + 1)) {
            (Some(&a), Some(&b)) if a < b => a,
            _ => NONE,
        }
    }

    /// Element `e`'s hint: its first corner's fit on its part.
    pub fn element_fit(&self, e: usize) -> Option<u32> {
        self.element_fit.get(e).copied()
    }

    pub fn fit_count(&self) -> usize {
        self.fits.len()
    }

    fn distance(&self, f: u32, p: DVec3) -> f64 {
        (self.fits[f as usize].plane.origin - p).length()
    }

    /// The nearest point of the blended fits to `p`, on the part of fit `hint` (anywhere
    /// for [`NONE`]): the foot of `p` on the fit whose node is nearest (moved on to the fit
    /// whose node is nearest the foot, while that changes), then at that foot (on the
    /// surface, near its nodes) the fits within reach blended by their distances.
    /// Blending at `p` itself would average feet far apart when `p` is far off the surface
    /// (a max-min step through a fold): their mean lies inside a curved surface, and
    /// projecting it again would move it. Every search is by position (the grid): a
    /// tangled file's neighbours in the mesh are not neighbours in space.
    pub fn project(&self, p: DVec3, hint: u32) -> Projected {
        if self.fits.is_empty() {
            return Projected {
                point: p,
                normal: DVec3::Z,
                face: NONE,
            };
        }
        let part = self.fits.get(hint as usize).map(|f| f.part);
        let mut cur = self.nearest_fit(p, part);
        let (mut foot, _) = self.fits[cur as usize].nearest(p);
        // a foot far from its fit's node (clamped at its reach, where the quadric is
        // extrapolated) settles on the fit whose node is nearest it
        for _ in 0..MAX_SETTLE {
            let next = self.nearest_fit(foot, part);
            if next == cur {
                break;
            }
            cur = next;
            foot = self.fits[cur as usize].nearest(foot).0;
        }
        self.blend(foot, cur)
    }

    /// The fit on `part` (on any part for `None`) whose node is nearest `p`.
    fn nearest_fit(&self, p: DVec3, part: Option<u32>) -> u32 {
        self.grid.nearest(p, |f| {
            let fit = &self.fits[f as usize];
            (part.is_none() || part == Some(fit.part)).then_some(fit.plane.origin)
        })
    }

    /// The fits on the part of fit `cur` (whose node is the nearest to `x`) within reach
    /// of `x` blended there: each fit's nearest point and normal, weighted by its distance.
    fn blend(&self, x: DVec3, cur: u32) -> Projected {
        let part = self.fits[cur as usize].part;
        let reach = self.distance(cur, x) + self.fits[cur as usize].spacing;
        let (mut sum, mut normal, mut total) = (DVec3::ZERO, DVec3::ZERO, 0.0);
        let mut at_node = None;
        self.grid.near(x, reach, |f| {
            let fit = &self.fits[f as usize];
            let d = self.distance(f, x);
            if fit.part != part || d >= reach || d.is_nan() {
                return;
            }
            if d == 0.0 {
                // at a node, its own fit alone: the fitted surface passes through the nodes
                at_node = Some(f);
                return;
            }
            // Shepard's factor 1/d² makes the blend interpolate the nodes; (1 − t²)² ends
            // each fit's say smoothly at the reach
            let t = d / reach;
            let w = (1.0 - t * t) * (1.0 - t * t) / (t * t);
            let (q, n) = fit.nearest(x);
            sum += w * q;
            normal += w * n;
            total += w;
        });
        let (point, normal) = (sum / total, crate::numeric::direction(normal));
        let alone = at_node.unwrap_or(cur);
        if at_node.is_some() || !(total > 0.0 && point.is_finite() && normal != DVec3::ZERO) {
            let (point, normal) = self.fits[alone as usize].nearest(x);
            return Projected {
                point,
                normal,
                face: alone,
            };
        }
        Projected {
            point,
            normal,
            face: cur,
        }
    }
}

/// The quadric through `origin` fitted to `near` by least squares in the frame of the
/// points' plane of least spread (their covariance's smallest eigenvector), of unit
/// scale. Too few points or points in a line: the plane's linear terms alone, else flat.
fn fit(origin: DVec3, near: impl Iterator<Item = DVec3> + Clone, part: u32, spacing: f64) -> Fit {
    let scale = near
        .clone()
        .map(|q| (q - origin).length())
        .fold(0.0, f64::max);
    let flat = |normal: DVec3| Fit {
        plane: Plane::with_normal(origin, normal),
        normal,
        scale: 1.0,
        q: [0.0; 5],
        part,
        spacing,
    };
    if !(scale > 0.0 && scale.is_finite()) {
        return flat(DVec3::Z);
    }
    let local: Vec<DVec3> = near.map(|q| (q - origin) / scale).collect();
    // each point's row weighted by √w, w = 1 / (1 + (d / h)²) with h the ring's spacing:
    // the nearer points, where the node's moves land, count more
    let h = (spacing / scale).max(f64::MIN_POSITIVE);
    let weight: Vec<f64> = local
        .iter()
        .map(|q| (1.0 / (1.0 + (q.length() / h).powi(2))).sqrt())
        .collect();
    let mean = (local.iter().sum::<DVec3>() + DVec3::ZERO) / (local.len() + 1) as f64;
    let mut c = [[0.0; 3]; 3];
    for d in local
        .iter()
        .map(|&q| q - mean)
        .chain(std::iter::once(-mean))
    {
        for i in 0..3 {
            for j in 0..3 {
                c[i][j] += d[i] * d[j];
            }
        }
    }
    // the frame whose height field fits best, of the three axes of the spread: the plane of
    // least spread is the surface's tangent plane unless the points run along a curve
    // (a strip of a cylinder's side along its rim: then its radial axis, not its axis
    // across the strip, is the normal)
    let axes = eigenvectors(c);
    let mut best: Option<(f64, Fit)> = None;
    for normal in axes {
        let plane = Plane::with_normal(origin, normal);
        let coords: Vec<[f64; 3]> = local
            .iter()
            .map(|q| [q.dot(plane.u), q.dot(plane.w), q.dot(normal)])
            .collect();
        let rows = |full: bool| -> Vec<(Vec<f64>, f64)> {
            coords
                .iter()
                .zip(&weight)
                .map(|(&[x, y, z], &r)| {
                    let row = if full {
                        vec![x, y, x * x, x * y, y * y]
                    } else {
                        vec![x, y]
                    };
                    (row.into_iter().map(|a| r * a).collect(), r * z)
                })
                .collect()
        };
        let tame = |q: &[f64; 5]| {
            q[0].hypot(q[1]) <= MAX_SLOPE && q[2..].iter().all(|c| c.abs() <= MAX_CURVATURE)
        };
        let quadric = least_squares(&rows(true))
            .map(|q| [q[0], q[1], q[2], q[3], q[4]])
            .filter(tame);
        let Some(q) = quadric.or_else(|| {
            least_squares(&rows(false))
                .map(|q| [q[0], q[1], 0.0, 0.0, 0.0])
                .filter(tame)
        }) else {
            continue;
        };
        let f = Fit {
            plane,
            normal,
            scale,
            q,
            part,
            spacing,
        };
        // the misfit: the largest distance of a point from the quadric (measured along its
        // normal, so frames compare)
        let misfit = coords
            .iter()
            .map(|&[x, y, z]| {
                let (h, hx, hy) = f.height(x, y);
                (z - h).abs() / (1.0 + hx * hx + hy * hy).sqrt()
            })
            .fold(0.0, f64::max);
        if best.as_ref().map_or(true, |b| misfit < b.0) {
            best = Some((misfit, f));
        }
    }
    best.map(|b| b.1).unwrap_or_else(|| flat(DVec3::Z))
}

/// The least-squares solution of `a x = b` over `rows` (each a row of `a` and its `b`) by
/// the normal equations and Gaussian elimination with partial pivoting; `None` when they
/// are singular (a pivot below 1e-10 of the largest diagonal entry).
fn least_squares(rows: &[(Vec<f64>, f64)]) -> Option<Vec<f64>> {
    let m = rows.first()?.0.len();
    if rows.len() < m {
        return None;
    }
    let mut a = vec![vec![0.0; m + 1]; m];
    for (r, b) in rows {
        for i in 0..m {
            for j in 0..m {
                a[i][j] += r[i] * r[j];
            }
            a[i][m] += r[i] * b;
        }
    }
    let big = (0..m).map(|i| a[i][i]).fold(0.0, f64::max);
    for col in 0..m {
        let pivot = (col..m).max_by(|&x, &y| a[x][col].abs().total_cmp(&a[y][col].abs()))?;
        if a[pivot][col].is_nan() || a[pivot][col].abs() <= 1e-10 * big {
            return None;
        }
        a.swap(col, pivot);
        for row in col + 1..m {
            let f = a[row][col] / a[col][col];
            let pivot_row = a[col].clone();
            for (x, p) in a[row][col..].iter_mut().zip(&pivot_row[col..]) {
                *x -= f * p;
            }
        }
    }
    let mut x = vec![0.0; m];
    for i in (0..m).rev() {
        let s: f64 = (i + 1..m).map(|k| a[i][k] * x[k]).sum();
        x[i] = (a[i][m] - s) / a[i][i];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// The unit eigenvectors of the symmetric 3×3 `c`, smallest eigenvalue first (Jacobi's
/// rotations).
fn eigenvectors(mut c: [[f64; 3]; 3]) -> [DVec3; 3] {
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _ in 0..32 {
        let off = c[0][1].abs() + c[0][2].abs() + c[1][2].abs();
        let diag = c[0][0].abs() + c[1][1].abs() + c[2][2].abs();
        if off.is_nan() || off <= 1e-15 * diag {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if c[p][q] == 0.0 {
                continue;
            }
            let theta = (c[q][q] - c[p][p]) / (2.0 * c[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let t = if theta == 0.0 { 1.0 } else { t };
            let (cs, sn) = (1.0 / (t * t + 1.0).sqrt(), t / (t * t + 1.0).sqrt());
            // c ← Jᵀ c J, v ← v J, J the rotation in the (p, q) plane
            for row in &mut c {
                let (ckp, ckq) = (row[p], row[q]);
                row[p] = cs * ckp - sn * ckq;
                row[q] = sn * ckp + cs * ckq;
            }
            let (rp, rq) = (c[p], c[q]);
            c[p] = [0, 1, 2].map(|k| cs * rp[k] - sn * rq[k]);
            c[q] = [0, 1, 2].map(|k| sn * rp[k] + cs * rq[k]);
            for row in &mut v {
                let (vp, vq) = (row[p], row[q]);
                row[p] = cs * vp - sn * vq;
                row[q] = sn * vp + cs * vq;
            }
        }
    }
    let mut order = [0, 1, 2];
    order.sort_by(|&a, &b| c[a][a].total_cmp(&c[b][b]));
    let axis = |i: usize| {
        DVec3::new(v[0][i], v[1][i], v[2][i])
            .try_normalize()
            .unwrap_or(DVec3::Z)
    };
    order.map(axis)
}

/// Turns the fits' normals the way the elements face. The sign of an eigenvector is
/// arbitrary: each fit is turned to agree with the fit it is reached from, across the
/// rings from the fit whose elements agree most on a side; then each connected set of
/// fits as a whole to face the way most of its elements (by area) do.
fn orient_fits(
    fits: &mut [Fit],
    ring_start: &[u32],
    ring: &[u32],
    points: &[DVec3],
    mesh: &Mesh,
    part: &impl Fn(usize) -> u32,
    fit_of: impl Fn(usize, u32) -> u32,
) {
    let nf = fits.len();
    // per fit, the area vectors of its node's elements on its part, summed
    let mut star = vec![DVec3::ZERO; nf];
    let mut area = vec![0.0; nf];
    for e in 0..mesh.element_count() {
        let n = crate::surface::element_normal(mesh, points, e);
        for &v in mesh.element(e) {
            let f = fit_of(v as usize, part(e)) as usize;
            star[f] += n;
            area[f] += n.length();
        }
    }
    let agreement: Vec<f64> = (0..nf)
        .map(|f| {
            if area[f] > 0.0 {
                star[f].dot(fits[f].normal) / area[f]
            } else {
                0.0
            }
        })
        .collect();
    // by |agreement|, largest first, ties to the lower fit
    let order = stable_order(nf, |f| !total_order_key(agreement[f].abs()));
    // Hoppe et al.'s orientation (1992): across the rings along a minimum spanning tree of
    // the cost 1 − |nᵢ·nⱼ|, so a sign passes between near-parallel normals first and one
    // poor fit does not turn the fits beyond it
    let mut done = vec![false; nf];
    let mut heap = std::collections::BinaryHeap::new();
    let cost = |a: &Fit, b: &Fit| {
        std::cmp::Reverse((1.0 - a.normal.dot(b.normal).abs()).max(0.0).to_bits())
    };
    for seed in order.into_iter().map(|f| f as usize) {
        if done[seed] {
            continue;
        }
        if agreement[seed] < 0.0 {
            flip(&mut fits[seed]);
        }
        let mut members = Vec::new();
        heap.push((std::cmp::Reverse(0u64), seed, seed));
        while let Some((_, f, from)) = heap.pop() {
            if done[f] {
                continue;
            }
            done[f] = true;
            if fits[f].normal.dot(fits[from].normal) < 0.0 {
                flip(&mut fits[f]);
            }
            members.push(f);
            for &g in &ring[ring_start[f] as usize..ring_start[f + 1] as usize] {
                let g = g as usize;
                if !done[g] {
                    heap.push((cost(&fits[f], &fits[g]), g, f));
                }
            }
        }
        let vote: f64 = members.iter().map(|&f| star[f].dot(fits[f].normal)).sum();
        if vote < 0.0 {
            for f in members {
                flip(&mut fits[f]);
            }
        }
    }
}

/// The same quadric seen from the other side: the frame's normal and `w` reversed (so the
/// frame stays right-handed) and the heights negated, `y` with `w`.
fn flip(f: &mut Fit) {
    f.normal = -f.normal;
    f.plane.w = -f.plane.w;
    // z → −z and y → −y: h'(x, y') = −h(x, −y')
    let q = f.q;
    f.q = [-q[0], q[1], -q[2], q[3], -q[4]];
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jacobi_finds_the_eigenvectors_in_order() {
        // diag(3, 1, 2) rotated: the smallest is the rotated y axis
        let r = glam::DMat3::from_rotation_x(0.3) * glam::DMat3::from_rotation_z(0.7);
        let d = glam::DMat3::from_diagonal(DVec3::new(3.0, 1.0, 2.0));
        let m = r * d * r.transpose();
        let c = [0, 1, 2].map(|i| [0, 1, 2].map(|j| m.col(j)[i]));
        let v = eigenvectors(c)[0];
        let want = r * DVec3::Y;
        assert!(v.cross(want).length() < 1e-12, "{v} vs {want}");
        let [_, mid, big] = eigenvectors(c);
        assert!(
            mid.cross(r * DVec3::Z).length() < 1e-12 && big.cross(r * DVec3::X).length() < 1e-12
        );
    }

    #[test]
    fn a_flipped_fit_is_the_same_surface() {
        let near: Vec<DVec3> = (0..12)
            .map(|i| {
                let a = i as f64 * std::f64::consts::FRAC_PI_6;
                let r = 0.1 + 0.02 * i as f64;
                DVec3::new(r * a.cos(), r * a.sin(), (1.0 - r * r).sqrt() - 1.0)
            })
            .collect();
        let f = fit(DVec3::ZERO, near.iter().copied(), 0, 0.1);
        let mut g = f.clone();
        flip(&mut g);
        let p = DVec3::new(0.05, -0.03, 0.2);
        let (a, na) = f.nearest(p);
        let (b, nb) = g.nearest(p);
        assert!(
            (a - b).length() < 1e-14 && (na + nb).length() < 1e-14,
            "{a} {b} {na} {nb}"
        );
        // the unit sphere through the origin (centre (0, 0, −1)): the fit is near it
        let on = DVec3::new(0.0, 0.0, -1.0) + (p - DVec3::new(0.0, 0.0, -1.0)).normalize();
        assert!((a - on).length() < 1e-3, "{a} vs {on}");
    }
}
