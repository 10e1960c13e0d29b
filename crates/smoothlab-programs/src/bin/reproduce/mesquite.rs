//! §3: Mesquite's tangled meshes.

use std::fmt::Write as _;
use std::path::PathBuf;

use smoothlab::io;
use smoothlab::objective::ObjectiveKind;
use smoothlab::quality::mesh_stats;
use smoothlab::smooth::{Order, Strategy};
use smoothlab_page::lab::tour::measured::Table;

use crate::common::{fmt_kappa, kappa, meshes_dir, never, opts, run, untangle_opts, untangled, Choice, NEW_ANGLE};
use crate::report::Report;

pub(crate) fn mesquite_files() -> Option<Vec<(String, PathBuf)>> {
    let root = meshes_dir().join("mesquite");
    if !root.is_dir() {
        return None;
    }
    let mut files = Vec::new();
    for group in ["tris", "quads", "mixed"] {
        let dir = root.join(group).join("tangled");
        let Ok(rd) = std::fs::read_dir(&dir) else { continue };
        let mut names: Vec<PathBuf> =
            rd.filter_map(|e| e.ok().map(|e| e.path())).filter(|p| p.extension().is_some_and(|e| e == "vtk")).collect();
        names.sort();
        for p in names {
            let name = format!("{group}/tangled/{}", p.file_name().unwrap_or_default().to_string_lossy());
            files.push((name, p));
        }
    }
    let shest = root.join("quads/untangled/shest_grid32.vtk");
    if shest.is_file() {
        files.push(("quads/untangled/shest_grid32.vtk".into(), shest));
    }
    Some(files)
}

pub(crate) fn mesquite_tangled(out: &mut Report) {
    out.section(3, "Mesquite's tangled meshes");
    let _ = writeln!(
        out,
        "Every file of Mesquite's `tris/tangled`, `quads/tangled` and `mixed/tangled` folders, plus \
         `quads/untangled/shest_grid32.vtk` (which Mesquite's untangling test uses), with the files' `fixed` flags. \
         Three pipelines: `new` + `rules` with the defaults (the barrier penalty, priority order; passes until no \
         element is inverted, at most 10; the aim is ≤ 3), and the same with the first, angle design of the penalty; `untangle` (Knupp's objective in Mesquite's form, see §4) by optimization pass after pass until no element is inverted (at most 10), \
         then 3 optimization passes of `condition`; and `old` + `opt` (10 passes). Mesquite reaches 0 inverted on all \
         of them except `mixed/tangled/hybrid_3quad_1tri_tangled.vtk` (three free nodes start on one point).\n"
    );
    let Some(files) = mesquite_files() else {
        let _ = writeln!(out, "*Skipped: the external Mesquite meshes (`../shared/meshes`) were not found.*\n");
        return;
    };
    let mut table = Table::new(&[
        "mesh",
        "elements",
        "free nodes",
        "inverted at start",
        "`new`+`rules`: inverted after 1/2/3 passes, passes to 0",
        "the same with the angle design",
        "`untangle`→`condition`: passes to 0, inverted after, max κ",
        "`old`+`opt`: inverted after 3 / 10 passes",
    ]);
    let (mut tangled, mut done3, mut done3_angle) = (0, 0, 0);
    let mut unt_hybrid = None;
    let (mut unt_ok, mut unt_max) = (0, 0);
    let (mut failed, mut hybrid_ok) = (Vec::new(), false);
    for (name, path) in files {
        let mesh = match io::read_path(&path) {
            Ok(m) => m,
            Err(e) => {
                let mut cells = vec![name.clone(), format!("cannot be read: {e}")];
                cells.resize(8, String::new());
                table.row(cells);
                continue;
            }
        };
        let s0 = mesh_stats(&mesh);
        let cell = |choice: Choice| {
            let new = run(&mesh, choice, opts(Strategy::Rules, Order::Priority), 10, untangled);
            let first3: Vec<String> =
                (0..3).map(|i| new.passes.get(i).map_or("·".into(), |p| p.after.inverted.to_string())).collect();
            format!(
                "{} — {}",
                first3.join("/"),
                new.passes_to_valid()
                    .map_or(format!("not in 10 ({} left)", new.last_inverted(s0.inverted)), |n| n.to_string())
            )
        };
        let (new_cell, angle_cell) = (cell(ObjectiveKind::SmoothShape.into()), cell(NEW_ANGLE));
        if s0.inverted > 0 {
            tangled += 1;
            let within3 = |c: &str| c.rsplit("— ").next().and_then(|n| n.parse::<u32>().ok()).is_some_and(|n| n <= 3);
            done3 += within3(&new_cell) as usize;
            if !within3(&new_cell) {
                failed.push(format!("`{name}`"));
            } else if name.contains("hybrid") {
                hybrid_ok = true;
            }
            done3_angle += within3(&angle_cell) as usize;
        }
        let unt = run(&mesh, ObjectiveKind::Untangle, untangle_opts(), 10, untangled);
        if s0.inverted > 0 {
            unt_ok += unt.passes_to_valid().is_some() as usize;
            unt_max = unt_max.max(unt.passes_to_valid().unwrap_or(0));
            if name.contains("hybrid") {
                unt_hybrid = Some(unt.passes_to_valid().is_some());
            }
        }
        let unt_cell = match unt.passes_to_valid() {
            Some(n) => {
                let cond = run(&unt.mesh, ObjectiveKind::Condition, opts(Strategy::Opt, Order::Input), 3, never);
                let s = mesh_stats(&cond.mesh);
                format!("{n}, {}, {}", s.inverted, fmt_kappa(kappa(&cond.mesh).0))
            }
            None => format!("not in 10, {} left, —", unt.last_inverted(s0.inverted)),
        };
        let old = run(&mesh, ObjectiveKind::MaxMinShape, opts(Strategy::Opt, Order::Input), 10, never);
        let old_cell = format!("{} / {}", old.passes[2].after.inverted, old.passes[9].after.inverted);
        table.row(vec![
            name.clone(),
            s0.elements.to_string(),
            s0.free_nodes.to_string(),
            s0.inverted.to_string(),
            new_cell,
            angle_cell,
            unt_cell,
            old_cell,
        ]);
    }
    out.table(table);
    let _ = writeln!(
        out,
        "\nOf the {tangled} files that start with inverted elements, `new` + `rules` with the defaults leaves none \
         inverted within 3 passes on {done3} (with the angle design: {done3_angle}). Mesquite's own untangler (its \
         best metric) reaches 0 on all but the hybrid mesh. The hybrid mesh (three free nodes on one point) is {} by \
         `new` + `rules` within 3 passes. Not untangled within 3 passes with the defaults: {}. `untangle` (then \
         `condition`) leaves none inverted on {unt_ok} of the {tangled} ({}), in at most {unt_max} passes.\n",
        if hybrid_ok { "untangled" } else { "not untangled" },
        if failed.is_empty() { "none".to_string() } else { failed.join(", ") },
        match unt_hybrid {
            Some(true) => "the hybrid mesh included",
            Some(false) => "not the hybrid mesh",
            None => "the hybrid mesh was not found",
        }
    );
}
