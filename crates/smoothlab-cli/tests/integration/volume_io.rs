//! Tetrahedral meshes in files and on the command line: every format round-trips
//! (`.msh` 2.2 and 4.1, `.vtk`, TetGen `.node`/`.ele`; 4- and 10-node), Gmsh's and
//! TetGen's node orders are read as they are written by those tools, bad files are refused
//! naming the line or element, and `generate cube`, `perturb`, `stats`, `smooth`,
//! `convert` and `render` work on tetrahedra.

use std::path::PathBuf;

use serde_json::Value;
use smoothlab::io::{self, Format, MshVersion, WriteOptions};
use smoothlab::model::Model;
use smoothlab::volume::VolumeMesh;
use crate::common::{ok, refused, p};

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("smoothlab-volume-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn volume(model: Model) -> VolumeMesh {
    match model {
        Model::Volume(v) => v,
        other => panic!("not read as tetrahedra: {other:?}"),
    }
}

fn same(a: &VolumeMesh, b: &VolumeMesh) {
    assert_eq!(a.nodes(), b.nodes());
    assert_eq!(a.element_count(), b.element_count());
    for e in 0..a.element_count() {
        assert_eq!(a.element(e), b.element(e), "element {e}");
    }
    assert_eq!(a.fixed(), b.fixed());
}

fn samples() -> Vec<VolumeMesh> {
    let cube = smoothlab::generate::tet_cube(3).unwrap();
    let tangled = smoothlab::generate::perturb_volume(&cube, 0.7, 5).unwrap();
    let quadratic = tangled.to_quadratic(false).unwrap();
    vec![cube, tangled, quadratic]
}

#[test]
fn every_format_round_trips_exactly() {
    let d = dir("roundtrip");
    for (i, m) in samples().into_iter().enumerate() {
        let model = Model::Volume(m.clone());
        for (format, version) in
            [(Format::Msh, MshVersion::V22), (Format::Msh, MshVersion::V41), (Format::Vtk, MshVersion::V41)]
        {
            let text = io::write_model_string(&model, format, &WriteOptions { msh_version: version }).unwrap();
            same(&m, &volume(io::read_model_str(&text, format).unwrap()));
        }
        // TetGen: fixed = boundary ∪ markers, which are the fixed flags here
        let path = d.join(format!("m{i}.node"));
        io::write_model_path(&model, &path, &WriteOptions::default()).unwrap();
        same(&m, &volume(io::read_model_path(&path).unwrap()));
        let (node, ele) =
            (std::fs::read_to_string(&path).unwrap(), std::fs::read_to_string(d.join(format!("m{i}.ele"))).unwrap());
        same(&m, &volume(io::read_model_pair(&node, &ele).unwrap()));
    }
    // OBJ and OFF hold no tetrahedra
    let e = io::write_model_string(&Model::Volume(samples().remove(0)), Format::Obj, &WriteOptions::default());
    assert!(e.unwrap_err().to_string().contains("hold surfaces, not volume elements"));
}

/// One 10-node tetrahedron as Gmsh writes it: mid-edge nodes on (0,1) (1,2) (2,0) (3,0)
/// (3,2) (3,1), tags 1-based; node 9 (Gmsh's (3,2)) is put off its edge's middle to see
/// where it lands.
const GMSH_TET10: &str = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n10\n\
1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n\
5 0.5 0 0\n6 0.5 0.5 0\n7 0 0.5 0\n8 0 0 0.5\n9 0 0.5 0.6\n10 0.5 0 0.5\n$EndNodes\n\
$Elements\n1\n1 11 2 0 1 1 2 3 4 5 6 7 8 9 10\n$EndElements\n";

