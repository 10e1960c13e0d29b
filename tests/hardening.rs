//! Regression tests for what an attack on the readers and the metrics found (issue 16),
//! one named test per finding; the inputs are in `tests/data/hardening/` (and
//! `tests/data/bad/`, checked with the rest of that corpus by `io_bad.rs`), the big ones
//! generated here.

use std::path::{Path, PathBuf};

use glam::DVec2;
use smoothlab::io::{self, Format, WriteOptions};
use smoothlab::{Error, Mesh};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/hardening").join(name)
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("smoothlab-hardening-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn same_mesh(a: &Mesh, b: &Mesh, what: &str) {
    assert_eq!(a.nodes, b.nodes, "{what}: nodes");
    assert_eq!(a.element_count(), b.element_count(), "{what}: elements");
    for e in 0..a.element_count() {
        assert_eq!((a.kind(e), a.element(e)), (b.kind(e), b.element(e)), "{what}: element {e}");
    }
    assert_eq!(a.fixed, b.fixed, "{what}: fixed flags");
}

// ---- 1. non-planar meshes -----------------------------------------------------------------

/// The node a non-planar refusal names, and the message.
fn not_planar(text: &str, format: Format) -> (usize, String) {
    match io::read_str(text, format) {
        Err(e @ Error::NotPlanar { node, .. }) => (node, e.to_string()),
        other => panic!("expected NotPlanar, got {:?}", other.map(|m| m.node_count())),
    }
}

/// The rand2D of the issue (580 nodes) as OBJ text, node `lifted` at z = `z`.
fn rand2d_obj(lifted: usize, z: f64) -> String {
    let m = smoothlab::generate::rand2d(500, 20, 7).unwrap();
    assert_eq!(m.node_count(), 580);
    let obj = io::write_string(&m, Format::Obj, &WriteOptions::default()).unwrap();
    let mut seen = 0;
    let mut out = String::new();
    for line in obj.lines() {
        if line.starts_with("v ") {
            if seen == lifted {
                let mut t: Vec<&str> = line.split(' ').collect();
                let zs = z.to_string();
                t.truncate(3);
                out += &format!("{} {zs}\n", t.join(" "));
                seen += 1;
                continue;
            }
            seen += 1;
        }
        out += line;
        out.push('\n');
    }
    out
}

/// One node lifted far off an otherwise flat mesh is refused, naming that node, however
/// small its lift is next to the bounding box it inflates (the fit tilted toward it and
/// squeezed the other nodes onto lines).
#[test]
fn an_outlier_node_is_refused_by_name() {
    // the 2 x 2 quad grid with a corner at z = 1e6 (tests/data/bad/non_planar_outlier.obj)
    let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/bad/non_planar_outlier.obj")).unwrap();
    let (node, msg) = not_planar(&text, Format::Obj);
    assert_eq!(node, 8, "{msg}");
    // a 580-node rand2D with one interior node at z = 3e6, and at heights down to a
    // thousandth of an element
    for z in [3e6, 1.0, 1e-3] {
        for lifted in [0, 100, 579] {
            let (node, msg) = not_planar(&rand2d_obj(lifted, z), Format::Obj);
            assert_eq!(node, lifted, "z = {z}: {msg}");
            assert!(msg.contains(&format!("node {lifted} (line ")), "{msg}");
        }
    }
}

/// Planar meshes still read: tilted, far from the origin, and with their coordinates
/// rounded to 6 significant digits, as many tools print them (the tolerance excuses
/// rounding relative to the coordinates' magnitude).
#[test]
fn rounded_tilted_planes_still_read() {
    let m = smoothlab::generate::rand2d(2000, 30, 3).unwrap();
    let (s, c) = (0.3f64.sin(), 0.3f64.cos());
    for (origin, digits) in [(0.0, 6), (1e3, 7), (-5e4, 9)] {
        let mut obj = String::new();
        for p in &m.nodes {
            let q = [origin + p.x, origin + p.y * c, origin + p.y * s];
            obj += &format!("v {:.*e} {:.*e} {:.*e}\n", digits - 1, q[0], digits - 1, q[1], digits - 1, q[2]);
        }
        for e in 0..m.element_count() {
            let ids: Vec<String> = m.element(e).iter().map(|i| (i + 1).to_string()).collect();
            obj += &format!("f {}\n", ids.join(" "));
        }
        let back = io::read_str(&obj, Format::Obj).unwrap_or_else(|e| panic!("origin {origin}, {digits} digits: {e}"));
        assert_eq!(back.element_count(), m.element_count());
    }
}

