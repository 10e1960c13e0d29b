//! Golden images of every view on small fixed inputs, the numbers behind the mesh
//! picture, picking, and (ignored by default) the timing of a 100k-node mesh.
//!
//! Goldens live in `tests/images/`. `UPDATE_GOLDEN=1 cargo test --lib render::` rewrites
//! them; a mismatch writes the actual picture to `target/golden-failures/`.

use std::path::{Path, PathBuf};

use glam::DVec2;
use tiny_skia::{Color, Pixmap};

use super::*;
use smoothlab::mesh::{ElementKind, Mesh, MeshBuilder};
use smoothlab::objective::{Goal, Objective, Star, Term};
use smoothlab::quality::{corner_edges, element_quality, lo_alpha_corner, mesh_stats};

fn golden_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/images").join(format!("{name}.png"))
}

/// Compares with the golden PNG exactly, as tiny-skia's own tests do: rendering is
/// deterministic (f32 rasterisation on one target, our own glyphs), so any changed pixel
/// is a changed picture. A mismatch names how many pixels and where the first one is.
fn golden(name: &str, pixmap: &Pixmap) {
    let path = golden_path(name);
    if std::env::var_os("UPDATE_GOLDEN").is_some() {
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        pixmap.save_png(&path).unwrap();
        return;
    }
    let expected = Pixmap::load_png(&path)
        .unwrap_or_else(|e| panic!("cannot read golden image {}: {e} (UPDATE_GOLDEN=1 writes it)", path.display()));
    assert_eq!((expected.width(), expected.height()), (pixmap.width(), pixmap.height()), "{name}: size");
    let differing: Vec<usize> = expected
        .pixels()
        .iter()
        .zip(pixmap.pixels())
        .enumerate()
        .filter(|(_, (a, b))| a != b)
        .map(|(i, _)| i)
        .collect();
    if let Some(&first) = differing.first() {
        let out = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../target/golden-failures");
        std::fs::create_dir_all(&out).unwrap();
        pixmap.save_png(out.join(format!("{name}.png"))).unwrap();
        let w = pixmap.width() as usize;
        panic!(
            "{name}: {} pixels differ from the golden image, the first at ({}, {}) (actual in target/golden-failures)",
            differing.len(),
            first % w,
            first / w
        );
    }
}

fn build(nodes: &[[f64; 2]], elems: &[(ElementKind, &[u32])]) -> Mesh {
    let mut b = MeshBuilder::new();
    for p in nodes {
        b.add_node([p[0], p[1], 0.0], 0);
    }
    for (k, ids) in elems {
        b.add_element(*k, ids, 0);
    }
    b.build().unwrap()
}

/// A triangle and a quad sharing an edge.
fn two_elements() -> Mesh {
    build(
        &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [2.6, 0.15]],
        &[(ElementKind::Quad4, &[0, 1, 2, 3]), (ElementKind::Tri3, &[1, 4, 2])],
    )
}

/// Two 6-node triangles; the bottom edge of the first is bowed outwards.
fn quadratic_pair() -> Mesh {
    build(
        &[[0.0, 0.0], [2.0, 0.0], [0.0, 2.0], [2.0, 2.0], [1.0, -0.45], [1.0, 1.0], [0.0, 1.0], [2.0, 1.0], [1.0, 2.0]],
        &[(ElementKind::Tri6, &[0, 1, 2, 4, 5, 6]), (ElementKind::Tri6, &[1, 3, 2, 7, 8, 5])],
    )
}

/// Four triangles around node 4, which has been pulled outside so one folds over.
fn folded_star() -> Mesh {
    build(
        &[[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0], [2.4, 1.1], [1.0, -1.0], [3.0, 1.0], [1.0, 3.0], [-1.0, 1.0]],
        &[
            (ElementKind::Tri3, &[0, 1, 4]),
            (ElementKind::Tri3, &[1, 2, 4]),
            (ElementKind::Tri3, &[2, 3, 4]),
            (ElementKind::Tri3, &[3, 0, 4]),
            (ElementKind::Tri3, &[0, 5, 1]),
            (ElementKind::Tri3, &[1, 6, 2]),
            (ElementKind::Tri3, &[2, 7, 3]),
            (ElementKind::Tri3, &[3, 8, 0]),
        ],
    )
}

