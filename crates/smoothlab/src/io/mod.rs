//! Mesh file formats: Gmsh `.msh` (2.2 and 4.1 ASCII), legacy VTK ASCII
//! `UNSTRUCTURED_GRID`, Triangle `.node`/`.ele`, OBJ, OFF and Medit `.mesh` (ASCII).
//!
//! Readers parse text into a [`MeshBuilder`], recording the
//! file line of every node and element, so every error names a line or an element.
//! Nothing here panics on any input, and no header count is trusted for an allocation
//! before it is checked against the bytes left to read.
//!
//! What a written file gives back when read (nodes always bit for bit, printed in the
//! shortest form that round-trips; elements, their order and kinds always):
//!
//! | format | element kinds | fixed flags |
//! |---|---|---|
//! | `.msh` 2.2 / 4.1 | all five | exactly (a `$NodeData` view named `fixed`) |
//! | `.vtk` | all five | exactly (`POINT_DATA` `SCALARS fixed`) |
//! | `.node`/`.ele` | all `Tri3` or all `Tri6` | boundary ∪ fixed (markers) |
//! | `.obj`, `.off` | `Tri3`, `Quad4` | none: the boundary |
//! | `.mesh` | `Tri3`, `Quad4` (grouped by kind) | boundary ∪ fixed (`RequiredVertices`) |
//!
//! Volume meshes ([`crate::volume`]) — tetrahedra, hexahedra, wedges, pyramids, mixed, and
//! 10-, 20- and 27-node kinds alone — are read from `.msh` (types 4, 5, 6, 7, 11, 17, 12)
//! and `.vtk` (cell types 10, 12, 13, 14, 24, 25, 29), tetrahedra also from TetGen's
//! `.node`/`.ele` pair (dimension 3, 4 or 10 nodes), and written to the same formats
//! ([`write_model_string`], [`write_model_path`]; TetGen refuses the other kinds) with the
//! fixed flags kept as for planar meshes and the elements in their order (4.1: a block per
//! run of one kind); OBJ and OFF hold surfaces only. Medit's `.mesh` holds the linear kinds
//! in VTK's node orders, read and written a section per kind.
//!
//! Files from elsewhere: `.msh` without that view gets the boundary plus the nodes of line
//! and point elements; VTK without `fixed` the boundary plus the points of vertex and line
//! cells; Triangle the boundary plus nonzero-marker nodes; OBJ and OFF the boundary.

use crate::error::{Error, Result};
use crate::mesh::{Mesh, MeshBuilder};
use crate::model::Model;

mod arrays;
pub use arrays::{mesh_arrays, model_from_arrays, volume_arrays, CellBlock, MeshArrays};
mod lex;
mod medit;
mod msh;
mod objoff;
mod out;
use out::Out;
mod triangle;
pub use triangle::flat_note;
mod volume;
mod vtk;

/// The size limit of mesh files, for reading and writing alike: files larger than this
/// are refused before they are read (by [`read_path`] and [`read_bytes`]), and the
/// writers refuse to produce one (so what smoothlab writes, it reads back). 1 GiB: some
/// seven million nodes in `.msh`, the most verbose format (a 2.5-million-node mesh is
/// about 340 MB there).
pub const MAX_FILE_BYTES: u64 = 1 << 30;

/// The page's own limit on the files it reads (the page checks it before reading, holding
/// the file and the mesh in the browser's memory; its control sheet hands it over). Every file of a mesh the page
/// holds (at most the page crate's `MAX_NODES` nodes) is smaller, so what the page exports,
/// it reads back.
pub const PAGE_MAX_FILE_BYTES: u64 = 256 << 20;

enum_with_all! {
    /// A mesh file format, chosen from a file name's extension.
    #[derive(Clone, Copy, Debug, PartialEq, Eq)]
    pub enum Format {
        Msh,
        Vtk,
        /// Triangle's `.node` + `.ele` pair.
        Triangle,
        Obj,
        Off,
        /// Medit's `.mesh` (ASCII): MMG, CGAL, geogram, HexaLab.
        Medit,
    }
}

