//! Issue 33: the time to quality, the release CLI's defaults on tangled meshes.

use std::fmt::Write as _;
use std::time::Instant;

use smoothlab::generate::PlateKind;
use smoothlab::model::Model;
use smoothlab::quality::mesh_stats;

use crate::common::{fmt_ms, median, target_mark};

/// The release binary `smoothlab` beside this program (`target/release/smoothlab` for
/// `target/release/perf`), which `make performance` builds first.
fn smoothlab_binary() -> Option<std::path::PathBuf> {
    let exe = std::env::current_exe().ok()?;
    let bin = exe.parent()?.join(format!("smoothlab{}", std::env::consts::EXE_SUFFIX));
    bin.is_file().then_some(bin)
}

/// The passes to try before saying a mesh is not untangled, as the reproduction's.
const MAX_PASSES_TO_VALID: u32 = 10;

/// One run of `smoothlab smooth IN -o OUT --passes N --json`: each pass's inverted count
/// after it, the smoothing time it reports (`time_ms`) and the process's wall time.
struct CliRun {
    inverted: Vec<u64>,
    time_ms: f64,
    wall_ms: f64,
}

fn cli_smooth(bin: &std::path::Path, input: &std::path::Path, out: &std::path::Path, passes: u32) -> Result<CliRun, String> {
    let t = Instant::now();
    let o = std::process::Command::new(bin)
        .arg("smooth")
        .arg(input)
        .arg("-o")
        .arg(out)
        .args(["--passes", &passes.to_string(), "--json"])
        .output()
        .map_err(|e| e.to_string())?;
    let wall_ms = t.elapsed().as_secs_f64() * 1e3;
    if !o.status.success() {
        return Err(String::from_utf8_lossy(&o.stderr).trim().to_string());
    }
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).map_err(|e| e.to_string())?;
    let inverted = v["passes"].as_array().into_iter().flatten().map(|p| p["inverted"].as_u64().unwrap_or(u64::MAX)).collect();
    Ok(CliRun { inverted, time_ms: v["time_ms"].as_f64().unwrap_or(f64::NAN), wall_ms })
}

/// A mesh's time to quality with the CLI's defaults.
struct ToValid {
    inverted0: usize,
    /// Passes to 0 inverted (0: valid as read), or `None` when not within
    /// [`MAX_PASSES_TO_VALID`], with what is left.
    passes: Option<u32>,
    left: u64,
    /// Median wall time of `smoothlab smooth --passes K` and the smoothing time it reports, ms.
    wall_ms: f64,
    smoothing_ms: f64,
}

/// The passes the defaults take to 0 inverted, then `smoothlab smooth --passes K` timed
/// `reps` times. K is found by runs of [`PROBE_PASSES`] passes in turn (each run's `--json`
/// gives every pass's inverted count, so a run of N passes finds any K ≤ N); the run that
/// found K counts as one of the timed runs when it ran K passes.
fn time_to_valid(bin: &std::path::Path, input: &std::path::Path, dir: &std::path::Path, inverted0: usize, reps: usize) -> Result<ToValid, String> {
    let ext = input.extension().map(|e| e.to_string_lossy().into_owned()).unwrap_or_else(|| "vtk".into());
    let out = dir.join(format!("smoothed.{ext}"));
    let (mut runs, mut passes, mut left) = (Vec::new(), None, 0);
    for n in PROBE_PASSES {
        let run = cli_smooth(bin, input, &out, n)?;
        left = run.inverted.last().copied().unwrap_or(0);
        passes = if inverted0 == 0 { Some(0) } else { run.inverted.iter().position(|&i| i == 0).map(|k| k as u32 + 1) };
        if passes.is_some_and(|k| k.max(1) == n) || (passes.is_none() && n == MAX_PASSES_TO_VALID) {
            runs.push(run);
        }
        if passes.is_some() {
            break;
        }
    }
    let timed = passes.unwrap_or(MAX_PASSES_TO_VALID).max(1);
    while runs.len() < reps {
        runs.push(cli_smooth(bin, input, &out, timed)?);
    }
    Ok(ToValid {
        inverted0,
        passes,
        left,
        wall_ms: median(runs.iter().map(|r| r.wall_ms).collect()),
        smoothing_ms: median(runs.iter().map(|r| r.time_ms).collect()),
    })
}

/// The runs that look for the passes to 0 inverted, in turn: 1, 2, the CLI's default 3,
/// then [`MAX_PASSES_TO_VALID`].
const PROBE_PASSES: [u32; 4] = [1, 2, 3, MAX_PASSES_TO_VALID];

fn fmt_passes(t: &ToValid) -> String {
    match t.passes {
        Some(0) => "valid as read".into(),
        Some(k) => k.to_string(),
        None => format!("not in {MAX_PASSES_TO_VALID} ({} left)", t.left),
    }
}