/// A structured triangle grid of `n × n` nodes on the unit square, interior nodes
/// jittered by up to `jitter` of the spacing (a fixed pseudo-random sequence).
pub(crate) fn grid_mesh(n: usize, jitter: f64) -> Mesh {
    let mut b = MeshBuilder::with_capacity(n * n, 2 * (n - 1) * (n - 1));
    let h = 1.0 / (n - 1) as f64;
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut rnd = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    for j in 0..n {
        for i in 0..n {
            let interior = i > 0 && j > 0 && i < n - 1 && j < n - 1;
            let (dx, dy) = if interior { (rnd() * jitter * h, rnd() * jitter * h) } else { (0.0, 0.0) };
            b.add_node([i as f64 * h + dx, j as f64 * h + dy, 0.0], 0);
        }
    }
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let a = (j * n + i) as u32;
            let (b1, c, d) = (a + 1, a + 1 + n as u32, a + n as u32);
            b.add_element(ElementKind::Tri3, &[a, b1, c], 0);
            b.add_element(ElementKind::Tri3, &[a, c, d], 0);
        }
    }
    b.build().unwrap()
}

fn pixmap(w: u32, h: u32) -> Pixmap {
    Pixmap::new(w, h).unwrap()
}

#[test]
fn golden_two_elements() {
    let mesh = two_elements();
    let mut p = pixmap(420, 260);
    render_mesh(&mut p, &mesh, &MeshView { highlight: Some(2), ..Default::default() });
    golden("mesh_two_elements", &p);
}

#[test]
fn golden_quadratic_curved_edge_at_dpr_2() {
    let mesh = quadratic_pair();
    assert!(mesh.edges().iter().any(|e| e.curved));
    let mut p = pixmap(640, 520);
    render_mesh(&mut p, &mesh, &MeshView::default().with_dpr(2.0).with_metric(Metric::MinAngle));
    golden("mesh_quadratic_dpr2", &p);
}

#[test]
fn golden_inverted_element() {
    let mesh = folded_star();
    assert_eq!(mesh_stats(&mesh).inverted, 1);
    let mut p = pixmap(460, 380);
    render_mesh(&mut p, &mesh, &MeshView { highlight: Some(4), metric: Metric::Condition, ..Default::default() });
    golden("mesh_inverted", &p);
}

#[test]
fn golden_compare() {
    let before = grid_mesh(9, 0.9);
    let after = grid_mesh(9, 0.2);
    let lines = |m: &Mesh| {
        let s = mesh_stats(m);
        vec![
            format!("min angle {:.1}\u{b0}, max {:.1}\u{b0}", s.min_angle_deg, s.max_angle_deg),
            format!("min \u{3b1} {:.3}, mean {:.3}", s.min_quality, s.mean_quality),
        ]
    };
    let (la, lb) = (lines(&before), lines(&after));
    let mut p = pixmap(760, 400);
    render_compare(
        &mut p,
        &ComparePanel { mesh: &before, title: "jittered grid", lines: &la },
        &ComparePanel { mesh: &after, title: "less jitter", lines: &lb },
        &MeshView::default(),
    );
    golden("compare", &p);
}

use smoothlab::optimize::test_objectives::WalledBowl as Bowl;

/// The worst corner α at the free node over the star (maximised): a max-min objective
/// whose gradients are central differences, enough for a picture.
struct MinAlpha;

impl Objective for MinAlpha {
    fn name(&self) -> &'static str {
        "min-alpha"
    }
    fn goal(&self) -> Goal {
        Goal::MaximizeMin
    }
    fn terms(&self, star: &Star, x: DVec2, out: &mut Vec<Term>) {
        let alpha = |el: &smoothlab::objective::StarElement, x: DVec2| {
            let p = el.at(x);
            let ce = corner_edges(el.kind, &p[..el.kind.node_count()]);
            ce[..el.kind.corners()].iter().map(|(a, b)| lo_alpha_corner(*a, *b)).fold(f64::INFINITY, f64::min)
        };
        let h = 1e-6;
        for (i, el) in star.elems.iter().enumerate() {
            let gx = (alpha(el, x + DVec2::X * h) - alpha(el, x - DVec2::X * h)) / (2.0 * h);
            let gy = (alpha(el, x + DVec2::Y * h) - alpha(el, x - DVec2::Y * h)) / (2.0 * h);
            out.push(Term { elem: i as u32, value: alpha(el, x), grad: DVec2::new(gx, gy) });
        }
    }
}

