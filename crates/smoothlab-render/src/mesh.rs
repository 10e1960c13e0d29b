//! The mesh view: elements coloured by a quality metric, inverted elements hatched,
//! true curved edges for quadratic elements, fixed and free nodes marked, an optional
//! highlighted node with its star, and a colour bar. Also the inverse mapping for
//! clicks: [`pick_node`].

use glam::DVec2;
use tiny_skia::{Color, FillRule, Mask, PathBuilder, Pixmap, Rect, Stroke, Transform};

use super::axes::{format_tick, nice_ticks};
use super::colormap::{bucket, bucket_color, Colormap, BUCKETS};
use super::paint::{fill, fill_rect, push_marker, rgba, solid, stroke, Marker};
use super::text::{draw_text, Align, TextStyle, Valign};
use super::theme::Theme;
use super::view::{sane_dpr, Frame, View, ZoomPan};
use super::view3d::{draw_marks_at, Mark, NodeMark, SLIDE_DOTS_MIN_EDGE_PX};
use smoothlab::mesh::{BoundaryNode, BoundaryRule, Mesh, NodeRole, NONE};
use smoothlab::quality::{element_quality, ElementQuality};

smoothlab::enum_with_names! {
    /// Which element metric colours the elements (all from
    /// [`element_quality`](smoothlab::quality::element_quality)).
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
    pub enum Metric {
        /// Lo's α for triangles, Canann's β for quads (Chen et al. 2003, eqs. 1–2), on [0, 1].
        #[default]
        Shape => ("alpha", "Lo's α for triangles, Canann's β for quads"),
        /// The smallest corner angle in degrees, on [0°, 60°] for triangle meshes and
        /// [0°, 90°] when quads are present (the ideal element's angle).
        MinAngle => ("angle", "the smallest corner angle"),
        /// Knupp's `2/κ` (Knupp 1999), on [0, 1].
        Condition => ("condition", "2/κ, Knupp's condition number"),
    }
}

impl Metric {
    /// The value shown for one element.
    pub fn value(self, q: &ElementQuality) -> f64 {
        match self {
            Metric::Shape => q.shape,
            Metric::MinAngle => q.min_angle.to_degrees(),
            Metric::Condition => q.inverse_condition(),
        }
    }
    /// The range the colour map spans for `mesh`.
    pub fn domain(self, mesh: &Mesh) -> (f64, f64) {
        match self {
            Metric::Shape | Metric::Condition => (0.0, 1.0),
            Metric::MinAngle => (0.0, if mesh.has_quads() { 90.0 } else { 60.0 }),
        }
    }
    /// The colour bar's title for `mesh`.
    pub fn label(self, mesh: &Mesh) -> &'static str {
        match self {
            Metric::Shape => match (mesh.has_triangles(), mesh.has_quads()) {
                (true, false) => "Lo's \u{3b1}",
                (false, true) => "Canann's \u{3b2}",
                _ => "\u{3b1} / \u{3b2}",
            },
            Metric::MinAngle => "min angle (\u{b0})",
            Metric::Condition => "2/\u{3ba} (Knupp)",
        }
    }
}

/// Whether to draw a layer: always, never, or when it is legible at this size.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Show {
    #[default]
    Auto,
    Always,
    Never,
}

/// Options of [`render_mesh`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshView {
    /// Default [`Metric::Shape`].
    pub metric: Metric,
    /// Default viridis.
    pub colormap: Colormap,
    /// The user's zoom and pan. Default none.
    pub zoom: ZoomPan,
    /// Device-pixel ratio (device pixels per CSS pixel). Default 1.
    pub dpr: f32,
    /// Where to draw, in CSS pixels. Default `None`: the whole pixmap.
    pub frame: Option<Frame>,
    /// Space around the mesh, CSS pixels. Default 16.
    pub margin: f32,
    /// Draw the colour bar: a thin band along the bottom ([`colour_bar_band`]), left out
    /// when the frame is too small for it. Default true.
    pub colour_bar: bool,
    /// Element edges; `Auto` draws them when edges are on average at least 5 device
    /// pixels long (shorter ones turn the picture into a dark texture).
    pub edges: Show,
    /// Node marks; `Auto` draws them when edges are at least 10 CSS pixels long and the
    /// mesh has at most 20 000 nodes.
    pub nodes: Show,
    /// A node to highlight with its star. Default none.
    pub highlight: Option<usize>,
    /// The world box to fit instead of the mesh's bounds (so several panels share a
    /// scale). Default `None`.
    pub bounds: Option<(DVec2, DVec2)>,
    /// Fill the frame with the theme's paper first (else leave the pixmap as it is).
    /// Default true.
    pub background: bool,
    /// Colours and label sizes. Default [`Theme::light`].
    pub theme: Theme,
}

