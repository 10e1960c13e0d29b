//! §9: surface meshes.

use std::fmt::Write as _;

use smoothlab::generate::{perturb, perturb_surface, plate, surface, SurfaceKind, SurfaceShape};
use smoothlab::io;
use smoothlab::model::Model;
use smoothlab::objective::{objective_with, ObjectiveKind, Penalty};
use smoothlab::quality::{mesh_stats, MeshStats};
use smoothlab::smooth::{Order, PassRecord, SmoothOptions, Strategy};
use smoothlab::surface::{Surface, SurfaceSmoother};
use smoothlab_page::lab::tour::measured::Table;

use crate::chen::PLATES;
use crate::common::{clock, meshes_dir, opts, run};
use crate::report::Report;

/// `passes` passes of `kind` with `opts` over a copy of `s`, stopping after the first pass
/// that leaves no element inverted when `stop_untangled`.
fn run_surface(
    s: &Surface,
    kind: ObjectiveKind,
    opts: SmoothOptions,
    passes: u32,
    stop_untangled: bool,
) -> (Surface, Vec<PassRecord>) {
    let mut t = s.clone();
    let obj = objective_with(kind, Penalty::default());
    let mut smoother = SurfaceSmoother::new(opts).expect("valid options");
    let c = clock();
    let mut records = Vec::new();
    for _ in 0..passes {
        let r = smoother.pass(&mut t, &*obj, &c);
        let done = stop_untangled && r.after.inverted == 0;
        records.push(r);
        if done {
            break;
        }
    }
    (t, records)
}

fn surface_row(name: &str, s: &MeshStats, ms: Option<f64>) -> Vec<String> {
    vec![
        name.to_string(),
        s.inverted.to_string(),
        format!("{:.2}", s.min_angle_deg),
        format!("{:.2}", s.max_angle_deg),
        format!("{:.4}", s.min_quality),
        format!("{:.4}", s.mean_quality),
        format!("{:.1e}", s.max_distance_from_surface.unwrap_or(f64::NAN)),
        ms.map_or("".into(), |m| format!("{m:.0}")),
    ]
}

