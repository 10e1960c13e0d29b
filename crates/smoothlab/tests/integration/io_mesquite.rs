//! The Mesquite walk: every VTK file of Mesquite's 2D test meshes is read. Planar ones
//! must load with the node and element counts of their headers, their `fixed` flags, a
//! positive total area and a sane topology; the others must be refused for the reason
//! stated here, file by file. The counts and flags are parsed here independently of
//! the reader.


use std::path::{Path, PathBuf};

use smoothlab::io::{read_model_path, read_path};
use smoothlab::model::Model;
use smoothlab::mesh::NodeRole;
use smoothlab::Error;

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

/// What the file says, read with plain string handling.
struct Header {
    points: usize,
    cells: usize,
    cell_types: usize,
    /// `SCALARS fixed` values, when present.
    fixed: Option<Vec<bool>>,
    /// (cell index, line, vertex count) of the first cell with more than 4 points.
    first_polygon: Option<(usize, usize, usize)>,
}

fn header(text: &str) -> Header {
    let lines: Vec<&str> = text.lines().collect();
    let find = |kw: &str| lines.iter().position(|l| l.split_whitespace().next() == Some(kw));
    let field = |i: usize, k: usize| -> usize { lines[i].split_whitespace().nth(k).unwrap().parse().unwrap() };
    let p = find("POINTS").unwrap();
    let c = find("CELLS").unwrap();
    let t = find("CELL_TYPES").unwrap();
    let cells = field(c, 1);
    // Mesquite writes one cell per line.
    let first_polygon = (0..cells).find_map(|i| {
        let k: usize = lines[c + 1 + i].split_whitespace().next().unwrap().parse().unwrap();
        (k > 4).then_some((i, c + 2 + i, k))
    });
    let fixed = lines.iter().position(|l| l.starts_with("SCALARS fixed")).map(|s| {
        let points = field(p, 1);
        let mut start = s + 1;
        if lines[start].starts_with("LOOKUP_TABLE") {
            start += 1;
        }
        let values: Vec<bool> = lines[start..]
            .iter()
            .flat_map(|l| l.split_whitespace())
            .take(points)
            .map(|v| v.parse::<f64>().unwrap() != 0.0)
            .collect();
        assert_eq!(values.len(), points);
        values
    });
    Header { points: field(p, 1), cells, cell_types: field(t, 1), fixed, first_polygon }
}

const NOT_PLANAR: [&str; 4] = [
    "quads/untangled/quads_on_sphere_529.vtk",
    "quads/untangled/paraboloid.vtk",
    "quads/untangled/bias-sphere-quads.vtk",
    "tris/untangled/Mesquite_geo_10242.vtk",
];
const POLYGONS: [&str; 3] = ["N-Polygonal/poly1.vtk", "N-Polygonal/poly2.vtk", "N-Polygonal/poly3.vtk"];
/// `CELL_TYPES` lists 19 types for 6 cells: read, the first 6 types used.
const TYPE_COUNT_SURPLUS: [&str; 6] = [
    "quadratic/triPatch_0_0.vtk",
    "quadratic/triPatch_0_7.vtk",
    "quadratic/triPatch_0_8.vtk",
    "quadratic/triPatch_1_0.vtk",
    "quadratic/triPatch_1_1.vtk",
    "quadratic/triPatch_1_2.vtk",
];
/// Corrupt: its first point reads `4225 0 0` (the point count leaked into the data, so
/// every coordinate is shifted by one token) and its cells read `3 a b c d`: counts of 3
/// followed by 4 indices. Refused, naming the line where the counts stop fitting.
const CORRUPT_CELLS: &str = "quads/untangled/shashkov_quad_opt.vtk";

#[test]
fn every_mesquite_file_loads_or_is_refused_for_its_reason() {
    let Some(root) = crate::common::mesquite_meshes() else { return };
    let mut files = Vec::new();
    walk(&root, &mut files);
    files.sort();
    assert!(files.len() >= 60, "expected Mesquite's ~68 VTK files, found {}", files.len());
    let mut loaded = 0;
    for path in &files {
        let rel = path.strip_prefix(&root).unwrap().to_string_lossy().replace('\\', "/");
        let text = std::fs::read_to_string(path).unwrap();
        let h = header(&text);
        let result = read_path(path);
        if NOT_PLANAR.contains(&rel.as_str()) {
            // refused as a planar mesh, read as a surface
            match result {
                Err(e @ Error::NotPlanar { relative, .. }) => {
                    assert!(relative > 0.01, "{rel}: {relative}");
                    assert!(e.to_string().contains("not planar"), "{rel}: {e}");
                }
                other => panic!("{rel}: expected NotPlanar, got {:?}", other.map(|m| m.node_count())),
            }
            let Ok(Model::Surface(s)) = read_model_path(path) else { panic!("{rel} must load as a surface") };
            assert_eq!(s.node_count(), h.points, "{rel}");
            let st = s.stats();
            assert!(st.surface && st.inverted == 0, "{rel}: {st:?}");
            assert_eq!(st.max_distance_from_surface, Some(0.0), "{rel}: the nodes are the reference's vertices");
        } else if POLYGONS.contains(&rel.as_str()) {
            let (i, line, k) = h.first_polygon.expect("a polygon file has a polygon");
            let e = result.err().unwrap_or_else(|| panic!("{rel} must be refused"));
            let want = format!("polygons are not supported: element {i} at line {line} has {k} vertices");
            assert!(matches!(e, Error::Unsupported { .. }) && e.to_string().contains(&want), "{rel}: {e}");
        } else if rel == CORRUPT_CELLS {
            let e = result.err().unwrap_or_else(|| panic!("{rel} must be refused")).to_string();
            assert!(e.contains("point counts of the cells do not match") && e.contains("line "), "{rel}: {e}");
        } else {
            let mesh = result.unwrap_or_else(|e| panic!("{rel} must load: {e}"));
            loaded += 1;
            if TYPE_COUNT_SURPLUS.contains(&rel.as_str()) {
                assert!(h.cell_types > h.cells, "{rel}: the surplus of CELL_TYPES is what this case tests");
            }
            assert_eq!(mesh.node_count(), h.points, "{rel}: nodes");
            assert_eq!(mesh.element_count(), h.cells, "{rel}: elements");
            if let Some(f) = &h.fixed {
                for (n, &fixed) in f.iter().enumerate() {
                    // nodes no element uses are always fixed
                    let want = fixed || mesh.role(n) == NodeRole::Unused;
                    assert_eq!(mesh.fixed()[n], want, "{rel}: fixed flag of node {n}");
                }
            }
            let total: f64 = (0..mesh.element_count()).map(|e| mesh.corner_area(e)).sum();
            assert!(total > 0.0, "{rel}: total area {total}");
            mesh.sanity_check().unwrap_or_else(|e| panic!("{rel}: {e}"));
        }
    }
    let refused = NOT_PLANAR.len() + POLYGONS.len() + 1;
    assert_eq!(loaded + refused, files.len());
    assert!(loaded >= 50, "only {loaded} files loaded");
}

