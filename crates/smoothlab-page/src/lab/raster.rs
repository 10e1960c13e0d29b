//! The page's fast mesh picture for meshes too fine to show their edges (a 100k- or
//! 1M-node mesh on a canvas of a few hundred pixels). [`smoothlab_render::render_mesh`]
//! draws such a mesh without edges or node marks and without anti-aliasing, but still
//! builds a tiny-skia path per element and measures every element with all its metrics
//! (about 0.5 µs per element natively). Here each element's colour bucket comes with the
//! statistics the page keeps anyway ([`super::stats::QuickAcc`]: the bucket of its α or
//! β, as `render_mesh` chooses it), and its corner polygon is scan-converted straight
//! into a bucket per pixel, in fixed point with the top-left rule, so neighbouring
//! elements share their edge pixels without gaps (about 60 ns per element natively).
//! Inverted elements (red, hatched, outlined), the highlighted star and the colour bar
//! look as `render_mesh` draws them; the tests compare the two pictures.

use tiny_skia::{Color, FillRule, Paint, PathBuilder, Pixmap, Rect, Stroke, Transform};

use super::stats::INVERTED_BUCKET;
use smoothlab_render::{bucket_color, BUCKETS};
use smoothlab::mesh::Mesh;
use smoothlab_render::{
    colour_bar_band, draw_colour_bar, draw_inverted, mesh_view, push_element, Frame, MeshView, Metric, Show,
    View, INVERTED,
};

/// Sub-pixel steps per pixel of the fixed-point rasterizer.
const SUB: i64 = 256;
/// Device coordinates beyond this (pixels) go to tiny-skia instead (a node dragged far
/// away): the fixed-point products stay far inside `i64`.
const FAR: f64 = 32768.0;

/// Whether [`render_fine`] draws a mesh whose mean edge length is `mean_edge` with
/// `opts` as `render_mesh` would (elements coloured by shape, no edges or nodes at this
/// scale, the whole pixmap as frame).
pub fn applies(mean_edge: f64, view: &View, opts: &MeshView) -> bool {
    let hidden_edges = match opts.edges {
        Show::Never => true,
        Show::Always => false,
        Show::Auto => mean_edge * view.device_scale() < 5.0,
    };
    let hidden_nodes = match opts.nodes {
        Show::Never => true,
        Show::Always => false,
        // render_mesh's rule: only where edges are ≥ 10 CSS px, which implies edges shown
        Show::Auto => hidden_edges,
    };
    hidden_edges && hidden_nodes && opts.metric == Metric::Shape && opts.frame.is_none() && opts.background
}

/// The view `render_mesh` uses on this pixmap.
pub fn view_of(pixmap: &Pixmap, mesh: &Mesh, opts: &MeshView) -> View {
    mesh_view(pixmap.width(), pixmap.height(), mesh, opts)
}

