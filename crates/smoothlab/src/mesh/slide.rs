//! Boundaries that slide (issue 58), what planar and volume meshes share: the rule, each
//! node's part in it, and the feature curves as polylines their nodes slide along.
//!
//! A curve is a run of feature edges joined through nodes of exactly two whose directions
//! turn by at most the feature angle. A node on one feature edge, or on three or more, or
//! where its curve turns, is a corner and stays. A node the file fixed stays.
//!
//! A planar mesh's boundary is its feature curves: its edges of one element. A node where
//! the boundary turns by more than the feature angle is a corner, unless an element of
//! either edge was inverted as loaded (a fold is not a corner). The others slide along the
//! boundary as loaded ([`Mesh::set_boundary`]). A quadratic element's boundary edge is the
//! quadratic through its corners and mid-side node ([`Piece`]); a sliding corner carries
//! the mid-side nodes of its boundary edges along the curve ([`Chains`]).

use std::ops::{Add, Mul, Sub};
use std::sync::Arc;

use glam::{DVec2, DVec3};

use super::chain::Chains;
use super::piece::Piece;
use super::{Mesh, NodeRole, NONE};

crate::enum_with_names! {
    /// What boundary nodes do (the command line's `--boundary`).
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
    #[serde(rename_all = "kebab-case")]
    pub enum BoundaryRule {
        /// Boundary nodes stay where the file put them: the papers' setting.
        #[default]
        Fixed => ("fixed", "boundary nodes stay where the file put them (the papers)"),
        /// Boundary nodes slide on the boundary as loaded; feature curves hold their nodes.
        Slide => ("slide", "boundary nodes slide on the boundary as loaded, along its feature curves; corners stay"),
    }
}

impl BoundaryRule {
    /// The rule with command-line name `s` (exact, lowercase), if any.
    pub fn parse(s: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|r| r.name() == s)
    }
}

/// The default feature angle, degrees: two boundary faces (a planar mesh's boundary
/// edges) that turn by more meet at a feature curve (a corner). Chosen on Livesu et al.'s
/// eleven real hexahedral meshes (defaults plus sliding; `docs/reproduction.md` §13): 30°,
/// 45° and 60° untangled 9, 8 and 8 of them and reached the published smallest scaled
/// Jacobian on 3, 4 and 5. A coarse mesh of an organic shape turns by 30° between faces in
/// many places that are no crease; a CAD part's edges turn by 90°.
pub const FEATURE_ANGLE_DEG: f64 = 60.0;

/// The shortest feature curve kept where it ends at no other feature curve, in edges.
pub const MIN_CURVE_SEGMENTS: usize = 3;

/// What a node does under the sliding rule.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BoundaryNode {
    /// Off the boundary: moves as before.
    Interior,
    /// Fixed by the file, or not a corner of any element.
    Held,
    /// Where feature curves meet or one turns or ends: stays.
    Corner,
    /// On a feature curve: slides along it.
    Curve,
    /// On a smooth part of a volume's boundary: slides on it.
    Surface,
}

impl BoundaryNode {
    /// Whether the node slides (on a curve or a surface).
    #[inline]
    pub fn slides(self) -> bool {
        matches!(self, BoundaryNode::Curve | BoundaryNode::Surface)
    }
}

/// The coordinates a curve lies in: [`DVec2`] or [`DVec3`].
pub(crate) trait Coords: Copy + PartialEq + Add<Output = Self> + Sub<Output = Self> + Mul<f64, Output = Self> {
    fn dot(self, other: Self) -> f64;
    /// The unit vector along `self`, or zero.
    fn unit(self) -> Self;
}

macro_rules! coords_by_glam {
    ($v:ty) => {
        impl Coords for $v {
            #[inline]
            fn dot(self, other: Self) -> f64 {
                <$v>::dot(self, other)
            }
            #[inline]
            fn unit(self) -> Self {
                self.normalize_or_zero()
            }
        }
    };
}
coords_by_glam!(DVec2);
coords_by_glam!(DVec3);

/// Feature edges joined into curves over the positions as loaded, and each node's class
/// by them.
#[derive(Debug)]
pub(crate) struct Curves<P> {
    /// The positions as loaded: the polylines the curve nodes stay on.
    points: Vec<P>,
    /// The feature edges, sorted.
    pub(crate) segments: Vec<[u32; 2]>,
    /// Per segment, the mid-side node of the quadratic element's edge it is ([`NONE`] for
    /// a straight one); empty where every segment is straight.
    pub(crate) mids: Vec<u32>,
    /// CSR: the segments at each node.
    seg_start: Vec<u32>,
    node_segs: Vec<u32>,
    pub(crate) class: Vec<BoundaryNode>,
    /// Per segment, its curve.
    pub(crate) curve: Vec<u32>,
    pub(crate) count: usize,
}

impl<P: Coords> Curves<P> {
    /// The curves of feature edges `segments` (sorted; quadratic where `mids`, empty or
    /// one a segment, gives a mid-side node) over `points`, whose boundary nodes are
    /// `on_boundary`; `held` nodes stay, and a node where its two edges' tangents turn by
    /// more than the feature angle (`cos_feature`) is a corner, unless it is `folded`.
    pub(crate) fn new(
        points: &[P],
        on_boundary: &[bool],
        held: &[bool],
        folded: &[bool],
        segments: Vec<[u32; 2]>,
        mids: Vec<u32>,
        cos_feature: f64,
    ) -> Curves<P> {
        let n = points.len();
        let mut pairs: Vec<(u32, u32)> =
            segments.iter().enumerate().flat_map(|(s, &[a, b])| [(a, s as u32), (b, s as u32)]).collect();
        let (seg_start, node_segs) = csr(n, &mut pairs);
        let segs_at = |v: usize| &node_segs[seg_start[v] as usize..seg_start[v + 1] as usize];
        let class: Vec<BoundaryNode> = (0..n)
            .map(|v| {
                if !on_boundary[v] {
                    return if held[v] { BoundaryNode::Held } else { BoundaryNode::Interior };
                }
                if held[v] {
                    return BoundaryNode::Held;
                }
                match *segs_at(v) {
                    [] => BoundaryNode::Surface,
                    [s, t] => {
                        // the directions the two pieces leave v in: the first reversed
                        let leaving = |s: u32| {
                            let s = s as usize;
                            piece_of(points, &segments, &mids, s).leaving(segments[s][1] as usize == v)
                        };
                        let (u, w) = ((leaving(s) * -1.0).unit(), leaving(t).unit());
                        if u.dot(w) < cos_feature && !folded[v] {
                            BoundaryNode::Corner
                        } else {
                            BoundaryNode::Curve
                        }
                    }
                    _ => BoundaryNode::Corner,
                }
            })
            .collect();
        // segments joined through curve nodes
        let mut curve = vec![u32::MAX; segments.len()];
        let mut count = 0u32;
        for s0 in 0..segments.len() {
            if curve[s0] != u32::MAX {
                continue;
            }
            let mut stack = vec![s0 as u32];
            curve[s0] = count;
            while let Some(s) = stack.pop() {
                for &v in &segments[s as usize] {
                    if class[v as usize] != BoundaryNode::Curve {
                        continue;
                    }
                    for &t in segs_at(v as usize) {
                        if curve[t as usize] == u32::MAX {
                            curve[t as usize] = count;
                            stack.push(t);
                        }
                    }
                }
            }
            count += 1;
        }
        Curves { points: points.to_vec(), segments, mids, seg_start, node_segs, class, curve, count: count as usize }
    }

