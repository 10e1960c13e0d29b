//! Small objectives with known optima for the solver and driver tests, and a few meshes
//! to hang them on. Finite-difference gradients appear only here.

use glam::DVec2;

use crate::mesh::{ElementKind, Mesh, MeshBuilder};
use crate::objective::{Goal, Objective, Star, Term};
use crate::quality::element_quality;

/// A regular hexagon of six unit triangles around node 0 at the origin (star size 1).
pub fn hexagon(centre: DVec2) -> Mesh {
    let mut b = MeshBuilder::new();
    b.add_node([centre.x, centre.y, 0.0], 0);
    for i in 0..6 {
        let a = i as f64 * std::f64::consts::PI / 3.0;
        b.add_node([a.cos(), a.sin(), 0.0], 0);
    }
    for i in 0..6u32 {
        b.add_element(ElementKind::Tri3, &[0, 1 + i, 1 + (i + 1) % 6], 0);
    }
    b.build().expect("hexagon")
}

/// The star of node 0 of [`hexagon`] with the centre at the origin.
pub fn unit_star() -> Star {
    let mut s = Star::new();
    s.gather(&hexagon(DVec2::ZERO), 0);
    s
}

/// An anisotropic bowl `d.x² + 4·d.y²`, `d = x − c` (minimised), with a barrier right of
/// `wall`: +∞ there (the level-set views' hatched region).
pub struct WalledBowl {
    pub c: DVec2,
    pub wall: f64,
}

impl Objective for WalledBowl {
    fn name(&self) -> &'static str {
        "bowl"
    }
    fn goal(&self) -> Goal {
        Goal::MinimizeSum
    }
    fn terms(&self, _star: &Star, x: DVec2, out: &mut Vec<Term>) {
        let d = x - self.c;
        let (value, grad) = if x.x > self.wall {
            (f64::INFINITY, DVec2::ZERO)
        } else {
            (d.x * d.x + 4.0 * d.y * d.y, DVec2::new(2.0 * d.x, 8.0 * d.y))
        };
        out.push(Term { elem: 0, value, grad });
    }
}

/// `(x − c)ᵀ A (x − c)` with symmetric positive definite `A`: minimum 0 at `c`.
pub struct Bowl {
    pub centre: DVec2,
    pub a: [[f64; 2]; 2],
}

impl Bowl {
    /// An elongated bowl: eigenvalues 1 and `ratio`, axes rotated by `angle`.
    pub fn elongated(centre: DVec2, ratio: f64, angle: f64) -> Self {
        let (s, c) = angle.sin_cos();
        // R diag(1, ratio) Rᵀ
        let a = [[c * c + ratio * s * s, (1.0 - ratio) * c * s], [(1.0 - ratio) * c * s, s * s + ratio * c * c]];
        Bowl { centre, a }
    }
    fn mul(&self, v: DVec2) -> DVec2 {
        DVec2::new(self.a[0][0] * v.x + self.a[0][1] * v.y, self.a[1][0] * v.x + self.a[1][1] * v.y)
    }
}

impl Objective for Bowl {
    fn name(&self) -> &'static str {
        "bowl"
    }
    fn goal(&self) -> Goal {
        Goal::MinimizeSum
    }
    fn terms(&self, _star: &Star, x: DVec2, out: &mut Vec<Term>) {
        let d = x - self.centre;
        let ad = self.mul(d);
        out.push(Term { elem: 0, value: d.dot(ad), grad: 2.0 * ad });
    }
    fn value_gradient_hessian(&self, star: &Star, x: DVec2) -> Option<(f64, DVec2, glam::DMat2)> {
        let (v, g) = self.value_and_gradient(star, x);
        let a = glam::DMat2::from_cols(DVec2::new(self.a[0][0], self.a[1][0]), DVec2::new(self.a[0][1], self.a[1][1]));
        Some((v, g, a * 2.0))
    }
}

/// A Rosenbrock-like valley `(1 − x)² + b·(y − x²)²`: minimum 0 at (1, 1).
pub struct Rosenbrock {
    pub b: f64,
}

impl Objective for Rosenbrock {
    fn name(&self) -> &'static str {
        "rosenbrock"
    }
    fn goal(&self) -> Goal {
        Goal::MinimizeSum
    }
    fn terms(&self, _star: &Star, p: DVec2, out: &mut Vec<Term>) {
        let r = p.y - p.x * p.x;
        let value = (1.0 - p.x).powi(2) + self.b * r * r;
        let grad = DVec2::new(-2.0 * (1.0 - p.x) - 4.0 * self.b * p.x * r, 2.0 * self.b * r);
        out.push(Term { elem: 0, value, grad });
    }
}

