//! The tour's `knupp-hex`: Knupp's kind of tangled test grid in hexahedra (the gallery's
//! [`Sample::HexTangled`](crate::lab::sample::Sample::HexTangled)) untangled pass by pass,
//! the old max-min objective against the new one, in the page's cut view. The passes are
//! the 3D lab's ([`Lab3d`]), run once and kept: the picture and the text read one run.

use std::sync::OnceLock;

use tiny_skia::Pixmap;

use super::{find, gallery_sample};
use smoothlab::error::{Error, Result};
use crate::lab::lab3d::Lab3d;
use crate::lab::sample::{HEX_TANGLE_AMOUNT, SAMPLE_SEED};
use crate::lab::lab3d::Mesh3d;
use crate::lab::views::{pixmap, Canvas};
use crate::lab::Side;
use smoothlab::model::Model;
use smoothlab_render::Theme;
use smoothlab::volume::{volume_stats, VolumeMesh};
use smoothlab_render::{draw_node_mark, Cut, SurfaceView, VolumePicture};

/// The figure's run: each side's mesh as loaded and after each pass.
pub(super) struct HexRun {
    /// `stages[side][p]`: after `p` passes (0: as loaded).
    stages: [Vec<VolumeMesh>; 2],
    /// The objective's name on each side.
    objective: [String; 2],
}

impl HexRun {
    /// Inverted elements of each side, as loaded and after each pass.
    fn inverted(&self, side: Side) -> Vec<usize> {
        self.stages[side.index()].iter().map(|m| volume_stats(m).inverted).collect()
    }
}

/// Elements inverted inside only: every measured corner's Jacobian positive, yet the
/// element not valid ([`smoothlab::quality::solid::SolidMeasures::inverted_inside`]).
fn inverted_inside(m: &VolumeMesh) -> usize {
    (0..m.element_count()).filter(|&e| m.measures(e).inverted_inside).count()
}

/// The smallest scaled Jacobian of any element's corner.
fn worst_scaled_jacobian(m: &VolumeMesh) -> f64 {
    (0..m.element_count()).map(|e| m.measures(e).scaled_jacobian).fold(f64::INFINITY, f64::min)
}

/// The figure's gallery sample in the 3D lab with the figure's settings, its passes run
/// (made once: the page asks for the picture and the text of one run).
pub(super) fn hex_run() -> Result<&'static HexRun> {
    static RUN: OnceLock<HexRun> = OnceLock::new();
    if let Some(r) = RUN.get() {
        return Ok(r);
    }
    let (_, fig) = find("knupp-hex")?;
    let st = fig.state()?;
    let sample = gallery_sample(fig.name).ok_or_else(|| Error::invalid("knupp-hex names no gallery sample"))?;
    let Model::Volume(mesh) = sample.model()? else {
        return Err(Error::invalid("knupp-hex: its sample is not a volume mesh"));
    };
    let mut lab = Lab3d::new(mesh)?;
    lab.set_settings(st.settings)?;
    let mut stages = [vec![lab.original().clone()], vec![lab.original().clone()]];
    for _ in 0..st.passes {
        lab.step(&|| 0.0);
        for side in Side::BOTH {
            stages[side.index()].push(lab.mesh(side).clone());
        }
    }
    let settings = lab.settings();
    let objective = Side::BOTH.map(|s| settings.choice(s).objective.to_string());
    Ok(RUN.get_or_init(|| HexRun { stages, objective }))
}

