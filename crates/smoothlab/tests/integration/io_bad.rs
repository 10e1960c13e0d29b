//! The malformed-input corpus (`tests/data/bad/`, one small file per failure mode, named
//! for it): each must be refused with a message that names its line or element and what
//! was expected. Nothing may panic: every corpus file also goes through every reader, and
//! random truncations and corruptions of the good fixtures go through theirs.

use std::collections::BTreeSet;
use std::path::PathBuf;

use proptest::prelude::*;
use smoothlab::io::{self, Format};

fn dir(sub: &str) -> PathBuf {
    crate::common::repo().join("tests/data").join(sub)
}

/// File (a Triangle pair by its stem) → the pieces its message must contain. Nodes and
/// elements are named as the file numbers them: VTK and OFF from 0, OBJ and Medit from 1,
/// Gmsh by tag, Triangle by the numbers it writes.
const EXPECTED: &[(&str, &[&str])] = &[
    // Gmsh
    ("truncated_nodes.msh", &["line 7", "ends here", "node 3 of the 3"]),
    ("huge_count.msh", &["line 5", "1000000000 nodes"]),
    ("quadratic_prism.msh", &["quadratic prisms (wedges) are not supported yet: line 24: Gmsh element type 18 (15-node prism); smoothlab reads"]),
    ("missing_elements.msh", &["line 9", "without an $Elements section"]),
    ("wrong_count.msh", &["line 8", "expected '$EndNodes'", "opened at line 4"]),
    ("undefined_node_tag.msh", &["element 1 (line 12)", "node tag 99 is not defined", "tags 1 to 3"]),
    ("duplicate_node_tag.msh", &["line 8", "node tag 2 is defined twice (first at line 7)"]),
    ("bad_number.msh", &["line 7", "y coordinate of node tag 2", "'0.0.0'"]),
    ("binary.msh", &["line 2", "binary .msh files are not supported"]),
    ("version1.msh", &["line 1", "version 1"]),
    ("block_count_mismatch.msh", &["line 18", "element 2 of the block at line 16", "'$EndElements'"]),
    ("repeated_node.msh", &["element 1 (line 12)", "node tag 2 appears twice"]),
    // issue 16: lines end at a lone CR too; a fixed set says nothing twice
    ("cr_only_bad_number.msh", &["line 7", "y coordinate of node tag 2", "'0.0.0'"]),
    ("fixed_node_twice.msh", &["line 24", "'fixed' view lists node tag 1 twice (first at line 22)"]),
    ("two_fixed_views.msh", &["line 24", "a second 'fixed' view (the first is at line 14)"]),
    // VTK
    ("index_out_of_range.vtk", &["element 0 (line 11)", "point index 9 is out of range", "0 to 3"]),
    ("polygon_cell.vtk", &["line 13", "polygons are not supported: element 0 at line 13 has 5 vertices"]),
    ("empty.vtk", &["empty mesh", "no nodes and no elements"]),
    ("inf_coordinate.vtk", &["line 7", "y coordinate of point 1", "finite", "'inf'"]),
    ("missing_cell_types.vtk", &["line 11", "without the CELL_TYPES section", "line 10"]),
    ("cell_types_count.vtk", &["line 13", "CELL_TYPES announces 1 types", "has 2 cells"]),
    ("wrong_node_count_for_type.vtk", &["element 0 (line 11)", "needs 4 points", "lists 3"]),
    ("voxel_cell.vtk", &["voxels (hexahedra numbered as a grid) are not supported yet: line 17: VTK cell type 11 (voxel) of element 0; smoothlab reads"]),
    ("truncated_points.vtk", &["line 8", "ends here", "z coordinate of point 2"]),
    ("bad_header.vtk", &["line 1", "# vtk DataFile Version"]),
    ("binary.vtk", &["line 3", "binary VTK files are not supported"]),
    ("huge_count.vtk", &["line 5", "1000000000 points"]),
    ("non_planar.vtk", &["not planar: node", "off the plane of the mesh", "times the size of its elements"]),
    ("point_data_count.vtk", &["line 14", "POINT_DATA announces 3 values", "4 points"]),
    ("bad_fixed_value.vtk", &["line 17", "'fixed' value of point 2", "'yes'"]),
    ("unknown_section.vtk", &["line 15", "expected a section", "'POLYGONS'"]),
    ("repeated_node.vtk", &["element 0 (line 10)", "point 2 appears twice"]),
    ("cr_only_inf_coordinate.vtk", &["line 7", "y coordinate of point 1", "'inf'"]),
    ("huge_coordinate.vtk", &["node 1 (line 7)", "coordinate 1.5e308 is too large to compute with", "1.1e307"]),
    ("two_fixed_arrays.vtk", &["line 17", "a second SCALARS fixed (the first is at line 14)"]),
    // OBJ
    ("nan_coordinate.obj", &["line 3", "vertex 2", "finite", "'nan'"]),
    ("polygon_face.obj", &["line 6", "5 vertices", "polygons are not supported"]),
    ("index_out_of_range.obj", &["element 1 (line 4)", "vertex index 9 is out of range", "1 to 3"]),
    ("relative_index_before_first.obj", &["line 4", "-4", "-1 to -3"]),
    ("index_zero.obj", &["line 3", "vertex index 0 is invalid"]),
    ("edge_in_three_faces.obj", &["element 3 (line 8)", "nodes 1 and 2 is shared by 3 elements (1, 2, 3)"]),
    ("no_elements.obj", &["empty mesh"]),
    ("not_utf8.obj", &["line 3", "not UTF-8", "byte 29 (0xe9)"]),
    ("repeated_node.obj", &["element 1 (line 4)", "vertex 3 appears twice"]),
    ("cr_only_nan_coordinate.obj", &["line 3", "vertex 2", "'nan'"]),
    ("non_planar_outlier.obj", &["not planar: node 9 (line 10) lies 1.000e6 off the plane", "7.071e5 times the size"]),
    // OFF
    ("repeated_node.off", &["element 0 (line 6)", "vertex 1 appears twice"]),
    ("cr_only_index_out_of_range.off", &["element 0 (line 6)", "vertex index 3 is out of range"]),
    ("wrong_count.off", &["line 2", "5 vertices", "ends after 4"]),
    ("index_out_of_range.off", &["element 0 (line 6)", "vertex index 3 is out of range", "0 to 2"]),
    ("huge_count.off", &["line 2", "2000000000 vertices"]),
    ("not_off.off", &["line 1", "expected 'OFF'", "'PLY'"]),
    ("extra_face.off", &["line 7", "after the 3 vertices and 1 faces"]),
    // Medit
    ("index_zero.mesh", &["line 10", "triangle 1: vertex index 0 is invalid: Medit counts from 1"]),
    ("index_out_of_range.mesh", &["line 10", "triangle 1: vertex index 9 is out of range", "1 to 3"]),
    ("repeated_node.mesh", &["line 10", "triangle 1: vertex 3 appears twice"]),
    ("huge_count.mesh", &["line 4", "1000000000 vertices"]),
    ("unknown_section.mesh", &["line 8", "Medit section 'Identifier' is not known", "cannot be skipped"]),
    ("quadratic_triangles.mesh", &["quadratic triangles (Medit's TrianglesP2) are not supported yet: line 11"]),
    ("truncated_vertices.mesh", &["line 6", "ends here", "x coordinate of vertex 3"]),
    ("wrong_count.mesh", &["line 13", "the reference of triangle 2", "'Quadrilaterals'"]),
    // Triangle pairs
    ("triangle_out_of_range", &["element 2 (line 3)", "node 5 is out of range", "1 to 4", ".ele"]),
    ("triangle_not_consecutive", &["line 4", "consecutive: expected 3, found 4", ".node file"]),
    ("triangle_quads", &["line 1", "4 nodes are not supported", ".ele file"]),
    ("triangle_repeated_node", &["element 1 (line 2)", "node 3 appears twice", ".ele"]),
];