enum_with_names! {
    /// Which `.msh` version to write.
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
    pub enum MshVersion {
        /// 2.2 ASCII: what most other tools read (the default).
        #[default]
        V22 => ("2.2", "ASCII 2.2, what most other tools read"),
        /// 4.1 ASCII.
        V41 => ("4.1", "ASCII 4.1"),
    }
}

/// Options for writing.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct WriteOptions {
    pub msh_version: MshVersion,
}

impl Format {
    /// Its file extensions, lowercase and without the dot (Triangle's pair has two).
    pub fn extensions(self) -> &'static [&'static str] {
        match self {
            Format::Msh => &["msh"],
            Format::Vtk => &["vtk"],
            Format::Triangle => &["node", "ele"],
            Format::Obj => &["obj"],
            Format::Off => &["off"],
            Format::Medit => &["mesh"],
        }
    }

    /// The format of a file name by its extension (`.node` and `.ele` both mean Triangle).
    pub fn from_name(name: &str) -> Option<Format> {
        let ext = name.rsplit_once('.')?.1.to_ascii_lowercase();
        Format::ALL.into_iter().find(|f| f.extensions().contains(&ext.as_str()))
    }
}

/// Every format's extensions in words: `.msh, .vtk, .node/.ele, .obj, .off or .mesh`.
pub fn extensions_in_words() -> String {
    let each: Vec<String> = Format::ALL
        .iter()
        .map(|f| f.extensions().iter().map(|e| format!(".{e}")).collect::<Vec<_>>().join("/"))
        .collect();
    match each.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
        _ => each.concat(),
    }
}

/// Error for a name whose extension is not a mesh format.
pub fn unknown_format(name: &str) -> Error {
    Error::invalid(format!("cannot tell the mesh format of '{name}': use {}", extensions_in_words()))
}

/// Reads a mesh from text in the given format. A Triangle mesh is a `.node`/`.ele`
/// pair and needs [`read_triangle`].
/// A leading UTF-8 byte-order mark (as some Windows editors write) is skipped.
pub fn read_str(text: &str, format: Format) -> Result<Mesh> {
    parse_str(text, format)?.build()
}

/// What [`read_str`] reads, before the mesh is built: the builder holds the nodes and
/// elements with their lines, so the text can be let go before the topology is built (a
/// 1M-node file is 130 MB of text).
fn parse_str(text: &str, format: Format) -> Result<MeshBuilder> {
    let text = without_bom(text);
    match format {
        Format::Msh => msh::parse(text),
        Format::Vtk => vtk::parse(text),
        Format::Obj => objoff::parse_obj(text),
        Format::Off => objoff::parse_off(text),
        Format::Medit => medit::parse(text),
        Format::Triangle => {
            Err(Error::invalid("a Triangle mesh is a .node/.ele pair: read both files together (read_triangle)"))
        }
    }
}

/// Reads a mesh from the bytes of a file called `name` (the format follows its
/// extension). The bytes must be UTF-8 text; the error for anything else names the
/// byte offset and line (or, for a binary `.msh`/`.vtk`, says that binary is unsupported).
pub fn read_bytes(bytes: &[u8], name: &str) -> Result<Mesh> {
    let format = Format::from_name(name).ok_or_else(|| unknown_format(name))?;
    check_size(bytes.len() as u64, name)?;
    read_str(utf8(bytes, format)?, format)
}

/// Reads what a text holds: a planar mesh ([`read_str`]'s), or a surface in 3D when its
/// points are not in a plane ([`Model::build`]).
///
/// ```
/// use smoothlab::io::{read_model_str, write_model_string, Format, WriteOptions};
/// use smoothlab::Model;
///
/// // a triangle in the plane z = 1 is a planar mesh, written back in its own plane
/// let obj = "v 0 0 1\nv 1 0 1\nv 0 1 1\nf 1 2 3\n";
/// let model = read_model_str(obj, Format::Obj)?;
/// assert!(matches!(model, Model::Planar(_)));
/// let text = write_model_string(&model, Format::Obj, &WriteOptions::default())?;
/// assert!(text.contains("v 0.0 0.0 1.0"));
/// # Ok::<(), smoothlab::Error>(())
/// ```
pub fn read_model_str(text: &str, format: Format) -> Result<Model> {
    Model::build(parse_str(text, format)?)
}

