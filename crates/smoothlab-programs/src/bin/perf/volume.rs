//! Issue 33: the 3D passes, on rand3D and on a valid block of hexahedra.

use std::fmt::Write as _;
use std::time::Instant;

use smoothlab::objective::{solid_objective, CornerStar, ObjectiveKind};
use smoothlab::smooth::{DriverStar, Order, SmoothOptions, Strategy, DEFAULT_MAX_ITER};
use smoothlab::volume::{volume_stats, VolumeMesh, VolumeSmoother};

use crate::common::{fmt_ns, median};

/// The seed of rand3D, as `benches/smoothing.rs` (`tetrahedra`) and Freitag's Table 2's first.
const RAND3D_SEED: u64 = 1;
/// The block of hexahedra: `HEX_CELLS³` cells of the unit cube (about rand3D's node count),
/// every free node moved by up to `HEX_AMOUNT` mean edge lengths (`perturb_volume`,
/// seed 1), a perturbation small enough that every hexahedron stays valid.
const HEX_CELLS: usize = 10;
const HEX_AMOUNT: f64 = 0.2;

/// The 3D passes: name, strategy, objective, order and solver iterations per call.
const VOLUME_PASSES: [(&str, Strategy, ObjectiveKind, Order, u32); 8] = [
    ("laplace", Strategy::Laplace, ObjectiveKind::SmoothShape, Order::Input, DEFAULT_MAX_ITER),
    ("smart", Strategy::Smart, ObjectiveKind::SmoothShape, Order::Input, DEFAULT_MAX_ITER),
    ("opt+new", Strategy::Opt, ObjectiveKind::SmoothShape, Order::Input, DEFAULT_MAX_ITER),
    ("rules+new, priority order", Strategy::Rules, ObjectiveKind::SmoothShape, Order::Priority, DEFAULT_MAX_ITER),
    ("opt+old, 20 it", Strategy::Opt, ObjectiveKind::MaxMinShape, Order::Input, 20),
    ("opt+sine", Strategy::Opt, ObjectiveKind::Sine, Order::Input, DEFAULT_MAX_ITER),
    ("opt+condition", Strategy::Opt, ObjectiveKind::Condition, Order::Input, DEFAULT_MAX_ITER),
    ("opt+untangle", Strategy::Opt, ObjectiveKind::Untangle, Order::Input, DEFAULT_MAX_ITER),
];

/// A volume mesh measured by the 3D section: its words, sizes and the measured corners of
/// its free nodes' stars.
struct VolumeBench {
    what: String,
    mesh: VolumeMesh,
    free: usize,
    /// Σ over the free nodes of their stars' measured corners (`CornerStar::tets`: one
    /// per tetrahedron; a hexahedron's corners whose corner tetrahedron holds the node).
    corners: usize,
}

impl VolumeBench {
    fn new(what: String, mesh: VolumeMesh) -> Self {
        let mut star = CornerStar::default();
        let free = mesh.free_count();
        let corners = (0..mesh.node_count())
            .filter(|&n| mesh.is_free(n))
            .map(|n| {
                star.gather(&mesh, n);
                star.tets.len()
            })
            .sum();
        VolumeBench { what, mesh, free, corners }
    }
    fn corners_per_node(&self) -> f64 {
        self.corners as f64 / self.free.max(1) as f64
    }
}

/// One 3D pass on one mesh: ns per free node, visits per free node, ns per measured corner.
#[derive(Clone, Copy)]
pub(crate) struct VolumeFigure {
    pub(crate) ns_per_node: f64,
    visits_per_node: f64,
    pub(crate) ns_per_corner: f64,
}