/// Errors that are about the whole mesh rather than a place in the file.
fn whole_mesh(msg: &str) -> bool {
    msg.starts_with("empty mesh") || msg.contains("not planar")
}

#[test]
fn every_bad_file_is_refused_naming_where_and_what() {
    let bad = dir("bad");
    let mut on_disk = BTreeSet::new();
    for e in std::fs::read_dir(&bad).unwrap() {
        let name = e.unwrap().file_name().to_string_lossy().into_owned();
        let key = match name.rsplit_once('.') {
            Some((stem, "node" | "ele")) => stem.to_string(),
            _ => name,
        };
        on_disk.insert(key);
    }
    let listed: BTreeSet<String> = EXPECTED.iter().map(|(f, _)| f.to_string()).collect();
    assert_eq!(on_disk, listed, "every corpus file needs an expectation here, and every expectation a file");

    for (file, wants) in EXPECTED {
        let is_pair = !file.contains('.');
        let msg = if is_pair {
            // either file of the pair reads both
            let a = io::read_path(&bad.join(format!("{file}.node"))).unwrap_err().to_string();
            let b = io::read_path(&bad.join(format!("{file}.ele"))).unwrap_err().to_string();
            assert_eq!(a, b, "{file}");
            a
        } else {
            let path = bad.join(file);
            let by_path = io::read_path(&path).map(|_| ()).unwrap_err().to_string();
            // the page's way in: bytes and a name
            let bytes = std::fs::read(&path).unwrap();
            let by_bytes = io::read_bytes(&bytes, file).map(|_| ()).unwrap_err().to_string();
            assert_eq!(by_path, by_bytes, "{file}");
            by_path
        };
        for w in *wants {
            assert!(msg.contains(w), "{file}: message lacks {w:?}: {msg}");
        }
        // an element kind smoothlab does not read is said first in plain words, then where
        let at = msg.split_once(" are not supported yet: ").map_or(msg.as_str(), |(_, rest)| rest);
        let placed = at.starts_with("line ") || at.starts_with("element ") || at.starts_with("node ");
        assert!(placed || whole_mesh(&msg), "{file}: message names no line or element: {msg}");
    }
}

