//! Legacy VTK, ASCII: `UNSTRUCTURED_GRID` (and simple `POLYDATA` with `POLYGONS`).
//!
//! Read: `POINTS n <any type>`; `CELLS` in the legacy layout (`CELLS n size`, then
//! `k i1 … ik` per cell) and in the VTK 5.1 layout (`OFFSETS` / `CONNECTIVITY`);
//! `CELL_TYPES` 5 (triangle), 9 (quad), 8 (pixel, reordered to a quad), 22 (6-node
//! triangle), 23 (8-node quad), 28 (9-node biquadratic quad), 7 (polygon: read when it
//! has 3 or 4 vertices, refused naming the element and its vertex count otherwise);
//! the volume elements of [`VolumeKind`] by their rows' `vtk_type` — 10 (tetrahedron),
//! 12 (hexahedron), 13 (wedge), 14 (pyramid), 24 (10-node tetrahedron), 25 (20-node
//! hexahedron), 29 (27-node hexahedron), in VTK's node order, which is ours — linear
//! kinds mixed freely, a quadratic kind alone (the builder refuses a mix, naming the line);
//! vertex and line cells (1, 2, 3, 4, 21) mark their points as fixed. `POINT_DATA` with
//! `SCALARS fixed …` gives the fixed flags exactly (nonzero = fixed, as Mesquite writes
//! them); every other attribute, `CELL_DATA`, `FIELD` and `METADATA` block is skipped.
//! Data may wrap over lines freely; errors still name the line.
//!
//! Like Mesquite's own reader, the `size` number of a legacy `CELLS` header (redundant:
//! the cells carry their own counts) is not held against the file. A `CELL_TYPES` count
//! *larger* than the number of cells (Mesquite's `triPatch_*.vtk` announce and list 19
//! types for 6 cells) is read in full and the first types, one per cell, are used; a
//! count smaller than the number of cells is an error.
//!
//! Written: `UNSTRUCTURED_GRID` with `POINTS … double` at full `f64` precision (z = 0),
//! legacy `CELLS`, `CELL_TYPES`, and `POINT_DATA` `SCALARS fixed int 1`, so nodes,
//! elements, kinds and fixed flags all round-trip.

use std::fmt::Write as _;

use crate::error::{Error, Result};
use crate::io::lex::{prealloc, repeated, shown, split_line, Lexer};
use crate::io::out::Out;
use crate::io::volume::{volume_codes, MAX_VOLUME_NODES};
use crate::mesh::{ElementKind, FixedSpec, MeshBuilder, VolumeKind};

#[derive(Clone, Copy, PartialEq)]
enum Dataset {
    UnstructuredGrid,
    PolyData,
}

/// Cells as read: flat point indices, offsets, and the line where each cell starts.
#[derive(Default)]
struct Cells {
    conn: Vec<u64>,
    start: Vec<usize>,
    lines: Vec<u32>,
    /// Line of the section header.
    header: usize,
}

impl Cells {
    fn len(&self) -> usize {
        self.lines.len()
    }
    fn cell(&self, i: usize) -> &[u64] {
        let end = self.start.get(i + 1).copied().unwrap_or(self.conn.len());
        &self.conn[self.start[i]..end]
    }
}

/// What a VTK cell type is to us.
enum VtkType {
    Element(ElementKind),
    /// A volume element ([`crate::volume`]), of the kind whose cell type it is.
    Solid(VolumeKind),
    Pixel,
    Polygon,
    Marker,
    /// The cell's name in VTK's terms and, for a kind a reader of the mesh knows by name,
    /// that name in plain words (plural), which the message leads with.
    Unsupported(&'static str, Option<&'static str>),
}

fn vtk_type(t: u64) -> VtkType {
    use VtkType::*;
    if let Some(kind) = VolumeKind::from_vtk_type(t) {
        return Solid(kind);
    }
    match t {
        5 => Element(ElementKind::Tri3),
        9 => Element(ElementKind::Quad4),
        22 => Element(ElementKind::Tri6),
        23 => Element(ElementKind::Quad8),
        28 => Element(ElementKind::Quad9),
        8 => Pixel,
        7 => Polygon,
        1 | 2 | 3 | 4 | 21 => Marker,
        6 => Unsupported("triangle strip", Some("triangle strips")),
        11 => Unsupported("voxel", Some("voxels (hexahedra numbered as a grid)")),
        26 => Unsupported("quadratic wedge", Some("quadratic wedges (prisms)")),
        27 => Unsupported("quadratic pyramid", Some("quadratic pyramids")),
        32 => Unsupported("biquadratic-quadratic wedge", Some("quadratic wedges (prisms)")),
        42 => Unsupported("polyhedron", Some("polyhedra")),
        _ => Unsupported("not a cell smoothlab knows", None),
    }
}

