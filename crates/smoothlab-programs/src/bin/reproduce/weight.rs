//! §7: how the barrier's weight k1 was chosen.

use std::fmt::Write as _;

use smoothlab::generate::{rand2d, GridKind};
use smoothlab::objective::{ChenTristanoKwok, ObjectiveKind, RegularisedBarrier, BARRIER_WEIGHT};
use smoothlab::quality::mesh_stats;
use smoothlab::smooth::{Order, Strategy};
use smoothlab::Mesh;
use smoothlab_page::lab::tour::measured::Table;

use crate::common::{mean, never, opts, run, run_with, untangled, Run};
use crate::knupp::random_grid;
use crate::report::Report;

/// How `k1` was chosen: the Table 1 figures and Knupp's grids for a range of weights.
pub(crate) fn barrier_weight(out: &mut Report) {
    let meshes: Vec<Mesh> = (1..=5).map(|s| rand2d(500, 20, s).expect("rand2d")).collect();
    let grids: Vec<Mesh> = [GridKind::Quad, GridKind::Tri]
        .into_iter()
        .flat_map(|k| (1..=5u64).map(move |seed| random_grid(k, seed)))
        .collect();
    // k1 was chosen on the page's opening sample of the time, the tangled quad plate
    let page = smoothlab_page::lab::sample::Sample::PlateQuadTangled.generate().expect("sample");
    let page_stats = |r: Run| {
        let s = mesh_stats(&r.mesh);
        (s.min_angle_deg, s.mean_quality, s.inverted)
    };
    let old_page = page_stats(run(&page, ObjectiveKind::MaxMinShape, opts(Strategy::Rules, Order::Priority), 3, never));
    out.section(7, "Choosing the barrier's weight k1");
    let _ = writeln!(
        out,
        "`new` + `rules` with the defaults but for k1 (ε = {}): the mean min / max angle and mean α after 3 passes \
         on the rand2D meshes of §1, the passes to 0 inverted on the ten random grids of §4 (at most 10), and the \
         tangled quad plate (`plate-quad-tangled`, the page's opening sample when k1 was chosen; §8) after 3 passes against the old side's max-min \
         objective (same rules and order): {:.2}° min angle, mean β {:.4}. The default is k1 = {BARRIER_WEIGHT}.\n",
        smoothlab::objective::BARRIER_EPSILON,
        old_page.0,
        old_page.1,
    );
    let mut table = Table::new(&[
        "k1",
        "rand2D: min angle",
        "max angle",
        "mean α",
        "random grids: untangled (most passes)",
        "tangled quad plate: inverted, min angle, mean β",
    ]);
    for k1 in [0.02, 0.05, 0.1, 0.15, 0.2, 0.3, 0.5, 1.0] {
        let obj = ChenTristanoKwok::Barrier(RegularisedBarrier { k1, ..RegularisedBarrier::default() });
        let o = opts(Strategy::Rules, Order::Priority);
        let (mut mn, mut mx, mut q) = (vec![], vec![], vec![]);
        for m in &meshes {
            let r = run_with(m, &obj, o, 3, never);
            let last = r.passes.last().expect("three passes");
            mn.push(last.after.min_angle_deg);
            mx.push(last.after.max_angle_deg);
            q.push(mesh_stats(&r.mesh).mean_quality);
        }
        let passes: Vec<Option<usize>> =
            grids.iter().map(|g| run_with(g, &obj, o, 10, untangled).passes_to_valid()).collect();
        let most = passes
            .iter()
            .map(|p| p.map_or("not in 10".to_string(), |n| n.to_string()))
            .max_by_key(|s| (s.len(), s.clone()));
        let untangled_count = passes.iter().filter(|p| p.is_some()).count();
        let (pa, pq, pi) = page_stats(run_with(&page, &obj, o, 3, never));
        table.row(vec![
            k1.to_string(),
            format!("{:.2}", mean(&mn)),
            format!("{:.1}", mean(&mx)),
            format!("{:.4}", mean(&q)),
            format!("{untangled_count} of {} ({})", grids.len(), most.unwrap_or_default()),
            format!("{pi}, {pa:.2}°, {pq:.4}"),
        ]);
    }
    out.table(table);
    let _ = writeln!(out);
}
