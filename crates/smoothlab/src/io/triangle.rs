//! Shewchuk's Triangle `.node` / `.ele` pair, and Si's TetGen pair of the same names.
//!
//! TetGen's files are Triangle's in 3D: `.node` of dimension 3 (`number x y z …`) and
//! `.ele` of 4 or 10 nodes per tetrahedron (`-o2`: the six extra nodes taken as the
//! middles of edges 1-2, 2-3, 3-1, 1-4, 2-4, 3-4 in TetGen's 1-based words, which is VTK's
//! order); such a pair is read as a tetrahedral mesh ([`crate::volume`]) and written back
//! in the same layout.
//!
//! `.node`: a header `n 2 attributes markers(0|1)`, then `number x y [attributes] [marker]`
//! per node; numbering starts at 0 or 1 (decided by the first node) and is consecutive.
//! A nonzero boundary marker marks the node fixed, on top of the mesh boundary.
//! `.ele`: a header `m 3|6 attributes`, then `number n1 n2 n3 [n4 n5 n6] [attributes]`.
//! With `-o2`, the three extra nodes are the mid-nodes *opposite* corners 0, 1, 2 (on
//! edges 1-2, 2-0, 0-1); they are remapped to smoothlab's order (mid-nodes of 0-1, 1-2, 2-0).
//! `#` starts a comment anywhere.
//!
//! Written (triangles only): marker 1 on fixed nodes, 0 elsewhere; reading back gives the
//! same nodes and elements, and fixed = boundary ∪ written markers, which equals the
//! written fixed flags whenever every boundary node is fixed (the default).

use std::fmt::Write as _;

use crate::error::{Error, Result};
use crate::io::lex::{check_count, content_lines, parse_f64, prealloc, repeated, shown};
use crate::io::out::Out;
use crate::mesh::{ElementKind, FixedSpec, Mesh, MeshBuilder};

/// Our local index `i` takes Triangle's local index `TRIANGLE_ORDER[i]`.
const TRIANGLE_ORDER: [usize; 6] = [0, 1, 2, 5, 3, 4];

/// Adds which file an error is in (the two files share line numbers).
fn in_file(e: Error, file: &str) -> Error {
    match e {
        Error::Parse { line, message } => Error::Parse { line, message: format!("{message} (in the {file} file)") },
        Error::Element { element, line, message } => {
            Error::Element { element, line, message: format!("{message} (line numbers of the .ele file)") }
        }
        Error::Node { node, line, message } => {
            Error::Node { node, line, message: format!("{message} (line numbers of the .node file)") }
        }
        Error::Unsupported { lead, line, message } => {
            Error::Unsupported { lead, line, message: format!("{message} (in the {file} file)") }
        }
        other => other,
    }
}

fn int(tok: &str, line: usize, what: impl Fn() -> String) -> Result<i64> {
    tok.parse::<i64>()
        .map_err(|_| Error::parse(line, format!("expected {} (an integer), found {}", what(), shown(tok))))
}

/// Reads the header line of a file: its integers, at least `min` of them.
fn header<'a>(
    lines: &mut impl Iterator<Item = (usize, &'a str)>,
    file: &str,
    fields: &str,
    min: usize,
) -> Result<(usize, Vec<i64>)> {
    let Some((line, text)) = lines.next() else {
        return Err(Error::Empty(format!("the {file} file has no header line ({fields})")));
    };
    let mut v = Vec::new();
    for t in text.split_whitespace() {
        v.push(int(t, line, || format!("a header value ({fields})"))?);
    }
    if v.len() < min {
        return Err(Error::parse(line, format!("the header must give {fields}, found {}", shown(text))));
    }
    Ok((line, v))
}

pub(crate) fn read(node: &str, ele: &str) -> Result<Mesh> {
    parse(node, ele)?.build().map_err(|e| in_file(e, ".ele"))
}

