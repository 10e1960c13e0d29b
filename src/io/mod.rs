//! Mesh file formats: Gmsh `.msh` (2.2 and 4.1 ASCII), legacy VTK ASCII
//! `UNSTRUCTURED_GRID`, Triangle `.node`/`.ele`, OBJ and OFF.
//!
//! Readers parse text into a [`MeshBuilder`](crate::mesh::MeshBuilder), recording the
//! file line of every node and element, so every error names a line or an element.
//! Nothing here panics on any input.

use crate::error::{Error, Result};
use crate::mesh::Mesh;

/// A mesh file format, chosen from a file name's extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Msh,
    Vtk,
    /// Triangle's `.node` + `.ele` pair.
    Triangle,
    Obj,
    Off,
}

/// Which `.msh` version to write.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MshVersion {
    /// 2.2 ASCII: what most other tools read (the default).
    #[default]
    V22,
    /// 4.1 ASCII.
    V41,
}

/// Options for writing.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct WriteOptions {
    pub msh_version: MshVersion,
}

impl Format {
    /// The format of a file name by its extension (`.node` and `.ele` both mean Triangle).
    pub fn from_name(name: &str) -> Option<Format> {
        let ext = name.rsplit_once('.')?.1.to_ascii_lowercase();
        Some(match ext.as_str() {
            "msh" => Format::Msh,
            "vtk" => Format::Vtk,
            "node" | "ele" => Format::Triangle,
            "obj" => Format::Obj,
            "off" => Format::Off,
            _ => return None,
        })
    }
}

/// Error for a name whose extension is not a mesh format.
pub fn unknown_format(name: &str) -> Error {
    Error::invalid(format!(
        "cannot tell the mesh format of '{name}': use .msh, .vtk, .node/.ele, .obj or .off"
    ))
}
