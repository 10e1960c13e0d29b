//! Gmsh `.msh` ASCII, versions 2.2 (also 2.0, 2.1) and 4.1.
//!
//! Read: `$MeshFormat`, `$Nodes`, `$Elements` in both layouts (4.1: entity blocks with
//! sparse, non-contiguous tags), and a `$NodeData` view named `fixed`; every other section
//! (`$PhysicalNames`, `$Entities`, `$Periodic`, other views, …) is skipped. Element types
//! 2 (tri3), 3 (quad4), 9 (tri6), 16 (quad8), 10 (quad9) become elements; the volume
//! elements of [`VolumeKind`] by their rows' `gmsh_type` — 4 (tetrahedron), 5 (hexahedron),
//! 6 (prism), 7 (pyramid), 11 (10-node tetrahedron), 17 (20-node hexahedron), 12 (27-node
//! hexahedron) — are put from Gmsh's node order into ours by the row's `gmsh_order` (a
//! volume file's triangles and quads are then its given faces); lines (1, 8) and points
//! (15) mark their nodes as fixed (on top of the boundary); anything else is refused naming
//! the line and the type.
//!
//! Written: nodes with tags `1..=n` at full `f64` precision, the elements in order, and
//! the fixed flags as a one-component `$NodeData` view named `"fixed"` (1 = fixed). When
//! that view is present it decides the fixed flags exactly, so nodes, elements, kinds and
//! fixed flags all round-trip; files from Gmsh itself (no such view) get boundary nodes
//! plus the nodes of line and point elements.
//!
//! One writer per format version ([`write`]): each takes any mesh through [`MshSource`]
//! (a planar mesh or surface, a volume with its file's faces), the elements' Gmsh types
//! from their kinds.

use crate::error::{Error, Numbering, Result};
use crate::io::lex::{prealloc, repeated, shown, Lexer};
use crate::io::volume::{volume_codes, MAX_VOLUME_NODES};
use crate::mesh::{ElementKind, FixedSpec, MeshBuilder, VolumeKind, NONE};

mod write;
pub(crate) use write::{type_of, write, MshBlock, MshSource};
#[cfg(test)]
use write::runs;

/// What a Gmsh element type is to us.
enum GmshType {
    Surface(ElementKind),
    /// A volume element ([`crate::volume`]), of the kind whose Gmsh type it is.
    Solid(VolumeKind),
    /// Lines and points: their nodes are marked fixed.
    Marker(usize),
    /// The element's name in Gmsh's terms and, for a kind a reader of the mesh knows by
    /// name, that name in plain words (plural), which the message leads with.
    Unsupported(&'static str, Option<&'static str>),
}

fn gmsh_type(t: u64) -> GmshType {
    use GmshType::*;
    if let Some(kind) = VolumeKind::from_gmsh_type(t) {
        return Solid(kind);
    }
    match t {
        2 => Surface(ElementKind::Tri3),
        3 => Surface(ElementKind::Quad4),
        9 => Surface(ElementKind::Tri6),
        16 => Surface(ElementKind::Quad8),
        10 => Surface(ElementKind::Quad9),
        1 => Marker(2),
        8 => Marker(3),
        15 => Marker(1),
        13 => Unsupported("18-node prism", Some("quadratic prisms (wedges)")),
        14 => Unsupported("14-node pyramid", Some("quadratic pyramids")),
        18 => Unsupported("15-node prism", Some("quadratic prisms (wedges)")),
        19 => Unsupported("13-node pyramid", Some("quadratic pyramids")),
        20 => Unsupported("9-node incomplete cubic triangle", Some("cubic triangles")),
        21 => Unsupported("10-node cubic triangle", Some("cubic triangles")),
        22..=25 => Unsupported("higher-order triangle", Some("triangles above second order")),
        26..=28 => Unsupported("higher-order line", Some("lines above second order")),
        _ => Unsupported("unknown type", None),
    }
}

/// What smoothlab reads of a `.msh` file, said after a refused element type.
fn gmsh_reads() -> String {
    format!(
        "smoothlab reads triangles (types 2, 9), quads (3, 16, 10) and the volume elements {}, and takes \
         lines (1, 8) and points (15) as fixed nodes",
        volume_codes(|r| r.gmsh_type)
    )
}

/// The refusal of element type `t` (given at `line`): in plain words first when the kind
/// has a name people know (`hexahedra are not supported yet: line 17: Gmsh element type 5
/// (8-node hexahedron); smoothlab reads …`).
fn unsupported_type(t: u64, line: usize) -> Error {
    let GmshType::Unsupported(name, words) = gmsh_type(t) else { unreachable!("only called for unsupported types") };
    match words {
        Some(words) => Error::unsupported_kind(
            format!("{words} are not supported yet"),
            line,
            format!("Gmsh element type {t} ({name}); {}", gmsh_reads()),
        ),
        None => {
            Error::unsupported(Some(line), format!("Gmsh element type {t} ({name}) is not supported: {}", gmsh_reads()))
        }
    }
}