    /// Segment `s` as a piece of its curve.
    pub(crate) fn piece(&self, s: u32) -> Piece<P> {
        piece_of(&self.points, &self.segments, &self.mids, s as usize)
    }

    /// The segments at node `v`.
    pub(crate) fn segs_at(&self, v: usize) -> &[u32] {
        &self.node_segs[self.seg_start[v] as usize..self.seg_start[v + 1] as usize]
    }

    /// The nearest point of segment `s` to `p`, and its parameter there.
    fn on_segment(&self, p: P, s: u32) -> (P, f64) {
        self.piece(s).nearest(p)
    }

    /// The nearest point to `p` of the curve of segment `hint`, by a walk from it over
    /// the segments of the same curve while the distance falls.
    pub(crate) fn on_curve(&self, p: P, hint: u32) -> Foot<P> {
        let curve = self.curve[hint as usize];
        let (mut s, (mut q, mut t)) = (hint, self.on_segment(p, hint));
        let mut d = (q - p).dot(q - p);
        for _ in 0..self.segments.len() {
            let mut best = (d, s, q, t);
            for &v in &self.segments[s as usize] {
                for &r in self.segs_at(v as usize) {
                    if r != s && self.curve[r as usize] == curve {
                        let (qr, tr) = self.on_segment(p, r);
                        let dr = (qr - p).dot(qr - p);
                        if dr < best.0 {
                            best = (dr, r, qr, tr);
                        }
                    }
                }
            }
            if best.1 == s {
                break;
            }
            (d, s, q, t) = best;
        }
        Foot { point: q, tangent: self.piece(s).derivative(t).unit(), segment: s, t }
    }

    /// The unit direction of segment `s` at parameter `t`, as [`on_curve`](Self::on_curve)
    /// finds it there (a straight segment's is the same everywhere).
    fn direction(&self, s: u32, t: f64) -> P {
        self.piece(s).derivative(t).unit()
    }

    /// The distance of `x` from the whole curve of segment `hint`.
    pub(crate) fn distance(&self, x: P, hint: u32) -> f64 {
        let curve = self.curve[hint as usize];
        (0..self.segments.len() as u32)
            .filter(|&s| self.curve[s as usize] == curve)
            .map(|s| {
                let q = self.on_segment(x, s).0;
                (q - x).dot(q - x).sqrt()
            })
            .fold(f64::INFINITY, f64::min)
    }
}

/// Where a point lies on a curve ([`Curves::on_curve`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Foot<P> {
    pub(crate) point: P,
    /// The curve's unit direction there.
    pub(crate) tangent: P,
    pub(crate) segment: u32,
    /// The parameter of `point` on its segment's [`Piece`].
    pub(crate) t: f64,
}

/// Segment `s` of `segments` over `points` as a piece: quadratic where `mids` gives it a
/// mid-side node.
fn piece_of<P: Coords>(points: &[P], segments: &[[u32; 2]], mids: &[u32], s: usize) -> Piece<P> {
    let [a, b] = segments[s].map(|v| points[v as usize]);
    match mids.get(s) {
        Some(&m) if m != NONE => Piece::Quadratic { a, m: points[m as usize], b },
        _ => Piece::Straight { a, b },
    }
}

/// Builds CSR arrays from (key, value) pairs over `n` keys.
pub(crate) fn csr(n: usize, pairs: &mut [(u32, u32)]) -> (Vec<u32>, Vec<u32>) {
    pairs.sort_unstable();
    let mut start = vec![0u32; n + 1];
    for &(k, _) in pairs.iter() {
        start[k as usize + 1] += 1;
    }
    for i in 0..n {
        start[i + 1] += start[i];
    }
    (start, pairs.iter().map(|&(_, v)| v).collect())
}

/// The fixed flags a file gave: exactly (VTK `fixed`: a node it leaves free is free, on the
/// boundary too), or as marks added to the boundary's (Gmsh points and lines, Medit
/// `Corners`, Triangle's markers).
#[derive(Clone, Debug)]
pub(crate) struct GivenFlags {
    pub(crate) flags: Vec<bool>,
    pub(crate) exact: bool,
}

/// What the file's fixed flags `given` say under the sliding rule, per node: whether it is
/// held (not a corner of an element, or fixed by the file), and whether it is a boundary
/// node the file's exact flags leave free (it then moves freely, as with the boundary
/// fixed, rather than slide). Flags that fix every boundary node (what smoothlab's writers
/// and Mesquite's write) say no more than where the boundary is: they hold the nodes off it
/// only.
pub(crate) fn held_nodes(
    on_boundary: &[bool],
    given: Option<&GivenFlags>,
    role: impl Fn(usize) -> NodeRole,
) -> (Vec<bool>, Vec<bool>) {
    let g = |v: usize| given.is_some_and(|g| g.flags[v]);
    let whole = given.is_some() && (0..on_boundary.len()).all(|v| !on_boundary[v] || g(v));
    let held = (0..on_boundary.len()).map(|v| role(v) != NodeRole::Corner || (g(v) && !(whole && on_boundary[v]))).collect();
    let exact = given.is_some_and(|g| g.exact);
    let freed = (0..on_boundary.len()).map(|v| exact && !whole && on_boundary[v] && !g(v)).collect();
    (held, freed)
}

/// A planar mesh's sliding rule: its boundary as loaded, and per node where its last
/// projection landed.
#[derive(Clone, Debug)]
pub(crate) struct PlanarSliding {
    curves: Arc<Curves<DVec2>>,
    feature_angle_deg: f64,
    /// Per node: the segment it lies on.
    hint: Vec<u32>,
    /// Per node: the unit direction of its curve there (zero unless it slides).
    tangent: Vec<DVec2>,
    /// A quadratic mesh's: the curves as chains, and what its sliding nodes carry.
    carrying: Option<Carrying>,
}