#[test]
fn gmsh_ten_node_tetrahedra_are_read_in_gmsh_order() {
    let m = volume(io::read_model_str(GMSH_TET10, Format::Msh).unwrap());
    assert!(m.is_quadratic());
    // ours: (0,1) (1,2) (0,2) (0,3) (1,3) (2,3): Gmsh's node 9 (index 8, on (3,2)) is our
    // last, Gmsh's node 10 (index 9, on (3,1)) our fifth mid-edge node
    assert_eq!(m.element(0), &[0, 1, 2, 3, 4, 5, 6, 7, 9, 8]);
    // and written back in Gmsh's order
    let text =
        io::write_model_string(&Model::Volume(m.clone()), Format::Msh, &WriteOptions { msh_version: MshVersion::V22 })
            .unwrap();
    assert!(text.contains(" 11 2 0 1 1 2 3 4 5 6 7 8 9 10\n"), "{text}");
}

#[test]
fn bad_tetrahedral_files_are_refused_naming_the_line_or_element() {
    let vtk = |cells: &str, types: &str, n: usize| {
        format!(
            "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 5 double\n\
0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\nCELLS {n} {}\n{cells}CELL_TYPES {n}\n{types}",
            5 * n
        )
    };
    let err = |text: String| io::read_model_str(&text, Format::Vtk).unwrap_err().to_string();
    assert!(err(vtk("4 0 1 2 7\n", "10\n", 1)).contains("point index 7 is out of range"));
    assert!(err(vtk("4 0 1 1 3\n", "10\n", 1)).contains("point 1 appears twice"));
    // a flat tetrahedron: the four corners in the plane z = 0
    let flat = "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n\
0 0 0\n1 0 0\n0 1 0\n1 1 0\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\n";
    let e = io::read_model_str(flat, Format::Vtk).unwrap_err().to_string();
    assert!(e.starts_with("element 0 (line 11): the tetrahedron has no volume"), "{e}");
    // NaN coordinate
    let nan = GMSH_TET10.replace("3 0 1 0\n", "3 0 nan 0\n");
    let e = io::read_model_str(&nan, Format::Msh).unwrap_err().to_string();
    assert!(e.starts_with("line 8: ") && e.contains("node tag 3"), "{e}");
    // mixing 4- and 10-node tetrahedra
    let mixed = GMSH_TET10.replace("$Elements\n1\n", "$Elements\n2\n2 4 2 0 1 1 2 3 4\n");
    let e = io::read_model_str(&mixed, Format::Msh).unwrap_err().to_string();
    assert!(e.contains("mixes 4-node and 10-node tetrahedra"), "{e}");
    // read as a planar mesh: said so
    let e = io::read_str(GMSH_TET10, Format::Msh).unwrap_err().to_string();
    assert!(e.contains("holds volume elements, not a planar mesh"), "{e}");
}