/// What a `.node`/`.ele` pair holds, before it is built: triangles, or TetGen's tetrahedra.
pub(crate) fn parse(node: &str, ele: &str) -> Result<MeshBuilder> {
    let mut b = MeshBuilder::new();
    let (base, marks, dim) = read_nodes(node, &mut b).map_err(|e| in_file(e, ".node"))?;
    // the file's own node numbers, from its first: messages name the nodes so
    b.number_nodes(crate::error::Numbering::From(base.max(0) as u64));
    read_elements(ele, base, dim, &mut b).map_err(|e| in_file(e, ".ele"))?;
    b.fixed = match marks {
        Some(m) => FixedSpec::BoundaryAnd(m),
        None => FixedSpec::Boundary,
    };
    Ok(b)
}

/// [`parse`] then built as a model ([`Model::build`](crate::model::Model::build)): a planar mesh, or
/// TetGen's tetrahedra; errors say which file.
pub(crate) fn read_model(node: &str, ele: &str) -> Result<crate::model::Model> {
    crate::model::Model::build(parse(node, ele)?).map_err(|e| in_file(e, ".ele"))
}

/// Reads the nodes; returns the first node number, the boundary marks, if any, and the
/// dimension (2: Triangle, 3: TetGen).
fn read_nodes(text: &str, b: &mut MeshBuilder) -> Result<(i64, Option<Vec<bool>>, i64)> {
    let mut lines = content_lines(text, Some('#'));
    let (hl, h) = header(&mut lines, ".node", "nodes, dimension, attributes, boundary markers", 1)?;
    let count = h[0];
    let dim = h.get(1).copied().unwrap_or(2);
    let attrs = h.get(2).copied().unwrap_or(0);
    let nmark = h.get(3).copied().unwrap_or(0);
    if dim != 2 && dim != 3 {
        return Err(Error::parse(hl, format!("the dimension must be 2 (Triangle) or 3 (TetGen), found {dim}")));
    }
    if attrs < 0 || !(0..=1).contains(&nmark) || count < 0 {
        return Err(Error::parse(
            hl,
            "the node count and attribute count must be non-negative, the marker count 0 or 1",
        ));
    }
    let n = check_count(count as u64, text.len() as u64, 6, "nodes", hl)?;
    // No line can hold more attributes than the file has bytes; checked first so that
    // the field count below cannot overflow (a 32-bit usize in the page's wasm).
    let attrs = check_count(attrs as u64, text.len() as u64, 2, "attributes per node", hl)?;
    let per = 1 + dim as usize + attrs + nmark as usize;
    *b = MeshBuilder::with_capacity(n, 0);
    let mut marks = (nmark == 1).then(|| Vec::with_capacity(prealloc(n)));
    let mut base = 0;
    for i in 0..n {
        let Some((line, text)) = lines.next() else {
            return Err(Error::parse(hl, format!("the header announces {n} nodes, but the file ends after {i}")));
        };
        let f: Vec<&str> = text.split_whitespace().collect();
        if f.len() != per {
            return Err(Error::parse(
                line,
                format!(
                    "a node line has {per} values here (number, {}, {attrs} attribute(s), {nmark} marker(s), \
                     as the header at line {hl} says), found {}",
                    if dim == 2 { "x, y" } else { "x, y, z" },
                    f.len()
                ),
            ));
        }
        let number = int(f[0], line, || "the node number".into())?;
        if i == 0 {
            if number != 0 && number != 1 {
                return Err(Error::parse(line, format!("the first node must be numbered 0 or 1, found {number}")));
            }
            base = number;
        } else if number != base + i as i64 {
            return Err(Error::parse(
                line,
                format!("node numbers must be consecutive: expected {}, found {number}", base + i as i64),
            ));
        }
        let x = parse_f64(f[1], line, || format!("the x coordinate of node {number}"))?;
        let y = parse_f64(f[2], line, || format!("the y coordinate of node {number}"))?;
        let z = if dim == 3 { parse_f64(f[3], line, || format!("the z coordinate of node {number}"))? } else { 0.0 };
        b.add_node([x, y, z], line);
        if let Some(m) = marks.as_mut() {
            m.push(int(f[per - 1], line, || format!("the boundary marker of node {number}"))? != 0);
        }
    }
    if let Some((line, text)) = lines.next() {
        return Err(Error::parse(
            line,
            format!("unexpected {} after the {n} nodes the header (line {hl}) announces", shown(text)),
        ));
    }
    Ok((base, marks, dim))
}

