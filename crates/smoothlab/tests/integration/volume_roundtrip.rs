//! Volume meshes of every kind written and read back exactly: for every kind and for a
//! mixed mesh (its kinds interleaved), every format that holds it — `.vtk`, `.msh` 2.2
//! and 4.1; TetGen's `.node`/`.ele` for tetrahedra only, which refuses the rest saying
//! so — gives back the nodes to the bit, the kinds, each element's node list in order
//! and the fixed flags (drawn at random, so they are the file's and not the skin again).
//! Medit's `.mesh` holds the linear kinds, a section per kind: it gives them back grouped
//! by kind, with fixed = the skin ∪ the required vertices.
//! The meshes are small blocks of the unit lattice, jittered.

use glam::DVec3;
use proptest::prelude::*;
use smoothlab::io::{self, Format, MshVersion, WriteOptions};
use smoothlab::mesh::{FixedSpec, VolumeKind};
use smoothlab::model::Model;
use smoothlab::numeric::SplitMix64;
use smoothlab::volume::{SolidParts, VolumeMesh};

/// The lattice points `(x, y, z)`, `x < nx + 1` fastest, and the corners of cell
/// `(i, j, k)` in VTK's hexahedron order.
struct Lattice {
    nx: u32,
    ny: u32,
}

impl Lattice {
    fn id(&self, x: u32, y: u32, z: u32) -> u32 {
        x + (self.nx + 1) * (y + (self.ny + 1) * z)
    }
    fn points(&self, nz: u32) -> Vec<DVec3> {
        let mut p = Vec::new();
        for z in 0..=nz {
            for y in 0..=self.ny {
                for x in 0..=self.nx {
                    p.push(DVec3::new(x as f64, y as f64, z as f64));
                }
            }
        }
        p
    }
    fn cell(&self, i: u32, j: u32, k: u32) -> [u32; 8] {
        let c = |dx, dy, dz| self.id(i + dx, j + dy, k + dz);
        [c(0, 0, 0), c(1, 0, 0), c(1, 1, 0), c(0, 1, 0), c(0, 0, 1), c(1, 0, 1), c(1, 1, 1), c(0, 1, 1)]
    }
}

/// A hexahedron's faces, outward, in VTK's numbering.
const HEX_FACES: [[usize; 4]; 6] = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]];

/// The two wedges of a cell cut by its diagonal plane through corners 0, 2, 4, 6, each
/// in VTK's order (the first triangle turning away from the second).
fn wedges(c: [u32; 8]) -> [Vec<u32>; 2] {
    [vec![c[0], c[2], c[1], c[4], c[6], c[5]], vec![c[0], c[3], c[2], c[4], c[7], c[6]]]
}

/// The six pyramids from a cell's faces to its centre node `m` (each base turning
/// towards the apex: the outward face reversed).
fn pyramids(c: [u32; 8], m: u32) -> Vec<Vec<u32>> {
    HEX_FACES.iter().map(|f| vec![c[f[0]], c[f[3]], c[f[2]], c[f[1]], m]).collect()
}

/// Kuhn's six tetrahedra of a cell along its diagonal 0–6, each turned right-handed.
fn tets(c: [u32; 8], p: &[DVec3]) -> Vec<Vec<u32>> {
    let paths = [[1, 2], [1, 5], [4, 5], [4, 7], [3, 7], [3, 2]];
    paths
        .iter()
        .map(|&[a, b]| {
            let mut t = vec![c[0], c[a], c[b], c[6]];
            let q = |i: usize| p[t[i] as usize];
            if (q(1) - q(0)).cross(q(2) - q(0)).dot(q(3) - q(0)) < 0.0 {
                t.swap(1, 2);
            }
            t
        })
        .collect()
}

/// What each test mesh is made of.
#[derive(Clone, Copy, Debug)]
enum Sample {
    /// A 2×2×2 block of hexahedra.
    Hexahedra,
    /// Its 20-node and 27-node hexahedra.
    Hex20,
    Hex27,
    /// A 2×2×1 block, each cell cut into two wedges.
    Wedges,
    /// A 2×1×1 block of Kuhn tetrahedra, and its 10-node ones.
    Tetrahedra,
    Tet10,
    /// A row of four cells: a hexahedron, six pyramids to a centre node, two wedges and
    /// six tetrahedra, the elements shuffled so that the kinds interleave.
    Mixed,
}

const SAMPLES: [Sample; 7] =
    [Sample::Hexahedra, Sample::Hex20, Sample::Hex27, Sample::Wedges, Sample::Tetrahedra, Sample::Tet10, Sample::Mixed];

fn mesh_of(nodes: Vec<DVec3>, elements: &[(VolumeKind, Vec<u32>)]) -> VolumeMesh {
    VolumeMesh::from_elements(nodes, elements.iter().map(|(k, e)| (*k, e.as_slice()))).unwrap()
}