/// `|x − (1, 0)|² − ln(1/2 − x)` for `x < 1/2`, `+∞` beyond: a barrier whose minimum is
/// at the origin (`2(x − 1) + 1/(1/2 − x) = 0` ⇒ `x = 0`).
pub struct LogBarrier;

impl Objective for LogBarrier {
    fn name(&self) -> &'static str {
        "log-barrier"
    }
    fn goal(&self) -> Goal {
        Goal::MinimizeSum
    }
    fn terms(&self, _star: &Star, p: DVec2, out: &mut Vec<Term>) {
        let c = DVec2::new(1.0, 0.0);
        let room = 0.5 - p.x;
        if room <= 0.0 {
            out.push(Term { elem: 0, value: f64::INFINITY, grad: DVec2::ZERO });
            return;
        }
        let value = (p - c).length_squared() - room.ln();
        let grad = 2.0 * (p - c) + DVec2::new(1.0 / room, 0.0);
        out.push(Term { elem: 0, value, grad });
    }
}

/// `max min_i (a_i·x + b_i)` over three linear functions with gradients 120° apart,
/// all equal (to 0) at `peak`, which is the unique maximiser.
pub struct ThreePlanes {
    pub peak: DVec2,
    pub scale: [f64; 3],
}

impl ThreePlanes {
    fn grad(&self, i: usize) -> DVec2 {
        let a = std::f64::consts::TAU * i as f64 / 3.0 + 0.3;
        self.scale[i] * DVec2::new(a.cos(), a.sin())
    }
}

impl Objective for ThreePlanes {
    fn name(&self) -> &'static str {
        "three-planes"
    }
    fn goal(&self) -> Goal {
        Goal::MaximizeMin
    }
    fn terms(&self, _star: &Star, x: DVec2, out: &mut Vec<Term>) {
        for i in 0..3 {
            let g = self.grad(i);
            out.push(Term { elem: i as u32, value: g.dot(x - self.peak), grad: g });
        }
    }
}

/// The shape metric (α / β) of each star element at `x`.
pub fn element_shape_at(star: &Star, i: usize, x: DVec2) -> f64 {
    let e = &star.elems[i];
    let n = e.kind.node_count();
    element_quality(e.kind, &e.at(x)[..n]).shape
}

fn fd_grad(f: impl Fn(DVec2) -> f64, x: DVec2, h: f64) -> DVec2 {
    let dx = DVec2::new(h, 0.0);
    let dy = DVec2::new(0.0, h);
    DVec2::new((f(x + dx) - f(x - dx)) / (2.0 * h), (f(x + dy) - f(x - dy)) / (2.0 * h))
}

/// The "old" objective for tests: maximise the minimum element α/β over the star, with
/// central-difference gradients.
pub struct ShapeMaxMin;

impl Objective for ShapeMaxMin {
    fn name(&self) -> &'static str {
        "shape-max-min"
    }
    fn goal(&self) -> Goal {
        Goal::MaximizeMin
    }
    fn terms(&self, star: &Star, x: DVec2, out: &mut Vec<Term>) {
        let h = 1e-7 * crate::objective::star_scale(star).max(f64::MIN_POSITIVE);
        for i in 0..star.len() {
            let f = |p: DVec2| element_shape_at(star, i, p);
            out.push(Term { elem: i as u32, value: f(x), grad: fd_grad(f, x, h) });
        }
    }
}

/// A smooth objective for tests: `Σ (1 − q_e)²` over the star's α/β, finite differences.
pub struct ShapeSum;

impl Objective for ShapeSum {
    fn name(&self) -> &'static str {
        "shape-sum"
    }
    fn goal(&self) -> Goal {
        Goal::MinimizeSum
    }
    fn terms(&self, star: &Star, x: DVec2, out: &mut Vec<Term>) {
        let h = 1e-7 * crate::objective::star_scale(star).max(f64::MIN_POSITIVE);
        for i in 0..star.len() {
            let f = |p: DVec2| (1.0 - element_shape_at(star, i, p)).powi(2);
            out.push(Term { elem: i as u32, value: f(x), grad: fd_grad(f, x, h) });
        }
    }
}
