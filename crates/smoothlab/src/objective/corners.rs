//! The geometry every objective shares: a star element's corner edge vectors at a
//! trial position of the free node, and how each moves with that position.
//!
//! Every node of a star element is an affine function of the free node's position `x`
//! with a *scalar* weight: 1 for the free node itself, ½ for a mid-side node that follows
//! it (it stays at the midpoint of its straight edge), 0 for everything else. The corner
//! edge vectors of [`quality::corner_edge_vectors`] (chords, or the end tangents `4M − 3P0 − P2`
//! of quadratic edges) are linear in the node coordinates with scalar coefficients, so
//! each edge vector is `e = c·x + const` for a scalar `c`, and its Jacobian is `c·I`.
//! The chain rule from a metric's partials `∂q/∂e1`, `∂q/∂e2` to `∂q/∂x` is then just
//! `c1·∂q/∂e1 + c2·∂q/∂e2` ([`CornerJet::chain`]). We get `c` by applying `corner_edge_vectors`
//! itself to the node weights, so the derivative can never disagree with the geometry.

use glam::DVec2;

use super::StarElement;
use crate::mesh::ElementKind;
use crate::quality;

/// The two edge vectors at one corner at the trial position, with their weights:
/// `e1 = c1·x + const`, `e2 = c2·x + const`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CornerJet {
    /// Towards the next corner (tangent for quadratic edges).
    pub e1: DVec2,
    /// Towards the previous corner.
    pub e2: DVec2,
    pub c1: f64,
    pub c2: f64,
}

impl CornerJet {
    /// Whether the corner changes when the free node moves.
    pub fn moves(&self) -> bool {
        self.c1 != 0.0 || self.c2 != 0.0
    }
    /// `∂q/∂x` from the partials of a corner metric `q(e1, e2)`.
    pub fn chain(&self, g1: DVec2, g2: DVec2) -> DVec2 {
        self.c1 * g1 + self.c2 * g2
    }
}

/// The scalar weights `(c1, c2)` of corner `i`'s edge vectors: the formula of
/// [`quality::corner_edge_vectors`] applied to the node weights (the same arithmetic on one
/// coordinate, so the weights agree with the geometry exactly).
#[inline]
fn corner_edge_weights(kind: ElementKind, w: &[f64; 9], i: usize) -> (f64, f64) {
    let k = kind.corners();
    let next = (i + 1) % k;
    let prev = (i + k - 1) % k;
    match (kind.mid(i), kind.mid(prev)) {
        (Some(m_next), Some(m_prev)) => (4.0 * w[m_next] - 3.0 * w[i] - w[next], 4.0 * w[m_prev] - 3.0 * w[i] - w[prev]),
        _ => (w[next] - w[i], w[prev] - w[i]),
    }
}

/// One star element evaluated at a trial position: node coordinates, node weights
/// (`∂node/∂x`, a scalar per node) and the corner jets.
#[derive(Clone, Copy, Debug)]
pub struct ElementJets {
    pub kind: ElementKind,
    /// Local index of the free corner.
    pub slot: usize,
    pub pts: [DVec2; 9],
    pub weights: [f64; 9],
    pub corners: [CornerJet; 4],
}

impl ElementJets {
    /// Evaluates `el` with its free node at `x`.
    #[inline]
    pub fn new(el: &StarElement, x: DVec2) -> Self {
        let kind = el.kind;
        let k = kind.corners();
        let n = kind.node_count();
        let s = el.slot as usize;
        let pts = el.at(x);
        let mut weights = [0.0; 9];
        weights[s] = 1.0;
        if el.follow_next {
            weights[k + s] = 0.5;
        }
        if el.follow_prev {
            weights[k + (s + k - 1) % k] = 0.5;
        }
        let edges = quality::corner_edge_vectors(kind, &pts[..n]);
        let mut corners = [CornerJet::default(); 4];
        for i in 0..k {
            let (c1, c2) = corner_edge_weights(kind, &weights, i);
            corners[i] = CornerJet { e1: edges[i].0, e2: edges[i].1, c1, c2 };
        }
        ElementJets { kind, slot: s, pts, weights, corners }
    }

    /// Each corner's edge pair and weights in its frame `frames[i]` ([`crate::target::in_frame`]):
    /// the corners as their targets measure them. The chords ([`chord`](Self::chord)) stay.
    #[inline]
    pub fn in_frames(&mut self, frames: &[glam::DMat2; 4]) {
        for (c, m) in self.corners[..self.kind.corners()].iter_mut().zip(frames) {
            (c.e1, c.e2) = crate::target::in_frame(m, c.e1, c.e2);
            (c.c1, c.c2) = crate::target::in_frame(m, c.c1, c.c2);
        }
    }

    /// The jets of the corners, only the meaningful ones.
    pub fn corner_jets(&self) -> &[CornerJet] {
        &self.corners[..self.kind.corners()]
    }

    /// The straight chord from corner `u` to corner `v` with its weight.
    pub fn chord(&self, u: usize, v: usize) -> (DVec2, f64) {
        (self.pts[v] - self.pts[u], self.weights[v] - self.weights[u])
    }

    /// The direction from corner `u` towards corner `v` as seen at `u`: the element edge
    /// vector (end tangent of a quadratic edge) when `u`, `v` share an edge, the chord
    /// otherwise (a quad's diagonal is straight).
    pub fn dir(&self, u: usize, v: usize) -> (DVec2, f64) {
        let k = self.kind.corners();
        let c = &self.corners[u];
        if v == (u + 1) % k {
            (c.e1, c.c1)
        } else if v == (u + k - 1) % k {
            (c.e2, c.c2)
        } else {
            self.chord(u, v)
        }
    }
}
