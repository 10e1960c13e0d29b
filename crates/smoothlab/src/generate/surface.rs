//! Surface samples on exact surfaces: a cube-sphere, a capped cylinder (a grid round its
//! side, O-grid caps, a feature edge at each rim) and a torus from a periodic grid. Quads, triangles (each quad
//! split, diagonals alternating) or mixed (every other quad split), linear or quadratic
//! with their mid-side nodes on the surface.

use std::collections::HashMap;
use std::f64::consts::{FRAC_PI_4, PI};

use glam::DVec3;

use crate::error::{Error, Result};
use crate::mesh::{ElementKind, MeshBuilder};
use crate::surface::{Analytic, Surface};

enum_with_names! {
    /// Which exact surface a surface sample lies on.
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
    pub enum SurfaceShape {
        #[default]
        Sphere => ("sphere", "the unit sphere, a cube-sphere (closed)"),
        Cylinder => ("cylinder", "a cylinder of radius 1 and height 2 with flat caps (feature edges at the rims)"),
        Torus => ("torus", "a torus of radii 3 and 1 (closed)"),
    }
}

enum_with_names! {
    /// The elements of a surface sample.
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
    pub enum SurfaceKind {
        #[default]
        Quad => ("quad", "quads"),
        Tri => ("tri", "triangles, each quad split"),
        Mixed => ("mixed", "quads with every other one split into triangles"),
    }
}

/// The largest `resolution` of a surface sample.
pub const MAX_SURFACE_RESOLUTION: usize = 256;

/// A surface sample: `shape` meshed by `kind` elements of `order` 1 or 2, `resolution`
/// cells along each edge of the cube (the sphere) or of the caps' middle squares (the
/// cylinder: four times as many round it), or four times as many round the torus's tube
/// and twelve times round its axis. Its reference is the exact surface.
pub fn surface(shape: SurfaceShape, kind: SurfaceKind, order: u8, resolution: usize) -> Result<Surface> {
    if !(1..=2).contains(&order) {
        return Err(Error::invalid(format!("the order must be 1 (linear) or 2 (quadratic), not {order}")));
    }
    if !(1..=MAX_SURFACE_RESOLUTION).contains(&resolution) {
        return Err(Error::invalid(format!(
            "the resolution must be from 1 to {MAX_SURFACE_RESOLUTION}, not {resolution}"
        )));
    }
    let n = resolution as i64;
    let o = order as i64;
    let mut s = Lattice { kind, order, ids: HashMap::new(), b: MeshBuilder::new() };
    // Cells are given by their corners' integer coordinates on a lattice of `o` steps a
    // cell (mid-side nodes at the odd ones); a map gives each lattice point its key (one
    // node per key: where regions meet, or a periodic lattice meets itself, the map gives
    // the one point one key) and its position.
    let analytic = match shape {
        SurfaceShape::Sphere => {
            let m = n * o;
            // equal-angle cube-sphere: the cube [-1, 1]³, tan spreads the nodes evenly in angle
            let map = |l: [i64; 3]| {
                let c = l.map(|v| ((2.0 * v as f64 / m as f64 - 1.0) * FRAC_PI_4).tan());
                (l, DVec3::from(c).normalize())
            };
            for face in 0..6 {
                let axis = face / 2;
                let side = if face % 2 == 0 { 0 } else { m };
                // (u, v) span the face; u × v points out of the cube
                let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
                let (u, v) = if face % 2 == 0 { (v, u) } else { (u, v) };
                for i in 0..n {
                    for j in 0..n {
                        let at = |du: i64, dv: i64| {
                            let mut l = [0i64; 3];
                            l[axis] = side;
                            l[u] = (i + du) * o;
                            l[v] = (j + dv) * o;
                            l
                        };
                        s.cell([at(0, 0), at(1, 0), at(1, 1), at(0, 1)], (i + j) % 2 == 0, &map);
                    }
                }
            }
            Analytic::Sphere { centre: DVec3::ZERO, radius: 1.0 }
        }
        SurfaceShape::Cylinder => {
            cylinder(&mut s, n, o);
            Analytic::CappedCylinder { radius: 1.0, z0: -1.0, z1: 1.0 }
        }
        SurfaceShape::Torus => {
            let (major, minor) = (3.0, 1.0);
            // four cells round the tube per unit of resolution (22.5° apart at 4: under the
            // feature angle), three times as many round the axis (its circle is 3 times longer)
            let (around, tube) = (12 * n * o, 4 * n * o);
            // lattice (i, j, 0): i round the axis, j round the tube, both periodic
            let map = |l: [i64; 3]| {
                let (a, b) = (l[0].rem_euclid(around), l[1].rem_euclid(tube));
                let theta = 2.0 * PI * a as f64 / around as f64;
                let phi = 2.0 * PI * b as f64 / tube as f64;
                let r = major + minor * phi.cos();
                ([a, b, 0], DVec3::new(r * theta.cos(), r * theta.sin(), minor * phi.sin()))
            };
            for i in 0..12 * n {
                for j in 0..4 * n {
                    let l = |di: i64, dj: i64| [(i + di) * o, (j + dj) * o, 0];
                    s.cell([l(0, 0), l(1, 0), l(1, 1), l(0, 1)], (i + j) % 2 == 0, &map);
                }
            }
            Analytic::Torus { major, minor }
        }
    };
    crate::surface::Surface::build(s.b, Some(analytic))
}

