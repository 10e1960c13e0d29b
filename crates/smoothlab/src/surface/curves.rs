//! Feature curves and open boundaries as curves their nodes slide along
//! ([`Surface::slide_along_curves`]): a node with exactly two curve edges, both
//! straight (linear elements), moves along the curve — the polyline of the curve edges as
//! loaded, or an exact surface's own curve (the capped cylinder's rims) — instead of
//! staying fixed. Corners of curves (one curve edge, or three and more) stay fixed.

use std::sync::Arc;

use glam::DVec3;

use super::{Analytic, Reference, Surface};
use crate::mesh::{BoundaryNode, NONE};

/// The curves of a surface as loaded, for the nodes that slide along them.
#[derive(Clone, Debug)]
pub(crate) struct Curves {
    /// Per node, its two neighbours along the curve when it slides; `[NONE; 2]` else.
    nbrs: Vec<[u32; 2]>,
    /// The nodes' positions as loaded: the polyline the sliding nodes stay on.
    origin: Vec<DVec3>,
}

impl Curves {
    /// Whether node `n` slides along a curve.
    pub(crate) fn slides(&self, n: usize) -> bool {
        self.nbrs.get(n).is_some_and(|b| b[0] != NONE)
    }

    /// The nearest point of the polyline to `p`, walking from the segment `from` (a
    /// curve edge as loaded) to the next one while that is strictly nearer; with the
    /// segment it lies on.
    fn on_polyline(&self, p: DVec3, from: [u32; 2]) -> (DVec3, [u32; 2]) {
        let nearest = |[a, b]: [u32; 2]| {
            let (pa, pb) = (self.origin[a as usize], self.origin[b as usize]);
            let d = pb - pa;
            let t = if d.length_squared() > 0.0 { ((p - pa).dot(d) / d.length_squared()).clamp(0.0, 1.0) } else { 0.0 };
            (pa + t * d, t)
        };
        let mut seg = from;
        let (mut q, mut t) = nearest(seg);
        for _ in 0..self.origin.len() {
            // past an end that is itself a sliding node: the segment beyond it
            let (end, other) = if t <= 0.0 {
                (seg[0], seg[1])
            } else if t >= 1.0 {
                (seg[1], seg[0])
            } else {
                break;
            };
            let Some(&next) = self.nbrs[end as usize].iter().find(|&&m| m != other && m != NONE) else { break };
            let cand = [end, next];
            let (qc, tc) = nearest(cand);
            if (qc - p).length_squared() < (q - p).length_squared() {
                (seg, q, t) = (cand, qc, tc);
            } else {
                break;
            }
        }
        (q, seg)
    }
}

impl Analytic {
    /// The nearest point to `p` of the exact curve through `on` (a point of a feature
    /// curve): for the capped cylinder, the rim circle at `on`'s height.
    fn on_curve(&self, p: DVec3, on: DVec3) -> Option<DVec3> {
        match *self {
            Analytic::CappedCylinder { radius, .. } => {
                let radial = DVec3::new(p.x, p.y, 0.0).try_normalize()?;
                Some(radial * radius + DVec3::Z * on.z)
            }
            _ => None,
        }
    }
}

impl Surface {
    /// Lets the nodes of the feature curves and open boundaries slide along them (see the
    /// module docs) rather than stay fixed. When the file gave the fixed flags, the file
    /// decides and nothing changes.
    pub fn slide_along_curves(&mut self) {
        self.slide_along_curves_with(None);
    }

    /// [`slide_along_curves`](Self::slide_along_curves), with the nodes where a curve turns
    /// by more than `corner_deg` degrees held as corners (the boundary rule's feature angle,
    /// [`crate::mesh::BoundaryRule::Slide`]); every node with two straight curve edges
    /// slides where it is `None`.
    ///
    /// Under the rule the file's flags hold their nodes, as everywhere; flags on every curve
    /// node and no other (what smoothlab writes of a sample) only mark the boundary.
    pub fn slide_along_curves_with(&mut self, corner_deg: Option<f64>) {
        if self.curves.is_some() || (self.flags_given && corner_deg.is_none()) {
            return;
        }
        let on_curve = {
            let mut on = vec![false; self.points.len()];
            for &[a, b, _] in self.curve_edges.iter() {
                on[a as usize] = true;
                on[b as usize] = true;
            }
            on
        };
        self.flags_mark_only = self.flags_given && (0..self.points.len()).all(|i| self.flat.is_fixed(i) == on_curve[i]);
        let held_by_file = |i: usize| self.flags_given && !self.flags_mark_only && self.flat.is_fixed(i);
        self.corner_deg = corner_deg;
        let n = self.points.len();
        let mut count = vec![0u8; n];
        let mut nbrs = vec![[NONE; 2]; n];
        let mut curved = vec![false; n];
        for &[a, b, straight] in self.curve_edges.iter() {
            for (x, y) in [(a, b), (b, a)] {
                let c = &mut count[x as usize];
                if (*c as usize) < 2 {
                    nbrs[x as usize][*c as usize] = y;
                }
                *c = c.saturating_add(1);
                curved[x as usize] |= straight == 0;
            }
        }
        let turns_sharply = |i: usize, [a, b]: [u32; 2]| {
            corner_deg.is_some_and(|limit| {
                let p = self.points[i];
                let (u, v) = ((p - self.points[a as usize]).normalize_or_zero(), (self.points[b as usize] - p).normalize_or_zero());
                u.dot(v).clamp(-1.0, 1.0).acos().to_degrees() > limit
            })
        };
        for i in 0..n {
            if count[i] != 2 || curved[i] || self.flat.role(i) != crate::mesh::NodeRole::Corner || turns_sharply(i, nbrs[i]) || held_by_file(i) {
                nbrs[i] = [NONE; 2];
            }
        }
        let curves = Curves { nbrs, origin: self.points.clone() };
        self.flat.release(|i| curves.slides(i));
        self.curve_hint = (0..n).map(|i| [i as u32, curves.nbrs[i][0]]).collect();
        self.curves = Some(Arc::new(curves));
    }

