//! §1: Freitag (1997), Table 1 on rand2D.

use std::fmt::Write as _;

use smoothlab::generate::rand2d;
use smoothlab::objective::ObjectiveKind;
use smoothlab::quality::{element_quality, mesh_stats};
use smoothlab::smooth::{Measure, Order, PassRecord, SmoothOptions, Strategy};
use smoothlab::Mesh;

use smoothlab_page::lab::tour::measured::Table;

use crate::common::{mean, mean_range, never, opts, run, Choice, NEW_ANGLE, NEW_DESIGNS};
use crate::report::Report;

/// Table 1's row of `new` + `rules` in priority order with Newton's first trial off.
const CHEN_ALONE: &str = "rules, `new`, priority, Chen's search alone (no Newton step)";

/// Freitag's figures for rand2D: (row, min angle, max angle, Laplacian, optimization).
const FREITAG_TABLE_1: [(&str, f64, f64, u32, u32); 15] = [
    ("original", 0.714, 175.92, 0, 0),
    ("Lap", 10.50, 156.2, 1500, 0),
    ("Opt", 18.20, 143.5, 0, 1500),
    ("C1 5°", 10.37, 156.3, 1457, 43),
    ("C1 10°", 12.24, 149.1, 1337, 163),
    ("C1 15°", 15.95, 148.0, 1107, 393),
    ("C1 30°", 18.20, 143.5, 258, 1242),
    ("C2 5°", 10.47, 156.3, 1500, 5),
    ("C2 10°", 11.52, 154.8, 1500, 23),
    ("C2 15°", 16.28, 145.8, 1500, 54),
    ("C2 30°", 18.55, 140.5, 1500, 593),
    ("C3 5°", 5.26, 166.0, 23, 5),
    ("C3 10°", 10.01, 155.1, 65, 24),
    ("C3 15°", 15.00, 148.8, 132, 58),
    ("C3 30°", 18.55, 140.5, 749, 609),
];

fn paper_row(name: &str) -> String {
    FREITAG_TABLE_1
        .iter()
        .find(|r| r.0 == name)
        .map(|r| format!("{:.2} / {:.1} ({} / {})", r.1, r.2, r.3, r.4))
        .unwrap_or_else(|| "—".into())
}

pub(crate) struct Row {
    pub(crate) name: String,
    pub(crate) paper: String,
    pub(crate) min: Vec<f64>,
    pub(crate) max: Vec<f64>,
    pub(crate) lap: Vec<f64>,
    pub(crate) opt: Vec<f64>,
    pub(crate) ms: Vec<f64>,
}