/// [`read_bytes`] for a planar mesh or a surface (see [`read_model_str`]).
pub fn read_model_bytes(bytes: &[u8], name: &str) -> Result<Model> {
    let format = Format::from_name(name).ok_or_else(|| unknown_format(name))?;
    check_size(bytes.len() as u64, name)?;
    if format == Format::Triangle {
        return Err(Error::invalid("a Triangle mesh is a .node/.ele pair: read both files together (read_triangle)"));
    }
    read_model_str(utf8(bytes, format)?, format)
}

/// Reads a Triangle mesh from the texts of its `.node` and `.ele` files.
/// A leading byte-order mark in either is skipped.
pub fn read_triangle(node: &str, ele: &str) -> Result<Mesh> {
    triangle::read(without_bom(node), without_bom(ele))
}

/// Reads what a `.node`/`.ele` pair holds: a Triangle mesh, or TetGen's tetrahedra
/// (dimension 3 in `.node`) as a tetrahedral model.
pub fn read_model_pair(node: &str, ele: &str) -> Result<Model> {
    triangle::read_model(without_bom(node), without_bom(ele))
}

/// The text without a leading UTF-8 byte-order mark (U+FEFF), which is not part of the
/// content: left in, it glued itself to the first token (an OBJ's first `v` line was
/// not a `v` line any more; `$MeshFormat` was not recognised).
fn without_bom(text: &str) -> &str {
    text.strip_prefix('\u{feff}').unwrap_or(text)
}

/// What the writers write: a planar mesh (its 2D positions, in its own plane) or a
/// surface (its 3D positions), with the elements and fixed flags of `mesh`.
#[derive(Clone, Copy, Debug)]
pub struct Writable<'a> {
    pub mesh: &'a Mesh,
    /// A surface's node positions; `None` for a planar mesh.
    points: Option<&'a [glam::DVec3]>,
}

impl<'a> From<&'a Mesh> for Writable<'a> {
    fn from(mesh: &'a Mesh) -> Self {
        Writable { mesh, points: None }
    }
}

impl<'a> From<&'a crate::surface::Surface> for Writable<'a> {
    fn from(s: &'a crate::surface::Surface) -> Self {
        Writable { mesh: s.flat(), points: Some(s.points()) }
    }
}

impl Writable<'_> {
    /// Node `i` in 3D: a surface's point, a planar mesh's in its plane ([`Mesh::node_3d`]:
    /// as the file gave it while it has not moved).
    pub(crate) fn xyz(&self, i: usize) -> glam::DVec3 {
        match self.points {
            Some(p) => p[i],
            None => self.mesh.node_3d(i),
        }
    }
    /// Element `e`'s nodes as the writers write them: in the order its file gave them
    /// ([`Mesh::element_as_given`]).
    pub(crate) fn element(&self, e: usize) -> crate::mesh::GivenNodes {
        self.mesh.element_as_given(e)
    }
    /// Whether every node is at z = 0 (a 2D mesh): the writers write `x y 0`.
    pub(crate) fn in_xy_plane(&self) -> bool {
        self.points.is_none() && self.mesh.plane.is_none()
    }
    /// Writes node `i` as the 3D formats do, `x y z` (Rust's shortest exact decimals):
    /// `x y 0` for a 2D mesh, else the point in 3D, so a mesh read from 3D is written
    /// back where it was.
    pub(crate) fn write_xyz(&self, s: &mut Out, i: usize) {
        use std::fmt::Write;
        // writing to an `Out` cannot fail
        let _ = if self.in_xy_plane() {
            let p = self.mesh.nodes()[i];
            write!(s, "{:?} {:?} 0", p.x, p.y)
        } else {
            let q = self.xyz(i);
            write!(s, "{:?} {:?} {:?}", q.x, q.y, q.z)
        };
    }
}

