//! §12: Livesu et al.'s real hexahedral meshes with the boundary fixed.

use std::fmt::Write as _;

use smoothlab::model::Model;
use smoothlab::{MeshStats, Smoothing, VolumeMesh};
use smoothlab_page::lab::tour::measured::Table;

use crate::common::meshes_dir;
use crate::report::Report;

/// The inputs the defaults untangle with their boundary fixed (the rows of [`LIVESU_ALL`]).
const LIVESU: [&str; 6] = ["block", "block_stresstest", "bunny", "cap", "dancingchildren", "hanger_stresstest"];

/// The folder of the meshes, or a line saying they were not found.
fn livesu_root(out: &mut Report) -> Option<std::path::PathBuf> {
    let root = meshes_dir().join("livesu2015");
    if !root.is_dir() {
        let _ = writeln!(out, "*Skipped: the external meshes (`../shared/meshes/livesu2015`) were not found.*\n");
        return None;
    }
    Some(root)
}

/// The smallest and the mean of the elements' smallest corner scaled Jacobians.
fn scaled_jacobians(m: &VolumeMesh) -> (f64, f64) {
    let sj: Vec<f64> = (0..m.element_count()).map(|e| m.measures(e).scaled_jacobian).collect();
    (sj.iter().copied().fold(f64::INFINITY, f64::min), sj.iter().sum::<f64>() / sj.len() as f64)
}

pub(crate) fn livesu(out: &mut Report) {
    out.section(12, "Real hexahedral meshes (Livesu et al. 2015), the boundary fixed");
    let _ = writeln!(
        out,
        "The inputs of Livesu, Sheffer, Vining and Tarini's \"Practical Hex-Mesh Optimization via Edge-Cone \
         Rectification\" (SIGGRAPH 2015) that the defaults untangle with their boundary skin fixed. \"SJ\" is the \
         smallest corner scaled Jacobian of an element; min and mean are over the elements, as the published figures \
         are. \"no finish\" is the defaults with `--finish 0`; \"defaults\" adds the finish (`docs/formulas.md` §4). \
         \"cap\" is the most any smoother can reach with the boundary where it is: a corner whose node and two edge \
         neighbours are fixed has an SJ of at most the sine of the angle between those two edges \
         (`VolumeMesh::scaled_jacobian_cap`). The published outputs move the boundary; §13 lets it slide.\n"
    );
    let Some(root) = livesu_root(out) else { return };
    let mut table = Table::new(&[
        "mesh",
        "hexahedra",
        "inverted at start",
        "no finish: inverted, min / mean SJ",
        "defaults: inverted, min / mean SJ, time",
        "cap",
        "published: min / mean SJ",
    ]);
    let (mut reached, mut below_cap) = (Vec::new(), Vec::new());
    for (name, published_min, published_mean) in LIVESU_ALL.into_iter().filter(|(n, ..)| LIVESU.contains(n)) {
        let Ok(Model::Volume(input)) = smoothlab::read(root.join(format!("{name}_in.mesh"))) else {
            table.row(vec![format!("`{name}`"), "not read as a volume".into(), String::new(), String::new(), String::new(), String::new(), String::new()]);
            continue;
        };
        let inverted = |s: &MeshStats| s.inverted;
        let start = input.element_count();
        let at_start = (0..start).filter(|&e| input.is_inverted(e)).count();
        let run = |smoothing: Smoothing| {
            let mut m = Model::Volume(input.clone());
            let report = m.smooth(&smoothing).expect("the defaults take every volume");
            let Model::Volume(v) = m else { unreachable!("smoothing keeps the kind") };
            (report, v)
        };
        let (plain, p) = run(Smoothing::default().finish(0));
        let (full, f) = run(Smoothing::default());
        let ((p_min, p_mean), (f_min, f_mean)) = (scaled_jacobians(&p), scaled_jacobians(&f));
        let cap = input.scaled_jacobian_cap();
        if f_min >= published_min {
            reached.push(format!("`{name}`"));
        }
        if cap < published_min {
            below_cap.push(format!("`{name}`"));
        }
        table.row(vec![
            format!("`{name}`"),
            start.to_string(),
            at_start.to_string(),
            format!("{}, {p_min:.3} / {p_mean:.3}", inverted(plain.stats())),
            format!("{}, {f_min:.3} / {f_mean:.3}, {:.0} ms", inverted(full.stats()), full.time_ms()),
            format!("{cap:.3}"),
            format!("{published_min:.3} / {published_mean:.3}"),
        ]);
    }
    out.table(table);
    let _ = writeln!(
        out,
        "\nThe defaults reach the published smallest SJ on {}. The published value lies above the cap, out of reach \
         with the boundary fixed, on {}.\n",
        if reached.is_empty() { "none".to_string() } else { reached.join(", ") },
        if below_cap.is_empty() { "none".to_string() } else { below_cap.join(", ") }
    );
}

