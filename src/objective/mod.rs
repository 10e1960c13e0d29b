//! Objective functions of one free node over its star.
//!
//! Every objective implements [`Objective`]: per-term values with their gradients
//! (one term per star element for most objectives, several for angle-based ones), and
//! how the terms combine — summed and minimised (smooth objectives, solved by
//! Fletcher–Reeves) or their minimum maximised (the non-smooth max-min objectives, solved
//! by Freitag's active-set ascent). Solvers and drivers see only this trait, so adding
//! an objective never touches them.

use glam::DVec2;

use crate::mesh::{ElementKind, Mesh, NodeRole};

/// How an objective's terms combine, and which way is better.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Goal {
    /// Minimise the sum of the terms (a smooth objective).
    MinimizeSum,
    /// Maximise the minimum of the terms (a non-smooth max-min objective).
    MaximizeMin,
}

/// One term of an objective at a position, with its gradient with respect to the
/// free node's position.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Term {
    /// Index of the element in [`Star::elems`] the term belongs to.
    pub elem: u32,
    pub value: f64,
    pub grad: DVec2,
}

/// One element of a star, with its node coordinates and where the free node sits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StarElement {
    pub kind: ElementKind,
    /// Element index in the mesh.
    pub element: u32,
    /// Node coordinates in element order (first `kind.node_count()` used).
    pub pts: [DVec2; 9],
    /// Local index of the free node (a corner) in the element.
    pub slot: u8,
    /// Whether the mid-side node of the edge leaving the free node forward (to the next
    /// corner) / backward (to the previous corner) follows it, staying at the midpoint
    /// of the straight edge. False on linear elements and on curved boundary edges.
    pub follow_next: bool,
    pub follow_prev: bool,
}

impl StarElement {
    /// The element's node coordinates with the free node at `x` (and following mid-side
    /// nodes at their edge midpoints).
    pub fn at(&self, x: DVec2) -> [DVec2; 9] {
        let mut p = self.pts;
        let k = self.kind.corners();
        let s = self.slot as usize;
        p[s] = x;
        if self.follow_next {
            p[k + s] = 0.5 * (x + p[(s + 1) % k]);
        }
        if self.follow_prev {
            let prev = (s + k - 1) % k;
            p[k + prev] = 0.5 * (x + p[prev]);
        }
        p
    }
}

/// The star of a free node: the elements that contain it, gathered once per visit.
/// A `Star` is a reusable scratch buffer: [`Star::gather`] clears and refills it.
#[derive(Clone, Debug, Default)]
pub struct Star {
    /// The free node.
    pub node: u32,
    /// Its position when gathered.
    pub x0: DVec2,
    pub elems: Vec<StarElement>,
    /// True when the mesh has both triangles and quads (Chen's ×3 triangle weight applies).
    pub mixed: bool,
}

impl Star {
    pub fn new() -> Self {
        Self::default()
    }
    /// Fills the star of `node` from `mesh`.
    pub fn gather(&mut self, mesh: &Mesh, node: usize) {
        self.node = node as u32;
        self.x0 = mesh.nodes[node];
        self.mixed = mesh.has_triangles() && mesh.has_quads();
        self.elems.clear();
        for &e in mesh.node_elements(node) {
            let e = e as usize;
            let kind = mesh.kind(e);
            let ids = mesh.element(e);
            let k = kind.corners();
            let Some(slot) = ids[..k].iter().position(|&i| i as usize == node) else {
                continue; // the node is a mid-side node of this element: not a corner star
            };
            let follows = |edge: usize| {
                kind.mid(edge).is_some_and(|m| {
                    let mid = ids[m] as usize;
                    !mesh.fixed[mid] && !mesh.is_on_curved_boundary(mid) && mesh.role(mid) == NodeRole::Mid
                })
            };
            self.elems.push(StarElement {
                kind,
                element: e as u32,
                pts: mesh.element_points_array(e),
                slot: slot as u8,
                follow_next: follows(slot),
                follow_prev: follows((slot + k - 1) % k),
            });
        }
    }
    pub fn len(&self) -> usize {
        self.elems.len()
    }
    pub fn is_empty(&self) -> bool {
        self.elems.is_empty()
    }
}

/// An objective of a free node's position over its star (see the module docs).
pub trait Objective {
    /// A short name, as on the command line (`new`, `old`, …).
    fn name(&self) -> &'static str;
    /// How the terms combine.
    fn goal(&self) -> Goal;
    /// Appends the terms at position `x` (values and gradients) to `out`.
    fn terms(&self, star: &Star, x: DVec2, out: &mut Vec<Term>);
    /// The objective value at `x`: the sum or the minimum of the terms.
    fn value(&self, star: &Star, x: DVec2) -> f64 {
        self.value_and_gradient(star, x).0
    }
    /// Value and gradient at `x`. For a max-min objective the gradient is that of one
    /// active (minimum) term — a subgradient; Freitag's solver uses [`terms`](Self::terms).
    fn value_and_gradient(&self, star: &Star, x: DVec2) -> (f64, DVec2) {
        let mut t = Vec::with_capacity(star.len() * 3);
        self.terms(star, x, &mut t);
        combine(self.goal(), &t)
    }
}

/// Combines terms by the goal: sum (with summed gradient) or minimum (with the gradient
/// of the first minimal term). An empty set gives 0.
pub fn combine(goal: Goal, terms: &[Term]) -> (f64, DVec2) {
    match goal {
        Goal::MinimizeSum => terms.iter().fold((0.0, DVec2::ZERO), |(v, g), t| (v + t.value, g + t.grad)),
        Goal::MaximizeMin => terms
            .iter()
            .fold(None, |best: Option<&Term>, t| match best {
                Some(b) if b.value <= t.value => Some(b),
                _ => Some(t),
            })
            .map(|t| (t.value, t.grad))
            .unwrap_or((0.0, DVec2::ZERO)),
    }
}
