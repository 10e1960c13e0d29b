//! The 3D surface view: the projection's numbers, the depth order, the light, odd input,
//! the camera's text form, picking, and two golden pictures.

use glam::{DVec2, DVec3};
use tiny_skia::Pixmap;

use super::super::*;
use super::golden;

const EPS: f64 = 1e-9;

fn close(a: DVec2, b: DVec2) -> bool {
    (a - b).length() < EPS
}

/// The corners of the box `[1, 3] × [2, 4] × [−1, 1]`: centre (2, 3, 0), bounding sphere
/// radius √3.
fn box_corners() -> Vec<DVec3> {
    let mut v = Vec::new();
    for x in [1.0, 3.0] {
        for y in [2.0, 4.0] {
            for z in [-1.0, 1.0] {
                v.push(DVec3::new(x, y, z));
            }
        }
    }
    v
}

#[test]
fn yaw_0_pitch_0_looks_along_plus_y_with_x_right_and_z_up() {
    let cam = Camera { yaw: 0.0, pitch: 0.0, zoom: 1.0 };
    let (r, u, f) = cam.basis();
    assert!((r - DVec3::X).length() < EPS && (u - DVec3::Z).length() < EPS && (f - DVec3::Y).length() < EPS);
    // frame 200 × 100 at (0, 0), margin 10: the sphere's radius √3 spans (100 − 20)/2 = 40 px
    let p = Projection::fit(&box_corners(), &cam, Frame::new(0.0, 0.0, 200.0, 100.0), 10.0, 1.0);
    let k = 40.0 / 3f64.sqrt();
    assert!((p.scale() - k).abs() < EPS);
    assert!((p.centre() - DVec3::new(2.0, 3.0, 0.0)).length() < EPS);
    // the box's centre is the frame's centre; +x is right, +z is up, +y is depth only
    assert!(close(p.to_css(DVec3::new(2.0, 3.0, 0.0)), DVec2::new(100.0, 50.0)));
    assert!(close(p.to_css(DVec3::new(3.0, 3.0, 0.0)), DVec2::new(100.0 + k, 50.0)));
    assert!(close(p.to_css(DVec3::new(2.0, 3.0, 1.0)), DVec2::new(100.0, 50.0 - k)));
    assert!(close(p.to_css(DVec3::new(2.0, 7.0, 0.0)), DVec2::new(100.0, 50.0)));
    assert!((p.depth(DVec3::new(2.0, 4.0, 0.0)) - 1.0).abs() < EPS, "+y is away from the viewer");
    assert!((p.depth(DVec3::new(9.0, 2.0, 5.0)) + 1.0).abs() < EPS);
    // every corner lies within the margin
    for c in box_corners() {
        let q = p.to_css(c);
        assert!(q.x >= 10.0 - EPS && q.x <= 190.0 + EPS && q.y >= 10.0 - EPS && q.y <= 90.0 + EPS, "{q:?}");
    }
    // zoom scales about the centre; the device pixel is dpr × the CSS pixel
    let z =
        Projection::fit(&box_corners(), &Camera { zoom: 2.5, ..cam }, Frame::new(0.0, 0.0, 200.0, 100.0), 10.0, 2.0);
    assert!(close(z.to_css(DVec3::new(3.0, 3.0, 0.0)), DVec2::new(100.0 + 2.5 * k, 50.0)));
    assert!(close(z.to_device(DVec3::new(3.0, 3.0, 0.0)), 2.0 * DVec2::new(100.0 + 2.5 * k, 50.0)));
}

