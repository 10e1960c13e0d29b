//! Boundaries that slide (issue 58): a volume mesh's boundary nodes move along the
//! boundary as it was loaded, rather than stay where the file put them.
//!
//! The boundary skin (the faces of one element) is cut into smooth parts at its feature
//! curves: the edges where its two faces turn by more than the feature angle, and the
//! edges of more or fewer than two faces. Each boundary node is then one of:
//! - a *corner* (on one feature edge, or on three or more, or where its curve turns by
//!   more than the feature angle): it stays;
//! - a *curve* node (on two feature edges): it slides along its curve;
//! - a *surface* node (on none): it slides on its smooth part of the skin.
//!
//! A node the file fixed stays; flags that fix the whole skin, as smoothlab's writers
//! and Mesquite's write them, say only where the boundary is. Features are never found from a tangle: an edge of a
//! folded skin face is never a crease (a fold is not a feature). A face is folded where
//! one of its corners turns against it (a quad's bow tie), or its normal opposes the
//! skin's at one of its nodes (the faces' normals there summed by area).
//!
//! A sliding node moves in its tangent: the solver sees the objective's gradient
//! projected onto the node's tangent plane or line ([`Tangent`]). The point it reaches is
//! projected onto the reference, the skin as loaded: its flat triangles (a quad is two)
//! for a surface node, its curve's segments for a curve node. The acceptance rule then
//! measures the star there.

use std::sync::Arc;

use glam::{DMat3, DVec3};

use crate::mesh::{Curves, ElementKind, MIN_CURVE_SEGMENTS, NONE};
use crate::surface::Facets;

pub use crate::mesh::{BoundaryNode, BoundaryRule, FEATURE_ANGLE_DEG};

/// The space a sliding node moves in at its position: the plane with this unit normal,
/// or the line with this unit direction.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Tangent {
    /// Not sliding: every direction.
    #[default]
    Free,
    Plane(DVec3),
    Line(DVec3),
}

impl Tangent {
    /// `v` projected onto the tangent.
    #[inline]
    pub fn along(self, v: DVec3) -> DVec3 {
        match self {
            Tangent::Free => v,
            Tangent::Plane(n) => v - n * v.dot(n),
            Tangent::Line(t) => t * v.dot(t),
        }
    }
    /// The symmetric `P·H·P` of a Hessian `H`, with `P` the projector onto the tangent.
    pub fn along_hessian(self, h: DMat3) -> DMat3 {
        let p = match self {
            Tangent::Free => return h,
            Tangent::Plane(n) => DMat3::IDENTITY - outer(n, n),
            Tangent::Line(t) => outer(t, t),
        };
        p * h * p
    }
}

fn outer(a: DVec3, b: DVec3) -> DMat3 {
    DMat3::from_cols(a * b.x, a * b.y, a * b.z)
}

/// The boundary as loaded, shared by clones of the mesh: the skin's flat triangles cut
/// into parts at the feature curves, the curves, each node's class.
#[derive(Debug)]
struct Reference {
    facets: Facets,
    curves: Curves<DVec3>,
    feature_angle_deg: f64,
    /// The mean length of the skin's edges as loaded.
    mean_edge: f64,
}

/// The sliding rule of a volume mesh: the reference, and per node where its last
/// projection landed.
#[derive(Clone, Debug)]
pub(crate) struct Sliding {
    reference: Arc<Reference>,
    /// Per node: the facet (surface node) or segment (curve node) it lies on.
    hint: Vec<u32>,
    /// Per node: its tangent there.
    tangent: Vec<Tangent>,
}