/// Node tags → 0-based node indices, without an array sized by the largest tag unless
/// the tags are dense enough for that to be small.
#[derive(Debug)]
enum TagMap {
    Dense { min: u64, index: Vec<u32> },
    Sorted(Vec<(u64, u32)>),
}

impl TagMap {
    /// Builds the map; a tag given twice is an error naming both lines.
    fn new(tags: &[u64], lines: &[u32]) -> Result<TagMap> {
        let n = tags.len();
        let (Some(&min), Some(&max)) = (tags.iter().min(), tags.iter().max()) else {
            return Ok(TagMap::Sorted(Vec::new()));
        };
        let dup = |first: u32, second: u32, tag: u64| {
            Error::node(
                tag,
                Some(lines[second as usize] as usize),
                format!("node tag {tag} is defined twice (first at line {})", lines[first as usize]),
            )
        };
        if max - min < 2 * n as u64 + 1024 {
            let mut index = vec![NONE; (max - min + 1) as usize];
            for (i, &t) in tags.iter().enumerate() {
                let slot = &mut index[(t - min) as usize];
                if *slot != NONE {
                    return Err(dup(*slot, i as u32, t));
                }
                *slot = i as u32;
            }
            Ok(TagMap::Dense { min, index })
        } else {
            let mut v: Vec<(u64, u32)> = tags.iter().enumerate().map(|(i, &t)| (t, i as u32)).collect();
            v.sort_unstable();
            if let Some(w) = v.windows(2).find(|w| w[0].0 == w[1].0) {
                return Err(dup(w[0].1, w[1].1, w[0].0));
            }
            Ok(TagMap::Sorted(v))
        }
    }

    fn get(&self, tag: u64) -> Option<u32> {
        match self {
            TagMap::Dense { min, index } => {
                let i = tag.checked_sub(*min)?;
                index.get(usize::try_from(i).ok()?).copied().filter(|&v| v != NONE)
            }
            TagMap::Sorted(v) => v.binary_search_by_key(&tag, |p| p.0).ok().map(|i| v[i].1),
        }
    }
}

/// An element as read: kind, file line and where its node tags start in the tag list.
struct RawElement {
    kind: ElementKind,
    line: u32,
    start: u32,
    /// Its tag in the file.
    tag: u64,
}

struct Reader {
    builder: MeshBuilder,
    node_tags: Vec<u64>,
    /// Node tags → indices, made when `$Elements` follows `$Nodes` (as it does in every
    /// file Gmsh writes): the elements then go straight into the builder as indices,
    /// and `elements` and `elem_tags` stay empty.
    map: Option<TagMap>,
    /// In that case, the first element that names an undefined node tag or one tag
    /// twice: reported when the whole file has been read, as the raw elements' errors are.
    element_error: Option<Error>,
    /// Surface elements read so far.
    surface_elements: usize,
    /// The elements as read, when `$Elements` comes before `$Nodes` (or the node tags
    /// repeat): resolved when the whole file has been read.
    elements: Vec<RawElement>,
    elem_tags: Vec<u64>,
    /// Node tags of line and point elements, with their lines.
    marks: Vec<(u64, u32)>,
    /// Volume elements as read (node tags, their kind's count each, in Gmsh's order) with
    /// their lines, kinds and tags: resolved when the whole file has been read.
    solid_tags: Vec<u64>,
    solid_lines: Vec<(u32, VolumeKind, u64)>,
    /// The `fixed` view: (node tag, fixed, line).
    fixed_view: Option<Vec<(u64, bool, u32)>>,
    /// Line of the `$NodeData` section of the `fixed` view.
    fixed_view_line: Option<usize>,
    nodes_line: Option<usize>,
    elements_line: Option<usize>,
}

#[derive(Clone, Copy, PartialEq)]
enum Layout {
    V2,
    V41,
}