fn load(rel: &str) -> Option<smoothlab::Mesh> {
    let root = crate::common::mesquite_meshes()?;
    Some(read_path(&root.join(rel)).unwrap())
}

/// Raw signed area of the corner polygons in the file's own x, y (before any mapping).
fn raw_xy_area(rel: &str) -> f64 {
    let text = std::fs::read_to_string(crate::common::mesquite_meshes().unwrap().join(rel)).unwrap();
    let tok: Vec<&str> = text.split_whitespace().collect();
    let p = tok.iter().position(|t| *t == "POINTS").unwrap();
    let n: usize = tok[p + 1].parse().unwrap();
    let xy: Vec<(f64, f64)> =
        (0..n).map(|i| (tok[p + 3 + 3 * i].parse().unwrap(), tok[p + 4 + 3 * i].parse().unwrap())).collect();
    let c = tok.iter().position(|t| *t == "CELLS").unwrap();
    let m: usize = tok[c + 1].parse().unwrap();
    let mut at = c + 3;
    let mut total = 0.0;
    for _ in 0..m {
        let k: usize = tok[at].parse().unwrap();
        let corners = if k == 3 || k == 6 { 3 } else { 4 };
        let ids: Vec<usize> = (0..corners).map(|j| tok[at + 1 + j].parse().unwrap()).collect();
        for j in 0..corners {
            let (a, b) = (xy[ids[j]], xy[ids[(j + 1) % corners]]);
            total += 0.5 * (a.0 * b.1 - a.1 * b.0);
        }
        at += k + 1;
    }
    total
}

#[test]
fn a_mesh_facing_down_in_z_minus_5_comes_out_counter_clockwise() {
    // hole_in_square: z = -5, normal (0, 0, -1): clockwise as seen from +z.
    let rel = "quads/tangled/hole_in_square.vtk";
    let Some(mesh) = load(rel) else { return };
    assert!(raw_xy_area(rel) < 0.0, "the file is clockwise in x, y");
    for e in 0..mesh.element_count() {
        assert!(mesh.corner_area(e) > 0.0, "element {e}: {}", mesh.corner_area(e));
    }
    let total: f64 = (0..mesh.element_count()).map(|e| mesh.corner_area(e)).sum();
    assert!((total + raw_xy_area(rel)).abs() < 1e-9 * total, "same area, flipped");
}

#[test]
fn tilted_and_vertical_planes_keep_their_true_area() {
    // Mesquite's README: 10 × 10 squares in a tilted plane, normal (.5, 0, .866), and in y = -5.
    for rel in ["tris/untangled/tri_5_not_xy.vtk", "quads/untangled/quad_2_not_xy.vtk", "tris/untangled/tri_5_xz.vtk"] {
        let Some(mesh) = load(rel) else { return };
        let total: f64 = (0..mesh.element_count()).map(|e| mesh.corner_area(e)).sum();
        assert!((total - 100.0).abs() < 1e-3, "{rel}: {total}");
        assert!((raw_xy_area(rel) - 100.0).abs() > 10.0, "{rel}: the raw x, y area is not the true one");
        for e in 0..mesh.element_count() {
            assert!(mesh.corner_area(e) > 0.0, "{rel}: element {e}");
        }
    }
}

#[test]
fn quadratic_meshes_keep_their_mid_nodes() {
    let Some(mesh) = load("quadratic/quadPart.vtk") else { return };
    assert!(mesh.kinds().iter().all(|k| *k == smoothlab::ElementKind::Quad9));
    let Some(mesh) = load("quadratic/horseShoe0.vtk") else { return };
    assert!(mesh.kinds().iter().all(|k| *k == smoothlab::ElementKind::Tri6));
    // mid nodes are mid nodes, each within its element's corner bounding box (give or take curvature)
    for e in 0..mesh.element_count() {
        let ids = mesh.element(e);
        for i in 0..3 {
            let (a, b, m) = (mesh.nodes()[ids[i] as usize], mesh.nodes()[ids[(i + 1) % 3] as usize], mesh.nodes()[ids[3 + i] as usize]);
            assert!(m.distance(0.5 * (a + b)) < 0.5 * a.distance(b), "element {e} edge {i}");
        }
    }
}