pub(crate) fn freitag_table_1(out: &mut Report) {
    const SEEDS: [u64; 5] = [1, 2, 3, 4, 5];
    let meshes: Vec<Mesh> = SEEDS.iter().map(|&s| rand2d(500, 20, s).expect("rand2d")).collect();
    let nodes = meshes[0].node_count();
    let tris = meshes[0].element_count();
    // Freitag's configuration: her measure (the min sine) for the smart Laplacian and the
    // thresholds, node order as numbered.
    let freitag = |s: Strategy| opts(s, Order::Input).with_smart_measure(Measure::MinSine);
    let mut configs: Vec<(String, String, Choice, SmoothOptions)> = vec![
        ("laplace (plain)".into(), paper_row("Lap"), ObjectiveKind::Sine.into(), freitag(Strategy::Laplace)),
        ("smart (min sine)".into(), "—".into(), ObjectiveKind::Sine.into(), freitag(Strategy::Smart)),
        ("opt, `sine`".into(), paper_row("Opt"), ObjectiveKind::Sine.into(), freitag(Strategy::Opt)),
        ("opt, `old` (α)".into(), "—".into(), ObjectiveKind::MaxMinShape.into(), freitag(Strategy::Opt)),
    ];
    for (s, n) in [(Strategy::C1, "C1"), (Strategy::C2, "C2"), (Strategy::C3, "C3")] {
        for t in [5.0, 10.0, 15.0, 30.0] {
            let name = format!("{n} {t}°");
            configs.push((
                format!("{name}, `sine`"),
                paper_row(&name),
                ObjectiveKind::Sine.into(),
                freitag(s).with_threshold_deg(t),
            ));
        }
    }
    for (choice, _) in NEW_DESIGNS {
        let tag = if choice == NEW_ANGLE { " (angle design)" } else { "" };
        for (name, o) in [
            ("opt, `new`", opts(Strategy::Opt, Order::Input)),
            ("rules, `new`, input order", opts(Strategy::Rules, Order::Input)),
            ("rules, `new`, priority", opts(Strategy::Rules, Order::Priority)),
            ("rules, `new`, priority, 10 iterations/call", opts(Strategy::Rules, Order::Priority).with_max_iter(10)),
        ] {
            configs.push((format!("{name}{tag}"), "—".into(), choice, o));
        }
        if choice != NEW_ANGLE {
            // the default tries Newton's step first (the barrier design has a Hessian);
            // Chen's search alone for comparison (`docs/performance.md`)
            let o = opts(Strategy::Rules, Order::Priority).with_newton(false);
            configs.push((format!("{CHEN_ALONE}{tag}"), "—".into(), choice, o));
        }
    }

    let mut rows = Vec::new();
    let orig: Vec<PassRecord> = Vec::new();
    let _ = orig;
    let mut inverted_after = Vec::new();
    let mut original = Row {
        name: "original".into(),
        paper: paper_row("original"),
        min: vec![],
        max: vec![],
        lap: vec![],
        opt: vec![],
        ms: vec![],
    };
    for m in &meshes {
        let s = mesh_stats(m);
        original.min.push(s.min_angle_deg);
        original.max.push(s.max_angle_deg);
    }
    rows.push(original);
    for (name, paper, kind, o) in &configs {
        let mut row = Row {
            name: name.clone(),
            paper: paper.clone(),
            min: vec![],
            max: vec![],
            lap: vec![],
            opt: vec![],
            ms: vec![],
        };
        for m in &meshes {
            let r = run(m, *kind, *o, 3, never);
            let last = r.passes.last().expect("three passes");
            if name == "rules, `new`, priority" {
                inverted_after.push(last.after.inverted);
            }
            row.min.push(last.after.min_angle_deg);
            row.max.push(last.after.max_angle_deg);
            row.lap.push(r.laplacian_moves() as f64);
            row.opt.push(r.optimization_calls() as f64);
            row.ms.push(r.ms());
        }
        rows.push(row);
    }
    out.section(1, "Freitag (1997), Table 1: rand2D");
    let _ = writeln!(
        out,
        "`rand2d(500, 20, seed)` for seeds 1–5: the Delaunay triangulation of 500 uniform random points in the unit \
         square plus 20 equally spaced points per side ({nodes} nodes, {tris} triangles, as Freitag's), boundary fixed, \
         3 passes. Each cell is the mean over the five seeds with the range in brackets. Freitag's rows use her \
         measure: the smart Laplacian must raise the star's smallest sine, the thresholds of C1/C2/C3 are on the \
         smallest sine, the optimizer maximises the smallest sine (`sine`, active-set ascent); nodes in input order. \
         \"Laplacian moves\" counts nodes moved by a (plain or smart) Laplacian step, \"opt. calls\" calls to the \
         solver, summed over the 3 passes (Freitag's \"Num. Lap.\"/\"Num. Opt.\": 500 interior nodes × 3 passes = 1500). \
         The paper column gives Freitag's min / max angle (Laplacian / optimization counts); our copy of the \
         paper has the counts of the Lap and Opt rows run together, and we read them as 1500/0 and 0/1500.\n"
    );
    let mut table = Table::new(&[
        "method",
        "min angle",
        "max angle",
        "Laplacian moves",
        "opt. calls",
        "time ms (3 passes)",
        "paper: min / max (lap / opt)",
    ]);
    for r in &rows {
        let cell = |v: &Vec<f64>, d: usize| if v.is_empty() { "—".to_string() } else { mean_range(v, d) };
        let count = |v: &Vec<f64>| if v.is_empty() { "—".to_string() } else { format!("{:.0}", mean(v)) };
        table.row(vec![
            r.name.clone(),
            cell(&r.min, 2),
            cell(&r.max, 1),
            count(&r.lap),
            count(&r.opt),
            if r.ms.is_empty() { "—".into() } else { format!("{:.1}", mean(&r.ms)) },
            r.paper.clone(),
        ]);
    }
    out.table(table);
    let find = |n: &str| rows.iter().find(|r| r.name == n).expect("row");
    let smart_ms = mean(&find("smart (min sine)").ms);
    let opt_ms = mean(&find("opt, `sine`").ms);
    let sine = find("opt, `sine`");
    let c2 = find("C2 30°, `sine`");
    let c3 = find("C3 30°, `sine`");
    let new_rules = find("rules, `new`, priority");
    let new_opt = find("opt, `new`");
    let angle_rules = find("rules, `new`, priority (angle design)");
    let _ = writeln!(
        out,
        "\nMeasured: optimization with `sine` costs {:.1}× the smart Laplacian here (Freitag: about 5×; the time \
         column of our copy of her Table 1 is garbled, so only that ratio from her text is compared). `sine`+`opt` \
         reaches a min angle of {:.2}° (Freitag 18.20°) and a max of {:.1}° (143.5°); C2/C3 at 30° reach {:.2}° / {:.2}° \
         (Freitag 18.55° for both). The new objective with Chen's rules reaches {:.2}° / {:.1}° ({} elements \
         inverted after the 3 passes, over the five meshes), with plain optimization {:.2}° / {:.1}°; with the first \
         design of its penalty, Chen's rules reach {:.2}° / {:.1}°.\n",
        opt_ms / smart_ms,
        mean(&sine.min),
        mean(&sine.max),
        mean(&c2.min),
        mean(&c3.min),
        mean(&new_rules.min),
        mean(&new_rules.max),
        inverted_after.iter().sum::<usize>(),
        mean(&new_opt.min),
        mean(&new_opt.max),
        mean(&angle_rules.min),
        mean(&angle_rules.max),
    );
    let best = mean(&c2.min).max(mean(&c3.min)).max(mean(&sine.min));
    let (paper_min, paper_max) = (18.55, 140.5);
    let (nmin, nmax) = (mean(&new_rules.min), mean(&new_rules.max));
    let _ = writeln!(
        out,
        "Against Freitag's best row as she published it (C2/C3 at 30°: {paper_min}° / {paper_max}°), `new` + `rules` \
         {} on the min angle ({nmin:.2}°) and {} on the max angle ({nmax:.1}°).\n",
        if nmin >= paper_min { "is at least as good" } else { "falls short" },
        if nmax <= paper_max { "at least as good" } else { "worse" },
    );
    let chen = find(CHEN_ALONE);
    let _ = writeln!(
        out,
        "With Chen's search alone (no Newton step: the default before issue 15) `new` + `rules` reaches {:.2}° / \
         {:.1}° in {:.1} ms, against {nmin:.2}° / {nmax:.1}° in {:.1} ms with Newton's first trial; the choice is \
         measured in `docs/performance.md`.\n",
        mean(&chen.min),
        mean(&chen.max),
        mean(&chen.ms),
        mean(&new_rules.ms),
    );
    if mean(&new_rules.min) > best {
        let _ = writeln!(
            out,
            "`new` + `rules` beats the best of Freitag's rows as we measure them ({:.2}° against {best:.2}°) on the \
             min angle, and (table below) on the mean α.\n",
            mean(&new_rules.min)
        );
    } else {
        let _ = writeln!(
            out,
            "`new` + `rules` does not beat the best of Freitag's rows as we measure them ({:.2}° against {best:.2}°) \
             on the min angle. The reason is what it optimises: Σ(1 − α)² plus the angle penalties, an average over \
             each star, where the max-min objectives spend all their effort on the single worst angle. The table \
             below shows the trade: the new objective has the highest mean α and the fewest small angles, not the \
             largest smallest angle.\n",
            mean(&new_rules.min)
        );
    }
    freitag_why_new(out, &meshes);
    freitag_boundary(out, &meshes);
}