/// A pentagon star with an off-centre free node 0.
fn pentagon_star() -> Star {
    let mut nodes = vec![[0.25, -0.1]];
    for k in 0..5 {
        let a = 0.3 + k as f64 * std::f64::consts::TAU / 5.0;
        let r = if k == 2 { 0.7 } else { 1.0 };
        nodes.push([r * a.cos(), r * a.sin()]);
    }
    let elems: Vec<[u32; 3]> = (0..5u32).map(|k| [0, 1 + k, 1 + (k + 1) % 5]).collect();
    let e: Vec<(ElementKind, &[u32])> = elems.iter().map(|t| (ElementKind::Tri3, &t[..])).collect();
    let mesh = build(&nodes, &e);
    let mut star = Star::new();
    star.gather(&mesh, 0);
    star
}

#[test]
fn golden_level_set_with_path() {
    let star = pentagon_star();
    let obj = Bowl { c: DVec2::new(-0.05, 0.05), wall: 0.7 };
    let field = sample_field(&obj, &star, star_bounds(&star, 0.08), 121, 121).unwrap();
    let path = [
        (star.x0, PathKind::Start),
        (DVec2::new(0.12, 0.12), PathKind::Gradient),
        (DVec2::new(0.0, 0.02), PathKind::Conjugate),
        (DVec2::new(-0.04, 0.05), PathKind::Conjugate),
    ];
    let data = LevelSet { field: &field, star: &star, path: &path, optimum: Some(obj.c), title: "bowl with a barrier" };
    let mut p = pixmap(440, 480);
    render_level_set(&mut p, &data, &LevelSetView::default());
    golden("levelset_bowl", &p);
}

#[test]
fn golden_level_sets_side_by_side() {
    let star = pentagon_star();
    let b = star_bounds(&star, 0.08);
    let old = sample_field(&MinAlpha, &star, b, 121, 121).unwrap();
    let bowl = Bowl { c: DVec2::new(-0.05, 0.05), wall: 10.0 };
    let new = sample_field(&bowl, &star, b, 121, 121).unwrap();
    let old_path = [(star.x0, PathKind::Start), (DVec2::new(0.1, -0.02), PathKind::ActiveSet), (DVec2::new(0.02, 0.03), PathKind::ActiveSet)];
    let new_path = [(star.x0, PathKind::Start), (DVec2::new(0.05, 0.02), PathKind::Gradient), (DVec2::new(-0.05, 0.05), PathKind::Conjugate)];
    let left = LevelSet { field: &old, star: &star, path: &old_path, optimum: None, title: "old: max min \u{3b1}" };
    let right = LevelSet { field: &new, star: &star, path: &new_path, optimum: Some(bowl.c), title: "new: a smooth bowl" };
    let mut p = pixmap(760, 420);
    render_level_sets_side_by_side(&mut p, &left, &right, &LevelSetView { legend: false, ..Default::default() });
    golden("levelset_side_by_side", &p);
}

#[test]
fn golden_convergence_chart() {
    let f: Vec<DVec2> = (0..=12).map(|i| DVec2::new(i as f64, 3.0 * 0.35f64.powi(i) + 1e-6)).collect();
    let g: Vec<DVec2> = (0..=12).map(|i| DVec2::new(i as f64, 3.0 * 0.7f64.powi(i))).collect();
    let series = [Series::new("Fletcher\u{2013}Reeves", &f).with_marker(Marker::Circle), Series::new("steepest descent", &g).with_dash(true)];
    let chart = Chart { title: "Objective during one node's solve", x_label: "iteration", y_label: "f \u{2212} f*", log_y: true, ..Default::default() };
    let mut p = pixmap(520, 340);
    render_chart(&mut p, &series, &chart);
    golden("chart_convergence", &p);
}

#[test]
fn golden_pass_histories() {
    let old = PassHistory {
        label: "old (max-min)",
        min_angle_deg: &[0.7, 9.5, 14.0, 16.2],
        max_angle_deg: &[175.9, 158.0, 149.0, 145.0],
        min_quality: &[-0.4, 0.21, 0.33, 0.38],
        inverted: &[12.0, 3.0, 1.0, 1.0],
        color: None,
    };
    let new = PassHistory {
        label: "new (Chen et al.)",
        min_angle_deg: &[0.7, 12.0, 17.5, 18.2],
        max_angle_deg: &[175.9, 150.0, 144.0, 143.5],
        min_quality: &[-0.4, 0.3, 0.41, 0.44],
        inverted: &[12.0, 0.0, 0.0, 0.0],
        color: None,
    };
    let mut p = pixmap(700, 480);
    render_pass_histories(&mut p, &[old, new], &Chart { title: "Per pass: old vs new", ..Default::default() });
    golden("chart_passes", &p);
}