#[test]
fn yaw_and_pitch_turn_the_view_as_documented() {
    let pts = [DVec3::splat(-1.0), DVec3::splat(1.0)];
    let frame = Frame::new(0.0, 0.0, 100.0, 100.0);
    // yaw 90: the viewer stands on +x looking along −x; +y is right
    let p = Projection::fit(&pts, &Camera { yaw: 90.0, pitch: 0.0, zoom: 1.0 }, frame, 0.0, 1.0);
    let k = 50.0 / 3f64.sqrt();
    assert!(close(p.to_css(DVec3::Y), DVec2::new(50.0 + k, 50.0)));
    assert!(close(p.to_css(DVec3::X), DVec2::new(50.0, 50.0)));
    assert!((p.depth(DVec3::X) + 1.0).abs() < EPS, "+x is towards the viewer");
    // pitch 90: looking straight down along −z, +x right and +y up
    let p = Projection::fit(&pts, &Camera { yaw: 0.0, pitch: 90.0, zoom: 1.0 }, frame, 0.0, 1.0);
    assert!(close(p.to_css(DVec3::X), DVec2::new(50.0 + k, 50.0)));
    assert!(close(p.to_css(DVec3::Y), DVec2::new(50.0, 50.0 - k)));
    assert!((p.depth(DVec3::Z) + 1.0).abs() < EPS);
    // the default three-quarter view: a point on +x is right of centre and nearer
    let p = Projection::fit(&pts, &Camera::default(), frame, 0.0, 1.0);
    assert!(p.to_css(DVec3::X).x > 50.0 && p.depth(DVec3::X) < 0.0);
    // a point on +z is above the centre
    assert!(p.to_css(DVec3::Z).y < 50.0);
}

/// A square of side 2 in the plane y = `y` centred on the y axis, ring ordered so its
/// Newell normal is −y (towards a viewer at yaw 0, pitch 0) or +y when `away`.
fn square_at(points: &mut Vec<DVec3>, rings: &mut Vec<u32>, y: f64, away: bool) {
    let base = points.len() as u32;
    let mut corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
    if away {
        corners.reverse();
    }
    for (x, z) in corners {
        points.push(DVec3::new(x, y, z));
    }
    rings.extend((0..4).map(|i| base + i));
}

fn front_view() -> SurfaceView {
    SurfaceView { camera: Camera { yaw: 0.0, pitch: 0.0, zoom: 1.0 }, colour_bar: false, ..Default::default() }
}

#[test]
fn a_face_in_front_is_painted_over_one_behind_whatever_their_order() {
    for front_first in [true, false] {
        let (mut points, mut rings) = (Vec::new(), Vec::new());
        let mut values = Vec::new();
        for (y, v) in [(0.0, 1.0), (1.0, 0.0)] {
            // front: y = 0, top of the map (yellow); back: y = 1, bottom (purple)
            square_at(&mut points, &mut rings, y, false);
            values.push(v);
        }
        if !front_first {
            points.rotate_left(4);
            values.reverse();
        }
        let faces = Faces {
            points: &points,
            ring_start: &[0, 4, 8],
            rings: &rings,
            values: &values,
            inverted: &[],
            faded: &[],
            inverted_elements: None,
        };
        let mut p = Pixmap::new(120, 120).unwrap();
        let proj = render_surface(&mut p, &faces, &front_view());
        let c = proj.to_device(DVec3::new(0.3, 0.0, 0.2));
        let px = p.pixel(c.x as u32, c.y as u32).unwrap();
        assert!(
            px.green() > 150 && px.blue() < 60,
            "front_first {front_first}: the yellow front face shows, got {px:?}"
        );
    }
}

