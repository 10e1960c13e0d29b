//! The Mesquite 3D walk: every VTK file of Mesquite's 3D test meshes
//! (`../shared/meshes/mesquite3d`, read in place) is read — hexahedra tangled and
//! untangled, a mixed hexahedron/pyramid/tetrahedron mesh, wedges, pyramids, 20-node
//! hexahedra, tetrahedra — with the counts of its header, each cell of its kind with its
//! nodes as the file lists them (none turned over: every kind's orientation is the
//! file's), the file's `fixed` flags, and the inverted elements Mesquite's README counts
//! (0 in the untangled files). The one file of quads is a surface. The headers are read
//! here with plain string handling, independently of the reader.
//!
//! Then the command line on them: `stats` names the kinds, `smooth` untangles the tangled
//! ones and keeps the fixed nodes where they were.


use std::path::{Path, PathBuf};
use std::process::Command;

use smoothlab::io::{read_model_path, read_model_str, Format};
use smoothlab::mesh::{NodeRole, VolumeKind};
use smoothlab::model::Model;
use smoothlab::volume::{volume_stats, VolumeMesh};

/// What a file says, read as plain text: its points, cells (type and point list) and
/// `SCALARS fixed` values.
struct Header {
    points: usize,
    cells: Vec<(u32, Vec<u32>)>,
    fixed: Option<Vec<bool>>,
}

fn header(text: &str) -> Header {
    let lines: Vec<&str> = text.lines().collect();
    let at = |kw: &str| lines.iter().position(|l| l.split_whitespace().next() == Some(kw)).unwrap();
    let field = |i: usize, k: usize| -> usize { lines[i].split_whitespace().nth(k).unwrap().parse().unwrap() };
    let points = field(at("POINTS"), 1);
    let c = at("CELLS");
    let n = field(c, 1);
    // Mesquite writes one cell per line, its point count first
    let lists: Vec<Vec<u32>> =
        (0..n).map(|i| lines[c + 1 + i].split_whitespace().skip(1).map(|v| v.parse().unwrap()).collect()).collect();
    let t = at("CELL_TYPES");
    let types: Vec<u32> = lines[t + 1..].iter().flat_map(|l| l.split_whitespace()).take(n).map(|v| v.parse().unwrap()).collect();
    let fixed = lines.iter().position(|l| l.starts_with("SCALARS fixed")).map(|s| {
        let start = if lines[s + 1].starts_with("LOOKUP_TABLE") { s + 2 } else { s + 1 };
        let v: Vec<bool> = lines[start..]
            .iter()
            .flat_map(|l| l.split_whitespace())
            .take(points)
            .map(|v| v.parse::<f64>().unwrap() != 0.0)
            .collect();
        assert_eq!(v.len(), points);
        v
    });
    Header { points, cells: types.into_iter().zip(lists).collect(), fixed }
}

/// The inverted elements of each tangled file, as Mesquite's README counts them (by the
/// 8 corner Jacobians of its hexahedra); every other volume file is untangled (0).
const TANGLED: [(&str, usize); 7] = [
    ("hexes/tangled/pave1.e.vtk", 56),
    ("hexes/tangled/pave2.e.vtk", 4),
    ("hexes/tangled/pave3.e.vtk", 106),
    ("hexes/tangled/pave_cyl.e.vtk", 116),
    ("hexes/tangled/hex_5_tangled.vtk", 36),
    ("mixed/tangled/mixed-hex-pyr-tet.vtk", 3),
    ("tets/tangled/tet_4_tangled.vtk", 9),
];
/// Quads (VTK type 9) in the hexahedra's folder: a surface in 3D.
const QUADS: &str = "hexes/untangled/sph-10-zsquare.vtk";

fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let p = entry.unwrap().path();
        if p.is_dir() {
            walk(&p, out);
        } else if p.extension().is_some_and(|e| e == "vtk") {
            out.push(p);
        }
    }
}

fn volume(model: Model, rel: &str) -> VolumeMesh {
    match model {
        Model::Volume(v) => v,
        other => panic!("{rel}: not read as a volume mesh: {:?}", other.stats()),
    }
}

#[test]
fn every_mesquite_3d_file_reads_with_its_counts_kinds_fixed_flags_and_inverted_elements() {
    let Some(root) = crate::common::mesquite3d_meshes() else { return };
    let mut files = Vec::new();
    walk(&root, &mut files);
    files.sort();
    assert_eq!(files.len(), 18, "Mesquite's 3D subset holds 18 VTK files");
    let mut kinds_seen = std::collections::BTreeSet::new();
    for path in &files {
        let rel = path.strip_prefix(&root).unwrap().to_string_lossy().replace('\\', "/");
        let h = header(&std::fs::read_to_string(path).unwrap());
        let model = read_model_path(path).unwrap_or_else(|e| panic!("{rel} must read: {e}"));
        if rel == QUADS {
            let Model::Surface(s) = model else { panic!("{rel}: quads in 3D are a surface") };
            assert!(h.cells.iter().all(|(t, _)| *t == 9), "{rel}: the file holds quads");
            let st = s.stats();
            assert_eq!((s.node_count(), st.quads, st.inverted), (h.points, h.cells.len(), 0), "{rel}");
            continue;
        }
        let m = volume(model, &rel);
        assert_eq!((m.node_count(), m.element_count()), (h.points, h.cells.len()), "{rel}");
        for (e, (ty, list)) in h.cells.iter().enumerate() {
            let kind = m.element_kind(e);
            kinds_seen.insert(kind);
            assert_eq!(kind.row().vtk_type, *ty, "{rel}: element {e}");
            // as the file lists it: the mesh was not turned over, so each kind's corners
            // turn as the file's do
            assert_eq!(m.element(e), list.as_slice(), "{rel}: element {e}");
        }
        let fixed = h.fixed.as_ref().unwrap_or_else(|| panic!("{rel}: every volume file here carries 'fixed'"));
        for (n, &f) in fixed.iter().enumerate() {
            // nodes no element uses are always fixed
            assert_eq!(m.fixed()[n], f || m.role(n) == NodeRole::Unused, "{rel}: fixed flag of node {n}");
        }
        let want = TANGLED.iter().find(|(f, _)| *f == rel).map_or(0, |&(_, n)| n);
        let stats = volume_stats(&m);
        assert_eq!(stats.inverted, want, "{rel}: inverted elements");
        // the statistics count each kind as the file's types do
        for k in VolumeKind::ALL {
            let n = h.cells.iter().filter(|(t, _)| *t == k.row().vtk_type).count();
            assert_eq!(stats.volume_kinds.get(k), n, "{rel}: {k:?}");
        }
    }
    // the files hold five of the seven kinds (no 10-node tetrahedra, no 27-node hexahedra)
    use VolumeKind::*;
    assert_eq!(kinds_seen.into_iter().collect::<Vec<_>>(), vec![Tet4, Hex8, Hex20, Wedge6, Pyramid5]);
}

