//! The uniform grid over the loaded reference's facets: the global nearest-facet search,
//! where the walk from a node's last facet does not settle.

use glam::DVec3;

use crate::mesh::NONE;

/// A uniform grid of cells over the facets' bounding box, each cell listing the triangles
/// whose bounding boxes meet it: the global nearest-triangle search.
#[derive(Clone, Debug)]
pub(super) struct Grid {
    lo: DVec3,
    cell: f64,
    dims: [usize; 3],
    start: Vec<u32>,
    tris: Vec<u32>,
}

impl Grid {
    pub(super) fn new(points: &[DVec3], triangles: &[[u32; 3]]) -> Grid {
        let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        for t in triangles {
            for &v in t {
                lo = lo.min(points[v as usize]);
                hi = hi.max(points[v as usize]);
            }
        }
        if triangles.is_empty() || !(lo.is_finite() && hi.is_finite()) {
            return Grid {
                lo: DVec3::ZERO,
                cell: 1.0,
                dims: [1; 3],
                start: vec![0, 0],
                tris: Vec::new(),
            };
        }
        let size = (hi - lo).max_element().max(f64::MIN_POSITIVE);
        // about two triangles a cell on a surface: cells ~ √(triangles) along the longest side
        let along = ((triangles.len() as f64).sqrt().ceil() as usize).clamp(1, 256);
        let cell = size / along as f64;
        let dims = [0, 1, 2].map(|i| (((hi[i] - lo[i]) / cell).floor() as usize + 1).min(257));
        let index = |c: [usize; 3]| (c[2] * dims[1] + c[1]) * dims[0] + c[0];
        let cell_of = |p: DVec3| {
            [0, 1, 2].map(|i| (((p[i] - lo[i]) / cell).floor().max(0.0) as usize).min(dims[i] - 1))
        };
        let mut count = vec![0u32; dims[0] * dims[1] * dims[2] + 1];
        let cells = |t: &[u32; 3], f: &mut dyn FnMut(usize)| {
            let (mut a, mut b) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
            for &v in t {
                a = a.min(points[v as usize]);
                b = b.max(points[v as usize]);
            }
            let (ca, cb) = (cell_of(a), cell_of(b));
            for z in ca[2]..=cb[2] {
                for y in ca[1]..=cb[1] {
                    for x in ca[0]..=cb[0] {
                        f(index([x, y, z]));
                    }
                }
            }
        };
        for t in triangles {
            cells(t, &mut |c| count[c + 1] += 1);
        }
        for i in 1..count.len() {
            count[i] += count[i - 1];
        }
        let mut fill = count.clone();
        let mut tris = vec![0u32; *count.last().expect("one cell at least") as usize];
        for (i, t) in triangles.iter().enumerate() {
            cells(t, &mut |c| {
                tris[fill[c] as usize] = i as u32;
                fill[c] += 1;
            });
        }
        Grid {
            lo,
            cell,
            dims,
            start: count,
            tris,
        }
    }

    /// The triangle nearest to `p` by `nearest_point` (`None`: not a candidate), searching shells of cells outward
    /// from `p`'s cell until the next shell is farther than the best found.
    pub(super) fn nearest(&self, p: DVec3, nearest_point: impl Fn(u32) -> Option<DVec3>) -> u32 {
        let dims = self.dims;
        let rel = (p - self.lo) / self.cell;
        let centre = [0, 1, 2].map(|i| (rel[i].floor().max(0.0) as usize).min(dims[i] - 1));
        let reach = dims.into_iter().max().unwrap_or(1);
        let (mut best, mut best_d) = (NONE, f64::INFINITY);
        // the distance from p to its cell's outside, so a shell r away is at least this far
        let inside = [0, 1, 2]
            .map(|i| {
                let f = rel[i] - centre[i] as f64;
                f.min(1.0 - f).max(0.0)
            })
            .into_iter()
            .fold(f64::INFINITY, f64::min)
            * self.cell;
        for r in 0..=reach {
            if best != NONE && inside + (r as f64 - 1.0).max(0.0) * self.cell > best_d {
                break;
            }
            let range = |i: usize| centre[i].saturating_sub(r)..=(centre[i] + r).min(dims[i] - 1);
            for z in range(2) {
                for y in range(1) {
                    // the shell's cells only: the whole row where z or y is on the shell,
                    // else its two ends (the cube's inside was searched at smaller r; a far
                    // query's r grows with the grid, and its cube with r³)
                    let on_shell = z.abs_diff(centre[2]) == r || y.abs_diff(centre[1]) == r;
                    let ends = [
                        centre[0].checked_sub(r),
                        Some(centre[0] + r).filter(|&x| x < dims[0] && r > 0),
                    ];
                    let mut row = |x: usize| {
                        let c = (z * dims[1] + y) * dims[0] + x;
                        for &t in &self.tris[self.start[c] as usize..self.start[c + 1] as usize] {
                            let Some(q) = nearest_point(t) else { continue };
                            let d = (q - p).length();
                            if d < best_d || (d == best_d && t < best) {
                                (best, best_d) = (t, d);
                            }
                        }
                    };
                    if on_shell {
                        range(0).for_each(&mut row);
                    } else {
                        ends.into_iter().flatten().for_each(&mut row);
                    }
                }
            }
        }
        best
    }

    /// Calls `visit` with every item listed in the cells the ball of `radius` about `p`
    /// meets (each cell's items once; an item in several cells comes once a cell).
    pub(super) fn near(&self, p: DVec3, radius: f64, mut visit: impl FnMut(u32)) {
        let dims = self.dims;
        let cell_of = |q: DVec3, i: usize| {
            (((q[i] - self.lo[i]) / self.cell).floor().max(0.0) as usize).min(dims[i] - 1)
        };
        let (a, b) = (p - DVec3::splat(radius), p + DVec3::splat(radius));
        if !(a.is_finite() && b.is_finite()) {
            return;
        }
        for z in cell_of(a, 2)..=cell_of(b, 2) {
            for y in cell_of(a, 1)..=cell_of(b, 1) {
                for x in cell_of(a, 0)..=cell_of(b, 0) {
                    let c = (z * dims[1] + y) * dims[0] + x;
                    self.tris[self.start[c] as usize..self.start[c + 1] as usize]
                        .iter()
                        .for_each(|&t| visit(t));
                }
            }
        }
    }
}
