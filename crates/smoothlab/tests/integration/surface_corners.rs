//! Issue 58: a valid closed surface with sharp corners reads as valid. Solids of flat faces
//! (a right triangular prism, in triangles or with quad sides; a right-corner tetrahedron;
//! a square pyramid; a cube), each face subdivided so that some nodes lie inside it, read
//! from a file with and without fixed flags:
//!
//! 1. `stats` reads none inverted, and the angles the faces were cut into: the prism's
//!    sides of 1 by 1 cut in 2 by 2, its slanted side's rectangles of √2/2 by 1/2 split
//!    along a diagonal, atan(1/√2) = 35.26° and 90°; the tetrahedron's right faces 45° and
//!    90°, its slanted face 60°; the pyramid's sides (apex 1/2 over the unit base, so its
//!    edges are √3/2 long) acos(1/√3) = 54.74° at the base and 70.53° at the apex.
//! 2. Its feature curves are the solid's edges: a node is on one when it is on two faces;
//!    without fixed flags those nodes are fixed, with them the file's flags stay.
//! 3. Every strategy with the default objective, and every objective with `rules`, leaves
//!    the solid, and a copy with its inner nodes moved within their faces, valid and no
//!    worse in its smallest and largest angle.
//! 4. The defaults never turn an element inward (against its normal as read).
//!
//! Before, the fold test compared each facet with its vertices' area-weighted normals,
//! which across an edge turning past a right angle (the prism's slanted side, 135° from
//! its legs) or at a corner face away from one face: the file was taken for tangled and
//! fitted through its nodes, 9 of the prism's 32 triangles read inverted and one pass of
//! the defaults turned triangles inward.

use smoothlab::io::{read_model_str, Format};
use smoothlab::model::Model;
use smoothlab::objective::ObjectiveKind;
use smoothlab::smooth::Strategy;
use smoothlab::surface::Reference;
use smoothlab::Smoothing;

type P = [f64; 3];

fn sub(a: P, b: P) -> P {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: P, b: P) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: P, b: P) -> P {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}
fn lerp(a: P, b: P, t: f64) -> P {
    [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])]
}

#[derive(Clone, Copy, Debug)]
enum Solid {
    /// The right prism over the triangle (0,0), (1,0), (0,1), 1 high.
    Prism,
    /// The tetrahedron of the origin and the three unit points.
    Tetrahedron,
    /// The pyramid over the unit square, its apex 1/2 over the centre.
    Pyramid,
    Cube,
}

