//! Wavefront OBJ and Geomview OFF: triangles and quads (linear only).
//!
//! OBJ: `v x y [z]`, `f a b c [d]` with `a`, `a/t`, `a//n`, `a/t/n` and negative
//! (relative) indices; `#` comments; every other statement is ignored. OFF: an `OFF`
//! (or `COFF`, `NOFF`, `CNOFF`) header, the counts `vertices faces edges`, the vertices
//! (`x y z`, extra values such as colours ignored) and the faces `k i1 … ik` (0-based;
//! trailing colour values ignored); `#` comments. Faces of more than 4 vertices are
//! refused naming the line.
//!
//! Written: vertices at full `f64` precision (z = 0) and the faces. Neither format has
//! fixed flags, so reading back gives the same nodes and elements with fixed = boundary.

use std::fmt::Write as _;

use crate::error::{Error, Numbering, Result};
use crate::io::lex::{check_count, content_lines, parse_f64, repeated, shown};
use crate::io::out::Out;
use crate::mesh::{ElementKind, Mesh, MeshBuilder};

fn face_kind(k: usize, line: usize, what: &str) -> Result<ElementKind> {
    match k {
        3 => Ok(ElementKind::Tri3),
        4 => Ok(ElementKind::Quad4),
        0..=2 => Err(Error::parse(line, format!("{what} has {k} vertices; a face needs at least 3"))),
        _ => Err(Error::unsupported(
            Some(line),
            format!("{what} has {k} vertices: polygons are not supported (smoothlab reads triangles and quads)"),
        )),
    }
}

/// Reads an OBJ file.
pub(crate) fn parse_obj(text: &str) -> Result<MeshBuilder> {
    let mut b = MeshBuilder::new();
    // Faces as 0-based vertex indices (checked once all vertices are known).
    let mut faces: Vec<(ElementKind, [i64; 4], usize)> = Vec::new();
    for (line, l) in content_lines(text, Some('#')) {
        let mut f = l.split_whitespace();
        match f.next() {
            Some("v") => {
                let mut c = [0.0; 3];
                let mut k = 0;
                for (i, t) in f.take(3).enumerate() {
                    c[i] = parse_f64(t, line, || format!("coordinate {} of vertex {}", i + 1, b.node_count() + 1))?;
                    k += 1;
                }
                if k < 2 {
                    return Err(Error::parse(line, format!("a vertex needs at least x and y, found {}", shown(l))));
                }
                b.add_node(c, line);
            }
            Some("f") => {
                let refs: Vec<&str> = f.collect();
                let kind = face_kind(refs.len(), line, &format!("face {}", faces.len() + 1))?;
                let mut ids = [0i64; 4];
                for (j, r) in refs.iter().enumerate() {
                    let v = r.split('/').next().unwrap_or("");
                    let i: i64 = v.parse().map_err(|_| {
                        Error::parse(
                            line,
                            format!("expected a vertex index for corner {} of the face, found {}", j + 1, shown(r)),
                        )
                    })?;
                    let nv = b.node_count() as i64;
                    ids[j] = match i {
                        0 => {
                            return Err(Error::parse(
                                line,
                                "vertex index 0 is invalid: OBJ counts from 1 (or -1 for the last)",
                            ))
                        }
                        i if i > 0 => i - 1,
                        // `i >= -nv`, not `-i <= nv`: the negation of i64::MIN overflows.
                        i if i >= -nv => nv + i,
                        i => return Err(Error::parse(
                            line,
                            format!(
                                "relative vertex index {i} reaches before the first vertex (valid here: -1 to -{nv})"
                            ),
                        )),
                    };
                }
                faces.push((kind, ids, line));
            }
            _ => {}
        }
    }
    let nv = b.node_count() as i64;
    // OBJ counts its vertices from 1, and its faces so in these messages
    b.number_nodes(Numbering::From(1));
    let mut ids = [0u32; 4];
    for (e, (kind, f, line)) in faces.iter().enumerate() {
        let number = e as u64 + 1;
        for j in 0..kind.node_count() {
            if f[j] >= nv {
                return Err(Error::element(
                    number,
                    Some(*line),
                    format!("vertex index {} is out of range: the file has {nv} vertices (1 to {nv})", f[j] + 1),
                ));
            }
            ids[j] = f[j] as u32;
        }
        if let Some(v) = repeated(&ids[..kind.node_count()]) {
            return Err(Error::element(number, Some(*line), format!("vertex {} appears twice in the face", v + 1)));
        }
        b.add_element_numbered(*kind, &ids[..kind.node_count()], *line, number);
    }
    Ok(b)
}

