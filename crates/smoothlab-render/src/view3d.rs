//! The 3D view of a surface mesh: faces (triangles and quads, linear or quadratic) in
//! space, seen by an orbit [`Camera`], filled with their quality colour and shaded.
//!
//! - **Projection**: orthographic. The camera looks at the centre of the points'
//!   bounding box from the direction set by its yaw and pitch; the bounding sphere (about
//!   that centre, through the farthest point) fills the frame's shorter side less the
//!   margin at zoom 1, so no turn of the camera takes a point out of the frame. An
//!   orthographic projection is affine, so a quadratic edge (a parabola in space) stays
//!   a parabola on screen and is drawn exactly as a quadratic Bézier through its mid node.
//! - **Depth sort**: the painter's algorithm. Faces are painted from the farthest to the
//!   nearest by the depth of their centroid (the mean of the ring's nodes); faces at
//!   equal depth go in face order, so the picture is deterministic. Faces that pierce one
//!   another, or long faces overlapping short ones, can be ordered wrongly: it is a view
//!   for looking at a mesh, not a z-buffer.
//! - **Light**: one directional light fixed to the camera (from the viewer's upper left,
//!   towards the scene), Lambert with an ambient term: a face's colour is multiplied by
//!   `AMBIENT + (1 − AMBIENT)·|n·l|`, with `n` the ring's Newell normal, so both sides
//!   are lit. A face seen from its back (its normal points away from the viewer) is
//!   darkened further by [`BACK_FACE`].
//!
//! The data are plain slices ([`Faces`]), so any surface mesh can be drawn.

use glam::{DVec2, DVec3};
use tiny_skia::{Color, FillRule, Mask, PathBuilder, Pixmap, Rect, Stroke, Transform};

use super::colormap::{bucket, bucket_color, Colormap};
use super::mesh::{bezier_control, colour_bar_band, draw_colour_bar, draw_inverted};
use super::theme::Theme;
use super::paint::{fill_rect, rect_mask, rgba, solid};
use super::text::{draw_text, Align, TextStyle, Valign};
use super::view::{sane_dpr, Frame};
use smoothlab::numeric::order::{sort_stable_by_key, total_order_key};
use smoothlab::{Error, Result};

/// An orbit camera: it turns about the vertical (z) axis by `yaw` and rises above the
/// horizon by `pitch`, always looking at the centre of the picture's bounding box.
///
/// At yaw 0 and pitch 0 the viewer stands on the −y side looking along +y: +x points
/// right on screen and +z up. A positive yaw carries the viewer counter-clockwise about
/// +z (seen from above), towards +x; a positive pitch lifts the viewer, who then looks
/// down.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Degrees about +z.
    pub yaw: f64,
    /// Degrees above the horizon, in [−90, 90].
    pub pitch: f64,
    /// Magnification over the fitted view (1: the bounding sphere fills the frame).
    pub zoom: f64,
}

impl Default for Camera {
    /// A three-quarter view from above: yaw 30°, pitch 25°, zoom 1.
    fn default() -> Self {
        Camera { yaw: 30.0, pitch: 25.0, zoom: 1.0 }
    }
}

/// The range of [`Camera::zoom`] a picture uses (values outside are clamped).
pub const ZOOM_RANGE: (f64, f64) = (0.01, 100.0);
/// The pitch a drag stops at, degrees: short of the poles, where yaw would spin the view.
pub const MAX_DRAG_PITCH: f64 = 89.0;
/// Degrees of yaw or pitch per CSS pixel of a drag in [`Camera::orbited`].
pub const DEGREES_PER_PIXEL: f64 = 0.5;

impl Camera {
    /// Parses `"yaw,pitch"` or `"yaw,pitch,zoom"` (degrees, degrees, factor), e.g.
    /// `30,25,1.5`, as a `--camera` option gives it.
    pub fn parse(text: &str) -> Result<Camera> {
        let parts: Vec<&str> = text.split(',').map(str::trim).collect();
        if !(2..=3).contains(&parts.len()) {
            return Err(Error::Invalid(format!(
                "camera \"{text}\": expected yaw,pitch or yaw,pitch,zoom (degrees, degrees, factor), e.g. 30,25,1.5"
            )));
        }
        let names = ["yaw", "pitch", "zoom"];
        let mut v = [0.0, 0.0, 1.0];
        for (k, part) in parts.iter().enumerate() {
            v[k] = part
                .parse::<f64>()
                .map_err(|_| Error::Invalid(format!("camera \"{text}\": {} \"{part}\" is not a number", names[k])))?;
            if !v[k].is_finite() {
                return Err(Error::Invalid(format!("camera \"{text}\": {} \"{part}\" is not finite", names[k])));
            }
        }
        let [yaw, pitch, zoom] = v;
        if !(-90.0..=90.0).contains(&pitch) {
            return Err(Error::Invalid(format!("camera \"{text}\": pitch {pitch} is outside [-90, 90] degrees")));
        }
        if zoom <= 0.0 {
            return Err(Error::Invalid(format!("camera \"{text}\": zoom {zoom} must be greater than 0")));
        }
        Ok(Camera { yaw, pitch, zoom })
    }

