//! `smoothlab smooth IN -o OUT [--objective …] [--strategy …] [--threshold DEG]
//! [--passes N] [--order priority|input] [--max-iter K] [--json]`.
//!
//! Which options go with which strategy (refused otherwise, so an option never silently
//! does nothing):
//! - `--threshold` only with `c1`, `c2`, `c3` (the only strategies with a threshold);
//! - `--max-iter` not with `laplace` or `smart` (they never call the solver);
//! - `--objective` with every strategy: `laplace` and `smart` never move a node by it,
//!   but each pass still reports its total, so it is accepted and the summary says so;
//! - `--order` with every strategy (Gauss–Seidel: the order changes the result);
//! - `--penalty` only with the `new` objective (the design of its eq. (8));
//! - `--pass-through-folds` / `--no-pass-through-folds` not with `laplace` or `smart`;
//! - `--target input` only with `opt` and `rules` (the others take Laplacian steps,
//!   which aim at the ideal).
//!
//! When elements stay inverted because no smoother can make them valid (an inverted corner
//! of fixed nodes, coincident fixed nodes), the summary names them and says why (`--json`:
//! `untangling_impossible`).
//!
//! `--slide-curves` (surfaces only): the nodes of the feature curves and open boundaries
//! slide along them instead of staying fixed.
//!
//! `--boundary slide` (planar meshes, surfaces and linear volume meshes): boundary nodes
//! slide on the boundary as loaded, curve nodes along its feature curves (`--feature-angle`;
//! a quadratic planar mesh's curved edges, its mid-side nodes carried along), corners stay;
//! the summary says how many of each and the largest distance from the boundary.

use std::path::PathBuf;

use clap::Args;
use smoothlab::model::Model;
use smoothlab::objective::{ObjectiveKind, Penalty};
use smoothlab::smooth::{Obstacle, Order, SmoothOptions, Strategy};
use smoothlab::volume::BoundaryRule;
use smoothlab::{Report, Smoothing, Target};

use crate::args::{msh_version_parser, named, order_parser, penalty_parser, strategy_parser};
use crate::files::{read_model, write_model};
use smoothlab::io::MshVersion;

use smoothlab::smooth::limits::{threshold_in_range, BATCH_MAX_ITER, BATCH_PASSES};

#[derive(Args)]
pub struct SmoothArgs {
    /// Input mesh (.msh, .vtk, .node/.ele, .obj, .off, .mesh)
    pub input: PathBuf,
    /// Output mesh; the format follows the extension
    #[arg(short, long)]
    pub output: PathBuf,
    /// Objective of the optimization steps; laplace and smart only report its total [default: new]
    #[arg(long, value_parser = named(&ObjectiveKind::ALL, ObjectiveKind::name, ObjectiveKind::describe))]
    pub objective: Option<ObjectiveKind>,
    /// How each node is smoothed
    #[arg(long, value_parser = strategy_parser(), default_value = SmoothOptions::default().strategy.name())]
    pub strategy: Strategy,
    /// Threshold angle of c1/c2/c3, degrees, in (0, 90] [default: 30]
    #[arg(long)]
    pub threshold: Option<f64>,
    /// Number of passes over the mesh
    #[arg(long, default_value_t = smoothlab::smooth::DEFAULT_PASSES)]
    pub passes: u32,
    /// Node order [default: priority for rules, input otherwise]
    #[arg(long, value_parser = order_parser())]
    pub order: Option<Order>,
    /// Solver iterations per optimization call [default: 3]
    #[arg(long)]
    pub max_iter: Option<u32>,
    /// Design of the new objective's angle penalty, eq. (8): barrier (regularised, the
    /// default) or angle (the first design, on the adjusted angle)
    #[arg(long, value_parser = penalty_parser())]
    pub penalty: Option<Penalty>,
    /// Let an already inverted star fold one more element when that lowers its total
    /// inversion [default: on for the untangling objectives new and untangle, off otherwise;
    /// a valid star is never folded]
    #[arg(long, overrides_with = "no_pass_through_folds")]
    pub pass_through_folds: bool,
    /// Never let an optimization call raise a star's inverted count
    #[arg(long, overrides_with = "pass_through_folds")]
    pub no_pass_through_folds: bool,
    /// Passes of the finish aimed at the worst element, once the mesh is valid: Freitag's
    /// max-min ascent on the smallest sine (a corner's scaled Jacobian; a tetrahedron's
    /// dihedral sines), worst star first; 0 for none
    #[arg(long, default_value_t = Smoothing::DEFAULT_FINISH)]
    pub finish: u32,
    /// What each corner is measured against: ideal (the ideal element of each kind, the
    /// papers), input (each corner as the mesh was read, where valid: its stretch and skew
    /// kept) or stretch (each element's stretch as read, averaged along its layer; the
    /// ideal where the mesh has none made on purpose; a valid planar or volume mesh of
    /// linear elements is first fitted to it whole). Default: stretch for opt and rules, the ideal for the strategies that
    /// take Laplacian steps
    #[arg(long, value_parser = named(&Target::ALL, Target::name, Target::describe))]
    pub target: Option<Target>,
    /// A surface's feature curves and open boundaries: their nodes slide along them
    /// instead of staying fixed (corners of the curves stay; a file's own fixed flags decide)
    #[arg(long)]
    pub slide_curves: bool,
    /// What a planar or linear volume mesh's boundary nodes do: fixed (where the file put
    /// them, the papers) or slide (on the boundary as loaded, along its feature curves, a
    /// quadratic mesh's curved edges; corners and the file's fixed nodes stay)
    #[arg(long, value_parser = named(&BoundaryRule::ALL, BoundaryRule::name, BoundaryRule::describe), default_value = BoundaryRule::default().name())]
    pub boundary: BoundaryRule,
    /// With --boundary slide: two boundary faces that turn by more than this many degrees
    /// meet at a feature curve [default: 60]
    #[arg(long)]
    pub feature_angle: Option<f64>,
    /// Print one JSON object instead of a summary
    #[arg(long)]
    pub json: bool,
    /// Version of .msh files written
    #[arg(long, value_parser = msh_version_parser(), default_value = MshVersion::default().name())]
    pub msh_version: MshVersion,
}

