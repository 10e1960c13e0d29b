//! A quadratic element's curved patch of the loaded reference: its shape functions
//! through its nodes, and the projection of a point onto it.

use glam::DVec3;

use crate::mesh::ElementKind;

/// A quadratic element's curved patch: `x(u, v) = Σ Nᵢ(u, v) xᵢ` with its shape functions
/// — the 6-node triangle's on the unit triangle (corners (0,0), (1,0), (0,1)), the 8-node
/// (serendipity) and 9-node (Lagrange) quads' on [−1, 1]².
#[derive(Clone, Copy, Debug)]
pub(super) struct Patch {
    pub(super) kind: ElementKind,
    pub(super) nodes: [u32; 9],
}

/// Gauss–Newton steps of a projection onto a patch.
const PATCH_ITERATIONS: usize = 12;

impl Patch {
    /// Node `i`'s parameters (the element's node order: corners, then mid-sides, centre).
    pub(super) fn node_parameter(&self, i: usize) -> [f64; 2] {
        match self.kind {
            ElementKind::Tri6 => [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.5, 0.0], [0.5, 0.5], [0.0, 0.5]][i],
            _ => [
                [-1.0, -1.0],
                [1.0, -1.0],
                [1.0, 1.0],
                [-1.0, 1.0],
                [0.0, -1.0],
                [1.0, 0.0],
                [0.0, 1.0],
                [-1.0, 0.0],
                [0.0, 0.0],
            ][i],
        }
    }

    /// The parameters of the vertices of the element's flat triangles, in the order
    /// [`Facets::new`] makes them.
    pub(super) fn triangle_parameters(&self) -> Vec<[[f64; 2]; 3]> {
        let q = |i: usize| self.node_parameter(i);
        match self.kind {
            ElementKind::Tri6 => vec![[q(0), q(3), q(5)], [q(3), q(1), q(4)], [q(5), q(4), q(2)], [q(3), q(4), q(5)]],
            _ => (0..4).flat_map(|i| [[q(i), q(4 + i), [0.0, 0.0]], [q(4 + i), q((i + 1) % 4), [0.0, 0.0]]]).collect(),
        }
    }

    /// The shape functions at `(u, v)`.
    pub(super) fn shape(&self, [u, v]: [f64; 2]) -> [f64; 9] {
        let mut n = [0.0; 9];
        match self.kind {
            ElementKind::Tri6 => {
                let (l1, l2, l3) = (1.0 - u - v, u, v);
                n[..6].copy_from_slice(&[
                    l1 * (2.0 * l1 - 1.0),
                    l2 * (2.0 * l2 - 1.0),
                    l3 * (2.0 * l3 - 1.0),
                    4.0 * l1 * l2,
                    4.0 * l2 * l3,
                    4.0 * l3 * l1,
                ]);
            }
            ElementKind::Quad8 => {
                for (i, slot) in n.iter_mut().enumerate().take(8) {
                    let [a, b] = self.node_parameter(i);
                    *slot = if i < 4 {
                        0.25 * (1.0 + a * u) * (1.0 + b * v) * (a * u + b * v - 1.0)
                    } else if a == 0.0 {
                        0.5 * (1.0 - u * u) * (1.0 + b * v)
                    } else {
                        0.5 * (1.0 + a * u) * (1.0 - v * v)
                    };
                }
            }
            _ => {
                // Lagrange on {−1, 0, 1} in each direction
                let l = |s: f64, at: f64| match at {
                    a if a < 0.0 => 0.5 * s * (s - 1.0),
                    a if a > 0.0 => 0.5 * s * (s + 1.0),
                    _ => 1.0 - s * s,
                };
                for (i, slot) in n.iter_mut().enumerate() {
                    let [a, b] = self.node_parameter(i);
                    *slot = l(u, a) * l(v, b);
                }
            }
        }
        n
    }

    pub(super) fn at(&self, points: &[DVec3], uv: [f64; 2]) -> DVec3 {
        let n = self.shape(uv);
        (0..self.kind.node_count()).map(|i| n[i] * points[self.nodes[i] as usize]).sum()
    }

    /// `uv` moved into the parameter domain.
    pub(super) fn clamp(&self, [u, v]: [f64; 2]) -> [f64; 2] {
        match self.kind {
            ElementKind::Tri6 => {
                let (u, v) = (u.max(0.0), v.max(0.0));
                let s = u + v;
                if s > 1.0 {
                    [u / s, v / s]
                } else {
                    [u, v]
                }
            }
            _ => [u.clamp(-1.0, 1.0), v.clamp(-1.0, 1.0)],
        }
    }

    /// The point of the patch nearest to `p`, from the parameters `start`, by Gauss–Newton
    /// on `|x(u, v) − p|²` kept in the domain (derivatives by central differences; a step
    /// is taken only where it brings the point nearer, halved until it does), and the
    /// patch's unit normal there (`∂x/∂u × ∂x/∂v`: the element's orientation).
    pub(super) fn nearest(&self, points: &[DVec3], p: DVec3, start: [f64; 2]) -> (DVec3, DVec3) {
        let h = 1e-6;
        let mut uv = self.clamp(start);
        let derivatives = |uv: [f64; 2]| {
            let d = |j: usize| {
                let (mut a, mut b) = (uv, uv);
                a[j] -= h;
                b[j] += h;
                (self.at(points, b) - self.at(points, a)) / (2.0 * h)
            };
            (d(0), d(1))
        };
        let mut d = (self.at(points, uv) - p).length_squared();
        'iterations: for _ in 0..PATCH_ITERATIONS {
            let x = self.at(points, uv);
            let (xu, xv) = derivatives(uv);
            let r = p - x;
            let (a, b, c) = (xu.dot(xu), xu.dot(xv), xv.dot(xv));
            let det = a * c - b * b;
            if !(det.is_finite() && det > 0.0) {
                break;
            }
            let (gu, gv) = (xu.dot(r), xv.dot(r));
            let mut step = [(c * gu - b * gv) / det, (a * gv - b * gu) / det];
            for _ in 0..20 {
                let next = self.clamp([uv[0] + step[0], uv[1] + step[1]]);
                let dn = (self.at(points, next) - p).length_squared();
                if dn <= d {
                    let moved = (next[0] - uv[0]).abs().max((next[1] - uv[1]).abs());
                    (uv, d) = (next, dn);
                    if moved < 1e-15 {
                        break 'iterations;
                    }
                    continue 'iterations;
                }
                step = [0.5 * step[0], 0.5 * step[1]];
            }
            break;
        }
        let (xu, xv) = derivatives(uv);
        let normal = xu.cross(xv).try_normalize().unwrap_or(DVec3::Z);
        (self.at(points, uv), normal)
    }
}
