//! The stretch target (issue 57): a boundary layer smoothed with the defaults keeps its
//! first row, in 2D and 3D, where the ideal target thickens it; a mesh with no stretch
//! made on purpose is smoothed exactly as against the ideal.

use glam::{DVec2, DVec3};
use smoothlab::generate::{grid, hex_grid, rand2d, GridKind, HexBlock};
use smoothlab::model::Model;
use smoothlab::volume::{VolumeKind, VolumeMesh};
use smoothlab::{Smoothing, Target};

/// The layer's columns and rows, and how much thicker each row is than the one below.
const NX: usize = 40;
const NY: usize = 30;
const RATIO: f64 = 1.2;

/// The height of row `j` of the layer's rows, graded by [`RATIO`] from the wall to a total
/// of 1: the wall's row is about 0.0009 high, 28 times thinner than its width.
fn row_top(j: usize) -> f64 {
    (RATIO.powi(j as i32) - 1.0) / (RATIO.powi(NY as i32) - 1.0)
}

/// A fixed sequence of pseudo-random numbers in [−1, 1) from `state` (xorshift).
fn uniform(mut state: u64) -> impl FnMut() -> f64 {
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}

/// A 40 × 30 boundary layer of `kind`, its interior nodes moved by up to a fifth of their
/// cell each way (a fixed sequence of pseudo-random numbers).
fn layer(kind: GridKind) -> Model {
    let mut m = grid(NX, NY, kind).unwrap();
    let mut next = uniform(0x2545_f491_4f6c_dd1d);
    for p in m.nodes_mut() {
        let (i, j) = ((p.x * NX as f64).round() as usize, (p.y * NY as f64).round() as usize);
        let mut q = DVec2::new(p.x, row_top(j));
        if 0 < i && i < NX && 0 < j && j < NY {
            let h = (row_top(j) - row_top(j - 1)).min(row_top(j + 1) - row_top(j));
            q += DVec2::new(next() / NX as f64, next() * h) / 5.0;
        }
        *p = q;
    }
    Model::Planar(m)
}

/// The median height of the first row: each interior column's node above the wall.
fn first_row(model: &Model) -> f64 {
    let nodes = model.mesh().unwrap().nodes();
    let mut h: Vec<f64> = (1..NX).map(|i| nodes[NX + 1 + i].y - nodes[i].y).collect();
    h.sort_by(f64::total_cmp);
    h[h.len() / 2]
}

#[test]
fn the_defaults_keep_a_boundary_layer_s_first_row() {
    for kind in [GridKind::Quad, GridKind::Tri] {
        let input = layer(kind);
        let (h0, s0) = (first_row(&input), input.stats());
        let mut stretched = input.clone();
        let report = stretched.smooth(&Smoothing::default()).unwrap();
        assert_eq!(report.target(), Target::Stretch, "{kind:?}: a layer is stretched on purpose");
        let (h, s) = (first_row(&stretched), stretched.stats());
        // the fit to the targets runs first (docs/formulas.md, Targets)
        assert!(report.passes()[0].counts.fit_steps > 0, "{kind:?}: the fit kept no step");
        assert!((h / h0 - 1.0).abs() < 0.05, "{kind:?}: first row {h0} → {h}");
        assert!(s.min_angle_deg >= s0.min_angle_deg && s.max_angle_deg <= s0.max_angle_deg, "{kind:?}: angles worse");
        assert!(s.min_angle_deg > s0.min_angle_deg, "{kind:?}: the smallest angle not lifted");
        if kind == GridKind::Quad {
            // its cells come back near rectangles (the input's angles: 5.5°–174.5°)
            assert!(s.min_angle_deg > 80.0 && s.max_angle_deg < 100.0, "angles {s:?}");
        }
        // the ideal target pulls the wall's row toward squares
        let mut ideal = input.clone();
        ideal.smooth(&Smoothing::default().target(Target::Ideal)).unwrap();
        assert!(first_row(&ideal) > 1.3 * h0, "{kind:?}: the ideal kept the row ({})", first_row(&ideal));
    }
}

