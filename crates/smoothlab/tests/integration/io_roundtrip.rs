//! Write, read back, compare: nodes to the last bit, elements, kinds, and the fixed flags
//! as far as each format holds them (msh and VTK: exactly; OBJ and OFF: none, so the
//! boundary; Triangle: boundary ∪ written markers; Medit: boundary ∪ required vertices,
//! the elements grouped by kind). Property-tested over random meshes of every element
//! kind at scales from 1e-100 to 1e100.

use glam::DVec2;
use proptest::prelude::*;
use smoothlab::io::{self, Format, MshVersion, WriteOptions};
use smoothlab::mesh::{FixedSpec, MeshBuilder, NodeRole};
use smoothlab::{ElementKind, Mesh};

#[derive(Clone, Copy, Debug)]
enum Family {
    Tri3,
    Quad4,
    MixedLinear,
    Tri6,
    Quad8,
    Quad9,
    MixedQuadratic,
}

const FAMILIES: [Family; 7] =
    [Family::Tri3, Family::Quad4, Family::MixedLinear, Family::Tri6, Family::Quad8, Family::Quad9, Family::MixedQuadratic];

/// An `nx` × `ny` grid of cells of the family, nodes jittered by `jitter` (cycled) and
/// scaled by `scale`, fixed flags from `fixed` (cycled).
fn grid(nx: usize, ny: usize, family: Family, jitter: &[(f64, f64)], scale: f64, fixed: &[bool]) -> Mesh {
    let quadratic = matches!(family, Family::Tri6 | Family::Quad8 | Family::Quad9 | Family::MixedQuadratic);
    let step = if quadratic { 2 } else { 1 };
    let (w, h) = (step * nx + 1, step * ny + 1);
    let mut b = MeshBuilder::new();
    for j in 0..h {
        for i in 0..w {
            let k = j * w + i;
            let (jx, jy) = jitter[k % jitter.len()];
            let unit = 1.0 / step as f64;
            b.add_node([(i as f64 + jx) * unit * scale, (j as f64 + jy) * unit * scale, 0.0], 0);
        }
    }
    let at = |i: usize, j: usize| (j * w + i) as u32;
    for cj in 0..ny {
        for ci in 0..nx {
            let (i, j) = (step * ci, step * cj);
            let pick = match family {
                Family::MixedLinear => [Family::Quad4, Family::Tri3][(ci + cj) % 2],
                Family::MixedQuadratic => [Family::Quad9, Family::Quad8, Family::Tri6][(ci + cj) % 3],
                f => f,
            };
            match pick {
                Family::Tri3 => {
                    b.add_element(ElementKind::Tri3, &[at(i, j), at(i + 1, j), at(i + 1, j + 1)], 0);
                    b.add_element(ElementKind::Tri3, &[at(i, j), at(i + 1, j + 1), at(i, j + 1)], 0);
                }
                Family::Quad4 => b.add_element(ElementKind::Quad4, &[at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)], 0),
                Family::Tri6 => {
                    let c = at(i + 1, j + 1);
                    b.add_element(ElementKind::Tri6, &[at(i, j), at(i + 2, j), at(i + 2, j + 2), at(i + 1, j), at(i + 2, j + 1), c], 0);
                    b.add_element(ElementKind::Tri6, &[at(i, j), at(i + 2, j + 2), at(i, j + 2), c, at(i + 1, j + 2), at(i, j + 1)], 0);
                }
                Family::Quad8 | Family::Quad9 => {
                    let mut ids = vec![
                        at(i, j),
                        at(i + 2, j),
                        at(i + 2, j + 2),
                        at(i, j + 2),
                        at(i + 1, j),
                        at(i + 2, j + 1),
                        at(i + 1, j + 2),
                        at(i, j + 1),
                    ];
                    let kind = if matches!(pick, Family::Quad9) {
                        ids.push(at(i + 1, j + 1));
                        ElementKind::Quad9
                    } else {
                        ElementKind::Quad8
                    };
                    b.add_element(kind, &ids, 0);
                }
                _ => unreachable!(),
            }
        }
    }
    let n = w * h;
    b.fixed = FixedSpec::Exact((0..n).map(|i| fixed[i % fixed.len()]).collect());
    b.build().unwrap()
}

fn same_nodes(a: &Mesh, b: &Mesh, what: &str) {
    assert_eq!(a.node_count(), b.node_count(), "{what}: node count");
    for (i, (p, q)) in a.nodes().iter().zip(b.nodes()).enumerate() {
        assert!(
            p.x.to_bits() == q.x.to_bits() && p.y.to_bits() == q.y.to_bits(),
            "{what}: node {i}: {p:?} became {q:?}"
        );
    }
}

fn same_geometry(a: &Mesh, b: &Mesh, what: &str) {
    same_nodes(a, b, what);
    assert_eq!(a.kinds(), b.kinds(), "{what}: kinds");
    for e in 0..a.element_count() {
        assert_eq!(a.element(e), b.element(e), "{what}: element {e}");
    }
}

/// Boundary and unused nodes: the fixed flags of a format that stores none.
fn boundary_fixed(m: &Mesh) -> Vec<bool> {
    (0..m.node_count()).map(|i| m.is_boundary(i) || m.role(i) == NodeRole::Unused).collect()
}

/// The fixed flags of a format that marks fixed nodes on top of the boundary.
fn boundary_or_fixed(m: &Mesh) -> Vec<bool> {
    boundary_fixed(m).iter().zip(m.fixed()).map(|(a, b)| *a || *b).collect()
}