impl Default for MeshView {
    fn default() -> Self {
        MeshView {
            metric: Metric::Shape,
            colormap: Colormap::Viridis,
            zoom: ZoomPan::default(),
            dpr: 1.0,
            frame: None,
            margin: 16.0,
            colour_bar: true,
            edges: Show::Auto,
            nodes: Show::Auto,
            highlight: None,
            bounds: None,
            background: true,
            theme: Theme::light(),
        }
    }
}

impl MeshView {
    pub fn with_metric(mut self, metric: Metric) -> Self {
        self.metric = metric;
        self
    }
    pub fn with_dpr(mut self, dpr: f32) -> Self {
        self.dpr = dpr;
        self
    }
    pub fn with_zoom(mut self, zoom: ZoomPan) -> Self {
        self.zoom = zoom;
        self
    }
    pub fn with_frame(mut self, frame: Frame) -> Self {
        self.frame = Some(frame);
        self
    }
    pub fn with_highlight(mut self, node: Option<usize>) -> Self {
        self.highlight = node;
        self
    }
}

/// The most of a picture's short side the colour bar's band may take.
pub const COLOUR_BAR_SHARE: f32 = 0.12;
/// The shortest gradient strip worth drawing, CSS pixels.
const MIN_STRIP: f32 = 48.0;
/// Fill of inverted elements (sRGB): a red that no colour of viridis comes near.
pub const INVERTED: [u8; 3] = [228, 26, 28];
/// Default radius of [`pick_node`], CSS pixels.
pub const PICK_RADIUS: f64 = 12.0;

/// The view (world ↔ pixels) that [`render_mesh`] uses for `mesh` on a pixmap of
/// `width × height` device pixels, without drawing: for mapping pointer events.
pub fn mesh_view(width: u32, height: u32, mesh: &Mesh, opts: &MeshView) -> View {
    let dpr = sane_dpr(opts.dpr);
    let frame = opts.frame.unwrap_or(Frame::new(0.0, 0.0, width as f32 / dpr, height as f32 / dpr));
    let plot = match opts.colour_bar.then(|| colour_bar_band(frame, opts.metric.label(mesh), &opts.theme)).flatten() {
        Some(bar) => frame.inset(0.0, 0.0, 0.0, bar.h),
        None => frame,
    };
    let (lo, hi) = opts.bounds.unwrap_or_else(|| mesh.bounds());
    View::fit(lo, hi, plot, opts.margin, opts.zoom, dpr)
}

/// Nearest node (any node an element uses) to the CSS pixel `(px, py)` within
/// [`PICK_RADIUS`]; `None` when there is none.
pub fn pick_node(mesh: &Mesh, view: &View, px: f64, py: f64) -> Option<usize> {
    pick_node_within(mesh, view, px, py, PICK_RADIUS)
}

/// [`pick_node`] with a chosen radius in CSS pixels.
pub fn pick_node_within(mesh: &Mesh, view: &View, px: f64, py: f64, radius: f64) -> Option<usize> {
    let c = DVec2::new(px, py);
    if !c.is_finite() {
        return None;
    }
    let mut best = None;
    let mut best_d2 = radius * radius;
    for (n, p) in mesh.nodes().iter().enumerate() {
        if mesh.role(n) == NodeRole::Unused {
            continue;
        }
        let d2 = view.to_css(*p).distance_squared(c);
        if d2 <= best_d2 {
            best_d2 = d2;
            best = Some(n);
        }
    }
    best
}

/// Adds the outline of element `e` (curved edges as quadratic Béziers) to `pb`, in
/// device pixels. Returns false (adding nothing) when a node is not finite.
pub fn push_element(pb: &mut PathBuilder, mesh: &Mesh, view: &View, e: usize) -> bool {
    let kind = mesh.kind(e);
    let ids = mesh.element(e);
    let k = kind.corners();
    let mut pts = [(0.0f32, 0.0f32); 9];
    for (i, &n) in ids.iter().enumerate() {
        let (x, y) = view.device_xy(mesh.nodes()[n as usize]);
        if !(x.is_finite() && y.is_finite()) {
            return false;
        }
        pts[i] = (x, y);
    }
    let n = ids.len();
    if pts[..n].iter().any(|p| p.0.abs() > FAR_PX || p.1.abs() > FAR_PX) {
        return push_far_element(pb, &pts[..n], kind);
    }
    pb.move_to(pts[0].0, pts[0].1);
    for i in 0..k {
        let b = pts[(i + 1) % k];
        match kind.mid(i) {
            Some(m) => {
                let (c0, c1) = bezier_control(pts[i], pts[m], b);
                pb.quad_to(c0, c1, b.0, b.1);
            }
            None => pb.line_to(b.0, b.1),
        }
    }
    pb.close();
    true
}

/// Device coordinates beyond which an element is clipped before it is drawn: tiny-skia's
/// rasterizer fails on paths millions of pixels across (a solver can fling a node of a
/// tangled mesh that far), and every picture lies well inside.
const FAR_PX: f32 = 65_536.0;