fn linear(sample: Sample, rng: &mut SplitMix64) -> VolumeMesh {
    use VolumeKind::*;
    match sample {
        Sample::Hexahedra | Sample::Hex20 | Sample::Hex27 => {
            let l = Lattice { nx: 2, ny: 2 };
            let cells: Vec<_> = (0..8).map(|c| (Hex8, l.cell(c % 2, c / 2 % 2, c / 4).to_vec())).collect();
            mesh_of(l.points(2), &cells)
        }
        Sample::Wedges => {
            let l = Lattice { nx: 2, ny: 2 };
            let cells: Vec<_> = (0..4).flat_map(|c| wedges(l.cell(c % 2, c / 2, 0))).map(|w| (Wedge6, w)).collect();
            mesh_of(l.points(1), &cells)
        }
        Sample::Tetrahedra | Sample::Tet10 => {
            let l = Lattice { nx: 2, ny: 1 };
            let p = l.points(1);
            let cells: Vec<_> = (0..2).flat_map(|c| tets(l.cell(c, 0, 0), &p)).map(|t| (Tet4, t)).collect();
            mesh_of(p, &cells)
        }
        Sample::Mixed => {
            let l = Lattice { nx: 4, ny: 1 };
            let mut p = l.points(1);
            let centre = p.len() as u32;
            p.push(DVec3::new(1.5, 0.5, 0.5));
            let mut cells = vec![(Hex8, l.cell(0, 0, 0).to_vec())];
            cells.extend(pyramids(l.cell(1, 0, 0), centre).into_iter().map(|e| (Pyramid5, e)));
            cells.extend(wedges(l.cell(2, 0, 0)).into_iter().map(|e| (Wedge6, e)));
            cells.extend(tets(l.cell(3, 0, 0), &p).into_iter().map(|e| (Tet4, e)));
            // shuffled (Fisher–Yates): the kinds come in runs of every length
            for i in (1..cells.len()).rev() {
                cells.swap(i, (rng.next_u64() % (i as u64 + 1)) as usize);
            }
            mesh_of(p, &cells)
        }
    }
}

/// The sample's mesh with every node moved by up to a tenth of the spacing (positions
/// with every bit of the mantissa in use) and fixed flags drawn at random.
fn sample(s: Sample, seed: u64) -> VolumeMesh {
    let mut rng = SplitMix64::new(seed);
    let m = linear(s, &mut rng);
    let mut m = match s {
        Sample::Hex20 => m.to_quadratic(true).unwrap(),
        Sample::Hex27 | Sample::Tet10 => m.to_quadratic(false).unwrap(),
        _ => m,
    };
    for p in m.nodes_mut() {
        *p += DVec3::new(rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1));
    }
    let mut elements = Vec::new();
    for e in 0..m.element_count() {
        elements.extend_from_slice(m.element(e));
    }
    let fixed = (0..m.node_count()).map(|_| rng.next_u64() % 3 == 0).collect();
    let m = VolumeMesh::build(SolidParts {
        nodes: m.nodes().to_vec(),
        node_lines: Vec::new(),
        kinds: (0..m.element_count()).map(|e| m.element_kind(e)).collect(),
        elements,
        element_lines: Vec::new(),
        fixed: FixedSpec::Exact(fixed),
        faces: Vec::new(),
    })
    .unwrap();
    assert_eq!((0..m.element_count()).filter(|&e| m.is_inverted(e)).count(), 0, "{s:?}: a valid mesh to start from");
    m
}

/// `b` is `a`: nodes to the bit, kinds, element node lists, fixed flags.
fn identical(a: &VolumeMesh, b: &VolumeMesh, what: &str) {
    let bits = |m: &VolumeMesh| m.nodes().iter().map(|p| p.to_array().map(f64::to_bits)).collect::<Vec<_>>();
    assert_eq!(bits(a), bits(b), "{what}: nodes");
    assert_eq!(a.element_count(), b.element_count(), "{what}");
    for e in 0..a.element_count() {
        assert_eq!((a.element_kind(e), a.element(e)), (b.element_kind(e), b.element(e)), "{what}: element {e}");
    }
    assert_eq!(a.fixed(), b.fixed(), "{what}: fixed flags");
}

fn volume(m: Model) -> VolumeMesh {
    match m {
        Model::Volume(v) => v,
        other => panic!("not a volume mesh: {:?}", other.stats()),
    }
}