impl Sliding {
    /// The rule over a mesh with `points` whose boundary skin is `faces` (their nodes, 3
    /// or 4, outward); `held` says which nodes stay (fixed by the file, or not corners).
    pub(crate) fn new(points: &[DVec3], faces: &[&[u32]], held: &[bool], freed: &[bool], feature_angle_deg: f64) -> Sliding {
        let n = points.len();
        let area = |f: &[u32]| -> DVec3 {
            let p = |i: usize| points[f[i] as usize];
            let [u, v] = if f.len() == 4 { [p(2) - p(0), p(3) - p(1)] } else { [p(1) - p(0), p(2) - p(0)] };
            let [u, v] = crate::numeric::in_unit_scale_3d([u, v]);
            u.cross(v)
        };
        let areas: Vec<DVec3> = faces.iter().map(|f| area(f)).collect();
        let normals: Vec<DVec3> = areas.iter().map(|&a| crate::numeric::direction(a)).collect();
        let mut skin_normal = vec![DVec3::ZERO; n];
        for (f, a) in faces.iter().zip(&areas) {
            for &v in *f {
                skin_normal[v as usize] += *a;
            }
        }
        let folded: Vec<bool> = faces
            .iter()
            .zip(&normals)
            .map(|(f, &normal)| {
                let k = f.len();
                let p = |i: usize| points[f[i % k] as usize];
                let bow_tie = k == 4
                    && (0..4).any(|i| {
                        let [u, v] = crate::numeric::in_unit_scale_3d([p(i + 1) - p(i), p(i + 3) - p(i)]);
                        u.cross(v).dot(normal) <= 0.0
                    });
                bow_tie || f.iter().any(|&v| skin_normal[v as usize].dot(normal) <= 0.0)
            })
            .collect();
        // the skin's edges with their faces, sorted by the edge's nodes
        let mut edges: Vec<([u32; 2], u32)> = Vec::with_capacity(faces.len() * 4);
        for (i, f) in faces.iter().enumerate() {
            let k = f.len();
            for a in 0..k {
                let (u, v) = (f[a], f[(a + 1) % k]);
                edges.push(([u.min(v), u.max(v)], i as u32));
            }
        }
        edges.sort_unstable();
        let cos_feature = feature_angle_deg.to_radians().cos();
        // per skin edge: its nodes, its two faces (`u32::MAX` where it has not two), and
        // whether it turns by more than the feature angle between unfolded faces
        let mut skin_edges: Vec<([u32; 2], [u32; 2], bool)> = Vec::with_capacity(edges.len() / 2);
        let mut i = 0;
        while i < edges.len() {
            let mut j = i + 1;
            while j < edges.len() && edges[j].0 == edges[i].0 {
                j += 1;
            }
            skin_edges.push(if j - i == 2 {
                let (f, g) = (edges[i].1 as usize, edges[i + 1].1 as usize);
                let turns = normals[f].dot(normals[g]) < cos_feature;
                (edges[i].0, [f as u32, g as u32], turns && !folded[f] && !folded[g])
            } else {
                (edges[i].0, [u32::MAX; 2], true)
            });
            i = j;
        }
        let mut on_skin = vec![false; n];
        for f in faces {
            for &v in *f {
                on_skin[v as usize] = true;
            }
        }
        let found: Vec<[u32; 2]> = skin_edges.iter().filter(|e| e.2).map(|e| e.0).collect();
        let none_folded = vec![false; n];
        // a node the file leaves free moves freely, as off the skin
        let on_skin: Vec<bool> = on_skin.iter().zip(freed).map(|(&s, &f)| s && !f).collect();
        let first = Curves::new(points, &on_skin, held, &none_folded, found, Vec::new(), cos_feature);
        // a crease shorter than MIN_CURVE_SEGMENTS edges that ends nowhere (at a node of
        // no other feature edge) is the coarse mesh's noise, not a feature: its edges are
        // smooth (an edge of more or fewer than two faces stays)
        let mut length = vec![0usize; first.count];
        let mut dangles = vec![false; first.count];
        for (s, &c) in first.segments.iter().zip(&first.curve) {
            length[c as usize] += 1;
            dangles[c as usize] |= s.iter().any(|&v| first.segs_at(v as usize).len() == 1);
        }
        let short = |e: &[u32; 2]| match first.segments.binary_search(e) {
            Ok(s) => {
                let c = first.curve[s] as usize;
                length[c] < MIN_CURVE_SEGMENTS && dangles[c]
            }
            Err(_) => false,
        };
        for e in skin_edges.iter_mut().filter(|e| e.2 && e.1[0] != u32::MAX) {
            e.2 = !short(&e.0);
        }
        let kept: Vec<[u32; 2]> = skin_edges.iter().filter(|e| e.2).map(|e| e.0).collect();
        let curves = Curves::new(points, &on_skin, held, &none_folded, kept, Vec::new(), cos_feature);
        // faces joined across smooth edges: the parts (union–find)
        let mut parent: Vec<u32> = (0..faces.len() as u32).collect();
        fn root(parent: &mut [u32], mut i: u32) -> u32 {
            while parent[i as usize] != i {
                parent[i as usize] = parent[parent[i as usize] as usize];
                i = parent[i as usize];
            }
            i
        }
        for &(_, [f, g], feature) in &skin_edges {
            if !feature && f != u32::MAX {
                let (a, b) = (root(&mut parent, f), root(&mut parent, g));
                parent[a.max(b) as usize] = a.min(b);
            }
        }
        let part: Vec<u32> = (0..faces.len() as u32).map(|f| root(&mut parent, f)).collect();
        let kinds: Vec<ElementKind> =
            faces.iter().map(|f| if f.len() == 4 { ElementKind::Quad4 } else { ElementKind::Tri3 }).collect();
        let facets = Facets::new(points, &kinds, |e| faces[e], |e| part[e], |_| 0).with_normals_across_parts();
        // each skin edge once per face it bounds: twice, as every one of a closed skin
        let (mut sum, mut count) = (0.0, 0usize);
        for f in faces {
            for a in 0..f.len() {
                sum += points[f[a] as usize].distance(points[f[(a + 1) % f.len()] as usize]);
                count += 1;
            }
        }
        let mean_edge = if count == 0 { 0.0 } else { sum / count as f64 };
        let reference = Reference { facets, curves, feature_angle_deg, mean_edge };
        let mut sliding = Sliding { hint: vec![NONE; n], tangent: vec![Tangent::Free; n], reference: Arc::new(reference) };
        for (v, &at) in points.iter().enumerate() {
            match sliding.reference.curves.class[v] {
                BoundaryNode::Surface => sliding.hint[v] = sliding.reference.facets.triangle_at_vertex(v),
                BoundaryNode::Curve => sliding.hint[v] = sliding.reference.curves.segs_at(v)[0],
                _ => continue,
            }
            sliding.settle(v, at);
        }
        sliding
    }