fn check_size(len: u64, name: &str) -> Result<()> {
    if len > MAX_FILE_BYTES {
        return Err(Error::TooLarge(format!(
            "{name} is {len} bytes, over the limit of {MAX_FILE_BYTES} bytes (1 GiB) for mesh files"
        )));
    }
    Ok(())
}

/// Refuses to write a text of `len` bytes that would be refused when read back (see
/// [`MAX_FILE_BYTES`]).
fn check_written(len: u64, ext: &str) -> Result<()> {
    if len > MAX_FILE_BYTES {
        return Err(Error::TooLarge(format!(
            "the mesh as {ext} would be {len} bytes, over the limit of {MAX_FILE_BYTES} bytes (1 GiB) \
             smoothlab reads back; a more compact format (.vtk) may fit"
        )));
    }
    Ok(())
}

/// The bytes as text, or an error naming where they stop being UTF-8.
fn utf8(bytes: &[u8], format: Format) -> Result<&str> {
    match std::str::from_utf8(bytes) {
        Ok(s) => Ok(s),
        Err(e) => {
            let at = e.valid_up_to();
            // A binary .msh or .vtk has a text header: let the reader say "binary".
            if matches!(format, Format::Msh | Format::Vtk) {
                // The prefix up to `at` is valid UTF-8 by definition.
                let head = std::str::from_utf8(&bytes[..at]).unwrap_or("");
                if let Err(err @ Error::Unsupported { .. }) = read_str(head, format) {
                    return Err(err);
                }
            }
            let line = lex::line_of_byte(bytes, at);
            Err(Error::parse(
                line,
                format!("the file is not UTF-8 text: byte {at} (0x{:02x}) is not valid UTF-8", bytes[at]),
            ))
        }
    }
}

/// Reads a mesh file; `x.node` or `x.ele` reads both of the pair. Only regular files
/// are read (a device such as `/dev/zero`, a named pipe or a directory is refused, also
/// behind a symbolic link); files over [`MAX_FILE_BYTES`] are refused before reading, and
/// the read itself stops after that many bytes whatever the file's metadata says.
#[cfg(not(target_arch = "wasm32"))]
pub fn read_path(path: &std::path::Path) -> Result<Mesh> {
    read_path_as(path, MeshBuilder::build)
}

/// [`read_path`] for a planar mesh or a surface (see [`read_model_str`]); a Triangle pair
/// is planar.
#[cfg(not(target_arch = "wasm32"))]
pub fn read_model_path(path: &std::path::Path) -> Result<Model> {
    read_path_as(path, Model::build)
}

#[cfg(not(target_arch = "wasm32"))]
fn read_path_as<T>(path: &std::path::Path, build: fn(MeshBuilder) -> Result<T>) -> Result<T> {
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let format = Format::from_name(&name).ok_or_else(|| unknown_format(&path.display().to_string()))?;
    if format == Format::Triangle {
        let (node, ele) = triangle_pair(path, &name)?;
        let (nb, eb) = (read_file(&node)?, read_file(&ele)?);
        let b = triangle::parse(without_bom(utf8(&nb, format)?), without_bom(utf8(&eb, format)?))?;
        return build(b);
    }
    // the file's bytes are dropped before the mesh is built
    let builder = {
        let bytes = read_file(path)?;
        parse_str(utf8(&bytes, format)?, format)?
    };
    build(builder)
}

/// The `.node` and `.ele` paths of a Triangle pair named by either. A name that is only
/// the extension (`.node`) has no stem to pair: it is refused rather than taken as the
/// stem `.node` (which made `.node.node` and `.node.ele`).
#[cfg(not(target_arch = "wasm32"))]
fn triangle_pair(path: &std::path::Path, name: &str) -> Result<(std::path::PathBuf, std::path::PathBuf)> {
    let stem = name.rsplit_once('.').map_or("", |(stem, _)| stem);
    if stem.is_empty() {
        return Err(Error::invalid(format!(
            "'{}': a Triangle pair needs a name before the extension, such as mesh.node and mesh.ele",
            path.display()
        )));
    }
    let base = path.with_file_name(stem);
    let with = |ext: &str| {
        let mut p = base.clone().into_os_string();
        p.push(".");
        p.push(ext);
        std::path::PathBuf::from(p)
    };
    Ok((with("node"), with("ele")))
}