    /// Turned by a drag of `(dx, dy)` CSS pixels: right turns the model to the right
    /// (the viewer moves left, yaw falls), down tips its top towards the viewer (the
    /// viewer rises, pitch grows), [`DEGREES_PER_PIXEL`] each, pitch held within
    /// ±[`MAX_DRAG_PITCH`] and yaw kept in [0, 360).
    pub fn orbited(self, dx: f64, dy: f64) -> Camera {
        let (dx, dy) = (if dx.is_finite() { dx } else { 0.0 }, if dy.is_finite() { dy } else { 0.0 });
        let yaw = (self.yaw - DEGREES_PER_PIXEL * dx).rem_euclid(360.0);
        let pitch = (self.pitch + DEGREES_PER_PIXEL * dy).clamp(-MAX_DRAG_PITCH, MAX_DRAG_PITCH);
        Camera {
            yaw: if yaw.is_finite() { yaw } else { 0.0 },
            pitch: if pitch.is_finite() { pitch } else { 0.0 },
            ..self
        }
    }

    /// Magnified by `factor` (a wheel step), within [`ZOOM_RANGE`]; a factor that is not
    /// positive and finite changes nothing.
    pub fn zoomed(self, factor: f64) -> Camera {
        if !(factor.is_finite() && factor > 0.0) {
            return self;
        }
        Camera { zoom: (self.sane_zoom() * factor).clamp(ZOOM_RANGE.0, ZOOM_RANGE.1), ..self }
    }

    fn sane_zoom(&self) -> f64 {
        if self.zoom.is_finite() && self.zoom > 0.0 {
            self.zoom.clamp(ZOOM_RANGE.0, ZOOM_RANGE.1)
        } else {
            1.0
        }
    }

    /// The camera's screen-right, screen-up and viewing direction (into the scene), unit
    /// vectors in world coordinates.
    pub fn basis(&self) -> (DVec3, DVec3, DVec3) {
        let yaw = if self.yaw.is_finite() { self.yaw.to_radians() } else { 0.0 };
        let pitch = if self.pitch.is_finite() { self.pitch.clamp(-90.0, 90.0).to_radians() } else { 0.0 };
        let (sy, cy) = yaw.sin_cos();
        let (sp, cp) = pitch.sin_cos();
        let right = DVec3::new(cy, sy, 0.0);
        let forward = DVec3::new(-sy * cp, cy * cp, -sp);
        (right, right.cross(forward), forward)
    }
}

/// The faces of a surface mesh as flat slices (CSR).
///
/// Face `f`'s outline is `rings[ring_start[f]..ring_start[f + 1]]`, node ids in order
/// around it. A ring of 6 or 8 nodes is a quadratic triangle or quad listed corner, mid,
/// corner, mid, …, and its edges are drawn as the parabolas through the mid nodes; any
/// other ring (3 or 4 nodes for linear faces) is drawn as a polygon. `values[f]` in
/// [0, 1] is the face's place on the colour map; `inverted[f]` marks an inverted element;
/// `faded[f]` draws the face pale, behind what matters (a tetrahedral mesh's boundary
/// around its cut). Missing values count as 0 and missing flags as not inverted and not
/// faded; a face with a node id
/// out of range, fewer than 3 nodes, or a coordinate that is not finite is not drawn.
///
/// The colour bar's "N inverted" counts elements: `inverted_elements` where the faces are
/// not one an element (a volume mesh's cut, whose count is the mesh's,
/// [`VolumePicture`](crate::VolumePicture)); when `None`, the faces flagged inverted
/// (a surface's, each face an element).
#[derive(Clone, Copy, Debug, Default)]
pub struct Faces<'a> {
    pub points: &'a [DVec3],
    pub ring_start: &'a [u32],
    pub rings: &'a [u32],
    pub values: &'a [f64],
    pub inverted: &'a [bool],
    pub faded: &'a [bool],
    pub inverted_elements: Option<usize>,
}