/// An edge with an end beyond [`FAR_PX`]: its chords (16 for a curved one) clipped to
/// the square of half-side [`FAR_PX`] (Liang–Barsky).
fn push_far_edge(path: &mut PathBuilder, a: (f32, f32), mid: Option<(f32, f32)>, b: (f32, f32)) {
    let mut pts = vec![a];
    if let Some(m) = mid {
        let c = bezier_control(a, m, b);
        for j in 1..16 {
            let t = j as f32 / 16.0;
            let u = 1.0 - t;
            pts.push((u * u * a.0 + 2.0 * u * t * c.0 + t * t * b.0, u * u * a.1 + 2.0 * u * t * c.1 + t * t * b.1));
        }
    }
    pts.push(b);
    for w in pts.windows(2) {
        let (p, q) = (w[0], w[1]);
        let d = (q.0 - p.0, q.1 - p.1);
        let (mut t0, mut t1) = (0.0f32, 1.0f32);
        let mut keep = true;
        for (dp, v) in [(-d.0, p.0 + FAR_PX), (d.0, FAR_PX - p.0), (-d.1, p.1 + FAR_PX), (d.1, FAR_PX - p.1)] {
            if dp == 0.0 {
                keep &= v >= 0.0;
            } else {
                let r = v / dp;
                if dp < 0.0 {
                    t0 = t0.max(r);
                } else {
                    t1 = t1.min(r);
                }
            }
        }
        if keep && t0 <= t1 {
            path.move_to(p.0 + t0 * d.0, p.1 + t0 * d.1);
            path.line_to(p.0 + t1 * d.0, p.1 + t1 * d.1);
        }
    }
}

/// An element with a corner beyond [`FAR_PX`]: its outline (curved edges as 16 chords)
/// clipped to the square of half-side [`FAR_PX`] (Sutherland–Hodgman), which holds the
/// picture, so what shows is unchanged.
fn push_far_element(pb: &mut PathBuilder, pts: &[(f32, f32)], kind: smoothlab::mesh::ElementKind) -> bool {
    let k = kind.corners();
    let mut poly: Vec<(f32, f32)> = Vec::with_capacity(16 * k);
    for i in 0..k {
        let (a, b) = (pts[i], pts[(i + 1) % k]);
        poly.push(a);
        if let Some(m) = kind.mid(i) {
            let c = bezier_control(a, pts[m], b);
            for j in 1..16 {
                let t = j as f32 / 16.0;
                let u = 1.0 - t;
                poly.push((u * u * a.0 + 2.0 * u * t * c.0 + t * t * b.0, u * u * a.1 + 2.0 * u * t * c.1 + t * t * b.1));
            }
        }
    }
    // clip against x ≥ −F, x ≤ F, y ≥ −F, y ≤ F in turn
    for (axis, sign) in [(0, 1.0f32), (0, -1.0), (1, 1.0), (1, -1.0)] {
        let inside = |p: (f32, f32)| sign * if axis == 0 { p.0 } else { p.1 } >= -FAR_PX;
        let mut out = Vec::with_capacity(poly.len() + 4);
        for i in 0..poly.len() {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            let (ia, ib) = (inside(a), inside(b));
            if ia {
                out.push(a);
            }
            if ia != ib {
                let (va, vb) = if axis == 0 { (a.0, b.0) } else { (a.1, b.1) };
                let t = (-FAR_PX * sign - va) / (vb - va);
                out.push((a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)));
            }
        }
        poly = out;
        if poly.is_empty() {
            return false;
        }
    }
    pb.move_to(poly[0].0, poly[0].1);
    for p in &poly[1..] {
        pb.line_to(p.0, p.1);
    }
    pb.close();
    true
}

/// Control point of the quadratic Bézier from `p0` to `p2` that passes through `m` at
/// its middle (t = ½): `2m − (p0 + p2)/2`. The quadratic edge of `docs/formulas.md` §1 is this
/// same parabola, so the drawn curve is the element's true edge.
pub fn bezier_control(p0: (f32, f32), m: (f32, f32), p2: (f32, f32)) -> (f32, f32) {
    (2.0 * m.0 - 0.5 * (p0.0 + p2.0), 2.0 * m.1 - 0.5 * (p0.1 + p2.1))
}

