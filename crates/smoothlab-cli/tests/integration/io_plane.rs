//! A mesh read from points in a 3D plane (not z = 0) is written back in that plane, by
//! every 3D format and by `smoothlab convert`; Triangle's 2D `.node` says why it cannot.

use std::process::Command;

use glam::{DVec2, DVec3};
use smoothlab::io::{self, Format, MshVersion, WriteOptions};

/// A 3 × 3 grid of quads split into triangles, in the plane through `o` along `a`, `b`
/// (not orthonormal: the reader finds its own axes), as an OBJ file.
fn tilted_obj(o: DVec3, a: DVec3, b: DVec3) -> (String, Vec<DVec3>) {
    let mut pts = Vec::new();
    let mut s = String::new();
    for j in 0..4 {
        for i in 0..4 {
            let jitter = if (1..3).contains(&i) && (1..3).contains(&j) { 0.13 * ((i * 7 + j * 3) % 5) as f64 / 5.0 } else { 0.0 };
            let p = o + a * (i as f64 + jitter) + b * (j as f64 - jitter);
            s.push_str(&format!("v {:?} {:?} {:?}\n", p.x, p.y, p.z));
            pts.push(p);
        }
    }
    for j in 0..3 {
        for i in 0..3 {
            let k = j * 4 + i + 1;
            s.push_str(&format!("f {} {} {}\nf {} {} {}\n", k, k + 1, k + 5, k, k + 5, k + 4));
        }
    }
    (s, pts)
}

/// The 3D points a written file holds, in node order (the formats here all write `x y z`
/// per node line, Medit with a reference after it; the test reads them the simple way).
fn points_of(text: &str, format: Format) -> Vec<DVec3> {
    let lines: Vec<&str> = text.lines().collect();
    let xyz = |l: &str| {
        let v: Vec<f64> = l.split_whitespace().map(|t| t.parse().unwrap()).collect();
        DVec3::new(v[v.len() - 3], v[v.len() - 2], v[v.len() - 1])
    };
    match format {
        Format::Obj => lines.iter().filter(|l| l.starts_with("v ")).map(|l| xyz(&l[2..])).collect(),
        Format::Off => lines[2..18].iter().map(|l| xyz(l)).collect(),
        Format::Vtk => {
            let at = lines.iter().position(|l| l.starts_with("POINTS")).unwrap();
            lines[at + 1..at + 17].iter().map(|l| xyz(l)).collect()
        }
        Format::Msh => {
            let at = lines.iter().position(|l| *l == "$Nodes").unwrap();
            lines[at + 2..at + 18].iter().map(|l| xyz(l)).collect()
        }
        Format::Medit => {
            // `x y z ref`: the reference last
            let at = lines.iter().position(|l| *l == "Vertices").unwrap();
            lines[at + 2..at + 18].iter().map(|l| xyz(l.rsplit_once(' ').unwrap().0)).collect()
        }
        Format::Triangle => unreachable!(),
    }
}

const TOL: f64 = 1e-12;

#[test]
fn every_3d_format_writes_the_mesh_back_in_its_own_plane() {
    let (o, a, b) = (DVec3::new(1.0, -2.0, 3.0), DVec3::new(0.6, 0.0, 0.8), DVec3::new(0.0, 1.0, 0.3));
    let (obj, pts) = tilted_obj(o, a, b);
    let mesh = io::read_str(&obj, Format::Obj).unwrap();
    let plane = mesh.plane.expect("the mesh keeps its plane");
    assert!(plane.u.dot(plane.w).abs() < TOL && (plane.u.length() - 1.0).abs() < TOL);
    for (i, p) in pts.iter().enumerate() {
        assert!(mesh.to_3d(mesh.nodes()[i]).distance(*p) < TOL, "node {i}");
    }
    let normal = a.cross(b).normalize();
    for format in [Format::Obj, Format::Off, Format::Vtk, Format::Msh, Format::Medit] {
        let text = io::write_string(&mesh, format, &WriteOptions::default()).unwrap();
        let back = points_of(&text, format);
        assert_eq!(back.len(), pts.len(), "{format:?}");
        for (i, (q, p)) in back.iter().zip(&pts).enumerate() {
            assert!(q.distance(*p) < TOL, "{format:?} node {i}: wrote {q}, read {p}");
        }
        // a smoothed node moves within the plane
        let mut moved = mesh.clone();
        moved.nodes_mut()[5] += DVec2::new(0.05, -0.02);
        let q = points_of(&io::write_string(&moved, format, &WriteOptions::default()).unwrap(), format)[5];
        assert!((q - o).dot(normal).abs() < TOL, "{format:?}: the moved node left the plane");
        assert!(q.distance(pts[5]) > 0.04);
        // and reads back as the same 2D mesh
        let again = io::read_str(&text, format).unwrap();
        for (q, p) in again.nodes().iter().zip(&pts) {
            assert!(again.to_3d(*q).distance(*p) < TOL);
        }
    }
    let v41 = io::write_string(&mesh, Format::Msh, &WriteOptions { msh_version: MshVersion::V41 }).unwrap();
    assert!(io::read_str(&v41, Format::Msh).unwrap().plane.is_some());
}