impl Faces<'_> {
    /// How many faces `ring_start` describes.
    pub fn count(&self) -> usize {
        self.ring_start.len().saturating_sub(1)
    }

    /// Face `f`'s ring, or `None` when it is malformed (bad range, fewer than 3 nodes, a
    /// node id out of range, a coordinate that is not finite).
    pub fn ring(&self, f: usize) -> Option<&[u32]> {
        let (a, b) = (*self.ring_start.get(f)? as usize, *self.ring_start.get(f + 1)? as usize);
        let ring = self.rings.get(a..b)?;
        let ok = ring.len() >= 3 && ring.iter().all(|&n| self.points.get(n as usize).is_some_and(|p| p.is_finite()));
        ok.then_some(ring)
    }
}

/// Options of [`render_surface`].
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceView {
    /// Default [`Camera::default`].
    pub camera: Camera,
    /// Device-pixel ratio (device pixels per CSS pixel). Default 1.
    pub dpr: f32,
    /// Where to draw, in CSS pixels. Default `None`: the whole pixmap.
    pub frame: Option<Frame>,
    /// Space around the bounding sphere, CSS pixels. Default 16.
    pub margin: f32,
    /// Stroke the face outlines thin and dark. Default true.
    pub show_edges: bool,
    /// A title above the picture. Default none.
    pub title: Option<String>,
    /// Draw the colour bar: a thin band along the bottom, left out when the frame is too
    /// small for it ([`colour_bar_band`](super::colour_bar_band)). Default true.
    pub colour_bar: bool,
    /// The colour bar's title. Default "quality".
    pub bar_title: String,
    /// What the values 0 and 1 stand for, for the colour bar's ticks. Default (0, 1).
    pub domain: (f64, f64),
    /// Default viridis.
    pub colormap: Colormap,
    /// Colours (its paper filled first) and label sizes. Default [`Theme::light`].
    pub theme: Theme,
}

impl Default for SurfaceView {
    fn default() -> Self {
        SurfaceView {
            camera: Camera::default(),
            dpr: 1.0,
            frame: None,
            margin: 16.0,
            show_edges: true,
            title: None,
            colour_bar: true,
            bar_title: "quality".to_string(),
            domain: (0.0, 1.0),
            colormap: Colormap::Viridis,
            theme: Theme::light(),
        }
    }
}

/// The share of a face's colour it keeps when the light grazes it.
pub const AMBIENT: f64 = 0.35;
/// Brightness factor of a face seen from its back.
pub const BACK_FACE: f64 = 0.6;
/// CSS pixels above the picture a title takes.
const TITLE_H: f32 = 26.0;
/// Device coordinates beyond which a face is clipped before it is drawn (tiny-skia's
/// rasterizer fails on paths millions of pixels across).
const FAR_PX: f32 = 65_536.0;

/// The direction light travels in (from the viewer's upper left towards the scene), in
/// camera coordinates (right, up, into the scene).
fn light_in_camera() -> DVec3 {
    DVec3::new(0.45, -0.55, 0.7).normalize()
}

/// The camera's mapping from world points to CSS pixels, as [`render_surface`] used it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Projection {
    /// World point drawn at the centre of the picture.
    centre: DVec3,
    right: DVec3,
    up: DVec3,
    forward: DVec3,
    /// CSS pixels per world unit.
    scale: f64,
    /// Centre of the picture, CSS pixels.
    frame_centre: DVec2,
    dpr: f64,
}