/// What a quadratic mesh's sliding nodes carry: the mid-side nodes of their boundary
/// edges, put on the curve at the middle in parameter of their edge's span, so each
/// boundary edge stays on the curve with its mid-side node centred.
#[derive(Clone, Debug)]
struct Carrying {
    chains: Arc<Chains>,
    /// Per node: a mid-side node of a boundary edge that the file does not fix.
    carried: Arc<Vec<bool>>,
    /// Per node: its parameter on its segment `hint` (sliding nodes).
    t: Vec<f64>,
}

impl PlanarSliding {
    /// The mid-side nodes sliding node `n` carries when it moves to `x` (a point of its
    /// curve), each with where it goes: on the curve, at the middle in parameter of its
    /// edge's span from `x` to the edge's other corner where it lies now.
    fn carried(&self, n: usize, x: DVec2) -> [Option<(usize, DVec2)>; 2] {
        let mut out = [None; 2];
        let Some(c) = &self.carrying else { return out };
        if !self.curves.class[n].slides() {
            return out;
        }
        let foot = self.curves.on_curve(x, self.hint[n]);
        let curve = self.curves.curve[foot.segment as usize];
        let from = c.chains.param(foot.segment, foot.t);
        for (slot, &s) in out.iter_mut().zip(self.curves.segs_at(n)) {
            let mid = self.curves.mids.get(s as usize).copied().unwrap_or(NONE);
            if mid == NONE || !c.carried[mid as usize] {
                continue;
            }
            let [a, b] = self.curves.segments[s as usize];
            let other = if a as usize == n { b } else { a } as usize;
            let to = if self.curves.class[other].slides() {
                c.chains.param(self.hint[other], c.t[other])
            } else {
                c.chains.param(s, if other == b as usize { 1.0 } else { 0.0 })
            };
            let (segment, t) = c.chains.at(curve, c.chains.middle(curve, from, to));
            *slot = Some((mid as usize, self.curves.piece(segment).at(t)));
        }
        out
    }
}

impl Mesh {
    /// Sets what boundary nodes do from now on. [`BoundaryRule::Slide`] takes the boundary
    /// as it is now as the curves the sliding nodes stay on: polylines, and a quadratic
    /// element's edge the quadratic through its corners and mid-side node (its
    /// isoparametric edge). A node where it turns by more than `feature_angle_deg` is a
    /// corner and stays. A sliding node of a quadratic mesh carries the mid-side nodes of
    /// its boundary edges along the curve. [`BoundaryRule::Fixed`] holds them again.
    pub fn set_boundary(&mut self, rule: BoundaryRule, feature_angle_deg: f64) {
        if rule == BoundaryRule::Fixed {
            self.sliding = None;
            return;
        }
        let n = self.node_count();
        let mut pieces = Vec::new();
        let mut on_boundary = vec![false; n];
        for e in self.topology().boundary_edges() {
            pieces.push(([e.a, e.b], e.mid));
            for v in [e.a, e.b, e.mid].into_iter().filter(|&v| v != NONE) {
                on_boundary[v as usize] = true;
            }
        }
        pieces.sort_unstable();
        let segments: Vec<[u32; 2]> = pieces.iter().map(|p| p.0).collect();
        let quadratic = self.has_quadratic();
        let mids: Vec<u32> = if quadratic { pieces.iter().map(|p| p.1).collect() } else { Vec::new() };
        // a boundary node of an element with a corner turned over: its turn is no corner
        let turned = |e: usize| {
            let (k, p) = (self.kind(e).corners(), self.element_points_array(e));
            (0..k).any(|i| (p[(i + 1) % k] - p[i]).perp_dot(p[(i + k - 1) % k] - p[i]) <= 0.0)
        };
        let folded: Vec<bool> =
            (0..n).map(|v| on_boundary[v] && self.node_elements(v).iter().any(|&e| turned(e as usize))).collect();
        let given = self.given_fixed.as_deref();
        let (held, freed) = held_nodes(&on_boundary, given, |v| self.role(v));
        let sliding_boundary: Vec<bool> = on_boundary.iter().zip(&freed).map(|(&b, &f)| b && !f).collect();
        let curves = Curves::new(self.nodes(), &sliding_boundary, &held, &folded, segments, mids, feature_angle_deg.to_radians().cos());
        let carrying = quadratic.then(|| {
            // a mid-side node is held by the file's flags as a corner is
            let (pinned, _) = held_nodes(&on_boundary, given, |_| NodeRole::Corner);
            let mut carried = vec![false; n];
            for &m in curves.mids.iter().filter(|&&m| m != NONE) {
                carried[m as usize] = !pinned[m as usize];
            }
            Carrying { chains: Arc::new(Chains::new(&curves)), carried: Arc::new(carried), t: vec![0.0; n] }
        });
        let mut sliding = PlanarSliding {
            hint: vec![NONE; n],
            tangent: vec![DVec2::ZERO; n],
            curves: Arc::new(curves),
            feature_angle_deg,
            carrying,
        };
        for v in 0..n {
            if sliding.curves.class[v] == BoundaryNode::Curve {
                sliding.hint[v] = sliding.curves.segs_at(v)[0];
                sliding.settle_at(v, self.nodes()[v]);
            }
        }
        self.sliding = Some(Box::new(sliding));
    }

    /// What boundary nodes do now.
    pub fn boundary_rule(&self) -> BoundaryRule {
        if self.sliding.is_some() {
            BoundaryRule::Slide
        } else {
            BoundaryRule::Fixed
        }
    }

    /// What node `n` does under the sliding rule; `None` when boundary nodes are fixed.
    #[inline]
    pub fn boundary_node(&self, n: usize) -> Option<BoundaryNode> {
        self.sliding.as_ref().map(|s| s.curves.class[n])
    }

    /// The feature angle and the number of boundary curves, when boundary nodes slide.
    pub fn feature_curves(&self) -> Option<(f64, usize)> {
        self.sliding.as_ref().map(|s| (s.feature_angle_deg, s.curves.count))
    }

    /// The unit direction node `n` slides along (zero unless it slides).
    #[inline]
    pub fn slide_direction(&self, n: usize) -> DVec2 {
        self.sliding.as_ref().map_or(DVec2::ZERO, |s| s.tangent[n])
    }

