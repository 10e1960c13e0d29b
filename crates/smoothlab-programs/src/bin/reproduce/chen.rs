//! §2: Chen, Tristano & Kwok (2003), Figs 13–15, the perturbed plate with a hole.

use std::fmt::Write as _;

use smoothlab::generate::{perturb, plate, PlateKind};
use smoothlab::quality::mesh_stats;
use smoothlab::smooth::{Order, Strategy};
use smoothlab_page::lab::tour::measured::Table;

use crate::common::{mean, mean_range, opts, run, untangled, NEW_DESIGNS};
use crate::report::Report;

/// The plates of §2 (and §9's comparison): their names, kinds and orders.
pub(crate) const PLATES: [(&str, PlateKind, u8); 6] = [
    ("tri", PlateKind::Tri, 1),
    ("quad", PlateKind::Quad, 1),
    ("mixed", PlateKind::Mixed, 1),
    ("tri, order 2", PlateKind::Tri, 2),
    ("quad, order 2", PlateKind::Quad, 2),
    ("mixed, order 2", PlateKind::Mixed, 2),
];

pub(crate) fn chen_plate(out: &mut Report) {
    const SEEDS: [u64; 5] = [1, 2, 3, 4, 5];
    const AMOUNTS: [f64; 5] = [0.6, 0.8, 1.0, 1.25, 1.5];
    const MAX_PASSES: u32 = 10;
    out.section(2, "Chen, Tristano & Kwok (2003), Figs 13–15: the perturbed plate with a hole");
    let _ = writeln!(
        out,
        "`plate(kind, order, 4)`: the square [−1,1]² with a hole of radius 0.4, an O-grid of 32 nodes round the hole \
         and the square and 8 rings (order 2: 6-node triangles / 8-node quads with the mid-side nodes of the hole on \
         the circle, so those edges are curved). Every interior node is moved by `perturb(mesh, amount, seed)`, a \
         uniform random offset in a disk of radius amount × the mean edge length — Chen's \"perturbing the nodal \
         locations of each interior node randomly\" — for amounts {} and seeds {}: {} plates. Then `new` + `rules` \
         pass after pass (at most {MAX_PASSES}) until no element is inverted, in priority and in input order, with \
         each design of the penalty. Cells: passes to 0 inverted, mean [min–max] over the seeds, and how many seeds \
         were not untangled in {MAX_PASSES}; \"min angle after\" is over the seeds after the last pass (negative: not \
         untangled). Chen: untangled in 3 passes with priority (§5.2; §4.2 says 4) against 7 in \"first come first \
         serve\" order; Chen's amount is not stated, their picture shows nodes pushed outside the plate, as ours from \
         1.0 on.\n",
        AMOUNTS.map(|a| a.to_string()).join(", "),
        SEEDS.map(|a| a.to_string()).join(", "),
        6 * AMOUNTS.len() * SEEDS.len()
    );
    let mut table = Table::new(&[
        "plate",
        "amount",
        "inverted at start",
        "barrier: priority",
        "barrier: input order",
        "barrier: min angle after (priority)",
        "angle design: priority",
        "angle design: input order",
    ]);
    // per design and order: (untangled within 3, in the first pass, within MAX_PASSES, passes summed)
    let mut tally = [[(0usize, 0usize, 0usize, 0usize); 2]; 2];
    let mut runs = 0usize;
    let mut example: Option<(String, Vec<usize>, Vec<usize>)> = None;
    for (label, kind, order) in PLATES {
        let base = plate(kind, order, 4).expect("plate");
        for amount in AMOUNTS {
            let mut start = vec![];
            let mut ang = vec![];
            // [design][order] → (passes of the untangled runs, failures)
            let mut cells: [[(Vec<f64>, usize); 2]; 2] = Default::default();
            runs += SEEDS.len();
            for &seed in &SEEDS {
                let m = perturb(&base, amount, seed).expect("perturb");
                start.push(mesh_stats(&m).inverted as f64);
                for (d, (choice, _)) in NEW_DESIGNS.iter().enumerate() {
                    let mut trajectories = Vec::new();
                    for (o, node_order) in [Order::Priority, Order::Input].into_iter().enumerate() {
                        let r = run(&m, *choice, opts(Strategy::Rules, node_order), MAX_PASSES, untangled);
                        let t = &mut tally[d][o];
                        match r.passes_to_valid() {
                            Some(n) => {
                                cells[d][o].0.push(n as f64);
                                t.0 += (n <= 3) as usize;
                                t.1 += (n == 1) as usize;
                                t.2 += 1;
                                t.3 += n;
                            }
                            None => cells[d][o].1 += 1,
                        }
                        if d == 0 && o == 0 {
                            ang.push(r.passes.last().expect("a pass").after.min_angle_deg);
                        }
                        let s0 = mesh_stats(&m).inverted;
                        trajectories
                            .push(std::iter::once(s0).chain(r.passes.iter().map(|p| p.after.inverted)).collect());
                    }
                    if example.is_none() && d == 0 && label == "tri" && amount == 1.5 {
                        let i = trajectories.pop().expect("input");
                        let p = trajectories.pop().expect("priority");
                        example = Some((format!("tri plate, amount 1.5, seed {seed}, barrier"), p, i));
                    }
                }
            }
            let passes = |(v, fail): &(Vec<f64>, usize)| {
                let mut s = if v.is_empty() {
                    "—".to_string()
                } else {
                    format!(
                        "{:.1} [{:.0}–{:.0}]",
                        mean(v),
                        v.iter().cloned().fold(f64::INFINITY, f64::min),
                        v.iter().cloned().fold(0.0, f64::max)
                    )
                };
                if *fail > 0 {
                    let _ = write!(s, " ({fail} not in {MAX_PASSES})");
                }
                s
            };
            table.row(vec![
                label.to_string(),
                amount.to_string(),
                mean_range(&start, 0),
                passes(&cells[0][0]),
                passes(&cells[0][1]),
                mean_range(&ang, 1),
                passes(&cells[1][0]),
                passes(&cells[1][1]),
            ]);
        }
    }
    out.table(table);
    let _ = writeln!(out);
    // the plates untangled, per design and order, summed over every row above
    let within = format!("untangled within {MAX_PASSES}");
    let mut summary = Table::new(&[
        "penalty design",
        "order",
        "plates",
        "untangled within 3 passes",
        "in the first pass",
        &within,
        "passes on average",
    ]);
    for (d, (_, design)) in NEW_DESIGNS.iter().enumerate() {
        for (o, name) in ["priority", "input"].iter().enumerate() {
            let (w3, first, ok, sum) = tally[d][o];
            summary.row(vec![
                design.to_string(),
                name.to_string(),
                runs.to_string(),
                w3.to_string(),
                first.to_string(),
                ok.to_string(),
                if ok > 0 { format!("{:.2}", sum as f64 / ok as f64) } else { "—".into() },
            ]);
        }
    }
    out.table(summary);
    let _ = writeln!(out);
    if let Some((name, p, i)) = example {
        let list = |v: &Vec<usize>| v.iter().map(|n| n.to_string()).collect::<Vec<_>>().join(" → ");
        let _ = writeln!(
            out,
            "Inverted elements after each pass ({name}; first number: before smoothing):\n\n\
             - priority order: {}\n- input order: {}\n",
            list(&p),
            list(&i)
        );
    }
}