/// Reads a `.msh` file (ASCII 2.x or 4.1) into a builder (see [`super::parse_str`]).
pub(crate) fn parse(text: &str) -> Result<MeshBuilder> {
    let mut lex = Lexer::new(text);
    let first = lex.expect(|| "'$MeshFormat' (an empty file is not a mesh)".into())?;
    match first.text {
        "$MeshFormat" => {}
        "$NOD" | "$NOE" => {
            return Err(Error::unsupported(
                Some(first.line),
                "this is a version 1 .msh file; save it as version 2.2 or 4.1 (ASCII)",
            ))
        }
        other => {
            return Err(Error::parse(
                first.line,
                format!("not a Gmsh .msh file: expected '$MeshFormat', found {}", shown(other)),
            ))
        }
    }
    let v = lex.expect(|| "the .msh version (2.2 or 4.1)".into())?;
    let layout = match v.text {
        "2" | "2.0" | "2.1" | "2.2" => Layout::V2,
        "4.1" => Layout::V41,
        "4" | "4.0" => {
            return Err(Error::unsupported(
                Some(v.line),
                ".msh version 4.0 is not supported; save as 4.1 or 2.2 (ASCII)",
            ))
        }
        other => {
            return Err(Error::unsupported(
                Some(v.line),
                format!(".msh version {} is not supported; smoothlab reads 2.2 and 4.1 (ASCII)", shown(other)),
            ))
        }
    };
    let (file_type, ft_line) = lex.u64(|| "the file type (0 for ASCII)".into())?;
    if file_type != 0 {
        return Err(Error::unsupported(
            Some(ft_line),
            "binary .msh files are not supported; save as ASCII (Gmsh option Mesh.Binary = 0)",
        ));
    }
    lex.u64(|| "the data size".into())?;
    end_of(&mut lex, "MeshFormat", first.line)?;

    let mut r = Reader {
        builder: MeshBuilder::new(),
        node_tags: Vec::new(),
        map: None,
        element_error: None,
        surface_elements: 0,
        elements: Vec::new(),
        elem_tags: Vec::new(),
        marks: Vec::new(),
        solid_tags: Vec::new(),
        solid_lines: Vec::new(),
        fixed_view: None,
        fixed_view_line: None,
        nodes_line: None,
        elements_line: None,
    };
    while let Some(t) = lex.next() {
        match t.text {
            "$Nodes" => {
                if let Some(l) = r.nodes_line {
                    return Err(Error::parse(t.line, format!("a second $Nodes section (the first is at line {l})")));
                }
                r.nodes_line = Some(t.line);
                match layout {
                    Layout::V2 => r.nodes_v2(&mut lex)?,
                    Layout::V41 => r.nodes_v41(&mut lex)?,
                }
                end_of(&mut lex, "Nodes", t.line)?;
            }
            "$Elements" => {
                if let Some(l) = r.elements_line {
                    return Err(Error::parse(t.line, format!("a second $Elements section (the first is at line {l})")));
                }
                r.elements_line = Some(t.line);
                if r.nodes_line.is_some() {
                    // a repeated tag leaves the map unmade: `finish` reports it
                    r.map = TagMap::new(&r.node_tags, r.builder.node_lines()).ok();
                }
                match layout {
                    Layout::V2 => r.elements_v2(&mut lex)?,
                    Layout::V41 => r.elements_v41(&mut lex)?,
                }
                end_of(&mut lex, "Elements", t.line)?;
            }
            "$NodeData" => r.node_data(&mut lex, t.line)?,
            s if s.starts_with('$') && !s.starts_with("$End") && s.len() > 1 => {
                skip_section(&mut lex, &s[1..], t.line)?
            }
            other => {
                return Err(Error::parse(
                    t.line,
                    format!("expected a section such as '$Nodes' or '$Elements', found {}", shown(other)),
                ))
            }
        }
    }
    if r.nodes_line.is_none() {
        return Err(Error::parse(lex.last_line(), "the file ends without a $Nodes section"));
    }
    if r.elements_line.is_none() {
        return Err(Error::parse(lex.last_line(), "the file ends without an $Elements section"));
    }
    r.finish()
}

/// Expects `$End<name>` for the section opened at `open_line`.
fn end_of(lex: &mut Lexer, name: &str, open_line: usize) -> Result<()> {
    let t = lex.expect(|| format!("'$End{name}' to close the section opened at line {open_line}"))?;
    if t.text.strip_prefix("$End") == Some(name) {
        Ok(())
    } else {
        Err(Error::parse(
            t.line,
            format!(
                "expected '$End{name}' to close the section opened at line {open_line}, found {} \
                 (does the count in the section's header match its data?)",
                shown(t.text)
            ),
        ))
    }
}

fn skip_section(lex: &mut Lexer, name: &str, open_line: usize) -> Result<()> {
    loop {
        let t = lex.expect(|| format!("'$End{name}' to close the section opened at line {open_line}"))?;
        if t.text.strip_prefix("$End") == Some(name) {
            return Ok(());
        }
    }
}

impl Reader {
    fn add_node(&mut self, lex: &mut Lexer, tag: u64, tag_line: usize, extra: usize) -> Result<()> {
        let i = self.node_tags.len();
        let what = |c: &str| format!("the {c} coordinate of node tag {tag} (line {tag_line})");
        let (x, line) = lex.f64(|| what("x"))?;
        let (y, _) = lex.f64(|| what("y"))?;
        let (z, _) = lex.f64(|| what("z"))?;
        for _ in 0..extra {
            lex.f64(|| format!("a parametric coordinate of node tag {tag}"))?;
        }
        debug_assert_eq!(self.builder.node_count(), i);
        self.builder.add_node([x, y, z], line);
        self.node_tags.push(tag);
        Ok(())
    }

