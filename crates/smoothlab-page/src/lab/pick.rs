//! Choosing a node by pointing at it: the nearest node of any kind within reach, and when
//! it is not one the smoothers move, why not, in words the page shows as it is.

use glam::DVec2;
use serde::Serialize;

use super::{Playground, Side};
use smoothlab::mesh::{Mesh, NodeRole};
use smoothlab::quality::element_quality;
use smoothlab_render::View;

/// What a press at a point of a panel found.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Pick {
    /// The free node chosen, if the nearest node within reach is one.
    pub node: Option<usize>,
    /// The nearest node within reach, whatever its kind.
    pub nearest: Option<usize>,
    /// Why nothing was chosen (no node within reach, or the nearest one is fixed or
    /// follows its element), for people.
    pub message: Option<String>,
}

/// Why node `n` cannot be chosen or moved, if it cannot.
pub fn why_not_free(mesh: &Mesh, n: usize) -> Option<String> {
    if n >= mesh.node_count() {
        return Some(format!(
            "there is no node {n}: the nodes are numbered 0 to {}",
            mesh.node_count().saturating_sub(1)
        ));
    }
    if mesh.boundary_node(n).is_some_and(|c| c.slides()) {
        return Some(format!("node {n} slides along the boundary with the passes: choose or drag a node inside"));
    }
    if mesh.is_free(n) {
        return None;
    }
    Some(match mesh.role(n) {
        NodeRole::Mid => format!(
            "node {n} is a mid-side node of a quadratic element: it follows the two corners of its edge, so choose a corner"
        ),
        NodeRole::Centre => format!("node {n} is the centre node of a 9-node quad: it follows its element's corners"),
        NodeRole::Unused => format!("node {n} belongs to no element"),
        NodeRole::Corner if mesh.is_boundary(n) => {
            format!("node {n} is fixed: it is on the boundary, and smoothing keeps the boundary in place")
        }
        NodeRole::Corner => format!("node {n} is fixed (the file marks it so), so smoothing never moves it"),
    })
}

impl Playground {
    /// The node nearest to the CSS pixel `css` of `side`'s panel within `radius` CSS
    /// pixels: chosen when it is free, otherwise said why not.
    pub fn pick(&self, side: Side, view: &View, css: DVec2, radius: f64) -> Pick {
        let mesh = &self.panel(side).mesh;
        let mut nearest = None;
        let mut best = radius * radius;
        if css.is_finite() {
            for (n, p) in mesh.nodes().iter().enumerate() {
                if mesh.role(n) == NodeRole::Unused {
                    continue;
                }
                let d2 = view.to_css(*p).distance_squared(css);
                // a free node wins a tie with a node drawn at the same place
                if d2 < best || (d2 == best && why_not_free(mesh, n).is_none()) {
                    best = d2;
                    nearest = Some(n);
                }
            }
        }
        match nearest {
            None => Pick {
                node: None,
                nearest: None,
                message: Some(format!("No node within {radius:.0} pixels of that point: press on a node (a dot where edges meet).")),
            },
            Some(n) => match why_not_free(mesh, n) {
                None => Pick { node: Some(n), nearest: Some(n), message: None },
                Some(why) => Pick { node: None, nearest: Some(n), message: Some(sentence(&why)) },
            },
        }
    }
}

/// A reason as a sentence: its first letter a capital, a full stop at the end.
pub(crate) fn sentence(why: &str) -> String {
    let mut chars = why.chars();
    let first: String = chars.next().map(|c| c.to_uppercase().collect()).unwrap_or_default();
    format!("{first}{}.", chars.as_str())
}

/// The free node whose star has the smallest element quality (α/β), if any node is free
/// (a sliding boundary node is not chosen: [`why_not_free`]):
/// the node `smoothlab render` studies and an embedded level-set view opens on.
pub fn worst_free_node(mesh: &Mesh) -> Option<usize> {
    let q: Vec<f64> = (0..mesh.element_count())
        .map(|e| {
            let p = mesh.element_points_array(e);
            element_quality(mesh.kind(e), &p[..mesh.kind(e).node_count()]).shape
        })
        .collect();
    (0..mesh.node_count())
        .filter(|&n| why_not_free(mesh, n).is_none())
        .map(|n| (n, mesh.node_elements(n).iter().map(|&e| q[e as usize]).fold(f64::INFINITY, f64::min)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(n, _)| n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lab::sample::Sample;
    use crate::lab::views::Canvas;

    const C: Canvas = Canvas { w: 400, h: 400, dpr: 1.0 };

    #[test]
    fn a_press_near_a_free_node_chooses_it_and_near_a_fixed_one_says_why_not() {
        let pg = Playground::new(Sample::StarRegular.generate().unwrap()).unwrap();
        let view = pg.panel_view(C);
        let free = pg.topology().node_count() - 1;
        let at = view.to_css(pg.original_nodes()[free]);
        let p = pg.pick(Side::A, &view, at + DVec2::new(10.0, 5.0), 16.0);
        assert_eq!((p.node, p.message), (Some(free), None));
        let p = pg.pick(Side::A, &view, view.to_css(pg.original_nodes()[0]), 16.0);
        assert_eq!((p.node, p.nearest), (None, Some(0)));
        assert_eq!(p.message.unwrap(), "Node 0 is fixed: it is on the boundary, and smoothing keeps the boundary in place.");
        let far = pg.pick(Side::A, &view, DVec2::new(-500.0, -500.0), 16.0);
        assert!(far.node.is_none() && far.message.unwrap().starts_with("No node within 16 pixels"));
    }

    #[test]
    fn a_mid_side_node_is_named_as_one() {
        let pg = Playground::new(Sample::PlateQuadratic.generate().unwrap()).unwrap();
        let m = pg.topology();
        let mid = (0..m.node_count()).find(|&n| m.role(n) == NodeRole::Mid && !m.is_boundary(n)).unwrap();
        let why = why_not_free(m, mid).unwrap();
        assert!(why.contains("mid-side node") && why.contains(&format!("node {mid}")), "{why}");
        let view = pg.panel_view(C);
        let p = pg.pick(Side::B, &view, view.to_css(pg.original_nodes()[mid]), 2.0);
        assert_eq!(p.nearest, Some(mid));
        assert!(p.message.unwrap().contains("mid-side"));
        assert!(why_not_free(m, m.node_count()).unwrap().contains("no node"));
    }
}