/// Draws `mesh` into `pixmap` as `opts` says, and returns the view it used (for
/// [`pick_node`] and [`View::css_to_world`]).
pub fn render_mesh(pixmap: &mut Pixmap, mesh: &Mesh, opts: &MeshView) -> View {
    let dpr = sane_dpr(opts.dpr);
    let s = dpr;
    let frame = opts.frame.unwrap_or(Frame::of_pixmap(pixmap, dpr));
    let view = mesh_view(pixmap.width(), pixmap.height(), mesh, &MeshView { frame: Some(frame), ..*opts });
    let theme = &opts.theme;
    if opts.background {
        fill_rect(pixmap, frame.x * s, frame.y * s, frame.w * s, frame.h * s, theme.paper);
    }
    note_mesh_area(pixmap, mesh, &view, frame, s);
    let clip = frame_mask(pixmap, frame, s);
    let clip = clip.as_ref();
    let (w, h) = (pixmap.width() as f32, pixmap.height() as f32);
    let visible = |lo: (f32, f32), hi: (f32, f32)| hi.0 >= 0.0 && hi.1 >= 0.0 && lo.0 <= w && lo.1 <= h;
    let mean_edge_dev = mesh.mean_edge_length() * view.device_scale();
    let show_edges = match opts.edges {
        Show::Always => true,
        Show::Never => false,
        Show::Auto => mean_edge_dev >= 5.0,
    };
    let show_nodes = match opts.nodes {
        Show::Always => true,
        Show::Never => false,
        Show::Auto => mean_edge_dev / s as f64 >= 10.0 && mesh.node_count() <= 20_000,
    };

    // Elements by colour bucket, inverted ones apart.
    let (d0, d1) = opts.metric.domain(mesh);
    let mut buckets: Vec<PathBuilder> = (0..BUCKETS).map(|_| PathBuilder::new()).collect();
    let mut inverted = PathBuilder::new();
    let mut n_inverted = 0usize;
    for e in 0..mesh.element_count() {
        let kind = mesh.kind(e);
        let p = mesh.element_points_array(e);
        let p = &p[..kind.node_count()];
        let (mut lo, mut hi) = ((f32::MAX, f32::MAX), (f32::MIN, f32::MIN));
        for q in p {
            let (x, y) = view.device_xy(*q);
            lo = (lo.0.min(x), lo.1.min(y));
            hi = (hi.0.max(x), hi.1.max(y));
        }
        let q = element_quality(kind, p);
        if q.inverted {
            n_inverted += 1;
        }
        if !visible(lo, hi) {
            continue;
        }
        if q.inverted {
            push_element(&mut inverted, mesh, &view, e);
        } else {
            let t = (opts.metric.value(&q) - d0) / (d1 - d0);
            let b = bucket(t);
            push_element(&mut buckets[b], mesh, &view, e);
        }
    }
    // Anti-aliased fills leave faint seams between elements unless edges cover them, and
    // cost twice as much; on large meshes the edges hide the jagged borders anyway.
    let smooth_fill = show_edges && mesh.element_count() <= 20_000;
    for (b, pb) in buckets.into_iter().enumerate() {
        if !pb.is_empty() {
            let c = bucket_color(opts.colormap, b);
            fill_masked(pixmap, pb, c, smooth_fill, clip);
        }
    }
    if !inverted.is_empty() {
        draw_inverted(pixmap, inverted, s, clip);
    }

    // Edges: interior thin, boundary thicker; curved ones as Béziers.
    if show_edges {
        let mut inner = PathBuilder::new();
        let mut outer = PathBuilder::new();
        for edge in mesh.edges() {
            let (a, b) = (mesh.nodes()[edge.a as usize], mesh.nodes()[edge.b as usize]);
            let (pa, pb_) = (view.device_xy(a), view.device_xy(b));
            let mid = (edge.mid != NONE).then(|| view.device_xy(mesh.nodes()[edge.mid as usize]));
            let mut lo = (pa.0.min(pb_.0), pa.1.min(pb_.1));
            let mut hi = (pa.0.max(pb_.0), pa.1.max(pb_.1));
            if let Some(m) = mid {
                lo = (lo.0.min(m.0), lo.1.min(m.1));
                hi = (hi.0.max(m.0), hi.1.max(m.1));
            }
            let finite = lo.0.is_finite() && lo.1.is_finite() && hi.0.is_finite() && hi.1.is_finite();
            if !(finite && visible(lo, hi)) {
                continue;
            }
            let path = if edge.is_boundary() { &mut outer } else { &mut inner };
            let far = |p: (f32, f32)| p.0.abs() > FAR_PX || p.1.abs() > FAR_PX;
            if far(pa) || far(pb_) || mid.is_some_and(far) {
                push_far_edge(path, pa, mid, pb_);
                continue;
            }
            path.move_to(pa.0, pa.1);
            match mid {
                Some(m) => {
                    let c = bezier_control(pa, m, pb_);
                    path.quad_to(c.0, c.1, pb_.0, pb_.1);
                }
                None => path.line_to(pb_.0, pb_.1),
            }
        }
        stroke_masked(pixmap, inner, rgba(25, 25, 25, 200), 0.9 * s, clip);
        stroke_masked(pixmap, outer, theme.ink, 1.8 * s, clip);
    }

    // The highlighted node's star.
    if let Some(n) = opts.highlight.filter(|&n| n < mesh.node_count()) {
        let mut star = PathBuilder::new();
        for &e in mesh.node_elements(n) {
            push_element(&mut star, mesh, &view, e as usize);
        }
        stroke_masked(pixmap, star, rgba(230, 159, 0, 255), 3.0 * s, clip);
    }

    if show_nodes {
        draw_nodes(pixmap, mesh, &view, s, clip);
    }
    draw_sliding_boundary(pixmap, mesh, &view, s, clip);
    if let Some(n) = opts.highlight.filter(|&n| n < mesh.node_count()) {
        let (x, y) = view.device_xy(mesh.nodes()[n]);
        let mut ring = PathBuilder::new();
        push_marker(&mut ring, Marker::Circle, x, y, 7.0 * s);
        stroke_masked(pixmap, ring.clone(), rgba(0, 0, 0, 255), 3.5 * s, clip);
        stroke_masked(pixmap, ring, rgba(230, 159, 0, 255), 2.0 * s, clip);
    }

    if let Some(bar) = opts.colour_bar.then(|| colour_bar_band(frame, opts.metric.label(mesh), theme)).flatten() {
        // a zoomed mesh may run under the bar: give the bar its own ground
        fill_rect(pixmap, bar.x * s, bar.y * s, bar.w * s, bar.h * s, theme.paper);
        draw_colour_bar(pixmap, bar, opts.colormap, (d0, d1), opts.metric.label(mesh), n_inverted, s, theme);
    }
    view
}