#[test]
fn the_light_follows_lambert_and_back_faces_are_darker() {
    let l = DVec3::new(0.45, -0.55, 0.7).normalize();
    // seen along the light: facing it, its back, and grazed by it (n·view = 0 is the front)
    assert!((shade(-l, l, l) - 1.0).abs() < EPS);
    assert!((shade(l * 3.0, l, l) - BACK_FACE).abs() < EPS, "n·view > 0: the normal points away from the viewer");
    assert!((shade(-l, l, -l) - BACK_FACE).abs() < EPS);
    assert!((shade(l.cross(DVec3::X), l, l) - AMBIENT).abs() < EPS);
    assert!((shade(DVec3::ZERO, l, l) - AMBIENT).abs() < EPS);

    // on the picture: one square seen from the front, then the same from its back. At yaw 0,
    // pitch 0 the light's component along the normal ±y is 0.7/|(0.45, −0.55, 0.7)|.
    let lit = AMBIENT + (1.0 - AMBIENT) * 0.7 / (0.45f64 * 0.45 + 0.55 * 0.55 + 0.7 * 0.7).sqrt();
    let base = Colormap::Viridis.rgb(bucket(0.5) as f64 / (BUCKETS - 1) as f64);
    let mut seen = Vec::new();
    for away in [false, true] {
        let (mut points, mut rings) = (Vec::new(), Vec::new());
        square_at(&mut points, &mut rings, 0.0, away);
        let n = newell_normal(&points);
        assert!((n - if away { 8.0 } else { -8.0 } * DVec3::Y).length() < EPS, "{n:?}");
        let faces = Faces {
            points: &points,
            ring_start: &[0, 4],
            rings: &rings,
            values: &[0.5],
            inverted: &[false],
            faded: &[],
            inverted_elements: None,
        };
        let mut p = Pixmap::new(100, 100).unwrap();
        render_surface(&mut p, &faces, &front_view());
        let px = p.pixel(50, 50).unwrap();
        let k = if away { lit * BACK_FACE } else { lit };
        let want = base.map(|c| c as f64 * k);
        let got = [px.red() as f64, px.green() as f64, px.blue() as f64];
        for i in 0..3 {
            assert!((got[i] - want[i]).abs() <= 1.0, "away {away}: want {want:?}, got {got:?}");
        }
        seen.push(got);
    }
    assert!(seen[1].iter().sum::<f64>() < 0.7 * seen[0].iter().sum::<f64>());
}

#[test]
fn an_inverted_face_is_red_and_hatched() {
    let (mut points, mut rings) = (Vec::new(), Vec::new());
    square_at(&mut points, &mut rings, 0.0, false);
    let faces =
        Faces { points: &points, ring_start: &[0, 4], rings: &rings, values: &[0.5], inverted: &[true], faded: &[], inverted_elements: None };
    let mut p = Pixmap::new(100, 100).unwrap();
    render_surface(&mut p, &faces, &front_view());
    let (mut red, mut dark) = (0, 0);
    for y in 40..60 {
        for x in 40..60 {
            let px = p.pixel(x, y).unwrap();
            red += (px.red() > 180 && px.green() < 80) as u32;
            dark += (px.red() < 80 && px.green() < 80 && px.blue() < 80) as u32;
        }
    }
    assert!(red > 100 && dark > 20, "red {red}, hatch {dark}");
}

/// How many pixels differ from the background (white).
fn painted(p: &Pixmap) -> usize {
    p.pixels().iter().filter(|c| (c.red(), c.green(), c.blue()) != (255, 255, 255)).count()
}

