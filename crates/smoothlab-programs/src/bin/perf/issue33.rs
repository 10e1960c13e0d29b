//! Issue 33: performance versus Mesquite.
//! Its sections are the 3D passes (`volume.rs`) and the time to quality of the CLI's
//! defaults (`quality.rs`), then here the "versus Mesquite" table and the targets.

use std::fmt::Write as _;

use crate::planar::{SizeReport, RULES_PRIORITY};
use crate::quality::{time_to_quality, QualityReport, PAVE1_MESQUITE_S};
use crate::volume::{measure_volume, volume_section, VolumeReport};
use crate::wasm::wasm_rows;
use crate::common::{fmt_ms, fmt_ns, read_json, target_mark};

/// Issue 33's targets for the browser: the wasm / native ratio of every pass, the module's
/// gzipped bytes (its size on the issue's day) and one default Step on the 1M sample.
pub(crate) const WASM_NATIVE_TARGET: f64 = 1.3;
const MODULE_GZIP_TARGET: f64 = 649_479.0;
const STEP_1M_TARGET_S: f64 = 5.0;

fn fmt_ratio(x: f64) -> String {
    if x >= 10.0 {
        format!("{x:.0}")
    } else if x >= 1.0 {
        format!("{x:.1}")
    } else {
        format!("{x:.2}")
    }
}

/// The planar mesh of the comparisons: rand2d of 100k nodes, Hilbert order (the wasm
/// bench's size).
pub(crate) const PLANAR_NODES: usize = 100_000;

/// The pairs of issue 33's table: (pair, smoothlab's planar pass, its 3D pass, the issue's
/// ratio in 2D, in 3D), ratio = Mesquite's time / smoothlab's, measured before this work.
const MESQUITE_PAIRS: [(&str, &str, Option<&str>, &str, &str); 8] = [
    ("Laplace (same algorithm, equal output)", "laplace", Some("laplace"), "39–62×", "130–174×"),
    ("smart Laplace", "smart", Some("smart"), "5.2–12.4×", "3.2–3.7×"),
    ("`new` 3 it vs FeasibleNewton 3 it (mean ratio)", "opt+new", Some("opt+new"), "4.1–4.8×", "1.0–1.1×"),
    ("`rules` (the default) vs FeasibleNewton", RULES_PRIORITY, Some("rules+new, priority order"), "1.8–2.4×", "0.3–0.6×"),
    ("`condition` 3 it vs Mesquite's CG on Σ(1/α)²", "opt+condition", Some("opt+condition"), "1.2–1.6×", "2.1–2.2×"),
    ("`old` vs NonSmoothDescent, both capped at 20 iterations", "opt+old, 20 it", Some("opt+old, 20 it"), "0.6–0.9×", "0.5–0.9×"),
    ("`sine` 20 it vs NonSmoothDescent on max-min sine", "opt+sine, 20 it", None, "0.7–1.1×", "—"),
    ("`untangle` vs UntangleWrapper's body", "opt+untangle", Some("opt+untangle"), "0.7–1.7×", "8–11×"),
];

/// The planar passes the issue-33 sections read (the wasm bench's and the pairs' and the
/// targets'), for a run that measures those alone (`--issue33`).
pub(crate) const ISSUE33_PLANAR: [&str; 11] = [
    "laplace",
    "smart",
    "opt+new",
    "opt+old",
    "opt+old, 20 it",
    "opt+sine",
    "opt+sine, 20 it",
    "opt+condition",
    "opt+untangle",
    "rules+new",
    RULES_PRIORITY,
];

/// Issue 33's speed-ups measured before and after in one run by `scripts/before_after.py`
/// (`make performance`): the CLI of the issue's day (a base commit) and this tree's, one pass
/// of each target on the same file, alternating, the median of a few runs of the pass's own
/// time; rows by target, `"{2D|3D|hexahedra} {pass}"`.
struct BeforeAfter {
    base: String,
    reps: u64,
    /// (target, mesh, options, before ms, after ms, runs of each binary)
    rows: Vec<(String, String, String, f64, f64, u64)>,
}