impl Solid {
    /// The faces: planar convex polygons (outward or not: [`mesh`] orients them).
    fn faces(self) -> Vec<Vec<P>> {
        match self {
            Solid::Prism => {
                let tri = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
                let at = |i: usize, z: f64| [tri[i][0], tri[i][1], z];
                let mut f = vec![(0..3).map(|i| at(i, 0.0)).collect(), (0..3).map(|i| at(i, 1.0)).collect()];
                f.extend((0..3).map(|i| vec![at(i, 0.0), at((i + 1) % 3, 0.0), at((i + 1) % 3, 1.0), at(i, 1.0)]));
                f
            }
            Solid::Tetrahedron => {
                let [o, x, y, z] = [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
                vec![vec![o, x, y], vec![o, x, z], vec![o, y, z], vec![x, y, z]]
            }
            Solid::Pyramid => {
                let base = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
                let apex = [0.5, 0.5, 0.5];
                let mut f = vec![base.to_vec()];
                f.extend((0..4).map(|i| vec![base[i], base[(i + 1) % 4], apex]));
                f
            }
            Solid::Cube => {
                let c = |i: usize| [(i & 1) as f64, (i >> 1 & 1) as f64, (i >> 2 & 1) as f64];
                [[0, 1, 3, 2], [4, 5, 7, 6], [0, 1, 5, 4], [2, 3, 7, 6], [0, 2, 6, 4], [1, 3, 7, 5]]
                    .iter()
                    .map(|f| f.iter().map(|&i| c(i)).collect())
                    .collect()
            }
        }
    }
}

/// A solid's surface: its points, its elements (outward) and per node the number of faces
/// it lies on.
struct Solidmesh {
    points: Vec<P>,
    elements: Vec<Vec<usize>>,
    faces_at: Vec<usize>,
}

/// `solid` with each edge of each face cut in `n`: a triangle into n² triangles, a quad
/// into n² quads (`quads`) or each of them split into two triangles. Nodes inside a face
/// move within it by up to `shift` of a cell, at random (by `seed`).
fn mesh(solid: Solid, n: usize, quads: bool, shift: f64, seed: u64) -> Solidmesh {
    let faces = solid.faces();
    let corners: Vec<P> = faces.iter().flatten().copied().collect();
    let centre = corners.iter().fold([0.0; 3], |c, p| [c[0] + p[0], c[1] + p[1], c[2] + p[2]]);
    let centre = centre.map(|c| c / corners.len() as f64);
    let mut points: Vec<P> = Vec::new();
    let node = |p: P, points: &mut Vec<P>| -> usize {
        let key = |q: &P| q.map(|x| (x * 1e9).round() as i64);
        match points.iter().position(|q| key(q) == key(&p)) {
            Some(i) => i,
            None => {
                points.push(p);
                points.len() - 1
            }
        }
    };
    let mut elements = Vec::new();
    for f in &faces {
        let mut e: Vec<Vec<usize>> = Vec::new();
        let nf = n as f64;
        if f.len() == 3 {
            let at = |i: usize, j: usize| {
                let (u, v) = (i as f64 / nf, j as f64 / nf);
                lerp(lerp(f[0], f[1], u), lerp(f[0], f[2], u), if u == 0.0 { 0.0 } else { v / u })
            };
            // (i, j): i steps along 0 → 1 and 0 → 2 together, j of them towards 2
            let id = |i: usize, j: usize, points: &mut Vec<P>| node(at(i, j), points);
            for i in 0..n {
                for j in 0..=i {
                    let t = [id(i, j, &mut points), id(i + 1, j, &mut points), id(i + 1, j + 1, &mut points)];
                    e.push(t.to_vec());
                    if j < i {
                        e.push(vec![id(i, j, &mut points), id(i + 1, j + 1, &mut points), id(i, j + 1, &mut points)]);
                    }
                }
            }
        } else {
            let at = |i: usize, j: usize| {
                lerp(lerp(f[0], f[1], i as f64 / nf), lerp(f[3], f[2], i as f64 / nf), j as f64 / nf)
            };
            for i in 0..n {
                for j in 0..n {
                    let q = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)].map(|(a, b)| node(at(a, b), &mut points));
                    if quads {
                        e.push(q.to_vec());
                    } else {
                        e.push(vec![q[0], q[1], q[2]]);
                        e.push(vec![q[0], q[2], q[3]]);
                    }
                }
            }
        }
        // outward: the face's normal points away from the solid's centre
        if dot(cross(sub(f[1], f[0]), sub(f[2], f[0])), sub(f[0], centre)) < 0.0 {
            e.iter_mut().for_each(|x| x.reverse());
        }
        elements.extend(e);
    }
    let on = |p: P, f: &Vec<P>| {
        let normal = cross(sub(f[1], f[0]), sub(f[2], f[0]));
        dot(sub(p, f[0]), normal).abs() < 1e-9 * dot(normal, normal).sqrt()
    };
    let faces_at: Vec<usize> = points.iter().map(|&p| faces.iter().filter(|f| on(p, f)).count()).collect();
    // a node inside a face moves within it
    let mut state = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    let mut random = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let cell = 1.0 / n as f64;
    for (p, &k) in points.iter_mut().zip(&faces_at) {
        let (Some(f), 1) = (faces.iter().find(|f| on(*p, f)), k) else { continue };
        let (u, w) = (sub(f[1], f[0]), sub(f[2], f[0]));
        let w = cross(cross(u, w), u);
        let (u, w) = (u.map(|x| x / dot(u, u).sqrt()), w.map(|x| x / dot(w, w).sqrt()));
        let (a, b) = (shift * cell * random(), shift * cell * random());
        *p = [0, 1, 2].map(|i| p[i] + a * u[i] + b * w[i]);
    }
    Solidmesh { points, elements, faces_at }
}