#[test]
fn odd_input_draws_what_it_can_and_never_panics() {
    let mut p = Pixmap::new(80, 60).unwrap();
    let opts = front_view();
    // nothing at all, one point, no faces
    render_surface(&mut p, &Faces::default(), &opts);
    assert_eq!(painted(&p), 0);
    let one = [DVec3::new(1.0, 2.0, 3.0)];
    let proj = render_surface(&mut p, &Faces { points: &one, ..Default::default() }, &opts);
    assert!(close(proj.to_css(one[0]), DVec2::new(40.0, 30.0)) && proj.scale().is_finite());
    assert_eq!(proj.pick(&one, 40.0, 30.0, 1.0), Some(0));
    // all points equal: a face of zero size, drawn as nothing (or a dot), mapped to the centre
    let same = [DVec3::splat(5.0); 4];
    let proj = render_surface(
        &mut p,
        &Faces {
            points: &same,
            ring_start: &[0, 4],
            rings: &[0, 1, 2, 3],
            values: &[1.0],
            inverted: &[false],
            faded: &[],
            inverted_elements: None,
        },
        &opts,
    );
    assert!(close(proj.to_css(same[0]), DVec2::new(40.0, 30.0)));
    // a NaN and an infinite coordinate: those faces are skipped, the good one is drawn
    let (mut points, mut rings) = (Vec::new(), Vec::new());
    for y in [0.0, 1.0, 2.0] {
        square_at(&mut points, &mut rings, y, false);
    }
    points[5].x = f64::NAN;
    points[10].z = f64::INFINITY;
    let faces = Faces {
        points: &points,
        ring_start: &[0, 4, 8, 12],
        rings: &rings,
        values: &[1.0, 0.0, 0.0],
        inverted: &[],
        faded: &[],
        inverted_elements: None,
    };
    let proj = render_surface(&mut p, &faces, &opts);
    assert!(proj.scale().is_finite() && painted(&p) > 100);
    // slices that do not match: short values and flags, a ring past the end, ids out of
    // range, a backwards range, a two-node ring
    let faces = Faces {
        points: &points[..4],
        ring_start: &[0, 4, 2, 30, 40],
        rings: &[0, 1, 2, 3, 9, 1, 2],
        values: &[],
        inverted: &[],
        faded: &[],
        inverted_elements: None,
    };
    render_surface(&mut p, &faces, &opts);
    let faces = Faces {
        points: &points[..4],
        ring_start: &[0, 2, 4, 7],
        rings: &[0, 1, 2, 3, 0, 1, 99],
        values: &[f64::NAN],
        inverted: &[true, true, true, true],
        faded: &[],
        inverted_elements: None,
    };
    render_surface(&mut p, &faces, &opts);
    // a camera and options gone wrong
    let wild = SurfaceView {
        camera: Camera { yaw: f64::NAN, pitch: 1e9, zoom: -3.0 },
        dpr: f32::NAN,
        frame: Some(Frame::new(-5.0, -5.0, 0.0, 0.0)),
        margin: 1e6,
        title: Some("a title far wider than the frame it is drawn in".into()),
        domain: (f64::NAN, 0.0),
        ..Default::default()
    };
    let faces = Faces {
        points: &points[..4],
        ring_start: &[0, 4],
        rings: &rings[..4],
        values: &[0.5],
        inverted: &[],
        faded: &[],
        inverted_elements: None,
    };
    render_surface(&mut p, &faces, &wild);
    // coordinates far beyond the picture (clipped, not handed to the rasterizer whole)
    let far = [
        DVec3::new(-1.0, 0.0, -1.0),
        DVec3::new(1.0, 0.0, -1.0),
        DVec3::new(1e12, 0.0, 1e12),
        DVec3::new(-1.0, 0.0, 1.0),
    ];
    let mut big = Pixmap::new(100, 100).unwrap();
    let opts = SurfaceView { camera: Camera { zoom: 100.0, ..front_view().camera }, ..front_view() };
    render_surface(
        &mut big,
        &Faces {
            points: &far,
            ring_start: &[0, 4],
            rings: &[0, 1, 2, 3],
            values: &[1.0],
            inverted: &[true],
            faded: &[],
            inverted_elements: None,
        },
        &opts,
    );
    let mut tiny = Pixmap::new(1, 1).unwrap();
    render_surface(&mut tiny, &faces, &SurfaceView::default());
}

#[test]
fn camera_parses_its_text_form_and_says_what_is_wrong() {
    assert_eq!(Camera::parse("30,25").unwrap(), Camera { yaw: 30.0, pitch: 25.0, zoom: 1.0 });
    assert_eq!(Camera::parse(" -45 , 90 , 1.5 ").unwrap(), Camera { yaw: -45.0, pitch: 90.0, zoom: 1.5 });
    let err = |s: &str| Camera::parse(s).unwrap_err().to_string();
    assert!(err("30").contains("yaw,pitch"), "{}", err("30"));
    assert!(err("30,25,1,2").contains("yaw,pitch"));
    assert!(err("").contains("yaw,pitch"));
    assert!(err("east,25").contains("yaw \"east\" is not a number"), "{}", err("east,25"));
    assert!(err("30,,1").contains("pitch \"\" is not a number"));
    assert!(err("30,25,big").contains("zoom \"big\" is not a number"));
    assert!(err("30,91").contains("pitch 91 is outside [-90, 90]"), "{}", err("30,91"));
    assert!(err("30,-90.5").contains("outside"));
    assert!(err("30,25,0").contains("zoom 0 must be greater than 0"), "{}", err("30,25,0"));
    assert!(err("30,25,-2").contains("zoom"));
    assert!(err("30,25,inf").contains("zoom \"inf\" is not finite"));
    assert!(err("NaN,25").contains("yaw \"NaN\" is not finite"));
}