    /// What node `n` does.
    #[inline]
    pub(crate) fn class(&self, n: usize) -> BoundaryNode {
        self.reference.curves.class[n]
    }

    /// The feature angle the curves were found by, degrees.
    pub(crate) fn feature_angle_deg(&self) -> f64 {
        self.reference.feature_angle_deg
    }

    /// How many feature curves the skin has.
    pub(crate) fn curve_count(&self) -> usize {
        self.reference.curves.count
    }

    /// The feature edges: their two nodes.
    pub(crate) fn feature_edges(&self) -> &[[u32; 2]] {
        &self.reference.curves.segments
    }

    /// The tangent of node `n` where it is now.
    #[inline]
    pub(crate) fn tangent(&self, n: usize) -> Tangent {
        self.tangent[n]
    }

    /// The point of the reference nearest `x` for sliding node `n` (searched from where
    /// it lies now), its tangent there, and the facet or segment it lies on; `x` itself
    /// for another node.
    pub(crate) fn project(&self, n: usize, x: DVec3) -> (DVec3, Tangent, u32) {
        let r = &*self.reference;
        match r.curves.class[n] {
            BoundaryNode::Surface => {
                let p = r.facets.project(x, self.hint[n]);
                (p.point, Tangent::Plane(p.normal), p.face)
            }
            BoundaryNode::Curve => {
                let foot = r.curves.on_curve(x, self.hint[n]);
                (foot.point, Tangent::Line(foot.tangent), foot.segment)
            }
            _ => (x, Tangent::Free, NONE),
        }
    }

    /// Records that node `n` now lies at `x` (a point of the reference): where its next
    /// search starts, and its tangent.
    pub(crate) fn settle(&mut self, n: usize, x: DVec3) {
        if self.reference.curves.class[n].slides() {
            let (_, tangent, hint) = self.project(n, x);
            self.hint[n] = hint;
            self.tangent[n] = tangent;
        }
    }

    /// The distance of node `n` at `x` from the reference, searched over all of it (not
    /// from where the node lay): from the whole skin for a surface node, from its whole
    /// curve for a curve node; 0 for a node that does not slide.
    pub(crate) fn distance(&self, n: usize, x: DVec3) -> f64 {
        let r = &*self.reference;
        match r.curves.class[n] {
            BoundaryNode::Surface => r.facets.project(x, NONE).point.distance(x),
            BoundaryNode::Curve => r.curves.distance(x, self.hint[n]),
            _ => 0.0,
        }
    }
}