/// The quad layer bent a quarter turn about its rows' direction: a surface. Its stretch
/// is read in 3D and each target in its star's tangent plane; surfaces get no fit, so a
/// quadrilateral keeps its turn. First row's height: the wall's neighbours' y.
#[test]
fn the_defaults_keep_a_bent_boundary_layer_s_first_row() {
    let Model::Planar(flat) = layer(GridKind::Quad) else { unreachable!() };
    let input = bent(&flat);
    let points = |m: &Model| match m {
        Model::Surface(s) => s.points().to_vec(),
        _ => unreachable!(),
    };
    let row = |m: &Model| {
        let p = points(m);
        let mut h: Vec<f64> = (1..NX).map(|i| p[NX + 1 + i].y - p[i].y).collect();
        h.sort_by(f64::total_cmp);
        h[h.len() / 2]
    };
    let (h0, s0) = (row(&input), input.stats());
    let mut stretched = input.clone();
    let report = stretched.smooth(&Smoothing::default()).unwrap();
    assert_eq!(report.target(), Target::Stretch, "a bent layer is stretched on purpose");
    let (h, s) = (row(&stretched), stretched.stats());
    // the node passes alone, as the plane's before its fit: within 7 % (+5.3 % here,
    // −5.0 … +5.2 % on the script's six seeds: docs/formulas.md, Targets)
    assert!((h / h0 - 1.0).abs() < 0.07, "first row {h0} → {h}");
    assert!(s.min_angle_deg >= s0.min_angle_deg && s.max_angle_deg <= s0.max_angle_deg, "angles worse");
    let mut ideal = input.clone();
    ideal.smooth(&Smoothing::default().target(Target::Ideal)).unwrap();
    assert!(row(&ideal) > 1.3 * h0, "the ideal kept the row ({})", row(&ideal));
}

#[test]
fn a_mesh_not_stretched_on_purpose_is_smoothed_as_against_the_ideal() {
    let input = Model::Planar(rand2d(400, 10, 7).unwrap());
    let mut stretch = input.clone();
    let report = stretch.smooth(&Smoothing::default()).unwrap();
    assert_eq!(report.target(), Target::Ideal);
    let mut ideal = input;
    ideal.smooth(&Smoothing::default().target(Target::Ideal)).unwrap();
    assert_eq!(stretch.mesh().unwrap().nodes(), ideal.mesh().unwrap().nodes());
}

/// A 3D boundary layer: 10 × 10 hexahedra 0.025 wide (each cut into two wedges with
/// `wedges`), 16 rows graded ×1.25 from a wall row 0.001 high (25 times thinner than
/// wide), its interior nodes moved by up to a fifth of their cell each way; and each
/// interior column's node's row.
fn layer_3d(wedges: bool) -> (Model, Vec<usize>) {
    const ROWS: usize = 16;
    let top = |k: usize| 0.001 * (1.25f64.powi(k as i32) - 1.0) / 0.25;
    let mut m = hex_grid(&HexBlock { cells: [10, 10, ROWS], size: DVec3::ONE, bend: 0.0 }).unwrap();
    let mut next = uniform(0x9e37_79b9_7f4a_7c15);
    let mut rows = Vec::new();
    for p in m.nodes_mut() {
        let (i, j, k) = ((p.x * 10.0).round() as usize, (p.y * 10.0).round() as usize, (p.z * ROWS as f64).round() as usize);
        let mut q = DVec3::new(p.x * 0.25, p.y * 0.25, top(k));
        if 0 < i && i < 10 && 0 < j && j < 10 && 0 < k && k < ROWS {
            let h = (top(k) - top(k - 1)).min(top(k + 1) - top(k));
            q += DVec3::new(next() * 0.025, next() * 0.025, next() * h) / 5.0;
        }
        *p = q;
        rows.push(if 0 < i && i < 10 && 0 < j && j < 10 { k } else { usize::MAX });
    }
    if wedges {
        let halves: Vec<[u32; 6]> = (0..m.element_count())
            .flat_map(|e| {
                let [a, b, c, d, e, f, g, h] = std::array::from_fn(|i| m.element(e)[i]);
                [[a, b, d, e, f, h], [b, c, d, f, g, h]]
            })
            .collect();
        m = VolumeMesh::from_elements(m.nodes().to_vec(), halves.iter().map(|w| (VolumeKind::Wedge6, &w[..]))).unwrap();
    }
    (Model::Volume(m), rows)
}

