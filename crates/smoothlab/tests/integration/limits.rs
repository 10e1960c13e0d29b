//! Resource limits of the readers: what a hostile or broken file can cost.
//!
//! - A header that claims 10⁹ items (in every format, for every counted section) is
//!   refused before anything is allocated for it, naming the line and the count.
//! - A file over `io::MAX_FILE_BYTES` is refused by its size before it is read (sparse
//!   files, so nothing big is written).
//! - Unterminated sections, attribute data that never ends, a million comment lines and
//!   a single 50 MB line of digits are refused early (or read) with the right line.
//! - Memory: claims the data does not back cost a bounded amount. Allocations are counted
//!   per thread by a wrapper around the system allocator, so the figures are exact and
//!   do not depend on the other tests running in parallel; nothing here measures time.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::path::PathBuf;

use smoothlab::io::{self, Format};
use smoothlab::Error;

/// The system allocator, counting the bytes each thread has live and its peak.
struct Counting;

thread_local! {
    static LIVE: Cell<usize> = const { Cell::new(0) };
    static PEAK: Cell<usize> = const { Cell::new(0) };
}

fn grew(by: usize) {
    let _ = LIVE.try_with(|l| {
        let now = l.get() + by;
        l.set(now);
        let _ = PEAK.try_with(|p| p.set(p.get().max(now)));
    });
}

fn shrank(by: usize) {
    let _ = LIVE.try_with(|l| l.set(l.get().saturating_sub(by)));
}