#[test]
fn the_command_line_generates_perturbs_measures_smooths_and_converts_tetrahedra() {
    let d = dir("cli");
    let cube = d.join("cube.vtk");
    let tangled = d.join("tangled.msh");
    let smoothed = d.join("smoothed.vtk");
    ok(&["generate", "cube", "--cells", "4", "-o", p(&cube)]);
    ok(&["generate", "perturb", p(&cube), "--amount", "0.8", "--seed", "2", "-o", p(&tangled)]);
    let before: Value = serde_json::from_str(&ok(&["stats", "--json", p(&tangled)])).unwrap();
    assert_eq!(before["volume_kinds"], serde_json::json!({"Tet4": 384}));
    assert_eq!(before["free_nodes"], 27);
    assert!(before["inverted"].as_u64().unwrap() > 0);
    let table = ok(&["stats", p(&tangled)]);
    assert!(table.contains("elements         384 4-node tetrahedra\n") && table.contains("dihedral angles"), "{table}");
    let report: Value = serde_json::from_str(&ok(&[
        "smooth",
        p(&tangled),
        "--strategy",
        "rules",
        "--passes",
        "3",
        "--json",
        "-o",
        p(&smoothed),
    ]))
    .unwrap();
    assert_eq!(report["final"]["inverted"], 0);
    let after: Value = serde_json::from_str(&ok(&["stats", "--json", p(&smoothed)])).unwrap();
    assert_eq!(after["inverted"], 0);
    assert!(after["min_angle_deg"].as_f64().unwrap() > before["min_angle_deg"].as_f64().unwrap());
    // boundary nodes stay where they were, bit for bit
    let (a, b) = (volume(io::read_model_path(&tangled).unwrap()), volume(io::read_model_path(&smoothed).unwrap()));
    for n in 0..a.node_count() {
        if !a.is_free(n) {
            assert_eq!(a.nodes()[n], b.nodes()[n], "node {n}");
        }
    }
    let pair = d.join("smoothed.node");
    ok(&["convert", p(&smoothed), p(&pair)]);
    assert!(d.join("smoothed.ele").exists());
    assert_eq!(serde_json::from_str::<Value>(&ok(&["stats", "--json", p(&pair)])).unwrap()["volume_kinds"]["Tet4"], 384);
    // what does not apply to tetrahedra is refused, saying why
    assert!(refused(&["smooth", p(&tangled), "--slide-curves", "-o", p(&smoothed)])
        .contains("this mesh is made of tetrahedra"));
    // pictures: the cut 3D view, old and new side by side, and the dihedral histograms
    let png = d.join("compare.png");
    ok(&["render", p(&tangled), "--view", "compare", "--passes", "1", "--cut", "y=0.5", "-o", p(&png)]);
    assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));
    ok(&["render", p(&tangled), "--view", "histogram", "-o", p(&d.join("h.png"))]);
    assert!(refused(&["render", p(&tangled), "--view", "levelset", "-o", p(&png)]).contains("a volume mesh is drawn by"));
    assert!(refused(&["render", p(&tangled), "--cut", "w=2", "-o", p(&png)]).contains("--cut"));
    let grid = d.join("grid.vtk");
    ok(&["generate", "grid", "-o", p(&grid)]);
    assert!(refused(&["render", p(&grid), "--cut", "z=0.5", "-o", p(&png)]).contains("--cut cuts a volume mesh; this mesh is planar"));
    assert!(refused(&["convert", p(&tangled), p(&d.join("x.obj"))]).contains("not volume elements"));
}