const FORMATS: [Format; 5] = [Format::Msh, Format::Vtk, Format::Obj, Format::Off, Format::Medit];

#[test]
fn every_file_through_every_reader_never_panics() {
    let mut texts = Vec::new();
    for sub in ["bad", ""] {
        for e in std::fs::read_dir(dir(sub)).unwrap() {
            let p = e.unwrap().path();
            if p.is_file() {
                texts.push(String::from_utf8_lossy(&std::fs::read(&p).unwrap()).into_owned());
            }
        }
    }
    for t in &texts {
        for f in FORMATS {
            let _ = io::read_str(t, f);
        }
        let _ = io::read_triangle(t, t);
    }
}

fn good_fixtures() -> Vec<(String, Format)> {
    [
        "grid_lines.msh",
        "sparse_blocks.msh",
        "wrapped.vtk",
        "offsets_tri6.vtk",
        "polydata.vtk",
        "relative.obj",
        "three_tris.off",
        "two_quads_one_triangle.mesh",
    ]
        .iter()
        .map(|n| (std::fs::read_to_string(dir("").join(n)).unwrap(), Format::from_name(n).unwrap()))
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    /// Cut anywhere: refused with a message naming a line, or (cut between sections) read.
    #[test]
    fn truncated_fixtures_fail_cleanly(which in 0usize..8, cut in 0.0f64..1.0) {
        let (text, format) = &good_fixtures()[which];
        let mut at = (cut * text.len() as f64) as usize;
        while !text.is_char_boundary(at) {
            at -= 1;
        }
        if let Err(e) = io::read_str(&text[..at], *format) {
            let msg = e.to_string();
            prop_assert!(msg.starts_with("line ") || msg.starts_with("element ") || msg.starts_with("node ") || whole_mesh(&msg), "{}", msg);
        }
    }

    /// One token replaced by something else: never a panic.
    #[test]
    fn corrupted_tokens_never_panic(
        which in 0usize..8,
        pick in 0.0f64..1.0,
        with in prop::sample::select(vec!["-1", "0", "4294967295", "18446744073709551615", "1e308", "nan", "-inf", "x", "$Nodes", "CELLS", "7", "99999999999", ""]),
    ) {
        let (text, format) = &good_fixtures()[which];
        let tokens: Vec<&str> = text.split_whitespace().collect();
        let k = ((pick * tokens.len() as f64) as usize).min(tokens.len() - 1);
        let mut seen = 0;
        let mut out = String::new();
        for line in text.lines() {
            let mut parts = Vec::new();
            for t in line.split_whitespace() {
                parts.push(if seen == k { with } else { t });
                seen += 1;
            }
            out += &parts.join(" ");
            out.push('\n');
        }
        let _ = io::read_str(&out, *format);
    }
}

/// Issue 61, finding 5: one triangle listed 200,000 times once gave a message of 1.49 MB,
/// every element sharing the edge listed. A message lists the first few and a count.
#[test]
fn a_message_lists_the_first_few_and_a_count_whatever_the_file() {
    let n = 200_000;
    let mut vtk = String::from("# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 3 double\n");
    vtk += "0 0 0\n1 0 0\n0 1 0\n";
    vtk += &format!("CELLS {n} {}\n", 4 * n);
    vtk += &"3 0 1 2\n".repeat(n);
    vtk += &format!("CELL_TYPES {n}\n");
    vtk += &"5\n".repeat(n);
    let msg = io::read_model_str(&vtk, Format::Vtk).unwrap_err().to_string();
    assert!(msg.len() < 300, "{} bytes: {}", msg.len(), &msg[..msg.len().min(600)]);
    assert!(msg.contains(&format!("shared by {n} elements (0, 1, 2, 3, 4 and {} more)", n - 5)), "{msg}");
    // the same in volumes: a tetrahedron listed 1,000 times
    let k = 1000;
    let mut vtk = String::from("# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n");
    vtk += "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
    vtk += &format!("CELLS {k} {}\n", 5 * k);
    vtk += &"4 0 1 2 3\n".repeat(k);
    vtk += &format!("CELL_TYPES {k}\n");
    vtk += &"10\n".repeat(k);
    let msg = io::read_model_str(&vtk, Format::Vtk).unwrap_err().to_string();
    assert!(msg.len() < 300, "{} bytes: {msg}", msg.len());
    assert!(msg.contains(&format!("is a face of {k} elements (0, 1, 2, 3, 4 and {} more", k - 5)), "{msg}");
}