#[test]
fn golden_angle_histogram() {
    let bell = |mu: f64, sd: f64, n: f64| -> Vec<u64> {
        (0..30).map(|b| (n * (-(((b as f64 + 0.5) * 6.0 - mu) / sd).powi(2) / 2.0).exp()).round() as u64).collect()
    };
    let (a, b, c) = (bell(60.0, 30.0, 400.0), bell(60.0, 16.0, 600.0), bell(60.0, 11.0, 800.0));
    let series = [
        HistogramSeries { color: None, label: "original", counts: &a },
        HistogramSeries { color: None, label: "Laplacian", counts: &b },
        HistogramSeries { color: None, label: "new", counts: &c },
    ];
    let mut p = pixmap(560, 340);
    render_angle_histogram(&mut p, &series, &AngleHistogram::default()).unwrap();
    golden("histogram_angles", &p);
}

/// The colour at the centroid of each element is its metric's colour.
#[test]
fn element_colours_follow_the_metric() {
    let mesh = two_elements();
    let mut p = pixmap(400, 300);
    let opts = MeshView { edges: Show::Never, nodes: Show::Never, ..Default::default() };
    let view = render_mesh(&mut p, &mesh, &opts);
    for e in 0..mesh.element_count() {
        let pts = mesh.element_points_array(e);
        let k = mesh.kind(e).corners();
        let c = pts[..k].iter().sum::<DVec2>() / k as f64;
        let q = element_quality(mesh.kind(e), &pts[..mesh.kind(e).node_count()]);
        // the fill takes one of 64 steps of the map: the nearest to the element's value
        let step = (q.shape * 63.0).round() / 63.0;
        assert!((step - q.shape).abs() <= 0.5 / 63.0);
        let want = Colormap::Viridis.rgb(step);
        let d = view.to_device(c);
        let got = p.pixel(d.x as u32, d.y as u32).unwrap();
        let diff = [got.red().abs_diff(want[0]), got.green().abs_diff(want[1]), got.blue().abs_diff(want[2])];
        assert!(diff.iter().all(|&x| x <= 1), "element {e}: shape {} wants {want:?}, got {got:?}", q.shape);
    }
}

#[test]
fn inverted_elements_are_red_and_hatched() {
    let mesh = folded_star();
    let mut p = pixmap(400, 400);
    let view = render_mesh(&mut p, &mesh, &MeshView { nodes: Show::Never, ..Default::default() });
    let bad = (0..mesh.element_count()).find(|&e| element_quality(mesh.kind(e), &mesh.element_points_array(e)[..3]).inverted).unwrap();
    let pts = mesh.element_points_array(bad);
    let c = view.to_device((pts[0] + pts[1] + pts[2]) / 3.0);
    let (mut red, mut dark) = (0, 0);
    for dy in -3i32..=3 {
        for dx in -3i32..=3 {
            let px = p.pixel((c.x as i32 + dx) as u32, (c.y as i32 + dy) as u32).unwrap();
            if px.red() > 180 && px.green() < 80 {
                red += 1;
            }
            if px.red() < 80 && px.green() < 80 && px.blue() < 80 {
                dark += 1;
            }
        }
    }
    assert!(red > 10 && dark > 3, "red {red}, hatch {dark}");
}

#[test]
fn picking_finds_the_nearest_node_within_the_radius() {
    let mesh = grid_mesh(6, 0.4);
    for dpr in [1.0, 2.0] {
        let opts = MeshView { zoom: ZoomPan { zoom: 1.7, pan: DVec2::new(-30.0, 12.0) }, dpr, ..Default::default() };
        let view = mesh_view(600 * dpr as u32, 400 * dpr as u32, &mesh, &opts);
        for (n, p) in mesh.nodes().iter().enumerate() {
            let css = view.to_css(*p);
            if css.x < 0.0 || css.y < 0.0 || css.x > 600.0 || css.y > 400.0 {
                continue;
            }
            assert_eq!(pick_node(&mesh, &view, css.x + 2.0, css.y - 3.0), Some(n));
            // the click maps back to the mesh point
            assert!((view.css_to_world(css) - *p).length() < 1e-12);
        }
        let far = view.to_css(DVec2::new(-1.0, -1.0));
        assert_eq!(pick_node(&mesh, &view, far.x, far.y), None);
        assert_eq!(pick_node(&mesh, &view, f64::NAN, 0.0), None);
        // half-way between two neighbours, the nearer one wins
        let (a, b) = (view.to_css(mesh.nodes()[0]), view.to_css(mesh.nodes()[1]));
        let q = a + 0.4 * (b - a);
        assert_eq!(pick_node_within(&mesh, &view, q.x, q.y, 1e9), Some(0));
    }
}

