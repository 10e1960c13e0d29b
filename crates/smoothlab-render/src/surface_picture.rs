//! A surface drawn by the 3D view ([`render_surface`]): its elements as faces coloured
//! by a quality metric measured in their own planes, inverted ones hatched.

use glam::DVec3;
use tiny_skia::Pixmap;

use smoothlab::surface::Surface;
use smoothlab::quality::element_quality;
use smoothlab::mesh::BoundaryNode;
use crate::{render_surface_marked, FaceMarks, Faces, Mark, Metric, NodeMark, Projection, SurfaceView};

/// The faces of a surface as the 3D view takes them: each element's outline (corner,
/// mid-side node, corner, … for a quadratic one), its metric value scaled onto [0, 1] by
/// the metric's domain, and whether it is inverted.
#[derive(Clone, Debug, Default)]
pub struct SurfaceFaces {
    pub ring_start: Vec<u32>,
    pub rings: Vec<u32>,
    pub values: Vec<f64>,
    pub inverted: Vec<bool>,
}

impl SurfaceFaces {
    /// The faces over the surface's points.
    pub fn faces<'a>(&'a self, points: &'a [DVec3]) -> Faces<'a> {
        Faces {
            points,
            ring_start: &self.ring_start,
            rings: &self.rings,
            values: &self.values,
            inverted: &self.inverted,
            faded: &[],
            // one face an element: the faces flagged are the elements inverted
            inverted_elements: None,
        }
    }
}

/// What the 3D view draws of a surface: its faces by a metric, and the picture.
pub trait SurfacePicture {
    /// The faces the 3D view draws, coloured by `metric`.
    fn faces(&self, metric: Metric) -> SurfaceFaces;
    /// Draws the surface coloured by `metric` with the view's camera, frame and title.
    fn render(&self, pixmap: &mut Pixmap, metric: Metric, view: &SurfaceView) -> Projection;
}

impl SurfacePicture for Surface {
    /// The faces the 3D view draws, coloured by `metric`.
    fn faces(&self, metric: Metric) -> SurfaceFaces {
        let mesh = self.flat();
        let (lo, hi) = metric.domain(mesh);
        let mut f = SurfaceFaces { ring_start: vec![0], ..Default::default() };
        for e in 0..mesh.element_count() {
            let kind = mesh.kind(e);
            let ids = mesh.element(e);
            let k = kind.corners();
            for i in 0..k {
                f.rings.push(ids[i]);
                if let Some(m) = kind.mid(i) {
                    f.rings.push(ids[m]);
                }
            }
            f.ring_start.push(f.rings.len() as u32);
            let q = element_quality(kind, &self.element_points_2d(e)[..kind.node_count()]);
            f.values.push(((metric.value(&q) - lo) / (hi - lo)).clamp(0.0, 1.0));
            f.inverted.push(q.inverted);
        }
        f
    }

    /// Draws the surface coloured by `metric` with the view's camera, frame and title
    /// (its colour bar titled and scaled for the metric); while its curves slide, with
    /// their marks: the curves, the corners and the sliding nodes.
    fn render(&self, pixmap: &mut Pixmap, metric: Metric, view: &SurfaceView) -> Projection {
        let faces = self.faces(metric);
        let opts = SurfaceView {
            bar_title: metric.label(self.flat()).to_string(),
            domain: metric.domain(self.flat()),
            ..view.clone()
        };
        let marks = surface_marks(self, &faces);
        render_surface_marked(pixmap, &faces.faces(self.points()), &opts, marks.as_ref())
    }
}

/// Each face's edges on a curve, and its curve nodes that stay or slide, while the
/// surface's curves slide ([`Surface::curve_nodes`]); `None` while they are held.
fn surface_marks(surface: &Surface, faces: &SurfaceFaces) -> Option<FaceMarks> {
    let nodes = surface.curve_nodes()?;
    let curve: std::collections::HashSet<[u32; 2]> = surface.curve_edges().map(|[a, b]| [a.min(b), a.max(b)]).collect();
    let mut out = FaceMarks { start: vec![0], marks: Vec::new() };
    for f in 0..faces.ring_start.len().saturating_sub(1) {
        let ring = &faces.rings[faces.ring_start[f] as usize..faces.ring_start[f + 1] as usize];
        // a quadratic element's ring has a mid-side node between its corners
        let step = if ring.len() >= 6 { 2 } else { 1 };
        for i in (0..ring.len()).step_by(step) {
            let (a, b) = (ring[i], ring[(i + step) % ring.len()]);
            if curve.contains(&[a.min(b), a.max(b)]) {
                out.marks.push(Mark::Line(a, b));
            }
        }
        for &v in ring {
            match nodes[v as usize] {
                BoundaryNode::Corner | BoundaryNode::Held => out.marks.push(Mark::Node(v, NodeMark::Stays)),
                BoundaryNode::Curve => out.marks.push(Mark::Node(v, NodeMark::Slides)),
                _ => {}
            }
        }
        out.start.push(out.marks.len() as u32);
    }
    Some(out)
}