#[test]
fn dragging_orbits_and_the_wheel_zooms_within_limits() {
    let c = Camera::default().orbited(10.0, 20.0);
    assert!((c.yaw - 25.0).abs() < EPS && (c.pitch - 35.0).abs() < EPS && c.zoom == 1.0);
    assert_eq!(Camera::default().orbited(0.0, 1000.0).pitch, MAX_DRAG_PITCH);
    assert_eq!(Camera::default().orbited(0.0, -1000.0).pitch, -MAX_DRAG_PITCH);
    assert!((Camera::default().orbited(100.0, 0.0).yaw - 340.0).abs() < EPS, "yaw wraps into [0, 360)");
    assert_eq!(Camera::default().orbited(f64::NAN, f64::INFINITY), Camera { yaw: 30.0, ..Camera::default() });
    assert_eq!(Camera::default().zoomed(2.0).zoom, 2.0);
    assert_eq!(Camera::default().zoomed(1e9).zoom, ZOOM_RANGE.1);
    assert_eq!(Camera::default().zoomed(1e-9).zoom, ZOOM_RANGE.0);
    assert_eq!(Camera::default().zoomed(-1.0), Camera::default());
    assert_eq!(Camera::default().zoomed(f64::NAN), Camera::default());
}

#[test]
fn picking_prefers_the_near_side_then_the_nearest_on_screen() {
    let pts = [
        DVec3::new(0.0, 1.0, 0.0),  // behind the centre
        DVec3::new(0.0, -1.0, 0.0), // in front, on the same pixel
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.1, -1.0, 0.0), // in front, a little to the right
        DVec3::new(0.0, 0.0, f64::NAN),
    ];
    let p = Projection::fit(
        &pts,
        &Camera { yaw: 0.0, pitch: 0.0, zoom: 1.0 },
        Frame::new(0.0, 0.0, 200.0, 200.0),
        0.0,
        1.0,
    );
    let c = p.to_css(DVec3::ZERO);
    assert_eq!(p.pick(&pts, c.x, c.y, 5.0), Some(1));
    let right = p.to_css(pts[3]);
    assert_eq!(p.pick(&pts, right.x + 0.5, right.y, 20.0), Some(3));
    let x = p.to_css(pts[2]);
    assert_eq!(p.pick(&pts, x.x, x.y + 3.0, 4.0), Some(2));
    assert_eq!(p.pick(&pts, x.x, x.y + 5.0, 4.0), None);
    assert_eq!(p.pick(&pts, f64::NAN, 0.0, 4.0), None);
    assert_eq!(p.pick(&[], c.x, c.y, 4.0), None);
}

/// A UV sphere of radius 1: 8 sectors × 6 rings, quads between the rings and triangles
/// at the poles, normals outwards; two faces facing the default camera are left out so
/// the inside (seen from the back, darker) shows through the hole.
fn uv_sphere() -> (Vec<DVec3>, Vec<u32>, Vec<u32>) {
    let (sectors, rings) = (8u32, 6u32);
    let mut points = vec![DVec3::new(0.0, 0.0, -1.0)];
    for j in 1..rings {
        let theta = std::f64::consts::PI * (j as f64 / rings as f64 - 0.5);
        for i in 0..sectors {
            let phi = std::f64::consts::TAU * i as f64 / sectors as f64;
            points.push(DVec3::new(theta.cos() * phi.cos(), theta.cos() * phi.sin(), theta.sin()));
        }
    }
    points.push(DVec3::new(0.0, 0.0, 1.0));
    let top = points.len() as u32 - 1;
    let at = |j: u32, i: u32| 1 + (j - 1) * sectors + i % sectors;
    let (mut start, mut ids) = (vec![0u32], Vec::new());
    let mut push = |ring: &[u32]| {
        ids.extend_from_slice(ring);
        start.push(ids.len() as u32);
    };
    for i in 0..sectors {
        push(&[0, at(1, i + 1), at(1, i)]);
    }
    for j in 1..rings - 1 {
        for i in 0..sectors {
            // seen from outside, counter-clockwise: the camera's view of it is the normal's
            if (j == 2 || j == 3) && i == 4 {
                continue;
            }
            push(&[at(j, i), at(j, i + 1), at(j + 1, i + 1), at(j + 1, i)]);
        }
    }
    for i in 0..sectors {
        push(&[at(rings - 1, i), at(rings - 1, i + 1), top]);
    }
    (points, start, ids)
}