#[test]
fn without_the_files_fixed_flags_the_boundary_skin_is_fixed() {
    let Some(root) = crate::common::mesquite3d_meshes() else { return };
    // six wedges around an axis: the file frees the axis's two ends, on the skin
    let text = std::fs::read_to_string(root.join("prisms/untangled/6-wedge-prism.vtk")).unwrap();
    let with = volume(read_model_str(&text, Format::Vtk).unwrap(), "wedges");
    let cut = text.find("POINT_DATA").unwrap();
    let without = volume(read_model_str(&text[..cut], Format::Vtk).unwrap(), "wedges without POINT_DATA");
    let mut skin = vec![false; without.node_count()];
    for f in without.boundary_faces() {
        for &i in f.nodes() {
            skin[i as usize] = true;
        }
    }
    for (n, s) in skin.iter_mut().enumerate() {
        *s |= without.role(n) == NodeRole::Unused;
    }
    assert_eq!(without.fixed(), skin.as_slice());
    // the file's flags are not the skin's: the file frees two nodes of it
    let (a, b) = (with.fixed().iter().filter(|&&f| f).count(), skin.iter().filter(|&&f| f).count());
    assert_eq!((a, b), (12, 14));
    assert!(with.fixed().iter().zip(&skin).all(|(f, s)| !f || *s), "the file fixes only skin nodes");
}

fn smoothlab(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_smoothlab")).args(args).output().unwrap();
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap()
}

#[test]
fn the_command_line_measures_and_smooths_every_kind_of_mesquite_file() {
    let Some(root) = crate::common::mesquite3d_meshes() else { return };
    let s = |rel: &str| root.join(rel).to_str().unwrap().to_string();
    let table = smoothlab(&["stats", &s("mixed/tangled/mixed-hex-pyr-tet.vtk")]);
    assert!(
        table.contains("elements         940 (445 4-node tetrahedra, 305 8-node hexahedra, 190 5-node pyramids)\n"),
        "{table}"
    );
    // certain validity: of the 3, none is inverted inside with every corner positive
    assert!(table.contains("inverted         3 (0 inside, every corner positive)\n"), "{table}");
    assert!(table.contains("scaled Jacobian  min -0.2849\n"), "{table}");
    let json: serde_json::Value =
        serde_json::from_str(&smoothlab(&["stats", "--json", &s("quadratic/6x6x6-hex20.vtk")])).unwrap();
    assert_eq!(json["volume_kinds"], serde_json::json!({"Hex20": 216}));
    let d = std::env::temp_dir().join(format!("smoothlab-mesquite3d-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    // every kind, tangled where Mesquite has them so: each comes out untangled (measured:
    // rules with the new objective untangles each in its first pass), the fixed nodes
    // where they were to the bit
    for rel in [
        "hexes/tangled/hex_5_tangled.vtk",
        "mixed/tangled/mixed-hex-pyr-tet.vtk",
        "tets/tangled/tet_4_tangled.vtk",
        "prisms/untangled/6-wedge-prism.vtk",
        "pyramids/untangled/6-pyramid-brick.vtk",
        "quadratic/6x6x6-hex20.vtk",
    ] {
        let out = d.join(rel.replace('/', "-").replace(".vtk", ".msh"));
        let report: serde_json::Value =
            serde_json::from_str(&smoothlab(&["smooth", &s(rel), "--json", "-o", out.to_str().unwrap()])).unwrap();
        assert_eq!(report["final"]["inverted"], 0, "{rel}");
        let (before, after) = (volume(read_model_path(&root.join(rel)).unwrap(), rel), volume(read_model_path(&out).unwrap(), rel));
        assert_eq!(volume_stats(&after).inverted, 0, "{rel}: as written");
        assert_eq!(before.fixed(), after.fixed(), "{rel}");
        for n in 0..before.node_count() {
            if before.fixed()[n] {
                assert_eq!(before.nodes()[n], after.nodes()[n], "{rel}: fixed node {n}");
            }
        }
        for e in 0..before.element_count() {
            assert_eq!((before.element_kind(e), before.element(e)), (after.element_kind(e), after.element(e)), "{rel}");
        }
    }
}