impl Projection {
    /// The projection of `points` (those with finite coordinates) by `camera` into
    /// `frame` (CSS pixels) less `margin`, at device-pixel ratio `dpr`. With no finite
    /// point, or all of them equal, the bounding sphere is taken of radius 1.
    ///
    /// The centre is the middle of the points' bounding box and the sphere's radius the
    /// distance from it to the farthest point.
    pub fn fit(points: &[DVec3], camera: &Camera, frame: Frame, margin: f32, dpr: f32) -> Projection {
        let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        for p in points.iter().filter(|p| p.is_finite()) {
            lo = lo.min(*p);
            hi = hi.max(*p);
        }
        let centre = if lo.x <= hi.x { 0.5 * lo + 0.5 * hi } else { DVec3::ZERO };
        let centre = if centre.is_finite() { centre } else { DVec3::ZERO };
        // the sphere about the box's centre through the farthest point: it holds every
        // point whichever way the camera turns
        let mut radius = points.iter().filter(|p| p.is_finite()).map(|p| p.distance(centre)).fold(0.0, f64::max);
        if !(radius.is_finite() && radius > 1e-300) {
            radius = 1.0;
        }
        let avail = 0.5 * ((frame.w.min(frame.h) - 2.0 * margin).max(1.0) as f64);
        let (right, up, forward) = camera.basis();
        Projection {
            centre,
            right,
            up,
            forward,
            scale: avail / radius * camera.sane_zoom(),
            frame_centre: frame.centre(),
            dpr: sane_dpr(dpr) as f64,
        }
    }
    /// CSS pixels per world unit.
    pub fn scale(&self) -> f64 {
        self.scale
    }
    /// The world point drawn at the centre of the picture (the bounding box's centre).
    pub fn centre(&self) -> DVec3 {
        self.centre
    }
    /// The viewing direction (unit, into the scene).
    pub fn forward(&self) -> DVec3 {
        self.forward
    }
    /// World point → CSS pixel (x right, y down).
    pub fn to_css(&self, p: DVec3) -> DVec2 {
        let d = p - self.centre;
        self.frame_centre + self.scale * DVec2::new(d.dot(self.right), -d.dot(self.up))
    }
    /// World point → device pixel.
    pub fn to_device(&self, p: DVec3) -> DVec2 {
        self.to_css(p) * self.dpr
    }
    /// Distance of `p` in front of (negative) or behind (positive) the plane through the
    /// centre facing the viewer, in world units: larger is farther from the viewer.
    pub fn depth(&self, p: DVec3) -> f64 {
        (p - self.centre).dot(self.forward)
    }
    /// The point of `points` under the CSS pixel `(px, py)`: among the points within
    /// `radius` CSS pixels of it, those no more than `radius` (in pixels of the picture's
    /// scale) behind the front-most one are kept, so a point on the far side of the
    /// surface never wins over one on the near side, and of those the nearest on screen
    /// wins (ties: the lower index). `None` when no point is within `radius`.
    pub fn pick(&self, points: &[DVec3], px: f64, py: f64, radius: f64) -> Option<usize> {
        let c = DVec2::new(px, py);
        if !(c.is_finite() && radius.is_finite() && radius >= 0.0) {
            return None;
        }
        let near: Vec<(usize, f64, f64)> = points
            .iter()
            .enumerate()
            .filter(|(_, p)| p.is_finite())
            .map(|(i, p)| (i, self.to_css(*p).distance_squared(c), self.depth(*p) * self.scale))
            .filter(|&(_, d2, z)| d2 <= radius * radius && z.is_finite())
            .collect();
        let front = near.iter().map(|n| n.2).fold(f64::INFINITY, f64::min);
        near.iter()
            .filter(|n| n.2 <= front + radius)
            .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)))
            .map(|n| n.0)
    }
}

impl Projection {
    /// The face of `faces` drawn over the CSS pixel `(px, py)` by [`render_surface`] with
    /// this projection: of the faces whose outline (its ring's nodes joined by straight
    /// lines) holds the point, the one painted last (the nearest by the depth of its
    /// centroid; at equal depth the later face). `None` when no face is there.
    pub fn face_at(&self, faces: &Faces, px: f64, py: f64) -> Option<usize> {
        let c = DVec2::new(px, py);
        if !c.is_finite() {
            return None;
        }
        let mut best: Option<(f64, usize)> = None;
        for f in 0..faces.count() {
            let Some(ring) = faces.ring(f) else { continue };
            let poly: Vec<DVec2> = ring.iter().map(|&n| self.to_css(faces.points[n as usize])).collect();
            if !polygon_holds(&poly, c) {
                continue;
            }
            let z = ring.iter().map(|&n| self.depth(faces.points[n as usize])).sum::<f64>() / ring.len() as f64;
            if best.map_or(true, |(bz, _)| z <= bz) {
                best = Some((z, f));
            }
        }
        best.map(|(_, f)| f)
    }

    /// The node of the face drawn over the CSS pixel `(px, py)` ([`face_at`](Self::face_at))
    /// nearest to it on screen (ties: the first in the ring), or `None` when no face is there.
    pub fn pick_on_faces(&self, faces: &Faces, px: f64, py: f64) -> Option<usize> {
        let f = self.face_at(faces, px, py)?;
        let c = DVec2::new(px, py);
        let ring = faces.ring(f)?;
        ring.iter()
            .map(|&n| (n as usize, self.to_css(faces.points[n as usize]).distance_squared(c)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(n, _)| n)
    }
}

/// Whether the closed polygon `poly` holds `p` (even–odd rule), a point on its outline
/// (within a millionth of a pixel) included: a click on a node is on each face round it.
fn polygon_holds(poly: &[DVec2], p: DVec2) -> bool {
    let on_edge = (0..poly.len()).any(|i| {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        let ab = b - a;
        let t = if ab.length_squared() > 0.0 { ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0) } else { 0.0 };
        (a + t * ab).distance_squared(p) <= 1e-12
    });
    if on_edge {
        return true;
    }
    let mut inside = false;
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        if (a.y > p.y) != (b.y > p.y) {
            let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
            if p.x < x {
                inside = !inside;
            }
        }
    }
    inside
}

