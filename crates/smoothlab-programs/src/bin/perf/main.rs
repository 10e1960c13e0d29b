//! Performance figures of smoothlab, written as `docs/performance.md` (run by
//! `make performance`; see that file for what is measured and how).
//!
//! ```text
//! cargo run --release -p smoothlab-programs --features parallel --bin perf -- \
//!     [--sizes 10000,100000,1000000] [--wasm wasm.json] [--page page.json]
//!     [--page-memory page-memory.json] [--before-after before_after.json]
//!     [--out docs/performance.md] [--json native.json]
//! cargo run --release -p smoothlab-programs --bin perf -- --memory-only [--page-memory page-memory.json]
//! cargo run --release -p smoothlab-programs --features parallel --bin perf -- --issue33 [--quick] [--wasm wasm.json] [--page page.json]
//!     [--before-after before_after.json]
//! ```
//!
//! Every figure is the median of a few timed passes, each over a fresh copy of the same
//! generated mesh (the copy is not timed), in nanoseconds per node visit. `--wasm` reads the
//! browser bench's JSON (`node tests/browser/bench.mjs`) and adds the wasm/native table.
//! The memory section (alone with `--memory-only`, printed) measures each command in a
//! child process of this program (`--memory-child`), whose peak resident memory it reports.
//! Issue 33's sections (alone, printed, with `--issue33`: about 2 minutes; `--quick` fewer
//! repetitions): the 3D passes on rand3D and on hexahedra, the time to quality of the
//! release binary `smoothlab` (built beside this program: `make performance` builds it),
//! versus Mesquite, and the issue's targets, whose speed-ups are read from
//! `scripts/before_after.py`'s JSON (`--before-after`: the CLI of the issue's day and this
//! tree's timed in one run).
//!
//! The sections, one module each: `planar.rs` times the planar passes and `report.rs`
//! writes their sections; `wasm.rs`, `memory.rs` and `page.rs` write theirs; issue 33's
//! are `volume.rs`, `quality.rs` and `issue33.rs`. `common.rs` holds what several read.
//! The document's prose is wrapped at 100 characters (`markdown.rs`).

mod common;
mod issue33;
#[path = "../../markdown.rs"]
mod markdown;
mod memory;
mod page;
mod planar;
mod quality;
mod report;
mod volume;
mod wasm;

use common::fmt_ns;
use issue33::{issue33_sections, ISSUE33_PLANAR, PLANAR_NODES};
use memory::{memory_child, memory_section};
use page::page_section;
use planar::{measure, measure_rows, newton_quality};
use report::render;
use wasm::native_peers;

fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .map(|l| l.split(':').nth(1).unwrap_or("").trim().to_string())
        })
        .unwrap_or_else(|| "unknown".into());
    let cores = std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1);
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    let load: Vec<&str> = load.split_whitespace().take(3).collect();
    format!("{cores} cores ({cpu}); load average {} at the start", load.join(" "))
}

fn main() {
    let mut sizes = vec![10_000, 100_000, 1_000_000];
    let mut wasm: Option<String> = None;
    let mut page: Option<String> = None;
    let mut page_only = false;
    let mut memory_only = false;
    let mut page_memory: Option<String> = None;
    let mut out: Option<String> = None;
    let mut json_out: Option<String> = None;
    let mut quick = false;
    let mut issue33_only = false;
    let mut before_after: Option<String> = None;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--sizes" => sizes = args.next().unwrap_or_default().split(',').filter_map(|s| s.parse().ok()).collect(),
            "--wasm" => wasm = args.next(),
            "--page" => page = args.next(),
            "--page-only" => page_only = true,
            "--memory-only" => memory_only = true,
            "--page-memory" => page_memory = args.next(),
            "--memory-child" => {
                memory_child(&args.by_ref().collect::<Vec<_>>());
                return;
            }
            "--out" => out = args.next(),
            "--json" => json_out = args.next(),
            "--quick" => quick = true,
            "--issue33" => issue33_only = true,
            "--native-peers" => {
                native_peers(&args.next().unwrap_or_else(|| panic!("--native-peers needs the bench page's JSON file")));
                return;
            }
            "--before-after" => before_after = args.next(),
            other => {
                eprintln!("perf: unknown argument {other}");
                std::process::exit(2);
            }
        }
    }
    if page_only {
        // the "In the page" section alone, from the page bench's JSON (no native run)
        print!("{}", page_section(page.as_deref()));
        return;
    }
    if memory_only {
        // the memory section alone (no timing), as the whole run writes it
        print!("{}", memory_section(page_memory.as_deref()));
        return;
    }
    if issue33_only {
        // issue 33's sections alone: the planar passes they read (100k nodes, both orders),
        // the 3D passes, the time to quality, versus Mesquite and the targets
        eprintln!("perf: {PLANAR_NODES} nodes, the passes of issue 33 …");
        let reports = [measure_rows(PLANAR_NODES, &ISSUE33_PLANAR, quick)];
        // the planar passes these sections read (the full run's table has them all)
        println!("## The planar passes of issue 33, {PLANAR_NODES} nodes, ns per node-pass\n\n| pass | file order | Hilbert |\n|---|---:|---:|");
        for (name, a, b) in &reports[0].rows {
            println!("| {name} | {} | {} |", fmt_ns(*a), fmt_ns(*b));
        }
        println!();
        print!("{}", issue33_sections(&reports, quick, wasm.as_deref(), page.as_deref(), before_after.as_deref()));
        return;
    }
    let machine = machine();
    let mut reports = Vec::new();
    for &n in &sizes {
        eprintln!("perf: {n} nodes …");
        let r = measure(n, quick);
        reports.push(r);
    }
    eprintln!("perf: Newton's first trial against Chen's search, quality …");
    let quality = newton_quality();
    let memory = memory_section(page_memory.as_deref());
    // issue 33's sections read the planar passes of the 100k mesh: measured apart when
    // that size is not among --sizes
    let extra = (!reports.iter().any(|r| r.nodes == PLANAR_NODES)).then(|| {
        eprintln!("perf: {PLANAR_NODES} nodes, the passes of issue 33 …");
        measure_rows(PLANAR_NODES, &ISSUE33_PLANAR, quick)
    });
    let issue33 = match extra {
        Some(r) => issue33_sections(&[r], quick, wasm.as_deref(), page.as_deref(), before_after.as_deref()),
        None => issue33_sections(&reports, quick, wasm.as_deref(), page.as_deref(), before_after.as_deref()),
    };
    let doc = render(&machine, &reports, &quality, &memory, wasm.as_deref()) + &issue33 + &page_section(page.as_deref());
    let doc = markdown::wrap(&doc);
    match out {
        Some(p) => std::fs::write(&p, &doc).unwrap_or_else(|e| panic!("cannot write {p}: {e}")),
        None => print!("{doc}"),
    }
    if let Some(p) = json_out {
        let mut j = serde_json::Map::new();
        for r in &reports {
            let mut m = serde_json::Map::new();
            for (name, a, b) in &r.rows {
                m.insert(name.clone(), serde_json::json!({"file_order_ns": a, "hilbert_ns": b}));
            }
            j.insert(r.nodes.to_string(), serde_json::Value::Object(m));
        }
        std::fs::write(&p, serde_json::to_string_pretty(&j).expect("json"))
            .unwrap_or_else(|e| panic!("cannot write {p}: {e}"));
    }
}