/// The eleven inputs, with the published outputs' smallest and mean scaled Jacobian
/// (`../shared/meshes/README.md`).
const LIVESU_ALL: [(&str, f64, f64); 11] = [
    ("armadillo", 0.143, 0.900),
    ("armadillo_stresstest", 0.129, 0.944),
    ("block", 0.250, 0.870),
    ("block_stresstest", 0.250, 0.834),
    ("bunny", 0.606, 0.972),
    ("bust", 0.114, 0.922),
    ("cap", 0.106, 0.870),
    ("dancingchildren", 0.354, 0.942),
    ("dragon", 0.102, 0.905),
    ("hanger_stresstest", 0.716, 0.987),
    ("impeller_stresstest", 0.184, 0.942),
];

pub(crate) fn livesu_sliding(out: &mut Report) {
    use smoothlab::volume::{BoundaryRule, FEATURE_ANGLE_DEG};
    out.section(13, "Sliding boundaries: real hexahedral meshes (Livesu et al. 2015), Mesquite's files");
    let _ = writeln!(
        out,
        "The eleven inputs of §12 with the defaults and `--boundary slide` (issue 58): boundary nodes slide on the \
         boundary as loaded, curve nodes along its feature curves (faces turning by more than {FEATURE_ANGLE_DEG}°, \
         curves of fewer than 3 edges that end nowhere dropped, never at a folded face), corners stay. \"fixed\" is \
         the defaults. \"distance\" is the largest distance of a sliding node from the boundary as loaded, in its \
         mean edge lengths. \"inverted\" counts by the certain test (the Jacobian's sign inside the element too); \
         \"impossible\" is how many of them have an inverted corner of four nodes that cannot move. A pass that \
         ends with inverted elements gives their free corners a last search that raises the least Bernstein \
         coefficient of their `det J` (a fold inside a hexahedron its corners do not see); there a sliding node may \
         leave the boundary by up to {lift} % of its mean edge, issue 58's bound. \"10 passes\" runs on where 3 \
         leave the mesh tangled.\n",
        lift = smoothlab::volume::LIFT * 100.0
    );
    let Some(root) = livesu_root(out) else { return };
    let mut table = Table::new(&[
        "mesh",
        "hexahedra",
        "inverted at start",
        "fixed: inverted, min / mean SJ",
        "slide: inverted (impossible), min / mean SJ, time",
        "corners, curves",
        "distance",
        "slide, 10 passes: inverted, min / mean SJ, distance, time",
        "published: min / mean SJ",
    ]);
    let (mut untangled, mut untangled_longer, mut reached) = (0, 0, Vec::new());
    for (name, published_min, published_mean) in LIVESU_ALL {
        let Ok(Model::Volume(input)) = smoothlab::read(root.join(format!("{name}_in.mesh"))) else {
            let mut row = vec![format!("`{name}`"), "not read as a volume".into()];
            row.resize(9, String::new());
            table.row(row);
            continue;
        };
        let at_start = (0..input.element_count()).filter(|&e| input.is_inverted(e)).count();
        let run = |smoothing: Smoothing| {
            let mut m = Model::Volume(input.clone());
            let report = m.smooth(&smoothing).expect("the defaults take every linear volume");
            let Model::Volume(v) = m else { unreachable!("smoothing keeps the kind") };
            (report, v)
        };
        let (fixed, f) = run(Smoothing::default());
        let (slide, s) = run(Smoothing::default().boundary(BoundaryRule::Slide));
        let ((f_min, f_mean), (s_min, s_mean)) = (scaled_jacobians(&f), scaled_jacobians(&s));
        let b = slide.boundary().expect("a sliding run reports its boundary");
        let inverted = slide.stats().inverted;
        untangled += (inverted == 0) as usize;
        if inverted == 0 && s_min >= published_min {
            reached.push(format!("`{name}`"));
        }
        let longer = if inverted == 0 {
            "as 3".to_string()
        } else {
            let (r, l) = run(Smoothing::default().boundary(BoundaryRule::Slide).passes(10));
            let (l_min, l_mean) = scaled_jacobians(&l);
            let lb = r.boundary().expect("a sliding run reports its boundary");
            untangled_longer += (r.stats().inverted == 0) as usize;
            format!(
                "{}, {l_min:.3} / {l_mean:.3}, {:.1e}, {:.0} ms",
                r.stats().inverted,
                lb.max_distance / lb.mean_edge,
                r.time_ms()
            )
        };
        table.row(vec![
            format!("`{name}`"),
            input.element_count().to_string(),
            at_start.to_string(),
            format!("{}, {f_min:.3} / {f_mean:.3}", fixed.stats().inverted),
            format!(
                "{inverted} ({}), {s_min:.3} / {s_mean:.3}, {:.0} ms",
                slide.untangling_impossible().len(),
                slide.time_ms()
            ),
            format!("{}, {}", b.corners, b.curves),
            format!("{:.1e}", b.max_distance / b.mean_edge),
            longer,
            format!("{published_min:.3} / {published_mean:.3}"),
        ]);
    }
    out.table(table);
    let _ = writeln!(
        out,
        "\nSliding untangles {untangled} of the eleven in 3 passes, {} in 10; its smallest SJ (3 passes) reaches the \
         published one on {}.\n",
        untangled + untangled_longer,
        if reached.is_empty() { "none".to_string() } else { reached.join(", ") }
    );
    mesquite_sliding(out);
}

