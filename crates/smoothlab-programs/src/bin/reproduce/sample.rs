//! §8: the page's opening sample.

use std::fmt::Write as _;

use smoothlab::generate::{perturb, plate, rand2d, PlateKind};
use smoothlab::objective::ObjectiveKind;
use smoothlab::quality::mesh_stats;
use smoothlab::smooth::{Order, Strategy};
use smoothlab_page::lab::tour::measured::Table;
use smoothlab_page::lab::{Playground, Side};

use crate::common::{never, opts, run};
use crate::report::Report;

/// The sample the page opens on, chosen by what one press of Step shows with the page's
/// own settings (the lab's `Playground`, as the page runs it): kinds, amounts and seeds
/// where the old objective leaves elements inverted and the new one none. Then old
/// against new on the plates tangled by the gallery's amount, after 3 passes.
pub(crate) fn default_sample(out: &mut Report) {
    use smoothlab_page::lab::sample::{Sample, HARD_TANGLE_AMOUNT, PLATE_RESOLUTION, SAMPLE_SEED, TANGLE_AMOUNT};
    const SEEDS: u64 = 20;
    out.section(8, "The page's opening sample");
    let opening = Sample::DEFAULT.name();
    let _ = writeln!(
        out,
        "The page opens on the sample where one press of Step, with the page's default settings (old against new, \
         `rules` in priority order), shows the papers' claim: the old objective leaves elements inverted and the new \
         one leaves none. Each generated kind, perturbed (every free node moved by up to the amount, in mean edge \
         lengths) with seeds 1–{SEEDS}, is stepped once as the page steps it: in how many seeds the claim shows, and \
         the old side's inverted elements after the Step (smallest, median, largest over the seeds) and after 3 \
         passes (median, and in how many seeds the new side has none). The page opens on `{opening}`: the \
         quad plate at {HARD_TANGLE_AMOUNT:.1}, seed {SAMPLE_SEED}, where the claim shows in every seed, on the \
         papers' own test mesh (Chen et al.'s plate with a hole) and on quads, whose β makes the max-min objective \
         kinked (their Fig. 20). At the gallery's {TANGLE_AMOUNT:.1} the old objective too untangles the plates in \
         one Step in almost every seed; rand2D shows the claim at every amount, but it is a random point set, and \
         at {TANGLE_AMOUNT:.1} the old side leaves few elements inverted.\n"
    );
    let mut claim = Table::new(&["mesh", "amount", "claim shows", "old inverted after 1 Step: smallest", "median", "largest", "after 3 passes: median", "new untangled"]);
    let kinds = [
        ("plate, tri", plate(PlateKind::Tri, 1, PLATE_RESOLUTION).expect("plate")),
        ("plate, quad", plate(PlateKind::Quad, 1, PLATE_RESOLUTION).expect("plate")),
        ("plate, mixed", plate(PlateKind::Mixed, 1, PLATE_RESOLUTION).expect("plate")),
        ("rand2D", rand2d(500, 20, SAMPLE_SEED).expect("rand2d")),
    ];
    let median = |v: &mut Vec<usize>| {
        v.sort_unstable();
        0.5 * (v[(v.len() - 1) / 2] + v[v.len() / 2]) as f64
    };
    for amount in [TANGLE_AMOUNT, 0.75, HARD_TANGLE_AMOUNT] {
        for (name, base) in &kinds {
            let (mut shows, mut first, mut third, mut new_valid) = (0, Vec::new(), Vec::new(), 0);
            for seed in 1..=SEEDS {
                let mut pg = Playground::new(perturb(base, amount, seed).expect("perturb")).expect("playground");
                let [old, new] = pg.step(&|| 0.0);
                shows += (old.after.inverted > 0 && new.after.inverted == 0) as u32;
                first.push(old.after.inverted);
                pg.step(&|| 0.0);
                pg.step(&|| 0.0);
                third.push(pg.full_stats(Side::A).inverted);
                new_valid += (pg.full_stats(Side::B).inverted == 0) as u32;
            }
            claim.row(vec![
                name.to_string(),
                format!("{amount:.2}"),
                format!("{shows} of {SEEDS}"),
                format!("{}", first.iter().min().expect("seeds")),
                format!("{}", median(&mut first)),
                format!("{}", first.iter().max().expect("seeds")),
                format!("{}", median(&mut third)),
                format!("{new_valid} of {SEEDS}"),
            ]);
        }
    }
    out.table(claim);
    let _ = writeln!(
        out,
        "\nThe plates tangled by the gallery's amount ({TANGLE_AMOUNT:.1}; `plate-quad-tangled` opened the page \
         before): both objectives with `rules` in priority order, 3 passes, over the same seeds: in how many \
         seeds each side ends with no inverted element, in how many the new side has the larger smallest angle and \
         the better mean quality, and the new side's lead in smallest angle (new − old, degrees; over the seeds \
         where both untangle).\n"
    );
    let mut table = Table::new(&[
        "plate",
        "untangled: old",
        "new",
        "new has the larger min angle",
        "new has the better mean quality",
        "lead in min angle: median",
        "smallest",
        "largest",
    ]);
    for (name, kind) in [("tri", PlateKind::Tri), ("quad", PlateKind::Quad), ("mixed", PlateKind::Mixed)] {
        let base = plate(kind, 1, PLATE_RESOLUTION).expect("plate");
        let (mut untangled, mut ahead, mut better_mean, mut lead) = ([0; 2], 0, 0, vec![]);
        for seed in 1..=SEEDS {
            let m = perturb(&base, TANGLE_AMOUNT, seed).expect("perturb");
            let [o, n] = [ObjectiveKind::MaxMinShape, ObjectiveKind::SmoothShape]
                .map(|k| mesh_stats(&run(&m, k, opts(Strategy::Rules, Order::Priority), 3, never).mesh));
            untangled[0] += (o.inverted == 0) as u32;
            untangled[1] += (n.inverted == 0) as u32;
            ahead += (n.min_angle_deg > o.min_angle_deg) as u32;
            better_mean += (n.mean_quality > o.mean_quality) as u32;
            if o.inverted == 0 && n.inverted == 0 {
                lead.push(n.min_angle_deg - o.min_angle_deg);
            }
        }
        lead.sort_by(f64::total_cmp);
        let median = if lead.is_empty() { f64::NAN } else { 0.5 * (lead[(lead.len() - 1) / 2] + lead[lead.len() / 2]) };
        table.row(vec![
            name.to_string(),
            format!("{} of {SEEDS}", untangled[0]),
            format!("{} of {SEEDS}", untangled[1]),
            format!("{ahead} of {SEEDS}"),
            format!("{better_mean} of {SEEDS}"),
            format!("{median:+.2}"),
            format!("{:+.2}", lead.first().copied().unwrap_or(f64::NAN)),
            format!("{:+.2}", lead.last().copied().unwrap_or(f64::NAN)),
        ]);
    }
    out.table(table);
    let _ = writeln!(
        out,
        "\nOn triangles the two objectives end level in the smallest angle (the worst triangles of these plates have \
         two fixed nodes and one free, whose angle the max-min objective optimises directly); on quads, where \
         Canann's β makes the max-min objective kinked (Chen's Fig. 20), the new one leads.\n"
    );
}