    fn nodes_v2(&mut self, lex: &mut Lexer) -> Result<()> {
        let (n, line) = lex.u64(|| "the number of nodes".into())?;
        let n = lex.check_count(n, 8, "nodes", line)?;
        self.reserve_nodes(n);
        for i in 0..n {
            let (tag, tl) = lex.u64(|| format!("the tag of node {} of the {n} announced at line {line}", i + 1))?;
            self.add_node(lex, tag, tl, 0)?;
        }
        Ok(())
    }

    fn reserve_nodes(&mut self, n: usize) {
        // Only one $Nodes section is read, so the builder holds no nodes yet.
        self.builder = MeshBuilder::with_capacity(n, 0);
        self.node_tags.reserve(prealloc(n));
    }

    fn nodes_v41(&mut self, lex: &mut Lexer) -> Result<()> {
        let (blocks, bl) = lex.u64(|| "the number of node entity blocks".into())?;
        let blocks = lex.check_count(blocks, 8, "node entity blocks", bl)?;
        let (n, nl) = lex.u64(|| "the number of nodes".into())?;
        let n = lex.check_count(n, 8, "nodes", nl)?;
        lex.u64(|| "the smallest node tag".into())?;
        lex.u64(|| "the largest node tag".into())?;
        self.reserve_nodes(n);
        let mut tags = Vec::new();
        for b in 0..blocks {
            let what = |s: &str| format!("the {s} of node block {} of {blocks}", b + 1);
            let (dim, dl) = lex.u64(|| what("entity dimension"))?;
            if dim > 3 {
                return Err(Error::parse(dl, format!("node block entity dimension must be 0 to 3, found {dim}")));
            }
            lex.i64(|| what("entity tag"))?;
            let (parametric, pl) = lex.u64(|| what("parametric flag"))?;
            if parametric > 1 {
                return Err(Error::parse(pl, format!("the parametric flag must be 0 or 1, found {parametric}")));
            }
            let (count, cl) = lex.u64(|| what("node count"))?;
            let left = n - self.node_tags.len();
            if count > left as u64 {
                return Err(Error::parse(
                    cl,
                    format!("this block has {count} nodes, but only {left} of the {n} announced at line {nl} are left"),
                ));
            }
            tags.clear();
            for i in 0..count {
                tags.push(lex.u64(|| format!("tag {} of the {count} in the node block at line {dl}", i + 1))?);
            }
            let extra = if parametric == 1 { dim as usize } else { 0 };
            for &(tag, tl) in &tags {
                self.add_node(lex, tag, tl, extra)?;
            }
        }
        if self.node_tags.len() != n {
            return Err(Error::parse(
                nl,
                format!("the $Nodes header announces {n} nodes but its blocks hold {}", self.node_tags.len()),
            ));
        }
        Ok(())
    }

    /// Reads one element's node tags (the kind's count, or the marker's).
    fn element_nodes(
        &mut self,
        lex: &mut Lexer,
        ty: GmshType,
        (tag, line): (u64, usize),
        number: impl Fn() -> String,
    ) -> Result<()> {
        match ty {
            GmshType::Surface(kind) if self.map.is_some() => {
                let mut tags = [0u64; 9];
                for (j, tag) in tags[..kind.node_count()].iter_mut().enumerate() {
                    *tag = lex.u64(|| format!("node {} of {} ({})", j + 1, number(), kind.name()))?.0;
                }
                self.surface_elements += 1;
                if self.element_error.is_none() {
                    match self.resolve(tag, &tags[..kind.node_count()], line) {
                        Ok(ids) => self.builder.add_element_numbered(kind, &ids[..kind.node_count()], line, tag),
                        Err(err) => self.element_error = Some(err),
                    }
                }
            }
            GmshType::Surface(kind) => {
                let start = self.elem_tags.len() as u32;
                for j in 0..kind.node_count() {
                    let (tag, _) = lex.u64(|| format!("node {} of {} ({})", j + 1, number(), kind.name()))?;
                    self.elem_tags.push(tag);
                }
                self.elements.push(RawElement { kind, line: line as u32, start, tag });
            }
            GmshType::Solid(kind) => {
                for j in 0..kind.nodes() {
                    let (tag, _) = lex.u64(|| format!("node {} of {} (a {})", j + 1, number(), kind.name()))?;
                    self.solid_tags.push(tag);
                }
                self.solid_lines.push((line as u32, kind, tag));
            }
            GmshType::Marker(k) => {
                for j in 0..k {
                    let (tag, _) = lex.u64(|| format!("node {} of {}", j + 1, number()))?;
                    self.marks.push((tag, line as u32));
                }
            }
            GmshType::Unsupported(..) => unreachable!("refused by the callers"),
        }
        Ok(())
    }