fn check_all_formats(m: &Mesh) {
    for v in [MshVersion::V22, MshVersion::V41] {
        let text = io::write_string(m, Format::Msh, &WriteOptions { msh_version: v }).unwrap();
        let back = io::read_str(&text, Format::Msh).unwrap();
        same_geometry(m, &back, &format!("msh {v:?}"));
        assert_eq!(back.fixed(), m.fixed(), "msh {v:?}: fixed");
    }
    let text = io::write_string(m, Format::Vtk, &WriteOptions::default()).unwrap();
    let back = io::read_str(&text, Format::Vtk).unwrap();
    same_geometry(m, &back, "vtk");
    assert_eq!(back.fixed(), m.fixed(), "vtk: fixed");
    if !m.has_quadratic() {
        for f in [Format::Obj, Format::Off] {
            let text = io::write_string(m, f, &WriteOptions::default()).unwrap();
            let back = io::read_str(&text, f).unwrap();
            same_geometry(m, &back, &format!("{f:?}"));
            assert_eq!(back.fixed(), boundary_fixed(m), "{f:?}: fixed = boundary");
        }
    }
    // Medit: linear kinds, a section per kind (triangles first), fixed nodes required
    match io::write_string(m, Format::Medit, &WriteOptions::default()) {
        Ok(text) => {
            let back = io::read_str(&text, Format::Medit).unwrap();
            let grouped: Vec<usize> = [ElementKind::Tri3, ElementKind::Quad4]
                .iter()
                .flat_map(|&k| (0..m.element_count()).filter(move |&e| m.kind(e) == k))
                .collect();
            same_nodes(m, &back, "Medit");
            assert_eq!(back.element_count(), grouped.len(), "Medit: element count");
            for (b, &e) in grouped.iter().enumerate() {
                assert_eq!((back.kind(b), back.element(b)), (m.kind(e), m.element(e)), "Medit: element {e}, read as {b}");
            }
            assert_eq!(back.fixed(), boundary_or_fixed(m), "Medit: fixed = boundary ∪ required");
        }
        Err(e) => assert!(m.has_quadratic(), "Medit refused a linear mesh: {e}"),
    }
    let one_kind = m.kinds().iter().all(|&k| k == m.kind(0));
    if m.kind(0).is_triangle() && one_kind {
        let (node, ele) = io::write_triangle(m).unwrap();
        let back = io::read_triangle(&node, &ele).unwrap();
        same_geometry(m, &back, "triangle");
        assert_eq!(back.fixed(), boundary_or_fixed(m), "triangle: fixed = boundary ∪ markers");
    } else {
        assert!(io::write_triangle(m).is_err());
    }
}

#[test]
fn every_family_round_trips_through_every_writer() {
    let jitter = [(0.0, 0.0), (0.1, -0.2), (-0.15, 0.05), (0.2, 0.2), (1.0 / 3.0, -0.1)];
    for family in FAMILIES {
        let m = grid(3, 2, family, &jitter, 1.0, &[true, false, false]);
        check_all_formats(&m);
    }
}

#[test]
fn files_round_trip_through_the_file_system() {
    let m = grid(2, 2, Family::Tri6, &[(0.0, 0.0), (0.1, 0.2)], 0.7, &[false, true]);
    let dir = std::env::temp_dir().join(format!("smoothlab-io-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for name in ["m.msh", "m.vtk", "m.node"] {
        let path = dir.join(name);
        io::write_path(&m, &path, &WriteOptions { msh_version: MshVersion::V41 }).unwrap();
        let back = io::read_path(&path).unwrap();
        same_geometry(&m, &back, name);
    }
    // the pair was written under both names
    assert!(dir.join("m.ele").is_file());
    let back = io::read_path(&dir.join("m.ele")).unwrap();
    same_geometry(&m, &back, "m.ele");
    let e = io::read_path(&dir.join("absent.vtk")).unwrap_err().to_string();
    assert!(e.contains("absent.vtk"), "{e}");
    // over the size limit: refused from its length, before reading (a sparse file)
    let big = dir.join("big.msh");
    std::fs::File::create(&big).unwrap().set_len(io::MAX_FILE_BYTES + 1).unwrap();
    let e = io::read_path(&big).unwrap_err();
    assert!(matches!(e, smoothlab::Error::TooLarge(_)), "{e:?}");
    assert!(e.to_string().contains(&io::MAX_FILE_BYTES.to_string()), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn random_meshes_round_trip_bit_for_bit(
        nx in 1usize..4,
        ny in 1usize..4,
        family in 0usize..FAMILIES.len(),
        jitter in prop::collection::vec((-0.3f64..0.3, -0.3f64..0.3), 1..40),
        exponent in -100i32..100,
        fixed in prop::collection::vec(any::<bool>(), 1..20),
    ) {
        let m = grid(nx, ny, FAMILIES[family], &jitter, 10f64.powi(exponent), &fixed);
        check_all_formats(&m);
    }
}

#[test]
fn awkward_numbers_survive() {
    // shortest round-trip forms: exponents, subnormal-adjacent, negative zero
    let jitter = [(f64::EPSILON, -0.0), (1e-17, 0.1 + 0.2 - 0.3), (-1.0 / 3.0 + 0.3, 0.25)];
    let mut m = grid(2, 1, Family::Quad4, &jitter, 1e-300, &[true]);
    m.nodes_mut()[0] = DVec2::new(-0.0, 0.0);
    check_all_formats(&m);
    let m = grid(2, 1, Family::Tri3, &jitter, 1e300, &[false]);
    check_all_formats(&m);
}