#[test]
fn mesh_fits_inside_the_frame_above_the_colour_bar() {
    let mesh = grid_mesh(5, 0.3);
    let opts = MeshView::default().with_dpr(1.5);
    let view = mesh_view(900, 600, &mesh, &opts);
    let (w, h) = (900.0 / 1.5, 600.0 / 1.5);
    let bar = colour_bar_band(Frame::new(0.0, 0.0, w as f32, h as f32), opts.metric.label(&mesh), &opts.theme).unwrap();
    assert!(bar.h > 10.0 && bar.h <= COLOUR_BAR_SHARE * 400.0 && bar.y + bar.h == h as f32);
    for p in mesh.nodes() {
        let c = view.to_css(*p);
        assert!(c.x >= 16.0 - 1e-9 && c.y >= 16.0 - 1e-9, "{c:?}");
        assert!(c.x <= w - 16.0 + 1e-9 && c.y <= h - bar.h as f64 - 16.0 + 1e-9, "{c:?}");
    }
}

#[test]
fn png_round_trip() {
    let mut p = pixmap(120, 90);
    render_mesh(&mut p, &two_elements(), &MeshView::default());
    let bytes = encode_png(&p).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");
    assert_eq!(Pixmap::decode_png(&bytes).unwrap().data(), p.data());
}

#[test]
fn odd_inputs_do_not_panic() {
    let mut mesh = two_elements();
    mesh.nodes_mut()[4] = DVec2::new(f64::NAN, 1.0);
    let mut p = pixmap(50, 40);
    render_mesh(&mut p, &mesh, &MeshView { highlight: Some(99), dpr: 0.0, margin: 100.0, ..Default::default() });
    render_mesh(&mut p, &mesh, &MeshView { zoom: ZoomPan { zoom: -1.0, pan: DVec2::splat(f64::INFINITY) }, ..Default::default() });
    let mut tiny = pixmap(1, 1);
    render_mesh(&mut tiny, &two_elements(), &MeshView { frame: Some(Frame::new(-5.0, -5.0, 0.0, 0.0)), ..Default::default() });
}

/// 100k nodes, ~200k triangles, 1600 × 1200 device pixels. Run with
/// `cargo test --release --lib render::tests::large_mesh_renders_fast -- --ignored --nocapture`.
#[test]
#[ignore]
fn large_mesh_renders_fast() {
    let mesh = grid_mesh(317, 0.3);
    assert!(mesh.node_count() >= 100_000);
    let mut p = pixmap(1600, 1200);
    let mut best = f64::INFINITY;
    for _ in 0..3 {
        let t = std::time::Instant::now();
        render_mesh(&mut p, &mesh, &MeshView::default());
        best = best.min(t.elapsed().as_secs_f64());
    }
    let mut p2 = pixmap(1600, 1200);
    let t = std::time::Instant::now();
    render_mesh(&mut p2, &mesh, &MeshView { edges: Show::Always, zoom: ZoomPan { zoom: 4.0, pan: DVec2::ZERO }, ..Default::default() });
    let zoomed = t.elapsed().as_secs_f64();
    if let Some(dir) = std::env::var_os("RENDER_SAVE_DIR") {
        p2.save_png(Path::new(&dir).join("large_mesh_zoomed.png")).unwrap();
        p.save_png(Path::new(&dir).join("large_mesh.png")).unwrap();
    }
    println!("render_mesh: {} nodes, {} elements, 1600x1200: {:.0} ms fitted (best of 3), {:.0} ms zoomed x4 with edges", mesh.node_count(), mesh.element_count(), best * 1e3, zoomed * 1e3);
    // the figure that matters is the optimised build's (the CLI and the page ship it)
    if !cfg!(debug_assertions) {
        assert!(best < 1.0, "{best} s");
    }
}



/// A title too wide for its frame is drawn smaller, not clipped; one that fits keeps its size.
#[test]
fn text_shrinks_to_fit_its_width() {
    use super::text::{size_to_fit, text_width};
    let title = "B: new: Chen, Tristano & Kwok (Fletcher–Reeves), barrier penalty";
    let full = text_width(title, 14.0);
    let fit = size_to_fit(title, 14.0, 200.0);
    assert!(full > 200.0 && fit < 14.0);
    assert!(text_width(title, fit) <= 200.0 + 0.5, "{}", text_width(title, fit));
    assert_eq!(size_to_fit("A: old", 14.0, 200.0), 14.0);
}

