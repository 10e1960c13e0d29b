//! The page's gallery of generated samples: each name stands for one call of the core's
//! own generators ([`smoothlab::generate`]), so the page needs no files for them and a
//! permalink names a sample in a few characters.

use serde::{Deserialize, Serialize};

use smoothlab::error::{Error, Result};
use smoothlab::generate::{
    perturb, plate, quadratic_star, rand2d, rand2d_spatial, random_grid, star, surface, GridKind, PlateKind,
    QuadraticStar, StarKind, SurfaceKind, SurfaceShape,
};
use smoothlab::mesh::Mesh;
use smoothlab::generate::{hex_grid, mixed_block, perturb_surface, perturb_volume, HexBlock};
use smoothlab::model::Model;

/// Seed of every generated sample (the page's perturb button takes its own seed).
pub const SAMPLE_SEED: u64 = 1;
/// Perturbation of the tangled samples, in mean edge lengths: Chen, Tristano & Kwok
/// (2003, §5.2) perturb "the nodal locations of each interior node randomly"; 0.5
/// inverts 32 of the 800 triangles of the plate (seed 1).
pub const TANGLE_AMOUNT: f64 = 0.5;
/// Cells per side of the random grid (Knupp's Figure 1; the reproduction's §4).
pub const RANDOM_GRID_CELLS: usize = 10;
/// Perturbation of the opening sample ([`Sample::PlateQuadTangledHard`]), in mean edge
/// lengths: at 1.0 one Step (the page's default settings) leaves elements inverted on the
/// old side and none on the new in each of the seeds 1–20 (`docs/reproduction.md` §8; at
/// 0.5, in none); at seed 1, 219 of its 400 quads are inverted, 15 after the old side's Step.
pub const HARD_TANGLE_AMOUNT: f64 = 1.0;
/// Resolution of the plate samples: 40 nodes round the hole, 10 rings (440 corner nodes).
pub const PLATE_RESOLUTION: usize = 5;
/// Interior points of the large sample (Freitag's rand2d with ~100k nodes).
pub const LARGE_INTERIOR: usize = 99_200;
/// Points per side and interior points of the 1M sample: exactly 1 000 000 nodes, the
/// most the page takes ([`super::MAX_NODES`]).
pub const MILLION_PER_SIDE: usize = 1000;
pub const MILLION_INTERIOR: usize = 1_000_000 - 4 * MILLION_PER_SIDE;
/// Resolution of the surface samples ([`surface`]): 6 cells along each edge of the
/// sphere's cube (216 quads), of the cylinder's cap squares, and 8 × 24 cells round the torus.
pub const SURFACE_RESOLUTION: usize = 6;
pub const TORUS_RESOLUTION: usize = 2;
/// Perturbation of the quadratic torus ([`Sample::TorusQuadraticTangled`]), in mean edge
/// lengths: at 1.0 (seed 1) 86 of its 288 elements are inverted, and 3 passes of the old
/// max-min objective with Chen's rules leave 10 of them inverted where the new objective
/// untangles all in the first pass (the tour's `chen-18`); at 0.8 both untangle it.
pub const QUADRATIC_TANGLE_AMOUNT: f64 = 1.0;
/// Cells a side of the tangled block of hexahedra ([`Sample::HexTangled`]): 6³ = 216
/// hexahedra, 125 free nodes.
pub const HEX_CELLS: usize = 6;
/// Perturbation of the block of hexahedra, in mean edge lengths (Knupp 1999's test grids
/// are perturbed by 0.5–1): at 1.0 (seed 1) 128 of its 216 hexahedra are inverted, and 3
/// passes of the old max-min objective with Chen's rules leave 40 inverted where the new
/// one untangles every one in the first pass (the tour's `knupp-hex`).
pub const HEX_TANGLE_AMOUNT: f64 = 1.0;
/// Cells a side of the mixed block ([`Sample::MixedTangled`]): 4³ cells as 98 elements of
/// the four linear kinds.
pub const MIXED_CELLS: usize = 4;
/// Perturbation of the mixed block, in mean edge lengths: a little, so that a few
/// elements (5 of 98 at seed 1) are inverted and one pass untangles them.
pub const MIXED_TANGLE_AMOUNT: f64 = 0.6;