/// The planar element kind of VTK cell type `t`, as the reader takes it (not pixels and
/// polygons, whose nodes it reorders or counts).
pub(crate) fn planar_kind(t: u64) -> Option<ElementKind> {
    match vtk_type(t) {
        VtkType::Element(kind) => Some(kind),
        _ => None,
    }
}

/// Whether VTK cell type `t` marks its points fixed (vertex and line cells), as the reader
/// takes it.
pub(crate) fn is_marker(t: u64) -> bool {
    matches!(vtk_type(t), VtkType::Marker)
}

struct Reader<'a> {
    lex: Lexer<'a>,
    dataset: Dataset,
    builder: MeshBuilder,
    points_line: Option<usize>,
    cells: Option<Cells>,
    types: Option<(Vec<u64>, Vec<u32>, usize)>,
    /// POLYDATA `VERTICES`/`LINES`: points to mark fixed.
    marked: Vec<u64>,
    fixed: Option<Vec<bool>>,
    /// Line of the `SCALARS fixed` that gave `fixed`.
    fixed_line: Option<usize>,
}

/// Reads a legacy VTK file into a builder (see [`super::parse_str`]).
pub(crate) fn parse(text: &str) -> Result<MeshBuilder> {
    // The first three lines are line-oriented: version, title, ASCII/BINARY.
    let mut rest = text;
    let mut header = ["", "", ""];
    for (i, h) in header.iter_mut().enumerate() {
        if rest.is_empty() {
            return Err(Error::parse(
                i.max(1),
                "the file ends inside the VTK header (version line, title line, ASCII line)",
            ));
        }
        let (line, next) = split_line(rest);
        *h = line.trim();
        rest = next.unwrap_or("");
    }
    let version = header[0].to_ascii_lowercase();
    if !version.starts_with("# vtk datafile version") {
        return Err(Error::parse(
            1,
            format!("not a legacy VTK file: line 1 must be '# vtk DataFile Version x.y', found {}", shown(header[0])),
        ));
    }
    if header[2].eq_ignore_ascii_case("BINARY") {
        return Err(Error::unsupported(Some(3), "binary VTK files are not supported; save as ASCII"));
    }
    if !header[2].eq_ignore_ascii_case("ASCII") {
        return Err(Error::parse(3, format!("expected 'ASCII' or 'BINARY' on line 3, found {}", shown(header[2]))));
    }
    let mut lex = Lexer::starting_at(rest, 4);
    let kw = lex.keyword("DATASET", || "the dataset line after the header".into())?;
    let ty = lex.expect(|| "the dataset type after DATASET".into())?;
    let dataset = if ty.text.eq_ignore_ascii_case("UNSTRUCTURED_GRID") {
        Dataset::UnstructuredGrid
    } else if ty.text.eq_ignore_ascii_case("POLYDATA") {
        Dataset::PolyData
    } else {
        return Err(Error::unsupported(
            Some(ty.line.max(kw.line)),
            format!("VTK dataset {} is not supported; smoothlab reads UNSTRUCTURED_GRID and POLYDATA", shown(ty.text)),
        ));
    };
    let mut r = Reader {
        lex,
        dataset,
        builder: MeshBuilder::new(),
        points_line: None,
        cells: None,
        types: None,
        marked: Vec::new(),
        fixed: None,
        fixed_line: None,
    };
    r.sections()?;
    r.finish()
}

fn is(t: &str, kw: &str) -> bool {
    t.eq_ignore_ascii_case(kw)
}