/// Draws `mesh` as `render_mesh(pixmap, mesh, opts)` does when [`applies`] says so,
/// except the highlighted star (see [`draw_highlight`]): background, elements by colour
/// bucket, inverted elements hatched, colour bar. Returns the number of inverted elements.
///
/// `buckets` holds each element's colour bucket for the mesh's positions, as
/// [`super::stats::QuickAcc`] writes them (the page keeps them with its statistics).
pub fn render_fine(pixmap: &mut Pixmap, mesh: &Mesh, buckets: &[u8], view: &View, opts: &MeshView) -> usize {
    let (w, h) = (pixmap.width() as usize, pixmap.height() as usize);
    let s = smoothlab_render::view::sane_dpr(opts.dpr);
    let bg = opts.theme.paper;
    pixmap.fill(bg);

    // device positions of all nodes in fixed point (i32::MIN: far away or not finite)
    let pts: Vec<(i32, i32)> = mesh
        .nodes()
        .iter()
        .map(|p| {
            let d = view.to_device(*p);
            if d.x.abs() < FAR && d.y.abs() < FAR {
                (fixed(d.x), fixed(d.y))
            } else {
                (i32::MIN, i32::MIN)
            }
        })
        .collect();

    let mut bucket = vec![0u8; w * h];
    let mut inverted: Vec<u32> = Vec::new();
    let mut far: Vec<(u32, u8)> = Vec::new();
    let mut bottom = i64::MIN; // lowest device row of the inverted elements, fixed point
    for (e, &v) in buckets.iter().enumerate().take(mesh.element_count()) {
        let ids = mesh.element(e);
        let k = mesh.kind(e).corners();
        let mut c = [(0i64, 0i64); 4];
        let mut ok = true;
        for i in 0..k {
            let (x, y) = pts[ids[i] as usize];
            ok &= x != i32::MIN;
            c[i] = (x as i64, y as i64);
        }
        if !ok {
            far.push((e as u32, v));
            continue;
        }
        if v == INVERTED_BUCKET {
            inverted.push(e as u32);
            bottom = bottom.max(c[..k].iter().map(|p| p.1).max().unwrap_or(i64::MIN));
        }
        // inverted elements go on top of the rest (the largest value), as render_mesh
        // fills them after every bucket
        fill_triangle(&mut bucket, w, h, c[0], c[1], c[2], v);
        if k == 4 {
            fill_triangle(&mut bucket, w, h, c[0], c[2], c[3], v);
        }
    }
    drop(pts);

    // buckets to colours (the pixmap is opaque, so premultiplied = straight); inverted
    // elements red under render_mesh's hatch: lines x + y ≡ bottom (mod 6 px) of width
    // 1.3 px, black at alpha 230
    let colours: Vec<[u8; 3]> = (0..BUCKETS).map(|b| opts.colormap.rgb(b as f64 / (BUCKETS - 1) as f64)).collect();
    let step = 6.0 * s as f64;
    let reach = 0.5 * 1.3 * s as f64 * std::f64::consts::SQRT_2;
    let origin = bottom as f64 / SUB as f64;
    let hatch = [INVERTED[0], INVERTED[1], INVERTED[2]].map(|c| ((c as u32 * 25 + 127) / 255) as u8);
    let data = pixmap.data_mut();
    for (i, &v) in bucket.iter().enumerate() {
        if v == 0 {
            continue;
        }
        let rgb = if v == INVERTED_BUCKET {
            let (x, y) = ((i % w) as f64 + 0.5, (i / w) as f64 + 0.5);
            let r = (x + y - origin).rem_euclid(step);
            if r.min(step - r) <= reach {
                hatch
            } else {
                INVERTED
            }
        } else {
            colours[v as usize - 1]
        };
        data[4 * i..4 * i + 4].copy_from_slice(&[rgb[0], rgb[1], rgb[2], 255]);
    }

    // elements with a node far off the canvas: tiny-skia draws them (rare: a dragged node)
    let mut far_inverted = PathBuilder::new();
    for (e, v) in far {
        if v == INVERTED_BUCKET {
            push_element(&mut far_inverted, mesh, view, e as usize);
            inverted.push(e);
            continue;
        }
        let mut pb = PathBuilder::new();
        if push_element(&mut pb, mesh, view, e as usize) {
            if let Some(path) = pb.finish() {
                let mut p = solid(bucket_color(opts.colormap, (v - 1) as usize));
                p.anti_alias = false;
                pixmap.fill_path(&path, &p, FillRule::Winding, Transform::identity(), None);
            }
        }
    }
    draw_inverted(pixmap, far_inverted, s, None);

    // the outline of the inverted elements, as render_mesh strokes it
    if !inverted.is_empty() {
        let mut pb = PathBuilder::new();
        for &e in &inverted {
            push_element(&mut pb, mesh, view, e as usize);
        }
        if let Some(path) = pb.finish() {
            let st = Stroke { width: 2.5 * s, line_join: tiny_skia::LineJoin::Round, ..Default::default() };
            pixmap.stroke_path(&path, &solid(rgba(120, 0, 0, 255)), &st, Transform::identity(), None);
        }
    }

    let frame = Frame::new(0.0, 0.0, w as f32 / s, h as f32 / s);
    if let Some(bar) = opts.colour_bar.then(|| colour_bar_band(frame, opts.metric.label(mesh), &opts.theme)).flatten() {
        fill_rect(pixmap, bar.x * s, bar.y * s, bar.w * s, bar.h * s, bg);
        let (d0, d1) = opts.metric.domain(mesh);
        draw_colour_bar(pixmap, bar, opts.colormap, (d0, d1), opts.metric.label(mesh), inverted.len(), s, &opts.theme);
    }
    inverted.len()
}

/// A device coordinate (|x| < [`FAR`]) in fixed point, rounded to nearest: a float to
/// integer cast of a positive number, which is one instruction (where `round` is a call).
#[inline]
fn fixed(x: f64) -> i32 {
    const OFFSET: f64 = (1u64 << 32) as f64;
    ((x * SUB as f64 + 0.5 + OFFSET) as i64 - (1i64 << 32)) as i32
}