/// Draws the marks of `mesh`'s sliding boundary as the 3D views draw a volume's
/// ([`Mark`]): its edges as thick reddish-purple lines (a quadratic element's as the curve
/// through its mid-side node, which its sliding nodes keep to), the nodes that stay
/// (corners, and nodes the file fixed) as dark squares and the sliding nodes as white
/// dots, where its edges are long enough on screen for them. A mid-side node that a
/// sliding node carries along the boundary gets no mark of its own (it lies on the line,
/// and a dot of its own would hide the curve between the sliding nodes); one between two
/// that stay, or fixed by the file, stays. Nothing while its boundary is held.
pub fn draw_sliding_boundary(pixmap: &mut Pixmap, mesh: &Mesh, view: &View, dpr: f32, clip: Option<&Mask>) {
    if mesh.boundary_rule() != BoundaryRule::Slide {
        return;
    }
    let mut marks = Vec::new();
    for e in mesh.topology().boundary_edges() {
        if e.mid == NONE {
            marks.push(Mark::Line(e.a, e.b));
            continue;
        }
        marks.push(Mark::Curve(e.a, e.mid, e.b));
        if ![e.a, e.b].iter().any(|&v| mesh.carries(v as usize, e.mid as usize)) {
            marks.push(Mark::Node(e.mid, NodeMark::Stays));
        }
    }
    for n in (0..mesh.node_count()).filter(|&n| mesh.is_boundary(n) && mesh.role(n) != NodeRole::Mid) {
        match mesh.boundary_node(n) {
            Some(BoundaryNode::Corner | BoundaryNode::Held) => marks.push(Mark::Node(n as u32, NodeMark::Stays)),
            Some(c) if c.slides() => marks.push(Mark::Node(n as u32, NodeMark::Slides)),
            _ => {}
        }
    }
    let s = sane_dpr(dpr);
    let dots = mesh.mean_edge_length() * view.device_scale() / s as f64 >= SLIDE_DOTS_MIN_EDGE_PX;
    let at = |n: u32| -> Option<(f32, f32)> {
        let (x, y) = view.device_xy(*mesh.nodes().get(n as usize)?);
        (x.is_finite() && y.is_finite() && x.abs() < FAR_PX && y.abs() < FAR_PX).then_some((x, y))
    };
    draw_marks_at(pixmap, &marks, &at, s, dots, clip);
}

/// Notes ([`super::layout`]) where the mesh lies in `frame`: its bounding box as `view`
/// draws it, within the frame.
fn note_mesh_area(pixmap: &Pixmap, mesh: &Mesh, view: &View, frame: Frame, s: f32) {
    let (lo, hi) = mesh.bounds();
    let (a, b) = (view.device_xy(lo), view.device_xy(hi));
    let x0 = a.0.min(b.0).max(frame.x * s);
    let x1 = a.0.max(b.0).min(frame.right() * s);
    let y0 = a.1.min(b.1).max(frame.y * s);
    let y1 = a.1.max(b.1).min(frame.bottom() * s);
    if x1 > x0 && y1 > y0 {
        super::layout::note(pixmap, super::layout::RegionKind::Plot, x0, y0, x1 - x0, y1 - y0);
    }
}