/// The mesh as a VTK file, with the fixed flags of the nodes on two faces when `flags`.
fn vtk(m: &Solidmesh, flags: bool) -> String {
    let mut s = format!("# vtk DataFile Version 3.0\nsolid\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS {} double\n", m.points.len());
    for p in &m.points {
        s += &format!("{:?} {:?} {:?}\n", p[0], p[1], p[2]);
    }
    let size: usize = m.elements.iter().map(|e| e.len() + 1).sum();
    s += &format!("CELLS {} {size}\n", m.elements.len());
    for e in &m.elements {
        s += &format!("{} {}\n", e.len(), e.iter().map(|i| i.to_string()).collect::<Vec<_>>().join(" "));
    }
    s += &format!("CELL_TYPES {}\n", m.elements.len());
    for e in &m.elements {
        s += if e.len() == 3 { "5\n" } else { "9\n" };
    }
    if flags {
        s += &format!("POINT_DATA {}\nSCALARS fixed int 1\nLOOKUP_TABLE default\n", m.points.len());
        for &k in &m.faces_at {
            s += if k >= 2 { "1\n" } else { "0\n" };
        }
    }
    s
}

fn read(m: &Solidmesh, flags: bool) -> Model {
    let model = read_model_str(&vtk(m, flags), Format::Vtk).unwrap();
    assert!(matches!(model, Model::Surface(_)), "a solid's skin reads as a surface");
    model
}

/// Every case: the solid, its cuts, quads or triangles, its smallest and largest angle.
fn cases() -> Vec<(Solid, usize, bool, f64, f64)> {
    let deg = |x: f64| x.to_degrees();
    vec![
        (Solid::Prism, 2, false, deg((1.0 / 2f64.sqrt()).atan()), 90.0),
        (Solid::Prism, 3, false, deg((1.0 / 2f64.sqrt()).atan()), 90.0),
        (Solid::Prism, 2, true, 45.0, 90.0),
        (Solid::Tetrahedron, 3, false, 45.0, 90.0),
        (Solid::Pyramid, 2, false, 45.0, 90.0),
        (Solid::Pyramid, 3, true, deg((1.0 / 3f64.sqrt()).acos()), 90.0),
        (Solid::Cube, 3, false, 45.0, 90.0),
        (Solid::Cube, 3, true, 90.0, 90.0),
    ]
}

fn name(solid: Solid, n: usize, quads: bool, flags: bool) -> String {
    let kind = if quads { "quads" } else { "triangles" };
    format!("{solid:?} cut in {n}, {kind}, {}", if flags { "fixed flags" } else { "no flags" })
}

#[test]
fn a_solid_reads_as_valid_with_its_angles_and_its_edges_as_feature_curves() {
    for (solid, n, quads, min, max) in cases() {
        let m = mesh(solid, n, quads, 0.0, 0);
        for flags in [false, true] {
            let what = name(solid, n, quads, flags);
            let model = read(&m, flags);
            let st = model.stats();
            assert_eq!(st.inverted, 0, "{what}: {st:?}");
            assert!((st.min_angle_deg - min).abs() < 1e-9, "{what}: smallest angle {} not {min}", st.min_angle_deg);
            assert!((st.max_angle_deg - max).abs() < 1e-9, "{what}: largest angle {} not {max}", st.max_angle_deg);
            let Model::Surface(s) = &model else { unreachable!() };
            assert!(matches!(s.reference(), Reference::Facets(_)), "{what}: {}", s.reference().describe());
            for (i, &k) in m.faces_at.iter().enumerate() {
                assert_eq!(s.is_feature(i), k >= 2, "{what}: node {i} on {k} faces");
                assert_eq!(s.flat().is_fixed(i), k >= 2, "{what}: node {i} on {k} faces");
            }
            // some nodes are free: the faces' inner nodes
            assert!(m.faces_at.contains(&1), "{what}");
        }
    }
}