#[test]
fn a_mesh_at_constant_z_keeps_its_z_and_one_at_zero_is_written_as_before() {
    let (obj, _) = tilted_obj(DVec3::new(0.0, 0.0, 5.5), DVec3::X, DVec3::Y);
    let mesh = io::read_str(&obj, Format::Obj).unwrap();
    let text = io::write_string(&mesh, Format::Vtk, &WriteOptions::default()).unwrap();
    assert!(points_of(&text, Format::Vtk).iter().all(|p| p.z == 5.5));
    let (flat, _) = tilted_obj(DVec3::ZERO, DVec3::X, DVec3::Y);
    let mesh = io::read_str(&flat, Format::Obj).unwrap();
    assert!(mesh.plane.is_none());
    assert!(io::write_string(&mesh, Format::Obj, &WriteOptions::default()).unwrap().contains("v 0.0 0.0 0\n"));
}

#[test]
fn convert_keeps_the_plane_and_says_why_a_node_file_cannot() {
    let dir = std::env::temp_dir().join(format!("smoothlab-plane-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (o, a, b) = (DVec3::new(0.0, 0.0, 2.0), DVec3::new(0.0, 1.0, 0.0), DVec3::new(0.0, 0.0, 1.0));
    let (obj, pts) = tilted_obj(o, a, b);
    let input = dir.join("wall.obj");
    std::fs::write(&input, obj).unwrap();
    let bin = env!("CARGO_BIN_EXE_smoothlab");
    let out = dir.join("wall.vtk");
    let r = Command::new(bin).arg("convert").arg(&input).arg(&out).output().unwrap();
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let back = points_of(&std::fs::read_to_string(&out).unwrap(), Format::Vtk);
    for (q, p) in back.iter().zip(&pts) {
        assert!(q.distance(*p) < TOL, "{q} vs {p}: the wall x = 0 was flattened");
    }
    let node = dir.join("wall.node");
    let r = Command::new(bin).arg("convert").arg(&input).arg(&node).output().unwrap();
    assert!(r.status.success());
    let err = String::from_utf8_lossy(&r.stderr);
    assert!(err.contains("3D plane") && err.contains("2D points"), "{err}");
    assert!(std::fs::read_to_string(&node).unwrap().contains("# the mesh lay in a 3D plane"));
    std::fs::remove_dir_all(&dir).ok();
}

/// Issue 29: in a tilted plane the fixed nodes came back a rounding off (the plane's
/// rotation there and back), so `smooth --strategy smart` moved 15 of 16 fixed nodes and
/// `convert` changed 24 of 25. A node where it was read is written as the file gave it,
/// to the bit, by every 3D format, also after smoothing (the fixed nodes).
#[test]
fn nodes_that_did_not_move_are_written_back_to_the_bit_in_a_tilted_plane() {
    let (o, a, b) = (DVec3::new(0.1, 0.2, 0.3), DVec3::new(0.6, 0.0, 0.8), DVec3::new(0.0, 1.0, 0.3));
    let (obj, pts) = tilted_obj(o, a, b);
    let mesh = io::read_str(&obj, Format::Obj).unwrap();
    let mut smoothed = mesh.clone();
    let objective = smoothlab::objective::objective(smoothlab::objective::ObjectiveKind::SmoothShape);
    let opts = smoothlab::smooth::SmoothOptions::default().with_strategy(smoothlab::smooth::Strategy::Smart);
    smoothlab::smooth::smooth(&mut smoothed, objective.as_ref(), opts, 2, &|| 0.0).unwrap();
    let moved = (0..mesh.node_count()).filter(|&i| smoothed.nodes()[i] != mesh.nodes()[i]).count();
    assert!(moved > 0, "the smart Laplacian moves a jittered node");
    for format in [Format::Obj, Format::Off, Format::Vtk, Format::Msh] {
        let back = points_of(&io::write_string(&mesh, format, &WriteOptions::default()).unwrap(), format);
        assert_eq!(back, pts, "{format:?}: converted");
        let back = points_of(&io::write_string(&smoothed, format, &WriteOptions::default()).unwrap(), format);
        for i in (0..pts.len()).filter(|&i| mesh.is_fixed(i)) {
            assert_eq!(back[i], pts[i], "{format:?}: fixed node {i}");
        }
    }
}

/// Issue 29: the writers re-oriented what the readers oriented (a clockwise planar mesh,
/// surface faces against their neighbours). Each element is written in its file's order.
#[test]
fn elements_are_written_in_the_order_their_file_gave() {
    let faces = |text: &str| -> Vec<Vec<u32>> {
        text.lines().filter(|l| l.starts_with("f ")).map(|l| l[2..].split_whitespace().map(|t| t.parse().unwrap()).collect()).collect()
    };
    // the tilted grid clockwise, and a tetrahedron's surface with one face turned
    let (ccw, _) = tilted_obj(DVec3::ZERO, DVec3::X, DVec3::Y);
    let cw: String = ccw
        .lines()
        .map(|l| match l.strip_prefix("f ") {
            Some(f) => format!("f {}\n", f.split_whitespace().rev().collect::<Vec<_>>().join(" ")),
            None => format!("{l}\n"),
        })
        .collect();
    let tet = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\nf 1 2 3\n".replace("f 1 2 3\n", "");
    let turned = tet.replace("f 2 3 4", "f 2 4 3");
    for text in [cw, turned] {
        let given = faces(&text);
        for format in [Format::Obj, Format::Vtk, Format::Msh] {
            let model = io::read_model_str(&text, Format::Obj).unwrap();
            let written = io::write_model_string(&model, format, &WriteOptions::default()).unwrap();
            let back = io::read_model_str(&written, format).unwrap();
            let again = faces(&io::write_model_string(&back, Format::Obj, &WriteOptions::default()).unwrap());
            assert_eq!(again, given, "{format:?}");
        }
    }
}