    fn elements_v2(&mut self, lex: &mut Lexer) -> Result<()> {
        let (n, line) = lex.u64(|| "the number of elements".into())?;
        let n = lex.check_count(n, 10, "elements", line)?;
        self.elements.reserve(prealloc(n));
        for i in 0..n {
            let number = || format!("element {} of the {n} announced at line {line}", i + 1);
            let (tag, el) = lex.u64(|| format!("the tag of {}", number()))?;
            let (t, tl) = lex.u64(|| format!("the type of {}", number()))?;
            let ty = gmsh_type(t);
            if let GmshType::Unsupported(..) = ty {
                return Err(unsupported_type(t, tl));
            }
            let (ntags, _) = lex.u64(|| format!("the number of tags of {}", number()))?;
            lex.skip(ntags, || format!("the {ntags} tags of {}", number()))?;
            self.element_nodes(lex, ty, (tag, el), number)?;
        }
        Ok(())
    }

    fn elements_v41(&mut self, lex: &mut Lexer) -> Result<()> {
        let (blocks, bl) = lex.u64(|| "the number of element entity blocks".into())?;
        let blocks = lex.check_count(blocks, 8, "element entity blocks", bl)?;
        let (n, nl) = lex.u64(|| "the number of elements".into())?;
        let n = lex.check_count(n, 4, "elements", nl)?;
        lex.u64(|| "the smallest element tag".into())?;
        lex.u64(|| "the largest element tag".into())?;
        self.elements.reserve(prealloc(n));
        let mut seen = 0usize;
        for b in 0..blocks {
            let what = |s: &str| format!("the {s} of element block {} of {blocks}", b + 1);
            lex.u64(|| what("entity dimension"))?;
            lex.i64(|| what("entity tag"))?;
            let (t, tl) = lex.u64(|| what("element type"))?;
            let ty = gmsh_type(t);
            if let GmshType::Unsupported(..) = ty {
                return Err(unsupported_type(t, tl));
            }
            let (count, cl) = lex.u64(|| what("element count"))?;
            if count > (n - seen) as u64 {
                return Err(Error::parse(
                    cl,
                    format!(
                        "this block has {count} elements, but only {} of the {n} announced at line {nl} are left",
                        n - seen
                    ),
                ));
            }
            for i in 0..count {
                let number = || format!("element {} of the block at line {tl}", i + 1);
                let (tag, el) = lex.u64(|| format!("the tag of {}", number()))?;
                let ty = gmsh_type(t);
                self.element_nodes(lex, ty, (tag, el), number)?;
            }
            seen += count as usize;
        }
        if seen != n {
            return Err(Error::parse(
                nl,
                format!("the $Elements header announces {n} elements but its blocks hold {seen}"),
            ));
        }
        Ok(())
    }

    /// A `$NodeData` section: read when its view is named `fixed`, else skipped.
    fn node_data(&mut self, lex: &mut Lexer, open: usize) -> Result<()> {
        let (ns, _) = lex.u64(|| "the number of string tags of $NodeData".into())?;
        let mut name = None;
        for i in 0..ns {
            let t = lex.text_line().ok_or_else(|| lex.eof(format!("string tag {} of $NodeData", i + 1)))?;
            if i == 0 {
                name = Some(t.text.trim_matches('"'));
            }
        }
        if name != Some("fixed") {
            return skip_section(lex, "NodeData", open);
        }
        if let Some(first) = self.fixed_view_line {
            // which one should win is anybody's guess: say so rather than pick one
            return Err(Error::parse(open, format!("a second 'fixed' view (the first is at line {first}): give one")));
        }
        self.fixed_view_line = Some(open);
        let (nr, _) = lex.u64(|| "the number of real tags".into())?;
        for _ in 0..nr {
            lex.f64(|| "a real tag".into())?;
        }
        let (ni, il) = lex.u64(|| "the number of integer tags".into())?;
        if ni < 3 {
            return Err(Error::parse(
                il,
                format!("the 'fixed' view needs 3 integer tags (step, components, count), found {ni}"),
            ));
        }
        let mut ints = [0u64; 3];
        let mut count_line = il;
        for i in 0..ni {
            let (v, l) = lex.u64(|| format!("integer tag {} of the 'fixed' view", i + 1))?;
            if (i as usize) < 3 {
                ints[i as usize] = v;
                count_line = l;
            }
        }
        if ints[1] != 1 {
            return Err(Error::parse(count_line, format!("the 'fixed' view must have 1 component, found {}", ints[1])));
        }
        let n = lex.check_count(ints[2], 4, "values in the 'fixed' view", count_line)?;
        let mut v = Vec::with_capacity(prealloc(n));
        for i in 0..n {
            let (tag, tl) = lex.u64(|| format!("the node tag of value {} of the 'fixed' view", i + 1))?;
            let (x, _) = lex.f64(|| format!("the 'fixed' value of node tag {tag}"))?;
            v.push((tag, x != 0.0, tl as u32));
        }
        self.fixed_view = Some(v);
        end_of(lex, "NodeData", open)
    }