/// Marks a chosen node on a picture drawn with `proj`, as the planar mesh view marks
/// it: its star's edges (`star`, polylines in space) and a ring round the node, in the
/// highlight's orange over a dark halo, on top of everything (a node behind the surface
/// shows where it is).
pub fn draw_node_mark(pixmap: &mut Pixmap, proj: &Projection, node: DVec3, star: &[Vec<DVec3>], dpr: f32) {
    let s = sane_dpr(dpr);
    let orange = rgba(230, 159, 0, 255);
    let mut edges = PathBuilder::new();
    for line in star {
        for (i, p) in line.iter().enumerate() {
            let d = proj.to_device(*p);
            if !d.is_finite() || d.x.abs() > FAR_PX as f64 || d.y.abs() > FAR_PX as f64 {
                break;
            }
            if i == 0 {
                edges.move_to(d.x as f32, d.y as f32);
            } else {
                edges.line_to(d.x as f32, d.y as f32);
            }
        }
    }
    let line = |pm: &mut Pixmap, pb: PathBuilder, c: Color, w: f32| {
        if let Some(path) = pb.finish() {
            let st = Stroke { width: w, line_join: tiny_skia::LineJoin::Round, line_cap: tiny_skia::LineCap::Round, ..Default::default() };
            pm.stroke_path(&path, &solid(c), &st, Transform::identity(), None);
        }
    };
    line(pixmap, edges.clone(), rgba(0, 0, 0, 160), 4.5 * s);
    line(pixmap, edges, orange, 2.5 * s);
    let d = proj.to_device(node);
    if d.is_finite() && d.x.abs() < FAR_PX as f64 && d.y.abs() < FAR_PX as f64 {
        let mut ring = PathBuilder::new();
        ring.push_circle(d.x as f32, d.y as f32, 7.0 * s);
        line(pixmap, ring.clone(), rgba(0, 0, 0, 255), 3.5 * s);
        line(pixmap, ring, orange, 2.0 * s);
    }
}

/// What a node mark of [`FaceMarks`] says of its node.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NodeMark {
    /// The node stays (a corner of a sliding boundary, or fixed by the file): a dark
    /// square with a white rim.
    Stays,
    /// The node slides (along a feature curve or on the boundary): a small dot in the line's colour
    /// with a dark rim, left out where the faces are drawn too small for it.
    Slides,
}

/// One mark of [`FaceMarks`]: a line between two nodes, or a node.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mark {
    /// A feature curve's segment: a thick reddish-purple line with a dark outline.
    Line(u32, u32),
    /// A curved segment, as [`Mark::Line`]: the quadratic through its first node, its
    /// mid-side node (the second) and its last node (a quadratic element's edge).
    Curve(u32, u32, u32),
    Node(u32, NodeMark),
}

/// The colour of a [`Mark::Line`]: Okabe and Ito's reddish purple, apart from the quality
/// colours, the chosen node's orange and the inverted elements' red.
pub const MARK_LINE_RGB: [u8; 3] = [204, 121, 167];

/// Marks drawn on a picture of [`Faces`] (a sliding boundary's feature curves, corners
/// and sliding nodes), each right after a face it lies on, in the faces' depth order:
/// a nearer face covers them as it covers the faces behind it, and one on several faces
/// is drawn after the nearest of them too. Face `f`'s marks are
/// `marks[start[f]..start[f + 1]]`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FaceMarks {
    pub start: Vec<u32>,
    pub marks: Vec<Mark>,
}

impl FaceMarks {
    fn of(&self, f: usize) -> &[Mark] {
        match (self.start.get(f), self.start.get(f + 1)) {
            (Some(&a), Some(&b)) => self.marks.get(a as usize..b as usize).unwrap_or(&[]),
            _ => &[],
        }
    }
}

/// The smallest mean length of the faces' edges on screen, CSS pixels, at which
/// [`NodeMark::Slides`] dots are drawn: below it they would cover the faces.
pub(crate) const SLIDE_DOTS_MIN_EDGE_PX: f64 = 9.0;

/// Draws face `f`'s marks (see [`FaceMarks`]); `dots`: the sliding nodes' dots too.
fn draw_marks(pixmap: &mut Pixmap, faces: &Faces, marks: &[Mark], proj: &Projection, s: f32, dots: bool, clip: Option<&Mask>) {
    let at = |n: u32| -> Option<(f32, f32)> {
        let d = proj.to_device(*faces.points.get(n as usize)?);
        (d.is_finite() && d.x.abs() < FAR_PX as f64 && d.y.abs() < FAR_PX as f64).then_some((d.x as f32, d.y as f32))
    };
    draw_marks_at(pixmap, marks, &at, s, dots, clip);
}

