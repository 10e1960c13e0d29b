//! `generate hexgrid` and `generate mixed` end to end: written, read back, counted by hand,
//! perturbed into Knupp's tangled test grid and smoothed; bad requests refused in words.

use std::path::{Path, PathBuf};

use serde_json::Value;
use smoothlab::io::read_model_path;
use smoothlab::mesh::VolumeKind;
use smoothlab::model::Model;
use smoothlab::volume::VolumeMesh;
use crate::common::{ok, refused, p};

fn out(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("volume_generate");
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn volume(path: &Path) -> VolumeMesh {
    match read_model_path(path).unwrap() {
        Model::Volume(v) => v,
        _ => panic!("{} is not a volume mesh", path.display()),
    }
}

fn count(m: &VolumeMesh, kind: VolumeKind) -> usize {
    (0..m.element_count()).filter(|&e| m.element_kind(e) == kind).count()
}

fn inverted(m: &VolumeMesh) -> usize {
    (0..m.element_count()).filter(|&e| m.is_inverted(e)).count()
}

#[test]
fn hexgrid_writes_the_block_it_is_asked_for() {
    let cube = out("cube.vtk");
    ok(&["generate", "hexgrid", "--cells", "3", "-o", p(&cube)]);
    let m = volume(&cube);
    assert_eq!((m.node_count(), m.element_count(), m.free_count()), (64, 27, 8));
    assert_eq!(m.kinds(), &[VolumeKind::Hex8]);
    assert_eq!(inverted(&m), 0);
    // per axis, a size, a bend: 4 × 3 × 2 cells, the bottom 2 long bent by 90°
    let beam = out("beam.msh");
    ok(&["generate", "hexgrid", "--cells", "4,3,2", "--size", "2,1,0.5", "--bend", "90", "-o", p(&beam)]);
    let b = volume(&beam);
    assert_eq!((b.node_count(), b.element_count()), (5 * 4 * 3, 24));
    assert_eq!(inverted(&b), 0);
    // the far end of the bottom at (R, ·, −R), R = 2/(π/2)
    let r = 4.0 / std::f64::consts::PI;
    assert!(b.nodes().iter().any(|q| (q.x - r).abs() < 1e-12 && (q.z + r).abs() < 1e-12), "the far end is not on the arc");
    // the same command, the same file
    let again = out("beam2.msh");
    ok(&["generate", "hexgrid", "--cells", "4,3,2", "--size", "2,1,0.5", "--bend", "90", "-o", p(&again)]);
    assert_eq!(std::fs::read(&beam).unwrap(), std::fs::read(&again).unwrap());
    // 27- and 20-node hexahedra: VTK cell types 29 and 25
    for (flags, ty, nodes) in [(&["--order", "2"][..], "29", 125), (&["--order", "2", "--serendipity"][..], "25", 27 + 54)] {
        let q = out(&format!("q{ty}.vtk"));
        let mut args = vec!["generate", "hexgrid", "--cells", "2"];
        args.extend_from_slice(flags);
        args.extend(["-o", p(&q)]);
        ok(&args);
        let text = std::fs::read_to_string(&q).unwrap();
        let types: Vec<&str> = text.split("CELL_TYPES").nth(1).unwrap().split_whitespace().skip(1).take(8).collect();
        assert_eq!(types, vec![ty; 8], "{flags:?}");
        assert!(text.contains(&format!("POINTS {nodes} ")), "{flags:?}");
    }
}

#[test]
fn mixed_writes_every_kind_conforming_and_valid() {
    let path = out("mixed.vtk");
    ok(&["generate", "mixed", "--cells", "3", "-o", p(&path)]);
    let m = volume(&path);
    // by hand: the wedge column 3 cells × 2, the pyramid row's 3 cells with 8 boundary
    // faces (16 tetrahedra) and 10 inner faces (pyramids), 27 − 6 = 21 hexahedra
    let counts = [VolumeKind::Tet4, VolumeKind::Hex8, VolumeKind::Wedge6, VolumeKind::Pyramid5].map(|k| count(&m, k));
    assert_eq!(counts, [16, 21, 6, 10]);
    assert_eq!((m.node_count(), inverted(&m)), (67, 0));
    // the surface: 54 quads, but 10 of them in two triangles each
    assert_eq!(m.boundary_faces().len(), 54 + 10);
    let stats: Value = serde_json::from_str(&ok(&["stats", "--json", p(&path)])).unwrap();
    assert_eq!((stats["elements"].as_u64(), stats["inverted"].as_u64()), (Some(53), Some(0)));
}

#[test]
fn a_perturbed_block_is_knupps_tangled_grid_and_smoothing_untangles_it() {
    let grid = out("grid6.vtk");
    let tangled = out("grid6-tangled.vtk");
    let smoothed = out("grid6-smoothed.vtk");
    ok(&["generate", "hexgrid", "--cells", "6", "-o", p(&grid)]);
    ok(&["generate", "perturb", p(&grid), "--amount", "0.6", "--seed", "1", "-o", p(&tangled)]);
    let (g, t) = (volume(&grid), volume(&tangled));
    assert!(inverted(&t) > 0, "0.6 edge lengths tangles the block");
    for n in 0..g.node_count() {
        if g.fixed()[n] {
            assert_eq!(g.nodes()[n], t.nodes()[n], "fixed node {n} moved");
        } else {
            assert_ne!(g.nodes()[n], t.nodes()[n], "free node {n} stayed");
        }
    }
    let report: Value = serde_json::from_str(&ok(&["smooth", p(&tangled), "--passes", "2", "--json", "-o", p(&smoothed)])).unwrap();
    assert_eq!(report["final"]["inverted"], 0);
    assert_eq!(inverted(&volume(&smoothed)), 0);
}

#[test]
fn bad_blocks_are_refused_in_words() {
    let o = out("bad.vtk");
    let o = p(&o);
    assert!(refused(&["generate", "hexgrid", "--cells", "4,3", "-o", o]).contains("three separated by commas"));
    assert!(refused(&["generate", "hexgrid", "--cells", "x", "-o", o]).contains("'x' is not a number"));
    assert!(refused(&["generate", "hexgrid", "--cells", "0", "-o", o]).contains("0 cells along x: give 1 to 200"));
    assert!(refused(&["generate", "hexgrid", "--bend", "300", "-o", o]).contains("give 0 to 270"));
    assert!(refused(&["generate", "hexgrid", "--size", "1,-1,1", "-o", o]).contains("finite numbers > 0"));
    assert!(refused(&["generate", "hexgrid", "--serendipity", "-o", o]).contains("give it with --order 2"));
    assert!(refused(&["generate", "hexgrid", "--order", "3", "-o", o]).contains("--order 3"));
    assert!(refused(&["generate", "mixed", "--cells", "1,2,2", "-o", o]).contains("a mixed block: 1 cells along x: give 2 to 200"));
}