fn read_elements(text: &str, base: i64, dim: i64, b: &mut MeshBuilder) -> Result<()> {
    if dim == 3 {
        return read_tetrahedra(text, base, b);
    }
    let mut lines = content_lines(text, Some('#'));
    let (hl, h) = header(&mut lines, ".ele", "triangles, nodes per triangle, attributes", 2)?;
    let (count, per, attrs) = (h[0], h[1], h.get(2).copied().unwrap_or(0));
    let kind = match per {
        3 => ElementKind::Tri3,
        6 => ElementKind::Tri6,
        _ => {
            return Err(Error::unsupported(Some(hl), format!("triangles with {per} nodes are not supported (3 or 6)")))
        }
    };
    if count < 0 || attrs < 0 {
        return Err(Error::parse(hl, "the triangle and attribute counts must be non-negative"));
    }
    let m = check_count(count as u64, text.len() as u64, 8, "triangles", hl)?;
    let attrs = check_count(attrs as u64, text.len() as u64, 2, "attributes per triangle", hl)?;
    let np = b.node_count() as i64;
    let fields = 1 + per as usize + attrs;
    let mut ids = [0u32; 6];
    for i in 0..m {
        let Some((line, text)) = lines.next() else {
            return Err(Error::parse(hl, format!("the header announces {m} triangles, but the file ends after {i}")));
        };
        let f: Vec<&str> = text.split_whitespace().collect();
        if f.len() != fields {
            return Err(Error::parse(
                line,
                format!(
                    "a triangle line has {fields} values here (number, {per} nodes, {attrs} attribute(s), as the \
                     header at line {hl} says), found {}",
                    f.len()
                ),
            ));
        }
        // its number as the file writes it, for messages
        let number = u64::try_from(int(f[0], line, || "the triangle number".into())?).unwrap_or(i as u64);
        for (ours, &theirs) in TRIANGLE_ORDER[..per as usize].iter().enumerate() {
            let v = int(f[1 + theirs], line, || format!("node {} of triangle {i}", theirs + 1))?;
            if v < base || v >= base + np {
                return Err(Error::element(
                    number,
                    Some(line),
                    format!("node {v} is out of range: the .node file numbers its nodes {base} to {}", base + np - 1),
                ));
            }
            ids[ours] = (v - base) as u32;
        }
        if let Some(v) = repeated(&ids[..per as usize]) {
            return Err(Error::element(
                number,
                Some(line),
                format!("node {} appears twice in the triangle", v as i64 + base),
            ));
        }
        b.add_element_numbered(kind, &ids[..per as usize], line, number);
    }
    if let Some((line, text)) = lines.next() {
        return Err(Error::parse(
            line,
            format!("unexpected {} after the {m} triangles the header (line {hl}) announces", shown(text)),
        ));
    }
    Ok(())
}

/// TetGen's `.ele`: a header `m 4|10 attributes`, then `number n1 … n4 [n5 … n10]
/// [attributes]` (see the module docs for the order of the extra nodes).
fn read_tetrahedra(text: &str, base: i64, b: &mut MeshBuilder) -> Result<()> {
    let mut lines = content_lines(text, Some('#'));
    let (hl, h) = header(&mut lines, ".ele", "tetrahedra, nodes per tetrahedron, attributes", 2)?;
    let (count, per, attrs) = (h[0], h[1], h.get(2).copied().unwrap_or(0));
    if per != 4 && per != 10 {
        return Err(Error::unsupported(Some(hl), format!("tetrahedra with {per} nodes are not supported (4 or 10)")));
    }
    if count < 0 || attrs < 0 {
        return Err(Error::parse(hl, "the tetrahedron and attribute counts must be non-negative"));
    }
    let m = check_count(count as u64, text.len() as u64, 10, "tetrahedra", hl)?;
    let attrs = check_count(attrs as u64, text.len() as u64, 2, "attributes per tetrahedron", hl)?;
    let np = b.node_count() as i64;
    let per = per as usize;
    let kind = crate::mesh::VolumeKind::with_nodes(per).expect("4 or 10 nodes, checked above");
    let fields = 1 + per + attrs;
    let mut ids = [0u32; 10];
    for i in 0..m {
        let Some((line, text)) = lines.next() else {
            return Err(Error::parse(hl, format!("the header announces {m} tetrahedra, but the file ends after {i}")));
        };
        let f: Vec<&str> = text.split_whitespace().collect();
        if f.len() != fields {
            return Err(Error::parse(
                line,
                format!(
                    "a tetrahedron line has {fields} values here (number, {per} nodes, {attrs} attribute(s), as the \
                     header at line {hl} says), found {}",
                    f.len()
                ),
            ));
        }
        let number = u64::try_from(int(f[0], line, || "the tetrahedron number".into())?).unwrap_or(i as u64);
        for (j, id) in ids[..per].iter_mut().enumerate() {
            let v = int(f[1 + j], line, || format!("node {} of tetrahedron {i}", j + 1))?;
            if v < base || v >= base + np {
                return Err(Error::element(
                    number,
                    Some(line),
                    format!("node {v} is out of range: the .node file numbers its nodes {base} to {}", base + np - 1),
                ));
            }
            *id = (v - base) as u32;
        }
        if let Some(v) = repeated(&ids[..per]) {
            return Err(Error::element(
                number,
                Some(line),
                format!("node {} appears twice in the tetrahedron", v as i64 + base),
            ));
        }
        b.add_volume_element_numbered(kind, &ids[..per], line, number)?;
    }
    if let Some((line, text)) = lines.next() {
        return Err(Error::parse(
            line,
            format!("unexpected {} after the {m} tetrahedra the header (line {hl}) announces", shown(text)),
        ));
    }
    Ok(())
}