/// The picture: one row a side, the block as loaded and after each pass, cut half way up
/// z (the plane placed by the fixed boundary, so the same in every panel), each panel
/// titled with its inverted count. A node thrown out of the block lies in the view (the
/// panel zooms out to hold it) but its elements' faces are hidden between the elements
/// the cut keeps: it is marked, with its edges, as the page marks a chosen node.
pub(super) fn knupp_hex(c: Canvas, t: &Theme) -> Result<Vec<Pixmap>> {
    let run = hex_run()?;
    let m0 = &run.stages[0][0];
    let mut out = Vec::new();
    for side in Side::BOTH {
        let counts = run.inverted(side);
        for (p, m) in run.stages[side.index()].iter().enumerate() {
            // short: four panels share a row, a few hundred pixels in an embed (the rows'
            // objectives are the sides', named in the words)
            let when = if p == 0 { "start".to_string() } else { format!("pass {p}") };
            let title = format!("{}, {when}: {} inverted", side.letter(), counts[p]);
            let mut pm = pixmap(c.w, c.h)?;
            let view = SurfaceView { dpr: c.dpr, title: Some(title), theme: *t, ..SurfaceView::default() };
            let proj = m.render_cut(&mut pm, Cut::default(), &view);
            if let Some((n, _)) = thrown(m0, m) {
                draw_node_mark(&mut pm, &proj, m.nodes()[n], &m.star_lines(n), c.dpr);
            }
            out.push(pm);
        }
    }
    Ok(out)
}

/// The node of `m` farthest outside the box of `m0`'s nodes, and how far, in `m0`'s mean
/// edge lengths, when it lies more than one edge length out: a node thrown out.
fn thrown(m0: &VolumeMesh, m: &VolumeMesh) -> Option<(usize, f64)> {
    let (lo, hi) = m0.nodes().iter().fold((glam::DVec3::INFINITY, glam::DVec3::NEG_INFINITY), |(l, h), &p| (l.min(p), h.max(p)));
    let far = m.nodes().iter().map(|&p| p.distance(p.clamp(lo, hi)) / m0.mean_edge_length()).enumerate();
    far.max_by(|a, b| a.1.total_cmp(&b.1)).filter(|&(_, d)| d > 1.0)
}

/// The columns of the picture: the mesh as loaded and after each pass.
pub(super) fn columns() -> Result<usize> {
    Ok(hex_run()?.stages[0].len())
}

/// How far the farthest node of `m` lies outside the box of `m0`'s nodes, in `m0`'s mean
/// edge lengths (0: every node inside).
fn farthest_outside(m0: &VolumeMesh, m: &VolumeMesh) -> f64 {
    let (lo, hi) = m0.nodes().iter().fold((glam::DVec3::INFINITY, glam::DVec3::NEG_INFINITY), |(l, h), &p| (l.min(p), h.max(p)));
    m.nodes().iter().map(|&p| p.distance(p.clamp(lo, hi))).fold(0.0, f64::max) / m0.mean_edge_length()
}

/// Where side A's nodes went (`objective` its objective's name), in words: outside the
/// block (its panels zoom out to hold them) or not.
fn outside_words(m0: &VolumeMesh, m: &VolumeMesh, objective: &str) -> String {
    let d = farthest_outside(m0, m);
    if d > 0.0 {
        format!("; {objective} threw a node {d:.1} edge lengths out of the block (marked in orange with its edges; its panels zoom out to hold it)")
    } else {
        String::new()
    }
}

