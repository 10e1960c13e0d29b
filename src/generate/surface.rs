//! Surface samples on exact surfaces: a sphere and a capped cylinder from the lattice of a
//! cube's surface (the sphere's a cube-sphere, the cylinder's caps discs with a feature
//! edge at each rim), and a torus from a periodic grid. Quads, triangles (each quad
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
/// cells along each edge of the cube (sphere, cylinder), or four times as many round the
/// torus's tube and twelve times round its axis. Its reference is the exact surface.
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
    let mut s = Lattice { kind, order, m: n * order as i64, ids: HashMap::new(), b: MeshBuilder::new() };
    let analytic = match shape {
        SurfaceShape::Sphere | SurfaceShape::Cylinder => {
            let map = |l: [i64; 3], m: i64| {
                // the cube [-1, 1]³ at lattice step 2/m
                let c = l.map(|v| 2.0 * v as f64 / m as f64 - 1.0);
                match shape {
                    // equal-angle cube-sphere: tan spreads the nodes evenly in angle
                    SurfaceShape::Sphere => DVec3::from(c.map(|v| (v * FRAC_PI_4).tan())).normalize(),
                    // the elliptical square-to-disc map takes the square's sides to the circle
                    _ => {
                        let (x, y) = (c[0], c[1]);
                        DVec3::new(x * (1.0 - y * y / 2.0).sqrt(), y * (1.0 - x * x / 2.0).sqrt(), c[2])
                    }
                }
            };
            for face in 0..6 {
                let axis = face / 2;
                let side = if face % 2 == 0 { 0 } else { n };
                // (u, v) span the face; u × v points out of the cube
                let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
                let (u, v) = if face % 2 == 0 { (v, u) } else { (u, v) };
                for i in 0..n {
                    for j in 0..n {
                        let at = |du: i64, dv: i64| {
                            let mut l = [0i64; 3];
                            l[axis] = side;
                            l[u] = i + du;
                            l[v] = j + dv;
                            l
                        };
                        s.cell([at(0, 0), at(1, 0), at(1, 1), at(0, 1)], (i + j) % 2 == 0, &|l, m| map(l, m));
                    }
                }
            }
            match shape {
                SurfaceShape::Sphere => Analytic::Sphere { centre: DVec3::ZERO, radius: 1.0 },
                _ => Analytic::CappedCylinder { radius: 1.0, z0: -1.0, z1: 1.0 },
            }
        }
        SurfaceShape::Torus => {
            let (major, minor) = (3.0, 1.0);
            // four cells round the tube per unit of resolution (22.5° apart at 4: under the
            // feature angle), three times as many round the axis (its circle is 3 times longer)
            let (around, tube) = (12 * n, 4 * n);
            // lattice (i, j, 0): i round the axis, j round the tube, both periodic
            let map = |l: [i64; 3], m: i64| {
                let scale = m / n; // lattice steps per cell: 1 or 2
                let (a, b) = (l[0].rem_euclid(around * scale), l[1].rem_euclid(tube * scale));
                let theta = 2.0 * PI * a as f64 / (around * scale) as f64;
                let phi = 2.0 * PI * b as f64 / (tube * scale) as f64;
                let r = major + minor * phi.cos();
                DVec3::new(r * theta.cos(), r * theta.sin(), minor * phi.sin())
            };
            for i in 0..around {
                for j in 0..tube {
                    let l = |di: i64, dj: i64| [i + di, j + dj, 0];
                    s.cell([l(0, 0), l(1, 0), l(1, 1), l(0, 1)], (i + j) % 2 == 0, &|l, m| map(l, m));
                }
            }
            Analytic::Torus { major, minor }
        }
    };
    s.b.build_surface(Some(analytic))
}

/// The elements of a sample as they are made: lattice points (at twice the resolution for
/// quadratic elements) mapped onto the surface, each made a node once.
struct Lattice {
    kind: SurfaceKind,
    order: u8,
    /// Lattice steps along a cube edge (round the torus's tube): the resolution times
    /// the order.
    m: i64,
    /// Node of each lattice point, by its mapped position's bits (periodic lattices meet
    /// themselves where the map does).
    ids: HashMap<[u64; 3], u32>,
    b: MeshBuilder,
}

impl Lattice {
    fn node(&mut self, l: [i64; 3], map: &dyn Fn([i64; 3], i64) -> DVec3) -> u32 {
        let p = map(l, self.m);
        // −0 and 0 are one point
        let key = p.to_array().map(|c| (c + 0.0).to_bits());
        if let Some(&id) = self.ids.get(&key) {
            return id;
        }
        let id = self.b.add_node(p.to_array(), 0) as u32;
        self.ids.insert(key, id);
        id
    }

    /// One lattice cell with corners `c` (counter-clockwise seen from outside): a quad,
    /// or two triangles (split along `c0–c2` when `diagonal`, else `c1–c3`).
    fn cell(&mut self, c: [[i64; 3]; 4], diagonal: bool, map: &dyn Fn([i64; 3], i64) -> DVec3) {
        let o = self.order as i64;
        let m = |l: [i64; 3]| l.map(|v| v * o);
        let mid = |a: [i64; 3], b: [i64; 3]| [0, 1, 2].map(|i| (a[i] * o + b[i] * o) / 2);
        let split = match self.kind {
            SurfaceKind::Quad => false,
            SurfaceKind::Tri => true,
            SurfaceKind::Mixed => diagonal,
        };
        let lat = |this: &mut Self, l: [i64; 3]| this.node(l, map);
        if !split {
            let corners: Vec<u32> = c.iter().map(|&l| lat(self, m(l))).collect();
            if o == 1 {
                self.b.add_element(ElementKind::Quad4, &corners, 0);
            } else {
                let mids: Vec<u32> = (0..4).map(|i| lat(self, mid(c[i], c[(i + 1) % 4]))).collect();
                self.b.add_element(ElementKind::Quad8, &[corners, mids].concat(), 0);
            }
            return;
        }
        let tris = if diagonal { [[0, 1, 2], [0, 2, 3]] } else { [[0, 1, 3], [1, 2, 3]] };
        for t in tris {
            let corners: Vec<u32> = t.iter().map(|&i| lat(self, m(c[i]))).collect();
            if o == 1 {
                self.b.add_element(ElementKind::Tri3, &corners, 0);
            } else {
                let mids: Vec<u32> = (0..3).map(|i| lat(self, mid(c[t[i]], c[t[(i + 1) % 3]]))).collect();
                self.b.add_element(ElementKind::Tri6, &[corners, mids].concat(), 0);
            }
        }
    }
}
