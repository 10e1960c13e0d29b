//! Iso-lines of a sampled scalar field by marching squares.
//!
//! Each grid cell is classified by which of its four corners lie above the level; the
//! level crosses the cell's edges where the linear interpolant between two corners
//! reaches it. The two ambiguous (saddle) cases are resolved by the cell-centre value
//! (the mean of the corners): when it is above the level the two high corners are
//! joined through the centre. Cells with a non-finite corner are skipped, so a masked
//! region (a barrier objective's +∞, or NaN) simply has no lines.

use glam::DVec2;

/// A regular grid of `nx × ny` samples over the rectangle `lo..hi`; sample `(i, j)` sits
/// at `lo + (i·dx, j·dy)` and is stored at `j·nx + i` (row-major, `j` upwards).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grid {
    pub nx: usize,
    pub ny: usize,
    pub lo: DVec2,
    pub hi: DVec2,
}

impl Grid {
    /// Spacing between samples.
    pub fn spacing(&self) -> DVec2 {
        (self.hi - self.lo) / DVec2::new((self.nx.max(2) - 1) as f64, (self.ny.max(2) - 1) as f64)
    }
    /// Position of sample `(i, j)`.
    pub fn point(&self, i: usize, j: usize) -> DVec2 {
        self.lo + self.spacing() * DVec2::new(i as f64, j as f64)
    }
    pub fn len(&self) -> usize {
        self.nx * self.ny
    }
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// The bilinear interpolant of `values` at `p`; NaN outside the grid or when a corner
    /// of the cell is not finite.
    pub fn bilinear(&self, values: &[f64], p: DVec2) -> f64 {
        if self.nx < 2 || self.ny < 2 || values.len() < self.len() {
            return f64::NAN;
        }
        let u = (p - self.lo) / self.spacing();
        if !(u.x >= 0.0 && u.y >= 0.0 && u.x <= (self.nx - 1) as f64 && u.y <= (self.ny - 1) as f64) {
            return f64::NAN;
        }
        let i = (u.x.floor() as usize).min(self.nx - 2);
        let j = (u.y.floor() as usize).min(self.ny - 2);
        let (fx, fy) = (u.x - i as f64, u.y - j as f64);
        let v = |a: usize, b: usize| values[b * self.nx + a];
        let (v00, v10, v01, v11) = (v(i, j), v(i + 1, j), v(i, j + 1), v(i + 1, j + 1));
        let r = (1.0 - fy) * ((1.0 - fx) * v00 + fx * v10) + fy * ((1.0 - fx) * v01 + fx * v11);
        if v00.is_finite() && v10.is_finite() && v01.is_finite() && v11.is_finite() {
            r
        } else {
            f64::NAN
        }
    }
}

/// Appends to `out` the segments of the iso-line `values = level` over `grid`, one or
/// two per crossed cell, in world coordinates. `values` has `grid.len()` samples
/// (fewer: nothing is drawn).
pub fn iso_segments(grid: &Grid, values: &[f64], level: f64, out: &mut Vec<[DVec2; 2]>) {
    if grid.nx < 2 || grid.ny < 2 || values.len() < grid.len() || !level.is_finite() {
        return;
    }
    let d = grid.spacing();
    for j in 0..grid.ny - 1 {
        for i in 0..grid.nx - 1 {
            // corners counter-clockwise from bottom left
            let v = [
                values[j * grid.nx + i],
                values[j * grid.nx + i + 1],
                values[(j + 1) * grid.nx + i + 1],
                values[(j + 1) * grid.nx + i],
            ];
            if !v.iter().all(|x| x.is_finite()) {
                continue;
            }
            let case = v.iter().enumerate().fold(0usize, |c, (k, &x)| c | (((x > level) as usize) << k));
            if case == 0 || case == 15 {
                continue;
            }
            let p0 = grid.lo + d * DVec2::new(i as f64, j as f64);
            let corner = [p0, p0 + DVec2::new(d.x, 0.0), p0 + d, p0 + DVec2::new(0.0, d.y)];
            // crossing on edge e (corner e → corner e+1)
            let cross = |e: usize| {
                let (a, b) = (e, (e + 1) % 4);
                let t = ((level - v[a]) / (v[b] - v[a])).clamp(0.0, 1.0);
                corner[a] + t * (corner[b] - corner[a])
            };
            let centre_high = 0.25 * (v[0] + v[1] + v[2] + v[3]) > level;
            let mut seg = |a: usize, b: usize| out.push([cross(a), cross(b)]);
            // edges: 0 bottom, 1 right, 2 top, 3 left
            match case {
                1 | 14 => seg(3, 0),
                2 | 13 => seg(0, 1),
                3 | 12 => seg(3, 1),
                4 | 11 => seg(1, 2),
                6 | 9 => seg(0, 2),
                7 | 8 => seg(2, 3),
                5 => {
                    // corners 0 and 2 high
                    if centre_high {
                        seg(0, 1);
                        seg(2, 3);
                    } else {
                        seg(3, 0);
                        seg(1, 2);
                    }
                }
                10 => {
                    // corners 1 and 3 high
                    if centre_high {
                        seg(3, 0);
                        seg(1, 2);
                    } else {
                        seg(0, 1);
                        seg(2, 3);
                    }
                }
                _ => {}
            }
        }
    }
}