#[test]
fn golden_uv_sphere() {
    let (points, start, rings) = uv_sphere();
    let n = start.len() - 1;
    // every face points outwards
    for f in 0..n {
        let ring: Vec<DVec3> =
            rings[start[f] as usize..start[f + 1] as usize].iter().map(|&i| points[i as usize]).collect();
        let c = ring.iter().sum::<DVec3>() / ring.len() as f64;
        assert!(newell_normal(&ring).dot(c) > 0.0, "face {f}");
    }
    let values: Vec<f64> = (0..n).map(|f| ((f * 7) % 11) as f64 / 10.0).collect();
    let mut inverted = vec![false; n];
    inverted[13] = true;
    let faces =
        Faces { points: &points, ring_start: &start, rings: &rings, values: &values, inverted: &inverted, faded: &[], inverted_elements: None };
    let mut p = Pixmap::new(420, 320).unwrap();
    let opts = SurfaceView {
        camera: Camera { yaw: -60.0, pitch: 20.0, zoom: 1.0 },
        bar_title: "Canann's \u{3b2}".into(),
        ..Default::default()
    };
    render_surface(&mut p, &faces, &opts);
    golden("surface_uv_sphere", &p);
}

/// A saddle `z = (x² − y²)/2` over [−1, 1]², 8 six-node triangles on a 5 × 5 grid of
/// nodes (corners on the even rows and columns, mid nodes between them), every node on
/// the surface, so the edges are curved.
fn quadratic_saddle() -> (Vec<DVec3>, Vec<u32>, Vec<u32>) {
    let mut points = Vec::new();
    for j in 0..5 {
        for i in 0..5 {
            let (x, y) = (i as f64 * 0.5 - 1.0, j as f64 * 0.5 - 1.0);
            points.push(DVec3::new(x, y, 0.5 * (x * x - y * y)));
        }
    }
    let id = |i: u32, j: u32| j * 5 + i;
    let (mut start, mut ids) = (vec![0u32], Vec::new());
    for j in [0, 2] {
        for i in [0, 2] {
            for tri in [[(0, 0), (2, 0), (2, 2)], [(0, 0), (2, 2), (0, 2)]] {
                for k in 0..3 {
                    let (a, b) = (tri[k], tri[(k + 1) % 3]);
                    ids.push(id(i + a.0, j + a.1));
                    ids.push(id(i + (a.0 + b.0) / 2, j + (a.1 + b.1) / 2));
                }
                start.push(ids.len() as u32);
            }
        }
    }
    (points, start, ids)
}

#[test]
fn golden_quadratic_saddle_at_dpr_2() {
    let (points, start, rings) = quadratic_saddle();
    assert_eq!(start.len(), 9);
    let values: Vec<f64> = (0..8).map(|f| 0.3 + 0.09 * f as f64).collect();
    let mut inverted = [false; 8];
    inverted[5] = true;
    let faces =
        Faces { points: &points, ring_start: &start, rings: &rings, values: &values, inverted: &inverted, faded: &[], inverted_elements: None };
    let mut p = Pixmap::new(760, 560).unwrap();
    let opts = SurfaceView {
        dpr: 2.0,
        title: Some("quadratic saddle".into()),
        bar_title: "Lo's \u{3b1}".into(),
        ..Default::default()
    };
    let proj = render_surface(&mut p, &faces, &opts);
    // a mid node of a curved edge is drawn where it projects (the edge passes through it)
    let m = proj.to_device(points[1]);
    let px = p.pixel(m.x.round() as u32, m.y.round() as u32).unwrap();
    assert!(px.red() < 120 && px.green() < 120, "the edge is stroked through the mid node: {px:?}");
    golden("surface_quadratic_saddle_dpr2", &p);
}