/// Mesquite's tangled hexahedra and its planar test files, fixed against sliding: the
/// files' `fixed` flags cover their whole boundary, so they mark it and hold nothing.
fn mesquite_sliding(out: &mut Report) {
    use smoothlab::volume::BoundaryRule;
    let _ = writeln!(
        out,
        "\nMesquite's tangled hexahedra (`mesquite3d/hexes/tangled`) and its planar files of §3 (linear ones), with \
         the defaults, the boundary fixed and sliding. \"angles\" are dihedral angles in volumes; \"SJ\" the \
         smallest corner scaled Jacobian (volumes).\n"
    );
    let mut files: Vec<(String, std::path::PathBuf)> = Vec::new();
    let hexes = meshes_dir().join("mesquite3d/hexes/tangled");
    if let Ok(rd) = std::fs::read_dir(&hexes) {
        let mut names: Vec<_> = rd.filter_map(|e| e.ok().map(|e| e.path())).filter(|p| p.extension().is_some_and(|e| e == "vtk")).collect();
        names.sort();
        files.extend(names.into_iter().map(|p| (format!("hexes/tangled/{}", p.file_name().unwrap_or_default().to_string_lossy()), p)));
    }
    files.extend(crate::mesquite::mesquite_files().unwrap_or_default());
    if files.is_empty() {
        let _ = writeln!(out, "*Skipped: the external Mesquite meshes (`../shared/meshes`) were not found.*\n");
        return;
    }
    let mut table = Table::new(&[
        "file",
        "elements",
        "inverted at start",
        "fixed: inverted, angles, SJ",
        "slide: inverted, angles, SJ",
        "corners, sliding nodes",
        "distance",
    ]);
    let (mut better, mut more_inverted, mut rows) = (0, Vec::new(), 0);
    for (name, path) in files {
        let Ok(model) = smoothlab::read(&path) else { continue };
        let quadratic = match &model {
            Model::Planar(m) => m.has_quadratic(),
            Model::Volume(v) => v.is_quadratic(),
            Model::Surface(_) => true,
        };
        if quadratic {
            continue;
        }
        let start = model.stats();
        let run = |rule: BoundaryRule| {
            let mut m = model.clone();
            m.smooth(&Smoothing::default().boundary(rule)).expect("the defaults take every linear mesh")
        };
        let (fixed, slide) = (run(BoundaryRule::Fixed), run(BoundaryRule::Slide));
        let shown = |s: &MeshStats| {
            let sj = s.solid.as_ref().map_or(String::new(), |v| format!(", {:.3}", v.min_scaled_jacobian));
            format!("{}, {:.1}°–{:.1}°{sj}", s.inverted, s.min_angle_deg, s.max_angle_deg)
        };
        let b = slide.boundary().expect("a sliding run reports its boundary");
        let (f, s) = (fixed.stats(), slide.stats());
        better += (s.inverted < f.inverted || (s.inverted == f.inverted && s.min_angle_deg > f.min_angle_deg)) as usize;
        if s.inverted > f.inverted {
            more_inverted.push(format!("`{name}`"));
        }
        rows += 1;
        table.row(vec![
            format!("`{name}`"),
            start.elements.to_string(),
            start.inverted.to_string(),
            shown(f),
            shown(s),
            format!("{}, {}", b.corners + b.held, b.surface_nodes + b.curve_nodes),
            format!("{:.1e}", b.max_distance / b.mean_edge),
        ]);
    }
    out.table(table);
    let _ = writeln!(
        out,
        "\nSliding ends with fewer inverted elements, or as many and a larger smallest angle, on {better} of these {rows} \
         files, and with more inverted elements than the fixed boundary on {}. A tangled planar mesh's boundary is \
         held until a pass leaves it valid (its boundary edges may be folded with it).\n",
        if more_inverted.is_empty() { "none".to_string() } else { more_inverted.join(", ") }
    );
}
