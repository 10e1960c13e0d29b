//! §11: hexahedra, wedges and pyramids.

use std::fmt::Write as _;

use smoothlab::generate::{hex_grid, perturb_volume, HexBlock};
use smoothlab::io;
use smoothlab::model::Model;
use smoothlab::objective::{solid_objective, ObjectiveKind};
use smoothlab::quality::MeshStats;
use smoothlab::smooth::{Order, SmoothOptions, Strategy};
use smoothlab::volume::{volume_stats, VolumeMesh};
use smoothlab_page::lab::tour::measured::Table;

use crate::common::{clock, meshes_dir, opts, untangle_opts};
use crate::report::Report;
use crate::tetrahedra::run_volume;

/// Mesquite's figures on its tangled 3D files (`../shared/meshes/README.md`: Mesquite
/// ea2fc2a7 built -O3, the boundary skin fixed): its ShapeImprover's inverted before and
/// after and time, where given.
const MESQUITE_3D: [(&str, &str); 6] = [
    ("hexes/tangled/hex_5_tangled.vtk", "36 → 0"),
    ("hexes/tangled/pave1.e.vtk", "56 → 0 in 5.4 s (UntangleWrapper(BETA): 0 in 0.19 s; (SIZE) 3 passes: 240)"),
    ("hexes/tangled/pave2.e.vtk", "4 → 0 in 0.9 s"),
    ("hexes/tangled/pave3.e.vtk", "106 → 0 in 0.7 s (UntangleWrapper(BETA): 5 left)"),
    ("hexes/tangled/pave_cyl.e.vtk", "116 → 0 in 1.7 s (UntangleWrapper(BETA): 4 left)"),
    ("mixed/tangled/mixed-hex-pyr-tet.vtk", "3 inverted at start"),
];

/// Passes until no element is inverted (at most `max`) with their smoothing time, and the
/// mesh after `keep` passes (or after the last when it untangled later).
fn to_valid(mesh: &VolumeMesh, kind: ObjectiveKind, o: SmoothOptions, max: u32) -> (Option<u32>, f64, VolumeMesh) {
    let mut m = mesh.clone();
    let clock = clock();
    let mut s = smoothlab::volume::VolumeSmoother::new(o).expect("valid options");
    let objective = solid_objective(kind).expect("a 3D form");
    let mut ms = 0.0;
    for pass in 1..=max {
        let r = s.pass(&mut m, &*objective, pass, &clock);
        ms += r.elapsed_ms;
        if r.after.inverted == 0 {
            return (Some(pass), ms, m);
        }
    }
    (None, ms, m)
}