/// The median height of a 3D layer's first row: each interior column's node above the
/// wall.
fn first_row_3d(model: &Model, rows: &[usize]) -> f64 {
    let Model::Volume(m) = model else { unreachable!("a volume") };
    let mut h: Vec<f64> = m.nodes().iter().zip(rows).filter(|&(_, &k)| k == 1).map(|(p, _)| p.z).collect();
    h.sort_by(f64::total_cmp);
    h[h.len() / 2]
}

/// The defaults keep a 3D layer's first row within 5 %, of hexahedra and of wedges (the
/// fit to the targets, then the passes: `docs/formulas.md`, Targets), and lift its
/// dihedral angles; the ideal target thickens the row.
#[test]
fn the_defaults_keep_a_3d_boundary_layer_s_first_row() {
    for wedges in [false, true] {
        a_3d_layer_keeps_its_first_row(wedges);
    }
}

fn a_3d_layer_keeps_its_first_row(wedges: bool) {
    let (input, rows) = layer_3d(wedges);
    let (h0, s0) = (first_row_3d(&input, &rows), input.stats());
    let mut stretched = input.clone();
    let report = stretched.smooth(&Smoothing::default()).unwrap();
    assert_eq!(report.target(), Target::Stretch);
    assert!(report.passes()[0].counts.fit_steps > 0, "wedges {wedges}: the fit kept no step");
    let (h, s) = (first_row_3d(&stretched, &rows), stretched.stats());
    assert!((h / h0 - 1.0).abs() < 0.05, "wedges {wedges}: first row {h0} → {h}");
    let (lo, hi) = ((s0.min_angle_deg, s.min_angle_deg), (s0.max_angle_deg, s.max_angle_deg));
    assert!(lo.1 > lo.0 + 10.0 && hi.1 < hi.0 - 10.0, "wedges {wedges}: angles {lo:?}, {hi:?}");
    let mut ideal = input;
    ideal.smooth(&Smoothing::default().target(Target::Ideal)).unwrap();
    assert!(first_row_3d(&ideal, &rows) > 1.15 * h0, "wedges {wedges}: the ideal kept the row ({})", first_row_3d(&ideal, &rows));
}

/// The planar quad mesh `m` bent a quarter turn about the y axis (its x from 0 to 1 on a
/// quarter circle, its y kept): a surface in 3D, read back from a legacy VTK file.
pub(crate) fn bent(m: &smoothlab::mesh::Mesh) -> smoothlab::model::Model {
    use std::fmt::Write;
    let r = 2.0 / std::f64::consts::PI;
    let mut vtk = format!("# vtk DataFile Version 2.0\nbent\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS {} double\n", m.node_count());
    for p in m.nodes() {
        writeln!(vtk, "{:?} {:?} {:?}", r * (p.x / r).sin(), p.y, r * (1.0 - (p.x / r).cos())).unwrap();
    }
    writeln!(vtk, "CELLS {} {}", m.element_count(), 5 * m.element_count()).unwrap();
    for e in 0..m.element_count() {
        let c = m.element(e);
        writeln!(vtk, "4 {} {} {} {}", c[0], c[1], c[2], c[3]).unwrap();
    }
    writeln!(vtk, "CELL_TYPES {}\n{}", m.element_count(), "9\n".repeat(m.element_count())).unwrap();
    let model = smoothlab::io::read_model_str(&vtk, smoothlab::io::Format::Vtk).unwrap();
    assert!(matches!(model, smoothlab::model::Model::Surface(_)), "a bent mesh reads as a surface");
    model
}