/// A title too wide even at the smallest size keeps its leading words and "…" (centred
/// and clipped, the figure's B title lost its first and last words); one that fits is whole.
#[test]
fn a_title_too_wide_at_the_smallest_size_keeps_its_leading_words() {
    use super::text::{fit_words, text_width};
    let title = "B: new: Chen, Tristano & Kwok (Fletcher–Reeves), barrier penalty";
    let width = 0.7 * text_width(title, 10.0);
    let shown = fit_words(title, 10.0, width);
    assert!(shown.starts_with("B: new: Chen") && shown.ends_with('…'), "{shown}");
    assert!(text_width(&shown, 10.0) <= width, "{shown}");
    assert_eq!(fit_words(title, 10.0, 2.0 * width), title);
    assert_eq!(fit_words("A: old", 10.0, 1.0), "…");
}

#[test]
fn an_inverted_element_flung_far_away_is_hatched_only_where_it_shows() {
    // the max-min objective can fling a node of a tangled mesh a billion units away: the
    // hatching covers the picture, not the element's whole bounds (which hung the page)
    let mut b = smoothlab::mesh::MeshBuilder::with_capacity(4, 2);
    for p in [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]] {
        b.add_node(p, 0);
    }
    b.add_element(smoothlab::mesh::ElementKind::Tri3, &[0, 1, 2], 0);
    b.add_element(smoothlab::mesh::ElementKind::Tri3, &[0, 2, 3], 0);
    let mut m = b.build().unwrap();
    m.nodes_mut()[3] = glam::DVec2::new(1.0e12, -0.5e12);
    assert!(smoothlab::quality::mesh_stats(&m).inverted > 0);
    let mut pm = tiny_skia::Pixmap::new(300, 300).unwrap();
    let view = MeshView { bounds: Some((glam::DVec2::ZERO, glam::DVec2::ONE)), ..MeshView::default() };
    render_mesh(&mut pm, &m, &view);
    let dark = pm.pixels().iter().filter(|p| p.alpha() == 255 && p.red() < 40 && p.green() < 40 && p.blue() < 40).count();
    let red = pm.pixels().iter().filter(|p| p.red() > 150 && p.green() < 80 && p.blue() < 80).count();
    assert!(red > 40 && dark > 40, "the visible part is red and hatched: {red} red, {dark} dark pixels");
}

mod view3d;