/// A sample mesh made in the browser by the core's generators.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Sample {
    /// Freitag (1997) Table 1: 500 random points + 20 per side (580 nodes).
    Rand2d,
    /// Chen et al. (2003) Figure 13: the plate with a hole, triangles.
    PlateTri,
    PlateQuad,
    PlateMixed,
    /// The same plates with every free node perturbed ([`TANGLE_AMOUNT`]).
    PlateTriTangled,
    PlateQuadTangled,
    PlateMixedTangled,
    /// The quad plate with every free node moved by up to [`HARD_TANGLE_AMOUNT`]: the
    /// sample the page opens on.
    PlateQuadTangledHard,
    /// rand2d perturbed: tangled triangles with random sizes.
    Rand2dTangled,
    /// Mesquite's `equil_tri` star: six triangles round a displaced free node.
    StarRegular,
    /// Chen's non-convex star-shaped configuration (Figure 10, our reading).
    StarChen,
    /// Four quads round one free node (Chen Figure 20a, our reading).
    StarQuad,
    /// Six 6-node triangles, the top edge curved in towards the free node (Chen Figure 9,
    /// our reading: [`QuadraticStar::PushedEdge`]).
    StarPushed,
    /// A free node joined to a curved quadratic boundary (Chen Figure 16, our reading:
    /// [`QuadraticStar::CurvedBoundary`]).
    StarCurved,
    /// Knupp (1999) Figure 1: a 10 × 10 quad grid, every interior node at a random place
    /// in the square (seed 1), as the reproduction's §4.
    GridRandomTangled,
    /// The plate with 6-node triangles, its hole a curved boundary.
    PlateQuadratic,
    /// rand2d with about 100 000 nodes, to show that the page stays responsive.
    Rand2dLarge,
    /// The unit sphere (a cube-sphere of quads), every free node perturbed in its tangent
    /// plane ([`TANGLE_AMOUNT`]): a tangled surface (Chen et al. 2003 smooth surface meshes).
    SphereTangled,
    /// A torus of quads and triangles, perturbed likewise.
    TorusTangled,
    /// A cylinder with flat caps (O-grids; its rims are feature curves whose nodes stay
    /// fixed), quads, perturbed likewise.
    CylinderCapped,
    /// A torus of quadratic quads and triangles (8-node quads, 6-node triangles: Chen et
    /// al. 2003 smooth "quadratic mixed surface meshes", their Figs. 18–19), every free node
    /// perturbed in its tangent plane by [`QUADRATIC_TANGLE_AMOUNT`].
    TorusQuadraticTangled,
    /// Freitag (1997) Table 2: rand3D, 1086 points in the unit cube in about 5900
    /// tetrahedra ([`smoothlab::generate::rand3d`]).
    Rand3d,
    /// Knupp (1999)'s kind of tangled test grid in 3D: a block of [`HEX_CELLS`]³
    /// hexahedra, every free node moved by up to [`HEX_TANGLE_AMOUNT`] mean edge lengths
    /// ([`smoothlab::generate::hex_grid`], [`perturb_volume`]).
    HexTangled,
    /// Every linear volume kind in one conforming mesh — hexahedra, a column of wedges, a
    /// row of pyramids and tetrahedra ([`smoothlab::generate::mixed_block`], [`MIXED_CELLS`]³
    /// cells) — tangled a little ([`MIXED_TANGLE_AMOUNT`]).
    MixedTangled,
    /// rand2d with 1 000 000 nodes (about 2 million triangles): the page at its limit
    /// (last in the gallery, its title says it is slow).
    Rand2dMillion,
}

