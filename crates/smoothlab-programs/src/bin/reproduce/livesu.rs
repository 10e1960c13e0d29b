//! §12: Livesu et al.'s real hexahedral meshes with the boundary fixed.

use std::fmt::Write as _;

use smoothlab::model::Model;
use smoothlab::{MeshStats, Smoothing, VolumeMesh};
use smoothlab_page::lab::tour::measured::Table;

use crate::common::meshes_dir;
use crate::report::Report;

/// The inputs the defaults untangle with their boundary fixed, with the published
/// outputs' smallest and mean scaled Jacobian (`../shared/meshes/README.md`).
const LIVESU: [(&str, f64, f64); 6] = [
    ("block", 0.250, 0.870),
    ("block_stresstest", 0.250, 0.834),
    ("bunny", 0.606, 0.972),
    ("cap", 0.106, 0.870),
    ("dancingchildren", 0.354, 0.942),
    ("hanger_stresstest", 0.716, 0.987),
];

/// The smallest and the mean of the elements' smallest corner scaled Jacobians.
fn scaled_jacobians(m: &VolumeMesh) -> (f64, f64) {
    let sj: Vec<f64> = (0..m.element_count()).map(|e| m.measures(e).scaled_jacobian).collect();
    (sj.iter().copied().fold(f64::INFINITY, f64::min), sj.iter().sum::<f64>() / sj.len() as f64)
}

pub(crate) fn livesu(out: &mut Report) {
    out.section(12, "Real hexahedral meshes (Livesu et al. 2015), the boundary fixed");
    let _ = writeln!(
        out,
        "The inputs of Livesu, Sheffer, Vining and Tarini's \"Practical Hex-Mesh Optimization via Edge-Cone \
         Rectification\" (SIGGRAPH 2015) that the defaults untangle with their boundary skin fixed. \"SJ\" is the \
         smallest corner scaled Jacobian of an element; min and mean are over the elements, as the published figures \
         are. \"no finish\" is the defaults with `--finish 0`; \"defaults\" adds the finish (`docs/formulas.md` §4). \
         \"cap\" is the most any smoother can reach with the boundary where it is: a corner whose node and two edge \
         neighbours are fixed has an SJ of at most the sine of the angle between those two edges \
         (`VolumeMesh::scaled_jacobian_cap`). The published outputs move the boundary (issue 58).\n"
    );
    let root = meshes_dir().join("livesu2015");
    if !root.is_dir() {
        let _ = writeln!(out, "*Skipped: the external meshes (`../shared/meshes/livesu2015`) were not found.*\n");
        return;
    }
    let mut table = Table::new(&[
        "mesh",
        "hexahedra",
        "inverted at start",
        "no finish: inverted, min / mean SJ",
        "defaults: inverted, min / mean SJ, time",
        "cap",
        "published: min / mean SJ",
    ]);
    let (mut reached, mut below_cap) = (Vec::new(), Vec::new());
    for (name, published_min, published_mean) in LIVESU {
        let Ok(Model::Volume(input)) = smoothlab::read(root.join(format!("{name}_in.mesh"))) else {
            table.row(vec![format!("`{name}`"), "not read as a volume".into(), String::new(), String::new(), String::new(), String::new(), String::new()]);
            continue;
        };
        let inverted = |s: &MeshStats| s.inverted;
        let start = input.element_count();
        let at_start = (0..start).filter(|&e| input.is_inverted(e)).count();
        let run = |smoothing: Smoothing| {
            let mut m = Model::Volume(input.clone());
            let report = m.smooth(&smoothing).expect("the defaults take every volume");
            let Model::Volume(v) = m else { unreachable!("smoothing keeps the kind") };
            (report, v)
        };
        let (plain, p) = run(Smoothing::default().finish(0));
        let (full, f) = run(Smoothing::default());
        let ((p_min, p_mean), (f_min, f_mean)) = (scaled_jacobians(&p), scaled_jacobians(&f));
        let cap = input.scaled_jacobian_cap();
        if f_min >= published_min {
            reached.push(format!("`{name}`"));
        }
        if cap < published_min {
            below_cap.push(format!("`{name}`"));
        }
        table.row(vec![
            format!("`{name}`"),
            start.to_string(),
            at_start.to_string(),
            format!("{}, {p_min:.3} / {p_mean:.3}", inverted(plain.stats())),
            format!("{}, {f_min:.3} / {f_mean:.3}, {:.0} ms", inverted(full.stats()), full.time_ms()),
            format!("{cap:.3}"),
            format!("{published_min:.3} / {published_mean:.3}"),
        ]);
    }
    out.table(table);
    let _ = writeln!(
        out,
        "\nThe defaults reach the published smallest SJ on {}. The published value lies above the cap, out of reach \
         with the boundary fixed, on {}.\n",
        if reached.is_empty() { "none".to_string() } else { reached.join(", ") },
        if below_cap.is_empty() { "none".to_string() } else { below_cap.join(", ") }
    );
}
