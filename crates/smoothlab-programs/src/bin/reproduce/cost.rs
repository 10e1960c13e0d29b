//! §6: the cost of a node visit with each design of the penalty.

use std::fmt::Write as _;

use smoothlab::generate::rand2d;
use smoothlab::smooth::{Order, Strategy};
use smoothlab_page::lab::tour::measured::Table;

use crate::common::{never, opts, run, NEW_DESIGNS};
use crate::report::Report;

/// Time per node visit of `new` with each penalty design, one pass on a fresh rand2D,
/// alternating the designs, the median of 5 runs each.
pub(crate) fn visit_cost(out: &mut Report) {
    const RUNS: usize = 5;
    let mesh = rand2d(10_000, 100, 2003).expect("rand2d");
    out.section(6, "The cost of a node visit: the two designs of the penalty");
    let _ = writeln!(
        out,
        "One pass over `rand2d(10000, 100, 2003)` ({} nodes, {} triangles, valid: no untangling sweeps), each \
         design in turn, {RUNS} times; the median time of the node loop over its visits. The barrier evaluates one \
         square root per sub-triangle, the angle design one `atan2` and two `exp` per angle, two angles per \
         sub-triangle.\n",
        mesh.node_count(),
        mesh.element_count()
    );
    let mut table = Table::new(&["strategy", "barrier: ns per visit", "angle design: ns per visit", "barrier / angle"]);
    for (label, o) in [
        ("`opt` (every visit optimises)", opts(Strategy::Opt, Order::Input)),
        ("`rules`, priority order", opts(Strategy::Rules, Order::Priority)),
    ] {
        let mut ns = [Vec::new(), Vec::new()];
        for _ in 0..RUNS {
            for (d, (choice, _)) in NEW_DESIGNS.iter().enumerate() {
                let r = run(&mesh, *choice, o, 1, never);
                let p = &r.passes[0];
                ns[d].push(p.elapsed_ms * 1e6 / p.counts.visits as f64);
            }
        }
        let median = |v: &mut Vec<f64>| {
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        };
        let (b, a) = (median(&mut ns[0]), median(&mut ns[1]));
        table.row(vec![label.to_string(), format!("{b:.0}"), format!("{a:.0}"), format!("{:.2}", b / a)]);
    }
    out.table(table);
    let _ = writeln!(out);
}