/// Whether [`render_mesh`] draws the colour bar for `mesh` with `opts` on a pixmap of
/// `width × height` device pixels (a small picture leaves it out, and the page shows the
/// scale beside it instead).
pub fn mesh_colour_bar_shown(width: u32, height: u32, mesh: &Mesh, opts: &MeshView) -> bool {
    let dpr = sane_dpr(opts.dpr);
    let frame = opts.frame.unwrap_or(Frame::new(0.0, 0.0, width as f32 / dpr, height as f32 / dpr));
    opts.colour_bar && colour_bar_band(frame, opts.metric.label(mesh), &opts.theme).is_some()
}

/// The colour bar's label size, CSS pixels.
fn bar_label(theme: &Theme) -> f32 {
    theme.text_px(11.0, 1.0)
}

/// The band along the bottom of `frame` (CSS pixels) that the colour bar titled `title`
/// takes in `theme`: one line of the title, the gradient between its end values and the
/// inverted swatch with its count, [`COLOUR_BAR_SHARE`] of the frame's short side at most.
/// `None` when it does not fit (the bar is then left out).
pub fn colour_bar_band(frame: Frame, title: &str, theme: &Theme) -> Option<Frame> {
    let l = bar_label(theme);
    let h = l * 1.35 + 8.0;
    let tw = |t: &str| super::text::text_width(t, l);
    // the widest end values of the metrics' domains and a five-digit count
    let need = 8.0 + tw(title) + 10.0 + tw("0") + 5.0 + MIN_STRIP + 5.0 + tw("60") + 12.0 + l + 4.0 + tw("99999") + 8.0;
    let fits = h <= COLOUR_BAR_SHARE * frame.w.min(frame.h) && need <= frame.w;
    fits.then(|| Frame::new(frame.x, frame.bottom() - h, frame.w, h))
}

fn inverted_color() -> Color {
    Color::from_rgba8(INVERTED[0], INVERTED[1], INVERTED[2], 255)
}

/// A mask for the frame when it does not cover the whole pixmap.
fn frame_mask(pixmap: &Pixmap, frame: Frame, s: f32) -> Option<Mask> {
    let full = frame.x <= 0.0 && frame.y <= 0.0 && frame.right() * s >= pixmap.width() as f32 && frame.bottom() * s >= pixmap.height() as f32;
    if full {
        return None;
    }
    super::paint::rect_mask(pixmap, Rect::from_xywh(frame.x * s, frame.y * s, frame.w * s, frame.h * s)?)
}

fn fill_masked(pixmap: &mut Pixmap, pb: PathBuilder, c: Color, aa: bool, mask: Option<&Mask>) {
    if mask.is_none() {
        return fill(pixmap, pb, c, aa);
    }
    if let Some(path) = pb.finish() {
        let mut p = solid(c);
        p.anti_alias = aa;
        pixmap.fill_path(&path, &p, FillRule::Winding, Transform::identity(), mask);
    }
}

fn stroke_masked(pixmap: &mut Pixmap, pb: PathBuilder, c: Color, width: f32, mask: Option<&Mask>) {
    if mask.is_none() {
        return stroke(pixmap, pb, c, width, None);
    }
    if let Some(path) = pb.finish() {
        let st = Stroke { width, line_join: tiny_skia::LineJoin::Round, ..Default::default() };
        pixmap.stroke_path(&path, &solid(c), &st, Transform::identity(), mask);
    }
}

/// Inverted elements: red fill, black diagonal hatch clipped to them, thick outline.
pub fn draw_inverted(pixmap: &mut Pixmap, pb: PathBuilder, s: f32, clip: Option<&Mask>) {
    let Some(path) = pb.finish() else { return };
    pixmap.fill_path(&path, &solid(inverted_color()), FillRule::Winding, Transform::identity(), clip);
    if let Some(mut mask) = Mask::new(pixmap.width(), pixmap.height()) {
        mask.fill_path(&path, FillRule::Winding, true, Transform::identity());
        if let Some(c) = clip {
            for (m, k) in mask.data_mut().iter_mut().zip(c.data()) {
                *m = ((*m as u16 * *k as u16) / 255) as u8;
            }
        }
        // the hatched box: the element's bounds within the picture (an element flung
        // far away by a solver spans millions of pixels; the mask clips to it anyway)
        let b = path.bounds();
        let (left, right) = (b.left().max(0.0), b.right().min(pixmap.width() as f32));
        let (top, bottom) = (b.top().max(0.0), b.bottom().min(pixmap.height() as f32));
        let mut hatch = PathBuilder::new();
        let step = 6.0 * s;
        let span = bottom - top;
        // lines x − y = const, from the bottom-left to the top-right of the box
        let mut t = (left - span) - (left - span).rem_euclid(step);
        while left < right && top < bottom && t <= right {
            hatch.move_to(t, bottom);
            hatch.line_to(t + span, top);
            t += step;
        }
        if let Some(h) = hatch.finish() {
            let st = Stroke { width: 1.3 * s, ..Default::default() };
            pixmap.stroke_path(&h, &solid(rgba(0, 0, 0, 230)), &st, Transform::identity(), Some(&mask));
        }
    }
    let st = Stroke { width: 2.5 * s, line_join: tiny_skia::LineJoin::Round, ..Default::default() };
    pixmap.stroke_path(&path, &solid(rgba(120, 0, 0, 255)), &st, Transform::identity(), clip);
}

