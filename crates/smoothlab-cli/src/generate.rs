//! `smoothlab generate KIND … -o OUT`: write a sample mesh.

use std::path::PathBuf;

use clap::{Args, Subcommand};

use crate::args::{msh_version_parser, named, per_axis};
use smoothlab::generate::{self, GridKind, HexBlock, PlateKind, StarKind, SurfaceKind, SurfaceShape};
use smoothlab::generate::perturb_surface;
use smoothlab::model::Model;
use smoothlab::Mesh;

use crate::files::{read_model, write_mesh, write_model};
use smoothlab::io::MshVersion;

#[derive(Args)]
pub struct GenerateArgs {
    #[command(subcommand)]
    pub kind: Kind,
}

/// Where to write, shared by every kind.
#[derive(Args)]
pub struct Output {
    /// Output mesh; the format follows the extension (.msh, .vtk, .node, .obj, .off, .mesh)
    #[arg(short, long)]
    pub output: PathBuf,
    /// Version of .msh files written
    #[arg(long, value_parser = msh_version_parser(), default_value = MshVersion::default().name())]
    pub msh_version: MshVersion,
}

#[derive(Subcommand)]
pub enum Kind {
    /// Freitag's rand2d: Delaunay triangulation of random points in the unit square
    Rand2d {
        /// Random interior points
        #[arg(long, default_value_t = 500)]
        points: usize,
        /// Equally spaced points on each side of the square (corners counted once)
        #[arg(long, default_value_t = 20)]
        per_side: usize,
        /// Seed of the random points
        #[arg(long, default_value_t = 1)]
        seed: u64,
        #[command(flatten)]
        out: Output,
    },
    /// A structured grid on the unit square
    Grid {
        /// Cells along x
        #[arg(long, default_value_t = 10)]
        nx: usize,
        /// Cells along y
        #[arg(long, default_value_t = 10)]
        ny: usize,
        /// Triangles (each square split lower-left to upper-right) or quads
        #[arg(long, value_parser = named(&GridKind::ALL, GridKind::name, GridKind::describe), default_value = GridKind::default().name())]
        kind: GridKind,
        #[command(flatten)]
        out: Output,
    },
    /// A square plate [-1,1]² with a hole of radius 0.4 (O-grid)
    Plate {
        /// Triangles, quads, or quads round the hole and triangles outside
        #[arg(long, value_parser = named(&PlateKind::ALL, PlateKind::name, PlateKind::describe), default_value = PlateKind::default().name())]
        kind: PlateKind,
        /// 1 for linear elements, 2 for quadratic ones with a curved hole
        #[arg(long, default_value_t = 1)]
        order: u8,
        /// 8·N nodes round the hole and the square, 2·N rings between them
        #[arg(long, default_value_t = 4)]
        resolution: usize,
        #[command(flatten)]
        out: Output,
    },
    /// One free node with a ring of fixed neighbours
    Star {
        /// Regular (Mesquite's equil_tri), Chen's non-convex star, or quads
        #[arg(long, value_parser = named(&StarKind::ALL, StarKind::name, StarKind::describe), default_value = StarKind::default().name())]
        kind: StarKind,
        /// Elements round the free node [default: 6 regular, 8 chen, 4 quad]
        #[arg(long)]
        k: Option<usize>,
        #[command(flatten)]
        out: Output,
    },
    /// A surface sample on the unit sphere (a cube-sphere)
    Sphere(SurfaceArgs),
    /// A surface sample on a cylinder of radius 1 and height 2 with flat caps (feature edges at the rims)
    Cylinder(SurfaceArgs),
    /// A surface sample on a torus of radii 3 and 1
    Torus(SurfaceArgs),
    /// Freitag's rand3d: Delaunay tetrahedra of random points in the unit cube (boundary
    /// points at the interior's density)
    Rand3d {
        /// Points in all, corners, edges and faces included
        #[arg(long, default_value_t = generate::RAND3D_POINTS)]
        points: usize,
        /// Seed of the random points
        #[arg(long, default_value_t = 1)]
        seed: u64,
        #[command(flatten)]
        out: Output,
    },
    /// The unit cube in tetrahedra: N cubes a side, each cut into Kuhn's six tetrahedra
    Cube {
        /// Cubes along each side
        #[arg(long, default_value_t = 8)]
        cells: usize,
        /// 1 for 4-node tetrahedra, 2 for 10-node ones (a node at the middle of every edge)
        #[arg(long, default_value_t = 1)]
        order: u8,
        #[command(flatten)]
        out: Output,
    },
    /// A block of hexahedra, straight or bent about an axis parallel to y like a curved
    /// beam (the bottom face keeps its length on an arc of the bend's angle; every element
    /// stays valid); perturb it to tangle it (Knupp 1999's test grids)
    Hexgrid {
        #[command(flatten)]
        block: BlockArgs,
        /// 1 for 8-node hexahedra, 2 for 27-node ones (a node at the middle of every edge,
        /// face and cell)
        #[arg(long, default_value_t = 1)]
        order: u8,
        /// With --order 2: 20-node hexahedra (mid-edge nodes only)
        #[arg(long)]
        serendipity: bool,
        #[command(flatten)]
        out: Output,
    },
    /// A block of hexahedra with one column of cells cut into wedges and the row of cells
    /// along its bottom front edge cut into pyramids round each cell's centre, those on the
    /// boundary into two tetrahedra: every linear kind in one conforming mesh
    Mixed {
        #[command(flatten)]
        block: BlockArgs,
        #[command(flatten)]
        out: Output,
    },
    /// Move every free node of a mesh at random (to tangle it); a surface's nodes move in
    /// their tangent planes and back onto the surface, a volume mesh's in a ball
    Perturb {
        /// The mesh to perturb
        input: PathBuf,
        /// Largest move, as a multiple of the mean edge length
        #[arg(long, default_value_t = 0.5, allow_hyphen_values = true)]
        amount: f64,
        /// Seed of the random moves
        #[arg(long, default_value_t = 1)]
        seed: u64,
        #[command(flatten)]
        out: Output,
    },
}