    /// The curves' edges (open boundary edges and feature edges), each once.
    pub fn curve_edges(&self) -> impl Iterator<Item = [u32; 2]> + '_ {
        self.curve_edges.iter().map(|&[a, b, _]| [a, b])
    }

    /// What each node does while the curves slide: a curve node slides
    /// ([`BoundaryNode::Curve`]), is held by the file's flags ([`BoundaryNode::Held`]) or
    /// stays as a corner ([`BoundaryNode::Corner`]); a node off the curves is
    /// [`BoundaryNode::Interior`]. `None` while the curves are held.
    pub fn curve_nodes(&self) -> Option<Vec<BoundaryNode>> {
        self.curves.as_ref()?;
        let mut out = vec![BoundaryNode::Interior; self.points.len()];
        for [a, b] in self.curve_edges() {
            for n in [a as usize, b as usize] {
                out[n] = self.curve_node(n);
            }
        }
        Some(out)
    }

    /// What curve node `n` does while the curves slide ([`curve_nodes`](Self::curve_nodes)).
    fn curve_node(&self, n: usize) -> BoundaryNode {
        if self.slides(n) {
            BoundaryNode::Curve
        } else if self.flags_given && !self.flags_mark_only && self.flat.is_fixed(n) {
            BoundaryNode::Held
        } else {
            BoundaryNode::Corner
        }
    }

    /// Holds the curves' nodes again where [`slide_along_curves_with`](Self::slide_along_curves_with)
    /// let them slide: the boundary fixed, as the surface was read.
    pub fn hold_curves(&mut self) {
        let Some(curves) = self.curves.take() else { return };
        self.flat.hold(|i| curves.slides(i));
        self.curve_hint = Vec::new();
        self.corner_deg = None;
        self.flags_mark_only = false;
    }

    /// Whether node `n` slides along a curve.
    pub fn slides(&self, n: usize) -> bool {
        self.curves.as_ref().is_some_and(|c| c.slides(n))
    }

    /// The corner angle the curves slide by, where the boundary rule set them sliding
    /// ([`slide_along_curves_with`](Self::slide_along_curves_with)).
    pub fn boundary_corner_deg(&self) -> Option<f64> {
        self.corner_deg.filter(|_| self.curves.is_some())
    }

    /// The boundary's curves as the rule reads them: how many (the chains of curve edges
    /// between corners; a closed one with no corner is one), and per curve node whether it
    /// slides, is a corner, or is held by the file's flags.
    pub fn boundary_counts(&self) -> SurfaceBoundary {
        let n = self.points.len();
        let mut edges_of: Vec<Vec<usize>> = vec![Vec::new(); n];
        for (k, &[a, b, _]) in self.curve_edges.iter().enumerate() {
            edges_of[a as usize].push(k);
            edges_of[b as usize].push(k);
        }
        // the chains: curve edges joined at the nodes that slide
        let mut parent: Vec<usize> = (0..self.curve_edges.len()).collect();
        fn root(parent: &mut [usize], mut k: usize) -> usize {
            while parent[k] != k {
                parent[k] = parent[parent[k]];
                k = parent[k];
            }
            k
        }
        let mut out = SurfaceBoundary::default();
        for (i, edges) in edges_of.iter().enumerate().filter(|(_, e)| !e.is_empty()) {
            match self.curve_node(i) {
                BoundaryNode::Curve => {
                    out.sliding += 1;
                    let (r0, r1) = (root(&mut parent, edges[0]), root(&mut parent, edges[1]));
                    parent[r0] = r1;
                }
                BoundaryNode::Held => out.held += 1,
                _ => out.corners += 1,
            }
        }
        out.curves = (0..parent.len()).filter(|&k| root(&mut parent, k) == k).count();
        out
    }

    /// The largest distance of a sliding node from its curve as loaded.
    pub fn max_distance_from_curves(&self) -> f64 {
        let Some(curves) = &self.curves else { return 0.0 };
        (0..self.points.len())
            .filter(|&i| curves.slides(i))
            .map(|i| {
                let p = self.points[i];
                let on = match &*self.reference {
                    Reference::Analytic(a) => a.on_curve(p, curves.origin[i]),
                    _ => None,
                };
                let q = on.unwrap_or_else(|| curves.on_polyline(p, self.curve_hint[i]).0);
                (q - p).length()
            })
            .fold(0.0, f64::max)
    }
}

/// What [`Surface::boundary_counts`] reads of a surface's curves.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SurfaceBoundary {
    pub curves: usize,
    pub sliding: usize,
    pub corners: usize,
    pub held: usize,
}

impl Surface {
    /// Moves sliding node `n` to the nearest point of its curve to `p`.
    pub(crate) fn slide_to(&mut self, n: usize, p: DVec3) {
        let Some(curves) = self.curves.clone() else { return };
        if let Reference::Analytic(a) = &*self.reference {
            if let Some(q) = a.on_curve(p, curves.origin[n]) {
                self.points[n] = q;
                return;
            }
        }
        let (q, seg) = curves.on_polyline(p, self.curve_hint[n]);
        self.points[n] = q;
        self.curve_hint[n] = seg;
    }
}