impl Sample {
    /// The gallery: [`Sample::ALL`], the surfaces, the volumes, then the 1M-node sample.
    pub const GALLERY: [Sample; 25] = {
        let mut g = [Sample::Rand2dMillion; 25];
        let mut i = 0;
        while i < Sample::ALL.len() {
            g[i] = Sample::ALL[i];
            i += 1;
        }
        let mut j = 0;
        while j < Sample::SURFACES.len() {
            g[i + j] = Sample::SURFACES[j];
            j += 1;
        }
        let mut k = 0;
        while k < Sample::VOLUMES.len() {
            g[i + j + k] = Sample::VOLUMES[k];
            k += 1;
        }
        g
    };

    /// The volume samples, in gallery order: tetrahedra, hexahedra, every kind mixed.
    pub const VOLUMES: [Sample; 3] = [Sample::Rand3d, Sample::HexTangled, Sample::MixedTangled];

    /// The surface samples, in gallery order.
    pub const SURFACES: [Sample; 4] = [Sample::SphereTangled, Sample::TorusTangled, Sample::CylinderCapped, Sample::TorusQuadraticTangled];

    /// The sample the page opens on, first in the gallery: the hard-tangled quad plate,
    /// where one press of Step shows the papers' claim — the old objective leaves elements
    /// inverted, the new one none — in each of 20 seeds (`docs/reproduction.md` §8; the
    /// plates tangled by [`TANGLE_AMOUNT`] untangle on both sides). On quads the max-min
    /// objective's β is kinked (Chen et al.'s Fig. 20).
    pub const DEFAULT: Sample = Sample::ALL[0];

    /// The planar samples of the gallery but the 1M-node one, in gallery order (a
    /// permalink names every sample of [`Sample::GALLERY`]: [`permalink::SAMPLES`](super::permalink::SAMPLES)).
    pub const ALL: [Sample; 17] = [
        Sample::PlateQuadTangledHard,
        Sample::PlateQuadTangled,
        Sample::PlateTriTangled,
        Sample::PlateMixedTangled,
        Sample::Rand2d,
        Sample::Rand2dTangled,
        Sample::PlateTri,
        Sample::PlateQuad,
        Sample::PlateMixed,
        Sample::PlateQuadratic,
        Sample::StarRegular,
        Sample::StarChen,
        Sample::StarQuad,
        Sample::StarPushed,
        Sample::StarCurved,
        Sample::GridRandomTangled,
        Sample::Rand2dLarge,
    ];