pub(crate) struct VolumeReport {
    meshes: [VolumeBench; 2],
    reps: usize,
    /// (pass, [rand3D, hexahedra])
    rows: Vec<(&'static str, [VolumeFigure; 2])>,
}

impl VolumeReport {
    /// The figure of pass `name` on mesh `i` (0 rand3D, 1 hexahedra).
    pub(crate) fn get(&self, name: &str, i: usize) -> Option<VolumeFigure> {
        self.rows.iter().find(|r| r.0 == name).map(|r| r.1[i])
    }
}

/// The 3D passes on rand3D and on a valid block of hexahedra: one sweep
/// (`VolumeSmoother::sweep`, no statistics), median of a few on fresh copies.
pub(crate) fn measure_volume(quick: bool) -> VolumeReport {
    use smoothlab::generate::{hex_grid, perturb_volume, rand3d, HexBlock, RAND3D_POINTS};
    let tet = rand3d(RAND3D_POINTS, RAND3D_SEED).expect("rand3d");
    let tet_words = format!(
        "Freitag's rand3D (`rand3d({RAND3D_POINTS}, {RAND3D_SEED})`, as the criterion bench): {} nodes, {} tetrahedra",
        tet.node_count(),
        tet.element_count()
    );
    let block = hex_grid(&HexBlock::cube(HEX_CELLS)).expect("a block of hexahedra");
    let hex = perturb_volume(&block, HEX_AMOUNT, 1).expect("perturbed");
    assert_eq!(volume_stats(&hex).inverted, 0, "the perturbed block of hexahedra is valid");
    let hex_words = format!(
        "a block of hexahedra (`hex_grid(&HexBlock::cube({HEX_CELLS}))`, every free node moved by up to {HEX_AMOUNT} mean edge lengths by `perturb_volume`, seed 1; every hexahedron valid): {} nodes, {} hexahedra",
        hex.node_count(),
        hex.element_count()
    );
    let meshes = [VolumeBench::new(tet_words, tet), VolumeBench::new(hex_words, hex)];
    let reps = if quick { 3 } else { 21 };
    let rows = VOLUME_PASSES
        .iter()
        .map(|&(name, strategy, kind, order, max_iter)| {
            let obj = solid_objective(kind).expect("a form on tetrahedra");
            let o = SmoothOptions::default().with_strategy(strategy).with_order(order).with_max_iter(max_iter);
            let mut smoothers = [0, 1].map(|_| VolumeSmoother::new(o).expect("options"));
            // the two meshes' passes alternate, so that both see the machine as it is (the
            // ratio of their medians is what the target reads); per free node, the visits
            // kept apart
            let (mut ns, mut visits) = ([Vec::new(), Vec::new()], [0; 2]);
            for _ in 0..reps {
                for (i, s) in smoothers.iter_mut().enumerate() {
                    let mut m = meshes[i].mesh.clone();
                    let t = Instant::now();
                    visits[i] = s.sweep(&mut m, &*obj).visits;
                    ns[i].push(t.elapsed().as_nanos() as f64 / meshes[i].free.max(1) as f64);
                }
            }
            let figures = [0, 1].map(|i| {
                let (b, ns) = (&meshes[i], median(std::mem::take(&mut ns[i])));
                VolumeFigure {
                    ns_per_node: ns,
                    visits_per_node: visits[i] as f64 / b.free.max(1) as f64,
                    ns_per_corner: ns / b.corners_per_node(),
                }
            });
            (name, figures)
        })
        .collect();
    VolumeReport { meshes, reps, rows }
}

pub(crate) fn volume_section(v: &VolumeReport) -> String {
    let mut w = String::new();
    let [tet, hex] = &v.meshes;
    let _ = writeln!(w, "## Tetrahedra and hexahedra, ns per free node and pass (issue 33)\n");
    let _ = writeln!(
        w,
        "The 3D passes on {} ({} free nodes, {:.1} measured corners per free node), and on {} ({} free nodes, {:.1} measured corners per free node). \
         A pass is one sweep over the free nodes (`VolumeSmoother::sweep`, no statistics), the median of {} passes each on a fresh copy of the mesh, the two meshes alternating. \
         Figures are per free node, and per measured corner of its star (`CornerStar::tets`: a tetrahedron gives one corner, a hexahedron 4). \
         Issue 33's target: hexahedra no slower per corner than tetrahedra (hex / tet ≤ 1).\n",
        tet.what,
        tet.free,
        tet.corners_per_node(),
        hex.what,
        hex.free,
        hex.corners_per_node(),
        v.reps
    );
    let _ = writeln!(w, "| pass | rand3D per free node | visits per free node | per corner | hexahedra per free node | visits per free node | per corner | hex / tet per corner (target ≤ 1) |");
    let _ = writeln!(w, "|---|---:|---:|---:|---:|---:|---:|---:|");
    for (name, [t, h]) in &v.rows {
        let ratio = h.ns_per_corner / t.ns_per_corner;
        let _ = writeln!(
            w,
            "| {name} | {} | {:.2} | {} | {} | {:.2} | {} | {ratio:.2} {} |",
            fmt_ns(t.ns_per_node),
            t.visits_per_node,
            fmt_ns(t.ns_per_corner),
            fmt_ns(h.ns_per_node),
            h.visits_per_node,
            fmt_ns(h.ns_per_corner),
            if ratio <= 1.0 { "✓" } else { "✗" }
        );
    }
    let _ = writeln!(w, "\nFigures in ns unless marked µs.\n");
    w
}