/// Strategies that never call the solver.
fn is_laplacian_only(strategy: Strategy) -> bool {
    strategy.max_iter_unused().is_some()
}

/// The smoothing the arguments ask for, or why they cannot be used together (in the words
/// of the flags; the core checks the same settings in its own words).
fn smoothing(a: &SmoothArgs) -> Result<Smoothing, String> {
    let strategy = a.strategy;
    if !BATCH_PASSES.contains(a.passes.into()) {
        return Err(format!(
            "--passes {}: give 1 to {}",
            a.passes, BATCH_PASSES.max
        ));
    }
    if u64::from(a.finish) > BATCH_PASSES.max {
        return Err(format!(
            "--finish {}: give 0 to {}",
            a.finish, BATCH_PASSES.max
        ));
    }
    if let Some(t) = a.threshold {
        if strategy.threshold_unused().is_some() {
            return Err(format!(
                "--threshold applies to the combined strategies c1, c2 and c3 only, not to {}",
                strategy.name()
            ));
        }
        if !threshold_in_range(t) {
            return Err(format!(
                "--threshold {t}: give an angle in degrees above 0 and at most 90"
            ));
        }
    }
    if let Some(k) = a.max_iter {
        if is_laplacian_only(strategy) {
            return Err(format!(
                "--max-iter: {} never calls the solver, so it has no iterations to limit",
                strategy.name()
            ));
        }
        if !BATCH_MAX_ITER.contains(k.into()) {
            return Err(format!(
                "--max-iter {k}: give 1 to {} solver iterations per call",
                BATCH_MAX_ITER.max
            ));
        }
    }
    if (a.pass_through_folds || a.no_pass_through_folds) && is_laplacian_only(strategy) {
        let flag = if a.pass_through_folds {
            "--pass-through-folds"
        } else {
            "--no-pass-through-folds"
        };
        return Err(format!(
            "{flag}: {} never calls the solver",
            strategy.name()
        ));
    }
    if let Some(t) = a.target.filter(|&t| t != Target::Ideal && !matches!(strategy, Strategy::Opt | Strategy::Rules)) {
        return Err(format!(
            "--target {}: the targets are measured by opt and rules; {} takes Laplacian steps, which aim at the ideal",
            t,
            strategy.name()
        ));
    }
    if let Some(d) = a.feature_angle {
        if a.boundary != BoundaryRule::Slide {
            return Err("--feature-angle finds the curves sliding nodes keep to: use it with --boundary slide".into());
        }
        if !(d > 0.0 && d < 180.0) {
            return Err(format!("--feature-angle {d}: give degrees above 0 and below 180"));
        }
    }
    if a.penalty.is_some() && a.objective.is_some_and(|k| k != ObjectiveKind::SmoothShape) {
        return Err("--penalty chooses the design of the new objective's penalty: use it with --objective new".into());
    }
    let mut s = Smoothing::default()
        .strategy(strategy)
        .objective(a.objective.unwrap_or(ObjectiveKind::SmoothShape))
        .passes(a.passes)
        .finish(a.finish)
        .slide_curves(a.slide_curves)
        .boundary(a.boundary);
    if let Some(t) = a.target {
        s = s.target(t);
    }
    if let Some(d) = a.feature_angle {
        s = s.feature_angle(d);
    }
    if let Some(o) = a.order {
        s = s.order(o);
    }
    if let Some(t) = a.threshold {
        s = s.threshold(t);
    }
    if let Some(k) = a.max_iter {
        s = s.max_iter(k);
    }
    if let Some(p) = a.penalty {
        s = s.penalty(p);
    }
    if a.pass_through_folds || a.no_pass_through_folds {
        s = s.pass_through_folds(a.pass_through_folds);
    }
    s.options().map_err(|e| e.to_string())?;
    Ok(s)
}