impl Reader<'_> {
    fn sections(&mut self) -> Result<()> {
        while let Some(t) = self.lex.next() {
            let k = t.text;
            if is(k, "POINTS") {
                if let Some(l) = self.points_line {
                    return Err(Error::parse(t.line, format!("a second POINTS section (the first is at line {l})")));
                }
                self.points(t.line)?;
            } else if self.dataset == Dataset::UnstructuredGrid && is(k, "CELLS") {
                if let Some(c) = &self.cells {
                    return Err(Error::parse(
                        t.line,
                        format!("a second CELLS section (the first is at line {})", c.header),
                    ));
                }
                self.cells = Some(self.cell_list(t.line, "CELLS")?);
            } else if self.dataset == Dataset::UnstructuredGrid && is(k, "CELL_TYPES") {
                self.cell_types(t.line)?;
            } else if self.dataset == Dataset::PolyData && is(k, "POLYGONS") {
                if let Some(c) = &self.cells {
                    return Err(Error::parse(
                        t.line,
                        format!("a second POLYGONS section (the first is at line {})", c.header),
                    ));
                }
                self.cells = Some(self.cell_list(t.line, "POLYGONS")?);
            } else if self.dataset == Dataset::PolyData && (is(k, "VERTICES") || is(k, "LINES")) {
                let c = self.cell_list(t.line, k)?;
                self.marked.extend_from_slice(&c.conn);
            } else if self.dataset == Dataset::PolyData && is(k, "TRIANGLE_STRIPS") {
                return Err(Error::unsupported(Some(t.line), "VTK triangle strips are not supported"));
            } else if is(k, "POINT_DATA") || is(k, "CELL_DATA") {
                self.attributes(t.line, is(k, "POINT_DATA"))?;
            } else if is(k, "FIELD") {
                self.field(t.line)?;
            } else if is(k, "METADATA") {
                self.lex.skip_to_blank_line();
            } else {
                let expected = match self.dataset {
                    Dataset::UnstructuredGrid => "POINTS, CELLS, CELL_TYPES, POINT_DATA or CELL_DATA",
                    Dataset::PolyData => "POINTS, POLYGONS, VERTICES, LINES, POINT_DATA or CELL_DATA",
                };
                return Err(Error::parse(t.line, format!("expected a section ({expected}), found {}", shown(k))));
            }
        }
        Ok(())
    }

    fn points(&mut self, line: usize) -> Result<()> {
        let (n, nl) = self.lex.u64(|| "the number of points after POINTS".into())?;
        let n = self.lex.check_count(n, 6, "points", nl)?;
        self.lex.expect(|| "the data type of POINTS (float, double, …)".into())?;
        self.builder = MeshBuilder::with_capacity(n, 0);
        for i in 0..n {
            let what = |c: &str| format!("the {c} coordinate of point {i} (of the {n} announced at line {line})");
            let (x, xl) = self.lex.f64(|| what("x"))?;
            let (y, _) = self.lex.f64(|| what("y"))?;
            let (z, _) = self.lex.f64(|| what("z"))?;
            self.builder.add_node([x, y, z], xl);
        }
        self.points_line = Some(line);
        Ok(())
    }

    /// A cell list (`CELLS`, `POLYGONS`, `LINES`, …) in either layout.
    fn cell_list(&mut self, line: usize, name: &str) -> Result<Cells> {
        let (a, al) = self.lex.u64(|| format!("the number of cells after {name}"))?;
        let (b, _) = self.lex.u64(|| format!("the size of the {name} list"))?;
        let mut c = Cells { header: line, ..Default::default() };
        if self.lex.peek().is_some_and(|t| is(t.text, "OFFSETS")) {
            // VTK 5.1: `a` offsets (one more than the cells), `b` connectivity entries.
            self.lex.next();
            self.lex.expect(|| "the data type of OFFSETS".into())?;
            let n_off = self.lex.check_count(a, 2, "offsets", al)?;
            let n_conn = self.lex.check_count(b, 2, "connectivity entries", al)?;
            let mut offsets = Vec::with_capacity(prealloc(n_off));
            for i in 0..n_off {
                let (o, ol) = self.lex.u64(|| format!("offset {i} of the {n_off} announced at line {line}"))?;
                if let Some(&(prev, _)) = offsets.last() {
                    if o < prev {
                        return Err(Error::parse(ol, format!("offsets must not decrease: {o} follows {prev}")));
                    }
                } else if o != 0 {
                    return Err(Error::parse(ol, format!("the first offset must be 0, found {o}")));
                }
                offsets.push((o, ol as u32));
            }
            let last = offsets.last().map_or(0, |p| p.0);
            if last != b {
                return Err(Error::parse(
                    offsets.last().map_or(al, |p| p.1 as usize),
                    format!("the last offset is {last} but the header announces {b} connectivity entries"),
                ));
            }
            self.lex.keyword("CONNECTIVITY", || format!("after the offsets of {name} (line {line})"))?;
            self.lex.expect(|| "the data type of CONNECTIVITY".into())?;
            c.conn.reserve(prealloc(n_conn));
            let mut cell_lines = Vec::with_capacity(prealloc(n_conn));
            for i in 0..n_conn {
                let (v, vl) =
                    self.lex.u64(|| format!("connectivity entry {i} of the {n_conn} announced at line {line}"))?;
                c.conn.push(v);
                cell_lines.push(vl as u32);
            }
            for w in offsets.windows(2) {
                c.start.push(w[0].0 as usize);
                c.lines.push(cell_lines.get(w[0].0 as usize).copied().unwrap_or(w[0].1));
            }
        } else {
            let n = self.lex.check_count(a, 4, "cells", al)?;
            c.start.reserve(prealloc(n));
            c.lines.reserve(prealloc(n));
            c.conn.reserve(prealloc(self.lex.check_count(b, 2, "list entries", al).unwrap_or(0).min(16 * n)));
            // A keyword where a number should be: the cells' counts do not fit the data.
            let cut_short = |lex: &Lexer, i: usize| -> Result<()> {
                match lex.peek() {
                    Some(t) if t.text.starts_with(|ch: char| ch.is_ascii_alphabetic()) => Err(Error::parse(
                        t.line,
                        format!(
                            "{name} (line {line}) announces {n} cells, but cell {i} is cut short by {}: \
                             the point counts of the cells do not match the data",
                            shown(t.text)
                        ),
                    )),
                    _ => Ok(()),
                }
            };
            for i in 0..n {
                cut_short(&self.lex, i)?;
                let (k, kl) =
                    self.lex.u64(|| format!("the point count of cell {i} (of the {n} announced at line {line})"))?;
                c.start.push(c.conn.len());
                c.lines.push(kl as u32);
                for j in 0..k {
                    cut_short(&self.lex, i)?;
                    let (v, _) = self.lex.u64(|| format!("point {j} of the {k} of cell {i} (line {kl})"))?;
                    c.conn.push(v);
                }
            }
        }
        Ok(c)
    }

    fn cell_types(&mut self, line: usize) -> Result<()> {
        let Some(cells) = &self.cells else {
            return Err(Error::parse(line, "CELL_TYPES comes before any CELLS section"));
        };
        if let Some((_, _, l)) = &self.types {
            return Err(Error::parse(line, format!("a second CELL_TYPES section (the first is at line {l})")));
        }
        let (announced, nl) = self.lex.u64(|| "the number of cell types".into())?;
        if announced < cells.len() as u64 {
            return Err(Error::parse(
                nl,
                format!(
                    "CELL_TYPES announces {announced} types, but CELLS (line {}) has {} cells",
                    cells.header,
                    cells.len()
                ),
            ));
        }
        // The whole announced count must fit in the rest of the file (so the message
        // names the count the header gives, not the surplus over the cells).
        self.lex.check_count(announced, 2, "cell types", nl)?;
        let n = cells.len();
        let mut types = Vec::with_capacity(n);
        let mut lines = Vec::with_capacity(n);
        for i in 0..n {
            let (t, tl) = self.lex.u64(|| format!("the type of cell {i} (of the {n} at line {line})"))?;
            types.push(t);
            lines.push(tl as u32);
        }
        // More types than cells: read (and check) the surplus, use the first ones.
        let extra = self.lex.check_count(announced - n as u64, 2, "cell types", nl)?;
        for i in 0..extra {
            self.lex.u64(|| format!("cell type {} of the {announced} announced at line {nl}", n + i))?;
        }
        self.types = Some((types, lines, line));
        Ok(())
    }

    /// The attributes after `POINT_DATA n` / `CELL_DATA n`, up to the next section.
    fn attributes(&mut self, line: usize, point_data: bool) -> Result<()> {
        let what = if point_data { "POINT_DATA" } else { "CELL_DATA" };
        let (n, nl) = self.lex.u64(|| format!("the count after {what}"))?;
        if point_data {
            match self.points_line {
                Some(pl) if n as usize != self.builder.node_count() => {
                    return Err(Error::parse(
                        nl,
                        format!(
                            "POINT_DATA announces {n} values, but POINTS (line {pl}) has {} points",
                            self.builder.node_count()
                        ),
                    ))
                }
                None => return Err(Error::parse(line, "POINT_DATA comes before POINTS")),
                _ => {}
            }
        }
        let n = self.lex.check_count(n, 2, "values", nl)? as u64;
        while let Some(t) = self.lex.peek() {
            let k = t.text;
            if is(k, "SCALARS") {
                self.lex.next();
                let name = self.lex.expect(|| "the name of the SCALARS".into())?;
                self.lex.expect(|| format!("the data type of SCALARS {}", name.text))?;
                let mut comps = 1;
                if let Some(c) = self.lex.peek().filter(|c| c.line == t.line) {
                    comps = c.text.parse::<u64>().ok().filter(|c| (1..=4).contains(c)).ok_or_else(|| {
                        Error::parse(
                            c.line,
                            format!("expected the number of components (1 to 4), found {}", shown(c.text)),
                        )
                    })?;
                    self.lex.next();
                }
                if self.lex.peek().is_some_and(|l| is(l.text, "LOOKUP_TABLE")) {
                    self.lex.next();
                    self.lex.expect(|| "the name of the LOOKUP_TABLE".into())?;
                }
                if point_data && name.text == "fixed" {
                    if let Some(first) = self.fixed_line {
                        return Err(Error::parse(
                            t.line,
                            format!("a second SCALARS fixed (the first is at line {first}): give one"),
                        ));
                    }
                    self.fixed_line = Some(t.line);
                    if comps != 1 {
                        return Err(Error::parse(
                            t.line,
                            format!("SCALARS fixed must have 1 component, found {comps}"),
                        ));
                    }
                    let mut f = Vec::with_capacity(prealloc(n as usize));
                    for i in 0..n {
                        let (v, _) =
                            self.lex.f64(|| format!("the 'fixed' value of point {i} (SCALARS at line {})", t.line))?;
                        f.push(v != 0.0);
                    }
                    self.fixed = Some(f);
                } else {
                    self.skip_values(n * comps, &format!("SCALARS {}", name.text), t.line)?;
                }
            } else if is(k, "COLOR_SCALARS") {
                self.lex.next();
                self.lex.expect(|| "the name of the COLOR_SCALARS".into())?;
                let (c, _) = self.lex.u64(|| "the number of colour values".into())?;
                self.skip_values(n.saturating_mul(c), "COLOR_SCALARS", t.line)?;
            } else if is(k, "VECTORS") || is(k, "NORMALS") || is(k, "TENSORS") || is(k, "TENSORS6") {
                self.lex.next();
                self.lex.expect(|| format!("the name of the {k}"))?;
                self.lex.expect(|| format!("the data type of the {k}"))?;
                let per = if is(k, "TENSORS") {
                    9
                } else if is(k, "TENSORS6") {
                    6
                } else {
                    3
                };
                self.skip_values(n * per, k, t.line)?;
            } else if is(k, "TEXTURE_COORDINATES") {
                self.lex.next();
                self.lex.expect(|| "the name of the TEXTURE_COORDINATES".into())?;
                let (d, _) = self.lex.u64(|| "the texture dimension".into())?;
                self.lex.expect(|| "the data type of the TEXTURE_COORDINATES".into())?;
                self.skip_values(n.saturating_mul(d), k, t.line)?;
            } else if is(k, "LOOKUP_TABLE") {
                self.lex.next();
                self.lex.expect(|| "the name of the LOOKUP_TABLE".into())?;
                let (s, _) = self.lex.u64(|| "the size of the LOOKUP_TABLE".into())?;
                self.skip_values(s.saturating_mul(4), k, t.line)?;
            } else if is(k, "FIELD") {
                self.lex.next();
                self.field(t.line)?;
            } else if is(k, "METADATA") {
                self.lex.next();
                self.lex.skip_to_blank_line();
            } else {
                break;
            }
        }
        Ok(())
    }

    fn skip_values(&mut self, count: u64, what: &str, line: usize) -> Result<()> {
        self.lex.check_count(count, 2, &format!("values of {what}"), line)?;
        self.lex.skip(count, || format!("a value of {what} (line {line})"))
    }

    /// `FIELD name n`, then `n` arrays `name components tuples type` with their values.
    fn field(&mut self, line: usize) -> Result<()> {
        self.lex.expect(|| "the name of the FIELD".into())?;
        let (arrays, al) = self.lex.u64(|| "the number of arrays of the FIELD".into())?;
        self.lex.check_count(arrays, 8, "field arrays", al)?;
        for _ in 0..arrays {
            let name = self.lex.expect(|| format!("the name of an array of the FIELD at line {line}"))?;
            let (c, _) = self.lex.u64(|| format!("the number of components of array {}", name.text))?;
            let (t, _) = self.lex.u64(|| format!("the number of tuples of array {}", name.text))?;
            self.lex.expect(|| format!("the data type of array {}", name.text))?;
            self.skip_values(c.saturating_mul(t), name.text, name.line)?;
            if self.lex.peek().is_some_and(|m| is(m.text, "METADATA")) {
                self.lex.next();
                self.lex.skip_to_blank_line();
            }
        }
        Ok(())
    }

    fn finish(self) -> Result<MeshBuilder> {
        let Reader { lex, dataset, mut builder, points_line, cells, types, mut marked, fixed, .. } = self;
        if points_line.is_none() {
            return Err(Error::parse(lex.last_line(), "the file ends without a POINTS section"));
        }
        let np = builder.node_count();
        let Some(cells) = cells else {
            return Err(Error::Empty(format!(
                "{np} points but no {} section",
                if dataset == Dataset::PolyData { "POLYGONS" } else { "CELLS" }
            )));
        };
        let types = match (dataset, types) {
            (Dataset::UnstructuredGrid, None) => {
                return Err(Error::parse(
                    lex.last_line(),
                    format!(
                        "the file ends without the CELL_TYPES section for the {} cells of line {}",
                        cells.len(),
                        cells.header
                    ),
                ))
            }
            (_, t) => t,
        };
        let mut ids = [0u32; 9];
        for i in 0..cells.len() {
            let conn = cells.cell(i);
            let line = cells.lines[i] as usize;
            let (ty, type_line) = match &types {
                Some((t, l, _)) => (t[i], l[i] as usize),
                None => (7, line), // POLYDATA polygons
            };
            let check = |nodes: &[u64], ids: &mut [u32]| -> Result<()> {
                if let Some(v) = repeated(nodes) {
                    return Err(Error::element(i, Some(line), format!("point {v} appears twice in the cell")));
                }
                for (j, &v) in nodes.iter().enumerate() {
                    if v >= np as u64 {
                        return Err(Error::element(
                            i,
                            Some(line),
                            format!(
                                "point index {v} is out of range: the file has {np} points (0 to {})",
                                np.saturating_sub(1)
                            ),
                        ));
                    }
                    ids[j] = v as u32;
                }
                Ok(())
            };
            let kind = match vtk_type(ty) {
                VtkType::Element(kind) => {
                    if conn.len() != kind.node_count() {
                        return Err(Error::element(
                            i,
                            Some(line),
                            format!(
                                "cell type {ty} ({}) needs {} points, but the cell lists {}",
                                kind.name(),
                                kind.node_count(),
                                conn.len()
                            ),
                        ));
                    }
                    check(conn, &mut ids)?;
                    kind
                }
                VtkType::Solid(kind) => {
                    let k = kind.nodes();
                    if conn.len() != k {
                        return Err(Error::element(
                            i,
                            Some(line),
                            format!("cell type {ty} (a {}) needs {k} points, but the cell lists {}", kind.name(), conn.len()),
                        ));
                    }
                    let mut solid = [0u32; MAX_VOLUME_NODES];
                    check(conn, &mut solid[..k])?;
                    builder.add_volume_element_numbered(kind, &solid[..k], line, i as u64)?;
                    continue;
                }
                VtkType::Pixel => {
                    if conn.len() != 4 {
                        return Err(Error::element(
                            i,
                            Some(line),
                            format!("a pixel needs 4 points, but the cell lists {}", conn.len()),
                        ));
                    }
                    check(conn, &mut ids)?;
                    ids.swap(2, 3);
                    ElementKind::Quad4
                }
                VtkType::Polygon => match conn.len() {
                    3 | 4 => {
                        check(conn, &mut ids)?;
                        if conn.len() == 3 {
                            ElementKind::Tri3
                        } else {
                            ElementKind::Quad4
                        }
                    }
                    k => {
                        return Err(Error::unsupported(
                            Some(line),
                            format!(
                                "polygons are not supported: element {i} at line {line} has {k} vertices \
                                 (smoothlab reads triangles and quads)"
                            ),
                        ))
                    }
                },
                VtkType::Marker => {
                    for &v in conn {
                        if v >= np as u64 {
                            return Err(Error::element(
                                i,
                                Some(line),
                                format!(
                                    "point index {v} is out of range: the file has {np} points (0 to {})",
                                    np.saturating_sub(1)
                                ),
                            ));
                        }
                    }
                    marked.extend_from_slice(conn);
                    continue;
                }
                VtkType::Unsupported(name, words) => {
                    let reads = format!(
                        "smoothlab reads types 5, 9, 22, 23, 28 (and 7 with 3 or 4 vertices) and the volume \
                         elements {}",
                        volume_codes(|r| r.vtk_type)
                    );
                    return Err(match words {
                        Some(words) => Error::unsupported_kind(
                            format!("{words} are not supported yet"),
                            type_line,
                            format!("VTK cell type {ty} ({name}) of element {i}; {reads}"),
                        ),
                        None => Error::unsupported(
                            Some(type_line),
                            format!("VTK cell type {ty} ({name}) of element {i} is not supported: {reads}"),
                        ),
                    });
                }
            };
            builder.add_element_numbered(kind, &ids[..kind.node_count()], line, i as u64);
        }
        builder.fixed = if let Some(f) = fixed {
            FixedSpec::Exact(f)
        } else if marked.is_empty() {
            FixedSpec::Boundary
        } else {
            let mut f = vec![false; np];
            for v in marked {
                match f.get_mut(v as usize) {
                    Some(s) => *s = true,
                    None => {
                        return Err(Error::parse(
                            lex.last_line(),
                            format!("a vertex or line cell refers to point {v}, but the file has {np} points"),
                        ))
                    }
                }
            }
            FixedSpec::BoundaryAnd(f)
        };
        Ok(builder)
    }
}