pub(crate) fn surfaces(out: &mut Report) {
    out.section(9, "Surface meshes (Chen, Tristano & Kwok 2003, §5, Figs. 18–19)");
    let _ = writeln!(
        out,
        "A surface's free node is smoothed in its tangent plane: its star is flattened there, every strategy and \
         objective runs on it as on a planar star, and the new position is projected back onto the surface as it was \
         loaded (the file's elements: flat triangles, or a quadratic element's curved patch; a tangled file's: the \
         surface fitted through its nodes, `docs/formulas.md` §7), or onto the exact surface of a generated sample. Every element \
         is measured in its own plane; an element facing against the surface counts as inverted. \
         \"distance\" is the largest distance of a node from that surface after smoothing.\n"
    );
    out.subsection("Mesquite's surface meshes");
    let _ = writeln!(
        out,
        "3 passes of `new` + `rules` (priority order) and of `old` + `opt`, with the files' `fixed` flags (and \
         their feature curves fixed: none of these has one).\n"
    );
    let mut table =
        Table::new(&["mesh", "inverted", "min angle", "max angle", "min α/β", "mean α/β", "distance", "ms"]);
    let root = meshes_dir().join("mesquite");
    let files = [
        "quads/untangled/quads_on_sphere_529.vtk",
        "quads/untangled/bias-sphere-quads.vtk",
        "quads/untangled/paraboloid.vtk",
        "tris/untangled/Mesquite_geo_10242.vtk",
    ];
    if !root.is_dir() {
        out.table(table);
        let _ = writeln!(out, "\n*Skipped: the external Mesquite meshes (`../shared/meshes`) were not found.*\n");
    } else {
        for f in files {
            let model = match io::read_model_path(&root.join(f)) {
                Ok(m) => m,
                Err(e) => {
                    let mut cells = vec![f.to_string(), format!("could not be read: {e}")];
                    cells.resize(8, String::new());
                    table.row(cells);
                    continue;
                }
            };
            let Model::Surface(s) = model else {
                let mut cells = vec![f.to_string(), "read as planar".to_string()];
                cells.resize(8, String::new());
                table.row(cells);
                continue;
            };
            table.row(surface_row(&format!("`{f}` as loaded"), &s.stats(), None));
            for (kind, strategy) in [(ObjectiveKind::SmoothShape, Strategy::Rules), (ObjectiveKind::MaxMinShape, Strategy::Opt)] {
                let order = if strategy == Strategy::Rules { Order::Priority } else { Order::Input };
                let (t, r) = run_surface(&s, kind, opts(strategy, order), 3, false);
                let ms: f64 = r.iter().map(|p| p.elapsed_ms).sum();
                table.row(surface_row(&format!("{} + {}", kind.name(), strategy.name()), &t.stats(), Some(ms)));
            }
        }
        out.table(table);
        let _ = writeln!(out);
    }
    out.subsection("Tangled surface samples");
    let _ = writeln!(
        out,
        "Each sample (`smoothlab generate sphere|cylinder|torus --kind K --order O`, resolution 6: the torus 24 × 72 \
         cells) perturbed in its tangent planes by 0.6 and by 1.0 mean edge lengths (seeds 1–3), then `new` + `rules` \
         (priority order) pass after pass until no element is inverted, at most 10. The cylinder's rims are feature \
         curves (fixed). Means over the 6 runs of each row; \"passes\" is the largest number any run needed.\n"
    );
    let mut table = Table::new(&[
        "sample",
        "nodes",
        "inverted before",
        "untangled",
        "passes",
        "min angle",
        "max angle",
        "mean α/β",
        "distance",
    ]);
    for shape in SurfaceShape::ALL {
        for kind in SurfaceKind::ALL {
            for order in [1u8, 2] {
                let base = surface(shape, kind, order, 6).expect("a sample");
                let (mut inverted, mut done, mut most, mut lo, mut hi, mut q, mut far, mut runs) =
                    (0usize, 0usize, 0usize, 0.0, 0.0, 0.0, 0.0f64, 0usize);
                for amount in [0.6, 1.0] {
                    for seed in 1..=3 {
                        let p = perturb_surface(&base, amount, seed).expect("perturbed");
                        inverted += p.stats().inverted;
                        let (t, r) =
                            run_surface(&p, ObjectiveKind::SmoothShape, opts(Strategy::Rules, Order::Priority), 10, true);
                        let st = t.stats();
                        done += (st.inverted == 0) as usize;
                        most = most.max(r.len());
                        lo += st.min_angle_deg;
                        hi += st.max_angle_deg;
                        q += st.mean_quality;
                        far = far.max(st.max_distance_from_surface.unwrap_or(f64::NAN));
                        runs += 1;
                    }
                }
                let k = runs as f64;
                table.row(vec![
                    format!("{} {} order {order}", shape.name(), kind.name()),
                    base.node_count().to_string(),
                    format!("{:.1}", inverted as f64 / k),
                    format!("{done} of {runs}"),
                    most.to_string(),
                    format!("{:.2}", lo / k),
                    format!("{:.2}", hi / k),
                    format!("{:.4}", q / k),
                    format!("{far:.1e}"),
                ]);
            }
        }
    }
    out.table(table);
    tangled_from_files(out);
    let _ = writeln!(
        out,
        "\nChen et al.'s Figs. 18–19 in spirit, a surface mesh improved (`make figures`): a torus of quads and \
         triangles (resolution 3) tangled in its tangent planes by 0.7 mean edge lengths, read from its file — its reference the \
         surface fitted through the file's nodes — then one pass of the old max-min objective (left) and of the new one (right), both \
         with `rules`:\n\n\
         ![the tangled torus](images/surface-torus-tangled.png)\n\n\
         ![the torus after one pass, old and new](images/surface-torus-compare.png)\n"
    );
}

