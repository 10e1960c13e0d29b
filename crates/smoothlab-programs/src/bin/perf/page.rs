//! The "In the page" section, from the page bench's JSON (`--page`).

use std::fmt::Write as _;

use crate::common::median;

/// The "In the page" section from the JSON of `node tests/browser/page_bench.mjs`
/// (`--page FILE`; `--page-only` prints this section alone, without a native run): the
/// playground page itself at 100k and 1M nodes.
pub(crate) fn page_section(path: Option<&str>) -> String {
    let mut w = String::new();
    let _ = writeln!(w, "## In the page
");
    let v: serde_json::Value = match path.map(std::fs::read_to_string) {
        None => {
            let _ = writeln!(w, "Not measured in this run (no `--page` file).\n");
            return w;
        }
        Some(Err(e)) => {
            let _ = writeln!(w, "The page bench's output could not be read ({e}).\n");
            return w;
        }
        Some(Ok(text)) => match serde_json::from_str(&text) {
            Ok(v) => v,
            Err(e) => {
                let _ = writeln!(w, "The page bench's output could not be read ({e}).\n");
                return w;
            }
        },
    };
    let f = |x: &serde_json::Value| x.as_f64().unwrap_or(f64::NAN);
    let ms = |x: &serde_json::Value| format!("{:.0}", f(x));
    let pair = |x: &serde_json::Value| format!("{} / {}", ms(&x[0]), ms(&x[1]));
    let h = &v["hundred_k"];
    let steps = h["steps"].as_array().cloned().unwrap_or_default();
    let canvas = steps.first().map(|s| &s["median"]["canvas"]).cloned().unwrap_or_default();
    let _ = writeln!(
        w,
        "The playground page itself (`www/index.html`), driven as a user drives it by `node tests/browser/page_bench.mjs` \
         ({}, viewport {}×{}, mesh canvases {}×{} device pixels). The figures are the page's own measurements \
         (`window.smoothlab.metrics`). A pass runs in the worker in slices of {} ms, so the progress bar moves and Stop is \
         heard during a pass.\n",
        v["browser"].as_str().unwrap_or("Chromium"),
        v["viewport"][0],
        v["viewport"][1],
        canvas[0],
        canvas[1],
        v["slice_ms"]
    );
    let _ = writeln!(
        w,
        "### One pass + redraw, {} nodes ({} elements)\n\nStep on the mesh as loaded: from the click to both meshes and both statistics tables redrawn (target < 100 ms), \
         median of {} clicks; then where the time went, old / new side, ms. The charts (per-pass curves, two angle histograms) are drawn after.\n",
        h["nodes"],
        h["elements"],
        steps.first().map(|s| s["reps"].clone()).unwrap_or_default()
    );
    let _ = writeln!(w, "| settings | click → redrawn | < 100 ms | all but smoothing | smoothing | statistics | rendering | copy out of wasm | messages | putImageData | charts after |");
    let _ = writeln!(w, "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    for s in &steps {
        let m = &s["median"];
        let wall = f(&m["wall_ms"]);
        let _ = writeln!(
            w,
            "| {} | {:.0} ms | {} | {:.0} ms | {} | {} | {} | {:.1} | {:.1} | {:.1} / {:.1} | {} |",
            s["name"].as_str().unwrap_or("?"),
            wall,
            if wall < 100.0 { "met" } else { "not met" },
            // per click, then the median (medians of the parts need not add up); in two
            // workers the two sides' sweeps overlap, and the longer one is the smoothing's time
            median(
                s["runs"]
                    .as_array()
                    .map(|runs| runs
                        .iter()
                        .map(|r| {
                            let (a, b) = (f(&r["sweep_ms"][0]), f(&r["sweep_ms"][1]));
                            f(&r["wall_ms"]) - if f(&r["workers"]) == 2.0 { a.max(b) } else { a + b }
                        })
                        .collect())
                    .unwrap_or_else(|| vec![f64::NAN])
            ),
            pair(&m["sweep_ms"]),
            pair(&m["stats_ms"]),
            pair(&m["render_ms"]),
            f(&m["copy_ms"]),
            f(&m["messaging_ms"]) + f(&m["transfer_ms"]),
            f(&m["paint_ms"][0]),
            f(&m["paint_ms"][1]),
            ms(&m["charts_ms"])
        );
    }
    let _ = writeln!(
        w,
        "\nBoth sides use the default settings (Chen's rules in priority order), old objective on one side and new on the other. \
         *Smoothing* is each side's node loop; *all but smoothing* is the rest of the click: statistics, drawing, copies, \
         messages, painting and the tables."
    );
    let ready = &h["second_worker_ready_ms"];
    let workers = steps.first().map(|s| f(&s["median"]["workers"])).unwrap_or(f64::NAN);
    let _ = writeln!(
        w,
        "\nA planar mesh of 20k to 500k nodes is smoothed in two workers, one side each (`www/app/workers.js`; \
         the same meshes as one worker, bit for bit{}). The default Step above ran in {} worker(s).",
        if ready.is_null() { String::new() } else { format!("; here the second was ready {} ms after the load", ms(ready)) },
        if workers.is_nan() { "?".to_string() } else { format!("{workers:.0}") }
    );
    let st = &v["startup"]["median"];
    if !st.is_null() {
        let first = f(&st["first_mesh_ms"]);
        let _ = writeln!(
            w,
            "\nThe first visit, from the navigation to the first mesh drawn (target ≤ 500 ms): {} ms, {}, median of {} fresh pages \
             ({}: the engine (worker and wasm module) answered after {} ms, the menus were filled by {} ms, the first frame of both \
             meshes took {} ms). The module: {} bytes, {} bytes gzipped (zlib level 9; target ≤ 400 KB).",
            ms(&st["first_mesh_ms"]),
            if first <= 500.0 { "met" } else { "not met" },
            v["startup"]["runs"],
            st["sample"].as_str().unwrap_or("the default sample"),
            ms(&st["engine_ready_ms"]),
            ms(&st["menus_ms"]),
            ms(&st["first_frame_ms"]),
            v["wasm"]["bytes"],
            v["wasm"]["gzip_bytes"]
        );
    }
    let targets = |got: f64, target: f64, unit: &str| {
        if got.is_nan() {
            "not measured".to_string()
        } else if got <= target {
            format!("{got:.0} {unit}, met")
        } else {
            format!("{got:.0} {unit}, not met ({:.1}× the target)", got / target)
        }
    };
    let million_step = f(&v["million"]["default_step"]["wall_ms"]) / 1000.0;
    let _ = writeln!(
        w,
        "\nIssue 15's targets in this run{}: one default Step at 100k ≤ 1000 ms: {}; at 1M ≤ 10 s: {}; the first mesh ≤ 500 ms: {}; \
         the module ≤ 400 KB gzipped: {}.",
        v["load_average"].as_array().map(|l| format!(" (load average {} at the start)", l.first().map(|x| x.to_string()).unwrap_or_default())).unwrap_or_default(),
        targets(f(&steps.first().map(|s| s["median"]["wall_ms"].clone()).unwrap_or_default()), 1000.0, "ms"),
        targets(million_step, 10.0, "s"),
        targets(f(&st["first_mesh_ms"]), 500.0, "ms"),
        targets(f(&v["wasm"]["gzip_bytes"]) / 1000.0, 400.0, "KB")
    );
    let load = &h["load"];
    let _ = writeln!(
        w,
        "\nLoading the {}-node sample (generated in wasm, statistics, first drawing): {} ms; the main thread's longest gap between animation frames meanwhile {} ms.\n",
        h["nodes"],
        ms(&load["ms"]),
        ms(&load["longest_frame_gap_ms"])
    );
    let m = &v["million"];
    if m.is_null() {
        let _ = writeln!(w, "The 1M-node sample was not measured in this run.\n");
        return w;
    }
    let _ = writeln!(w, "### 1M nodes: load, 3 passes, Stop\n");
    let load = &m["load"];
    let mib = |x: &serde_json::Value| format!("{:.0} MiB", f(x) / 1048576.0);
    let _ = writeln!(
        w,
        "- The sample ({} nodes, {} elements, generated in wasm) loads and is drawn in {:.1} s; the main thread's longest gap between animation frames meanwhile {} ms, a 50 ms interval at most {} ms late.",
        m["nodes"],
        m["elements"],
        f(&load["ms"]) / 1000.0,
        ms(&load["longest_frame_gap_ms"]),
        ms(&load["worst_interval_lateness_ms"])
    );
    let run = &m["run"];
    let passes = run["passes"].as_array().cloned().unwrap_or_default();
    let _ = writeln!(
        w,
        "- Run, 3 passes of {}: {:.1} s in all (charts included). The main thread's longest gap between frames during the run {} ms, a 50 ms interval at most {} ms late.",
        m["strategy"].as_str().unwrap_or("?"),
        f(&run["total_ms"]) / 1000.0,
        ms(&run["longest_frame_gap_ms"]),
        ms(&run["worst_interval_lateness_ms"])
    );
    let _ = writeln!(w, "\n| pass | pass + redraw | slices | progress updates during the pass | smoothing old / new | statistics old / new | rendering old / new |");
    let _ = writeln!(w, "|---:|---:|---:|---:|---:|---:|---:|");
    for (i, p) in passes.iter().enumerate() {
        let _ = writeln!(
            w,
            "| {} | {:.1} s | {} | {} | {} ms | {} ms | {} ms |",
            p["pass"],
            f(&p["wall_ms"]) / 1000.0,
            p["slices"],
            run["progress_updates_within_pass"][i],
            pair(&p["sweep_ms"]),
            pair(&p["stats_ms"]),
            pair(&p["render_ms"])
        );
    }
    let stop = &m["stop"];
    let _ = writeln!(
        w,
        "\n- Stop during a pass: the page is idle again after {} ms (the pass is undone: both meshes as before it).",
        ms(&stop["to_idle_ms"])
    );
    if let Some(ms_) = m["stop_while_ordering"]["to_status_ms"].as_f64() {
        let _ = writeln!(
            w,
            "- Stop while the default settings order the nodes worst first (`Smoother::plan_some`, in slices): {ms_:.0} ms."
        );
    }
    let d = &m["default_step"];
    if !d.is_null() {
        let _ = writeln!(
            w,
            "- One Step with the default settings, on the mesh as the run above left it: {:.1} s to the redrawn meshes (smoothing old {:.1} s, new {:.1} s; {} node visits a side in \
             priority order), in {} slices; the main thread's longest gap between frames meanwhile {} ms.",
            f(&d["wall_ms"]) / 1000.0,
            f(&d["sweep_ms"][0]) / 1000.0,
            f(&d["sweep_ms"][1]) / 1000.0,
            d["visits"][0],
            d["slices"],
            ms(&d["longest_frame_gap_ms"])
        );
    }
    let _ = writeln!(
        w,
        "- wasm memory (`memory.buffer.byteLength`, which never shrinks): {} at the end, {} at most.\n",
        mib(&m["memory"]["bytes"]),
        mib(&m["memory"]["peak_bytes"])
    );
    w
}