impl super::VolumeMesh {
    /// Sets what boundary nodes do from now on. [`BoundaryRule::Slide`] finds the feature
    /// curves of the boundary as it is now, by `feature_angle_deg`, and takes it as the
    /// reference the sliding nodes stay on; [`BoundaryRule::Fixed`] holds them again.
    /// Linear meshes only: a quadratic mesh's boundary nodes stay (its mid-edge nodes
    /// would leave the curved faces).
    pub fn set_boundary(&mut self, rule: BoundaryRule, feature_angle_deg: f64) {
        if rule == BoundaryRule::Fixed || self.is_quadratic() {
            self.sliding = None;
            return;
        }
        let faces: Vec<&[u32]> = self.boundary_faces().iter().map(|f| f.nodes()).collect();
        let mut on_skin = vec![false; self.node_count()];
        for f in &faces {
            for &v in *f {
                on_skin[v as usize] = true;
            }
        }
        let (held, freed) = crate::mesh::held_nodes(&on_skin, self.given_fixed.as_ref(), |v| self.role(v));
        let sliding = Sliding::new(self.nodes(), &faces, &held, &freed, feature_angle_deg);
        self.sliding = Some(sliding);
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
    pub fn boundary_node(&self, n: usize) -> Option<BoundaryNode> {
        self.sliding.as_ref().map(|s| s.class(n))
    }

    /// The feature edges of the boundary (their two nodes) when boundary nodes slide.
    pub fn feature_edges(&self) -> &[[u32; 2]] {
        self.sliding.as_ref().map_or(&[], |s| s.feature_edges())
    }

    /// The feature angle and the number of feature curves, when boundary nodes slide.
    pub fn feature_curves(&self) -> Option<(f64, usize)> {
        self.sliding.as_ref().map(|s| (s.feature_angle_deg(), s.curve_count()))
    }

    /// The tangent node `n` moves in ([`Tangent::Free`] unless it slides).
    #[inline]
    pub fn tangent(&self, n: usize) -> Tangent {
        self.sliding.as_ref().map_or(Tangent::Free, |s| s.tangent(n))
    }

    /// Where node `n` would be moved to `x`: `x` itself, or for a sliding node the nearest
    /// point of its curve or smooth part of the boundary as loaded.
    #[inline]
    pub fn onto_boundary(&self, n: usize, x: DVec3) -> DVec3 {
        match &self.sliding {
            Some(s) if s.class(n).slides() => s.project(n, x).0,
            _ => x,
        }
    }

    /// Records that node `n` was moved (to a point [`onto_boundary`](Self::onto_boundary)
    /// gave): its tangent there. A caller that moves a node itself (the page's one-node
    /// solve, its undo) calls it after the move.
    #[inline]
    pub fn settle(&mut self, n: usize) {
        let x = self.nodes()[n];
        if let Some(s) = &mut self.sliding {
            s.settle(n, x);
        }
    }

    /// The mean length of the boundary skin's edges as loaded, when boundary nodes slide.
    pub fn skin_mean_edge(&self) -> Option<f64> {
        self.sliding.as_ref().map(|s| s.reference.mean_edge)
    }

    /// The largest distance of a sliding node from the boundary as loaded (0 when none
    /// slides).
    pub fn max_distance_from_boundary(&self) -> f64 {
        let Some(s) = &self.sliding else { return 0.0 };
        (0..self.node_count()).map(|n| s.distance(n, self.nodes()[n])).fold(0.0, f64::max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{hex_grid, HexBlock};
    use crate::model::Model;
    use crate::smoothing::Smoothing;
    use crate::volume::VolumeMesh;

    /// Which of the unit cube's planes x, y, z = 0 or 1 point `p` lies on.
    fn planes(p: DVec3) -> usize {
        p.to_array().iter().filter(|&&c| c == 0.0 || c == 1.0).count()
    }

    /// The unit cube in 4³ hexahedra with its boundary nodes moved within their faces and
    /// along their edges (each kept on its planes), the interior perturbed too: a
    /// boundary placed no better than its interior.
    fn badly_placed_block() -> VolumeMesh {
        let mut m = hex_grid(&HexBlock::cube(4)).unwrap();
        let mut rng = crate::objective::testing::SplitMix64::new(7);
        for p in m.nodes_mut() {
            let mut q = *p;
            for c in 0..3 {
                if p[c] != 0.0 && p[c] != 1.0 {
                    q[c] += rng.uniform(-0.09, 0.09);
                }
            }
            *p = q;
        }
        m
    }

    /// The page's "Smooth this node" solves one star as the drivers do: a sliding node in
    /// its tangent plane or line (issue 58: it was solved in space, then projected), so
    /// every boundary node of the badly placed block solves to a point on its planes.
    #[test]
    fn one_node_s_solve_keeps_a_sliding_node_in_its_tangent() {
        use crate::objective::{solid_objective, CornerStar, ObjectiveKind};
        use crate::smooth::{solve_corner_star, DriverStar, SmoothOptions};
        let mut m = badly_placed_block();
        m.set_boundary(BoundaryRule::Slide, 60.0);
        let objective = solid_objective(ObjectiveKind::SmoothShape).unwrap();
        let mut solved = 0;
        for n in (0..m.node_count()).filter(|&n| matches!(m.boundary_node(n), Some(BoundaryNode::Surface | BoundaryNode::Curve))) {
            let mut star = CornerStar::default();
            star.gather(&m, n);
            let p = m.nodes()[n];
            let r = solve_corner_star(&*objective, &star, p, &SmoothOptions::default()).unwrap();
            for c in 0..3 {
                if p[c] == 0.0 || p[c] == 1.0 {
                    assert_eq!(r.x[c], p[c], "node {n} left its plane: {p} to {}", r.x);
                }
            }
            solved += (r.x != p) as usize;
        }
        assert!(solved > 20, "{solved}");
    }

    #[test]
    fn a_cube_s_corners_edges_and_faces_are_found() {
        let mut m = hex_grid(&HexBlock::cube(3)).unwrap();
        m.set_boundary(BoundaryRule::Slide, FEATURE_ANGLE_DEG);
        let (_, curves) = m.feature_curves().unwrap();
        assert_eq!(curves, 12, "the cube's twelve edges");
        assert_eq!(m.feature_edges().len(), 12 * 3);
        for n in 0..m.node_count() {
            let want = match planes(m.nodes()[n]) {
                0 => BoundaryNode::Interior,
                1 => BoundaryNode::Surface,
                2 => BoundaryNode::Curve,
                _ => BoundaryNode::Corner,
            };
            assert_eq!(m.boundary_node(n), Some(want), "node {n} at {}", m.nodes()[n]);
            assert_eq!(m.is_free(n), want != BoundaryNode::Corner, "node {n}");
        }
        // a feature angle above the cube's 90° finds no curve: every boundary node slides
        // on its face, and the cube's corners are nodes of no feature edge either
        m.set_boundary(BoundaryRule::Slide, 100.0);
        assert_eq!(m.feature_curves(), Some((100.0, 0)));
        m.set_boundary(BoundaryRule::Fixed, FEATURE_ANGLE_DEG);
        assert_eq!(m.boundary_node(0), None);
        assert_eq!(m.free_count(), 8);
    }

    #[test]
    fn sliding_nodes_stay_on_their_faces_and_edges_and_corners_hold() {
        let start = badly_placed_block();
        let mut model = Model::Volume(start.clone());
        let fixed = {
            let mut m = Model::Volume(start.clone());
            m.smooth(&Smoothing::default()).unwrap().stats().clone()
        };
        let report = model.smooth(&Smoothing::default().boundary(BoundaryRule::Slide)).unwrap();
        let Model::Volume(m) = &model else { unreachable!() };
        let b = report.boundary().expect("sliding reported");
        assert_eq!((b.corners, b.curves), (8, 12));
        let mut moved = 0;
        for (n, (p, q)) in start.nodes().iter().zip(m.nodes()).enumerate() {
            // on the planes it was on, exactly (the faces are flat: the projection onto them
            // is exact in the doubles up to the rounding of the triangles' closest point)
            for c in 0..3 {
                if p[c] == 0.0 || p[c] == 1.0 {
                    assert!((q[c] - p[c]).abs() < 1e-15, "node {n} left its plane: {p} to {q}");
                }
            }
            if planes(*p) == 3 {
                assert_eq!(p, q, "corner {n} moved");
            }
            moved += (planes(*p) > 0 && p != q) as usize;
        }
        assert!(moved > 50, "only {moved} boundary nodes moved");
        assert!(b.max_distance < 1e-15, "{}", b.max_distance);
        // sliding reaches what the fixed boundary cannot: a better worst element
        let (s, f) = (report.stats(), &fixed);
        assert_eq!(s.inverted, 0);
        let sj = |s: &crate::MeshStats| s.solid.as_ref().unwrap().min_scaled_jacobian;
        assert!(sj(s) > sj(f) + 0.05, "scaled Jacobian: slide {} fixed {}", sj(s), sj(f));
        assert!(s.min_angle_deg > f.min_angle_deg, "{} vs {}", s.min_angle_deg, f.min_angle_deg);
    }

    #[test]
    fn a_fold_is_not_a_crease() {
        // the middle node of the cube's top face pulled past the face's edge, within its
        // plane: the two quads beyond it fold over (each a bow tie, or turned against the
        // skin), and they meet their neighbours at 180°, yet no edge of theirs is a crease
        // and the node slides on the face rather than being a corner
        let mut m = hex_grid(&HexBlock::cube(2)).unwrap();
        let top = (0..m.node_count()).find(|&n| m.nodes()[n] == DVec3::new(0.5, 0.5, 1.0)).unwrap();
        m.nodes_mut()[top].x = 1.3;
        assert!((0..m.element_count()).filter(|&e| m.is_inverted(e)).count() >= 2);
        m.set_boundary(BoundaryRule::Slide, FEATURE_ANGLE_DEG);
        assert_eq!(m.boundary_node(top), Some(BoundaryNode::Surface));
        assert!(m.feature_edges().iter().all(|e| !e.contains(&(top as u32))));
    }

    #[test]
    fn the_file_s_fixed_nodes_stay() {
        let mut m = badly_placed_block();
        let held = (0..m.node_count()).find(|&n| planes(m.nodes()[n]) == 1).unwrap();
        let mut flags = m.fixed().to_vec();
        flags.iter_mut().for_each(|f| *f = false);
        flags[held] = true;
        m.given_fixed = Some(crate::mesh::GivenFlags { flags, exact: true });
        m.set_boundary(BoundaryRule::Slide, FEATURE_ANGLE_DEG);
        assert_eq!(m.boundary_node(held), Some(BoundaryNode::Held));
        let at = m.nodes()[held];
        let mut model = Model::Volume(m);
        model.smooth(&Smoothing::default().boundary(BoundaryRule::Slide)).unwrap();
        let Model::Volume(m) = &model else { unreachable!() };
        assert_eq!(m.nodes()[held], at);
    }

    #[test]
    fn flags_on_the_whole_skin_only_say_where_the_boundary_is() {
        // what smoothlab writes: every boundary node flagged fixed, and one node inside
        let mut m = badly_placed_block();
        let inside = (0..m.node_count()).find(|&n| planes(m.nodes()[n]) == 0).unwrap();
        let mut flags = m.fixed().to_vec();
        flags[inside] = true;
        m.given_fixed = Some(crate::mesh::GivenFlags { flags, exact: true });
        m.set_boundary(BoundaryRule::Slide, FEATURE_ANGLE_DEG);
        for n in 0..m.node_count() {
            let want = match planes(m.nodes()[n]) {
                _ if n == inside => BoundaryNode::Held,
                0 => BoundaryNode::Interior,
                1 => BoundaryNode::Surface,
                2 => BoundaryNode::Curve,
                _ => BoundaryNode::Corner,
            };
            assert_eq!(m.boundary_node(n), Some(want), "node {n}");
        }
    }

    #[test]
    fn a_tangent_projects_vectors_and_hessians() {
        let n = DVec3::new(1.0, 2.0, 2.0) / 3.0;
        let v = DVec3::new(0.3, -1.0, 4.0);
        let plane = Tangent::Plane(n);
        assert!(plane.along(v).dot(n).abs() < 1e-15);
        assert!(plane.along(n).length() < 1e-15);
        let line = Tangent::Line(n);
        assert!((line.along(v) - n * v.dot(n)).length() < 1e-15);
        assert_eq!(Tangent::Free.along(v), v);
        // P·H·P is symmetric, and zero along the normal
        let h = DMat3::from_cols(DVec3::new(2.0, 0.5, 0.1), DVec3::new(0.5, 3.0, -0.2), DVec3::new(0.1, -0.2, 1.0));
        let p = plane.along_hessian(h);
        assert!((p - p.transpose()).abs().to_cols_array().iter().all(|&x| x < 1e-15));
        assert!((p * n).length() < 1e-14);
        // a vector in the plane sees H's own quadratic form
        let u = plane.along(v);
        assert!((u.dot(p * u) - u.dot(h * u)).abs() < 1e-12);
    }
}