    /// What `$Nodes` defined, for messages about undefined tags.
    fn tag_range(&self) -> String {
        match (self.node_tags.iter().min(), self.node_tags.iter().max()) {
            (Some(a), Some(b)) => format!("$Nodes defines tags {a} to {b}"),
            _ => "$Nodes defines no nodes".to_string(),
        }
    }

    /// The node indices of the surface element tagged `e` (on file line `line`) from its
    /// node tags, or the error naming the element: a tag given twice, or not defined.
    fn resolve(&self, e: u64, tags: &[u64], line: usize) -> Result<[u32; 9]> {
        let ids = self.resolve_nodes(e, tags, line, "element")?;
        Ok(std::array::from_fn(|j| ids[j]))
    }

    /// The node indices of `tags` (at most [`MAX_VOLUME_NODES`]), for a surface or volume
    /// element tagged `e` (`what`) on file line `line`, or the error naming it: a tag given
    /// twice, or not defined.
    fn resolve_nodes(&self, e: u64, tags: &[u64], line: usize, what: &str) -> Result<[u32; MAX_VOLUME_NODES]> {
        let map = self.map.as_ref().expect("resolve after the map is made");
        if let Some(t) = repeated(tags) {
            return Err(Error::element(e, Some(line), format!("node tag {t} appears twice in the {what}")));
        }
        let mut ids = [0u32; MAX_VOLUME_NODES];
        for (j, &tag) in tags.iter().enumerate() {
            ids[j] = map.get(tag).ok_or_else(|| {
                Error::element(e, Some(line), format!("node tag {tag} is not defined ({})", self.tag_range()))
            })?;
        }
        Ok(ids)
    }