/// Whichever way the camera turns, every point lies in the frame less the margin, left of
/// the colour bar and under the title.
#[test]
fn every_camera_keeps_the_mesh_inside_the_plot() {
    let (points, _, _) = uv_sphere();
    let shifted: Vec<DVec3> =
        points.iter().map(|p| *p * DVec3::new(3.0, 1.0, 0.5) + DVec3::new(10.0, -4.0, 2.0)).collect();
    for yaw in (0..360).step_by(15) {
        for pitch in (-90..=90).step_by(15) {
            let camera = Camera { yaw: yaw as f64, pitch: pitch as f64, zoom: 1.0 };
            let mut p = Pixmap::new(300, 200).unwrap();
            let opts = SurfaceView { camera, title: Some("t".into()), ..Default::default() };
            let proj = render_surface(&mut p, &Faces { points: &shifted, ..Default::default() }, &opts);
            for q in &shifted {
                let c = proj.to_css(*q);
                // the margin of a 200-px picture is 6 px; the colour bar's band is under it
                let bar_h = colour_bar_band(Frame::new(0.0, 26.0, 300.0, 174.0), "quality", &Theme::light()).map_or(0.0, |b| b.h);
                let (x1, y1) = (300.0 - 6.0, 200.0 - bar_h as f64 - 6.0);
                assert!(
                    c.x >= 6.0 - EPS && c.x <= x1 + EPS && c.y >= 26.0 + 6.0 - EPS && c.y <= y1 + EPS,
                    "{camera:?}: {c:?}"
                );
            }
        }
    }
}

/// An 8-node ring is a quadratic quad: its bowed edge is the parabola through the mid
/// node (at a quarter of the edge it bulges ¾ of the mid node's offset, where the polyline
/// through the mid node reaches ½), and the straight ones stay straight.
#[test]
fn a_quadratic_quad_is_drawn_with_its_parabolic_edge() {
    let h = 0.8;
    let (x, z) = (DVec3::X, DVec3::Z);
    let ring_pts = [-x - z, -z * (1.0 + h), x - z, x, x + z, z, -x + z, -x];
    let points: Vec<DVec3> = ring_pts.to_vec();
    assert!(newell_normal(&points).y < 0.0, "faces the viewer");
    let faces = Faces {
        points: &points,
        ring_start: &[0, 8],
        rings: &[0, 1, 2, 3, 4, 5, 6, 7],
        values: &[1.0],
        inverted: &[],
        faded: &[],
        inverted_elements: None,
    };
    let mut p = Pixmap::new(200, 200).unwrap();
    let proj = render_surface(&mut p, &faces, &SurfaceView { show_edges: false, ..front_view() });
    let filled = |q: DVec3| {
        let d = proj.to_device(q);
        let px = p.pixel(d.x.round() as u32, d.y.round() as u32).unwrap();
        (px.red(), px.green(), px.blue()) != (255, 255, 255)
    };
    // at a quarter of the bowed edge: the curve is 0.75 h below the chord
    assert!(filled(DVec3::new(-0.5, 0.0, -1.0 - 0.68 * h)), "inside the parabola, outside the polyline");
    assert!(!filled(DVec3::new(-0.5, 0.0, -1.0 - 0.82 * h)), "outside the parabola");
    assert!(filled(DVec3::new(0.0, 0.0, -1.0 - 0.95 * h)) && !filled(DVec3::new(0.0, 0.0, -1.0 - 1.08 * h)));
    // a straight edge stays where it is
    assert!(filled(DVec3::new(0.95, 0.0, 0.0)) && !filled(DVec3::new(1.08, 0.0, 0.0)));
}

/// A tangled cube of tetrahedra cut half way up z: the cut coloured by mean ratio, an
/// inverted tetrahedron hatched, the boundary faded.
#[test]
fn golden_tetrahedra_cut() {
    let cube = smoothlab::generate::tet_cube(3).unwrap();
    let m = smoothlab::generate::perturb_volume(&cube, 0.9, 2).unwrap();
    let cut = m.cut_faces(crate::Cut::default(), Camera::default().basis().2);
    assert!(cut.inverted.iter().zip(&cut.faded).any(|(&i, &f)| i && !f), "the picture must show an inverted face");
    // its key says the mesh's count, as the statistics give it
    assert_eq!(cut.inverted_elements, smoothlab::volume::volume_stats(&m).inverted);
    let mut p = Pixmap::new(360, 300).unwrap();
    let view = SurfaceView { title: Some("z = ½".into()), ..SurfaceView::default() };
    m.render_cut(&mut p, crate::Cut::default(), &view);
    golden("tetrahedra_cut", &p);
}