/// Tangled surfaces as a user has them: written to a file and read back, so the
/// reference is fitted through the nodes (`docs/formulas.md` §7), not the generator's
/// exact surface; beside the planar plates tangled by the same amounts.
fn tangled_from_files(out: &mut Report) {
    const SEEDS: [u64; 3] = [1, 2, 3];
    const AMOUNTS: [f64; 3] = [0.5, 1.0, 1.5];
    const PASSES: u32 = 3;
    const COLUMNS: [&str; 8] = [
        "mesh",
        "amount",
        "nodes",
        "inverted: before → pass 1 → 2 → 3",
        "untangled",
        "distance",
        "min angle",
        "max angle",
    ];
    out.subsection("Tangled surfaces read from a file");
    let _ = writeln!(
        out,
        "A tangled file's elements fold, so it is not its own reference: smoothlab fits a surface through its nodes \
         (`docs/formulas.md` §7). Each sample (`smoothlab generate sphere|torus|cylinder --kind K --order O`, \
         resolution 6; the sphere and the cylinder of radius 1, the torus of radii 1 and 0.3) perturbed in its \
         tangent planes by {} mean edge lengths (seeds {}), written as `.vtk` (its fixed flags with it: the \
         cylinder's rims) and read back, then the defaults (`new` + `rules`, priority order) for {PASSES} passes. \
         The planar plates (`plate(kind, order, 4)`, §2) perturbed by the same amounts run the same way, for \
         comparison. \"inverted\": the mean over the seeds before smoothing and after each pass; \"untangled\": the \
         seeds with none inverted after pass {PASSES}; \"distance\": the largest distance of a node from the exact \
         surface after the last pass (the generator's sphere, torus or capped cylinder; the reference the smoother \
         saw was the fitted one); angles over the seeds after the last pass.\n",
        AMOUNTS.map(|a| a.to_string()).join(", "),
        SEEDS.map(|a| a.to_string()).join(", ")
    );
    // one row: the mean inverted count before and after each pass, the seeds untangled,
    // the farthest node from the exact surface, the smallest and largest angle
    let row = |name: &str, amount: f64, nodes: usize, runs: &[(Vec<usize>, Option<f64>, f64, f64)]| {
        let k = runs.len() as f64;
        let per_pass = (0..=PASSES as usize)
            .map(|i| format!("{:.1}", runs.iter().map(|r| r.0[i.min(r.0.len() - 1)] as f64).sum::<f64>() / k))
            .collect::<Vec<_>>()
            .join(" → ");
        let untangled = runs.iter().filter(|r| r.0.last() == Some(&0)).count();
        let far = match runs.iter().map(|r| r.1).collect::<Option<Vec<f64>>>() {
            Some(d) => format!("{:.1e}", d.into_iter().fold(0.0, f64::max)),
            None => "—".into(),
        };
        let lo = runs.iter().map(|r| r.2).fold(f64::INFINITY, f64::min);
        let hi = runs.iter().map(|r| r.3).fold(0.0, f64::max);
        vec![
            name.to_string(),
            amount.to_string(),
            nodes.to_string(),
            per_pass,
            format!("{untangled} of {}", runs.len()),
            far,
            format!("{lo:.2}"),
            format!("{hi:.2}"),
        ]
    };
    // a tangled sample written in `format` and read back, smoothed: one row per amount
    let from_file = |table: &mut Table, format: io::Format, orders: &[u8], amounts: &[f64]| {
        for shape in SurfaceShape::ALL {
            for kind in SurfaceKind::ALL {
                for &order in orders {
                    let base = surface(shape, kind, order, 6).expect("a sample");
                    let smoothlab::surface::Reference::Analytic(exact) = *base.reference() else {
                        unreachable!("a generated surface knows its exact surface")
                    };
                    for &amount in amounts {
                        let runs: Vec<_> = SEEDS
                            .iter()
                            .map(|&seed| {
                                let p = perturb_surface(&base, amount, seed).expect("perturbed");
                                let text = io::write_model_string(&Model::Surface(p), format, &Default::default())
                                    .expect("written");
                                let Ok(Model::Surface(loaded)) = io::read_model_str(&text, format) else {
                                    unreachable!("a surface file reads back as a surface")
                                };
                                let before = loaded.stats().inverted;
                                let (t, r) = run_surface(
                                    &loaded,
                                    ObjectiveKind::SmoothShape,
                                    opts(Strategy::Rules, Order::Priority),
                                    PASSES,
                                    false,
                                );
                                let inverted = std::iter::once(before).chain(r.iter().map(|p| p.after.inverted)).collect();
                                let far = t
                                    .points()
                                    .iter()
                                    .map(|&q| (exact.project(q, smoothlab::mesh::NONE).point - q).length())
                                    .fold(0.0, f64::max);
                                let st = t.stats();
                                (inverted, Some(far), st.min_angle_deg, st.max_angle_deg)
                            })
                            .collect();
                        let name = format!("{} {} order {order}", shape.name(), kind.name());
                        table.row(row(&name, amount, base.node_count(), &runs));
                    }
                }
            }
        }
    };
    let mut table = Table::new(&COLUMNS);
    from_file(&mut table, io::Format::Vtk, &[1, 2], &AMOUNTS);
    for (label, kind, order) in PLATES {
        let base = plate(kind, order, 4).expect("plate");
        for amount in AMOUNTS {
            let runs: Vec<_> = SEEDS
                .iter()
                .map(|&seed| {
                    let m = perturb(&base, amount, seed).expect("perturb");
                    let r = run(&m, ObjectiveKind::SmoothShape, opts(Strategy::Rules, Order::Priority), PASSES, |_| false);
                    let inverted = std::iter::once(mesh_stats(&m).inverted).chain(r.passes.iter().map(|p| p.after.inverted)).collect();
                    let last = r.passes.last().expect("a pass");
                    (inverted, None, last.after.min_angle_deg, last.after.max_angle_deg)
                })
                .collect();
            table.row(row(&format!("plate {label}"), amount, base.node_count(), &runs));
        }
    }
    out.table(table);
    let _ = writeln!(
        out,
        "\nThe same from `.off`, which keeps no fixed flags (linear elements, 1.0 and 1.5 edge lengths): a \
         tangled file's angles are the tangle's, so without flags it has no feature curves and is fitted as one \
         smooth surface (`docs/formulas.md` §7). The sphere and the torus have none to lose; the cylinder's \
         rims are smoothed over (their nodes free, the fits beside a rim spanning the cap and the side: the \
         distance below), and an element by a rim may stay inverted. Keep the flags (`.vtk`, `.msh`) for a tangled surface with creases.\n"
    );
    let mut table = Table::new(&COLUMNS);
    from_file(&mut table, io::Format::Off, &[1], &AMOUNTS[1..]);
    out.table(table);
    let _ = writeln!(out);
}
