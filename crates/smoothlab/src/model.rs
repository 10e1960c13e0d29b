//! What a mesh file holds, above the planar core, the surfaces and the volumes: a
//! [`Model`] is a planar [`Mesh`], a [`Surface`] in 3D or a [`VolumeMesh`], and
//! [`Model::build`] decides which from what a reader put in a [`MeshBuilder`].

use crate::error::{Error, Result};
use crate::mesh::{Flat, Mesh, MeshBuilder};
use crate::quality::{mesh_stats, MeshStats};
use crate::surface::Surface;
use crate::volume::{volume_stats, VolumeMesh};

/// What a mesh file holds: a planar mesh (the 2D core), a surface in 3D, or a volume mesh
/// of tetrahedra, hexahedra, wedges and pyramids ([`crate::volume`]).
#[derive(Clone, Debug)]
#[allow(clippy::large_enum_variant)]
pub enum Model {
    Planar(Mesh),
    Surface(Surface),
    Volume(VolumeMesh),
}

impl From<Mesh> for Model {
    fn from(m: Mesh) -> Model {
        Model::Planar(m)
    }
}

impl Model {
    /// Measures every corner against `target` from now on: [`Input`](crate::target::Target::Input)
    /// takes the mesh as it is now, [`Ideal`](crate::target::Target::Ideal) the ideal of each kind.
    pub fn set_target(&mut self, target: crate::target::Target) {
        match self {
            Model::Planar(m) => m.set_target_from(target, m.nodes().to_vec()),
            Model::Surface(s) => s.set_target_from(target, s.points().to_vec()),
            Model::Volume(v) => v.set_target_from(target, v.nodes().to_vec()),
        }
    }

    /// Whether its corners are measured against targets other than the ideal
    /// ([`set_target`](Self::set_target)).
    pub fn has_target(&self) -> bool {
        match self {
            Model::Planar(m) => m.target_nodes().is_some(),
            Model::Surface(s) => s.flat().target_nodes().is_some(),
            Model::Volume(v) => v.target_nodes().is_some(),
        }
    }

    /// Builds what a reader found: a volume mesh when the file has volume elements (its
    /// triangles and quads then the boundary faces, [`VolumeMesh::from_builder`]), else a
    /// planar [`Mesh`] when its points lie in a plane (as [`MeshBuilder::build`]), else a
    /// surface in 3D — the checks of a planar mesh, the elements oriented consistently
    /// (see [`Surface`]), its points as given, and why they are not planar
    /// ([`Surface::not_planar`]).
    pub fn build(builder: MeshBuilder) -> Result<Model> {
        if builder.has_tets() {
            return VolumeMesh::from_builder(builder).map(Model::Volume);
        }
        match builder.build_planar_or_surface()? {
            Flat::Planar(m) => Ok(Model::Planar(m)),
            Flat::Surface(parts) => Surface::from_surface_parts(parts, None).map(Model::Surface),
        }
    }
    /// The elements, topology and fixed flags of a planar mesh or a surface (for a
    /// surface, with scratch positions: see [`Surface::flat`]); `None` for a volume mesh.
    pub fn mesh(&self) -> Option<&Mesh> {
        match self {
            Model::Planar(m) => Some(m),
            Model::Surface(s) => Some(s.flat()),
            Model::Volume(_) => None,
        }
    }
    /// The statistics `stats` prints.
    pub fn stats(&self) -> MeshStats {
        match self {
            Model::Planar(m) => mesh_stats(m),
            Model::Surface(s) => s.stats(),
            Model::Volume(v) => volume_stats(v),
        }
    }
    /// The planar mesh, or an error saying that `what` takes planar meshes only.
    pub fn planar(self, what: &str) -> Result<Mesh> {
        match self {
            Model::Planar(m) => Ok(m),
            Model::Surface(_) => {
                Err(Error::invalid(format!("{what} takes planar meshes only; this mesh is a surface in 3D")))
            }
            Model::Volume(v) => Err(Error::invalid(format!(
                "{what} takes planar meshes only; this mesh is made of {}",
                v.family_words()
            ))),
        }
    }
}
