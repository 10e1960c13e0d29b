//! The WebAssembly figures: the browser bench's passes against the same passes natively.

use std::fmt::Write as _;

use crate::issue33::WASM_NATIVE_TARGET;
use crate::planar::{measure_rows, SizeReport};
use crate::common::{fmt_ns, read_json};

/// The native ns/visit of pass `name` on the mesh of `nodes` nodes, file order.
fn native(reports: &[SizeReport], nodes: usize, name: &str) -> Option<(f64, f64)> {
    let r = reports.iter().find(|r| r.nodes == nodes)?;
    r.rows.iter().find(|row| row.0 == name).map(|row| (row.1, row.2))
}

/// The wasm table: the bench page's ns/visit against the native figure of the same pass
/// on the same mesh and numbering.
pub(crate) fn wasm_table(w: &mut String, v: &serde_json::Value, reports: &[SizeReport]) {
    let nodes = v["nodes"].as_u64().unwrap_or(0) as usize;
    let _ = writeln!(
        w,
        "The bench page (`www/bench.html`) generates the same rand2d mesh ({} nodes, seed {}) in wasm and times one pass with `performance.now()`, median of {} passes on fresh copies. {} {}\n",
        nodes,
        v["seed"],
        v["reps"],
        v["browser"].as_str().map(|b| format!("Browser: {b}.")).unwrap_or_default(),
        if v["passes"].as_array().into_iter().flatten().any(|r| r["native_ns_per_visit"].is_f64()) {
            "The native figures were measured straight after the page, on the same mesh and numbering (`perf --native-peers`)."
        } else {
            "The native figures are this run's planar table's, measured some minutes after the page."
        }
    );
    let _ = writeln!(w, "| pass | order | wasm ns/visit | native ns/visit | wasm / native (target ≤ 1.3) |");
    let _ = writeln!(w, "|---|---|---:|---:|---:|");
    let mut ratios = Vec::new();
    for (name, hilbert, ns, nat) in wasm_rows(v, reports) {
        let (nat_s, ratio) = match nat {
            Some(n) => {
                ratios.push(ns / n);
                (fmt_ns(n), format!("{:.2}", ns / n))
            }
            None => ("not measured".into(), "—".into()),
        };
        let _ = writeln!(
            w,
            "| {name} | {} | {} | {nat_s} | {ratio} |",
            if hilbert { "Hilbert" } else { "file" },
            fmt_ns(ns)
        );
    }
    let (lo, hi) = ratios.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &r| (lo.min(r), hi.max(r)));
    if hi > WASM_NATIVE_TARGET {
        let _ = writeln!(w, "\nNot met: the strategies run {lo:.2}–{hi:.2}× their native time in Chromium (the table).");
    }
    let _ = writeln!(w);
}

/// Measures natively the passes of the bench page's JSON at `path` (`tests/browser/bench.mjs`'s
/// output) on the same mesh and numbering, and writes each pass's figure into that JSON
/// (`native_ns_per_visit`, read by [`wasm_rows`]). `make performance` runs it straight
/// after the bench page, so a wasm / native ratio compares two figures of the same minute
/// on a shared machine rather than of minutes apart (the same binaries' ratios moved by
/// some 0.5 between runs when the native half came from the planar table).
pub(crate) fn native_peers(path: &str) {
    let mut v = read_json(Some(path)).unwrap_or_else(|| panic!("cannot read the bench page's JSON {path}"));
    let nodes = v["nodes"].as_u64().unwrap_or(0) as usize;
    let mut names: Vec<String> = Vec::new();
    for row in v["passes"].as_array().into_iter().flatten() {
        let name = row["name"].as_str().unwrap_or("?").to_string();
        if !names.contains(&name) {
            names.push(name);
        }
    }
    let refs: Vec<&str> = names.iter().map(String::as_str).collect();
    eprintln!("perf: the bench page's passes natively, {nodes} nodes …");
    let report = measure_rows(nodes, &refs, false);
    assert_eq!(report.nodes, nodes, "the native mesh is the bench page's");
    for row in v["passes"].as_array_mut().into_iter().flatten() {
        let name = row["name"].as_str().unwrap_or("?").to_string();
        let hilbert = row["hilbert"].as_bool().unwrap_or(false);
        if let Some((a, b)) = native(std::slice::from_ref(&report), nodes, &name) {
            row["native_ns_per_visit"] = serde_json::json!(if hilbert { b } else { a });
        }
    }
    let text = serde_json::to_string_pretty(&v).expect("json");
    std::fs::write(path, text).unwrap_or_else(|e| panic!("cannot write {path}: {e}"));
}

/// The bench page's rows: (pass, Hilbert order, wasm ns/visit, native ns/visit): the
/// native figure measured beside the page ([`native_peers`]) when there is one, else this
/// run's planar table's.
pub(crate) fn wasm_rows(v: &serde_json::Value, reports: &[SizeReport]) -> Vec<(String, bool, f64, Option<f64>)> {
    let nodes = v["nodes"].as_u64().unwrap_or(0) as usize;
    v["passes"]
        .as_array()
        .into_iter()
        .flatten()
        .map(|row| {
            let name = row["name"].as_str().unwrap_or("?").to_string();
            let hilbert = row["hilbert"].as_bool().unwrap_or(false);
            let beside = row["native_ns_per_visit"].as_f64();
            let nat = beside.or_else(|| native(reports, nodes, &name).map(|(a, b)| if hilbert { b } else { a }));
            (name, hilbert, row["ns_per_visit"].as_f64().unwrap_or(f64::NAN), nat)
        })
        .collect()
}
