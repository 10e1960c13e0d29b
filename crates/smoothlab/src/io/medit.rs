//! Medit `.mesh`, ASCII: the format of MMG, CGAL, geogram and HexaLab's data sets (the
//! keywords of INRIA's libMeshb; Frey, "MEDIT: an interactive mesh visualization
//! software", INRIA RT-0253, 2001).
//!
//! A file is a list of keywords, each followed by its data. Tokens are separated by any
//! whitespace, so a count may sit on its keyword's line or the next. Keywords are read in
//! any case. A `#` token where a keyword is due starts a comment, to the end of its line.
//!
//! Read: `MeshVersionFormatted` 1 to 4 (first); `Dimension` 2 or 3 (before `Vertices`);
//! `Vertices` (the coordinates and a reference each); `Triangles`, `Quadrilaterals`,
//! `Tetrahedra`, `Hexahedra`, `Prisms`, `Pyramids` and `Edges` (1-based vertex indices
//! and a reference each); `Corners` and `RequiredVertices` (a vertex index each); `End`,
//! which ends the file. Each section appears once. The sections of other entities' flags
//! and of normals and tangents are skipped by their counts ([`SECTIONS`]); the quadratic
//! kinds (`TrianglesP2`, …) and any unknown section are refused, naming the line.
//!
//! Node orders are VTK's, so elements are kept as given:
//! - a tetrahedron is right-handed, `det(p2 − p1, p3 − p1, p4 − p1) > 0`, as MMG turns them;
//! - a hexahedron has the face 1 2 3 4, then 5 6 7 8 above it, 5 over 1 (checked on
//!   HexaLab's meshes: none turned over, none inverted);
//! - a prism has the triangle 1 2 3, then 4 5 6 above it: MMG's prism faces
//!   (`MMG5_idir_pr`) are VTK's wedge faces, outward;
//! - a pyramid has the base 1 2 3 4, then the apex, as in VTK and Gmsh.
//!
//! A mesh given the other way round is turned over whole when built, as from any format.
//! A volume file's triangles and quads are its given faces, as in `.msh` and `.vtk`.
//!
//! References are labels (MMG's boundary and region numbers; HexaLab writes −1 on every
//! vertex), as Gmsh's physical tags are to the `.msh` reader: they fix no node. Fixed
//! nodes are the boundary plus the vertices of `Edges`, `Corners` and `RequiredVertices`,
//! which MMG keeps in place, as the `.msh` reader adds the nodes of line and point elements.
//!
//! Written: `MeshVersionFormatted 2`, `Dimension 2` for a mesh in the xy plane (else 3),
//! the vertices at full `f64` precision, the elements a section per kind, the fixed nodes
//! as `RequiredVertices`, and `End`; every reference is 0. Reading back gives the same
//! nodes to the bit and fixed = boundary ∪ fixed. Medit has a section per kind, so a mesh
//! of mixed kinds comes back grouped by kind, in its order within each kind.

use std::fmt::Write as _;

use crate::error::{Error, Numbering, Result};
use crate::io::lex::{repeated, shown, Lexer, Token};
use crate::io::out::Out;
use crate::mesh::{ElementKind, FixedSpec, MeshBuilder, VolumeKind};
use crate::volume::VolumeMesh;