pub fn run(a: SmoothArgs) -> Result<(), String> {
    let smoothing = smoothing(&a)?;
    let kind = a.objective.unwrap_or(ObjectiveKind::SmoothShape);
    let mut model = read_model(&a.input)?;
    if a.slide_curves && !matches!(model, Model::Surface(_)) {
        let what = match &model {
            Model::Volume(v) => format!("made of {}", v.family_words()),
            _ => "planar".to_string(),
        };
        return Err(format!(
            "--slide-curves: the nodes of a surface's feature curves slide along them; this mesh is {what}"
        ));
    }
    if let Model::Volume(v) = &model {
        if a.boundary == BoundaryRule::Slide && v.is_quadratic() {
            return Err("--boundary slide takes planar meshes and linear meshes of volume elements so far: a quadratic volume mesh's boundary nodes stay".into());
        }
    }
    if a.penalty.is_some() && matches!(model, Model::Volume(_)) {
        return Err(
            "--penalty: the angle penalty's designs are planar; volume elements take new's regularised barrier".into()
        );
    }
    if let Model::Planar(mesh) = &model {
        smoothlab::objective::check_scale(kind, mesh)
            .map_err(|e| format!("{}: {e}", a.input.display()))?;
    }
    let report = model.smooth(&smoothing).map_err(|e| e.to_string())?;
    write_model(&model, &a.output, a.msh_version)?;
    if a.json {
        println!(
            "{}",
            serde_json::to_string(&report).map_err(|e| e.to_string())?
        );
    } else {
        // a tangled surface's nodes stay on a surface fitted through them, not on its facets
        let fitted = matches!(&model, Model::Surface(m) if matches!(m.reference(), smoothlab::surface::Reference::Fitted(_)));
        print!("{}", summary(&report, fitted));
        print!(
            "{}",
            obstacle_summary(report.untangling_impossible(), report.inverted())
        );
        let inverted: Vec<usize> = report.passes().iter().map(|r| r.after.inverted).collect();
        print!(
            "{}",
            more_passes_hint(&inverted, report.untangling_impossible().len())
        );
    }
    Ok(())
}

/// A line saying that more passes may untangle what is left, where the last pass still
/// untangled some (`inverted`: the count after each pass) and not every element left is
/// one no smoother can make valid; nothing otherwise.
fn more_passes_hint(inverted: &[usize], impossible: usize) -> String {
    match inverted {
        [.., before, last] if last < before && *last > impossible => format!(
            "still inverted: {last} (the last pass untangled {}); more passes (--passes) may untangle them\n",
            before - last
        ),
        _ => String::new(),
    }
}