/// The smallest and largest angle and the inverted count the statistics read, and each
/// element's normal in 3D (Newell's).
fn reading(model: &Model) -> (f64, f64, usize, Vec<P>) {
    let Model::Surface(s) = model else { panic!("a surface") };
    let st = model.stats();
    let normals = (0..s.element_count())
        .map(|e| {
            let ids = s.flat().element(e);
            let k = s.flat().kind(e).corners();
            let p = |i: usize| s.points()[ids[i % k] as usize].to_array();
            (0..k).fold([0.0; 3], |n, i| {
                let c = cross(p(i), p(i + 1));
                [n[0] + c[0], n[1] + c[1], n[2] + c[2]]
            })
        })
        .collect();
    (st.min_angle_deg, st.max_angle_deg, st.inverted, normals)
}

#[test]
fn no_strategy_or_objective_makes_a_solid_worse() {
    let mut runs: Vec<(String, Smoothing)> = Strategy::ALL
        .iter()
        .map(|&s| (format!("{} new", s.name()), Smoothing::default().strategy(s)))
        .collect();
    runs.extend(ObjectiveKind::ALL.iter().map(|&o| {
        (format!("rules {}", o.name()), Smoothing::default().strategy(Strategy::Rules).objective(o))
    }));
    for (solid, n, quads, _, _) in cases() {
        // as cut, and with the inner nodes moved within their faces by up to 0.3 of a cell
        for (shift, seed) in [(0.0, 0), (0.6, 1), (0.6, 2)] {
            let m = mesh(solid, n, quads, shift, seed);
            for flags in [false, true] {
                let what = format!("{} moved {shift} (seed {seed})", name(solid, n, quads, flags));
                let model = read(&m, flags);
                let (min, max, inverted, before) = reading(&model);
                assert_eq!(inverted, 0, "{what}");
                for (run, smoothing) in &runs {
                    let mut t = model.clone();
                    let report = t.smooth(&smoothing.passes(2)).unwrap();
                    let (tmin, tmax, tinverted, after) = reading(&t);
                    assert_eq!((tinverted, report.inverted()), (0, 0), "{what}, {run}");
                    // turned inward: against its normal as read
                    for (e, (b, a)) in before.iter().zip(&after).enumerate() {
                        assert!(dot(*b, *a) > 0.0, "{what}, {run}: element {e} turned inward");
                    }
                    assert!(tmin >= min - 1e-9, "{what}, {run}: smallest angle {min} → {tmin}");
                    assert!(tmax <= max + 1e-9, "{what}, {run}: largest angle {max} → {tmax}");
                }
            }
        }
    }
}

/// The prism: 18 nodes, 32 triangles, its three side faces' centres free; one
/// pass of the defaults turned 4 triangles inward.
#[test]
fn the_defaults_never_turn_the_prism_inward() {
    let m = mesh(Solid::Prism, 2, false, 0.0, 0);
    assert_eq!((m.points.len(), m.elements.len()), (18, 32));
    for flags in [false, true] {
        let mut model = read(&m, flags);
        let (_, _, _, before) = reading(&model);
        for pass in 1..=3 {
            model.smooth(&Smoothing::default()).unwrap();
            let (min, max, inverted, after) = reading(&model);
            assert_eq!(inverted, 0, "pass {pass}");
            assert!(before.iter().zip(&after).all(|(b, a)| dot(*b, *a) > 0.0), "pass {pass}: turned inward");
            assert!((min - 35.264389682754654).abs() < 1e-9 && (max - 90.0).abs() < 1e-9, "pass {pass}: {min} {max}");
        }
    }
}