/// Fixed corner nodes as dark squares, free corners as white dots, mid-side and centre
/// nodes as small grey dots.
fn draw_nodes(pixmap: &mut Pixmap, mesh: &Mesh, view: &View, s: f32, clip: Option<&Mask>) {
    let (w, h) = (pixmap.width() as f32, pixmap.height() as f32);
    let mut fixed = PathBuilder::new();
    let mut free = PathBuilder::new();
    let mut mid = PathBuilder::new();
    for (n, p) in mesh.nodes().iter().enumerate() {
        let (x, y) = view.device_xy(*p);
        if !(x > -10.0 && y > -10.0 && x < w + 10.0 && y < h + 10.0) {
            continue;
        }
        match mesh.role(n) {
            NodeRole::Unused => {}
            NodeRole::Corner if mesh.fixed()[n] => push_marker(&mut fixed, Marker::Square, x, y, 3.2 * s),
            NodeRole::Corner => push_marker(&mut free, Marker::Circle, x, y, 3.0 * s),
            NodeRole::Mid | NodeRole::Centre => push_marker(&mut mid, Marker::Circle, x, y, 1.8 * s),
        }
    }
    fill_masked(pixmap, mid, rgba(90, 90, 90, 255), true, clip);
    fill_masked(pixmap, fixed, rgba(30, 30, 30, 255), true, clip);
    let outline = free.clone();
    fill_masked(pixmap, free, Color::WHITE, true, clip);
    stroke_masked(pixmap, outline, rgba(30, 30, 30, 255), 1.2 * s, clip);
}

/// The colour bar in the band `area` (CSS pixels, from [`colour_bar_band`]), on one
/// line: the title, the gradient between its end values with the ticks between marked on
/// it, and the inverted swatch with the count of inverted elements.
#[allow(clippy::too_many_arguments)]
pub fn draw_colour_bar(
    pixmap: &mut Pixmap,
    area: Frame,
    map: Colormap,
    (d0, d1): (f64, f64),
    title: &str,
    n_inverted: usize,
    s: f32,
    theme: &Theme,
) {
    super::layout::note(pixmap, super::layout::RegionKind::Legend, area.x * s, area.y * s, area.w * s, area.h * s);
    let l = bar_label(theme);
    let label = TextStyle::new(l * s).with_color(theme.caption).with_align(Align::Left, Valign::Middle);
    let tw = |t: &str| super::text::text_width(t, l);
    let cy = area.y + 0.5 * area.h;
    let ticks = nice_ticks(d0, d1, 5);
    let (lo, hi) = (format_tick(d0, ticks.step), format_tick(d1, ticks.step));
    let swatch = l;
    let long = format!("{n_inverted} inverted");
    let mut x = area.x + 8.0;
    draw_text(pixmap, title, x * s, cy * s, label);
    x += tw(title) + 10.0;
    draw_text(pixmap, &lo, x * s, cy * s, label);
    x += tw(&lo) + 5.0;
    // the count in words when there is room, else the number alone
    let tail = |count: &str| 5.0 + tw(&hi) + 12.0 + swatch + 4.0 + tw(count) + 8.0;
    let count = if area.right() - tail(&long) - x >= MIN_STRIP { long } else { n_inverted.to_string() };
    let strip_end = area.right() - tail(&count);
    if strip_end - x < 8.0 {
        return;
    }
    let sh = 0.8 * l;
    let (x0, x1) = (x * s, strip_end * s);
    let (y0, y1) = ((cy - 0.5 * sh) * s, (cy + 0.5 * sh) * s);
    let cols = (x1 - x0).ceil().max(1.0) as usize;
    for c in 0..cols {
        let t = (c as f64 + 0.5) / cols as f64;
        fill_rect(pixmap, x0 + c as f32, y0, 1.0, y1 - y0, map.color(t));
    }
    let mut frame = PathBuilder::new();
    if let Some(r) = Rect::from_ltrb(x0, y0, x1, y1) {
        frame.push_rect(r);
    }
    for &v in &ticks.values {
        let t = ((v - d0) / (d1 - d0)) as f32;
        if t > 0.01 && t < 0.99 {
            let tx = x0 + (x1 - x0) * t;
            frame.move_to(tx, y1);
            frame.line_to(tx, y1 - 0.3 * sh * s);
        }
    }
    stroke(pixmap, frame, theme.caption, s, None);
    let mut x = strip_end + 5.0;
    draw_text(pixmap, &hi, x * s, cy * s, label);
    x += tw(&hi) + 12.0;
    // inverted swatch
    if let Some(r) = Rect::from_xywh(x * s, (cy - 0.5 * swatch) * s, swatch * s, swatch * s) {
        pixmap.fill_rect(r, &solid(inverted_color()), Transform::identity(), None);
        let mut hatch = PathBuilder::new();
        let mut t = r.left() - r.height();
        while t < r.right() {
            hatch.move_to(t, r.bottom());
            hatch.line_to(t + r.height(), r.top());
            t += 4.0 * s;
        }
        if let (Some(hp), Some(mask)) = (hatch.finish(), super::paint::rect_mask(pixmap, r)) {
            let st = Stroke { width: 1.2 * s, ..Default::default() };
            pixmap.stroke_path(&hp, &solid(rgba(0, 0, 0, 230)), &st, Transform::identity(), Some(&mask));
        }
        let pb = PathBuilder::from_rect(r);
        pixmap.stroke_path(&pb, &solid(rgba(120, 0, 0, 255)), &Stroke { width: 1.5 * s, ..Default::default() }, Transform::identity(), None);
    }
    draw_text(pixmap, &count, (x + swatch + 4.0) * s, cy * s, label);
}