/// The bytes of a regular file of at most [`MAX_FILE_BYTES`] bytes.
#[cfg(not(target_arch = "wasm32"))]
fn read_file(p: &std::path::Path) -> Result<Vec<u8>> {
    use std::io::Read;
    let fail = |e: std::io::Error| Error::Io(format!("cannot read {}: {e}", p.display()));
    let regular = |meta: &std::fs::Metadata| -> Result<()> {
        if meta.is_file() {
            return Ok(());
        }
        let what = if meta.is_dir() { "a directory" } else { "a device, pipe or socket" };
        Err(Error::Io(format!("cannot read {}: it is {what}, not a regular file", p.display())))
    };
    // Checked before opening, since opening a named pipe waits for a writer, and again
    // on the opened file, which is the one read.
    regular(&std::fs::metadata(p).map_err(fail)?)?;
    let file = std::fs::File::open(p).map_err(fail)?;
    let meta = file.metadata().map_err(fail)?;
    regular(&meta)?;
    check_size(meta.len(), &p.display().to_string())?;
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    // One byte past the limit tells a file that grew while it was read.
    file.take(MAX_FILE_BYTES + 1).read_to_end(&mut bytes).map_err(fail)?;
    check_size(bytes.len() as u64, &p.display().to_string())?;
    Ok(bytes)
}

/// Writes a mesh as text. OBJ and OFF hold linear meshes only; Triangle output is a
/// pair of files (see [`write_triangle`]). What round-trips is documented per format:
/// nodes (to the last bit), elements and kinds always; fixed flags in `.msh` and `.vtk`.
pub fn write_string<'a>(mesh: impl Into<Writable<'a>>, format: Format, opts: &WriteOptions) -> Result<String> {
    let mesh = mesh.into();
    let mut out = Out::string(64 * mesh.mesh.node_count() + 48 * mesh.mesh.element_count() + 256);
    write_to(mesh, format, opts, &mut out)?;
    Ok(out.into_string())
}

/// Writes a mesh in `format` (not Triangle's pair) into `out`, refusing a text over
/// [`MAX_FILE_BYTES`] when it is done.
fn write_to(mesh: Writable, format: Format, opts: &WriteOptions, out: &mut Out) -> Result<()> {
    let ext = match format {
        Format::Msh => {
            msh::write(&mesh, opts.msh_version, out);
            ".msh"
        }
        Format::Vtk => {
            vtk::write(mesh, out);
            ".vtk"
        }
        Format::Obj => {
            objoff::write_obj(mesh, out)?;
            ".obj"
        }
        Format::Off => {
            objoff::write_off(mesh, out)?;
            ".off"
        }
        Format::Medit => {
            medit::write(mesh, out)?;
            ".mesh"
        }
        Format::Triangle => {
            return Err(Error::invalid(
                "Triangle output is a .node/.ele pair: use write_triangle, or write_path with a .node or .ele name",
            ))
        }
    };
    check_written(out.len(), ext)
}

/// Writes a triangle mesh (all 3-node or all 6-node triangles) as the texts of a
/// Triangle `.node` and `.ele` file; fixed nodes get boundary marker 1.
pub fn write_triangle<'a>(mesh: impl Into<Writable<'a>>) -> Result<(String, String)> {
    let mesh = mesh.into();
    let (mut node, mut ele) =
        (Out::string(48 * mesh.mesh.node_count() + 64), Out::string(40 * mesh.mesh.element_count() + 64));
    triangle::write(mesh, &mut node, &mut ele)?;
    check_written(node.len(), ".node")?;
    check_written(ele.len(), ".ele")?;
    Ok((node.into_string(), ele.into_string()))
}