pub(crate) fn type_of(kind: ElementKind) -> u32 {
    match kind {
        ElementKind::Tri3 => 5,
        ElementKind::Quad4 => 9,
        ElementKind::Tri6 => 22,
        ElementKind::Quad8 => 23,
        ElementKind::Quad9 => 28,
    }
}

/// Writes a legacy VTK `UNSTRUCTURED_GRID` (ASCII) with the fixed flags as point data.
pub(crate) fn write(w: super::Writable, s: &mut Out) {
    let mesh = w.mesh;
    let n = mesh.node_count();
    let m = mesh.element_count();
    let size: usize = (0..m).map(|e| mesh.kind(e).node_count() + 1).sum();
    let _ =
        write!(s, "# vtk DataFile Version 3.0\nsmoothlab mesh\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS {n} double\n");
    for i in 0..n {
        w.write_xyz(s, i);
        s.push('\n');
    }
    let _ = writeln!(s, "CELLS {m} {size}");
    for e in 0..m {
        let ids = w.element(e);
        let _ = write!(s, "{}", ids.len());
        for &i in ids.iter() {
            let _ = write!(s, " {i}");
        }
        s.push('\n');
    }
    let _ = writeln!(s, "CELL_TYPES {m}");
    for &k in mesh.kinds() {
        let _ = writeln!(s, "{}", type_of(k));
    }
    write_fixed(mesh.fixed(), s);
}