/// Joins segments that share endpoints (within `tol`) into polylines, so an iso-line
/// can be stroked with a continuous dash pattern and smooth joins. Every segment is used
/// once; a closed loop ends at its first point.
pub fn chain_segments(segs: &[[DVec2; 2]], tol: f64) -> Vec<Vec<DVec2>> {
    use std::collections::HashMap;
    let tol = if tol > 0.0 && tol.is_finite() { tol } else { 1e-9 };
    let key = |p: DVec2| ((p.x / tol).round() as i64, (p.y / tol).round() as i64);
    // endpoint key → (segment, which end)
    let mut at: HashMap<(i64, i64), Vec<(usize, usize)>> = HashMap::with_capacity(segs.len() * 2);
    for (i, s) in segs.iter().enumerate() {
        for (end, p) in s.iter().enumerate() {
            at.entry(key(*p)).or_default().push((i, end));
        }
    }
    let mut used = vec![false; segs.len()];
    let mut lines = Vec::new();
    // extends `line` from its last point through unused segments
    let grow = |line: &mut Vec<DVec2>, used: &mut Vec<bool>| loop {
        let last = *line.last().unwrap_or(&DVec2::ZERO);
        let next = at.get(&key(last)).and_then(|v| v.iter().find(|(i, _)| !used[*i]).copied());
        match next {
            Some((i, end)) => {
                used[i] = true;
                line.push(segs[i][1 - end]);
            }
            None => break,
        }
    };
    for i in 0..segs.len() {
        if used[i] {
            continue;
        }
        used[i] = true;
        let mut line = vec![segs[i][0], segs[i][1]];
        grow(&mut line, &mut used);
        // then the other way from the first point
        line.reverse();
        grow(&mut line, &mut used);
        lines.push(line);
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(grid: &Grid, f: impl Fn(DVec2) -> f64) -> Vec<f64> {
        let mut v = Vec::with_capacity(grid.len());
        for j in 0..grid.ny {
            for i in 0..grid.nx {
                v.push(f(grid.point(i, j)));
            }
        }
        v
    }

    #[test]
    fn circle_iso_line_of_a_paraboloid() {
        let grid = Grid { nx: 81, ny: 81, lo: DVec2::splat(-2.0), hi: DVec2::splat(2.0) };
        let v = sample(&grid, |p| p.length_squared());
        let h = grid.spacing().x;
        // levels that no sample hits exactly (x² + y² = c has no solution on the grid):
        // a sample exactly on the level makes zero-length pieces at that sample
        for c in [0.3, 1.1, 2.7] {
            let mut segs = Vec::new();
            iso_segments(&grid, &v, c, &mut segs);
            let r = f64::sqrt(c);
            // linear interpolation of r² along a cell edge is off the circle by O(h²)
            for s in &segs {
                for p in s {
                    assert!((p.length() - r).abs() < h * h, "r² = {c}: point at radius {}", p.length());
                }
            }
            // the pieces add up to the circumference, and the line is closed: every
            // endpoint is shared by exactly two segments
            let len: f64 = segs.iter().map(|s| s[0].distance(s[1])).sum();
            assert!((len - 2.0 * std::f64::consts::PI * r).abs() < 0.01 * r, "length {len} for r {r}");
            let ends: Vec<DVec2> = segs.iter().flat_map(|s| [s[0], s[1]]).collect();
            for p in &ends {
                let twins = ends.iter().filter(|q| q.distance(*p) < 1e-9).count();
                assert_eq!(twins, 2, "open or branching line at {p:?}");
            }
            // and chained, it is one closed polyline
            let lines = chain_segments(&segs, 1e-9);
            assert_eq!(lines.len(), 1);
            assert_eq!(lines[0].len(), segs.len() + 1);
            assert!(lines[0][0].distance(lines[0][segs.len()]) < 1e-9);
        }
    }

    #[test]
    fn saddle_cells_follow_the_centre_value() {
        let grid = Grid { nx: 2, ny: 2, lo: DVec2::ZERO, hi: DVec2::ONE };
        // high corners bottom-left and top-right, centre mean 0.25 above the level 0:
        // the high corners join, so the segments cut off the low corners (1,0) and (0,1)
        let mut segs = Vec::new();
        iso_segments(&grid, &[1.5, -1.0, -1.0, 1.5], 0.0, &mut segs);
        assert_eq!(segs.len(), 2);
        let cuts = |s: &[DVec2; 2], corner: DVec2| s.iter().all(|p| p.distance(corner) < 0.99);
        let a = DVec2::new(1.0, 0.0);
        let b = DVec2::new(0.0, 1.0);
        assert!(segs.iter().any(|s| cuts(s, a)) && segs.iter().any(|s| cuts(s, b)), "{segs:?}");
        // the cut points: bottom edge at t = 1.5/2.5, right edge at 0.4
        let bottom = DVec2::new(0.6, 0.0);
        assert!(segs.iter().any(|s| s.iter().any(|p| p.distance(bottom) < 1e-12)), "{segs:?}");
        // centre mean below the level: the high corners are cut off instead
        segs.clear();
        iso_segments(&grid, &[1.0, -1.5, -1.5, 1.0], 0.0, &mut segs);
        assert_eq!(segs.len(), 2);
        assert!(segs.iter().any(|s| cuts(s, DVec2::ZERO)) && segs.iter().any(|s| cuts(s, DVec2::ONE)), "{segs:?}");
        // the mirror saddle (case 10)
        segs.clear();
        iso_segments(&grid, &[-1.0, 1.5, 1.5, -1.0], 0.0, &mut segs);
        assert!(segs.iter().any(|s| cuts(s, DVec2::ZERO)) && segs.iter().any(|s| cuts(s, DVec2::ONE)), "{segs:?}");
    }

    #[test]
    fn masked_cells_have_no_lines_and_short_input_is_ignored() {
        let grid = Grid { nx: 3, ny: 2, lo: DVec2::ZERO, hi: DVec2::new(2.0, 1.0) };
        let mut segs = Vec::new();
        iso_segments(&grid, &[0.0, 1.0, f64::INFINITY, 0.0, 1.0, f64::NAN], 0.5, &mut segs);
        assert_eq!(segs.len(), 1, "only the finite cell crosses");
        assert!(segs[0].iter().all(|p| (p.x - 0.5).abs() < 1e-12));
        segs.clear();
        iso_segments(&grid, &[0.0; 4], 0.5, &mut segs);
        iso_segments(&grid, &[0.0; 6], f64::NAN, &mut segs);
        assert!(segs.is_empty());
    }

    #[test]
    fn bilinear_reproduces_bilinear_functions() {
        let grid = Grid { nx: 5, ny: 4, lo: DVec2::new(-1.0, 2.0), hi: DVec2::new(3.0, 5.0) };
        let f = |p: DVec2| 2.0 + 0.5 * p.x - p.y + 0.25 * p.x * p.y;
        let v = sample(&grid, f);
        for p in [DVec2::new(-1.0, 2.0), DVec2::new(0.3, 4.1), DVec2::new(3.0, 5.0), DVec2::new(2.99, 2.01)] {
            assert!((grid.bilinear(&v, p) - f(p)).abs() < 1e-12);
        }
        assert!(grid.bilinear(&v, DVec2::new(5.0, 3.0)).is_nan());
    }
}