#[cfg(test)]
mod tests {
    use super::*;
    use smoothlab::generate::{quadratic_star, QuadraticStar};

    /// Whether a pixel within one of `(x, y)` is the sliding boundary's reddish purple.
    fn purple_near(pm: &Pixmap, (x, y): (f32, f32)) -> bool {
        let (x, y) = (x.round() as i64, y.round() as i64);
        (x - 1..=x + 1).flat_map(|i| (y - 1..=y + 1).map(move |j| (i, j))).any(|(i, j)| {
            let p = (i >= 0 && j >= 0).then(|| pm.pixel(i as u32, j as u32)).flatten();
            p.is_some_and(|p| [p.red(), p.green(), p.blue()] == crate::MARK_LINE_RGB)
        })
    }

    #[test]
    fn a_quadratic_mesh_s_sliding_boundary_is_drawn_along_its_curved_edges() {
        // Chen's star by a curved boundary: its two bottom edges bulge up through their
        // mid-side nodes; the sliding boundary's line follows the curve, not the chord. The
        // node between them turns by about 62°: a corner at the default feature angle (both
        // mid-side nodes stay: squares), a sliding node at 80° (it carries them: no mark)
        let start = quadratic_star(QuadraticStar::CurvedBoundary).unwrap();
        let mut fixed = Pixmap::new(400, 300).unwrap();
        render_mesh(&mut fixed, &start, &MeshView::default());
        for (angle, carries) in [(smoothlab::mesh::FEATURE_ANGLE_DEG, false), (80.0, true)] {
            let mut mesh = start.clone();
            mesh.set_boundary(BoundaryRule::Slide, angle);
            assert_eq!(mesh.carries_mid_nodes(1), carries, "{angle}°: {:?}", mesh.boundary_node(1));
            let mut pm = Pixmap::new(400, 300).unwrap();
            let view = render_mesh(&mut pm, &mesh, &MeshView::default());
            let mut checked = 0;
            for e in mesh.topology().boundary_edges().filter(|e| e.mid != NONE) {
                let [a, m, b] = [e.a, e.mid, e.b].map(|v| mesh.nodes()[v as usize]);
                // a quarter of the way along: on the quadratic through a, m and b, and on the chord
                let on_curve = 0.375 * a + 0.75 * m - 0.125 * b;
                let on_chord = 0.75 * a + 0.25 * b;
                let (c, h) = (view.device_xy(on_curve), view.device_xy(on_chord));
                if (c.0 - h.0).hypot(c.1 - h.1) < 8.0 {
                    continue; // a straight edge, or too short on screen to tell
                }
                let what = format!("{angle}°, edge {}–{}", e.a, e.b);
                assert!(purple_near(&pm, c), "{what}: no line on its curve at {c:?}");
                assert!(!purple_near(&pm, h), "{what}: a line on its chord at {h:?}");
                assert!(!purple_near(&fixed, c), "a held boundary is not marked");
                // a carried mid-side node lies under the line; one that stays has its square
                let carried = [e.a, e.b].iter().any(|&v| mesh.carries(v as usize, e.mid as usize));
                assert_eq!(carried, carries, "{what}");
                assert_eq!(purple_near(&pm, view.device_xy(m)), carried, "{what}: its mid-side node");
                checked += 1;
            }
            assert_eq!(checked, 2, "{angle}°: the star's two curved edges");
            // node 1 itself: a sliding node's dot is the line's colour at its centre (every
            // free node is drawn white), a corner's square is dark
            let (x, y) = view.device_xy(mesh.nodes()[1]);
            let p = pm.pixel(x.round() as u32, y.round() as u32).expect("on the picture");
            let purple = [p.red(), p.green(), p.blue()] == crate::MARK_LINE_RGB;
            assert_eq!(purple, carries, "{angle}°: node 1's mark");
        }
    }
}