/// What a section holds.
#[derive(Clone, Copy, Debug)]
enum Section {
    Vertices,
    /// Triangles or quads, named in the singular in messages.
    Faces(ElementKind, &'static str),
    /// Volume elements, named in the singular in messages.
    Solids(VolumeKind, &'static str),
    /// Two vertices and a reference each: their vertices are fixed.
    Edges,
    /// A vertex index each: those vertices are fixed.
    Marks,
    /// Items of so many tokens, skipped.
    Skip(u64),
    /// Vectors of the file's dimension, skipped.
    Vectors,
    /// A quadratic kind, in plain words.
    Quadratic(&'static str),
    End,
}

/// Every section read, by its keyword.
const SECTIONS: &[(&str, Section)] = {
    use Section::*;
    &[
        ("Vertices", Vertices),
        ("Triangles", Faces(ElementKind::Tri3, "triangle")),
        ("Quadrilaterals", Faces(ElementKind::Quad4, "quadrilateral")),
        ("Tetrahedra", Solids(VolumeKind::Tet4, "tetrahedron")),
        ("Hexahedra", Solids(VolumeKind::Hex8, "hexahedron")),
        ("Prisms", Solids(VolumeKind::Wedge6, "prism")),
        ("Pyramids", Solids(VolumeKind::Pyramid5, "pyramid")),
        ("Edges", Edges),
        ("Corners", Marks),
        ("RequiredVertices", Marks),
        ("Ridges", Skip(1)),
        ("RequiredEdges", Skip(1)),
        ("RequiredTriangles", Skip(1)),
        ("RequiredQuadrilaterals", Skip(1)),
        ("RequiredTetrahedra", Skip(1)),
        ("RequiredHexahedra", Skip(1)),
        ("Normals", Vectors),
        ("Tangents", Vectors),
        ("NormalAtVertices", Skip(2)),
        ("TangentAtVertices", Skip(2)),
        ("NormalAtTriangleVertices", Skip(3)),
        ("NormalAtQuadrilateralVertices", Skip(3)),
        ("TangentAtEdges", Skip(3)),
        ("EdgesP2", Quadratic("quadratic edges")),
        ("TrianglesP2", Quadratic("quadratic triangles")),
        ("QuadrilateralsQ2", Quadratic("quadratic quadrilaterals")),
        ("TetrahedraP2", Quadratic("quadratic tetrahedra")),
        ("HexahedraQ2", Quadratic("quadratic hexahedra")),
        ("End", End),
    ]
};

/// What the reader reads, for its messages.
const READS: &str = "Vertices, Triangles, Quadrilaterals, Tetrahedra, Hexahedra, Prisms, Pyramids, Edges, \
                     Corners and RequiredVertices";

struct Reader<'a> {
    lex: Lexer<'a>,
    b: MeshBuilder,
    /// The file's dimension (0 until `Dimension`).
    dim: usize,
    /// The sections seen, with their lines.
    seen: Vec<(&'static str, usize)>,
    /// Whether `Vertices` was read: then indices are checked as they come.
    vertices_read: bool,
    /// 0-based indices of the vertices to fix.
    marked: Vec<u32>,
    /// The highest index read before `Vertices`, its line and what held it: checked at
    /// the end.
    pending: Option<(u64, usize, String)>,
}

/// Reads a Medit file into a builder (see [`super::parse_str`]).
pub(crate) fn parse(text: &str) -> Result<MeshBuilder> {
    let mut r = Reader {
        lex: Lexer::new(text),
        b: MeshBuilder::new(),
        dim: 0,
        seen: Vec::new(),
        vertices_read: false,
        marked: Vec::new(),
        pending: None,
    };
    r.header()?;
    r.sections()?;
    r.finish()
}

impl<'a> Reader<'a> {
    /// The next token where a keyword is due, past `#` comments.
    fn keyword(&mut self) -> Option<Token<'a>> {
        loop {
            let t = self.lex.next()?;
            if !t.text.starts_with('#') {
                return Some(t);
            }
            self.lex.skip_rest_of_line();
        }
    }

    fn header(&mut self) -> Result<()> {
        let Some(t) = self.keyword() else {
            return Err(Error::Empty("the Medit file is empty".into()));
        };
        if !t.text.eq_ignore_ascii_case("MeshVersionFormatted") {
            return Err(Error::parse(
                t.line,
                format!("not a Medit file: expected 'MeshVersionFormatted' first, found {}", shown(t.text)),
            ));
        }
        self.seen.push(("MeshVersionFormatted", t.line));
        let (v, vl) = self.lex.u64(|| "the version after MeshVersionFormatted (1 or 2)".into())?;
        if !(1..=4).contains(&v) {
            return Err(Error::parse(vl, format!("MeshVersionFormatted {v} is not a version of the format (1 to 4)")));
        }
        Ok(())
    }

    /// Refuses a second section of one name.
    fn once(&mut self, name: &'static str, line: usize) -> Result<()> {
        if let Some(&(_, first)) = self.seen.iter().find(|(n, _)| *n == name) {
            return Err(Error::parse(line, format!("a second {name} section (the first is at line {first})")));
        }
        self.seen.push((name, line));
        Ok(())
    }

    fn sections(&mut self) -> Result<()> {
        while let Some(t) = self.keyword() {
            if t.text.eq_ignore_ascii_case("MeshVersionFormatted") {
                self.once("MeshVersionFormatted", t.line)?;
            }
            if t.text.eq_ignore_ascii_case("Dimension") {
                self.once("Dimension", t.line)?;
                let (d, dl) = self.lex.u64(|| "the dimension after Dimension (2 or 3)".into())?;
                if !(2..=3).contains(&d) {
                    return Err(Error::parse(dl, format!("Dimension {d}: smoothlab reads dimension 2 or 3")));
                }
                self.dim = d as usize;
                continue;
            }
            let Some(&(name, section)) = SECTIONS.iter().find(|(k, _)| t.text.eq_ignore_ascii_case(k)) else {
                if t.text.starts_with(|c: char| c.is_ascii_alphabetic()) {
                    return Err(Error::unsupported(
                        Some(t.line),
                        format!(
                            "Medit section {} is not known to smoothlab, so its data cannot be skipped; it reads {READS}",
                            shown(t.text)
                        ),
                    ));
                }
                return Err(Error::parse(
                    t.line,
                    format!("expected a section keyword, found {}: a count and its data disagree?", shown(t.text)),
                ));
            };
            self.once(name, t.line)?;
            match section {
                Section::End => return Ok(()),
                Section::Vertices => self.vertices(t.line)?,
                Section::Faces(kind, one) => self.elements(name, one, kind.node_count(), t.line, |b, ids, l, e| {
                    b.add_element_numbered(kind, ids, l, e);
                    Ok(())
                })?,
                Section::Solids(kind, one) => {
                    if self.dim == 2 {
                        return Err(Error::parse(t.line, format!("{name} in a file of Dimension 2: they need Dimension 3")));
                    }
                    self.elements(name, one, kind.nodes(), t.line, |b, ids, l, e| {
                        b.add_volume_element_numbered(kind, ids, l, e)
                    })?
                }
                Section::Edges => {
                    let mut marked = std::mem::take(&mut self.marked);
                    self.elements(name, "edge", 2, t.line, |_, ids, _, _| {
                        marked.extend_from_slice(ids);
                        Ok(())
                    })?;
                    self.marked = marked;
                }
                Section::Marks => self.marks(name)?,
                Section::Skip(per) => self.skip(name, per, t.line)?,
                Section::Vectors => {
                    let dim = self.dimension(name, t.line)?;
                    self.skip(name, dim as u64, t.line)?
                }
                Section::Quadratic(words) => {
                    return Err(Error::unsupported_kind(
                        format!("{words} (Medit's {name}) are not supported yet"),
                        t.line,
                        format!("smoothlab reads {READS}"),
                    ))
                }
            }
        }
        Ok(())
    }

    /// The file's dimension, which `name` at `line` needs.
    fn dimension(&self, name: &str, line: usize) -> Result<usize> {
        match self.dim {
            0 => Err(Error::parse(line, format!("{name} comes before Dimension: its values per item are not known"))),
            d => Ok(d),
        }
    }

    /// A section's count, checked against the bytes left: each item takes at least `per`
    /// tokens of two bytes.
    fn count(&mut self, name: &str, per: u64, what: &str) -> Result<usize> {
        let (n, nl) = self.lex.u64(|| format!("the number of {what} after {name}"))?;
        self.lex.check_count(n, 2 * per, what, nl)
    }

    fn vertices(&mut self, line: usize) -> Result<()> {
        let dim = self.dimension("Vertices", line)?;
        let n = self.count("Vertices", dim as u64 + 1, "vertices")?;
        if self.b.node_count() == 0 && self.b.element_count() == 0 && !self.b.has_tets() {
            self.b = MeshBuilder::with_capacity(n, 0);
        }
        for i in 1..=n {
            let what = |c: &str| format!("the {c} coordinate of vertex {i}");
            let (x, xl) = self.lex.f64(|| what("x"))?;
            let (y, _) = self.lex.f64(|| what("y"))?;
            let z = if dim == 3 { self.lex.f64(|| what("z"))?.0 } else { 0.0 };
            self.lex.i64(|| format!("the reference of vertex {i}"))?;
            self.b.add_node([x, y, z], xl);
        }
        self.vertices_read = true;
        Ok(())
    }

    /// Vertex index `v` (1-based) of `what`, on `line`, as a 0-based index.
    fn vertex(&mut self, v: u64, line: usize, what: impl Fn() -> String) -> Result<u32> {
        if v == 0 {
            return Err(Error::parse(line, format!("{}: vertex index 0 is invalid: Medit counts from 1", what())));
        }
        let n = self.b.node_count() as u64;
        if self.vertices_read {
            if v > n {
                return Err(out_of_range(v, n, line, &what()));
            }
        } else if v > u32::MAX as u64 {
            return Err(out_of_range(v, 0, line, &what()));
        } else if self.pending.as_ref().map_or(true, |p| v > p.0) {
            self.pending = Some((v, line, what()));
        }
        Ok((v - 1) as u32)
    }

    /// A section of elements of `k` vertices and a reference each, given to `add` with
    /// their line and their number in the section (from 1, as Medit counts).
    fn elements(
        &mut self,
        name: &str,
        one: &str,
        k: usize,
        line: usize,
        mut add: impl FnMut(&mut MeshBuilder, &[u32], usize, u64) -> Result<()>,
    ) -> Result<()> {
        let n = self.count(name, k as u64 + 1, &format!("{name} (line {line})"))?;
        let mut ids = [0u32; 8];
        for e in 1..=n {
            let mut at = line;
            for (j, id) in ids.iter_mut().enumerate().take(k) {
                let (v, vl) = self.lex.u64(|| format!("vertex {} of {one} {e}", j + 1))?;
                if j == 0 {
                    at = vl;
                }
                *id = self.vertex(v, vl, || format!("{one} {e}"))?;
            }
            self.lex.i64(|| format!("the reference of {one} {e}"))?;
            if let Some(v) = repeated(&ids[..k]) {
                return Err(Error::parse(at, format!("{one} {e}: vertex {} appears twice", v + 1)));
            }
            add(&mut self.b, &ids[..k], at, e as u64)?;
        }
        Ok(())
    }

    /// `Corners` or `RequiredVertices`: a vertex index each, marked fixed.
    fn marks(&mut self, name: &str) -> Result<()> {
        let n = self.count(name, 1, "vertex indices")?;
        for i in 1..=n {
            let (v, vl) = self.lex.u64(|| format!("vertex index {i} of {name}"))?;
            let id = self.vertex(v, vl, || format!("{name} entry {i}"))?;
            self.marked.push(id);
        }
        Ok(())
    }

    /// A section whose items of `per` tokens are not used.
    fn skip(&mut self, name: &str, per: u64, line: usize) -> Result<()> {
        let n = self.count(name, per, &format!("items of {name}"))?;
        self.lex.skip(n as u64 * per, || format!("the data of {name} (line {line})"))
    }

    fn finish(self) -> Result<MeshBuilder> {
        let Reader { mut b, marked, pending, .. } = self;
        // Medit numbers its vertices from 1: messages name them so
        b.number_nodes(Numbering::From(1));
        let n = b.node_count();
        if let Some((v, line, what)) = pending {
            if v > n as u64 {
                return Err(out_of_range(v, n as u64, line, &what));
            }
        }
        if !marked.is_empty() {
            let mut f = vec![false; n];
            for i in marked {
                if let Some(x) = f.get_mut(i as usize) {
                    *x = true;
                }
            }
            b.fixed = FixedSpec::BoundaryAnd(f);
        }
        Ok(b)
    }
}

fn out_of_range(v: u64, n: u64, line: usize, what: &str) -> Error {
    let valid = if n == 0 { "the file has no vertices".to_string() } else { format!("the file has {n} vertices (1 to {n})") };
    Error::parse(line, format!("{what}: vertex index {v} is out of range: {valid}"))
}

fn header(s: &mut Out, dim: usize, n: usize) {
    let _ = write!(s, "MeshVersionFormatted 2\n\nDimension {dim}\n\nVertices\n{n}\n");
}

/// One element's line: its 1-based vertex indices and reference 0.
fn element_line(s: &mut Out, ids: &[u32]) {
    for &i in ids {
        let _ = write!(s, "{} ", i + 1);
    }
    s.push_str("0\n");
}

/// The fixed nodes as `RequiredVertices`, then `End`.
fn footer(s: &mut Out, fixed: &[bool]) {
    let count = fixed.iter().filter(|&&f| f).count();
    if count > 0 {
        let _ = write!(s, "\nRequiredVertices\n{count}\n");
        for (i, _) in fixed.iter().enumerate().filter(|(_, &f)| f) {
            let _ = writeln!(s, "{}", i + 1);
        }
    }
    s.push_str("\nEnd\n");
}

/// Writes a planar mesh or a surface (linear elements only).
pub(crate) fn write(w: super::Writable, s: &mut Out) -> Result<()> {
    let mesh = w.mesh;
    super::objoff::linear_only(mesh, "Medit")?;
    let n = mesh.node_count();
    let flat = w.in_xy_plane();
    header(s, if flat { 2 } else { 3 }, n);
    for i in 0..n {
        if flat {
            let p = mesh.nodes()[i];
            let _ = write!(s, "{:?} {:?}", p.x, p.y);
        } else {
            w.write_xyz(s, i);
        }
        s.push_str(" 0\n");
    }
    for (kind, name) in [(ElementKind::Tri3, "Triangles"), (ElementKind::Quad4, "Quadrilaterals")] {
        let count = mesh.kinds().iter().filter(|&&k| k == kind).count();
        if count == 0 {
            continue;
        }
        let _ = write!(s, "\n{name}\n{count}\n");
        for e in (0..mesh.element_count()).filter(|&e| mesh.kind(e) == kind) {
            element_line(s, &w.element(e));
        }
    }
    footer(s, mesh.fixed());
    Ok(())
}

/// Writes a volume mesh of linear elements: its given faces, then its elements, a section
/// per kind.
pub(crate) fn write_volume(v: &VolumeMesh, s: &mut Out) -> Result<()> {
    if let Some(e) = (0..v.element_count()).find(|&e| v.element_kind(e).is_quadratic()) {
        return Err(Error::invalid(format!(
            "Medit's volume sections hold linear elements, but element {e} is a {}: write .msh or .vtk",
            v.element_kind(e).name()
        )));
    }
    if let Some(f) = v.faces().iter().position(|f| f.kind.is_quadratic()) {
        return Err(Error::invalid(format!(
            "Medit's Triangles and Quadrilaterals are linear, but the file's face {f} is a {}: write .msh or .vtk",
            v.faces()[f].kind.name()
        )));
    }
    header(s, 3, v.node_count());
    for p in v.nodes() {
        let _ = writeln!(s, "{:?} {:?} {:?} 0", p.x, p.y, p.z);
    }
    for (kind, name) in [(ElementKind::Tri3, "Triangles"), (ElementKind::Quad4, "Quadrilaterals")] {
        let count = v.faces().iter().filter(|f| f.kind == kind).count();
        if count > 0 {
            let _ = write!(s, "\n{name}\n{count}\n");
            for f in v.faces().iter().filter(|f| f.kind == kind) {
                element_line(s, f.nodes());
            }
        }
    }
    for (kind, name) in SECTIONS.iter().filter_map(|&(name, s)| match s {
        Section::Solids(kind, _) => Some((kind, name)),
        _ => None,
    }) {
        let count = (0..v.element_count()).filter(|&e| v.element_kind(e) == kind).count();
        if count > 0 {
            let _ = write!(s, "\n{name}\n{count}\n");
            for e in (0..v.element_count()).filter(|&e| v.element_kind(e) == kind) {
                element_line(s, v.element(e));
            }
        }
    }
    footer(s, v.fixed());
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Model;

    fn model(text: &str) -> Model {
        Model::build(parse(text).unwrap()).unwrap()
    }

    fn refused(text: &str) -> String {
        match parse(text).and_then(Model::build) {
            Ok(_) => panic!("read: {text}"),
            Err(e) => e.to_string(),
        }
    }

    #[test]
    fn a_planar_file_with_comments_any_case_and_skipped_sections() {
        let text = "# from MMG\nMeshVersionFormatted 2\ndimension\n2\n# the vertices\nVERTICES 5\n0 0 1\n1 0 1\n1 1 2\n\
                    0 1 2\n2 0 7\nTriangles\n1\n2 5 3 4\nQuadrilaterals 1\n1 2 3 4 0\nNormals 1\n0 1\n\
                    NormalAtVertices 1 5 1\nRidges 0\nCorners\n1\n5\nEnd\nanything after End";
        let Model::Planar(m) = model(text) else { panic!("planar") };
        assert_eq!((m.node_count(), m.kinds()), (5, &[ElementKind::Tri3, ElementKind::Quad4][..]));
        assert_eq!(m.element_as_given(0).to_vec(), vec![1, 4, 2]);
        // every node here is on the boundary; the references fix nothing more
        assert_eq!(m.fixed(), &[true; 5]);
    }

    #[test]
    fn required_vertices_and_edges_fix_nodes_inside() {
        let grid = |extra: &str| {
            let mut t = String::from("MeshVersionFormatted 1\nDimension 3\nVertices\n9\n");
            for k in 0..9 {
                t += &format!("{} {} 0 -1\n", k % 3, k / 3);
            }
            t += "Quadrilaterals\n4\n1 2 5 4 0\n2 3 6 5 0\n4 5 8 7 0\n5 6 9 8 0\n";
            t + extra + "End\n"
        };
        let fixed = |t: String| match model(&t) {
            Model::Planar(m) => m.fixed()[4],
            _ => panic!("planar"),
        };
        assert!(!fixed(grid("")), "the middle node is free");
        assert!(fixed(grid("RequiredVertices 1 5\n")));
        assert!(fixed(grid("Edges 1 5 6 3\n")));
    }

    /// The lattice points of a cube's 3×3×3 lattice (spacing 1/2, x fastest), then `body`.
    fn lattice(body: &str) -> String {
        let mut t = String::from("MeshVersionFormatted 2\nDimension 3\nVertices\n27\n");
        for k in 0..27 {
            t += &format!("{} {} {} 0\n", (k % 3) as f64 / 2.0, (k / 3 % 3) as f64 / 2.0, (k / 9) as f64 / 2.0);
        }
        t + body
    }

    #[test]
    fn every_linear_volume_kind_is_read_as_given_and_valid() {
        // VTK's orders (1-based): a right-handed tetrahedron, the hexahedron 1 2 3 4 under
        // 5 6 7 8, the prism's triangle turning away from the one above it, the pyramid's
        // base turning towards its apex
        let cases: [(&str, &[u32], VolumeKind); 4] = [
            ("Tetrahedra", &[1, 3, 7, 19], VolumeKind::Tet4),
            ("Hexahedra", &[1, 3, 9, 7, 19, 21, 27, 25], VolumeKind::Hex8),
            ("Prisms", &[1, 7, 3, 19, 25, 21], VolumeKind::Wedge6),
            ("Pyramids", &[1, 3, 9, 7, 23], VolumeKind::Pyramid5),
        ];
        for (name, ids, kind) in cases {
            let line: Vec<String> = ids.iter().map(u32::to_string).collect();
            let Model::Volume(m) = model(&lattice(&format!("{name}\n1\n{} 3\nEnd\n", line.join(" ")))) else {
                panic!("{name}: a volume")
            };
            assert_eq!((m.element_count(), m.element_kind(0)), (1, kind), "{name}");
            let given: Vec<u32> = ids.iter().map(|i| i - 1).collect();
            assert_eq!(m.element(0), &given[..], "{name}: as given, not turned over");
            assert!(!m.is_inverted(0), "{name}");
        }
        // a hexahedron's boundary quad is a given face, written back
        let text = lattice("Quadrilaterals\n1\n1 7 9 3 4\nHexahedra\n1\n1 3 9 7 19 21 27 25 0\nEnd\n");
        let Model::Volume(m) = model(&text) else { panic!("a volume") };
        assert_eq!(m.faces().len(), 1);
        let mut out = Out::string(0);
        write_volume(&m, &mut out).unwrap();
        let back = out.into_string();
        assert!(back.contains("\nQuadrilaterals\n1\n1 7 9 3 0\n\nHexahedra\n1\n1 3 9 7 19 21 27 25 0\n"), "{back}");
        let Model::Volume(again) = model(&back) else { panic!("a volume") };
        assert_eq!((again.element(0), again.faces()[0].nodes(), again.fixed()), (m.element(0), m.faces()[0].nodes(), m.fixed()));
    }

    #[test]
    fn bad_files_are_refused_naming_the_line() {
        let v3 = "MeshVersionFormatted 1\nDimension 3\nVertices\n3\n0 0 0 0\n1 0 0 0\n0 1 0 0\n";
        let cases: [(String, &str); 16] = [
            ("".into(), "empty mesh: the Medit file is empty"),
            ("Vertices 0\n".into(), "line 1: not a Medit file: expected 'MeshVersionFormatted' first, found 'Vertices'"),
            ("MeshVersionFormatted 7".into(), "line 1: MeshVersionFormatted 7 is not a version of the format (1 to 4)"),
            ("MeshVersionFormatted 1\nDimension 4".into(), "line 2: Dimension 4: smoothlab reads dimension 2 or 3"),
            ("MeshVersionFormatted 1\nVertices 1\n0 0 0".into(), "line 2: Vertices comes before Dimension"),
            (format!("{v3}Triangles\n1\n1 2 0 0\n"), "line 10: triangle 1: vertex index 0 is invalid: Medit counts from 1"),
            (format!("{v3}Triangles\n1\n1 2 4 0\n"), "line 10: triangle 1: vertex index 4 is out of range: the file has 3 vertices (1 to 3)"),
            (format!("{v3}Triangles\n2\n1 2 3 0\n1 3 3 0\n"), "line 11: triangle 2: vertex 3 appears twice"),
            (format!("{v3}Triangles\n1\n1 2 3\n"), "line 10: the file ends here, but the reference of triangle 1 was expected"),
            (format!("{v3}Vertices 0\n"), "line 8: a second Vertices section (the first is at line 3)"),
            (format!("{v3}Identifier\n\"x\"\n"), "line 8: Medit section 'Identifier' is not known to smoothlab, so its data cannot be skipped"),
            (format!("{v3}Triangles 1 1 2 3 0 4 End"), "line 8: expected a section keyword, found '4'"),
            (format!("{v3}TrianglesP2 0"), "quadratic triangles (Medit's TrianglesP2) are not supported yet: line 8: smoothlab reads"),
            (format!("{v3}Triangles 1000000000"), "line 8: the header announces 1000000000 Triangles (line 8)"),
            ("MeshVersionFormatted 1\nDimension 2\nTetrahedra 0".into(), "line 3: Tetrahedra in a file of Dimension 2"),
            ("MeshVersionFormatted 1\nDimension 2\nTriangles 1\n1 2 9 0\nVertices 3\n0 0 0\n1 0 0\n0 1 0\n".into(),
             "line 4: triangle 1: vertex index 9 is out of range: the file has 3 vertices (1 to 3)"),
        ];
        for (text, want) in cases {
            let e = refused(&text);
            assert!(e.starts_with(want), "{text:?}\n  gave {e}\n  want {want}");
        }
    }

    #[test]
    fn the_writer_writes_dimension_2_in_the_plane_and_the_fixed_nodes_as_required() {
        let text = "MeshVersionFormatted 1\nDimension 2\nVertices 4\n0 0 0\n1 0 0\n1 1 0\n0.1 0.3 0\n\
                    Triangles 2\n1 2 4 0\n2 3 4 0\nEnd";
        let Model::Planar(m) = model(text) else { panic!("planar") };
        let mut out = Out::string(0);
        write((&m).into(), &mut out).unwrap();
        assert_eq!(
            out.into_string(),
            "MeshVersionFormatted 2\n\nDimension 2\n\nVertices\n4\n0.0 0.0 0\n1.0 0.0 0\n1.0 1.0 0\n0.1 0.3 0\n\n\
             Triangles\n2\n1 2 4 0\n2 3 4 0\n\nRequiredVertices\n4\n1\n2\n3\n4\n\nEnd\n"
        );
    }
}