/// The capped cylinder of radius 1 from z = −1 to 1: the side a grid of `4n` cells round
/// and about `4n/π` up (square cells), each cap an O-grid — a square of `n × n` cells in
/// the middle and rings of cells out to the rim — so no cell has a corner of 180° where a
/// square grid would meet the circle.
fn cylinder(s: &mut Lattice, n: i64, o: i64) {
    let m = n * o; // lattice steps along a side of the cap's square
    let around = 4 * m; // lattice steps round the rim
    let tall = ((4 * n) as f64 / PI).round().max(1.0) as i64 * o;
    // rings from the square (half-width 0.5) to the rim, cells about as wide as the side's
    let rings = ((n as f64) * 0.5 / (PI / 2.0)).round().max(1.0) as i64 * o;
    let a = 0.5;
    let rim_angle = |i: i64| -3.0 * FRAC_PI_4 + 2.0 * PI * i.rem_euclid(around) as f64 / around as f64;
    // the square's boundary point i (counter-clockwise from its corner (0, 0)), in its lattice
    let boundary = |i: i64| {
        let (side, t) = (i.rem_euclid(around) / m, i.rem_euclid(around) % m);
        match side {
            0 => (t, 0),
            1 => (m, t),
            2 => (m - t, m),
            _ => (0, m - t),
        }
    };
    let square_point = |(x, y): (i64, i64)| {
        glam::DVec2::new(a * (2.0 * x as f64 / m as f64 - 1.0), a * (2.0 * y as f64 / m as f64 - 1.0))
    };
    // keys: [region, u, v], region 0–1 the bottom and top squares, 2–3 their rings, 4–5
    // the rims, 6 the side
    let cap_point = |cap: i64, l: [i64; 3]| -> ([i64; 3], DVec3) {
        let z = if cap == 0 { -1.0 } else { 1.0 };
        match l[2] {
            // the square: (x, y)
            0 => ([cap, l[0], l[1]], square_point((l[0], l[1])).extend(z)),
            // the rings: (i round, j out); ring 0 is the square's boundary, the last the rim
            _ => {
                let (i, j) = (l[0], l[1]);
                if j == 0 {
                    let (x, y) = boundary(i);
                    return ([cap, x, y], square_point((x, y)).extend(z));
                }
                let rim = glam::DVec2::from_angle(rim_angle(i));
                if j == rings {
                    return ([4 + cap, i.rem_euclid(around), 0], rim.extend(z));
                }
                let t = j as f64 / rings as f64;
                ([2 + cap, i.rem_euclid(around), j], (square_point(boundary(i)) * (1.0 - t) + rim * t).extend(z))
            }
        }
    };
    let side_point = |l: [i64; 3]| -> ([i64; 3], DVec3) {
        let (i, k) = (l[0], l[1]);
        let rim = glam::DVec2::from_angle(rim_angle(i));
        let z = -1.0 + 2.0 * k as f64 / tall as f64;
        if k == 0 {
            ([4, i.rem_euclid(around), 0], rim.extend(-1.0))
        } else if k == tall {
            ([5, i.rem_euclid(around), 0], rim.extend(1.0))
        } else {
            ([6, i.rem_euclid(around), k], rim.extend(z))
        }
    };
    // the side: (i round, k up); outward is (round) × (up)
    for i in 0..4 * n {
        for k in 0..tall / o {
            let l = |di: i64, dk: i64| [(i + di) * o, (k + dk) * o, 0];
            s.cell([l(0, 0), l(1, 0), l(1, 1), l(0, 1)], (i + k) % 2 == 0, &side_point);
        }
    }
    for cap in 0..2 {
        // corners counter-clockwise seen from +z; the bottom cap faces −z, so reversed
        let order = |c: [[i64; 3]; 4]| if cap == 1 { c } else { [c[0], c[3], c[2], c[1]] };
        let map = |l: [i64; 3]| cap_point(cap, l);
        for x in 0..n {
            for y in 0..n {
                let l = |dx: i64, dy: i64| [(x + dx) * o, (y + dy) * o, 0];
                s.cell(order([l(0, 0), l(1, 0), l(1, 1), l(0, 1)]), (x + y) % 2 == 0, &map);
            }
        }
        // a ring cell: (j out, i round) then (j out + 1) ...: outward × round = +z
        for i in 0..4 * n {
            for j in 0..rings / o {
                let l = |di: i64, dj: i64| [(i + di) * o, (j + dj) * o, 1];
                s.cell(order([l(0, 0), l(0, 1), l(1, 1), l(1, 0)]), (i + j) % 2 == 0, &map);
            }
        }
    }
}

