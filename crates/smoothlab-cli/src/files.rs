//! Reading and writing mesh files for the subcommands, with the file name in errors.

use std::path::{Path, PathBuf};

use clap::Args;

use crate::args::msh_version_parser;
use smoothlab::io::{self, MshVersion, WriteOptions};
use smoothlab::quality::element_quality;
use smoothlab::model::Model;
use smoothlab::Mesh;

/// Reads a planar mesh or a surface, naming the file in any error, and warns (stderr)
/// about a planar mesh's elements of zero area, which load but count as inverted until
/// smoothed.
pub fn read_model(path: &Path) -> Result<Model, String> {
    let model = io::read_model_path(path).map_err(|e| format!("{}: {e}", path.display()))?;
    match &model {
        Model::Planar(mesh) => warn_zero_area(mesh, path),
        // a mistyped coordinate makes a planar mesh a surface: say which node did
        Model::Surface(s) => {
            if let Some(why) = s.not_planar() {
                eprintln!("smoothlab: note: {}: read as a surface in 3D: {why}", path.display());
            }
        }
        Model::Volume(v) => {
            if let Some(note) = v.stray_faces_note() {
                eprintln!("smoothlab: note: {}: {note}", path.display());
            }
        }
    }
    Ok(model)
}

fn warn_zero_area(mesh: &Mesh, path: &Path) {
    // zero area by the shoelace formula and inverted by the metrics' own test (a corner
    // with det ≤ 0), so the warning never contradicts the `inverted` count of the stats
    let flat: Vec<usize> = (0..mesh.element_count())
        .filter(|&e| {
            mesh.corner_area(e) == 0.0 && {
                let kind = mesh.kind(e);
                element_quality(kind, &mesh.element_points_array(e)[..kind.node_count()]).inverted
            }
        })
        .collect();
    if !flat.is_empty() {
        let shown: Vec<String> = flat.iter().take(5).map(|e| e.to_string()).collect();
        eprintln!(
            "smoothlab: warning: {}: {} element(s) of zero area (element {}{}); they count as inverted",
            path.display(),
            flat.len(),
            shown.join(", "),
            if flat.len() > 5 { ", …" } else { "" }
        );
    }
}

/// Writes a mesh (planar or a surface) in the format of the file's extension.
pub fn write_mesh<'a>(mesh: impl Into<io::Writable<'a>>, path: &Path, msh_version: MshVersion) -> Result<(), String> {
    let opts = WriteOptions { msh_version };
    let mesh = mesh.into();
    io::write_path(mesh, path, &opts).map_err(|e| format!("{}: {e}", path.display()))?;
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
    if ext == "node" || ext == "ele" {
        if let Some(note) = io::flat_note(mesh.mesh) {
            eprintln!("{}: note: {note}", path.display());
        }
    }
    Ok(())
}

/// Writes what a model holds (planar, surface or volume) in the format of the file's
/// extension.
pub fn write_model(model: &Model, path: &Path, msh_version: MshVersion) -> Result<(), String> {
    match model {
        Model::Planar(m) => write_mesh(m, path, msh_version),
        Model::Surface(s) => write_mesh(s, path, msh_version),
        Model::Volume(_) => io::write_model_path(model, path, &WriteOptions { msh_version })
            .map_err(|e| format!("{}: {e}", path.display())),
    }
}

#[derive(Args)]
pub struct ConvertArgs {
    /// Input mesh (.msh, .vtk, .node/.ele, .obj, .off, .mesh; volume meshes in .msh, .vtk, .mesh, tetrahedra also TetGen .node/.ele)
    pub input: PathBuf,
    /// Output mesh; the format follows the extension
    pub output: PathBuf,
    /// Version of .msh files written
    #[arg(long, value_parser = msh_version_parser(), default_value = MshVersion::default().name())]
    pub msh_version: MshVersion,
}

pub fn convert(a: ConvertArgs) -> Result<(), String> {
    let model = read_model(&a.input)?;
    write_model(&model, &a.output, a.msh_version)
}
