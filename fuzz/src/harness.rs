//! What each fuzz target does with its input, in plain Rust with no fuzzer types, so the
//! regression tests (`tests/fuzz_regressions.rs`, which includes this file by path) replay
//! a kept finding exactly as the fuzzer ran it.
//!
//! Every reader target parses the bytes; when a mesh comes back it also computes
//! `quality::mesh_stats` and writes the mesh in every format, reads each text back and
//! checks that the round trip keeps what the io module documents (nodes to the last bit,
//! elements and kinds; fixed flags for `.msh` and `.vtk`; Medit's `.mesh` groups the
//! elements by kind). A broken promise panics, which the fuzzer reports as a crash. The
//! Medit target also reads volume meshes: written as `.mesh` and read back, a volume
//! writes the same text again.
//!
//! Since issue 16 also: a leading byte-order mark changes nothing (the text targets read
//! every input twice, with and without one); no statistic is NaN, nor any message of an
//! input that does not say NaN itself; and the
//! statistics of a mesh are those of the same mesh scaled by a power of two up to the
//! largest coordinates smoothlab takes (the metrics work in each element's own scale).

use smoothlab::io::{self, Format, MshVersion, WriteOptions};
use smoothlab::{quality, Mesh};

/// The fuzz targets, by the names `cargo fuzz run` takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// A `.msh` 2.2 body: the input follows a fixed `$MeshFormat 2.2 0 8` header.
    Msh22,
    /// A `.msh` 4.1 body: the input follows a fixed `$MeshFormat 4.1 0 8` header.
    Msh41,
    Vtk,
    /// A Triangle pair: the input up to the first [`TRIANGLE_SEPARATOR`] is the `.node`
    /// text, the rest the `.ele` text.
    Triangle,
    Obj,
    Off,
    /// A Medit `.mesh` file, read as a planar mesh and as a model (volumes too).
    Medit,
    /// `io::read_bytes` with the file name chosen by the first byte ([`READ_BYTES_NAMES`]).
    ReadBytes,
}

impl Target {
    pub const ALL: [Target; 8] = [
        Target::Msh22,
        Target::Msh41,
        Target::Vtk,
        Target::Triangle,
        Target::Obj,
        Target::Off,
        Target::Medit,
        Target::ReadBytes,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Target::Msh22 => "msh22",
            Target::Msh41 => "msh41",
            Target::Vtk => "vtk",
            Target::Triangle => "triangle",
            Target::Obj => "obj",
            Target::Off => "off",
            Target::Medit => "medit",
            Target::ReadBytes => "read_bytes",
        }
    }

    pub fn parse(s: &str) -> Option<Target> {
        Target::ALL.into_iter().find(|t| t.name() == s)
    }
}

/// Splits a `triangle` input into its `.node` and `.ele` parts.
pub const TRIANGLE_SEPARATOR: u8 = 0;

/// File names `read_bytes` is called with, indexed by the first input byte (modulo the length).
/// (`.mesh` came last, so the bytes that picked the others still do.)
pub const READ_BYTES_NAMES: [&str; 8] =
    ["fuzz.msh", "fuzz.vtk", "fuzz.obj", "fuzz.off", "fuzz.node", "fuzz.ele", "fuzz.txt", "fuzz.mesh"];

const MSH22_HEADER: &str = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
const MSH41_HEADER: &str = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";

/// What a run gave: a mesh (already checked) or a refusal.
#[derive(Debug)]
pub enum Outcome {
    Mesh(Box<Mesh>),
    Refused(smoothlab::Error),
    /// Not UTF-8 text, for the targets that take text.
    NotText,
}