/// Writes a triangle mesh as a `.node` and an `.ele` text (1-based, markers = fixed flags).
/// Why a Triangle file cannot keep a mesh's 3D plane, when it had one: `.node` holds 2D
/// points, so the coordinates written are those in the mesh's own plane.
pub fn flat_note(mesh: &Mesh) -> Option<String> {
    let p = mesh.plane?;
    Some(format!(
        "the mesh lay in a 3D plane (through {:?} along {:?} and {:?}); Triangle's .node holds 2D points, \
         so these are its coordinates in that plane (write .msh, .vtk, .obj, .off or .mesh to keep the plane)",
        p.origin.to_array(),
        p.u.to_array(),
        p.w.to_array()
    ))
}

/// The one kind of triangles of the mesh, or why Triangle's files cannot hold it.
pub(crate) fn writable(w: super::Writable) -> Result<ElementKind> {
    if w.points.is_some() {
        return Err(Error::invalid(
            "Triangle's .node holds 2D points and this mesh is a surface in 3D; write .msh, .vtk, .obj, .off or .mesh instead",
        ));
    }
    let mesh = w.mesh;
    let kind = mesh.kind(0);
    if let Some(e) = (0..mesh.element_count()).find(|&e| mesh.kind(e) != kind || !kind.is_triangle()) {
        return Err(Error::invalid(format!(
            "Triangle's .ele holds triangles of one kind only, but element {e} is a {} (element 0 is a {}); \
             write .msh or .vtk instead",
            mesh.kind(e).name(),
            kind.name()
        )));
    }
    Ok(kind)
}

pub(crate) fn write(w: super::Writable, node: &mut Out, ele: &mut Out) -> Result<()> {
    let kind = writable(w)?;
    let mesh = w.mesh;
    let _ = writeln!(node, "# written by smoothlab: number x y boundary-marker (1 = fixed)");
    if let Some(note) = flat_note(mesh) {
        let _ = writeln!(node, "# {note}");
    }
    let _ = writeln!(node, "{} 2 0 1", mesh.node_count());
    for (i, p) in mesh.nodes().iter().enumerate() {
        let _ = writeln!(node, "{} {:?} {:?} {}", i + 1, p.x, p.y, u8::from(mesh.fixed()[i]));
    }
    let per = kind.node_count();
    let _ = writeln!(ele, "{} {per} 0", mesh.element_count());
    let mut theirs = [0u32; 6];
    for e in 0..mesh.element_count() {
        let ids = w.element(e);
        for (ours, &t) in TRIANGLE_ORDER[..per].iter().enumerate() {
            theirs[t] = ids[ours];
        }
        let _ = write!(ele, "{}", e + 1);
        for &i in &theirs[..per] {
            let _ = write!(ele, " {}", i + 1);
        }
        ele.push('\n');
    }
    Ok(())
}