impl BeforeAfter {
    fn read(path: Option<&str>) -> Self {
        let v = read_json(path).unwrap_or(serde_json::Value::Null);
        let text = |r: &serde_json::Value, k: &str| r[k].as_str().unwrap_or("?").to_string();
        let rows = v["rows"]
            .as_array()
            .into_iter()
            .flatten()
            .filter_map(|r| {
                let runs = r["runs"].as_u64().unwrap_or(v["reps"].as_u64().unwrap_or(0));
                Some((text(r, "target"), text(r, "mesh"), text(r, "options"), r["before_ms"].as_f64()?, r["after_ms"].as_f64()?, runs))
            })
            .collect();
        BeforeAfter { base: v["base"].as_str().unwrap_or("?").to_string(), reps: v["reps"].as_u64().unwrap_or(0), rows }
    }
    /// Before / after of `pass` in `dim` (2D, 3D, hexahedra), when measured.
    fn speedup(&self, dim: &str, pass: &str) -> Option<f64> {
        let name = format!("{dim} {pass}");
        self.rows.iter().find(|r| r.0 == name).map(|r| r.3 / r.4)
    }
    /// The table of every measured target.
    fn table(&self) -> String {
        let mut w = String::new();
        if self.rows.is_empty() {
            let _ = writeln!(w, "Before and after in one run: not measured (no `--before-after` file: `scripts/before_after.py` writes it).\n");
            return w;
        }
        let _ = writeln!(
            w,
            "Before and after in one run (`scripts/before_after.py`): the `smoothlab` CLI of the issue's day (commit {}) and this tree's, \
             `smoothlab smooth MESH --passes 1 --json OPTIONS` on the same file, the two binaries alternating. Each figure is the median \
             of the runs (at least {}, at most 25) of the pass's own time (`elapsed_ms`: the node loop alone).\n",
            self.base, self.reps
        );
        let _ = writeln!(w, "| target | mesh | options | runs | before | after | speed-up |");
        let _ = writeln!(w, "|---|---|---|---:|---:|---:|---:|");
        let mut last = "";
        for (t, mesh, options, b, a, runs) in &self.rows {
            // a mesh named once for the rows that share it
            let shown = if mesh == last { "as above" } else { mesh.as_str() };
            last = mesh;
            let _ = writeln!(w, "| {t} | {shown} | `{options}` | {runs} | {} | {} | {:.2}× |", fmt_ms(*b), fmt_ms(*a), b / a);
        }
        w.push('\n');
        w
    }
}

/// smoothlab's figure of `pass` in this run: 2D on rand2d 100k Hilbert, 3D on rand3D.
fn this_run(planar: Option<&SizeReport>, volume: &VolumeReport, dim: &str, pass: &str) -> Option<f64> {
    if dim == "3D" {
        volume.get(pass, 0).map(|f| f.ns_per_node)
    } else {
        planar?.rows.iter().find(|r| r.0 == pass).map(|r| r.2)
    }
}

fn versus_mesquite(planar: Option<&SizeReport>, volume: &VolumeReport, before_after: &BeforeAfter) -> String {
    let mut w = String::new();
    let _ = writeln!(w, "## Versus Mesquite (issue 33)\n");
    let _ = writeln!(
        w,
        "**ratio = Mesquite's time per free node and pass / smoothlab's** (> 1: smoothlab faster), on the same mesh and machine. \
         Mesquite is not built by this project, so its half is not re-measured: the ratios are issue 33's, measured before this work. \
         smoothlab's half is this run's: 2D on rand2d of {PLANAR_NODES} nodes in Hilbert order, 3D on rand3D (the sections above). \
         *Estimate now* is the issue's ratio times smoothlab's speed-up since (the next section): an estimate, not a measurement.\n"
    );
    let _ = writeln!(w, "| pair | smoothlab 2D | issue's ratio 2D | estimate now 2D | smoothlab 3D | issue's ratio 3D | estimate now 3D |");
    let _ = writeln!(w, "|---|---:|---:|---:|---:|---:|---:|");
    let scaled = |ratio: &str, dim: &str, pass: &str| -> String {
        let Some(s) = before_after.speedup(dim, pass) else { return "—".into() };
        let parts: Vec<f64> = ratio.trim_end_matches('×').split('–').filter_map(|x| x.parse().ok()).collect();
        match parts.as_slice() {
            [a, b] => format!("{}–{}×", fmt_ratio(a * s), fmt_ratio(b * s)),
            [a] => format!("{}×", fmt_ratio(a * s)),
            _ => "—".into(),
        }
    };
    let ns = |v: Option<f64>| v.map_or("not measured".to_string(), fmt_ns);
    for (pair, p2, p3, r2, r3) in MESQUITE_PAIRS {
        let n2 = this_run(planar, volume, "2D", p2);
        let n3 = p3.and_then(|p| this_run(planar, volume, "3D", p));
        let _ = writeln!(
            w,
            "| {pair} | {} | {r2} | {} | {} | {r3} | {} |",
            ns(n2),
            scaled(r2, "2D", p2),
            if p3.is_some() { ns(n3) } else { "—".into() },
            p3.map_or("—".into(), |p| scaled(r3, "3D", p))
        );
    }
    let _ = writeln!(
        w,
        "\nFigures in ns unless marked µs; `rules` runs in priority order, as the CLI runs it. \
         Peak memory at 1M planar nodes (issue 33, before this work): smoothlab 199 MB, Mesquite 311 MB.\n"
    );
    w
}