pub(crate) fn hexahedra(out: &mut Report) {
    out.section(11, "Hexahedra, wedges and pyramids (Knupp 1999; Mesquite's 3D files)");
    let _ = writeln!(
        out,
        "Every element measured by its corners' Jacobians against its kind's ideal (`docs/formulas.md` §9); an element \
         is inverted unless its Jacobian determinant is positive *everywhere* in it, decided for certain by its \
         Bernstein coefficients (\"inside\": inverted though every corner is positive). `new` + `rules` are the \
         defaults (passes until 0 inverted, at most 10; the time is the smoothing passes' wall clock); `old` + `opt` \
         is the max-min mean ratio by Freitag's ascent (10 passes). \"min SJ\" is the smallest corner scaled \
         Jacobian after the passes (1 for a cube's corner).\n"
    );
    let root = meshes_dir().join("mesquite3d");
    if !root.is_dir() {
        let _ = writeln!(out, "*Skipped: the external Mesquite meshes (`../shared/meshes/mesquite3d`) were not found.*\n");
        return;
    }
    let mut table = Table::new(&[
        "mesh",
        "elements",
        "free nodes",
        "inverted at start (inside)",
        "`new`+`rules`: passes to 0, time",
        "min SJ, mean ratio min / mean",
        "then 10 passes: min SJ",
        "`old`+`opt` 10 passes: inverted, min SJ",
        "Mesquite",
    ]);
    let (mut reached, mut worst_passes, mut pave1_ms, mut old_left) = (0, 0, None, Vec::new());
    for (file, mesquite) in MESQUITE_3D {
        // a file that cannot be smoothed: its name, why, and Mesquite's figures
        let unread = |why: String| {
            let mut cells = vec![format!("`{file}`"), why];
            cells.resize(8, String::new());
            cells.push(mesquite.to_string());
            cells
        };
        let mesh = match io::read_model_path(&root.join(file)) {
            Ok(Model::Volume(v)) => v,
            Ok(_) => {
                table.row(unread("not read as a volume".into()));
                continue;
            }
            Err(e) => {
                table.row(unread(format!("cannot be read: {e}")));
                continue;
            }
        };
        let s0 = volume_stats(&mesh);
        let v0 = s0.solid.clone().expect("a volume's statistics");
        let kinds = s0.volume_kinds.words();
        let (passes, ms, m) = to_valid(&mesh, ObjectiveKind::SmoothShape, SmoothOptions::default(), 10);
        if let Some(p) = passes {
            reached += 1;
            worst_passes = worst_passes.max(p);
            if file.contains("pave1") {
                pave1_ms = Some(ms);
            }
        }
        let s = volume_stats(&m);
        let (ten, _) = run_volume(&mesh, ObjectiveKind::SmoothShape, SmoothOptions::default(), 10);
        let s10 = volume_stats(&ten);
        let (old, _) = run_volume(&mesh, ObjectiveKind::MaxMinShape, opts(Strategy::Opt, Order::Input), 10);
        let so = volume_stats(&old);
        if so.inverted > 0 {
            old_left.push(format!("`{}`", file.rsplit('/').next().unwrap_or(file)));
        }
        let sj = |s: &MeshStats| s.solid.as_ref().map_or(f64::NAN, |v| v.min_scaled_jacobian);
        table.row(vec![
            format!("`{file}`"),
            kinds,
            mesh.free_count().to_string(),
            format!("{} ({})", s0.inverted, v0.inverted_inside),
            passes.map_or(format!("not in 10 ({} left), {ms:.0} ms", s.inverted), |p| format!("{p}, {ms:.0} ms")),
            format!("{:.3}, {:.3} / {:.3}", sj(&s), s.min_quality, s.mean_quality),
            format!("{:.3}", sj(&s10)),
            format!("{}, {:.3}", so.inverted, sj(&so)),
            mesquite.to_string(),
        ]);
    }
    out.table(table);
    let _ = writeln!(
        out,
        "\nWith the defaults {reached} of the {} files end with 0 inverted (certain: no element folded anywhere inside), \
         in at most {worst_passes} pass(es); Mesquite's ShapeImprover reaches 0 on every tangled hexahedral file, its UntangleWrapper(BETA) \
         leaves 5 and 4 on `pave3` and `pave_cyl`, and its FeasibleNewton refuses every tangled input. {}\
         The max-min `old` objective by Freitag's ascent leaves inverted elements in {}.",
        MESQUITE_3D.len(),
        pave1_ms.map_or(String::new(), |ms| format!(
            "On `pave1` the passes to 0 took {ms:.0} ms here against ShapeImprover's 5.4 s (measured on another run of \
             another machine: {:.1}× as a rough ratio, not a benchmark). ",
            5400.0 / ms
        )),
        if old_left.is_empty() { "none of them".to_string() } else { old_left.join(", ") }
    );
    let _ = writeln!(out);
    knupp_hex_grids(out);
}

/// Knupp's random grids in hexahedra: a block's free nodes moved at random.
fn knupp_hex_grids(out: &mut Report) {
    let block = hex_grid(&HexBlock::cube(8)).expect("hex grid");
    out.subsection("Knupp's random hexahedral grids");
    let _ = writeln!(
        out,
        "`generate hexgrid --cells 8` ({} nodes, {} hexahedra, {} free) with every free node moved at random within a \
         ball of 0.6 mean edge lengths (`perturb`, seeds 1–5), as Knupp tangles his grids. `new` + `rules` (the \
         defaults, 3 passes) against Knupp's procedure: `untangle` by optimization until no element is inverted (at \
         most 10 passes), then 3 passes of `condition`. \"min SJ\" is the smallest corner scaled Jacobian at the end.\n",
        block.node_count(),
        block.element_count(),
        block.free_count()
    );
    let mut table = Table::new(&[
        "seed",
        "inverted at start (inside)",
        "`new`+`rules`: inverted after 1/2/3 passes, min SJ, time",
        "`untangle`→`condition`: passes to 0, min SJ",
    ]);
    let sj = |s: &MeshStats| s.solid.as_ref().map_or(f64::NAN, |v| v.min_scaled_jacobian);
    for seed in 1..=5 {
        let tangled = perturb_volume(&block, 0.6, seed).expect("perturb");
        let s0 = volume_stats(&tangled);
        let (new, rec) = run_volume(&tangled, ObjectiveKind::SmoothShape, SmoothOptions::default(), 3);
        let per: Vec<String> = rec.iter().map(|r| r.after.inverted.to_string()).collect();
        let ms: f64 = rec.iter().map(|r| r.elapsed_ms).sum();
        let (valid, _, m) = to_valid(&tangled, ObjectiveKind::Untangle, untangle_opts(), 10);
        let (knupp, _) = run_volume(&m, ObjectiveKind::Condition, opts(Strategy::Opt, Order::Input), 3);
        table.row(vec![
            seed.to_string(),
            format!("{} ({})", s0.inverted, s0.solid.as_ref().map_or(0, |v| v.inverted_inside)),
            format!("{}, {:.3}, {ms:.0} ms", per.join("/"), sj(&volume_stats(&new))),
            format!("{}, {:.3}", valid.map_or("not in 10".to_string(), |p| p.to_string()), sj(&volume_stats(&knupp))),
        ]);
    }
    out.table(table);
    let _ = writeln!(out);
}