/// Where `sine` + `opt` stops: per seed, the worst element after 3 passes and after 10
/// passes of 20 iterations per call, with how many of its nodes are fixed.
fn freitag_boundary(out: &mut Report, meshes: &[Mesh]) {
    let o = opts(Strategy::Opt, Order::Input).with_smart_measure(Measure::MinSine);
    let worst = |m: &Mesh| {
        let mut w = (f64::INFINITY, 0usize);
        for e in 0..m.element_count() {
            let k = m.kind(e);
            let p = m.element_points_array(e);
            let a = element_quality(k, &p[..k.node_count()]).min_angle;
            if a < w.0 {
                w = (a, e);
            }
        }
        (w.0.to_degrees(), m.element(w.1).iter().filter(|&&n| m.fixed()[n as usize]).count())
    };
    let _ = writeln!(
        out,
        "Where `sine` + `opt` stops, per seed: the min angle after 3 passes (3 iterations per call, as above) and \
         after 10 passes of 20 iterations per call, with the number of fixed (boundary) nodes of the element that \
         has it.\n"
    );
    let mut table =
        Table::new(&["seed", "original", "3 passes: min angle (fixed nodes of its element)", "10 passes × 20 iterations"]);
    let (mut at_boundary, mut longer) = (0, Vec::new());
    for (i, m) in meshes.iter().enumerate() {
        let a = run(m, ObjectiveKind::Sine, o, 3, never);
        let b = run(m, ObjectiveKind::Sine, o.with_max_iter(20), 10, never);
        let (wa, fa) = worst(&a.mesh);
        let (wb, fb) = worst(&b.mesh);
        at_boundary += (fa >= 2) as usize;
        longer.push(wb);
        table.row(vec![
            (i + 1).to_string(),
            format!("{:.2}", mesh_stats(m).min_angle_deg),
            format!("{wa:.2} ({fa})"),
            format!("{wb:.2} ({fb})"),
        ]);
    }
    out.table(table);
    let _ = writeln!(
        out,
        "\nOur rand2D meshes differ from Freitag's one mesh (her original min angle 0.714°; ours 0.13°–0.84°), and \
         the per-seed spread of every row is wide. In {at_boundary} of {} seeds the worst angle after 3 passes of \
         `sine` + `opt` sits in an element with two fixed boundary nodes, where only one node can move; with 10 passes \
         of 20 iterations the mean rises to {:.2}°. So the optimizer is not stuck at a poor point: 3 passes of 3 \
         iterations are not enough on these meshes to reach Freitag's 18.20°, which one of our seeds (2) does reach. \
         The combined rows follow Freitag's pattern — the min angle and the number of optimization calls \
         grow with the threshold, C2 and C3 at 30° do best, C3 at 5° worst.\n",
        meshes.len(),
        mean(&longer)
    );
}