/// The fixed flags as `POINT_DATA` scalar `fixed` (1 = fixed).
pub(crate) fn write_fixed(fixed: &[bool], s: &mut Out) {
    let _ = writeln!(s, "POINT_DATA {}\nSCALARS fixed int 1\nLOOKUP_TABLE default", fixed.len());
    for &f in fixed {
        let _ = writeln!(s, "{}", u8::from(f));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One cell of each listed type on the 27 points of a cube's 3×3×3 lattice (spacing
    /// 1/2, x fastest), the cells at line 34 on: what every kind is read from.
    fn lattice_file(cells: &[(u64, &[u32])]) -> String {
        let mut t = String::from("# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 27 double\n");
        for k in 0..27 {
            t.push_str(&format!("{} {} {}\n", (k % 3) as f64 / 2.0, (k / 3 % 3) as f64 / 2.0, (k / 9) as f64 / 2.0));
        }
        let size: usize = cells.iter().map(|(_, c)| c.len() + 1).sum();
        t.push_str(&format!("CELLS {} {size}\n", cells.len()));
        for (_, c) in cells {
            t.push_str(&format!("{}{}\n", c.len(), c.iter().map(|i| format!(" {i}")).collect::<String>()));
        }
        t.push_str(&format!("CELL_TYPES {}\n", cells.len()));
        for (ty, _) in cells {
            t.push_str(&format!("{ty}\n"));
        }
        t
    }

    /// The lattice points of a hexahedron's corners, edge middles, face centres and
    /// centre in VTK's order (those of `QUADRATIC_HEXAHEDRON`, `TRIQUADRATIC_HEXAHEDRON`):
    /// lattice point `x + 3y + 9z` for `x, y, z` in half-units.
    const HEX27: [u32; 27] = [0, 2, 8, 6, 18, 20, 26, 24, 1, 5, 7, 3, 19, 23, 25, 21, 9, 11, 17, 15, 12, 14, 10, 16, 4, 22, 13];

    #[test]
    fn every_volume_kind_is_read_by_its_cell_type_and_the_rest_are_refused_in_plain_words_first() {
        // every kind of the rows, one cell of its type: read, of that kind, nodes as given
        let wedge: &[u32] = &[0, 6, 2, 18, 24, 20]; // (0 1 2) turns away from (3 4 5)
        let pyramid: &[u32] = &[0, 2, 8, 6, 22]; // the base turns towards the apex
        let tet: &[u32] = &[0, 2, 6, 18];
        let tet10: &[u32] = &[0, 2, 6, 18, 1, 4, 3, 9, 10, 12];
        let cases: [(u64, &[u32], VolumeKind); 7] = [
            (10, tet, VolumeKind::Tet4),
            (24, tet10, VolumeKind::Tet10),
            (12, &HEX27[..8], VolumeKind::Hex8),
            (25, &HEX27[..20], VolumeKind::Hex20),
            (29, &HEX27, VolumeKind::Hex27),
            (13, wedge, VolumeKind::Wedge6),
            (14, pyramid, VolumeKind::Pyramid5),
        ];
        for (ty, cell, kind) in cases {
            let model = crate::model::Model::build(parse(&lattice_file(&[(ty, cell)])).unwrap());
            let Ok(crate::model::Model::Volume(m)) = model else { panic!("type {ty}: {model:?}") };
            assert_eq!((m.element_count(), m.element_kind(0)), (1, kind), "type {ty}");
            assert_eq!(m.element(0), cell, "type {ty}: read as given (not turned over)");
            assert!(!m.is_inverted(0), "type {ty}");
        }
        // a voxel, quadratic wedges and pyramids, a polyhedron: refused, in words first
        let refused = [
            (11, 8, "voxels (hexahedra numbered as a grid) are not supported yet: line 36: VTK cell type 11 (voxel) of element 0; "),
            (26, 15, "quadratic wedges (prisms) are not supported yet: line 36: VTK cell type 26 (quadratic wedge) of element 0; "),
            (27, 13, "quadratic pyramids are not supported yet: line 36: VTK cell type 27 (quadratic pyramid) of element 0; "),
            (32, 18, "quadratic wedges (prisms) are not supported yet: line 36: VTK cell type 32 (biquadratic-quadratic wedge)"),
            (42, 8, "polyhedra are not supported yet: line 36: VTK cell type 42 (polyhedron) of element 0; "),
        ];
        for (ty, n, want) in refused {
            let e = parse(&lattice_file(&[(ty, &HEX27[..n])])).unwrap_err();
            assert!(matches!(e, Error::Unsupported { line: Some(36), .. }), "{e:?}");
            let e = e.to_string();
            assert!(e.starts_with(want), "type {ty}: {e}");
            assert!(e.ends_with("and the volume elements 10, 12, 13, 14, 24, 25, 29"), "{e}");
        }
        // a type with no name people know keeps the file's terms alone, line first
        let e = parse(&lattice_file(&[(99, &HEX27[..8])])).unwrap_err().to_string();
        assert!(e.starts_with("line 36: VTK cell type 99 (not a cell smoothlab knows) of element 0 is not supported"), "{e}");
    }

    #[test]
    fn linear_kinds_mix_and_a_quadratic_kind_mixed_with_another_is_refused_naming_the_line() {
        // a hexahedron, a wedge (sharing its face x = 1/2) and a pyramid on its face y = 1/2:
        // one mesh, none of them inverted
        let mixed = [(12, &[0u32, 1, 4, 3, 9, 10, 13, 12][..]), (13, &[1, 4, 2, 10, 13, 11]), (14, &[3, 4, 7, 6, 12])];
        let b = parse(&lattice_file(&mixed)).unwrap();
        let Ok(crate::model::Model::Volume(m)) = crate::model::Model::build(b) else { panic!("not a volume") };
        assert_eq!(m.kinds(), &[VolumeKind::Hex8, VolumeKind::Wedge6, VolumeKind::Pyramid5]);
        assert_eq!((0..3).filter(|&e| m.is_inverted(e)).count(), 0);
        // a 20-node hexahedron and then a linear one: refused at the second cell's line
        let e = parse(&lattice_file(&[(25, &HEX27[..20]), (12, &HEX27[..8])])).unwrap_err();
        assert_eq!(
            e.to_string(),
            "element 1 (line 35): the file mixes 8-node and 20-node hexahedra: smoothlab mixes linear kinds, \
             but a quadratic mesh is of one kind"
        );
        let e = parse(&lattice_file(&[(10, &[0, 2, 6, 18]), (29, &HEX27)])).unwrap_err().to_string();
        assert!(e.starts_with("element 1 (line 35): the file mixes 4-node tetrahedra and 27-node hexahedra"), "{e}");
    }
}