/// Draws `marks` with their nodes where `at` puts them, in device pixels (`None`: left
/// out), at device-pixel ratio `s`; `dots`: the sliding nodes' dots too. The planar mesh
/// view draws a sliding boundary's marks with it as well.
pub(crate) fn draw_marks_at(pixmap: &mut Pixmap, marks: &[Mark], at: &dyn Fn(u32) -> Option<(f32, f32)>, s: f32, dots: bool, clip: Option<&Mask>) {
    let stroke = |w: f32| Stroke { width: w, line_cap: tiny_skia::LineCap::Round, ..Default::default() };
    let mut lines = PathBuilder::new();
    for m in marks {
        match *m {
            Mark::Line(a, b) => {
                if let (Some(p), Some(q)) = (at(a), at(b)) {
                    lines.move_to(p.0, p.1);
                    lines.line_to(q.0, q.1);
                }
            }
            Mark::Curve(a, mid, b) => {
                if let (Some(p), Some(c), Some(q)) = (at(a), at(mid), at(b)) {
                    let c = super::mesh::bezier_control(p, c, q);
                    lines.move_to(p.0, p.1);
                    lines.quad_to(c.0, c.1, q.0, q.1);
                }
            }
            Mark::Node(..) => {}
        }
    }
    if let Some(path) = lines.finish() {
        let [r, g, b] = MARK_LINE_RGB;
        pixmap.stroke_path(&path, &solid(rgba(20, 20, 20, 230)), &stroke(5.0 * s), Transform::identity(), clip);
        pixmap.stroke_path(&path, &solid(rgba(r, g, b, 255)), &stroke(3.2 * s), Transform::identity(), clip);
    }
    for m in marks {
        let Mark::Node(n, kind) = *m else { continue };
        let Some((x, y)) = at(n) else { continue };
        let mut pb = PathBuilder::new();
        let (fill, rim) = match kind {
            NodeMark::Stays => {
                let h = 4.2 * s;
                if let Some(r) = Rect::from_xywh(x - h, y - h, 2.0 * h, 2.0 * h) {
                    pb.push_rect(r);
                }
                (rgba(20, 20, 20, 255), rgba(255, 255, 255, 255))
            }
            // the line's colour, not white: a planar picture draws every free node white
            NodeMark::Slides if dots => {
                pb.push_circle(x, y, 2.7 * s);
                let [r, g, b] = MARK_LINE_RGB;
                (rgba(r, g, b, 255), rgba(20, 20, 20, 255))
            }
            NodeMark::Slides => continue,
        };
        if let Some(path) = pb.finish() {
            pixmap.fill_path(&path, &solid(fill), FillRule::Winding, Transform::identity(), clip);
            pixmap.stroke_path(&path, &solid(rim), &stroke(1.4 * s), Transform::identity(), clip);
        }
    }
}

/// Draws `faces` into `pixmap` as `opts` says (see the module's notes on the projection,
/// the depth sort and the light) and returns the projection it used, for picking.
pub fn render_surface(pixmap: &mut Pixmap, faces: &Faces, opts: &SurfaceView) -> Projection {
    render_surface_marked(pixmap, faces, opts, None)
}