/// Issue 29: a tetrahedral file's triangles (the boundary faces Gmsh writes) were read
/// for the nodes they fix and then dropped from every output; one inside the volume fixed
/// its nodes without a word. They are written back (`.msh` 2.2 and 4.1, `.vtk`), and a
/// triangle off the boundary that fixes a node inside is named in a note.
#[test]
fn a_tetrahedral_files_triangles_are_kept_and_one_inside_is_named() {
    // the unit cube of 2³ cells in tetrahedra, its boundary faces and one inner face as
    // triangles, no fixed flags of its own (the triangles fix)
    let cube = smoothlab::generate::tet_cube(2).unwrap();
    let mut faces: std::collections::HashMap<[u32; 3], (u32, [u32; 3])> = std::collections::HashMap::new();
    for e in 0..cube.element_count() {
        let t = cube.element(e);
        for f in [[t[1], t[2], t[3]], [t[0], t[3], t[2]], [t[0], t[1], t[3]], [t[0], t[2], t[1]]] {
            let mut key = f;
            key.sort_unstable();
            faces.entry(key).or_insert((0, f)).0 += 1;
        }
    }
    let mut tris: Vec<[u32; 3]> = faces.values().filter(|(c, _)| *c == 1).map(|(_, f)| *f).collect();
    tris.sort_unstable();
    let inner = faces.values().filter(|(c, _)| *c == 2).map(|(_, f)| *f).find(|f| f.iter().any(|&i| cube.is_free(i as usize))).unwrap();
    tris.push(inner);
    let mut text = format!("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n{}\n", cube.node_count());
    for (i, p) in cube.nodes().iter().enumerate() {
        text += &format!("{} {:?} {:?} {:?}\n", i + 1, p.x, p.y, p.z);
    }
    text += &format!("$EndNodes\n$Elements\n{}\n", cube.element_count() + tris.len());
    for e in 0..cube.element_count() {
        let t = cube.element(e);
        text += &format!("{} 4 2 0 1 {} {} {} {}\n", e + 1, t[0] + 1, t[1] + 1, t[2] + 1, t[3] + 1);
    }
    for (j, f) in tris.iter().enumerate() {
        text += &format!("{} 2 2 7 1 {} {} {}\n", cube.element_count() + j + 1, f[0] + 1, f[1] + 1, f[2] + 1);
    }
    text += "$EndElements\n";
    let m = volume(io::read_model_str(&text, Format::Msh).unwrap());
    let given: Vec<Vec<u32>> = tris.iter().map(|f| f.to_vec()).collect();
    let kept = |m: &VolumeMesh| -> Vec<Vec<u32>> { m.faces().iter().map(|f| f.nodes().to_vec()).collect() };
    assert_eq!(kept(&m), given);
    let note = m.stray_faces_note().expect("the inner triangle is named");
    let free = inner.iter().find(|&&i| cube.is_free(i as usize)).unwrap();
    assert!(note.starts_with("1 of the file's triangles") && note.contains(&format!("fixes node {}", free + 1)), "{note}");
    for (format, opts) in [
        (Format::Msh, WriteOptions { msh_version: MshVersion::V22 }),
        (Format::Msh, WriteOptions { msh_version: MshVersion::V41 }),
        (Format::Vtk, WriteOptions::default()),
    ] {
        let written = io::write_model_string(&Model::Volume(m.clone()), format, &opts).unwrap();
        let back = volume(io::read_model_str(&written, format).unwrap());
        assert_eq!(kept(&back), given, "{format:?} {opts:?}");
        same(&m, &back);
    }
    // without the inner triangle: the boundary's triangles fix nothing inside, no note
    let boundary_only = text.lines().filter(|l| !l.starts_with(&format!("{} 2 ", cube.element_count() + tris.len()))).collect::<Vec<_>>().join("\n");
    let boundary_only = boundary_only.replacen(&format!("$Elements\n{}\n", cube.element_count() + tris.len()), &format!("$Elements\n{}\n", cube.element_count() + tris.len() - 1), 1);
    assert!(volume(io::read_model_str(&boundary_only, Format::Msh).unwrap()).stray_faces_note().is_none());
}

#[test]
fn medit_files_convert_both_ways_and_give_their_stats() {
    let d = dir("medit");
    let (vtk, mesh, back) = (d.join("h.vtk"), d.join("h.mesh"), d.join("back.vtk"));
    ok(&["generate", "hexgrid", "--cells", "2", "-o", p(&vtk)]);
    ok(&["convert", p(&vtk), p(&mesh)]);
    ok(&["convert", p(&mesh), p(&back)]);
    let (a, b) = (volume(io::read_model_path(&vtk).unwrap()), volume(io::read_model_path(&back).unwrap()));
    same(&a, &b);
    assert_eq!(ok(&["stats", p(&vtk)]), ok(&["stats", p(&mesh)]), "the same statistics from .vtk and .mesh");
    // a quadratic mesh is refused by name
    let q = d.join("q.vtk");
    ok(&["generate", "cube", "--cells", "1", "--order", "2", "-o", p(&q)]);
    let e = refused(&["convert", p(&q), p(&d.join("q.mesh"))]);
    assert!(e.contains("Medit's volume sections hold linear elements, but element 0 is a 10-node tetrahedron"), "{e}");
    // HexaLab's block (Livesu et al. 2015) as the CLI sees it
    let Some(livesu) = crate::common::livesu_meshes() else { return };
    let stats = ok(&["stats", p(&livesu.join("block_in.mesh"))]);
    assert!(stats.starts_with("nodes            3180 (1984 free, 1196 fixed)\nelements         2520 8-node hexahedra\n"), "{stats}");
    assert!(stats.contains("inverted         31 (0 inside, every corner positive)\n"), "{stats}");
}