    /// Where node `n` would be moved to `x`: `x` itself, or for a sliding node the nearest
    /// point of its curve of the boundary as loaded.
    #[inline]
    pub fn onto_boundary(&self, n: usize, x: DVec2) -> DVec2 {
        match &self.sliding {
            Some(s) if s.curves.class[n].slides() => s.curves.on_curve(x, s.hint[n]).point,
            _ => x,
        }
    }

    /// Whether moving node `n` moves mid-side nodes onto the boundary with it: a sliding
    /// node of a quadratic mesh, whose boundary edges' mid-side nodes it carries.
    #[inline]
    pub fn carries_mid_nodes(&self, n: usize) -> bool {
        self.sliding.as_ref().is_some_and(|s| s.carrying.is_some() && s.curves.class[n].slides())
    }

    /// Whether moving node `n` carries mid-side node `mid` along the boundary
    /// ([`carries_mid_nodes`](Self::carries_mid_nodes)).
    #[inline]
    pub fn carries(&self, n: usize, mid: usize) -> bool {
        self.carries_mid_nodes(n) && self.sliding.as_ref().and_then(|s| s.carrying.as_ref()).is_some_and(|c| c.carried[mid])
    }

    /// The mid-side nodes node `n` carries when moved to `x` (a point
    /// [`onto_boundary`](Self::onto_boundary) gave), with where they go: on the curve, at
    /// the middle in parameter of their edge's new span. None unless `n` slides on a
    /// quadratic mesh's boundary.
    pub fn carried_mid_nodes(&self, n: usize, x: DVec2) -> [Option<(usize, DVec2)>; 2] {
        self.sliding.as_ref().map_or([None; 2], |s| s.carried(n, x))
    }

    /// Records that node `n` was moved (to a point [`onto_boundary`](Self::onto_boundary)
    /// gave): its segment and direction there, and the mid-side nodes it carries put where
    /// [`carried_mid_nodes`](Self::carried_mid_nodes) says.
    #[inline]
    pub fn settle(&mut self, n: usize) {
        let x = self.nodes()[n];
        if let Some(s) = &mut self.sliding {
            if s.curves.class[n].slides() {
                let carried = s.carried(n, x);
                s.settle_at(n, x);
                for (mid, at) in carried.into_iter().flatten() {
                    self.nodes[mid] = at;
                }
            }
        }
    }

    /// The positions the sliding boundary was taken from (every node's, as
    /// [`set_boundary`](Self::set_boundary) found them), when boundary nodes slide.
    pub fn boundary_taken_from(&self) -> Option<&[DVec2]> {
        self.sliding.as_ref().map(|s| &s.curves.points[..])
    }

    /// Per node, the boundary segment a sliding node was last put on ([`NONE`] for a node
    /// that does not slide), when boundary nodes slide. A copy of the mesh whose boundary
    /// was taken from the same positions slides its nodes as this one does once given them
    /// with [`boundary_parameters`](Self::boundary_parameters)
    /// ([`set_boundary_segments`](Self::set_boundary_segments)).
    pub fn boundary_segments(&self) -> Option<&[u32]> {
        self.sliding.as_ref().map(|s| &s.hint[..])
    }

    /// Per node, where a sliding node lies on its segment
    /// ([`boundary_segments`](Self::boundary_segments)): the parameter, 0 to 1, along the
    /// quadratic through the segment's corners and mid-side node (0 for a node that does
    /// not slide). Only a quadratic mesh's sliding boundary keeps them (they place the
    /// mid-side nodes its sliding nodes carry); `None` otherwise.
    pub fn boundary_parameters(&self) -> Option<&[f64]> {
        self.sliding.as_ref().and_then(|s| s.carrying.as_ref()).map(|c| &c.t[..])
    }

    /// Puts each sliding node on the segment `segments` names (another copy's
    /// [`boundary_segments`](Self::boundary_segments)) at the parameter `parameters` gives
    /// (its [`boundary_parameters`](Self::boundary_parameters): empty for a linear mesh),
    /// and its direction there. Refused, changing nothing, unless boundary nodes slide,
    /// each sliding node names a segment of its own curve (and every other node
    /// [`NONE`]), and a quadratic mesh gives each sliding node a parameter from 0 to 1.
    pub fn set_boundary_segments(&mut self, segments: &[u32], parameters: &[f64]) -> crate::error::Result<()> {
        use crate::error::Error;
        let Some(s) = &mut self.sliding else {
            return Err(Error::invalid("boundary segments were given, but the boundary nodes do not slide"));
        };
        let n = s.hint.len();
        if segments.len() != n {
            return Err(Error::invalid(format!("{} boundary segments for a mesh of {n} nodes: give one a node", segments.len())));
        }
        match (&s.carrying, parameters.len()) {
            (None, 0) => {}
            (None, k) => return Err(Error::invalid(format!("{k} boundary parameters for a linear mesh: its sliding nodes take none"))),
            (Some(_), k) if k != n => {
                return Err(Error::invalid(format!("{k} boundary parameters for a quadratic mesh of {n} nodes: give one a node")))
            }
            (Some(_), _) => {}
        }
        let c = &s.curves;
        for (v, &seg) in segments.iter().enumerate() {
            let fits = if c.class[v].slides() {
                (seg as usize) < c.segments.len() && c.segs_at(v).first().is_some_and(|&f| c.curve[f as usize] == c.curve[seg as usize])
            } else {
                seg == NONE
            };
            if !fits {
                return Err(Error::node(v, None, format!("cannot lie on boundary segment {seg}: it is not on the node's curve")));
            }
            if let Some(&t) = parameters.get(v).filter(|_| c.class[v].slides()) {
                if !(0.0..=1.0).contains(&t) {
                    return Err(Error::node(v, None, format!("cannot lie at parameter {t} of its boundary segment: give one from 0 to 1")));
                }
            }
        }
        for (v, &seg) in segments.iter().enumerate() {
            if c.class[v].slides() {
                let t = parameters.get(v).copied().unwrap_or(0.0);
                (s.hint[v], s.tangent[v]) = (seg, c.direction(seg, t));
                if let Some(carrying) = &mut s.carrying {
                    carrying.t[v] = t;
                }
            }
        }
        Ok(())
    }

    /// The largest distance of a sliding node, or a mid-side node it carries, from its
    /// curve of the boundary as loaded (0 when none slides).
    pub fn max_distance_from_boundary(&self) -> f64 {
        let Some(s) = &self.sliding else { return 0.0 };
        let carried = s.carrying.as_ref().map_or(&[][..], |c| &c.carried[..]);
        let mids = s.curves.mids.iter().enumerate().filter(|(_, &m)| m != NONE && carried[m as usize]);
        (0..self.node_count())
            .filter(|&n| s.curves.class[n].slides())
            .map(|n| s.curves.distance(self.nodes()[n], s.hint[n]))
            .chain(mids.map(|(seg, &m)| s.curves.distance(self.nodes()[m as usize], seg as u32)))
            .fold(0.0, f64::max)
    }
}

