//! Each reader against small hand-written fixtures (`tests/data/`) with hand-checked
//! counts, coordinates and connectivity; 3D input in planes; and the API's choices of
//! format by name.

use std::path::PathBuf;

use glam::DVec2;
use smoothlab::io::{self, Format};
use smoothlab::mesh::MeshBuilder;
use smoothlab::{ElementKind, Error, Mesh};

fn data(name: &str) -> PathBuf {
    crate::common::repo().join("tests/data").join(name)
}

fn read(name: &str) -> Mesh {
    let m = io::read_path(&data(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
    m.sanity_check().unwrap_or_else(|e| panic!("{name}: {e}"));
    m
}

fn total_area(m: &Mesh) -> f64 {
    (0..m.element_count()).map(|e| m.corner_area(e)).sum()
}

fn p(x: f64, y: f64) -> DVec2 {
    DVec2::new(x, y)
}

fn elements(m: &Mesh) -> Vec<Vec<u32>> {
    (0..m.element_count()).map(|e| m.element(e).to_vec()).collect()
}

#[test]
fn msh22_with_sparse_tags_skipped_sections_and_marker_lines() {
    let m = read("grid_lines.msh");
    assert_eq!((m.node_count(), m.element_count()), (9, 4));
    assert!(m.kinds().iter().all(|&k| k == ElementKind::Quad4));
    // tags 10, 20, … 90 → indices 0 … 8 in file order
    assert_eq!(m.nodes()[4], p(1.0, 1.0));
    assert_eq!(m.nodes()[8], p(2.0, 2.0));
    assert_eq!(m.element(0), &[0, 1, 4, 3]);
    assert!((total_area(&m) - 4.0).abs() < 1e-15);
    // the centre is interior, and fixed only because the line element 20-50 marks it
    assert!(!m.is_boundary(4));
    assert!(m.fixed().iter().all(|&f| f));

    // the same file without that line: the centre is free
    let text = std::fs::read_to_string(data("grid_lines.msh")).unwrap();
    let text = text.replace("7\n1 1 2", "6\n1 1 2").replace("3 1 2 1 3 20 50\n", "");
    let m = io::read_str(&text, Format::Msh).unwrap();
    assert_eq!(m.fixed().iter().filter(|&&f| !f).count(), 1);
    assert!(!m.fixed()[4]);
}

#[test]
fn msh41_with_several_blocks_parametric_nodes_and_huge_tags() {
    let m = read("sparse_blocks.msh");
    assert_eq!((m.node_count(), m.element_count()), (9, 6));
    // node order is the order of appearance across blocks
    let want = [p(0., 0.), p(2., 0.), p(0., 2.), p(2., 2.), p(1., 0.), p(2., 1.), p(1., 2.), p(0., 1.), p(1., 1.)];
    assert_eq!(m.nodes(), want);
    use ElementKind::*;
    assert_eq!(m.kinds(), &[Quad4, Quad4, Tri3, Tri3, Tri3, Tri3]);
    assert_eq!(
        elements(&m),
        vec![vec![0, 4, 8, 7], vec![7, 8, 6, 2], vec![4, 1, 5], vec![4, 5, 8], vec![8, 5, 3], vec![8, 3, 6]]
    );
    assert!((total_area(&m) - 4.0).abs() < 1e-15);
    // node 8 (tag 56) is interior and fixed by the point element
    assert!(!m.is_boundary(8) && m.fixed()[8]);
}

#[test]
fn vtk_wrapped_data_skipped_attributes_and_exact_fixed_flags() {
    let m = read("wrapped.vtk");
    assert_eq!((m.node_count(), m.element_count()), (6, 3));
    assert_eq!(m.kinds(), &[ElementKind::Quad4, ElementKind::Tri3, ElementKind::Tri3]);
    assert_eq!(m.nodes()[5], p(2.0, 1.0));
    assert_eq!(elements(&m), vec![vec![0, 1, 4, 3], vec![1, 2, 5], vec![1, 5, 4]]);
    assert!((total_area(&m) - 2.0).abs() < 1e-15);
    // exactly as the file says, although nodes 1, 4 and 5 are on the boundary
    assert_eq!(m.fixed(), vec![true, false, true, true, false, false]);
}

#[test]
fn vtk_51_offsets_layout_with_metadata_and_quadratic_triangles() {
    let m = read("offsets_tri6.vtk");
    assert_eq!((m.node_count(), m.element_count()), (9, 2));
    assert_eq!(m.kinds(), &[ElementKind::Tri6, ElementKind::Tri6]);
    assert_eq!(elements(&m), vec![vec![0, 1, 2, 4, 5, 6], vec![0, 2, 3, 6, 7, 8]]);
    assert!((total_area(&m) - 4.0).abs() < 1e-15);
    // no fixed data: the boundary, mid-nodes included; the diagonal's mid-node is free
    let free: Vec<usize> = (0..9).filter(|&i| !m.fixed()[i]).collect();
    assert_eq!(free, vec![6]);
}

#[test]
fn vtk_polydata_polygons() {
    let m = read("polydata.vtk");
    assert_eq!(m.kinds(), &[ElementKind::Quad4, ElementKind::Tri3]);
    assert!((total_area(&m) - 1.5).abs() < 1e-15);
}

#[test]
fn triangle_o2_mid_nodes_are_remapped_onto_their_edges() {
    let m = read("square_o2.node");
    assert_eq!((m.node_count(), m.element_count()), (9, 2));
    assert!(m.kinds().iter().all(|&k| k == ElementKind::Tri6));
    for e in 0..2 {
        let ids = m.element(e);
        for i in 0..3 {
            let (a, b) = (m.nodes()[ids[i] as usize], m.nodes()[ids[(i + 1) % 3] as usize]);
            assert_eq!(m.nodes()[ids[3 + i] as usize], 0.5 * (a + b), "element {e}, edge {i}");
        }
    }
    // 1-based file numbers → 0-based indices: element 1 is nodes 1 2 3 | 7 6 5
    assert_eq!(m.element(0), &[0, 1, 2, 6, 5, 4]);
    // reading the .ele names the same pair
    assert_eq!(elements(&read("square_o2.ele")), elements(&m));
    assert!(m.edges().iter().all(|e| !e.curved));
}

#[test]
fn triangle_zero_based_with_attributes_and_a_marked_interior_node() {
    let node = "5 2 1 1\n0 0 0 7.5 1\n1 2 0 7.5 1\n2 2 2 7.5 1\n3 0 2 7.5 1\n4 1 1 7.5 5 # marked\n";
    let ele = "4 3 1\n0 0 1 4 0.0\n1 1 2 4 0.0\n2 2 3 4 0.0\n3 3 0 4 0.0\n";
    let m = io::read_triangle(node, ele).unwrap();
    assert_eq!(m.element(0), &[0, 1, 4]);
    assert!(!m.is_boundary(4) && m.fixed()[4]);
    let unmarked = node.replace("7.5 5 #", "7.5 0 #");
    assert!(!io::read_triangle(&unmarked, ele).unwrap().fixed()[4]);
}

#[test]
fn obj_relative_indices_and_slash_forms() {
    let m = read("relative.obj");
    assert_eq!((m.node_count(), m.element_count()), (6, 3));
    assert_eq!(elements(&m), vec![vec![0, 1, 2], vec![0, 2, 3], vec![1, 4, 5, 2]]);
    assert_eq!(m.kinds(), &[ElementKind::Tri3, ElementKind::Tri3, ElementKind::Quad4]);
    assert!((total_area(&m) - 2.0).abs() < 1e-15);
}

#[test]
fn off_with_comments_and_face_colours() {
    let m = read("three_tris.off");
    assert_eq!((m.node_count(), m.element_count()), (5, 3));
    assert_eq!(elements(&m), vec![vec![0, 1, 2], vec![0, 2, 3], vec![1, 4, 2]]);
    assert!((total_area(&m) - 1.5).abs() < 1e-15);
    // the counts may share the OFF line
    let t = std::fs::read_to_string(data("three_tris.off")).unwrap().replacen("OFF\n# a comment line\n5 3 0", "OFF 5 3 0", 1);
    assert_eq!(elements(&io::read_str(&t, Format::Off).unwrap()), elements(&m));
}

/// A 2 × 1 quad strip in VTK with the given 3D points.
fn vtk_strip(points: &[[f64; 3]; 6], clockwise: bool) -> String {
    let mut s = String::from("# vtk DataFile Version 3.0\nstrip\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 6 double\n");
    for q in points {
        s += &format!("{:?} {:?} {:?}\n", q[0], q[1], q[2]);
    }
    s += if clockwise { "CELLS 2 10\n4 0 3 4 1\n4 1 4 5 2\n" } else { "CELLS 2 10\n4 0 1 4 3\n4 1 2 5 4\n" };
    s + "CELL_TYPES 2\n9\n9\n"
}

/// The strip's points (x in 0, 1, 2; y in 0, 1) through a map to 3D.
fn strip(f: impl Fn(f64, f64) -> [f64; 3]) -> [[f64; 3]; 6] {
    [f(0., 0.), f(1., 0.), f(2., 0.), f(0., 1.), f(1., 1.), f(2., 1.)]
}

#[test]
fn planar_3d_input_is_mapped_and_oriented_counter_clockwise() {
    // z = 5, counter-clockwise: kept as x, y
    let m = io::read_str(&vtk_strip(&strip(|x, y| [x, y, 5.0]), false), Format::Vtk).unwrap();
    assert_eq!(m.nodes()[4], p(1.0, 1.0));
    // z = -5 facing down (clockwise seen from +z): every element comes out CCW
    let m = io::read_str(&vtk_strip(&strip(|x, y| [x, y, -5.0]), true), Format::Vtk).unwrap();
    for e in 0..2 {
        assert!((m.corner_area(e) - 1.0).abs() < 1e-15, "element {e}: {}", m.corner_area(e));
    }
    // a tilted plane, facing either way: true areas, counter-clockwise
    let (s, c) = (35f64.to_radians().sin(), 35f64.to_radians().cos());
    for clockwise in [false, true] {
        let m = io::read_str(&vtk_strip(&strip(|x, y| [x * c, y, 3.0 + x * s]), clockwise), Format::Vtk).unwrap();
        for e in 0..2 {
            assert!((m.corner_area(e) - 1.0).abs() < 1e-12, "element {e}: {}", m.corner_area(e));
        }
        assert!((m.nodes()[0].distance(m.nodes()[2]) - 2.0).abs() < 1e-12, "lengths are kept");
    }
    // the plane y = -5
    let m = io::read_str(&vtk_strip(&strip(|x, y| [x, -5.0, y]), false), Format::Vtk).unwrap();
    assert!((total_area(&m) - 2.0).abs() < 1e-12);
}

#[test]
fn non_planar_input_is_refused_saying_how_far_off() {
    let bent = strip(|x, y| [x, y, if x == 2.0 && y == 1.0 { 0.4 } else { 0.0 }]);
    let e = io::read_str(&vtk_strip(&bent, false), Format::Vtk).unwrap_err();
    let Error::NotPlanar { max_distance, .. } = e else { panic!("{e:?}") };
    // the plane is the one of the other nodes (one bent node no longer tilts it)
    assert!((max_distance - 0.4).abs() < 1e-12, "{max_distance}");
    let msg = e.to_string();
    assert!(msg.contains("not planar") && msg.contains("lies 0.4 off"), "{msg}");
}

#[test]
fn formats_by_name_and_pairs() {
    let bytes = std::fs::read(data("relative.obj")).unwrap();
    assert_eq!(io::read_bytes(&bytes, "upload.OBJ").unwrap().element_count(), 3);
    let e = io::read_bytes(&bytes, "mesh.stl").unwrap_err().to_string();
    assert!(e.contains("mesh.stl") && e.contains(".msh"), "{e}");
    let node = std::fs::read(data("square_o2.node")).unwrap();
    for e in [io::read_bytes(&node, "square_o2.node").unwrap_err(), io::read_str("", Format::Triangle).unwrap_err()] {
        assert!(e.to_string().contains(".node/.ele pair"), "{e}");
    }
}

#[test]
fn writers_refuse_what_their_format_cannot_hold() {
    let quadratic = read("offsets_tri6.vtk");
    for f in [Format::Obj, Format::Off] {
        let e = io::write_string(&quadratic, f, &Default::default()).unwrap_err().to_string();
        assert!(e.contains("6-node triangle") && e.contains("linear"), "{e}");
    }
    let quads = read("grid_lines.msh");
    let e = io::write_triangle(&quads).unwrap_err().to_string();
    assert!(e.contains("4-node quad"), "{e}");
    let e = io::write_string(&quads, Format::Triangle, &Default::default()).unwrap_err().to_string();
    assert!(e.contains("write_triangle"), "{e}");
}

#[test]
fn unused_nodes_are_kept_and_fixed() {
    let mut b = MeshBuilder::new();
    for q in [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [9.0, 9.0, 0.0], [0.0, 1.0, 0.0]] {
        b.add_node(q, 0);
    }
    b.add_element(ElementKind::Tri3, &[0, 1, 3], 0);
    let m = b.build().unwrap();
    let text = io::write_string(&m, Format::Off, &Default::default()).unwrap();
    let back = io::read_str(&text, Format::Off).unwrap();
    assert_eq!(back.nodes(), m.nodes());
    assert!(back.fixed()[2]);
}

#[test]
fn files_stream_the_same_bytes_and_refusals_make_no_file() {
    // write_path hands the text to the file in chunks: the bytes must be write_string's
    let big = smoothlab::generate::rand2d(3000, 20, 5).unwrap(); // a text of several chunks
    let dir = std::env::temp_dir().join(format!("smoothlab-io-stream-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, format) in [("m.msh", Format::Msh), ("m.vtk", Format::Vtk), ("m.obj", Format::Obj), ("m.off", Format::Off)] {
        let path = dir.join(name);
        io::write_path(&big, &path, &Default::default()).unwrap();
        let text = io::write_string(&big, format, &Default::default()).unwrap();
        assert!(text.len() > 1 << 17, "{name}: {} bytes", text.len());
        assert_eq!(std::fs::read(&path).unwrap(), text.as_bytes(), "{name}");
    }
    io::write_path(&big, &dir.join("m.node"), &Default::default()).unwrap();
    let (node, ele) = io::write_triangle(&big).unwrap();
    assert_eq!(std::fs::read(dir.join("m.node")).unwrap(), node.as_bytes());
    assert_eq!(std::fs::read(dir.join("m.ele")).unwrap(), ele.as_bytes());
    // what a format cannot hold is refused before any file is made
    let quadratic = read("offsets_tri6.vtk");
    for name in ["q.obj", "q.off"] {
        assert!(io::write_path(&quadratic, &dir.join(name), &Default::default()).is_err());
        assert!(!dir.join(name).exists(), "{name}");
    }
    let quads = read("grid_lines.msh");
    assert!(io::write_path(&quads, &dir.join("q.node"), &Default::default()).is_err());
    assert!(!dir.join("q.node").exists() && !dir.join("q.ele").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn medit_fixture_reads_its_sections_in_their_order() {
    // comments, a count on the next line, quads before triangles, Corners fixing a node
    let m = read("two_quads_one_triangle.mesh");
    assert_eq!((m.node_count(), m.kinds()), (7, &[ElementKind::Quad4, ElementKind::Quad4, ElementKind::Tri3][..]));
    assert_eq!(m.element_as_given(2).to_vec(), vec![2, 6, 5]);
    assert!(m.nodes().iter().all(|p| p.x.fract() == 0.0 || p.x == 3.0), "the references are not coordinates");
    assert_eq!(m.fixed().iter().filter(|&&f| f).count(), 7, "every node is on the boundary");
}