/// Why the new objective does (not) beat the max-min angle rows: it minimises Σ(1−α)²
/// plus a penalty, an average, and α is not the min angle.
fn freitag_why_new(out: &mut Report, meshes: &[Mesh]) {
    let mut table = Table::new(&["method", "min α", "mean α", "min angle", "angles < 18° (%)"]);
    for (label, kind, o) in [
        (
            "opt, `sine`",
            Choice::from(ObjectiveKind::Sine),
            opts(Strategy::Opt, Order::Input).with_smart_measure(Measure::MinSine),
        ),
        ("opt, `old` (α)", ObjectiveKind::MaxMinShape.into(), opts(Strategy::Opt, Order::Input)),
        ("opt, `new`", ObjectiveKind::SmoothShape.into(), opts(Strategy::Opt, Order::Input)),
        ("rules, `new`, priority", ObjectiveKind::SmoothShape.into(), opts(Strategy::Rules, Order::Priority)),
        ("rules, `new` (angle design), priority", NEW_ANGLE, opts(Strategy::Rules, Order::Priority)),
    ] {
        let (mut minq, mut meanq, mut mina, mut small) = (vec![], vec![], vec![], vec![]);
        for m in meshes {
            let r = run(m, kind, o, 3, never);
            let s = mesh_stats(&r.mesh);
            minq.push(s.min_quality);
            meanq.push(s.mean_quality);
            mina.push(s.min_angle_deg);
            // corner angles below 20°: the share the min-angle objectives fight
            let below: u64 = s.angle_histogram_6deg[..3].iter().sum::<u64>();
            let total: u64 = s.angle_histogram_6deg.iter().sum();
            small.push(100.0 * below as f64 / total as f64);
        }
        table.row(vec![
            label.to_string(),
            mean_range(&minq, 3),
            mean_range(&meanq, 4),
            mean_range(&mina, 2),
            mean_range(&small, 2),
        ]);
    }
    let _ = writeln!(
        out,
        "What each objective optimises, after 3 passes (same meshes): the smallest and mean α, the min angle, and \
         the share of corner angles below 18°.\n"
    );
    out.table(table);
    let _ = writeln!(out);
}