/// The elements of a sample as they are made: lattice points mapped onto the surface,
/// each key made a node once.
struct Lattice {
    kind: SurfaceKind,
    order: u8,
    ids: HashMap<[i64; 3], u32>,
    b: MeshBuilder,
}

/// A lattice point's key and position.
type Map<'a> = dyn Fn([i64; 3]) -> ([i64; 3], DVec3) + 'a;

impl Lattice {
    fn node(&mut self, l: [i64; 3], map: &Map) -> u32 {
        let (key, p) = map(l);
        if let Some(&id) = self.ids.get(&key) {
            return id;
        }
        let id = self.b.add_node(p.to_array(), 0) as u32;
        self.ids.insert(key, id);
        id
    }

    /// One cell with lattice corners `c` (counter-clockwise seen from outside): a quad,
    /// or two triangles (split along `c0–c2` when `diagonal`, else `c1–c3`); quadratic
    /// elements take their mid-side nodes at the lattice points between the corners.
    fn cell(&mut self, c: [[i64; 3]; 4], diagonal: bool, map: &Map) {
        let mid = |a: [i64; 3], b: [i64; 3]| [0, 1, 2].map(|i| (a[i] + b[i]) / 2);
        let split = match self.kind {
            SurfaceKind::Quad => false,
            SurfaceKind::Tri => true,
            SurfaceKind::Mixed => diagonal,
        };
        let quadratic = self.order == 2;
        if !split {
            let corners: Vec<u32> = c.iter().map(|&l| self.node(l, map)).collect();
            if !quadratic {
                self.b.add_element(ElementKind::Quad4, &corners, 0);
            } else {
                let mids: Vec<u32> = (0..4).map(|i| self.node(mid(c[i], c[(i + 1) % 4]), map)).collect();
                self.b.add_element(ElementKind::Quad8, &[corners, mids].concat(), 0);
            }
            return;
        }
        let tris = if diagonal { [[0, 1, 2], [0, 2, 3]] } else { [[0, 1, 3], [1, 2, 3]] };
        for t in tris {
            let corners: Vec<u32> = t.iter().map(|&i| self.node(c[i], map)).collect();
            if !quadratic {
                self.b.add_element(ElementKind::Tri3, &corners, 0);
            } else {
                let mids: Vec<u32> = (0..3).map(|i| self.node(mid(c[t[i]], c[t[(i + 1) % 3]]), map)).collect();
                self.b.add_element(ElementKind::Tri6, &[corners, mids].concat(), 0);
            }
        }
    }
}