/// Bytes per node and per element that no format's line exceeds: an index of at most 10
/// digits, three coordinates of at most 25 characters each (Rust's shortest exact
/// form), up to nine node numbers of at most 11 characters with their spaces.
#[cfg(not(target_arch = "wasm32"))]
const LINE_BOUND: u64 = 256;

/// Reads the mesh file at `path`, whatever it holds: a planar mesh, a surface in 3D or a
/// volume mesh (the format by the extension, as [`read_model_path`]).
#[cfg(not(target_arch = "wasm32"))]
pub fn read(path: impl AsRef<std::path::Path>) -> Result<Model> {
    read_model_path(path.as_ref())
}

/// Writes `model` to `path` in the format of its extension, with the default options:
/// what `smoothlab smooth IN -o OUT` writes (as [`write_model_path`]).
#[cfg(not(target_arch = "wasm32"))]
pub fn write(model: &Model, path: impl AsRef<std::path::Path>) -> Result<()> {
    write_model_path(model, path.as_ref(), &WriteOptions::default())
}

/// Writes a mesh file in the format of the path's extension (`.node`/`.ele`: both files).
/// The text goes to the file in chunks, never whole in memory. A mesh whose text could
/// pass [`MAX_FILE_BYTES`] (by `LINE_BOUND`) is measured first, so that a text too large
/// is refused before anything is written, as it always was.
#[cfg(not(target_arch = "wasm32"))]
pub fn write_path<'a>(mesh: impl Into<Writable<'a>>, path: &std::path::Path, opts: &WriteOptions) -> Result<()> {
    let mesh = mesh.into();
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let format = Format::from_name(&name).ok_or_else(|| unknown_format(&path.display().to_string()))?;
    let bound = LINE_BOUND * (mesh.mesh.node_count() as u64 + mesh.mesh.element_count() as u64) + 4096;
    let cannot = |p: &std::path::Path, e: std::io::Error| Error::Io(format!("cannot write {}: {e}", p.display()));
    if format == Format::Triangle {
        let (node_path, ele_path) = triangle_pair(path, &name)?;
        triangle::writable(mesh)?;
        if bound > MAX_FILE_BYTES {
            let (mut node, mut ele) = (Out::counter(), Out::counter());
            triangle::write(mesh, &mut node, &mut ele)?;
            check_written(node.len(), ".node")?;
            check_written(ele.len(), ".ele")?;
        }
        let mut nf = std::fs::File::create(&node_path).map_err(|e| cannot(&node_path, e))?;
        let mut ef = std::fs::File::create(&ele_path).map_err(|e| cannot(&ele_path, e))?;
        let (mut node, mut ele) = (Out::file(&mut nf), Out::file(&mut ef));
        triangle::write(mesh, &mut node, &mut ele)?;
        node.finish().map_err(|e| cannot(&node_path, e))?;
        return ele.finish().map_err(|e| cannot(&ele_path, e));
    }
    match format {
        Format::Obj => objoff::linear_only(mesh.mesh, "OBJ")?,
        Format::Off => objoff::linear_only(mesh.mesh, "OFF")?,
        Format::Medit => objoff::linear_only(mesh.mesh, "Medit")?,
        _ => {}
    }
    if bound > MAX_FILE_BYTES {
        write_to(mesh, format, opts, &mut Out::counter())?;
    }
    let mut file = std::fs::File::create(path).map_err(|e| cannot(path, e))?;
    let mut out = Out::file(&mut file);
    write_to(mesh, format, opts, &mut out)?;
    out.finish().map_err(|e| cannot(path, e))
}

