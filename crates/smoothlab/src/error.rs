//! The one error type of the core. Every variant names where the problem is
//! (a line of the file, an element or a node) and what was expected, so the CLI
//! and the page can show it as it is.

use std::fmt;

/// Where in the input a problem was found.
#[derive(Clone, Debug, PartialEq)]
pub enum Error {
    /// The text of a file is malformed at `line` (1-based).
    Parse { line: usize, message: String },
    /// An element is invalid (0-based element index as read, with its file line when known).
    Element { element: usize, line: Option<usize>, message: String },
    /// A node is invalid (0-based node index as read, with its file line when known).
    Node { node: usize, line: Option<usize>, message: String },
    /// Points are given in 3D and do not lie on one plane: `node` (0-based, with its file
    /// line when known) is the farthest off, by `max_distance`, which is `relative` times
    /// the size of the largest element it belongs to.
    NotPlanar { node: usize, line: Option<usize>, max_distance: f64, relative: f64, tolerance: f64 },
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
    pub fn element(element: usize, line: Option<usize>, message: impl Into<String>) -> Self {
        Error::Element { element, line, message: message.into() }
    }
    pub fn node(node: usize, line: Option<usize>, message: impl Into<String>) -> Self {
        Error::Node { node, line, message: message.into() }
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