/// Runs target `t` on `data` as the fuzzer does. Panics when a promise is broken.
pub fn run(t: Target, data: &[u8]) -> Outcome {
    let text = || std::str::from_utf8(data).ok();
    let read = match t {
        Target::Msh22 | Target::Msh41 => {
            let Some(body) = text() else { return Outcome::NotText };
            let head = if t == Target::Msh22 { MSH22_HEADER } else { MSH41_HEADER };
            io::read_str(&format!("{head}{body}"), Format::Msh)
        }
        Target::Vtk => match text() {
            Some(s) => io::read_str(s, Format::Vtk),
            None => return Outcome::NotText,
        },
        Target::Obj => match text() {
            Some(s) => io::read_str(s, Format::Obj),
            None => return Outcome::NotText,
        },
        Target::Off => match text() {
            Some(s) => io::read_str(s, Format::Off),
            None => return Outcome::NotText,
        },
        Target::Medit => match text() {
            Some(s) => {
                check_medit_model(s);
                io::read_str(s, Format::Medit)
            }
            None => return Outcome::NotText,
        },
        Target::Triangle => {
            let (node, ele) = match data.iter().position(|&b| b == TRIANGLE_SEPARATOR) {
                Some(i) => (&data[..i], &data[i + 1..]),
                None => (data, &[][..]),
            };
            match (std::str::from_utf8(node), std::str::from_utf8(ele)) {
                (Ok(n), Ok(e)) => io::read_triangle(n, e),
                _ => return Outcome::NotText,
            }
        }
        Target::ReadBytes => {
            let Some((&first, rest)) = data.split_first() else { return Outcome::NotText };
            io::read_bytes(rest, READ_BYTES_NAMES[first as usize % READ_BYTES_NAMES.len()])
        }
    };
    // The text targets again with a byte-order mark in front (one: a text that starts
    // with one already is read as it is): the same outcome.
    let bom = |s: &str| if s.starts_with('\u{feff}') { s.to_string() } else { format!("\u{feff}{s}") };
    let with_bom = match t {
        Target::Msh22 | Target::Msh41 => text().map(|body| {
            let head = if t == Target::Msh22 { MSH22_HEADER } else { MSH41_HEADER };
            io::read_str(&bom(&format!("{head}{body}")), Format::Msh)
        }),
        Target::Vtk => text().map(|s| io::read_str(&bom(s), Format::Vtk)),
        Target::Obj => text().map(|s| io::read_str(&bom(s), Format::Obj)),
        Target::Off => text().map(|s| io::read_str(&bom(s), Format::Off)),
        Target::Medit => text().map(|s| io::read_str(&bom(s), Format::Medit)),
        _ => None,
    };
    match (&read, with_bom) {
        (Ok(a), Some(Ok(b))) => same(a, &b, true, "with a byte-order mark"),
        (Err(a), Some(Err(b))) => assert_eq!(a.to_string(), b.to_string(), "a byte-order mark changed the message"),
        (a, Some(b)) => panic!("a byte-order mark changed the outcome: {:?} vs {:?}", a.as_ref().map(|_| ()), b.map(|_| ())),
        (_, None) => {}
    }
    match read {
        Ok(mesh) => {
            check_mesh(&mesh);
            Outcome::Mesh(Box::new(mesh))
        }
        Err(e) => {
            // Messages are shown to people: they must render (and not be empty, nor say NaN).
            let m = e.to_string();
            assert!(!m.is_empty(), "empty error message: {e:?}");
            // (a message may quote the input, which may say NaN itself)
            let quoted = String::from_utf8_lossy(data).to_ascii_lowercase().contains("nan");
            assert!(quoted || !m.contains("NaN"), "NaN in a message: {m}");
            Outcome::Refused(e)
        }
    }
}

/// Statistics that must not be NaN (κ may be +∞: an inverted element).
fn no_nan(s: &quality::MeshStats, what: &str) {
    for (name, v) in [
        ("min_angle_deg", s.min_angle_deg),
        ("max_angle_deg", s.max_angle_deg),
        ("min_quality", s.min_quality),
        ("mean_quality", s.mean_quality),
        ("max_condition", s.max_condition),
    ] {
        assert!(!v.is_nan(), "{what}: {name} is NaN");
    }
}

/// Everything a mesh that was read must survive: its statistics and a round trip
/// through every writer that accepts it.
pub fn check_mesh(mesh: &Mesh) {
    if let Err(e) = mesh.sanity_check() {
        panic!("a mesh that was read fails its sanity check: {e}");
    }
    let stats = quality::mesh_stats(mesh);
    assert_eq!((stats.nodes, stats.elements), (mesh.node_count(), mesh.element_count()));
    no_nan(&stats, "mesh_stats");
    // The same mesh scaled up by a power of two (exact) towards the largest coordinates
    // smoothlab takes has the same statistics, bit for bit.
    let largest = mesh.nodes().iter().fold(0.0f64, |m, p| m.max(p.x.abs()).max(p.y.abs()));
    if largest > 0.0 {
        let room = (smoothlab::mesh::MAX_COORDINATE / largest).log2().floor() as i32;
        if room >= 1 {
            let f = 2f64.powi(room.min(1000));
            let mut scaled = mesh.clone();
            for p in scaled.nodes_mut() {
                *p *= f;
            }
            let s = quality::mesh_stats(&scaled);
            assert_eq!(
                (s.inverted, &s.angle_histogram_6deg, s.min_quality.to_bits(), s.max_condition.to_bits()),
                (stats.inverted, &stats.angle_histogram_6deg, stats.min_quality.to_bits(), stats.max_condition.to_bits()),
                "the statistics changed with the scale (×{f:e})"
            );
        }
    }
    for (format, version) in [
        (Format::Msh, MshVersion::V22),
        (Format::Msh, MshVersion::V41),
        (Format::Vtk, MshVersion::V22),
        (Format::Obj, MshVersion::V22),
        (Format::Off, MshVersion::V22),
    ] {
        let opts = WriteOptions { msh_version: version };
        let Ok(text) = io::write_string(mesh, format, &opts) else {
            // OBJ and OFF refuse quadratic elements, by design.
            assert!(matches!(format, Format::Obj | Format::Off) && mesh.has_quadratic(), "{format:?} refused a mesh");
            continue;
        };
        let back = io::read_str(&text, format)
            .unwrap_or_else(|e| panic!("{format:?} {version:?} does not read back what it wrote: {e}\n{text}"));
        same(mesh, &back, matches!(format, Format::Msh | Format::Vtk), &format!("{format:?} {version:?}"));
    }
    // Medit: linear kinds only, a section per kind (triangles first)
    match io::write_string(mesh, Format::Medit, &WriteOptions::default()) {
        Ok(text) => {
            let back = io::read_str(&text, Format::Medit)
                .unwrap_or_else(|e| panic!("Medit does not read back what it wrote: {e}\n{text}"));
            let order: Vec<usize> = [smoothlab::ElementKind::Tri3, smoothlab::ElementKind::Quad4]
                .iter()
                .flat_map(|&k| (0..mesh.element_count()).filter(|&e| mesh.kind(e) == k).collect::<Vec<_>>())
                .collect();
            same_in_order(mesh, &back, &order, false, "Medit");
        }
        Err(_) => assert!(mesh.has_quadratic(), "Medit refused a linear mesh"),
    }
    match io::write_triangle(mesh) {
        Ok((node, ele)) => {
            let back = io::read_triangle(&node, &ele)
                .unwrap_or_else(|e| panic!("Triangle does not read back what it wrote: {e}\n{node}\n{ele}"));
            same(mesh, &back, false, "Triangle");
        }
        Err(_) => assert!(
            mesh.kinds().iter().any(|k| *k != mesh.kind(0)) || !mesh.kind(0).is_triangle(),
            "Triangle refused a mesh of triangles of one kind"
        ),
    }
}