    fn finish(mut self) -> Result<MeshBuilder> {
        if let Some(err) = self.element_error.take() {
            return Err(err);
        }
        if self.map.is_none() {
            self.map = Some(TagMap::new(&self.node_tags, self.builder.node_lines())?);
            let (elements, elem_tags) = (std::mem::take(&mut self.elements), std::mem::take(&mut self.elem_tags));
            for raw in &elements {
                let k = raw.kind.node_count();
                let ids = self.resolve(raw.tag, &elem_tags[raw.start as usize..raw.start as usize + k], raw.line as usize)?;
                self.builder.add_element_numbered(raw.kind, &ids[..k], raw.line as usize, raw.tag);
            }
        }
        let mut at = 0;
        for &(line, kind, tag) in &self.solid_lines {
            let k = kind.nodes();
            let given = self.resolve_nodes(tag, &self.solid_tags[at..at + k], line as usize, kind.name())?;
            // Gmsh's node order to ours (VTK's), by the kind's row
            let mut ids = [0u32; MAX_VOLUME_NODES];
            for (&g, &ours) in given.iter().zip(kind.row().gmsh_order) {
                ids[ours] = g;
            }
            at += k;
            self.builder.add_volume_element_numbered(kind, &ids[..k], line as usize, tag)?;
        }
        // messages name the nodes by their tags
        let mut numbers = Numbering::From(self.node_tags.first().copied().unwrap_or(1));
        for (i, &tag) in self.node_tags.iter().enumerate() {
            numbers.push(i, tag);
        }
        self.builder.number_nodes(numbers);
        let range = self.tag_range();
        let Reader { mut builder, node_tags, map, marks, fixed_view, .. } = self;
        let map = map.expect("made above");
        let range = || range.clone();
        let n = node_tags.len();
        let resolve = |tag: u64, line: u32, what: &str| {
            map.get(tag).ok_or_else(|| {
                Error::parse(
                    line as usize,
                    format!("{what} refers to node tag {tag}, which is not defined ({})", range()),
                )
            })
        };
        builder.fixed = if let Some(view) = fixed_view {
            let mut f = vec![false; n];
            // the line each node's value came from, to refuse a node listed twice
            let mut seen = vec![0u32; n];
            for (tag, fixed, line) in view {
                let i = resolve(tag, line, "the 'fixed' view")? as usize;
                if seen[i] != 0 {
                    return Err(Error::parse(
                        line as usize,
                        format!(
                            "the 'fixed' view lists node tag {tag} twice (first at line {}): give each node once",
                            seen[i]
                        ),
                    ));
                }
                seen[i] = line.max(1);
                f[i] = fixed;
            }
            FixedSpec::Exact(f)
        } else if marks.is_empty() {
            FixedSpec::Boundary
        } else {
            let mut f = vec![false; n];
            for (tag, line) in marks {
                f[resolve(tag, line, "a line or point element")? as usize] = true;
            }
            FixedSpec::BoundaryAnd(f)
        };
        Ok(builder)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tag_maps_dense_and_sparse() {
        let m = TagMap::new(&[5, 7, 6], &[1, 2, 3]).unwrap();
        assert!(matches!(m, TagMap::Dense { .. }));
        assert_eq!((m.get(5), m.get(6), m.get(7), m.get(8), m.get(4)), (Some(0), Some(2), Some(1), None, None));
        let m = TagMap::new(&[1, 1_000_000_000_000, 40], &[1, 2, 3]).unwrap();
        assert!(matches!(m, TagMap::Sorted(_)));
        assert_eq!((m.get(1_000_000_000_000), m.get(40), m.get(2)), (Some(1), Some(2), None));
        let e = TagMap::new(&[3, 4, 3], &[10, 11, 12]).unwrap_err().to_string();
        assert!(e.contains("line 12") && e.contains("first at line 10") && e.contains("tag 3"), "{e}");
    }

    #[test]
    fn elements_before_or_after_nodes_read_alike() {
        // $Nodes first: elements are resolved as they are read; $Elements first: at the end
        let nodes = "$Nodes\n4\n10 0 0 0\n20 1 0 0\n30 1 1 0\n40 0 1 0\n$EndNodes\n";
        let elements = |third: u64| {
            format!("$Elements\n3\n1 15 2 0 1 10\n2 2 2 0 1 10 20 30\n3 2 2 0 1 10 30 {third}\n$EndElements\n")
        };
        let head = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
        let build = |text: String| parse(&text).and_then(|b| b.build());
        let a = build(format!("{head}{nodes}{}", elements(40))).unwrap();
        let b = build(format!("{head}{}{nodes}", elements(40))).unwrap();
        assert_eq!((a.nodes().to_vec(), a.fixed().to_vec()), (b.nodes().to_vec(), b.fixed().to_vec()));
        for e in 0..2 {
            assert_eq!((a.kind(e), a.element(e)), (b.kind(e), b.element(e)));
        }
        // an undefined tag names the same element and line either way, after a later
        // syntax error has had its say
        let ea = build(format!("{head}{nodes}{}", elements(41))).unwrap_err().to_string();
        let eb = build(format!("{head}{}{nodes}", elements(41))).unwrap_err().to_string();
        assert!(ea.starts_with("element 3 (line 15)") && ea.contains("tag 41") && ea.contains("tags 10 to 40"), "{ea}");
        assert_eq!(ea.replace("line 15", "line 8"), eb, "the lines differ by the node section's 7 lines");
        let late = build(format!("{head}{nodes}{}$Bad\n", elements(41))).unwrap_err().to_string();
        assert!(late.contains("line 17") && late.contains("EndBad"), "{late}");
    }

    /// A 2.2 file of the 27 points of a cube's 3×3×3 lattice (spacing 1/2, x fastest; tag
    /// `k + 1` for point `x + 3y + 9z` in half-units) and one element per `(type, points)`,
    /// in Gmsh's node order, from line 36 on.
    fn lattice_msh(elements: &[(u64, &[u32])]) -> String {
        let mut t = String::from("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n27\n");
        for k in 0..27 {
            t.push_str(&format!("{} {} {} {}\n", k + 1, (k % 3) as f64 / 2.0, (k / 3 % 3) as f64 / 2.0, (k / 9) as f64 / 2.0));
        }
        t.push_str(&format!("$EndNodes\n$Elements\n{}\n", elements.len()));
        for (e, (ty, ids)) in elements.iter().enumerate() {
            let tags: String = ids.iter().map(|i| format!(" {}", i + 1)).collect();
            t.push_str(&format!("{} {ty} 2 0 1{tags}\n", e + 1));
        }
        t.push_str("$EndElements\n");
        t
    }

    /// The lattice points of a hexahedron's 27 nodes in VTK's order (ours).
    const HEX27_VTK: [u32; 27] = [0, 2, 8, 6, 18, 20, 26, 24, 1, 5, 7, 3, 19, 23, 25, 21, 9, 11, 17, 15, 12, 14, 10, 16, 4, 22, 13];

    #[test]
    fn every_volume_kind_is_read_from_gmsh_order_and_the_rest_are_refused_in_plain_words_first() {
        // each kind as Gmsh's documentation numbers it, and the nodes it must have in ours:
        // the prism's first triangle turns anticlockwise seen from its second (VTK's the
        // other way); the 20-node hexahedron's edges (0,1) (0,3) (0,4) (1,2) (1,5) (2,3)
        // (2,6) (3,7) (4,5) (4,7) (5,6) (6,7); the 27-node one's face centres z=0, y=0,
        // x=0, x=1, y=1, z=1, then its centre
        let hex20_gmsh = [0, 2, 8, 6, 18, 20, 26, 24, 1, 3, 9, 5, 11, 7, 17, 15, 19, 21, 23, 25];
        let hex27_gmsh: Vec<u32> = hex20_gmsh.iter().copied().chain([4, 10, 12, 14, 16, 22, 13]).collect();
        let cases: [(u64, &[u32], &[u32], VolumeKind); 5] = [
            (5, &HEX27_VTK[..8], &HEX27_VTK[..8], VolumeKind::Hex8),
            (6, &[0, 2, 6, 18, 20, 24], &[0, 6, 2, 18, 24, 20], VolumeKind::Wedge6),
            (7, &[0, 2, 8, 6, 22], &[0, 2, 8, 6, 22], VolumeKind::Pyramid5),
            (17, &hex20_gmsh, &HEX27_VTK[..20], VolumeKind::Hex20),
            (12, &hex27_gmsh, &HEX27_VTK, VolumeKind::Hex27),
        ];
        for (ty, gmsh, ours, kind) in cases {
            let model = crate::model::Model::build(parse(&lattice_msh(&[(ty, gmsh)])).unwrap());
            let Ok(crate::model::Model::Volume(m)) = model else { panic!("type {ty}: {model:?}") };
            assert_eq!((m.element_count(), m.element_kind(0)), (1, kind), "type {ty}");
            assert_eq!(m.element(0), ours, "type {ty}: in our (VTK's) order, not turned over");
            assert!(!m.is_inverted(0), "type {ty}");
        }
        // quadratic prisms and pyramids: refused in words first, in 2.2 and 4.1 (the
        // element's node list is never read)
        let v22 = |t: u64| format!("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Elements\n1\n1 {t} 2 0 1 1 2 3 4\n$EndElements\n");
        let v41 = |t: u64| format!("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Elements\n1 1 1 1\n3 1 {t} 1\n1 1 2 3 4\n$EndElements\n");
        let refused = [
            (13, "quadratic prisms (wedges) are not supported yet: line 6: Gmsh element type 13 (18-node prism); smoothlab reads"),
            (14, "quadratic pyramids are not supported yet: line 6: Gmsh element type 14 (14-node pyramid); "),
            (18, "quadratic prisms (wedges) are not supported yet: line 6: Gmsh element type 18 (15-node prism); "),
            (19, "quadratic pyramids are not supported yet: line 6: Gmsh element type 19 (13-node pyramid); "),
        ];
        for (t, want) in refused {
            let e = parse(&v22(t)).unwrap_err();
            assert!(matches!(e, Error::Unsupported { line: Some(6), .. }), "{e:?}");
            assert!(e.to_string().starts_with(want), "type {t}: {e}");
            assert!(e.to_string().contains("the volume elements 4, 5, 6, 7, 11, 12, 17, and takes lines"), "{e}");
            let e = parse(&v41(t)).unwrap_err().to_string();
            assert!(e.starts_with(want), "type {t} in 4.1: {e}");
        }
        // a type with no name people know keeps the file's terms alone, line first
        let e = parse(&v22(99)).unwrap_err().to_string();
        assert!(e.starts_with("line 6: Gmsh element type 99 (unknown type) is not supported: smoothlab reads"), "{e}");
    }

    #[test]
    fn a_quadratic_kind_mixed_with_another_is_refused_naming_the_line() {
        // a hexahedron and a prism beside it: one mesh
        let b = parse(&lattice_msh(&[(5, &[0, 1, 4, 3, 9, 10, 13, 12]), (6, &[1, 2, 4, 10, 11, 13])])).unwrap();
        let Ok(crate::model::Model::Volume(m)) = crate::model::Model::build(b) else { panic!("not a volume") };
        assert_eq!(m.kinds(), &[VolumeKind::Hex8, VolumeKind::Wedge6]);
        assert!(!m.is_inverted(0) && !m.is_inverted(1));
        // a 27-node hexahedron, then a linear one at line 37
        let text = lattice_msh(&[(12, &[0, 2, 8, 6, 18, 20, 26, 24, 1, 3, 9, 5, 11, 7, 17, 15, 19, 21, 23, 25, 4, 10, 12, 14, 16, 22, 13]), (5, &HEX27_VTK[..8])]);
        assert_eq!(
            parse(&text).unwrap_err().to_string(),
            "element 2 (line 37): the file mixes 8-node and 27-node hexahedra: smoothlab mixes linear kinds, \
             but a quadratic mesh is of one kind"
        );
    }

    #[test]
    fn runs_keep_order() {
        use ElementKind::*;
        assert_eq!(runs(&[Tri3, Tri3, Quad4, Tri3]), vec![(0, 2), (2, 3), (3, 4)]);
        assert_eq!(runs(&[]), vec![]);
    }
}
