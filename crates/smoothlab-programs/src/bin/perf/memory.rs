//! The memory section: the bytes of the 1M-node mesh's arrays, and each command's peak.
//! Each command runs in a child process of this program (`--memory-child`).

use std::fmt::Write as _;
use std::time::Instant;

use smoothlab::generate::rand2d;
use smoothlab::objective::{objective, ObjectiveKind};
use smoothlab::quality::mesh_stats;
use smoothlab::smooth::{Order, SmoothOptions, Smoother, Strategy};

use crate::common::SEED;

/// Peak resident memory of this process, bytes (Linux `VmHWM`).
fn vm_hwm() -> Option<usize> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = s.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: usize = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// The mesh of the memory figures: the 1M-node rand2D of the memory issue (Freitag's
/// rand2d with 999 576 points inside and 1000 per side, seed 2003: 1 003 576 nodes).
const MEMORY_MESH: (usize, usize, u64) = (999_576, 1000, SEED);

/// The commands whose peak resident memory the memory section reports, each run in a
/// child process (`--memory-child`): (what it does, its words for `memory_child`).
const MEMORY_COMMANDS: [(&str, &[&str]); 6] = [
    ("`smoothlab generate rand2d` (spade's Delaunay), written as .msh", &["generate"]),
    ("`smoothlab stats` (read the .msh, statistics)", &["stats"]),
    ("`smoothlab smooth`: read, 3 passes of rules + new in priority order (the default), write", &["smooth", "rules"]),
    ("`smooth --strategy laplace`: read, 3 passes, write", &["smooth", "laplace"]),
    ("`smooth --strategy opt`: read, 3 passes, write", &["smooth", "opt"]),
    ("`smooth --strategy smart`: read, 3 passes, write", &["smooth", "smart"]),
];

/// A command of [`MEMORY_COMMANDS`] as `smoothlab` runs it (the library calls of its
/// `generate`, `stats` and `smooth`), then prints this process's peak resident memory.
/// Words: `generate OUT`, `stats IN`, `smooth STRATEGY IN OUT`.
pub(crate) fn memory_child(words: &[String]) {
    let w: Vec<&str> = words.iter().map(String::as_str).collect();
    let opts = smoothlab::io::WriteOptions::default();
    match w.as_slice() {
        ["generate", out] => {
            let (inside, per_side, seed) = MEMORY_MESH;
            let mesh = rand2d(inside, per_side, seed).expect("rand2d");
            smoothlab::io::write_path(&mesh, std::path::Path::new(out), &opts).expect("write");
        }
        ["stats", input] => {
            let mesh = smoothlab::io::read_path(std::path::Path::new(input)).expect("read");
            std::hint::black_box(mesh_stats(&mesh));
        }
        ["smooth", strategy, input, out] => {
            let mut mesh = smoothlab::io::read_path(std::path::Path::new(input)).expect("read");
            let (strategy, order) = match *strategy {
                "rules" => (Strategy::Rules, Order::Priority),
                "laplace" => (Strategy::Laplace, Order::Input),
                "opt" => (Strategy::Opt, Order::Input),
                "smart" => (Strategy::Smart, Order::Input),
                other => panic!("perf: no strategy {other}"),
            };
            let obj = objective(ObjectiveKind::SmoothShape);
            let mut smoother =
                Smoother::new(SmoothOptions::default().with_strategy(strategy).with_order(order)).expect("options");
            let t0 = Instant::now();
            let clock = move || t0.elapsed().as_secs_f64() * 1e3;
            for _ in 0..3 {
                std::hint::black_box(smoother.pass(&mut mesh, &*obj, &clock));
            }
            smoothlab::io::write_path(&mesh, std::path::Path::new(out), &opts).expect("write");
            std::hint::black_box(mesh_stats(&mesh));
        }
        _ => panic!("perf: --memory-child generate OUT | stats IN | smooth STRATEGY IN OUT"),
    }
    println!("{}", vm_hwm().unwrap_or(0));
}

/// The peak resident memory, bytes, of a child running `memory_child` with `words`.
fn child_peak(words: &[&str]) -> Option<usize> {
    let exe = std::env::current_exe().ok()?;
    let out = std::process::Command::new(exe).arg("--memory-child").args(words).output().ok()?;
    if !out.status.success() {
        eprintln!("perf: --memory-child {}: {}", words.join(" "), String::from_utf8_lossy(&out.stderr));
        return None;
    }
    String::from_utf8(out.stdout).ok()?.trim().parse().ok()
}