/// Reads an OFF file.
pub(crate) fn parse_off(text: &str) -> Result<MeshBuilder> {
    let mut lines = content_lines(text, Some('#'));
    let Some((hl, head)) = lines.next() else {
        return Err(Error::Empty("the OFF file is empty".into()));
    };
    let mut tokens = head.split_whitespace();
    let magic = tokens.next().unwrap_or("");
    if !matches!(magic, "OFF" | "COFF" | "NOFF" | "CNOFF") {
        return Err(Error::parse(
            hl,
            format!("not an OFF file: expected 'OFF' on the first line, found {}", shown(magic)),
        ));
    }
    if tokens.clone().next().is_some_and(|t| t.eq_ignore_ascii_case("BINARY")) {
        return Err(Error::unsupported(Some(hl), "binary OFF files are not supported"));
    }
    let mut counts: Vec<(&str, usize)> = tokens.map(|t| (t, hl)).collect();
    if counts.is_empty() {
        let Some((l, t)) = lines.next() else {
            return Err(Error::parse(hl, "the file ends before the counts line (vertices faces edges)"));
        };
        counts = t.split_whitespace().map(|x| (x, l)).collect();
    }
    let cl = counts.first().map_or(hl, |c| c.1);
    if counts.len() < 2 {
        return Err(Error::parse(cl, "expected the counts 'vertices faces edges'"));
    }
    let count = |i: usize, what: &str| {
        counts[i]
            .0
            .parse::<u64>()
            .map_err(|_| Error::parse(cl, format!("expected the number of {what}, found {}", shown(counts[i].0))))
    };
    let room = text.len() as u64;
    let nv = check_count(count(0, "vertices")?, room, 6, "vertices", cl)?;
    let nf = check_count(count(1, "faces")?, room, 8, "faces", cl)?;
    let mut b = MeshBuilder::with_capacity(nv, nf);
    for i in 0..nv {
        let Some((line, l)) = lines.next() else {
            return Err(Error::parse(cl, format!("the counts announce {nv} vertices, but the file ends after {i}")));
        };
        let f: Vec<&str> = l.split_whitespace().take(3).collect();
        if f.len() < 3 {
            return Err(Error::parse(line, format!("vertex {i} needs x y z, found {}", shown(l))));
        }
        let mut c = [0.0; 3];
        for (j, t) in f.iter().enumerate() {
            c[j] = parse_f64(t, line, || format!("coordinate {} of vertex {i}", j + 1))?;
        }
        b.add_node(c, line);
    }
    let mut ids = [0u32; 4];
    for e in 0..nf {
        let Some((line, l)) = lines.next() else {
            return Err(Error::parse(cl, format!("the counts announce {nf} faces, but the file ends after {e}")));
        };
        let mut f = l.split_whitespace();
        let k = f.next().unwrap_or("");
        let k: usize = k
            .parse()
            .map_err(|_| Error::parse(line, format!("expected the vertex count of face {e}, found {}", shown(k))))?;
        let kind = face_kind(k, line, &format!("face {e}"))?;
        for (j, id) in ids.iter_mut().enumerate().take(k) {
            let t =
                f.next().ok_or_else(|| Error::parse(line, format!("face {e} announces {k} vertices but lists {j}")))?;
            let v: u64 = t.parse().map_err(|_| {
                Error::parse(line, format!("expected vertex index {j} of face {e}, found {}", shown(t)))
            })?;
            if v >= nv as u64 {
                return Err(Error::element(
                    e,
                    Some(line),
                    format!(
                        "vertex index {v} is out of range: the file has {nv} vertices (0 to {})",
                        nv.saturating_sub(1)
                    ),
                ));
            }
            *id = v as u32;
        }
        if let Some(v) = repeated(&ids[..k]) {
            return Err(Error::element(e, Some(line), format!("vertex {v} appears twice in the face")));
        }
        b.add_element(kind, &ids[..k], line);
    }
    if let Some((line, l)) = lines.next() {
        return Err(Error::parse(
            line,
            format!("unexpected {} after the {nv} vertices and {nf} faces the counts (line {cl}) announce", shown(l)),
        ));
    }
    Ok(b)
}

pub(crate) fn linear_only(mesh: &Mesh, format: &str) -> Result<()> {
    match mesh.kinds().iter().position(|k| k.is_quadratic()) {
        Some(e) => Err(Error::invalid(format!(
            "{format} holds linear triangles and quads only, but element {e} is a {}; write .msh or .vtk instead",
            mesh.kind(e).name()
        ))),
        None => Ok(()),
    }
}

/// Writes an OBJ file (linear meshes only).
pub(crate) fn write_obj(w: super::Writable, s: &mut Out) -> Result<()> {
    let mesh = w.mesh;
    linear_only(mesh, "OBJ")?;
    s.push_str("# written by smoothlab\n");
    for i in 0..mesh.node_count() {
        s.push_str("v ");
        w.write_xyz(s, i);
        s.push('\n');
    }
    for e in 0..mesh.element_count() {
        s.push('f');
        for &i in w.element(e).iter() {
            let _ = write!(s, " {}", i + 1);
        }
        s.push('\n');
    }
    Ok(())
}

/// Writes an OFF file (linear meshes only).
pub(crate) fn write_off(w: super::Writable, s: &mut Out) -> Result<()> {
    let mesh = w.mesh;
    linear_only(mesh, "OFF")?;
    let _ = writeln!(s, "OFF\n{} {} 0", mesh.node_count(), mesh.element_count());
    for i in 0..mesh.node_count() {
        w.write_xyz(s, i);
        s.push('\n');
    }
    for e in 0..mesh.element_count() {
        let ids = w.element(e);
        let _ = write!(s, "{}", ids.len());
        for &i in ids.iter() {
            let _ = write!(s, " {i}");
        }
        s.push('\n');
    }
    Ok(())
}