/// [`render_surface`] with `marks` drawn with the faces they lie on ([`FaceMarks`]).
pub fn render_surface_marked(pixmap: &mut Pixmap, faces: &Faces, opts: &SurfaceView, marks: Option<&FaceMarks>) -> Projection {
    let s = sane_dpr(opts.dpr);
    let frame = opts.frame.unwrap_or(Frame::of_pixmap(pixmap, s));
    let theme = &opts.theme;
    fill_rect(pixmap, frame.x * s, frame.y * s, frame.w * s, frame.h * s, theme.paper);
    let top = if opts.title.is_some() { TITLE_H * theme.grow(14.0) } else { 0.0 };
    let bar = opts.colour_bar.then(|| colour_bar_band(frame.inset(0.0, top, 0.0, 0.0), &opts.bar_title, theme)).flatten();
    let plot = frame.inset(0.0, top, 0.0, bar.map_or(0.0, |b| b.h));
    // a small picture keeps a thinner margin, so the surface never shrinks to a dot
    let margin = opts.margin.min((0.03 * frame.w.min(frame.h)).max(4.0));
    let proj = Projection::fit(faces.points, &opts.camera, plot, margin, s);
    if frame.w * s < 1.0 || frame.h * s < 1.0 {
        return proj;
    }
    // the surface is drawn within `plot`, above the colour bar ([`super::layout`])
    super::layout::note(pixmap, super::layout::RegionKind::Plot, plot.x * s, plot.y * s, plot.w * s, plot.h * s);
    let clip = frame_mask(pixmap, frame, s);
    let clip = clip.as_ref();

    // Faces that can be drawn, farthest first.
    let mut order: Vec<(f64, usize)> = (0..faces.count())
        .filter_map(|f| {
            let ring = faces.ring(f)?;
            let z = ring.iter().map(|&n| proj.depth(faces.points[n as usize])).sum::<f64>() / ring.len() as f64;
            Some((z, f))
        })
        .collect();
    sort_stable_by_key(&mut order, |&(z, _)| !total_order_key(z)); // ties in face order

    let light = {
        let l = light_in_camera();
        l.x * proj.right + l.y * proj.up + l.z * proj.forward
    };
    let edge_paint = solid(rgba(25, 25, 25, 200));
    let edge_stroke = Stroke { width: 0.9 * s, line_join: tiny_skia::LineJoin::Round, ..Default::default() };
    // the sliding nodes' dots where the faces' edges are long enough on screen for them
    let dots = marks.is_some_and(|_| {
        let (mut sum, mut count) = (0.0, 0usize);
        for &(_, f) in &order {
            let ring = faces.ring(f).unwrap_or(&[]);
            for (i, &a) in ring.iter().enumerate() {
                let b = ring[(i + 1) % ring.len()];
                sum += proj.to_css(faces.points[a as usize]).distance(proj.to_css(faces.points[b as usize]));
                count += 1;
            }
        }
        count > 0 && sum / count as f64 >= SLIDE_DOTS_MIN_EDGE_PX
    });
    for &(_, f) in &order {
        let Some(ring) = faces.ring(f) else { continue };
        let pts: Vec<DVec3> = ring.iter().map(|&n| faces.points[n as usize]).collect();
        let Some(pb) = face_path(&pts, &proj) else { continue };
        let faded = faces.faded.get(f).copied().unwrap_or(false);
        if !faded && faces.inverted.get(f).copied().unwrap_or(false) {
            draw_inverted(pixmap, pb, s, clip);
            if let Some(m) = marks {
                draw_marks(pixmap, faces, m.of(f), &proj, s, dots, clip);
            }
            continue;
        }
        let Some(path) = pb.finish() else { continue };
        let value = faces.values.get(f).copied().unwrap_or(0.0);
        let base = if faded { faded_colour() } else { bucket_color(opts.colormap, bucket(value)) };
        let colour = shaded(base, shade(newell_normal(&pts), light, proj.forward));
        let mut paint = solid(colour);
        paint.anti_alias = opts.show_edges;
        pixmap.fill_path(&path, &paint, FillRule::Winding, Transform::identity(), clip);
        if opts.show_edges {
            pixmap.stroke_path(&path, &edge_paint, &edge_stroke, Transform::identity(), clip);
        }
        if let Some(m) = marks {
            draw_marks(pixmap, faces, m.of(f), &proj, s, dots, clip);
        }
    }

    if let Some(title) = &opts.title {
        // whole, or its leading clauses, at no less than the theme's smallest label
        let (shown, size) = theme.fit_title(title, 14.0 * s, (frame.w - 8.0).max(1.0) * s, s);
        let style = TextStyle::new(size).with_color(theme.ink).with_align(Align::Centre, Valign::Baseline);
        draw_text(pixmap, &shown, (plot.x + 0.5 * plot.w) * s, (frame.y + 18.0 * theme.grow(14.0)) * s, style);
    }
    if let Some(bar) = bar {
        fill_rect(pixmap, bar.x * s, bar.y * s, bar.w * s, bar.h * s, theme.paper);
        let n_inverted = faces.inverted_elements.unwrap_or_else(|| faces.inverted.iter().take(faces.count()).filter(|&&b| b).count());
        let (d0, d1) = opts.domain;
        let domain = if d0.is_finite() && d1.is_finite() && d1 > d0 { (d0, d1) } else { (0.0, 1.0) };
        draw_colour_bar(pixmap, bar, opts.colormap, domain, &opts.bar_title, n_inverted, s, theme);
    }
    proj
}