/// What a Medit text holds, read as a model: a volume written as `.mesh` reads back with
/// its nodes to the bit, and writes the same text again.
fn check_medit_model(text: &str) {
    let Ok(smoothlab::Model::Volume(v)) = io::read_model_str(text, Format::Medit) else { return };
    let model = smoothlab::Model::Volume(v);
    let Ok(written) = io::write_model_string(&model, Format::Medit, &WriteOptions::default()) else {
        panic!("Medit refused a volume it read (linear kinds only)")
    };
    let back = match io::read_model_str(&written, Format::Medit) {
        Ok(smoothlab::Model::Volume(b)) => b,
        other => panic!("Medit does not read back the volume it wrote: {:?}\n{written}", other.map(|_| ())),
    };
    let smoothlab::Model::Volume(v) = &model else { unreachable!() };
    let bits = |m: &smoothlab::volume::VolumeMesh| m.nodes().iter().map(|q| q.to_array().map(f64::to_bits)).collect::<Vec<_>>();
    assert_eq!(bits(v), bits(&back), "Medit volume: nodes");
    assert_eq!(v.fixed(), back.fixed(), "Medit volume: fixed flags");
    let again = io::write_model_string(&smoothlab::Model::Volume(back), Format::Medit, &WriteOptions::default()).unwrap();
    assert_eq!(written, again, "Medit volume: written, read back and written again");
}

fn same(a: &Mesh, b: &Mesh, fixed: bool, what: &str) {
    let order: Vec<usize> = (0..a.element_count()).collect();
    same_in_order(a, b, &order, fixed, what);
}

/// `b` is `a` with its elements in `order` (element `k` of `b` is `a`'s `order[k]`).
fn same_in_order(a: &Mesh, b: &Mesh, order: &[usize], fixed: bool, what: &str) {
    assert_eq!(a.node_count(), b.node_count(), "{what}: node count");
    assert_eq!(a.element_count(), b.element_count(), "{what}: element count");
    assert_eq!(order.len(), b.element_count(), "{what}: element count");
    for (k, &e) in order.iter().enumerate() {
        assert_eq!(a.kind(e), b.kind(k), "{what}: kind of element {e}");
    }
    if what != "Triangle" && (a.plane.is_some() || b.plane.is_some()) {
        // written in its own 3D plane and read back (Triangle writes 2D coordinates): the plane is fitted again, so the
        // 2D coordinates may differ by a rigid motion; the 3D points agree to rounding
        let scale = a.nodes().iter().map(|&p| a.to_3d(p).abs().max_element()).fold(f64::MIN_POSITIVE, f64::max);
        for (i, (p, q)) in a.nodes().iter().zip(b.nodes()).enumerate() {
            let (p3, q3) = (a.to_3d(*p), b.to_3d(*q));
            assert!((p3 - q3).abs().max_element() <= 1e-9 * scale, "{what}: node {i} was at {p3:?}, read back at {q3:?}");
        }
    } else {
        for (i, (p, q)) in a.nodes().iter().zip(b.nodes()).enumerate() {
            assert!(
                p.x.to_bits() == q.x.to_bits() && p.y.to_bits() == q.y.to_bits(),
                "{what}: node {i} was {p:?}, read back as {q:?}"
            );
        }
    }
    for (k, &e) in order.iter().enumerate() {
        assert_eq!(a.element(e), b.element(k), "{what}: nodes of element {e}");
    }
    if fixed {
        assert_eq!(a.fixed(), b.fixed(), "{what}: fixed flags");
    }
}