    /// What the gallery shows for the sample.
    pub fn title(self) -> &'static str {
        match self {
            Sample::Rand2d => "rand2D (Freitag): 580 nodes",
            Sample::PlateTri => "Plate with a hole: triangles",
            Sample::PlateQuad => "Plate with a hole: quads",
            Sample::PlateMixed => "Plate with a hole: mixed",
            Sample::PlateTriTangled => "Tangled plate: triangles",
            Sample::PlateQuadTangled => "Tangled plate: quads",
            Sample::PlateMixedTangled => "Tangled plate: mixed",
            Sample::PlateQuadTangledHard => "Tangled plate: quads, heavily",
            Sample::Rand2dTangled => "Tangled rand2D",
            Sample::StarRegular => "Star: regular (Mesquite)",
            Sample::StarChen => "Star: Chen's star shape",
            Sample::StarQuad => "Star: quads",
            Sample::StarPushed => "Star: pushed-in quadratic edge",
            Sample::StarCurved => "Star: by a curved boundary",
            Sample::GridRandomTangled => "Random grid (Knupp)",
            Sample::PlateQuadratic => "Quadratic plate, curved hole",
            Sample::Rand2dLarge => "rand2D, 100k nodes",
            Sample::SphereTangled => "Surface: tangled sphere, quads",
            Sample::TorusTangled => "Surface: tangled torus, mixed",
            Sample::CylinderCapped => "Surface: capped cylinder, perturbed quads",
            Sample::TorusQuadraticTangled => "Surface: tangled torus, quadratic mixed",
            Sample::Rand3d => "Tetrahedra: rand3D (Freitag), 1086 nodes",
            Sample::HexTangled => "Hexahedra: tangled block (Knupp), 6³ cells",
            Sample::MixedTangled => "Mixed solids: hexahedra, wedges, pyramids, tetrahedra, tangled",
            Sample::Rand2dMillion => "rand2D, 1M nodes (large: slow, ~350 MB of memory)",
        }
    }

    /// The sample's name, as serde writes it (kebab-case): the page's menu value and the
    /// permalink's `sample=`.
    pub const fn name(self) -> &'static str {
        match self {
            Sample::Rand2d => "rand2d",
            Sample::PlateTri => "plate-tri",
            Sample::PlateQuad => "plate-quad",
            Sample::PlateMixed => "plate-mixed",
            Sample::PlateTriTangled => "plate-tri-tangled",
            Sample::PlateQuadTangled => "plate-quad-tangled",
            Sample::PlateMixedTangled => "plate-mixed-tangled",
            Sample::PlateQuadTangledHard => "plate-quad-tangled-hard",
            Sample::Rand2dTangled => "rand2d-tangled",
            Sample::StarRegular => "star-regular",
            Sample::StarChen => "star-chen",
            Sample::StarQuad => "star-quad",
            Sample::StarPushed => "star-pushed",
            Sample::StarCurved => "star-curved",
            Sample::GridRandomTangled => "grid-random-tangled",
            Sample::PlateQuadratic => "plate-quadratic",
            Sample::Rand2dLarge => "rand2d-large",
            Sample::SphereTangled => "sphere-tangled",
            Sample::TorusTangled => "torus-tangled",
            Sample::CylinderCapped => "cylinder-capped",
            Sample::TorusQuadraticTangled => "torus-quadratic-tangled",
            Sample::Rand3d => "rand3d",
            Sample::HexTangled => "hex-tangled",
            Sample::MixedTangled => "mixed-tangled",
            Sample::Rand2dMillion => "rand2d-million",
        }
    }

    /// Whether a permalink can name the sample (it is one of
    /// [`permalink::SAMPLES`](super::permalink::SAMPLES): all are).
    pub fn linkable(self) -> bool {
        super::permalink::SAMPLES.contains(&self.name())
    }

    /// Makes the mesh: a planar one, a surface in 3D ([`Sample::SURFACES`]) or a volume
    /// mesh ([`Sample::VOLUMES`]).
    pub fn model(self) -> Result<Model> {
        let tangled = |s| perturb_surface(&s, TANGLE_AMOUNT, SAMPLE_SEED);
        let r = SURFACE_RESOLUTION;
        Ok(match self {
            Sample::SphereTangled => Model::Surface(tangled(surface(SurfaceShape::Sphere, SurfaceKind::Quad, 1, r)?)?),
            Sample::TorusTangled => {
                Model::Surface(tangled(surface(SurfaceShape::Torus, SurfaceKind::Mixed, 1, TORUS_RESOLUTION)?)?)
            }
            Sample::CylinderCapped => {
                Model::Surface(tangled(surface(SurfaceShape::Cylinder, SurfaceKind::Quad, 1, r)?)?)
            }
            Sample::TorusQuadraticTangled => Model::Surface(perturb_surface(
                &surface(SurfaceShape::Torus, SurfaceKind::Mixed, 2, TORUS_RESOLUTION)?,
                QUADRATIC_TANGLE_AMOUNT,
                SAMPLE_SEED,
            )?),
            Sample::Rand3d => Model::Volume(smoothlab::generate::rand3d(smoothlab::generate::RAND3D_POINTS, SAMPLE_SEED)?),
            Sample::HexTangled => Model::Volume(perturb_volume(
                &hex_grid(&HexBlock::cube(HEX_CELLS))?,
                HEX_TANGLE_AMOUNT,
                SAMPLE_SEED,
            )?),
            Sample::MixedTangled => Model::Volume(perturb_volume(
                &mixed_block(&HexBlock::cube(MIXED_CELLS))?,
                MIXED_TANGLE_AMOUNT,
                SAMPLE_SEED,
            )?),
            planar => Model::Planar(planar.generate()?),
        })
    }

    /// Makes the planar mesh; a surface sample is refused (see [`model`](Self::model)).
    pub fn generate(self) -> Result<Mesh> {
        let plate1 = |k| plate(k, 1, PLATE_RESOLUTION);
        let tangled = |m: Mesh| perturb(&m, TANGLE_AMOUNT, SAMPLE_SEED);
        match self {
            Sample::Rand2d => rand2d(500, 20, SAMPLE_SEED),
            Sample::PlateTri => plate1(PlateKind::Tri),
            Sample::PlateQuad => plate1(PlateKind::Quad),
            Sample::PlateMixed => plate1(PlateKind::Mixed),
            Sample::PlateTriTangled => tangled(plate1(PlateKind::Tri)?),
            Sample::PlateQuadTangled => tangled(plate1(PlateKind::Quad)?),
            Sample::PlateMixedTangled => tangled(plate1(PlateKind::Mixed)?),
            Sample::PlateQuadTangledHard => perturb(&plate1(PlateKind::Quad)?, HARD_TANGLE_AMOUNT, SAMPLE_SEED),
            Sample::Rand2dTangled => tangled(rand2d(500, 20, SAMPLE_SEED)?),
            Sample::StarRegular => star(StarKind::Regular, StarKind::Regular.default_k()),
            Sample::StarChen => star(StarKind::Chen, StarKind::Chen.default_k()),
            Sample::StarQuad => star(StarKind::Quad, StarKind::Quad.default_k()),
            Sample::StarPushed => quadratic_star(QuadraticStar::PushedEdge),
            Sample::StarCurved => quadratic_star(QuadraticStar::CurvedBoundary),
            Sample::GridRandomTangled => random_grid(RANDOM_GRID_CELLS, GridKind::Quad, SAMPLE_SEED),
            Sample::PlateQuadratic => plate(PlateKind::Tri, 2, PLATE_RESOLUTION),
            Sample::Rand2dLarge => rand2d_spatial(LARGE_INTERIOR, 200, SAMPLE_SEED),
            Sample::Rand2dMillion => rand2d_spatial(MILLION_INTERIOR, MILLION_PER_SIDE, SAMPLE_SEED),
            Sample::SphereTangled | Sample::TorusTangled | Sample::CylinderCapped | Sample::TorusQuadraticTangled => {
                Err(Error::invalid(format!("the sample '{}' is a surface in 3D, not a planar mesh", self.title())))
            }
            Sample::Rand3d | Sample::HexTangled | Sample::MixedTangled => {
                Err(Error::invalid(format!("the sample '{}' is a volume mesh, not a planar mesh", self.title())))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use smoothlab::quality::mesh_stats;

    #[test]
    fn every_small_sample_builds_and_tangled_ones_are_tangled() {
        for s in Sample::ALL {
            if s == Sample::Rand2dLarge {
                continue;
            }
            let m = s.generate().unwrap_or_else(|e| panic!("{s:?}: {e}"));
            m.sanity_check().unwrap();
            let st = mesh_stats(&m);
            let name = format!("{s:?}");
            if name.contains("Tangled") {
                assert!(st.inverted > 0, "{s:?} has no inverted element");
            } else {
                assert_eq!(st.inverted, 0, "{s:?}");
            }
            assert!(m.free_count() > 0, "{s:?} has nothing to smooth");
        }
    }

    #[test]
    fn surface_samples_are_tangled_surfaces_and_planar_ones_planar() {
        for s in Sample::SURFACES {
            let Model::Surface(m) = s.model().unwrap() else { panic!("{s:?} is not a surface") };
            let st = m.stats();
            assert!(st.surface && st.inverted > 0, "{s:?}: {} inverted", st.inverted);
            assert!(st.max_distance_from_surface.unwrap() < 1e-9, "{s:?} is on its surface");
            let e = s.generate().unwrap_err().to_string();
            assert!(e.contains("surface in 3D"), "{e}");
        }
        assert!(matches!(Sample::PlateTri.model().unwrap(), Model::Planar(_)));
    }

    /// The volume sample's mesh and its inverted elements.
    fn volume(s: Sample) -> (smoothlab::volume::VolumeMesh, usize) {
        let Model::Volume(m) = s.model().unwrap() else { panic!("{s:?} is not a volume mesh") };
        let inverted = (0..m.element_count()).filter(|&e| m.is_inverted(e)).count();
        (m, inverted)
    }

    #[test]
    fn the_tangled_hexahedra_are_knupps_block_as_their_words_say() {
        let (m, inverted) = volume(Sample::HexTangled);
        assert_eq!(m.kinds(), &[smoothlab::mesh::VolumeKind::Hex8]);
        assert_eq!((m.element_count(), m.node_count(), m.free_count()), (216, 343, 125));
        assert!(Sample::HexTangled.title().contains("6³") && HEX_CELLS == 6);
        assert_eq!(inverted, 128, "HEX_TANGLE_AMOUNT's words");
        let e = Sample::HexTangled.generate().unwrap_err().to_string();
        assert!(e.contains("a volume mesh"), "{e}");
    }

    #[test]
    fn the_mixed_sample_has_every_linear_kind_a_few_inverted() {
        use smoothlab::mesh::VolumeKind;
        let (m, inverted) = volume(Sample::MixedTangled);
        assert_eq!(m.kinds(), &[VolumeKind::Tet4, VolumeKind::Hex8, VolumeKind::Wedge6, VolumeKind::Pyramid5]);
        assert_eq!(m.element_count(), 98);
        assert_eq!(inverted, 5, "MIXED_TANGLE_AMOUNT's words");
        let title = Sample::MixedTangled.title();
        for family in ["hexahedra", "wedges", "pyramids", "tetrahedra"] {
            assert!(title.contains(family), "{title}");
        }
    }

    #[test]
    fn titles_are_distinct() {
        let titles: std::collections::HashSet<_> = Sample::GALLERY.iter().map(|s| s.title()).collect();
        assert_eq!(titles.len(), Sample::GALLERY.len());
    }

    #[test]
    fn the_gallery_is_every_linkable_sample_the_surfaces_the_volumes_then_the_million() {
        let n = Sample::ALL.len();
        assert_eq!(&Sample::GALLERY[..n], &Sample::ALL);
        let k = Sample::SURFACES.len();
        assert_eq!(&Sample::GALLERY[n..n + k], &Sample::SURFACES);
        assert_eq!(Sample::GALLERY[n + k..], [Sample::Rand3d, Sample::HexTangled, Sample::MixedTangled, Sample::Rand2dMillion]);
        assert!(Sample::GALLERY.iter().all(|s| s.linkable()), "a link names every sample of the gallery");
        let Model::Volume(v) = Sample::Rand3d.model().unwrap() else { panic!("rand3d is tetrahedral") };
        assert_eq!(v.node_count(), smoothlab::generate::RAND3D_POINTS);
        assert!(Sample::Rand3d.generate().unwrap_err().to_string().contains("a volume mesh"));
        assert!(Sample::Rand2dMillion.title().contains("1M") && Sample::Rand2dMillion.title().contains("slow"));
        assert_eq!(serde_json::to_string(&Sample::Rand2dMillion).unwrap(), "\"rand2d-million\"");
        assert_eq!(MILLION_INTERIOR + 4 * MILLION_PER_SIDE, super::super::MAX_NODES);
    }

    #[test]
    fn names_round_trip_through_serde() {
        for s in Sample::GALLERY {
            let j = serde_json::to_string(&s).unwrap();
            assert_eq!(serde_json::from_str::<Sample>(&j).unwrap(), s);
            assert_eq!(j, format!("\"{}\"", s.name()));
        }
        assert_eq!(serde_json::to_string(&Sample::PlateTriTangled).unwrap(), "\"plate-tri-tangled\"");
        assert!(serde_json::from_str::<Sample>("\"plate-hexagons\"").is_err());
    }
}