/// The page's theme (14-px labels, light or dark) at pixel ratios 1 and 2: every text of
/// every view is at least 14 CSS pixels, as `text.rs` records the smallest size drawn.
#[test]
fn every_label_is_at_least_the_pages_size() {
    use super::text::take_smallest_text;
    let mesh = folded_star();
    let star = pentagon_star();
    let obj = Bowl { c: DVec2::new(-0.05, 0.05), wall: 0.7 };
    let field = sample_field(&obj, &star, star_bounds(&star, 0.08), 41, 41).unwrap();
    let path = [(star.x0, PathKind::Start), (DVec2::new(0.1, 0.1), PathKind::Gradient), (DVec2::new(0.0, 0.02), PathKind::Conjugate)];
    let data = LevelSet { field: &field, star: &star, path: &path, optimum: Some(obj.c), title: "bowl with a barrier" };
    let pts: Vec<DVec2> = (0..=12).map(|i| DVec2::new(i as f64, 3.0 * 0.5f64.powi(i))).collect();
    let below: Vec<DVec2> = vec![DVec2::new(0.0, -170.0), DVec2::new(1.0, 20.0), DVec2::new(2.0, 25.0)];
    let counts: Vec<u64> = (0..30).map(|b| (b * 7 % 13) as u64).collect();
    let lines = vec!["min angle 3.4°".to_string(), "inverted 1".to_string()];
    let (sphere, rings, starts) = view3d_sphere();
    for theme in [Theme::for_page(false, 14.0), Theme::for_page(true, 14.0)] {
        for dpr in [1.0f32, 2.0] {
            let px = |w: u32, h: u32| pixmap((w as f32 * dpr) as u32, (h as f32 * dpr) as u32);
            let mut views: Vec<(&str, Drawing<'_>)> = Vec::new();
            views.push(("mesh", Box::new(|| {
                for side in [200u32, 320, 640] {
                    let mut p = px(side, side);
                    render_mesh(&mut p, &mesh, &MeshView { theme, dpr, highlight: Some(4), ..Default::default() });
                }
            })));
            views.push(("compare", Box::new(|| {
                let mut p = px(760, 420);
                let panel = ComparePanel { mesh: &mesh, title: "a mesh", lines: &lines };
                render_compare(&mut p, &panel, &panel, &MeshView { theme, dpr, ..Default::default() });
            })));
            views.push(("level set", Box::new(|| {
                for (w, h) in [(260u32, 380u32), (440, 480)] {
                    let mut p = px(w, h);
                    render_level_set(&mut p, &data, &LevelSetView { theme, dpr, ..Default::default() });
                }
            })));
            views.push(("charts", Box::new(|| {
                let mut p = px(520, 340);
                let ser = [Series::new("a curve", &pts), Series::new("another", &pts).with_dash(true)];
                render_chart(&mut p, &ser, &Chart { title: "t", x_label: "x", y_label: "y", log_y: true, theme, dpr, ..Default::default() });
                let ser = [Series::new("folded", &below)];
                render_chart(&mut p, &ser, &Chart { title: "t", y_break: Some(0.0), theme, dpr, ..Default::default() });
                render_chart(&mut p, &[], &Chart { theme, dpr, ..Default::default() });
                let h = PassHistory { label: "A", min_angle_deg: &[1.0, 2.0], max_angle_deg: &[170.0, 150.0], min_quality: &[0.1, 0.2], inverted: &[3.0, 0.0], color: None };
                let mut p = px(700, 480);
                render_pass_histories(&mut p, &[h], &Chart { title: "Per pass", theme, dpr, ..Default::default() });
            })));
            views.push(("histogram", Box::new(|| {
                let mut p = px(520, 280);
                let ser = [HistogramSeries { label: "as loaded", counts: &counts, color: None }];
                render_angle_histogram(&mut p, &ser, &AngleHistogram { theme, dpr, ..Default::default() }).unwrap();
            })));
            views.push(("3D", Box::new(|| {
                for side in [200u32, 400] {
                    let mut p = px(side, side);
                    let faces = Faces { points: &sphere, rings: &rings, ring_start: &starts, ..Default::default() };
                    render_surface(&mut p, &faces, &SurfaceView { title: Some("a sphere".into()), theme, dpr, ..Default::default() });
                }
            })));
            views.push(("sketch and titled", Box::new(|| {
                let mut p = px(300, 260);
                let lines = [SketchLine { from: DVec2::ZERO, to: DVec2::X, color: theme.ink, label: "y = 0" }];
                let sketch = Sketch { title: "a sketch", points: &[(DVec2::Y, "A")], lines: &lines, dashed: &[] };
                render_sketch(&mut p, &sketch, Frame::new(0.0, 0.0, 300.0, 260.0), dpr, &theme);
                render_titled(&[p], 1, "a figure", dpr, &theme).unwrap();
            })));
            for (name, draw) in &views {
                take_smallest_text();
                draw();
                let smallest = take_smallest_text();
                assert!(smallest.is_finite(), "{name}: no text drawn");
                assert!(smallest >= 14.0 * dpr - 1e-3, "{name}, dark {}, dpr {dpr}: a label of {smallest} px", theme.paper != Color::WHITE);
            }
        }
    }
    // the light theme keeps each label's own size: the legend's 9.9 px
    take_smallest_text();
    render_level_set(&mut pixmap(440, 480), &data, &LevelSetView::default());
    assert!((take_smallest_text() - 9.9).abs() < 1e-3);
}

/// A view drawn by the label size test.
type Drawing<'a> = Box<dyn Fn() + 'a>;

fn view3d_sphere() -> (Vec<glam::DVec3>, Vec<u32>, Vec<u32>) {
    let mut points = Vec::new();
    let mut rings = Vec::new();
    let mut offsets = vec![0u32];
    let (nu, nv) = (12usize, 8usize);
    for j in 0..=nv {
        for i in 0..nu {
            let (u, v) = (i as f64 / nu as f64 * std::f64::consts::TAU, j as f64 / nv as f64 * std::f64::consts::PI);
            points.push(glam::DVec3::new(v.sin() * u.cos(), v.sin() * u.sin(), v.cos()));
        }
    }
    for j in 0..nv {
        for i in 0..nu {
            let a = (j * nu + i) as u32;
            let b = (j * nu + (i + 1) % nu) as u32;
            rings.extend([a, b, b + nu as u32, a + nu as u32]);
            offsets.push(rings.len() as u32);
        }
    }
    (points, rings, offsets)
}

/// A square mesh fills at least 70% of a square canvas's side at every size from 150 px,
/// in the light and the page's theme: the colour bar takes at most 12% of the side or is
/// left out, never half the canvas.
#[test]
fn a_mesh_fills_most_of_a_small_canvas() {
    let mesh = grid_mesh(6, 0.0);
    let (lo, hi) = mesh.bounds();
    for theme in [Theme::light(), Theme::for_page(true, 14.0)] {
        for dpr in [1.0f32, 2.0] {
            for side in (150..=1000).step_by(10) {
                let d = (side as f32 * dpr) as u32;
                let opts = MeshView { theme, dpr, ..Default::default() };
                let view = mesh_view(d, d, &mesh, &opts);
                let extent = (view.to_css(hi) - view.to_css(lo)).abs().min_element();
                assert!(extent >= 0.7 * side as f64 - 1e-6, "{side} px at dpr {dpr}: {extent}");
                let frame = Frame::new(0.0, 0.0, side as f32, side as f32);
                let bar = colour_bar_band(frame, opts.metric.label(&mesh), &theme);
                assert_eq!(bar.is_some(), mesh_colour_bar_shown(d, d, &mesh, &opts));
                if let Some(b) = bar {
                    assert!(b.h <= COLOUR_BAR_SHARE * side as f32);
                }
                if side <= 180 {
                    assert!(bar.is_none(), "{side} px: no room for a bar");
                }
                if side >= 400 {
                    assert!(bar.is_some(), "{side} px: the bar is drawn");
                }
            }
        }
    }
}

/// The 3D view, titled as the page draws it, keeps a sphere at least 70% of a square
/// canvas's side from 150 px.
#[test]
fn a_surface_fills_most_of_a_small_canvas() {
    let (points, rings, starts) = view3d_sphere();
    for theme in [Theme::light(), Theme::for_page(true, 14.0)] {
        for side in (150..=600u32).step_by(25) {
            let mut p = pixmap(side, side);
            let faces = Faces { points: &points, rings: &rings, ring_start: &starts, ..Default::default() };
            let proj = render_surface(&mut p, &faces, &SurfaceView { title: Some("A: old".into()), theme, ..Default::default() });
            let xs: Vec<f64> = points.iter().map(|q| proj.to_css(*q).x).collect();
            let width = xs.iter().cloned().fold(f64::MIN, f64::max) - xs.iter().cloned().fold(f64::MAX, f64::min);
            assert!(width >= 0.7 * side as f64, "{side} px: {width}");
        }
    }
}

/// The level-set window frames the feasible region with the start and the optimum: for
/// a star whose node can move only in a sliver, the window is a fraction of the star's.
#[test]
fn the_level_set_window_frames_the_feasible_region() {
    // a star-shaped ring of six spikes: the node can move only within the inner part
    // before a triangle folds
    let mut nodes = vec![[0.05, 0.02]];
    for k in 0..12 {
        let a = k as f64 * std::f64::consts::PI / 6.0;
        let r = if k % 2 == 0 { 1.0 } else { 0.3 };
        nodes.push([r * a.cos(), r * a.sin()]);
    }
    let tris: Vec<[u32; 3]> = (0..12u32).map(|k| [0, 1 + k, 1 + (k + 1) % 12]).collect();
    let e: Vec<(ElementKind, &[u32])> = tris.iter().map(|t| (ElementKind::Tri3, &t[..])).collect();
    let mesh = build(&nodes, &e);
    let mut star = Star::new();
    star.gather(&mesh, 0);
    let whole = star_bounds(&star, 0.1);
    let opt = DVec2::new(-0.05, 0.1);
    let (lo, hi) = feasible_bounds(&star, &[star.x0, opt], 0.1);
    let (ws, fs) = ((whole.1 - whole.0).x, (hi - lo).x);
    assert!(fs < 0.5 * ws, "the window {fs} is not the star's {ws}");
    for p in [star.x0, opt] {
        assert!(p.cmpge(lo).all() && p.cmple(hi).all(), "{p} in {lo}..{hi}");
    }
    // every feasible point of the star lies in it
    for j in 0..60 {
        for i in 0..60 {
            let p = whole.0 + (whole.1 - whole.0) * DVec2::new(i as f64 / 59.0, j as f64 / 59.0);
            let valid = star.elems.iter().all(|el| {
                let q = el.at(p);
                let ce = corner_edges(el.kind, &q[..el.kind.node_count()]);
                ce[..3].iter().all(|(a, b)| smoothlab::quality::scaled_jacobian(*a, *b) > 0.0)
            });
            if valid {
                assert!(p.cmpge(lo).all() && p.cmple(hi).all(), "feasible {p} outside {lo}..{hi}");
            }
        }
    }
    // a star with no feasible point keeps its own box
    assert_eq!(feasible_bounds(&Star::new(), &[], 0.1), star_bounds(&Star::new(), 0.1));
}