// ---- 2. a UTF-8 byte-order mark -------------------------------------------------------

/// A leading BOM is skipped in every format: the file reads as the same file without it
/// (the OBJ lost its first vertex; .msh, .vtk and .node were refused).
#[test]
fn byte_order_mark_is_skipped_in_every_format() {
    for name in ["bom.obj", "bom.off", "bom.msh", "bom.vtk", "bom.node", "bom.ele"] {
        let bytes = std::fs::read(data(name)).unwrap();
        assert_eq!(&bytes[..3], b"\xef\xbb\xbf", "{name} starts with a BOM");
        let with = io::read_path(&data(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        let format = Format::from_name(name).unwrap();
        let without = if format == Format::Triangle {
            let text = |ext: &str| std::fs::read_to_string(data(&format!("bom.{ext}"))).unwrap()[3..].to_string();
            io::read_triangle(&text("node"), &text("ele")).unwrap()
        } else {
            io::read_str(std::str::from_utf8(&bytes[3..]).unwrap(), format).unwrap()
        };
        same_mesh(&with, &without, name);
        if format != Format::Triangle {
            // the page's way in
            same_mesh(&io::read_bytes(&bytes, name).unwrap(), &without, name);
        }
    }
    // the OBJ: four vertices and two faces, the first vertex kept
    let m = io::read_path(&data("bom.obj")).unwrap();
    assert_eq!((m.node_count(), m.element_count()), (4, 2));
    assert_eq!(m.nodes[0], DVec2::ZERO);
}

// ---- 4. files that are not regular files ------------------------------------------------

/// A device behind a `.msh` name is refused as not a regular file, before anything is read
/// (`/dev/zero` grew memory without bound; `/dev/urandom` read for seconds).
#[cfg(unix)]
#[test]
fn devices_behind_a_mesh_name_are_refused() {
    let d = scratch("devices");
    for dev in ["/dev/zero", "/dev/urandom", "/dev/null"] {
        if !Path::new(dev).exists() {
            continue;
        }
        let link = d.join(format!("{}.msh", dev.trim_start_matches("/dev/")));
        std::os::unix::fs::symlink(dev, &link).unwrap();
        let t = std::time::Instant::now();
        let e = io::read_path(&link).unwrap_err();
        assert!(t.elapsed().as_secs() < 5, "{dev}: took {:?}", t.elapsed());
        let msg = e.to_string();
        assert!(msg.contains("not a regular file") && msg.contains(&link.display().to_string()), "{dev}: {msg}");
    }
    // a directory with a mesh name
    let dir = d.join("folder.vtk");
    std::fs::create_dir(&dir).unwrap();
    let msg = io::read_path(&dir).unwrap_err().to_string();
    assert!(msg.contains("a directory, not a regular file"), "{msg}");
    std::fs::remove_dir_all(&d).unwrap();
}

/// A named pipe is refused at once instead of waiting forever for a writer (the test
/// runs the read on a thread and gives it five seconds).
#[cfg(unix)]
#[test]
fn a_named_pipe_is_refused_without_waiting() {
    let d = scratch("fifo");
    let fifo = d.join("pipe.obj");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    if !made.is_ok_and(|s| s.success()) {
        // no mkfifo on this system: nothing to test here (the devices test still runs)
        eprintln!("mkfifo unavailable; skipped");
        return;
    }
    let (tx, rx) = std::sync::mpsc::channel();
    let f = fifo.clone();
    std::thread::spawn(move || {
        let _ = tx.send(io::read_path(&f).map(|_| ()).unwrap_err().to_string());
    });
    let msg = rx.recv_timeout(std::time::Duration::from_secs(5));
    if msg.is_err() {
        // unblock the reader so the process can end, then fail
        let _ = std::fs::write(&fifo, b"");
        panic!("reading a named pipe blocked");
    }
    let msg = msg.unwrap();
    assert!(msg.contains("a device, pipe or socket, not a regular file"), "{msg}");
    std::fs::remove_dir_all(&d).unwrap();
}

// ---- 5. what smoothlab writes, it reads -------------------------------------------------

/// A 2.5-million-node mesh written as `.msh` (over 256 MiB, the old read limit) reads
/// back (it was written, then refused as too large).
#[test]
fn a_written_large_msh_reads_back() {
    let d = scratch("large");
    let mut m = smoothlab::generate::grid(1580, 1580, smoothlab::generate::GridKind::Tri).unwrap();
    // coordinates with all their digits, as after smoothing
    for p in &mut m.nodes {
        *p = *p * std::f64::consts::PI + DVec2::new(1.0 / 3.0, 2.0 / 7.0);
    }
    let path = d.join("big.msh");
    io::write_path(&m, &path, &WriteOptions::default()).unwrap();
    let len = std::fs::metadata(&path).unwrap().len();
    assert!(len > 256 << 20, "{len} bytes: the case of the issue is over 256 MiB");
    assert!(len <= io::MAX_FILE_BYTES);
    let back = io::read_path(&path).unwrap_or_else(|e| panic!("{len} bytes written, not read back: {e}"));
    assert_eq!(back.node_count(), m.node_count());
    assert_eq!(back.nodes, m.nodes);
    std::fs::remove_dir_all(&d).unwrap();
}

/// The largest mesh the page holds, with the longest coordinates, exported in every
/// format, fits under the page's own file limit (so the page reads what it exports), and
/// the page checks that same limit.
#[test]
fn the_page_reads_what_it_exports() {
    let side = (smoothlab::lab::MAX_NODES as f64).sqrt() as usize - 1;
    let mut m = smoothlab::generate::grid(side, side, smoothlab::generate::GridKind::Tri).unwrap();
    assert!(m.node_count() <= smoothlab::lab::MAX_NODES);
    for p in &mut m.nodes {
        // 17 significant digits, a sign and a three-digit exponent on every coordinate
        *p = -(*p + DVec2::new(1.0 / 3.0, 1.0 / 7.0)) * 1.2345678901234567e-123;
    }
    for format in [Format::Msh, Format::Vtk, Format::Obj, Format::Off] {
        let text = io::write_string(&m, format, &WriteOptions { msh_version: io::MshVersion::V41 }).unwrap();
        assert!((text.len() as u64) < io::PAGE_MAX_FILE_BYTES, "{format:?}: {} bytes", text.len());
        let text = io::write_string(&m, format, &WriteOptions::default()).unwrap();
        assert!((text.len() as u64) < io::PAGE_MAX_FILE_BYTES, "{format:?}: {} bytes", text.len());
    }
    let (node, ele) = io::write_triangle(&m).unwrap();
    assert!(((node.len() + ele.len()) as u64) < io::PAGE_MAX_FILE_BYTES);
    let app = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("www/app.js")).unwrap();
    assert!(
        app.contains(&format!("const MAX_FILE_BYTES = {} * 1024 * 1024;", io::PAGE_MAX_FILE_BYTES >> 20)),
        "www/app.js checks io::PAGE_MAX_FILE_BYTES"
    );
}

// ---- 7. names and messages ---------------------------------------------------------------

/// `.node` as a Triangle output name has no stem: refused, instead of writing
/// `.node.node` and `.node.ele`.
#[test]
fn a_triangle_name_without_a_stem_is_refused() {
    let d = scratch("stem");
    let m = io::read_path(&data("bom.obj")).unwrap();
    for name in [".node", ".ele"] {
        let e = io::write_path(&m, &d.join(name), &WriteOptions::default()).unwrap_err();
        assert!(matches!(e, Error::Invalid(_)), "{e:?}");
        assert!(e.to_string().contains("needs a name before the extension"), "{e}");
        assert!(io::read_path(&d.join(name)).unwrap_err().to_string().contains("needs a name before the extension"));
    }
    assert_eq!(std::fs::read_dir(&d).unwrap().count(), 0, "nothing written");
    // a proper stem, with dots in it, still pairs
    io::write_path(&m, &d.join("a.b.node"), &WriteOptions::default()).unwrap();
    assert!(d.join("a.b.node").is_file() && d.join("a.b.ele").is_file());
    same_mesh(&io::read_path(&d.join("a.b.ele")).unwrap(), &m, "a.b");
    std::fs::remove_dir_all(&d).unwrap();
}
