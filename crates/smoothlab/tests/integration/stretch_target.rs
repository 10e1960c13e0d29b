//! The stretch target (issue 57): a boundary layer smoothed with the defaults keeps its
//! first row, where the ideal target thickens it; a mesh with no stretch made on purpose
//! is smoothed exactly as against the ideal.

use glam::DVec2;
use smoothlab::generate::{grid, rand2d, GridKind};
use smoothlab::model::Model;
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

/// A 40 × 30 boundary layer of `kind`, its interior nodes moved by up to a fifth of their
/// cell each way (a fixed sequence of pseudo-random numbers).
fn layer(kind: GridKind) -> Model {
    let mut m = grid(NX, NY, kind).unwrap();
    let mut state = 0x2545_f491_4f6c_dd1d_u64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
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
        // the input's own median is off the design by its noise (±4 %): the smoothed row
        // comes back near the design, within 7 % of the input (docs/formulas.md, Targets)
        assert!((h / h0 - 1.0).abs() < 0.07, "{kind:?}: first row {h0} → {h}");
        assert!(s.min_angle_deg >= s0.min_angle_deg && s.max_angle_deg <= s0.max_angle_deg, "{kind:?}: angles worse");
        assert!(s.min_angle_deg > s0.min_angle_deg, "{kind:?}: the smallest angle not lifted");
        // the ideal target pulls the wall's row toward squares
        let mut ideal = input.clone();
        ideal.smooth(&Smoothing::default().target(Target::Ideal)).unwrap();
        assert!(first_row(&ideal) > 1.3 * h0, "{kind:?}: the ideal kept the row ({})", first_row(&ideal));
    }
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