// SAFETY: every call is passed straight to `System`; the counters are plain thread-local
// cells (const-initialised, no destructor, never allocating).
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            grew(layout.size());
        }
        p
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc_zeroed(layout) };
        if !p.is_null() {
            grew(layout.size());
        }
        p
    }
    unsafe fn dealloc(&self, p: *mut u8, layout: Layout) {
        unsafe { System.dealloc(p, layout) };
        shrank(layout.size());
    }
    unsafe fn realloc(&self, p: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let q = unsafe { System.realloc(p, layout, new_size) };
        if !q.is_null() {
            // Counted as the moment both blocks may exist: the worst case of a realloc.
            grew(new_size);
            shrank(layout.size());
        }
        q
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// Runs `f` and returns its result with the most bytes this thread had allocated at once
/// during the call, beyond what it held before.
fn peak_during<T>(f: impl FnOnce() -> T) -> (T, usize) {
    let before = LIVE.with(Cell::get);
    PEAK.with(|p| p.set(before));
    let out = f();
    (out, PEAK.with(Cell::get) - before)
}

const KIB: usize = 1 << 10;
const MIB: usize = 1 << 20;

/// The error of reading `text` as `format`, with the peak allocation of the attempt.
fn refused(text: &str, format: Format) -> (Error, usize) {
    let (r, peak) = peak_during(|| io::read_str(text, format));
    match r {
        Ok(m) => panic!("{format:?} read a mesh of {} nodes from input that should be refused", m.node_count()),
        Err(e) => (e, peak),
    }
}

fn assert_mentions(e: &Error, want: &[&str]) {
    let msg = e.to_string();
    for w in want {
        assert!(msg.contains(w), "{msg:?} should mention {w:?}");
    }
    assert!(msg.len() < 400, "messages stay short: {} bytes", msg.len());
}

const MSH22: &str = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
const MSH41: &str = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
const MSH22_NODES: &str = "$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n";
const MSH41_NODES: &str = "$Nodes\n1 3 1 3\n2 1 0 3\n1\n2\n3\n0 0 0\n1 0 0\n0 1 0\n$EndNodes\n";
const VTK_HEAD: &str = "# vtk DataFile Version 3.0\nlimits\nASCII\nDATASET UNSTRUCTURED_GRID\n";
const VTK_POINTS: &str = "POINTS 3 double\n0 0 0\n1 0 0\n0 1 0\n";
const VTK_CELLS: &str = "CELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n5\n";

#[test]
fn a_billion_of_anything_is_refused_before_allocating() {
    let g = "1000000000";
    // (format, text, line the message must name, what it must say)
    let cases: Vec<(Format, String, &str, &str)> = vec![
        (Format::Msh, format!("{MSH22}$Nodes\n{g}\n1 0 0 0\n"), "line 5", "nodes"),
        (Format::Msh, format!("{MSH22}{MSH22_NODES}$Elements\n{g}\n1 2 0 1 2 3\n"), "line 11", "elements"),
        (Format::Msh, format!("{MSH41}$Nodes\n1 {g} 1 {g}\n2 1 0 1\n1\n0 0 0\n"), "line 5", "nodes"),
        (Format::Msh, format!("{MSH41}$Nodes\n{g} 3 1 3\n"), "line 5", "node entity blocks"),
        (Format::Msh, format!("{MSH41}$Nodes\n1 3 1 3\n2 1 0 {g}\n"), "line 6", "block has 1000000000 nodes"),
        (Format::Msh, format!("{MSH22}{MSH22_NODES}$Elements\n1\n1 2 0 1 2 3\n$EndElements\n$NodeData\n1\n\"fixed\"\n0\n3\n0\n1\n{g}\n1 1\n"), "line 21", "values in the 'fixed' view"),
        (Format::Vtk, format!("{VTK_HEAD}POINTS {g} double\n0 0 0\n"), "line 5", "points"),
        (Format::Vtk, format!("{VTK_HEAD}{VTK_POINTS}CELLS {g} 4\n3 0 1 2\n"), "line 9", "cells"),
        (Format::Vtk, format!("{VTK_HEAD}{VTK_POINTS}CELLS {g} 4\nOFFSETS vtktypeint64\n0 3\n"), "line 9", "offsets"),
        (Format::Vtk, format!("{VTK_HEAD}{VTK_POINTS}CELLS 2 {g}\nOFFSETS vtktypeint64\n0 3\n"), "line 9", "connectivity entries"),
        (Format::Vtk, format!("{VTK_HEAD}{VTK_POINTS}CELLS 1 4\n3 0 1 2\nCELL_TYPES {g}\n5\n"), "line 11", "cell types"),
        (Format::Vtk, format!("{VTK_HEAD}{VTK_POINTS}{VTK_CELLS}CELL_DATA {g}\nSCALARS s float\n"), "line 13", "values"),
        (Format::Vtk, format!("{VTK_HEAD}{VTK_POINTS}{VTK_CELLS}POINT_DATA 3\nLOOKUP_TABLE t {}\n0 0 0 1\n", 250_000_000), "line 14", "values of LOOKUP_TABLE"),
        (Format::Vtk, format!("{VTK_HEAD}{VTK_POINTS}{VTK_CELLS}FIELD f {g}\na 1 1 float\n0\n"), "line 13", "field arrays"),
        (Format::Vtk, format!("{VTK_HEAD}{VTK_POINTS}{VTK_CELLS}FIELD f 1\na {g} {g} float\n0\n"), "line 14", "values of a"),
        (Format::Off, format!("OFF\n{g} 1 0\n0 0 0\n"), "line 2", "vertices"),
        (Format::Off, format!("OFF\n3 {g} 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"), "line 2", "faces"),
        (Format::Off, format!("OFF {g} 1 0\n0 0 0\n"), "line 1", "vertices"),
    ];
    for (format, text, line, what) in &cases {
        let (e, peak) = refused(text, *format);
        assert_mentions(&e, &[line, g, what]);
        assert!(peak < 64 * KIB, "{format:?} {what}: allocated {peak} bytes for a claim it refused:\n{text}");
    }
    // Triangle: both files of the pair.
    let (r, peak) = peak_during(|| io::read_triangle(&format!("{g} 2 0 0\n1 0 0\n"), "1 3 0\n1 1 2 3\n"));
    assert_mentions(&r.unwrap_err(), &["line 1", g, "nodes", ".node file"]);
    assert!(peak < 64 * KIB, "{peak}");
    let (r, peak) = peak_during(|| io::read_triangle("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n", &format!("{g} 3 0\n1 1 2 3\n")));
    assert_mentions(&r.unwrap_err(), &["line 1", g, "triangles", ".ele file"]);
    assert!(peak < 64 * KIB, "{peak}");
    // A cell that claims a billion points reads what is there and stops at the next keyword.
    let (e, peak) = refused(&format!("{VTK_HEAD}{VTK_POINTS}CELLS 1 4\n{g} 0 1 2\nCELL_TYPES 1\n5\n"), Format::Vtk);
    assert_mentions(&e, &["line 11", "cut short by 'CELL_TYPES'"]);
    assert!(peak < 64 * KIB, "{peak}");
}

#[test]
fn counts_the_data_does_not_back_cost_a_bounded_amount() {
    // Counts just small enough to pass the "could the rest of the file hold them" check,
    // over 32 MiB of blank space instead of data: what is reserved up front must stay a
    // fixed amount, not grow with the claim (it once did: up to 14 bytes per byte of
    // blank space for VTK 5.1 offsets, 28 bytes per announced node up to 2²⁰ nodes).
    let blank = " ".repeat(32 * MIB);
    let n = blank.len() / 2 - 8;
    let cases: Vec<(Format, String, &str)> = vec![
        (Format::Vtk, format!("{VTK_HEAD}{VTK_POINTS}CELLS {n} {n}\nOFFSETS vtktypeint64\n0{blank}"), "offset 1"),
        (Format::Vtk, format!("{VTK_HEAD}{VTK_POINTS}CELLS {} {n}\n{blank}", n / 2), "point count of cell 0"),
        (Format::Vtk, format!("{VTK_HEAD}POINTS {} double\n{blank}", n / 3), "x coordinate of point 0"),
        (Format::Msh, format!("{MSH22}$Nodes\n{}\n{blank}", n / 4), "tag of node 1"),
        (Format::Msh, format!("{MSH22}{MSH22_NODES}$Elements\n{}\n{blank}", n / 5), "tag of element 1"),
        (Format::Msh, format!("{MSH41}$Nodes\n1 {} 1 1\n{blank}", n / 4), "entity dimension of node block 1"),
        (Format::Msh, format!("{MSH41}{MSH41_NODES}$Elements\n1 {} 1 1\n{blank}", n / 2), "entity dimension of element block 1"),
        (
            Format::Msh,
            format!("{MSH22}{MSH22_NODES}$Elements\n1\n1 2 0 1 2 3\n$EndElements\n$NodeData\n1\n\"fixed\"\n0\n3\n0\n1\n{}\n{blank}", n / 2),
            "node tag of value 1",
        ),
        (Format::Off, format!("OFF\n{} {} 0\n{blank}", n / 3, n / 4), "ends after 0"),
    ];
    for (format, text, what) in &cases {
        let (e, peak) = refused(text, *format);
        assert_mentions(&e, &[what]);
        assert!(peak < 4 * MIB, "{format:?} ({what}): {} MiB allocated for 32 MiB of blank space: {e}", peak / MIB);
    }
}

/// A fresh directory for this test's files.
fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("smoothlab-limits-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn files_over_the_size_limit_are_refused_unread() {
    let dir = scratch("big");
    let two_gb = 2u64 << 30;
    assert!(two_gb > io::MAX_FILE_BYTES);
    for name in ["big.msh", "big.vtk", "big.obj", "big.off"] {
        let p = dir.join(name);
        // A sparse file: its length is 2 GiB, its blocks are never written.
        std::fs::File::create(&p).unwrap().set_len(two_gb).unwrap();
        let (r, peak) = peak_during(|| io::read_path(&p));
        let e = r.unwrap_err();
        assert!(matches!(e, Error::TooLarge(_)), "{name}: {e:?}");
        assert_mentions(&e, &[name, &two_gb.to_string(), &io::MAX_FILE_BYTES.to_string()]);
        assert!(peak < 64 * KIB, "{name}: allocated {peak} bytes before refusing");
    }
    // Triangle pairs: a small .node with a huge .ele, and the other way round.
    let node = "3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n";
    let ele = "1 3 0\n1 1 2 3\n";
    for (big, small, text) in [("ele", "node", node), ("node", "ele", ele)] {
        let stem = dir.join(format!("pair-{big}"));
        std::fs::write(stem.with_extension(small), text).unwrap();
        std::fs::File::create(stem.with_extension(big)).unwrap().set_len(two_gb).unwrap();
        for ext in ["node", "ele"] {
            let (r, peak) = peak_during(|| io::read_path(&stem.with_extension(ext)));
            let e = r.unwrap_err();
            assert!(matches!(e, Error::TooLarge(_)), "{e:?}");
            assert_mentions(&e, &[&format!("pair-{big}.{big}")]);
            assert!(peak < 64 * KIB, "allocated {peak} bytes before refusing");
        }
    }
    // Just at the limit is not refused for its size (it is read and found not to be a mesh).
    let p = dir.join("at-limit.off");
    std::fs::File::create(&p).unwrap().set_len(io::MAX_FILE_BYTES).unwrap();
    let e = io::read_path(&p).unwrap_err();
    assert!(!matches!(e, Error::TooLarge(_)), "{e:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn unterminated_and_endless_sections_are_refused_at_their_line() {
    // A $Comments section that never closes: the error is at the file's last token.
    let lines = 100_000;
    let text = format!("{MSH22}$Comments\n{}", "just words\n".repeat(lines));
    let (e, peak) = refused(&text, Format::Msh);
    assert_mentions(&e, &[&format!("line {}", 4 + lines), "'$EndComments'", "opened at line 4"]);
    assert!(peak < 64 * KIB, "{peak}");
    // $Nodes with its data but no $EndNodes, and the file goes on with another section.
    let text = format!("{MSH22}$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$Elements\n1\n1 2 0 1 2 3\n$EndElements\n");
    assert_mentions(&refused(&text, Format::Msh).0, &["line 9", "expected '$EndNodes'", "found '$Elements'"]);
    // A VTK POINT_DATA whose values go on past its count: refused right after the count.
    let values = "0.5\n".repeat(1_000_000);
    let text = format!("{VTK_HEAD}{VTK_POINTS}{VTK_CELLS}POINT_DATA 3\nSCALARS s float 1\nLOOKUP_TABLE default\n{values}");
    let (e, peak) = refused(&text, Format::Vtk);
    assert_mentions(&e, &["line 19", "expected a section", "'0.5'"]);
    assert!(peak < 64 * KIB, "{peak}");
    // …and one whose values stop short.
    let text = format!("{VTK_HEAD}{VTK_POINTS}{VTK_CELLS}POINT_DATA 3\nSCALARS s float 1\nLOOKUP_TABLE default\n1\n2\n");
    assert_mentions(&refused(&text, Format::Vtk).0, &["line 17", "ends here", "SCALARS s"]);
    // A METADATA block with no blank line runs to the end of the file, and is only skipped.
    let text = format!("{VTK_HEAD}{VTK_POINTS}{VTK_CELLS}METADATA\n{}", "INFORMATION 1\n".repeat(10_000));
    assert_eq!(io::read_str(&text, Format::Vtk).unwrap().element_count(), 1);
    // An OFF file whose faces go on past the count.
    let text = format!("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n{}", "3 0 1 2\n".repeat(1000));
    assert_mentions(&refused(&text, Format::Off).0, &["line 7", "after the 3 vertices and 1 faces"]);
}

#[test]
fn a_million_comment_lines_cost_nothing_and_keep_line_numbers() {
    let million = 1_000_000;
    let comments = "# a comment line\n".repeat(million);
    // OBJ: the first real statements come after the comments; an error names its true line.
    let text = format!("{comments}v 0 0\nv 1 0\nv 0 1\nf 1 2 x\n");
    let (e, peak) = refused(&text, Format::Obj);
    assert_mentions(&e, &[&format!("line {}", million + 4), "corner 3", "'x'"]);
    assert!(peak < 64 * KIB, "{peak}");
    let text = format!("{comments}v 0 0\nv 1 0\nv 0 1\nf 1 2 3\n");
    let (m, peak) = peak_during(|| io::read_str(&text, Format::Obj));
    assert_eq!(m.unwrap().element_count(), 1);
    assert!(peak < 64 * KIB, "{peak}");
    // OFF: comments between the header and the counts, and between vertices.
    let text = format!("OFF\n{comments}3 1 0\n0 0 0\n{comments}1 0 0\n0 1 0\n3 0 1 3\n");
    assert_mentions(&refused(&text, Format::Off).0, &[&format!("element 0 (line {})", 2 * million + 6), "vertex index 3"]);
    // Triangle: comments everywhere in the .node file.
    let node = format!("{comments}3 2 0 0\n1 0 0\n{comments}2 1 0\n3 0 one\n");
    let e = io::read_triangle(&node, "1 3 0\n1 1 2 3\n").unwrap_err();
    assert_mentions(&e, &[&format!("line {}", 2 * million + 4), "y coordinate of node 3", "'one'"]);
    // A .msh $Comments section of a million lines, then a mesh: read.
    let text = format!("{MSH22}$Comments\n{comments}$EndComments\n{MSH22_NODES}$Elements\n1\n1 2 0 1 2 3\n$EndElements\n");
    let (m, peak) = peak_during(|| io::read_str(&text, Format::Msh));
    assert_eq!(m.unwrap().node_count(), 3);
    assert!(peak < 64 * KIB, "{peak}");
}

#[test]
fn a_single_fifty_megabyte_line_of_digits() {
    let digits = "7".repeat(50 * MIB);
    let quoted_cut = format!("'{}…'", "7".repeat(40));
    // Where a count is expected: not a number we can hold. The message quotes 40 digits.
    let cases: Vec<(Format, String, &str)> = vec![
        (Format::Msh, format!("{MSH22}$Nodes\n{digits}\n"), "line 5"),
        (Format::Msh, format!("{MSH41}$Nodes\n1 {digits} 1 1\n"), "line 5"),
        (Format::Vtk, format!("{VTK_HEAD}POINTS {digits} double\n"), "line 5"),
        (Format::Off, format!("OFF\n{digits} 1 0\n"), "line 2"),
        // Where a coordinate is expected: a finite-looking number that is not finite.
        (Format::Vtk, format!("{VTK_HEAD}POINTS 1 double\n{digits} 0 0\n"), "line 6"),
        (Format::Obj, format!("v {digits} 0\n"), "line 1"),
    ];
    for (format, text, line) in &cases {
        let (e, peak) = refused(text, *format);
        assert_mentions(&e, &[line, &quoted_cut]);
        assert!(peak < 64 * KIB, "{format:?}: {peak} bytes allocated");
    }
    let node = format!("{digits} 2 0 0\n");
    let (r, peak) = peak_during(|| io::read_triangle(&node, ""));
    assert_mentions(&r.unwrap_err(), &["line 1", &quoted_cut, ".node file"]);
    assert!(peak < 64 * KIB, "{peak}");
    // The same line fed as bytes, with a name.
    let (r, peak) = peak_during(|| io::read_bytes(digits.as_bytes(), "digits.off"));
    assert_mentions(&r.unwrap_err(), &["line 1", "expected 'OFF'", &quoted_cut]);
    assert!(peak < 64 * KIB, "{peak}");
}

#[test]
fn real_data_costs_memory_in_proportion() {
    // A real mesh: a 300 × 300 grid of quads written as VTK (about 4 MB). Reading it may
    // cost several times its size (coordinates, topology), but not more than that.
    let n = 300;
    let mut text = format!("{VTK_HEAD}POINTS {} double\n", (n + 1) * (n + 1));
    for j in 0..=n {
        for i in 0..=n {
            text.push_str(&format!("{i} {j} 0\n"));
        }
    }
    text.push_str(&format!("CELLS {} {}\n", n * n, 5 * n * n));
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i;
            text.push_str(&format!("4 {a} {} {} {}\n", a + 1, a + n + 2, a + n + 1));
        }
    }
    text.push_str(&format!("CELL_TYPES {}\n{}", n * n, "9\n".repeat(n * n)));
    let (m, peak) = peak_during(|| io::read_str(&text, Format::Vtk));
    let m = m.unwrap();
    assert_eq!((m.node_count(), m.element_count()), ((n + 1) * (n + 1), n * n));
    let per_node = peak / m.node_count();
    assert!(peak < 16 * text.len(), "{} MiB for a {} MiB file", peak / MIB, text.len() / MIB);
    assert!(per_node < 1024, "{per_node} bytes per node");
}