/// Issue 61, finding 6: an edge shared by three triangles was reported as "nodes 4 and 5"
/// for a VTK file whose indices are 3 and 4 and a Gmsh file whose tags are 40 and 50.
/// Every message names nodes and elements as the file numbers them.
#[test]
fn messages_name_nodes_and_elements_as_the_file_numbers_them() {
    let points = ["0.5 1 0", "0.5 -1 0", "0.5 2 0", "0 0 0", "1 0 0", "3 3 0"];
    let tris = [[3, 4, 0], [3, 4, 1], [4, 3, 2]];
    let mut vtk = String::from("# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 6 double\n");
    for p in points {
        vtk += &format!("{p}\n");
    }
    vtk += "CELLS 3 12\n";
    for t in tris {
        vtk += &format!("3 {} {} {}\n", t[0], t[1], t[2]);
    }
    vtk += "CELL_TYPES 3\n5\n5\n5\n";
    let msg = io::read_model_str(&vtk, Format::Vtk).unwrap_err().to_string();
    assert!(msg.starts_with("element 2 (line 15): edge between nodes 3 and 4 is shared by 3 elements (0, 1, 2)"), "{msg}");

    let tag = |i: usize| 10 * (i + 1);
    let mut msh = String::from("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n6\n");
    for (i, p) in points.iter().enumerate() {
        msh += &format!("{} {p}\n", tag(i));
    }
    msh += "$EndNodes\n$Elements\n3\n";
    for (e, t) in tris.iter().enumerate() {
        msh += &format!("{} 2 0 {} {} {}\n", 7 + e, tag(t[0]), tag(t[1]), tag(t[2]));
    }
    msh += "$EndElements\n";
    let msg = io::read_model_str(&msh, Format::Msh).unwrap_err().to_string();
    assert!(msg.starts_with("element 9 (line 17): edge between nodes 40 and 50 is shared by 3 elements (7, 8, 9)"), "{msg}");

    let mut medit = String::from("MeshVersionFormatted 2\nDimension 3\nVertices\n6\n");
    for p in points {
        medit += &format!("{p} 0\n");
    }
    medit += "Triangles\n3\n";
    for t in tris {
        medit += &format!("{} {} {} 0\n", t[0] + 1, t[1] + 1, t[2] + 1);
    }
    medit += "End\n";
    let msg = io::read_model_str(&medit, Format::Medit).unwrap_err().to_string();
    assert!(msg.starts_with("element 3 (line 15): edge between nodes 4 and 5 is shared by 3 elements (1, 2, 3)"), "{msg}");

    // volumes too: node and element tags of a Gmsh file, a face of three tetrahedra
    let mut msh = String::from("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n6\n");
    for (i, p) in ["0 0 0", "1 0 0", "0 1 0", "0 0 1", "0 0 -1", "1 1 1"].iter().enumerate() {
        msh += &format!("{} {p}\n", tag(i));
    }
    msh += "$EndNodes\n$Elements\n3\n";
    for (e, t) in [[0, 1, 2, 3], [0, 2, 1, 4], [0, 1, 2, 5]].iter().enumerate() {
        msh += &format!("{} 4 0 {} {} {} {}\n", 101 + e, tag(t[0]), tag(t[1]), tag(t[2]), tag(t[3]));
    }
    msh += "$EndElements\n";
    let msg = io::read_model_str(&msh, Format::Msh).unwrap_err().to_string();
    assert!(msg.contains("its face [10, 20, 30] is a face of 3 elements (101, 102, 103"), "{msg}");
    assert!(msg.starts_with("element 103 (line 17)"), "{msg}");
    // a node whose coordinate cannot be computed with, by its tag
    let huge = msh.replacen("60 1 1 1", "60 1e308 1 1", 1);
    let msg = io::read_model_str(&huge, Format::Msh).unwrap_err().to_string();
    assert!(msg.starts_with("node 60 (line 11)"), "{msg}");
}