/// The text's numbers, from the run the picture shows.
pub(super) fn knupp_hex_measured() -> Result<String> {
    let run = hex_run()?;
    let words = |v: &[usize]| v.iter().map(usize::to_string).collect::<Vec<_>>().join(" → ");
    let m0 = &run.stages[0][0];
    let last = |side: Side| run.stages[side.index()].last().unwrap_or(m0);
    let (a, b) = (last(Side::A), last(Side::B));
    let [oa, ob] = &run.objective;
    Ok(format!(
        "Measured ({} hexahedra, free nodes moved by up to {HEX_TANGLE_AMOUNT} mean edge length{}, seed {SAMPLE_SEED}), \
         inverted pass by pass: {} with {oa}, {} with {ob}. As loaded {} are inverted inside only, all eight corner \
         Jacobians positive; after the last pass {} ({oa}), {} ({ob}); worst corner's scaled Jacobian {:.3} ({oa}), \
         {:.3} ({ob}){}.",
        m0.element_count(),
        if HEX_TANGLE_AMOUNT == 1.0 { "" } else { "s" },
        words(&run.inverted(Side::A)),
        words(&run.inverted(Side::B)),
        inverted_inside(m0),
        inverted_inside(a),
        inverted_inside(b),
        worst_scaled_jacobian(a),
        worst_scaled_jacobian(b),
        outside_words(m0, a, oa),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_new_objective_untangles_the_hexahedra_and_the_old_does_not() {
        let run = hex_run().unwrap();
        let (old, new) = (run.inverted(Side::A), run.inverted(Side::B));
        assert_eq!(old.len(), 4, "as loaded and 3 passes");
        assert!(old[0] > 100 && old[0] == new[0], "{old:?} {new:?}");
        assert_eq!(new[1], 0, "the new objective untangles in the first pass: {new:?}");
        assert!(*old.last().unwrap() > 0, "the old one does not: {old:?}");
        assert_eq!(run.objective, ["old".to_string(), "new".to_string()]);
        let text = knupp_hex_measured().unwrap();
        let words = |v: &[usize]| v.iter().map(usize::to_string).collect::<Vec<_>>().join(" → ");
        assert!(text.contains(&words(&old)) && text.contains(&words(&new)), "{text}");
        assert!(text.contains("216 hexahedra"), "{text}");
        // the old side's shrinking panels: a node pushed out of the block, said in the text
        let far = farthest_outside(&run.stages[0][0], run.stages[0].last().unwrap());
        assert!(far > 1.0 && text.contains(&format!("a node {far:.1} edge lengths out of the block")), "{far}: {text}");
        assert_eq!(farthest_outside(&run.stages[1][0], run.stages[1].last().unwrap()), 0.0, "the new side stays inside");
        // the thrown node is in its panel's view and marked with its edges (issue 59: its
        // elements' faces are hidden by the cut, and it was not drawn): the mark's orange
        let panels = knupp_hex(Canvas { w: 350, h: 330, dpr: 1.0 }, &Theme::light()).unwrap();
        let orange = |pm: &Pixmap| pm.pixels().iter().filter(|p| (p.red(), p.green(), p.blue()) == (230, 159, 0)).count();
        let cols = columns().unwrap();
        assert!(orange(&panels[cols - 1]) > 100, "A's last panel: {} orange pixels", orange(&panels[cols - 1]));
        assert_eq!(orange(&panels[0]) + orange(&panels[2 * cols - 1]), 0, "no node thrown as loaded, nor by the new side");
    }

    #[test]
    fn inverted_inside_counts_a_hexahedron_whose_corners_are_all_positive() {
        // unit cubes with their corners moved at random: among them, hexahedra whose eight
        // corner determinants are positive but whose det J is negative inside (certain:
        // `Validity::Inverted`, not undecided)
        use smoothlab::quality::solid::{validity, Validity};
        let kind = smoothlab::mesh::VolumeKind::Hex8;
        let ideal: Vec<glam::DVec3> = kind.row().ideal.iter().map(|&c| glam::DVec3::from(c)).collect();
        let mut rng = smoothlab::numeric::SplitMix64::new(1);
        let mut found = None;
        for _ in 0..100_000 {
            let p: Vec<glam::DVec3> = ideal.iter().map(|&c| c + 0.6 * rng.in_unit_ball()).collect();
            let corners_positive = (0..8).all(|c| {
                let t = smoothlab::quality::solid::corner_tet(kind, &p, c);
                smoothlab::quality::tet::signed_volume(&t) > 0.0
            });
            if corners_positive && validity(kind, &p) == Validity::Inverted {
                found = Some(p);
                break;
            }
        }
        let p = found.expect("some hexahedron is inverted inside with its corners positive");
        let m = VolumeMesh::from_elements(p, [(kind, &[0u32, 1, 2, 3, 4, 5, 6, 7][..])]).unwrap();
        assert_eq!(inverted_inside(&m), 1);
        assert!(worst_scaled_jacobian(&m) > 0.0, "its corners are positive");
        assert!(m.is_inverted(0));
        // and a cube is not
        let cube = smoothlab::generate::hex_grid(&smoothlab::generate::HexBlock::cube(1)).unwrap();
        assert_eq!(inverted_inside(&cube), 0);
    }
}
