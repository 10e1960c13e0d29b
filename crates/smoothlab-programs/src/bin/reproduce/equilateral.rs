//! §5: Mesquite's `equil_tri` meshes.

use std::fmt::Write as _;

use smoothlab::io;
use smoothlab::objective::{objective_with, ObjectiveKind, Penalty};
use smoothlab::smooth::{Order, Smoother, Strategy};
use smoothlab_page::lab::tour::measured::Table;

use crate::common::{clock, meshes_dir, opts, worst_alpha_error};
use crate::report::Report;

pub(crate) fn equilateral(out: &mut Report) {
    const MAX_PASSES: u32 = 50;
    const MAX_ITER: u32 = 20;
    out.section(5, "Mesquite's `equil_tri.vtk` and `equil_tri2.vtk`");
    let _ = writeln!(
        out,
        "One free node inside a regular hexagon (`equil_tri`: six triangles; `equil_tri2`: its own file). \
         Optimization (`opt`) with `new`, `old` and `condition`, {MAX_ITER} solver iterations per call, passes until \
         every corner α is within 10⁻⁶ of 1 (at most {MAX_PASSES}). Mesquite: \"become exactly equilateral\". The file \
         stores √3 to 9 digits, which bounds how equilateral the triangles can be.\n"
    );
    let dir = meshes_dir().join("mesquite/tris/untangled");
    if !dir.is_dir() {
        let _ = writeln!(out, "*Skipped: the external Mesquite meshes (`../shared/meshes`) were not found.*\n");
        return;
    }
    let mut table =
        Table::new(&["mesh", "objective", "worst |α − 1| at start", "after", "passes", "solver iterations"]);
    for file in ["equil_tri.vtk", "equil_tri2.vtk"] {
        let mesh = match io::read_path(&dir.join(file)) {
            Ok(m) => m,
            Err(e) => {
                let mut cells = vec![file.to_string(), format!("cannot be read: {e}")];
                cells.resize(6, String::new());
                table.row(cells);
                continue;
            }
        };
        for kind in [ObjectiveKind::SmoothShape, ObjectiveKind::MaxMinShape, ObjectiveKind::Condition] {
            let mut m = mesh.clone();
            let obj = objective_with(kind, Penalty::default());
            let mut s = Smoother::new(opts(Strategy::Opt, Order::Input).with_max_iter(MAX_ITER)).expect("options");
            let c = clock();
            let (mut passes, mut iters) = (0, 0);
            while passes < MAX_PASSES && worst_alpha_error(&m) > 1e-6 {
                let r = s.pass(&mut m, &*obj, &c);
                passes += 1;
                iters += r.counts.solver_iterations;
            }
            table.row(vec![
                file.to_string(),
                format!("`{kind}`"),
                format!("{:.3e}", worst_alpha_error(&mesh)),
                format!("{:.3e}", worst_alpha_error(&m)),
                passes.to_string(),
                iters.to_string(),
            ]);
        }
    }
    out.table(table);
    let _ = writeln!(out);
}