/// The memory section: the bytes of each array of the 1M-node mesh per node and per
/// element, the peak resident memory of each command on it, and the page's wasm memory
/// (from `tests/browser/page_memory.mjs`'s JSON, when given).
pub(crate) fn memory_section(page_memory: Option<&str>) -> String {
    let mut w = String::new();
    let (inside, per_side, seed) = MEMORY_MESH;
    eprintln!("perf: memory …");
    let mesh = rand2d(inside, per_side, seed).expect("rand2d");
    let (n, e) = (mesh.node_count(), mesh.element_count());
    let _ = writeln!(w, "## Memory\n");
    let _ = writeln!(
        w,
        "The 1M-node rand2D of the memory issue (rand2d with {inside} points inside and {per_side} per side, seed {seed}: {n} nodes, {e} triangles, {} edges). \
         Each array of the mesh (`Mesh::memory_parts`, capacities) in bytes per node and per element. \
         *Shared* arrays are shared by the mesh's clones, so the page's two sides hold them once.\n",
        mesh.edges().len()
    );
    let _ = writeln!(w, "| array | MB | bytes per node | bytes per element | shared |\n|---|---:|---:|---:|---|");
    let parts = mesh.memory_parts();
    for p in &parts {
        let _ = writeln!(
            w,
            "| {} | {:.1} | {:.2} | {:.2} | {} |",
            p.name,
            p.bytes as f64 / 1e6,
            p.bytes as f64 / n as f64,
            p.bytes as f64 / e as f64,
            if p.shared { "yes" } else { "no" }
        );
    }
    let total: usize = parts.iter().map(|p| p.bytes).sum();
    let own: usize = parts.iter().filter(|p| !p.shared).map(|p| p.bytes).sum();
    let _ = writeln!(
        w,
        "| **the mesh** (`Mesh::heap_bytes`) | **{:.1}** | **{:.1}** | **{:.1}** | |\n| a clone's own arrays | {:.1} | {:.1} | {:.1} | |\n",
        total as f64 / 1e6,
        total as f64 / n as f64,
        total as f64 / e as f64,
        own as f64 / 1e6,
        own as f64 / n as f64,
        own as f64 / e as f64
    );
    // the commands, each in a child process, on the mesh written as .msh
    let dir = std::env::temp_dir().join(format!("smoothlab-perf-memory-{}", std::process::id()));
    let _ = std::fs::create_dir_all(&dir);
    let file = dir.join("rand2d-1m.msh");
    let out = dir.join("smoothed.msh");
    smoothlab::io::write_path(&mesh, &file, &smoothlab::io::WriteOptions::default()).expect("write the test mesh");
    drop(mesh);
    let size = std::fs::metadata(&file).map(|m| m.len()).unwrap_or(0);
    let _ = writeln!(
        w,
        "Peak resident memory of each command on that mesh ({:.0} MB as .msh 2.2), the whole process: each command runs in a child process, whose `VmHWM` is read at its end. \
         Target of the memory issue: read, 3 passes and written in ≤ 250 MB.\n",
        size as f64 / 1e6
    );
    let _ = writeln!(w, "| command | peak RSS | ≤ 250 MB |\n|---|---:|---|");
    let (f, o) = (file.to_string_lossy().into_owned(), out.to_string_lossy().into_owned());
    let gen_out = dir.join("generated.msh").to_string_lossy().into_owned();
    for (what, words) in MEMORY_COMMANDS {
        let mut args: Vec<&str> = words.to_vec();
        match words[0] {
            "generate" => args.push(&gen_out),
            "stats" => args.push(&f),
            _ => {
                args.push(&f);
                args.push(&o);
            }
        }
        eprintln!("perf: memory of {}", args.join(" "));
        let peak = child_peak(&args);
        let shown = peak.map(|b| format!("{:.0} MB", b as f64 / 1e6)).unwrap_or_else(|| "failed".into());
        let met = match (words[0], peak) {
            ("smooth", Some(b)) => if b as f64 <= 250e6 { "✓" } else { "✗" },
            _ => "",
        };
        let _ = writeln!(w, "| {what} | {shown} | {met} |");
    }
    let _ = std::fs::remove_dir_all(&dir);
    let _ = writeln!(w);
    // the page
    let _ = writeln!(w, "The page (`node tests/browser/page_memory.mjs`): the worker's wasm memory (`memory.buffer.byteLength`, which never shrinks) with the 1M-node sample, both sides in one worker. Target: ≤ 400 MiB.\n");
    let v: Option<serde_json::Value> =
        page_memory.and_then(|p| std::fs::read_to_string(p).ok()).and_then(|t| serde_json::from_str(&t).ok());
    match v {
        None => {
            let _ = writeln!(w, "Not measured in this run (no `--page-memory` file).\n");
        }
        Some(v) => {
            let mib = |x: &serde_json::Value| x.as_f64().map(|b| b / (1u64 << 20) as f64).unwrap_or(f64::NAN);
            let mark = |x: f64| if x <= 400.0 { "✓" } else { "✗" };
            let (loaded, smoothed) = (mib(&v["loaded"]["peak_bytes"]), mib(&v["smoothed"]["peak_bytes"]));
            let _ = writeln!(
                w,
                "| {} ({} nodes, {} elements) | wasm memory | ≤ 400 MiB |\n|---|---:|---|\n| the sample loaded and drawn | {loaded:.0} MiB | {} |\n| after one Step (rules, priority order, both sides) | {smoothed:.0} MiB | {} |\n",
                v["browser"].as_str().unwrap_or("Chromium"),
                v["nodes"],
                v["elements"],
                mark(loaded),
                mark(smoothed)
            );
        }
    }
    w
}
