//! §8: the page's default sample.

use std::fmt::Write as _;

use smoothlab::generate::{perturb, plate, PlateKind};
use smoothlab::objective::ObjectiveKind;
use smoothlab::quality::mesh_stats;
use smoothlab::smooth::{Order, Strategy};
use smoothlab_page::lab::tour::measured::Table;

use crate::common::{never, opts, run};
use crate::report::Report;

/// Old against new on the page's tangled plates (its resolution and perturbation), many
/// seeds: the sample the page opens on is chosen by this table, not by one lucky seed.
pub(crate) fn default_sample(out: &mut Report) {
    use smoothlab_page::lab::sample::{Sample, PLATE_RESOLUTION, TANGLE_AMOUNT};
    const SEEDS: u64 = 20;
    out.section(8, "The page's default sample");
    let _ = writeln!(
        out,
        "The page compares the old objective (max-min α/β) with the new one, both with `rules` in priority order, \
         3 passes. Its tangled plates (resolution {PLATE_RESOLUTION}, every free node moved by up to \
         {TANGLE_AMOUNT} mean edge lengths) over seeds 1–{SEEDS}: in how many seeds each side ends with no inverted \
         element, in how many the new side has the larger smallest angle and the better mean quality, and the \
         new side's lead in smallest angle (new − old, degrees; over the seeds where both untangle). The page \
         opens on `{}`, seed 1.\n",
        serde_json::to_value(Sample::DEFAULT).expect("name").as_str().expect("a name")
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