/// The human-readable summary: one line per pass, then the final state.
fn summary(report: &Report, fitted: bool) -> String {
    let (kind, strategy, order) = report.settings();
    let (passes, s, ms) = (report.passes(), report.stats(), report.time_ms());
    let mut t = format!(
        "smoothing: strategy {}, objective {kind}{}{}, {} order\n",
        strategy.name(),
        if is_laplacian_only(strategy) {
            " (measured only: this strategy never optimizes)"
        } else {
            ""
        },
        match report.target() {
            Target::Ideal => String::new(),
            t => format!(" against the {t} target"),
        },
        match order {
            Order::Priority => "priority",
            Order::Input => "input",
        }
    );
    let first_finish = passes.len() - report.finish_passes() as usize;
    for (i, p) in passes.iter().enumerate() {
        t.push_str(&format!(
            "{} {:>3}: inverted {:>5}  angles {:>7.2}°–{:>6.2}°  min quality {:>7.4}  objective {:>12.6e}  laplacian {:>6}  optimized {:>6} ({} iterations){}{}  {:.1} ms\n",
            if i < first_finish { "pass" } else { "finish" },
            p.pass,
            p.after.inverted,
            p.after.min_angle_deg,
            p.after.max_angle_deg,
            p.after.min_quality,
            p.objective_total.unwrap_or(f64::NAN),
            p.counts.laplacian_moves,
            p.counts.optimization_calls,
            p.counts.solver_iterations,
            match p.counts.untangle_sweeps {
                0 => String::new(),
                n => format!(", {n} untangling sweep{}", if n == 1 { "" } else { "s" }),
            },
            match p.counts.fit_steps {
                0 => String::new(),
                n => format!(", fitted to the targets in {n} step{} first", if n == 1 { "" } else { "s" }),
            },
            p.elapsed_ms
        ));
    }
    t.push_str(&format!(
        "final: {}, {} inverted, angles {:.2}°–{:.2}°, quality min {:.4} mean {:.4}; {:.1} ms\n",
        crate::args::count(s.elements, "element", "elements"),
        s.inverted,
        s.min_angle_deg,
        s.max_angle_deg,
        s.min_quality,
        s.mean_quality,
        ms
    ));
    if let Some(b) = report.boundary() {
        t.push_str(&format!(
            "boundary: {}{} along {}, {} held ({} corners{}); every node within {:.3e} of the boundary as loaded ({:.2}% of its mean edge)\n",
            match b.surface_nodes {
                0 => String::new(),
                n => format!("{} slid on the surface, ", crate::args::count(n, "node", "nodes")),
            },
            crate::args::count(b.curve_nodes, "node", "nodes"),
            crate::args::count(b.curves, "feature curve", "feature curves"),
            b.corners + b.held,
            b.corners,
            if b.held > 0 { format!(", {} fixed by the file", b.held) } else { String::new() },
            b.max_distance,
            100.0 * b.max_distance / b.mean_edge
        ));
    }
    if let Some(d) = s.max_distance_from_surface {
        let reference = if fitted { "fitted through its nodes as loaded (the file was tangled)" } else { "as it was loaded" };
        t.push_str(&format!("surface: every node within {d:.3e} of the surface {reference}\n"));
    }
    t
}

/// How many of the elements no smoother can make valid the summary names, one line each.
const OBSTACLES_SHOWN: usize = 10;

/// The elements no smoother can make valid, one line each (the first
/// [`OBSTACLES_SHOWN`], then how many more: the summary's length does not grow with the
/// mesh; `--json` lists them all), after a line that says how many of the inverted
/// elements they are (nothing when there are none).
fn obstacle_summary(obstacles: &[Obstacle], inverted: usize) -> String {
    if obstacles.is_empty() {
        return String::new();
    }
    let mut t = format!(
        "untangling is impossible for {} of the {inverted} inverted elements (fixed nodes decide them):\n",
        obstacles.len()
    );
    for o in obstacles.iter().take(OBSTACLES_SHOWN) {
        t.push_str(&format!("  element {}: {}\n", o.element, o.reason));
    }
    if obstacles.len() > OBSTACLES_SHOWN {
        t.push_str(&format!(
            "  … and {} more (--json lists them all)\n",
            obstacles.len() - OBSTACLES_SHOWN
        ));
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue 61, finding 5: what the CLI prints does not grow with the mesh either.
    #[test]
    fn the_obstacle_summary_names_the_first_few_and_counts_the_rest() {
        let many: Vec<Obstacle> = (0..5000)
            .map(|e| Obstacle {
                element: e,
                reason: "its corner is set by fixed nodes alone".into(),
            })
            .collect();
        let t = obstacle_summary(&many, 6000);
        assert_eq!(t.lines().count(), 2 + OBSTACLES_SHOWN, "{t}");
        assert!(
            t.starts_with("untangling is impossible for 5000 of the 6000 inverted elements"),
            "{t}"
        );
        assert!(
            t.contains("  element 9: ") && !t.contains("element 10:"),
            "{t}"
        );
        assert!(
            t.ends_with("  … and 4990 more (--json lists them all)\n"),
            "{t}"
        );
        let few = obstacle_summary(&many[..3], 3);
        assert_eq!(few.lines().count(), 4, "{few}");
    }

    /// Issue 58: dragon, sliding, leaves 11, 5, 1 inverted after its 3 passes; 10 passes
    /// untangle it. The hint says so only where the last pass still untangled some.
    #[test]
    fn more_passes_are_suggested_only_while_they_untangle() {
        assert_eq!(
            more_passes_hint(&[11, 5, 1], 0),
            "still inverted: 1 (the last pass untangled 4); more passes (--passes) may untangle them\n"
        );
        assert_eq!(more_passes_hint(&[7, 7, 7], 0), "", "no progress");
        assert_eq!(more_passes_hint(&[9, 4, 2], 2), "", "what is left is impossible");
        assert_eq!(more_passes_hint(&[5, 0], 0), "", "valid");
        assert_eq!(more_passes_hint(&[5], 0), "", "one pass");
    }
}