/// The Newell normal of a closed polygon (twice its vector area; zero when degenerate).
pub fn newell_normal(ring: &[DVec3]) -> DVec3 {
    let mut n = DVec3::ZERO;
    for (i, a) in ring.iter().enumerate() {
        let b = ring[(i + 1) % ring.len()];
        n += DVec3::new((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
    }
    n
}

/// The brightness of a face of normal `normal` (any length) under the light travelling
/// along `light` (unit), seen along `view` (unit, into the scene): `AMBIENT + (1 −
/// AMBIENT)·|n·l|`, times [`BACK_FACE`] when the normal points away from the viewer. A
/// degenerate face gets the ambient term alone.
pub fn shade(normal: DVec3, light: DVec3, view: DVec3) -> f64 {
    let n = normal.normalize_or_zero();
    let lambert = AMBIENT + (1.0 - AMBIENT) * n.dot(light).abs();
    if n.dot(view) > 0.0 {
        lambert * BACK_FACE
    } else {
        lambert
    }
}

/// The colour of a faded face, before the light: a pale grey.
fn faded_colour() -> Color {
    Color::from_rgba8(222, 224, 228, 255)
}

fn shaded(c: Color, k: f64) -> Color {
    let k = k.clamp(0.0, 1.0) as f32;
    Color::from_rgba(c.red() * k, c.green() * k, c.blue() * k, 1.0).unwrap_or(Color::BLACK)
}

/// The outline of a face in device pixels: edges of a 6- or 8-node ring as quadratic
/// Béziers through the mid nodes, of any other as lines. `None` when a point does not map
/// to a finite pixel. A face reaching beyond [`FAR_PX`] is flattened and clipped to it.
fn face_path(pts: &[DVec3], proj: &Projection) -> Option<PathBuilder> {
    let mut xy = Vec::with_capacity(pts.len());
    for p in pts {
        let d = proj.to_device(*p);
        let (x, y) = (d.x as f32, d.y as f32);
        if !(x.is_finite() && y.is_finite()) {
            return None;
        }
        xy.push((x, y));
    }
    let curved = matches!(xy.len(), 6 | 8);
    let mut pb = PathBuilder::new();
    if xy.iter().any(|p| p.0.abs() > FAR_PX || p.1.abs() > FAR_PX) {
        let poly = clip_to_far(flatten(&xy, curved));
        let (first, rest) = poly.split_first()?;
        pb.move_to(first.0, first.1);
        for p in rest {
            pb.line_to(p.0, p.1);
        }
    } else if curved {
        let k = xy.len() / 2;
        pb.move_to(xy[0].0, xy[0].1);
        for i in 0..k {
            let (m, b) = (xy[2 * i + 1], xy[(2 * i + 2) % xy.len()]);
            let c = bezier_control(xy[2 * i], m, b);
            pb.quad_to(c.0, c.1, b.0, b.1);
        }
    } else {
        pb.move_to(xy[0].0, xy[0].1);
        for p in &xy[1..] {
            pb.line_to(p.0, p.1);
        }
    }
    pb.close();
    Some(pb)
}

/// The outline as a polygon, curved edges as 16 chords each.
fn flatten(xy: &[(f32, f32)], curved: bool) -> Vec<(f32, f32)> {
    if !curved {
        return xy.to_vec();
    }
    let mut out = Vec::with_capacity(8 * xy.len());
    for i in (0..xy.len()).step_by(2) {
        let (a, m, b) = (xy[i], xy[i + 1], xy[(i + 2) % xy.len()]);
        let c = bezier_control(a, m, b);
        for j in 0..16 {
            let t = j as f32 / 16.0;
            let u = 1.0 - t;
            out.push((u * u * a.0 + 2.0 * u * t * c.0 + t * t * b.0, u * u * a.1 + 2.0 * u * t * c.1 + t * t * b.1));
        }
    }
    out
}

/// The polygon clipped to the square of half-side [`FAR_PX`] (Sutherland–Hodgman).
fn clip_to_far(mut poly: Vec<(f32, f32)>) -> Vec<(f32, f32)> {
    for (axis, sign) in [(0, 1.0f32), (0, -1.0), (1, 1.0), (1, -1.0)] {
        let coord = |p: (f32, f32)| if axis == 0 { p.0 } else { p.1 };
        let inside = |p: (f32, f32)| sign * coord(p) >= -FAR_PX;
        let mut out = Vec::with_capacity(poly.len() + 4);
        for i in 0..poly.len() {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            if inside(a) {
                out.push(a);
            }
            if inside(a) != inside(b) {
                let t = (-FAR_PX * sign - coord(a)) / (coord(b) - coord(a));
                out.push((a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)));
            }
        }
        poly = out;
    }
    poly
}

/// A mask for the frame when it does not cover the whole pixmap.
fn frame_mask(pixmap: &Pixmap, frame: Frame, s: f32) -> Option<Mask> {
    let full = frame.x <= 0.0
        && frame.y <= 0.0
        && frame.right() * s >= pixmap.width() as f32
        && frame.bottom() * s >= pixmap.height() as f32;
    if full {
        return None;
    }
    rect_mask(pixmap, Rect::from_xywh(frame.x * s, frame.y * s, frame.w * s, frame.h * s)?)
}