/// Sets `buf[pixel] = max(buf[pixel], v)` for every pixel whose centre lies in the
/// triangle `a b c` (fixed point, `SUB` steps per pixel; either orientation). Edges
/// follow the top-left rule, so triangles that share an edge never both take, nor both
/// miss, a pixel centre on it.
fn fill_triangle(buf: &mut [u8], w: usize, h: usize, a: (i64, i64), b: (i64, i64), c: (i64, i64), v: u8) {
    let area = (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0);
    if area == 0 {
        return;
    }
    let (a, b, c) = if area > 0 { (a, b, c) } else { (a, c, b) };
    let half = SUB / 2;
    // first and last pixel whose centre is at or after `lo` / at or before `hi`: ceiling
    // and floor division by SUB (a power of two: arithmetic shifts)
    const SHIFT: u32 = SUB.trailing_zeros();
    let first = |lo: i64| (lo - half + SUB - 1) >> SHIFT;
    let last = |hi: i64| (hi - half) >> SHIFT;
    let x0 = first(a.0.min(b.0).min(c.0)).max(0);
    let x1 = last(a.0.max(b.0).max(c.0)).min(w as i64 - 1);
    let y0 = first(a.1.min(b.1).min(c.1)).max(0);
    let y1 = last(a.1.max(b.1).max(c.1)).min(h as i64 - 1);
    if x0 > x1 || y0 > y1 {
        return;
    }
    // edge p→q: E(x, y) = dx (y − py) − dy (x − px) > 0 inside; +1 on top or left edges
    let edge = |p: (i64, i64), q: (i64, i64)| {
        let (dx, dy) = (q.0 - p.0, q.1 - p.1);
        let top_left = (dy == 0 && dx > 0) || dy < 0;
        let (cx, cy) = (x0 * SUB + half, y0 * SUB + half);
        let e0 = dx * (cy - p.1) - dy * (cx - p.0) + top_left as i64;
        (e0, -dy * SUB, dx * SUB)
    };
    let (mut r0, sx0, sy0) = edge(a, b);
    let (mut r1, sx1, sy1) = edge(b, c);
    let (mut r2, sx2, sy2) = edge(c, a);
    for y in y0..=y1 {
        let (mut e0, mut e1, mut e2) = (r0, r1, r2);
        let row = y as usize * w;
        for x in x0..=x1 {
            if e0 > 0 && e1 > 0 && e2 > 0 {
                let px = &mut buf[row + x as usize];
                if *px < v {
                    *px = v;
                }
            }
            e0 += sx0;
            e1 += sx1;
            e2 += sx2;
        }
        r0 += sy0;
        r1 += sy1;
        r2 += sy2;
    }
}

/// Draws the highlighted node's star and its ring as `render_mesh` does (nodes hidden).
pub fn draw_highlight(pixmap: &mut Pixmap, mesh: &Mesh, view: &View, node: usize, dpr: f32) {
    if node >= mesh.node_count() {
        return;
    }
    let s = smoothlab_render::view::sane_dpr(dpr);
    let mut star = PathBuilder::new();
    for &e in mesh.node_elements(node) {
        push_element(&mut star, mesh, view, e as usize);
    }
    stroke(pixmap, star, rgba(230, 159, 0, 255), 3.0 * s);
    let (x, y) = view.device_xy(mesh.nodes()[node]);
    if x.is_finite() && y.is_finite() {
        let mut ring = PathBuilder::new();
        ring.push_circle(x, y, 7.0 * s);
        stroke(pixmap, ring.clone(), rgba(0, 0, 0, 255), 3.5 * s);
        stroke(pixmap, ring, rgba(230, 159, 0, 255), 2.0 * s);
    }
}

fn rgba(r: u8, g: u8, b: u8, a: u8) -> Color {
    Color::from_rgba8(r, g, b, a)
}

fn solid(c: Color) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color(c);
    p
}

fn fill_rect(pixmap: &mut Pixmap, x: f32, y: f32, w: f32, h: f32, c: Color) {
    if let Some(r) = Rect::from_xywh(x, y, w, h) {
        pixmap.fill_rect(r, &solid(c), Transform::identity(), None);
    }
}