impl PlanarSliding {
    /// Records that sliding node `n` lies at `x`: its segment, direction and parameter.
    fn settle_at(&mut self, n: usize, x: DVec2) {
        let foot = self.curves.on_curve(x, self.hint[n]);
        (self.tangent[n], self.hint[n]) = (foot.tangent, foot.segment);
        if let Some(c) = &mut self.carrying {
            c.t[n] = foot.t;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{grid, plate, GridKind, PlateKind};
    use crate::model::Model;
    use crate::smoothing::Smoothing;

    /// The unit square in 10 × 10 cells of `kind`, its boundary nodes bunched towards the
    /// corners along the sides (smoothstep spacing): a boundary placed no better than a
    /// careless mesher places it, every element valid.
    fn bunched_square(kind: GridKind) -> Mesh {
        let mut m = grid(10, 10, kind).unwrap();
        let bunch = |t: f64| t * t * (3.0 - 2.0 * t);
        for p in m.nodes_mut() {
            let on = |c: f64| c == 0.0 || c == 1.0;
            if on(p.y) && !on(p.x) {
                p.x = bunch(p.x);
            } else if on(p.x) && !on(p.y) {
                p.y = bunch(p.y);
            }
        }
        m
    }

    #[test]
    fn sliding_lifts_the_smallest_angle_past_what_the_fixed_boundary_reaches() {
        for kind in [GridKind::Tri, GridKind::Quad] {
            let start = bunched_square(kind);
            let mut fixed = Model::Planar(start.clone());
            let f = fixed.smooth(&Smoothing::default()).unwrap().stats().clone();
            let mut slid = Model::Planar(start.clone());
            let report = slid.smooth(&Smoothing::default().boundary(BoundaryRule::Slide)).unwrap();
            let s = report.stats();
            assert_eq!(s.inverted, 0);
            assert!(s.min_angle_deg > f.min_angle_deg + 20.0, "{kind:?}: slide {} fixed {}", s.min_angle_deg, f.min_angle_deg);
            assert!(s.max_angle_deg <= f.max_angle_deg, "{kind:?}: slide {} fixed {}", s.max_angle_deg, f.max_angle_deg);
            let b = report.boundary().unwrap();
            assert_eq!((b.corners, b.curves, b.curve_nodes, b.held), (4, 4, 36, 0), "{kind:?}");
            let Model::Planar(m) = &slid else { unreachable!() };
            for (n, (p, q)) in start.nodes().iter().zip(m.nodes()).enumerate() {
                // a side's node stays on its side, exactly; a corner stays
                for c in 0..2 {
                    if p[c] == 0.0 || p[c] == 1.0 {
                        assert_eq!(q[c], p[c], "{kind:?}: node {n} left its side: {p} to {q}");
                    }
                }
                if (p.x == 0.0 || p.x == 1.0) && (p.y == 0.0 || p.y == 1.0) {
                    assert_eq!(p, q, "{kind:?}: corner {n} moved");
                }
            }
        }
    }

    /// The bunched square bent into a quarter of a cylinder (radius 2/π, so the square's
    /// side is a quarter turn), as an OBJ surface: its four rims turn by 90° at the
    /// corners. Sliding along them lifts its smallest angle past the fixed boundary's, the
    /// corners hold, and every rim node stays on its rim as loaded.
    #[test]
    fn a_surface_slides_along_its_open_edges_and_its_corners_hold() {
        use std::fmt::Write;
        let flat = bunched_square(GridKind::Tri);
        let r = 2.0 / std::f64::consts::PI;
        let bend = |p: DVec2| DVec3::new(r * (p.x / r).sin(), p.y, r * (p.x / r).cos());
        let mut obj = String::new();
        for p in flat.nodes() {
            let q = bend(*p);
            writeln!(obj, "v {} {} {}", q.x, q.y, q.z).unwrap();
        }
        for e in 0..flat.element_count() {
            let ids = flat.element(e);
            writeln!(obj, "f {} {} {}", ids[0] + 1, ids[1] + 1, ids[2] + 1).unwrap();
        }
        let start = crate::io::read_model_str(&obj, crate::io::Format::Obj).unwrap();
        let Model::Surface(loaded) = &start else { panic!("a surface") };
        let loaded = loaded.clone();
        let (mut fixed, mut slid) = (start.clone(), start.clone());
        let f = fixed.smooth(&Smoothing::default()).unwrap().stats().clone();
        let report = slid.smooth(&Smoothing::default().boundary(BoundaryRule::Slide)).unwrap();
        let s = report.stats();
        assert_eq!(s.inverted, 0);
        assert!(s.min_angle_deg > f.min_angle_deg + 10.0, "slide {} fixed {}", s.min_angle_deg, f.min_angle_deg);
        let b = report.boundary().expect("a boundary report");
        assert_eq!((b.corners, b.curves, b.curve_nodes, b.held), (4, 4, 36, 0));
        assert!(b.max_distance < 1e-12 * b.mean_edge, "{b:?}");
        let Model::Surface(m) = &slid else { unreachable!() };
        for (n, (p, q)) in flat.nodes().iter().zip(m.points()).enumerate() {
            let was = loaded.points()[n];
            if (p.x == 0.0 || p.x == 1.0) && (p.y == 0.0 || p.y == 1.0) {
                assert_eq!(was, *q, "corner {n} moved");
            } else if p.y == 0.0 || p.y == 1.0 {
                assert_eq!(q.y, was.y, "node {n} left its rim: {was} to {q}");
            } else if p.x == 0.0 || p.x == 1.0 {
                assert!((q.x - was.x).abs() < 1e-15 && (q.z - was.z).abs() < 1e-15, "node {n} left its rim: {was} to {q}");
            }
        }
    }

    #[test]
    fn a_tangled_mesh_is_untangled_with_its_boundary_held_then_slides() {
        // the bunched square with its interior tangled: its boundary edges are sound, but a
        // tangled file's may be folded, so the boundary is held until a pass leaves the
        // mesh valid, then slides
        let start = crate::generate::perturb(&bunched_square(GridKind::Quad), 0.8, 5).unwrap();
        assert!(Model::Planar(start.clone()).stats().inverted > 0);
        let mut fixed = Model::Planar(start.clone());
        let f = fixed.smooth(&Smoothing::default()).unwrap().stats().clone();
        let mut slid = Model::Planar(start.clone());
        let report = slid.smooth(&Smoothing::default().boundary(BoundaryRule::Slide)).unwrap();
        let s = report.stats();
        assert_eq!((f.inverted, s.inverted), (0, 0));
        assert!(s.min_angle_deg > f.min_angle_deg + 10.0, "slide {} fixed {}", s.min_angle_deg, f.min_angle_deg);
        assert!(report.boundary().is_some_and(|b| b.curve_nodes == 36));
        // the pass that untangles it holds the boundary
        let mut one = Model::Planar(start.clone());
        let r = one.smooth(&Smoothing::default().boundary(BoundaryRule::Slide).passes(1).finish(0)).unwrap();
        assert_eq!(r.stats().inverted, 0);
        let Model::Planar(m) = &one else { unreachable!() };
        for e in start.topology().boundary_edges() {
            for v in [e.a as usize, e.b as usize] {
                assert_eq!(start.nodes()[v], m.nodes()[v], "boundary node {v} moved while the mesh was tangled");
            }
        }
    }

    #[test]
    fn a_copy_given_the_segments_slides_as_the_mesh_does() {
        use crate::objective::{objective_with, ObjectiveKind, Penalty};
        use crate::smooth::{SmoothOptions, Smoother};
        let objective = objective_with(ObjectiveKind::SmoothShape, Penalty::default());
        let pass = |m: &mut Mesh| Smoother::new(SmoothOptions::default()).unwrap().pass(m, &*objective, &|| 0.0);
        let mut m = plate(PlateKind::Tri, 1, 2).unwrap();
        m.set_boundary(BoundaryRule::Slide, FEATURE_ANGLE_DEG);
        pass(&mut m);
        // another copy: the boundary taken from the same positions, then the nodes now
        let mut copy = plate(PlateKind::Tri, 1, 2).unwrap();
        copy.nodes_mut().copy_from_slice(m.boundary_taken_from().unwrap());
        copy.set_boundary(BoundaryRule::Slide, FEATURE_ANGLE_DEG);
        copy.nodes_mut().copy_from_slice(m.nodes());
        let segments = m.boundary_segments().unwrap().to_vec();
        assert!(segments.iter().filter(|&&s| s != NONE).count() > 20);
        // refused, changing nothing: the wrong count, a segment of another curve, a
        // sliding node on none, a mesh whose boundary is fixed
        let hole = (0..m.node_count()).find(|&n| m.boundary_node(n) == Some(BoundaryNode::Curve) && m.nodes()[n].length() < 0.5).unwrap();
        let outer = (0..m.node_count()).find(|&n| m.boundary_node(n) == Some(BoundaryNode::Curve) && m.nodes()[n].length() > 0.9).unwrap();
        let before = copy.boundary_segments().unwrap().to_vec();
        let mut other = segments.clone();
        other[hole] = segments[outer];
        let mut none = segments.clone();
        none[hole] = NONE;
        for bad in [&segments[1..], &other[..], &none[..]] {
            assert!(copy.set_boundary_segments(bad, &[]).is_err());
            assert_eq!(copy.boundary_segments().unwrap(), &before[..]);
        }
        assert!(plate(PlateKind::Tri, 1, 2).unwrap().set_boundary_segments(&segments, &[]).is_err());
        assert!(copy.set_boundary_segments(&segments, &vec![0.5; segments.len()]).is_err(), "a linear mesh takes no parameters");
        assert_eq!(copy.boundary_parameters(), None);
        copy.set_boundary_segments(&segments, &[]).unwrap();
        for n in 0..m.node_count() {
            assert_eq!(copy.slide_direction(n), m.slide_direction(n), "node {n}");
        }
        pass(&mut m);
        pass(&mut copy);
        assert_eq!(copy.nodes(), m.nodes());
        assert_eq!(copy.boundary_segments(), m.boundary_segments());
    }

    /// A quadratic mesh's copy needs each sliding node's parameter on its segment as well:
    /// given both, it slides (and carries its mid-side nodes) as the mesh does, bit for bit.
    #[test]
    fn a_quadratic_copy_given_segments_and_parameters_slides_as_the_mesh_does() {
        use super::super::ElementKind;
        use crate::objective::{objective_with, ObjectiveKind, Penalty};
        use crate::smooth::{SmoothOptions, Smoother};
        let objective = objective_with(ObjectiveKind::SmoothShape, Penalty::default());
        let pass = |m: &mut Mesh| Smoother::new(SmoothOptions::default()).unwrap().pass(m, &*objective, &|| 0.0);
        for kind in [ElementKind::Tri6, ElementKind::Quad8] {
            let start = bunched_annulus_quarter(kind);
            let mut m = start.clone();
            m.set_boundary(BoundaryRule::Slide, FEATURE_ANGLE_DEG);
            pass(&mut m);
            let mut copy = start.clone();
            copy.set_boundary(BoundaryRule::Slide, FEATURE_ANGLE_DEG);
            copy.nodes_mut().copy_from_slice(m.nodes());
            let (segments, params) = (m.boundary_segments().unwrap().to_vec(), m.boundary_parameters().unwrap().to_vec());
            // a node inside its segment: its parameter is neither end
            assert!(params.iter().any(|&t| t > 0.01 && t < 0.99), "{kind:?}");
            let sliding = (0..m.node_count()).find(|&n| m.boundary_node(n).is_some_and(|c| c.slides())).unwrap();
            let mut beyond = params.clone();
            beyond[sliding] = 1.5;
            let mut nan = params.clone();
            nan[sliding] = f64::NAN;
            let before = copy.boundary_parameters().unwrap().to_vec();
            for bad in [&[][..], &params[1..], &beyond[..], &nan[..]] {
                assert!(copy.set_boundary_segments(&segments, bad).is_err(), "{kind:?}");
                assert_eq!(copy.boundary_parameters().unwrap(), &before[..], "{kind:?}: a refusal changed the parameters");
            }
            copy.set_boundary_segments(&segments, &params).unwrap();
            for n in 0..m.node_count() {
                assert_eq!(copy.slide_direction(n), m.slide_direction(n), "{kind:?}: node {n}");
            }
            pass(&mut m);
            pass(&mut copy);
            assert_eq!(copy.nodes(), m.nodes(), "{kind:?}");
            assert_eq!(copy.boundary_parameters(), m.boundary_parameters(), "{kind:?}");
        }
    }

    #[test]
    fn a_curved_boundary_s_nodes_stay_on_its_polyline() {
        // the plate's hole is a polygon of 16 sides turning by 22.5°: every node slides
        // along it; the plate's own four corners turn by 90° and hold
        let start = plate(PlateKind::Tri, 1, 2).unwrap();
        let mut model = Model::Planar(start.clone());
        let report = model.smooth(&Smoothing::default().boundary(BoundaryRule::Slide)).unwrap();
        let b = report.boundary().unwrap();
        assert_eq!(b.corners, 4, "{b:?}");
        assert!(b.max_distance < 1e-12 * b.mean_edge, "{b:?}");
        assert_eq!(report.stats().inverted, 0);
        let Model::Planar(m) = &model else { unreachable!() };
        for (n, p) in start.nodes().iter().enumerate() {
            if m.boundary_node(n) == Some(BoundaryNode::Corner) {
                assert_eq!(*p, m.nodes()[n], "corner {n} moved");
            }
        }
    }

    #[test]
    fn the_file_s_own_flags_hold_and_flags_on_the_whole_boundary_do_not() {
        let mut m = bunched_square(GridKind::Tri);
        let boundary = m.fixed.clone();
        let side = (0..m.node_count()).find(|&n| m.nodes()[n].y == 0.0 && m.nodes()[n].x > 0.3).unwrap();
        let mut flags = vec![false; m.node_count()];
        flags[side] = true;
        // as a file with exact flags reads: those flags are the fixed ones
        m.fixed = flags.clone();
        m.given_fixed = Some(Arc::new(GivenFlags { flags, exact: true }));
        m.set_boundary(BoundaryRule::Slide, FEATURE_ANGLE_DEG);
        assert_eq!(m.boundary_node(side), Some(BoundaryNode::Held));
        assert!(!m.is_free(side));
        // exact flags leave the other boundary nodes free: they move freely, as with the
        // boundary fixed; the same flags as marks (Gmsh points) add to the boundary's: they
        // slide
        let other = (0..m.node_count()).find(|&n| m.nodes()[n].x == 0.0 && m.nodes()[n].y > 0.3).unwrap();
        assert_eq!(m.boundary_node(other), Some(BoundaryNode::Interior));
        assert!(m.is_free(other));
        let flags = m.given_fixed.as_ref().unwrap().flags.clone();
        m.fixed = boundary.iter().zip(&flags).map(|(&b, &f)| b || f).collect();
        m.given_fixed = Some(Arc::new(GivenFlags { flags, exact: false }));
        m.set_boundary(BoundaryRule::Slide, FEATURE_ANGLE_DEG);
        assert_eq!(m.boundary_node(side), Some(BoundaryNode::Held));
        assert_eq!(m.boundary_node(other), Some(BoundaryNode::Curve));
        // every boundary node flagged (what smoothlab writes): they slide
        m.given_fixed = Some(Arc::new(GivenFlags { flags: m.fixed().to_vec(), exact: true }));
        m.set_boundary(BoundaryRule::Slide, FEATURE_ANGLE_DEG);
        assert_eq!(m.boundary_node(side), Some(BoundaryNode::Curve));
        assert!(m.is_free(side));
        m.set_boundary(BoundaryRule::Fixed, FEATURE_ANGLE_DEG);
        assert!(!m.is_free(side));
    }

    /// A quarter of the annulus 1 ≤ r ≤ 2, 0 ≤ θ ≤ 90°, in 4 × 10 cells of `kind` (6-node
    /// triangles, 8- or 9-node quads): the arcs' mid-side nodes on their circles (curved
    /// edges), the others at their edges' middles (a 9-node quad's centre at the mean of
    /// its other nodes). The corner nodes of both arcs and both straight sides are bunched
    /// towards the ends (smoothstep), the interior ones evenly spaced: every element valid,
    /// those along the boundary skewed.
    fn bunched_annulus_quarter(kind: super::super::ElementKind) -> Mesh {
        use super::super::{ElementKind, MeshBuilder};
        let (rings, sectors) = (4, 10);
        let bunch = |t: f64| t * t * (3.0 - 2.0 * t);
        // corner (i, j): ring i outwards, sector boundary j round
        let polar = |i: usize, j: usize| {
            let (s, t) = (i as f64 / rings as f64, j as f64 / sectors as f64);
            let r = 1.0 + if j == 0 || j == sectors { bunch(s) } else { s };
            (r, std::f64::consts::FRAC_PI_2 * if i == 0 || i == rings { bunch(t) } else { t })
        };
        let corner = |i: usize, j: usize| {
            let (r, theta) = polar(i, j);
            if j == sectors { DVec2::new(0.0, r) } else { DVec2::new(r * theta.cos(), r * theta.sin()) }
        };
        // node (I, J) of the doubled grid: corners at even I and J, mid-side nodes between
        let at = |i2: usize, j2: usize| -> DVec2 {
            let (i, j) = (i2 / 2, j2 / 2);
            match (i2 % 2, j2 % 2) {
                (0, 0) => corner(i, j),
                (1, 0) => 0.5 * (corner(i, j) + corner(i + 1, j)),
                (0, _) if i == 0 || i == rings => {
                    let (r, a) = polar(i, j);
                    let theta = 0.5 * (a + polar(i, j + 1).1);
                    DVec2::new(r * theta.cos(), r * theta.sin())
                }
                (0, _) => 0.5 * (corner(i, j) + corner(i, j + 1)),
                _ => 0.5 * (corner(i + 1, j) + corner(i, j + 1)),
            }
        };
        let mut b = MeshBuilder::new();
        let mut ids = std::collections::HashMap::new();
        let mut id = |b: &mut MeshBuilder, i2: usize, j2: usize| {
            *ids.entry((i2, j2)).or_insert_with(|| {
                let p = at(i2, j2);
                b.add_node([p.x, p.y, 0.0], 0) as u32
            })
        };
        for i in 0..rings {
            for j in 0..sectors {
                let (i2, j2) = (2 * i, 2 * j);
                let c = [id(&mut b, i2, j2), id(&mut b, i2 + 2, j2), id(&mut b, i2 + 2, j2 + 2), id(&mut b, i2, j2 + 2)];
                let m = [id(&mut b, i2 + 1, j2), id(&mut b, i2 + 2, j2 + 1), id(&mut b, i2 + 1, j2 + 2), id(&mut b, i2, j2 + 1)];
                match kind {
                    ElementKind::Tri6 => {
                        let d = id(&mut b, i2 + 1, j2 + 1);
                        b.add_element(kind, &[c[0], c[1], c[3], m[0], d, m[3]], 0);
                        b.add_element(kind, &[c[1], c[2], c[3], m[1], m[2], d], 0);
                    }
                    ElementKind::Quad8 => b.add_element(kind, &[c[0], c[1], c[2], c[3], m[0], m[1], m[2], m[3]], 0),
                    _ => {
                        let centre = b.add_node([0.0; 3], 0) as u32;
                        b.add_element(kind, &[c[0], c[1], c[2], c[3], m[0], m[1], m[2], m[3], centre], 0);
                    }
                }
            }
        }
        let mut mesh = b.build().unwrap();
        mesh.update_mid_nodes();
        mesh
    }

    /// The distance of `x` from the quadratic pieces through `pieces` (corner, mid-side
    /// node, corner), found without [`Piece::nearest`]: the nearest of 2,000 samples of
    /// each, then a golden-section search about it.
    fn distance_from_pieces(pieces: &[[DVec2; 3]], x: DVec2) -> f64 {
        let mut best = f64::INFINITY;
        for &[a, m, b] in pieces {
            let piece = Piece::Quadratic { a, m, b };
            let d = |t: f64| piece.at(t).distance(x);
            let n = 2000;
            let k = (0..=n).min_by(|&i, &j| d(i as f64 / n as f64).total_cmp(&d(j as f64 / n as f64))).unwrap();
            let (mut lo, mut hi) = (((k as f64 - 1.0) / n as f64).max(0.0), ((k as f64 + 1.0) / n as f64).min(1.0));
            let g = 0.5 * (5f64.sqrt() - 1.0);
            for _ in 0..80 {
                let (u, w) = (hi - g * (hi - lo), lo + g * (hi - lo));
                if d(u) < d(w) {
                    hi = w;
                } else {
                    lo = u;
                }
            }
            best = best.min(d(0.5 * (lo + hi))).min(d(k as f64 / n as f64));
        }
        best
    }

    /// Issue 58 on quadratic meshes: a bunched annulus quarter's boundary slides along its
    /// curved boundary. Every boundary node ends on the input's piecewise-quadratic curve,
    /// the four corners and the file's fixed nodes stay, the smallest angle ends above the
    /// fixed boundary's, the report measures the distance from the curve (a chord is
    /// farther than 10⁻⁴ from the curve's mid-side nodes), and a second run repeats the
    /// first bit for bit.
    #[test]
    fn a_quadratic_mesh_s_boundary_slides_along_its_curved_edges() {
        use super::super::ElementKind;
        for kind in [ElementKind::Tri6, ElementKind::Quad8, ElementKind::Quad9] {
            let mut start = bunched_annulus_quarter(kind);
            assert_eq!(crate::quality::mesh_stats(&start).inverted, 0, "{kind:?}");
            // the file fixes one node of the outer arc and one mid-side node of the inner
            let on_arc = |p: DVec2, r: f64| (p.length() - r).abs() < 1e-12 && p.x > 0.0 && p.y > 0.0;
            let outer = (0..start.node_count()).find(|&n| start.role(n) == NodeRole::Corner && on_arc(start.nodes()[n], 2.0) && start.nodes()[n].x < 1.5).unwrap();
            let inner_mid = (0..start.node_count()).find(|&n| start.role(n) == NodeRole::Mid && on_arc(start.nodes()[n], 1.0) && start.nodes()[n].y > 0.5).unwrap();
            let mut flags = vec![false; start.node_count()];
            flags[outer] = true;
            flags[inner_mid] = true;
            start.fixed = start.fixed.iter().zip(&flags).map(|(&b, &f)| b || f).collect();
            start.given_fixed = Some(Arc::new(GivenFlags { flags, exact: false }));
            let pieces: Vec<[DVec2; 3]> = start
                .topology()
                .boundary_edges()
                .map(|e| [e.a, e.mid, e.b].map(|v| start.nodes()[v as usize]))
                .collect();
            let fixed = Model::Planar(start.clone()).smooth(&Smoothing::default()).unwrap().stats().clone();
            let smooth = || {
                let mut model = Model::Planar(start.clone());
                let report = model.smooth(&Smoothing::default().boundary(BoundaryRule::Slide)).unwrap();
                let Model::Planar(m) = model else { unreachable!() };
                (m, report)
            };
            let (m, report) = smooth();
            let s = report.stats();
            assert_eq!(s.inverted, 0, "{kind:?}");
            assert!(s.min_angle_deg > fixed.min_angle_deg + 20.0, "{kind:?}: slide {} fixed {}", s.min_angle_deg, fixed.min_angle_deg);
            let b = report.boundary().unwrap();
            assert_eq!((b.corners, b.curves, b.held), (4, 5, 1), "{kind:?}: {b:?}");
            assert!(b.max_distance < 1e-12, "{kind:?}: {b:?}");
            let mut moved = 0;
            for e in start.topology().boundary_edges() {
                for v in [e.a, e.mid, e.b].map(|v| v as usize) {
                    let (was, now) = (start.nodes()[v], m.nodes()[v]);
                    moved += usize::from(was != now);
                    let d = distance_from_pieces(&pieces, now);
                    assert!(d < 1e-9, "{kind:?}: node {v} at {now} is {d} off the curve");
                    // a straight side's nodes stay on it exactly
                    if was.x == 0.0 || was.y == 0.0 {
                        assert!(now.x == was.x || now.y == was.y, "{kind:?}: node {v} left its side: {was} to {now}");
                    }
                    if m.boundary_node(v) == Some(BoundaryNode::Corner) || v == outer || v == inner_mid {
                        assert_eq!(was, now, "{kind:?}: node {v} held, yet moved");
                    }
                }
                // each carried mid-side node is centred in parameter on its edge
                if e.mid as usize != inner_mid {
                    let sliding = m.sliding.as_deref().unwrap();
                    let chains = &sliding.carrying.as_ref().unwrap().chains;
                    let seg = sliding.curves.segments.binary_search(&[e.a, e.b]).unwrap() as u32;
                    let u = |v: u32| {
                        let foot = sliding.curves.on_curve(m.nodes()[v as usize], seg);
                        chains.param(foot.segment, foot.t)
                    };
                    let (ua, um, ub) = (u(e.a), u(e.mid), u(e.b));
                    assert!((um - 0.5 * (ua + ub)).abs() < 1e-9, "{kind:?}: edge {}–{} at {ua}, {um}, {ub}", e.a, e.b);
                }
            }
            assert!(moved > 40, "{kind:?}: {moved} boundary nodes moved");
            let (again, _) = smooth();
            assert!(m.nodes().iter().zip(again.nodes()).all(|(p, q)| p.x.to_bits() == q.x.to_bits() && p.y.to_bits() == q.y.to_bits()), "{kind:?}: a second run differs");
        }
    }
}