/// The tangled plates of the reproduction (`docs/reproduction.md` §2): kind, order.
const TANGLED_PLATES: [(&str, PlateKind, u8); 6] = [
    ("triangles", PlateKind::Tri, 1),
    ("quads", PlateKind::Quad, 1),
    ("mixed", PlateKind::Mixed, 1),
    ("triangles, order 2", PlateKind::Tri, 2),
    ("quads, order 2", PlateKind::Quad, 2),
    ("mixed, order 2", PlateKind::Mixed, 2),
];
/// Their perturbation amounts and seeds (§2's: 150 plates).
const PLATE_AMOUNTS: [f64; 5] = [0.6, 0.8, 1.0, 1.25, 1.5];
const PLATE_SEEDS: [u64; 5] = [1, 2, 3, 4, 5];

/// Mesquite's meshes, read in place beside the crate (as the `reproduce` program and the tests).
fn mesquite_dir(name: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/meshes").join(name)
}

/// The `.vtk` files of `root/group/tangled` for each group, sorted, as `group/tangled/NAME`.
fn tangled_files(root: &std::path::Path, groups: &[&str]) -> Vec<(String, std::path::PathBuf)> {
    let mut files = Vec::new();
    for group in groups {
        let Ok(rd) = std::fs::read_dir(root.join(group).join("tangled")) else { continue };
        let mut names: Vec<std::path::PathBuf> =
            rd.filter_map(|e| e.ok().map(|e| e.path())).filter(|p| p.extension().is_some_and(|e| e == "vtk")).collect();
        names.sort();
        for p in names {
            files.push((format!("{group}/tangled/{}", p.file_name().unwrap_or_default().to_string_lossy()), p));
        }
    }
    files
}

/// Mesquite's ShapeImprover on `pave1.e.vtk` (`../shared/meshes/README.md`: 56 → 0
/// inverted in 5.4 s), and issue 33's target: 10× below it.
pub(crate) const PAVE1_MESQUITE_S: f64 = 5.4;

/// The time-to-quality rows: (family or file, mesh words, its figures), and pave1's wall time.
pub(crate) struct QualityReport {
    pub(crate) text: String,
    pub(crate) pave1_ms: Option<f64>,
    /// (meshes reaching 0 inverted, meshes, most passes taken)
    pub(crate) reached: (usize, usize, u32),
}