/// The options of the blocks of hexahedra (and of the mixed block cut from one).
#[derive(Args)]
pub struct BlockArgs {
    /// Cells along each axis: N, or NX,NY,NZ
    #[arg(long, value_parser = per_axis::<usize>, default_value = "8")]
    cells: [usize; 3],
    /// The straight block's size: L (a cube), or LX,LY,LZ
    #[arg(long, value_parser = per_axis::<f64>, default_value = "1")]
    size: [f64; 3],
    /// Bend the block by this angle, degrees (0 to 270): about the axis parallel to y
    /// through (0, ·, −R), R = LX/angle
    #[arg(long, default_value_t = 0.0)]
    bend: f64,
}

impl BlockArgs {
    fn block(&self) -> HexBlock {
        HexBlock { cells: self.cells, size: self.size.into(), bend: self.bend }
    }
}

/// The options of the surface samples.
#[derive(Args)]
pub struct SurfaceArgs {
    /// Quads, triangles (each quad split), or quads with every other one split
    #[arg(long, value_parser = named(&SurfaceKind::ALL, SurfaceKind::name, SurfaceKind::describe), default_value = SurfaceKind::default().name())]
    kind: SurfaceKind,
    /// 1 for linear elements, 2 for quadratic ones with their mid-side nodes on the surface
    #[arg(long, default_value_t = 1)]
    order: u8,
    /// Cells along each edge of the cube the sphere and cylinder are made from (the torus:
    /// 4 times as many round its tube, 12 times round its axis)
    #[arg(long, default_value_t = 8)]
    resolution: usize,
    #[command(flatten)]
    out: Output,
}

pub fn run(a: GenerateArgs) -> Result<(), String> {
    let surface_sample = |shape: SurfaceShape, s: SurfaceArgs| {
        let surface = generate::surface(shape, s.kind, s.order, s.resolution).map_err(|e| e.to_string())?;
        write_mesh(&surface, &s.out.output, s.out.msh_version)
    };
    let (mesh, out): (Mesh, Output) = match a.kind {
        Kind::Sphere(s) => return surface_sample(SurfaceShape::Sphere, s),
        Kind::Cylinder(s) => return surface_sample(SurfaceShape::Cylinder, s),
        Kind::Torus(s) => return surface_sample(SurfaceShape::Torus, s),
        Kind::Rand2d { points, per_side, seed, out } => {
            (generate::rand2d(points, per_side, seed).map_err(|e| e.to_string())?, out)
        }
        Kind::Grid { nx, ny, kind, out } => (generate::grid(nx, ny, kind).map_err(|e| e.to_string())?, out),
        Kind::Plate { kind, order, resolution, out } => {
            (generate::plate(kind, order, resolution).map_err(|e| e.to_string())?, out)
        }
        Kind::Star { kind, k, out } => {
            (generate::star(kind, k.unwrap_or(kind.default_k())).map_err(|e| e.to_string())?, out)
        }
        Kind::Perturb { input, amount, seed, out } => match read_model(&input)? {
            Model::Planar(mesh) => {
                (generate::perturb(&mesh, amount, seed).map_err(|e| format!("{}: {e}", input.display()))?, out)
            }
            Model::Surface(s) => {
                let moved = perturb_surface(&s, amount, seed).map_err(|e| format!("{}: {e}", input.display()))?;
                return write_mesh(&moved, &out.output, out.msh_version);
            }
            Model::Volume(v) => {
                let moved =
                    generate::perturb_volume(&v, amount, seed).map_err(|e| format!("{}: {e}", input.display()))?;
                return write_model(&Model::Volume(moved), &out.output, out.msh_version);
            }
        },
        Kind::Rand3d { points, seed, out } => {
            let mesh = generate::rand3d(points, seed).map_err(|e| e.to_string())?;
            return write_model(&Model::Volume(mesh), &out.output, out.msh_version);
        }
        Kind::Hexgrid { block, order, serendipity, out } => {
            let grid = generate::hex_grid(&block.block()).map_err(|e| e.to_string())?;
            let grid = match (order, serendipity) {
                (1, false) => grid,
                (1, true) => return Err("--serendipity makes 20-node hexahedra: give it with --order 2".into()),
                (2, s) => grid.to_quadratic(s).map_err(|e| e.to_string())?,
                (o, _) => return Err(format!("--order {o}: give 1 (8-node hexahedra) or 2 (27-node; 20-node with --serendipity)")),
            };
            return write_model(&Model::Volume(grid), &out.output, out.msh_version);
        }
        Kind::Mixed { block, out } => {
            let mesh = generate::mixed_block(&block.block()).map_err(|e| e.to_string())?;
            return write_model(&Model::Volume(mesh), &out.output, out.msh_version);
        }
        Kind::Cube { cells, order, out } => {
            let cube = generate::tet_cube(cells).map_err(|e| e.to_string())?;
            let cube = match order {
                1 => cube,
                2 => cube.to_quadratic(false).map_err(|e| e.to_string())?,
                o => return Err(format!("--order {o}: give 1 (4-node tetrahedra) or 2 (10-node)")),
            };
            return write_model(&Model::Volume(cube), &out.output, out.msh_version);
        }
    };
    write_mesh(&mesh, &out.output, out.msh_version)
}