/// Writes what a model holds as text in `format`: a planar mesh or a surface as
/// [`write_string`] does, a volume mesh as `.msh`, `.vtk` or `.mesh` (linear kinds;
/// TetGen's pair: see [`write_model_path`]; OBJ and OFF hold no volumes).
pub fn write_model_string(model: &Model, format: Format, opts: &WriteOptions) -> Result<String> {
    match model {
        Model::Planar(m) => write_string(m, format, opts),
        Model::Surface(sf) => write_string(sf, format, opts),
        Model::Volume(v) => {
            let mut out = Out::string(80 * v.node_count() + 48 * v.element_count() + 256);
            let ext = match format {
                Format::Msh => {
                    msh::write(v, opts.msh_version, &mut out);
                    ".msh"
                }
                Format::Vtk => {
                    volume::write_vtk(v, &mut out);
                    ".vtk"
                }
                Format::Medit => {
                    medit::write_volume(v, &mut out)?;
                    ".mesh"
                }
                other => return Err(volume_refused(other)),
            };
            check_written(out.len(), ext)?;
            Ok(out.into_string())
        }
    }
}

/// Writes a tetrahedral mesh as the texts of a TetGen `.node` (1-based, dimension 3,
/// marker 1 on fixed nodes) and `.ele` file.
pub fn write_tetgen(mesh: &crate::volume::VolumeMesh) -> Result<(String, String)> {
    if !mesh.is_tets() {
        return Err(Error::invalid(format!(
            "TetGen's .ele holds tetrahedra, and this mesh has {}: write .msh or .vtk",
            mesh.family_words()
        )));
    }
    let (mut node, mut ele) = (Out::string(80 * mesh.node_count() + 64), Out::string(48 * mesh.element_count() + 64));
    volume::write_tetgen(mesh, &mut node, &mut ele);
    check_written(node.len(), ".node")?;
    check_written(ele.len(), ".ele")?;
    Ok((node.into_string(), ele.into_string()))
}

/// Why `format` cannot hold a volume mesh (as text).
fn volume_refused(format: Format) -> Error {
    Error::invalid(match format {
        Format::Triangle => "TetGen's output is a .node/.ele pair: write it to a path ending in .node or .ele".into(),
        f => format!(
            "{f:?} files hold surfaces, not volume elements: write a volume mesh as .msh, .vtk or .mesh (tetrahedra \
             also as a TetGen .node/.ele pair)"
        ),
    })
}

/// Writes what a model holds to a file in the format of the path's extension: a planar
/// mesh or a surface as [`write_path`] does; a volume mesh as `.msh`, `.vtk` or `.mesh`,
/// tetrahedra also as a TetGen `.node`/`.ele` pair.
#[cfg(not(target_arch = "wasm32"))]
pub fn write_model_path(model: &Model, path: &std::path::Path, opts: &WriteOptions) -> Result<()> {
    let v = match model {
        Model::Planar(m) => return write_path(m, path, opts),
        Model::Surface(sf) => return write_path(sf, path, opts),
        Model::Volume(v) => v,
    };
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let format = Format::from_name(&name).ok_or_else(|| unknown_format(&path.display().to_string()))?;
    let cannot = |p: &std::path::Path, e: std::io::Error| Error::Io(format!("cannot write {}: {e}", p.display()));
    if format == Format::Triangle {
        let (node_path, ele_path) = triangle_pair(path, &name)?;
        let (node, ele) = write_tetgen(v)?;
        std::fs::write(&node_path, node).map_err(|e| cannot(&node_path, e))?;
        return std::fs::write(&ele_path, ele).map_err(|e| cannot(&ele_path, e));
    }
    let text = write_model_string(model, format, opts)?;
    std::fs::write(path, text).map_err(|e| cannot(path, e))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_format_is_found_by_each_of_its_extensions_and_named_in_the_message() {
        for f in Format::ALL {
            for e in f.extensions() {
                assert_eq!(Format::from_name(&format!("mesh.{e}")), Some(f));
                assert_eq!(Format::from_name(&format!("MESH.{}", e.to_uppercase())), Some(f));
            }
        }
        assert_eq!(Format::from_name("mesh.txt"), None);
        assert_eq!(Format::from_name("msh"), None, "no extension");
        assert_eq!(extensions_in_words(), ".msh, .vtk, .node/.ele, .obj, .off or .mesh");
        assert_eq!(
            unknown_format("a.stl").to_string(),
            "cannot tell the mesh format of 'a.stl': use .msh, .vtk, .node/.ele, .obj, .off or .mesh"
        );
    }
}
