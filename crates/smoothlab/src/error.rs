//! The one error type of the core. Every variant names where the problem is
//! (a line of the file, an element or a node) and what was expected, so the CLI
//! and the page can show it as it is.

use std::fmt;

/// Where in the input a problem was found.
#[derive(Clone, Debug, PartialEq)]
pub enum Error {
    /// The text of a file is malformed at `line` (1-based).
    Parse { line: usize, message: String },
    /// An element is invalid: its number as the file numbers it ([`Numbering`]), with its
    /// file line when known.
    Element { element: u64, line: Option<usize>, message: String },
    /// A node is invalid: its number as the file numbers it ([`Numbering`]), with its file
    /// line when known.
    Node { node: u64, line: Option<usize>, message: String },
    /// Points are given in 3D and do not lie on one plane: `node` (as the file numbers it,
    /// with its file line when known) is the farthest off, by `max_distance`, which is
    /// `relative` times the size of the largest element it belongs to.
    NotPlanar { node: u64, line: Option<usize>, max_distance: f64, relative: f64, tolerance: f64 },
    /// The input is well-formed but asks for something smoothlab does not do
    /// (polygons, volume cells, binary files, …). `lead`, when given, says it first in
    /// words a reader of the mesh knows (`hexahedra are not supported yet`), before the
    /// line and the file's own terms (`VTK cell type 12`).
    Unsupported { lead: Option<String>, line: Option<usize>, message: String },
    /// The mesh has no elements (or no nodes).
    Empty(String),
    /// The input is larger than a stated limit.
    TooLarge(String),
    /// A request (options, arguments) that cannot be carried out.
    Invalid(String),
    /// Reading or writing a file failed.
    Io(String),
}

impl Error {
    pub fn parse(line: usize, message: impl Into<String>) -> Self {
        Error::Parse { line, message: message.into() }
    }
    /// An error about element `element`, numbered as the file numbers it.
    pub fn element(element: impl TryInto<u64>, line: Option<usize>, message: impl Into<String>) -> Self {
        Error::Element { element: element.try_into().unwrap_or(u64::MAX), line, message: message.into() }
    }
    /// An error about node `node`, numbered as the file numbers it.
    pub fn node(node: impl TryInto<u64>, line: Option<usize>, message: impl Into<String>) -> Self {
        Error::Node { node: node.try_into().unwrap_or(u64::MAX), line, message: message.into() }
    }
    pub fn unsupported(line: Option<usize>, message: impl Into<String>) -> Self {
        Error::Unsupported { lead: None, line, message: message.into() }
    }
    /// An element kind smoothlab does not read, said first in plain words (`lead`, e.g.
    /// `hexahedra are not supported yet`), then the line and the file's terms.
    pub fn unsupported_kind(lead: impl Into<String>, line: usize, message: impl Into<String>) -> Self {
        Error::Unsupported { lead: Some(lead.into()), line: Some(line), message: message.into() }
    }
    pub fn invalid(message: impl Into<String>) -> Self {
        Error::Invalid(message.into())
    }
}

fn at_line(f: &mut fmt::Formatter<'_>, line: Option<usize>) -> fmt::Result {
    match line {
        Some(l) => write!(f, " (line {l})"),
        None => Ok(()),
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Parse { line, message } => write!(f, "line {line}: {message}"),
            Error::Element { element, line, message } => {
                write!(f, "element {element}")?;
                at_line(f, *line)?;
                write!(f, ": {message}")
            }
            Error::Node { node, line, message } => {
                write!(f, "node {node}")?;
                at_line(f, *line)?;
                write!(f, ": {message}")
            }
            Error::NotPlanar { node, line, max_distance, relative, tolerance } => {
                write!(f, "the mesh is not planar: node {node}")?;
                at_line(f, *line)?;
                write!(
                    f,
                    " lies {} off the plane of the mesh, {} times the size of its elements (the tolerance is {tolerance:.0e}); \
                     it is a surface in 3D, not a planar mesh (io::read_model_* reads it as one)",
                    shown_number(*max_distance),
                    shown_number(*relative)
                )
            }
            Error::Unsupported { lead, line, message } => {
                if let Some(lead) = lead {
                    write!(f, "{lead}: ")?;
                }
                if let Some(l) = line {
                    write!(f, "line {l}: ")?;
                }
                write!(f, "{message}")
            }
            Error::Empty(m) => write!(f, "empty mesh: {m}"),
            Error::TooLarge(m) => write!(f, "too large: {m}"),
            Error::Invalid(m) => write!(f, "{m}"),
            Error::Io(m) => write!(f, "{m}"),
        }
    }
}