const WRITTEN: [(Format, MshVersion, &str); 3] =
    [(Format::Vtk, MshVersion::V22, ".vtk"), (Format::Msh, MshVersion::V22, ".msh 2.2"), (Format::Msh, MshVersion::V41, ".msh 4.1")];

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn every_kind_and_a_mixed_mesh_round_trip_exactly_in_every_format_that_holds_them(
        which in 0..SAMPLES.len(),
        seed in any::<u64>(),
    ) {
        let s = SAMPLES[which];
        let m = sample(s, seed);
        let model = Model::Volume(m.clone());
        for (format, msh_version, name) in WRITTEN {
            let text = io::write_model_string(&model, format, &WriteOptions { msh_version }).unwrap();
            identical(&m, &volume(io::read_model_str(&text, format).unwrap()), &format!("{s:?} as {name}"));
        }
        // Medit: the linear kinds, grouped (tetrahedra, hexahedra, prisms, pyramids)
        match io::write_model_string(&model, Format::Medit, &WriteOptions::default()) {
            Ok(text) => {
                prop_assert!(!m.is_quadratic(), "{s:?}");
                let order = [VolumeKind::Tet4, VolumeKind::Hex8, VolumeKind::Wedge6, VolumeKind::Pyramid5];
                let grouped: Vec<usize> =
                    order.iter().flat_map(|&k| (0..m.element_count()).filter(|&e| m.element_kind(e) == k).collect::<Vec<_>>()).collect();
                let want = VolumeMesh::build(SolidParts {
                    nodes: m.nodes().to_vec(),
                    node_lines: Vec::new(),
                    kinds: grouped.iter().map(|&e| m.element_kind(e)).collect(),
                    elements: grouped.iter().flat_map(|&e| m.element(e).to_vec()).collect(),
                    element_lines: Vec::new(),
                    fixed: FixedSpec::BoundaryAnd(m.fixed().to_vec()),
                    faces: Vec::new(),
                })
                .unwrap();
                identical(&want, &volume(io::read_model_str(&text, Format::Medit).unwrap()), &format!("{s:?} as .mesh"));
            }
            Err(e) => {
                prop_assert!(m.is_quadratic(), "{s:?}: {e}");
                let e = e.to_string();
                prop_assert!(e.starts_with("Medit's volume sections hold linear elements, but element 0 is a "), "{e}");
            }
        }
        // TetGen's pair holds tetrahedra (fixed = the skin and the markers: every flag
        // here is a marker), and refuses every other kind saying what the mesh has
        match io::write_tetgen(&m) {
            Ok((node, ele)) => {
                prop_assert!(m.is_tets(), "{s:?}");
                let back = volume(io::read_model_pair(&node, &ele).unwrap());
                let mut elements = Vec::new();
                for e in 0..m.element_count() {
                    elements.extend_from_slice(m.element(e));
                }
                let want = VolumeMesh::build(SolidParts {
                    nodes: m.nodes().to_vec(),
                    node_lines: Vec::new(),
                    kinds: (0..m.element_count()).map(|e| m.element_kind(e)).collect(),
                    elements,
                    element_lines: Vec::new(),
                    fixed: FixedSpec::BoundaryAnd(m.fixed().to_vec()),
                    faces: Vec::new(),
                })
                .unwrap();
                identical(&want, &back, &format!("{s:?} as TetGen's pair"));
            }
            Err(e) => {
                prop_assert!(!m.is_tets(), "{s:?}");
                let e = e.to_string();
                prop_assert!(e.starts_with("TetGen's .ele holds tetrahedra, and this mesh has "), "{e}");
                prop_assert!(e.ends_with(": write .msh or .vtk"), "{e}");
            }
        }
    }
}

#[test]
fn msh_4_1_writes_a_block_per_run_of_one_kind_and_tetgen_names_what_it_refuses() {
    let m = sample(Sample::Mixed, 7);
    let runs = 1 + (1..m.element_count()).filter(|&e| m.element_kind(e) != m.element_kind(e - 1)).count();
    assert!(runs > 4, "the shuffled kinds interleave: {runs} runs of 4 kinds");
    let text = io::write_model_string(&Model::Volume(m.clone()), Format::Msh, &WriteOptions { msh_version: MshVersion::V41 })
        .unwrap();
    let elements = &text[text.find("$Elements\n").unwrap() + 10..];
    let header: Vec<usize> = elements.lines().next().unwrap().split(' ').map(|v| v.parse().unwrap()).collect();
    assert_eq!(header, vec![runs, m.element_count(), 1, m.element_count()], "blocks, elements, tags");
    let e = io::write_tetgen(&m).unwrap_err().to_string();
    assert_eq!(e, "TetGen's .ele holds tetrahedra, and this mesh has tetrahedra, hexahedra, wedges and pyramids: write .msh or .vtk");
    let d = std::env::temp_dir().join(format!("smoothlab-volume-roundtrip-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    let path = d.join("mixed.node");
    let e = io::write_model_path(&Model::Volume(m), &path, &WriteOptions::default()).unwrap_err().to_string();
    assert!(e.starts_with("TetGen's .ele holds tetrahedra"), "{e}");
    assert!(!path.exists() && !d.join("mixed.ele").exists(), "nothing written");
}