fn stroke(pixmap: &mut Pixmap, pb: PathBuilder, c: Color, width: f32) {
    if let Some(path) = pb.finish() {
        let st = Stroke {
            width,
            line_join: tiny_skia::LineJoin::Round,
            line_cap: tiny_skia::LineCap::Round,
            ..Default::default()
        };
        pixmap.stroke_path(&path, &solid(c), &st, Transform::identity(), None);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use smoothlab::generate::{perturb, plate, rand2d, PlateKind};
    use smoothlab_render::render_mesh;

    /// Pixels that differ (any channel by more than 2) between two pictures.
    fn differing(a: &Pixmap, b: &Pixmap) -> usize {
        a.data().chunks(4).zip(b.data().chunks(4)).filter(|(p, q)| p.iter().zip(*q).any(|(x, y)| x.abs_diff(*y) > 2)).count()
    }

    fn both(mesh: &Mesh, w: u32, h: u32, opts: &MeshView) -> (Pixmap, Pixmap) {
        let mut reference = Pixmap::new(w, h).unwrap();
        render_mesh(&mut reference, mesh, opts);
        let mut fast = Pixmap::new(w, h).unwrap();
        let view = view_of(&fast, mesh, opts);
        assert!(applies(mesh.mean_edge_length(), &view, opts));
        let mut buckets = Vec::new();
        crate::lab::stats::quick_stats_and_buckets(mesh, &mut buckets);
        render_fine(&mut fast, mesh, &buckets, &view, opts);
        if let Some(n) = opts.highlight {
            draw_highlight(&mut fast, mesh, &view, n, opts.dpr);
        }
        (reference, fast)
    }

    #[test]
    fn a_fine_mesh_is_drawn_as_render_mesh_draws_it() {
        let m = rand2d(20000, 140, 5).unwrap();
        let (r, f) = both(&m, 300, 260, &MeshView::default());
        let d = differing(&r, &f);
        // the same buckets and overlays; only pixels on element borders may go to the
        // neighbour (tiny-skia's scan conversion is not the top-left rule)
        assert!(d * 100 < (300 * 260) * 3, "{d} of {} pixels differ", 300 * 260);
    }

    #[test]
    fn inverted_elements_highlight_and_dpr_match_too() {
        let m = perturb(&plate(PlateKind::Quad, 1, 40).unwrap(), 0.6, 4).unwrap();
        let node = (0..m.node_count()).find(|&n| m.is_free(n)).unwrap();
        let opts = MeshView::default().with_dpr(2.0).with_highlight(Some(node));
        let (r, f) = both(&m, 360, 300, &opts);
        let d = differing(&r, &f);
        assert!(d * 100 < (360 * 300) * 4, "{d} of {} pixels differ", 360 * 300);
    }

    #[test]
    fn no_pixel_is_left_blank_inside_a_valid_mesh() {
        // the unit square filled by triangles: every pixel centre inside it is coloured
        let m = rand2d(5000, 60, 2).unwrap();
        let opts = MeshView { colour_bar: false, margin: 0.0, ..MeshView::default() };
        let mut pm = Pixmap::new(200, 200).unwrap();
        let view = view_of(&pm, &m, &opts);
        let mut buckets = Vec::new();
        crate::lab::stats::quick_stats_and_buckets(&m, &mut buckets);
        render_fine(&mut pm, &m, &buckets, &view, &opts);
        let white = pm.pixels().iter().filter(|p| p.red() == 255 && p.green() == 255 && p.blue() == 255).count();
        // at most the outermost row or column of pixels may miss (centres on the border)
        assert!(white <= 4 * 200, "{white} white pixels");
    }

    #[test]
    fn the_rule_covers_each_pixel_of_a_split_square_once() {
        let (w, h) = (8, 8);
        let s = SUB;
        let (a, b, c, d) = ((0, 0), (8 * s, 0), (8 * s, 8 * s), (0, 8 * s));
        // two triangles sharing the diagonal, which runs through 8 pixel centres
        let mut one = vec![0u8; w * h];
        fill_triangle(&mut one, w, h, a, b, c, 1);
        let mut other = vec![0u8; w * h];
        fill_triangle(&mut other, w, h, c, d, a, 1);
        assert!(one.iter().zip(&other).all(|(x, y)| x + y == 1), "each pixel exactly once");
        // either orientation of the same triangle takes the same pixels
        let mut reversed = vec![0u8; w * h];
        fill_triangle(&mut reversed, w, h, c, b, a, 1);
        assert_eq!(one, reversed);
    }
}