/// How a file numbers its nodes, or its elements: every message names a node or an element
/// by the file's own number (VTK's 0-based indices, Gmsh's tags, Medit's 1-based numbers
/// within a section), so it can be found in the file as the message says.
#[derive(Clone, Debug, PartialEq)]
pub enum Numbering {
    /// The `i`-th (0-based, in file order) is number `first + i`.
    From(u64),
    /// Each has its own number (Gmsh's tags), in file order.
    Tags(Vec<u64>),
}

impl Default for Numbering {
    /// 0-based indices in file order.
    fn default() -> Self {
        Numbering::From(0)
    }
}

impl Numbering {
    /// The file's number of the `i`-th (0-based, in file order).
    pub fn of(&self, i: usize) -> u64 {
        match self {
            Numbering::From(first) => first.saturating_add(i as u64),
            Numbering::Tags(tags) => tags.get(i).copied().unwrap_or(i as u64),
        }
    }
    /// Records the number of the next one, the `count`-th: the list of tags is made only
    /// when a number breaks the run from the first.
    pub(crate) fn push(&mut self, count: usize, number: u64) {
        match self {
            Numbering::From(first) if first.checked_add(count as u64) == Some(number) => {}
            Numbering::From(first) => {
                let first = *first;
                let mut tags: Vec<u64> = (0..count as u64).map(|i| first.saturating_add(i)).collect();
                tags.push(number);
                *self = Numbering::Tags(tags);
            }
            Numbering::Tags(tags) => {
                tags.truncate(count);
                tags.push(number);
            }
        }
    }
    /// The number after the `count` so far (the next in the run, or after the last tag).
    pub(crate) fn next(&self, count: usize) -> u64 {
        match self {
            Numbering::From(first) => first.saturating_add(count as u64),
            Numbering::Tags(tags) => tags.get(count.wrapping_sub(1)).map_or(count as u64, |t| t.saturating_add(1)),
        }
    }
}

/// How many items a message lists before it says how many more there are.
pub const LISTED: usize = 5;

/// A list for a message, of bounded length whatever the file: the first [`LISTED`] of the
/// `count` items, then how many more ("0, 1, 2, 3, 4 and 199995 more").
pub(crate) fn listed<T: fmt::Display>(items: impl IntoIterator<Item = T>, count: usize) -> String {
    let shown: Vec<String> = items.into_iter().take(LISTED).map(|x| x.to_string()).collect();
    let more = count.saturating_sub(shown.len());
    let mut s = shown.join(", ");
    if more > 0 {
        s.push_str(&format!(" and {more} more"));
    }
    s
}

/// A number for a message: 4 significant digits, in scientific notation when very large
/// or small, and never "NaN" (shown as "an unknown amount", which no caller should need).
pub(crate) fn shown_number(x: f64) -> String {
    if x.is_nan() {
        "an unknown amount".into()
    } else if x.is_infinite() {
        if x > 0.0 { "infinitely many".into() } else { "minus infinity".into() }
    } else if x != 0.0 && !(1e-3..1e4).contains(&x.abs()) {
        format!("{x:.3e}")
    } else {
        let s = format!("{x:.4}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

impl std::error::Error for Error {}

impl From<std::io::Error> for Error {
    fn from(e: std::io::Error) -> Self {
        Error::Io(e.to_string())
    }
}

pub type Result<T, E = Error> = std::result::Result<T, E>;