pub(crate) fn time_to_quality(quick: bool) -> QualityReport {
    use smoothlab::generate::{perturb, plate};
    let mut w = String::new();
    let mut reached = (0usize, 0usize, 0u32);
    let mut pave1_ms = None;
    let _ = writeln!(w, "## Time to quality (issue 33)\n");
    let Some(bin) = smoothlab_binary() else {
        let _ = writeln!(
            w,
            "Not measured in this run: the release binary `smoothlab` was not found beside this program (`make performance` builds it first: `cargo build --release -p smoothlab-cli --features parallel --bin smoothlab`).\n"
        );
        return QualityReport { text: w, pave1_ms, reached };
    };
    let reps = if quick { 1 } else { 3 };
    let _ = writeln!(
        w,
        "The user's figure: the wall time of `smoothlab smooth IN -o OUT --passes K`, the release binary with every other option the default \
         (`rules` with `new`, priority order), reading and writing included. K is the number of passes the defaults take to 0 inverted elements, \
         found by runs of {} passes (a file valid as read is only counted). *Smoothing* is the passes' own time as the command reports it \
         (`time_ms`). Median of {reps} run(s) of each mesh.\n",
        PROBE_PASSES.map(|n| n.to_string()).join(", then ")
    );
    // the meshes tangled at start (some files of the tangled folders are valid as read)
    let record = |reached: &mut (usize, usize, u32), t: &ToValid| {
        if t.inverted0 == 0 {
            return;
        }
        reached.1 += 1;
        if let Some(k) = t.passes {
            reached.0 += 1;
            reached.2 = reached.2.max(k);
        }
    };
    let dir = std::env::temp_dir().join(format!("smoothlab-perf-quality-{}", std::process::id()));
    let _ = std::fs::create_dir_all(&dir);
    // the tangled plates of the reproduction, generated and written as .msh
    let _ = writeln!(
        w,
        "**Tangled plates** (`docs/reproduction.md` §2: `plate(kind, order, 4)`, every interior node moved by `perturb` by {} mean edge lengths, seeds {}: {} plates of each kind), each run once:\n",
        PLATE_AMOUNTS.map(|a| a.to_string()).join(", "),
        PLATE_SEEDS.map(|s| s.to_string()).join(", "),
        PLATE_AMOUNTS.len() * PLATE_SEEDS.len()
    );
    let _ = writeln!(w, "| plates | nodes | inverted at start | passes to 0: most (plates untangled) | wall time: median / largest | smoothing: median / largest |");
    let _ = writeln!(w, "|---|---:|---:|---:|---:|---:|");
    for (name, kind, order) in TANGLED_PLATES {
        let base = plate(kind, order, 4).expect("a plate");
        let mut runs = Vec::new();
        for amount in PLATE_AMOUNTS {
            for seed in PLATE_SEEDS {
                let m = perturb(&base, amount, seed).expect("perturbed");
                let file = dir.join("plate.msh");
                smoothlab::io::write_path(&m, &file, &smoothlab::io::WriteOptions::default()).expect("write a plate");
                match time_to_valid(&bin, &file, &dir, mesh_stats(&m).inverted, 1) {
                    Ok(t) => runs.push(t),
                    Err(e) => eprintln!("perf: smoothlab smooth on a {name} plate: {e}"),
                }
            }
        }
        runs.iter().for_each(|t| record(&mut reached, t));
        let inv: Vec<usize> = runs.iter().map(|t| t.inverted0).collect();
        let most = runs.iter().filter_map(|t| t.passes).max().unwrap_or(0);
        let done = runs.iter().filter(|t| t.passes.is_some()).count();
        let wall: Vec<f64> = runs.iter().map(|t| t.wall_ms).collect();
        let sm: Vec<f64> = runs.iter().map(|t| t.smoothing_ms).collect();
        let max = |v: &[f64]| v.iter().copied().fold(f64::NAN, f64::max);
        let _ = writeln!(
            w,
            "| {name} | {} | {}–{} | {most} ({done} of {}) | {} / {} | {} / {} |",
            base.node_count(),
            inv.iter().min().unwrap_or(&0),
            inv.iter().max().unwrap_or(&0),
            runs.len(),
            fmt_ms(median(wall.clone())),
            fmt_ms(max(&wall)),
            fmt_ms(median(sm.clone())),
            fmt_ms(max(&sm))
        );
    }
    // Mesquite's tangled files
    for (folder, groups, what) in [
        ("mesquite", &["tris", "quads", "mixed"][..], "Mesquite's tangled planar files"),
        ("mesquite3d", &["hexes", "mixed"][..], "Mesquite's tangled 3D files (hexahedra; a mixed mesh)"),
    ] {
        let root = mesquite_dir(folder);
        let _ = writeln!(w, "\n**{what}** (`../shared/meshes/{folder}`, every `.vtk` of its `*/tangled` folders, read with their `fixed` flags):\n");
        if !root.is_dir() {
            let _ = writeln!(w, "*Not measured: the external Mesquite meshes (`../shared/meshes/{folder}`) were not found.*");
            continue;
        }
        let _ = writeln!(w, "| file | nodes | elements | inverted at start | passes to 0 | wall time | smoothing |");
        let _ = writeln!(w, "|---|---:|---:|---:|---:|---:|---:|");
        // the files valid as read are timed too, but only counted: they have no time to quality
        let mut valid = 0;
        for (name, path) in tangled_files(&root, groups) {
            let model = match smoothlab::io::read_model_path(&path) {
                Ok(m) => m,
                Err(e) => {
                    let _ = writeln!(w, "| `{name}` | cannot be read: {e} | | | | | |");
                    continue;
                }
            };
            let (nodes, elements) = match &model {
                Model::Planar(m) => (m.node_count(), m.element_count()),
                Model::Surface(s) => (s.flat().node_count(), s.flat().element_count()),
                Model::Volume(v) => (v.node_count(), v.element_count()),
            };
            eprintln!("perf: time to quality, {name} …");
            match time_to_valid(&bin, &path, &dir, model.stats().inverted, reps) {
                Ok(t) if t.passes == Some(0) => valid += 1,
                Ok(t) => {
                    record(&mut reached, &t);
                    if name.ends_with("pave1.e.vtk") && t.passes.is_some() {
                        pave1_ms = Some(t.wall_ms);
                    }
                    let _ = writeln!(
                        w,
                        "| `{name}` | {nodes} | {elements} | {} | {} | {} | {} |",
                        t.inverted0,
                        fmt_passes(&t),
                        fmt_ms(t.wall_ms),
                        fmt_ms(t.smoothing_ms)
                    );
                }
                Err(e) => {
                    let _ = writeln!(w, "| `{name}` | {nodes} | {elements} | `smoothlab smooth` failed: {e} | | | |");
                }
            }
        }
        if valid > 0 {
            let _ = writeln!(w, "\nAnd {valid} file(s) of these folders valid as read.");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    let _ = writeln!(
        w,
        "\n{} of the {} meshes tangled at start end with 0 inverted with the defaults, in at most {} pass(es). Issue 33's target on hexahedra: below Mesquite's ShapeImprover's \
         {PAVE1_MESQUITE_S} s on `pave1` by 10×, ≤ {:.2} s: {}.\n",
        reached.0,
        reached.1,
        reached.2,
        PAVE1_MESQUITE_S / 10.0,
        match pave1_ms {
            Some(ms) => format!("{} {}", fmt_ms(ms), target_mark(ms / 1e3, PAVE1_MESQUITE_S / 10.0)),
            None => "not measured (the file was not found or not untangled)".into(),
        }
    );
    QualityReport { text: w, pave1_ms, reached }
}