/// Issue 33's targets in one table.
fn issue33_targets(
    reports: &[SizeReport],
    volume: &VolumeReport,
    quality: &QualityReport,
    before_after: &BeforeAfter,
    wasm: Option<&str>,
    page: Option<&str>,
    load: &str,
) -> String {
    let mut w = String::new();
    let _ = writeln!(w, "## Against the targets of issue 33 (performance versus Mesquite)\n");
    w += &before_after.table();
    let _ = writeln!(
        w,
        "Each row below: the figure, then ✓ where it meets the target and ✗ where it does not, with how far. \
         The load average was {load} when the 3D passes began.\n"
    );
    let _ = writeln!(w, "| target | before | after | figure | met |");
    let _ = writeln!(w, "|---|---:|---:|---:|---|");
    let speedups: [(&str, &str, &str, f64); 7] = [
        ("3D: `opt`+`new` ≥ 3× faster", "3D", "opt+new", 3.0),
        ("3D: `rules`+`new` (priority order) ≥ 3× faster", "3D", "rules+new, priority order", 3.0),
        ("3D: `old` with 20 iterations ≥ 2× faster", "3D", "opt+old, 20 it", 2.0),
        ("2D: `condition` ≥ 3× faster", "2D", "opt+condition", 3.0),
        ("2D: `old` with 20 iterations ≥ 2× faster per node-pass", "2D", "opt+old, 20 it", 2.0),
        ("2D: `sine` with 20 iterations ≥ 2× faster per node-pass", "2D", "opt+sine, 20 it", 2.0),
        ("2D: `untangle` ≥ 2× faster", "2D", "opt+untangle", 2.0),
    ];
    for (what, dim, pass, target) in speedups {
        let name = format!("{dim} {pass}");
        let cells = match before_after.rows.iter().find(|r| r.0 == name) {
            Some((_, _, _, b, a, _)) => {
                let s = b / a;
                let met = if s >= target { "✓".to_string() } else { format!("✗ ({:.2}× of the {target}×)", s) };
                format!("{} | {} | {s:.2}× | {met}", fmt_ms(*b), fmt_ms(*a))
            }
            None => "not measured | not measured | — | not measured (no `--before-after` file)".to_string(),
        };
        let _ = writeln!(w, "| {what} | {cells} |");
    }
    // hexahedra per corner, the worst of the passes the target names
    let worst = ["opt+new", "rules+new, priority order", "opt+old, 20 it"]
        .iter()
        .filter_map(|&p| Some((p, volume.get(p, 1)?.ns_per_corner / volume.get(p, 0)?.ns_per_corner)))
        .max_by(|a, b| a.1.total_cmp(&b.1));
    if let Some((p, r)) = worst {
        let _ = writeln!(
            w,
            "| 3D: hexahedra not slower per corner than tetrahedra (`opt`+`new`, `rules`+`new`, `old` 20 it; the worst) | — | {r:.2} ({p}) | hex / tet per corner ≤ 1 | {} |",
            target_mark(r, 1.0)
        );
    }
    let (ok, all, most) = quality.reached;
    let _ = writeln!(
        w,
        "| time to quality: the tangled plates and Mesquite's tangled files to 0 inverted with the defaults (reported with the passes) | — | {ok} of the {all} tangled at start, at most {most} pass(es) | the section above | {} |",
        if all == 0 { "not measured" } else if ok == all { "✓" } else { "✗" }
    );
    let _ = writeln!(
        w,
        "| time to quality on `pave1`: below Mesquite's ShapeImprover's {PAVE1_MESQUITE_S} s by 10× | {PAVE1_MESQUITE_S} s (Mesquite) | {} | ≤ {:.2} s | {} |",
        quality.pave1_ms.map_or("not measured".into(), fmt_ms),
        PAVE1_MESQUITE_S / 10.0,
        quality.pave1_ms.map_or("not measured".into(), |ms| target_mark(ms / 1e3, PAVE1_MESQUITE_S / 10.0))
    );
    // wasm: the worst ratio of the browser bench's passes
    match read_json(wasm) {
        Some(v) => {
            let ratios: Vec<(String, f64)> = wasm_rows(&v, reports)
                .into_iter()
                .filter_map(|(n, h, ns, nat)| Some((format!("{n}, {}", if h { "Hilbert" } else { "file order" }), ns / nat?)))
                .collect();
            let worst = ratios.iter().max_by(|a, b| a.1.total_cmp(&b.1));
            let _ = writeln!(
                w,
                "| wasm in Chromium ≤ {WASM_NATIVE_TARGET}× native for every strategy | 1.36–2.40× | {} | ≤ {WASM_NATIVE_TARGET} | {} |",
                worst.map_or("not measured".into(), |(n, r)| format!("{r:.2}× at most ({n})")),
                worst.map_or("not measured".into(), |(_, r)| target_mark(*r, WASM_NATIVE_TARGET))
            );
        }
        None => {
            let _ = writeln!(w, "| wasm in Chromium ≤ {WASM_NATIVE_TARGET}× native for every strategy | 1.36–2.40× | not measured (no `--wasm` file) | ≤ {WASM_NATIVE_TARGET} | not measured |");
        }
    }
    let page = read_json(page);
    let gz = page.as_ref().and_then(|v| v["wasm"]["gzip_bytes"].as_f64());
    let _ = writeln!(
        w,
        "| the module no larger gzipped than issue 33's day | {MODULE_GZIP_TARGET} bytes (`docs/performance.md` of 2026-11-24) | {} | ≤ {MODULE_GZIP_TARGET} bytes | {} |",
        gz.map_or("not measured (no `--page` file)".into(), |b| format!("{b:.0} bytes")),
        gz.map_or("not measured".into(), |b| target_mark(b, MODULE_GZIP_TARGET))
    );
    let step = page.as_ref().and_then(|v| v["million"]["default_step"]["wall_ms"].as_f64());
    let _ = writeln!(
        w,
        "| the page: one default Step on the 1M sample ≤ {STEP_1M_TARGET_S} s | 10.0 s (`docs/performance.md` of 2026-11-24) | {} | ≤ {STEP_1M_TARGET_S} s | {} |",
        step.map_or("not measured (no `--page` file)".into(), fmt_ms),
        step.map_or("not measured".into(), |ms| target_mark(ms / 1e3, STEP_1M_TARGET_S))
    );
    w.push('\n');
    w
}

/// Issue 33's sections: the 3D passes, the time to quality, versus Mesquite and the targets
/// (the planar figures from `reports`, the 100k one).
pub(crate) fn issue33_sections(reports: &[SizeReport], quick: bool, wasm: Option<&str>, page: Option<&str>, before_after: Option<&str>) -> String {
    let before_after = BeforeAfter::read(before_after);
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    let load = load.split_whitespace().take(3).collect::<Vec<_>>().join(" ");
    eprintln!("perf: tetrahedra and hexahedra …");
    let volume = measure_volume(quick);
    eprintln!("perf: time to quality …");
    let quality = time_to_quality(quick);
    let planar = reports.iter().find(|r| r.nodes == PLANAR_NODES);
    volume_section(&volume)
        + &quality.text
        + &versus_mesquite(planar, &volume, &before_after)
        + &issue33_targets(reports, &volume, &quality, &before_after, wasm, page, &load)
}
