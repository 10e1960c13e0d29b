//! Shewchuk's Triangle `.node` / `.ele` pair.
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
        Error::Unsupported { line, message } => Error::Unsupported { line, message: format!("{message} (in the {file} file)") },
        other => other,
    }
}

fn int(tok: &str, line: usize, what: impl Fn() -> String) -> Result<i64> {
    tok.parse::<i64>()
        .map_err(|_| Error::parse(line, format!("expected {} (an integer), found {}", what(), shown(tok))))
}

/// Reads the header line of a file: its integers, at least `min` of them.
fn header<'a>(lines: &mut impl Iterator<Item = (usize, &'a str)>, file: &str, fields: &str, min: usize) -> Result<(usize, Vec<i64>)> {
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
    let mut b = MeshBuilder::new();
    let (base, marks) = read_nodes(node, &mut b).map_err(|e| in_file(e, ".node"))?;
    read_elements(ele, base, &mut b).map_err(|e| in_file(e, ".ele"))?;
    b.fixed = match marks {
        Some(m) => FixedSpec::BoundaryAnd(m),
        None => FixedSpec::Boundary,
    };
    b.build().map_err(|e| in_file(e, ".ele"))
}

/// Reads the nodes; returns the first node number and the boundary marks, if any.
fn read_nodes(text: &str, b: &mut MeshBuilder) -> Result<(i64, Option<Vec<bool>>)> {
    let mut lines = content_lines(text, Some('#'));
    let (hl, h) = header(&mut lines, ".node", "nodes, dimension, attributes, boundary markers", 1)?;
    let count = h[0];
    let dim = h.get(1).copied().unwrap_or(2);
    let attrs = h.get(2).copied().unwrap_or(0);
    let nmark = h.get(3).copied().unwrap_or(0);
    if dim != 2 {
        return Err(Error::parse(hl, format!("Triangle meshes are 2D: the dimension must be 2, found {dim}")));
    }
    if attrs < 0 || !(0..=1).contains(&nmark) || count < 0 {
        return Err(Error::parse(hl, "the node count and attribute count must be non-negative, the marker count 0 or 1"));
    }
    let n = check_count(count as u64, text.len() as u64, 6, "nodes", hl)?;
    // No line can hold more attributes than the file has bytes; checked first so that
    // the field count below cannot overflow (a 32-bit usize in the page's wasm).
    let attrs = check_count(attrs as u64, text.len() as u64, 2, "attributes per node", hl)?;
    let per = 3 + attrs + nmark as usize;
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
                    "a node line has {per} values here (number, x, y, {attrs} attribute(s), {nmark} marker(s), \
                     as the header at line {hl} says), found {}",
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
        b.add_node([x, y, 0.0], line);
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
    Ok((base, marks))
}

fn read_elements(text: &str, base: i64, b: &mut MeshBuilder) -> Result<()> {
    let mut lines = content_lines(text, Some('#'));
    let (hl, h) = header(&mut lines, ".ele", "triangles, nodes per triangle, attributes", 2)?;
    let (count, per, attrs) = (h[0], h[1], h.get(2).copied().unwrap_or(0));
    let kind = match per {
        3 => ElementKind::Tri3,
        6 => ElementKind::Tri6,
        _ => return Err(Error::unsupported(Some(hl), format!("triangles with {per} nodes are not supported (3 or 6)"))),
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
        int(f[0], line, || "the triangle number".into())?;
        for (ours, &theirs) in TRIANGLE_ORDER[..per as usize].iter().enumerate() {
            let v = int(f[1 + theirs], line, || format!("node {} of triangle {i}", theirs + 1))?;
            if v < base || v >= base + np {
                return Err(Error::element(
                    i,
                    Some(line),
                    format!("node {v} is out of range: the .node file numbers its nodes {base} to {}", base + np - 1),
                ));
            }
            ids[ours] = (v - base) as u32;
        }
        if let Some(v) = repeated(&ids[..per as usize]) {
            return Err(Error::element(i, Some(line), format!("node {} appears twice in the triangle", v as i64 + base)));
        }
        b.add_element(kind, &ids[..per as usize], line);
    }
    if let Some((line, text)) = lines.next() {
        return Err(Error::parse(
            line,
            format!("unexpected {} after the {m} triangles the header (line {hl}) announces", shown(text)),
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
         so these are its coordinates in that plane (write .msh, .vtk, .obj or .off to keep the plane)",
        p.origin.to_array(),
        p.u.to_array(),
        p.w.to_array()
    ))
}

/// The one kind of triangles of the mesh, or why Triangle's files cannot hold it.
pub(crate) fn writable(w: super::Writable) -> Result<ElementKind> {
    if w.points.is_some() {
        return Err(Error::invalid(
            "Triangle's .node holds 2D points and this mesh is a surface in 3D; write .msh, .vtk, .obj or .off instead",
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
        let ids = mesh.element(e);
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
