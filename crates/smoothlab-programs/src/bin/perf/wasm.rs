//! The WebAssembly figures: the browser bench's passes against the same passes natively.

use std::fmt::Write as _;

use crate::issue33::WASM_NATIVE_TARGET;
use crate::planar::{measure_rows, SizeReport};
use crate::common::{fmt_ns, read_json};

/// What was tried for the wasm / native ratio (target ≤ 1.3), after its table.
const WASM_TRIED: &str = "Tried: the module is built with 128-bit SIMD (`+simd128`, which tiny-skia's pipelines use, and LLVM's vectoriser where it finds pairs in the core), from the same code as the native build, so the speed-ups of the native kernels (issue 15's Newton trial, the δ memo, the inline triangles, the old objective's corners) carry over (opt+new in Chromium, Hilbert order: 3872 ns a visit in the run before them, the table above now) while the ratio stays about where it was (1.40 for that pass then); the crate built for size is slower still (the page section). Tried for the issue's simd128 kernels, and not kept: the `new` objective's term of two linear triangles at once, each number a pair of lanes with the one-triangle kernel's operations in its order (the same bits: a unit test compared value, gradient and Hessian over 40000 random pairs, δ = 0 and δ > 0, at scales 1e±150); LLVM made its arithmetic `f64x2` instructions (186 `f64x2.mul`, 10 `f64x2.div` in the objective's Hessian function), but in node opt+new was no faster (Hilbert order, three alternating runs: 3107, 3019, 2992 ns a visit before, 3001, 3022, 2998 after; file order and rules+new within the noise) and the module 4.3 KB larger gzipped, with 46 `f64x2.extract_lane` and 18 `replace_lane` to pack and unpack the lanes beside the paired arithmetic. The native half of each ratio is now measured straight after the page (`--native-peers`): with the native figures of the planar table, measured minutes later on this shared machine, the same binaries' ratios had read 1.07–2.80 in one run; measured together, in two runs before this one, the optimizers (smart, opt+new, opt+old, rules+new) ran 1.44–1.87× their native time (once 3.71×, smart in file order) and laplace 1.86–3.05×. V8's baseline compiler is not the cause: with `--no-liftoff` (every function compiled by TurboFan from the start) the bench page was no faster (one run). Where the time goes: the passes profiled in node (`node --cpu-prof`, the module built with its names kept) and natively (`perf record`), the same passes on the same mesh: each function takes about the same share of the pass in both, so the wasm build is slower across the whole of the code rather than at a hot spot; the exception was the inverted test of an element (7.8% of opt+new in wasm against 3.4% natively: its range test's maxima), made cheaper since (the module section above). Tried and not kept: binaryen's `-O4` (3.5 KB larger gzipped and no faster: two alternating runs of four passes in node); reading ahead in node order too, which the drivers do only in a scattered order (natively rules+new in file order 12–20% faster, but laplace 4× slower and every pass in Hilbert order slower; in wasm 0–8% faster in file order and some 6% slower in Hilbert order), and later for every strategy but the two Laplacians alone, whose visits cost more than their reads (natively, the CLI on a rand2D of 20000 points in file order and renumbered along a Hilbert curve, medians of 9 to 15 alternating runs: opt+old with 20 iterations 1.4% faster in file order and level in Hilbert order, opt+new 2% and 4% slower, rules+new in node order 2.5% slower). Where the time goes in a scattered numbering (`perf` on node's code with its jitted functions' listings): in a Laplacian's visit in file order, most of the samples sit on the loads of the neighbours' positions, as natively, but V8's code for a visit is longer (the visit's calls, a stack check in each loop), so fewer visits' loads are in flight at once and the misses cost more. Tried and not kept for it: the smart Laplacian's test reading a star's other corners first and measuring them after, so that the reads go out together (in node, the two modules alternating in one process, 21 sweeps each: smart in file order 730–832 against 772–990 ns a visit, but in Hilbert order, the page's samples' numbering, 2–10% slower, and rules+new in either order within the noise; natively within the noise too; the same meshes).";

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
            "The native figures were measured straight after the page (`perf --native-peers`: the same passes on the same mesh and numbering, \
             the median of a few passes each), so each ratio compares two figures of the same minute on this shared machine."
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
        let _ = writeln!(w, "\nNot met: the strategies run {lo:.2}–{hi:.2}× their native time in Chromium (the table). {WASM_TRIED}");
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
